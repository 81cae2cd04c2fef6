// SPDX-License-Identifier: MIT
// `pluecker_sim_cascade check`: generated float queries, each set up in
// both formats by the model, through every lane of the cascade with
// back-pressure on every output stream, idle inputs and resets mid-stream;
// each answer compared with the model's cascade_answer.
#include "cascade_query.hpp"
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
    "usage: pluecker_sim_cascade check [--n N] [--kind K] [--seed S] [--ready P] [--valid P]\n"
    "                                  [--reset-every C]\n"
    "N generated float queries (default 200000, in chunks of 65536), each set up in the\n"
    "narrow and the wide format as the renderer does (a ray that never meets a format's\n"
    "range cube is a miss without an RTL query), spread over the lanes round-robin, every\n"
    "lane driven every clock; each answer is compared with the model's cascade_answer:\n"
    "a certain answer must be the narrow answer of a query the model is sure about, an\n"
    "escalated one the wide test of a query the model finds uncertain (mismatches on\n"
    "stderr, exit 1). Every query is answered exactly once.\n"
    "  --kind K         random | extreme | mixed (half of each, default) | setup (rays from\n"
    "                   anywhere into boxes of the narrow range) | all (every kind, an\n"
    "                   equal share of each chunk)\n"
    "  --ready P        each lane's out_ready_i and esc_ready_i high with probability P  [1]\n"
    "  --valid P        a lane with a query waiting offers it with probability P         [1]\n"
    "  --reset-every C  a reset (rst_i for 1 to 3 cycles) every C cycles on average\n"
    "                   (at least 16): the unanswered queries are dropped, none may be\n"
    "                   answered after it, and they are sent again                  [never]\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

constexpr std::size_t kChunk = 65536;
const std::vector<std::string> kKinds = {"random", "extreme", "setup"};

// The RTL queries of a chunk with the model's answers.
struct Chunk {
    std::vector<CascadeQuery> packed;
    std::vector<CascadeAnswer> expect;
    std::vector<std::string> kind;  // of each query, for messages
    std::size_t missed = 0;         // rays that never meet a range cube: no RTL query
};

// n float queries of a kind, set up in both formats.
void add_float(Chunk& c, const std::string& kind, std::uint64_t seed, std::size_t n, const CascadeFormats& f) {
    const std::vector<Query> qs = kind == "random"    ? random_queries(seed, n)
                                  : kind == "extreme" ? extreme_queries(seed, n)
                                                      : setup_queries(seed, n, f.narrow.coord_bits);
    for (const Query& q : qs) {
        const std::optional<CascadeItem> item = setup_query(q.ray, q.box, f);
        if (!item) {
            ++c.missed;
            continue;
        }
        c.packed.push_back(item->ports);
        c.expect.push_back(item->model);
        c.kind.push_back(kind);
    }
}

std::vector<std::string> kinds_of(const std::string& kind) {
    if (kind == "mixed") return {"random", "extreme"};
    if (kind == "all") return kKinds;
    if (std::find(kKinds.begin(), kKinds.end(), kind) != kKinds.end()) return {kind};
    throw InputError("option --kind: '" + kind + "' is not one of random, extreme, mixed, setup, all");
}

// k queries of the kinds, an equal share each, from the chunk's seed.
Chunk make_chunk(const std::vector<std::string>& kinds, std::uint64_t seed, std::size_t k) {
    const CascadeFormats f = built_formats();
    Chunk c;
    for (std::size_t j = 0; j < kinds.size(); ++j) {
        const std::size_t share = k / kinds.size() + (j < k % kinds.size() ? 1 : 0);
        add_float(c, kinds[j], seed + j, share, f);
    }
    return c;
}

struct Totals {
    std::uint64_t queries = 0, missed = 0, hits = 0, escalated = 0, mismatches = 0;
};

