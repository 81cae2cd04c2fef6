// SPDX-License-Identifier: MIT
// BVH construction: structure, boxes, epsilon, child order and degenerate
// inputs, for both build methods, on seeded random meshes and built-in scenes.
#include "pluecker/app/names.hpp"  // parse_* (the applications' name parsing)
#include "pluecker/bvh.hpp"
#include "pluecker/mesh.hpp"

#include <gtest/gtest.h>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

namespace pluecker {
namespace {

using Tri = std::array<std::uint32_t, 3>;

struct Soup {
    std::vector<Vec3> v;
    std::vector<Tri> t;
};

// n small random triangles (size up to `size`) in [-1,1]^3.
Soup random_soup(std::uint32_t seed, std::size_t n, float size) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1.0f, 1.0f);
    std::uniform_real_distribution<float> off(-size, size);
    Soup s;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 c(pos(rng), pos(rng), pos(rng));
        const auto base = static_cast<std::uint32_t>(s.v.size());
        for (int k = 0; k < 3; ++k)
            s.v.push_back(glm::clamp(c + Vec3(off(rng), off(rng), off(rng)), -1.0f, 1.0f));
        s.t.push_back({base, base + 1, base + 2});
    }
    return s;
}

// Triangles over random shared vertices (long, overlapping triangles).
Soup random_indexed(std::uint32_t seed, std::size_t nv, std::size_t nt) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1.0f, 1.0f);
    std::uniform_int_distribution<std::uint32_t> idx(0, static_cast<std::uint32_t>(nv - 1));
    Soup s;
    for (std::size_t i = 0; i < nv; ++i) s.v.emplace_back(pos(rng), pos(rng), pos(rng));
    for (std::size_t i = 0; i < nt; ++i) s.t.push_back({idx(rng), idx(rng), idx(rng)});
    return s;
}

// Tight float bounds of one triangle, as a plain min/max of its vertices.
Box tri_box(const Soup& s, std::uint32_t id) {
    Box b;
    for (std::uint32_t k : s.t[id]) b.grow(s.v[k]);
    return b;
}

float centroid2(const Box& b, int axis) { return b.lo[axis] + b.hi[axis]; }

bool contains(const Box& outer, const Box& inner) {
    for (int a = 0; a < 3; ++a)
        if (!(outer.lo[a] <= inner.lo[a] && inner.hi[a] <= outer.hi[a])) return false;
    return true;
}

bool same_box(const Box& a, const Box& b) { return a.lo == b.lo && a.hi == b.hi; }

