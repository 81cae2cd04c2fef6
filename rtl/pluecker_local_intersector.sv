// SPDX-License-Identifier: MIT
// Pipelined local-frame ray/box intersector: the box test whose width no
// longer depends on the size of the scene. Computes, bit for bit,
// local_node_ray and local_hit of model/core/src/local.cpp (the format, the
// set-up and the proof that conservative mode never misses:
// model/core/include/pluecker/local.hpp): per query, the ray held at the
// global width G in the frame of one BVH node (pluecker_local_frame, the
// per-node set-up), then CHILDREN K-bit child boxes of that node against
// it (pluecker_local_child, one per box, all sharing the node set-up).
//
// Ports
//   in_*   one query per transfer (in_valid_i && in_ready_o at a rising edge
//          with rst_i low). Vectors pack x in the low field, then y, z.
//          ray_class_i     bit a set = axis a negative
//          ray_org_i       O: GRID_BITS two's complement (the global grid)
//          ray_dir_i       DG: GRID_BITS unsigned, the largest component
//                          exactly 2^(G-1), the others at most that
//          ray_end_i       E: GRID_BITS two's complement, ignored when
//                          ray_end_valid_i is low
//          frame_org_i     F: GRID_BITS two's complement
//          frame_exp_i     e: EXP_BITS unsigned each, 0..G-K+1
//          box_min_i, box_max_i  CHILDREN boxes, child c in bits
//                          [c*3K +: 3K]: K-bit unsigned offsets (any
//                          values, also LO > HI)
//   out_*  results in input order (out_valid_o && out_ready_i at a rising
//          edge with rst_i low); out_tag_o is in_tag_i of the query,
//          out_hit_o[c] the answer for child box c.
//   rst_i  synchronous, active high. Every query accepted before a reset is
//          dropped; no result of it appears after the reset. While rst_i is
//          high no transfer takes place (in_ready_o and out_valid_o are low
//          from the first reset edge on; in_ready_o rises one cycle after
//          the reset is released).
// Parameters: BOX_BITS = K (4..16), DIR_BITS = D (4..24), GRID_BITS = G
// (K+2..32: the model takes up to 48, but the node set-up's six moment
// products are (G+3) x (G+1) bits and pluecker_mul takes operands of at most
// 35 bits), TAG_BITS, CONSERVATIVE, MUL_STYLE, CHILDREN (1..2), EXP_BITS
// (derived; checked). All are checked at elaboration.
//
// The port contract (model/core/include/pluecker/local_contract.hpp) packs
// a LocalRay, a LocalFrame and LocalBoxes into these ports and excludes a
// DG without a component at 2^(G-1) and exponents above G-K+1: for those
// the unit computes the RTL's answer, which is not specified.
//
// Pipeline (one query per clock; the datapath never stalls and has no clock
// enable: valid bits shift every cycle, results go into an output FIFO and
// a credit counter makes in_ready_o a flop, so back-pressure never reaches
// the pipeline)
//   S0            input registers (the frame's F0; tag, boxes)
//   F1..L5        pluecker_local_frame: FRAME_LATENCY = 9 + FRAME_MUL_ADD
//                 register stages from the ports to the node ray (S0
//                 included); the boxes and the tag wait beside it
//   C1..C4        pluecker_local_child, CHILDREN of them on the one node
//                 ray: CHILD_LATENCY = 4 + CHILD_MUL_ADD stages
//   FIFO          the answers are written into the output FIFO
// Latency: LATENCY = FRAME_LATENCY + CHILD_LATENCY + 1 cycles from the
// input handshake to the earliest output handshake: 14 up to GRID_BITS 15,
// 15 at 16..17, 16 from 18 bits (FRAME_MUL_ADD: operands over 18 bits split
// on ECP5 DSP blocks), one more with MUL_STYLE "dsp" from DIR_BITS 18
// (CHILD_MUL_ADD); with MUL_STYLE "lut" always 14.
//
// Multipliers (MUL_STYLE): the six moment products of the node set-up
// ((G+3) x (G+1) bits, signed) and the twelve products of each child (K x D
// bits, unsigned):
//   "auto"  node set-up on pluecker_mul (MULT18X18D blocks on ECP5: 6 at
//           G <= 15, 12 at 16..17, 24 from 18), children in fabric
//           (pluecker_mul_lut): the per-child multipliers take no DSP block
//   "dsp"   both on pluecker_mul (12 more MULT18X18D per child, 24 from
//           DIR_BITS 18)
//   "lut"   both in fabric
//
// The port contract's generated package pluecker_local_contract_pkg
// (rtl/pluecker_local_contract_pkg.sv) gives the limits checked below and
// the contract's row for every configuration class; elaboration fails when
// what this module derives differs from the row. in_ready_o and
// out_valid_o are driven by flops only.
//
// Flow control: credits_q counts free FIFO entries not yet promised to a
// query in flight; FIFO_DEPTH >= LATENCY + 2 entries, so the FIFO never
// overflows and a never-stalled output sustains one query per clock.
`default_nettype none

module pluecker_local_intersector #(
    parameter int BOX_BITS = 8,    // K: box offsets
    parameter int DIR_BITS = 11,   // D: local direction
    parameter int GRID_BITS = 32,  // G: the global grid (ray, frame origins)
    parameter int TAG_BITS = 16,
    parameter bit CONSERVATIVE = 1,  // 1: conservative margin (never misses); 0: 'nearest'
    parameter MUL_STYLE = "auto",  // "auto", "dsp" or "lut" (see the header)
    parameter int CHILDREN = 1,  // child boxes per query (1 or 2), one node set-up
    // Bits of one frame exponent: $clog2(G - K + 2) (0..G-K+1); checked.
    parameter int EXP_BITS = $clog2(GRID_BITS - BOX_BITS + 2)
) (
    input wire clk_i,
    input wire rst_i,  // synchronous, active high; resets control flops only

    input  wire                           in_valid_i,
    output wire                           in_ready_o,
    input  wire [           TAG_BITS-1:0] in_tag_i,
    input  wire [                    2:0] ray_class_i,
    input  wire [        3*GRID_BITS-1:0] ray_org_i,
    input  wire [        3*GRID_BITS-1:0] ray_dir_i,
    input  wire [        3*GRID_BITS-1:0] ray_end_i,
    input  wire                           ray_end_valid_i,
    input  wire [        3*GRID_BITS-1:0] frame_org_i,
    input  wire [         3*EXP_BITS-1:0] frame_exp_i,
    input  wire [CHILDREN*3*BOX_BITS-1:0] box_min_i,
    input  wire [CHILDREN*3*BOX_BITS-1:0] box_max_i,

    output wire                out_valid_o,
    input  wire                out_ready_i,
    output wire [TAG_BITS-1:0] out_tag_o,
    output wire [CHILDREN-1:0] out_hit_o
);

  // -------------------------------------------------------------------------
  // Parameter checks (elaboration time; messages without format arguments,
  // which Yosys prints verbatim). The limits are the port contract's.
  // -------------------------------------------------------------------------
  localparam bit BOX_BITS_OK = BOX_BITS >= pluecker_local_contract_pkg::MIN_BOX_BITS &&
      BOX_BITS <= pluecker_local_contract_pkg::MAX_BOX_BITS;
  localparam bit DIR_BITS_OK = DIR_BITS >= pluecker_local_contract_pkg::MIN_DIR_BITS &&
      DIR_BITS <= pluecker_local_contract_pkg::MAX_DIR_BITS;
  localparam bit GRID_BITS_OK = GRID_BITS >= BOX_BITS + pluecker_local_contract_pkg::GRID_MARGIN &&
      GRID_BITS <= pluecker_local_contract_pkg::MAX_GRID_BITS;
  localparam bit TAG_BITS_OK = TAG_BITS >= pluecker_local_contract_pkg::MIN_TAG_BITS;
  localparam bit CHILDREN_OK = CHILDREN >= 1 && CHILDREN <= pluecker_local_contract_pkg::MAX_CHILDREN;
  localparam bit EXP_BITS_OK = EXP_BITS == $clog2(GRID_BITS - BOX_BITS + 2);
  if (!BOX_BITS_OK) begin : g_bad_box_bits
    $error("pluecker_local_intersector: parameter BOX_BITS is outside MIN_BOX_BITS..MAX_BOX_BITS of pluecker_local_contract_pkg");
  end
  if (!DIR_BITS_OK) begin : g_bad_dir_bits
    $error("pluecker_local_intersector: parameter DIR_BITS is outside MIN_DIR_BITS..MAX_DIR_BITS of pluecker_local_contract_pkg");
  end
  if (!GRID_BITS_OK) begin : g_bad_grid_bits
    $error("pluecker_local_intersector: parameter GRID_BITS is outside BOX_BITS + GRID_MARGIN..MAX_GRID_BITS of pluecker_local_contract_pkg");
  end
  if (!TAG_BITS_OK) begin : g_bad_tag_bits
    $error("pluecker_local_intersector: parameter TAG_BITS must be at least 1");
  end
  if (!CHILDREN_OK) begin : g_bad_children
    $error("pluecker_local_intersector: parameter CHILDREN must be 1 or 2");
  end
  if (!EXP_BITS_OK) begin : g_bad_exp_bits
    $error("pluecker_local_intersector: parameter EXP_BITS must be $clog2(GRID_BITS - BOX_BITS + 2)");
  end
  // MUL_STYLE compared as a 32-bit pattern (see pluecker_intersector).
  localparam logic [31:0] MUL_STYLE_S = 32'(MUL_STYLE);
  localparam bit MUL_STYLE_OK = MUL_STYLE_S == 32'("auto") || MUL_STYLE_S == 32'("dsp") ||
      MUL_STYLE_S == 32'("lut");
  if (!MUL_STYLE_OK) begin : g_bad_mul_style
    $error("pluecker_local_intersector: parameter MUL_STYLE must be auto, dsp or lut");
  end

  // -------------------------------------------------------------------------
  // Derived constants
  // -------------------------------------------------------------------------
  localparam int K = BOX_BITS;
  localparam int D = DIR_BITS;
  localparam int G = GRID_BITS;
  // Multiplier styles: fabric moment products only with "lut"; fabric child
  // products unless "dsp".
  localparam bit FRAME_LUT = MUL_STYLE_S == 32'("lut");
  localparam bit CHILD_LUT = MUL_STYLE_S != 32'("dsp");
  // pluecker_mul's adder stages: one per operand wider than one DSP operand.
  // Moment products: Delta (G+3 bits signed) x DG (G+1); child: DIR (D+1) x
  // ent/ext (K+1, never over 17).
  localparam int DSP_OPERAND_BITS = pluecker_local_contract_pkg::DSP_OPERAND_BITS;
  localparam int FRAME_MUL_ADD = FRAME_LUT ? 0 :
      ((G + 3 > DSP_OPERAND_BITS) ? 1 : 0) + ((G + 1 > DSP_OPERAND_BITS) ? 1 : 0);
  localparam int CHILD_MUL_ADD = CHILD_LUT ? 0 :
      ((D + 1 > DSP_OPERAND_BITS) ? 1 : 0) + ((K + 1 > DSP_OPERAND_BITS) ? 1 : 0);
  // Register stages of the node set-up (S0 included) and of a child (the
  // documented latencies of pluecker_local_frame and pluecker_local_child).
  localparam int FRAME_LATENCY = 9 + FRAME_MUL_ADD;
  localparam int CHILD_LATENCY = 4 + CHILD_MUL_ADD;
  // Valid bits: S0 .. the child's last stage.
  localparam int NV = FRAME_LATENCY + CHILD_LATENCY;
  // Input handshake to the earliest output handshake: the stages and the
  // FIFO write.
  localparam int LATENCY = NV + 1;
  // A power of two >= LATENCY + 2: full throughput with out_ready_i high.
  localparam int FIFO_DEPTH = 1 << $clog2(LATENCY + 2);
  localparam int FIFO_AW = $clog2(FIFO_DEPTH);
  localparam int FIFO_PW = FIFO_AW + 1;
  // Credit counter: 0..FIFO_DEPTH.
  localparam int CW = $clog2(FIFO_DEPTH + 1);
  localparam logic [CW-1:0] CREDITS_FULL = FIFO_DEPTH[CW-1:0];
  // Node-ray field widths (pluecker_local_frame's outputs).
  localparam int WO = K + 2;
  localparam int WW = K + D + 2;
  localparam int BOXW = 3 * K;

  // The port contract's row for this configuration (checked only when every
  // parameter is valid, so that a bad one gets its own message alone).
  localparam bit PARAMS_OK = BOX_BITS_OK && DIR_BITS_OK && GRID_BITS_OK && TAG_BITS_OK && CHILDREN_OK &&
      EXP_BITS_OK && MUL_STYLE_OK;
  localparam int CONTRACT_CLASS = pluecker_local_contract_pkg::local_contract_class(DIR_BITS, GRID_BITS,
                                                                                    MUL_STYLE_S);
  if (PARAMS_OK) begin : g_contract
    if (CONTRACT_CLASS < 0) begin : g_no_class
      $error("pluecker_local_intersector: the configuration is in no class of the port contract (pluecker_local_contract_pkg)");
    end else begin : g_row
      if (FRAME_LUT != pluecker_local_contract_pkg::local_contract_frame_lut(CONTRACT_CLASS)) begin : g_bad_frame_lut
        $error("pluecker_local_intersector: the node set-up's multiplier style differs from the port contract (pluecker_local_contract_pkg)");
      end
      if (CHILD_LUT != pluecker_local_contract_pkg::local_contract_child_lut(CONTRACT_CLASS)) begin : g_bad_child_lut
        $error("pluecker_local_intersector: the children's multiplier style differs from the port contract (pluecker_local_contract_pkg)");
      end
      if (FRAME_MUL_ADD != pluecker_local_contract_pkg::local_contract_frame_mul_add(CONTRACT_CLASS)) begin : g_bad_frame_add
        $error("pluecker_local_intersector: FRAME_MUL_ADD differs from the port contract (pluecker_local_contract_pkg)");
      end
      if (CHILD_MUL_ADD != pluecker_local_contract_pkg::local_contract_child_mul_add(CONTRACT_CLASS)) begin : g_bad_child_add
        $error("pluecker_local_intersector: CHILD_MUL_ADD differs from the port contract (pluecker_local_contract_pkg)");
      end
      if (LATENCY != pluecker_local_contract_pkg::local_contract_latency(CONTRACT_CLASS)) begin : g_bad_latency
        $error("pluecker_local_intersector: LATENCY differs from the port contract (pluecker_local_contract_pkg)");
      end
      if (FIFO_DEPTH != pluecker_local_contract_pkg::local_contract_fifo_depth(CONTRACT_CLASS)) begin : g_bad_fifo_depth
        $error("pluecker_local_intersector: FIFO_DEPTH differs from the port contract (pluecker_local_contract_pkg)");
      end
    end
  end

  // -------------------------------------------------------------------------
  // Control: valid bits, credits, FIFO pointers (the only reset flops)
  // -------------------------------------------------------------------------
  logic [NV-1:0] v_q;  // v_q[s]: a query in stage s (0 = S0)
  logic ready_q;
  logic [CW-1:0] credits_q, credits_d;
  logic [FIFO_PW-1:0] wr_ptr_q, rd_ptr_q;

  wire take = in_valid_i && ready_q;
  wire give = out_valid_o && out_ready_i;
  wire write = v_q[NV-1];

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
      v_q <= NV'({v_q, take});
      ready_q <= credits_d != '0;
      credits_q <= credits_d;
      if (write) wr_ptr_q <= wr_ptr_q + 1'b1;
      if (give) rd_ptr_q <= rd_ptr_q + 1'b1;
    end
  end

  assign in_ready_o  = ready_q;
  assign out_valid_o = wr_ptr_q != rd_ptr_q;

  // -------------------------------------------------------------------------
  // The node set-up (its F0 registers are S0)
  // -------------------------------------------------------------------------
  wire [2:0] nr_cls;
  wire [3*D-1:0] nr_dir;
  wire [6*WW-1:0] nr_w;
  wire [3*WO-1:0] nr_org, nr_end;
  wire nr_endv;

  pluecker_local_frame #(
      .BOX_BITS(K),
      .DIR_BITS(D),
      .GRID_BITS(G),
      .EXP_BITS(EXP_BITS),
      .CONSERVATIVE(CONSERVATIVE),
      .MUL_LUT(FRAME_LUT)
  ) u_frame (
      .clk_i(clk_i),
      .ray_class_i(ray_class_i),
      .ray_org_i(ray_org_i),
      .ray_dir_i(ray_dir_i),
      .ray_end_i(ray_end_i),
      .ray_end_valid_i(ray_end_valid_i),
      .frame_org_i(frame_org_i),
      .frame_exp_i(frame_exp_i),
      .cls_o(nr_cls),
      .dir_o(nr_dir),
      .w_o(nr_w),
      .org_o(nr_org),
      .end_o(nr_end),
      .end_valid_o(nr_endv)
  );

  // The boxes wait beside the node set-up (S0 and FRAME_LATENCY - 1 more
  // stages), the tag beside the whole pipeline.
  wire [CHILDREN*BOXW-1:0] box_min_f, box_max_f;
  pluecker_pipe #(.WIDTH(2 * CHILDREN * BOXW), .STAGES(FRAME_LATENCY)) u_box_pipe (
      .clk_i(clk_i), .d_i({box_max_i, box_min_i}), .q_o({box_max_f, box_min_f}));
  wire [TAG_BITS-1:0] tag_c;
  pluecker_pipe #(.WIDTH(TAG_BITS), .STAGES(NV)) u_tag_pipe (
      .clk_i(clk_i), .d_i(in_tag_i), .q_o(tag_c));

  // -------------------------------------------------------------------------
  // The children, all on the one node ray
  // -------------------------------------------------------------------------
  wire [CHILDREN-1:0] hit_c;
  for (genvar c = 0; c < CHILDREN; c++) begin : g_child
    pluecker_local_child #(
        .BOX_BITS(K),
        .DIR_BITS(D),
        .CONSERVATIVE(CONSERVATIVE),
        .MUL_LUT(CHILD_LUT)
    ) u_child (
        .clk_i(clk_i),
        .cls_i(nr_cls),
        .dir_i(nr_dir),
        .w_i(nr_w),
        .org_i(nr_org),
        .end_i(nr_end),
        .end_valid_i(nr_endv),
        .box_min_i(box_min_f[c*BOXW+:BOXW]),
        .box_max_i(box_max_f[c*BOXW+:BOXW]),
        .hit_o(hit_c[c])
    );
  end

  // -------------------------------------------------------------------------
  // Output FIFO (contents not reset; the pointers are)
  // -------------------------------------------------------------------------
  logic [TAG_BITS+CHILDREN-1:0] fifo_q[FIFO_DEPTH];

  always_ff @(posedge clk_i) begin
    if (write) fifo_q[wr_ptr_q[FIFO_AW-1:0]] <= {tag_c, hit_c};
  end

  assign {out_tag_o, out_hit_o} = fifo_q[rd_ptr_q[FIFO_AW-1:0]];

  // -------------------------------------------------------------------------
  // Handshake and flow-control assertions (simulation, --assert); written as
  // in pluecker_intersector (immediate assertions on flopped history).
  // -------------------------------------------------------------------------
`ifdef ASSERT_ON
  localparam int IN_W = TAG_BITS + 3 + 4 * 3 * G + 1 + 3 * EXP_BITS + 2 * CHILDREN * BOXW;
  logic chk_live_q;  // the previous edge had rst_i low
  logic out_stall_q, in_stall_q;
  logic [TAG_BITS+CHILDREN-1:0] out_prev_q;
  logic [IN_W-1:0] in_prev_q;
  wire [IN_W-1:0] in_now = {
    in_tag_i, ray_class_i, ray_org_i, ray_dir_i, ray_end_i, ray_end_valid_i, frame_org_i, frame_exp_i,
    box_min_i, box_max_i
  };
  wire [FIFO_PW-1:0] fifo_count = wr_ptr_q - rd_ptr_q;
  logic [31:0] in_flight;
  always_comb begin
    in_flight = '0;
    for (int s = 0; s < NV; s++) in_flight = in_flight + 32'(v_q[s]);
  end

  always_ff @(posedge clk_i) begin
    chk_live_q  <= !rst_i;
    out_stall_q <= out_valid_o && !out_ready_i;
    out_prev_q  <= {out_tag_o, out_hit_o};
    in_stall_q  <= in_valid_i && !in_ready_o;
    in_prev_q   <= in_now;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_i && chk_live_q) begin
      // A result, once offered, stays offered and unchanged until taken.
      if (out_stall_q) begin
        a_out_hold :
        assert (out_valid_o && {out_tag_o, out_hit_o} == out_prev_q);
      end
      // The same rule for the upstream side (a check on the environment).
      if (in_stall_q) begin
        a_in_hold :
        assert (in_valid_i && in_now == in_prev_q);
      end
    end
    if (!rst_i) begin
      // Credits, queries in flight and FIFO entries always add up to the
      // depth: the FIFO never overflows, no slot is promised twice.
      a_credit_balance :
      assert (32'(credits_q) + in_flight + 32'(fifo_count) == FIFO_DEPTH);
      a_ready_credit :
      assert (!ready_q || credits_q != '0);
    end
  end
`endif

endmodule

`default_nettype wire
