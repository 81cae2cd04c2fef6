// SPDX-License-Identifier: MIT
#include "local_engine.hpp"

#include <chrono>
#include <cstdio>

namespace pluecker::sim {

namespace {
// Mismatches printed in full before the harness only counts them.
constexpr std::uint64_t kMaxReported = 10;
}  // namespace

QueryPlan plan_queries(std::span<const ChildTest> tests) {
    QueryPlan plan;
    std::array<LocalBox, kChildren> boxes{};
    for (std::size_t i = 0; i < tests.size();) {
        const ChildTest& t = tests[i];
        std::array<std::int64_t, 2> slot = {static_cast<std::int64_t>(i), -1};
        boxes[0] = *t.box;
        std::size_t used = 1;
        if constexpr (kChildren == 2) {
            boxes[1] = *t.box;
            if (i + 1 < tests.size() && same_ray(*tests[i + 1].ray, *t.ray) && *tests[i + 1].frame == *t.frame) {
                boxes[1] = *tests[i + 1].box;
                slot[1] = static_cast<std::int64_t>(i + 1);
                used = 2;
            }
        }
        plan.packed.push_back(pack_local(*t.ray, *t.frame, boxes));
        plan.slot.push_back(slot);
        i += used;
    }
    return plan;
}

void answers_of(const QueryPlan& plan, std::span<const std::uint8_t> rtl, std::span<std::uint8_t> hits) {
    for (std::size_t q = 0; q < plan.slot.size(); ++q)
        for (int c = 0; c < kChildren; ++c)
            if (plan.slot[q][static_cast<std::size_t>(c)] >= 0)
                hits[static_cast<std::size_t>(plan.slot[q][static_cast<std::size_t>(c)])] = (rtl[q] >> c) & 1;
}

RtlLocalEngine::RtlLocalEngine(RtlLocal& rtl) : rtl_(&rtl), format_(built_local_format()) {}

void RtlLocalEngine::test(std::span<const LocalBoxQuery> batch, std::span<std::uint8_t> hits) {
    const auto t0 = std::chrono::steady_clock::now();
    tests_.clear();
    for (const LocalBoxQuery& q : batch) tests_.push_back(ChildTest{&q.ray, &q.frame, &q.box});
    const QueryPlan plan = plan_queries(tests_);
    rtl_hits_.resize(plan.packed.size());
    rtl_->run(plan.packed.data(), plan.packed.size(), rtl_hits_.data());
    answers_of(plan, rtl_hits_, hits);
    rtl_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (std::size_t q = 0; q < plan.slot.size(); ++q) {
        const auto first = static_cast<std::size_t>(plan.slot[q][0]);
        paired_ += plan.slot[q][1] >= 0;
        for (int c = 0; c < kChildren; ++c) {
            const std::int64_t s = plan.slot[q][static_cast<std::size_t>(c)];
            const LocalBoxQuery& bq = batch[s >= 0 ? static_cast<std::size_t>(s) : first];
            const bool golden = local_hit(bq.node_ray, bq.box, format_);
            const bool rtl = (rtl_hits_[q] >> c) & 1;
            if (rtl == golden) continue;
            if (++mismatches_ <= kMaxReported)
                std::fprintf(stderr,
                             "mismatch: batch %llu RTL query %zu child %d (node %u%s): RTL %d, model %d; query: %a %a "
                             "%a %a %a %a %a %a %a %a %a %a %a\n",
                             static_cast<unsigned long long>(batches_), q, c, bq.node, s < 0 ? ", filled slot" : "",
                             rtl ? 1 : 0, golden ? 1 : 0, double(bq.query.ray.o.x), double(bq.query.ray.o.y),
                             double(bq.query.ray.o.z), double(bq.query.ray.d.x), double(bq.query.ray.d.y),
                             double(bq.query.ray.d.z), double(bq.query.ray.tmax), double(bq.query.box.lo.x),
                             double(bq.query.box.lo.y), double(bq.query.box.lo.z), double(bq.query.box.hi.x),
                             double(bq.query.box.hi.y), double(bq.query.box.hi.z));
        }
    }
    box_tests_ += batch.size();
    rtl_queries_ += plan.packed.size();
    ++batches_;
}

}  // namespace pluecker::sim
