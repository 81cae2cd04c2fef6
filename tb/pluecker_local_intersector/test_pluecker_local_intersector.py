# SPDX-License-Identifier: MIT
"""cocotb bench for rtl/pluecker_local_intersector.sv against the golden model.

Structure: driver -> model (pluecker_py: local_node_ray and local_hit of
every child box, computed when the stimulus is built) -> in-order
scoreboard on the output handshake (pluecker_tb.bench). Nothing assumes
the pipeline latency; results are matched by order and tag. Widths, mode
and CHILDREN are read back from the DUT's parameters; the port contract of
those parameters (pluecker_py.LocalPortContract) packs the queries.

Tests (each cocotb test runs on every build of the pytest sweep below)
  stream      stimulus source (pluecker_tb.local_vectors: random box chains
              in tight and ancestor frames, extreme and set-up families in
              tight frames, raw port-range operands, a render's traversal)
              x idle gaps x output stalls (cocotb.parametrize)
  reset       resets asserted in the middle of a stream: every query accepted
              before a reset must vanish, and out_valid_o stays low while in
              reset and right after it
  throughput  one query per clock without stalls, constant latency equal to
              the port contract's LATENCY, and in_ready_o dropping after
              exactly the contract's FIFO depth of queries while the output
              is blocked; the DUT's LATENCY and FIFO_DEPTH localparams and
              its port widths must be the contract's

Environment
  PLUECKER_LONG=1  25x more queries per test and more configurations
  PLUECKER_TB_QUERIES  factor on the queries of one build (set by the pytest
                   side per configuration, see CONFIGS)
  PLUECKER_TB_MUL_STYLE  the MUL_STYLE the build was made with (the
                   contract's derived constants depend on it)
  PLUECKER_SEED, PLUECKER_PY_DIR, PLUECKER_TB_BUILD, PLUECKER_RTL_DIR: see
                   tb/pluecker_tb/config.py and tb/conftest.py
"""

from __future__ import annotations

import os

import pytest

from pluecker_tb import config
from pluecker_tb.local import TOPLEVEL

SCALE = config.SCALE
QUERIES = float(os.environ.get("PLUECKER_TB_QUERIES", "1"))
MUL_STYLE = os.environ.get("PLUECKER_TB_MUL_STYLE", "auto")
_seed = config.seed

try:
    import cocotb

    from pluecker_tb import bench as unit_tests
    from pluecker_tb.local import LocalBench
    from pluecker_tb.local import stimulus as _stimulus
except ImportError:  # pragma: no cover - only the pytest runner part is usable
    cocotb = None


def _n(base: int) -> int:
    """Queries of a stream or reset test: base x SCALE x QUERIES, at least 40."""
    return max(40, int(base * SCALE * QUERIES))


def _bench(dut, seed: int, idle: bool = False, backpressure: bool = False):
    return LocalBench(dut, seed, idle, backpressure, mul_style=MUL_STYLE)


# ---------------------------------------------------------------------------
# cocotb side
# ---------------------------------------------------------------------------

if cocotb is not None:

    @cocotb.test()
    @cocotb.parametrize(
        source=["random", "extreme", "setup", "raw", "edge", "trace"],
        idle=[False, True],
        backpressure=[False, True],
    )
    async def stream(dut, source: str, idle: bool, backpressure: bool) -> None:
        """Every stimulus source under idle gaps and stalls."""
        bench = _bench(dut, _seed("local stream", source, idle, backpressure), idle, backpressure)
        await bench.start()
        vectors = _stimulus(bench, source, _n(300), (idle, backpressure))
        await bench.drive(vectors)
        await bench.drain()
        assert bench.compared == len(vectors), f"compared {bench.compared} of {len(vectors)}"
        bench.finish(f"stream {source}")

    @cocotb.test()
    async def reset_mid_stream(dut) -> None:
        """Resets in the middle of a stream drop everything in flight."""
        bench = _bench(dut, _seed("local reset"), idle=True, backpressure=True)
        await bench.start()
        vectors = _stimulus(bench, "random", _n(1200), "reset")
        resets = await unit_tests.reset_mid_stream(bench, vectors)
        bench.finish(f"reset ({resets} resets)")

    @cocotb.test()
    async def throughput(dut) -> None:
        """One query per clock, the contract's latency, credits stop the input."""
        bench = _bench(dut, _seed("local throughput"))
        await bench.start()
        contract = bench.contract
        latency, depth = contract.latency, contract.fifo_depth
        dut_values = (int(dut.LATENCY.value), int(dut.FIFO_DEPTH.value))
        assert dut_values == (latency, depth), (
            f"DUT LATENCY, FIFO_DEPTH = {dut_values}, port contract {(latency, depth)} ({contract!r})")
        for port in contract.ports:
            assert len(getattr(dut, port.name)) == port.width, (
                f"{port.name}: {len(getattr(dut, port.name))} bits, port contract {port.width}")
        await unit_tests.full_rate(bench, _stimulus(bench, "random", 200 * SCALE, "throughput"), latency)
        more = _stimulus(bench, "extreme", depth + 16, "credits")
        await unit_tests.credits_stop_input(bench, more, latency, depth)
        bench.finish(f"throughput (LATENCY {latency}, FIFO_DEPTH {depth})")


