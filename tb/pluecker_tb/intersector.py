# SPDX-License-Identifier: MIT
"""IntersectorBench: the stream bench (pluecker_tb.stream_bench) around
rtl/pluecker_intersector.sv (cocotb side), and its stimulus.

Widths, tag width and mode are read back from the DUT's parameters. Every
expected answer comes from the golden model (pluecker_py, through
pluecker_tb.vectors); nothing here computes a box test.
"""

from __future__ import annotations

import os
from pathlib import Path

from . import config
from .stream_bench import StreamBench

TOPLEVEL = "pluecker_intersector"


class IntersectorBench(StreamBench):
    """The bench of rtl/pluecker_intersector.sv (StreamBench with its
    payload ports); widths, tag width and mode are read back from the DUT's
    parameters."""

    def __init__(self, dut, seed: int, idle: bool = False, backpressure: bool = False, traffic_gen=None):
        from . import vectors as pv

        self.coord_bits = int(dut.COORD_BITS.value)
        self.dir_bits = int(dut.DIR_BITS.value)
        self.conservative = bool(int(dut.CONSERVATIVE.value))
        self.fmt = pv.fixed_format(self.coord_bits, self.dir_bits, self.conservative)
        c3, d3 = 3 * self.coord_bits, 3 * self.dir_bits
        payload = {"ray_class_i": 3, "ray_org_i": c3, "ray_dir_i": d3, "ray_end_i": c3, "ray_end_valid_i": 1,
                   "box_min_i": c3, "box_max_i": c3}
        super().__init__(dut, seed, payload, idle, backpressure, traffic_gen)
        dut._log.info(
            "DUT COORD_BITS=%d DIR_BITS=%d TAG_BITS=%d CONSERVATIVE=%d LATENCY=%s, seed %d, idle=%s backpressure=%s",
            self.coord_bits, self.dir_bits, self.tag_bits, self.conservative, self.latency_text(), seed, idle,
            backpressure)


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
