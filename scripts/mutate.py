#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Seeded bugs as a standing check of the tests (`make mutate`,
`make mutate-smoke`).

Every mutant is a small, exact textual edit of the RTL, the model or the
harness (an edit that no longer applies, because the source changed, stops
the run with a message naming it). The tracked files of the tree are copied
into a work tree (build/mutate/tree); each mutant is applied there in turn,
the tests that must catch it run on the copy, and the edit is undone. A
mutant is caught when every one of its tests fails on it; the run fails
when a mutant survives one of them.

Checks (the fewest, fastest tests that catch the mutant):
  ctest:FILTER            model_tests --gtest_filter=FILTER, built in the copy
  harness:CxD[n]:KIND:N   the Verilator harness of the copy's RTL at that
                          configuration (n = nearest): `pluecker_sim gen
                          --kind KIND --n N` then `query --check`; KIND bench
                          runs `pluecker_sim bench --n N` (random
                          back-pressure on the output) instead
  cocotb:NODE[@FILTER]    one pytest node of the copy's tb/ (its cocotb tests
                          filtered by the regular expression FILTER)
  formal:CONFIG           fpga/formal/run.sh's bounded check (bmc) at CONFIG
A build that fails counts as a catch only when the mutant says it must (a
change the port contract forbids fails elaboration by design); any other
failure of a build or a tool stops the run (status 2): it says nothing about
the tests.

Before the mutants, every check they use runs once on the unmodified copy
and must pass (a check that fails anyway could not tell). --smoke runs the
few fast mutants of `make test` and skips that baseline: the same checks
pass in the rest of `make test`.

Builds are reused: the copy's model build (build/mutate/tree/build/model)
and harness builds (build/mutate/tree/build/sim/...) sit at the same place
relative to the copy as the project's own builds relative to the project,
and both compile through ccache with paths hashed relative to the build
folder (model/CMakeLists.txt, sim/CMakeLists.txt), so every file the
project's build compiled is a cache hit in the copy; then a model mutant
recompiles its file and relinks the tests, an RTL mutant re-verilates each
configuration it uses. The copy and its builds stay for the next run.

