// SPDX-License-Identifier: MIT
// `pluecker_sim_local`: the Verilator harness of
// rtl/pluecker_local_intersector.sv, linked with the golden model library.
#include "commands.hpp"
#include "harness_main.hpp"
#include "rtl_local.hpp"

#include "pluecker/app/names.hpp"

#include <string>

namespace pluecker::sim {

void check_build_options(const app::Args& args) {
    const LocalFormat built = built_local_format();
    LocalFormat want = built;
    want.box_bits = static_cast<int>(args.get_int("box-bits", built.box_bits, -1'000'000, 1'000'000));
    want.dir_bits = static_cast<int>(args.get_int("dir-bits", built.dir_bits, -1'000'000, 1'000'000));
    want.grid_bits = static_cast<int>(args.get_int("grid-bits", built.grid_bits, -1'000'000, 1'000'000));
    if (args.has("mode")) want.mode = parse_fixed_mode(args.get("mode", ""));
    try {
        want.validate();
    } catch (const InputError& e) {
        throw InputError(std::string("--box-bits/--dir-bits/--grid-bits: ") + e.what());
    }
    if (want.box_bits != built.box_bits || want.dir_bits != built.dir_bits || want.grid_bits != built.grid_bits ||
        want.mode != built.mode) {
        const LocalRtlConfig c = built_local_config();
        throw InputError("this harness drives the RTL built for " + build_name() + ", not K" +
                         std::to_string(want.box_bits) + " D" + std::to_string(want.dir_bits) + " G" +
                         std::to_string(want.grid_bits) + " " + mode_name(want.mode) +
                         "; build that one with: make sim-local BOX_BITS=" + std::to_string(want.box_bits) +
                         " LOCAL_DIR_BITS=" + std::to_string(want.dir_bits) + " GRID_BITS=" +
                         std::to_string(want.grid_bits) + " CHILDREN=" + std::to_string(c.children) +
                         " MODE=" + mode_name(want.mode));
    }
}

TightQuery tight_query(const Query& q, const LocalFormat& f) {
    TightQuery t;
    t.frame = local_frame_for(q.box, f);
    t.box = local_quantize_box(q.box, t.frame, f);
    t.ray = local_setup_ray(q.ray, f);
    return t;
}

}  // namespace pluecker::sim

namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim_local <command> [options]\n"
    "  the Verilator model of rtl/pluecker_local_intersector.sv, driven through the golden model\n"
    "commands:\n"
    "  query   stream queries from a file through the RTL (each box in its tightest frame) and print\n"
    "          its answers (1 = hit, 0 = miss)\n"
    "  render  render a scene with every box test answered by the RTL, checked against the model\n"
    "  bench   RTL throughput in queries per second, with and without backpressure\n"
    "  gen     write random, extreme, set-up or boundary queries in the query text format\n"
    "run 'pluecker_sim_local <command> --help' for its options\n";

}  // namespace

int main(int argc, char** argv) {
    using namespace pluecker::sim;
    return harness_main(argc, argv, "pluecker_sim_local", kUsage, build_name() + ", TAG_BITS " + std::to_string(SIM_TAG_BITS),
                        {{"query", cmd_query}, {"render", cmd_render}, {"bench", cmd_bench}, {"gen", cmd_gen}});
}
