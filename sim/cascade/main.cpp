// SPDX-License-Identifier: MIT
// `pluecker_sim_cascade`: the Verilator harness of rtl/pluecker_cascade.sv
// (N narrow TERNARY lanes escalating their uncertain answers to one wide
// unit), linked with the golden model library.
#include "commands.hpp"
#include "harness_main.hpp"

#include "pluecker/app/names.hpp"

#include <string>

namespace pluecker::sim {
namespace {

std::string pair_text(int c, int d) { return std::to_string(c) + "x" + std::to_string(d); }

// The build's widths, or the one pair `--name` gives (InputError for a list).
WidthPair given_pair(const app::Args& args, const char* name, const FixedFormat& built) {
    const std::string flag = std::string("--") + name;
    if (!args.has(name)) return {built.coord_bits, built.dir_bits};
    const std::vector<WidthPair> w = parse_widths(args.get(name, ""), flag);
    if (w.size() != 1) throw InputError("option " + flag + ": this harness drives one width pair, e.g. 8x8");
    return w.front();
}

}  // namespace

void check_build_widths(const app::Args& args) {
    const CascadeFormats built = built_formats();
    const WidthPair n = given_pair(args, "narrow", built.narrow);
    const WidthPair w = given_pair(args, "wide", built.wide);
    if (n == WidthPair{built.narrow.coord_bits, built.narrow.dir_bits} &&
        w == WidthPair{built.wide.coord_bits, built.wide.dir_bits})
        return;
    throw InputError("this harness drives the cascade built for " + build_name() + ", not " + std::to_string(kLanes) +
                     " lanes " + pair_text(n.coord_bits, n.dir_bits) + " -> " + pair_text(w.coord_bits, w.dir_bits) +
                     "; build that one with: make sim-cascade CASCADE_N=" + std::to_string(kLanes) +
                     " NARROW_COORD_BITS=" + std::to_string(n.coord_bits) + " NARROW_DIR_BITS=" +
                     std::to_string(n.dir_bits) + " WIDE_COORD_BITS=" + std::to_string(w.coord_bits) +
                     " WIDE_DIR_BITS=" + std::to_string(w.dir_bits));
}

nlohmann::json lanes_json(const CascadeRtl& rtl) {
    nlohmann::json lanes = nlohmann::json::array();
    for (int l = 0; l < kLanes; ++l) {
        const auto k = static_cast<std::size_t>(l);
        const CascadeLaneStats& s = rtl.lane_stats()[k];
        lanes.push_back({{"lane", l},
                         {"certain_latency", rtl.certain_latency()[k]},
                         {"escalated_latency", rtl.escalated_latency()[k]},
                         {"queries", s.certain + s.escalated},
                         {"certain", s.certain},
                         {"escalated", s.escalated},
                         {"stall_cycles", s.stall_cycles},
                         {"max_in_flight", s.max_in_flight},
                         {"dropped", s.dropped}});
    }
    return lanes;
}

}  // namespace pluecker::sim

namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim_cascade <command> [options]\n"
    "  the Verilator model of rtl/pluecker_cascade.sv (N narrow TERNARY lanes, their\n"
    "  uncertain answers re-tested by one shared wide unit), driven through the golden\n"
    "  model: every query is set up in both formats, the queries are spread over the\n"
    "  lanes round-robin, all lanes are driven every clock, certain answers are matched\n"
    "  per lane and escalated ones by lane and tag, and each is checked against the\n"
    "  model's cascade_answer\n"
    "commands:\n"
    "  render  render a scene with every box test answered by the cascade (as 'pluecker\n"
    "          cascade' renders it), checked against the model\n"
    "  check   generated float queries through every lane (back-pressure, idle inputs,\n"
    "          resets mid-stream), every answer against the model\n"
    "run 'pluecker_sim_cascade <command> --help' for its options\n";

}  // namespace

int main(int argc, char** argv) {
    using namespace pluecker::sim;
    return harness_main(argc, argv, "pluecker_sim_cascade", kUsage,
                        build_name() + ", TAG_BITS " + std::to_string(SIM_TAG_BITS) + ", PIPELINE " +
                            std::to_string(SIM_PIPELINE),
                        {{"render", cmd_render}, {"check", cmd_check}});
}
