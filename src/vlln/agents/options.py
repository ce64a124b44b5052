"""Typed options of agents that take them (which server, which model), stored in ``run.json``.

Each such agent has one options class; its field defaults are the only place those defaults
live. The evaluation's flat flags (``--base-url``, ``--model-timeout``, ...) and the web app's
``--agent-option AGENT.KEY=VALUE`` both become an options object through :meth:`parse`, by
field name or by the flag's name (a field's alias), so no flag is mapped by hand.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Self

from pydantic import AliasChoices, BaseModel, ConfigDict, ValidationError

from vlln.errors import ConfigError


class AgentOptions(BaseModel):
    """Options of one agent kind; the base itself is the empty set of an agent without any."""

    model_config = ConfigDict(
        frozen=True,
        extra="forbid",
        populate_by_name=True,
        use_attribute_docstrings=True,
        protected_namespaces=(),
    )

    @classmethod
    def names(cls) -> dict[str, str]:
        """Every name an option goes by (field names and flag aliases) -> its field name."""
        names = {}
        for field_name, field in cls.model_fields.items():
            names[field_name] = field_name
            alias = field.validation_alias
            for choice in alias.choices if isinstance(alias, AliasChoices) else [alias]:
                if isinstance(choice, str):
                    names[choice] = field_name
        return names

    @classmethod
    def parse(cls, agent: str, values: Mapping[str, Any]) -> Self:
        """The options ``values`` (keyed by field or flag name; strings are converted) for
        ``agent``; anything wrong is one :class:`ConfigError` line naming the option."""
        names = cls.names()
        unknown = sorted(set(values) - set(names))
        if unknown:
            if not names:
                raise ConfigError(f"agent {agent!r} takes no options, got {', '.join(unknown)}")
            raise ConfigError(
                f"unknown {agent} option {unknown[0]!r}; known: {', '.join(cls.option_names())}"
            )
        by_field = {names[key]: value for key, value in values.items()}
        try:
            return cls.model_validate(by_field)
        except ValidationError as error:
            raise ConfigError(_describe(agent, cls, error)) from None

    @classmethod
    def option_names(cls) -> list[str]:
        """The options' field names, in order."""
        return list(cls.model_fields)

    def to_json(self) -> dict[str, Any]:
        """The options given (not their defaults), sorted by name: what ``run.json`` stores."""
        given = self.model_dump(mode="json", exclude_unset=True)
        return dict(sorted(given.items()))

    def get(self, name: str) -> Any:
        """An option's value, or None when this agent has no such option."""
        return getattr(self, name, None) if name in self.option_names() else None


def _describe(agent: str, options: type[AgentOptions], error: ValidationError) -> str:
    """One line for every problem of the options of ``agent``."""
    parts = []
    for problem in error.errors():
        name = ".".join(str(part) for part in problem["loc"])
        field = options.model_fields.get(name)
        flag = "--" + name.replace("_", "-")
        if problem["type"] == "missing" and field is not None:
            parts.append(f"the {agent} agent needs {flag} ({field.description})")
        else:
            message = str(problem["msg"]).removeprefix("Value error, ")
            parts.append(f"{agent} option {name} = {problem.get('input')!r}: {message}")
    return "; ".join(parts)
