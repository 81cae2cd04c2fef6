"""Floorplans for whole-chip runs on the LFE5U-85F.

dsp: each unit's MULT18X18D blocks side by side, so that the placer can
put the unit's fabric next to all of them.

grid: each unit without MULT18X18D (fabric or table multipliers) gets a
region of a grid over the logic tiles, and a few of its flip-flops are
pinned at the region's centre (`anchor_units`). Nothing else of the unit
is pinned: the anchors only give each unit a place of its own. Without
them every unit of a chip of independent lanes has the same quadratic
solution, and HeAP spreads them from one point into each other.

Left alone, nextpnr's placer spreads a unit's twelve MULT18X18D along the
DSP rows, and the fabric that feeds and reads them cannot be near all of
them (fpga/TIMING.md, "DSP floorplan"). `pin_units` gives every
MULT18X18D of a Yosys netlist a BEL attribute (nextpnr places such cells
first, where they are told): the blocks of one unit take consecutive
sites in a snake order over the device's three DSP rows (left to right,
right to left, left to right), and units of different kinds (e.g. the
wide units of cascades and plain units) are spread evenly over the rows.
`apply` does both floorplans' steps in one read and one write of the
netlist (scripts/synth.py calls it).

A unit is the hierarchy above the intersector's product generate blocks
(`<unit>.g_mul[i]...`, or `<unit>.g_pair...` where one block does two
products); a MULT18X18D elsewhere is refused by name.
"""
from __future__ import annotations

import json
import math
import re
from collections import defaultdict
from pathlib import Path

# LFE5U-85F MULT18X18D sites as nextpnr-ecp5 names them, read from the
# placement of a design with 156 multipliers: three DSP rows (tile Y 10, 34,
# 58), 13 DSP slices per row, each slice with four multipliers at X, X+1
# (MULT18_0, MULT18_1) and X+4, X+5 (MULT18_4, MULT18_5).
DSP_ROWS_85F = (10, 34, 58)
DSP_SLICE_X_85F = (4, 13, 22, 31, 40, 49, 58, 69, 78, 87, 96, 105, 114)
_SLICE = ((0, 0), (1, 1), (4, 4), (5, 5))  # (X offset, MULT18_<n>)


# LFE5U-85F logic (PLC) tiles as nextpnr-ecp5 names their slices: columns
# 2-124, rows 2-93 except the block-RAM and DSP rows (every twelfth from 10),
# found by pinning flip-flops to every column and row.
PLC_X_85F = tuple(range(2, 125))
PLC_Y_85F = tuple(y for y in range(2, 94) if (y - 10) % 12)
PLC_W_85F = len(PLC_X_85F)  # the span of the logic tiles, in tiles
PLC_H_85F = PLC_Y_85F[-1] - PLC_Y_85F[0] + 1
ANCHORS = 4  # flip-flops a unit pinned at its region's centre (grid), one a slice of its tile


class FloorplanError(ValueError):
    pass


def dsp_sites() -> list[str]:
    """Every MULT18X18D site of the LFE5U-85F, in snake order: row by row,
    every other row right to left, so consecutive sites are neighbours."""
    order = []
    for i, y in enumerate(DSP_ROWS_85F):
        row = [(x + dx, f"X{x + dx}/Y{y}/MULT18_{n}") for x in DSP_SLICE_X_85F for dx, n in _SLICE]
        row.sort(reverse=bool(i % 2))
        order += [name for _, name in row]
    return order


def _natural(s: str) -> list:
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", s)]


# The intersector's product generate blocks: one MULT18X18D a product
# (g_mul[k]) or two products a block (g_pair, rtl/pluecker_mul_pair.sv).
_PRODUCT_BLOCK = re.compile(r"\.g_(?:mul\[|pair\.)")


def unit_of(name: str) -> str:
    """The unit of a MULT18X18D cell: its name up to the last product
    block."""
    m = None
    for m in _PRODUCT_BLOCK.finditer(name):
        pass
    if m is None or m.start() <= 0:
        raise FloorplanError(f"MULT18X18D '{name}' is not in an intersector's product block "
                             "('<unit>.g_mul[i]' or '<unit>.g_pair'): no unit to place it with")
    return name[:m.start()]


def unit_groups(names: list[str]) -> dict[str, list[str]]:
    """MULT18X18D cell names grouped by unit (the hierarchy above
    '.g_mul[' or '.g_pair.'), each group in natural order."""
    groups: dict[str, list[str]] = defaultdict(list)
    for n in names:
        groups[unit_of(n)].append(n)
    return {g: sorted(cells, key=_natural) for g, cells in sorted(groups.items(), key=lambda kv: _natural(kv[0]))}


