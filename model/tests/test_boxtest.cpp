// SPDX-License-Identifier: MIT
// The exact test on hand-made cases and against two independent
// formulations; the float tests (smits-mul-cls, pluecker-cls) against the
// exact test, with their false misses and false hits printed per family.
#include "pluecker/boxtest.hpp"
#include "pluecker/query.hpp"
#include "pluecker/querygen.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace pluecker {
namespace {

Query make(Vec3 o, Vec3 d, float tmax, Vec3 lo, Vec3 hi) {
    Query q;
    q.ray.o = o;
    q.ray.d = d;
    q.ray.tmax = tmax;
    q.box.lo = lo;
    q.box.hi = hi;
    return q;
}

bool smits(const Query& q) { return smits_hit(smits_setup(q.ray), q.box); }
bool pluecker(const Query& q) { return pluecker_hit(pluecker_setup(q.ray), q.box); }
bool exact(const Query& q) { return exact_hit(q.ray, q.box); }

std::string show(const Query& q) {
    std::ostringstream s;
    write_query(s, q);
    return s.str();
}

// ---------------------------------------------------------------------------
// Hand-made cases with known answers. `float_exact` marks the cases whose
// float arithmetic is exact (small dyadic numbers), where both float tests
// must give the true answer too.
// ---------------------------------------------------------------------------

struct Case {
    const char* what;
    Query q;
    bool hit;
    bool float_exact;
};

constexpr float kUlp1 = 0x1p-23f;  // ulp of 1 (upwards)
const Vec3 kLo(0.0f), kHi(1.0f);   // the unit box

std::vector<Case> hand_cases() {
    const Vec3 z(0, 0, 1);
    return {
        {"through a face centre", make({0.5f, 0.5f, -1}, z, kInf, kLo, kHi), true, true},
        {"pointing away", make({0.5f, 0.5f, -1}, -z, kInf, kLo, kHi), false, true},
        {"origin inside", make({0.5f, 0.5f, 0.5f}, {0.3f, -0.7f, 0.1f}, kInf, kLo, kHi), true, true},
        {"along edge x=0,y=0", make({0, 0, -1}, z, kInf, kLo, kHi), true, true},
        {"along edge x=1,y=1", make({1, 1, -1}, z, kInf, kLo, kHi), true, true},
        {"along edge, -0 components", make({1, 0, -1}, {-0.0f, -0.0f, 1}, kInf, kLo, kHi), true, true},
        {"in face plane x=0, +0", make({0, 0.5f, -1}, {0.0f, 0, 1}, kInf, kLo, kHi), true, true},
        {"in face plane x=0, -0", make({0, 0.5f, -1}, {-0.0f, 0, 1}, kInf, kLo, kHi), true, true},
        {"in face plane x=1, -0", make({1, 0.5f, -1}, {-0.0f, 0, 1}, kInf, kLo, kHi), true, true},
        {"1 ulp beside face x=1", make({1 + kUlp1, 0.5f, -1}, z, kInf, kLo, kHi), false, true},
        {"1 ulp beside face x=0", make({-0x1p-149f, 0.5f, -1}, {-0.0f, 0, 1}, kInf, kLo, kHi), false, true},
        {"touches edge x=0,y=0 at z=0.5", make({-1, 1, 0.5f}, {1, -1, 0}, kInf, kLo, kHi), true, true},
        {"touches corner 0,0,0 only", make({-1, 1, -1}, {1, -1, 1}, kInf, kLo, kHi), true, true},
        {"misses corner by 2^-20", make({-1, 1 - 0x1p-20f, -1}, {1, -1, 1}, kInf, kLo, kHi), false, true},
        {"passes corner 2^-20 inside", make({-1, 1 + 0x1p-20f, -1}, {1, -1, 1}, kInf, kLo, kHi), true, true},
        {"touches corner 1,1,1 from outside", make({2, 0, 2}, {-1, 1, -1}, kInf, kLo, kHi), true, true},
        {"segment ends on entry face", make({0.5f, 0.5f, -1}, z, 1.0f, kLo, kHi), true, true},
        {"segment ends 1 ulp before face", make({0.5f, 0.5f, -1}, z, 1 - 0x1p-24f, kLo, kHi), false, true},
        {"segment ends 1 ulp past face", make({0.5f, 0.5f, -1}, z, 1 + kUlp1, kLo, kHi), true, true},
        {"segment, scaled direction", make({0.5f, 0.5f, -1}, {0, 0, 4}, 0.25f, kLo, kHi), true, true},
        {"segment, scaled, short", make({0.5f, 0.5f, -1}, {0, 0, 4}, 0.25f - 0x1p-26f, kLo, kHi), false, true},
        {"segment ends on -x entry face", make({3, 0.5f, 0.5f}, {-1, 0, 0}, 2.0f, kLo, kHi), true, true},
        {"segment past the box", make({0.5f, 0.5f, -1}, z, 100.0f, kLo, kHi), true, true},
        {"tmax 0, origin inside", make({0.5f, 0.5f, 0.5f}, z, 0.0f, kLo, kHi), true, true},
        {"tmax 0, origin on corner", make({1, 1, 1}, z, 0.0f, kLo, kHi), true, true},
        {"tmax -0, origin on face", make({0.5f, 0, 0.5f}, {0, -1, 0}, -0.0f, kLo, kHi), true, true},
        {"tmax 0, origin 1 ulp out", make({0.5f, 1 + kUlp1, 0.5f}, {0, -1, 0}, 0.0f, kLo, kHi), false, true},
        {"origin on face, pointing away", make({0.5f, 0.5f, 1}, z, kInf, kLo, kHi), true, true},
        {"origin on corner, pointing away", make({1, 1, 1}, {1, 1, 1}, kInf, kLo, kHi), true, true},
        {"origin 1 ulp out, pointing away", make({0.5f, 0.5f, 1 + kUlp1}, z, kInf, kLo, kHi), false, true},
        {"flat box, through", make({0.5f, 0.5f, 0}, z, kInf, kLo, {1, 1, 0.5f}), true, true},
        {"flat box, in its plane", make({-1, 0.5f, 0.5f}, {1, 0, 0}, kInf, {0, 0, 0.5f}, {1, 1, 0.5f}), true, true},
        {"flat box, 2^-24 above plane",
         make({-1, 0.5f, 0.5f + 0x1p-24f}, {1, 0, 0}, kInf, {0, 0, 0.5f}, {1, 1, 0.5f}), false, true},
        {"point box, hit", make({0, 0, 0}, {1, 1, 1}, kInf, Vec3(0.25f), Vec3(0.25f)), true, true},
        {"point box, d 1 ulp off", make({0, 0, 0}, {1, 1, 1 + kUlp1}, kInf, Vec3(0.25f), Vec3(0.25f)), false, false},
        {"point box, segment ends on it", make({0, 0, 0}, {1, 1, 1}, 0.25f, Vec3(0.25f), Vec3(0.25f)), true, true},
        {"point box, segment 1 ulp short",
         make({0, 0, 0}, {1, 1, 1}, 0.25f - 0x1p-26f, Vec3(0.25f), Vec3(0.25f)), false, true},
        {"denormal dx keeps x inside", make({0.5f, 0.5f, -1}, {0x1p-149f, 0, 1}, kInf, kLo, kHi), true, false},
        {"denormal dx leaves the face x=1", make({1, 0.5f, -1}, {0x1p-149f, 0, 1}, kInf, kLo, kHi), false, false},
        {"near-axis leaves face x=0", make({0, 0.5f, -1}, {-0x1p-30f, 0, 1}, kInf, kLo, kHi), false, false},
        {"near-axis along face x=0 inward", make({0, 0.5f, -1}, {0x1p-30f, 0, 1}, kInf, kLo, kHi), true, false},
        {"huge direction", make({0.5f, -1, -1}, {0, 1e30f, 1e30f}, kInf, kLo, kHi), true, false},
        {"huge direction, miss", make({0.5f, 0.5f, -1}, {0, 1e30f, 1e30f}, kInf, kLo, kHi), false, false},
        {"tiny direction, segment", make({0.5f, 0.5f, -1}, {0, 0, 0x1p-100f}, 0x1p100f, kLo, kHi), true, true},
        {"tiny direction, segment short",
         make({0.5f, 0.5f, -1}, {0, 0, 0x1p-100f}, 0x1p100f - 0x1p76f, kLo, kHi), false, true},
    };
}

TEST(ExactHit, HandMadeCases) {
    for (const Case& c : hand_cases()) {
        ASSERT_NO_THROW(validate_query(c.q, c.what));
        EXPECT_EQ(exact(c.q), c.hit) << c.what << ": " << show(c.q);
    }
}

TEST(FloatTests, AgreeOnHandMadeCasesWithExactArithmetic) {
    for (const Case& c : hand_cases()) {
        if (!c.float_exact) continue;
        EXPECT_EQ(smits(c.q), c.hit) << "smits: " << c.what << ": " << show(c.q);
        EXPECT_EQ(pluecker(c.q), c.hit) << "pluecker: " << c.what << ": " << show(c.q);
    }
}

TEST(FloatTests, SmitsNeverNaNDriven) {
    // Origin on a slab plane with a zero direction component, both signs of
    // zero, every plane: the ray lies in the plane, inside the closed slab.
    for (float zero : {0.0f, -0.0f})
        for (float x : {0.0f, 1.0f})
            for (float dz : {1.0f, -1.0f}) {
                const Query q = make({x, 0.5f, dz > 0 ? -1.0f : 2.0f}, {zero, zero, dz}, kInf, kLo, kHi);
                EXPECT_TRUE(smits(q)) << show(q);
                EXPECT_TRUE(pluecker(q)) << show(q);
                EXPECT_TRUE(exact(q)) << show(q);
            }
}

TEST(FloatTests, SmitsEntryDistance) {
    float t = -1;
    ASSERT_TRUE(smits_hit(smits_setup(make({0.5f, 0.5f, -1}, {0, 0, 2}, kInf, kLo, kHi).ray), {kLo, kHi}, &t));
    EXPECT_EQ(t, 0.5f);
    ASSERT_TRUE(smits_hit(smits_setup(make({0.5f, 0.5f, 0.5f}, {0, 0, 1}, kInf, kLo, kHi).ray), {kLo, kHi}, &t));
    EXPECT_EQ(t, 0.0f);
    ASSERT_TRUE(smits_hit(smits_setup(make({-1, -2, 0.5f}, {1, 1, 0}, kInf, kLo, kHi).ray), {kLo, kHi}, &t));
    EXPECT_EQ(t, 2.0f);
}

TEST(FloatTests, PlueckerSetup) {
    const PlueckerRay p = pluecker_setup(make({1, 2, 3}, {-1, 0.5f, -0.0f}, 2.0f, kLo, kHi).ray);
    EXPECT_TRUE(p.has_end);
    EXPECT_EQ(p.e, Vec3(-1, 3, 3));
    EXPECT_EQ(p.cls, 1u | 4u);
    EXPECT_EQ(class_name(p.cls), "MPM");
    EXPECT_FALSE(pluecker_setup(make({1, 2, 3}, {1, 1, 1}, kInf, kLo, kHi).ray).has_end);
}

// ---------------------------------------------------------------------------
// Independent formulation 1: slab intervals as normalised GMP rationals,
// t = (plane - o) / d, intersected with [0, tmax].
// ---------------------------------------------------------------------------

bool mpq_hit(const Query& q) {
    mpq_class t0(0), t1(0);
    bool bounded = std::isfinite(q.ray.tmax);
    if (bounded) t1 = mpq_class(double(q.ray.tmax));
    for (int a = 0; a < 3; ++a) {
        const mpq_class o(double(q.ray.o[a])), lo(double(q.box.lo[a])), hi(double(q.box.hi[a]));
        if (q.ray.d[a] == 0.0f) {
            if (o < lo || o > hi) return false;
            continue;
        }
        const mpq_class d(double(q.ray.d[a]));
        mpq_class ta = (lo - o) / d, tb = (hi - o) / d;
        if (ta > tb) std::swap(ta, tb);
        if (ta > t0) t0 = ta;
        if (!bounded || tb < t1) {
            t1 = tb;
            bounded = true;
        }
    }
    return !bounded || t0 <= t1;
}

TEST(ExactHit, MatchesRationalSlabsOnRandomQueries) {
    const auto qs = random_queries(0xb0c5e001, 50000);
    for (const Query& q : qs) ASSERT_EQ(exact(q), mpq_hit(q)) << show(q);
}

TEST(ExactHit, MatchesRationalSlabsOnExtremeQueries) {
    const auto qs = extreme_queries(0xb0c5e002, 64000);
    for (const Query& q : qs) ASSERT_EQ(exact(q), mpq_hit(q)) << show(q);
}

// Floats over the whole finite range (random exponents, denormals, zeros of
// both signs): the double filter and the integer fallback must stay exact.
TEST(ExactHit, MatchesRationalSlabsOnWideRangeFloats) {
    std::uint64_t state = 0x3a7e;
    auto next = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return state >> 11;
    };
    auto wide = [&]() -> float {
        switch (next() % 8) {
            case 0: return (next() & 1) ? -0.0f : 0.0f;
            case 1: return std::ldexp(float(next() % (1u << 23)), -149) * ((next() & 1) ? -1.0f : 1.0f);
            default: {
                const float m = 1.0f + float(next() % (1u << 23)) * 0x1p-23f;
                const int e = int(next() % 254) - 126;
                return std::ldexp(m, e) * ((next() & 1) ? -1.0f : 1.0f);
            }
        }
    };
    std::size_t hits = 0, n = 40000;
    for (std::size_t i = 0; i < n; ++i) {
        Query q;
        for (int a = 0; a < 3; ++a) {
            q.ray.o[a] = wide();
            const float u = wide(), v = wide();
            q.box.lo[a] = std::min(u, v);
            q.box.hi[a] = std::max(u, v);
        }
        if (next() & 1) {  // aim at a box corner, when the difference is finite
            for (int a = 0; a < 3; ++a) q.ray.d[a] = ((next() & 1) ? q.box.lo[a] : q.box.hi[a]) - q.ray.o[a];
        } else {
            for (int a = 0; a < 3; ++a) q.ray.d[a] = wide();
        }
        if (!std::isfinite(q.ray.d.x) || !std::isfinite(q.ray.d.y) || !std::isfinite(q.ray.d.z) ||
            q.ray.d == Vec3(0.0f))
            q.ray.d = Vec3(wide(), wide(), 1.0f);
        q.ray.tmax = (next() & 1) ? kInf : std::fabs(wide());
        ASSERT_NO_THROW(validate_query(q, "wide"));
        const bool e = exact(q);
        hits += e;
        ASSERT_EQ(e, mpq_hit(q)) << show(q);
    }
    EXPECT_GT(hits, n / 20);
}

