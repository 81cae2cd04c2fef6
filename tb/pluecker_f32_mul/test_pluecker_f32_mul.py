# SPDX-License-Identifier: MIT
"""cocotb bench of rtl/pluecker_f32_mul.sv: every product equals the golden
model's (pluecker_py.f32_mul, f32unit.hpp) bit for bit, exactly LATENCY
edges after its operands (pluecker_tb.f32_ops operand sets). Builds: the
generic multiplier path rounded to nearest, and the ECP5 path
(PLUECKER_ECP5, the MULT18X18D model of pluecker_tb/hdl) with MUL_DSP 1, 3
and 4 in the three rounding modes. PLUECKER_LONG=1: 25x the random pairs.
"""

from __future__ import annotations

import random

import pytest

from pluecker_tb import config

try:
    import cocotb

    from pluecker_tb.f32_ops import ROUND_NAMES, operand_pairs, run_pairs
except ImportError:  # pragma: no cover - only the pytest runner part is usable
    cocotb = None

if cocotb is not None:

    @cocotb.test()
    async def operations(dut) -> None:
        """Special, random, near and tiny operand pairs, one per clock."""
        import pluecker_py as pp

        rnd, dsp = int(dut.ROUND.value), int(dut.MUL_DSP.value)
        name = ROUND_NAMES[rnd]
        rng = random.Random(config.seed("pluecker_f32_mul", rnd, dsp))
        await run_pairs(dut, dut.p_o, operand_pairs(rng, 6000 * config.SCALE), lambda a, b: pp.f32_mul(a, b, name),
                        pp.FloatPortContract.MUL_LATENCY, f"mul {name} MUL_DSP {dsp}")


# (ROUND, MUL_DSP, ECP5 path)
CONFIGS = [(0, 4, False), (0, 1, True), (1, 3, True), (2, 4, True)]


@pytest.mark.parametrize("rnd,dsp,ecp5", CONFIGS, ids=[f"round{r}_dsp{d}{'_ecp5' if e else ''}" for r, d, e in CONFIGS])
def test_pluecker_f32_mul(rnd: int, dsp: int, ecp5: bool) -> None:
    from pluecker_tb import ecp5 as e5
    from pluecker_tb.runner import Build, need_model, rtl_sources

    need_model()
    sources = rtl_sources() + (e5.model_sources() if ecp5 else [])
    b = Build(f"pluecker_f32_mul_round{rnd}_dsp{dsp}{'_ecp5' if ecp5 else ''}").build(
        sources=sources, hdl_toplevel="pluecker_f32_mul", parameters={"ROUND": rnd, "MUL_DSP": dsp},
        defines={"PLUECKER_ECP5": 1} if ecp5 else {})
    b.test("test_pluecker_f32_mul")
