// SPDX-License-Identifier: MIT
// Pipelined fixed-point Plücker ray/box intersector.
//
// Computes, bit for bit, the datapath of model/core/include/pluecker/fixed.hpp
// (Mahovsky & Wyvill, JGT 9(1) 2004: the ray class selects the box planes,
// then an origin test, a segment-end test and six 2x2 determinant sign tests
// on the silhouette edges). One datapath serves all eight ray classes: the
// class bits only act in S0 (a borrow into each subtract, and which
// differences are kept).
//
// Ports
//   in_*   one query per transfer (in_valid_i && in_ready_o at a rising edge
//          with rst_i low). ray_class_i bit a set = axis a negative. Vectors
//          pack x in the low field, then y, then z. Coordinates (origin,
//          segment end, box planes) are COORD_BITS two's complement,
//          directions DIR_BITS unsigned magnitudes (1.0 = 2^(DIR_BITS-1)).
//          ray_end_i is ignored when ray_end_valid_i is low.
//   out_*  results in input order (out_valid_o && out_ready_i at a rising
//          edge with rst_i low); out_tag_o is in_tag_i of the query.
//          out_hit_o is the test (conservative or nearest). out_strict_o
//          (TERNARY = 1 only, else 0) is the strict test of
//          model/core/include/pluecker/ternary.hpp: it holds only when the
//          query is a real hit of the float box even after every rounding
//          (a certain hit), and implies out_hit_o. Together: certain miss
//          (out_hit_o low), certain hit (both high), uncertain (out_hit_o
//          alone: the test passed only thanks to its margin).
//   rst_i  synchronous, active high. Every query accepted before a reset is
//          dropped; no result of it appears after the reset. While rst_i is
//          high no transfer takes place (in_ready_o and out_valid_o are low
//          from the first reset edge on; in_ready_o rises one cycle after
//          the reset is released).
//
// Pipeline (one query per clock; the datapath never stalls, there is no
// clock enable on it: valid bits shift every cycle and back-pressure is
// handled by an output FIFO and a credit counter)
//   S0  subtract in front of the input registers (from the ports: one
//       carry chain per box plane serves both classes, then the class
//       picks and inverts the results, one LUT level): A_i, B_i
//       and the end tests G_i >= 0, G_i >= 2 are registered, so that the
//       multipliers' operands leave flops straight for their input
//       registers (on a full chip the DSP columns are crowded and the
//       route into them is long: it gets a whole clock period)
//   S1  the multipliers' input registers; |A_i|, |B_j| in ones' complement
//       form, D_i + D_j + 1
//   S2  12 multipliers B_j*D_i, A_i*D_j (pluecker_mul: on ECP5 a MULT18X18D
//       whose input registers are the S1 registers of the operands and whose
//       output register is the S2 register; or, by MUL_STYLE, the fabric
//       multiplier pluecker_mul_lut with the same two register stages; at
//       6/6 with "dsp" and PIPELINE = 2 one MULT18X18D per difference does
//       both its products, pluecker_mul_pair; with "rom" each product is
//       looked up in a block RAM, pluecker_mul_rom, whose address and
//       output registers are the S1 and S2 registers); in parallel
//       |A_i| + |B_j| (in ones' complement form), origin test B_i >= 0,
//       end test
//   S2x PIPELINE + MUL_ADD stages: PIPELINE (0..2) for the multipliers'
//       extra registers (1: the MULT18X18D pipeline register, in fabric the
//       register across pluecker_mul_lut's adder tree; 2: also a fabric
//       register after every product, or in pluecker_mul_lut with 5 or
//       more rows the same registers spread over its adder tree),
//       MUL_ADD (0 when
//       both multiplier operands fit 18 bits, i.e. COORD_BITS <= 17 and
//       DIR_BITS <= 17; else 1 or 2) for the sums of 18x18 partial products
//       of wider products on ECP5 (pluecker_mul); the first of them
//       completes the margin M_ij and registers the half S4 needs (so only
//       that half, not the margin's parts, waits in the others); everything
//       else is only delayed
//   S3  combine: T_ij = B_j*D_i - A_i*D_j (and the margin when there is no
//       S2x stage)
//   S4  compare: 2*T_ij + M_ij >= 0 (conservative) or T_ij >= 0 (nearest),
//       as T_ij + floor(M_ij/2) >= 0: one carry chain whose sign bit is
//       the S4 register's input;
//       with TERNARY also the strict test 2*T_ij - M_ij - 2*(D_i+D_j+1) >= 0
//       (its origin and end tests B_i >= 2, G_i >= 2 ride along from S2)
//   F   the AND of all tests is written into the output FIFO
//
// Latency: LATENCY = 6 + PIPELINE + MUL_ADD cycles from input handshake to
// output handshake (at PIPELINE = 0: 6 up to 17/17 bits; 7 when one of
// COORD_BITS, DIR_BITS is 18 or more, 8 when both are). Without S2x stages
// a query taken at rising edge k is in S0 after edge k, in S4 after edge
// k + 4, in the FIFO (out_valid_o high) after edge k + 5, and is taken at
// edge k + 6 at the earliest; each S2x stage adds one edge.
//
// The port contract (model/core/include/pluecker/contract.hpp) states the limits
// of every parameter and what this module derives from them (multiplier
// style, MUL_ADD, LATENCY, FIFO_DEPTH); its generated package
// pluecker_contract_pkg (rtl/pluecker_contract_pkg.sv) gives the limits
// checked below and the contract's row for every configuration class, and
// elaboration fails when what this module derives differs from the row.
// in_ready_o and out_valid_o are driven by flops only (no combinational path
// from any input to any output).
//
// Flow control: credits_q counts free FIFO entries not yet promised to a
// query in flight (a thermometer code, as occ_q counts the results in the
// FIFO). A transfer in takes a credit, a transfer out returns one,
// so the FIFO (FIFO_DEPTH >= LATENCY + 2 entries) can never overflow and a
// never-stalled output sustains one query per clock.

