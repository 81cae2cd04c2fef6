# SPDX-License-Identifier: MIT
"""PartBench: driver -> model -> in-order scoreboard around the stream tops
of the local unit's two parts (hdl/local_frame_stream.sv,
hdl/local_child_stream.sv), and their vectors.

The parts have no handshake: each is a fixed-latency pipeline whose
LATENCY the module documents; the stream top puts a valid bit of that
latency beside it, so pairing every valid output with the oldest
outstanding input checks the values and the latency together. Inputs while
in_valid_i is low are random junk (it must not reach a checked output).
The traffic is crossed with idle gaps (no ready: the sink always takes).

Vectors come from the model (pluecker_py) alone:
  frame  the unit's stimulus sources (local_vectors: chains, extreme,
         set-up, raw, trace); inputs packed by the port contract, the
         expected outputs local_node_ray packed as the frame's output
         ports (local_frame_out_ports); END is compared only when the ray
         has an end (without one the model keeps no END)
  child  the node rays of the same sources with their boxes (each box one
         vector), node rays with every field drawn from its port range
         (any DIR, W, ORG, END, class and box), and boundary vectors whose
         one edge test lands on 2 (ext_j DIR_i - ent_i DIR_j) + M + W in
         {-1, 0, 1}; expected local_hit
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Callable

import cocotb

from . import clock_reset, traffic
from .stream import InOrderScoreboard, StreamDriver, StreamSink, drain


@dataclass
class PartVector:
    ports: dict[str, int]
    expect: dict[str, int]  # output port -> value
    describe: Callable[[], str]


class PartBench:
    def __init__(self, dut, seed: int, idle: bool, inputs: tuple[str, ...], outputs: tuple[str, ...]):
        self.dut = dut
        self.inputs, self.outputs = inputs, outputs
        self.latency = int(dut.LATENCY.value)
        self.ecp5 = int(dut.ECP5.value)
        self.rng = random.Random(seed)
        self.idle_gen = traffic.idle_generator(random.Random(seed + 1), idle)
        self.scoreboard = InOrderScoreboard(dut._log, self._compare)

    async def start(self) -> None:
        dut = self.dut
        dut.in_valid_i.value = 0
        self._junk()
        self.edges = await clock_reset.start(dut.clk_i, dut.rst_i, 3)
        self.driver = StreamDriver(dut.clk_i, dut.in_valid_i, None, dut.rst_i, self.edges, self.idle_gen,
                                   self._apply, self._junk, lambda item, edge: self.scoreboard.push(None, item, edge))
        self.sink = StreamSink(dut.clk_i, dut.out_valid_o, None, dut.rst_i, self.edges, traffic.AlwaysReady(),
                               self._transfer, self.scoreboard.error, quiet=[dut.out_valid_o])
        self.sink_task = cocotb.start_soon(self.sink.run())

    def _junk(self) -> None:
        for name in self.inputs:
            handle = getattr(self.dut, name)
            handle.value = self.rng.getrandbits(len(handle))

    def _apply(self, vec: PartVector) -> None:
        for name, value in vec.ports.items():
            getattr(self.dut, name).value = value

    def _transfer(self, edge: int) -> None:
        self.scoreboard.check(None, {name: int(getattr(self.dut, name).value) for name in self.outputs}, edge)

    @staticmethod
    def _compare(vec: PartVector, got: dict[str, int]) -> str | None:
        wrong = [f"{name} = {got[name]:#x}, model {want:#x}" for name, want in vec.expect.items() if got[name] != want]
        return f"{'; '.join(wrong)} for {vec.describe()}" if wrong else None

    async def run(self, vectors: list[PartVector], what: str) -> None:
        await self.driver.send(vectors)
        await drain(self.dut.clk_i, self.scoreboard)
        sb = self.scoreboard
        sb.assert_clean()
        assert sb.compared == len(vectors), f"compared {sb.compared} of {len(vectors)}"
        assert set(sb.latencies) == {self.latency}, f"latency {dict(sb.latencies)}, LATENCY = {self.latency}"
        self.dut._log.info("%s: %d vectors compared, latency histogram %s", what, sb.compared, sb.histogram())


# ---------------------------------------------------------------------------
# Vectors
# ---------------------------------------------------------------------------

FRAME_INPUTS = ("ray_class_i", "ray_org_i", "ray_dir_i", "ray_end_i", "ray_end_valid_i", "frame_org_i",
                "frame_exp_i")
FRAME_OUTPUTS = ("cls_o", "dir_o", "w_o", "org_o", "end_o", "end_valid_o")
CHILD_INPUTS = ("cls_i", "dir_i", "w_i", "org_i", "end_i", "end_valid_i", "box_min_i", "box_max_i")
CHILD_OUTPUTS = ("hit_o",)


def frame_vectors(source: str, contract, seed: int, n: int) -> tuple[list[PartVector], str]:
    import pluecker_py as pp

    from . import local_vectors as lv

    fmt = contract.format
    qs, _, origin = lv.make_queries(source, fmt, 1, seed, n)
    out = []
    for q in qs:
        ports = {k: v for k, v in contract.rtl_ports(q.ray, q.frame, q.boxes).items() if k in FRAME_INPUTS}
        nr = pp.local_node_ray(q.ray, q.frame, fmt)
        expect = pp.local_frame_out_ports(nr, fmt)
        if not nr.has_end:
            del expect["end_o"]
        out.append(PartVector(ports, expect, lambda q=q, nr=nr: f"{q.what()}\n  {q.ray}\n  {q.frame}\n  model {nr}"))
    return out, origin


def _child_vector(nr, box, fmt, what: Callable[[], str]) -> PartVector:
    import pluecker_py as pp

    return PartVector(pp.local_child_in_ports(nr, box, fmt), {"hit_o": int(pp.local_hit(nr, box, fmt))},
                      lambda: f"{what()}\n  {nr}\n  {box}")


def child_vectors(source: str, fmt, seed: int, n: int) -> tuple[list[PartVector], str]:
    import pluecker_py as pp

    from . import local_vectors as lv

    rng = random.Random(seed)
    if source == "raw_node":
        return [_child_vector(*_raw_node(rng, fmt), fmt, lambda k=k: f"raw node ray {k} (seed {seed})")
                for k in range(n)], f"raw node rays (seed={seed}, n={n})"
    if source == "boundary":
        out = []
        while len(out) < n:
            nr, box, how = _boundary(rng, fmt)
            out.append(_child_vector(nr, box, fmt, lambda k=len(out), how=how: f"boundary vector {k} ({how}, "
                                     f"seed {seed})"))
        return out, f"boundary vectors (seed={seed}, n={n})"
    qs, _, origin = lv.make_queries(source, fmt, 1, seed, n)
    out = []
    for q in qs:
        nr = pp.local_node_ray(q.ray, q.frame, fmt)
        out.append(_child_vector(nr, q.boxes[0], fmt, q.what))
    return out, origin


def _signed_range(bits: int) -> tuple[int, int]:
    return -(1 << (bits - 1)), (1 << (bits - 1)) - 1


def _raw_node(rng: random.Random, fmt):
    """A node ray with every field anywhere in its port range (corners mixed
    in) and any K-bit box."""
    import pluecker_py as pp

    from .local_vectors import random_box

    k, d = fmt.box_bits, fmt.dir_bits
    wlo, whi = _signed_range(k + d + 2)
    olo, ohi = _signed_range(k + 2)
    w_corners = [wlo, wlo + 1, fmt.w_min(), fmt.w_min() + 1, -2, -1, 0, 1, 2, fmt.w_max() - 1, fmt.w_max(), whi]
    o_corners = [olo, -2, -1, 0, 1, fmt.box_max() - 1, fmt.box_max(), 1 << k, (1 << k) + 1, ohi]
    d_corners = [0, 1, (1 << (d - 1)) - 1, 1 << (d - 1), (1 << d) - 1]

    def pick(corners: list[int], lo: int, hi: int) -> int:
        return rng.choice(corners) if rng.random() < 0.3 else rng.randint(lo, hi)

    nr = pp.LocalNodeRay(rng.randrange(8), [pick(d_corners, 0, (1 << d) - 1) for _ in range(3)],
                         [pick(w_corners, wlo, whi) for _ in range(6)],
                         [pick(o_corners, olo, ohi) for _ in range(3)], [pick(o_corners, olo, ohi) for _ in range(3)],
                         rng.random() < 0.5)
    return nr, random_box(rng, fmt)


def _boundary(rng: random.Random, fmt):
    """A node ray and box whose origin and end tests pass and whose edge test
    k lands on V_k in {-1, 0, 1} (the other W at their maximum): W_k is
    chosen from the planes and directions here, the answer is the model's."""
    import pluecker_py as pp

    from .local_vectors import random_box

    k_bits, d = fmt.box_bits, fmt.dir_bits
    top = fmt.box_max()
    cls = rng.randrange(8)
    box = random_box(rng, fmt)
    dirs = [rng.choice([0, 1, 1 << (d - 1), rng.randint(0, 1 << (d - 1))]) for _ in range(3)]
    # ent/ext of the box by class: the choice of W below needs them (the
    # datapath's answer itself still comes from local_hit).
    ent = [(top - box.hi[a]) if (cls >> a) & 1 else box.lo[a] for a in range(3)]
    ext = [(top - box.lo[a]) if (cls >> a) & 1 else box.hi[a] for a in range(3)]
    k = rng.randrange(6)
    i, j = pp.local_pair(k)
    cons = fmt.mode == pp.FixedMode.Conservative
    t = rng.choice([-1, 0, 1])
    edge = 2 * (ext[j] * dirs[i] - ent[i] * dirs[j]) + ((ext[j] + ent[i]) if cons else 0)
    w = [fmt.w_max()] * 6
    w[k] = t - edge
    nr = pp.LocalNodeRay(cls, dirs, w, [-1, -1, -1], [1 << k_bits] * 3, rng.random() < 0.5)
    return nr, box, f"edge {k} at {t}"
