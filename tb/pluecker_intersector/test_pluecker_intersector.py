# SPDX-License-Identifier: MIT
"""cocotb bench for rtl/pluecker_intersector.sv against the golden model.

Structure: driver -> model (pluecker_py, computed when the stimulus is
built) -> in-order scoreboard on the output handshake. Nothing assumes the
pipeline latency; results are matched by order and tag. Widths and mode are
read back from the DUT's parameters.

Tests (each cocotb test runs on every build of the pytest sweep below)
  stream      stimulus source x idle gaps x output stalls (cocotb.parametrize)
  reset       resets asserted in the middle of a stream: every query accepted
              before a reset must vanish, and out_valid_o stays low while in
              reset and right after it
  throughput  one query per clock without stalls, constant latency equal to
              the port contract's LATENCY, and in_ready_o dropping after
              exactly the contract's FIFO depth of queries while the output
              is blocked; the DUT's LATENCY and FIFO_DEPTH localparams and
              its port widths must be the contract's (pluecker_py.PortContract,
              computed from the DUT's parameters alone)

Environment
  PLUECKER_TRACE   query file (`pluecker trace` output) for the 'trace' source
  PLUECKER_TRACE_LIMIT  queries taken from its start per test (default: as
                   many as the other sources use; 0 = the whole file)
  PLUECKER_LONG=1  about 25x more queries per test, and every width pair in
                   both modes
  PLUECKER_TB_QUERIES  factor on the queries per test of one build (set by
                   the pytest side: 1 for the first configurations, less for
                   the added ones; see CONFIGS)
  PLUECKER_SEED, PLUECKER_PY_DIR, PLUECKER_TB_BUILD, PLUECKER_RTL_DIR: see
                   tb/pluecker_tb/config.py and tb/conftest.py
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

import pytest

from pluecker_tb import config
from pluecker_tb.intersector import TOPLEVEL

LONG = config.LONG
SCALE = config.SCALE
# The configuration's factor on the stream and reset tests' queries.
QUERIES = float(os.environ.get("PLUECKER_TB_QUERIES", "1"))
_seed = config.seed

try:
    import cocotb

    from pluecker_tb import bench as unit_tests
    from pluecker_tb.intersector import IntersectorBench as Bench
    from pluecker_tb.intersector import stimulus as _stimulus
except ImportError:  # pragma: no cover - only the pytest runner part is usable
    cocotb = None


def _n(base: int) -> int:
    """Queries of a stream or reset test: base x SCALE x QUERIES, at least 50."""
    return max(50, int(base * SCALE * QUERIES))


# ---------------------------------------------------------------------------
# cocotb side (the bench itself: pluecker_tb.intersector)
# ---------------------------------------------------------------------------

if cocotb is not None:

    @cocotb.test()
    @cocotb.parametrize(
        source=["random", "extreme", "raw", "boundary", "setup", "trace"],
        idle=[False, True],
        backpressure=[False, True],
    )
    async def stream(dut, source: str, idle: bool, backpressure: bool) -> None:
        """Every stimulus source (see pluecker_tb.vectors) under idle gaps and stalls."""
        bench = Bench(dut, _seed("stream", source, idle, backpressure), idle, backpressure)
        await bench.start()
        vectors = _stimulus(bench, source, _n(1000), (idle, backpressure))
        await bench.drive(vectors)
        await bench.drain()
        assert bench.compared == len(vectors), f"compared {bench.compared} of {len(vectors)}"
        bench.finish(f"stream {source}")

    @cocotb.test()
    async def ternary_answers(dut) -> None:
        """TERNARY builds (the others only log): out_hit_o and out_strict_o
        against fixed_hit and fixed_strict_hit on random and set-up queries
        in which all three answers occur (every test of this module compares
        both bits on a TERNARY build)."""
        bench = Bench(dut, _seed("ternary"), idle=True, backpressure=True)
        if not bench.ternary:
            dut._log.info("TERNARY = 0: out_strict_o is not built")
            return
        await bench.start()
        vectors = _stimulus(bench, "random", _n(2000), "ternary") + _stimulus(bench, "setup", _n(1000), "ternary")
        answers = {a: sum(1 for v in vectors if v.hit == a) for a in (0, 1, 2, 3)}
        assert answers[1] == 0, "the model has a strict hit that fails the conservative test"
        assert answers[0] and answers[2] and answers[3], f"not every ternary answer occurs: {answers}"
        await bench.drive(vectors)
        await bench.drain()
        assert bench.compared == len(vectors), f"compared {bench.compared} of {len(vectors)}"
        bench.finish(f"ternary (certain miss/uncertain/certain hit: {answers[0]}/{answers[2]}/{answers[3]})")

    @cocotb.test()
    async def reset_mid_stream(dut) -> None:
        """Resets in the middle of a stream drop everything in flight."""
        bench = Bench(dut, _seed("reset"), idle=True, backpressure=True)
        await bench.start()
        vectors = _stimulus(bench, "random", _n(3000), "reset")
        resets = await unit_tests.reset_mid_stream(bench, vectors)
        bench.finish(f"reset ({resets} resets)")

    @cocotb.test()
    async def throughput(dut) -> None:
        """One query per clock, the contract's latency, credits stop the input."""
        import pluecker_py as pp

        bench = Bench(dut, _seed("throughput"))
        await bench.start()
        # The expected LATENCY and FIFO depth: the port contract's for the
        # DUT's parameters, computed independently of the DUT's localparams,
        # which must agree with it.
        contract = pp.PortContract(bench.coord_bits, bench.dir_bits, bench.tag_bits, bench.conservative,
                                   os.environ.get("PLUECKER_TB_MUL_STYLE", "auto"), int(dut.PIPELINE.value))
        latency, depth = contract.latency, contract.fifo_depth
        dut_values = (int(dut.LATENCY.value), int(dut.FIFO_DEPTH.value))
        assert dut_values == (latency, depth), (
            f"DUT LATENCY, FIFO_DEPTH = {dut_values}, port contract {(latency, depth)} ({contract!r})")
        for port in contract.ports:
            assert len(getattr(dut, port.name)) == port.width, (
                f"{port.name}: {len(getattr(dut, port.name))} bits, port contract {port.width}")

        # Phase 1: never stalled, so one query is taken every clock.
        # PLUECKER_BENCH_N sets its length and PLUECKER_BENCH_JSON a file for
        # the wall-clock rate (scripts/cocotb_bench.py, `make bench`).
        n_bench = int(os.environ.get("PLUECKER_BENCH_N", "0")) or 300 * SCALE
        vectors = _stimulus(bench, "random", n_bench, "throughput")
        start = time.perf_counter()
        await unit_tests.full_rate(bench, vectors, latency)
        seconds = time.perf_counter() - start
        n = len(vectors)
        dut._log.info("cocotb throughput: %d queries in %.3f s wall = %.0f queries/s "
                      "(driver, sink and scoreboard included)", n, seconds, n / seconds)
        if os.environ.get("PLUECKER_BENCH_JSON"):
            Path(os.environ["PLUECKER_BENCH_JSON"]).write_text(json.dumps(
                {"queries": n, "seconds": seconds, "queries_per_second": n / seconds,
                 "coord_bits": bench.coord_bits, "dir_bits": bench.dir_bits}) + "\n")

        # Phase 2: output blocked; exactly FIFO_DEPTH queries get in.
        more = _stimulus(bench, "extreme", depth + 16, "credits")
        await unit_tests.credits_stop_input(bench, more, latency, depth)
        bench.finish(f"throughput (LATENCY {latency}, FIFO_DEPTH {depth})")


