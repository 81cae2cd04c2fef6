// SPDX-License-Identifier: MIT
// `pluecker accuracy` end to end: the built CLI (PLUECKER_CLI) prints every
// test's tally against exact, and its figures are the library's.
#include "pluecker/boxtest.hpp"
#include "pluecker/f32unit.hpp"
#include "pluecker/querygen.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>

namespace pluecker {
namespace {

struct Line {
    std::size_t count = 0, real = 0, false_misses = 0, false_hits = 0;
};

std::string run(const std::string& args, int& status) {
    const std::string cmd = std::string("'") + PLUECKER_CLI + "' accuracy " + args + " 2>&1";
    std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
    std::string out;
    std::array<char, 4096> buf{};
    while (std::fgets(buf.data(), static_cast<int>(buf.size()), p.get())) out += buf.data();
    const int raw = pclose(p.release());
    status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    return out;
}

// The tally of `test` on the `set` line ("extreme  f32-smits  ...").
Line find(const std::string& out, const std::string& set, const std::string& test) {
    std::istringstream in(out);
    std::string s, t;
    Line l;
    while (in >> s) {
        if (s != set) {
            std::getline(in, t);
            continue;
        }
        in >> t;
        if (t == "fixed") {
            std::string w;
            in >> w;
            t += " " + w;
        }
        Line x;
        in >> x.count >> x.real >> x.false_misses >> x.false_hits;
        if (t == test) return x;
    }
    ADD_FAILURE() << "no line for " << set << " " << test << " in:\n" << out;
    return l;
}

TEST(CliAccuracy, TalliesAreTheLibrarys) {
    int status = -1;
    const std::string out = run("--n 900 --seed 3 --random 300 --widths 12,16", status);
    ASSERT_EQ(status, 0) << out;
    const std::vector<Query> ex = extreme_queries(3, 900);
    Line want;
    for (const Query& q : ex) {
        const bool e = exact_hit(q.ray, q.box), h = f32_smits_hit(q.ray, q.box);
        ++want.count;
        want.real += e;
        want.false_misses += e && !h;
        want.false_hits += !e && h;
    }
    const Line got = find(out, "extreme", "f32-smits");
    EXPECT_EQ(got.count, want.count);
    EXPECT_EQ(got.real, want.real);
    EXPECT_EQ(got.false_misses, want.false_misses);
    EXPECT_EQ(got.false_hits, want.false_hits);
    // The tests that must never miss.
    for (const char* t : {"f32-pluecker-cons", "fixed 12x12", "fixed 16x16"})
        for (const char* set : {"extreme", "random"}) EXPECT_EQ(find(out, set, t).false_misses, 0u) << set << " " << t;
    EXPECT_EQ(find(out, "random", "pluecker").count, 300u);
}

TEST(CliAccuracy, BadOptions) {
    int status = -1;
    for (const char* args : {"--n -1", "--widths 5", "--frob 1", "extra"}) {
        const std::string out = run(args, status);
        EXPECT_EQ(status, 2) << args << ": " << out;
        EXPECT_NE(out.find("error"), std::string::npos) << args << ": " << out;
    }
}

}  // namespace
}  // namespace pluecker
