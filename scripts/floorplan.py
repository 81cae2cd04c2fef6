"""DSP floorplan for whole-chip runs: each unit's MULT18X18D blocks side by
side on the LFE5U-85F, so that the placer can put the unit's fabric next to
all of them.

Left alone, nextpnr's placer spreads a unit's twelve MULT18X18D along the
DSP rows, and the fabric that feeds and reads them cannot be near all of
them (fpga/TIMING.md, "DSP floorplan"). `pin_units` gives every
MULT18X18D of a Yosys netlist a BEL attribute (nextpnr places such cells
first, where they are told): the blocks of one unit take consecutive
sites in a snake order over the device's three DSP rows (left to right,
right to left, left to right), and units of different kinds (e.g. the
wide units of cascades and plain units) are spread evenly over the rows.

A unit is the hierarchy above the intersector's product generate blocks
(`<unit>.g_mul[i]...`, or `<unit>.g_pair...` where one block does two
products); a MULT18X18D elsewhere is refused by name.
"""
from __future__ import annotations

import json
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


def pin_units(netlist: Path, top: str) -> dict[str, list[str]]:
    """Writes a BEL attribute on every MULT18X18D of the netlist's top
    module (in place); returns each unit's first and last site."""
    with open(netlist) as f:
        data = json.load(f)
    if top not in data.get("modules", {}):
        raise FloorplanError(f"{netlist}: no module '{top}'")
    cells = data["modules"][top]["cells"]
    sites = assign([n for n, c in cells.items() if c["type"] == "MULT18X18D"])
    for n, site in sites.items():
        cells[n].setdefault("attributes", {})["BEL"] = site
    with open(netlist, "w") as f:
        json.dump(data, f)
    spans: dict[str, list[str]] = {}
    for n, site in sites.items():
        g = unit_of(n)
        spans.setdefault(g, [site, site])[1] = site
    return spans
