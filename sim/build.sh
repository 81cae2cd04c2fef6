#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the Verilator harness `pluecker_sim` for one RTL configuration:
# configures sim/CMakeLists.txt (rtl/pluecker_intersector.sv verilated with
# -G parameters, the harness in sim/, the model's libraries from the CMake
# package of its build directory) in SIM_OUT and builds it. SIM_UNIT=local
# builds `pluecker_sim_local` instead: rtl/pluecker_local_intersector.sv
# with the harness in sim/local/, configured by BOX_BITS (4..16, default
# 8), DIR_BITS (4..24, default BOX_BITS + 3), GRID_BITS (BOX_BITS+2..32,
# default 32), CHILDREN (1..2, default 1), MUL_STYLE (auto|dsp|lut, default
# auto) and MODE; SIM_OUT defaults to
# build/sim/local_k<K>_d<D>_g<G>_c<C>[_nearest][_<style>]. SIM_UNIT=float
# (rtl/pluecker_float_intersector.sv) or smits
# (rtl/pluecker_smits_intersector.sv) builds `pluecker_sim` of a binary32
# unit with the harness in sim/float/: MODE defaults to nearest (float:
# conservative = CONSERVATIVE 1; smits has nearest only), SIM_MUL_DSP (1, 3
# or 4; default the contract's) is MUL_DSP, the widths are not used, and
# SIM_OUT defaults to build/sim/<unit>[_cons]_dsp<M>. SIM_UNIT=array builds
# `pluecker_sim_array`: rtl/pluecker_array.sv with the harness in
# sim/array/, ARRAY_DSP units with MUL_STYLE dsp, ARRAY_LUT with
# MUL_STYLE lut and ARRAY_ROM with MUL_STYLE rom (0..256 each, 1..256
# together; default 1, 1 and 0), one lane each, at COORD_BITS, DIR_BITS,
# MODE, SIM_TAG_BITS and SIM_PIPELINE; a style the port contract has no
# class for at those widths and PIPELINE (fabric units take up to 17 bits,
# table units 6/6 with PIPELINE 2) is refused; SIM_OUT defaults to
# build/sim/array_<N_DSP>x<N_LUT>[x<N_ROM>]_<C>x<D>[_nearest][_p<P>]. SIM_UNIT=cascade builds
# `pluecker_sim_cascade`: rtl/pluecker_cascade.sv with the harness in
# sim/cascade/, CASCADE_N narrow lanes (1..64, default 2; TERNARY units at
# NARROW_COORD_BITS x NARROW_DIR_BITS, default 8 x 8) escalating to one wide
# conservative unit at WIDE_COORD_BITS x WIDE_DIR_BITS (default 16 x 16, at
# least the narrow widths), all within the port contract's limits, at
# SIM_TAG_BITS and SIM_PIPELINE; MODE must be conservative and COORD_BITS /
# DIR_BITS are not used; SIM_OUT defaults to
# build/sim/cascade_<N>_<NC>x<ND>_<WC>x<WD>[_p<P>] (_p<P>: SIM_PIPELINE=P, 1 or 2).
#
# Settings (environment): COORD_BITS, DIR_BITS (the port contract's limits,
# 6..24; default 16),
# MODE (conservative|nearest, default conservative), SIM_TAG_BITS (default 8),
# MODEL_BUILD (default build/model), SIM_RTL (default
# rtl/pluecker_intersector.sv), SIM_OUT (default build/sim/<C>x<D>[_nearest]),
# SIM_JOBS (default 2), SIM_PIPELINE=1 or 2 (the multipliers' extra registers),
# SIM_ASSERT=1 (compile the RTL's ASSERT_ON properties
# into the model; slower), SIM_DIRECT_EVAL=0 (plain eval(), see
# sim/rtl_intersector.cpp), SIM_VFLAGS (extra Verilator flags). Verilator is
# always the venv's: run from elsewhere, the script runs itself again
# through scripts/venv-exec.sh. Prints the binary's path last. Exit 2 on
# bad settings.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"

die() {
  echo "sim/build.sh: error: $*" >&2
  exit 2
}

unit="${SIM_UNIT:-global}"
case "$unit" in
  float | smits) MODE="${MODE:-nearest}" ;;
  *) MODE="${MODE:-conservative}" ;;
