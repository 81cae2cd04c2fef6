# SPDX-License-Identifier: MIT
"""cocotb bench of rtl/pluecker_f32_add.sv: every sum or difference equals
the golden model's (pluecker_py.f32_add / f32_sub, f32unit.hpp) bit for
bit, exactly LATENCY edges after its operands (pluecker_tb.f32_ops: special
patterns crossed, random patterns over every exponent, near pairs,
operands around 2^-126). Builds: subtraction rounded to nearest, up and
down, and addition rounded up. PLUECKER_LONG=1: 25x the random pairs.
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

        sub, rnd = int(dut.SUB.value), int(dut.ROUND.value)
        name = ROUND_NAMES[rnd]
        op = pp.f32_sub if sub else pp.f32_add
        rng = random.Random(config.seed("pluecker_f32_add", sub, rnd))
        await run_pairs(dut, dut.s_o, operand_pairs(rng, 6000 * config.SCALE), lambda a, b: op(a, b, name),
                        pp.FloatPortContract.ADD_LATENCY, f"{'sub' if sub else 'add'} {name}")


CONFIGS = [(1, 0), (1, 1), (1, 2), (0, 1)]


@pytest.mark.parametrize("sub,rnd", CONFIGS, ids=[f"{'sub' if s else 'add'}_round{r}" for s, r in CONFIGS])
def test_pluecker_f32_add(sub: int, rnd: int) -> None:
    from pluecker_tb.runner import Build, need_model, rtl_sources

    need_model()
    b = Build(f"pluecker_f32_add_sub{sub}_round{rnd}").build(
        sources=rtl_sources(), hdl_toplevel="pluecker_f32_add", parameters={"SUB": sub, "ROUND": rnd})
    b.test("test_pluecker_f32_add")
