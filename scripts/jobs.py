# SPDX-License-Identifier: MIT
"""Runs a list of independent jobs, here or on a Dask distributed cluster.

Used by scripts/synth.py (`make synth`), scripts/regress.py (`make
sim-regress`) and scripts/report.py (`make report`). Each of them splits its
work into jobs (a configuration's synthesis, one place-and-route run, a
scene's study, one width of the regression...) and hands them to
run_jobs().

  DASK_SCHEDULER=host:port   the jobs go to the Dask distributed scheduler
                             at that address (tcp:// is added when no scheme
                             is given); any cluster that Dask reaches works:
                             `dask scheduler` + `dask worker` by hand,
                             dask-ssh, dask-jobqueue (Slurm, LSF, PBS...).
                             The workers must see the project at the same
                             path (a shared file system) and run the
                             project's venv (scripts/requirements.txt).
  unset                      the jobs run on this machine, `jobs` at a time
                             (threads: every job's work is in subprocesses)

A job names a function as "module:function" and the folders to import it
from (default: scripts/); only this module travels to the workers, by value,
and imports the function there, so a worker needs no set-up beyond the
shared project folder. Arguments and results must pickle (plain data,
pathlib paths, argparse namespaces). A worker process imports a target's
module once and keeps it: restart the workers after changing the scripts.

Progress: one line per finished job ("[label] [k/n] name: done in 12 s").
Failures: a job that raises, or whose worker dies under it (Dask's
KilledWorker, after the scheduler's allowed-failures retries on other
workers), is reported by name with the reason; the other jobs run on, and
the results of every finished job are kept: in the JobsFailed exception
(.results, .errors) and, when a journal path is given, in that JSON-lines
file, one line per finished job, written as each finishes.
"""
from __future__ import annotations

import concurrent.futures
import importlib
import json
import os
import sys
import threading
import time
import traceback
import uuid
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCRIPTS = ROOT / "scripts"
ENV_SCHEDULER = "DASK_SCHEDULER"
CONNECT_TIMEOUT = "30s"


@dataclass
class Job:
    """One unit of work: target "module:function" called with args/kwargs,
    imported from the folders in `path`."""

    name: str
    target: str
    args: tuple = ()
    kwargs: dict = field(default_factory=dict)
    path: tuple[str, ...] = (str(SCRIPTS),)


class JobError(RuntimeError):
    """One failed job: its name and why."""

    def __init__(self, name: str, reason: str):
        super().__init__(f"job '{name}' failed: {reason}")
        self.name, self.reason = name, reason


class JobsFailed(RuntimeError):
    """Some jobs failed; the results of the others are in .results."""

    def __init__(self, label: str, errors: list[JobError], results: dict, journal: Path | None):
        kept = f"; the {len(results)} finished jobs' results are kept" + (f" in {journal}" if journal else "")
        lines = "\n".join(f"  {e}" for e in errors)
        super().__init__(f"{label}: {len(errors)} of {len(errors) + len(results)} jobs failed{kept}:\n{lines}")
        self.errors, self.results, self.journal = errors, results, journal


def call(path: Sequence[str], target: str, args: tuple, kwargs: dict):
    """Runs on the worker: imports target from path and calls it."""
    for p in reversed(path):
        if p not in sys.path:
            sys.path.insert(0, p)
    module, _, func = target.partition(":")
    return getattr(importlib.import_module(module), func)(*args, **kwargs)


def timed_call(path: Sequence[str], target: str, args: tuple, kwargs: dict) -> tuple[object, float]:
    """call() and the seconds it took where it ran."""
    t0 = time.monotonic()
    return call(path, target, args, kwargs), time.monotonic() - t0


def scheduler_address(value: str | None = None) -> str | None:
    """DASK_SCHEDULER (or value) as a Dask address, None when unset."""
    addr = (value if value is not None else os.environ.get(ENV_SCHEDULER, "")).strip()
    if not addr:
        return None
    return addr if "://" in addr else f"tcp://{addr}"


def where(scheduler: str | None = None) -> str:
    addr = scheduler_address(scheduler)
    return f"Dask scheduler {addr}" if addr else "this machine"


class _Progress:
    def __init__(self, label: str, total: int, journal: Path | None):
        self.label, self.total, self.done = label, total, 0
        self.journal = journal
        self.lock = threading.Lock()
        if journal:
            journal.parent.mkdir(parents=True, exist_ok=True)
            journal.write_text("")

    def finished(self, name: str, seconds: float, result=None, error: str | None = None,
                 summary: Callable | None = None) -> None:
        with self.lock:
            self.done += 1
            if error is None:
                extra = f": {summary(result)}" if summary and result is not None else ""
                msg = f"done in {seconds:.0f} s{extra}"
            else:
                msg = f"FAILED after {seconds:.0f} s: {error.splitlines()[0] if error else ''}"
            print(f"[{self.label}] [{self.done}/{self.total}] {name}: {msg}", flush=True)
            if self.journal:
                with open(self.journal, "a") as f:
                    entry = {"job": name, "seconds": round(seconds, 1)}
                    entry.update({"error": error} if error is not None else {"result": result})
                    f.write(json.dumps(entry, default=str) + "\n")


