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
import queue
import threading
import typing


logger = logging.getLogger(__name__)


#: What a `run` needs after the mesh, heaviest first. Not gmsh: its import
#: installs a signal handler, which only the main thread may do (the command
#: line imports gmsh before it starts the thread: loaded side by side, the
#: two slowed each other, 0.47 s for gmsh instead of 0.26 s).
RUN_MODULES = ("dolfinx.fem.petsc", "cracklip._cracklip", "cracklip.analysis.solve", "cracklip.io.outputs")


class Prefetch:
    """A daemon thread importing the modules put to it, in order, until
    close()."""

    def __init__(self, modules: typing.Sequence[str], thread: bool = True):
        self._queue: queue.SimpleQueue = queue.SimpleQueue()
        self.add(*modules)
        self.thread = None
        if thread:
            self.thread = threading.Thread(target=self._load, name="cracklip-prefetch", daemon=True)
            self.thread.start()

    def add(self, *modules: str) -> None:
        """Import these too, after those already asked for."""
        for name in modules:
            self._queue.put(name)

    def close(self) -> None:
        """Nothing more to import: the thread ends after the last one."""
        self._queue.put(None)

    def _load(self) -> None:
        while (name := self._queue.get()) is not None:
            try:
                importlib.import_module(name)
            except Exception as e:  # the main thread's import reports it
                logger.debug("prefetch of %s failed: %s", name, e)


def start(modules: typing.Sequence[str] = RUN_MODULES) -> Prefetch:
    """Import `modules` in a daemon thread (more with add(); close() when done).
    Under mpirun no thread: PETSc's import initialises MPI-aware state while
    the main thread's first collective (the scene's agreement) runs, and 6 of 8
    four-process runs died at start-up with a garbled message (UnpicklingError:
    invalid load key); the modules are then imported by the main thread."""
    from ..scene.processes import launched_on_several
    return Prefetch(modules, thread=not launched_on_several())
