// SPDX-License-Identifier: MIT
// Where the fabric multiplier (pluecker_mul_lut.sv) puts its registers,
// as one rule that the multiplier and its users both call: the multiplier
// builds its adder tree from it, and pluecker_intersector gives each
// multiplier its own direction register (DIR_COPIES) exactly where the
// rows are not registered.
package pluecker_mul_lut_pkg;
  // Tree levels above the WB partial-product rows.
  function automatic int mul_lut_levels(input int wb);
    mul_lut_levels = $clog2(wb);
  endfunction

  // PIPELINE 2 with 3 or more levels spreads three registers over the tree
  // and has none after the root's p_q.
  function automatic bit mul_lut_spread(input int pipeline, input int lv);
    mul_lut_spread = (pipeline == 2) && (lv >= 3);
  endfunction

  // Whether the nodes of tree level l (0: the rows, lv: the root) are
  // registered, for a multiplier of lv levels at the given PIPELINE
  // (pluecker_mul_lut.sv's header lists the cases). Where level 0 is not
  // registered, the row ANDs and the level-1 adders share one period.
  function automatic bit mul_lut_registered(input int pipeline, input int lv, input int l);
    if (mul_lut_spread(pipeline, lv))
      mul_lut_registered = (l == (lv - 2) / 2) || (l == lv - 2) || (l == lv - 1);
    else
      mul_lut_registered = (l == 0) || (pipeline != 0 && l == (lv + 1) / 2);
  endfunction
endpackage