def _check_names(jobs: Sequence[Job]) -> None:
    seen = set()
    for j in jobs:
        if j.name in seen:
            raise ValueError(f"two jobs named '{j.name}'")
        seen.add(j.name)


def run_jobs(jobs: Sequence[Job], *, label: str, local_workers: int = 2, scheduler: str | None = None,
             journal: Path | str | None = None, summary: Callable | None = None) -> dict:
    """Runs every job; returns {name: result} in the order of `jobs`.

    scheduler: a Dask address (default: DASK_SCHEDULER; none = here,
    local_workers at a time). summary(result) -> text for the progress line.
    Raises JobsFailed (naming every failed job, holding the finished ones'
    results) when any job failed."""
    jobs = list(jobs)
    _check_names(jobs)
    journal = Path(journal) if journal else None
    progress = _Progress(label, len(jobs), journal)
    addr = scheduler_address(scheduler)
    print(f"[{label}] {len(jobs)} job{'' if len(jobs) == 1 else 's'} on {where(scheduler)}"
          + ("" if addr else f", {max(1, min(local_workers, len(jobs)))} at a time"), flush=True)
    if addr:
        results, errors = _run_dask(jobs, addr, label, progress, summary)
    else:
        results, errors = _run_local(jobs, local_workers, progress, summary)
    ordered = {j.name: results[j.name] for j in jobs if j.name in results}
    if errors:
        order = {j.name: i for i, j in enumerate(jobs)}
        errors.sort(key=lambda e: order[e.name])
        raise JobsFailed(label, errors, ordered, journal)
    return ordered


def _run_local(jobs, workers, progress, summary):
    results, errors = {}, []

    def one(job: Job):
        t0 = time.monotonic()
        try:
            r, seconds = timed_call(job.path, job.target, job.args, job.kwargs)
        except BaseException as e:  # noqa: BLE001 - reported by name, the others go on
            reason = f"{type(e).__name__}: {e}"
            progress.finished(job.name, time.monotonic() - t0, error=reason + "\n" + traceback.format_exc())
            return job.name, None, JobError(job.name, reason)
        progress.finished(job.name, seconds, result=r, summary=summary)
        return job.name, r, None

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, workers)) as pool:
        for name, r, err in pool.map(one, jobs):
            if err is None:
                results[name] = r
            else:
                errors.append(err)
    return results, errors


def _connect(addr: str):
    from distributed import Client

    try:
        return Client(addr, timeout=CONNECT_TIMEOUT, set_as_default=False)
    except (OSError, TimeoutError) as e:
        raise SystemExit(f"jobs: cannot reach the Dask scheduler at {addr} ({ENV_SCHEDULER}): {e}") from None


def _run_dask(jobs, addr, label, progress, summary):
    import cloudpickle
    from distributed import as_completed

    # This module travels by value, so that the scheduler and the workers
    # need nothing but the project folder (for the targets' modules) at the
    # same path: Dask pickles a task with the standard pickle (a function by
    # reference: `jobs` would have to be importable there) unless that
    # fails, as it does for a local function, which it then pickles with
    # cloudpickle, by value, together with what it calls from a module
    # registered by value.
    cloudpickle.register_pickle_by_value(sys.modules[__name__])

    def job_call(*a):
        return timed_call(*a)

    client = _connect(addr)
    results, errors = {}, []
    try:
        run = uuid.uuid4().hex[:8]
        futures, started = {}, {}
        for j in jobs:
            f = client.submit(job_call, j.path, j.target, j.args, j.kwargs, key=f"{label}-{j.name}-{run}", pure=False)
            futures[f] = j.name
            started[j.name] = time.monotonic()
        for f in as_completed(list(futures), loop=client.loop):
            name = futures[f]
            seconds = time.monotonic() - started[name]  # since submission, for a failure
            try:
                r, seconds = f.result()
            except BaseException as e:  # noqa: BLE001
                reason = _dask_reason(e)
                progress.finished(name, seconds, error=reason)
                errors.append(JobError(name, reason))
                continue
            results[name] = r
            progress.finished(name, seconds, result=r, summary=summary)
    finally:
        client.close()
    return results, errors


def _dask_reason(e: BaseException) -> str:
    kind = type(e).__name__
    if kind == "KilledWorker":
        return f"its worker died while running it (Dask KilledWorker: {e})"
    if kind in ("CancelledError", "FutureCancelledError"):
        return f"cancelled: the scheduler or the connection to it was lost ({kind}: {e})"
    return f"{kind}: {e}"
