// SPDX-License-Identifier: MIT
// The binary32 units' model (f32unit.hpp) against the host FPU and the
// float box tests:
//   - add, sub and mul in the three rounding modes against the host's
//     result (fesetround) on random and edge operands: identical wherever
//     the documented format agrees with IEEE-754 (no subnormal operand, no
//     underflow); where it does not, the documented rule, checked against
//     the host on the flushed operands;
//   - lt and le against the host's comparisons on every pattern, NaN and
//     subnormals included: always identical;
//   - the units: f32_pluecker_hit (nearest) against pluecker_hit and
//     f32_smits_hit against smits_hit: identical on random queries, the
//     differences on the extreme families counted and printed, each one
//     traced to a subnormal operand or result; the conservative Plücker
//     unit never misses a real hit (exact_hit) and its segment end is the
//     exact outward rounding.
// PLUECKER_LONG=1 (make sim-regress) runs 10x the operands and queries.
#include "pluecker/boxtest.hpp"
#include "pluecker/f32unit.hpp"
#include "pluecker/querygen.hpp"
#include "pluecker/rng.hpp"

#include "fixed_test_support.hpp"

#include <gtest/gtest.h>

#include <cfenv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace pluecker {
namespace {

using f32::Bits;
using f32::Round;
using test_support::long_run;
__extension__ typedef __float128 Quad;  // binary128: exact for the end test's magnitudes

std::size_t scaled(std::size_t n) { return long_run() ? 10 * n : n; }

// --- the host FPU as reference ------------------------------------------------

int fe_mode(Round r) {
    switch (r) {
        case Round::Up: return FE_UPWARD;
        case Round::Down: return FE_DOWNWARD;
        default: return FE_TONEAREST;
    }
}

enum class Op { Add, Sub, Mul };

struct HostResult {
    Bits bits;
};

// One host operation in rounding mode r (volatile operands and result, so
// that the compiler neither folds nor moves it across fesetround).
HostResult host(Op op, Bits a, Bits b, Round r) {
    volatile float x = f32::float_of(a), y = f32::float_of(b);
    volatile float z = 0;
    std::fesetround(fe_mode(r));
    switch (op) {
        case Op::Add: z = x + y; break;
        case Op::Sub: z = x - y; break;
        case Op::Mul: z = x * y; break;
    }
    std::fesetround(FE_TONEAREST);
    return {f32::bits_of(z)};
}

Bits model(Op op, Bits a, Bits b, Round r) {
    switch (op) {
        case Op::Add: return f32::add(a, b, r);
        case Op::Sub: return f32::sub(a, b, r);
        default: return f32::mul(a, b, r);
    }
}

const char* op_name(Op op) { return op == Op::Add ? "add" : op == Op::Sub ? "sub" : "mul"; }
const char* round_name(Round r) { return r == Round::Nearest ? "nearest" : r == Round::Up ? "up" : "down"; }

// The documented flush of a subnormal operand, as the host's operand: the
// same value the model reads (f32unit.hpp).
Bits flushed_operand(Op op, Bits x, Bits other, Round r, bool second) {
    if (!f32::is_subnormal(x)) return x;
    const bool sx = (x & f32::kSignBit) != 0;
    bool grow = false;
    if (op == Op::Mul) {
        const bool s = sx != ((other & f32::kSignBit) != 0);
        grow = (r == Round::Up && !s) || (r == Round::Down && s);
    } else {
        const bool s = (op == Op::Sub && second) ? !sx : sx;  // the sign it is added with
        grow = (r == Round::Up && !s) || (r == Round::Down && s);
    }
    return (grow ? f32::kMinNormal : 0u) | (x & f32::kSignBit);
}

// The documented flush of a tiny result (below 2^-126 after rounding with
// an unbounded exponent): the host's underflowing result decides the sign.
Bits flushed_result(Bits host_bits, Round r) {
    const bool s = (host_bits & f32::kSignBit) != 0;
    const bool grow = (r == Round::Up && !s) || (r == Round::Down && s);
    return (grow ? f32::kMinNormal : 0u) | (host_bits & f32::kSignBit);
}

// True when the exact product of a and b, rounded to 24 bits in mode r
// with an unbounded exponent, is below 2^-126 in magnitude (and not zero).
bool mul_is_tiny(Bits a, Bits b, Round r) {
    const double exact = double(f32::float_of(a)) * double(f32::float_of(b));  // exact
    if (exact == 0 || !std::isfinite(exact) || std::fabs(exact) >= 0x1p-126) return false;
    volatile double scaled = exact * 0x1p100;  // exact, far from the subnormals
    std::fesetround(fe_mode(r));
    volatile float rounded = static_cast<float>(scaled);
    std::fesetround(FE_TONEAREST);
    return std::fabs(rounded) < 0x1p-26f;
}

struct Agreement {
    std::size_t compared = 0, exact = 0, flushed_operand = 0, tiny = 0;
};

// Checks one operation: identical to the host where the format agrees
// with IEEE-754; otherwise the documented rule, with the host's result on
// the flushed operands as reference.
void check_op(Op op, Bits a, Bits b, Round r, Agreement& agr) {
    const Bits got = model(op, a, b, r);
    const Bits fa = flushed_operand(op, a, b, r, false);
    const Bits fb = flushed_operand(op, b, a, r, true);
    const HostResult h = host(op, fa, fb, r);
    ++agr.compared;
    agr.flushed_operand += (fa != a || fb != b);
    Bits want = h.bits;
    if (f32::is_nan(h.bits)) {
        EXPECT_TRUE(f32::is_nan(got)) << op_name(op) << " " << round_name(r) << std::hex << " a=" << a << " b=" << b;
        EXPECT_EQ(got, f32::kNaN);
        return;
    }
    // A result below 2^-126 after rounding to 24 bits with an unbounded
    // exponent is flushed (f32unit.hpp). A sum of two binary32 values that
    // small is exact, so the host returns it as a subnormal; a product may
    // round, so its exact value (a double: 48 significand bits) is rounded
    // by the host at an exponent far from the subnormal range.
    const bool tiny = op == Op::Mul ? mul_is_tiny(fa, fb, r) : f32::is_subnormal(h.bits);
    if (tiny) {
        ++agr.tiny;
        want = flushed_result(h.bits, r);
    } else if (fa == a && fb == b) {
        ++agr.exact;
    }
    EXPECT_EQ(got, want) << op_name(op) << " " << round_name(r) << std::hex << " a=0x" << a << " b=0x" << b
                         << " host=0x" << h.bits;
}

// Random patterns that cover every exponent, with extra weight on the
// ones close to each other (cancellation) and at the ends of the range.
Bits random_operand(Rng& g) {
    const std::uint32_t kind = g.below(16);
    Bits x = static_cast<Bits>(g.next());
    if (kind < 2) x = (x & 0x807fffffu) | ((110u + g.below(20)) << 23);  // near 2^-8..2^11
    if (kind == 2) x = (x & 0x807fffffu) | (g.below(3) << 23);          // tiny and subnormal
    if (kind == 3) x = (x & 0x807fffffu) | ((252u + g.below(3)) << 23); // huge
    return x;
}

Bits near(Rng& g, Bits x) {
    // A neighbour within a few ulps, or with another sign.
    const Bits y = x + g.below(8) - 4;
    return g.coin() ? y : y ^ f32::kSignBit;
}

std::vector<Bits> edge_operands() {
    std::vector<Bits> v = {0x00000000u, 0x00000001u, 0x00000002u, 0x007fffffu, 0x00400000u, 0x00800000u,
                           0x00800001u, 0x00ffffffu, 0x01000000u, 0x0d000000u, 0x33800000u, 0x34000000u,
                           0x3f000000u, 0x3f7fffffu, 0x3f800000u, 0x3f800001u, 0x3fc00000u, 0x40000000u,
                           0x4b000000u, 0x4b7fffffu, 0x7e800000u, 0x7f000000u, 0x7f7ffffeu, 0x7f7fffffu,
                           0x7f800000u, 0x7f800001u, 0x7fc00000u, 0x7fffffffu, 0x1f800000u, 0x5f800000u};
    const std::size_t n = v.size();
    for (std::size_t i = 0; i < n; ++i) v.push_back(v[i] ^ f32::kSignBit);
    return v;
}

constexpr Round kRounds[] = {Round::Nearest, Round::Up, Round::Down};
constexpr Op kOps[] = {Op::Add, Op::Sub, Op::Mul};

TEST(F32Unit, PrimitivesMatchTheHostOnEdgeOperands) {
    const std::vector<Bits> v = edge_operands();
    for (Op op : kOps)
        for (Round r : kRounds) {
            Agreement agr;
            for (Bits a : v)
                for (Bits b : v) check_op(op, a, b, r, agr);
            std::printf("[ f32 edge ] %s %-7s: %zu pairs, %zu as IEEE-754, %zu with a flushed operand, %zu tiny results\n",
                        op_name(op), round_name(r), agr.compared, agr.exact, agr.flushed_operand, agr.tiny);
        }
}

TEST(F32Unit, PrimitivesMatchTheHostOnRandomOperands) {
    Rng g(0xf32a0001);
    const std::size_t n = scaled(300000);
    for (Op op : kOps)
        for (Round r : kRounds) {
            Agreement agr;
            for (std::size_t k = 0; k < n; ++k) {
                const Bits a = random_operand(g);
                const Bits b = g.below(4) == 0 ? near(g, a) : random_operand(g);
                check_op(op, a, b, r, agr);
                if (::testing::Test::HasFailure() && agr.compared > 1000) break;
            }
            std::printf("[ f32 random ] %s %-7s: %zu pairs, %zu as IEEE-754, %zu with a flushed operand, %zu tiny "
                        "results\n",
                        op_name(op), round_name(r), agr.compared, agr.exact, agr.flushed_operand, agr.tiny);
            EXPECT_GT(agr.exact, n * 8 / 10);
            EXPECT_GT(agr.flushed_operand, 0u);
            EXPECT_GT(agr.tiny, 0u);
        }
}

// Normal operands with normal results: every rounding case (ties, carries
// out of the significand, cancellation) against the host, the most common
// path of the units.
TEST(F32Unit, NormalResultsAreIeee) {
    Rng g(0xf32a0002);
    std::size_t checked = 0;
    for (std::size_t k = 0; k < scaled(200000); ++k) {
        const Bits a = (static_cast<Bits>(g.next()) & 0x807fffffu) | ((100u + g.below(50)) << 23);
        Bits b = (static_cast<Bits>(g.next()) & 0x807fffffu) | ((100u + g.below(50)) << 23);
        if (g.below(3) == 0) b = (a & 0xff800000u) | (static_cast<Bits>(g.next()) & 0x7fffffu & ~(0xffu << g.below(24)));
        for (Op op : kOps)
            for (Round r : kRounds) {
                const HostResult h = host(op, a, b, r);
                EXPECT_EQ(model(op, a, b, r), h.bits)
                    << op_name(op) << " " << round_name(r) << std::hex << " a=0x" << a << " b=0x" << b;
                ++checked;
            }
        if (::testing::Test::HasFailure()) break;
    }
    std::printf("[ f32 normal ] %zu operations identical to the host\n", checked);
}

TEST(F32Unit, ComparisonsAreIeeeOnEveryPattern) {
    std::vector<Bits> v = edge_operands();
    Rng g(0xf32a0003);
    for (int k = 0; k < 400; ++k) v.push_back(random_operand(g));
    std::size_t n = 0;
    for (Bits a : v)
        for (Bits b : v) {
            const float x = f32::float_of(a), y = f32::float_of(b);
            ASSERT_EQ(f32::lt(a, b), x < y) << std::hex << a << " " << b;
            ASSERT_EQ(f32::le(a, b), x <= y) << std::hex << a << " " << b;
            ++n;
        }
    std::printf("[ f32 compare ] %zu pairs identical to the host\n", n);
}

TEST(F32Unit, RoundPackFlushesAndOverflowsAsDocumented) {
    using f32::round_pack;
    // 2^-127 exactly: tiny. Nearest: +0; Up: 2^-126; Down: +0; negative mirrored.
    EXPECT_EQ(round_pack(false, 1, -127, Round::Nearest), 0x00000000u);
    EXPECT_EQ(round_pack(false, 1, -127, Round::Up), f32::kMinNormal);
    EXPECT_EQ(round_pack(false, 1, -127, Round::Down), 0x00000000u);
    EXPECT_EQ(round_pack(true, 1, -127, Round::Nearest), 0x80000000u);
    EXPECT_EQ(round_pack(true, 1, -127, Round::Up), 0x80000000u);
    EXPECT_EQ(round_pack(true, 1, -127, Round::Down), 0x80800000u);
    // (2^24 - 1) * 2^-150 = 2^-126 - 2^-150 rounds (nearest, up) to 2^-126 with
    // an unbounded exponent: kept; down: tiny.
    EXPECT_EQ(round_pack(false, (1u << 25) - 1, -151, Round::Nearest), f32::kMinNormal);
    EXPECT_EQ(round_pack(false, (1u << 25) - 1, -151, Round::Up), f32::kMinNormal);
    EXPECT_EQ(round_pack(false, (1u << 25) - 1, -151, Round::Down), 0u);
    // 2^128: overflow.
    EXPECT_EQ(round_pack(false, 1, 128, Round::Nearest), f32::kInf);
    EXPECT_EQ(round_pack(false, 1, 128, Round::Up), f32::kInf);
    EXPECT_EQ(round_pack(false, 1, 128, Round::Down), f32::kMaxFinite);
    EXPECT_EQ(round_pack(true, 1, 128, Round::Up), f32::kMaxFinite | f32::kSignBit);
    EXPECT_EQ(round_pack(true, 1, 128, Round::Down), f32::kInf | f32::kSignBit);
    // Far-apart operands: the smaller one only as a sticky remainder.
    EXPECT_EQ(f32::add(0x7f000000u, 0x00800000u, Round::Up), 0x7f000001u);
    EXPECT_EQ(f32::add(0x7f000000u, 0x80800000u, Round::Down), 0x7effffffu);
    EXPECT_EQ(f32::add(0x7f000000u, 0x80800000u, Round::Nearest), 0x7f000000u);
}

// --- the units --------------------------------------------------------------------

bool has_subnormal(const Query& q) {
    auto sub = [](float x) { return f32::is_subnormal(f32::bits_of(x)); };
    for (int a = 0; a < 3; ++a)
        if (sub(q.ray.o[a]) || sub(q.ray.d[a]) || sub(q.box.lo[a]) || sub(q.box.hi[a])) return true;
    return sub(q.ray.tmax);
}

// True when an add or mul of the unit's datapath has a subnormal operand or
// a result the host makes subnormal or underflows: where the format is
// documented to differ from IEEE-754.
bool pluecker_touches_subnormals(const Query& q) {
    if (has_subnormal(q)) return true;
    const PlueckerRay p = pluecker_setup(q.ray);
    float A[3], B[3], D[3];
    auto tiny = [](float x) { return x != 0 && std::fabs(x) < std::numeric_limits<float>::min(); };
    for (int i = 0; i < 3; ++i) {
        const bool n = class_negative(p.cls, i);
        A[i] = n ? p.o[i] - q.box.hi[i] : q.box.lo[i] - p.o[i];
        B[i] = n ? p.o[i] - q.box.lo[i] : q.box.hi[i] - p.o[i];
        D[i] = std::fabs(p.d[i]);
        if (tiny(A[i]) || tiny(B[i])) return true;
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            if (i == j) continue;
            const double pe = double(B[j]) * D[i], qe = double(A[i]) * D[j];  // exact products
            if ((pe != 0 && std::fabs(pe) < 0x1p-126) || (qe != 0 && std::fabs(qe) < 0x1p-126)) return true;
        }
    return false;
}

bool smits_touches_subnormals(const Query& q) {
    if (has_subnormal(q)) return true;
    const SmitsRay s = smits_setup(q.ray);
    auto tiny = [](double x) { return x != 0 && std::fabs(x) < 0x1p-126; };
    for (int a = 0; a < 3; ++a) {
        if (f32::is_subnormal(f32::bits_of(s.inv[a]))) return true;
        for (float plane : {q.box.lo[a], q.box.hi[a]}) {
            const float dpl = plane - s.o[a];
            if (tiny(dpl) || tiny(double(dpl) * s.inv[a])) return true;
        }
    }
    return false;
}

struct UnitTally {
    std::size_t queries = 0, differ = 0, differ_unexplained = 0, real_hits = 0, false_misses = 0, false_hits = 0,
                host_false_misses = 0, host_false_hits = 0;
};

template <class Unit, class Host, class Explained>
UnitTally compare_unit(const std::vector<Query>& qs, Unit unit, Host host_test, Explained explained) {
    UnitTally t;
    for (const Query& q : qs) {
        const bool u = unit(q), h = host_test(q), e = exact_hit(q.ray, q.box);
        ++t.queries;
        t.real_hits += e;
        t.false_misses += e && !u;
        t.false_hits += !e && u;
        t.host_false_misses += e && !h;
        t.host_false_hits += !e && h;
        if (u != h) {
            ++t.differ;
            if (!explained(q)) {
                ++t.differ_unexplained;
                if (t.differ_unexplained <= 5) ADD_FAILURE() << "unit and host differ without a subnormal: " << q.ray.o.x;
            }
        }
    }
    return t;
}

void print_tally(const char* what, const char* unit, const char* host, const UnitTally& t) {
    std::printf("[ f32 %-8s] %-14s %zu queries, %zu real hits: false misses %zu, false hits %zu; %-8s false misses "
                "%zu, false hits %zu; unit != %s on %zu (all with a subnormal operand or result: %s)\n",
                what, unit, t.queries, t.real_hits, t.false_misses, t.false_hits, host, t.host_false_misses,
                t.host_false_hits, host, t.differ, t.differ_unexplained == 0 ? "yes" : "NO");
}

auto pluecker_unit = [](const Query& q) { return f32_pluecker_hit(q.ray, q.box, false); };
auto pluecker_host = [](const Query& q) { return pluecker_hit(pluecker_setup(q.ray), q.box); };
auto smits_unit = [](const Query& q) { return f32_smits_hit(q.ray, q.box); };
auto smits_host = [](const Query& q) { return smits_hit(smits_setup(q.ray), q.box); };

TEST(F32Unit, UnitsEqualTheHostFloatTestsOnRandomQueries) {
    const std::vector<Query> qs = random_queries(0xf32b0001, scaled(100000));
    const UnitTally p = compare_unit(qs, pluecker_unit, pluecker_host, pluecker_touches_subnormals);
    const UnitTally s = compare_unit(qs, smits_unit, smits_host, smits_touches_subnormals);
    print_tally("random", "f32 pluecker", "pluecker", p);
    print_tally("random", "f32 smits", "smits", s);
    EXPECT_EQ(p.differ, 0u);
    EXPECT_EQ(s.differ, 0u);
}

TEST(F32Unit, UnitsOnTheExtremeFamilies) {
    std::vector<std::size_t> fam;
    const std::vector<Query> qs = extreme_queries(0xf32b0002, scaled(60000), &fam);
    const UnitTally p = compare_unit(qs, pluecker_unit, pluecker_host, pluecker_touches_subnormals);
    const UnitTally s = compare_unit(qs, smits_unit, smits_host, smits_touches_subnormals);
    print_tally("extreme", "f32 pluecker", "pluecker", p);
    print_tally("extreme", "f32 smits", "smits", s);
    EXPECT_EQ(p.differ_unexplained, 0u);
    EXPECT_EQ(s.differ_unexplained, 0u);
    // Per family, the answers that differ from the host's.
    std::vector<std::size_t> pd(extreme_family_count()), sd(extreme_family_count());
    for (std::size_t i = 0; i < qs.size(); ++i) {
        pd[fam[i]] += pluecker_unit(qs[i]) != pluecker_host(qs[i]);
        sd[fam[i]] += smits_unit(qs[i]) != smits_host(qs[i]);
    }
    for (std::size_t f = 0; f < pd.size(); ++f)
        if (pd[f] || sd[f])
            std::printf("[ f32 extreme ] family %-18s: f32 pluecker != pluecker %zu, f32 smits != smits %zu\n",
                        extreme_family_name(f), pd[f], sd[f]);
}

TEST(F32Unit, ConservativePlueckerNeverMisses) {
    std::vector<Query> qs = extreme_queries(0xf32b0003, scaled(100000));
    const std::vector<Query> rq = random_queries(0xf32b0004, scaled(50000));
    qs.insert(qs.end(), rq.begin(), rq.end());
    std::size_t real = 0, fm = 0, fh = 0, nfm = 0;
    for (const Query& q : qs) {
        const bool e = exact_hit(q.ray, q.box);
        const bool c = f32_pluecker_hit(q.ray, q.box, true);
        const bool n = f32_pluecker_hit(q.ray, q.box, false);
        real += e;
        fm += e && !c;
        fh += !e && c;
        nfm += e && !n;
        if (e && !c && fm <= 5) ADD_FAILURE() << "conservative f32 pluecker misses a real hit: " << q.ray.o.x;
    }
    std::printf("[ f32 conservative ] %zu queries, %zu real hits: false misses %zu, false hits %zu (nearest: false "
                "misses %zu)\n",
                qs.size(), real, fm, fh, nfm);
    EXPECT_EQ(fm, 0u);
}

// The conservative set-up's segment end: each component the exact o + t*d
// rounded outward (checked in binary128, exact for these magnitudes).
TEST(F32Unit, ConservativeEndIsTheOutwardRounding) {
    Rng g(0xf32b0005);
    std::size_t checked = 0;
    for (std::size_t k = 0; k < scaled(50000); ++k) {
        Ray r;
        for (int a = 0; a < 3; ++a) {
            r.o[a] = g.sym() * std::ldexp(1.0f, static_cast<int>(g.below(20)) - 10);
            r.d[a] = g.sym() * std::ldexp(1.0f, static_cast<int>(g.below(20)) - 10);
        }
        r.tmax = g.unit() * std::ldexp(1.0f, static_cast<int>(g.below(20)) - 10);
        if (r.d == Vec3(0.0f)) continue;
        Box b;
        b.lo = Vec3(-1.0f);
        b.hi = Vec3(1.0f);
        const F32PlueckerQuery q = f32_pluecker_query(r, b, true);
        ASSERT_TRUE(q.has_end);
        for (int a = 0; a < 3; ++a) {
            const Quad exact = static_cast<Quad>(r.o[a]) +
                                     static_cast<Quad>(r.tmax) * static_cast<Quad>(r.d[a]);
            const float e = f32::float_of(q.end[static_cast<std::size_t>(a)]);
            const bool up = !class_negative(q.cls, a);
            const float beyond = std::nextafter(e, up ? -kInf : kInf);  // the float on the other side
            const Quad qe = static_cast<Quad>(e), qb = static_cast<Quad>(beyond);
            ASSERT_TRUE(up ? (qe >= exact && qb < exact) : (qe <= exact && qb > exact))
                << "axis " << a << ": o " << r.o[a] << " t " << r.tmax << " d " << r.d[a] << " end " << e;
            ++checked;
        }
    }
    std::printf("[ f32 end ] %zu components rounded outward exactly\n", checked);
}

}  // namespace
}  // namespace pluecker
