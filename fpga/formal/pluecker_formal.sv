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
//     (a query offered and not taken is offered again, unchanged);
//   - in_tag_i = {epoch, in_count}: in_count counts the queries taken since
//     the last reset (mod 2^SEQ_BITS), epoch counts reset pulses
//     (mod 2^EPOCH_BITS). Tags thus number the queries.
// With the tags numbered, the harness proves:
//   p_order         out_valid_o -> out_tag_o == {epoch, out_count}: results
//                   leave in input order, none is lost or duplicated, and no
//                   query taken before a reset leaves after it (it would
//                   carry an older epoch; a leak across exactly a multiple
//                   of 2^EPOCH_BITS reset pulses is the one case the epoch
//                   cannot tell)
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
    parameter int SEQ_BITS = 5,  // > log2(FIFO_DEPTH + 1): in-order numbers never alias
    parameter int EPOCH_BITS = 3
) (
    input wire clk_i,
    input wire rst_i,
    input wire in_valid_i,
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
  if (S2X_STAGES < 0 || LATENCY != 6 + S2X_STAGES || FIFO_DEPTH < LATENCY + 2) begin : g_bad_contract
    $error("pluecker_formal: S2X_STAGES, LATENCY and FIFO_DEPTH must be the port contract's (run.sh sets them)");
  end
  if ((1 << SEQ_BITS) <= FIFO_DEPTH + 1) begin : g_bad_seq_bits
    $error("pluecker_formal: SEQ_BITS must exceed log2(FIFO_DEPTH + 1)");
  end
  localparam int TAG_BITS = EPOCH_BITS + SEQ_BITS;

  wire in_ready_o, out_valid_o, out_hit_o;
  wire [TAG_BITS-1:0] out_tag_o;

  logic [EPOCH_BITS-1:0] epoch_q = '0;
  logic [SEQ_BITS-1:0] in_count_q = '0, out_count_q = '0;
  wire [TAG_BITS-1:0] in_tag_i = {epoch_q, in_count_q};

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
      .out_hit_o(out_hit_o)
  );

  wire take = in_valid_i && in_ready_o && !rst_i;
  wire give = out_valid_o && out_ready_i && !rst_i;

  // -------------------------------------------------------------------------
  // History (initial values: the first cycle is cycle 0)
  // -------------------------------------------------------------------------
  logic first_q = 1'b1;  // cycle 0
  logic rst1_q = 1'b0;  // rst_i in the previous cycle
  logic rst2_q = 1'b0;  // ... two cycles ago
  logic open1_q = 1'b0;  // previous cycle: not reset and out_ready_i high
  logic in_stall_q = 1'b0;  // previous cycle: offered and not taken, no reset
  localparam int IN_W = 3 + 4 * 3 * COORD_BITS + 3 * DIR_BITS + 1;
  wire [IN_W-1:0] in_now = {
    ray_class_i, ray_org_i, ray_dir_i, ray_end_i, ray_end_valid_i, box_min_i, box_max_i
  };
  logic [IN_W-1:0] in_prev_q = '0;
  logic [SEQ_BITS:0] burst_q = '0;  // consecutive output handshakes (saturating)
  logic full_seen_q = 1'b0;
  wire [SEQ_BITS-1:0] outstanding = in_count_q - out_count_q;

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
      if (!rst1_q) epoch_q <= epoch_q + 1'b1;  // one step per reset pulse
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
  localparam int PW = $clog2(FIFO_DEPTH) + 1;  // the DUT's FIFO pointer width
  localparam int S2W = (S2X_STAGES > 0) ? S2X_STAGES : 1;
  wire probe_v0, probe_v1, probe_v2, probe_v3, probe_v4;
  wire [S2W-1:0] probe_v2x;
  wire [PW-1:0] probe_wr, probe_rd;
  wire [TAG_BITS-1:0] probe_tag0, probe_tag1, probe_tag2, probe_tag3, probe_tag4;
  wire [S2W-1:0][TAG_BITS-1:0] probe_tag2x;
  wire [TAG_BITS:0] probe_fifo[FIFO_DEPTH];  // {tag, hit}
  if (S2X_STAGES == 0) begin : g_no_s2x
    assign probe_v2x = '0;
    assign probe_tag2x = '0;
  end
  wire [PW-1:0] fifo_count = probe_wr - probe_rd;
  logic [PW-1:0] in_flight;
  always_comb begin
    in_flight = PW'(probe_v0) + PW'(probe_v1) + PW'(probe_v2) + PW'(probe_v3) + PW'(probe_v4);
    for (int s = 0; s < S2X_STAGES; s++) in_flight = in_flight + PW'(probe_v2x[s]);
  end
  // Query numbers of the pipeline stages: the FIFO holds out_count ..
  // out_count + fifo_count - 1, then the stages from S4 back to S0. seq2x[s]
  // is the number behind S2x stage s (seq2x[S2X_STAGES] behind S3), so stage
  // s holds seq2x[s + 1] and S2 holds seq2x[0].
  wire [SEQ_BITS-1:0] seq4 = out_count_q + SEQ_BITS'(fifo_count);
  wire [SEQ_BITS-1:0] seq3 = seq4 + SEQ_BITS'(probe_v4);
  wire [S2X_STAGES:0][SEQ_BITS-1:0] seq2x;
  assign seq2x[S2X_STAGES] = seq3 + SEQ_BITS'(probe_v3);
  for (genvar s = 0; s < S2X_STAGES; s++) begin : g_seq2x
    assign seq2x[s] = seq2x[s+1] + SEQ_BITS'(probe_v2x[s]);
  end
  wire [SEQ_BITS-1:0] seq2 = seq2x[0];
  wire [SEQ_BITS-1:0] seq1 = seq2 + SEQ_BITS'(probe_v2);
  wire [SEQ_BITS-1:0] seq0 = seq1 + SEQ_BITS'(probe_v1);

  // -------------------------------------------------------------------------
  // Environment
  // -------------------------------------------------------------------------
  always_comb begin
    if (first_q) assume (rst_i);
    // The upstream valid/ready rule (what the DUT's a_in_hold checks).
    if (!rst_i && in_stall_q) assume (in_valid_i && in_now == in_prev_q);
  end

  // -------------------------------------------------------------------------
  // Properties
  // -------------------------------------------------------------------------
  always_comb begin
    if (!first_q && !rst_i) begin
      if (out_valid_o) p_order : assert (out_tag_o == {epoch_q, out_count_q});
      p_outstanding : assert (outstanding <= FIFO_DEPTH);
      if (open1_q) p_full_rate : assert (in_ready_o);
    end
    if (rst1_q) p_reset_quiet : assert (!in_ready_o && !out_valid_o);
    if (rst2_q && !rst1_q) p_ready_after : assert (in_ready_o);
  end

  // -------------------------------------------------------------------------
  // Lemmas (proved like the properties; they make the properties inductive):
  // every query in flight sits in the stage or FIFO slot its number says.
  // -------------------------------------------------------------------------
  always_comb begin
    if (!first_q) begin
      l_in_flight : assert (SEQ_BITS'(in_flight) + SEQ_BITS'(fifo_count) == outstanding);
      if (probe_v4) l_tag4 : assert (probe_tag4 == {epoch_q, seq4});
      if (probe_v3) l_tag3 : assert (probe_tag3 == {epoch_q, seq3});
      if (probe_v2) l_tag2 : assert (probe_tag2 == {epoch_q, seq2});
      if (probe_v1) l_tag1 : assert (probe_tag1 == {epoch_q, seq1});
      if (probe_v0) l_tag0 : assert (probe_tag0 == {epoch_q, seq0});
    end
  end
  for (genvar s = 0; s < S2X_STAGES; s++) begin : g_stage2x
    // l_tag2x (unlabelled, as l_slot below)
    always_comb begin
      if (!first_q && probe_v2x[s]) assert (probe_tag2x[s] == {epoch_q, seq2x[s+1]});
    end
  end
  for (genvar k = 0; k < FIFO_DEPTH; k++) begin : g_slot
    // l_slot (unlabelled: Yosys does not prefix labels inside generate blocks)
    wire [PW-2:0] idx = (PW - 1)'(k) - probe_rd[PW-2:0];  // position behind the head
    always_comb begin
      if (!first_q && PW'(idx) < fifo_count)
        assert (probe_fifo[k][TAG_BITS:1] == {epoch_q, out_count_q + SEQ_BITS'(idx)});
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
