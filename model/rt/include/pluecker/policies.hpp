// SPDX-License-Identifier: MIT
// The box tests as traversal policies (smits, pluecker, exact, fixed, and a
// recording wrapper), the interface traverse_loops.hpp is written against.
#pragma once

#include "pluecker/accel.hpp"
#include "pluecker/box_kernels.hpp"
#include "pluecker/boxtest.hpp"
#include "pluecker/f32unit.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/local.hpp"
#include "pluecker/query.hpp"
#include "pluecker/traversal.hpp"

#include <cstdint>
#include <type_traits>
#include <vector>

namespace pluecker {

// ---------------------------------------------------------------------------
// Box tests as traversal policies. Each has a per-ray State, set up once and
// updated when tmax shrinks, and answers hit(state, node index, box).

// A policy's hit<C>(state, node, box, tnear) may use the class C of the ray
// (the traversal passes the class of the ray it set up).
// A policy with kPairs also answers hit2<C>(state, pair, tnear): the bits
// of the children of a NodePair it hits (traverse_pairs); with kDistance
// their entry distances in lanes 0, 1 of tnear.
struct SmitsPolicy {
    static constexpr bool kDistance = true;
    static constexpr bool kPairs = true;
    struct State {
        FastSmitsRay s;
        Ray ray;
        SmitsPairRay pr;
    };
    State setup(const Ray& r) const {
        const FastSmitsRay s = fast_smits_setup(r);
        return {s, r, smits_pair_setup(s)};
    }
    bool live(const State&) const { return true; }
    void shrink(State& st, float t) const {
        st.s.tmax = t;
        st.ray.tmax = t;
        st.pr.init = Float4{0.0f, 0.0f, -t, -t};
    }
    template <RayClass C>
    [[gnu::always_inline]] bool hit(const State& st, std::uint32_t, const Box& b, float* tnear) const {
        return fast_smits_hit<C>(st.s, b, tnear);
    }
    template <RayClass C>
    [[gnu::always_inline]] unsigned hit2(const State& st, const NodePair& p, Float4& tnear) const {
        return fast_smits_pair<C>(st.pr, p, tnear);
    }
    Ray query_ray(const State& st) const { return st.ray; }
};

struct PlueckerPolicy {
    static constexpr bool kDistance = false;
    static constexpr bool kPairs = true;
    struct State {
        FastPlueckerRay p;
        Ray ray;
        PlueckerPairRay pr;
    };
    State setup(const Ray& r) const {
        const FastPlueckerRay p = fast_pluecker_setup(r);
        return {p, r, pluecker_pair_setup(p)};
    }
    bool live(const State&) const { return true; }
    void shrink(State& st, float t) const {
        st.ray.tmax = t;
        st.p = fast_pluecker_setup(st.ray);
        st.pr = pluecker_pair_setup(st.p);
    }
    template <RayClass C>
    [[gnu::always_inline]] bool hit(const State& st, std::uint32_t, const Box& b, float*) const {
        return fast_pluecker_hit<C>(st.p, b);
    }
    template <RayClass C>
    [[gnu::always_inline]] unsigned hit2(const State& st, const NodePair& p, Float4&) const {
        return fast_pluecker_pair<C>(st.pr, p);
    }
    Ray query_ray(const State& st) const { return st.ray; }
};

struct ExactPolicy {
    static constexpr bool kDistance = false;
    struct State {
        Ray ray;
    };
    State setup(const Ray& r) const { return {r}; }
    bool live(const State&) const { return true; }
    void shrink(State& st, float t) const { st.ray.tmax = t; }
    template <RayClass>
    bool hit(const State& st, std::uint32_t, const Box& b, float*) const {
        return exact_hit(st.ray, b);
    }
    Ray query_ray(const State& st) const { return st.ray; }
};

// One ray/box query of the global fixed-point datapath as the RTL takes
// it, plus its float form (the batched traversal's unit, batched.hpp).
struct BoxQuery {
    Query query;         // the ray as given (tmax as the test sees it) and the node's float box
    FixedRay ray;        // *fixed_setup_ray(query.ray, format)
    FixedBox box;        // fixed_quantize_box(query.box, format)
    std::uint32_t node;  // BVH node index of the box
};

struct FixedPolicy {
    static constexpr bool kDistance = false;
    using BatchQuery = BoxQuery;
    explicit FixedPolicy(const Accel& a) : accel(&a) {}
    const Accel* accel;
    struct State {
        Ray ray;  // the ray as given, tmax shrunk to the best hit
        FixedRay fr;
        bool live = false;
    };
    State setup(const Ray& r) const;
    bool live(const State& st) const { return st.live; }
    void shrink(State& st, float t) const;
    template <RayClass>
    bool hit(const State& st, std::uint32_t node, const Box&, float*) const {
        return fixed_hit(st.fr, accel->qboxes[node], accel->format);
    }
    Ray query_ray(const State& st) const { return st.ray; }
    BoxQuery batch_query(const State& st, std::uint32_t node) const {
        return BoxQuery{Query{st.ray, accel->nodes[node].box}, st.fr, accel->qboxes[node], node};
    }
};

// One child query of the local-frame datapath as its RTL takes it (the ray
// at the global width, the frame of the node's parent and the node's box
// in that frame), the node ray the unit computes from the first two
// (local_node_ray, for engines that model the child datapath alone), and
// the float form.
struct LocalBoxQuery {
    Query query;         // the ray as given and the node's float box
    LocalRay ray;
    LocalFrame frame;
    LocalNodeRay node_ray;
    LocalBox box;
    std::uint32_t node;
};

// The local frames (local.hpp) over Accel::local. A node's box is tested
// in its parent's frame; both children of a node are tested one after the
// other, so the state keeps the last node ray (what a traversal unit would
// compute once per node visit).
struct LocalPolicy {
    static constexpr bool kDistance = false;
    using BatchQuery = LocalBoxQuery;
    explicit LocalPolicy(const Accel& a);
    const Accel* accel;
    struct State {
        Ray ray;  // the ray as given, tmax shrunk to the best hit
        LocalRay lr;
        bool live = false;
        mutable std::uint32_t frame_key = kNoKey;  // whose frame nr is in
        mutable LocalNodeRay nr;
    };
    static constexpr std::uint32_t kNoKey = 0xfffffffeu;
    State setup(const Ray& r) const;
    bool live(const State& st) const { return st.live; }
    void shrink(State& st, float t) const;
    // The ray in the frame node `node`'s box is tested in.
    const LocalNodeRay& node_ray(const State& st, std::uint32_t node) const;
    template <RayClass>
    bool hit(const State& st, std::uint32_t node, const Box&, float*) const {
        return local_hit(node_ray(st, node), accel->local->boxes[node], accel->local->format);
    }
    Ray query_ray(const State& st) const { return st.ray; }
    LocalBoxQuery batch_query(const State& st, std::uint32_t node) const {
        return LocalBoxQuery{Query{st.ray, accel->nodes[node].box}, st.lr,   accel->local->test_frame(node),
                             node_ray(st, node),                      accel->local->boxes[node], node};
    }
};

// One query of a binary32 unit (f32unit.hpp) as its RTL takes it: the
// unit's set-up of the ray as given (tmax as the test sees it) and the
// node's float box, plus the float form.
template <BoxTestKind T>
struct F32BoxQuery {
    static_assert(T == BoxTestKind::F32Pluecker || T == BoxTestKind::F32PlueckerCons || T == BoxTestKind::F32Smits);
    using Unit = std::conditional_t<T == BoxTestKind::F32Smits, F32SmitsQuery, F32PlueckerQuery>;
    Query query;
    Unit unit;
    std::uint32_t node;
};

// The unit's set-up of a float query, and its answer.
template <BoxTestKind T>
typename F32BoxQuery<T>::Unit f32_unit_query(const Ray& r, const Box& b) {
    if constexpr (T == BoxTestKind::F32Smits)
        return f32_smits_query(r, b);
    else
        return f32_pluecker_query(r, b, T == BoxTestKind::F32PlueckerCons);
}
template <BoxTestKind T>
bool f32_unit_hit(const typename F32BoxQuery<T>::Unit& q) {
    if constexpr (T == BoxTestKind::F32Smits)
        return f32_smits_hit(q);
    else
        return f32_pluecker_hit(q, T == BoxTestKind::F32PlueckerCons);
}

// A binary32 unit on the float BVH: the ray as given, every box query set
// up for the unit (f32_unit_query) and answered by its model.
template <BoxTestKind T>
struct F32Policy {
    static constexpr bool kDistance = false;
    using BatchQuery = F32BoxQuery<T>;
    explicit F32Policy(const Accel& a) : accel(&a) {}
    const Accel* accel;
    struct State {
        Ray ray;  // tmax shrunk to the best hit
    };
    State setup(const Ray& r) const { return {r}; }
    bool live(const State&) const { return true; }
    void shrink(State& st, float t) const { st.ray.tmax = t; }
    template <RayClass>
    bool hit(const State& st, std::uint32_t, const Box& b, float*) const {
        return f32_unit_hit<T>(f32_unit_query<T>(st.ray, b));
    }
    Ray query_ray(const State& st) const { return st.ray; }
    BatchQuery batch_query(const State& st, std::uint32_t node) const {
        const Box& b = accel->nodes[node].box;
        return BatchQuery{Query{st.ray, b}, f32_unit_query<T>(st.ray, b), node};
    }
};

// Wraps a policy and appends every query it answers to *out.
template <class Inner>
struct RecordingPolicy {
    static constexpr bool kDistance = Inner::kDistance;
    const Inner* inner;
    std::vector<Query>* out;
    using State = typename Inner::State;
    State setup(const Ray& r) const { return inner->setup(r); }
    bool live(const State& st) const { return inner->live(st); }
    void shrink(State& st, float t) const { inner->shrink(st, t); }
    template <RayClass C>
    bool hit(const State& st, std::uint32_t node, const Box& b, float* tnear) const {
        out->push_back(Query{inner->query_ray(st), b});
        return inner->template hit<C>(st, node, b, tnear);
    }
    Ray query_ray(const State& st) const { return inner->query_ray(st); }
};

}  // namespace pluecker
