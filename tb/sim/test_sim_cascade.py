# SPDX-License-Identifier: MIT
"""The cascade's Verilator harness (sim/cascade/, pluecker_sim_cascade): two
narrow TERNARY lanes at 8/8 escalating to one wide conservative unit at
16/16, checked against the golden model. A hardware-in-the-loop render of
the teapot (every batch set up in both formats, spread over the lanes, all
lanes streaming at once, also under back-pressure on every output stream
and idle inputs) must give the answers of `pluecker cascade` with the same
settings (escalated count included) and a PNG byte-identical to the model's
render on the wide format, which `pluecker cascade` finds pixel-identical to
its cascade render; `check` must find no mismatch with back-pressure, idle
inputs and resets mid-stream; bad settings and bad input must exit 2.

Environment: PLUECKER_MODEL_BUILD or PLUECKER_PY_DIR (set by `make test-tb`)
names the model's build directory (default build/model).
"""
import fcntl
import json
import os
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
MODEL_BUILD = Path(os.environ.get("PLUECKER_MODEL_BUILD") or os.environ.get("PLUECKER_PY_DIR")
                   or ROOT / "build" / "model")
CLI = MODEL_BUILD / "pluecker"
N, NC, ND, WC, WD = 2, 8, 8, 16, 16
BUILD_SH = [ROOT / "scripts" / "venv-exec.sh", ROOT / "sim" / "build.sh"]
SCENE = ["--scene", "teapot", "--size", "32", "--order", "dsa", "--quiet"]


def run(args, **kw):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, cwd=ROOT, **kw)