TEST(ExactHit, MatchesRationalSlabsOnHandMadeCases) {
    for (const Case& c : hand_cases()) EXPECT_EQ(mpq_hit(c.q), c.hit) << c.what;
}

// ---------------------------------------------------------------------------
// Independent formulation 2, small integers: if the segment meets the box,
// the meeting set is an interval whose left end is 0 or an entry parameter
// (plane - o)/d. So the segment meets the box iff the point at one of those
// candidate parameters t = p/q (q > 0, 0 <= t <= tmax) lies in the box:
// lo*q <= o*q + p*d <= hi*q, all in 64-bit integers (exact).
// ---------------------------------------------------------------------------

struct SmallQuery {
    std::int64_t o[3], d[3], lo[3], hi[3];
    std::int64_t tmax;  // < 0: unbounded
};

bool point_test_hit(const SmallQuery& s) {
    struct T {
        std::int64_t p, q;
    };
    std::vector<T> cand = {{0, 1}};
    for (int a = 0; a < 3; ++a) {
        if (s.d[a] == 0) continue;
        for (std::int64_t plane : {s.lo[a], s.hi[a]}) {
            T t{plane - s.o[a], s.d[a]};
            if (t.q < 0) t = {-t.p, -t.q};
            cand.push_back(t);
        }
    }
    for (const T& t : cand) {
        if (t.p < 0) continue;                                // t < 0
        if (s.tmax >= 0 && t.p > s.tmax * t.q) continue;      // t > tmax
        bool inside = true;
        for (int a = 0; a < 3; ++a) {
            const std::int64_t x = s.o[a] * t.q + t.p * s.d[a];
            inside = inside && s.lo[a] * t.q <= x && x <= s.hi[a] * t.q;
        }
        if (inside) return true;
    }
    return false;
}

