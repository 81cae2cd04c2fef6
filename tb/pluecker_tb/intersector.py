# SPDX-License-Identifier: MIT
"""IntersectorBench: the UnitBench (pluecker_tb.bench: clock and reset,
driver, sink and in-order scoreboard) around rtl/pluecker_intersector.sv
(cocotb side), and its stimulus.

Widths, tag width and mode are read back from the DUT's parameters. Every
expected answer comes from the golden model (pluecker_py, through
pluecker_tb.vectors); nothing here computes a box test. Results are matched
by order and tag; nothing assumes the pipeline latency (the checks every
cycle: pluecker_tb.bench).
"""

from __future__ import annotations

import os
from pathlib import Path

from . import config
from .bench import UnitBench

TOPLEVEL = "pluecker_intersector"
PAYLOAD = ("ray_class_i", "ray_org_i", "ray_dir_i", "ray_end_i", "ray_end_valid_i", "box_min_i", "box_max_i")


class IntersectorBench(UnitBench):
    """UnitBench around rtl/pluecker_intersector.sv; widths, tag width and
    mode read back from the DUT's parameters."""

    PAYLOAD = PAYLOAD

    def __init__(self, dut, seed: int, idle: bool = False, backpressure: bool = False, traffic_gen=None):
        from . import vectors as pv

        super().__init__(dut, seed, idle, backpressure, traffic_gen)
        self.coord_bits = int(dut.COORD_BITS.value)
        self.dir_bits = int(dut.DIR_BITS.value)
        self.conservative = bool(int(dut.CONSERVATIVE.value))
        self.fmt = pv.fixed_format(self.coord_bits, self.dir_bits, self.conservative)
        try:  # a parameter the stress bench's flattened netlist does not keep
            self.ternary = bool(int(dut.TERNARY.value))
        except AttributeError:
            self.ternary = False
        try:  # a localparam: not in a flattened netlist (the stress bench's Icarus run)
            latency = str(int(dut.LATENCY.value))
        except AttributeError:
            latency = "?"
        dut._log.info(
            "DUT COORD_BITS=%d DIR_BITS=%d TAG_BITS=%d CONSERVATIVE=%d TERNARY=%d LATENCY=%s, seed %d, idle=%s "
            "backpressure=%s", self.coord_bits, self.dir_bits, self.tag_bits, self.conservative, self.ternary, latency,
            seed, idle, backpressure)

    def _transfer(self, edge: int) -> None:
        """A TERNARY unit's answer is two bits: (out_hit_o << 1) | out_strict_o."""
        if not self.ternary:
            super()._transfer(edge)
            return
        dut = self.dut
        self.scoreboard.check(int(dut.out_tag_o.value), (int(dut.out_hit_o.value) << 1) | int(dut.out_strict_o.value),
                              edge)


def stimulus(bench: IntersectorBench, source: str, n: int, salt: object) -> list:
    """n vectors of a stimulus source (see vectors.make_stimulus); different
    widths and modes see different queries."""
    from . import vectors as pv

    work = Path(os.environ.get("PLUECKER_TB_WORK", "."))
    seed = config.seed(source, salt, bench.coord_bits, bench.dir_bits, bench.conservative)
    stim = pv.make_stimulus(source, bench.fmt, seed, n, work)
    bench.dut._log.info("stimulus: %s, %d vectors, %d queries skipped (outside the format)",
                        stim.origin, len(stim.vectors), stim.skipped)
    assert stim.vectors, "no stimulus"
    if bench.ternary:
        vectors = pv.ternary_vectors(stim.vectors, bench.fmt)
        counts = [sum(1 for v in vectors if v.hit == a) for a in (0, 2, 3)]
        bench.dut._log.info("ternary answers of the model: %d certain misses, %d uncertain, %d certain hits", *counts)
        return vectors
    return stim.vectors
