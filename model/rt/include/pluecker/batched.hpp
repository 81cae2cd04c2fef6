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
// engine calls fixed_hit, the Verilator harness in sim/ sends the same
// queries through the RTL. Given the same answers, the batched traversal
// issues the same queries per ray, visits the same nodes and returns the
// same hit as traverse<FixedPolicy, ...>.

// One ray/box query as the RTL takes it, plus its float form.
struct BoxQuery {
    Query query;         // the ray as given (tmax as the test sees it) and the node's float box
    FixedRay ray;        // *fixed_setup_ray(query.ray, format)
    FixedBox box;        // fixed_quantize_box(query.box, format)
    std::uint32_t node;  // BVH node index of the box
};

class BoxEngine {
public:
    virtual ~BoxEngine() = default;
    // Answers a whole batch: hits[i] = 1 when batch[i] hits, else 0.
    // hits.size() == batch.size() >= 1.
    virtual void test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) = 0;
};

// The software engine: fixed_hit on every query.
class SoftwareBoxEngine final : public BoxEngine {
public:
    explicit SoftwareBoxEngine(const FixedFormat& f) : format_(f) {}
    void test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) override;

private:
    FixedFormat format_;
};

// One ray's resumable traversal. The Accel must be quantised.
class RayTraversal {
public:
    RayTraversal(const Accel& a, ChildOrder o);  // o: fixed or dsa
    // Starts a ray; afterwards either done() or pending() is non-empty.
    void start(const Ray& r, bool any_hit);
    bool done() const { return done_; }
    // The queries awaiting answers (1 for the root, 2 for a node's children).
    std::span<const BoxQuery> pending() const { return {queries_.data(), done_ ? 0u : pending_}; }
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
    FixedPolicy policy_;
    FixedPolicy::State state_;
    TriRay tri_{};
    RayClass cls_ = 0;
    bool any_hit_ = false;
    bool done_ = true;
    Hit best_;
    TraversalStats stats_;
    std::uint32_t node_ = 0;  // the node whose children are pending
    bool root_pending_ = false;
    std::uint32_t pending_ = 0;
    std::array<BoxQuery, 2> queries_{};
    std::vector<std::uint32_t> stack_;
};

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
void run_batched(const Accel& a, ChildOrder o, BoxEngine& engine, std::size_t pool,
                 const std::function<bool(BatchRay&)>& next, const std::function<void(const BatchResult&)>& finish,
                 TraversalStats& st, BatchStats* bs = nullptr);

// Convenience: traces a list of rays; result i belongs to rays[i].
std::vector<Hit> trace_batched(const Accel& a, ChildOrder o, BoxEngine& engine, std::size_t pool,
                               std::span<const Ray> rays, bool any_hit, TraversalStats& st);


}  // namespace pluecker
