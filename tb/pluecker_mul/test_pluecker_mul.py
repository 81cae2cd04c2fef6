# SPDX-License-Identifier: MIT
"""rtl/pluecker_mul.sv: every product equals a plain signed multiply, after
exactly the latency the module documents (2 + PIPELINE + ADD_STAGES edges),
on the ECP5 path (MULT18X18D blocks, wide operands split) and on the generic
path. The bench (tb_pluecker_mul.sv) is self-checking; Verilator --binary
builds it, one build directory per path."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]


@pytest.mark.parametrize("path", ["ecp5", "generic"])
def test_pluecker_mul(path: str) -> None:
    verilator = shutil.which("verilator")
    assert verilator, "verilator not on PATH (run through scripts/venv-exec.sh or make test)"
    build = REPO / "build" / "tb" / f"pluecker_mul_{path}"
    build.mkdir(parents=True, exist_ok=True)
    sources = [HERE / "tb_pluecker_mul.sv", REPO / "rtl" / "pluecker_mul.sv"]
    defines = []
    if path == "ecp5":
        sources.append(HERE / "mult18x18d_model.sv")
        defines.append("-DPLUECKER_ECP5")
    cmd = [verilator, "--binary", "-j", "2", "-CFLAGS", "-std=c++20", "-Wno-fatal", "-Wno-WIDTH", "--top-module", "tb_pluecker_mul",
           "-Mdir", str(build / "obj"), *defines, *map(str, sources)]
    built = subprocess.run(cmd, cwd=build, capture_output=True, text=True)
    assert built.returncode == 0, f"verilator failed:\n{built.stdout[-3000:]}\n{built.stderr[-3000:]}"
    run = subprocess.run([str(build / "obj" / "Vtb_pluecker_mul")], cwd=build, capture_output=True, text=True,
                         timeout=600)
    out = run.stdout + run.stderr
    assert run.returncode == 0, out[-3000:]
    assert "MISMATCH" not in out, out[-3000:]
    m = re.search(r"done: (\d+) cycles, (\d+) error cycles", out)
    assert m, f"the bench did not finish:\n{out[-3000:]}"
    assert int(m.group(1)) >= 100000 and int(m.group(2)) == 0, m.group(0)
