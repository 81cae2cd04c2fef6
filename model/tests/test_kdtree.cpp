// SPDX-License-Identifier: MIT
// The K-D tree: closest and any hit equal brute force on camera, random,
// axis-parallel and surface rays (both builds, three scenes); every
// triangle that overlaps a leaf's cell (exact rational test) is in the
// leaf's list and every listed triangle overlaps the cell (within 1e-8); the build's
// overlap test is conservative; the renderer gives the BVH's image through
// a K-D tracer; bad input is refused.
#include "pluecker/bvh.hpp"
#include "pluecker/image.hpp"
#include "pluecker/kdtree.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/render.hpp"
#include "pluecker/traverse.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace pluecker {
namespace {

// ---------------------------------------------------------------------------
// Separating axis test over any number type, the box as centre c and half
// extents h (touching counts as overlap).

template <class T>
bool sat_overlap(const std::array<std::array<T, 3>, 3>& tri, const std::array<T, 3>& c, const std::array<T, 3>& h) {
    std::array<std::array<T, 3>, 3> v;
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) v[i][k] = tri[i][k] - c[k];
    auto sep = [](const T& p0, const T& p1, const T& p2, const T& r) {
        const T lo = std::min(p0, std::min(p1, p2)), hi = std::max(p0, std::max(p1, p2));
        return lo > r || hi < T(-r);
    };
    auto absv = [](const T& x) { return x < T(0) ? T(-x) : x; };
    for (int k = 0; k < 3; ++k)
        if (sep(v[0][k], v[1][k], v[2][k], h[k])) return false;
    std::array<std::array<T, 3>, 3> f;
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) f[i][k] = v[(i + 1) % 3][k] - v[i][k];
    for (const auto& e : f) {
        for (int k = 0; k < 3; ++k) {
            // axis = unit(k) x e: components on k1 = -e[k2], on k2 = e[k1]
            const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
            auto p = [&](const std::array<T, 3>& x) { return T(-e[k2] * x[k1] + e[k1] * x[k2]); };
            const T r = h[k1] * absv(e[k2]) + h[k2] * absv(e[k1]);
            if (sep(p(v[0]), p(v[1]), p(v[2]), r)) return false;
        }
    }
    std::array<T, 3> n;
    for (int k = 0; k < 3; ++k) {
        const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        n[k] = f[0][k1] * f[1][k2] - f[0][k2] * f[1][k1];
    }
    const T d = n[0] * v[0][0] + n[1] * v[0][1] + n[2] * v[0][2];
    const T r = h[0] * absv(n[0]) + h[1] * absv(n[1]) + h[2] * absv(n[2]);
    return !(absv(d) > r);
}

// Exact: rationals, the box grown by `grow` on every side (0: the box itself).
bool exact_overlap(const Vec3& a, const Vec3& b, const Vec3& c, const Box& box, double grow = 0.0) {
    std::array<std::array<mpq_class, 3>, 3> tri;
    const Vec3* vs[3] = {&a, &b, &c};
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) tri[i][k] = mpq_class((*vs[i])[k]);
    std::array<mpq_class, 3> cen, h;
    for (int k = 0; k < 3; ++k) {
        cen[k] = (mpq_class(box.lo[k]) + mpq_class(box.hi[k])) / 2;
        h[k] = (mpq_class(box.hi[k]) - mpq_class(box.lo[k])) / 2 + mpq_class(grow);
    }
    return sat_overlap(tri, cen, h);
}

// Double with the box grown by `grow` (negative: shrunk); for |grow| far
// above double rounding the answer is certain.
bool double_overlap(const Vec3& a, const Vec3& b, const Vec3& c, const Box& box, double grow) {
    std::array<std::array<double, 3>, 3> tri;
    const Vec3* vs[3] = {&a, &b, &c};
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) tri[i][k] = (*vs[i])[k];
    std::array<double, 3> cen, h;
    for (int k = 0; k < 3; ++k) {
        cen[k] = 0.5 * (double(box.lo[k]) + double(box.hi[k]));
        h[k] = 0.5 * (double(box.hi[k]) - double(box.lo[k])) + grow;
        if (h[k] < 0.0) return false;
    }
    return sat_overlap(tri, cen, h);
}