void compare(const Chunk& c, const std::vector<std::uint8_t>& hits, const std::vector<AnswerPath>& paths,
             std::size_t chunk, std::uint64_t seed, Totals& t) {
    for (std::size_t i = 0; i < hits.size(); ++i) {
        t.hits += hits[i];
        t.escalated += paths[i] == AnswerPath::Escalated;
        const char* why = disagreement(c.expect[i], hits[i] != 0, paths[i]);
        if (!why) continue;
        if (++t.mismatches <= 10)
            std::fprintf(stderr,
                         "mismatch: %s query %zu of chunk %zu (seed %llu): %s: RTL %d on the %s stream, model narrow "
                         "%s, cascade %d\n",
                         c.kind[i].c_str(), i, chunk, static_cast<unsigned long long>(seed), why, hits[i],
                         path_name(paths[i]), ternary_name(c.expect[i].narrow), c.expect[i].hit ? 1 : 0);
    }
    t.queries += hits.size();
    t.missed += c.missed;
}

std::string lane_counts(const CascadeRtl& rtl) {
    std::string s;
    for (const CascadeLaneStats& l : rtl.lane_stats())
        s += (s.empty() ? "" : " ") + std::to_string(l.certain + l.escalated);
    return s;
}

std::uint64_t dropped(const CascadeRtl& rtl) {
    std::uint64_t d = 0;
    for (const CascadeLaneStats& l : rtl.lane_stats()) d += l.dropped;
    return d;
}

void print_totals(const Totals& t, const std::string& kind, const CascadeRtl& rtl, double seconds) {
    const auto share = [&](std::uint64_t v) {
        return t.queries ? 100.0 * static_cast<double>(v) / static_cast<double>(t.queries) : 0.0;
    };
    std::printf("check (%s): %llu %s queries through %d %s (%s a lane), %llu missed a range cube, "
                "%llu escalated (%.3f %%), %llu hits, %llu mismatches, %llu cycles (%.2f queries a cycle), "
                "%llu resets (%llu queries dropped and sent again), %.2f s\n",
                build_name().c_str(), static_cast<unsigned long long>(t.queries), kind.c_str(), kLanes,
                kLanes == 1 ? "lane" : "lanes", lane_counts(rtl).c_str(), static_cast<unsigned long long>(t.missed),
                static_cast<unsigned long long>(t.escalated), share(t.escalated),
                static_cast<unsigned long long>(t.hits), static_cast<unsigned long long>(t.mismatches),
                static_cast<unsigned long long>(rtl.stats().cycles),
                rtl.stats().cycles ? static_cast<double>(t.queries) / static_cast<double>(rtl.stats().cycles) : 0.0,
                static_cast<unsigned long long>(rtl.resets()), static_cast<unsigned long long>(dropped(rtl)), seconds);
}

}  // namespace

int cmd_check(const std::vector<std::string>& argv) {
    const app::Args args(argv, {"n", "kind", "seed", "ready", "valid", "reset-every"}, {"help"});
    if (args.has("help")) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (!args.positional().empty()) throw InputError("unexpected argument '" + args.positional()[0] + "'");
    const auto [n, kind, seed, ready, valid, reset_every] = lane_check_options(args);
    const std::vector<std::string> kinds = kinds_of(kind);

    CascadeRtl rtl;
    configure_stream(rtl, ready, valid, seed);
    rtl.set_resets(reset_every);
    Totals t;
    std::vector<std::uint8_t> hits;
    std::vector<AnswerPath> paths;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t done = 0, chunk = 0; done < n; ++chunk) {
        const std::size_t k = std::min(kChunk, n - done);
        const std::uint64_t chunk_seed = seed * 1000003u + chunk * kKinds.size();
        const Chunk c = make_chunk(kinds, chunk_seed, k);
        hits.assign(c.packed.size(), 0);
        paths.assign(c.packed.size(), AnswerPath::None);
        if (!c.packed.empty()) rtl.run(c.packed.data(), c.packed.size(), hits.data(), paths.data());
        compare(c, hits, paths, chunk, chunk_seed, t);
        done += k;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    print_totals(t, kind, rtl, seconds);
    return t.mismatches == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