// Every property the builder promises: a full binary tree reaching every
// node once, every triangle in exactly one leaf, every box exactly the tight
// bounds of its triangles grown by epsilon, child 0 on the lower side.
void check_bvh(const Bvh& bvh, const Soup& s, const BuildOptions& opt) {
    ASSERT_FALSE(bvh.nodes.empty());
    ASSERT_EQ(bvh.tri_order.size(), s.t.size());
    const std::size_t nn = bvh.nodes.size();
    EXPECT_LE(nn, 2 * s.t.size() - 1);

    // Every triangle id exactly once in tri_order.
    std::vector<int> seen(s.t.size(), 0);
    for (std::uint32_t id : bvh.tri_order) {
        ASSERT_LT(id, s.t.size());
        ++seen[id];
    }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));

    // Walk the tree: each node reached once, each tri_order slot in exactly
    // one leaf, boxes = tight bounds grown by epsilon, children inside.
    std::vector<int> reached(nn, 0);
    std::vector<int> covered(s.t.size(), 0);
    std::vector<Box> tight(nn);  // tight bounds of the triangles below each node
    std::vector<Box> cent(nn);   // doubled-centroid bounds below each node
    std::vector<int> order;      // nodes, parents before children
    order.push_back(0);
    reached[0] = 1;
    for (std::size_t q = 0; q < order.size(); ++q) {
        const BvhNode& node = bvh.nodes[static_cast<std::size_t>(order[q])];
        if (node.is_leaf()) {
            ASSERT_GE(node.first, 0);
            ASSERT_LE(static_cast<std::size_t>(node.first) + static_cast<std::size_t>(node.count),
                      s.t.size());
            const int cap = opt.method == BuildMethod::Median ? opt.max_leaf_size : opt.sah_max_leaf_size;
            EXPECT_LE(node.count, cap);
        } else {
            ASSERT_GE(node.axis(), 0);
            ASSERT_LE(node.axis(), 2);
            ASSERT_GT(node.first, order[q]);
            ASSERT_LT(static_cast<std::size_t>(node.first) + 1, nn);
            for (int c = 0; c < 2; ++c) {
                const auto ci = static_cast<std::size_t>(node.first + c);
                ASSERT_EQ(reached[ci], 0) << "node " << ci << " has two parents";
                reached[ci] = 1;
                order.push_back(static_cast<int>(ci));
            }
        }
    }
    EXPECT_TRUE(std::all_of(reached.begin(), reached.end(), [](int r) { return r == 1; }))
        << "unreachable nodes";

    const Vec3 eps(opt.epsilon);
    for (std::size_t q = order.size(); q-- > 0;) {  // children before parents
        const auto i = static_cast<std::size_t>(order[q]);
        const BvhNode& node = bvh.nodes[i];
        if (node.is_leaf()) {
            for (int k = 0; k < node.count; ++k) {
                const auto slot = static_cast<std::size_t>(node.first + k);
                ++covered[slot];
                const std::uint32_t id = bvh.tri_order[slot];
                const Box b = tri_box(s, id);
                tight[i].grow(b);
                cent[i].grow(Vec3(centroid2(b, 0), centroid2(b, 1), centroid2(b, 2)));
                for (std::uint32_t vi : s.t[id]) {
                    const Box pt{s.v[vi], s.v[vi]};
                    ASSERT_TRUE(contains(node.box, pt)) << "leaf " << i << " misses a vertex";
                }
            }
        } else {
            const auto c0 = static_cast<std::size_t>(node.first);
            ASSERT_TRUE(contains(node.box, bvh.nodes[c0].box)) << "node " << i;
            ASSERT_TRUE(contains(node.box, bvh.nodes[c0 + 1].box)) << "node " << i;
            tight[i] = tight[c0];
            tight[i].grow(tight[c0 + 1]);
            cent[i] = cent[c0];
            cent[i].grow(cent[c0 + 1]);
            // Child 0 holds the lower side of the split axis.
            const int a = node.axis();
            EXPECT_LE(cent[c0].hi[a], cent[c0 + 1].lo[a]) << "child order at node " << i;
        }
        // Box = tight bounds grown by epsilon, with the builder's float ops.
        const Box want{tight[i].lo - eps, tight[i].hi + eps};
        ASSERT_TRUE(same_box(node.box, want)) << "node " << i << " box is not tight + epsilon";
    }
    EXPECT_TRUE(std::all_of(covered.begin(), covered.end(), [](int c) { return c == 1; }))
        << "tri_order slots not covered by exactly one leaf";

    std::size_t leaves = 0;
    for (const BvhNode& n : bvh.nodes) leaves += n.is_leaf() ? 1 : 0;
    EXPECT_EQ(bvh.leaf_count(), leaves);
    EXPECT_EQ(nn, 2 * leaves - 1);
    EXPECT_GE(bvh.depth(), 1);
    EXPECT_GE(bvh.build_ms, 0.0);
}

Soup from_mesh(const Mesh& m) { return Soup{m.vertices, m.triangles}; }

Bvh build(const Soup& s, const BuildOptions& opt) {
    return build_bvh(std::span<const Vec3>(s.v), std::span<const Tri>(s.t), opt);
}

BuildOptions with(BuildMethod m) {
    BuildOptions o;
    o.method = m;
    return o;
}

// SAH cost of a tree relative to the root (cost_traverse = cost_intersect = 1).
double sah_cost(const Bvh& bvh) {
    const double root = bvh.nodes[0].box.half_area();
    double c = 0;
    for (const BvhNode& n : bvh.nodes) c += n.box.half_area() / root * (n.is_leaf() ? n.count : 1);
    return c;
}

class BvhMethods : public ::testing::TestWithParam<BuildMethod> {};

TEST(Bvh, NodeIs32Bytes) {
    EXPECT_EQ(sizeof(BvhNode), 32u);
    const BvhNode leaf{Box{}, 3, 2};
    EXPECT_TRUE(leaf.is_leaf());
    const BvhNode inner{Box{}, 1, -2};
    EXPECT_FALSE(inner.is_leaf());
    EXPECT_EQ(inner.axis(), 2);
    const BvhNode inner_x{Box{}, 1, 0};
    EXPECT_FALSE(inner_x.is_leaf());
    EXPECT_EQ(inner_x.axis(), 0);
}

