"""``vlln data stats``: statistics, the dataset figure and a Markdown report of a built dataset.

* :mod:`vlln.datagen.stats.compute` -- ``dataset_stats``: counts over the house folders
* :mod:`vlln.datagen.stats.episodes` -- the episode stage's ``<split>_stats.json``
* :mod:`vlln.datagen.stats.figure` -- the six-panel statistics figure
* :mod:`vlln.datagen.stats.report` -- ``write_stats``: stats.json, stats.png, stats.md
"""
