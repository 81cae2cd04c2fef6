// SPDX-License-Identifier: MIT
// What a traversal reads (Accel): the BVH nodes, the triangles in leaf
// order, the pair layout of the float kernels, the quantised boxes of the
// fixed-point path.
#pragma once

#include "pluecker/bvh.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/local_bvh.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/triangle.hpp"

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <span>
#include <vector>

namespace pluecker {

// ---------------------------------------------------------------------------
// The layout of the float traversal kernels (smits and pluecker): the two
// children of an interior node in one 64-byte record, their boxes as one
// 4-lane vector per axis, so that both boxes are tested at once.

// A child as the kernels see it: a leaf (count > 0: triangles tris[first,
// first + count)) or an interior node (count <= 0, its children in
// pairs[first]; -count = split axis + 4 * treelet size, see Accel).
struct ChildRef {
    std::int32_t first;
    std::int32_t count;
    bool is_leaf() const { return count > 0; }
    int axis() const { return -count & 3; }
    // Pairs of the treelet this node's pair starts (0: not a treelet root).
    int treelet_size() const { return -count >> 2; }
};

// Levels of the pair layout's treelets (Accel): up to 1 + 2 + 4 pairs.
inline constexpr int kTreeletDepth = 3;

struct alignas(64) NodePair {
    // box[a] = {lo of child 0, lo of child 1, hi of child 0, hi of child 1}
    // on axis a.
    float box[3][4];
    ChildRef child[2];
};
static_assert(sizeof(NodePair) == 64);

// ---------------------------------------------------------------------------
// What a traversal reads: the BVH nodes, the triangles copied in leaf order
// (tris[i] is triangle bvh.tri_order[i]) and, for the fixed-point path, the
// node boxes quantised once.
struct Accel {
    // Copies the nodes (same indices) so that every sibling pair
    // (first, first + 1) shares one 64-byte cache line, and builds the pair
    // layout of the same tree. Large arrays are 2 MiB aligned and asked for
    // transparent huge pages (fewer TLB misses on incoherent rays).
    Accel(const Mesh& mesh, const Bvh& bvh);

    std::span<const BvhNode> nodes;
    int depth = 1;  // levels of the BVH
    std::span<const LeafTri> tris;
    // The same tree for the float kernels: root = nodes[0] as a ChildRef
    // (an interior root names its children's pair). Pairs are laid out in
    // treelets of kTreeletDepth levels: treelets in depth-first order, the
    // pairs of a treelet breadth-first and contiguous, so that a ray
    // entering a treelet (at its root, ChildRef::treelet_size() > 0) fetches
    // all of its lines at once rather than one level at a time.
    ChildRef root{};
    std::span<const NodePair> pairs;
    struct FreeDeleter {
        void operator()(void* p) const { std::free(p); }
    };
    std::unique_ptr<BvhNode[], FreeDeleter> node_store;  // 64-byte aligned; nodes[i] = node_store[i + 1]
    std::unique_ptr<NodePair[], FreeDeleter> pair_store;
    std::unique_ptr<LeafTri[], FreeDeleter> tri_store;

    // Quantises every node box (fixed_quantize_box) for format f.
    void quantize(const FixedFormat& f);
    bool quantized = false;
    FixedFormat format;
    std::vector<FixedBox> qboxes;

    // The local frames' hierarchy of the same tree (build_local_bvh), for
    // the local test; empty until localize().
    void localize(const LocalFormat& f, const LocalBuildOptions& o);
    std::unique_ptr<const LocalBvh> local;
};

}  // namespace pluecker
