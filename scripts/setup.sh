#!/usr/bin/env bash
# Sets vlln up on a fresh Debian/Ubuntu machine with Python 3.11+, in a virtual environment in
# .venv. Two sizes:
#   scripts/setup.sh demo   the package alone (what `make demo` runs: about 0.5 GB), and the
#                           system EGL/Mesa libraries for headless rendering when missing;
#   scripts/setup.sh dev    (the default) everything the tests use besides: Chromium for the
#                           browser tests, torch's CPU build, every extra and the dev tools.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup-lib.sh

MODE="${1:-dev}"
if [ "$MODE" != demo ] && [ "$MODE" != dev ]; then
  echo "error: unknown set-up '$MODE'; use: scripts/setup.sh demo, or scripts/setup.sh dev" >&2
  exit 1
fi

PYTHON="${PYTHON:-python3}"
if ! "$PYTHON" -c 'import sys; sys.exit(sys.version_info < (3, 11))' 2>/dev/null; then
  echo "error: vlln needs Python 3.11 or newer; set PYTHON=/path/to/python3.11" >&2
  exit 1
fi

have_egl() {
  ldconfig -p 2>/dev/null | grep -q 'libEGL.so.1' &&
    { ldconfig -p 2>/dev/null | grep -q 'libEGL_mesa.so.0' ||
      ls /usr/lib/*/dri/swrast_dri.so /usr/lib/*/dri/llvmpipe_dri.so >/dev/null 2>&1; }
}

# apt_install WHY PACKAGE...: install Debian packages, with sudo when not root.
apt_install() {
  local why="$1"
  shift
  echo "Installing $why: $*"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null; then SUDO="sudo"; else
      echo "error: $* missing and this user cannot install them;" \
        "ask an administrator to run: apt-get install $*" >&2
      exit 1
    fi
  fi
  apt_get update -q
  apt_get install -y -q "$@"
}

if ! have_egl; then
  apt_install "the system packages for headless rendering" libegl1 libgl1-mesa-dri
fi
# Headless Chromium for the browser tests (web app, report videos) and `vlln bench web`:
# Debian's package, driven by Playwright's Python client; Playwright's own browser download is
# never used.
if [ "$MODE" = dev ] && ! command -v chromium >/dev/null; then
  apt_install "a headless browser for the browser tests" chromium
fi

if [ ! -x .venv/bin/python ]; then
  "$PYTHON" -m venv .venv
fi
.venv/bin/python -m pip install -q --upgrade pip
if [ "$MODE" = demo ]; then
  .venv/bin/python -m pip install -q -e .
else
  # torch first, the CPU build, so the model extra in .[dev] finds it installed and pulls no
  # CUDA build.
  install_torch .venv/bin/python
  .venv/bin/python -m pip install -q -e '.[dev]'
fi
echo "vlln is installed in .venv (activate with: source .venv/bin/activate)"
