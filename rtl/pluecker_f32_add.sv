// SPDX-License-Identifier: MIT
// Pipelined binary32 adder/subtractor: s_o = a_i + b_i (SUB = 0) or
// a_i - b_i (SUB = 1), rounded by ROUND (0 nearest even, 1 up, 2 down),
// LATENCY = 8 clock edges after a_i, b_i; one operation per clock. Bit for
// bit f32::add / f32::sub of model/core/include/pluecker/f32unit.hpp:
// subnormal operands flushed (to zero of their sign, or under directed
// rounding to the neighbour among {0, +-2^-126} in the rounding
// direction), tiny results flushed the same way, IEEE-754 infinities,
// signed zeros and overflow, the one NaN 0x7fc00000. Datapath only: no
// reset, no enable, no valid (the units carry the valid bits).
//
// Stages (each ends in a register):
//   1  operands: b negated for SUB, subnormals flushed; the special results
//      (NaN, inf, two zeros)
//   2  order: the larger magnitude is `greater` (a 31-bit compare), the
//      exponent difference d
//   3  align: the smaller significand shifted right by d into 24 + 2 bits
//      (guard, round), the OR of everything shifted further into a sticky
//      bit below them (27 bits, 3 below the significand's last place)
//   4  add or subtract (greater >= lesser, so the difference is >= 0): 28 bits
//   5  leading zeros of the sum (0 after a carry out)
//   6  normalise: shift left, exponent e_big + 1 - lz; 24 bits, guard and
//      sticky
//   7, 8  round and pack (pluecker_f32_round, two stages)
// Three bits below the significand (guard, round, sticky) give the correctly
// rounded result: a difference loses at most one leading bit when d >= 2,
// and is exact when d <= 1.
`default_nettype none

module pluecker_f32_add #(
    parameter bit SUB = 0,
    parameter int ROUND = 0
) (
    input  wire        clk_i,
    input  wire [31:0] a_i,
    input  wire [31:0] b_i,
    output wire [31:0] s_o
);
  localparam int LATENCY = 8;

  if (ROUND < 0 || ROUND > 2) begin : g_bad_round
    $error("pluecker_f32_add: parameter ROUND must be 0 (nearest), 1 (up) or 2 (down)");
  end
  if (LATENCY != pluecker_contract_float_pkg::ADD_LATENCY) begin : g_bad_latency
    $error("pluecker_f32_add: LATENCY differs from the port contract (pluecker_contract_float_pkg)");
  end

  // A subnormal operand of the addition, flushed toward the rounding
  // direction (nearest: to zero of its sign).
  function automatic logic [31:0] flush(input logic [31:0] x);
    logic away;
    away = (ROUND == 1 && !x[31]) || (ROUND == 2 && x[31]);
    if (x[30:23] == 8'd0 && x[22:0] != 23'd0) flush = {x[31], away ? 8'd1 : 8'd0, 23'd0};
    else flush = x;
  endfunction

  // ---------------------------------------------------------------------
  // Stage 1: operands (b negated for SUB, subnormals flushed), specials
  // ---------------------------------------------------------------------
  wire [31:0] fa = flush(a_i);
  wire [31:0] fb = flush({b_i[31] ^ SUB, b_i[30:0]});
  wire nan_a = &fa[30:23] && |fa[22:0];
  wire nan_b = &fb[30:23] && |fb[22:0];
  wire inf_a = &fa[30:23] && !(|fa[22:0]);
  wire inf_b = &fb[30:23] && !(|fb[22:0]);
  wire zero_a = !(|fa[30:0]);
  wire zero_b = !(|fb[30:0]);

  logic [31:0] xa1_q, xb1_q;
  logic nan1_q, inf1_q, inf_sign1_q, zero1_q, zero_sign1_q;

  always_ff @(posedge clk_i) begin
    xa1_q <= fa;
    xb1_q <= fb;
    nan1_q <= nan_a || nan_b || (inf_a && inf_b && (fa[31] ^ fb[31]));
    inf1_q <= inf_a || inf_b;
    inf_sign1_q <= inf_a ? fa[31] : fb[31];
    zero1_q <= zero_a && zero_b;
    zero_sign1_q <= (fa[31] && fb[31]) || ((fa[31] || fb[31]) && ROUND == 2);
  end

  // ---------------------------------------------------------------------
  // Stage 2: order (the larger magnitude first), exponent difference
  // ---------------------------------------------------------------------
  wire a_big = xa1_q[30:0] >= xb1_q[30:0];
  wire [31:0] greater = a_big ? xa1_q : xb1_q;
  wire [30:0] lesser = a_big ? xb1_q[30:0] : xa1_q[30:0];  // its sign is in sub2_q
  wire [7:0] d_ab = xa1_q[30:23] - xb1_q[30:23];
  wire [7:0] d_ba = xb1_q[30:23] - xa1_q[30:23];

  logic sign2_q, sub2_q, nan2_q, inf2_q, inf_sign2_q, zero2_q, zero_sign2_q;
  logic [7:0] e2_q, d2_q;
  logic [23:0] mb2_q, ms2_q;

  always_ff @(posedge clk_i) begin
    sign2_q <= greater[31];
    sub2_q <= xa1_q[31] ^ xb1_q[31];
    e2_q <= greater[30:23];
    d2_q <= a_big ? d_ab : d_ba;
    mb2_q <= {|greater[30:23], greater[22:0]};
    ms2_q <= {|lesser[30:23], lesser[22:0]};
    nan2_q <= nan1_q;
    inf2_q <= inf1_q;
    inf_sign2_q <= inf_sign1_q;
    zero2_q <= zero1_q;
    zero_sign2_q <= zero_sign1_q;
  end

  // ---------------------------------------------------------------------
  // Stage 3: align the smaller significand (27 bits: 24, guard, round,
  // sticky)
  // ---------------------------------------------------------------------
  wire [4:0] dd = (d2_q >= 8'd27) ? 5'd27 : d2_q[4:0];
  wire [26:0] shifted = {ms2_q, 3'b000} >> dd;
  // Bit k of the significand sits at position k + 3 and is shifted out
  // when k + 3 < dd.
  logic [23:0] out_mask;
  always_comb begin
    for (int k = 0; k < 24; k++) out_mask[k] = (k + 3) < int'(dd);
  end
  wire sticky = |(ms2_q & out_mask);

  logic sign3_q, sub3_q;
  logic [7:0] e3_q;
  logic [23:0] mb3_q;
  logic [26:0] ms3_q;
  logic [4:0] spec3_q;

  always_ff @(posedge clk_i) begin
    sign3_q <= sign2_q;
    sub3_q <= sub2_q;
    e3_q <= e2_q;
    mb3_q <= mb2_q;
    ms3_q <= {shifted[26:1], shifted[0] | sticky};
    spec3_q <= {nan2_q, inf2_q, inf_sign2_q, zero2_q, zero_sign2_q};
  end

  // ---------------------------------------------------------------------
  // Stage 4: add or subtract
  // ---------------------------------------------------------------------
  wire [27:0] big28 = {1'b0, mb3_q, 3'b000};
  wire [27:0] small28 = {1'b0, ms3_q};

  logic sign4_q;
  logic [7:0] e4_q;
  logic [27:0] sum4_q;
  logic [4:0] spec4_q;

  always_ff @(posedge clk_i) begin
    sign4_q <= sign3_q;
    e4_q <= e3_q;
    sum4_q <= sub3_q ? big28 - small28 : big28 + small28;
    spec4_q <= spec3_q;
  end

  // ---------------------------------------------------------------------
  // Stage 5: leading zeros (28 when the sum is zero)
  // ---------------------------------------------------------------------
  logic [4:0] lz;
  always_comb begin
    lz = 5'd28;
    for (int k = 0; k < 28; k++) begin
      if (sum4_q[k]) lz = 5'(27 - k);
    end
  end

  logic sign5_q;
  logic [7:0] e5_q;
  logic [27:0] sum5_q;
  logic [4:0] lz5_q;
  logic [4:0] spec5_q;

  always_ff @(posedge clk_i) begin
    sign5_q <= sign4_q;
    e5_q <= e4_q;
    sum5_q <= sum4_q;
    lz5_q <= lz;
    spec5_q <= spec4_q;
  end

  // ---------------------------------------------------------------------
  // Stage 6: normalise. The leading one goes to bit 27; it stood at bit 26
  // for a sum of e_big's magnitude, so the exponent is e_big + 1 - lz.
  // ---------------------------------------------------------------------
  wire [27:0] norm = sum5_q << lz5_q;

  logic sign6_q, guard6_q, sticky6_q, cancel6_q;
  logic signed [9:0] e6_q;
  logic [23:0] mant6_q;
  logic [4:0] spec6_q;

  always_ff @(posedge clk_i) begin
    sign6_q <= sign5_q;
    e6_q <= $signed({2'b00, e5_q}) + 10'sd1 - $signed({5'd0, lz5_q});
    mant6_q <= norm[27:4];
    guard6_q <= norm[3];
    sticky6_q <= |norm[2:0];
    cancel6_q <= sum5_q == 28'd0;
    spec6_q <= spec5_q;
  end

  // ---------------------------------------------------------------------
  // Stages 7, 8: round and pack. An exact cancellation is +0 (-0 rounding
  // down); two zero operands keep the IEEE-754 sign of their sum.
  // ---------------------------------------------------------------------
  wire nan6 = spec6_q[4];
  wire inf6 = spec6_q[3];
  wire both_zero6 = spec6_q[1];
  wire zero6 = both_zero6 || cancel6_q;
  wire sign6 = inf6 ? spec6_q[2] : both_zero6 ? spec6_q[0] : cancel6_q ? (ROUND == 2) : sign6_q;

  pluecker_f32_round #(.ROUND(ROUND)) u_round (
      .clk_i(clk_i), .sign_i(sign6), .exp_i(e6_q), .mant_i(mant6_q), .guard_i(guard6_q), .sticky_i(sticky6_q),
      .nan_i(nan6), .inf_i(inf6), .zero_i(zero6), .res_o(s_o));
endmodule

`default_nettype wire
