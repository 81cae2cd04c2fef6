// SPDX-License-Identifier: MIT
// An array of pluecker_intersector units: N = N_DSP + N_LUT + N_ROM lanes,
// each a complete intersector stream.
//
// Interface. A valid/ready stream carries at most one query per clock and a
// unit takes one query per clock, so N units need N queries per clock: the
// array has N lanes, each with the ports of rtl/pluecker_intersector.sv,
// lane l in bits [l*W +: W] of every port (W the intersector port's width).
// Lane l is unit l: dispatch is by lane, without a crossbar, so every unit
// runs at one query per clock whenever its lane is fed. A lane's results
// leave in the order of its queries, with their tags; lanes are
// independent (no lane ever waits for another). A producer with fewer
// streams than lanes spreads its queries over the lanes (e.g. one lane per
// traversal of a ray packet) and matches answers by lane and tag.
//
// Units. Lanes 0..N_DSP-1 use MUL_STYLE "dsp" (on ECP5 twelve MULT18X18D a
// unit up to 17/17 bits; six at 6/6 with PIPELINE = 2, two products a
// block, rtl/pluecker_mul_pair.sv), the next N_LUT lanes MUL_STYLE "lut"
// (multipliers in fabric, up to 17/17 bits) and the last N_ROM lanes
// MUL_STYLE "rom" (each product looked up in a block RAM, twelve DP16KD a
// unit; 6/6 bits with PIPELINE = 2, rtl/pluecker_mul_rom.sv), so one chip
// can fill its DSP blocks, its block RAM and its LUTs at once: a mixed
// array. Every unit has the same COORD_BITS, DIR_BITS, TAG_BITS,
// CONSERVATIVE and PIPELINE, hence one query encoding; where several styles
// take a configuration they have the same LATENCY (the port contract's).
//
// Each lane keeps every rule of the intersector's ports: in_ready_o and
// out_valid_o come from flops, results in input order, nothing accepted
// before a reset (rst_i, synchronous, shared) leaves after it. Parameters
// are checked at elaboration here (the counts) and in each unit (the rest).
//
// Reset tree. With RST_STAGES = 0 rst_i drives every unit's control flops
// directly: on a whole chip one net from one flop to all of them (on an
// LFE5U-85F 13 units across the die, 5.9 ns of routing; fpga/TIMING.md).
// RST_STAGES = K > 0 gives every unit a chain of K flops of its own in
// front of its rst_i (kept: synthesis must not merge the copies), so each
// net is short enough for one clock. The array then acts on rst_i K clocks
// late: a reset takes effect K clocks after rst_i rises and ends K clocks
// after it falls. Hold rst_i high for at least K + 1 clocks; in the first
// K of them the lanes still run: an offered query must stay on offer (the
// stream rule; what a lane takes then is dropped by the reset), and
// out_ready_i must be low (a result delivered then would belong to before
// the reset). in_ready_o stays low for the K clocks after rst_i falls.
`default_nettype none

module pluecker_array #(
    parameter int N_DSP = 1,  // units with DSP multipliers (lanes 0..N_DSP-1)
    parameter int N_LUT = 1,  // units with fabric multipliers (the next lanes)
    parameter int N_ROM = 0,  // units with block-RAM table multipliers (the last lanes)
    parameter int COORD_BITS = 16,
    parameter int DIR_BITS = 16,
    parameter int TAG_BITS = 16,
    parameter bit CONSERVATIVE = 1,
    parameter int PIPELINE = 0,
    parameter int RST_STAGES = 0,  // reset flops per unit in front of its rst_i (0..8)
    // Lanes in all (not to be overridden).
    localparam int N = N_DSP + N_LUT + N_ROM
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
  // An upper bound on the lanes (an LFE5U-85F holds well under 100 units).
  localparam int MAX_UNITS = 256;
  if (N_DSP < 0 || N_LUT < 0 || N_ROM < 0) begin : g_bad_counts
    $error("pluecker_array: parameters N_DSP, N_LUT and N_ROM must not be negative");
  end
  if (N < 1 || N > MAX_UNITS) begin : g_bad_n
    $error("pluecker_array: N_DSP + N_LUT + N_ROM must be 1..256");
  end

  if (RST_STAGES < 0 || RST_STAGES > 8) begin : g_bad_rst_stages
    $error("pluecker_array: parameter RST_STAGES must be 0..8");
  end

  localparam int C3 = 3 * COORD_BITS;
  localparam int D3 = 3 * DIR_BITS;

  for (genvar l = 0; l < N; l++) begin : g_unit
    localparam logic [31:0] STYLE = (l < N_DSP) ? 32'("dsp") : (l < N_DSP + N_LUT) ? 32'("lut") : 32'("rom");
    wire unused_strict;
    wire unit_rst;
    // One kept chain per unit (rtl/pluecker_rst_chain.sv).
    pluecker_rst_chain #(
        .STAGES(RST_STAGES)
    ) u_rst (
        .clk_i(clk_i),
        .rst_i(rst_i),
        .rst_o(unit_rst)
    );
    pluecker_intersector #(
        .COORD_BITS(COORD_BITS),
        .DIR_BITS(DIR_BITS),
        .TAG_BITS(TAG_BITS),
        .CONSERVATIVE(CONSERVATIVE),
        .MUL_STYLE(STYLE),
        .PIPELINE(PIPELINE)
    ) u_unit (
        .clk_i(clk_i),
        .rst_i(unit_rst),
        .in_valid_i(in_valid_i[l]),
        .in_ready_o(in_ready_o[l]),
        .in_tag_i(in_tag_i[l*TAG_BITS+:TAG_BITS]),
        .ray_class_i(ray_class_i[l*3+:3]),
        .ray_org_i(ray_org_i[l*C3+:C3]),
        .ray_dir_i(ray_dir_i[l*D3+:D3]),
        .ray_end_i(ray_end_i[l*C3+:C3]),
        .ray_end_valid_i(ray_end_valid_i[l]),
        .box_min_i(box_min_i[l*C3+:C3]),
        .box_max_i(box_max_i[l*C3+:C3]),
        .out_valid_o(out_valid_o[l]),
        .out_ready_i(out_ready_i[l]),
        .out_tag_o(out_tag_o[l*TAG_BITS+:TAG_BITS]),
        .out_hit_o(out_hit_o[l]),
        .out_strict_o(unused_strict)  // TERNARY = 0: constant 0
    );
  end

endmodule

`default_nettype wire