`default_nettype none

module pluecker_intersector #(
    parameter int COORD_BITS = 16,
    parameter int DIR_BITS = 16,
    parameter int TAG_BITS = 16,
    parameter bit CONSERVATIVE = 1,  // 1: conservative margin (never misses); 0: 'nearest' (no margin)
    // Multipliers: "dsp" = pluecker_mul (on ECP5 MULT18X18D blocks),
    // "lut" = pluecker_mul_lut (fabric only), "rom" = pluecker_mul_rom
    // (block-RAM tables, one DP16KD a product; PIPELINE = 2 and
    // COORD_BITS + 1 + ceil(DIR_BITS/2) <= 10, i.e. 6/6), "auto" = "lut"
    // when both COORD_BITS and DIR_BITS are at most MUL_LUT_MAX_BITS, else
    // "dsp".
    parameter MUL_STYLE = "auto",
    // 1: one more register in every multiplier (its PIPELINE: the
    // MULT18X18D pipeline register; in fabric a register across the middle
    // of the adder tree), one more S2x stage and one more cycle of LATENCY;
    // 2: also a fabric register after every product (so that the route out
    // of a DSP column gets a whole period on a full chip), one more again.
    parameter int PIPELINE = 0,
    // 1: also compute the strict test (out_strict_o); needs CONSERVATIVE = 1
    parameter bit TERNARY = 0
) (
    input wire clk_i,
    input wire rst_i,  // synchronous, active high; resets control flops only

    input  wire                      in_valid_i,
    output wire                      in_ready_o,
    input  wire [      TAG_BITS-1:0] in_tag_i,
    input  wire [               2:0] ray_class_i,      // bit a set = axis a negative
    input  wire [3*COORD_BITS-1:0] ray_org_i,        // signed, x in the low field
    input  wire [  3*DIR_BITS-1:0] ray_dir_i,        // unsigned magnitudes
    input  wire [3*COORD_BITS-1:0] ray_end_i,        // signed
    input  wire                      ray_end_valid_i,
    input  wire [3*COORD_BITS-1:0] box_min_i,        // signed
    input  wire [3*COORD_BITS-1:0] box_max_i,        // signed

    output wire                out_valid_o,
    input  wire                out_ready_i,
    output wire [TAG_BITS-1:0] out_tag_o,
    output wire                out_hit_o,
    output wire                out_strict_o      // TERNARY: a certain hit
);

  // -------------------------------------------------------------------------
  // Parameter checks (elaboration time; messages without format arguments,
  // which Yosys prints verbatim). The limits are the port contract's.
  // -------------------------------------------------------------------------
  localparam int MIN_BITS = pluecker_contract_pkg::MIN_BITS;
  localparam int MAX_BITS = pluecker_contract_pkg::MAX_BITS;
  localparam bit COORD_BITS_OK = COORD_BITS >= MIN_BITS && COORD_BITS <= MAX_BITS;
  localparam bit DIR_BITS_OK = DIR_BITS >= MIN_BITS && DIR_BITS <= MAX_BITS;
  localparam bit TAG_BITS_OK = TAG_BITS >= pluecker_contract_pkg::MIN_TAG_BITS;
  localparam bit PIPELINE_OK = PIPELINE >= 0 && PIPELINE <= pluecker_contract_pkg::MAX_PIPELINE;
  localparam bit TERNARY_OK = !TERNARY || CONSERVATIVE;
  if (!COORD_BITS_OK) begin : g_bad_coord_bits
    $error("pluecker_intersector: parameter COORD_BITS is outside MIN_BITS..MAX_BITS of pluecker_contract_pkg");
  end
  if (!DIR_BITS_OK) begin : g_bad_dir_bits
    $error("pluecker_intersector: parameter DIR_BITS is outside MIN_BITS..MAX_BITS of pluecker_contract_pkg");
  end
  if (!TAG_BITS_OK) begin : g_bad_tag_bits
    $error("pluecker_intersector: parameter TAG_BITS must be at least 1");
  end
  if (!PIPELINE_OK) begin : g_bad_pipeline
    $error("pluecker_intersector: parameter PIPELINE must be 0, 1 or 2");
  end
  if (!TERNARY_OK) begin : g_bad_ternary
    $error("pluecker_intersector: parameter TERNARY = 1 needs CONSERVATIVE = 1 (nearest has no margin)");
  end
  // MUL_STYLE compared as a 32-bit pattern (a string parameter of up to four
  // characters, without width warnings).
  localparam logic [31:0] MUL_STYLE_S = 32'(MUL_STYLE);
  localparam bit MUL_STYLE_OK = MUL_STYLE_S == 32'("auto") || MUL_STYLE_S == 32'("dsp") ||
      MUL_STYLE_S == 32'("lut") || MUL_STYLE_S == 32'("rom");
  if (!MUL_STYLE_OK) begin : g_bad_mul_style
    $error("pluecker_intersector: parameter MUL_STYLE must be auto, dsp, lut or rom");
  end

  // Pairs (i, j), i != j, of the six edge tests, k = 0..5:
  // (0,1) (0,2) (1,2) (1,0) (2,0) (2,1).
  function automatic int pair_i(input int k);
    pair_i = k / 2;
  endfunction
  function automatic int pair_j(input int k);
    pair_j = (k / 2 + 1 + k % 2) % 3;
  endfunction

  // -------------------------------------------------------------------------
  // Widths (C = COORD_BITS, D = DIR_BITS). The bounds hold for every value
  // the ports can carry: any C-bit coordinates (also LO > HI) and any D-bit
  // direction up to 2^D - 1, beyond the set-up's maximum of 2^(D-1) (1.0),
  // so no operand pattern can overflow an intermediate.
  // -------------------------------------------------------------------------
  localparam int C = COORD_BITS;
  localparam int D = DIR_BITS;
  // A, B: difference of two C-bit signed values, |A|, |B| <= 2^C - 1.
  localparam int WA = C + 1;
  // Multiplier direction operand: D_i <= 2^D - 1 zero-extended to signed.
  localparam int WDS = D + 1;
  // Products and T: the full product width of a WA x WDS signed multiply.
  // |B_j*D_i| <= (2^C - 1)(2^D - 1) < 2^(C+D) and |T_ij| < 2^(C+D+1), so
  // T needs all C+D+2 bits (C+D+1 suffice for set-up directions only).
  localparam int WP = WA + WDS;
  // |A_i| in ones' complement form (A ^ sign): at most 2^C - 1, C bits.
  localparam int WMAG = C;
  // a'_i + b'_j + sign(A_i) <= 2*(2^C - 1) + 1 < 2^(C+1).
  localparam int WM1 = C + 1;
  // D_i + D_j + 1 <= 2*(2^D - 1) + 1 < 2^(D+1).
  localparam int WDD = D + 1;
  // Margin M = |A_i| + |B_j| + D_i + D_j + 1 <= 2^(C+1) + 2^(D+1) - 3
  // < 2^(max(C,D)+2), unsigned.
  localparam int WM = ((C > D) ? C : D) + 2;

  // Multiplier operands wider than one 18x18 DSP operand (WA = C + 1,
  // WDS = D + 1): each adds one registered adder stage (S2x) to pluecker_mul.
  localparam int DSP_OPERAND_BITS = pluecker_contract_pkg::DSP_OPERAND_BITS;
  localparam int MUL_ADD = ((WA > DSP_OPERAND_BITS) ? 1 : 0) + ((WDS > DSP_OPERAND_BITS) ? 1 : 0);

  // Multiplier style. On the LFE5U-85F (156 MULT18X18D, 83,640 LUT4 slots)
  // twelve DSP multipliers bound a chip to 13 units at any width (26 at 6/6
  // with PIPELINE = 2, MUL_PAIR below); fabric
  // multipliers make a unit LUT-bound: more units, each slower. Measured
  // (scripts/synth.py, 1 seed, speed 6, units x Fmax): 6/6 55 x 128 MHz
  // against 13 x 222 MHz, 8/8 38 x 133 against 13 x 204, 10/10 28 x 96
  // against 13 x 209 (a tie), 12/12 22 x 95 against 13 x 200. "auto" takes
  // fabric up to MUL_LUT_MAX_BITS = 9 bits (where MUL_ADD is always 0).
  localparam int MUL_LUT_MAX_BITS = pluecker_contract_pkg::MUL_LUT_MAX_BITS;
  localparam bit MUL_LUT = MUL_STYLE_S == 32'("lut") ||
      (MUL_STYLE_S == 32'("auto") && C <= MUL_LUT_MAX_BITS && D <= MUL_LUT_MAX_BITS);
  localparam bit LUT_WIDTH_OK = !(MUL_STYLE_S == 32'("lut") && MUL_ADD != 0);
  if (!LUT_WIDTH_OK) begin : g_bad_lut_width
    $error("pluecker_intersector: MUL_STYLE \"lut\" supports COORD_BITS and DIR_BITS up to 17");
  end

  // Table multipliers (MUL_STYLE "rom", rtl/pluecker_mul_rom.sv): one
  // DP16KD a product, both read ports of a table t[{x, a}] = a*x with x a
  // half of D_i; the address takes WA + ceil(D/2) bits of a 1K x 18 port.
  localparam bit MUL_ROM = MUL_STYLE_S == 32'("rom");
  localparam int ROM_ADDRESS_BITS = pluecker_contract_pkg::ROM_ADDRESS_BITS;
  localparam bit ROM_OK = !MUL_ROM || (PIPELINE == 2 && WA + (D + 1) / 2 <= ROM_ADDRESS_BITS);
  if (!ROM_OK) begin : g_bad_rom
    $error("pluecker_intersector: MUL_STYLE \"rom\" needs PIPELINE = 2 and COORD_BITS + 1 + ceil(DIR_BITS/2) <= 10");
  end
  // DP16KD of one unit's multipliers (the port contract's dp16kd).
  localparam int N_DP16KD = MUL_ROM ? 12 : 0;

  // Paired products: with DSP multipliers, PIPELINE = 2 and
  // C + 2 D <= DSP_OPERAND_BITS (6/6 bits) each MULT18X18D does the two
  // products of one difference (A_i by D_j and D_k, B_j by D_i and D_k;
  // rtl/pluecker_mul_pair.sv): six blocks a unit instead of twelve, same
  // LATENCY.
  localparam bit MUL_PAIR = !MUL_LUT && !MUL_ROM && PIPELINE == 2 && C + 2 * D <= DSP_OPERAND_BITS;
  // MULT18X18D of one unit (the port contract's mult18x18d).
  localparam int N_MULT18X18D = (MUL_LUT || MUL_ROM) ? 0 : MUL_PAIR ? 6 :
      12 * (1 + ((WA > DSP_OPERAND_BITS) ? 1 : 0)) * (1 + ((WDS > DSP_OPERAND_BITS) ? 1 : 0));

  // S2x stages between S2 and S3: the multipliers' pipeline register and
  // their adder stages.
  localparam int S2X = PIPELINE + MUL_ADD;
  // Cycles from the input handshake to the earliest output handshake:
  // S0..S4, S2x and the FIFO write.
  localparam int LATENCY = 6 + S2X;
  // A power of two >= LATENCY + 2: full throughput with out_ready_i high.
  localparam int FIFO_DEPTH = 1 << $clog2(LATENCY + 2);
  // FIFO index bits and pointer bits (one extra bit tells full from empty).
  localparam int FIFO_AW = $clog2(FIFO_DEPTH);
  localparam int FIFO_PW = FIFO_AW + 1;
  // Credit counter: 0..FIFO_DEPTH.
  localparam int CW = $clog2(FIFO_DEPTH + 1);
  localparam logic [CW-1:0] CREDITS_FULL = FIFO_DEPTH[CW-1:0];

  // The port contract's row for this configuration (checked only when every
  // parameter is valid, so that a bad one gets its own message alone).
  localparam bit PARAMS_OK = COORD_BITS_OK && DIR_BITS_OK && TAG_BITS_OK && PIPELINE_OK && MUL_STYLE_OK &&
      LUT_WIDTH_OK && ROM_OK && TERNARY_OK;
  localparam int CONTRACT_CLASS = pluecker_contract_pkg::contract_class(COORD_BITS, DIR_BITS, MUL_STYLE_S, PIPELINE);
  if (PARAMS_OK) begin : g_contract
    if (CONTRACT_CLASS < 0) begin : g_no_class
      $error("pluecker_intersector: the configuration is in no class of the port contract (pluecker_contract_pkg)");
    end else begin : g_row
      if (MUL_LUT != pluecker_contract_pkg::contract_mul_lut(CONTRACT_CLASS)) begin : g_bad_mul_lut
        $error("pluecker_intersector: the multiplier style differs from the port contract (pluecker_contract_pkg)");
      end
      if (MUL_ADD != pluecker_contract_pkg::contract_mul_add(CONTRACT_CLASS)) begin : g_bad_mul_add
        $error("pluecker_intersector: MUL_ADD differs from the port contract (pluecker_contract_pkg)");
      end
      if (LATENCY != pluecker_contract_pkg::contract_latency(CONTRACT_CLASS)) begin : g_bad_latency
        $error("pluecker_intersector: LATENCY differs from the port contract (pluecker_contract_pkg)");
      end
      if (FIFO_DEPTH != pluecker_contract_pkg::contract_fifo_depth(CONTRACT_CLASS)) begin : g_bad_fifo_depth
        $error("pluecker_intersector: FIFO_DEPTH differs from the port contract (pluecker_contract_pkg)");
      end
      if (N_MULT18X18D != pluecker_contract_pkg::contract_mult18x18d(CONTRACT_CLASS)) begin : g_bad_mult18x18d
        $error("pluecker_intersector: the MULT18X18D count differs from the port contract (pluecker_contract_pkg)");
      end
      if (MUL_ROM != pluecker_contract_pkg::contract_mul_rom(CONTRACT_CLASS)) begin : g_bad_mul_rom
        $error("pluecker_intersector: the table multipliers differ from the port contract (pluecker_contract_pkg)");
      end
      if (N_DP16KD != pluecker_contract_pkg::contract_dp16kd(CONTRACT_CLASS)) begin : g_bad_dp16kd
        $error("pluecker_intersector: the DP16KD count differs from the port contract (pluecker_contract_pkg)");
      end
    end
  end

  // -------------------------------------------------------------------------
  // Control: valid bits, credits, FIFO pointers (the only reset flops)
  // -------------------------------------------------------------------------
  logic v0_q, v1_q, v2_q, v3_q, v4_q;
  wire v2x_q;  // v2_q after the S2x stages
  logic ready_q;
  logic [FIFO_PW-1:0] wr_ptr_q, rd_ptr_q;
  // The credits and the results in the FIFO (wr_ptr_q - rd_ptr_q) as
  // thermometer codes (bit i set: more than i), one bit above FIFO_DEPTH
  // (never set): a take or give shifts them by one, so in_ready_o's and
  // out_valid_o's flops are one or two LUT levels from flops, with no
  // carry chain (the clock rate's shortest paths).
  localparam int CT = FIFO_DEPTH + 1;
  logic [CT-1:0] credits_q, credits_d, occ_q, occ_d;

  wire take = in_valid_i && ready_q;
  wire give = occ_q[0] && out_ready_i;

  always_comb begin
    credits_d = credits_q;
    if (take && !give) credits_d = credits_q >> 1;
    if (give && !take) credits_d = {credits_q[CT-2:0], 1'b1};
    occ_d = occ_q;
    if (v4_q && !give) occ_d = {occ_q[CT-2:0], 1'b1};
    // The top bit (never set) refills itself rather than a constant 0:
    // the same value, but Yosys then folds no synchronous reset into it, so
    // that flop shares its slice's set/reset with the other occ_q bits
    // (a flop with a set/reset net of its own stopped nextpnr's HeAP
    // legaliser on a 13 + 20 unit chip; fpga/TIMING.md).
    if (give && !v4_q) occ_d = {occ_q[CT-1], occ_q[CT-1:1]};
  end

  always_ff @(posedge clk_i) begin
    if (rst_i) begin
      v0_q <= 1'b0;
      v1_q <= 1'b0;
      v2_q <= 1'b0;
      v3_q <= 1'b0;
      v4_q <= 1'b0;
      ready_q <= 1'b0;
      credits_q <= (CT'(1) << CREDITS_FULL) - 1'b1;
      wr_ptr_q <= '0;
      rd_ptr_q <= '0;
      occ_q <= '0;
    end else begin
      v0_q <= take;
      v1_q <= v0_q;
      v2_q <= v1_q;
      v3_q <= v2x_q;
      v4_q <= v3_q;
      ready_q <= credits_d[0];
      credits_q <= credits_d;
      if (v4_q) wr_ptr_q <= wr_ptr_q + 1'b1;
      if (give) rd_ptr_q <= rd_ptr_q + 1'b1;
      occ_q <= occ_d;
    end
  end

  assign in_ready_o  = ready_q;
  assign out_valid_o = occ_q[0];

  // -------------------------------------------------------------------------
  // S0: subtract from the ports into the input registers (no reset, no
  // enable)
  //   A_i = n_i ? O_i - HI_i : LO_i - O_i      (entry plane)
  //   B_i = n_i ? O_i - LO_i : HI_i - O_i      (exit plane)
  //   G_i = n_i ? HI_i - E_i : E_i - LO_i      (end test: G_i >= 0)
  // -------------------------------------------------------------------------
  logic [TAG_BITS-1:0] tag0_q;
  logic [2:0][D-1:0] dir0_q;
  logic endv0_q;
  logic [2:0][WA-1:0] a0_q, b0_q;
  logic [2:0] end_in0_q;
  logic [2:0] end_in20_q;  // G_i >= 2 (the strict end test)

  always_ff @(posedge clk_i) begin
    tag0_q  <= in_tag_i;
    dir0_q  <= ray_dir_i;
    endv0_q <= ray_end_valid_i;
  end

  for (genvar i = 0; i < 3; i++) begin : g_sel
    wire n = ray_class_i[i];
    wire [C-1:0] o0 = ray_org_i[i*C+:C];
    wire [C-1:0] lo = box_min_i[i*C+:C];
    wire [C-1:0] hi = box_max_i[i*C+:C];
    wire [C-1:0] e0 = ray_end_i[i*C+:C];
    // Sign-extended to WA bits.
    wire signed [WA-1:0] o = {o0[C-1], o0};
    wire signed [WA-1:0] l = {lo[C-1], lo};
    wire signed [WA-1:0] h = {hi[C-1], hi};
    wire signed [WA-1:0] e = {e0[C-1], e0};
    // Differences straight from the ports (four carry chains), then the
    // class picks the results (one LUT level before the flops), so the class
    // bit drives no operand multiplexer in front of a chain (on a full chip
    // that fan-out, about 100 LUT inputs from one flop, limited Fmax).
    // One chain per box plane serves both classes: it computes P - O - n
    // ({P, 0} - {O, n}, upper WA bits), which is P - O for n = 0 and
    // ~(O - P) for n = 1 (P - O - 1 = ~(O - P)), so
    //   A = n ? ~dh : dl     B = n ? ~dl : dh
    // and each origin bit feeds two chains, not four.
    // Bit 0 of each only carries n's borrow into bit 1 (waived: unused).
    /* verilator lint_off UNUSEDSIGNAL */
    wire [WA:0] dl_x = {l, 1'b0} - {o, n};
    wire [WA:0] dh_x = {h, 1'b0} - {o, n};
    /* verilator lint_on UNUSEDSIGNAL */
    wire [WA-1:0] dl = dl_x[WA:1];  // l - o - n
    wire [WA-1:0] dh = dh_x[WA:1];  // h - o - n
    wire signed [WA-1:0] g_pos = e - l;  // end test, positive axis
    wire signed [WA-1:0] g_neg = h - e;  // end test, negative axis
    // G >= 0 and G >= 2 of each class, then the class picks.
    wire gp_in = !g_pos[WA-1];
    wire gn_in = !g_neg[WA-1];
    wire gp_in2 = gp_in && (|g_pos[WA-2:1]);
    wire gn_in2 = gn_in && (|g_neg[WA-2:1]);
    always_ff @(posedge clk_i) begin
      a0_q[i] <= n ? ~dh : dl;
      b0_q[i] <= n ? ~dl : dh;
      end_in0_q[i] <= n ? gn_in : gp_in;
      end_in20_q[i] <= n ? gn_in2 : gp_in2;
    end
  end

  // -------------------------------------------------------------------------
  // S1: the multipliers' input registers (inside them), and beside them the
  // margin's magnitudes and D_i + D_j + 1
  // -------------------------------------------------------------------------
  wire [2:0][WA-1:0] a_d = a0_q;
  wire [2:0][WA-1:0] b_d = b0_q;
  wire [2:0] end_in_d = end_in0_q;
  wire [2:0] end_in2_d = end_in20_q;

  // D_i + D_j + 1 of pair k.
  logic [5:0][WDD-1:0] dd_d;
  for (genvar k = 0; k < 6; k++) begin : g_dsum
    localparam int I = pair_i(k);
    localparam int J = pair_j(k);
    assign dd_d[k] = {1'b0, dir0_q[I]} + {1'b0, dir0_q[J]} + 1'b1;
  end

  logic [TAG_BITS-1:0] tag1_q;
  // The ones'-complement magnitudes a' = A ^ sign(A) (|A| = a' + sign(A);
  // A ^ sign(A) has a zero top bit: the low C bits) and the signs, so that
  // S2's margin sum is a bare carry chain.
  logic [2:0][WMAG-1:0] ma1_q, mb1_q;
  logic [2:0] sa1_q, sb1_q;
  logic [5:0][WDD-1:0] dd1_q;
  logic [2:0] end_in1_q, end_in21_q;
  logic endv1_q;

  always_ff @(posedge clk_i) begin
    tag1_q    <= tag0_q;
    for (int i = 0; i < 3; i++) begin
      ma1_q[i] <= a_d[i][WMAG-1:0] ^ {WMAG{a_d[i][WA-1]}};
      mb1_q[i] <= b_d[i][WMAG-1:0] ^ {WMAG{b_d[i][WA-1]}};
      sa1_q[i] <= a_d[i][WA-1];
      sb1_q[i] <= b_d[i][WA-1];
    end
    dd1_q     <= dd_d;
    end_in1_q <= end_in_d;
    end_in21_q <= end_in2_d;
    endv1_q   <= endv0_q;
  end

  // -------------------------------------------------------------------------
  // S2: multiply (registers before: S1, after: S2), and in parallel the
  // first part of the margin from the S1 magnitudes:
  //   m1_ij = a'_i + b'_j + sign(A_i); sign(B_j) is added in S3.
  // -------------------------------------------------------------------------
  // Products B_j*D_i and A_i*D_j, registered inside the multipliers (after
  // S2 and the S2x stages).
  wire [5:0][WP-1:0] pb2_q, pa2_q;
  logic [5:0][WM1-1:0] m1_d;
  logic [2:0] sb_d;
  logic [2:0] b2_d;  // B_i >= 2 (the strict origin test)
  localparam int MUL_PIPELINE = PIPELINE_OK ? PIPELINE : 0;
  // Fabric multipliers whose row ANDs feed an adder in the same period
  // (pluecker_mul_lut at PIPELINE 2 with 9 or more rows: its first
  // register is after tree level 1) get their own copy of their
  // direction's S0 register. Shared, a direction flop drives the row ANDs
  // of the four multipliers that use it (4 x WA loads: 36 at 8/8), and that
  // net's first wire limited the unit and the full chip (ECP5 speed 8, one
  // unit alone, median of five seeds: 8/8 249.7 -> 266.3 MHz, 9/9 243.9 ->
  // 267.9). The copies load the port, as dir0_q does (which then feeds
  // only D_i + D_j + 1); the keep attribute stops Yosys from merging the
  // identical flops. A and B stay shared (two multipliers each): copies of
  // them take the subtract and class multiplexer's output a long way and
  // limit S0 instead. With registered rows (PIPELINE 0 or 1, or fewer
  // rows) the AND has a period of its own and a copy only costs: one 6/6
  // unit 306.1 -> 292.1 MHz with them. So the copies go exactly where the
  // multiplier's rows are not registered (PIPELINE 2 and 9 or more rows),
  // by the rule the multiplier itself follows.
  localparam bit DIR_COPIES = MUL_LUT && !pluecker_mul_lut_pkg::mul_lut_registered(
      MUL_PIPELINE, pluecker_mul_lut_pkg::mul_lut_levels(WDS), 0);

  for (genvar i = 0; i < 3; i++) begin : g_sign
    assign sb_d[i] = sb1_q[i];
    // B >= 0 is below 2^C: its magnitude bits are B itself.
    assign b2_d[i] = !sb1_q[i] && (|mb1_q[i][WMAG-1:1]);
  end

  if (MUL_PAIR) begin : g_pair
    // Pair k = 2i and 2i + 1 is (i, i+1) and (i, i+2): A_i times D_(i+1)
    // and D_(i+2) in one block; B_j is B_J of pairs 2(j+2)+0 (times
    // D_(j+2)) and 2(j+1)+1 (times D_(j+1)), indices mod 3.
    for (genvar i = 0; i < 3; i++) begin : g_axis
      localparam int I1 = (i + 1) % 3;
      localparam int I2 = (i + 2) % 3;
      pluecker_mul_pair #(.WA(WA), .WU(D)) u_mul_a (
          .clk_i(clk_i), .a_i(a_d[i]), .b0_i(dir0_q[I1]), .b1_i(dir0_q[I2]),
          .p0_o(pa2_q[2*i]), .p1_o(pa2_q[2*i+1]));
      pluecker_mul_pair #(.WA(WA), .WU(D)) u_mul_b (
          .clk_i(clk_i), .a_i(b_d[i]), .b0_i(dir0_q[I2]), .b1_i(dir0_q[I1]),
          .p0_o(pb2_q[2*I2]), .p1_o(pb2_q[2*I1+1]));
    end
  end

  if (MUL_ROM) begin : g_rom
    // Pair k's two products, each from a block-RAM table.
    for (genvar k = 0; k < 6; k++) begin : g_prod
      localparam int I = pair_i(k);
      localparam int J = pair_j(k);
      pluecker_mul_rom #(.WA(WA), .WU(D)) u_mul_b (
          .clk_i(clk_i), .a_i(b_d[J]), .b_i(dir0_q[I]), .p_o(pb2_q[k]));
      pluecker_mul_rom #(.WA(WA), .WU(D)) u_mul_a (
          .clk_i(clk_i), .a_i(a_d[I]), .b_i(dir0_q[J]), .p_o(pa2_q[k]));
    end
  end

  for (genvar k = 0; k < 6; k++) begin : g_mul
    localparam int I = pair_i(k);
    localparam int J = pair_j(k);
    // Operands from the S0 registers (a_d, b_d, dir0_q; with DIR_COPIES the
    // direction from the multiplier's own copy), registered inside the
    // multiplier (as S1), product registered inside it (as S2).
    // Same ports and latency in every style.
    if (MUL_PAIR || MUL_ROM) begin : g_paired
      // The products come from g_pair or g_rom above.
    end else if (MUL_LUT) begin : g_lut
      // The directions: with DIR_COPIES each multiplier has its own copy of
      // its direction's S0 register (see DIR_COPIES), else dir0_q.
      logic [D-1:0] dir_b, dir_a;
      if (DIR_COPIES) begin : g_dir_copy
        logic [D-1:0] dirb0_q, dira0_q;
        (* keep *)
        always_ff @(posedge clk_i) begin
          dirb0_q <= ray_dir_i[I*D+:D];
          dira0_q <= ray_dir_i[J*D+:D];
        end
        assign dir_b = dirb0_q;
        assign dir_a = dira0_q;
      end else begin : g_dir_shared
        assign dir_b = dir0_q[I];
        assign dir_a = dir0_q[J];
      end
      pluecker_mul_lut #(.WA(WA), .WB(WDS), .PIPELINE(MUL_PIPELINE)) u_mul_b (
          .clk_i(clk_i), .a_i(b_d[J]), .b_i({1'b0, dir_b}), .p_o(pb2_q[k]));
      pluecker_mul_lut #(.WA(WA), .WB(WDS), .PIPELINE(MUL_PIPELINE)) u_mul_a (
          .clk_i(clk_i), .a_i(a_d[I]), .b_i({1'b0, dir_a}), .p_o(pa2_q[k]));
    end else begin : g_dsp
      pluecker_mul #(.WA(WA), .WB(WDS), .PIPELINE(MUL_PIPELINE), .ADD_STAGES(MUL_ADD)) u_mul_b (
          .clk_i(clk_i), .a_i(b_d[J]), .b_i({1'b0, dir0_q[I]}), .p_o(pb2_q[k]));
      pluecker_mul #(.WA(WA), .WB(WDS), .PIPELINE(MUL_PIPELINE), .ADD_STAGES(MUL_ADD)) u_mul_a (
          .clk_i(clk_i), .a_i(a_d[I]), .b_i({1'b0, dir0_q[J]}), .p_o(pa2_q[k]));
    end
    assign m1_d[k] = {1'b0, ma1_q[I]} + {1'b0, mb1_q[J]} + {{WMAG{1'b0}}, sa1_q[I]};
  end

  logic [TAG_BITS-1:0] tag2_q;
  logic [5:0][WM1-1:0] m12_q;
  logic [5:0][WDD-1:0] dd2_q;
  logic [2:0] sb2_q;
  logic ok2_q, oks2_q;

  always_ff @(posedge clk_i) begin
    oks2_q <= (!endv1_q || (&end_in21_q)) && (&b2_d);  // strict end and origin tests
    tag2_q <= tag1_q;
    m12_q  <= m1_d;
    dd2_q  <= dd1_q;
    sb2_q  <= sb_d;
    ok2_q  <= (!endv1_q || (&end_in1_q)) && !(|sb_d);  // end test, origin test
  end

  // -------------------------------------------------------------------------
  // The margins, from the S2 registers (so in the first S2x stage, or in S3
  // when there is none): only the halves S4 needs wait for the
  // multipliers, not their parts (fewer flip-flops in the S2x stages)
  //   M_ij  = |A_i| + |B_j| + D_i + D_j + 1 = m1_ij + (D_i + D_j + 1) + sign(B_j)
  //   MS_ij = M_ij + 2*(D_i + D_j + 1), the strict test's margin
  //   MH_ij = floor(M_ij / 2), MSH_ij = ceil(MS_ij / 2)
  // For an integer T: 2*T + M >= 0 <=> T >= -M/2 <=> T + floor(M/2) >= 0,
  // and 2*T - MS >= 0 <=> T >= MS/2 <=> T - ceil(MS/2) >= 0 (S4).
  // -------------------------------------------------------------------------
  localparam int WMS = WM + 1;  // MS < 2^(WM+1), and MSH <= 2^WM: WMS bits
  localparam int WMH = WM - 1;  // MH < 2^(WM-1)
  logic [5:0][WM-1:0] m_d;
  logic [5:0][WMS:0] ms1_d;  // MS + 1
  logic [5:0][WMH-1:0] mh_d;
  logic [5:0][WMS-1:0] msh_d;

  for (genvar k = 0; k < 6; k++) begin : g_margin
    localparam int J = pair_j(k);
    assign m_d[k] = WM'(m12_q[k]) + WM'(dd2_q[k]) + WM'(sb2_q[J]);
    assign mh_d[k] = m_d[k][WM-1:1];
    // MS + 1 from the parts, beside M rather than from M's sum (two
    // carry chains in series would lengthen this stage).
    assign ms1_d[k] = (WMS + 1)'(m12_q[k]) + (WMS + 1)'({dd2_q[k], 1'b0}) + (WMS + 1)'(dd2_q[k]) +
        (WMS + 1)'(sb2_q[J]) + 1'b1;
    assign msh_d[k] = ms1_d[k][WMS:1];
  end

  // -------------------------------------------------------------------------
  // S2x: S2X = PIPELINE + MUL_ADD stages while the multipliers finish (their
  // pipeline register, then pluecker_mul's partial-product sums); the first
  // registers the margins, the others only delay them.
  // -------------------------------------------------------------------------
  localparam int SIDE_W = 6 * WMH + 6 * WMS + 2;
  wire [SIDE_W-1:0] side2_d = {mh_d, msh_d, ok2_q, oks2_q};
  wire [TAG_BITS-1:0] tag2x_q;
  wire [SIDE_W-1:0] side2x_q;
  wire [5:0][WMH-1:0] mh2x_q;
  wire [5:0][WMS-1:0] msh2x_q;
  wire ok2x_q, oks2x_q;
`ifdef ASSERT_ON
  logic [31:0] s2x_in_flight;  // valid bits in the S2x stages
