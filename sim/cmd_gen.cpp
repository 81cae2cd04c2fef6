// SPDX-License-Identifier: MIT
// `pluecker_sim gen`: random and extreme queries (querygen.hpp) as a query
// file, for `pluecker_sim query --check` and the cocotb benches.
#include "commands.hpp"
#include "rtl_intersector.hpp"

#include "pluecker/query.hpp"
#include "pluecker/querygen.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim gen [--n N] [--seed S] [--kind random|extreme|mixed|setup] --out FILE\n"
    "Writes N queries (default 10000) of the model's seeded generators (querygen.hpp):\n"
    "  random   origins and boxes in [-1,1]^3, half of the rays aimed near the box\n"
    "  extreme  axis-parallel and near-axis rays, signed zeros, exact edge/corner hits and\n"
    "           their 1-ulp neighbours, flat boxes, ... (every family in turn)\n"
    "  mixed    half of each (default)\n"
    "  setup    rays from anywhere into boxes of this build's COORD_BITS range: far cameras\n"
    "           and lights through box corners and edges, long unnormalised directions\n"
    "           ending on entry faces, the range cube's own edges (setup_queries)\n"
    "exit status: 0 ok, 2 bad input or options\n";

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
        throw InputError("option --kind: '" + kind + "' is not one of random, extreme, mixed, setup");
    }
    std::ofstream out(path);
    if (!out) throw InputError(path + ": cannot create (" + std::strerror(errno) + ")");
    out << "# pluecker_sim gen --kind " << kind << " --seed " << seed << " --n " << n << "\n";
    for (const Query& q : qs) write_query(out, q);
    out.close();
    if (!out) throw InputError(path + ": write error");
    return 0;
}

}  // namespace pluecker::sim
