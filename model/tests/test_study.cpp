// SPDX-License-Identifier: MIT
// The width study and the plan (pluecker/study.hpp) on a small scene.
#include "pluecker/app/names.hpp"  // parse_* (the applications' name parsing)
#include "pluecker/study.hpp"

#include "pluecker/bvh.hpp"
#include "pluecker/mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace pluecker {
namespace {

struct Small {
    Small() : mesh(make_scene("sphere:2000")), bvh(build_bvh(mesh, BuildOptions{})) {
        opts.width = opts.height = 32;
        opts.order = ChildOrder::Dsa;
    }
    Mesh mesh;
    Bvh bvh;
    RenderOptions opts;
};

const Small& small() {
    static const Small s;
    return s;
}

const StudyResult& study() {
    static const StudyResult r = [] {
        StudyOptions so;
        so.render = small().opts;
        so.widths = parse_widths("6:24:2");
        so.threads = 2;
        return run_study(small().mesh, small().bvh, so);
    }();
    return r;
}

TEST(Study, ParseWidths) {
    EXPECT_EQ(parse_widths("6:10:2"), (std::vector<WidthPair>{{6, 6}, {8, 8}, {10, 10}}));
    EXPECT_EQ(parse_widths("7:9"), (std::vector<WidthPair>{{7, 7}, {8, 8}, {9, 9}}));
    EXPECT_EQ(parse_widths("12,16x10"), (std::vector<WidthPair>{{12, 12}, {16, 10}}));
    for (const char* bad : {"", "5", "25", "6:24:0", "10:8", "6:", "12x", "x12", "1a", "6:24:2:1", "12,,14"}) {
        try {
            parse_widths(bad, "--widths");
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("--widths"), std::string::npos) << e.what();
        }
    }
}

TEST(Study, ConservativeNeverMissesAtAnyWidth) {
    const StudyResult& r = study();
    ASSERT_EQ(r.queries.size(), 10u);
    ASSERT_GT(r.reference.checked.queries, 10000u);
    for (std::size_t k = 0; k < r.queries.size(); ++k) {
        SCOPED_TRACE(r.options.widths[k].coord_bits);
        EXPECT_EQ(r.queries[k].conservative.queries, r.reference.checked.queries);
        EXPECT_EQ(r.queries[k].conservative.false_misses, 0u);
        EXPECT_EQ(r.work[k].checked.false_misses, 0u);
        // No false miss: every ray finds the reference's hit.
        EXPECT_EQ(r.work[k].wrong_pixels, 0u);
        EXPECT_EQ(r.work[k].stats.rays, r.reference.stats.rays);
        EXPECT_GE(r.work[k].stats.traversal.box_tests, r.reference.stats.traversal.box_tests);
    }
    // The narrowest width has false hits; the reference answers exactly.
    EXPECT_GT(r.queries.front().conservative.false_hits, 0u);
    EXPECT_EQ(r.reference.checked.false_hits + r.reference.checked.false_misses, 0u);
    // The direct exact render (unclipped rays) gives the same image.
    ASSERT_TRUE(r.direct_exact.has_value());
    EXPECT_EQ(r.direct_exact->wrong_pixels, 0u);
}

TEST(Study, ExtraWorkFallsToAboutZero) {
    const StudyResult& r = study();
    const auto ref = r.reference.stats.traversal.box_tests;
    double prev = std::numeric_limits<double>::infinity();
    for (const WorkFigures& w : r.work) {
        const double e = extra_percent(w.stats.traversal.box_tests, ref);
        EXPECT_LE(e, prev);
        prev = e;
    }
    EXPECT_GT(extra_percent(r.work.front().stats.traversal.box_tests, ref), 20.0);  // 6 bits: measured ~89%
    EXPECT_LT(prev, 0.01);                                                          // 24 bits: measured 0
    // The false-hit rate falls with the width too.
    EXPECT_GT(r.queries.front().conservative.false_hit_rate(), r.queries.back().conservative.false_hit_rate());
}

TEST(Study, NearestMissesAtNarrowWidths) {
    const StudyResult& r = study();
    ASSERT_EQ(r.nearest.size(), 10u);
    // 6 bits without margin loses hits and pixels; the error vanishes when wide.
    EXPECT_GT(r.queries.front().nearest.false_misses, 0u);
    EXPECT_GT(r.nearest.front().checked.false_misses, 0u);
    EXPECT_GT(r.nearest.front().wrong_pixels, 0u);
    EXPECT_EQ(r.nearest.back().wrong_pixels, 0u);
}

TEST(Study, FloatTestsAgreeWithExactOnTheReferenceQueries) {
    const StudyResult& r = study();
    EXPECT_EQ(r.pluecker.queries, r.reference.checked.queries);
    EXPECT_EQ(r.smits.queries, r.reference.checked.queries);
    // Reported, not assumed zero: only bounded here.
    EXPECT_LT(r.pluecker.false_misses + r.pluecker.false_hits, r.pluecker.queries / 1000 + 1);
    EXPECT_LT(r.smits.false_misses + r.smits.false_hits, r.smits.queries / 1000 + 1);
}

