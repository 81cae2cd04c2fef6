// SPDX-License-Identifier: MIT
// Deterministic query generators (see querygen.hpp).
//
// The "exact" constructions put every coordinate on a dyadic grid (multiples
// of 2^-8 in [-1, 1]), so the difference P - o of two grid points is exact
// in float and a ray with d = (P - o) * 2^s passes through P exactly at
// t = 2^-s. That is how rays through box edges and corners and segments
// ending exactly on a face are made; the "ulp" variants then move one plane,
// one origin coordinate or tmax by a single float ulp.
#include "pluecker/querygen.hpp"

#include "pluecker/rng.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace pluecker {

namespace {

constexpr int kGridBits = 8;  // grid step 2^-8

// A multiple of 2^-bits in [-1, 1].
float grid(Rng& g, int bits = 6) {
    const int n = 1 << bits;
    return std::ldexp(static_cast<float>(static_cast<int>(g.below(2 * n + 1)) - n), -bits);
}
Vec3 grid_point(Rng& g, int bits = kGridBits) { return {grid(g, bits), grid(g, bits), grid(g, bits)}; }

float up(float x) { return std::nextafter(x, kInf); }
float down(float x) { return std::nextafter(x, -kInf); }
float ulp_step(Rng& g, float x) { return g.coin() ? up(x) : down(x); }

// A box with planes on the 2^-6 grid, each axis at least one step wide.
Box grid_box(Rng& g) {
    Box b;
    for (int a = 0; a < 3; ++a) {
        float p = grid(g), q = grid(g);
        while (p == q) q = grid(g);
        b.lo[a] = std::min(p, q);
        b.hi[a] = std::max(p, q);
    }
    return b;
}

// A point of the box with `fixed` coordinates on planes (1 face, 2 edge,
// 3 corner) and the others strictly inside, all on the 2^-8 grid.
Vec3 point_on_box(Rng& g, const Box& b, int fixed) {
    int axes[3] = {0, 1, 2};
    for (int i = 2; i > 0; --i) std::swap(axes[i], axes[g.below(i + 1)]);
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
        const int a = axes[k];
        if (k < fixed) p[a] = g.coin() ? b.lo[a] : b.hi[a];
        else p[a] = b.lo[a] + (b.hi[a] - b.lo[a]) * 0.25f * static_cast<float>(1 + g.below(3));
    }
    return p;
}

// A grid origin different from p.
Vec3 origin_off(Rng& g, const Vec3& p) {
    Vec3 o = grid_point(g);
    while (o == p) o = grid_point(g);
    return o;
}

// d = (p - o) * 2^s, exact: the ray meets p at t = 2^-s.
struct Aim {
    Vec3 d;
    float t;
};
Aim aim(Rng& g, const Vec3& o, const Vec3& p) {
    const int s = static_cast<int>(g.below(5)) - 2;
    return {(p - o) * std::ldexp(1.0f, s), std::ldexp(1.0f, -s)};
}

Vec3 random_dir(Rng& g) {
    for (;;) {
        const Vec3 v(g.sym(), g.sym(), g.sym());
        const float l2 = v.x * v.x + v.y * v.y + v.z * v.z;
        if (l2 > 0x1p-20f && l2 <= 1.0f) return v;
    }
}

// A nonzero direction with components in {-1, -3/4, ..., 1}: many zeros and
// exact axis/diagonal directions.
Vec3 grid_dir(Rng& g) {
    for (;;) {
        const Vec3 v = grid_point(g, 2);
        if (v != Vec3(0.0f)) return v;
    }
}

// A coordinate near a slab [lo, hi]: on a plane, 1 ulp either side of one,
// inside or outside.
float near_slab(Rng& g, float lo, float hi) {
    switch (g.below(7)) {
        case 0: return lo;
        case 1: return hi;
        case 2: return ulp_step(g, lo);
        case 3: return ulp_step(g, hi);
        case 4: return 0.5f * (lo + hi);
        case 5: return grid(g, kGridBits);
        default: return g.sym();
    }
}

float maybe_segment(Rng& g, float t_hit) {
    switch (g.below(4)) {
        case 0: return t_hit;
        case 1: return 2.0f * g.unit() * t_hit;
        default: return kInf;
    }
}

// Keeps a generated query valid and in [-1, 1].
Query fit(Query q) {
    auto clamp1 = [](float x) { return std::min(1.0f, std::max(-1.0f, x)); };
    for (int a = 0; a < 3; ++a) {
        q.ray.o[a] = clamp1(q.ray.o[a]);
        q.box.lo[a] = clamp1(q.box.lo[a]);
        q.box.hi[a] = clamp1(q.box.hi[a]);
        if (q.box.lo[a] > q.box.hi[a]) std::swap(q.box.lo[a], q.box.hi[a]);
    }
    if (q.ray.d.x == 0.0f && q.ray.d.y == 0.0f && q.ray.d.z == 0.0f) q.ray.d.z = 0x1p-149f;
    if (!(q.ray.tmax >= 0.0f)) q.ray.tmax = kInf;
    return q;
}

