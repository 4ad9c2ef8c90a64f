"""``python3 -m cracklip``: see cracklip.cli."""
import os
import signal
import sys

from .solvers.huge_pages import reexec_with_huge_pages

# First of all: malloc on huge pages where the kernel gives them on request
# only (solvers/huge_pages.py; CRACKLIP_HUGE_PAGES=0 keeps this process).
reexec_with_huge_pages()

from .cli import finish_processes, main  # noqa: E402

# Die quietly when the reader of stdout goes away (`... | head`), as Unix
# tools do, instead of PETSc's signal handler aborting MPI with a report.
if hasattr(signal, "SIGPIPE"):
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
status = main()
# Leave without the interpreter's teardown (MPI and PETSc finalisation,
# freeing the mesh and matrices: ~0.25 s of a 2.5 s run): every output file
# is closed by now, only the standard streams need flushing.
sys.stdout.flush()
sys.stderr.flush()
finish_processes()
os._exit(status)
