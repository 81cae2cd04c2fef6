# SPDX-License-Identifier: MIT
"""AXI4-Stream pieces of the benches (cocotb side), around cocotbext-axi.

  port_bus(dut, prefix, slave)  an AxiStreamBus of the project's port names
                        (s_axis_tdata_i, s_axis_tready_o, m_axis_tdata_o, ...:
                        cocotbext-axi expects the names without the _i/_o
                        suffix)
  stream_bus(dut, prefix, slave)  a plain valid/ready stream (in_valid_i,
                        in_ready_o, in_data_i) as an AxiStreamBus
  endpoints(bus, clk, rst, seed, idle, backpressure, **kw)
                        the source and monitor on the DUT's input stream and
                        the sink on its output, with the idle and
                        back-pressure pauses of pluecker_tb.traffic
  idle_pauses(gen), stall_pauses(gen)
                        cocotbext-axi pause generators (True = pause this
                        cycle) from the idle and backpressure generators of
                        pluecker_tb.traffic, so that the AXI4-Stream benches
                        see the same traffic as the others
  tdata_of(ports, fields)
                        one query's tdata (an int) from the intersector's port
                        values (pluecker_py.rtl_ports) and the port contract's
                        field offsets (pluecker_py.PortContract.axis_tdata_fields)
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterator

from cocotbext.axi import AxiStreamBus, AxiStreamMonitor, AxiStreamSink, AxiStreamSource

from . import traffic

# (signal, direction on the DUT's slave side); a master port flips them.
_SIGNALS = {"tdata": "i", "tvalid": "i", "tready": "o", "tlast": "i", "tid": "i", "tuser": "i",
            "tkeep": "i", "tdest": "i"}


def _bus(dut, prefix: str, names: dict[str, str]) -> AxiStreamBus:
    """An AxiStreamBus of the ports prefix_<names[signal]>."""
    bus = AxiStreamBus.__new__(AxiStreamBus)
    optional = {k: v for k, v in names.items() if k != "tdata"}
    # cocotb_bus.Bus with {attribute: port name} maps: tdata is required.
    super(AxiStreamBus, bus).__init__(dut, prefix, {"tdata": names["tdata"]}, optional_signals=optional)
    return bus


def port_bus(dut, prefix: str, slave: bool) -> AxiStreamBus:
    """The AXI4-Stream bus `prefix` of the DUT whose ports carry _i/_o
    suffixes; slave=True for an input stream of the DUT."""
    flip = {"i": "o", "o": "i"}
    return _bus(dut, prefix, {sig: f"{sig}_{d if slave else flip[d]}" for sig, d in _SIGNALS.items()})


def stream_bus(dut, prefix: str, slave: bool) -> AxiStreamBus:
    """A plain valid/ready stream (prefix_valid_i, prefix_ready_o,
    prefix_data_i; flipped for an output) as an AxiStreamBus, so that
    cocotbext-axi drives and watches it (with byte_size = the data width)."""
    i, o = ("i", "o") if slave else ("o", "i")
    return _bus(dut, prefix, {"tdata": f"data_{i}", "tvalid": f"valid_{i}", "tready": f"ready_{o}"})


def endpoints(bus: Callable[[bool], AxiStreamBus], clk, rst, seed: int, idle: bool, backpressure: bool, **kw):
    """(source, monitor, sink): AxiStreamSource and AxiStreamMonitor on the
    input stream bus(True), AxiStreamSink on the output stream bus(False)
    (kw: e.g. reset_active_level, byte_size); the source pauses as
    traffic.IdleGaps when `idle`, the sink as traffic.Backpressure when
    `backpressure` (seeded from seed + 1 and seed + 2)."""
    source = AxiStreamSource(bus(True), clk, rst, **kw)
    monitor = AxiStreamMonitor(bus(True), clk, rst, **kw)
    sink = AxiStreamSink(bus(False), clk, rst, **kw)
    if idle:
        source.set_pause_generator(idle_pauses(traffic.IdleGaps(random.Random(seed + 1))))
    if backpressure:
        sink.set_pause_generator(stall_pauses(traffic.Backpressure(random.Random(seed + 2))))
    return source, monitor, sink


def idle_pauses(gen) -> Iterator[bool]:
    """Source pauses from a pluecker_tb.traffic idle generator."""
    while True:
        yield bool(gen.idle_now())


def stall_pauses(gen) -> Iterator[bool]:
    """Sink pauses (ready low) from a pluecker_tb.traffic ready generator."""
    while True:
        yield not gen.ready_now()


def tdata_of(ports: dict[str, int], fields: list[tuple[str, int, int]]) -> int:
    """The port values placed at the contract's offsets; each value must fit
    its field (pluecker_py.rtl_ports checks the operands)."""
    word = 0
    for name, lsb, width in fields:
        value = ports[name]
        if not 0 <= value < (1 << width):
            raise ValueError(f"{name} = {value} does not fit its {width}-bit field")
        word |= value << lsb
    return word


def cycle_of(sim_time: int, clock_ns: int) -> int:
    """The clock cycle of a cocotbext-axi frame time (simulator steps)."""
    from cocotb.utils import get_sim_steps

    return int(sim_time // get_sim_steps(clock_ns, "ns"))


def span_cycles(first, last, clock_ns: int) -> int:
    """Clock cycles from the first beat of frame `first` to the last beat
    of frame `last`, both counted."""
    return cycle_of(last.sim_time_end, clock_ns) - cycle_of(first.sim_time_start, clock_ns) + 1
