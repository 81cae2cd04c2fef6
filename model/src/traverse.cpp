// SPDX-License-Identifier: MIT
#include "pluecker/traverse.hpp"

#include "records.hpp"

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

BoxTestKind parse_box_test(const std::string& s) {
    if (s == "exact") return BoxTestKind::Exact;
    if (s == "smits") return BoxTestKind::Smits;
    if (s == "pluecker") return BoxTestKind::Pluecker;
    if (s == "fixed") return BoxTestKind::Fixed;
    throw InputError("--test: '" + s + "' is not one of exact, smits, pluecker, fixed");
}

const char* test_name(BoxTestKind t) {
    switch (t) {
        case BoxTestKind::Exact: return "exact";
        case BoxTestKind::Smits: return "smits";
        case BoxTestKind::Pluecker: return "pluecker";
        case BoxTestKind::Fixed: return "fixed";
    }
    return "?";
}

ChildOrder parse_child_order(const std::string& s) {
    if (s == "fixed") return ChildOrder::Fixed;
    if (s == "dsa") return ChildOrder::Dsa;
    if (s == "dist") return ChildOrder::Dist;
    throw InputError("--order: '" + s + "' is not one of fixed, dsa, dist");
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
    }
    throw std::logic_error("make_tracer: unreachable test");
}

// ---------------------------------------------------------------------------
// Batched traversal

void SoftwareBoxEngine::test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) {
    for (std::size_t i = 0; i < batch.size(); ++i) hits[i] = fixed_hit(batch[i].ray, batch[i].box, format_) ? 1 : 0;
}

RayTraversal::RayTraversal(const Accel& a, ChildOrder o) : accel_(&a), order_(o), policy_(a) {
    if (!a.quantized) throw std::logic_error("RayTraversal: the Accel is not quantised");
    if (o == ChildOrder::Dist) check_combination(BoxTestKind::Fixed, o);
    stack_.reserve(kMaxStack);
}

void RayTraversal::start(const Ray& r, bool any_hit) {
    any_hit_ = any_hit;
    best_ = Hit{};
    best_.t = r.tmax;
    stats_ = TraversalStats{};
    stack_.clear();
    pending_ = 0;
    state_ = policy_.setup(r);
    if (!policy_.live(state_)) {
        done_ = true;
        return;
    }
    done_ = false;
    tri_ = tri_setup(r);
    cls_ = ray_class(r.d);
    root_pending_ = true;
    emit(0, 0);
    pending_ = 1;
}

void RayTraversal::emit(std::uint32_t node, std::size_t slot) {
    BoxQuery& q = queries_[slot];
    q.query = Query{state_.ray, accel_->nodes[node].box};
    q.ray = state_.fr;
    q.box = accel_->qboxes[node];
    q.node = node;
}

bool RayTraversal::pop(std::uint32_t& node) {
    if (stack_.empty()) return false;
    node = stack_.back();
    stack_.pop_back();
    return true;
}

void RayTraversal::resume(std::span<const std::uint8_t> hits) {
    if (done_ || hits.size() != pending_) throw std::logic_error("RayTraversal::resume: answers do not match");
    stats_.box_tests += pending_;
    std::uint32_t next;
    if (root_pending_) {
        root_pending_ = false;
        if (!hits[0]) {
            done_ = true;
            return;
        }
        next = 0;
    } else {
        const std::uint32_t c0 = static_cast<std::uint32_t>(accel_->nodes[node_].first);
        const bool h0 = hits[0] != 0, h1 = hits[1] != 0;
        if (h0 && h1) {
            const bool swap = order_ == ChildOrder::Dsa && dsa_first_child(cls_, accel_->nodes[node_].axis()) != 0;
            stack_.push_back(swap ? c0 : c0 + 1);
            next = swap ? c0 + 1 : c0;
        } else if (h0 || h1) {
            next = h0 ? c0 : c0 + 1;
        } else if (!pop(next)) {
            done_ = true;
            return;
        }
    }
    advance(next);
}

