// SPDX-License-Identifier: MIT
// `pluecker_sim bench`: how many queries per second the Verilated RTL
// answers, with out_ready held high and with random backpressure.
#include "commands.hpp"
#include "rtl_intersector.hpp"

#include "pluecker/querygen.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
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

double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Pass {
    std::string name;
    double p_ready;
    std::uint64_t queries = 0, cycles = 0, mismatches = 0;
    double seconds = 0;      // wall clock
    double cpu_seconds = 0;  // this thread's CPU time (the machine may be shared)
    double qps() const { return seconds > 0 ? static_cast<double>(queries) / seconds : 0; }
    double cpu_qps() const { return cpu_seconds > 0 ? static_cast<double>(queries) / cpu_seconds : 0; }
};

void run_pass(Pass& pass, std::size_t n, const std::vector<PackedQuery>& packed,
              const std::vector<std::uint8_t>& expect, std::uint64_t seed) {
    RtlIntersector rtl;
    rtl.set_backpressure(pass.p_ready, seed);
    std::vector<std::uint8_t> hits(packed.size());
    std::size_t done = 0;
    double seconds = 0, cpu = 0;
    while (done < n) {
        const std::size_t k = std::min(packed.size(), n - done);
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = thread_cpu_seconds();
        rtl.run(packed.data(), k, hits.data());
        cpu += thread_cpu_seconds() - c0;
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        for (std::size_t i = 0; i < k; ++i) pass.mismatches += hits[i] != expect[i];
        done += k;
    }
    pass.queries = rtl.stats().queries;
    pass.cycles = rtl.stats().cycles;
    pass.seconds = seconds;
    pass.cpu_seconds = cpu;
}

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

    std::vector<Pass> passes = {{"out_ready high", 1.0}, {"random backpressure", p}};
    std::uint64_t mismatches = 0;
    std::printf("bench %s, TAG_BITS %d: %zu queries (pool of %zu, %.1f%% hits)\n", build_name().c_str(),
                SIM_TAG_BITS, n, qs.size(), 100.0 * static_cast<double>(hits) / static_cast<double>(qs.size()));
    for (Pass& pass : passes) {
        run_pass(pass, n, packed, expect, seed);
        mismatches += pass.mismatches;
        std::printf("  %-20s out_ready p=%.2f: %.3f s, %.3f M queries/s (%.3f M per CPU second), %.3f cycles/query, "
                    "%llu mismatches\n",
                    pass.name.c_str(), pass.p_ready, pass.seconds, pass.qps() / 1e6, pass.cpu_qps() / 1e6,
                    static_cast<double>(pass.cycles) / static_cast<double>(pass.queries),
                    static_cast<unsigned long long>(pass.mismatches));
        std::fflush(stdout);
    }

    if (args.has("json")) {
        const std::string path = args.get("json", "");
        std::ofstream out(path);
        if (!out) throw InputError(path + ": cannot create (" + std::strerror(errno) + ")");
        const FixedFormat f = built_format();
        out << "{\n  \"coord_bits\": " << f.coord_bits << ",\n  \"dir_bits\": " << f.dir_bits << ",\n  \"mode\": \""
            << mode_name(f.mode) << "\",\n  \"tag_bits\": " << SIM_TAG_BITS << ",\n  \"passes\": [\n";
        for (std::size_t i = 0; i < passes.size(); ++i) {
            const Pass& ps = passes[i];
            out << "    {\"name\": \"" << ps.name << "\", \"p_ready\": " << ps.p_ready << ", \"queries\": " << ps.queries
                << ", \"cycles\": " << ps.cycles << ", \"seconds\": " << ps.seconds
                << ", \"cpu_seconds\": " << ps.cpu_seconds << ", \"queries_per_second\": " << ps.qps()
                << ", \"queries_per_cpu_second\": " << ps.cpu_qps() << ", \"mismatches\": " << ps.mismatches << "}"
                << (i + 1 < passes.size() ? ",\n" : "\n");
        }
        out << "  ]\n}\n";
        if (!out) throw InputError(path + ": write error");
    }
    return mismatches == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
