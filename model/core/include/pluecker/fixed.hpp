// SPDX-License-Identifier: MIT
// The fixed-point Plücker ray/box test: the one definition of the format,
// the ray set-up that feeds the RTL, and the bit-exact datapath.
//
// ---------------------------------------------------------------------------
// Format (COORD_BITS = C, DIR_BITS = D, each 6..24: the port contract's
// limits, contract.hpp)
//
//   coordinate  C-bit two's complement, value = q * 2^-(C-2): the range is
//               the grid [-2, 2 - 2^-(C-2)] (at C = 6: [-2, 1.9375], at
//               C = 16: [-2, 1.99993896]), the scene cube [-1,1] with room
//               for boxes grown by epsilon. Used for box planes, ray origin
//               and segment end. The range cube R = [-2, 2 - 2^-(C-2)]^3
//               (FixedFormat::range_box) holds every box the datapath takes.
//   direction   D-bit unsigned magnitude of d_i / max_k |d_k|, value =
//               q * 2^-(D-1); the largest component is exactly 2^(D-1) (1.0).
//               The sign of every component is carried by the ray class
//               (bit i set = axis i negative, sign bit of the float, so -0
//               is negative). The test is invariant under scaling d > 0.
//
// The range contract (what fixed_setup_ray and fixed_quantize_box take)
//   box     every plane inside R (lo >= -2, hi <= 2 - 2^-(C-2)), in both
//           modes; otherwise InputError naming the axis and the range.
//   ray     any finite origin, any finite non-zero direction (of any
//           magnitude, denormal components included), tmax >= 0 or inf;
//           otherwise InputError. An origin inside R is rounded as it is.
//           An origin outside R is clipped: moved along the ray, exactly,
//           to the point where the segment enters R. A segment that never
//           meets R meets no box of the range: the set-up returns nullopt
//           and the answer is a miss, without a datapath query.
//
// Ray set-up (software, in front of the RTL)
//   class  from the sign bits of d.
//   D_i    |d_i| / m * 2^(D-1) rounded to nearest (exactly, m = max|d_k|).
//   O_i    inside R: o_i * 2^(C-2) rounded to nearest. Outside R: the
//          clip point p = o + t0*d, t0 the exact parameter where the
//          segment enters R (the latest slab entry of R, chosen by exact
//          comparisons), on the entry face exactly the face's plane, every
//          other coordinate the exact rational o_b + (P - o_e) d_b / d_e
//          rounded to nearest (ties to even).
//   E_i    segment end e = o + tmax*d of the ray as given (never of the
//          clipped ray), exact real value; conservative mode: rounded
//          outward along the ray (ceil on positive axes, floor on negative
//          ones); nearest mode: rounded to nearest. When tmax is inf, or
//          any E_i is out of range, the ray is treated as unbounded
//          (has_end = false), which can only add hits. Shortening the
//          segment (closest-hit traversal) re-runs only this step
//          (fixed_setup_end) with the new tmax of the same ray.
//   box    conservative: LO = floor(lo*2^(C-2)), HI = ceil(hi*2^(C-2)), so the
//          quantised box contains the float box; nearest: both to nearest.
//
// Datapath (the RTL computes exactly this; n_i = class bit of axis i)
//   A_i = n_i ? O_i - HI_i : LO_i - O_i     entry plane, along the ray
//   B_i = n_i ? O_i - LO_i : HI_i - O_i     exit plane, along the ray
//   G_i = n_i ? HI_i - E_i : E_i - LO_i     segment end past the entry plane
//   origin test      B_i >= 0 for all i
//   end test         !has_end or G_i >= 0 for all i
//   six edge tests   for the ordered pairs (i, j), i != j:
//                      T_ij = B_j*D_i - A_i*D_j   (entry of slab i no later
//                                                 than exit of slab j)
//                    conservative: 2*T_ij + |A_i| + |B_j| + D_i + D_j + 1 >= 0
//                    nearest:      T_ij >= 0
//   hit = all of them.
//
// Widths (no intermediate can overflow): A, B, G are differences of two C-bit
// values: C+1 bits signed. D_i <= 2^(D-1): D bits unsigned. B*D: C+D+1 bits
// signed; T: C+D+2 bits; |A|+|B|+D_i+D_j+1 <= 2^(C+1)+2^D+1 < 2^(C+D+1);
// 2T + margin: C+D+4 bits signed. At 24/24 that is 52 bits, so int64_t
// holds every value of the model exactly.
//
// Why conservative mode never misses (the margin's bound)
//   Work in LSB units: u_c = 2^-(C-2) for coordinates, u_d = 2^-(D-1) for
//   directions. Let a_i, b_i be the exact entry/exit offsets of the
//   *quantised* box from the exact float origin, and delta_i the exact
//   scaled |d_i|. Rounding to nearest gives A_i = a_i + e_i, B_j = b_j + e'_j
//   with |e|,|e'| <= 1/2 (the origin moved by at most half an LSB) and
//   D_i = delta_i + h_i with |h_i| <= 1/2.
//   1. The float box is inside the quantised box, so a real hit on the float
//      box is a real hit on the quantised box.
//   2. A real hit implies, for every i != j, t_ij = b_j*delta_i - a_i*delta_j
//      >= 0 (slab i is entered no later than slab j is left; this also holds
//      for zero components, where it says a_i <= 0 <= b_i).
//   3. T_ij - t_ij = b_j*h_i + e'_j*D_i - a_i*h_j - e_i*D_j, so
//      |T_ij - t_ij| <= (|b_j| + |a_i|)/2 + (D_i + D_j)/2
//                    <= (|B_j| + |A_i| + 1 + D_i + D_j)/2     (|b| <= |B|+1/2)
//      hence t_ij >= 0 implies 2*T_ij + |A_i| + |B_j| + D_i + D_j + 1 >= 0.
//   4. Origin test: the exit plane lies on the grid and rounding to nearest
//      is monotone, so b_i >= 0 implies B_i >= 0.
//   5. End test: a real hit has t_enter <= tmax, i.e. the exact end point is
//      past every entry plane, which lies on the grid; rounding E outward
//      along the ray keeps it there (and has_end = false drops the test).
//      Rounding to nearest would keep it there too (monotone onto a grid
//      plane, as in step 4); outward is the choice made, so that the
//      quantised segment, like the quantised box, contains the real one
//      whatever the grid: FixedSetup.SegmentEndRoundsOutward pins it.
//   6. The clip. Steps 1-5 use only that O lies within half an LSB of an
//      exact point of the ray's line from which the segment still reaches
//      every hit: the exact origin need not be a float. Every box of the
//      range lies in R, so every real hit of the given segment [0, tmax] is
//      at some t >= t0 (t0 = entry into R); the clip point p = o + t0*d is
//      exact, the segment from p to the same end point e holds every such
//      hit, and O is p rounded to nearest (half an LSB). A segment that
//      misses R (decided by the exact test) has no real hit on any box of
//      the range, so answering "miss" without the datapath loses none.
//   7. Segment shortening. A closest-hit traversal that has found a hit at
//      t shortens the given ray to [0, t] and recomputes E from o + t*d of
//      that ray (step 5 then holds for [0, t]); the clipped origin does not
//      change. No distance is rounded between the user's ray and E.
//   Every test of the datapath is implied by a real hit of the ray as given,
//   from any finite origin: no false misses.
//   False hits remain possible and are counted, never hidden.
// ---------------------------------------------------------------------------
#pragma once

