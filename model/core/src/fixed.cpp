// SPDX-License-Identifier: MIT
// The fixed-point Plücker test: ray set-up, box quantisation and the
// bit-exact datapath documented in fixed.hpp.
#include "pluecker/fixed.hpp"

#include "exact_sum.hpp"
#include "pluecker/boxtest.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace pluecker {
namespace {

using i64 = std::int64_t;

std::string fmt_float(float v) {
    std::ostringstream s;
    s.precision(9);
    s << v;
    return s.str();
}

const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

// Round an exact value s + err (s a double, err the exact rounding error of
// a TwoSum, |err| <= ulp(s)/2, |s| < 2^52) to an integer.
double floor_exact(double s, double err) {
    double f = std::floor(s);
    if (s == f && err < 0) f -= 1;
    return f;
}
double ceil_exact(double s, double err) {
    double c = std::ceil(s);
    if (s == c && err > 0) c += 1;
    return c;
}
double nearest_exact(double s, double err) {
    const double f = floor_exact(s, err);
    // s - f and (s - f) - 0.5 are exact: both are small multiples of ulp(s).
    const double h = (s - f) - 0.5;
    if (h > -err) return f + 1;
    if (h < -err) return f;
    return std::fmod(f, 2.0) == 0 ? f : f + 1;  // tie: to even
}

// Exact s + err = a + b (Knuth's TwoSum).
void two_sum(double a, double b, double& s, double& err) {
    s = a + b;
    const double bb = s - a;
    err = (a - (s - bb)) + (b - bb);
}

bool in_coord_range(double q, const FixedFormat& f) {
    return q >= static_cast<double>(f.coord_min()) && q <= static_cast<double>(f.coord_max());
}

// Coordinate x (a float, so x * 2^(C-2) is exact in double) rounded by `mode`.
enum class Round { Down, Up, Nearest };
double quantize(float x, Round mode, const FixedFormat& f) {
    const double v = std::ldexp(static_cast<double>(x), f.coord_bits - 2);
    switch (mode) {
        case Round::Down: return std::floor(v);
        case Round::Up: return std::ceil(v);
        case Round::Nearest: return nearest_exact(v, 0.0);
    }
    return v;
}

// Float as integer mantissa * 2^exp, mantissa < 2^24 (exact for every
// finite float, denormals included).
void split_float(float x, i64& mant, int& exp) {
    int e = 0;
    const double fr = std::frexp(static_cast<double>(x), &e);  // x = fr * 2^e, fr in [0.5, 1)
    mant = static_cast<i64>(std::ldexp(fr, 24));
    exp = e - 24;
}

// round(|x| / m * 2^(D-1)) to nearest, ties to even, exactly; |x| <= m, m > 0.
i64 scaled_direction(float x, float m, int dir_bits) {
    if (x == 0.0f) return 0;
    i64 mx = 0, mm = 0;
    int ex = 0, em = 0;
    split_float(std::fabs(x), mx, ex);
    split_float(m, mm, em);
    // value = mx / mm * 2^sh
    const int sh = ex - em + dir_bits - 1;  // <= dir_bits - 1 + 24 since |x| <= m
    i64 num = mx, den = mm;
    if (sh >= 0) {
        num = mx << sh;  // mx < 2^24, sh <= 47: fits
    } else {
        // mx / mm < 2, so value < 2^(sh + 1) <= 1/2 for sh <= -2: rounds to 0.
        // (Shifting mm by up to 40 overflowed 64 bits; see
        // Extremes.TinyDirectionRatiosRoundToZero.)
        if (sh <= -2) return 0;
        den = mm << 1;  // sh == -1; mm < 2^24: fits
    }
    i64 q = num / den;
    const i64 rem = num - q * den;
    if (2 * rem > den || (2 * rem == den && (q & 1))) ++q;
    return q;
}

}  // namespace

void FixedFormat::validate() const {
    auto check = [](int bits, const char* name) {
        if (bits < kMinBits || bits > kMaxBits)
            throw InputError(std::string(name) + " = " + std::to_string(bits) + " is outside the supported " +
                             std::to_string(kMinBits) + ".." + std::to_string(kMaxBits));
    };
    check(coord_bits, "COORD_BITS");
    check(dir_bits, "DIR_BITS");
}

double FixedFormat::coord_lsb() const { return std::ldexp(1.0, -(coord_bits - 2)); }
double FixedFormat::dir_lsb() const { return std::ldexp(1.0, -(dir_bits - 1)); }

const char* mode_name(FixedMode m) { return m == FixedMode::Conservative ? "conservative" : "nearest"; }

