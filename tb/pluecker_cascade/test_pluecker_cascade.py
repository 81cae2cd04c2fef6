# SPDX-License-Identifier: MIT
"""cocotb bench for rtl/pluecker_cascade.sv: narrow TERNARY lanes and one
shared wide unit against the golden model (pluecker_py: fixed_ternary on
the narrow format, fixed_hit on the wide one; ternary.hpp's
cascade_answer).

Every float query is set up twice by the model (fixed_setup_ray,
fixed_quantize_box), once per format, and sent on one lane with both
encodings. Each lane has its own idle generator and out_ready_i generator,
the escalation stream its own esc_ready_i generator. Scoreboard, per lane,
in query order: a certain answer on the lane's stream must be the oldest
outstanding query of the lane that the model does not call uncertain (the
uncertain ones before it have left for the wide unit), with the model's
narrow answer; an answer on esc_* must be the oldest outstanding uncertain
query of its lane, with the wide format's answer. Every query is answered
exactly once; nothing assumes a latency.

Tests
  stream   idle gaps x stalls on every output stream (cocotb.parametrize):
           all queries answered, each where and as the model says
  reset    resets in the middle of the streams: everything in flight is
           gone (an answer with no query of its lane outstanding is an
           error); afterwards every lane works again
"""

from __future__ import annotations

import random

import pytest

from pluecker_tb import config

try:
    import cocotb
    from cocotb.clock import Clock
    from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge

    import pluecker_py as pp
    from pluecker_tb import traffic
    from pluecker_tb import vectors as pv
except ImportError:  # pragma: no cover - only the pytest runner part is usable
    cocotb = None

TOPLEVEL = "pluecker_cascade"
PAYLOAD = ("ray_class_i", "ray_org_i", "ray_dir_i", "ray_end_i", "ray_end_valid_i", "box_min_i", "box_max_i")
MISS, UNCERTAIN, HIT = 0, 1, 2


class Query:
    """One float query in both formats, with the model's answers."""

    def __init__(self, q, narrow, wide, fmt_n, fmt_w):
        self.q = q
        self.narrow_ports = pp.rtl_ports(narrow[0], narrow[1], fmt_n)
        self.wide_ports = pp.rtl_ports(wide[0], wide[1], fmt_w)
        self.narrow = int(pp.fixed_ternary(narrow[0], narrow[1], fmt_n))
        self.wide_hit = bool(pp.fixed_hit(wide[0], wide[1], fmt_w))

    def describe(self) -> str:
        return f"{self.q.line()} (narrow {['miss', 'uncertain', 'hit'][self.narrow]}, wide hit {int(self.wide_hit)})"


def make_queries(source: str, seed: int, n: int, fmt_n, fmt_w) -> list:
    """Float queries of a model generator that both formats can take (a
    query the narrow set-up drops is a miss without a box test; the wide
    format's range is the narrow one's, so it drops the same)."""
    if source == "random":
        floats = pp.random_queries(seed, n)
    elif source == "extreme":
        floats = pp.extreme_queries(seed, n)
    elif source == "setup":
        floats = pp.setup_queries(seed, n, fmt_n.coord_bits)
    else:
        raise ValueError(source)
    out = []
    for q in floats:
        try:
            nb, wb = pp.fixed_quantize_box(q.box, fmt_n), pp.fixed_quantize_box(q.box, fmt_w)
        except pp.InputError:
            continue
        nr, wr = pp.fixed_setup_ray(q.ray, fmt_n), pp.fixed_setup_ray(q.ray, fmt_w)
        if nr is None or wr is None:
            continue
        out.append(Query(q, (nr, nb), (wr, wb), fmt_n, fmt_w))
    return out


