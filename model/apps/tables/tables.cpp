// SPDX-License-Identifier: MIT
// pluecker_tables: the experiments of Mahovsky's 2005 technical report on
// this project's scenes, one configuration after another in one run:
//   smits-mul-cls, smits-dist, smits-dsa, pluecker-cls, pluecker-dsa (median
//   BVH), pluecker-dsa-sah (SAH BVH), K-D (median K-D tree), K-D-sah (SAH
//   K-D tree).
// Every configuration renders the same image (render.hpp, one thread) and
// then traces the same recorded rays of that render (camera, shadow,
// reflection, refraction) without shading. Times are CPU seconds of the
// working thread, best of --repeat. The four tables print, per scene, our
// render-time ratios beside the report's on the same scene (teapot and
// teapot.obj: Teapot, spheres: Spheres, bunny.ply: Bunny) and ours / report;
// other scenes print "no report scene", and the report's lowest and highest
// ratio over all its scenes closes each table.
// Results: stdout, OUT/tables.json, OUT/tables.md.
#include "pluecker/app/tables_common.hpp"
#include "pluecker/app/tool.hpp"

#include "pluecker/bvh.hpp"
#include "pluecker/image.hpp"
#include "pluecker/kdtree.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/render.hpp"
#include "pluecker/traverse.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace pluecker;
using namespace pluecker::tables;
using namespace pluecker::app;
using nlohmann::json;

// ---------------------------------------------------------------------------
// The report's figures [R]: J. Mahovsky, technical report, University of
// Calgary, 2005. Render times are whole-image seconds on the report's own
// machine (recursive traversal, one thread), so only ratios compare with ours.

constexpr const char* kSourceR =
    "[R] J. Mahovsky, technical report, University of Calgary, 2005: per-scene render times in seconds of its "
    "Tables 1-4 (on its own machine; only ratios compare), build times and memory as its text gives them";

// One scene of [R]: its render time in seconds for each of our
// configurations (indexed by ConfigId; the report's Tables 1-2 give the
// first five on the median round-robin BVH, Table 3 pluecker-dsa-sah,
// Table 4 K-D and K-D-sah). kNotRun: no figure (Lucy's K-D-sah ran out of
// memory).
constexpr double kNotRun = -1.0;
struct ReportScene {
    const char* name;
    std::size_t triangles;
    std::array<double, 8> render_s;  // smits-mul-cls, smits-dist, smits-dsa, pluecker-cls, pluecker-dsa,
                                     // pluecker-dsa-sah, K-D, K-D-sah
};
const std::array<ReportScene, 9> kReportScenes = {{
    {"Teapot", 2262, {20.4, 20.2, 19.3, 18.3, 17.9, 14.3, 16.6, 14.4}},
    {"Spheres", 24578, {24.9, 22.2, 21.5, 22.3, 19.3, 13.5, 17.2, 13.3}},
    {"Bunny", 69463, {37.5, 38.8, 33.0, 33.3, 30.1, 19.0, 24.7, 21.9}},
    {"Branch", 312706, {21.8, 21.4, 21.5, 19.1, 19.6, 16.1, 23.9, 17.7}},
    {"Poppy", 395460, {14.8, 13.2, 13.5, 13.3, 12.3, 10.5, 13.7, 12.3}},
    {"Powerplant-front", 12748512, {91.5, 42.7, 41.2, 78.9, 37.3, 22.7, 20.8, 14.7}},
    {"Powerplant-north", 12748512, {264.2, 263.5, 216.7, 210.9, 176.2, 73.4, 87.8, 54.6}},
    {"Powerplant-boiler", 12748512, {529.2, 157.5, 156.0, 447.3, 130.3, 62.9, 64.0, 42.6}},
    {"Lucy", 28057792, {62.3, 66.0, 60.4, 53.1, 53.6, 50.5, 58.3, kNotRun}},
}};

// Build times [R] gives, for its two largest models only (seconds).
struct ReportBuild {
    const char* name;
    std::size_t triangles;
    double bvh_median_s;  // median BVH
    double bvh_sah_s;     // SAH BVH: "over 15 minutes" (Powerplant), "nearly an hour" (Lucy)
    bool sah_at_least;    // bvh_sah_s is a lower bound
    const char* sah_as_given;
    double kd_median_s;   // K-D tree (not SAH)
};
const std::array<ReportBuild, 2> kReportBuilds = {{
    {"Powerplant", 12748512, 30.0, 15.0 * 60.0, true, "over 15 minutes", 615.0},
    {"Lucy", 28057792, 78.0, 60.0 * 60.0, false, "nearly an hour", 736.0},
}};
constexpr const char* kReportSahBuildLong =
    "SAH BVH build: over 15 minutes for Powerplant's 12.7M triangles (under 0.014 Mtri/s), nearly an hour for "
    "Lucy's 28M (about 0.008 Mtri/s) [R]";
constexpr const char* kReportKdBuildLong =
    "K-D tree build (not SAH) against the median BVH: 615 s vs 30 s (Powerplant), 736 s vs 78 s (Lucy) [R]; no "
    "build figure for the other scenes or for an SAH K-D tree";