def unit_order(groups: list[str]) -> list[str]:
    """The units in placement order: each kind (the name with its indices
    removed) spread evenly, so that e.g. 4 cascades among 13 units land at
    every third or fourth slot rather than side by side."""
    kinds: dict[str, list[str]] = defaultdict(list)
    for g in groups:
        kinds[re.sub(r"\[\d+\]", "[]", g)].append(g)
    keyed = [((i + 0.5) / len(gs), k, g) for k, gs in kinds.items() for i, g in enumerate(gs)]
    return [g for _, _, g in sorted(keyed)]


def assign(names: list[str]) -> dict[str, str]:
    """MULT18X18D cell name -> site (BEL name), units on consecutive sites."""
    sites = dsp_sites()
    if len(names) > len(sites):
        raise FloorplanError(f"{len(names)} MULT18X18D, the LFE5U-85F has {len(sites)}")
    groups = unit_groups(names)
    out: dict[str, str] = {}
    for g in unit_order(list(groups)):
        for n in groups[g]:
            out[n] = sites[len(out)]
    return out


def _read(netlist: Path, top: str) -> tuple[dict, dict]:
    """A Yosys netlist and its top module's cells."""
    with open(netlist) as f:
        data = json.load(f)
    if top not in data.get("modules", {}):
        raise FloorplanError(f"{netlist}: no module '{top}'")
    return data, data["modules"][top]["cells"]


def _write(netlist: Path, data: dict) -> None:
    with open(netlist, "w") as f:
        json.dump(data, f)


def pin_dsp(cells: dict) -> dict[str, list[str]]:
    """A BEL attribute on every MULT18X18D of the cells; each unit's first
    and last site."""
    sites = assign([n for n, c in cells.items() if c["type"] == "MULT18X18D"])
    for n, site in sites.items():
        cells[n].setdefault("attributes", {})["BEL"] = site
    spans: dict[str, list[str]] = {}
    for n, site in sites.items():
        spans.setdefault(unit_of(n), [site, site])[1] = site
    return spans


def pin_units(netlist: Path, top: str) -> dict[str, list[str]]:
    """Writes a BEL attribute on every MULT18X18D of the netlist's top
    module (in place); returns each unit's first and last site."""
    data, cells = _read(netlist, top)
    spans = pin_dsp(cells)
    _write(netlist, data)
    return spans


# --- grid: anchors for units without MULT18X18D ---------------------------

_ARRAY_UNIT = re.compile(r"^(.*?\.g_unit\[\d+\]\.u_unit)\.")


def array_unit_of(name: str) -> str | None:
    """The array unit ('<...>.g_unit[i].u_unit') a cell belongs to, or
    None for the harness and the array's own cells."""
    m = _ARRAY_UNIT.match(name)
    return m.group(1) if m else None


