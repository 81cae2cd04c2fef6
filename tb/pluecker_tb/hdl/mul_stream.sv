// SPDX-License-Identifier: MIT
// Bench top of the multiplier unit tests: one multiplier (LUT = 0:
// rtl/pluecker_mul.sv, on its ECP5 path when PLUECKER_ECP5 is defined;
// LUT = 1: rtl/pluecker_mul_lut.sv) with a valid bit beside it.
//
// The multipliers have no handshake: their contract is the product
// p_o = a_i * b_i exactly LATENCY clock edges after the operands, with
//   pluecker_mul:      LATENCY = 2 + PIPELINE + ADD_STAGES
//                      (ADD_STAGES = number of operands wider than 18 bits)
//   pluecker_mul_lut:  LATENCY = 2 + PIPELINE
// as both modules document it and the intersector's pipeline relies on.
// out_valid_o is in_valid_i delayed by that LATENCY (reset by rst_i), so a
// scoreboard that pairs each valid output with the oldest outstanding
// operand pair checks the product and the latency together.
`default_nettype none

module mul_stream #(
    parameter int WA = 17,
    parameter int WB = 17,
    parameter int PIPELINE = 0,
    parameter bit LUT = 0
) (
    input  wire                    clk_i,
    input  wire                    rst_i,
    input  wire                    in_valid_i,
    input  wire signed [WA-1:0]    a_i,
    input  wire signed [WB-1:0]    b_i,
    output wire                    out_valid_o,
    output wire signed [WA+WB-1:0] p_o
);
  localparam int ADD_STAGES = LUT ? 0 : ((WA > 18) ? 1 : 0) + ((WB > 18) ? 1 : 0);
  localparam int LATENCY = 2 + PIPELINE + ADD_STAGES;
  localparam bit SIGNED = 1;  // both multipliers are signed
`ifdef PLUECKER_ECP5
  localparam bit ECP5 = 1;
`else
  localparam bit ECP5 = 0;
`endif

  if (LUT) begin : g_lut
    pluecker_mul_lut #(.WA(WA), .WB(WB), .PIPELINE(PIPELINE)) u_dut (
        .clk_i(clk_i), .a_i(a_i), .b_i(b_i), .p_o(p_o));
  end else begin : g_mul
    pluecker_mul #(.WA(WA), .WB(WB), .PIPELINE(PIPELINE), .ADD_STAGES(ADD_STAGES)) u_dut (
        .clk_i(clk_i), .a_i(a_i), .b_i(b_i), .p_o(p_o));
  end

  logic [LATENCY-1:0] valid_q;
  always_ff @(posedge clk_i) begin
    if (rst_i) valid_q <= '0;
    else valid_q <= {valid_q[LATENCY-2:0], in_valid_i};
  end
  assign out_valid_o = valid_q[LATENCY-1];
endmodule

`default_nettype wire
