// SPDX-License-Identifier: MIT
// Subcommands of `pluecker_sim`, the Verilator harness. Each returns the
// exit status (0 ok, 1 mismatch or RTL protocol error, 2 bad input) and
// throws InputError for bad input.
#pragma once

#include "pluecker/app/args.hpp"

#include "pluecker/fixed.hpp"

#include <string>
#include <vector>

namespace pluecker::sim {

int cmd_query(const std::vector<std::string>& argv);
int cmd_render(const std::vector<std::string>& argv);
int cmd_bench(const std::vector<std::string>& argv);
int cmd_gen(const std::vector<std::string>& argv);

// Options every subcommand shares: --mode, --coord-bits, --dir-bits. They
// must agree with the configuration the RTL was built for (one binary per
// configuration); a mismatch is an InputError naming the make command that
// builds the right one.
void check_build_options(const app::Args& args);

// "16x16 conservative" for messages.
std::string build_name();

}  // namespace pluecker::sim
