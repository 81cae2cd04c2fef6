// SPDX-License-Identifier: MIT
// The fixed-point Plücker test: ray set-up, box quantisation and the
// bit-exact datapath documented in fixed.hpp.
#include "pluecker/fixed.hpp"

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

FixedMode parse_fixed_mode(const std::string& s) {
    if (s == "conservative") return FixedMode::Conservative;
    if (s == "nearest") return FixedMode::Nearest;
    throw InputError("mode '" + s + "' is not one of conservative, nearest");
}

const char* mode_name(FixedMode m) { return m == FixedMode::Conservative ? "conservative" : "nearest"; }

FixedRay fixed_setup_ray(const Ray& r, const FixedFormat& f) {
    f.validate();
    FixedRay out;
    out.cls = ray_class(r.d);
    const float m = std::max({std::fabs(r.d.x), std::fabs(r.d.y), std::fabs(r.d.z)});
    if (!(m > 0.0f) || !std::isfinite(m))
        throw InputError("ray direction (" + fmt_float(r.d.x) + ", " + fmt_float(r.d.y) + ", " + fmt_float(r.d.z) +
                         ") is zero, NaN or infinite");
    if (std::isnan(r.tmax) || r.tmax < 0.0f) throw InputError("ray tmax " + fmt_float(r.tmax) + " is negative or NaN");
    for (int a = 0; a < 3; ++a) {
        const double q = std::isfinite(r.o[a]) ? quantize(r.o[a], Round::Nearest, f) : NAN;
        if (!in_coord_range(q, f))
            throw InputError(std::string("ray origin ") + axis_name(a) + " = " + fmt_float(r.o[a]) +
                             " is outside the fixed-point range [-2, 2)");
        out.org[a] = static_cast<i64>(q);
        out.dir[a] = scaled_direction(r.d[a], m, f.dir_bits);
    }
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
    return out;
}

FixedBox fixed_quantize_box(const Box& b, const FixedFormat& f) {
    f.validate();
    FixedBox out;
    const bool cons = f.mode == FixedMode::Conservative;
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(b.lo[a]) || !std::isfinite(b.hi[a]) || b.lo[a] > b.hi[a])
            throw InputError(std::string("box ") + axis_name(a) + " extent [" + fmt_float(b.lo[a]) + ", " +
                             fmt_float(b.hi[a]) + "] is empty or not finite");
        const double lo = quantize(b.lo[a], cons ? Round::Down : Round::Nearest, f);
        const double hi = quantize(b.hi[a], cons ? Round::Up : Round::Nearest, f);
        if (!in_coord_range(lo, f) || !in_coord_range(hi, f))
            throw InputError(std::string("box ") + axis_name(a) + " extent [" + fmt_float(b.lo[a]) + ", " +
                             fmt_float(b.hi[a]) + "] is outside the fixed-point range [-2, 2)");
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
    return fixed_hit(fixed_setup_ray(r, f), fixed_quantize_box(b, f), f);
}

std::optional<ClippedRay> fixed_clip_ray(const Ray& r) {
    const double h = kClipHalfWidth;
    bool inside = true;
    for (int a = 0; a < 3; ++a) inside = inside && std::fabs(r.o[a]) <= kClipHalfWidth;
    if (inside) return ClippedRay{r, 0.0f};
    double t0 = 0.0, t1 = std::isfinite(r.tmax) ? static_cast<double>(r.tmax) : INFINITY;
    for (int a = 0; a < 3; ++a) {
        const double o = r.o[a], d = r.d[a];
        if (d == 0.0) {
            if (std::fabs(o) > h) return std::nullopt;
            continue;
        }
        double ta = (-h - o) / d, tb = (h - o) / d;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    if (!(t0 <= t1)) return std::nullopt;
    ClippedRay c;
    c.t0 = static_cast<float>(t0);
    for (int a = 0; a < 3; ++a) {
        const double p = static_cast<double>(r.o[a]) + t0 * static_cast<double>(r.d[a]);
        c.ray.o[a] = static_cast<float>(std::clamp(p, -h, h));
    }
    c.ray.d = r.d;
    c.ray.tmax = std::isfinite(r.tmax) ? std::nextafter(static_cast<float>(r.tmax - t0), kInf) : kInf;
    if (c.ray.tmax < 0.0f) c.ray.tmax = 0.0f;
    return c;
}

}  // namespace pluecker