// Visits nodes from `node` on until an interior node needs its children
// tested (queries emitted) or the traversal ends.
void RayTraversal::advance(std::uint32_t node) {
    const LeafTri* tris = accel_->tris.data();
    for (;;) {
        ++stats_.node_visits;
        const BvhNode& n = accel_->nodes[node];
        if (!n.is_leaf()) {
            node_ = node;
            const std::uint32_t c0 = static_cast<std::uint32_t>(n.first);
            emit(c0, 0);
            emit(c0 + 1, 1);
            pending_ = 2;
            return;
        }
        const float before = best_.t;
        const std::uint32_t end = static_cast<std::uint32_t>(n.first + n.count);
        for (std::uint32_t i = static_cast<std::uint32_t>(n.first); i < end; ++i) {
            ++stats_.tri_tests;
            const LeafTri& tri = tris[i];
            float t, b1, b2;
            if (tri_intersect(tri_, tri.v0, tri.v1, tri.v2, best_.t, t, b1, b2) && closer(t, tri.id, best_)) {
                best_ = Hit{t, b1, b2, tri.id};
                if (any_hit_) {
                    done_ = true;
                    return;
                }
            }
        }
        if (best_.t < before) policy_.shrink(state_, best_.t);
        if (!pop(node)) {
            done_ = true;
            return;
        }
    }
}

void run_batched(const Accel& a, ChildOrder o, BoxEngine& engine, std::size_t pool,
                 const std::function<bool(BatchRay&)>& next, const std::function<void(const BatchResult&)>& finish,
                 TraversalStats& st, BatchStats* bs) {
    if (pool == 0) throw InputError("--pool: must be at least 1");
    std::vector<RayTraversal> slots(pool, RayTraversal(a, o));
    std::vector<std::uint64_t> tags(pool);
    std::vector<bool> busy(pool, false);
    std::vector<BoxQuery> batch;
    std::vector<std::uint8_t> hits;
    batch.reserve(2 * pool);
    hits.reserve(2 * pool);
    bool source_open = true;  // next() has not yet said "none" since the last finish()
    std::size_t in_flight = 0;

    auto complete = [&](std::size_t i) {
        busy[i] = false;
        --in_flight;
        st += slots[i].stats();
        finish(BatchResult{tags[i], slots[i].hit()});
        source_open = true;
    };
    auto fill = [&] {
        for (std::size_t i = 0; i < pool && source_open; ++i) {
            while (!busy[i] && source_open) {
                BatchRay br;
                if (!next(br)) {
                    source_open = false;
                    break;
                }
                tags[i] = br.tag;
                busy[i] = true;
                ++in_flight;
                slots[i].start(br.ray, br.any_hit);
                if (slots[i].done()) complete(i);  // missed the clip cube
            }
        }
    };

    for (;;) {
        fill();
        if (in_flight == 0) {
            if (!source_open) break;
            continue;
        }
        batch.clear();
        for (std::size_t i = 0; i < pool; ++i)
            if (busy[i])
                for (const BoxQuery& q : slots[i].pending()) batch.push_back(q);
        hits.assign(batch.size(), 0);
        engine.test(batch, hits);
        if (bs) {
            ++bs->batches;
            bs->queries += batch.size();
            if (batch.size() > bs->max_batch) bs->max_batch = batch.size();
        }
        std::size_t k = 0;
        for (std::size_t i = 0; i < pool; ++i) {
            if (!busy[i]) continue;
            const std::size_t n = slots[i].pending().size();
            slots[i].resume(std::span<const std::uint8_t>(hits.data() + k, n));
            k += n;
            if (slots[i].done()) complete(i);
        }
    }
}

std::vector<Hit> trace_batched(const Accel& a, ChildOrder o, BoxEngine& engine, std::size_t pool,
                               std::span<const Ray> rays, bool any_hit, TraversalStats& st) {
    std::vector<Hit> out(rays.size());
    std::size_t next_ray = 0;
    run_batched(
        a, o, engine, pool,
        [&](BatchRay& br) {
            if (next_ray == rays.size()) return false;
            br = BatchRay{rays[next_ray], any_hit, next_ray};
            ++next_ray;
            return true;
        },
        [&](const BatchResult& r) { out[r.tag] = r.hit; }, st);
    return out;
}

}  // namespace pluecker