@pytest.fixture(scope="module")
def cascade():
    """Builds (or finds up to date) the harness; a lock keeps xdist workers apart."""
    assert (MODEL_BUILD / "pluecker-config.cmake").exists(), f"model libraries not built in {MODEL_BUILD} (make build)"
    out = ROOT / "build" / "sim" / f"cascade_{N}_{NC}x{ND}_{WC}x{WD}"
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, SIM_UNIT="cascade", CASCADE_N=str(N), NARROW_COORD_BITS=str(NC),
               NARROW_DIR_BITS=str(ND), WIDE_COORD_BITS=str(WC), WIDE_DIR_BITS=str(WD), MODE="conservative",
               MODEL_BUILD=str(MODEL_BUILD), SIM_OUT=str(out))
    with open(out / ".build.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        r = run(BUILD_SH, env=env)
    assert r.returncode == 0, f"sim/build.sh failed:\n{r.stdout}\n{r.stderr}"
    return out / "pluecker_sim_cascade"


@pytest.fixture(scope="module")
def model(tmp_path_factory):
    """The model's cascade figures and its render on the wide format."""
    d = tmp_path_factory.mktemp("model")
    c = run([CLI, "cascade", *SCENE, "--narrow", f"{NC}x{ND}", "--wide", f"{WC}x{WD}", "--threads", "1",
             "--json", d / "cascade.json"])
    assert c.returncode == 0, c.stdout + c.stderr
    r = run([CLI, "render", *SCENE, "--test", "fixed", "--coord-bits", WC, "--dir-bits", WD, "--mode", "conservative",
             "--out", d / "wide.png", "--stats", d / "wide.json"])
    assert r.returncode == 0, r.stdout + r.stderr
    figures = json.loads((d / "cascade.json").read_text())
    (row,) = figures["narrow"]
    # The cascade's image and the wide width's alone are both the reference's.
    assert row["cascade"]["wrong_pixels"] == 0 and figures["wide_alone"]["wrong_pixels"] == 0
    return row, d / "wide.png"


def render(sim, tmp_path, extra=()):
    r = run([sim, "render", *SCENE, *extra, "--out", tmp_path / "rtl.png", "--stats", tmp_path / "rtl.json"])
    assert r.returncode == 0, r.stdout + r.stderr
    assert " 0 mismatches" in r.stdout, r.stdout
    print(r.stdout.strip())
    return json.loads((tmp_path / "rtl.json").read_text())


def test_render_identical_to_model(cascade, model, tmp_path):
    row, wide_png = model
    rtl = render(cascade, tmp_path)
    c = run(["cmp", tmp_path / "rtl.png", wide_png])
    assert c.returncode == 0, "the cascade's render differs from the model's: " + c.stdout
    # The answers of `pluecker cascade`, counted on the RTL's answers.
    answers = rtl["cascade"]["answers"]
    assert answers == row["answers"] == rtl["cascade"]["model_answers"]
    assert answers["escalated"] == row["answers"]["escalated"] > 1000
    assert 0 < answers["escalated_fraction"] < 1
    # The same traversal, every box test of it through the cascade.
    for key in ("box_tests", "node_visits", "triangle_tests", "rays"):
        assert rtl[key] == row["cascade"][key], key
    section = rtl["rtl"]
    assert section["mismatches"] == 0 and section["queries"] == rtl["box_tests"]
    assert section["escalated"] == answers["escalated"]
    lanes = section["lanes"]
    assert len(lanes) == N
    # Narrow 8/8 LATENCY 6 and a clock in the lane's answer register; then a
    # clock in the escalation slot, one in the registered grant and one in
    # the wide unit's input register, wide 16/16 LATENCY 6.
    assert all(lane["certain_latency"] == 7 and lane["escalated_latency"] == 16 for lane in lanes)
    counts = [lane["queries"] for lane in lanes]
    assert sum(counts) == section["queries"] and max(counts) - min(counts) <= N
    assert sum(lane["escalated"] for lane in lanes) == answers["escalated"]
    assert section["queries"] > 1.5 * section["cycles"]


def test_render_backpressure(cascade, model, tmp_path):
    """Every stream out of step: each lane's out_ready_i, esc_ready_i and each
    lane's in_valid_i drawn on their own; image and answers stay the model's."""
    row, wide_png = model
    rtl = render(cascade, tmp_path, ["--ready", "0.5", "--valid", "0.7", "--seed", "5"])
    assert run(["cmp", tmp_path / "rtl.png", wide_png]).returncode == 0
    assert rtl["cascade"]["answers"] == row["answers"]
    assert rtl["rtl"]["stall_cycles"] > 0 and rtl["rtl"]["esc_stall_cycles"] > 0
    # Two lanes answer 1.74 queries a cycle with every output ready.
    assert rtl["rtl"]["queries"] < 1.3 * rtl["rtl"]["cycles"]


CHECK_RE = re.compile(r"check \(.*\): (\d+) (\w+) queries through (\d+) lanes? \(([\d ]+) a lane\), "
                      r"(\d+) missed a range cube, (\d+) escalated \(([\d.]+) %\), (\d+) hits, (\d+) mismatches, "
                      r"(\d+) cycles \(([\d.]+) queries a cycle\), (\d+) resets \((\d+) queries dropped")


def check(sim, *args):
    r = run([sim, "check", *args])
    assert r.returncode == 0, r.stdout + r.stderr
    m = CHECK_RE.search(r.stdout)
    assert m, r.stdout
    print(r.stdout.strip())
    return m


def test_check_backpressure_resets(cascade):
    m = check(cascade, "--n", "60000", "--kind", "all", "--seed", "9", "--ready", "0.5", "--valid", "0.8",
              "--reset-every", "250")
    queries, lanes, per_lane, escalated, mismatches = int(m[1]), int(m[3]), m[4].split(), int(m[6]), int(m[9])
    resets, dropped = int(m[12]), int(m[13])
    assert mismatches == 0 and lanes == N == len(per_lane)
    assert queries > 55000 and sum(map(int, per_lane)) == queries
    assert 0.05 * queries < escalated < 0.95 * queries
    assert resets > 50 and dropped > 0


def test_check_full_rate(cascade):
    """Every lane fed every clock, every output ready: more than one answer a
    cycle (the wide unit takes one escalation a clock)."""
    m = check(cascade, "--n", "40000", "--kind", "mixed")
    assert int(m[9]) == 0 and float(m[11]) > 1.2


def test_bad_settings():
    def expect2(settings, text):
        env = dict(os.environ, SIM_UNIT="cascade", MODEL_BUILD=str(MODEL_BUILD), **settings)
        r = run(BUILD_SH, env=env)
        assert r.returncode == 2, (settings, r.stdout, r.stderr)
        assert text in r.stderr, (settings, r.stderr)

    expect2({"WIDE_COORD_BITS": "6"}, "the wide widths must be at least the narrow ones")
    expect2({"NARROW_DIR_BITS": "12", "WIDE_DIR_BITS": "10"}, "is narrower than the narrow lanes")
    expect2({"NARROW_COORD_BITS": "5"}, "NARROW_COORD_BITS=5 is not an integer in 6..24")
    expect2({"WIDE_DIR_BITS": "25"}, "WIDE_DIR_BITS=25 is not an integer in 6..24")
    expect2({"CASCADE_N": "0"}, "CASCADE_N=0 is not an integer in 1..64")
    expect2({"CASCADE_N": "65"}, "CASCADE_N=65 is not an integer in 1..64")
    expect2({"MODE": "nearest"}, "the cascade is conservative only")
    expect2({"SIM_PIPELINE": "3"}, "SIM_PIPELINE=3 is not 0, 1 or 2")


def test_bad_input(cascade):
    def expect2(args, text):
        r = run([cascade, *args])
        assert r.returncode == 2, (args, r.stdout, r.stderr)
        assert text in r.stderr, (args, r.stderr)

    expect2(["render", "--size", "16", "--narrow", "10x10"],
            "make sim-cascade CASCADE_N=2 NARROW_COORD_BITS=10 NARROW_DIR_BITS=10 WIDE_COORD_BITS=16")
    expect2(["render", "--size", "16", "--wide", "12x12,16x16"], "one width pair")
    expect2(["render", "--size", "16", "--test", "fixed"], "unknown option --test")
    expect2(["render", "--size", "16", "--threads", "2"], "runs on one thread")
    expect2(["render", "--size", "16", "--ready", "0"], "option --ready: 0 is outside (0, 1]")
    expect2(["check", "--kind", "ports"], "random, extreme, mixed, setup, all")
    expect2(["check", "--valid", "1.5"], "option --valid: 1.5 is outside (0, 1]")
    expect2(["check", "--reset-every", "5"], "below 16 cycles")
    expect2(["frobnicate"], "unknown command")
