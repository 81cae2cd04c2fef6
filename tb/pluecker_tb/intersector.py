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
        try:  # a localparam: not in a flattened netlist (the stress bench's Icarus run)
            latency = str(int(dut.LATENCY.value))
        except AttributeError:
            latency = "?"
        dut._log.info(
            "DUT COORD_BITS=%d DIR_BITS=%d TAG_BITS=%d CONSERVATIVE=%d LATENCY=%s, seed %d, idle=%s backpressure=%s",
            self.coord_bits, self.dir_bits, self.tag_bits, self.conservative, latency, seed, idle, backpressure)


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
    return stim.vectors
