// SPDX-License-Identifier: MIT
// `pluecker_sim bench`: how many queries per second the Verilated RTL
// answers, with out_ready held high and with random backpressure.
#include "commands.hpp"
#include "bench_pass.hpp"
#include "rtl_intersector.hpp"

#include "pluecker/querygen.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim bench [--n N] [--seed S] [--ready P] [--json FILE]\n"
    "Streams N queries (default 2000000; a pool of up to 65536 random queries, set up,\n"
    "quantised and packed before timing, used round-robin) through the RTL as fast as\n"
    "it takes them, first with out_ready held high, then with out_ready high with\n"
    "probability P each cycle (default 0.5). Prints queries per second and compares\n"
    "every answer with the golden model.\n"
    "  --json FILE   also write the results as JSON\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

constexpr std::size_t kPool = 65536;

}  // namespace

int cmd_bench(const std::vector<std::string>& argv) {
    const app::Args args(argv, {"n", "seed", "ready", "json", "mode", "coord-bits", "dir-bits"}, {"help"});
    if (args.has("help")) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    check_build_options(args);
    if (!args.positional().empty()) throw InputError("unexpected argument '" + args.positional()[0] + "'");
    const auto n = static_cast<std::size_t>(args.get_int("n", 2'000'000, 1, 1'000'000'000'000l));
    const auto seed = static_cast<std::uint64_t>(args.get_int("seed", 1, 0, 0x7fffffffffffffffl));
    const double p = args.get_double("ready", 0.5);
    if (!(p > 0.0 && p <= 1.0)) throw InputError("option --ready: " + args.get("ready", "") + " is outside (0, 1]");

    const FixedFormat fmt = built_format();
    const std::vector<Query> qs = random_queries(seed, std::min(n, kPool));
    std::vector<PackedQuery> packed(qs.size());
    std::vector<std::uint8_t> expect(qs.size());
    std::size_t hits = 0;
    for (std::size_t i = 0; i < qs.size(); ++i) {
        const FixedRay r = *fixed_setup_ray(qs[i].ray, fmt);  // random_queries start inside the range
        const FixedBox b = fixed_quantize_box(qs[i].box, fmt);
        packed[i] = pack_query(r, b);
        expect[i] = fixed_hit(r, b, fmt) ? 1 : 0;
        hits += expect[i];
    }

    std::vector<BenchPass> passes = {{"out_ready high", 1.0}, {"random backpressure", p}};
    std::uint64_t mismatches = 0;
    std::printf("bench %s, TAG_BITS %d: %zu queries (pool of %zu, %.1f%% hits)\n", build_name().c_str(),
                SIM_TAG_BITS, n, qs.size(), 100.0 * static_cast<double>(hits) / static_cast<double>(qs.size()));
    for (BenchPass& pass : passes) {
        run_bench_pass<RtlIntersector>(pass, n, packed, expect, seed);
        mismatches += pass.mismatches;
        print_bench_pass(pass);
    }

    if (args.has("json")) {
        const std::string path = args.get("json", "");
        std::ofstream out(path);
        if (!out) throw InputError(path + ": cannot create (" + std::strerror(errno) + ")");
        const FixedFormat f = built_format();
        write_bench_json(out,
                         "\"coord_bits\": " + std::to_string(f.coord_bits) + ",\n  \"dir_bits\": " +
                             std::to_string(f.dir_bits) + ",\n  \"mode\": \"" + mode_name(f.mode) +
                             "\",\n  \"tag_bits\": " + std::to_string(SIM_TAG_BITS),
                         passes);
        if (!out) throw InputError(path + ": write error");
    }
    return mismatches == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
