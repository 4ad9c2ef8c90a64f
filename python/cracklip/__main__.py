"""``python3 -m cracklip``: see cracklip.cli."""
import os
import signal
import sys

from .cli import finish_processes, main

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
