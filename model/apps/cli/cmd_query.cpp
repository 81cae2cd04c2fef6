// SPDX-License-Identifier: MIT
// `pluecker query`: answer ray/box queries from a file, one 1/0 a line.
#include "commands.hpp"

#include "pluecker/app/names.hpp"
#include "pluecker/app/query_file.hpp"

#include "pluecker/boxtest.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/query.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace pluecker::cli {

namespace {

constexpr const char* kQueryUsage =
    "usage: pluecker query --test exact|smits|pluecker|fixed\n"
    "                      [--coord-bits N] [--dir-bits M] [--mode conservative|nearest] FILE\n"
    "Reads ray/box queries (13 numbers a line: ox oy oz dx dy dz tmax minx miny minz\n"
    "maxx maxy maxz; '#' comments; FILE '-' is standard input) and prints one line\n"
    "per query: 1 = the segment meets the box, 0 = it does not.\n"
    "  --test exact      exact rational arithmetic on the float inputs (the truth)\n"
    "  --test smits      float slab test, inverse direction, per ray class\n"
    "  --test pluecker   float Plücker test (Mahovsky & Wyvill 2004), per ray class\n"
    "  --test fixed      the bit-exact fixed-point datapath of the RTL behind the\n"
    "                    renderer's ray set-up: any finite origin (one outside the\n"
    "                    range cube [-2, 2 - 2^(2-N)]^3 is moved exactly onto it; a\n"
    "                    ray that never meets the cube is a miss); box planes must\n"
    "                    lie in [-2, 2 - 2^(2-N)]\n"
    "  --coord-bits N    fixed only: coordinate width, 6..24 (default 16)\n"
    "  --dir-bits M      fixed only: direction width, 6..24 (default 16)\n"
    "  --mode MODE       fixed only: conservative (default, never misses) or nearest\n"
    "exit status: 0 ok, 2 bad input or options\n";

}  // namespace

int cmd_query(const std::vector<std::string>& argv) {
    const Args args(argv, {"test", "coord-bits", "dir-bits", "mode"}, {"help"});
    if (args.has("help")) {
        std::fputs(kQueryUsage, stdout);
        return 0;
    }
    if (!args.has("test")) throw InputError("missing --test (exact, smits, pluecker or fixed)");
    BoxTestKind test;
    try {
        test = parse_box_test(args.get("test", ""));
    } catch (const InputError& e) {
        throw InputError(std::string("option ") + e.what());  // "option --test: ..."
    }
    FixedFormat fmt;
    if (test == BoxTestKind::Fixed) {
        fmt.coord_bits = static_cast<int>(args.get_int("coord-bits", FixedFormat::kDefaultCoordBits,
                                                       FixedFormat::kMinBits, FixedFormat::kMaxBits));
        fmt.dir_bits = static_cast<int>(
            args.get_int("dir-bits", FixedFormat::kDefaultDirBits, FixedFormat::kMinBits, FixedFormat::kMaxBits));
        if (args.has("mode")) {
            try {
                fmt.mode = parse_fixed_mode(args.get("mode", ""));
            } catch (const InputError& e) {
                throw InputError(std::string("option --mode: ") + e.what());
            }
        }
        fmt.validate();
    } else {
        for (const char* opt : {"coord-bits", "dir-bits", "mode"})
            if (args.has(opt)) throw InputError(std::string("option --") + opt + " needs --test fixed");
    }
    if (args.positional().size() != 1)
        throw InputError("expected one query FILE ('-' for standard input), got " +
                         std::to_string(args.positional().size()));
    const std::string path = args.positional()[0];

    std::vector<std::size_t> lines;
    const std::vector<Query> queries = read_query_file(path, lines);
    const std::string source = query_source_name(path);

    std::string out;
    out.reserve(queries.size() * 2);
    for (std::size_t i = 0; i < queries.size(); ++i) {
        const Query& q = queries[i];
        bool hit = false;
        switch (test) {
            case BoxTestKind::Exact: hit = exact_hit(q.ray, q.box); break;
            case BoxTestKind::Smits: hit = smits_hit(smits_setup(q.ray), q.box); break;
            case BoxTestKind::Pluecker: hit = pluecker_hit(pluecker_setup(q.ray), q.box); break;
            case BoxTestKind::Fixed:
                try {
                    hit = fixed_hit(q.ray, q.box, fmt);
                } catch (const InputError& e) {
                    throw InputError(source + ":" + std::to_string(lines[i]) + ": " + e.what());
                }
                break;
        }
        out += hit ? "1\n" : "0\n";
    }
    if (!out.empty() && std::fwrite(out.data(), 1, out.size(), stdout) != out.size())
        throw std::runtime_error("cannot write the answers to standard output");
    return std::fflush(stdout) == 0 ? 0 : 1;
}

}  // namespace pluecker::cli
