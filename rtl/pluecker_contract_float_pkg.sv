// SPDX-License-Identifier: MIT
// Generated from model/core/src/float_contract.cpp by `pluecker contract --write rtl`:
// do not edit (the test FloatContract.GeneratedFilesAreCurrent compares this file).
//
// The port contract of the binary32 units pluecker_float_intersector and
// pluecker_smits_intersector (model/core/include/pluecker/float_contract.hpp):
// the limits they check and the constants they must derive; elaboration fails
// when a unit's LATENCY or FIFO_DEPTH, or a primitive's latency, differs.
package pluecker_contract_float_pkg;
  localparam int MIN_TAG_BITS = 1;
  // Latencies of pluecker_f32_add and pluecker_f32_mul.
  localparam int ADD_LATENCY = 8;
  localparam int MUL_LATENCY = 7;
  // MULT18X18D per significand product when MUL_DSP is not given.
  localparam int DEFAULT_MUL_DSP = 4;
  // pluecker_float_intersector
  localparam int FLOAT_LATENCY = 18;
  localparam int FLOAT_FIFO_DEPTH = 32;
  localparam int FLOAT_MULTIPLIERS = 12;
  // pluecker_smits_intersector
  localparam int SMITS_LATENCY = 20;
  localparam int SMITS_FIFO_DEPTH = 32;
  localparam int SMITS_MULTIPLIERS = 6;

  // MUL_DSP values the units take.
  function automatic bit mul_dsp_ok(input int m);
    mul_dsp_ok = m == 1 || m == 3 || m == 4;
  endfunction
endpackage