TEST(Study, JsonHasEveryFigure) {
    const nlohmann::json j = study_json(study(), small().mesh, small().bvh, BuildMethod::Sah);
    for (const char* k : {"scene", "reference", "direct_exact", "queries", "widths", "definitions"})
        EXPECT_TRUE(j.contains(k)) << k;
    ASSERT_EQ(j["widths"].size(), 10u);
    const auto& w = j["widths"][0];
    EXPECT_EQ(w["coord_bits"], 6);
    for (const char* k : {"query", "work", "nearest"}) EXPECT_TRUE(w.contains(k)) << k;
    EXPECT_TRUE(w["work"]["extra_percent"].contains("box_tests"));
    EXPECT_TRUE(w["query"]["conservative"].contains("false_hit_rate"));
    EXPECT_TRUE(w["nearest"].contains("wrong_pixels"));
}

// A plan's choice: the last step measured, the first within the bound p,
// its extra work over the plan's reference, and no false miss.
template <class Result>
void expect_first_within(const Result& r, double p) {
    ASSERT_TRUE(r.chosen.has_value());
    ASSERT_EQ(*r.chosen + 1, r.steps.size());
    const auto& c = r.steps[*r.chosen];
    EXPECT_LE(c.extra_box_tests_percent, p);
    EXPECT_DOUBLE_EQ(c.extra_box_tests_percent,
                     extra_percent(c.work.stats.traversal.box_tests, r.reference.stats.traversal.box_tests));
    for (std::size_t k = 0; k + 1 < r.steps.size(); ++k) EXPECT_GT(r.steps[k].extra_box_tests_percent, p);
    EXPECT_EQ(c.work.checked.false_misses, 0u);
}

TEST(Plan, PicksTheFirstWidthWithinTheBound) {
    const std::vector<WidthPair> widths = parse_widths("6:24");
    for (const double p : {0.0, 1.0, 10.0}) {
        SCOPED_TRACE(p);
        const PlanResult r = plan_widths(small().mesh, small().bvh, small().opts, widths, p);
        expect_first_within(r, p);
    }
}

TEST(Plan, NoWidthMeetsAnImpossibleBound) {
    const PlanResult r = plan_widths(small().mesh, small().bvh, small().opts, parse_widths("6,7"), 0.0);
    EXPECT_FALSE(r.chosen.has_value());
    EXPECT_EQ(r.steps.size(), 2u);
}

TEST(Plan, RejectsBadBounds) {
    for (const double p : {-1.0, -1e-9, std::nan(""), std::numeric_limits<double>::infinity()})
        EXPECT_THROW(check_max_extra_work(p), InputError) << p;
    EXPECT_NO_THROW(check_max_extra_work(0.0));
    EXPECT_THROW(plan_widths(small().mesh, small().bvh, small().opts, parse_widths("12"), -0.5), InputError);
}

TEST(Plan, LocalPicksTheFirstBoxWidthWithinTheBound) {
    std::vector<LocalSpec> specs;
    for (const int k : {4, 6, 8, 10, 12}) {
        LocalSpec sp;
        sp.format.box_bits = k;
        sp.format.dir_bits = k + 3;
        specs.push_back(sp);
    }
    for (const double p : {1.0, 10.0}) {
        SCOPED_TRACE(p);
        const LocalPlanResult r = plan_local(small().mesh, small().bvh, small().opts, specs, p);
        expect_first_within(r, p);
    }
    EXPECT_THROW(plan_local(small().mesh, small().bvh, small().opts, {}, 1.0), InputError);
    specs[1].format.grid_bits = 24;
    EXPECT_THROW(plan_local(small().mesh, small().bvh, small().opts, specs, 1.0), InputError);
}

