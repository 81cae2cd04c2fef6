// SPDX-License-Identifier: MIT
// Traversal against brute force: every configuration, both builders, three
// scenes; the watertight triangle test; the DSA table; the batched
// (hardware-in-the-loop) traversal against the direct one.
#include "pluecker/app/names.hpp"  // parse_* (the applications' name parsing)
#include "pluecker/bvh.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/querygen.hpp"
#include "pluecker/render.hpp"
#include "pluecker/rng.hpp"
#include "pluecker/traverse.hpp"
#include "pluecker/triangle.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace pluecker {
namespace {

// Seeded rays and points from the project's generator (pluecker/rng.hpp).
struct RayRng : Rng {
    using Rng::Rng;
    float uniform(float lo, float hi) { return lo + (hi - lo) * unit(); }
    Vec3 in_cube(float h) { return Vec3(uniform(-h, h), uniform(-h, h), uniform(-h, h)); }
    Vec3 direction() {
        for (;;) {
            const Vec3 v = in_cube(1.0f);
            const float l = glm::length(v);
            if (l > 0.05f && l <= 1.0f) return v / l;
        }
    }
};

// Random rays in and around the cube (some aimed at a vertex, some finite
// segments, some axis-parallel) and camera rays of the default view.
std::vector<Ray> make_rays(const Mesh& m, std::size_t n_random, int camera_side, std::uint64_t seed) {
    RayRng rng(seed);
    std::vector<Ray> rays;
    for (std::size_t i = 0; i < n_random; ++i) {
        Ray r;
        r.o = rng.in_cube(1.4f);
        switch (i % 5) {
            case 0:
            case 1: r.d = rng.direction(); break;
            case 2: {  // at a vertex: edge and vertex hits
                const Vec3 target = m.vertices[rng.next() % m.vertices.size()];
                r.d = target - r.o;
                if (glm::length(r.d) == 0.0f) r.d = Vec3(0.0f, 0.0f, 1.0f);
                break;
            }
            case 3: {  // axis-parallel, either sign
                r.d = Vec3(0.0f);
                r.d[static_cast<int>(rng.next() % 3)] = (rng.next() & 1) ? 1.0f : -1.0f;
                break;
            }
            default: r.d = rng.direction() * rng.uniform(0.1f, 3.0f); break;
        }
        if (i % 4 == 0) r.tmax = rng.uniform(0.0f, 2.5f);
        rays.push_back(r);
    }
    RenderOptions o;
    o.width = o.height = camera_side;
    const Camera c = default_camera(m);
    const Vec3 w = glm::normalize(c.eye - c.look);
    const Vec3 u = glm::normalize(glm::cross(c.up, w));
    const Vec3 v = glm::cross(w, u);
    const float th = std::tan(c.fov_deg * 3.14159265f / 360.0f);
    for (int y = 0; y < camera_side; ++y)
        for (int x = 0; x < camera_side; ++x) {
            const float sx = (2.0f * (x + 0.5f) / camera_side - 1.0f) * th;
            const float sy = (1.0f - 2.0f * (y + 0.5f) / camera_side) * th;
            rays.push_back(Ray{c.eye, glm::normalize(sx * u + sy * v - w), kInf});
        }
    return rays;
}

struct Config {
    BoxTestKind test;
    ChildOrder order;
};

const std::vector<Config> kConfigs = {
    {BoxTestKind::Smits, ChildOrder::Fixed},    {BoxTestKind::Smits, ChildOrder::Dist},
    {BoxTestKind::Smits, ChildOrder::Dsa},      {BoxTestKind::Pluecker, ChildOrder::Fixed},
    {BoxTestKind::Pluecker, ChildOrder::Dsa},   {BoxTestKind::Fixed, ChildOrder::Fixed},
    {BoxTestKind::Fixed, ChildOrder::Dsa},      {BoxTestKind::Exact, ChildOrder::Dsa},
};

bool same_hit(const Hit& a, const Hit& b) {
    return a.tri == b.tri && std::bit_cast<std::uint32_t>(a.t) == std::bit_cast<std::uint32_t>(b.t) &&
           std::bit_cast<std::uint32_t>(a.b1) == std::bit_cast<std::uint32_t>(b.b1) &&
           std::bit_cast<std::uint32_t>(a.b2) == std::bit_cast<std::uint32_t>(b.b2);
}

// One scene: brute force once, then every configuration and both builders.
void check_scene(const std::string& spec, std::size_t n_random, int camera_side, std::size_t exact_every) {
    const Mesh m = make_scene(spec);
    const std::vector<Ray> rays = make_rays(m, n_random, camera_side, 0x5eed0000u + m.triangles.size());
    std::vector<Hit> truth(rays.size());
    std::vector<char> any_truth(rays.size());
    std::size_t found = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        truth[i] = brute_force_closest(m, rays[i]);
        any_truth[i] = brute_force_any(m, rays[i]);
        ASSERT_EQ(truth[i].found(), bool(any_truth[i])) << "ray " << i;
        found += truth[i].found();
    }
    // The ray set is not trivial.
    EXPECT_GT(found, rays.size() / 5) << spec;
    EXPECT_LT(found, rays.size()) << spec;

