# SPDX-License-Identifier: MIT
"""MulBench: driver -> model (the exact signed product) -> in-order
scoreboard around hdl/mul_stream.sv, the bench top of the two multipliers
(cocotb side), and its operand sets.

WA, WB, PIPELINE, LUT, LATENCY, ECP5 (the path built) and SIGNED are read
back from the DUT. The multipliers have no ready: the sink always takes, and the
traffic is crossed with idle gaps only (random operands while in_valid_i
is low, which must not reach a checked product).
"""

from __future__ import annotations

import random

import cocotb

from . import clock_reset, traffic
from .stream import InOrderScoreboard, StreamDriver, StreamSink, drain


def to_signed(v: int, w: int) -> int:
    v &= (1 << w) - 1
    return v - (1 << w) if v >> (w - 1) else v


def corner_values(w: int) -> list[int]:
    """Signed w-bit operands where a multiplier breaks first: min, max,
    -1, 0, 1 and their neighbours, every single bit and its complement,
    every run of ones from bit 0 (2^k - 1) and its negation."""
    lo, hi = -(1 << (w - 1)), (1 << (w - 1)) - 1
    vals = {lo, lo + 1, -2, -1, 0, 1, 2, hi - 1, hi}
    for k in range(w):
        vals.add(to_signed(1 << k, w))
        vals.add(to_signed(~(1 << k), w))
        vals.add(to_signed((1 << k) - 1, w))
        vals.add(to_signed(-((1 << k) - 1), w))
    return sorted({to_signed(v, w) for v in vals})  # (at small widths some wrap: keep them in range)


def core_values(w: int) -> list[int]:
    """min, min + 1, -1, 0, 1, max - 1, max."""
    lo, hi = -(1 << (w - 1)), (1 << (w - 1)) - 1
    return sorted({to_signed(v, w) for v in (lo, lo + 1, -1, 0, 1, hi - 1, hi)})


def corner_pairs(rng: random.Random, wa: int, wb: int, n_cross: int = 500) -> list[tuple[int, int]]:
    """Every corner value of each operand against the core values of the
    other, and n_cross pairs of corner values drawn at random."""
    ca, cb = corner_values(wa), corner_values(wb)
    pairs = {(a, b) for a in ca for b in core_values(wb)} | {(a, b) for a in core_values(wa) for b in cb}
    cross = [(a, b) for a in ca for b in cb]
    pairs |= set(rng.sample(cross, min(n_cross, len(cross))))
    out = sorted(pairs)
    rng.shuffle(out)
    return out


def random_pairs(rng: random.Random, wa: int, wb: int, n: int) -> list[tuple[int, int]]:
    return [(to_signed(rng.getrandbits(wa), wa), to_signed(rng.getrandbits(wb), wb)) for _ in range(n)]


def all_pairs(wa: int, wb: int) -> list[tuple[int, int]]:
    """Every signed operand pair (exhaustive, small widths only)."""
    return [(to_signed(i, wa), to_signed(j, wb)) for j in range(1 << wb) for i in range(1 << wa)]


