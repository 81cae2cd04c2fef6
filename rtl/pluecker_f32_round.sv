// SPDX-License-Identifier: MIT
// Round and pack one binary32 result (combinational): the last step of
// pluecker_f32_add and pluecker_f32_mul, as f32::round_pack and the special
// cases of model/core/include/pluecker/f32unit.hpp.
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
`default_nettype none

module pluecker_f32_round #(
    parameter int ROUND = 0
) (
    input  wire              sign_i,
    input  wire signed [9:0] exp_i,     // biased exponent of mant_i[23]
    input  wire       [23:0] mant_i,    // normalised: mant_i[23] = 1
    input  wire              guard_i,
    input  wire              sticky_i,
    input  wire              nan_i,
    input  wire              inf_i,
    input  wire              zero_i,
    output logic      [31:0] res_o
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
  wire signed [9:0] exp_r = exp_i + $signed({9'd0, sum[24]});
  wire ovf = exp_r >= 10'sd255;
  wire tiny = exp_r <= 10'sd0;

  always_comb begin
    if (nan_i) res_o = 32'h7fc0_0000;
    else if (inf_i) res_o = {sign_i, 8'hff, 23'd0};
    else if (zero_i) res_o = {sign_i, 31'd0};
    else if (ovf) res_o = (ROUND == 0 || away) ? {sign_i, 8'hff, 23'd0} : {sign_i, 8'hfe, 23'h7f_ffff};
    else if (tiny) res_o = away ? {sign_i, 8'h01, 23'd0} : {sign_i, 31'd0};
    else res_o = {sign_i, exp_r[7:0], sum[22:0]};
  end
endmodule

`default_nettype wire