TEST(ExactHit, MatchesPointTestOnSmallIntegers) {
    std::uint64_t state = 0x51ca11;
    auto rnd = [&](int lo, int hi) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return lo + static_cast<int>((state >> 33) % static_cast<std::uint64_t>(hi - lo + 1));
    };
    std::size_t hits = 0, n = 200000;
    for (std::size_t i = 0; i < n; ++i) {
        SmallQuery s;
        Query q;
        do {
            for (int a = 0; a < 3; ++a) s.d[a] = rnd(-3, 3);
        } while (s.d[0] == 0 && s.d[1] == 0 && s.d[2] == 0);
        for (int a = 0; a < 3; ++a) {
            s.o[a] = rnd(-6, 6);
            const int u = rnd(-4, 4), v = rnd(-4, 4);
            s.lo[a] = std::min(u, v);
            s.hi[a] = std::max(u, v);
            q.ray.o[a] = float(s.o[a]);
            // Zero components get both signs of zero.
            q.ray.d[a] = s.d[a] == 0 ? (rnd(0, 1) ? -0.0f : 0.0f) : float(s.d[a]);
            q.box.lo[a] = float(s.lo[a]);
            q.box.hi[a] = float(s.hi[a]);
        }
        if (rnd(0, 1)) {  // aim at an integer point of the box or next to it
            std::int64_t t[3];
            for (int a = 0; a < 3; ++a) t[a] = rnd(int(s.lo[a]) - 1, int(s.hi[a]) + 1) - s.o[a];
            if (t[0] != 0 || t[1] != 0 || t[2] != 0) {
                for (int a = 0; a < 3; ++a) {
                    s.d[a] = t[a];
                    q.ray.d[a] = t[a] == 0 ? (rnd(0, 1) ? -0.0f : 0.0f) : float(t[a]);
                }
            }
        }
        s.tmax = rnd(-3, 6);  // negative: unbounded
        q.ray.tmax = s.tmax < 0 ? kInf : float(s.tmax);
        const bool want = point_test_hit(s);
        hits += want;
        ASSERT_EQ(exact(q), want) << show(q);
    }
    // Both answers well represented.
    EXPECT_GT(hits, n / 10);
    EXPECT_LT(hits, n - n / 10);
}

