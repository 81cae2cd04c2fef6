// SPDX-License-Identifier: MIT
// Out-of-context timing harness for the ECP5 flow (scripts/synth.py).
//
// Registers every port of pluecker_intersector once, so that every timed path
// of the placed design starts and ends at a flip-flop: the figures nextpnr
// reports are the intersector's own register-to-register paths plus one level
// of routing to and from these harness registers, never pad or IO timing.
// nextpnr runs with --out-of-context (no IO buffers), so the ~270 port bits
// need no package pins. The parameters are the intersector's, passed on.
//
// The harness is for timing and utilisation only: the extra register stage
// delays in_ready_o by a cycle, so it does not keep the valid/ready contract
// and must not be simulated as the intersector. Its flip-flops are named
// ooc_*_q; scripts/synth.py counts them (by source file) apart from the
// intersector's.
`default_nettype none

module ooc_wrapper #(
    parameter int COORD_BITS = 16,
    parameter int DIR_BITS = 16,
    parameter int TAG_BITS = 16,
    parameter bit CONSERVATIVE = 1,
    parameter MUL_STYLE = "auto",
    parameter int PIPELINE = 0,
    parameter bit TERNARY = 0
) (
    input wire clk_i,
    input wire rst_i,

    input  wire                    in_valid_i,
    output wire                    in_ready_o,
    input  wire [    TAG_BITS-1:0] in_tag_i,
    input  wire [             2:0] ray_class_i,
    input  wire [3*COORD_BITS-1:0] ray_org_i,
    input  wire [  3*DIR_BITS-1:0] ray_dir_i,
    input  wire [3*COORD_BITS-1:0] ray_end_i,
    input  wire                    ray_end_valid_i,
    input  wire [3*COORD_BITS-1:0] box_min_i,
    input  wire [3*COORD_BITS-1:0] box_max_i,

    output wire                out_valid_o,
    input  wire                out_ready_i,
    output wire [TAG_BITS-1:0] out_tag_o,
    output wire                out_hit_o,
    output wire                out_strict_o
);
  localparam int CW = 3 * COORD_BITS;
  localparam int DW = 3 * DIR_BITS;

  // Control flops (reset): ooc_rst_q, ooc_in_valid_q, ooc_out_ready_q,
  // ooc_in_ready_q, ooc_out_valid_q. Data flops (no reset): the rest.
  logic ooc_rst_q;
  logic ooc_in_valid_q, ooc_out_ready_q;
  logic [TAG_BITS-1:0] ooc_in_tag_q;
  logic [2:0] ooc_ray_class_q;
  logic [CW-1:0] ooc_ray_org_q, ooc_ray_end_q, ooc_box_min_q, ooc_box_max_q;
  logic [DW-1:0] ooc_ray_dir_q;
  logic ooc_ray_end_valid_q;
  logic ooc_in_ready_q, ooc_out_valid_q, ooc_out_hit_q, ooc_out_strict_q;
  logic [TAG_BITS-1:0] ooc_out_tag_q;

  wire dut_in_ready, dut_out_valid, dut_out_hit, dut_out_strict;
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
    ooc_in_tag_q        <= in_tag_i;
    ooc_ray_class_q     <= ray_class_i;
    ooc_ray_org_q       <= ray_org_i;
    ooc_ray_dir_q       <= ray_dir_i;
    ooc_ray_end_q       <= ray_end_i;
    ooc_ray_end_valid_q <= ray_end_valid_i;
    ooc_box_min_q       <= box_min_i;
    ooc_box_max_q       <= box_max_i;
    ooc_out_tag_q       <= dut_out_tag;
    ooc_out_hit_q       <= dut_out_hit;
    ooc_out_strict_q    <= dut_out_strict;
  end

  pluecker_intersector #(
      .COORD_BITS(COORD_BITS),
      .DIR_BITS(DIR_BITS),
      .TAG_BITS(TAG_BITS),
      .CONSERVATIVE(CONSERVATIVE),
      .MUL_STYLE(MUL_STYLE),
      .PIPELINE(PIPELINE),
      .TERNARY(TERNARY)
  ) u_dut (
      .clk_i(clk_i),
      .rst_i(ooc_rst_q),
      .in_valid_i(ooc_in_valid_q),
      .in_ready_o(dut_in_ready),
      .in_tag_i(ooc_in_tag_q),
      .ray_class_i(ooc_ray_class_q),
      .ray_org_i(ooc_ray_org_q),
      .ray_dir_i(ooc_ray_dir_q),
      .ray_end_i(ooc_ray_end_q),
      .ray_end_valid_i(ooc_ray_end_valid_q),
      .box_min_i(ooc_box_min_q),
      .box_max_i(ooc_box_max_q),
      .out_valid_o(dut_out_valid),
      .out_ready_i(ooc_out_ready_q),
      .out_tag_o(dut_out_tag),
      .out_hit_o(dut_out_hit),
      .out_strict_o(dut_out_strict)
  );

  assign in_ready_o  = ooc_in_ready_q;
  assign out_valid_o = ooc_out_valid_q;
  assign out_tag_o   = ooc_out_tag_q;
  assign out_hit_o   = ooc_out_hit_q;
  assign out_strict_o = ooc_out_strict_q;
endmodule

`default_nettype wire