    for (const BuildMethod method : {BuildMethod::Median, BuildMethod::Sah}) {
        BuildOptions bo;
        bo.method = method;
        const Bvh bvh = build_bvh(m, bo);
        Accel accel(m, bvh);
        accel.quantize(FixedFormat{});
        for (const Config& c : kConfigs) {
            const auto tracer = make_tracer(accel, c.test, c.order);
            const std::size_t step = c.test == BoxTestKind::Exact ? exact_every : 1;
            std::size_t bad_closest = 0, bad_any = 0;
            TraversalStats st;
            for (std::size_t i = 0; i < rays.size(); i += step) {
                const Hit h = tracer->closest(rays[i], st);
                if (!same_hit(h, truth[i])) {
                    if (bad_closest++ < 3)
                        ADD_FAILURE() << spec << " " << method_name(method) << " " << config_name(c.test, c.order)
                                      << " ray " << i << ": tri " << h.tri << " t " << h.t << " vs brute force tri "
                                      << truth[i].tri << " t " << truth[i].t;
                }
                if (tracer->occluded(rays[i], st) != bool(any_truth[i])) ++bad_any;
            }
            EXPECT_EQ(bad_closest, 0u) << spec << " " << method_name(method) << " " << config_name(c.test, c.order);
            EXPECT_EQ(bad_any, 0u) << spec << " " << method_name(method) << " " << config_name(c.test, c.order);
            // The BVH does less work than brute force.
            EXPECT_LT(st.tri_tests, (rays.size() / step) * m.triangles.size() / 4) << spec;
        }
    }
}

TEST(Traverse, TeapotAllConfigsMatchBruteForce) { check_scene("teapot", 3000, 48, 7); }
TEST(Traverse, SpheresAllConfigsMatchBruteForce) { check_scene("spheres", 2000, 40, 9); }
TEST(Traverse, BigSphereAllConfigsMatchBruteForce) { check_scene("sphere:20000", 1500, 32, 11); }

// ---------------------------------------------------------------------------

TEST(Dsa, TableIsTheReportRule) {
    // Child 0 is the lower side of the split axis: a ray negative along it
    // visits child 1 first, a positive one child 0.
    for (int c = 0; c < 8; ++c)
        for (int axis = 0; axis < 3; ++axis)
            EXPECT_EQ(dsa_first_child(static_cast<RayClass>(c), axis), class_negative(static_cast<RayClass>(c), axis) ? 1 : 0)
                << class_name(static_cast<RayClass>(c)) << " axis " << axis;
}

