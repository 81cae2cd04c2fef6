// SPDX-License-Identifier: MIT
// Ternary answers (ternary.hpp) against the exact test: a certain miss is
// never a real hit, a certain hit always is; the strict test's terms are all
// needed (weaker variants give false certain hits); the cascade never
// misses a real hit.
#include "pluecker/boxtest.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/querygen.hpp"
#include "pluecker/ternary.hpp"

#include "fixed_test_support.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace pluecker {
namespace {

using test_support::for_each_lattice_ray;
using test_support::format;
using test_support::lattice_boxes;
using test_support::long_run;
using test_support::setup_ray;

using i64 = std::int64_t;

// Ternary answers against exact ones.
struct Tally3 {
    std::size_t queries = 0, real_hits = 0, hits = 0, misses = 0, uncertain = 0;
    std::size_t false_hits = 0;    // certain hit, no real hit
    std::size_t false_misses = 0;  // certain miss, a real hit
    void add(bool exact, TernaryAnswer a) {
        ++queries;
        real_hits += exact;
        hits += a == TernaryAnswer::Hit;
        misses += a == TernaryAnswer::Miss;
        uncertain += a == TernaryAnswer::Uncertain;
        false_hits += a == TernaryAnswer::Hit && !exact;
        false_misses += a == TernaryAnswer::Miss && exact;
    }
    void print(const char* what, int c, int d) const {
        std::printf("[ ternary %-8s] %2d/%-2d: %zu queries, %zu real hits: certain hits %zu, certain misses %zu, "
                    "uncertain %zu (%.2f%%); false certain hits %zu, false certain misses %zu\n",
                    what, c, d, queries, real_hits, hits, misses, uncertain,
                    queries ? 100.0 * double(uncertain) / double(queries) : 0.0, false_hits, false_misses);
    }
};

Tally3 run(const std::vector<Query>& qs, const FixedFormat& f) {
    Tally3 t;
    for (const Query& q : qs) {
        const TernaryAnswer a = fixed_ternary(q.ray, q.box, f);
        // The ternary answer refines the conservative one.
        EXPECT_EQ(a != TernaryAnswer::Miss, fixed_hit(q.ray, q.box, f));
        t.add(exact_hit(q.ray, q.box), a);
    }
    return t;
}

std::vector<std::pair<int, int>> widths() { return {{6, 6}, {8, 8}, {10, 12}, {16, 16}, {24, 24}, {6, 24}, {24, 6}}; }

void expect_sound(const char* what, const std::vector<Query>& qs, bool some_certain_hits) {
    for (auto [c, d] : widths()) {
        const Tally3 t = run(qs, format(c, d));
        t.print(what, c, d);
        EXPECT_EQ(t.false_hits, 0u) << what << " at " << c << "/" << d;
        EXPECT_EQ(t.false_misses, 0u) << what << " at " << c << "/" << d;
        if (some_certain_hits && c >= 10 && d >= 10) {
            EXPECT_GT(t.hits, 0u) << what << " at " << c << "/" << d;
        }
    }
}

TEST(Ternary, NearestModeIsRefused) {
    const FixedFormat f = format(16, 16, FixedMode::Nearest);
    const FixedRay r{};
    const FixedBox b{};
    EXPECT_THROW(fixed_ternary(r, b, f), InputError);
    EXPECT_THROW(fixed_strict_hit(r, b, f), InputError);
    CascadeFormats cf{format(8, 8), f};
    EXPECT_THROW(cf.validate(), InputError);
}

TEST(Ternary, RandomQueries) { expect_sound("random", random_queries(0x7e57a001, 20000), true); }

TEST(Ternary, ExtremeQueries) { expect_sound("extreme", extreme_queries(0x7e57a002, long_run() ? 200000 : 20000), false); }

TEST(Ternary, SetupQueriesFromAnywhere) {
    for (auto [c, d] : widths()) {
        const auto qs = setup_queries(0x7e57a003 + static_cast<std::uint64_t>(c), long_run() ? 30000 : 3000, c);
        const Tally3 t = run(qs, format(c, d));
        t.print("setup", c, d);
        EXPECT_EQ(t.false_hits, 0u) << c << "/" << d;
        EXPECT_EQ(t.false_misses, 0u) << c << "/" << d;
    }
}

// A finite segment whose end leaves the range cube: the set-up drops the end
// (has_end false), which loses no condition of a certain hit (ternary.hpp,
// step 2): the ray left the cube for good.
TEST(Ternary, DroppedEndKeepsCertainHitsReal) {
    const FixedFormat f = format(8, 8);
    Ray r;
    r.o = Vec3(-1.5f, 0.05f, 0.0f);
    r.d = Vec3(1.0f, 0.03f, 0.05f);
    r.tmax = 5.0f;  // ends at x = 3.5, outside [-2, 2)
    Box b;
    b.lo = Vec3(-0.5f, -0.25f, -0.25f);
    b.hi = Vec3(0.5f, 0.25f, 0.25f);
    ASSERT_FALSE(setup_ray(r, f).has_end);
    EXPECT_TRUE(exact_hit(r, b));
    EXPECT_EQ(fixed_ternary(r, b, f), TernaryAnswer::Hit);
    r.tmax = 0.9f;  // ends at x = -0.6, before the box: in range, kept
    ASSERT_TRUE(setup_ray(r, f).has_end);
    EXPECT_FALSE(exact_hit(r, b));
    EXPECT_EQ(fixed_ternary(r, b, f), TernaryAnswer::Miss);
}

// ---------------------------------------------------------------------------
// The strict test term by term, with weaker variants: each drops one thing
// the proof needs. On the lattice below every one of them calls a box a
// certain hit that the ray misses; the real test never does.
// ---------------------------------------------------------------------------
enum class Variant {
    Strict,          // ternary.hpp
    NoInward,        // box as quantised (outward): B >= 0, G >= 0, 2T - M >= 0
    NoMargin,        // box shrunk inward, no margin: B' >= 0, G' >= 0, T' >= 0
    NoDirTerm,       // 2T - M >= 0 with B >= 2, G >= 2 (the 2(D_i + D_j + 1) dropped)
    OriginOneLsb,    // B >= 1 instead of B >= 2
};
constexpr std::array<Variant, 5> kVariants = {Variant::Strict, Variant::NoInward, Variant::NoMargin,
                                              Variant::NoDirTerm, Variant::OriginOneLsb};
const char* variant_name(Variant v) {
    switch (v) {
        case Variant::Strict: return "strict";
        case Variant::NoInward: return "no inward shrink";
        case Variant::NoMargin: return "inward, no margin";
        case Variant::NoDirTerm: return "no 2(Di+Dj+1)";
        case Variant::OriginOneLsb: return "B >= 1";
    }
    return "?";
}

bool variant_hit(const FixedRay& r, const FixedBox& b, Variant v) {
    i64 A[3], B[3];
    const i64 shrink = v == Variant::NoInward ? 0 : 1;
    const i64 b_min = v == Variant::Strict || v == Variant::NoDirTerm ? 2 : v == Variant::OriginOneLsb ? 1 : 0;
    const i64 g_min = v == Variant::NoInward || v == Variant::NoMargin ? 0 : 2;
    for (int i = 0; i < 3; ++i) {
        const bool neg = class_negative(r.cls, i);
        A[i] = (neg ? r.org[i] - b.hi[i] : b.lo[i] - r.org[i]) + (v == Variant::NoMargin ? shrink : 0);
        B[i] = (neg ? r.org[i] - b.lo[i] : b.hi[i] - r.org[i]) - (v == Variant::NoMargin ? shrink : 0);
        if (B[i] < b_min) return false;
        if (r.has_end) {
            const i64 G = (neg ? b.hi[i] - r.end[i] : r.end[i] - b.lo[i]) - (v == Variant::NoMargin ? shrink : 0);
            if (G < g_min) return false;
        }
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            if (i == j) continue;
            const i64 T = B[j] * r.dir[i] - A[i] * r.dir[j];
            const i64 dd = r.dir[i] + r.dir[j] + 1;
            const i64 M = std::llabs(A[i]) + std::llabs(B[j]) + dd;
            i64 s = 0;
            switch (v) {
                case Variant::Strict:
                case Variant::OriginOneLsb: s = 2 * T - M - 2 * dd; break;
                case Variant::NoInward:
                case Variant::NoDirTerm: s = 2 * T - M; break;
                case Variant::NoMargin: s = T; break;
            }
            if (s < 0) return false;
        }
    return true;
}

// 6/6 (LSB u = 1/16): boxes from 0.7 to 7.9 LSB wide with planes off the
// grid, origins near and between grid points, directions with zero and
// small components, both segment kinds. Every certain hit (of the test or a
// variant) is checked against exact_hit. (A ray with two direction
// components that round to zero gets no certain hit: T = 0 on that pair.)
TEST(Ternary, LatticeAndWeakerVariants) {
    const FixedFormat f = format(6, 6);
    const float u = 1.0f / 16.0f;
    const float planes[] = {-4.3f * u, -1.5f * u, 0.2f * u, 0.9f * u, 3.6f * u};
    const float coords[] = {-5.2f * u, -0.5f * u, 0.4f * u, 1.47f * u, 4.5f * u};
    const float dirs[] = {-1.0f, -0.3f, 0.0f, 0.26f, 1.0f};
    const float tmaxes[] = {kInf, 0.3f};
    const std::vector<Box> boxes = lattice_boxes(planes);
    std::vector<FixedBox> qboxes;
    for (const Box& b : boxes) qboxes.push_back(fixed_quantize_box(b, f));
    std::array<std::size_t, kVariants.size()> certain{}, wrong{};
    Tally3 t;
    for_each_lattice_ray(coords, dirs, tmaxes, [&](const Ray& r) {
        const FixedRay fr = setup_ray(r, f);
        for (std::size_t k = 0; k < boxes.size(); ++k) {
            const TernaryAnswer a = fixed_ternary(fr, qboxes[k], f);
            EXPECT_EQ(a == TernaryAnswer::Hit, variant_hit(fr, qboxes[k], Variant::Strict));
            if (a == TernaryAnswer::Miss) {  // no real hit: fixed.hpp's suites check that
                ++t.queries;
                ++t.misses;
                continue;
            }
            bool any = false;
            std::array<bool, kVariants.size()> says{};
            for (std::size_t v = 0; v < kVariants.size(); ++v) {
                says[v] = fixed_hit(fr, qboxes[k], f) && variant_hit(fr, qboxes[k], kVariants[v]);
                any = any || says[v];
            }
            if (!any) {  // uncertain, and no variant claims a certain hit
                ++t.queries;
                ++t.uncertain;
                continue;
            }
            const bool e = exact_hit(r, boxes[k]);
            t.add(e, a);
            for (std::size_t v = 0; v < kVariants.size(); ++v) {
                certain[v] += says[v];
                wrong[v] += says[v] && !e;
            }
        }
    });
    std::printf("[ ternary lattice 6/6 ] %zu queries: certain hits %zu (all checked), certain misses %zu, uncertain "
                "%zu; false certain hits %zu\n",
                t.queries, t.hits, t.misses, t.uncertain, t.false_hits);
    for (std::size_t v = 0; v < kVariants.size(); ++v)
        std::printf("[ ternary lattice 6/6 ]   variant %-18s: %zu certain hits, %zu of them false\n",
                    variant_name(kVariants[v]), certain[v], wrong[v]);
    EXPECT_EQ(t.false_hits, 0u);
    EXPECT_EQ(wrong[0], 0u);
    EXPECT_GT(certain[0], 1000u);
    for (std::size_t v = 1; v < kVariants.size(); ++v)
        EXPECT_GT(wrong[v], 0u) << "variant '" << variant_name(kVariants[v]) << "' gave no false certain hit";
}

// ---------------------------------------------------------------------------
// The cascade
// ---------------------------------------------------------------------------
TEST(Cascade, NeverMissesARealHit) {
    auto qs = random_queries(0x7e57a004, 20000);
    const auto ex = extreme_queries(0x7e57a005, 20000);
    qs.insert(qs.end(), ex.begin(), ex.end());
    for (int n : {6, 8, 10}) {
        const CascadeFormats cf{format(n, n), format(16, 16)};
        std::size_t escalated = 0, hits = 0, false_hits = 0, wide_false_hits = 0, narrow_false_hits = 0;
        for (const Query& q : qs) {
            const bool e = exact_hit(q.ray, q.box);
            const CascadeAnswer a = cascade_answer(q.ray, q.box, cf);
            const bool narrow_hit = fixed_hit(q.ray, q.box, cf.narrow);
            const bool wide_hit = fixed_hit(q.ray, q.box, cf.wide);
            ASSERT_FALSE(e && !a.hit) << "cascade " << n << "/16 lost a real hit";
            // The cascade's hit: a certain narrow hit, or the wide answer.
            EXPECT_EQ(a.hit, a.narrow == TernaryAnswer::Hit || (a.escalated() && wide_hit));
            escalated += a.escalated();
            hits += a.hit;
            false_hits += a.hit && !e;
            wide_false_hits += wide_hit && !e;
            narrow_false_hits += narrow_hit && !e;
        }
        std::printf("[ cascade %2d/%2d -> 16/16 ] %zu queries: escalated %zu (%.2f%%), hits %zu; false hits: "
                    "cascade %zu, narrow alone %zu, wide alone %zu\n",
                    n, n, qs.size(), escalated, 100.0 * double(escalated) / double(qs.size()), hits, false_hits,
                    narrow_false_hits, wide_false_hits);
        // A cascade false hit is a wide false hit (certain narrow hits are real).
        EXPECT_LE(false_hits, wide_false_hits);
        EXPECT_LE(false_hits, narrow_false_hits);
    }
}

TEST(Cascade, FixedQueriesMatchTheFloatForm) {
    const CascadeFormats cf{format(8, 8), format(16, 16)};
    for (const Query& q : random_queries(0x7e57a006, 5000)) {
        const auto nr = fixed_setup_ray(q.ray, cf.narrow);
        const auto wr = fixed_setup_ray(q.ray, cf.wide);
        const CascadeAnswer a = cascade_answer(q.ray, q.box, cf);
        if (!nr || !wr) {
            EXPECT_FALSE(a.hit);
            continue;
        }
        const CascadeAnswer b = cascade_answer(*nr, fixed_quantize_box(q.box, cf.narrow), *wr,
                                               fixed_quantize_box(q.box, cf.wide), cf);
        EXPECT_EQ(a.hit, b.hit);
        EXPECT_EQ(a.narrow, b.narrow);
    }
}

}  // namespace
}  // namespace pluecker
