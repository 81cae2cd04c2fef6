// SPDX-License-Identifier: MIT
#include "pluecker/batched.hpp"

#include <stdexcept>
#include <vector>

namespace pluecker {

// ---------------------------------------------------------------------------
// Batched traversal

void SoftwareBoxEngine::test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) {
    for (std::size_t i = 0; i < batch.size(); ++i) hits[i] = fixed_hit(batch[i].ray, batch[i].box, format_) ? 1 : 0;
}

void SoftwareLocalEngine::test(std::span<const LocalBoxQuery> batch, std::span<std::uint8_t> hits) {
    for (std::size_t i = 0; i < batch.size(); ++i) hits[i] = local_hit(batch[i].node_ray, batch[i].box, format_) ? 1 : 0;
}

namespace {

// The Accel holds what the policy reads.
void check_prepared(const Accel& a, const FixedPolicy*) {
    if (!a.quantized) throw std::logic_error("RayTraversal: the Accel is not quantised");
}
void check_prepared(const Accel& a, const LocalPolicy*) {
    if (!a.local) throw std::logic_error("RayTraversal: the Accel is not localised");
}
template <BoxTestKind T>
void check_prepared(const Accel&, const F32Policy<T>*) {}  // the float BVH is always there

}  // namespace

template <class Policy>
RayTraversalT<Policy>::RayTraversalT(const Accel& a, ChildOrder o) : accel_(&a), order_(o), policy_(a) {
    check_prepared(a, static_cast<const Policy*>(nullptr));
    if (o == ChildOrder::Dist) check_combination(BoxTestKind::Fixed, o);
    stack_.reserve(kMaxStack);
}

template <class Policy>
void RayTraversalT<Policy>::start(const Ray& r, bool any_hit) {
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

template <class Policy>
void RayTraversalT<Policy>::emit(std::uint32_t node, std::size_t slot) {
    queries_[slot] = policy_.batch_query(state_, node);
}

template <class Policy>
bool RayTraversalT<Policy>::pop(std::uint32_t& node) {
    if (stack_.empty()) return false;
    node = stack_.back();
    stack_.pop_back();
    return true;
}

template <class Policy>
void RayTraversalT<Policy>::resume(std::span<const std::uint8_t> hits) {
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
template <class Policy>
void RayTraversalT<Policy>::advance(std::uint32_t node) {
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

namespace {

template <class Policy>
void run_batched_t(const Accel& a, ChildOrder o, BoxEngineT<typename Policy::BatchQuery>& engine, std::size_t pool,
                   const NextRay& next, const FinishRay& finish, TraversalStats& st, BatchStats* bs) {
    using Q = typename Policy::BatchQuery;
    if (pool == 0) throw InputError("--pool: must be at least 1");
    std::vector<RayTraversalT<Policy>> slots(pool, RayTraversalT<Policy>(a, o));
    std::vector<std::uint64_t> tags(pool);
    std::vector<bool> busy(pool, false);
    std::vector<Q> batch;
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
                for (const Q& q : slots[i].pending()) batch.push_back(q);
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

template <class Engine>
std::vector<Hit> trace_batched_t(const Accel& a, ChildOrder o, Engine& engine, std::size_t pool,
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

}  // namespace

template class RayTraversalT<FixedPolicy>;
template class RayTraversalT<LocalPolicy>;
template class RayTraversalT<F32Policy<BoxTestKind::F32Pluecker>>;
template class RayTraversalT<F32Policy<BoxTestKind::F32PlueckerCons>>;
template class RayTraversalT<F32Policy<BoxTestKind::F32Smits>>;

void run_batched(const Accel& a, ChildOrder o, BoxEngine& engine, std::size_t pool, const NextRay& next,
                 const FinishRay& finish, TraversalStats& st, BatchStats* bs) {
    run_batched_t<FixedPolicy>(a, o, engine, pool, next, finish, st, bs);
}
void run_batched(const Accel& a, ChildOrder o, LocalBoxEngine& engine, std::size_t pool, const NextRay& next,
                 const FinishRay& finish, TraversalStats& st, BatchStats* bs) {
    run_batched_t<LocalPolicy>(a, o, engine, pool, next, finish, st, bs);
}

std::vector<Hit> trace_batched(const Accel& a, ChildOrder o, BoxEngine& engine, std::size_t pool,
                               std::span<const Ray> rays, bool any_hit, TraversalStats& st) {
    return trace_batched_t(a, o, engine, pool, rays, any_hit, st);
}
std::vector<Hit> trace_batched(const Accel& a, ChildOrder o, LocalBoxEngine& engine, std::size_t pool,
                               std::span<const Ray> rays, bool any_hit, TraversalStats& st) {
    return trace_batched_t(a, o, engine, pool, rays, any_hit, st);
}

template <BoxTestKind T>
void run_batched(const Accel& a, ChildOrder o, F32BoxEngine<T>& engine, std::size_t pool, const NextRay& next,
                 const FinishRay& finish, TraversalStats& st, BatchStats* bs) {
    run_batched_t<F32Policy<T>>(a, o, engine, pool, next, finish, st, bs);
}
template <BoxTestKind T>
std::vector<Hit> trace_batched(const Accel& a, ChildOrder o, F32BoxEngine<T>& engine, std::size_t pool,
                               std::span<const Ray> rays, bool any_hit, TraversalStats& st) {
    return trace_batched_t(a, o, engine, pool, rays, any_hit, st);
}

#define PLUECKER_F32_BATCHED(T)                                                                                \
    template void run_batched<T>(const Accel&, ChildOrder, F32BoxEngine<T>&, std::size_t, const NextRay&,     \
                                 const FinishRay&, TraversalStats&, BatchStats*);                              \
    template std::vector<Hit> trace_batched<T>(const Accel&, ChildOrder, F32BoxEngine<T>&, std::size_t,        \
                                               std::span<const Ray>, bool, TraversalStats&);
PLUECKER_F32_BATCHED(BoxTestKind::F32Pluecker)
PLUECKER_F32_BATCHED(BoxTestKind::F32PlueckerCons)
PLUECKER_F32_BATCHED(BoxTestKind::F32Smits)
#undef PLUECKER_F32_BATCHED

}  // namespace pluecker
