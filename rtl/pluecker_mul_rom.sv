// SPDX-License-Identifier: MIT
// The table multipliers of one axis: four registered products of two
// signed operands by two unsigned ones, looked up in three block RAMs,
//   pa0_o = A * d0_i, pa1_o = A * d1_i, pb0_o = B * d0_i, pb1_o = B * d1_i
// 4 clock edges after the operands, as pluecker_mul with PIPELINE = 2
// (d0_i, d1_i WU-bit unsigned). The signed operands A, B (WA bits) come in
// the form the tables take: a_i = {s, m} with s = sign(A) and
// m = A[WA-2:0] ^ s, i.e. A = s ? -(m + 1) : m (the intersector forms it in
// its S0 registers, so that the blocks' address pins are driven straight
// from flops). Products pa0_o..pb1_o are two's complement.
//
// The intersector's MUL_STYLE "rom" (PIPELINE = 2): axis i multiplies its
// two differences A_i, B_i by the two other direction magnitudes, so three
// of these do a unit's twelve products in nine DP16KD, and a chip whose
// MULT18X18D blocks are taken and whose fabric is full of fabric
// multipliers still has its block RAM for more units (the LFE5U-85F has
// 208 DP16KD: 23 units).
//
// Magnitude and sign. With s = sign(a) and m = a ^ s (the WM = WA - 1 low
// bits; m = a when s = 0, m = |a| - 1 when s = 1; a_i carries {s, m}):
//   a * d = s ? -(m*d) - d : m*d
// so the tables hold unsigned products of m alone and the sign is applied
// in fabric: with w = m*d + (s ? d - 1 : 0), a*d = s ? ~w : w (as
// -(m*d) - d = -(w + 1) = ~w). Split d = dh * 2^UL + dl (UL =
// min(WU - 1, 10 - WM) low bits, UH = WU - UL high bits):
// m*d = m*dl + (m*dh) * 2^UL.
//   lo table  t[{x, m}] = m*x, x < 2^UL (WM + UL <= 10 address bits)
//   hi table  t[{x1, x0, m}] = {m*x1, m*x0}, x0, x1 < 2^UH (WM + 2 UH <= 10
//             address bits, two (WM + UH)-bit products in one word)
// Block 0 (lo table) looks up m_a*d0l and m_a*d1l on its two read ports,
// block 1 (lo table) m_b*d0l and m_b*d1l, block 2 (hi table) both high
// parts of a and of b: six look-ups, four products. Then, per product,
//   L = m*dl + (s ? d - 1 : 0)
//   w = L + (m*dh) * 2^UL
//   p = w ^ s                            (every bit)
// Exact for every operand value.
//
// Edges
//   1  the blocks' address registers; beside them s and d in fabric
//   2  the blocks' output registers (REGMODE OUTREG: without them the
//      block's clock-to-output, 4.3 ns at speed 8, is most of a period);
//      beside them the correction s ? d - 1 : 0
//   3  L and m*dh registered in fabric (the route out of the block and
//      one carry chain, no LUT between them)
//   4  p_q = w ^ s (a carry chain above bit UL, then one LUT level)
//
// With PLUECKER_ECP5 defined (scripts/synth.py defines it for Yosys): three
// DP16KD instances, both ports 1K x 18 read-only, INITVAL_00..3F built from
// the tables by init_slice (word w at bits 20 (w mod 16) of INITVAL w / 16,
// as Yosys's own ECP5 block-RAM mapping lays them out; Yosys 0.70 infers
// the tables but never the output registers, hence the instances).
// Otherwise (simulation, lint, other targets) generic tables with the same
// registers: identical results and latency.
`default_nettype none

module pluecker_mul_rom #(
    parameter int WA = 7,  // operands a_i, b_i: {sign, magnitude bits} (above)
    parameter int WU = 6,  // unsigned operands d0_i, d1_i
    // Product width (signed, as pluecker_mul with WB = WU + 1; not to be
    // overridden).
    localparam int W = WA + WU + 1
) (
    input  wire                 clk_i,
    input  wire signed [WA-1:0] a_i,
    input  wire signed [WA-1:0] b_i,
    input  wire        [WU-1:0] d0_i,
    input  wire        [WU-1:0] d1_i,
    output wire signed [W-1:0]  pa0_o,
    output wire signed [W-1:0]  pa1_o,
    output wire signed [W-1:0]  pb0_o,
    output wire signed [W-1:0]  pb1_o
);
  localparam int WM = WA - 1;  // magnitude bits m = a ^ sign(a)
  localparam int UL0 = 10 - WM;
  localparam int UL = (WU - 1 < UL0) ? WU - 1 : UL0;  // low part of d
  localparam int UH = WU - UL;  // high part of d
  localparam int DL = WM + UL;  // lo entry: m*x < 2^(WM+UL)
  localparam int DH = WM + UH;  // one of the hi entry's two products
  if (WA < 2 || WU < 2 || UL < 1 || WM + 2 * UH > 10) begin : g_bad_width
    // (3 (WA - 1) + 2 WU <= 30 is WM + 2 UH <= 10 for WU >= 2.)
    $error("pluecker_mul_rom: needs WA >= 2, WU >= 2 and 3 (WA - 1) + 2 WU <= 30 (the high parts of two products in one 1K x 18 look-up)");
  end

  // Table entries at address w: kind 0 (lo) m*x with m = w[WM-1:0],
  // x = w >> WM; kind 1 (hi) {m*x1, m*x0} with x0 = w[WM+:UH], x1 the UH
  // bits above. (32-bit arithmetic: entries below 2^18.)
  function automatic logic [17:0] entry(input int kind, input int w);
    int mv, x0, x1;
    mv = w & ((1 << WM) - 1);
    if (kind == 0) begin
      x0 = (w >> WM) & ((1 << UL) - 1);
      entry = 18'(mv * x0);
    end else begin
      x0 = (w >> WM) & ((1 << UH) - 1);
      x1 = (w >> (WM + UH)) & ((1 << UH) - 1);
      entry = 18'((mv * x1) << DH) | 18'(mv * x0);
    end
  endfunction

`ifdef PLUECKER_ECP5
  // INITVAL number s of a table of this kind: words 16 s .. 16 s + 15, 20
  // bits each (18 used).
  function automatic logic [319:0] init_slice(input int kind, input int s);
    init_slice = '0;
    for (int i = 0; i < 16; i++) init_slice[20*i+:18] = entry(kind, 16 * s + i);
  endfunction
