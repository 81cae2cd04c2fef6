# SPDX-License-Identifier: MIT
"""cocotb bench of rtl/pluecker_mul_rom.sv: the product a*b (a signed, b
unsigned) looked up in a block-RAM table, two halves of b through the
block's two read ports and one adder, equal to the exact product exactly 4
clock edges after the operands (bench top pluecker_tb/hdl/mul_rom_stream.sv,
bench pluecker_tb.multiplier.RomBench).

Paths
  ecp5     PLUECKER_ECP5 defined: one DP16KD instance, its INITVAL_00..3F
           built by the module (the project's model of the cell,
           pluecker_tb/hdl/DP16KD.v, checked against Yosys' own block-RAM
           mapping by tb/dp16kd/test_dp16kd.py)
  generic  the same table and registers in plain SystemVerilog

Operands: every (a, b) at the intersector's 7 x 6 (6/6 bits); at the other
widths the module allows (WA + ceil(WU/2) <= 10) the corner values of a
against every b (or b's corners and 256 at random), and random pairs; with
and without idle gaps. (scripts/lint.sh checks that wider operands are
refused at elaboration.)
"""

from __future__ import annotations

import cocotb
import pytest

from pluecker_tb import config
from pluecker_tb.multiplier import RomBench


@cocotb.test()
@cocotb.parametrize(idle=[False, True])
async def stream(dut, idle: bool) -> None:
    """Every or corner (a, b) pairs and random ones, with or without idle gaps."""
    bench = RomBench(dut, config.seed("pluecker_mul_rom", int(dut.WA.value), int(dut.WU.value), idle), idle)
    assert bench.ecp5 == int(cocotb.plusargs.get("pluecker_ecp5", "0")), "built on the wrong path"
    await bench.start()
    await bench.run(bench.pairs(1000 * config.SCALE), f"stream idle={idle}")


# (WA, WU): the intersector's 6/6 (C + 1 = 7 by D = 6), a narrow signed
# operand with the widest unsigned one, and the widest signed operand.
WIDTHS = [(7, 6), (4, 12), (9, 2)]


@pytest.mark.parametrize("ecp5", [True, False], ids=["ecp5", "generic"])
@pytest.mark.parametrize("wa,wu", WIDTHS, ids=[f"{a}x{u}" for a, u in WIDTHS])
def test_pluecker_mul_rom(wa: int, wu: int, ecp5: bool) -> None:
    from pluecker_tb import ecp5 as e5
    from pluecker_tb.runner import Build, rtl_sources

    name = f"pluecker_mul_rom_{'ecp5' if ecp5 else 'generic'}_{wa}x{wu}"
    sources = [*rtl_sources(), e5.HDL / "mul_rom_stream.sv"] + (e5.model_sources() if ecp5 else [])
    b = Build(name).build(sources=sources, hdl_toplevel="mul_rom_stream", parameters={"WA": wa, "WU": wu},
                          defines={"PLUECKER_ECP5": 1} if ecp5 else {})
    b.test("test_pluecker_mul_rom", plusargs=[f"+pluecker_ecp5={int(ecp5)}"])
