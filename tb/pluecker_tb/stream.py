# SPDX-License-Identifier: MIT
"""Valid/ready driver, sink and in-order scoreboard (cocotb side).

They are wired by callbacks and share one EdgeCounter, so that both sides
speak of the same rising edge:

    driver --on_accept(item, edge)--> scoreboard.push
    sink   --on_transfer(edge)------> the bench reads the outputs and calls
                                      scoreboard.check(tag, got, edge)
    sink   --on_reset_edge()--------> scoreboard.drop_all  (a synchronous
                                      reset drops everything in flight)

Nothing assumes the DUT's latency: a result is matched with the oldest
outstanding item (and its tag, when the DUT has tags); the scoreboard keeps
the latency histogram for benches that check a latency contract themselves.
"""

from __future__ import annotations

import collections
from collections.abc import Callable, Sequence

from cocotb.triggers import ClockCycles, ReadOnly, RisingEdge

from .clock_reset import EdgeCounter


class InOrderScoreboard:
    """Expected items in input order; each result must match the oldest one.

    compare(item, got) returns None when the result is right, else a text
    saying what is wrong; describe(item) names the item in messages."""

    MAX_ERRORS = 10

    def __init__(self, log, compare: Callable[[object, object], str | None]):
        self.log = log
        self.compare = compare
        self.expected: collections.deque = collections.deque()  # (tag, item, in_edge)
        self.accepted = 0
        self.compared = 0
        self.dropped = 0
        self.dropped_tags: set = set()
        self.latencies: collections.Counter = collections.Counter()
        self.in_edges: list[int] = []
        self.out_edges: list[int] = []
        self.errors: list[str] = []

    def push(self, tag, item, edge: int) -> None:
        self.expected.append((tag, item, edge))
        self.in_edges.append(edge)
        self.accepted += 1

    def drop_all(self) -> None:
        self.dropped += len(self.expected)
        self.dropped_tags.update(t for t, _, _ in self.expected)
        self.expected.clear()

    def check(self, tag, got, edge: int) -> None:
        self.out_edges.append(edge)
        why = " (a query accepted before a reset)" if tag is not None and tag in self.dropped_tags else ""
        if not self.expected:
            self.error(f"edge {edge}: result tag {tag} = {got} with nothing outstanding{why}")
            return
        etag, item, in_edge = self.expected.popleft()
        if tag != etag:
            self.error(f"edge {edge}: result tag {tag}{why}, expected tag {etag}")
            return
        self.latencies[edge - in_edge] += 1
        self.compared += 1
        wrong = self.compare(item, got)
        if wrong:
            self.error(f"edge {edge}: tag {tag}: {wrong}")

    def error(self, msg: str) -> None:
        self.errors.append(msg)
        self.log.error("%s", msg)
        if len(self.errors) >= self.MAX_ERRORS:
            raise AssertionError(f"{len(self.errors)} errors, first: {self.errors[0]}")

    def histogram(self) -> str:
        return "{" + ", ".join(f"{k}:{v}" for k, v in sorted(self.latencies.items())) + "}"

    def assert_clean(self) -> None:
        assert not self.errors, f"{len(self.errors)} errors, first: {self.errors[0]}"


class StreamDriver:
    """Offers items on a valid/ready input, one at a time, each until taken.

    apply(item) drives the payload of an offered item; junk() drives the
    payload while valid is low (the DUT must ignore it); idle.idle_now()
    says when to leave the input idle. ready may be None (always ready) and
    rst None (no reset); a transfer needs valid, ready and rst low at a
    rising edge. on_accept(item, edge) is called for every transfer."""

    def __init__(self, clk, valid, ready, rst, edges: EdgeCounter, idle, apply: Callable[[object], None],
                 junk: Callable[[], None], on_accept: Callable[[object, int], None]):
        self.clk, self.valid, self.ready, self.rst = clk, valid, ready, rst
        self.edges, self.idle = edges, idle
        self.apply, self.junk, self.on_accept = apply, junk, on_accept

    async def send(self, items: Sequence) -> None:
        """Offers every item once; returns when the last one is taken."""
        i, cur = 0, None
        while cur is not None or i < len(items):
            if cur is None:
                if self.idle.idle_now():
                    self.valid.value = 0
                    self.junk()
                else:
                    cur = items[i]
                    i += 1
                    self.apply(cur)
                    self.valid.value = 1
            await ReadOnly()  # settled: these are the values the next edge samples
            fire = (cur is not None and (self.ready is None or int(self.ready.value) == 1)
                    and (self.rst is None or int(self.rst.value) == 0))
            edge = self.edges.edges + 1
            await RisingEdge(self.clk)
            if fire:
                self.on_accept(cur, edge)
                cur = None
        self.valid.value = 0
        self.junk()


class StreamSink:
    """Takes results from a valid/ready output.

    ready_gen.ready_now() drives ready (ready may be None: always taken).
    on_transfer(edge) is called in the ReadOnly phase of every cycle whose
    edge transfers a result (valid, ready, rst low), to read the outputs.
    With a reset (rst not None): on_reset_edge() at every rising edge with
    rst high, and the handles in `quiet` (e.g. valid and the input's ready)
    must be low from the second reset cycle on, and valid also in the first
    cycle after a reset; error(text) reports a violation (e.g. the
    scoreboard's error, so that it counts)."""

    def __init__(self, clk, valid, ready, rst, edges: EdgeCounter, ready_gen,
                 on_transfer: Callable[[int], None], error: Callable[[str], None],
                 on_reset_edge: Callable[[], None] = lambda: None, quiet: Sequence = ()):
        self.clk, self.valid, self.ready, self.rst = clk, valid, ready, rst
        self.edges, self.ready_gen = edges, ready_gen
        self.on_transfer, self.on_reset_edge = on_transfer, on_reset_edge
        self.quiet = list(quiet)
        self.error = error
        self.reset_run = 0  # consecutive reset edges just seen

    async def run(self) -> None:
        while True:
            ready = self.ready_gen.ready_now()
            if self.ready is not None:
                self.ready.value = ready
            else:
                ready = 1
            await ReadOnly()
            edge = self.edges.edges + 1
            rst = int(self.rst.value) if self.rst is not None else 0
            valid = int(self.valid.value)
            if rst:
                if self.reset_run > 0:
                    loud = [f"{h._name}={int(h.value)}" for h in self.quiet if int(h.value)]
                    if loud:
                        self.error(f"edge {edge}: {' '.join(loud)} while in reset (must be low)")
            else:
                if self.reset_run > 0 and valid:
                    self.error(f"edge {edge}: {self.valid._name} high right after a reset")
                if ready and valid:
                    self.on_transfer(edge)
            await RisingEdge(self.clk)
            if rst:
                self.reset_run += 1
                self.on_reset_edge()
            else:
                self.reset_run = 0


async def drain(clk, scoreboard: InOrderScoreboard, limit: int = 5000, quiet_cycles: int = 20) -> None:
    """Waits until every accepted item has come out (or was reset away),
    then `quiet_cycles` more in which nothing may appear."""
    for _ in range(limit):
        if not scoreboard.expected:
            break
        await RisingEdge(clk)
    await ClockCycles(clk, quiet_cycles)
    assert not scoreboard.expected, f"{len(scoreboard.expected)} items never came out"
