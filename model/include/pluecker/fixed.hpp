// SPDX-License-Identifier: MIT
// The fixed-point Plücker ray/box test: the one definition of the format,
// the ray set-up that feeds the RTL, and the bit-exact datapath.
//
// ---------------------------------------------------------------------------
// Format (COORD_BITS = C, DIR_BITS = D, each 6..24)
//
//   coordinate  C-bit two's complement, value = q * 2^-(C-2), so the range is
//               [-2, 2): the scene cube [-1,1] with room for boxes grown by
//               epsilon. Used for box planes, ray origin and segment end.
//   direction   D-bit unsigned magnitude of d_i / max_k |d_k|, value =
//               q * 2^-(D-1); the largest component is exactly 2^(D-1) (1.0).
//               The sign of every component is carried by the ray class
//               (bit i set = axis i negative, sign bit of the float, so -0
//               is negative). The test is invariant under scaling d > 0.
//
// Ray set-up (software, in front of the RTL)
//   class  from the sign bits of d.
//   D_i    |d_i| / m * 2^(D-1) rounded to nearest (exactly, m = max|d_k|).
//   O_i    o_i * 2^(C-2) rounded to nearest. Out of range -> InputError.
//   E_i    segment end e = o + tmax*d (exact real value), conservative mode:
//          rounded outward along the ray (ceil on positive axes, floor on
//          negative ones); nearest mode: rounded to nearest. When tmax is inf,
//          or any E_i is out of range, the ray is treated as unbounded
//          (has_end = false), which can only add hits.
//   box    conservative: LO = floor(lo*2^(C-2)), HI = ceil(hi*2^(C-2)), so the
//          quantised box contains the float box; nearest: both to nearest.
//          Out of range -> InputError.
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
//      past every entry plane; rounding E outward along the ray keeps it
//      there (and has_end = false drops the test).
//   Every test of the datapath is implied by a real hit: no false misses.
//   False hits remain possible and are counted, never hidden.
// ---------------------------------------------------------------------------
#pragma once

#include "pluecker/geometry.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace pluecker {

enum class FixedMode { Conservative, Nearest };

struct FixedFormat {
    static constexpr int kMinBits = 6;
    static constexpr int kMaxBits = 24;
    static constexpr int kDefaultCoordBits = 16;
    static constexpr int kDefaultDirBits = 16;

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
};

FixedMode parse_fixed_mode(const std::string& s);  // "conservative" | "nearest"
const char* mode_name(FixedMode m);

// The quantised ray, as the RTL receives it.
struct FixedRay {
    RayClass cls = 0;
    std::array<std::int64_t, 3> org{};  // C-bit signed
    std::array<std::int64_t, 3> dir{};  // D-bit unsigned magnitudes
    std::array<std::int64_t, 3> end{};  // C-bit signed, valid when has_end
    bool has_end = false;
};

// The quantised box, as the RTL receives it.
struct FixedBox {
    std::array<std::int64_t, 3> lo{};
    std::array<std::int64_t, 3> hi{};
};

// Ray set-up. Throws InputError for a zero or NaN direction or an origin
// outside the representable range.
FixedRay fixed_setup_ray(const Ray& r, const FixedFormat& f);
// Box quantisation. Throws InputError when the box leaves the range.
FixedBox fixed_quantize_box(const Box& b, const FixedFormat& f);
// The bit-exact datapath.
bool fixed_hit(const FixedRay& r, const FixedBox& b, const FixedFormat& f);

// Convenience: set up and test one float query.
bool fixed_hit(const Ray& r, const Box& b, const FixedFormat& f);

// Half width of the cube that renderer rays are clipped to before set-up:
// inside the representable range [-2, 2) and around every box of a scene
// normalised to [-1, 1] (boxes grown by epsilon).
inline constexpr float kClipHalfWidth = 1.5f;

// Camera and light rays may start outside the representable range. The
// renderer's fixed-point path first moves such an origin forward to where
// the ray enters the cube [-kClipHalfWidth, kClipHalfWidth]^3 (in double,
// then rounded to float) and shortens tmax to match (rounded up). Returns the
// ray unchanged when its origin is already inside, and nullopt when the ray
// (or segment) never reaches the cube: it can then hit no box of the scene.
// The clipped ray is the query the fixed-point test answers; the no-miss
// guarantee above holds with respect to it.
struct ClippedRay {
    Ray ray;
    float t0 = 0.0f;  // distance along the original ray where `ray` starts
};
std::optional<ClippedRay> fixed_clip_ray(const Ray& r);

}  // namespace pluecker
