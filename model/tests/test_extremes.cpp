// SPDX-License-Identifier: MIT
// Numerical extremes standing suite: the fixed-point test (conservative
// mode) against exact_hit on queries at the edges of what floats and the
// fixed-point format resolve, on a grid of width pairs. Zero false misses
// are required; false hits are counted and printed.
//
// Two sources:
//   families     every family of querygen's extreme_queries (axis-parallel,
//                near-axis, signed zeros, exact edge/corner hits and their
//                1-ulp neighbours, flat boxes, origins on the box, segments
//                ending on a face, +-1 coordinates, denormal, tiny and huge
//                directions, tiny boxes, zero-length segments)
//   transformed  random and extreme queries pushed further by one or more of:
//                coordinates snapped to exactly +-1 or one ulp inside,
//                denormal and signed-zero direction components, directions
//                scaled by 1e-30 or 1e30 (tmax scaled back), boxes shrunk to
//                widths 1e-6 .. 1e-12, one ulp or zero around a point on
//                the ray, and segments of length +0 or -0
//
// Short (ctest): 100k queries per source, widths {6, 12, 18, 24}^2 plus a
// few odd pairs. PLUECKER_LONG=1: 1M queries per source, widths
// {6, 9, ..., 24}^2 (step 3 in both), as `make sim-regress` runs it.
#include "pluecker/boxtest.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/query.hpp"
#include "pluecker/querygen.hpp"
#include "pluecker/rng.hpp"

