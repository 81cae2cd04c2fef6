# SPDX-License-Identifier: MIT
"""scripts/report.py in a tiny configuration (one scene, two widths, small
image, no synthesis, no RTL check): the HTML page and the JSON exist and hold
the expected figures; the hardware figures are derived from a summary.json
when one is present and reported as not measured otherwise."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
MODEL_BUILD = Path(os.environ.get("PLUECKER_MODEL_BUILD") or os.environ.get("PLUECKER_PY_DIR")
                   or ROOT / "build" / "model")
CLI = MODEL_BUILD / "pluecker"
sys.path.insert(0, str(ROOT / "scripts"))


def run_report(tmp_path, synth_dir, extra=()):
    assert CLI.exists(), f"{CLI} not built (make build)"
    out = tmp_path / "report"
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "report.py"), "--cli", str(CLI),
                        "--scenes", "sphere:500", "--widths", "8,16", "--size", "16", "--rtl-widths", "",
                        "--synth", "0", "--synth-dir", str(synth_dir), "--jobs", "1", "--out", str(out), *extra],
                       cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    return out, r.stdout


def test_tiny_report(tmp_path):
    out, log = run_report(tmp_path, tmp_path / "no_synth")
    assert "[report studies] [1/1] sphere:500: done in" in log  # progress printed
    html = (out / "report.html").read_text()
    assert html.startswith("<!DOCTYPE html>") and "data:image/png;base64," in html
    assert "not measured" in html
    j = json.loads((out / "report.json").read_text())
    for key in ("config", "device", "scenes", "hardware", "derived", "rtl_vs_model", "timing_seconds"):
        assert key in j, key
    s = j["scenes"]["sphere:500"]
    assert [(w["coord_bits"], w["dir_bits"]) for w in s["widths"]] == [(8, 8), (16, 16)]
    for w in s["widths"]:
        assert w["query"]["conservative"]["false_misses"] == 0
        assert w["work"]["wrong_pixels"] == 0
        for k in ("extra_percent", "per_ray", "checked"):
            assert k in w["work"], k
        assert "wrong_pixels" in w["nearest"]
        assert "vs_pluecker" in w["query"]
    assert s["widths"][0]["work"]["extra_percent"]["box_tests"] >= s["widths"][1]["work"]["extra_percent"]["box_tests"]
    for k in ("pluecker", "smits", "count"):
        assert k in s["queries"], k
    assert j["hardware"] == {"8x8": None, "16x16": None}
    for name in ("extra_work", "false_hits", "nearest"):
        assert (out / "plots" / f"{name}.png").stat().st_size > 1000


def test_hardware_figures_from_a_summary(tmp_path):
    import report_lib as rl
    synth = tmp_path / "synth"
    (synth / "16x16").mkdir(parents=True)
    summary = {"utilisation": {"LUT4": 300, "CCU2C": 400, "TRELLIS_FF": 1700, "MULT18X18D": 12,
                               "placed": {"TRELLIS_COMB": 1400, "TRELLIS_FF": 1700, "MULT18X18D": 12}},
               "latency": 6, "pnr": True, "fmax_mhz": {"8": {"median": 150.0, "min": 140.0, "max": 160.0, "seeds": 3}}}
    (synth / "16x16" / "summary.json").write_text(json.dumps(summary))
    cap, src = rl.device_capacity(synth)
    assert cap == rl.FALLBACK_CAPACITY and "nextpnr" in src
    h = rl.hardware(synth, 16, 16, cap)
    assert h["units_per_chip"] == 156 // 12 and h["limited_by"] == "MULT18X18D"
    assert h["box_tests_per_s_per_unit"]["8"] == pytest.approx(150e6)
    assert h["box_tests_per_s_per_chip"]["8"] == pytest.approx(13 * 150e6)
    assert rl.hardware(synth, 12, 12, cap) is None
    out, _ = run_report(tmp_path, synth)
    j = json.loads((out / "report.json").read_text())
    d = j["derived"]["sphere:500"]["16x16"]
    bpr = j["scenes"]["sphere:500"]["widths"][1]["work"]["per_ray"]["box_tests"]
    assert d["rays_per_s_per_chip"]["8"] == pytest.approx(13 * 150e6 / bpr)
    assert (out / "plots" / "hardware.png").exists()


def test_float32_comparison(tmp_path):
    """A binary32 unit's summary beside the fixed-point 16/16: the area and
    per-chip ratios and the rays per chip at the reference's box tests per
    ray, with the unit's false misses from the study."""
    synth = tmp_path / "synth"
    fixed = {"utilisation": {"LUT4": 400, "CCU2C": 400, "TRELLIS_FF": 1000, "MULT18X18D": 12,
                             "placed": {"TRELLIS_COMB": 1300, "TRELLIS_FF": 1000, "MULT18X18D": 12}},
             "latency": 6, "pnr": True, "fmax_mhz": {"8": {"median": 240.0, "min": 240.0, "max": 240.0, "seeds": 1}}}
    flt = {"utilisation": {"LUT4": 6000, "CCU2C": 3000, "TRELLIS_FF": 12000, "MULT18X18D": 12,
                           "placed": {"TRELLIS_COMB": 13000, "TRELLIS_FF": 12000, "MULT18X18D": 12}},
           "latency": 18, "pnr": True, "design": "pluecker_float_intersector", "mul_dsp": 1,
           "fmax_mhz": {"8": {"median": 120.0, "min": 120.0, "max": 120.0, "seeds": 1}}}
    for name, summ in (("16x16", fixed), ("float_dsp1", flt)):
        (synth / name).mkdir(parents=True)
        (synth / name / "summary.json").write_text(json.dumps(summ))
    out, log = run_report(tmp_path, synth)
    j = json.loads((out / "report.json").read_text())
    fl = j["float32"]
    assert set(fl["hardware"]) == {"float_dsp1"}
    u = fl["hardware"]["float_dsp1"]
    assert u["units_per_chip"] == 83640 // 13000 and u["limited_by"].startswith("LUT4")
    (cmp,) = [r for r in fl["comparison"] if r["fixed"] == "16x16"]
    assert cmp["area_placed_comb"] == pytest.approx(13000 / 1300)
    assert cmp["chip_ratio"]["8"] == pytest.approx((13 * 240e6) / (6 * 120e6))
    rows = {r["config"]: r for r in fl["rays"]["sphere:500"]}
    s = j["scenes"]["sphere:500"]
    assert rows["float_dsp1"]["box_tests_per_ray"] == s["reference"]["per_ray"]["box_tests"]
    assert rows["float_dsp1"]["false_misses"] == s["queries"]["f32_pluecker"]["false_misses"]
    assert rows["fixed 16x16"]["false_misses"] == 0
    assert "float_dsp1 against fixed 16x16" in log
    assert "Fixed point against float32" in (out / "report.html").read_text()


