// SPDX-License-Identifier: MIT
#include "pluecker/local_bvh.hpp"

#include <bit>
#include <string>

namespace pluecker {

int LocalBvh::memory_bits() const {
    const int exp_bits = std::bit_width(static_cast<unsigned>(format.max_exp()));
    return 6 * format.box_bits + (options.uniform ? 1 : 3) * exp_bits +
           (options.parent_origin ? 0 : 3 * format.grid_bits) + 64;
}

LocalBvh build_local_bvh(std::span<const BvhNode> nodes, const LocalFormat& f, const LocalBuildOptions& o) {
    f.validate();
    if (nodes.empty()) throw InputError("local frames: empty BVH");
    LocalBvh q;
    q.format = f;
    q.options = o;
    q.frames.resize(nodes.size());
    q.boxes.resize(nodes.size());
    q.parent.assign(nodes.size(), LocalBvh::kNoParent);
    q.root_frame = local_frame_for(nodes[0].box, f, o.uniform);
    q.boxes[0] = local_quantize_box(nodes[0].box, q.root_frame, f);
    // A node's own frame holds its float box: it is derived from the box
    // rounded outward in the frame it is tested in, in both modes (a box
    // rounded to nearest may start below its float lo).
    LocalFormat outward = f;
    outward.mode = FixedMode::Conservative;
    auto own_frame = [&](std::uint32_t n, const LocalFrame& test) {
        return o.parent_origin
                   ? local_child_frame(nodes[n].box, test, local_quantize_box(nodes[n].box, test, outward), f, o.uniform)
                   : local_frame_for(nodes[n].box, f, o.uniform);
    };
    q.frames[0] = own_frame(0, q.root_frame);
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty()) {
        const std::uint32_t n = stack.back();
        stack.pop_back();
        if (nodes[n].is_leaf()) continue;
        const auto first = static_cast<std::uint32_t>(nodes[n].first);
        for (std::uint32_t c = first; c < first + 2; ++c) {
            if (c == 0 || c >= nodes.size() || q.parent[c] != LocalBvh::kNoParent)
                throw InputError("local frames: BVH node " + std::to_string(n) + " names child " + std::to_string(c));
            q.parent[c] = n;
            q.boxes[c] = local_quantize_box(nodes[c].box, q.frames[n], f);
            q.frames[c] = own_frame(c, q.frames[n]);
            stack.push_back(c);
        }
    }
    return q;
}

}  // namespace pluecker