`endif

  if (S2X == 0) begin : g_no_s2x
    assign v2x_q = v2_q;
    assign tag2x_q = tag2_q;
    assign side2x_q = side2_d;
`ifdef ASSERT_ON
    assign s2x_in_flight = '0;
`endif
  end else begin : g_s2x
    // Stage s in bit s, bits [s*TAG_BITS +: TAG_BITS], [s*SIDE_W +: SIDE_W].
    logic [S2X-1:0] v_q;  // control: reset
    logic [S2X*TAG_BITS-1:0] tag_q;
    logic [S2X*SIDE_W-1:0] side_q;
    always_ff @(posedge clk_i) begin
      tag_q  <= (S2X * TAG_BITS)'({tag_q, tag2_q});
      side_q <= (S2X * SIDE_W)'({side_q, side2_d});
    end
    always_ff @(posedge clk_i) begin
      if (rst_i) v_q <= '0;
      else v_q <= S2X'({v_q, v2_q});
    end
    assign v2x_q = v_q[S2X-1];
    assign tag2x_q = tag_q[(S2X-1)*TAG_BITS+:TAG_BITS];
    assign side2x_q = side_q[(S2X-1)*SIDE_W+:SIDE_W];
`ifdef ASSERT_ON
    always_comb begin
      s2x_in_flight = '0;
      for (int s = 0; s < S2X; s++) s2x_in_flight = s2x_in_flight + 32'(v_q[s]);
    end
