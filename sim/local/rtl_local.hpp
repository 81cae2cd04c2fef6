// SPDX-License-Identifier: MIT
// The Verilated local unit (rtl/pluecker_local_intersector.sv) behind the
// streaming interface of rtl_stream.hpp: queries (a ray, a frame and
// CHILDREN boxes) go in with valid/ready, one a clock when the RTL is ready,
// answers (one bit per box) come back matched by tag.
//
// Widths, mode, CHILDREN and the multiplier style are fixed when the harness
// is built (sim/build.sh with SIM_UNIT=local passes them to Verilator as -G
// parameters and to this code as SIM_* macros), so one binary drives one
// configuration. The port encoding and the expected LATENCY are the local
// port contract's (pluecker/local_contract.hpp): the constructor checks the
// Verilated ports' widths and measures the latency of one query against it.
#pragma once

#include "Vpluecker_local_intersector.h"
#include "rtl_stream.hpp"

#include "pluecker/local_contract.hpp"

#include <cstdint>
#include <span>
#include <string>

#ifndef SIM_BOX_BITS
#error "SIM_BOX_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_DIR_BITS
#error "SIM_DIR_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_GRID_BITS
#error "SIM_GRID_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_CHILDREN
#error "SIM_CHILDREN must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_TAG_BITS
#error "SIM_TAG_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_CONSERVATIVE
#error "SIM_CONSERVATIVE must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_MUL_STYLE
#error "SIM_MUL_STYLE must be defined (sim/build.sh passes it: 0 auto, 1 dsp, 2 lut)"
#endif
static_assert(SIM_CHILDREN >= 1 && SIM_CHILDREN <= pluecker::LocalContractLimits::kMaxChildren,
              "SIM_CHILDREN outside the port contract's limits");

namespace pluecker::sim {

inline constexpr int kChildren = SIM_CHILDREN;

// The configuration the RTL was built for, its port contract and format.
LocalRtlConfig built_local_config();
const LocalPortContract& built_local_contract();
LocalFormat built_local_format();
// "K8 D11 G32, 1 child, conservative, MUL_STYLE auto" for messages.
std::string build_name();

// One query in the RTL's port encoding, packed once, driven many times.
struct PackedLocalQuery {
    using Top = Vpluecker_local_intersector;
    PortType<decltype(Top::ray_org_i)> org{};
    PortType<decltype(Top::ray_dir_i)> dir{};
    PortType<decltype(Top::ray_end_i)> end{};
    PortType<decltype(Top::frame_org_i)> frame_org{};
    PortType<decltype(Top::frame_exp_i)> frame_exp{};
    PortType<decltype(Top::box_min_i)> lo{};
    PortType<decltype(Top::box_max_i)> hi{};
    std::uint8_t cls = 0;
    std::uint8_t end_valid = 0;
    void apply(Top& t) const;
};

// Packs a set-up ray, a frame and kChildren boxes with the port contract's
// pack_local_query; InputError when an operand is outside the contract.
PackedLocalQuery pack_local(const LocalRay& r, const LocalFrame& fr, std::span<const LocalBox> boxes);

// Two set-up rays are the same ray (the node set-up's operands).
bool same_ray(const LocalRay& a, const LocalRay& b);

class RtlLocal : public RtlStream<Vpluecker_local_intersector, PackedLocalQuery> {
public:
    static constexpr int kTagBits = SIM_TAG_BITS;
    RtlLocal();
};

}  // namespace pluecker::sim
