"""Evaluation: play agents over episode sets into resumable run directories, score them
offline, and report.

* :mod:`vlln.eval.config` -- what a run is (``EvalConfig``), stored as ``run.json``
* :mod:`vlln.eval.sharding` -- ``--shard i/n``
* :mod:`vlln.eval.runner` -- ``run_evaluation``: plan, resume, append, summarise, with an
  executor that plays (in this process, or on Ray: :mod:`vlln.cluster.evaluation`)
* :mod:`vlln.eval.play` -- playing planned episodes: seeds, sweeps, refusals
* :mod:`vlln.eval.run_dir` -- the run directory's file names and run.json's fields
* :mod:`vlln.eval.results` -- the run directory: JSONL append, resume, repair, merge
* :mod:`vlln.eval.summary` -- metric tables from episode lines (``vlln score``)
* :mod:`vlln.eval.report` -- report.md / report.html with charts and episode maps
"""