// ---------------------------------------------------------------------------
// Float tests against the exact test.
// ---------------------------------------------------------------------------

struct Errors {
    std::size_t n = 0, hits = 0, smits_fm = 0, smits_fh = 0, pl_fm = 0, pl_fh = 0;
    void add(const Query& q) {
        const bool e = exact(q), s = smits(q), p = pluecker(q);
        ++n;
        hits += e;
        smits_fm += e && !s;
        smits_fh += !e && s;
        pl_fm += e && !p;
        pl_fh += !e && p;
    }
};

void print_row(const char* name, const Errors& e) {
    std::printf("  %-14s %7zu %7zu | %8zu %8zu | %8zu %8zu\n", name, e.n, e.hits, e.smits_fm, e.smits_fh, e.pl_fm,
                e.pl_fh);
}
void print_header(const char* title) {
    std::printf("%s\n  %-14s %7s %7s | %8s %8s | %8s %8s\n", title, "family", "queries", "hits", "smits FM",
                "smits FH", "pl FM", "pl FH");
}

TEST(FloatTests, AgainstExactOnRandomQueries) {
    Errors e;
    for (const Query& q : random_queries(0xf1a7e001, 200000)) e.add(q);
    print_header("float tests vs exact, random queries (FM = false misses, FH = false hits):");
    print_row("random", e);
    std::fflush(stdout);
    RecordProperty("random_queries", static_cast<int>(e.n));
    RecordProperty("random_smits_false_misses", static_cast<int>(e.smits_fm));
    RecordProperty("random_smits_false_hits", static_cast<int>(e.smits_fh));
    RecordProperty("random_pluecker_false_misses", static_cast<int>(e.pl_fm));
    RecordProperty("random_pluecker_false_hits", static_cast<int>(e.pl_fh));
    // The counts are deterministic: seeded queries and IEEE float arithmetic
    // without contraction (-ffp-contract=off, model/core/CMakeLists.txt)
    // give the same answers on every run. On these ordinary queries both
    // float tests agree with the exact test everywhere (measured: 0 of
    // 200,000), so any error here is a change of a float test, not rounding.
    EXPECT_GT(e.hits, e.n / 5);
    EXPECT_EQ(e.smits_fm + e.smits_fh, 0u);
    EXPECT_EQ(e.pl_fm + e.pl_fh, 0u);
}

