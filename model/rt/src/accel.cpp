// SPDX-License-Identifier: MIT
#include "pluecker/accel.hpp"

#include "records.hpp"

#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace pluecker {

// ---------------------------------------------------------------------------
// Accel

Accel::Accel(const Mesh& mesh, const Bvh& bvh) {
    if (bvh.nodes.empty()) throw InputError("traversal: empty BVH");
    // Sibling pairs start at odd indices (1, 3, ...): with node i at slot
    // i + 1 of a 64-byte aligned store, every pair fills one cache line.
    static_assert(sizeof(BvhNode) == 32);
    const std::size_t nn = bvh.nodes.size();
    node_store.reset(alloc_records<BvhNode>(nn + 1));
    std::memcpy(static_cast<void*>(node_store.get() + 1), bvh.nodes.data(), nn * sizeof(BvhNode));
    nodes = std::span<const BvhNode>(node_store.get() + 1, nn);
    depth = bvh.depth();

    const std::size_t nt = bvh.tri_order.size();
    tri_store.reset(alloc_records<LeafTri>(nt));
    for (std::size_t i = 0; i < nt; ++i) {
        const std::uint32_t id = bvh.tri_order[i];
        if (id >= mesh.triangles.size()) throw InputError("traversal: BVH names triangle " + std::to_string(id));
        const auto& t = mesh.triangles[id];
        std::construct_at(tri_store.get() + i,
                          LeafTri{mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], id});
    }
    tris = std::span<const LeafTri>(tri_store.get(), nt);

    // Pair layout: one pair per interior node reached from the root, in
    // treelets of kTreeletDepth levels (see Accel::pairs): treelet roots
    // are taken depth first, child 0's side first; a treelet's pairs level
    // by level. A node reached twice is an error (the BVH is not a tree).
    std::vector<std::int32_t> pair_of(nn, -1);  // interior node -> pair of its children
    std::vector<std::uint8_t> treelet(nn, 0);   // pairs of the treelet a root starts
    std::vector<std::uint32_t> order;           // order[k]: the node whose children pair k holds
    std::vector<std::uint32_t> roots{0};
    std::vector<std::uint32_t> level, below;
    while (!roots.empty()) {
        const std::uint32_t r = roots.back();
        roots.pop_back();
        if (bvh.nodes[r].is_leaf()) continue;  // the root alone may be a leaf here
        const std::size_t start = order.size();
        level.assign(1, r);
        for (int d = 0; d < kTreeletDepth && !level.empty(); ++d) {
            below.clear();
            for (const std::uint32_t i : level) {
                const BvhNode& n = bvh.nodes[i];
                const std::int32_t f = n.first;
                if (f < 0 || static_cast<std::size_t>(f) + 1 >= nn || n.axis() > 2)
                    throw InputError("traversal: BVH node " + std::to_string(i) + " names children " +
                                     std::to_string(f) + " on axis " + std::to_string(n.axis()));
                if (pair_of[i] >= 0) throw InputError("traversal: BVH node " + std::to_string(i) + " is reached twice");
                pair_of[i] = static_cast<std::int32_t>(order.size());
                order.push_back(i);
                for (std::uint32_t c = 0; c < 2; ++c)
                    if (!bvh.nodes[static_cast<std::size_t>(f) + c].is_leaf()) below.push_back(static_cast<std::uint32_t>(f) + c);
            }
            level.swap(below);
        }
        treelet[r] = static_cast<std::uint8_t>(order.size() - start);
        roots.insert(roots.end(), level.rbegin(), level.rend());  // the leftmost on top
    }
    auto ref = [&](std::size_t i) {
        const BvhNode& n = bvh.nodes[i];
        return n.is_leaf() ? ChildRef{n.first, n.count} : ChildRef{pair_of[i], -(n.axis() + 4 * treelet[i])};
    };
    pair_store.reset(alloc_records<NodePair>(order.size()));
    for (std::size_t k = 0; k < order.size(); ++k) {
        NodePair p;
        const auto f = static_cast<std::size_t>(bvh.nodes[order[k]].first);
        for (int c = 0; c < 2; ++c) {
            const Box& b = bvh.nodes[f + static_cast<std::size_t>(c)].box;
            for (int a = 0; a < 3; ++a) {
                p.box[a][c] = b.lo[a];
                p.box[a][c + 2] = b.hi[a];
            }
            p.child[c] = ref(f + static_cast<std::size_t>(c));
        }
        std::construct_at(pair_store.get() + k, p);
    }
    pairs = std::span<const NodePair>(pair_store.get(), order.size());
    root = ref(0);
}

void Accel::quantize(const FixedFormat& f) {
    f.validate();
    format = f;
    qboxes.resize(nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) qboxes[i] = fixed_quantize_box(nodes[i].box, f);
    quantized = true;
}

void Accel::localize(const LocalFormat& f, const LocalBuildOptions& o) {
    local = std::make_unique<const LocalBvh>(build_local_bvh(nodes, f, o));
}

}  // namespace pluecker
