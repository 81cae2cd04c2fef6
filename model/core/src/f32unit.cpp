// SPDX-License-Identifier: MIT
// The binary32 units of the RTL in integer code (f32unit.hpp): each
// operation computes its exact result and rounds it once (round_pack), an
// implementation independent of the RTL's pipelined one, so that the
// RTL-versus-model comparisons check one against the other.
#include "pluecker/f32unit.hpp"

#include "pluecker/boxtest.hpp"

#include <bit>
#include <cmath>

namespace pluecker {
namespace f32 {
namespace {

using u128 = Mag;

constexpr int kFracBits = 23;
constexpr Bits kFracMask = (Bits{1} << kFracBits) - 1;
constexpr int kExpMax = 255;
constexpr int kBias = 127;

bool sign_of(Bits x) { return (x & kSignBit) != 0; }
int exp_of(Bits x) { return static_cast<int>((x >> kFracBits) & 0xffu); }
Bits frac_of(Bits x) { return x & kFracMask; }
bool is_inf(Bits x) { return (x & ~kSignBit) == kInf; }
bool is_zero(Bits x) { return (x & ~kSignBit) == 0; }
Bits with_sign(Bits magnitude, bool sign) { return sign ? (magnitude | kSignBit) : magnitude; }

// True when rounding in direction r moves a value of this sign away from
// zero (Nearest: never by this rule).
bool away_from_zero(Round r, bool sign) { return (r == Round::Up && !sign) || (r == Round::Down && sign); }

// A subnormal operand flushed: 2^-126 of its sign when `grow` (its
// magnitude rounded up helps the rounding direction), else zero of its sign.
Bits flush_operand(Bits x, bool grow) { return with_sign(grow ? kMinNormal : 0u, sign_of(x)); }

// An add operand: a subnormal moves in the rounding direction (to the
// neighbour among 0 and +-2^-126 on that side; Nearest: to zero).
Bits add_operand(Bits x, Round r) {
    return is_subnormal(x) ? flush_operand(x, away_from_zero(r, sign_of(x))) : x;
}

// The significand (hidden bit included) and the biased exponent of a
// normal number: value = m * 2^(e - 150).
std::uint32_t significand(Bits x) { return frac_of(x) | (Bits{1} << kFracBits); }

// A result below 2^-126 in magnitude, flushed (see f32unit.hpp).
Bits tiny_result(bool sign, Round r) { return with_sign(away_from_zero(r, sign) ? kMinNormal : 0u, sign); }

// A result beyond FLT_MAX.
Bits overflow_result(bool sign, Round r) {
    const bool to_inf = r == Round::Nearest || away_from_zero(r, sign);
    return with_sign(to_inf ? kInf : kMaxFinite, sign);
}

int msb_index(u128 v) {
    const auto hi = static_cast<std::uint64_t>(v >> 64);
    if (hi != 0) return 127 - std::countl_zero(hi);
    return 63 - std::countl_zero(static_cast<std::uint64_t>(v));
}

// Alignment of add(): exact up to kExactAlign places (24 + 96 bits fit
// 128); beyond, the smaller operand becomes one unit kFarAlign places below
// the larger one's significand (kFarAlign + 24 < kExactAlign + 1, so that
// unit is more than the whole smaller operand).
constexpr int kExactAlign = 96;
constexpr int kFarAlign = 72;

}  // namespace

Bits bits_of(float x) { return std::bit_cast<Bits>(x); }
float float_of(Bits b) { return std::bit_cast<float>(b); }

bool is_nan(Bits x) { return exp_of(x) == kExpMax && frac_of(x) != 0; }
bool is_subnormal(Bits x) { return exp_of(x) == 0 && frac_of(x) != 0; }

Bits round_pack(bool sign, u128 mag, int exp2, Round r) {
    const int p = msb_index(mag);
    int e = p + exp2 + kBias;  // biased exponent of the leading bit
    const int shift = p - kFracBits;
    std::uint64_t m = 0;
    if (shift > 0) {
        m = static_cast<std::uint64_t>(mag >> shift);
        const u128 rem = mag & ((u128{1} << shift) - 1);
        const u128 half = u128{1} << (shift - 1);
        bool inc = false;
        if (r == Round::Nearest)
            inc = rem > half || (rem == half && (m & 1u) != 0);
        else
            inc = rem != 0 && away_from_zero(r, sign);
        m += inc ? 1u : 0u;
        if (m == (std::uint64_t{1} << (kFracBits + 1))) {
            m >>= 1;
            ++e;
        }
    } else {
        m = static_cast<std::uint64_t>(mag) << -shift;
    }
    if (e >= kExpMax) return overflow_result(sign, r);
    if (e <= 0) return tiny_result(sign, r);
    return with_sign((static_cast<Bits>(e) << kFracBits) | (static_cast<Bits>(m) & kFracMask), sign);
}

Bits add(Bits a, Bits b, Round r) {
    a = add_operand(a, r);
    b = add_operand(b, r);
    if (is_nan(a) || is_nan(b)) return kNaN;
    const bool sa = sign_of(a), sb = sign_of(b);
    if (is_inf(a) && is_inf(b) && sa != sb) return kNaN;
    if (is_inf(a)) return a;
    if (is_inf(b)) return b;
    if (is_zero(a) && is_zero(b)) return with_sign(0u, (sa && sb) || ((sa || sb) && r == Round::Down));
    if (is_zero(a)) return b;
    if (is_zero(b)) return a;
    // Both normal: value = m * 2^(e - 150). The larger exponent's
    // significand is shifted up over the smaller one's, exactly, up to
    // kExactAlign places; beyond that the smaller operand is below one unit
    // of the shifted sum (its 24 bits end more than kExactAlign - 24 places
    // down) and far below the rounding position, where only its being
    // nonzero matters: it is replaced by one unit at kFarAlign places.
    const bool a_big = exp_of(a) >= exp_of(b);
    const Bits big = a_big ? a : b, small = a_big ? b : a;
    const int d = exp_of(big) - exp_of(small);
    const bool far = d > kExactAlign;
    const int k = far ? kFarAlign : d;
    const u128 mb = u128{significand(big)} << k;
    const u128 ms = far ? u128{1} : u128{significand(small)};
    const int exp2 = exp_of(big) - k - 150;
    const bool sbig = sign_of(big), ssmall = sign_of(small);
    if (sbig == ssmall) return round_pack(sbig, mb + ms, exp2, r);
    if (mb == ms) return with_sign(0u, r == Round::Down);
    return mb > ms ? round_pack(sbig, mb - ms, exp2, r) : round_pack(ssmall, ms - mb, exp2, r);
}

Bits sub(Bits a, Bits b, Round r) { return add(a, b ^ kSignBit, r); }

Bits mul(Bits a, Bits b, Round r) {
    const bool s = sign_of(a) != sign_of(b);
    // A subnormal operand moves the product's magnitude up when that moves
    // the product in the rounding direction, else to zero.
    const bool grow = away_from_zero(r, s);
    if (is_subnormal(a)) a = flush_operand(a, grow);
    if (is_subnormal(b)) b = flush_operand(b, grow);
    if (is_nan(a) || is_nan(b)) return kNaN;
    if ((is_inf(a) && is_zero(b)) || (is_zero(a) && is_inf(b))) return kNaN;
    if (is_inf(a) || is_inf(b)) return with_sign(kInf, s);
    if (is_zero(a) || is_zero(b)) return with_sign(0u, s);
    const u128 m = u128{significand(a)} * significand(b);
    return round_pack(s, m, exp_of(a) + exp_of(b) - 300, r);
}

bool lt(Bits a, Bits b) {
    if (is_nan(a) || is_nan(b)) return false;
    if (is_zero(a) && is_zero(b)) return false;
    const Bits ma = a & ~kSignBit, mb = b & ~kSignBit;
    // Zeros are compared as +0 (the case of two zeros is above).
    const bool sa = sign_of(a) && ma != 0, sb = sign_of(b) && mb != 0;
    if (sa != sb) return sa;
    return sa ? ma > mb : ma < mb;
}

bool le(Bits a, Bits b) {
    if (is_nan(a) || is_nan(b)) return false;
    return !lt(b, a);
}

}  // namespace f32

namespace {

using f32::Bits;
using f32::Round;

std::array<Bits, 3> bits3(const Vec3& v) { return {f32::bits_of(v.x), f32::bits_of(v.y), f32::bits_of(v.z)}; }

// o + t*d rounded to float in the direction `up`, exactly: t*d is exact in
// double (24 x 24 significand bits), the sum's rounding error is recovered
// exactly (TwoSum), and the float neighbour on the right side is chosen.
float directed_end(float o, float t, float d, bool up) {
    const double p = static_cast<double>(t) * static_cast<double>(d);
    const double s = static_cast<double>(o) + p;
    const double bb = s - o;
    const double err = (o - (s - bb)) + (p - bb);  // exact: o + p = s + err
    const float f = static_cast<float>(s);
    const double fd = static_cast<double>(f);
    const float dir = up ? kInf : -kInf;
    if (up) {
        if (fd > s || (fd == s && !(err > 0))) return f;
    } else {
        if (fd < s || (fd == s && !(err < 0))) return f;
    }
    return std::nextafter(f, dir);
}

}  // namespace

F32PlueckerQuery f32_pluecker_query(const Ray& r, const Box& b, bool conservative) {
    const PlueckerRay p = pluecker_setup(r);
    F32PlueckerQuery q;
    q.cls = p.cls;
    q.org = bits3(p.o);
    q.dir = bits3(p.d);
    q.has_end = p.has_end;
    q.end = bits3(p.e);
    if (conservative && p.has_end) {
        for (int i = 0; i < 3; ++i)
            q.end[static_cast<std::size_t>(i)] =
                f32::bits_of(directed_end(r.o[i], r.tmax, r.d[i], !class_negative(p.cls, i)));
    }
    q.lo = bits3(b.lo);
    q.hi = bits3(b.hi);
    return q;
}

bool f32_pluecker_hit(const F32PlueckerQuery& q, bool conservative) {
    using namespace f32;
    const Round ra = conservative ? Round::Down : Round::Nearest;  // A_i and A_i*D_j: lower bounds
    const Round rb = conservative ? Round::Up : Round::Nearest;    // B_j and B_j*D_i: upper bounds
    std::array<Bits, 3> A{}, B{}, D{};
    bool ok = true;
    for (std::size_t i = 0; i < 3; ++i) {
        const bool n = class_negative(q.cls, static_cast<int>(i));
        const Bits o = q.org[i], lo = q.lo[i], hi = q.hi[i], e = q.end[i];
        A[i] = n ? sub(o, hi, ra) : sub(lo, o, ra);
        B[i] = n ? sub(o, lo, rb) : sub(hi, o, rb);
        D[i] = q.dir[i] & ~kSignBit;
        if (n ? lt(o, lo) : lt(hi, o)) ok = false;                        // origin test: B_i < 0
        if (q.has_end && (n ? lt(hi, e) : lt(e, lo))) ok = false;         // end test: G_i < 0
    }
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) {
            if (i == j) continue;
            if (lt(mul(B[j], D[i], rb), mul(A[i], D[j], ra))) ok = false;  // B_j*D_i - A_i*D_j < 0
        }
    return ok;
}

