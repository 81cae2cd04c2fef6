# SPDX-License-Identifier: MIT
"""The binary32 units' bench (cocotb side): FloatUnitBench, the stream bench
(pluecker_tb.bench) around rtl/pluecker_float_intersector.sv (unit
"float") or rtl/pluecker_smits_intersector.sv (unit "smits"), their
stimulus, and the cocotb tests both units' bench files import.

Every expected answer comes from the golden model (pluecker_py:
f32_pluecker_hit, f32_smits_hit, the C++ of f32unit.hpp); every port value
from the port contract's packing (F32PlueckerQuery.ports(),
F32SmitsQuery.ports()). Nothing here computes a box test.

Stimulus sources
  random   pluecker_py.random_queries through the unit's ray set-up
  extreme  pluecker_py.extreme_queries (the extreme families)
  trace    a query file (PLUECKER_TRACE, else generated and read back)
  raw      bit patterns over the full port range: NaNs (quiet, signalling,
           negative), infinities, signed zeros, subnormals, 2^-126 and its
           neighbours, FLT_MAX, random patterns, values a few ulps from
           each other (cancellation) and lo > hi boxes; any class, end
           valid or not
  tiny     operands around 2^-126 and below (exponents 0..8), so that
           differences and products take the flushing paths
Tests (each runs on every build of a unit's pytest sweep)
  stream      source x idle gaps x output stalls
  reset_mid_stream  resets in the middle of a stream drop everything in flight
  throughput  one query per clock, latency = the port contract's LATENCY,
              in_ready_o dropping after exactly the contract's FIFO depth
              with the output blocked; the DUT's LATENCY and FIFO_DEPTH
              localparams and its port widths are the contract's
"""

from __future__ import annotations

import os
import random
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import cocotb

from . import config
from . import bench as unit_tests
from .bench import UnitBench

FLOAT_TOP = "pluecker_float_intersector"
SMITS_TOP = "pluecker_smits_intersector"
SOURCES = ["random", "extreme", "raw", "tiny", "trace"]


@dataclass
class Vector:
    """One query as driven into the DUT, with the model's answer."""

    ports: dict[str, int]
    hit: bool
    describe: Callable[[], str]  # called only for error messages


class FloatUnitBench(UnitBench):
    """The bench of one binary32 unit; the unit, TAG_BITS, CONSERVATIVE and
    MUL_DSP are read back from the DUT."""

    def __init__(self, dut, seed: int, idle: bool = False, backpressure: bool = False, traffic_gen=None):
        self.unit = "smits" if hasattr(dut, "ray_inv_i") else "float"
        self.conservative = self.unit == "float" and bool(int(dut.CONSERVATIVE.value))
        self.mul_dsp = int(dut.MUL_DSP.value)
        if self.unit == "float":
            self.PAYLOAD = ("ray_class_i", "ray_org_i", "ray_dir_i", "ray_end_i", "ray_end_valid_i", "box_min_i",
                            "box_max_i")
        else:
            self.PAYLOAD = ("ray_class_i", "ray_org_i", "ray_inv_i", "ray_tmax_i", "box_min_i", "box_max_i")
        super().__init__(dut, seed, idle, backpressure, traffic_gen)
        dut._log.info("DUT %s TAG_BITS=%d CONSERVATIVE=%d MUL_DSP=%d LATENCY=%s, seed %d, idle=%s backpressure=%s",
                      self.unit, self.tag_bits, self.conservative, self.mul_dsp, unit_tests.latency_text(dut), seed, idle,
                      backpressure)

    def contract(self):
        import pluecker_py as pp

        return pp.FloatPortContract(self.unit, self.tag_bits, self.conservative, self.mul_dsp)


# ---------------------------------------------------------------------------
# Stimulus
# ---------------------------------------------------------------------------

