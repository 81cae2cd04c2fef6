// SPDX-License-Identifier: MIT
// The child datapath of the local-frame box test: one K-bit box against the
// node ray of its frame, bit for bit local_hit of model/core/src/local.cpp
// (model/core/include/pluecker/local.hpp). A fixed-latency pipeline without a
// stall or an enable: hit_o answers the inputs applied before rising edge 1
// after edge LATENCY = 4 + MUL_ADD. Datapath only (no reset).
//
// Inputs (x in the low field; the node ray as pluecker_local_frame gives it)
//   cls_i            bit a set = axis a negative
//   dir_i            DIR, DIR_BITS unsigned each (any value: up to 2^D - 1)
//   w_i              W_k, K+D+2 bits signed each, pair order k = 0..5:
//                    (0,1) (0,2) (1,2) (1,0) (2,0) (2,1)
//   org_i, end_i     ORG, END, K+2 bits signed each (any value)
//   end_valid_i      0: no end test
//   box_min_i, box_max_i  LO, HI: K bits unsigned each (any values, also LO > HI)
// Output: hit_o (combinational from the last registers: the AND of 7 flags).
//
// Datapath (local.hpp), n_i the class bit:
//   ent_i = n_i ? ~HI_i : LO_i,  ext_i = n_i ? ~LO_i : HI_i   (K bits)
//   origin test   ext_i - ORG_i >= 0 for all i
//   end test      no end, or END_i - ent_i >= 0 for all i
//   edge tests    V_ij = 2 (ext_j DIR_i - ent_i DIR_j) + M_ij + W_ij >= 0,
//                 M_ij = ext_j + ent_i (CONSERVATIVE), 0 (nearest)
//
// Pipeline (edge numbers: inputs applied before edge 1; MA = MUL_ADD)
//   C1 edge 1     ent/ext (the class picks them in front of the registers);
//                 the multipliers' operand registers
//   C2 edge 2     origin and end tests, M_ij + W_ij; the twelve products
//                 ext_j DIR_i, ent_i DIR_j after edge 2 + MA (pluecker_mul:
//                 MA = (D+1 > 18), the DIR operand split on ECP5;
//                 pluecker_mul_lut: MA = 0)
//   C3 edge 3+MA  X_ij = ext_j DIR_i - ent_i DIR_j
//   C4 edge 4+MA  V_ij >= 0
`default_nettype none

module pluecker_local_child #(
    parameter int BOX_BITS = 8,   // K
    parameter int DIR_BITS = 11,  // D
    parameter bit CONSERVATIVE = 1,
    // 1: the twelve products in fabric (pluecker_mul_lut), 0: pluecker_mul.
    parameter bit MUL_LUT = 1
) (
    input wire clk_i,

    input wire [                         2:0] cls_i,
    input wire [              3*DIR_BITS-1:0] dir_i,
    input wire [6*(BOX_BITS+DIR_BITS+2)-1:0] w_i,
    input wire [          3*(BOX_BITS+2)-1:0] org_i,
    input wire [          3*(BOX_BITS+2)-1:0] end_i,
    input wire                                end_valid_i,
    input wire [              3*BOX_BITS-1:0] box_min_i,
    input wire [              3*BOX_BITS-1:0] box_max_i,

    output wire hit_o
);
  localparam int K = BOX_BITS;
  localparam int D = DIR_BITS;

  if (BOX_BITS < 1 || DIR_BITS < 1) begin : g_bad_widths
    $error("pluecker_local_child: BOX_BITS and DIR_BITS must be at least 1");
  end

  function automatic int pair_i(input int k);
    pair_i = k / 2;
  endfunction
  function automatic int pair_j(input int k);
    pair_j = (k / 2 + 1 + k % 2) % 3;
  endfunction

  // -------------------------------------------------------------------------
  // Widths (for every value the inputs can carry)
  // -------------------------------------------------------------------------
  // Multiplier operands, zero-extended to signed: DIR (D+1), ent/ext (K+1).
  localparam int WMA = D + 1;
  localparam int WMB = K + 1;
  // Products (< 2^(K+D)) and X = difference of two: the full WMA x WMB
  // product width, K+D+2 bits signed.
  localparam int WX = WMA + WMB;
  localparam int DSP_OPERAND_BITS = 18;
  localparam int MUL_ADD = MUL_LUT ? 0 : ((WMA > DSP_OPERAND_BITS) ? 1 : 0) + ((WMB > DSP_OPERAND_BITS) ? 1 : 0);
  // ORG, END: K+2 bits signed; ext - ORG and END - ent: K+3 bits signed.
  localparam int WO = K + 2;
  localparam int WT = K + 3;
  // W: K+D+2 bits signed; M = ext_j + ent_i <= 2^(K+1) - 2; M + W: K+D+3.
  localparam int WW = K + D + 2;
  localparam int WMW = WW + 1;
  // V = 2X + M + W: |2X| < 2^(K+D+1), |M + W| < 2^(K+D+2): K+D+4 bits.
  localparam int WV = K + D + 4;

  // -------------------------------------------------------------------------
  // C1: entry and exit planes (registered), multiplier operands
  // -------------------------------------------------------------------------
  logic [2:0][K-1:0] ent_d, ext_d;
  for (genvar i = 0; i < 3; i++) begin : g_planes
    wire [K-1:0] lo = box_min_i[i*K+:K];
    wire [K-1:0] hi = box_max_i[i*K+:K];
    assign ent_d[i] = cls_i[i] ? ~hi : lo;
    assign ext_d[i] = cls_i[i] ? ~lo : hi;
  end

  // Products ext_j DIR_i (pb) and ent_i DIR_j (pa) of pair k, registered in
  // the multipliers (operands at edge 1, products at edge 2 + MUL_ADD).
  wire [5:0][WX-1:0] pb_q, pa_q;
  for (genvar k = 0; k < 6; k++) begin : g_mul
    localparam int I = pair_i(k);
    localparam int J = pair_j(k);
    wire [WMA-1:0] dir_i_op = {1'b0, dir_i[I*D+:D]};
    wire [WMA-1:0] dir_j_op = {1'b0, dir_i[J*D+:D]};
    if (MUL_LUT) begin : g_lut
      pluecker_mul_lut #(.WA(WMA), .WB(WMB), .PIPELINE(0)) u_mul_b (
          .clk_i(clk_i), .a_i(dir_i_op), .b_i({1'b0, ext_d[J]}), .p_o(pb_q[k]));
      pluecker_mul_lut #(.WA(WMA), .WB(WMB), .PIPELINE(0)) u_mul_a (
          .clk_i(clk_i), .a_i(dir_j_op), .b_i({1'b0, ent_d[I]}), .p_o(pa_q[k]));
    end else begin : g_dsp
      pluecker_mul #(.WA(WMA), .WB(WMB), .PIPELINE(0), .ADD_STAGES(MUL_ADD)) u_mul_b (
          .clk_i(clk_i), .a_i(dir_i_op), .b_i({1'b0, ext_d[J]}), .p_o(pb_q[k]));
      pluecker_mul #(.WA(WMA), .WB(WMB), .PIPELINE(0), .ADD_STAGES(MUL_ADD)) u_mul_a (
          .clk_i(clk_i), .a_i(dir_j_op), .b_i({1'b0, ent_d[I]}), .p_o(pa_q[k]));
    end
  end

  logic [2:0][K-1:0] ent1_q, ext1_q;
  logic [2:0][WO-1:0] org1_q, end1_q;
  logic [5:0][WW-1:0] w1_q;
  logic endv1_q;

  always_ff @(posedge clk_i) begin
    ent1_q  <= ent_d;
    ext1_q  <= ext_d;
    org1_q  <= org_i;
    end1_q  <= end_i;
    w1_q    <= w_i;
    endv1_q <= end_valid_i;
  end

  // -------------------------------------------------------------------------
  // C2: origin and end tests, M + W
  // -------------------------------------------------------------------------
  logic [2:0] org_ok_d, end_ok_d;
  for (genvar i = 0; i < 3; i++) begin : g_tests
    wire signed [WT-1:0] t_org = WT'(ext1_q[i]) - WT'($signed(org1_q[i]));
    wire signed [WT-1:0] t_end = WT'($signed(end1_q[i])) - WT'(ent1_q[i]);
    assign org_ok_d[i] = !t_org[WT-1];
    assign end_ok_d[i] = !t_end[WT-1];
  end

  logic [5:0][WMW-1:0] mw_d;
  for (genvar k = 0; k < 6; k++) begin : g_mw
    localparam int I = pair_i(k);
    localparam int J = pair_j(k);
    wire [WMW-1:0] m = CONSERVATIVE ? WMW'(ext1_q[J]) + WMW'(ent1_q[I]) : '0;
    assign mw_d[k] = m + WMW'($signed(w1_q[k]));
  end

  logic [5:0][WMW-1:0] mw2_q;
  logic ok2_q;
  always_ff @(posedge clk_i) begin
    mw2_q <= mw_d;
    ok2_q <= (&org_ok_d) && (!endv1_q || (&end_ok_d));
  end

  // While the products finish (MUL_ADD stages), M + W and the flags wait.
  wire [5:0][WMW-1:0] mw2x_q;
  wire ok2x_q;
  pluecker_pipe #(.WIDTH(6 * WMW + 1), .STAGES(MUL_ADD)) u_side_pipe (
      .clk_i(clk_i), .d_i({mw2_q, ok2_q}), .q_o({mw2x_q, ok2x_q}));

  // -------------------------------------------------------------------------
  // C3: X = ext_j DIR_i - ent_i DIR_j.  C4: 2X + M + W >= 0.
  // -------------------------------------------------------------------------
  logic [5:0][WX-1:0] x3_q;
  logic [5:0][WMW-1:0] mw3_q;
  logic ok3_q;
  always_ff @(posedge clk_i) begin
    for (int k = 0; k < 6; k++) x3_q[k] <= pb_q[k] - pa_q[k];
    mw3_q <= mw2x_q;
    ok3_q <= ok2x_q;
  end

  logic [5:0] edge_ok_d;
  for (genvar k = 0; k < 6; k++) begin : g_cmp
    wire signed [WV-1:0] v = (WV'($signed(x3_q[k])) <<< 1) + WV'($signed(mw3_q[k]));
    assign edge_ok_d[k] = !v[WV-1];
  end

  logic [5:0] edge_ok4_q;
  logic ok4_q;
  always_ff @(posedge clk_i) begin
    edge_ok4_q <= edge_ok_d;
    ok4_q      <= ok3_q;
  end

  assign hit_o = ok4_q && (&edge_ok4_q);

endmodule

`default_nettype wire