constexpr const char* kReportKdMemory = "> 1 (Powerplant, Lucy) [R]";
constexpr const char* kReportKdMemoryLong =
    "K-D memory similar to or greater than the BVH's; on Powerplant and Lucy the K-D leaf object lists took more "
    "memory than the K-D nodes [R]; no memory figure per scene";

// Our scenes that are [R]'s (by label, and only when the triangle count is
// within 1% of the report's): the built-in teapot and teapot.obj are
// Teapot, the built-in spheres (three spheres over a floor, the same count)
// is Spheres, bunny.ply (the Stanford bunny) is Bunny.
struct SceneMap {
    const char* label;
    const char* report;
};
constexpr std::array<SceneMap, 4> kSceneMap = {{
    {"teapot", "Teapot"}, {"teapot.obj", "Teapot"}, {"spheres", "Spheres"}, {"bunny.ply", "Bunny"}}};
constexpr const char* kNoReportScene = "no report scene";

const ReportScene* report_scene(const std::string& label, std::size_t triangles) {
    for (const SceneMap& m : kSceneMap) {
        if (label != m.label) continue;
        for (const ReportScene& r : kReportScenes)
            if (std::string(r.name) == m.report &&
                std::abs(double(triangles) - double(r.triangles)) <= 0.01 * double(r.triangles))
                return &r;
    }
    return nullptr;
}

// The report's time ratio num / den on scene r; NaN when one is not known.
double report_ratio(const ReportScene& r, int num, int den) {
    const double a = r.render_s[static_cast<std::size_t>(num)], b = r.render_s[static_cast<std::size_t>(den)];
    return a > 0 && b > 0 ? a / b : std::nan("");
}

// ---------------------------------------------------------------------------
// Options

using Options = RunOptions;

void usage() {
    std::printf(
        "usage: pluecker_tables [options]\n"
        "  --size N        image N x N for every render                    [512]\n"
        "  --repeat N      best of N timings per configuration              [3]\n"
        "  --synthetic N   triangles of the synthetic scene (0: none)        [4000000]\n"
        "  --shared DIR    folder of the shared scenes                       [../shared/scenes]\n"
        "  --scenes LIST   comma-separated specs instead of the default list\n"
        "                  (teapot, spheres, sphere:N, FILE, synthetic:N)\n"
        "  --out DIR       tables.json and tables.md                         [out/tables]\n");
}

Options parse(int argc, char** argv) {
    Options o(512, 3, "out/tables");
    const Args args = tool_args(argc, argv, kRunOptions);
    if (wants_help(args)) {
        usage();
        std::exit(0);
    }
    read_run_options(args, o);
    return o;
}

// ---------------------------------------------------------------------------
// Configurations

enum Structure { BvhMedian, BvhSah, KdMedian, KdSah, kStructures };
const char* kStructureNames[kStructures] = {"bvh-median", "bvh-sah", "kd-median", "kd-sah"};

struct Config {
    const char* name;
    Structure structure;
    BoxTestKind test;
    ChildOrder order;
};
const std::array<Config, 8> kConfigs = {{
    {"smits-mul-cls", BvhMedian, BoxTestKind::Smits, ChildOrder::Fixed},
    {"smits-dist", BvhMedian, BoxTestKind::Smits, ChildOrder::Dist},
    {"smits-dsa", BvhMedian, BoxTestKind::Smits, ChildOrder::Dsa},
    {"pluecker-cls", BvhMedian, BoxTestKind::Pluecker, ChildOrder::Fixed},
    {"pluecker-dsa", BvhMedian, BoxTestKind::Pluecker, ChildOrder::Dsa},
    {"pluecker-dsa-sah", BvhSah, BoxTestKind::Pluecker, ChildOrder::Dsa},
    {"K-D", KdMedian, BoxTestKind::Pluecker, ChildOrder::Dsa},
    {"K-D-sah", KdSah, BoxTestKind::Pluecker, ChildOrder::Dsa},
}};
enum ConfigId { SmitsCls, SmitsDist, SmitsDsa, PlueckerCls, PlueckerDsa, PlueckerDsaSah, Kd, KdSahC };

struct ConfigResult {
    double render_s = 0;  // best CPU seconds of the render
    double trace_s = 0;   // best CPU seconds tracing the recorded rays
    std::uint64_t rays = 0;
    TraversalStats st;    // of one trace of the recorded rays
    bool same_image = true;
    bool same_hits = true;
};

struct StructureResult {
    double build_s = 0;  // CPU seconds
    std::size_t nodes = 0, leaves = 0, refs = 0;
    std::size_t node_bytes = 0, list_bytes = 0;  // BVH: 32-byte nodes, tri_order; K-D: 8-byte nodes, leaf lists
    int depth = 0;
};

struct SceneResult {
    std::string label;
    std::size_t triangles = 0;
    std::uint64_t rays = 0;
    std::array<ConfigResult, 8> c;
    std::array<StructureResult, kStructures> s;
};

