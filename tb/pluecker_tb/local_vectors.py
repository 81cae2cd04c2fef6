# SPDX-License-Identifier: MIT
"""Stimulus for the local-frame benches (test_pluecker_local_intersector and
the benches of its two parts).

Every expected answer comes from the golden model (pluecker_py: the set-up
local_setup_ray, the frames local_frame_for / local_child_frame, the boxes
local_quantize_box, the node ray local_node_ray and the child datapath
local_hit); this module only chooses operands and never computes a test.
The port values come from the port contract (LocalPortContract.rtl_ports).

A query is (LocalRay, LocalFrame, [LocalBox] * CHILDREN); sources
  random   random_queries' rays against boxes in chains of frames, as a BVH
           nests them: a box, its tight frame (local_frame_for), a child box
           inside it, the child's frame (local_child_frame), ... and every
           box of the chain tested in its parent's frame and in the frames
           of older ancestors (the rays: the query's own and rays aimed at
           the chain's boxes)
  extreme  extreme_queries (the edge and corner families of the format),
           each box in its tight frame
  setup    setup_queries (rays from anywhere: far cameras and lights, long
           directions, the range's edges), each box in its tight frame
  raw      operands drawn straight from the contract's port ranges: any
           G-bit origin, end and frame origin, any class, a direction with
           one component at 2^(G-1) and the others anywhere in 0..2^(G-1),
           any exponent in 0..G-K+1, any K-bit box (also LO > HI), corner
           values mixed in; checks that no intermediate of the RTL overflows
  trace    the queries of a small local-frame render of the teapot
           (pluecker_py.local_render_queries: the LocalBoxQuery stream of
           the batched traversal; the conservative hierarchy and set-up in
           both modes)
With CHILDREN = 2 a query carries two boxes in one frame: the chain's boxes
of one frame, the traversal's two children of a node, or (extreme, setup,
raw) a second box drawn from the stream or the port range.
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Callable

import pluecker_py as pp


@dataclass
class Vector:
    """One query as driven into the DUT, with the model's answers (bit c of
    `hit` for child box c)."""

    ports: dict[str, int]
    hit: int
    describe: Callable[[], str]  # called only for error messages


@dataclass
class Stimulus:
    vectors: list[Vector]
    skipped: int  # float queries the local format cannot take
    origin: str


@dataclass
class LocalQuery:
    ray: object  # pp.LocalRay
    frame: object  # pp.LocalFrame
    boxes: list  # [pp.LocalBox] * CHILDREN
    what: Callable[[], str]


def model_hits(q: LocalQuery, fmt: pp.LocalFormat) -> int:
    nr = pp.local_node_ray(q.ray, q.frame, fmt)
    return sum(int(pp.local_hit(nr, b, fmt)) << c for c, b in enumerate(q.boxes))


def to_vector(q: LocalQuery, contract: pp.LocalPortContract) -> Vector:
    fmt = contract.format
    return Vector(contract.rtl_ports(q.ray, q.frame, q.boxes), model_hits(q, fmt),
                  lambda: f"{q.what()}\n  {q.ray}\n  {q.frame}\n  " + "\n  ".join(map(repr, q.boxes)))


def random_box(rng: random.Random, fmt: pp.LocalFormat) -> pp.LocalBox:
    """Any K-bit box (LO > HI too)."""
    top = fmt.box_max()
    corners = [0, 1, top - 1, top]

    def v() -> int:
        return rng.choice(corners) if rng.random() < 0.2 else rng.randint(0, top)

    return pp.LocalBox([v() for _ in range(3)], [v() for _ in range(3)])


def _fill(queries: list[LocalQuery], children: int, rng: random.Random, fmt: pp.LocalFormat) -> None:
    """Brings every query to `children` boxes: a second box from another
    query of the stream when it fits this one's frame, else a K-bit box."""
    for q in queries:
        while len(q.boxes) < children:
            q.boxes.append(random_box(rng, fmt))


def _tight(fq, fmt: pp.LocalFormat):
    """(LocalRay, LocalFrame, LocalBox) of a float query in its box's tight
    frame; None when the box is outside the range or the ray misses it."""
    try:
        frame = pp.local_frame_for(fq.box, fmt)
        box = pp.local_quantize_box(fq.box, frame, fmt)
    except pp.InputError:
        return None
    ray = pp.local_setup_ray(fq.ray, fmt)
    if ray is None:
        return None
    return ray, frame, box


