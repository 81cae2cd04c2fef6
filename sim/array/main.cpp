// SPDX-License-Identifier: MIT
// `pluecker_sim_array`: the Verilator harness of rtl/pluecker_array.sv
// (N_DSP + N_LUT + N_ROM intersector units side by side, one lane each), linked with
// the golden model library.
#include "commands.hpp"
#include "harness_main.hpp"

#include "pluecker/app/names.hpp"

#include <string>

namespace pluecker::sim {

void check_build_options(const app::Args& args) {
    const FixedFormat built = built_format();
    FixedFormat want = built;
    want.coord_bits = static_cast<int>(args.get_int("coord-bits", built.coord_bits, -1'000'000, 1'000'000));
    want.dir_bits = static_cast<int>(args.get_int("dir-bits", built.dir_bits, -1'000'000, 1'000'000));
    if (args.has("mode")) want.mode = parse_fixed_mode(args.get("mode", ""));
    try {
        want.validate();
    } catch (const InputError& e) {
        throw InputError(std::string("--coord-bits/--dir-bits: ") + e.what());
    }
    if (want.coord_bits == built.coord_bits && want.dir_bits == built.dir_bits && want.mode == built.mode) return;
    throw InputError("this harness drives the array built for " + build_name() + ", not " +
                     std::to_string(want.coord_bits) + "x" + std::to_string(want.dir_bits) + " " +
                     mode_name(want.mode) + "; build that one with: make sim-array ARRAY_DSP=" +
                     std::to_string(SIM_ARRAY_DSP) + " ARRAY_LUT=" + std::to_string(SIM_ARRAY_LUT) +
                     (SIM_ARRAY_ROM ? " ARRAY_ROM=" + std::to_string(SIM_ARRAY_ROM) : std::string()) +
                     " COORD_BITS=" + std::to_string(want.coord_bits) + " DIR_BITS=" +
                     std::to_string(want.dir_bits) + " MODE=" + mode_name(want.mode));
}

std::optional<std::string> take_option(std::vector<std::string>& argv, const std::string& name) {
    const std::string flag = "--" + name;
    for (std::size_t i = 0; i < argv.size(); ++i) {
        if (argv[i].rfind(flag + "=", 0) == 0) {
            std::string v = argv[i].substr(flag.size() + 1);
            argv.erase(argv.begin() + static_cast<std::ptrdiff_t>(i));
            return v;
        }
        if (argv[i] != flag) continue;
        if (i + 1 >= argv.size()) throw InputError("option " + flag + " needs a value");
        std::string v = argv[i + 1];
        argv.erase(argv.begin() + static_cast<std::ptrdiff_t>(i), argv.begin() + static_cast<std::ptrdiff_t>(i + 2));
        return v;
    }
    return std::nullopt;
}

nlohmann::json lanes_json(const ArrayRtl& rtl) {
    nlohmann::json lanes = nlohmann::json::array();
    for (int l = 0; l < kLanes; ++l) {
        const LaneStats& s = rtl.lane_stats()[static_cast<std::size_t>(l)];
        lanes.push_back({{"lane", l},
                         {"mul_style", lane_style(l)},
                         {"latency", rtl.measured_latency()[static_cast<std::size_t>(l)]},
                         {"queries", s.queries},
                         {"stall_cycles", s.stall_cycles},
                         {"max_in_flight", s.max_in_flight},
                         {"dropped", s.dropped}});
    }
    return lanes;
}

}  // namespace pluecker::sim

namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim_array <command> [options]\n"
    "  the Verilator model of rtl/pluecker_array.sv (N_DSP + N_LUT + N_ROM intersector units,\n"
    "  one lane each), driven through the golden model: every batch of queries is spread over\n"
    "  the lanes round-robin, all lanes are driven every clock, and each lane's answers are\n"
    "  matched in order by tag and checked against the model's fixed_hit\n"
    "commands:\n"
    "  render  render a scene with every box test answered by the array, checked against the model\n"
    "  check   generated queries or operands through every lane (back-pressure, idle inputs,\n"
    "          resets mid-stream), every answer against the model\n"
    "  bench   the array's throughput in queries per second, with and without backpressure\n"
    "run 'pluecker_sim_array <command> --help' for its options\n";

}  // namespace

int main(int argc, char** argv) {
    using namespace pluecker::sim;
    return harness_main(argc, argv, "pluecker_sim_array", kUsage,
                        build_name() + ", TAG_BITS " + std::to_string(SIM_TAG_BITS) + ", PIPELINE " +
                            std::to_string(SIM_PIPELINE),
                        {{"render", cmd_render}, {"check", cmd_check}, {"bench", cmd_bench}});
}
