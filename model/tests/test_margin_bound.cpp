// SPDX-License-Identifier: MIT
// The conservative margin of fixed.hpp exercised at its bound.
//
// Slack. For one edge test (i, j) the datapath checks s_ij >= 0 with
//   s_ij = 2*T_ij + |A_i| + |B_j| + D_i + D_j + 1,   T_ij = B_j*D_i - A_i*D_j
// (fixed.hpp). s is an integer; its unit is half an LSB of T.
//
// What the tests below establish
//   1. No real hit ever fails the test (the proof in fixed.hpp), also for
//      rays built to pass exactly through a box edge or corner (exact
//      t_ij = 0) with origin and direction components on half-LSB rounding
//      ties, rounded both ways (ties to even, both parities of the planes).
//   2. The bound is tight to within one unit of s, and the "+1" is the unit
//      it gives away: every real hit has s_ij >= 1, not only >= 0.
//      Why: fixed.hpp step 3 bounds 2*(T - t) from below by
//        -(|b_j| + |a_i| + D_i + D_j) >= -(|B_j| + |A_i| + 1 + D_i + D_j),
//      so s >= 2t >= 0, with s = 0 only if t = 0 and every inequality is
//      tight: |e_i| = |e_j| = 1/2 (origin on ties in i and j) with
//      sign(e_j) = -sign(b_j), sign(e_i) = -sign(a_i), D_j*e_i = +D_j/2,
//      D_i*e_j = -D_i/2, |h_i| = 1/2 with b_j*h_i <= 0, and
//      |h_j| = 1/2 with a_i*h_j >= 0. A real hit has b_j >= 0, here b_j > 0,
//      so e_j = -1/2. If a_i < 0 (e_i = +1/2), t = b_j*delta_i + |a_i|*delta_j
//      = 0 forces delta_i = delta_j = 0, hence h_i = 0, but b_j*h_i must be
//      -|b_j|/2 < 0. If a_i > 0 (e_i = -1/2), D_j*e_i = +D_j/2 forces D_j = 0,
//      so delta_j <= 1/2 and h_j = -delta_j <= 0, but a_i*h_j must be
//      +|a_i|/2 > 0. a_i = 0 contradicts |a_i| = |A_i| + 1/2. So s >= 1:
//      the datapath would still never miss with the margin reduced by one
//      (dropping the "+1"); it would miss with the margin reduced by two, or
//      with any one of |A_i|, |B_j|, D_i, D_j dropped. The exhaustive lattice
//      below finds a real hit with s = 1 and a false miss for each of those
//      reduced margins, and none for the margin without the "+1".
//   3. The same holds on random and extreme queries at many widths.
//
// PLUECKER_LONG=1 enlarges every domain and adds exhaustive runs at 7/6 and
// 6/8 on a second lattice (off-grid box planes, non-dyadic directions,
// segments).
#include "pluecker/boxtest.hpp"
#include "pluecker/contract.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/querygen.hpp"

