# SPDX-License-Identifier: MIT
"""scripts/chip_effective.py on hand-written summaries (a placed array at
8/8, one 16/16 unit extrapolated, a placed chip of cascades whose wide units
keep up, one whose wide units saturate, one with plain wide units beside
its cascades, and a mixed array with two clocks) and a small scene: each figure
follows from the summary and the `pluecker cascade` JSON the script wrote;
unusable summaries are refused by name."""
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
SCENE = "sphere:500"


def fmax(mhz):
    return {"8": {"median": mhz, "min": mhz, "max": mhz, "seeds": 1}}


def write(folder: Path, summary: dict) -> Path:
    folder.mkdir(parents=True)
    (folder / "summary.json").write_text(json.dumps(summary))
    return folder


def array(tmp, c, d, units, mhz):
    return write(tmp / f"array_{c}x{d}", {
        "design": "pluecker_array", "name": f"array_{c}x{d}", "coord_bits": c, "dir_bits": d, "pnr": True,
        "fmax_mhz": fmax(mhz), "array": {"units": units, "box_tests_per_s": {"8": units * mhz * 1e6}}})


def unit(tmp, c, d, per_chip, mhz):
    return write(tmp / f"{c}x{d}", {
        "design": "pluecker_intersector", "name": f"{c}x{d}", "coord_bits": c, "dir_bits": d, "pnr": True,
        "fmax_mhz": fmax(mhz), "units_per_chip": per_chip, "box_tests_per_s_per_chip": {"8": per_chip * mhz * 1e6}})


def cascades(tmp, m, n, c, d, mhz, plain=0):
    name = f"cascade_{m}x{n}_{c}x{d}" + (f"_w{plain}" if plain else "")
    return write(tmp / name, {
        "design": "pluecker_cascade", "name": name, "coord_bits": c, "dir_bits": d,
        "wide_coord_bits": 16, "wide_dir_bits": 16, "n_narrow": n, "n_cascades": m, "n_wide_units": plain,
        "pnr": True, "fmax_mhz": fmax(mhz),
        "cascade_chip": {"cascades": m, "lanes": m * n, "wide_units": plain,
                         "box_tests_per_s": {"8": (m * n + plain) * mhz * 1e6}}})


def run(args, tmp_path):
    assert CLI.exists(), f"{CLI} not built (make build)"
    return subprocess.run([sys.executable, str(ROOT / "scripts" / "chip_effective.py"), "--cli", str(CLI),
                           "--scenes", SCENE, "--size", "16", "--jobs", "1", "--out", str(tmp_path / "out"),
                           *map(str, args)], cwd=ROOT, capture_output=True, text=True, timeout=600)


