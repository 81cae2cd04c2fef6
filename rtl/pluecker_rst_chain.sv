// SPDX-License-Identifier: MIT
// A reset chain: rst_o is rst_i delayed by STAGES flops (STAGES = 0: a
// wire). One chain per unit (or per harness lane) makes a reset tree: each
// net from one flop to the next is short enough for one clock, where a
// single reset net across a whole chip is not.
//
// The flops are kept: identical chains would otherwise be merged into one
// by synthesis, which would rebuild the chip-wide net the chains are there
// to avoid. They have no reset of their own (they carry the reset). In
// simulation they start high, so that the logic behind the chain sees a
// reset from its first clock, as it would without the chain.
`default_nettype none

module pluecker_rst_chain #(
    parameter int STAGES = 1  // flops from rst_i to rst_o (0..8)
) (
    input  wire clk_i,
    input  wire rst_i,
    output wire rst_o
);
  if (STAGES < 0 || STAGES > 8) begin : g_bad_stages
    $error("pluecker_rst_chain: parameter STAGES must be 0..8");
  end

  if (STAGES == 0) begin : g_wire
    assign rst_o = rst_i;
    // Unused at STAGES = 0: the clock.
    wire unused_clk = clk_i;
  end else begin : g_chain
    logic [STAGES-1:0] rst_q;
`ifndef SYNTHESIS
    initial rst_q = '1;
`endif
    (* keep *)
    always_ff @(posedge clk_i) begin
      rst_q[0] <= rst_i;
      for (int s = 1; s < STAGES; s++) rst_q[s] <= rst_q[s-1];
    end
    assign rst_o = rst_q[STAGES-1];
  end
endmodule

`default_nettype wire