def grid_shape(n: int) -> tuple[int, int]:
    """Columns and rows of a grid of at least n regions over the logic
    tiles, the shape that minimises |log(a region's width / height)| + 2 x
    (empty regions) / n: square regions, few of them empty (20 and 17
    units both take 5 x 4 regions; 17 x 1 would be too narrow)."""
    if n < 1:
        raise FloorplanError(f"a grid of {n} regions")
    w, h = PLC_W_85F, PLC_H_85F
    best = None
    for cols in range(1, min(n, w) + 1):
        rows = -(-n // cols)
        if rows > h:
            continue
        cost = abs(math.log((w / cols) / (h / rows))) + 2.0 * (cols * rows - n) / n
        if best is None or cost < best[0] - 1e-12:
            best = (cost, (cols, rows))
    if best is None:
        raise FloorplanError(f"{n} regions do not fit the LFE5U-85F's logic tiles")
    return best[1]


def _snap_row(y: float) -> int:
    return min(PLC_Y_85F, key=lambda r: (abs(r - y), r))


def grid_centres(n: int) -> list[tuple[int, int]]:
    """The centre tiles (X, Y) of n regions, row by row, every other row
    right to left (neighbouring units in neighbouring regions); each centre
    on a logic row."""
    cols, rows = grid_shape(n)
    x0, w = PLC_X_85F[0], PLC_W_85F
    y0, h = PLC_Y_85F[0], PLC_H_85F
    out = []
    for r in range(rows):
        xs = [x0 + int((c + 0.5) * w / cols) for c in range(cols)]
        if r % 2:
            xs.reverse()
        y = _snap_row(y0 + (r + 0.5) * h / rows)
        out += [(x, y) for x in xs]
    return out[:n]


def anchor_cells(ffs: list[str], k: int = ANCHORS) -> list[str]:
    """k of a unit's flip-flops, evenly spaced in natural name order, so
    that the anchors come from different parts of the unit."""
    if len(ffs) < k:
        raise FloorplanError(f"{len(ffs)} flip-flops in a unit, {k} anchors wanted")
    ordered = sorted(ffs, key=_natural)
    return [ordered[(2 * i + 1) * len(ordered) // (2 * k)] for i in range(k)]


def _plain_copy(cell: dict, ff_q: set) -> bool:
    """A flip-flop loaded from a flip-flop, with no set/reset or clock
    enable signal. nextpnr refuses the BEL of one that a CCU2C or LUT4
    feeds (it packs the two together) and, as measured on the 20 x 8/8
    chip, of one with a set/reset signal; clock enables are left out too."""
    conn = cell["connections"]
    if not conn.get("DI") or not set(conn["DI"]) <= ff_q:
        return False
    return all(isinstance(b, str) for port in ("LSR", "CE") for b in conn.get(port, []))  # constants only


def anchor(cells: dict, k: int = ANCHORS) -> dict[str, str]:
    """A BEL attribute on k flip-flops of each array unit without
    MULT18X18D, the unit's anchors at the centre tile of its grid region
    (one a slice, SLICEA-D FF0); each unit's tile. The anchors are plain
    register-to-register flip-flops (pipeline copies), which nextpnr
    places on their own."""
    if not 1 <= k <= 4:
        raise FloorplanError(f"{k} anchors a unit: 1 to 4 (one a slice of the centre tile)")
    ff_q = {bit for c in cells.values() if c["type"] == "TRELLIS_FF" for bit in c["connections"].get("Q", [])}
    ffs: dict[str, list[str]] = defaultdict(list)
    every, with_dsp = set(), set()
    for n, c in cells.items():
        u = array_unit_of(n)
        if u is None:
            continue
        every.add(u)
        if c["type"] == "TRELLIS_FF" and _plain_copy(c, ff_q):
            ffs[u].append(n)
        elif c["type"] == "MULT18X18D":
            with_dsp.add(u)
    units = sorted(every - with_dsp, key=_natural)
    if not units:
        raise FloorplanError("no array unit without MULT18X18D ('<...>.g_unit[i].u_unit') to anchor; "
                             "--floorplan dsp pins the MULT18X18D of the others")
    tiles: dict[str, str] = {}
    for u, (x, y) in zip(units, grid_centres(len(units))):
        if len(ffs[u]) < k:
            raise FloorplanError(f"unit '{u}' has {len(ffs[u])} register-to-register flip-flops without "
                                 f"set/reset or enable, {k} anchors wanted")
        for slot, n in zip("ABCD", anchor_cells(ffs[u], k)):
            cells[n].setdefault("attributes", {})["BEL"] = f"X{x}/Y{y}/SLICE{slot}.FF0"
        tiles[u] = f"X{x}/Y{y}"
    return tiles


def anchor_units(netlist: Path, top: str, k: int = ANCHORS) -> dict[str, str]:
    """Writes the anchors of `anchor` into the netlist's top module (in
    place); returns each anchored unit's tile."""
    data, cells = _read(netlist, top)
    tiles = _anchor_named(netlist, cells, k)
    _write(netlist, data)
    return tiles


def _anchor_named(netlist: Path, cells: dict, k: int = ANCHORS) -> dict[str, str]:
    """anchor, its errors naming the netlist."""
    try:
        return anchor(cells, k)
    except FloorplanError as e:
        raise FloorplanError(f"{netlist}: {e}") from None


def apply(netlist: Path, top: str, grid: bool) -> dict:
    """One read and one write of the netlist for a whole floorplan: the
    MULT18X18D pinned (if there are any; summary key dsp_sites) and, with
    grid, the other units anchored (anchor_tiles)."""
    data, cells = _read(netlist, top)
    out: dict = {}
    if any(c["type"] == "MULT18X18D" for c in cells.values()):
        out["dsp_sites"] = pin_dsp(cells)
    if grid:
        out["anchor_tiles"] = _anchor_named(netlist, cells)
    _write(netlist, data)
    return out
