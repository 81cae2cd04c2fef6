// SPDX-License-Identifier: MIT
// The binary32 units of the RTL, bit for bit: the adder/subtractor, the
// multiplier and the comparators (rtl/pluecker_f32_*.sv) and the two float
// box tests built from them, rtl/pluecker_float_intersector.sv (the Plücker
// test in the operation order of pluecker_hit) and
// rtl/pluecker_smits_intersector.sv (the slab test of smits_hit).
//
// Everything here is integer code on IEEE-754 binary32 bit patterns; the
// host's floating point is never used on this path (it is the separate
// reference the tests compare against).
//
// ---------------------------------------------------------------------------
// The format (every choice below is what the RTL does)
//   Rounding        each add/sub and mul is rounded once, from its exact
//                   result: Round::Nearest is round to nearest, ties to even
//                   (IEEE-754 roundTiesToEven); Round::Up / Round::Down are
//                   roundTowardPositive / roundTowardNegative (the
//                   conservative Plücker unit's bounds).
//   Denormals       flushed. A subnormal operand of add/sub/mul is read as
//                   zero of its sign (Nearest), or, under directed rounding,
//                   as whichever of {zero of its sign, 2^-126 of its sign}
//                   moves the result in the rounding direction, so that a
//                   bound stays a bound. A result whose magnitude, rounded
//                   with an unbounded exponent, is below 2^-126 becomes
//                   zero of its sign (Nearest) or, under directed rounding,
//                   the neighbour of the exact value in the rounding
//                   direction among {0, +-2^-126}. IEEE-754 would keep
//                   subnormals (gradual underflow): results differ from the
//                   host only where an operand or a result of an add or mul
//                   is below 2^-126 in magnitude.
//   Overflow        as IEEE-754: +-inf when rounding away from zero (always
//                   under Nearest), else +-FLT_MAX.
//   Infinities      as IEEE-754 (inf - inf and 0 * inf are NaN).
//   NaN             any NaN operand or invalid operation gives the one NaN
//                   kNaN (0x7fc00000); payloads and signs of NaNs are not
//                   kept (only comparisons read a NaN, and they are false).
//   Signed zeros    as IEEE-754: x + (-x) and (+0) + (-0) are +0 (-0 under
//                   Round::Down), a product's sign is the XOR of the signs.
//   Comparisons     lt/le are the IEEE-754 comparisons on the bit patterns,
//                   subnormals included (no flushing: a comparator needs
//                   none): -0 == +0, NaN compares false.
//
// The units compare instead of subtracting where the model subtracts only
// to test a sign: for binary floats with gradual underflow,
// fl(x - y) < 0 is exactly x < y (x - y rounds to zero only when x == y, a
// rounded difference keeps the sign, inf - inf is NaN and inf < inf is
// false), so the origin, end and edge tests of pluecker_hit are computed as
// the comparisons B_i: hi < o, G_i: e < lo, T_ij: B_j*D_i < A_i*D_j, which
// is the host's answer for those steps, subnormal differences included.
// ---------------------------------------------------------------------------
#pragma once

#include "pluecker/geometry.hpp"

#include <array>
#include <cstdint>

