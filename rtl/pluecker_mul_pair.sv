// SPDX-License-Identifier: MIT
// Two registered products with one shared signed operand in one MULT18X18D:
//   p0_o = a_i * b0_i, p1_o = a_i * b1_i
// (a_i WA-bit two's complement, b0_i and b1_i WU-bit unsigned), 4 clock
// edges after the operands, as pluecker_mul with PIPELINE = 2.
//
// The intersector multiplies each of its six differences A_i, B_j by two
// direction magnitudes (A_i by D_j and D_k, B_j by D_i and D_k), so at
// 6/6 bits six blocks do its twelve products (pluecker_intersector,
// MUL_STYLE "dsp", PIPELINE = 2): twice the DSP units per chip.
//
// Packing. With K = WA - 1 + WU, one block multiplies a (signed) by
//   B = b0 + b1 * 2^K  (unsigned; fits the 18-bit port when K + WU <= 18,
//                       i.e. COORD_BITS + 2 DIR_BITS <= 18 in the unit)
// so P = a*B = lo + hi * 2^K with lo = a*b0, hi = a*b1. Since
// |lo| <= 2^(WA-1) (2^WU - 1) < 2^K, lo is the (K+1)-bit two's complement
// {s, P[K-1:0]} with s = (lo < 0) = (a < 0 and b0 != 0), and the high
// bits of P are floor(P / 2^K) = hi - s, so hi = P[..:K] + s. s is taken
// from the operands and travels beside the block (3 flops); the fabric
// output register (the PIPELINE = 2 register of pluecker_mul) holds both
// products after the increment. Exact for every operand value.
//
// With PLUECKER_ECP5 defined (scripts/synth.py defines it for Yosys): one
// MULT18X18D, SIGNEDA = 1, SIGNEDB = 0, input, pipeline and output
// registers clocked (nextpnr-ecp5 does not time the internal pipeline
// register, see pluecker_mul). Otherwise (simulation, lint) the same
// packing around a generic 18 x 18 `*` with the same registers, so every
// simulation checks the packing arithmetic.
`default_nettype none

module pluecker_mul_pair #(
    parameter int WA = 7,  // signed operand a_i
    parameter int WU = 6,  // unsigned operands b0_i, b1_i
    // Product width (signed, as pluecker_mul with WB = WU + 1; not to be
    // overridden).
    localparam int W = WA + WU + 1
) (
    input  wire                   clk_i,
    input  wire signed [WA-1:0]   a_i,
    input  wire        [WU-1:0]   b0_i,
    input  wire        [WU-1:0]   b1_i,
    output wire signed [W-1:0]    p0_o,
    output wire signed [W-1:0]    p1_o
);
  localparam int K = WA - 1 + WU;  // weight of b1 in the packed operand
  if (WA < 2 || WU < 1 || WA > 18 || K + WU > 18) begin : g_bad_width
    $error("pluecker_mul_pair: needs 2 <= WA <= 18, WU >= 1 and WA - 1 + 2 WU <= 18");
  end

  wire [17:0] a18 = 18'($signed(a_i));
  wire [17:0] b18 = 18'({b1_i, K'(b0_i)});
  // s = (a*b0 < 0), delayed as the block delays its product (3 edges).
  wire s_d = a_i[WA-1] && (|b0_i);
  logic [2:0] s_q;
  always_ff @(posedge clk_i) s_q <= {s_q[1:0], s_d};

  // a*B, after the block's output register; bits above K + W - 1 only
  // repeat hi's sign (waived: unused by design).
  /* verilator lint_off UNUSEDSIGNAL */
  wire [35:0] p36;
  /* verilator lint_on UNUSEDSIGNAL */
`ifdef PLUECKER_ECP5
  MULT18X18D #(
      .REG_INPUTA_CLK  ("CLK0"),
      .REG_INPUTB_CLK  ("CLK0"),
      .REG_PIPELINE_CLK("CLK0"),
      .REG_OUTPUT_CLK  ("CLK0"),
      .GSR             ("DISABLED"),
      .RESETMODE       ("SYNC")
  ) u_mult (
      .A0(a18[0]), .A1(a18[1]), .A2(a18[2]), .A3(a18[3]), .A4(a18[4]), .A5(a18[5]),
      .A6(a18[6]), .A7(a18[7]), .A8(a18[8]), .A9(a18[9]), .A10(a18[10]), .A11(a18[11]),
      .A12(a18[12]), .A13(a18[13]), .A14(a18[14]), .A15(a18[15]), .A16(a18[16]), .A17(a18[17]),
      .B0(b18[0]), .B1(b18[1]), .B2(b18[2]), .B3(b18[3]), .B4(b18[4]), .B5(b18[5]),
      .B6(b18[6]), .B7(b18[7]), .B8(b18[8]), .B9(b18[9]), .B10(b18[10]), .B11(b18[11]),
      .B12(b18[12]), .B13(b18[13]), .B14(b18[14]), .B15(b18[15]), .B16(b18[16]), .B17(b18[17]),
      .C0(1'b0), .C1(1'b0), .C2(1'b0), .C3(1'b0), .C4(1'b0), .C5(1'b0),
      .C6(1'b0), .C7(1'b0), .C8(1'b0), .C9(1'b0), .C10(1'b0), .C11(1'b0),
      .C12(1'b0), .C13(1'b0), .C14(1'b0), .C15(1'b0), .C16(1'b0), .C17(1'b0),
      .SIGNEDA(1'b1), .SIGNEDB(1'b0), .SOURCEA(1'b0), .SOURCEB(1'b0),
      .CLK0(clk_i), .CLK1(1'b0), .CLK2(1'b0), .CLK3(1'b0),
      .CE0(1'b1), .CE1(1'b0), .CE2(1'b0), .CE3(1'b0),
      .RST0(1'b0), .RST1(1'b0), .RST2(1'b0), .RST3(1'b0),
      .P0(p36[0]), .P1(p36[1]), .P2(p36[2]), .P3(p36[3]), .P4(p36[4]), .P5(p36[5]),
      .P6(p36[6]), .P7(p36[7]), .P8(p36[8]), .P9(p36[9]), .P10(p36[10]), .P11(p36[11]),
      .P12(p36[12]), .P13(p36[13]), .P14(p36[14]), .P15(p36[15]), .P16(p36[16]), .P17(p36[17]),
      .P18(p36[18]), .P19(p36[19]), .P20(p36[20]), .P21(p36[21]), .P22(p36[22]), .P23(p36[23]),
      .P24(p36[24]), .P25(p36[25]), .P26(p36[26]), .P27(p36[27]), .P28(p36[28]), .P29(p36[29]),
      .P30(p36[30]), .P31(p36[31]), .P32(p36[32]), .P33(p36[33]), .P34(p36[34]), .P35(p36[35])
  );
`else
  begin : g_generic
    logic signed [17:0] a_q;
    logic [17:0] b_q;
    logic signed [35:0] m_q, p_q;
    always_ff @(posedge clk_i) begin
      a_q <= a18;
      b_q <= b18;
      m_q <= a_q * $signed({1'b0, b_q});  // signed x unsigned, exact in 36 bits
      p_q <= m_q;
    end
    assign p36 = p_q;
  end
`endif

  // The fabric output register: lo = {s, P[K-1:0]}, hi = P[K+W-1:K] + s,
  // both sign-extended to W bits.
  logic signed [W-1:0] p0_q, p1_q;
  always_ff @(posedge clk_i) begin
    p0_q <= W'($signed({s_q[2], p36[K-1:0]}));
    p1_q <= p36[K+W-1:K] + W'(s_q[2]);
  end
  assign p0_o = p0_q;
  assign p1_o = p1_q;

endmodule

`default_nettype wire