TEST(Options, ParseAndCombinations) {
    EXPECT_EQ(parse_box_test("pluecker"), BoxTestKind::Pluecker);
    EXPECT_EQ(parse_child_order("dist"), ChildOrder::Dist);
    EXPECT_THROW(parse_box_test("slab"), InputError);
    EXPECT_THROW(parse_child_order("near"), InputError);
    EXPECT_NO_THROW(check_combination(BoxTestKind::Smits, ChildOrder::Dist));
    for (const BoxTestKind t : {BoxTestKind::Exact, BoxTestKind::Pluecker, BoxTestKind::Fixed}) {
        try {
            check_combination(t, ChildOrder::Dist);
            ADD_FAILURE() << "dist accepted with " << test_name(t);
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("--order"), std::string::npos) << what;
            EXPECT_NE(what.find("--test"), std::string::npos) << what;
        }
    }
    EXPECT_EQ(config_name(BoxTestKind::Smits, ChildOrder::Fixed), "smits-mul-cls");
    EXPECT_EQ(config_name(BoxTestKind::Smits, ChildOrder::Dist), "smits-dist");
    EXPECT_EQ(config_name(BoxTestKind::Smits, ChildOrder::Dsa), "smits-dsa");
    EXPECT_EQ(config_name(BoxTestKind::Pluecker, ChildOrder::Fixed), "pluecker-cls");
    EXPECT_EQ(config_name(BoxTestKind::Pluecker, ChildOrder::Dsa), "pluecker-dsa");
}

// ---------------------------------------------------------------------------
// The inline class-specialised box tests equal boxtest.cpp

template <RayClass C>
void check_kernels_class(const Query& q, std::size_t i, std::size_t& bad) {
    const SmitsRay ref_s = smits_setup(q.ray);
    float ref_t = -1.0f, fast_t = -1.0f;
    const bool ref_hit = smits_hit(ref_s, q.box, &ref_t);
    const bool fast_hit = fast_smits_hit<C>(fast_smits_setup(q.ray), q.box, &fast_t);
    if (ref_hit != fast_hit || std::bit_cast<std::uint32_t>(ref_t) != std::bit_cast<std::uint32_t>(fast_t)) {
        if (bad++ < 3) ADD_FAILURE() << "smits differs on query " << i;
    }
    if (pluecker_hit(pluecker_setup(q.ray), q.box) != fast_pluecker_hit<C>(fast_pluecker_setup(q.ray), q.box)) {
        if (bad++ < 3) ADD_FAILURE() << "pluecker differs on query " << i;
    }
}

void check_kernels(const Query& q, std::size_t i, std::size_t& bad) {
    switch (ray_class(q.ray.d)) {
        case 0: return check_kernels_class<0>(q, i, bad);
        case 1: return check_kernels_class<1>(q, i, bad);
        case 2: return check_kernels_class<2>(q, i, bad);
        case 3: return check_kernels_class<3>(q, i, bad);
        case 4: return check_kernels_class<4>(q, i, bad);
        case 5: return check_kernels_class<5>(q, i, bad);
        case 6: return check_kernels_class<6>(q, i, bad);
        default: return check_kernels_class<7>(q, i, bad);
    }
}

TEST(Kernels, InlineBoxTestsEqualTheLibrary) {
    std::size_t bad = 0;
    const std::vector<Query> rnd = random_queries(11, 200000);
    for (std::size_t i = 0; i < rnd.size(); ++i) check_kernels(rnd[i], i, bad);
    const std::vector<Query> ext = extreme_queries(12, 200000);
    for (std::size_t i = 0; i < ext.size(); ++i) check_kernels(ext[i], i, bad);
    EXPECT_EQ(bad, 0u);
}

// ---------------------------------------------------------------------------
// A BVH deeper than the in-frame stack

