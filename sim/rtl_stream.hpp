// SPDX-License-Identifier: MIT
// A Verilated valid/ready unit with a tag (pluecker_intersector,
// pluecker_local_intersector) behind a small streaming interface: queries go
// in with valid/ready, one a clock when the RTL is ready, answers come back
// matched by tag. The part both harnesses share: reset, the clock loop, the
// latency measurement, back-pressure and the port-width checks.
//
// Top is the Verilated model; it has the ports clk_i, rst_i, in_valid_i,
// in_ready_o, in_tag_i, out_valid_o, out_ready_i, out_tag_o and out_hit_o
// (up to 8 bits: one per answer of a query). Packed is one query packed
// into the model's port types, with `void apply(Top&) const` driving its
// payload; a value-initialised Packed is the all-zero query.
//
// Clocking, per cycle: drive the inputs with the clock low and evaluate
// (combinational outputs settle), sample in_ready_o, out_valid_o, the tag
// and the answer, then raise the clock and evaluate. At most 2^TAG_BITS
// queries are in flight, so a tag names one of them.
#pragma once

#include "verilated.h"

#include "pluecker/contract.hpp"

#include <array>
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

// A port value of a contract's encoding (32-bit words, least significant
// first, zero above the port) into a port that is either a plain integer (up
// to 64 bits) or a VlWide word array.
template <class Port, std::size_t N>
void drive(Port& port, const std::array<std::uint32_t, N>& w) {
    if constexpr (VlIsVlWide<Port>::value) {
        static_assert(sizeof(port.m_storage[0]) == 4, "VlWide words are 32 bits");
        static_assert(Port::Words <= N, "port wider than the contract's words");
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
void check_port(const char* name, int width) {
    const int cap = port_capacity<Port>();
    const int need = width <= 8 ? 8 : width <= 16 ? 16 : width <= 32 ? 32 : width <= 64 ? 64 : (width + 31) / 32 * 32;
    if (cap != need)
        throw ProtocolError(std::string(name) + ": the Verilated port holds " + std::to_string(cap) +
                            " bits, the port contract's width is " + std::to_string(width));
}

// Counters of one unit since construction.
struct StreamStats {
    std::uint64_t cycles = 0;        // clock cycles simulated (reset excluded)
    std::uint64_t queries = 0;       // answers received
    std::uint64_t stall_cycles = 0;  // cycles with in_valid high and in_ready low
    std::uint64_t max_in_flight = 0;
};

template <class Top, class Packed>
class RtlStream {
public:
    using Root = std::remove_pointer_t<decltype(std::declval<Top&>().rootp)>;
    // Verilator's generated scheduler (see start()); nullptr: plain eval().
    using EvalFn = void (*)(Root*);

    // The unit's TAG_BITS (1..16) and a name for messages.
    RtlStream(int tag_bits, const char* name)
        : ctx_(std::make_unique<VerilatedContext>()),
          tag_mask_((std::uint64_t{1} << tag_bits) - 1),
          max_in_flight_(std::uint64_t{1} << tag_bits) {
        ctx_->randReset(0);  // deterministic initial state for anything not reset
        top_ = std::make_unique<Top>(ctx_.get(), name);
    }
    ~RtlStream() {
        if (top_) top_->final();
    }
    RtlStream(const RtlStream&) = delete;
    RtlStream& operator=(const RtlStream&) = delete;

    Top& top() { return *top_; }

    // Resets the unit, measures the latency of one query and resets it again;
    // ProtocolError when the latency is not the contract's. `direct` is the
    // generated scheduler the harness then calls itself: Verilator's eval()
    // wraps it in per-call housekeeping (deferred deletes and the message
    // queue of multithreaded models, each behind a mutex) that these
    // single-threaded models without DPI never need.
    void start(int contract_latency, EvalFn direct) {
        reset();
        direct_ = direct;
        latency_ = measure_latency();
        if (latency_ != contract_latency)
            throw ProtocolError("the RTL answers after " + std::to_string(latency_) +
                                " cycles, the port contract's LATENCY is " + std::to_string(contract_latency));
        reset();
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

    // Streams q[0..n) back to back and stores out_hit_o of q[i] in hits[i].
    // The tag of a query is its index in the stream of all queries this unit
    // has seen, modulo 2^TAG_BITS. Throws ProtocolError.
    void run(const Packed* q, std::size_t n, std::uint8_t* hits);

    const StreamStats& stats() const { return stats_; }
    // Cycles from the input to the output handshake of one query, measured
    // by start() (it equals the port contract's LATENCY).
    int measured_latency() const { return latency_; }
    // True when the harness calls Verilator's scheduler directly.
    bool direct_eval() const { return direct_ != nullptr; }

private:
    // A cycle budget without any handshake before the harness gives up.
    static constexpr std::uint64_t kStallLimit = 1'000'000;

    void eval() {
        if (direct_) direct_(top_->rootp);
        else top_->eval();
    }

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
    }

    // One query (all ports zero) with the output always ready: the number of
    // rising edges from its input handshake to its output handshake.
    int measure_latency() {
        Top& t = *top_;
        Packed{}.apply(t);
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
    std::uint64_t tag_mask_;
    std::uint64_t max_in_flight_;
    EvalFn direct_ = nullptr;
    StreamStats stats_;
    std::uint64_t stream_index_ = 0;     // queries issued so far (tag source)
    std::uint32_t ready_threshold_ = 0;  // out_ready when rng < threshold
    bool always_ready_ = true;
    int latency_ = 0;
    std::uint64_t rng_ = 0x9e3779b97f4a7c15ull;
};

template <class Top, class Packed>
void RtlStream<Top, Packed>::run(const Packed* q, std::size_t n, std::uint8_t* hits) {
    Top& t = *top_;
    // Queries [base+n_out, base+n_in) are in flight; the RTL answers in
    // order, and a tag identifies one query of that window.
    const std::uint64_t base = stream_index_;
    std::uint64_t n_in = 0, n_out = 0, idle = 0, cycles = 0, stalls = 0;
    std::uint64_t max_flight = stats_.max_in_flight;
    const Packed* driven = nullptr;
    while (n_out < n) {
        const bool want = n_in < n && n_in - n_out < max_in_flight_;
        t.in_valid_i = want;
        if (want && driven != q + n_in) {
            q[n_in].apply(t);
            t.in_tag_i = static_cast<PortType<decltype(t.in_tag_i)>>((base + n_in) & tag_mask_);
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
            const std::uint64_t tag = static_cast<std::uint64_t>(t.out_tag_o) & tag_mask_;
            const std::uint64_t expect = (base + n_out) & tag_mask_;
            if (tag != expect) {
                const std::uint64_t k = n_out + ((tag - expect) & tag_mask_);
                throw ProtocolError("out_tag_o = " + std::to_string(tag) + " but the oldest query in flight has tag " +
                                    std::to_string(expect) +
                                    (k < n_in ? " (answer out of order)" : " (no query in flight has this tag)") +
                                    ", query " + std::to_string(base + n_out));
            }
            hits[n_out] = static_cast<std::uint8_t>(t.out_hit_o);
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
                                std::to_string(n_in - n_out) + " queries in flight and " + std::to_string(n - n_in) +
                                " waiting");
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