TEST(FloatTests, AgainstExactOnExtremeFamilies) {
    std::vector<std::size_t> fam;
    const auto qs = extreme_queries(0xf1a7e002, 16 * 6000, &fam);
    std::vector<Errors> per(extreme_family_count());
    Errors total;
    for (std::size_t i = 0; i < qs.size(); ++i) {
        per[fam[i]].add(qs[i]);
        total.add(qs[i]);
    }
    print_header("float tests vs exact, extreme families (FM = false misses, FH = false hits):");
    for (std::size_t f = 0; f < per.size(); ++f) {
        print_row(extreme_family_name(f), per[f]);
        const std::string key = extreme_family_name(f);
        RecordProperty(key + "_smits_fm", static_cast<int>(per[f].smits_fm));
        RecordProperty(key + "_smits_fh", static_cast<int>(per[f].smits_fh));
        RecordProperty(key + "_pluecker_fm", static_cast<int>(per[f].pl_fm));
        RecordProperty(key + "_pluecker_fh", static_cast<int>(per[f].pl_fh));
    }
    print_row("total", total);
    std::fflush(stdout);
    // Per family, the errors measured on these queries (deterministic, as
    // above) are the ceiling: a change of a float test that errs more often
    // in any family fails here (one that errs less should lower the table).
    // On these queries pluecker-cls misses no real hit; smits-mul-cls misses
    // most often exact edge and corner hits, flat and tiny boxes.
    struct Ceiling {
        const char* family;
        std::size_t smits_fm, smits_fh, pl_fm, pl_fh;
    };
    constexpr Ceiling kCeiling[] = {
        {"axis-parallel", 0, 0, 0, 0},      {"near-axis", 0, 53, 0, 34},        {"signed-zero", 27, 0, 0, 1},
        {"edge-exact", 255, 0, 0, 0},       {"edge-ulp", 165, 207, 0, 204},     {"corner-exact", 648, 0, 0, 0},
        {"corner-ulp", 346, 385, 0, 423},   {"flat-box", 1029, 167, 0, 176},    {"origin-on-box", 0, 0, 0, 2},
        {"segment-end", 0, 230, 0, 605},    {"unit-coords", 54, 384, 0, 437},   {"denormal-dir", 50, 0, 0, 0},
        {"tiny-dir", 81, 413, 0, 528},      {"huge-dir", 22, 540, 0, 567},      {"tiny-box", 480, 1373, 0, 1564},
        {"zero-length", 0, 0, 0, 0},
    };
    ASSERT_EQ(std::size(kCeiling), per.size());
    for (std::size_t f = 0; f < per.size(); ++f) {
        const Ceiling& c = kCeiling[f];
        ASSERT_STREQ(c.family, extreme_family_name(f));
        EXPECT_LE(per[f].smits_fm, c.smits_fm) << c.family;
        EXPECT_LE(per[f].smits_fh, c.smits_fh) << c.family;
        EXPECT_LE(per[f].pl_fm, c.pl_fm) << c.family;
        EXPECT_LE(per[f].pl_fh, c.pl_fh) << c.family;
        EXPECT_GT(per[f].hits, 0u) << c.family;
        EXPECT_LT(per[f].hits, per[f].n) << c.family;
    }
    // Exact axis-parallel rays are within reach of float arithmetic once the
    // 0*inf case is handled: smits must get every unbounded one right.
    Errors axis;
    for (std::size_t i = 0; i < qs.size(); ++i)
        if (fam[i] == 0 && std::isinf(qs[i].ray.tmax)) axis.add(qs[i]);
    EXPECT_EQ(axis.smits_fm + axis.smits_fh, 0u);
    EXPECT_EQ(axis.pl_fm + axis.pl_fh, 0u);
}

}  // namespace
}  // namespace pluecker