`endif
  end
  assign {mh2x_q, msh2x_q, ok2x_q, oks2x_q} = side2x_q;

  // -------------------------------------------------------------------------
  // S3: combine
  //   T_ij = B_j*D_i - A_i*D_j
  // -------------------------------------------------------------------------
  logic [5:0][WP-1:0] t_d;

  for (genvar k = 0; k < 6; k++) begin : g_comb
    assign t_d[k] = pb2_q[k] - pa2_q[k];
  end

  logic [TAG_BITS-1:0] tag3_q;
  logic [5:0][WP-1:0] t3_q;
  logic [5:0][WMH-1:0] mh3_q;
  logic [5:0][WMS-1:0] msh3_q;
  logic ok3_q, oks3_q;

  always_ff @(posedge clk_i) begin
    tag3_q <= tag2x_q;
    t3_q   <= t_d;
    mh3_q  <= mh2x_q;
    msh3_q <= msh2x_q;
    ok3_q  <= ok2x_q;
    oks3_q <= oks2x_q;
  end

  // -------------------------------------------------------------------------
  // S4: compare. Each test is the sign of one sum on one carry chain, whose
  // top bit the S4 flop takes straight (no LUT after the chain; a set bit
  // is a failed test):
  //   conservative  T + MH  < 0  (2*T + M  < 0)
  //   nearest       T       < 0  (the sign bit of T3, no chain)
  //   strict        T - MSH < 0  (2*T - MS < 0)
  // One bit wider than T (WP + 1): T + MH and T - MSH never overflow.
  // -------------------------------------------------------------------------
  logic [5:0] edge_fail_d, edge_sfail_d;

  for (genvar k = 0; k < 6; k++) begin : g_cmp
    wire [WP:0] t_x = {t3_q[k][WP-1], t3_q[k]};
    wire [WP:0] t_plus_mh = t_x + (WP + 1)'(mh3_q[k]);
    wire [WP:0] t_minus_msh = t_x - (WP + 1)'(msh3_q[k]);
    // The margin only in conservative mode.
    assign edge_fail_d[k] = CONSERVATIVE ? t_plus_mh[WP] : t3_q[k][WP-1];
    assign edge_sfail_d[k] = t_minus_msh[WP];
  end

  logic [TAG_BITS-1:0] tag4_q;
  logic [5:0] edge_fail4_q, edge_sfail4_q;
  logic ok4_q, oks4_q;

  always_ff @(posedge clk_i) begin
    tag4_q        <= tag3_q;
    edge_fail4_q  <= edge_fail_d;
    ok4_q         <= ok3_q;
    edge_sfail4_q <= edge_sfail_d;
    oks4_q        <= oks3_q;
  end
  // The strict test only exists with TERNARY (else the logic is removed).
  wire strict4 = TERNARY && oks4_q && !(|edge_sfail4_q);

  // -------------------------------------------------------------------------
  // Output FIFO (contents not reset; the pointers are)
  // -------------------------------------------------------------------------
  logic [TAG_BITS+1:0] fifo_q[FIFO_DEPTH];

  always_ff @(posedge clk_i) begin
    if (v4_q) fifo_q[wr_ptr_q[FIFO_AW-1:0]] <= {tag4_q, ok4_q && !(|edge_fail4_q), strict4};
  end

  assign {out_tag_o, out_hit_o, out_strict_o} = fifo_q[rd_ptr_q[FIFO_AW-1:0]];

  // -------------------------------------------------------------------------
  // Handshake and flow-control assertions (simulation, --assert)
  // -------------------------------------------------------------------------
`ifdef ASSERT_ON
  // Written as labelled immediate assertions on flopped history (no
  // concurrent properties, no action blocks) so that Verilator (--assert)
  // and Yosys (read_verilog -formal) both take them; a failure names the
  // label. The bookkeeping flops exist only here (a formal harness assumes
  // rst_i in the first cycle).
  localparam int IN_W = TAG_BITS + 3 + 4 * 3 * C + 3 * D + 1;
  logic chk_live_q;  // the previous edge had rst_i low
  logic out_stall_q, in_stall_q;
  logic [TAG_BITS+1:0] out_prev_q;
  logic [IN_W-1:0] in_prev_q;
  wire [IN_W-1:0] in_now = {
    in_tag_i, ray_class_i, ray_org_i, ray_dir_i, ray_end_i, ray_end_valid_i, box_min_i, box_max_i
  };
  wire [FIFO_PW-1:0] fifo_count = wr_ptr_q - rd_ptr_q;
  function automatic int ones(input logic [CT-1:0] t);
    ones = 0;
    for (int i = 0; i < CT; i++) ones += 32'(t[i]);
  endfunction

  always_ff @(posedge clk_i) begin
    chk_live_q  <= !rst_i;
    out_stall_q <= out_valid_o && !out_ready_i;
    out_prev_q  <= {out_tag_o, out_hit_o, out_strict_o};
    in_stall_q  <= in_valid_i && !in_ready_o;
    in_prev_q   <= in_now;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_i && chk_live_q) begin
      // A result, once offered, stays offered and unchanged until taken.
      if (out_stall_q) begin
        a_out_hold :
        assert (out_valid_o && {out_tag_o, out_hit_o, out_strict_o} == out_prev_q);
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
      assert (ones(credits_q) + 32'(v0_q) + 32'(v1_q) + 32'(v2_q) + 32'(v3_q) + 32'(v4_q) +
              s2x_in_flight +
              32'(fifo_count) == FIFO_DEPTH);
      a_ready_credit :
      assert (!ready_q || credits_q[0]);
      // Thermometer codes, and the result count follows the pointers.
      a_thermometer :
      assert (((credits_q + 1'b1) & credits_q) == '0 && ((occ_q + 1'b1) & occ_q) == '0);
      a_occupancy :
      assert (ones(occ_q) == 32'(fifo_count));
    end
  end
`endif

endmodule

`default_nettype wire
