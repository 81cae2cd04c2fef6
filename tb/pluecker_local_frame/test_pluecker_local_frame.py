# SPDX-License-Identifier: MIT
"""cocotb bench of rtl/pluecker_local_frame.sv, the local unit's per-node
set-up: every field of the node ray (class, DIR, the six W, ORG, END and
the end flag) equals local_node_ray of the model, after exactly the latency
the module documents (9 + MUL_ADD edges; see
pluecker_tb/hdl/local_frame_stream.sv).

Each build runs `stream` for every stimulus source of the unit
(pluecker_tb.local_vectors: box chains in tight and ancestor frames,
extreme and set-up families, raw port-range operands, a render's traversal)
with and without idle gaps; PLUECKER_LONG=1: 25x the vectors and more
configurations. Comparing the node ray itself sees what a final hit bit can
hide (a wrong W where an origin test already fails).
"""

from __future__ import annotations

import pytest

from pluecker_tb import config

try:
    import cocotb

    from pluecker_tb.local_parts import FRAME_INPUTS, FRAME_OUTPUTS, PartBench, frame_vectors
except ImportError:  # pragma: no cover - only the pytest runner part is usable
    cocotb = None

if cocotb is not None:

    @cocotb.test()
    @cocotb.parametrize(source=["random", "extreme", "setup", "raw", "trace"], idle=[False, True])
    async def stream(dut, source: str, idle: bool) -> None:
        """Every stimulus source, with or without idle gaps."""
        import pluecker_py as pp

        k, d, g = int(dut.BOX_BITS.value), int(dut.DIR_BITS.value), int(dut.GRID_BITS.value)
        cons = bool(int(dut.CONSERVATIVE.value))
        mul = "lut" if int(dut.MUL_LUT.value) else "dsp"
        assert int(dut.ECP5.value) == int(cocotb.plusargs.get("pluecker_ecp5", "0")), "built on the wrong path"
        contract = pp.LocalPortContract(k, d, g, 1, cons, mul, 1)
        assert int(dut.LATENCY.value) == contract.frame_latency, (
            f"LATENCY {int(dut.LATENCY.value)}, port contract FRAME_LATENCY {contract.frame_latency}")
        seed = config.seed("local_frame", k, d, g, cons, source, idle)
        bench = PartBench(dut, seed, idle, FRAME_INPUTS, FRAME_OUTPUTS)
        await bench.start()
        vectors, origin = frame_vectors(source, contract, seed, 250 * config.SCALE)
        dut._log.info("stimulus: %s, %d vectors", origin, len(vectors))
        assert vectors, "no stimulus"
        await bench.run(vectors, f"stream {source} idle={idle}")


# (BOX_BITS, DIR_BITS, GRID_BITS, CONSERVATIVE, path): generic = pluecker_mul's
# `*` (MUL_ADD as on ECP5, as delay), ecp5 = MULT18X18D blocks (the moment
# products' operands G+3 and G+1 split from 16 and 18 bits), lut = fabric.
SHORT = [
    (8, 11, 32, 1, "generic"),
    (4, 24, 32, 0, "generic"),   # D - K + 1 = 21: the moment's left shift at its widest; nearest
]
# PLUECKER_LONG=1 (make sim-regress): also these.
LONG_ONLY = [
    (16, 4, 18, 1, "ecp5"),      # D < K (no left shift); both operands split
    (4, 7, 6, 1, "generic"),
    (12, 15, 14, 0, "lut"),
    (16, 19, 32, 1, "ecp5"),
    (8, 11, 16, 1, "ecp5"),      # one operand split
    (10, 13, 17, 1, "generic"),
]
CONFIGS = SHORT + LONG_ONLY if config.LONG else SHORT


@pytest.mark.parametrize("box_bits,dir_bits,grid_bits,conservative,path", CONFIGS,
                         ids=[f"k{k}_d{d}_g{g}_{'cons' if c else 'near'}_{p}" for k, d, g, c, p in CONFIGS])
def test_pluecker_local_frame(box_bits: int, dir_bits: int, grid_bits: int, conservative: int, path: str) -> None:
    from pluecker_tb import ecp5 as e5
    from pluecker_tb.runner import NO_SPLIT_ARGS, Build, need_model, rtl_sources

    need_model()
    params = {"BOX_BITS": box_bits, "DIR_BITS": dir_bits, "GRID_BITS": grid_bits, "CONSERVATIVE": conservative,
              "MUL_LUT": int(path == "lut")}
    name = f"local_frame_k{box_bits}_d{dir_bits}_g{grid_bits}_{'cons' if conservative else 'near'}_{path}"
    sources = [*rtl_sources(), e5.HDL / "local_frame_stream.sv"] + (e5.model_sources() if path == "ecp5" else [])
    b = Build(name).build(sources=sources, hdl_toplevel="local_frame_stream", parameters=params,
                          defines={"PLUECKER_ECP5": 1} if path == "ecp5" else {}, build_args=NO_SPLIT_ARGS)
    b.test("test_pluecker_local_frame", plusargs=[f"+pluecker_ecp5={int(path == 'ecp5')}"])