TEST_P(BvhMethods, RandomSoups) {
    for (std::uint32_t seed = 1; seed <= 8; ++seed) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        const std::size_t n = 1 + (seed * 977u) % 3000;
        const Soup s = random_soup(seed, n, 0.05f);
        check_bvh(build(s, with(GetParam())), s, with(GetParam()));
    }
}

TEST_P(BvhMethods, RandomSharedVertices) {
    for (std::uint32_t seed = 11; seed <= 14; ++seed) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        const Soup s = random_indexed(seed, 200, 1500);
        check_bvh(build(s, with(GetParam())), s, with(GetParam()));
    }
}

TEST_P(BvhMethods, OptionVariants) {
    const Soup s = random_soup(21, 2000, 0.1f);
    for (int leaf : {1, 2, 7}) {
        for (int bins : {2, 3, 16, 32, 64}) {
            SCOPED_TRACE("leaf " + std::to_string(leaf) + " bins " + std::to_string(bins));
            BuildOptions o = with(GetParam());
            o.max_leaf_size = leaf;
            o.sah_max_leaf_size = leaf;
            o.bins = bins;
            o.epsilon = bins == 3 ? 0.0f : 1e-3f;
            check_bvh(build(s, o), s, o);
        }
    }
    BuildOptions o = with(GetParam());
    o.cost_traverse = 0.0f;  // always split when it helps at all
    check_bvh(build(s, o), s, o);
    o.cost_traverse = 8.0f;  // large leaves
    check_bvh(build(s, o), s, o);
}

TEST_P(BvhMethods, OneTriangle) {
    const Soup s{{Vec3(0.1f, 0.2f, 0.3f), Vec3(0.5f, -0.2f, 0.0f), Vec3(-0.4f, 0.9f, 0.3f)}, {{0, 1, 2}}};
    const Bvh bvh = build(s, with(GetParam()));
    check_bvh(bvh, s, with(GetParam()));
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_EQ(bvh.nodes[0].count, 1);
    EXPECT_EQ(bvh.depth(), 1);
    EXPECT_EQ(bvh.nodes[0].box.lo, Vec3(-0.4f, -0.2f, 0.0f) - Vec3(1e-6f));
}

TEST_P(BvhMethods, IdenticalTriangles) {
    for (std::size_t n : {2u, 17u, 1000u}) {
        SCOPED_TRACE("n " + std::to_string(n));
        Soup s{{Vec3(0.1f, 0.2f, 0.3f), Vec3(0.5f, -0.2f, 0.0f), Vec3(-0.4f, 0.9f, 0.3f)}, {}};
        for (std::size_t i = 0; i < n; ++i) s.t.push_back({0, 1, 2});
        const Bvh bvh = build(s, with(GetParam()));
        check_bvh(bvh, s, with(GetParam()));
        EXPECT_LE(bvh.depth(), 16);  // halving, not peeling one at a time
    }
}

TEST_P(BvhMethods, PointTriangles) {
    // Zero-area, zero-extent triangles at a few points: node areas are 0.
    Soup s{{Vec3(0.0f), Vec3(0.25f, 0.0f, 0.0f), Vec3(-0.5f, 0.5f, 0.5f)}, {}};
    for (std::uint32_t i = 0; i < 300; ++i) s.t.push_back({i % 3, i % 3, i % 3});
    check_bvh(build(s, with(GetParam())), s, with(GetParam()));
}

TEST_P(BvhMethods, CollinearCentroids) {
    // Real triangles whose centroids all lie on the x axis; and segments
    // (degenerate triangles) along one line.
    Soup s;
    for (std::uint32_t i = 0; i < 500; ++i) {
        const float x = -1.0f + 2.0f * static_cast<float>(i) / 500.0f;
        const auto b = static_cast<std::uint32_t>(s.v.size());
        s.v.push_back(Vec3(x, -0.01f, -0.01f));
        s.v.push_back(Vec3(x, 0.02f, -0.01f));
        s.v.push_back(Vec3(x, -0.01f, 0.02f));
        s.t.push_back({b, b + 1, b + 2});
        s.v.push_back(Vec3(x, 0.0f, 0.0f));
        s.v.push_back(Vec3(x + 0.001f, 0.0f, 0.0f));
        s.t.push_back({b + 3, b + 4, b + 4});
    }
    const Bvh bvh = build(s, with(GetParam()));
    check_bvh(bvh, s, with(GetParam()));
    EXPECT_LE(bvh.depth(), 64);
}

