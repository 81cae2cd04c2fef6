// SPDX-License-Identifier: MIT
// `pluecker_sim_local bench`: how many queries per second the Verilated local
// unit answers, with out_ready held high and with random backpressure.
#include "bench_pass.hpp"
#include "commands.hpp"
#include "local_engine.hpp"

#include "pluecker/querygen.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim_local bench [--n N] [--seed S] [--ready P] [--json FILE]\n"
    "Streams N queries (default 2000000; a pool of up to 65536 random queries, each box in\n"
    "its tightest frame, with CHILDREN = 2 the next query's box in the same frame when it\n"
    "fits, set up and packed before timing, used round-robin) through the RTL as fast as\n"
    "it takes them, first with out_ready held high, then with out_ready high with\n"
    "probability P each cycle (default 0.5). Prints queries per second and compares every\n"
    "answer with the golden model.\n"
    "  --json FILE   also write the results as JSON\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

constexpr std::size_t kPool = 65536;

}  // namespace

int cmd_bench(const std::vector<std::string>& argv) {
    const app::Args args(argv, {"n", "seed", "ready", "json", "mode", "box-bits", "dir-bits", "grid-bits"}, {"help"});
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

    const LocalFormat fmt = built_local_format();
    const std::vector<Query> qs = random_queries(seed, std::min(n, kPool));
    std::vector<PackedLocalQuery> packed;
    std::vector<std::uint8_t> expect;
    std::size_t hits = 0;
    for (std::size_t i = 0; i < qs.size(); ++i) {
        const TightQuery t = tight_query(qs[i], fmt);
        if (!t.ray) continue;
        std::array<LocalBox, kChildren> boxes;
        boxes.fill(t.box);
        if (kChildren == 2 && i + 1 < qs.size()) {
            try {
                boxes.back() = local_quantize_box(qs[i + 1].box, t.frame, fmt);
            } catch (const InputError&) {
                // does not fit this frame: the query's own box twice
            }
        }
        const LocalNodeRay nr = local_node_ray(*t.ray, t.frame, fmt);
        std::uint8_t want = 0;
        for (int c = 0; c < kChildren; ++c) want |= static_cast<std::uint8_t>(local_hit(nr, boxes[c], fmt)) << c;
        packed.push_back(pack_local(*t.ray, t.frame, boxes));
        expect.push_back(want);
        hits += static_cast<std::size_t>(__builtin_popcount(want));
    }
    if (packed.empty()) throw InputError("no query of the pool reaches the RTL");

    std::vector<BenchPass> passes = {{"out_ready high", 1.0}, {"random backpressure", p}};
    std::uint64_t mismatches = 0;
    std::printf("bench %s, TAG_BITS %d: %zu queries (pool of %zu, %.1f%% of the box tests hit)\n",
                build_name().c_str(), SIM_TAG_BITS, n, packed.size(),
                100.0 * static_cast<double>(hits) / static_cast<double>(packed.size() * kChildren));
    for (BenchPass& pass : passes) {
        run_bench_pass<RtlLocal>(pass, n, packed, expect, seed);
        mismatches += pass.mismatches;
        print_bench_pass(pass);
    }

    if (args.has("json")) {
        const std::string path = args.get("json", "");
        std::ofstream out(path);
        if (!out) throw InputError(path + ": cannot create (" + std::strerror(errno) + ")");
        const LocalRtlConfig c = built_local_config();
        write_bench_json(out,
                         "\"box_bits\": " + std::to_string(c.box_bits) + ",\n  \"dir_bits\": " +
                             std::to_string(c.dir_bits) + ",\n  \"grid_bits\": " + std::to_string(c.grid_bits) +
                             ",\n  \"children\": " + std::to_string(c.children) + ",\n  \"mode\": \"" +
                             (c.conservative ? "conservative" : "nearest") + "\",\n  \"tag_bits\": " +
                             std::to_string(SIM_TAG_BITS),
                         passes);
        if (!out) throw InputError(path + ": write error");
    }
    return mismatches == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
