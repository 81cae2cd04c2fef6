// SPDX-License-Identifier: MIT
// A Verilated box-test unit with the intersectors' stream interface (clk_i,
// rst_i, in_valid_i/in_ready_o/in_tag_i, out_valid_o/out_ready_i/out_tag_o/
// out_hit_o) driven from C++: reset, the measured latency of one query,
// optional random backpressure, and streams of queries whose answers are
// matched by tag. Shared by the fixed-point harness (rtl_intersector.hpp,
// Vpluecker_intersector) and the binary32 units' harness (float/).
//
// Clocking, each cycle: drive the inputs with the clock low and evaluate
// (combinational outputs settle), sample in_ready_o, out_valid_o, the tag
// and the hit, then raise the clock and evaluate. At most 2^TAG_BITS queries
// are in flight, so a tag names one of them.
#pragma once

#include "verilated.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>

namespace pluecker::sim {

// The RTL broke the stream protocol (an answer nobody asked for, a wrong
// tag, no progress): a harness or RTL bug, not bad input.
struct ProtocolError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

template <class T>
using PortType = std::remove_cv_t<std::remove_reference_t<T>>;

// Counters of one unit since construction.
struct StreamStats {
    std::uint64_t cycles = 0;       // clock cycles simulated (reset excluded)
    std::uint64_t queries = 0;      // answers received
    std::uint64_t stall_cycles = 0; // cycles with in_valid high and in_ready low
    std::uint64_t max_in_flight = 0;
};

// Top: the Verilated class. kTagBits: its TAG_BITS. direct_eval: Verilator's
// generated scheduler for Top's root (see rtl_intersector.cpp), or null for
// plain eval().
template <class Top, int kTagBits>
class StreamRtl {
public:
    using Root = std::remove_pointer_t<decltype(std::declval<Top&>().rootp)>;
    using DirectEval = void (*)(Root*);
    static constexpr std::uint64_t kTagMask = (std::uint64_t{1} << kTagBits) - 1;
    // At most 2^TAG_BITS queries are in flight, so a tag names one of them.
    static constexpr std::uint64_t kMaxInFlight = std::uint64_t{1} << kTagBits;
    // A cycle budget without any handshake before the harness gives up.
    static constexpr std::uint64_t kStallLimit = 1'000'000;

    StreamRtl(const char* name, DirectEval direct_eval) : ctx_(std::make_unique<VerilatedContext>()) {
        ctx_->randReset(0);  // deterministic initial state for anything not reset
        top_ = std::make_unique<Top>(ctx_.get(), name);
        direct_ = direct_eval;
    }
    ~StreamRtl() {
        if (top_) top_->final();
    }
    StreamRtl(const StreamRtl&) = delete;
    StreamRtl& operator=(const StreamRtl&) = delete;

    Top& top() { return *top_; }
    const StreamStats& stats() const { return stats_; }
    bool direct_eval() const { return use_direct_; }

    // Eight cycles with rst_i high; the clock is left low.
    void reset() {
        Top& t = *top_;
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
        use_direct_ = direct_ != nullptr;
    }

    void eval() {
        if (use_direct_)
            direct_(top_->rootp);
        else
            top_->eval();
    }