float FixedFormat::coord_lo_value() const { return -2.0f; }
float FixedFormat::coord_hi_value() const { return 2.0f - std::ldexp(1.0f, 2 - coord_bits); }
Box FixedFormat::range_box() const { return Box{Vec3(coord_lo_value()), Vec3(coord_hi_value())}; }

std::string FixedFormat::range_text() const {
    // One stream, the numbers as fmt_float prints them (no chain of
    // temporary strings: GCC 12 at -O3 warns falsely on one, -Wrestrict).
    std::ostringstream s;
    s.precision(9);
    s << '[' << coord_lo_value() << ", " << coord_hi_value() << "] of COORD_BITS = " << coord_bits;
    return s.str();
}

namespace {

void check_ray(const Ray& r) {
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(r.o[a]))
            throw InputError(std::string("ray origin ") + axis_name(a) + " = " + fmt_float(r.o[a]) + " is not finite");
    const float m = std::max({std::fabs(r.d.x), std::fabs(r.d.y), std::fabs(r.d.z)});
    if (!(m > 0.0f) || !std::isfinite(m))
        throw InputError("ray direction (" + fmt_float(r.d.x) + ", " + fmt_float(r.d.y) + ", " + fmt_float(r.d.z) +
                         ") is zero, NaN or infinite");
    if (std::isnan(r.tmax) || r.tmax < 0.0f) throw InputError("ray tmax " + fmt_float(r.tmax) + " is negative or NaN");
}

bool inside(const Vec3& p, const Box& b) {
    for (int a = 0; a < 3; ++a)
        if (!(b.lo[a] <= p[a] && p[a] <= b.hi[a])) return false;
    return true;
}

// The plane of `range` through which a ray moving along d_a enters slab a.
float entry_plane(const Box& range, const Ray& r, int a) { return r.d[a] > 0.0f ? range.lo[a] : range.hi[a]; }

// Exactly: does the ray enter slab a later than slab b (both moving)? The
// entry parameters are (P_a - o_a) / d_a; compare (P_a - o_a) * d_b * sgn
// against (P_b - o_b) * d_a * sgn, sgn making both denominators positive.
bool enters_later(const Ray& r, const Box& range, int a, int b) {
    const double sa = r.d[a] > 0.0f ? 1.0 : -1.0, sb = r.d[b] > 0.0f ? 1.0 : -1.0;
    const double qa = std::fabs(double(r.d[a])), qb = std::fabs(double(r.d[b]));
    const double p[4] = {
        sa * double(entry_plane(range, r, a)) * qb,
        -sa * double(r.o[a]) * qb,
        -sb * double(entry_plane(range, r, b)) * qa,
        sb * double(r.o[b]) * qa,
    };
    return detail::exact_sign_of_sum(p, 4) > 0;
}

// The origin of a ray that starts outside `range` but meets it: the point
// p = o + t0*d where it enters the range (t0 > 0 exactly the entry
// parameter), every coordinate rounded to nearest from its exact value.
std::array<i64, 3> clipped_origin(const Ray& r, const FixedFormat& f) {
    const Box range = f.range_box();
    int e = -1;  // the entry axis: the moving axis whose slab is entered last
    for (int a = 0; a < 3; ++a)
        if (r.d[a] != 0.0f && (e < 0 || enters_later(r, range, a, e))) e = a;
    const double scale = std::ldexp(1.0, f.coord_bits - 2);
    const float pe = entry_plane(range, r, e);
    const double se = r.d[e] > 0.0f ? 1.0 : -1.0;
    std::array<i64, 3> q{};
    for (int b = 0; b < 3; ++b) {
        if (b == e) {
            q[b] = r.d[e] > 0.0f ? f.coord_min() : f.coord_max();  // on the entry face, a grid plane
        } else if (r.d[b] == 0.0f) {
            q[b] = static_cast<i64>(quantize(r.o[b], Round::Nearest, f));  // inside its slab: exact_hit said so
        } else {
            // p_b = o_b + (P_e - o_e) * d_b / d_e = (o_b*d_e + P_e*d_b - o_e*d_b) / d_e, in LSB units.
            const double t[3] = {
                se * double(r.o[b]) * double(r.d[e]) * scale,
                se * double(pe) * double(r.d[b]) * scale,
                -se * double(r.o[e]) * double(r.d[b]) * scale,
            };
            q[b] = detail::exact_round_ratio(t, 3, std::fabs(r.d[e]));
        }
    }
    return q;
}

}  // namespace

