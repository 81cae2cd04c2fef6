// SPDX-License-Identifier: MIT
// Local frames: ray and node set-up, box quantisation in a frame and the
// bit-exact child datapath documented in local.hpp.
#include "pluecker/local.hpp"

#include "grid.hpp"
#include "pluecker/boxtest.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pluecker {
namespace {

using i64 = std::int64_t;
__extension__ typedef __int128 i128;  // a GCC/Clang extension
using detail::axis_name;
using detail::fmt_float;
using detail::Round;



// x * 2^-e for an integer x, |x| < 2^110 (every value here), exactly
// (e <= 0), or rounded up or to nearest with ties to even (e > 0;
// arithmetic shifts floor). Above e = 120 every result is what it is at
// 120 (|x| / 2^e < 2^-10), so e is capped there to keep the shifts defined.
constexpr int kShiftCap = 120;
i128 ceil_shift(i128 x, int e) { return e <= 0 ? x << -e : -((-x) >> std::min(e, kShiftCap)); }
i128 round_shift(i128 x, int e) {
    if (e <= 0) return x << -e;
    e = std::min(e, kShiftCap);
    const i128 f = x >> e;
    const i128 rem = x - (f << e);  // 0 <= rem < 2^e
    const i128 half = i128{1} << (e - 1);
    if (rem > half || (rem == half && (f & 1))) return f + 1;
    return f;
}

i64 clamp64(i128 v, i64 lo, i64 hi) { return static_cast<i64>(v < lo ? lo : v > hi ? hi : v); }
i128 abs128(i128 v) { return v < 0 ? -v : v; }

int bit_length(i64 v) {
    int n = 0;
    while (v > 0) {
        ++n;
        v >>= 1;
    }
    return n;
}

// The box plane x in frame units (x - F) / 2^e on the grid, rounded by
// `mode`, exactly: x * 2^(G-2) is exact in a double and so is the TwoSum.
i64 plane_in_frame(float x, i64 origin, int e, Round mode, int grid_bits) {
    double s = 0, err = 0;
    detail::two_sum(std::ldexp(static_cast<double>(x), grid_bits - 2), -static_cast<double>(origin), s, err);
    s = std::ldexp(s, -e);
    err = std::ldexp(err, -e);
    switch (mode) {
        case Round::Down: return static_cast<i64>(detail::floor_exact(s, err));
        case Round::Up: return static_cast<i64>(detail::ceil_exact(s, err));
        case Round::Nearest: return static_cast<i64>(detail::nearest_exact(s, err));
    }
    return 0;
}

void check_box_range(const Box& b, const LocalFormat& f) {
    const Box range = f.range_box();
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(b.lo[a]) || !std::isfinite(b.hi[a]) || b.lo[a] > b.hi[a])
            throw InputError(std::string("box ") + axis_name(a) + " extent [" + fmt_float(b.lo[a]) + ", " +
                             fmt_float(b.hi[a]) + "] is empty or not finite");
        if (b.lo[a] < range.lo[a] || b.hi[a] > range.hi[a])
            throw InputError(std::string("box ") + axis_name(a) + " extent [" + fmt_float(b.lo[a]) + ", " +
                             fmt_float(b.hi[a]) + "] is outside the local format's range " + f.range_text());
    }
}

}  // namespace

void LocalFormat::validate() const {
    auto check = [](int v, int lo, int hi, const char* name) {
        if (v < lo || v > hi)
            throw InputError(std::string(name) + " = " + std::to_string(v) + " is outside the supported " +
                             std::to_string(lo) + ".." + std::to_string(hi));
    };
    check(box_bits, kMinBoxBits, kMaxBoxBits, "BOX_BITS");
    check(dir_bits, kMinDirBits, kMaxDirBits, "DIR_BITS");
    check(grid_bits, box_bits + 2, kMaxGridBits, "GRID_BITS");
}

i64 LocalFormat::w_max() const { return box_max() << dir_bits; }
i64 LocalFormat::w_min() const { return -w_max() - (i64{2} << box_bits) + 1; }

Box LocalFormat::range_box() const { return detail::grid_float_range(grid_bits); }

std::string LocalFormat::range_text() const {
    const Box r = range_box();
    std::ostringstream s;
    s.precision(9);
    s << '[' << r.lo.x << ", " << r.hi.x << "] of GRID_BITS = " << grid_bits;
    return s.str();
}

