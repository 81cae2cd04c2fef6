// SPDX-License-Identifier: MIT
// The renderer: determinism over pools and threads, the batched fixed-point
// path, the trace output, the statistics and the CLI.
#include "pluecker/bvh.hpp"
#include "pluecker/image.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/query.hpp"
#include "pluecker/render.hpp"
#include "pluecker/traverse.hpp"
#include "pluecker/batched.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <span>
#include <sstream>
#include <string>

namespace pluecker {
namespace {

struct Fixture {
    explicit Fixture(const std::string& spec, const FixedFormat& f = FixedFormat{}) : mesh(make_scene(spec)) {
        bvh = build_bvh(mesh, BuildOptions{});
        accel = std::make_unique<Accel>(mesh, bvh);
        accel->quantize(f);
        scene = std::make_unique<RenderScene>(mesh, *accel);
    }
    Mesh mesh;
    Bvh bvh;
    std::unique_ptr<Accel> accel;
    std::unique_ptr<RenderScene> scene;
};

RenderOptions small(BoxTestKind t, ChildOrder o, int side) {
    RenderOptions opts;
    opts.width = side;
    opts.height = side;
    opts.test = t;
    opts.order = o;
    return opts;
}

std::size_t non_background(const Image& img, const RenderOptions& o) {
    Image bg(1, 1);
    bg.set(0, 0, o.background);
    std::size_t n = 0;
    for (std::size_t i = 0; i < img.rgb.size(); i += 3)
        n += img.rgb[i] != bg.rgb[0] || img.rgb[i + 1] != bg.rgb[1] || img.rgb[i + 2] != bg.rgb[2];
    return n;
}

TEST(Render, BatchedImageDoesNotDependOnPool) {
    const Fixture fx("spheres");  // diffuse, mirror and glass: every ray kind
    RenderOptions o = small(BoxTestKind::Fixed, ChildOrder::Dsa, 40);
    RenderStats ref_st;
    o.pool = 1;
    const Image ref = render(*fx.scene, o, ref_st);
    EXPECT_GT(ref_st.rays[static_cast<int>(RayKind::Reflection)], 0u);
    EXPECT_GT(ref_st.rays[static_cast<int>(RayKind::Refraction)], 0u);
    EXPECT_GT(ref_st.rays[static_cast<int>(RayKind::Shadow)], 0u);
    for (const std::size_t pool : {std::size_t{5}, std::size_t{256}}) {
        o.pool = pool;
        SoftwareBoxEngine eng(o.fixed);
        RenderStats st;
        const Image img = render_batched(*fx.scene, o, eng, st);
        EXPECT_TRUE(img == ref) << "pool " << pool;
        EXPECT_EQ(st.rays, ref_st.rays);
        EXPECT_EQ(st.traversal, ref_st.traversal);
        EXPECT_EQ(st.batch.queries, st.traversal.box_tests);
        EXPECT_LT(st.batch.batches, ref_st.batch.batches);
    }
}

TEST(Render, FixedPathRendersTheSceneAndMatchesTheDirectPath) {
    const Fixture fx("teapot");
    const RenderOptions o = small(BoxTestKind::Fixed, ChildOrder::Fixed, 48);
    RenderStats st;
    const Image batched = render(*fx.scene, o, st);
    EXPECT_GT(non_background(batched, o), 48u * 48u / 5);
    EXPECT_GT(st.traversal.box_tests, 0u);
    RenderStats direct_st;
    const Image direct = render_direct(*fx.scene, o, direct_st);
    EXPECT_TRUE(batched == direct);
    EXPECT_EQ(st.traversal, direct_st.traversal);
    // Conservative mode never misses a box, so the closest hits and hence
    // the image equal the float renders.
    RenderStats fst;
    const Image flt = render(*fx.scene, small(BoxTestKind::Pluecker, ChildOrder::Dsa, 48), fst);
    EXPECT_TRUE(batched == flt);
}

TEST(Render, NearestModeAndNarrowFormatRender) {
    FixedFormat f;
    f.coord_bits = 8;
    f.dir_bits = 7;
    f.mode = FixedMode::Nearest;
    const Fixture fx("teapot", f);
    RenderOptions o = small(BoxTestKind::Fixed, ChildOrder::Dsa, 32);
    o.fixed = f;
    RenderStats st;
    const Image img = render(*fx.scene, o, st);
    EXPECT_GT(non_background(img, o), 32u * 32u / 5);
}

TEST(Render, ThreadsDoNotChangeTheImage) {
    const Fixture fx("spheres");
    RenderOptions o = small(BoxTestKind::Smits, ChildOrder::Dist, 40);
    RenderStats st1, st3;
    const Image a = render(*fx.scene, o, st1);
    o.threads = 3;
    const Image b = render(*fx.scene, o, st3);
    EXPECT_TRUE(a == b);
    EXPECT_EQ(st1.traversal, st3.traversal);
    EXPECT_EQ(st1.rays, st3.rays);
}

TEST(Render, EveryConfigurationGivesTheSameImage) {
    const Fixture fx("spheres");
    RenderStats st0;
    const Image ref = render(*fx.scene, small(BoxTestKind::Smits, ChildOrder::Fixed, 32), st0);
    for (const auto& [t, o] : std::vector<std::pair<BoxTestKind, ChildOrder>>{{BoxTestKind::Smits, ChildOrder::Dist},
                                                                             {BoxTestKind::Smits, ChildOrder::Dsa},
                                                                             {BoxTestKind::Pluecker, ChildOrder::Fixed},
                                                                             {BoxTestKind::Pluecker, ChildOrder::Dsa},
                                                                             {BoxTestKind::Fixed, ChildOrder::Dsa}}) {
        RenderStats st;
        EXPECT_TRUE(render(*fx.scene, small(t, o, 32), st) == ref) << config_name(t, o);
    }
}

// The binary32 units' models through the batched path: the same image and
// counts as the direct traversal of the same test, at any pool; the
// conservative unit never misses a box, so its image is the float one.
TEST(Render, F32UnitsBatchedMatchTheDirectPath) {
    const Fixture fx("spheres");
    RenderStats fst;
    const Image flt = render(*fx.scene, small(BoxTestKind::Pluecker, ChildOrder::Dsa, 32), fst);
    for (const BoxTestKind t : {BoxTestKind::F32Pluecker, BoxTestKind::F32PlueckerCons, BoxTestKind::F32Smits}) {
        RenderOptions o = small(t, ChildOrder::Dsa, 32);
        o.pool = 9;
        RenderStats st, direct_st;
        const Image batched = render(*fx.scene, o, st);
        const Image direct = render_direct(*fx.scene, o, direct_st);
        EXPECT_TRUE(batched == direct) << test_name(t);
        EXPECT_EQ(st.traversal, direct_st.traversal) << test_name(t);
        EXPECT_EQ(st.batch.queries, st.traversal.box_tests) << test_name(t);
        EXPECT_GT(st.batch.batches, 0u) << test_name(t);
        if (t == BoxTestKind::F32PlueckerCons) {
            EXPECT_TRUE(batched == flt);
        }
    }
}

// A batched engine answers what it is asked: an engine that says "miss" to
// every query renders the background only.
TEST(Render, F32BatchedPathTakesTheEnginesAnswers) {
    struct Blind final : F32BoxEngine<BoxTestKind::F32Smits> {
        std::uint64_t asked = 0;
        void test(std::span<const F32BoxQuery<BoxTestKind::F32Smits>> batch, std::span<std::uint8_t> hits) override {
            asked += batch.size();
            for (auto& h : hits) h = 0;
        }
    };
    const Fixture fx("teapot");
    const RenderOptions o = small(BoxTestKind::F32Smits, ChildOrder::Fixed, 16);
    Blind blind;
    RenderStats st;
    const Image img = render_batched(*fx.scene, o, blind, st);
    EXPECT_EQ(non_background(img, o), 0u);
    EXPECT_EQ(blind.asked, 16u * 16u);  // the root box of every camera ray
    EXPECT_THROW(render_batched(*fx.scene, small(BoxTestKind::F32Pluecker, ChildOrder::Fixed, 16), blind, st),
                 InputError);
}

TEST(Render, BadOptionsAreInputErrors) {
    const Fixture fx("teapot");
    RenderStats st;
    EXPECT_THROW(render(*fx.scene, small(BoxTestKind::Pluecker, ChildOrder::Dist, 8), st), InputError);
    RenderOptions o = small(BoxTestKind::Fixed, ChildOrder::Fixed, 8);
    o.pool = 0;
    EXPECT_THROW(render(*fx.scene, o, st), InputError);
    o = small(BoxTestKind::Smits, ChildOrder::Fixed, 0);
    EXPECT_THROW(render(*fx.scene, o, st), InputError);
}

TEST(Trace, QueriesParseAndCountEqualsBoxTests) {
    for (const BoxTestKind t : {BoxTestKind::Pluecker, BoxTestKind::Fixed}) {
        const Fixture fx("spheres");
        const RenderOptions o = small(t, ChildOrder::Dsa, 16);
        std::stringstream ss;
        RenderStats tst;
        const std::uint64_t n = trace_render(*fx.scene, o, ss, 0, tst);
        const std::vector<Query> qs = read_queries(ss, "trace");
        RenderStats rst;
        render_direct(*fx.scene, o, rst);
        EXPECT_EQ(qs.size(), n);
        EXPECT_EQ(n, rst.traversal.box_tests) << test_name(t);
        // Re-answering the written queries gives the traversal's answers.
        const auto tracer = make_tracer(*fx.accel, t, o.order);
        std::size_t hits = 0;
        for (const Query& q : qs) hits += t == BoxTestKind::Fixed ? fixed_hit(q.ray, q.box, o.fixed)
                                                                  : pluecker_hit(pluecker_setup(q.ray), q.box);
        EXPECT_GT(hits, 0u);
        EXPECT_LT(hits, qs.size());
        if (t == BoxTestKind::Fixed) {
            for (const Query& q : qs) ASSERT_TRUE(fixed_setup_ray(q.ray, o.fixed).has_value());
        }
        // The limit.
        std::stringstream lim;
        RenderStats lst;
        EXPECT_EQ(trace_render(*fx.scene, o, lim, 100, lst), 100u);
        EXPECT_EQ(read_queries(lim, "limited").size(), 100u);
    }
}

TEST(Stats, JsonHasTheFields) {
    const Fixture fx("teapot");
    RenderOptions o = small(BoxTestKind::Fixed, ChildOrder::Dsa, 16);
    RenderStats st;
    render(*fx.scene, o, st);
    const nlohmann::json j = stats_json(*fx.scene, fx.bvh, BuildMethod::Sah, o, st);
    for (const char* k : {"scene", "triangles", "test", "order", "build", "width", "height", "rays", "node_visits",
                          "box_tests", "triangle_tests", "build_ms", "render_ms", "fixed"})
        EXPECT_TRUE(j.contains(k)) << k;
    EXPECT_EQ(j["scene"], "teapot");
    EXPECT_EQ(j["rays"]["camera"], 256u);
    EXPECT_EQ(j["fixed"]["coord_bits"], 16);
    EXPECT_EQ(j["fixed"]["mode"], "conservative");
}

// ---------------------------------------------------------------------------
// CLI

#ifdef PLUECKER_CLI
int run(const std::string& args, std::string* err = nullptr) {
    const auto dir = std::filesystem::temp_directory_path() / ("pluecker_render_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string errfile = (dir / "stderr.txt").string();
    const int rc = std::system((std::string(PLUECKER_CLI) + " " + args + " 2>" + errfile).c_str());
    if (err) {
        std::ifstream f(errfile);
        std::stringstream ss;
        ss << f.rdbuf();
        *err = ss.str();
    }
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(Cli, RenderWritesPngAndStats) {
    const auto dir = std::filesystem::temp_directory_path() / ("pluecker_render_cli_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string png = (dir / "img.png").string(), js = (dir / "stats.json").string();
    ASSERT_EQ(run("render --scene teapot --test fixed --order dsa --size 24 --pool 7 --coord-bits 14 --dir-bits 12"
                  " --out " + png + " --stats " + js + " --quiet"),
              0);
    EXPECT_TRUE(std::filesystem::file_size(png) > 100);
    std::ifstream f(js);
    const nlohmann::json j = nlohmann::json::parse(f);
    EXPECT_EQ(j["fixed"]["coord_bits"], 14);
    EXPECT_EQ(j["batch"]["pool"], 7);
    EXPECT_EQ(j["width"], 24);
    std::filesystem::remove_all(dir);
}

TEST(Cli, RenderThroughAFloatUnitModel) {
    const auto dir = std::filesystem::temp_directory_path() / ("pluecker_render_f32_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string png = (dir / "img.png").string(), js = (dir / "stats.json").string();
    ASSERT_EQ(run("render --scene teapot --test f32-pluecker-cons --size 16 --pool 5 --out " + png + " --stats " + js +
                  " --quiet"),
              0);
    std::ifstream f(js);
    const nlohmann::json j = nlohmann::json::parse(f);
    EXPECT_EQ(j["f32"]["unit"], "f32-pluecker-cons");
    EXPECT_EQ(j["batch"]["pool"], 5);
    std::string err;
    EXPECT_EQ(run("render --test f32-smits --mode nearest --size 8 --out /dev/null", &err), 2);
    EXPECT_NE(err.find("--mode"), std::string::npos) << err;
    EXPECT_EQ(run("render --test f32-smits --order dist --size 8 --out /dev/null", &err), 2);
    EXPECT_NE(err.find("--order"), std::string::npos) << err;
    EXPECT_EQ(run("render --test pluecker --pool 4 --size 8 --out /dev/null", &err), 2);
    EXPECT_NE(err.find("--pool"), std::string::npos) << err;
    std::filesystem::remove_all(dir);
}

TEST(Cli, IllegalCombinationsNameTheFlags) {
    std::string err;
    EXPECT_EQ(run("render --test pluecker --order dist --size 8 --out /dev/null", &err), 2);
    EXPECT_NE(err.find("--order"), std::string::npos) << err;
    EXPECT_NE(err.find("--test"), std::string::npos) << err;
    EXPECT_EQ(run("render --test smits --coord-bits 12 --size 8 --out /dev/null", &err), 2);
    EXPECT_NE(err.find("--coord-bits"), std::string::npos) << err;
    EXPECT_EQ(run("render --test fixed --coord-bits 40 --size 8 --out /dev/null", &err), 2);
    EXPECT_NE(err.find("--coord-bits"), std::string::npos) << err;
    EXPECT_EQ(run("trace --size 8", &err), 2);
    EXPECT_NE(err.find("--out"), std::string::npos) << err;
}

TEST(Cli, TraceWritesQueries) {
    const auto dir = std::filesystem::temp_directory_path() / ("pluecker_trace_cli_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string out = (dir / "q.txt").string();
    ASSERT_EQ(run("trace --scene sphere:500 --test fixed --order fixed --build median --size 8 --limit 500 --out " +
                  out + " --quiet"),
              0);
    EXPECT_EQ(read_queries_file(out).size(), 500u);
    std::filesystem::remove_all(dir);
}
#endif

}  // namespace
}  // namespace pluecker
