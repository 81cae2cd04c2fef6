#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The long reliability regression (`make sim-regress`).

  1. model: the long versions of the numerical-extremes and margin suites
     (PLUECKER_LONG=1 model_tests --gtest_filter='Extremes.*:MarginBound.*'):
     1M extreme + 1M transformed queries at every width pair of
     {6, 9, ..., 24}^2, the margin's boundary constructions, the exhaustive
     6/6 lattice and the 7/6 and 6/8 domains; zero false misses required;
     and the set-up suites (PLUECKER_LONG=1 model_tests --gtest_filter=
     'Setup.*': rays from anywhere at every width pair 6..24);
  2. rtl: REGRESS_N (default 10^6) extreme queries (pluecker_sim gen --kind
     extreme) and REGRESS_N set-up queries (--kind setup: far cameras and
     lights, long directions, the range cube's edges, for the width's
     range) through the Verilated RTL at each of REGRESS_WIDTHS with
     `pluecker_sim query --check` (zero mismatches against the model), and
     the RTL's answers against `pluecker query --test exact` (zero false
     misses in conservative mode); then REGRESS_N datapath operands on the
     decision boundaries (--kind boundary: the margin's bound, the end and
     origin tests) and REGRESS_N from the full port ranges (--kind ports),
     the cocotb bench's boundary and raw sources, against the model (zero
     mismatches; they are not float queries, so there is no exact run).
     The harness is built with the RTL's ASSERT_ON assertions compiled in
     (SIM_ASSERT=1), in its own directories (REGRESS_SIM_ROOT), so that it
     does not force `make sim`'s builds to be redone;
  2b. local: the local unit (rtl/pluecker_local_intersector.sv) through its
     harness (pluecker_sim_local, SIM_UNIT=local, ASSERT_ON compiled in) at
     each of REGRESS_LOCAL_CONFIGS: REGRESS_LOCAL_N extreme queries and
     REGRESS_LOCAL_N / 2 each of set-up, boundary and random queries
     (pluecker_sim_local gen), each box in its tight frame, with
     `pluecker_sim_local query --check` (zero mismatches against the model,
     every child box of every RTL query checked) and, in conservative mode,
     the answers against `pluecker query --test exact` (zero false misses);
     2.5 REGRESS_LOCAL_N queries per configuration, 10^7 at the defaults;
  3. cocotb: the long stress bench (PLUECKER_LONG=1
     tb/pluecker_intersector/test_stress.py: LATENCY 6, 7 and 8), its sizes
     scaled with REGRESS_N (25x the `make test` sizes at 10^6, never below
     1x);
  4. sweep: the long cocotb sweeps (PLUECKER_LONG=1): the intersector at
     every width pair of its sweep in both modes and its DSP builds
     (tb/pluecker_intersector/test_pluecker_intersector.py), the local unit
     and its two parts at every configuration of their sweeps, their
     MULT18X18D builds included (tb/pluecker_local_intersector,
     tb/pluecker_local_frame, tb/pluecker_local_child), and the
     multipliers and the MULT18X18D model checks (tb/pluecker_mul,
     tb/pluecker_mul_lut, tb/mult18x18d), 25x the `make test` queries;
     the binary32 units and their primitives (tb/pluecker_float_intersector,
     tb/pluecker_smits_intersector with their ECP5 DSP builds,
     tb/pluecker_f32_add, tb/pluecker_f32_mul);
  5. float: the binary32 units through the Verilator harness (sim/float,
     built with ASSERT_ON): for each of REGRESS_FLOAT_UNITS (default
     "float float_cons smits") REGRESS_FLOAT_N (default 10^7) queries with
     `pluecker_sim check`: 40 % extreme families and 20 % random queries
     (also against exact_hit: false misses and false hits), 30 % bit
     patterns over the whole port range (raw) and 10 % operands around
     2^-126 (tiny); zero mismatches against the model required, and zero
     false misses for the conservative unit. The long model suite of the
     units (PLUECKER_LONG=1 model_tests --gtest_filter='F32Unit.*') too.

