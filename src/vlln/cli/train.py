"""``vlln train ...``: fine-tune a vision-language model on exported data."""

from __future__ import annotations

import argparse
from pathlib import Path

from vlln.cli.options import Commands


def _train_sft(args: argparse.Namespace) -> int:
    from vlln.train.config import TrainConfig
    from vlln.train.sft import train_sft

    config = TrainConfig(
        data_dir=Path(args.data),
        model=args.model,
        out_dir=Path(args.out),
        epochs=args.epochs,
        learning_rate=args.lr,
        vision_learning_rate=args.vision_lr,
        batch_size=args.batch_size,
        grad_accumulation=args.grad_accum,
        max_steps=args.max_steps,
        save_steps=args.save_steps,
        logging_steps=args.logging_steps,
        workers=args.workers,
        seed=args.seed,
        lora=args.lora,
        lora_rank=args.lora_rank,
        max_pixels=args.max_pixels,
        gradient_checkpointing=args.gradient_checkpointing,
        resume=None if args.resume is None else Path(args.resume),
    )
    outcome = train_sft(config)
    if outcome.unchanged:
        print(f"already trained to step {outcome.steps}; nothing to do (model in {args.out})")
        return 0
    resumed = f", resumed from {outcome.resumed_from}" if outcome.resumed_from else ""
    curve = " -> ".join(f"{loss:.3f}" for _, loss in outcome.losses) or "no new steps"
    print(
        f"trained to step {outcome.steps} on {outcome.samples} samples in "
        f"{outcome.seconds:.1f} s{resumed}; loss {curve}; model in {args.out}"
    )
    return 0


def _train_tiny_model(args: argparse.Namespace) -> int:
    from vlln.files import replace_folder
    from vlln.train.tiny import build_tiny_model, is_tiny_model_file

    out = Path(args.out)
    replace_folder(out, lambda folder: build_tiny_model(folder, seed=args.seed), is_tiny_model_file)
    print(
        f"wrote a tiny randomly initialised Qwen2.5-VL-style model to {out} (it has learnt "
        f"nothing): try the pipeline on a CPU with vlln train sft --model {out} and "
        f"vlln eval --agent vlln --model {out}"
    )
    return 0


def add_train_commands(commands: Commands) -> None:
    train = commands.add_parser("train", help="fine-tuning").add_subparsers(
        dest="train_command", required=True
    )
    sft = train.add_parser("sft", help="supervised fine-tuning on a training export")
    sft.add_argument("--data", required=True, help="a folder made by vlln data export-sft")
    sft.add_argument("--model", required=True, help="model folder or Hugging Face name")
    sft.add_argument("--out", required=True, help="output folder (a rerun resumes it)")
    sft.add_argument("--epochs", type=float, default=5.0, help="epochs (default 5)")
    sft.add_argument("--lr", type=float, default=2e-5, help="learning rate (default 2e-5)")
    sft.add_argument(
        "--vision-lr", type=float, default=5e-6, help="vision tower's rate (default 5e-6)"
    )
    sft.add_argument("--batch-size", type=int, default=2, help="per device (default 2)")
    sft.add_argument("--grad-accum", type=int, default=1, help="accumulation steps (default 1)")
    sft.add_argument("--max-steps", type=int, default=-1, help="stop after N optimizer steps")
    sft.add_argument("--save-steps", type=int, default=500, help="checkpoint every N steps")
    sft.add_argument("--logging-steps", type=int, default=10, help="log loss every N steps")
    sft.add_argument("--workers", type=int, default=4, help="data-loader workers (default 4)")
    sft.add_argument("--seed", type=int, default=0, help="seed (default 0)")
    sft.add_argument("--lora", action="store_true", help="train LoRA adapters (small GPUs)")
    sft.add_argument("--lora-rank", type=int, default=16, help="LoRA rank (default 16)")
    sft.add_argument("--max-pixels", type=int, help="cap on pixels per image (fewer tokens)")
    sft.add_argument(
        "--gradient-checkpointing",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="recompute activations (default: on with a GPU)",
    )
    sft.add_argument("--resume", help="a checkpoint folder (default: the newest in --out)")
    sft.set_defaults(handler=_train_sft)

    tiny = train.add_parser(
        "tiny-model",
        help="write a tiny random Qwen2.5-VL-style model (CPU trials and tests; no download)",
    )
    tiny.add_argument("--out", required=True, help="model folder (replaced on a rerun)")
    tiny.add_argument("--seed", type=int, default=0, help="seed of its weights (default 0)")
    tiny.set_defaults(handler=_train_tiny_model)
