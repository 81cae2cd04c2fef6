// SPDX-License-Identifier: MIT
// PLACEHOLDER: replaced by the real 'pluecker query' implementation.
#include "args.hpp"

#include <cstdio>

namespace pluecker::cli {

int cmd_query(const std::vector<std::string>&) {
    std::fprintf(stderr, "pluecker query: not built yet\n");
    return 2;
}

}  // namespace pluecker::cli