    // One query (the payload as it is, tag 0) with the output always ready:
    // the number of rising edges from its input to its output handshake.
    int measure_latency() {
        Top& t = *top_;
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

    // out_ready_i is high with probability p_ready each cycle (1: always),
    // drawn from a PRNG seeded with `seed`.
    void set_backpressure(double p_ready, std::uint64_t seed) {
        always_ready_ = !(p_ready < 1.0);
        const double p = p_ready < 0.0 ? 0.0 : p_ready;
        ready_threshold_ = static_cast<std::uint32_t>(p * 4294967295.0);
        rng_ = seed * 0x9e3779b97f4a7c15ull + 0x2545f4914f6cdd1dull;
        if (rng_ == 0) rng_ = 1;
    }

    // Streams queries 0..n-1 back to back (apply(t, i) drives the payload of
    // query i into the top) and stores the answer of query i in hits[i]. The
    // tag of a query is its index in the stream of all queries this unit has
    // seen, modulo 2^TAG_BITS. Throws ProtocolError.
    template <class Apply>
    void run(std::size_t n, Apply&& apply, std::uint8_t* hits) {
        Top& t = *top_;
        // Queries [base+n_out, base+n_in) are in flight; the RTL answers in
        // order, and a tag identifies one query of that window.
        const std::uint64_t base = stream_index_;
        std::uint64_t n_in = 0, n_out = 0, idle = 0, cycles = 0, stalls = 0;
        std::uint64_t max_flight = stats_.max_in_flight;
        std::uint64_t driven = ~std::uint64_t{0};
        while (n_out < n) {
            const bool want = n_in < n && n_in - n_out < kMaxInFlight;
            t.in_valid_i = want;
            if (want && driven != n_in) {
                apply(t, static_cast<std::size_t>(n_in));
                t.in_tag_i = static_cast<PortType<decltype(t.in_tag_i)>>((base + n_in) & kTagMask);
                driven = n_in;
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
                    throw ProtocolError("out_tag_o = " + std::to_string(tag) +
                                        " but the oldest query in flight has tag " + std::to_string(expect) +
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

private:
    bool draw_ready() {
        if (always_ready_) return true;
        // xorshift64*
        rng_ ^= rng_ >> 12;
        rng_ ^= rng_ << 25;
        rng_ ^= rng_ >> 27;
        const auto r = static_cast<std::uint32_t>((rng_ * 0x2545f4914f6cdd1dull) >> 32);
        return r < ready_threshold_;
    }

    std::unique_ptr<VerilatedContext> ctx_;
    std::unique_ptr<Top> top_;
    DirectEval direct_ = nullptr;
    bool use_direct_ = false;
    StreamStats stats_;
    std::uint64_t stream_index_ = 0;     // queries issued so far (tag source)
    std::uint32_t ready_threshold_ = 0;  // out_ready when rng < threshold; 0 = always
    bool always_ready_ = true;
    std::uint64_t rng_ = 0x9e3779b97f4a7c15ull;
};

// Number of data bits a Verilated port type can carry (integer or VlWide).
template <class Port>
constexpr int port_capacity() {
    if constexpr (VlIsVlWide<Port>::value)
        return static_cast<int>(Port::Words) * 32;
    else
        return static_cast<int>(sizeof(Port)) * 8;
}

// A Verilated port holds a width in the smallest type that does
// (Verilator's choice); ProtocolError when `Port` is not that type for
// `width` bits (the configurations of the RTL and the harness differ).
template <class Port>
void check_port_width(const char* name, int width) {
    const int cap = port_capacity<Port>();
    const int need = width <= 8 ? 8 : width <= 16 ? 16 : width <= 32 ? 32 : width <= 64 ? 64 : (width + 31) / 32 * 32;
    if (cap != need)
        throw ProtocolError(std::string(name) + ": the Verilated port holds " + std::to_string(cap) +
                            " bits, the port contract's width is " + std::to_string(width));
}

// A port value of the contract's encoding (32-bit words, least significant
// first, zero above the port) into a port that is either a plain integer (up
// to 64 bits) or a VlWide word array.
template <class Port, class Words>
void drive_port(Port& port, const Words& w) {
    if constexpr (VlIsVlWide<Port>::value) {
        static_assert(sizeof(port.m_storage[0]) == 4, "VlWide words are 32 bits");
        static_assert(Port::Words <= std::tuple_size_v<Words>, "port wider than the contract's words");
        for (std::size_t k = 0; k < Port::Words; ++k) port.m_storage[k] = w[k];
    } else {
        static_assert(std::is_integral_v<Port>, "narrow ports are integers");
        port = static_cast<Port>(w[0] | (static_cast<std::uint64_t>(w[1]) << 32));
    }
}

}  // namespace pluecker::sim
