# SPDX-License-Identifier: MIT
"""LocalBench: the UnitBench (pluecker_tb.bench: clock and reset, driver,
sink and in-order scoreboard) around rtl/pluecker_local_intersector.sv
(cocotb side), and its stimulus (pluecker_tb.local_vectors).

Widths, mode, CHILDREN and tag width are read back from the DUT's
parameters; the port contract (pluecker_py.LocalPortContract) of those
parameters packs the queries. out_hit_o carries one answer per child box,
compared as a whole with the model's (bit c = child c).
"""

from __future__ import annotations

from . import config
from .bench import UnitBench

TOPLEVEL = "pluecker_local_intersector"
PAYLOAD = ("ray_class_i", "ray_org_i", "ray_dir_i", "ray_end_i", "ray_end_valid_i", "frame_org_i", "frame_exp_i",
           "box_min_i", "box_max_i")


class LocalBench(UnitBench):
    PAYLOAD = PAYLOAD

    def __init__(self, dut, seed: int, idle: bool = False, backpressure: bool = False, traffic_gen=None,
                 mul_style: str = "auto"):
        import pluecker_py as pp

        super().__init__(dut, seed, idle, backpressure, traffic_gen)
        self.box_bits = int(dut.BOX_BITS.value)
        self.dir_bits = int(dut.DIR_BITS.value)
        self.grid_bits = int(dut.GRID_BITS.value)
        self.children = int(dut.CHILDREN.value)
        self.conservative = bool(int(dut.CONSERVATIVE.value))
        self.contract = pp.LocalPortContract(self.box_bits, self.dir_bits, self.grid_bits, self.tag_bits,
                                             self.conservative, mul_style, self.children)
        dut._log.info("DUT BOX_BITS=%d DIR_BITS=%d GRID_BITS=%d CHILDREN=%d TAG_BITS=%d CONSERVATIVE=%d "
                      "MUL_STYLE=%s LATENCY=%d, seed %d, idle=%s backpressure=%s", self.box_bits, self.dir_bits,
                      self.grid_bits, self.children, self.tag_bits, self.conservative, mul_style,
                      int(dut.LATENCY.value), seed, idle, backpressure)


def stimulus(bench: LocalBench, source: str, n: int, salt: object) -> list:
    """n vectors (at most) of a stimulus source (local_vectors.make_stimulus);
    different configurations see different queries."""
    from . import local_vectors as lv

    seed = config.seed("local", source, salt, bench.box_bits, bench.dir_bits, bench.grid_bits, bench.conservative,
                       bench.children)
    stim = lv.make_stimulus(source, bench.contract, seed, n)
    bench.dut._log.info("stimulus: %s, %d vectors, %d queries skipped (outside the format or missing the range)",
                        stim.origin, len(stim.vectors), stim.skipped)
    assert stim.vectors, "no stimulus"
    return stim.vectors