TEST(Traverse, DeepBvhUsesTheHeapStack) {
    // A chain: interior node k has a leaf (triangle k) as child 0 and the
    // rest of the chain as child 1.
    const int n = 2 * kMaxStack + 10;
    Mesh m;
    m.name = "chain";
    m.materials.push_back(Material{});
    for (int k = 0; k < n; ++k) {
        const float x = -1.0f + 2.0f * static_cast<float>(k) / static_cast<float>(n);
        const auto v = static_cast<std::uint32_t>(m.vertices.size());
        m.vertices.push_back(Vec3(x, -0.5f, -0.5f));
        m.vertices.push_back(Vec3(x, 0.5f, -0.5f));
        m.vertices.push_back(Vec3(x, 0.0f, 0.5f));
        m.triangles.push_back({v, v + 1, v + 2});
        m.tri_material.push_back(0);
    }
    Bvh bvh;
    auto tri_box = [&](int k) {
        Box b;
        for (int j = 0; j < 3; ++j) b.grow(m.vertices[m.triangles[k][j]]);
        b.lo -= Vec3(1e-6f);
        b.hi += Vec3(1e-6f);
        return b;
    };
    bvh.nodes.push_back(BvhNode{});  // root, filled below
    for (int k = 0; k < n; ++k) bvh.tri_order.push_back(static_cast<std::uint32_t>(k));
    // Node layout: 0 root; pair (2k+1, 2k+2) = (leaf k, chain rest).
    for (int k = 0; k + 1 < n; ++k) {
        bvh.nodes.push_back(BvhNode{tri_box(k), k, 1});
        bvh.nodes.push_back(BvhNode{});
    }
    bvh.nodes.back() = BvhNode{tri_box(n - 1), n - 1, 1};
    for (int k = n - 2; k >= 0; --k) {
        const std::size_t self = k == 0 ? 0 : static_cast<std::size_t>(2 * k);
        Box b = bvh.nodes[static_cast<std::size_t>(2 * k + 1)].box;
        b.grow(bvh.nodes[static_cast<std::size_t>(2 * k + 2)].box);
        bvh.nodes[self] = BvhNode{b, 2 * k + 1, 0};
    }
    ASSERT_GT(bvh.depth(), kMaxStack);
    Accel accel(m, bvh);
    accel.quantize(FixedFormat{});
    const auto tracer = make_tracer(accel, BoxTestKind::Smits, ChildOrder::Dsa);
    RayRng rng(5);
    for (int i = 0; i < 200; ++i) {
        // Along -x and +x through all the triangles: the whole chain is on the stack.
        Ray r{Vec3(i % 2 ? 1.2f : -1.2f, rng.uniform(-0.3f, 0.3f), rng.uniform(-0.3f, 0.3f)),
              Vec3(i % 2 ? -1.0f : 1.0f, rng.uniform(-0.01f, 0.01f), rng.uniform(-0.01f, 0.01f)), kInf};
        TraversalStats st;
        ASSERT_TRUE(same_hit(tracer->closest(r, st), brute_force_closest(m, r))) << i;
    }
    SoftwareBoxEngine eng(FixedFormat{});
    TraversalStats st;
    const std::vector<Ray> rays = {Ray{Vec3(1.2f, 0.0f, 0.0f), Vec3(-1.0f, 0.001f, 0.0f), kInf}};
    const auto got = trace_batched(accel, ChildOrder::Fixed, eng, 4, rays, false, st);
    EXPECT_TRUE(same_hit(got[0], brute_force_closest(m, rays[0])));
}

// ---------------------------------------------------------------------------
// Triangle test

TEST(Triangle, HitDistanceAndBarycentrics) {
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    const Ray r{Vec3(0.25f, 0.5f, 2.0f), Vec3(0, 0, -1), kInf};
    float t, b1, b2;
    ASSERT_TRUE(tri_intersect(tri_setup(r), a, b, c, kInf, t, b1, b2));
    EXPECT_FLOAT_EQ(t, 2.0f);
    EXPECT_FLOAT_EQ(b1, 0.25f);
    EXPECT_FLOAT_EQ(b2, 0.5f);
    // Both windings (no culling), segment bound, behind the origin.
    EXPECT_TRUE(tri_intersect(tri_setup(r), a, c, b, kInf, t, b1, b2));
    EXPECT_FALSE(tri_intersect(tri_setup(r), a, b, c, 1.5f, t, b1, b2));
    const Ray away{Vec3(0.25f, 0.5f, 2.0f), Vec3(0, 0, 1), kInf};
    EXPECT_FALSE(tri_intersect(tri_setup(away), a, b, c, kInf, t, b1, b2));
    const Ray outside{Vec3(0.75f, 0.5f, 2.0f), Vec3(0, 0, -1), kInf};
    EXPECT_FALSE(tri_intersect(tri_setup(outside), a, b, c, kInf, t, b1, b2));
}

