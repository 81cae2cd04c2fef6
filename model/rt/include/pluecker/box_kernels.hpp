// SPDX-License-Identifier: MIT
// The float box tests of the traversal loops: smits and pluecker inline and
// per ray class, one box at a time and both children of a NodePair at once.
#pragma once

#include "pluecker/accel.hpp"
#include "pluecker/boxtest.hpp"
#include "pluecker/geometry.hpp"
#include "pluecker/vec4.hpp"

#include <glm/common.hpp>

namespace pluecker {

// Inline forms of smits_hit and pluecker_hit for the traversal loop,
// specialised per ray class C (the report's eight-class form: near and far
// planes and signs are resolved at compile time; the traversal dispatches
// on the class once per ray). They perform the same float operations as
// boxtest.cpp on the same set-up, so they give the same answers (and, for
// smits, the same entry distance). test_traverse.cpp checks the agreement
// on random and extreme queries.
// Component i of v without glm's operator[] (its bounds assert is live in
// -O2 builds without NDEBUG); with a constant i it folds to one load.
[[gnu::always_inline]] inline float at(const Vec3& v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }

struct FastSmitsRay {
    Vec3 o, inv;
    float tmax;
};
struct FastPlueckerRay {
    Vec3 o, d, e;  // d: |d_i|
    bool has_end;
};

inline FastSmitsRay fast_smits_setup(const Ray& r) {
    const SmitsRay s = smits_setup(r);
    return FastSmitsRay{s.o, s.inv, s.tmax};
}

template <RayClass C>
[[gnu::always_inline]] inline bool fast_smits_hit(const FastSmitsRay& r, const Box& b, float* tnear) {
    constexpr bool n[3] = {(C & 1) != 0, (C & 2) != 0, (C & 4) != 0};
    float t0 = 0.0f, t1 = r.tmax;
    for (int a = 0; a < 3; ++a) {
        const float en = (at(n[a] ? b.hi : b.lo, a) - at(r.o, a)) * at(r.inv, a);
        const float ex = (at(n[a] ? b.lo : b.hi, a) - at(r.o, a)) * at(r.inv, a);
        t0 = en > t0 ? en : t0;  // NaN (ray inside a plane): keep
        t1 = ex < t1 ? ex : t1;
    }
    if (!(t0 <= t1)) return false;
    if (tnear) *tnear = t0;
    return true;
}

inline FastPlueckerRay fast_pluecker_setup(const Ray& r) {
    const PlueckerRay p = pluecker_setup(r);
    return FastPlueckerRay{p.o, glm::abs(p.d), p.e, p.has_end};
}

template <RayClass C>
[[gnu::always_inline]] inline bool fast_pluecker_hit(const FastPlueckerRay& r, const Box& b) {
    constexpr bool n[3] = {(C & 1) != 0, (C & 2) != 0, (C & 4) != 0};
    float A[3], B[3];
    for (int i = 0; i < 3; ++i) {
        A[i] = n[i] ? at(r.o, i) - at(b.hi, i) : at(b.lo, i) - at(r.o, i);
        B[i] = n[i] ? at(r.o, i) - at(b.lo, i) : at(b.hi, i) - at(r.o, i);
    }
    const float D[3] = {r.d.x, r.d.y, r.d.z};
    // All tests evaluated, one branch at the end: the same conjunction as
    // boxtest.cpp's early returns.
    bool miss = (B[0] < 0.0f) | (B[1] < 0.0f) | (B[2] < 0.0f);
    miss |= B[1] * D[0] - A[0] * D[1] < 0.0f;
    miss |= B[0] * D[1] - A[1] * D[0] < 0.0f;
    miss |= B[2] * D[0] - A[0] * D[2] < 0.0f;
    miss |= B[0] * D[2] - A[2] * D[0] < 0.0f;
    miss |= B[2] * D[1] - A[1] * D[2] < 0.0f;
    miss |= B[1] * D[2] - A[2] * D[1] < 0.0f;
    if (r.has_end)
        for (int i = 0; i < 3; ++i) miss |= (n[i] ? at(b.hi, i) - at(r.e, i) : at(r.e, i) - at(b.lo, i)) < 0.0f;
    return !miss;
}

// Both children of a NodePair at once: the same float operations, per
// lane, as fast_smits_hit and fast_pluecker_hit on each child's box, so the
// same answers (and entry distances). Lanes of a 4-vector (GCC/Clang vector
// extensions; SSE on x86-64) hold {child 0, child 1} twice: for the box
// coordinates {lo, lo, hi, hi}. Bit c of the result is set when child c is
// hit. test_traverse_pairs.cpp checks them against the one-box kernels.

struct SmitsPairRay {
    Float4 o[3];    // o_a in every lane
    Float4 inv[3];  // {1/d_a, 1/d_a, -1/d_a, -1/d_a}
    Float4 init;    // {0, 0, -tmax, -tmax}
};

inline SmitsPairRay smits_pair_setup(const FastSmitsRay& r) {
    SmitsPairRay p;
    for (int a = 0; a < 3; ++a) {
        const float i = at(r.inv, a);
        p.o[a] = splat4(at(r.o, a));
        p.inv[a] = Float4{i, i, -i, -i};
    }
    p.init = Float4{0.0f, 0.0f, -r.tmax, -r.tmax};
    return p;
}

// Lanes 0, 1 accumulate the entry distance t0 of each child, lanes 2, 3 the
// negated exit distance -t1: (far - o) * -inv is exactly -((far - o) * inv),
// and -ex > -t1 exactly when ex < t1, so one max keeps both (a NaN lane
// keeps the old value, as in fast_smits_hit).
template <RayClass C>
[[gnu::always_inline]] inline unsigned fast_smits_pair(const SmitsPairRay& r, const NodePair& p, Float4& tnear) {
    constexpr bool n[3] = {(C & 1) != 0, (C & 2) != 0, (C & 4) != 0};
    Float4 acc = r.init;
    for (int a = 0; a < 3; ++a) {
        const Float4 b = load4(p.box[a]);
        const Float4 v = ((n[a] ? swap_halves(b) : b) - r.o[a]) * r.inv[a];  // {en, en, -ex, -ex}
        acc = v > acc ? v : acc;
    }
    tnear = acc;  // lanes 0, 1
    return lane_bits(acc <= -swap_halves(acc)) & 3u;
}

struct PlueckerPairRay {
    Float4 o[3];   // o_a in every lane
    Float4 e[3];   // segment end e_a in every lane
    Float4 dv[3];  // cross tests (i, j) = (0,1), (0,2), (1,2): {D_i, D_i, D_j, D_j}
    Float4 du[3];  //                                          {D_j, D_j, D_i, D_i}
    bool has_end;
};

inline PlueckerPairRay pluecker_pair_setup(const FastPlueckerRay& r) {
    PlueckerPairRay p;
    for (int a = 0; a < 3; ++a) {
        p.o[a] = splat4(at(r.o, a));
        p.e[a] = splat4(at(r.e, a));
    }
    constexpr int ij[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    for (int k = 0; k < 3; ++k) {
        const float di = at(r.d, ij[k][0]), dj = at(r.d, ij[k][1]);
        p.dv[k] = Float4{di, di, dj, dj};
        p.du[k] = Float4{dj, dj, di, di};
    }
    p.has_end = r.has_end;
    return p;
}

// W[a] = {A_a, A_a, B_a, B_a} (children 0, 1). Lanes 0, 1 of the result:
// B_j*D_i - A_i*D_j < 0; lanes 2, 3: B_i*D_j - A_j*D_i < 0.
template <int I, int J>
[[gnu::always_inline]] inline Int4 pluecker_cross_miss(const Float4* W, Float4 dv, Float4 du) {
    const Float4 b = __builtin_shufflevector(W[J], W[I], 2, 3, 6, 7);  // {B_j, B_j, B_i, B_i}
    const Float4 a = __builtin_shufflevector(W[I], W[J], 0, 1, 4, 5);  // {A_i, A_i, A_j, A_j}
    return b * dv - a * du < Float4{};
}

template <RayClass C>
[[gnu::always_inline]] inline unsigned fast_pluecker_pair(const PlueckerPairRay& r, const NodePair& p) {
    constexpr bool n[3] = {(C & 1) != 0, (C & 2) != 0, (C & 4) != 0};
    const Float4 zero{};
    Float4 bx[3], W[3];
    for (int a = 0; a < 3; ++a) {
        bx[a] = load4(p.box[a]);
        W[a] = n[a] ? swap_halves(r.o[a] - bx[a]) : bx[a] - r.o[a];
    }
    // Origin test (lanes 2, 3: B < 0), then the six silhouette tests.
    Int4 miss = ((W[0] < zero) | (W[1] < zero) | (W[2] < zero)) & Int4{0, 0, -1, -1};
    miss |= pluecker_cross_miss<0, 1>(W, r.dv[0], r.du[0]);
    miss |= pluecker_cross_miss<0, 2>(W, r.dv[1], r.du[1]);
    miss |= pluecker_cross_miss<1, 2>(W, r.dv[2], r.du[2]);
    if (r.has_end) {  // lanes 0, 1: e - lo (positive axis) or hi - e (negative)
        Int4 end{};
        for (int a = 0; a < 3; ++a) end |= (n[a] ? swap_halves(bx[a] - r.e[a]) : r.e[a] - bx[a]) < zero;
        miss |= end & Int4{-1, -1, 0, 0};
    }
    const unsigned bits = lane_bits(miss);
    return ~(bits | bits >> 2) & 3u;
}

}  // namespace pluecker
