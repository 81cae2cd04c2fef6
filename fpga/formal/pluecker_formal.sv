// SPDX-License-Identifier: MIT
// Formal harness for rtl/pluecker_intersector.sv (SymbiYosys, Yosys SMT flow;
// see fpga/formal/README.md).
//
// The DUT is read with ASSERT_ON, so its own assertions (a_out_hold,
// a_in_hold, a_credit_balance, a_ready_credit) are proof obligations here.
// Every DUT input is a free variable in every cycle, except for what this
// harness assumes about the environment:
//   - rst_i is high in the first cycle;
//   - the upstream side keeps the valid/ready rule the DUT's a_in_hold checks
//     (a query offered and not taken is offered again, unchanged, tag
//     included);
//   - one watched query: the queries are numbered from 0 after every reset
//     (in_count, mod 2^SEQ_BITS); the one numbered watch_seq carries the tag
//     watch_tag. watch_seq and watch_tag are free constants (anyconst), every
//     other tag is a free input. A proof for every watch_seq and watch_tag
//     is a proof for every query and every tag.
// The harness proves:
//   p_order         out_valid_o && out_count == watch_seq -> out_tag_o ==
//                   watch_tag: the k-th result after a reset carries the tag
//                   of the k-th query after it, for every k and every tag:
//                   results leave in input order, none is lost, duplicated,
//                   or left over from before a reset
//   p_outstanding   at most FIFO_DEPTH queries are accepted and not yet
//                   delivered
//   p_reset_quiet   in_ready_o and out_valid_o are low from the second reset
//                   cycle on and in the first cycle after it
//   p_ready_after   in_ready_o is high in the second cycle with rst_i low
//                   after a reset (it rises one cycle after the release)
//   p_full_rate     in_ready_o is high whenever the previous cycle was not a
//                   reset and had out_ready_i high: an unblocked output never
//                   blocks the input (one query per clock)
// and covers the FIFO full, a reset while it is full and stalled, a hit, a
// miss, FIFO_DEPTH results back to back, and a full FIFO drained.
//
// The lemmas below (l_*) make all of it 1-inductive: each holds in every
// state after the first and, with the others, is kept by every transition.
// They are written without sums of valid bits (counting is what SAT
// solvers find hard): the harness keeps the number of the query in every
// pipeline stage (a shadow shift register beside the DUT's), the numbers
// in flight are consecutive, the oldest is the next FIFO write, and the FIFO
// pointers equal the query counts (SEQ_BITS is the pointer width).
//
// Configurations: the datapath does not take part in any handshake, but the
// pipeline length does: it has PIPELINE + MUL_ADD stages S2x between S2 and
// S3, and the FIFO depth follows from LATENCY. fpga/formal/run.sh runs the
// proof at one configuration of every S2x count and passes the port
// contract's S2X_STAGES, LATENCY and FIFO_DEPTH for it (rtl/
// pluecker_contract.json); the DUT checks at elaboration that it derives the
// same, so the harness's stage model is the DUT's.
`default_nettype none

module pluecker_formal #(
    parameter int COORD_BITS = 6,
    parameter int DIR_BITS = 6,
    parameter MUL_STYLE = "auto",
    parameter int PIPELINE = 0,
    parameter bit CONSERVATIVE = 1,
    // The port contract's values for the configuration (run.sh sets them).
    parameter int S2X_STAGES = -1,
    parameter int LATENCY = -1,
    parameter int FIFO_DEPTH = -1,
    // Tags are free data here (only the watched one is fixed): 4 bits tell a
    // tag from a permutation or a constant of its bits.
    parameter int TAG_BITS = 4
) (
    input wire clk_i,
    input wire rst_i,
    input wire in_valid_i,
    input wire [TAG_BITS-1:0] in_tag_i,
    input wire [2:0] ray_class_i,
    input wire [3*COORD_BITS-1:0] ray_org_i,
    input wire [3*DIR_BITS-1:0] ray_dir_i,
    input wire [3*COORD_BITS-1:0] ray_end_i,
    input wire ray_end_valid_i,
    input wire [3*COORD_BITS-1:0] box_min_i,
    input wire [3*COORD_BITS-1:0] box_max_i,
    input wire out_ready_i
);
  // S0..S4, the S2x stages and the FIFO write.
  if (S2X_STAGES < 0 || LATENCY != 6 + S2X_STAGES || FIFO_DEPTH < LATENCY + 2 ||
      (FIFO_DEPTH & (FIFO_DEPTH - 1)) != 0) begin : g_bad_contract
    $error("pluecker_formal: S2X_STAGES, LATENCY and FIFO_DEPTH must be the port contract's (run.sh sets them)");
  end
  // The DUT's FIFO pointer width (one bit more than the index), also the
  // width of the query numbers: a pointer is then the number of the query
  // it points at, and 2^SEQ_BITS > FIFO_DEPTH queries outstanding never alias.
  localparam int SEQ_BITS = $clog2(FIFO_DEPTH) + 1;
  localparam int AW = SEQ_BITS - 1;  // FIFO index bits
  // Pipeline stages from the oldest (S4, index 0) to the youngest (S0).
  localparam int NST = 5 + S2X_STAGES;

  wire in_ready_o, out_valid_o, out_hit_o;
  wire out_strict_o;  // TERNARY = 0: constant 0
  wire [TAG_BITS-1:0] out_tag_o;

  pluecker_intersector #(
      .COORD_BITS(COORD_BITS),
      .DIR_BITS(DIR_BITS),
      .TAG_BITS(TAG_BITS),
      .CONSERVATIVE(CONSERVATIVE),
      .MUL_STYLE(MUL_STYLE),
      .PIPELINE(PIPELINE)
  ) dut (
      .clk_i(clk_i),
      .rst_i(rst_i),
      .in_valid_i(in_valid_i),
      .in_ready_o(in_ready_o),
      .in_tag_i(in_tag_i),
      .ray_class_i(ray_class_i),
      .ray_org_i(ray_org_i),
      .ray_dir_i(ray_dir_i),
      .ray_end_i(ray_end_i),
      .ray_end_valid_i(ray_end_valid_i),
      .box_min_i(box_min_i),
      .box_max_i(box_max_i),
      .out_valid_o(out_valid_o),
      .out_ready_i(out_ready_i),
      .out_tag_o(out_tag_o),
      .out_hit_o(out_hit_o),
      .out_strict_o(out_strict_o)
  );

  wire take = in_valid_i && in_ready_o && !rst_i;
  wire give = out_valid_o && out_ready_i && !rst_i;

  // The watched query (free, constant over the trace).
  (* anyconst *) logic [SEQ_BITS-1:0] watch_seq;
  (* anyconst *) logic [TAG_BITS-1:0] watch_tag;

  // -------------------------------------------------------------------------
  // History (initial values: the first cycle is cycle 0)
  // -------------------------------------------------------------------------
  logic first_q = 1'b1;  // cycle 0
  logic rst1_q = 1'b0;  // rst_i in the previous cycle
  logic rst2_q = 1'b0;  // ... two cycles ago
  logic open1_q = 1'b0;  // previous cycle: not reset and out_ready_i high
  logic in_stall_q = 1'b0;  // previous cycle: offered and not taken, no reset
  // The DUT's in_now: the tag and every query field.
  localparam int IN_W = TAG_BITS + 3 + 4 * 3 * COORD_BITS + 3 * DIR_BITS + 1;
  wire [IN_W-1:0] in_now = {
    in_tag_i, ray_class_i, ray_org_i, ray_dir_i, ray_end_i, ray_end_valid_i, box_min_i, box_max_i
  };
  logic [IN_W-1:0] in_prev_q = '0;
  // Queries taken and results given since the last reset (mod 2^SEQ_BITS).
  logic [SEQ_BITS-1:0] in_count_q = '0, out_count_q = '0;
  wire [SEQ_BITS-1:0] outstanding = in_count_q - out_count_q;
  logic [SEQ_BITS:0] burst_q = '0;  // consecutive output handshakes (saturating)
  logic full_seen_q = 1'b0;

  always_ff @(posedge clk_i) begin
    first_q <= 1'b0;
    rst1_q <= rst_i;
    rst2_q <= rst1_q;
    open1_q <= !rst_i && out_ready_i;
    in_stall_q <= !rst_i && in_valid_i && !in_ready_o;
    in_prev_q <= in_now;
    if (rst_i) begin
      in_count_q <= '0;
      out_count_q <= '0;
    end else begin
      if (take) in_count_q <= in_count_q + 1'b1;
      if (give) out_count_q <= out_count_q + 1'b1;
    end
    burst_q <= give ? (burst_q == '1 ? burst_q : burst_q + 1'b1) : '0;
    if (rst_i) full_seen_q <= 1'b0;
    else if (!in_ready_o && out_valid_o && outstanding == FIFO_DEPTH) full_seen_q <= 1'b1;
  end

  // -------------------------------------------------------------------------
  // Probes of DUT state, for the lemmas below. Undriven here: the .sby script
  // connects them to the flattened DUT's flops (`connect -set`), since Yosys
  // does not resolve hierarchical references. The S2x probes exist only
  // with S2x stages (dut.g_s2x.v_q and dut.g_s2x.tag_q, stage s at index s);
  // without, they are tied to zero here.
  // -------------------------------------------------------------------------
  localparam int S2W = (S2X_STAGES > 0) ? S2X_STAGES : 1;
  wire probe_v0, probe_v1, probe_v2, probe_v3, probe_v4;
  wire [S2W-1:0] probe_v2x;
  wire [TAG_BITS-1:0] probe_tag0, probe_tag1, probe_tag2, probe_tag3, probe_tag4;
  wire [S2W-1:0][TAG_BITS-1:0] probe_tag2x;
  wire [SEQ_BITS-1:0] probe_wr, probe_rd;
  wire [TAG_BITS+1:0] probe_fifo[FIFO_DEPTH];  // {tag, hit, strict}
  wire [FIFO_DEPTH:0] probe_credits;  // the DUT's thermometer codes (bit i: more than i)
  wire probe_ready;
  wire [FIFO_DEPTH:0] probe_occ;
  // The history flops of the DUT's own assertions (ASSERT_ON).
  wire probe_chk_live, probe_in_stall, probe_out_stall;
  wire [IN_W-1:0] probe_in_prev;
  wire [TAG_BITS+1:0] probe_out_prev;
  if (S2X_STAGES == 0) begin : g_no_s2x
    assign probe_v2x = '0;
    assign probe_tag2x = '0;
  end
  wire [SEQ_BITS-1:0] fifo_count = probe_wr - probe_rd;
  // n as the DUT's thermometer code (bits 0..n-1 set).
  function automatic logic [FIFO_DEPTH:0] thermometer(input logic [SEQ_BITS-1:0] n);
    thermometer = ((FIFO_DEPTH + 1)'(1) << n) - 1'b1;
  endfunction

  // The stages from the oldest (index 0: S4, S3, the S2x stages from the
  // last, S2, S1) to the youngest (NST - 1: S0): valid bit and tag.
  logic [NST-1:0] v;
  logic [NST-1:0][TAG_BITS-1:0] tag;
  always_comb begin
    v[0] = probe_v4;
    tag[0] = probe_tag4;
    v[1] = probe_v3;
    tag[1] = probe_tag3;
    for (int s = 0; s < S2X_STAGES; s++) begin
      v[2+s] = probe_v2x[S2X_STAGES-1-s];
      tag[2+s] = probe_tag2x[S2X_STAGES-1-s];
    end
    v[NST-3] = probe_v2;
    tag[NST-3] = probe_tag2;
    v[NST-2] = probe_v1;
    tag[NST-2] = probe_tag1;
    v[NST-1] = probe_v0;
    tag[NST-1] = probe_tag0;
  end

  // Shadow pipeline: seq_q[i] is the number the query in stage i got when it
  // was taken (in_count then); it shifts with the DUT's stages, valid or not.
  logic [NST-1:0][SEQ_BITS-1:0] seq_q;
  always_ff @(posedge clk_i) begin
    seq_q[NST-1] <= in_count_q;
    for (int i = 0; i < NST - 1; i++) seq_q[i] <= seq_q[i+1];
  end

  // next[i]: the number of the oldest query in stages i..NST-1, or in_count
  // when they are empty (next[NST] = in_count: the next query to be taken).
  logic [NST:0][SEQ_BITS-1:0] next;
  always_comb begin
    next[NST] = in_count_q;
    for (int i = NST - 1; i >= 0; i--) next[i] = v[i] ? seq_q[i] : next[i+1];
  end

  // -------------------------------------------------------------------------
  // Environment
  // -------------------------------------------------------------------------
  always_comb begin
    if (first_q) assume (rst_i);
    // The upstream valid/ready rule (what the DUT's a_in_hold checks).
    if (!rst_i && in_stall_q) assume (in_valid_i && in_now == in_prev_q);
    if (in_count_q == watch_seq) assume (in_tag_i == watch_tag);
  end

  // -------------------------------------------------------------------------
  // Properties
  // -------------------------------------------------------------------------
  always_comb begin
    if (!first_q && !rst_i) begin
      if (out_valid_o && out_count_q == watch_seq) p_order : assert (out_tag_o == watch_tag);
      p_outstanding : assert (outstanding <= FIFO_DEPTH);
      if (open1_q) p_full_rate : assert (in_ready_o);
    end
    if (rst1_q) p_reset_quiet : assert (!in_ready_o && !out_valid_o);
    if (rst2_q && !rst1_q) p_ready_after : assert (in_ready_o);
  end

  // -------------------------------------------------------------------------
  // Lemmas (proved like the properties; they make everything 1-inductive).
  // -------------------------------------------------------------------------
  always_comb begin
    if (!first_q) begin
      // The FIFO holds the queries out_count .. wr - 1 (the read pointer is
      // the number of results given), the stages hold wr .. in_count - 1.
      l_rd : assert (probe_rd == out_count_q);
      l_wr : assert (probe_wr == next[0]);
      l_fifo : assert (fifo_count <= outstanding);
      // Credits: FIFO_DEPTH less the queries outstanding; ready follows the
      // credits (the DUT's a_credit_balance and a_ready_credit, which Yosys
      // checks one cycle late, as of the current state).
      l_credits : assert (probe_credits == thermometer(SEQ_BITS'(FIFO_DEPTH) - outstanding));
      l_ready : assert (rst1_q ? !probe_ready : probe_ready == probe_credits[0]);
      // The result count follows the pointers.
      l_count : assert (probe_occ == thermometer(fifo_count));
      // The DUT's assertion history is the harness's.
      l_hist : assert (probe_chk_live == !rst1_q && probe_in_prev == in_prev_q &&
                       (rst1_q || probe_in_stall == in_stall_q));
      // A result offered and not taken is still offered (a_out_hold, now).
      if (!rst_i && !rst1_q && probe_out_stall)
        l_out_hold : assert (out_valid_o && {out_tag_o, out_hit_o, out_strict_o} == probe_out_prev);
    end
  end
  for (genvar i = 0; i < NST; i++) begin : g_stage
    // l_next, l_tag (unlabelled: Yosys does not prefix labels inside
    // generate blocks): the numbers in flight are consecutive, and the
    // watched query in a stage carries its tag.
    always_comb begin
      if (!first_q && v[i]) begin
        assert (SEQ_BITS'(seq_q[i] + 1'b1) == next[i+1]);
        if (seq_q[i] == watch_seq) assert (tag[i] == watch_tag);
      end
    end
  end
  for (genvar k = 0; k < FIFO_DEPTH; k++) begin : g_slot
    // l_slot (unlabelled): the watched query in the FIFO carries its tag.
    wire [AW-1:0] idx = AW'(k) - probe_rd[AW-1:0];  // position behind the head
    always_comb begin
      if (!first_q && SEQ_BITS'(idx) < fifo_count && probe_rd + SEQ_BITS'(idx) == watch_seq)
        assert (probe_fifo[k][TAG_BITS+1:2] == watch_tag);
    end
  end

  // -------------------------------------------------------------------------
  // Cover
  // -------------------------------------------------------------------------
  always_comb begin
    if (!first_q) begin
      c_fifo_full : cover (!rst_i && !in_ready_o && out_valid_o && outstanding == FIFO_DEPTH);
      c_reset_while_full : cover (rst_i && !rst1_q && !in_ready_o && !out_ready_i && outstanding == FIFO_DEPTH);
      c_hit : cover (give && out_hit_o);
      c_miss : cover (give && !out_hit_o);
      c_burst : cover (burst_q == (SEQ_BITS + 1)'(FIFO_DEPTH));
      c_full_then_drained : cover (full_seen_q && !rst_i && in_ready_o && outstanding == '0);
    end
  end
endmodule

`default_nettype wire
