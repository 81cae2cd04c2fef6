// SPDX-License-Identifier: MIT
// A K-D tree of triangles, the BVH's counterpart in the comparison of
// Mahovsky's 2005 report (BVH vs K-D tree, each with and without the surface
// area heuristic): 8-byte nodes that split a cell by an axis-aligned plane,
// leaves that list the triangles overlapping their cell, front-to-back
// traversal with the watertight triangle test of triangle.hpp.
//
// Cells
//   The root cell is the bounds of the mesh's vertices, grown by
//   root_epsilon() on every side. An interior node splits its cell at
//   `split` on `axis`: the below child gets [lo, split], the above child
//   [split, hi] on that axis (closed boxes that share the plane). A triangle
//   goes to every child cell it overlaps: a triangle whose bounds end below
//   the plane (hi < split) goes below, one whose bounds start above it
//   (lo > split) goes above, and every other one is decided by the
//   triangle/box overlap test below for each child. Leaves may therefore
//   share triangles; there is no mailbox, so a triangle in several leaves
//   of one ray's path is tested (and counted) once per leaf.
//
// Triangle/box overlap
//   The separating axis test of T. Akenine-Möller, "Fast 3D triangle-box
//   overlap testing", journal of graphics tools 6(1), 2001: with the box
//   centre at the origin, the triangle and the box are disjoint iff one of
//   13 axes separates their projections: the 9 cross products of the box's
//   axes with the triangle's edges, the 3 box axes (the triangle's bounds
//   against the box) and the triangle's normal (its plane against the box).
//   Touching counts as overlap (closed sets). It runs in double with the box
//   grown by kOverlapSlack times max(1, largest |coordinate| of the box),
//   so rounding can only add a triangle to a cell, never drop one (every
//   float difference and product of the test is exact or nearly so in
//   double; the slack is many orders above the error).
//
// Median build (spatial median): a node of more than max_leaf_size
//   triangles is split at the middle of its cell on axis depth % 3 (x, y, z
//   round robin, as the BVH's median build; a cell of zero extent on that
//   axis tries the next axes). It becomes a leaf instead when it holds at
//   most max_leaf_size triangles, at the depth limit, or when the split
//   would leave every triangle in both children.
// SAH build (binned): for each axis of non-zero cell extent, `bins` equal
//   bins over the cell; every triangle's bounds clipped to the cell are
//   counted by the bin of their low end and the bin of their high end, and
//   each of the bins - 1 inner bin boundaries is costed with the BVH's cost
//   model and parameters (bvh.hpp):
//     cost_traverse + cost_intersect * (AL*NL + AR*NR) / A
//   (A, AL, AR: half surface areas of the cell and of the two child cells;
//   NL: triangles whose clipped bounds start below the plane's bin boundary,
//   NR: those ending at or above it). A node becomes a leaf when
//   n * cost_intersect is no more than the best cost, or at the depth limit.
//   Ties go to the lower axis, then the lower plane. Clipped bounds are the
//   triangle's bounds intersected with the cell (not the bounds of the
//   triangle clipped to the cell).
// Depth limit: max_depth, or when 0, 8 + 1.3 log2(n) rounded to the nearest
//   integer (the rule of the K-D tree of M. Pharr and G. Humphreys,
//   Physically Based Rendering, 2004), capped at kKdMaxDepth.
//
// Traversal (closest hit)
//   The ray is clipped to the root cell (one slab test, counted as the one
//   box test of the ray). A stack of (node, tmin, tmax) entries: at an
//   interior node the child on the origin's side of the plane is the near
//   one; with t = the plane's distance, only the near child is visited when
//   t <= 0 or t lies beyond tmax, only the far child when t lies before
//   tmin, else the near child with [tmin, t] and the far one pushed with
//   [t, tmax]. A leaf tests its triangles against the best hit so far
//   (the (t, id) order of triangle.hpp, so the answer equals brute force);
//   the traversal stops when the best hit lies before the leaf's tmax (it
//   cannot be beaten by a later cell), and skips popped entries that start
//   beyond the best hit. The comparisons with tmin/tmax keep a margin
//   (kd_margin) for rounding: a child is culled and the search stopped only
//   when the plane or the hit is clearly past the bound. Any hit (shadow
//   rays) stops at the first triangle hit in [0, tmax].
//   Counted (TraversalStats): node_visits = nodes entered, leaves included;
//   box_tests = 1 per ray that reaches the traversal (the root clip);
//   tri_tests = triangle tests, repeats in several leaves included.
#pragma once

