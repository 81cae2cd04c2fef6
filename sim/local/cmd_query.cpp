// SPDX-License-Identifier: MIT
// `pluecker_sim_local query`: the queries of a file through the RTL, each box
// in its tightest frame, one 1/0 a line.
#include "commands.hpp"
#include "local_engine.hpp"

#include "pluecker/app/query_file.hpp"

#include <cstdio>
#include <stdexcept>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim_local query [--check] [--mode M] [--box-bits K] [--dir-bits D] [--grid-bits G] FILE\n"
    "Sets up every query of FILE (the text format of 'pluecker query'; '-' is standard\n"
    "input) with the golden model as 'pluecker query --test local' does: the ray at the\n"
    "global width (any finite origin, one outside the grid's range clipped exactly onto\n"
    "it; a ray that never meets the range is a miss without an RTL query), the box in\n"
    "its tightest frame (local_frame_for). Streams them through the RTL with valid/ready\n"
    "(tag = RTL query index modulo 2^TAG_BITS) and prints the answer per query, in order:\n"
    "1 = hit, 0 = miss. With CHILDREN = 2 each RTL query carries a second box in the same\n"
    "frame: the next query's box when it fits the frame, else the query's own again;\n"
    "its answer is checked, not printed. The options must match the build.\n"
    "  --check   compare every answer with the model (local_hit on local_node_ray);\n"
    "            mismatches on stderr\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

// Mismatches printed in full before the harness only counts them.
constexpr std::size_t kMaxReported = 20;

}  // namespace

int cmd_query(const std::vector<std::string>& argv) {
    const app::Args args(argv, {"mode", "box-bits", "dir-bits", "grid-bits"}, {"check", "help"});
    if (args.has("help")) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    check_build_options(args);
    if (args.positional().size() != 1)
        throw InputError("expected one query FILE ('-' for standard input), got " +
                         std::to_string(args.positional().size()));
    const std::string path = args.positional()[0];
    const std::string source = app::query_source_name(path);
    const LocalFormat fmt = built_local_format();

    std::vector<std::size_t> lines;
    const std::vector<Query> queries = app::read_query_file(path, lines);
    std::vector<TightQuery> set(queries.size());
    for (std::size_t i = 0; i < queries.size(); ++i) {
        try {
            set[i] = tight_query(queries[i], fmt);
        } catch (const InputError& e) {
            throw InputError(source + ":" + std::to_string(lines[i]) + ": " + e.what());
        }
    }
    // The child tests: each query's own (printed), and with two children a
    // partner box in its frame (checked only). partner[i]: the next query's
    // box in query i's frame.
    std::vector<LocalBox> partner(queries.size());
    std::vector<ChildTest> tests;
    std::vector<std::int64_t> own;  // test index of query i's own box, -1: no RTL query
    std::vector<std::size_t> query_of;  // query index of every test
    std::size_t clipped = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
        own.push_back(-1);
        if (!set[i].ray) continue;
        clipped += set[i].ray->clipped;
        own.back() = static_cast<std::int64_t>(tests.size());
        tests.push_back(ChildTest{&*set[i].ray, &set[i].frame, &set[i].box});
        query_of.push_back(i);
        if (kChildren < 2) continue;
        partner[i] = set[i].box;
        if (i + 1 < queries.size()) {
            try {
                partner[i] = local_quantize_box(queries[i + 1].box, set[i].frame, fmt);
            } catch (const InputError&) {
                // does not fit this frame: the query's own box again
            }
        }
        tests.push_back(ChildTest{&*set[i].ray, &set[i].frame, &partner[i]});
        query_of.push_back(i);
    }

    const QueryPlan plan = plan_queries(tests);
    std::vector<std::uint8_t> rtl_hits(plan.packed.size()), hits(tests.size());
    RtlLocal rtl;
    if (!plan.packed.empty()) rtl.run(plan.packed.data(), plan.packed.size(), rtl_hits.data());
    answers_of(plan, rtl_hits, hits);

    std::string out;
    out.reserve(queries.size() * 2);
    for (const std::int64_t t : own) out += t >= 0 && hits[static_cast<std::size_t>(t)] ? "1\n" : "0\n";
    if (!out.empty() && std::fwrite(out.data(), 1, out.size(), stdout) != out.size())
        throw std::runtime_error("cannot write the answers to standard output");
    if (std::fflush(stdout) != 0) throw std::runtime_error("cannot write the answers to standard output");

    if (!args.has("check")) return 0;
    std::size_t mismatches = 0;
    for (std::size_t t = 0; t < tests.size(); ++t) {
        const LocalNodeRay nr = local_node_ray(*tests[t].ray, *tests[t].frame, fmt);
        const bool golden = local_hit(nr, *tests[t].box, fmt);
        if ((hits[t] != 0) == golden) continue;
        const std::size_t q = query_of[t];
        if (++mismatches <= kMaxReported)
            std::fprintf(stderr, "%s:%zu: mismatch%s: RTL %d, model %d\n", source.c_str(), lines[q],
                         static_cast<std::int64_t>(t) == own[q] ? "" : " (partner box)", hits[t] ? 1 : 0,
                         golden ? 1 : 0);
    }
    const StreamStats& st = rtl.stats();
    std::fprintf(stderr,
                 "check (%s): %zu queries (%zu through the RTL, %zu of them clipped onto the grid's range; %zu miss "
                 "the range), %zu child box tests in %zu RTL queries, %zu mismatches, %llu cycles, max %llu in "
                 "flight\n",
                 build_name().c_str(), queries.size(), static_cast<std::size_t>(tests.size() / kChildren), clipped,
                 queries.size() - static_cast<std::size_t>(tests.size() / kChildren), tests.size(),
                 plan.packed.size(), mismatches, static_cast<unsigned long long>(st.cycles),
                 static_cast<unsigned long long>(st.max_in_flight));
    return mismatches == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
