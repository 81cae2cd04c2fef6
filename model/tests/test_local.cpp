// SPDX-License-Identifier: MIT
// The local-frame datapath (local.hpp): format and frame rules, and the
// standing check that it never misses a real hit, against exact_hit, on the
// random, extreme and set-up query families at box widths K = 4..16, with
// each query's box in the tightest frame of its own (local_frame_for).
// PLUECKER_LONG=1 (make sim-regress) runs ten times the queries.
#include "pluecker/boxtest.hpp"
#include "pluecker/local.hpp"
#include "pluecker/querygen.hpp"
#include "pluecker/rng.hpp"

#include "fixed_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace pluecker {
namespace {

using test_support::long_run;
using test_support::Tally;

LocalFormat lformat(int k, int d, int g, FixedMode m = FixedMode::Conservative) {
    LocalFormat f;
    f.box_bits = k;
    f.dir_bits = d;
    f.grid_bits = g;
    f.mode = m;
    return f;
}

// The formats of the standing checks: every K of 4..16 with a narrow, a
// matched and a wide direction, on a narrow and a wide grid.
std::vector<LocalFormat> formats() {
    std::vector<LocalFormat> fs;
    for (int k = 4; k <= 16; ++k)
        for (int d : {4, k + 3 > 24 ? 24 : k + 3, 24})
            for (int g : {k + 2 > 24 ? k + 2 : 24, 40}) fs.push_back(lformat(k, d, g));
    return fs;
}

std::string describe(const Query& q) {
    char buf[512];
    std::snprintf(buf, sizeof buf, "%a %a %a  %a %a %a  %a  %a %a %a  %a %a %a", q.ray.o.x, q.ray.o.y, q.ray.o.z,
                  q.ray.d.x, q.ray.d.y, q.ray.d.z, q.ray.tmax, q.box.lo.x, q.box.lo.y, q.box.lo.z, q.box.hi.x,
                  q.box.hi.y, q.box.hi.z);
    return buf;
}

// Every query at every format: no false miss. Returns the tally summed
// over the formats.
Tally expect_no_false_miss(const std::vector<Query>& qs, const char* what) {
    std::vector<char> exact(qs.size());
    for (std::size_t i = 0; i < qs.size(); ++i) exact[i] = exact_hit(qs[i].ray, qs[i].box);
    Tally total;
    for (const LocalFormat& f : formats()) {
        Tally t;
        for (std::size_t i = 0; i < qs.size(); ++i) {
            const bool h = local_hit(qs[i].ray, qs[i].box, f);
            t.add(exact[i], h);
            if (exact[i] && !h)
                ADD_FAILURE() << what << ": false miss at K=" << f.box_bits << " D=" << f.dir_bits
                              << " G=" << f.grid_bits << ": " << describe(qs[i]);
        }
        total.add(t);
    }
    std::printf("[ local %-8s] %zu queries x %zu formats: %zu real hits, 0 false misses expected (%zu), "
                "false-hit rate %.3f %%\n",
                what, qs.size(), formats().size(), total.real_hits, total.false_misses,
                100.0 * total.false_hit_rate());
    return total;
}

std::size_t n_queries() { return long_run() ? 200000 : 20000; }

TEST(Local, FormatRejectsWhatTheRtlRefuses) {
    EXPECT_NO_THROW(lformat(8, 11, 32).validate());
    EXPECT_THROW(lformat(3, 11, 32).validate(), InputError);
    EXPECT_THROW(lformat(17, 11, 32).validate(), InputError);
    EXPECT_THROW(lformat(8, 3, 32).validate(), InputError);
    EXPECT_THROW(lformat(8, 25, 32).validate(), InputError);
    EXPECT_THROW(lformat(8, 11, 9).validate(), InputError);
    EXPECT_THROW(lformat(8, 11, 49).validate(), InputError);
    try {
        lformat(8, 11, 49).validate();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("GRID_BITS = 49"), std::string::npos) << e.what();
    }
}

TEST(Local, TightestFrameHoldsTheBoxAndNoSmallerCellDoes) {
    Rng rng(11);
    for (int k : {4, 8, 12, 16}) {
        const LocalFormat f = lformat(k, k + 3, 32);
        for (int n = 0; n < 2000; ++n) {
            Box b;
            const float size = std::ldexp(1.0f, -static_cast<int>(rng.below(26)));
            for (int a = 0; a < 3; ++a) {
                const float lo = rng.sym();
                const float ext = size * rng.unit() * (rng.below(8) == 0 ? 0.0f : 1.0f);
                b.lo[a] = lo;
                b.hi[a] = std::min(lo + ext, 1.5f);
            }
            const LocalFrame fr = local_frame_for(b, f);
            const LocalBox q = local_quantize_box(b, fr, f);  // throws when it does not fit
            for (int a = 0; a < 3; ++a) {
                ASSERT_GE(q.lo[a], 0);
                ASSERT_LE(q.hi[a], f.box_max());
                if (fr.exp[a] > 0) {  // one exponent less would not fit from its own floored origin
                    LocalFrame finer = local_frame_for(b, f);
                    finer.exp[a] -= 1;
                    finer.origin[a] = static_cast<std::int64_t>(
                                          std::floor(std::ldexp(static_cast<double>(b.lo[a]), 30 - finer.exp[a])))
                                      << finer.exp[a];
                    EXPECT_THROW(local_quantize_box(b, finer, f), InputError);
                }
            }
        }
    }
}