TEST_P(BvhMethods, LargeFan) {
    // A disc of 20,000 triangles around one centre vertex: the midpoint split
    // peels a quarter fan one triangle per level until the depth cap.
    Soup s{{Vec3(0.0f)}, {}};
    const std::uint32_t n = 20000;
    for (std::uint32_t i = 0; i < n; ++i) {
        const float a = 6.2831853f * static_cast<float>(i) / static_cast<float>(n);
        s.v.emplace_back(std::cos(a), std::sin(a), 0.0f);
        s.t.push_back({0, 1 + i, 1 + (i + 1) % n});
    }
    const Bvh bvh = build(s, with(GetParam()));
    check_bvh(bvh, s, with(GetParam()));
    EXPECT_LE(bvh.depth(), 256 + 2 * 15 + 15 + 1);  // cap, then halving
}

TEST_P(BvhMethods, FlatMesh) {
    // A planar grid (z = 0): every box is flat, half areas stay positive.
    Soup s;
    const int g = 40;
    for (int y = 0; y <= g; ++y)
        for (int x = 0; x <= g; ++x)
            s.v.emplace_back(-1.0f + 2.0f * x / g, -1.0f + 2.0f * y / g, 0.0f);
    for (std::uint32_t y = 0; y < g; ++y)
        for (std::uint32_t x = 0; x < g; ++x) {
            const std::uint32_t a = y * (g + 1) + x;
            s.t.push_back({a, a + 1, a + g + 1});
            s.t.push_back({a + 1, a + g + 2, a + g + 1});
        }
    check_bvh(build(s, with(GetParam())), s, with(GetParam()));
}

TEST_P(BvhMethods, BuiltInScenes) {
    for (const char* spec : {"teapot", "spheres", "sphere:20000"}) {
        SCOPED_TRACE(spec);
        const Mesh m = make_scene(spec);
        const Bvh bvh = build_bvh(m, with(GetParam()));
        check_bvh(bvh, from_mesh(m), with(GetParam()));
    }
}

TEST_P(BvhMethods, Deterministic) {
    const Soup s = random_soup(5, 5000, 0.05f);
    const Bvh a = build(s, with(GetParam()));
    const Bvh b = build(s, with(GetParam()));
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    EXPECT_EQ(a.tri_order, b.tri_order);
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
        EXPECT_TRUE(same_box(a.nodes[i].box, b.nodes[i].box));
        EXPECT_EQ(a.nodes[i].first, b.nodes[i].first);
        EXPECT_EQ(a.nodes[i].count, b.nodes[i].count);
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, BvhMethods, ::testing::Values(BuildMethod::Median, BuildMethod::Sah),
                         [](const auto& info) { return std::string(method_name(info.param)); });

TEST(Bvh, MedianSplitsRoundRobin) {
    // A uniform grid of tiny triangles: the midpoint split always works, so
    // the axes go x, y, z, x, ... by depth.
    Soup s;
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) {
                const Vec3 c(-0.875f + 0.25f * x, -0.875f + 0.25f * y, -0.875f + 0.25f * z);
                const auto b = static_cast<std::uint32_t>(s.v.size());
                s.v.push_back(c);
                s.v.push_back(c + Vec3(0.01f, 0.0f, 0.0f));
                s.v.push_back(c + Vec3(0.0f, 0.01f, 0.0f));
                s.t.push_back({b, b + 1, b + 2});
            }
    BuildOptions o = with(BuildMethod::Median);
    o.max_leaf_size = 1;
    const Bvh bvh = build(s, o);
    check_bvh(bvh, s, o);
    EXPECT_EQ(bvh.depth(), 10);  // 512 triangles, one per leaf, balanced
    std::vector<std::pair<int, int>> todo{{0, 0}};
    while (!todo.empty()) {
        const auto [i, d] = todo.back();
        todo.pop_back();
        const BvhNode& n = bvh.nodes[static_cast<std::size_t>(i)];
        if (n.is_leaf()) continue;
        EXPECT_EQ(n.axis(), d % 3) << "node " << i << " depth " << d;
        todo.emplace_back(n.first, d + 1);
        todo.emplace_back(n.first + 1, d + 1);
    }
}

#if defined(__SSE__)
TEST(Bvh, DenormalsAreZeroMode) {
    // The SAH bins count in a float lane; a DAZ/FTZ FPU mode set by some
    // other library must not change the tree.
    const Soup s = random_soup(9, 3000, 0.05f);
    const Bvh ref = build(s, with(BuildMethod::Sah));
    const unsigned csr = _mm_getcsr();
    _mm_setcsr(csr | 0x8040u);  // DAZ | FTZ
    const Bvh daz = build(s, with(BuildMethod::Sah));
    _mm_setcsr(csr);
    check_bvh(daz, s, with(BuildMethod::Sah));
    EXPECT_EQ(daz.tri_order, ref.tri_order);
    EXPECT_EQ(daz.nodes.size(), ref.nodes.size());
}
#endif

