// SPDX-License-Identifier: MIT
#include "pluecker/traversal.hpp"

#include "pluecker/accel.hpp"
#include "pluecker/policies.hpp"
#include "pluecker/traverse_loops.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <new>
#include <utility>
#include <stdexcept>

namespace pluecker {

// ---------------------------------------------------------------------------
// Names

const char* test_name(BoxTestKind t) {
    switch (t) {
        case BoxTestKind::Exact: return "exact";
        case BoxTestKind::Smits: return "smits";
        case BoxTestKind::Pluecker: return "pluecker";
        case BoxTestKind::Fixed: return "fixed";
        case BoxTestKind::Local: return "local";
        case BoxTestKind::F32Pluecker: return "f32-pluecker";
        case BoxTestKind::F32PlueckerCons: return "f32-pluecker-cons";
        case BoxTestKind::F32Smits: return "f32-smits";
    }
    return "?";
}

const char* order_name(ChildOrder o) {
    switch (o) {
        case ChildOrder::Fixed: return "fixed";
        case ChildOrder::Dsa: return "dsa";
        case ChildOrder::Dist: return "dist";
    }
    return "?";
}

void check_combination(BoxTestKind t, ChildOrder o) {
    if (o == ChildOrder::Dist && t != BoxTestKind::Smits)
        throw InputError(std::string("--order dist needs the entry distance of --test smits, not --test ") +
                         test_name(t));
}

std::string config_name(BoxTestKind t, ChildOrder o) {
    if (t == BoxTestKind::Smits && o == ChildOrder::Fixed) return "smits-mul-cls";
    if (t == BoxTestKind::Pluecker && o == ChildOrder::Fixed) return "pluecker-cls";
    return std::string(test_name(t)) + "-" + order_name(o);
}

// ---------------------------------------------------------------------------
// Fixed policy

FixedPolicy::State FixedPolicy::setup(const Ray& r) const {
    State st;
    const std::optional<FixedRay> fr = fixed_setup_ray(r, accel->format);
    if (!fr) return st;
    st.ray = r;
    st.fr = *fr;
    st.live = true;
    return st;
}

void FixedPolicy::shrink(State& st, float t) const {
    if (!(t < st.ray.tmax)) return;
    st.ray.tmax = t;
    fixed_setup_end(st.fr, st.ray, accel->format);
}

// ---------------------------------------------------------------------------
// Local policy

LocalPolicy::LocalPolicy(const Accel& a) : accel(&a) {
    if (!a.local) throw std::logic_error("LocalPolicy: the local test needs Accel::localize first");
}

LocalPolicy::State LocalPolicy::setup(const Ray& r) const {
    State st;
    const std::optional<LocalRay> lr = local_setup_ray(r, accel->local->format);
    if (!lr) return st;
    st.ray = r;
    st.lr = *lr;
    st.live = true;
    return st;
}

void LocalPolicy::shrink(State& st, float t) const {
    if (!(t < st.ray.tmax)) return;
    st.ray.tmax = t;
    local_setup_end(st.lr, st.ray, accel->local->format);
    st.frame_key = kNoKey;  // the node ray's end changed
}

const LocalNodeRay& LocalPolicy::node_ray(const State& st, std::uint32_t node) const {
    const LocalBvh& q = *accel->local;
    const std::uint32_t key = q.parent[node];  // kNoParent for the root
    if (st.frame_key != key) {
        st.nr = local_node_ray(st.lr, q.test_frame(node), q.format);
        st.frame_key = key;
    }
    return st.nr;
}

// ---------------------------------------------------------------------------
// Brute force

Hit brute_force_closest(const Mesh& m, const Ray& r) {
    const TriRay tr = tri_setup(r);
    Hit best;
    best.t = r.tmax;
    for (std::uint32_t i = 0; i < m.triangles.size(); ++i) {
        const auto& tri = m.triangles[i];
        float t, b1, b2;
        if (tri_intersect(tr, m.vertices[tri[0]], m.vertices[tri[1]], m.vertices[tri[2]], best.t, t, b1, b2) &&
            closer(t, i, best))
            best = Hit{t, b1, b2, i};
    }
    return best.found() ? best : Hit{};
}

bool brute_force_any(const Mesh& m, const Ray& r) {
    const TriRay tr = tri_setup(r);
    for (const auto& tri : m.triangles) {
        float t, b1, b2;
        if (tri_intersect(tr, m.vertices[tri[0]], m.vertices[tri[1]], m.vertices[tri[2]], r.tmax, t, b1, b2))
            return true;
    }
    return false;
}

// ---------------------------------------------------------------------------
// Tracer

namespace {

template <class Policy, ChildOrder Order>
class TracerImpl final : public Tracer {
public:
    TracerImpl(const Accel& a, Policy p) : a_(a), p_(p) {}
    Hit closest(const Ray& r, TraversalStats& st) const override {
        return traverse<Policy, Order, false>(a_, p_, r, st);
    }
    bool occluded(const Ray& r, TraversalStats& st) const override {
        return traverse<Policy, Order, true>(a_, p_, r, st).found();
    }

private:
    const Accel& a_;
    Policy p_;
};

// Owns the inner policy so a recording tracer keeps it alive.
template <class Inner, ChildOrder Order>
class RecordingTracer final : public Tracer {
public:
    RecordingTracer(const Accel& a, Inner inner, std::vector<Query>* out)
        : inner_(inner), impl_(a, RecordingPolicy<Inner>{&inner_, out}) {}
    Hit closest(const Ray& r, TraversalStats& st) const override { return impl_.closest(r, st); }
    bool occluded(const Ray& r, TraversalStats& st) const override { return impl_.occluded(r, st); }

private:
    Inner inner_;
    TracerImpl<RecordingPolicy<Inner>, Order> impl_;
};

template <class Policy, ChildOrder Order>
std::unique_ptr<Tracer> make_one(const Accel& a, Policy p, std::vector<Query>* record) {
    if (record) return std::make_unique<RecordingTracer<Policy, Order>>(a, p, record);
    return std::make_unique<TracerImpl<Policy, Order>>(a, p);
}

template <class Policy>
std::unique_ptr<Tracer> make_ordered(const Accel& a, Policy p, ChildOrder o, std::vector<Query>* record) {
    switch (o) {
        case ChildOrder::Fixed: return make_one<Policy, ChildOrder::Fixed>(a, p, record);
        case ChildOrder::Dsa: return make_one<Policy, ChildOrder::Dsa>(a, p, record);
        case ChildOrder::Dist:
            if constexpr (Policy::kDistance) return make_one<Policy, ChildOrder::Dist>(a, p, record);
            break;
    }
    throw std::logic_error("make_tracer: unreachable order");
}

}  // namespace

std::unique_ptr<Tracer> make_tracer(const Accel& a, BoxTestKind t, ChildOrder o, std::vector<Query>* record) {
    check_combination(t, o);
    switch (t) {
        case BoxTestKind::Exact: return make_ordered(a, ExactPolicy{}, o, record);
        case BoxTestKind::Smits: return make_ordered(a, SmitsPolicy{}, o, record);
        case BoxTestKind::Pluecker: return make_ordered(a, PlueckerPolicy{}, o, record);
        case BoxTestKind::Fixed:
            if (!a.quantized) throw std::logic_error("make_tracer: the fixed test needs Accel::quantize first");
            return make_ordered(a, FixedPolicy{a}, o, record);
        case BoxTestKind::Local: return make_ordered(a, LocalPolicy{a}, o, record);
        case BoxTestKind::F32Pluecker: return make_ordered(a, F32Policy<BoxTestKind::F32Pluecker>{a}, o, record);
        case BoxTestKind::F32PlueckerCons:
            return make_ordered(a, F32Policy<BoxTestKind::F32PlueckerCons>{a}, o, record);
        case BoxTestKind::F32Smits: return make_ordered(a, F32Policy<BoxTestKind::F32Smits>{a}, o, record);
    }
    throw std::logic_error("make_tracer: unreachable test");
}

}  // namespace pluecker