#ifdef PLUECKER_CLI
int run_cli(const std::string& args, std::string* out = nullptr) {
    const auto dir = std::filesystem::temp_directory_path();
    const std::string log = (dir / ("pluecker_study_cli_" + std::to_string(::getpid()) + ".txt")).string();
    const int rc = std::system((std::string(PLUECKER_CLI) + " " + args + " > " + log + " 2>&1").c_str());
    if (out) {
        std::ifstream f(log);
        std::stringstream ss;
        ss << f.rdbuf();
        *out = ss.str();
    }
    std::filesystem::remove(log);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(PlanCli, WritesThePlanFileAndRejectsBadInput) {
    const auto dir = std::filesystem::temp_directory_path() / ("pluecker_plan_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string mk = (dir / "plan.mk").string();
    std::string out;
    ASSERT_EQ(run_cli("plan --scene sphere:2000 --size 24 --max-extra-work 5 --quiet --synth-dir " +
                          (dir / "none").string() + " --out " + mk,
                      &out),
              0)
        << out;
    EXPECT_NE(out.find("make synth COORD_BITS="), std::string::npos) << out;
    EXPECT_NE(out.find("not measured yet"), std::string::npos) << out;
    std::ifstream f(mk);
    std::stringstream ss;
    ss << f.rdbuf();
    EXPECT_NE(ss.str().find("COORD_BITS := "), std::string::npos);
    EXPECT_NE(ss.str().find("DIR_BITS := "), std::string::npos);
    EXPECT_EQ(run_cli("plan --scene sphere:2000 --size 24 --max-extra-work -1", &out), 2);
    EXPECT_NE(out.find("--max-extra-work"), std::string::npos) << out;
    EXPECT_EQ(run_cli("plan --scene sphere:2000 --size 24", &out), 2);
    EXPECT_EQ(run_cli("plan --scene sphere:2000 --size 24 --max-extra-work 0 --widths 6", &out), 1);
    EXPECT_EQ(run_cli("study --scene sphere:2000 --size 24 --widths 4:8", &out), 2);
    EXPECT_NE(out.find("--widths"), std::string::npos) << out;
    EXPECT_EQ(run_cli("study --scene sphere:2000 --size 24 --order dist", &out), 2);
    EXPECT_EQ(run_cli("plan --scene sphere:2000 --size 24 --max-extra-work 5 --children 2", &out), 2);
    EXPECT_NE(out.find("--children needs --local"), std::string::npos) << out;
    EXPECT_EQ(run_cli("plan --scene sphere:2000 --size 24 --max-extra-work 5 --local 12 --children 3", &out), 2);
    EXPECT_NE(out.find("--children"), std::string::npos) << out;
    std::filesystem::remove_all(dir);
}

// Global or local: the larger effective box tests per second per chip, from
// the synthesis summaries in --synth-dir (written here with chosen rates).
TEST(PlanCli, ChoosesBetweenGlobalAndLocalByEffectiveTestsPerChip) {
    const auto dir = std::filesystem::temp_directory_path() / ("pluecker_plan_choice_" + std::to_string(::getpid()));
    const auto summary = [&](const std::string& name, double rate) {
        std::filesystem::create_directories(dir / name);
        std::ofstream(dir / name / "summary.json") << "{\"box_tests_per_s_per_chip\": {\"6\": 1, \"8\": " << rate
                                                   << "}}\n";
    };
    const std::string mk = (dir / "plan.mk").string();
    const std::string cmd = "plan --scene sphere:2000 --size 24 --max-extra-work 1000 --widths 16x16 --local 12 "
                            "--quiet --synth-dir " + dir.string() + " --out " + mk;
    const auto plan_file = [&] {
        std::ifstream f(mk);
        std::stringstream ss;
        ss << f.rdbuf();
        return ss.str();
    };
    std::string out;
    std::filesystem::create_directories(dir);
    ASSERT_EQ(run_cli(cmd, &out), 0) << out;  // nothing synthesised: the global unit, said why
    EXPECT_NE(out.find("until then the plan keeps the global unit"), std::string::npos) << out;
    EXPECT_NE(plan_file().find("COORD_BITS := 16"), std::string::npos) << plan_file();
    summary("16x16", 1e9);
    summary("local_k12_d15_g32_c2", 4e9);
    ASSERT_EQ(run_cli(cmd, &out), 0) << out;
    EXPECT_NE(out.find("chosen: local frames K=12 D=15 G=32"), std::string::npos) << out;
    const std::string local_plan = plan_file();
    for (const char* v : {"UNIT := local", "BOX_BITS := 12", "LOCAL_DIR_BITS := 15", "GRID_BITS := 32", "CHILDREN := 2"})
        EXPECT_NE(local_plan.find(v), std::string::npos) << v << "\n" << local_plan;
    summary("16x16", 8e9);
    ASSERT_EQ(run_cli(cmd, &out), 0) << out;
    EXPECT_NE(out.find("chosen: COORD_BITS=16 DIR_BITS=16"), std::string::npos) << out;
    EXPECT_EQ(plan_file().find("UNIT := local"), std::string::npos) << plan_file();
    std::filesystem::remove_all(dir);
}

TEST(StudyCli, WritesJson) {
    const auto path = std::filesystem::temp_directory_path() / ("pluecker_study_" + std::to_string(::getpid()) + ".json");
    std::string out;
    ASSERT_EQ(run_cli("study --scene sphere:2000 --size 16 --widths 8,16x12 --quiet --json " + path.string(), &out), 0)
        << out;
    std::ifstream f(path);
    const nlohmann::json j = nlohmann::json::parse(f);
    EXPECT_EQ(j["widths"].size(), 2u);
    EXPECT_EQ(j["widths"][1]["coord_bits"], 16);
    EXPECT_EQ(j["widths"][1]["dir_bits"], 12);
    EXPECT_EQ(j["width"], 16);
    std::filesystem::remove(path);
}
#endif

}  // namespace
}  // namespace pluecker
