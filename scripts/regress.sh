#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The long reliability regression (`make sim-regress`):
#
#   1. model: the long versions of the numerical-extremes and margin suites
#      (PLUECKER_LONG=1 model_tests --gtest_filter='Extremes.*:MarginBound.*'):
#      1M extreme + 1M transformed queries at every width pair of
#      {6, 9, ..., 24}^2, the margin's boundary constructions, the exhaustive
#      6/6 lattice and the 7/6 and 6/8 domains; zero false misses required;
#      and the set-up suites (PLUECKER_LONG=1 model_tests --gtest_filter=
#      'Setup.*': rays from anywhere at every width pair 6..24);
#   2. RTL: REGRESS_N (default 10^6) extreme queries (pluecker_sim gen --kind
#      extreme) and REGRESS_N set-up queries (--kind setup: far cameras and
#      lights, long directions, the range cube's edges, for the width's
#      range) through the Verilated RTL at each of REGRESS_WIDTHS with
#      `pluecker_sim query --check` (zero mismatches against the model), and
#      the RTL's answers against `pluecker query --test exact` (zero false
#      misses in conservative mode); then REGRESS_N datapath operands on the
#      decision boundaries (--kind boundary: the margin's bound, the end and
#      origin tests) and REGRESS_N from the full port ranges (--kind ports),
#      the cocotb bench's boundary and raw sources, against the model (zero
#      mismatches; they are not float queries, so there is no exact run).
#      The harness is built with the RTL's
#      ASSERT_ON assertions compiled in (SIM_ASSERT=1), in its own
#      directories (REGRESS_SIM_ROOT), so that it does not force `make sim`'s
#      builds to be redone;
#   2b. local: the local unit (rtl/pluecker_local_intersector.sv) through its
#      harness (pluecker_sim_local, SIM_UNIT=local, ASSERT_ON compiled in) at
#      each of REGRESS_LOCAL_CONFIGS: REGRESS_LOCAL_N extreme queries and
#      REGRESS_LOCAL_N / 2 each of set-up, boundary and random queries
#      (pluecker_sim_local gen), each box in its tight frame, with
#      `pluecker_sim_local query --check` (zero mismatches against the model,
#      every child box of every RTL query checked) and, in conservative mode,
#      the answers against `pluecker query --test exact` (zero false misses);
#      2.5 REGRESS_LOCAL_N queries per configuration, 10^7 at the defaults;
#   3. cocotb: the long stress bench (PLUECKER_LONG=1
#      tb/pluecker_intersector/test_stress.py: LATENCY 6, 7 and 8), its sizes
#      scaled with REGRESS_N (25x the `make test` sizes at 10^6, never below
#      1x);
#   4. sweep: the long cocotb sweeps (PLUECKER_LONG=1): the intersector at
#      every width pair of its sweep in both modes and its DSP builds
#      (tb/pluecker_intersector/test_pluecker_intersector.py), the local unit
#      and its two parts at every configuration of their sweeps, their
#      MULT18X18D builds included (tb/pluecker_local_intersector,
#      tb/pluecker_local_frame, tb/pluecker_local_child), and the
#      multipliers and the MULT18X18D model checks (tb/pluecker_mul,
#      tb/pluecker_mul_lut, tb/mult18x18d), 25x the `make test` queries;
#      the binary32 units and their primitives (tb/pluecker_float_intersector,
#      tb/pluecker_smits_intersector with their ECP5 DSP builds,
#      tb/pluecker_f32_add, tb/pluecker_f32_mul);
#   5. float: the binary32 units through the Verilator harness (sim/float,
#      built with ASSERT_ON): for each of REGRESS_FLOAT_UNITS (default
#      "float float_cons smits") REGRESS_FLOAT_N (default 10^7) queries with
#      `pluecker_sim check`: 40 % extreme families and 20 % random queries
#      (also against exact_hit: false misses and false hits), 30 % bit
#      patterns over the whole port range (raw) and 10 % operands around
#      2^-126 (tiny); zero mismatches against the model required, and zero
#      false misses for the conservative unit. The long model suite of the
#      units (PLUECKER_LONG=1 model_tests --gtest_filter='F32Unit.*') first.
#
# Environment: MODEL_BUILD (default build/model; must hold model_tests,
# pluecker and the Python module), JOBS (default 2), REGRESS_N,
# REGRESS_WIDTHS (default "6x6 9x15 16x16 20x8 22x22 23x23 24x24 16x16n 7x22n":
# LATENCY 6, 7 and 8; a trailing n = nearest mode, where the exact comparison
# is skipped), REGRESS_SIM_ROOT
# (default build/regress/sim), REGRESS_ASSERT (default 1: SIM_ASSERT for the
# harness), REGRESS_OUT (default build/regress), REGRESS_PARTS (default
# "model rtl local cocotb sweep float"), REGRESS_LOCAL_N (default 1000000),
# REGRESS_LOCAL_CONFIGS (default "8x11x32c1 8x11x32c2 12x15x32c2 4x7x6c1":
# BOX_BITSxDIR_BITSxGRID_BITS, c CHILDREN, a trailing n = nearest mode),
# REGRESS_FLOAT_N, REGRESS_FLOAT_UNITS.
# Exit status 0 only when every part passes. Run through scripts/venv-exec.sh
# (the Makefile does).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
model_build="$(cd "${MODEL_BUILD:-build/model}" && pwd)"
jobs="${JOBS:-2}"
n="${REGRESS_N:-1000000}"
widths="${REGRESS_WIDTHS:-6x6 9x15 16x16 20x8 22x22 23x23 24x24 16x16n 7x22n}"
sim_root="${REGRESS_SIM_ROOT:-build/regress/sim}"
sim_assert="${REGRESS_ASSERT:-1}"
out="${REGRESS_OUT:-build/regress}"
parts="${REGRESS_PARTS:-model rtl local cocotb sweep float}"
local_n="${REGRESS_LOCAL_N:-1000000}"
local_configs="${REGRESS_LOCAL_CONFIGS:-8x11x32c1 8x11x32c2 12x15x32c2 4x7x6c1}"
float_n="${REGRESS_FLOAT_N:-10000000}"
float_units="${REGRESS_FLOAT_UNITS:-float float_cons smits}"
mkdir -p "$out"
summary="$out/summary.txt"
: > "$summary"
fail=0

