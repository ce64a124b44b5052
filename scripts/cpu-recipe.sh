#!/usr/bin/env bash
# The CPU recipe (docs/learning.md): teacher data on small training houses, a model made from
# scratch and trained on it, then the model, random, FBE (noisy detector) and the teacher
# played on held-out test houses that nothing was trained or tuned on.
#
#   make setup-train && scripts/cpu-recipe.sh            # everything into out/recipe
#   OUT=out/r2 STEPS=2000 EPISODES=50 scripts/cpu-recipe.sh
#
# Every stage resumes what an earlier call left (data, export, checkpoints, evaluation runs),
# so a killed recipe goes on where it stopped. Figures: $OUT/figures.md (held-out SR and SPL
# with intervals of every run, dialog gains, the learning curve; vlln bench recipe-figures).
# The scale is set by the variables below; the defaults fit 3 hours on a 2-core machine.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VLLN="${VLLN:-$root/.venv/bin/vlln}"
OUT="${OUT:-out/recipe}"
HOUSES="${HOUSES:-30}"          # small training houses (their ObjectNav split: 109 MB of JSON;
                                # above about 35, raise VLLN_MAX_EPISODE_FILE_MB from 128)
PER_HOUSE="${PER_HOUSE:-6}"     # teacher trajectories tried per house and task
SIZE="${SIZE:-tiny}"            # vlln train new-model --size
STEPS="${STEPS:-4000}"          # training steps; a checkpoint every quarter
BATCH="${BATCH:-8}"
LR="${LR:-2e-3}"
EPISODES="${EPISODES:-100}"     # held-out episodes per task and run
CURVE_EPISODES="${CURVE_EPISODES:-50}"  # held-out episodes per earlier checkpoint
SEED="${SEED:-0}"
# The data build and every evaluation run JOBS processes side by side (one per core).
JOBS="${JOBS:-2}"

mkdir -p "$OUT"
log() { printf '%s %s\n' "$(date +%H:%M:%S)" "$*" >&2; }

# 1. Teacher data: frontier exploration with dialog (IIGN) and without (ObjectNav), on the
#    training split of the small houses, built in JOBS shards side by side.
for task in iign objectnav; do
    log "data build $task"
    for ((shard = 0; shard < JOBS; shard++)); do
        "$VLLN" data build --preset small --split train --houses "$HOUSES" \
            --per-house "$PER_HOUSE" --task "$task" --seed "$SEED" --shard "$shard/$JOBS" \
            --out "$OUT/data-$task" --quiet --yes &
    done
    wait
done

#    A few teacher trajectories on held-out test houses: never trained on, only asked, to
#    measure how much of the teacher's decisions a checkpoint makes alike off its training data.
log "data build held-out iign"
"$VLLN" data build --preset small --split test --houses "${AGREEMENT_HOUSES:-6}" --per-house 4 \
    --task iign --seed "$SEED" --out "$OUT/data-heldout" --quiet --yes

# 2. One mixed export of both tasks (the reference's conversation format, 8 history frames),
#    with a one-step sample where the teacher steps forward with no goal in view: without
#    them an exact imitator is stranded before the STOP in most trajectories.
if [[ ! -f "$OUT/sft/export.json" ]]; then
    log "export"
    "$VLLN" data export-sft "$OUT/data-iign" "$OUT/data-objectnav" --seed "$SEED" \
        --forward-steps --out "$OUT/sft" --quiet
fi

if [[ ! -f "$OUT/sft-heldout/export.json" ]]; then
    "$VLLN" data export-sft "$OUT/data-heldout" --seed "$SEED" --forward-steps \
        --out "$OUT/sft-heldout" --quiet
fi

# 3. A model from scratch, trained with a checkpoint every quarter (the learning curve).
if [[ ! -f "$OUT/model-new/config.json" ]]; then
    "$VLLN" train new-model --size "$SIZE" --seed "$SEED" --out "$OUT/model-new"
fi
log "train $STEPS steps"
OMP_NUM_THREADS="${OMP_NUM_THREADS:-$JOBS}" "$VLLN" train sft --data "$OUT/sft" \
    --model "$OUT/model-new" --out "$OUT/model" --max-steps "$STEPS" --batch-size "$BATCH" \
    --lr "$LR" --vision-lr "$LR" --save-steps $((STEPS / 4)) --save-limit 4 --workers 1 \
    --logging-steps $((STEPS / 40 > 0 ? STEPS / 40 : 1)) --seed "$SEED"

# 4. Held-out evaluation: the test split of the small houses, never trained on. Each run is
#    JOBS shards side by side (one core each) and resumes; the model plays CONCURRENT
#    episodes per shard, its decisions batched.
evaluate() {  # evaluate NAME TASK EPISODES AGENT-FLAGS...
    local name="$1" task="$2" episodes="$3"
    shift 3
    log "eval $name"
    for ((shard = 0; shard < JOBS; shard++)); do
        OMP_NUM_THREADS=1 "$VLLN" eval --preset small --split test --task "$task" \
            --episodes "$episodes" --seed "$SEED" --shard "$shard/$JOBS" \
            --out "$OUT/eval/$name/shard-$shard" --quiet "$@" > /dev/null &
    done
    wait
}
model=(--agent vlln --concurrent "${CONCURRENT:-8}")
for task in iign objectnav; do
    budgets=(--budgets 0,5)
    [[ "$task" == objectnav ]] && budgets=(--budgets 0)
    evaluate "$task-model" "$task" "$EPISODES" "${model[@]}" --model "$OUT/model" "${budgets[@]}"
    evaluate "$task-random" "$task" "$EPISODES" --agent random "${budgets[@]}"
    evaluate "$task-fbe" "$task" "$EPISODES" --agent fbe --detector noisy "${budgets[@]}"
    evaluate "$task-teacher" "$task" "$EPISODES" --agent frontier --detector truth "${budgets[@]}"
done

# 5. The learning curve: each checkpoint's agreement with the teacher on training and
#    held-out prompts, and held-out IIGN SR at budget 5 of each earlier checkpoint; then the
#    figures (SR and SPL with intervals, dialog gains, the curve) into figures.md.
mkdir -p "$OUT/agreement"
for checkpoint in "$OUT"/model/checkpoint-*; do
    steps="${checkpoint##*-}"
    for split in train heldout; do
        export_dir="$OUT/sft"
        [[ "$split" == heldout ]] && export_dir="$OUT/sft-heldout"
        file="$OUT/agreement/$steps-$split.jsonl"
        [[ -s "$file" ]] && continue
        log "agreement $steps $split"
        OMP_NUM_THREADS="$JOBS" "$VLLN" bench agreement --model "$checkpoint" \
            --export "$export_dir" --samples "${AGREEMENT_SAMPLES:-200}" --json > "$file.part"
        mv "$file.part" "$file"
    done
done
for checkpoint in "$OUT"/model/checkpoint-*; do
    steps="${checkpoint##*-}"
    # the final model's run is iign-model; CURVE_EPISODES=0 leaves the curve out
    [[ "$steps" == "$STEPS" || "$CURVE_EPISODES" == 0 ]] && continue
    evaluate "curve-$steps" iign "$CURVE_EPISODES" "${model[@]}" --model "$checkpoint" \
        --budgets 5
done
"$VLLN" bench recipe-figures --out "$OUT" > "$OUT/figures.md"
log "done: $OUT/figures.md"
