// SPDX-License-Identifier: MIT
// Driving the Verilated intersector: port packing, reset and the clock loop.
#include "rtl_intersector.hpp"

#include <array>
#include <string>

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

// Three fields of `bits` bits each, x in the low bits, into a port that is
// either a plain integer (up to 64 bits) or a VlWide word array. Every field
// is masked to its width, so the bits above the port stay zero as Verilator
// requires of inputs.
template <class Port>
void pack3(Port& port, const std::array<std::int64_t, 3>& v, int bits) {
    const std::uint64_t mask = (std::uint64_t{1} << bits) - 1;
    if constexpr (VlIsVlWide<Port>::value) {
        static_assert(sizeof(port.m_storage[0]) == 4, "VlWide words are 32 bits");
        for (std::size_t w = 0; w < Port::Words; ++w) port.m_storage[w] = 0;
        for (int a = 0; a < 3; ++a) {
            const std::uint64_t u = static_cast<std::uint64_t>(v[a]) & mask;
            const int pos = a * bits;
            const int word = pos / 32, shift = pos % 32;
            port.m_storage[word] |= static_cast<std::uint32_t>(u << shift);
            if (shift + bits > 32) port.m_storage[word + 1] |= static_cast<std::uint32_t>(u >> (32 - shift));
        }
    } else {
        static_assert(std::is_integral_v<Port>, "narrow ports are integers");
        std::uint64_t w = 0;
        for (int a = 0; a < 3; ++a) w |= (static_cast<std::uint64_t>(v[a]) & mask) << (a * bits);
        port = static_cast<Port>(w);
    }
}

// Number of data bits a port type can carry (integer or VlWide).
template <class Port>
constexpr int port_capacity() {
    if constexpr (VlIsVlWide<Port>::value) return static_cast<int>(Port::Words) * 32;
    else return static_cast<int>(sizeof(Port)) * 8;
}

static_assert(port_capacity<decltype(PackedQuery::org)>() >= 3 * kC, "ray_org_i narrower than 3*COORD_BITS");
static_assert(port_capacity<decltype(PackedQuery::dir)>() >= 3 * kD, "ray_dir_i narrower than 3*DIR_BITS");
static_assert(port_capacity<decltype(PackedQuery::org)>() < 3 * kC + 32, "ray_org_i wider than 3*COORD_BITS");
static_assert(port_capacity<decltype(PackedQuery::dir)>() < 3 * kD + 32, "ray_dir_i wider than 3*DIR_BITS");

}  // namespace

FixedFormat built_format() {
    FixedFormat f;
    f.coord_bits = kC;
    f.dir_bits = kD;
    f.mode = SIM_CONSERVATIVE ? FixedMode::Conservative : FixedMode::Nearest;
    return f;
}

PackedQuery pack_query(const FixedRay& r, const FixedBox& b) {
    PackedQuery p;
    pack3(p.org, r.org, kC);
    pack3(p.dir, r.dir, kD);
    pack3(p.end, r.has_end ? r.end : std::array<std::int64_t, 3>{0, 0, 0}, kC);
    pack3(p.lo, b.lo, kC);
    pack3(p.hi, b.hi, kC);
    p.cls = static_cast<std::uint8_t>(r.cls & 7u);
    p.end_valid = r.has_end ? 1 : 0;
    return p;
}

RtlIntersector::RtlIntersector() : ctx_(std::make_unique<VerilatedContext>()) {
    ctx_->randReset(0);  // deterministic initial state for anything not reset
    top_ = std::make_unique<Vpluecker_intersector>(ctx_.get(), "pluecker_intersector");
    reset();
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
