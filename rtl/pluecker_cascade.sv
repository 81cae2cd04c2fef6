// SPDX-License-Identifier: MIT
// A cascade: N_NARROW narrow units answer certain hit / certain miss /
// uncertain (pluecker_intersector with TERNARY = 1); the uncertain queries
// are re-tested by one wide conservative unit shared by all of them.
//
// Why it never misses a real hit (model/core/include/pluecker/ternary.hpp
// proves each step; cascade_answer there is this module's model): a narrow
// certain miss fails the conservative test, which every real hit passes; a
// narrow certain hit passes the strict test, which only real hits pass; an
// uncertain query gets the wide unit's conservative answer, which misses no
// real hit. The cascade's false hits are the wide unit's false hits on the
// uncertain queries.
//
// Interface
//   Lane l (0..N_NARROW-1) takes one query per transfer, in_valid_i[l] &&
//   in_ready_o[l] at a rising edge with rst_i low: in_tag_i, the query in
//   the narrow format (ray_*_i, box_*_i, packed as in
//   rtl/pluecker_intersector.sv at NARROW_COORD_BITS / NARROW_DIR_BITS) and
//   the same float query set up in the wide format (wide_*_i at
//   WIDE_COORD_BITS / WIDE_DIR_BITS). Every vector port packs lane l in
//   bits [l*W +: W] (W the width of one lane's field).
//   Certain answers leave on lane l's own stream out_*[l] (out_hit_o: 1 a
//   certain hit, 0 a certain miss), in the order of that lane's queries.
//   Uncertain answers leave on the one escalation stream esc_*: esc_lane_o
//   and esc_tag_o name the query, esc_hit_o is the wide unit's answer.
//   Order: a query's answer leaves on exactly one of the two streams; on its
//   lane's stream in order; on esc_* in the order the queries were
//   escalated (so in order per lane as well). A consumer matches esc_*
//   answers by lane and tag.
//   The consumer must take the lane streams and esc_* independently (never
//   hold esc_ready_i low waiting for a lane answer, or the reverse): each
//   lane's answers leave its narrow unit in order, so an uncertain answer
//   that finds its lane's escalation slot still occupied holds the lane's
//   certain answers behind it.
//   rst_i (synchronous, active high) drops every query in flight anywhere;
//   no answer of a query taken before it appears after it.
//
// Answer registers: each narrow unit's answers pass a skid register
// (pluecker_axis_skid) before the lane decides certain or uncertain, so the
// narrow unit's out_ready is a flop and no path runs from its output FIFO's
// read through that decision back into its credits. A certain answer takes
// the narrow unit's LATENCY plus one clock.
//
// Escalation slots: an uncertain answer leaves its answer register into its
// lane's slot (one entry: tag and wide query, loaded when the slot is
// empty), so the lane's next answers move on while it waits for the wide
// unit, and the arbiter works on flops only: its path (slot valid bits and
// a credit flop -> grant) never crosses a narrow unit's FIFO read or
// another lane's handshake.
// Arbitration: each clock the arbiter grants at most one slot, the first
// full one at or after a round-robin pointer, when it holds a credit of the
// wide unit; an offer not granted is offered again unchanged (the pointer
// stays on it), a granted one moves the pointer past its lane and empties
// its slot. The grant is registered (grant_q, and one copy of it per 32
// bits of the wide query); in the next clock the granted slot's query and
// tag move through a multiplexer driven by those flops into the wide
// unit's input register, which loads every clock (no enable: the decision
// reaches its few hundred flops from registers of small fanout, not from
// the arbiter's logic). The slot is refilled no earlier than the clock
// after it emptied, so the multiplexer reads the granted query.
// Credits: the cascade mirrors the wide unit's (wcred_q, its FIFO_DEPTH
// from the port contract): a grant takes one, an esc_* transfer returns
// one a clock later (registered, give_q). A granted query reaches the
// wide unit two clocks later, so the wide unit holds at least as many
// credits as the cascade plus the queries on their way: it is always
// ready when its input register is full (asserted under ASSERT_ON).
// An escalated answer spends four more clocks than the two units' LATENCY:
// one in its answer register, one in its slot, one in grant_q, one in the
// input register. A lane escalates at most every other clock (its slot
// refills the clock after it empties); with N_NARROW lanes each escalating
// a fraction e <= 1/2 of its queries, the cascade sustains N_NARROW
// queries per clock while N_NARROW * e <= 1; above that the wide unit sets
// the pace (lanes wait through their credits, nothing is lost).
//
// Per lane, the wide query waits in a FIFO beside the narrow unit (of
// SIDE_DEPTH entries, below): written when the narrow unit takes the query
// (from registers, a clock later), read in the clock after its answer
// leaves the answer register (its pointers move a clock after their
// events, from registers). The narrow unit holds at most FIFO_DEPTH
// queries (its credits) and the answer register two more, so the lane
// takes no query while the side FIFO counts itself full (a flop).
//
// Outputs from flops through the narrow units' output FIFOs and a few gates
// (no combinational path from any input to any output).
`default_nettype none

module pluecker_cascade #(
    parameter int N_NARROW = 2,
    parameter int NARROW_COORD_BITS = 8,
    parameter int NARROW_DIR_BITS = 8,
    parameter NARROW_MUL_STYLE = "auto",
    parameter int WIDE_COORD_BITS = 16,
    parameter int WIDE_DIR_BITS = 16,
    parameter WIDE_MUL_STYLE = "auto",
    parameter int TAG_BITS = 8,
    parameter int PIPELINE = 0,
    // Bits of a lane number (not to be overridden).
    localparam int LANE_BITS = (N_NARROW > 1) ? $clog2(N_NARROW) : 1
) (
    input wire clk_i,
    input wire rst_i,

    input  wire [                N_NARROW-1:0] in_valid_i,
    output wire [                N_NARROW-1:0] in_ready_o,
    input  wire [       N_NARROW*TAG_BITS-1:0] in_tag_i,
    input  wire [              N_NARROW*3-1:0] ray_class_i,
    input  wire [N_NARROW*3*NARROW_COORD_BITS-1:0] ray_org_i,
    input  wire [  N_NARROW*3*NARROW_DIR_BITS-1:0] ray_dir_i,
    input  wire [N_NARROW*3*NARROW_COORD_BITS-1:0] ray_end_i,
    input  wire [                N_NARROW-1:0] ray_end_valid_i,
    input  wire [N_NARROW*3*NARROW_COORD_BITS-1:0] box_min_i,
    input  wire [N_NARROW*3*NARROW_COORD_BITS-1:0] box_max_i,
    input  wire [              N_NARROW*3-1:0] wide_ray_class_i,
    input  wire [N_NARROW*3*WIDE_COORD_BITS-1:0] wide_ray_org_i,
    input  wire [  N_NARROW*3*WIDE_DIR_BITS-1:0] wide_ray_dir_i,
    input  wire [N_NARROW*3*WIDE_COORD_BITS-1:0] wide_ray_end_i,
    input  wire [                N_NARROW-1:0] wide_ray_end_valid_i,
    input  wire [N_NARROW*3*WIDE_COORD_BITS-1:0] wide_box_min_i,
    input  wire [N_NARROW*3*WIDE_COORD_BITS-1:0] wide_box_max_i,

    output wire [         N_NARROW-1:0] out_valid_o,
    input  wire [         N_NARROW-1:0] out_ready_i,
    output wire [N_NARROW*TAG_BITS-1:0] out_tag_o,
    output wire [         N_NARROW-1:0] out_hit_o,

    output wire                 esc_valid_o,
    input  wire                 esc_ready_i,
    output wire [LANE_BITS-1:0] esc_lane_o,
    output wire [ TAG_BITS-1:0] esc_tag_o,
    output wire                 esc_hit_o
);
  localparam int N = N_NARROW;
  localparam int NC3 = 3 * NARROW_COORD_BITS;
  localparam int ND3 = 3 * NARROW_DIR_BITS;
  localparam int WC3 = 3 * WIDE_COORD_BITS;
  localparam int WD3 = 3 * WIDE_DIR_BITS;
  // One wide query: class, origin, direction, end, end valid, box.
  localparam int WQ = 3 + 4 * WC3 + WD3 + 1;

  // An upper bound on the lanes of one wide unit (each lane costs a port of
  // the arbiter's multiplexer).
  localparam int MAX_LANES = 64;
  if (N < 1 || N > MAX_LANES) begin : g_bad_n
    $error("pluecker_cascade: parameter N_NARROW must be 1..64");
  end
  if (WIDE_COORD_BITS < NARROW_COORD_BITS || WIDE_DIR_BITS < NARROW_DIR_BITS) begin : g_bad_widths
    $error("pluecker_cascade: the wide format must be at least as wide as the narrow one (WIDE_COORD_BITS >= NARROW_COORD_BITS, WIDE_DIR_BITS >= NARROW_DIR_BITS)");
  end
  // The narrow unit's FIFO depth, from the port contract (the units check
  // their own parameters; a bad one makes the class -1 and this a guess).
  localparam logic [31:0] NARROW_STYLE_S = 32'(NARROW_MUL_STYLE);
  localparam int NARROW_CLASS = pluecker_contract_pkg::contract_class(NARROW_COORD_BITS, NARROW_DIR_BITS,
                                                                       NARROW_STYLE_S, PIPELINE);
  // The side FIFO's depth: the smallest power of two of at least the narrow
  // unit's LATENCY + 4, so that a lane takes a query every clock (its
  // occupancy counts a query from the clock after its push to the second
  // clock after its answer leaves the answer register). Measured with
  // pluecker_sim_cascade check: 16 entries keep the full rate at LATENCY
  // 6, 8 and 10; 8 entries at LATENCY 6 cost 16 % of it.
  localparam int NARROW_LATENCY = (NARROW_CLASS < 0) ? 12 : pluecker_contract_pkg::contract_latency(NARROW_CLASS);
  localparam int SIDE_DEPTH = 1 << $clog2(NARROW_LATENCY + 4);
  localparam int SIDE_AW = $clog2(SIDE_DEPTH);
  // A control flop that drives a wide query's register enables, write
  // enables or multiplexer selects (the registered grant, the slots' valid
  // bits, the side FIFO's write enable) is kept in CTRL_COPIES copies, one
  // per CTRL_FANOUT bits of the wide query.
  localparam int CTRL_FANOUT = 32;
  localparam int CTRL_COPIES = (WQ + CTRL_FANOUT - 1) / CTRL_FANOUT;

  // Narrow answers: valid, tag, conservative, strict; the same out of each
  // lane's answer register (a skid register: a_*).
  wire [N-1:0] n_valid, n_ready, n_hit, n_strict, n_in_ready;
  wire [N*TAG_BITS-1:0] n_tag;
  wire [N-1:0] a_valid, a_ready, a_hit, a_strict;
  wire [N*TAG_BITS-1:0] a_tag;
  // Uncertain answers leaving a lane's answer register; full escalation
  // slots (the arbiter's requests) and the grant.
  wire [N-1:0] uncertain = a_valid & a_hit & ~a_strict;
  logic [N-1:0] slot_v_q;
  logic [N-1:0] grant;
  wire [N*WQ-1:0] side_head;  // per lane, the wide query of the narrow unit's oldest answer
  wire [N*WQ-1:0] slot_query;  // per lane, the wide query in its slot
  wire [N*TAG_BITS-1:0] slot_tag;
  // The wide unit's ready: implied by the credits (read only by an
  // assertion under ASSERT_ON).
  /* verilator lint_off UNUSEDSIGNAL */
  wire w_in_ready;
  /* verilator lint_on UNUSEDSIGNAL */
  // The wide unit's input register (one query: the granted slot's; valid
  // bit reset, contents not).
  logic wq_v_q;
  // The wide unit's FIFO depth (its credits), from the port contract.
  localparam logic [31:0] WIDE_STYLE_S = 32'(WIDE_MUL_STYLE);
  localparam int WIDE_CLASS = pluecker_contract_pkg::contract_class(WIDE_COORD_BITS, WIDE_DIR_BITS,
                                                                     WIDE_STYLE_S, PIPELINE);
  localparam int WIDE_CREDITS = (WIDE_CLASS < 0) ? 1 : pluecker_contract_pkg::contract_fifo_depth(WIDE_CLASS);
  // The cascade's credits of the wide unit, a thermometer code (bit i set:
  // more than i), one bit above WIDE_CREDITS (never set).
  localparam int WCT = WIDE_CREDITS + 1;
  logic [WCT-1:0] wcred_q;
  wire esc_give = esc_valid_o && esc_ready_i;

  for (genvar l = 0; l < N; l++) begin : g_lane
    wire side_full;  // the lane's side FIFO (below) is full (a flop's output)
    pluecker_intersector #(
        .COORD_BITS(NARROW_COORD_BITS),
        .DIR_BITS(NARROW_DIR_BITS),
        .TAG_BITS(TAG_BITS),
        .CONSERVATIVE(1),
        .MUL_STYLE(NARROW_MUL_STYLE),
        .PIPELINE(PIPELINE),
        .TERNARY(1)
    ) u_narrow (
        .clk_i(clk_i),
        .rst_i(rst_i),
        .in_valid_i(in_valid_i[l] && !side_full),
        .in_ready_o(n_in_ready[l]),
        .in_tag_i(in_tag_i[l*TAG_BITS+:TAG_BITS]),
        .ray_class_i(ray_class_i[l*3+:3]),
        .ray_org_i(ray_org_i[l*NC3+:NC3]),
        .ray_dir_i(ray_dir_i[l*ND3+:ND3]),
        .ray_end_i(ray_end_i[l*NC3+:NC3]),
        .ray_end_valid_i(ray_end_valid_i[l]),
        .box_min_i(box_min_i[l*NC3+:NC3]),
        .box_max_i(box_max_i[l*NC3+:NC3]),
        .out_valid_o(n_valid[l]),
        .out_ready_i(n_ready[l]),
        .out_tag_o(n_tag[l*TAG_BITS+:TAG_BITS]),
        .out_hit_o(n_hit[l]),
        .out_strict_o(n_strict[l])
    );

    // The lane's answer register: its ready (to the narrow unit) and its
    // answer (to the decision below) are flops, so no path runs from the
    // narrow unit's output FIFO read through the certain/uncertain decision
    // back into its credits.
    pluecker_axis_skid #(
        .DATA_BITS(TAG_BITS + 2)
    ) u_answer (
        .clk_i(clk_i),
        .rst_i(rst_i),
        .in_valid_i(n_valid[l]),
        .in_ready_o(n_ready[l]),
        .in_data_i({n_tag[l*TAG_BITS+:TAG_BITS], n_hit[l], n_strict[l]}),
        .out_valid_o(a_valid[l]),
        .out_ready_i(a_ready[l]),
        .out_data_o({a_tag[l*TAG_BITS+:TAG_BITS], a_hit[l], a_strict[l]})
    );

    // Certain answers (hit == strict) leave on the lane; uncertain ones move
    // into the lane's escalation slot when it is empty (not in the clock a
    // grant empties it: the multiplexer reads it in the next one).
    wire slot_take = grant[l] && w_take;
    wire slot_free = !slot_v_q[l];
    wire slot_load = uncertain[l] && slot_free;
    assign out_valid_o[l] = a_valid[l] && !uncertain[l];
    assign out_tag_o[l*TAG_BITS+:TAG_BITS] = a_tag[l*TAG_BITS+:TAG_BITS];
    assign out_hit_o[l] = a_hit[l];
    assign a_ready[l] = uncertain[l] ? slot_free : out_ready_i[l];
    // The side FIFO holds the queries in the narrow unit and in the answer
    // register: a lane takes no query while it is full.
    assign in_ready_o[l] = n_in_ready[l] && !side_full;

    // The escalation slot (valid bit reset, contents not). While empty its
    // tag loads the head of the answer register every clock, so the clock
    // that fills it loads the uncertain answer's tag; full, it holds. Its
    // wide query follows a clock later: the side FIFO's read pointers move
    // a clock after the answer leaves (below), so in the clock after the
    // slot fills the FIFO's head is still that answer's query, and the
    // query register loads while the slot was empty a clock before
    // (slot_vd_rep_q, a copy per CTRL_FANOUT bits: the certain/uncertain
    // decision does not fan out to the WQ flops). A grant reads the query
    // no earlier than the second clock after the slot filled, and the slot
    // refills no earlier than the clock after the grant emptied it, so
    // the register holds through the read.
    logic [TAG_BITS-1:0] slot_tag_q;
    logic [WQ-1:0] slot_query_q;
    logic [CTRL_COPIES-1:0] slot_v_rep_q, slot_vd_rep_q;
    always_ff @(posedge clk_i) begin
      if (rst_i) slot_v_q[l] <= 1'b0;
      else if (slot_load) slot_v_q[l] <= 1'b1;
      else if (slot_take) slot_v_q[l] <= 1'b0;
    end
    for (genvar r = 0; r < CTRL_COPIES; r++) begin : g_slot_v_rep
      (* keep *)
      always_ff @(posedge clk_i) begin
        if (rst_i) slot_v_rep_q[r] <= 1'b0;
        else if (slot_load) slot_v_rep_q[r] <= 1'b1;
        else if (slot_take) slot_v_rep_q[r] <= 1'b0;
      end
    end
    // (control, reset)
    (* keep *)
    always_ff @(posedge clk_i) begin
      if (rst_i) slot_vd_rep_q <= '0;
      else slot_vd_rep_q <= slot_v_rep_q;
    end
    always_ff @(posedge clk_i) begin
      if (!slot_v_q[l]) slot_tag_q <= a_tag[l*TAG_BITS+:TAG_BITS];
      for (int b = 0; b < WQ; b++)
        if (!slot_vd_rep_q[b/CTRL_FANOUT]) slot_query_q[b] <= side_head[l*WQ+b];
    end
    assign slot_tag[l*TAG_BITS+:TAG_BITS] = slot_tag_q;
    assign slot_query[l*WQ+:WQ] = slot_query_q;

    // The side FIFO of wide queries (pointers reset, contents not). Every
    // pointer and count moves a clock after its event, from registers, so
    // neither the lane's handshake (push: in the narrow unit's region) nor
    // the answer register's (pop) reaches more than a few flops: a push is
    // written a clock later (each CTRL_FANOUT-bit chunk of the FIFO has its
    // own copy of the delayed push, we_q, and its own write pointer, which
    // we_q moves on), and each chunk's read pointer moves on its own copy
    // of the delayed pop (pop_rep_q). So in the clock after a pop the head
    // is still the popped answer's query, which the slot loads then (above).
    // An entry is read no earlier than the narrow unit's LATENCY after its
    // push, and a freed one is written only after a later push.
    // The occupancy, a thermometer code (bit i set: more than i entries),
    // counts pushes and pops a clock late (push_q, pop_q), so it may be one
    // push short of the truth and a pop over it: the lane takes no query
    // while it counts more than SIDE_DEPTH - 2 (side_full, a flop), so it
    // never holds more than SIDE_DEPTH (queries in the narrow unit, in the
    // answer register and the one being written).
    logic [SIDE_DEPTH-1:0] side_occ_q;
    logic push_q, pop_q;
    wire push = in_valid_i[l] && in_ready_o[l];
    wire pop = a_valid[l] && a_ready[l];
    always_ff @(posedge clk_i) begin
      if (rst_i) begin
        side_occ_q <= '0;
        push_q <= 1'b0;
        pop_q <= 1'b0;
      end else begin
        push_q <= push;
        pop_q <= pop;
        if (push_q && !pop_q) side_occ_q <= {side_occ_q[SIDE_DEPTH-2:0], 1'b1};
        else if (pop_q && !push_q) side_occ_q <= side_occ_q >> 1;
      end
    end
    assign side_full = side_occ_q[SIDE_DEPTH-2];
`ifdef ASSERT_ON
    // The full pointers, for the checks alone (each chunk of the FIFO
    // writes and reads at its own copies, which must agree with them).
    logic [SIDE_AW:0] side_wr_q, side_rd_q;
    always_ff @(posedge clk_i) begin
      if (rst_i) begin
        side_wr_q <= '0;
        side_rd_q <= '0;
      end else begin
        if (push) side_wr_q <= side_wr_q + 1'b1;
        if (pop) side_rd_q <= side_rd_q + 1'b1;
      end
    end
