// SPDX-License-Identifier: MIT
// Generators of datapath operands (querygen.hpp): the full port ranges and
// queries built on the decision boundaries of fixed.hpp's tests. They only
// choose operands; every answer is fixed_hit's.
#include "pluecker/querygen.hpp"

#include "pluecker/rng.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <numeric>
#include <stdexcept>
#include <string>

namespace pluecker {
namespace {

using i64 = std::int64_t;

// Uniform integer in [lo, hi] (hi - lo < 2^62).
i64 between(Rng& g, i64 lo, i64 hi) {
    return lo + static_cast<i64>(g.next() % static_cast<std::uint64_t>(hi - lo + 1));
}

template <class T, std::size_t N>
T pick(Rng& g, const std::array<T, N>& v) {
    return v[g.below(static_cast<std::uint32_t>(N))];
}

// Probability p as a draw.
bool chance(Rng& g, double p) { return g.unit() < p; }

i64 floor_mod(i64 a, i64 m) {
    const i64 r = a % m;
    return r < 0 ? r + m : r;
}

// x with a*x == 1 (mod m), gcd(a, m) = 1, m > 1 (extended Euclid).
i64 mod_inverse(i64 a, i64 m) {
    i64 r0 = m, r1 = floor_mod(a, m), s0 = 0, s1 = 1;
    while (r1 != 0) {
        const i64 q = r0 / r1;
        r0 -= q * r1;
        std::swap(r0, r1);
        s0 -= q * s1;
        std::swap(s0, s1);
    }
    return floor_mod(s0, m);
}

// The operands of one attempt do not exist (no solution in range): draw again.
struct Retry {};

// A random x in [lo, hi] with coef*x == rhs (mod mod).
i64 solve_linear(Rng& g, i64 coef, i64 rhs, i64 mod, i64 lo, i64 hi) {
    const i64 gcd = std::gcd(coef, mod);
    if (floor_mod(rhs, gcd) != 0) throw Retry{};
    const i64 m = mod / gcd;
    const i64 x0 = m > 1 ? floor_mod(floor_mod(rhs / gcd, m) * mod_inverse(coef / gcd, m), m) : 0;
    i64 first = x0;
    if (first < lo) first += (lo - first + m - 1) / m * m;  // smallest solution >= lo
    if (first > hi) throw Retry{};
    return first + m * between(g, 0, (hi - first) / m);
}

// --- full port ranges ------------------------------------------------------

FixedQuery port_range_query(Rng& g, const FixedFormat& f, std::size_t k) {
    const i64 cmin = f.coord_min(), cmax = f.coord_max(), one = f.dir_one();
    const i64 dmax = (i64{1} << f.dir_bits) - 1;
    const std::array<i64, 7> coord_corners{cmin, cmin + 1, -1, 0, 1, cmax - 1, cmax};
    const std::array<i64, 7> dir_corners{0, 1, one - 1, one, one + 1, dmax - 1, dmax};
    auto coord = [&] { return chance(g, 0.2) ? pick(g, coord_corners) : between(g, cmin, cmax); };
    auto direction = [&] {
        const float r = g.unit();
        if (r < 0.2f) return pick(g, dir_corners);
        return between(g, 0, r < 0.6f ? one : dmax);  // the set-up's range, then the whole port
    };
    const std::size_t style = k % 3;
    FixedQuery q;
    for (int a = 0; a < 3; ++a) {
        q.box.lo[a] = coord();
        q.box.hi[a] = coord();
    }
    if (chance(g, 0.9))  // mostly proper boxes; some with LO > HI
        for (int a = 0; a < 3; ++a)
            if (q.box.lo[a] > q.box.hi[a]) std::swap(q.box.lo[a], q.box.hi[a]);
    for (int a = 0; a < 3; ++a)  // style 0: origin inside the box's span
        q.ray.org[a] = style == 0 ? between(g, std::min(q.box.lo[a], q.box.hi[a]), std::max(q.box.lo[a], q.box.hi[a]))
                                  : coord();
    q.ray.has_end = g.coin();
    if (q.ray.has_end || g.coin())  // an end the DUT must ignore, too
        for (int a = 0; a < 3; ++a) q.ray.end[a] = coord();
    for (int a = 0; a < 3; ++a) q.ray.dir[a] = direction();
    if (style == 2) q.ray.dir[g.below(3)] = one;  // one dominant axis at 1.0, as the set-up makes it
    q.ray.cls = static_cast<RayClass>(g.below(8));
    return q;
}

// --- decision boundaries ---------------------------------------------------

enum class Kind { Edge, End, Origin };
constexpr Kind kKinds[] = {Kind::Edge, Kind::Edge, Kind::Edge, Kind::End, Kind::Origin};
constexpr std::size_t kKindCount = sizeof(kKinds) / sizeof(kKinds[0]);

// The offsets of one query along the ray, per axis (fixed.hpp's A_i, B_i,
// G_i) and its direction, before they become planes.
struct Offsets {
    std::array<i64, 3> A{}, B{}, D{}, G{};
    bool has_end = false;
};

// 2*(B_j*D_i - A_i*D_j) + A_i + B_j + D_i + D_j + 1 = t (conservative) or
// B_j*D_i - A_i*D_j = t (nearest), with 0 < A_i <= lim, 0 <= B_j <= span.
void place_edge(Rng& g, Offsets& o, int i, int j, i64 lim, i64 span, bool cons) {
    const i64 di = o.D[i], dj = o.D[j];
    i64 ai = 0, num = 0, m = 0;
    if (cons) {
        const i64 t = between(g, -2, 1);
        m = 2 * di + 1;
        ai = solve_linear(g, 2 * dj - 1, di + dj + 1 - t, m, 1, lim);
        num = t - di - dj - 1 + ai * (2 * dj - 1);
    } else {
        const i64 t = between(g, -1, 1);
        m = di;
        ai = solve_linear(g, dj, floor_mod(-t, di), di, 1, lim);
        num = t + ai * dj;
    }
    if (num % m != 0 || num / m < 0 || num / m > span) throw Retry{};
    o.A[i] = ai;
    o.B[j] = num / m;
}

Offsets boundary_offsets(Rng& g, const FixedFormat& f, Kind kind) {
    const i64 span = f.coord_max() - f.coord_min();  // the largest |A|, |B|
    const i64 one = f.dir_one();
    const bool cons = f.mode == FixedMode::Conservative;
    auto direction = [&] {
        const float r = g.unit();
        if (r < 0.25f) return one;
        return r < 0.4f ? between(g, 1, 8) : between(g, 1, one);
    };
    const int i = static_cast<int>(g.below(3));
    const int j = (i + 1 + static_cast<int>(g.below(2))) % 3;
    const int k = 3 - i - j;
    const std::array<i64, 3> lims{span / 8, span / 2, span};
    const i64 lim = pick(g, lims);
    Offsets o;
    for (int a = 0; a < 3; ++a) {  // by default the origin is inside every slab
        o.A[a] = -between(g, 0, lim / 2);
        o.B[a] = between(g, 0, lim / 2);
        o.D[a] = direction();
    }
    switch (kind) {
        case Kind::Edge:
            place_edge(g, o, i, j, lim, span, cons);
            o.B[i] = o.A[i] + between(g, 0, lim / 2);  // slab i is left after it is entered
            o.A[j] = -between(g, 0, lim / 2);          // origin inside slab j: T_ji >= 0
            o.D[k] = chance(g, 0.7) ? 0 : between(g, 1, 4);
            o.A[k] = -between(g, 0, lim / 2);
            o.B[k] = between(g, lim / 4, lim);
            break;
        case Kind::End:
            o.has_end = true;
            for (int a = 0; a < 3; ++a) o.G[a] = between(g, 0, lim);
            o.G[i] = between(g, -1, 1);
            break;
        case Kind::Origin:
            o.B[i] = between(g, -1, 1);
            o.A[i] = o.B[i] - between(g, 1, lim / 2 + 1);
            break;
    }
    return o;
}

// The planes of the offsets for a random class and origin inside the range.
FixedQuery boundary_planes(Rng& g, const FixedFormat& f, const Offsets& o) {
    const i64 cmin = f.coord_min(), cmax = f.coord_max(), span = cmax - cmin;
    FixedQuery q;
    q.ray.cls = static_cast<RayClass>(g.below(8));
    q.ray.dir = o.D;
    q.ray.has_end = o.has_end;
    for (int a = 0; a < 3; ++a) {
        const bool neg = class_negative(q.ray.cls, a);
        if (std::max(std::llabs(o.A[a]), std::llabs(o.B[a])) > span) throw Retry{};
        // Positive axis: LO = O + A, HI = O + B; negative: HI = O - A, LO = O - B.
        const i64 s = neg ? -1 : 1;
        const i64 lo_off = std::min({i64{0}, s * o.A[a], s * o.B[a]});
        const i64 hi_off = std::max({i64{0}, s * o.A[a], s * o.B[a]});
        if (cmin - lo_off > cmax - hi_off) throw Retry{};
        const i64 org = between(g, cmin - lo_off, cmax - hi_off);
        q.ray.org[a] = org;
        q.box.lo[a] = neg ? org - o.B[a] : org + o.A[a];
        q.box.hi[a] = neg ? org - o.A[a] : org + o.B[a];
        q.ray.end[a] = neg ? q.box.hi[a] - o.G[a] : q.box.lo[a] + o.G[a];
        if (o.has_end && (q.ray.end[a] < cmin || q.ray.end[a] > cmax)) throw Retry{};
    }
    if (!o.has_end)  // ignored by the datapath
        for (int a = 0; a < 3; ++a) q.ray.end[a] = between(g, cmin, cmax);
    return q;
}

}  // namespace

std::vector<FixedQuery> port_range_queries(std::uint64_t seed, std::size_t n, const FixedFormat& f) {
    f.validate();
    Rng g(seed ^ 0x504f525452414e47ull);
    std::vector<FixedQuery> out;
    out.reserve(n);
    for (std::size_t k = 0; k < n; ++k) out.push_back(port_range_query(g, f, k));
    return out;
}

std::vector<FixedQuery> boundary_queries(std::uint64_t seed, std::size_t n, const FixedFormat& f,
                                         std::vector<std::size_t>* kinds) {
    f.validate();
    Rng g(seed ^ 0x424f554e44415259ull);
    std::vector<FixedQuery> out;
    out.reserve(n);
    if (kinds) kinds->clear();
    // Every kind succeeds in a few draws at any width (the edge kind, the
    // rarest, in about one of three); the bound only stops a broken change.
    const std::size_t max_tries = 200 * n + 1000;
    for (std::size_t tries = 0; out.size() < n; ++tries) {
        if (tries == max_tries)
            throw std::logic_error("boundary_queries: only " + std::to_string(out.size()) + " of " +
                                   std::to_string(n) + " queries after " + std::to_string(tries) + " draws");
        const std::size_t kind = out.size() % kKindCount;
        try {
            out.push_back(boundary_planes(g, f, boundary_offsets(g, f, kKinds[kind])));
        } catch (const Retry&) {
            continue;
        }
        if (kinds) kinds->push_back(kind);
    }
    return out;
}

std::size_t boundary_kind_count() { return kKindCount; }

const char* boundary_kind_name(std::size_t i) {
    if (i >= kKindCount) return "?";
    switch (kKinds[i]) {
        case Kind::Edge: return "edge";
        case Kind::End: return "end";
        case Kind::Origin: return "origin";
    }
    return "?";
}

}  // namespace pluecker
