// SPDX-License-Identifier: MIT
// Pipelined binary32 Plücker ray/box intersector: the float test
// pluecker_hit of model/core/src/boxtest.cpp (Mahovsky & Wyvill, JGT 9(1),
// 2004) in its operation order, bit for bit f32_pluecker_hit of
// model/core/include/pluecker/f32unit.hpp. Same interface style as the
// fixed-point pluecker_intersector: valid/ready, a tag, one query per clock,
// a never-stalling pipeline with an output FIFO and credits.
//
// Ports
//   in_*   one query per transfer (in_valid_i && in_ready_o at a rising edge
//          with rst_i low). Vectors pack x in bits [31:0], then y, then z;
//          every field is an IEEE-754 binary32 bit pattern (every pattern is
//          taken: NaN, inf, subnormals, lo > hi). ray_class_i bit a set =
//          axis a negative (it alone selects the planes); ray_dir_i is the
//          direction, of which the unit uses the magnitudes |d_a| (sign bits
//          ignored); ray_end_i the segment end o + tmax*d computed by the
//          ray set-up, ignored when ray_end_valid_i is low.
//   out_*  results in input order; out_tag_o is in_tag_i of the query.
//   rst_i  synchronous, active high: every query accepted before it is
//          dropped (pluecker_pipe_flow).
//
// The test, per axis i with class bit n_i (f32unit.hpp):
//   A_i = n_i ? o_i - hi_i : lo_i - o_i    pluecker_f32_add (SUB), ROUND RA
//   B_i = n_i ? o_i - lo_i : hi_i - o_i    pluecker_f32_add (SUB), ROUND RB
//   reject: B_i < 0, as (n_i ? o_i < lo_i : hi_i < o_i)          pluecker_f32_cmp
//           G_i < 0 when the end is valid, as (n_i ? hi_i < e_i : e_i < lo_i)
//           B_j*D_i - A_i*D_j < 0, as B_j*D_i < A_i*D_j for the six
//           pairs i != j (12 pluecker_f32_mul: B_j*D_i with RB, A_i*D_j
//           with RA; pluecker_f32_cmp)
// A comparison of the two operands of the model's subtraction is the sign
// test of its rounded difference (f32unit.hpp), without a subtractor.
//   CONSERVATIVE = 0: RA = RB = round to nearest even (the float model).
//   CONSERVATIVE = 1: RA = down, RB = up: every edge test compares an upper
//                     bound of B_j*D_i with a lower bound of A_i*D_j, so it
//                     rejects only when the exact value does; with the
//                     set-up's segment end rounded outward the unit never
//                     misses a real hit.
// Format: f32unit.hpp (subnormal operands of adds and multiplies flushed,
// tiny results flushed, IEEE-754 infinities, signed zeros and comparisons,
// NaN 0x7fc00000; a NaN never rejects).
//
// Pipeline (one query per clock, no stall; stage = register index)
//   S0       input registers; the class picks the operands in front of them
//   S1..S8   the six adders (ADD_LATENCY = 8); S1 also holds the origin and
//            end comparisons; the magnitudes |d| wait
//   S9..S15  the twelve multipliers (MUL_LATENCY = 7; MUL_DSP MULT18X18D
//            each on ECP5: pluecker_f32_mant_mul)
//   S16      the six edge comparisons
//   F        the AND of every test is written into the output FIFO
// LATENCY = 1 + ADD_LATENCY + MUL_LATENCY + 2 = 18 cycles from input to
// output handshake; FIFO_DEPTH = 32 (a power of two >= LATENCY + 2). Both
// are the port contract's (model/core/include/pluecker/float_contract.hpp,
// generated package pluecker_contract_float_pkg); elaboration fails when
// they differ. in_ready_o and out_valid_o are flops.
`default_nettype none

module pluecker_float_intersector #(
    parameter int TAG_BITS = 16,
    parameter bit CONSERVATIVE = 0,
    parameter int MUL_DSP = pluecker_contract_float_pkg::DEFAULT_MUL_DSP
) (
    input wire clk_i,
    input wire rst_i,

    input  wire                in_valid_i,
    output wire                in_ready_o,
    input  wire [TAG_BITS-1:0] in_tag_i,
    input  wire [         2:0] ray_class_i,
    input  wire [        95:0] ray_org_i,
    input  wire [        95:0] ray_dir_i,
    input  wire [        95:0] ray_end_i,
    input  wire                ray_end_valid_i,
    input  wire [        95:0] box_min_i,
    input  wire [        95:0] box_max_i,

    output wire                out_valid_o,
    input  wire                out_ready_i,
    output wire [TAG_BITS-1:0] out_tag_o,
    output wire                out_hit_o
);
  // -------------------------------------------------------------------------
  // Parameters and the port contract
  // -------------------------------------------------------------------------
  localparam int ADD_LATENCY = pluecker_contract_float_pkg::ADD_LATENCY;
  localparam int MUL_LATENCY = pluecker_contract_float_pkg::MUL_LATENCY;
  // Register index of the differences, the products and the edge
  // comparisons.
  localparam int S_ADD = ADD_LATENCY;
  localparam int S_MUL = S_ADD + MUL_LATENCY;
  localparam int S_EDGE = S_MUL + 1;
  localparam int STAGES = S_EDGE + 1;
  localparam int LATENCY = STAGES + 1;
  localparam int FIFO_DEPTH = 1 << $clog2(LATENCY + 2);

  localparam bit TAG_BITS_OK = TAG_BITS >= pluecker_contract_float_pkg::MIN_TAG_BITS;
  localparam bit MUL_DSP_OK = pluecker_contract_float_pkg::mul_dsp_ok(MUL_DSP);
  if (!TAG_BITS_OK) begin : g_bad_tag_bits
    $error("pluecker_float_intersector: parameter TAG_BITS must be at least 1");
  end
  if (!MUL_DSP_OK) begin : g_bad_mul_dsp
    $error("pluecker_float_intersector: parameter MUL_DSP must be 1, 3 or 4 (MULT18X18D per significand product)");
  end
  if (LATENCY != pluecker_contract_float_pkg::FLOAT_LATENCY) begin : g_bad_latency
    $error("pluecker_float_intersector: LATENCY differs from the port contract (pluecker_contract_float_pkg)");
  end
  if (FIFO_DEPTH != pluecker_contract_float_pkg::FLOAT_FIFO_DEPTH) begin : g_bad_fifo_depth
    $error("pluecker_float_intersector: FIFO_DEPTH differs from the port contract (pluecker_contract_float_pkg)");
  end

  localparam int RA = CONSERVATIVE ? 2 : 0;  // A_i and A_i*D_j: down (lower bounds)
  localparam int RB = CONSERVATIVE ? 1 : 0;  // B_j and B_j*D_i: up (upper bounds)

  // Pairs (i, j), i != j, of the six edge tests, k = 0..5:
  // (0,1) (0,2) (1,2) (1,0) (2,0) (2,1).
  function automatic int pair_i(input int k);
    pair_i = k / 2;
  endfunction
  function automatic int pair_j(input int k);
    pair_j = (k / 2 + 1 + k % 2) % 3;
  endfunction

  // -------------------------------------------------------------------------
  // Control: valid bits, tags, credits, output FIFO
  // -------------------------------------------------------------------------
  wire hit_last;
  pluecker_pipe_flow #(.STAGES(STAGES), .TAG_BITS(TAG_BITS), .FIFO_DEPTH(FIFO_DEPTH)) u_flow (
      .clk_i(clk_i), .rst_i(rst_i), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o), .in_tag_i(in_tag_i),
      .res_hit_i(hit_last), .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_tag_o(out_tag_o),
      .out_hit_o(out_hit_o));

  // -------------------------------------------------------------------------
  // S0: input registers (data only), the operands chosen by the class
  // -------------------------------------------------------------------------
  logic [2:0][31:0] al0_q, ar0_q, bl0_q, br0_q, gl0_q, gr0_q, d0_q;
  logic endv0_q;
  // The direction's sign bits: the class port stands for them.
  wire unused_dir_signs = ^{ray_dir_i[95], ray_dir_i[63], ray_dir_i[31]};

  always_ff @(posedge clk_i) endv0_q <= ray_end_valid_i;

  for (genvar i = 0; i < 3; i++) begin : g_sel
    wire n = ray_class_i[i];
    wire [31:0] o = ray_org_i[i*32+:32];
    wire [31:0] lo = box_min_i[i*32+:32];
    wire [31:0] hi = box_max_i[i*32+:32];
    wire [31:0] e = ray_end_i[i*32+:32];
    always_ff @(posedge clk_i) begin
      al0_q[i] <= n ? o : lo;  // A = al - ar
      ar0_q[i] <= n ? hi : o;
      bl0_q[i] <= n ? o : hi;  // B = bl - br
      br0_q[i] <= n ? lo : o;
      gl0_q[i] <= n ? hi : e;  // G = gl - gr
      gr0_q[i] <= n ? e : lo;
      d0_q[i] <= {1'b0, ray_dir_i[i*32+:31]};  // |d_i|
    end
  end

  // -------------------------------------------------------------------------
  // S1..S8: A_i, B_i; origin and end tests in S1
  // -------------------------------------------------------------------------
  logic [2:0][31:0] a_s, b_s;  // A_i, B_i at S_ADD
  logic [2:0] orig_rej, end_rej;

  for (genvar i = 0; i < 3; i++) begin : g_sub
    pluecker_f32_add #(.SUB(1), .ROUND(RA)) u_a (.clk_i(clk_i), .a_i(al0_q[i]), .b_i(ar0_q[i]), .s_o(a_s[i]));
    pluecker_f32_add #(.SUB(1), .ROUND(RB)) u_b (.clk_i(clk_i), .a_i(bl0_q[i]), .b_i(br0_q[i]), .s_o(b_s[i]));
    wire unused_le_o, unused_le_g;
    pluecker_f32_cmp u_orig (.a_i(bl0_q[i]), .b_i(br0_q[i]), .lt_o(orig_rej[i]), .le_o(unused_le_o));
    pluecker_f32_cmp u_end (.a_i(gl0_q[i]), .b_i(gr0_q[i]), .lt_o(end_rej[i]), .le_o(unused_le_g));
  end

  logic ok1_q;
  always_ff @(posedge clk_i) ok1_q <= !(|orig_rej) && !(endv0_q && |end_rej);

  wire ok_edge;  // ok1_q at S_EDGE
  pluecker_pipe #(.WIDTH(1), .STAGES(S_EDGE - 1)) u_ok (.clk_i(clk_i), .d_i(ok1_q), .q_o(ok_edge));

  wire [2:0][31:0] d_s;  // |d| at S_ADD
  pluecker_pipe #(.WIDTH(96), .STAGES(ADD_LATENCY)) u_dir (.clk_i(clk_i), .d_i(d0_q), .q_o(d_s));

  // -------------------------------------------------------------------------
  // S9..S15: products B_j*D_i and A_i*D_j; S16: edge comparisons
  // -------------------------------------------------------------------------
  logic [5:0] edge_rej;
  for (genvar k = 0; k < 6; k++) begin : g_edge
    localparam int I = pair_i(k);
    localparam int J = pair_j(k);
    wire [31:0] p, q;
    wire unused_le;
    pluecker_f32_mul #(.ROUND(RB), .MUL_DSP(MUL_DSP)) u_p (.clk_i(clk_i), .a_i(b_s[J]), .b_i(d_s[I]), .p_o(p));
    pluecker_f32_mul #(.ROUND(RA), .MUL_DSP(MUL_DSP)) u_q (.clk_i(clk_i), .a_i(a_s[I]), .b_i(d_s[J]), .p_o(q));
    pluecker_f32_cmp u_cmp (.a_i(p), .b_i(q), .lt_o(edge_rej[k]), .le_o(unused_le));
  end

  logic edge_ok_q;
  always_ff @(posedge clk_i) edge_ok_q <= !(|edge_rej);

  assign hit_last = ok_edge && edge_ok_q;
endmodule

`default_nettype wire
