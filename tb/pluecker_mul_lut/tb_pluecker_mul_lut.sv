// SPDX-License-Identifier: MIT
// Exhaustive self-checking bench of rtl/pluecker_mul_lut.sv: every signed
// WA x WB operand pair, the product compared with a plain multiply after the
// module's latency (2 + PIPELINE edges). Run by test_pluecker_mul_lut.py,
// one build per parameter set.
`default_nettype none
module tb_pluecker_mul_lut;
  parameter int WA = 7;
  parameter int WB = 7;
  parameter bit PIPELINE = 0;
  localparam int L = 2 + PIPELINE;
  logic clk = 0;
  logic signed [WA-1:0] a;
  logic signed [WB-1:0] b;
  wire signed [WA+WB-1:0] p;
  pluecker_mul_lut #(.WA(WA), .WB(WB), .PIPELINE(PIPELINE)) dut(.clk_i(clk), .a_i(a), .b_i(b), .p_o(p));
  longint exp_q[$];
  int errs = 0, n = 0;
  initial begin
    for (longint i = 0; i < (64'd1 << (WA + WB)) + L; i++) begin
      a = WA'(i); b = WB'(i >> WA);
      begin longint aa, bb; aa = a; bb = b; exp_q.push_back(aa * bb); end
      #1 clk = 1; #1 clk = 0;
      if (exp_q.size() > L - 1) begin
        longint e; e = exp_q.pop_front();
        n++;
        if (p !== (WA+WB)'(e)) begin errs++; if (errs < 5) $display("mismatch exp %0d got %0d", e, p); end
      end
    end
    $display("WA=%0d WB=%0d PIPE=%0d checked %0d errors %0d", WA, WB, PIPELINE, n, errs);
    if (errs != 0) $fatal(1, "FAIL");
    $finish;
  end
endmodule
