// SPDX-License-Identifier: MIT
// Driving the Verilated array: the lanes' contracts, the port checks, the
// latency of every lane and the clock loop that feeds all lanes at once.
#include "array_rtl.hpp"

#ifndef SIM_DIRECT_EVAL
#define SIM_DIRECT_EVAL 1
#endif

#if SIM_DIRECT_EVAL
// The generated scheduler (see RtlStream::start). Weak, so a Verilator whose
// generated code names it differently links and falls back to eval().
void Vpluecker_array___024root___eval(Vpluecker_array___024root* vlSelf) __attribute__((weak));
#endif

namespace pluecker::sim {
namespace {

constexpr int kC3 = 3 * SIM_COORD_BITS;
constexpr int kD3 = 3 * SIM_DIR_BITS;
constexpr int kT = SIM_TAG_BITS;

}  // namespace

RtlConfig lane_config(int lane) {
    RtlConfig c;
    c.coord_bits = SIM_COORD_BITS;
    c.dir_bits = SIM_DIR_BITS;
    c.tag_bits = SIM_TAG_BITS;
    c.conservative = SIM_CONSERVATIVE != 0;
    c.mul_style = lane < kDspLanes ? MulStyle::Dsp : lane < kDspLanes + kLutLanes ? MulStyle::Lut : MulStyle::Rom;
    c.pipeline = SIM_PIPELINE;
    return c;
}

// One contract per style, built when a lane of that style asks (a fabric
// or table contract refuses widths its multipliers do not take).
const PortContract& lane_contract(int lane) {
    if (lane < kDspLanes) {
        static const PortContract dsp(lane_config(0));
        return dsp;
    }
    if (lane < kDspLanes + kLutLanes) {
        static const PortContract lut(lane_config(kDspLanes));
        return lut;
    }
    static const PortContract rom(lane_config(kDspLanes + kLutLanes));
    return rom;
}

FixedFormat built_format() { return lane_contract(0).format(); }

const char* lane_style(int lane) { return mul_style_name(lane_config(lane).mul_style); }

std::string build_name() {
    const FixedFormat f = built_format();
    return std::to_string(SIM_ARRAY_DSP) + " dsp + " + std::to_string(SIM_ARRAY_LUT) + " lut" +
           (SIM_ARRAY_ROM ? " + " + std::to_string(SIM_ARRAY_ROM) + " rom" : std::string()) + ", " +
           std::to_string(f.coord_bits) + "x" + std::to_string(f.dir_bits) + " " + mode_name(f.mode);
}

LaneQuery pack_lane_query(const FixedRay& r, const FixedBox& b) { return pack_query(r, b, built_format()); }

ArrayRtl::ArrayRtl()
    : ctx_(std::make_unique<VerilatedContext>()),
      lanes_(kLanes),
      lane_stats_(kLanes),
      next_tag_(kLanes, 0),
      tag_mask_((std::uint64_t{1} << SIM_TAG_BITS) - 1),
      max_in_flight_(std::uint64_t{1} << SIM_TAG_BITS) {
    ctx_->randReset(0);  // deterministic initial state for anything not reset
    top_ = std::make_unique<Top>(ctx_.get(), "pluecker_array");
    for (int l = 0; l < kLanes; ++l) lane_contract(l);  // InputError for a refused style
    check_ports();
    hard_reset();
#if SIM_DIRECT_EVAL
    direct_ = &::Vpluecker_array___024root___eval;
#endif
    for (int l = 0; l < kLanes; ++l) {
        latency_.push_back(measure_latency(l));
        if (latency_.back() != lane_contract(l).latency())
            throw ProtocolError("lane " + std::to_string(l) + " (" + lane_style(l) + ") answers after " +
                                std::to_string(latency_.back()) + " cycles, the port contract's LATENCY is " +
                                std::to_string(lane_contract(l).latency()));
        hard_reset();
    }
}

ArrayRtl::~ArrayRtl() {
    if (top_) top_->final();
}

// Every port holds N lanes of the contract's width, in the smallest type
// that does.
void ArrayRtl::check_ports() {
    Top& t = *top_;
    const PortContract& c = lane_contract(0);
    auto check = [&]<class P>(const P&, const char* name) {
        check_port<PortType<P>>(name, kLanes * c.port(name).width());
    };
    check(t.in_valid_i, "in_valid_i");
    check(t.in_ready_o, "in_ready_o");
    check(t.in_tag_i, "in_tag_i");
    check(t.ray_class_i, "ray_class_i");
    check(t.ray_org_i, "ray_org_i");
    check(t.ray_dir_i, "ray_dir_i");
    check(t.ray_end_i, "ray_end_i");
    check(t.ray_end_valid_i, "ray_end_valid_i");
    check(t.box_min_i, "box_min_i");
    check(t.box_max_i, "box_max_i");
    check(t.out_valid_o, "out_valid_o");
    check(t.out_ready_i, "out_ready_i");
    check(t.out_tag_o, "out_tag_o");
    check(t.out_hit_o, "out_hit_o");
}

void ArrayRtl::eval() {
    if (direct_) direct_(top_->rootp);
    else top_->eval();
}

// rst_i for eight cycles with nothing offered (plain eval(): the first
// evaluations initialise the model).
void ArrayRtl::hard_reset() {
    Top& t = *top_;
    clear(t.in_valid_i);
    clear(t.out_ready_i);
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

// One all-zero query in lane `lane` alone, every output ready: the rising
// edges from its input handshake to its output handshake. No other lane
// may answer.
int ArrayRtl::measure_latency(int lane) {
    Top& t = *top_;
    for (int l = 0; l < kLanes; ++l) {
        set_lane(t.ray_org_i, l, kC3, PortWords{});
        set_lane(t.ray_dir_i, l, kD3, PortWords{});
        set_lane(t.ray_end_i, l, kC3, PortWords{});
        set_lane(t.box_min_i, l, kC3, PortWords{});
        set_lane(t.box_max_i, l, kC3, PortWords{});
        set_bits(t.ray_class_i, 3 * l, 3, 0);
        set_bits(t.in_tag_i, kT * l, kT, 0);
        set_bit(t.ray_end_valid_i, l, false);
        set_bit(t.out_ready_i, l, true);
    }
    set_bit(t.in_valid_i, lane, true);
    int fired = -1;
    for (int edge = 0; edge < 256; ++edge) {
        t.clk_i = 0;
        eval();
        for (int l = 0; l < kLanes; ++l)
            if (l != lane && get_bit(t.out_valid_o, l))
                throw ProtocolError("lane " + std::to_string(l) + " answers a query of lane " + std::to_string(lane));
        if (fired < 0 && get_bit(t.in_ready_o, lane)) fired = edge;
        const bool out = fired >= 0 && get_bit(t.out_valid_o, lane);
        t.clk_i = 1;
        eval();
        if (fired >= 0) set_bit(t.in_valid_i, lane, false);
        if (out) {
            clear(t.out_ready_i);
            t.clk_i = 0;
            eval();
            return edge - fired;
        }
    }
    throw ProtocolError("lane " + std::to_string(lane) + ": no answer within 256 cycles of one query");
}

void ArrayRtl::set_backpressure(double p_ready, std::uint64_t seed) {
    always_ready_ = !(p_ready < 1.0);
    ready_threshold_ = static_cast<std::uint32_t>((p_ready < 0.0 ? 0.0 : p_ready) * 4294967295.0);
    rng_ = Rng(seed * 0x9e3779b97f4a7c15ull + 0x2545f4914f6cdd1dull);
}

void ArrayRtl::set_idle(double p_valid) {
    always_valid_ = !(p_valid < 1.0);
    valid_threshold_ = static_cast<std::uint32_t>((p_valid < 0.0 ? 0.0 : p_valid) * 4294967295.0);
}

void ArrayRtl::set_resets(std::uint64_t cycles) {
    reset_every_ = cycles;
    until_reset_ = cycles ? cycles / 2 + rng_.next() % (cycles + 1) : 0;
}

bool ArrayRtl::draw(std::uint32_t threshold) { return static_cast<std::uint32_t>(rng_.next() >> 32) < threshold; }

// The batch round-robin over the lanes, from the lane after the last run's
// last query.
void ArrayRtl::assign(std::size_t n) {
    for (int l = 0; l < kLanes; ++l) {
        Lane& ln = lanes_[static_cast<std::size_t>(l)];
        ln.queries.clear();
        ln.n_in = ln.n_out = 0;
        ln.tag_base = next_tag_[static_cast<std::size_t>(l)];
        ln.driven = SIZE_MAX;
        ln.offered = false;
    }
    for (std::size_t i = 0; i < n; ++i)
        lanes_[(next_lane_ + i) % kLanes].queries.push_back(static_cast<std::uint32_t>(i));
    next_lane_ = (next_lane_ + n) % kLanes;
}

// in_valid_i of lane l and, for a new query, its payload and tag.
void ArrayRtl::offer(int l, const LaneQuery* q) {
    Top& t = *top_;
    Lane& ln = lanes_[static_cast<std::size_t>(l)];
    const bool waiting = ln.n_in < ln.queries.size() && ln.n_in - ln.n_out < max_in_flight_;
    if (!ln.offered) ln.offered = waiting && (always_valid_ || draw(valid_threshold_));
    set_bit(t.in_valid_i, l, ln.offered);
    if (!ln.offered || ln.driven == ln.n_in) return;
    const LaneQuery& p = q[ln.queries[ln.n_in]];
    set_lane(t.ray_org_i, l, kC3, p.ray_org);
    set_lane(t.ray_dir_i, l, kD3, p.ray_dir);
    set_lane(t.ray_end_i, l, kC3, p.ray_end);
    set_lane(t.box_min_i, l, kC3, p.box_min);
    set_lane(t.box_max_i, l, kC3, p.box_max);
    set_bits(t.ray_class_i, 3 * l, 3, p.ray_class);
    set_bit(t.ray_end_valid_i, l, p.ray_end_valid != 0);
    set_bits(t.in_tag_i, kT * l, kT, static_cast<std::uint32_t>((ln.tag_base + ln.n_in) & tag_mask_));
    ln.driven = ln.n_in;
}

void ArrayRtl::draw_ready() {
    for (int l = 0; l < kLanes; ++l) set_bit(top_->out_ready_i, l, always_ready_ || draw(ready_threshold_));
}

// The input handshake of lane l this cycle (sampled with the clock low).
bool ArrayRtl::take_input(int l) {
    Lane& ln = lanes_[static_cast<std::size_t>(l)];
    LaneStats& ls = lane_stats_[static_cast<std::size_t>(l)];
    if (!ln.offered) return false;
    if (!get_bit(top_->in_ready_o, l)) {
        ++ls.stall_cycles;
        ++stats_.stall_cycles;
        return false;
    }
    ++ln.n_in;
    ln.offered = false;
    if (ln.n_in - ln.n_out > ls.max_in_flight) ls.max_in_flight = ln.n_in - ln.n_out;
    return true;
}

// The output handshake of lane l: the oldest query in flight in the lane
// must carry the answer's tag.
bool ArrayRtl::take_output(int l, std::uint8_t* hits) {
    Top& t = *top_;
    Lane& ln = lanes_[static_cast<std::size_t>(l)];
    if (!get_bit(t.out_valid_o, l) || !get_bit(t.out_ready_i, l)) return false;
    const std::string where = "lane " + std::to_string(l) + " (" + lane_style(l) + "), cycle " +
                              std::to_string(stats_.cycles);
    if (ln.n_out == ln.n_in) throw ProtocolError(where + ": out_valid_o with no query in flight");
    const std::uint64_t tag = get_bits(t.out_tag_o, kT * l, kT);
    const std::uint64_t expect = (ln.tag_base + ln.n_out) & tag_mask_;
    if (tag != expect)
        throw ProtocolError(where + ": out_tag_o = " + std::to_string(tag) +
                            " but the oldest query in flight has tag " + std::to_string(expect));
    hits[ln.queries[ln.n_out]] = get_bit(t.out_hit_o, l) ? 1 : 0;
    ++ln.n_out;
    ++answered_;
    ++lane_stats_[static_cast<std::size_t>(l)].queries;
    return true;
}

// One clock of every lane: offers, back-pressure, then the handshakes
// sampled with the clock low (answers first: none may come from a query
// accepted in the same cycle), then the rising edge.
void ArrayRtl::cycle(const LaneQuery* q, std::uint8_t* hits) {
    Top& t = *top_;
    for (int l = 0; l < kLanes; ++l) offer(l, q);
    draw_ready();
    t.clk_i = 0;
    eval();
    bool progress = false;
    for (int l = 0; l < kLanes; ++l) progress |= take_output(l, hits);
    std::uint64_t flight = 0;
    for (int l = 0; l < kLanes; ++l) {
        progress |= take_input(l);
        flight += lanes_[static_cast<std::size_t>(l)].n_in - lanes_[static_cast<std::size_t>(l)].n_out;
    }
    t.clk_i = 1;
    eval();
    ++stats_.cycles;
    if (flight > stats_.max_in_flight) stats_.max_in_flight = flight;
    idle_ = progress ? 0 : idle_ + 1;
    if (idle_ > kStallLimit)
        throw ProtocolError("no handshake in any lane for " + std::to_string(kStallLimit) + " cycles with " +
                            std::to_string(flight) + " queries in flight");
}

// rst_i high for 1 to 3 cycles, the inputs as they were (a lane may offer a
// query: none may be taken). From the first reset edge on, in_ready_o and
// out_valid_o must be low. Every query in flight is dropped: it is sent
// again with a new tag, so that an answer of the dropped one is caught.
void ArrayRtl::reset_mid_stream() {
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
        t.clk_i = 1;
        eval();
        ++stats_.cycles;
    }
    t.rst_i = 0;
    for (int l = 0; l < kLanes; ++l) {
        Lane& ln = lanes_[static_cast<std::size_t>(l)];
        const std::size_t dropped = ln.n_in - ln.n_out;
        ln.tag_base += dropped;
        ln.n_in = ln.n_out;
        ln.driven = SIZE_MAX;
        lane_stats_[static_cast<std::size_t>(l)].dropped += dropped;
    }
    ++resets_;
    set_resets(reset_every_);
}

void ArrayRtl::run(const LaneQuery* q, std::size_t n, std::uint8_t* hits) {
    assign(n);
    answered_ = 0;
    while (answered_ < n) {
        if (reset_every_ != 0 && until_reset_-- == 0) reset_mid_stream();
        else cycle(q, hits);
    }
    finish_run(n);
}

// Leaves the clock low with nothing offered; the lanes' tags go on from
// here in the next run.
void ArrayRtl::finish_run(std::size_t n) {
    Top& t = *top_;
    clear(t.in_valid_i);
    clear(t.out_ready_i);
    t.clk_i = 0;
    eval();
    for (std::size_t l = 0; l < lanes_.size(); ++l) next_tag_[l] = lanes_[l].tag_base + lanes_[l].queries.size();
    stats_.queries += n;
}

}  // namespace pluecker::sim
