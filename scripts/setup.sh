#!/usr/bin/env bash
# Installs everything vlln needs on a fresh Debian/Ubuntu machine with Python 3.11+:
# the system EGL/Mesa libraries for headless rendering and Chromium for the browser tests
# (each only when missing), a virtual
# environment in .venv, and the package with its development tools.
set -euo pipefail
cd "$(dirname "$0")/.."

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
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q "$@"
}

if ! have_egl; then
  apt_install "the system packages for headless rendering" libegl1 libgl1-mesa-dri
fi
# Headless Chromium for the browser tests (web app, report videos) and `vlln bench web`:
# Debian's package, driven by Playwright's Python client; Playwright's own browser download is
# never used.
if ! command -v chromium >/dev/null; then
  apt_install "a headless browser for the browser tests" chromium
fi

if [ ! -x .venv/bin/python ]; then
  "$PYTHON" -m venv .venv
fi
.venv/bin/python -m pip install -q --upgrade pip
# torch first, pinned to the CPU build, so the model extra in .[dev] finds it installed and
# pulls no CUDA build.
.venv/bin/python -m pip install -q torch==2.13.0
.venv/bin/python -m pip install -q -e '.[dev]'
echo "vlln is installed in .venv (activate with: source .venv/bin/activate)"
