// SPDX-License-Identifier: MIT
// The ray/box query text format shared by the CLI, `pluecker trace`, the
// Verilator harness and the cocotb tests.
//
// One query a line, 13 numbers separated by white space:
//   ox oy oz dx dy dz tmax minx miny minz maxx maxy maxz
// Numbers are read as C's strtod reads them (decimal, hex floats such as
// 0x1.8p-3, inf) and then rounded to float32. tmax = inf is an unbounded
// ray. Blank lines and text after '#' are ignored. Rejected, with the line
// number: a malformed line, NaN, an all-zero direction, a negative tmax,
// min > max.
#pragma once

#include "pluecker/geometry.hpp"

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

namespace pluecker {

// Throws InputError("<source>:<line>: <what>") on the first bad line.
std::vector<Query> read_queries(std::istream& in, const std::string& source);
// As above; also stores the 1-based line number of each query in *lines
// (when given), so later errors (e.g. a fixed-point range error) can name it.
std::vector<Query> read_queries(std::istream& in, const std::string& source,
                                std::vector<std::size_t>* lines);
std::vector<Query> read_queries_file(const std::string& path);

// Checks one query the way read_queries does; throws InputError naming
// `where` and the field.
void validate_query(const Query& q, const std::string& where);

// Writes one query line with hex floats, so read_queries gives back the
// same bits.
void write_query(std::ostream& out, const Query& q);

}  // namespace pluecker
