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
// A cycle budget without any handshake before the harness gives up.
constexpr std::uint64_t kStallLimit = 1'000'000;

// A port value of the contract's encoding (32-bit words, least significant
// first, zero above the port) into a port that is either a plain integer (up
// to 64 bits) or a VlWide word array.
template <class Port>
void drive(Port& port, const PortWords& w) {
    if constexpr (VlIsVlWide<Port>::value) {
        static_assert(sizeof(port.m_storage[0]) == 4, "VlWide words are 32 bits");
        static_assert(Port::Words <= std::tuple_size_v<PortWords>, "port wider than the contract's 72 bits");
        for (std::size_t k = 0; k < Port::Words; ++k) port.m_storage[k] = w[k];
    } else {
        static_assert(std::is_integral_v<Port>, "narrow ports are integers");
        port = static_cast<Port>(w[0] | (static_cast<std::uint64_t>(w[1]) << 32));
    }
}

// Number of data bits a port type can carry (integer or VlWide).
template <class Port>
constexpr int port_capacity() {
    if constexpr (VlIsVlWide<Port>::value) return static_cast<int>(Port::Words) * 32;
    else return static_cast<int>(sizeof(Port)) * 8;
}

// A Verilated port must hold the contract's width in the smallest type that
// does (Verilator's choice), or the configurations of the RTL and the
// harness differ.
template <class Port>
void check_port(const char* name) {
    const int width = built_contract().port(name).width();
    const int cap = port_capacity<Port>();
    const int need = width <= 8 ? 8 : width <= 16 ? 16 : width <= 32 ? 32 : width <= 64 ? 64 : (width + 31) / 32 * 32;
    if (cap != need)
        throw ProtocolError(std::string(name) + ": the Verilated port holds " + std::to_string(cap) +
                            " bits, the port contract's width is " + std::to_string(width));
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
    drive(p.org, q.ray_org);
    drive(p.dir, q.ray_dir);
    drive(p.end, q.ray_end);
    drive(p.lo, q.box_min);
    drive(p.hi, q.box_max);
    p.cls = static_cast<std::uint8_t>(q.ray_class);
    p.end_valid = static_cast<std::uint8_t>(q.ray_end_valid);
    return p;
}

RtlIntersector::RtlIntersector() : ctx_(std::make_unique<VerilatedContext>()) {
    ctx_->randReset(0);  // deterministic initial state for anything not reset
    top_ = std::make_unique<Vpluecker_intersector>(ctx_.get(), "pluecker_intersector");
    Vpluecker_intersector& t = *top_;
    check_port<PortType<decltype(t.in_tag_i)>>("in_tag_i");
    check_port<PortType<decltype(t.ray_org_i)>>("ray_org_i");
    check_port<PortType<decltype(t.ray_dir_i)>>("ray_dir_i");
    check_port<PortType<decltype(t.ray_end_i)>>("ray_end_i");
    check_port<PortType<decltype(t.box_min_i)>>("box_min_i");
    check_port<PortType<decltype(t.box_max_i)>>("box_max_i");
    check_port<PortType<decltype(t.out_tag_o)>>("out_tag_o");
    reset();
    latency_ = measure_latency();
    if (latency_ != built_contract().latency())
        throw ProtocolError("the RTL answers after " + std::to_string(latency_) +
                            " cycles, the port contract's LATENCY is " + std::to_string(built_contract().latency()));
    reset();
}

// One query (all ports zero) with the output always ready: the number of
// rising edges from its input handshake to its output handshake.
int RtlIntersector::measure_latency() {
    Vpluecker_intersector& t = *top_;
    const PortWords zero{};
    drive(t.ray_org_i, zero);
    drive(t.ray_dir_i, zero);
    drive(t.ray_end_i, zero);
    drive(t.box_min_i, zero);
    drive(t.box_max_i, zero);
    t.ray_class_i = 0;
    t.ray_end_valid_i = 0;
    t.in_tag_i = 0;
    t.out_ready_i = 1;
    t.in_valid_i = 1;
    int fired = -1;
    for (int edge = 0; edge < 256; ++edge) {
        t.clk_i = 0;
        eval();
        if (fired < 0 && t.in_ready_o) fired = edge;
        const bool out = fired >= 0 && t.out_valid_o;
        t.clk_i = 1;
        eval();
        if (fired >= 0) t.in_valid_i = 0;
        if (out) {
            t.out_ready_i = 0;
            t.clk_i = 0;
            eval();
            return edge - fired;
        }
    }
    throw ProtocolError("no answer within 256 cycles of one query");
}

RtlIntersector::~RtlIntersector() {
    if (top_) top_->final();
}

