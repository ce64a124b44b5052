"""Ray as the engine for many machines: ``vlln eval --ray`` and ``vlln data build --ray``.

The driver plans the same work as the local runner, sends it to the cluster in chunks (one
Ray task per chunk, retried explicitly when its worker dies), and writes every result itself,
in plan order, into the same output folder as a local run, so the finished folder is the
local run's. Ray is an extra (README, Install). Set-up (local cluster, cloud
cluster YAML, SLURM) is in ``docs/ray.md``.
"""
