# SPDX-License-Identifier: MIT
"""cocotb bench for rtl/pluecker_rst_chain.sv (one chain of a reset tree).

Tests
  delay   rst_o starts high (simulation: the chain starts in reset) and,
          under a seeded random rst_i (runs of 1 to 12 clocks at each
          level), equals rst_i of STAGES clocks before at every edge
          (STAGES = 0: the same clock)
"""

from __future__ import annotations

import random

import pytest

from pluecker_tb import config

try:
    import cocotb
    from cocotb.clock import Clock
    from cocotb.triggers import FallingEdge, RisingEdge
except ImportError:  # pragma: no cover - only the pytest runner part is usable
    cocotb = None

TOPLEVEL = "pluecker_rst_chain"
CLOCK_NS = 10
_seed = config.seed


if cocotb is not None:

    @cocotb.test()
    async def delay(dut):
        stages = int(dut.STAGES.value)
        rng = random.Random(_seed())
        dut.rst_i.value = 0
        Clock(dut.clk_i, CLOCK_NS, unit="ns").start()
        await RisingEdge(dut.clk_i)
        # applied[k]: rst_i at rising edge k (edge 1 is the first).
        applied = [None, 0]
        level, run = 0, 0
        for edge in range(1, 400):
            await FallingEdge(dut.clk_i)  # after edge `edge`, rst_i unchanged
            if stages == 0:
                want = applied[edge]  # a wire
            else:  # the last flop holds rst_i of edge - stages + 1; before that, the start value 1
                k = edge - stages + 1
                want = applied[k] if k >= 1 else 1
            got = int(dut.rst_o.value)
            assert got == want, f"after edge {edge}: rst_o {got}, expected {want} ({stages} stages)"
            if run == 0:  # a new run of 1..12 clocks at the other level
                level, run = 1 - level, rng.randint(1, 12)
            run -= 1
            dut.rst_i.value = level
            applied.append(level)


# ---------------------------------------------------------------------------
# pytest side
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("stages", [0, 1, 3, 8])
def test_pluecker_rst_chain(stages: int) -> None:
    from pluecker_tb.runner import VERILATOR_RTL_ARGS, Build

    Build(f"pluecker_rst_chain_s{stages}").build(
        sources=[config.RTL_DIR / "pluecker_rst_chain.sv"], hdl_toplevel=TOPLEVEL,
        parameters={"STAGES": stages}, build_args=VERILATOR_RTL_ARGS).test("test_pluecker_rst_chain")
