// SPDX-License-Identifier: MIT
// Local frames: the Plücker ray/box test with every box stored as K-bit
// offsets in a frame of its own size, so that the width a box test needs no
// longer depends on the size of the scene. The one definition of the local
// format, the per-ray and per-node set-up that feed the child unit, and the
// bit-exact child datapath (rtl/pluecker_local_intersector.sv).
//
// ---------------------------------------------------------------------------
// Why moments. The edge tests of the global datapath (fixed.hpp) are, for
// the pair (i, j) of axes,
//     t_ij = b_j*d_i - a_i*d_j = ext_j*d_i - ent_i*d_j + (o_i*d_j - o_j*d_i)
// with ent/ext the entry/exit planes along the ray and a = ent - o, b =
// ext - o. The last term is the ray's Plücker moment about the origin of
// the coordinates: it alone carries the ray's position, and it changes by
// a cross product when the coordinates move. In a frame of the node, the
// box terms are small (K bits); the moment about the frame origin is
// computed once per node from the ray held at the global width G, rounded
// to the frame's units and clamped where it decides the test alone. The
// per-child products are then K-bit box offsets times a D-bit direction,
// narrow in both operands, whatever the distance from the ray's origin to
// the node (Mahovsky & Wyvill, JGT 9(1) 2004, for the edge tests; Mahovsky's
// PhD thesis, Calgary 2005, and Mahovsky & Wyvill, CGF 25(2) 2006, for
// boxes stored as integers relative to their parent).
//
// Format (LocalFormat)
//   K = box_bits   4..16  child box planes: unsigned offsets 0..2^K - 1 in
//                         the frame's cells
//   D = dir_bits   4..24  local direction: unsigned magnitudes, the largest
//                         at most 2^(D-1)
//   G = grid_bits  K+2..48  the global grid: coordinates q * 2^-(G-2) in
//                         [-2, 2) (a G-bit two's complement integer q), for
//                         the ray's origin and end and the frame origins;
//                         the ray's global direction at G bits (the largest
//                         component = 2^(G-1))
//   mode           conservative (never misses) or nearest (no margin)
//
// Frame (LocalFrame): origin F (a point of the global grid) and a power-of-
// two cell per axis, s_i = 2^e_i grid units, 0 <= e_i <= G - K + 1 (at
// G - K + 1 the 2^K - 1 cells span twice the grid, so any box of the range
// fits one frame, wherever its lo lies). It spans
// [F_i, F_i + (2^K - 1) s_i] on axis i; a box in it is LO_i, HI_i in
// 0..2^K - 1, rounded outward (conservative) or to nearest.
//
// The ray (LocalRay, once per ray, the range contract of fixed.hpp on the
// global grid): class; the origin O on the grid (rounded to nearest, or, for
// an origin outside the grid's float range, clipped exactly onto it and
// rounded); the segment end E on the grid (outward along the ray, or none);
// the global direction DG_i = round(|d_i| / m * 2^(G-1)), m = max |d_k|.
//
// The node ray (LocalNodeRay, once per ray and node: what the child datapath
// receives with each child box of the node), computed from the ray's
// G-bit values alone. Mirrored coordinates make the direction positive on
// every axis: with n_i the class bit of axis i, the mirrored frame origin is
// F~_i = n_i ? F_i + S_i : F_i, S_i = (2^K - 1) 2^e_i (the frame's extent in
// grid units), and a mirrored offset is x' = sigma_i (x - F~_i), sigma_i =
// n_i ? -1 : 1, so the frame still spans 0..2^K - 1 cells and a box's entry
// and exit planes are
//     ent_i = n_i ? (2^K - 1) - HI_i : LO_i,  ext_i = n_i ? (2^K - 1) - LO_i : HI_i
// (for n_i a bitwise NOT of the K-bit plane). Per node, from the ray and
// the frame:
//   Delta_i = sigma_i (O_i - F~_i)              origin offset, grid units
//   ORG_i = clamp(round(Delta_i / 2^e_i), -1, 2^K)            local origin
//   END_i = clamp(ceil(sigma_i (E_i - F~_i) / 2^e_i), -1, 2^K)  (nearest
//           mode: round) local segment end, when the ray has one
//   c = min over the axes with DG_i != 0 of c_i:  c_i = e_i when DG_i =
//           2^(G-1), else e_i + G - 1 - bitlen(DG_i); then every
//           DG_i 2^(c - e_i) < 2^(G-1), or = 2^(G-1) on the largest
//           component when the cells are equal
//   DIR_i = round(DG_i * 2^(c - e_i + D - G))      local direction, <= 2^(D-1)
//   for the ordered pairs (i, j), i != j, in the RTL's order k = 0..5:
//           (0,1) (0,2) (1,2) (1,0) (2,0) (2,1)
//     lambda_ij = Delta_i*DG_j - Delta_j*DG_i          exact moment, grid units
//     sh_ij = G + e_i + e_j - c - D
//     L_ij = round(lambda_ij / 2^sh_ij)                 in local units
//     mu_ij = ceil((|Delta_i| + |Delta_j| + S_i + S_j + DG_i + DG_j + 1) / 2^(sh_ij + 1))
//     W_ij = conservative: 2 L_ij + 2 mu_ij + 1;  nearest: 2 L_ij
//            clamped to [-W_LIM - 2^(K+1) + 1, W_LIM], W_LIM = (2^K - 1) 2^D
//   Roundings: to nearest, ties to even; ceil/round of exact quotients.
//   Widths of the node set-up (every value exact): O, E, F: G bits signed;
//   S_i < 2^(G+1); |Delta_i| < 2^(G-1) + 2^(G-1) + 2^(G+1) < 2^(G+2): G + 3
//   bits signed; DG <= 2^(G-1): G bits unsigned; |lambda| < 2^(2G+2): 2G + 3
//   bits signed; the mu numerator < 2^(G+4); 0 <= c <= G - K + 1 (the largest
//   component has DG = 2^(G-1)), so K - D - 1 <= sh_ij <= 3G - 2K + 2 - D.
//
// The child datapath (local_hit; the RTL computes exactly this)
//   origin test   ext_i - ORG_i >= 0 for all i
//   end test      no end, or END_i - ent_i >= 0 for all i
//   edge tests    V_ij = 2 (ext_j*DIR_i - ent_i*DIR_j) + M_ij + W_ij >= 0,
//                 M_ij = ext_j + ent_i (conservative), 0 (nearest)
//   hit = all of them.
//   Widths: ent, ext K bits; DIR D bits (<= 2^(D-1)); products K + D - 1
//   bits; |2 X| <= (2^K - 1) 2^D; W and V: K + D + 2 bits signed.
//
// Why conservative mode never misses. Units: cells of each axis for
// coordinates, 2^-(D-1) for the local direction (after the node's scaling
// by 2^(c - e_i)), and their products for moments.
//   1. The frame's box contains the float box (outward rounding), so a real
//      hit of the ray as given on the float box is a real hit on the frame's
//      box; as in fixed.hpp (steps 6-7) the ray starts at its origin or at
//      the exact clip point p (every hit of a box of the range is at t >= t0)
//      and ends at its exact end.
//   2. In mirrored cells the exact ray has origin o' and direction
//      delta'_i = |d_i| / m * 2^(c - e_i + D - 1) >= 0 (local units). A real hit gives,
//      for every i != j (zero components included, as in fixed.hpp step 2),
//          t_ij = ext_j delta'_i - ent_i delta'_j + l_ij >= 0,
//          l_ij = o'_i delta'_j - o'_j delta'_i
//      (t_ij is (b_j d_i - a_i d_j) m^-1 2^(c + D - 1) / (s_i s_j) in grid
//      units: a positive multiple of the real edge value).
//   3. The datapath computes T_ij = ext_j DIR_i - ent_i DIR_j + L_ij. The
//      exact global direction in grid units is DG_i + g_i, |g_i| <= 1/2 (DG
//      rounded to nearest), so delta'_i = (DG_i + g_i) 2^(c - e_i + D - G)
//      and DIR_i = delta'_i + h_i with |h_i| <= 1/2 + |beta_i|, beta_i =
//      g_i 2^(c - e_i + D - G) (DIR rounds DG's scaled value). Then
//        T_ij - t_ij = ext_j h_i - ent_i h_j + (L_ij - lambda_ij 2^-sh)
//                      + (lambda_ij 2^-sh - l_ij).
//      The first two are at most (ext_j + ent_i)/2 + (2^K - 1)(|beta_i| +
//      |beta_j|), the rounding of L at most 1/2. For the last, lambda 2^-sh =
//      o^_i d^_j - o^_j d^_i with o^_i = Delta_i 2^-e_i = o'_i + alpha_i,
//      |alpha_i| <= 2^-(e_i + 1) (O is the exact origin rounded to nearest
//      on the grid), and d^_j = DG_j 2^(c - e_j + D - G) = delta'_j - beta_j:
//        lambda 2^-sh - l_ij = -o'_i beta_j + alpha_i d^_j + o'_j beta_i - alpha_j d^_i.
//      With |o'_i| <= (|Delta_i| + 1/2) 2^-e_i, each term is at most
//      2^-(sh+1) times (|Delta_i| + 1/2), DG_j, (|Delta_j| + 1/2), DG_i; and
//      (2^K - 1)(|beta_i| + |beta_j|) <= (S_i + S_j) 2^-(sh+1) (as
//      2^(c - e_i + D - G) = 2^(e_j - sh)). In all
//        |T_ij - t_ij| <= (ext_j + ent_i + 1)/2
//                         + (|Delta_i| + |Delta_j| + S_i + S_j + DG_i + DG_j + 1) 2^-(sh+1),
//      and the last term is at most mu_ij. So t_ij >= 0 implies
//        2 T_ij + ext_j + ent_i + 1 + 2 mu_ij >= 0, which is V_ij >= 0.
//      (DIR_i <= 2^(D-1): by the choice of c, DG_i 2^(c - e_i) is at most
//      2^(G-1) - 2^(G-1-bitlen(DG_i)) below the top, or exactly 2^(G-1).)
//   4. Clamping W keeps every outcome: for any K-bit planes and DIR <=
//      2^(D-1), |2 (ext_j DIR_i - ent_i DIR_j)| <= W_LIM and 0 <= M <=
//      2^(K+1) - 2, so W >= W_LIM passes and W < -W_LIM - 2^(K+1) + 2
//      fails whatever the box.
//   5. Origin test: a real hit has o'_i <= ext_i. If e_i = 0, ORG_i = Delta_i
//      is the exact origin rounded to nearest, and rounding is monotone with
//      ext_i an integer; if e_i >= 1, o^_i <= ext_i + 1/4, which rounds to at
//      most ext_i. Clamping to [-1, 2^K] keeps the outcome for ext in
//      0..2^K - 1.
//   6. End test: a real hit has the exact end past every entry plane,
//      e'_i >= ent_i; E is rounded outward on the grid and END outward again
//      (ceil in mirrored cells), so END_i >= e'_i >= ent_i; the clamp keeps
//      the outcome.
//   Every test of the child datapath is implied by a real hit of the float
//   ray on the float box: no false misses. mu_ij is what the global width G
//   costs: about (distance from the origin to the far side of the frame) /
//   (cell size * 2^(G-D)), below one unit unless the node's cells come
//   within 2^(G-D) of the grid's resolution times that distance.
// ---------------------------------------------------------------------------
#pragma once

