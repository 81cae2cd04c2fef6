# SPDX-License-Identifier: MIT
"""scripts/regress.py (`make sim-regress`) without running a regression:

  - a bad setting is refused before any job runs, naming the variable and
    the value (exit 2);
  - the summary keeps the order of the parts, fails the run when a job
    failed its checks or was lost (a crash, a dead worker), names the lost
    job and counts the local part's queries of the jobs that finished.
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import jobs  # noqa: E402  (scripts/jobs.py)
import regress  # noqa: E402  (scripts/regress.py)


@pytest.mark.parametrize("var,value,says", [
    ("REGRESS_WIDTHS", "6x6 16x", "REGRESS_WIDTHS: '16x' is not CxD[n]"),
    ("REGRESS_LOCAL_CONFIGS", "8x11x32", "REGRESS_LOCAL_CONFIGS: '8x11x32' is not KxDxGcC[n]"),
    ("REGRESS_FLOAT_UNITS", "float smits_cons", "REGRESS_FLOAT_UNITS: 'smits_cons' is not float, float_cons or smits"),
    ("REGRESS_PARTS", "model rtll", "REGRESS_PARTS: 'rtll' is not one of model, rtl, local"),
    ("REGRESS_N", "1e6", "REGRESS_N='1e6' is not a positive integer"),
    ("REGRESS_WIDTHS", "6x6 6x6", "REGRESS_WIDTHS: '6x6 6x6' names an entry twice"),
])
def test_bad_setting_is_named(tmp_path, var, value, says):
    env = dict(os.environ, REGRESS_OUT=str(tmp_path), **{var: value})
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "regress.py")], cwd=ROOT, env=env,
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2, r.stdout + r.stderr
    assert says in r.stderr, r.stderr
    assert not (tmp_path / "summary.txt").exists(), "a job ran"


def test_summary_of_passed_failed_and_lost_jobs(tmp_path):
    s = {"out": str(tmp_path), "stress_scale": 3}
    job_lists = {"rtl": [jobs.Job("rtl 6x6", "regress:rtl_job"), jobs.Job("rtl 9x15", "regress:rtl_job")],
                 "local": [jobs.Job("local 4x7x6c1", "regress:local_job"),
                           jobs.Job("local 8x11x32c2", "regress:local_job")],
                 "cocotb": [jobs.Job("cocotb a", "regress:pytest_job"), jobs.Job("cocotb b", "regress:pytest_job")]}
    results = {"rtl 6x6": {"pass": True, "lines": ["regress: rtl 6x6 ok"]},
               "local 4x7x6c1": {"pass": True, "lines": ["regress: local 4x7x6c1 ok"], "queries": 5000},
               "local 8x11x32c2": {"pass": False, "lines": ["regress: local 8x11x32c2 bad"], "queries": 2500},
               "cocotb a": {"pass": True, "node": "a", "log": str(tmp_path / "a.log"), "tail": [], "seconds": 3.0}}
    lost = {"rtl 9x15": jobs.JobError("rtl 9x15", "its worker died while running it"),
            "cocotb b": jobs.JobError("cocotb b", "RuntimeError: boom")}
    ok, lines = regress.summary_lines(s, job_lists, {"cocotb": ["a", "b"]}, results, lost)
    assert not ok
    assert lines[:5] == ["regress: rtl 6x6 ok",
                         "regress: job 'rtl 9x15' failed: its worker died while running it",
                         "regress: local 4x7x6c1 ok", "regress: local 8x11x32c2 bad",
                         "regress: local: 7500 queries through the local unit's RTL"], lines
    assert lines[5] == "regress: cocotb: stress scale 3 (x the make-test sizes)", lines
    assert lines[6].startswith("regress: cocotb: long stress FAIL (2 tests, 1 failed,"), lines
    assert lines[7] == "regress: job 'cocotb b' failed: RuntimeError: boom", lines
    everything = {k: v for k, v in results.items() if k != "local 8x11x32c2"}
    everything.update({"rtl 9x15": results["rtl 6x6"], "cocotb b": results["cocotb a"],
                       "local 8x11x32c2": dict(results["local 8x11x32c2"], **{"pass": True})})
    ok, lines = regress.summary_lines(s, job_lists, {"cocotb": ["a", "b"]}, everything, {})
    assert ok, lines
    assert any(x.startswith("regress: cocotb: long stress PASS (2 tests, 0 failed,") for x in lines), lines