std::optional<LocalRay> local_setup_ray(const Ray& r, const LocalFormat& f) {
    f.validate();
    detail::check_ray(r);
    LocalRay out;
    out.cls = ray_class(r.d);
    const float m = std::max({std::fabs(r.d.x), std::fabs(r.d.y), std::fabs(r.d.z)});
    for (int a = 0; a < 3; ++a) out.dir_g[a] = detail::scaled_direction(r.d[a], m, f.grid_bits);
    const Box range = f.range_box();
    if (detail::inside(r.o, range)) {
        for (int a = 0; a < 3; ++a)
            out.org[a] = static_cast<i64>(detail::round_to_grid(r.o[a], Round::Nearest, f.grid_bits));
    } else {
        if (!exact_hit(r, range)) return std::nullopt;  // never meets a box the format takes
        out.org = detail::clipped_origin(r, f.grid_bits);
        out.clipped = true;
    }
    local_setup_end(out, r, f);
    return out;
}

void local_setup_end(LocalRay& out, const Ray& r, const LocalFormat& f) {
    out.has_end = detail::segment_end(r, out.cls, f.mode == FixedMode::Conservative, f.grid_bits, out.end);
}

void check_frame(const LocalFrame& fr, const LocalFormat& f) {
    for (int a = 0; a < 3; ++a) {
        if (fr.exp[a] < 0 || fr.exp[a] > f.max_exp())
            throw InputError(std::string("frame exponent ") + axis_name(a) + " = " + std::to_string(fr.exp[a]) +
                             " is outside 0.." + std::to_string(f.max_exp()) + " (GRID_BITS - BOX_BITS + 1)");
        if (fr.origin[a] < f.grid_min() || fr.origin[a] > f.grid_max())
            throw InputError(std::string("frame origin ") + axis_name(a) + " = " + std::to_string(fr.origin[a]) +
                             " is outside the GRID_BITS = " + std::to_string(f.grid_bits) + " grid");
    }
}

LocalBox local_quantize_box(const Box& b, const LocalFrame& fr, const LocalFormat& f) {
    f.validate();
    check_frame(fr, f);
    check_box_range(b, f);
    const bool cons = f.mode == FixedMode::Conservative;
    LocalBox out;
    for (int a = 0; a < 3; ++a) {
        out.lo[a] = plane_in_frame(b.lo[a], fr.origin[a], fr.exp[a], cons ? Round::Down : Round::Nearest, f.grid_bits);
        out.hi[a] = plane_in_frame(b.hi[a], fr.origin[a], fr.exp[a], cons ? Round::Up : Round::Nearest, f.grid_bits);
        if (out.lo[a] < 0 || out.hi[a] > f.box_max())
            throw InputError(std::string("box ") + axis_name(a) + " extent [" + fmt_float(b.lo[a]) + ", " +
                             fmt_float(b.hi[a]) + "] does not fit the frame (offsets " + std::to_string(out.lo[a]) +
                             ".." + std::to_string(out.hi[a]) + " of 0.." + std::to_string(f.box_max()) + ")");
    }
    return out;
}

LocalFrame local_frame_for(const Box& b, const LocalFormat& f, bool uniform) {
    f.validate();
    check_box_range(b, f);
    LocalFrame fr;
    // Per axis the smallest exponent whose outward-rounded box spans at most
    // 2^K - 1 cells from its floored lo; e = G - K + 1 always fits.
    auto fits = [&](int a, int e) {
        const i64 lo = plane_in_frame(b.lo[a], 0, e, Round::Down, f.grid_bits);
        const i64 hi = plane_in_frame(b.hi[a], 0, e, Round::Up, f.grid_bits);
        return hi - lo <= f.box_max();
    };
    for (int a = 0; a < 3; ++a) {
        int e = 0;
        while (e < f.max_exp() && !fits(a, e)) ++e;
        fr.exp[a] = e;
    }
    if (uniform) fr.exp.fill(*std::max_element(fr.exp.begin(), fr.exp.end()));
    for (int a = 0; a < 3; ++a)
        fr.origin[a] = plane_in_frame(b.lo[a], 0, fr.exp[a], Round::Down, f.grid_bits) << fr.exp[a];
    return fr;
}

