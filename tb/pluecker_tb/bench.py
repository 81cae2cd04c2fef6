# SPDX-License-Identifier: MIT
"""UnitBench: clock and reset, driver, sink and in-order scoreboard around
a valid/ready unit with a tag (cocotb side): the part of the intersector
benches that does not depend on the unit's payload.

A subclass names the unit's payload input ports (PAYLOAD, driven with
random junk while in_valid_i is low, which the DUT must ignore) and
compares a result with its vector (`compare`). A vector's `ports` dict
drives the payload, its `hit` (an int: one bit per answer) is the model's
answer and `describe()` names it in messages. Results are matched by order
and tag; nothing assumes the pipeline latency.

Checked every cycle: each result leaves once, in order, with its query's
tag and the model's answer; nothing accepted before a reset leaves after it
(the scoreboard forgets every query at a reset edge; a later result with no
query outstanding, or with another tag, is an error naming the reset);
in_ready_o and out_valid_o are low from the second reset cycle on, and
out_valid_o in the first cycle after a reset.
"""

from __future__ import annotations

import random

import cocotb
from cocotb.triggers import ClockCycles

from . import clock_reset, traffic
from .stream import InOrderScoreboard, StreamDriver, StreamSink, drain


class UnitBench:
    """One DUT: idle and ready generators by default those of `idle` and
    `backpressure` (traffic.IdleGaps, traffic.Backpressure); a bench with
    its own traffic passes `traffic_gen` (both at once, e.g. traffic.Phases)."""

    PAYLOAD: tuple[str, ...] = ()

    def __init__(self, dut, seed: int, idle: bool = False, backpressure: bool = False, traffic_gen=None):
        self.dut = dut
        self.tag_bits = int(dut.TAG_BITS.value)
        self.seed = seed
        self.rng = random.Random(seed)  # payload junk
        if traffic_gen is not None:
            self.idle_gen = self.ready_gen = traffic_gen
        else:
            self.idle_gen = traffic.idle_generator(random.Random(seed + 1), idle)
            self.ready_gen = traffic.ready_generator(random.Random(seed + 2), backpressure)
        self.next_tag = 0
        self.hits = 0
        self.scoreboard = InOrderScoreboard(dut._log, self._compare)
        self.edge_counter: clock_reset.EdgeCounter | None = None

    # -- the scoreboard's figures, as the tests read them ------------------------
    accepted = property(lambda self: self.scoreboard.accepted)
    compared = property(lambda self: self.scoreboard.compared)
    dropped = property(lambda self: self.scoreboard.dropped)
    latencies = property(lambda self: self.scoreboard.latencies)
    in_edges = property(lambda self: self.scoreboard.in_edges)
    out_edges = property(lambda self: self.scoreboard.out_edges)
    errors = property(lambda self: self.scoreboard.errors)
    expected = property(lambda self: self.scoreboard.expected)
    edges = property(lambda self: self.edge_counter.edges if self.edge_counter else 0)

    @property
    def ready_override(self) -> int | None:
        """out_ready_i forced to this value when set (None: the generator's)."""
        return self.ready_gen.override

    @ready_override.setter
    def ready_override(self, value: int | None) -> None:
        self.ready_gen.override = value

    # -- set-up ---------------------------------------------------------------------
    async def start(self) -> None:
        dut = self.dut
        dut.in_valid_i.value = 0
        dut.out_ready_i.value = 0
        self._junk()
        self.edge_counter = await clock_reset.start(dut.clk_i, dut.rst_i, 3)
        self.driver = StreamDriver(dut.clk_i, dut.in_valid_i, dut.in_ready_o, dut.rst_i, self.edge_counter,
                                   self.idle_gen, self._apply, self._junk, self._accepted)
        self.sink = StreamSink(dut.clk_i, dut.out_valid_o, dut.out_ready_i, dut.rst_i, self.edge_counter,
                               self.ready_gen, self._transfer, self.scoreboard.error,
                               on_reset_edge=self.scoreboard.drop_all, quiet=[dut.out_valid_o, dut.in_ready_o])
        self.sink_task = cocotb.start_soon(self.sink.run())

    def _junk(self) -> None:
        """Random payload while in_valid_i is low: the DUT must ignore it."""
        for name in ("in_tag_i", *self.PAYLOAD):
            handle = getattr(self.dut, name)
            handle.value = self.rng.getrandbits(len(handle))

    def _apply(self, item) -> None:
        tag, vec = item
        for name, value in vec.ports.items():
            getattr(self.dut, name).value = value
        self.dut.in_tag_i.value = tag

    def _accepted(self, item, edge: int) -> None:
        self.scoreboard.push(item[0], item[1], edge)

    def _transfer(self, edge: int) -> None:
        self.scoreboard.check(int(self.dut.out_tag_o.value), int(self.dut.out_hit_o.value), edge)

    def _compare(self, vec, hit: int) -> str | None:
        expected = int(vec.hit)
        self.hits += bin(expected).count("1")
        if hit != expected:
            return f"RTL hit={hit:b}, model hit={expected:b} for {vec.describe()}"
        return None

    def _error(self, msg: str) -> None:
        self.scoreboard.error(msg)

    # -- traffic ------------------------------------------------------------------------
    async def drive(self, vectors) -> None:
        """Offers every vector once, with consecutive tags; returns when the
        last one is taken."""
        items = []
        for v in vectors:
            items.append((self.next_tag, v))
            self.next_tag = (self.next_tag + 1) % (1 << self.tag_bits)
        await self.driver.send(items)

    async def drain(self, limit: int = 5000) -> None:
        """Waits until every accepted query has come out (or was reset away)."""
        self.ready_override = None
        await drain(self.dut.clk_i, self.scoreboard, limit)

    def finish(self, what: str) -> None:
        self.scoreboard.assert_clean()
        self.dut._log.info(
            "%s: %d results compared (%d hits), %d dropped by reset, %d cycles, latency histogram %s",
            what, self.compared, self.hits, self.dropped, self.edges, self.scoreboard.histogram())


