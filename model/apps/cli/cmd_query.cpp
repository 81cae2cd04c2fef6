// SPDX-License-Identifier: MIT
// `pluecker query`: answer ray/box queries from a file, one 1/0 a line.
#include "commands.hpp"

#include "pluecker/app/names.hpp"
#include "pluecker/app/render_options.hpp"
#include "pluecker/app/query_file.hpp"

#include "pluecker/boxtest.hpp"
#include "pluecker/f32unit.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/local.hpp"
#include "pluecker/query.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace pluecker::cli {

namespace {

constexpr const char* kQueryUsage =
    "usage: pluecker query --test exact|smits|pluecker|fixed|local|f32-pluecker|f32-pluecker-cons|f32-smits\n"
    "                      [--coord-bits N] [--box-bits K] [--grid-bits G] [--dir-bits M]\n"
    "                      [--mode conservative|nearest] FILE\n"
    "Reads ray/box queries (13 numbers a line: ox oy oz dx dy dz tmax minx miny minz\n"
    "maxx maxy maxz; '#' comments; FILE '-' is standard input) and prints one line\n"
    "per query: 1 = the segment meets the box, 0 = it does not.\n"
    "  --test exact      exact rational arithmetic on the float inputs (the truth)\n"
    "  --test smits      float slab test, inverse direction, per ray class\n"
    "  --test pluecker   float Plücker test (Mahovsky & Wyvill 2004), per ray class\n"
    "  --test f32-pluecker, f32-pluecker-cons, f32-smits\n"
    "                    the binary32 units' bit-exact models (f32unit.hpp: the\n"
    "                    Plücker unit rounding to nearest or outward, the slab unit)\n"
    "  --test fixed      the bit-exact fixed-point datapath of the RTL behind the\n"
    "                    renderer's ray set-up: any finite origin (one outside the\n"
    "                    range cube [-2, 2 - 2^(2-N)]^3 is moved exactly onto it; a\n"
    "                    ray that never meets the cube is a miss); box planes must\n"
    "                    lie in [-2, 2 - 2^(2-N)]\n"
    "  --test local      the bit-exact local-frame datapath: each query's box in the\n"
    "                    tightest frame of its own (K-bit offsets), the ray set up\n"
    "                    on the G-bit global grid as the fixed test's (any finite\n"
    "                    origin) and brought into that frame; box planes must lie\n"
    "                    in [-2, 2) (exactly: the grid's float range)\n"
    "  --coord-bits N    fixed only: coordinate width, 6..24 (default 16)\n"
    "  --box-bits K      local only: box offset width, 4..16 (default 8)\n"
    "  --grid-bits G     local only: global grid width, K+2..48 (default 32)\n"
    "  --dir-bits M      fixed: direction width, 6..24 (default 16); local: 4..24\n"
    "                    (default K + 3)\n"
    "  --mode MODE       fixed and local: conservative (default, never misses) or\n"
    "                    nearest\n"
    "exit status: 0 ok, 2 bad input or options\n";

}  // namespace

int cmd_query(const std::vector<std::string>& argv) {
    const Args args(argv, {"test", "coord-bits", "dir-bits", "mode", "box-bits", "grid-bits"}, {"help"});
    if (args.has("help")) {
        std::fputs(kQueryUsage, stdout);
        return 0;
    }
    if (!args.has("test"))
        throw InputError("missing --test (exact, smits, pluecker, fixed, local, f32-pluecker, f32-pluecker-cons or "
                         "f32-smits)");
    BoxTestKind test;
    try {
        test = parse_box_test(args.get("test", ""));
    } catch (const InputError& e) {
        throw InputError(std::string("option ") + e.what());  // "option --test: ..."
    }
    const bool fixed = test == BoxTestKind::Fixed, local = test == BoxTestKind::Local;
    if (args.has("coord-bits") && !fixed) throw InputError("option --coord-bits needs --test fixed");
    for (const char* opt : {"box-bits", "grid-bits"})
        if (args.has(opt) && !local) throw InputError(std::string("option --") + opt + " needs --test local");
    for (const char* opt : {"dir-bits", "mode"})
        if (args.has(opt) && !fixed && !local)
            throw InputError(std::string("option --") + opt + " needs --test fixed or local");
    FixedMode mode = FixedMode::Conservative;
    if (args.has("mode")) {
        try {
            mode = parse_fixed_mode(args.get("mode", ""));
        } catch (const InputError& e) {
            throw InputError(std::string("option --mode: ") + e.what());
        }
    }
    FixedFormat fmt;
    LocalFormat lfmt;
    if (fixed) {
        fmt.coord_bits = static_cast<int>(args.get_int("coord-bits", FixedFormat::kDefaultCoordBits,
                                                       FixedFormat::kMinBits, FixedFormat::kMaxBits));
        fmt.dir_bits = static_cast<int>(
            args.get_int("dir-bits", FixedFormat::kDefaultDirBits, FixedFormat::kMinBits, FixedFormat::kMaxBits));
        fmt.mode = mode;
        fmt.validate();
    }
    if (local) {
        lfmt = app::parse_local_format(args, mode);
        lfmt.validate();
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
            case BoxTestKind::Local:
                try {
                    hit = local_hit(q.ray, q.box, lfmt);
                } catch (const InputError& e) {
                    throw InputError(source + ":" + std::to_string(lines[i]) + ": " + e.what());
                }
                break;
            case BoxTestKind::F32Pluecker: hit = f32_pluecker_hit(q.ray, q.box, false); break;
            case BoxTestKind::F32PlueckerCons: hit = f32_pluecker_hit(q.ray, q.box, true); break;
            case BoxTestKind::F32Smits: hit = f32_smits_hit(q.ray, q.box); break;
        }
        out += hit ? "1\n" : "0\n";
    }
    if (!out.empty() && std::fwrite(out.data(), 1, out.size(), stdout) != out.size())
        throw std::runtime_error("cannot write the answers to standard output");
    return std::fflush(stdout) == 0 ? 0 : 1;
}

}  // namespace pluecker::cli