#include "fixed_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace pluecker {
namespace {

using test_support::format;
using test_support::setup_ray;
using test_support::long_run;
using test_support::Tally;

std::size_t query_count() { return long_run() ? 1000000 : 100000; }

std::vector<std::pair<int, int>> width_grid() {
    std::vector<std::pair<int, int>> g;
    const int step = long_run() ? 3 : 6;
    for (int c = 6; c <= 24; c += step)
        for (int d = 6; d <= 24; d += step) g.emplace_back(c, d);
    if (!long_run())
        for (auto p : {std::pair{7, 23}, std::pair{23, 7}, std::pair{11, 13}}) g.push_back(p);
    return g;
}

// Runs every query at every width pair; per-group tallies (a group is a
// family or a transform) summed over the widths, and per-width tallies.
struct Report {
    std::vector<Tally> per_group;
    std::vector<Tally> per_width;
    std::vector<std::string> first_misses;  // up to a few, for the failure message
};

Report run(const std::vector<Query>& qs, const std::vector<std::size_t>& group, std::size_t groups) {
    std::vector<char> exact(qs.size());
    for (std::size_t i = 0; i < qs.size(); ++i) exact[i] = exact_hit(qs[i].ray, qs[i].box);
    const auto grid = width_grid();
    Report rep;
    rep.per_group.resize(groups);
    rep.per_width.resize(grid.size());
    for (std::size_t w = 0; w < grid.size(); ++w) {
        const FixedFormat f = format(grid[w].first, grid[w].second);
        for (std::size_t i = 0; i < qs.size(); ++i) {
            const bool h = fixed_hit(qs[i].ray, qs[i].box, f);
            rep.per_width[w].add(exact[i], h);
            rep.per_group[group[i]].add(exact[i], h);
            if (exact[i] && !h && rep.first_misses.size() < 5) {
                char buf[320];
                std::snprintf(buf, sizeof buf, "%d/%d query %zu: %a %a %a %a %a %a %a %a %a %a %a %a %a", grid[w].first,
                              grid[w].second, i, qs[i].ray.o.x, qs[i].ray.o.y, qs[i].ray.o.z, qs[i].ray.d.x,
                              qs[i].ray.d.y, qs[i].ray.d.z, qs[i].ray.tmax, qs[i].box.lo.x, qs[i].box.lo.y,
                              qs[i].box.lo.z, qs[i].box.hi.x, qs[i].box.hi.y, qs[i].box.hi.z);
                rep.first_misses.push_back(buf);
            }
        }
    }
    return rep;
}

void print_and_check(const char* what, const Report& rep, const std::vector<std::string>& group_names) {
    const auto grid = width_grid();
    Tally all;
    for (std::size_t w = 0; w < grid.size(); ++w) {
        const Tally& t = rep.per_width[w];
        all.add(t);
        std::printf("[ extremes %-11s] %2d/%-2d: %zu queries, %zu real hits, false misses %zu, false hits %zu\n", what,
                    grid[w].first, grid[w].second, t.queries, t.real_hits, t.false_misses, t.false_hits);
        EXPECT_EQ(t.false_misses, 0u) << what << " at " << grid[w].first << "/" << grid[w].second;
    }
    for (std::size_t g = 0; g < rep.per_group.size(); ++g) {
        const Tally& t = rep.per_group[g];
        std::printf("[ extremes %-11s] %-16s (all widths): %zu queries, %zu real hits, false misses %zu, false hits "
                    "%zu\n",
                    what, group_names[g].c_str(), t.queries, t.real_hits, t.false_misses, t.false_hits);
        EXPECT_GT(t.queries, 0u) << group_names[g];
    }
    std::printf("[ extremes %-11s] total over %zu width pairs: %zu query runs, %zu real hits, false misses %zu, "
                "false hits %zu\n",
                what, grid.size(), all.queries, all.real_hits, all.false_misses, all.false_hits);
    for (const std::string& m : rep.first_misses) ADD_FAILURE() << "false miss: " << m;
}

TEST(Extremes, EveryQuerygenFamilyAtEveryWidth) {
    std::vector<std::size_t> fam;
    const std::vector<Query> qs = extreme_queries(0xe7e7e001, query_count(), &fam);
    std::vector<std::string> names;
    for (std::size_t i = 0; i < extreme_family_count(); ++i) names.push_back(extreme_family_name(i));
    print_and_check("families", run(qs, fam, names.size()), names);
}

// ---------------------------------------------------------------------------
// Transformed queries
// ---------------------------------------------------------------------------
enum Transform { kUnitCoords, kDenormalDir, kSignedZero, kTinyDir, kHugeDir, kTinyBox, kZeroLength, kCombined, kTransforms };
const char* kTransformNames[kTransforms] = {"+-1 and 1ulp", "denormal dir", "signed zero", "dir x 1e-30",
                                            "dir x 1e30",   "tiny box",     "zero length", "combined"};

constexpr float kOneInside = 0x1.fffffep-1f;  // 1 - 2^-24: one ulp inside 1

float snap_unit(Rng& g, float x) {
    switch (g.below(5)) {
        case 0: return 1.0f;
        case 1: return -1.0f;
        case 2: return kOneInside;
        case 3: return -kOneInside;
        default: return x;
    }
}

void unit_coords(Rng& g, Query& q) {
    for (int a = 0; a < 3; ++a) {
        q.ray.o[a] = snap_unit(g, q.ray.o[a]);
        q.box.lo[a] = snap_unit(g, q.box.lo[a]);
        q.box.hi[a] = snap_unit(g, q.box.hi[a]);
        if (q.box.lo[a] > q.box.hi[a]) std::swap(q.box.lo[a], q.box.hi[a]);
    }
}

float denormal(Rng& g) {
    switch (g.below(4)) {
        case 0: return 0x1p-149f;  // the smallest
        case 1: return 0x1.fffffcp-127f;  // the largest
        case 2: return std::ldexp(static_cast<float>(1 + g.below(1u << 20)), -149);
        default: return std::ldexp(1.0f, -127 - static_cast<int>(g.below(22)));
    }
}

void denormal_dir(Rng& g, Query& q) {
    const int n = 1 + static_cast<int>(g.below(3));  // 1..3 components
    const int first = static_cast<int>(g.below(3));
    for (int k = 0; k < n; ++k) {
        const int a = (first + k) % 3;
        q.ray.d[a] = (q.ray.d[a] < 0 || std::signbit(q.ray.d[a]) ? -1.0f : 1.0f) * denormal(g);
    }
}

void signed_zero(Rng& g, Query& q) {
    const int n = 1 + static_cast<int>(g.below(2));
    const int first = static_cast<int>(g.below(3));
    for (int k = 0; k < n; ++k) q.ray.d[(first + k) % 3] = g.coin() ? -0.0f : 0.0f;
}

void scale_dir(Query& q, float s, float inv) {
    const Vec3 before = q.ray.d;
    const float m = std::max({std::fabs(before.x), std::fabs(before.y), std::fabs(before.z)});
    if (!std::isfinite(m * s)) s = 1e30f / m;  // already huge (or scaled twice): largest component 1e30
    q.ray.d *= s;
    if (q.ray.d == Vec3(0.0f)) {  // all underflowed: keep the smallest step along the largest axis
        int a = 0;
        for (int k = 1; k < 3; ++k)
            if (std::fabs(before[k]) > std::fabs(before[a])) a = k;
        q.ray.d[a] = std::copysign(0x1p-149f, before[a]);
    }
    if (std::isfinite(q.ray.tmax)) q.ray.tmax = std::min(q.ray.tmax * inv, 0x1p127f);
}

void tiny_box(Rng& g, Query& q) {
    static constexpr float kWidth[] = {1e-6f, 1e-7f, 1e-9f, 1e-12f, 0.0f, -1.0f /* one ulp */};
    // Around a point of the ray (so hits are common) or the box's centre.
    Vec3 c = q.box.center();
    if (g.coin()) {
        const float m = std::max({std::fabs(q.ray.d.x), std::fabs(q.ray.d.y), std::fabs(q.ray.d.z)});
        const float t = g.unit() * 0.5f / m;
        const Vec3 p = q.ray.o + t * q.ray.d;
        if (std::fabs(p.x) <= 1 && std::fabs(p.y) <= 1 && std::fabs(p.z) <= 1) c = p;
    }
    const float w = kWidth[g.below(6)];
    for (int a = 0; a < 3; ++a) {
        const float lo = std::min(std::max(c[a], -1.0f), kOneInside);
        q.box.lo[a] = lo;
        q.box.hi[a] = w < 0 ? std::nextafter(lo, 2.0f) : std::min(1.0f, lo + w);
    }
}

void zero_length(Rng& g, Query& q) {
    q.ray.tmax = g.coin() ? 0.0f : -0.0f;
    if (g.coin()) q.ray.o = q.box.center();
}

void apply(Transform t, Rng& g, Query& q) {
    switch (t) {
        case kUnitCoords: unit_coords(g, q); break;
        case kDenormalDir: denormal_dir(g, q); break;
        case kSignedZero: signed_zero(g, q); break;
        case kTinyDir: scale_dir(q, 1e-30f, 1e30f); break;
        case kHugeDir: scale_dir(q, 1e30f, 1e-30f); break;
        case kTinyBox: tiny_box(g, q); break;
        case kZeroLength: zero_length(g, q); break;
        case kCombined: {
            const int n = 2 + static_cast<int>(g.below(2));
            for (int k = 0; k < n; ++k) apply(static_cast<Transform>(g.below(kCombined)), g, q);
            break;
        }
        default: break;
    }
    if (q.ray.d == Vec3(0.0f)) q.ray.d.z = g.sign() * 0x1p-149f;
}

TEST(Extremes, TransformedQueriesAtEveryWidth) {
    const std::size_t n = query_count();
    std::vector<Query> base = random_queries(0xe7e7e002, n / 2);
    const std::vector<Query> ex = extreme_queries(0xe7e7e003, n - n / 2);
    base.insert(base.end(), ex.begin(), ex.end());
    Rng g(0xe7e7e004);
    std::vector<std::size_t> group(base.size());
    std::size_t invalid = 0;
    for (std::size_t i = 0; i < base.size(); ++i) {
        const auto t = static_cast<Transform>(i % kTransforms);
        group[i] = t;
        apply(t, g, base[i]);
        try {
            validate_query(base[i], "transformed query " + std::to_string(i));
        } catch (const InputError& e) {
            if (++invalid <= 3) ADD_FAILURE() << e.what();
        }
    }
    EXPECT_EQ(invalid, 0u) << "the transforms must keep every query valid";
    // Every kind of extreme is really present.
    std::size_t denormals = 0, zeros = 0, tiny = 0, huge = 0, units = 0, zero_len = 0, small_boxes = 0;
    for (const Query& q : base) {
        for (int a = 0; a < 3; ++a) {
            const float d = std::fabs(q.ray.d[a]);
            denormals += d > 0 && d < 0x1p-126f;
            zeros += d == 0;
            tiny += d > 0 && d < 1e-25f;
            huge += d > 1e25f;
            units += std::fabs(q.ray.o[a]) == 1.0f || std::fabs(q.ray.o[a]) == kOneInside;
            small_boxes += q.box.hi[a] - q.box.lo[a] <= 1e-6f;
        }
        zero_len += q.ray.tmax == 0.0f;
    }
    std::printf("[ extremes transformed ] components: %zu denormal, %zu signed zero, %zu below 1e-25, %zu above 1e25; "
                "%zu origin coordinates at +-1 or one ulp inside; %zu box extents <= 1e-6; %zu zero-length "
                "segments\n",
                denormals, zeros, tiny, huge, units, small_boxes, zero_len);
    EXPECT_GT(denormals, 0u);
    EXPECT_GT(zeros, 0u);
    EXPECT_GT(tiny, 0u);
    EXPECT_GT(huge, 0u);
    EXPECT_GT(units, 0u);
    EXPECT_GT(small_boxes, 0u);
    EXPECT_GT(zero_len, 0u);
    std::vector<std::string> names(kTransformNames, kTransformNames + kTransforms);
    print_and_check("transformed", run(base, group, kTransforms), names);
}

// A direction component far below the largest one scales to D_i = 0. The
// set-up computes round(|x| / m * 2^(D-1)) in 64-bit integers as
// mx / (mm << s) with mantissas mx, mm in [2^23, 2^24); for s = 40 the shifted
// mantissa needs 64 bits and overflowed, and the component came out as 1
// (found by TransformedQueriesAtEveryWidth under PLUECKER_LONG=1 at D = 9:
// d = (0x1p-149, 0x1.27fd12p-101, 0x1.eaee54p-101), a false miss). The ratio
// is swept here over every shift from 30 to 48 at every direction width.
TEST(Extremes, TinyDirectionRatiosRoundToZero) {
    std::size_t wrong = 0, cases = 0;
    for (int dbits = FixedFormat::kMinBits; dbits <= FixedFormat::kMaxBits; ++dbits) {
        const FixedFormat f = format(16, dbits);
        for (float mant_m : {1.0f, 1.5f, 1.92f, 0x1.fffffep0f})
            for (float mant_x : {1.0f, 1.3f, 0x1.fffffep0f})
                for (int ratio = 30; ratio <= 48; ++ratio)  // |x| / m ~ 2^-(ratio + dbits - 1)
                    for (int em : {-101, -60, 0, 60}) {
                        const float m = std::ldexp(mant_m, em);
                        const float x = std::ldexp(mant_x, em - ratio - (dbits - 1));
                        if (x == 0.0f) continue;
                        Ray r;
                        r.o = Vec3(0.0f);
                        r.d = Vec3(x, -x, m);
                        const FixedRay q = setup_ray(r, f);
                        ++cases;
                        if (q.dir[0] != 0 || q.dir[1] != 0) {
                            if (++wrong <= 5)
                                ADD_FAILURE() << "D=" << dbits << ": d = (" << std::hexfloat << x << ", " << -x << ", "
                                              << m << std::defaultfloat << ") gives D = (" << q.dir[0] << ", "
                                              << q.dir[1] << ", " << q.dir[2] << "), expected (0, 0, " << f.dir_one()
                                              << ")";
                        }
                    }
    }
    std::printf("[ extremes tiny ratios ] %zu set-ups, %zu with a nonzero scaled component\n", cases, wrong);
    EXPECT_EQ(wrong, 0u);
}

}  // namespace
}  // namespace pluecker