// The local segment end, END = (end - mirror) / 2^e in cells: a ceiling in
// conservative mode (what the proof's end test assumes, and the RTL's
// choice) and to nearest otherwise. Pinned so that a change of either
// rounding fails here, not only where the margin happens to hide it.
TEST(Local, SegmentEndRoundsOutwardInConservativeMode) {
    for (const FixedMode m : {FixedMode::Conservative, FixedMode::Nearest}) {
        const LocalFormat f = lformat(8, 11, 24, m);
        Rng rng(4242);
        int inexact = 0;
        for (int n = 0; n < 20000; ++n) {
            LocalRay r;
            r.cls = static_cast<RayClass>(rng.below(8));
            r.has_end = true;
            r.dir_g = {std::int64_t{1} << 23, rng.below(1u << 23), rng.below(1u << 23)};
            LocalFrame fr;
            const int e = 1 + static_cast<int>(rng.below(8));
            for (int i = 0; i < 3; ++i) {
                fr.exp[i] = e;
                fr.origin[i] = static_cast<std::int64_t>(rng.below(1u << 22)) - (std::int64_t{1} << 21);
                r.org[i] = static_cast<std::int64_t>(rng.below(1u << 22)) - (std::int64_t{1} << 21);
                r.end[i] = fr.origin[i] + rng.below(1u << (f.box_bits + e));
            }
            const LocalNodeRay nr = local_node_ray(r, fr, f);
            for (int i = 0; i < 3; ++i) {
                const bool neg = class_negative(r.cls, i);
                const std::int64_t mirror = neg ? fr.origin[i] + (f.box_max() << e) : fr.origin[i];
                const std::int64_t de = neg ? mirror - r.end[i] : r.end[i] - mirror;  // grid units
                const std::int64_t got = nr.end[i];
                if (got <= -1 || got >= (std::int64_t{1} << f.box_bits)) continue;  // clamped
                const std::int64_t cell = std::int64_t{1} << e;
                if (de % cell != 0) ++inexact;
                if (m == FixedMode::Conservative) {
                    ASSERT_GE(got * cell, de) << "END rounded inward: cell " << cell << ", end offset " << de;
                    ASSERT_LT((got - 1) * cell, de) << "END more than a cell outward: offset " << de;
                } else {
                    ASSERT_LE(2 * std::abs(got * cell - de), cell) << "END not nearest: offset " << de;
                }
            }
        }
        EXPECT_GT(inexact, 10000) << "too few ends between cell boundaries to tell the roundings apart";
    }
}

// The node ray's moment term in nearest mode: W_k = 2 RNE(lambda / 2^sh),
// lambda = Delta_i DG_j - Delta_j DG_i about the (mirrored) frame origin.
// With DG_x = 2^(G-1) and one exponent e on every axis, c = e and
// sh = G + e - D. Pinned: a truncation or floor of the moment (which the
// conservative margin may hide) fails here.
TEST(Local, MomentRoundsToNearest) {
    const LocalFormat f = lformat(8, 11, 24, FixedMode::Nearest);
    Rng rng(777);
    int inexact = 0;
    for (int n = 0; n < 20000; ++n) {
        LocalRay r;
        r.cls = static_cast<RayClass>(rng.below(8));
        r.dir_g = {std::int64_t{1} << 23, rng.below(1u << 23), rng.below(1u << 23)};
        LocalFrame fr;
        const int e = 1 + static_cast<int>(rng.below(8));
        std::array<std::int64_t, 3> delta{};
        for (int i = 0; i < 3; ++i) {
            fr.exp[i] = e;
            fr.origin[i] = static_cast<std::int64_t>(rng.below(1u << 20)) - (std::int64_t{1} << 19);
            r.org[i] = fr.origin[i] + static_cast<std::int64_t>(rng.below(1u << 12)) - (std::int64_t{1} << 11);
            const bool neg = class_negative(r.cls, i);
            const std::int64_t mirror = neg ? fr.origin[i] + (f.box_max() << e) : fr.origin[i];
            delta[i] = neg ? mirror - r.org[i] : r.org[i] - mirror;
        }
        const LocalNodeRay nr = local_node_ray(r, fr, f);
        const int sh = f.grid_bits + e - f.dir_bits;
        for (int k = 0; k < 6; ++k) {
            const int i = local_pair_i(k), j = local_pair_j(k);
            const std::int64_t lambda = delta[i] * r.dir_g[j] - delta[j] * r.dir_g[i];
            if (nr.w[k] <= f.w_min() || nr.w[k] >= f.w_max()) continue;  // clamped
            ASSERT_EQ(nr.w[k] % 2, 0) << "nearest mode: W is even (2L)";
            const std::int64_t err = (nr.w[k] / 2) * (std::int64_t{1} << sh) - lambda;
            if (lambda % (std::int64_t{1} << sh) != 0) ++inexact;
            ASSERT_LE(2 * std::abs(err), std::int64_t{1} << sh)
                << "W_" << k << " = " << nr.w[k] << " is not 2 RNE(lambda / 2^" << sh << "), lambda " << lambda;
        }
    }
    EXPECT_GT(inexact, 50000) << "too few moments between steps to tell the roundings apart";
}