void RtlIntersector::reset() {
    Vpluecker_intersector& t = *top_;
    t.in_valid_i = 0;
    t.out_ready_i = 0;
    t.rst_i = 1;
    for (int i = 0; i < 8; ++i) {
        t.clk_i = 0;
        t.eval();
        t.clk_i = 1;
        t.eval();
    }
    t.rst_i = 0;
    t.clk_i = 0;
    t.eval();
#if SIM_DIRECT_EVAL
    direct_eval_ = &::Vpluecker_intersector___024root___eval != nullptr;
#endif
}

void RtlIntersector::eval() {
#if SIM_DIRECT_EVAL
    if (direct_eval_) {
        ::Vpluecker_intersector___024root___eval(top_->rootp);
        return;
    }
#endif
    top_->eval();
}

void RtlIntersector::set_backpressure(double p_ready, std::uint64_t seed) {
    always_ready_ = !(p_ready < 1.0);
    const double p = p_ready < 0.0 ? 0.0 : p_ready;
    ready_threshold_ = static_cast<std::uint32_t>(p * 4294967295.0);
    rng_ = seed * 0x9e3779b97f4a7c15ull + 0x2545f4914f6cdd1dull;
    if (rng_ == 0) rng_ = 1;
}

bool RtlIntersector::draw_ready() {
    if (always_ready_) return true;
    // xorshift64*
    rng_ ^= rng_ >> 12;
    rng_ ^= rng_ << 25;
    rng_ ^= rng_ >> 27;
    const auto r = static_cast<std::uint32_t>((rng_ * 0x2545f4914f6cdd1dull) >> 32);
    return r < ready_threshold_;
}

void RtlIntersector::run(const PackedQuery* q, std::size_t n, std::uint8_t* hits) {
    Vpluecker_intersector& t = *top_;
    // Queries [base+n_out, base+n_in) are in flight; the RTL answers in
    // order, and a tag identifies one query of that window.
    const std::uint64_t base = stream_index_;
    std::uint64_t n_in = 0, n_out = 0, idle = 0, cycles = 0, stalls = 0;
    std::uint64_t max_flight = stats_.max_in_flight;
    const PackedQuery* driven = nullptr;
    while (n_out < n) {
        const bool want = n_in < n && n_in - n_out < kMaxInFlight;
        t.in_valid_i = want;
        if (want && driven != q + n_in) {
            const PackedQuery& p = q[n_in];
            t.ray_org_i = p.org;
            t.ray_dir_i = p.dir;
            t.ray_end_i = p.end;
            t.box_min_i = p.lo;
            t.box_max_i = p.hi;
            t.ray_class_i = p.cls;
            t.ray_end_valid_i = p.end_valid;
            t.in_tag_i = static_cast<PortType<decltype(t.in_tag_i)>>((base + n_in) & kTagMask);
            driven = q + n_in;
        }
        const bool ready = draw_ready();
        t.out_ready_i = ready;
        // Settle the combinational outputs for this cycle's inputs, decide
        // the handshakes, then the rising edge.
        t.clk_i = 0;
        eval();
        const bool fire_in = want && t.in_ready_o;
        if (want && !fire_in) ++stalls;
        bool progress = fire_in;
        if (t.out_valid_o && ready) {
            if (n_out == n_in)
                throw ProtocolError("out_valid_o with no query in flight (cycle " + std::to_string(cycles) + ")");
            const std::uint64_t tag = static_cast<std::uint64_t>(t.out_tag_o) & kTagMask;
            const std::uint64_t expect = (base + n_out) & kTagMask;
            if (tag != expect) {
                const std::uint64_t k = n_out + ((tag - expect) & kTagMask);
                throw ProtocolError("out_tag_o = " + std::to_string(tag) + " but the oldest query in flight has tag " +
                                    std::to_string(expect) +
                                    (k < n_in ? " (answer out of order)" : " (no query in flight has this tag)") +
                                    ", query " + std::to_string(base + n_out));
            }
            hits[n_out] = t.out_hit_o ? 1 : 0;
            ++n_out;
            progress = true;
        }
        t.clk_i = 1;
        eval();
        if (fire_in) ++n_in;
        if (n_in - n_out > max_flight) max_flight = n_in - n_out;
        ++cycles;
        idle = progress ? 0 : idle + 1;
        if (idle > kStallLimit)
            throw ProtocolError("no handshake for " + std::to_string(kStallLimit) + " cycles with " +
                                std::to_string(n_in - n_out) + " queries in flight and " +
                                std::to_string(n - n_in) + " waiting");
    }
    // Leave the clock low with nothing offered.
    t.in_valid_i = 0;
    t.out_ready_i = 0;
    t.clk_i = 0;
    eval();
    stream_index_ += n;
    stats_.cycles += cycles;
    stats_.queries += n;
    stats_.stall_cycles += stalls;
    stats_.max_in_flight = max_flight;
}

}  // namespace pluecker::sim
