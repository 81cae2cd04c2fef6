// SPDX-License-Identifier: MIT
// A BoxEngine (batched.hpp) that answers every batch of box queries with
// the Verilated RTL and checks each answer against the golden model.
#pragma once

#include "rtl_intersector.hpp"

#include "pluecker/batched.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace pluecker::sim {

class RtlBoxEngine final : public BoxEngine {
public:
    // `rtl` must outlive the engine; its format is built_format().
    explicit RtlBoxEngine(RtlIntersector& rtl);

    // Streams the batch through the RTL (all queries back to back) and
    // returns the RTL's answers; every answer is compared with fixed_hit.
    void test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) override;

    std::uint64_t queries() const { return queries_; }
    std::uint64_t mismatches() const { return mismatches_; }
    std::uint64_t batches() const { return batches_; }
    // Wall time spent inside the RTL simulation (packing included), seconds.
    double rtl_seconds() const { return rtl_seconds_; }

private:
    RtlIntersector* rtl_;
    FixedFormat format_;
    std::vector<PackedQuery> packed_;
    std::uint64_t queries_ = 0;
    std::uint64_t mismatches_ = 0;
    std::uint64_t batches_ = 0;
    double rtl_seconds_ = 0;
};

}  // namespace pluecker::sim
