# SPDX-License-Identifier: MIT
"""Stimulus for the pluecker_intersector benches (test_pluecker_intersector,
test_stress).

Every expected result comes from the golden model (pluecker_py); this module
only picks the model's generators and turns their queries into port values;
it never computes a test itself.

Sources
  random   pluecker_py.random_queries, set up and quantised by the model
  extreme  pluecker_py.extreme_queries (edge and corner cases of the format)
  trace    the query file named by PLUECKER_TRACE (as `pluecker trace`
           writes it); without it, generated queries written to a query file
           and read back through the same parser
  raw      pluecker_py.port_range_queries: operand integers drawn straight
           from the port ranges (full COORD_BITS and DIR_BITS ranges, corner
           values, lo > hi boxes), which the float set-up never produces:
           checks that no intermediate of the RTL overflows
  boundary pluecker_py.boundary_queries: operands placed exactly on a
           decision boundary of one test (edge, end, origin)
The operand generators are the model's (querygen.hpp), shared with the
Verilator harness (`pluecker_sim gen --kind boundary|ports`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import pluecker_py as pp


@dataclass
class Vector:
    """One query as driven into the DUT, with the model's answer."""

    ports: dict[str, int]
    hit: bool
    describe: Callable[[], str]  # called only for error messages
    ray: pp.FixedRay | None = None  # the quantised operands, when the vector has them
    box: pp.FixedBox | None = None


@dataclass
class Stimulus:
    vectors: list[Vector]
    skipped: int  # float queries the fixed-point format cannot take
    origin: str


def fixed_format(coord_bits: int, dir_bits: int, conservative: bool) -> pp.FixedFormat:
    mode = pp.FixedMode.Conservative if conservative else pp.FixedMode.Nearest
    return pp.FixedFormat(coord_bits, dir_bits, mode)


def _fixed_vector(ray: pp.FixedRay, box: pp.FixedBox, fmt: pp.FixedFormat, what: Callable[[], str]) -> Vector:
    return Vector(pp.rtl_ports(ray, box, fmt), pp.fixed_hit(ray, box, fmt), lambda: f"{what()}\n  {ray}\n  {box}",
                  ray, box)


def ternary_vectors(vectors: list[Vector], fmt: pp.FixedFormat) -> list[Vector]:
    """The same queries with the answer of a TERNARY unit as two bits:
    (out_hit_o << 1) | out_strict_o = (fixed_hit << 1) | fixed_strict_hit
    (0 certain miss, 2 uncertain, 3 certain hit; 1 would be a strict hit
    that fails the conservative test, which ternary.hpp proves impossible)."""
    out = []
    for v in vectors:
        assert v.ray is not None and v.box is not None, "a ternary vector needs its quantised operands"
        strict = pp.fixed_strict_hit(v.ray, v.box, fmt)
        out.append(Vector(v.ports, (int(v.hit) << 1) | int(strict), v.describe, v.ray, v.box))
    return out


def from_queries(queries: list, fmt: pp.FixedFormat, origin: str) -> Stimulus:
    """Float queries -> vectors, through the renderer's fixed-point set-up:
    any finite origin (clipped exactly onto the range cube when outside it),
    the box quantised."""
    vectors: list[Vector] = []
    skipped = 0
    for k, q in enumerate(queries):
        try:
            box = pp.fixed_quantize_box(q.box, fmt)
        except pp.InputError:
            skipped += 1  # box outside the fixed-point range
            continue
        ray = pp.fixed_setup_ray(q.ray, fmt)
        if ray is None:
            skipped += 1  # never meets the range cube: a miss without an RTL query
            continue
        vectors.append(_fixed_vector(ray, box, fmt, lambda q=q, k=k: f"{origin} query #{k}: {q.line()}"))
    return Stimulus(vectors, skipped, origin)


def random_stimulus(fmt: pp.FixedFormat, seed: int, n: int) -> Stimulus:
    return from_queries(pp.random_queries(seed, n), fmt, f"random_queries(seed={seed}, n={n})")


def extreme_stimulus(fmt: pp.FixedFormat, seed: int, n: int) -> Stimulus:
    return from_queries(pp.extreme_queries(seed, n), fmt, f"extreme_queries(seed={seed}, n={n})")


def setup_stimulus(fmt: pp.FixedFormat, seed: int, n: int) -> Stimulus:
    """Rays from anywhere (far cameras and lights, long directions, the range
    cube's edges) into boxes of the format's range, through the set-up."""
    return from_queries(pp.setup_queries(seed, n, fmt.coord_bits), fmt,
                        f"setup_queries(seed={seed}, n={n}, coord_bits={fmt.coord_bits})")


def trace_stimulus(fmt: pp.FixedFormat, seed: int, n: int, work_dir: Path) -> Stimulus:
    """The first PLUECKER_TRACE_LIMIT (default n, 0 = all) queries of the
    PLUECKER_TRACE file, else n generated queries written to a query file in
    work_dir and read back."""
    path = os.environ.get("PLUECKER_TRACE")
    if path:
        limit = int(os.environ.get("PLUECKER_TRACE_LIMIT", str(n)))
        queries = pp.read_queries_file(path)
        if limit > 0:
            queries = queries[:limit]
        return from_queries(queries, fmt, f"trace {path}")
    queries = pp.random_queries(seed, n // 2) + pp.extreme_queries(seed + 1, n - n // 2)
    work_dir.mkdir(parents=True, exist_ok=True)
    gen = work_dir / f"generated_trace_{seed}.txt"
    gen.write_text("".join(q.line() + "\n" for q in queries))
    return from_queries(pp.read_queries_file(str(gen)), fmt, f"generated trace {gen}")


def _operand_stimulus(pairs: list, fmt: pp.FixedFormat, what: Callable[[int], str], origin: str) -> Stimulus:
    """(FixedRay, FixedBox) operands of the model's generators -> vectors."""
    vectors = [_fixed_vector(ray, box, fmt, lambda k=k: what(k)) for k, (ray, box) in enumerate(pairs)]
    return Stimulus(vectors, 0, origin)


def raw_stimulus(fmt: pp.FixedFormat, seed: int, n: int) -> Stimulus:
    """pluecker_py.port_range_queries: operands from the full port ranges."""
    return _operand_stimulus(pp.port_range_queries(seed, n, fmt), fmt, lambda k: f"raw vector {k} (seed {seed})",
                             f"port_range_queries(seed={seed}, n={n})")


def boundary_stimulus(fmt: pp.FixedFormat, seed: int, n: int) -> Stimulus:
    """pluecker_py.boundary_queries: operands exactly on a decision boundary
    of one test (edge, end, origin; see querygen.hpp)."""
    kinds = pp.boundary_query_kinds(seed, n, fmt)
    return _operand_stimulus(
        pp.boundary_queries(seed, n, fmt), fmt,
        lambda k: f"boundary vector {k} ({pp.boundary_kind_name(kinds[k])}, seed {seed})",
        f"boundary_queries(seed={seed}, n={n})")


def make_stimulus(source: str, fmt: pp.FixedFormat, seed: int, n: int, work_dir: Path) -> Stimulus:
    if source == "random":
        return random_stimulus(fmt, seed, n)
    if source == "extreme":
        return extreme_stimulus(fmt, seed, n)
    if source == "trace":
        return trace_stimulus(fmt, seed, n, work_dir)
    if source == "setup":
        return setup_stimulus(fmt, seed, n)
    if source == "raw":
        return raw_stimulus(fmt, seed, n)
    if source == "boundary":
        return boundary_stimulus(fmt, seed, n)
    raise ValueError(f"unknown stimulus source {source!r}")
