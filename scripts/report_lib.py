# SPDX-License-Identifier: MIT
"""Helpers shared by scripts/report.py (`make report`),
scripts/main_report.py (the main job's short report) and
scripts/chip_effective.py (`make chip-effective`): the scene list, running
the CLI with progress, the hardware figures of
out/synth/<C>x<D>/summary.json and what follows from them, and a small
self-contained HTML writer (tables, base64 PNG images and matplotlib
plots)."""
from __future__ import annotations

import base64
import html
import io
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# LFE5U-85F capacities used when no nextpnr report of the width is at hand.
# Source: nextpnr-ecp5 --85k, report.json "utilization" -> "available"
# (MULT18X18D 156, TRELLIS_COMB 83,640 LUT4 slots, TRELLIS_FF 83,640), the
# same figures as out/synth/16x16/pnr/*/report.json of this project.
DEVICE = "LFE5U-85F"
FALLBACK_CAPACITY = {"MULT18X18D": 156, "TRELLIS_COMB": 83640, "TRELLIS_FF": 83640}


def say(msg: str) -> None:
    print(msg, flush=True)


class CommandFailed(RuntimeError):
    """A command run by run() failed (an exception, not SystemExit, so that
    a job of scripts/jobs.py that runs it fails by name)."""


def run(cmd: list, *, check: bool = True, capture: bool = False, env=None, cwd=ROOT,
        echo: bool = True) -> subprocess.CompletedProcess:
    """Runs a command from the project root; stderr passes through (progress)
    unless captured."""
    cmd = [str(c) for c in cmd]
    if echo:
        say("  $ " + " ".join(cmd))
    t0 = time.monotonic()
    r = subprocess.run(cmd, cwd=cwd, env=env, text=True,
                       stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE if capture else None)
    r.seconds = time.monotonic() - t0
    if check and r.returncode != 0:
        tail = "\n".join(((r.stdout or "") + (r.stderr or "")).strip().splitlines()[-10:])
        raise CommandFailed(f"command failed (exit {r.returncode}): {' '.join(cmd)}" + (f"\n{tail}" if tail else ""))
    return r


SHARED_SCENES = ROOT.parent / "shared" / "scenes"


def scene_list(spec: str, who: str = "report") -> list[str]:
    """A comma list of scene specs, or 'auto': teapot, spheres and the
    .obj/.ply files of ../shared/scenes/ when that folder is present."""
    if spec != "auto":
        return [s for s in spec.split(",") if s]
    scenes = ["teapot", "spheres"]
    if SHARED_SCENES.is_dir():
        files = sorted(f for f in SHARED_SCENES.iterdir() if f.suffix.lower() in (".obj", ".ply"))
        scenes += [os.path.relpath(f, ROOT) for f in files]
        say(f"{who}: scenes from {SHARED_SCENES}: {', '.join(f.name for f in files) or 'none'}")
    else:
        say(f"{who}: {SHARED_SCENES} absent: built-in scenes only")
    return scenes


def is_scene_file(spec: str) -> bool:
    """A mesh file's path, not a built-in scene (teapot, spheres, sphere:N)."""
    return "/" in spec or "." in spec


def short_name(spec: str) -> str:
    return Path(spec).name if is_scene_file(spec) else spec


def parse_widths(spec: str) -> list[tuple[int, int]]:
    """The CLI's --widths syntax: A:B[:S] | W,W | CxD,CxD."""
    spec = spec.strip()
    if ":" in spec:
        parts = [int(p) for p in spec.split(":")]
        a, b = parts[0], parts[1]
        step = parts[2] if len(parts) > 2 else 1
        return [(w, w) for w in range(a, b + 1, step)]
    out = []
    for item in spec.replace(" ", ",").split(","):
        if not item:
            continue
        if "x" in item:
            c, d = item.split("x")
            out.append((int(c), int(d)))
        else:
            out.append((int(item), int(item)))
    return out


def rel(path) -> str:
    """A path relative to the project root when inside it."""
    p = Path(path).resolve()
    return str(p.relative_to(ROOT)) if p.is_relative_to(ROOT) else str(p)


def pair_name(c: int, d: int) -> str:
    return f"{c}x{d}"


# --------------------------------------------------------------------------
# Hardware figures

