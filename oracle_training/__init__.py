"""Training the oracle's question classifier, outside the installed package (which ships only
the artefact and :mod:`vlln.oracle.classifier`): the question sets in ``questions/``
(:mod:`.question_sets`), fitting (:mod:`.training`, ``vlln oracle train-classifier``),
measuring (:mod:`.validation`, ``vlln oracle classify-cv``) and the generated questions
(:mod:`.generator`). Run from the repository root or by a checkout's ``vlln``.
"""