say() { echo "regress: $*" | tee -a "$summary"; }
elapsed() { echo "$(($(date +%s) - $1)) s"; }

for tool in model_tests pluecker; do
  [[ -x "$model_build/$tool" ]] || { echo "regress: $model_build/$tool missing (run 'make build')" >&2; exit 2; }
done

# --- 1. model ------------------------------------------------------------------
if [[ " $parts " == *" model "* ]]; then
  t0=$(date +%s)
  if PLUECKER_LONG=1 "$model_build/model_tests" --gtest_filter='Extremes.*:MarginBound.*:Setup.*' > "$out/model.log" 2>&1; then
    say "model: long extremes, margin and set-up suites PASS ($(elapsed "$t0"); log $out/model.log)"
  else
    say "model: long extremes, margin and set-up suites FAIL ($(elapsed "$t0"); log $out/model.log)"
    grep -E "FAILED|Failure" "$out/model.log" | head -10 | tee -a "$summary" || true
    fail=1
  fi
  grep -E "total over|min slack of a real hit|exhaustive .*queries|lattice 6/6 \] [0-9]|setup (total|bites|traversal)" "$out/model.log" \
    | sed 's/^/regress:   /' | tee -a "$summary" || true
fi

# --- 2. RTL ------------------------------------------------------------------------
if [[ " $parts " == *" rtl "* ]]; then
  queries="$out/extreme_${n}.txt"
  exact="$out/extreme_${n}.exact"
  for w in $widths; do
    mode=conservative
    [[ "$w" == *n ]] && mode=nearest
    cd_="${w%n}"
    c="${cd_%x*}"
    d="${cd_#*x}"
    dir="$sim_root/${c}x${d}$([[ $mode == nearest ]] && echo _nearest || true)"
    t0=$(date +%s)
    if ! COORD_BITS="$c" DIR_BITS="$d" MODE="$mode" MODEL_BUILD="$model_build" SIM_OUT="$dir" SIM_JOBS="$jobs" \
      SIM_ASSERT="$sim_assert" sim/build.sh > "$out/build_$w.log" 2>&1; then
      say "rtl $w: harness build FAIL (log $out/build_$w.log)"
      fail=1
      continue
    fi
    sim="$dir/pluecker_sim"
    if [[ ! -s "$queries" ]]; then
      "$sim" gen --n "$n" --kind extreme --seed 20261 --out "$queries"
      "$model_build/pluecker" query --test exact "$queries" > "$exact"
    fi
    # The set-up queries depend on COORD_BITS (boxes inside its range).
    setup_q="$out/setup_${c}_${n}.txt"
    setup_exact="$out/setup_${c}_${n}.exact"
    if [[ ! -s "$setup_q" ]]; then
      "$sim" gen --n "$n" --kind setup --seed 20262 --out "$setup_q"
      "$model_build/pluecker" query --test exact "$setup_q" > "$setup_exact"
    fi
    # Operands for this build's widths and mode (the file's header says them).
    for kind in boundary ports; do
      "$sim" gen --n "$n" --kind "$kind" --seed 20263 --out "$out/${kind}_${w}_${n}.txt"
    done
    for kind in extreme setup boundary ports; do
      case $kind in
        extreme) qf="$queries" ef="$exact" ;;
        setup) qf="$setup_q" ef="$setup_exact" ;;
        *) qf="$out/${kind}_${w}_${n}.txt" ef="" ;;
      esac
      tag="${w}_$kind"
      rc=0
      "$sim" query --check "$qf" > "$out/rtl_$tag.answers" 2> "$out/rtl_$tag.log" || rc=$?
      check="$(grep -E '^check' "$out/rtl_$tag.log" | tail -1)"
      if [[ $rc -ne 0 ]]; then
        say "rtl $w ($mode, $kind): FAIL, $check ($(elapsed "$t0"))"
        head -5 "$out/rtl_$tag.log" | tee -a "$summary"
        fail=1
        continue
      fi
      if [[ $mode == conservative && -n "$ef" ]]; then
        # Columns: exact answer, RTL answer. A false miss is 1 0.
        read -r fm fh hits <<< "$(paste -d' ' "$ef" "$out/rtl_$tag.answers" \
          | awk '$1==1 && $2==0 {m++} $1==0 && $2==1 {h++} $1==1 {r++} END {print m+0, h+0, r+0}')"
        say "rtl $w ($mode, $kind): $check; against exact: $hits real hits, $fm false misses, $fh false hits ($(elapsed "$t0"))"
        [[ "$fm" == 0 ]] || fail=1
      else
        say "rtl $w ($mode, $kind): $check ($(elapsed "$t0"))"
      fi
    done
  done
