// SPDX-License-Identifier: MIT
// Bench top of the child datapath's unit test: rtl/pluecker_local_child.sv
// (on its ECP5 path when PLUECKER_ECP5 is defined) with a valid bit beside
// it. The module has no handshake: its contract is hit_o for the inputs
// exactly LATENCY = 4 + MUL_ADD clock edges after them, MUL_ADD = 0 in
// fabric (MUL_LUT) or the number of product operands (D+1, K+1 bits) wider
// than 18, as the module documents it and pluecker_local_intersector's
// pipeline relies on. out_valid_o is in_valid_i delayed by that LATENCY
// (reset by rst_i).
`default_nettype none

module local_child_stream #(
    parameter int BOX_BITS = 8,
    parameter int DIR_BITS = 11,
    parameter bit CONSERVATIVE = 1,
    parameter bit MUL_LUT = 1
) (
    input wire clk_i,
    input wire rst_i,
    input wire in_valid_i,

    input wire [                         2:0] cls_i,
    input wire [              3*DIR_BITS-1:0] dir_i,
    input wire [6*(BOX_BITS+DIR_BITS+2)-1:0] w_i,
    input wire [          3*(BOX_BITS+2)-1:0] org_i,
    input wire [          3*(BOX_BITS+2)-1:0] end_i,
    input wire                                end_valid_i,
    input wire [              3*BOX_BITS-1:0] box_min_i,
    input wire [              3*BOX_BITS-1:0] box_max_i,

    output wire out_valid_o,
    output wire hit_o
);
  localparam int MUL_ADD = MUL_LUT ? 0 : ((DIR_BITS + 1 > 18) ? 1 : 0) + ((BOX_BITS + 1 > 18) ? 1 : 0);
  localparam int LATENCY = 4 + MUL_ADD;
`ifdef PLUECKER_ECP5
  localparam bit ECP5 = 1;
`else
  localparam bit ECP5 = 0;
`endif

  pluecker_local_child #(
      .BOX_BITS(BOX_BITS),
      .DIR_BITS(DIR_BITS),
      .CONSERVATIVE(CONSERVATIVE),
      .MUL_LUT(MUL_LUT)
  ) u_dut (
      .clk_i(clk_i),
      .cls_i(cls_i),
      .dir_i(dir_i),
      .w_i(w_i),
      .org_i(org_i),
      .end_i(end_i),
      .end_valid_i(end_valid_i),
      .box_min_i(box_min_i),
      .box_max_i(box_max_i),
      .hit_o(hit_o)
  );

  logic [LATENCY-1:0] valid_q;
  always_ff @(posedge clk_i) begin
    if (rst_i) valid_q <= '0;
    else valid_q <= {valid_q[LATENCY-2:0], in_valid_i};
  end
  assign out_valid_o = valid_q[LATENCY-1];
endmodule

`default_nettype wire