# ---------------------------------------------------------------------------
# The tests every unit bench runs (the benches' cocotb tests call them)
# ---------------------------------------------------------------------------

def latency_text(dut) -> str:
    """The DUT's LATENCY localparam for messages ("?" in a flattened netlist)."""
    try:
        return str(int(dut.LATENCY.value))
    except AttributeError:
        return "?"


def check_contract(bench: UnitBench, contract) -> tuple[int, int]:
    """The DUT's LATENCY and FIFO_DEPTH localparams and its port widths must
    be the port contract's (`contract`: computed from the DUT's parameters
    alone, with latency, fifo_depth and ports); returns (LATENCY, FIFO depth)."""
    dut = bench.dut
    latency, depth = contract.latency, contract.fifo_depth
    dut_values = (int(dut.LATENCY.value), int(dut.FIFO_DEPTH.value))
    assert dut_values == (latency, depth), (
        f"DUT LATENCY, FIFO_DEPTH = {dut_values}, port contract {(latency, depth)} ({contract!r})")
    for port in contract.ports:
        assert len(getattr(dut, port.name)) == port.width, (
            f"{port.name}: {len(getattr(dut, port.name))} bits, port contract {port.width}")
    return latency, depth


async def reset_mid_stream(bench: UnitBench, vectors) -> int:
    """Drives `vectors` while resets of 1..7 cycles come every 10..200
    cycles: every query accepted before a reset must vanish (the bench's
    scoreboard and sink check it); returns the number of resets."""
    dut = bench.dut
    resets = 0

    async def reset_pulses() -> None:
        nonlocal resets
        rng = random.Random(bench.seed + 1)
        while True:
            await ClockCycles(dut.clk_i, rng.randint(10, 200))
            dut.rst_i.value = 1
            await ClockCycles(dut.clk_i, rng.choice([1, 1, 2, 3, 7]))
            dut.rst_i.value = 0
            resets += 1

    pulses = cocotb.start_soon(reset_pulses())
    await bench.drive(vectors)
    pulses.cancel()
    dut.rst_i.value = 0
    await bench.drain()
    assert resets >= 3, f"only {resets} resets happened"
    assert bench.dropped > 0, "no reset hit a query in flight"
    assert bench.compared + bench.dropped == bench.accepted == len(vectors), (
        f"accepted {bench.accepted}, compared {bench.compared}, dropped {bench.dropped}")
    return resets


async def full_rate(bench: UnitBench, vectors, latency: int) -> None:
    """Never stalled: one query taken and one result given every clock, each
    after exactly `latency` cycles (the port contract's LATENCY)."""
    await bench.drive(vectors)
    await bench.drain()
    n = len(vectors)
    assert bench.in_edges[-1] - bench.in_edges[0] == n - 1, "input was not taken every clock"
    assert bench.out_edges[-1] - bench.out_edges[0] == n - 1, "results did not come every clock"
    assert set(bench.latencies) == {latency}, f"latency {dict(bench.latencies)}, LATENCY = {latency}"


async def credits_stop_input(bench: UnitBench, more, latency: int, depth: int) -> None:
    """Output blocked: exactly `depth` (the FIFO depth) of `more` get in,
    the rest after the output is released; every result is compared."""
    before_compared = bench.compared
    bench.ready_override = 0
    before = bench.accepted
    task = cocotb.start_soon(bench.drive(more))
    await ClockCycles(bench.dut.clk_i, depth + latency + 50)
    assert bench.accepted - before == depth, f"{bench.accepted - before} taken with the output blocked"
    bench.ready_override = None
    await task
    await bench.drain()
    assert bench.compared - before_compared == len(more)
