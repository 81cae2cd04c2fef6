// SPDX-License-Identifier: MIT
// The passes of `bench` (both harnesses): a pool of packed queries streamed
// through a fresh RTL unit round-robin until N answers came back, timed by
// the wall clock and by this thread's CPU time (the machine may be shared),
// every answer compared with the model's.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <ostream>
#include <string>
#include <vector>

namespace pluecker::sim {

struct BenchPass {
    std::string name;
    double p_ready;
    std::uint64_t queries = 0, cycles = 0, mismatches = 0;
    double seconds = 0;      // wall clock
    double cpu_seconds = 0;  // this thread's CPU time
    double qps() const { return seconds > 0 ? static_cast<double>(queries) / seconds : 0; }
    double cpu_qps() const { return cpu_seconds > 0 ? static_cast<double>(queries) / cpu_seconds : 0; }
};

inline double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Streams `packed` round-robin through a new Rtl (RtlIntersector, RtlLocal)
// with out_ready_i high with probability pass.p_ready, until n answers came
// back; expect[i] is the model's answer of packed[i] (out_hit_o).
template <class Rtl, class Packed>
void run_bench_pass(BenchPass& pass, std::size_t n, const std::vector<Packed>& packed,
                    const std::vector<std::uint8_t>& expect, std::uint64_t seed) {
    Rtl rtl;
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

inline void print_bench_pass(const BenchPass& pass) {
    std::printf("  %-20s out_ready p=%.2f: %.3f s, %.3f M queries/s (%.3f M per CPU second), %.3f cycles/query, "
                "%llu mismatches\n",
                pass.name.c_str(), pass.p_ready, pass.seconds, pass.qps() / 1e6, pass.cpu_qps() / 1e6,
                static_cast<double>(pass.cycles) / static_cast<double>(pass.queries),
                static_cast<unsigned long long>(pass.mismatches));
    std::fflush(stdout);
}

// The passes as the "passes" member of a JSON object whose other members
// (`head`, e.g. "\"coord_bits\": 16,\n  ...") the caller writes.
inline void write_bench_json(std::ostream& out, const std::string& head, const std::vector<BenchPass>& passes) {
    out << "{\n  " << head << ",\n  \"passes\": [\n";
    for (std::size_t i = 0; i < passes.size(); ++i) {
        const BenchPass& ps = passes[i];
        out << "    {\"name\": \"" << ps.name << "\", \"p_ready\": " << ps.p_ready << ", \"queries\": " << ps.queries
            << ", \"cycles\": " << ps.cycles << ", \"seconds\": " << ps.seconds << ", \"cpu_seconds\": " << ps.cpu_seconds
            << ", \"queries_per_second\": " << ps.qps() << ", \"queries_per_cpu_second\": " << ps.cpu_qps()
            << ", \"mismatches\": " << ps.mismatches << "}" << (i + 1 < passes.size() ? ",\n" : "\n");
    }
    out << "  ]\n}\n";
}

}  // namespace pluecker::sim
