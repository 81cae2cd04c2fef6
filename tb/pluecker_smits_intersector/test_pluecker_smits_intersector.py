# SPDX-License-Identifier: MIT
"""cocotb bench of rtl/pluecker_smits_intersector.sv (the binary32 slab
test) against the golden model, f32_smits_hit of f32unit.hpp.

The cocotb tests are pluecker_tb.float_units' (shared with the Plücker
unit): every stimulus source crossed with idle gaps and output stalls,
resets in the middle of a stream, and one query per clock at the port
contract's LATENCY and FIFO depth. Build: MUL_DSP 4 on the generic
multiplier path. PLUECKER_LONG=1 (make sim-regress): 25x the queries, and
MUL_DSP 1 on the ECP5 DSP path (PLUECKER_ECP5) too.
"""

from __future__ import annotations

import pytest

from pluecker_tb import config
from pluecker_tb.float_units import SMITS_TOP

try:  # the cocotb tests, found by the runner in this module's namespace
    from pluecker_tb.float_units import reset_mid_stream, stream, throughput  # noqa: F401
except ImportError:  # pragma: no cover - only the pytest runner part is usable
    pass

# (MUL_DSP, ECP5 path, queries factor)
SHORT = [(4, False, 1.0)]
LONG_CONFIGS = [(4, False, 1.0), (1, True, 0.25)]
CONFIGS = LONG_CONFIGS if config.LONG else SHORT


def _name(mul_dsp: int, ecp5: bool) -> str:
    return f"dsp{mul_dsp}{'_ecp5' if ecp5 else ''}"


@pytest.mark.parametrize("mul_dsp,ecp5,queries", CONFIGS, ids=[_name(*c[:2]) for c in CONFIGS])
def test_pluecker_smits_intersector(mul_dsp: int, ecp5: bool, queries: float) -> None:
    from pluecker_tb.runner import need_model
    from pluecker_tb.float_build import build_and_test

    need_model()
    build_and_test(SMITS_TOP, "test_pluecker_smits_intersector", _name(mul_dsp, ecp5),
                   {"TAG_BITS": 16, "MUL_DSP": mul_dsp}, ecp5, queries)
