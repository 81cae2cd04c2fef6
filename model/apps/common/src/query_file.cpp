// SPDX-License-Identifier: MIT
#include "pluecker/app/query_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>

namespace pluecker::app {

std::vector<Query> read_query_file(const std::string& path, std::vector<std::size_t>& lines) {
    if (path == "-") return read_queries(std::cin, query_source_name(path), &lines);
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
    return read_queries(in, path, &lines);
}

}  // namespace pluecker::app
