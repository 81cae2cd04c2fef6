// SPDX-License-Identifier: MIT
// The Verilated RTL intersector (rtl/pluecker_intersector.sv) behind a small
// streaming interface: queries go in with valid/ready, one a clock when the
// RTL is ready, answers come back matched by tag.
//
// Widths and mode are fixed when the harness is built (sim/build.sh passes
// them to Verilator as -G parameters and to this code as SIM_* macros), so
// one binary drives one configuration of the RTL. The port encoding and the
// expected LATENCY are the port contract's (pluecker/contract.hpp): the
// constructor checks the Verilated ports' widths and measures the latency of
// one query against it. SIM_PIPELINE (default 0) must match a -GPIPELINE
// given through SIM_VFLAGS.
#pragma once

#include "Vpluecker_intersector.h"
#include "verilated.h"

#include "pluecker/contract.hpp"
#include "pluecker/fixed.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

#ifndef SIM_COORD_BITS
#error "SIM_COORD_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_DIR_BITS
#error "SIM_DIR_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_TAG_BITS
#error "SIM_TAG_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_CONSERVATIVE
#error "SIM_CONSERVATIVE must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_PIPELINE
#define SIM_PIPELINE 0
#endif
static_assert(SIM_COORD_BITS >= pluecker::ContractLimits::kMinBits &&
                  SIM_COORD_BITS <= pluecker::ContractLimits::kMaxBits,
              "SIM_COORD_BITS outside the port contract's limits");
static_assert(SIM_DIR_BITS >= pluecker::ContractLimits::kMinBits && SIM_DIR_BITS <= pluecker::ContractLimits::kMaxBits,
              "SIM_DIR_BITS outside the port contract's limits");

namespace pluecker::sim {

// The configuration the RTL was built for, its port contract and format.
RtlConfig built_config();
const PortContract& built_contract();
FixedFormat built_format();

// The RTL broke the stream protocol (an answer nobody asked for, a wrong
// tag, no progress): a harness or RTL bug, not bad input.
struct ProtocolError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

template <class T>
using PortType = std::remove_cv_t<std::remove_reference_t<T>>;

// One query in the RTL's port encoding, packed once, driven many times.
struct PackedQuery {
    PortType<decltype(Vpluecker_intersector::ray_org_i)> org{};
    PortType<decltype(Vpluecker_intersector::ray_dir_i)> dir{};
    PortType<decltype(Vpluecker_intersector::ray_end_i)> end{};
    PortType<decltype(Vpluecker_intersector::box_min_i)> lo{};
    PortType<decltype(Vpluecker_intersector::box_max_i)> hi{};
    std::uint8_t cls = 0;
    std::uint8_t end_valid = 0;
};

// Packs a set-up ray and a quantised box (widths of built_format()) with the
// port contract's pack_query; InputError when an operand does not fit.
PackedQuery pack_query(const FixedRay& r, const FixedBox& b);

// Counters of one intersector since construction.
struct StreamStats {
    std::uint64_t cycles = 0;       // clock cycles simulated (reset excluded)
    std::uint64_t queries = 0;      // answers received
    std::uint64_t stall_cycles = 0; // cycles with in_valid high and in_ready low
    std::uint64_t max_in_flight = 0;
};

class RtlIntersector {
public:
    static constexpr int kTagBits = SIM_TAG_BITS;
    static constexpr std::uint64_t kTagMask = (std::uint64_t{1} << kTagBits) - 1;
    // At most 2^TAG_BITS queries are in flight, so a tag names one of them.
    static constexpr std::uint64_t kMaxInFlight = std::uint64_t{1} << kTagBits;

    RtlIntersector();
    ~RtlIntersector();
    RtlIntersector(const RtlIntersector&) = delete;
    RtlIntersector& operator=(const RtlIntersector&) = delete;

    // out_ready_i is high with probability p_ready each cycle (1: always),
    // drawn from a PRNG seeded with `seed`.
    void set_backpressure(double p_ready, std::uint64_t seed);

    // Streams q[0..n) back to back and stores the answer of q[i] in hits[i]
    // (0 or 1). The tag of a query is its index in the stream of all queries
    // this intersector has seen, modulo 2^TAG_BITS. Throws ProtocolError.
    void run(const PackedQuery* q, std::size_t n, std::uint8_t* hits);

    const StreamStats& stats() const { return stats_; }
    // Cycles from the input to the output handshake of one query, measured
    // at construction (it equals the port contract's LATENCY, or the
    // constructor throws ProtocolError).
    int measured_latency() const { return latency_; }
    // True when the harness calls Verilator's scheduler directly.
    bool direct_eval() const { return direct_eval_; }

private:
    void reset();
    void eval();
    int measure_latency();
    bool draw_ready();

    std::unique_ptr<VerilatedContext> ctx_;
    std::unique_ptr<Vpluecker_intersector> top_;
    StreamStats stats_;
    std::uint64_t stream_index_ = 0;  // queries issued so far (tag source)
    std::uint32_t ready_threshold_ = 0;  // out_ready when rng < threshold; 0 = always
    bool always_ready_ = true;
    bool direct_eval_ = false;  // see SIM_DIRECT_EVAL in the .cpp
    int latency_ = 0;
    std::uint64_t rng_ = 0x9e3779b97f4a7c15ull;
};

}  // namespace pluecker::sim
