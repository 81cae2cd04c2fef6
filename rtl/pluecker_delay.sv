// SPDX-License-Identifier: MIT
// A W-bit value delayed by N clock edges (N >= 0; N = 0 is a wire). Data
// only: no reset, no enable. The float units use it to keep operands and
// partial results beside the stages that compute others.
`default_nettype none

module pluecker_delay #(
    parameter int W = 1,
    parameter int N = 1
) (
    input  wire          clk_i,
    input  wire  [W-1:0] d_i,
    output wire  [W-1:0] q_o
);
  if (W < 1 || N < 0) begin : g_bad
    $error("pluecker_delay: W must be at least 1 and N at least 0");
  end

  if (N == 0) begin : g_wire
    assign q_o = d_i;
    wire unused_clk = clk_i;
  end else begin : g_regs
    // Stage s in bits [s*W +: W].
    logic [N*W-1:0] q_q;
    if (N == 1) begin : g_one
      always_ff @(posedge clk_i) q_q <= d_i;
    end else begin : g_more
      always_ff @(posedge clk_i) q_q <= {q_q[(N-1)*W-1:0], d_i};
    end
    assign q_o = q_q[(N-1)*W+:W];
  end
endmodule

`default_nettype wire
