// SPDX-License-Identifier: MIT
// `pluecker_sim` built for a binary32 unit (SIM_UNIT float or smits): the
// Verilator harness of rtl/pluecker_float_intersector.sv or
// rtl/pluecker_smits_intersector.sv, linked with the golden model.
//
//   query [--check] FILE   the queries of a file through the unit
//   check [--n N] [--kind K] [--seed S] [--ready P] [--exact]
//                          N generated queries through the unit, every answer
//                          against the model (and, with --exact, against
//                          exact_hit: false misses and false hits)
//   bench [--n N] [--ready P]   queries per second
//   render [options of 'pluecker render']   hardware-in-the-loop render
//                          (cmd_render.cpp)
// Exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input.
#include "float_rtl.hpp"
#include "harness_main.hpp"

#include "pluecker/app/args.hpp"
#include "pluecker/app/query_file.hpp"

#include "pluecker/boxtest.hpp"
#include "pluecker/querygen.hpp"
#include "pluecker/rng.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <exception>
#include <string>
#include <vector>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim <command> [options]\n"
    "  the Verilator model of a binary32 unit, driven through the golden model\n"
    "commands:\n"
    "  query [--check] FILE    the queries of FILE (the text format of 'pluecker query';\n"
    "                          '-' is stdin) set up for the unit (f32unit.hpp), streamed\n"
    "                          through the RTL; one 1/0 a line. --check compares each\n"
    "                          answer with the model (mismatches on stderr, exit 1)\n"
    "  check [--n N] [--kind random|extreme|raw|tiny|mixed] [--seed S] [--ready P] [--exact]\n"
    "                          N generated queries (default 1000000, in chunks) through the\n"
    "                          RTL, every answer against the model; raw: bit patterns over\n"
    "                          the whole port range (NaN, inf, subnormals, signed zeros);\n"
    "                          tiny: operands around 2^-126; --exact also counts false\n"
    "                          misses and false hits against exact_hit (random, extreme)\n"
    "  bench [--n N] [--ready P]  queries per second (out_ready high, then with probability P)\n"
    "  render [options of 'pluecker render']   the scene rendered with every box query\n"
    "                          answered by the RTL and checked against the model; the image\n"
    "                          equals 'pluecker render --test <this unit>' ('render --help')\n";

constexpr std::size_t kChunk = 65536;

double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// --- raw bit patterns (stimulus only: the model computes every answer) -------

constexpr f32::Bits kSpecials[] = {0x00000000, 0x80000000, 0x00000001, 0x80000001, 0x007fffff, 0x807fffff,
                                   0x00400000, 0x00800000, 0x80800000, 0x00800001, 0x00ffffff, 0x3f800000,
                                   0xbf800000, 0x3f7fffff, 0x7f7fffff, 0xff7fffff, 0x7f800000, 0xff800000,
                                   0x7fc00000, 0xffc00000, 0x7f800001, 0x7fbfffff, 0xffffffff};

f32::Bits pattern(Rng& g, const f32::Bits* near, bool tiny) {
    const float r = g.unit();
    const auto sign = static_cast<f32::Bits>(g.coin()) << 31;
    const auto frac = static_cast<f32::Bits>(g.next() & 0x7fffffu);
    if (tiny) {
        if (r < 0.15f) return kSpecials[g.below(11)];
        if (near && r < 0.5f) return *near + g.below(7) - 3;
        return sign | (g.below(9) << 23) | frac;
    }
    if (r < 0.25f) return kSpecials[g.below(sizeof kSpecials / sizeof kSpecials[0])];
    if (near && r < 0.45f) return *near + g.below(9) - 4;
    if (r < 0.6f) return static_cast<f32::Bits>(g.next());
    return sign | ((110 + g.below(21)) << 23) | frac;
}

UnitQuery raw_query(Rng& g, bool tiny) {
    UnitQuery q;
    q.cls = static_cast<RayClass>(g.below(8));
    for (std::size_t a = 0; a < 3; ++a) {
        q.org[a] = pattern(g, nullptr, tiny);
        q.lo[a] = pattern(g, &q.org[a], tiny);
        q.hi[a] = pattern(g, g.coin() ? &q.lo[a] : &q.org[a], tiny);
    }
#if SIM_FLOAT_UNIT == 0
    for (std::size_t a = 0; a < 3; ++a) {
        q.dir[a] = pattern(g, nullptr, tiny);
        q.end[a] = pattern(g, g.coin() ? &q.hi[a] : &q.lo[a], tiny);
    }
    q.has_end = g.coin();
#else
    for (std::size_t a = 0; a < 3; ++a) q.inv[a] = pattern(g, nullptr, tiny);
    q.tmax = pattern(g, nullptr, tiny);
#endif
    return q;
}

