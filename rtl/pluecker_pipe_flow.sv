// SPDX-License-Identifier: MIT
// Flow control of a never-stalling pipeline of STAGES register stages (the
// float units pluecker_float_intersector and pluecker_smits_intersector):
// the valid bits and tags beside the datapath, the output FIFO and the
// credit counter, as pluecker_intersector keeps them.
//
// A query is taken at a rising edge with in_valid_i && in_ready_o and rst_i
// low; the datapath registers it (its stage 0) at that edge, and
// STAGES - 1 edges later it is in the datapath's last stage, whose answer
// res_hit_i (combinational from that stage's registers) is written into the
// FIFO at the next edge with the query's tag. Results leave in input order
// (out_valid_o && out_ready_i). LATENCY = STAGES + 1 edges from the input
// to the earliest output handshake.
//
// The datapath never stalls and has no clock enable. credits_q counts free
// FIFO entries not yet promised to a query in flight: a transfer in takes
// one, a transfer out returns one, so the FIFO (FIFO_DEPTH >= LATENCY + 2
// entries sustain one query per clock with out_ready_i high) never
// overflows. in_ready_o and out_valid_o are flops; rst_i (synchronous,
// active high) drops every query in flight: in_ready_o and out_valid_o are
// low from the first reset edge on, in_ready_o rises one cycle after the
// release. Only the valid bits, the credits and the FIFO pointers are reset.
`default_nettype none

module pluecker_pipe_flow #(
    parameter int STAGES = 2,
    parameter int TAG_BITS = 16,
    parameter int FIFO_DEPTH = 8
) (
    input  wire                clk_i,
    input  wire                rst_i,
    input  wire                in_valid_i,
    output wire                in_ready_o,
    input  wire [TAG_BITS-1:0] in_tag_i,
    input  wire                res_hit_i,    // answer of the query in the last stage
    output wire                out_valid_o,
    input  wire                out_ready_i,
    output wire [TAG_BITS-1:0] out_tag_o,
    output wire                out_hit_o
);
  localparam int LATENCY = STAGES + 1;
  localparam bit DEPTH_POW2 = FIFO_DEPTH >= 2 && (FIFO_DEPTH & (FIFO_DEPTH - 1)) == 0;
  if (STAGES < 1 || TAG_BITS < 1 || !DEPTH_POW2 || FIFO_DEPTH < LATENCY + 2) begin : g_bad
    $error("pluecker_pipe_flow: STAGES and TAG_BITS must be at least 1, FIFO_DEPTH a power of two >= STAGES + 3");
  end

  // FIFO index bits and pointer bits (one extra bit tells full from empty).
  localparam int FIFO_AW = $clog2(FIFO_DEPTH);
  localparam int FIFO_PW = FIFO_AW + 1;
  // Credit counter: 0..FIFO_DEPTH.
  localparam int CW = $clog2(FIFO_DEPTH + 1);
  localparam logic [CW-1:0] CREDITS_FULL = FIFO_DEPTH[CW-1:0];

  // Control (reset): valid bits of the stages, credits, pointers.
  logic [STAGES-1:0] v_q;
  logic ready_q;
  logic [CW-1:0] credits_q, credits_d;
  logic [FIFO_PW-1:0] wr_ptr_q, rd_ptr_q;

  wire take = in_valid_i && ready_q;
  wire give = out_valid_o && out_ready_i;
  wire last = v_q[STAGES-1];

  always_comb begin
    credits_d = credits_q;
    if (take && !give) credits_d = credits_q - 1'b1;
    if (give && !take) credits_d = credits_q + 1'b1;
  end

  always_ff @(posedge clk_i) begin
    if (rst_i) begin
      v_q <= '0;
      ready_q <= 1'b0;
      credits_q <= CREDITS_FULL;
      wr_ptr_q <= '0;
      rd_ptr_q <= '0;
    end else begin
      v_q <= STAGES'({v_q, take});
      ready_q <= credits_d != '0;
      credits_q <= credits_d;
      if (last) wr_ptr_q <= wr_ptr_q + 1'b1;
      if (give) rd_ptr_q <= rd_ptr_q + 1'b1;
    end
  end

  assign in_ready_o  = ready_q;
  assign out_valid_o = wr_ptr_q != rd_ptr_q;

  // Tags beside the datapath (data: no reset).
  wire [TAG_BITS-1:0] tag_last;
  pluecker_pipe #(.WIDTH(TAG_BITS), .STAGES(STAGES)) u_tag (.clk_i(clk_i), .d_i(in_tag_i), .q_o(tag_last));

  // Output FIFO (contents not reset; the pointers are).
  logic [TAG_BITS:0] fifo_q[FIFO_DEPTH];

  always_ff @(posedge clk_i) begin
    if (last) fifo_q[wr_ptr_q[FIFO_AW-1:0]] <= {tag_last, res_hit_i};
  end

  assign {out_tag_o, out_hit_o} = fifo_q[rd_ptr_q[FIFO_AW-1:0]];

`ifdef ASSERT_ON
  // Handshake and flow-control assertions, as pluecker_intersector's:
  // labelled immediate assertions on flopped history.
  logic chk_live_q;  // the previous edge had rst_i low
  logic out_stall_q, in_stall_q;
  logic [TAG_BITS:0] out_prev_q;
  logic [TAG_BITS-1:0] in_prev_q;
  wire [FIFO_PW-1:0] fifo_count = wr_ptr_q - rd_ptr_q;
  logic [31:0] in_flight;

  always_comb begin
    in_flight = '0;
    for (int s = 0; s < STAGES; s++) in_flight = in_flight + 32'(v_q[s]);
  end

  always_ff @(posedge clk_i) begin
    chk_live_q  <= !rst_i;
    out_stall_q <= out_valid_o && !out_ready_i;
    out_prev_q  <= {out_tag_o, out_hit_o};
    in_stall_q  <= in_valid_i && !in_ready_o;
    in_prev_q   <= in_tag_i;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_i && chk_live_q) begin
      // A result, once offered, stays offered and unchanged until taken.
      if (out_stall_q) begin
        a_out_hold :
        assert (out_valid_o && {out_tag_o, out_hit_o} == out_prev_q);
      end
      // The same rule upstream (a check on the environment; the units
      // compare their whole payload in their own assertion).
      if (in_stall_q) begin
        a_in_hold :
        assert (in_valid_i && in_tag_i == in_prev_q);
      end
    end
    if (!rst_i) begin
      // Credits, queries in flight and FIFO entries add up to the depth.
      a_credit_balance :
      assert (32'(credits_q) + in_flight + 32'(fifo_count) == FIFO_DEPTH);
      a_ready_credit :
      assert (!ready_q || credits_q != '0);
    end
  end
`endif
endmodule

`default_nettype wire
