# SPDX-License-Identifier: MIT
"""The local unit's Verilator harness (sim/local/, pluecker_sim_local): one
build, K8 D11 G32 with two children per query (a node per clock), checked
against the golden model: a hardware-in-the-loop render must be
byte-identical to `pluecker render --test local` with the same traversal
(every box test through the RTL, a node's two children in one query);
query mode --check must find no mismatch on the extreme, set-up and
boundary families and lose no real hit against exact; the bench must agree
with the model; bad input must exit 2.

`make sim-regress` runs 10^7 queries over four configurations
(scripts/regress.py, part "local").

Environment: PLUECKER_MODEL_BUILD or PLUECKER_PY_DIR (set by `make test-tb`)
names the model's build directory (default build/model).
"""
import fcntl
import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
MODEL_BUILD = Path(os.environ.get("PLUECKER_MODEL_BUILD") or os.environ.get("PLUECKER_PY_DIR")
                   or ROOT / "build" / "model")
CLI = MODEL_BUILD / "pluecker"
K, D, G, CHILDREN = 8, 11, 32, 2


def run(args, **kw):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, cwd=ROOT, **kw)


@pytest.fixture(scope="module")
def sim():
    assert (MODEL_BUILD / "pluecker-config.cmake").exists(), f"model libraries not built in {MODEL_BUILD} (make build)"
    out = ROOT / "build" / "sim" / f"local_k{K}_d{D}_g{G}_c{CHILDREN}"
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, SIM_UNIT="local", BOX_BITS=str(K), DIR_BITS=str(D), GRID_BITS=str(G),
               CHILDREN=str(CHILDREN), MODE="conservative", MODEL_BUILD=str(MODEL_BUILD), SIM_OUT=str(out))
    with open(out / ".build.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        r = run([ROOT / "scripts" / "venv-exec.sh", ROOT / "sim" / "build.sh"], env=env)
    assert r.returncode == 0, f"sim/build.sh failed:\n{r.stdout}\n{r.stderr}"
    return out / "pluecker_sim_local"


def test_render_identical_to_model(sim, tmp_path):
    common = ["--scene", "teapot", "--size", "40", "--order", "dsa", "--quiet"]
    r = run([sim, "render", *common, "--out", tmp_path / "rtl.png", "--stats", tmp_path / "rtl.json"])
    assert r.returncode == 0, r.stdout + r.stderr
    assert " 0 mismatches" in r.stdout
    m = run([CLI, "render", "--test", "local", "--box-bits", K, "--dir-bits", D, "--grid-bits", G, *common,
             "--out", tmp_path / "model.png", "--stats", tmp_path / "model.json"])
    assert m.returncode == 0, m.stdout + m.stderr
    c = run(["cmp", tmp_path / "rtl.png", tmp_path / "model.png"])
    assert c.returncode == 0, "RTL render differs from the model's: " + c.stdout
    rtl = json.loads((tmp_path / "rtl.json").read_text())
    model = json.loads((tmp_path / "model.json").read_text())
    assert rtl["rtl"]["mismatches"] == 0
    for key in ("rays", "node_visits", "box_tests", "triangle_tests", "batch"):
        assert rtl[key] == model[key], key
    # Every box test through the RTL, most of them two to a query.
    assert rtl["rtl"]["queries"] == model["box_tests"] > 20000
    assert rtl["rtl"]["paired_queries"] > 0.4 * rtl["rtl"]["queries"]
    assert rtl["rtl"]["rtl_queries"] == rtl["rtl"]["queries"] - rtl["rtl"]["paired_queries"]


def false_misses(exact: str, answers: str) -> tuple[int, int]:
    """(real hits, real hits the answers miss) of two 1/0-a-line outputs."""
    pairs = list(zip(exact.split(), answers.split()))
    assert len(pairs) == len(exact.split()) == len(answers.split())
    return sum(e == "1" for e, _ in pairs), sum(e == "1" and a == "0" for e, a in pairs)


@pytest.mark.parametrize("kind", ["extreme", "setup", "boundary"])
def test_query_check(sim, tmp_path, kind):
    q = tmp_path / "q.txt"
    g = run([sim, "gen", "--n", "6000", "--kind", kind, "--seed", "11", "--out", q])
    assert g.returncode == 0, g.stderr
    r = run([sim, "query", "--check", q])
    assert r.returncode == 0, r.stderr
    assert "6000 queries" in r.stderr and " 0 mismatches" in r.stderr, r.stderr
    m = run([CLI, "query", "--test", "local", "--box-bits", K, "--dir-bits", D, "--grid-bits", G, q])
    assert m.returncode == 0, m.stderr
    assert r.stdout == m.stdout
    e = run([CLI, "query", "--test", "exact", q])
    assert e.returncode == 0, e.stderr
    hits, lost = false_misses(e.stdout, r.stdout)
    print(f"{kind}: {r.stderr.strip()}; {hits} real hits, {lost} lost")
    assert hits > 1000 and lost == 0


def test_bench_short(sim):
    r = run([sim, "bench", "--n", "50000"])
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.count(" 0 mismatches") == 2


def test_bad_input(sim, tmp_path):
    def expect2(args, text, **kw):
        r = run([sim, *args], **kw)
        assert r.returncode == 2, (args, r.stdout, r.stderr)
        assert text in r.stderr, (args, r.stderr)

    expect2(["query", "--bogus", "x"], "unknown option --bogus")
    expect2(["query", tmp_path / "missing.txt"], "cannot open")
    expect2(["query", "--box-bits", "10", tmp_path / "missing.txt"], "make sim-local BOX_BITS=10")
    expect2(["render", "--size", "16", "--test", "fixed"], "local test only")
    expect2(["gen", "--kind", "wild", "--out", tmp_path / "x.txt"], "random, extreme, mixed, setup, boundary")
    expect2(["frobnicate"], "unknown command")
    bad = tmp_path / "bad.txt"
    bad.write_text("0 0 0 0 0 1 inf -1 -1 -1 1 1 1\n0 0 0 1 0 0 inf -1 -1 -1 2.5 1 1\n")
    r = run([sim, "query", bad])
    assert r.returncode == 2 and f"{bad}:2: box x extent [-1, 2.5]" in r.stderr, r.stderr
    env = dict(os.environ, SIM_UNIT="local", BOX_BITS="8", GRID_BITS="9", MODEL_BUILD=str(MODEL_BUILD))
    b = run([ROOT / "scripts" / "venv-exec.sh", ROOT / "sim" / "build.sh"], env=env)
    assert b.returncode == 2 and "GRID_BITS=9 is not an integer in 10..32" in b.stderr, b.stderr
