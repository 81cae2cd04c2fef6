# SPDX-License-Identifier: MIT
"""Clock, start-up reset and a rising-edge counter (cocotb side)."""

from __future__ import annotations

import cocotb
from cocotb.clock import Clock
from cocotb.handle import Immediate
from cocotb.triggers import ClockCycles, RisingEdge

CLOCK_NS = 10


def on_verilator() -> bool:
    return "verilator" in cocotb.SIM_NAME.lower()


def settle_low(clk, rst) -> None:
    """clk low and rst high before the first evaluation.

    Under +verilator+rand+reset the clock input may start at 1, which
    Verilator's edge detector (starting from 0) takes for a rising edge that
    clocks the unreset state before any reset; the RTL's ASSERT_ON checks
    then rightly fail. The writes must be immediate: a scheduled one lands
    after that first evaluation. Under Icarus, scheduled writes are the ones
    that work (immediate ones leave a netlist unreset at the first edge)."""
    write = Immediate if on_verilator() else int
    clk.value = write(0)
    rst.value = write(1)


class EdgeCounter:
    """Counts rising edges of a clock; edges + 1 is the edge that samples
    the values settled now (read in the ReadOnly phase)."""

    def __init__(self, clk):
        self.clk = clk
        self.edges = 0
        self.task = cocotb.start_soon(self._run())

    async def _run(self) -> None:
        while True:
            await RisingEdge(self.clk)
            self.edges += 1


async def start(clk, rst, cycles: int = 3, before_release=None) -> EdgeCounter:
    """Starts the clock with rst high, holds it for `cycles` rising edges
    and releases it; `before_release()` runs (e.g. starts a sink) just
    before rst falls. Returns the edge counter (started with the clock)."""
    settle_low(clk, rst)
    Clock(clk, CLOCK_NS, unit="ns").start()
    counter = EdgeCounter(clk)
    rst.value = 1
    await ClockCycles(clk, cycles)
    rst.value = 0
    if before_release is not None:
        before_release()
    return counter
