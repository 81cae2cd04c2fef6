// SPDX-License-Identifier: MIT
// A box engine (batched.hpp) that answers every batch of box queries with a
// Verilated unit and checks each answer against the golden model: the
// hardware-in-the-loop renders of the global and binary32 harnesses.
#pragma once

#include "pluecker/batched.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <span>
#include <vector>

namespace pluecker::sim {

// Q: the batch's query type (BoxQuery, F32BoxQuery<T>: its float form in
// `query`, its BVH node in `node`); Rtl: an RtlStream of Packed queries.
template <class Q, class Rtl, class Packed>
class RtlBoxEngine final : public BoxEngineT<Q> {
public:
    // `rtl` must outlive the engine; `pack` gives a query's port encoding,
    // `golden` the model's answer.
    RtlBoxEngine(Rtl& rtl, std::function<Packed(const Q&)> pack, std::function<bool(const Q&)> golden)
        : rtl_(&rtl), pack_(std::move(pack)), golden_(std::move(golden)) {}

    // Streams the batch through the RTL (all queries back to back) and
    // returns its answers; every answer is compared with the model.
    void test(std::span<const Q> batch, std::span<std::uint8_t> hits) override {
        const auto t0 = std::chrono::steady_clock::now();
        packed_.resize(batch.size());
        for (std::size_t i = 0; i < batch.size(); ++i) packed_[i] = pack_(batch[i]);
        rtl_->run(packed_.data(), batch.size(), hits.data());
        rtl_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        for (std::size_t i = 0; i < batch.size(); ++i)
            if ((hits[i] != 0) != golden_(batch[i]) && ++mismatches_ <= kMaxReported) report(batch[i], i, hits[i]);
        queries_ += batch.size();
        ++batches_;
    }

    std::uint64_t queries() const { return queries_; }
    std::uint64_t mismatches() const { return mismatches_; }
    std::uint64_t batches() const { return batches_; }
    // Wall time spent inside the RTL simulation (packing included), seconds.
    double rtl_seconds() const { return rtl_seconds_; }
    double queries_per_second() const {
        return rtl_seconds_ > 0 ? static_cast<double>(queries_) / rtl_seconds_ : 0.0;
    }

private:
    // Mismatches printed in full before the engine only counts them.
    static constexpr std::uint64_t kMaxReported = 10;

    void report(const Q& b, std::size_t i, std::uint8_t hit) const {
        const Query& q = b.query;
        std::fprintf(stderr,
                     "mismatch: batch %llu query %zu (node %u): RTL %d, model %d; query: %a %a %a %a %a %a %a %a "
                     "%a %a %a %a %a\n",
                     static_cast<unsigned long long>(batches_), i, b.node, hit ? 1 : 0, hit ? 0 : 1,
                     double(q.ray.o.x), double(q.ray.o.y), double(q.ray.o.z), double(q.ray.d.x), double(q.ray.d.y),
                     double(q.ray.d.z), double(q.ray.tmax), double(q.box.lo.x), double(q.box.lo.y),
                     double(q.box.lo.z), double(q.box.hi.x), double(q.box.hi.y), double(q.box.hi.z));
    }

    Rtl* rtl_;
    std::function<Packed(const Q&)> pack_;
    std::function<bool(const Q&)> golden_;
    std::vector<Packed> packed_;
    std::uint64_t queries_ = 0;
    std::uint64_t mismatches_ = 0;
    std::uint64_t batches_ = 0;
    double rtl_seconds_ = 0;
};

}  // namespace pluecker::sim
