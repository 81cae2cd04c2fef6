// SPDX-License-Identifier: MIT
// `pluecker_sim query`: the queries of a file through the RTL, one 1/0 a line.
#include "commands.hpp"
#include "rtl_intersector.hpp"

#include "pluecker/app/query_file.hpp"

#include "pluecker/query.hpp"

#include <cstdio>
#include <optional>
#include <stdexcept>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim query [--check] [--mode conservative|nearest] [--coord-bits N] [--dir-bits M] FILE\n"
    "Sets up every query of FILE (the text format of 'pluecker query'; '-' is standard\n"
    "input) with the golden model, as the renderer does: any finite origin, a ray from\n"
    "outside the range cube clipped exactly onto it, a ray that never meets the cube a\n"
    "miss without an RTL query. Streams the others through the RTL with valid/ready\n"
    "(tag = query index modulo 2^TAG_BITS) and prints the answer per query, in order:\n"
    "1 = hit, 0 = miss. --mode/--coord-bits/--dir-bits must match the build.\n"
    "  --check   compare every answer with the model's fixed_hit; mismatches on stderr\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

// Mismatches printed in full before the harness only counts them.
constexpr std::size_t kMaxReported = 20;

}  // namespace

int cmd_query(const std::vector<std::string>& argv) {
    const app::Args args(argv, {"mode", "coord-bits", "dir-bits"}, {"check", "help"});
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
    const FixedFormat fmt = built_format();

    std::vector<std::size_t> lines;
    const std::vector<Query> queries = app::read_query_file(path, lines);
    // The model's set-up (fixed.hpp's range contract): any finite origin;
    // a ray that never meets the range cube is a miss without an RTL query.
    std::vector<std::optional<FixedRay>> rays(queries.size());
    std::vector<FixedBox> boxes(queries.size());
    std::vector<PackedQuery> packed;
    std::vector<std::size_t> sent;  // query index of every RTL query
    std::size_t clipped = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
        try {
            boxes[i] = fixed_quantize_box(queries[i].box, fmt);
            rays[i] = fixed_setup_ray(queries[i].ray, fmt);
        } catch (const InputError& e) {
            throw InputError(source + ":" + std::to_string(lines[i]) + ": " + e.what());
        }
        if (!rays[i]) continue;
        clipped += rays[i]->clipped;
        packed.push_back(pack_query(*rays[i], boxes[i]));
        sent.push_back(i);
    }

    std::vector<std::uint8_t> rtl_hits(packed.size());
    RtlIntersector rtl;
    if (!packed.empty()) rtl.run(packed.data(), packed.size(), rtl_hits.data());
    std::vector<std::uint8_t> hits(queries.size(), 0);
    for (std::size_t k = 0; k < sent.size(); ++k) hits[sent[k]] = rtl_hits[k];

    std::string out;
    out.reserve(queries.size() * 2);
    for (const std::uint8_t h : hits) out += h ? "1\n" : "0\n";
    if (!out.empty() && std::fwrite(out.data(), 1, out.size(), stdout) != out.size())
        throw std::runtime_error("cannot write the answers to standard output");
    if (std::fflush(stdout) != 0) throw std::runtime_error("cannot write the answers to standard output");

    if (!args.has("check")) return 0;
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
        const bool golden = rays[i] && fixed_hit(*rays[i], boxes[i], fmt);
        if ((hits[i] != 0) == golden) continue;
        if (++mismatches <= kMaxReported)
            std::fprintf(stderr, "%s:%zu: mismatch: RTL %d, model %d\n", source.c_str(), lines[i], hits[i] ? 1 : 0,
                         golden ? 1 : 0);
    }
    const StreamStats& st = rtl.stats();
    std::fprintf(stderr,
                 "check (%s): %zu queries (%zu through the RTL, %zu of them clipped onto the range cube; %zu miss "
                 "the cube), %zu mismatches, %llu cycles, max %llu in flight\n",
                 build_name().c_str(), queries.size(), packed.size(), clipped, queries.size() - packed.size(),
                 mismatches, static_cast<unsigned long long>(st.cycles),
                 static_cast<unsigned long long>(st.max_in_flight));
    return mismatches == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