`endif

  // Sign and magnitude bits, straight from the ports (no logic before the
  // blocks' address registers).
  wire sa = a_i[WA-1];
  wire sb = b_i[WA-1];
  wire [WM-1:0] ma = a_i[WM-1:0];
  wire [WM-1:0] mb = b_i[WM-1:0];
  wire [UL-1:0] d0l = d0_i[UL-1:0];
  wire [UL-1:0] d1l = d1_i[UL-1:0];
  wire [UH-1:0] d0h = d0_i[WU-1:UL];
  wire [UH-1:0] d1h = d1_i[WU-1:UL];

  // Block g's port A and port B addresses, and its words after the output
  // registers.
  wire [2:0][9:0] addr_a = {10'({d1h, d0h, ma}), 10'({d0l, mb}), 10'({d0l, ma})};
  wire [2:0][9:0] addr_b = {10'({d1h, d0h, mb}), 10'({d1l, mb}), 10'({d1l, ma})};
  wire [2:0][17:0] word_a, word_b;

  for (genvar g = 0; g < 3; g++) begin : g_block
    localparam int KIND = (g == 2) ? 1 : 0;
`ifdef PLUECKER_ECP5
    wire [9:0] ada = addr_a[g];
    wire [9:0] adb = addr_b[g];
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
        .INITVAL_00(init_slice(KIND, 0)),
        .INITVAL_01(init_slice(KIND, 1)),
        .INITVAL_02(init_slice(KIND, 2)),
        .INITVAL_03(init_slice(KIND, 3)),
        .INITVAL_04(init_slice(KIND, 4)),
        .INITVAL_05(init_slice(KIND, 5)),
        .INITVAL_06(init_slice(KIND, 6)),
        .INITVAL_07(init_slice(KIND, 7)),
        .INITVAL_08(init_slice(KIND, 8)),
        .INITVAL_09(init_slice(KIND, 9)),
        .INITVAL_0A(init_slice(KIND, 10)),
        .INITVAL_0B(init_slice(KIND, 11)),
        .INITVAL_0C(init_slice(KIND, 12)),
        .INITVAL_0D(init_slice(KIND, 13)),
        .INITVAL_0E(init_slice(KIND, 14)),
        .INITVAL_0F(init_slice(KIND, 15)),
        .INITVAL_10(init_slice(KIND, 16)),
        .INITVAL_11(init_slice(KIND, 17)),
        .INITVAL_12(init_slice(KIND, 18)),
        .INITVAL_13(init_slice(KIND, 19)),
        .INITVAL_14(init_slice(KIND, 20)),
        .INITVAL_15(init_slice(KIND, 21)),
        .INITVAL_16(init_slice(KIND, 22)),
        .INITVAL_17(init_slice(KIND, 23)),
        .INITVAL_18(init_slice(KIND, 24)),
        .INITVAL_19(init_slice(KIND, 25)),
        .INITVAL_1A(init_slice(KIND, 26)),
        .INITVAL_1B(init_slice(KIND, 27)),
        .INITVAL_1C(init_slice(KIND, 28)),
        .INITVAL_1D(init_slice(KIND, 29)),
        .INITVAL_1E(init_slice(KIND, 30)),
        .INITVAL_1F(init_slice(KIND, 31)),
        .INITVAL_20(init_slice(KIND, 32)),
        .INITVAL_21(init_slice(KIND, 33)),
        .INITVAL_22(init_slice(KIND, 34)),
        .INITVAL_23(init_slice(KIND, 35)),
        .INITVAL_24(init_slice(KIND, 36)),
        .INITVAL_25(init_slice(KIND, 37)),
        .INITVAL_26(init_slice(KIND, 38)),
        .INITVAL_27(init_slice(KIND, 39)),
        .INITVAL_28(init_slice(KIND, 40)),
        .INITVAL_29(init_slice(KIND, 41)),
        .INITVAL_2A(init_slice(KIND, 42)),
        .INITVAL_2B(init_slice(KIND, 43)),
        .INITVAL_2C(init_slice(KIND, 44)),
        .INITVAL_2D(init_slice(KIND, 45)),
        .INITVAL_2E(init_slice(KIND, 46)),
        .INITVAL_2F(init_slice(KIND, 47)),
        .INITVAL_30(init_slice(KIND, 48)),
        .INITVAL_31(init_slice(KIND, 49)),
        .INITVAL_32(init_slice(KIND, 50)),
        .INITVAL_33(init_slice(KIND, 51)),
        .INITVAL_34(init_slice(KIND, 52)),
        .INITVAL_35(init_slice(KIND, 53)),
        .INITVAL_36(init_slice(KIND, 54)),
        .INITVAL_37(init_slice(KIND, 55)),
        .INITVAL_38(init_slice(KIND, 56)),
        .INITVAL_39(init_slice(KIND, 57)),
        .INITVAL_3A(init_slice(KIND, 58)),
        .INITVAL_3B(init_slice(KIND, 59)),
        .INITVAL_3C(init_slice(KIND, 60)),
        .INITVAL_3D(init_slice(KIND, 61)),
        .INITVAL_3E(init_slice(KIND, 62)),
        .INITVAL_3F(init_slice(KIND, 63)),
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
    assign word_a[g] = doa;
    assign word_b[g] = dob;
