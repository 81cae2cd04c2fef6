# SPDX-License-Identifier: MIT
"""Run-wide settings of the benches, read from the environment.

  PLUECKER_LONG=1   the long variants (make sim-regress): more queries per
                    test, more configurations where a bench says so
  PLUECKER_SEED     base seed of every random choice (default 1)
  PLUECKER_TB_BUILD root of the per-parameter build folders (default build/tb)
  PLUECKER_RTL_DIR  directory holding the RTL (*.sv) and lint.vlt (default
                    rtl/; lets a mutated copy be checked)
"""

from __future__ import annotations

import os
import zlib
from pathlib import Path

LONG = os.environ.get("PLUECKER_LONG", "0") not in ("", "0")
SEED = int(os.environ.get("PLUECKER_SEED", "1"))
# Queries per test are SCALE x the short sizes.
SCALE = 25 if LONG else 1

REPO = Path(__file__).resolve().parents[2]
TB_DIR = REPO / "tb"
RTL_DIR = Path(os.environ.get("PLUECKER_RTL_DIR", str(REPO / "rtl")))


def build_root() -> Path:
    return Path(os.environ.get("PLUECKER_TB_BUILD", str(REPO / "build" / "tb")))


def seed(*parts: object) -> int:
    """A stable seed from the base seed and a test's identity."""
    return zlib.crc32(repr((SEED,) + parts).encode())
