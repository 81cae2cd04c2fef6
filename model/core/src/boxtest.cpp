// SPDX-License-Identifier: MIT
// The two single-precision float ray/box tests in the report's eight-class
// form: 'smits-mul-cls' (slab test with the inverse direction) and
// 'pluecker-cls' (Mahovsky & Wyvill, "Fast ray-axis aligned bounding box
// overlap tests with Plücker coordinates", JGT 9(1), 2004).
//
// Both answer: does the segment {o + t*d : 0 <= t <= tmax} meet the closed
// box? They are float approximations; exact_hit (exact.cpp) is the truth.
#include "pluecker/boxtest.hpp"

#include <cmath>

namespace pluecker {

// ---------------------------------------------------------------------------
// smits-mul-cls
//
// Per axis, the slab [lo, hi] is crossed for t in [(near - o) * inv,
// (far - o) * inv], where near/far are lo/hi for a positive axis and hi/lo
// for a negative one (the ray class picks them, so no swap is needed). The
// segment meets the box when max(0, entries) <= min(tmax, exits).
//
// A zero direction component gives inv = +-inf. Then (plane - o) * inv is
// +-inf when the origin is off the plane (the right limit) and 0*inf = NaN
// when the origin lies exactly on it. In that case the ray runs inside the
// plane, i.e. inside the closed slab, so the slab must not constrain t: the
// entry must count as -inf and the exit as +inf. The updates below are
// written `cand > cur ? cand : cur` and `cand < cur ? cand : cur`, which keep
// the current bound when cand is NaN: exactly "no constraint". The answer is
// therefore the closed-box answer and never decided by a NaN.
// ---------------------------------------------------------------------------

SmitsRay smits_setup(const Ray& r) {
    SmitsRay s;
    s.o = r.o;
    s.inv = Vec3(1.0f / r.d.x, 1.0f / r.d.y, 1.0f / r.d.z);  // 1/+-0 = +-inf
    s.tmax = r.tmax;
    s.cls = ray_class(r.d);
    return s;
}

namespace {

inline float raise_entry(float cur, float cand) { return cand > cur ? cand : cur; }  // NaN: keep
inline float lower_exit(float cur, float cand) { return cand < cur ? cand : cur; }   // NaN: keep

}  // namespace

bool smits_hit(const SmitsRay& r, const Box& b, float* tnear) {
    float t0 = 0.0f;
    float t1 = r.tmax;
    for (int a = 0; a < 3; ++a) {
        const bool neg = class_negative(r.cls, a);
        const float near_plane = neg ? b.hi[a] : b.lo[a];
        const float far_plane = neg ? b.lo[a] : b.hi[a];
        t0 = raise_entry(t0, (near_plane - r.o[a]) * r.inv[a]);
        t1 = lower_exit(t1, (far_plane - r.o[a]) * r.inv[a]);
    }
    if (!(t0 <= t1)) return false;
    if (tnear) *tnear = t0;
    return true;
}

// ---------------------------------------------------------------------------
// pluecker-cls
//
// With n_i the class bit of axis i and D_i = |d_i|, the signed offsets of the
// box planes from the origin, measured along the ray, are
//   A_i = entry plane offset = n_i ? o_i - hi_i : lo_i - o_i
//   B_i = exit plane offset  = n_i ? o_i - lo_i : hi_i - o_i
// The tests (the same as the fixed-point datapath in fixed.hpp):
//   origin test: B_i >= 0 for every axis (the origin is not past an exit
//                plane; Mahovsky & Wyvill's first rejection per class),
//   edge tests:  T_ij = B_j*D_i - A_i*D_j >= 0 for the six ordered pairs
//                i != j. T_ij is, up to the sign fixed by the class, the
//                Plücker side product of the ray with the silhouette edge
//                of the box shared by the entry face of i and the exit face
//                of j; written out for class MMM it is the paper's
//                d_x*(lo_y - o_y) - d_y*(hi_x - o_x) and so on.
//   end test:    when tmax is finite, the segment end e = o + tmax*d is not
//                before any entry plane: G_i = n_i ? hi_i - e_i : e_i - lo_i
//                >= 0.
// A test rejects only on a definite negative value, as the paper's
// `if (... < 0) return false` form does.
// ---------------------------------------------------------------------------

PlueckerRay pluecker_setup(const Ray& r) {
    PlueckerRay p;
    p.o = r.o;
    p.d = r.d;
    p.has_end = std::isfinite(r.tmax);
    p.e = p.has_end ? r.o + r.tmax * r.d : r.o;
    p.cls = ray_class(r.d);
    return p;
}

namespace {

// The class-specialised test: NX, NY, NZ are the class bits, so every
// near/far selection and sign is resolved at compile time, as in the
// paper's eight per-class functions.
template <bool NX, bool NY, bool NZ>
bool pluecker_cls(const PlueckerRay& r, const Box& b) {
    constexpr bool neg[3] = {NX, NY, NZ};
    float A[3], B[3], D[3];
    for (int i = 0; i < 3; ++i) {
        A[i] = neg[i] ? r.o[i] - b.hi[i] : b.lo[i] - r.o[i];
        B[i] = neg[i] ? r.o[i] - b.lo[i] : b.hi[i] - r.o[i];
        D[i] = std::fabs(r.d[i]);
    }
    // Origin test.
    if (B[0] < 0.0f || B[1] < 0.0f || B[2] < 0.0f) return false;
    // Six silhouette-edge tests.
    if (B[1] * D[0] - A[0] * D[1] < 0.0f) return false;  // (x, y)
    if (B[0] * D[1] - A[1] * D[0] < 0.0f) return false;  // (y, x)
    if (B[2] * D[0] - A[0] * D[2] < 0.0f) return false;  // (x, z)
    if (B[0] * D[2] - A[2] * D[0] < 0.0f) return false;  // (z, x)
    if (B[2] * D[1] - A[1] * D[2] < 0.0f) return false;  // (y, z)
    if (B[1] * D[2] - A[2] * D[1] < 0.0f) return false;  // (z, y)
    // Segment end test.
    if (r.has_end) {
        for (int i = 0; i < 3; ++i) {
            const float g = neg[i] ? b.hi[i] - r.e[i] : r.e[i] - b.lo[i];
            if (g < 0.0f) return false;
        }
    }
    return true;
}

}  // namespace

bool pluecker_hit(const PlueckerRay& r, const Box& b) {
    switch (r.cls & 7u) {
        case 0: return pluecker_cls<false, false, false>(r, b);  // PPP
        case 1: return pluecker_cls<true, false, false>(r, b);   // MPP
        case 2: return pluecker_cls<false, true, false>(r, b);   // PMP
        case 3: return pluecker_cls<true, true, false>(r, b);    // MMP
        case 4: return pluecker_cls<false, false, true>(r, b);   // PPM
        case 5: return pluecker_cls<true, false, true>(r, b);    // MPM
        case 6: return pluecker_cls<false, true, true>(r, b);    // PMM
        default: return pluecker_cls<true, true, true>(r, b);    // MMM
    }
}

}  // namespace pluecker
