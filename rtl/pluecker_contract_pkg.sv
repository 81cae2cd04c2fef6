// SPDX-License-Identifier: MIT
// Generated from model/core/src/contract.cpp by `pluecker contract --write rtl`: do
// not edit (the test Contract.GeneratedFilesAreCurrent compares this file).
//
// The port contract of pluecker_intersector (model/core/include/pluecker/contract.hpp):
// the parameter limits the module checks and the configuration classes,
// each with the constants the module must derive from its parameters. The
// module looks its configuration up (contract_class) and fails elaboration
// when what it derives differs from the class's row.
package pluecker_contract_pkg;
  localparam int MIN_BITS = 6;  // COORD_BITS, DIR_BITS
  localparam int MAX_BITS = 24;
  localparam int MIN_TAG_BITS = 1;
  localparam int MAX_PIPELINE = 2;
  // A multiplier operand wider than this is split over two DSP operands.
  localparam int DSP_OPERAND_BITS = 18;
  // MUL_STYLE "auto": fabric multipliers when both widths are at most this.
  localparam int MUL_LUT_MAX_BITS = 9;

  // The class of a configuration (c = COORD_BITS, d = DIR_BITS, s = MUL_STYLE
  // as a 32-bit pattern, p = PIPELINE), -1 when the module refuses it.
  function automatic int contract_class(input int c, input int d, input logic [31:0] s, input int p);
    contract_class = -1;
    if (c >= 6 && c <= 9 && d >= 6 && d <= 9 && s == 32'("auto") && p == 0) contract_class = 0;
    if (c >= 6 && c <= 9 && d >= 10 && d <= 17 && s == 32'("auto") && p == 0) contract_class = 1;
    if (c >= 6 && c <= 9 && d >= 18 && d <= 24 && s == 32'("auto") && p == 0) contract_class = 2;
    if (c >= 10 && c <= 17 && d >= 6 && d <= 9 && s == 32'("auto") && p == 0) contract_class = 3;
    if (c >= 10 && c <= 17 && d >= 10 && d <= 17 && s == 32'("auto") && p == 0) contract_class = 4;
    if (c >= 10 && c <= 17 && d >= 18 && d <= 24 && s == 32'("auto") && p == 0) contract_class = 5;
    if (c >= 18 && c <= 24 && d >= 6 && d <= 9 && s == 32'("auto") && p == 0) contract_class = 6;
    if (c >= 18 && c <= 24 && d >= 10 && d <= 17 && s == 32'("auto") && p == 0) contract_class = 7;
    if (c >= 18 && c <= 24 && d >= 18 && d <= 24 && s == 32'("auto") && p == 0) contract_class = 8;
    if (c >= 6 && c <= 9 && d >= 6 && d <= 9 && s == 32'("auto") && p == 1) contract_class = 9;
    if (c >= 6 && c <= 9 && d >= 10 && d <= 17 && s == 32'("auto") && p == 1) contract_class = 10;
    if (c >= 6 && c <= 9 && d >= 18 && d <= 24 && s == 32'("auto") && p == 1) contract_class = 11;
    if (c >= 10 && c <= 17 && d >= 6 && d <= 9 && s == 32'("auto") && p == 1) contract_class = 12;
    if (c >= 10 && c <= 17 && d >= 10 && d <= 17 && s == 32'("auto") && p == 1) contract_class = 13;
    if (c >= 10 && c <= 17 && d >= 18 && d <= 24 && s == 32'("auto") && p == 1) contract_class = 14;
    if (c >= 18 && c <= 24 && d >= 6 && d <= 9 && s == 32'("auto") && p == 1) contract_class = 15;
    if (c >= 18 && c <= 24 && d >= 10 && d <= 17 && s == 32'("auto") && p == 1) contract_class = 16;
    if (c >= 18 && c <= 24 && d >= 18 && d <= 24 && s == 32'("auto") && p == 1) contract_class = 17;
    if (c >= 6 && c <= 9 && d >= 6 && d <= 9 && s == 32'("auto") && p == 2) contract_class = 18;
    if (c >= 6 && c <= 9 && d >= 10 && d <= 17 && s == 32'("auto") && p == 2) contract_class = 19;
    if (c >= 6 && c <= 9 && d >= 18 && d <= 24 && s == 32'("auto") && p == 2) contract_class = 20;
    if (c >= 10 && c <= 17 && d >= 6 && d <= 9 && s == 32'("auto") && p == 2) contract_class = 21;
    if (c >= 10 && c <= 17 && d >= 10 && d <= 17 && s == 32'("auto") && p == 2) contract_class = 22;
    if (c >= 10 && c <= 17 && d >= 18 && d <= 24 && s == 32'("auto") && p == 2) contract_class = 23;
    if (c >= 18 && c <= 24 && d >= 6 && d <= 9 && s == 32'("auto") && p == 2) contract_class = 24;
    if (c >= 18 && c <= 24 && d >= 10 && d <= 17 && s == 32'("auto") && p == 2) contract_class = 25;
    if (c >= 18 && c <= 24 && d >= 18 && d <= 24 && s == 32'("auto") && p == 2) contract_class = 26;
    if (c >= 6 && c <= 9 && d >= 6 && d <= 9 && s == 32'("dsp") && p == 0) contract_class = 27;
    if (c >= 6 && c <= 9 && d >= 10 && d <= 17 && s == 32'("dsp") && p == 0) contract_class = 28;
    if (c >= 6 && c <= 9 && d >= 18 && d <= 24 && s == 32'("dsp") && p == 0) contract_class = 29;
    if (c >= 10 && c <= 17 && d >= 6 && d <= 9 && s == 32'("dsp") && p == 0) contract_class = 30;
    if (c >= 10 && c <= 17 && d >= 10 && d <= 17 && s == 32'("dsp") && p == 0) contract_class = 31;
    if (c >= 10 && c <= 17 && d >= 18 && d <= 24 && s == 32'("dsp") && p == 0) contract_class = 32;
    if (c >= 18 && c <= 24 && d >= 6 && d <= 9 && s == 32'("dsp") && p == 0) contract_class = 33;
    if (c >= 18 && c <= 24 && d >= 10 && d <= 17 && s == 32'("dsp") && p == 0) contract_class = 34;
    if (c >= 18 && c <= 24 && d >= 18 && d <= 24 && s == 32'("dsp") && p == 0) contract_class = 35;
    if (c >= 6 && c <= 9 && d >= 6 && d <= 9 && s == 32'("dsp") && p == 1) contract_class = 36;
    if (c >= 6 && c <= 9 && d >= 10 && d <= 17 && s == 32'("dsp") && p == 1) contract_class = 37;
    if (c >= 6 && c <= 9 && d >= 18 && d <= 24 && s == 32'("dsp") && p == 1) contract_class = 38;
    if (c >= 10 && c <= 17 && d >= 6 && d <= 9 && s == 32'("dsp") && p == 1) contract_class = 39;
    if (c >= 10 && c <= 17 && d >= 10 && d <= 17 && s == 32'("dsp") && p == 1) contract_class = 40;
    if (c >= 10 && c <= 17 && d >= 18 && d <= 24 && s == 32'("dsp") && p == 1) contract_class = 41;
    if (c >= 18 && c <= 24 && d >= 6 && d <= 9 && s == 32'("dsp") && p == 1) contract_class = 42;
    if (c >= 18 && c <= 24 && d >= 10 && d <= 17 && s == 32'("dsp") && p == 1) contract_class = 43;
    if (c >= 18 && c <= 24 && d >= 18 && d <= 24 && s == 32'("dsp") && p == 1) contract_class = 44;
    if (c >= 6 && c <= 9 && d >= 6 && d <= 9 && s == 32'("dsp") && p == 2) contract_class = 45;
    if (c >= 6 && c <= 9 && d >= 10 && d <= 17 && s == 32'("dsp") && p == 2) contract_class = 46;
    if (c >= 6 && c <= 9 && d >= 18 && d <= 24 && s == 32'("dsp") && p == 2) contract_class = 47;
    if (c >= 10 && c <= 17 && d >= 6 && d <= 9 && s == 32'("dsp") && p == 2) contract_class = 48;
    if (c >= 10 && c <= 17 && d >= 10 && d <= 17 && s == 32'("dsp") && p == 2) contract_class = 49;
    if (c >= 10 && c <= 17 && d >= 18 && d <= 24 && s == 32'("dsp") && p == 2) contract_class = 50;
    if (c >= 18 && c <= 24 && d >= 6 && d <= 9 && s == 32'("dsp") && p == 2) contract_class = 51;
    if (c >= 18 && c <= 24 && d >= 10 && d <= 17 && s == 32'("dsp") && p == 2) contract_class = 52;
    if (c >= 18 && c <= 24 && d >= 18 && d <= 24 && s == 32'("dsp") && p == 2) contract_class = 53;
    if (c >= 6 && c <= 9 && d >= 6 && d <= 9 && s == 32'("lut") && p == 0) contract_class = 54;
    if (c >= 6 && c <= 9 && d >= 10 && d <= 17 && s == 32'("lut") && p == 0) contract_class = 55;
    if (c >= 10 && c <= 17 && d >= 6 && d <= 9 && s == 32'("lut") && p == 0) contract_class = 56;
    if (c >= 10 && c <= 17 && d >= 10 && d <= 17 && s == 32'("lut") && p == 0) contract_class = 57;
    if (c >= 6 && c <= 9 && d >= 6 && d <= 9 && s == 32'("lut") && p == 1) contract_class = 58;
    if (c >= 6 && c <= 9 && d >= 10 && d <= 17 && s == 32'("lut") && p == 1) contract_class = 59;
    if (c >= 10 && c <= 17 && d >= 6 && d <= 9 && s == 32'("lut") && p == 1) contract_class = 60;
    if (c >= 10 && c <= 17 && d >= 10 && d <= 17 && s == 32'("lut") && p == 1) contract_class = 61;
    if (c >= 6 && c <= 9 && d >= 6 && d <= 9 && s == 32'("lut") && p == 2) contract_class = 62;
    if (c >= 6 && c <= 9 && d >= 10 && d <= 17 && s == 32'("lut") && p == 2) contract_class = 63;
    if (c >= 10 && c <= 17 && d >= 6 && d <= 9 && s == 32'("lut") && p == 2) contract_class = 64;
    if (c >= 10 && c <= 17 && d >= 10 && d <= 17 && s == 32'("lut") && p == 2) contract_class = 65;
  endfunction

  // 1: fabric multipliers (pluecker_mul_lut), 0: pluecker_mul of class k.
  function automatic bit contract_mul_lut(input int k);
    case (k)
      0: contract_mul_lut = 1;
      1: contract_mul_lut = 0;
      2: contract_mul_lut = 0;
      3: contract_mul_lut = 0;
      4: contract_mul_lut = 0;
      5: contract_mul_lut = 0;
      6: contract_mul_lut = 0;
      7: contract_mul_lut = 0;
      8: contract_mul_lut = 0;
      9: contract_mul_lut = 1;
      10: contract_mul_lut = 0;
      11: contract_mul_lut = 0;
      12: contract_mul_lut = 0;
      13: contract_mul_lut = 0;
      14: contract_mul_lut = 0;
      15: contract_mul_lut = 0;
      16: contract_mul_lut = 0;
      17: contract_mul_lut = 0;
      18: contract_mul_lut = 1;
      19: contract_mul_lut = 0;
      20: contract_mul_lut = 0;
      21: contract_mul_lut = 0;
      22: contract_mul_lut = 0;
      23: contract_mul_lut = 0;
      24: contract_mul_lut = 0;
      25: contract_mul_lut = 0;
      26: contract_mul_lut = 0;
      27: contract_mul_lut = 0;
      28: contract_mul_lut = 0;
      29: contract_mul_lut = 0;
      30: contract_mul_lut = 0;
      31: contract_mul_lut = 0;
      32: contract_mul_lut = 0;
      33: contract_mul_lut = 0;
      34: contract_mul_lut = 0;
      35: contract_mul_lut = 0;
      36: contract_mul_lut = 0;
      37: contract_mul_lut = 0;
      38: contract_mul_lut = 0;
      39: contract_mul_lut = 0;
      40: contract_mul_lut = 0;
      41: contract_mul_lut = 0;
      42: contract_mul_lut = 0;
      43: contract_mul_lut = 0;
      44: contract_mul_lut = 0;
      45: contract_mul_lut = 0;
      46: contract_mul_lut = 0;
      47: contract_mul_lut = 0;
      48: contract_mul_lut = 0;
      49: contract_mul_lut = 0;
      50: contract_mul_lut = 0;
      51: contract_mul_lut = 0;
      52: contract_mul_lut = 0;
      53: contract_mul_lut = 0;
      54: contract_mul_lut = 1;
      55: contract_mul_lut = 1;
      56: contract_mul_lut = 1;
      57: contract_mul_lut = 1;
      58: contract_mul_lut = 1;
      59: contract_mul_lut = 1;
      60: contract_mul_lut = 1;
      61: contract_mul_lut = 1;
      62: contract_mul_lut = 1;
      63: contract_mul_lut = 1;
      64: contract_mul_lut = 1;
      65: contract_mul_lut = 1;
      default: contract_mul_lut = 0;
    endcase
  endfunction

  // MUL_ADD of class k.
  function automatic int contract_mul_add(input int k);
    case (k)
      0: contract_mul_add = 0;
      1: contract_mul_add = 0;
      2: contract_mul_add = 1;
      3: contract_mul_add = 0;
      4: contract_mul_add = 0;
      5: contract_mul_add = 1;
      6: contract_mul_add = 1;
      7: contract_mul_add = 1;
      8: contract_mul_add = 2;
      9: contract_mul_add = 0;
      10: contract_mul_add = 0;
      11: contract_mul_add = 1;
      12: contract_mul_add = 0;
      13: contract_mul_add = 0;
      14: contract_mul_add = 1;
      15: contract_mul_add = 1;
      16: contract_mul_add = 1;
      17: contract_mul_add = 2;
      18: contract_mul_add = 0;
      19: contract_mul_add = 0;
      20: contract_mul_add = 1;
      21: contract_mul_add = 0;
      22: contract_mul_add = 0;
      23: contract_mul_add = 1;
      24: contract_mul_add = 1;
      25: contract_mul_add = 1;
      26: contract_mul_add = 2;
      27: contract_mul_add = 0;
      28: contract_mul_add = 0;
      29: contract_mul_add = 1;
      30: contract_mul_add = 0;
      31: contract_mul_add = 0;
      32: contract_mul_add = 1;
      33: contract_mul_add = 1;
      34: contract_mul_add = 1;
      35: contract_mul_add = 2;
      36: contract_mul_add = 0;
      37: contract_mul_add = 0;
      38: contract_mul_add = 1;
      39: contract_mul_add = 0;
      40: contract_mul_add = 0;
      41: contract_mul_add = 1;
      42: contract_mul_add = 1;
      43: contract_mul_add = 1;
      44: contract_mul_add = 2;
      45: contract_mul_add = 0;
      46: contract_mul_add = 0;
      47: contract_mul_add = 1;
      48: contract_mul_add = 0;
      49: contract_mul_add = 0;
      50: contract_mul_add = 1;
      51: contract_mul_add = 1;
      52: contract_mul_add = 1;
      53: contract_mul_add = 2;
      54: contract_mul_add = 0;
      55: contract_mul_add = 0;
      56: contract_mul_add = 0;
      57: contract_mul_add = 0;
      58: contract_mul_add = 0;
      59: contract_mul_add = 0;
      60: contract_mul_add = 0;
      61: contract_mul_add = 0;
      62: contract_mul_add = 0;
      63: contract_mul_add = 0;
      64: contract_mul_add = 0;
      65: contract_mul_add = 0;
      default: contract_mul_add = 0;
    endcase
  endfunction

  // LATENCY of class k.
  function automatic int contract_latency(input int k);
    case (k)
      0: contract_latency = 6;
      1: contract_latency = 6;
      2: contract_latency = 7;
      3: contract_latency = 6;
      4: contract_latency = 6;
      5: contract_latency = 7;
      6: contract_latency = 7;
      7: contract_latency = 7;
      8: contract_latency = 8;
      9: contract_latency = 7;
      10: contract_latency = 7;
      11: contract_latency = 8;
      12: contract_latency = 7;
      13: contract_latency = 7;
      14: contract_latency = 8;
      15: contract_latency = 8;
      16: contract_latency = 8;
      17: contract_latency = 9;
      18: contract_latency = 8;
      19: contract_latency = 8;
      20: contract_latency = 9;
      21: contract_latency = 8;
      22: contract_latency = 8;
      23: contract_latency = 9;
      24: contract_latency = 9;
      25: contract_latency = 9;
      26: contract_latency = 10;
      27: contract_latency = 6;
      28: contract_latency = 6;
      29: contract_latency = 7;
      30: contract_latency = 6;
      31: contract_latency = 6;
      32: contract_latency = 7;
      33: contract_latency = 7;
      34: contract_latency = 7;
      35: contract_latency = 8;
      36: contract_latency = 7;
      37: contract_latency = 7;
      38: contract_latency = 8;
      39: contract_latency = 7;
      40: contract_latency = 7;
      41: contract_latency = 8;
      42: contract_latency = 8;
      43: contract_latency = 8;
      44: contract_latency = 9;
      45: contract_latency = 8;
      46: contract_latency = 8;
      47: contract_latency = 9;
      48: contract_latency = 8;
      49: contract_latency = 8;
      50: contract_latency = 9;
      51: contract_latency = 9;
      52: contract_latency = 9;
      53: contract_latency = 10;
      54: contract_latency = 6;
      55: contract_latency = 6;
      56: contract_latency = 6;
      57: contract_latency = 6;
      58: contract_latency = 7;
      59: contract_latency = 7;
      60: contract_latency = 7;
      61: contract_latency = 7;
      62: contract_latency = 8;
      63: contract_latency = 8;
      64: contract_latency = 8;
      65: contract_latency = 8;
      default: contract_latency = 0;
    endcase
  endfunction

  // FIFO_DEPTH of class k.
  function automatic int contract_fifo_depth(input int k);
    case (k)
      0: contract_fifo_depth = 8;
      1: contract_fifo_depth = 8;
      2: contract_fifo_depth = 16;
      3: contract_fifo_depth = 8;
      4: contract_fifo_depth = 8;
      5: contract_fifo_depth = 16;
      6: contract_fifo_depth = 16;
      7: contract_fifo_depth = 16;
      8: contract_fifo_depth = 16;
      9: contract_fifo_depth = 16;
      10: contract_fifo_depth = 16;
      11: contract_fifo_depth = 16;
      12: contract_fifo_depth = 16;
      13: contract_fifo_depth = 16;
      14: contract_fifo_depth = 16;
      15: contract_fifo_depth = 16;
      16: contract_fifo_depth = 16;
      17: contract_fifo_depth = 16;
      18: contract_fifo_depth = 16;
      19: contract_fifo_depth = 16;
      20: contract_fifo_depth = 16;
      21: contract_fifo_depth = 16;
      22: contract_fifo_depth = 16;
      23: contract_fifo_depth = 16;
      24: contract_fifo_depth = 16;
      25: contract_fifo_depth = 16;
      26: contract_fifo_depth = 16;
      27: contract_fifo_depth = 8;
      28: contract_fifo_depth = 8;
      29: contract_fifo_depth = 16;
      30: contract_fifo_depth = 8;
      31: contract_fifo_depth = 8;
      32: contract_fifo_depth = 16;
      33: contract_fifo_depth = 16;
      34: contract_fifo_depth = 16;
      35: contract_fifo_depth = 16;
      36: contract_fifo_depth = 16;
      37: contract_fifo_depth = 16;
      38: contract_fifo_depth = 16;
      39: contract_fifo_depth = 16;
      40: contract_fifo_depth = 16;
      41: contract_fifo_depth = 16;
      42: contract_fifo_depth = 16;
      43: contract_fifo_depth = 16;
      44: contract_fifo_depth = 16;
      45: contract_fifo_depth = 16;
      46: contract_fifo_depth = 16;
      47: contract_fifo_depth = 16;
      48: contract_fifo_depth = 16;
      49: contract_fifo_depth = 16;
      50: contract_fifo_depth = 16;
      51: contract_fifo_depth = 16;
      52: contract_fifo_depth = 16;
      53: contract_fifo_depth = 16;
      54: contract_fifo_depth = 8;
      55: contract_fifo_depth = 8;
      56: contract_fifo_depth = 8;
      57: contract_fifo_depth = 8;
      58: contract_fifo_depth = 16;
      59: contract_fifo_depth = 16;
      60: contract_fifo_depth = 16;
      61: contract_fifo_depth = 16;
      62: contract_fifo_depth = 16;
      63: contract_fifo_depth = 16;
      64: contract_fifo_depth = 16;
      65: contract_fifo_depth = 16;
      default: contract_fifo_depth = 0;
    endcase
  endfunction

  // The AXI4-Stream wrapper (pluecker_axis): s_axis_tdata_i holds the
  // intersector's payload input ports back to back from bit 0, field k
  // (0..axis_fields() - 1) at axis_field_lsb(k, c, d), axis_field_bits(k, c, d)
  // wide (c = COORD_BITS, d = DIR_BITS), zeros above axis_query_bits(c, d)
  // up to axis_tdata_bits(c, d), a whole number of bytes.
  function automatic int axis_fields();
    axis_fields = 7;
  endfunction
  function automatic int axis_field_lsb(input int k, input int c, input int d);
    case (k)
      0: axis_field_lsb = 0;  // ray_class_i
      1: axis_field_lsb = 3;  // ray_org_i
      2: axis_field_lsb = 3 + 3 * c;  // ray_dir_i
      3: axis_field_lsb = 3 + 3 * c + 3 * d;  // ray_end_i
      4: axis_field_lsb = 3 + 6 * c + 3 * d;  // ray_end_valid_i
      5: axis_field_lsb = 4 + 6 * c + 3 * d;  // box_min_i
      6: axis_field_lsb = 4 + 9 * c + 3 * d;  // box_max_i
      default: axis_field_lsb = -1;
    endcase
  endfunction
  function automatic int axis_field_bits(input int k, input int c, input int d);
    case (k)
      0: axis_field_bits = 3;  // ray_class_i
      1: axis_field_bits = 3 * c;  // ray_org_i
      2: axis_field_bits = 3 * d;  // ray_dir_i
      3: axis_field_bits = 3 * c;  // ray_end_i
      4: axis_field_bits = 1;  // ray_end_valid_i
      5: axis_field_bits = 3 * c;  // box_min_i
      6: axis_field_bits = 3 * c;  // box_max_i
      default: axis_field_bits = -1;
    endcase
  endfunction
  function automatic int axis_query_bits(input int c, input int d);
    axis_query_bits = 4 + 12 * c + 3 * d;
  endfunction
  function automatic int axis_tdata_bits(input int c, input int d);
    axis_tdata_bits = (axis_query_bits(c, d) + 7) / 8 * 8;
  endfunction
endpackage