`else
    logic [17:0] table_r[1024];
    initial begin
      for (int w = 0; w < 1024; w++) table_r[w] = entry(KIND, w);
    end
    logic [17:0] a_m_q, b_m_q, a_r_q, b_r_q;
    always_ff @(posedge clk_i) begin
      a_m_q <= table_r[addr_a[g]];  // edge 1: address register and read
      b_m_q <= table_r[addr_b[g]];
      a_r_q <= a_m_q;  // edge 2: output register
      b_r_q <= b_m_q;
    end
    assign word_a[g] = a_r_q;
    assign word_b[g] = b_r_q;
`endif
  end

  // The four products' parts: [0] a*d0, [1] a*d1, [2] b*d0, [3] b*d1.
  wire [3:0][DL-1:0] lo = {word_b[1][DL-1:0], word_a[1][DL-1:0], word_b[0][DL-1:0], word_a[0][DL-1:0]};
  wire [3:0][DH-1:0] hi = {
    word_b[2][2*DH-1:DH], word_b[2][DH-1:0], word_a[2][2*DH-1:DH], word_a[2][DH-1:0]
  };

  // Edges 1 to 4 in fabric.
  localparam int WC = WU + 1;  // d - 1: signed
  localparam int WL = (DL > WU ? DL : WU) + 2;  // L: -1 <= L <= m*dl + d - 1
  localparam int WPH = W - UL;  // p's bits above the low UL
  logic [1:0] s1_q, s2_q, s3_q;  // signs of a and b
  logic [1:0][WU-1:0] d1_q;  // d0, d1
  logic [3:0][WC-1:0] c2_q;  // s ? d - 1 : 0
  logic [3:0][WL-1:0] l3_q;  // L (signed)
  logic [3:0][DH-1:0] h3_q;  // m*dh
  logic [3:0][W-1:0] p_q;
  logic [3:0][WPH-1:0] wh_d;  // (w >> UL) = (L >> UL) + m*dh

  always_comb begin
    for (int k = 0; k < 4; k++) begin
      wh_d[k] = WPH'($signed(l3_q[k][WL-1:UL])) + WPH'(h3_q[k]);
    end
  end

  always_ff @(posedge clk_i) begin
    s1_q <= {sb, sa};
    d1_q <= {d1_i, d0_i};
    s2_q <= s1_q;
    s3_q <= s2_q;
    for (int k = 0; k < 4; k++) begin
      c2_q[k] <= s1_q[k/2] ? WC'(d1_q[k%2]) - WC'(1) : '0;
      l3_q[k] <= WL'(lo[k]) + WL'($signed(c2_q[k]));
      h3_q[k] <= hi[k];
      p_q[k]  <= {wh_d[k], l3_q[k][UL-1:0]} ^ {W{s3_q[k/2]}};
    end
  end
  assign {pb1_o, pb0_o, pa1_o, pa0_o} = p_q;

endmodule

`default_nettype wire
