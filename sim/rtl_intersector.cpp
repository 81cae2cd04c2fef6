// SPDX-License-Identifier: MIT
// Driving the Verilated intersector: port packing and the contract checks;
// reset and the clock loop are rtl_stream.hpp's.
#include "rtl_intersector.hpp"

#ifndef SIM_DIRECT_EVAL
#define SIM_DIRECT_EVAL 1
#endif

#if SIM_DIRECT_EVAL
// The generated scheduler (see RtlStream::start). Weak, so a Verilator whose
// generated code names it differently links and falls back to eval().
void Vpluecker_intersector___024root___eval(Vpluecker_intersector___024root* vlSelf) __attribute__((weak));
#endif

namespace pluecker::sim {

RtlConfig built_config() {
    RtlConfig c;
    c.coord_bits = SIM_COORD_BITS;
    c.dir_bits = SIM_DIR_BITS;
    c.tag_bits = SIM_TAG_BITS;
    c.conservative = SIM_CONSERVATIVE != 0;
    c.pipeline = SIM_PIPELINE;
    return c;
}

const PortContract& built_contract() {
    static const PortContract contract(built_config());
    return contract;
}

FixedFormat built_format() { return built_contract().format(); }

PackedQuery pack_query(const FixedRay& r, const FixedBox& b) {
    const QueryPorts q = pluecker::pack_query(r, b, built_format());
    PackedQuery p;
    drive(p.org, q.ray_org);
    drive(p.dir, q.ray_dir);
    drive(p.end, q.ray_end);
    drive(p.lo, q.box_min);
    drive(p.hi, q.box_max);
    p.cls = static_cast<std::uint8_t>(q.ray_class);
    p.end_valid = static_cast<std::uint8_t>(q.ray_end_valid);
    return p;
}

void PackedQuery::apply(Vpluecker_intersector& t) const {
    t.ray_org_i = org;
    t.ray_dir_i = dir;
    t.ray_end_i = end;
    t.box_min_i = lo;
    t.box_max_i = hi;
    t.ray_class_i = cls;
    t.ray_end_valid_i = end_valid;
}

RtlIntersector::RtlIntersector() : RtlStream(SIM_TAG_BITS, "pluecker_intersector") {
    Vpluecker_intersector& t = top();
    const PortContract& c = built_contract();
    auto width = [&](const char* name) { return c.port(name).width(); };
    check_port<PortType<decltype(t.in_tag_i)>>("in_tag_i", width("in_tag_i"));
    check_port<PortType<decltype(t.ray_org_i)>>("ray_org_i", width("ray_org_i"));
    check_port<PortType<decltype(t.ray_dir_i)>>("ray_dir_i", width("ray_dir_i"));
    check_port<PortType<decltype(t.ray_end_i)>>("ray_end_i", width("ray_end_i"));
    check_port<PortType<decltype(t.box_min_i)>>("box_min_i", width("box_min_i"));
    check_port<PortType<decltype(t.box_max_i)>>("box_max_i", width("box_max_i"));
    check_port<PortType<decltype(t.out_tag_o)>>("out_tag_o", width("out_tag_o"));
    EvalFn direct = nullptr;
#if SIM_DIRECT_EVAL
    direct = &::Vpluecker_intersector___024root___eval;
#endif
    start(c.latency(), direct);
}

}  // namespace pluecker::sim