`endif
    logic [WQ-1:0] side_wdata_q;
    always_ff @(posedge clk_i) begin
      side_wdata_q <= {
        wide_ray_class_i[l*3+:3],
        wide_ray_org_i[l*WC3+:WC3],
        wide_ray_dir_i[l*WD3+:WD3],
        wide_ray_end_i[l*WC3+:WC3],
        wide_ray_end_valid_i[l],
        wide_box_min_i[l*WC3+:WC3],
        wide_box_max_i[l*WC3+:WC3]
      };
    end
    for (genvar c = 0; c < CTRL_COPIES; c++) begin : g_side
      localparam int LO = c * CTRL_FANOUT;
      localparam int CW = (WQ - LO < CTRL_FANOUT) ? WQ - LO : CTRL_FANOUT;
      // this chunk's copies of the delayed push and pop, and its pointers
      // (control, reset)
      logic we_q, pop_rep_q;
      logic [SIDE_AW-1:0] waddr_q, raddr_q;
      (* keep *)
      always_ff @(posedge clk_i) begin
        if (rst_i) begin
          we_q <= 1'b0;
          pop_rep_q <= 1'b0;
          waddr_q <= '0;
          raddr_q <= '0;
        end else begin
          we_q <= push;
          pop_rep_q <= pop;
          if (we_q) waddr_q <= waddr_q + 1'b1;
          if (pop_rep_q) raddr_q <= raddr_q + 1'b1;
        end
      end
      logic [CW-1:0] mem_q[SIDE_DEPTH];
      always_ff @(posedge clk_i) begin
        if (we_q) mem_q[waddr_q] <= side_wdata_q[LO+:CW];
      end
      assign side_head[l*WQ+LO+:CW] = mem_q[raddr_q];
`ifdef ASSERT_ON
      always_ff @(posedge clk_i) begin
        if (!rst_i) begin
          assert (waddr_q == side_wr_q[SIDE_AW-1:0] - SIDE_AW'(we_q));
          assert (raddr_q == side_rd_q[SIDE_AW-1:0] - SIDE_AW'(pop_rep_q));
        end
      end
`endif
    end

`ifdef ASSERT_ON
    // The side FIFO holds exactly the lane's queries (in the narrow unit
    // and in the answer register) and, for a clock after its pop, the query
    // the slot may load: never more than its depth. (Unlabelled: Yosys does
    // not prefix labels inside generate blocks, so one label per lane
    // clashes.)
    wire [SIDE_AW:0] side_diff = side_wr_q - side_rd_q;
    wire [SIDE_AW+1:0] side_count = {1'b0, side_diff} + (SIDE_AW+2)'(pop_q);
    always_ff @(posedge clk_i) begin
      if (!rst_i) assert (32'(side_count) <= SIDE_DEPTH);
    end
`endif
  end

  // -------------------------------------------------------------------------
  // Round-robin arbiter over the full slots (rr_q: the lane with priority;
  // control, reset)
  // -------------------------------------------------------------------------
  logic [LANE_BITS-1:0] rr_q, gidx;
  wire [N-1:0] req = slot_v_q;
  wire any_req = |req;

  int idx;
  always_comb begin
    grant = '0;
    gidx = rr_q;
    idx = 0;
    for (int s = N - 1; s >= 0; s--) begin
      // Lane rr_q + s (mod N); the loop runs downwards so that the smallest
      // s with a request wins.
      idx = 32'(rr_q) + s;
      if (idx >= N) idx = idx - N;
      if (req[idx]) begin
        grant = '0;
        grant[idx] = 1'b1;
        gidx = LANE_BITS'(idx);
      end
    end
  end

  wire w_take = any_req && wcred_q[0];
  always_ff @(posedge clk_i) begin
    if (rst_i) rr_q <= '0;
    // Past a taken lane; onto an offered one that waits (held unchanged).
    else if (w_take) rr_q <= (32'(gidx) + 1 >= N) ? '0 : gidx + 1'b1;
    else if (any_req) rr_q <= gidx;
  end

  // Credits: a grant takes one, an answer on esc_* returns one a clock
  // later (give_q: the output handshake, with esc_ready_i from the
  // consumer, never reaches the counter in the same clock).
  logic give_q;
  always_ff @(posedge clk_i) begin
    if (rst_i) give_q <= 1'b0;
    else give_q <= esc_give;
  end
  always_ff @(posedge clk_i) begin
    if (rst_i) wcred_q <= (WCT'(1) << WIDE_CREDITS) - 1'b1;
    // the top bit (never set, a_wcred_top) refills itself rather than a
    // constant 0, so Yosys folds no set/reset of its own into its flop
    else if (w_take && !give_q) wcred_q <= {wcred_q[WCT-1], wcred_q[WCT-1:1]};
    else if (give_q && !w_take) wcred_q <= {wcred_q[WCT-2:0], 1'b1};
  end

  // The grant, registered (one-hot; control, reset) with its lane number.
  logic [N-1:0] grant_q;
  logic [LANE_BITS-1:0] gidx_q;
  always_ff @(posedge clk_i) begin
    if (rst_i) grant_q <= '0;
    else grant_q <= w_take ? grant : '0;
  end
  always_ff @(posedge clk_i) gidx_q <= gidx;

  // Copies of grant_q (CTRL_COPIES), so that no flop drives more than
  // CTRL_FANOUT multiplexer inputs (one flop driving all WQ of them, spread
  // over the wide unit's region: a 6.3 ns net on its own). The keep
  // attribute stops Yosys from merging the identical flops.
  logic [CTRL_COPIES*N-1:0] grant_rep_q;
  for (genvar r = 0; r < CTRL_COPIES; r++) begin : g_grant_rep
    (* keep *)
    always_ff @(posedge clk_i) begin
      if (rst_i) grant_rep_q[r*N+:N] <= '0;
      else grant_rep_q[r*N+:N] <= w_take ? grant : '0;
    end
  end

  // The granted slot's wide query and tag (one-hot multiplexer from the
  // copies of grant_q) into the wide unit's input register, every clock:
  // the wide unit's class multiplexers and subtracts start from flops.
  logic [WQ-1:0] w_query, wq_q;
  logic [TAG_BITS-1:0] w_tag;
  logic [LANE_BITS+TAG_BITS-1:0] wq_tag_q;
  always_comb begin
    w_query = '0;
    w_tag = '0;
    for (int l = 0; l < N; l++) begin
      for (int b = 0; b < WQ; b++)
        if (grant_rep_q[(b / CTRL_FANOUT) * N + l]) w_query[b] = w_query[b] | slot_query[l*WQ+b];
      if (grant_q[l]) w_tag = w_tag | slot_tag[l*TAG_BITS+:TAG_BITS];
    end
  end
  always_ff @(posedge clk_i) begin
    if (rst_i) wq_v_q <= 1'b0;
    else wq_v_q <= |grant_q;
  end
  always_ff @(posedge clk_i) begin
    wq_q <= w_query;
    wq_tag_q <= {gidx_q, w_tag};
  end

`ifdef ASSERT_ON
  // The credits keep the wide unit ready for every query in its input
  // register, and never exceed its FIFO depth.
  always_ff @(posedge clk_i) begin
    if (!rst_i) begin
      a_wide_ready : assert (!wq_v_q || w_in_ready);
      a_wcred_top : assert (!wcred_q[WCT-1]);
    end
  end
`endif

  // -------------------------------------------------------------------------
  // The wide unit: tag = {lane, tag}
  // -------------------------------------------------------------------------
  wire [2:0] w_class;
  wire [WC3-1:0] w_org, w_end, w_min, w_max;
  wire [WD3-1:0] w_dir;
  wire w_end_valid;
  assign {w_class, w_org, w_dir, w_end, w_end_valid, w_min, w_max} = wq_q;
  wire unused_wide_strict;

  pluecker_intersector #(
      .COORD_BITS(WIDE_COORD_BITS),
      .DIR_BITS(WIDE_DIR_BITS),
      .TAG_BITS(LANE_BITS + TAG_BITS),
      .CONSERVATIVE(1),
      .MUL_STYLE(WIDE_MUL_STYLE),
      .PIPELINE(PIPELINE)
  ) u_wide (
      .clk_i(clk_i),
      .rst_i(rst_i),
      .in_valid_i(wq_v_q),
      .in_ready_o(w_in_ready),
      .in_tag_i(wq_tag_q),
      .ray_class_i(w_class),
      .ray_org_i(w_org),
      .ray_dir_i(w_dir),
      .ray_end_i(w_end),
      .ray_end_valid_i(w_end_valid),
      .box_min_i(w_min),
      .box_max_i(w_max),
      .out_valid_o(esc_valid_o),
      .out_ready_i(esc_ready_i),
      .out_tag_o({esc_lane_o, esc_tag_o}),
      .out_hit_o(esc_hit_o),
      .out_strict_o(unused_wide_strict)  // TERNARY = 0: constant 0
  );

endmodule

`default_nettype wire
