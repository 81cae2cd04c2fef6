#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Effective box tests per second per chip on each scene
(`make chip-effective`).

A chip's raw rate (units x Fmax, from the summary.json that `make chip` or
`make synth` wrote) counts every box test alike; a narrow unit's false hits
make the traversal do more of them. The useful rate of a chip on a scene is
its raw rate divided by 1 + the extra box tests of its answers against
exact ones (`pluecker cascade`, the same renders the README's tables use:
SAH BVH, DSA order, N x N image):

  array of units at C/D (placed chip, or one unit extrapolated to a chip):
      rate / (1 + extra(C/D alone))
  cascades of L narrow lanes at C/D and one wide unit each:
      served = min(lane rate, wide rate / escalated share)
      (the wide unit takes one query per clock: it saturates when
      L x the escalated share exceeds one), then
      served / (1 + extra(cascade))
      plus, for W plain wide units beside the cascades (--cascade ...+W),
      their rate / (1 + extra(wide alone))

The extra work and the escalated share come from one `pluecker cascade` run
per scene (every answer checked against the exact test; narrow widths: all
the chips' widths below the wide one; a chip at the wide width takes the
wide unit's figure alone). Inputs are summary folders or files:

  placed whole chips   out/synth/array_<NDSP>x<NLUT>_<C>x<D>[_p<P>]/ and
                       out/synth/cascade_<M>x<N>_<C>x<D>_<WC>x<WD>[_p<P>]/
  extrapolations       out/synth/<C>x<D>[...]/ (one unit: its units per
                       chip) and out/synth/cascade_<N>_... (one cascade)

Output: <out>/effective.json (every figure), effective.md (a table per
speed grade), effective_speed<S>.png (bars per scene and chip), and the
tables on stdout.
The scene runs are jobs of scripts/jobs.py (here, or on a Dask cluster with
DASK_SCHEDULER), one progress line each.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import jobs  # noqa: E402
import report_lib as rl  # noqa: E402
from report_lib import ROOT, say  # noqa: E402


class BadInput(SystemExit):
    """A summary this script cannot use: exits non-zero with the message."""

    def __init__(self, msg: str):
        super().__init__(f"chip-effective: {msg}")


@dataclass
class Chip:
    """One chip's raw figures: box tests (lane queries) per second per speed
    grade, the width of its box tests and, for cascades, the wide unit's."""

    name: str
    source: str
    placed: bool
    width: tuple[int, int]
    rate: dict[str, float]
    # {"lanes": per cascade, "wide": (C, D), "cascades": M, "plain": W, and with two clocks
    # "lane_rate": the lanes' box tests per second per speed grade (the rest is the plain units')}
    cascade: dict | None = None
    fmax: dict[str, float] = field(default_factory=dict)
    fmax2: dict[str, float] = field(default_factory=dict)  # two clocks: the second clock's Fmax
    fmax2_key: str = ""  # ... and its summary key (fmax_lut_mhz: fabric units, fmax_wide_mhz: plain wide units)


def _width(s: dict, key: str = "") -> tuple[int, int]:
    return int(s[f"{key}coord_bits"]), int(s[f"{key}dir_bits"])


def _fmax(s: dict, where: str, key: str = "fmax_mhz") -> dict[str, float]:
    f = {sp: float(st["median"]) for sp, st in (s.get(key) or {}).items() if st and st.get("median")}
    if not s.get("pnr") or not f:
        raise BadInput(f"{where}: no placed-and-routed Fmax (a Yosys-only summary, --no-pnr?)")
    return f


def load_chip(arg: str) -> Chip:
    """A summary.json (or its folder) of a placed chip, one unit or one cascade."""
    path = Path(arg)
    if path.is_dir():
        path = path / "summary.json"
    try:
        s = json.loads(path.read_text())
    except OSError as e:
        raise BadInput(f"{arg}: cannot read {path}: {e.strerror}") from None
    except ValueError as e:
        raise BadInput(f"{path}: not JSON: {e}") from None
    where = rl.rel(path)
    try:
        design = s["design"]
        fmax = _fmax(s, where)
        name = s.get("name") or path.parent.name
        if design == "pluecker_array":
            rate = s["array"]["box_tests_per_s"]  # with two clocks: NDSP x Fmax + NLUT x the fabric clock's
            two = s.get("clocks") == 2
            return Chip(f"{name} (placed{', two clocks' if two else ''})", where, True, _width(s), rate,
                        fmax=fmax, fmax2=_fmax(s, where, "fmax_lut_mhz") if two else {}, fmax2_key="fmax_lut_mhz")
        if design == "pluecker_cascade":
            cc = s.get("cascade_chip")  # a placed chip; else one cascade, extrapolated to a chip of them
            rate = cc["box_tests_per_s"] if cc else s["box_tests_per_s_per_chip"]
            two = s.get("clocks") == 2  # the plain wide units on a clock of their own
            label = f"{name} ({'placed' if cc else 'extrapolated from one cascade'}{', two clocks' if two else ''})"
            casc = {"lanes": int(s["n_narrow"]), "wide": _width(s, "wide_"),
                    "cascades": int(cc["cascades"]) if cc else 1,
                    "plain": int(cc.get("wide_units", 0)) if cc else 0}
            if two:
                casc["lane_rate"] = {sp: float(v) for sp, v in cc["lanes_box_tests_per_s"].items()}
            return Chip(label, where, bool(cc), _width(s), rate, casc, fmax,
                        fmax2=_fmax(s, where, "fmax_wide_mhz") if two else {}, fmax2_key="fmax_wide_mhz")
        if design == "pluecker_intersector":
            return Chip(f"{name} (extrapolated from one unit)", where, False, _width(s),
                        s["box_tests_per_s_per_chip"], fmax=fmax)
    except KeyError as e:
        raise BadInput(f"{where}: summary lacks {e} (written by an older scripts/synth.py?)") from None
    raise BadInput(f"{where}: design '{design}' is not a fixed-point unit, array or cascade")


def width_name(w: tuple[int, int]) -> str:
    return f"{w[0]}x{w[1]}"


def wide_of(chips: list[Chip], default: str) -> tuple[int, int]:
    wides = {c.cascade["wide"] for c in chips if c.cascade}
    if len(wides) > 1:
        raise BadInput("cascades with different wide widths (" + ", ".join(map(width_name, sorted(wides)))
                       + "): give them in separate runs")
    if wides:
        return wides.pop()
    m = re.fullmatch(r"(\d+)x(\d+)", default)
    if not m:
        raise BadInput(f"--wide: '{default}' is not CxD (e.g. 16x16)")
    return int(m[1]), int(m[2])


def run_scene(cli: str, spec: str, narrow: list[str], wide: str, size: int, threads: int, out: Path) -> dict:
    """Job: `pluecker cascade` of one scene; its JSON."""
    path = out / f"cascade_{re.sub(r'[^A-Za-z0-9_.-]', '_', rl.short_name(spec))}.json"
    rl.run([cli, "cascade", "--scene", spec, "--size", size, "--narrow", ",".join(narrow), "--wide", wide,
            "--threads", threads, "--quiet", "--json", path], echo=False)
    return json.loads(path.read_text())


def scene_figures(j: dict) -> dict:
    """{width name: {"extra": alone %, "cascade_extra": %, "escalated": share}} and the wide's."""
    figs = {width_name(_width(j["wide"])): {"extra": j["wide_alone"]["extra_percent"]["box_tests"]}}
    for n in j["narrow"]:
        figs[width_name(_width(n))] = {
            "extra": n["narrow_alone"]["extra_percent"]["box_tests"],
            "cascade_extra": n["cascade"]["extra_percent"]["box_tests"],
            "escalated": n["answers"]["escalated_fraction"],
        }
    return figs


def effective(chip: Chip, figs: dict, speed: str) -> dict | None:
    """The chip's figures on one scene at one speed grade (None: not measured there)."""
    raw = chip.rate.get(speed)
    if raw is None:
        return None
    f = figs[width_name(chip.width)]
    if chip.cascade is None:
        return {"raw": raw, "extra_percent": f["extra"], "effective": raw / (1 + f["extra"] / 100)}
    esc = f["escalated"]
    lanes, plain = chip.cascade["cascades"] * chip.cascade["lanes"], chip.cascade["plain"]
    lane_rate = chip.cascade.get("lane_rate", {}).get(speed)  # two clocks: the lanes' own
    if lane_rate is None:
        lane_rate = raw * lanes / (lanes + plain)  # every lane and plain unit at the same clock
    plain_rate = raw - lane_rate
    wide_rate = lane_rate / chip.cascade["lanes"]  # one wide unit per cascade of `lanes` lanes
    served = lane_rate if esc == 0 else min(lane_rate, wide_rate / esc)
    e = {"raw": raw, "extra_percent": f["cascade_extra"], "escalated": esc, "served": served,
         "wide_saturated": served < lane_rate, "effective": served / (1 + f["cascade_extra"] / 100)}
    if plain:
        x = figs[width_name(chip.cascade["wide"])]["extra"]
        e.update(plain_rate=plain_rate, plain_extra_percent=x, effective=e["effective"] + plain_rate / (1 + x / 100))
    return e


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("chips", nargs="+", help="summary.json files or their folders")
    p.add_argument("--cli", default=str(ROOT / "build" / "model" / "pluecker"), help="the pluecker CLI")
    p.add_argument("--scenes", default="auto",
                   help="comma list of scene specs; 'auto' = teapot, spheres and ../shared/scenes/* when present")
    p.add_argument("--size", type=int, default=128, help="image size N (N x N) of the scene renders")
    p.add_argument("--wide", default="16x16",
                   help="the wide width when no cascade is given (its extra work is the reference)")
    p.add_argument("--jobs", type=int, default=2, help="scenes at once (on this machine)")
    p.add_argument("--out", default=str(ROOT / "out" / "chip-effective"))
    a = p.parse_args(argv)
    if a.size < 1:
        p.error(f"--size: {a.size} must be at least 1")
    if a.jobs < 1:
        p.error(f"--jobs: {a.jobs} must be at least 1")
    return a


def render_table(chips: list[Chip], scenes: list[str], rows: dict, speed: str) -> str:
    head = ["chip", "width", f"raw, speed {speed}"] + [rl.short_name(s) for s in scenes]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for c in chips:
        if speed not in c.rate:
            continue
        cells = [c.name, f"{c.width[0]}/{c.width[1]}" + (
            f" > {c.cascade['wide'][0]}/{c.cascade['wide'][1]}" if c.cascade else "") + (
            f", + {c.cascade['plain']} x {c.cascade['wide'][0]}/{c.cascade['wide'][1]}"
            if c.cascade and c.cascade["plain"] else ""),
                 f"{c.rate[speed] / 1e9:.2f} G"]
        for s in scenes:
            e = rows[s][c.name][speed]
            x = e["extra_percent"]
            note = f" ({x:.3g} % extra" if x < 100 else f" ({x:,.0f} % extra"
            if "escalated" in e:
                note += f", {100 * e['escalated']:.0f} % escalated"
            note += ", wide saturated)" if e.get("wide_saturated") else ")"
            cells.append(f"{e['effective'] / 1e9:.2f} G{note}")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def plot(chips: list[Chip], scenes: list[str], rows: dict, speed: str, path: Path) -> None:
    plt = rl.mpl()
    fig, ax = plt.subplots(figsize=(max(6.0, 1.6 * len(scenes) + 2), 4.2))
    shown = [c for c in chips if speed in c.rate]
    bw = 0.8 / max(1, len(shown))
    for i, c in enumerate(shown):
        xs = [k + (i - (len(shown) - 1) / 2) * bw for k in range(len(scenes))]
        ax.bar(xs, [rows[s][c.name][speed]["effective"] / 1e9 for s in scenes], bw, label=c.name,
               hatch=None if c.placed else "//", edgecolor="white" if c.placed else "black", linewidth=0.3)
    ax.set_xticks(range(len(scenes)), [rl.short_name(s) for s in scenes])
    ax.set_ylabel(f"effective box tests/s per chip (G), speed {speed}")
    ax.set_title("Useful box tests per second: raw rate / (1 + extra box tests); hatched: extrapolated")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)