#include "fixed_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace pluecker {
namespace {

using test_support::for_each_lattice_ray;
using test_support::format;
using test_support::setup_ray;
using test_support::lattice_boxes;
using test_support::long_run;
using test_support::Tally;

using i64 = std::int64_t;

// ---------------------------------------------------------------------------
// The datapath of fixed.hpp, term by term (so the margin can be varied). It
// is checked against fixed_hit on every query it sees.
// ---------------------------------------------------------------------------
constexpr int kPair[6][2] = {{0, 1}, {0, 2}, {1, 2}, {1, 0}, {2, 0}, {2, 1}};

struct Terms {
    bool origin_ok = true, end_ok = true;
    std::array<i64, 6> T{}, abs_a{}, abs_b{}, d_i{}, d_j{};
};

Terms terms(const FixedRay& r, const FixedBox& b) {
    Terms t;
    i64 A[3], B[3];
    for (int a = 0; a < 3; ++a) {
        const bool neg = class_negative(r.cls, a);
        A[a] = neg ? r.org[a] - b.hi[a] : b.lo[a] - r.org[a];
        B[a] = neg ? r.org[a] - b.lo[a] : b.hi[a] - r.org[a];
        t.origin_ok = t.origin_ok && B[a] >= 0;
        if (r.has_end) t.end_ok = t.end_ok && (neg ? b.hi[a] - r.end[a] : r.end[a] - b.lo[a]) >= 0;
    }
    for (int k = 0; k < 6; ++k) {
        const int i = kPair[k][0], j = kPair[k][1];
        t.T[k] = B[j] * r.dir[i] - A[i] * r.dir[j];
        t.abs_a[k] = std::llabs(A[i]);
        t.abs_b[k] = std::llabs(B[j]);
        t.d_i[k] = r.dir[i];
        t.d_j[k] = r.dir[j];
    }
    return t;
}

enum class Margin { Full, NoPlusOne, MinusTwo, NoAbsA, NoAbsB, NoDi, NoDj };
constexpr Margin kReduced[] = {Margin::NoPlusOne, Margin::MinusTwo, Margin::NoAbsA,
                               Margin::NoAbsB,    Margin::NoDi,     Margin::NoDj};

const char* margin_name(Margin m) {
    switch (m) {
        case Margin::Full: return "|A_i|+|B_j|+D_i+D_j+1";
        case Margin::NoPlusOne: return "without +1";
        case Margin::MinusTwo: return "minus 2";
        case Margin::NoAbsA: return "without |A_i|";
        case Margin::NoAbsB: return "without |B_j|";
        case Margin::NoDi: return "without D_i";
        case Margin::NoDj: return "without D_j";
    }
    return "?";
}

i64 slack(const Terms& t, int k, Margin m = Margin::Full) {
    i64 s = 2 * t.T[k] + t.abs_a[k] + t.abs_b[k] + t.d_i[k] + t.d_j[k] + 1;
    switch (m) {
        case Margin::Full: break;
        case Margin::NoPlusOne: s -= 1; break;
        case Margin::MinusTwo: s -= 2; break;
        case Margin::NoAbsA: s -= t.abs_a[k]; break;
        case Margin::NoAbsB: s -= t.abs_b[k]; break;
        case Margin::NoDi: s -= t.d_i[k]; break;
        case Margin::NoDj: s -= t.d_j[k]; break;
    }
    return s;
}

bool hit_with(const Terms& t, Margin m) {
    if (!t.origin_ok || !t.end_ok) return false;
    for (int k = 0; k < 6; ++k)
        if (slack(t, k, m) < 0) return false;
    return true;
}

// Slack statistics over the edge tests of real hits.
struct SlackStats {
    std::size_t queries = 0, real_hits = 0, false_misses = 0, false_hits = 0, model_disagreements = 0;
    i64 min_slack = std::numeric_limits<i64>::max();
    std::map<i64, std::size_t> hist;  // slack -> edge tests of real hits (capped at kCap)
    std::map<Margin, std::size_t> reduced_misses;
    std::map<Margin, std::string> reduced_example;
    static constexpr i64 kCap = 12;

    void add(const Query& q, const FixedRay& r, const FixedBox& b, const FixedFormat& f, bool exact) {
        const Terms t = terms(r, b);
        const bool full = hit_with(t, Margin::Full);
        ++queries;
        model_disagreements += full != fixed_hit(r, b, f);
        false_misses += exact && !full;
        false_hits += !exact && full;
        if (!exact) return;
        ++real_hits;
        for (int k = 0; k < 6; ++k) {
            const i64 s = slack(t, k);
            min_slack = std::min(min_slack, s);
            ++hist[std::min(s, kCap)];
        }
        for (Margin m : kReduced) {
            if (hit_with(t, m)) continue;
            if (reduced_misses[m]++ == 0) reduced_example[m] = describe(q, t, m);
        }
    }

    static std::string describe(const Query& q, const Terms& t, Margin m) {
        char buf[512];
        int worst = 0;
        for (int k = 1; k < 6; ++k)
            if (slack(t, k, m) < slack(t, worst, m)) worst = k;
        std::snprintf(buf, sizeof buf,
                      "o=(%a %a %a) d=(%a %a %a) tmax=%a box=[%a %a %a]..[%a %a %a]: edge (%d,%d) "
                      "T=%lld |A|=%lld |B|=%lld D_i=%lld D_j=%lld, s=%lld",
                      q.ray.o.x, q.ray.o.y, q.ray.o.z, q.ray.d.x, q.ray.d.y, q.ray.d.z, q.ray.tmax, q.box.lo.x,
                      q.box.lo.y, q.box.lo.z, q.box.hi.x, q.box.hi.y, q.box.hi.z, kPair[worst][0], kPair[worst][1],
                      (long long)t.T[worst], (long long)t.abs_a[worst], (long long)t.abs_b[worst],
                      (long long)t.d_i[worst], (long long)t.d_j[worst], (long long)slack(t, worst));
        return buf;
    }