LocalFrame local_child_frame(const Box& child, const LocalFrame& parent, const LocalBox& qchild,
                             const LocalFormat& f, bool uniform) {
    LocalFrame fr;
    for (int a = 0; a < 3; ++a) {
        fr.origin[a] = parent.origin[a] + (qchild.lo[a] << parent.exp[a]);
        // e = parent.exp[a] always fits: the child spans HI - LO <= 2^K - 1
        // parent cells from its LO.
        int e = 0;
        while (e < parent.exp[a] &&
               plane_in_frame(child.hi[a], fr.origin[a], e, Round::Up, f.grid_bits) > f.box_max())
            ++e;
        fr.exp[a] = e;
    }
    if (uniform) fr.exp.fill(*std::max_element(fr.exp.begin(), fr.exp.end()));
    return fr;
}

LocalNodeRay local_node_ray(const LocalRay& r, const LocalFrame& fr, const LocalFormat& f) {
    const bool cons = f.mode == FixedMode::Conservative;
    const int K = f.box_bits, D = f.dir_bits, G = f.grid_bits;
    const i64 cells_hi = i64{1} << K;  // the clamp 2^K of ORG and END
    LocalNodeRay out;
    out.cls = r.cls;
    std::array<i128, 3> delta{};
    for (int i = 0; i < 3; ++i) {
        const bool neg = class_negative(r.cls, i);
        const i128 mirror = neg ? fr.origin[i] + (f.box_max() << fr.exp[i]) : fr.origin[i];
        delta[i] = neg ? mirror - r.org[i] : r.org[i] - mirror;
        out.org[i] = clamp64(round_shift(delta[i], fr.exp[i]), -1, cells_hi);
        if (r.has_end) {
            const i128 de = neg ? mirror - r.end[i] : r.end[i] - mirror;
            out.end[i] = clamp64(cons ? ceil_shift(de, fr.exp[i]) : round_shift(de, fr.exp[i]), -1, cells_hi);
        }
    }
    out.has_end = r.has_end;
    // c: the largest scaling with every local component at most 2^(D-1).
    const i64 top = i64{1} << (G - 1);
    int c = 0;
    bool any = false;
    for (int i = 0; i < 3; ++i) {
        if (r.dir_g[i] == 0) continue;
        const int ci = r.dir_g[i] == top ? fr.exp[i] : fr.exp[i] + G - 1 - bit_length(r.dir_g[i]);
        c = any ? std::min(c, ci) : ci;
        any = true;
    }
    for (int i = 0; i < 3; ++i) out.dir[i] = static_cast<i64>(round_shift(r.dir_g[i], G - D + fr.exp[i] - c));
    for (int k = 0; k < 6; ++k) {
        const int i = local_pair_i(k), j = local_pair_j(k);
        const i128 lambda = delta[i] * r.dir_g[j] - delta[j] * r.dir_g[i];
        const int sh = G + fr.exp[i] + fr.exp[j] - c - D;
        i128 w = 2 * round_shift(lambda, sh);
        if (cons) {
            const i128 extent = (i128{f.box_max()} << fr.exp[i]) + (i128{f.box_max()} << fr.exp[j]);
            const i128 mu =
                ceil_shift(abs128(delta[i]) + abs128(delta[j]) + extent + r.dir_g[i] + r.dir_g[j] + 1, sh + 1);
            w += 2 * mu + 1;
        }
        out.w[k] = clamp64(w, f.w_min(), f.w_max());
    }
    return out;
}

bool local_hit(const LocalNodeRay& r, const LocalBox& b, const LocalFormat& f) {
    const i64 top = f.box_max();
    i64 ent[3], ext[3];
    for (int i = 0; i < 3; ++i) {
        const bool neg = class_negative(r.cls, i);
        ent[i] = neg ? top - b.hi[i] : b.lo[i];
        ext[i] = neg ? top - b.lo[i] : b.hi[i];
        if (ext[i] - r.org[i] < 0) return false;                // origin past the exit plane
        if (r.has_end && r.end[i] - ent[i] < 0) return false;   // segment ends before the entry plane
    }
    const bool cons = f.mode == FixedMode::Conservative;
    for (int k = 0; k < 6; ++k) {
        const int i = local_pair_i(k), j = local_pair_j(k);
        const i64 v = 2 * (ext[j] * r.dir[i] - ent[i] * r.dir[j]) + (cons ? ext[j] + ent[i] : 0) + r.w[k];
        if (v < 0) return false;
    }
    return true;
}

bool local_hit(const Ray& r, const Box& b, const LocalFormat& f) {
    const LocalFrame fr = local_frame_for(b, f);
    const LocalBox qb = local_quantize_box(b, fr, f);
    const std::optional<LocalRay> qr = local_setup_ray(r, f);
    return qr && local_hit(local_node_ray(*qr, fr, f), qb, f);
}

}  // namespace pluecker