def _vector(bench: FloatUnitBench, q, what: Callable[[], str]) -> Vector:
    """A unit query (pp.F32PlueckerQuery or pp.F32SmitsQuery) with the model's answer."""
    import pluecker_py as pp

    hit = pp.f32_pluecker_hit(q, bench.conservative) if bench.unit == "float" else pp.f32_smits_hit(q)
    return Vector(q.ports(), hit, lambda: f"{what()}\n  {q}")


def from_queries(bench: FloatUnitBench, queries: list, origin: str) -> list[Vector]:
    """Float queries through the unit's ray set-up."""
    import pluecker_py as pp

    out = []
    for k, fq in enumerate(queries):
        q = pp.f32_pluecker_query(fq, bench.conservative) if bench.unit == "float" else pp.f32_smits_query(fq)
        out.append(_vector(bench, q, lambda fq=fq, k=k: f"{origin} query #{k}: {fq.line()}"))
    return out


SPECIALS = [0x00000000, 0x80000000, 0x00000001, 0x80000001, 0x007fffff, 0x807fffff, 0x00400000, 0x00800000,
            0x80800000, 0x00800001, 0x00ffffff, 0x3f800000, 0xbf800000, 0x3f7fffff, 0x7f7fffff, 0xff7fffff,
            0x7f800000, 0xff800000, 0x7fc00000, 0xffc00000, 0x7f800001, 0x7fbfffff, 0xffffffff]


def _pattern(rng: random.Random, near: int | None, tiny: bool) -> int:
    """One 32-bit field: a special value, a neighbour of `near`, a random
    pattern or a moderate value (tiny: exponents 0..8 only)."""
    r = rng.random()
    if tiny:
        if r < 0.15:
            return rng.choice(SPECIALS[:11])
        if near is not None and r < 0.5:
            return (near + rng.randint(-3, 3)) & 0xffffffff
        return (rng.getrandbits(1) << 31) | (rng.randint(0, 8) << 23) | rng.getrandbits(23)
    if r < 0.25:
        return rng.choice(SPECIALS)
    if near is not None and r < 0.45:
        return (near + rng.randint(-4, 4)) & 0xffffffff
    if r < 0.6:
        return rng.getrandbits(32)
    return (rng.getrandbits(1) << 31) | (rng.randint(110, 130) << 23) | rng.getrandbits(23)


def raw_vectors(bench: FloatUnitBench, seed: int, n: int, tiny: bool = False) -> list[Vector]:
    """Bit patterns over the whole port range (see the module doc)."""
    import pluecker_py as pp

    rng = random.Random(seed)
    out = []
    for k in range(n):
        o = [_pattern(rng, None, tiny) for _ in range(3)]
        lo = [_pattern(rng, o[a], tiny) for a in range(3)]
        hi = [_pattern(rng, lo[a] if rng.random() < 0.5 else o[a], tiny) for a in range(3)]
        cls = rng.randrange(8)
        what = (lambda k=k: f"{'tiny' if tiny else 'raw'} vector {k} (seed {seed})")
        if bench.unit == "float":
            d = [_pattern(rng, None, tiny) for _ in range(3)]
            end = [_pattern(rng, hi[a] if rng.random() < 0.5 else lo[a], tiny) for a in range(3)]
            q = pp.F32PlueckerQuery(cls, o, d, end, rng.random() < 0.5, lo, hi)
        else:
            inv = [_pattern(rng, None, tiny) for _ in range(3)]
            q = pp.F32SmitsQuery(cls, o, inv, _pattern(rng, None, tiny), lo, hi)
        out.append(_vector(bench, q, what))
    return out


