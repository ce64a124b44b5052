"""Rewrite the packaged generated training questions from their templates.

    PYTHONPATH=src python scripts/oracle_questions.py [--seed 0]

then retrain with ``vlln oracle train-classifier`` and commit both files.
"""

from __future__ import annotations

import argparse

from vlln.oracle.classifier.generator import generated_jsonl
from vlln.oracle.question_set import packaged_question_set_path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=0, help="seed of the draws (default 0)")
    args = parser.parse_args()
    path = packaged_question_set_path("generated")
    path.write_text(generated_jsonl(args.seed), encoding="utf-8")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