std::optional<FixedRay> fixed_setup_ray(const Ray& r, const FixedFormat& f) {
    f.validate();
    check_ray(r);
    FixedRay out;
    out.cls = ray_class(r.d);
    const float m = std::max({std::fabs(r.d.x), std::fabs(r.d.y), std::fabs(r.d.z)});
    for (int a = 0; a < 3; ++a) out.dir[a] = scaled_direction(r.d[a], m, f.dir_bits);
    const Box range = f.range_box();
    if (inside(r.o, range)) {
        for (int a = 0; a < 3; ++a) out.org[a] = static_cast<i64>(quantize(r.o[a], Round::Nearest, f));
    } else {
        if (!exact_hit(r, range)) return std::nullopt;  // never meets a representable box
        out.org = clipped_origin(r, f);
        out.clipped = true;
    }
    fixed_setup_end(out, r, f);
    return out;
}

void fixed_setup_end(FixedRay& out, const Ray& r, const FixedFormat& f) {
    if (std::isnan(r.tmax) || r.tmax < 0.0f) throw InputError("ray tmax " + fmt_float(r.tmax) + " is negative or NaN");
    // Segment end e = o + tmax*d, exact: tmax*d is exact in double (two
    // 24-bit mantissas), the sum is kept as s + err.
    out.has_end = std::isfinite(r.tmax);
    for (int a = 0; a < 3 && out.has_end; ++a) {
        const double p = static_cast<double>(r.tmax) * static_cast<double>(r.d[a]);
        const double scale = std::ldexp(1.0, f.coord_bits - 2);
        double s = 0, err = 0;
        two_sum(static_cast<double>(r.o[a]) * scale, p * scale, s, err);
        if (!std::isfinite(s) || std::fabs(s) > 0x1p50) {
            out.has_end = false;
            break;
        }
        double q = 0;
        if (f.mode == FixedMode::Nearest)
            q = nearest_exact(s, err);
        else
            q = class_negative(out.cls, a) ? floor_exact(s, err) : ceil_exact(s, err);
        if (!in_coord_range(q, f)) {
            out.has_end = false;  // fall back to the unbounded ray: only adds hits
            break;
        }
        out.end[a] = static_cast<i64>(q);
    }
    if (!out.has_end) out.end = {0, 0, 0};
}

FixedBox fixed_quantize_box(const Box& b, const FixedFormat& f) {
    f.validate();
    FixedBox out;
    const bool cons = f.mode == FixedMode::Conservative;
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(b.lo[a]) || !std::isfinite(b.hi[a]) || b.lo[a] > b.hi[a])
            throw InputError(std::string("box ") + axis_name(a) + " extent [" + fmt_float(b.lo[a]) + ", " +
                             fmt_float(b.hi[a]) + "] is empty or not finite");
        if (b.lo[a] < f.coord_lo_value() || b.hi[a] > f.coord_hi_value())
            throw InputError(std::string("box ") + axis_name(a) + " extent [" + fmt_float(b.lo[a]) + ", " +
                             fmt_float(b.hi[a]) + "] is outside the fixed-point range " + f.range_text());
        const double lo = quantize(b.lo[a], cons ? Round::Down : Round::Nearest, f);
        const double hi = quantize(b.hi[a], cons ? Round::Up : Round::Nearest, f);
        out.lo[a] = static_cast<i64>(lo);
        out.hi[a] = static_cast<i64>(hi);
    }
    return out;
}

bool fixed_hit(const FixedRay& r, const FixedBox& b, const FixedFormat& f) {
    i64 A[3], B[3];
    for (int i = 0; i < 3; ++i) {
        const bool neg = class_negative(r.cls, i);
        A[i] = neg ? r.org[i] - b.hi[i] : b.lo[i] - r.org[i];
        B[i] = neg ? r.org[i] - b.lo[i] : b.hi[i] - r.org[i];
        if (B[i] < 0) return false;  // origin past the exit plane
        if (r.has_end) {
            const i64 G = neg ? b.hi[i] - r.end[i] : r.end[i] - b.lo[i];
            if (G < 0) return false;  // segment ends before the entry plane
        }
    }
    const bool cons = f.mode == FixedMode::Conservative;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            if (i == j) continue;
            const i64 T = B[j] * r.dir[i] - A[i] * r.dir[j];
            const i64 v = cons ? 2 * T + std::llabs(A[i]) + std::llabs(B[j]) + r.dir[i] + r.dir[j] + 1 : T;
            if (v < 0) return false;
        }
    }
    return true;
}

bool fixed_hit(const Ray& r, const Box& b, const FixedFormat& f) {
    const FixedBox qb = fixed_quantize_box(b, f);
    const std::optional<FixedRay> qr = fixed_setup_ray(r, f);
    return qr && fixed_hit(*qr, qb, f);
}

}  // namespace pluecker
