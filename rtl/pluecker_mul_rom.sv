// SPDX-License-Identifier: MIT
// Registered signed multiply by table look-up in one block RAM:
//   p_o = a_i * b_i (a_i WA-bit two's complement, b_i WU-bit unsigned),
//   4 clock edges after the operands, as pluecker_mul with PIPELINE = 2.
//
// The intersector's MUL_STYLE "rom" (6/6 bits, PIPELINE = 2): twelve of
// these a unit, one DP16KD each, so a chip whose MULT18X18D blocks are
// taken and whose fabric is full of fabric multipliers still has its
// block RAM for more units (the LFE5U-85F has 208 DP16KD).
//
// Split b = bh * 2^UL + bl (UL = ceil(WU/2) low bits, UH = WU - UL high
// bits), so a*b = a*bl + (a*bh) * 2^UL. One table t[{x, a}] = a * x
// (x < 2^UL, entries WA + UL bits signed, 2^(WA+UL) words) serves both
// parts: the block's two read ports look up a*bl and a*bh in the same
// cycle. Exact for every operand value.
//
// Edges
//   1  the block's address registers (port A {bl, a}, port B {bh, a})
//   2  the block's output registers (REGMODE OUTREG: without them the
//      block's clock-to-output, 4.3 ns at speed 8, is most of a period)
//   3  both parts registered in fabric (the route out of the block gets a
//      whole period)
//   4  p_q = a*bl + (a*bh << UL)
//
// With PLUECKER_ECP5 defined (scripts/synth.py defines it for Yosys): one
// DP16KD instance, both ports 1K x 18 read-only, its INITVAL_00..3F built
// from the table by init_slice (word w at bits 20 (w mod 16) of INITVAL
// w / 16, as Yosys's own ECP5 block-RAM mapping lays them out; Yosys 0.70
// infers the table but never the output registers, hence the instance).
// Otherwise (simulation, lint, other targets) a generic table with the
// same registers: identical results and latency.
`default_nettype none

module pluecker_mul_rom #(
    parameter int WA = 7,  // signed operand a_i
    parameter int WU = 6,  // unsigned operand b_i
    // Product width (signed, as pluecker_mul with WB = WU + 1; not to be
    // overridden).
    localparam int W = WA + WU + 1
) (
    input  wire                 clk_i,
    input  wire signed [WA-1:0] a_i,
    input  wire        [WU-1:0] b_i,
    output wire signed [W-1:0]  p_o
);
  localparam int UL = (WU + 1) / 2;  // low part of b
  localparam int AW = WA + UL;  // table address bits
  localparam int DW = WA + UL;  // table entry bits: |a*x| <= 2^(WA-1) (2^UL - 1)
  if (WA < 2 || WU < 2 || AW > 10) begin : g_bad_width
    $error("pluecker_mul_rom: needs WA >= 2, WU >= 2 and WA + ceil(WU/2) <= 10 (one 1K x 18 port)");
  end

  // Table entry at address w: a * x with a = w[WA-1:0], x = w[AW-1:WA].
  // (32-bit integer arithmetic: |a * x| < 2^(DW-1) <= 2^9.)
  function automatic logic [DW-1:0] entry(input int w);
    logic signed [WA-1:0] a;
    int av, xv;
    a = WA'(w);
    av = int'(a);  // sign-extended
    xv = (w >> WA) & ((1 << UL) - 1);
    entry = DW'(av * xv);
  endfunction

  wire [AW-1:0] addr_lo = {b_i[UL-1:0], a_i};
  wire [AW-1:0] addr_hi = {UL'(b_i[WU-1:UL]), a_i};
  wire [DW-1:0] lo, hi;  // a*bl, a*bh after the block's output registers

`ifdef PLUECKER_ECP5
  // INITVAL number s: words 16 s .. 16 s + 15, 20 bits each (18 used).
  function automatic logic [319:0] init_slice(input int s);
    init_slice = '0;
    for (int i = 0; i < 16; i++) begin
      if (16 * s + i < (1 << AW)) init_slice[20*i+:18] = 18'(entry(16 * s + i));
    end
  endfunction

  wire [9:0] ada = 10'(addr_lo);
  wire [9:0] adb = 10'(addr_hi);
  wire [17:0] doa, dob;
  DP16KD #(
      .DATA_WIDTH_A(18),
      .DATA_WIDTH_B(18),
      .REGMODE_A("OUTREG"),
      .REGMODE_B("OUTREG"),
      .RESETMODE("SYNC"),
      .ASYNC_RESET_RELEASE("SYNC"),
      .CSDECODE_A("0b000"),
      .CSDECODE_B("0b000"),
      .WRITEMODE_A("NORMAL"),
      .WRITEMODE_B("NORMAL"),
      .GSR("DISABLED"),
      .INITVAL_00(init_slice(0)),
      .INITVAL_01(init_slice(1)),
      .INITVAL_02(init_slice(2)),
      .INITVAL_03(init_slice(3)),
      .INITVAL_04(init_slice(4)),
      .INITVAL_05(init_slice(5)),
      .INITVAL_06(init_slice(6)),
      .INITVAL_07(init_slice(7)),
      .INITVAL_08(init_slice(8)),
      .INITVAL_09(init_slice(9)),
      .INITVAL_0A(init_slice(10)),
      .INITVAL_0B(init_slice(11)),
      .INITVAL_0C(init_slice(12)),
      .INITVAL_0D(init_slice(13)),
      .INITVAL_0E(init_slice(14)),
      .INITVAL_0F(init_slice(15)),
      .INITVAL_10(init_slice(16)),
      .INITVAL_11(init_slice(17)),
      .INITVAL_12(init_slice(18)),
      .INITVAL_13(init_slice(19)),
      .INITVAL_14(init_slice(20)),
      .INITVAL_15(init_slice(21)),
      .INITVAL_16(init_slice(22)),
      .INITVAL_17(init_slice(23)),
      .INITVAL_18(init_slice(24)),
      .INITVAL_19(init_slice(25)),
      .INITVAL_1A(init_slice(26)),
      .INITVAL_1B(init_slice(27)),
      .INITVAL_1C(init_slice(28)),
      .INITVAL_1D(init_slice(29)),
      .INITVAL_1E(init_slice(30)),
      .INITVAL_1F(init_slice(31)),
      .INITVAL_20(init_slice(32)),
      .INITVAL_21(init_slice(33)),
      .INITVAL_22(init_slice(34)),
      .INITVAL_23(init_slice(35)),
      .INITVAL_24(init_slice(36)),
      .INITVAL_25(init_slice(37)),
      .INITVAL_26(init_slice(38)),
      .INITVAL_27(init_slice(39)),
      .INITVAL_28(init_slice(40)),
      .INITVAL_29(init_slice(41)),
      .INITVAL_2A(init_slice(42)),
      .INITVAL_2B(init_slice(43)),
      .INITVAL_2C(init_slice(44)),
      .INITVAL_2D(init_slice(45)),
      .INITVAL_2E(init_slice(46)),
      .INITVAL_2F(init_slice(47)),
      .INITVAL_30(init_slice(48)),
      .INITVAL_31(init_slice(49)),
      .INITVAL_32(init_slice(50)),
      .INITVAL_33(init_slice(51)),
      .INITVAL_34(init_slice(52)),
      .INITVAL_35(init_slice(53)),
      .INITVAL_36(init_slice(54)),
      .INITVAL_37(init_slice(55)),
      .INITVAL_38(init_slice(56)),
      .INITVAL_39(init_slice(57)),
      .INITVAL_3A(init_slice(58)),
      .INITVAL_3B(init_slice(59)),
      .INITVAL_3C(init_slice(60)),
      .INITVAL_3D(init_slice(61)),
      .INITVAL_3E(init_slice(62)),
      .INITVAL_3F(init_slice(63)),
      .INIT_DATA("STATIC")
  ) u_block (
      .CLKA(clk_i), .CEA(1'b1), .OCEA(1'b1), .WEA(1'b0), .RSTA(1'b0),
      .CSA2(1'b0), .CSA1(1'b0), .CSA0(1'b0),
      .ADA13(ada[9]), .ADA12(ada[8]), .ADA11(ada[7]), .ADA10(ada[6]), .ADA9(ada[5]),
      .ADA8(ada[4]), .ADA7(ada[3]), .ADA6(ada[2]), .ADA5(ada[1]), .ADA4(ada[0]),
      .ADA3(1'b0), .ADA2(1'b0), .ADA1(1'b0), .ADA0(1'b0),
      .DIA17(1'b0), .DIA16(1'b0), .DIA15(1'b0), .DIA14(1'b0), .DIA13(1'b0), .DIA12(1'b0),
      .DIA11(1'b0), .DIA10(1'b0), .DIA9(1'b0), .DIA8(1'b0), .DIA7(1'b0), .DIA6(1'b0),
      .DIA5(1'b0), .DIA4(1'b0), .DIA3(1'b0), .DIA2(1'b0), .DIA1(1'b0), .DIA0(1'b0),
      .DOA17(doa[17]), .DOA16(doa[16]), .DOA15(doa[15]), .DOA14(doa[14]), .DOA13(doa[13]),
      .DOA12(doa[12]), .DOA11(doa[11]), .DOA10(doa[10]), .DOA9(doa[9]), .DOA8(doa[8]),
      .DOA7(doa[7]), .DOA6(doa[6]), .DOA5(doa[5]), .DOA4(doa[4]), .DOA3(doa[3]),
      .DOA2(doa[2]), .DOA1(doa[1]), .DOA0(doa[0]),
      .CLKB(clk_i), .CEB(1'b1), .OCEB(1'b1), .WEB(1'b0), .RSTB(1'b0),
      .CSB2(1'b0), .CSB1(1'b0), .CSB0(1'b0),
      .ADB13(adb[9]), .ADB12(adb[8]), .ADB11(adb[7]), .ADB10(adb[6]), .ADB9(adb[5]),
      .ADB8(adb[4]), .ADB7(adb[3]), .ADB6(adb[2]), .ADB5(adb[1]), .ADB4(adb[0]),
      .ADB3(1'b0), .ADB2(1'b0), .ADB1(1'b0), .ADB0(1'b0),
      .DIB17(1'b0), .DIB16(1'b0), .DIB15(1'b0), .DIB14(1'b0), .DIB13(1'b0), .DIB12(1'b0),
      .DIB11(1'b0), .DIB10(1'b0), .DIB9(1'b0), .DIB8(1'b0), .DIB7(1'b0), .DIB6(1'b0),
      .DIB5(1'b0), .DIB4(1'b0), .DIB3(1'b0), .DIB2(1'b0), .DIB1(1'b0), .DIB0(1'b0),
      .DOB17(dob[17]), .DOB16(dob[16]), .DOB15(dob[15]), .DOB14(dob[14]), .DOB13(dob[13]),
      .DOB12(dob[12]), .DOB11(dob[11]), .DOB10(dob[10]), .DOB9(dob[9]), .DOB8(dob[8]),
      .DOB7(dob[7]), .DOB6(dob[6]), .DOB5(dob[5]), .DOB4(dob[4]), .DOB3(dob[3]),
      .DOB2(dob[2]), .DOB1(dob[1]), .DOB0(dob[0])
  );
  assign lo = doa[DW-1:0];
  assign hi = dob[DW-1:0];
`else
  begin : g_generic
    logic [DW-1:0] table_r[1 << AW];
    initial begin
      for (int w = 0; w < (1 << AW); w++) table_r[w] = entry(w);
    end
    logic [DW-1:0] lo_m_q, hi_m_q, lo_r_q, hi_r_q;
    always_ff @(posedge clk_i) begin
      lo_m_q <= table_r[addr_lo];  // edge 1: address register and read
      hi_m_q <= table_r[addr_hi];
      lo_r_q <= lo_m_q;  // edge 2: output register
      hi_r_q <= hi_m_q;
    end
    assign lo = lo_r_q;
    assign hi = hi_r_q;
  end
`endif

  // Edges 3 and 4 in fabric.
  logic [DW-1:0] lo_q, hi_q;
  logic signed [W-1:0] p_q;
  always_ff @(posedge clk_i) begin
    lo_q <= lo;
    hi_q <= hi;
    p_q  <= W'($signed(lo_q)) + (W'($signed(hi_q)) << UL);
  end
  assign p_o = p_q;

endmodule

`default_nettype wire
