// SPDX-License-Identifier: MIT
// Pipelined binary32 multiplier: p_o = a_i * b_i rounded by ROUND (0
// nearest even, 1 up, 2 down), LATENCY = 7 clock edges after a_i, b_i; one
// operation per clock. Bit for bit f32::mul of
// model/core/include/pluecker/f32unit.hpp: a subnormal operand is read as
// zero of its sign, or under directed rounding as 2^-126 of its sign when
// that moves the product in the rounding direction; tiny results flushed
// (pluecker_f32_round); IEEE-754 infinities, signed zeros and overflow;
// 0 * inf and NaN operands give the NaN 0x7fc00000. Datapath only.
//
// Stages:
//   1..4  the significand product (pluecker_f32_mant_mul: MUL_DSP of its
//         four partial products on MULT18X18D); the operands' flush and
//         decode is the one LUT level in front of its operand registers;
//         sign, exponent sum and special cases wait beside it
//   5     normalise: the product of two significands in [2^23, 2^24) lies in
//         [2^46, 2^48); 24 bits from bit 47 or 46, guard, sticky
//   6, 7  round and pack (pluecker_f32_round, two stages)
`default_nettype none

module pluecker_f32_mul #(
    parameter int ROUND = 0,
    parameter int MUL_DSP = 4
) (
    input  wire        clk_i,
    input  wire [31:0] a_i,
    input  wire [31:0] b_i,
    output wire [31:0] p_o
);
  localparam int MANT_LATENCY = 4;
  localparam int LATENCY = MANT_LATENCY + 3;

  if (ROUND < 0 || ROUND > 2) begin : g_bad_round
    $error("pluecker_f32_mul: parameter ROUND must be 0 (nearest), 1 (up) or 2 (down)");
  end
  if (LATENCY != pluecker_contract_float_pkg::MUL_LATENCY) begin : g_bad_latency
    $error("pluecker_f32_mul: LATENCY differs from the port contract (pluecker_contract_float_pkg)");
  end

  wire sign = a_i[31] ^ b_i[31];
  // Under directed rounding a larger magnitude moves the product in the
  // rounding direction when its sign agrees with it.
  wire grow = (ROUND == 1 && !sign) || (ROUND == 2 && sign);

  // A subnormal operand becomes 2^-126 (exponent 1) when growing, else zero.
  function automatic logic [30:0] flush(input logic [30:0] x, input logic g);
    if (x[30:23] == 8'd0 && x[22:0] != 23'd0) flush = {g ? 8'd1 : 8'd0, 23'd0};
    else flush = x;
  endfunction

  wire [30:0] xa = flush(a_i[30:0], grow);
  wire [30:0] xb = flush(b_i[30:0], grow);
  wire nan_a = &xa[30:23] && |xa[22:0];
  wire nan_b = &xb[30:23] && |xb[22:0];
  wire inf_a = &xa[30:23] && !(|xa[22:0]);
  wire inf_b = &xb[30:23] && !(|xb[22:0]);
  wire zero_a = !(|xa[30:23]);  // after the flush, exponent 0 means zero
  wire zero_b = !(|xb[30:23]);
  wire nan = nan_a || nan_b || (inf_a && zero_b) || (zero_a && inf_b);
  wire inf = inf_a || inf_b;
  wire zero = zero_a || zero_b;
  // Exponent of the product's bit 46: ea + eb - 127 (10 bits, signed).
  wire signed [9:0] e_sum = $signed({2'b00, xa[30:23]}) + $signed({2'b00, xb[30:23]}) - 10'sd127;

  // Significands (hidden bit set for a normal number; zero for a zero,
  // whose result the special flags decide).
  wire [47:0] prod;
  pluecker_f32_mant_mul #(.MUL_DSP(MUL_DSP)) u_mant (
      .clk_i(clk_i), .a_i({!zero_a, xa[22:0]}), .b_i({!zero_b, xb[22:0]}), .p_o(prod));

  // Sign, exponent and special flags beside the product.
  localparam int SIDE_W = 1 + 10 + 3;
  wire [SIDE_W-1:0] side;
  pluecker_pipe #(.WIDTH(SIDE_W), .STAGES(MANT_LATENCY)) u_side (
      .clk_i(clk_i), .d_i({sign, e_sum, nan, inf, zero}), .q_o(side));
  wire sign4 = side[13];
  wire signed [9:0] e4 = side[12:3];
  wire [2:0] spec4 = side[2:0];

  // Stage 5: normalise.
  wire top = prod[47];
  logic sign5_q, guard5_q, sticky5_q;
  logic signed [9:0] e5_q;
  logic [23:0] mant5_q;
  logic [2:0] spec5_q;

  always_ff @(posedge clk_i) begin
    sign5_q <= sign4;
    e5_q <= e4 + $signed({9'd0, top});
    mant5_q <= top ? prod[47:24] : prod[46:23];
    guard5_q <= top ? prod[23] : prod[22];
    sticky5_q <= top ? |prod[22:0] : |prod[21:0];
    spec5_q <= spec4;
  end

  // Stages 6, 7: round and pack.
  pluecker_f32_round #(.ROUND(ROUND)) u_round (
      .clk_i(clk_i), .sign_i(sign5_q), .exp_i(e5_q), .mant_i(mant5_q), .guard_i(guard5_q), .sticky_i(sticky5_q),
      .nan_i(spec5_q[2]), .inf_i(spec5_q[1]), .zero_i(spec5_q[0]), .res_o(p_o));
endmodule

`default_nettype wire
