// SPDX-License-Identifier: MIT
// Driving the Verilated local unit: port packing and the contract checks;
// reset and the clock loop are rtl_stream.hpp's.
#include "rtl_local.hpp"

#include "pluecker/contract.hpp"  // mul_style_name

#ifndef SIM_DIRECT_EVAL
#define SIM_DIRECT_EVAL 1
#endif

#if SIM_DIRECT_EVAL
// The generated scheduler (see RtlStream::start). Weak, so a Verilator whose
// generated code names it differently links and falls back to eval().
void Vpluecker_local_intersector___024root___eval(Vpluecker_local_intersector___024root* vlSelf)
    __attribute__((weak));
#endif

namespace pluecker::sim {

LocalRtlConfig built_local_config() {
    LocalRtlConfig c;
    c.box_bits = SIM_BOX_BITS;
    c.dir_bits = SIM_DIR_BITS;
    c.grid_bits = SIM_GRID_BITS;
    c.tag_bits = SIM_TAG_BITS;
    c.conservative = SIM_CONSERVATIVE != 0;
    c.children = SIM_CHILDREN;
    constexpr MulStyle styles[] = {MulStyle::Auto, MulStyle::Dsp, MulStyle::Lut};
    c.mul_style = styles[SIM_MUL_STYLE];
    return c;
}

const LocalPortContract& built_local_contract() {
    static const LocalPortContract contract(built_local_config());
    return contract;
}

LocalFormat built_local_format() { return built_local_contract().format(); }

std::string build_name() {
    const LocalRtlConfig c = built_local_config();
    return "K" + std::to_string(c.box_bits) + " D" + std::to_string(c.dir_bits) + " G" + std::to_string(c.grid_bits) +
           ", " + std::to_string(c.children) + (c.children == 1 ? " child, " : " children, ") +
           (c.conservative ? "conservative" : "nearest") + ", MUL_STYLE " + mul_style_name(c.mul_style);
}

PackedLocalQuery pack_local(const LocalRay& r, const LocalFrame& fr, std::span<const LocalBox> boxes) {
    const LocalQueryPorts q = pack_local_query(r, fr, boxes, built_local_contract());
    PackedLocalQuery p;
    drive(p.org, q.ray_org);
    drive(p.dir, q.ray_dir);
    drive(p.end, q.ray_end);
    drive(p.frame_org, q.frame_org);
    drive(p.lo, q.box_min);
    drive(p.hi, q.box_max);
    p.frame_exp = static_cast<decltype(p.frame_exp)>(q.frame_exp);
    p.cls = static_cast<std::uint8_t>(q.ray_class);
    p.end_valid = static_cast<std::uint8_t>(q.ray_end_valid);
    return p;
}

bool same_ray(const LocalRay& a, const LocalRay& b) {
    return a.cls == b.cls && a.org == b.org && a.dir_g == b.dir_g && a.has_end == b.has_end &&
           (!a.has_end || a.end == b.end);
}

void PackedLocalQuery::apply(Top& t) const {
    t.ray_org_i = org;
    t.ray_dir_i = dir;
    t.ray_end_i = end;
    t.frame_org_i = frame_org;
    t.frame_exp_i = frame_exp;
    t.box_min_i = lo;
    t.box_max_i = hi;
    t.ray_class_i = cls;
    t.ray_end_valid_i = end_valid;
}

RtlLocal::RtlLocal() : RtlStream(SIM_TAG_BITS, "pluecker_local_intersector") {
    Vpluecker_local_intersector& t = top();
    const LocalPortContract& c = built_local_contract();
    auto width = [&](const char* name) { return c.port(name).width(); };
    check_port<PortType<decltype(t.in_tag_i)>>("in_tag_i", width("in_tag_i"));
    check_port<PortType<decltype(t.ray_org_i)>>("ray_org_i", width("ray_org_i"));
    check_port<PortType<decltype(t.ray_dir_i)>>("ray_dir_i", width("ray_dir_i"));
    check_port<PortType<decltype(t.ray_end_i)>>("ray_end_i", width("ray_end_i"));
    check_port<PortType<decltype(t.frame_org_i)>>("frame_org_i", width("frame_org_i"));
    check_port<PortType<decltype(t.frame_exp_i)>>("frame_exp_i", width("frame_exp_i"));
    check_port<PortType<decltype(t.box_min_i)>>("box_min_i", width("box_min_i"));
    check_port<PortType<decltype(t.box_max_i)>>("box_max_i", width("box_max_i"));
    check_port<PortType<decltype(t.out_tag_o)>>("out_tag_o", width("out_tag_o"));
    check_port<PortType<decltype(t.out_hit_o)>>("out_hit_o", width("out_hit_o"));
    EvalFn direct = nullptr;
#if SIM_DIRECT_EVAL
    direct = &::Vpluecker_local_intersector___024root___eval;
#endif
    start(c.latency(), direct);
}

}  // namespace pluecker::sim
