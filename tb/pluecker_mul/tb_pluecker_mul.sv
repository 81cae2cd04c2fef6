// SPDX-License-Identifier: MIT
// Self-checking bench of rtl/pluecker_mul.sv on its ECP5 path
// (PLUECKER_ECP5: MULT18X18D blocks, operands over 18 bits split into
// partial products added in registered stages), against a plain `*` delayed
// by the module's latency. Sixteen width pairs from 6 to 35 bits, one or both
// operands split, PIPELINE 0 and 1; random and extreme operands (min, max,
// -1, single bits). The MULT18X18D is the behavioural stand-in
// mult18x18d_model.sv. Run by test_pluecker_mul.py.
`default_nettype none
module tb_one #(parameter int WA = 17, parameter int WB = 17, parameter bit PIPE = 0) (input wire clk, input wire [31:0] cyc, output logic bad);
  localparam int AS = ((WA > 18) ? 1 : 0) + ((WB > 18) ? 1 : 0);
  localparam int LAT = 2 + PIPE + AS;
  localparam int W = WA + WB;
  logic signed [WA-1:0] a; logic signed [WB-1:0] b;
  wire signed [W-1:0] p;
  logic signed [W-1:0] exp_q [LAT];
  pluecker_mul #(.WA(WA), .WB(WB), .PIPELINE(PIPE), .ADD_STAGES(AS)) dut (.clk_i(clk), .a_i(a), .b_i(b), .p_o(p));
  function automatic logic [63:0] pick(input int w, input int r);
    logic [63:0] v = {$urandom, $urandom};
    case (r % 8)
      0: v = 64'(1) << (w - 1);          // min
      1: v = ~(64'(1) << (w - 1));       // max
      2: v = '1;                          // -1
      3: v = 64'(1) << ($urandom % w);
      4: v = ~(64'(1) << ($urandom % w));
      default: ;
    endcase
    return v;
  endfunction
  always @(negedge clk) begin
    a = WA'(pick(WA, int'($urandom)));
    b = WB'(pick(WB, int'($urandom)));
  end
  // a, b change only through $urandom in always_comb; sample them each edge
  logic signed [WA-1:0] a_s; logic signed [WB-1:0] b_s;
  always_ff @(posedge clk) begin
    a_s <= a; b_s <= b;
    exp_q[0] <= W'(a) * W'(b);
    for (int i = 1; i < LAT; i++) exp_q[i] <= exp_q[i-1];
    bad <= 1'b0;
    if (cyc > 40 && p !== exp_q[LAT-1]) begin
      bad <= 1'b1;
      $display("MISMATCH WA=%0d WB=%0d PIPE=%0d cyc %0d: p=%0d exp=%0d", WA, WB, PIPE, cyc, p, exp_q[LAT-1]);
    end
  end
endmodule

module tb_pluecker_mul;
  logic clk = 0;
  logic [31:0] cyc = 0;
  wire [15:0] bad;
  tb_one #(17, 17, 0) t0 (clk, cyc, bad[0]);
  tb_one #(19, 17, 0) t1 (clk, cyc, bad[1]);
  tb_one #(17, 19, 0) t2 (clk, cyc, bad[2]);
  tb_one #(19, 19, 0) t3 (clk, cyc, bad[3]);
  tb_one #(25, 25, 0) t4 (clk, cyc, bad[4]);
  tb_one #(25, 7, 0)  t5 (clk, cyc, bad[5]);
  tb_one #(7, 25, 0)  t6 (clk, cyc, bad[6]);
  tb_one #(21, 25, 1) t7 (clk, cyc, bad[7]);
  tb_one #(25, 18, 1) t8 (clk, cyc, bad[8]);
  tb_one #(18, 18, 1) t9 (clk, cyc, bad[9]);
  tb_one #(35, 18, 0) t10 (clk, cyc, bad[10]);
  tb_one #(26, 26, 0) t11 (clk, cyc, bad[11]);
  tb_one #(23, 21, 0) t12 (clk, cyc, bad[12]);
  tb_one #(6, 7, 0)   t13 (clk, cyc, bad[13]);
  tb_one #(19, 25, 0) t14 (clk, cyc, bad[14]);
  tb_one #(25, 19, 1) t15 (clk, cyc, bad[15]);
  int errors = 0;
  always #5 clk = ~clk;
  always @(posedge clk) begin
    cyc <= cyc + 1;
    if (|bad) errors++;
    if (cyc == 100000) begin
      $display("done: %0d cycles, %0d error cycles", cyc, errors);
      $finish;
    end
  end
endmodule
