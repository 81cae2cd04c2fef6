// SPDX-License-Identifier: MIT
// Ternary answers of the fixed-point test: certain miss, certain hit or
// uncertain, and the cascade that re-tests the uncertain ones on a wider
// format. The RTL computes the same (rtl/pluecker_intersector.sv with
// TERNARY = 1: out_hit_o, out_strict_o; rtl/pluecker_cascade.sv).
//
// ---------------------------------------------------------------------------
// The tests (conservative mode only; fixed.hpp's notation, n_i the class bit)
//   conservative  fixed_hit: B_i >= 0, the end test G_i >= 0 (when has_end),
//                 and for the six ordered pairs i != j
//                   2*T_ij + M_ij >= 0,   M_ij = |A_i| + |B_j| + D_i + D_j + 1
//   strict        B_i >= 2 for all i, G_i >= 2 for all i (when has_end), and
//                   2*T_ij - M_ij - 2*(D_i + D_j + 1) >= 0
//   answer        conservative fails            -> Miss      (certain miss)
//                 conservative and strict pass  -> Hit       (certain hit)
//                 only the conservative passes  -> Uncertain
//   The strict test implies the conservative one term by term (M >= 0,
//   D_i + D_j + 1 > 0), so the three cases are exhaustive.
//
// Why a certain miss has no real hit: it is a miss of fixed_hit, and
// fixed.hpp proves that every test of fixed_hit is implied by a real hit.
//
// Why a certain hit is a real hit of the float box
//   Work in LSB units as fixed.hpp does, in the frame mirrored by the class
//   (every axis positive), for the ray the set-up quantised: origin o (the
//   given origin, or the exact clip point of fixed.hpp step 6, which lies on
//   the given ray at a parameter t0 >= 0), exact scaled direction delta_i >= 0,
//   float box [lo_i, hi_i] (nonempty: lo_i <= hi_i), exact segment end
//   x = o + s_end*delta when has_end (delta is a positive multiple of the
//   float direction, so the ray's points are o + s*delta, s >= 0). The
//   set-up gives
//     O_i = o_i + e_i,  |e_i| <= 1/2   (origin rounded to nearest)
//     D_i = delta_i + h_i, |h_i| <= 1/2 (direction rounded to nearest)
//     LO_i <= lo_i < LO_i + 1,  HI_i - 1 < hi_i <= HI_i  (box rounded outward)
//     E_i - 1 < x_i <= E_i             (end rounded outward along the ray)
//   with A_i = LO_i - O_i, B_i = HI_i - O_i, G_i = E_i - LO_i mirrored (the
//   mirror flips the sign of e_i on negative axes; only |e_i| <= 1/2 is used).
//
//   0. What a real hit is. Let a_i = lo_i - o_i, b_i = hi_i - o_i (the float
//      box's entry and exit offsets from the exact origin), g_i = x_i - lo_i,
//      t_ij = b_j*delta_i - a_i*delta_j. If
//        (1) b_i >= 0 for all i, (2) g_i >= 0 for all i (when has_end), and
//        (3) t_ij >= 0 for all i != j,
//      the segment meets the float box. For the axes with delta_i > 0 the
//      slab is crossed on [a_i/delta_i, b_i/delta_i], nonempty since
//      lo_i <= hi_i; (3) says every entry is no later than every exit, (1)
//      that every exit is at s >= 0, (2) that every entry is at s <= s_end.
//      An axis with delta_i = 0 holds the whole ray in its slab: (3) with
//      the largest component delta_j > 0 gives -a_i*delta_j >= 0, so
//      a_i <= 0, and (1) gives b_i >= 0. So the parameter interval
//      [max(0, entries), min(s_end, exits)] is not empty. From a clipped
//      origin the segment is part of the given one (t0 >= 0, same end), so
//      its hit is a hit of the ray as given.
//   1. Origin: b_i = hi_i - O_i + e_i > HI_i - 1 - O_i - 1/2 = B_i - 3/2, so
//      B_i >= 2 gives b_i > 1/2 > 0: (1).
//   2. End: g_i = x_i - lo_i > (E_i - 1) - (LO_i + 1) = G_i - 2, so G_i >= 2
//      gives g_i > 0: (2). Without an end (has_end false) the set-up either
//      had tmax = inf, or found the exact end point outside the range cube R
//      (rounding outward keeps a point of R inside R, whose bounds are grid
//      values, so a rounded end outside R comes from an exact end outside
//      R). The segment starts in R (o, or the clip point on R's surface), R
//      is convex, so once the ray has left R it never comes back: every
//      point of the unbounded ray inside R, hence inside any box of the
//      range, is on the segment. Dropping the end drops no condition.
//   3. Pairs. Take the box shrunk inward by one LSB per plane, in grid
//      values LO_i + 1 and HI_i - 1, and its offsets from the exact origin
//        a'_i = LO_i + 1 - o_i = A'_i + e_i,  b'_j = HI_j - 1 - o_j = B'_j + e_j
//      with A'_i = A_i + 1, B'_j = B_j - 1 (integers). Since lo_i < LO_i + 1
//      and hi_j > HI_j - 1: a_i < a'_i and b_j > b'_j, and with delta >= 0
//        t_ij >= t'_ij = b'_j*delta_i - a'_i*delta_j.
//      (The shrunk box may be empty; only these inequalities are used, and
//      step 0 is applied to the float box.) Expanding with
//      T'_ij = B'_j*D_i - A'_i*D_j (fixed.hpp step 3, with b'_j = B'_j + e_j,
//      a'_i = A'_i + e_i):
//        T'_ij - t'_ij = b'_j*h_i - a'_i*h_j - e_j*D_i + e_i*D_j
//        |T'_ij - t'_ij| <= (|b'_j| + |a'_i| + D_i + D_j)/2
//                        <= (|B'_j| + |A'_i| + 1 + D_i + D_j)/2 = M'_ij/2,
//      so 2*T'_ij - M'_ij >= 0 gives t'_ij >= 0, hence t_ij >= 0: (3). Now
//        T'_ij = T_ij - D_i - D_j,  M'_ij = |A_i + 1| + |B_j - 1| + D_i + D_j + 1
//                                       <= M_ij + 2,
//      so 2*T'_ij - M'_ij >= 2*T_ij - M_ij - 2*(D_i + D_j + 1): the strict
//      pair test implies 2*T'_ij - M'_ij >= 0.
//   With (1), (2) and (3) step 0 gives a real hit of the float box by the
//   segment of the ray as given: a certain hit is never a false hit.
//
// The cascade (cascade_answer): a narrow format answers first; its Miss and
// Hit stand, its Uncertain is re-tested by the conservative test of a wide
// format on the same float ray and box (each format sets the query up from
// the floats itself). Every branch is implied by a real hit or implies one,
// so the cascade never misses a real hit: a narrow Miss has no real hit, a
// narrow Hit is one, and the wide conservative test misses no real hit
// (fixed.hpp). The cascade's false hits are the wide test's false hits on
// the uncertain queries.
// ---------------------------------------------------------------------------
#pragma once

