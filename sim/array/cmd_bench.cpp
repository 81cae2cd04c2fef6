// SPDX-License-Identifier: MIT
// `pluecker_sim_array bench`: how many queries per second the Verilated
// array answers (all lanes fed), with out_ready held high and with random
// backpressure; the passes are the other harnesses' (bench_pass.hpp).
#include "bench_pass.hpp"
#include "commands.hpp"

#include "pluecker/querygen.hpp"

#include <algorithm>
#include <cstdio>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim_array bench [--n N] [--seed S] [--ready P]\n"
    "Streams N queries (default 2000000; a pool of up to 65536 random queries, set up,\n"
    "quantised and packed before timing) through the array's lanes round-robin, first\n"
    "with every out_ready_i held high, then high with probability P each cycle (default\n"
    "0.5). Prints queries per second and per cycle and compares every answer with the\n"
    "golden model.\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

constexpr std::size_t kPool = 65536;

}  // namespace

int cmd_bench(const std::vector<std::string>& argv) {
    const app::Args args(argv, {"n", "seed", "ready", "mode", "coord-bits", "dir-bits"}, {"help"});
    if (args.has("help")) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    check_build_options(args);
    if (!args.positional().empty()) throw InputError("unexpected argument '" + args.positional()[0] + "'");
    const auto n = static_cast<std::size_t>(args.get_int("n", 2'000'000, 1, 1'000'000'000'000l));
    const auto seed = static_cast<std::uint64_t>(args.get_int("seed", 1, 0, 0x7fffffffffffffffl));
    const double p = probability(args, "ready", 0.5);

    const FixedFormat fmt = built_format();
    const std::vector<Query> qs = random_queries(seed, std::min(n, kPool));
    std::vector<LaneQuery> packed(qs.size());
    std::vector<std::uint8_t> expect(qs.size());
    for (std::size_t i = 0; i < qs.size(); ++i) {
        const FixedRay r = *fixed_setup_ray(qs[i].ray, fmt);  // random_queries start inside the range
        const FixedBox b = fixed_quantize_box(qs[i].box, fmt);
        packed[i] = pack_lane_query(r, b);
        expect[i] = fixed_hit(r, b, fmt) ? 1 : 0;
    }
    std::vector<BenchPass> passes = {{"out_ready high", 1.0}, {"random backpressure", p}};
    std::uint64_t mismatches = 0;
    std::printf("bench %s, TAG_BITS %d, %d lanes: %zu queries (pool of %zu)\n", build_name().c_str(), SIM_TAG_BITS,
                kLanes, n, qs.size());
    for (BenchPass& pass : passes) {
        run_bench_pass<ArrayRtl>(pass, n, packed, expect, seed);
        mismatches += pass.mismatches;
        print_bench_pass(pass);
    }
    std::printf("  %llu mismatches\n", static_cast<unsigned long long>(mismatches));
    return mismatches == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