bool f32_pluecker_hit(const Ray& r, const Box& b, bool conservative) {
    return f32_pluecker_hit(f32_pluecker_query(r, b, conservative), conservative);
}

F32SmitsQuery f32_smits_query(const Ray& r, const Box& b) {
    const SmitsRay s = smits_setup(r);
    F32SmitsQuery q;
    q.cls = s.cls;
    q.org = bits3(s.o);
    q.inv = bits3(s.inv);
    q.tmax = f32::bits_of(s.tmax);
    q.lo = bits3(b.lo);
    q.hi = bits3(b.hi);
    return q;
}

bool f32_smits_hit(const F32SmitsQuery& q) {
    using namespace f32;
    Bits t0 = 0, t1 = q.tmax;
    for (std::size_t a = 0; a < 3; ++a) {
        const bool n = class_negative(q.cls, static_cast<int>(a));
        const Bits near_plane = n ? q.hi[a] : q.lo[a];
        const Bits far_plane = n ? q.lo[a] : q.hi[a];
        const Bits tn = mul(sub(near_plane, q.org[a]), q.inv[a]);
        const Bits tf = mul(sub(far_plane, q.org[a]), q.inv[a]);
        if (lt(t0, tn)) t0 = tn;  // raise_entry: a NaN keeps t0
        if (lt(tf, t1)) t1 = tf;  // lower_exit: a NaN keeps t1
    }
    return le(t0, t1);
}

bool f32_smits_hit(const Ray& r, const Box& b) { return f32_smits_hit(f32_smits_query(r, b)); }

}  // namespace pluecker