#include "pluecker/bvh.hpp"
#include "pluecker/geometry.hpp"
#include "pluecker/traversal.hpp"
#include "pluecker/triangle.hpp"

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace pluecker {

struct Mesh;  // pluecker/mesh.hpp

// Deepest tree the build makes (and the traversal stack's size).
inline constexpr int kKdMaxDepth = 64;
// Relative slack of the build's overlap test (see above).
inline constexpr double kOverlapSlack = 1e-9;

// 8-byte node.
//   a: interior: the split position (float bits); leaf: first entry of its
//      list in KdTree::refs.
//   b: bits 0-1: the split axis 0..2, or 3 for a leaf; bits 2-31: interior:
//      the index of the above child (the below child is the next node);
//      leaf: the number of triangles in its list.
struct KdNode {
    std::uint32_t a;
    std::uint32_t b;
    bool is_leaf() const { return (b & 3u) == 3u; }
    int axis() const { return static_cast<int>(b & 3u); }
    float split() const { return std::bit_cast<float>(a); }
    std::uint32_t above() const { return b >> 2; }
    std::uint32_t first() const { return a; }
    std::uint32_t count() const { return b >> 2; }
    static KdNode interior(int axis, float split, std::uint32_t above) {
        return KdNode{std::bit_cast<std::uint32_t>(split), (above << 2) | static_cast<std::uint32_t>(axis)};
    }
    static KdNode leaf(std::uint32_t first, std::uint32_t count) { return KdNode{first, (count << 2) | 3u}; }
};
static_assert(sizeof(KdNode) == 8);

struct KdBuildOptions {
    BuildMethod method = BuildMethod::Sah;
    // The BVH's SAH cost parameters (BuildOptions): same meaning, same defaults.
    float cost_traverse = 1.0f;
    float cost_intersect = 1.0f;
    // Median build: a node of <= max_leaf_size triangles is a leaf.
    int max_leaf_size = 4;
    // SAH build: bins per axis over the cell (2..256); bins - 1 candidate planes.
    int bins = 32;
    // 0: 8 + 1.3 log2(n); else 1..kKdMaxDepth.
    int max_depth = 0;

    // Throws InputError naming the field when a value is out of range.
    void validate() const;
    // Method, costs and median leaf size of a BVH's options.
    static KdBuildOptions from(const BuildOptions& b);
};

struct KdTree {
    std::vector<KdNode> nodes;         // nodes[0] is the root
    std::vector<std::uint32_t> refs;   // leaf lists: triangle ids, contiguous per leaf
    Box bounds;                        // the root cell
    double build_ms = 0;               // wall time of build_kdtree
    int depth = 0;                     // levels (1 for a single leaf)
    std::size_t leaves = 0;
    std::size_t empty_leaves = 0;

    std::size_t node_bytes() const { return nodes.size() * sizeof(KdNode); }
    std::size_t list_bytes() const { return refs.size() * sizeof(std::uint32_t); }
    // The cell of every node (index = node index).
    std::vector<Box> cells() const;
};

// The growth of the root cell on every side for a mesh of these bounds.
float root_epsilon(const Box& tight);

// Builds over triangles given as vertex indices. Throws InputError for no
// triangles, an index outside `vertices` (naming the triangle), a vertex
// that is not finite, more than 2^30 nodes or references, or bad options.
KdTree build_kdtree(std::span<const Vec3> vertices, std::span<const std::array<std::uint32_t, 3>> triangles,
                    const KdBuildOptions& opt);
KdTree build_kdtree(const Mesh& mesh, const KdBuildOptions& opt);

// The build's overlap test: false only when the triangle and the box,
// grown by the slack, are disjoint.
bool tri_box_overlap(const Vec3& v0, const Vec3& v1, const Vec3& v2, const Box& box);

// What a traversal reads: the nodes, the leaf lists and the triangles in
// mesh order (refs index them).
struct KdAccel {
    KdAccel(const Mesh& mesh, const KdTree& tree);
    std::vector<KdNode> nodes;
    std::vector<std::uint32_t> refs;
    std::vector<LeafTri> tris;  // tris[i] is mesh triangle i
    Box bounds;
};

// Closest hit ((t, id) order, equal to brute_force_closest) and any hit.
Hit kd_closest(const KdAccel& a, const Ray& r, TraversalStats& st);
bool kd_occluded(const KdAccel& a, const Ray& r, TraversalStats& st);

// The Tracer of traversal.hpp over a K-D tree, for render_direct.
std::unique_ptr<Tracer> make_kd_tracer(const KdAccel& a);

}  // namespace pluecker
