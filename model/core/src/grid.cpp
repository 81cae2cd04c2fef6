// SPDX-License-Identifier: MIT
// Exact rounding onto a fixed-point grid (grid.hpp).
#include "grid.hpp"

#include "exact_sum.hpp"
#include "pluecker/boxtest.hpp"

#include <algorithm>
#include <sstream>
#include <string>

namespace pluecker::detail {

const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

std::string fmt_float(float v) {
    std::ostringstream s;
    s.precision(9);
    s << v;
    return s.str();
}

namespace {

// Float as integer mantissa * 2^exp, mantissa < 2^24 (exact for every
// finite float, denormals included).
void split_float(float x, i64& mant, int& exp) {
    int e = 0;
    const double fr = std::frexp(static_cast<double>(x), &e);  // x = fr * 2^e, fr in [0.5, 1)
    mant = static_cast<i64>(std::ldexp(fr, 24));
    exp = e - 24;
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
    return exact_sign_of_sum(p, 4) > 0;
}

}  // namespace

Box grid_float_range(int bits) {
    const float hi = 2.0f - std::ldexp(1.0f, -std::min(bits - 2, 23));
    return Box{Vec3(-2.0f), Vec3(hi)};
}

double round_to_grid(float x, Round mode, int bits) {
    const double v = std::ldexp(static_cast<double>(x), bits - 2);
    switch (mode) {
        case Round::Down: return std::floor(v);
        case Round::Up: return std::ceil(v);
        case Round::Nearest: return nearest_exact(v, 0.0);
    }
    return v;
}

i64 scaled_direction(float x, float m, int bits) {
    if (x == 0.0f) return 0;
    i64 mx = 0, mm = 0;
    int ex = 0, em = 0;
    split_float(std::fabs(x), mx, ex);
    split_float(m, mm, em);
    // value = mx / mm * 2^sh, and mx / mm * 2^(ex - em) <= 1 since |x| <= m.
    const int sh = ex - em + bits - 1;
    __extension__ typedef unsigned __int128 u128;  // GCC/Clang extension
    u128 num = static_cast<u128>(mx), den = static_cast<u128>(mm);
    if (sh >= 0) {
        // mx << (ex - em) < 2^24 (|x| <= m) and the value is below 2^62, so
        // the shifted numerator stays below 2^(24 + 62 + 24).
        num <<= sh;
    } else {
        // mx / mm < 2, so value < 2^(sh + 1) <= 1/2 for sh <= -2: rounds to 0.
        // (Shifting mm by up to 40 overflowed 64 bits once; see
        // Extremes.TinyDirectionRatiosRoundToZero.)
        if (sh <= -2) return 0;
        den <<= 1;  // sh == -1
    }
    u128 q = num / den;
    const u128 rem = num - q * den;
    if (2 * rem > den || (2 * rem == den && (q & 1))) ++q;
    return static_cast<i64>(q);
}

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

std::array<i64, 3> clipped_origin(const Ray& r, int bits) {
    const Box range = grid_float_range(bits);
    int e = -1;  // the entry axis: the moving axis whose slab is entered last
    for (int a = 0; a < 3; ++a)
        if (r.d[a] != 0.0f && (e < 0 || enters_later(r, range, a, e))) e = a;
    const double scale = std::ldexp(1.0, bits - 2);
    const float pe = entry_plane(range, r, e);
    const double se = r.d[e] > 0.0f ? 1.0 : -1.0;
    std::array<i64, 3> q{};
    for (int b = 0; b < 3; ++b) {
        if (b == e) {
            q[b] = static_cast<i64>(round_to_grid(pe, Round::Nearest, bits));  // on the entry face, a grid plane
        } else if (r.d[b] == 0.0f) {
            q[b] = static_cast<i64>(round_to_grid(r.o[b], Round::Nearest, bits));  // inside its slab: exact_hit said so
        } else {
            // p_b = o_b + (P_e - o_e) * d_b / d_e = (o_b*d_e + P_e*d_b - o_e*d_b) / d_e, in LSB units.
            const double t[3] = {
                se * double(r.o[b]) * double(r.d[e]) * scale,
                se * double(pe) * double(r.d[b]) * scale,
                -se * double(r.o[e]) * double(r.d[b]) * scale,
            };
            q[b] = exact_round_ratio(t, 3, std::fabs(r.d[e]), bits);
        }
    }
    return q;
}

bool segment_end(const Ray& r, RayClass cls, bool outward, int bits, std::array<i64, 3>& end) {
    if (std::isnan(r.tmax) || r.tmax < 0.0f) throw InputError("ray tmax " + fmt_float(r.tmax) + " is negative or NaN");
    end = {0, 0, 0};
    if (!std::isfinite(r.tmax)) return false;
    // e = o + tmax*d, exact: tmax*d is exact in double (two 24-bit
    // mantissas), the sum is kept as s + err.
    const double scale = std::ldexp(1.0, bits - 2);
    for (int a = 0; a < 3; ++a) {
        const double p = static_cast<double>(r.tmax) * static_cast<double>(r.d[a]);
        double s = 0, err = 0;
        two_sum(static_cast<double>(r.o[a]) * scale, p * scale, s, err);
        if (!std::isfinite(s) || std::fabs(s) > 0x1p50) {
            end = {0, 0, 0};
            return false;
        }
        const double q = !outward                 ? nearest_exact(s, err)
                         : class_negative(cls, a) ? floor_exact(s, err)
                                                  : ceil_exact(s, err);
        if (!in_grid(q, bits)) {
            end = {0, 0, 0};
            return false;  // fall back to the unbounded ray: only adds hits
        }
        end[a] = static_cast<i64>(q);
    }
    return true;
}

}  // namespace pluecker::detail