fi

# --- 2b. the local unit ---------------------------------------------------------------
if [[ " $parts " == *" local "* ]]; then
  total=0
  for cfg in $local_configs; do
    mode=conservative
    [[ "$cfg" == *n ]] && mode=nearest
    spec="${cfg%n}"
    ch="${spec##*c}"
    kdg="${spec%c*}"
    IFS=x read -r k d g <<< "$kdg"
    dir="$sim_root/local_k${k}_d${d}_g${g}_c${ch}$([[ $mode == nearest ]] && echo _nearest || true)"
    t0=$(date +%s)
    if ! SIM_UNIT=local BOX_BITS="$k" DIR_BITS="$d" GRID_BITS="$g" CHILDREN="$ch" MODE="$mode" \
      MODEL_BUILD="$model_build" SIM_OUT="$dir" SIM_JOBS="$jobs" SIM_ASSERT="$sim_assert" sim/build.sh \
      > "$out/build_local_$cfg.log" 2>&1; then
      say "local $cfg: harness build FAIL (log $out/build_local_$cfg.log)"
      fail=1
      continue
    fi
    sim="$dir/pluecker_sim_local"
    for kind in extreme setup boundary random; do
      count=$local_n
      [[ $kind == extreme ]] || count=$((local_n / 2))
      # The set-up queries depend on the grid's range; the others on nothing.
      qf="$out/local_${kind}_$([[ $kind == setup ]] && echo "g${g}_" || true)${count}.txt"
      ef="${qf%.txt}.exact"
      if [[ ! -s "$qf" ]]; then
        "$sim" gen --n "$count" --kind "$kind" --seed 20263 --out "$qf"
        "$model_build/pluecker" query --test exact "$qf" > "$ef"
      fi
      tag="local_${cfg}_$kind"
      rc=0
      "$sim" query --check "$qf" > "$out/$tag.answers" 2> "$out/$tag.log" || rc=$?
      check="$(grep -E '^check' "$out/$tag.log" | tail -1)"
      if [[ $rc -ne 0 ]]; then
        say "local $cfg ($mode, $kind): FAIL, $check ($(elapsed "$t0"))"
        head -5 "$out/$tag.log" | tee -a "$summary"
        fail=1
        continue
      fi
      total=$((total + count))
      if [[ $mode == conservative ]]; then
        read -r fm fh hits <<< "$(paste -d' ' "$ef" "$out/$tag.answers" \
          | awk '$1==1 && $2==0 {m++} $1==0 && $2==1 {h++} $1==1 {r++} END {print m+0, h+0, r+0}')"
        say "local $cfg ($mode, $kind): $check; against exact: $hits real hits, $fm false misses, $fh false hits ($(elapsed "$t0"))"
        [[ "$fm" == 0 ]] || fail=1
      else
        say "local $cfg ($mode, $kind): $check ($(elapsed "$t0"))"
      fi
    done
  done
  say "local: $total queries through the local unit's RTL"
