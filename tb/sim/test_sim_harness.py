# SPDX-License-Identifier: MIT
"""The Verilator harness (sim/): builds pluecker_sim for 16/16, 23/23 and 24/24
conservative and checks that the RTL agrees with the golden model: a
hardware-in-the-loop render must be byte-identical to `pluecker render --test
fixed` (and, with the camera far outside the scene at 23/23 and 24/24, to the
exact render), query mode --check must find no mismatch on a render trace, on
random + extreme queries, on the set-up families (rays from anywhere, no
real hit lost against exact) and on operand files of decision-boundary and
full-port-range operands, and bad input must exit 2.

A second build, 24/24 nearest (wide VlWide ports, no margin), costs another
Verilator compile; it runs when PLUECKER_SIM_WIDE=1 (`make sim-query
COORD_BITS=24 DIR_BITS=24 MODE=nearest` checks the same).

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
RTL = ROOT / "rtl" / "pluecker_intersector.sv"


def build_sim(coord_bits, dir_bits, mode):
    """Builds (or finds up to date) the harness; a lock keeps xdist workers apart."""
    assert RTL.exists(), f"{RTL} is missing"
    assert (MODEL_BUILD / "pluecker-config.cmake").exists(), f"model libraries not built in {MODEL_BUILD} (make build)"
    suffix = "_nearest" if mode == "nearest" else ""
    out = ROOT / "build" / "sim" / f"{coord_bits}x{dir_bits}{suffix}"
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, COORD_BITS=str(coord_bits), DIR_BITS=str(dir_bits), MODE=mode,
               MODEL_BUILD=str(MODEL_BUILD), SIM_OUT=str(out))
    with open(out / ".build.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        r = subprocess.run([str(ROOT / "scripts" / "venv-exec.sh"), str(ROOT / "sim" / "build.sh")],
                           cwd=ROOT, env=env, capture_output=True, text=True)
    assert r.returncode == 0, f"sim/build.sh failed:\n{r.stdout}\n{r.stderr}"
    return out / "pluecker_sim"


def run(args, **kw):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, cwd=ROOT, **kw)


@pytest.fixture(scope="module")
def sim16():
    return build_sim(16, 16, "conservative")


@pytest.mark.parametrize("scene,size,order,build", [("teapot", 64, "dsa", "sah"), ("spheres", 48, "fixed", "median")])
def test_render_identical_to_model(sim16, tmp_path, scene, size, order, build):
    common = ["--scene", scene, "--size", str(size), "--order", order, "--build", build, "--quiet"]
    r = run([sim16, "render", *common, "--out", tmp_path / "rtl.png", "--stats", tmp_path / "rtl.json"])
    assert r.returncode == 0, r.stdout + r.stderr
    assert " 0 mismatches" in r.stdout
    m = run([CLI, "render", "--test", "fixed", "--coord-bits", "16", "--dir-bits", "16", *common,
             "--out", tmp_path / "model.png", "--stats", tmp_path / "model.json"])
    assert m.returncode == 0, m.stdout + m.stderr
    c = run(["cmp", tmp_path / "rtl.png", tmp_path / "model.png"])
    assert c.returncode == 0, "RTL render differs from the model's: " + c.stdout
    rtl = json.loads((tmp_path / "rtl.json").read_text())
    model = json.loads((tmp_path / "model.json").read_text())
    assert rtl["rtl"]["mismatches"] == 0
    # Same traversal; every box test of it went through the RTL.
    for key in ("rays", "node_visits", "box_tests", "triangle_tests", "batch"):
        assert rtl[key] == model[key], key
    assert rtl["rtl"]["queries"] == model["box_tests"] > 10000


def test_query_check_render_trace(sim16, tmp_path):
    trace = tmp_path / "trace.txt"
    t = run([CLI, "trace", "--scene", "teapot", "--size", "32", "--test", "fixed", "--order", "dsa",
             "--out", trace])
    assert t.returncode == 0, t.stdout + t.stderr
    r = run([sim16, "query", "--check", trace])
    assert r.returncode == 0, r.stderr
    assert " 0 mismatches" in r.stderr
    m = run([CLI, "query", "--test", "fixed", trace])
    assert m.returncode == 0, m.stderr
    assert r.stdout == m.stdout
    assert len(r.stdout.splitlines()) > 1000
    # `make report` reads this summary line with its CHECK_RE.
    import importlib.util
    spec = importlib.util.spec_from_file_location("report", ROOT / "scripts" / "report.py")
    report = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(report)
    parsed = report.CHECK_RE.search(r.stderr)
    assert parsed, r.stderr
    assert int(parsed.group(2)) == len(r.stdout.splitlines()) and int(parsed.group(3)) == 0


def test_query_check_generated(sim16, tmp_path):
    q = tmp_path / "q.txt"
    g = run([sim16, "gen", "--n", "40000", "--kind", "mixed", "--seed", "7", "--out", q])
    assert g.returncode == 0, g.stderr
    r = run([sim16, "query", "--check", q])
    assert r.returncode == 0, r.stderr
    assert "40000 queries" in r.stderr and " 0 mismatches" in r.stderr, r.stderr
    answers = r.stdout.splitlines()
    assert len(answers) == 40000 and set(answers) == {"0", "1"}


@pytest.mark.parametrize("kind", ["boundary", "ports"])
def test_query_check_operands(sim16, tmp_path, kind):
    """Datapath operands the float set-up never makes (the cocotb bench's
    boundary and raw sources, from the same generators): decision
    boundaries on the margin's bound, the full port ranges."""
    q = tmp_path / f"{kind}.txt"
    g = run([sim16, "gen", "--n", "20000", "--kind", kind, "--seed", "5", "--out", q])
    assert g.returncode == 0, g.stderr
    assert q.read_text().splitlines()[1] == "operands 16 16 conservative"
    r = run([sim16, "query", "--check", q])
    assert r.returncode == 0, r.stderr
    assert "20000 operand queries, all through the RTL, 0 mismatches" in r.stderr, r.stderr
    answers = r.stdout.splitlines()
    assert len(answers) == 20000 and answers.count("1") > 1000 and answers.count("0") > 1000


