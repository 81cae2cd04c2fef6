# SPDX-License-Identifier: MIT
"""The Verilator harness of the binary32 units (sim/float, SIM_UNIT float
and smits): builds pluecker_sim for pluecker_float_intersector (round to
nearest) and pluecker_smits_intersector and checks that the RTL agrees with
the golden model (f32unit.hpp): `check` on generated queries (random and
extreme, also against exact_hit: the nearest Plücker unit and the slab
unit have no guarantee, so their false misses are printed, not required to
be zero), on bit patterns over the whole port range and around 2^-126,
with backpressure; `query --check` on a query file; a hardware-in-the-loop
render of the teapot byte-identical to `pluecker render --test f32-pluecker`
(or f32-smits), with the same counts; bad input exits 2.
`make sim-regress` runs 10^7 queries through each unit and the conservative
unit (zero false misses there).

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
CHECK_RE = re.compile(r"check \(([^)]*)\): (\d+) (\w+) queries, (\d+) hits, (\d+) mismatches")


def build_float_sim(unit: str) -> Path:
    """Builds (or finds up to date) the harness of a unit (MUL_DSP 4, nearest)."""
    assert (MODEL_BUILD / "pluecker-config.cmake").exists(), f"model libraries not built in {MODEL_BUILD} (make build)"
    out = ROOT / "build" / "sim" / f"{unit}_dsp4"
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, SIM_UNIT=unit, MODE="nearest", SIM_MUL_DSP="4", MODEL_BUILD=str(MODEL_BUILD),
               SIM_OUT=str(out))
    with open(out / ".build.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        r = subprocess.run([str(ROOT / "scripts" / "venv-exec.sh"), str(ROOT / "sim" / "build.sh")],
                           cwd=ROOT, env=env, capture_output=True, text=True)
    assert r.returncode == 0, f"sim/build.sh failed:\n{r.stdout}\n{r.stderr}"
    return out / "pluecker_sim"


def run(args, **kw):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, cwd=ROOT, **kw)


@pytest.fixture(scope="module", params=["float", "smits"])
def sim(request):
    return request.param, build_float_sim(request.param)


@pytest.mark.parametrize("kind,extra", [("mixed", ["--exact"]), ("raw", ["--ready", "0.6"]), ("tiny", [])])
def test_check_generated(sim, kind, extra):
    unit, binary = sim
    r = run([binary, "check", "--n", "30000", "--kind", kind, "--seed", "7", *extra])
    assert r.returncode == 0, (r.stdout, r.stderr)
    m = CHECK_RE.search(r.stdout)
    assert m, r.stdout
    assert m.group(1).startswith(unit), m.group(1)
    assert int(m.group(2)) == 30000 and int(m.group(5)) == 0, r.stdout
    assert int(m.group(4)) > 0, "no hit at all: the stimulus does not reach the hit paths"
    print(r.stdout.strip())


def test_query_check_file(sim, tmp_path):
    unit, binary = sim
    import pluecker_py as pp

    qs = pp.random_queries(3, 2000) + pp.extreme_queries(4, 2000)
    f = tmp_path / "q.txt"
    f.write_text("".join(q.line() + "\n" for q in qs))
    r = run([binary, "query", "--check", f])
    assert r.returncode == 0, r.stderr
    answers = [int(x) for x in r.stdout.split()]
    assert len(answers) == len(qs)
    model = ([pp.f32_pluecker_hit(pp.f32_pluecker_query(q, False), False) for q in qs] if unit == "float"
             else [pp.f32_smits_hit(pp.f32_smits_query(q)) for q in qs])
    assert answers == [int(h) for h in model]
    assert "0 mismatches" in r.stderr, r.stderr


def test_render_identical_to_model(sim, tmp_path):
    unit, binary = sim
    test = {"float": "f32-pluecker", "smits": "f32-smits"}[unit]
    common = ["--scene", "teapot", "--size", "32", "--order", "dsa", "--pool", "64", "--quiet"]
    r = run([binary, "render", *common, "--out", tmp_path / "rtl.png", "--stats", tmp_path / "rtl.json"])
    assert r.returncode == 0, r.stdout + r.stderr
    assert " 0 mismatches" in r.stdout, r.stdout
    m = run([CLI, "render", "--test", test, *common, "--out", tmp_path / "model.png",
             "--stats", tmp_path / "model.json"])
    assert m.returncode == 0, m.stdout + m.stderr
    c = run(["cmp", tmp_path / "rtl.png", tmp_path / "model.png"])
    assert c.returncode == 0, "RTL render differs from the model's: " + c.stdout
    rtl = json.loads((tmp_path / "rtl.json").read_text())
    model = json.loads((tmp_path / "model.json").read_text())
    assert rtl["test"] == model["test"] == test
    for key in ("rays", "node_visits", "box_tests", "triangle_tests", "batch"):
        assert rtl[key] == model[key], key
    assert rtl["rtl"]["mismatches"] == 0
    assert rtl["rtl"]["queries"] == model["box_tests"] > 5000
    # The harness renders only its own unit's test.
    other = {"float": "f32-smits", "smits": "f32-pluecker"}[unit]
    r = run([binary, "render", "--test", other, "--size", "4", "--out", tmp_path / "x.png"])
    assert r.returncode == 2 and "--test" in r.stderr, r.stderr


def test_bad_input(sim, tmp_path):
    _, binary = sim
    bad = tmp_path / "bad.txt"
    bad.write_text("0 0 0 1 0 0 inf 0 0 0 1 1\n")  # 12 numbers
    for args in (["check", "--kind", "wide"], ["check", "--n", "0"], ["check", "--kind", "raw", "--exact"],
                 ["check", "--ready", "0"], ["query", bad], ["query"], ["frobnicate"]):
        r = run([binary, *args])
        assert r.returncode == 2, (args, r.stdout, r.stderr)
    r = run([binary, "query", bad])
    assert "bad.txt:1" in r.stderr, r.stderr
