"""``vlln train sft``: supervised fine-tuning of a Qwen-VL-style model on a training export,
with Hugging Face's Trainer.

The out folder holds ``checkpoint-N/`` folders while training (a rerun with the same out
folder resumes from the newest one, its weights included; a rerun of a finished run changes
nothing), then the final model with its tokenizer, image
processor and chat template, loadable by ``vlln eval --agent vlln --model OUT``, its model card
(:mod:`vlln.agents.local.card`: the export's history length and houses, which the agent and
``vlln eval`` read) and ``training.json`` with the settings and the loss curve. LoRA adapters
are merged into the final model. Under ``accelerate launch`` or ``torchrun`` every process
trains on its share of each batch (see docs/training.md).
"""

from __future__ import annotations

import json
import shutil
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from vlln.agents.local.card import read_card, write_card
from vlln.agents.local.dependencies import MODEL_PACKAGES, require_model_extra
from vlln.errors import ConfigError, DataFormatError, WriteError
from vlln.files import ReadCap, parse_json, write_text_atomic, writing
from vlln.train.config import TrainConfig

SUMMARY_FILE = "training.json"
_STATE_FILE = "trainer_state.json"
_WEIGHT_FILES = ("model.safetensors", "model.safetensors.index.json")
# Both hold one short entry per logged step: 64 MiB is hundreds of thousands of steps.
_RECORD_CAP = ReadCap("a trainer_state.json or training.json", 64)
LORA_TARGETS = r".*language_model.*\.(q_proj|k_proj|v_proj|o_proj|gate_proj|up_proj|down_proj)"


@dataclass
class TrainOutcome:
    out_dir: Path
    samples: int
    steps: int
    seconds: float
    losses: list[tuple[int, float]] = field(default_factory=list)  # (step, training loss)
    resumed_from: str | None = None
    unchanged: bool = False  # the run had finished before: nothing trained, nothing written


def train_sft(config: TrainConfig) -> TrainOutcome:
    """Fine-tune ``config.model`` on ``config.data_dir`` into ``config.out_dir``."""
    require_model_extra((*MODEL_PACKAGES, "peft") if config.lora else MODEL_PACKAGES)
    import torch
    from transformers import Trainer, TrainerCallback, TrainerState
    from transformers.trainer_utils import get_last_checkpoint

    from vlln.agents.local.encoding import ChatEncoder
    from vlln.train.data import SftCollator, export_facts, read_export
    from vlln.train.optim import parameter_groups

    samples = read_export(config.data_dir)
    facts = export_facts(config.data_dir)
    config.out_dir.mkdir(parents=True, exist_ok=True)
    resume = _resume_point(config, get_last_checkpoint)
    encoder = ChatEncoder.load(config.model, max_pixels=config.max_pixels)
    on_gpu = torch.cuda.is_available()
    model, weights_from = _load_model(config, resume)
    arguments = _training_arguments(config, on_gpu)

    class SftTrainer(Trainer):
        def create_optimizer(self, model: Any = None) -> Any:
            if self.optimizer is None:
                trained: Any = self.model
                optimizer_class, options = Trainer.get_optimizer_cls_and_kwargs(self.args, trained)
                groups = parameter_groups(
                    trained, config.learning_rate, config.vision_learning_rate
                )
                self.optimizer = optimizer_class(groups, **options)
            return self.optimizer

        def _load_from_checkpoint(self, resume_from_checkpoint: str, model: Any = None) -> None:
            # The Trainer's own loader reads the checkpoint's keys as saved, in the original
            # layout (``visual.*``), not the model's (``model.visual.*``), and so loads nothing
            # (huggingface/transformers#43701); the weights came through from_pretrained above.
            if resume_from_checkpoint != weights_from or self.is_fsdp_enabled:
                super()._load_from_checkpoint(resume_from_checkpoint, model)

        def _save_checkpoint(self, model: Any, trial: Any) -> None:
            # One cut short (a full disk) is removed, so a rerun resumes from the one before.
            folder = config.out_dir / f"checkpoint-{self.state.global_step}"
            try:
                with writing(folder):
                    super()._save_checkpoint(model, trial)
            except WriteError:
                shutil.rmtree(folder, ignore_errors=True)
                raise

    class SaveEncoder(TrainerCallback):
        """Each checkpoint also gets the tokenizer, image processor and template."""

        def on_save(self, args: Any, state: Any, control: Any, **kwargs: Any) -> None:
            if state.is_world_process_zero and not config.lora:
                folder = Path(args.output_dir) / f"checkpoint-{state.global_step}"
                with writing(folder):
                    encoder.save(folder)

    trainer = SftTrainer(
        model=model,
        args=arguments,
        train_dataset=samples,
        data_collator=SftCollator(encoder),
        callbacks=[SaveEncoder()],
    )
    planned = trainer.set_initial_training_values(arguments, trainer.get_train_dataloader())[-1]
    started = time.perf_counter()
    finished = False
    if resume is not None and _steps_done(resume) >= planned:
        # Finished already; the Trainer would take one step more before it checks the end.
        finished = True
        trainer.state = TrainerState.load_from_json(str(Path(resume) / _STATE_FILE))
    else:
        trainer.train(resume_from_checkpoint=resume)
    seconds = time.perf_counter() - started
    losses = [
        (int(entry["step"]), float(entry["loss"]))
        for entry in trainer.state.log_history
        if "loss" in entry
    ]
    outcome = TrainOutcome(
        config.out_dir, len(samples), trainer.state.global_step, seconds, losses, resume
    )
    if finished and _final_is_saved(config, outcome.steps):
        outcome.unchanged = True
        return outcome
    with writing(config.out_dir):
        _save_final(trainer, encoder, config)
    if trainer.is_world_process_zero():
        _write_summary(config, outcome)
        card = read_card(config.model).replace(
            history_frames=facts.history_frames,
            image_max_pixels=encoder.image_processor.size.get("longest_edge"),
            houses=facts.houses,
            trained_steps=outcome.steps,
        )
        write_card(config.out_dir, card)
    return outcome