def test_bench_short(sim16):
    r = run([sim16, "bench", "--n", "100000"])
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.count(" 0 mismatches") == 2


def test_bad_input(sim16, tmp_path):
    def expect2(args, text, **kw):
        r = run([sim16, *args], **kw)
        assert r.returncode == 2, (args, r.stdout, r.stderr)
        assert text in r.stderr, (args, r.stderr)

    expect2(["query", "--bogus", "x"], "unknown option --bogus")
    expect2(["query", tmp_path / "missing.txt"], "cannot open")
    expect2(["query", "--mode", "nearest", tmp_path / "missing.txt"], "make sim")
    expect2(["query", "--coord-bits", "5", tmp_path / "missing.txt"], "6..24")
    expect2(["render", "--size", "16", "--test", "smits"], "this RTL answers the fixed test only")
    expect2(["frobnicate"], "unknown command")
    # A box past the range of the build: the same message and status as the CLI.
    bad = tmp_path / "bad.txt"
    bad.write_text("0 0 0 0 0 1 inf -1 -1 -1 1 1 1\n2.5 0 0 1 0 0 inf -1 -1 -1 2 1 1\n")
    r = run([sim16, "query", bad])
    assert r.returncode == 2
    assert f"{bad}:2: box x extent [-1, 2] is outside the fixed-point range [-2, 1.99993896] of COORD_BITS = 16" \
        in r.stderr
    m = run([CLI, "query", "--test", "fixed", bad])
    assert m.returncode == 2
    assert r.stderr.split("error: ", 1)[1] == m.stderr.split("error: ", 1)[1]
    # Operand files: the header must be the build's, every field an integer
    # inside its port range.
    ops = tmp_path / "ops.txt"
    line = "0 1 2 3 4 5 6 0 0 0 0 -8 -8 -8 8 8 8"
    cases = [("operands 16 16 conservative\n" + line + " 1\n", "ops.txt:2: more than 17 fields"),
             ("operands 16 12 conservative\n" + line + "\n", "ops.txt:1: operands for 16 12 conservative, not 16 16"),
             ("operands 16 16 nearest\n" + line + "\n", "ops.txt:1: operands for 16 16 nearest, not 16 16 "),
             ("operands 16 16\n" + line + "\n", "ops.txt:1: expected the header 'operands COORD_BITS DIR_BITS MODE'"),
             ("# c\noperands 16 16 conservative\n8 1 2 3 4 5 6 0 0 0 0 -8 -8 -8 8 8 8\n",
              "ops.txt:3: field 1 (cls): 8 is outside its port range 0..7"),
             ("operands 16 16 conservative\n0 32768 2 3 4 5 6 0 0 0 0 -8 -8 -8 8 8 8\n",
              "ops.txt:2: field 2 (ox): 32768 is outside its port range -32768..32767"),
             ("operands 16 16 conservative\n0 1 2 3 4 5 65536 0 0 0 0 -8 -8 -8 8 8 8\n",
              "ops.txt:2: field 7 (dz): 65536 is outside its port range 0..65535"),
             ("operands 16 16 conservative\n0 1 2 3 4 5 6 2 0 0 0 -8 -8 -8 8 8 8\n",
              "ops.txt:2: field 8 (end_valid): 2 is outside its port range 0..1"),
             ("operands 16 16 conservative\n0 1 2 3 4 5 0x6 0 0 0 0 -8 -8 -8 8 8 8\n",
              "ops.txt:2: field 7 (dz): '0x6' is not an integer"),
             ("operands 16 16 conservative\n0 1 2 3\n", "ops.txt:2: expected 17 integers, got 4")]
    for text, message in cases:
        ops.write_text(text)
        expect2(["query", ops], message)
    expect2(["gen", "--kind", "edges", "--out", ops], "'edges' is not one of random, extreme, mixed, setup, "
            "boundary, ports")
    # Illegal widths stop the build script with status 2.
    env = dict(os.environ, COORD_BITS="5", MODEL_BUILD=str(MODEL_BUILD))
    b = run([ROOT / "scripts" / "venv-exec.sh", ROOT / "sim" / "build.sh"], env=env)
    assert b.returncode == 2 and "COORD_BITS=5" in b.stderr


