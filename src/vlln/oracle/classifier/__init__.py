"""The learned question classifier: TF-IDF over word and character n-grams, a linear model.

:mod:`~vlln.oracle.classifier.model` loads the shipped artefact and labels questions;
:mod:`~vlln.oracle.classifier.entities` finds the colours, materials and rooms a question
names, and :mod:`~vlln.oracle.classifier.roles` reads them by role for the features. Training
(``vlln oracle train-classifier``) is in the repository's ``oracle_training/``, not shipped.
"""
