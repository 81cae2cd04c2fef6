// SPDX-License-Identifier: MIT
// The two-box kernels of the pair layout (traverse.hpp: fast_smits_pair,
// fast_pluecker_pair) against the one-box kernels they mirror, and the
// packed triangle test (triangle.hpp: tri_intersect_packed) against
// tri_intersect: same answers, same bits, on random and extreme queries.
#include "pluecker/querygen.hpp"
#include "pluecker/traverse.hpp"
#include "pluecker/triangle.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <vector>

namespace pluecker {
namespace {

std::uint32_t bits(float f) { return std::bit_cast<std::uint32_t>(f); }

NodePair make_pair(const Box& b0, const Box& b1) {
    NodePair p{};
    const Box* b[2] = {&b0, &b1};
    for (int c = 0; c < 2; ++c)
        for (int a = 0; a < 3; ++a) {
            p.box[a][c] = b[c]->lo[a];
            p.box[a][c + 2] = b[c]->hi[a];
        }
    return p;
}

// Query i's ray against the boxes of queries i and j.
template <RayClass C>
void check_pair_class(const Ray& ray, const Box& b0, const Box& b1, std::size_t i, std::size_t& bad) {
    const NodePair p = make_pair(b0, b1);
    const Box* box[2] = {&b0, &b1};

    const FastSmitsRay s = fast_smits_setup(ray);
    Float4 tn;
    const unsigned hs = fast_smits_pair<C>(smits_pair_setup(s), p, tn);
    for (int c = 0; c < 2; ++c) {
        float t = -1.0f;
        const bool h = fast_smits_hit<C>(s, *box[c], &t);
        if (h != (((hs >> c) & 1u) != 0) || (h && bits(t) != bits(tn[c]))) {
            if (bad++ < 3) ADD_FAILURE() << "smits pair differs on query " << i << " child " << c;
        }
    }

    const FastPlueckerRay q = fast_pluecker_setup(ray);
    const unsigned hp = fast_pluecker_pair<C>(pluecker_pair_setup(q), p);
    for (int c = 0; c < 2; ++c)
        if (fast_pluecker_hit<C>(q, *box[c]) != (((hp >> c) & 1u) != 0)) {
            if (bad++ < 3) ADD_FAILURE() << "pluecker pair differs on query " << i << " child " << c;
        }
}

void check_pair(const Ray& ray, const Box& b0, const Box& b1, std::size_t i, std::size_t& bad) {
    switch (ray_class(ray.d)) {
        case 0: return check_pair_class<0>(ray, b0, b1, i, bad);
        case 1: return check_pair_class<1>(ray, b0, b1, i, bad);
        case 2: return check_pair_class<2>(ray, b0, b1, i, bad);
        case 3: return check_pair_class<3>(ray, b0, b1, i, bad);
        case 4: return check_pair_class<4>(ray, b0, b1, i, bad);
        case 5: return check_pair_class<5>(ray, b0, b1, i, bad);
        case 6: return check_pair_class<6>(ray, b0, b1, i, bad);
        default: return check_pair_class<7>(ray, b0, b1, i, bad);
    }
}

void check_queries(const std::vector<Query>& qs, std::size_t& bad) {
    for (std::size_t i = 0; i < qs.size(); ++i) {
        const Query& q = qs[i];
        const Box& other = qs[(i * 7 + 3) % qs.size()].box;
        check_pair(q.ray, q.box, other, i, bad);  // the query's box as child 0
        check_pair(q.ray, other, q.box, i, bad);  // and as child 1
        // Shorter segments: the end test of pluecker, tmax of smits.
        Ray r = q.ray;
        r.tmax = q.ray.tmax < kInf ? q.ray.tmax * 0.5f : 1.0f;
        check_pair(r, q.box, other, i, bad);
    }
}

TEST(PairKernels, EqualTheOneBoxKernels) {
    std::size_t bad = 0;
    check_queries(random_queries(21, 100000), bad);
    check_queries(extreme_queries(22, 100000), bad);
    EXPECT_EQ(bad, 0u);
}

// tri_intersect_packed with the (KZ, SWAP) of the ray's set-up.
bool packed(const TriRay& r, const LeafTri& t, float tmax, float& th, float& b1, float& b2) {
    const bool swap = r.kx != (r.kz + 1) % 3;
    switch (r.kz * 2 + (swap ? 1 : 0)) {
        case 0: return tri_intersect_packed<0, false>(r, t, tmax, th, b1, b2);
        case 1: return tri_intersect_packed<0, true>(r, t, tmax, th, b1, b2);
        case 2: return tri_intersect_packed<1, false>(r, t, tmax, th, b1, b2);
        case 3: return tri_intersect_packed<1, true>(r, t, tmax, th, b1, b2);
        case 4: return tri_intersect_packed<2, false>(r, t, tmax, th, b1, b2);
        default: return tri_intersect_packed<2, true>(r, t, tmax, th, b1, b2);
    }
}

TEST(PairKernels, PackedTriangleTestEqualsTriIntersect) {
    // Triangles from the corners of query boxes (some degenerate: shared
    // corners), rays of the queries, some aimed at a vertex or an edge.
    const std::vector<Query> qs = random_queries(23, 60000);
    const std::vector<Query> ext = extreme_queries(24, 60000);
    std::size_t bad = 0, hits = 0;
    for (std::size_t i = 0; i < qs.size(); ++i) {
        const Box& b = qs[i].box;
        const Box& c = qs[(i * 5 + 1) % qs.size()].box;
        const LeafTri tri{b.lo, b.hi, (i % 7 == 0) ? b.lo : Vec3(c.lo.x, b.hi.y, c.hi.z), static_cast<std::uint32_t>(i)};
        Ray r = (i % 2 ? ext[i] : qs[i]).ray;
        if (i % 5 == 1) r.d = tri.v1 - r.o;                   // through a vertex
        if (i % 5 == 2) r.d = 0.5f * (tri.v0 + tri.v2) - r.o;  // through an edge midpoint
        if (r.d == Vec3(0.0f)) continue;
        const TriRay tr = tri_setup(r);
        float t0 = -1, u0 = -1, v0 = -1, t1 = -1, u1 = -1, v1 = -1;
        const bool h0 = tri_intersect(tr, tri.v0, tri.v1, tri.v2, r.tmax, t0, u0, v0);
        const bool h1 = packed(tr, tri, r.tmax, t1, u1, v1);
        hits += h0;
        if (h0 != h1 || (h0 && (bits(t0) != bits(t1) || bits(u0) != bits(u1) || bits(v0) != bits(v1)))) {
            if (bad++ < 3) ADD_FAILURE() << "packed triangle test differs on case " << i;
        }
    }
    EXPECT_EQ(bad, 0u);
    EXPECT_GT(hits, 100u);
}

}  // namespace
}  // namespace pluecker
