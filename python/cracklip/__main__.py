"""``python3 -m cracklip``: see cracklip.cli."""
import signal
import sys

from .cli import main

# Die quietly when the reader of stdout goes away (`... | head`), as Unix
# tools do, instead of PETSc's signal handler aborting MPI with a report.
if hasattr(signal, "SIGPIPE"):
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
sys.exit(main())
