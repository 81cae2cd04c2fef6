# SPDX-License-Identifier: MIT
"""Stress bench for rtl/pluecker_intersector.sv: long random streams under
changing traffic, resets at random and chosen moments, and X checks.

Reuses the driver, sink and in-order scoreboard of the shared bench package
(pluecker_tb.intersector.IntersectorBench, with the phase traffic of
pluecker_tb.traffic.Phases) and its stimulus (pluecker_tb.vectors): every
expected answer comes from the golden model (pluecker_py); nothing here
computes a box test.

What is checked, every cycle
  - every result leaves exactly once, in input order, with its tag (tags are
    32 bits wide here, so every query of a run has its own tag), and with the
    model's answer (Bench's scoreboard)
  - nothing accepted before a reset leaves after it (Bench: the scoreboard
    forgets every query at a reset edge; a later result with no query
    outstanding, or with another tag, is an error naming the reset)
  - in_ready_o and out_valid_o are low from the second reset cycle on
    (the bench's sink)
  - a result offered and not taken stays offered, unchanged, until taken,
    unless a reset intervenes (checked here, independently of the RTL's own
    ASSERT_ON assertions, which are compiled in and live: --assert)
  - in_ready_o and out_valid_o are never X/Z, and out_tag_o / out_hit_o are
    never X/Z while out_valid_o is high (see "X checks" below)

Traffic: phases of a few hundred cycles each (full rate, bursty input,
sparse ready, random jitter, trickle input, and output stalls with
out_ready_i held low for 100..800 cycles), chosen at random. Resets: at
random moments (1..40 cycles long), and on purpose while the output is
stalled and the FIFO is full (in_ready_o low). The run asserts that each
kind of moment occurred: a reset with the FIFO full and stalled, a reset in
a cycle with an input or an output handshake offered, and a stall of at
least 100 cycles.

X checks
  Verilator (2-state): built with --x-assign unique --x-initial unique and
  run with +verilator+rand+reset+2, so every flop without a reset starts
  from a random value. The same stimulus is run twice with different
  initialisation seeds (test_stress_init_independence) and the cycle-by-cycle
  output traces (in_ready_o, out_valid_o, and tag/hit while valid) must be
  identical from the first reset on. This shows that no value a flop holds
  before it is first written reaches an output, for the two sampled
  initialisations; it cannot show it for every initial value, and a 2-state
  simulator never shows an X itself.
  Icarus (4-state, test_stress_x_icarus): the RTL is turned into a plain
  Verilog netlist by Yosys (read_verilog -sv; proc; flatten; write_verilog:
  Icarus cannot read the SystemVerilog source) and simulated with every
  unreset flop at X, the payload inputs driven to X whenever in_valid_i
  is low, and ray_end_i driven to X in queries whose ray_end_valid_i is low
  (the RTL must ignore it). The monitor then checks directly that no X
  reaches in_ready_o, out_valid_o, or out_tag_o/out_hit_o while out_valid_o
  is high. Yosys' muxes become ?: expressions, which Icarus evaluates
  X-pessimistically, so a pass is meaningful; what it cannot show: X
  behaviour of the original SystemVerilog under another simulator's
  semantics (the netlist is Yosys' reading of it).

Sizes: the pytest run (make test) uses two configurations, 9/7 (LATENCY 6)
with about 2x10^4 queries and 7/22 (LATENCY 7) with a quarter of that;
PLUECKER_LONG=1 runs five (6/6, 24/24 and 20/8 conservative, 16/16 and 7/22
nearest: LATENCY 6, 7 and 8) with 25x as many queries and the X checks at
each. PLUECKER_STRESS_SCALE=K sets the factor (1 = the short sizes).

Environment: as test_pluecker_intersector (PLUECKER_LONG, PLUECKER_SEED,
PLUECKER_PY_DIR, PLUECKER_TB_BUILD, PLUECKER_RTL_DIR), plus
PLUECKER_STRESS_TRACE (set by the pytest side: file for the output trace
digest) and PLUECKER_STRESS_QUERIES (set by the pytest side: the factor of
a configuration on the short sizes).
"""

from __future__ import annotations

import hashlib
import os
import random
from pathlib import Path

import cocotb
import pytest
from cocotb.triggers import ClockCycles, ReadOnly, RisingEdge, Timer

