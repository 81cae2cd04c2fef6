// SPDX-License-Identifier: MIT
// Subcommands of `pluecker_sim_cascade`, the Verilator harness of the
// cascade. Each returns the exit status (0 ok, 1 mismatch or RTL protocol
// error, 2 bad input) and throws InputError for bad input.
#pragma once

#include "cascade_rtl.hpp"

#include "lane_options.hpp"
#include "pluecker/app/args.hpp"
#include "pluecker/cascade.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace pluecker::sim {

int cmd_render(const std::vector<std::string>& argv);
int cmd_check(const std::vector<std::string>& argv);

// --narrow CxD and --wide CxD (one pair each) must be the build's widths
// (one binary per configuration); a mismatch is an InputError naming the
// make command that builds the right one.
void check_build_widths(const app::Args& args);

// The "lanes" list of a JSON report: each lane's latencies, certain and
// escalated answers, stall cycles, most queries in flight and queries
// dropped by resets.
nlohmann::json lanes_json(const CascadeRtl& rtl);

}  // namespace pluecker::sim
