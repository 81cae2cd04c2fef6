# SPDX-License-Identifier: MIT
"""scripts/jobs.py, the job runner of `make synth`, `make sim-regress` and
`make report`, on a Dask cluster of a scheduler and two single-thread worker
processes started as a deployment starts them (the `dask` command line, in
a folder of their own, without the project on their Python path: a job
that needs more than the shared project folder fails here):

  - a small sweep (the tiny report's studies: two scenes at two widths,
    with the local-frame studies) gives the same figures on the cluster
    (DASK_SCHEDULER) as on this machine;
  - the jobs run in the worker processes;
  - a failing job is named, the others' results are kept (returned and in
    the journal);
  - a job whose worker process is killed under it is named, the others'
    results are kept.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(ROOT / "scripts"))
import jobs  # noqa: E402  (scripts/jobs.py)

MODEL_BUILD = Path(os.environ.get("PLUECKER_PY_DIR") or ROOT / "build" / "model")


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """The scheduler's address."""
    from distributed import Client

    home = tmp_path_factory.mktemp("dask")
    dask_cli = Path(sys.executable).parent / "dask"
    assert dask_cli.exists(), f"{dask_cli} missing (`make setup` installs dask and distributed)"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    # A job whose worker dies is not retried on another worker, so that the
    # test sees the failure at once (the default retries it up to 3 times).
    env["DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES"] = "0"
    address_file = home / "scheduler.json"
    common = ["--host", "127.0.0.1", "--no-dashboard"]
    procs = []
    with open(home / "dask.log", "w") as log:
        try:
            procs.append(subprocess.Popen([dask_cli, "scheduler", "--port", "0", "--scheduler-file", address_file,
                                           *common], cwd=home, env=env, stdout=log, stderr=subprocess.STDOUT))
            deadline = time.monotonic() + 120
            while not address_file.exists():
                assert time.monotonic() < deadline and procs[0].poll() is None, \
                    f"the Dask scheduler did not start: {(home / 'dask.log').read_text()}"
                time.sleep(0.2)
            procs.append(subprocess.Popen([dask_cli, "worker", "--scheduler-file", address_file, "--nworkers", "2",
                                           "--nthreads", "1", *common], cwd=home, env=env, stdout=log,
                                          stderr=subprocess.STDOUT))
            address = json.loads(address_file.read_text())["address"]
            with Client(address, timeout="60s") as client:
                client.wait_for_workers(2, timeout=120)
            yield address
        finally:
            for p in reversed(procs):
                p.terminate()
            for p in procs:
                try:
                    p.wait(timeout=30)
                except subprocess.TimeoutExpired:
                    p.kill()


def job(name: str, func: str, *args) -> jobs.Job:
    return jobs.Job(name, f"job_funcs:{func}", args, path=(str(HERE),))


def journal_entries(path: Path) -> dict:
    return {e["job"]: e for e in map(json.loads, path.read_text().splitlines())}


def tiny_report(out: Path, env: dict) -> dict:
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "report.py"), "--cli", str(MODEL_BUILD / "pluecker"),
                        "--scenes", "sphere:300,teapot", "--widths", "8,16", "--size", "12", "--rtl-widths", "",
                        "--jobs", "1", "--synth-dir", str(out / "no_synth"), "--out", str(out)],
                       cwd=ROOT, env=env, capture_output=True, text=True, timeout=900)
    assert r.returncode == 0, r.stdout + r.stderr
    j = without_times(json.loads((out / "report.json").read_text()))
    return {"scenes": j["scenes"], "derived": j["derived"], "log": r.stdout}


def without_times(x):
    """The report's figures without run times and file paths, which differ
    from run to run."""
    if isinstance(x, dict):
        return {k: without_times(v) for k, v in x.items()
                if not (k.endswith("_ms") or "seconds" in k or k == "study_file")}
    if isinstance(x, list):
        return [without_times(v) for v in x]
    return x


def test_cluster_sweep_equals_local(cluster, tmp_path):
    assert (MODEL_BUILD / "pluecker").exists(), f"{MODEL_BUILD}/pluecker not built (make build)"
    env = {k: v for k, v in os.environ.items() if k != jobs.ENV_SCHEDULER}
    local = tiny_report(tmp_path / "local", env)
    remote = tiny_report(tmp_path / "cluster", dict(env, DASK_SCHEDULER=cluster))
    assert "2 jobs on this machine" in local["log"], local["log"]
    assert f"2 jobs on Dask scheduler {cluster}" in remote["log"], remote["log"]
    assert "[report studies] [2/2]" in remote["log"], remote["log"]
    assert set(remote["scenes"]) == {"sphere:300", "teapot"}
    assert remote["scenes"] == local["scenes"]
    assert remote["derived"] == local["derived"]


def test_cluster_runs_the_jobs_on_workers(cluster):
    res = jobs.run_jobs([job(f"sq{i}", "square", i) for i in range(8)], label="t",
                        scheduler=cluster)
    assert [r["square"] for r in res.values()] == [i * i for i in range(8)]
    assert list(res) == [f"sq{i}" for i in range(8)]  # in the order given
    assert os.getpid() not in {r["pid"] for r in res.values()}, "ran in the client, not on the workers"


@pytest.mark.parametrize("where", ["local", "cluster"])
def test_failed_job_is_named_and_the_rest_kept(cluster, tmp_path, where):
    scheduler = cluster if where == "cluster" else ""
    journal = tmp_path / "jobs.jsonl"
    with pytest.raises(jobs.JobsFailed) as e:
        jobs.run_jobs([job("one", "square", 1), job("broken", "fail", 7), job("three", "square", 3)],
                      label="t", scheduler=scheduler, journal=journal)
    msg = str(e.value)
    assert "1 of 3 jobs failed" in msg and "job 'broken' failed: ValueError: bad input 7" in msg, msg
    assert [x.name for x in e.value.errors] == ["broken"]
    assert {k: v["square"] for k, v in e.value.results.items()} == {"one": 1, "three": 9}
    entries = journal_entries(journal)
    assert entries["one"]["result"]["square"] == 1 and entries["three"]["result"]["square"] == 9
    assert "bad input 7" in entries["broken"]["error"]


def test_dead_worker_is_named_and_the_rest_kept(cluster, tmp_path):
    journal = tmp_path / "jobs.jsonl"
    with pytest.raises(jobs.JobsFailed) as e:
        jobs.run_jobs([job("one", "square", 1), job("victim", "kill_my_worker", 0.5), job("two", "square", 2)],
                      label="t", scheduler=cluster, journal=journal)
    msg = str(e.value)
    assert "job 'victim' failed: its worker died while running it" in msg, msg
    assert [x.name for x in e.value.errors] == ["victim"]
    assert {k: v["square"] for k, v in e.value.results.items()} == {"one": 1, "two": 4}
    assert set(journal_entries(journal)) == {"one", "two", "victim"}


def test_unreachable_scheduler_is_a_clear_error(monkeypatch):
    monkeypatch.setattr(jobs, "CONNECT_TIMEOUT", "2s")
    with pytest.raises(SystemExit, match="cannot reach the Dask scheduler at tcp://127.0.0.1:9"):
        jobs.run_jobs([job("one", "square", 1)], label="t", scheduler="127.0.0.1:9")
