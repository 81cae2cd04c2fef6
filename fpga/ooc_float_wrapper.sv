// SPDX-License-Identifier: MIT
// Out-of-context timing harness of the binary32 units for the ECP5 flow
// (scripts/synth.py --unit float|smits), as fpga/ooc_wrapper.sv is for the
// fixed-point intersector: every port of the unit is registered once, so
// every timed path starts and ends at a flip-flop (nextpnr runs with
// --out-of-context: no IO buffers, no pins). UNIT "float" is
// pluecker_float_intersector, "smits" pluecker_smits_intersector; the other
// parameters are passed on. The payload ports are concatenated into one bus
// (in_data_i: ray_class_i first, in port order, at the top).
//
// For timing and utilisation only: the extra register stage delays
// in_ready_o by a cycle, so it does not keep the valid/ready contract. Its
// flip-flops are named ooc_*_q; scripts/synth.py counts them (by source
// file) apart from the unit's.
`default_nettype none

module ooc_float_wrapper #(
    parameter UNIT = "float",
    parameter int TAG_BITS = 16,
    parameter bit CONSERVATIVE = 0,
    parameter int MUL_DSP = pluecker_contract_float_pkg::DEFAULT_MUL_DSP,
    // Payload bits (derived from UNIT; checked below): class, origin, then
    // float: direction, end, end valid; smits: inverse direction, tmax; box.
    parameter int IN_W = (40'(UNIT) == 40'("smits")) ? 3 + 4 * 96 + 32 : 3 + 5 * 96 + 1
) (
    input wire clk_i,
    input wire rst_i,

    input  wire                in_valid_i,
    output wire                in_ready_o,
    input  wire [TAG_BITS-1:0] in_tag_i,
    input  wire [   IN_W-1:0] in_data_i,

    output wire                out_valid_o,
    input  wire                out_ready_i,
    output wire [TAG_BITS-1:0] out_tag_o,
    output wire                out_hit_o
);
  // UNIT compared as a 40-bit pattern (a string parameter of up to five
  // characters, without width warnings).
  localparam logic [39:0] UNIT_S = 40'(UNIT);
  localparam bit SMITS = UNIT_S == 40'("smits");
  if (!SMITS && UNIT_S != 40'("float")) begin : g_bad_unit
    $error("ooc_float_wrapper: parameter UNIT must be float or smits");
  end
  if (IN_W != (SMITS ? 3 + 4 * 96 + 32 : 3 + 5 * 96 + 1)) begin : g_bad_in_w
    $error("ooc_float_wrapper: parameter IN_W must be left at its default (the unit's payload width)");
  end

  // Control flops (reset): ooc_rst_q, ooc_in_valid_q, ooc_out_ready_q,
  // ooc_in_ready_q, ooc_out_valid_q. Data flops (no reset): the rest.
  logic ooc_rst_q;
  logic ooc_in_valid_q, ooc_out_ready_q, ooc_in_ready_q, ooc_out_valid_q, ooc_out_hit_q;
  logic [TAG_BITS-1:0] ooc_in_tag_q, ooc_out_tag_q;
  logic [IN_W-1:0] ooc_in_data_q;

  wire dut_in_ready, dut_out_valid, dut_out_hit;
  wire [TAG_BITS-1:0] dut_out_tag;

  always_ff @(posedge clk_i) begin
    ooc_rst_q <= rst_i;
    if (ooc_rst_q) begin
      ooc_in_valid_q  <= 1'b0;
      ooc_out_ready_q <= 1'b0;
      ooc_in_ready_q  <= 1'b0;
      ooc_out_valid_q <= 1'b0;
    end else begin
      ooc_in_valid_q  <= in_valid_i;
      ooc_out_ready_q <= out_ready_i;
      ooc_in_ready_q  <= dut_in_ready;
      ooc_out_valid_q <= dut_out_valid;
    end
  end

  always_ff @(posedge clk_i) begin
    ooc_in_tag_q  <= in_tag_i;
    ooc_in_data_q <= in_data_i;
    ooc_out_tag_q <= dut_out_tag;
    ooc_out_hit_q <= dut_out_hit;
  end

  if (SMITS) begin : g_smits
    wire [2:0] cls;
    wire [95:0] org, inv, lo, hi;
    wire [31:0] tmax;
    assign {cls, org, inv, tmax, lo, hi} = ooc_in_data_q;
    pluecker_smits_intersector #(.TAG_BITS(TAG_BITS), .MUL_DSP(MUL_DSP)) u_dut (
        .clk_i(clk_i), .rst_i(ooc_rst_q), .in_valid_i(ooc_in_valid_q), .in_ready_o(dut_in_ready),
        .in_tag_i(ooc_in_tag_q), .ray_class_i(cls), .ray_org_i(org), .ray_inv_i(inv), .ray_tmax_i(tmax),
        .box_min_i(lo), .box_max_i(hi), .out_valid_o(dut_out_valid), .out_ready_i(ooc_out_ready_q),
        .out_tag_o(dut_out_tag), .out_hit_o(dut_out_hit));
  end else begin : g_float
    wire [2:0] cls;
    wire [95:0] org, dir, e, lo, hi;
    wire endv;
    assign {cls, org, dir, e, endv, lo, hi} = ooc_in_data_q;
    pluecker_float_intersector #(.TAG_BITS(TAG_BITS), .CONSERVATIVE(CONSERVATIVE), .MUL_DSP(MUL_DSP)) u_dut (
        .clk_i(clk_i), .rst_i(ooc_rst_q), .in_valid_i(ooc_in_valid_q), .in_ready_o(dut_in_ready),
        .in_tag_i(ooc_in_tag_q), .ray_class_i(cls), .ray_org_i(org), .ray_dir_i(dir), .ray_end_i(e),
        .ray_end_valid_i(endv), .box_min_i(lo), .box_max_i(hi), .out_valid_o(dut_out_valid),
        .out_ready_i(ooc_out_ready_q), .out_tag_o(dut_out_tag), .out_hit_o(dut_out_hit));
  end

  assign in_ready_o  = ooc_in_ready_q;
  assign out_valid_o = ooc_out_valid_q;
  assign out_tag_o   = ooc_out_tag_q;
  assign out_hit_o   = ooc_out_hit_q;
endmodule

`default_nettype wire