from pluecker_tb import clock_reset, config, traffic
from pluecker_tb.intersector import TOPLEVEL, IntersectorBench, stimulus

LONG = config.LONG
# Queries per test: SCALE x the short sizes x the configuration's factor;
# PLUECKER_STRESS_SCALE overrides SCALE (scripts/regress.py derives it from
# REGRESS_N).
SCALE = max(1, int(os.environ.get("PLUECKER_STRESS_SCALE", "") or config.SCALE))
QUERIES = float(os.environ.get("PLUECKER_STRESS_QUERIES", "1"))
TAG_BITS = 32


def _seed(*parts: object) -> int:
    return config.seed("stress", *parts)


def _n(base: int) -> int:
    return max(200, int(base * SCALE * QUERIES))


# ---------------------------------------------------------------------------
# cocotb side
# ---------------------------------------------------------------------------

class StressBench(IntersectorBench):
    """The intersector bench with phase traffic and X-driving of idle payload."""

    def __init__(self, dut, seed: int, x_idle: bool = False):
        self.phases = traffic.Phases(random.Random(seed + 3))
        super().__init__(dut, seed, traffic_gen=self.phases)
        self.x_idle = x_idle

    @property
    def mode(self) -> str:
        return self.phases.mode

    def set_mode(self, mode: str) -> None:
        self.phases.set_mode(mode)

    def _junk(self) -> None:
        if not self.x_idle:
            super()._junk()
            return
        from cocotb.types import LogicArray

        dut, c3, d3 = self.dut, 3 * self.coord_bits, 3 * self.dir_bits
        for name, width in (("in_tag_i", self.tag_bits), ("ray_class_i", 3), ("ray_org_i", c3),
                            ("ray_dir_i", d3), ("ray_end_i", c3), ("ray_end_valid_i", 1),
                            ("box_min_i", c3), ("box_max_i", c3)):
            getattr(dut, name).value = LogicArray("X" * width)

    async def start(self) -> None:
        # The monitor first, so that its X checks come before the sink's
        # int() conversions in each cycle.
        # The clock input starts from a random value under
        # +verilator+rand+reset: settle it low first, so that the clock's
        # first rising edge comes at the same time in every run. The writes
        # must be immediate: a scheduled one lands after Verilator's first
        # evaluation, which takes a random clk_i = 1 for a rising edge (its
        # edge detector starts from 0) and clocks the unreset state with a
        # random rst_i, where the RTL's ASSERT_ON checks (a_credit_balance)
        # rightly fail, since no reset has come yet. (Verilator only: under
        # Icarus the same immediate writes leave the netlist unreset at the
        # first edge, and scheduled ones work there.)
        clock_reset.settle_low(self.dut.clk_i, self.dut.rst_i)
        await Timer(1, "ns")
        self.monitor = Monitor(self)
        self.monitor_task = cocotb.start_soon(self.monitor.run())
        await super().start()


