// SPDX-License-Identifier: MIT
#include "rtl_engine.hpp"

#include <chrono>
#include <cstdio>

namespace pluecker::sim {

namespace {
// Mismatches printed in full before the harness only counts them.
constexpr std::uint64_t kMaxReported = 10;
}  // namespace

RtlBoxEngine::RtlBoxEngine(RtlIntersector& rtl) : rtl_(&rtl), format_(built_format()) {}

void RtlBoxEngine::test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) {
    const auto t0 = std::chrono::steady_clock::now();
    packed_.resize(batch.size());
    for (std::size_t i = 0; i < batch.size(); ++i) packed_[i] = pack_query(batch[i].ray, batch[i].box);
    rtl_->run(packed_.data(), batch.size(), hits.data());
    rtl_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (std::size_t i = 0; i < batch.size(); ++i) {
        const bool golden = fixed_hit(batch[i].ray, batch[i].box, format_);
        if ((hits[i] != 0) == golden) continue;
        if (++mismatches_ <= kMaxReported) {
            const BoxQuery& q = batch[i];
            std::fprintf(stderr,
                         "mismatch: batch %llu query %zu (node %u): RTL %d, model %d; query: %a %a %a %a %a %a %a "
                         "%a %a %a %a %a %a\n",
                         static_cast<unsigned long long>(batches_), i, q.node, hits[i] ? 1 : 0, golden ? 1 : 0,
                         double(q.query.ray.o.x), double(q.query.ray.o.y), double(q.query.ray.o.z),
                         double(q.query.ray.d.x), double(q.query.ray.d.y), double(q.query.ray.d.z),
                         double(q.query.ray.tmax), double(q.query.box.lo.x), double(q.query.box.lo.y),
                         double(q.query.box.lo.z), double(q.query.box.hi.x), double(q.query.box.hi.y),
                         double(q.query.box.hi.z));
        }
    }
    queries_ += batch.size();
    ++batches_;
}

}  // namespace pluecker::sim
