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
# SIM_OUT defaults to build/sim/<unit>[_cons]_dsp<M>.
#
# Settings (environment): COORD_BITS, DIR_BITS (the port contract's limits,
# 6..24; default 16),
# MODE (conservative|nearest, default conservative), SIM_TAG_BITS (default 8),
# MODEL_BUILD (default build/model), SIM_RTL (default
# rtl/pluecker_intersector.sv), SIM_OUT (default build/sim/<C>x<D>[_nearest]),
# SIM_JOBS (default 2), SIM_PIPELINE=1 (the multipliers' extra register),
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
unit_args=()
case "$unit" in
  global)
    C="${COORD_BITS:-16}"
    D="${DIR_BITS:-16}"
    # The width limits of the port contract (rtl/pluecker_contract.json).
    read -r lo hi < <(python3 "$root/scripts/contract.py" limits) || true
    [[ "${lo:-}" =~ ^[0-9]+$ && "${hi:-}" =~ ^[0-9]+$ ]] || die "cannot read the port contract (scripts/contract.py limits)"
    for v in "COORD_BITS=$C" "DIR_BITS=$D"; do
      val="${v#*=}"
      is_int_in "$val" "$lo" "$hi" || die "${v%%=*}=$val is not an integer in $lo..$hi"
    done
    C=$((10#$C))
    D=$((10#$D))
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
  *) die "SIM_UNIT=$unit is not one of global, local, float, smits" ;;
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
