// SPDX-License-Identifier: MIT
// AXI4-Stream wrapper of pluecker_intersector: one ray/box query per beat in,
// one result per beat out, in order, one query per clock under any
// back-pressure.
//
// Slave (queries), s_axis_*:
//   tdata_i[TDATA_BITS]  the intersector's payload input ports back to back
//                        from bit 0 (the field table below; zeros above
//                        QUERY_BITS up to whole bytes)
//   tid_i[TAG_BITS]      the query's tag, returned with its result
//   tlast_i              end of a packet (e.g. the boxes of one ray), returned
//                        with the packet's last result
//   tvalid_i, tready_o   the handshake; tready_o is a flip-flop (the
//                        intersector's credit-based in_ready_o)
// Master (results), m_axis_*:
//   tdata_o[8]           bit 0: hit, bits 7..1: zero
//   tuser_o              hit (the same bit, for sinks that route by TUSER)
//   tid_o, tlast_o       the query's tid_i and tlast_i
//   tvalid_o, tready_i   the handshake; every m_axis output is a flip-flop and
//                        tready_i reaches no logic but a skid register
//                        (pluecker_axis_skid), so the result stream runs at one
//                        beat per clock and tready_i need not be registered
//                        in front of this block
//
// tdata fields (C = COORD_BITS, D = DIR_BITS; each port's own encoding, x in
// the low field: see rtl/pluecker_intersector.sv). The offsets are not
// written here: they come from the functions axis_field_lsb/axis_field_bits
// of the generated rtl/pluecker_contract_pkg.sv, derived from the port list
// of the port contract (model/core/include/pluecker/axis_contract.hpp), and
// this module checks at elaboration that each field is as wide as the port
// it feeds. At the time of writing they are:
//   k  port             bits  lsb
//   0  ray_class_i      3     0
//   1  ray_org_i        3C    3
//   2  ray_dir_i        3D    3 + 3C
//   3  ray_end_i        3C    3 + 3C + 3D
//   4  ray_end_valid_i  1     3 + 6C + 3D
//   5  box_min_i        3C    4 + 6C + 3D
//   6  box_max_i        3C    4 + 9C + 3D
//   QUERY_BITS = 4 + 12C + 3D; TDATA_BITS = QUERY_BITS rounded up to bytes
//   (`pluecker contract --coord-bits C --dir-bits D` prints the table)
//
// aclk_i, aresetn_i: AXI4-Stream's clock and active-low reset (synchronous);
// a reset drops every query in flight, as the intersector's rst_i does.
// Latency: the intersector's LATENCY plus one cycle of the skid register.
`default_nettype none

module pluecker_axis #(
    parameter int COORD_BITS = 16,
    parameter int DIR_BITS = 16,
    parameter int TAG_BITS = 8,
    parameter bit CONSERVATIVE = 1,
    parameter MUL_STYLE = "auto",
    parameter int PIPELINE = 0,
    // Derived (the port contract's tdata layout): do not override.
    parameter int QUERY_BITS = pluecker_contract_pkg::axis_query_bits(COORD_BITS, DIR_BITS),
    parameter int TDATA_BITS = pluecker_contract_pkg::axis_tdata_bits(COORD_BITS, DIR_BITS)
) (
    input wire aclk_i,
    input wire aresetn_i,

    input  wire [TDATA_BITS-1:0] s_axis_tdata_i,
    input  wire [  TAG_BITS-1:0] s_axis_tid_i,
    input  wire                  s_axis_tlast_i,
    input  wire                  s_axis_tvalid_i,
    output wire                  s_axis_tready_o,

    output wire [         7:0] m_axis_tdata_o,
    output wire                m_axis_tuser_o,
    output wire [TAG_BITS-1:0] m_axis_tid_o,
    output wire                m_axis_tlast_o,
    output wire                m_axis_tvalid_o,
    input  wire                m_axis_tready_i
);

  localparam int C = COORD_BITS;
  localparam int D = DIR_BITS;
  // Field k of tdata: lowest bit and width (the contract package's table).
  function automatic int lsb(input int k);
    lsb = pluecker_contract_pkg::axis_field_lsb(k, C, D);
  endfunction
  function automatic int bits(input int k);
    bits = pluecker_contract_pkg::axis_field_bits(k, C, D);
  endfunction
  localparam int CLASS_LSB = lsb(0);
  localparam int ORG_LSB = lsb(1);
  localparam int DIR_LSB = lsb(2);
  localparam int END_LSB = lsb(3);
  localparam int END_VALID_LSB = lsb(4);
  localparam int BOX_MIN_LSB = lsb(5);
  localparam int BOX_MAX_LSB = lsb(6);

  if (TAG_BITS < 1) begin : g_bad_tag_bits
    $error("pluecker_axis: parameter TAG_BITS (the tid width) must be at least 1");
  end
  if (QUERY_BITS != pluecker_contract_pkg::axis_query_bits(C, D) ||
      TDATA_BITS != pluecker_contract_pkg::axis_tdata_bits(C, D)) begin : g_bad_derived
    $error("pluecker_axis: parameters QUERY_BITS and TDATA_BITS are derived; do not override them");
  end
  // The table must feed every port of the intersector with its own width.
  if (pluecker_contract_pkg::axis_fields() != 7 || bits(0) != 3 || bits(1) != 3 * C || bits(2) != 3 * D ||
      bits(3) != 3 * C || bits(4) != 1 || bits(5) != 3 * C || bits(6) != 3 * C ||
      QUERY_BITS != BOX_MAX_LSB + 3 * C) begin : g_bad_table
    $error("pluecker_axis: the tdata table of pluecker_contract_pkg does not match the intersector's ports");
  end

  wire rst = !aresetn_i;

  // The intersector's tag carries tid and tlast.
  wire                in_ready;
  wire                out_valid;
  wire                out_ready;
  wire [TAG_BITS:0]   out_tag;
  wire                out_hit;
  wire                unused_strict;

  pluecker_intersector #(
      .COORD_BITS  (COORD_BITS),
      .DIR_BITS    (DIR_BITS),
      .TAG_BITS    (TAG_BITS + 1),
      .CONSERVATIVE(CONSERVATIVE),
      .MUL_STYLE   (MUL_STYLE),
      .PIPELINE    (PIPELINE)
  ) u_intersector (
      .clk_i          (aclk_i),
      .rst_i          (rst),
      .in_valid_i     (s_axis_tvalid_i),
      .in_ready_o     (in_ready),
      .in_tag_i       ({s_axis_tlast_i, s_axis_tid_i}),
      .ray_class_i    (s_axis_tdata_i[CLASS_LSB+:3]),
      .ray_org_i      (s_axis_tdata_i[ORG_LSB+:3*C]),
      .ray_dir_i      (s_axis_tdata_i[DIR_LSB+:3*D]),
      .ray_end_i      (s_axis_tdata_i[END_LSB+:3*C]),
      .ray_end_valid_i(s_axis_tdata_i[END_VALID_LSB]),
      .box_min_i      (s_axis_tdata_i[BOX_MIN_LSB+:3*C]),
      .box_max_i      (s_axis_tdata_i[BOX_MAX_LSB+:3*C]),
      .out_valid_o    (out_valid),
      .out_ready_i    (out_ready),
      .out_tag_o      (out_tag),
      .out_hit_o      (out_hit),
      .out_strict_o   (unused_strict)  // TERNARY = 0: constant 0
  );

  // Padding bits of tdata above QUERY_BITS carry nothing.
  if (TDATA_BITS > QUERY_BITS) begin : g_pad
    wire unused_pad = ^s_axis_tdata_i[TDATA_BITS-1:QUERY_BITS];
  end

  assign s_axis_tready_o = in_ready;

  // {tlast, tid, hit}
  wire [TAG_BITS+1:0] result;

  pluecker_axis_skid #(
      .DATA_BITS(TAG_BITS + 2)
  ) u_skid (
      .clk_i      (aclk_i),
      .rst_i      (rst),
      .in_valid_i (out_valid),
      .in_ready_o (out_ready),
      .in_data_i  ({out_tag, out_hit}),
      .out_valid_o(m_axis_tvalid_o),
      .out_ready_i(m_axis_tready_i),
      .out_data_o (result)
  );

  assign m_axis_tlast_o = result[TAG_BITS+1];
  assign m_axis_tid_o   = result[TAG_BITS:1];
  assign m_axis_tuser_o = result[0];
  assign m_axis_tdata_o = {7'b0, result[0]};

endmodule

`default_nettype wire