esac
T="${SIM_TAG_BITS:-8}"
jobs="${SIM_JOBS:-2}"
is_int_in() {  # <value> <lo> <hi>
  [[ "$1" =~ ^[0-9]+$ ]] && ((10#$1 >= $2 && 10#$1 <= $3))
}
case "$MODE" in
  conservative) suffix="" ;;
  nearest) suffix="_nearest" ;;
  *) die "MODE=$MODE is not one of conservative, nearest" ;;
esac
# C and D from COORD_BITS and DIR_BITS (default 16), within the width
# limits of the port contract (rtl/pluecker_contract.json).
fixed_widths() {
  C="${COORD_BITS:-16}"
  D="${DIR_BITS:-16}"
  read -r lo hi < <(python3 "$root/scripts/contract.py" limits) || true
  [[ "${lo:-}" =~ ^[0-9]+$ && "${hi:-}" =~ ^[0-9]+$ ]] || die "cannot read the port contract (scripts/contract.py limits)"
  for v in "COORD_BITS=$C" "DIR_BITS=$D"; do
    val="${v#*=}"
    is_int_in "$val" "$lo" "$hi" || die "${v%%=*}=$val is not an integer in $lo..$hi"
  done
  C=$((10#$C))
  D=$((10#$D))
}
# The array's units of MUL_STYLE $2 (count $1, named by setting $3) must
# have a class in the port contract at C x D and PIPELINE $4.
array_style_ok() {
  local count="$1" style="$2" setting="$3" pipeline="$4" msg range
  ((count > 0)) || return 0
  msg="$(python3 "$root/scripts/contract.py" row "$C" "$D" --mul-style "$style" --pipeline "$pipeline" \
    2>&1 > /dev/null)" && return 0
  [[ "$msg" == contract:* ]] || die "cannot read the port contract (scripts/contract.py row): $msg"
  range="$(python3 "$root/scripts/contract.py" classes |
    awk -v s="$style" '$5 == s { if ($2 > c) c = $2; if ($4 > d) d = $4; p[$6] = 1 }
      END { printf "up to COORD_BITS=%s DIR_BITS=%s", c, d
            if (!(0 in p) || !(1 in p) || !(2 in p)) { printf " with PIPELINE"; for (k in p) printf " %s", k }
            print "" }')"
  die "$setting=$count: a unit with MUL_STYLE $style takes $range (the port contract," \
    "rtl/pluecker_contract.json), not COORD_BITS=$C DIR_BITS=$D PIPELINE=$pipeline; set $setting=0 or other widths"
}
unit_args=()
case "$unit" in
  global)
    fixed_widths
    default_out="build/sim/${C}x${D}${suffix}"
    unit_args=(-DSIM_COORD_BITS="$C" -DSIM_DIR_BITS="$D")
    binary=pluecker_sim
    ;;
  local)
    # The limits of the local port contract (rtl/pluecker_local_contract.json).
    read -r klo khi dlo dhi margin gmax cmax < <(python3 "$root/scripts/contract.py" local-limits) || true
    [[ "${gmax:-}" =~ ^[0-9]+$ && "${cmax:-}" =~ ^[0-9]+$ ]] ||
      die "cannot read the local port contract (scripts/contract.py local-limits)"
    K="${BOX_BITS:-8}"
    is_int_in "$K" "$klo" "$khi" || die "BOX_BITS=$K is not an integer in $klo..$khi"
    K=$((10#$K))
    dd=$((K + 3 > dhi ? dhi : K + 3))
    D="${DIR_BITS:-$dd}"
    G="${GRID_BITS:-$gmax}"
    CH="${CHILDREN:-1}"
    style="${MUL_STYLE:-auto}"
    is_int_in "$D" "$dlo" "$dhi" || die "DIR_BITS=$D is not an integer in $dlo..$dhi"
    is_int_in "$G" $((K + margin)) "$gmax" || die "GRID_BITS=$G is not an integer in $((K + margin))..$gmax"
    is_int_in "$CH" 1 "$cmax" || die "CHILDREN=$CH is not an integer in 1..$cmax"
    [[ "$style" =~ ^(auto|dsp|lut)$ ]] || die "MUL_STYLE=$style is not one of auto, dsp, lut"
    D=$((10#$D))
    G=$((10#$G))
    CH=$((10#$CH))
    default_out="build/sim/local_k${K}_d${D}_g${G}_c${CH}${suffix}$([[ $style == auto ]] || echo "_$style")"
    unit_args=(-DSIM_BOX_BITS="$K" -DSIM_DIR_BITS="$D" -DSIM_GRID_BITS="$G" -DSIM_CHILDREN="$CH"
      -DSIM_MUL_STYLE="$style")
    binary=pluecker_sim_local
    ;;
  float | smits)
    [[ "$unit" == smits && "$MODE" == conservative ]] && die "SIM_UNIT=smits has no conservative variant (MODE=nearest)"
    mul_dsps="$(python3 "$root/scripts/contract.py" float-limits)" || die "cannot read the float port contract"
    M="${SIM_MUL_DSP:-$(sed -n 's/^default_mul_dsp=//p' <<< "$mul_dsps")}"
    [[ " $(sed -n 's/^mul_dsp=//p' <<< "$mul_dsps") " == *" $M "* ]] ||
      die "SIM_MUL_DSP=$M is not one of $(sed -n 's/^mul_dsp=//p' <<< "$mul_dsps")"
    default_out="build/sim/${unit}$([[ $MODE == conservative ]] && echo _cons || true)_dsp${M}"
    unit_args=(-DSIM_MUL_DSP="$M")
    binary=pluecker_sim
    ;;
  array)
    fixed_widths
    ND="${ARRAY_DSP:-1}"
    NL="${ARRAY_LUT:-1}"
    NR="${ARRAY_ROM:-0}"
    P="${SIM_PIPELINE:-0}"
    is_int_in "$ND" 0 256 || die "ARRAY_DSP=$ND is not an integer in 0..256"
    is_int_in "$NL" 0 256 || die "ARRAY_LUT=$NL is not an integer in 0..256"
    is_int_in "$NR" 0 256 || die "ARRAY_ROM=$NR is not an integer in 0..256"
    ND=$((10#$ND))
    NL=$((10#$NL))
    NR=$((10#$NR))
    ((ND + NL + NR >= 1 && ND + NL + NR <= 256)) ||
      die "ARRAY_DSP + ARRAY_LUT + ARRAY_ROM = $((ND + NL + NR)) is not in 1..256 (the array needs at least one unit)"
    [[ "$P" =~ ^[012]$ ]] || die "SIM_PIPELINE=$P is not 0, 1 or 2"
    array_style_ok "$ND" dsp ARRAY_DSP "$P"
    array_style_ok "$NL" lut ARRAY_LUT "$P"
    array_style_ok "$NR" rom ARRAY_ROM "$P"
    default_out="build/sim/array_${ND}x${NL}$([[ $NR != 0 ]] && echo "x$NR" || true)_${C}x${D}${suffix}$([[ $P != 0 ]] && echo "_p$P" || true)"
    unit_args=(-DSIM_COORD_BITS="$C" -DSIM_DIR_BITS="$D" -DSIM_ARRAY_DSP="$ND" -DSIM_ARRAY_LUT="$NL"
      -DSIM_ARRAY_ROM="$NR")
    binary=pluecker_sim_array
    ;;
  cascade)
    [[ "$MODE" == conservative ]] ||
      die "MODE=$MODE: the cascade is conservative only (its narrow units answer certain hit, certain miss or uncertain)"
    read -r lo hi < <(python3 "$root/scripts/contract.py" limits) || true
    [[ "${lo:-}" =~ ^[0-9]+$ && "${hi:-}" =~ ^[0-9]+$ ]] || die "cannot read the port contract (scripts/contract.py limits)"
    N="${CASCADE_N:-2}"
    NC="${NARROW_COORD_BITS:-8}"
    ND="${NARROW_DIR_BITS:-8}"
    WC="${WIDE_COORD_BITS:-16}"
    WD="${WIDE_DIR_BITS:-16}"
    P="${SIM_PIPELINE:-0}"
    is_int_in "$N" 1 64 || die "CASCADE_N=$N is not an integer in 1..64 (the cascade's narrow lanes)"
    for v in "NARROW_COORD_BITS=$NC" "NARROW_DIR_BITS=$ND" "WIDE_COORD_BITS=$WC" "WIDE_DIR_BITS=$WD"; do
      val="${v#*=}"
      is_int_in "$val" "$lo" "$hi" || die "${v%%=*}=$val is not an integer in $lo..$hi (the port contract's widths)"
    done
    [[ "$P" =~ ^[012]$ ]] || die "SIM_PIPELINE=$P is not 0, 1 or 2"
    N=$((10#$N))
    NC=$((10#$NC))
    ND=$((10#$ND))
    WC=$((10#$WC))
    WD=$((10#$WD))
    ((WC >= NC && WD >= ND)) ||
      die "the wide unit (WIDE_COORD_BITS=$WC WIDE_DIR_BITS=$WD) is narrower than the narrow lanes" \
        "(NARROW_COORD_BITS=$NC NARROW_DIR_BITS=$ND): the wide widths must be at least the narrow ones"
    default_out="build/sim/cascade_${N}_${NC}x${ND}_${WC}x${WD}$([[ $P != 0 ]] && echo "_p$P" || true)"
    unit_args=(-DSIM_CASCADE_N="$N" -DSIM_NARROW_COORD_BITS="$NC" -DSIM_NARROW_DIR_BITS="$ND"
      -DSIM_WIDE_COORD_BITS="$WC" -DSIM_WIDE_DIR_BITS="$WD")
    binary=pluecker_sim_cascade
    ;;
  *) die "SIM_UNIT=$unit is not one of global, local, float, smits, array, cascade" ;;
esac
is_int_in "$T" 1 16 || die "SIM_TAG_BITS=$T is not an integer in 1..16"
T=$((10#$T))
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || die "SIM_JOBS=$jobs is not a positive integer"

model_build="${MODEL_BUILD:-build/model}"
rtl="${SIM_RTL:-rtl/pluecker_intersector.sv}"
out="${SIM_OUT:-$default_out}"
[[ -f "$rtl" ]] || die "RTL source $rtl not found"
[[ -f "$model_build/pluecker-config.cmake" ]] ||
  die "model build $model_build has no CMake package pluecker-config.cmake (run 'make build' first)"

# The venv's Verilator, as scripts/venv-exec.sh sets it.
[[ -x "$root/.venv/bin/python" ]] || die "no venv at $root/.venv (run 'make setup' first)"
venv_root="$("$root/.venv/bin/python" -c 'import os, verilator; print(os.path.dirname(verilator.__file__))')" ||
  die "the venv has no verilator package (run 'make setup')"
if [[ "${VERILATOR_ROOT:-}" != "$venv_root" ]]; then
  exec "$root/scripts/venv-exec.sh" "$0" "$@"
fi

# Absolute paths: CMake keeps them in the build directory's cache.
model_build="$(cd "$model_build" && pwd)"
rtl="$(cd "$(dirname "$rtl")" && pwd)/$(basename "$rtl")"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
asserts=OFF
[[ "${SIM_ASSERT:-0}" = 1 ]] && asserts=ON
direct=ON
[[ "${SIM_DIRECT_EVAL:-1}" = 0 ]] && direct=OFF
# shellcheck disable=SC2206
vflags=(${SIM_VFLAGS:-})
IFS=';'
vlist="${vflags[*]}"
unset IFS

cmake -S "$root/sim" -B "$out" -DCMAKE_BUILD_TYPE=Release -DPLUECKER_MODEL_BUILD="$model_build" \
  -DSIM_UNIT="$unit" "${unit_args[@]}" -DSIM_MODE="$MODE" -DSIM_TAG_BITS="$T" -DSIM_PIPELINE="${SIM_PIPELINE:-0}" -DSIM_RTL="$rtl" \
  -DSIM_ASSERT="$asserts" -DSIM_DIRECT_EVAL="$direct" -DSIM_VFLAGS="$vlist" > "$out/configure.log" 2>&1 ||
  {
    cat "$out/configure.log" >&2
    echo "sim/build.sh: CMake configuration failed (log: $out/configure.log)" >&2
    exit 1
  }
cmake --build "$out" -j "$jobs" > "$out/build.log" 2>&1 ||
  {
    cat "$out/build.log" >&2
    echo "sim/build.sh: Verilator build failed (log: $out/build.log)" >&2
    exit 1
  }
echo "$out/$binary"
