// SPDX-License-Identifier: MIT
// Command-line names of the libraries' enums and lists, parsed here, by
// the applications alone; the libraries take the enums (and print the
// names back with test_name, order_name, method_name, mode_name).
// Each throws InputError naming the bad value.
#pragma once

#include "pluecker/bvh.hpp"
#include "pluecker/contract.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/float_contract.hpp"
#include "pluecker/study.hpp"
#include "pluecker/traversal.hpp"

#include <string>
#include <vector>

namespace pluecker {

BoxTestKind parse_box_test(const std::string& s);      // exact | smits | pluecker | fixed | local
ChildOrder parse_child_order(const std::string& s);    // fixed | dsa | dist
BuildMethod parse_build_method(const std::string& s);  // median | sah
FixedMode parse_fixed_mode(const std::string& s);      // conservative | nearest
MulStyle parse_mul_style(const std::string& s);        // auto | dsp | lut (the RTL's MUL_STYLE)
FloatUnit parse_float_unit(const std::string& s);      // float | smits (the binary32 units)

// Width list of --widths (`flag` names it in errors):
//   "A:B:S"          A, A+S, ..., <= B, COORD_BITS = DIR_BITS (S >= 1;
//                    "A:B" is step 1)
//   "W1,W2,..."      equal pairs
//   "12x10,16x16"    separate pairs COORD_BITSxDIR_BITS (mixable with W)
// Every width in 6..24; at least one; InputError naming the flag otherwise.
std::vector<WidthPair> parse_widths(const std::string& spec, const std::string& flag = "--widths");

// A list of widths in lo..hi: "A:B[:S]" or "W1,W2,...", as above (the
// local frames' box widths of `pluecker study --local`).
std::vector<int> parse_bit_list(const std::string& spec, const std::string& flag, int lo, int hi);

}  // namespace pluecker
