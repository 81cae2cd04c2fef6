// SPDX-License-Identifier: MIT
// pluecker_peer: Embree 3 against this project's best configurations on the
// same rays (built only by `make peer`, with -DPLUECKER_PEER=ON and Embree 3
// found).
//
// For each scene: the rays of one render (render.hpp at --size, one thread,
// pluecker-dsa on the SAH BVH) recorded and split by kind (camera rays start
// at the camera's eye; shadow rays are any-hit; the other closest-hit rays
// are reflection and refraction rays), plus --random random rays (origins in
// the cube, unbounded, closest hit). Every structure traces every ray in one
// thread: Embree's BVH (one device with threads=1, scene flag
// RTC_SCENE_FLAG_ROBUST, build quality MEDIUM and HIGH: Embree's binned SAH
// builder, HIGH adding spatial splits) and ours (SAH BVH with pluecker-dsa
// and smits-dsa, SAH K-D tree). Printed: build time, Mrays/s per thread for
// each ray kind and its ratio to Embree MEDIUM's in the same run, and the
// agreement of hit/miss and triangle id between ours and Embree HIGH over
// all rays, with the count of differences and examples (t values of both
// sides); ours are first checked to agree with each other bit for bit.
#include "pluecker/app/tables_common.hpp"
#include "pluecker/app/tool.hpp"

#include "pluecker/bvh.hpp"
#include "pluecker/kdtree.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/render.hpp"
#include "pluecker/traverse.hpp"

#include <embree3/rtcore.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace pluecker;
using namespace pluecker::tables;
using namespace pluecker::app;
using nlohmann::json;

struct Options : RunOptions {
    Options() : RunOptions(1024, 2, "out/peer") {}
    std::size_t random = 1000000;
    int examples = 5;
};

void usage() {
    std::printf(
        "usage: pluecker_peer [options]\n"
        "  --size N        render N x N whose rays are traced               [1024]\n"
        "  --random N      random rays per scene                             [1000000]\n"
        "  --repeat N      best of N timings                                 [2]\n"
        "  --examples N    differences shown per comparison                  [5]\n"
        "  --synthetic N   triangles of the synthetic scene (0: none)        [4000000]\n"
        "  --shared DIR    folder of the shared scenes                       [../shared/scenes]\n"
        "  --scenes LIST   comma-separated specs instead of the default list\n"
        "  --out DIR       peer.json                                         [out/peer]\n");
}

Options parse(int argc, char** argv) {
    Options o;
    std::set<std::string> options = kRunOptions;
    options.insert({"random", "examples"});
    const Args args = tool_args(argc, argv, options);
    if (wants_help(args)) {
        usage();
        std::exit(0);
    }
    read_run_options(args, o);
    o.random = static_cast<std::size_t>(args.get_int("random", static_cast<long>(o.random), 0, 100000000));
    o.examples = static_cast<int>(args.get_int("examples", o.examples, 0, 1000));
    return o;
}

// ---------------------------------------------------------------------------
// Ray sets and answers

enum Kind { Camera, Shadow, Secondary, Random, kKinds };
const char* kKindNames[kKinds] = {"camera", "shadow", "secondary", "random"};

struct RaySet {
    std::vector<Ray> rays;
    bool any_hit = false;
};

// One answer: the triangle (kNoHit for a miss; 0/kNoHit for any hit) and t.
struct Answer {
    std::uint32_t tri = kNoHit;
    float t = 0.0f;
};

class Engine {
public:
    virtual ~Engine() = default;
    virtual Answer closest(const Ray& r) = 0;
    virtual bool occluded(const Ray& r) = 0;
};

class OurEngine final : public Engine {
public:
    explicit OurEngine(std::unique_ptr<Tracer> t) : t_(std::move(t)) {}
    Answer closest(const Ray& r) override {
        const Hit h = t_->closest(r, st_);
        return Answer{h.tri, h.found() ? h.t : 0.0f};
    }
    bool occluded(const Ray& r) override { return t_->occluded(r, st_); }

private:
    std::unique_ptr<Tracer> t_;
    TraversalStats st_;
};

