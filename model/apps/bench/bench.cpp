// SPDX-License-Identifier: MIT
// pluecker_bench: BVH build time and single-thread traversal throughput of
// the report's five configurations (smits-mul-cls, smits-dist, smits-dsa,
// pluecker-cls, pluecker-dsa) on a large synthetic sphere, for camera rays
// (a view of the sphere) and random rays (origins and directions random in
// the cube), closest hit. Last, the fixed-point box test of the software
// renderer (--test fixed, 16/16 bits, conservative) against float pluecker
// on the same rays: the fixed test through the direct traversal and through
// the batched traversal with the software engine (the renderer's path).
// Then the exact rational test (exact_hit, the ground truth of the suites)
// on random and extreme queries, in queries per second.
#include "pluecker/boxtest.hpp"
#include "pluecker/bvh.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/querygen.hpp"
#include "pluecker/render.hpp"
#include "pluecker/rng.hpp"
#include "pluecker/traverse.hpp"

#include "pluecker/app/names.hpp"
#include "pluecker/app/tool.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <utility>
#include <exception>
#include <string>
#include <vector>

namespace {

using namespace pluecker;
using namespace pluecker::app;

struct Options {
    std::string scene = "sphere:1000000";
    int size = 1024;            // camera rays: size x size
    std::size_t random = 1000000;  // random rays
    int repeat = 1;             // best of N timings
    std::vector<BuildMethod> builds{BuildMethod::Median, BuildMethod::Sah};
    std::vector<int> configs{0, 1, 2, 3, 4};  // indices into kConfigNames
    bool fixed = true;                         // the fixed-point comparison
    int fixed_size = 512;                      // its camera rays: N x N
    int bins = BuildOptions{}.bins;            // SAH bins per axis
};

const char* kConfigNames[5] = {"smits-mul-cls", "smits-dist", "smits-dsa", "pluecker-cls", "pluecker-dsa"};

void usage() {
    std::printf(
        "usage: pluecker_bench [--scene S] [--size N] [--random N] [--repeat N]\n"
        "  --scene S    scene spec (teapot | spheres | sphere:N | FILE)  [sphere:1000000]\n"
        "  --size N     camera rays: N x N view of the scene, 8x8 tiles\n"
        "               in Morton order                                   [1024]\n"
        "  --random N   random rays, origins and directions in the cube   [1000000]\n"
        "  --repeat N   time each run N times, report the best            [1]\n"
        "  --build B    median | sah | both                               [both]\n"
        "  --config C   one configuration (smits-mul-cls, smits-dist, smits-dsa,\n"
        "               pluecker-cls, pluecker-dsa) or all                [all]\n"
        "  --bins N     SAH build: bins per axis (2..64)                  [16]\n"
        "  --fixed N    fixed-point vs float comparison on N x N camera rays\n"
        "               and N*N random rays; 0: skip                      [512]\n");
}

Options parse(int argc, char** argv) {
    const Args args = tool_args(argc, argv, {"scene", "size", "random", "repeat", "build", "config", "bins", "fixed"});
    if (wants_help(args)) {
        usage();
        std::exit(0);
    }
    Options o;
    o.scene = args.get("scene", o.scene);
    o.size = static_cast<int>(args.get_int("size", o.size, 1, 16384));
    o.random = static_cast<std::size_t>(args.get_int("random", static_cast<long>(o.random), 1, 1L << 30));
    o.repeat = static_cast<int>(args.get_int("repeat", o.repeat, 1, 100));
    if (args.has("build")) {
        const std::string v = args.get("build", "");
        o.builds = v == "both" ? std::vector<BuildMethod>{BuildMethod::Median, BuildMethod::Sah}
                               : std::vector<BuildMethod>{parse_build_method(v)};
    }
    if (args.has("config")) {
        const std::string v = args.get("config", "");
        o.configs.clear();
        for (int c = 0; c < 5; ++c)
            if (v == "all" || v == kConfigNames[c]) o.configs.push_back(c);
        if (o.configs.empty()) throw InputError("option --config: unknown configuration '" + v + "'");
    }
    o.bins = static_cast<int>(args.get_int("bins", o.bins, 2, 64));
    if (args.has("fixed")) {
        o.fixed_size = static_cast<int>(args.get_int("fixed", o.fixed_size, 0, 16384));
        o.fixed = o.fixed_size > 0;
    }
    return o;
}

std::vector<Ray> camera_rays(const Mesh& m, int side) {
    const Camera c = default_camera(m);
    const Vec3 w = glm::normalize(c.eye - c.look);
    const Vec3 u = glm::normalize(glm::cross(c.up, w));
    const Vec3 v = glm::cross(w, u);
    const float th = std::tan(glm::radians(c.fov_deg) * 0.5f);
    std::vector<Ray> rays;
    rays.reserve(static_cast<std::size_t>(side) * side);
    // 8x8 pixel tiles, as a tiled renderer issues them: neighbouring rays
    // share the upper BVH levels in the cache. The tiles are taken in Morton
    // (Z) order of their tile coordinates, so that a tile's neighbours above
    // and below are also traced soon after it. The rays are those of a
    // row-major order; only their order differs.
    constexpr int kTile = 8;
    const int tiles_per_side = (side + kTile - 1) / kTile;
    std::vector<std::pair<std::uint64_t, int>> tiles;  // (Morton key, tile index)
    tiles.reserve(static_cast<std::size_t>(tiles_per_side) * tiles_per_side);
    for (int k = 0; k < tiles_per_side * tiles_per_side; ++k) {
        const auto tx = static_cast<std::uint64_t>(k % tiles_per_side), ty = static_cast<std::uint64_t>(k / tiles_per_side);
        std::uint64_t key = 0;
        for (int b = 0; b < 16; ++b) key |= (tx >> b & 1) << (2 * b) | (ty >> b & 1) << (2 * b + 1);
        tiles.emplace_back(key, k);
    }
    std::sort(tiles.begin(), tiles.end());
    for (const auto& [key, k] : tiles) {
        const int tx = k % tiles_per_side * kTile, ty = k / tiles_per_side * kTile;
        for (int y = ty; y < std::min(ty + kTile, side); ++y)
            for (int x = tx; x < std::min(tx + kTile, side); ++x) {
                const float sx = (2.0f * (x + 0.5f) / side - 1.0f) * th;
                const float sy = (1.0f - 2.0f * (y + 0.5f) / side) * th;
                rays.push_back(Ray{c.eye, glm::normalize(sx * u + sy * v - w), kInf});
            }
    }
    return rays;
}

std::vector<Ray> random_rays(std::size_t n, std::uint64_t seed) {
    Rng rng(seed);
    auto uni = [&rng] { return rng.sym(); };
    std::vector<Ray> rays(n);
    for (Ray& r : rays) {
        r.o = Vec3(uni(), uni(), uni());
        Vec3 d;
        do d = Vec3(uni(), uni(), uni());
        while (glm::length(d) < 0.05f || glm::length(d) > 1.0f);
        r.d = glm::normalize(d);
        r.tmax = kInf;
    }
    return rays;
}

// SAH cost of a tree relative to its root box, with unit costs: the sum
// over nodes of half-area / root half-area, times the triangle count for a
// leaf.
double sah_cost(const Bvh& bvh) {
    const double root = bvh.nodes[0].box.half_area();
    double c = 0;
    for (const BvhNode& n : bvh.nodes) c += n.box.half_area() / root * (n.is_leaf() ? n.count : 1);
    return c;
}

struct Result {
    double mrays = 0;
    TraversalStats st;
    std::uint64_t hits = 0;
    std::uint64_t checksum = 0;
};

template <class Policy, ChildOrder Order>
Result run(const Accel& a, const Policy& p, const std::vector<Ray>& rays, int repeat) {
    Result best;
    for (int k = 0; k < repeat; ++k) {
        Result r;
        const double t0 = thread_seconds();
        for (const Ray& ray : rays) {
            const Hit h = traverse<Policy, Order, false>(a, p, ray, r.st);
            r.hits += h.found();
            r.checksum = r.checksum * 31 + h.tri;
        }
        const double s = thread_seconds() - t0;
        r.mrays = static_cast<double>(rays.size()) / s * 1e-6;
        if (r.mrays > best.mrays) best = r;
    }
    return best;
}

Result run_config(const Accel& a, int config, const std::vector<Ray>& rays, int repeat) {
    switch (config) {
        case 0: return run<SmitsPolicy, ChildOrder::Fixed>(a, SmitsPolicy{}, rays, repeat);
        case 1: return run<SmitsPolicy, ChildOrder::Dist>(a, SmitsPolicy{}, rays, repeat);
        case 2: return run<SmitsPolicy, ChildOrder::Dsa>(a, SmitsPolicy{}, rays, repeat);
        case 3: return run<PlueckerPolicy, ChildOrder::Fixed>(a, PlueckerPolicy{}, rays, repeat);
        default: return run<PlueckerPolicy, ChildOrder::Dsa>(a, PlueckerPolicy{}, rays, repeat);
    }
}

// Closest hits of `rays` through a tracer, best of `repeat`.
Result run_tracer(const Tracer& t, const std::vector<Ray>& rays, int repeat) {
    Result best;
    for (int k = 0; k < repeat; ++k) {
        Result r;
        const double t0 = thread_seconds();
        for (const Ray& ray : rays) {
            const Hit h = t.closest(ray, r.st);
            r.hits += h.found();
            r.checksum = r.checksum * 31 + h.tri;
        }
        r.mrays = static_cast<double>(rays.size()) / (thread_seconds() - t0) * 1e-6;
        if (r.mrays > best.mrays) best = r;
    }
    return best;
}

// The same through the batched traversal and the software engine, the
// fixed-test path of the renderer (render_batched, pool 256).
Result run_batched(const Accel& a, const std::vector<Ray>& rays, int repeat) {
    Result best;
    SoftwareBoxEngine engine(a.format);
    for (int k = 0; k < repeat; ++k) {
        Result r;
        const double t0 = thread_seconds();
        const std::vector<Hit> hits = trace_batched(a, ChildOrder::Dsa, engine, RenderOptions{}.pool, rays, false, r.st);
        r.mrays = static_cast<double>(rays.size()) / (thread_seconds() - t0) * 1e-6;
        for (const Hit& h : hits) {
            r.hits += h.found();
            r.checksum = r.checksum * 31 + h.tri;
        }
        if (r.mrays > best.mrays) best = r;
    }
    return best;
}

// Fixed-point (16/16 conservative, the renderer's default) against float
// pluecker, dsa order, on the same rays: Mray/s and box tests per second.
int compare_fixed(const Mesh& mesh, const Bvh& bvh, BuildMethod method, const Options& o) {
    Accel accel(mesh, bvh);
    const FixedFormat f;
    accel.quantize(f);
    const std::vector<Ray> sets[2] = {camera_rays(mesh, o.fixed_size),
                                      random_rays(static_cast<std::size_t>(o.fixed_size) * o.fixed_size, 0xf1c5du)};
    const char* set_names[2] = {"camera", "random"};
    std::printf("\nfixed-point %d/%d %s vs float pluecker, dsa order, %s BVH; %d x %d camera rays, %zu random\n",
                f.coord_bits, f.dir_bits, mode_name(f.mode), method_name(method), o.fixed_size, o.fixed_size, sets[1].size());
    std::printf("%-7s %-26s %10s %12s %9s %9s\n", "rays", "test (path)", "Mray/s", "Mbox tests/s", "boxes/ray",
                "tris/ray");
    const auto pluecker = make_tracer(accel, BoxTestKind::Pluecker, ChildOrder::Dsa);
    const auto fixed = make_tracer(accel, BoxTestKind::Fixed, ChildOrder::Dsa);
    int status = 0;
    for (int s = 0; s < 2; ++s) {
        const std::vector<Ray>& rays = sets[s];
        const Result r[3] = {run_tracer(*pluecker, rays, o.repeat), run_tracer(*fixed, rays, o.repeat),
                             run_batched(accel, rays, o.repeat)};
        const char* names[3] = {"pluecker float (direct)", "fixed (direct)", "fixed (batched, software)"};
        for (int k = 0; k < 3; ++k) {
            const double n = static_cast<double>(rays.size());
            const double boxes = static_cast<double>(r[k].st.box_tests);
            std::printf("%-7s %-26s %10.2f %12.1f %9.1f %9.1f\n", set_names[s], names[k], r[k].mrays,
                        r[k].mrays * boxes / n, boxes / n, static_cast<double>(r[k].st.tri_tests) / n);
            if (r[k].checksum != r[0].checksum) {
                std::printf("ERROR: %s finds other hits than float pluecker\n", names[k]);
                status = 1;
            }
        }
        std::printf("%-7s fixed/float: %.2fx Mray/s (direct), %.2fx (batched)\n", set_names[s],
                    r[1].mrays / r[0].mrays, r[2].mrays / r[0].mrays);
    }
    return status;
}

// exact_hit over qs, best of `repeat` in thread CPU time: queries per second.
double exact_rate(const std::vector<Query>& qs, int repeat) {
    double best = 0;
    std::size_t hits = 0;
    for (int k = 0; k < repeat; ++k) {
        const double t = thread_seconds();
        hits = 0;
        for (const Query& q : qs) hits += exact_hit(q.ray, q.box);
        const double s = thread_seconds() - t;
        if (k == 0 || s < best) best = s;
    }
    if (hits == 0) std::printf("ERROR: exact_hit found no hit\n");
    return static_cast<double>(qs.size()) / best;
}

void bench_exact(const Options& o) {
    const double r = exact_rate(random_queries(0x7e570001, 500000), o.repeat);
    const double x = exact_rate(extreme_queries(0x7e570002, 160000), o.repeat);
    std::printf("\nexact_hit: %.0f queries/s (500000 random), %.0f queries/s (160000 extreme families); "
                "one thread, best of %d\n", r, x, o.repeat);
}

int bench(const Options& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const Mesh mesh = make_scene(o.scene);
    std::printf("scene %s: %zu triangles (made in %.0f ms)\n", mesh.name.c_str(), mesh.triangles.size(),
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    const std::vector<Ray> cam = camera_rays(mesh, o.size);
    const std::vector<Ray> rnd = random_rays(o.random, 0xbe7c4u);
    std::printf("rays: %zu camera (%dx%d view), %zu random; one thread, closest hit, best of %d;\n"
                "build time and Mray/s in thread CPU time\n\n",
                cam.size(),
                o.size, o.size, rnd.size(), o.repeat);
    std::printf("%-7s %-14s %10s %9s %9s %9s %10s %9s %9s %9s\n", "build", "config", "cam Mray/s", "nodes/ray",
                "boxes/ray", "tris/ray", "rnd Mray/s", "nodes/ray", "boxes/ray", "tris/ray");
    int status = 0;
    for (const BuildMethod method : o.builds) {
        BuildOptions bo;
        bo.method = method;
        bo.bins = o.bins;
        // Best of `repeat` builds, in thread CPU time.
        Bvh bvh;
        double build_ms = 0;
        for (int k = 0; k < o.repeat; ++k) {
            const double t = thread_seconds();
            Bvh b = build_bvh(mesh, bo);
            const double ms = (thread_seconds() - t) * 1e3;
            if (k == 0 || ms < build_ms) build_ms = ms;
            if (k == 0) bvh = std::move(b);
        }
        const Accel accel(mesh, bvh);
        std::printf("%-7s build %.1f ms: %zu nodes, %zu leaves, depth %d, SAH cost %.2f\n", method_name(method),
                    build_ms, bvh.nodes.size(), bvh.leaf_count(), bvh.depth(), sah_cost(bvh));
        std::uint64_t cam_sum = 0, rnd_sum = 0;
        bool first = true;
        for (const int c : o.configs) {
            const Result rc = run_config(accel, c, cam, o.repeat);
            const Result rr = run_config(accel, c, rnd, o.repeat);
            auto per = [](std::uint64_t v, std::size_t n) { return static_cast<double>(v) / static_cast<double>(n); };
            std::printf("%-7s %-14s %10.2f %9.1f %9.1f %9.1f %10.2f %9.1f %9.1f %9.1f\n", method_name(method),
                        kConfigNames[c], rc.mrays, per(rc.st.node_visits, cam.size()), per(rc.st.box_tests, cam.size()),
                        per(rc.st.tri_tests, cam.size()), rr.mrays, per(rr.st.node_visits, rnd.size()),
                        per(rr.st.box_tests, rnd.size()), per(rr.st.tri_tests, rnd.size()));
            std::fflush(stdout);
            // Every configuration must find the same hits.
            if (first) {
                cam_sum = rc.checksum;
                rnd_sum = rr.checksum;
                first = false;
            } else if (rc.checksum != cam_sum || rr.checksum != rnd_sum) {
                std::printf("ERROR: %s finds other hits than %s\n", kConfigNames[c], kConfigNames[o.configs[0]]);
                status = 1;
            }
        }
        if (o.fixed && method == o.builds.back()) status |= compare_fixed(mesh, bvh, method, o);
    }
    bench_exact(o);
    return status;
}

}  // namespace

int main(int argc, char** argv) {
    return pluecker::app::run_tool("pluecker_bench", [&] { return bench(parse(argc, argv)); });
}
