# SPDX-License-Identifier: MIT
"""cocotb bench of rtl/pluecker_mul_pair.sv: two products a*b0 and a*b1
(a signed, b0 and b1 unsigned) from one packed multiplier, each equal to
the exact product, exactly 4 clock edges after the operands (bench top
pluecker_tb/hdl/mul_pair_stream.sv).

Paths
  ecp5     PLUECKER_ECP5 defined: one MULT18X18D (SIGNEDA 1, SIGNEDB 0;
           the project's model of the cell, pluecker_tb/hdl/MULT18X18D.v)
  generic  the same packing around a plain 18 x 18 `*`

Operands: every (a, b0) with b1 drawn at random and every (a, b1) with
b0 drawn at random (a: every value up to 9 bits, else its corner values
and 512 at random) (so every low product, and every high product with its
borrow s = (a*b0 < 0) both set and clear), the corner triples (a in min,
min + 1, -1, 0, 1, max; b0, b1 in 0, 1, max - 1, max), and random
triples; with and without idle gaps. Widths: the intersector's 7 x 6
(6/6 bits) and the extremes the module allows (WA - 1 + 2 WU = 18).
"""

from __future__ import annotations

import itertools
import random

import cocotb
import pytest

from pluecker_tb import clock_reset, config, traffic
from pluecker_tb.multiplier import corner_values, to_signed
from pluecker_tb.stream import InOrderScoreboard, StreamDriver, StreamSink, drain


class PairBench:
    def __init__(self, dut, seed: int, idle: bool):
        self.dut = dut
        self.wa = int(dut.WA.value)
        self.wu = int(dut.WU.value)
        self.ecp5 = int(dut.ECP5.value)
        self.rng = random.Random(seed)
        self.idle_gen = traffic.idle_generator(random.Random(seed + 1), idle)
        self.scoreboard = InOrderScoreboard(dut._log, self._compare)
        dut._log.info("DUT pluecker_mul_pair WA=%d WU=%d%s, seed %d, idle=%s", self.wa, self.wu,
                      " (ECP5 path: MULT18X18D)" if self.ecp5 else "", seed, idle)

    async def start(self) -> None:
        dut = self.dut
        dut.in_valid_i.value = 0
        self._junk()
        self.edges = await clock_reset.start(dut.clk_i, dut.rst_i, 3)
        self.driver = StreamDriver(dut.clk_i, dut.in_valid_i, None, dut.rst_i, self.edges, self.idle_gen,
                                   self._apply, self._junk, lambda item, edge: self.scoreboard.push(None, item, edge))
        self.sink = StreamSink(dut.clk_i, dut.out_valid_o, None, dut.rst_i, self.edges, traffic.AlwaysReady(),
                               self._transfer, self.scoreboard.error, quiet=[dut.out_valid_o])
        cocotb.start_soon(self.sink.run())

    def _junk(self) -> None:
        self.dut.a_i.value = self.rng.getrandbits(self.wa)
        self.dut.b0_i.value = self.rng.getrandbits(self.wu)
        self.dut.b1_i.value = self.rng.getrandbits(self.wu)

    def _apply(self, t) -> None:
        self.dut.a_i.value = t[0] & ((1 << self.wa) - 1)
        self.dut.b0_i.value = t[1]
        self.dut.b1_i.value = t[2]

    def _transfer(self, edge: int) -> None:
        w = self.wa + self.wu + 1
        got = (to_signed(int(self.dut.p0_o.value), w), to_signed(int(self.dut.p1_o.value), w))
        self.scoreboard.check(None, got, edge)

    @staticmethod
    def _compare(t, got) -> str | None:
        want = (t[0] * t[1], t[0] * t[2])
        return None if got == want else f"a={t[0]} b0={t[1]} b1={t[2]}: got {got}, expected {want}"

    def triples(self) -> list[tuple[int, int, int]]:
        wa, wu, rng = self.wa, self.wu, self.rng
        # Every a up to 9 bits; wider: the corner values and 512 at random.
        a_all = ([to_signed(i, wa) for i in range(1 << wa)] if wa <= 9 else
                 corner_values(wa) + [to_signed(rng.getrandbits(wa), wa) for _ in range(512)])
        b_all = range(1 << wu)
        ub = lambda: rng.getrandbits(wu)  # noqa: E731
        out = [(a, b0, ub()) for a in a_all for b0 in b_all] + [(a, ub(), b1) for a in a_all for b1 in b_all]
        lo, hi, bmax = -(1 << (wa - 1)), (1 << (wa - 1)) - 1, (1 << wu) - 1
        a_c = sorted({lo, lo + 1, -1, 0, 1, hi})
        b_c = sorted({0, 1, bmax - 1, bmax})
        out += list(itertools.product(a_c, b_c, b_c))
        out += [(to_signed(rng.getrandbits(wa), wa), ub(), ub()) for _ in range(1000 * config.SCALE)]
        rng.shuffle(out)
        return out

    async def run(self, what: str) -> None:
        items = self.triples()
        await self.driver.send(items)
        await drain(self.dut.clk_i, self.scoreboard)
        sb = self.scoreboard
        sb.assert_clean()
        assert sb.compared == len(items), f"compared {sb.compared} of {len(items)}"
        self.dut._log.info("%s: %d product pairs compared, latency histogram %s", what, sb.compared, sb.histogram())


@cocotb.test()
@cocotb.parametrize(idle=[False, True])
async def stream(dut, idle: bool) -> None:
    """Every (a, b0), every (a, b1), corners and random, with or without idle gaps."""
    bench = PairBench(dut, config.seed("pluecker_mul_pair", int(dut.WA.value), int(dut.WU.value), idle), idle)
    assert bench.ecp5 == int(cocotb.plusargs.get("pluecker_ecp5", "0")), "built on the wrong path"
    await bench.start()
    await bench.run(f"stream idle={idle}")


# (WA, WU): the intersector's 6/6 (C + 1 = 7 by D = 6), the widest shared
# operand and the widest pair the 18-bit port takes (WA - 1 + 2 WU = 18).
WIDTHS = [(7, 6), (17, 1), (3, 8)]


def _build_and_run(wa: int, wu: int, ecp5: bool) -> None:
    from pluecker_tb import ecp5 as e5
    from pluecker_tb.runner import Build, rtl_sources

    name = f"pluecker_mul_pair_{'ecp5' if ecp5 else 'generic'}_{wa}x{wu}"
    sources = [*rtl_sources(), e5.HDL / "mul_pair_stream.sv"] + (e5.model_sources() if ecp5 else [])
    b = Build(name).build(sources=sources, hdl_toplevel="mul_pair_stream", parameters={"WA": wa, "WU": wu},
                          defines={"PLUECKER_ECP5": 1} if ecp5 else {})
    b.test("test_pluecker_mul_pair", plusargs=[f"+pluecker_ecp5={int(ecp5)}"])


@pytest.mark.parametrize("ecp5", [True, False], ids=["ecp5", "generic"])
@pytest.mark.parametrize("wa,wu", WIDTHS, ids=[f"{a}x{u}" for a, u in WIDTHS])
def test_pluecker_mul_pair(wa: int, wu: int, ecp5: bool) -> None:
    _build_and_run(wa, wu, ecp5)