def test_build_takes_the_venvs_verilator(sim16, tmp_path):
    """sim/build.sh run outside the venv, with Debian's Verilator first on PATH and
    VERILATOR_ROOT pointing at it, still builds with the venv's; CMake itself
    refuses any other VERILATOR_ROOT with a clear message."""
    env = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV",)}
    env.update(PATH="/usr/bin:/bin", VERILATOR_ROOT="/usr/share/verilator", COORD_BITS="16", DIR_BITS="16",
               MODE="conservative", MODEL_BUILD=str(MODEL_BUILD), SIM_OUT=str(sim16.parent))
    with open(sim16.parent / ".build.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        b = run(["bash", ROOT / "sim" / "build.sh"], env=env)
    assert b.returncode == 0, b.stderr
    assert b.stdout.strip().endswith("pluecker_sim")
    c = run(["cmake", "-S", ROOT / "sim", "-B", tmp_path / "wrong", f"-DPLUECKER_MODEL_BUILD={MODEL_BUILD}"],
            env=dict(env, PATH=os.environ["PATH"]))
    assert c.returncode != 0
    assert "VERILATOR_ROOT=/usr/share/verilator is not the venv's Verilator" in c.stdout + c.stderr


@pytest.fixture(scope="module", params=[(23, 23), (24, 24)], ids=["23x23", "24x24"])
def sim_wide(request):
    c, d = request.param
    return c, d, build_sim(c, d, "conservative")


def false_misses(exact: str, answers: str) -> tuple[int, int]:
    """(real hits, real hits the answers miss) of two 1/0-a-line outputs."""
    pairs = list(zip(exact.split(), answers.split()))
    assert len(pairs) == len(exact.split()) == len(answers.split())
    return sum(e == "1" for e, _ in pairs), sum(e == "1" and a == "0" for e, a in pairs)


@pytest.mark.parametrize("c,d", [(16, 16), (23, 23), (24, 24)])
def test_query_check_setup_families(tmp_path, c, d):
    """Rays from anywhere (far cameras and lights, long directions, the range
    cube's edges) through the RTL's query mode: the model's set-up, 0
    mismatches, and no real hit lost against exact."""
    sim = build_sim(c, d, "conservative")
    q = tmp_path / "setup.txt"
    g = run([sim, "gen", "--n", "20000", "--kind", "setup", "--seed", str(c), "--out", q])
    assert g.returncode == 0, g.stderr
    r = run([sim, "query", "--check", q])
    assert r.returncode == 0, r.stderr
    assert "20000 queries" in r.stderr and " 0 mismatches" in r.stderr, r.stderr
    m = run([CLI, "query", "--test", "fixed", "--coord-bits", c, "--dir-bits", d, q])
    assert m.returncode == 0, m.stderr
    assert r.stdout == m.stdout
    e = run([CLI, "query", "--test", "exact", q])
    assert e.returncode == 0, e.stderr
    hits, lost = false_misses(e.stdout, r.stdout)
    print(f"{c}/{d}: {r.stderr.strip()}; {hits} real hits, {lost} lost")
    assert hits > 5000 and lost == 0


def test_far_camera_render(sim_wide, tmp_path):
    """The camera 1,400 units away: the hardware-in-the-loop render equals the
    model's byte for byte and the exact render's, with the same hits."""
    c, d, sim = sim_wide
    view = ["--scene", "teapot", "--eye", "600,800,-1000", "--look", "0,0,0", "--fov", "0.09", "--size", "64",
            "--order", "dsa", "--quiet"]
    r = run([sim, "render", *view, "--out", tmp_path / "rtl.png", "--stats", tmp_path / "rtl.json"])
    assert r.returncode == 0, r.stdout + r.stderr
    assert " 0 mismatches" in r.stdout
    outs = {}
    for test, extra in (("fixed", ["--coord-bits", str(c), "--dir-bits", str(d)]), ("exact", [])):
        m = run([CLI, "render", "--test", test, *extra, *view, "--out", tmp_path / f"{test}.png",
                 "--stats", tmp_path / f"{test}.json"])
        assert m.returncode == 0, m.stdout + m.stderr
        outs[test] = json.loads((tmp_path / f"{test}.json").read_text())
    assert (tmp_path / "rtl.png").read_bytes() == (tmp_path / "fixed.png").read_bytes(), "RTL render differs"
    assert (tmp_path / "fixed.png").read_bytes() == (tmp_path / "exact.png").read_bytes(), \
        "the fixed-point render lost a hit the exact render finds"
    rtl = json.loads((tmp_path / "rtl.json").read_text())
    exact_hits, fixed_hits = outs["exact"]["hits"], rtl["hits"]
    lost = {k: exact_hits[k] - fixed_hits[k] for k in exact_hits}
    print(f"{c}/{d} far camera: {rtl['rtl']['queries']} RTL queries, hits {fixed_hits}, lost against exact {lost}")
    assert fixed_hits == exact_hits and fixed_hits["camera"] > 1000
    assert rtl["rtl"]["mismatches"] == 0 and rtl["rtl"]["queries"] == outs["fixed"]["box_tests"]


@pytest.mark.skipif(os.environ.get("PLUECKER_SIM_WIDE") != "1", reason="set PLUECKER_SIM_WIDE=1 (second Verilator build)")
def test_wide_ports_nearest(tmp_path):
    """24/24 puts 72-bit ports in VlWide arrays; nearest mode drops the margin."""
    sim = build_sim(24, 24, "nearest")
    q = tmp_path / "q.txt"
    assert run([sim, "gen", "--n", "20000", "--kind", "mixed", "--seed", "3", "--out", q]).returncode == 0
    r = run([sim, "query", "--check", q])
    assert r.returncode == 0, r.stderr
    assert "20000 queries" in r.stderr and " 0 mismatches" in r.stderr, r.stderr
    m = run([CLI, "query", "--test", "fixed", "--coord-bits", "24", "--dir-bits", "24", "--mode", "nearest", q])
    assert m.returncode == 0 and r.stdout == m.stdout