// Exact answer, through certain double answers where they exist.
bool overlap_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Box& box) {
    if (double_overlap(a, b, c, box, -1e-9)) return true;
    if (!double_overlap(a, b, c, box, 1e-9)) return false;
    return exact_overlap(a, b, c, box);
}

bool boxes_touch(const Box& a, const Box& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
           b.lo.z <= a.hi.z;
}

Box tri_bounds(const Mesh& m, std::uint32_t id) {
    Box b;
    for (int k = 0; k < 3; ++k) b.grow(m.vertices[m.triangles[id][static_cast<std::size_t>(k)]]);
    return b;
}

KdBuildOptions kd_opts(BuildMethod m) {
    KdBuildOptions o;
    o.method = m;
    return o;
}

// ---------------------------------------------------------------------------
// Rays

std::vector<Ray> test_rays(const Mesh& m, std::uint32_t seed, int n) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), u01(0.0f, 1.0f);
    std::vector<Ray> rays;
    auto dir = [&] {
        Vec3 d;
        do d = Vec3(u(rng), u(rng), u(rng));
        while (glm::length(d) < 0.1f || glm::length(d) > 1.0f);
        return d;
    };
    // Camera rays of the default view.
    const Camera c = default_camera(m);
    const Vec3 w = glm::normalize(c.eye - c.look), uu = glm::normalize(glm::cross(c.up, w)), vv = glm::cross(w, uu);
    const float th = std::tan(glm::radians(c.fov_deg) * 0.5f);
    for (int i = 0; i < n; ++i)
        rays.push_back(Ray{c.eye, glm::normalize(u(rng) * th * uu + u(rng) * th * vv - w), kInf});
    // Random rays, origins in and around the cube, unnormalised directions.
    for (int i = 0; i < n; ++i) rays.push_back(Ray{1.3f * Vec3(u(rng), u(rng), u(rng)), dir(), kInf});
    // Axis-parallel and in-plane directions (zero components).
    for (int i = 0; i < n / 4; ++i) {
        Vec3 d = dir();
        d[static_cast<int>(rng() % 3)] = 0.0f;
        if (rng() % 2) d[static_cast<int>(rng() % 3)] = 0.0f;
        if (d == Vec3(0.0f)) d.x = 1.0f;
        rays.push_back(Ray{1.3f * Vec3(u(rng), u(rng), u(rng)), d, kInf});
    }
    // From surface points (secondary-ray-like), some with a finite tmax, and
    // rays aimed at vertices (edge and vertex hits).
    std::uniform_int_distribution<std::uint32_t> tri(0, static_cast<std::uint32_t>(m.triangles.size() - 1));
    for (int i = 0; i < n / 2; ++i) {
        const auto& t = m.triangles[tri(rng)];
        float b1 = u01(rng), b2 = u01(rng);
        if (b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
        const Vec3 p = (1.0f - b1 - b2) * m.vertices[t[0]] + b1 * m.vertices[t[1]] + b2 * m.vertices[t[2]];
        const Vec3 d = dir();
        rays.push_back(Ray{p + 1e-4f * d, d, i % 3 == 0 ? 0.5f + u01(rng) : kInf});
        const Vec3 target = m.vertices[t[i % 3]];
        const Vec3 o = 1.5f * Vec3(u(rng), u(rng), u(rng));
        if (target != o) rays.push_back(Ray{o, target - o, i % 2 ? 2.0f : kInf});
    }
    return rays;
}

