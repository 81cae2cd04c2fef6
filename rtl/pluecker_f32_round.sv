// SPDX-License-Identifier: MIT
// Round and pack one binary32 result, in two registered stages (LATENCY =
// 2 clock edges; datapath only): the last step of pluecker_f32_add and
// pluecker_f32_mul, as f32::round_pack and the special cases of
// model/core/include/pluecker/f32unit.hpp.
//
// The value (-1)^sign_i * 1.mant_i[22:0] * 2^(exp_i - 127), followed by the
// guard bit guard_i and the OR of every bit below it, sticky_i, is rounded
// to 24 significand bits with an unbounded exponent:
//   ROUND 0  to nearest, ties to even
//   ROUND 1  toward +inf
//   ROUND 2  toward -inf
// then packed: an exponent of 255 or more overflows (+-inf when rounding
// away from zero, which nearest always does, else +-FLT_MAX); one of 0 or
// less is a tiny result and flushed: zero of its sign, or +-2^-126 when
// rounding away from zero. nan_i, inf_i and zero_i (in that priority)
// replace the value: the canonical NaN 0x7fc00000, or inf / zero of sign_i.
//
// Stages: 1 the rounding increment (one carry chain) beside both candidate
// exponents and their range checks; 2 the choice among the candidates and
// the special results (a few LUT levels).
`default_nettype none

module pluecker_f32_round #(
    parameter int ROUND = 0
) (
    input  wire              clk_i,
    input  wire              sign_i,
    input  wire signed [9:0] exp_i,     // biased exponent of mant_i[23]
    input  wire       [23:0] mant_i,    // normalised: mant_i[23] = 1
    input  wire              guard_i,
    input  wire              sticky_i,
    input  wire              nan_i,
    input  wire              inf_i,
    input  wire              zero_i,
    output wire       [31:0] res_o
);
  if (ROUND < 0 || ROUND > 2) begin : g_bad_round
    $error("pluecker_f32_round: parameter ROUND must be 0 (nearest), 1 (up) or 2 (down)");
  end

  // Rounding away from zero in magnitude (directed modes, by the sign).
  wire away = (ROUND == 1 && !sign_i) || (ROUND == 2 && sign_i);
  wire inc = (ROUND == 0) ? guard_i && (sticky_i || mant_i[0]) : away && (guard_i || sticky_i);
  // The rounded significand; a carry out (all ones + 1) leaves zeros below.
  wire [24:0] sum = {1'b0, mant_i} + {24'd0, inc};
  wire unused_hidden = sum[23];  // the hidden bit (or 0 after a carry out)
  wire carry = sum[24];
  // The exponent after rounding, exp_i + carry, and its range checks: both
  // candidates are computed beside the significand's carry chain and
  // registered; stage 2 only selects.
  wire [7:0] exp_p1 = exp_i[7:0] + 8'd1;  // the low 8 bits of exp_i + 1

  logic sign1_q, carry1_q, nan1_q, inf1_q, zero1_q;
  logic [22:0] frac1_q;
  logic [7:0] exp1_q, exp_p1_1_q;
  logic ovf0_q, ovf1_q, tiny0_q, tiny1_q;

  always_ff @(posedge clk_i) begin
    sign1_q <= sign_i;
    carry1_q <= carry;
    frac1_q <= sum[22:0];
    exp1_q <= exp_i[7:0];
    exp_p1_1_q <= exp_p1;
    ovf0_q <= exp_i >= 10'sd255;
    ovf1_q <= exp_i >= 10'sd254;
    tiny0_q <= exp_i <= 10'sd0;
    tiny1_q <= exp_i <= -10'sd1;
    nan1_q <= nan_i;
    inf1_q <= inf_i;
    zero1_q <= zero_i;
  end

  // Stage 2: choose and pack.
  wire away1 = (ROUND == 1 && !sign1_q) || (ROUND == 2 && sign1_q);
  wire ovf = carry1_q ? ovf1_q : ovf0_q;
  wire tiny = carry1_q ? tiny1_q : tiny0_q;
  wire [7:0] exp_r = carry1_q ? exp_p1_1_q : exp1_q;
  logic [31:0] res;

  always_comb begin
    if (nan1_q) res = 32'h7fc0_0000;
    else if (inf1_q) res = {sign1_q, 8'hff, 23'd0};
    else if (zero1_q) res = {sign1_q, 31'd0};
    else if (ovf) res = (ROUND == 0 || away1) ? {sign1_q, 8'hff, 23'd0} : {sign1_q, 8'hfe, 23'h7f_ffff};
    else if (tiny) res = away1 ? {sign1_q, 8'h01, 23'd0} : {sign1_q, 31'd0};
    else res = {sign1_q, exp_r, frac1_q};
  end

  logic [31:0] res2_q;
  always_ff @(posedge clk_i) res2_q <= res;
  assign res_o = res2_q;
endmodule

`default_nettype wire