def float_stimulus(queries: list, fmt: pp.LocalFormat, children: int, rng: random.Random,
                   origin: str) -> tuple[list[LocalQuery], int]:
    """Float queries, each box in its tight frame; with two children the
    next query's box joins when it fits the frame."""
    out: list[LocalQuery] = []
    skipped = 0
    for k, fq in enumerate(queries):
        t = _tight(fq, fmt)
        if t is None:
            skipped += 1
            continue
        ray, frame, box = t
        boxes = [box]
        if children > 1 and k + 1 < len(queries):
            try:
                boxes.append(pp.local_quantize_box(queries[k + 1].box, frame, fmt))
            except pp.InputError:
                pass
        out.append(LocalQuery(ray, frame, boxes, lambda fq=fq, k=k: f"{origin} query #{k}: {fq.line()}"))
    _fill(out, children, rng, fmt)
    return out, skipped


def _sub_box(rng: random.Random, b: pp.Box) -> pp.Box:
    """A random box inside b (sometimes flat on an axis, sometimes a sliver)."""
    lo, hi = [], []
    for a in range(3):
        x0, x1 = b.lo[a], b.hi[a]
        r = rng.random()
        if r < 0.1:  # flat
            v = rng.uniform(x0, x1)
            u = w = v
        elif r < 0.2:  # a sliver at one side
            f = rng.choice([1e-3, 1e-5])
            u, w = (x0, x0 + (x1 - x0) * f) if rng.random() < 0.5 else (x1 - (x1 - x0) * f, x1)
        else:
            u, w = sorted((rng.uniform(x0, x1), rng.uniform(x0, x1)))
        lo.append(u)
        hi.append(w)
    return pp.Box(lo, hi)


def _aimed_ray(rng: random.Random, b: pp.Box, far: float) -> pp.Ray:
    """A ray from a random origin (up to `far` away) through a random point
    of b, sometimes as a segment that ends near the box."""
    p = [rng.uniform(b.lo[a], b.hi[a]) for a in range(3)]
    o = [p[a] + rng.uniform(-far, far) for a in range(3)]
    d = [p[a] - o[a] for a in range(3)]
    if not any(d):
        d = [1.0, 0.0, 0.0]
    tmax = rng.choice([float("inf"), float("inf"), rng.uniform(0.5, 1.5)])
    return pp.Ray(o, d, tmax)