// ---------------------------------------------------------------------------
// The families.
// ---------------------------------------------------------------------------

Query axis_parallel(Rng& g) {
    Query q;
    q.box = grid_box(g);
    const int k = static_cast<int>(g.below(3));
    for (int a = 0; a < 3; ++a) {
        q.ray.d[a] = g.sign() * (a == k ? 1.0f : 0.0f);
        q.ray.o[a] = a == k ? grid(g, kGridBits) : near_slab(g, q.box.lo[a], q.box.hi[a]);
    }
    q.ray.tmax = g.below(4) == 0 ? 2.0f * g.unit() : kInf;
    return q;
}

Query near_axis(Rng& g) {
    static constexpr float kTiny[] = {0x1p-23f, 0x1p-24f, 0x1p-30f, 0x1p-126f, 0x1p-149f};
    Query q = axis_parallel(g);
    for (int a = 0; a < 3; ++a)
        if (q.ray.d[a] == 0.0f && g.below(3) != 0) q.ray.d[a] = g.sign() * kTiny[g.below(5)];
    return q;
}

Query signed_zero(Rng& g) {
    Query q;
    q.box = grid_box(g);
    const Vec3 p = point_on_box(g, q.box, static_cast<int>(g.below(4)));
    q.ray.o = grid_point(g);
    const int zeros = 1 + static_cast<int>(g.below(2));
    const int first = static_cast<int>(g.below(3));
    for (int k = 0; k < 3; ++k) {
        const int a = (first + k) % 3;
        if (k < zeros) {
            q.ray.d[a] = g.coin() ? -0.0f : 0.0f;
            q.ray.o[a] = near_slab(g, q.box.lo[a], q.box.hi[a]);
        } else {
            const float d = p[a] - q.ray.o[a];
            q.ray.d[a] = d != 0.0f ? d : g.sign() * 0x1p-4f;
        }
    }
    q.ray.tmax = maybe_segment(g, 1.0f);
    return q;
}

// A ray through an exact box point with `fixed` coordinates on planes.
Query through(Rng& g, int fixed) {
    Query q;
    q.box = grid_box(g);
    const Vec3 p = point_on_box(g, q.box, fixed);
    q.ray.o = origin_off(g, p);
    const Aim h = aim(g, q.ray.o, p);
    q.ray.d = h.d;
    q.ray.tmax = maybe_segment(g, h.t);
    return q;
}

// Moves one plane or one origin coordinate, or tmax, by one ulp.
Query ulp_nudge(Rng& g, Query q) {
    const int a = static_cast<int>(g.below(3));
    switch (g.below(4)) {
        case 0: q.box.lo[a] = ulp_step(g, q.box.lo[a]); break;
        case 1: q.box.hi[a] = ulp_step(g, q.box.hi[a]); break;
        case 2: q.ray.o[a] = ulp_step(g, q.ray.o[a]); break;
        default:
            if (std::isfinite(q.ray.tmax)) q.ray.tmax = ulp_step(g, q.ray.tmax);
            else q.ray.d[a] = ulp_step(g, q.ray.d[a]);
    }
    return q;
}

Query edge_exact(Rng& g) { return through(g, 2); }
Query edge_ulp(Rng& g) { return ulp_nudge(g, through(g, 2)); }
Query corner_exact(Rng& g) { return through(g, 3); }
Query corner_ulp(Rng& g) { return ulp_nudge(g, through(g, 3)); }

Query flat_box(Rng& g) {
    Query q;
    q.box = grid_box(g);
    const int flat = 1 + static_cast<int>(g.below(3));  // 1 plane, 2 line, 3 point
    const int first = static_cast<int>(g.below(3));
    for (int k = 0; k < flat; ++k) {
        const int a = (first + k) % 3;
        q.box.hi[a] = q.box.lo[a] = grid(g, kGridBits);
    }
    const Vec3 p = point_on_box(g, q.box, static_cast<int>(g.below(4)));
    q.ray.o = origin_off(g, p);
    const Aim h = aim(g, q.ray.o, p);
    q.ray.d = h.d;
    q.ray.tmax = maybe_segment(g, h.t);
    return g.below(3) == 0 ? ulp_nudge(g, q) : q;
}

