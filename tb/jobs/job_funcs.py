# SPDX-License-Identifier: MIT
"""Job functions of tb/jobs/test_jobs.py, imported by the Dask workers from
this folder (scripts/jobs.py's Job.path)."""
from __future__ import annotations

import os
import signal
import time


def square(x: int) -> dict:
    return {"x": x, "square": x * x, "pid": os.getpid()}


def fail(x: int) -> dict:
    raise ValueError(f"bad input {x}")


def kill_my_worker(delay: float) -> dict:
    """Kills the worker process that runs it (SIGKILL: no clean-up)."""
    time.sleep(delay)
    os.kill(os.getpid(), signal.SIGKILL)
    return {}
