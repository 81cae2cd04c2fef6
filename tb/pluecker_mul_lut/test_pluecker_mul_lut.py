# SPDX-License-Identifier: MIT
"""rtl/pluecker_mul_lut.sv, the fabric multiplier: exhaustive over every
operand pair at small widths (tb_pluecker_mul_lut.sv is self-checking),
widths swept, one Verilator build directory per parameter set."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]


@pytest.mark.parametrize("wa,wb,pipeline", [(2, 2, 0), (3, 9, 0), (9, 3, 1), (8, 8, 0), (7, 7, 1)],
                         ids=["2x2", "3x9", "9x3-pipe", "8x8", "7x7-pipe"])
def test_pluecker_mul_lut(wa: int, wb: int, pipeline: int) -> None:
    verilator = shutil.which("verilator")
    assert verilator, "verilator not on PATH (run through scripts/venv-exec.sh or make test)"
    build = REPO / "build" / "tb" / f"pluecker_mul_lut_{wa}x{wb}_p{pipeline}"
    build.mkdir(parents=True, exist_ok=True)
    cmd = [verilator, "--binary", "-j", "2", "-CFLAGS", "-std=c++20", "-Wno-fatal", "-Wno-WIDTH",
           "--top-module", "tb_pluecker_mul_lut", f"-GWA={wa}", f"-GWB={wb}", f"-GPIPELINE={pipeline}",
           "-Mdir", str(build / "obj"), str(HERE / "tb_pluecker_mul_lut.sv"), str(REPO / "rtl" / "pluecker_mul_lut.sv")]
    built = subprocess.run(cmd, cwd=build, capture_output=True, text=True)
    assert built.returncode == 0, f"verilator failed:\n{built.stdout[-3000:]}\n{built.stderr[-3000:]}"
    run = subprocess.run([str(build / "obj" / "Vtb_pluecker_mul_lut")], cwd=build, capture_output=True,
                         text=True, timeout=600)
    out = run.stdout + run.stderr
    assert run.returncode == 0, out[-3000:]
    m = re.search(r"checked (\d+) errors (\d+)", out)
    assert m, f"the bench did not finish:\n{out[-3000:]}"
    assert int(m.group(1)) >= 1 << (wa + wb), m.group(0)
    assert int(m.group(2)) == 0, m.group(0)