class Monitor:
    """Per-cycle protocol and X checks, coverage counters, output trace."""

    def __init__(self, bench: StressBench):
        self.bench = bench
        self.dut = bench.dut
        self.started = False  # from the cycle after the first reset edge on
        self.cycle = 0
        self.prev_offer = None  # (tag, hit) offered and not taken in the previous cycle
        self.digest = hashlib.sha256()
        self.full_cycles = 0
        self.longest_ready_low = 0
        self._ready_low = 0
        self.resets_full_stalled = 0
        self.resets_with_in_handshake = 0
        self.resets_with_out_handshake = 0
        self.reset_pulses = 0
        self._in_reset = False

    @staticmethod
    def _resolved(handle) -> bool:
        return handle.value.is_resolvable

    def _value(self, handle, what: str):
        if not self._resolved(handle):
            self.bench._error(f"cycle {self.cycle}: {what} is {handle.value} (X/Z)")
            return None
        return int(handle.value)

    async def run(self) -> None:
        dut = self.dut
        while True:
            await ReadOnly()
            rst = int(dut.rst_i.value)
            if self.started:
                self._sample(rst)
            await RisingEdge(dut.clk_i)
            self.started = self.started or bool(rst)
            self.cycle += 1

    def _sample(self, rst: int) -> None:
        dut = self.dut
        ready = self._value(dut.in_ready_o, "in_ready_o")
        valid = self._value(dut.out_valid_o, "out_valid_o")
        oready = int(dut.out_ready_i.value)
        ivalid = int(dut.in_valid_i.value)
        offer = None
        if valid:
            tag = self._value(dut.out_tag_o, "out_tag_o (out_valid_o high)")
            hit = self._value(dut.out_hit_o, "out_hit_o (out_valid_o high)")
            offer = (tag, hit)
        # A result offered and not taken stays, unchanged (no reset between).
        if self.prev_offer is not None and not rst:
            if not valid:
                self.bench._error(f"cycle {self.cycle}: out_valid_o dropped while result {self.prev_offer} "
                                  "was not taken")
            elif offer != self.prev_offer:
                self.bench._error(f"cycle {self.cycle}: result changed from {self.prev_offer} to {offer} "
                                  "while stalled")
        self.prev_offer = offer if (valid and not oready and not rst) else None
        # Coverage.
        if rst and not self._in_reset:
            self.reset_pulses += 1
            if valid and not ready and not oready:
                self.resets_full_stalled += 1
            if ivalid and ready:
                self.resets_with_in_handshake += 1
            if valid and oready:
                self.resets_with_out_handshake += 1
        self._in_reset = bool(rst)
        if not rst and valid and not ready:
            self.full_cycles += 1
        self._ready_low = 0 if oready else self._ready_low + 1
        self.longest_ready_low = max(self.longest_ready_low, self._ready_low)
        self.digest.update(f"{self.cycle}:{rst}{ready}{valid}:{offer}\n".encode())


async def _phases(bench: StressBench) -> None:
    rng = random.Random(bench.seed + 7)
    while True:
        if bench.mode != "stall":  # a stall ends by itself
            bench.set_mode(rng.choice(traffic.Phases.MODES))
        await ClockCycles(bench.dut.clk_i, rng.randint(50, 600))


async def _resets(bench: StressBench, mon: Monitor, mean_gap: int) -> None:
    """Reset pulses at random moments, and every third one on purpose while
    the FIFO is full and the output stalled."""
    dut = bench.dut
    rng = random.Random(bench.seed + 11)
    k = 0
    while True:
        await ClockCycles(dut.clk_i, max(1, int(rng.expovariate(1.0 / mean_gap))))
        k += 1
        if k % 3 == 0:
            bench.set_mode("stall")
            for _ in range(3000):  # until in_ready_o is low with a result waiting
                await RisingEdge(dut.clk_i)
                await ReadOnly()
                if int(dut.out_valid_o.value) and not int(dut.in_ready_o.value) and not int(dut.out_ready_i.value):
                    break
            await RisingEdge(dut.clk_i)
        dut.rst_i.value = 1
        await ClockCycles(dut.clk_i, rng.choice([1, 1, 1, 2, 3, 5, 17, rng.randint(1, 40)]))
        dut.rst_i.value = 0