std::string fmt(const char* f, double v) {
    char buf[256];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

// ---------------------------------------------------------------------------
// Running

struct Progress {
    std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
    void operator()(const std::string& msg) const {
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::fprintf(stderr, "tables [%6.1f s] %s\n", s, msg.c_str());
    }
};

std::uint64_t hit_checksum(std::uint64_t h, std::uint32_t tri, float t) {
    std::uint32_t bits;
    std::memcpy(&bits, &t, sizeof bits);
    return (h ^ (std::uint64_t{tri} << 32 | bits)) * 0x100000001b3ull;
}

struct Runner {
    const Options& opt;
    const RenderScene& scene;
    const std::vector<RecordedRay>& rays;
    const Image& ref_image;
    std::uint64_t ref_hits;

    RenderOptions render_options(const Config& c) const {
        RenderOptions o;
        o.width = o.height = opt.size;
        o.test = c.test;
        o.order = c.order;
        o.threads = 1;
        return o;
    }

    std::uint64_t trace_all(const Tracer& tr, TraversalStats& st) const {
        std::uint64_t h = 0;
        for (const RecordedRay& r : rays) {
            if (r.shadow) {
                h = hit_checksum(h, tr.occluded(r.ray, st) ? 1u : 0u, 0.0f);
            } else {
                const Hit hit = tr.closest(r.ray, st);
                h = hit_checksum(h, hit.tri, hit.found() ? hit.t : 0.0f);
            }
        }
        return h;
    }

    ConfigResult run(const Config& c, const Tracer& tr) const {
        ConfigResult r;
        const RenderOptions o = render_options(c);
        r.render_s = r.trace_s = 1e300;
        for (int k = 0; k < opt.repeat; ++k) {
            RenderStats st;
            const double t0 = thread_seconds();
            const Image img = render_direct(scene, o, tr, st);
            r.render_s = std::min(r.render_s, thread_seconds() - t0);
            r.same_image = r.same_image && img == ref_image;
            r.rays = 0;
            for (const auto n : st.rays) r.rays += n;
        }
        for (int k = 0; k < opt.repeat; ++k) {
            TraversalStats st;
            const double t0 = thread_seconds();
            const std::uint64_t h = trace_all(tr, st);
            r.trace_s = std::min(r.trace_s, thread_seconds() - t0);
            r.same_hits = r.same_hits && h == ref_hits;
            r.st = st;
        }
        return r;
    }
};

StructureResult bvh_result(const Bvh& b, double build_s) {
    StructureResult s;
    s.build_s = build_s;
    s.nodes = b.nodes.size();
    s.leaves = b.leaf_count();
    s.refs = b.tri_order.size();
    s.node_bytes = b.nodes.size() * sizeof(BvhNode);
    s.list_bytes = b.tri_order.size() * sizeof(std::uint32_t);
    s.depth = b.depth();
    return s;
}

StructureResult kd_result(const KdTree& t, double build_s) {
    StructureResult s;
    s.build_s = build_s;
    s.nodes = t.nodes.size();
    s.leaves = t.leaves;
    s.refs = t.refs.size();
    s.node_bytes = t.node_bytes();
    s.list_bytes = t.list_bytes();
    s.depth = t.depth;
    return s;
}

SceneResult run_scene(const Options& opt, const SceneSpec& spec, const Progress& progress) {
    SceneResult res;
    res.label = spec.label;
    progress("scene " + spec.label + ": loading");
    const Mesh mesh = load_scene(spec);
    res.triangles = mesh.triangles.size();
    auto timed = [](auto&& f) {
        const double t0 = thread_seconds();
        auto v = f();
        return std::make_pair(std::move(v), thread_seconds() - t0);
    };
    auto log_build = [&](Structure s) {
        const StructureResult& r = res.s[s];
        progress(spec.label + ": " + kStructureNames[s] + " built in " + fmt("%.3f", r.build_s) + " s, " +
                 std::to_string(r.nodes) + " nodes, " + std::to_string(r.refs) + " references");
    };
    progress(spec.label + ": " + std::to_string(res.triangles) + " triangles; building the median BVH");
    BuildOptions bo;
    bo.method = BuildMethod::Median;
    auto [bvh_med, med_s] = timed([&] { return build_bvh(mesh, bo); });
    res.s[BvhMedian] = bvh_result(bvh_med, med_s);
    log_build(BvhMedian);
    const Accel accel_med(mesh, bvh_med);
    const RenderScene scene(mesh, accel_med);

    // The reference render (pluecker-dsa on the median BVH), its rays recorded.
    std::vector<RecordedRay> rays;
    Image ref_image;
    std::uint64_t ref_hits = 0;
    {
        const auto inner = make_tracer(accel_med, BoxTestKind::Pluecker, ChildOrder::Dsa);
        const RecordingTracer rec(*inner, rays);
        RenderOptions o;
        o.width = o.height = opt.size;
        o.threads = 1;
        RenderStats st;
        ref_image = render_direct(scene, o, rec, st);
        TraversalStats tst;
        const Runner r0{opt, scene, rays, ref_image, 0};
        ref_hits = r0.trace_all(*inner, tst);
    }
    res.rays = rays.size();
    std::filesystem::create_directories(opt.out);
    write_png(ref_image, (std::filesystem::path(opt.out) / (spec.label + ".png")).string());
    const Runner runner{opt, scene, rays, ref_image, ref_hits};
    auto run = [&](ConfigId id, const Tracer& tr) {
        res.c[id] = runner.run(kConfigs[id], tr);
        const ConfigResult& c = res.c[id];
        char buf[256];
        std::snprintf(buf, sizeof buf, "%s: %-16s render %.3f s, trace %.3f s (%.2f Mrays/s)%s", spec.label.c_str(),
                      kConfigs[id].name, c.render_s, c.trace_s, static_cast<double>(rays.size()) / c.trace_s * 1e-6,
                      c.same_image && c.same_hits ? "" : "  DIFFERENT IMAGE OR HITS");
        progress(buf);
    };
    progress(spec.label + ": " + std::to_string(rays.size()) + " rays a render");
    for (const ConfigId id : {SmitsCls, SmitsDist, SmitsDsa, PlueckerCls, PlueckerDsa})
        run(id, *make_tracer(accel_med, kConfigs[id].test, kConfigs[id].order));
    {
        bo.method = BuildMethod::Sah;
        auto [bvh_sah, s] = timed([&] { return build_bvh(mesh, bo); });
        res.s[BvhSah] = bvh_result(bvh_sah, s);
        log_build(BvhSah);
        const Accel a(mesh, bvh_sah);
        run(PlueckerDsaSah, *make_tracer(a, BoxTestKind::Pluecker, ChildOrder::Dsa));
    }
    for (const BuildMethod m : {BuildMethod::Median, BuildMethod::Sah}) {
        const Structure st = m == BuildMethod::Median ? KdMedian : KdSah;
        BuildOptions kb;
        kb.method = m;
        std::unique_ptr<KdAccel> a;
        {
            auto [tree, s] = timed([&] { return build_kdtree(mesh, KdBuildOptions::from(kb)); });
            res.s[st] = kd_result(tree, s);
            log_build(st);
            a = std::make_unique<KdAccel>(mesh, tree);
        }
        run(st == KdMedian ? Kd : KdSahC, *make_kd_tracer(*a));
    }
    return res;
}

// ---------------------------------------------------------------------------
// Tables

std::string ratio(double a, double b) { return b > 0 ? fmt("%.2f", a / b) : "n/a"; }
// Where our ratio a / b lies against the report's range [lo, hi] (for the
// figures the report gives only for other scenes than ours).
std::string versus(double a, double b, double lo, double hi) {
    if (!(b > 0)) return "n/a";
    const double v = a / b;
    return v < lo ? "below" : (v > hi ? "above" : "within");
}
std::string mb(std::size_t bytes) { return fmt("%.1f", static_cast<double>(bytes) / (1024.0 * 1024.0)); }
std::string ms(double s) { return fmt("%.0f", s * 1e3); }

// One of our time ratios set beside the report's on the same scene.
struct Comparison {
    double ours = std::nan("");    // our render-time ratio
    double report = std::nan("");  // the report's, NaN: no report scene or no figure
    double quotient() const { return ours / report; }  // ours / report
};
Comparison compare(const ReportScene* r, double ours_num_s, double ours_den_s, ConfigId num, ConfigId den) {
    Comparison c;
    if (ours_den_s > 0) c.ours = ours_num_s / ours_den_s;
    if (r) c.report = report_ratio(*r, num, den);
    return c;
}
// The two cells "report" and "ours/report" of a comparison.
std::array<std::string, 2> cells(const ReportScene* r, const Comparison& c) {
    if (!r) return {"-", "-"};
    if (!std::isfinite(c.report)) return {"n/a", "n/a"};
    return {fmt("%.2f", c.report), std::isfinite(c.quotient()) ? fmt("%.2f", c.quotient()) : "n/a"};
}
json to_json(const Comparison& c) {
    auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
    return {{"ours", num(c.ours)}, {"report", num(c.report)}, {"ours_over_report", num(c.quotient())}};
}

// The report's ratio num / den over all its scenes: "lo (scene)-hi (scene)".
std::string report_range(ConfigId num, ConfigId den) {
    const ReportScene *lo = nullptr, *hi = nullptr;
    for (const ReportScene& r : kReportScenes) {
        const double v = report_ratio(r, num, den);
        if (!std::isfinite(v)) continue;
        if (!lo || v < report_ratio(*lo, num, den)) lo = &r;
        if (!hi || v > report_ratio(*hi, num, den)) hi = &r;
    }
    return fmt("%.2f", report_ratio(*lo, num, den)) + " (" + lo->name + ")-" + fmt("%.2f", report_ratio(*hi, num, den)) +
           " (" + hi->name + ")";
}
// The report's K-D / median BVH build-time ratios (Powerplant, Lucy): the
// lowest and the highest.
double kd_build_ratio(const ReportBuild& b) { return b.kd_median_s / b.bvh_median_s; }
std::pair<const ReportBuild*, const ReportBuild*> report_kd_build_ends() {
    const auto [lo, hi] = std::minmax_element(kReportBuilds.begin(), kReportBuilds.end(), [](const auto& x, const auto& y) {
        return kd_build_ratio(x) < kd_build_ratio(y);
    });
    return {&*lo, &*hi};
}
std::string report_kd_build() {
    const auto [lo, hi] = report_kd_build_ends();
    return fmt("%.1f", kd_build_ratio(*lo)) + " (" + lo->name + ")-" + fmt("%.1f", kd_build_ratio(*hi)) + " (" + hi->name + ")";
}

// The report scene's cell: its name (with the triangle counts where
// `with_triangles`), or "no report scene".
std::string report_scene_cell(const ReportScene* r, std::size_t triangles, bool with_triangles) {
    if (!r) return kNoReportScene;
    if (!with_triangles) return r->name;
    const long d = static_cast<long>(triangles) - static_cast<long>(r->triangles);
    return std::string(r->name) + " (" + std::to_string(r->triangles) + " tri, " +
           (d == 0 ? std::string("same") : "ours " + std::string(d > 0 ? "+" : "") + std::to_string(d)) + ")";
}

struct Table {
    std::string title;
    std::vector<std::string> head;
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> notes;

    std::string text() const {
        std::vector<std::size_t> w(head.size());
        for (std::size_t i = 0; i < head.size(); ++i) w[i] = head[i].size();
        for (const auto& r : rows)
            for (std::size_t i = 0; i < r.size() && i < w.size(); ++i) w[i] = std::max(w[i], display_width(r[i]));
        std::string s = title + "\n";
        auto line = [&](const std::vector<std::string>& r) {
            for (std::size_t i = 0; i < r.size(); ++i) {
                s += i ? "  " : "";
                s += r[i];
                if (i + 1 < r.size()) s += std::string(w[i] - display_width(r[i]), ' ');
            }
            s += "\n";
        };
        line(head);
        for (const auto& r : rows) line(r);
        for (const auto& n : notes) s += "  " + n + "\n";
        return s;
    }
    std::string markdown() const {
        std::string s = "### " + title + "\n\n|";
        for (const auto& h : head) s += " " + h + " |";
        s += "\n|";
        for (std::size_t i = 0; i < head.size(); ++i) s += i ? " ---: |" : " --- |";
        s += "\n";
        for (const auto& r : rows) {
            s += "|";
            for (const auto& c : r) s += " " + c + " |";
            s += "\n";
        }
        s += "\n";
        for (const auto& n : notes) s += "- " + n + "\n";
        return s + "\n";
    }
    // UTF-8 code points (ü counts once).
    static std::size_t display_width(const std::string& x) {
        std::size_t n = 0;
        for (const unsigned char ch : x) n += (ch & 0xc0) != 0x80;
        return n;
    }
};

// Our render-time ratios that the report also gives, per scene.
struct SceneComparisons {
    const ReportScene* report = nullptr;
    Comparison box_test, smits_fixed_dsa, smits_dist_dsa, pluecker_fixed_dsa, median_sah, kd_bvh_median, kd_bvh_sah;
};
SceneComparisons comparisons(const SceneResult& s) {
    SceneComparisons k;
    k.report = report_scene(s.label, s.triangles);
    auto cmp = [&](ConfigId num, ConfigId den) { return compare(k.report, s.c[num].render_s, s.c[den].render_s, num, den); };
    k.box_test = cmp(SmitsCls, PlueckerCls);
    k.smits_fixed_dsa = cmp(SmitsCls, SmitsDsa);
    k.smits_dist_dsa = cmp(SmitsDist, SmitsDsa);
    k.pluecker_fixed_dsa = cmp(PlueckerCls, PlueckerDsa);
    k.median_sah = cmp(PlueckerDsa, PlueckerDsaSah);
    k.kd_bvh_median = cmp(Kd, PlueckerDsa);
    k.kd_bvh_sah = cmp(KdSahC, PlueckerDsaSah);
    return k;
}

std::vector<Table> make_tables(const std::vector<SceneResult>& all) {
    std::vector<Table> t(5);
    t[0].title = "Table 1. Box test: smits-mul-cls vs pluecker-cls (median BVH, fixed order); ratio = smits / pluecker time";
    t[0].head = {"scene", "triangles", "report scene", "smits-mul-cls ms", "pluecker-cls ms", "ours: render", "report",
                 "ours/report", "ours: trace"};
    t[1].title = "Table 2. Child order (median BVH); ratio = other order's time / DSA time";
    t[1].head = {"scene", "report scene", "smits cls/dist/dsa ms", "pluecker cls/dsa ms", "smits fixed/dsa", "report",
                 "ours/report", "smits dist/dsa", "report", "ours/report", "pluecker fixed/dsa", "report", "ours/report",
                 "trace: smits fixed/dsa", "trace: pluecker fixed/dsa"};
    t[2].title = "Table 3. BVH build: median vs SAH (pluecker-dsa); ratio = median / SAH render time";
    t[2].head = {"scene", "report scene", "median build ms", "SAH build ms", "SAH Mtri/s", "median ms", "SAH ms",
                 "ours: render", "report", "ours/report", "ours: trace"};
    t[3].title = "Table 4. BVH vs K-D tree (pluecker-dsa BVH; K-D: front-to-back, same triangle test)";
    t[3].head = {"scene", "report scene", "render K-D/BVH med", "report", "ours/report", "render K-D/BVH SAH", "report",
                 "ours/report", "build K-D/BVH med", "build K-D/BVH SAH", "BVH MB med/SAH", "K-D nodes MB med/SAH",
                 "K-D lists MB med/SAH", "lists/nodes med/SAH", "refs/tri med/SAH",
                 "ours vs report: build med; lists/nodes med/SAH"};
    t[4].title = "Every configuration: trace-only Mrays/s (one thread) and work per ray";
    t[4].head = {"scene", "config", "render ms", "trace Mrays/s", "nodes/ray", "boxes/ray", "tris/ray", "same image+hits"};
    const double kd_lo = kd_build_ratio(*report_kd_build_ends().first), kd_hi = kd_build_ratio(*report_kd_build_ends().second);
    for (const SceneResult& s : all) {
        const auto& c = s.c;
        auto rs = [&](ConfigId i) { return c[i].render_s; };
        auto ts = [&](ConfigId i) { return c[i].trace_s; };
        const SceneComparisons k = comparisons(s);
        const ReportScene* r = k.report;
        const std::string name = report_scene_cell(r, s.triangles, false);
        auto add = [&](std::vector<std::string>& row, const Comparison& cmp) {
            row.push_back(std::isfinite(cmp.ours) ? fmt("%.2f", cmp.ours) : "n/a");
            for (const std::string& x : cells(r, cmp)) row.push_back(x);
        };
        std::vector<std::string> r0{s.label, std::to_string(s.triangles), report_scene_cell(r, s.triangles, true),
                                    ms(rs(SmitsCls)), ms(rs(PlueckerCls))};
        add(r0, k.box_test);
        r0.push_back(ratio(ts(SmitsCls), ts(PlueckerCls)));
        t[0].rows.push_back(r0);

        std::vector<std::string> r1{s.label, name, ms(rs(SmitsCls)) + "/" + ms(rs(SmitsDist)) + "/" + ms(rs(SmitsDsa)),
                                    ms(rs(PlueckerCls)) + "/" + ms(rs(PlueckerDsa))};
        add(r1, k.smits_fixed_dsa);
        add(r1, k.smits_dist_dsa);
        add(r1, k.pluecker_fixed_dsa);
        r1.push_back(ratio(ts(SmitsCls), ts(SmitsDsa)));
        r1.push_back(ratio(ts(PlueckerCls), ts(PlueckerDsa)));
        t[1].rows.push_back(r1);

        const auto& st = s.s;
        std::vector<std::string> r2{s.label, name, fmt("%.1f", st[BvhMedian].build_s * 1e3),
                                    fmt("%.1f", st[BvhSah].build_s * 1e3),
                                    fmt("%.2f", static_cast<double>(s.triangles) / st[BvhSah].build_s * 1e-6),
                                    ms(rs(PlueckerDsa)), ms(rs(PlueckerDsaSah))};
        add(r2, k.median_sah);
        r2.push_back(ratio(ts(PlueckerDsa), ts(PlueckerDsaSah)));
        t[2].rows.push_back(r2);

        auto pair = [](const std::string& a, const std::string& b) { return a + "/" + b; };
        std::vector<std::string> r3{s.label, name};
        add(r3, k.kd_bvh_median);
        add(r3, k.kd_bvh_sah);
        for (const std::string& x :
             {ratio(st[KdMedian].build_s, st[BvhMedian].build_s), ratio(st[KdSah].build_s, st[BvhSah].build_s),
              pair(mb(st[BvhMedian].node_bytes + st[BvhMedian].list_bytes), mb(st[BvhSah].node_bytes + st[BvhSah].list_bytes)),
              pair(mb(st[KdMedian].node_bytes), mb(st[KdSah].node_bytes)),
              pair(mb(st[KdMedian].list_bytes), mb(st[KdSah].list_bytes)),
              pair(ratio(double(st[KdMedian].list_bytes), double(st[KdMedian].node_bytes)),
                   ratio(double(st[KdSah].list_bytes), double(st[KdSah].node_bytes))),
              pair(ratio(double(st[KdMedian].refs), double(s.triangles)), ratio(double(st[KdSah].refs), double(s.triangles))),
              versus(st[KdMedian].build_s, st[BvhMedian].build_s, kd_lo, kd_hi) + "; " +
                  (st[KdMedian].list_bytes > st[KdMedian].node_bytes ? "more" : "less") + "/" +
                  (st[KdSah].list_bytes > st[KdSah].node_bytes ? "more" : "less")})
            r3.push_back(x);
        t[3].rows.push_back(r3);
        for (std::size_t i = 0; i < kConfigs.size(); ++i) {
            const ConfigResult& cr = c[i];
            const double n = static_cast<double>(s.rays);
            t[4].rows.push_back({s.label, kConfigs[i].name, ms(cr.render_s), fmt("%.2f", n / cr.trace_s * 1e-6),
                                 fmt("%.1f", double(cr.st.node_visits) / n), fmt("%.1f", double(cr.st.box_tests) / n),
                                 fmt("%.1f", double(cr.st.tri_tests) / n), cr.same_image && cr.same_hits ? "yes" : "NO"});
        }
    }
    const std::string its = "report, its " + std::to_string(kReportScenes.size()) + " scenes";
    t[0].rows.push_back({its, "", "", "", "", "", report_range(SmitsCls, PlueckerCls), "", ""});
    t[1].rows.push_back({its, "", "", "", "", report_range(SmitsCls, SmitsDsa), "", "", report_range(SmitsDist, SmitsDsa), "",
                         "", report_range(PlueckerCls, PlueckerDsa), "", "", ""});
    std::string sah_builds;
    for (const ReportBuild& b : kReportBuilds)
        sah_builds += (sah_builds.empty() ? "" : "; ") + std::string(b.sah_at_least ? "<" : "~") +
                      fmt("%.3f", double(b.triangles) / b.bvh_sah_s * 1e-6) + " (" + b.name + ")";
    t[2].rows.push_back({its, "", "", "", sah_builds, "", "", "", report_range(PlueckerDsa, PlueckerDsaSah), "", ""});
    t[3].rows.push_back({its, "", "", report_range(Kd, PlueckerDsa), "", "", report_range(KdSahC, PlueckerDsaSah), "",
                         report_kd_build(), "n/a", "n/a", "n/a", "n/a", kReportKdMemory, "n/a", ""});
    for (const SceneResult& s : all)
        if (s.label == "synthetic") {
            const double ours = static_cast<double>(s.triangles) / s.s[BvhSah].build_s * 1e-6;
            std::string note = "SAH BVH build throughput, synthetic scene vs the report's:";
            for (const ReportBuild& b : kReportBuilds)
                note += fmt(b.sah_at_least ? " at least %.0fx" : " about %.0fx", ours / (double(b.triangles) / b.bvh_sah_s * 1e-6)) +
                        " its " + b.name + " build" + (&b == &kReportBuilds.back() ? "" : ",");
            t[2].notes.push_back(note);
        }
    std::string map;
    for (const SceneMap& m : kSceneMap) map += (map.empty() ? "" : ", ") + std::string(m.label) + " -> " + m.report;
    const std::string per_scene =
        "report, ours/report: the report's render-time ratio on the same scene (" + map +
        "; only when the triangle count is within 1%) and ours divided by it; '-': the scene has no report scene. "
        "The report times whole renders on its own machine: compare ours: render, not trace";
    for (std::size_t i = 0; i < 4; ++i) t[i].notes.push_back(per_scene);
    t[0].notes.push_back("report scene: the report's triangle count, and ours minus it");
    t[0].notes.push_back("report, its scenes: the lowest and highest of the report's ratios over all its scenes");
    t[2].notes.push_back(std::string("report: ") + kReportSahBuildLong);
    t[3].notes.push_back(std::string("report: ") + kReportKdBuildLong);
    t[3].notes.push_back(std::string("report: ") + kReportKdMemoryLong);
    t[3].notes.push_back("report render ratios: K-D / pluecker-dsa (median BVH) and K-D-sah / pluecker-dsa-sah, from its Tables 3 and 4");
    t[3].notes.push_back("BVH memory: 32-byte nodes + 4-byte triangle index per triangle; K-D: 8-byte nodes + 4-byte leaf-list entries; triangles themselves (same for both) not counted");
    t[3].notes.push_back("last column: our median K-D/BVH build ratio against the report's range (Powerplant, Lucy; it gives no SAH K-D build time), and whether our K-D leaf lists take more or less memory than the K-D nodes");
    return t;
}

json report_json() {
    json j;
    j["sources"] = {kSourceR};
    j["render_s_columns"] = json::array();
    for (const Config& c : kConfigs) j["render_s_columns"].push_back(c.name);
    for (const ReportScene& r : kReportScenes) {
        json js = {{"scene", r.name}, {"triangles", r.triangles}};
        for (std::size_t i = 0; i < kConfigs.size(); ++i)
            js["render_s"][kConfigs[i].name] = r.render_s[i] > 0 ? json(r.render_s[i]) : json(nullptr);
        j["scenes"].push_back(js);
    }
    for (const ReportBuild& b : kReportBuilds)
        j["builds"].push_back({{"scene", b.name},
                               {"triangles", b.triangles},
                               {"bvh_median_s", b.bvh_median_s},
                               {"bvh_sah_s", b.bvh_sah_s},
                               {"bvh_sah_s_is_lower_bound", b.sah_at_least},
                               {"bvh_sah_as_given", b.sah_as_given},
                               {"kd_median_s", b.kd_median_s}});
    for (const SceneMap& m : kSceneMap) j["scene_map"][m.label] = m.report;
    j["sah_build"] = kReportSahBuildLong;
    j["kd_build"] = kReportKdBuildLong;
    j["kd_memory"] = kReportKdMemoryLong;
    j["ranges"] = {{"box_test", report_range(SmitsCls, PlueckerCls)},
                   {"smits_fixed_over_dsa", report_range(SmitsCls, SmitsDsa)},
                   {"smits_dist_over_dsa", report_range(SmitsDist, SmitsDsa)},
                   {"pluecker_fixed_over_dsa", report_range(PlueckerCls, PlueckerDsa)},
                   {"median_over_sah", report_range(PlueckerDsa, PlueckerDsaSah)},
                   {"kd_over_bvh_median", report_range(Kd, PlueckerDsa)},
                   {"kd_over_bvh_sah", report_range(KdSahC, PlueckerDsaSah)},
                   {"kd_over_bvh_build_median", report_kd_build()}};
    return j;
}

json to_json(const Options& o, const std::vector<SceneResult>& all) {
    json j;
    j["settings"] = {{"size", o.size}, {"repeat", o.repeat}, {"threads", 1}, {"synthetic", o.synthetic},
                     {"timing", "CPU seconds of the working thread, best of repeat"}};
    j["report"] = report_json();
    for (const SceneResult& s : all) {
        json js;
        js["scene"] = s.label;
        js["triangles"] = s.triangles;
        js["rays_per_render"] = s.rays;
        const SceneComparisons k = comparisons(s);
        if (k.report)
            js["report_scene"] = {{"name", k.report->name},
                                  {"triangles", k.report->triangles},
                                  {"ours_minus_report_triangles",
                                   static_cast<long>(s.triangles) - static_cast<long>(k.report->triangles)}};
        else
            js["report_scene"] = nullptr;
        js["versus_report"] = {{"note", "render-time ratios: ours, the report's on the same scene (null: "
                                        "no report scene), ours / report"},
                               {"box_test_smits_over_pluecker", to_json(k.box_test)},
                               {"smits_fixed_over_dsa", to_json(k.smits_fixed_dsa)},
                               {"smits_dist_over_dsa", to_json(k.smits_dist_dsa)},
                               {"pluecker_fixed_over_dsa", to_json(k.pluecker_fixed_dsa)},
                               {"median_over_sah", to_json(k.median_sah)},
                               {"kd_over_bvh_median", to_json(k.kd_bvh_median)},
                               {"kd_sah_over_bvh_sah", to_json(k.kd_bvh_sah)}};
        for (std::size_t i = 0; i < kConfigs.size(); ++i) {
            const ConfigResult& r = s.c[i];
            js["configs"][kConfigs[i].name] = {
                {"structure", kStructureNames[kConfigs[i].structure]},
                {"render_s", r.render_s},
                {"trace_s", r.trace_s},
                {"trace_mrays_s", static_cast<double>(s.rays) / r.trace_s * 1e-6},
                {"node_visits", r.st.node_visits},
                {"box_tests", r.st.box_tests},
                {"tri_tests", r.st.tri_tests},
                {"same_image", r.same_image},
                {"same_hits", r.same_hits}};
        }
        for (int k2 = 0; k2 < kStructures; ++k2) {
            const StructureResult& r = s.s[static_cast<std::size_t>(k2)];
            js["structures"][kStructureNames[k2]] = {{"build_s", r.build_s},   {"nodes", r.nodes},
                                                     {"leaves", r.leaves},     {"references", r.refs},
                                                     {"node_bytes", r.node_bytes}, {"list_bytes", r.list_bytes},
                                                     {"depth", r.depth}};
        }
        j["scenes"].push_back(js);
    }
    return j;
}

int tables_main(const Options& o) {
    const Progress progress;
    const std::vector<SceneSpec> specs = run_scenes(o);
    std::string list;
    for (const auto& s : specs) list += (list.empty() ? "" : ", ") + s.label;
    progress("scenes: " + list + "; " + std::to_string(o.size) + "x" + std::to_string(o.size) + ", best of " +
             std::to_string(o.repeat) + ", one thread");
    std::vector<SceneResult> all;
    for (const auto& s : specs) all.push_back(run_scene(o, s, progress));

    const std::vector<Table> tables = make_tables(all);
    std::string md = "## Tables of Mahovsky's 2005 report, reproduced\n\n";
    md += "Image " + std::to_string(o.size) + "x" + std::to_string(o.size) +
          " per render, one thread, CPU time of the thread, best of " + std::to_string(o.repeat) + "; `render` = the whole render (shading included), `trace` = the render's " +
          "rays traced again without shading.\n\n";
    std::printf("\n");
    for (const Table& t : tables) {
        std::printf("%s\n", t.text().c_str());
        md += t.markdown();
    }
    std::printf("Source of the report's figures:\n  %s\n", kSourceR);
    md += std::string("Source of the report's figures:\n\n- ") + kSourceR + "\n";
    std::filesystem::create_directories(o.out);
    const std::filesystem::path dir(o.out);
    std::ofstream(dir / "tables.json") << to_json(o, all).dump(2) << "\n";
    std::ofstream(dir / "tables.md") << md;
    int status = 0;
    for (const SceneResult& s : all)
        for (const ConfigResult& r : s.c)
            if (!r.same_image || !r.same_hits) status = 1;
    if (status) std::printf("ERROR: a configuration rendered another image or found other hits (see the last table)\n");
    std::printf("tables: wrote %s and %s\n", (dir / "tables.json").c_str(), (dir / "tables.md").c_str());
    return status;
}

}  // namespace

int main(int argc, char** argv) {
    return pluecker::app::run_tool("pluecker_tables", [&] { return tables_main(parse(argc, argv)); });
}
