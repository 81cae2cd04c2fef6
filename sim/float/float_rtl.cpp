// SPDX-License-Identifier: MIT
// Driving a Verilated binary32 unit: port packing, the contract checks.
#include "float_rtl.hpp"

#ifndef SIM_DIRECT_EVAL
#define SIM_DIRECT_EVAL 1
#endif

#if SIM_DIRECT_EVAL
// Verilator's generated scheduler, called directly as the fixed-point
// harness does (../rtl_intersector.cpp); weak, so a Verilator that names it
// differently links and falls back to eval().
void Vfloat_unit___024root___eval(Vfloat_unit___024root* vlSelf) __attribute__((weak));
#endif

namespace pluecker::sim {
namespace {

FloatRtlConfig built_config() {
    FloatRtlConfig c;
    c.unit = SIM_FLOAT_UNIT == 0 ? FloatUnit::Pluecker : FloatUnit::Smits;
    c.tag_bits = SIM_TAG_BITS;
    c.conservative = SIM_CONSERVATIVE != 0;
    c.mul_dsp = SIM_MUL_DSP;
    return c;
}

template <class Port>
void check_contract_port(const char* name) {
    check_port<Port>(name, built_contract().port(name).width());
}

// The contract's packing of one query, by port name.
const PortWords& value_of(const std::vector<FloatPortValue>& v, const char* name) {
    for (const FloatPortValue& p : v)
        if (p.name == name) return p.value;
    throw ProtocolError(std::string("the port contract packs no value for ") + name);
}

}  // namespace

const FloatPortContract& built_contract() {
    static const FloatPortContract contract(built_config());
    return contract;
}

std::string build_name() {
    const FloatRtlConfig& c = built_contract().config();
    return std::string(float_unit_name(c.unit)) + (c.conservative ? " conservative" : " nearest") + ", MUL_DSP " +
           std::to_string(c.mul_dsp);
}

PackedQuery pack(const UnitQuery& q) {
    const std::vector<FloatPortValue> v = pack_float_query(q);
    PackedQuery p;
    p.cls = static_cast<std::uint8_t>(value_of(v, "ray_class_i")[0]);
    drive(p.org, value_of(v, "ray_org_i"));
    drive(p.lo, value_of(v, "box_min_i"));
    drive(p.hi, value_of(v, "box_max_i"));
#if SIM_FLOAT_UNIT == 0
    drive(p.dir, value_of(v, "ray_dir_i"));
    drive(p.end, value_of(v, "ray_end_i"));
    p.end_valid = static_cast<std::uint8_t>(value_of(v, "ray_end_valid_i")[0]);
#else
    drive(p.inv, value_of(v, "ray_inv_i"));
    p.tmax = value_of(v, "ray_tmax_i")[0];
#endif
    return p;
}

void PackedQuery::apply(Vfloat_unit& t) const {
    t.ray_class_i = cls;
    t.ray_org_i = org;
    t.box_min_i = lo;
    t.box_max_i = hi;
#if SIM_FLOAT_UNIT == 0
    t.ray_dir_i = dir;
    t.ray_end_i = end;
    t.ray_end_valid_i = end_valid;
#else
    t.ray_inv_i = inv;
    t.ray_tmax_i = tmax;
#endif
}

FloatRtl::FloatRtl() : RtlStream(SIM_TAG_BITS, built_contract().module()) {
    Vfloat_unit& t = top();
    check_contract_port<PortType<decltype(t.in_tag_i)>>("in_tag_i");
    check_contract_port<PortType<decltype(t.out_tag_o)>>("out_tag_o");
    check_contract_port<PortType<decltype(t.ray_org_i)>>("ray_org_i");
    check_contract_port<PortType<decltype(t.box_min_i)>>("box_min_i");
    check_contract_port<PortType<decltype(t.box_max_i)>>("box_max_i");
#if SIM_FLOAT_UNIT == 0
    check_contract_port<PortType<decltype(t.ray_dir_i)>>("ray_dir_i");
    check_contract_port<PortType<decltype(t.ray_end_i)>>("ray_end_i");
#else
    check_contract_port<PortType<decltype(t.ray_inv_i)>>("ray_inv_i");
    check_contract_port<PortType<decltype(t.ray_tmax_i)>>("ray_tmax_i");
#endif
    EvalFn direct = nullptr;
#if SIM_DIRECT_EVAL
    direct = &::Vfloat_unit___024root___eval;
#endif
    start(built_contract().latency(), direct);  // one all-zero query
}

}  // namespace pluecker::sim
