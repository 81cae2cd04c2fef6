# SPDX-License-Identifier: MIT
"""Stimulus for the pluecker_intersector benches (test_pluecker_intersector,
test_stress).

Every expected result comes from the golden model (pluecker_py); this module
only chooses operands and never computes a test itself.

Sources
  random   pluecker_py.random_queries, set up and quantised by the model
  extreme  pluecker_py.extreme_queries (edge and corner cases of the format)
  trace    the query file named by PLUECKER_TRACE (as `pluecker trace`
           writes it); without it, generated queries written to a query file
           and read back through the same parser
  raw      operand integers drawn straight from the port ranges (full
           COORD_BITS and DIR_BITS ranges, corner values, lo > hi boxes),
           which the float set-up never produces: checks that no
           intermediate of the RTL overflows
  boundary operands placed exactly on a decision boundary of one test
           (see boundary_stimulus)
"""

from __future__ import annotations

import math
import os
import random
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


@dataclass
class Stimulus:
    vectors: list[Vector]
    skipped: int  # float queries the fixed-point format cannot take
    origin: str


def fixed_format(coord_bits: int, dir_bits: int, conservative: bool) -> pp.FixedFormat:
    mode = pp.FixedMode.Conservative if conservative else pp.FixedMode.Nearest
    return pp.FixedFormat(coord_bits, dir_bits, mode)


def _fixed_vector(ray: pp.FixedRay, box: pp.FixedBox, fmt: pp.FixedFormat, what: Callable[[], str]) -> Vector:
    return Vector(pp.rtl_ports(ray, box, fmt), pp.fixed_hit(ray, box, fmt), lambda: f"{what()}\n  {ray}\n  {box}")


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


def raw_stimulus(fmt: pp.FixedFormat, seed: int, n: int) -> Stimulus:
    rng = random.Random(seed)
    cmin, cmax = fmt.coord_min(), fmt.coord_max()
    dbits = fmt.dir_bits
    dmax = (1 << dbits) - 1
    one = 1 << (dbits - 1)
    coord_corners = [cmin, cmin + 1, -1, 0, 1, cmax - 1, cmax]
    dir_corners = [0, 1, one - 1, one, one + 1, dmax - 1, dmax]

    def coord() -> int:
        return rng.choice(coord_corners) if rng.random() < 0.2 else rng.randint(cmin, cmax)

    def direction() -> int:
        r = rng.random()
        if r < 0.2:
            return rng.choice(dir_corners)
        if r < 0.6:
            return rng.randint(0, one)  # the range the set-up produces
        return rng.randint(0, dmax)

    def between(a: int, b: int) -> int:
        lo, hi = min(a, b), max(a, b)
        return rng.randint(lo, hi)

    vectors: list[Vector] = []
    for k in range(n):
        style = k % 3
        lo = [coord() for _ in range(3)]
        hi = [coord() for _ in range(3)]
        if rng.random() < 0.9:  # mostly proper boxes; some with lo > hi
            lo, hi = [min(a, b) for a, b in zip(lo, hi)], [max(a, b) for a, b in zip(lo, hi)]
        if style == 0:  # origin inside the box's span
            org = [between(lo[a], hi[a]) for a in range(3)]
        else:
            org = [coord() for _ in range(3)]
        has_end = rng.random() < 0.5
        end = [coord() for _ in range(3)] if has_end or rng.random() < 0.5 else [0, 0, 0]
        dirs = [direction() for _ in range(3)]
        if style == 2:  # one dominant axis at 1.0, as the set-up produces
            dirs[rng.randrange(3)] = one
        ray = pp.FixedRay(rng.randrange(8), org, dirs, end, has_end)
        box = pp.FixedBox(lo, hi)
        vectors.append(_fixed_vector(ray, box, fmt, lambda k=k: f"raw vector {k} (seed {seed})"))
    return Stimulus(vectors, 0, f"raw operands (seed={seed}, n={n})")


class _Retry(Exception):
    pass


