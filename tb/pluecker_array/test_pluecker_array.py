# SPDX-License-Identifier: MIT
"""cocotb bench for rtl/pluecker_array.sv: small arrays (two to four units,
DSP, fabric and block-RAM table lanes mixed) against the golden model.

Every lane gets its own stimulus, its own idle and back-pressure generators
and its own in-order scoreboard (pluecker_tb.stream.InOrderScoreboard):
each result must be the oldest outstanding query of its lane, with its tag
and the model's answer (pluecker_py, through pluecker_tb.vectors); nothing
assumes the latency. Lanes are driven at once, each query held until its
lane takes it.

Tests
  stream   every lane fed from a different stimulus source, idle gaps x
           output stalls per lane (cocotb.parametrize): all queries come out,
           in order per lane, right
  reset    resets in the middle of the streams: everything in flight in any
           lane vanishes (a result after the reset with no query of its lane
           outstanding is an error); afterwards every lane works again. With
           a reset tree (RST_STAGES = K) the array acts K clocks late: the
           bench holds rst_i K clocks longer and checks that every lane's
           in_ready_o stays low for K clocks after rst_i falls
  rate     no idle, no stall: every lane takes one query per clock, so the
           array answers N queries per clock
"""

from __future__ import annotations

import random

import pytest

from pluecker_tb import config

try:
    import cocotb
    from cocotb.clock import Clock
    from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge

    from pluecker_tb import traffic
    from pluecker_tb import vectors as pv
    from pluecker_tb.stream import InOrderScoreboard
except ImportError:  # pragma: no cover - only the pytest runner part is usable
    cocotb = None

TOPLEVEL = "pluecker_array"
PAYLOAD = ("ray_class_i", "ray_org_i", "ray_dir_i", "ray_end_i", "ray_end_valid_i", "box_min_i", "box_max_i")
SOURCES = ["random", "extreme", "boundary", "raw"]


