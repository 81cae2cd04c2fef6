// SPDX-License-Identifier: MIT
// A query file named on a command line (`pluecker query`, `pluecker_sim
// query`): the text format of query.hpp, '-' for standard input.
#pragma once

#include "pluecker/query.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace pluecker::app {

// The queries of `path` ('-': standard input, named "<stdin>" in errors);
// lines[i] is the line number of query i. InputError when the file cannot
// be opened or a line is malformed (read_queries).
std::vector<Query> read_query_file(const std::string& path, std::vector<std::size_t>& lines);

// How errors name the file: "<stdin>" for '-'.
inline std::string query_source_name(const std::string& path) { return path == "-" ? "<stdin>" : path; }

}  // namespace pluecker::app
