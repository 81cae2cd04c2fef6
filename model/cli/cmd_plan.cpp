// SPDX-License-Identifier: MIT
// PLACEHOLDER: replaced by the real 'pluecker plan' implementation.
#include "args.hpp"

#include <cstdio>

namespace pluecker::cli {

int cmd_plan(const std::vector<std::string>&) {
    std::fprintf(stderr, "pluecker plan: not built yet\n");
    return 2;
}

}  // namespace pluecker::cli
