// SPDX-License-Identifier: MIT
// Operand files: queries as the datapath's ports take them (querygen.hpp's
// FixedQuery), for the harness (`pluecker_sim gen --kind boundary|ports`,
// `pluecker_sim query`). The float query format (query.hpp) cannot carry
// them: the set-up never makes directions above 1.0, boxes with LO > HI or
// the operands a decision-boundary query needs.
//
// Text, one query a line after a header line; '#' starts a comment:
//   operands COORD_BITS DIR_BITS MODE
//   cls ox oy oz dx dy dz end_valid ex ey ez lox loy loz hix hiy hiz
// 17 decimal integers: cls 0..7 (bit a set = axis a negative), coordinates
// in the C-bit two's-complement range, directions in 0..2^D - 1, end_valid
// 0 or 1. The header's format must be the reader's.
#pragma once

#include "pluecker/fixed.hpp"
#include "pluecker/querygen.hpp"

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

namespace pluecker::app {

void write_operand_header(std::ostream& out, const FixedFormat& f);
void write_operands(std::ostream& out, const FixedQuery& q);

// True when the first line of `path` that is not blank or a comment is an
// operand header ('-' is never an operand file: standard input is read once).
bool is_operand_file(const std::string& path);

// The queries of an operand file for format f; lines[i] is the line number
// of query i. InputError naming file:line for a missing or different
// header, a malformed line or an operand outside its port range.
std::vector<FixedQuery> read_operand_file(const std::string& path, const FixedFormat& f,
                                          std::vector<std::size_t>& lines);

}  // namespace pluecker::app
