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
`default_nettype none

module ooc_array_wrapper #(
    parameter int N_DSP = 1,
    parameter int N_LUT = 1,
    parameter int COORD_BITS = 16,
    parameter int DIR_BITS = 16,
    parameter int TAG_BITS = 16,
    parameter bit CONSERVATIVE = 1,
    parameter int PIPELINE = 0,
    parameter int RST_STAGES = 0,
    localparam int N = N_DSP + N_LUT
) (
    input wire clk_i,
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

  // Control flops (reset): ooc_rst_q and the valid/ready bits. Data flops
  // (no reset): the rest.
  logic ooc_rst_q;
  logic [N-1:0] ooc_in_valid_q, ooc_out_ready_q, ooc_in_ready_q, ooc_out_valid_q;
  logic [TW-1:0] ooc_in_tag_q, ooc_out_tag_q;
  logic [N*3-1:0] ooc_ray_class_q;
  logic [CW-1:0] ooc_ray_org_q, ooc_ray_end_q, ooc_box_min_q, ooc_box_max_q;
  logic [DW-1:0] ooc_ray_dir_q;
  logic [N-1:0] ooc_ray_end_valid_q, ooc_out_hit_q;

  wire [N-1:0] dut_in_ready, dut_out_valid, dut_out_hit;
  wire [TW-1:0] dut_out_tag;

  always_ff @(posedge clk_i) ooc_rst_q <= rst_i;

  for (genvar l = 0; l < N; l++) begin : g_lane
    // A kept chain as deep as a unit's (one per lane), so that the
    // harness's reset reaches the far lanes in as many hops.
    wire lane_rst;
    pluecker_rst_chain #(
        .STAGES(RST_STAGES)
    ) u_lane_rst (
        .clk_i(clk_i),
        .rst_i(ooc_rst_q),
        .rst_o(lane_rst)
    );
    always_ff @(posedge clk_i) begin
      if (lane_rst) begin
        ooc_in_valid_q[l]  <= 1'b0;
        ooc_out_ready_q[l] <= 1'b0;
        ooc_in_ready_q[l]  <= 1'b0;
        ooc_out_valid_q[l] <= 1'b0;
      end else begin
        ooc_in_valid_q[l]  <= in_valid_i[l];
        ooc_out_ready_q[l] <= out_ready_i[l];
        ooc_in_ready_q[l]  <= dut_in_ready[l];
        ooc_out_valid_q[l] <= dut_out_valid[l];
      end
    end
  end

  always_ff @(posedge clk_i) begin
    ooc_in_tag_q        <= in_tag_i;
    ooc_ray_class_q     <= ray_class_i;
    ooc_ray_org_q       <= ray_org_i;
    ooc_ray_dir_q       <= ray_dir_i;
    ooc_ray_end_q       <= ray_end_i;
    ooc_ray_end_valid_q <= ray_end_valid_i;
    ooc_box_min_q       <= box_min_i;
    ooc_box_max_q       <= box_max_i;
    ooc_out_tag_q       <= dut_out_tag;
    ooc_out_hit_q       <= dut_out_hit;
  end

  pluecker_array #(
      .N_DSP(N_DSP),
      .N_LUT(N_LUT),
      .COORD_BITS(COORD_BITS),
      .DIR_BITS(DIR_BITS),
      .TAG_BITS(TAG_BITS),
      .CONSERVATIVE(CONSERVATIVE),
      .PIPELINE(PIPELINE),
      .RST_STAGES(RST_STAGES)
  ) u_dut (
      .clk_i(clk_i),
      .rst_i(ooc_rst_q),
      .in_valid_i(ooc_in_valid_q),
      .in_ready_o(dut_in_ready),
      .in_tag_i(ooc_in_tag_q),
      .ray_class_i(ooc_ray_class_q),
      .ray_org_i(ooc_ray_org_q),
      .ray_dir_i(ooc_ray_dir_q),
      .ray_end_i(ooc_ray_end_q),
      .ray_end_valid_i(ooc_ray_end_valid_q),
      .box_min_i(ooc_box_min_q),
      .box_max_i(ooc_box_max_q),
      .out_valid_o(dut_out_valid),
      .out_ready_i(ooc_out_ready_q),
      .out_tag_o(dut_out_tag),
      .out_hit_o(dut_out_hit)
  );

  assign in_ready_o  = ooc_in_ready_q;
  assign out_valid_o = ooc_out_valid_q;
  assign out_tag_o   = ooc_out_tag_q;
  assign out_hit_o   = ooc_out_hit_q;
endmodule

`default_nettype wire