Usage: scripts/venv-exec.sh python scripts/mutate.py [--smoke] [--only A,B] [--list]
       [--model-build DIR (the project's build, for pluecker_py)] [--jobs N]
Exit status: 0 every mutant caught, 1 a mutant survived, 2 bad use or a
check that cannot run.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RTL = "rtl/pluecker_intersector.sv"
FIXED = "model/core/src/fixed.cpp"
GRID = "model/core/src/grid.cpp"
LOCAL = "model/core/src/local.cpp"
LOCAL_CHILD = "rtl/pluecker_local_child.sv"
LOCAL_FRAME = "rtl/pluecker_local_frame.sv"
# The local unit's short cocotb configuration (K 8, D 11, G 32, conservative): every stream.
LOCAL_TB = ("cocotb:tb/pluecker_local_intersector/test_pluecker_local_intersector.py::"
            "test_pluecker_local_intersector[k8_d11_g32_c1_cons]@stream")


class Stop(Exception):
    """A failure that is not a verdict on a mutant (exit status 2)."""


@dataclass
class Mutant:
    name: str
    what: str
    edits: list[tuple[str, str, str]]  # (file, exact old text, new text)
    checks: list[str]
    build_error: str = ""  # a build failing with this (regex) is a catch
    smoke: bool = False


# ---------------------------------------------------------------------------
# The mutants
# ---------------------------------------------------------------------------

def _class_rtl(k: int) -> Mutant:
    return Mutant(
        f"rtl-planes-class{k}", f"RTL: box planes LO/HI swapped for ray class {k} only",
        [(RTL, "    wire [C-1:0] lo = box_min_i[i*C+:C];\n    wire [C-1:0] hi = box_max_i[i*C+:C];",
          f"    wire [C-1:0] lo = ray_class_i == 3'd{k} ? box_max_i[i*C+:C] : box_min_i[i*C+:C];\n"
          f"    wire [C-1:0] hi = ray_class_i == 3'd{k} ? box_min_i[i*C+:C] : box_max_i[i*C+:C];")],
        ["harness:6x6:boundary:20000"])


def _class_model(k: int) -> Mutant:
    return Mutant(
        f"model-planes-class{k}", f"model: entry and exit planes swapped for ray class {k} only",
        [(FIXED, "        const bool neg = class_negative(r.cls, i);\n        A[i] =",
          f"        const bool neg = class_negative(r.cls, i) != (r.cls == {k});\n        A[i] =")],
        ["ctest:FixedVsExact.RandomQueriesNeverMissInConservativeMode"])


# A stage more between S4 and the FIFO (valid and result), LATENCY unchanged.
_EXTRA_STAGE = (
    RTL,
    "  always_ff @(posedge clk_i) begin\n"
    "    if (v4_q) fifo_q[wr_ptr_q[FIFO_AW-1:0]] <= {tag4_q, ok4_q && !(|edge_fail4_q), strict4};\n  end",
    "  logic v5_q;\n  logic [TAG_BITS+1:0] res5_q;\n"
    "  always_ff @(posedge clk_i) begin\n"
    "    v5_q <= rst_i ? 1'b0 : v4_q;\n    res5_q <= {tag4_q, ok4_q && !(|edge_fail4_q), strict4};\n  end\n"
    "  always_ff @(posedge clk_i) begin\n"
    "    if (v5_q) fifo_q[wr_ptr_q[FIFO_AW-1:0]] <= res5_q;\n  end")
_EXTRA_STAGE_PTR = (RTL, "      if (v4_q) wr_ptr_q <= wr_ptr_q + 1'b1;", "      if (v5_q) wr_ptr_q <= wr_ptr_q + 1'b1;")

CASCADE_RTL = "rtl/pluecker_cascade.sv"
CASCADE_TB = "cocotb:tb/pluecker_cascade/test_pluecker_cascade.py::test_pluecker_cascade[n2_8x8_to_16x16]"
# A cascade whose side FIFOs can fill (narrow FIFO_DEPTH 16 = SIDE_DEPTH; at
# the 8/8 cascade's FIFO_DEPTH 8 a side FIFO of 16 never fills).
CASCADE_TB_FULL = "cocotb:tb/pluecker_cascade/test_pluecker_cascade.py::test_pluecker_cascade[n3_6x6_to_12x12_p1]"

MUTANTS: list[Mutant] = [
    # --- RTL datapath --------------------------------------------------------
    Mutant("rtl-margin-plus-one", "RTL: the margin's +1 dropped (D_i + D_j + 1 -> D_i + D_j)",
           [(RTL, "assign dd_d[k] = {1'b0, dir0_q[I]} + {1'b0, dir0_q[J]} + 1'b1;",
             "assign dd_d[k] = {1'b0, dir0_q[I]} + {1'b0, dir0_q[J]};")],
           ["harness:16x16:boundary:20000"], smoke=True),
    # Not listed, because no input can tell them: dropping the sign(A_i)
    # or sign(B_j) correction of |A_i|, |B_j| in the margin. A_i < 0 with
    # B_j >= 0 makes T_ij >= 0, so the edge test passes with any margin, and
    # B_j < 0 fails the origin test whatever the margin.
    # 2T + M > 0 <=> 2T + M - 1 >= 0 <=> T + floor((M - 1)/2) >= 0 (M >= 1):
    # the half margin taken of M - 1.
    Mutant("rtl-edge-strict", "RTL: edge test 2T + M > 0 instead of >= 0",
           [(RTL, "assign mh_d[k] = m_d[k][WM-1:1];", "assign mh_d[k] = WMH'((m_d[k] - 1'b1) >> 1);")],
           ["harness:6x6:boundary:20000"]),
    Mutant("rtl-nearest-margin", "RTL: nearest mode keeps the margin",
           [(RTL, "assign edge_fail_d[k] = CONSERVATIVE ? t_plus_mh[WP] : t3_q[k][WP-1];",
             "assign edge_fail_d[k] = t_plus_mh[WP];")],
           ["harness:8x8n:boundary:20000"]),
    *[_class_rtl(k) for k in range(8)],
    Mutant("rtl-entry-plane-pos", "RTL: entry plane of positive axes from HI (A_i = HI_i - O_i)",
           [(RTL, "a0_q[i] <= n ? ~dh : dl;", "a0_q[i] <= n ? ~dh : dh;")],
           ["harness:6x6:boundary:20000"]),
    Mutant("rtl-exit-plane-neg", "RTL: exit plane of negative axes from HI (B_i = O_i - HI_i)",
           [(RTL, "b0_q[i] <= n ? ~dl : dh;", "b0_q[i] <= n ? ~dh : dh;")],
           ["harness:6x6:boundary:20000"]),
    Mutant("rtl-s0-borrow-dropped", "RTL: S0's class borrow dropped (negative axes' A_i, B_i one too small)",
           [(RTL, "wire [WA:0] dl_x = {l, 1'b0} - {o, n};", "wire [WA:0] dl_x = {l, 1'b0} - {o, 1'b0};"),
            (RTL, "wire [WA:0] dh_x = {h, 1'b0} - {o, n};", "wire [WA:0] dh_x = {h, 1'b0} - {o, 1'b0};")],
           ["harness:6x6:boundary:20000"]),
    Mutant("rtl-end-plane-pos", "RTL: end test of positive axes against HI instead of LO",
           [(RTL, "wire signed [WA-1:0] g_pos = e - l;", "wire signed [WA-1:0] g_pos = e - h;")],
           ["harness:6x6:boundary:20000"]),
    Mutant("rtl-end-plane-neg", "RTL: end test of negative axes against LO instead of HI",
           [(RTL, "wire signed [WA-1:0] g_neg = h - e;", "wire signed [WA-1:0] g_neg = l - e;")],
           ["harness:6x6:boundary:20000"]),
    Mutant("rtl-end-valid-ignored", "RTL: the end test applied to unbounded rays too",
           [(RTL, "ok2_q  <= (!endv1_q || (&end_in1_q)) && !(|sb_d);", "ok2_q  <= (&end_in1_q) && !(|sb_d);")],
           ["harness:6x6:boundary:20000"]),
    Mutant("rtl-origin-test-dropped", "RTL: the origin test (B_i >= 0) dropped",
           [(RTL, "ok2_q  <= (!endv1_q || (&end_in1_q)) && !(|sb_d);", "ok2_q  <= (!endv1_q || (&end_in1_q));")],
           ["harness:6x6:boundary:20000"]),
    # --- RTL flow control and latency ----------------------------------------
    Mutant("rtl-fifo-write-index", "RTL: results written at the read pointer (lost under back-pressure)",
           [(RTL, "if (v4_q) fifo_q[wr_ptr_q[FIFO_AW-1:0]] <=", "if (v4_q) fifo_q[rd_ptr_q[FIFO_AW-1:0]] <=")],
           ["harness:6x6:bench:20000"]),
    Mutant("rtl-credits-plus-one", "RTL: one credit more than FIFO entries (overflow under back-pressure)",
           [(RTL, "localparam logic [CW-1:0] CREDITS_FULL = FIFO_DEPTH[CW-1:0];",
             "localparam logic [CW-1:0] CREDITS_FULL = CW'(FIFO_DEPTH + 1);")],
           ["cocotb:tb/pluecker_intersector/test_pluecker_intersector.py::test_pluecker_intersector[c6_d6_cons]"
            "@throughput"]),
    Mutant("rtl-latency-plus-one", "RTL: one stage more in front of the FIFO, LATENCY left at the contract's",
           [_EXTRA_STAGE, _EXTRA_STAGE_PTR],
           ["harness:6x6:boundary:2000",
            "cocotb:tb/pluecker_intersector/test_pluecker_intersector.py::test_pluecker_intersector[c6_d6_cons]"
            "@throughput"]),
    Mutant("rtl-latency-plus-one-declared", "RTL: one stage more and LATENCY raised with it (RTL only)",
           [_EXTRA_STAGE, _EXTRA_STAGE_PTR,
            (RTL, "localparam int LATENCY = 6 + S2X;", "localparam int LATENCY = 7 + S2X;")],
           ["harness:6x6:boundary:2000"], build_error=r"LATENCY differs from the port contract"),
    Mutant("rtl-latency-minus-one", "RTL: the S4 register bypassed (results one cycle early)",
           [(RTL, "    if (v4_q) fifo_q[wr_ptr_q[FIFO_AW-1:0]] <= {tag4_q, ok4_q && !(|edge_fail4_q), strict4};",
             "    if (v3_q) fifo_q[wr_ptr_q[FIFO_AW-1:0]] <= {tag3_q, ok3_q && !(|edge_fail_d),\n"
             "        TERNARY && oks3_q && !(|edge_sfail_d)};"),
            (RTL, "      if (v4_q) wr_ptr_q <= wr_ptr_q + 1'b1;", "      if (v3_q) wr_ptr_q <= wr_ptr_q + 1'b1;"),
            # out_valid_o's count too, or the answers would only be written
            # a clock before they are offered (no change at the ports).
            (RTL, "    if (v4_q && !give) occ_d =", "    if (v3_q && !give) occ_d ="),
            (RTL, "    if (give && !v4_q) occ_d =", "    if (give && !v3_q) occ_d =")],
           ["harness:6x6:boundary:2000",
            "cocotb:tb/pluecker_intersector/test_pluecker_intersector.py::test_pluecker_intersector[c6_d6_cons]"
            "@throughput"]),
    # The cascade's escalation path (rtl/pluecker_cascade.sv).
    Mutant("cascade-slot-overwrite", "cascade: an uncertain answer taken while its escalation slot is full",
           [(CASCADE_RTL, "wire slot_load = uncertain[l] && slot_free;", "wire slot_load = uncertain[l];")],
           [CASCADE_TB]),
    Mutant("cascade-wide-input-overwrite", "cascade: a slot granted without a credit of the wide unit "
           "(its input register offered while it is not ready: lost)",
           [(CASCADE_RTL, "wire w_take = any_req && wcred_q[0];", "wire w_take = any_req;")],
           [CASCADE_TB]),
    Mutant("cascade-side-overflow", "cascade: a narrow unit takes a query while its lane's side FIFO is full "
           "(a wide query overwritten: the lane's in_ready_o low, the query taken twice)",
           [(CASCADE_RTL, ".in_valid_i(in_valid_i[l] && !side_full),", ".in_valid_i(in_valid_i[l]),")],
           [CASCADE_TB_FULL]),
    Mutant("cascade-side-count-late", "cascade: the side FIFO's full flag forgets that its count learns of a push "
           "a clock late (one query more than its depth: a wide query overwritten)",
           [(CASCADE_RTL, "assign side_full = side_occ_q[SIDE_DEPTH-2];",
             "assign side_full = side_occ_q[SIDE_DEPTH-1];")],
           [CASCADE_TB_FULL]),
    Mutant("cascade-slot-early", "cascade: the slot's wide query loaded in the clock the slot fills, before the "
           "side FIFO's read pointers reach its answer (another query's wide query escalated)",
           [(CASCADE_RTL, "if (!slot_vd_rep_q[b/CTRL_FANOUT]) slot_query_q[b] <= side_head[l*WQ+b];",
             "if (!slot_v_rep_q[b/CTRL_FANOUT]) slot_query_q[b] <= side_head[l*WQ+b];")],
           [CASCADE_TB]),
    # The handshake mutants of the formal harness (bounded check).
    Mutant("formal-credit-leak", "RTL: a credit returned on every output handshake, also with an input",
           [(RTL, "if (give && !take) credits_d = {credits_q[CT-2:0], 1'b1};",
             "if (give) credits_d = {credits_q[CT-2:0], 1'b1};")],
           ["formal:6x6"]),
    Mutant("formal-read-without-ready", "RTL: the read pointer advances without out_ready_i",
           [(RTL, "if (give) rd_ptr_q <= rd_ptr_q + 1'b1;", "if (out_valid_o) rd_ptr_q <= rd_ptr_q + 1'b1;")],
           ["formal:6x6"]),
    Mutant("formal-reset-keeps-stage", "RTL: a reset keeps stage S2's valid bit",
           [(RTL, "      v1_q <= 1'b0;\n      v2_q <= 1'b0;\n", "      v1_q <= 1'b0;\n")],
           ["formal:6x6"]),
    Mutant("formal-credits-one-too-many", "RTL: one credit too many (formal)",
           [(RTL, "localparam logic [CW-1:0] CREDITS_FULL = FIFO_DEPTH[CW-1:0];",
             "localparam logic [CW-1:0] CREDITS_FULL = CW'(FIFO_DEPTH + 1);")],
           ["formal:6x6"]),
    Mutant("formal-reset-keeps-s2x-stage", "RTL: a reset keeps the S2x valid bits (PIPELINE = 1)",
           [(RTL, "      if (rst_i) v_q <= '0;", "      if (rst_i) v_q <= v_q;")],
           ["formal:6x6p1"]),
    Mutant("formal-credit-leak-18x18", "RTL: the credit leak at the widest configuration (MUL_ADD 2)",
           [(RTL, "if (give && !take) credits_d = {credits_q[CT-2:0], 1'b1};",
             "if (give) credits_d = {credits_q[CT-2:0], 1'b1};")],
           ["formal:18x18"]),
    # --- multipliers ---------------------------------------------------------
    Mutant("mul-dsp-unsigned-a", "pluecker_mul: MULT18X18D with SIGNEDA low (operand A unsigned)",
           [("rtl/pluecker_mul.sv", ".SIGNED_A(1'b1)", ".SIGNED_A(1'b0)")],
           ["cocotb:tb/pluecker_mul/test_pluecker_mul.py::test_pluecker_mul_ecp5[17x17_p0]"]),
    Mutant("mul-dsp-unsigned-b", "pluecker_mul: MULT18X18D with SIGNEDB low (operand B unsigned)",
           [("rtl/pluecker_mul.sv", ".SIGNED_B(1'b1)", ".SIGNED_B(1'b0)")],
           ["cocotb:tb/pluecker_mul/test_pluecker_mul.py::test_pluecker_mul_ecp5[17x17_p0]"]),
    Mutant("mul-dsp-split-high-unsigned", "pluecker_mul: high part of a split operand A zero-extended",
           [("rtl/pluecker_mul.sv", "assign a_part[1] = 18'($signed(a_i[WA-1:17]));",
             "assign a_part[1] = 18'(a_i[WA-1:17]);")],
           ["cocotb:tb/pluecker_mul/test_pluecker_mul.py::test_pluecker_mul_ecp5[19x17_p0]"]),
    Mutant("mul-generic-unsigned", "pluecker_mul: the generic path multiplies A as unsigned",
           [("rtl/pluecker_mul.sv", "    logic signed [WA-1:0] a_q;", "    logic [WA-1:0] a_q;")],
           ["harness:16x16:boundary:20000"]),
    Mutant("mul-pair-no-borrow", "pluecker_mul_pair: the high product without the low product's borrow",
           [("rtl/pluecker_mul_pair.sv", "p1_q <= p36[K+W-1:K] + W'(s_q[2]);", "p1_q <= p36[K+W-1:K];")],
           ["cocotb:tb/pluecker_mul_pair/test_pluecker_mul_pair.py::test_pluecker_mul_pair[7x6-ecp5]"]),
    Mutant("mul-pair-borrow-at-zero", "pluecker_mul_pair: a borrow also when b0 = 0 (a < 0)",
           [("rtl/pluecker_mul_pair.sv", "wire s_d = a_i[WA-1] && (|b0_i);", "wire s_d = a_i[WA-1];")],
           ["cocotb:tb/pluecker_mul_pair/test_pluecker_mul_pair.py::test_pluecker_mul_pair[7x6-generic]"]),
    Mutant("mul-rom-initval-packed", "pluecker_mul_rom: table words packed 18 bits apart in INITVAL (not 20)",
           [("rtl/pluecker_mul_rom.sv", "init_slice[20*i+:18] = 18'(entry(16 * s + i));",
             "init_slice[18*i+:18] = 18'(entry(16 * s + i));")],
           ["cocotb:tb/pluecker_mul_rom/test_pluecker_mul_rom.py::test_pluecker_mul_rom[7x6-ecp5]"]),
    Mutant("mul-rom-high-weight", "pluecker_mul_rom: the high half's product at weight 2^(UL-1)",
           [("rtl/pluecker_mul_rom.sv", "(W'($signed(hi_q)) << UL);", "(W'($signed(hi_q)) << (UL - 1));")],
           ["cocotb:tb/pluecker_mul_rom/test_pluecker_mul_rom.py::test_pluecker_mul_rom[7x6-generic]"]),
    Mutant("mul-lut-sign-row-added", "pluecker_mul_lut: the sign row of B added instead of subtracted",
           [("rtl/pluecker_mul_lut.sv", "wire signed [WS-1:0] s = SUB ? WS'(hi) - WS'(right) : WS'(hi) + WS'(right);",
             "wire signed [WS-1:0] s = WS'(hi) + WS'(right);")],
           ["cocotb:tb/pluecker_mul_lut/test_pluecker_mul_lut.py::test_pluecker_mul_lut[8x8_p0]"]),
    Mutant("mul-lut-rows-unsigned", "pluecker_mul_lut: partial-product rows not sign-extended",
           [("rtl/pluecker_mul_lut.sv", "        wire signed [WR-1:0] right = g_lvl[l-1].g_node[2*g+1].v;",
             "        wire [WR-1:0] right = g_lvl[l-1].g_node[2*g+1].v;")],
           ["harness:6x6:boundary:20000"]),
    Mutant("mul-lut-spread-extra-register", "pluecker_mul_lut: PIPELINE 2 spread over the tree keeps the register after p_q",
           [("rtl/pluecker_mul_lut.sv", "if (PIPELINE > 1 && !SPREAD) begin : g_out_reg", "if (PIPELINE > 1) begin : g_out_reg")],
           ["cocotb:tb/pluecker_mul_lut/test_pluecker_mul_lut.py::test_pluecker_mul_lut[10x10_p2]"]),
    Mutant("rtl-dir-copy-wrong-axis", "RTL: a fabric multiplier's own direction copy (DIR_COPIES) loads the other axis",
           [(RTL, "dira0_q <= ray_dir_i[J*D+:D];", "dira0_q <= ray_dir_i[I*D+:D];")],
           ["cocotb:tb/pluecker_intersector/test_pluecker_intersector.py::test_pluecker_intersector[c8_d8_p2_cons]"]),
    # --- model: set-up (fixed.cpp, grid.cpp) and datapath (fixed.cpp) ---------
    Mutant("model-origin-truncated", "model: origin inside R truncated (floor) instead of rounded to nearest",
           [(FIXED, "out.org[a] = static_cast<i64>(detail::round_to_grid(r.o[a], Round::Nearest, f.coord_bits));",
             "out.org[a] = static_cast<i64>(detail::round_to_grid(r.o[a], Round::Down, f.coord_bits));")],
           ["ctest:MarginBound.RaysThroughEdgesAndCornersAtRoundingTies"]),
    Mutant("model-direction-truncated", "model: direction truncated instead of rounded to nearest",
           [(GRID, "    if (2 * rem > den || (2 * rem == den && (q & 1))) ++q;\n", "")],
           ["ctest:FixedVsExact.RandomQueriesNeverMissInConservativeMode"]),
    Mutant("model-box-lo-nearest", "model: conservative box LO rounded to nearest instead of down",
           [(FIXED, "detail::round_to_grid(b.lo[a], cons ? Round::Down : Round::Nearest, f.coord_bits);",
             "detail::round_to_grid(b.lo[a], Round::Nearest, f.coord_bits);")],
           ["ctest:FixedSetup.BoxRoundsOutwardInConservativeMode"]),
    Mutant("model-box-hi-nearest", "model: conservative box HI rounded to nearest instead of up",
           [(FIXED, "detail::round_to_grid(b.hi[a], cons ? Round::Up : Round::Nearest, f.coord_bits);",
             "detail::round_to_grid(b.hi[a], Round::Nearest, f.coord_bits);")],
           ["ctest:FixedSetup.BoxRoundsOutwardInConservativeMode"]),
    Mutant("model-end-nearest", "model: conservative segment end rounded to nearest instead of outward",
           [(GRID, "const double q = !outward                 ? nearest_exact(s, err)",
             "const double q = true                     ? nearest_exact(s, err)")],
           ["ctest:FixedSetup.SegmentEndRoundsOutward"], smoke=True),
    Mutant("model-end-inward", "model: conservative segment end rounded inward",
           [(GRID, ": class_negative(cls, a) ? floor_exact(s, err)\n"
                   "                                                  : ceil_exact(s, err);",
             ": class_negative(cls, a) ? ceil_exact(s, err)\n"
             "                                                  : floor_exact(s, err);")],
           ["ctest:FixedSetup.SegmentEndRoundsOutward"]),
    Mutant("model-clip-first-entry", "model: clip onto the first slab entered instead of the last",
           [(GRID, "if (r.d[a] != 0.0f && (e < 0 || enters_later(r, range, a, e))) e = a;",
             "if (r.d[a] != 0.0f && (e < 0 || enters_later(r, range, e, a))) e = a;")],
           ["ctest:Setup.ClippedOriginIsTheExactEntryPointRoundedToNearest"]),
    Mutant("model-clip-truncated", "model: clip point truncated toward the entry face's corner",
           [(GRID, "q[b] = exact_round_ratio(t, 3, std::fabs(r.d[e]), bits);",
             "q[b] = static_cast<i64>(std::floor((t[0] + t[1] + t[2]) / std::fabs(double(r.d[e]))));")],
           ["ctest:Setup.ClippedOriginIsTheExactEntryPointRoundedToNearest"]),
    *[_class_model(k) for k in range(8)],
    Mutant("model-margin-plus-one", "model: the margin's +1 dropped",
           [(FIXED, "std::llabs(B[j]) + r.dir[i] + r.dir[j] + 1 : T;", "std::llabs(B[j]) + r.dir[i] + r.dir[j] : T;")],
           ["ctest:MarginBound.SlackOfEveryRealHitIsAtLeastOne"]),
    Mutant("model-end-test-dropped", "model: the end test (G_i >= 0) dropped",
           [(FIXED, "            if (G < 0) return false;  // segment ends before the entry plane\n",
             "            (void)G;\n")],
           ["ctest:MarginBound.SlackOfEveryRealHitIsAtLeastOne"]),
    # --- model: local frames (local.cpp) ---------------------------------------
    Mutant("local-mu-dropped", "local frames: the global width's share of the margin (mu) dropped",
           [(LOCAL, "            w += 2 * mu + 1;", "            w += 1;")],
           ["ctest:Local.NeverMissesOnRaysFromAnywhere"]),
    Mutant("local-margin-dropped", "local frames: the child margin ext_j + ent_i dropped",
           [(LOCAL, "(cons ? ext[j] + ent[i] : 0) + r.w[k];", "r.w[k];")],
           ["ctest:Local.NeverMissesOnRandomQueries"]),
    Mutant("local-mirror-lo", "local frames: negative axes mirror about the frame's lo corner",
           [(LOCAL, "const i128 mirror = neg ? fr.origin[i] + (f.box_max() << fr.exp[i]) : fr.origin[i];",
             "const i128 mirror = fr.origin[i];")],
           ["ctest:Local.NeverMissesOnRandomQueries"]),
    Mutant("local-moment-floor", "local frames: the moment rounded down instead of to nearest",
           [(LOCAL, "        i128 w = 2 * round_shift(lambda, sh);", "        i128 w = 2 * (sh <= 0 ? lambda << -sh : lambda >> std::min(sh, 120));")],
           ["ctest:Local.MomentRoundsToNearest"]),
    Mutant("local-box-lo-nearest", "local frames: a box's LO rounded to nearest in its frame",
           [(LOCAL, "out.lo[a] = plane_in_frame(b.lo[a], fr.origin[a], fr.exp[a], cons ? Round::Down : Round::Nearest, "
                    "f.grid_bits);",
             "out.lo[a] = plane_in_frame(b.lo[a], fr.origin[a], fr.exp[a], Round::Nearest, f.grid_bits);")],
           ["ctest:Local.NeverMissesOnRandomQueries"]),
    Mutant("local-end-nearest", "local frames: the local segment end rounded to nearest in conservative mode",
           [(LOCAL, "cons ? ceil_shift(de, fr.exp[i]) : round_shift(de, fr.exp[i])", "round_shift(de, fr.exp[i])")],
           ["ctest:Local.SegmentEndRoundsOutwardInConservativeMode"]),
    # --- RTL: the local unit (pluecker_local_child, pluecker_local_frame) -------
    Mutant("local-rtl-margin-dropped", "local unit RTL: the child margin ext_j + ent_i dropped",
           [(LOCAL_CHILD, "CONSERVATIVE ? WMW'(ext1_q[J]) + WMW'(ent1_q[I]) : '0", "'0")],
           [LOCAL_TB]),
    Mutant("local-rtl-entry-plane-neg", "local unit RTL: entry plane of negative axes from LO (no mirror)",
           [(LOCAL_CHILD, "assign ent_d[i] = cls_i[i] ? ~hi : lo;", "assign ent_d[i] = lo;")],
           [LOCAL_TB]),
    Mutant("local-rtl-end-valid-ignored", "local unit RTL: the end test applied to unbounded rays too",
           [(LOCAL_CHILD, "(!endv1_q || (&end_ok_d))", "(&end_ok_d)")],
           [LOCAL_TB]),
    Mutant("local-rtl-origin-test-dropped", "local unit RTL: the origin test dropped",
           [(LOCAL_CHILD, "ok2_q <= (&org_ok_d) && ", "ok2_q <= ")],
           [LOCAL_TB]),
    Mutant("local-rtl-w-plus-one-dropped", "local unit RTL: the node set-up's +1 of W dropped in conservative mode",
           [(LOCAL_FRAME, " + WZ'(CONSERVATIVE ? 1 : 0);", ";")],
           [LOCAL_TB]),
    # --- harness and port contract --------------------------------------------
    Mutant("contract-pack-end-as-origin", "port contract: pack_query puts the origin on the end port",
           [("model/core/src/contract.cpp", "p.ray_end = pack3(r.end, f.coord_bits);",
             "p.ray_end = pack3(r.org, f.coord_bits);")],
           ["ctest:Contract.PackUnpackRoundTrip"]),
]


# ---------------------------------------------------------------------------
# The copy and its builds
# ---------------------------------------------------------------------------

def run(cmd: list, cwd: Path, env: dict | None = None, timeout: int = 3600) -> subprocess.CompletedProcess:
    return subprocess.run([str(c) for c in cmd], cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)


def tracked_files() -> list[str]:
    r = run(["git", "ls-files", "-z"], ROOT)
    if r.returncode != 0:
        raise Stop(f"git ls-files failed in {ROOT}: {r.stderr.strip()} (the copy is made of the tracked files)")
    return [f for f in r.stdout.split("\0") if f]


def sync_tree(tree: Path) -> None:
    """The tracked files of the work tree into `tree`; unchanged files keep
    their time stamps (so the copy's builds stay incremental), files no
    longer tracked leave (a stale source would be built)."""
    tracked = tracked_files()
    keep = set(tracked)
    for top, dirs, files in os.walk(tree):
        if Path(top) == tree:
            dirs[:] = [d for d in dirs if d not in ("build", ".venv")]
        for f in files:
            p = Path(top) / f
            if p.relative_to(tree).as_posix() not in keep and p.name != ".venv":
                p.unlink()
    for rel in tracked:
        src, dst = ROOT / rel, tree / rel
        if not src.exists():  # deleted in the work tree, not yet committed
            continue
        if dst.exists() and dst.read_bytes() == src.read_bytes():
            continue
        dst.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(src, dst)
    venv = tree / ".venv"
    if not venv.exists():
        venv.symlink_to((ROOT / ".venv").resolve())


class Tree:
    """The copy, its builds and the checks run in it."""

    def __init__(self, tree: Path, py_dir: Path, jobs: int):
        self.dir = tree
        self.py_dir = py_dir
        self.jobs = jobs
        self.model = tree / "build" / "model"
        self.env = dict(os.environ)

    def venv_cmd(self, *cmd) -> list:
        return [self.dir / "scripts" / "venv-exec.sh", *cmd]

    # -- model ----------------------------------------------------------------
    def build_model(self, targets: list[str]) -> subprocess.CompletedProcess | None:
        """None when built; the failed build otherwise."""
        if not (self.model / "CMakeCache.txt").exists():
            self.model.mkdir(parents=True, exist_ok=True)
            r = run(["cmake", "-S", self.dir / "model", "-B", self.model, "-DCMAKE_BUILD_TYPE=Release",
                     "-DPLUECKER_PYTHON=OFF"], self.dir, self.env)
            if r.returncode != 0:
                raise Stop(f"configuring the copy's model failed:\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
        r = run(["cmake", "--build", self.model, f"-j{self.jobs}", "--target", *targets], self.dir, self.env)
        return None if r.returncode == 0 else r

    # -- harness --------------------------------------------------------------
    def build_sim(self, cfg: str) -> tuple[Path, subprocess.CompletedProcess | None]:
        m = re.fullmatch(r"(\d+)x(\d+)(n?)", cfg)
        if not m:
            raise Stop(f"bad harness configuration '{cfg}' (CxD, CxDn for nearest)")
        failed = self.build_model(["pluecker_app"])
        if failed:
            raise Stop(f"the copy's model libraries do not build:\n{failed.stderr[-3000:]}")
        out = self.dir / "build" / "sim" / (f"{m[1]}x{m[2]}" + ("_nearest" if m[3] else ""))
        # No lint or style warnings (a mutant may leave a signal unused):
        # linting is `make lint`'s job. Not -Wno-fatal, which would let the
        # RTL's elaboration checks ($error, USERERROR) pass.
        env = dict(self.env, COORD_BITS=m[1], DIR_BITS=m[2], MODE="nearest" if m[3] else "conservative",
                   MODEL_BUILD=str(self.model), SIM_OUT=str(out), SIM_JOBS=str(self.jobs), SIM_VFLAGS="-Wno-lint -Wno-style")
        r = run(self.venv_cmd(self.dir / "sim" / "build.sh"), self.dir, env)
        return out / "pluecker_sim", (None if r.returncode == 0 else r)


@dataclass
class Verdict:
    state: str  # "pass", "caught", "error"
    detail: str = ""
    seconds: float = 0.0


def _tail(r: subprocess.CompletedProcess, lines: int = 12) -> str:
    return "\n".join((r.stdout + r.stderr).strip().splitlines()[-lines:])


def _build_failure(r: subprocess.CompletedProcess, mutant: Mutant | None) -> Verdict:
    text = r.stdout + r.stderr
    if mutant and mutant.build_error:
        m = re.search(mutant.build_error, text)
        if m:
            return Verdict("caught", f"build fails: ...{m.group(0)}")
    return Verdict("error", "build failed:\n" + _tail(r, 30))


def check_ctest(tree: Tree, arg: str, mutant: Mutant | None) -> Verdict:
    failed = tree.build_model(["model_tests"])
    if failed:
        return _build_failure(failed, mutant)
    r = run([tree.model / "model_tests", f"--gtest_filter={arg}"], tree.model, tree.env)
    names = re.findall(r"^\[  FAILED  \] (\S+\.\S+)", r.stdout, re.M)
    if r.returncode == 0:
        return Verdict("pass")
    if names:
        uniq = sorted(set(names))
        return Verdict("caught", f"{len(uniq)} failed: " + ", ".join(uniq[:4]) + (" ..." if len(uniq) > 4 else ""))
    return Verdict("error", "model_tests ended without a test failure:\n" + _tail(r))


def check_harness(tree: Tree, arg: str, mutant: Mutant | None) -> Verdict:
    cfg, kind, n = arg.split(":")
    sim, failed = tree.build_sim(cfg)
    if failed:
        return _build_failure(failed, mutant)
    if kind == "bench":
        r = run([sim, "bench", "--n", n, "--ready", "0.5"], tree.dir, tree.env)
        summary = " ".join(re.findall(r"(\d+ mismatches)", r.stdout))
    else:
        q = sim.parent / f"mutate_{kind}_{n}.txt"
        g = run([sim, "gen", "--kind", kind, "--n", n, "--seed", "17", "--out", q], tree.dir, tree.env)
        if g.returncode != 0:
            return Verdict("error", "pluecker_sim gen failed:\n" + _tail(g))
        r = run([sim, "query", "--check", q], tree.dir, tree.env)
        summary = next((ln for ln in r.stderr.splitlines() if ln.startswith("check")), "")
    if r.returncode == 0:
        return Verdict("pass")
    if r.returncode == 1:
        first = next((ln for ln in r.stderr.splitlines() if "mismatch:" in ln or "protocol" in ln), "")
        first = first.replace(str(sim.parent) + "/", "")
        return Verdict("caught", (first + "; " + summary).strip("; "))
    return Verdict("error", f"pluecker_sim exit {r.returncode}:\n" + _tail(r))


def check_cocotb(tree: Tree, arg: str, mutant: Mutant | None) -> Verdict:
    node, _, filt = arg.partition("@")
    env = dict(tree.env, PLUECKER_PY_DIR=str(tree.py_dir), PLUECKER_TB_BUILD=str(tree.dir / "build" / "tb"),
               PLUECKER_RTL_DIR=str(tree.dir / "rtl"))
    if filt:
        env["COCOTB_TEST_FILTER"] = filt
    r = run(tree.venv_cmd("python", "-m", "pytest", "-q", "-p", "no:cacheprovider", node), tree.dir, env)
    if r.returncode == 0:
        return Verdict("pass")
    text = r.stdout + r.stderr
    if "cocotb.regression" not in text:  # no simulation ran: the build failed
        return _build_failure(r, mutant)
    if r.returncode == 1:
        fails = sorted(set(re.findall(r"\w+\.(\w+)\s+FAIL\b", text)))
        rtl = re.search(r"Assertion failed in (\S+?):", text)
        msg = re.search(r"AssertionError: (.+)", text)
        first = f"RTL assertion {rtl.group(1)}" if rtl else msg.group(1).strip() if msg else ""
        return Verdict("caught", (f"cocotb {', '.join(fails)} failed" if fails else "failed") +
                       (f": {first[:160]}" if first else ""))
    return Verdict("error", f"pytest exit {r.returncode}:\n" + _tail(r))


def check_formal(tree: Tree, arg: str, mutant: Mutant | None) -> Verdict:
    out = tree.dir / "build" / "formal"
    env = dict(tree.env, FORMAL_PROVE_CONFIGS=arg, FORMAL_BMC_CONFIGS=arg, FORMAL_COVER_CONFIGS=arg,
               FORMAL_TASKS="bmc", FORMAL_OUT=str(out), VENV=str((ROOT / ".venv").resolve()))
    r = run([tree.dir / "fpga" / "formal" / "run.sh"], tree.dir, env)
    if r.returncode == 0:
        return Verdict("pass")
    fails = sorted(set(re.findall(r"failed assertion \S+", r.stdout)))
    if r.returncode == 1 and fails:
        return Verdict("caught", "bmc: " + ", ".join(f.split()[-1] for f in fails[:4]))
    if r.returncode == 1 and mutant and mutant.build_error and re.search(mutant.build_error, r.stdout):
        return Verdict("caught", "elaboration fails")
    return Verdict("error", f"fpga/formal/run.sh exit {r.returncode}:\n" + _tail(r))


CHECKS = {"ctest": check_ctest, "harness": check_harness, "cocotb": check_cocotb, "formal": check_formal}


def run_check(tree: Tree, check: str, mutant: Mutant | None) -> Verdict:
    kind, _, arg = check.partition(":")
    if kind not in CHECKS:
        raise Stop(f"unknown check '{check}'")
    t0 = time.monotonic()
    v = CHECKS[kind](tree, arg, mutant)
    v.seconds = time.monotonic() - t0
    return v


# ---------------------------------------------------------------------------
# Applying a mutant
# ---------------------------------------------------------------------------

def apply(tree: Path, m: Mutant) -> dict[Path, str]:
    """Applies every edit of m; returns the original text of each file."""
    originals: dict[Path, str] = {}
    for rel, old, new in m.edits:
        p = tree / rel
        text = p.read_text()
        originals.setdefault(p, text)
        count = text.count(old)
        if count != 1:
            restore(originals)
            raise Stop(f"mutant {m.name}: the edit of {rel} no longer applies: the text to replace occurs {count} "
                       f"times (once expected); the source changed, so mend the mutant in scripts/mutate.py:\n"
                       f"  {old!r}")
        p.write_text(text.replace(old, new))
    return originals


def restore(originals: dict[Path, str]) -> None:
    for p, text in originals.items():
        p.write_text(text)


def fmt_s(s: float) -> str:
    return f"{s:.0f} s" if s < 120 else f"{s / 60:.1f} min"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--smoke", action="store_true", help="the fast subset of `make test`, without the baseline")
    ap.add_argument("--only", default="", help="comma-separated mutant names")
    ap.add_argument("--list", action="store_true", help="list the mutants and their checks")
    ap.add_argument("--out", default=str(ROOT / "build" / "mutate"), help="work folder (default build/mutate)")
    ap.add_argument("--model-build", default=str(ROOT / "build" / "model"),
                    help="the project's model build, for pluecker_py (default build/model)")
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args()

    chosen = [m for m in MUTANTS if m.smoke] if a.smoke else list(MUTANTS)
    if a.only:
        names = [n.strip() for n in a.only.split(",") if n.strip()]
        unknown = [n for n in names if n not in {m.name for m in MUTANTS}]
        if unknown:
            print(f"mutate: unknown mutant(s) {', '.join(unknown)} (--list names them)", file=sys.stderr)
            return 2
        chosen = [m for m in MUTANTS if m.name in names]
    if a.list:
        for m in chosen:
            print(f"{m.name:32s} {m.what}\n{'':32s}   checks: {', '.join(m.checks)}")
        return 0

    t_start = time.monotonic()
    tree = Tree(Path(a.out).resolve() / "tree", Path(a.model_build).resolve(), a.jobs)
    try:
        sync_tree(tree.dir)
        if not a.smoke:
            checks = list(dict.fromkeys(c for m in chosen for c in m.checks))
            print(f"mutate: baseline: {len(checks)} checks on the unmodified copy", flush=True)
            for c in checks:
                v = run_check(tree, c, None)
                print(f"mutate:   {c}: {v.state} ({fmt_s(v.seconds)})", flush=True)
                if v.state != "pass":
                    raise Stop(f"check {c} does not pass on the unmodified tree, so it cannot tell a mutant:\n"
                               f"{v.detail}")
        rows, survived = [], []
        for m in chosen:
            originals = apply(tree.dir, m)
            try:
                t0 = time.monotonic()
                results = [(c, run_check(tree, c, m)) for c in m.checks]
            finally:
                restore(originals)
            for c, v in results:
                if v.state == "error":
                    raise Stop(f"mutant {m.name}, check {c}: {v.detail}")
            missed = [c for c, v in results if v.state != "caught"]
            if missed:
                survived.append(m.name)
            rows.append((m, results, time.monotonic() - t0))
            verdict = "SURVIVED " + ", ".join(missed) if missed else "caught"
            print(f"mutate: {m.name}: {verdict} ({fmt_s(time.monotonic() - t0)})", flush=True)
            for c, v in results:
                print(f"mutate:   {c}: {v.state}{': ' + v.detail if v.detail else ''} ({fmt_s(v.seconds)})",
                      flush=True)
    except Stop as e:
        print(f"mutate: error: {e}", file=sys.stderr)
        return 2

    print("\n| mutant | caught by | time |\n|---|---|---:|")
    for m, results, secs in rows:
        by = "; ".join(f"`{c}`" + ("" if v.state == "caught" else " **missed**") for c, v in results)
        print(f"| {m.name} | {by} | {fmt_s(secs)} |")
    total = time.monotonic() - t_start
    print(f"\nmutate: {len(rows)} mutants, {len(rows) - len(survived)} caught, {len(survived)} survived "
          f"({fmt_s(total)} in all{', baseline included' if not a.smoke else ''})")
    if survived:
        print(f"mutate: FAIL: survived: {', '.join(survived)}", file=sys.stderr)
        return 1
    print("mutate: PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
