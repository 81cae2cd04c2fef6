// SPDX-License-Identifier: MIT
// binary32 comparison (combinational): lt_o = a_i < b_i, le_o = a_i <= b_i,
// the IEEE-754 comparisons on the bit patterns (f32::lt and f32::le of
// model/core/include/pluecker/f32unit.hpp). Subnormals compare as their
// values (a comparator needs no flushing), -0 equals +0, and a NaN operand
// makes both outputs 0.
`default_nettype none

module pluecker_f32_cmp (
    input  wire [31:0] a_i,
    input  wire [31:0] b_i,
    output wire        lt_o,
    output wire        le_o
);
  wire [30:0] mag_a = a_i[30:0];
  wire [30:0] mag_b = b_i[30:0];
  wire nan = (&a_i[30:23] && |a_i[22:0]) || (&b_i[30:23] && |b_i[22:0]);
  // Signs of the values (a zero counts as +0).
  wire sa = a_i[31] && |mag_a;
  wire sb = b_i[31] && |mag_b;
  wire mag_lt = mag_a < mag_b;
  wire mag_eq = mag_a == mag_b;
  // Same sign: the magnitudes decide (reversed for negative values).
  wire same_lt = sa ? !(mag_lt || mag_eq) : mag_lt;
  wire same_le = sa ? !mag_lt : (mag_lt || mag_eq);

  assign lt_o = !nan && ((sa != sb) ? sa : same_lt);
  assign le_o = !nan && ((sa != sb) ? sa : same_le);
endmodule

`default_nettype wire