void check_against_brute_force(const std::string& spec, BuildMethod method, int n) {
    SCOPED_TRACE(spec + " " + method_name(method));
    const Mesh m = make_scene(spec);
    const KdTree tree = build_kdtree(m, kd_opts(method));
    const KdAccel a(m, tree);
    TraversalStats st;
    std::size_t hits = 0, checked = 0;
    std::vector<Ray> rays = test_rays(m, 1234u + static_cast<std::uint32_t>(m.triangles.size()), n);
    // Rays lying in split planes (the plane distance is NaN) and rays along
    // them from every side.
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (std::size_t i = 0; i < tree.nodes.size() && i < 200; ++i) {
        const KdNode& node = tree.nodes[i];
        if (node.is_leaf()) continue;
        Vec3 o(u(rng), u(rng), u(rng)), d(u(rng), u(rng), u(rng));
        o[node.axis()] = node.split();
        d[node.axis()] = 0.0f;
        if (d == Vec3(0.0f)) d.x = 1.0f;
        rays.push_back(Ray{o, d, kInf});
        d[node.axis()] = i % 2 ? 0.5f : -0.5f;
        rays.push_back(Ray{o, d, kInf});
    }
    for (const Ray& r : rays) {
        const Hit ref = brute_force_closest(m, r);
        const Hit h = kd_closest(a, r, st);
        ++checked;
        hits += ref.found();
        ASSERT_EQ(h.tri, ref.tri) << "ray " << checked << " o=(" << r.o.x << "," << r.o.y << "," << r.o.z << ") d=("
                                  << r.d.x << "," << r.d.y << "," << r.d.z << ")";
        ASSERT_EQ(std::memcmp(&h.t, &ref.t, sizeof(float)), 0) << h.t << " vs " << ref.t;
        ASSERT_EQ(kd_occluded(a, r, st), brute_force_any(m, r));
    }
    EXPECT_GT(hits, checked / 5);  // the rays do hit
    EXPECT_EQ(st.box_tests, 2 * checked);
    EXPECT_GT(st.node_visits, 0u);
}

TEST(KdTree, ClosestHitEqualsBruteForceTeapot) {
    check_against_brute_force("teapot", BuildMethod::Median, 1000);
    check_against_brute_force("teapot", BuildMethod::Sah, 1000);
}

TEST(KdTree, ClosestHitEqualsBruteForceSpheres) {
    check_against_brute_force("spheres", BuildMethod::Median, 800);
    check_against_brute_force("spheres", BuildMethod::Sah, 800);
}

TEST(KdTree, ClosestHitEqualsBruteForceSphere20000) {
    check_against_brute_force("sphere:20000", BuildMethod::Median, 800);
    check_against_brute_force("sphere:20000", BuildMethod::Sah, 800);
}

// ---------------------------------------------------------------------------
// Leaf lists

void check_leaf_lists(const Mesh& m, BuildMethod method) {
    SCOPED_TRACE(m.name + " " + method_name(method));
    const KdTree tree = build_kdtree(m, kd_opts(method));
    const std::vector<Box> cells = tree.cells();
    ASSERT_EQ(cells.size(), tree.nodes.size());
    std::size_t leaves = 0, refs = 0, overlaps = 0;
    for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
        const KdNode& n = tree.nodes[i];
        if (!n.is_leaf()) {
            // Children follow their parent; the split lies inside the cell.
            ASSERT_GT(n.above(), i + 1);
            ASSERT_LT(n.above(), tree.nodes.size());
            ASSERT_GT(n.split(), cells[i].lo[n.axis()]);
            ASSERT_LT(n.split(), cells[i].hi[n.axis()]);
            continue;
        }
        ++leaves;
        refs += n.count();
        ASSERT_LE(std::size_t{n.first()} + n.count(), tree.refs.size());
        std::vector<std::uint32_t> list(tree.refs.begin() + n.first(), tree.refs.begin() + n.first() + n.count());
        std::sort(list.begin(), list.end());
        ASSERT_TRUE(std::adjacent_find(list.begin(), list.end()) == list.end()) << "duplicate in leaf " << i;
        // Every listed triangle overlaps the cell (grown by far less than a
        // float ulp of its coordinates, for the build's slack).
        for (const std::uint32_t id : list) {
            const auto& t = m.triangles[id];
            ASSERT_TRUE(exact_overlap(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], cells[i], 1e-8))
                << "leaf " << i << " lists triangle " << id << " that does not overlap its cell";
        }
        // Every triangle that overlaps the cell is listed.
        for (std::uint32_t id = 0; id < m.triangles.size(); ++id) {
            if (!boxes_touch(tri_bounds(m, id), cells[i])) continue;
            const auto& t = m.triangles[id];
            if (!overlap_exact(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], cells[i])) continue;
            ++overlaps;
            ASSERT_TRUE(std::binary_search(list.begin(), list.end(), id))
                << "triangle " << id << " overlaps leaf " << i << " but is not in its list";
        }
    }
    EXPECT_EQ(leaves, tree.leaves);
    EXPECT_EQ(refs, tree.refs.size());
    // The lists hold the overlapping triangles and, through the build's
    // slack, a few that pass within 1e-8 of the cell.
    EXPECT_LE(overlaps, refs);
    EXPECT_LE(refs - overlaps, refs / 200);
    EXPECT_GE(refs, m.triangles.size());
    EXPECT_EQ(tree.node_bytes(), 8 * tree.nodes.size());
    EXPECT_EQ(tree.list_bytes(), 4 * tree.refs.size());
}