// --- commands ---------------------------------------------------------------------

int cmd_query(const std::vector<std::string>& argv) {
    const app::Args args(argv, {}, {"check"});
    if (args.positional().size() != 1)
        throw InputError("expected one query FILE ('-' for standard input), got " +
                         std::to_string(args.positional().size()));
    const std::string path = args.positional()[0];
    std::vector<std::size_t> lines;
    const std::vector<Query> queries = app::read_query_file(path, lines);
    std::vector<UnitQuery> uq(queries.size());
    std::vector<PackedQuery> packed(queries.size());
    for (std::size_t i = 0; i < queries.size(); ++i) {
        uq[i] = setup_query(queries[i]);
        packed[i] = pack(uq[i]);
    }
    std::vector<std::uint8_t> hits(queries.size());
    FloatRtl rtl;
    if (!packed.empty()) rtl.run(packed.data(), packed.size(), hits.data());
    std::string out;
    out.reserve(hits.size() * 2);
    for (std::uint8_t h : hits) out += h ? "1\n" : "0\n";
    std::fwrite(out.data(), 1, out.size(), stdout);
    std::fflush(stdout);
    if (!args.has("check")) return 0;
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
        if ((hits[i] != 0) == model_hit(uq[i])) continue;
        if (++mismatches <= 20)
            std::fprintf(stderr, "%s:%zu: mismatch: RTL %d, model %d\n", app::query_source_name(path).c_str(), lines[i],
                         hits[i], hits[i] ? 0 : 1);
    }
    std::fprintf(stderr, "check (%s): %zu queries, %zu mismatches, %llu cycles, max %llu in flight\n",
                 build_name().c_str(), queries.size(), mismatches,
                 static_cast<unsigned long long>(rtl.stats().cycles),
                 static_cast<unsigned long long>(rtl.stats().max_in_flight));
    return mismatches == 0 ? 0 : 1;
}

// n queries of a kind, generated chunk by chunk from `seed`.
std::vector<Query> float_queries(const std::string& kind, std::uint64_t seed, std::size_t n) {
    if (kind == "random") return random_queries(seed, n);
    if (kind == "extreme") return extreme_queries(seed, n);
    std::vector<Query> q = random_queries(seed, n / 2);
    const std::vector<Query> e = extreme_queries(seed, n - n / 2);
    q.insert(q.end(), e.begin(), e.end());
    return q;
}

