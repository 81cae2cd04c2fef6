# SPDX-License-Identifier: MIT
"""The array's Verilator harness (sim/array/, pluecker_sim_array): a mixed
array of one DSP and one fabric unit and an all-fabric array of three, both
at 8/8 conservative, and a 6/6 array of one DSP and one block-RAM table
unit (PIPELINE 2), checked against the golden model: a
hardware-in-the-loop render (every batch spread over the lanes, all lanes
streaming at once, also under back-pressure and idle inputs) must be
byte-identical to `pluecker render --test fixed` with the same widths and
traversal; `check` must find no mismatch on every query and operand kind
with back-pressure, idle inputs and resets mid-stream; bad settings and bad
input must exit 2.

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
C, D = 8, 8
BUILD_SH = [ROOT / "scripts" / "venv-exec.sh", ROOT / "sim" / "build.sh"]


def run(args, **kw):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, cwd=ROOT, **kw)


def build_array(n_dsp, n_lut, n_rom=0, c=C, d=D, pipeline=0):
    """Builds (or finds up to date) the harness; a lock keeps xdist workers apart."""
    assert (MODEL_BUILD / "pluecker-config.cmake").exists(), f"model libraries not built in {MODEL_BUILD} (make build)"
    out = ROOT / "build" / "sim" / (f"array_{n_dsp}x{n_lut}{f'x{n_rom}' if n_rom else ''}_{c}x{d}"
                                    + (f"_p{pipeline}" if pipeline else ""))
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, SIM_UNIT="array", ARRAY_DSP=str(n_dsp), ARRAY_LUT=str(n_lut), ARRAY_ROM=str(n_rom),
               COORD_BITS=str(c), DIR_BITS=str(d), SIM_PIPELINE=str(pipeline), MODE="conservative",
               MODEL_BUILD=str(MODEL_BUILD), SIM_OUT=str(out))
    with open(out / ".build.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        r = run(BUILD_SH, env=env)
    assert r.returncode == 0, f"sim/build.sh failed:\n{r.stdout}\n{r.stderr}"
    return out / "pluecker_sim_array"


ARRAYS = {"1x1": (1, 1), "0x3": (0, 3)}


@pytest.fixture(scope="module", params=list(ARRAYS))
def array(request):
    n_dsp, n_lut = ARRAYS[request.param]
    return build_array(n_dsp, n_lut), n_dsp, n_lut


@pytest.fixture(scope="module")
def mixed():
    return build_array(1, 1)


def render_pair(sim, tmp_path, extra=(), c=C, d=D):
    """The array's render and the model's, same options; both stats."""
    common = ["--scene", "teapot", "--size", "32", "--order", "dsa", "--quiet"]
    r = run([sim, "render", *common, *extra, "--out", tmp_path / "rtl.png", "--stats", tmp_path / "rtl.json"])
    assert r.returncode == 0, r.stdout + r.stderr
    assert " 0 mismatches" in r.stdout, r.stdout
    m = run([CLI, "render", "--test", "fixed", "--coord-bits", c, "--dir-bits", d, "--mode", "conservative", *common,
             "--out", tmp_path / "model.png", "--stats", tmp_path / "model.json"])
    assert m.returncode == 0, m.stdout + m.stderr
    c = run(["cmp", tmp_path / "rtl.png", tmp_path / "model.png"])
    assert c.returncode == 0, "the array's render differs from the model's: " + c.stdout
    return json.loads((tmp_path / "rtl.json").read_text()), json.loads((tmp_path / "model.json").read_text())


def test_render_identical_to_model(array, tmp_path):
    sim, n_dsp, n_lut = array
    rtl, model = render_pair(sim, tmp_path)
    # Same traversal; every box test of it went through the array.
    for key in ("rays", "node_visits", "box_tests", "triangle_tests", "batch"):
        assert rtl[key] == model[key], key
    section = rtl["rtl"]
    assert section["mismatches"] == 0
    assert section["queries"] == model["box_tests"] > 20000
    assert section["units"] == {"dsp": n_dsp, "lut": n_lut, "rom": 0}
    lanes = section["lanes"]
    assert [lane["mul_style"] for lane in lanes] == ["dsp"] * n_dsp + ["lut"] * n_lut
    assert all(lane["latency"] == 6 for lane in lanes)
    # Round-robin: every lane takes its share, and the lanes run side by side.
    counts = [lane["queries"] for lane in lanes]
    assert sum(counts) == section["queries"] and max(counts) - min(counts) <= len(lanes)
    assert section["queries"] > 0.85 * len(lanes) * section["cycles"]
    assert section["max_in_flight"] > len(lanes)


def test_render_backpressure(mixed, tmp_path):
    """Lanes out of step: each lane's out_ready_i and in_valid_i drawn on
    their own; the image and the traversal stay the model's."""
    rtl, model = render_pair(mixed, tmp_path, ["--ready", "0.5", "--valid", "0.7", "--seed", "5"])
    assert rtl["box_tests"] == model["box_tests"] == rtl["rtl"]["queries"]
    assert rtl["rtl"]["stall_cycles"] > 0
    assert rtl["rtl"]["queries"] < rtl["rtl"]["cycles"]


CHECK_RE = re.compile(r"check \(.*\): (\d+) (\w+) queries through (\d+) lanes \(([\d ]+) a lane\), "
                      r"(\d+) missed the range cube, (\d+) hits, (\d+) mismatches, (\d+) cycles .*, "
                      r"(\d+) resets \((\d+) queries dropped")


