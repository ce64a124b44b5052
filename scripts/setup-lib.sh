# Functions of scripts/setup.sh, in a file of their own so the tests can run them one by one.
# Source it; it runs nothing.

# Another package manager (unattended-upgrades, a second set-up) may hold apt's locks: wait up
# to this many seconds for them instead of failing at once.
APT_LOCK_TIMEOUT="${APT_LOCK_TIMEOUT:-600}"
# The torch build the tests pin, and torch's index of CPU-only wheels (pytorch.org's install
# selector, "Compute Platform: CPU"). On Linux the default index (PyPI) gives the CUDA build,
# which pulls in about 18 nvidia packages and several GB.
TORCH_VERSION="${TORCH_VERSION:-2.13.0}"
TORCH_CPU_INDEX="${TORCH_CPU_INDEX:-https://download.pytorch.org/whl/cpu}"

# apt_get ARGS...: apt-get ARGS as root (prefixed with $SUDO when set), non-interactive,
# waiting up to APT_LOCK_TIMEOUT seconds for locks that another process holds. apt waits for
# the dpkg locks itself (DPkg::Lock::Timeout, apt >= 1.9.11) but not for the package lists'
# lock that `apt-get update` takes, so a run that failed on a lock is tried again until then.
apt_get() {
  local deadline=$((SECONDS + APT_LOCK_TIMEOUT)) log status announced=""
  log="$(mktemp)"
  while :; do
    {
      ${SUDO:-} env DEBIAN_FRONTEND=noninteractive LC_ALL=C apt-get \
        -o DPkg::Lock::Timeout="$((deadline > SECONDS ? deadline - SECONDS : 0))" "$@" \
        2>&1 | tee "$log"
      status="${PIPESTATUS[0]}"
    } || true
    if [ "$status" -eq 0 ] || ! grep -q 'Could not get lock' "$log" ||
      [ "$SECONDS" -ge "$deadline" ]; then
      rm -f "$log"
      return "$status"
    fi
    if [ -z "$announced" ]; then
      echo "waiting up to ${APT_LOCK_TIMEOUT} s for another package manager to release its lock"
      announced=1
    fi
    sleep 2
  done
}

# install_torch PYTHON: torch==$TORCH_VERSION, the CPU build, into PYTHON's environment. From
# torch's CPU wheel index when it answers; where it cannot be reached (a mirror-only or offline
# machine) from pip's configured index, saying so, since on Linux PyPI's build is CUDA's.
install_torch() {
  local python="$1" log
  log="$(mktemp)"
  if "$python" -m pip install -q --retries 1 --timeout 20 --index-url "$TORCH_CPU_INDEX" \
    "torch==$TORCH_VERSION" >"$log" 2>&1; then
    rm -f "$log"
    return 0
  fi
  echo "note: torch's CPU wheel index $TORCH_CPU_INDEX could not be used" \
    "($(grep -m1 -E '^ERROR' "$log" || tail -n1 "$log")); installing torch==$TORCH_VERSION" \
    "from pip's configured index instead (on Linux, PyPI's torch is the larger CUDA build)" >&2
  rm -f "$log"
  "$python" -m pip install -q "torch==$TORCH_VERSION"
}
