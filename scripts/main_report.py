#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The main job's short report (out/report/main.html): the golden-model
render and the hardware-in-the-loop render through the Verilated RTL side by
side, their statistics, the byte-for-byte comparison, and a small width
sweep (`pluecker study`) of extra work and false hits.

Writes the page whatever the verdict; the Makefile's `cmp` decides the exit
status of `make`. Exit 1 here only when an input is missing."""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import report_lib as rl  # noqa: E402
from report_lib import fmt, table  # noqa: E402


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--scene", default="teapot")
    p.add_argument("--cli", required=True)
    p.add_argument("--model-png", required=True)
    p.add_argument("--model-json", required=True)
    p.add_argument("--rtl-png", required=True)
    p.add_argument("--rtl-json", required=True)
    p.add_argument("--out", required=True, help="HTML page; the JSON goes beside it")
    p.add_argument("--sweep-size", type=int, default=64)
    p.add_argument("--sweep-widths", default="8:24:4")
    p.add_argument("--order", default="dsa")
    p.add_argument("--jobs", type=int, default=2)
    return p.parse_args(argv)


def pixel_diff(a: Path, b: Path) -> tuple[int | None, bytes | None]:
    """Pixels whose RGB differs, and a difference image (PNG) when any do."""
    try:
        import numpy as np
        from PIL import Image
    except ImportError:
        return None, None
    x = np.asarray(Image.open(a).convert("RGB"), dtype=np.int16)
    y = np.asarray(Image.open(b).convert("RGB"), dtype=np.int16)
    if x.shape != y.shape:
        return None, None
    diff = np.any(x != y, axis=2)
    n = int(diff.sum())
    if n == 0:
        return 0, None
    import io
    img = np.zeros(x.shape, dtype=np.uint8)
    img[diff] = (255, 40, 40)
    buf = io.BytesIO()
    Image.fromarray(img).save(buf, format="PNG")
    return n, buf.getvalue()


def stats_rows(m: dict, r: dict) -> list[list]:
    rows = []
    for k in ("camera", "shadow", "reflection", "refraction", "total"):
        rows.append([f"{k} rays", m["rays"][k], r["rays"][k], m["rays"][k] == r["rays"][k]])
    for k in ("node_visits", "box_tests", "triangle_tests"):
        rows.append([k.replace("_", " "), m[k], r[k], m[k] == r[k]])
        rows.append([f"{k.replace('_', ' ')} per ray", m[k] / max(1, m["rays"]["total"]),
                     r[k] / max(1, r["rays"]["total"]), m[k] == r[k]])
    rows.append(["render ms", m["render_ms"], r["render_ms"], ""])
    return rows


def main(argv) -> int:
    a = parse_args(argv)
    t0 = time.monotonic()
    for p in (a.model_png, a.model_json, a.rtl_png, a.rtl_json):
        if not Path(p).exists():
            print(f"main_report: {p} missing", file=sys.stderr)
            return 1
    out = Path(a.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    m = json.loads(Path(a.model_json).read_text())
    r = json.loads(Path(a.rtl_json).read_text())
    same_bytes = Path(a.model_png).read_bytes() == Path(a.rtl_png).read_bytes()
    npix, diff_png = pixel_diff(Path(a.model_png), Path(a.rtl_png))
    rtl = r.get("rtl", {})

    print(f"main_report: width sweep at {a.sweep_size}x{a.sweep_size}, widths {a.sweep_widths}", flush=True)
    sweep_json = out.parent / "main_study.json"
    rl.run([a.cli, "study", "--scene", a.scene, "--size", a.sweep_size, "--widths", a.sweep_widths,
            "--order", a.order, "--threads", a.jobs, "--no-direct", "--quiet", "--json", sweep_json])
    sweep = json.loads(sweep_json.read_text())

    fx = m.get("fixed", {})
    verdict = ('<p class="ok">IDENTICAL: the RTL render is byte-for-byte the golden model\'s '
               f'({Path(a.model_png).stat().st_size:,} bytes), {rtl.get("queries", 0):,} box queries through '
               f'the RTL, {rtl.get("mismatches", "?")} mismatches against the model.</p>') if same_bytes else (
               f'<p class="bad">DIFFERENT: the PNG files differ; {npix if npix is not None else "?"} pixels differ; '
               f'{rtl.get("mismatches", "?")} RTL answers differ from the model.</p>')
    body = [f"<h1>Main job: {rl.esc(m['scene'])}, golden model vs RTL</h1>",
            f"<p class='note'>{time.strftime('%Y-%m-%d %H:%M')}. {m['width']}&times;{m['height']} pixels, "
            f"{m['triangles']:,} triangles, {m['build']} BVH ({m['bvh']['nodes']:,} nodes), order {m['order']}, "
            f"fixed-point COORD_BITS={fx.get('coord_bits')} DIR_BITS={fx.get('dir_bits')} "
            f"({fx.get('mode')}). Model: <code>pluecker render --test fixed</code>; RTL: "
            f"<code>pluecker_sim render</code> (the Verilated <code>rtl/pluecker_intersector.sv</code> answers "
            f"every box test).</p>",
            "<h2>Verdict</h2>", verdict,
            '<div class="imgs">', rl.img_file(Path(a.model_png), "golden model (pluecker render --test fixed)"),
            rl.img_file(Path(a.rtl_png), "RTL in the loop (pluecker_sim render)")]
    if diff_png:
        body.append(f'<figure><img src="{rl.png_data_uri(diff_png)}" alt="difference">'
                    f'<figcaption>differing pixels (red)</figcaption></figure>')
    body.append("</div>")
    body.append("<h2>Statistics</h2>")
    body.append(table(["", "model", "RTL", "equal"], stats_rows(m, r)))
    if rtl:
        body.append(table(["RTL harness", "value"],
                          [["box queries through the RTL", rtl.get("queries")],
                           ["answers differing from the model", rtl.get("mismatches")],
                           ["batches", rtl.get("batches")], ["clock cycles", rtl.get("cycles")],
                           ["stall cycles", rtl.get("stall_cycles")], ["max in flight", rtl.get("max_in_flight")],
                           ["simulated queries per second (RTL loop)", rtl.get("queries_per_second")],
                           ["wall seconds", rtl.get("wall_seconds")]]))

    body.append(f"<h2>Width sweep ({sweep['width']}&times;{sweep['height']})</h2>")
    body.append("<p>Extra work = 100 &middot; (box tests at W &minus; box tests with exact answers) / box tests "
                "with exact answers, over all rays of the render; false-hit rate = false hits / exact misses "
                "on the exact traversal's box queries; nearest mode drops the conservative margin. Definitions: "
                "<code>model/rt/include/pluecker/study.hpp</code>; the full sweep is <code>make report</code>.</p>")
    rows = []
    for w in sweep["widths"]:
        rows.append([rl.pair_name(w["coord_bits"], w["dir_bits"]), w["query"]["conservative"]["false_misses"],
                     w["query"]["conservative"]["false_hit_rate"], w["work"]["extra_percent"]["box_tests"],
                     w["work"]["extra_percent"]["node_visits"], w["work"]["extra_percent"]["triangle_tests"],
                     w["nearest"]["wrong_pixels"], w["query"]["nearest"]["false_misses"]])
    body.append(table(["CxD", "false misses", "false-hit rate", "extra box tests %", "extra node visits %",
                       "extra tri tests %", "nearest: wrong px", "nearest: false misses"], rows))
    plt = rl.mpl()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.4))
    xs = [w["coord_bits"] for w in sweep["widths"]]
    a1.plot(xs, [w["work"]["extra_percent"]["box_tests"] for w in sweep["widths"]], marker="o")
    a1.set_yscale("symlog", linthresh=0.01)
    a1.set_title("Extra box tests (conservative)")
    a1.set_ylabel("%")
    a2.plot(xs, [w["query"]["conservative"]["false_hit_rate"] or float("nan") for w in sweep["widths"]],
            marker="o", label="conservative")
    a2.plot(xs, [w["query"]["nearest"]["false_hit_rate"] or float("nan") for w in sweep["widths"]],
            marker="s", ls="--", label="nearest")
    a2.set_yscale("log")
    a2.set_title("False-hit rate per query (zeros not drawn)")
    a2.legend(fontsize=8)
    for ax in (a1, a2):
        ax.set_xlabel("COORD_BITS = DIR_BITS")
        ax.set_xticks(xs)
    h, data = rl.fig_html(fig, "width sweep")
    (out.parent / "main_sweep.png").write_bytes(data)
    body.append(h)
    out.write_text(rl.page(f"Main job: {m['scene']}", body))
    summary = {"scene": m["scene"], "identical_png": same_bytes, "differing_pixels": npix,
               "rtl": rtl, "model_stats": m, "rtl_stats": r, "sweep": str(sweep_json),
               "seconds": round(time.monotonic() - t0, 1)}
    out.with_suffix(".json").write_text(json.dumps(summary, indent=1) + "\n")
    print(f"main_report: {out} ({'identical' if same_bytes else 'DIFFERENT'})", flush=True)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except rl.CommandFailed as e:
        sys.exit(f"main_report: {e}")
