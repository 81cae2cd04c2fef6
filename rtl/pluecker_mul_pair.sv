// SPDX-License-Identifier: MIT
// Two registered products with one shared signed operand in one MULT18X18D:
//   p0_o = a_i * b0_i, p1_o = a_i * b1_i
// (a_i WA-bit two's complement, b0_i and b1_i WU-bit unsigned), 4 clock
// edges after the operands, as pluecker_mul with PIPELINE = 2.
//
// The intersector multiplies each of its six differences A_i, B_j by two
// direction magnitudes (A_i by D_j and D_k, B_j by D_i and D_k), so at
// 6/6 bits six blocks do its twelve products (pluecker_intersector,
// MUL_STYLE "dsp", PIPELINE = 2): twice the DSP units per chip.
//
// Packing. With K = WA - 1 + WU, one block multiplies a (signed) by
//   B = b0 + b1 * 2^K  (unsigned; fits the 18-bit port when K + WU <= 18,
//                       i.e. COORD_BITS + 2 DIR_BITS <= 18 in the unit)
// so P = a*B = lo + hi * 2^K with lo = a*b0, hi = a*b1. Since
// |lo| <= 2^(WA-1) (2^WU - 1) < 2^K, lo is the (K+1)-bit two's complement
// {s, P[K-1:0]} with s = (lo < 0) = (a < 0 and b0 != 0), and the high
// bits of P are floor(P / 2^K) = hi - s, so hi = P[..:K] + s. s is taken
// from the operands and travels beside the block (3 flops); the fabric
// output register (the PIPELINE = 2 register of pluecker_mul) holds both
// products after the increment. Exact for every operand value.
//
// The block is pluecker_dsp18 (on ECP5 one MULT18X18D, SIGNEDA = 1,
// SIGNEDB = 0, input, pipeline and output registers clocked; elsewhere a
// generic 18 x 18 `*` with the same registers), so every simulation, with
// or without the MULT18X18D model, checks the packing arithmetic.
`default_nettype none

module pluecker_mul_pair #(
    parameter int WA = 7,  // signed operand a_i
    parameter int WU = 6,  // unsigned operands b0_i, b1_i
    // Product width (signed, as pluecker_mul with WB = WU + 1; not to be
    // overridden).
    localparam int W = WA + WU + 1
) (
    input  wire                   clk_i,
    input  wire signed [WA-1:0]   a_i,
    input  wire        [WU-1:0]   b0_i,
    input  wire        [WU-1:0]   b1_i,
    output wire signed [W-1:0]    p0_o,
    output wire signed [W-1:0]    p1_o
);
  localparam int K = WA - 1 + WU;  // weight of b1 in the packed operand
  if (WA < 2 || WU < 1 || WA > 18 || K + WU > 18) begin : g_bad_width
    $error("pluecker_mul_pair: needs 2 <= WA <= 18, WU >= 1 and WA - 1 + 2 WU <= 18");
  end

  wire [17:0] a18 = 18'($signed(a_i));
  wire [17:0] b18 = 18'({b1_i, K'(b0_i)});
  // s = (a*b0 < 0), delayed as the block delays its product (3 edges).
  wire s_d = a_i[WA-1] && (|b0_i);
  logic [2:0] s_q;
  always_ff @(posedge clk_i) s_q <= {s_q[1:0], s_d};

  // a*B, after the block's output register; bits above K + W - 1 only
  // repeat hi's sign (waived: unused by design).
  /* verilator lint_off UNUSEDSIGNAL */
  wire [35:0] p36;
  /* verilator lint_on UNUSEDSIGNAL */
  pluecker_dsp18 #(
      .PIPELINE_REG(1'b1),
      .SIGNED_A(1'b1),
      .SIGNED_B(1'b0)
  ) u_mult (
      .clk_i(clk_i),
      .a_i(a18),
      .b_i(b18),
      .p_o(p36)
  );

  // The fabric output register: lo = {s, P[K-1:0]}, hi = P[K+W-1:K] + s,
  // both sign-extended to W bits.
  logic signed [W-1:0] p0_q, p1_q;
  always_ff @(posedge clk_i) begin
    p0_q <= W'($signed({s_q[2], p36[K-1:0]}));
    p1_q <= p36[K+W-1:K] + W'(s_q[2]);
  end
  assign p0_o = p0_q;
  assign p1_o = p1_q;

endmodule

`default_nettype wire
