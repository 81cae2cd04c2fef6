#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The port contracts of rtl/pluecker_intersector.sv,
rtl/pluecker_local_intersector.sv and the binary32 units, for the scripts.

Reads rtl/pluecker_contract.json, rtl/pluecker_local_contract.json and
rtl/pluecker_contract_float.json, generated from the model's port contracts
(model/core/include/pluecker/contract.hpp, local_contract.hpp,
float_contract.hpp) by `pluecker contract --write rtl` and checked by the
tests Contract.GeneratedFilesAreCurrent,
LocalContract.GeneratedFilesAreCurrent and
FloatContract.GeneratedFilesAreCurrent. Nothing here derives a constant:
every value is looked up in a file's table of configuration classes. Used
by scripts/synth.py and scripts/report.py (import), scripts/lint.sh,
fpga/formal/run.sh and sim/build.sh (command line).

Command line (one answer a line, for shell scripts):
  contract.py limits                 "<min> <max>" widths (COORD_BITS, DIR_BITS)
  contract.py row C D [--mul-style S] [--pipeline P]
                                     key=value lines of the configuration's row
                                     (multiplier, mul_add, s2x_stages, latency,
                                     fifo_depth, mult18x18d, dp16kd); exit 2 if
                                     the RTL refuses the configuration
  contract.py classes                one class a line: coord_lo coord_hi dir_lo
                                     dir_hi mul_style pipeline multiplier mul_add
                                     s2x_stages latency fifo_depth mult18x18d
                                     dp16kd
  contract.py float UNIT [--mul-dsp M]
                                     key=value lines of a binary32 unit (float
                                     or smits): module, latency, fifo_depth,
                                     adders, multipliers, mult18x18d; exit 2 for
                                     an unknown unit or MUL_DSP
  contract.py float-limits           mul_dsp=<values> and default_mul_dsp=<M>
The local unit (rtl/pluecker_local_contract.json):
  contract.py local-limits           "<box min> <box max> <dir min> <dir max>
                                     <grid margin> <grid max> <children max>"
  contract.py local-row K D G [--mul-style S] [--children C]
                                     key=value lines of the row (LOCAL_ROW_KEYS)
                                     and mult18x18d, the unit's total; exit 2 if
                                     the RTL refuses the configuration
  contract.py local-classes          one class a line: dir_lo dir_hi grid_lo
                                     grid_hi mul_style and the LOCAL_ROW_KEYS values
Option --file PATH reads another copy of the table (of the fixed-point
contract, of the local contract for the local commands, of the float
contract for the float commands).
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CONTRACT_JSON = ROOT / "rtl" / "pluecker_contract.json"
FLOAT_CONTRACT_JSON = ROOT / "rtl" / "pluecker_contract_float.json"
ROW_KEYS = ("multiplier", "mul_add", "s2x_stages", "latency", "fifo_depth", "mult18x18d", "dp16kd")
LOCAL_CONTRACT_JSON = ROOT / "rtl" / "pluecker_local_contract.json"
LOCAL_ROW_KEYS = ("frame_multiplier", "child_multiplier", "frame_mul_add", "child_mul_add", "latency", "fifo_depth",
                  "frame_mult18x18d", "child_mult18x18d")


class ContractError(ValueError):
    """A configuration the RTL refuses (outside every class of the table)."""


_cache: dict[Path, dict] = {}


def load(path: Path | str | None = None) -> dict:
    p = Path(path) if path else CONTRACT_JSON
    if p not in _cache:
        with open(p) as f:
            _cache[p] = json.load(f)
    return _cache[p]


def limits(path: Path | str | None = None) -> tuple[int, int]:
    """(min, max) of COORD_BITS and DIR_BITS."""
    lo, hi = load(path)["limits"]["coord_bits"]
    return int(lo), int(hi)


def defaults(path: Path | str | None = None) -> dict:
    return dict(load(path)["defaults"])


def classes(path: Path | str | None = None) -> list[dict]:
    return list(load(path)["classes"])


def row(coord_bits: int, dir_bits: int, mul_style: str = "auto", pipeline: int = 0,
        path: Path | str | None = None) -> dict:
    """The class holding the configuration (a dict: coord_bits [lo, hi],
    dir_bits [lo, hi], mul_style, pipeline and the ROW_KEYS values)."""
    for k in classes(path):
        (clo, chi), (dlo, dhi) = k["coord_bits"], k["dir_bits"]
        if (clo <= coord_bits <= chi and dlo <= dir_bits <= dhi and k["mul_style"] == mul_style
                and k["pipeline"] == pipeline):
            return k
    raise ContractError(f"COORD_BITS={coord_bits} DIR_BITS={dir_bits} MUL_STYLE={mul_style} "
                        f"PIPELINE={pipeline} is in no class of the port contract ({CONTRACT_JSON.name})")


def local_limits(path: Path | str | None = None) -> dict:
    return dict(load(path or LOCAL_CONTRACT_JSON)["limits"])


def local_classes(path: Path | str | None = None) -> list[dict]:
    return list(load(path or LOCAL_CONTRACT_JSON)["classes"])