class EmbreeEngine final : public Engine {
public:
    EmbreeEngine(RTCDevice device, const Mesh& m, RTCBuildQuality q) {
        scene_ = rtcNewScene(device);
        rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(scene_, q);
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), m.vertices.size()));
        auto* ix = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), m.triangles.size()));
        for (std::size_t i = 0; i < m.vertices.size(); ++i) {
            v[3 * i] = m.vertices[i].x;
            v[3 * i + 1] = m.vertices[i].y;
            v[3 * i + 2] = m.vertices[i].z;
        }
        for (std::size_t i = 0; i < m.triangles.size(); ++i)
            for (int k = 0; k < 3; ++k) ix[3 * i + static_cast<std::size_t>(k)] = m.triangles[i][static_cast<std::size_t>(k)];
        rtcSetGeometryBuildQuality(g, q);
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene_, g);
        rtcReleaseGeometry(g);
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = process_seconds();
        rtcCommitScene(scene_);
        build_cpu_s = process_seconds() - c0;
        build_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw std::runtime_error("embree: scene commit failed");
    }
    ~EmbreeEngine() override { rtcReleaseScene(scene_); }
    EmbreeEngine(const EmbreeEngine&) = delete;
    EmbreeEngine& operator=(const EmbreeEngine&) = delete;

    Answer closest(const Ray& r) override {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh{};
        set_ray(rh.ray, r);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &ctx, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return Answer{};
        return Answer{rh.hit.primID, rh.ray.tfar};
    }
    bool occluded(const Ray& r) override {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRay ray{};
        set_ray(ray, r);
        rtcOccluded1(scene_, &ctx, &ray);
        return ray.tfar == -std::numeric_limits<float>::infinity();
    }
    static double process_seconds() {
        timespec ts{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
        return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
    }
    double build_wall_s = 0, build_cpu_s = 0;

private:
    static void set_ray(RTCRay& out, const Ray& r) {
        out.org_x = r.o.x;
        out.org_y = r.o.y;
        out.org_z = r.o.z;
        out.dir_x = r.d.x;
        out.dir_y = r.d.y;
        out.dir_z = r.d.z;
        out.tnear = 0.0f;
        out.tfar = r.tmax;
        out.time = 0.0f;
        out.mask = 0xffffffffu;
        out.flags = 0;
    }
    RTCScene scene_ = nullptr;
};

struct KindResult {
    double seconds = 0;
    std::vector<Answer> answers;
};

KindResult trace(Engine& e, const RaySet& set, int repeat) {
    KindResult r;
    r.seconds = 1e300;
    for (int k = 0; k < repeat; ++k) {
        std::vector<Answer> out(set.rays.size());
        const double t0 = thread_seconds();
        if (set.any_hit) {
            for (std::size_t i = 0; i < set.rays.size(); ++i) out[i] = Answer{e.occluded(set.rays[i]) ? 0u : kNoHit, 0.0f};
        } else {
            for (std::size_t i = 0; i < set.rays.size(); ++i) out[i] = e.closest(set.rays[i]);
        }
        r.seconds = std::min(r.seconds, thread_seconds() - t0);
        r.answers = std::move(out);
    }
    return r;
}

struct Row {
    std::string name;
    double build_wall_s = 0, build_cpu_s = 0;
    std::array<KindResult, kKinds> kinds;
};

std::string mrays(std::size_t n, double s) {
    char b[32];
    std::snprintf(b, sizeof b, "%.2f", s > 0 ? static_cast<double>(n) / s * 1e-6 : 0.0);
    return b;
}

// A triangle difference whose t differs by more than this (relative) is not
// a tie between neighbours at one point; counted apart.
constexpr double kFarRelDt = 1e-5;