# ---------------------------------------------------------------------------
# pytest side: one Verilator build per parameter set
# ---------------------------------------------------------------------------

# Multiplier styles: "auto" (the default: the node set-up's six moment
# products on pluecker_mul, whose generic `*` path Verilator simulates, the
# children's products in fabric), "lut" (everything in fabric) and
# "dsp-ecp5": MUL_STYLE "dsp" with PLUECKER_ECP5 defined, i.e. the
# MULT18X18D blocks of the FPGA build (the project's model of the cell,
# pluecker_tb/hdl/): the moment products split into four partial products
# from GRID_BITS 18 on, the children's from DIR_BITS 18.
#
# (BOX_BITS, DIR_BITS, GRID_BITS, CONSERVATIVE, CHILDREN, style, queries):
# LATENCY 14 + FRAME_MUL_ADD + CHILD_MUL_ADD (the port contract). K = 4, 8,
# 12, 16 with D = K + 3; D at both ends (24 and 4); G = K + 2 and the RTL's
# maximum 32; both modes; CHILDREN 1 and 2; the DSP path.
SHORT = [
    (8, 11, 32, 1, 1, "auto", 1.0),        # the defaults, LATENCY 16
    (4, 7, 6, 1, 1, "auto", 0.5),          # the smallest widths, G = K + 2, LATENCY 14
    (12, 15, 14, 0, 2, "auto", 0.5),       # a node (two children) per query, nearest, G = K + 2
]
# PLUECKER_LONG=1 (make sim-regress): also these, at the full (25x) counts.
LONG_ONLY = [
    (8, 11, 32, 1, 2, "auto", 1.0),        # two children at the default widths
    (16, 19, 32, 1, 2, "dsp-ecp5", 1.0),   # MULT18X18D: moment products split in four, DIR operand split (LATENCY 17)
    (4, 24, 32, 1, 1, "auto", 1.0),        # D at its maximum: the moment's left shift up to D - K + 1 = 21
    (16, 4, 18, 1, 1, "auto", 1.0),        # D below K: no left shift
    (8, 11, 20, 1, 1, "lut", 1.0),         # everything in fabric
    (12, 15, 32, 0, 1, "auto", 1.0),       # nearest at the maximum grid
    (8, 11, 16, 1, 2, "dsp-ecp5", 1.0),    # MULT18X18D, one operand split (FRAME_MUL_ADD 1)
]
CONFIGS = SHORT + LONG_ONLY if config.LONG else SHORT


def _name(k: int, d: int, g: int, cons: int, children: int, mul: str) -> str:
    return (f"k{k}_d{d}_g{g}_c{children}_{'cons' if cons else 'near'}" + ("" if mul == "auto" else f"_{mul}"))


@pytest.mark.parametrize("box_bits,dir_bits,grid_bits,conservative,children,mul,queries", CONFIGS,
                         ids=[_name(*k[:6]) for k in CONFIGS])
def test_pluecker_local_intersector(box_bits: int, dir_bits: int, grid_bits: int, conservative: int, children: int,
                                    mul: str, queries: float) -> None:
    from pluecker_tb import ecp5
    from pluecker_tb.runner import VERILATOR_RTL_ARGS, Build, need_model, rtl_sources, verilator_plusargs

    need_model()
    name = "local_" + _name(box_bits, dir_bits, grid_bits, conservative, children, mul)
    parameters = {"BOX_BITS": box_bits, "DIR_BITS": dir_bits, "GRID_BITS": grid_bits, "TAG_BITS": 12,
                  "CONSERVATIVE": conservative, "CHILDREN": children}
    sources, defines = rtl_sources(), {"ASSERT_ON": 1}
    if mul == "lut":
        parameters["MUL_STYLE"] = '"lut"'
    elif mul == "dsp-ecp5":
        parameters["MUL_STYLE"] = '"dsp"'
        sources += ecp5.model_sources()
        defines["PLUECKER_ECP5"] = 1
    build = Build(name).build(sources=sources, hdl_toplevel=TOPLEVEL, parameters=parameters, defines=defines,
                              build_args=VERILATOR_RTL_ARGS)
    if mul == "dsp-ecp5":
        assert (any(build.dir.glob("Vtop_MULT18X18D*.h"))
                or any(b"u_mult__" in h.read_bytes() for h in build.dir.glob("Vtop*.h"))), \
            "the build has no MULT18X18D: not the DSP path"
    build.test("test_pluecker_local_intersector", plusargs=verilator_plusargs(_seed(name)),
               extra_env={"PLUECKER_TB_QUERIES": str(queries),
                          "PLUECKER_TB_MUL_STYLE": {"auto": "auto", "lut": "lut", "dsp-ecp5": "dsp"}[mul]})
