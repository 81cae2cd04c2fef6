// SPDX-License-Identifier: MIT
// Subcommands of `pluecker_sim_array`, the Verilator harness of the array
// of intersector units. Each returns the exit status (0 ok, 1 mismatch or
// RTL protocol error, 2 bad input) and throws InputError for bad input.
#pragma once

#include "array_rtl.hpp"

#include "lane_options.hpp"
#include "pluecker/app/args.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace pluecker::sim {

int cmd_render(const std::vector<std::string>& argv);
int cmd_check(const std::vector<std::string>& argv);
int cmd_bench(const std::vector<std::string>& argv);

// --mode, --coord-bits and --dir-bits must agree with the build (one binary
// per configuration); a mismatch is an InputError naming the make command
// that builds the right one.
void check_build_options(const app::Args& args);

// Removes `--name VALUE` (or `--name=VALUE`) from argv and returns VALUE.
std::optional<std::string> take_option(std::vector<std::string>& argv, const std::string& name);

// The "lanes" list of a JSON report: each lane's style, latency, answers,
// stall cycles, most queries in flight and queries dropped by resets.
nlohmann::json lanes_json(const ArrayRtl& rtl);

}  // namespace pluecker::sim