TEST(KdTree, LeafListsHoldTheOverlappingTrianglesTeapot) {
    const Mesh m = make_scene("teapot");
    check_leaf_lists(m, BuildMethod::Median);
    check_leaf_lists(m, BuildMethod::Sah);
}

TEST(KdTree, LeafListsHoldTheOverlappingTrianglesSphere) {
    const Mesh m = make_scene("sphere:3000");
    check_leaf_lists(m, BuildMethod::Median);
    check_leaf_lists(m, BuildMethod::Sah);
}

TEST(KdTree, LeafListsHoldTheOverlappingTrianglesLongTriangles) {
    // Long, crossing triangles over shared random vertices: many straddle
    // the planes, so the overlap test decides most of the placements.
    std::mt19937 rng(77);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Mesh m;
    m.name = "long";
    m.materials.push_back(Material{});
    for (int i = 0; i < 120; ++i) m.vertices.emplace_back(u(rng), u(rng), u(rng));
    std::uniform_int_distribution<std::uint32_t> vi(0, 119);
    for (int i = 0; i < 160; ++i) m.triangles.push_back({vi(rng), vi(rng), vi(rng)});
    m.tri_material.assign(m.triangles.size(), 0);
    check_leaf_lists(m, BuildMethod::Median);
    check_leaf_lists(m, BuildMethod::Sah);
}

// ---------------------------------------------------------------------------
// The build's overlap test

TEST(KdTree, OverlapTestIsConservativeAndTight) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), s(0.0f, 0.6f);
    int yes = 0, no = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 c(u(rng), u(rng), u(rng));
        const Vec3 h(s(rng), s(rng), s(rng));
        Box box{c - h, c + h};
        if (i % 7 == 0) box.hi.x = box.lo.x;  // flat boxes
        Vec3 v[3];
        for (auto& p : v) p = Vec3(u(rng), u(rng), u(rng)) * (i % 3 == 0 ? 0.3f : 1.0f) + (i % 3 == 0 ? c : Vec3(0.0f));
        if (i % 11 == 0) v[2] = v[0] + 0.5f * (v[1] - v[0]);  // degenerate
        if (i % 13 == 0) v[1].x = v[0].x = v[2].x = box.hi.x;  // in a face's plane
        const bool exact = exact_overlap(v[0], v[1], v[2], box);
        const bool got = tri_box_overlap(v[0], v[1], v[2], box);
        if (exact) {
            ASSERT_TRUE(got) << "case " << i;
        }
        if (got) {
            ASSERT_TRUE(exact_overlap(v[0], v[1], v[2], box, 1e-8)) << "case " << i;
        }
        (exact ? yes : no)++;
    }
    EXPECT_GT(yes, 1000);
    EXPECT_GT(no, 1000);
    // Touching at one corner counts.
    const Box unit{Vec3(0.0f), Vec3(1.0f)};
    EXPECT_TRUE(tri_box_overlap(Vec3(1.0f), Vec3(2.0f, 1.0f, 1.0f), Vec3(1.0f, 2.0f, 3.0f), unit));
    EXPECT_FALSE(tri_box_overlap(Vec3(1.001f, 1.0f, 1.0f), Vec3(2.0f, 1.0f, 1.0f), Vec3(1.001f, 2.0f, 3.0f), unit));
    // Crossing the box's diagonal without a vertex inside.
    EXPECT_TRUE(tri_box_overlap(Vec3(-1.0f, 0.5f, 0.5f), Vec3(2.0f, 0.5f, -1.0f), Vec3(2.0f, 0.5f, 2.0f), unit));
    // Its plane passes beside the corner.
    EXPECT_FALSE(tri_box_overlap(Vec3(2.6f, 0.0f, 0.0f), Vec3(0.0f, 2.6f, 0.0f), Vec3(0.0f, 0.0f, 2.6f), Box{Vec3(-1.0f), Vec3(0.8f)}));
}

