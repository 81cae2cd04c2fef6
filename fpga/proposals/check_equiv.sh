#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Checks that fpga/proposals/timing.patch keeps rtl/pluecker_intersector.sv
# cycle-exact: builds tb_equiv.sv with Verilator (--binary --timing) around
# the current RTL and a patched copy (pluecker_mul.sv in its generic form,
# PLUECKER_ECP5 undefined) and compares them on random traffic.
# Usage: fpga/proposals/check_equiv.sh ["C D CONS" ...]   (default: a few widths)
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
if [ -z "${VERILATOR_ROOT:-}" ] && [ -x "$ROOT/.venv/bin/python" ]; then
    VERILATOR_ROOT=$("$ROOT/.venv/bin/python" -c 'import os, verilator; print(os.path.dirname(verilator.__file__))')
    export VERILATOR_ROOT PATH=$VERILATOR_ROOT/bin:$PATH
fi
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cp "$ROOT/rtl/pluecker_intersector.sv" "$WORK/new.sv"
patch -s "$WORK/new.sv" < "$HERE/timing.patch"
sed -i 's/^module pluecker_intersector /module pi_new /' "$WORK/new.sv"
sed 's/^module pluecker_intersector /module pi_base /' "$ROOT/rtl/pluecker_intersector.sv" > "$WORK/base.sv"
configs=("$@")
[ ${#configs[@]} -gt 0 ] || configs=("16 16 1" "16 16 0" "12 20 1" "24 24 1" "6 6 1")
for cfg in "${configs[@]}"; do
    read -r c d cons <<< "$cfg"
    dir="$WORK/obj_${c}_${d}_${cons}"
    verilator --binary --timing -CFLAGS -fcoroutines -Wno-fatal -Wno-lint -Wno-style -j 2 \
        --top-module tb_equiv -GC="$c" -GD="$d" -GCONSERVATIVE="$cons" --Mdir "$dir" -o tb \
        "$HERE/tb_equiv.sv" "$WORK/base.sv" "$WORK/new.sv" "$HERE/pluecker_mul.sv" > "$dir.log" 2>&1 \
        || { cat "$dir.log"; exit 1; }
    "$dir/tb" | grep -E "^tb_equiv|mismatch|FAIL"
done
