// SPDX-License-Identifier: MIT
// Watertight ray/triangle intersection (Woop, Benthin, Wald, "Watertight
// Ray/Triangle Intersection", JCGT 2(1), 2013).
//
// Per ray, once: pick the dominant axis kz of d, the two others kx, ky
// (swapped when d[kz] < 0 to keep the winding), and the shear constants
// Sx = d[kx]/d[kz], Sy = d[ky]/d[kz], Sz = 1/d[kz] that map the ray onto the
// +z axis. Per triangle: translate the vertices by -o, shear them, and take
// the three 2D edge functions U, V, W at the origin (as the paper does, they
// are recomputed in double when one of them is exactly zero, so an edge or
// vertex hit is decided consistently for the triangles sharing it). The ray
// passes through the triangle iff U, V, W share a sign (two-sided: no
// culling); then det = U+V+W, T = U*Az + V*Bz + W*Cz, t = T/det.
//
// Order independence: a hit is accepted when 0 <= t <= tmax; t is a function
// of the ray and the triangle alone, so a closest-hit search that compares
// (t, triangle id) lexicographically returns the same hit in any visit order
// (brute force, any BVH, any child order).
#pragma once

#include "pluecker/geometry.hpp"
#include "pluecker/vec4.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

namespace pluecker {

inline constexpr std::uint32_t kNoHit = std::numeric_limits<std::uint32_t>::max();

// Closest or any hit of a ray: triangle id (mesh index), distance, and the
// barycentric weights b1, b2 of vertices 1 and 2 (vertex 0 has 1-b1-b2).
struct Hit {
    float t = kInf;
    float b1 = 0.0f;
    float b2 = 0.0f;
    std::uint32_t tri = kNoHit;
    bool found() const { return tri != kNoHit; }
};

// (t, id) lexicographic order: the tie break that makes closest hits
// independent of the visit order.
inline bool closer(float t, std::uint32_t id, const Hit& best) {
    return t < best.t || (t == best.t && id < best.tri);
}

// The per-ray constants of the test.
struct TriRay {
    float o[3];
    int kx, ky, kz;
    float sx, sy, sz;
};

inline TriRay tri_setup(const Ray& r) {
    TriRay t;
    const float d[3] = {r.d.x, r.d.y, r.d.z};
    t.o[0] = r.o.x;
    t.o[1] = r.o.y;
    t.o[2] = r.o.z;
    const float ax = std::fabs(d[0]), ay = std::fabs(d[1]), az = std::fabs(d[2]);
    t.kz = ax >= ay ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
    t.kx = (t.kz + 1) % 3;
    t.ky = (t.kx + 1) % 3;
    if (d[t.kz] < 0.0f) {
        const int k = t.kx;
        t.kx = t.ky;
        t.ky = k;
    }
    t.sx = d[t.kx] / d[t.kz];
    t.sy = d[t.ky] / d[t.kz];
    t.sz = 1.0f / d[t.kz];
    return t;
}

// The last step of both triangle tests below: with det = u + v + w != 0
// and tt = the scaled distance, a hit when t = tt / det lies in [0, tmax];
// then t and the barycentrics b1 = v / det, b2 = w / det are set.
[[gnu::always_inline]] inline bool tri_finish(float det, float tt, float v, float w, float tmax, float& t, float& b1,
                                              float& b2) {
    // t >= 0 iff tt and det share a sign.
    if ((det < 0.0f && tt > 0.0f) || (det > 0.0f && tt < 0.0f)) return false;
    const float rcp = 1.0f / det;
    const float th = tt * rcp;
    if (!(th <= tmax)) return false;
    t = th;
    b1 = v * rcp;
    b2 = w * rcp;
    return true;
}

// Returns true for a hit with 0 <= t <= tmax; then t, b1, b2 are set.
// (Plain arrays, not glm's operator[], whose bounds assert is live in -O2
// builds without NDEBUG.)
[[gnu::always_inline]] inline bool tri_intersect(const TriRay& r, const Vec3& v0, const Vec3& v1, const Vec3& v2,
                                                 float tmax, float& t, float& b1, float& b2) {
    const float a[3] = {v0.x - r.o[0], v0.y - r.o[1], v0.z - r.o[2]};
    const float b[3] = {v1.x - r.o[0], v1.y - r.o[1], v1.z - r.o[2]};
    const float c[3] = {v2.x - r.o[0], v2.y - r.o[1], v2.z - r.o[2]};
    const float ax = a[r.kx] - r.sx * a[r.kz];
    const float ay = a[r.ky] - r.sy * a[r.kz];
    const float bx = b[r.kx] - r.sx * b[r.kz];
    const float by = b[r.ky] - r.sy * b[r.kz];
    const float cx = c[r.kx] - r.sx * c[r.kz];
    const float cy = c[r.ky] - r.sy * c[r.kz];
    float u = cx * by - cy * bx;
    float v = ax * cy - ay * cx;
    float w = bx * ay - by * ax;
    if (u == 0.0f || v == 0.0f || w == 0.0f) {
        // The products of floats are exact in double, so the signs are exact.
        u = static_cast<float>(double(cx) * double(by) - double(cy) * double(bx));
        v = static_cast<float>(double(ax) * double(cy) - double(ay) * double(cx));
        w = static_cast<float>(double(bx) * double(ay) - double(by) * double(ax));
    }
    if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return false;
    const float det = u + v + w;
    if (det == 0.0f) return false;
    const float az = r.sz * a[r.kz];
    const float bz = r.sz * b[r.kz];
    const float cz = r.sz * c[r.kz];
    const float tt = u * az + v * bz + w * cz;
    return tri_finish(det, tt, v, w, tmax, t, b1, b2);
}

// A triangle stored for traversal: vertices and the mesh triangle id.
struct LeafTri {
    Vec3 v0, v1, v2;
    std::uint32_t id;
};
static_assert(sizeof(LeafTri) == 40);

// tri_intersect on a LeafTri, for a ray whose tri_setup chose kz = KZ and
// swapped kx, ky iff SWAP, with the three vertices in the lanes of 4-vectors:
// the same float operations per vertex and edge function as tri_intersect
// (each lane one of its scalar expressions), so the same result.
template <int KZ, bool SWAP>
[[gnu::always_inline]] inline bool tri_intersect_packed(const TriRay& r, const LeafTri& tri, float tmax, float& t,
                                                        float& b1, float& b2) {
    constexpr int kx0 = (KZ + 1) % 3, ky0 = (kx0 + 1) % 3;
    constexpr int KX = SWAP ? ky0 : kx0, KY = SWAP ? kx0 : ky0;
    // Rows {v0, v1, v2} of each axis; lane 3 repeats v2 (never the id).
    const Float4 p0 = load4(&tri.v0.x), p1 = load4(&tri.v1.x), p2 = load4(&tri.v2.x);
    const Float4 lo = __builtin_shufflevector(p0, p1, 0, 4, 1, 5);  // x0 x1 y0 y1
    const Float4 hi = __builtin_shufflevector(p0, p1, 2, 6, 2, 6);  // z0 z1 z0 z1
    const Float4 row[3] = {__builtin_shufflevector(lo, p2, 0, 1, 4, 4),
                           __builtin_shufflevector(lo, p2, 2, 3, 5, 5),
                           __builtin_shufflevector(hi, p2, 0, 1, 6, 6)};
    // Translated: lanes {a, b, c} of tri_intersect per axis.
    const Float4 X = row[KX] - splat4(r.o[KX]);
    const Float4 Y = row[KY] - splat4(r.o[KY]);
    const Float4 Z = row[KZ] - splat4(r.o[KZ]);
    const Float4 sx = X - splat4(r.sx) * Z;  // {ax, bx, cx}
    const Float4 sy = Y - splat4(r.sy) * Z;  // {ay, by, cy}
    // {u, v, w} = {cx*by - cy*bx, ax*cy - ay*cx, bx*ay - by*ax}
    const Float4 x2 = __builtin_shufflevector(sx, sx, 2, 0, 1, 3), y1 = __builtin_shufflevector(sy, sy, 1, 2, 0, 3);
    const Float4 y2 = __builtin_shufflevector(sy, sy, 2, 0, 1, 3), x1 = __builtin_shufflevector(sx, sx, 1, 2, 0, 3);
    Float4 uvw = x2 * y1 - y2 * x1;
    const Float4 zero{};
    if (lane_bits(uvw == zero) & 7u) [[unlikely]] {
        // The products of floats are exact in double, so the signs are exact.
        const double ax = sx[0], bx = sx[1], cx = sx[2], ay = sy[0], by = sy[1], cy = sy[2];
        uvw = Float4{static_cast<float>(cx * by - cy * bx), static_cast<float>(ax * cy - ay * cx),
                     static_cast<float>(bx * ay - by * ax), 0.0f};
    }
    const unsigned neg = lane_bits(uvw < zero) & 7u, pos = lane_bits(uvw > zero) & 7u;
    if (neg && pos) return false;
    const float u = uvw[0], v = uvw[1], w = uvw[2];
    const float det = u + v + w;
    if (det == 0.0f) return false;
    const Float4 p = uvw * (splat4(r.sz) * Z);  // {u*az, v*bz, w*cz}
    const float tt = p[0] + p[1] + p[2];
    return tri_finish(det, tt, v, w, tmax, t, b1, b2);
}

}  // namespace pluecker
