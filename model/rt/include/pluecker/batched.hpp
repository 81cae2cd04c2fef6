// SPDX-License-Identifier: MIT
// Batched, resumable fixed-point traversal (hardware in the loop).
#pragma once

#include "pluecker/accel.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/policies.hpp"
#include "pluecker/query.hpp"
#include "pluecker/traversal.hpp"
#include "pluecker/triangle.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace pluecker {

// A ray is a state machine: it emits the box queries it needs (the root box,
// then the two child boxes of each interior node it enters), waits for their
// answers, and continues. A driver keeps many rays in flight, gathers their
// queries into one batch and hands the batch to a BoxEngine: the software
// engine calls fixed_hit (or local_hit), the Verilator harness in sim/
// sends the same queries through the RTL. Given the same answers, the
// batched traversal issues the same queries per ray, visits the same nodes
// and returns the same hit as traverse<FixedPolicy, ...> (or LocalPolicy).

// The engines: one per query type of a policy (policies.hpp): BoxQuery
// for the global fixed-point datapath, LocalBoxQuery for the local frames.
template <class Q>
class BoxEngineT {
public:
    virtual ~BoxEngineT() = default;
    // Answers a whole batch: hits[i] = 1 when batch[i] hits, else 0.
    // hits.size() == batch.size() >= 1.
    virtual void test(std::span<const Q> batch, std::span<std::uint8_t> hits) = 0;
};
using BoxEngine = BoxEngineT<BoxQuery>;
using LocalBoxEngine = BoxEngineT<LocalBoxQuery>;
// T: BoxTestKind::F32Pluecker, F32PlueckerCons or F32Smits.
template <BoxTestKind T>
using F32BoxEngine = BoxEngineT<F32BoxQuery<T>>;

// The software engines: fixed_hit / local_hit on every query.
class SoftwareBoxEngine final : public BoxEngine {
public:
    explicit SoftwareBoxEngine(const FixedFormat& f) : format_(f) {}
    void test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) override;

private:
    FixedFormat format_;
};
class SoftwareLocalEngine final : public LocalBoxEngine {
public:
    explicit SoftwareLocalEngine(const LocalFormat& f) : format_(f) {}
    void test(std::span<const LocalBoxQuery> batch, std::span<std::uint8_t> hits) override;

private:
    LocalFormat format_;
};
template <BoxTestKind T>
class SoftwareF32Engine final : public F32BoxEngine<T> {
public:
    void test(std::span<const F32BoxQuery<T>> batch, std::span<std::uint8_t> hits) override {
        for (std::size_t i = 0; i < batch.size(); ++i) hits[i] = f32_unit_hit<T>(batch[i].unit) ? 1 : 0;
    }
};

// One ray's resumable traversal with the box test of Policy (FixedPolicy:
// the Accel must be quantised; LocalPolicy: localised).
template <class Policy>
class RayTraversalT {
public:
    using BatchQuery = typename Policy::BatchQuery;
    RayTraversalT(const Accel& a, ChildOrder o);  // o: fixed or dsa
    // Starts a ray; afterwards either done() or pending() is non-empty.
    void start(const Ray& r, bool any_hit);
    bool done() const { return done_; }
    // The queries awaiting answers (1 for the root, 2 for a node's children).
    std::span<const BatchQuery> pending() const { return {queries_.data(), done_ ? 0u : pending_}; }
    // Answers to pending(), in order. Tests the triangles of the leaves it
    // reaches and stops at the next interior node or when done.
    void resume(std::span<const std::uint8_t> hits);
    // Closest (or any) hit; valid when done(). Hit{} when none.
    Hit hit() const { return best_.found() ? best_ : Hit{}; }
    const TraversalStats& stats() const { return stats_; }

private:
    void emit(std::uint32_t node, std::size_t slot);
    void advance(std::uint32_t node);
    bool pop(std::uint32_t& node);

    const Accel* accel_;
    ChildOrder order_;
    Policy policy_;
    typename Policy::State state_;
    TriRay tri_{};
    RayClass cls_ = 0;
    bool any_hit_ = false;
    bool done_ = true;
    Hit best_;
    TraversalStats stats_;
    std::uint32_t node_ = 0;  // the node whose children are pending
    bool root_pending_ = false;
    std::uint32_t pending_ = 0;
    std::array<BatchQuery, 2> queries_{};
    std::vector<std::uint32_t> stack_;
};
using RayTraversal = RayTraversalT<FixedPolicy>;
using LocalRayTraversal = RayTraversalT<LocalPolicy>;

// A ray handed to the driver, and its answer.
struct BatchRay {
    Ray ray;
    bool any_hit = false;
    std::uint64_t tag = 0;  // the caller's handle, returned with the result
};
struct BatchResult {
    std::uint64_t tag;
    Hit hit;
};

struct BatchStats {
    std::uint64_t batches = 0;
    std::uint64_t queries = 0;
    std::size_t max_batch = 0;
};

// The driver. Keeps up to `pool` rays in flight: asks next() for a ray
// whenever a slot is free (next returns false when it has none right now;
// the driver stops when it returns false and no ray is in flight), gathers
// the pending queries of all rays in slot order into one batch per round,
// calls engine.test once per round, and calls finish() for every ray that
// completes (in slot order). finish() may make new rays available to next().
// The engine's query type picks the box test: BoxEngine the global
// fixed-point datapath (Accel quantised), LocalBoxEngine the local frames
// (Accel localised), F32BoxEngine<T> a binary32 unit (the float BVH).
using NextRay = std::function<bool(BatchRay&)>;
using FinishRay = std::function<void(const BatchResult&)>;
void run_batched(const Accel& a, ChildOrder o, BoxEngine& engine, std::size_t pool, const NextRay& next,
                 const FinishRay& finish, TraversalStats& st, BatchStats* bs = nullptr);
void run_batched(const Accel& a, ChildOrder o, LocalBoxEngine& engine, std::size_t pool, const NextRay& next,
                 const FinishRay& finish, TraversalStats& st, BatchStats* bs = nullptr);
template <BoxTestKind T>
void run_batched(const Accel& a, ChildOrder o, F32BoxEngine<T>& engine, std::size_t pool, const NextRay& next,
                 const FinishRay& finish, TraversalStats& st, BatchStats* bs = nullptr);

// Convenience: traces a list of rays; result i belongs to rays[i].
std::vector<Hit> trace_batched(const Accel& a, ChildOrder o, BoxEngine& engine, std::size_t pool,
                               std::span<const Ray> rays, bool any_hit, TraversalStats& st);
std::vector<Hit> trace_batched(const Accel& a, ChildOrder o, LocalBoxEngine& engine, std::size_t pool,
                               std::span<const Ray> rays, bool any_hit, TraversalStats& st);
template <BoxTestKind T>
std::vector<Hit> trace_batched(const Accel& a, ChildOrder o, F32BoxEngine<T>& engine, std::size_t pool,
                               std::span<const Ray> rays, bool any_hit, TraversalStats& st);

}  // namespace pluecker
