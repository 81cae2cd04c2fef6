// SPDX-License-Identifier: MIT
// The query text format (read/write/validate) and the query generators.
#include "pluecker/app/operand_file.hpp"
#include "pluecker/boxtest.hpp"
#include "pluecker/contract.hpp"
#include "pluecker/query.hpp"
#include "pluecker/querygen.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace pluecker {
namespace {

std::vector<std::uint32_t> bits(const Query& q) {
    const float f[13] = {q.ray.o.x,    q.ray.o.y,    q.ray.o.z,    q.ray.d.x,    q.ray.d.y,
                         q.ray.d.z,    q.ray.tmax,   q.box.lo.x,   q.box.lo.y,   q.box.lo.z,
                         q.box.hi.x,   q.box.hi.y,   q.box.hi.z};
    std::vector<std::uint32_t> out;
    for (float v : f) out.push_back(std::bit_cast<std::uint32_t>(v));
    return out;
}

std::vector<Query> parse(const std::string& text, const std::string& source = "t.txt") {
    std::istringstream in(text);
    return read_queries(in, source);
}

std::string text_of(const std::vector<Query>& qs) {
    std::ostringstream out;
    for (const Query& q : qs) write_query(out, q);
    return out.str();
}

// The read must fail with a message that starts with "<where>: " and
// contains `what`.
void expect_error(const std::string& text, const std::string& where, const std::string& what) {
    try {
        parse(text);
        ADD_FAILURE() << "no error for:\n" << text;
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind(where + ": ", 0), 0u) << msg;
        EXPECT_NE(msg.find(what), std::string::npos) << "'" << msg << "' lacks '" << what << "'";
    }
}

const std::string kGood = "0 0 -1  0 0 1  inf  -0.5 -0.5 -0.5 0.5 0.5 0.5\n";

// ---------------------------------------------------------------------------
// Reading and writing
// ---------------------------------------------------------------------------

TEST(QueryFormat, RoundTripIsBitExact) {
    std::vector<Query> qs = random_queries(0x9e1, 2000);
    const auto ex = extreme_queries(0x9e2, 2000);
    qs.insert(qs.end(), ex.begin(), ex.end());
    Query special;
    special.ray.o = Vec3(-0.0f, 0x1p-149f, -std::numeric_limits<float>::max());
    special.ray.d = Vec3(std::numeric_limits<float>::min(), -0.0f, 0.1f);
    special.ray.tmax = kInf;
    special.box.lo = Vec3(-0.0f, -1.0f, 1.0f / 3.0f);
    special.box.hi = Vec3(0.0f, std::nextafter(1.0f, 0.0f), std::numeric_limits<float>::max());
    qs.push_back(special);
    special.ray.tmax = -0.0f;
    qs.push_back(special);
    const auto back = parse(text_of(qs));
    ASSERT_EQ(back.size(), qs.size());
    for (std::size_t i = 0; i < qs.size(); ++i) ASSERT_EQ(bits(back[i]), bits(qs[i])) << "query " << i;
}

TEST(QueryFormat, WritesHexFloatsAndInf) {
    Query q;
    q.ray.o = Vec3(0.5f, -0.0f, 1.0f);
    q.ray.d = Vec3(0.0f, 0.0f, -1.0f);
    q.ray.tmax = kInf;
    q.box.lo = Vec3(-1.0f, 0.1875f, 0.0f);
    q.box.hi = Vec3(1.0f, 0.25f, 0x1p-149f);
    std::ostringstream out;
    write_query(out, q);
    EXPECT_EQ(out.str(), "0x1p-1 -0x0p+0 0x1p+0 0x0p+0 0x0p+0 -0x1p+0 inf -0x1p+0 0x1.8p-3 0x0p+0 0x1p+0 0x1p-2 0x1p-149\n");
}