Jobs: every part is split into independent jobs of scripts/jobs.py: the
model suites (one job), a job per width of rtl, per configuration of
local, per pytest test of cocotb and sweep, the binary32 model suite and a
job per unit of float. They run on this machine, JOBS at a time (each
harness build with SIM_JOBS=1, as they run side by side), or on a Dask
distributed cluster when DASK_SCHEDULER=host:port is set (the workers see
the project at the same path and run its venv), with a progress line per
finished job. A job that crashes, or whose worker dies, is named and fails
the run; the others go on, and the results of every finished job are kept
in <REGRESS_OUT>/jobs.jsonl. The summary (printed at the end and in
<REGRESS_OUT>/summary.txt) has the lines of each part in the order above;
the cocotb and sweep parts say PASS or FAIL for all their tests together
and name each failing test with the tail of its log.

Environment: MODEL_BUILD (default build/model; must hold model_tests,
pluecker and the Python module), JOBS (default 2), REGRESS_N,
REGRESS_WIDTHS (default "6x6 9x15 16x16 20x8 22x22 23x23 24x24 16x16n 7x22n":
LATENCY 6, 7 and 8; a trailing n = nearest mode, where the exact comparison
is skipped), REGRESS_SIM_ROOT (default build/regress/sim), REGRESS_ASSERT
(default 1: SIM_ASSERT for the harness), REGRESS_OUT (default
build/regress), REGRESS_PARTS (default "model rtl local cocotb sweep
float"), REGRESS_LOCAL_N (default 1000000), REGRESS_LOCAL_CONFIGS (default
"8x11x32c1 8x11x32c2 12x15x32c2 4x7x6c1": BOX_BITSxDIR_BITSxGRID_BITS, c
CHILDREN, a trailing n = nearest mode), REGRESS_FLOAT_N, REGRESS_FLOAT_UNITS.
Relative paths are taken from the project root. Exit status 0 only when
every part passes, 2 on bad settings or a missing model build. Run through
scripts/venv-exec.sh (the Makefile does).
"""
from __future__ import annotations

import itertools
import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
import jobs  # noqa: E402  (scripts/jobs.py: here or on a Dask cluster)

PARTS = ("model", "rtl", "local", "cocotb", "sweep", "float")
MODEL_FIGURES = re.compile(r"total over|min slack of a real hit|exhaustive .*queries|lattice 6/6 \] [0-9]|"
                           r"setup (total|bites|traversal)")
FLOAT_FIGURES = re.compile(r"^\[ f32 (extreme|random|conservative) *\]")
STRESS = ("tb/pluecker_intersector/test_stress.py",)
SWEEP = ("tb/pluecker_intersector/test_pluecker_intersector.py", "tb/pluecker_local_intersector",
         "tb/pluecker_local_frame", "tb/pluecker_local_child", "tb/pluecker_mul", "tb/pluecker_mul_lut",
         "tb/mult18x18d", "tb/pluecker_float_intersector", "tb/pluecker_smits_intersector", "tb/pluecker_f32_add",
         "tb/pluecker_f32_mul")
# The float part's shares of REGRESS_FLOAT_N: kind, percent, also against exact.
FLOAT_KINDS = (("extreme", 40, True), ("random", 20, True), ("raw", 30, False), ("tiny", 10, False))
WIDTH_RE = re.compile(r"(\d+)x(\d+)(n?)")
LOCAL_RE = re.compile(r"(\d+)x(\d+)x(\d+)c(\d+)(n?)")
FLOAT_UNIT_RE = re.compile(r"float(_cons)?|smits")


class BadSetting(Exception):
    """A bad setting (exit 2)."""


def env_int(name: str, default: int) -> int:
    text = os.environ.get(name, "") or str(default)
    if not text.isdigit() or int(text) < 1:
        raise BadSetting(f"{name}='{text}' is not a positive integer")
    return int(text)


def env_list(name: str, default: str, pattern: re.Pattern, what: str) -> list[str]:
    items = (os.environ.get(name, "") or default).split()
    for item in items:
        if not pattern.fullmatch(item):
            raise BadSetting(f"{name}: '{item}' is not {what}")
    if len(set(items)) != len(items):
        raise BadSetting(f"{name}: '{' '.join(items)}' names an entry twice")
    return items


def env_path(name: str, default: str) -> str:
    return str(ROOT / (os.environ.get(name, "") or default))  # an absolute value stays as it is


def settings() -> dict:
    n = env_int("REGRESS_N", 1000000)
    parts = env_list("REGRESS_PARTS", " ".join(PARTS), re.compile("|".join(PARTS)), f"one of {', '.join(PARTS)}")
    return {
        "model_build": env_path("MODEL_BUILD", "build/model"),
        "jobs": env_int("JOBS", 2),
        "n": n,
        "widths": env_list("REGRESS_WIDTHS", "6x6 9x15 16x16 20x8 22x22 23x23 24x24 16x16n 7x22n", WIDTH_RE,
                           "CxD[n] (e.g. 16x16, 16x16n)"),
        "sim_root": env_path("REGRESS_SIM_ROOT", "build/regress/sim"),
        "assert": os.environ.get("REGRESS_ASSERT", "") or "1",
        "out": env_path("REGRESS_OUT", "build/regress"),
        "parts": parts,
        "local_n": env_int("REGRESS_LOCAL_N", 1000000),
        "local_configs": env_list("REGRESS_LOCAL_CONFIGS", "8x11x32c1 8x11x32c2 12x15x32c2 4x7x6c1", LOCAL_RE,
                                  "KxDxGcC[n] (e.g. 8x11x32c2)"),
        "float_n": env_int("REGRESS_FLOAT_N", 10000000),
        "float_units": env_list("REGRESS_FLOAT_UNITS", "float float_cons smits", FLOAT_UNIT_RE,
                                "float, float_cons or smits"),
        "stress_scale": max(1, (25 * n + 500000) // 1000000),
    }


# --------------------------------------------------------------------------
# Helpers of the jobs (they run here or on a worker: absolute paths only)

def shown(path: Path | str) -> str:
    """A path as the summary prints it: from the project root when inside."""
    try:
        return str(Path(path).relative_to(ROOT))
    except ValueError:
        return str(path)


def say(lines: list[str], text: str) -> None:
    lines.append(f"regress: {text}")


def elapsed(t0: float) -> str:
    return f"{int(time.monotonic() - t0)} s"


def log_lines(log: Path) -> list[str]:
    return log.read_text(errors="replace").splitlines() if log.exists() else []


def run(cmd: list, log: Path, env: dict | None = None) -> int:
    """A command from the project root, its output into log."""
    with open(log, "w") as f:
        return subprocess.run([str(c) for c in cmd], cwd=ROOT, env=env, stdout=f,
                              stderr=subprocess.STDOUT).returncode


def write_once(path: Path, cmd: list) -> None:
    """Makes path with cmd (an argument "{out}" is the file to write, else
    its standard output is) unless it is there and not empty, through a
    temporary file: jobs that need the same query file may race, and each
    writes the same content."""
    if path.exists() and path.stat().st_size > 0:
        return
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{time.monotonic_ns()}")
    argv = [str(tmp) if c == "{out}" else str(c) for c in cmd]
    try:
        with open(os.devnull if "{out}" in cmd else tmp, "w") as f:
            subprocess.run(argv, cwd=ROOT, stdout=f, check=True)
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


def build_harness(s: dict, env: dict, log: Path) -> bool:
    env = dict(os.environ, MODEL_BUILD=s["model_build"], SIM_JOBS="1", SIM_ASSERT=s["assert"], **env)
    return run([ROOT / "sim" / "build.sh"], log, env) == 0


def against_exact(exact: Path, answers: Path) -> tuple[int, int, int]:
    """(false misses, false hits, real hits) of the RTL's answers, line by
    line against the exact ones (first field of each line)."""
    fm = fh = hits = 0
    with open(exact) as e, open(answers) as a:
        for le, la in itertools.zip_longest(e, a, fillvalue=""):
            x, r = (le.split() or [""])[0], (la.split() or [""])[0]
            fm += x == "1" and r == "0"
            fh += x == "0" and r == "1"
            hits += x == "1"
    return fm, fh, hits


def check_queries(sim: Path, queries: Path, exact: Path | None, out: Path, label: str, kind: str, mode: str,
                  t0: float, lines: list[str]) -> bool | None:
    """`<sim> query --check queries` (answers and log in out/<label>_<kind>.*):
    True when it passes (and, in conservative mode with an exact file, has
    no false miss), False when it has false misses, None when the check
    itself failed. Its summary lines go to lines."""
    tag = f"{label.replace(' ', '_')}_{kind}"
    answers, log = out / f"{tag}.answers", out / f"{tag}.log"
    with open(answers, "w") as a, open(log, "w") as e:
        rc = subprocess.run([str(sim), "query", "--check", str(queries)], cwd=ROOT, stdout=a, stderr=e).returncode
    check = ([x for x in log_lines(log) if x.startswith("check")] or [""])[-1]
    if rc != 0:
        say(lines, f"{label} ({mode}, {kind}): FAIL, {check} ({elapsed(t0)})")
        lines += log_lines(log)[:5]
        return None
    if mode == "conservative" and exact is not None:
        fm, fh, hits = against_exact(exact, answers)
        say(lines, f"{label} ({mode}, {kind}): {check}; against exact: {hits} real hits, {fm} false misses, "
                   f"{fh} false hits ({elapsed(t0)})")
        return fm == 0
    say(lines, f"{label} ({mode}, {kind}): {check} ({elapsed(t0)})")
    return True


# --------------------------------------------------------------------------
# Jobs: each returns {"pass": bool, "lines": [summary lines], ...}

def model_job(s: dict, name: str, gtest_filter: str, log_name: str, figures: str, show_failures: bool) -> dict:
    """The long model suites of gtest_filter: a PASS or FAIL line and the
    lines of the log that match figures."""
    t0 = time.monotonic()
    log = Path(s["out"]) / log_name
    rc = run([Path(s["model_build"]) / "model_tests", f"--gtest_filter={gtest_filter}"], log,
             dict(os.environ, PLUECKER_LONG="1"))
    lines: list[str] = []
    say(lines, f"{name} {'PASS' if rc == 0 else 'FAIL'} ({elapsed(t0)}; log {shown(log)})")
    if rc != 0 and show_failures:
        lines += [x for x in log_lines(log) if "FAILED" in x or "Failure" in x][:10]
    lines += [f"regress:   {x}" for x in log_lines(log) if re.search(figures, x)]
    return {"pass": rc == 0, "lines": lines}


def rtl_job(s: dict, w: str) -> dict:
    """One width of the rtl part: the harness build and its four query sets."""
    t0 = time.monotonic()
    out, n = Path(s["out"]), s["n"]
    c, d, nearest = WIDTH_RE.fullmatch(w).groups()
    mode = "nearest" if nearest else "conservative"
    simdir = Path(s["sim_root"]) / f"{c}x{d}{'_nearest' if nearest else ''}"
    lines: list[str] = []
    if not build_harness(s, {"COORD_BITS": c, "DIR_BITS": d, "MODE": mode, "SIM_OUT": str(simdir)},
                         out / f"build_{w}.log"):
        say(lines, f"rtl {w}: harness build FAIL (log {shown(out / f'build_{w}.log')})")
        return {"pass": False, "lines": lines}
    sim, cli = simdir / "pluecker_sim", Path(s["model_build"]) / "pluecker"
    # The extreme queries serve every width; the set-up queries depend on
    # COORD_BITS (boxes inside its range); the operands on the build.
    sets = {"extreme": (out / f"extreme_{n}.txt", "20261"), "setup": (out / f"setup_{c}_{n}.txt", "20262")}
    ok = True
    for kind in ("extreme", "setup", "boundary", "ports"):
        if kind in sets:
            queries, seed = sets[kind]
            exact = queries.with_suffix(".exact")
            write_once(queries, [sim, "gen", "--n", n, "--kind", kind, "--seed", seed, "--out", "{out}"])
            write_once(exact, [cli, "query", "--test", "exact", queries])
        else:
            queries, exact = out / f"{kind}_{w}_{n}.txt", None
            subprocess.run([str(sim), "gen", "--n", str(n), "--kind", kind, "--seed", "20263", "--out", str(queries)],
                           cwd=ROOT, check=True)
        ok &= bool(check_queries(sim, queries, exact, out, f"rtl {w}", kind, mode, t0, lines))
    return {"pass": ok, "lines": lines}


def local_job(s: dict, cfg: str) -> dict:
    """One configuration of the local part: the harness build and its four
    query sets; "queries" counts the queries of the sets that ran."""
    t0 = time.monotonic()
    out, n = Path(s["out"]), s["local_n"]
    k, d, g, ch, nearest = LOCAL_RE.fullmatch(cfg).groups()
    mode = "nearest" if nearest else "conservative"
    simdir = Path(s["sim_root"]) / f"local_k{k}_d{d}_g{g}_c{ch}{'_nearest' if nearest else ''}"
    lines: list[str] = []
    env = {"SIM_UNIT": "local", "BOX_BITS": k, "DIR_BITS": d, "GRID_BITS": g, "CHILDREN": ch, "MODE": mode,
           "SIM_OUT": str(simdir)}
    if not build_harness(s, env, out / f"build_local_{cfg}.log"):
        say(lines, f"local {cfg}: harness build FAIL (log {shown(out / f'build_local_{cfg}.log')})")
        return {"pass": False, "lines": lines, "queries": 0}
    sim, cli = simdir / "pluecker_sim_local", Path(s["model_build"]) / "pluecker"
    ok, total = True, 0
    for kind in ("extreme", "setup", "boundary", "random"):
        count = n if kind == "extreme" else n // 2
        # The set-up queries depend on the grid's range; the others on nothing.
        queries = out / f"local_{kind}_{f'g{g}_' if kind == 'setup' else ''}{count}.txt"
        exact = queries.with_suffix(".exact")
        write_once(queries, [sim, "gen", "--n", count, "--kind", kind, "--seed", "20263", "--out", "{out}"])
        write_once(exact, [cli, "query", "--test", "exact", queries])
        r = check_queries(sim, queries, exact, out, f"local {cfg}", kind, mode, t0, lines)
        ok &= bool(r)
        total += count if r is not None else 0
    return {"pass": ok, "lines": lines, "queries": total}


def pytest_job(s: dict, node: str, log: str, extra_env: dict) -> dict:
    """One pytest test with PLUECKER_LONG=1, its output into log."""
    t0 = time.monotonic()
    env = dict(os.environ, PLUECKER_LONG="1", PLUECKER_PY_DIR=s["model_build"], **extra_env)
    rc = run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", node], Path(log), env)
    return {"pass": rc == 0, "node": node, "log": log, "tail": log_lines(Path(log))[-5:],
            "seconds": time.monotonic() - t0}


def float_job(s: dict, u: str) -> dict:
    """One binary32 unit of the float part: its harness and the four kinds
    of `pluecker_sim check`."""
    t0 = time.monotonic()
    out = Path(s["out"])
    unit = u.removesuffix("_cons")
    mode = "conservative" if u.endswith("_cons") else "nearest"
    simdir = Path(s["sim_root"]) / u
    lines: list[str] = []
    if not build_harness(s, {"SIM_UNIT": unit, "MODE": mode, "SIM_OUT": str(simdir)}, out / f"build_{u}.log"):
        say(lines, f"float {u}: harness build FAIL (log {shown(out / f'build_{u}.log')})")
        return {"pass": False, "lines": lines}
    ok = True
    for kind, pct, exact in FLOAT_KINDS:
        log = out / f"float_{u}_{kind}.log"
        with open(log, "w") as e:
            r = subprocess.run([str(simdir / "pluecker_sim"), "check", "--n", str(s["float_n"] * pct // 100),
                                "--kind", kind, "--seed", "20263", *(["--exact"] if exact else [])],
                               cwd=ROOT, stdout=subprocess.PIPE, stderr=e, text=True)
        line = r.stdout.rstrip("\n")
        if r.returncode != 0:
            say(lines, f"float {u} {kind}: FAIL ({line})")
            lines += log_lines(log)[:5]
            ok = False
            continue
        say(lines, f"float {u}: {line}")
        if mode == "conservative" and exact:
            m = re.search(r" (\d*) false misses", line)
            fm = m.group(1) if m else ""
            if fm != "0":
                say(lines, f"float {u} {kind}: {fm} false misses (conservative)")
                ok = False
    say(lines, f"float {u}: done ({elapsed(t0)})")
    return {"pass": ok, "lines": lines}


# --------------------------------------------------------------------------
# The driver

def collect(s: dict, paths: tuple, extra_env: dict, log: Path) -> list[str] | None:
    """The test ids of paths with PLUECKER_LONG=1 (one job each); None when
    pytest cannot collect them (its output in log)."""
    env = dict(os.environ, PLUECKER_LONG="1", PLUECKER_PY_DIR=s["model_build"], **extra_env)
    r = subprocess.run([sys.executable, "-m", "pytest", "--collect-only", "-q", "-p", "no:cacheprovider", *paths],
                       cwd=ROOT, env=env, capture_output=True, text=True)
    log.write_text(r.stdout + r.stderr)
    nodes = [x.strip() for x in r.stdout.splitlines() if "::" in x]
    return nodes if r.returncode == 0 and nodes else None


def log_name(out: Path, part: str, node: str) -> str:
    return str(out / f"{part}_{re.sub(r'[^A-Za-z0-9_.-]', '_', node.removeprefix('tb/'))}.log")


def plan(s: dict) -> tuple[dict[str, list[jobs.Job]], dict]:
    """The jobs of each part, and the pytest parts' test ids (None when
    pytest could not collect them)."""
    out, parts = Path(s["out"]), s["parts"]
    job_lists: dict[str, list[jobs.Job]] = {p: [] for p in PARTS if p in parts}
    tests: dict[str, list | None] = {}
    if "model" in parts:
        job_lists["model"] = [jobs.Job("model", "regress:model_job",
                                       (s, "model: long extremes, margin and set-up suites",
                                        "Extremes.*:MarginBound.*:Setup.*", "model.log", MODEL_FIGURES.pattern,
                                        True))]
    if "rtl" in parts:
        job_lists["rtl"] = [jobs.Job(f"rtl {w}", "regress:rtl_job", (s, w)) for w in s["widths"]]
    if "local" in parts:
        job_lists["local"] = [jobs.Job(f"local {c}", "regress:local_job", (s, c)) for c in s["local_configs"]]
    for part, paths, env in (("cocotb", STRESS, {"PLUECKER_STRESS_SCALE": str(s["stress_scale"])}),
                             ("sweep", SWEEP, {})):
        if part in parts:
            tests[part] = collect(s, paths, env, out / f"{part}_collect.log")
            job_lists[part] = [jobs.Job(f"{part} {node}", "regress:pytest_job",
                                        (s, node, log_name(out, part, node), env)) for node in tests[part] or []]
    if "float" in parts:
        job_lists["float"] = [jobs.Job("float model", "regress:model_job",
                                       (s, "float: long model suite", "F32Unit.*", "float_model.log",
                                        FLOAT_FIGURES.pattern, False))]
        job_lists["float"] += [jobs.Job(f"float {u}", "regress:float_job", (s, u)) for u in s["float_units"]]
    return job_lists, tests


PYTEST_HEADLINES = {"cocotb": "long stress", "sweep": "long cocotb sweeps"}


def pytest_summary(part: str, results: list[dict], crashed: list[jobs.JobError], collected: list | None,
                   out: Path) -> tuple[bool, list[str]]:
    """One PASS/FAIL line for all the tests of a pytest part, then each
    failed test with the tail of its log, and each lost job."""
    lines: list[str] = []
    head = f"{part}: {PYTEST_HEADLINES[part]}"
    if collected is None:
        say(lines, f"{head} FAIL (pytest collected no test; log {shown(out / f'{part}_collect.log')})")
        return False, lines
    failed = [r for r in results if not r["pass"]]
    ok = not failed and not crashed
    seconds = sum(r["seconds"] for r in results)
    say(lines, f"{head} {'PASS' if ok else 'FAIL'} ({len(collected)} tests, {len(failed) + len(crashed)} failed, "
               f"{int(seconds)} s in all; logs {shown(out)}/{part}_*.log)")
    for r in failed:
        say(lines, f"{part} {r['node']}: FAIL (log {shown(r['log'])})")
        lines += r["tail"]
    lines += [f"regress: {e}" for e in crashed]
    return ok, lines


def summary_lines(s: dict, job_lists: dict, tests: dict, results: dict,
                  crashed: dict[str, jobs.JobError]) -> tuple[bool, list[str]]:
    """Every part's lines in the order of the parts; (passed, lines)."""
    lines: list[str] = []
    ok = True
    for part, part_jobs in job_lists.items():
        if part == "cocotb":
            say(lines, f"cocotb: stress scale {s['stress_scale']} (x the make-test sizes)")
        if part in PYTEST_HEADLINES:
            part_ok, part_lines = pytest_summary(part, [results[j.name] for j in part_jobs if j.name in results],
                                                 [crashed[j.name] for j in part_jobs if j.name in crashed],
                                                 tests[part], Path(s["out"]))
            ok &= part_ok
            lines += part_lines
            continue
        for j in part_jobs:
            if j.name in crashed:
                say(lines, str(crashed[j.name]))
                ok = False
                continue
            lines += results[j.name]["lines"]
            ok &= results[j.name]["pass"]
        if part == "local":
            total = sum(results[j.name]["queries"] for j in part_jobs if j.name in results)
            say(lines, f"local: {total} queries through the local unit's RTL")
    return ok, lines


def main() -> int:
    try:
        s = settings()
    except BadSetting as e:
        print(f"regress: {e}", file=sys.stderr)
        return 2
    for tool in ("model_tests", "pluecker"):
        if not os.access(Path(s["model_build"]) / tool, os.X_OK):
            print(f"regress: {s['model_build']}/{tool} missing (run 'make build')", file=sys.stderr)
            return 2
    out = Path(s["out"])
    out.mkdir(parents=True, exist_ok=True)
    summary = out / "summary.txt"
    summary.write_text("")
    job_lists, tests = plan(s)
    try:
        results = jobs.run_jobs([j for js in job_lists.values() for j in js], label="regress",
                                local_workers=s["jobs"], journal=out / "jobs.jsonl",
                                summary=lambda r: "PASS" if r["pass"] else "FAIL")
        crashed: dict[str, jobs.JobError] = {}
    except jobs.JobsFailed as e:
        results, crashed = e.results, {x.name: x for x in e.errors}
    ok, lines = summary_lines(s, job_lists, tests, results, crashed)
    say(lines, f"{'all PASS' if ok else 'FAILED'} (summary {shown(summary)})")
    summary.write_text("\n".join(lines) + "\n")
    print("\n".join(lines), flush=True)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
