# SPDX-License-Identifier: MIT
"""cocotb bench of rtl/pluecker_mul_lut.sv, the fabric multiplier: every
product equals the exact signed product, after exactly the latency the
module documents (2 + PIPELINE edges; see pluecker_tb/hdl/mul_stream.sv).

  exhaustive  every signed WA x WB operand pair, at full rate
  stream      random and corner operands with idle gaps (the operands while
              in_valid_i is low must not reach a checked product)

Widths swept (one build each); 17x17 (the widest the intersector uses the
fabric multiplier at) is too wide for every pair and runs `stream` only.
"""

from __future__ import annotations

import random

import cocotb
import pytest

from pluecker_tb import config
from pluecker_tb.multiplier import MulBench, all_pairs, corner_pairs, random_pairs

EXHAUSTIVE_MAX_BITS = 16  # WA + WB


@cocotb.test()
async def exhaustive(dut) -> None:
    """Every operand pair, in order, at full rate."""
    bench = MulBench(dut, config.seed("pluecker_mul_lut", "exhaustive"))
    assert bench.wa + bench.wb <= EXHAUSTIVE_MAX_BITS, f"{bench.wa}x{bench.wb}: too many pairs"
    await bench.start()
    pairs = all_pairs(bench.wa, bench.wb)
    await bench.run(pairs, "exhaustive")
    assert bench.scoreboard.compared == 1 << (bench.wa + bench.wb)


@cocotb.test()
async def stream(dut) -> None:
    """Random and corner operands with idle gaps."""
    bench = MulBench(dut, config.seed("pluecker_mul_lut", "stream", int(dut.WA.value), int(dut.WB.value)), idle=True)
    await bench.start()
    rng = random.Random(bench.rng.random())
    pairs = corner_pairs(rng, bench.wa, bench.wb) + random_pairs(rng, bench.wa, bench.wb, 1500 * config.SCALE)
    rng.shuffle(pairs)
    await bench.run(pairs, "stream idle=True")


# PIPELINE 2 at every tree depth: LV = 2 (4x3), 3 (6x6), 4 (9x9, and 10x10,
# a 9/9 cascade lane's), 5 (17x17); they place their registers differently.
LUT_WIDTHS = [(2, 2, 0), (2, 2, 1), (3, 9, 0), (9, 3, 1), (8, 8, 0), (9, 9, 1), (7, 7, 1), (17, 17, 0),
              (4, 3, 2), (6, 6, 2), (9, 9, 2), (10, 10, 2), (17, 17, 2)]


@pytest.mark.parametrize("wa,wb,pipeline", LUT_WIDTHS, ids=[f"{a}x{b}_p{p}" for a, b, p in LUT_WIDTHS])
def test_pluecker_mul_lut(wa: int, wb: int, pipeline: int) -> None:
    from pluecker_tb import ecp5 as e5
    from pluecker_tb.runner import Build, rtl_sources

    b = Build(f"pluecker_mul_lut_{wa}x{wb}_p{pipeline}").build(
        sources=[*rtl_sources(), e5.HDL / "mul_stream.sv"], hdl_toplevel="mul_stream",
        parameters={"WA": wa, "WB": wb, "PIPELINE": pipeline, "LUT": 1})
    cases = ["exhaustive", "stream"] if wa + wb <= EXHAUSTIVE_MAX_BITS else ["stream"]
    assert b.test("test_pluecker_mul_lut", testcase=cases) == len(cases)
