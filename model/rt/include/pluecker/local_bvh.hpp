// SPDX-License-Identifier: MIT
// The quantised hierarchy of the local frames (local.hpp), built from a
// float BVH of any scene: every node's box as K-bit offsets in its parent's
// frame, rounded outward, and every node's own frame (the frame of its
// children's boxes).
//
// Frames
//   The root box is tested in the tightest frame holding it (root_frame);
//   a child's frame is local_child_frame of its parent's: origin at the
//   child's quantised lo corner in the parent's grid (parent_origin, the
//   default: a node stores only its exponents) or at the child's own float
//   lo rounded down to its cell (own origins: G bits per axis stored per
//   node, a tighter fit), and per axis the smallest power-of-two cell with
//   which the child's float box fits (uniform: one cell for the three axes).
//
// Memory (memory_bits): what one node costs in the quantised layout
//   box      6 K bits        its planes in the parent's frame
//   exps     3 (or 1) x E    its frame's exponents, E = bit width of G - K + 1
//   origin   3 G bits        own origins only
//   links    64 bits         first child / first triangle and count, as in
//                            the float node
//   against the float node's 32 bytes (a 24-byte box and the same links).
#pragma once

#include "pluecker/bvh.hpp"
#include "pluecker/local.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace pluecker {

struct LocalBuildOptions {
    bool uniform = false;        // one cell size for the three axes of a frame
    bool parent_origin = true;   // frame origin from the parent's grid (else stored per node)
    bool operator==(const LocalBuildOptions&) const = default;
};

struct LocalBvh {
    static constexpr std::uint32_t kNoParent = 0xffffffffu;

    LocalFormat format;
    LocalBuildOptions options;
    LocalFrame root_frame;                // the frame the root box is tested in
    std::vector<LocalFrame> frames;       // frames[n]: node n's own frame
    std::vector<LocalBox> boxes;          // boxes[n]: node n's box in its parent's frame (root: root_frame)
    std::vector<std::uint32_t> parent;    // parent[n]; kNoParent for the root

    // The frame node n's box is tested in.
    const LocalFrame& test_frame(std::uint32_t n) const {
        return parent[n] == kNoParent ? root_frame : frames[parent[n]];
    }
    // Bits of one node in the quantised layout (see above), and of a float node.
    int memory_bits() const;
    static constexpr int kFloatNodeBits = 32 * 8;
};

// Builds over the nodes of a BVH (nodes[0] the root, children adjacent as
// in bvh.hpp). Throws InputError for a bad format or a box outside its range.
LocalBvh build_local_bvh(std::span<const BvhNode> nodes, const LocalFormat& f, const LocalBuildOptions& o);

}  // namespace pluecker
