// SPDX-License-Identifier: MIT
// Child box tests as RTL queries, and the LocalBoxEngine (batched.hpp) that
// answers every batch of a traversal with the Verilated local unit, each
// answer checked against the golden model.
#pragma once

#include "rtl_local.hpp"

#include "pluecker/batched.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace pluecker::sim {

// One child box test: a set-up ray, the frame of the node and the box.
struct ChildTest {
    const LocalRay* ray;
    const LocalFrame* frame;
    const LocalBox* box;
};

// The RTL queries of a list of child tests, in order. With CHILDREN = 2,
// two consecutive tests of the same ray and frame share one query (a node's
// two children, as a traversal unit would send them); a test without a
// partner fills both slots with its box. slot[q][c] is the test in slot c
// of query q, or -1 for such a filled slot (its answer is checked too).
struct QueryPlan {
    std::vector<PackedLocalQuery> packed;
    std::vector<std::array<std::int64_t, 2>> slot;
};
QueryPlan plan_queries(std::span<const ChildTest> tests);

// The RTL's answer of every test (and of every filled slot, checked against
// the model in `filled_mismatches`): out_hit_o bit c of query q.
void answers_of(const QueryPlan& plan, std::span<const std::uint8_t> rtl, std::span<std::uint8_t> hits);

class RtlLocalEngine final : public LocalBoxEngine {
public:
    // `rtl` must outlive the engine; its format is built_local_format().
    explicit RtlLocalEngine(RtlLocal& rtl);

    // Streams the batch through the RTL (all queries back to back) and
    // returns the RTL's answers; every answer is compared with local_hit on
    // the query's node ray.
    void test(std::span<const LocalBoxQuery> batch, std::span<std::uint8_t> hits) override;

    std::uint64_t box_tests() const { return box_tests_; }      // answers returned
    std::uint64_t rtl_queries() const { return rtl_queries_; }  // queries through the RTL
    std::uint64_t paired() const { return paired_; }            // queries carrying two tests
    std::uint64_t mismatches() const { return mismatches_; }
    std::uint64_t batches() const { return batches_; }
    // Wall time spent inside the RTL simulation (packing included), seconds.
    double rtl_seconds() const { return rtl_seconds_; }

private:
    RtlLocal* rtl_;
    LocalFormat format_;
    std::vector<ChildTest> tests_;
    std::vector<std::uint8_t> rtl_hits_;
    std::uint64_t box_tests_ = 0, rtl_queries_ = 0, paired_ = 0, mismatches_ = 0, batches_ = 0;
    double rtl_seconds_ = 0;
};

}  // namespace pluecker::sim