def _resume_point(config: TrainConfig, last_checkpoint: Any) -> str | None:
    if config.resume is not None:
        if not (config.resume / _STATE_FILE).is_file():
            raise ConfigError(
                f"{config.resume} is not a training checkpoint (no trainer_state.json); "
                f"pass one of the checkpoint-N folders in {config.out_dir}"
            )
        return str(config.resume)
    found = last_checkpoint(str(config.out_dir))
    return None if found is None else str(found)


def _load_model(config: TrainConfig, resume: str | None) -> tuple[Any, str]:
    """The model to train and the folder its trained weights came from: the checkpoint when
    resuming (through from_pretrained, which maps the saved key layout onto the model's),
    else ``config.model``. With LoRA the base model is ``config.model`` and the adapters come
    from the checkpoint."""
    import torch
    from transformers import AutoModelForImageTextToText

    from vlln.agents.local.encoding import model_loading

    names = ("adapter_config.json",) if config.lora else _WEIGHT_FILES
    saved = resume is not None and any((Path(resume) / name).is_file() for name in names)
    source = config.model if config.lora or not saved else str(resume)
    with model_loading(source):
        model = AutoModelForImageTextToText.from_pretrained(source, dtype=torch.float32)
    if not config.lora:
        return model, source
    from peft import LoraConfig, PeftModel, get_peft_model

    if saved:
        return PeftModel.from_pretrained(model, str(resume), is_trainable=True), str(resume)
    rank = config.lora_rank
    settings = LoraConfig(
        r=rank, lora_alpha=2 * rank, lora_dropout=0.05, target_modules=LORA_TARGETS
    )
    return get_peft_model(model, settings), source


def _steps_done(checkpoint: str) -> int:
    path = Path(checkpoint) / _STATE_FILE
    try:
        return int(parse_json(_RECORD_CAP.read(path)).get("global_step", 0))
    except (OSError, ValueError, TypeError, AttributeError) as error:
        raise DataFormatError(
            f"{path}: not a trainer state ({error}); delete its checkpoint folder or resume "
            "from another with --resume"
        ) from None


def _final_is_saved(config: TrainConfig, steps: int) -> bool:
    """Whether ``out_dir`` already holds the final model of a run of ``steps`` steps."""
    summary = config.out_dir / SUMMARY_FILE
    if not summary.is_file() or not any((config.out_dir / n).is_file() for n in _WEIGHT_FILES):
        return False
    try:
        return int(parse_json(_RECORD_CAP.read(summary)).get("steps", -1)) == steps
    except (ValueError, TypeError, AttributeError):
        return False


def _training_arguments(config: TrainConfig, on_gpu: bool) -> Any:
    import torch
    from transformers import TrainingArguments

    bf16 = on_gpu and torch.cuda.is_bf16_supported()
    checkpointing = (
        on_gpu if config.gradient_checkpointing is None else config.gradient_checkpointing
    )
    return TrainingArguments(
        output_dir=str(config.out_dir),
        num_train_epochs=config.epochs,
        max_steps=config.max_steps,
        per_device_train_batch_size=config.batch_size,
        gradient_accumulation_steps=config.grad_accumulation,
        learning_rate=config.learning_rate,
        lr_scheduler_type="cosine",
        warmup_steps=config.warmup_ratio,  # a value below 1 is a fraction of the steps
        weight_decay=0.0,
        max_grad_norm=config.max_grad_norm,
        bf16=bf16,
        activation_checkpointing=checkpointing,
        activation_checkpointing_kwargs={"use_reentrant": False} if checkpointing else None,
        logging_steps=config.logging_steps,
        save_strategy="steps",
        save_steps=config.save_steps,
        save_total_limit=config.save_limit,
        dataloader_num_workers=config.workers,
        dataloader_persistent_workers=config.workers > 0,  # each keeps the frames it processed
        dataloader_pin_memory=on_gpu,
        remove_unused_columns=False,
        report_to="none",
        seed=config.seed,
        disable_tqdm=False,
    )


def _save_final(trainer: Any, encoder: Any, config: TrainConfig) -> None:
    """The final model in ``out_dir`` (called on every process: a sharded model is gathered)."""
    if not config.lora:
        trainer.save_model(str(config.out_dir))
    elif trainer.is_world_process_zero():
        trainer.model.merge_and_unload().save_pretrained(config.out_dir)
    if trainer.is_world_process_zero():
        encoder.save(config.out_dir)


def _write_summary(config: TrainConfig, outcome: TrainOutcome) -> None:
    document = {
        "settings": config.to_json(),
        "samples": outcome.samples,
        "steps": outcome.steps,
        "seconds": round(outcome.seconds, 3),
        "resumed_from": outcome.resumed_from,
        "losses": [{"step": step, "loss": loss} for step, loss in outcome.losses],
    }
    write_text_atomic(config.out_dir / SUMMARY_FILE, json.dumps(document, indent=2) + "\n")
