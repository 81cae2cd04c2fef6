# SPDX-License-Identifier: MIT
"""cocotb bench of rtl/pluecker_local_child.sv, the local unit's child
datapath: hit_o equals local_hit of the model, after exactly the latency
the module documents (4 + MUL_ADD edges; see
pluecker_tb/hdl/local_child_stream.sv).

Each build runs `stream` for the node rays of the unit's stimulus sources
(local_node_ray of box chains, extreme and set-up families, a render's
traversal, with their boxes), for node rays with every field drawn from
its port range (raw_node: any DIR up to 2^D - 1, any W, ORG and END, also
beyond what the node set-up gives, any box, also LO > HI) and for boundary
vectors (one edge test exactly at -1, 0 or 1), with and without idle gaps.
PLUECKER_LONG=1: 25x the vectors and more configurations.
"""

from __future__ import annotations

import pytest

from pluecker_tb import config

try:
    import cocotb

    from pluecker_tb.local_parts import CHILD_INPUTS, CHILD_OUTPUTS, PartBench, child_vectors
except ImportError:  # pragma: no cover - only the pytest runner part is usable
    cocotb = None

if cocotb is not None:

    @cocotb.test()
    @cocotb.parametrize(source=["random", "extreme", "trace", "raw_node", "boundary"], idle=[False, True])
    async def stream(dut, source: str, idle: bool) -> None:
        """Every stimulus source, with or without idle gaps."""
        import pluecker_py as pp

        k, d = int(dut.BOX_BITS.value), int(dut.DIR_BITS.value)
        cons = bool(int(dut.CONSERVATIVE.value))
        mul = "auto" if int(dut.MUL_LUT.value) else "dsp"
        assert int(dut.ECP5.value) == int(cocotb.plusargs.get("pluecker_ecp5", "0")), "built on the wrong path"
        contract = pp.LocalPortContract(k, d, k + 2, 1, cons, mul, 1)
        assert int(dut.LATENCY.value) == contract.child_latency, (
            f"LATENCY {int(dut.LATENCY.value)}, port contract CHILD_LATENCY {contract.child_latency}")
        seed = config.seed("local_child", k, d, cons, source, idle)
        bench = PartBench(dut, seed, idle, CHILD_INPUTS, CHILD_OUTPUTS)
        await bench.start()
        # The grid of the node rays: the widest the RTL takes.
        fmt = pp.LocalFormat(k, d, pp.LocalPortContract.MAX_GRID_BITS, "conservative" if cons else "nearest")
        vectors, origin = child_vectors(source, fmt, seed, 400 * config.SCALE)
        dut._log.info("stimulus: %s, %d vectors, %d hits", origin, len(vectors),
                      sum(v.expect["hit_o"] for v in vectors))
        assert vectors, "no stimulus"
        await bench.run(vectors, f"stream {source} idle={idle}")


# (BOX_BITS, DIR_BITS, CONSERVATIVE, path): lut = pluecker_mul_lut (the
# default "auto" style), generic = pluecker_mul's `*`, ecp5 = MULT18X18D
# blocks (the DIR operand split from DIR_BITS 18).
SHORT = [
    (8, 11, 1, "lut"),
    (4, 24, 0, "lut"),
]
# PLUECKER_LONG=1 (make sim-regress): also these.
LONG_ONLY = [
    (16, 19, 1, "ecp5"),
    (4, 7, 1, "lut"),
    (12, 15, 1, "generic"),
    (16, 4, 0, "lut"),
    (16, 24, 1, "ecp5"),
    (8, 11, 0, "ecp5"),
]
CONFIGS = SHORT + LONG_ONLY if config.LONG else SHORT


@pytest.mark.parametrize("box_bits,dir_bits,conservative,path", CONFIGS,
                         ids=[f"k{k}_d{d}_{'cons' if c else 'near'}_{p}" for k, d, c, p in CONFIGS])
def test_pluecker_local_child(box_bits: int, dir_bits: int, conservative: int, path: str) -> None:
    from pluecker_tb import ecp5 as e5
    from pluecker_tb.runner import NO_SPLIT_ARGS, Build, need_model, rtl_sources

    need_model()
    params = {"BOX_BITS": box_bits, "DIR_BITS": dir_bits, "CONSERVATIVE": conservative,
              "MUL_LUT": int(path == "lut")}
    name = f"local_child_k{box_bits}_d{dir_bits}_{'cons' if conservative else 'near'}_{path}"
    sources = [*rtl_sources(), e5.HDL / "local_child_stream.sv"] + (e5.model_sources() if path == "ecp5" else [])
    b = Build(name).build(sources=sources, hdl_toplevel="local_child_stream", parameters=params,
                          defines={"PLUECKER_ECP5": 1} if path == "ecp5" else {}, build_args=NO_SPLIT_ARGS)
    b.test("test_pluecker_local_child", plusargs=[f"+pluecker_ecp5={int(path == 'ecp5')}"])