class CascadeBench:
    def __init__(self, dut, seed: int, idle: bool, backpressure: bool):
        self.dut = dut
        self.n = int(dut.N_NARROW.value)
        self.tag_bits = int(dut.TAG_BITS.value)
        self.fmt_n = pv.fixed_format(int(dut.NARROW_COORD_BITS.value), int(dut.NARROW_DIR_BITS.value), True)
        self.fmt_w = pv.fixed_format(int(dut.WIDE_COORD_BITS.value), int(dut.WIDE_DIR_BITS.value), True)
        self.lane_bits = len(dut.esc_lane_o)
        self.width = {name: len(getattr(dut, name)) // self.n for name in ("in_tag_i", *PAYLOAD)}
        self.wwidth = {name: len(getattr(dut, "wide_" + name)) // self.n for name in PAYLOAD}
        self.rng = random.Random(seed)
        self.idle = [traffic.idle_generator(random.Random(seed + 10 + l), idle) for l in range(self.n)]
        self.ready = [traffic.ready_generator(random.Random(seed + 20 + l), backpressure) for l in range(self.n)]
        self.esc_ready = traffic.ready_generator(random.Random(seed + 5), backpressure)
        self.queues: list[list] = [[] for _ in range(self.n)]
        self.offered: list = [None] * self.n
        self.outstanding: list[list] = [[] for _ in range(self.n)]  # (tag, Query), in query order
        self.next_tag = [0] * self.n
        self.errors: list[str] = []
        self.answered = {"certain": 0, "escalated": 0, "hits": 0, "dropped": 0}
        self.edge = 0

    def load(self, lane: int, queries) -> None:
        for q in queries:
            self.queues[lane].append((self.next_tag[lane], q))
            self.next_tag[lane] = (self.next_tag[lane] + 1) % (1 << self.tag_bits)

    def pending(self) -> bool:
        return any(self.queues) or any(o is not None for o in self.offered) or any(self.outstanding)

    def _error(self, msg: str) -> None:
        self.dut._log.error("edge %d: %s", self.edge, msg)
        self.errors.append(msg)

    def _certain(self, lane: int, tag: int, hit: int) -> None:
        for k, (t, q) in enumerate(self.outstanding[lane]):
            if q.narrow == UNCERTAIN:
                continue  # left for the wide unit before this one
            if t != tag:
                self._error(f"lane {lane}: certain answer with tag {tag}, expected tag {t} ({q.describe()})")
            elif hit != (q.narrow == HIT):
                self._error(f"lane {lane} tag {tag}: certain answer hit={hit}, model {q.describe()}")
            del self.outstanding[lane][k]
            self.answered["certain"] += 1
            self.answered["hits"] += hit
            return
        self._error(f"lane {lane}: certain answer (tag {tag}) with no certain query outstanding")

    def _escalated(self, lane: int, tag: int, hit: int) -> None:
        if lane >= self.n:
            self._error(f"escalated answer from lane {lane} of {self.n}")
            return
        for k, (t, q) in enumerate(self.outstanding[lane]):
            if q.narrow != UNCERTAIN:
                continue
            if t != tag:
                self._error(f"lane {lane}: escalated answer with tag {tag}, expected tag {t} ({q.describe()})")
            elif hit != q.wide_hit:
                self._error(f"lane {lane} tag {tag}: escalated answer hit={hit}, model {q.describe()}")
            del self.outstanding[lane][k]
            self.answered["escalated"] += 1
            self.answered["hits"] += hit
            return
        self._error(f"lane {lane}: escalated answer (tag {tag}) with no uncertain query outstanding")

    def cycle(self) -> None:
        """At a falling edge: read the outputs (from flops, stable until the
        next edge), drive the inputs of that edge and book its handshakes."""
        dut = self.dut
        in_ready, out_valid = int(dut.in_ready_o.value), int(dut.out_valid_o.value)
        tags, hits = int(dut.out_tag_o.value), int(dut.out_hit_o.value)
        esc_valid = int(dut.esc_valid_o.value)
        mask = (1 << self.tag_bits) - 1
        self.edge += 1
        fields = {name: 0 for name in ("in_tag_i", *PAYLOAD)}
        wfields = {name: 0 for name in PAYLOAD}
        valid = ready = 0
        for l in range(self.n):
            if self.offered[l] is None and self.queues[l] and not self.idle[l].idle_now():
                self.offered[l] = self.queues[l].pop(0)
            if self.offered[l] is not None:
                tag, q = self.offered[l]
                values, wvalues = dict(q.narrow_ports, in_tag_i=tag), q.wide_ports
                valid |= 1 << l
            else:
                values = {name: self.rng.getrandbits(w) for name, w in self.width.items()}
                wvalues = {name: self.rng.getrandbits(w) for name, w in self.wwidth.items()}
            for name, w in self.width.items():
                fields[name] |= (values[name] & ((1 << w) - 1)) << (l * w)
            for name, w in self.wwidth.items():
                wfields[name] |= (wvalues[name] & ((1 << w) - 1)) << (l * w)
            lane_ready = self.ready[l].ready_now()
            ready |= lane_ready << l
            if self.offered[l] is not None and in_ready >> l & 1:
                self.outstanding[l].append(self.offered[l])
                self.offered[l] = None
            if lane_ready and out_valid >> l & 1:
                self._certain(l, tags >> (l * self.tag_bits) & mask, hits >> l & 1)
        esc_ready = self.esc_ready.ready_now()
        if esc_valid and esc_ready:
            self._escalated(int(dut.esc_lane_o.value), int(dut.esc_tag_o.value), int(dut.esc_hit_o.value))
        for name, value in fields.items():
            getattr(dut, name).value = value
        for name, value in wfields.items():
            getattr(dut, "wide_" + name).value = value
        dut.in_valid_i.value = valid
        dut.out_ready_i.value = ready
        dut.esc_ready_i.value = esc_ready

    async def run(self, limit: int, reset_every: int = 0) -> int:
        dut, resets, cycles = self.dut, 0, 0
        while self.pending():
            cycles += 1
            assert cycles < limit, f"not drained in {limit} cycles: {[len(o) for o in self.outstanding]}"
            assert not self.errors, self.errors[0]
            await FallingEdge(dut.clk_i)
            if reset_every and cycles % reset_every == 0 and resets < 3:
                resets += 1
                await self.reset()
                await FallingEdge(dut.clk_i)
            self.cycle()
        return resets

    async def reset(self, cycles: int = 2) -> None:
        dut = self.dut
        dut.in_valid_i.value = 0
        dut.out_ready_i.value = 0
        dut.esc_ready_i.value = 0
        dut.rst_i.value = 1
        self.answered["dropped"] += sum(len(o) for o in self.outstanding)
        self.outstanding = [[] for _ in range(self.n)]
        for k in range(cycles):
            await RisingEdge(dut.clk_i)
            self.edge += 1
            await ReadOnly()
            if k >= 1:
                assert int(dut.in_ready_o.value) == 0 and int(dut.out_valid_o.value) == 0, "ready/valid in reset"
                assert int(dut.esc_valid_o.value) == 0, "esc_valid_o in reset"
            await FallingEdge(dut.clk_i)
        dut.rst_i.value = 0
        await RisingEdge(dut.clk_i)
        self.edge += 1
        await ReadOnly()
        assert int(dut.out_valid_o.value) == 0 and int(dut.esc_valid_o.value) == 0, "valid right after a reset"

    def finish(self, what: str) -> None:
        assert not self.errors, f"{len(self.errors)} errors, first: {self.errors[0]}"
        assert not any(self.outstanding), "queries left unanswered"
        self.dut._log.info("%s: %d lanes, %s, %d edges", what, self.n, self.answered, self.edge)


async def _start(dut, seed: int, idle: bool, backpressure: bool) -> CascadeBench:
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    bench = CascadeBench(dut, seed, idle, backpressure)
    dut.in_valid_i.value = 0
    dut.out_ready_i.value = 0
    dut.esc_ready_i.value = 0
    dut.rst_i.value = 1
    for _ in range(3):
        await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.rst_i.value = 0
    dut._log.info("cascade: N_NARROW=%d, narrow %d/%d, wide %d/%d, seed %d", bench.n, bench.fmt_n.coord_bits,
                  bench.fmt_n.dir_bits, bench.fmt_w.coord_bits, bench.fmt_w.dir_bits, seed)
    return bench


SOURCES = ["random", "setup", "extreme"]
N_QUERIES = max(60, int(300 * config.SCALE))

if cocotb is not None:

    def _load(bench: CascadeBench, n: int, salt) -> dict:
        counts = [0, 0, 0]
        for l in range(bench.n):
            src = SOURCES[l % len(SOURCES)]
            qs = make_queries(src, config.seed("cascade", src, l, salt, bench.fmt_n.coord_bits), n, bench.fmt_n,
                              bench.fmt_w)
            assert qs, f"no queries from {src}"
            for q in qs:
                counts[q.narrow] += 1
            bench.load(l, qs)
        bench.dut._log.info("model: %d certain misses, %d uncertain, %d certain hits", *counts)
        return {"miss": counts[MISS], "uncertain": counts[UNCERTAIN], "hit": counts[HIT]}

    @cocotb.test()
    @cocotb.parametrize(idle=[False, True], backpressure=[False, True])
    async def stream(dut, idle: bool, backpressure: bool) -> None:
        """A different source per lane, idle gaps x stalls on every stream."""
        bench = await _start(dut, config.seed("cascade stream", idle, backpressure), idle, backpressure)
        counts = _load(bench, N_QUERIES, (idle, backpressure))
        assert counts["uncertain"] and counts["hit"] and counts["miss"], f"not every narrow answer occurs: {counts}"
        await bench.run(limit=60 * N_QUERIES + 2000)
        assert bench.answered["escalated"] == counts["uncertain"], (bench.answered, counts)
        assert bench.answered["certain"] == counts["miss"] + counts["hit"], (bench.answered, counts)
        bench.finish(f"stream idle={idle} backpressure={backpressure}")

    @cocotb.test()
    async def reset_mid_stream(dut) -> None:
        """Resets in the middle of the streams drop everything in flight."""
        bench = await _start(dut, config.seed("cascade reset"), True, True)
        _load(bench, N_QUERIES, "reset")
        resets = await bench.run(limit=60 * N_QUERIES + 2000, reset_every=89)
        assert resets == 3, resets
        assert bench.answered["dropped"] > 0, "no query was in flight at any reset"
        bench.finish(f"reset ({resets} resets)")


# ---------------------------------------------------------------------------
# pytest side: one Verilator build per cascade
# ---------------------------------------------------------------------------

# (N_NARROW, narrow C/D, wide C/D, PIPELINE): two 8/8 lanes (fabric
# multipliers) escalating to 16/16; three 6/6 lanes to 12/12 with the
# multipliers' extra register; four 10/10 lanes to 24/24 (split products).
CONFIGS = [
    (2, 8, 8, 16, 16, 0),
    (3, 6, 6, 12, 12, 1),
    (4, 10, 10, 24, 24, 0),
]


def _name(n, nc, nd, wc, wd, pipe) -> str:
    return f"n{n}_{nc}x{nd}_to_{wc}x{wd}{f'_p{pipe}' if pipe else ''}"


@pytest.mark.parametrize("n,nc,nd,wc,wd,pipeline", CONFIGS, ids=[_name(*c) for c in CONFIGS])
def test_pluecker_cascade(n, nc, nd, wc, wd, pipeline) -> None:
    from pluecker_tb.runner import VERILATOR_RTL_ARGS, Build, need_model, rtl_sources

    need_model()
    parameters = {"N_NARROW": n, "NARROW_COORD_BITS": nc, "NARROW_DIR_BITS": nd, "WIDE_COORD_BITS": wc,
                  "WIDE_DIR_BITS": wd, "TAG_BITS": 8, "PIPELINE": pipeline}
    build = Build("cascade_" + _name(n, nc, nd, wc, wd, pipeline))
    build.build(sources=rtl_sources(), hdl_toplevel=TOPLEVEL, parameters=parameters, defines={"ASSERT_ON": 1},
                build_args=VERILATOR_RTL_ARGS)
    build.test("test_pluecker_cascade")