TEST(Triangle, WatertightOnSharedEdgesAndClosedMeshes) {
    // Rays through points of a closed sphere from inside always hit: no ray
    // slips between triangles, even through shared edges and vertices.
    const Mesh m = make_scene("sphere:2000");
    RayRng rng(7);
    std::size_t misses = 0;
    for (int i = 0; i < 3000; ++i) {
        Ray r;
        r.o = rng.in_cube(0.3f);
        // Every third ray aims exactly at a vertex, every third at an edge midpoint.
        const auto& tri = m.triangles[rng.next() % m.triangles.size()];
        if (i % 3 == 0)
            r.d = m.vertices[tri[0]] - r.o;
        else if (i % 3 == 1)
            r.d = 0.5f * (m.vertices[tri[0]] + m.vertices[tri[1]]) - r.o;
        else
            r.d = rng.direction();
        misses += !brute_force_closest(m, r).found();
    }
    EXPECT_EQ(misses, 0u);
}

// ---------------------------------------------------------------------------
// Batched traversal

// Checks that every query carries the quantised forms of its float query,
// then answers like the software engine. Records batch sizes.
class CheckingEngine final : public BoxEngine {
public:
    explicit CheckingEngine(const FixedFormat& f) : f_(f), sw_(f) {}
    void test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) override {
        ++batches;
        max_batch = std::max(max_batch, batch.size());
        for (const BoxQuery& q : batch) {
            const std::optional<FixedRay> fr = fixed_setup_ray(q.query.ray, f_);
            const FixedBox fb = fixed_quantize_box(q.query.box, f_);
            if (!fr) {
                ++culled;  // a query of a ray that never meets the range cube
                continue;
            }
            clipped += fr->clipped;
            if (fr->cls != q.ray.cls || fr->org != q.ray.org || fr->dir != q.ray.dir ||
                fr->has_end != q.ray.has_end || fr->end != q.ray.end || fb.lo != q.box.lo || fb.hi != q.box.hi)
                ++mismatches;
        }
        sw_.test(batch, hits);
    }
    std::size_t batches = 0, max_batch = 0, mismatches = 0, culled = 0, clipped = 0;

private:
    FixedFormat f_;
    SoftwareBoxEngine sw_;
};

TEST(Batched, SameHitsAndCountsAsDirectTraversalForEveryPool) {
    const Mesh m = make_scene("spheres");
    BuildOptions bo;
    const Bvh bvh = build_bvh(m, bo);
    for (const FixedMode mode : {FixedMode::Conservative, FixedMode::Nearest}) {
        FixedFormat f;
        f.coord_bits = 12;
        f.dir_bits = 10;
        f.mode = mode;
        Accel accel(m, bvh);
        accel.quantize(f);
        std::vector<Ray> rays = make_rays(m, 1500, 24, 99);
        // Rays that miss the range cube and rays from far outside.
        rays.push_back(Ray{Vec3(5.0f, 5.0f, 5.0f), Vec3(1.0f, 0.0f, 0.0f), kInf});
        rays.push_back(Ray{Vec3(-9.0f, 0.1f, 0.2f), Vec3(1.0f, 0.0f, 0.0f), kInf});
        for (const ChildOrder order : {ChildOrder::Fixed, ChildOrder::Dsa}) {
            const auto tracer = make_tracer(accel, BoxTestKind::Fixed, order);
            for (const bool any : {false, true}) {
                TraversalStats direct_st;
                std::vector<Hit> direct;
                for (const Ray& r : rays)
                    direct.push_back(any ? (tracer->occluded(r, direct_st) ? Hit{0, 0, 0, 0} : Hit{})
                                         : tracer->closest(r, direct_st));
                for (const std::size_t pool : {std::size_t{1}, std::size_t{7}, std::size_t{256}}) {
                    CheckingEngine eng(f);
                    TraversalStats st;
                    const std::vector<Hit> got = trace_batched(accel, order, eng, pool, rays, any, st);
                    ASSERT_EQ(got.size(), rays.size());
                    std::size_t bad = 0;
                    for (std::size_t i = 0; i < rays.size(); ++i)
                        bad += any ? got[i].found() != direct[i].found() : !same_hit(got[i], direct[i]);
                    EXPECT_EQ(bad, 0u) << "pool " << pool << " order " << order_name(order);
                    EXPECT_EQ(st, direct_st) << "pool " << pool;
                    EXPECT_EQ(eng.mismatches, 0u);
                    EXPECT_EQ(eng.culled, 0u);
                    EXPECT_GT(eng.clipped, 0u);  // the far rays reach the engine clipped
                    EXPECT_LE(eng.max_batch, 2 * pool);
                    if (pool == 256) {
                        EXPECT_GT(eng.max_batch, 256u);  // rays really are in flight together
                    }
                }
            }
        }
    }
}

