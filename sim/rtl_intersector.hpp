// SPDX-License-Identifier: MIT
// The Verilated RTL intersector (rtl/pluecker_intersector.sv) behind the
// streaming interface of rtl_stream.hpp: queries go in with valid/ready, one
// a clock when the RTL is ready, answers come back matched by tag.
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
#include "rtl_stream.hpp"

#include "pluecker/contract.hpp"
#include "pluecker/fixed.hpp"

#include <cstdint>

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

// One query in the RTL's port encoding, packed once, driven many times.
struct PackedQuery {
    PortType<decltype(Vpluecker_intersector::ray_org_i)> org{};
    PortType<decltype(Vpluecker_intersector::ray_dir_i)> dir{};
    PortType<decltype(Vpluecker_intersector::ray_end_i)> end{};
    PortType<decltype(Vpluecker_intersector::box_min_i)> lo{};
    PortType<decltype(Vpluecker_intersector::box_max_i)> hi{};
    std::uint8_t cls = 0;
    std::uint8_t end_valid = 0;
    void apply(Vpluecker_intersector& t) const;
};

// Packs a set-up ray and a quantised box (widths of built_format()) with the
// port contract's pack_query; InputError when an operand does not fit.
PackedQuery pack_query(const FixedRay& r, const FixedBox& b);

// The intersector: RtlStream (rtl_stream.hpp) on the Verilated model. The
// constructor checks the Verilated ports' widths against the port contract
// and measures the latency of one query against its LATENCY.
class RtlIntersector : public RtlStream<Vpluecker_intersector, PackedQuery> {
public:
    static constexpr int kTagBits = SIM_TAG_BITS;
    RtlIntersector();
};

}  // namespace pluecker::sim
