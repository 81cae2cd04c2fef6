// SPDX-License-Identifier: MIT
// Bench top of the node set-up's unit test: rtl/pluecker_local_frame.sv
// (on its ECP5 path when PLUECKER_ECP5 is defined) with a valid bit beside
// it. The module has no handshake: its contract is the node ray of the
// inputs exactly LATENCY = 9 + MUL_ADD clock edges after them, MUL_ADD = 0
// in fabric (MUL_LUT) or the number of moment-product operands (G+3, G+1
// bits) wider than 18, as the module documents it and
// pluecker_local_intersector's pipeline relies on. out_valid_o is in_valid_i
// delayed by that LATENCY (reset by rst_i), so a scoreboard that pairs each
// valid output with the oldest outstanding input checks the node ray and
// the latency together.
`default_nettype none

module local_frame_stream #(
    parameter int BOX_BITS = 8,
    parameter int DIR_BITS = 11,
    parameter int GRID_BITS = 32,
    parameter bit CONSERVATIVE = 1,
    parameter bit MUL_LUT = 0
) (
    input wire clk_i,
    input wire rst_i,
    input wire in_valid_i,

    input wire [             2:0] ray_class_i,
    input wire [ 3*GRID_BITS-1:0] ray_org_i,
    input wire [ 3*GRID_BITS-1:0] ray_dir_i,
    input wire [ 3*GRID_BITS-1:0] ray_end_i,
    input wire                    ray_end_valid_i,
    input wire [ 3*GRID_BITS-1:0] frame_org_i,
    input wire [3*$clog2(GRID_BITS-BOX_BITS+2)-1:0] frame_exp_i,

    output wire                                out_valid_o,
    output wire [                         2:0] cls_o,
    output wire [              3*DIR_BITS-1:0] dir_o,
    output wire [6*(BOX_BITS+DIR_BITS+2)-1:0] w_o,
    output wire [          3*(BOX_BITS+2)-1:0] org_o,
    output wire [          3*(BOX_BITS+2)-1:0] end_o,
    output wire                                end_valid_o
);
  localparam int MUL_ADD = MUL_LUT ? 0 : ((GRID_BITS + 3 > 18) ? 1 : 0) + ((GRID_BITS + 1 > 18) ? 1 : 0);
  localparam int LATENCY = 9 + MUL_ADD;
`ifdef PLUECKER_ECP5
  localparam bit ECP5 = 1;
`else
  localparam bit ECP5 = 0;
`endif

  pluecker_local_frame #(
      .BOX_BITS(BOX_BITS),
      .DIR_BITS(DIR_BITS),
      .GRID_BITS(GRID_BITS),
      .CONSERVATIVE(CONSERVATIVE),
      .MUL_LUT(MUL_LUT)
  ) u_dut (
      .clk_i(clk_i),
      .ray_class_i(ray_class_i),
      .ray_org_i(ray_org_i),
      .ray_dir_i(ray_dir_i),
      .ray_end_i(ray_end_i),
      .ray_end_valid_i(ray_end_valid_i),
      .frame_org_i(frame_org_i),
      .frame_exp_i(frame_exp_i),
      .cls_o(cls_o),
      .dir_o(dir_o),
      .w_o(w_o),
      .org_o(org_o),
      .end_o(end_o),
      .end_valid_o(end_valid_o)
  );

  logic [LATENCY-1:0] valid_q;
  always_ff @(posedge clk_i) begin
    if (rst_i) valid_q <= '0;
    else valid_q <= {valid_q[LATENCY-2:0], in_valid_i};
  end
  assign out_valid_o = valid_q[LATENCY-1];
endmodule

`default_nettype wire
