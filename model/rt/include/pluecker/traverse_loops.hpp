// SPDX-License-Identifier: MIT
// The traversal loops (templates over a policy, a child order, closest or
// any hit, and the ray class; traversal.hpp describes the traversal), and
// traverse(), which dispatches on the ray class.
#pragma once

#include "pluecker/accel.hpp"
#include "pluecker/geometry.hpp"
#include "pluecker/traversal.hpp"
#include "pluecker/triangle.hpp"
#include "pluecker/vec4.hpp"

#include <bit>
#include <cstdint>

namespace pluecker {

// ---------------------------------------------------------------------------
// The traversal loop for rays of class C.

[[gnu::always_inline]] inline void prefetch_below(const Accel& a, const BvhNode& n) {
    const void* p = n.is_leaf() ? static_cast<const void*>(a.tris.data() + n.first)
                                : static_cast<const void*>(a.nodes.data() + n.first);
    __builtin_prefetch(p);
}

template <class Policy, ChildOrder Order, bool AnyHit, RayClass C>
Hit traverse_class(const Accel& a, const Policy& test, const Ray& ray, TraversalStats& st) {
    static_assert(Order != ChildOrder::Dist || Policy::kDistance, "dist order needs the entry distance");
    struct Entry {
        std::uint32_t node;
        float tnear;
    };
    auto s = test.setup(ray);
    if (!test.live(s)) return Hit{};
    const BvhNode* nodes = a.nodes.data();
    const LeafTri* tris = a.tris.data();
    const TriRay tr = tri_setup(ray);
    Hit best;
    best.t = ray.tmax;
    Entry local[kMaxStack];
    Entry* const stack = traversal_stack(local, a.depth);
    int sp = 0;
    float tn0 = 0.0f, tn1 = 0.0f;
    // Counters in locals: the compiler keeps them in registers.
    std::uint64_t visits = 0, boxes = 1, tri_tests = 0;
    std::uint32_t cur = 0;
    if (!test.template hit<C>(s, 0, nodes[0].box, &tn0)) goto done;
    for (;;) {
        ++visits;
        {
            const BvhNode& n = nodes[cur];
            if (n.is_leaf()) {
                const float before = best.t;
                const std::uint32_t end = static_cast<std::uint32_t>(n.first + n.count);
                for (std::uint32_t i = static_cast<std::uint32_t>(n.first); i < end; ++i) {
                    ++tri_tests;
                    const LeafTri& tri = tris[i];
                    float t, b1, b2;
                    if (tri_intersect(tr, tri.v0, tri.v1, tri.v2, best.t, t, b1, b2) && closer(t, tri.id, best)) {
                        best = Hit{t, b1, b2, tri.id};
                        if constexpr (AnyHit) goto done;
                    }
                }
                if (best.t < before) test.shrink(s, best.t);
            } else {
                const std::uint32_t c0 = static_cast<std::uint32_t>(n.first);
                boxes += 2;
                // Both children's data (their child pair or their triangles)
                // is fetched while the boxes are tested: one level of memory
                // latency hidden on rays that leave the cache.
                prefetch_below(a, nodes[c0]);
                prefetch_below(a, nodes[c0 + 1]);
                const bool h0 = test.template hit<C>(s, c0, nodes[c0].box, &tn0);
                const bool h1 = test.template hit<C>(s, c0 + 1, nodes[c0 + 1].box, &tn1);
                if (h0 && h1) {
                    bool swap;
                    if constexpr (Order == ChildOrder::Fixed)
                        swap = false;
                    else if constexpr (Order == ChildOrder::Dsa)
                        swap = dsa_first_child(C, n.axis()) != 0;
                    else
                        swap = tn1 < tn0;
                    stack[sp++] = swap ? Entry{c0, tn0} : Entry{c0 + 1, tn1};
                    cur = swap ? c0 + 1 : c0;
                    continue;
                }
                if (h0 || h1) {
                    cur = h0 ? c0 : c0 + 1;
                    continue;
                }
            }
        }
        for (;;) {
            if (sp == 0) goto done;
            const Entry e = stack[--sp];
            if constexpr (Order == ChildOrder::Dist) {
                if (e.tnear > best.t) continue;
            }
            cur = e.node;
            break;
        }
    }
done:
    st.node_visits += visits;
    st.box_tests += boxes;
    st.tri_tests += tri_tests;
    return best.found() ? best : Hit{};
}

// The triangles tris[0, count) of one leaf, in order, with the test
// specialised for the ray's shear axes (tri_intersect_packed). Returns true
// when an any-hit search may stop; `tested` counts the triangles tested.
// One out-of-line copy per (KZ, SWAP): the traversal picks it once per ray
// (leaf_fn) and calls it through a pointer, which predicts well.
template <int KZ, bool SWAP, bool AnyHit>
[[gnu::noinline]] bool leaf_hits(const TriRay& tr, const LeafTri* t, std::int32_t count, Hit& best,
                                 std::uint64_t& tested) {
    const LeafTri* end = t + count;
    for (; t != end; ++t) {
        float th, b1, b2;
        if (tri_intersect_packed<KZ, SWAP>(tr, *t, best.t, th, b1, b2) && closer(th, t->id, best)) {
            best = Hit{th, b1, b2, t->id};
            if constexpr (AnyHit) {
                tested += static_cast<std::uint64_t>(t - end + count + 1);
                return true;
            }
        }
    }
    tested += static_cast<std::uint64_t>(count);
    return false;
}

template <bool AnyHit>
using LeafFn = bool (*)(const TriRay&, const LeafTri*, std::int32_t, Hit&, std::uint64_t&);

template <bool AnyHit>
LeafFn<AnyHit> leaf_fn(const TriRay& tr) {
    static constexpr LeafFn<AnyHit> kFns[3][2] = {
        {leaf_hits<0, false, AnyHit>, leaf_hits<0, true, AnyHit>},
        {leaf_hits<1, false, AnyHit>, leaf_hits<1, true, AnyHit>},
        {leaf_hits<2, false, AnyHit>, leaf_hits<2, true, AnyHit>},
    };
    return kFns[tr.kz][tr.kx != (tr.kz + 1) % 3 ? 1 : 0];
}

template <class Policy>
inline constexpr bool kHasPairs = requires { requires Policy::kPairs; };

// The same traversal over Accel::pairs for a policy with kPairs: both
// children of a node tested by one hit2 call. Visits the same nodes in the
// same order, counts the same and returns the same hit as traverse_class.
template <class Policy, ChildOrder Order, bool AnyHit, RayClass C>
Hit traverse_pairs(const Accel& a, const Policy& test, const Ray& ray, TraversalStats& st) {
    static_assert(Order != ChildOrder::Dist || Policy::kDistance, "dist order needs the entry distance");
    struct Entry {
        ChildRef ref;
        float tnear;
    };
    auto s = test.setup(ray);
    const NodePair* pairs = a.pairs.data();
    const LeafTri* tris = a.tris.data();
    const TriRay tr = tri_setup(ray);
    const LeafFn<AnyHit> leaf = leaf_fn<AnyHit>(tr);
    Hit best;
    best.t = ray.tmax;
    Entry local[kMaxStack];
    Entry* const stack = traversal_stack(local, a.depth);
    int sp = 0;
    // Counters in registers; box tests = 1 (the root) + 2 per interior node
    // visited, taken from the visits and the leaf visits at the end.
    std::uint64_t visits = 0, leaves = 0, tri_tests = 0;
    ChildRef cur = a.root;
    {
        float t0;
        if (!test.template hit<C>(s, 0, a.nodes[0].box, &t0)) goto done;
    }
    for (;;) {
        ++visits;
        if (cur.is_leaf()) {
            ++leaves;
            const float before = best.t;
            if (leaf(tr, tris + cur.first, cur.count, best, tri_tests)) goto done;
            if (best.t < before) test.shrink(s, best.t);
        } else {
            const NodePair& p = pairs[cur.first];
            // Entering a treelet: its other pairs are fetched now. (Fetching
            // both children's pair or triangles here as well made camera
            // rays 8% slower: most of those lines are not needed, and they
            // compete with the ones that are.)
            for (int k = 1; k < cur.treelet_size(); ++k) __builtin_prefetch(&p + k);
            Float4 tn;
            const unsigned hit = test.template hit2<C>(s, p, tn);
            // Branches on the hit mask, not a computed index: the next
            // node's address is then predicted, and its loads start before
            // the test ends. The order of two hit children is a select.
            if (hit == 3u) {
                bool swap;
                if constexpr (Order == ChildOrder::Fixed)
                    swap = false;
                else if constexpr (Order == ChildOrder::Dsa)
                    swap = dsa_first_child(C, cur.axis()) != 0;
                else
                    swap = tn[1] < tn[0];
                constexpr bool kDist = Order == ChildOrder::Dist;
                const auto r0 = std::bit_cast<std::uint64_t>(p.child[0]);
                const auto r1 = std::bit_cast<std::uint64_t>(p.child[1]);
                const std::uint64_t near_ref = swap ? r1 : r0, far_ref = swap ? r0 : r1;
                const float far_t = kDist ? (swap ? tn[0] : tn[1]) : 0.0f;
                stack[sp++] = Entry{std::bit_cast<ChildRef>(far_ref), far_t};
                cur = std::bit_cast<ChildRef>(near_ref);
                continue;
            }
            if (hit == 1u) {
                cur = p.child[0];
                continue;
            }
            if (hit == 2u) {
                cur = p.child[1];
                continue;
            }
        }
        for (;;) {
            if (sp == 0) goto done;
            --sp;
            if constexpr (Order == ChildOrder::Dist) {
                if (stack[sp].tnear > best.t) continue;
            }
            cur = stack[sp].ref;
            break;
        }
    }
done:
    st.node_visits += visits;
    st.box_tests += 1 + 2 * (visits - leaves);
    st.tri_tests += tri_tests;
    return best.found() ? best : Hit{};
}

// The traversal. Returns the closest hit (AnyHit = false) or the first hit
// found (AnyHit = true) with 0 <= t <= ray.tmax; Hit{} when none. Policies
// with kPairs take traverse_pairs, the others traverse_class.
template <class Policy, ChildOrder Order, bool AnyHit, RayClass C>
Hit traverse_any(const Accel& a, const Policy& test, const Ray& ray, TraversalStats& st) {
    if constexpr (kHasPairs<Policy>)
        return traverse_pairs<Policy, Order, AnyHit, C>(a, test, ray, st);
    else
        return traverse_class<Policy, Order, AnyHit, C>(a, test, ray, st);
}

template <class Policy, ChildOrder Order, bool AnyHit>
Hit traverse(const Accel& a, const Policy& test, const Ray& ray, TraversalStats& st) {
    switch (ray_class(ray.d)) {
        case 0: return traverse_any<Policy, Order, AnyHit, 0>(a, test, ray, st);
        case 1: return traverse_any<Policy, Order, AnyHit, 1>(a, test, ray, st);
        case 2: return traverse_any<Policy, Order, AnyHit, 2>(a, test, ray, st);
        case 3: return traverse_any<Policy, Order, AnyHit, 3>(a, test, ray, st);
        case 4: return traverse_any<Policy, Order, AnyHit, 4>(a, test, ray, st);
        case 5: return traverse_any<Policy, Order, AnyHit, 5>(a, test, ray, st);
        case 6: return traverse_any<Policy, Order, AnyHit, 6>(a, test, ray, st);
        default: return traverse_any<Policy, Order, AnyHit, 7>(a, test, ray, st);
    }
}

}  // namespace pluecker