#include "pluecker/fixed.hpp"
#include "pluecker/geometry.hpp"

#include <cstdint>

namespace pluecker {

enum class TernaryAnswer : std::uint8_t { Miss = 0, Uncertain = 1, Hit = 2 };

const char* ternary_name(TernaryAnswer a);

// The strict test alone (bit-exact with out_strict_o). Throws InputError
// unless f is in conservative mode.
bool fixed_strict_hit(const FixedRay& r, const FixedBox& b, const FixedFormat& f);
// The ternary answer (out_hit_o, out_strict_o of the RTL). Throws InputError
// unless f is in conservative mode.
TernaryAnswer fixed_ternary(const FixedRay& r, const FixedBox& b, const FixedFormat& f);
// Convenience: set up and test one float query (a Miss when the ray never
// meets the range cube R).
TernaryAnswer fixed_ternary(const Ray& r, const Box& b, const FixedFormat& f);

// A narrow ternary format and a wide conservative one (both conservative;
// InputError otherwise).
struct CascadeFormats {
    FixedFormat narrow;
    FixedFormat wide;
    void validate() const;
};

// One query through the cascade: the narrow answer, and whether it was
// escalated to the wide test.
struct CascadeAnswer {
    bool hit = false;
    TernaryAnswer narrow = TernaryAnswer::Miss;
    bool escalated() const { return narrow == TernaryAnswer::Uncertain; }
};
CascadeAnswer cascade_answer(const Ray& r, const Box& b, const CascadeFormats& f);
// The same on queries set up by the caller at both widths (as the RTL gets
// them).
CascadeAnswer cascade_answer(const FixedRay& narrow_ray, const FixedBox& narrow_box, const FixedRay& wide_ray,
                             const FixedBox& wide_box, const CascadeFormats& f);

}  // namespace pluecker