    void print(const char* what) const {
        std::printf("[ margin %s ] %zu queries, %zu real hits, false misses %zu, false hits %zu, min slack of a real "
                    "hit %lld\n",
                    what, queries, real_hits, false_misses, false_hits,
                    real_hits ? (long long)min_slack : -1LL);
        std::printf("[ margin %s ] slack histogram of the edge tests of real hits:", what);
        for (auto [s, n] : hist) std::printf(" %s%lld:%zu", s == kCap ? ">=" : "", (long long)s, n);
        std::printf("\n");
        for (Margin m : kReduced) {
            const auto it = reduced_misses.find(m);
            const std::size_t n = it == reduced_misses.end() ? 0 : it->second;
            std::printf("[ margin %s ]   margin %-14s: %zu false misses%s%s\n", what, margin_name(m), n,
                        n ? ", e.g. " : "", n ? reduced_example.at(m).c_str() : "");
        }
    }

    std::size_t misses_with(Margin m) const {
        const auto it = reduced_misses.find(m);
        return it == reduced_misses.end() ? 0 : it->second;
    }
};

// ---------------------------------------------------------------------------
// 1. Rays exactly through a box edge (and corner) at rounding ties.
// ---------------------------------------------------------------------------
// Geometry, in LSB units (coordinate LSB u = 2^-(C-2), direction LSB =
// 2^-(D-1) of the largest component). Axis k carries the largest component
// (exactly 1.0, delta_k = 2^(D-1)). The ray meets the line where the entry
// plane P_i of slab i and the exit plane P_j of slab j cross, at parameter
// 1/lambda: a_i = P_i - o_i (along the ray) and b_j = P_j - o_j satisfy
// delta_i = lambda*a_i and delta_j = lambda*b_j, so t_ij = b_j*delta_i -
// a_i*delta_j = 0 exactly. With a_i, b_j half-integers and lambda odd, the
// origin coordinates and both direction components sit on rounding ties.
struct AxisSpec {
    bool neg = false;
    double lo = 0, hi = 0, o = 0;  // LSB units
    double delta = 0;              // direction, direction-LSB units
};

Query build_query(const std::array<AxisSpec, 3>& ax, const FixedFormat& f) {
    Query q;
    const double u = f.coord_lsb(), ud = f.dir_lsb();
    for (int a = 0; a < 3; ++a) {
        q.ray.o[a] = static_cast<float>(ax[a].o * u);
        const float d = static_cast<float>(ax[a].delta * ud);
        q.ray.d[a] = ax[a].neg ? -d : d;
        q.box.lo[a] = static_cast<float>(ax[a].lo * u);
        q.box.hi[a] = static_cast<float>(ax[a].hi * u);
    }
    q.ray.tmax = kInf;
    return q;
}

// True when every number of the construction is a float as it stands.
bool exact_in_float(const std::array<AxisSpec, 3>& ax, const FixedFormat& f) {
    const double u = f.coord_lsb(), ud = f.dir_lsb();
    auto ok = [](double v) { return static_cast<double>(static_cast<float>(v)) == v; };
    for (const AxisSpec& s : ax)
        if (!ok(s.o * u) || !ok(s.lo * u) || !ok(s.hi * u) || !ok(s.delta * ud)) return false;
    return true;
}

bool in_range(double v, const FixedFormat& f) {
    return v >= static_cast<double>(f.coord_min()) && v <= static_cast<double>(f.coord_max());
}

TEST(MarginBound, RaysThroughEdgesAndCornersAtRoundingTies) {
    const std::vector<std::pair<int, int>> widths = {{6, 6},   {7, 6},   {6, 8},   {8, 8},   {12, 10},
                                                     {10, 14}, {16, 16}, {6, 24},  {24, 6},  {24, 24}};
    const std::vector<double> offsets = long_run()
                                            ? std::vector<double>{0.25, 0.5, 0.75, 1.5, 2.5, 3.5, 4.5, 5.5, 7.5, 10.5, 13.25}
                                            : std::vector<double>{0.5, 0.75, 1.5, 2.5, 3.5, 5.5};
    const std::vector<int> fixed_lambdas = long_run() ? std::vector<int>{1, 3, 5, 7, 9, 11, 15, 33, 63, 255}
                                                      : std::vector<int>{1, 3, 5, 9, 33};
    std::size_t total = 0;
    for (auto [c, dbits] : widths) {
        const FixedFormat f = format(c, dbits);
        const double one = std::ldexp(1.0, dbits - 1);
        // Odd lambdas near 2^(D-1)/16, /8, /4: the crossing point a few LSB
        // away along the major axis, so narrow coordinates fit wide directions.
        std::vector<int> lambdas = fixed_lambdas;
        for (int sh : {5, 4, 3}) lambdas.push_back((1 << (dbits - sh)) + 1);
        std::sort(lambdas.begin(), lambdas.end());
        lambdas.erase(std::unique(lambdas.begin(), lambdas.end()), lambdas.end());
        SlackStats st;
        std::map<i64, std::size_t> edge_hist;  // slack of the (i, j) edge the ray passes through
        i64 edge_min = std::numeric_limits<i64>::max();
        std::size_t corners = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                if (i == j) continue;
                const int k = 3 - i - j;
                for (int signs = 0; signs < 8; ++signs)
                    for (int lambda : lambdas)
                        for (double ai : offsets)
                            for (double bj : offsets)
                                for (int parity = 0; parity < 4; ++parity)
                                    for (int corner = 0; corner < 3; ++corner) {
                                        const double di = lambda * ai, dj = lambda * bj;
                                        if (di > one || dj > one) continue;
                                        const double ak = one / lambda;  // a_k = t* * delta_k
                                        if (corner && (lambda != 1)) continue;
                                        std::array<AxisSpec, 3> ax;
                                        ax[i].neg = signs & 1;
                                        ax[j].neg = signs & 2;
                                        ax[k].neg = signs & 4;
                                        const double Pi = (parity & 1) - 1.0, Pj = (parity >> 1) & 1;
                                        const double wi = 1 + (lambda % 3), wj = 2 - (lambda % 3 == 1);
                                        // slab i entered at P_i, slab j left at P_j
                                        if (!ax[i].neg) ax[i] = {false, Pi, Pi + wi, Pi - ai, di};
                                        else ax[i] = {true, Pi - wi, Pi, Pi + ai, di};
                                        if (!ax[j].neg) ax[j] = {false, Pj - wj, Pj, Pj - bj, dj};
                                        else ax[j] = {true, Pj, Pj + wj, Pj + bj, dj};
                                        // axis k: origin on a tie; the crossing point P_k inside
                                        // the slab, or (corner) on its entry or exit plane.
                                        const double sk = ax[k].neg ? -1.0 : 1.0;
                                        double ok = (parity & 1) ? 0.5 : -0.5;
                                        if (corner) ok = std::floor(ok);  // a_k is an integer: keep P_k on the grid
                                        const double Pk = ok + sk * ak;
                                        double lok = std::floor(std::min(ok, Pk)) - 1, hik = std::ceil(std::max(ok, Pk)) + 1;
                                        if (corner == 1) (ax[k].neg ? hik : lok) = Pk;  // entry plane of k
                                        if (corner == 2) (ax[k].neg ? lok : hik) = Pk;  // exit plane of k
                                        ax[k] = {ax[k].neg, lok, hik, ok, one};
                                        bool fits = true;
                                        for (const AxisSpec& s : ax)
                                            fits = fits && in_range(s.lo, f) && in_range(s.hi, f) && in_range(s.o, f);
                                        if (!fits || !exact_in_float(ax, f)) continue;
                                        const Query q = build_query(ax, f);
                                        const bool exact = exact_hit(q.ray, q.box);
                                        ASSERT_TRUE(exact) << "construction does not touch the box: "
                                                           << SlackStats::describe(q, Terms{}, Margin::Full);
                                        const FixedRay r = setup_ray(q.ray, f);
                                        const FixedBox b = fixed_quantize_box(q.box, f);
                                        st.add(q, r, b, f, exact);
                                        const Terms t = terms(r, b);
                                        int e = 0;
                                        while (kPair[e][0] != i || kPair[e][1] != j) ++e;
                                        ++edge_hist[std::min(slack(t, e), SlackStats::kCap)];
                                        edge_min = std::min(edge_min, slack(t, e));
                                        corners += corner != 0;
                                    }
            }
        char what[32];
        std::snprintf(what, sizeof what, "edge/corner %d/%d", c, dbits);
        st.print(what);
        std::printf("[ margin %s ] %zu corner rays; slack of the edge the ray passes through: min %lld, histogram",
                    what, corners, (long long)edge_min);
        for (auto [s, n] : edge_hist) std::printf(" %s%lld:%zu", s == SlackStats::kCap ? ">=" : "", (long long)s, n);
        std::printf("\n");
        EXPECT_GT(st.queries, 1000u) << what;
        EXPECT_EQ(st.false_misses, 0u) << what;
        EXPECT_EQ(st.model_disagreements, 0u) << what;
        EXPECT_GE(st.min_slack, 1) << what;
        EXPECT_EQ(st.misses_with(Margin::NoPlusOne), 0u) << what;
        total += st.queries;
    }
    std::printf("[ margin edge/corner ] %zu constructed rays in all\n", total);
}