Query origin_on_box(Rng& g) {
    Query q;
    q.box = grid_box(g);
    q.ray.o = point_on_box(g, q.box, 1 + static_cast<int>(g.below(3)));
    if (g.below(3) == 0) {  // or 1 ulp beside it
        const int a = static_cast<int>(g.below(3));
        q.ray.o[a] = ulp_step(g, q.ray.o[a]);
    }
    q.ray.d = g.coin() ? random_dir(g) : grid_dir(g);
    switch (g.below(4)) {
        case 0: q.ray.tmax = 0.0f; break;
        case 1: q.ray.tmax = g.unit(); break;
        default: q.ray.tmax = kInf;
    }
    return q;
}

Query segment_end(Rng& g) {
    Query q;
    q.box = grid_box(g);
    Vec3 p = point_on_box(g, q.box, 1);
    q.ray.o = origin_off(g, p);
    // Put p on the face that looks at the origin, when there is one.
    for (int a = 0; a < 3; ++a) {
        if (q.ray.o[a] < q.box.lo[a]) {
            p = point_on_box(g, q.box, 0);
            p[a] = q.box.lo[a];
            break;
        }
        if (q.ray.o[a] > q.box.hi[a]) {
            p = point_on_box(g, q.box, 0);
            p[a] = q.box.hi[a];
            break;
        }
    }
    if (p == q.ray.o) q.ray.o = origin_off(g, p);
    const Aim h = aim(g, q.ray.o, p);
    q.ray.d = h.d;
    switch (g.below(3)) {
        case 0: q.ray.tmax = h.t; break;
        case 1: q.ray.tmax = down(h.t); break;
        default: q.ray.tmax = up(h.t); break;
    }
    return q;
}

Query unit_coords(Rng& g) {
    const float one_in = down(1.0f);  // 1 - 2^-24
    auto low = [&] { return g.coin() ? -1.0f : (g.coin() ? -one_in : grid(g)); };
    auto high = [&] { return g.coin() ? 1.0f : (g.coin() ? one_in : grid(g)); };
    Query q;
    for (int a = 0; a < 3; ++a) {
        q.box.lo[a] = low();
        q.box.hi[a] = high();
        switch (g.below(5)) {
            case 0: q.ray.o[a] = 1.0f; break;
            case 1: q.ray.o[a] = -1.0f; break;
            case 2: q.ray.o[a] = one_in; break;
            case 3: q.ray.o[a] = -one_in; break;
            default: q.ray.o[a] = grid(g, kGridBits);
        }
    }
    if (g.coin()) {
        const int k = static_cast<int>(g.below(3));
        for (int a = 0; a < 3; ++a) q.ray.d[a] = a == k ? g.sign() : (g.coin() ? 0.0f : -0.0f);
    } else {
        Vec3 p;
        for (int a = 0; a < 3; ++a) p[a] = g.coin() ? q.box.lo[a] : q.box.hi[a];
        q.ray.d = p - q.ray.o;
        if (q.ray.d == Vec3(0.0f)) q.ray.d = random_dir(g);
    }
    q.ray.tmax = maybe_segment(g, 1.0f);
    return q;
}

// A ray aimed at a random point in or on a grid box (not exact unless the
// direction is left alone).
Query aimed(Rng& g) {
    Query q;
    q.box = grid_box(g);
    const Vec3 p = point_on_box(g, q.box, static_cast<int>(g.below(4)));
    q.ray.o = origin_off(g, p);
    const Aim h = aim(g, q.ray.o, p);
    q.ray.d = h.d;
    q.ray.tmax = maybe_segment(g, h.t);
    return q;
}

Query denormal_dir(Rng& g) {
    Query q = aimed(g);
    if (g.coin()) {
        const int n = 1 + static_cast<int>(g.below(2));
        const int first = static_cast<int>(g.below(3));
        for (int k = 0; k < n; ++k)
            q.ray.d[(first + k) % 3] = g.sign() * std::ldexp(static_cast<float>(1 + g.below((1u << 23) - 1)), -149);
    } else {
        // The whole direction in the denormal range (grid components are
        // multiples of 2^-10 below 8, so they stay exact and nonzero).
        q.ray.d *= 0x1p-130f;
        if (std::isfinite(q.ray.tmax))
            q.ray.tmax = static_cast<float>(std::min(std::ldexp(double(q.ray.tmax), 130), 0x1p127));
    }
    return q;
}

Query tiny_dir(Rng& g) {
    Query q = aimed(g);
    q.ray.d *= 1e-30f;
    if (std::isfinite(q.ray.tmax)) q.ray.tmax *= 1e30f;
    return q;
}

Query huge_dir(Rng& g) {
    Query q = aimed(g);
    q.ray.d *= 1e30f;
    if (std::isfinite(q.ray.tmax)) q.ray.tmax *= 1e-30f;
    return q;
}

