# SPDX-License-Identifier: MIT
"""The FuseSoC cores (rtl/*.core, fpga/ooc_wrapper.core) as another project
uses them: `fusesoc` from the venv, the repository's core folders as its
libraries, nothing else set up.

  - the core list holds every core of the project;
  - `fusesoc run --target lint` (Verilator -Wall through Edalize) passes
    for the intersector at the defaults and at 6/6 and for the AXI4-Stream
    wrapper at the defaults and at COORD_BITS = 24, for a mixed array
    (two DSP lanes, one fabric lane), the ternary unit and a cascade of
    three 8/8 lanes, and fails, naming the parameter, at
    COORD_BITS = 5;
  - `fusesoc run --target sim` of the intersector (cocotb on Verilator
    through Edalize) runs the bench's throughput test at 6/6 against the
    golden model and passes.
"""
from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MODEL_BUILD = Path(os.environ.get("PLUECKER_PY_DIR") or ROOT / "build" / "model")
CORES = ["pluecker:fpga:ooc_wrapper:1.0.0", "pluecker:ip:array:1.0.0", "pluecker:ip:axis:1.0.0",
         "pluecker:ip:cascade:1.0.0", "pluecker:ip:common:1.0.0", "pluecker:ip:intersector:1.0.0"]


def fusesoc(args: list[str], build_root: Path, env: dict | None = None, timeout: int = 1800):
    cmd = [sys.executable, "-m", "fusesoc.main", "--cores-root", str(ROOT / "rtl"), "--cores-root",
           str(ROOT / "fpga"), *args]
    if args[0] == "run":
        cmd[cmd.index("run") + 1:cmd.index("run") + 1] = ["--build-root", str(build_root)]
    return subprocess.run(cmd, cwd=build_root.parent, env=env or os.environ.copy(), capture_output=True, text=True,
                          timeout=timeout)


def test_core_list(tmp_path):
    r = fusesoc(["core", "list"], tmp_path / "b")
    assert r.returncode == 0, r.stdout + r.stderr
    for core in CORES:
        assert core in r.stdout, r.stdout


def _core_files(core: Path) -> tuple[str, list[str], list[str]]:
    """A core file's name, its RTL files and the cores it depends on (by name)."""
    text = core.read_text()
    name = re.search(r"^name: (\S+):[\d.]+$", text, re.M).group(1)
    files = re.findall(r"^\s+- (\S+\.sv)$", text, re.M)
    deps = [d.rsplit(":", 1)[0] for d in re.findall(r'^\s+- ">=(\S+)"$', text, re.M)]
    return name, files, deps


def test_cores_hold_every_module_they_instantiate():
    """Every pluecker_* module that a core's RTL instantiates (in any
    generate branch, at any depth) is in that core or a core it depends on:
    a user's FuseSoC build finds every module at every parameter value."""
    cores = {n: (f, d) for n, f, d in map(_core_files, (ROOT / "rtl").glob("*.core"))}

    def closure(name: str) -> set[str]:
        files, deps = cores[name]
        return set(files).union(*(closure(d) for d in deps if d in cores))

    inst = re.compile(r"^\s*(pluecker_\w+)\s*(?:#\s*\(|\w+\s*\()", re.M)
    for name in cores:
        have = closure(name)
        todo, seen = [f for f in have if not f.endswith("_pkg.sv")], set()
        while todo:
            f = todo.pop()
            if f in seen:
                continue
            seen.add(f)
            for mod in inst.findall((ROOT / "rtl" / f).read_text()):
                assert f"{mod}.sv" in have, f"{name}: {f} instantiates {mod}, whose file the core lacks"
                todo.append(f"{mod}.sv")


def test_lint_targets(tmp_path):
    for core, params in [("pluecker:ip:intersector", []), ("pluecker:ip:intersector", ["--COORD_BITS=6",
                          "--DIR_BITS=6"]), ("pluecker:ip:axis", []), ("pluecker:ip:axis", ["--COORD_BITS=24"]),
                         ("pluecker:ip:intersector", ["--COORD_BITS=6", "--DIR_BITS=6", "--PIPELINE=2",
                                                      "--MUL_STYLE=dsp"]),  # two products a block
                         ("pluecker:ip:array", ["--N_DSP=2", "--N_LUT=1"]),
                         ("pluecker:ip:array", ["--N_DSP=1", "--N_LUT=1", "--N_ROM=1", "--COORD_BITS=6",
                                                "--DIR_BITS=6", "--PIPELINE=2"]),  # block-RAM tables
                         ("pluecker:ip:intersector", ["--TERNARY=1"]),
                         ("pluecker:ip:cascade", ["--N_NARROW=3", "--NARROW_COORD_BITS=8", "--NARROW_DIR_BITS=8"])]:
        r = fusesoc(["run", "--target", "lint", core, *params], tmp_path / "lint")
        assert r.returncode == 0, f"{core} {params}:\n{r.stdout}\n{r.stderr}"
        assert "verilator -f" in r.stdout + r.stderr, r.stdout + r.stderr
    r = fusesoc(["run", "--target", "lint", "pluecker:ip:intersector", "--COORD_BITS=5"], tmp_path / "bad")
    assert r.returncode != 0
    assert "parameter COORD_BITS is outside" in r.stdout + r.stderr, r.stdout + r.stderr


def test_sim_target(tmp_path):
    assert (MODEL_BUILD / "pluecker_py.cpython-311-x86_64-linux-gnu.so").exists() or any(
        MODEL_BUILD.glob("pluecker_py*.so")), f"pluecker_py not built in {MODEL_BUILD} (make build)"
    env = os.environ.copy()
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT / "tb"), str(ROOT / "tb" / "pluecker_intersector"),
                                         str(MODEL_BUILD), env.get("PYTHONPATH", "")])
    env["PLUECKER_PY_DIR"] = str(MODEL_BUILD)
    env["COCOTB_TEST_FILTER"] = "throughput"
    env["COCOTB_TOPLEVEL"] = "pluecker_intersector"
    # Edalize 0.6.8 sets cocotb 1.x's variables only; cocotb 2 loads its
    # Python through GPI_USERS.
    config = [sys.executable, "-m", "cocotb_tools.config"]
    env["GPI_USERS"] = ";".join(subprocess.run(config + [flag], capture_output=True, text=True, check=True).stdout.strip()
                                for flag in ("--libpython", "--pygpi-entry-point"))
    r = fusesoc(["run", "--target", "sim", "pluecker:ip:intersector", "--COORD_BITS=6", "--DIR_BITS=6"],
                tmp_path / "sim", env)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out[-6000:]
    assert "test_pluecker_intersector.throughput" in out and "PASS=1" in out and "FAIL=0" in out, out[-6000:]
