// SPDX-License-Identifier: MIT
// `pluecker_sim_array check`: generated queries through every lane of the
// array, with back-pressure, idle inputs and resets mid-stream, each answer
// compared with the model's fixed_hit on the same operands.
#include "commands.hpp"

#include "pluecker/querygen.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim_array check [--n N] [--kind K] [--seed S] [--ready P] [--valid P]\n"
    "                                [--reset-every C]\n"
    "N generated queries (default 200000, in chunks of 65536) spread over the lanes\n"
    "round-robin, every lane driven every clock; each answer is compared with the\n"
    "model's fixed_hit on the same operands (mismatches on stderr, exit 1).\n"
    "  --kind K         random | extreme | mixed (half of each, default) | setup (rays from\n"
    "                   anywhere, set up as the renderer does) | boundary (operands on a\n"
    "                   decision boundary) | ports (operands over the full port ranges) |\n"
    "                   all (every kind, an equal share of each chunk)\n"
    "  --ready P        each lane's out_ready_i high with probability P a cycle      [1]\n"
    "  --valid P        a lane with a query waiting offers it with probability P     [1]\n"
    "  --reset-every C  a reset (rst_i for 1 to 3 cycles) every C cycles on average\n"
    "                   (at least 16): the queries in flight are dropped, none may be\n"
    "                   answered after it, and they are sent again              [never]\n"
    "  --mode, --coord-bits, --dir-bits  must match the build\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

constexpr std::size_t kChunk = 65536;
const std::vector<std::string> kKinds = {"random", "extreme", "setup", "boundary", "ports"};

// Queries in the array's port encoding with the model's answers.
struct Chunk {
    std::vector<LaneQuery> packed;
    std::vector<std::uint8_t> expect;
    std::vector<std::string> kind;  // of each query, for messages
    std::size_t missed = 0;         // rays that never meet the range cube: no RTL query
};

void add(Chunk& c, const FixedRay& r, const FixedBox& b, const std::string& kind, const FixedFormat& f) {
    c.packed.push_back(pack_lane_query(r, b));
    c.expect.push_back(fixed_hit(r, b, f) ? 1 : 0);
    c.kind.push_back(kind);
}

// n float queries of a kind, set up as the renderer does (fixed.hpp).
void add_float(Chunk& c, const std::string& kind, std::uint64_t seed, std::size_t n, const FixedFormat& f) {
    const std::vector<Query> qs = kind == "random"    ? random_queries(seed, n)
                                  : kind == "extreme" ? extreme_queries(seed, n)
                                                      : setup_queries(seed, n, f.coord_bits);
    for (const Query& q : qs) {
        const FixedBox b = fixed_quantize_box(q.box, f);
        const std::optional<FixedRay> r = fixed_setup_ray(q.ray, f);
        if (r) add(c, *r, b, kind, f);
        else ++c.missed;
    }
}

// n datapath operands of a kind (boundary, ports), as they are.
void add_operands(Chunk& c, const std::string& kind, std::uint64_t seed, std::size_t n, const FixedFormat& f) {
    const std::vector<FixedQuery> qs =
        kind == "boundary" ? boundary_queries(seed, n, f) : port_range_queries(seed, n, f);
    for (const FixedQuery& q : qs) add(c, q.ray, q.box, kind, f);
}

std::vector<std::string> kinds_of(const std::string& kind) {
    if (kind == "mixed") return {"random", "extreme"};
    if (kind == "all") return kKinds;
    if (std::find(kKinds.begin(), kKinds.end(), kind) != kKinds.end()) return {kind};
    throw InputError("option --kind: '" + kind + "' is not one of random, extreme, mixed, setup, boundary, ports, all");
}