# ---------------------------------------------------------------------------
# pytest side: one Verilator build per parameter set
# ---------------------------------------------------------------------------

# Multiplier styles: "auto" (the RTL's default: fabric when both widths are
# at most 9 bits, else pluecker_mul, whose generic `*` path Verilator
# simulates), "lut" (MUL_STYLE "lut"), and "dsp-ecp5": MUL_STYLE "dsp" with
# PLUECKER_ECP5 defined, i.e. the MULT18X18D blocks of the FPGA build
# (simulated with the model in tb/pluecker_tb/hdl/, see pluecker_tb.ecp5),
# one per product up to 17 bits, split into partial products above; at
# 6/6 with PIPELINE = 2 one per difference for both its products
# (rtl/pluecker_mul_pair.sv); "rom": MUL_STYLE "rom" (6/6, PIPELINE = 2:
# every product from a block-RAM table, rtl/pluecker_mul_rom.sv) on its
# generic path, "rom-ecp5" the same with PLUECKER_ECP5 defined, i.e. the
# DP16KD instances of the FPGA build (the model in tb/pluecker_tb/hdl/).
#
# (COORD_BITS, DIR_BITS, CONSERVATIVE, style, PIPELINE, queries): LATENCY =
# 6 + MUL_ADD + PIPELINE,
# MUL_ADD = (COORD_BITS >= 18) + (DIR_BITS >= 18) (rtl/pluecker_intersector.sv).
# The first five have the full query counts; the others a quarter of them.
SHORT = [
    (6, 6, 1, "auto", 0, 1.0),        # LATENCY 6, fabric multipliers
    (10, 12, 1, "auto", 0, 1.0),      # LATENCY 6
    (16, 16, 1, "auto", 0, 1.0),      # LATENCY 6, the default widths
    (16, 16, 0, "auto", 0, 1.0),      # LATENCY 6, nearest
    (24, 24, 1, "auto", 0, 1.0),      # LATENCY 8
    (6, 6, 1, "auto", 1, 0.25),       # LATENCY 7: PIPELINE = 1, the multipliers' extra register
    (8, 8, 0, "auto", 0, 0.25),       # LATENCY 6, nearest at a narrow width, fabric multipliers
    (20, 8, 1, "dsp-ecp5", 0, 0.25),  # LATENCY 7 (COORD_BITS >= 18): DSP, the coordinate operand split
    (7, 22, 1, "auto", 0, 0.25),      # LATENCY 7 (DIR_BITS >= 18)
    (16, 16, 1, "dsp-ecp5", 0, 0.25),  # LATENCY 6, one MULT18X18D per product
    (24, 24, 0, "dsp-ecp5", 0, 0.25),  # LATENCY 8, nearest at a wide width, DSP with both operands split
    (16, 16, 1, "dsp-ecp5", 2, 0.25),  # LATENCY 8: PIPELINE = 2, a fabric register after every MULT18X18D
    (8, 8, 1, "auto", 2, 0.25),       # LATENCY 8: PIPELINE = 2 in fabric (registers spread over the tree, DIR_COPIES)
    (6, 6, 1, "dsp-ecp5", 2, 0.25),   # LATENCY 8: PIPELINE = 2, two products per MULT18X18D (paired)
    (6, 6, 1, "rom-ecp5", 2, 0.25),   # LATENCY 8: every product from a DP16KD table
    (6, 6, 0, "rom", 2, 0.25),        # LATENCY 8: the same tables on the generic path, nearest
]
# PLUECKER_LONG=1: every width pair above in both modes with the default
# multipliers, and the other builds, all at the full (25x) query counts.
_WIDTHS = [(6, 6), (8, 8), (10, 12), (16, 16), (20, 8), (7, 22), (24, 24)]
LONG_CONFIGS = ([(c, d, cons, "auto", 0, 1.0) for c, d in _WIDTHS for cons in (1, 0)]
                + [(c, d, cons, m, pipe, 1.0) for c, d, cons, m, pipe, _ in SHORT if m != "auto" or pipe])
