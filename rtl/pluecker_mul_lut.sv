// SPDX-License-Identifier: MIT
// Registered signed multiply in FPGA fabric (LUTs and carry chains), a
// drop-in for pluecker_mul with the same ports, the same product and the
// same latency:
//   p_o = a_i * b_i (signed WA x WB, full WA+WB-bit product),
//   2 (+1 with PIPELINE) clock edges after a_i, b_i.
//
// It contains no `*`, so no synthesis tool can map it to a DSP block; the
// intersector uses it at narrow widths, where twelve MULT18X18D blocks per
// unit (not LUTs) would limit how many units fit on a chip.
//
// Structure
//   edge 1  the WB partial-product rows r_j = b_i[j] ? a_i : 0 (signed,
//           WA bits) are registered (where a DSP has its input registers)
//   comb.   the rows are summed by a balanced binary tree of adders:
//             a*b = sum_{j<WB-1} r_j 2^j - r_{WB-1} 2^(WB-1)
//           (the row of the sign bit of b is subtracted). A node covering
//           c rows holds |value| <= 2^(WA-1) (2^c - 1), WA + c signed bits
//           (WA for a single row), capped at the product bits above its
//           lowest row (all arithmetic is modulo 2^(WA+WB)). Adding a node
//           whose rows start k rows higher leaves the low k bits of the
//           left node as they are: each adder is only as wide as the
//           overlap plus its growth, never the full product width.
//   edge 2  PIPELINE >= 1 only: the nodes of tree level PL = ceil(LV/2)
//           are registered (the tree cut in the middle, so each of the two
//           clock periods holds about half of its adders; a register after
//           the product would leave the whole tree in one period)
//   edge 2  (edge 3 with PIPELINE) p_q <= root of the tree (as a DSP's
//           output register)
//   edge 4  PIPELINE = 2 only: p_q registered once more (the latency of
//           pluecker_mul's fabric register after the block)
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
  localparam int LV = $clog2(WB);  // tree levels above the rows
  localparam int PL = (LV + 1) / 2;  // PIPELINE: the registered level (1..LV)

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

  // Edge 1: the partial-product rows r_j = b_i[j] ? a_i : 0 (one LUT level
  // in front of the registers; the adder tree alone is left for edge 2).
  logic [WB-1:0][WA-1:0] row_q;

  for (genvar j = 0; j < WB; j++) begin : g_rowreg
    always_ff @(posedge clk_i) row_q[j] <= b_i[j] ? a_i : '0;
  end

  // Node g of level l is g_lvl[l].g_node[g].v, width_of(l, g) bits (one
  // signal per node, read by its parent only): its sum c, registered at
  // level PL with PIPELINE.
  for (genvar l = 0; l <= LV; l++) begin : g_lvl
    for (genvar g = 0; g < (WB + (1 << l) - 1) >> l; g++) begin : g_node
      localparam int WD = width_of(l, g);
      wire [WD-1:0] c, v;
      if (PIPELINE != 0 && l == PL) begin : g_reg
        logic [WD-1:0] v_q;
        always_ff @(posedge clk_i) v_q <= c;
        assign v = v_q;
      end else begin : g_wire
        assign v = c;
      end
      if (l == 0) begin : g_row
        // Row g (the sign row too: the adder tree subtracts it).
        assign c = row_q[g];
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

  if (PIPELINE > 1) begin : g_out_reg
    logic signed [W-1:0] p2_q;
    always_ff @(posedge clk_i) p2_q <= p_q;
    assign p_o = p2_q;
  end else begin : g_out_wire
    assign p_o = p_q;
  end

endmodule

`default_nettype wire
