// SPDX-License-Identifier: MIT
// Pipelined binary32 slab-test ray/box intersector: the float test
// smits_hit of model/core/src/boxtest.cpp ('smits-mul-cls': the ray class
// selects the near and far planes, the inverse direction comes from the
// ray set-up, multiplications only), bit for bit f32_smits_hit of
// model/core/include/pluecker/f32unit.hpp. Same interface style as
// pluecker_intersector and pluecker_float_intersector.
//
// Ports
//   in_*   one query per transfer. Vectors pack x in bits [31:0], then y,
//          then z; every field an IEEE-754 binary32 bit pattern (all taken).
//          ray_class_i bit a set = axis a negative; ray_inv_i the inverse
//          direction 1/d computed by the set-up (+-inf for a zero
//          component); ray_tmax_i the segment length (inf: unbounded ray).
//   out_*  results in input order with the query's tag; rst_i drops
//          every query in flight (pluecker_pipe_flow).
//
// The test (round to nearest even, format of f32unit.hpp), per axis a:
//   near = n_a ? hi_a : lo_a, far = n_a ? lo_a : hi_a
//   tn = (near - o_a) * inv_a, tf = (far - o_a) * inv_a   (pluecker_f32_add,
//                                                           pluecker_f32_mul)
//   t0 = tn > t0 ? tn : t0,  t1 = tf < t1 ? tf : t1       (from t0 = +0,
//   t1 = tmax, axis by axis: a NaN candidate keeps the bound: the model's
//   raise_entry / lower_exit)
// hit = t0 <= t1 (pluecker_f32_cmp).
//
// Pipeline (stage = register index)
//   S0        input registers (planes chosen by the class)
//   S1..S8    six adders (ADD_LATENCY = 8); inv and tmax wait
//   S9..S15   six multipliers (MUL_LATENCY = 7; MUL_DSP MULT18X18D each on
//             ECP5)
//   S16..S18  the bounds, one axis a stage
//   F         t0 <= t1 written into the output FIFO
// LATENCY = 1 + ADD_LATENCY + MUL_LATENCY + 3 + 1 = 20, FIFO_DEPTH = 32:
// the port contract's (pluecker_contract_float_pkg); elaboration fails when
// they differ.
`default_nettype none

module pluecker_smits_intersector #(
    parameter int TAG_BITS = 16,
    parameter int MUL_DSP = pluecker_contract_float_pkg::DEFAULT_MUL_DSP
) (
    input wire clk_i,
    input wire rst_i,

    input  wire                in_valid_i,
    output wire                in_ready_o,
    input  wire [TAG_BITS-1:0] in_tag_i,
    input  wire [         2:0] ray_class_i,
    input  wire [        95:0] ray_org_i,
    input  wire [        95:0] ray_inv_i,
    input  wire [        31:0] ray_tmax_i,
    input  wire [        95:0] box_min_i,
    input  wire [        95:0] box_max_i,

    output wire                out_valid_o,
    input  wire                out_ready_i,
    output wire [TAG_BITS-1:0] out_tag_o,
    output wire                out_hit_o
);
  localparam int ADD_LATENCY = pluecker_contract_float_pkg::ADD_LATENCY;
  localparam int MUL_LATENCY = pluecker_contract_float_pkg::MUL_LATENCY;
  // Register index of the products, and of the bounds after axis 2.
  localparam int S_MUL = ADD_LATENCY + MUL_LATENCY;
  localparam int S_BOUNDS = S_MUL + 3;
  localparam int STAGES = S_BOUNDS + 1;
  localparam int LATENCY = STAGES + 1;
  localparam int FIFO_DEPTH = 1 << $clog2(LATENCY + 2);

  localparam bit TAG_BITS_OK = TAG_BITS >= pluecker_contract_float_pkg::MIN_TAG_BITS;
  localparam bit MUL_DSP_OK = pluecker_contract_float_pkg::mul_dsp_ok(MUL_DSP);
  if (!TAG_BITS_OK) begin : g_bad_tag_bits
    $error("pluecker_smits_intersector: parameter TAG_BITS must be at least 1");
  end
  if (!MUL_DSP_OK) begin : g_bad_mul_dsp
    $error("pluecker_smits_intersector: parameter MUL_DSP must be 1, 3 or 4 (MULT18X18D per significand product)");
  end
  if (LATENCY != pluecker_contract_float_pkg::SMITS_LATENCY) begin : g_bad_latency
    $error("pluecker_smits_intersector: LATENCY differs from the port contract (pluecker_contract_float_pkg)");
  end
  if (FIFO_DEPTH != pluecker_contract_float_pkg::SMITS_FIFO_DEPTH) begin : g_bad_fifo_depth
    $error("pluecker_smits_intersector: FIFO_DEPTH differs from the port contract (pluecker_contract_float_pkg)");
  end

  // -------------------------------------------------------------------------
  // Control: valid bits, tags, credits, output FIFO
  // -------------------------------------------------------------------------
  wire hit_last;
  pluecker_pipe_flow #(.STAGES(STAGES), .TAG_BITS(TAG_BITS), .FIFO_DEPTH(FIFO_DEPTH)) u_flow (
      .clk_i(clk_i), .rst_i(rst_i), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o), .in_tag_i(in_tag_i),
      .res_hit_i(hit_last), .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_tag_o(out_tag_o),
      .out_hit_o(out_hit_o));

  // -------------------------------------------------------------------------
  // S0: input registers, near and far planes by the class
  // -------------------------------------------------------------------------
  logic [2:0][31:0] near0_q, far0_q, o0_q, inv0_q;
  logic [31:0] tmax0_q;

  always_ff @(posedge clk_i) tmax0_q <= ray_tmax_i;

  for (genvar a = 0; a < 3; a++) begin : g_sel
    wire n = ray_class_i[a];
    wire [31:0] lo = box_min_i[a*32+:32];
    wire [31:0] hi = box_max_i[a*32+:32];
    always_ff @(posedge clk_i) begin
      near0_q[a] <= n ? hi : lo;
      far0_q[a] <= n ? lo : hi;
      o0_q[a] <= ray_org_i[a*32+:32];
      inv0_q[a] <= ray_inv_i[a*32+:32];
    end
  end

  // -------------------------------------------------------------------------
  // S1..S15: tn = (near - o) * inv, tf = (far - o) * inv
  // -------------------------------------------------------------------------
  wire [2:0][31:0] inv_s;
  pluecker_pipe #(.WIDTH(96), .STAGES(ADD_LATENCY)) u_inv (.clk_i(clk_i), .d_i(inv0_q), .q_o(inv_s));
  wire [31:0] tmax_s;
  pluecker_pipe #(.WIDTH(32), .STAGES(S_MUL)) u_tmax (.clk_i(clk_i), .d_i(tmax0_q), .q_o(tmax_s));

  wire [2:0][31:0] tn_s, tf_s;
  for (genvar a = 0; a < 3; a++) begin : g_slab
    wire [31:0] dn, df;
    pluecker_f32_add #(.SUB(1)) u_dn (.clk_i(clk_i), .a_i(near0_q[a]), .b_i(o0_q[a]), .s_o(dn));
    pluecker_f32_add #(.SUB(1)) u_df (.clk_i(clk_i), .a_i(far0_q[a]), .b_i(o0_q[a]), .s_o(df));
    pluecker_f32_mul #(.MUL_DSP(MUL_DSP)) u_tn (.clk_i(clk_i), .a_i(dn), .b_i(inv_s[a]), .p_o(tn_s[a]));
    pluecker_f32_mul #(.MUL_DSP(MUL_DSP)) u_tf (.clk_i(clk_i), .a_i(df), .b_i(inv_s[a]), .p_o(tf_s[a]));
  end

  // -------------------------------------------------------------------------
  // S16..S18: the bounds, axis a in stage S_MUL + 1 + a. The candidates of
  // the later axes wait.
  // -------------------------------------------------------------------------
  wire [3:0][31:0] t0, t1;  // bounds before axis a (index a), after axis 2 (index 3)
  assign t0[0] = 32'd0;  // +0
  assign t1[0] = tmax_s;

  for (genvar a = 0; a < 3; a++) begin : g_bound
    wire [31:0] tn, tf;
    pluecker_pipe #(.WIDTH(64), .STAGES(a)) u_wait (.clk_i(clk_i), .d_i({tn_s[a], tf_s[a]}), .q_o({tn, tf}));
    wire raise, lower, unused_le0, unused_le1;
    pluecker_f32_cmp u_raise (.a_i(t0[a]), .b_i(tn), .lt_o(raise), .le_o(unused_le0));  // tn > t0
    pluecker_f32_cmp u_lower (.a_i(tf), .b_i(t1[a]), .lt_o(lower), .le_o(unused_le1));  // tf < t1
    logic [31:0] t0_q, t1_q;
    always_ff @(posedge clk_i) begin
      t0_q <= raise ? tn : t0[a];
      t1_q <= lower ? tf : t1[a];
    end
    assign t0[a+1] = t0_q;
    assign t1[a+1] = t1_q;
  end

  wire unused_lt;
  pluecker_f32_cmp u_hit (.a_i(t0[3]), .b_i(t1[3]), .lt_o(unused_lt), .le_o(hit_last));
endmodule

`default_nettype wire