TEST(Batched, ResumableStateMachine) {
    const Mesh m = make_scene("teapot");
    const Bvh bvh = build_bvh(m, BuildOptions{});
    Accel accel(m, bvh);
    accel.quantize(FixedFormat{});
    RayTraversal rt(accel, ChildOrder::Dsa);
    const Camera cam = default_camera(m);
    rt.start(Ray{cam.eye, glm::normalize(cam.look - cam.eye), kInf}, false);
    ASSERT_FALSE(rt.done());
    ASSERT_EQ(rt.pending().size(), 1u);  // the root
    EXPECT_EQ(rt.pending()[0].node, 0u);
    SoftwareBoxEngine sw(FixedFormat{});
    std::size_t steps = 0;
    while (!rt.done()) {
        const auto q = rt.pending();
        std::vector<BoxQuery> copy(q.begin(), q.end());
        if (steps > 0) {
            ASSERT_EQ(copy.size(), 2u);
            EXPECT_EQ(copy[1].node, copy[0].node + 1);  // siblings
        }
        std::vector<std::uint8_t> hits(copy.size());
        sw.test(copy, hits);
        rt.resume(hits);
        ++steps;
    }
    EXPECT_TRUE(rt.hit().found());  // the view centre is on the teapot
    EXPECT_EQ(rt.stats().box_tests, 1 + 2 * (steps - 1));
    // A ray that misses the range cube is done at once.
    rt.start(Ray{Vec3(9.0f), Vec3(1.0f, 0.0f, 0.0f), kInf}, false);
    EXPECT_TRUE(rt.done());
    EXPECT_FALSE(rt.hit().found());
    EXPECT_THROW(RayTraversal(accel, ChildOrder::Dist), InputError);
}

TEST(Recording, OneQueryPerBoxTest) {
    const Mesh m = make_scene("teapot");
    const Bvh bvh = build_bvh(m, BuildOptions{});
    Accel accel(m, bvh);
    accel.quantize(FixedFormat{});
    const std::vector<Ray> rays = make_rays(m, 200, 8, 3);
    for (const BoxTestKind t : {BoxTestKind::Smits, BoxTestKind::Pluecker, BoxTestKind::Fixed}) {
        std::vector<Query> rec;
        const auto tracer = make_tracer(accel, t, ChildOrder::Fixed, &rec);
        TraversalStats st;
        for (const Ray& r : rays) tracer->closest(r, st);
        EXPECT_EQ(rec.size(), st.box_tests) << test_name(t);
        if (t == BoxTestKind::Fixed) {
            for (const Query& q : rec) ASSERT_TRUE(fixed_setup_ray(q.ray, FixedFormat{}).has_value());
        }
    }
}

}  // namespace
}  // namespace pluecker