namespace pluecker {
namespace f32 {

using Bits = std::uint32_t;

enum class Round { Nearest, Up, Down };

inline constexpr Bits kNaN = 0x7fc00000u;
inline constexpr Bits kSignBit = 0x80000000u;
inline constexpr Bits kMinNormal = 0x00800000u;  // 2^-126
inline constexpr Bits kMaxFinite = 0x7f7fffffu;  // FLT_MAX
inline constexpr Bits kInf = 0x7f800000u;

Bits bits_of(float x);
float float_of(Bits b);

bool is_nan(Bits x);
bool is_subnormal(Bits x);

// The RTL's primitives (pluecker_f32_add with SUB = 0/1, pluecker_f32_mul,
// pluecker_f32_cmp), as specified above.
Bits add(Bits a, Bits b, Round r = Round::Nearest);
Bits sub(Bits a, Bits b, Round r = Round::Nearest);  // add(a, -b)
Bits mul(Bits a, Bits b, Round r = Round::Nearest);
bool lt(Bits a, Bits b);  // a < b
bool le(Bits a, Bits b);  // a <= b

// An exact magnitude of up to 128 bits (GCC and Clang's extension type).
__extension__ typedef unsigned __int128 Mag;

// The RTL's round-and-pack step (rtl/pluecker_f32_round.sv): the value
// sign * mag * 2^exp2 (mag > 0) rounded to binary32 as above. Exposed for
// the tests.
Bits round_pack(bool sign, Mag mag, int exp2, Round r);

}  // namespace f32

// ---------------------------------------------------------------------------
// The Plücker float unit (rtl/pluecker_float_intersector.sv)
//
// Its query, as the ports carry it: IEEE binary32 bit patterns of the
// origin, the direction (the unit uses |d_i|: the sign bit is cleared; the
// class port alone selects the planes), the segment end and the box planes,
// x in field 0. Every pattern is taken (NaN, inf, subnormals, lo > hi).
//
// Per axis i with class bit n_i, as pluecker_hit:
//   A_i = n_i ? o_i - hi_i : lo_i - o_i       add/sub, rounded (Down when conservative)
//   B_i = n_i ? o_i - lo_i : hi_i - o_i       add/sub, rounded (Up when conservative)
//   D_i = |d_i|
//   reject when  B_i < 0            compared as (n_i ? o_i < lo_i : hi_i < o_i)
//                G_i < 0 (has_end)  compared as (n_i ? hi_i < e_i : e_i < lo_i)
//                B_j*D_i - A_i*D_j < 0 for the six pairs i != j, compared as
//                mul(B_j, D_i) < mul(A_i, D_j) (products rounded Up and Down
//                when conservative)
// hit = no test rejects.
//
// conservative = false: round to nearest even, the same operations as
// pluecker_hit (the float model). conservative = true: every A_i, B_i and
// product rounded outward (A down, B up, B_j*D_i up, A_i*D_j down) and the
// segment end rounded outward along the ray by the set-up, so that an edge
// or end test rejects only when the exact value of the float query does:
// the unit never misses a real hit (the premise being that of fixed.hpp: a
// real hit passes every exact test).
// ---------------------------------------------------------------------------
struct F32PlueckerQuery {
    RayClass cls = 0;
    std::array<f32::Bits, 3> org{}, dir{}, end{};
    bool has_end = false;
    std::array<f32::Bits, 3> lo{}, hi{};
};

// The set-up of a float query for the unit: pluecker_setup's class, origin,
// direction and segment end (e = o + tmax*d rounded to nearest by the host
// float model, has_end when tmax is finite); conservative = true rounds
// each e_i exactly outward instead: up when class bit i is 0, down when it
// is 1 (computed exactly from the float o, d, tmax; +-inf on overflow).
F32PlueckerQuery f32_pluecker_query(const Ray& r, const Box& b, bool conservative);
bool f32_pluecker_hit(const F32PlueckerQuery& q, bool conservative);
bool f32_pluecker_hit(const Ray& r, const Box& b, bool conservative);

// ---------------------------------------------------------------------------
// The slab float unit (rtl/pluecker_smits_intersector.sv): smits_hit with
// the inverse direction from the set-up (smits_setup, host float 1/d).
//   per axis a: near = n_a ? hi_a : lo_a, far = n_a ? lo_a : hi_a
//               tn = mul(sub(near, o_a), inv_a), tf = mul(sub(far, o_a), inv_a)
//               t0 = lt(t0, tn) ? tn : t0     (starting from +0; a NaN tn
//               t1 = lt(tf, t1) ? tf : t1      or tf leaves the bound alone)
//   (t1 starts at tmax), hit = le(t0, t1); round to nearest even.
// ---------------------------------------------------------------------------
struct F32SmitsQuery {
    RayClass cls = 0;
    std::array<f32::Bits, 3> org{}, inv{};
    f32::Bits tmax = 0;
    std::array<f32::Bits, 3> lo{}, hi{};
};

F32SmitsQuery f32_smits_query(const Ray& r, const Box& b);
bool f32_smits_hit(const F32SmitsQuery& q);
bool f32_smits_hit(const Ray& r, const Box& b);

}  // namespace pluecker