json compare(const Row& ours, const Row& ref, const std::array<RaySet, kKinds>& sets, int examples) {
    json j;
    std::printf("  agreement %s vs %s:\n", ours.name.c_str(), ref.name.c_str());
    std::size_t total = 0, total_diff = 0;
    for (int k = 0; k < kKinds; ++k) {
        const auto& a = ours.kinds[static_cast<std::size_t>(k)].answers;
        const auto& b = ref.kinds[static_cast<std::size_t>(k)].answers;
        std::size_t hitmiss = 0, tri = 0, tri_same_t = 0, tri_far = 0;
        double max_rel_dt = 0.0;
        std::size_t worst = a.size();  // the ray of max_rel_dt
        std::vector<std::string> ex;
        auto describe = [&](std::size_t i) {
            const Ray& r = sets[static_cast<std::size_t>(k)].rays[i];
            char buf[400];
            auto side = [&](const Answer& x) {
                char s[64];
                if (x.tri == kNoHit) std::snprintf(s, sizeof s, "miss");
                else if (sets[static_cast<std::size_t>(k)].any_hit) std::snprintf(s, sizeof s, "occluded");
                else std::snprintf(s, sizeof s, "tri %u t=%.9g", x.tri, static_cast<double>(x.t));
                return std::string(s);
            };
            std::snprintf(buf, sizeof buf, "ray %zu o=(%.9g,%.9g,%.9g) d=(%.9g,%.9g,%.9g) tmax=%g: ours %s, embree %s", i,
                          double(r.o.x), double(r.o.y), double(r.o.z), double(r.d.x), double(r.d.y), double(r.d.z),
                          double(r.tmax), side(a[i]).c_str(), side(b[i]).c_str());
            return std::string(buf);
        };
        for (std::size_t i = 0; i < a.size(); ++i) {
            const bool ha = a[i].tri != kNoHit, hb = b[i].tri != kNoHit;
            const bool differ_hm = ha != hb;
            const bool differ_tri = !differ_hm && ha && a[i].tri != b[i].tri;
            if (!differ_hm && !differ_tri) continue;
            hitmiss += differ_hm;
            tri += differ_tri;
            tri_same_t += differ_tri && a[i].t == b[i].t;
            if (differ_tri && b[i].t != 0.0f) {
                const double rel = std::fabs(double(a[i].t) - double(b[i].t)) / std::fabs(double(b[i].t));
                if (rel > max_rel_dt) max_rel_dt = rel, worst = i;
                tri_far += rel > kFarRelDt;
            }
            if (static_cast<int>(ex.size()) < examples) ex.push_back(describe(i));
        }
        // The largest difference in t is always shown.
        if (worst < a.size() && examples > 0) {
            const std::string w = describe(worst);
            if (std::find(ex.begin(), ex.end(), w) == ex.end()) ex.push_back(w + " (largest |dt|/t)");
        }
        total += a.size();
        total_diff += hitmiss + tri;
        std::printf("    %-9s %9zu rays: hit/miss differ %zu, triangle differs %zu (same t: %zu, |dt|/t > %.0e: %zu, "
                    "largest |dt|/t %.1e)\n",
                    kKindNames[k], a.size(), hitmiss, tri, tri_same_t, kFarRelDt, tri_far, max_rel_dt);
        for (const auto& e : ex) std::printf("      %s\n", e.c_str());
        j[kKindNames[k]] = {{"rays", a.size()}, {"hit_miss_differ", hitmiss}, {"triangle_differs", tri},
                            {"triangle_differs_same_t", tri_same_t},
                            {"triangle_differs_far", tri_far}, {"max_rel_dt", max_rel_dt}, {"examples", ex}};
    }
    std::printf("    all       %9zu rays: %zu differ (%.4f%%)\n", total, total_diff,
                total ? 100.0 * static_cast<double>(total_diff) / static_cast<double>(total) : 0.0);
    j["rays"] = total;
    j["differ"] = total_diff;
    return j;
}