def local_row(box_bits: int, dir_bits: int, grid_bits: int, mul_style: str = "auto", children: int = 1,
              path: Path | str | None = None) -> dict:
    """The local unit's class holding the configuration, with "mult18x18d"
    (the node set-up's blocks plus CHILDREN times a child's) added."""
    lim = local_limits(path)
    ok = (lim["box_bits"][0] <= box_bits <= lim["box_bits"][1] and lim["dir_bits"][0] <= dir_bits <= lim["dir_bits"][1]
          and box_bits + lim["grid_margin"] <= grid_bits <= lim["max_grid_bits"]
          and lim["children"][0] <= children <= lim["children"][1])
    for k in local_classes(path) if ok else []:
        (dlo, dhi), (glo, ghi) = k["dir_bits"], k["grid_bits"]
        if dlo <= dir_bits <= dhi and glo <= grid_bits <= ghi and k["mul_style"] == mul_style:
            row = dict(k)
            row["mult18x18d"] = k["frame_mult18x18d"] + children * k["child_mult18x18d"]
            return row
    raise ContractError(f"BOX_BITS={box_bits} DIR_BITS={dir_bits} GRID_BITS={grid_bits} MUL_STYLE={mul_style} "
                        f"CHILDREN={children} is in no class of the local port contract ({LOCAL_CONTRACT_JSON.name})")


def float_contract(path: Path | str | None = None) -> dict:
    return load(path or FLOAT_CONTRACT_JSON)


def float_unit(unit: str, mul_dsp: int | None = None, path: Path | str | None = None) -> dict:
    """A binary32 unit's row: module, latency, fifo_depth, adders,
    multipliers, conservative (allowed values), mul_dsp and mult18x18d (for
    MUL_DSP = mul_dsp, default the contract's)."""
    fc = float_contract(path)
    m = fc["defaults"]["mul_dsp"] if mul_dsp is None else mul_dsp
    if m not in fc["limits"]["mul_dsp"]:
        raise ContractError(f"MUL_DSP={m} is not one of {fc['limits']['mul_dsp']} "
                            f"({FLOAT_CONTRACT_JSON.name})")
    for u in fc["units"]:
        if u["unit"] == unit:
            row = {k: v for k, v in u.items() if k not in ("mult18x18d", "ports")}
            row["mul_dsp"] = m
            row["mult18x18d"] = u["mult18x18d"][str(m)]
            return row
    raise ContractError(f"unit {unit!r} is not one of {[u['unit'] for u in fc['units']]} "
                        f"({FLOAT_CONTRACT_JSON.name})")


FLOAT_KEYS = ("module", "latency", "fifo_depth", "adders", "multipliers", "mul_dsp", "mult18x18d")


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--file", default=None, help="contract table (default rtl/pluecker_contract.json)")
    sub = p.add_subparsers(dest="cmd", required=True)
    sub.add_parser("limits")
    r = sub.add_parser("row")
    r.add_argument("coord_bits", type=int)
    r.add_argument("dir_bits", type=int)
    r.add_argument("--mul-style", default="auto")
    r.add_argument("--pipeline", type=int, default=0)
    sub.add_parser("classes")
    f = sub.add_parser("float")
    f.add_argument("unit")
    f.add_argument("--mul-dsp", type=int, default=None)
    sub.add_parser("float-limits")
    sub.add_parser("local-limits")
    lr = sub.add_parser("local-row")
    lr.add_argument("box_bits", type=int)
    lr.add_argument("dir_bits", type=int)
    lr.add_argument("grid_bits", type=int)
    lr.add_argument("--mul-style", default="auto")
    lr.add_argument("--children", type=int, default=1)
    sub.add_parser("local-classes")
    args = p.parse_args(argv)
    if args.cmd == "float":
        try:
            k = float_unit(args.unit, args.mul_dsp, args.file)
        except ContractError as e:
            print(f"contract: {e}", file=sys.stderr)
            return 2
        for key in FLOAT_KEYS:
            print(f"{key}={k[key]}")
        return 0
    if args.cmd == "float-limits":
        fc = float_contract(args.file)
        print("mul_dsp=" + " ".join(str(m) for m in fc["limits"]["mul_dsp"]))
        print(f"default_mul_dsp={fc['defaults']['mul_dsp']}")
        return 0
    if args.cmd == "limits":
        print(*limits(args.file))
    elif args.cmd == "row":
        try:
            k = row(args.coord_bits, args.dir_bits, args.mul_style, args.pipeline, args.file)
        except ContractError as e:
            print(f"contract: {e}", file=sys.stderr)
            return 2
        for key in ROW_KEYS:
            print(f"{key}={k[key]}")
    elif args.cmd == "classes":
        for k in classes(args.file):
            print(*k["coord_bits"], *k["dir_bits"], k["mul_style"], k["pipeline"],
                  *(k[key] for key in ROW_KEYS))
    elif args.cmd == "local-limits":
        lim = local_limits(args.file)
        print(*lim["box_bits"], *lim["dir_bits"], lim["grid_margin"], lim["max_grid_bits"], lim["children"][1])
    elif args.cmd == "local-row":
        try:
            k = local_row(args.box_bits, args.dir_bits, args.grid_bits, args.mul_style, args.children, args.file)
        except ContractError as e:
            print(f"contract: {e}", file=sys.stderr)
            return 2
        for key in (*LOCAL_ROW_KEYS, "mult18x18d"):
            print(f"{key}={k[key]}")
    else:
        for k in local_classes(args.file):
            print(*k["dir_bits"], *k["grid_bits"], k["mul_style"], *(k[key] for key in LOCAL_ROW_KEYS))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
