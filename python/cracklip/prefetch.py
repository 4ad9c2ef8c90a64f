"""Start-up overlap for the command line: load the heavy modules (DOLFINx,
PETSc, the C++ kernels, the solver and output paths) in a background thread
while the main thread reads the scene and meshes it with gmsh, whose mesher
runs outside the GIL. A module is imported once whichever thread gets there
first (Python's per-module import locks), so the main thread's own imports
simply wait for, or find, what the thread loaded; a failure in the thread is
left to the main thread's import to report.
"""
from __future__ import annotations

import importlib
import logging
import threading
import typing

logger = logging.getLogger(__name__)

#: What a `run` needs after the mesh, heaviest first. Not gmsh: its import
#: installs a signal handler, which only the main thread may do.
RUN_MODULES = ("dolfinx.fem.petsc", "cracklip._cracklip", "cracklip.solve", "cracklip.outputs")


def start(modules: typing.Sequence[str] = RUN_MODULES) -> threading.Thread:
    """Import `modules` in a daemon thread; returns the (started) thread."""
    def load() -> None:
        for name in modules:
            try:
                importlib.import_module(name)
            except Exception as e:  # the main thread's import reports it
                logger.debug("prefetch of %s failed: %s", name, e)
    thread = threading.Thread(target=load, name="cracklip-prefetch", daemon=True)
    thread.start()
    return thread
