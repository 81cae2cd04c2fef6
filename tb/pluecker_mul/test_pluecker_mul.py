# SPDX-License-Identifier: MIT
"""cocotb bench of rtl/pluecker_mul.sv: every product equals the exact
signed product, after exactly the latency the module documents
(2 + PIPELINE + ADD_STAGES edges; see pluecker_tb/hdl/mul_stream.sv).

Paths
  ecp5     PLUECKER_ECP5 defined: MULT18X18D blocks (the project's model of
           the cell, pluecker_tb/hdl/MULT18X18D.v, checked against the
           installed Yosys' blackbox and DSP mapping by test_mult18x18d.py),
           operands over 18 bits split into partial products added in
           registered stages. Sixteen width pairs from 6 to 35 bits: both,
           one or no operand split, PIPELINE 0 and 1.
  generic  the plain `*` with the same registers (simulation and other
           targets), at a few width pairs.

Each build runs `stream` for random and corner operands (min, max, -1, 0, 1
and neighbours, single bits, runs of ones, their complements), with and
without idle gaps. PLUECKER_LONG=1: 25x the random operands.
"""

from __future__ import annotations

import random

import cocotb
import pytest

from pluecker_tb import config
from pluecker_tb.multiplier import MulBench, corner_pairs, random_pairs


@cocotb.test()
@cocotb.parametrize(idle=[False, True])
async def stream(dut, idle: bool) -> None:
    """Random and corner operands, with or without idle gaps."""
    bench = MulBench(dut, config.seed("pluecker_mul", int(dut.WA.value), int(dut.WB.value), idle), idle)
    assert bench.ecp5 == int(cocotb.plusargs.get("pluecker_ecp5", "0")), "built on the wrong path"
    await bench.start()
    rng = random.Random(bench.rng.random())
    pairs = corner_pairs(rng, bench.wa, bench.wb) + random_pairs(rng, bench.wa, bench.wb, 1500 * config.SCALE)
    rng.shuffle(pairs)
    await bench.run(pairs, f"stream idle={idle}")


# (WA, WB, PIPELINE): both operands whole, one split, both split; the widths
# the intersector uses (C + 1 by D + 1), the local unit's moment products
# ((G + 3) x (G + 1): 35 x 33 at G = 32, where the partial products are
# sign-extended into the 51-bit sum) and the extremes the module allows.
ECP5_WIDTHS = [(17, 17, 0), (19, 17, 0), (17, 19, 0), (19, 19, 0), (25, 25, 0), (25, 7, 0), (7, 25, 0),
               (21, 25, 1), (25, 18, 1), (18, 18, 1), (35, 18, 0), (26, 26, 0), (23, 21, 0), (6, 7, 0),
               (19, 25, 0), (25, 19, 1), (35, 33, 0), (21, 19, 0), (17, 17, 2), (25, 19, 2)]
GENERIC_WIDTHS = [(17, 17, 0), (25, 7, 1), (26, 26, 0), (19, 17, 2)]


def _build_and_run(wa: int, wb: int, pipeline: int, ecp5: bool) -> None:
    from pluecker_tb import ecp5 as e5
    from pluecker_tb.runner import Build, rtl_sources

    params = {"WA": wa, "WB": wb, "PIPELINE": pipeline, "LUT": 0}
    name = f"pluecker_mul_{'ecp5' if ecp5 else 'generic'}_{wa}x{wb}_p{pipeline}"
    sources = [*rtl_sources(), e5.HDL / "mul_stream.sv"] + (e5.model_sources() if ecp5 else [])
    b = Build(name).build(sources=sources, hdl_toplevel="mul_stream", parameters=params,
                          defines={"PLUECKER_ECP5": 1} if ecp5 else {})
    b.test("test_pluecker_mul", plusargs=[f"+pluecker_ecp5={int(ecp5)}"])


@pytest.mark.parametrize("wa,wb,pipeline", ECP5_WIDTHS, ids=[f"{a}x{b}_p{p}" for a, b, p in ECP5_WIDTHS])
def test_pluecker_mul_ecp5(wa: int, wb: int, pipeline: int) -> None:
    _build_and_run(wa, wb, pipeline, ecp5=True)


@pytest.mark.parametrize("wa,wb,pipeline", GENERIC_WIDTHS, ids=[f"{a}x{b}_p{p}" for a, b, p in GENERIC_WIDTHS])
def test_pluecker_mul_generic(wa: int, wb: int, pipeline: int) -> None:
    _build_and_run(wa, wb, pipeline, ecp5=False)
