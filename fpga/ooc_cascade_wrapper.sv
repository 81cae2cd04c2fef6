// SPDX-License-Identifier: MIT
// Out-of-context timing harness of pluecker_cascade for the ECP5 flow
// (scripts/synth.py --cascade): N_CASCADES independent cascades of
// N_NARROW lanes each (a whole chip of them with N_CASCADES > 1), every
// input registered once on its way in and every output once on its way
// out, so that every timed path starts and ends at a flip-flop and nextpnr
// (--out-of-context) needs no pins. Lane m*N_NARROW + l is lane l of
// cascade m; escalation stream m is cascade m's esc_*. With N_WIDE > 0
// the chip also holds N_WIDE plain wide units (a pluecker_array of
// N_WIDE MULT18X18D units at the wide format, conservative), on lanes
// M*N_NARROW .. M*N_NARROW+N_WIDE-1: they take the tag and the wide query
// of their payload (the narrow fields are unused) and answer on their
// out_* lanes; so a chip that leaves multiplier blocks over after its
// cascades puts them to work as further wide units. Timing and
// utilisation only: the extra register stage delays the ready bits by a
// cycle, so the harness does not keep the valid/ready contract. Its
// flip-flops are named ooc_*_q, besides the reset chains it builds
// (g_chain; all counted apart from the cascades'); the valid and ready
// bits are reset, the rest are not. RST_STAGES > 0 builds
// a reset tree, so that no reset net spans the chip: each cascade takes
// its rst_i from a kept chain of RST_STAGES flops of its own, the plain
// units from theirs (pluecker_array's RST_STAGES), the harness's flops of
// a lane or an escalation stream from a kept chain as deep each.
//
// CLOCKS = 1: everything on clk_i (clk_wide_i is not used). CLOCKS = 2
// (needs N_WIDE > 0): the plain wide units (u_wide), their lanes' harness
// flops and reset chains run on clk_wide_i, with rst_i registered on that
// clock too, so that they run at their own Fmax instead of the cascades'.
// The cascades, their lanes and escalation streams stay on clk_i. Nothing
// crosses between the domains (the plain units are lanes of their own);
// the chip's box tests per second are M*N_NARROW x Fmax(clk_i) + N_WIDE x
// Fmax(clk_wide_i).
`default_nettype none

module ooc_cascade_wrapper #(
    parameter int N_CASCADES = 1,
    parameter int N_NARROW = 2,
    parameter int NARROW_COORD_BITS = 8,
    parameter int NARROW_DIR_BITS = 8,
    parameter int WIDE_COORD_BITS = 16,
    parameter int WIDE_DIR_BITS = 16,
    parameter int TAG_BITS = 16,
    parameter int PIPELINE = 0,
    parameter int N_WIDE = 0,  // plain wide units beside the cascades
    parameter int RST_STAGES = 0,  // reset tree: flops per cascade in front of its rst_i (0..8)
    parameter int CLOCKS = 1,  // 1: one clock; 2: the plain wide units on clk_wide_i
    localparam int M = N_CASCADES,
    localparam int NL = M * N_NARROW,  // cascade lanes
    localparam int N = NL + N_WIDE,  // lanes in all
    localparam int LANE_BITS = (N_NARROW > 1) ? $clog2(N_NARROW) : 1,
    // The query payload of all lanes: narrow and wide class, origin,
    // direction, end, end valid, box.
    localparam int NQ = 3 + 4 * 3 * NARROW_COORD_BITS + 3 * NARROW_DIR_BITS + 1,
    localparam int WQ = 3 + 4 * 3 * WIDE_COORD_BITS + 3 * WIDE_DIR_BITS + 1,
    localparam int PW = N * (TAG_BITS + NQ + WQ),
    localparam int EW = LANE_BITS + TAG_BITS
) (
    input wire clk_i,
    // verilator lint_off UNUSEDSIGNAL
    input wire clk_wide_i,  // CLOCKS = 2 only
    // verilator lint_on UNUSEDSIGNAL
    input wire rst_i,

    input  wire [   N-1:0] in_valid_i,
    output wire [   N-1:0] in_ready_o,
    // Per lane l, bits [l*(TAG_BITS+NQ+WQ) +: ...]: {tag, narrow query as
    // the cascade's ray_*_i/box_*_i fields, wide query as its wide_* fields}.
    input  wire [  PW-1:0] payload_i,

    output wire [         N-1:0] out_valid_o,
    input  wire [         N-1:0] out_ready_i,
    output wire [N*TAG_BITS-1:0] out_tag_o,
    output wire [         N-1:0] out_hit_o,

    output wire [  M-1:0] esc_valid_o,
    input  wire [  M-1:0] esc_ready_i,
    output wire [M*EW-1:0] esc_tag_o,     // per cascade {lane, tag}
    output wire [  M-1:0] esc_hit_o
);
  localparam int NC3 = 3 * NARROW_COORD_BITS;
  localparam int ND3 = 3 * NARROW_DIR_BITS;
  localparam int WC3 = 3 * WIDE_COORD_BITS;
  localparam int WD3 = 3 * WIDE_DIR_BITS;
  localparam int LW = TAG_BITS + NQ + WQ;
  localparam int K = N_NARROW;

  if (N_CASCADES < 1) begin : g_bad_m
    $error("ooc_cascade_wrapper: parameter N_CASCADES must be at least 1");
  end
  if (N_WIDE < 0) begin : g_bad_w
    $error("ooc_cascade_wrapper: parameter N_WIDE must not be negative");
  end
  if (RST_STAGES < 0 || RST_STAGES > 8) begin : g_bad_rst_stages
    $error("ooc_cascade_wrapper: parameter RST_STAGES must be 0..8");
  end
  if (CLOCKS != 1 && CLOCKS != 2) begin : g_bad_clocks
    $error("ooc_cascade_wrapper: parameter CLOCKS must be 1 or 2");
  end
  if (CLOCKS == 2 && N_WIDE < 1) begin : g_bad_clocks_wide
    $error("ooc_cascade_wrapper: CLOCKS = 2 puts the plain wide units on clk_wide_i: N_WIDE must be at least 1");
  end

  logic ooc_rst_q;
  // The lanes' flops are driven lane by lane, each lane on its own clock
  // (clk_i or clk_wide): Verilator's MULTIDRIVEN (driving blocks with
  // different clocks) is waived for these vectors; each bit has one driver,
  // and this synthesis harness is never simulated.
  // verilator lint_off MULTIDRIVEN
  logic [N-1:0] ooc_in_valid_q, ooc_out_ready_q, ooc_in_ready_q, ooc_out_valid_q;
  logic [PW-1:0] ooc_payload_q;
  logic [N*TAG_BITS-1:0] ooc_out_tag_q;
  logic [N-1:0] ooc_out_hit_q;
  // verilator lint_on MULTIDRIVEN
  logic [M-1:0] ooc_esc_ready_q, ooc_esc_valid_q;
  logic [M*EW-1:0] ooc_esc_tag_q;
  logic [M-1:0] ooc_esc_hit_q;

  wire [N-1:0] dut_in_ready, dut_out_valid, dut_out_hit;
  wire [N*TAG_BITS-1:0] dut_out_tag;
  wire [M-1:0] dut_esc_valid, dut_esc_hit;
  wire [M*EW-1:0] dut_esc_tag;  // per cascade {lane, tag}

  always_ff @(posedge clk_i) ooc_rst_q <= rst_i;

  // The plain wide units' clock and registered reset: clk_i and ooc_rst_q
  // with one clock.
  wire clk_wide, rst_wide;
  if (CLOCKS == 2) begin : g_wide_clk
    logic ooc_rst_wide_q;
    always_ff @(posedge clk_wide_i) ooc_rst_wide_q <= rst_i;
    assign {clk_wide, rst_wide} = {clk_wide_i, ooc_rst_wide_q};
  end else begin : g_one_clk
    assign {clk_wide, rst_wide} = {clk_i, ooc_rst_q};
  end

  // The reset of a harness flop of lane l (or of escalation stream m) and
  // of cascade m: ooc_rst_q itself, or the end of a kept chain of
  // RST_STAGES flops (one per lane, stream and cascade; identical flops
  // would otherwise be merged into one).
  wire [N-1:0] lane_rst;
  wire [M-1:0] esc_rst, cascade_rst;
  // Chain c: lane c (c < N), escalation stream c - N, cascade c - N - M.
  wire [N+2*M-1:0] chain_end;
  for (genvar c = 0; c < N + 2 * M; c++) begin : g_chain
    localparam bit WIDE_LANE = c >= NL && c < N;  // a plain unit's lane: its domain
    pluecker_rst_chain #(
        .STAGES(RST_STAGES)
    ) u_rst (
        .clk_i(WIDE_LANE ? clk_wide : clk_i),
        .rst_i(WIDE_LANE ? rst_wide : ooc_rst_q),
        .rst_o(chain_end[c])
    );
  end
  assign {cascade_rst, esc_rst, lane_rst} = chain_end;

  // Each lane's harness flops on its lane's clock: the cascades' lanes on
  // clk_i, the plain units' on clk_wide.
  for (genvar l = 0; l < N; l++) begin : g_lane_ctrl
    wire lane_clk = (l >= NL) ? clk_wide : clk_i;
    always_ff @(posedge lane_clk) begin
      if (lane_rst[l]) begin
        {ooc_in_valid_q[l], ooc_out_ready_q[l], ooc_in_ready_q[l], ooc_out_valid_q[l]} <= '0;
      end else begin
        {ooc_in_valid_q[l], ooc_out_ready_q[l]} <= {in_valid_i[l], out_ready_i[l]};
        {ooc_in_ready_q[l], ooc_out_valid_q[l]} <= {dut_in_ready[l], dut_out_valid[l]};
      end
    end
  end
  for (genvar m = 0; m < M; m++) begin : g_esc_ctrl
    always_ff @(posedge clk_i) begin
      if (esc_rst[m]) {ooc_esc_ready_q[m], ooc_esc_valid_q[m]} <= '0;
      else {ooc_esc_ready_q[m], ooc_esc_valid_q[m]} <= {esc_ready_i[m], dut_esc_valid[m]};
    end
  end

  if (CLOCKS == 2) begin : g_two_clk_data
    always_ff @(posedge clk_i) begin
      ooc_payload_q[NL*LW-1:0] <= payload_i[NL*LW-1:0];
      {ooc_out_tag_q[NL*TAG_BITS-1:0], ooc_out_hit_q[NL-1:0]} <= {dut_out_tag[NL*TAG_BITS-1:0], dut_out_hit[NL-1:0]};
      {ooc_esc_tag_q, ooc_esc_hit_q} <= {dut_esc_tag, dut_esc_hit};
    end
    always_ff @(posedge clk_wide) begin
      ooc_payload_q[PW-1:NL*LW] <= payload_i[PW-1:NL*LW];
      {ooc_out_tag_q[N*TAG_BITS-1:NL*TAG_BITS], ooc_out_hit_q[N-1:NL]} <=
          {dut_out_tag[N*TAG_BITS-1:NL*TAG_BITS], dut_out_hit[N-1:NL]};
    end
  end else begin : g_one_clk_data
    always_ff @(posedge clk_i) begin
      ooc_payload_q <= payload_i;
      {ooc_out_tag_q, ooc_out_hit_q} <= {dut_out_tag, dut_out_hit};
      {ooc_esc_tag_q, ooc_esc_hit_q} <= {dut_esc_tag, dut_esc_hit};
    end
  end

  // The payload's fields, lane by lane.
  logic [N*TAG_BITS-1:0] tag;
  logic [N*3-1:0] cls, wcls;
  logic [N*NC3-1:0] org, fin, lo, hi;
  logic [N*ND3-1:0] dir;
  logic [N*WC3-1:0] worg, wfin, wlo, whi;
  logic [N*WD3-1:0] wdir;
  logic [N-1:0] finv, wfinv;
  for (genvar l = 0; l < N; l++) begin : g_lane
    assign {tag[l*TAG_BITS+:TAG_BITS], cls[l*3+:3], org[l*NC3+:NC3], dir[l*ND3+:ND3], fin[l*NC3+:NC3], finv[l],
            lo[l*NC3+:NC3], hi[l*NC3+:NC3], wcls[l*3+:3], worg[l*WC3+:WC3], wdir[l*WD3+:WD3],
            wfin[l*WC3+:WC3], wfinv[l], wlo[l*WC3+:WC3], whi[l*WC3+:WC3]} = ooc_payload_q[l*LW+:LW];
  end

  for (genvar m = 0; m < M; m++) begin : g_cascade
    wire [LANE_BITS-1:0] esc_lane;
    wire [TAG_BITS-1:0] esc_tag;
    pluecker_cascade #(
        .N_NARROW(N_NARROW),
        .NARROW_COORD_BITS(NARROW_COORD_BITS),
        .NARROW_DIR_BITS(NARROW_DIR_BITS),
        .WIDE_COORD_BITS(WIDE_COORD_BITS),
        .WIDE_DIR_BITS(WIDE_DIR_BITS),
        .TAG_BITS(TAG_BITS),
        .PIPELINE(PIPELINE)
    ) u_dut (
        .clk_i(clk_i),
        .rst_i(cascade_rst[m]),
        .in_valid_i(ooc_in_valid_q[m*K+:K]),
        .in_ready_o(dut_in_ready[m*K+:K]),
        .in_tag_i(tag[m*K*TAG_BITS+:K*TAG_BITS]),
        .ray_class_i(cls[m*K*3+:K*3]),
        .ray_org_i(org[m*K*NC3+:K*NC3]),
        .ray_dir_i(dir[m*K*ND3+:K*ND3]),
        .ray_end_i(fin[m*K*NC3+:K*NC3]),
        .ray_end_valid_i(finv[m*K+:K]),
        .box_min_i(lo[m*K*NC3+:K*NC3]),
        .box_max_i(hi[m*K*NC3+:K*NC3]),
        .wide_ray_class_i(wcls[m*K*3+:K*3]),
        .wide_ray_org_i(worg[m*K*WC3+:K*WC3]),
        .wide_ray_dir_i(wdir[m*K*WD3+:K*WD3]),
        .wide_ray_end_i(wfin[m*K*WC3+:K*WC3]),
        .wide_ray_end_valid_i(wfinv[m*K+:K]),
        .wide_box_min_i(wlo[m*K*WC3+:K*WC3]),
        .wide_box_max_i(whi[m*K*WC3+:K*WC3]),
        .out_valid_o(dut_out_valid[m*K+:K]),
        .out_ready_i(ooc_out_ready_q[m*K+:K]),
        .out_tag_o(dut_out_tag[m*K*TAG_BITS+:K*TAG_BITS]),
        .out_hit_o(dut_out_hit[m*K+:K]),
        .esc_valid_o(dut_esc_valid[m]),
        .esc_ready_i(ooc_esc_ready_q[m]),
        .esc_lane_o(esc_lane),
        .esc_tag_o(esc_tag),
        .esc_hit_o(dut_esc_hit[m])
    );
    assign dut_esc_tag[m*EW+:EW] = {esc_lane, esc_tag};
  end

  if (N_WIDE > 0) begin : g_wide
    // Plain wide units: lanes NL.., the wide fields of their payloads.
    wire unused_narrow = ^{cls[N*3-1:NL*3], org[N*NC3-1:NL*NC3], dir[N*ND3-1:NL*ND3],
                           fin[N*NC3-1:NL*NC3], finv[N-1:NL], lo[N*NC3-1:NL*NC3], hi[N*NC3-1:NL*NC3]};
    pluecker_array #(
        .N_DSP(N_WIDE),
        .N_LUT(0),
        .COORD_BITS(WIDE_COORD_BITS),
        .DIR_BITS(WIDE_DIR_BITS),
        .TAG_BITS(TAG_BITS),
        .CONSERVATIVE(1),
        .PIPELINE(PIPELINE),
        .RST_STAGES(RST_STAGES)
    ) u_wide (
        .clk_i(clk_wide),
        .rst_i(rst_wide),
        .in_valid_i(ooc_in_valid_q[N-1:NL]),
        .in_ready_o(dut_in_ready[N-1:NL]),
        .in_tag_i(tag[N*TAG_BITS-1:NL*TAG_BITS]),
        .ray_class_i(wcls[N*3-1:NL*3]),
        .ray_org_i(worg[N*WC3-1:NL*WC3]),
        .ray_dir_i(wdir[N*WD3-1:NL*WD3]),
        .ray_end_i(wfin[N*WC3-1:NL*WC3]),
        .ray_end_valid_i(wfinv[N-1:NL]),
        .box_min_i(wlo[N*WC3-1:NL*WC3]),
        .box_max_i(whi[N*WC3-1:NL*WC3]),
        .out_valid_o(dut_out_valid[N-1:NL]),
        .out_ready_i(ooc_out_ready_q[N-1:NL]),
        .out_tag_o(dut_out_tag[N*TAG_BITS-1:NL*TAG_BITS]),
        .out_hit_o(dut_out_hit[N-1:NL])
    );
  end

  assign in_ready_o = ooc_in_ready_q;
  assign {out_valid_o, out_tag_o, out_hit_o} = {ooc_out_valid_q, ooc_out_tag_q, ooc_out_hit_q};
  assign {esc_valid_o, esc_tag_o, esc_hit_o} = {ooc_esc_valid_q, ooc_esc_tag_q, ooc_esc_hit_q};
endmodule

`default_nettype wire
