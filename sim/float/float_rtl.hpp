// SPDX-License-Identifier: MIT
// A Verilated binary32 unit (rtl/pluecker_float_intersector.sv, "float", or
// rtl/pluecker_smits_intersector.sv, "smits") behind the stream harness of
// ../rtl_stream.hpp: queries in with valid/ready, answers back by tag.
//
// The unit and its parameters are fixed when the harness is built
// (sim/build.sh: SIM_UNIT, MODE, SIM_MUL_DSP, SIM_TAG_BITS as Verilator -G
// parameters and SIM_* macros). The port encoding is the port contract's
// (pluecker/float_contract.hpp: pack_float_query); the constructor checks
// the Verilated ports' widths against the contract's port list and
// measures the latency of one query against its LATENCY.
#pragma once

#include "Vfloat_unit.h"
#include "rtl_stream.hpp"

#include "pluecker/f32unit.hpp"
#include "pluecker/float_contract.hpp"
#include "pluecker/policies.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#ifndef SIM_FLOAT_UNIT
#error "SIM_FLOAT_UNIT must be defined (0 float, 1 smits; sim/build.sh passes it)"
#endif
#ifndef SIM_TAG_BITS
#error "SIM_TAG_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_CONSERVATIVE
#error "SIM_CONSERVATIVE must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_MUL_DSP
#error "SIM_MUL_DSP must be defined (sim/build.sh passes it)"
#endif

namespace pluecker::sim {

// The box test the built unit answers (policies.hpp), its query type and
// model.
inline constexpr BoxTestKind kBuiltTest = SIM_FLOAT_UNIT != 0 ? BoxTestKind::F32Smits
                                          : SIM_CONSERVATIVE != 0 ? BoxTestKind::F32PlueckerCons
                                                                  : BoxTestKind::F32Pluecker;
using UnitQuery = F32BoxQuery<kBuiltTest>::Unit;

const FloatPortContract& built_contract();
// "float nearest, MUL_DSP 4" for messages.
std::string build_name();

// The unit's set-up of a float query, and its answer (the golden model).
inline UnitQuery setup_query(const Query& q) { return f32_unit_query<kBuiltTest>(q.ray, q.box); }
inline bool model_hit(const UnitQuery& q) { return f32_unit_hit<kBuiltTest>(q); }

// One query in the unit's port encoding.
struct PackedQuery {
    PortType<decltype(Vfloat_unit::ray_org_i)> org{};
    PortType<decltype(Vfloat_unit::box_min_i)> lo{}, hi{};
#if SIM_FLOAT_UNIT == 0
    PortType<decltype(Vfloat_unit::ray_dir_i)> dir{};
    PortType<decltype(Vfloat_unit::ray_end_i)> end{};
    std::uint8_t end_valid = 0;
#else
    PortType<decltype(Vfloat_unit::ray_inv_i)> inv{};
    std::uint32_t tmax = 0;
#endif
    std::uint8_t cls = 0;
    void apply(Vfloat_unit& t) const;
};

PackedQuery pack(const UnitQuery& q);

// The unit: RtlStream (rtl_stream.hpp) on the Verilated model. The
// constructor checks the Verilated ports' widths against the port contract
// and measures the latency of one query against its LATENCY.
class FloatRtl : public RtlStream<Vfloat_unit, PackedQuery> {
public:
    FloatRtl();
};

// `pluecker_sim render` (cmd_render.cpp).
int cmd_render(const std::vector<std::string>& argv);

}  // namespace pluecker::sim