TEST(Bvh, SahBeatsMedianOnSphere) {
    const Mesh m = make_scene("sphere:20000");
    const Bvh sah = build_bvh(m, with(BuildMethod::Sah));
    const Bvh med = build_bvh(m, with(BuildMethod::Median));
    EXPECT_LT(sah_cost(sah), sah_cost(med));
}

TEST(Bvh, SahLeafCostModel) {
    // Two far-apart triangles: splitting pays, so the root is interior.
    Soup s{{Vec3(-1.0f), Vec3(-0.9f, -1.0f, -1.0f), Vec3(-1.0f, -0.9f, -1.0f), Vec3(1.0f),
            Vec3(0.9f, 1.0f, 1.0f), Vec3(1.0f, 0.9f, 1.0f)},
           {{0, 1, 2}, {3, 4, 5}}};
    Bvh bvh = build(s, with(BuildMethod::Sah));
    EXPECT_FALSE(bvh.nodes[0].is_leaf());
    // Two overlapping copies: a split cannot shrink anything, so one leaf.
    s.t[1] = s.t[0];
    bvh = build(s, with(BuildMethod::Sah));
    EXPECT_TRUE(bvh.nodes[0].is_leaf());
    // A very expensive traversal makes a leaf of anything up to the cap.
    const Soup r = random_soup(3, 16, 0.05f);
    BuildOptions o = with(BuildMethod::Sah);
    o.cost_traverse = 1000.0f;
    bvh = build(r, o);
    EXPECT_EQ(bvh.nodes.size(), 1u);
    o.sah_max_leaf_size = 4;
    bvh = build(r, o);
    check_bvh(bvh, r, o);
    EXPECT_GT(bvh.nodes.size(), 1u);
}

TEST(Bvh, BadInput) {
    const Soup s = random_soup(1, 4, 0.1f);
    const std::vector<Tri> none;
    EXPECT_THROW(build_bvh(std::span<const Vec3>(s.v), std::span<const Tri>(none), BuildOptions{}),
                 InputError);

    Soup bad = s;
    bad.t[3][1] = 99;
    try {
        build(bad, BuildOptions{});
        FAIL() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("triangle 3"), std::string::npos) << e.what();
    }

    bad = s;
    bad.v[5].y = std::numeric_limits<float>::quiet_NaN();
    try {
        build(bad, BuildOptions{});
        FAIL() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
    }
    bad.v[5].y = kInf;
    EXPECT_THROW(build(bad, BuildOptions{}), InputError);

    // Huge but finite coordinates are fine (the finite check must not
    // trip on an overflowing sum).
    bad = s;
    bad.v[0] = Vec3(3e38f);
    bad.v[1] = Vec3(3e38f);
    bad.v[2] = Vec3(3e38f);
    EXPECT_NO_THROW(build(bad, BuildOptions{}));

    auto expect_field = [&](BuildOptions o, const char* field) {
        try {
            build(s, o);
            FAIL() << "no InputError for " << field;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
        }
    };
    BuildOptions o;
    o.bins = 1;
    expect_field(o, "bins");
    o = {};
    o.bins = 65;
    expect_field(o, "bins");
    o = {};
    o.max_leaf_size = 0;
    expect_field(o, "max_leaf_size");
    o = {};
    o.sah_max_leaf_size = 0;
    expect_field(o, "sah_max_leaf_size");
    o = {};
    o.epsilon = -1e-6f;
    expect_field(o, "epsilon");
    o = {};
    o.cost_intersect = 0.0f;
    expect_field(o, "cost_intersect");
    o = {};
    o.cost_traverse = std::numeric_limits<float>::quiet_NaN();
    expect_field(o, "cost_traverse");
}

TEST(Bvh, ParseBuildMethod) {
    EXPECT_EQ(parse_build_method("median"), BuildMethod::Median);
    EXPECT_EQ(parse_build_method("sah"), BuildMethod::Sah);
    EXPECT_STREQ(method_name(BuildMethod::Median), "median");
    EXPECT_STREQ(method_name(BuildMethod::Sah), "sah");
    EXPECT_THROW(parse_build_method("SAH "), InputError);
    EXPECT_THROW(parse_build_method(""), InputError);
}

}  // namespace
}  // namespace pluecker
