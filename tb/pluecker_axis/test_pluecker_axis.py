# SPDX-License-Identifier: MIT
"""cocotb bench for rtl/pluecker_axis.sv (the AXI4-Stream wrapper) against the
golden model, with cocotbext-axi's bus models.

Structure: AxiStreamSource (queries, one per beat, in packets of 1..8 beats
with one tid each) -> DUT -> AxiStreamSink (results); an AxiStreamMonitor on
the slave side sees every accepted packet and pushes the model's answers
(pluecker_py, computed when the stimulus is built) into the shared in-order
scoreboard (pluecker_tb.stream), which the sink's packets are checked
against: the hits (tdata bit 0 and tuser of each beat), the tid and the
packet boundaries (tlast). Nothing assumes the latency. Widths are read back
from the DUT, and the tdata packing is the port contract's
(pluecker_py.PortContract.axis_tdata_fields), checked against the DUT's
localparams first.

Tests
  stream      stimulus source x source pauses (idle) x sink pauses
              (backpressure) (cocotb.parametrize), the pause patterns those of
              pluecker_tb.traffic
  full_rate   one query per clock in and out without pauses, and with the
              result stream blocked exactly FIFO_DEPTH + 2 queries get in
              (the intersector's FIFO and the two skid registers), then all
              come out in order
"""

from __future__ import annotations

import collections
import random

import pytest

from pluecker_tb import config

try:
    import cocotb
    from cocotb.clock import Clock
    from cocotb.triggers import ClockCycles, RisingEdge
    from cocotbext.axi import AxiStreamFrame

    from pluecker_tb import axis
except ImportError:  # pragma: no cover - only the pytest runner part is usable
    cocotb = None

TOPLEVEL = "pluecker_axis"
CLOCK_NS = 10
_seed = config.seed


# ---------------------------------------------------------------------------
# cocotb side
# ---------------------------------------------------------------------------

