#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The speed-for-accuracy report (`make report`): for each scene and width
pair, the study figures of `pluecker study` (per-query false hits and misses,
extra traversal work, nearest-mode image errors), the hardware cost from
`make synth` (out/synth/<C>x<D>/summary.json), the derived throughput per
unit and per LFE5U-85F, and the golden-model comparison (RTL vs model with
the Verilator harness, model vs float Pluecker, float vs exact).

Fixed point against float32: the binary32 units measured by `make synth
UNIT=float|smits` (out/synth/<unit>[_cons]_dsp<M>/summary.json) beside the
fixed-point unit at 16/16, 24/24 and, per scene, the narrowest width of the
sweep whose extra box tests are at most --equal-work percent (the float
units traverse without extra work): area, box tests per second per chip,
their ratios, and effective rays per second per chip with each test's false
misses on the study's queries.

The studies (one a scene), the harness builds (one a width) and the RTL
checks (one a scene and width) are jobs of scripts/jobs.py: on this machine,
or on a Dask distributed cluster when DASK_SCHEDULER=host:port is set, with a
progress line per finished job; a failed job ends the report naming it, and
<out>/jobs_<phase>.jsonl keeps the finished jobs' results.

Output: out/report/report.html (self-contained: tables and base64 PNG
plots), out/report/report.json (every figure), out/report/plots/*.png.
Definitions of the figures: model/rt/include/pluecker/study.hpp.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import jobs  # noqa: E402  (scripts/jobs.py: here or on a Dask cluster)
import report_lib as rl  # noqa: E402
from report_lib import ROOT, fmt, say, scene_list, short_name, table  # noqa: E402


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cli", default=str(ROOT / "build" / "model" / "pluecker"), help="the pluecker CLI")
    p.add_argument("--out", default=str(ROOT / "out" / "report"), help="output directory")
    p.add_argument("--size", type=int, default=128, help="study image size N (N x N)")
    p.add_argument("--widths", default="6:24:2", help="width pairs (the CLI's --widths syntax)")
    p.add_argument("--scenes", default="auto",
                   help="comma list of scene specs; 'auto' = teapot, spheres and ../shared/scenes/* when present")
    p.add_argument("--local", default="8:12:2",
                   help="local-frame box widths K (the CLI's study --local syntax; '' to skip)")
    p.add_argument("--order", default="dsa", choices=("fixed", "dsa"))
    p.add_argument("--build", default="sah", choices=("sah", "median"))
    p.add_argument("--synth", type=int, choices=(0, 1), default=0,
                   help="1: run `make synth` for widths without out/synth/<C>x<D>/summary.json")
    p.add_argument("--synth-dir", default=str(ROOT / "out" / "synth"))
    p.add_argument("--rtl-widths", default="8 16 24",
                   help="widths for the RTL vs model check ('' to skip); builds the harness when missing")
    p.add_argument("--sim-root", default=str(ROOT / "build" / "sim"),
                   help="where the harness builds live (<root>/<C>x<D>/pluecker_sim)")
    p.add_argument("--rtl-size", type=int, default=48, help="image size of the traced render for the RTL check")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--make", default=os.environ.get("MAKE", "make"))
    p.add_argument("--equal-work", type=float, default=0.01,
                   help="extra box tests (%%) at or below which a fixed-point width counts as doing the "
                        "float units' work (the narrowest such width per scene is compared)")
    p.add_argument("--from-json", help="redo hardware, plots and HTML from an earlier report.json (no runs)")
    return p.parse_args(argv)


# --------------------------------------------------------------------------
# Measurements

def run_study(args, spec: str, outdir: Path) -> dict:
    """Job: `pluecker study` of one scene; its JSON."""
    path = outdir / f"study_{re.sub(r'[^A-Za-z0-9_.-]', '_', short_name(spec))}.json"
    r = rl.run([args.cli, "study", "--scene", spec, "--size", args.size, "--widths", args.widths,
                "--order", args.order, "--build", args.build, "--threads", args.jobs, "--quiet", "--json", path]
               + (["--local", args.local] if args.local else []), echo=False)
    with open(path) as f:
        j = json.load(f)
    j["study_file"] = rl.rel(path)
    j["study_seconds_wall"] = round(r.seconds, 1)
    j["spec"] = spec
    return j


def study_line(j: dict) -> str:
    w = j["widths"][0]
    return (f"{j['triangles']:,} triangles, {j['queries']['count']:,} box queries; "
            f"{rl.pair_name(w['coord_bits'], w['dir_bits'])}: {w['work']['extra_percent']['box_tests']:.3g} % "
            "extra box tests")


def run_jobs(job_list: list, args, label: str, local_workers: int, summary) -> dict:
    """The jobs through scripts/jobs.py (here, or on the Dask cluster of
    DASK_SCHEDULER); a failed job ends the report with its name, after the
    finished jobs' results are written to <out>/jobs_<label>.jsonl."""
    try:
        return jobs.run_jobs(job_list, label=f"report {label}", local_workers=local_workers,
                             journal=Path(args.out) / f"jobs_{label}.jsonl", summary=summary)
    except jobs.JobsFailed as e:
        raise SystemExit(f"report: {e}") from None


def ensure_synth(args, widths, synth_dir: Path) -> None:
    for c, d in widths:
        if (synth_dir / rl.pair_name(c, d) / "summary.json").exists():
            continue
        if not args.synth:
            continue
        say(f"report: synthesising {c}x{d} (REPORT_SYNTH=1)")
        rl.run([args.make, "--no-print-directory", "synth", f"COORD_BITS={c}", f"DIR_BITS={d}", f"JOBS={args.jobs}"],
               check=False)


def sim_binary(args, w: int) -> tuple[Path | None, str]:
    """Job: builds (or finds up to date) the harness for w x w conservative."""
    out = Path(args.sim_root) / f"{w}x{w}"
    if not (ROOT / "rtl" / "pluecker_intersector.sv").exists():
        return None, "rtl/pluecker_intersector.sv missing"
    env = dict(os.environ, COORD_BITS=str(w), DIR_BITS=str(w), MODE="conservative",
               MODEL_BUILD=str(Path(args.cli).resolve().parent), SIM_OUT=str(out), SIM_JOBS=str(args.jobs))
    r = rl.run([ROOT / "scripts" / "venv-exec.sh", ROOT / "sim" / "build.sh"], env=env, check=False, capture=True,
               echo=False)
    if r.returncode != 0:
        return None, f"sim/build.sh failed: {(r.stderr or '').strip()[-400:]}"
    return out / "pluecker_sim", ""


# The harness's `query --check` summary (stderr), e.g. "check (16x16
# conservative): 67030 queries (67030 through the RTL, ...), 0 mismatches".
CHECK_RE = re.compile(r"check \(([^)]*)\): (\d+) queries(?: \([^)]*\))?, (\d+) mismatches")


def rtl_check(args, sim: Path, w: int, spec: str, tmpdir: Path) -> dict:
    """Job: the RTL against the model on the queries of one traced render."""
    trace = tmpdir / f"trace_{w}_{re.sub(r'[^A-Za-z0-9_.-]', '_', short_name(spec))}.txt"
    rl.run([args.cli, "trace", "--scene", spec, "--size", args.rtl_size, "--test", "fixed", "--coord-bits", w,
            "--dir-bits", w, "--order", args.order, "--build", args.build, "--quiet", "--out", trace], echo=False)
    r = rl.run([sim, "query", "--check", "--coord-bits", w, "--dir-bits", w, trace], check=False, capture=True,
               echo=False)
    trace.unlink(missing_ok=True)
    m = CHECK_RE.search(r.stderr or "")
    res = {"coord_bits": w, "dir_bits": w, "size": args.rtl_size, "exit": r.returncode,
           "queries": int(m.group(2)) if m else None, "mismatches": int(m.group(3)) if m else None}
    if not m:
        res["error"] = (r.stderr or "").strip()[-400:]
    return res


def rtl_line(res: dict) -> str:
    return (f"{res['queries']} queries, {res['mismatches']} mismatches" if res.get("queries") is not None
            else f"FAILED: {res.get('error')}")


# --------------------------------------------------------------------------
# Derived figures

def derived(studies: dict, hw: dict) -> dict:
    """Effective rays per second per chip: the chip's box tests per second
    over the box tests per ray of the conservative render at that width."""
    out = {}
    for name, j in studies.items():
        ref_bpr = j["reference"]["per_ray"]["box_tests"]
        per_w = {}
        for w in j["widths"]:
            key = rl.pair_name(w["coord_bits"], w["dir_bits"])
            h = hw.get(key)
            bpr = w["work"]["per_ray"]["box_tests"]
            e = {"box_tests_per_ray": bpr, "reference_box_tests_per_ray": ref_bpr}
            if h and h["box_tests_per_s_per_chip"]:
                e["rays_per_s_per_chip"] = {sp: v / bpr for sp, v in h["box_tests_per_s_per_chip"].items()}
                e["rays_per_s_per_unit"] = {sp: v / bpr for sp, v in h["box_tests_per_s_per_unit"].items()}
                # What the same chip would reach without the extra work.
                e["rays_per_s_per_chip_without_extra_work"] = {
                    sp: v / ref_bpr for sp, v in h["box_tests_per_s_per_chip"].items()}
            per_w[key] = e
        out[name] = per_w
    return out


def local_key(c: dict) -> str:
    return f"K{c['box_bits']} D{c['dir_bits']} G{c['grid_bits']}"


def local_hardware(studies: dict, synth_dir: Path, cap: dict) -> dict:
    """The local unit's synthesis summaries (make synth-local) of the
    studied configurations: out/synth/local_k<K>_d<D>_g<G>_c<C>[_style]."""
    out = {}
    for j in studies.values():
        for c in j.get("local", {}).get("configs", []):
            stem = f"local_k{c['box_bits']}_d{c['dir_bits']}_g{c['grid_bits']}_c"
            for d in sorted(synth_dir.glob(stem + "*")):
                h = rl.hardware_of(synth_dir, d.name, cap)
                if h and h["box_tests_per_s_per_chip"]:
                    out[d.name] = dict(h, key=local_key(c))
    return out


def local_derived(studies: dict, lhw: dict, der: dict) -> dict:
    """Effective rays per second per chip of each synthesised local unit on
    each scene (its box tests per second per chip over the local render's
    box tests per ray), beside the best global width's."""
    out = {}
    for name, j in studies.items():
        rows = []
        best_global = {}
        for e in der.get(name, {}).values():
            for sp, v in e.get("rays_per_s_per_chip", {}).items():
                best_global[sp] = max(best_global.get(sp, 0), v)
        for c in j.get("local", {}).get("configs", []):
            bpr = c["work"]["per_ray"]["box_tests"]
            for unit, h in lhw.items():
                if h["key"] != local_key(c):
                    continue
                rays = {sp: v / bpr for sp, v in h["box_tests_per_s_per_chip"].items()}
                rows.append({"unit": unit, "key": h["key"], "box_tests_per_ray": bpr, "rays_per_s_per_chip": rays,
                             "best_global_rays_per_s_per_chip": best_global,
                             "ratio_to_best_global": {sp: v / best_global[sp] for sp, v in rays.items()
                                                      if best_global.get(sp)}})
        out[name] = rows
    return out


# --------------------------------------------------------------------------
# Fixed point against float32

# The binary32 units' synthesis directories (scripts/synth.py --unit) and
# the study's per-query counts of the same test (study.hpp: F32Counts).
FLOAT_UNITS = {"float": ("binary32 Plücker, nearest", "f32_pluecker"),
               "float_cons": ("binary32 Plücker, conservative", "f32_pluecker_conservative"),
               "smits": ("binary32 slab (smits)", "f32_smits")}
FIXED_REFS = ("16x16", "24x24")


def float_unit_of(name: str) -> str | None:
    """'float_cons_dsp4' -> 'float_cons'; None for a width pair."""
    m = re.fullmatch(r"(float_cons|float|smits)_dsp\d", name)
    return m.group(1) if m else None


def float_hardware(synth_dir: Path, cap: dict) -> dict:
    """Every synthesised binary32 unit configuration: name -> hardware."""
    out = {}
    for d in sorted(synth_dir.glob("*_dsp*")):
        if float_unit_of(d.name):
            h = rl.hardware_of(synth_dir, d.name, cap)
            if h:
                out[d.name] = h
    return out


def equal_work_widths(studies: dict, threshold: float) -> dict:
    """Per scene, the narrowest width pair of the sweep whose extra box
    tests are at most `threshold` percent (None when none is)."""
    out = {}
    for name, j in studies.items():
        ws = sorted(j["widths"], key=lambda w: (w["coord_bits"], w["dir_bits"]))
        ok = [w for w in ws if w["work"]["extra_percent"]["box_tests"] <= threshold]
        out[name] = rl.pair_name(ok[0]["coord_bits"], ok[0]["dir_bits"]) if ok else None
    return out


def fixed_hardware(synth_dir: Path, keys, cap: dict, hw: dict) -> dict:
    """The fixed-point widths to compare: from the sweep's figures, else
    read from out/synth."""
    out = {}
    for k in keys:
        if k is None:
            continue
        h = hw.get(k)
        if h is None:
            h = rl.hardware_of(synth_dir, k, cap)
        out[k] = h
    return out


def comparison(fixed_hw: dict, float_hw: dict) -> list[dict]:
    """Area ratios (float / fixed) and box tests per second per chip ratios
    (fixed / float) for every pair of measured configurations."""
    rows = []
    for fk, f in fixed_hw.items():
        for uk, u in float_hw.items():
            if not f or not u:
                continue
            r = {"fixed": fk, "float": uk}
            for key in ("placed_comb", "placed_ff", "MULT18X18D", "LUT4", "CCU2C", "TRELLIS_FF"):
                r[f"area_{key}"] = (u[key] / f[key]) if f.get(key) and u.get(key) is not None else None
            r["chip_ratio"] = {sp: f["box_tests_per_s_per_chip"][sp] / u["box_tests_per_s_per_chip"][sp]
                               for sp in f["box_tests_per_s_per_chip"] if sp in u["box_tests_per_s_per_chip"]}
            r["units_ratio"] = (f["units_per_chip"] / u["units_per_chip"]
                                if f.get("units_per_chip") and u.get("units_per_chip") else None)
            rows.append(r)
    return rows


def float_rays(studies: dict, fixed_hw: dict, float_hw: dict, eq: dict) -> dict:
    """Per scene: effective rays per second per chip of the fixed-point
    references (box tests per ray at their width) and of the binary32 units
    (the reference's box tests per ray: no extra work), with the false
    misses and hits of each test on the study's queries."""
    out = {}
    for name, j in studies.items():
        ref_bpr = j["reference"]["per_ray"]["box_tests"]
        by_width = {rl.pair_name(w["coord_bits"], w["dir_bits"]): w for w in j["widths"]}
        rows = []
        for fk in [*FIXED_REFS, eq.get(name)]:
            h = fixed_hw.get(fk) if fk else None
            w = by_width.get(fk) if fk else None
            if not fk or any(r["config"] == f"fixed {fk}" for r in rows):
                continue
            bpr = w["work"]["per_ray"]["box_tests"] if w else None
            q = w["query"]["conservative"] if w else None
            rows.append({"config": f"fixed {fk}", "equal_work": fk == eq.get(name), "box_tests_per_ray": bpr,
                         "extra_percent": w["work"]["extra_percent"]["box_tests"] if w else None,
                         "false_misses": q["false_misses"] if q else None,
                         "false_hits": q["false_hits"] if q else None,
                         "rays_per_s_per_chip": ({sp: v / bpr for sp, v in h["box_tests_per_s_per_chip"].items()}
                                                 if h and bpr else {})})
        counts = j.get("queries", {})
        for uk, h in float_hw.items():
            c = counts.get(FLOAT_UNITS[float_unit_of(uk)][1], {})
            rows.append({"config": uk, "equal_work": False, "box_tests_per_ray": ref_bpr, "extra_percent": 0.0,
                         "false_misses": c.get("false_misses"), "false_hits": c.get("false_hits"),
                         "rays_per_s_per_chip": {sp: v / ref_bpr for sp, v in h["box_tests_per_s_per_chip"].items()}})
        out[name] = rows
    return out


# --------------------------------------------------------------------------
# Plots

MARKERS = "osD^v<>p*h"


def widths_of(j):
    return [w["coord_bits"] for w in j["widths"]]


def wlabel(j):
    return [rl.pair_name(w["coord_bits"], w["dir_bits"]) for w in j["widths"]]


def plot_all(studies: dict, hw: dict, der: dict, plotdir: Path, hw_dir: str) -> dict[str, str]:
    plt = rl.mpl()
    plots = {}
    names = list(studies)
    equal = all(w["coord_bits"] == w["dir_bits"] for j in studies.values() for w in j["widths"])
    xlab = "COORD_BITS = DIR_BITS" if equal else "width pair (COORD_BITS; see table for DIR_BITS)"

    def save(key, fig, alt):
        h, data = rl.fig_html(fig, alt)
        (plotdir / f"{key}.png").write_bytes(data)
        plots[key] = h

    # 1. Extra work.
    fig, ax = plt.subplots()
    for i, n in enumerate(names):
        j = studies[n]
        ax.plot(widths_of(j), [w["work"]["extra_percent"]["box_tests"] for w in j["widths"]],
                marker=MARKERS[i % len(MARKERS)], label=n)
    ax.set_yscale("symlog", linthresh=0.01)
    ax.set_xlabel(xlab)
    ax.set_ylabel("extra box tests vs exact [%]")
    ax.set_title("Extra traversal work of the conservative fixed-point test")
    ax.set_xticks(widths_of(studies[names[0]]))
    ax.legend(fontsize=8)
    save("extra_work", fig, "extra box tests per width")

    # 2. False-hit rates per query, conservative and nearest side by side.
    fig, axes = plt.subplots(1, 2, figsize=(10.5, 3.9), sharey=True)
    for ax, mode in zip(axes, ("conservative", "nearest")):
        for i, n in enumerate(names):
            j = studies[n]
            ax.plot(widths_of(j), [w["query"][mode]["false_hit_rate"] or float("nan") for w in j["widths"]],
                    marker=MARKERS[i % len(MARKERS)], label=n)
        ax.set_yscale("log")
        ax.set_xlabel(xlab)
        ax.set_title(f"{mode.capitalize()}: false-hit rate per query")
        ax.set_xticks(widths_of(studies[names[0]]))
    axes[0].set_ylabel("false hits / exact misses (zeros not drawn)")
    axes[0].legend(fontsize=8)
    save("false_hits", fig, "false-hit rate per width")

    # 3. Nearest mode: wrong pixels and false misses.
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10.5, 3.9))
    for i, n in enumerate(names):
        j = studies[n]
        a1.plot(widths_of(j), [100.0 * w["nearest"]["wrong_pixel_fraction"] for w in j["widths"]],
                marker=MARKERS[i % len(MARKERS)], label=n)
        q = j["queries"]["count"]
        a2.plot(widths_of(j), [w["query"]["nearest"]["false_misses"] / q * 1e6 for w in j["widths"]],
                marker=MARKERS[i % len(MARKERS)], label=n)
    for a, t, yl in ((a1, "Nearest mode: wrong pixels", "pixels differing from exact [%]"),
                     (a2, "Nearest mode: false misses", "false misses per million queries")):
        a.set_yscale("symlog", linthresh=0.01 if a is a1 else 1)
        a.set_xlabel(xlab)
        a.set_ylabel(yl)
        a.set_title(t)
        a.set_xticks(widths_of(studies[names[0]]))
    a1.legend(fontsize=8)
    save("nearest", fig, "nearest mode errors")

    # 4. Hardware and effective throughput (measured widths only).
    measured = sorted(((k, v) for k, v in hw.items() if v), key=lambda kv: int(kv[0].split("x")[0]))
    if measured:
        all_x = sorted({int(k.split("x")[0]) for k in hw})
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(10.5, 3.9))
        xs = [int(k.split("x")[0]) for k, _ in measured]
        cap = rl.device_capacity(Path(hw_dir))[0]
        for lab, key, capk, m in (("LUT4 slots (placed TRELLIS_COMB)", "placed_comb", "TRELLIS_COMB", "o"),
                                  ("FF", "TRELLIS_FF", "TRELLIS_FF", "s"),
                                  ("MULT18X18D", "MULT18X18D", "MULT18X18D", "D")):
            a1.plot(xs, [100.0 * (v[key] or 0) / cap[capk] for _, v in measured], marker=m, label=lab)
        a1.set_xlabel("COORD_BITS (= DIR_BITS)")
        a1.set_ylabel(f"share of one {rl.DEVICE} per unit [%]")
        a1.set_title("Cost of one unit (measured widths only)")
        a1.set_xticks(all_x)
        a1.set_xlim(all_x[0] - 0.5, all_x[-1] + 0.5)
        a1.set_ylim(bottom=0)
        a1.legend(fontsize=8)
        speeds = sorted({sp for _, v in measured for sp in v["fmax_mhz"]})
        sp = speeds[-1] if speeds else None
        a2.set_xticks(all_x)
        a2.set_xlim(all_x[0] - 0.5, all_x[-1] + 0.5)
        if sp:
            for i, n in enumerate(names):
                pts = sorted((int(k.split("x")[0]), der[n][k]["rays_per_s_per_chip"][sp] / 1e6)
                             for k in der[n] if sp in der[n][k].get("rays_per_s_per_chip", {}))
                if pts:
                    a2.plot([p[0] for p in pts], [p[1] for p in pts], marker=MARKERS[i % len(MARKERS)], label=n)
            a2.set_title(f"Effective rays/s per {rl.DEVICE} (speed grade {sp})")
            a2.set_ylabel("million rays per second")
            a2.set_xlabel("COORD_BITS (= DIR_BITS)")
            a2.set_ylim(bottom=0)
            a2.legend(fontsize=8)
        else:
            a2.text(0.5, 0.5, "Fmax not measured (no place and route)", ha="center", transform=a2.transAxes)
        save("hardware", fig, "hardware cost and throughput")
    return plots


# --------------------------------------------------------------------------
# HTML

def scene_section(name: str, j: dict, rtl: list[dict]) -> list[str]:
    ref = j["reference"]
    q = j.get("queries", {})
    b = [f"<h3>{rl.esc(name)}</h3>",
         f"<p>{j['triangles']:,} triangles, BVH {j['bvh']['nodes']:,} nodes (depth {j['bvh']['depth']}), "
         f"{j['build']} build, order {j['order']}, {j['width']}&times;{j['height']} pixels, "
         f"{ref['rays']['total']:,} rays ({ref['rays']['camera']:,} camera, {ref['rays']['shadow']:,} shadow, "
         f"{ref['rays']['reflection']:,} reflection, {ref['rays']['refraction']:,} refraction). "
         f"Exact reference: {fmt(ref['per_ray']['box_tests'], 2)} box tests, "
         f"{fmt(ref['per_ray']['node_visits'], 2)} node visits, {fmt(ref['per_ray']['triangle_tests'], 2)} "
         f"triangle tests per ray; {q.get('count', 0):,} box queries. Study: {j['seconds']:.1f} s.</p>"]
    rows = []
    for w in j["widths"]:
        qc, qn, wk, nr = w["query"]["conservative"], w["query"]["nearest"], w["work"], w["nearest"]
        rows.append([rl.pair_name(w["coord_bits"], w["dir_bits"]),
                     qc["false_misses"], qc["false_hit_rate"],
                     wk["extra_percent"]["box_tests"], wk["extra_percent"]["node_visits"],
                     wk["extra_percent"]["triangle_tests"], wk["per_ray"]["box_tests"], wk["wrong_pixels"],
                     qn["false_misses"], qn["false_hit_rate"], nr["checked"]["false_misses"], nr["wrong_pixels"],
                     100.0 * nr["wrong_pixel_fraction"]])
    b.append(table(["CxD", "cons. false misses", "cons. false-hit rate",
                    "extra box tests %", "extra node visits %", "extra tri tests %", "box tests / ray",
                    "cons. wrong px", "nearest false misses", "nearest false-hit rate",
                    "nearest render false misses", "nearest wrong px", "nearest wrong px %"], rows))
    loc = j.get("local")
    if loc:
        lref = loc.get("reference", {})
        b.append(f"<p>Local frames (<code>docs/local-frames.md</code>): against their own exact reference on the "
                 f"local path ({fmt(lref.get('per_ray', {}).get('box_tests'), 2)} box tests per ray).</p>")
        rows = []
        for c in loc["configs"]:
            qc, wk, nr = c["query"]["conservative"], c["work"], c["nearest"]
            rows.append([local_key(c), qc["false_misses"], qc["false_hit_rate"], wk["extra_percent"]["box_tests"],
                         wk["extra_percent"]["node_visits"], wk["extra_percent"]["triangle_tests"],
                         wk["per_ray"]["box_tests"], wk["checked"]["false_misses"], nr["wrong_pixels"],
                         c["memory"]["bytes_per_node"]])
        b.append(table(["local KxDxG", "cons. false misses", "cons. false-hit rate", "extra box tests %",
                        "extra node visits %", "extra tri tests %", "box tests / ray", "cons. render false misses",
                        "nearest wrong px", "bytes / node"], rows))
    if rtl:
        b.append(table(["RTL check", "traced size", "queries compared", "mismatches", "exit"],
                       [[rl.pair_name(r["coord_bits"], r["dir_bits"]), f"{r['size']}x{r['size']}",
                         r.get("queries"), r.get("mismatches"), r["exit"]] for r in rtl]))
    return b


def float_section(fl: dict) -> list[str]:
    """Fixed point against float32: hardware, ratios, rays per chip."""
    b = ["<h2>Fixed point against float32 (the same test on the same chip)</h2>",
         "<p>The binary32 units (<code>rtl/pluecker_float_intersector.sv</code>: the Plücker test in "
         "<code>pluecker_hit</code>'s operation order, rounded to nearest or outward; "
         "<code>rtl/pluecker_smits_intersector.sv</code>: the slab test) measured by the same flow "
         "(<code>make synth UNIT=float|smits</code>) beside the conservative fixed-point unit at "
         f"{', '.join(FIXED_REFS)} and, per scene, at the narrowest width whose extra box tests are at most "
         f"{fl['equal_work_percent']:g} % (equal work: the float units traverse without extra work). Area ratio "
         "= float / fixed; chip ratio = fixed box tests per second per chip / float.</p>"]
    speeds = sorted({sp for h in [*fl["fixed_hardware"].values(), *fl["hardware"].values()] if h
                     for sp in h["fmax_mhz"]})
    rows = []
    for k, h in [*[(f"fixed {k}", v) for k, v in fl["fixed_hardware"].items()], *fl["hardware"].items()]:
        if not h:
            rows.append([k, ("span", 8 + 2 * len(speeds), "not measured (<code>make synth</code>)")])
            continue
        rows.append([k, h["LUT4"], h["CCU2C"], h["TRELLIS_FF"], h["MULT18X18D"], h["placed_comb"], h["latency"],
                     h["units_per_chip"], h["limited_by"] or "–"]
                    + [(f"{h['fmax_mhz'][sp]['median']:.1f}" if sp in h["fmax_mhz"] else "–") for sp in speeds]
                    + [(f"{h['box_tests_per_s_per_chip'][sp] / 1e9:.2f}" if sp in h["box_tests_per_s_per_chip"]
                        else "–") for sp in speeds])
    if not fl["hardware"]:
        b.append("<p>No binary32 unit synthesised yet (<code>make synth UNIT=float</code>, "
                 "<code>UNIT=smits</code>).</p>")
    b.append(table(["unit", "LUT4", "CCU2C", "FF", "MULT18X18D", "LUT4 slots placed", "latency", "units/chip",
                    "limited by"] + [f"Fmax MHz speed {sp}" for sp in speeds]
                   + [f"G box tests/s/chip speed {sp}" for sp in speeds], rows))
    rows = [[r["fixed"], r["float"], r["area_placed_comb"], r["area_placed_ff"], r["area_MULT18X18D"],
             r["units_ratio"]] + [r["chip_ratio"].get(sp) for sp in speeds] for r in fl["comparison"]]
    if rows:
        b.append(table(["fixed", "float", "LUT4 slots ratio", "FF ratio", "MULT18X18D ratio",
                        "units/chip fixed : float"] + [f"box tests/s/chip fixed : float, speed {sp}"
                                                       for sp in speeds], rows, left=2))
    rows = []
    for scene, lst in fl["rays"].items():
        for r in lst:
            rows.append([scene, r["config"] + (" (equal work)" if r["equal_work"] else ""), r["box_tests_per_ray"],
                         r["extra_percent"], r["false_misses"], r["false_hits"]]
                        + [(r["rays_per_s_per_chip"][sp] / 1e6 if sp in r["rays_per_s_per_chip"] else None)
                           for sp in speeds])
    b.append("<h3>Effective rays per second per chip</h3>"
             "<p>Box tests per second per chip / box tests per ray: the fixed-point widths at their measured "
             "extra work, the float units at the exact traversal's box tests per ray. False misses and hits: "
             "each test's answers on the study's box queries against exact (a float unit's false misses are "
             "boxes it loses, which the fixed-point conservative unit never does).</p>")
    b.append(table(["scene", "unit", "box tests/ray", "extra box tests %", "false misses", "false hits"]
                   + [f"M rays/s/chip speed {sp}" for sp in speeds], rows, left=2))
    return b


def local_hardware_section(lhw: dict, lder: dict, speeds: list[str]) -> list[str]:
    b = ["<h3>The local unit (out/synth/local_*)</h3>"]
    if not lhw:
        return b + ["<p>Not synthesised for the studied box widths (<code>make synth-local BOX_BITS=K "
                    "CHILDREN=2</code>).</p>"]
    sp_all = sorted({sp for h in lhw.values() for sp in h["box_tests_per_s_per_chip"]})
    rows = [[u, h["box_tests_per_clock"], h["LUT4"], h["CCU2C"], h["TRELLIS_FF"], h["MULT18X18D"], h["latency"],
             h["units_per_chip"], h["limited_by"] or "–"]
            + [h["fmax_mhz"][sp]["median"] if sp in h["fmax_mhz"] else "–" for sp in sp_all]
            + [h["box_tests_per_s_per_chip"].get(sp, 0) / 1e9 for sp in sp_all] for u, h in lhw.items()]
    b.append(table(["unit", "children / query", "LUT4", "CCU2C", "FF", "MULT18X18D", "latency", "units/chip",
                    "limited by"] + [f"Fmax MHz speed {sp}" for sp in sp_all]
                   + [f"G box tests/s/chip speed {sp}" for sp in sp_all], rows))
    rows = []
    for n, lst in lder.items():
        for e in lst:
            rows.append([n, e["unit"], e["box_tests_per_ray"]]
                        + [e["rays_per_s_per_chip"].get(sp, 0) / 1e6 for sp in sp_all]
                        + [e["ratio_to_best_global"].get(sp, "–") for sp in sp_all])
    if rows:
        b.append("<p>Effective rays per second per chip of the local unit, and its ratio to the best global width "
                 "of the sweep that has been synthesised (same definition as above).</p>")
        b.append(table(["scene", "unit", "box tests/ray"] + [f"M rays/s/chip speed {sp}" for sp in sp_all]
                       + [f"local / best global, speed {sp}" for sp in sp_all], rows, left=2))
    return b


def write_html(args, outdir, scenes, studies, rtl, hw, der, cap, cap_src, plots, timing, fl=None,
               lhw=None, lder=None) -> None:
    body = ["<h1>Fixed-point Plücker box test: speed for accuracy</h1>",
            f"<p class='note'>Generated by <code>scripts/report.py</code> ({time.strftime('%Y-%m-%d %H:%M')}). "
            f"Study size {args.size}&times;{args.size}, widths <code>{rl.esc(args.widths)}</code>, order "
            f"{args.order}, {args.build} build. All figures are in <code>report.json</code>; per scene in "
            "<code>study_*.json</code>.</p>",
            "<h2>Definitions</h2><ul>"
            "<li><b>Reference</b>: the fixed-point path's batched traversal (same pixels, ray trees and ray "
            "clipping) with every box query answered by the exact test (rational arithmetic on the float "
            "inputs). Per-query figures are measured on its box queries.</li>"
            "<li><b>False miss</b>: exact hit, test miss. <b>False hit</b>: exact miss, test hit. "
            "<b>False-hit rate</b> = false hits / exact misses.</li>"
            "<li><b>Extra work</b> [%] = 100 &middot; (count<sub>W</sub> &minus; count<sub>exact</sub>) / "
            "count<sub>exact</sub>, counts summed over all rays of the render (camera, shadow, reflection, "
            "refraction) of a conservative render at width W. Box tests is the main figure: the RTL answers "
            "one box test per clock. The conservative test never misses, so the rays are the reference's.</li>"
            "<li><b>Nearest mode</b>: no margin (rounding to nearest), so boxes can be missed: wrong pixels "
            "(any RGB byte differs from the reference image) and false misses of its own box queries.</li>"
            "<li><b>Units per chip</b>: floor(capacity / use) for MULT18X18D, LUT4 slots (nextpnr's "
            "TRELLIS_COMB, which includes the carry cells) and FF, the smallest of the three; an upper bound "
            "with no routing or fill margin. Capacities: " + rl.esc(", ".join(f"{k} {v:,}" for k, v in cap.items()))
            + f" ({rl.esc(cap_src)}). <b>Box tests per second per unit</b> = Fmax (one per clock). "
            "<b>Effective rays per second per chip</b> = units &middot; Fmax / (box tests per ray at W).</li>"
            "</ul>"]
    body.append("<h2>Extra work and accuracy</h2>")
    for k in ("extra_work", "false_hits", "nearest"):
        body.append(plots[k])
    for n in scenes:
        if n in studies:
            body += scene_section(n, studies[n], rtl.get(n, []))

    body.append("<h2>Hardware per width (out/synth)</h2>")
    rows = []
    speeds = sorted({sp for v in hw.values() if v for sp in v["fmax_mhz"]})
    for key, v in hw.items():
        if not v:
            rows.append([key, ("span", 8 + 2 * len(speeds),
                               f"not measured (<code>make synth COORD_BITS={key.split('x')[0]} "
                               f"DIR_BITS={key.split('x')[1]}</code>, or <code>make report REPORT_SYNTH=1</code>)")])
            continue
        fm = [(f"{v['fmax_mhz'][sp]['median']:.1f} [{v['fmax_mhz'][sp]['min']:.1f}-{v['fmax_mhz'][sp]['max']:.1f}]"
               if sp in v["fmax_mhz"] else "–") for sp in speeds]
        chip = [(f"{v['box_tests_per_s_per_chip'][sp] / 1e9:.2f}" if sp in v["box_tests_per_s_per_chip"] else "–")
                for sp in speeds]
        rows.append([key, v["LUT4"], v["CCU2C"], v["TRELLIS_FF"], v["MULT18X18D"], v["placed_comb"], v["latency"],
                     v["units_per_chip"], v["limited_by"] or "–"] + fm + chip)
    body.append(table(["CxD", "LUT4", "CCU2C", "FF", "MULT18X18D", "LUT4 slots placed", "latency",
                       "units/chip", "limited by"] + [f"Fmax MHz speed {sp} median [min-max] = M box tests/s/unit"
                                                      for sp in speeds]
                      + [f"G box tests/s/chip speed {sp}" for sp in speeds], rows))
    if "hardware" in plots:
        body.append(plots["hardware"])
    if speeds:
        body.append("<h3>Effective rays per second per chip (after the extra work)</h3>")
        rows = []
        for n, per_w in der.items():
            for key, e in per_w.items():
                if "rays_per_s_per_chip" not in e:
                    continue
                rows.append([n, key, e["box_tests_per_ray"], e["reference_box_tests_per_ray"]]
                            + [e["rays_per_s_per_chip"].get(sp, 0) / 1e6 for sp in speeds]
                            + [e["rays_per_s_per_chip_without_extra_work"].get(sp, 0) / 1e6 for sp in speeds])
        body.append(table(["scene", "CxD", "box tests/ray", "exact box tests/ray"]
                          + [f"M rays/s/chip speed {sp}" for sp in speeds]
                          + [f"same without extra work, speed {sp}" for sp in speeds], rows, left=2))
    else:
        body.append("<p>Fmax not measured for any width of the sweep: no throughput figures.</p>")
    if args.local:
        body += local_hardware_section(lhw or {}, lder or {}, speeds)
    if fl:
        body += float_section(fl)
    body.append("<h2>Golden-model comparison</h2>")
    body.append("<p>RTL vs model: the Verilated RTL (<code>pluecker_sim query --check</code>) on every query of "
                "a traced fixed-point render (<code>pluecker trace --test fixed</code>), each answer compared "
                "with the model's <code>fixed_hit</code>. Model vs float: the conservative fixed test against "
                "float Plücker on the reference queries; float Plücker and Smits against exact.</p>")
    rows = []
    for n, lst in rtl.items():
        for r in lst:
            rows.append([n, rl.pair_name(r["coord_bits"], r["dir_bits"]), r.get("queries"), r.get("mismatches"),
                         ("html", '<span class="ok">identical</span>') if r.get("mismatches") == 0 and r["exit"] == 0
                         else ("html", f'<span class="bad">{rl.esc(r.get("error", "MISMATCH"))}</span>')])
    body.append(table(["scene", "CxD", "queries compared", "mismatches", "verdict"], rows, left=2)
                if rows else "<p>RTL check skipped (REPORT_RTL_WIDTHS empty or harness unavailable).</p>")
    rows = []
    for n, j in studies.items():
        q = j["queries"]
        for w in j["widths"]:
            vp = w["query"]["vs_pluecker"]
            rows.append([n, rl.pair_name(w["coord_bits"], w["dir_bits"]), q["count"], vp["fixed_hit_pluecker_miss"],
                         vp["fixed_miss_pluecker_hit"]])
    body.append(table(["scene", "CxD", "queries", "fixed hit, float Plücker miss", "fixed miss, float Plücker hit"],
                      rows, left=2))
    rows = [[n, j["queries"]["count"], j["queries"]["pluecker"]["false_misses"], j["queries"]["pluecker"]["false_hits"],
             j["queries"]["smits"]["false_misses"], j["queries"]["smits"]["false_hits"],
             j.get("direct_exact", {}).get("wrong_pixels")] for n, j in studies.items()]
    body.append(table(["scene", "queries", "Plücker false misses", "Plücker false hits", "Smits false misses",
                       "Smits false hits", "direct exact render vs reference: wrong px"], rows))
    body.append(f"<p class='note'>Run time: {timing['total']:.0f} s (studies {timing['studies']:.0f} s, "
                f"RTL checks {timing['rtl']:.0f} s, synthesis {timing['synth']:.0f} s).</p>")
    (outdir / "report.html").write_text(rl.page("Plücker box test: speed for accuracy", body))


def main(argv) -> int:
    args = parse_args(argv)
    t0 = time.monotonic()
    outdir = Path(args.out)
    outdir.mkdir(parents=True, exist_ok=True)
    plotdir = outdir / "plots"
    plotdir.mkdir(exist_ok=True)
    tmpdir = outdir / "tmp"
    tmpdir.mkdir(exist_ok=True)
    if not Path(args.cli).exists():
        raise SystemExit(f"report: {args.cli} not built (run 'make build')")
    widths = rl.parse_widths(args.widths)
    scenes = scene_list(args.scenes)
    timing = {"studies": 0.0, "rtl": 0.0, "synth": 0.0}

    studies = {}
    prior = None
    if args.from_json:
        with open(args.from_json) as f:
            prior = json.load(f)
        studies = prior["scenes"]
        scenes = prior["config"]["scenes"]
    present = []
    for spec in [] if prior else scenes:
        if "/" in spec and not (ROOT / spec).exists() and not Path(spec).exists():
            say(f"report: {spec}: absent, skipped")
            continue
        present.append(spec)
    if present:
        say(f"report: studies of {len(present)} scenes ({args.size}x{args.size}, widths {args.widths})")
        t = time.monotonic()
        done = run_jobs([jobs.Job(short_name(spec), "report:run_study", (args, spec, outdir)) for spec in present],
                        args, "studies", 1, study_line)
        studies.update(done)
        timing["studies"] += time.monotonic() - t
    if not studies:
        raise SystemExit("report: no scene to study")

    t = time.monotonic()
    synth_dir = Path(args.synth_dir)
    ensure_synth(args, widths, synth_dir)
    timing["synth"] = time.monotonic() - t
    cap, cap_src = rl.device_capacity(synth_dir)
    hw = {rl.pair_name(c, d): rl.hardware(synth_dir, c, d, cap) for c, d in widths}
    for k, v in hw.items():
        say(f"report: hardware {k}: " + ("not measured" if v is None else
            f"{v['units_per_chip']} units/chip ({v['limited_by']}), Fmax {v['fmax_mhz'] and {s: f['median'] for s, f in v['fmax_mhz'].items()}}"))
    der = derived(studies, hw)
    eq = equal_work_widths(studies, args.equal_work)
    fhw = float_hardware(synth_dir, cap)
    fixed_hw = fixed_hardware(synth_dir, [*FIXED_REFS, *eq.values()], cap, hw)
    fl = {"equal_work_percent": args.equal_work, "equal_work_widths": eq, "hardware": fhw,
          "fixed_hardware": fixed_hw, "comparison": comparison(fixed_hw, fhw),
          "rays": float_rays(studies, fixed_hw, fhw, eq)}
    for r in fl["comparison"]:
        say(f"report: {r['float']} against fixed {r['fixed']}: LUT4 slots x{fmt(r['area_placed_comb'], 2)}, "
            f"MULT18X18D x{fmt(r['area_MULT18X18D'], 2)}, box tests/s per chip fixed : float "
            + ", ".join(f"{fmt(v, 2)} (speed {sp})" for sp, v in sorted(r["chip_ratio"].items())))
    lhw = local_hardware(studies, synth_dir, cap)
    lder = local_derived(studies, lhw, der)

    t = time.monotonic()
    rtl: dict[str, list] = {}
    if prior:
        rtl = prior["rtl_vs_model"]
    rtl_widths = [] if prior else [int(x) for x in args.rtl_widths.replace(",", " ").split()]
    if rtl_widths:
        say(f"report: Verilator harnesses {', '.join(f'{w}x{w}' for w in rtl_widths)} (built when missing or out "
            "of date)")
        sims = run_jobs([jobs.Job(f"harness {w}x{w}", "report:sim_binary", (args, w)) for w in rtl_widths],
                        args, "harness", 1, lambda r: r[1] or str(r[0]))
        checks = [(w, name) for w in rtl_widths for name in studies]
        ok = [jobs.Job(f"rtl {name} {w}x{w}", "report:rtl_check",
                       (args, sims[f"harness {w}x{w}"][0], w, studies[name]["spec"], tmpdir))
              for w, name in checks if sims[f"harness {w}x{w}"][0] is not None]
        done = run_jobs(ok, args, "rtl", args.jobs, rtl_line) if ok else {}
        for w, name in checks:
            sim, why = sims[f"harness {w}x{w}"]
            rtl.setdefault(name, []).append(
                done[f"rtl {name} {w}x{w}"] if sim is not None else
                {"coord_bits": w, "dir_bits": w, "size": args.rtl_size, "exit": -1, "queries": None,
                 "mismatches": None, "error": why})
    timing["rtl"] = time.monotonic() - t

    plots = plot_all(studies, hw, der, plotdir, args.synth_dir)
    timing["total"] = time.monotonic() - t0
    write_html(args, outdir, scenes=[short_name(s) for s in scenes], studies=studies, rtl=rtl, hw=hw, der=der,
               cap=cap, cap_src=cap_src, plots=plots, timing=timing, fl=fl, lhw=lhw, lder=lder)
    report = {
        "config": {"size": args.size, "widths": args.widths, "order": args.order, "build": args.build,
                   "scenes": scenes, "local": args.local, "rtl_widths": args.rtl_widths, "rtl_size": args.rtl_size,
                   "synth": bool(args.synth)},
        "device": {"name": rl.DEVICE, "capacity": cap, "capacity_source": cap_src},
        "scenes": studies,
        "hardware": hw,
        "derived": der,
        "float32": fl,
        "local_hardware": lhw,
        "local_derived": lder,
        "rtl_vs_model": rtl,
        "timing_seconds": {k: round(v, 1) for k, v in timing.items()},
    }
    with open(outdir / "report.json", "w") as f:
        json.dump(report, f, indent=1)
        f.write("\n")
    try:
        tmpdir.rmdir()
    except OSError:
        pass
    bad = [r for lst in rtl.values() for r in lst if r.get("mismatches") not in (0, None) or
           (r.get("mismatches") is None and r["exit"] != -1)]
    say(f"report: {outdir / 'report.html'} and report.json in {timing['total']:.0f} s")
    if bad:
        say(f"report: RTL vs model MISMATCH in {len(bad)} checks (see the report)")
        return 1
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except rl.CommandFailed as e:
        sys.exit(f"report: {e}")
