// SPDX-License-Identifier: MIT
// A delay line of STAGES registers (no reset, no enable): q_o is d_i as it
// was STAGES rising edges ago; STAGES = 0 is a wire. The local and the
// binary32 units' pipelines use it to carry a value beside the stages that
// compute others (datapath only: valid bits, which are reset, are kept by
// the unit itself).
`default_nettype none

module pluecker_pipe #(
    parameter int WIDTH = 1,
    parameter int STAGES = 1
) (
    input  wire             clk_i,
    input  wire [WIDTH-1:0] d_i,
    output wire [WIDTH-1:0] q_o
);
  if (WIDTH < 1 || STAGES < 0) begin : g_bad_params
    $error("pluecker_pipe: WIDTH must be at least 1 and STAGES at least 0");
  end

  if (STAGES == 0) begin : g_wire
    assign q_o = d_i;
    wire unused_clk = clk_i;  // no register
  end else begin : g_regs
    // Stage s in bits [s*WIDTH +: WIDTH].
    logic [STAGES*WIDTH-1:0] line_q;
    always_ff @(posedge clk_i) line_q <= (STAGES * WIDTH)'({line_q, d_i});
    assign q_o = line_q[(STAGES-1)*WIDTH+:WIDTH];
  end

endmodule

`default_nettype wire
