// SPDX-License-Identifier: MIT
// The Verilated array of intersector units (rtl/pluecker_array.sv) behind
// the streaming interface of the other harnesses (run, set_backpressure,
// stats; rtl_stream.hpp): a batch of queries is spread over the N lanes
// round-robin, every lane is driven every clock, and each lane's answers
// are matched in order by its own tags.
//
// N_DSP, N_LUT, N_ROM, widths, mode, TAG_BITS and PIPELINE are fixed when
// the harness is built (sim/build.sh with SIM_UNIT=array passes them to
// Verilator as -G parameters and to this code as SIM_* macros). Lanes
// 0..N_DSP-1 are units with MUL_STYLE "dsp", the next N_LUT "lut", the
// last N_ROM "rom" (block-RAM tables, 6/6 with PIPELINE = 2). The port
// encoding of a lane and its LATENCY are the port contract's
// (pluecker/contract.hpp, one contract per multiplier style): the
// constructor checks the Verilated ports' widths (N lanes of the contract's
// width) and measures the latency of one query in every lane.
//
// Clocking, per cycle: drive every lane's inputs with the clock low and
// evaluate, sample every lane's in_ready_o, out_valid_o, tag and hit, then
// raise the clock and evaluate. At most 2^TAG_BITS queries are in flight in
// a lane, so a tag names one of them.
#pragma once

#include "Vpluecker_array.h"
#include "lanes.hpp"
#include "rtl_stream.hpp"

#include "pluecker/contract.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/rng.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#ifndef SIM_ARRAY_DSP
#error "SIM_ARRAY_DSP must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_ARRAY_LUT
#error "SIM_ARRAY_LUT must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_ARRAY_ROM
#define SIM_ARRAY_ROM 0
#endif
#ifndef SIM_COORD_BITS
#error "SIM_COORD_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_DIR_BITS
#error "SIM_DIR_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_TAG_BITS
#error "SIM_TAG_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_CONSERVATIVE
#error "SIM_CONSERVATIVE must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_PIPELINE
#define SIM_PIPELINE 0
#endif
static_assert(SIM_ARRAY_DSP >= 0 && SIM_ARRAY_LUT >= 0 && SIM_ARRAY_ROM >= 0 &&
                  SIM_ARRAY_DSP + SIM_ARRAY_LUT + SIM_ARRAY_ROM >= 1,
              "the array needs at least one unit");

namespace pluecker::sim {

inline constexpr int kDspLanes = SIM_ARRAY_DSP;
inline constexpr int kLutLanes = SIM_ARRAY_LUT;
inline constexpr int kLanes = SIM_ARRAY_DSP + SIM_ARRAY_LUT + SIM_ARRAY_ROM;

// The configuration of lane `lane`'s unit, its port contract, and the
// fixed-point format every lane computes.
RtlConfig lane_config(int lane);
const PortContract& lane_contract(int lane);
FixedFormat built_format();
// "1 dsp + 1 lut, 8x8 conservative" (+ " + 1 rom" with table units) for messages.
std::string build_name();
const char* lane_style(int lane);

// One lane's query: the port contract's encoding (pack_query).
using LaneQuery = QueryPorts;
// Packs a set-up ray and a quantised box (widths of built_format());
// InputError when an operand does not fit its port.
LaneQuery pack_lane_query(const FixedRay& r, const FixedBox& b);

// Counters of one lane since construction.
struct LaneStats {
    std::uint64_t queries = 0;        // answers received
    std::uint64_t stall_cycles = 0;   // cycles with in_valid high and in_ready low
    std::uint64_t max_in_flight = 0;
    std::uint64_t dropped = 0;        // in flight at a reset, sent again after it
};

class ArrayRtl {
public:
    using Top = Vpluecker_array;
    static constexpr int kTagBits = SIM_TAG_BITS;

    // Checks the ports against the contract, measures every lane's latency;
    // ProtocolError when it is not the contract's.
    ArrayRtl();
    ~ArrayRtl();
    ArrayRtl(const ArrayRtl&) = delete;
    ArrayRtl& operator=(const ArrayRtl&) = delete;

    // out_ready_i of each lane high with probability p_ready each cycle (1:
    // always), drawn from a PRNG seeded with `seed`.
    void set_backpressure(double p_ready, std::uint64_t seed);
    // A lane with a query waiting raises in_valid_i with probability p_valid
    // each cycle (1: always); once raised, it stays high until the handshake.
    void set_idle(double p_valid);
    // A reset (rst_i high for 1 to 3 cycles) after every `cycles` cycles of
    // streaming on average (0: never): every query in flight is dropped and
    // sent again after the reset with a new tag; no answer of a dropped one
    // may appear.
    void set_resets(std::uint64_t cycles);

    // Spreads q[0..n) over the lanes round-robin (continuing where the last
    // run stopped), streams them and stores out_hit_o of q[i] in hits[i].
    // Throws ProtocolError.
    void run(const LaneQuery* q, std::size_t n, std::uint8_t* hits);

    // Every lane together (max_in_flight: of all lanes at once).
    const StreamStats& stats() const { return stats_; }
    const std::vector<LaneStats>& lane_stats() const { return lane_stats_; }
    std::uint64_t resets() const { return resets_; }
    // Cycles from the input to the output handshake of one query, per lane.
    const std::vector<int>& measured_latency() const { return latency_; }
    bool direct_eval() const { return direct_ != nullptr; }

private:
    using Root = std::remove_pointer_t<decltype(std::declval<Top&>().rootp)>;
    using EvalFn = void (*)(Root*);
    static constexpr std::uint64_t kStallLimit = 1'000'000;

    // One lane's queue during a run: queries[k] is an index into the batch,
    // [n_out, n_in) are in flight, tag of queue position k is tag_base + k.
    struct Lane {
        std::vector<std::uint32_t> queries;
        std::size_t n_in = 0, n_out = 0;
        std::uint64_t tag_base = 0;
        std::size_t driven = SIZE_MAX;  // queue position on the lane's ports
        bool offered = false;           // in_valid_i high this cycle
    };

    void check_ports();
    void eval();
    void hard_reset();
    int measure_latency(int lane);
    void assign(std::size_t n);
    void offer(int l, const LaneQuery* q);
    void draw_ready();
    bool take_input(int l);
    bool take_output(int l, std::uint8_t* hits);
    void cycle(const LaneQuery* q, std::uint8_t* hits);
    void reset_mid_stream();
    void finish_run(std::size_t n);
    bool draw(std::uint32_t threshold);

    std::unique_ptr<VerilatedContext> ctx_;
    std::unique_ptr<Top> top_;
    EvalFn direct_ = nullptr;
    std::vector<Lane> lanes_;
    std::vector<LaneStats> lane_stats_;
    std::vector<std::uint64_t> next_tag_;  // per lane, across runs
    std::vector<int> latency_;
    StreamStats stats_;
    std::uint64_t tag_mask_;
    std::uint64_t max_in_flight_;
    std::size_t next_lane_ = 0;            // round-robin start of the next run
    std::uint64_t idle_ = 0;               // cycles without any handshake
    std::size_t answered_ = 0;             // answers of the current run
    std::uint64_t reset_every_ = 0;
    std::uint64_t until_reset_ = 0;
    std::uint64_t resets_ = 0;
    std::uint32_t ready_threshold_ = 0xffffffffu;
    std::uint32_t valid_threshold_ = 0xffffffffu;
    bool always_ready_ = true;
    bool always_valid_ = true;
    Rng rng_{1};
};

}  // namespace pluecker::sim