int cmd_check(const std::vector<std::string>& argv) {
    const app::Args args(argv, {"n", "kind", "seed", "ready"}, {"exact"});
    if (!args.positional().empty()) throw InputError("unexpected argument '" + args.positional()[0] + "'");
    const auto n = static_cast<std::size_t>(args.get_int("n", 1'000'000, 1, 10'000'000'000l));
    const std::string kind = args.get("kind", "mixed");
    const auto seed = static_cast<std::uint64_t>(args.get_int("seed", 1, 0, 0x7fffffffffffffffl));
    const double p = args.get_double("ready", 1.0);
    if (!(p > 0.0 && p <= 1.0)) throw InputError("option --ready: " + args.get("ready", "") + " is outside (0, 1]");
    const bool raw = kind == "raw" || kind == "tiny";
    if (!raw && kind != "random" && kind != "extreme" && kind != "mixed")
        throw InputError("option --kind: '" + kind + "' is not one of random, extreme, raw, tiny, mixed");
    const bool exact = args.has("exact");
    if (exact && raw) throw InputError("option --exact: raw and tiny patterns are not queries of exact_hit");

    FloatRtl rtl;
    rtl.set_backpressure(p, seed);
    Rng g(seed);
    std::uint64_t mismatches = 0, hits_total = 0, real = 0, false_misses = 0, false_hits = 0;
    std::vector<UnitQuery> uq;
    std::vector<PackedQuery> packed;
    std::vector<std::uint8_t> hits;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t done = 0, chunk = 0; done < n; ++chunk) {
        const std::size_t k = std::min(kChunk, n - done);
        std::vector<Query> fq;
        if (raw) {
            uq.resize(k);
            for (std::size_t i = 0; i < k; ++i) uq[i] = raw_query(g, kind == "tiny");
        } else {
            fq = float_queries(kind, seed * 1000003u + chunk, k);
            uq.resize(k);
            for (std::size_t i = 0; i < k; ++i) uq[i] = setup_query(fq[i]);
        }
        packed.resize(k);
        hits.resize(k);
        for (std::size_t i = 0; i < k; ++i) packed[i] = pack(uq[i]);
        rtl.run(packed.data(), k, hits.data());
        for (std::size_t i = 0; i < k; ++i) {
            const bool h = hits[i] != 0;
            hits_total += h;
            if (h != model_hit(uq[i]) && ++mismatches <= 10)
                std::fprintf(stderr, "mismatch: %s query %zu of chunk %zu (seed %llu): RTL %d\n", kind.c_str(), i,
                             chunk, static_cast<unsigned long long>(seed), h ? 1 : 0);
            if (exact) {
                const bool e = exact_hit(fq[i].ray, fq[i].box);
                real += e;
                false_misses += e && !h;
                false_hits += !e && h;
            }
        }
        done += k;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("check (%s): %zu %s queries, %llu hits, %llu mismatches, %llu cycles, %.1f s", build_name().c_str(), n,
                kind.c_str(), static_cast<unsigned long long>(hits_total), static_cast<unsigned long long>(mismatches),
                static_cast<unsigned long long>(rtl.stats().cycles), seconds);
    if (exact)
        std::printf("; against exact: %llu real hits, %llu false misses, %llu false hits",
                    static_cast<unsigned long long>(real), static_cast<unsigned long long>(false_misses),
                    static_cast<unsigned long long>(false_hits));
    std::printf("\n");
    return mismatches == 0 ? 0 : 1;
}

int cmd_bench(const std::vector<std::string>& argv) {
    const app::Args args(argv, {"n", "ready", "seed"}, {});
    if (!args.positional().empty()) throw InputError("unexpected argument '" + args.positional()[0] + "'");
    const auto n = static_cast<std::size_t>(args.get_int("n", 2'000'000, 1, 1'000'000'000'000l));
    const auto seed = static_cast<std::uint64_t>(args.get_int("seed", 1, 0, 0x7fffffffffffffffl));
    const double p = args.get_double("ready", 0.5);
    if (!(p > 0.0 && p <= 1.0)) throw InputError("option --ready: " + args.get("ready", "") + " is outside (0, 1]");
    const std::vector<Query> qs = random_queries(seed, std::min(n, kChunk));
    std::vector<PackedQuery> packed(qs.size());
    std::vector<std::uint8_t> expect(qs.size()), hits(qs.size());
    for (std::size_t i = 0; i < qs.size(); ++i) {
        const UnitQuery q = setup_query(qs[i]);
        packed[i] = pack(q);
        expect[i] = model_hit(q) ? 1 : 0;
    }
    std::uint64_t mismatches = 0;
    std::printf("bench %s, TAG_BITS %d: %zu queries (pool of %zu)\n", build_name().c_str(), SIM_TAG_BITS, n, qs.size());
    for (const double pr : {1.0, p}) {
        FloatRtl rtl;
        rtl.set_backpressure(pr, seed);
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = thread_cpu_seconds();
        for (std::size_t done = 0; done < n;) {
            const std::size_t k = std::min(packed.size(), n - done);
            rtl.run(packed.data(), k, hits.data());
            for (std::size_t i = 0; i < k; ++i) mismatches += hits[i] != expect[i];
            done += k;
        }
        const double cpu = thread_cpu_seconds() - c0;
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::printf("  out_ready p=%.2f: %.3f s, %.3f M queries/s (%.3f M per CPU second), %.3f cycles/query\n", pr,
                    wall, static_cast<double>(n) / wall / 1e6, static_cast<double>(n) / cpu / 1e6,
                    static_cast<double>(rtl.stats().cycles) / static_cast<double>(n));
    }
    std::printf("  %llu mismatches\n", static_cast<unsigned long long>(mismatches));
    return mismatches == 0 ? 0 : 1;
}

}  // namespace
}  // namespace pluecker::sim

int main(int argc, char** argv) {
    using namespace pluecker::sim;
    return harness_main(argc, argv, "pluecker_sim", kUsage,
                        build_name() + ", TAG_BITS " + std::to_string(SIM_TAG_BITS),
                        {{"query", cmd_query}, {"check", cmd_check}, {"bench", cmd_bench}, {"render", cmd_render}});
}
