// SPDX-License-Identifier: MIT
// The bounding volume hierarchy of the golden model: a binary BVH of
// triangles with 32-byte nodes (a box, a first index and a signed count, the
// layout of Mahovsky's 2005 report), built by a spatial median split or by a
// binned surface area heuristic.
//
// Layout
//   nodes[0] is the root. The two children of an interior node are adjacent:
//   child 0 at `first`, child 1 at `first + 1`. Child 0 holds the lower side
//   of the split axis (the triangles with the smaller centroids), so a
//   traversal can order the children by the sign of the ray direction on
//   axis() (the report's direction/split-axis order). A leaf owns
//   tri_order[first, first + count).
//
// Boxes
//   Every node box is the exact float bounds of the vertices of the node's
//   triangles, grown by BuildOptions::epsilon in all directions:
//     lo = tight.lo - epsilon, hi = tight.hi + epsilon   (float arithmetic)
//   Float subtraction of one constant is monotone, so an interior box is
//   also exactly the union of its children's boxes.
//
// Centroids are the centres of the triangles' bounding boxes.
//
// Median build (the report's): a node of more than max_leaf_size triangles
// is split at the midpoint of its box on axis depth % 3 (x, y, z round
// robin), triangles by centroid; if that leaves a side empty the next axes
// are tried, then the object median (the smaller half of the centroids on
// axis depth % 3 to child 0). Leaves hold <= max_leaf_size triangles. A
// spatial split of boxes that all contain one shared vertex peels a fan a
// triangle per level, so the tree can be deep (depth 270 for
// sphere:1000000): size traversal stacks by Bvh::depth(). To keep such
// fans from costing O(n^2), nodes at depth >= 256 + 2*bit_width(n) always
// take the object median.
//
// SAH build (binned, after I. Wald, "On fast construction of SAH-based
// bounding volume hierarchies", IEEE Symposium on Interactive Ray Tracing
// 2007): `bins` bins per axis over the node's centroid bounds, on all three
// axes; every boundary between non-empty bins is costed as
//   cost_traverse + cost_intersect * (AL*NL + AR*NR) / A
// (A, AL, AR: half surface areas of the tight boxes); equal costs go to the
// more balanced split, then to the lower axis and bin. A node becomes a leaf
// when n * cost_intersect is no more than the best split's cost and n <=
// sah_max_leaf_size. A node whose centroids all coincide is a leaf up to
// that size, else it is halved (object median).
#pragma once

#include "pluecker/geometry.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace pluecker {

struct Mesh;  // pluecker/mesh.hpp

// 32-byte node: box + first index + signed count.
struct BvhNode {
    Box box;             // 24 bytes, already grown by the build epsilon
    std::int32_t first;  // leaf: first triangle (into Bvh::tri_order); interior: child 0 (child 1 = first + 1)
    std::int32_t count;  // > 0: leaf with `count` triangles; <= 0: interior node, split axis = -count (0,1,2)
    bool is_leaf() const { return count > 0; }
    int axis() const { return -count; }
};
static_assert(sizeof(BvhNode) == 32);

enum class BuildMethod { Median, Sah };

struct BuildOptions {
    BuildMethod method = BuildMethod::Sah;
    // Every node box is grown by this in all directions (the report's value
    // for its scenes scaled into [-1,1]).
    float epsilon = 1e-6f;
    // SAH costs, in the report's terms costTraverse and costTriIntersect.
    // Default 1:1, a node visit weighted like one triangle test (our choice;
    // leaves then average about two triangles):
    // a node of n triangles and half-area A split into (nL, AL), (nR, AR)
    // costs cost_traverse + cost_intersect * (AL*nL + AR*nR) / A; as a leaf
    // it costs n * cost_intersect.
    float cost_traverse = 1.0f;
    float cost_intersect = 1.0f;
    // Median build: a node of <= max_leaf_size triangles is a leaf.
    int max_leaf_size = 4;
    // SAH build: a node larger than this is always split, even when the
    // cost model prefers a leaf.
    int sah_max_leaf_size = 16;
    // SAH build: bins per axis over the centroid bounds (2..64).
    int bins = 16;

    // Throws InputError naming the field when a value is out of range.
    void validate() const;
};

struct Bvh {
    std::vector<BvhNode> nodes;            // nodes[0] is the root
    std::vector<std::uint32_t> tri_order;  // triangle ids, contiguous per leaf
    double build_ms = 0;                   // wall time of build_bvh

    // Levels of the tree: 1 for a single leaf.
    int depth() const;
    std::size_t leaf_count() const;
};

// Builds over triangles given as vertex indices. Throws InputError for no
// triangles, an index outside `vertices` (naming the triangle), a vertex
// that is not finite, or bad options.
Bvh build_bvh(std::span<const Vec3> vertices, std::span<const std::array<std::uint32_t, 3>> triangles,
              const BuildOptions& opt);
Bvh build_bvh(const Mesh& mesh, const BuildOptions& opt);

const char* method_name(BuildMethod m);

}  // namespace pluecker