CONFIGS = LONG_CONFIGS if LONG else SHORT


def _name(c: int, d: int, cons: int, mul: str, pipe: int) -> str:
    return (f"c{c}_d{d}{f'_p{pipe}' if pipe else ''}_{'cons' if cons else 'near'}"
            + ("" if mul == "auto" else f"_{mul}"))


@pytest.mark.parametrize("coord_bits,dir_bits,conservative,mul,pipeline,queries", CONFIGS,
                         ids=[_name(*k[:5]) for k in CONFIGS])
def test_pluecker_intersector(coord_bits: int, dir_bits: int, conservative: int, mul: str, pipeline: int,
                              queries: float) -> None:
    from pluecker_tb import ecp5
    from pluecker_tb.runner import VERILATOR_RTL_ARGS, Build, need_model, rtl_sources, verilator_plusargs

    need_model()
    name = _name(coord_bits, dir_bits, conservative, mul, pipeline)
    parameters = {"COORD_BITS": coord_bits, "DIR_BITS": dir_bits, "TAG_BITS": 16, "CONSERVATIVE": conservative,
                  "PIPELINE": pipeline}
    sources, defines = rtl_sources(), {"ASSERT_ON": 1}
    style = mul.removesuffix("-ecp5")
    if style != "auto":
        parameters["MUL_STYLE"] = f'"{style}"'
    if mul.endswith("-ecp5"):
        sources += ecp5.model_sources()
        defines["PLUECKER_ECP5"] = 1
    build = Build(name).build(sources=sources, hdl_toplevel=TOPLEVEL, parameters=parameters, defines=defines,
                              build_args=VERILATOR_RTL_ARGS)
    if mul == "rom-ecp5":
        # pluecker_mul_rom's DP16KD instances (u_block) are in the model.
        assert (any(build.dir.glob("Vtop_DP16KD*.h"))
                or any(b"u_block__" in h.read_bytes() for h in build.dir.glob("Vtop*.h"))), \
            "the build has no DP16KD: not the block-RAM path"
    if mul == "dsp-ecp5":
        # pluecker_mul's MULT18X18D instances (u_mult) are in the model
        # Verilator made: a module of their own (Vtop_MULT18X18D*.h) or
        # inlined into pluecker_mul (signals named u_mult__...).
        assert (any(build.dir.glob("Vtop_MULT18X18D*.h"))
                or any(b"u_mult__" in h.read_bytes() for h in build.dir.glob("Vtop*.h"))), \
            "the build has no MULT18X18D: not the DSP path"
    build.test("test_pluecker_intersector", plusargs=verilator_plusargs(_seed(name)),
               extra_env={"PLUECKER_TB_QUERIES": str(queries), "PLUECKER_TB_MUL_STYLE": style})