// k queries of the kinds, an equal share each, from the chunk's seed.
Chunk make_chunk(const std::vector<std::string>& kinds, std::uint64_t seed, std::size_t k) {
    const FixedFormat f = built_format();
    Chunk c;
    for (std::size_t j = 0; j < kinds.size(); ++j) {
        const std::size_t share = k / kinds.size() + (j < k % kinds.size() ? 1 : 0);
        const bool operands = kinds[j] == "boundary" || kinds[j] == "ports";
        if (operands) add_operands(c, kinds[j], seed + j, share, f);
        else add_float(c, kinds[j], seed + j, share, f);
    }
    return c;
}

struct Totals {
    std::uint64_t queries = 0, missed = 0, hits = 0, mismatches = 0;
};

void compare(const Chunk& c, const std::vector<std::uint8_t>& hits, std::size_t chunk, std::uint64_t seed, Totals& t) {
    for (std::size_t i = 0; i < hits.size(); ++i) {
        t.hits += hits[i];
        if (hits[i] == c.expect[i]) continue;
        if (++t.mismatches <= 10)
            std::fprintf(stderr, "mismatch: %s query %zu of chunk %zu (seed %llu): RTL %d, model %d\n",
                         c.kind[i].c_str(), i, chunk, static_cast<unsigned long long>(seed), hits[i], c.expect[i]);
    }
    t.queries += hits.size();
    t.missed += c.missed;
}

std::string lane_counts(const ArrayRtl& rtl) {
    std::string s;
    for (const LaneStats& l : rtl.lane_stats()) s += (s.empty() ? "" : " ") + std::to_string(l.queries);
    return s;
}

std::uint64_t dropped(const ArrayRtl& rtl) {
    std::uint64_t d = 0;
    for (const LaneStats& l : rtl.lane_stats()) d += l.dropped;
    return d;
}

void print_totals(const Totals& t, const std::string& kind, const ArrayRtl& rtl, double seconds) {
    std::printf("check (%s): %llu %s queries through %d lanes (%s a lane), %llu missed the range cube, %llu hits, "
                "%llu mismatches, %llu cycles (%.2f queries a cycle), %llu resets (%llu queries dropped and sent "
                "again), %.2f s\n",
                build_name().c_str(), static_cast<unsigned long long>(t.queries), kind.c_str(), kLanes,
                lane_counts(rtl).c_str(), static_cast<unsigned long long>(t.missed),
                static_cast<unsigned long long>(t.hits), static_cast<unsigned long long>(t.mismatches),
                static_cast<unsigned long long>(rtl.stats().cycles),
                rtl.stats().cycles ? static_cast<double>(t.queries) / static_cast<double>(rtl.stats().cycles) : 0.0,
                static_cast<unsigned long long>(rtl.resets()), static_cast<unsigned long long>(dropped(rtl)), seconds);
}

}  // namespace

int cmd_check(const std::vector<std::string>& argv) {
    const app::Args args(argv, {"n", "kind", "seed", "ready", "valid", "reset-every", "mode", "coord-bits", "dir-bits"},
                         {"help"});
    if (args.has("help")) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    check_build_options(args);
    if (!args.positional().empty()) throw InputError("unexpected argument '" + args.positional()[0] + "'");
    const auto [n, kind, seed, ready, valid, reset_every] = lane_check_options(args);
    const std::vector<std::string> kinds = kinds_of(kind);

    ArrayRtl rtl;
    configure_stream(rtl, ready, valid, seed);
    rtl.set_resets(reset_every);
    Totals t;
    std::vector<std::uint8_t> hits;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t done = 0, chunk = 0; done < n; ++chunk) {
        const std::size_t k = std::min(kChunk, n - done);
        const std::uint64_t chunk_seed = seed * 1000003u + chunk * kKinds.size();
        const Chunk c = make_chunk(kinds, chunk_seed, k);
        hits.assign(c.packed.size(), 0);
        if (!c.packed.empty()) rtl.run(c.packed.data(), c.packed.size(), hits.data());
        compare(c, hits, chunk, chunk_seed, t);
        done += k;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    print_totals(t, kind, rtl, seconds);
    return t.mismatches == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