// ---------------------------------------------------------------------------
// Structure, render, errors

TEST(KdTree, BuildsAreDeterministicAndBounded) {
    const Mesh m = make_scene("spheres");
    for (const BuildMethod meth : {BuildMethod::Median, BuildMethod::Sah}) {
        const KdTree a = build_kdtree(m, kd_opts(meth)), b = build_kdtree(m, kd_opts(meth));
        ASSERT_EQ(a.nodes.size(), b.nodes.size());
        EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.node_bytes()), 0);
        EXPECT_EQ(a.refs, b.refs);
        const int limit = static_cast<int>(std::lround(8.0 + 1.3 * std::log2(double(m.triangles.size()))));
        EXPECT_LE(a.depth, limit);
        EXPECT_GT(a.depth, 5);
        EXPECT_EQ(a.nodes.size(), 2 * a.leaves - 1);
    }
    KdBuildOptions o = kd_opts(BuildMethod::Sah);
    o.max_depth = 1;
    const KdTree one = build_kdtree(m, o);
    EXPECT_EQ(one.nodes.size(), 1u);
    EXPECT_EQ(one.refs.size(), m.triangles.size());
}

TEST(KdTree, RenderThroughKdTracerMatchesBvh) {
    const Mesh m = make_scene("spheres");  // mirror and glass: every ray kind
    const Bvh bvh = build_bvh(m, BuildOptions{});
    const Accel accel(m, bvh);
    const RenderScene scene(m, accel);
    RenderOptions o;
    o.width = o.height = 48;
    o.threads = 2;
    RenderStats ref_st;
    const Image ref = render_direct(scene, o, ref_st);
    for (const BuildMethod meth : {BuildMethod::Median, BuildMethod::Sah}) {
        const KdTree tree = build_kdtree(m, kd_opts(meth));
        const KdAccel ka(m, tree);
        const auto tracer = make_kd_tracer(ka);
        RenderStats st;
        const Image img = render_direct(scene, o, *tracer, st);
        EXPECT_EQ(img.rgb, ref.rgb);
        EXPECT_EQ(st.rays, ref_st.rays);
        EXPECT_GT(st.traversal.tri_tests, 0u);
    }
}

TEST(KdTree, BadInputIsRefused) {
    const std::vector<Vec3> v{Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f)};
    const std::vector<std::array<std::uint32_t, 3>> none;
    EXPECT_THROW(build_kdtree(v, none, KdBuildOptions{}), InputError);
    const std::vector<std::array<std::uint32_t, 3>> bad{{0, 1, 3}};
    EXPECT_THROW(build_kdtree(v, bad, KdBuildOptions{}), InputError);
    std::vector<Vec3> nan = v;
    nan[1].y = std::nanf("");
    const std::vector<std::array<std::uint32_t, 3>> one{{0, 1, 2}};
    EXPECT_THROW(build_kdtree(nan, one, KdBuildOptions{}), InputError);
    KdBuildOptions o;
    o.bins = 1;
    EXPECT_THROW(build_kdtree(v, one, o), InputError);
    o = KdBuildOptions{};
    o.max_depth = 65;
    EXPECT_THROW(o.validate(), InputError);
    o = KdBuildOptions{};
    o.cost_intersect = 0.0f;
    EXPECT_THROW(o.validate(), InputError);
    // One triangle: a single leaf that the traversal uses.
    const KdTree t = build_kdtree(v, one, KdBuildOptions{});
    EXPECT_EQ(t.nodes.size(), 1u);
    Mesh m;
    m.vertices = v;
    m.triangles = one;
    const KdAccel a(m, t);
    TraversalStats st;
    const Hit h = kd_closest(a, Ray{Vec3(0.2f, 0.2f, 1.0f), Vec3(0.0f, 0.0f, -1.0f), kInf}, st);
    EXPECT_EQ(h.tri, 0u);
    EXPECT_FLOAT_EQ(h.t, 1.0f);
    EXPECT_FALSE(kd_occluded(a, Ray{Vec3(0.2f, 0.2f, 1.0f), Vec3(0.0f, 0.0f, -1.0f), 0.5f}, st));
}

}  // namespace
}  // namespace pluecker