fi

# --- 3. cocotb stress ----------------------------------------------------------------
if [[ " $parts " == *" cocotb "* ]]; then
  t0=$(date +%s)
  scale=$(((25 * n + 500000) / 1000000))
  ((scale >= 1)) || scale=1
  say "cocotb: stress scale $scale (x the make-test sizes)"
  if PLUECKER_LONG=1 PLUECKER_STRESS_SCALE="$scale" PLUECKER_PY_DIR="$model_build" python -m pytest -n "$jobs" -q \
    tb/pluecker_intersector/test_stress.py > "$out/cocotb.log" 2>&1; then
    say "cocotb: long stress PASS ($(elapsed "$t0"); log $out/cocotb.log)"
  else
    say "cocotb: long stress FAIL ($(elapsed "$t0"); log $out/cocotb.log)"
    tail -5 "$out/cocotb.log" | tee -a "$summary"
    fail=1
  fi
fi

# --- 4. cocotb sweeps ------------------------------------------------------------------
if [[ " $parts " == *" sweep "* ]]; then
  t0=$(date +%s)
  if PLUECKER_LONG=1 PLUECKER_PY_DIR="$model_build" python -m pytest -n "$jobs" -q \
    tb/pluecker_intersector/test_pluecker_intersector.py tb/pluecker_local_intersector tb/pluecker_local_frame \
    tb/pluecker_local_child tb/pluecker_mul tb/pluecker_mul_lut tb/mult18x18d \
    tb/pluecker_float_intersector tb/pluecker_smits_intersector tb/pluecker_f32_add tb/pluecker_f32_mul \
    > "$out/sweep.log" 2>&1; then
    say "sweep: long cocotb sweeps PASS ($(elapsed "$t0"); log $out/sweep.log)"
  else
    say "sweep: long cocotb sweeps FAIL ($(elapsed "$t0"); log $out/sweep.log)"
    tail -5 "$out/sweep.log" | tee -a "$summary"
    fail=1
  fi
fi

# --- 5. binary32 units ----------------------------------------------------------------
if [[ " $parts " == *" float "* ]]; then
  t0=$(date +%s)
  if PLUECKER_LONG=1 "$model_build/model_tests" --gtest_filter='F32Unit.*' > "$out/float_model.log" 2>&1; then
    say "float: long model suite PASS ($(elapsed "$t0"); log $out/float_model.log)"
  else
    say "float: long model suite FAIL ($(elapsed "$t0"); log $out/float_model.log)"
    fail=1
  fi
  grep -E "^\[ f32 (extreme|random|conservative) *\]" "$out/float_model.log" | sed 's/^/regress:   /' | tee -a "$summary" || true
  for u in $float_units; do
    unit="${u%_cons}"
    mode=nearest
    [[ "$u" == *_cons ]] && mode=conservative
    dir="$sim_root/$u"
    t0=$(date +%s)
    if ! SIM_UNIT="$unit" MODE="$mode" MODEL_BUILD="$model_build" SIM_OUT="$dir" SIM_JOBS="$jobs" \
      SIM_ASSERT="$sim_assert" sim/build.sh > "$out/build_$u.log" 2>&1; then
      say "float $u: harness build FAIL (log $out/build_$u.log)"
      fail=1
      continue
    fi
    # 40 % extreme, 20 % random (both against exact too), 30 % raw, 10 % tiny.
    for part in "extreme 40 --exact" "random 20 --exact" "raw 30" "tiny 10"; do
      read -r kind pct flag <<< "$part"
      k=$((float_n * pct / 100))
      rc=0
      line="$("$dir/pluecker_sim" check --n "$k" --kind "$kind" --seed 20263 ${flag:-} 2> "$out/float_${u}_$kind.log")" || rc=$?
      if [[ $rc -ne 0 ]]; then
        say "float $u $kind: FAIL ($line)"
        head -5 "$out/float_${u}_$kind.log" | tee -a "$summary"
        fail=1
        continue
      fi
      say "float $u: $line"
      if [[ $mode == conservative && -n "${flag:-}" ]]; then
        fm="$(sed -n 's/.* \([0-9]*\) false misses.*/\1/p' <<< "$line")"
        [[ "$fm" == 0 ]] || { say "float $u $kind: $fm false misses (conservative)"; fail=1; }
      fi
    done
    say "float $u: done ($(elapsed "$t0"))"
  done
fi

if [[ $fail == 0 ]]; then say "all PASS (summary $summary)"; else say "FAILED (summary $summary)"; fi
exit $fail