// ---------------------------------------------------------------------------
// 2. Exhaustive lattice at 6/6 with an exact integer oracle.
// ---------------------------------------------------------------------------
// Every quantity is an integer in quarter-LSB units: box planes on the grid,
// origin coordinates on the quarter-LSB lattice (on the grid, a quarter off,
// on a tie), direction magnitudes on the quarter direction-LSB lattice.
// Axis 2 carries the largest component (exactly 1.0). The exact answer for
// the unbounded ray is then a few integer comparisons (the same definition
// as exact_hit); a sample of the lattice goes through the float model
// (fixed_setup_ray, fixed_hit, exact_hit) to confirm both sides.
struct LatticeAxis {
    int lo, hi;   // LSB
    int oq;       // origin, quarter LSB
    int dq;       // |direction|, quarter direction-LSB
    bool neg;
    // derived
    i64 a4, b4;   // exact entry/exit offsets along the ray, quarter LSB
    i64 O, D;     // quantised origin and direction (rounded to nearest, ties to even)
};

i64 round_quarter(i64 n) {  // n/4 to nearest, ties to even
    const i64 q = n >= 0 ? n / 4 : -((-n + 3) / 4);  // floor
    const i64 r = n - 4 * q;
    if (r < 2) return q;
    if (r > 2) return q + 1;
    return (q % 2 == 0) ? q : q + 1;
}

