// SPDX-License-Identifier: MIT
// The Verilated cascade (rtl/pluecker_cascade.sv) behind the streaming
// interface of the other harnesses (run, set_backpressure, stats;
// rtl_stream.hpp): N narrow lanes, each a TERNARY intersector taking a
// query in both formats, whose uncertain answers one wide unit re-tests.
//
// A batch of queries is spread over the lanes round-robin and every lane
// is driven every clock. An answer leaves on one of two streams: a certain
// one on its lane's own out_* stream (in the order of the lane's queries),
// an uncertain one on the shared esc_* stream, named by esc_lane_o and
// esc_tag_o (in order per lane). The harness matches both by (lane, tag)
// and records which stream each query's answer took; the caller checks
// that against the model (a certain answer must be the model's narrow one,
// an escalated one the wide test of a query the model finds uncertain).
// Every query is answered exactly once: a second answer, an answer nobody
// asked for or one out of order is a ProtocolError.
//
// N_NARROW, the widths, TAG_BITS and PIPELINE are fixed when the harness is
// built (sim/build.sh with SIM_UNIT=cascade passes them to Verilator as -G
// parameters and to this code as SIM_* macros). The port encoding of each
// format and the LATENCY of each unit are the port contract's
// (pluecker/contract.hpp): the constructor checks every port's width and
// measures, in every lane, the latency of a certain answer (the narrow
// unit's LATENCY and a clock in the lane's answer register) and of an
// escalated one (that, a clock in the lane's escalation slot, one in the
// registered grant and one in the wide unit's input register, wide
// LATENCY).
//
// Clocking, per cycle: drive every lane's inputs with the clock low and
// evaluate, sample the output streams (esc_* first, then every lane's), the
// input handshakes, then raise the clock and evaluate. At most 2^TAG_BITS
// queries of a lane are unanswered at once, so a tag names one of them.
#pragma once

#include "Vpluecker_cascade.h"
#include "array/lanes.hpp"
#include "rtl_stream.hpp"

#include "pluecker/contract.hpp"
#include "pluecker/rng.hpp"
#include "pluecker/ternary.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#ifndef SIM_CASCADE_N
#error "SIM_CASCADE_N must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_NARROW_COORD_BITS
#error "SIM_NARROW_COORD_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_NARROW_DIR_BITS
#error "SIM_NARROW_DIR_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_WIDE_COORD_BITS
#error "SIM_WIDE_COORD_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_WIDE_DIR_BITS
#error "SIM_WIDE_DIR_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_TAG_BITS
#error "SIM_TAG_BITS must be defined (sim/build.sh passes it)"
#endif
#ifndef SIM_PIPELINE
#define SIM_PIPELINE 0
#endif
static_assert(SIM_CASCADE_N >= 1 && SIM_CASCADE_N <= 64, "the cascade has 1..64 narrow lanes");
static_assert(SIM_WIDE_COORD_BITS >= SIM_NARROW_COORD_BITS && SIM_WIDE_DIR_BITS >= SIM_NARROW_DIR_BITS,
              "the wide format is at least as wide as the narrow one");

namespace pluecker::sim {

inline constexpr int kLanes = SIM_CASCADE_N;
// Bits of a lane number ($clog2(N_NARROW), at least 1), the width of esc_lane_o.
inline constexpr int kLaneBits = kLanes > 1 ? static_cast<int>(std::bit_width(unsigned(kLanes - 1))) : 1;

// The port contracts of the narrow units and of the wide unit (whose tag
// carries the lane), and the formats they compute.
const PortContract& narrow_contract();
const PortContract& wide_contract();
CascadeFormats built_formats();
// "2 lanes 8x8 -> 16x16" for messages.
std::string build_name();

// One query as the cascade takes it: the same float query set up in the
// narrow format (ray_*_i, box_*_i) and in the wide one (wide_*_i), each
// packed by the port contract (pack_query).
struct CascadeQuery {
    QueryPorts narrow;
    QueryPorts wide;
};

// The stream an answer left the cascade on.
enum class AnswerPath : std::uint8_t { None = 0, Lane = 1, Escalated = 2 };
const char* path_name(AnswerPath p);

// Counters of one lane since construction.
struct CascadeLaneStats {
    std::uint64_t certain = 0;        // answers on the lane's own stream
    std::uint64_t escalated = 0;      // answers of the lane's queries on esc_*
    std::uint64_t stall_cycles = 0;   // cycles with in_valid high and in_ready low
    std::uint64_t max_in_flight = 0;  // most unanswered queries at once
    std::uint64_t dropped = 0;        // unanswered at a reset, sent again after it
};

class CascadeRtl {
public:
    using Top = Vpluecker_cascade;
    static constexpr int kTagBits = SIM_TAG_BITS;