class ArrayBench:
    """N lanes: per lane a queue of (tag, vector), generators, a scoreboard."""

    def __init__(self, dut, seed: int, idle: bool, backpressure: bool):
        self.dut = dut
        self.n = int(dut.N_DSP.value) + int(dut.N_LUT.value) + int(dut.N_ROM.value)
        self.tag_bits = int(dut.TAG_BITS.value)
        self.coord_bits, self.dir_bits = int(dut.COORD_BITS.value), int(dut.DIR_BITS.value)
        self.conservative = bool(int(dut.CONSERVATIVE.value))
        self.rst_stages = int(dut.RST_STAGES.value)  # the reset tree's delay in clocks
        self.fmt = pv.fixed_format(self.coord_bits, self.dir_bits, self.conservative)
        # Port widths of one lane (the intersector's).
        self.width = {name: len(getattr(dut, name)) // self.n for name in ("in_tag_i", *PAYLOAD)}
        self.rng = random.Random(seed)
        self.idle = [traffic.idle_generator(random.Random(seed + 10 + l), idle) for l in range(self.n)]
        self.ready = [traffic.ready_generator(random.Random(seed + 20 + l), backpressure) for l in range(self.n)]
        self.boards = [InOrderScoreboard(dut._log, self._compare) for _ in range(self.n)]
        self.queues: list[list] = [[] for _ in range(self.n)]
        self.offered: list = [None] * self.n  # (tag, vector) on the lane's inputs
        self.next_tag = [0] * self.n
        self.edge = 0
        self.hits = 0

    def _compare(self, vec, hit: int) -> str | None:
        self.hits += hit
        return None if hit == int(vec.hit) else f"RTL hit={hit}, model hit={int(vec.hit)} for {vec.describe()}"

    def load(self, lane: int, vectors) -> None:
        for v in vectors:
            self.queues[lane].append((self.next_tag[lane], v))
            self.next_tag[lane] = (self.next_tag[lane] + 1) % (1 << self.tag_bits)

    def pending(self) -> bool:
        return any(self.queues) or any(o is not None for o in self.offered) or any(b.expected for b in self.boards)

    def _cycle(self) -> None:
        """Between two rising edges (called at the falling edge): reads the
        DUT's outputs, which come from flops and hold until the next edge,
        drives the inputs of that edge (per lane the held or a new query,
        or idle with random junk on the payload; out_ready_i), and books
        the handshakes that edge will make."""
        dut = self.dut
        in_ready, out_valid = int(dut.in_ready_o.value), int(dut.out_valid_o.value)
        tags, hits = int(dut.out_tag_o.value), int(dut.out_hit_o.value)
        mask = (1 << self.tag_bits) - 1
        self.edge += 1  # the edge these inputs meet
        fields = {name: 0 for name in ("in_tag_i", *PAYLOAD)}
        valid = ready = 0
        for l in range(self.n):
            if self.offered[l] is None and self.queues[l] and not self.idle[l].idle_now():
                self.offered[l] = self.queues[l].pop(0)
            if self.offered[l] is not None:
                tag, vec = self.offered[l]
                values = dict(vec.ports, in_tag_i=tag)
                valid |= 1 << l
            else:
                values = {name: self.rng.getrandbits(w) for name, w in self.width.items()}
            for name, w in self.width.items():
                fields[name] |= (values[name] & ((1 << w) - 1)) << (l * w)
            lane_ready = self.ready[l].ready_now()
            ready |= lane_ready << l
            if self.offered[l] is not None and in_ready >> l & 1:
                self.boards[l].push(tag, vec, self.edge)
                self.offered[l] = None
            if lane_ready and out_valid >> l & 1:
                self.boards[l].check(tags >> (l * self.tag_bits) & mask, hits >> l & 1, self.edge)
        for name, value in fields.items():
            getattr(dut, name).value = value
        dut.in_valid_i.value = valid
        dut.out_ready_i.value = ready

    async def run(self, limit: int, reset_every: int = 0) -> int:
        """Clocks until every lane's queries are answered; with reset_every,
        a two-cycle reset now and then. Returns the resets done."""
        dut, resets, cycles = self.dut, 0, 0
        while self.pending():
            cycles += 1
            assert cycles < limit, f"not drained in {limit} cycles: {[len(b.expected) for b in self.boards]}"
            await FallingEdge(dut.clk_i)
            if reset_every and cycles % reset_every == 0 and resets < 3:
                resets += 1
                await self.reset()
                await FallingEdge(dut.clk_i)
            self._cycle()
        return resets

    async def reset(self, cycles: int = 2) -> None:
        """A synchronous reset (entered at a falling edge): whatever is in
        flight is gone; the held queries are offered again afterwards.
        in_ready_o and out_valid_o are low from the second reset cycle on
        and out_valid_o in the first cycle after it. With a reset tree of K
        stages all of it happens K clocks later: rst_i is held K clocks
        longer, the queries on offer stay on offer for the first K of them
        (the lanes still run; what they take then is dropped by the reset),
        out_ready_i is low, and in_ready_o is low in the K clocks after
        rst_i falls too (the lanes are still in reset)."""
        dut, k_tree = self.dut, self.rst_stages
        if not k_tree:
            dut.in_valid_i.value = 0
        dut.out_ready_i.value = 0
        dut.rst_i.value = 1
        for b in self.boards:
            b.drop_all()
        for k in range(cycles + k_tree):
            await RisingEdge(dut.clk_i)
            self.edge += 1
            await ReadOnly()
            if k >= 1 + k_tree or (cycles == 1 and k == k_tree):
                assert int(dut.in_ready_o.value) == 0 and int(dut.out_valid_o.value) == 0, "ready/valid in reset"
            await FallingEdge(dut.clk_i)
            if k == k_tree - 1:
                # The lanes are in reset from now on: only now may an offer
                # be withdrawn (what they took meanwhile is dropped).
                dut.in_valid_i.value = 0
        dut.rst_i.value = 0
        for k in range(k_tree + 1):
            await RisingEdge(dut.clk_i)
            self.edge += 1
            await ReadOnly()
            assert int(dut.out_valid_o.value) == 0, f"out_valid_o {k} clocks after a reset"
            if k < k_tree:
                assert int(dut.in_ready_o.value) == 0, f"in_ready_o {k} clocks after rst_i fell, {k_tree} reset stages"
            if k < k_tree:
                await FallingEdge(dut.clk_i)

    def finish(self, what: str) -> None:
        for l, b in enumerate(self.boards):
            b.assert_clean()
        self.dut._log.info("%s: %d lanes, compared %s, %d hits, dropped %s, %d edges", what, self.n,
                           [b.compared for b in self.boards], self.hits, [b.dropped for b in self.boards],
                           self.edge)


async def _start(dut, seed: int, idle: bool, backpressure: bool) -> ArrayBench:
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    bench = ArrayBench(dut, seed, idle, backpressure)
    dut.in_valid_i.value = 0
    dut.out_ready_i.value = 0
    dut.rst_i.value = 1
    for _ in range(3 + bench.rst_stages):
        await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.rst_i.value = 0
    dut._log.info("array: N_DSP=%d N_LUT=%d N_ROM=%d COORD_BITS=%d DIR_BITS=%d CONSERVATIVE=%d RST_STAGES=%d, "
                  "seed %d", int(dut.N_DSP.value), int(dut.N_LUT.value), int(dut.N_ROM.value), bench.coord_bits,
                  bench.dir_bits, bench.conservative,
                  bench.rst_stages, seed)
    return bench


def _vectors(bench: ArrayBench, lane: int, source: str, n: int, salt) -> list:
    from pathlib import Path
    import os

    seed = config.seed("array", source, lane, salt, bench.coord_bits, bench.dir_bits)
    stim = pv.make_stimulus(source, bench.fmt, seed, n, Path(os.environ.get("PLUECKER_TB_WORK", ".")))
    assert stim.vectors, f"no stimulus from {source}"
    return stim.vectors


N_QUERIES = max(60, int(300 * config.SCALE))

if cocotb is not None:

    @cocotb.test()
    @cocotb.parametrize(idle=[False, True], backpressure=[False, True])
    async def stream(dut, idle: bool, backpressure: bool) -> None:
        """A different stimulus source per lane, idle gaps x stalls per lane."""
        bench = await _start(dut, config.seed("array stream", idle, backpressure), idle, backpressure)
        total = 0
        for l in range(bench.n):
            vecs = _vectors(bench, l, SOURCES[l % len(SOURCES)], N_QUERIES, (idle, backpressure))
            bench.load(l, vecs)
            total += len(vecs)
        await bench.run(limit=40 * N_QUERIES + 2000)
        assert sum(b.compared for b in bench.boards) == total, f"compared {[b.compared for b in bench.boards]}"
        bench.finish(f"stream idle={idle} backpressure={backpressure}")

    @cocotb.test()
    async def reset_mid_stream(dut) -> None:
        """Resets in the middle of the streams drop everything in flight."""
        bench = await _start(dut, config.seed("array reset"), True, True)
        for l in range(bench.n):
            bench.load(l, _vectors(bench, l, "random", N_QUERIES, "reset"))
        resets = await bench.run(limit=40 * N_QUERIES + 2000, reset_every=97)
        assert resets == 3, resets
        assert sum(b.dropped for b in bench.boards) > 0, "no query was in flight at any reset"
        bench.finish(f"reset ({resets} resets)")

    @cocotb.test()
    async def rate(dut) -> None:
        """Without idle or stalls every lane takes a query every clock."""
        bench = await _start(dut, config.seed("array rate"), False, False)
        for l in range(bench.n):
            bench.load(l, _vectors(bench, l, "random", N_QUERIES, "rate"))
        await bench.run(limit=40 * N_QUERIES + 2000)
        for l, b in enumerate(bench.boards):
            edges = b.in_edges
            assert edges == list(range(edges[0], edges[0] + len(edges))), f"lane {l} missed a clock"
        bench.finish(f"rate ({bench.n} queries per clock)")


# ---------------------------------------------------------------------------
# pytest side: one Verilator build per array
# ---------------------------------------------------------------------------

# (N_DSP, N_LUT, N_ROM, COORD_BITS, DIR_BITS, CONSERVATIVE, PIPELINE,
# RST_STAGES, ecp5): a mixed pair at 16/16 (the DSP lane on the MULT18X18D
# model), three fabric lanes at 8/8, a mixed four with the multipliers'
# extra register and a two-stage reset tree, and the mixed 6/6 chip's
# lanes (PIPELINE = 2: DSP lanes with two products per MULT18X18D model,
# table lanes on the DP16KD model).
CONFIGS = [
    (1, 1, 0, 16, 16, 1, 0, 0, True),
    (0, 3, 0, 8, 8, 0, 0, 0, False),
    (2, 2, 0, 10, 12, 1, 1, 2, False),
    (2, 1, 1, 6, 6, 1, 2, 1, True),
]


def _name(nd, nl, nr, c, d, cons, pipe, rst, ecp5) -> str:
    return (f"d{nd}_l{nl}{f'_t{nr}' if nr else ''}_c{c}_d{d}_{'cons' if cons else 'near'}"
            f"{f'_p{pipe}' if pipe else ''}{f'_r{rst}' if rst else ''}{'_ecp5' if ecp5 else ''}")


@pytest.mark.parametrize("n_dsp,n_lut,n_rom,coord_bits,dir_bits,conservative,pipeline,rst_stages,ecp5", CONFIGS,
                         ids=[_name(*c) for c in CONFIGS])
def test_pluecker_array(n_dsp, n_lut, n_rom, coord_bits, dir_bits, conservative, pipeline, rst_stages,
                        ecp5) -> None:
    from pluecker_tb import ecp5 as ecp5_models
    from pluecker_tb.runner import VERILATOR_RTL_ARGS, Build, need_model, rtl_sources

    need_model()
    parameters = {"N_DSP": n_dsp, "N_LUT": n_lut, "N_ROM": n_rom, "COORD_BITS": coord_bits, "DIR_BITS": dir_bits,
                  "TAG_BITS": 8, "CONSERVATIVE": conservative, "PIPELINE": pipeline, "RST_STAGES": rst_stages}
    sources, defines = rtl_sources(), {"ASSERT_ON": 1}
    if ecp5:
        sources += ecp5_models.model_sources()
        defines["PLUECKER_ECP5"] = 1
    build = Build("array_" + _name(n_dsp, n_lut, n_rom, coord_bits, dir_bits, conservative, pipeline, rst_stages,
                                   ecp5))
    build.build(sources=sources, hdl_toplevel=TOPLEVEL, parameters=parameters, defines=defines,
                build_args=VERILATOR_RTL_ARGS)
    build.test("test_pluecker_array")