def _solve_linear(coef: int, rhs: int, mod: int, rng: random.Random, lo: int, hi: int) -> int:
    """A random x in [lo, hi] with coef*x == rhs (mod mod); _Retry if none."""
    g = math.gcd(coef, mod)
    if rhs % g:
        raise _Retry
    m = mod // g
    x0 = (rhs // g) * pow(coef // g, -1, m) % m if m > 1 else 0
    first = x0 + ((lo - x0 + m - 1) // m) * m  # smallest solution >= lo
    if first > hi:
        raise _Retry
    return first + m * rng.randint(0, (hi - first) // m)


def boundary_stimulus(fmt: pp.FixedFormat, seed: int, n: int) -> Stimulus:
    """Operands placed exactly on the decision boundaries of the datapath,
    where an off-by-one anywhere (margin terms, >= versus >, a rounding of
    the end point) flips the answer:
      edge    one edge test at 2*T + M in {-2, -1, 0, 1} (conservative) or
              T in {-1, 0, 1} (nearest), every other test passing with room
      end     one G_i in {-1, 0, 1}, the rest passing
      origin  one B_i in {-1, 0, 1}, the origin inside the other slabs
    The operands are chosen here; the expected answer still comes from the
    model (pluecker_py.fixed_hit)."""
    rng = random.Random(seed)
    cmin, cmax = fmt.coord_min(), fmt.coord_max()
    span = cmax - cmin  # largest |A|, |B|
    one = 1 << (fmt.dir_bits - 1)
    cons = fmt.mode == pp.FixedMode.Conservative

    def direction() -> int:
        r = rng.random()
        if r < 0.25:
            return one
        if r < 0.4:
            return rng.randint(1, 8)
        return rng.randint(1, one)

    def one_vector(kind: str) -> tuple[pp.FixedRay, pp.FixedBox]:
        cls = rng.randrange(8)
        i = rng.randrange(3)
        j = (i + rng.choice([1, 2])) % 3
        k = 3 - i - j
        lim = rng.choice([span // 8, span // 2, span])
        A, B, Dv = [0, 0, 0], [0, 0, 0], [0, 0, 0]
        for a in range(3):  # default: origin inside every slab
            A[a] = -rng.randint(0, lim // 2)
            B[a] = rng.randint(0, lim // 2)
            Dv[a] = direction()
        has_end = False
        G = [0, 0, 0]
        if kind == "edge":
            Di, Dj = Dv[i], Dv[j]
            t = rng.choice([-2, -1, 0, 1]) if cons else rng.choice([-1, 0, 1])
            if cons:
                # 2*(B_j*Di - A_i*Dj) + A_i + B_j + Di + Dj + 1 = t with A_i > 0, B_j >= 0
                m = 2 * Di + 1
                ai = _solve_linear(2 * Dj - 1, Di + Dj + 1 - t, m, rng, 1, lim)
                num = t - Di - Dj - 1 + ai * (2 * Dj - 1)
            else:
                # B_j*Di - A_i*Dj = t
                m = Di
                ai = _solve_linear(Dj, (-t) % Di, Di, rng, 1, lim)
                num = t + ai * Dj
            if num % m or not 0 <= num // m <= span:
                raise _Retry
            A[i], B[j] = ai, num // m
            B[i] = ai + rng.randint(0, lim // 2)  # slab i left after it is entered
            A[j] = -rng.randint(0, lim // 2)  # origin inside slab j: T_ji >= 0
            Dv[k] = 0 if rng.random() < 0.7 else rng.randint(1, 4)
            A[k], B[k] = -rng.randint(0, lim // 2), rng.randint(lim // 4, lim)
        elif kind == "end":
            has_end = True
            G = [rng.randint(0, lim) for _ in range(3)]
            G[i] = rng.choice([-1, 0, 1])
        else:  # origin
            B[i] = rng.choice([-1, 0, 1])
            A[i] = B[i] - rng.randint(1, lim // 2 + 1)
        org, lo, hi, end = [0, 0, 0], [0, 0, 0], [0, 0, 0], [0, 0, 0]
        for a in range(3):
            neg = (cls >> a) & 1
            if max(abs(A[a]), abs(B[a])) > span:
                raise _Retry
            # positive axis: LO = O + A, HI = O + B; negative: HI = O - A, LO = O - B
            s = -1 if neg else 1
            offs = [0, s * A[a], s * B[a]]
            o_lo, o_hi = cmin - min(offs), cmax - max(offs)
            if o_lo > o_hi:
                raise _Retry
            org[a] = rng.randint(o_lo, o_hi)
            lo[a], hi[a] = (org[a] - B[a], org[a] - A[a]) if neg else (org[a] + A[a], org[a] + B[a])
            end[a] = (hi[a] - G[a]) if neg else (lo[a] + G[a])
            if has_end and not cmin <= end[a] <= cmax:
                raise _Retry
        if not has_end:
            end = [rng.randint(cmin, cmax) for _ in range(3)]  # ignored by the DUT
        return pp.FixedRay(cls, org, Dv, end, has_end), pp.FixedBox(lo, hi)

    vectors: list[Vector] = []
    kinds = ["edge", "edge", "edge", "end", "origin"]
    tries = 0
    while len(vectors) < n:
        tries += 1
        if tries > 200 * n + 1000:
            raise RuntimeError(f"boundary_stimulus: only {len(vectors)} of {n} vectors after {tries} tries")
        kind = kinds[len(vectors) % len(kinds)]
        try:
            ray, box = one_vector(kind)
        except _Retry:
            continue
        idx = len(vectors)
        vectors.append(_fixed_vector(ray, box, fmt, lambda idx=idx, kind=kind: f"boundary vector {idx} ({kind}, seed {seed})"))
    return Stimulus(vectors, 0, f"boundary operands (seed={seed}, n={n})")


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
