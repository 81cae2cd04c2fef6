# SPDX-License-Identifier: MIT
"""cocotb bench for rtl/pluecker_axis_skid.sv (the skid register of the
AXI4-Stream wrapper), with cocotbext-axi's source, sink and monitor on its
valid/ready ports (pluecker_tb.axis.stream_bus, one DATA_BITS-wide "byte"
per beat).

Tests
  stream      random items under source pauses x sink pauses (the pause
              patterns of pluecker_tb.traffic): every item comes out once,
              in order, unchanged (the shared in-order scoreboard)
  full_rate   one item per clock through, and with the output blocked
              exactly two items get in (output and skid register), in_ready_o
              low from the next edge on
"""

from __future__ import annotations

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

TOPLEVEL = "pluecker_axis_skid"
CLOCK_NS = 10
_seed = config.seed


class SkidBench:
    def __init__(self, dut, seed: int, idle: bool = False, backpressure: bool = False):
        from pluecker_tb.stream import InOrderScoreboard

        self.dut = dut
        self.bits = int(dut.DATA_BITS.value)
        self.source, self.monitor, self.sink = axis.endpoints(
            lambda slave: axis.stream_bus(dut, "in" if slave else "out", slave), dut.clk_i, dut.rst_i, seed, idle,
            backpressure, byte_size=self.bits)
        self.rng = random.Random(seed)
        self.scoreboard = InOrderScoreboard(dut._log, lambda want, got: None if want == got else f"{got} != {want}")

    async def start(self) -> None:
        self.dut.rst_i.value = 1
        Clock(self.dut.clk_i, CLOCK_NS, unit="ns").start()
        await ClockCycles(self.dut.clk_i, 3)
        self.dut.rst_i.value = 0
        await RisingEdge(self.dut.clk_i)
        cocotb.start_soon(self._taken())

    async def _taken(self) -> None:
        while True:
            f = await self.monitor.recv(compact=False)
            for v in f.tdata:
                self.scoreboard.push(None, v, axis.cycle_of(f.sim_time_end, CLOCK_NS))

    def items(self, n: int) -> list[int]:
        return [self.rng.getrandbits(self.bits) for _ in range(n)]

    async def collect(self, n: int) -> list:
        """n items (the bus has no tlast: one item a packet)."""
        out = []
        while len(out) < n:
            f = await self.sink.recv(compact=False)
            for v in f.tdata:
                self.scoreboard.check(None, v, axis.cycle_of(f.sim_time_end, CLOCK_NS))
            out.append(f)
        return out


if cocotb is not None:

    @cocotb.test()
    @cocotb.parametrize(idle=[False, True], backpressure=[False, True])
    async def stream(dut, idle: bool, backpressure: bool) -> None:
        """Every item once, in order, unchanged, under pauses on both sides."""
        bench = SkidBench(dut, _seed("skid", idle, backpressure), idle, backpressure)
        await bench.start()
        items = bench.items(500 * config.SCALE)
        for v in items:  # one item a packet
            await bench.source.send(AxiStreamFrame([v]))
        await bench.collect(len(items))
        await ClockCycles(dut.clk_i, 10)
        assert bench.sink.empty(), "more items out than in"
        bench.scoreboard.assert_clean()
        assert bench.scoreboard.compared == len(items)

    @cocotb.test()
    async def full_rate(dut) -> None:
        """One item per clock; blocked, it takes exactly two."""
        bench = SkidBench(dut, _seed("skid-full-rate"))
        await bench.start()
        items = bench.items(100)
        await bench.source.send(AxiStreamFrame(items))  # one packet: back to back
        got = await bench.collect(len(items))  # no tlast: a packet a beat on the output
        span = axis.span_cycles(got[0], got[-1], CLOCK_NS)
        assert span == len(items), f"{len(items)} items took {span} cycles"
        bench.sink.pause = True
        more = bench.items(10)
        for v in more:
            await bench.source.send(AxiStreamFrame([v]))
        await ClockCycles(dut.clk_i, 20)
        assert bench.scoreboard.accepted - len(items) == 2, bench.scoreboard.accepted - len(items)
        assert int(dut.in_ready_o.value) == 0
        bench.sink.pause = False
        await bench.collect(len(more))
        bench.scoreboard.assert_clean()


# ---------------------------------------------------------------------------
# pytest side
# ---------------------------------------------------------------------------

def _build(data_bits: int):
    from pluecker_tb.runner import VERILATOR_RTL_ARGS, Build

    return Build(f"pluecker_axis_skid_w{data_bits}").build(
        sources=[config.RTL_DIR / "pluecker_axis_skid.sv"], hdl_toplevel=TOPLEVEL,
        parameters={"DATA_BITS": data_bits}, build_args=VERILATOR_RTL_ARGS)


@pytest.mark.parametrize("data_bits", [1, 13])
def test_pluecker_axis_skid(data_bits: int) -> None:
    _build(data_bits).test("test_pluecker_axis_skid")