LatticeAxis make_axis(int lo, int hi, int oq, int dq, bool neg) {
    LatticeAxis a{lo, hi, oq, dq, neg, 0, 0, 0, 0};
    a.a4 = neg ? oq - 4 * hi : 4 * lo - oq;
    a.b4 = neg ? oq - 4 * lo : 4 * hi - oq;
    a.O = round_quarter(oq);
    a.D = round_quarter(dq);
    return a;
}

bool lattice_exact(const LatticeAxis* ax[3]) {
    for (int i = 0; i < 3; ++i) {
        if (ax[i]->b4 < 0) return false;
        if (ax[i]->dq == 0 && ax[i]->a4 > 0) return false;
    }
    for (int i = 0; i < 3; ++i) {
        if (ax[i]->dq == 0) continue;
        for (int j = 0; j < 3; ++j)
            if (ax[j]->dq != 0 && ax[i]->a4 * ax[j]->dq > ax[j]->b4 * ax[i]->dq) return false;
    }
    return true;
}

struct LatticeDomain {
    int coord_bits, dir_bits;
    std::vector<LatticeAxis> minor;  // for axes 0 and 1
    std::vector<LatticeAxis> major;  // for axis 2
};

LatticeDomain lattice_domain(bool big) {
    LatticeDomain dom{6, 6, {}, {}};
    const int reach = big ? 3 : 2;        // origins up to this many LSB outside the box
    const int max_width = big ? 3 : 2;    // box widths 0..max_width LSB
    std::vector<int> dqs;
    const int one_q = 4 << (dom.dir_bits - 1);  // 1.0 in quarter units (128)
    if (big) {
        for (int d = 0; d <= 16; ++d) dqs.push_back(d);
        for (int d : {18, 22, 30, 34, 62, 66, 98, 126, 127, 128}) dqs.push_back(d);
    } else {
        dqs = {0, 1, 2, 3, 4, 5, 6, 7, 10, 14, 18, 30, 34, 66, 126, 128};
    }
    for (int lo = 0; lo <= 1; ++lo)
        for (int w = 0; w <= max_width; ++w)
            for (int oq = 4 * (lo - reach); oq <= 4 * (lo + w + reach); ++oq)
                for (int dq : dqs)
                    for (bool neg : {false, true}) dom.minor.push_back(make_axis(lo, lo + w, oq, dq, neg));
    struct Major {
        int lo, hi, oq;
        bool neg;
    };
    std::vector<Major> majors = {{-12, 12, 0, false}};
    if (big) majors = {{-12, 12, 0, false}, {-12, 12, 2, true}, {-3, 20, 1, false}, {-20, 3, -2, true}};
    for (const Major& m : majors) dom.major.push_back(make_axis(m.lo, m.hi, m.oq, one_q, m.neg));
    return dom;
}