TEST(Local, BoxOutsideItsFrameOrTheRangeIsRefused) {
    const LocalFormat f = lformat(8, 11, 32);
    Box b;
    b.lo = Vec3(0.0f);
    b.hi = Vec3(0.5f);
    LocalFrame fr = local_frame_for(b, f);
    fr.exp[1] -= 2;
    EXPECT_THROW(local_quantize_box(b, fr, f), InputError);
    Box far;
    far.lo = Vec3(0.0f);
    far.hi = Vec3(2.5f);
    EXPECT_THROW(local_frame_for(far, f), InputError);
    LocalFrame bad = local_frame_for(b, f);
    bad.exp[2] = f.max_exp() + 1;
    EXPECT_THROW(local_quantize_box(b, bad, f), InputError);
}

TEST(Local, NeverMissesOnRandomQueries) { expect_no_false_miss(random_queries(101, n_queries()), "random"); }

TEST(Local, NeverMissesOnExtremeFamilies) {
    std::vector<std::size_t> fam;
    const std::vector<Query> qs = extreme_queries(202, n_queries(), &fam);
    expect_no_false_miss(qs, "extreme");
}

TEST(Local, NeverMissesOnRaysFromAnywhere) {
    expect_no_false_miss(setup_queries(303, n_queries(), 24), "setup");
}

}  // namespace
}  // namespace pluecker

namespace pluecker {
namespace {

// The tiny and degenerate boxes of the extreme families: false hits of the
// local datapath at K = 12 and 16 against the global datapath at 24/24,
// per family (printed; the local test resolves each box in its own cells).
TEST(Local, ExtremeFamiliesFalseHitsAgainstTheGlobalDatapath) {
    std::vector<std::size_t> fam;
    const std::vector<Query> qs = extreme_queries(404, n_queries(), &fam);
    const std::size_t nf = extreme_family_count();
    std::vector<Tally> global(nf), k12(nf), k16(nf);
    const FixedFormat g = test_support::format(24, 24);
    for (std::size_t i = 0; i < qs.size(); ++i) {
        const bool e = exact_hit(qs[i].ray, qs[i].box);
        global[fam[i]].add(e, fixed_hit(qs[i].ray, qs[i].box, g));
        k12[fam[i]].add(e, local_hit(qs[i].ray, qs[i].box, lformat(12, 15, 40)));
        k16[fam[i]].add(e, local_hit(qs[i].ray, qs[i].box, lformat(16, 19, 40)));
    }
    for (std::size_t f = 0; f < nf; ++f) {
        std::printf("[ local family ] %-14s misses %6zu  false hits: global 24/24 %6zu  local K=12 %6zu  K=16 %6zu\n",
                    extreme_family_name(f), global[f].queries - global[f].real_hits, global[f].false_hits,
                    k12[f].false_hits, k16[f].false_hits);
        EXPECT_EQ(k12[f].false_misses + k16[f].false_misses, 0u) << extreme_family_name(f);
        const std::string name = extreme_family_name(f);
        // Boxes of 1e-6 and below: a few cells of the global grid, 2^K - 1
        // of their own frame.
        if (name == "tiny-box") {
            EXPECT_GT(global[f].false_hits, 0u) << "the family no longer tests what it claims";
            EXPECT_EQ(k12[f].false_hits, 0u);
            EXPECT_EQ(k16[f].false_hits, 0u);
        }
        // Flat boxes: the flat axis in cells of the global grid.
        if (name == "flat-box") {
            EXPECT_LT(k12[f].false_hits, global[f].false_hits);
            EXPECT_LT(k16[f].false_hits, global[f].false_hits);
        }
    }
}

}  // namespace
}  // namespace pluecker