TEST(QueryFormat, ReadsHexInfCommentsBlankLines) {
    const std::string text =
        "# a comment line\n"
        "\n"
        "   \t  \n"
        "0x1.8p-3 -0 1e-50  0 0 1 Infinity  -1 -1 -1 1 1 1   # trailing comment\n"
        "\t1\t2\t3\t-1 0 0 1e39 -1 -1 -1 1 1 1\r\n"
        "0.1 0 0 0 1 0 0x1p-2 0 0 0 0 0 0#comment right after\n"
        "0 0 0 0 1 0 INF 0 0 0 0 0 0\n";
    std::istringstream in(text);
    std::vector<std::size_t> lines;
    const auto qs = read_queries(in, "t.txt", &lines);
    ASSERT_EQ(qs.size(), 4u);
    EXPECT_EQ(lines, (std::vector<std::size_t>{4, 5, 6, 7}));
    EXPECT_TRUE(std::isinf(qs[3].ray.tmax));
    EXPECT_EQ(qs[0].ray.o.x, 0.1875f);
    EXPECT_TRUE(std::signbit(qs[0].ray.o.y));
    EXPECT_EQ(qs[0].ray.o.z, 0.0f);  // 1e-50 underflows to 0 in float
    EXPECT_TRUE(std::isinf(qs[0].ray.tmax));
    EXPECT_EQ(qs[1].ray.o, Vec3(1, 2, 3));
    EXPECT_TRUE(std::isinf(qs[1].ray.tmax));  // 1e39 is beyond the float range
    EXPECT_EQ(qs[1].box.hi.z, 1.0f);  // '\r' of CRLF is white space
    EXPECT_EQ(qs[2].ray.o.x, 0.1f);  // rounded to float
    EXPECT_EQ(qs[2].ray.tmax, 0.25f);
}

TEST(QueryFormat, RoundsDoublesToFloat) {
    auto first = [](const std::string& v) { return parse(v + " 0 0 0 0 1 inf -1e38 -1 -1 3.4e38 1 1\n")[0].ray.o.x; };
    EXPECT_EQ(first("16777217"), 16777216.0f);  // tie, to even
    EXPECT_EQ(first("16777219"), 16777220.0f);
    EXPECT_EQ(first("3.4028234663852886e38"), std::numeric_limits<float>::max());
    EXPECT_EQ(first("3.40282356e38"), std::numeric_limits<float>::max());  // just below the midpoint
    EXPECT_EQ(first("0x1.fffffefp127"), std::numeric_limits<float>::max());  // below the midpoint
    EXPECT_EQ(first("1e-46"), 0.0f);
    EXPECT_EQ(first("1e-45"), 0x1p-149f);
    // At or past the midpoint between FLT_MAX and 2^128: inf, so rejected as origin.
    expect_error("0x1.ffffffp127 0 0 0 0 1 inf -1 -1 -1 1 1 1\n", "t.txt:1", "ox is not a finite coordinate (inf)");
    expect_error("-1e39 0 0 0 0 1 inf -1 -1 -1 1 1 1\n", "t.txt:1", "ox is not a finite coordinate (-inf)");
}

TEST(QueryFormat, EmptyInput) {
    EXPECT_TRUE(parse("").empty());
    EXPECT_TRUE(parse("# nothing\n\n").empty());
}

