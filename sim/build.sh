#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the Verilator harness `pluecker_sim` for one RTL configuration:
# configures sim/CMakeLists.txt (rtl/pluecker_intersector.sv verilated with
# -G parameters, the harness in sim/, the model's libraries from the CMake
# package of its build directory) in SIM_OUT and builds it.
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

C="${COORD_BITS:-16}"
D="${DIR_BITS:-16}"
MODE="${MODE:-conservative}"
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
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || die "SIM_JOBS=$jobs is not a positive integer"

model_build="${MODEL_BUILD:-build/model}"
rtl="${SIM_RTL:-rtl/pluecker_intersector.sv}"
out="${SIM_OUT:-build/sim/${C}x${D}${suffix}}"
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
