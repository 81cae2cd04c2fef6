#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the libFuzzer targets of model/fuzz/ with clang (ASan + UBSan, the
# library instrumented for coverage too) in build/fuzz and runs each for a
# bounded time, seeded from model/fuzz/corpus/<target>/ and model/tests/data.
#
#   scripts/fuzz.sh [TARGET...]     default: every model/fuzz/fuzz_*.cpp
#   FUZZ_SECONDS=60                 run time per target
#   FUZZ_JOBS=2                     build parallelism
#   FUZZ_BUILD=build/fuzz           build directory
#   FUZZ_FLAGS=...                  extra libFuzzer flags
#
# The growing corpus is kept in $FUZZ_BUILD/corpus/<target> (never written
# into the repository); crashes, leaks, timeouts and out-of-memory inputs
# land in $FUZZ_BUILD/artifacts/<target>/. Exit status 1 when any target
# produced an artifact: turn each one into a regression case under
# model/tests/data/hostile/ (see model/tests/test_hostile.cpp).
set -euo pipefail
cd "$(dirname "$0")/.."

SECONDS_PER_TARGET=${FUZZ_SECONDS:-60}
JOBS=${FUZZ_JOBS:-2}
BUILD=${FUZZ_BUILD:-build/fuzz}
EXTRA=${FUZZ_FLAGS:-}

scripts/setup.sh --extra clang libclang-rt-14-dev
command -v clang++ >/dev/null || { echo "fuzz: clang++ not found" >&2; exit 1; }

if [ $# -gt 0 ]; then
  targets=("$@")
else
  targets=()
  for f in model/fuzz/fuzz_*.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi

# The library is compiled with -fsanitize=fuzzer-no-link so that libFuzzer
# sees coverage of the loader and parser, not only of the target file.
# PLUECKER_SANITIZE adds ASan + UBSan (no recovery: UB aborts the run).
echo "fuzz: configuring $BUILD"
CC=clang CXX=clang++ cmake -S model -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPLUECKER_FUZZ=ON -DPLUECKER_SANITIZE=ON -DPLUECKER_PYTHON=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link -O1 -g" > "$BUILD.configure.log" 2>&1 \
  || { cat "$BUILD.configure.log"; exit 1; }
echo "fuzz: building ${targets[*]}"
cmake --build "$BUILD" -j"$JOBS" --target "${targets[@]}" > "$BUILD.build.log" 2>&1 \
  || { tail -50 "$BUILD.build.log"; exit 1; }

# Inputs of open findings (cases with an 'open' line in cli_cases.txt) would
# stop a run at once (hang, crash): they are left out of the seeds.
open_inputs() {
  awk '/^case /{a=""} /^args /{a=$0} /^open /{print a}' model/tests/data/hostile/cli_cases.txt |
    grep -o '{hostile}/[^ ]*' | sed 's|{hostile}/||'
}
# Copies the hostile inputs of one kind (obj, ply, query), open ones excepted.
hostile_seeds() {
  local kind=$1 dir="$BUILD/seeds/$1"
  rm -rf "$dir"; mkdir -p "$dir"
  local skip; skip=$(open_inputs)
  for f in model/tests/data/hostile/"$kind"/*; do
    grep -qxF "$kind/$(basename "$f")" <<< "$skip" || cp "$f" "$dir/"
  done
  echo "$dir"
}
# Seeds per target: the committed corpus plus the matching test inputs.
seeds_for() {
  local t=$1
  echo "model/fuzz/corpus/$t"
  case $t in
    fuzz_mesh_obj) hostile_seeds obj ;;
    fuzz_mesh_ply) hostile_seeds ply ;;
    fuzz_query)    echo "model/tests/data/query"; hostile_seeds query ;;
  esac
}
dict_for() {
  case $1 in
    fuzz_mesh_obj) echo "model/fuzz/obj.dict" ;;
    fuzz_mesh_ply) echo "model/fuzz/ply.dict" ;;
    fuzz_query)    echo "model/fuzz/query.dict" ;;
  esac
}
# Mesh inputs beyond a few KiB only slow the loader down.
maxlen_for() { case $1 in fuzz_query) echo 2048 ;; *) echo 4096 ;; esac; }

# Assimp's own leaks on failed imports are suppressed (see the file).
export LSAN_OPTIONS="suppressions=$PWD/model/fuzz/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"

status=0
summary=()
for t in "${targets[@]}"; do
  bin="$BUILD/$t"
  work="$BUILD/corpus/$t"
  art="$BUILD/artifacts/$t"
  log="$BUILD/$t.log"
  mkdir -p "$work" "$art"
  stamp="$BUILD/$t.stamp"
  touch "$stamp"
  seeds=()
  for d in $(seeds_for "$t"); do [ -d "$d" ] && seeds+=("$d"); done
  dict=()
  d=$(dict_for "$t")
  [ -n "$d" ] && [ -f "$d" ] && dict=(-dict="$d")
  echo "fuzz: $t for ${SECONDS_PER_TARGET}s (log $log)"
  set +e
  # -fork is not used: one process keeps the 2-core machine usable.
  "$bin" "$work" "${seeds[@]}" "${dict[@]}" -max_total_time="$SECONDS_PER_TARGET" \
    -max_len="$(maxlen_for "$t")" -timeout=20 -rss_limit_mb=2048 -malloc_limit_mb=1024 \
    -print_final_stats=1 -artifact_prefix="$art/" $EXTRA > "$log" 2>&1
  rc=$?
  set -e
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
  eps=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
  cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -1 || true)
  crashes=$(find "$art" -type f -newer "$stamp" | wc -l)  # this run's findings only
  line="$t: rc=$rc runs=${runs:-?} exec/s=${eps:-?} ${cov:-cov: ?} corpus=$(find "$work" -type f | wc -l) artifacts=$crashes"
  summary+=("$line")
  # Edge coverage of the model's sources (core/src, rt/src) reached by the corpus (libFuzzer's
  # pc table: edges include sanitizer and exception paths, so 100% is not
  # reachable). One line per file with any edge.
  if [ "${FUZZ_COVERAGE:-1}" = 1 ] && [ "$rc" -eq 0 ]; then
    "$bin" "$work" -runs=0 -print_coverage=1 -timeout=60 2>&1 >/dev/null |
      awk '/^(UN)?COVERED_FUNC:/ { split($5, e, "/"); f = $NF; sub(/:[0-9]+$/, "", f);
             if (f !~ /\/model\/(core|rt)\/src\//) next; sub(/.*\/model\//, "", f);
             cov[f] += e[1]; tot[f] += e[2] }
           END { for (f in cov) if (cov[f] > 0) printf "%s %d/%d edges (%.0f%%)\n", f, cov[f], tot[f], 100 * cov[f] / tot[f] }' |
      sort > "$BUILD/$t.coverage"
    summary+=("  coverage of the model's sources: $(paste -sd ';' "$BUILD/$t.coverage" | sed 's/;/; /g')")
  fi
  if [ "$rc" -ne 0 ] || [ "$crashes" -gt 0 ]; then
    status=1
    grep -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error|.*terminate called|.*Test unit written)' "$log" | head -20 || true
  fi
done

echo "fuzz: summary"
printf '  %s\n' "${summary[@]}"
[ "$status" -eq 0 ] || echo "fuzz: findings in $BUILD/artifacts/ (make each one a case in model/tests/data/hostile/)"
exit $status
