// SPDX-License-Identifier: MIT
// PLACEHOLDER: replaced by the real 'pluecker render' implementation.
#include "args.hpp"

#include <cstdio>

namespace pluecker::cli {

int cmd_render(const std::vector<std::string>&) {
    std::fprintf(stderr, "pluecker render: not built yet\n");
    return 2;
}

}  // namespace pluecker::cli
