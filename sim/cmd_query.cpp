// SPDX-License-Identifier: MIT
// `pluecker_sim query`: the queries of a file (float queries or datapath
// operands) through the RTL, one 1/0 a line.
#include "commands.hpp"
#include "rtl_intersector.hpp"

#include "pluecker/app/operand_file.hpp"
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
    "An operand file ('pluecker_sim gen --kind boundary|ports': the header 'operands C D\n"
    "MODE' first) holds datapath operands instead, streamed as they are; its widths and\n"
    "mode must be the build's.\n"
    "  --check   compare every answer with the model's fixed_hit; mismatches on stderr\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

// Mismatches printed in full before the harness only counts them.
constexpr std::size_t kMaxReported = 20;

// The queries of a file as the datapath takes them: rays[i] empty for a
// ray that never meets the range cube (a miss without an RTL query).
struct Loaded {
    std::vector<std::optional<FixedRay>> rays;
    std::vector<FixedBox> boxes;
    std::vector<std::size_t> lines;
    std::size_t clipped = 0;
};

// A float query file through the model's set-up (fixed.hpp's range
// contract): any finite origin; a ray that never meets the range cube is a
// miss without an RTL query.
Loaded load_queries(const std::string& path, const FixedFormat& fmt) {
    Loaded l;
    const std::vector<Query> queries = app::read_query_file(path, l.lines);
    const std::string source = app::query_source_name(path);
    l.rays.resize(queries.size());
    l.boxes.resize(queries.size());
    for (std::size_t i = 0; i < queries.size(); ++i) {
        try {
            l.boxes[i] = fixed_quantize_box(queries[i].box, fmt);
            l.rays[i] = fixed_setup_ray(queries[i].ray, fmt);
        } catch (const InputError& e) {
            throw InputError(source + ":" + std::to_string(l.lines[i]) + ": " + e.what());
        }
        if (l.rays[i]) l.clipped += l.rays[i]->clipped;
    }
    return l;
}

// An operand file: every query goes to the RTL as it is.
Loaded load_operands(const std::string& path, const FixedFormat& fmt) {
    Loaded l;
    for (const FixedQuery& q : app::read_operand_file(path, fmt, l.lines)) {
        l.rays.emplace_back(q.ray);
        l.boxes.push_back(q.box);
    }
    return l;
}

void print_answers(const std::vector<std::uint8_t>& hits) {
    std::string out;
    out.reserve(hits.size() * 2);
    for (const std::uint8_t h : hits) out += h ? "1\n" : "0\n";
    if (!out.empty() && std::fwrite(out.data(), 1, out.size(), stdout) != out.size())
        throw std::runtime_error("cannot write the answers to standard output");
    if (std::fflush(stdout) != 0) throw std::runtime_error("cannot write the answers to standard output");
}

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
    const bool operands = app::is_operand_file(path);
    const Loaded l = operands ? load_operands(path, fmt) : load_queries(path, fmt);
    const std::size_t n = l.rays.size();
    std::vector<PackedQuery> packed;
    std::vector<std::size_t> sent;  // query index of every RTL query
    for (std::size_t i = 0; i < n; ++i) {
        if (!l.rays[i]) continue;
        packed.push_back(pack_query(*l.rays[i], l.boxes[i]));
        sent.push_back(i);
    }

    std::vector<std::uint8_t> rtl_hits(packed.size());
    RtlIntersector rtl;
    if (!packed.empty()) rtl.run(packed.data(), packed.size(), rtl_hits.data());
    std::vector<std::uint8_t> hits(n, 0);
    for (std::size_t k = 0; k < sent.size(); ++k) hits[sent[k]] = rtl_hits[k];
    print_answers(hits);

    if (!args.has("check")) return 0;
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const bool golden = l.rays[i] && fixed_hit(*l.rays[i], l.boxes[i], fmt);
        if ((hits[i] != 0) == golden) continue;
        if (++mismatches <= kMaxReported)
            std::fprintf(stderr, "%s:%zu: mismatch: RTL %d, model %d\n", source.c_str(), l.lines[i], hits[i] ? 1 : 0,
                         golden ? 1 : 0);
    }
    const StreamStats& st = rtl.stats();
    std::string what = std::to_string(n) + " operand queries, all through the RTL";
    if (!operands)
        what = std::to_string(n) + " queries (" + std::to_string(packed.size()) + " through the RTL, " +
               std::to_string(l.clipped) + " of them clipped onto the range cube; " +
               std::to_string(n - packed.size()) + " miss the cube)";
    std::fprintf(stderr, "check (%s): %s, %zu mismatches, %llu cycles, max %llu in flight\n", build_name().c_str(),
                 what.c_str(), mismatches, static_cast<unsigned long long>(st.cycles),
                 static_cast<unsigned long long>(st.max_in_flight));
    return mismatches == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
