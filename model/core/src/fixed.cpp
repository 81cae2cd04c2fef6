// SPDX-License-Identifier: MIT
// The fixed-point Plücker test: ray set-up, box quantisation and the
// bit-exact datapath documented in fixed.hpp.
#include "pluecker/fixed.hpp"

#include "grid.hpp"
#include "pluecker/boxtest.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace pluecker {
namespace {

using i64 = std::int64_t;
using detail::axis_name;
using detail::fmt_float;
using detail::Round;

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

std::optional<FixedRay> fixed_setup_ray(const Ray& r, const FixedFormat& f) {
    f.validate();
    detail::check_ray(r);
    FixedRay out;
    out.cls = ray_class(r.d);
    const float m = std::max({std::fabs(r.d.x), std::fabs(r.d.y), std::fabs(r.d.z)});
    for (int a = 0; a < 3; ++a) out.dir[a] = detail::scaled_direction(r.d[a], m, f.dir_bits);
    const Box range = f.range_box();
    if (detail::inside(r.o, range)) {
        for (int a = 0; a < 3; ++a)
            out.org[a] = static_cast<i64>(detail::round_to_grid(r.o[a], Round::Nearest, f.coord_bits));
    } else {
        if (!exact_hit(r, range)) return std::nullopt;  // never meets a representable box
        out.org = detail::clipped_origin(r, f.coord_bits);
        out.clipped = true;
    }
    fixed_setup_end(out, r, f);
    return out;
}

void fixed_setup_end(FixedRay& out, const Ray& r, const FixedFormat& f) {
    out.has_end = detail::segment_end(r, out.cls, f.mode == FixedMode::Conservative, f.coord_bits, out.end);
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
        const double lo = detail::round_to_grid(b.lo[a], cons ? Round::Down : Round::Nearest, f.coord_bits);
        const double hi = detail::round_to_grid(b.hi[a], cons ? Round::Up : Round::Nearest, f.coord_bits);
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
