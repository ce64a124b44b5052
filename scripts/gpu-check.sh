#!/usr/bin/env bash
# The GPU check: 20 `vlln train sft` steps, `--agent vlln` decisions at 1 and 4 episodes side
# by side, and the renderer's frame rate, on Qwen2.5-VL-3B-Instruct's architecture with random
# weights (no download). One JSON line per figure on stdout (docs/scale.md).
#
#   scripts/gpu-check.sh                # on a GPU machine: the 3B architecture in bfloat16
#   scripts/gpu-check.sh --tiny         # anywhere: the tiny model on the CPU (or VLLN_GPU_CHECK_TINY=1)
#   scripts/gpu-check.sh --help         # every flag (decisions, sft steps, device, work folder)
#
# PYTHON names the interpreter (default: python3); the repository's src/ is put first on
# PYTHONPATH, so a checkout runs without being installed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PYTHONPATH="$root/src${PYTHONPATH:+:$PYTHONPATH}"
args=(bench gpu-check --json)
if [[ "${VLLN_GPU_CHECK_TINY:-0}" == "1" ]]; then
    args+=(--tiny)
fi
exec "${PYTHON:-python3}" -m vlln.cli "${args[@]}" "$@"
