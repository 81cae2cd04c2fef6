// SPDX-License-Identifier: MIT
// The fixed-point test against the exact test: never a false miss in
// conservative mode, at every width pair; false hits counted and printed.
#include "pluecker/app/names.hpp"  // parse_* (the applications' name parsing)
#include "pluecker/boxtest.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/querygen.hpp"

#include "fixed_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace pluecker {
namespace {

using test_support::for_each_lattice_ray;
using test_support::format;
using test_support::setup_ray;
using test_support::lattice_boxes;
using test_support::long_run;
using test_support::Tally;

Tally run(const std::vector<Query>& qs, const std::vector<char>& exact, const FixedFormat& f) {
    Tally t;
    for (std::size_t i = 0; i < qs.size(); ++i) t.add(exact[i], fixed_hit(qs[i].ray, qs[i].box, f));
    return t;
}

std::vector<char> exact_answers(const std::vector<Query>& qs) {
    std::vector<char> out(qs.size());
    for (std::size_t i = 0; i < qs.size(); ++i) out[i] = exact_hit(qs[i].ray, qs[i].box);
    return out;
}

TEST(FixedFormat, RejectsIllegalWidths) {
    EXPECT_THROW(format(5, 16).validate(), InputError);
    EXPECT_THROW(format(16, 25).validate(), InputError);
    EXPECT_NO_THROW(format(6, 24).validate());
    EXPECT_THROW(parse_fixed_mode("round"), InputError);
}

TEST(FixedSetup, DirectionScaledSoLargestIsOne) {
    const FixedFormat f = format(16, 16);
    Ray r;
    r.o = Vec3(0.0f);
    r.d = Vec3(-3e-30f, 1.5e-30f, 0.0f);
    const FixedRay q = setup_ray(r, f);
    EXPECT_EQ(q.dir[0], f.dir_one());
    EXPECT_EQ(q.dir[1], f.dir_one() / 2);
    EXPECT_EQ(q.dir[2], 0);
    EXPECT_EQ(q.cls, 1u);  // x negative only
    r.d = Vec3(1e30f, -0.0f, 2e30f);
    const FixedRay p = setup_ray(r, f);
    EXPECT_EQ(p.dir[2], f.dir_one());
    EXPECT_EQ(p.dir[0], f.dir_one() / 2);
    EXPECT_EQ(p.cls, 2u);  // -0 counts as negative
}

TEST(FixedSetup, RejectsBadRaysAndBoxes) {
    const FixedFormat f = format(16, 16);
    Ray r;
    r.d = Vec3(0.0f);
    EXPECT_THROW(fixed_setup_ray(r, f), InputError);
    r.d = Vec3(NAN, 1.0f, 0.0f);
    EXPECT_THROW(fixed_setup_ray(r, f), InputError);
    r.d = Vec3(1.0f, 0.0f, 0.0f);
    r.o = Vec3(kInf, 0.0f, 0.0f);
    EXPECT_THROW(fixed_setup_ray(r, f), InputError);
    r.o = Vec3(2.0f, 0.0f, 0.0f);  // outside the range, moving away: never meets it
    EXPECT_FALSE(fixed_setup_ray(r, f).has_value());
    r.d = Vec3(-1.0f, 0.0f, 0.0f);  // moving back: clipped onto the face x = 2 - 2^-14
    const auto c = fixed_setup_ray(r, f);
    ASSERT_TRUE(c.has_value());
    EXPECT_TRUE(c->clipped);
    EXPECT_EQ(c->org[0], f.coord_max());
    r.o = Vec3(-2.0f, 0.0f, 0.0f);
    EXPECT_FALSE(setup_ray(r, f).clipped);
    Box b;
    b.lo = Vec3(0.0f);
    b.hi = Vec3(3.0f, 0.0f, 0.0f);
    EXPECT_THROW(fixed_quantize_box(b, f), InputError);
}

TEST(FixedSetup, SegmentEndOutOfRangeFallsBackToUnboundedRay) {
    const FixedFormat f = format(16, 16);
    Ray r;
    r.o = Vec3(0.0f);
    r.d = Vec3(1.0f, 0.0f, 0.0f);
    r.tmax = 10.0f;
    EXPECT_FALSE(setup_ray(r, f).has_end);
    r.tmax = 0.5f;
    const FixedRay q = setup_ray(r, f);
    EXPECT_TRUE(q.has_end);
    EXPECT_EQ(q.end[0], 1 << 13);  // 0.5 * 2^(16-2)
}

// The segment end is rounded outward along the ray in conservative mode
// (fixed.hpp, set-up E_i and proof step 5): ceil on positive axes, floor on
// negative ones; to nearest in nearest mode. Rounding to nearest would also
// keep every real hit (step 5), so only the values can tell the choice: they
// are pinned here.
TEST(FixedSetup, SegmentEndRoundsOutward) {
    Ray r;
    r.o = Vec3(0.0f);
    r.d = Vec3(1.0f, -1.0f, 0.5f);  // class 2: y negative
    r.tmax = 0.1f;                  // end (6.4, -6.4, 3.2) LSB at 8 bits (LSB 1/64), a little more
    const FixedRay c = setup_ray(r, format(8, 8));
    ASSERT_TRUE(c.has_end);
    EXPECT_EQ(c.cls, 2u);
    EXPECT_EQ(c.end[0], 7);   // ceil(6.4)
    EXPECT_EQ(c.end[1], -7);  // floor(-6.4)
    EXPECT_EQ(c.end[2], 4);   // ceil(3.2)
    const FixedRay n = setup_ray(r, format(8, 8, FixedMode::Nearest));
    ASSERT_TRUE(n.has_end);
    EXPECT_EQ(n.end[0], 6);
    EXPECT_EQ(n.end[1], -6);
    EXPECT_EQ(n.end[2], 3);
    // On the grid: exact in both modes (tmax = 0.125: 8, -8, 4 LSB).
    r.tmax = 0.125f;
    for (const FixedMode m : {FixedMode::Conservative, FixedMode::Nearest}) {
        const FixedRay e = setup_ray(r, format(8, 8, m));
        EXPECT_EQ(e.end[0], 8);
        EXPECT_EQ(e.end[1], -8);
        EXPECT_EQ(e.end[2], 4);
    }
}

TEST(FixedSetup, BoxRoundsOutwardInConservativeMode) {
    const FixedFormat f = format(8, 8);  // LSB 1/64
    Box b;
    b.lo = Vec3(0.01f, -0.01f, 0.25f);
    b.hi = Vec3(0.02f, 0.01f, 0.25f);
    const FixedBox q = fixed_quantize_box(b, f);
    EXPECT_EQ(q.lo[0], 0);
    EXPECT_EQ(q.hi[0], 2);
    EXPECT_EQ(q.lo[1], -1);
    EXPECT_EQ(q.hi[1], 1);
    EXPECT_EQ(q.lo[2], 16);
    EXPECT_EQ(q.hi[2], 16);
}

// The width grid of the standing suite: both widths on 6..24, every pair on
// a coarse grid plus the diagonal.
std::vector<std::pair<int, int>> width_grid() {
    std::vector<std::pair<int, int>> g;
    for (int c = 6; c <= 24; c += 6)
        for (int d = 6; d <= 24; d += 6) g.emplace_back(c, d);
    for (int w : {8, 10, 14, 16, 20}) g.emplace_back(w, w);
    g.emplace_back(10, 12);
    return g;
}

void expect_no_false_misses(const char* what, const std::vector<Query>& qs) {
    const std::vector<char> exact = exact_answers(qs);
    for (auto [c, d] : width_grid()) {
        const Tally t = run(qs, exact, format(c, d));
        EXPECT_EQ(t.false_misses, 0u) << what << " at " << c << "/" << d;
        std::printf("[ fixed %-8s] %2d/%-2d conservative: %zu queries, %zu hits, false misses %zu, false hits %zu "
                    "(%.3f%% of misses)\n",
                    what, c, d, t.queries, t.real_hits, t.false_misses, t.false_hits, 100.0 * t.false_hit_rate());
    }
}

TEST(FixedVsExact, RandomQueriesNeverMissInConservativeMode) {
    expect_no_false_misses("random", random_queries(0x5eed0001, 20000));
}

TEST(FixedVsExact, ExtremeQueriesNeverMissInConservativeMode) {
    expect_no_false_misses("extreme", extreme_queries(0x5eed0002, 20000));
}

TEST(FixedVsExact, NearestModeCostIsPrinted) {
    const auto qs = random_queries(0x5eed0003, 20000);
    const auto exact = exact_answers(qs);
    for (int w : {6, 10, 16, 24}) {
        const Tally t = run(qs, exact, format(w, w, FixedMode::Nearest));
        std::printf("[ fixed nearest ] %2d/%-2d: false misses %zu, false hits %zu of %zu queries\n", w, w,
                    t.false_misses, t.false_hits, t.queries);
    }
    // At 6 bits rounding to nearest must lose some real hits on random
    // queries: the mode exists to show what the margin buys.
    EXPECT_GT(run(qs, exact, format(6, 6, FixedMode::Nearest)).false_misses, 0u);
}

// Exhaustive at 6/6 over a constrained domain (LSB u = 1/16): every box with
// planes in {-1, 0, 1} u per axis, every origin with coordinates in a set of
// on-grid and off-grid points around it, every direction with components in
// {-1, -1/3, 0, 1/4, 1} (not all zero), unbounded and with a finite segment.
TEST(FixedVsExact, Exhaustive6x6ConstrainedDomain) {
    const FixedFormat f = format(6, 6);
    const float u = 1.0f / 16.0f;
    const float planes[] = {-u, 0.0f, u};
    const float coords[] = {-2.5f * u, -1.0f * u, -0.53f * u, 0.0f, 0.47f * u, 1.0f * u, 1.99f * u};
    const float dirs[] = {-1.0f, -1.0f / 3.0f, 0.0f, 0.25f, 1.0f};
    const float tmaxes[] = {kInf, 0.06f};
    const std::vector<Box> boxes = lattice_boxes(planes);
    std::vector<FixedBox> qboxes;
    for (const Box& b : boxes) qboxes.push_back(fixed_quantize_box(b, f));
    Tally t;
    for_each_lattice_ray(coords, dirs, tmaxes, [&](const Ray& r) {
        const FixedRay fr = setup_ray(r, f);
        for (std::size_t k = 0; k < boxes.size(); ++k) {
            const bool e = exact_hit(r, boxes[k]);
            const bool h = fixed_hit(fr, qboxes[k], f);
            t.add(e, h);
            if (e && !h) ADD_FAILURE() << "false miss";
        }
    });
    std::printf("[ fixed exhaustive 6/6 ] %zu queries, %zu real hits, false misses %zu, false hits %zu (%.2f%% of "
                "misses)\n",
                t.queries, t.real_hits, t.false_misses, t.false_hits, 100.0 * t.false_hit_rate());
    EXPECT_EQ(t.false_misses, 0u);
    EXPECT_GT(t.queries, 1000000u);
}

}  // namespace
}  // namespace pluecker
