// SPDX-License-Identifier: MIT
// `pluecker query` end to end: the built CLI (PLUECKER_CLI) on the files in
// tests/data/query and on generated files, compared with the library.
#include "pluecker/boxtest.hpp"
#include "pluecker/f32unit.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/query.hpp"
#include "pluecker/querygen.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace pluecker {
namespace {

namespace fs = std::filesystem;

const fs::path kData = fs::path(__FILE__).parent_path() / "data" / "query";

struct CliRun {
    int status = -1;
    std::string out, err;
};

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string quote(const std::string& s) { return "'" + s + "'"; }

// Runs `pluecker query ARGS` (ARGS already shell-quoted where needed),
// optionally with a file on standard input.
CliRun query_cli(const std::string& args, const std::string& stdin_file = "") {
    static int counter = 0;
    const fs::path dir = fs::path(testing::TempDir());
    const std::string tag = "pluecker_cli_query_" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
    const fs::path out = dir / (tag + ".out"), err = dir / (tag + ".err");
    std::string cmd = quote(PLUECKER_CLI) + " query " + args + " >" + quote(out) + " 2>" + quote(err);
    if (!stdin_file.empty()) cmd += " <" + quote(stdin_file);
    const int raw = std::system(cmd.c_str());
    CliRun r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    fs::remove(out);
    fs::remove(err);
    return r;
}

std::string data(const std::string& name) { return quote((kData / name).string()); }

TEST(CliQuery, GoodFileEveryFloatTest) {
    const std::string expected = slurp(kData / "good.expected");
    ASSERT_FALSE(expected.empty());
    for (const char* t : {"exact", "smits", "pluecker"}) {
        const CliRun r = query_cli(std::string("--test ") + t + " " + data("good.txt"));
        EXPECT_EQ(r.status, 0) << t << ": " << r.err;
        EXPECT_EQ(r.out, expected) << t;
        EXPECT_EQ(r.err, "") << t;
    }
}

TEST(CliQuery, GoodFileFixedNeverMisses) {
    const std::string expected = slurp(kData / "good.expected");
    for (const std::string opts : {"", "--coord-bits 8 --dir-bits 8", "--coord-bits=24 --dir-bits=24 --mode conservative"}) {
        const CliRun r = query_cli("--test fixed " + opts + " " + data("good.txt"));
        ASSERT_EQ(r.status, 0) << opts << ": " << r.err;
        ASSERT_EQ(r.out.size(), expected.size()) << opts;
        for (std::size_t i = 0; i < expected.size(); i += 2)
            if (expected[i] == '1') {
                EXPECT_EQ(r.out[i], '1') << opts << ": false miss on query " << i / 2 + 1;
            }
    }
    const CliRun n = query_cli("--test fixed --mode nearest " + data("good.txt"));
    EXPECT_EQ(n.status, 0) << n.err;
    EXPECT_EQ(n.out.size(), expected.size());
}

TEST(CliQuery, StandardInput) {
    const CliRun r = query_cli("--test exact -", (kData / "good.txt").string());
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, slurp(kData / "good.expected"));
    const CliRun bad = query_cli("--test exact -", (kData / "bad_nan.txt").string());
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.err.find("<stdin>:2: oz is NaN"), std::string::npos) << bad.err;
}

TEST(CliQuery, BadFilesNameTheLine) {
    struct Bad {
        const char* file;
        int line;
        const char* what;
    };
    const Bad cases[] = {
        {"bad_fields.txt", 3, "found 12"},
        {"bad_token.txt", 4, "cannot parse 'abc'"},
        {"bad_nan.txt", 2, "oz is NaN"},
        {"bad_zero_dir.txt", 5, "direction is zero"},
        {"bad_tmax.txt", 3, "tmax is negative"},
        {"bad_box.txt", 2, "min > max on axis x"},
        {"bad_inf_coord.txt", 3, "oy is not a finite coordinate"},
    };
    for (const Bad& b : cases)
        for (const char* t : {"exact", "smits", "pluecker", "fixed"}) {
            const CliRun r = query_cli(std::string("--test ") + t + " " + data(b.file));
            EXPECT_EQ(r.status, 2) << b.file << " " << t;
            EXPECT_EQ(r.out, "") << b.file << " " << t;  // nothing printed before the error
            const std::string where = (kData / b.file).string() + ":" + std::to_string(b.line) + ": ";
            EXPECT_NE(r.err.find(where), std::string::npos) << b.file << " " << t << ": " << r.err;
            EXPECT_NE(r.err.find(b.what), std::string::npos) << b.file << " " << t << ": " << r.err;
        }
}