class AxisBench:
    def __init__(self, dut, seed: int, idle: bool = False, backpressure: bool = False):
        import pluecker_py as pp

        from pluecker_tb import vectors as pv
        from pluecker_tb.stream import InOrderScoreboard

        self.dut = dut
        self.coord_bits, self.dir_bits = int(dut.COORD_BITS.value), int(dut.DIR_BITS.value)
        self.tag_bits = int(dut.TAG_BITS.value)
        self.conservative = bool(int(dut.CONSERVATIVE.value))
        self.fmt = pv.fixed_format(self.coord_bits, self.dir_bits, self.conservative)
        # The intersector inside carries tid and tlast in its tag.
        self.contract = pp.PortContract(self.coord_bits, self.dir_bits, self.tag_bits + 1, self.conservative)
        self.fields = self.contract.axis_tdata_fields
        self.rng = random.Random(seed)
        self.source, self.monitor, self.sink = axis.endpoints(
            lambda slave: axis.port_bus(dut, "s_axis" if slave else "m_axis", slave), dut.aclk_i, dut.aresetn_i,
            seed, idle, backpressure, reset_active_level=False)
        self.scoreboard = InOrderScoreboard(dut._log, self._compare)
        self.pending: collections.deque = collections.deque()  # (tdata, tid, vectors), sent, not yet taken
        self.last_taken = None  # the last packet the monitor saw
        self.hits = 0
        dut._log.info("DUT COORD_BITS=%d DIR_BITS=%d TAG_BITS=%d CONSERVATIVE=%d, s_axis_tdata_i %d bits, seed %d, "
                      "idle=%s backpressure=%s", self.coord_bits, self.dir_bits, self.tag_bits, self.conservative,
                      len(dut.s_axis_tdata_i), seed, idle, backpressure)

    def check_field_table(self) -> None:
        """The DUT's tdata offsets and widths are the port contract's."""
        dut, c = self.dut, self.contract
        assert len(dut.s_axis_tdata_i) == c.axis_tdata_bits, (len(dut.s_axis_tdata_i), c.axis_tdata_bits)
        assert int(dut.QUERY_BITS.value) == c.axis_query_bits, (int(dut.QUERY_BITS.value), c.axis_query_bits)
        rtl = {"ray_class_i": 0, "ray_org_i": int(dut.ORG_LSB.value), "ray_dir_i": int(dut.DIR_LSB.value),
               "ray_end_i": int(dut.END_LSB.value), "ray_end_valid_i": int(dut.END_VALID_LSB.value),
               "box_min_i": int(dut.BOX_MIN_LSB.value), "box_max_i": int(dut.BOX_MAX_LSB.value)}
        assert {name: lsb for name, lsb, _ in self.fields} == rtl, (self.fields, rtl)

    async def start(self) -> None:
        dut = self.dut
        dut.aresetn_i.value = 0
        Clock(dut.aclk_i, CLOCK_NS, unit="ns").start()
        await ClockCycles(dut.aclk_i, 4)
        dut.aresetn_i.value = 1
        await RisingEdge(dut.aclk_i)
        cocotb.start_soon(self._taken())

    def frames(self, vectors: list, max_beats: int = 8, exact: bool = False) -> list:
        """Packets of 1..max_beats queries (exactly max_beats: exact), one a
        beat, each with a random tid."""
        out, k = [], 0
        nbytes = self.contract.axis_tdata_bits // 8
        while k < len(vectors):
            beats = vectors[k:k + (max_beats if exact else self.rng.randint(1, max_beats))]
            k += len(beats)
            tid = self.rng.getrandbits(self.tag_bits)
            data = b"".join(axis.tdata_of(v.ports, self.fields).to_bytes(nbytes, "little") for v in beats)
            self.pending.append((data, tid, beats))
            out.append(AxiStreamFrame(data, tid=tid))
        return out

    async def _taken(self) -> None:
        """Every packet the DUT takes (the monitor's) goes into the scoreboard."""
        while True:
            frame = await self.monitor.recv()
            if not self.pending:
                self.scoreboard.error(f"the slave port took a packet nobody sent: {frame}")
                continue
            data, tid, beats = self.pending.popleft()
            if bytes(frame.tdata) != data or frame.tid != tid:
                self.scoreboard.error(f"the slave port took {frame}, not the packet sent (tid {tid})")
            self.last_taken = frame
            self.scoreboard.push(tid, beats, axis.cycle_of(frame.sim_time_end, CLOCK_NS))

    def _compare(self, beats, got) -> str | None:
        tdata, tuser = got
        want = [int(v.hit) for v in beats]
        self.hits += sum(want)
        hits = [b & 1 for b in tdata]
        if any(b >> 1 for b in tdata):
            return f"tdata bits 7..1 not zero: {list(tdata)}"
        if len(hits) != len(want):
            return f"{len(hits)} result beats for a packet of {len(want)} queries (tlast misplaced)"
        for k, (h, w) in enumerate(zip(hits, want)):
            if h != w:
                return f"beat {k}: RTL hit={h}, model hit={w} for {beats[k].describe()}"
        if tuser != hits:
            return f"tuser {tuser} is not the hit bits {hits}"
        return None

    async def collect(self, n_packets: int) -> list:
        """Takes n result packets and checks each against the scoreboard."""
        out = []
        for _ in range(n_packets):
            f = await self.sink.recv(compact=False)
            tuser = [int(u) for u in f.tuser] if isinstance(f.tuser, list) else [int(f.tuser)] * len(f.tdata)
            tids = set(f.tid) if isinstance(f.tid, list) else {f.tid}
            if len(tids) != 1:
                self.scoreboard.error(f"tid changes inside a result packet: {f.tid}")
            self.scoreboard.check(min(tids), (bytes(f.tdata), tuser), axis.cycle_of(f.sim_time_end, CLOCK_NS))
            out.append(f)
        return out

    async def run(self, vectors: list, max_beats: int = 8, exact: bool = False) -> list:
        """Sends the vectors in packets and checks every result packet."""
        frames = self.frames(vectors, max_beats, exact)
        compared = self.scoreboard.compared
        for f in frames:
            await self.source.send(f)
        got = await self.collect(len(frames))
        await ClockCycles(self.dut.aclk_i, 30)
        assert self.sink.empty(), f"{self.sink.count()} result packets more than queries sent"
        self.scoreboard.assert_clean()
        assert self.scoreboard.compared - compared == len(frames), (self.scoreboard.compared, len(frames))
        return got


