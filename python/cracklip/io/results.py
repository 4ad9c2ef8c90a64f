"""What every results writer shares (outputs, growth_outputs):
the output folder's check, the versions record of results.json, the check
that no NaN reaches a file, JSON values of numpy types, CSV rows."""
from __future__ import annotations

import csv
import json
import pathlib
import platform
import tempfile

import numpy as np

from .. import __version__
from ..errors import CracklipError, SolverError
from ..solvers.checked import blas_library
from ..solvers.huge_pages import pages
from .files import atomic_path


class OutputError(CracklipError, OSError):
    """An output folder or file cannot be written."""


def versions() -> dict[str, str]:
    import dolfinx
    import petsc4py
    import scipy
    return {"cracklip": __version__, "dolfinx": dolfinx.__version__, "petsc4py": petsc4py.__version__,
            "numpy": np.__version__, "scipy": scipy.__version__,
            "python": platform.python_version(), "blas": blas_library(),
            "malloc": pages()}


def ensure_output_dir(path: str | pathlib.Path) -> pathlib.Path:
    """Create the output folder and check that files can be written in it
    (before a long solve); OutputError naming the folder otherwise."""
    path = pathlib.Path(path)
    try:
        path.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=path, prefix=".cracklip-write-test"):
            pass
    except OSError as e:
        raise OutputError(f"cannot write to the output folder {path}: {e.strerror or e}") from None
    return path


def check_finite(name: str, *arrays) -> None:
    """SolverError if any of the arrays holds NaN or infinity (nothing such is written)."""
    for a in arrays:
        if not np.all(np.isfinite(np.asarray(a, dtype=float))):
            raise SolverError(f"{name} holds NaN or infinity: the solution is not usable")


def json_default(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"cannot write {type(value).__name__} to JSON")


def write_results_json(out: pathlib.Path, results: dict) -> None:
    """out/results.json of a command: strict JSON (no NaN or infinity: a
    SolverError, results.json not written), numpy values as numbers, complete or
    not at all."""
    try:
        text = json.dumps(results, indent=2, allow_nan=False, default=json_default)
    except ValueError as e:
        raise SolverError(f"results.json would hold NaN or infinity ({e}); results.json not written "
                          "(the other outputs of the run are)") from None
    with atomic_path(pathlib.Path(out) / "results.json") as tmp:
        tmp.write_text(text + "\n")


def write_csv(path: pathlib.Path, header: list[str], rows: list[list]) -> None:
    with atomic_path(path) as tmp:
        with tmp.open("w", newline="") as f:
            w = csv.writer(f)
            w.writerow(header)
            for r in rows:
                w.writerow(["" if v is None else f"{v:.12g}" if isinstance(v, (float, np.floating)) else v
                            for v in r])
