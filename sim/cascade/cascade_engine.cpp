// SPDX-License-Identifier: MIT
// The cascade's box engine (cascade_engine.hpp).
#include "cascade_engine.hpp"

#include "pluecker/boxtest.hpp"

#include <chrono>
#include <cstdio>

namespace pluecker::sim {
namespace {

// Every node's box quantised in format f, as CascadeBoxEngine does.
std::vector<FixedBox> quantize_boxes(const Bvh& bvh, const FixedFormat& f) {
    std::vector<FixedBox> out;
    out.reserve(bvh.nodes.size());
    for (const BvhNode& n : bvh.nodes) out.push_back(fixed_quantize_box(n.box, f));
    return out;
}

}  // namespace

CascadeRtlEngine::CascadeRtlEngine(CascadeRtl& rtl, const Bvh& bvh, bool check)
    : rtl_(&rtl),
      formats_(built_formats()),
      check_(check),
      narrow_boxes_(quantize_boxes(bvh, formats_.narrow)),
      wide_boxes_(quantize_boxes(bvh, formats_.wide)) {}

void CascadeRtlEngine::test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) {
    const auto t0 = std::chrono::steady_clock::now();
    setup(batch);
    rtl_hits_.assign(packed_.size(), 0);
    paths_.assign(packed_.size(), AnswerPath::None);
    if (!packed_.empty()) rtl_->run(packed_.data(), packed_.size(), rtl_hits_.data(), paths_.data());
    rtl_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    compare(batch, hits);
    rtl_queries_ += packed_.size();
    ++batches_;
}

// The model's answer of every query; the RTL queries of those whose ray
// meets both range cubes.
void CascadeRtlEngine::setup(std::span<const BoxQuery> batch) {
    answers_.assign(batch.size(), CascadeAnswer{});
    packed_.clear();
    where_.clear();
    for (std::size_t i = 0; i < batch.size(); ++i) {
        const BoxQuery& q = batch[i];
        const std::optional<CascadeItem> item =
            setup_query(q.query.ray, narrow_boxes_[q.node], wide_boxes_[q.node], formats_);
        if (!item) {
            ++missed_;
            continue;
        }
        answers_[i] = item->model;
        packed_.push_back(item->ports);
        where_.push_back(i);
    }
}

// The RTL's answers to the renderer, each checked against the model's; the
// counts of both (a query without an RTL query is a miss for both).
void CascadeRtlEngine::compare(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) {
    std::vector<CascadeAnswer> rtl(batch.size());
    for (std::size_t i = 0; i < batch.size(); ++i) hits[i] = 0;
    for (std::size_t k = 0; k < where_.size(); ++k) {
        const std::size_t i = where_[k];
        const bool hit = rtl_hits_[k] != 0;
        hits[i] = rtl_hits_[k];
        rtl[i] = rtl_answer(hit, paths_[k]);
        if (const char* why = disagreement(answers_[i], hit, paths_[k]))
            if (++mismatches_ <= kMaxReported) report(batch[i], i, why, hit, paths_[k], answers_[i]);
    }
    for (std::size_t i = 0; i < batch.size(); ++i) {
        model_counts_.add(answers_[i]);
        rtl_counts_.add(rtl[i]);
        if (!check_) continue;
        const bool exact = exact_hit(batch[i].query.ray, batch[i].query.box);
        model_counts_.add_exact(answers_[i], exact);
        rtl_counts_.add_exact(rtl[i], exact);
    }
}

void CascadeRtlEngine::report(const BoxQuery& b, std::size_t i, const char* why, bool hit, AnswerPath path,
                              const CascadeAnswer& model) const {
    const Query& q = b.query;
    std::fprintf(stderr,
                 "mismatch: batch %llu query %zu (node %u): %s: RTL %d on the %s stream, model narrow %s, cascade %d; "
                 "query: %a %a %a %a %a %a %a %a %a %a %a %a %a\n",
                 static_cast<unsigned long long>(batches_), i, b.node, why, hit ? 1 : 0, path_name(path),
                 ternary_name(model.narrow), model.hit ? 1 : 0, double(q.ray.o.x), double(q.ray.o.y),
                 double(q.ray.o.z), double(q.ray.d.x), double(q.ray.d.y), double(q.ray.d.z), double(q.ray.tmax),
                 double(q.box.lo.x), double(q.box.lo.y), double(q.box.lo.z), double(q.box.hi.x), double(q.box.hi.y),
                 double(q.box.hi.z));
}

}  // namespace pluecker::sim
