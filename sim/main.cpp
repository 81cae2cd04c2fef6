// SPDX-License-Identifier: MIT
// `pluecker_sim`: the Verilator harness of rtl/pluecker_intersector.sv,
// linked with the golden model library.
#include "commands.hpp"
#include "harness_main.hpp"
#include "rtl_intersector.hpp"

#include "pluecker/app/names.hpp"

#include <string>

namespace pluecker::sim {

std::string build_name() {
    const FixedFormat f = built_format();
    return std::to_string(f.coord_bits) + "x" + std::to_string(f.dir_bits) + " " + mode_name(f.mode);
}

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
    if (want.coord_bits != built.coord_bits || want.dir_bits != built.dir_bits || want.mode != built.mode) {
        throw InputError("this harness drives the RTL built for " + build_name() + ", not " +
                         std::to_string(want.coord_bits) + "x" + std::to_string(want.dir_bits) + " " +
                         mode_name(want.mode) + "; build that one with: make sim COORD_BITS=" +
                         std::to_string(want.coord_bits) + " DIR_BITS=" + std::to_string(want.dir_bits) +
                         " MODE=" + mode_name(want.mode));
    }
}

}  // namespace pluecker::sim

namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim <command> [options]\n"
    "  the Verilator model of rtl/pluecker_intersector.sv, driven through the golden model\n"
    "commands:\n"
    "  query   stream queries from a file through the RTL and print its answers (1 = hit, 0 = miss)\n"
    "  render  render a scene with every box test answered by the RTL, checked against the model\n"
    "  bench   RTL throughput in queries per second, with and without backpressure\n"
    "  gen     write random or extreme queries in the query text format\n"
    "run 'pluecker_sim <command> --help' for its options\n";

}  // namespace

int main(int argc, char** argv) {
    using namespace pluecker::sim;
    return harness_main(argc, argv, "pluecker_sim", kUsage, build_name() + ", TAG_BITS " + std::to_string(SIM_TAG_BITS),
                        {{"query", cmd_query}, {"render", cmd_render}, {"bench", cmd_bench}, {"gen", cmd_gen}});
}
