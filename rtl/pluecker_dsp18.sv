// SPDX-License-Identifier: MIT
// One registered 18 x 18 product, the building block of the DSP
// multipliers (pluecker_mul, pluecker_mul_pair):
//   p_o = a_i * b_i (36 bits), 2 + PIPELINE_REG clock edges after a_i, b_i,
// each operand two's complement (SIGNED_A, SIGNED_B = 1) or unsigned (0).
//
// With PLUECKER_ECP5 defined (scripts/synth.py defines it for Yosys): one
// MULT18X18D with its input registers (REG_INPUTA/B_CLK) and output register
// (REG_OUTPUT_CLK) clocked, and its internal pipeline register
// (REG_PIPELINE_CLK) when PIPELINE_REG = 1; GSR off, no clock enable, no
// reset (data only). Yosys 0.70's synth_ecp5 never packs fabric registers
// into MULT18X18D (it maps `*` to a combinational block), hence the
// instance. nextpnr-ecp5 times the block by its input and output registers
// only; it neither credits nor checks the internal pipeline register.
// Otherwise (simulation, lint, other targets) the same registers around a
// generic `*`: identical results and latency.
`default_nettype none

module pluecker_dsp18 #(
    parameter bit PIPELINE_REG = 0,  // 1: the block's internal pipeline register
    parameter bit SIGNED_A = 1,
    parameter bit SIGNED_B = 1
) (
    input  wire        clk_i,
    input  wire [17:0] a_i,
    input  wire [17:0] b_i,
    output wire [35:0] p_o
);
`ifdef PLUECKER_ECP5
  MULT18X18D #(
      .REG_INPUTA_CLK  ("CLK0"),
      .REG_INPUTB_CLK  ("CLK0"),
      .REG_PIPELINE_CLK(PIPELINE_REG ? "CLK0" : "NONE"),
      .REG_OUTPUT_CLK  ("CLK0"),
      .GSR             ("DISABLED"),
      .RESETMODE       ("SYNC")
  ) u_block (
      .A0(a_i[0]), .A1(a_i[1]), .A2(a_i[2]), .A3(a_i[3]), .A4(a_i[4]), .A5(a_i[5]),
      .A6(a_i[6]), .A7(a_i[7]), .A8(a_i[8]), .A9(a_i[9]), .A10(a_i[10]), .A11(a_i[11]),
      .A12(a_i[12]), .A13(a_i[13]), .A14(a_i[14]), .A15(a_i[15]), .A16(a_i[16]), .A17(a_i[17]),
      .B0(b_i[0]), .B1(b_i[1]), .B2(b_i[2]), .B3(b_i[3]), .B4(b_i[4]), .B5(b_i[5]),
      .B6(b_i[6]), .B7(b_i[7]), .B8(b_i[8]), .B9(b_i[9]), .B10(b_i[10]), .B11(b_i[11]),
      .B12(b_i[12]), .B13(b_i[13]), .B14(b_i[14]), .B15(b_i[15]), .B16(b_i[16]), .B17(b_i[17]),
      .C0(1'b0), .C1(1'b0), .C2(1'b0), .C3(1'b0), .C4(1'b0), .C5(1'b0),
      .C6(1'b0), .C7(1'b0), .C8(1'b0), .C9(1'b0), .C10(1'b0), .C11(1'b0),
      .C12(1'b0), .C13(1'b0), .C14(1'b0), .C15(1'b0), .C16(1'b0), .C17(1'b0),
      .SIGNEDA(SIGNED_A), .SIGNEDB(SIGNED_B), .SOURCEA(1'b0), .SOURCEB(1'b0),
      .CLK0(clk_i), .CLK1(1'b0), .CLK2(1'b0), .CLK3(1'b0),
      .CE0(1'b1), .CE1(1'b0), .CE2(1'b0), .CE3(1'b0),
      .RST0(1'b0), .RST1(1'b0), .RST2(1'b0), .RST3(1'b0),
      .P0(p_o[0]), .P1(p_o[1]), .P2(p_o[2]), .P3(p_o[3]), .P4(p_o[4]), .P5(p_o[5]),
      .P6(p_o[6]), .P7(p_o[7]), .P8(p_o[8]), .P9(p_o[9]), .P10(p_o[10]), .P11(p_o[11]),
      .P12(p_o[12]), .P13(p_o[13]), .P14(p_o[14]), .P15(p_o[15]), .P16(p_o[16]), .P17(p_o[17]),
      .P18(p_o[18]), .P19(p_o[19]), .P20(p_o[20]), .P21(p_o[21]), .P22(p_o[22]), .P23(p_o[23]),
      .P24(p_o[24]), .P25(p_o[25]), .P26(p_o[26]), .P27(p_o[27]), .P28(p_o[28]), .P29(p_o[29]),
      .P30(p_o[30]), .P31(p_o[31]), .P32(p_o[32]), .P33(p_o[33]), .P34(p_o[34]), .P35(p_o[35])
  );
`else
  begin : g_generic
    logic signed [18:0] a_q, b_q;  // extended by the sign bit or a zero
    logic signed [35:0] m_q, p_q;
    always_ff @(posedge clk_i) begin
      a_q <= {SIGNED_A & a_i[17], a_i};
      b_q <= {SIGNED_B & b_i[17], b_i};
      m_q <= a_q * b_q;  // exact: every 18 x 18 product fits 36 bits
      p_q <= m_q;
    end
    assign p_o = PIPELINE_REG ? p_q : m_q;
  end
`endif

endmodule

`default_nettype wire