class MulBench:
    def __init__(self, dut, seed: int, idle: bool = False):
        self.dut = dut
        self.wa = int(dut.WA.value)
        self.wb = int(dut.WB.value)
        self.pipeline = int(dut.PIPELINE.value)
        self.lut = int(dut.LUT.value)
        self.latency = int(dut.LATENCY.value)
        self.ecp5 = int(dut.ECP5.value)
        self.signed = int(dut.SIGNED.value)  # operands and product two's complement, else unsigned
        self._traffic(seed, idle)
        dut._log.info("DUT %s WA=%d WB=%d PIPELINE=%d LATENCY=%d%s, seed %d, idle=%s",
                      "pluecker_mul_lut" if self.lut else "pluecker_mul", self.wa, self.wb, self.pipeline,
                      self.latency, " (ECP5 path: MULT18X18D)" if self.ecp5 and not self.lut else "", seed, idle)

    def _traffic(self, seed: int, idle: bool) -> None:
        """The operand generator, the idle gaps and the scoreboard."""
        self.rng = random.Random(seed)
        self.idle_gen = traffic.idle_generator(random.Random(seed + 1), idle)
        self.scoreboard = InOrderScoreboard(self.dut._log, self._compare)

    async def start(self) -> None:
        dut = self.dut
        dut.in_valid_i.value = 0
        self._junk()
        self.edges = await clock_reset.start(dut.clk_i, dut.rst_i, 3)
        self.driver = StreamDriver(dut.clk_i, dut.in_valid_i, None, dut.rst_i, self.edges, self.idle_gen,
                                   self._apply, self._junk, lambda item, edge: self.scoreboard.push(None, item, edge))
        self.sink = StreamSink(dut.clk_i, dut.out_valid_o, None, dut.rst_i, self.edges, traffic.AlwaysReady(),
                               self._transfer, self.scoreboard.error, quiet=[dut.out_valid_o])
        self.sink_task = cocotb.start_soon(self.sink.run())

    def _junk(self) -> None:
        self.dut.a_i.value = self.rng.getrandbits(self.wa)
        self.dut.b_i.value = self.rng.getrandbits(self.wb)

    def _apply(self, pair) -> None:
        self.dut.a_i.value = pair[0] & ((1 << self.wa) - 1)
        self.dut.b_i.value = pair[1] & ((1 << self.wb) - 1)

    def _transfer(self, edge: int) -> None:
        p = int(self.dut.p_o.value)
        self.scoreboard.check(None, to_signed(p, self.wa + self.wb) if self.signed else p, edge)

    @staticmethod
    def _compare(pair, got: int) -> str | None:
        want = pair[0] * pair[1]
        return None if got == want else f"{pair[0]} * {pair[1]}: got {got}, expected {want}"

    async def run(self, pairs, what: str) -> None:
        """Drives the operand pairs (signed values; taken modulo 2^W as
        unsigned operands when the DUT's SIGNED is 0) and checks every
        product."""
        if not self.signed:
            pairs = [(a & ((1 << self.wa) - 1), b & ((1 << self.wb) - 1)) for a, b in pairs]
        await self.driver.send(pairs)
        await drain(self.dut.clk_i, self.scoreboard)
        sb = self.scoreboard
        sb.assert_clean()
        assert sb.compared == len(pairs), f"compared {sb.compared} of {len(pairs)}"
        self.dut._log.info("%s: %d products compared, latency histogram %s", what, sb.compared, sb.histogram())


class RomBench(MulBench):
    """The bench of the block-RAM table multiplier (rtl/pluecker_mul_rom.sv)
    around hdl/mul_rom_stream.sv or a Yosys netlist of it: a_i signed WA
    bits, b_i unsigned WU bits, p_o = a*b signed WA + WU + 1 bits, LATENCY
    edges after the operands (WA, WU, LATENCY, ECP5 read back from the DUT).
    MulBench's driver, sink, scoreboard and run serve it (b as a WU-bit
    operand that is never negative). Operands: every (a, b) when
    WA + WU <= 14, else the corner values of a against every b of up to 8
    bits (or b's corners and 256 at random), both sides at random besides;
    idle gaps optional."""

    def __init__(self, dut, seed: int, idle: bool = False):
        # Not MulBench.__init__: it reads parameters (PIPELINE, LUT, SIGNED)
        # that the table multiplier's bench top lacks.
        self.dut = dut
        self.wa = int(dut.WA.value)
        self.wu = self.wb = int(dut.WU.value)
        self.signed = 1  # the product is signed; run() then drives the pairs as given (b in 0..2^WU - 1)
        self.latency = int(dut.LATENCY.value)
        self.ecp5 = int(dut.ECP5.value)
        self._traffic(seed, idle)
        dut._log.info("DUT pluecker_mul_rom WA=%d WU=%d LATENCY=%d%s, seed %d, idle=%s", self.wa, self.wu,
                      self.latency, " (ECP5 path: DP16KD)" if self.ecp5 else "", seed, idle)

    def _transfer(self, edge: int) -> None:
        self.scoreboard.check(None, to_signed(int(self.dut.p_o.value), self.wa + self.wu + 1), edge)

    def pairs(self, n_random: int) -> list[tuple[int, int]]:
        wa, wu, rng = self.wa, self.wu, self.rng
        bs = list(range(1 << wu)) if wu <= 8 else sorted(
            {0, 1, 2, (1 << wu) - 2, (1 << wu) - 1} | {1 << k for k in range(wu)} | {(1 << k) - 1 for k in range(wu)}
            | {rng.getrandbits(wu) for _ in range(256)})
        if wa + wu <= 14:
            out = [(to_signed(i, wa), b) for i in range(1 << wa) for b in range(1 << wu)]
        else:
            out = [(a, b) for a in corner_values(wa) for b in bs]
        out += [(to_signed(rng.getrandbits(wa), wa), rng.getrandbits(wu)) for _ in range(n_random)]
        rng.shuffle(out)
        return out
