// SPDX-License-Identifier: MIT
// Bench top of the table multiplier's unit test: rtl/pluecker_mul_rom.sv
// (on its ECP5 path, one DP16KD instance, when PLUECKER_ECP5 is defined)
// with a valid bit beside it, delayed by the module's documented LATENCY of
// 4 clock edges (reset by rst_i), so a scoreboard that pairs each valid
// output with the oldest outstanding operands checks the product and the
// latency together.
`default_nettype none

module mul_rom_stream #(
    parameter int WA = 7,
    parameter int WU = 6
) (
    input  wire                  clk_i,
    input  wire                  rst_i,
    input  wire                  in_valid_i,
    input  wire signed [WA-1:0]  a_i,
    input  wire        [WU-1:0]  b_i,
    output wire                  out_valid_o,
    output wire signed [WA+WU:0] p_o
);
  localparam int LATENCY = 4;
`ifdef PLUECKER_ECP5
  localparam bit ECP5 = 1;
`else
  localparam bit ECP5 = 0;
`endif

  pluecker_mul_rom #(.WA(WA), .WU(WU)) u_dut (.clk_i(clk_i), .a_i(a_i), .b_i(b_i), .p_o(p_o));

  logic [LATENCY-1:0] valid_q;
  always_ff @(posedge clk_i) begin
    if (rst_i) valid_q <= '0;
    else valid_q <= {valid_q[LATENCY-2:0], in_valid_i};
  end
  assign out_valid_o = valid_q[LATENCY-1];
endmodule

`default_nettype wire
