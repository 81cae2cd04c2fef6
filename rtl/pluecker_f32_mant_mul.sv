// SPDX-License-Identifier: MIT
// Registered 24 x 24 unsigned significand product of pluecker_f32_mul:
//   p_o = a_i * b_i (48 bits, exact), LATENCY = 4 clock edges after a_i, b_i.
//
// Each operand is split into a low part of 17 bits and a high part of 7
// (x = xh * 2^17 + xl), and the four partial products are registered
// multipliers of two clock edges each (operand and product registers):
//   ll = al * bl   18 x 18 signed (positive)   pluecker_mul: one MULT18X18D
//   hl = ah * bl    8 x 18                     pluecker_mul or pluecker_mul_lut
//   lh = al * bh   18 x  8                     pluecker_mul or pluecker_mul_lut
//   hh = ah * bh    8 x  8                     pluecker_mul or pluecker_mul_lut
// MUL_DSP says how many of them are MULT18X18D blocks on ECP5 (pluecker_mul
// with PLUECKER_ECP5): 4 (all), 3 (hh in fabric) or 1 (ll alone; hl, lh and
// hh in fabric, pluecker_mul_lut: no `*`, so no tool maps them to a DSP).
// Both kinds have the same two register stages, so the latency and the
// product do not depend on MUL_DSP. Then, as pluecker_mul sums split
// products:
//   edge 3  c = {hh, ll[33:0]} (ll < 2^34: no add), x = hl + lh
//   edge 4  p = c + (x << 17)
`default_nettype none

module pluecker_f32_mant_mul #(
    parameter int MUL_DSP = 4
) (
    input  wire        clk_i,
    input  wire [23:0] a_i,
    input  wire [23:0] b_i,
    output wire [47:0] p_o
);
  if (MUL_DSP != 1 && MUL_DSP != 3 && MUL_DSP != 4) begin : g_bad_mul_dsp
    $error("pluecker_f32_mant_mul: parameter MUL_DSP must be 1, 3 or 4");
  end

  // Signed operands with a zero sign bit.
  wire signed [17:0] al = {1'b0, a_i[16:0]};
  wire signed [17:0] bl = {1'b0, b_i[16:0]};
  wire signed [7:0] ah = {1'b0, a_i[23:17]};
  wire signed [7:0] bh = {1'b0, b_i[23:17]};

  wire signed [35:0] ll;
  wire signed [25:0] hl, lh;
  wire signed [15:0] hh;

  pluecker_mul #(.WA(18), .WB(18)) u_ll (.clk_i(clk_i), .a_i(al), .b_i(bl), .p_o(ll));
  if (MUL_DSP >= 3) begin : g_cross_dsp
    pluecker_mul #(.WA(8), .WB(18)) u_hl (.clk_i(clk_i), .a_i(ah), .b_i(bl), .p_o(hl));
    pluecker_mul #(.WA(18), .WB(8)) u_lh (.clk_i(clk_i), .a_i(al), .b_i(bh), .p_o(lh));
  end else begin : g_cross_lut
    pluecker_mul_lut #(.WA(18), .WB(8)) u_hl (.clk_i(clk_i), .a_i(bl), .b_i(ah), .p_o(hl));
    pluecker_mul_lut #(.WA(18), .WB(8)) u_lh (.clk_i(clk_i), .a_i(al), .b_i(bh), .p_o(lh));
  end
  if (MUL_DSP == 4) begin : g_hh_dsp
    pluecker_mul #(.WA(8), .WB(8)) u_hh (.clk_i(clk_i), .a_i(ah), .b_i(bh), .p_o(hh));
  end else begin : g_hh_lut
    pluecker_mul_lut #(.WA(8), .WB(8)) u_hh (.clk_i(clk_i), .a_i(ah), .b_i(bh), .p_o(hh));
  end

  // Edge 3: hh (< 2^14) above ll (< 2^34); the cross products (< 2^24 each).
  logic [47:0] c_q;
  logic [24:0] x_q;
  logic [47:0] p_q;

  always_ff @(posedge clk_i) begin
    c_q <= {hh[13:0], ll[33:0]};
    x_q <= {1'b0, hl[23:0]} + {1'b0, lh[23:0]};
    p_q <= c_q + {6'd0, x_q, 17'd0};
  end

  assign p_o = p_q;
  // The partial products' top bits are zero (positive operands of 17 and 7
  // bits); Verilator ignores signals named unused*.
  wire unused_top = ^{ll[35:34], hl[25:24], lh[25:24], hh[15:14]};
endmodule

`default_nettype wire