def chain_stimulus(fmt: pp.LocalFormat, children: int, seed: int, n: int) -> tuple[list[LocalQuery], int]:
    """random_queries' boxes as chain roots, their rays and rays aimed at the
    chain's boxes, every box in its parent's and older ancestors' frames."""
    rng = random.Random(seed)
    out: list[LocalQuery] = []
    skipped = 0
    roots = pp.random_queries(seed, max(1, n // 8))
    for r, root in enumerate(roots):
        if len(out) >= n:
            break
        try:
            frames = [pp.local_frame_for(root.box, fmt)]
        except pp.InputError:
            skipped += 1
            continue
        boxes_f = [root.box]
        quant = [pp.local_quantize_box(root.box, frames[0], fmt)]
        depth = rng.randint(2, 5)
        for _ in range(depth):  # box k+1 inside box k, quantised in frame k
            child = _sub_box(rng, boxes_f[-1])
            try:  # (nearest mode rounds a plane inward: a grandchild may leave the frame)
                q = pp.local_quantize_box(child, frames[-1], fmt)
                frames.append(pp.local_child_frame(child, frames[-1], q, fmt))
            except pp.InputError:
                skipped += 1
                break
            boxes_f.append(child)
            quant.append(q)
        rays = [root.ray] + [_aimed_ray(rng, boxes_f[rng.randrange(len(boxes_f))], rng.choice([0.1, 1.0, 3.0]))
                             for _ in range(3)]
        for ray_f in rays:
            ray = pp.local_setup_ray(ray_f, fmt)
            if ray is None:
                skipped += 1
                continue
            for k in range(1, len(boxes_f)):
                # box k in its parent's frame (k - 1) and in an older ancestor's
                for j in sorted({k - 1, rng.randrange(k)}):
                    try:
                        bs = [quant[k] if j == k - 1 else pp.local_quantize_box(boxes_f[k], frames[j], fmt)]
                        if children > 1:  # a sibling: another box of the chain in frame j
                            sib = boxes_f[rng.randrange(j + 1, len(boxes_f))]
                            bs.append(pp.local_quantize_box(sib, frames[j], fmt))
                    except pp.InputError:
                        skipped += 1
                        continue
                    out.append(LocalQuery(ray, frames[j], bs,
                                          lambda r=r, k=k, j=j, ray_f=ray_f:
                                          f"chain {r} (seed {seed}): box {k} in frame {j}, ray {ray_f}"))
    return out[:n], skipped


def raw_stimulus(fmt: pp.LocalFormat, children: int, seed: int, n: int) -> list[LocalQuery]:
    rng = random.Random(seed)
    g = fmt.grid_bits
    gmin, gmax = fmt.grid_min(), fmt.grid_max()
    top = 1 << (g - 1)
    grid_corners = [gmin, gmin + 1, -1, 0, 1, gmax - 1, gmax]
    dir_corners = [0, 1, 2, top // 2, top - 1, top]
    emax = fmt.max_exp()

    def grid() -> int:
        return rng.choice(grid_corners) if rng.random() < 0.2 else rng.randint(gmin, gmax)

    def direction() -> int:
        r = rng.random()
        if r < 0.25:
            return rng.choice(dir_corners)
        if r < 0.5:  # small components: the node set-up's scaling c grows
            return rng.randint(0, 1 << rng.randint(0, g - 1))
        return rng.randint(0, top)

    def exponent() -> int:
        return rng.choice([0, 1, emax - 1, emax]) if rng.random() < 0.3 else rng.randint(0, emax)

    out = []
    for k in range(n):
        dirs = [direction() for _ in range(3)]
        dirs[rng.randrange(3)] = top
        has_end = rng.random() < 0.5
        ray = pp.LocalRay(rng.randrange(8), [grid() for _ in range(3)], dirs,
                          [grid() for _ in range(3)] if has_end or rng.random() < 0.5 else [0, 0, 0], has_end)
        frame = pp.LocalFrame([grid() for _ in range(3)], [exponent() for _ in range(3)])
        boxes = [random_box(rng, fmt) for _ in range(children)]
        if k % 4 < 2:  # the origin near the frame: the cells matter, not the clamps
            cells = [rng.randint(-2, fmt.box_max() + 2) for _ in range(3)]
            org = [min(gmax, max(gmin, frame.origin[a] + (cells[a] << frame.exp[a]) + rng.randint(
                0, (1 << frame.exp[a]) - 1))) for a in range(3)]
            ray = pp.LocalRay(ray.cls, org, ray.dir_g, ray.end, ray.has_end)
            if k % 4 == 0:  # boxes around the origin's cell (in unmirrored cells)
                top_cell = fmt.box_max()
                c = [min(top_cell, max(0, x)) for x in cells]
                boxes = [pp.LocalBox([rng.randint(0, c[a]) for a in range(3)],
                                     [rng.randint(c[a], top_cell) for a in range(3)]) for _ in range(children)]
        out.append(LocalQuery(ray, frame, boxes, lambda k=k: f"raw vector {k} (seed {seed})"))
    return out


def trace_stimulus(fmt: pp.LocalFormat, children: int, seed: int, n: int) -> list[LocalQuery]:
    """The first queries of a small teapot render's traversal; with two
    children a node's two child boxes (same ray, same frame) go together."""
    rng = random.Random(seed)
    size = 12 if n <= 2000 else 24
    # The hierarchy and rays of a conservative render at the same widths
    # (the model's nearest-mode hierarchy build refuses the teapot: a
    # child's planes rounded to nearest can leave its parent's frame); in
    # nearest mode the same operands are answered by the nearest datapath.
    record = pp.LocalFormat(fmt.box_bits, fmt.dir_bits, fmt.grid_bits, "conservative")
    raw = pp.local_render_queries("teapot", size, record, limit=2 * n)
    out: list[LocalQuery] = []
    i = 0
    while i < len(raw) and len(out) < n:
        ray, frame, box, node = raw[i]
        boxes = [box]
        nodes = [node]
        if children > 1 and i + 1 < len(raw) and raw[i + 1][0] == ray and raw[i + 1][1] == frame:
            boxes.append(raw[i + 1][2])
            nodes.append(raw[i + 1][3])
            i += 1
        i += 1
        out.append(LocalQuery(ray, frame, boxes, lambda nodes=nodes, i=i: f"teapot {size}x{size} trace query "
                              f"{i}, nodes {nodes}"))
    _fill(out, children, rng, fmt)
    return out


def _edge_box(rng: random.Random, fmt: pp.LocalFormat, node, k: int) -> pp.LocalBox | None:
    """A box whose edge test k (pair i, j) sits on its decision boundary:
    2 (ext_j DIR_i - ent_i DIR_j) + ext_j + ent_i + W_k (conservative) in
    {-1, 0}, so that a W or margin off by one flips the answer. None when no
    plane pair in 0..2^K - 1 gets there."""
    i, j = pp.local_pair(k)
    top = fmt.box_max()
    cons = fmt.mode == pp.FixedMode.Conservative
    d_i, d_j, w = node.dir[i], node.dir[j], node.w[k]
    a = (1 if cons else 0) - 2 * d_j  # V as a function of ent_i: a ent_i + b
    for ext_j in rng.sample(range(top + 1), min(top + 1, 64)):
        b = 2 * ext_j * d_i + (ext_j if cons else 0) + w
        for v in (rng.choice((-1, 0, 0)), -1, 0):
            if a != 0 and (v - b) % a == 0 and 0 <= (v - b) // a <= top:
                ent_i = (v - b) // a
                # Every other plane as far out as it goes, so that the other
                # tests pass as often as they can: axis i's exit and axis
                # j's entry at the frame's far and near ends, the third
                # axis the whole frame.
                lo, hi = [0, 0, 0], [top, top, top]
                if (node.cls >> i) & 1:  # ent_i = ~HI_i
                    hi[i] = top - ent_i
                else:
                    lo[i] = ent_i
                if (node.cls >> j) & 1:  # ext_j = ~LO_j
                    lo[j] = top - ext_j
                else:
                    hi[j] = ext_j
                return pp.LocalBox(lo, hi)
    return None


def edge_stimulus(fmt: pp.LocalFormat, children: int, seed: int, n: int) -> list[LocalQuery]:
    """Raw rays and frames (origins near the frame) whose boxes put one edge
    test exactly on its decision boundary (_edge_box), found from the
    model's node ray (local_node_ray): the operands where a W, a margin or
    a comparison off by one shows."""
    rng = random.Random(seed)
    out: list[LocalQuery] = []
    for q in raw_stimulus(fmt, children, seed, 4 * n):
        if len(out) == n:
            break
        if q.ray.has_end:  # the end test would decide too often
            q = LocalQuery(pp.LocalRay(q.ray.cls, q.ray.org, q.ray.dir_g, q.ray.end, False), q.frame, q.boxes,
                           q.what)
        node = pp.local_node_ray(q.ray, q.frame, fmt)
        if any(o > fmt.box_max() for o in node.org):  # past every exit plane: the origin test decides
            continue
        boxes = [_edge_box(rng, fmt, node, rng.randrange(6)) for _ in range(children)]
        if all(b is not None for b in boxes):
            out.append(LocalQuery(q.ray, q.frame, boxes, q.what))
    return out


def make_queries(source: str, fmt: pp.LocalFormat, children: int, seed: int,
                 n: int) -> tuple[list[LocalQuery], int, str]:
    """(queries, skipped, origin) of a stimulus source."""
    rng = random.Random(seed + 17)
    if source == "random":
        qs, skipped = chain_stimulus(fmt, children, seed, n)
        return qs, skipped, f"box chains of random_queries(seed={seed})"
    if source == "extreme":
        qs, skipped = float_stimulus(pp.extreme_queries(seed, n), fmt, children, rng,
                                     f"extreme_queries(seed={seed}, n={n})")
        return qs, skipped, f"extreme_queries(seed={seed}, n={n})"
    if source == "setup":
        bits = min(fmt.grid_bits, pp.FixedFormat.MAX_BITS)
        qs, skipped = float_stimulus(pp.setup_queries(seed, n, max(bits, pp.FixedFormat.MIN_BITS)), fmt, children,
                                     rng, f"setup_queries(seed={seed}, n={n})")
        return qs, skipped, f"setup_queries(seed={seed}, n={n}, coord_bits={bits})"
    if source == "raw":
        return raw_stimulus(fmt, children, seed, n), 0, f"raw operands (seed={seed}, n={n})"
    if source == "trace":
        return trace_stimulus(fmt, children, seed, n), 0, f"teapot trace (seed={seed})"
    if source == "edge":
        return edge_stimulus(fmt, children, seed, n), 0, f"edge tests on their boundary (seed={seed}, n={n})"
    raise ValueError(f"unknown stimulus source {source!r}")


def make_stimulus(source: str, contract: pp.LocalPortContract, seed: int, n: int) -> Stimulus:
    qs, skipped, origin = make_queries(source, contract.format, contract.children, seed, n)
    return Stimulus([to_vector(q, contract) for q in qs], skipped, origin)
