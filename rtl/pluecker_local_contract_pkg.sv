// SPDX-License-Identifier: MIT
// Generated from model/core/src/local_contract.cpp by `pluecker contract --write rtl`:
// do not edit (the test LocalContract.GeneratedFilesAreCurrent compares this file).
//
// The port contract of pluecker_local_intersector
// (model/core/include/pluecker/local_contract.hpp): the parameter limits the
// module checks and the configuration classes, each with the constants the
// module must derive from its parameters. The module looks its configuration
// up (local_contract_class) and fails elaboration when what it derives
// differs from the class's row.
package pluecker_local_contract_pkg;
  localparam int MIN_BOX_BITS = 4;
  localparam int MAX_BOX_BITS = 16;
  localparam int MIN_DIR_BITS = 4;
  localparam int MAX_DIR_BITS = 24;
  // GRID_BITS is BOX_BITS + GRID_MARGIN .. MAX_GRID_BITS.
  localparam int GRID_MARGIN = 2;
  localparam int MAX_GRID_BITS = 32;
  localparam int MIN_TAG_BITS = 1;
  localparam int MAX_CHILDREN = 2;
  // A multiplier operand wider than this is split over two DSP operands.
  localparam int DSP_OPERAND_BITS = 18;

  // The class of a configuration (d = DIR_BITS, g = GRID_BITS, s = MUL_STYLE
  // as a 32-bit pattern), -1 when the module refuses it.
  function automatic int local_contract_class(input int d, input int g, input logic [31:0] s);
    local_contract_class = -1;
    if (d >= 4 && d <= 17 && g >= 6 && g <= 15 && s == 32'("auto")) local_contract_class = 0;
    if (d >= 4 && d <= 17 && g >= 16 && g <= 17 && s == 32'("auto")) local_contract_class = 1;
    if (d >= 4 && d <= 17 && g >= 18 && g <= 32 && s == 32'("auto")) local_contract_class = 2;
    if (d >= 18 && d <= 24 && g >= 6 && g <= 15 && s == 32'("auto")) local_contract_class = 3;
    if (d >= 18 && d <= 24 && g >= 16 && g <= 17 && s == 32'("auto")) local_contract_class = 4;
    if (d >= 18 && d <= 24 && g >= 18 && g <= 32 && s == 32'("auto")) local_contract_class = 5;
    if (d >= 4 && d <= 17 && g >= 6 && g <= 15 && s == 32'("dsp")) local_contract_class = 6;
    if (d >= 4 && d <= 17 && g >= 16 && g <= 17 && s == 32'("dsp")) local_contract_class = 7;
    if (d >= 4 && d <= 17 && g >= 18 && g <= 32 && s == 32'("dsp")) local_contract_class = 8;
    if (d >= 18 && d <= 24 && g >= 6 && g <= 15 && s == 32'("dsp")) local_contract_class = 9;
    if (d >= 18 && d <= 24 && g >= 16 && g <= 17 && s == 32'("dsp")) local_contract_class = 10;
    if (d >= 18 && d <= 24 && g >= 18 && g <= 32 && s == 32'("dsp")) local_contract_class = 11;
    if (d >= 4 && d <= 17 && g >= 6 && g <= 15 && s == 32'("lut")) local_contract_class = 12;
    if (d >= 4 && d <= 17 && g >= 16 && g <= 17 && s == 32'("lut")) local_contract_class = 13;
    if (d >= 4 && d <= 17 && g >= 18 && g <= 32 && s == 32'("lut")) local_contract_class = 14;
    if (d >= 18 && d <= 24 && g >= 6 && g <= 15 && s == 32'("lut")) local_contract_class = 15;
    if (d >= 18 && d <= 24 && g >= 16 && g <= 17 && s == 32'("lut")) local_contract_class = 16;
    if (d >= 18 && d <= 24 && g >= 18 && g <= 32 && s == 32'("lut")) local_contract_class = 17;
  endfunction

  // 1: the node set-up's products in fabric (pluecker_mul_lut) of class k.
  function automatic bit local_contract_frame_lut(input int k);
    case (k)
      0: local_contract_frame_lut = 0;
      1: local_contract_frame_lut = 0;
      2: local_contract_frame_lut = 0;
      3: local_contract_frame_lut = 0;
      4: local_contract_frame_lut = 0;
      5: local_contract_frame_lut = 0;
      6: local_contract_frame_lut = 0;
      7: local_contract_frame_lut = 0;
      8: local_contract_frame_lut = 0;
      9: local_contract_frame_lut = 0;
      10: local_contract_frame_lut = 0;
      11: local_contract_frame_lut = 0;
      12: local_contract_frame_lut = 1;
      13: local_contract_frame_lut = 1;
      14: local_contract_frame_lut = 1;
      15: local_contract_frame_lut = 1;
      16: local_contract_frame_lut = 1;
      17: local_contract_frame_lut = 1;
      default: local_contract_frame_lut = 0;
    endcase
  endfunction

  // 1: the children's products in fabric (pluecker_mul_lut) of class k.
  function automatic bit local_contract_child_lut(input int k);
    case (k)
      0: local_contract_child_lut = 1;
      1: local_contract_child_lut = 1;
      2: local_contract_child_lut = 1;
      3: local_contract_child_lut = 1;
      4: local_contract_child_lut = 1;
      5: local_contract_child_lut = 1;
      6: local_contract_child_lut = 0;
      7: local_contract_child_lut = 0;
      8: local_contract_child_lut = 0;
      9: local_contract_child_lut = 0;
      10: local_contract_child_lut = 0;
      11: local_contract_child_lut = 0;
      12: local_contract_child_lut = 1;
      13: local_contract_child_lut = 1;
      14: local_contract_child_lut = 1;
      15: local_contract_child_lut = 1;
      16: local_contract_child_lut = 1;
      17: local_contract_child_lut = 1;
      default: local_contract_child_lut = 0;
    endcase
  endfunction

  // FRAME_MUL_ADD of class k.
  function automatic int local_contract_frame_mul_add(input int k);
    case (k)
      0: local_contract_frame_mul_add = 0;
      1: local_contract_frame_mul_add = 1;
      2: local_contract_frame_mul_add = 2;
      3: local_contract_frame_mul_add = 0;
      4: local_contract_frame_mul_add = 1;
      5: local_contract_frame_mul_add = 2;
      6: local_contract_frame_mul_add = 0;
      7: local_contract_frame_mul_add = 1;
      8: local_contract_frame_mul_add = 2;
      9: local_contract_frame_mul_add = 0;
      10: local_contract_frame_mul_add = 1;
      11: local_contract_frame_mul_add = 2;
      12: local_contract_frame_mul_add = 0;
      13: local_contract_frame_mul_add = 0;
      14: local_contract_frame_mul_add = 0;
      15: local_contract_frame_mul_add = 0;
      16: local_contract_frame_mul_add = 0;
      17: local_contract_frame_mul_add = 0;
      default: local_contract_frame_mul_add = 0;
    endcase
  endfunction

  // CHILD_MUL_ADD of class k.
  function automatic int local_contract_child_mul_add(input int k);
    case (k)
      0: local_contract_child_mul_add = 0;
      1: local_contract_child_mul_add = 0;
      2: local_contract_child_mul_add = 0;
      3: local_contract_child_mul_add = 0;
      4: local_contract_child_mul_add = 0;
      5: local_contract_child_mul_add = 0;
      6: local_contract_child_mul_add = 0;
      7: local_contract_child_mul_add = 0;
      8: local_contract_child_mul_add = 0;
      9: local_contract_child_mul_add = 1;
      10: local_contract_child_mul_add = 1;
      11: local_contract_child_mul_add = 1;
      12: local_contract_child_mul_add = 0;
      13: local_contract_child_mul_add = 0;
      14: local_contract_child_mul_add = 0;
      15: local_contract_child_mul_add = 0;
      16: local_contract_child_mul_add = 0;
      17: local_contract_child_mul_add = 0;
      default: local_contract_child_mul_add = 0;
    endcase
  endfunction

  // LATENCY of class k.
  function automatic int local_contract_latency(input int k);
    case (k)
      0: local_contract_latency = 14;
      1: local_contract_latency = 15;
      2: local_contract_latency = 16;
      3: local_contract_latency = 14;
      4: local_contract_latency = 15;
      5: local_contract_latency = 16;
      6: local_contract_latency = 14;
      7: local_contract_latency = 15;
      8: local_contract_latency = 16;
      9: local_contract_latency = 15;
      10: local_contract_latency = 16;
      11: local_contract_latency = 17;
      12: local_contract_latency = 14;
      13: local_contract_latency = 14;
      14: local_contract_latency = 14;
      15: local_contract_latency = 14;
      16: local_contract_latency = 14;
      17: local_contract_latency = 14;
      default: local_contract_latency = 0;
    endcase
  endfunction

  // FIFO_DEPTH of class k.
  function automatic int local_contract_fifo_depth(input int k);
    case (k)
      0: local_contract_fifo_depth = 16;
      1: local_contract_fifo_depth = 32;
      2: local_contract_fifo_depth = 32;
      3: local_contract_fifo_depth = 16;
      4: local_contract_fifo_depth = 32;
      5: local_contract_fifo_depth = 32;
      6: local_contract_fifo_depth = 16;
      7: local_contract_fifo_depth = 32;
      8: local_contract_fifo_depth = 32;
      9: local_contract_fifo_depth = 32;
      10: local_contract_fifo_depth = 32;
      11: local_contract_fifo_depth = 32;
      12: local_contract_fifo_depth = 16;
      13: local_contract_fifo_depth = 16;
      14: local_contract_fifo_depth = 16;
      15: local_contract_fifo_depth = 16;
      16: local_contract_fifo_depth = 16;
      17: local_contract_fifo_depth = 16;
      default: local_contract_fifo_depth = 0;
    endcase
  endfunction
endpackage
