// SPDX-License-Identifier: MIT
// Out-of-context timing harness of pluecker_array for the ECP5 flow
// (scripts/synth.py --array): every port of the array registered once, as
// fpga/ooc_wrapper.sv does for one unit, so that every timed path starts
// and ends at a flip-flop and nextpnr (--out-of-context) needs no pins.
// Timing and utilisation only: the extra register stage delays in_ready_o
// by a cycle, so the harness does not keep the valid/ready contract. Its
// flip-flops are named ooc_*_q, besides its lanes' reset chains (u_lane_rst;
// all counted apart from the array's). With RST_STAGES > 0 (the array's
// reset tree) the harness's lane flops take their reset from a kept chain
// per lane too, so no reset net spans the chip.
//
// CLOCKS = 1: every lane on clk_i (one pluecker_array, u_dut; clk_lut_i is
// not used). CLOCKS = 2: two clock domains, so that each kind of unit runs
// at its own Fmax: the N_DSP units (lanes 0..N_DSP-1) are one
// pluecker_array on clk_i (u_dut), the N_LUT fabric units (lanes
// N_DSP..N-1) another on clk_lut_i (g_lut_clk.u_dut), each lane's harness
// flops and rst_i's register on its lane's clock. Lanes are independent
// streams (rtl/pluecker_array.sv), so nothing crosses between the domains;
// the chip's box tests per second are N_DSP x Fmax(clk_i) + N_LUT x
// Fmax(clk_lut_i). The N_ROM table-multiplier units (the last lanes) need
// CLOCKS = 1.
`default_nettype none

module ooc_array_wrapper #(
    parameter int N_DSP = 1,
    parameter int N_LUT = 1,
    parameter int N_ROM = 0,
    parameter int COORD_BITS = 16,
    parameter int DIR_BITS = 16,
    parameter int TAG_BITS = 16,
    parameter bit CONSERVATIVE = 1,
    parameter int PIPELINE = 0,
    parameter int RST_STAGES = 0,
    parameter int CLOCKS = 1,  // 1: one clock; 2: the fabric units on clk_lut_i
    localparam int N = N_DSP + N_LUT + N_ROM
) (
    input wire clk_i,
    // verilator lint_off UNUSEDSIGNAL
    input wire clk_lut_i,  // CLOCKS = 2 only
    // verilator lint_on UNUSEDSIGNAL
    input wire rst_i,

    input  wire [             N-1:0] in_valid_i,
    output wire [             N-1:0] in_ready_o,
    input  wire [    N*TAG_BITS-1:0] in_tag_i,
    input  wire [           N*3-1:0] ray_class_i,
    input  wire [N*3*COORD_BITS-1:0] ray_org_i,
    input  wire [  N*3*DIR_BITS-1:0] ray_dir_i,
    input  wire [N*3*COORD_BITS-1:0] ray_end_i,
    input  wire [             N-1:0] ray_end_valid_i,
    input  wire [N*3*COORD_BITS-1:0] box_min_i,
    input  wire [N*3*COORD_BITS-1:0] box_max_i,

    output wire [         N-1:0] out_valid_o,
    input  wire [         N-1:0] out_ready_i,
    output wire [N*TAG_BITS-1:0] out_tag_o,
    output wire [         N-1:0] out_hit_o
);
  localparam int CW = N * 3 * COORD_BITS;
  localparam int DW = N * 3 * DIR_BITS;
  localparam int TW = N * TAG_BITS;
  localparam int C = 3 * COORD_BITS;  // a lane's coordinate bits
  localparam int D = 3 * DIR_BITS;  // a lane's direction bits

  if (CLOCKS != 1 && CLOCKS != 2) begin : g_bad_clocks
    $error("ooc_array_wrapper: CLOCKS must be 1 or 2");
  end
  if (CLOCKS == 2 && (N_DSP < 1 || N_LUT < 1)) begin : g_bad_split
    $error("ooc_array_wrapper: CLOCKS = 2 needs DSP and fabric units (N_DSP, N_LUT >= 1)");
  end
  if (CLOCKS == 2 && N_ROM != 0) begin : g_bad_rom_clocks
    $error("ooc_array_wrapper: CLOCKS = 2 takes no table-multiplier units (N_ROM = 0)");
  end

  // The lanes' registered ports (each lane's flops in g_lane[l]).
  wire [N-1:0] ooc_in_valid, ooc_out_ready, ooc_ray_end_valid;
  wire [TW-1:0] ooc_in_tag;
  wire [N*3-1:0] ooc_ray_class;
  wire [CW-1:0] ooc_ray_org, ooc_ray_end, ooc_box_min, ooc_box_max;
  wire [DW-1:0] ooc_ray_dir;

  wire [N-1:0] dut_in_ready, dut_out_valid, dut_out_hit;
  wire [TW-1:0] dut_out_tag;

  // The second domain's clock (clk_i itself with one clock).
  wire clk_lut = (CLOCKS == 2) ? clk_lut_i : clk_i;

  // rst_i registered in each domain (control flops).
  logic ooc_rst_q, ooc_rst_lut_q;
  always_ff @(posedge clk_i) ooc_rst_q <= rst_i;
  always_ff @(posedge clk_lut) ooc_rst_lut_q <= rst_i;

  for (genvar l = 0; l < N; l++) begin : g_lane
    wire lane_clk = (l >= N_DSP) ? clk_lut : clk_i;
    // A kept chain as deep as a unit's (one per lane), so that the
    // harness's reset reaches the far lanes in as many hops.
    wire lane_rst;
    pluecker_rst_chain #(
        .STAGES(RST_STAGES)
    ) u_lane_rst (
        .clk_i(lane_clk),
        .rst_i((l >= N_DSP) ? ooc_rst_lut_q : ooc_rst_q),
        .rst_o(lane_rst)
    );
    // Control flops (reset): the valid/ready bits. Data flops (no reset):
    // the rest.
    logic ooc_in_valid_q, ooc_out_ready_q, ooc_in_ready_q, ooc_out_valid_q;
    logic [TAG_BITS-1:0] ooc_in_tag_q, ooc_out_tag_q;
    logic [2:0] ooc_ray_class_q;
    logic [C-1:0] ooc_ray_org_q, ooc_ray_end_q, ooc_box_min_q, ooc_box_max_q;
    logic [D-1:0] ooc_ray_dir_q;
    logic ooc_ray_end_valid_q, ooc_out_hit_q;
    always_ff @(posedge lane_clk) begin
      if (lane_rst) begin
        ooc_in_valid_q  <= 1'b0;
        ooc_out_ready_q <= 1'b0;
        ooc_in_ready_q  <= 1'b0;
        ooc_out_valid_q <= 1'b0;
      end else begin
        ooc_in_valid_q  <= in_valid_i[l];
        ooc_out_ready_q <= out_ready_i[l];
        ooc_in_ready_q  <= dut_in_ready[l];
        ooc_out_valid_q <= dut_out_valid[l];
      end
    end
    always_ff @(posedge lane_clk) begin
      ooc_in_tag_q        <= in_tag_i[l*TAG_BITS+:TAG_BITS];
      ooc_ray_class_q     <= ray_class_i[l*3+:3];
      ooc_ray_org_q       <= ray_org_i[l*C+:C];
      ooc_ray_dir_q       <= ray_dir_i[l*D+:D];
      ooc_ray_end_q       <= ray_end_i[l*C+:C];
      ooc_ray_end_valid_q <= ray_end_valid_i[l];
      ooc_box_min_q       <= box_min_i[l*C+:C];
      ooc_box_max_q       <= box_max_i[l*C+:C];
      ooc_out_tag_q       <= dut_out_tag[l*TAG_BITS+:TAG_BITS];
      ooc_out_hit_q       <= dut_out_hit[l];
    end
    assign ooc_in_valid[l]                    = ooc_in_valid_q;
    assign ooc_out_ready[l]                   = ooc_out_ready_q;
    assign ooc_in_tag[l*TAG_BITS+:TAG_BITS]   = ooc_in_tag_q;
    assign ooc_ray_class[l*3+:3]              = ooc_ray_class_q;
    assign ooc_ray_org[l*C+:C]                = ooc_ray_org_q;
    assign ooc_ray_dir[l*D+:D]                = ooc_ray_dir_q;
    assign ooc_ray_end[l*C+:C]                = ooc_ray_end_q;
    assign ooc_ray_end_valid[l]               = ooc_ray_end_valid_q;
    assign ooc_box_min[l*C+:C]                = ooc_box_min_q;
    assign ooc_box_max[l*C+:C]                = ooc_box_max_q;
    assign in_ready_o[l]                      = ooc_in_ready_q;
    assign out_valid_o[l]                     = ooc_out_valid_q;
    assign out_tag_o[l*TAG_BITS+:TAG_BITS]    = ooc_out_tag_q;
    assign out_hit_o[l]                       = ooc_out_hit_q;
  end

  // u_dut: every lane (CLOCKS = 1) or the DSP units' lanes 0..N_DSP-1 on
  // clk_i; g_lut_clk.u_dut (CLOCKS = 2): the fabric units' lanes on
  // clk_lut_i, the same bit ranges of every port from lane N_DSP on.
  localparam int N0 = (CLOCKS == 2) ? N_DSP : N;  // lanes of u_dut

  pluecker_array #(
      .N_DSP(N_DSP),
      .N_LUT((CLOCKS == 2) ? 0 : N_LUT),
      .N_ROM(N_ROM),
      .COORD_BITS(COORD_BITS),
      .DIR_BITS(DIR_BITS),
      .TAG_BITS(TAG_BITS),
      .CONSERVATIVE(CONSERVATIVE),
      .PIPELINE(PIPELINE),
      .RST_STAGES(RST_STAGES)
  ) u_dut (
      .clk_i(clk_i),
      .rst_i(ooc_rst_q),
      .in_valid_i(ooc_in_valid[0+:N0]),
      .in_ready_o(dut_in_ready[0+:N0]),
      .in_tag_i(ooc_in_tag[0+:N0*TAG_BITS]),
      .ray_class_i(ooc_ray_class[0+:N0*3]),
      .ray_org_i(ooc_ray_org[0+:N0*C]),
      .ray_dir_i(ooc_ray_dir[0+:N0*D]),
      .ray_end_i(ooc_ray_end[0+:N0*C]),
      .ray_end_valid_i(ooc_ray_end_valid[0+:N0]),
      .box_min_i(ooc_box_min[0+:N0*C]),
      .box_max_i(ooc_box_max[0+:N0*C]),
      .out_valid_o(dut_out_valid[0+:N0]),
      .out_ready_i(ooc_out_ready[0+:N0]),
      .out_tag_o(dut_out_tag[0+:N0*TAG_BITS]),
      .out_hit_o(dut_out_hit[0+:N0])
  );

  if (CLOCKS == 2) begin : g_lut_clk
    localparam int L0 = N_DSP;  // first lane
    localparam int NL = N_LUT;
    pluecker_array #(
        .N_DSP(0),
        .N_LUT(NL),
        .COORD_BITS(COORD_BITS),
        .DIR_BITS(DIR_BITS),
        .TAG_BITS(TAG_BITS),
        .CONSERVATIVE(CONSERVATIVE),
        .PIPELINE(PIPELINE),
        .RST_STAGES(RST_STAGES)
    ) u_dut (
        .clk_i(clk_lut),
        .rst_i(ooc_rst_lut_q),
        .in_valid_i(ooc_in_valid[L0+:NL]),
        .in_ready_o(dut_in_ready[L0+:NL]),
        .in_tag_i(ooc_in_tag[L0*TAG_BITS+:NL*TAG_BITS]),
        .ray_class_i(ooc_ray_class[L0*3+:NL*3]),
        .ray_org_i(ooc_ray_org[L0*C+:NL*C]),
        .ray_dir_i(ooc_ray_dir[L0*D+:NL*D]),
        .ray_end_i(ooc_ray_end[L0*C+:NL*C]),
        .ray_end_valid_i(ooc_ray_end_valid[L0+:NL]),
        .box_min_i(ooc_box_min[L0*C+:NL*C]),
        .box_max_i(ooc_box_max[L0*C+:NL*C]),
        .out_valid_o(dut_out_valid[L0+:NL]),
        .out_ready_i(ooc_out_ready[L0+:NL]),
        .out_tag_o(dut_out_tag[L0*TAG_BITS+:NL*TAG_BITS]),
        .out_hit_o(dut_out_hit[L0+:NL])
    );
  end

endmodule

`default_nettype wire
