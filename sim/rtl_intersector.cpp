// SPDX-License-Identifier: MIT
// Driving the Verilated intersector: port packing, reset and the clock loop.
#include "rtl_intersector.hpp"

#include <array>
#include <string>
#include <tuple>

#ifndef SIM_DIRECT_EVAL
#define SIM_DIRECT_EVAL 1
#endif

#if SIM_DIRECT_EVAL
// Verilator's eval() wraps the generated scheduler in per-call housekeeping
// (deferred deletes and the message queue of multithreaded models, each
// behind a mutex) that this single-threaded model without DPI or dynamic
// objects never needs, and that costs about a quarter of a clock cycle's
// time. Once the model is initialised (the first eval(), in reset()) the
// harness calls the scheduler itself. Weak, so a Verilator whose generated
// code names it differently links and falls back to eval().
void Vpluecker_intersector___024root___eval(Vpluecker_intersector___024root* vlSelf) __attribute__((weak));
#endif

namespace pluecker::sim {
namespace {

constexpr int kC = SIM_COORD_BITS;
constexpr int kD = SIM_DIR_BITS;

// The weak scheduler symbol (see above), or null.
RtlIntersector::Stream::DirectEval direct_eval_fn() {
#if SIM_DIRECT_EVAL
    return &::Vpluecker_intersector___024root___eval;
#else
    return nullptr;
#endif
}

template <class Port>
void check_port(const char* name) {
    check_port_width<Port>(name, built_contract().port(name).width());
}

}  // namespace

RtlConfig built_config() {
    RtlConfig c;
    c.coord_bits = kC;
    c.dir_bits = kD;
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
    drive_port(p.org, q.ray_org);
    drive_port(p.dir, q.ray_dir);
    drive_port(p.end, q.ray_end);
    drive_port(p.lo, q.box_min);
    drive_port(p.hi, q.box_max);
    p.cls = static_cast<std::uint8_t>(q.ray_class);
    p.end_valid = static_cast<std::uint8_t>(q.ray_end_valid);
    return p;
}

RtlIntersector::RtlIntersector() : rtl_(std::make_unique<Stream>("pluecker_intersector", direct_eval_fn())) {
    Vpluecker_intersector& t = rtl_->top();
    check_port<PortType<decltype(t.in_tag_i)>>("in_tag_i");
    check_port<PortType<decltype(t.ray_org_i)>>("ray_org_i");
    check_port<PortType<decltype(t.ray_dir_i)>>("ray_dir_i");
    check_port<PortType<decltype(t.ray_end_i)>>("ray_end_i");
    check_port<PortType<decltype(t.box_min_i)>>("box_min_i");
    check_port<PortType<decltype(t.box_max_i)>>("box_max_i");
    check_port<PortType<decltype(t.out_tag_o)>>("out_tag_o");
    rtl_->reset();
    // One query with every port zero.
    const PortWords zero{};
    drive_port(t.ray_org_i, zero);
    drive_port(t.ray_dir_i, zero);
    drive_port(t.ray_end_i, zero);
    drive_port(t.box_min_i, zero);
    drive_port(t.box_max_i, zero);
    t.ray_class_i = 0;
    t.ray_end_valid_i = 0;
    latency_ = rtl_->measure_latency();
    if (latency_ != built_contract().latency())
        throw ProtocolError("the RTL answers after " + std::to_string(latency_) +
                            " cycles, the port contract's LATENCY is " + std::to_string(built_contract().latency()));
    rtl_->reset();
}

void RtlIntersector::run(const PackedQuery* q, std::size_t n, std::uint8_t* hits) {
    rtl_->run(n, [q](Vpluecker_intersector& t, std::size_t i) {
        const PackedQuery& p = q[i];
        t.ray_org_i = p.org;
        t.ray_dir_i = p.dir;
        t.ray_end_i = p.end;
        t.box_min_i = p.lo;
        t.box_max_i = p.hi;
        t.ray_class_i = p.cls;
        t.ray_end_valid_i = p.end_valid;
    }, hits);
}

}  // namespace pluecker::sim
