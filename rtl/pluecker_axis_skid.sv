// SPDX-License-Identifier: MIT
// Skid (spill) register of a valid/ready stream: every output, in_ready_o
// included, is a flip-flop, and it still passes one item per clock.
//
// The output register holds the item on offer (out_valid_o, out_data_o).
// in_ready_o is high while the skid register is empty. When the consumer
// stalls while an item arrives, the item lands in the skid register and
// in_ready_o falls at the next edge; when the output moves on, the skid
// item follows it. So out_ready_i reaches no output and no logic in front
// of this register, and a never-stalled consumer sees one item per clock.
// Items leave in the order they came; nothing is lost or doubled.
//
// rst_i (synchronous, active high) empties both registers; only the two
// valid bits are reset, never the data.
`default_nettype none

module pluecker_axis_skid #(
    parameter int DATA_BITS = 8
) (
    input wire clk_i,
    input wire rst_i,

    input  wire                 in_valid_i,
    output wire                 in_ready_o,
    input  wire [DATA_BITS-1:0] in_data_i,

    output wire                 out_valid_o,
    input  wire                 out_ready_i,
    output wire [DATA_BITS-1:0] out_data_o
);

  if (DATA_BITS < 1) begin : g_bad_data_bits
    $error("pluecker_axis_skid: parameter DATA_BITS must be at least 1");
  end

  logic out_valid_q, skid_valid_q;
  logic [DATA_BITS-1:0] out_data_q, skid_data_q;

  // The output register takes a new item when it is empty or being taken.
  wire out_free = out_ready_i || !out_valid_q;

  always_ff @(posedge clk_i) begin
    if (rst_i) begin
      out_valid_q  <= 1'b0;
      skid_valid_q <= 1'b0;
    end else if (skid_valid_q) begin
      if (out_free) begin  // the skid item moves to the output
        out_valid_q  <= 1'b1;
        skid_valid_q <= 1'b0;
      end
    end else if (out_free) begin  // an arriving item goes straight out
      out_valid_q <= in_valid_i;
    end else if (in_valid_i) begin  // output stalled: the item is parked
      skid_valid_q <= 1'b1;
    end
  end

  always_ff @(posedge clk_i) begin
    if (out_free) out_data_q <= skid_valid_q ? skid_data_q : in_data_i;
    if (!skid_valid_q && !out_free) skid_data_q <= in_data_i;
  end

  assign in_ready_o  = !skid_valid_q;
  assign out_valid_o = out_valid_q;
  assign out_data_o  = out_data_q;

endmodule

`default_nettype wire