def _vectors(bench: StressBench, n: int, salt: object) -> list:
    """n vectors from the random, extreme, raw and boundary sources, interleaved."""
    sources = ["random", "extreme", "raw", "boundary"]
    parts = [stimulus(bench, s, n // len(sources) + 1, ("stress", salt)) for s in sources]
    out = []
    for group in zip(*parts):
        out.extend(group)
    return out[:n]


def _x_end(bench: StressBench, v):
    """ray_end_i as X when ray_end_valid_i is low (the RTL ignores it then)."""
    if v.ports.get("ray_end_valid_i", 1):
        return v
    from cocotb.types import LogicArray

    ports = dict(v.ports, ray_end_i=LogicArray("X" * (3 * bench.coord_bits)))
    return type(v)(ports, v.hit, v.describe)


async def _run_stress(dut, n: int, mean_reset_gap: int, x_idle: bool, salt: object) -> None:
    # A configuration with fewer queries (QUERIES < 1) gets its resets
    # closer together, so that it sees as many kinds of reset moment.
    mean_reset_gap = max(50, int(mean_reset_gap * min(1.0, QUERIES)))
    bench = StressBench(dut, _seed(salt), x_idle=x_idle)
    assert bench.tag_bits >= 24, f"TAG_BITS={bench.tag_bits}: the stress build needs wide tags"
    await bench.start()
    mon, mon_task = bench.monitor, bench.monitor_task
    vectors = _vectors(bench, n, salt)
    if x_idle:
        vectors = [_x_end(bench, v) for v in vectors]
    phases = cocotb.start_soon(_phases(bench))
    resets = cocotb.start_soon(_resets(bench, mon, mean_reset_gap))
    await bench.drive(vectors)
    resets.cancel()
    phases.cancel()
    dut.rst_i.value = 0
    bench.set_mode("full")
    await bench.drain(limit=20000)
    mon_task.cancel()

    dut._log.info(
        "stress: %d vectors, %d accepted, %d compared, %d dropped by %d reset pulses (%d with the FIFO full and "
        "the output stalled, %d with an input and %d with an output handshake offered); %d cycles with the FIFO "
        "full, longest out_ready_i low %d cycles", len(vectors), bench.accepted, bench.compared, bench.dropped,
        mon.reset_pulses, mon.resets_full_stalled, mon.resets_with_in_handshake, mon.resets_with_out_handshake,
        mon.full_cycles, mon.longest_ready_low)
    assert bench.compared + bench.dropped == bench.accepted == len(vectors), (
        f"accepted {bench.accepted}, compared {bench.compared}, dropped {bench.dropped} of {len(vectors)}")
    assert mon.reset_pulses >= 5, f"only {mon.reset_pulses} resets"
    assert mon.resets_full_stalled >= 1, "no reset hit a full, stalled FIFO"
    assert mon.resets_with_in_handshake + mon.resets_with_out_handshake >= 1, "no reset hit a handshake"
    assert mon.longest_ready_low >= 100, f"longest stall only {mon.longest_ready_low} cycles"
    assert bench.dropped > 0, "no reset dropped a query in flight"
    trace = os.environ.get("PLUECKER_STRESS_TRACE")
    if trace:
        Path(trace).write_text(mon.digest.hexdigest() + "\n")
    bench.finish("stress")


@cocotb.test()
async def stress(dut) -> None:
    """Long random stream: traffic phases, long stalls, resets anywhere."""
    await _run_stress(dut, _n(20000), 700, x_idle=False, salt="stress")


@cocotb.test()
async def init_independence(dut) -> None:
    """A shorter stream whose output trace is compared across random
    initialisations by the pytest side."""
    await _run_stress(dut, _n(4000), 400, x_idle=False, salt="init")


@cocotb.test()
async def x_idle_payload(dut) -> None:
    """Payload inputs X while in_valid_i is low (meaningful on a 4-state
    simulator): no X may reach the outputs."""
    await _run_stress(dut, _n(3000), 400, x_idle=True, salt="xidle")


# ---------------------------------------------------------------------------
# pytest side
# ---------------------------------------------------------------------------

# (COORD_BITS, DIR_BITS, CONSERVATIVE, queries factor)
CONFIGS = ([(9, 7, 1, 1.0), (7, 22, 1, 0.25)] if not LONG else
           [(6, 6, 1, 1.0), (24, 24, 1, 1.0), (16, 16, 0, 1.0), (20, 8, 1, 1.0), (7, 22, 0, 1.0)])
IDS = [f"stress_c{c}_d{d}_{'cons' if cons else 'near'}" for c, d, cons, _ in CONFIGS]


def _params(c: int, d: int, cons: int) -> dict:
    return {"COORD_BITS": c, "DIR_BITS": d, "TAG_BITS": TAG_BITS, "CONSERVATIVE": cons}


def _name(c: int, d: int, cons: int) -> str:
    return f"stress_c{c}_d{d}_{'cons' if cons else 'near'}"


def _verilator_build(c: int, d: int, cons: int):
    """The Verilator build (two tests share it; Build locks its folder)."""
    from pluecker_tb.runner import VERILATOR_RTL_ARGS, Build, need_model, rtl_sources

    need_model()
    return Build(_name(c, d, cons)).build(sources=rtl_sources(), hdl_toplevel=TOPLEVEL, parameters=_params(c, d, cons),
                                          defines={"ASSERT_ON": 1}, build_args=VERILATOR_RTL_ARGS)


def _verilator_run(build, testcase: str, init_seed: int, queries: float, trace: Path | None = None) -> None:
    """Runs one cocotb test; init_seed seeds the random initial values."""
    from pluecker_tb.runner import verilator_plusargs

    env = {"PLUECKER_STRESS_QUERIES": str(queries)}
    if trace:
        env["PLUECKER_STRESS_TRACE"] = str(trace)
    build.test("test_stress", testcase=testcase, plusargs=verilator_plusargs(init_seed), extra_env=env,
               results_name=f"{testcase}_{init_seed % 1000000 + 1}")


def _icarus_wrapper(c: int, d: int, cons: int) -> str:
    """The netlist under the DUT's name and parameters (read back by the bench)."""
    ports = [("input", "clk_i", 1), ("input", "rst_i", 1), ("input", "in_valid_i", 1), ("output", "in_ready_o", 1),
             ("input", "in_tag_i", TAG_BITS), ("input", "ray_class_i", 3), ("input", "ray_org_i", 3 * c),
             ("input", "ray_dir_i", 3 * d), ("input", "ray_end_i", 3 * c), ("input", "ray_end_valid_i", 1),
             ("input", "box_min_i", 3 * c), ("input", "box_max_i", 3 * c), ("output", "out_valid_o", 1),
             ("input", "out_ready_i", 1), ("output", "out_tag_o", TAG_BITS), ("output", "out_hit_o", 1)]
    decl = ",\n".join(f"  {io} wire [{w - 1}:0] {n}" for io, n, w in ports)
    conn = ", ".join(f".{n}({n})" for _, n, _ in ports)
    params = ", ".join(f"parameter {k} = {v}" for k, v in _params(c, d, cons).items())
    return (f"// generated by tb/pluecker_intersector/test_stress.py\n"
            f"module {TOPLEVEL} #({params}) (\n{decl}\n);\n  pluecker_netlist u ({conn});\nendmodule\n")


@pytest.mark.parametrize("c,d,cons,queries", CONFIGS, ids=IDS)
def test_stress(c: int, d: int, cons: int, queries: float) -> None:
    _verilator_run(_verilator_build(c, d, cons), "stress", _seed("init", c, d, cons), queries)


@pytest.mark.parametrize("c,d,cons,queries", CONFIGS, ids=IDS)
def test_stress_init_independence(c: int, d: int, cons: int, queries: float) -> None:
    """The same stream under two random initialisations of every unreset
    flop gives the same output trace, cycle for cycle."""
    build = _verilator_build(c, d, cons)
    digests = []
    for k in (1, 2):
        trace = build.dir / f"init_trace_{k}.txt"
        trace.unlink(missing_ok=True)
        _verilator_run(build, "init_independence", _seed("init", k, c, d, cons), queries, trace)
        digests.append(trace.read_text().strip())
    assert digests[0] == digests[1], "the output trace depends on the initial values of unreset flops"


@pytest.mark.parametrize("c,d,cons,queries", CONFIGS, ids=IDS)
def test_stress_x_icarus(c: int, d: int, cons: int, queries: float) -> None:
    """4-state run of Yosys' netlist of the RTL under Icarus."""
    import shutil

    from pluecker_tb import ecp5
    from pluecker_tb.runner import Build, need_model, need_tool, rtl_files

    need_model()
    need_tool("iverilog", "the 4-state X check runs under Icarus")
    build = Build(_name(c, d, cons) + "_icarus", simulator="icarus")
    # YoWASP Yosys runs sandboxed: copy the sources next to the netlist
    # and use relative paths.
    srcs = rtl_files()
    for src in srcs:
        shutil.copy(src, build.dir / src.name)
    chparams = " ".join(f"-set {k} {v}" for k, v in _params(c, d, cons).items())
    try:
        ecp5.run_yosys(f"read_verilog -sv {' '.join(s.name for s in srcs)}; chparam {chparams} {TOPLEVEL}; "
                       f"hierarchy -check -top {TOPLEVEL}; proc; flatten; opt_clean; "
                       f"rename {TOPLEVEL} pluecker_netlist; write_verilog -noattr netlist.v", build.dir)
    except ecp5.MissingTool as e:
        pytest.fail(str(e))
    assert (build.dir / "netlist.v").exists()
    (build.dir / "wrapper.v").write_text(_icarus_wrapper(c, d, cons))
    build.build(sources=[build.dir / "netlist.v", build.dir / "wrapper.v"], hdl_toplevel=TOPLEVEL,
                timescale=("1ns", "1ps"))
    build.test("test_stress", testcase="x_idle_payload", extra_env={"PLUECKER_STRESS_QUERIES": str(queries)})