if cocotb is not None:
    from pluecker_tb.intersector import stimulus as _intersector_stimulus

    class _StimulusHost:
        """What pluecker_tb.intersector.stimulus reads of a bench."""

        def __init__(self, bench: AxisBench):
            self.coord_bits, self.dir_bits = bench.coord_bits, bench.dir_bits
            self.conservative, self.fmt, self.dut = bench.conservative, bench.fmt, bench.dut
            self.ternary = False  # the wrapper's unit answers hit or miss (TERNARY = 0)

    def _stimulus(bench: AxisBench, source: str, n: int, salt) -> list:
        return _intersector_stimulus(_StimulusHost(bench), source, n, salt)[:n]

    @cocotb.test()
    @cocotb.parametrize(source=["random", "extreme", "boundary"], idle=[False, True], backpressure=[False, True])
    async def stream(dut, source: str, idle: bool, backpressure: bool) -> None:
        """Packets of queries under source and sink pauses, in order against the model."""
        bench = AxisBench(dut, _seed("axis", source, idle, backpressure), idle, backpressure)
        bench.check_field_table()
        await bench.start()
        vectors = _stimulus(bench, source, max(50, 300 * config.SCALE), ("axis", idle, backpressure))
        await bench.run(vectors)
        dut._log.info("stream %s: %d queries in %d packets compared (%d hits), latency histogram %s",
                      source, len(vectors), bench.scoreboard.compared, bench.hits, bench.scoreboard.histogram())

    @cocotb.test()
    async def full_rate(dut) -> None:
        """One query per clock in and out; blocked, FIFO_DEPTH + 2 get in."""
        bench = AxisBench(dut, _seed("axis-full-rate"))
        await bench.start()
        # One packet of n beats, no pauses: n cycles on each side.
        n = 200
        vectors = _stimulus(bench, "random", n, "full-rate")
        got = await bench.run(vectors, max_beats=len(vectors), exact=True)
        taken = bench.last_taken
        span_in = axis.span_cycles(taken, taken, CLOCK_NS)
        span_out = axis.span_cycles(got[0], got[0], CLOCK_NS)
        assert len(taken.tdata) == len(vectors) * bench.contract.axis_tdata_bits // 8
        assert span_in == len(vectors), f"{len(vectors)} queries took {span_in} cycles to go in"
        assert span_out == len(vectors), f"{len(vectors)} results took {span_out} cycles to come out"

        # The result stream blocked: the intersector's FIFO and the skid
        # registers fill, then s_axis_tready_o falls.
        depth = bench.contract.fifo_depth + 2
        bench.sink.pause = True
        more = _stimulus(bench, "extreme", depth + 20, "blocked")
        frames = bench.frames(more, max_beats=1)
        accepted = bench.scoreboard.accepted
        for f in frames:
            await bench.source.send(f)
        await ClockCycles(dut.aclk_i, depth + bench.contract.latency + 60)
        assert bench.scoreboard.accepted - accepted == depth, (
            f"{bench.scoreboard.accepted - accepted} queries taken with the result stream blocked, expected {depth}")
        assert int(dut.s_axis_tready_o.value) == 0
        bench.sink.pause = False
        await bench.collect(len(frames))
        bench.scoreboard.assert_clean()
        dut._log.info("full rate: %d queries in %d cycles, %d out in %d; %d taken while blocked",
                      len(vectors), span_in, len(vectors), span_out, depth)


# ---------------------------------------------------------------------------
# pytest side: one Verilator build per parameter set
# ---------------------------------------------------------------------------

# (COORD_BITS, DIR_BITS, CONSERVATIVE): fabric multipliers and the default
# widths; LATENCY 8 with PLUECKER_LONG=1.
CONFIGS = [(6, 6, 1), (16, 16, 1)] + ([(24, 24, 0), (7, 22, 1)] if config.LONG else [])


@pytest.mark.parametrize("coord_bits,dir_bits,conservative", CONFIGS,
                         ids=[f"c{c}_d{d}_{'cons' if k else 'near'}" for c, d, k in CONFIGS])
@pytest.mark.parametrize("tag_bits", [8])
def test_pluecker_axis(coord_bits: int, dir_bits: int, conservative: int, tag_bits: int) -> None:
    from pluecker_tb.runner import VERILATOR_RTL_ARGS, Build, need_model, param_name, rtl_sources

    need_model()
    parameters = {"COORD_BITS": coord_bits, "DIR_BITS": dir_bits, "TAG_BITS": tag_bits,
                  "CONSERVATIVE": conservative}
    build = Build(param_name("axis", parameters, {"COORD_BITS": "c", "DIR_BITS": "d", "TAG_BITS": "t",
                                                  "CONSERVATIVE": "cons"}))
    build.build(sources=rtl_sources(), hdl_toplevel=TOPLEVEL, parameters=parameters, defines={"ASSERT_ON": 1},
                build_args=VERILATOR_RTL_ARGS)
    build.test("test_pluecker_axis")