TEST(MarginBound, Exhaustive6x6LatticeSlackAndReducedMargins) {
    const bool big = long_run();
    const LatticeDomain dom = lattice_domain(big);
    const FixedFormat f = format(dom.coord_bits, dom.dir_bits);
    SlackStats st;
    std::size_t checked = 0, setup_mismatch = 0, exact_mismatch = 0;
    std::size_t counter = 0;
    const std::size_t sample = big ? 997 : 101;
    for (const LatticeAxis& z : dom.major)
        for (const LatticeAxis& x : dom.minor)
            for (const LatticeAxis& y : dom.minor) {
                const LatticeAxis* ax[3] = {&x, &y, &z};
                const bool exact = lattice_exact(ax);
                FixedRay r;
                FixedBox b;
                r.cls = static_cast<RayClass>((x.neg ? 1 : 0) | (y.neg ? 2 : 0) | (z.neg ? 4 : 0));
                for (int a = 0; a < 3; ++a) {
                    r.org[a] = ax[a]->O;
                    r.dir[a] = ax[a]->D;
                    b.lo[a] = ax[a]->lo;
                    b.hi[a] = ax[a]->hi;
                }
                Query q;
                const bool check = ++counter % sample == 0;
                if (check || exact) {  // the float query, for the example lines and the sample check
                    std::array<AxisSpec, 3> spec;
                    for (int a = 0; a < 3; ++a)
                        spec[a] = {ax[a]->neg, double(ax[a]->lo), double(ax[a]->hi), ax[a]->oq / 4.0, ax[a]->dq / 4.0};
                    q = build_query(spec, f);
                }
                if (check) {
                    ++checked;
                    const FixedRay r2 = setup_ray(q.ray, f);
                    const FixedBox b2 = fixed_quantize_box(q.box, f);
                    setup_mismatch += r2.cls != r.cls || r2.org != r.org || r2.dir != r.dir || r2.has_end ||
                                      b2.lo != b.lo || b2.hi != b.hi;
                    exact_mismatch += exact_hit(q.ray, q.box) != exact;
                }
                st.add(q, r, b, f, exact);
            }
    std::printf("[ margin lattice 6/6 ] %zu minor-axis x %zu x %zu major-axis configurations; %zu sampled through "
                "the float model\n",
                dom.minor.size(), dom.minor.size(), dom.major.size(), checked);
    st.print("lattice 6/6");
    EXPECT_EQ(setup_mismatch, 0u) << "the lattice's quantisation differs from fixed_setup_ray/fixed_quantize_box";
    EXPECT_EQ(exact_mismatch, 0u) << "the lattice oracle differs from exact_hit";
    EXPECT_GT(checked, 1000u);
    EXPECT_EQ(st.model_disagreements, 0u);
    EXPECT_EQ(st.false_misses, 0u);
    // Tight to within one unit: a real hit with s = 1 exists, s = 0 does not.
    EXPECT_EQ(st.min_slack, 1);
    EXPECT_EQ(st.misses_with(Margin::NoPlusOne), 0u);
    for (Margin m : {Margin::MinusTwo, Margin::NoAbsA, Margin::NoAbsB, Margin::NoDi, Margin::NoDj})
        EXPECT_GT(st.misses_with(m), 0u) << "no false miss with the margin " << margin_name(m);
}