# TERNARY = 1 (out_strict_o: the strict test of ternary.hpp): fabric
# multipliers at a narrow width, the MULT18X18D model at 16/16 with the
# multipliers' extra register, and the widest format (both products split).
TERNARY_CONFIGS = [(8, 8, "auto", 0), (16, 16, "dsp-ecp5", 1), (24, 24, "auto", 0), (6, 6, "rom-ecp5", 2)]


@pytest.mark.parametrize("coord_bits,dir_bits,mul,pipeline", TERNARY_CONFIGS,
                         ids=[f"c{c}_d{d}_ternary{f'_p{p}' if p else ''}_{m}" for c, d, m, p in TERNARY_CONFIGS])
def test_pluecker_intersector_ternary(coord_bits: int, dir_bits: int, mul: str, pipeline: int) -> None:
    from pluecker_tb import ecp5
    from pluecker_tb.runner import VERILATOR_RTL_ARGS, Build, need_model, rtl_sources, verilator_plusargs

    need_model()
    name = f"c{coord_bits}_d{dir_bits}{f'_p{pipeline}' if pipeline else ''}_ternary_{mul}"
    parameters = {"COORD_BITS": coord_bits, "DIR_BITS": dir_bits, "TAG_BITS": 16, "CONSERVATIVE": 1,
                  "PIPELINE": pipeline, "TERNARY": 1}
    sources, defines = rtl_sources(), {"ASSERT_ON": 1}
    style = mul.removesuffix("-ecp5")
    if mul.endswith("-ecp5"):
        parameters["MUL_STYLE"] = f'"{style}"'
        sources += ecp5.model_sources()
        defines["PLUECKER_ECP5"] = 1
    build = Build(name).build(sources=sources, hdl_toplevel=TOPLEVEL, parameters=parameters, defines=defines,
                              build_args=VERILATOR_RTL_ARGS)
    build.test("test_pluecker_intersector", plusargs=verilator_plusargs(_seed(name)),
               extra_env={"PLUECKER_TB_QUERIES": "0.25", "PLUECKER_TB_MUL_STYLE": style})