#include "pluecker/fixed.hpp"
#include "pluecker/geometry.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace pluecker {

struct LocalFormat {
    static constexpr int kMinBoxBits = 4, kMaxBoxBits = 16;
    static constexpr int kMinDirBits = 4, kMaxDirBits = 24;
    static constexpr int kMaxGridBits = 48;

    int box_bits = 8;    // K
    int dir_bits = 11;   // D
    int grid_bits = 32;  // G
    FixedMode mode = FixedMode::Conservative;

    // Throws InputError naming the parameter when a value is out of range
    // (K 4..16, D 4..24, G K+2..48).
    void validate() const;
    // The largest box offset, 2^K - 1.
    std::int64_t box_max() const { return (std::int64_t{1} << box_bits) - 1; }
    // The largest frame exponent, G - K + 1: its 2^K - 1 cells span
    // (2^K - 1) 2^(G-K+1) > 2^G grid units, so every box of the range fits.
    int max_exp() const { return grid_bits - box_bits + 1; }
    // The clamp of W: W_LIM = (2^K - 1) 2^D and the lower end -W_LIM - 2^(K+1) + 1.
    std::int64_t w_max() const;
    std::int64_t w_min() const;
    // The global grid: integers [-2^(G-1), 2^(G-1) - 1].
    std::int64_t grid_min() const { return -(std::int64_t{1} << (grid_bits - 1)); }
    std::int64_t grid_max() const { return (std::int64_t{1} << (grid_bits - 1)) - 1; }
    // The float range of box planes and of origins taken as they are:
    // [-2, 2 - 2^-min(G-2, 23)] per axis; its text for error messages.
    Box range_box() const;
    std::string range_text() const;
};