def main(argv) -> int:
    args = parse_args(argv)
    chips = [load_chip(c) for c in args.chips]
    names = [c.name for c in chips]
    if len(set(names)) != len(names):
        raise BadInput("the same chip given twice: " + ", ".join(sorted({n for n in names if names.count(n) > 1})))
    if not Path(args.cli).exists():
        raise BadInput(f"{args.cli}: the pluecker CLI is not built (make build)")
    wide = wide_of(chips, args.wide)
    for c in chips:
        if not (c.width[0] <= wide[0] and c.width[1] <= wide[1]):
            raise BadInput(f"{c.source}: width {width_name(c.width)} is wider than the wide width "
                           f"{width_name(wide)}: give --wide")
    narrow = [width_name(w) for w in sorted({c.width for c in chips if c.width != wide})]
    # `pluecker cascade` needs a narrow width; with every chip at the wide
    # width only the wide unit's figure is used, so any narrower one does.
    run_narrow = narrow or [width_name((max(2, wide[0] // 2), max(2, wide[1] // 2)))]
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    # scene files as given from here; the CLI runs in the project root
    scenes = [str(Path(s).resolve()) if rl.is_scene_file(s) and not (ROOT / s).exists() and Path(s).exists()
              else s for s in rl.scene_list(args.scenes, who="chip-effective")]
    missing = [s for s in scenes if rl.is_scene_file(s) and not (ROOT / s).exists()]
    if missing:
        raise BadInput("scene file(s) not found: " + ", ".join(missing))
    say(f"chip-effective: {len(chips)} chip(s), widths {', '.join(narrow) or '-'} below the wide "
        f"{width_name(wide)}, {len(scenes)} scene(s) at {args.size}x{args.size}")
    threads = max(1, (os.cpu_count() or 2) // min(args.jobs, len(scenes)))
    try:
        runs = jobs.run_jobs([jobs.Job(rl.short_name(s), "chip_effective:run_scene",
                                       (args.cli, s, run_narrow, width_name(wide), args.size, threads, out))
                              for s in scenes], label="chip-effective", local_workers=args.jobs,
                             journal=out / "jobs.jsonl",
                             summary=lambda j: (f"{j['triangles']:,} triangles, "
                                                f"{j['reference']['box_tests']:,} box tests"))
    except jobs.JobsFailed as e:
        raise SystemExit(f"chip-effective: {e}") from None
    speeds = sorted({sp for c in chips for sp in c.rate}, key=int)
    rows = {}
    for s, j in zip(scenes, runs.values()):
        figs = scene_figures(j)
        rows[s] = {c.name: {sp: effective(c, figs, sp) for sp in speeds} for c in chips}
    result = {
        "definitions": {
            "raw": "box tests (cascades: lane queries, and the plain wide units' queries) per second per chip "
                   "from the summary",
            "extra_percent": "100 * (box tests - exact answers' box tests) / exact answers' box tests "
                             "(pluecker cascade; cascades: the cascade's answers)",
            "served": "cascades: min(lane rate, wide unit rate / escalated share)",
            "plain_rate": "cascade chips with plain wide units beside: their part of raw (with two clocks "
                          "at their own clock's Fmax, the lanes at clk_i's)",
            "effective": "(served or raw) / (1 + extra_percent / 100) "
                         "[+ plain_rate / (1 + plain_extra_percent / 100)]",
        },
        "size": args.size, "wide": width_name(wide),
        "chips": [{"name": c.name, "summary": c.source, "placed": c.placed, "width": width_name(c.width),
                   "raw": c.rate, "fmax_mhz": c.fmax, **({c.fmax2_key: c.fmax2} if c.fmax2 else {}),
                   **({"cascade": {"lanes": c.cascade["lanes"], "wide": width_name(c.cascade["wide"]),
                                   "cascades": c.cascade["cascades"], "plain_wide_units": c.cascade["plain"]}}
                      if c.cascade else {})} for c in chips],
        "scenes": {s: {"triangles": j["triangles"], "reference_box_tests": j["reference"]["box_tests"],
                       "chips": rows[s]} for s, j in zip(scenes, runs.values())},
    }
    (out / "effective.json").write_text(json.dumps(result, indent=2) + "\n")
    md = [f"Effective box tests per second per chip ({args.size}x{args.size}, SAH, DSA; "
          "raw / (1 + extra box tests); cascades: served lane queries / (1 + the cascade's extra))", ""]
    for sp in speeds:
        md += [render_table(chips, scenes, rows, sp), ""]
        plot(chips, scenes, rows, sp, out / f"effective_speed{sp}.png")
    (out / "effective.md").write_text("\n".join(md))
    print("\n".join(md))
    sp = speeds[-1]
    for s in scenes:
        for which, placed in (("placed", True), ("extrapolated", False)):
            pool = [c for c in chips if c.placed == placed and sp in c.rate]
            if pool:
                b = max(pool, key=lambda c: rows[s][c.name][sp]["effective"])
                say(f"chip-effective: {rl.short_name(s)}, speed {sp}: best {which}: {b.name}, "
                    f"{rows[s][b.name][sp]['effective'] / 1e9:.2f} G")
    say(f"chip-effective: wrote {rl.rel(out / 'effective.json')}, effective.md, "
        + ", ".join(f"effective_speed{sp}.png" for sp in speeds))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