TEST(CliQuery, FixedTakesAnyFiniteOrigin) {
    // The second ray starts at x = 3, outside the fixed-point range: the
    // set-up clips it onto the range, as the renderer does.
    const CliRun ok = query_cli("--test exact " + data("fixed_range.txt"));
    EXPECT_EQ(ok.status, 0) << ok.err;
    EXPECT_EQ(ok.out, "1\n1\n");
    const CliRun r = query_cli("--test fixed " + data("fixed_range.txt"));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "1\n1\n");
}

TEST(CliQuery, FixedBoxRangeErrorNamesTheLineAndTheLimit) {
    // Valid for the float tests; the box of line 3 reaches x = 2, past the
    // last coordinate of COORD_BITS = 6 (2 - 2^-4 = 1.9375).
    const CliRun ok = query_cli("--test exact " + data("fixed_box_range.txt"));
    EXPECT_EQ(ok.status, 0) << ok.err;
    const CliRun r = query_cli("--test fixed --coord-bits 6 " + data("fixed_box_range.txt"));
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find((kData / "fixed_box_range.txt").string() + ":3: box x extent [0, 2]"), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("outside the fixed-point range [-2, 1.9375] of COORD_BITS = 6"), std::string::npos) << r.err;
}

TEST(CliQuery, OptionErrors) {
    const std::string good = data("good.txt");
    struct Bad {
        std::string args, what;
    };
    const Bad cases[] = {
        {good, "--test"},
        {"--test smits --coord-bits 12 " + good, "--coord-bits"},
        {"--test exact --dir-bits 12 " + good, "--dir-bits"},
        {"--test pluecker --mode nearest " + good, "--mode"},
        {"--test bogus " + good, "bogus"},
        {"--test fixed --coord-bits 30 " + good, "--coord-bits"},
        {"--test fixed --dir-bits 5 " + good, "--dir-bits"},
        {"--test fixed --coord-bits x " + good, "--coord-bits"},
        {"--test fixed --mode round " + good, "round"},
        {"--test exact", "FILE"},
        {"--test exact " + good + " " + good, "FILE"},
        {"--test exact --frobnicate " + good, "--frobnicate"},
        {"--test exact " + data("no_such_file.txt"), "no_such_file.txt"},
    };
    for (const Bad& b : cases) {
        const CliRun r = query_cli(b.args);
        EXPECT_EQ(r.status, 2) << b.args;
        EXPECT_NE(r.err.find(b.what), std::string::npos) << b.args << ": " << r.err;
        EXPECT_EQ(r.out, "") << b.args;
    }
}

TEST(CliQuery, Help) {
    const CliRun r = query_cli("--help");
    EXPECT_EQ(r.status, 0);
    EXPECT_NE(r.out.find("usage: pluecker query"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("--coord-bits"), std::string::npos);
}

// A generated file through the CLI gives the library's answers.
TEST(CliQuery, GeneratedFileMatchesLibrary) {
    std::vector<Query> qs = random_queries(0xc11e0001, 20000);
    const auto ex = extreme_queries(0xc11e0002, 16 * 500);
    qs.insert(qs.end(), ex.begin(), ex.end());
    const fs::path file = fs::path(testing::TempDir()) / ("pluecker_cli_gen_" + std::to_string(::getpid()) + ".txt");
    {
        std::ofstream out(file);
        out << "# generated\n";
        for (const Query& q : qs) write_query(out, q);
    }
    FixedFormat fmt;
    fmt.coord_bits = 12;
    fmt.dir_bits = 10;
    const struct {
        const char* args;
        bool (*answer)(const Query&, const FixedFormat&);
    } tests[] = {
        {"--test exact", [](const Query& q, const FixedFormat&) { return exact_hit(q.ray, q.box); }},
        {"--test smits", [](const Query& q, const FixedFormat&) { return smits_hit(smits_setup(q.ray), q.box); }},
        {"--test pluecker",
         [](const Query& q, const FixedFormat&) { return pluecker_hit(pluecker_setup(q.ray), q.box); }},
        {"--test fixed --coord-bits 12 --dir-bits 10",
         [](const Query& q, const FixedFormat& f) { return fixed_hit(q.ray, q.box, f); }},
        {"--test f32-pluecker", [](const Query& q, const FixedFormat&) { return f32_pluecker_hit(q.ray, q.box, false); }},
        {"--test f32-pluecker-cons",
         [](const Query& q, const FixedFormat&) { return f32_pluecker_hit(q.ray, q.box, true); }},
        {"--test f32-smits", [](const Query& q, const FixedFormat&) { return f32_smits_hit(q.ray, q.box); }},
    };
    for (const auto& t : tests) {
        std::string want;
        for (const Query& q : qs) want += t.answer(q, fmt) ? "1\n" : "0\n";
        const CliRun r = query_cli(std::string(t.args) + " " + quote(file.string()));
        EXPECT_EQ(r.status, 0) << t.args << ": " << r.err;
        EXPECT_TRUE(r.out == want) << t.args << ": output differs from the library";
    }
    fs::remove(file);
}

}  // namespace
}  // namespace pluecker