// A node's frame: origin on the global grid, cell 2^exp[i] grid units per axis.
struct LocalFrame {
    std::array<std::int64_t, 3> origin{};
    std::array<int, 3> exp{};
    bool operator==(const LocalFrame&) const = default;
};

// A box as K-bit offsets in a frame.
struct LocalBox {
    std::array<std::int64_t, 3> lo{};
    std::array<std::int64_t, 3> hi{};
    bool operator==(const LocalBox&) const = default;
};

// The ray at the global width, set up once.
struct LocalRay {
    RayClass cls = 0;
    std::array<std::int64_t, 3> org{};    // G grid
    std::array<std::int64_t, 3> dir_g{};  // DG, largest = 2^(G-1)
    std::array<std::int64_t, 3> end{};    // G grid, valid when has_end
    bool has_end = false;
    bool clipped = false;
};

// The ray in one node's frame: the child unit's ray operands.
struct LocalNodeRay {
    RayClass cls = 0;
    std::array<std::int64_t, 3> dir{};  // D bits
    std::array<std::int64_t, 6> w{};    // W_ij in pair order k = 0..5, K + D + 2 bits signed
    std::array<std::int64_t, 3> org{};  // -1..2^K
    std::array<std::int64_t, 3> end{};  // -1..2^K, valid when has_end
    bool has_end = false;
    bool operator==(const LocalNodeRay&) const = default;
};

