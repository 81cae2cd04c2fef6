# SPDX-License-Identifier: MIT
"""cocotb throughput of the intersector, for comparison with the Verilator
harness (`make bench`).

Builds rtl/pluecker_intersector.sv at the given widths with Verilator through
cocotb's runner (build/tb/bench_c<C>_d<D>_cons) and runs only the `throughput`
test of tb/pluecker_intersector/test_pluecker_intersector.py with
PLUECKER_BENCH_N random queries, never stalled. The figure is wall-clock
queries per second of the whole cocotb bench: driver, sink and the in-order
scoreboard against the golden model included (the stimulus is generated
before the clock starts and is not timed).

Usage: scripts/venv-exec.sh python scripts/cocotb_bench.py [--n 20000]
       [--coord-bits 16] [--dir-bits 16] [--json FILE]
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
TB = REPO / "tb" / "pluecker_intersector"
RTL = REPO / "rtl"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=20000, help="queries (default 20000)")
    ap.add_argument("--coord-bits", type=int, default=16)
    ap.add_argument("--dir-bits", type=int, default=16)
    ap.add_argument("--py-dir", default=str(REPO / "build" / "model"),
                    help="build directory holding the pluecker_py module")
    ap.add_argument("--json", help="write the figures here")
    a = ap.parse_args()
    if a.n < 1000:
        ap.error(f"--n {a.n}: use at least 1000 queries for a meaningful rate")
    py_dir = Path(a.py_dir).resolve()
    if not any(py_dir.glob("pluecker_py*.so")):
        print(f"cocotb_bench: no pluecker_py module in {py_dir} (run `make build`)", file=sys.stderr)
        return 2
    for d in (str(py_dir), str(TB), str(REPO / "tb")):  # the bench and the pluecker_tb package
        if d not in sys.path:
            sys.path.insert(0, d)  # the runner hands sys.path to the simulator
    from cocotb_tools.runner import VerilatorControlFile, get_results, get_runner

    build_dir = REPO / "build" / "tb" / f"bench_c{a.coord_bits}_d{a.dir_bits}_cons"
    out_json = Path(a.json).resolve() if a.json else build_dir / "cocotb_bench.json"
    runner = get_runner("verilator")
    print(f"cocotb_bench: building {a.coord_bits}/{a.dir_bits} in {build_dir}", flush=True)
    runner.build(
        sources=[VerilatorControlFile(RTL / "lint.vlt"), *sorted(RTL.glob("*.sv"))],
        hdl_toplevel="pluecker_intersector",
        parameters={"COORD_BITS": a.coord_bits, "DIR_BITS": a.dir_bits, "TAG_BITS": 16, "CONSERVATIVE": 1},
        build_dir=build_dir,
        log_file=build_dir / "build.log",
    )
    if out_json.exists():
        out_json.unlink()
    print(f"cocotb_bench: {a.n} queries through the cocotb bench", flush=True)
    results = runner.test(
        hdl_toplevel="pluecker_intersector",
        test_module="test_pluecker_intersector",
        testcase="throughput",
        build_dir=build_dir,
        test_dir=build_dir,
        extra_env={"PLUECKER_TB_WORK": str(build_dir), "PLUECKER_BENCH_N": str(a.n),
                   "PLUECKER_BENCH_JSON": str(out_json), "PLUECKER_PY_DIR": str(py_dir)},
        log_file=build_dir / "test.log",
    )
    _, failed = get_results(results)
    if failed:
        print(f"cocotb_bench: the throughput test failed; see {build_dir / 'test.log'}", file=sys.stderr)
        return 1
    if not out_json.exists():
        print(f"cocotb_bench: the throughput test wrote no figures; see {build_dir / 'test.log'}", file=sys.stderr)
        return 1
    r = json.loads(out_json.read_text())
    print(f"cocotb bench {a.coord_bits}/{a.dir_bits}: {r['queries']} queries in {r['seconds']:.2f} s wall = "
          f"{r['queries_per_second'] / 1e3:.1f} k queries/s (driver, sink, scoreboard; one core)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