TEST(QueryFormat, ErrorsNameTheLineAndTheProblem) {
    const std::string pre = "# header\n" + kGood + "\n";  // the bad line is line 4
    expect_error(pre + "0 0 -1 0 0 1 inf -0.5 -0.5 -0.5 0.5 0.5\n", "t.txt:4", "expected 13 numbers");
    expect_error(pre + "0 0 -1 0 0 1 inf -0.5 -0.5 -0.5 0.5 0.5\n", "t.txt:4", "found 12");
    expect_error(pre + "0 0 -1 0 0 1 inf -0.5 -0.5 -0.5 0.5 0.5 0.5 7\n", "t.txt:4", "found 14");
    expect_error(pre + "0 0 -1 0 abc 1 inf -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "'abc'");
    expect_error(pre + "0 0 -1 0 abc 1 inf -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "field 5 (dy)");
    expect_error(pre + "0 0 -1 0 0 1 inf -0.5 -0.5 -0.5 0.5 0.5 1.5.2\n", "t.txt:4", "'1.5.2'");
    expect_error(pre + "0x 0 -1 0 0 1 inf -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "'0x'");
    expect_error(pre + "0 0 -1 0 0 1e inf -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "'1e'");
    expect_error(pre + "nan 0 -1 0 0 1 inf -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "ox is NaN");
    expect_error(pre + "0 0 -1 0 0 -nan inf -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "dz is NaN");
    expect_error(pre + "0 0 -1 0 0 1 inf -0.5 -0.5 -0.5 0.5 NAN 0.5\n", "t.txt:4", "maxy is NaN");
    expect_error(pre + "0 0 -1 0 0 1 nan -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "tmax is NaN");
    expect_error(pre + "0 0 -1 0 0 0 inf -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "direction is zero");
    expect_error(pre + "0 0 -1 -0 0 -0 inf -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "direction is zero");
    expect_error(pre + "0 0 -1 0 0 1e-50 inf -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "direction is zero");
    expect_error(pre + "0 0 -1 0 0 1 -1 -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "tmax is negative (-1)");
    expect_error(pre + "0 0 -1 0 0 1 -inf -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "tmax is negative");
    expect_error(pre + "0 0 -1 0 0 1 inf -0.5 0.5 -0.5 0.5 0.25 0.5\n", "t.txt:4", "min > max on axis y");
    expect_error(pre + "0 0 -1 0 0 1 inf -0.5 -0.5 0.75 0.5 0.5 0.5\n", "t.txt:4", "axis z (minz = 0.75 > maxz = 0.5)");
    expect_error(pre + "0 inf -1 0 0 1 inf -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "oy is not a finite coordinate");
    expect_error(pre + "0 0 -1 0 0 1 inf -inf -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4", "minx is not a finite coordinate");
    expect_error(pre + "0 0 -1 0 0 1 inf -0.5 -0.5 -0.5 0.5 0.5 inf\n", "t.txt:4", "maxz is not a finite coordinate");
    expect_error(pre + "0 0 -1 0 0 inf inf -0.5 -0.5 -0.5 0.5 0.5 0.5\n", "t.txt:4",
                 "dz is not a finite direction component");
}

TEST(QueryFormat, FirstBadLineWins) {
    expect_error(kGood + kGood + kGood + "1 2 3\n" + "nan\n", "t.txt:4", "found 3");
    expect_error("x\n" + kGood, "t.txt:1", "found 1");
}

TEST(QueryFormat, ValidateQueryNamesWhere) {
    Query q;
    q.box.lo = Vec3(0.0f);
    q.box.hi = Vec3(1.0f);
    EXPECT_NO_THROW(validate_query(q, "here"));
    q.ray.d = Vec3(0.0f);
    try {
        validate_query(q, "trace.txt:17");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "trace.txt:17: direction is zero (dx = dy = dz = 0)");
    }
    q.ray.d = Vec3(0, 0, 1);
    q.box = Box{};  // the empty box: lo = inf
    EXPECT_THROW(validate_query(q, "x"), InputError);
}

TEST(QueryFormat, ReadFile) {
    const std::string path = testing::TempDir() + "/pluecker_queries.txt";
    {
        std::FILE* f = std::fopen(path.c_str(), "w");
        ASSERT_NE(f, nullptr);
        std::fputs((kGood + "1 2\n").c_str(), f);
        std::fclose(f);
    }
    try {
        read_queries_file(path);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(path + ":2: ", 0), 0u) << e.what();
    }
    try {
        read_queries_file(path + ".missing");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(path + ".missing"), std::string::npos) << e.what();
    }
    std::remove(path.c_str());
}

// ---------------------------------------------------------------------------
// Generators
// ---------------------------------------------------------------------------

bool in_unit(const Vec3& v) {
    return std::fabs(v.x) <= 1.0f && std::fabs(v.y) <= 1.0f && std::fabs(v.z) <= 1.0f;
}

void expect_valid_and_in_range(const std::vector<Query>& qs) {
    for (std::size_t i = 0; i < qs.size(); ++i) {
        const Query& q = qs[i];
        ASSERT_NO_THROW(validate_query(q, "query " + std::to_string(i)));
        ASSERT_TRUE(in_unit(q.ray.o) && in_unit(q.box.lo) && in_unit(q.box.hi)) << "query " << i;
    }
}

TEST(QueryGen, DeterministicAndPrefixStable) {
    const auto a = random_queries(42, 1000), b = random_queries(42, 1000), c = random_queries(43, 1000);
    const auto p = random_queries(42, 100);
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(bits(a[i]), bits(b[i]));
    for (std::size_t i = 0; i < p.size(); ++i) ASSERT_EQ(bits(a[i]), bits(p[i]));
    EXPECT_NE(bits(a[0]), bits(c[0]));
    const auto x = extreme_queries(42, 1000), y = extreme_queries(42, 1000), z = extreme_queries(42, 50);
    for (std::size_t i = 0; i < x.size(); ++i) ASSERT_EQ(bits(x[i]), bits(y[i]));
    for (std::size_t i = 0; i < z.size(); ++i) ASSERT_EQ(bits(x[i]), bits(z[i]));
}

TEST(QueryGen, ValidAndInRange) {
    expect_valid_and_in_range(random_queries(7, 50000));
    expect_valid_and_in_range(extreme_queries(7, 50000));
}

TEST(QueryGen, RandomHasHitsAndMissesAndSegments) {
    const auto qs = random_queries(8, 20000);
    std::size_t hits = 0, segments = 0;
    for (const Query& q : qs) {
        hits += exact_hit(q.ray, q.box);
        segments += std::isfinite(q.ray.tmax);
    }
    std::printf("random_queries: %zu of %zu hit, %zu segments\n", hits, qs.size(), segments);
    EXPECT_GT(hits, qs.size() / 5);
    EXPECT_LT(hits, qs.size() * 4 / 5);
    EXPECT_GT(segments, qs.size() / 8);
}

TEST(QueryGen, FamiliesNamedAndCycled) {
    const std::size_t n = extreme_family_count();
    EXPECT_GE(n, 16u);
    std::set<std::string> names;
    for (std::size_t f = 0; f < n; ++f) names.insert(extreme_family_name(f));
    EXPECT_EQ(names.size(), n);
    EXPECT_EQ(names.count("?"), 0u);
    EXPECT_STREQ(extreme_family_name(n), "?");
    std::vector<std::size_t> fam;
    const auto qs = extreme_queries(9, 3 * n + 5, &fam);
    ASSERT_EQ(fam.size(), qs.size());
    for (std::size_t i = 0; i < fam.size(); ++i) EXPECT_EQ(fam[i], i % n);
}

std::size_t family_index(const std::string& name) {
    for (std::size_t f = 0; f < extreme_family_count(); ++f)
        if (name == extreme_family_name(f)) return f;
    return extreme_family_count();
}

TEST(QueryGen, FamilyContents) {
    std::vector<std::size_t> fam;
    const auto qs = extreme_queries(10, 16 * 2000, &fam);
    const std::size_t n = extreme_family_count();
    std::vector<std::size_t> count(n), hits(n);
    for (std::size_t i = 0; i < qs.size(); ++i) {
        ++count[fam[i]];
        hits[fam[i]] += exact_hit(qs[i].ray, qs[i].box);
    }
    std::printf("extreme family hit rates:");
    for (std::size_t f = 0; f < n; ++f) std::printf(" %s %.2f", extreme_family_name(f), double(hits[f]) / count[f]);
    std::printf("\n");
    // Unbounded rays built to pass exactly through a box edge or corner hit.
    for (const char* name : {"edge-exact", "corner-exact"}) {
        const std::size_t f = family_index(name);
        for (std::size_t i = 0; i < qs.size(); ++i)
            if (fam[i] == f && std::isinf(qs[i].ray.tmax)) {
                ASSERT_TRUE(exact_hit(qs[i].ray, qs[i].box)) << name << " " << i;
            }
    }
    // Every zero-length query has tmax = 0; every family has hits and misses.
    for (std::size_t i = 0; i < qs.size(); ++i)
        if (fam[i] == family_index("zero-length")) {
            ASSERT_EQ(qs[i].ray.tmax, 0.0f);
        }
    for (std::size_t f = 0; f < n; ++f) {
        EXPECT_GT(hits[f], 0u) << extreme_family_name(f);
        EXPECT_LT(hits[f], count[f]) << extreme_family_name(f);
    }
    // Denormal, tiny and huge families really have such directions.
    for (std::size_t i = 0; i < qs.size(); ++i) {
        const float m = std::max({std::fabs(qs[i].ray.d.x), std::fabs(qs[i].ray.d.y), std::fabs(qs[i].ray.d.z)});
        if (fam[i] == family_index("tiny-dir")) {
            ASSERT_LT(m, 1e-28f);
        }
        if (fam[i] == family_index("huge-dir")) {
            ASSERT_GT(m, 1e28f);
        }
        if (fam[i] == family_index("denormal-dir")) {
            const float mn = std::min({std::fabs(qs[i].ray.d.x) ? std::fabs(qs[i].ray.d.x) : 1.0f,
                                       std::fabs(qs[i].ray.d.y) ? std::fabs(qs[i].ray.d.y) : 1.0f,
                                       std::fabs(qs[i].ray.d.z) ? std::fabs(qs[i].ray.d.z) : 1.0f});
            ASSERT_LT(mn, std::numeric_limits<float>::min()) << i;
        }
    }
}

// ---------------------------------------------------------------------------
// Datapath operands: the full port ranges, and the operand file
// ---------------------------------------------------------------------------

bool same(const FixedQuery& a, const FixedQuery& b) {
    return a.ray.cls == b.ray.cls && a.ray.org == b.ray.org && a.ray.dir == b.ray.dir && a.ray.end == b.ray.end &&
           a.ray.has_end == b.ray.has_end && a.box.lo == b.box.lo && a.box.hi == b.box.hi;
}

TEST(QueryGen, PortRangeOperandsCoverThePorts) {
    for (const auto& [c, d] : {std::pair{6, 6}, std::pair{16, 16}, std::pair{7, 22}, std::pair{24, 24}}) {
        FixedFormat f;
        f.coord_bits = c;
        f.dir_bits = d;
        const auto qs = port_range_queries(3, 6000, f), again = port_range_queries(3, 6000, f);
        ASSERT_EQ(qs.size(), 6000u);
        const std::int64_t dmax = (std::int64_t{1} << d) - 1;
        std::set<int> classes;
        std::size_t inverted = 0, past_one = 0, ends = 0, coord_min = 0, coord_max = 0, dir_max = 0, hits = 0;
        for (std::size_t i = 0; i < qs.size(); ++i) {
            const FixedQuery& q = qs[i];
            ASSERT_TRUE(same(q, again[i])) << i;
            ASSERT_NO_THROW(pack_query(q.ray, q.box, f)) << i;  // every operand fits its port
            classes.insert(q.ray.cls);
            ends += q.ray.has_end;
            hits += fixed_hit(q.ray, q.box, f);
            for (int a = 0; a < 3; ++a) {
                inverted += q.box.lo[a] > q.box.hi[a];
                past_one += q.ray.dir[a] > f.dir_one();
                dir_max += q.ray.dir[a] == dmax;
                coord_min += q.box.lo[a] == f.coord_min() || q.ray.org[a] == f.coord_min();
                coord_max += q.box.hi[a] == f.coord_max() || q.ray.org[a] == f.coord_max();
            }
        }
        EXPECT_EQ(classes.size(), 8u);
        EXPECT_GT(inverted, 100u);
        EXPECT_GT(past_one, 1000u);
        EXPECT_GT(dir_max, 100u);
        EXPECT_GT(coord_min, 100u);
        EXPECT_GT(coord_max, 100u);
        EXPECT_GT(ends, 2000u);
        EXPECT_LT(ends, 4000u);
        EXPECT_GT(hits, 100u) << c << "/" << d;
    }
    FixedFormat bad;
    bad.coord_bits = 5;
    EXPECT_THROW(port_range_queries(1, 1, bad), InputError);
}

TEST(OperandFile, RoundTripAndHeader) {
    FixedFormat f;
    f.coord_bits = 9;
    f.dir_bits = 15;
    f.mode = FixedMode::Nearest;
    const auto qs = boundary_queries(11, 500, f);
    const std::string path = ::testing::TempDir() + "operands_roundtrip.txt";
    {
        std::ofstream out(path);
        out << "# a comment\n\n";
        app::write_operand_header(out, f);
        for (const FixedQuery& q : qs) app::write_operands(out, q);
    }
    EXPECT_TRUE(app::is_operand_file(path));
    std::vector<std::size_t> lines;
    const auto back = app::read_operand_file(path, f, lines);
    ASSERT_EQ(back.size(), qs.size());
    for (std::size_t i = 0; i < qs.size(); ++i) {
        ASSERT_TRUE(same(back[i], qs[i])) << i;
        ASSERT_EQ(lines[i], i + 4);
    }
    FixedFormat other = f;
    other.mode = FixedMode::Conservative;
    try {
        app::read_operand_file(path, other, lines);
        ADD_FAILURE() << "no error for a file of another mode";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(path + ":3: operands for 9 15 nearest, not 9 15 conservative"),
                  std::string::npos)
            << e.what();
    }
    std::ofstream(path) << kGood;
    EXPECT_FALSE(app::is_operand_file(path));
    std::remove(path.c_str());
}

}  // namespace
}  // namespace pluecker