    // Checks the ports against the contracts and measures every lane's two
    // latencies; ProtocolError when one is not the contracts'.
    CascadeRtl();
    ~CascadeRtl();
    CascadeRtl(const CascadeRtl&) = delete;
    CascadeRtl& operator=(const CascadeRtl&) = delete;

    // Each lane's out_ready_i and esc_ready_i high with probability p_ready
    // each cycle (1: always), each drawn on its own from a PRNG seeded with
    // `seed`.
    void set_backpressure(double p_ready, std::uint64_t seed);
    // A lane with a query waiting raises in_valid_i with probability p_valid
    // each cycle (1: always); once raised, it stays high until the handshake.
    void set_idle(double p_valid);
    // A reset (rst_i high for 1 to 3 cycles) after every `cycles` cycles of
    // streaming on average (0: never): every unanswered query is dropped and
    // sent again after the reset with a new tag; no answer of a dropped one
    // may appear.
    void set_resets(std::uint64_t cycles);

    // Spreads q[0..n) over the lanes round-robin (continuing where the last
    // run stopped) and streams them; hits[i] is the answer of q[i] and
    // paths[i] the stream it left on. Throws ProtocolError.
    void run(const CascadeQuery* q, std::size_t n, std::uint8_t* hits, AnswerPath* paths);

    // Every lane together (max_in_flight: of all lanes at once).
    const StreamStats& stats() const { return stats_; }
    const std::vector<CascadeLaneStats>& lane_stats() const { return lane_stats_; }
    std::uint64_t escalated() const { return escalated_; }
    // Cycles with esc_valid_o high and esc_ready_i low.
    std::uint64_t esc_stall_cycles() const { return esc_stalls_; }
    std::uint64_t resets() const { return resets_; }
    // Input to output handshake, per lane: a certain and an escalated answer.
    const std::vector<int>& certain_latency() const { return certain_latency_; }
    const std::vector<int>& escalated_latency() const { return escalated_latency_; }
    bool direct_eval() const { return direct_ != nullptr; }

private:
    using Root = std::remove_pointer_t<decltype(std::declval<Top&>().rootp)>;
    using EvalFn = void (*)(Root*);
    static constexpr std::uint64_t kStallLimit = 1'000'000;

    // A query a lane sent: its index in the batch and its sequence number
    // in the lane (tag = seq mod 2^TAG_BITS).
    struct Sent {
        std::uint32_t index = 0;
        std::uint64_t seq = 0;
        bool answered = false;
    };
    // One lane during a run. `flight` holds the sent queries from the oldest
    // unanswered one on, with consecutive sequence numbers; answers on each
    // stream must come in increasing seq (`certain_next`, `esc_next`: the
    // lowest seq the next one may have).
    struct Lane {
        std::deque<std::uint32_t> todo;  // batch indices not sent yet, in order
        std::deque<Sent> flight;
        std::uint64_t seq = 0;           // queries sent so far, across runs
        std::uint64_t certain_next = 0, esc_next = 0;
        std::uint64_t driven = UINT64_MAX;  // seq whose query is on the lane's ports
        bool offered = false;               // in_valid_i high this cycle
    };

    void check_ports();
    void eval();
    void hard_reset();
    void clear_inputs();
    void drive(int l, const CascadeQuery& q, std::uint64_t tag);
    void measure_latencies(int lane);
    int measure(int lane, const CascadeQuery& q, AnswerPath expect);
    void assign(std::size_t n);
    void offer(int l, const CascadeQuery* q);
    void draw_ready();
    bool take_input(int l);
    Sent& find(int l, std::uint64_t tag, const std::string& where);
    void record(int l, Sent& s, bool hit, AnswerPath path, std::uint8_t* hits, AnswerPath* paths);
    bool take_certain(int l, std::uint8_t* hits, AnswerPath* paths);
    bool take_escalated(std::uint8_t* hits, AnswerPath* paths);
    void cycle(const CascadeQuery* q, std::uint8_t* hits, AnswerPath* paths);
    void reset_mid_stream();
    void finish_run(std::size_t n);
    bool draw(std::uint32_t threshold);

    std::unique_ptr<VerilatedContext> ctx_;
    std::unique_ptr<Top> top_;
    EvalFn direct_ = nullptr;
    std::vector<Lane> lanes_;
    std::vector<CascadeLaneStats> lane_stats_;
    std::vector<int> certain_latency_, escalated_latency_;
    StreamStats stats_;
    std::uint64_t tag_mask_;
    std::uint64_t max_in_flight_;
    std::size_t next_lane_ = 0;  // round-robin start of the next run
    std::uint64_t idle_ = 0;     // cycles without any handshake
    std::size_t answered_ = 0;   // answers of the current run
    std::uint64_t escalated_ = 0;
    std::uint64_t esc_stalls_ = 0;
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
