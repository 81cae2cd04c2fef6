// SPDX-License-Identifier: MIT
// Driving the Verilated cascade: the units' contracts, the port checks, the
// latencies of every lane and the clock loop that feeds all lanes at once
// and takes answers from every lane's stream and the escalation stream.
#include "cascade_rtl.hpp"

#include <stdexcept>

#ifndef SIM_DIRECT_EVAL
#define SIM_DIRECT_EVAL 1
#endif

#if SIM_DIRECT_EVAL
// The generated scheduler (see RtlStream::start). Weak, so a Verilator whose
// generated code names it differently links and falls back to eval().
void Vpluecker_cascade___024root___eval(Vpluecker_cascade___024root* vlSelf) __attribute__((weak));
#endif

namespace pluecker::sim {
namespace {

constexpr int kNC3 = 3 * SIM_NARROW_COORD_BITS;
constexpr int kND3 = 3 * SIM_NARROW_DIR_BITS;
constexpr int kWC3 = 3 * SIM_WIDE_COORD_BITS;
constexpr int kWD3 = 3 * SIM_WIDE_DIR_BITS;
constexpr int kT = SIM_TAG_BITS;
// Clocks every answer spends in its lane's answer register (a skid register
// behind the narrow unit), and clocks an escalated answer waits between the
// units besides: one in its lane's escalation slot, one in the registered
// grant, one in the wide unit's input register (rtl/pluecker_cascade.sv).
constexpr int kAnswerCycles = 1;
constexpr int kSlotCycles = 3;

RtlConfig unit_config(int coord_bits, int dir_bits, int tag_bits) {
    RtlConfig c;
    c.coord_bits = coord_bits;
    c.dir_bits = dir_bits;
    c.tag_bits = tag_bits;
    c.conservative = true;
    c.mul_style = MulStyle::Auto;
    c.pipeline = SIM_PIPELINE;
    return c;
}

// A query the narrow format answers with a certain miss (the box behind
// the origin on every axis) or, with `uncertain`, one it is not sure about
// (every operand zero: the conservative test passes on its margin, the
// strict one fails); the model confirms which.
CascadeQuery probe(bool uncertain) {
    const CascadeFormats f = built_formats();
    FixedRay r;
    FixedBox b;
    if (!uncertain) b.lo = b.hi = {-2, -2, -2};
    const TernaryAnswer want = uncertain ? TernaryAnswer::Uncertain : TernaryAnswer::Miss;
    if (fixed_ternary(r, b, f.narrow) != want)
        throw std::logic_error(std::string("the latency probe is not a narrow ") + ternary_name(want));
    return {pack_query(r, b, f.narrow), pack_query(r, b, f.wide)};
}

}  // namespace

const PortContract& narrow_contract() {
    static const PortContract c(unit_config(SIM_NARROW_COORD_BITS, SIM_NARROW_DIR_BITS, SIM_TAG_BITS));
    return c;
}

const PortContract& wide_contract() {
    static const PortContract c(unit_config(SIM_WIDE_COORD_BITS, SIM_WIDE_DIR_BITS, kLaneBits + SIM_TAG_BITS));
    return c;
}

CascadeFormats built_formats() {
    CascadeFormats f{narrow_contract().format(), wide_contract().format()};
    f.validate();
    return f;
}

std::string build_name() {
    const CascadeFormats f = built_formats();
    return std::to_string(kLanes) + (kLanes == 1 ? " lane " : " lanes ") + std::to_string(f.narrow.coord_bits) + "x" +
           std::to_string(f.narrow.dir_bits) + " -> " + std::to_string(f.wide.coord_bits) + "x" +
           std::to_string(f.wide.dir_bits);
}

const char* path_name(AnswerPath p) {
    switch (p) {
        case AnswerPath::Lane: return "lane";
        case AnswerPath::Escalated: return "escalated";
        case AnswerPath::None: break;
    }
    return "none";
}

CascadeRtl::CascadeRtl()
    : ctx_(std::make_unique<VerilatedContext>()),
      lanes_(kLanes),
      lane_stats_(kLanes),
      tag_mask_((std::uint64_t{1} << SIM_TAG_BITS) - 1),
      max_in_flight_(std::uint64_t{1} << SIM_TAG_BITS) {
    ctx_->randReset(0);  // deterministic initial state for anything not reset
    top_ = std::make_unique<Top>(ctx_.get(), "pluecker_cascade");
    check_ports();
    hard_reset();
#if SIM_DIRECT_EVAL
    direct_ = &::Vpluecker_cascade___024root___eval;
#endif
    for (int l = 0; l < kLanes; ++l) measure_latencies(l);
}

CascadeRtl::~CascadeRtl() {
    if (top_) top_->final();
}

// Every lane port holds N lanes of its unit's contract width, in the
// smallest type that does; esc_* are one stream of the wide unit.
void CascadeRtl::check_ports() {
    Top& t = *top_;
    const PortContract& n = narrow_contract();
    const PortContract& w = wide_contract();
    auto lanes = [&]<class P>(const P&, const char* name, const PortContract& c, const char* unit_port) {
        check_port<PortType<P>>(name, kLanes * c.port(unit_port).width());
    };
    auto narrow = [&]<class P>(const P& p, const char* name) { lanes(p, name, n, name); };
    // wide_<port>: lane fields of the wide unit's <port>.
    auto wide = [&]<class P>(const P& p, const char* name, const char* unit_port) { lanes(p, name, w, unit_port); };
    narrow(t.in_valid_i, "in_valid_i");
    narrow(t.in_ready_o, "in_ready_o");
    narrow(t.in_tag_i, "in_tag_i");
    narrow(t.ray_class_i, "ray_class_i");
    narrow(t.ray_org_i, "ray_org_i");
    narrow(t.ray_dir_i, "ray_dir_i");
    narrow(t.ray_end_i, "ray_end_i");
    narrow(t.ray_end_valid_i, "ray_end_valid_i");
    narrow(t.box_min_i, "box_min_i");
    narrow(t.box_max_i, "box_max_i");
    wide(t.wide_ray_class_i, "wide_ray_class_i", "ray_class_i");
    wide(t.wide_ray_org_i, "wide_ray_org_i", "ray_org_i");
    wide(t.wide_ray_dir_i, "wide_ray_dir_i", "ray_dir_i");
    wide(t.wide_ray_end_i, "wide_ray_end_i", "ray_end_i");
    wide(t.wide_ray_end_valid_i, "wide_ray_end_valid_i", "ray_end_valid_i");
    wide(t.wide_box_min_i, "wide_box_min_i", "box_min_i");
    wide(t.wide_box_max_i, "wide_box_max_i", "box_max_i");
    narrow(t.out_valid_o, "out_valid_o");
    narrow(t.out_ready_i, "out_ready_i");
    narrow(t.out_tag_o, "out_tag_o");
    narrow(t.out_hit_o, "out_hit_o");
    check_port<PortType<decltype(t.esc_valid_o)>>("esc_valid_o", w.port("out_valid_o").width());
    check_port<PortType<decltype(t.esc_ready_i)>>("esc_ready_i", w.port("out_ready_i").width());
    check_port<PortType<decltype(t.esc_lane_o)>>("esc_lane_o", kLaneBits);
    check_port<PortType<decltype(t.esc_tag_o)>>("esc_tag_o", w.port("out_tag_o").width() - kLaneBits);
    check_port<PortType<decltype(t.esc_hit_o)>>("esc_hit_o", w.port("out_hit_o").width());
}

void CascadeRtl::eval() {
    if (direct_) direct_(top_->rootp);
    else top_->eval();
}

// rst_i for eight cycles with nothing offered (plain eval(): the first
// evaluations initialise the model).
void CascadeRtl::hard_reset() {
    Top& t = *top_;
    clear(t.in_valid_i);
    clear(t.out_ready_i);
    t.esc_ready_i = 0;
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

// Every lane's payload and tag to zero, nothing offered, every output ready.
void CascadeRtl::clear_inputs() {
    Top& t = *top_;
    clear(t.ray_class_i);
    clear(t.ray_org_i);
    clear(t.ray_dir_i);
    clear(t.ray_end_i);
    clear(t.ray_end_valid_i);
    clear(t.box_min_i);
    clear(t.box_max_i);
    clear(t.wide_ray_class_i);
    clear(t.wide_ray_org_i);
    clear(t.wide_ray_dir_i);
    clear(t.wide_ray_end_i);
    clear(t.wide_ray_end_valid_i);
    clear(t.wide_box_min_i);
    clear(t.wide_box_max_i);
    clear(t.in_tag_i);
    clear(t.in_valid_i);
    for (int l = 0; l < kLanes; ++l) set_bit(t.out_ready_i, l, true);
    t.esc_ready_i = 1;
}

// Lane l's payload in both formats and its tag.
void CascadeRtl::drive(int l, const CascadeQuery& q, std::uint64_t tag) {
    Top& t = *top_;
    set_lane(t.ray_org_i, l, kNC3, q.narrow.ray_org);
    set_lane(t.ray_dir_i, l, kND3, q.narrow.ray_dir);
    set_lane(t.ray_end_i, l, kNC3, q.narrow.ray_end);
    set_lane(t.box_min_i, l, kNC3, q.narrow.box_min);
    set_lane(t.box_max_i, l, kNC3, q.narrow.box_max);
    set_bits(t.ray_class_i, 3 * l, 3, q.narrow.ray_class);
    set_bit(t.ray_end_valid_i, l, q.narrow.ray_end_valid != 0);
    set_lane(t.wide_ray_org_i, l, kWC3, q.wide.ray_org);
    set_lane(t.wide_ray_dir_i, l, kWD3, q.wide.ray_dir);
    set_lane(t.wide_ray_end_i, l, kWC3, q.wide.ray_end);
    set_lane(t.wide_box_min_i, l, kWC3, q.wide.box_min);
    set_lane(t.wide_box_max_i, l, kWC3, q.wide.box_max);
    set_bits(t.wide_ray_class_i, 3 * l, 3, q.wide.ray_class);
    set_bit(t.wide_ray_end_valid_i, l, q.wide.ray_end_valid != 0);
    set_bits(t.in_tag_i, kT * l, kT, static_cast<std::uint32_t>(tag & tag_mask_));
}

// A certain answer takes the narrow unit's LATENCY plus kAnswerCycles; an
// escalated one, with the wide unit idle, that plus kSlotCycles plus the wide
// unit's.
void CascadeRtl::measure_latencies(int lane) {
    const std::string who = "lane " + std::to_string(lane) + ": ";
    const int certain = measure(lane, probe(false), AnswerPath::Lane);
    const int escalated = measure(lane, probe(true), AnswerPath::Escalated);
    const int want_certain = narrow_contract().latency() + kAnswerCycles;
    const int want_escalated = want_certain + kSlotCycles + wide_contract().latency();
    if (certain != want_certain)
        throw ProtocolError(who + "a certain answer after " + std::to_string(certain) +
                            " cycles, the narrow unit's LATENCY (port contract) and the answer register add up to " +
                            std::to_string(want_certain));
    if (escalated != want_escalated)
        throw ProtocolError(who + "an escalated answer after " + std::to_string(escalated) +
                            " cycles, the narrow unit's LATENCY, the clocks between the units and the wide unit's LATENCY add up to " +
                            std::to_string(want_escalated));
    certain_latency_.push_back(certain);
    escalated_latency_.push_back(escalated);
}

// One query in lane `lane` alone (tag 0), every output ready: the rising
// edges from its input handshake to its output handshake, which must be on
// the `expect` stream; no other lane may answer.
int CascadeRtl::measure(int lane, const CascadeQuery& q, AnswerPath expect) {
    Top& t = *top_;
    const std::string who = "lane " + std::to_string(lane) + ": ";
    clear_inputs();
    drive(lane, q, 0);
    set_bit(t.in_valid_i, lane, true);
    int fired = -1;
    for (int edge = 0; edge < 256; ++edge) {
        t.clk_i = 0;
        eval();
        for (int l = 0; l < kLanes; ++l)
            if (l != lane && get_bit(t.out_valid_o, l))
                throw ProtocolError("lane " + std::to_string(l) + " answers a query of lane " + std::to_string(lane));
        if (fired < 0 && get_bit(t.in_ready_o, lane)) fired = edge;
        const bool on_lane = fired >= 0 && get_bit(t.out_valid_o, lane);
        const bool on_esc = fired >= 0 && t.esc_valid_o;
        if (on_lane || on_esc) {
            const AnswerPath got = on_esc ? AnswerPath::Escalated : AnswerPath::Lane;
            if (got != expect || (on_lane && on_esc))
                throw ProtocolError(who + "the latency probe (a narrow " +
                                    (expect == AnswerPath::Lane ? "miss" : "uncertain answer") + ") answered on the " +
                                    (on_lane && on_esc ? "lane and the escalation" : path_name(got)) + " stream");
            if (on_esc && (t.esc_lane_o != lane || t.esc_tag_o != 0))
                throw ProtocolError(who + "escalated answer names lane " + std::to_string(t.esc_lane_o) + " tag " +
                                    std::to_string(t.esc_tag_o) + ", not lane " + std::to_string(lane) + " tag 0");
        }
        t.clk_i = 1;
        eval();
        if (fired >= 0) set_bit(t.in_valid_i, lane, false);
        if (on_lane || on_esc) {
            hard_reset();
            return edge - fired;
        }
    }
    throw ProtocolError(who + "no answer within 256 cycles of one query");
}

void CascadeRtl::set_backpressure(double p_ready, std::uint64_t seed) {
    always_ready_ = !(p_ready < 1.0);
    ready_threshold_ = static_cast<std::uint32_t>((p_ready < 0.0 ? 0.0 : p_ready) * 4294967295.0);
    rng_ = Rng(seed * 0x9e3779b97f4a7c15ull + 0x2545f4914f6cdd1dull);
}

void CascadeRtl::set_idle(double p_valid) {
    always_valid_ = !(p_valid < 1.0);
    valid_threshold_ = static_cast<std::uint32_t>((p_valid < 0.0 ? 0.0 : p_valid) * 4294967295.0);
}

void CascadeRtl::set_resets(std::uint64_t cycles) {
    reset_every_ = cycles;
    until_reset_ = cycles ? cycles / 2 + rng_.next() % (cycles + 1) : 0;
}

bool CascadeRtl::draw(std::uint32_t threshold) { return static_cast<std::uint32_t>(rng_.next() >> 32) < threshold; }

// The batch round-robin over the lanes, from the lane after the last run's
// last query.
void CascadeRtl::assign(std::size_t n) {
    for (Lane& ln : lanes_) {
        ln.todo.clear();
        ln.flight.clear();
        ln.driven = UINT64_MAX;
        ln.offered = false;
    }
    for (std::size_t i = 0; i < n; ++i)
        lanes_[(next_lane_ + i) % kLanes].todo.push_back(static_cast<std::uint32_t>(i));
    next_lane_ = (next_lane_ + n) % kLanes;
}

// in_valid_i of lane l and, for a new query, its payload and tag.
void CascadeRtl::offer(int l, const CascadeQuery* q) {
    Lane& ln = lanes_[static_cast<std::size_t>(l)];
    const bool waiting = !ln.todo.empty() && ln.flight.size() < max_in_flight_;
    if (!ln.offered) ln.offered = waiting && (always_valid_ || draw(valid_threshold_));
    set_bit(top_->in_valid_i, l, ln.offered);
    if (!ln.offered || ln.driven == ln.seq) return;
    drive(l, q[ln.todo.front()], ln.seq);
    ln.driven = ln.seq;
}

void CascadeRtl::draw_ready() {
    for (int l = 0; l < kLanes; ++l) set_bit(top_->out_ready_i, l, always_ready_ || draw(ready_threshold_));
    top_->esc_ready_i = always_ready_ || draw(ready_threshold_);
}

// The input handshake of lane l this cycle (sampled with the clock low).
bool CascadeRtl::take_input(int l) {
    Lane& ln = lanes_[static_cast<std::size_t>(l)];
    CascadeLaneStats& ls = lane_stats_[static_cast<std::size_t>(l)];
    if (!ln.offered) return false;
    if (!get_bit(top_->in_ready_o, l)) {
        ++ls.stall_cycles;
        ++stats_.stall_cycles;
        return false;
    }
    ln.flight.push_back({ln.todo.front(), ln.seq, false});
    ln.todo.pop_front();
    ++ln.seq;
    ln.offered = false;
    if (ln.flight.size() > ls.max_in_flight) ls.max_in_flight = ln.flight.size();
    return true;
}

// The unanswered query of lane l with tag `tag` (the flight's sequence
// numbers are consecutive, so the tag gives its position).
CascadeRtl::Sent& CascadeRtl::find(int l, std::uint64_t tag, const std::string& where) {
    Lane& ln = lanes_[static_cast<std::size_t>(l)];
    if (ln.flight.empty()) throw ProtocolError(where + ": an answer with no query of the lane in flight");
    const std::uint64_t at = (tag - ln.flight.front().seq) & tag_mask_;
    if (at >= ln.flight.size())
        throw ProtocolError(where + ": tag " + std::to_string(tag) + " names no query of the lane in flight");
    Sent& s = ln.flight[at];
    if (s.answered) throw ProtocolError(where + ": tag " + std::to_string(tag) + " was answered already");
    return s;
}

// Query s of lane l answered: its result, and the flight's answered head
// dropped.
void CascadeRtl::record(int l, Sent& s, bool hit, AnswerPath path, std::uint8_t* hits, AnswerPath* paths) {
    Lane& ln = lanes_[static_cast<std::size_t>(l)];
    CascadeLaneStats& ls = lane_stats_[static_cast<std::size_t>(l)];
    hits[s.index] = hit ? 1 : 0;
    paths[s.index] = path;
    s.answered = true;
    while (!ln.flight.empty() && ln.flight.front().answered) ln.flight.pop_front();
    ++answered_;
    ++(path == AnswerPath::Lane ? ls.certain : ls.escalated);
}

// The output handshake of lane l: a certain answer of a query in flight,
// later in the lane than the last one.
bool CascadeRtl::take_certain(int l, std::uint8_t* hits, AnswerPath* paths) {
    Top& t = *top_;
    if (!get_bit(t.out_valid_o, l) || !get_bit(t.out_ready_i, l)) return false;
    const std::string where = "lane " + std::to_string(l) + ", cycle " + std::to_string(stats_.cycles);
    Sent& s = find(l, get_bits(t.out_tag_o, kT * l, kT), where);
    Lane& ln = lanes_[static_cast<std::size_t>(l)];
    if (s.seq < ln.certain_next)
        throw ProtocolError(where + ": a certain answer out of order (tag " + std::to_string(s.seq & tag_mask_) +
                            " after a later query's)");
    ln.certain_next = s.seq + 1;
    record(l, s, get_bit(t.out_hit_o, l), AnswerPath::Lane, hits, paths);
    return true;
}

// The escalation stream's handshake: an answer of the lane esc_lane_o
// names, later in that lane than its last escalated one.
bool CascadeRtl::take_escalated(std::uint8_t* hits, AnswerPath* paths) {
    Top& t = *top_;
    if (!t.esc_valid_o) return false;
    if (!t.esc_ready_i) {
        ++esc_stalls_;
        return false;
    }
    const int l = t.esc_lane_o;
    const std::string where = "escalation stream, lane " + std::to_string(l) + ", cycle " +
                              std::to_string(stats_.cycles);
    if (l >= kLanes) throw ProtocolError(where + ": no such lane");
    Sent& s = find(l, t.esc_tag_o, where);
    Lane& ln = lanes_[static_cast<std::size_t>(l)];
    if (s.seq < ln.esc_next)
        throw ProtocolError(where + ": an escalated answer out of order (tag " + std::to_string(s.seq & tag_mask_) +
                            " after a later query's)");
    ln.esc_next = s.seq + 1;
    record(l, s, t.esc_hit_o != 0, AnswerPath::Escalated, hits, paths);
    ++escalated_;
    return true;
}

// One clock of every lane: offers, back-pressure, then the handshakes
// sampled with the clock low (answers first: none may come from a query
// accepted in the same cycle), then the rising edge.
void CascadeRtl::cycle(const CascadeQuery* q, std::uint8_t* hits, AnswerPath* paths) {
    Top& t = *top_;
    for (int l = 0; l < kLanes; ++l) offer(l, q);
    draw_ready();
    t.clk_i = 0;
    eval();
    bool progress = take_escalated(hits, paths);
    for (int l = 0; l < kLanes; ++l) progress |= take_certain(l, hits, paths);
    std::uint64_t flight = 0;
    for (int l = 0; l < kLanes; ++l) {
        progress |= take_input(l);
        flight += lanes_[static_cast<std::size_t>(l)].flight.size();
    }
    t.clk_i = 1;
    eval();
    ++stats_.cycles;
    if (flight > stats_.max_in_flight) stats_.max_in_flight = flight;
    idle_ = progress ? 0 : idle_ + 1;
    if (idle_ > kStallLimit)
        throw ProtocolError("no handshake on any stream for " + std::to_string(kStallLimit) + " cycles with " +
                            std::to_string(flight) + " queries unanswered");
}

// rst_i high for 1 to 3 cycles, the inputs as they were (a lane may offer a
// query: none may be taken). From the first reset edge on, in_ready_o,
// out_valid_o and esc_valid_o must be low. Every unanswered query is
// dropped: it goes back to the head of its lane's queue and is sent again
// with a new tag, so that an answer of the dropped one is caught.
void CascadeRtl::reset_mid_stream() {
    Top& t = *top_;
    const std::uint32_t n = 1 + rng_.below(3);
    t.rst_i = 1;
    for (std::uint32_t c = 0; c < n; ++c) {
        draw_ready();
        t.clk_i = 0;
        eval();
        for (int l = 0; l < kLanes && c > 0; ++l)
            if (get_bit(t.in_ready_o, l) || get_bit(t.out_valid_o, l))
                throw ProtocolError("lane " + std::to_string(l) + ": in_ready_o or out_valid_o high in reset");
        if (c > 0 && t.esc_valid_o) throw ProtocolError("esc_valid_o high in reset");
        t.clk_i = 1;
        eval();
        ++stats_.cycles;
    }
    t.rst_i = 0;
    for (std::size_t l = 0; l < lanes_.size(); ++l) {
        Lane& ln = lanes_[l];
        for (auto it = ln.flight.rbegin(); it != ln.flight.rend(); ++it)
            if (!it->answered) {
                ln.todo.push_front(it->index);
                ++lane_stats_[l].dropped;
            }
        ln.flight.clear();
        ln.driven = UINT64_MAX;
    }
    ++resets_;
    set_resets(reset_every_);
}

void CascadeRtl::run(const CascadeQuery* q, std::size_t n, std::uint8_t* hits, AnswerPath* paths) {
    assign(n);
    answered_ = 0;
    for (std::size_t i = 0; i < n; ++i) paths[i] = AnswerPath::None;
    while (answered_ < n) {
        if (reset_every_ != 0 && until_reset_-- == 0) reset_mid_stream();
        else cycle(q, hits, paths);
    }
    finish_run(n);
}

// Leaves the clock low with nothing offered; the lanes' tags go on from
// here in the next run.
void CascadeRtl::finish_run(std::size_t n) {
    Top& t = *top_;
    clear(t.in_valid_i);
    clear(t.out_ready_i);
    t.esc_ready_i = 0;
    t.clk_i = 0;
    eval();
    stats_.queries += n;
}

}  // namespace pluecker::sim
