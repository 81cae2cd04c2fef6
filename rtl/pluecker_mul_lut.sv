// SPDX-License-Identifier: MIT
// Registered signed multiply in FPGA fabric (LUTs and carry chains), a
// drop-in for pluecker_mul with the same ports, the same product and the
// same latency:
//   p_o = a_i * b_i (signed WA x WB, full WA+WB-bit product),
//   2 + PIPELINE clock edges after a_i, b_i.
//
// It contains no `*`, so no synthesis tool can map it to a DSP block; the
// intersector uses it at narrow widths, where twelve MULT18X18D blocks per
// unit (not LUTs) would limit how many units fit on a chip.
//
// Structure
//   The WB partial-product rows r_j = b_i[j] ? a_i : 0 (signed, WA bits;
//   tree level 0) are summed by a balanced binary tree of adders (levels
//   1..LV, LV = ceil(log2 WB)):
//     a*b = sum_{j<WB-1} r_j 2^j - r_{WB-1} 2^(WB-1)
//   (the row of the sign bit of b is subtracted). A node covering c rows
//   holds |value| <= 2^(WA-1) (2^c - 1), WA + c signed bits (WA for a
//   single row), capped at the product bits above its lowest row (all
//   arithmetic is modulo 2^(WA+WB)). Adding a node whose rows start k rows
//   higher leaves the low k bits of the left node as they are: each adder
//   is only as wide as the overlap plus its growth, never the full product
//   width. The root is registered in p_q (as a DSP's output register);
//   the clock edges before it register whole tree levels:
//     PIPELINE 0  level 0 (the rows, where a DSP has its input registers;
//                 the row AND sits in front of the flops), then p_q
//     PIPELINE 1  also level PL = ceil(LV/2) (the tree cut in the middle:
//                 each of the two periods holds about half of its adders)
//     PIPELINE 2  LV >= 3: levels (LV-2)/2, LV-2 and LV-1, then p_q: for
//                 LV = 3 the rows and levels 1 and 2, for LV = 4 (WB 9..16)
//                 levels 1, 2 and 3 (the row AND in front of the level-1
//                 adders), for LV = 5 levels 1, 3 and 4; at most one
//                 adder level per period up to WB = 16.
//                 LV < 3: as PIPELINE 1, and p_q registered once more.
//   Latency: 2 + PIPELINE clock edges (pluecker_mul's). Which levels are
//   registered is one rule, in pluecker_mul_lut_pkg.sv.
//
// With b_i's top bit tied to zero (a non-negative operand, as the
// intersector's directions are), the subtracted row is constant zero and
// the synthesis tool removes it.
`default_nettype none

module pluecker_mul_lut #(
    parameter int WA = 17,
    parameter int WB = 17,
    parameter int PIPELINE = 0
) (
    input  wire                    clk_i,
    input  wire signed [WA-1:0]    a_i,
    input  wire signed [WB-1:0]    b_i,
    output wire signed [WA+WB-1:0] p_o
);
  if (PIPELINE < 0 || PIPELINE > 2) begin : g_bad_pipeline
    $error("pluecker_mul_lut: parameter PIPELINE must be 0, 1 or 2");
  end
  if (WA < 2 || WB < 2) begin : g_bad_width
    $error("pluecker_mul_lut: parameters WA and WB must be at least 2");
  end

  localparam int W = WA + WB;  // product bits
  localparam int LV = pluecker_mul_lut_pkg::mul_lut_levels(WB);  // tree levels above the rows

  // Rows covered by node g of level l: rows g*2^l .. min((g+1)*2^l, WB) - 1.
  function automatic int rows_of(input int l, input int g);
    int lo, hi;
    lo = g << l;
    hi = (g + 1) << l;
    if (hi > WB) hi = WB;
    rows_of = (hi > lo) ? hi - lo : 0;
  endfunction

  // Signed bits a node needs (see the header), capped at the product bits
  // above its lowest row.
  function automatic int width_of(input int l, input int g);
    int c, w;
    c = rows_of(l, g);
    w = (c == 1) ? WA : WA + c;
    if (w > W - (g << l)) w = W - (g << l);
    width_of = w;
  endfunction

  // PIPELINE 2 with LV >= 3 spreads three registers over the tree and
  // needs no register after p_q (see the header).
  localparam bit SPREAD = pluecker_mul_lut_pkg::mul_lut_spread(PIPELINE, LV);

  // Whether the nodes of tree level l are registered (level 0: the rows).
  // The rule lives in pluecker_mul_lut_pkg, where pluecker_intersector
  // reads it too (DIR_COPIES: a direction register of each multiplier's
  // own where level 0 is not registered).
  function automatic bit registered(input int l);
    registered = pluecker_mul_lut_pkg::mul_lut_registered(PIPELINE, LV, l);
  endfunction

  // Node g of level l is g_lvl[l].g_node[g].v, width_of(l, g) bits (one
  // signal per node, read by its parent only): its sum c (at level 0 the
  // row g), registered where registered(l) says.
  for (genvar l = 0; l <= LV; l++) begin : g_lvl
    for (genvar g = 0; g < (WB + (1 << l) - 1) >> l; g++) begin : g_node
      localparam int WD = width_of(l, g);
      wire [WD-1:0] c, v;
      if (registered(l)) begin : g_reg
        logic [WD-1:0] v_q;
        always_ff @(posedge clk_i) v_q <= c;
        assign v = v_q;
      end else begin : g_wire
        assign v = c;
      end
      if (l == 0) begin : g_row
        // Row g (the sign row too: the adder tree subtracts it).
        assign c = b_i[g] ? a_i : '0;
      end else if (rows_of(l - 1, 2 * g + 1) == 0) begin : g_pass
        // No right child: the left child is this node (same width).
        assign c = g_lvl[l-1].g_node[2*g].v;
      end else begin : g_add
        localparam int K = 1 << (l - 1);  // the right child starts K rows up
        localparam int WL = width_of(l - 1, 2 * g);
        localparam int WR = width_of(l - 1, 2 * g + 1);
        localparam int WS = WD - K;  // adder width
        // The right child is the sign row of b alone: subtract it.
        localparam bit SUB = ((2 * g + 1) << (l - 1)) == WB - 1;
        wire [WL-1:0] left = g_lvl[l-1].g_node[2*g].v;
        wire signed [WR-1:0] right = g_lvl[l-1].g_node[2*g+1].v;
        wire signed [WL-K-1:0] hi = left[WL-1:K];
        wire signed [WS-1:0] s = SUB ? WS'(hi) - WS'(right) : WS'(hi) + WS'(right);
        assign c = {s, left[K-1:0]};
      end
    end
  end

  logic signed [W-1:0] p_q;

  always_ff @(posedge clk_i) begin
    p_q <= g_lvl[LV].g_node[0].v;
  end

  if (PIPELINE > 1 && !SPREAD) begin : g_out_reg
    logic signed [W-1:0] p2_q;
    always_ff @(posedge clk_i) p2_q <= p_q;
    assign p_o = p2_q;
  end else begin : g_out_wire
    assign p_o = p_q;
  end

endmodule

`default_nettype wire
