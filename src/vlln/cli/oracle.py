"""``vlln oracle ...``: serve the oracle, train and measure its question classifier."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from vlln.cli.options import Commands
from vlln.extras import SERVE_PACKAGES, require_extra


def _oracle_serve(args: argparse.Namespace) -> int:
    require_extra("serve", "vlln oracle serve", SERVE_PACKAGES)
    from vlln.oracle_service.server import serve, token_from_environment

    token = token_from_environment(args.token_env)
    serve(
        host=args.host,
        port=args.port,
        token=token,
        episodes=None if args.episodes is None else Path(args.episodes),
        allow_remote=args.allow_remote,
        max_sessions=args.max_sessions,
        oracle_seed=args.oracle_seed,
        builds_per_minute=args.builds_per_minute,
        client_builds_per_minute=args.client_builds_per_minute,
        log_level=args.log_level,
    )
    return 0


def _oracle_classify_report(args: argparse.Namespace) -> int:
    from vlln.oracle.classifier.model import packaged_classifier
    from vlln.oracle.question_set import classifier_report

    report = classifier_report(args.questions)
    report["classifier"] = packaged_classifier().meta
    if args.json:
        print(json.dumps({k: v for k, v in report.items() if k != "table"}, indent=2))
        return 0
    print(f"type accuracy: {report['accuracy']:.1%} of {report['questions']} questions")
    for kind, topic in report["topic_accuracy"].items():
        print(f"{kind} topic accuracy: {topic['accuracy']:.1%} of {topic['questions']}")
    print(f"\n{report['table']}")
    return 0


def _oracle_classify_cv(args: argparse.Namespace) -> int:
    from vlln.errors import ConfigError
    from vlln.oracle.classifier.training import training_sets
    from vlln.oracle.classifier.validation import grouped_cv, leave_one_out

    sets = training_sets()
    if args.leave_out not in sets:
        raise ConfigError(f"--leave-out {args.leave_out!r}: choose one of {sorted(sets)}")
    if args.folds < 2:
        raise ConfigError(f"--folds {args.folds}: cross-validation needs at least 2 folds")
    report = {
        "grouped_cv": grouped_cv(sets, args.folds, args.seed),
        "leave_one_out": leave_one_out(sets, args.leave_out, args.seed),
    }
    if args.json:
        print(json.dumps(report, indent=2))
        return 0
    cv, out = report["grouped_cv"], report["leave_one_out"]
    print(
        f"grouped {cv['folds']}-fold cross-validation over {cv['families']} families of "
        f"{cv['questions']} questions: type {cv['type_accuracy']:.1%}, "
        f"type and topic {cv['label_accuracy']:.1%}"
    )
    for name, accuracy in cv["type_accuracy_by_set"].items():
        print(f"  {name}: type {accuracy:.1%}")
    print(
        f"trained without {out['test_set']}, tested on its {out['questions']} questions: "
        f"type {out['type_accuracy']:.1%}, type and topic {out['label_accuracy']:.1%}"
    )
    return 0


def _oracle_train_classifier(args: argparse.Namespace) -> int:
    from vlln.oracle.classifier.model import load_classifier, packaged_artefact_path
    from vlln.oracle.classifier.training import train_packaged, write_artefact

    path = Path(args.out) if args.out else packaged_artefact_path()
    write_artefact(train_packaged(args.seed), path)
    meta = load_classifier(path).meta
    print(f"wrote {path} (training data {meta['training_digest'][:12]}, seed {args.seed})")
    return 0


def add_oracle_commands(commands: Commands) -> None:
    oracle = commands.add_parser("oracle", help="the oracle").add_subparsers(
        dest="oracle_command", required=True
    )
    serve = oracle.add_parser("serve", help="answer questions over HTTP (FastAPI)")
    serve.add_argument("--host", default="127.0.0.1", help="address (default loopback only)")
    serve.add_argument("--port", type=int, default=8765, help="port (default 8765)")
    serve.add_argument(
        "--token-env",
        help="environment variable holding the bearer token; it must be set and not empty "
        "(without the flag: VLLN_ORACLE_TOKEN when set, else no token, loopback only)",
    )
    serve.add_argument("--episodes", help="an episode file whose episodes sessions can name")
    serve.add_argument(
        "--allow-remote", action="store_true", help="allow a host other than loopback"
    )
    serve.add_argument("--max-sessions", type=int, default=64, help="sessions kept (default 64)")
    serve.add_argument("--oracle-seed", type=int, default=0, help="paraphrase seed (default 0)")
    serve.add_argument(
        "--builds-per-minute", type=int, default=60, help="house builds, all clients (default 60)"
    )
    serve.add_argument(
        "--client-builds-per-minute",
        type=int,
        default=20,
        help="house builds one client address may cause (default 20)",
    )
    serve.add_argument(
        "--log-level",
        default="warning",
        help="uvicorn log level (default warning: no line per request)",
    )
    serve.set_defaults(handler=_oracle_serve)
    report = oracle.add_parser(
        "classify-report", help="accuracy and confusion matrix of the offline classifier"
    )
    report.add_argument("--questions", help="a JSON Lines question set (default: held-out set)")
    report.add_argument("--json", action="store_true", help="print the figures as JSON")
    report.set_defaults(handler=_oracle_classify_report)
    cv = oracle.add_parser(
        "classify-cv",
        help="accuracy of the classifier on questions it was not trained on, without a "
        "held-out file: cross-validation over question families, and one set left out",
    )
    cv.add_argument("--folds", type=int, default=5, help="folds (default 5)")
    cv.add_argument("--seed", type=int, default=0, help="seed of the typo copies (default 0)")
    cv.add_argument("--leave-out", default="v6", help="training set to test on (default v6)")
    cv.add_argument("--json", action="store_true", help="print the figures (and misses) as JSON")
    cv.set_defaults(handler=_oracle_classify_cv)
    train = oracle.add_parser(
        "train-classifier",
        help="fit the offline question classifier on the packaged training questions",
    )
    train.add_argument("--seed", type=int, default=0, help="seed of the typo copies (default 0)")
    train.add_argument("--out", help="where to write it (default: the packaged artefact)")
    train.set_defaults(handler=_oracle_train_classifier)
