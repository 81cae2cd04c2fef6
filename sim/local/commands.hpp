// SPDX-License-Identifier: MIT
// Subcommands of `pluecker_sim_local`, the Verilator harness of the local
// unit. Each returns the exit status (0 ok, 1 mismatch or RTL protocol
// error, 2 bad input) and throws InputError for bad input.
#pragma once

#include "pluecker/app/args.hpp"

#include "pluecker/local.hpp"
#include "pluecker/query.hpp"

#include <optional>
#include <string>
#include <vector>

namespace pluecker::sim {

int cmd_query(const std::vector<std::string>& argv);
int cmd_render(const std::vector<std::string>& argv);
int cmd_bench(const std::vector<std::string>& argv);
int cmd_gen(const std::vector<std::string>& argv);

// Options every subcommand shares: --mode, --box-bits, --dir-bits,
// --grid-bits. They must agree with the configuration the RTL was built
// for (one binary per configuration); a mismatch is an InputError naming
// the make command that builds the right one.
void check_build_options(const app::Args& args);

// A float query set up as the harness sends it: the ray at the global
// width (nullopt: the segment never meets the grid's range, a miss without
// an RTL query) and the box in its tightest frame.
struct TightQuery {
    std::optional<LocalRay> ray;
    LocalFrame frame;
    LocalBox box;
};
// InputError for a box outside the format's range.
TightQuery tight_query(const Query& q, const LocalFormat& f);

}  // namespace pluecker::sim
