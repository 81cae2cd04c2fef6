// SPDX-License-Identifier: MIT
// An array of pluecker_intersector units: N = N_DSP + N_LUT lanes, each a
// complete intersector stream.
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
// unit up to 17/17 bits), lanes N_DSP..N-1 MUL_STYLE "lut" (multipliers in
// fabric, up to 17/17 bits), so one chip can fill its DSP blocks and its
// LUTs at once: a mixed array. Every unit has the same COORD_BITS,
// DIR_BITS, TAG_BITS, CONSERVATIVE and PIPELINE, hence one query encoding;
// up to 17/17 bits both styles have the same LATENCY (the port contract's).
//
// Each lane keeps every rule of the intersector's ports: in_ready_o and
// out_valid_o come from flops, results in input order, nothing accepted
// before a reset (rst_i, synchronous, shared) leaves after it. Parameters
// are checked at elaboration here (the counts) and in each unit (the rest).
`default_nettype none

module pluecker_array #(
    parameter int N_DSP = 1,  // units with DSP multipliers (lanes 0..N_DSP-1)
    parameter int N_LUT = 1,  // units with fabric multipliers (the next lanes)
    parameter int COORD_BITS = 16,
    parameter int DIR_BITS = 16,
    parameter int TAG_BITS = 16,
    parameter bit CONSERVATIVE = 1,
    parameter int PIPELINE = 0,
    // Lanes in all (not to be overridden).
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
  // An upper bound on the lanes (an LFE5U-85F holds well under 100 units).
  localparam int MAX_UNITS = 256;
  if (N_DSP < 0 || N_LUT < 0) begin : g_bad_counts
    $error("pluecker_array: parameters N_DSP and N_LUT must not be negative");
  end
  if (N < 1 || N > MAX_UNITS) begin : g_bad_n
    $error("pluecker_array: N_DSP + N_LUT must be 1..256");
  end

  localparam int C3 = 3 * COORD_BITS;
  localparam int D3 = 3 * DIR_BITS;

  for (genvar l = 0; l < N; l++) begin : g_unit
    localparam logic [31:0] STYLE = (l < N_DSP) ? 32'("dsp") : 32'("lut");
    wire unused_strict;
    pluecker_intersector #(
        .COORD_BITS(COORD_BITS),
        .DIR_BITS(DIR_BITS),
        .TAG_BITS(TAG_BITS),
        .CONSERVATIVE(CONSERVATIVE),
        .MUL_STYLE(STYLE),
        .PIPELINE(PIPELINE)
    ) u_unit (
        .clk_i(clk_i),
        .rst_i(rst_i),
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