Query tiny_box(Rng& g) {
    static constexpr float kWidth[] = {1e-6f, 1e-7f, 1e-8f, 0.0f};
    Query q;
    const Vec3 c(0.9f * g.sym(), 0.9f * g.sym(), 0.9f * g.sym());
    const std::uint32_t kind = g.below(6);
    for (int a = 0; a < 3; ++a) {
        q.box.lo[a] = c[a];
        if (kind < 4) q.box.hi[a] = c[a] + kWidth[kind];
        else q.box.hi[a] = kind == 4 ? up(c[a]) : up(up(up(up(c[a]))));  // 1 or 4 ulps
    }
    q.ray.o = grid_point(g);
    const Vec3 target = g.coin() ? q.box.center() : (g.coin() ? q.box.lo : q.box.hi);
    q.ray.d = target - q.ray.o;
    if (q.ray.d == Vec3(0.0f)) q.ray.d = random_dir(g);
    q.ray.tmax = maybe_segment(g, 1.0f);
    return q;
}

Query zero_length(Rng& g) {
    Query q;
    q.box = grid_box(g);
    const int fixed = static_cast<int>(g.below(4));
    q.ray.o = point_on_box(g, q.box, fixed);
    if (g.below(3) == 0) {
        const int a = static_cast<int>(g.below(3));
        q.ray.o[a] = ulp_step(g, q.ray.o[a]);
    } else if (g.below(4) == 0) {
        q.ray.o = grid_point(g);
    }
    q.ray.d = g.coin() ? random_dir(g) : grid_dir(g);
    q.ray.tmax = g.coin() ? 0.0f : -0.0f;
    return q;
}

using Family = Query (*)(Rng&);
struct FamilyEntry {
    const char* name;
    Family make;
};
constexpr FamilyEntry kFamilies[] = {
    {"axis-parallel", axis_parallel}, {"near-axis", near_axis},
    {"signed-zero", signed_zero},     {"edge-exact", edge_exact},
    {"edge-ulp", edge_ulp},           {"corner-exact", corner_exact},
    {"corner-ulp", corner_ulp},       {"flat-box", flat_box},
    {"origin-on-box", origin_on_box}, {"segment-end", segment_end},
    {"unit-coords", unit_coords},     {"denormal-dir", denormal_dir},
    {"tiny-dir", tiny_dir},           {"huge-dir", huge_dir},
    {"tiny-box", tiny_box},           {"zero-length", zero_length},
};
constexpr std::size_t kFamilyCount = sizeof kFamilies / sizeof kFamilies[0];

Query random_query(Rng& g) {
    Query q;
    const Vec3 c(g.sym(), g.sym(), g.sym());
    static constexpr float kScale[] = {1.0f, 0.3f, 0.1f, 0.01f};
    const float s = kScale[g.below(4)];
    for (int a = 0; a < 3; ++a) {
        const float h = s * g.unit();
        q.box.lo[a] = std::max(-1.0f, c[a] - h);
        q.box.hi[a] = std::min(1.0f, c[a] + h);
    }
    q.ray.o = Vec3(g.sym(), g.sym(), g.sym());
    const bool aimed_ray = g.coin();
    if (aimed_ray) {
        Vec3 p;
        for (int a = 0; a < 3; ++a) {
            const float u = -0.1f + 1.2f * g.unit();
            p[a] = std::min(1.0f, std::max(-1.0f, q.box.lo[a] + (q.box.hi[a] - q.box.lo[a]) * u));
        }
        q.ray.d = p - q.ray.o;
    }
    if (!aimed_ray || q.ray.d == Vec3(0.0f)) q.ray.d = random_dir(g);
    if (g.below(4) == 0) q.ray.tmax = (aimed_ray ? 1.5f : 3.0f) * g.unit();
    return q;
}

}  // namespace

std::vector<Query> random_queries(std::uint64_t seed, std::size_t n) {
    Rng g(seed ^ 0x52414e444f4d5121ull);
    std::vector<Query> out;
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) out.push_back(fit(random_query(g)));
    return out;
}

std::vector<Query> extreme_queries(std::uint64_t seed, std::size_t n, std::vector<std::size_t>* families) {
    Rng g(seed ^ 0x45585452454d4521ull);
    std::vector<Query> out;
    out.reserve(n);
    if (families) {
        families->clear();
        families->reserve(n);
    }
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t f = i % kFamilyCount;
        out.push_back(fit(kFamilies[f].make(g)));
        if (families) families->push_back(f);
    }
    return out;
}

std::size_t extreme_family_count() { return kFamilyCount; }

const char* extreme_family_name(std::size_t i) { return i < kFamilyCount ? kFamilies[i].name : "?"; }

}  // namespace pluecker