def trace_queries(seed: int, n: int, work_dir: Path) -> tuple[list, str]:
    """The first PLUECKER_TRACE_LIMIT (default n, 0 = all) queries of the
    PLUECKER_TRACE file, else n generated queries written to a query file in
    work_dir and read back."""
    import pluecker_py as pp

    path = os.environ.get("PLUECKER_TRACE")
    if path:
        limit = int(os.environ.get("PLUECKER_TRACE_LIMIT", str(n)))
        qs = pp.read_queries_file(path)
        return (qs[:limit] if limit > 0 else qs), f"trace {path}"
    qs = pp.random_queries(seed, n // 2) + pp.extreme_queries(seed + 1, n - n // 2)
    work_dir.mkdir(parents=True, exist_ok=True)
    gen = work_dir / f"generated_trace_{seed}.txt"
    gen.write_text("".join(q.line() + "\n" for q in qs))
    return pp.read_queries_file(str(gen)), f"generated trace {gen}"


def stimulus(bench: FloatUnitBench, source: str, n: int, salt: object) -> list[Vector]:
    import pluecker_py as pp

    seed = config.seed(source, salt, bench.unit, bench.conservative)
    if source == "random":
        vecs = from_queries(bench, pp.random_queries(seed, n), f"random_queries(seed={seed}, n={n})")
    elif source == "extreme":
        vecs = from_queries(bench, pp.extreme_queries(seed, n), f"extreme_queries(seed={seed}, n={n})")
    elif source == "trace":
        qs, origin = trace_queries(seed, n, Path(os.environ.get("PLUECKER_TB_WORK", ".")))
        vecs = from_queries(bench, qs, origin)
    elif source in ("raw", "tiny"):
        vecs = raw_vectors(bench, seed, n, tiny=source == "tiny")
    else:
        raise ValueError(f"unknown stimulus source {source!r}")
    bench.dut._log.info("stimulus: %s, %d vectors (%d hits)", source, len(vecs), sum(v.hit for v in vecs))
    assert vecs, "no stimulus"
    return vecs


# ---------------------------------------------------------------------------
# The cocotb tests (imported by tb/<unit>/test_<unit>.py)
# ---------------------------------------------------------------------------

QUERIES = float(os.environ.get("PLUECKER_TB_QUERIES", "1"))


def _n(base: int) -> int:
    """Queries of a stream or reset test: base x SCALE x QUERIES, at least 50."""
    return max(50, int(base * config.SCALE * QUERIES))


@cocotb.test()
@cocotb.parametrize(source=SOURCES, idle=[False, True], backpressure=[False, True])
async def stream(dut, source: str, idle: bool, backpressure: bool) -> None:
    """Every stimulus source under idle gaps and stalls."""
    bench = FloatUnitBench(dut, config.seed("stream", source, idle, backpressure), idle, backpressure)
    await bench.start()
    vectors = stimulus(bench, source, _n(400), (idle, backpressure))
    await bench.drive(vectors)
    await bench.drain()
    assert bench.compared == len(vectors), f"compared {bench.compared} of {len(vectors)}"
    bench.finish(f"stream {source}")


@cocotb.test()
async def reset_mid_stream(dut) -> None:
    """Resets in the middle of a stream drop everything in flight."""
    bench = FloatUnitBench(dut, config.seed("reset"), idle=True, backpressure=True)
    await bench.start()
    resets = await unit_tests.reset_mid_stream(bench, stimulus(bench, "random", _n(1500), "reset"))
    bench.finish(f"reset ({resets} resets)")


@cocotb.test()
async def throughput(dut) -> None:
    """One query per clock, the contract's latency, credits stop the input."""
    bench = FloatUnitBench(dut, config.seed("throughput"))
    await bench.start()
    latency, depth = unit_tests.check_contract(bench, bench.contract())
    # Phase 1: never stalled; phase 2: output blocked, FIFO_DEPTH queries get in.
    await unit_tests.full_rate(bench, stimulus(bench, "random", 300 * config.SCALE, "throughput"), latency)
    await unit_tests.credits_stop_input(bench, stimulus(bench, "extreme", depth + 16, "credits"), latency, depth)
    bench.finish(f"throughput (LATENCY {latency}, FIFO_DEPTH {depth})")