// The pair order of the six edge tests (as the RTL's pair_i, pair_j).
inline constexpr int local_pair_i(int k) { return k / 2; }
inline constexpr int local_pair_j(int k) { return (k / 2 + 1 + k % 2) % 3; }

// Ray set-up on the global grid (the range contract of fixed.hpp at G
// bits). Throws InputError for a non-finite origin, a zero, NaN or infinite
// direction, a negative or NaN tmax. nullopt when the segment never meets
// the grid's float range: it meets no box the datapath can take.
std::optional<LocalRay> local_setup_ray(const Ray& r, const LocalFormat& f);
// Recomputes the segment end for r.tmax (closest-hit shrinking).
void local_setup_end(LocalRay& out, const Ray& r, const LocalFormat& f);

// Throws InputError when the frame is not a frame of the format (an
// exponent outside 0..G-K+1, an origin off the grid).
void check_frame(const LocalFrame& fr, const LocalFormat& f);
// The box in the frame, rounded outward (conservative) or to nearest.
// Throws InputError when a plane lies outside the format's range or the
// box does not fit the frame.
LocalBox local_quantize_box(const Box& b, const LocalFrame& fr, const LocalFormat& f);
// The tightest frame of the format holding the box: per axis the smallest
// exponent (uniform: the smallest common one) with which the box fits,
// origin the box's lo rounded down to that cell. Throws InputError for a
// box outside the range.
LocalFrame local_frame_for(const Box& b, const LocalFormat& f, bool uniform = false);

// The frame of a child node, from its parent's frame and the child's box
// there (`qchild`, local_quantize_box of `child` in `parent`, rounded outward
// whatever the mode, so that the child fits its own frame): the origin
// is the child's quantised lo corner in the parent's grid, exactly F_i +
// LO_i 2^e_i (so a node stores no origin, only its exponents), and per
// axis the smallest exponent e <= the parent's with which the child's float
// box fits from that origin (uniform: the largest of the three).
LocalFrame local_child_frame(const Box& child, const LocalFrame& parent, const LocalBox& qchild,
                             const LocalFormat& f, bool uniform = false);

// The node ray of `r` in frame `fr`.
LocalNodeRay local_node_ray(const LocalRay& r, const LocalFrame& fr, const LocalFormat& f);
// The bit-exact child datapath.
bool local_hit(const LocalNodeRay& r, const LocalBox& b, const LocalFormat& f);

// Convenience: one float query in the tightest frame of its box.
bool local_hit(const Ray& r, const Box& b, const LocalFormat& f);

}  // namespace pluecker
