#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the Verilator harness `pluecker_sim` for one RTL configuration:
# configures sim/CMakeLists.txt (rtl/pluecker_intersector.sv, or a binary32
# unit, verilated with -G parameters, the harness in sim/ or sim/float/, the
# model's libraries from the CMake package of its build directory) in
# SIM_OUT and builds it.
#
# SIM_UNIT (fixed|float|smits, default fixed): the unit. For float and smits,
# MODE defaults to nearest (float: conservative = CONSERVATIVE 1; smits has
# nearest only), SIM_MUL_DSP (1, 3 or 4; default the contract's) is MUL_DSP,
# the widths are not used, and SIM_OUT defaults to
# build/sim/<unit>[_cons]_dsp<M>.
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

UNIT="${SIM_UNIT:-fixed}"
case "$UNIT" in
  fixed) MODE="${MODE:-conservative}" ;;
  float | smits) MODE="${MODE:-nearest}" ;;
  *) die "SIM_UNIT=$UNIT is not one of fixed, float, smits" ;;
esac
C="${COORD_BITS:-16}"
D="${DIR_BITS:-16}"
T="${SIM_TAG_BITS:-8}"
jobs="${SIM_JOBS:-2}"
# The width limits of the port contract (rtl/pluecker_contract.json).
read -r lo hi < <(python3 "$root/scripts/contract.py" limits) || true
[[ "${lo:-}" =~ ^[0-9]+$ && "${hi:-}" =~ ^[0-9]+$ ]] || die "cannot read the port contract (scripts/contract.py limits)"
for v in "COORD_BITS=$C" "DIR_BITS=$D"; do
  val="${v#*=}"
  [[ "$val" =~ ^[0-9]+$ ]] && ((10#$val >= lo && 10#$val <= hi)) ||
    die "${v%%=*}=$val is not an integer in $lo..$hi"
done
C=$((10#$C))
D=$((10#$D))
[[ "$T" =~ ^[0-9]+$ ]] && ((10#$T >= 1 && 10#$T <= 16)) || die "SIM_TAG_BITS=$T is not an integer in 1..16"
T=$((10#$T))
case "$MODE" in
  conservative) suffix="" ;;
  nearest) suffix="_nearest" ;;
  *) die "MODE=$MODE is not one of conservative, nearest" ;;
esac
[[ "$UNIT" == smits && "$MODE" == conservative ]] && die "SIM_UNIT=smits has no conservative variant (MODE=nearest)"
M="${SIM_MUL_DSP:-}"
if [[ "$UNIT" != fixed ]]; then
  mul_dsps="$(python3 "$root/scripts/contract.py" float-limits)" || die "cannot read the float port contract"
  [[ -n "$M" ]] || M="$(sed -n 's/^default_mul_dsp=//p' <<< "$mul_dsps")"
  [[ " $(sed -n 's/^mul_dsp=//p' <<< "$mul_dsps") " == *" $M "* ]] ||
    die "SIM_MUL_DSP=$M is not one of $(sed -n 's/^mul_dsp=//p' <<< "$mul_dsps")"
  name="${UNIT}$([[ $MODE == conservative ]] && echo _cons || true)_dsp${M}"
else
  M=4
  name="${C}x${D}${suffix}"
fi
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || die "SIM_JOBS=$jobs is not a positive integer"

model_build="${MODEL_BUILD:-build/model}"
rtl="${SIM_RTL:-rtl/pluecker_intersector.sv}"
out="${SIM_OUT:-build/sim/${name}}"
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
  -DSIM_COORD_BITS="$C" -DSIM_DIR_BITS="$D" -DSIM_MODE="$MODE" -DSIM_TAG_BITS="$T" -DSIM_PIPELINE="${SIM_PIPELINE:-0}" -DSIM_RTL="$rtl" \
  -DSIM_UNIT="$UNIT" -DSIM_MUL_DSP="$M" \
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
echo "$out/pluecker_sim"
