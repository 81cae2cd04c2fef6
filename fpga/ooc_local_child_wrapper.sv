// SPDX-License-Identifier: MIT
// Out-of-context timing harness of pluecker_local_child alone, the per-child
// part of the local unit (scripts/synth.py --local --part child): every port
// registered once, as in fpga/ooc_local_wrapper.sv, so that its cost and
// Fmax can be told apart from the node set-up's. The multiplier style is
// the unit's (MUL_STYLE "dsp": pluecker_mul, else pluecker_mul_lut). For
// timing and utilisation only. Its flip-flops are named ooc_*_q.
`default_nettype none

module ooc_local_child_wrapper #(
    parameter int BOX_BITS = 8,
    parameter int DIR_BITS = 11,
    parameter bit CONSERVATIVE = 1,
    parameter MUL_STYLE = "auto"
) (
    input wire clk_i,

    input wire [                         2:0] cls_i,
    input wire [              3*DIR_BITS-1:0] dir_i,
    input wire [6*(BOX_BITS+DIR_BITS+2)-1:0] w_i,
    input wire [          3*(BOX_BITS+2)-1:0] org_i,
    input wire [          3*(BOX_BITS+2)-1:0] end_i,
    input wire                                end_valid_i,
    input wire [              3*BOX_BITS-1:0] box_min_i,
    input wire [              3*BOX_BITS-1:0] box_max_i,

    output wire hit_o
);
  localparam bit MUL_LUT = 32'(MUL_STYLE) != 32'("dsp");

  logic [2:0] ooc_cls_q;
  logic [3*DIR_BITS-1:0] ooc_dir_q;
  logic [6*(BOX_BITS+DIR_BITS+2)-1:0] ooc_w_q;
  logic [3*(BOX_BITS+2)-1:0] ooc_org_q, ooc_end_q;
  logic ooc_end_valid_q;
  logic [3*BOX_BITS-1:0] ooc_box_min_q, ooc_box_max_q;
  logic ooc_hit_q;
  wire dut_hit;

  always_ff @(posedge clk_i) begin
    ooc_cls_q       <= cls_i;
    ooc_dir_q       <= dir_i;
    ooc_w_q         <= w_i;
    ooc_org_q       <= org_i;
    ooc_end_q       <= end_i;
    ooc_end_valid_q <= end_valid_i;
    ooc_box_min_q   <= box_min_i;
    ooc_box_max_q   <= box_max_i;
    ooc_hit_q       <= dut_hit;
  end

  pluecker_local_child #(
      .BOX_BITS(BOX_BITS),
      .DIR_BITS(DIR_BITS),
      .CONSERVATIVE(CONSERVATIVE),
      .MUL_LUT(MUL_LUT)
  ) u_dut (
      .clk_i(clk_i),
      .cls_i(ooc_cls_q),
      .dir_i(ooc_dir_q),
      .w_i(ooc_w_q),
      .org_i(ooc_org_q),
      .end_i(ooc_end_q),
      .end_valid_i(ooc_end_valid_q),
      .box_min_i(ooc_box_min_q),
      .box_max_i(ooc_box_max_q),
      .hit_o(dut_hit)
  );

  assign hit_o = ooc_hit_q;
endmodule

`default_nettype wire
