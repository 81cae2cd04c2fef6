# SPDX-License-Identifier: MIT
"""The local frames through the binding (pluecker_py): bad arguments raise
InputError naming what is wrong, the local port contract agrees with the
generated table the scripts read (rtl/pluecker_local_contract.json through
scripts/contract.py) at every configuration, and the model's pieces fit
together as the benches use them (the float convenience local_hit is the
set-up, frame, quantisation, node ray and child datapath in a row; the
port packing round-trips through the contract's fields).
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

pp = pytest.importorskip("pluecker_py")

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "scripts"))
import contract  # noqa: E402  (scripts/contract.py)

STYLES = ("auto", "dsp", "lut")


def test_local_limits_agree():
    lim = contract.local_limits()
    assert pp.LocalPortContract.MAX_GRID_BITS == lim["max_grid_bits"]
    assert pp.LocalPortContract.MAX_CHILDREN == lim["children"][1]
    d = contract.load(contract.LOCAL_CONTRACT_JSON)["defaults"]
    c = pp.LocalPortContract()
    assert (c.box_bits, c.dir_bits, c.grid_bits, c.tag_bits, int(c.conservative), pp.mul_style_name(c.mul_style),
            c.children) == (d["box_bits"], d["dir_bits"], d["grid_bits"], d["tag_bits"], d["conservative"],
                            d["mul_style"], d["children"])
    f = pp.LocalFormat()
    assert (f.box_bits, f.dir_bits, f.grid_bits) == (d["box_bits"], d["dir_bits"], d["grid_bits"])


def test_local_classes_agree():
    table = contract.local_classes()
    binding = pp.local_contract_classes()
    assert len(table) == len(binding)
    for t, b in zip(table, binding):
        assert {k: (list(v) if isinstance(v, tuple) else v) for k, v in b.items()} == t


def test_every_local_configuration_has_the_row_of_the_table():
    lim = contract.local_limits()
    n = 0
    for k in range(lim["box_bits"][0], lim["box_bits"][1] + 1):
        for d in range(lim["dir_bits"][0], lim["dir_bits"][1] + 1):
            for g in range(k, lim["max_grid_bits"] + 2):
                for style in STYLES:
                    for ch in (1, 2):
                        try:
                            row = contract.local_row(k, d, g, style, ch)
                        except contract.ContractError:
                            with pytest.raises(pp.InputError):
                                pp.LocalPortContract(k, d, g, mul_style=style, children=ch)
                            continue
                        pc = pp.LocalPortContract(k, d, g, mul_style=style, children=ch)
                        got = ("lut" if pc.frame_fabric else "dsp", "lut" if pc.child_fabric else "dsp",
                               pc.frame_mul_add, pc.child_mul_add, pc.latency, pc.fifo_depth, pc.frame_dsp_blocks,
                               pc.child_dsp_blocks, pc.dsp_blocks)
                        assert got == tuple(row[key] for key in (*contract.LOCAL_ROW_KEYS, "mult18x18d")), \
                            (k, d, g, style, ch)
                        n += 1
    assert n > 10000


@pytest.mark.parametrize("kwargs, part", [
    ({"box_bits": 3}, "BOX_BITS = 3"),
    ({"dir_bits": 25}, "DIR_BITS = 25"),
    ({"grid_bits": 33}, "GRID_BITS = 33"),
    ({"box_bits": 12, "grid_bits": 13}, "GRID_BITS = 13"),
    ({"tag_bits": 0}, "TAG_BITS = 0"),
    ({"children": 3}, "CHILDREN = 3"),
    ({"mul_style": "fast"}, "fast"),
])
def test_local_contract_refuses(kwargs, part):
    with pytest.raises(pp.InputError, match=part):
        pp.LocalPortContract(**kwargs)


@pytest.mark.parametrize("kwargs, part", [
    ({"box_bits": 17}, "BOX_BITS = 17"),
    ({"dir_bits": 3}, "DIR_BITS = 3"),
    ({"grid_bits": 49}, "GRID_BITS = 49"),
    ({"mode": "exact"}, "exact"),
])
def test_local_format_refuses(kwargs, part):
    with pytest.raises(pp.InputError, match=part):
        pp.LocalFormat(**kwargs)


FMT = pp.LocalFormat(4, 7, 6)  # grid -32..31, exponents 0..3, boxes 0..15


def test_frame_and_box_checks():
    ray = pp.LocalRay(0, [0, 0, 0], [32, 0, 0])
    with pytest.raises(pp.InputError, match="frame exponent y = 4 is outside 0..3"):
        pp.local_node_ray(ray, pp.LocalFrame([0, 0, 0], [0, 4, 0]), FMT)
    with pytest.raises(pp.InputError, match="frame origin z = 40"):
        pp.local_node_ray(ray, pp.LocalFrame([0, 0, 40], [0, 0, 0]), FMT)
    nr = pp.local_node_ray(ray, pp.LocalFrame(), FMT)
    with pytest.raises(pp.InputError, match="box y offset 16 is outside 0..15"):
        pp.local_hit(nr, pp.LocalBox([0, 0, 0], [0, 16, 0]), FMT)
    with pytest.raises(pp.InputError, match="does not fit the frame"):
        pp.local_quantize_box(pp.Box((0, 0, 0), (1.5, 0.1, 0.1)), pp.LocalFrame([0, 0, 0], [0, 0, 0]), FMT)
    with pytest.raises(pp.InputError, match="outside the local format's range"):
        pp.local_frame_for(pp.Box((0, 0, 0), (2.5, 0.1, 0.1)), FMT)


@pytest.mark.parametrize("ray, part", [
    (pp.LocalRay(0, [32, 0, 0], [32, 0, 0]), "ray origin x = 32 does not fit GRID_BITS = 6"),
    (pp.LocalRay(0, [0, 0, 0], [32, 33, 0]), "ray direction y = 33 is outside 0..32"),
    (pp.LocalRay(0, [0, 0, 0], [31, 7, 0]), "largest component is 31"),
    (pp.LocalRay(0, [0, 0, 0], [32, 0, 0], [0, -33, 0], True), "ray end y = -33"),
])
def test_node_ray_refuses_rays_outside_the_contract(ray, part):
    with pytest.raises(pp.InputError, match=part):
        pp.local_node_ray(ray, pp.LocalFrame(), FMT)


def test_node_ray_fields_checked_against_their_ports():
    box = pp.LocalBox()
    with pytest.raises(pp.InputError, match="node ray DIR x = 128 does not fit 7 bits"):
        pp.local_hit(pp.LocalNodeRay(0, [128, 0, 0]), box, FMT)
    with pytest.raises(pp.InputError, match="node ray W3 = 4096 does not fit 13 bits signed"):
        pp.local_hit(pp.LocalNodeRay(0, [1, 0, 0], [0, 0, 0, 4096, 0, 0]), box, FMT)
    with pytest.raises(pp.InputError, match="node ray ORG y = -33 does not fit 6 bits signed"):
        pp.local_hit(pp.LocalNodeRay(0, [1, 0, 0], [0] * 6, [0, -33, 0]), box, FMT)
    with pytest.raises(pp.InputError, match="ray class 9"):
        pp.LocalNodeRay(9)


def test_setup_rejects_bad_rays():
    with pytest.raises(pp.InputError):
        pp.local_setup_ray(pp.Ray((0, 0, 0), (0, 0, 0)), FMT)
    with pytest.raises(pp.InputError):
        pp.local_setup_ray(pp.Ray((float("nan"), 0, 0), (1, 0, 0)), FMT)
    assert pp.local_setup_ray(pp.Ray((5, 5, 5), (1, 0, 0)), FMT) is None  # never meets the range


def test_float_convenience_is_the_pieces_in_a_row():
    fmt = pp.LocalFormat(8, 11, 32)
    for q in pp.random_queries(5, 300) + pp.extreme_queries(6, 300):
        try:
            frame = pp.local_frame_for(q.box, fmt)
        except pp.InputError:
            continue
        box = pp.local_quantize_box(q.box, frame, fmt)
        ray = pp.local_setup_ray(q.ray, fmt)
        pieces = ray is not None and pp.local_hit(pp.local_node_ray(ray, frame, fmt), box, fmt)
        assert pieces == pp.local_hit(q.ray, q.box, fmt), q.line()


def test_rtl_ports_pack_the_contract_fields():
    c = pp.LocalPortContract(4, 7, 6, children=2)
    ray = pp.LocalRay(5, [1, -1, 0], [32, 3, 0], [2, 0, -32], True)
    frame = pp.LocalFrame([-1, 2, 3], [3, 0, 1])
    boxes = [pp.LocalBox([1, 2, 3], [4, 5, 6]), pp.LocalBox([15, 0, 7], [0, 15, 8])]
    p = c.rtl_ports(ray, frame, boxes)
    assert p["ray_class_i"] == 5
    assert p["ray_org_i"] == 1 | (63 << 6)
    assert p["ray_dir_i"] == 32 | (3 << 6)
    assert p["ray_end_i"] == 2 | (32 << 12) and p["ray_end_valid_i"] == 1
    assert p["frame_org_i"] == 63 | (2 << 6) | (3 << 12)
    assert p["frame_exp_i"] == 3 | (0 << 2) | (1 << 4)
    assert p["box_min_i"] == 1 | (2 << 4) | (3 << 8) | (15 << 12) | (0 << 16) | (7 << 20)
    assert p["box_max_i"] == 4 | (5 << 4) | (6 << 8) | (0 << 12) | (15 << 16) | (8 << 20)
    with pytest.raises(pp.InputError, match="1 boxes for CHILDREN = 2"):
        c.rtl_ports(ray, frame, boxes[:1])


def test_render_queries_are_the_traversal():
    fmt = pp.LocalFormat(8, 11, 32)
    qs = pp.local_render_queries("teapot", 8, fmt, limit=500)
    assert len(qs) == 500
    ray, frame, box, node = qs[0]
    assert node == 0  # the root first
    for ray, frame, box, node in qs:
        pp.local_hit(pp.local_node_ray(ray, frame, fmt), box, fmt)  # every operand inside the contract
    with pytest.raises(pp.InputError, match="frames must be"):
        pp.local_render_queries("teapot", 8, fmt, frames="none")


def test_local_pair_order():
    """Edge test k's axes: every ordered pair of distinct axes once, tests
    2m and 2m + 1 sharing axis i = m, anything outside 0..5 refused."""
    pairs = [pp.local_pair(k) for k in range(6)]
    assert sorted(pairs) == sorted((i, j) for i in range(3) for j in range(3) if i != j)
    for k in range(0, 6, 2):
        assert pairs[k][0] == pairs[k + 1][0] and pairs[k][1] != pairs[k + 1][1]
    for k in (-1, 6):
        with pytest.raises(pp.InputError, match="outside 0..5"):
            pp.local_pair(k)
