"""Agents: one module per agent, all behind the small :class:`vlln.agents.protocol.Agent`."""
