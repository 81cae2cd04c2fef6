// SPDX-License-Identifier: MIT
// A box engine (batched.hpp) that answers every batch of box queries with
// the Verilated cascade: the hardware-in-the-loop form of the model's
// CascadeBoxEngine (pluecker/cascade.hpp). Each query is set up as that
// engine sets it up (the float ray in each format against the node's box
// quantised once per format; a ray that misses a format's range cube is a
// miss without an RTL query), the rest go through the cascade's lanes, and
// every answer is checked against the model's cascade_answer. The renderer
// gets the RTL's answers.
#pragma once

#include "cascade_query.hpp"

#include "pluecker/batched.hpp"
#include "pluecker/bvh.hpp"
#include "pluecker/cascade.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace pluecker::sim {

class CascadeRtlEngine final : public BoxEngine {
public:
    // `rtl` and `bvh` must outlive the engine. With `check`, every answer is
    // also compared with exact_hit (the "checked" counts of the model).
    CascadeRtlEngine(CascadeRtl& rtl, const Bvh& bvh, bool check);

    void test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) override;

    // The counts of `pluecker cascade` on the model's answers and on the
    // RTL's (equal when nothing mismatched).
    const CascadeCounts& model_counts() const { return model_counts_; }
    const CascadeCounts& rtl_counts() const { return rtl_counts_; }
    std::uint64_t rtl_queries() const { return rtl_queries_; }  // box queries sent through the RTL
    std::uint64_t missed() const { return missed_; }            // answered without one
    std::uint64_t mismatches() const { return mismatches_; }
    std::uint64_t batches() const { return batches_; }
    // Wall time inside the RTL simulation (set-up and packing included).
    double rtl_seconds() const { return rtl_seconds_; }

private:
    static constexpr std::uint64_t kMaxReported = 10;

    void setup(std::span<const BoxQuery> batch);
    void compare(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits);
    void report(const BoxQuery& q, std::size_t i, const char* why, bool hit, AnswerPath path,
                const CascadeAnswer& model) const;

    CascadeRtl* rtl_;
    CascadeFormats formats_;
    bool check_;
    std::vector<FixedBox> narrow_boxes_, wide_boxes_;
    // Per batch: the model's answers, the RTL queries and their positions.
    std::vector<CascadeAnswer> answers_;
    std::vector<CascadeQuery> packed_;
    std::vector<std::size_t> where_;
    std::vector<std::uint8_t> rtl_hits_;
    std::vector<AnswerPath> paths_;
    CascadeCounts model_counts_, rtl_counts_;
    std::uint64_t rtl_queries_ = 0, missed_ = 0, mismatches_ = 0, batches_ = 0;
    double rtl_seconds_ = 0;
};

}  // namespace pluecker::sim
