// SPDX-License-Identifier: MIT
// The per-node set-up of the local-frame box test: the ray, held at the
// global width, in one node's frame ("node ray"), computed bit for bit as
// local_node_ray of model/core/src/local.cpp (format, proof and every width:
// model/core/include/pluecker/local.hpp). A fixed-latency pipeline without a
// stall or an enable: the node ray of the inputs applied before rising edge
// 1 is on the outputs after edge LATENCY = 9 + MUL_ADD. Datapath only (no
// reset: pluecker_local_intersector keeps the valid bits).
//
// Inputs (x in the low field, then y, then z)
//   ray_class_i      bit a set = axis a negative
//   ray_org_i        O, GRID_BITS two's complement (the global grid)
//   ray_dir_i        DG, GRID_BITS unsigned: the largest component exactly
//                    2^(G-1), the others at most that (local_setup_ray)
//   ray_end_i        E, GRID_BITS two's complement; ray_end_valid_i
//   frame_org_i      F, GRID_BITS two's complement
//   frame_exp_i      e, EXP_BITS unsigned each, 0..G-K+1
// Outputs: the LocalNodeRay
//   cls_o            the class (passed through)
//   dir_o            DIR, DIR_BITS unsigned each (<= 2^(D-1))
//   w_o              W_k, K+D+2 bits signed each, pair order k = 0..5:
//                    (0,1) (0,2) (1,2) (1,0) (2,0) (2,1), k in the low field
//   org_o, end_o     ORG, END: K+2 bits signed each, -1..2^K (end_o is
//                    computed whatever end_valid_o says)
//   end_valid_o      ray_end_valid_i (passed through)
// Out of contract (a DG with no component at 2^(G-1) or one above it, an
// exponent above G-K+1): the outputs are defined by this RTL but not
// specified; pluecker_local_intersector's port contract excludes them.
//
// Per node (local.hpp): n_i the class bit, S_i = (2^K - 1) 2^e_i,
// F~_i = n_i ? F_i + S_i : F_i, Delta_i = n_i ? F~_i - O_i : O_i - F~_i (and
// the same with E), c the smallest scaling of the direction, then
//   ORG_i = clamp(RNE(Delta_i / 2^e_i), -1, 2^K), END_i the same with ceil
//   (conservative) or RNE, DIR_i = RNE(DG_i 2^(c - e_i + D - G)),
//   lambda_ij = Delta_i DG_j - Delta_j DG_i, sh_ij = G + e_i + e_j - c - D,
//   L = RNE(lambda / 2^sh), mu = ceil(N_ij / 2^(sh+1)),
//   N_ij = |Delta_i| + |Delta_j| + S_i + S_j + DG_i + DG_j + 1,
//   W_ij = clamp(2L + 2mu + 1 (conservative) or 2L, W_MIN, W_MAX).
// Six products Delta_i DG_j (i != j) give the three lambdas; lambda_ji =
// -lambda_ij, sh and N are symmetric and RNE (ties to even) is odd, so
// W_ji = clamp(-2L + 2mu + 1). Computed as
//   V = +-2 RNE(lambda / 2^s) + Mterm,  W = clamp((V << l) + 1)
// with s = max(sh, 0), l = max(-sh, 0) (at most D-K+1: sh >= K-D-1) and
// Mterm = 2 ceil(N / 2^(sh+1)) for sh >= 0, N for sh < 0 (then every term is
// exact: 2L + 2mu = (2 lambda + N) 2^l). L is saturated at +-2^QS and V at
// +-2^(K+D+2) on the way; neither changes the clamped W (see the widths).
//
// Pipeline (edge numbers: inputs applied before edge 1; MA = MUL_ADD)
//   F0 edge 1     input registers
//   F1 edge 2     S_i (a shift), F~_i, leading zeros of DG_i -> c_i
//   F2 edge 3     Delta_i, E offsets, c = min c_i, S_i + S_j, DG_i + DG_j + 1;
//                 the multipliers' operand registers
//   F3 edge 4     ORG/END shifted (floor, guard, sticky), |Delta_i|, s, l,
//                 the DIR shift; products Delta_i DG_j (pluecker_mul: on
//                 ECP5 MULT18X18D, operands over 18 bits split and summed in
//                 MA = (G+3 > 18) + (G+1 > 18) registered stages; or
//                 pluecker_mul_lut in fabric, MA = 0) after edge 4 + MA
//   F4..F6        ORG/END rounded and clamped (5), DIR (6), N (6), Mterm (7)
//   L1 edge 5+MA  lambda = P_ij - P_ji
//   L2 edge 6+MA  floor(lambda / 2^s), guard, sticky
//   L3 edge 7+MA  L = RNE, saturated at +-2^QS
//   L4 edge 8+MA  V = +-2L + Mterm, saturated at +-2^(K+D+2)
//   L5 edge 9+MA  W = clamp((V << l) + 1); every output registered
`default_nettype none

module pluecker_local_frame #(
    parameter int BOX_BITS = 8,    // K
    parameter int DIR_BITS = 11,   // D
    parameter int GRID_BITS = 32,  // G
    // Bits of one frame exponent (0..G-K+1); pluecker_local_intersector
    // passes its own, which must equal this default.
    parameter int EXP_BITS = $clog2(GRID_BITS - BOX_BITS + 2),
    parameter bit CONSERVATIVE = 1,
    // 1: the six moment products in fabric (pluecker_mul_lut), 0: pluecker_mul.
    parameter bit MUL_LUT = 0
) (
    input wire clk_i,

    input wire [             2:0] ray_class_i,
    input wire [ 3*GRID_BITS-1:0] ray_org_i,
    input wire [ 3*GRID_BITS-1:0] ray_dir_i,
    input wire [ 3*GRID_BITS-1:0] ray_end_i,
    input wire                    ray_end_valid_i,
    input wire [ 3*GRID_BITS-1:0] frame_org_i,
    input wire [  3*EXP_BITS-1:0] frame_exp_i,

    output wire [                         2:0] cls_o,
    output wire [                3*DIR_BITS-1:0] dir_o,
    output wire [6*(BOX_BITS+DIR_BITS+2)-1:0] w_o,
    output wire [            3*(BOX_BITS+2)-1:0] org_o,
    output wire [            3*(BOX_BITS+2)-1:0] end_o,
    output wire                                end_valid_o
);
  localparam int K = BOX_BITS;
  localparam int D = DIR_BITS;
  localparam int G = GRID_BITS;
  localparam int EW = EXP_BITS;

  if (EXP_BITS != $clog2(GRID_BITS - BOX_BITS + 2)) begin : g_bad_exp_bits
    $error("pluecker_local_frame: EXP_BITS must be $clog2(GRID_BITS - BOX_BITS + 2)");
  end
  if (BOX_BITS < 4 || DIR_BITS < 4 || GRID_BITS < BOX_BITS + 2 || GRID_BITS > 32) begin : g_bad_widths
    $error("pluecker_local_frame: needs BOX_BITS >= 4, DIR_BITS >= 4, BOX_BITS + 2 <= GRID_BITS <= 32");
  end

  // Pairs (i, j) of the six edge tests, k = 0..5; k and k + 3 are the two
  // orders of the unordered pair p = k (k < 3).
  function automatic int pair_i(input int k);
    pair_i = k / 2;
  endfunction
  function automatic int pair_j(input int k);
    pair_j = (k / 2 + 1 + k % 2) % 3;
  endfunction

  // -------------------------------------------------------------------------
  // Widths. Every bound holds for the contract's inputs; the saturations are
  // chosen so that they never change a clamped W.
  // -------------------------------------------------------------------------
  // S_i = (2^K - 1) 2^e_i < 2^(G+1) (e_i <= G-K+1): G+1 bits unsigned.
  localparam int WS = G + 1;
  // F~_i < 2^(G-1) + 2^(G+1); Delta_i, E offsets in (-2^G, 3 2^G): G+3 bits signed.
  localparam int WF = G + 3;
  // |Delta_i| < 3 2^G: G+2 bits unsigned.
  localparam int WABS = G + 2;
  // DG_i <= 2^(G-1) as a signed multiplier operand.
  localparam int WDG = G + 1;
  // Products Delta_i DG_j and lambda (|lambda| < 3 2^(2G) < 2^(2G+2)): the
  // full WF x WDG product width.
  localparam int WP = WF + WDG;
  // Products on ECP5: each operand wider than 18 bits adds an adder stage.
  localparam int DSP_OPERAND_BITS = 18;
  localparam int MUL_ADD = MUL_LUT ? 0 : ((WF > DSP_OPERAND_BITS) ? 1 : 0) + ((WDG > DSP_OPERAND_BITS) ? 1 : 0);
  // ORG, END in -1..2^K: K+2 bits signed.
  localparam int WO = K + 2;
  // W in [W_MIN, W_MAX], |W| < 2^(K+D+1): K+D+2 bits signed.
  localparam int WW = K + D + 2;
  // Leading zeros of DG (0..G) and c_i = e_i + lz - 1 (< 2^EW + G).
  localparam int LZW = $clog2(G + 1);
  localparam int CWID = $clog2((1 << EW) + G);
  // sh = G - D + e_i + e_j - c and the other shift counts as signed
  // integers: |.| < 4 2^EW + 4 G + 48 < 2^15.
  localparam int SHW = 16;
  // RNE(lambda / 2^s) is 0 for s >= 2G+3 (|lambda| < 2^(2G+2)): cap s there.
  localparam int SCAP = 2 * G + 3;
  localparam int SW = $clog2(SCAP + 1);
  // l = -sh <= D-K+1 (sh >= K-D-1 for the contract's inputs).
  localparam int LCAP = (D - K + 1 > 0) ? D - K + 1 : 0;
  localparam int LW = (LCAP > 0) ? $clog2(LCAP + 1) : 1;
  // N < 11 2^G + 1 < 2^(G+4); ceil(N / 2^m) = 1 for m >= G+4: cap m there.
  // N + 2^m - 1 (the ceil as a floor) and Mterm < 2^(G+5): G+5 bits.
  localparam int WN = G + 5;
  localparam int MSCAP = G + 4;
  localparam int MSW = $clog2(MSCAP + 1);
  // DIR: DG << (D-2) (<= 2^(G+D-3)) shifted right by u = G-2+e_i-c >= K-3
  // with RNE; the result is 0 for u >= G+D-2: cap u there.
  localparam int WX = G + D - 2;
  localparam int UCAP = G + D - 2;
  localparam int UW = $clog2(UCAP + 1);
  // L saturated at +-2^QS, QS = max(G+4, K+D+1) + 1: when |L| >= 2^QS,
  // |+-2L + Mterm| >= 2^(QS+1) - 2^(G+4) > 2^(K+D+2) and W clamps by the
  // sign whatever L is. L_s: QS+2 bits signed.
  localparam int QS = (((G + 4) > (K + D + 1)) ? (G + 4) : (K + D + 1)) + 1;
  localparam int WLS = QS + 2;
  // V = +-2 L_s + Mterm, |V| < 2^(QS+1) + 2^(G+4) < 2^(QS+2): QS+3 bits.
  localparam int WV = QS + 3;
  // V saturated at +-2^(K+D+2) (beyond, (V << l) + 1 clamps by the sign):
  // K+D+4 bits signed; shifted left by up to LCAP.
  localparam int WVS = K + D + 4;
  localparam int WZ = WVS + LCAP;
  // The clamp of W (LocalFormat::w_max, w_min).
  localparam logic signed [WZ-1:0] W_MAX = WZ'(((1 << K) - 1)) <<< D;
  localparam logic signed [WZ-1:0] W_MIN = -W_MAX - WZ'(2 << K) + WZ'(1);

  // Mask of the low n bits of a w-bit word (n may exceed w: all ones).
  // Written per width below as ~({W{1'b1}} << n).

  // -------------------------------------------------------------------------
  // F0: input registers
  // -------------------------------------------------------------------------
  logic [2:0] cls0_q;
  logic endv0_q;
  logic [2:0][G-1:0] org0_q, dg0_q, end0_q, forg0_q;
  logic [2:0][EW-1:0] exp0_q;

  always_ff @(posedge clk_i) begin
    cls0_q  <= ray_class_i;
    endv0_q <= ray_end_valid_i;
    org0_q  <= ray_org_i;
    dg0_q   <= ray_dir_i;
    end0_q  <= ray_end_i;
    forg0_q <= frame_org_i;
    exp0_q  <= frame_exp_i;
  end

  // -------------------------------------------------------------------------
  // F1: S_i, the mirrored frame origin F~_i, c_i
  // -------------------------------------------------------------------------
  function automatic logic [LZW-1:0] lead_zeros(input logic [G-1:0] x);
    lead_zeros = LZW'(G);
    for (int b = 0; b < G; b++) if (x[b]) lead_zeros = LZW'(G - 1 - b);
  endfunction

  logic [2:0][WS-1:0] s_d;
  logic [2:0][WF-1:0] ftil_d;
  logic [2:0][CWID-1:0] ci_d;
  logic [2:0] nz_d;

  for (genvar i = 0; i < 3; i++) begin : g_f1
    wire signed [WF-1:0] f = WF'($signed(forg0_q[i]));
    wire [LZW-1:0] lz = lead_zeros(dg0_q[i]);
    assign s_d[i] = WS'((1 << K) - 1) << exp0_q[i];
    assign ftil_d[i] = cls0_q[i] ? f + WF'(s_d[i]) : f;
    // c_i = e_i for the largest component (lz = 0), else e_i + G - 1 - bitlen.
    assign ci_d[i] = CWID'(exp0_q[i]) + ((lz == '0) ? '0 : CWID'(lz) - CWID'(1));
    assign nz_d[i] = dg0_q[i] != '0;
  end

  logic [2:0] cls1_q;
  logic [2:0][G-1:0] org1_q, dg1_q, end1_q;
  logic [2:0][EW-1:0] exp1_q;
  logic [2:0][WS-1:0] s1_q;
  logic [2:0][WF-1:0] ftil1_q;
  logic [2:0][CWID-1:0] ci1_q;
  logic [2:0] nz1_q;

  always_ff @(posedge clk_i) begin
    cls1_q  <= cls0_q;
    org1_q  <= org0_q;
    dg1_q   <= dg0_q;
    end1_q  <= end0_q;
    exp1_q  <= exp0_q;
    s1_q    <= s_d;
    ftil1_q <= ftil_d;
    ci1_q   <= ci_d;
    nz1_q   <= nz_d;
  end

  // -------------------------------------------------------------------------
  // F2: Delta_i and the end offsets, c, pair sums; multiplier operands
  // -------------------------------------------------------------------------
  logic [2:0][WF-1:0] delta_d, de_d;

  for (genvar i = 0; i < 3; i++) begin : g_f2
    wire signed [WF-1:0] ft = ftil1_q[i];
    wire signed [WF-1:0] o = WF'($signed(org1_q[i]));
    wire signed [WF-1:0] e = WF'($signed(end1_q[i]));
    assign delta_d[i] = cls1_q[i] ? ft - o : o - ft;
    assign de_d[i] = cls1_q[i] ? ft - e : e - ft;
  end

  // c = min c_i over the non-zero components (0 when all are zero).
  logic [CWID-1:0] c_d;
  logic c_any;
  always_comb begin
    c_d = '0;
    c_any = 1'b0;
    for (int i = 0; i < 3; i++) begin
      if (nz1_q[i] && (!c_any || ci1_q[i] < c_d)) c_d = ci1_q[i];
      if (nz1_q[i]) c_any = 1'b1;
    end
  end

  // Per unordered pair p = (i, j) of k = p: S_i + S_j and DG_i + DG_j + 1.
  logic [2:0][WS:0] sd_d;
  logic [2:0][G:0] dd_d;
  for (genvar p = 0; p < 3; p++) begin : g_pairsum
    localparam int I = pair_i(p);
    localparam int J = pair_j(p);
    assign sd_d[p] = {1'b0, s1_q[I]} + {1'b0, s1_q[J]};
    assign dd_d[p] = {1'b0, dg1_q[I]} + {1'b0, dg1_q[J]} + (G + 1)'(1);
  end

  // The six products Delta_i * DG_j, registered in the multipliers (operands
  // at edge 3, product at edge 4 + MUL_ADD).
  wire [5:0][WP-1:0] prod_q;
  for (genvar k = 0; k < 6; k++) begin : g_mul
    localparam int I = pair_i(k);
    localparam int J = pair_j(k);
    if (MUL_LUT) begin : g_lut
      pluecker_mul_lut #(.WA(WF), .WB(WDG), .PIPELINE(0)) u_mul (
          .clk_i(clk_i), .a_i(delta_d[I]), .b_i({1'b0, dg1_q[J]}), .p_o(prod_q[k]));
    end else begin : g_dsp
      pluecker_mul #(.WA(WF), .WB(WDG), .PIPELINE(0), .ADD_STAGES(MUL_ADD)) u_mul (
          .clk_i(clk_i), .a_i(delta_d[I]), .b_i({1'b0, dg1_q[J]}), .p_o(prod_q[k]));
    end
  end

  logic [2:0][WF-1:0] delta2_q, de2_q;
  logic [2:0][EW-1:0] exp2_q;
  logic [2:0][G-1:0] dg2_q;
  logic [CWID-1:0] c2_q;
  logic [2:0][WS:0] sd2_q;
  logic [2:0][G:0] dd2_q;

  always_ff @(posedge clk_i) begin
    delta2_q <= delta_d;
    de2_q    <= de_d;
    exp2_q   <= exp1_q;
    dg2_q    <= dg1_q;
    c2_q     <= c_d;
    sd2_q    <= sd_d;
    dd2_q    <= dd_d;
  end

  // -------------------------------------------------------------------------
  // F3: ORG/END shifted by e_i, |Delta_i|, the shift counts, S + DG sums
  // -------------------------------------------------------------------------
  // Floor of x / 2^e with the guard bit (the last bit shifted out) and the
  // sticky bit (any below it): RNE adds guard & (sticky | lsb).
  logic [2:0][WF-1:0] org_fl_d, end_fl_d;
  logic [2:0] org_g_d, org_s_d, end_g_d, end_s_d;
  logic [2:0][WABS-1:0] abs_d;

  for (genvar i = 0; i < 3; i++) begin : g_f3
    wire signed [WF:0] ox = {delta2_q[i], 1'b0};
    wire signed [WF:0] oy = ox >>> exp2_q[i];
    assign org_fl_d[i] = oy[WF:1];
    assign org_g_d[i] = oy[0];
    assign org_s_d[i] = |(ox & ~({(WF + 1) {1'b1}} << exp2_q[i]));
    if (CONSERVATIVE) begin : g_ceil
      // END = ceil(x / 2^e): floor plus 'any bit shifted out' (in end_s).
      wire signed [WF-1:0] ex = de2_q[i];
      assign end_fl_d[i] = ex >>> exp2_q[i];
      assign end_g_d[i] = 1'b0;
      assign end_s_d[i] = |(ex & ~({WF{1'b1}} << exp2_q[i]));
    end else begin : g_rne
      wire signed [WF:0] ex = {de2_q[i], 1'b0};
      wire signed [WF:0] ey = ex >>> exp2_q[i];
      assign end_fl_d[i] = ey[WF:1];
      assign end_g_d[i] = ey[0];
      assign end_s_d[i] = |(ex & ~({(WF + 1) {1'b1}} << exp2_q[i]));
    end
    // |Delta| < 2^(G+2): the low WABS bits of Delta or of its negation.
    assign abs_d[i] = WABS'(delta2_q[i][WF-1] ? -delta2_q[i] : delta2_q[i]);
  end

  // Shift counts per pair: s = clamp(sh, 0, SCAP), l = clamp(-sh, 0, LCAP),
  // m = clamp(sh + 1, 0, MSCAP) (used when sh >= 0), and per axis the DIR
  // shift u = clamp(G - 2 + e_i - c, 0, UCAP).
  logic [2:0][SW-1:0] s_cnt_d;
  logic [2:0][LW-1:0] l_cnt_d;
  logic [2:0][MSW-1:0] m_cnt_d;
  logic [2:0] nonneg_d;
  logic [2:0][UW-1:0] u_cnt_d;
  logic [2:0][WS+1:0] sdd_d;

  for (genvar p = 0; p < 3; p++) begin : g_sh
    localparam int I = pair_i(p);
    localparam int J = pair_j(p);
    wire signed [SHW-1:0] sh = SHW'(G - D) + SHW'(exp2_q[I]) + SHW'(exp2_q[J]) - SHW'(c2_q);
    wire signed [SHW-1:0] nsh = -sh;
    wire signed [SHW-1:0] sh1 = sh + SHW'(1);
    assign nonneg_d[p] = !sh[SHW-1];
    assign s_cnt_d[p] = sh[SHW-1] ? '0 : (sh > SHW'(SCAP)) ? SW'(SCAP) : SW'(sh);
    assign l_cnt_d[p] = !sh[SHW-1] ? '0 : (nsh > SHW'(LCAP)) ? LW'(LCAP) : LW'(nsh);
    assign m_cnt_d[p] = sh[SHW-1] ? '0 : (sh1 > SHW'(MSCAP)) ? MSW'(MSCAP) : MSW'(sh1);
    // S_i + S_j + DG_i + DG_j + 1 (< 2^(G+3))
    assign sdd_d[p] = (WS + 2)'(sd2_q[p]) + (WS + 2)'(dd2_q[p]);
  end
  for (genvar i = 0; i < 3; i++) begin : g_ucnt
    wire signed [SHW-1:0] u = SHW'(G - 2) + SHW'(exp2_q[i]) - SHW'(c2_q);
    assign u_cnt_d[i] = u[SHW-1] ? '0 : (u > SHW'(UCAP)) ? UW'(UCAP) : UW'(u);
  end

  logic [2:0][WF-1:0] org_fl3_q, end_fl3_q;
  logic [2:0] org_g3_q, org_s3_q, end_g3_q, end_s3_q;
  logic [2:0][WABS-1:0] abs3_q;
  logic [2:0][SW-1:0] s_cnt3_q;
  logic [2:0][LW-1:0] l_cnt3_q;
  logic [2:0][MSW-1:0] m_cnt3_q;
  logic [2:0] nonneg3_q;
  logic [2:0][UW-1:0] u_cnt3_q;
  logic [2:0][WS+1:0] sdd3_q;
  logic [2:0][G-1:0] dg3_q;

  always_ff @(posedge clk_i) begin
    org_fl3_q <= org_fl_d;
    end_fl3_q <= end_fl_d;
    org_g3_q  <= org_g_d;
    org_s3_q  <= org_s_d;
    end_g3_q  <= end_g_d;
    end_s3_q  <= end_s_d;
    abs3_q    <= abs_d;
    s_cnt3_q  <= s_cnt_d;
    l_cnt3_q  <= l_cnt_d;
    m_cnt3_q  <= m_cnt_d;
    nonneg3_q <= nonneg_d;
    u_cnt3_q  <= u_cnt_d;
    sdd3_q    <= sdd_d;
    dg3_q     <= dg2_q;
  end

  // -------------------------------------------------------------------------
  // F4: ORG/END rounded and clamped; the DIR shift; N's sums
  // -------------------------------------------------------------------------
  function automatic logic [WO-1:0] clamp_cells(input logic signed [WF:0] r);
    if (r < -(WF + 1)'(1)) clamp_cells = -WO'(1);
    else if (r > (WF + 1)'(1 << K)) clamp_cells = WO'(1 << K);
    else clamp_cells = r[WO-1:0];
  endfunction

  logic [2:0][WO-1:0] org4_d, end4_d;
  logic [2:0][D-1:0] dir_fl_d;
  logic [2:0] dir_g_d, dir_s_d;
  logic [2:0][G+2:0] a2_d;
  logic [2:0][WN-1:0] sddm_d;

  for (genvar i = 0; i < 3; i++) begin : g_f4
    wire org_up = org_g3_q[i] & (org_s3_q[i] | org_fl3_q[i][0]);
    wire end_up = CONSERVATIVE ? end_s3_q[i] : end_g3_q[i] & (end_s3_q[i] | end_fl3_q[i][0]);
    assign org4_d[i] = clamp_cells((WF + 1)'($signed(org_fl3_q[i])) + (WF + 1)'(org_up));
    assign end4_d[i] = clamp_cells((WF + 1)'($signed(end_fl3_q[i])) + (WF + 1)'(end_up));
    // DG << (D-2), with a zero below for the guard: WX + 2 bits, shifted by
    // u. The floor is at most 2^(D-1) for the contract's inputs: D bits kept.
    wire [WX+1:0] dx = {1'b0, dg3_q[i], {(D - 2) {1'b0}}, 1'b0};
    wire [WX+1:0] dy = dx >> u_cnt3_q[i];
    assign dir_fl_d[i] = D'(dy[WX+1:1]);
    assign dir_g_d[i] = dy[0];
    assign dir_s_d[i] = |(dx & ~({(WX + 2) {1'b1}} << u_cnt3_q[i]));
  end
  for (genvar p = 0; p < 3; p++) begin : g_nsum
    localparam int I = pair_i(p);
    localparam int J = pair_j(p);
    assign a2_d[p] = (G + 3)'(abs3_q[I]) + (G + 3)'(abs3_q[J]);
    // + 2^m - 1 when sh >= 0: then floor((N + 2^m - 1) / 2^m) = ceil(N / 2^m).
    wire [WN-1:0] mask = nonneg3_q[p] ? ~({WN{1'b1}} << m_cnt3_q[p]) : '0;
    assign sddm_d[p] = WN'(sdd3_q[p]) + mask;
  end

  logic [2:0][WO-1:0] org4_q, end4_q;
  logic [2:0][D-1:0] dir_fl4_q;
  logic [2:0] dir_g4_q, dir_s4_q;
  logic [2:0][G+2:0] a24_q;
  logic [2:0][WN-1:0] sddm4_q;
  logic [2:0][MSW-1:0] m_cnt4_q;
  logic [2:0] nonneg4_q;

  always_ff @(posedge clk_i) begin
    org4_q    <= org4_d;
    end4_q    <= end4_d;
    dir_fl4_q <= dir_fl_d;
    dir_g4_q  <= dir_g_d;
    dir_s4_q  <= dir_s_d;
    a24_q     <= a2_d;
    sddm4_q   <= sddm_d;
    m_cnt4_q  <= m_cnt3_q;
    nonneg4_q <= nonneg3_q;
  end

  // -------------------------------------------------------------------------
  // F5: DIR rounded; N (+ 2^m - 1). F6: Mterm.
  // -------------------------------------------------------------------------
  logic [2:0][D-1:0] dir5_d;
  logic [2:0][WN-1:0] n5_d;
  for (genvar i = 0; i < 3; i++) begin : g_f5
    wire up = dir_g4_q[i] & (dir_s4_q[i] | dir_fl4_q[i][0]);
    assign dir5_d[i] = dir_fl4_q[i] + D'(up);  // <= 2^(D-1) for the contract's inputs
  end
  for (genvar p = 0; p < 3; p++) begin : g_n
    assign n5_d[p] = WN'(a24_q[p]) + sddm4_q[p];
  end

  logic [2:0][D-1:0] dir5_q;
  logic [2:0][WN-1:0] n5_q;
  logic [2:0][MSW-1:0] m_cnt5_q;
  logic [2:0] nonneg5_q;
  always_ff @(posedge clk_i) begin
    dir5_q    <= dir5_d;
    n5_q      <= n5_d;
    m_cnt5_q  <= m_cnt4_q;
    nonneg5_q <= nonneg4_q;
  end

  // Mterm = 2 ceil(N / 2^(sh+1)) for sh >= 0, N for sh < 0 (conservative;
  // nearest mode adds no margin).
  logic [2:0][WN-1:0] mterm6_d, mterm6_q;
  for (genvar p = 0; p < 3; p++) begin : g_mterm
    // 2 mu = 2 floor((N + 2^m - 1) / 2^m) < 2^(G+4)
    assign mterm6_d[p] = !CONSERVATIVE ? '0 : nonneg5_q[p] ? (n5_q[p] >> m_cnt5_q[p]) << 1 : n5_q[p];
  end
  always_ff @(posedge clk_i) mterm6_q <= mterm6_d;

  // -------------------------------------------------------------------------
  // L1..L5: lambda, its rounding, V and W
  // -------------------------------------------------------------------------
  // Shift counts and Mterm carried to where the lambda path needs them.
  wire [2:0][SW-1:0] s_cnt_l2;  // at L1 (edge 5 + MA)
  wire [2:0][LW-1:0] l_cnt_l5;  // at L4 (edge 8 + MA)
  wire [2:0][WN-1:0] mterm_l4;  // at L3 (edge 7 + MA)
  pluecker_pipe #(.WIDTH(3 * SW), .STAGES(1 + MUL_ADD)) u_s_pipe (
      .clk_i(clk_i), .d_i(s_cnt3_q), .q_o(s_cnt_l2));
  pluecker_pipe #(.WIDTH(3 * LW), .STAGES(4 + MUL_ADD)) u_l_pipe (
      .clk_i(clk_i), .d_i(l_cnt3_q), .q_o(l_cnt_l5));
  pluecker_pipe #(.WIDTH(3 * WN), .STAGES(MUL_ADD)) u_m_pipe (
      .clk_i(clk_i), .d_i(mterm6_q), .q_o(mterm_l4));

  // L1: lambda_p = P_ij - P_ji
  logic [2:0][WP-1:0] lam1_q;
  always_ff @(posedge clk_i) begin
    for (int p = 0; p < 3; p++) lam1_q[p] <= prod_q[p] - prod_q[p+3];
  end

  // L2: floor(lambda / 2^s), guard, sticky
  logic [2:0][WP-1:0] lam_fl2_d, lam_fl2_q;
  logic [2:0] lam_g2_d, lam_s2_d, lam_g2_q, lam_s2_q;
  for (genvar p = 0; p < 3; p++) begin : g_l2
    wire signed [WP:0] x = {lam1_q[p], 1'b0};
    wire signed [WP:0] y = x >>> s_cnt_l2[p];
    assign lam_fl2_d[p] = y[WP:1];
    assign lam_g2_d[p] = y[0];
    assign lam_s2_d[p] = |(x & ~({(WP + 1) {1'b1}} << s_cnt_l2[p]));
  end
  always_ff @(posedge clk_i) begin
    lam_fl2_q <= lam_fl2_d;
    lam_g2_q  <= lam_g2_d;
    lam_s2_q  <= lam_s2_d;
  end

  // L3: L = floor + RNE increment, saturated at +-2^QS.
  localparam logic signed [WLS-1:0] L_SAT = WLS'(1) <<< QS;
  logic [2:0][WLS-1:0] ls3_d, ls3_q;
  for (genvar p = 0; p < 3; p++) begin : g_l3
    wire signed [WP-1:0] fl = lam_fl2_q[p];
    wire up = lam_g2_q[p] & (lam_s2_q[p] | fl[0]);
    if (WP <= QS + 1) begin : g_fits  // fl fits QS+1 bits: no saturation
      assign ls3_d[p] = WLS'(fl) + WLS'(up);
    end else begin : g_sat
      // fl in [-2^QS, 2^QS - 1] <=> its bits QS..WP-1 are all equal.
      wire [WP-QS-1:0] top = fl[WP-1:QS];
      wire in_range = (&top) || !(|top);
      wire signed [WLS-1:0] near = WLS'($signed(fl[QS:0])) + WLS'(up);
      assign ls3_d[p] = in_range ? near : fl[WP-1] ? -L_SAT : L_SAT;
    end
  end
  always_ff @(posedge clk_i) ls3_q <= ls3_d;

  // L4: V = +-2 L + Mterm for k and k + 3, saturated at +-2^(K+D+2).
  localparam logic signed [WVS-1:0] V_SAT = WVS'(1) <<< (K + D + 2);
  logic [5:0][WVS-1:0] vs4_d, vs4_q;
  for (genvar k = 0; k < 6; k++) begin : g_l4
    localparam int P = k % 3;
    wire signed [WV-1:0] l2 = WV'($signed(ls3_q[P])) <<< 1;
    wire signed [WV-1:0] v = ((k < 3) ? l2 : -l2) + WV'(mterm_l4[P]);
    wire [WV-(K+D+2)-1:0] top = v[WV-1:K+D+2];
    wire in_range = (&top) || !(|top);
    assign vs4_d[k] = in_range ? WVS'(v) : v[WV-1] ? -V_SAT : V_SAT;
  end
  always_ff @(posedge clk_i) vs4_q <= vs4_d;

  // L5: W = clamp((V << l) + 1) (conservative) or clamp(V << l).
  logic [5:0][WW-1:0] w5_d, w5_q;
  for (genvar k = 0; k < 6; k++) begin : g_l5
    localparam int P = k % 3;
    wire signed [WZ-1:0] z = (WZ'($signed(vs4_q[k])) <<< l_cnt_l5[P]) + WZ'(CONSERVATIVE ? 1 : 0);
    assign w5_d[k] = (z > W_MAX) ? WW'(W_MAX) : (z < W_MIN) ? WW'(W_MIN) : WW'(z);
  end
  always_ff @(posedge clk_i) w5_q <= w5_d;

  // -------------------------------------------------------------------------
  // Outputs, all registered at edge 9 + MA
  // -------------------------------------------------------------------------
  pluecker_pipe #(.WIDTH(4), .STAGES(8 + MUL_ADD)) u_cls_pipe (
      .clk_i(clk_i), .d_i({cls0_q, endv0_q}), .q_o({cls_o, end_valid_o}));
  pluecker_pipe #(.WIDTH(3 * D), .STAGES(3 + MUL_ADD)) u_dir_pipe (
      .clk_i(clk_i), .d_i(dir5_q), .q_o(dir_o));
  pluecker_pipe #(.WIDTH(6 * WO), .STAGES(4 + MUL_ADD)) u_org_pipe (
      .clk_i(clk_i), .d_i({end4_q, org4_q}), .q_o({end_o, org_o}));
  assign w_o = w5_q;

endmodule

`default_nettype wire
