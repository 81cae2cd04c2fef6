// SPDX-License-Identifier: MIT
// Registered signed multiply for the intersector's 12 products:
//   p_o = a_i * b_i, 2 + PIPELINE + ADD_STAGES clock edges after a_i, b_i.
//
// PIPELINE (0..2): 1 clocks the MULT18X18D's internal pipeline register;
// 2 also registers every block's output in fabric (in front of the adder
// stages of split operands, or as the product itself), so that the route
// from a DSP column into the fabric gets a whole clock period (on a full
// chip the fabric next to the columns is crowded and that route is long).
//
// ADD_STAGES must be the number of operands wider than 18 bits (0, 1 or 2;
// elaboration fails otherwise), so that the latency is a function of the
// widths alone, the same on every target. Operands are at most 35 bits,
// 70 together (the intersector needs at most 25 each; the local unit's
// moment products up to 35 x 33, rtl/pluecker_local_frame.sv).
//
// With PLUECKER_ECP5 defined (scripts/synth.py defines it for Yosys):
//   - both operands at most 18 bits: one MULT18X18D with its input and
//     output registers clocked, and its internal pipeline register when
//     PIPELINE >= 1 (pluecker_dsp18: Yosys 0.70's synth_ecp5 never packs
//     fabric registers into MULT18X18D, so without the instance the
//     multiplier delay, 3.1 ns at speed 8, sits between two fabric
//     flip-flops).
//   - a wider operand x is split into a signed high part x[W-1:17] and an
//     unsigned low part {0, x[16:0]}, each an 18-bit signed DSP operand; every
//     partial product is a MULT18X18D registered as above, and the partial
//     products are summed in ADD_STAGES registered fabric stages of one
//     adder each (so no path crosses a DSP and an adder):
//       one operand split (x = xh*2^17 + xl, y whole):
//         +1  p = xl*y + (xh*y << 17)
//       both split:
//         +1  c = {ah*bh, al*bl[33:0]} (al*bl < 2^34, so no add)
//             x = ah*bl + al*bh (the two 36-bit products sign-extended
//             to the WA+WB-17 bits of x)
//         +2  p = c + (x << 17)
//     All sums are taken modulo 2^(WA+WB), which holds the exact product.
// Otherwise (simulation, lint, other targets) the same number of registers
// around a generic `*`: identical results and latency.
//
// nextpnr-ecp5 times the block by its input and output registers only; it
// ignores the internal pipeline register, so it neither credits nor checks
// the input-register -> output-register path. PIPELINE = 1 closes that
// path in the silicon at the cost of one cycle.
`default_nettype none

module pluecker_mul #(
    parameter int WA = 17,
    parameter int WB = 17,
    parameter int PIPELINE = 0,
    parameter int ADD_STAGES = 0
) (
    input  wire                    clk_i,
    input  wire signed [WA-1:0]    a_i,
    input  wire signed [WB-1:0]    b_i,
    output wire signed [WA+WB-1:0] p_o
);
  localparam int W = WA + WB;
  localparam int SPLIT_A = (WA > 18) ? 1 : 0;
  localparam int SPLIT_B = (WB > 18) ? 1 : 0;

  if (ADD_STAGES != SPLIT_A + SPLIT_B) begin : g_bad_add_stages
    $error("pluecker_mul: ADD_STAGES must equal the number of operands wider than 18 bits");
  end
  if (PIPELINE < 0 || PIPELINE > 2) begin : g_bad_pipeline
    $error("pluecker_mul: parameter PIPELINE must be 0, 1 or 2");
  end
  if (WA > 35 || WB > 35 || WA + WB > 70 || WA < 2 || WB < 2) begin : g_bad_width
    $error("pluecker_mul: operand widths must be 2..35 bits, 70 bits together");
  end

`ifdef PLUECKER_ECP5
  // Operand parts, 18-bit signed each: [0] low (or the whole operand), [1]
  // high (split operands only).
  localparam int NA = 1 + SPLIT_A;
  localparam int NB = 1 + SPLIT_B;
  wire [1:0][17:0] a_part, b_part;
  if (SPLIT_A != 0) begin : g_split_a
    assign a_part[0] = {1'b0, a_i[16:0]};
    assign a_part[1] = 18'($signed(a_i[WA-1:17]));
  end else begin : g_whole_a
    assign a_part[0] = 18'(a_i);
    assign a_part[1] = '0;
  end
  if (SPLIT_B != 0) begin : g_split_b
    assign b_part[0] = {1'b0, b_i[16:0]};
    assign b_part[1] = 18'($signed(b_i[WB-1:17]));
  end else begin : g_whole_b
    assign b_part[0] = 18'(b_i);
    assign b_part[1] = '0;
  end

  // pp[ia + 2*ib] = a_part[ia] * b_part[ib], registered inside the DSP.
  wire [3:0][35:0] pp;
  for (genvar k = 0; k < 4; k++) begin : g_dsp
    localparam int IA = k % 2;
    localparam int IB = k / 2;
    if (IA < NA && IB < NB) begin : g_used
      wire [17:0] a18 = a_part[IA];
      wire [17:0] b18 = b_part[IB];
      wire [35:0] p36;
      pluecker_dsp18 #(
          .PIPELINE_REG(PIPELINE != 0),
          .SIGNED_A(1'b1),
          .SIGNED_B(1'b1)
      ) u_mult (
          .clk_i(clk_i),
          .a_i(a18),
          .b_i(b18),
          .p_o(p36)
      );
      if (PIPELINE > 1) begin : g_out_reg
        // The block's output registered once more, in fabric.
        logic [35:0] p36_q;
        always_ff @(posedge clk_i) p36_q <= p36;
        assign pp[k] = p36_q;
      end else begin : g_out_wire
        assign pp[k] = p36;
      end
    end else begin : g_unused
      assign pp[k] = '0;
    end
  end

  if (SPLIT_A == 0 && SPLIT_B == 0) begin : g_one
    assign p_o = pp[0][W-1:0];
  end else if (SPLIT_A == 0 || SPLIT_B == 0) begin : g_two
    // Low part times the whole operand (signed), and the high part's product
    // at weight 2^17.
    localparam int KH = SPLIT_A ? 1 : 2;
    wire [W-1:0] lo = W'($signed(pp[0]));
    logic [W-1:0] p_q;
    always_ff @(posedge clk_i) p_q <= {lo[W-1:17] + pp[KH][W-18:0], lo[16:0]};
    assign p_o = p_q;
  end else begin : g_four
    logic [W-1:0] c_q, p_q;
    logic [W-18:0] x_q;
    always_ff @(posedge clk_i) begin
      c_q <= {pp[3][W-35:0], pp[0][33:0]};
      x_q <= (W - 17)'($signed(pp[1])) + (W - 17)'($signed(pp[2]));
      p_q <= {c_q[W-1:17] + x_q, c_q[16:0]};
    end
    assign p_o = p_q;
  end
`else
  begin : g_generic
    logic signed [WA-1:0] a_q;
    logic signed [WB-1:0] b_q;
    logic signed [W-1:0] m_q, p_q, p2_q;
    always_ff @(posedge clk_i) begin
      a_q <= a_i;
      b_q <= b_i;
      m_q <= a_q * b_q;
      p_q <= m_q;
      p2_q <= p_q;
    end
    wire signed [W-1:0] p_reg = (PIPELINE > 1) ? p2_q : (PIPELINE != 0) ? p_q : m_q;
    // The ECP5 build's adder stages, as plain delay.
    if (ADD_STAGES == 0) begin : g_nodelay
      assign p_o = p_reg;
    end else begin : g_delay
      // Stage s in bits [s*W +: W].
      logic [ADD_STAGES*W-1:0] d_q;
      always_ff @(posedge clk_i) d_q <= (ADD_STAGES * W)'({d_q, p_reg});
      assign p_o = d_q[(ADD_STAGES-1)*W+:W];
    end
  end
`endif

endmodule

`default_nettype wire