#include "pluecker/contract.hpp"
#include "pluecker/geometry.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace pluecker {

enum class FixedMode { Conservative, Nearest };

struct FixedFormat {
    // The RTL's limits and defaults (the port contract, contract.hpp).
    static constexpr int kMinBits = ContractLimits::kMinBits;
    static constexpr int kMaxBits = ContractLimits::kMaxBits;
    static constexpr int kDefaultCoordBits = ContractDefaults::kCoordBits;
    static constexpr int kDefaultDirBits = ContractDefaults::kDirBits;

    int coord_bits = kDefaultCoordBits;
    int dir_bits = kDefaultDirBits;
    FixedMode mode = FixedMode::Conservative;

    // Throws InputError naming the parameter when a width is outside 6..24.
    void validate() const;
    // Coordinates representable: [coord_min(), coord_max()] as integers.
    std::int64_t coord_min() const { return -(std::int64_t{1} << (coord_bits - 1)); }
    std::int64_t coord_max() const { return (std::int64_t{1} << (coord_bits - 1)) - 1; }
    std::int64_t dir_one() const { return std::int64_t{1} << (dir_bits - 1); }
    // Value of one coordinate LSB, 2^-(C-2), and one direction LSB, 2^-(D-1).
    double coord_lsb() const;
    double dir_lsb() const;
    // The range as float values: coord_lo_value() = -2, coord_hi_value() =
    // 2 - 2^-(C-2) (both exact floats); range_box() is the cube R.
    float coord_lo_value() const;
    float coord_hi_value() const;
    Box range_box() const;
    // "[-2, 1.9375] of COORD_BITS = 6": the range as error messages state it.
    std::string range_text() const;
};

const char* mode_name(FixedMode m);

// The quantised ray, as the RTL receives it.
struct FixedRay {
    RayClass cls = 0;
    std::array<std::int64_t, 3> org{};  // C-bit signed
    std::array<std::int64_t, 3> dir{};  // D-bit unsigned magnitudes
    std::array<std::int64_t, 3> end{};  // C-bit signed, valid when has_end
    bool has_end = false;
    bool clipped = false;  // set-up only: the origin was outside R and moved onto it
};

// The quantised box, as the RTL receives it.
struct FixedBox {
    std::array<std::int64_t, 3> lo{};
    std::array<std::int64_t, 3> hi{};
};

// Ray set-up (the range contract above). Throws InputError for a non-finite
// origin, a zero, NaN or infinite direction, or a negative or NaN tmax.
// Returns nullopt when the segment never meets the range cube R: it then
// meets no box the datapath can take, and the answer is a miss.
std::optional<FixedRay> fixed_setup_ray(const Ray& r, const FixedFormat& f);
// Recomputes the segment end of `out` (set up from a ray with the same o
// and d) for r.tmax: what a closest-hit traversal does when it shrinks the
// segment to its current best hit.
void fixed_setup_end(FixedRay& out, const Ray& r, const FixedFormat& f);
// Box quantisation. Throws InputError when a plane lies outside R.
FixedBox fixed_quantize_box(const Box& b, const FixedFormat& f);
// The bit-exact datapath.
bool fixed_hit(const FixedRay& r, const FixedBox& b, const FixedFormat& f);

// Convenience: set up and test one float query (a miss when the ray never
// meets R; the box is checked either way).
bool fixed_hit(const Ray& r, const Box& b, const FixedFormat& f);

}  // namespace pluecker