def test_report_in_a_browser(tmp_path):
    """The tiny report's page in headless Chromium (scripts/browser_check.py):
    every image decodes, every link resolves, a screenshot is written; and
    the same check finds each kind of breakage in a spoiled copy."""
    import browser_check as bc

    out, _ = run_report(tmp_path, tmp_path / "no_synth")
    page = out / "report.html"
    html = page.read_text()
    # A spoiled copy: a truncated PNG, a missing file, links to nothing.
    first = html.index("data:image/png;base64,") + len("data:image/png;base64,")
    spoiled = (html[:first] + html[first:first + 200] + html[html.index('"', first):]).replace(
        "</body>", '<img src="missing.png" alt="x"><a href="nowhere.html">a</a><a href="#no-such-id">b</a>'
                   '<a id="here" href="#here">c</a><a href="report.json">d</a></body>')
    (out / "spoiled.html").write_text(spoiled)
    good, bad = bc.check_pages([page, out / "spoiled.html"], tmp_path / "shots")

    n_images = html.count("<img ")
    assert good["images"] == n_images > 0 and not good["bad_images"] and not good["bad_links"], good
    shot = Path(good["screenshot"]).read_bytes()
    assert shot.startswith(b"\x89PNG") and len(shot) > 50_000, len(shot)
    assert len(bad["bad_images"]) == 2, bad["bad_images"]
    assert any("missing.png" in b for b in bad["bad_images"]), bad["bad_images"]
    assert any("PNG" in b or "decod" in b.lower() for b in bad["bad_images"]), bad["bad_images"]
    assert sorted(bad["bad_links"]) == sorted([f"nowhere.html ({out / 'nowhere.html'} does not exist)",
                                               "#no-such-id (no element with id 'no-such-id')"]), bad["bad_links"]
    # The command line fails on the spoiled page and names what is broken.
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "browser_check.py"), str(out / "spoiled.html"),
                        "--shots", str(tmp_path / "shots2")], capture_output=True, text=True, timeout=300)
    assert r.returncode == 1 and "broken image: missing.png" in r.stderr, r.stdout + r.stderr
    # and passes the good one.
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "browser_check.py"), str(page),
                        "--shots", str(tmp_path / "shots3")], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0 and (tmp_path / "shots3" / "report.png").is_file(), r.stdout + r.stderr