@pytest.mark.parametrize("kind", ["all", "boundary"])
def test_check_backpressure_resets(array, kind):
    sim, n_dsp, n_lut = array
    r = run([sim, "check", "--n", "60000", "--kind", kind, "--seed", "9", "--ready", "0.5", "--valid", "0.8",
             "--reset-every", "250"])
    assert r.returncode == 0, r.stdout + r.stderr
    m = CHECK_RE.search(r.stdout)
    assert m, r.stdout
    queries, lanes, per_lane, hits, mismatches = int(m[1]), int(m[3]), m[4].split(), int(m[6]), int(m[7])
    resets, dropped = int(m[9]), int(m[10])
    print(r.stdout.strip())
    assert mismatches == 0 and lanes == n_dsp + n_lut == len(per_lane)
    assert queries > 55000 and sum(map(int, per_lane)) == queries
    assert 0.2 * queries < hits < 0.8 * queries
    assert resets > 50 and dropped > 0


def test_check_full_rate(mixed):
    """Every lane fed every clock, every output ready: N answers a cycle."""
    r = run([mixed, "check", "--n", "40000", "--kind", "mixed"])
    assert r.returncode == 0, r.stdout + r.stderr
    assert " 0 mismatches" in r.stdout and "(2.00 queries a cycle)" in r.stdout, r.stdout


def test_bench_short(mixed):
    r = run([mixed, "bench", "--n", "50000"])
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.count(" 0 mismatches") == 3, r.stdout


def test_render_through_table_units(tmp_path):
    """One DSP and one block-RAM table unit at 6/6 (PIPELINE 2, LATENCY 8):
    the render through both lanes is byte-identical to the model's."""
    sim = build_array(1, 0, 1, 6, 6, 2)
    rtl, model = render_pair(sim, tmp_path, c=6, d=6)
    section = rtl["rtl"]
    assert section["mismatches"] == 0 and section["queries"] == model["box_tests"] > 20000
    assert section["units"] == {"dsp": 1, "lut": 0, "rom": 1} and section["pipeline"] == 2
    lanes = section["lanes"]
    assert [lane["mul_style"] for lane in lanes] == ["dsp", "rom"]
    assert all(lane["latency"] == 8 for lane in lanes) and min(lane["queries"] for lane in lanes) > 10000


def test_bad_settings():
    def expect2(settings, text):
        env = dict(os.environ, SIM_UNIT="array", MODEL_BUILD=str(MODEL_BUILD), **settings)
        r = run(BUILD_SH, env=env)
        assert r.returncode == 2, (settings, r.stdout, r.stderr)
        assert text in r.stderr, (settings, r.stderr)

    # Fabric units stop at 17 bits (the port contract's lut classes).
    expect2({"ARRAY_LUT": "1", "COORD_BITS": "18", "DIR_BITS": "8"},
            "ARRAY_LUT=1: a unit with MUL_STYLE lut takes up to COORD_BITS=17 DIR_BITS=17")
    # Table units: 6/6 with PIPELINE 2 only.
    expect2({"ARRAY_ROM": "1", "SIM_PIPELINE": "2"},
            "ARRAY_ROM=1: a unit with MUL_STYLE rom takes up to COORD_BITS=6 DIR_BITS=6 with PIPELINE 2")
    expect2({"ARRAY_ROM": "1", "COORD_BITS": "6", "DIR_BITS": "6"}, "not COORD_BITS=6 DIR_BITS=6 PIPELINE=0")
    expect2({"ARRAY_DSP": "0", "ARRAY_LUT": "0"}, "ARRAY_DSP + ARRAY_LUT + ARRAY_ROM = 0 is not in 1..256")
    expect2({"ARRAY_ROM": "x"}, "ARRAY_ROM=x is not an integer in 0..256")
    expect2({"ARRAY_DSP": "two"}, "ARRAY_DSP=two is not an integer in 0..256")
    expect2({"ARRAY_LUT": "257"}, "ARRAY_LUT=257 is not an integer in 0..256")
    expect2({"SIM_PIPELINE": "3"}, "SIM_PIPELINE=3 is not 0, 1 or 2")
    expect2({"COORD_BITS": "5"}, "COORD_BITS=5 is not an integer in 6..24")


def test_bad_input(mixed):
    def expect2(args, text):
        r = run([mixed, *args])
        assert r.returncode == 2, (args, r.stdout, r.stderr)
        assert text in r.stderr, (args, r.stderr)

    expect2(["render", "--size", "16", "--test", "smits"], "this RTL answers the fixed test only")
    expect2(["render", "--size", "16", "--ready", "0"], "option --ready: 0 is outside (0, 1]")
    expect2(["check", "--coord-bits", "16"], "make sim-array ARRAY_DSP=1 ARRAY_LUT=1 COORD_BITS=16")
    expect2(["check", "--kind", "wild"], "random, extreme, mixed, setup, boundary, ports, all")
    expect2(["check", "--valid", "1.5"], "option --valid: 1.5 is outside (0, 1]")
    expect2(["check", "--reset-every", "5"], "below 16 cycles")
    expect2(["check", "--bogus", "1"], "unknown option --bogus")
    expect2(["frobnicate"], "unknown command")
