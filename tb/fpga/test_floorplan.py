# SPDX-License-Identifier: MIT
"""scripts/floorplan.py: the LFE5U-85F's MULT18X18D sites and how a chip's
units are put on them (--floorplan dsp), and the grid of anchors for units
without them (--floorplan grid). Pure Python, no tools; the smoke
run in test_synth_smoke.py checks that nextpnr takes the site names."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "scripts"))
import floorplan  # noqa: E402  (scripts/floorplan.py)


def _xy(site: str) -> tuple[int, int]:
    m = re.fullmatch(r"X(\d+)/Y(\d+)/MULT18_[0145]", site)
    assert m, site
    return int(m.group(1)), int(m.group(2))


def _unit_cells(prefix: str, products: int = 6) -> list[str]:
    """The twelve MULT18X18D of one 16/16 unit as Yosys names them."""
    return [f"{prefix}.g_mul[{j}].g_dsp.u_mul_{ab}.g_dsp[0].g_used.u_mult.u_block"
            for j in range(products) for ab in "ab"]


def test_sites_snake_order():
    sites = floorplan.dsp_sites()
    assert len(sites) == len(set(sites)) == 156
    xy = [_xy(s) for s in sites]
    assert sorted({y for _, y in xy}) == list(floorplan.DSP_ROWS_85F)
    for (x0, y0), (x1, y1) in zip(xy, xy[1:]):
        # neighbours: the next site in the same row (at most one slice gap),
        # or straight below at a row change
        assert (y0 == y1 and 0 < abs(x1 - x0) <= 6) or (x0 == x1 and y1 > y0), (x0, y0, x1, y1)


def test_units_consecutive_and_kinds_spread():
    # a chip of 4 cascades' wide units and 9 plain units: 156 blocks
    names = [c for i in range(4) for c in _unit_cells(f"g_cascade[{i}].u_dut.u_wide")]
    names += [c for k in range(9) for c in _unit_cells(f"g_wide.u_wide.g_unit[{k}].u_unit")]
    sites = floorplan.assign(names)
    assert sorted(sites) == sorted(names) and len(set(sites.values())) == 156
    index = {s: i for i, s in enumerate(floorplan.dsp_sites())}
    starts = {}
    for unit in [f"g_cascade[{i}].u_dut.u_wide" for i in range(4)] + \
                [f"g_wide.u_wide.g_unit[{k}].u_unit" for k in range(9)]:
        idx = sorted(index[sites[c]] for c in _unit_cells(unit))
        assert idx == list(range(idx[0], idx[0] + 12)), (unit, idx)  # one run of sites
        assert idx[0] % 12 == 0
        starts[unit] = idx[0] // 12
    slots = sorted(starts[f"g_cascade[{i}].u_dut.u_wide"] for i in range(4))
    assert min(b - a for a, b in zip(slots, slots[1:])) >= 3, slots  # cascades spread, not side by side


def test_refused():
    with pytest.raises(floorplan.FloorplanError, match="u_dut.u_other.u_mult"):
        floorplan.assign(_unit_cells("u_dut.g_unit[0].u_unit") + ["u_dut.u_other.u_mult"])
    too_many = [c for k in range(14) for c in _unit_cells(f"u_dut.g_unit[{k}].u_unit")]
    with pytest.raises(floorplan.FloorplanError, match="168 MULT18X18D"):
        floorplan.assign(too_many)


def test_pin_units_writes_bel(tmp_path):
    cells = {n: {"type": "MULT18X18D", "attributes": {"src": "x.sv:1"}}
             for k in range(2) for n in _unit_cells(f"u_dut.g_unit[{k}].u_unit")}
    cells["ff"] = {"type": "TRELLIS_FF", "attributes": {}}
    path = tmp_path / "netlist.json"
    path.write_text(json.dumps({"modules": {"top": {"cells": cells}}}))
    spans = floorplan.pin_units(path, "top")
    out = json.loads(path.read_text())["modules"]["top"]["cells"]
    sites = floorplan.dsp_sites()
    assert [out[n]["attributes"]["BEL"] for n in _unit_cells("u_dut.g_unit[0].u_unit")] == sites[:12]
    assert [out[n]["attributes"]["BEL"] for n in _unit_cells("u_dut.g_unit[1].u_unit")] == sites[12:24]
    assert out["u_dut.g_unit[0].u_unit.g_mul[0].g_dsp.u_mul_a.g_dsp[0].g_used.u_mult.u_block"]["attributes"]["src"] == "x.sv:1"
    assert "BEL" not in out["ff"]["attributes"]
    assert spans == {"u_dut.g_unit[0].u_unit": [sites[0], sites[11]],
                     "u_dut.g_unit[1].u_unit": [sites[12], sites[23]]}
    with pytest.raises(floorplan.FloorplanError, match="no module 'other'"):
        floorplan.pin_units(path, "other")


def test_paired_units_grouped():
    # 6/6 units with two products a block (rtl/pluecker_mul_pair.sv): six
    # MULT18X18D under <unit>.g_pair; 26 such units fill the 156 sites.
    def paired(prefix: str) -> list[str]:
        return [f"{prefix}.g_pair.g_axis[{i}].u_mul_{ab}.u_mult.u_block" for i in range(3) for ab in "ab"]

    names = [c for k in range(26) for c in paired(f"u_dut.g_unit[{k}].u_unit")]
    sites = floorplan.assign(names)
    assert len(set(sites.values())) == 156
    index = {s: i for i, s in enumerate(floorplan.dsp_sites())}
    for k in range(26):
        idx = sorted(index[sites[c]] for c in paired(f"u_dut.g_unit[{k}].u_unit"))
        assert idx == list(range(6 * k, 6 * k + 6)), (k, idx)
    assert floorplan.unit_of("u_dut.g_unit[3].u_unit.g_pair.g_axis[1].u_mul_b.u_mult.u_block") == "u_dut.g_unit[3].u_unit"
    with pytest.raises(floorplan.FloorplanError, match="g_pairx"):
        floorplan.assign(["u_dut.g_pairx.u_mult"])


# --- grid: anchors for units without MULT18X18D ---------------------------

def test_grid_shape():
    assert floorplan.grid_shape(1) == (1, 1)
    for n in (2, 3, 4, 17, 20, 22, 38, 47, 100):
        cols, rows = floorplan.grid_shape(n)
        assert n <= cols * rows < n + max(cols, rows), (n, cols, rows)  # no empty row or column
        # regions no more than twice as long as wide on the die's logic tiles
        w = floorplan.PLC_W_85F / cols
        h = floorplan.PLC_H_85F / rows
        assert n < 4 or 0.5 <= w / h <= 2.0, (n, cols, rows, w, h)
    assert floorplan.grid_shape(20) == (5, 4)
    assert floorplan.grid_shape(17) == (5, 4)  # not 17 x 1
    with pytest.raises(floorplan.FloorplanError, match="0 regions"):
        floorplan.grid_shape(0)


def test_grid_centres_on_logic_tiles():
    for n in (1, 5, 20, 38):
        cs = floorplan.grid_centres(n)
        assert len(cs) == len(set(cs)) == n
        for x, y in cs:
            assert x in floorplan.PLC_X_85F and y in floorplan.PLC_Y_85F, (n, x, y)
    assert 10 not in floorplan.PLC_Y_85F and 58 not in floorplan.PLC_Y_85F  # DSP rows
    # snake order: consecutive regions are neighbours (same row, or the row below at its end)
    cs = floorplan.grid_centres(20)
    for (x0, y0), (x1, y1) in zip(cs, cs[1:]):
        assert (y0 == y1) != (x0 == x1), (x0, y0, x1, y1)


def _unit_ffs(prefix: str, n: int = 40) -> list[str]:
    return [f"{prefix}.g_mul[{k % 6}].v_TRELLIS_FF_Q_{k}" for k in range(n)]


def test_anchor_cells_spread():
    ffs = _unit_ffs("u")
    a = floorplan.anchor_cells(ffs, 4)
    assert len(set(a)) == 4 and set(a) <= set(ffs)
    assert len({c.split(".")[1] for c in a}) >= 3  # from different parts of the unit
    with pytest.raises(floorplan.FloorplanError, match="3 flip-flops in a unit, 4 anchors"):
        floorplan.anchor_cells(ffs[:3], 4)


def _ff(di: int, q: int) -> dict:
    return {"type": "TRELLIS_FF", "attributes": {}, "connections": {"CLK": [1], "DI": [di], "Q": [q]}}


def test_anchor_units_writes_bel(tmp_path):
    # each flip-flop k of a unit loads from its predecessor's Q (bits 100 + k)
    cells = {n: _ff(100 + i, 101 + i) for k in range(3)
             for i, n in enumerate(_unit_ffs(f"u_dut.g_unit[{k}].u_unit"))}
    # a unit with MULT18X18D is left to the DSP floorplan; harness flops are not anchored
    cells.update({n: _ff(100 + i, 101 + i) for i, n in enumerate(_unit_ffs("u_dut.g_unit[3].u_unit"))})
    cells["u_dut.g_unit[3].u_unit.g_mul[0].g_dsp.u_mult.u_block"] = {"type": "MULT18X18D", "attributes": {}}
    cells["g_lane[0].ooc_box_q_TRELLIS_FF_Q"] = _ff(99, 100)
    # flip-flops loaded from logic are never anchors (nextpnr clusters them with it),
    # nor copies with a set/reset signal (nextpnr refused their BEL)
    cells.update({f"u_dut.g_unit[{k}].u_unit.g_mul[{i % 6}].sum_TRELLIS_FF_Q_{i}": _ff(5000, 6000 + i)
                  for k in range(3) for i in range(120)})
    for k in range(3):
        for i in range(120):
            c = _ff(100, 7000 + i)
            c["connections"]["LSR"] = [4000]
            cells[f"u_dut.g_unit[{k}].u_unit.g_mul[{i % 6}].rst_sum_TRELLIS_FF_Q_{i}"] = c
    path = tmp_path / "netlist.json"
    path.write_text(json.dumps({"modules": {"top": {"cells": cells}}}))
    tiles = floorplan.anchor_units(path, "top")
    out = json.loads(path.read_text())["modules"]["top"]["cells"]
    centres = floorplan.grid_centres(3)
    assert tiles == {f"u_dut.g_unit[{k}].u_unit": f"X{x}/Y{y}" for k, (x, y) in enumerate(centres)}
    for k, (x, y) in enumerate(centres):
        bels = sorted(c["attributes"]["BEL"] for n, c in out.items()
                      if n.startswith(f"u_dut.g_unit[{k}].") and "BEL" in c["attributes"])
        assert bels == [f"X{x}/Y{y}/SLICE{s}.FF0" for s in "ABCD"]
    assert not any("BEL" in c["attributes"] for n, c in out.items()
                   if n.startswith("u_dut.g_unit[3].") or n.startswith("g_lane") or "sum_" in n)
    assert sum("BEL" in c["attributes"] for c in out.values()) == 12
    with pytest.raises(floorplan.FloorplanError, match="no array unit"):
        p2 = tmp_path / "empty.json"
        p2.write_text(json.dumps({"modules": {"top": {"cells": {"ff": _ff(1, 2)}}}}))
        floorplan.anchor_units(p2, "top")
    with pytest.raises(floorplan.FloorplanError, match="1 to 4"):
        floorplan.anchor_units(path, "top", k=5)
    # a unit whose flip-flops are all loaded from logic cannot be anchored: named
    p3 = tmp_path / "logic_only.json"
    p3.write_text(json.dumps({"modules": {"top": {"cells": {
        f"u_dut.g_unit[0].u_unit.sum_TRELLIS_FF_Q_{i}": _ff(5000, 6000 + i) for i in range(10)}}}}))
    with pytest.raises(floorplan.FloorplanError, match=r"unit 'u_dut.g_unit\[0\].u_unit' has 0 register-to-register"):
        floorplan.anchor_units(p3, "top")


def test_apply_pins_and_anchors_in_one_pass(tmp_path):
    # one DSP unit and two fabric units: grid pins the first's MULT18X18D
    # and anchors the others; dsp alone leaves the fabric units free
    cells = {n: {"type": "MULT18X18D", "attributes": {}} for n in _unit_cells("u_dut.g_unit[0].u_unit")}
    cells.update({n: _ff(100 + i, 101 + i) for k in (1, 2)
                  for i, n in enumerate(_unit_ffs(f"u_dut.g_unit[{k}].u_unit"))})
    path = tmp_path / "netlist.json"
    text = json.dumps({"modules": {"top": {"cells": cells}}})
    path.write_text(text)
    out = floorplan.apply(path, "top", grid=True)
    sites = floorplan.dsp_sites()
    assert out["dsp_sites"] == {"u_dut.g_unit[0].u_unit": [sites[0], sites[11]]}
    assert list(out["anchor_tiles"]) == ["u_dut.g_unit[1].u_unit", "u_dut.g_unit[2].u_unit"]
    written = json.loads(path.read_text())["modules"]["top"]["cells"]
    assert sum("BEL" in c["attributes"] for c in written.values()) == 12 + 2 * floorplan.ANCHORS
    path.write_text(text)
    assert list(floorplan.apply(path, "top", grid=False)) == ["dsp_sites"]
    written = json.loads(path.read_text())["modules"]["top"]["cells"]
    assert sum("BEL" in c["attributes"] for c in written.values()) == 12
