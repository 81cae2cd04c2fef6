// SPDX-License-Identifier: MIT
// Ternary answers of the fixed-point test and the cascade (ternary.hpp).
#include "pluecker/ternary.hpp"

#include <cstdlib>
#include <optional>

namespace pluecker {
namespace {

using i64 = std::int64_t;

void need_conservative(const FixedFormat& f, const char* what) {
    if (f.mode != FixedMode::Conservative)
        throw InputError(std::string(what) + ": the ternary answer needs conservative mode (nearest has no margin)");
}

}  // namespace

const char* ternary_name(TernaryAnswer a) {
    switch (a) {
        case TernaryAnswer::Miss: return "miss";
        case TernaryAnswer::Uncertain: return "uncertain";
        case TernaryAnswer::Hit: return "hit";
    }
    return "?";
}

bool fixed_strict_hit(const FixedRay& r, const FixedBox& b, const FixedFormat& f) {
    need_conservative(f, "fixed_strict_hit");
    i64 A[3], B[3];
    for (int i = 0; i < 3; ++i) {
        const bool neg = class_negative(r.cls, i);
        A[i] = neg ? r.org[i] - b.hi[i] : b.lo[i] - r.org[i];
        B[i] = neg ? r.org[i] - b.lo[i] : b.hi[i] - r.org[i];
        if (B[i] < 2) return false;  // the exit plane shrunk by one LSB, the origin moved by half a one
        if (r.has_end) {
            const i64 G = neg ? b.hi[i] - r.end[i] : r.end[i] - b.lo[i];
            if (G < 2) return false;
        }
    }
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            if (i == j) continue;
            const i64 T = B[j] * r.dir[i] - A[i] * r.dir[j];
            const i64 dd = r.dir[i] + r.dir[j] + 1;
            const i64 M = std::llabs(A[i]) + std::llabs(B[j]) + dd;
            if (2 * T - M - 2 * dd < 0) return false;
        }
    }
    return true;
}

TernaryAnswer fixed_ternary(const FixedRay& r, const FixedBox& b, const FixedFormat& f) {
    need_conservative(f, "fixed_ternary");
    if (!fixed_hit(r, b, f)) return TernaryAnswer::Miss;
    return fixed_strict_hit(r, b, f) ? TernaryAnswer::Hit : TernaryAnswer::Uncertain;
}

TernaryAnswer fixed_ternary(const Ray& r, const Box& b, const FixedFormat& f) {
    need_conservative(f, "fixed_ternary");
    const FixedBox qb = fixed_quantize_box(b, f);
    const std::optional<FixedRay> qr = fixed_setup_ray(r, f);
    return qr ? fixed_ternary(*qr, qb, f) : TernaryAnswer::Miss;
}

void CascadeFormats::validate() const {
    narrow.validate();
    wide.validate();
    need_conservative(narrow, "cascade (narrow format)");
    need_conservative(wide, "cascade (wide format)");
}

CascadeAnswer cascade_answer(const FixedRay& narrow_ray, const FixedBox& narrow_box, const FixedRay& wide_ray,
                             const FixedBox& wide_box, const CascadeFormats& f) {
    f.validate();
    CascadeAnswer a;
    a.narrow = fixed_ternary(narrow_ray, narrow_box, f.narrow);
    a.hit = a.narrow == TernaryAnswer::Hit ||
            (a.narrow == TernaryAnswer::Uncertain && fixed_hit(wide_ray, wide_box, f.wide));
    return a;
}

CascadeAnswer cascade_answer(const Ray& r, const Box& b, const CascadeFormats& f) {
    f.validate();
    CascadeAnswer a;
    a.narrow = fixed_ternary(r, b, f.narrow);
    a.hit = a.narrow == TernaryAnswer::Hit || (a.narrow == TernaryAnswer::Uncertain && fixed_hit(r, b, f.wide));
    return a;
}

}  // namespace pluecker