def read_json(path: Path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def device_capacity(synth_dir: Path) -> tuple[dict, str]:
    """Capacities from a nextpnr report of any measured width, else the
    fallback constants. Returns (capacity, source)."""
    for rep in sorted(synth_dir.glob("*/pnr/*/report.json")):
        j = read_json(rep)
        if j and "utilization" in j:
            u = j["utilization"]
            cap = {k: u[k]["available"] for k in FALLBACK_CAPACITY if k in u}
            if len(cap) == len(FALLBACK_CAPACITY):
                return cap, f"nextpnr report {rel(rep)}"
    return dict(FALLBACK_CAPACITY), "nextpnr-ecp5 --85k report (utilization.available), recorded in scripts/report_lib.py"


def hardware(synth_dir: Path, c: int, d: int, capacity: dict) -> dict | None:
    """Cost and derived throughput of one width pair from `make synth`'s
    summary; None when it has not been measured."""
    return hardware_of(synth_dir, pair_name(c, d), capacity)


def hardware_of(synth_dir: Path, name: str, capacity: dict) -> dict | None:
    """The same for any synthesised unit: out/synth/<name>/summary.json
    (a width pair CxD, a binary32 unit, e.g. float_dsp4, or a local unit,
    e.g. local_k8_d11_g32_c2)."""
    s = read_json(synth_dir / name / "summary.json")
    if s is None:
        return None
    u = s.get("utilisation", {})
    placed = u.get("placed", {})
    comb = placed.get("TRELLIS_COMB")
    ff = placed.get("TRELLIS_FF", u.get("TRELLIS_FF"))
    mult = u.get("MULT18X18D", placed.get("MULT18X18D", 0))
    limits = {}
    if mult:
        limits["MULT18X18D"] = capacity["MULT18X18D"] // mult
    if comb:
        limits["LUT4 slots (TRELLIS_COMB)"] = capacity["TRELLIS_COMB"] // comb
    if ff:
        limits["FF"] = capacity["TRELLIS_FF"] // ff
    units = min(limits.values()) if limits else None
    limited_by = min(limits, key=limits.get) if limits else None
    fmax = {sp: f["median"] for sp, f in (s.get("fmax_mhz") or {}).items()}
    # Box tests a unit answers per clock: one, or the local unit's CHILDREN.
    per_clock = s.get("box_tests_per_clock") or 1
    per_unit = {sp: f * 1e6 * per_clock for sp, f in fmax.items()}
    per_chip = {sp: v * units for sp, v in per_unit.items()} if units else {}
    return {
        "summary": rel(synth_dir / name / "summary.json"),
        "design": s.get("design"), "mul_dsp": s.get("mul_dsp"), "conservative": s.get("conservative"),
        "pnr": bool(s.get("pnr")),
        "LUT4": u.get("LUT4"), "CCU2C": u.get("CCU2C"), "TRELLIS_FF": u.get("TRELLIS_FF"),
        "dut_ff": u.get("dut_ff"), "harness_ff": u.get("harness_ff"), "MULT18X18D": mult,
        "placed_comb": comb, "placed_ff": ff,
        "latency": s.get("latency"),
        "fmax_mhz": s.get("fmax_mhz") or {},
        "units_per_chip": units, "units_limits": limits, "limited_by": limited_by,
        "box_tests_per_clock": per_clock,
        "box_tests_per_s_per_unit": per_unit,
        "box_tests_per_s_per_chip": per_chip,
    }


# --------------------------------------------------------------------------
# HTML

CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;max-width:1180px;margin:24px auto;
padding:0 16px;color:#1c2430;line-height:1.45}
h1{font-size:1.6em;margin-bottom:.2em}h2{margin-top:1.8em;border-bottom:1px solid #d7dde5;padding-bottom:4px}
table{border-collapse:collapse;margin:10px 0 18px;font-size:.88em}
th,td{border:1px solid #d0d7e0;padding:3px 7px;text-align:right}th{background:#eef2f7}
td.l,th.l{text-align:left}.ok{color:#11702f;font-weight:600}.bad{color:#b3261e;font-weight:600}
.note{color:#555;font-size:.9em}img.plot{max-width:100%;border:1px solid #e3e7ee;margin:6px 0}
.imgs{display:flex;gap:16px;flex-wrap:wrap}.imgs figure{margin:0}figcaption{font-size:.85em;color:#444}
code{background:#f3f5f8;padding:0 3px}
"""


def esc(x) -> str:
    return html.escape(str(x))


def fmt(v, digits: int = 3) -> str:
    if v is None:
        return "–"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, int):
        return f"{v:,}"
    if isinstance(v, float):
        if math.isinf(v) or math.isnan(v):
            return str(v)
        if v == 0:
            return "0"
        if abs(v) < 0.01:
            return f"{v:.2e}"
        return f"{v:,.{digits}f}"
    return str(v)


def table(head: list[str], rows: list[list], left: int = 1) -> str:
    """HTML table; the first `left` columns are left-aligned. Cells that are
    already HTML can be passed as ('html', text), or ('span', n, html) over
    n columns."""
    def cell(tag, v, i):
        cls = ' class="l"' if i < left else ""
        if isinstance(v, tuple) and v and v[0] == "html":
            return f"<{tag}{cls}>{v[1]}</{tag}>"
        if isinstance(v, tuple) and v and v[0] == "span":  # ("span", columns, html)
            return f'<{tag} class="l" colspan="{v[1]}">{v[2]}</{tag}>'

        return f"<{tag}{cls}>{esc(v if isinstance(v, str) else fmt(v))}</{tag}>"
    out = ["<table><tr>" + "".join(cell("th", h, i) for i, h in enumerate(head)) + "</tr>"]
    for r in rows:
        out.append("<tr>" + "".join(cell("td", v, i) for i, v in enumerate(r)) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def png_data_uri(data: bytes) -> str:
    return "data:image/png;base64," + base64.b64encode(data).decode("ascii")


def img_file(path: Path, caption: str, width: int | None = None) -> str:
    w = f' width="{width}"' if width else ""
    return (f'<figure><img src="{png_data_uri(Path(path).read_bytes())}"{w} '
            f'style="image-rendering:pixelated" alt="{esc(caption)}"><figcaption>{esc(caption)}</figcaption></figure>')


def fig_html(fig, alt: str) -> str:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, bbox_inches="tight")
    import matplotlib.pyplot as plt
    plt.close(fig)
    return f'<img class="plot" src="{png_data_uri(buf.getvalue())}" alt="{esc(alt)}">', buf.getvalue()


def page(title: str, body: list[str]) -> str:
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{esc(title)}</title><style>{CSS}</style></head><body>\n"
            + "\n".join(body) + "\n</body></html>\n")


def mpl():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams.update({"figure.figsize": (7.2, 4.0), "axes.grid": True, "grid.alpha": 0.3,
                         "font.size": 10, "axes.spines.top": False, "axes.spines.right": False})
    return plt
