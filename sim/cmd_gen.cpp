// SPDX-License-Identifier: MIT
// `pluecker_sim gen`: the model's seeded generators (querygen.hpp) as a
// query file, or as an operand file (operand_file.hpp) for the kinds that
// are datapath operands, for `pluecker_sim query --check`.
#include "commands.hpp"
#include "rtl_intersector.hpp"

#include "pluecker/app/operand_file.hpp"

#include "pluecker/query.hpp"
#include "pluecker/querygen.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim gen [--n N] [--seed S] [--kind random|extreme|mixed|setup|boundary|ports] --out FILE\n"
    "Writes N queries (default 10000) of the model's seeded generators (querygen.hpp):\n"
    "  random   origins and boxes in [-1,1]^3, half of the rays aimed near the box\n"
    "  extreme  axis-parallel and near-axis rays, signed zeros, exact edge/corner hits and\n"
    "           their 1-ulp neighbours, flat boxes, ... (every family in turn)\n"
    "  mixed    half of each (default)\n"
    "  setup    rays from anywhere into boxes of this build's COORD_BITS range: far cameras\n"
    "           and lights through box corners and edges, long unnormalised directions\n"
    "           ending on entry faces, the range cube's own edges (setup_queries)\n"
    "  boundary datapath operands exactly on a decision boundary of one test (the edge\n"
    "           tests on the margin's bound, the end and origin tests; boundary_queries)\n"
    "  ports    datapath operands from the full port ranges: any coordinates, directions\n"
    "           up to 2^DIR_BITS - 1, boxes with LO > HI (port_range_queries)\n"
    "boundary and ports write an operand file for this build's widths and mode (the\n"
    "header 'operands C D MODE', then 17 integers a line); 'query' reads both kinds\n"
    "exit status: 0 ok, 2 bad input or options\n";

std::ofstream create(const std::string& path) {
    std::ofstream out(path);
    if (!out) throw InputError(path + ": cannot create (" + std::strerror(errno) + ")");
    return out;
}

void finish(std::ofstream& out, const std::string& path) {
    out.close();
    if (!out) throw InputError(path + ": write error");
}

int write_operand_kind(const std::string& kind, std::uint64_t seed, std::size_t n, const std::string& path) {
    const FixedFormat fmt = built_format();
    const std::vector<FixedQuery> qs =
        kind == "boundary" ? boundary_queries(seed, n, fmt) : port_range_queries(seed, n, fmt);
    std::ofstream out = create(path);
    out << "# pluecker_sim gen --kind " << kind << " --seed " << seed << " --n " << n << "\n";
    app::write_operand_header(out, fmt);
    for (const FixedQuery& q : qs) app::write_operands(out, q);
    finish(out, path);
    return 0;
}

}  // namespace

int cmd_gen(const std::vector<std::string>& argv) {
    const app::Args args(argv, {"n", "seed", "kind", "out"}, {"help"});
    if (args.has("help")) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (!args.positional().empty()) throw InputError("unexpected argument '" + args.positional()[0] + "'");
    const auto n = static_cast<std::size_t>(args.get_int("n", 10000, 0, 100'000'000));
    const auto seed = static_cast<std::uint64_t>(args.get_int("seed", 1, 0, 0x7fffffffffffffffl));
    const std::string kind = args.get("kind", "mixed");
    if (!args.has("out")) throw InputError("missing --out FILE");
    const std::string path = args.get("out", "");

    if (kind == "boundary" || kind == "ports") return write_operand_kind(kind, seed, n, path);
    std::vector<Query> qs;
    if (kind == "random") {
        qs = random_queries(seed, n);
    } else if (kind == "extreme") {
        qs = extreme_queries(seed, n);
    } else if (kind == "mixed") {
        qs = random_queries(seed, n / 2);
        const std::vector<Query> ex = extreme_queries(seed, n - n / 2);
        qs.insert(qs.end(), ex.begin(), ex.end());
    } else if (kind == "setup") {
        qs = setup_queries(seed, n, built_format().coord_bits);
    } else {
        throw InputError("option --kind: '" + kind + "' is not one of random, extreme, mixed, setup, boundary, ports");
    }
    std::ofstream out = create(path);
    out << "# pluecker_sim gen --kind " << kind << " --seed " << seed << " --n " << n << "\n";
    for (const Query& q : qs) write_query(out, q);
    finish(out, path);
    return 0;
}

}  // namespace pluecker::sim
