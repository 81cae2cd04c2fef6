# SPDX-License-Identifier: MIT
"""cocotb bench of rtl/pluecker_float_intersector.sv (the binary32 Plücker
test) against the golden model, f32_pluecker_hit of f32unit.hpp.

Driver -> model (pluecker_py) -> in-order scoreboard on the output
handshake, nothing assuming the pipeline latency. The cocotb tests are
pluecker_tb.float_units' (shared with the slab unit): every stimulus source
(random, extreme families, full port range with NaN/inf/subnormal/signed
zero patterns, operands around 2^-126, a query file) crossed with idle gaps
and output stalls, resets in the middle of a stream, and one query per
clock at the port contract's LATENCY and FIFO depth.

Builds: round to nearest (CONSERVATIVE = 0) and the conservative variant
on the generic multiplier path (MUL_DSP 4; the significand product's DSP
and fabric paths are checked bit for bit by tb/pluecker_f32_mul).
PLUECKER_LONG=1 (make sim-regress): 25x the queries, and the ECP5 DSP path
(PLUECKER_ECP5, the MULT18X18D model of pluecker_tb/hdl) inside the unit at
MUL_DSP 1 and 3 (each such Verilator build takes about ten minutes).
"""

from __future__ import annotations

import pytest

from pluecker_tb import config
from pluecker_tb.float_units import FLOAT_TOP

try:  # the cocotb tests, found by the runner in this module's namespace
    from pluecker_tb.float_units import reset_mid_stream, stream, throughput  # noqa: F401
except ImportError:  # pragma: no cover - only the pytest runner part is usable
    pass

# (CONSERVATIVE, MUL_DSP, ECP5 path, queries factor)
SHORT = [(0, 4, False, 1.0), (1, 4, False, 0.5)]
LONG_CONFIGS = [(0, 4, False, 1.0), (1, 4, False, 1.0), (0, 1, True, 0.25), (1, 3, True, 0.25)]
CONFIGS = LONG_CONFIGS if config.LONG else SHORT


def _name(cons: int, mul_dsp: int, ecp5: bool) -> str:
    return f"{'cons' if cons else 'near'}_dsp{mul_dsp}{'_ecp5' if ecp5 else ''}"


@pytest.mark.parametrize("conservative,mul_dsp,ecp5,queries", CONFIGS, ids=[_name(*c[:3]) for c in CONFIGS])
def test_pluecker_float_intersector(conservative: int, mul_dsp: int, ecp5: bool, queries: float) -> None:
    from pluecker_tb.runner import need_model
    from pluecker_tb.float_build import build_and_test

    need_model()
    build_and_test(FLOAT_TOP, "test_pluecker_float_intersector", _name(conservative, mul_dsp, ecp5),
                   {"TAG_BITS": 16, "CONSERVATIVE": conservative, "MUL_DSP": mul_dsp}, ecp5, queries)
