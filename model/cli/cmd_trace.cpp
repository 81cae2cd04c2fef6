// SPDX-License-Identifier: MIT
// PLACEHOLDER: replaced by the real 'pluecker trace' implementation.
#include "args.hpp"

#include <cstdio>

namespace pluecker::cli {

int cmd_trace(const std::vector<std::string>&) {
    std::fprintf(stderr, "pluecker trace: not built yet\n");
    return 2;
}

}  // namespace pluecker::cli
