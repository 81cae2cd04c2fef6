// SPDX-License-Identifier: MIT
// Cycle-by-cycle equivalence bench for the timing proposal (check_equiv.sh):
// pi_base (rtl/pluecker_intersector.sv as it is) and pi_new (the same file
// with timing.patch applied, plus pluecker_mul.sv in its generic form) get
// the same random queries and back-pressure; in_ready_o, out_valid_o and,
// while valid, out_tag_o and out_hit_o must agree on every cycle.
// Half of the rays are aimed at a point of their box so that hits are common.
`default_nettype none

module tb_equiv #(
    parameter int C = 16,
    parameter int D = 16,
    parameter int CONSERVATIVE = 1,
    parameter int CYCLES = 200000
);
  localparam int T = 12;
  logic clk = 1'b0, rst = 1'b1;
  always #5 clk = ~clk;

  logic in_valid, out_ready, endv;
  logic [T-1:0] tag;
  logic [2:0] cls;
  logic [3*C-1:0] org, endp, lo, hi;
  logic [3*D-1:0] dir;
  wire r0, r1, v0, v1, h0, h1;
  wire [T-1:0] t0, t1;

  pi_base #(.COORD_BITS(C), .DIR_BITS(D), .TAG_BITS(T), .CONSERVATIVE(CONSERVATIVE)) u_base (
      clk, rst, in_valid, r0, tag, cls, org, dir, endp, endv, lo, hi, v0, out_ready, t0, h0);
  pi_new #(.COORD_BITS(C), .DIR_BITS(D), .TAG_BITS(T), .CONSERVATIVE(CONSERVATIVE)) u_new (
      clk, rst, in_valid, r1, tag, cls, org, dir, endp, endv, lo, hi, v1, out_ready, t1, h1);

  function automatic logic [C-1:0] coord(longint span);
    return C'(longint'($urandom_range(0, 32'(2 * span))) - span);
  endfunction

  int errors = 0, outs = 0, hits = 0;
  initial begin
    for (int cyc = 0; cyc < CYCLES; cyc++) begin
      @(negedge clk);
      if (cyc == 5) rst = 1'b0;
      in_valid = $urandom_range(0, 9) != 0;
      out_ready = $urandom_range(0, 7) != 0;
      tag = T'($urandom);
      cls = 3'($urandom);
      endv = 1'($urandom);
      for (int i = 0; i < 3; i++) begin
        automatic longint span = ($urandom_range(0, 3) == 0) ? (64'd1 << (C - 1)) - 1 : 64'd40;
        automatic logic [C-1:0] a = coord(span), b = coord(span);
        org[i*C+:C] = coord(span);
        lo[i*C+:C] = ($signed(a) < $signed(b)) ? a : b;
        hi[i*C+:C] = ($signed(a) < $signed(b)) ? b : a;
        endp[i*C+:C] = coord(span);
        dir[i*D+:D] = D'($urandom_range(0, 32'(1 << (D - 1))));
      end
      dir[$urandom_range(0, 2)*D+:D] = D'(1 << (D - 1));
      if ($urandom_range(0, 1) == 1) begin : aim
        automatic longint dv[3];
        automatic longint m = 1;
        for (int i = 0; i < 3; i++) begin
          automatic longint l = longint'($signed(lo[i*C+:C]));
          automatic longint h = longint'($signed(hi[i*C+:C]));
          automatic longint t = l + longint'($urandom_range(0, 32'(h - l))) + longint'($urandom_range(0, 6)) - 3;
          dv[i] = t - longint'($signed(org[i*C+:C]));
          cls[i] = dv[i] < 0;
          if (dv[i] < 0) dv[i] = -dv[i];
          if (dv[i] > m) m = dv[i];
        end
        for (int i = 0; i < 3; i++) dir[i*D+:D] = D'((dv[i] << (D - 1)) / m);
        if ($urandom_range(0, 3) != 0) endv = 1'b0;
      end
      @(posedge clk);
      #1;
      if (r0 !== r1 || v0 !== v1 || (v0 && (t0 !== t1 || h0 !== h1))) begin
        errors++;
        if (errors < 10)
          $display("mismatch at cycle %0d: ready %b/%b valid %b/%b tag %h/%h hit %b/%b",
                   cyc, r0, r1, v0, v1, t0, t1, h0, h1);
      end
      if (v0 && out_ready) begin
        outs++;
        hits += int'(h0);
      end
    end
    $display("tb_equiv C=%0d D=%0d CONSERVATIVE=%0d: %0d results, %0d hits, %0d mismatches",
             C, D, CONSERVATIVE, outs, hits, errors);
    if (errors != 0 || hits == 0) $fatal(1, "tb_equiv: FAIL");
    $finish;
  end
endmodule

`default_nettype wire