def test_figures_follow_from_the_summaries(tmp_path):
    chips = [array(tmp_path, 8, 8, 29, 137.0), unit(tmp_path, 16, 16, 13, 250.0),
             cascades(tmp_path, 6, 2, 8, 8, 120.0), cascades(tmp_path, 3, 6, 6, 6, 100.0),
             cascades(tmp_path, 2, 6, 6, 6, 110.0, plain=5)]
    # a mixed array with two clocks: 2 DSP units at 150 MHz, 3 fabric at 120
    two = write(tmp_path / "array_8x8_clk2", {
        "design": "pluecker_array", "name": "array_8x8_clk2", "coord_bits": 8, "dir_bits": 8, "pnr": True,
        "clocks": 2, "fmax_mhz": fmax(150.0), "fmax_lut_mhz": fmax(120.0),
        "array": {"units": 5, "box_tests_per_s": {"8": (2 * 150 + 3 * 120) * 1e6}}})
    chips.append(two)
    # a cascade chip with two clocks: 2 cascades of 6 6/6 lanes at 90 MHz
    # (clk_i), 5 plain 16/16 units at 200 MHz (clk_wide_i)
    two_c = write(tmp_path / "cascade_2x6_6x6_w5_clk2", {
        "design": "pluecker_cascade", "name": "cascade_2x6_6x6_w5_clk2", "coord_bits": 6, "dir_bits": 6,
        "wide_coord_bits": 16, "wide_dir_bits": 16, "n_narrow": 6, "n_cascades": 2, "n_wide_units": 5,
        "pnr": True, "clocks": 2, "fmax_mhz": fmax(90.0), "fmax_wide_mhz": fmax(200.0),
        "cascade_chip": {"cascades": 2, "lanes": 12, "wide_units": 5,
                         "box_tests_per_s": {"8": (12 * 90 + 5 * 200) * 1e6},
                         "lanes_box_tests_per_s": {"8": 12 * 90 * 1e6}}})
    chips.append(two_c)
    r = run(chips, tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "[chip-effective] [1/1] sphere:500: done in" in r.stdout  # progress
    out = tmp_path / "out"
    cj = json.loads((out / "cascade_sphere_500.json").read_text())  # the CLI's own figures
    narrow = {(n["coord_bits"], n["dir_bits"]): n for n in cj["narrow"]}
    assert set(narrow) == {(6, 6), (8, 8)} and (cj["wide"]["coord_bits"], cj["wide"]["dir_bits"]) == (16, 16)
    res = json.loads((out / "effective.json").read_text())
    got = res["scenes"][SCENE]["chips"]
    names = [c["name"] for c in res["chips"]]
    assert names == ["array_8x8 (placed)", "16x16 (extrapolated from one unit)", "cascade_6x2_8x8 (placed)",
                     "cascade_3x6_6x6 (placed)", "cascade_2x6_6x6_w5 (placed)",
                     "array_8x8_clk2 (placed, two clocks)", "cascade_2x6_6x6_w5_clk2 (placed, two clocks)"]

    x8 = narrow[(8, 8)]["narrow_alone"]["extra_percent"]["box_tests"]
    assert x8 > 0  # a narrow unit's false hits cost work on this scene
    e = got[names[0]]["8"]
    assert e["effective"] == pytest.approx(29 * 137e6 / (1 + x8 / 100))

    xw = cj["wide_alone"]["extra_percent"]["box_tests"]
    assert got[names[1]]["8"]["effective"] == pytest.approx(13 * 250e6 / (1 + xw / 100))

    # two lanes: the wide unit keeps up (2 x escalated share < 1)
    esc8 = narrow[(8, 8)]["answers"]["escalated_fraction"]
    xc8 = narrow[(8, 8)]["cascade"]["extra_percent"]["box_tests"]
    assert 2 * esc8 < 1
    e = got[names[2]]["8"]
    assert not e["wide_saturated"] and e["served"] == pytest.approx(12 * 120e6)
    assert e["effective"] == pytest.approx(12 * 120e6 / (1 + xc8 / 100))

    # six 6/6 lanes: the wide unit saturates, the chip serves wide rate / share
    esc6 = narrow[(6, 6)]["answers"]["escalated_fraction"]
    xc6 = narrow[(6, 6)]["cascade"]["extra_percent"]["box_tests"]
    assert 6 * esc6 > 1
    e = got[names[3]]["8"]
    assert e["wide_saturated"] and e["served"] == pytest.approx(3 * 100e6 / esc6)
    assert e["effective"] == pytest.approx(3 * 100e6 / esc6 / (1 + xc6 / 100))
    assert e["effective"] < 18 * 100e6

    # two such cascades (saturated) and five plain 16/16 units beside them:
    # the lanes serve what the two wide units take, the plain units their
    # own rate at the wide unit's extra work
    e = got[names[4]]["8"]
    assert e["raw"] == pytest.approx(17 * 110e6) and e["wide_saturated"]
    assert e["served"] == pytest.approx(2 * 110e6 / esc6) and e["plain_rate"] == pytest.approx(5 * 110e6)
    assert e["effective"] == pytest.approx(2 * 110e6 / esc6 / (1 + xc6 / 100) + 5 * 110e6 / (1 + xw / 100))

    # two clocks: the summary's rate (the sum over both clocks) at the 8/8 extra work
    assert got[names[5]]["8"]["effective"] == pytest.approx(660e6 / (1 + x8 / 100))
    assert res["chips"][5]["fmax_mhz"] == {"8": 150.0} and res["chips"][5]["fmax_lut_mhz"] == {"8": 120.0}

    # a cascade chip with two clocks: the lanes (and their wide units) at
    # clk_i's 90 MHz, the plain units at clk_wide_i's 200 MHz, not the
    # raw rate split by unit count
    e = got[names[6]]["8"]
    assert e["raw"] == pytest.approx(2080e6) and e["wide_saturated"]
    assert e["served"] == pytest.approx(2 * 90e6 / esc6) and e["plain_rate"] == pytest.approx(5 * 200e6)
    assert e["effective"] == pytest.approx(2 * 90e6 / esc6 / (1 + xc6 / 100) + 5 * 200e6 / (1 + xw / 100))
    assert res["chips"][6]["fmax_mhz"] == {"8": 90.0} and res["chips"][6]["fmax_wide_mhz"] == {"8": 200.0}

    md = (out / "effective.md").read_text()
    assert "| array_8x8 (placed) | 8/8 | 3.97 G |" in md and "wide saturated" in md
    assert "| cascade_2x6_6x6_w5 (placed) | 6/6 > 16/16, + 5 x 16/16 | 1.87 G |" in md
    assert (out / "effective_speed8.png").stat().st_size > 1000


def test_unusable_summaries_are_refused(tmp_path):
    r = run([tmp_path / "nowhere"], tmp_path)
    assert r.returncode != 0 and "nowhere" in r.stderr and "cannot read" in r.stderr

    yosys_only = write(tmp_path / "y", {"design": "pluecker_intersector", "coord_bits": 8, "dir_bits": 8,
                                        "pnr": False, "fmax_mhz": {}})
    r = run([yosys_only], tmp_path)
    assert r.returncode != 0 and "no placed-and-routed Fmax" in r.stderr and "summary.json" in r.stderr

    other = write(tmp_path / "f", {"design": "pluecker_float_intersector", "pnr": True, "fmax_mhz": fmax(90.0)})
    r = run([other], tmp_path)
    assert r.returncode != 0 and "pluecker_float_intersector" in r.stderr

    bad = tmp_path / "bad"
    bad.mkdir()
    (bad / "summary.json").write_text("{ not json")
    r = run([bad], tmp_path)
    assert r.returncode != 0 and "not JSON" in r.stderr

    r = run([array(tmp_path, 24, 24, 3, 150.0)], tmp_path)
    assert r.returncode != 0 and "wider than the wide width 16x16" in r.stderr
