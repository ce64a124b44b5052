"""``vlln oracle ...``: serve the oracle, train and measure its question classifier."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING

from vlln.cli.generated import add_config_command
from vlln.cli.options import Commands
from vlln.extras import SERVE_PACKAGES, require_extra

if TYPE_CHECKING:
    from vlln.cli.oracle_settings import (
        ClassifyCvCommand,
        ClassifyReportCommand,
        ServeCommand,
        TrainClassifierCommand,
    )


def _serve_command() -> type[ServeCommand]:
    from vlln.cli.oracle_settings import ServeCommand

    return ServeCommand


def _classify_report_command() -> type[ClassifyReportCommand]:
    from vlln.cli.oracle_settings import ClassifyReportCommand

    return ClassifyReportCommand


def _classify_cv_command() -> type[ClassifyCvCommand]:
    from vlln.cli.oracle_settings import ClassifyCvCommand

    return ClassifyCvCommand


def _train_classifier_command() -> type[TrainClassifierCommand]:
    from vlln.cli.oracle_settings import TrainClassifierCommand

    return TrainClassifierCommand


def _oracle_serve(command: ServeCommand) -> int:
    require_extra("serve", "vlln oracle serve", SERVE_PACKAGES)
    from vlln.oracle_service.config import ServiceConfig, ServiceLimits
    from vlln.oracle_service.server import serve, token_from_environment
    from vlln.tasks.episode import read_episodes

    limits = command.model_dump(include=set(ServiceLimits.model_fields))
    config = ServiceConfig.build(
        {
            **limits,
            "token": token_from_environment(command.token_env),
            "episodes": () if command.episodes is None else tuple(read_episodes(command.episodes)),
        },
        flags=False,
    )
    serve(
        config,
        command.host,
        command.port,
        allow_remote=command.allow_remote,
        log_level=command.log_level,
    )
    return 0


def _oracle_classify_report(command: ClassifyReportCommand) -> int:
    from vlln.oracle.classifier.model import packaged_classifier
    from vlln.oracle.question_set import classifier_report, import_training

    questions = command.questions
    if questions is None:
        import_training("vlln oracle classify-report without --questions (the held-out set)")
        from oracle_training.question_sets import question_set_path

        questions = question_set_path("heldout")
    report = classifier_report(questions)
    report["classifier"] = packaged_classifier().meta
    if command.as_json:
        print(json.dumps({k: v for k, v in report.items() if k != "table"}, indent=2))
        return 0
    print(f"type accuracy: {report['accuracy']:.1%} of {report['questions']} questions")
    for kind, topic in report["topic_accuracy"].items():
        print(f"{kind} topic accuracy: {topic['accuracy']:.1%} of {topic['questions']}")
    print(f"\n{report['table']}")
    return 0


def _oracle_classify_cv(command: ClassifyCvCommand) -> int:
    from vlln.errors import ConfigError
    from vlln.oracle.question_set import import_training

    import_training("vlln oracle classify-cv")
    from oracle_training.training import training_sets
    from oracle_training.validation import grouped_cv, leave_one_out

    sets = training_sets()
    if command.leave_out not in sets:
        raise ConfigError(f"--leave-out {command.leave_out!r}: choose one of {sorted(sets)}")
    report = {
        "grouped_cv": grouped_cv(sets, command.folds, command.seed),
        "leave_one_out": leave_one_out(sets, command.leave_out, command.seed),
    }
    if command.as_json:
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


def _oracle_train_classifier(command: TrainClassifierCommand) -> int:
    from vlln.oracle.classifier.model import load_classifier, packaged_artefact_path
    from vlln.oracle.question_set import import_training

    import_training("vlln oracle train-classifier")
    from oracle_training.training import train_all_sets, write_artefact

    path = command.out or packaged_artefact_path()
    write_artefact(train_all_sets(command.seed), path)
    meta = load_classifier(path).meta
    print(f"wrote {path} (training data {meta['training_digest'][:12]}, seed {command.seed})")
    return 0


def add_oracle_commands(commands: Commands) -> None:
    oracle = commands.add_parser("oracle", help="the oracle").add_subparsers(
        dest="oracle_command", required=True
    )
    add_config_command(
        oracle, "serve", _serve_command, _oracle_serve, help="answer questions over HTTP (FastAPI)"
    )
    add_config_command(
        oracle,
        "classify-report",
        _classify_report_command,
        _oracle_classify_report,
        help="accuracy and confusion matrix of the offline classifier",
    )
    add_config_command(
        oracle,
        "classify-cv",
        _classify_cv_command,
        _oracle_classify_cv,
        help="accuracy of the classifier on questions it was not trained on, without a "
        "held-out file: cross-validation over question families, and one set left out",
    )
    add_config_command(
        oracle,
        "train-classifier",
        _train_classifier_command,
        _oracle_train_classifier,
        help="fit the offline question classifier on the training questions of the "
        "repository's oracle_training/ (a checkout's vlln only)",
    )
