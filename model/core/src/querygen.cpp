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

#include "pluecker/contract.hpp"
#include "pluecker/rng.hpp"

#include <algorithm>
#include <cmath>
#include <string>
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

// A point of the box with `fixed` coordinates, on axes chosen at random, on
// planes (1 face, 2 edge, 3 corner) and the others inside(axis).
template <class Inside>
Vec3 point_on_planes(Rng& g, const Box& b, int fixed, Inside inside) {
    int axes[3] = {0, 1, 2};
    for (int i = 2; i > 0; --i) std::swap(axes[i], axes[g.below(i + 1)]);
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
        const int a = axes[k];
        p[a] = k < fixed ? (g.coin() ? b.lo[a] : b.hi[a]) : inside(a);
    }
    return p;
}

// ... the others strictly inside, all on the 2^-8 grid.
Vec3 point_on_box(Rng& g, const Box& b, int fixed) {
    return point_on_planes(g, b, fixed, [&](int a) {
        return b.lo[a] + (b.hi[a] - b.lo[a]) * 0.25f * static_cast<float>(1 + g.below(3));
    });
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

// ---------------------------------------------------------------------------
// Set-up families (setup_queries): the rays a renderer traces, from
// anywhere, into boxes of the range of one COORD_BITS.

// The range of COORD_BITS = c as float planes: [-2, 2 - 2^(2-c)].
float range_hi(int c) { return 2.0f - std::ldexp(1.0f, 2 - c); }

// A distance log-uniform in [1, 1e6] (powers of two times [1, 2), exact
// arithmetic only, so the same on every platform).
float far_distance(Rng& g) { return std::min(1e6f, std::ldexp(1.0f + g.unit(), static_cast<int>(g.below(20)))); }

// A multiple of 2^-3 at distance far_distance() from p, in a random
// direction: a camera or light far outside the scene. On the 2^-3 grid
// below 2^20, so q - o is exact in float for every q on that grid.
Vec3 far_point(Rng& g, const Vec3& p) {
    for (;;) {
        const Vec3 v = random_dir(g);
        const float len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
        const float r = far_distance(g);
        Vec3 o;
        for (int a = 0; a < 3; ++a) o[a] = std::ldexp(std::nearbyint(std::ldexp(p[a] + r * v[a] / len, 3)), -3);
        if (o != p) return o;
    }
}

// A box on the 2^-3 grid inside [-1.5, 1.5], each axis one to eight steps.
Box eighth_box(Rng& g) {
    Box b;
    for (int a = 0; a < 3; ++a) {
        const int lo = static_cast<int>(g.below(21)) - 12;  // -1.5 .. 1.0
        const int w = 1 + static_cast<int>(g.below(std::min(8, 12 - lo)));
        b.lo[a] = std::ldexp(static_cast<float>(lo), -3);
        b.hi[a] = std::ldexp(static_cast<float>(lo + w), -3);
    }
    return b;
}

// A point of b with `fixed` coordinates on planes and the rest on the
// 2^-3 grid inside (or at the plane when the box is one step wide).
Vec3 eighth_point_on_box(Rng& g, const Box& b, int fixed) {
    return point_on_planes(g, b, fixed, [&](int a) {
        const int steps = static_cast<int>(std::ldexp(b.hi[a] - b.lo[a], 3));
        return b.lo[a] + std::ldexp(static_cast<float>(steps > 1 ? 1 + g.below(steps - 1) : 0), -3);
    });
}

// Scales d by 2^s (exact) and returns the t at which the ray meets the
// point it was aimed at: long and short unnormalised directions.
float scale_dir(Rng& g, Vec3& d, int lo, int hi) {
    const int s = lo + static_cast<int>(g.below(static_cast<std::uint32_t>(hi - lo + 1)));
    d *= std::ldexp(1.0f, s);
    return std::ldexp(1.0f, -s);
}

// The segment ends exactly at t, or one ulp before or after it, or never.
float end_near(Rng& g, float t) {
    switch (g.below(4)) {
        case 0: return t;
        case 1: return down(t);
        case 2: return up(t);
        default: return kInf;
    }
}

// One ulp on one direction component, or on one box plane, or nothing.
void nudge(Rng& g, Query& q) {
    const int a = static_cast<int>(g.below(3));
    switch (g.below(3)) {
        case 0:
            if (q.ray.d[a] != 0.0f) q.ray.d[a] = ulp_step(g, q.ray.d[a]);
            break;
        case 1: {
            float& plane = g.coin() ? q.box.lo[a] : q.box.hi[a];
            plane = ulp_step(g, plane);
            if (q.box.lo[a] > q.box.hi[a]) std::swap(q.box.lo[a], q.box.hi[a]);
            break;
        }
        default: break;
    }
}

// A ray from far outside through a point of the box with `fixed`
// coordinates on its planes (3 corner, 2 edge), exactly, then nudged.
Query far_through(Rng& g, int fixed) {
    Query q;
    q.box = eighth_box(g);
    const Vec3 p = eighth_point_on_box(g, q.box, fixed);
    q.ray.o = far_point(g, p);
    q.ray.d = p - q.ray.o;  // exact: both on the 2^-3 grid below 2^20
    q.ray.tmax = end_near(g, scale_dir(g, q.ray.d, -4, 4));
    nudge(g, q);
    return q;
}
Query far_corner(Rng& g, int) { return far_through(g, 3); }
Query far_edge(Rng& g, int) { return far_through(g, 2); }

// A far camera aimed in float at an edge or corner of a float box in
// [-1, 1]: d = fl(p - o), so the ray passes within about |o| * 2^-24.
Query far_aimed(Rng& g, int) {
    Query q;
    const Vec3 c(g.sym(), g.sym(), g.sym());
    for (int a = 0; a < 3; ++a) {
        const float h = 0.3f * g.unit() + 0x1p-10f;
        q.box.lo[a] = std::max(-1.0f, c[a] - h);
        q.box.hi[a] = std::min(1.0f, c[a] + h);
    }
    Vec3 p;
    const int fixed = 2 + static_cast<int>(g.below(2));
    for (int a = 0; a < 3; ++a)
        p[a] = a < fixed ? (g.coin() ? q.box.lo[a] : q.box.hi[a]) : 0.5f * (q.box.lo[a] + q.box.hi[a]);
    std::swap(p[g.below(3)], p[g.below(3)]);
    const Vec3 v = random_dir(g);
    const float r = far_distance(g);
    q.ray.o = p + r * v;
    q.ray.d = p - q.ray.o;
    if (q.ray.d == Vec3(0.0f)) q.ray.d = v;
    if (g.coin()) nudge(g, q);
    return q;
}

// A light ray. Shadow ray: from a point on a face towards a far light
// (the segment ends far outside). Or from the light back to the point on
// the face the light sees, ending exactly on that entry face (or one ulp
// before or after it).
Query light_ray(Rng& g, int) {
    Query q;
    q.box = eighth_box(g);
    const Vec3 c = q.box.center();
    const Vec3 light = far_point(g, c);
    int a = 0;  // the axis along which the light is farthest from the box
    for (int k = 1; k < 3; ++k)
        if (std::fabs(light[k] - c[k]) > std::fabs(light[a] - c[a])) a = k;
    Vec3 p = eighth_point_on_box(g, q.box, 0);
    p[a] = light[a] > c[a] ? q.box.hi[a] : q.box.lo[a];  // on the face towards the light
    if (g.coin()) {
        q.ray.o = p;
        q.ray.d = light - p;
        q.ray.tmax = g.coin() ? 1.0f : kInf;
    } else {
        q.ray.o = light;
        q.ray.d = p - light;
        q.ray.tmax = end_near(g, scale_dir(g, q.ray.d, -4, 4));
    }
    return q;
}

// Long unnormalised directions (|d| up to about 100) from inside the
// scene, segments ending exactly on the box's entry face or one ulp off.
Query long_dir(Rng& g, int) {
    Query q;
    q.box = grid_box(g);
    Vec3 o;
    int a = 0;
    for (;;) {  // an origin outside the slab of axis a
        o = grid_point(g);
        a = static_cast<int>(g.below(3));
        if (o[a] < q.box.lo[a] || o[a] > q.box.hi[a]) break;
    }
    Vec3 p = point_on_box(g, q.box, 1 + static_cast<int>(g.below(3)));
    p[a] = o[a] < q.box.lo[a] ? q.box.lo[a] : q.box.hi[a];  // on the face o sees
    q.ray.o = o;
    q.ray.d = p - o;
    q.ray.tmax = end_near(g, scale_dir(g, q.ray.d, 0, 6));
    return q;
}

// The edges of the range itself: origins on a face of the range cube or
// one ulp outside it, rays along a face (d_a = +-0) or through an edge
// or corner of the cube, boxes that touch the range limits.
Query range_edge(Rng& g, int c) {
    Query q;
    const float lo = -2.0f, hi = range_hi(c);
    const float lsb = std::ldexp(1.0f, 2 - c);
    // A box with one to three planes on the range limits.
    for (int a = 0; a < 3; ++a) {
        const float u = g.sym() * 1.5f;
        const float w = std::ldexp(static_cast<float>(1 + g.below(64)), -6);
        q.box.lo[a] = std::max(lo, u - w);
        q.box.hi[a] = std::min(hi, u + w);
        switch (g.below(4)) {
            case 0: q.box.lo[a] = lo; break;
            case 1: q.box.hi[a] = hi; break;
            default: break;
        }
        if (q.box.lo[a] > q.box.hi[a]) std::swap(q.box.lo[a], q.box.hi[a]);
    }
    Vec3 p;  // a point of the box, on the range limits where the box touches them, else on the grid if it can
    for (int a = 0; a < 3; ++a) {
        const bool on_lo = q.box.lo[a] == lo, on_hi = q.box.hi[a] == hi;
        if (on_lo && (!on_hi || g.coin())) {
            p[a] = lo;
        } else if (on_hi) {
            p[a] = hi;
        } else {
            const float mid = q.box.lo[a] + (q.box.hi[a] - q.box.lo[a]) * 0.5f;
            const float on_grid = std::nearbyint(mid / lsb) * lsb;
            p[a] = on_grid >= q.box.lo[a] && on_grid <= q.box.hi[a] ? on_grid : mid;
        }
    }
    switch (g.below(3)) {
        case 0: {  // an origin on a range face or one ulp outside, moving along it
            const int a = static_cast<int>(g.below(3));
            q.ray.o = p;
            const float face = g.coin() ? lo : hi;
            q.ray.o[a] = g.coin() ? face : face == lo ? down(lo) : up(hi);
            const int b = (a + 1 + static_cast<int>(g.below(2))) % 3;
            q.ray.o[b] = g.coin() ? -3.0f : 3.0f;
            q.ray.d = Vec3(0.0f);
            q.ray.d[a] = g.coin() ? 0.0f : -0.0f;
            q.ray.d[b] = q.ray.o[b] > 0 ? -1.0f : 1.0f;
            q.ray.d[3 - a - b] = g.coin() ? 0.0f : std::ldexp(g.sym(), -static_cast<int>(g.below(30)));
            break;
        }
        case 1: {  // from outside, exactly through p (the grid of the range lets d be exact)
            const float reach = std::min(1e6f, std::ldexp(1.0f, 25 - c));
            Vec3 o;
            for (int a = 0; a < 3; ++a) {
                const float off = std::nearbyint(g.sym() * reach / lsb) * lsb;
                o[a] = p[a] + off;
            }
            if (o == p) o.x = p.x + 4.0f;
            q.ray.o = o;
            q.ray.d = p - o;
            q.ray.tmax = end_near(g, scale_dir(g, q.ray.d, -2, 2));
            nudge(g, q);
            break;
        }
        default: {  // origin one ulp outside a range face, aimed at p
            q.ray.o = p;
            const int a = static_cast<int>(g.below(3));
            q.ray.o[a] = g.coin() ? down(lo) : up(hi);
            q.ray.d = p - q.ray.o;
            if (q.ray.d == Vec3(0.0f)) q.ray.d = random_dir(g);
            break;
        }
    }
    return q;
}

using SetupFamily = Query (*)(Rng&, int);
struct SetupFamilyEntry {
    const char* name;
    SetupFamily make;
};
constexpr SetupFamilyEntry kSetupFamilies[] = {
    {"far-corner", far_corner}, {"far-edge", far_edge},   {"far-aimed", far_aimed},
    {"light-ray", light_ray},   {"long-dir", long_dir},   {"range-edge", range_edge},
};
constexpr std::size_t kSetupFamilyCount = sizeof kSetupFamilies / sizeof kSetupFamilies[0];

// Keeps a set-up query valid: boxes inside the range of COORD_BITS = c,
// finite origins (the generators make them finite; the clamp is a guard).
Query fit_range(Query q, int c) {
    const float lo = -2.0f, hi = range_hi(c);
    for (int a = 0; a < 3; ++a) {
        q.box.lo[a] = std::min(hi, std::max(lo, q.box.lo[a]));
        q.box.hi[a] = std::min(hi, std::max(lo, q.box.hi[a]));
        if (q.box.lo[a] > q.box.hi[a]) std::swap(q.box.lo[a], q.box.hi[a]);
    }
    if (q.ray.d.x == 0.0f && q.ray.d.y == 0.0f && q.ray.d.z == 0.0f) q.ray.d.z = 1.0f;
    if (!(q.ray.tmax >= 0.0f)) q.ray.tmax = kInf;
    return q;
}

// n queries, query i from family i % count (make(family) builds one),
// with the family of each in *families when given.
template <class Make>
std::vector<Query> round_robin(std::size_t n, std::size_t count, std::vector<std::size_t>* families, Make make) {
    std::vector<Query> out;
    out.reserve(n);
    if (families) {
        families->clear();
        families->reserve(n);
    }
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t f = i % count;
        out.push_back(make(f));
        if (families) families->push_back(f);
    }
    return out;
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
    return round_robin(n, kFamilyCount, families, [&](std::size_t f) { return fit(kFamilies[f].make(g)); });
}

std::size_t extreme_family_count() { return kFamilyCount; }

const char* extreme_family_name(std::size_t i) { return i < kFamilyCount ? kFamilies[i].name : "?"; }

std::vector<Query> setup_queries(std::uint64_t seed, std::size_t n, int coord_bits, std::vector<std::size_t>* families) {
    if (coord_bits < ContractLimits::kMinBits || coord_bits > ContractLimits::kMaxBits)
        throw InputError("setup_queries: COORD_BITS = " + std::to_string(coord_bits) + " is outside " +
                         std::to_string(ContractLimits::kMinBits) + ".." + std::to_string(ContractLimits::kMaxBits));
    Rng g(seed ^ 0x5345545550513121ull ^ (static_cast<std::uint64_t>(coord_bits) << 56));
    return round_robin(n, kSetupFamilyCount, families,
                       [&](std::size_t f) { return fit_range(kSetupFamilies[f].make(g, coord_bits), coord_bits); });
}

std::size_t setup_family_count() { return kSetupFamilyCount; }

const char* setup_family_name(std::size_t i) { return i < kSetupFamilyCount ? kSetupFamilies[i].name : "?"; }

}  // namespace pluecker