json run_scene(const Options& o, const SceneSpec& spec, RTCDevice device) {
    std::fprintf(stderr, "peer: %s: loading\n", spec.label.c_str());
    const Mesh mesh = load_scene(spec);
    BuildOptions bo;
    bo.method = BuildMethod::Sah;
    const double b0 = thread_seconds();
    const Bvh bvh = build_bvh(mesh, bo);
    const double bvh_s = thread_seconds() - b0;
    const Accel accel(mesh, bvh);
    const RenderScene scene(mesh, accel);

    // The rays of one render, split by kind, and random rays.
    std::array<RaySet, kKinds> sets;
    sets[Shadow].any_hit = true;
    {
        std::vector<RecordedRay> rec;
        const auto inner = make_tracer(accel, BoxTestKind::Pluecker, ChildOrder::Dsa);
        const RecordingTracer tr(*inner, rec);
        RenderOptions ro;
        ro.width = ro.height = o.size;
        RenderStats st;
        std::fprintf(stderr, "peer: %s: recording the rays of a %dx%d render\n", spec.label.c_str(), o.size, o.size);
        render_direct(scene, ro, tr, st);
        const Vec3 eye = default_camera(mesh).eye;
        for (const RecordedRay& r : rec) {
            const Kind k = r.shadow ? Shadow : (r.ray.o == eye ? Camera : Secondary);
            sets[k].rays.push_back(r.ray);
        }
    }
    sets[Random].rays = random_rays(o.random, 0x5eedull + mesh.triangles.size());
    std::size_t nrays = 0;
    for (const auto& s : sets) nrays += s.rays.size();

    std::vector<Row> rows;
    auto run_engine = [&](const std::string& name, Engine& e, double wall, double cpu) {
        Row r;
        r.name = name;
        r.build_wall_s = wall;
        r.build_cpu_s = cpu;
        for (int k = 0; k < kKinds; ++k) {
            std::fprintf(stderr, "peer: %s: %s %s rays\n", spec.label.c_str(), name.c_str(), kKindNames[k]);
            r.kinds[static_cast<std::size_t>(k)] = trace(e, sets[static_cast<std::size_t>(k)], o.repeat);
        }
        rows.push_back(std::move(r));
    };
    for (const auto& [q, name] : {std::pair{RTC_BUILD_QUALITY_MEDIUM, "embree-medium"}, std::pair{RTC_BUILD_QUALITY_HIGH, "embree-high"}}) {
        std::fprintf(stderr, "peer: %s: building %s\n", spec.label.c_str(), name);
        EmbreeEngine e(device, mesh, q);
        run_engine(name, e, e.build_wall_s, e.build_cpu_s);
    }
    {
        OurEngine e(make_tracer(accel, BoxTestKind::Pluecker, ChildOrder::Dsa));
        run_engine("ours pluecker-dsa-sah", e, bvh_s, bvh_s);
    }
    {
        OurEngine e(make_tracer(accel, BoxTestKind::Smits, ChildOrder::Dsa));
        run_engine("ours smits-dsa-sah", e, bvh_s, bvh_s);
    }
    {
        KdBuildOptions ko;
        const double k0 = thread_seconds();
        const KdTree tree = build_kdtree(mesh, ko);
        const double kd_s = thread_seconds() - k0;
        const KdAccel ka(mesh, tree);
        OurEngine e(make_kd_tracer(ka));
        run_engine("ours K-D-sah", e, kd_s, kd_s);
    }

    std::printf("\nscene %s: %zu triangles; rays: camera %zu, shadow %zu, secondary %zu, random %zu (%zu in all)\n",
                spec.label.c_str(), mesh.triangles.size(), sets[Camera].rays.size(), sets[Shadow].rays.size(),
                sets[Secondary].rays.size(), sets[Random].rays.size(), nrays);
    std::printf("  %-22s %12s %12s", "structure", "build ms", "build cpu ms");
    for (const char* k : kKindNames) std::printf(" %18s", (std::string(k) + " Mrays/s").c_str());
    std::printf("\n");
    const Row& base = rows[0];
    json j;
    j["scene"] = spec.label;
    j["triangles"] = mesh.triangles.size();
    for (const Row& r : rows) {
        std::printf("  %-22s %12.1f %12.1f", r.name.c_str(), r.build_wall_s * 1e3, r.build_cpu_s * 1e3);
        json jr = {{"build_wall_s", r.build_wall_s}, {"build_cpu_s", r.build_cpu_s}};
        for (int k = 0; k < kKinds; ++k) {
            const auto n = sets[static_cast<std::size_t>(k)].rays.size();
            const double s = r.kinds[static_cast<std::size_t>(k)].seconds;
            const double sb = base.kinds[static_cast<std::size_t>(k)].seconds;
            char cell[64];
            if (n == 0)
                std::snprintf(cell, sizeof cell, "-");
            else
                std::snprintf(cell, sizeof cell, "%s (x%.2f)", mrays(n, s).c_str(), s > 0 ? sb / s : 0.0);
            std::printf(" %18s", cell);
            if (n == 0) continue;
            jr["mrays_s"][kKindNames[k]] = s > 0 ? static_cast<double>(n) / s * 1e-6 : 0.0;
            jr["ratio_to_embree_medium"][kKindNames[k]] = s > 0 ? sb / s : 0.0;
        }
        std::printf("\n");
        j["structures"][r.name] = jr;
    }
    std::printf("  (x: Mrays/s as a ratio to embree-medium's; one thread; CPU time of the thread, best of %d)\n", o.repeat);
    // Ours agree with each other bit for bit (same triangle test, (t, id)
    // order); checked here, then compared with Embree once.
    std::size_t ours_differ = 0;
    for (std::size_t i = 3; i < rows.size(); ++i)
        for (int k = 0; k < kKinds; ++k) {
            const auto& a = rows[2].kinds[static_cast<std::size_t>(k)].answers;
            const auto& b = rows[i].kinds[static_cast<std::size_t>(k)].answers;
            for (std::size_t r = 0; r < a.size(); ++r)
                ours_differ += a[r].tri != b[r].tri || std::memcmp(&a[r].t, &b[r].t, sizeof(float)) != 0;
        }
    std::printf("  ours (%zu structures) agree with each other on triangle and t bits of all %zu rays: %s\n",
                rows.size() - 2, nrays, ours_differ == 0 ? "yes" : ("NO, " + std::to_string(ours_differ) + " differ").c_str());
    j["ours_differ_among_themselves"] = ours_differ;
    j["agreement"][rows[2].name + " vs " + rows[1].name] = compare(rows[2], rows[1], sets, o.examples);
    j["agreement"]["embree-medium vs embree-high"] = compare(rows[0], rows[1], sets, o.examples);
    std::fflush(stdout);
    return j;
}

int peer_main(const Options& o) {
    RTCDevice device = rtcNewDevice("threads=1");
    if (!device) throw std::runtime_error("embree: rtcNewDevice failed");
    {
        // Warm-up: Embree's first commit pays for its lazy set-up; keep it
        // out of the first measured build.
        Mesh one;
        one.vertices = {Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f)};
        one.triangles = {{0, 1, 2}};
        EmbreeEngine warm(device, one, RTC_BUILD_QUALITY_MEDIUM);
    }
    const std::vector<SceneSpec> specs = run_scenes(o);
    std::printf("Embree %d.%d.%d (robust scene flag, one thread) against this project's traversal\n",
                RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
    json all;
    for (const auto& s : specs) all["scenes"].push_back(run_scene(o, s, device));
    rtcReleaseDevice(device);
    std::filesystem::create_directories(o.out);
    const auto path = std::filesystem::path(o.out) / "peer.json";
    std::ofstream(path) << all.dump(2) << "\n";
    std::printf("\npeer: wrote %s\n", path.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return pluecker::app::run_tool("pluecker_peer", [&] { return peer_main(parse(argc, argv)); });
}
