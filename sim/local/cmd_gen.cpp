// SPDX-License-Identifier: MIT
// `pluecker_sim_local gen`: query files for `pluecker_sim_local query`: the
// model's seeded generators (querygen.hpp) and boundary queries.
#include "commands.hpp"
#include "rtl_local.hpp"

#include "pluecker/querygen.hpp"
#include "pluecker/rng.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim_local gen [--n N] [--seed S] [--kind K] --out FILE\n"
    "Writes N queries (default 10000); `query` tests each box in its tightest frame:\n"
    "  random    origins and boxes in [-1,1]^3, half of the rays aimed near the box\n"
    "  extreme   axis-parallel and near-axis rays, signed zeros, exact edge/corner hits and\n"
    "            their 1-ulp neighbours, flat and tiny boxes, ... (every family in turn)\n"
    "  mixed     half random, half extreme (default)\n"
    "  setup     rays from anywhere (far cameras and lights through box corners and edges,\n"
    "            long unnormalised directions ending on entry faces, the range's edges) into\n"
    "            boxes of this build's range (setup_queries)\n"
    "  boundary  rays through a corner, an edge or a face point of a random box (boxes of\n"
    "            every size down to flat), from near and far, with the box planes as they\n"
    "            are or moved one float ulp in or out, segments ending on the point\n"
    "exit status: 0 ok, 2 bad input or options\n";

// A point of box b on a corner, an edge or a face (the others' coordinates
// inside), picked by `where`: 0 corner, 1 edge, 2 face.
Vec3 boundary_point(Rng& g, const Box& b, int where) {
    Vec3 p;
    const int free_axes = where;  // coordinates left inside the box
    int axes[3] = {0, 1, 2};
    for (int k = 2; k > 0; --k) std::swap(axes[k], axes[g.below(static_cast<std::uint32_t>(k + 1))]);
    for (int k = 0; k < 3; ++k) {
        const int a = axes[k];
        p[a] = k < free_axes ? b.lo[a] + g.unit() * (b.hi[a] - b.lo[a]) : (g.coin() ? b.lo[a] : b.hi[a]);
    }
    return p;
}

std::vector<Query> boundary_queries(std::uint64_t seed, std::size_t n) {
    Rng g(seed);
    std::vector<Query> out;
    out.reserve(n);
    const float sizes[] = {1.0f, 0.1f, 1e-3f, 1e-6f, 0.0f};
    while (out.size() < n) {
        Box b;
        for (int a = 0; a < 3; ++a) {
            const float s = sizes[g.below(5)] * g.unit();
            const float lo = 0.9f * g.sym();
            b.lo[a] = lo;
            b.hi[a] = lo + s;
        }
        const Vec3 p = boundary_point(g, b, static_cast<int>(g.below(3)));
        const float dist = g.coin() ? 0.5f : (g.coin() ? 3.0f : 1e3f);
        Vec3 o;
        for (int a = 0; a < 3; ++a) o[a] = p[a] + dist * g.sym();
        Vec3 d = p - o;
        if (d.x == 0.0f && d.y == 0.0f && d.z == 0.0f) continue;
        // Planes moved by one ulp: in or out of the box.
        if (g.below(3) == 0) {
            const int a = static_cast<int>(g.below(3));
            const float inf = std::numeric_limits<float>::infinity();
            if (g.coin()) b.lo[a] = std::nextafter(b.lo[a], g.coin() ? -inf : b.hi[a]);
            else b.hi[a] = std::nextafter(b.hi[a], g.coin() ? inf : b.lo[a]);
        }
        const float tmax = g.below(3) == 0 ? 1.0f : std::numeric_limits<float>::infinity();
        out.push_back(Query{Ray{o, d, tmax}, b});
    }
    return out;
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
        // Boxes inside the range of a fixed-point width that fits this grid.
        const int bits = std::clamp(built_local_format().grid_bits, FixedFormat::kMinBits, FixedFormat::kMaxBits);
        qs = setup_queries(seed, n, bits);
    } else if (kind == "boundary") {
        qs = boundary_queries(seed, n);
    } else {
        throw InputError("option --kind: '" + kind + "' is not one of random, extreme, mixed, setup, boundary");
    }
    std::ofstream out(path);
    if (!out) throw InputError(path + ": cannot create (" + std::strerror(errno) + ")");
    out << "# pluecker_sim_local gen --kind " << kind << " --seed " << seed << " --n " << n << "\n";
    for (const Query& q : qs) write_query(out, q);
    out.close();
    if (!out) throw InputError(path + ": write error");
    return 0;
}

}  // namespace pluecker::sim