// ---------------------------------------------------------------------------
// 3. Generated queries at many widths: s >= 1 for every real hit.
// ---------------------------------------------------------------------------
TEST(MarginBound, SlackOfEveryRealHitIsAtLeastOne) {
    const std::size_t n = long_run() ? 200000 : 20000;
    std::vector<Query> qs = random_queries(0x3a561001, n);
    const std::vector<Query> ex = extreme_queries(0x3a561002, n);
    qs.insert(qs.end(), ex.begin(), ex.end());
    std::vector<char> exact(qs.size());
    for (std::size_t k = 0; k < qs.size(); ++k) exact[k] = exact_hit(qs[k].ray, qs[k].box);
    for (auto [c, d] : std::vector<std::pair<int, int>>{{6, 6}, {6, 24}, {24, 6}, {8, 8}, {12, 10}, {16, 16}, {24, 24}}) {
        const FixedFormat f = format(c, d);
        SlackStats st;
        for (std::size_t k = 0; k < qs.size(); ++k)
            st.add(qs[k], setup_ray(qs[k].ray, f), fixed_quantize_box(qs[k].box, f), f, exact[k]);
        char what[32];
        std::snprintf(what, sizeof what, "generated %d/%d", c, d);
        st.print(what);
        EXPECT_EQ(st.model_disagreements, 0u) << what;
        EXPECT_EQ(st.false_misses, 0u) << what;
        EXPECT_GE(st.min_slack, 1) << what;
        EXPECT_EQ(st.misses_with(Margin::NoPlusOne), 0u) << what;
    }
}

// ---------------------------------------------------------------------------
// 4. A second exhaustive domain (floats, exact_hit): off-grid box planes
//    (rounded outward), origins on an eighth-LSB lattice, non-dyadic and
//    signed-zero direction components, unbounded rays and segments.
//    Short: 7/6 on a reduced domain; long: 7/6 and 6/8 on the full one.
// ---------------------------------------------------------------------------
void exhaustive_float_domain(int c, int d, bool big) {
    const FixedFormat f = format(c, d);
    const float u = static_cast<float>(f.coord_lsb());
    const std::vector<float> planes = big ? std::vector<float>{-1.3f * u, -0.5f * u, 0.7f * u}
                                          : std::vector<float>{-0.5f * u, 0.7f * u, 1.0f * u};
    const std::vector<float> coords =
        big ? std::vector<float>{-2.5f * u, -1.0f * u, -0.625f * u, -0.125f * u, 0.0f, 0.375f * u, 1.0f * u, 2.25f * u}
            : std::vector<float>{-1.5f * u, -0.625f * u, -0.125f * u, 0.5f * u, 1.0f * u, 2.25f * u};
    const std::vector<float> dirs = big ? std::vector<float>{-1.0f, -0.75f, -1.0f / 3.0f, -1.0f / 64.0f, -0.0f, 0.0f,
                                                             0.2f, 0.5f + 1.0f / 64.0f, 1.0f}
                                        : std::vector<float>{-1.0f, -1.0f / 3.0f, -0.0f, 0.2f, 0.5f + 1.0f / 64.0f, 1.0f};
    const std::vector<float> tmaxes = big ? std::vector<float>{kInf, 0.07f} : std::vector<float>{kInf};
    const std::vector<Box> boxes = lattice_boxes(planes);
    std::vector<FixedBox> qboxes;
    for (const Box& b : boxes) qboxes.push_back(fixed_quantize_box(b, f));
    SlackStats st;
    for_each_lattice_ray(coords, dirs, tmaxes, [&](const Ray& ray) {
        Query q;
        q.ray = ray;
        const FixedRay r = setup_ray(q.ray, f);
        for (std::size_t k = 0; k < boxes.size(); ++k) {
            q.box = boxes[k];
            st.add(q, r, qboxes[k], f, exact_hit(q.ray, q.box));
        }
    });
    char what[40];
    std::snprintf(what, sizeof what, "exhaustive %d/%d%s", c, d, big ? "" : " (reduced)");
    st.print(what);
    EXPECT_EQ(st.model_disagreements, 0u) << what;
    EXPECT_EQ(st.false_misses, 0u) << what;
    EXPECT_GE(st.min_slack, 1) << what;
    EXPECT_GT(st.queries, 100000u) << what;
}

