#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the Verilator harness `pluecker_sim` for one RTL configuration:
# rtl/pluecker_intersector.sv verilated with -G parameters, the harness in
# sim/, and the golden model library (build/model/libpluecker_model.a).
#
# Settings (environment): COORD_BITS, DIR_BITS (the port contract's limits,
# 6..24; default 16),
# MODE (conservative|nearest, default conservative), SIM_TAG_BITS (default 8),
# MODEL_BUILD (default build/model), SIM_RTL (default
# rtl/pluecker_intersector.sv), SIM_OUT (default build/sim/<C>x<D>[_nearest]),
# SIM_JOBS (default 2), SIM_ASSERT=1 (compile the RTL's ASSERT_ON properties
# into the model; slower), SIM_DIRECT_EVAL=0 (plain eval(), see
# sim/rtl_intersector.cpp). Run through scripts/venv-exec.sh so that Verilator
# is the venv's. Prints the binary's path last. Exit 2 on bad settings.
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
  conservative) cons=1; suffix="" ;;
  nearest) cons=0; suffix="_nearest" ;;
  *) die "MODE=$MODE is not one of conservative, nearest" ;;
esac

model_build="${MODEL_BUILD:-build/model}"
rtl="${SIM_RTL:-rtl/pluecker_intersector.sv}"
out="${SIM_OUT:-build/sim/${C}x${D}${suffix}}"
lib="$model_build/libpluecker_model.a"
[[ -f "$rtl" ]] || die "RTL source $rtl not found"
[[ -f "$lib" ]] || die "model library $lib not found (run 'make build' first)"
# Absolute paths, so that the same configuration always gives Verilator the
# same command line (a different one makes it rebuild everything).
model_build="$(cd "$model_build" && pwd)"
lib="$model_build/libpluecker_model.a"
rtl="$(cd "$(dirname "$rtl")" && pwd)/$(basename "$rtl")"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
command -v verilator > /dev/null || die "verilator not on PATH (run through scripts/venv-exec.sh)"

# Include directories and libraries as the model's CMake configuration found them.
cache="$model_build/CMakeCache.txt"
cache_get() { sed -n "s/^$1:[A-Z]*=//p" "$cache" 2> /dev/null | head -n1; }
glm_inc="$(cache_get GLM_INCLUDE_DIR)"
gmpxx_lib="$(cache_get GMPXX_LIBRARY)"
gmp_lib="$(cache_get GMP_LIBRARY)"
incs=(-I"$root/model/include" -I"$root/model/cli")
[[ -n "$glm_inc" && "$glm_inc" != /usr/include ]] && incs+=(-I"$glm_inc")
libs=("$lib" -lassimp "${gmpxx_lib:--lgmpxx}" "${gmp_lib:--lgmp}" -pthread)

# Waivers that come with the RTL (rtl/*.vlt), the RTL directory for
# submodules (one module per file) and the port contract's package, which
# -y does not find.
rtl_dir="$(dirname "$rtl")"
shopt -s nullglob
vlt=("$rtl_dir"/*.vlt)
shopt -u nullglob

bin="$out/pluecker_sim"
# Verilator's make does not track the model library: relink when it changed.
if [[ -f "$bin" && "$lib" -nt "$bin" ]]; then rm -f "$bin"; fi

asserts=""
[[ "${SIM_ASSERT:-0}" = 1 ]] && asserts="-DASSERT_ON --assert"
defs="-DSIM_COORD_BITS=$C -DSIM_DIR_BITS=$D -DSIM_TAG_BITS=$T -DSIM_CONSERVATIVE=$cons -DSIM_DIRECT_EVAL=${SIM_DIRECT_EVAL:-1}"
# -ffp-contract=off: as the model library (model/CMakeLists.txt).
# shellcheck disable=SC2086
verilator --cc --exe --build -O3 --x-assign fast --x-initial fast -Wall \
  --top-module pluecker_intersector --prefix Vpluecker_intersector \
  -GCOORD_BITS="$C" -GDIR_BITS="$D" -GTAG_BITS="$T" -GCONSERVATIVE="$cons" \
  -y "$rtl_dir" $asserts ${SIM_VFLAGS:-} \
  --Mdir "$out" -o pluecker_sim -j "$jobs" \
  -CFLAGS "-std=c++20 -ffp-contract=off ${incs[*]} $defs" \
  -LDFLAGS "${libs[*]}" \
  -MAKEFLAGS "OPT_FAST=-O3 OPT_SLOW=-O1 OPT_GLOBAL=-O1" \
  "${vlt[@]}" "$rtl_dir/pluecker_contract_pkg.sv" "$rtl" \
  "$root"/sim/{main,cmd_query,cmd_render,cmd_bench,cmd_gen,rtl_intersector,rtl_engine}.cpp \
  "$root"/model/cli/args.cpp > "$out/build.log" 2>&1 ||
  {
    cat "$out/build.log" >&2
    echo "sim/build.sh: Verilator build failed (log: $out/build.log)" >&2
    exit 1
  }
echo "$bin"
