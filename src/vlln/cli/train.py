"""``vlln train ...``: fine-tune a vision-language model on exported data, or learn the
frontier agent's dialog policy."""

from __future__ import annotations

from vlln.cli.generated import add_config_command
from vlln.cli.options import Commands
from vlln.train.config import NewModelConfig, TrainConfig
from vlln.train.dialog_policy import DialogPolicyConfig


def _train_sft(config: TrainConfig) -> int:
    from vlln.train.sft import train_sft

    outcome = train_sft(config)
    if outcome.unchanged:
        print(f"already trained to step {outcome.steps}; nothing to do (model in {config.out_dir})")
        return 0
    resumed = f", resumed from {outcome.resumed_from}" if outcome.resumed_from else ""
    curve = " -> ".join(f"{loss:.3f}" for _, loss in outcome.losses)
    curve = curve or f"not logged (it is every --logging-steps {config.logging_steps} steps)"
    print(
        f"trained to step {outcome.steps} on {outcome.samples} samples in "
        f"{outcome.seconds:.1f} s{resumed}; loss {curve}; model in {config.out_dir}"
    )
    return 0


def _train_new_model(config: NewModelConfig) -> int:
    from vlln.files import replace_folder
    from vlln.train.scratch import build_model, is_model_file

    out = config.out
    replace_folder(out, lambda folder: build_model(folder, config.size, config.seed), is_model_file)
    print(
        f"wrote a randomly initialised {config.size} Qwen2.5-VL-style model to {out} (it has "
        f"learnt nothing): train it with vlln train sft --model {out}, or try the pipeline "
        f"with vlln eval --agent vlln --model {out}"
    )
    return 0


def _train_dialog_policy(config: DialogPolicyConfig) -> int:
    from vlln.train.dialog_policy import train_dialog_policy

    card = train_dialog_policy(config)
    print(
        f"trained on {card.timesteps} decisions ({card.episodes} episodes, {card.houses} "
        f"{card.preset} {card.split} houses) in {card.seconds:.0f} s; policy in {config.out}; "
        f"use it with: vlln eval --agent frontier --dialog-policy {config.out}"
    )
    return 0


def add_train_commands(commands: Commands) -> None:
    train = commands.add_parser("train", help="fine-tuning").add_subparsers(
        dest="train_command", required=True
    )
    add_config_command(
        train, "sft", TrainConfig, _train_sft, help="supervised fine-tuning on a training export"
    )

    add_config_command(
        train,
        "new-model",
        NewModelConfig,
        _train_new_model,
        help="write a random Qwen2.5-VL-style model of a named size (from scratch; no download)",
    )
    add_config_command(
        train,
        "dialog-policy",
        DialogPolicyConfig,
        _train_dialog_policy,
        help="learn when the frontier agent asks (PPO; success minus lam per question)",
    )