TEST(MarginBound, ExhaustiveSecondDomain) {
    if (!long_run()) {
        exhaustive_float_domain(7, 6, false);
        return;
    }
    exhaustive_float_domain(7, 6, true);
    exhaustive_float_domain(6, 8, true);
}

// ---------------------------------------------------------------------------
// querygen's boundary_queries (the cocotb bench's and the harness's boundary
// operands) sit on the boundary each claims, and reach every value of it.
// ---------------------------------------------------------------------------
TEST(MarginBound, BoundaryQueriesSitOnTheBound) {
    for (const auto& [c, d] : {std::pair{6, 6}, std::pair{8, 8}, std::pair{7, 22}, std::pair{16, 16},
                               std::pair{24, 24}}) {
        for (const FixedMode m : {FixedMode::Conservative, FixedMode::Nearest}) {
            const FixedFormat f = format(c, d, m);
            const bool cons = m == FixedMode::Conservative;
            const std::string where = std::to_string(c) + "/" + std::to_string(d) + " " + mode_name(m);
            std::vector<std::size_t> kinds;
            const auto qs = boundary_queries(77, 3000, f, &kinds);
            ASSERT_EQ(qs.size(), 3000u);
            ASSERT_EQ(kinds.size(), qs.size());
            std::map<std::string, std::array<std::size_t, 2>> answers;  // per kind: misses, hits
            std::set<i64> values;
            for (std::size_t n = 0; n < qs.size(); ++n) {
                const FixedQuery& q = qs[n];
                ASSERT_EQ(kinds[n], n % boundary_kind_count());
                ASSERT_NO_THROW(pack_query(q.ray, q.box, f)) << where << " " << n;
                const std::string kind = boundary_kind_name(kinds[n]);
                const Terms t = terms(q.ray, q.box);
                const bool hit = fixed_hit(q.ray, q.box, f);
                ++answers[kind][hit];
                i64 min_b = std::numeric_limits<i64>::max(), min_g = min_b;
                for (int a = 0; a < 3; ++a) {
                    const bool neg = class_negative(q.ray.cls, a);
                    min_b = std::min(min_b, neg ? q.ray.org[a] - q.box.lo[a] : q.box.hi[a] - q.ray.org[a]);
                    min_g = std::min(min_g, neg ? q.box.hi[a] - q.ray.end[a] : q.ray.end[a] - q.box.lo[a]);
                }
                if (kind == "edge") {
                    ASSERT_TRUE(t.origin_ok && !q.ray.has_end) << where << " " << n;
                    // One edge test on the boundary: -2..1 (conservative), -1..1.
                    bool on = false;
                    for (int k = 0; k < 6; ++k) {
                        const i64 v = cons ? slack(t, k) : t.T[k];
                        if (v >= (cons ? -2 : -1) && v <= 1) {
                            on = true;
                            values.insert(v);
                        }
                    }
                    ASSERT_TRUE(on) << where << " " << n;
                } else if (kind == "end") {
                    ASSERT_TRUE(q.ray.has_end && t.origin_ok) << where << " " << n;
                    ASSERT_TRUE(min_g >= -1 && min_g <= 1) << where << " " << n;
                } else {
                    ASSERT_EQ(kind, "origin");
                    ASSERT_TRUE(min_b >= -1 && min_b <= 1) << where << " " << n;
                }
            }
            EXPECT_EQ(values.size(), cons ? 4u : 3u) << where;
            for (const auto& [kind, a] : answers) {
                EXPECT_GT(a[0], 50u) << where << " " << kind << ": misses";
                EXPECT_GT(a[1], 50u) << where << " " << kind << ": hits";
            }
        }
    }
}

}  // namespace
}  // namespace pluecker
