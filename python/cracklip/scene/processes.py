"""Which process does what under ``mpirun``: the communicator, and refusals
every process takes alike.

cracklip runs on MPI.COMM_WORLD. A check that can refuse on one process only
(it looked at its own part of the mesh) must not raise there alone: the other
processes would wait forever in the next collective call. ``agree`` turns the
processes' local verdicts into one: every process raises the error of the
lowest rank that found one. ``not_parallel`` refuses a feature that does not
run on several processes yet, with the same message everywhere.

An error raised through either is marked ``collective``: the command line
prints it once (rank 0) and every process exits with status 2. Any other
error under mpirun aborts the whole job (MPI_Abort) instead of hanging it.
"""
from __future__ import annotations

import typing

from ..errors import CracklipError, InputError


def world():
    """MPI.COMM_WORLD (mpi4py imported on first use)."""
    from mpi4py import MPI
    return MPI.COMM_WORLD


def num_processes() -> int:
    return world().size


def mark_collective(error: BaseException) -> BaseException:
    """error, marked as raised alike on every process."""
    error.collective = True  # type: ignore[attr-defined]
    return error


def is_collective(error: BaseException) -> bool:
    return bool(getattr(error, "collective", False))


def agree(error: CracklipError | None, comm=None) -> None:
    """Collective: raise on every process the error of the lowest rank that
    has one (its class and message), or return on all if none has. In
    serial: raise error if given."""
    comm = world() if comm is None else comm
    if comm.size == 1:
        if error is not None:
            raise error
        return
    verdicts = comm.allgather(None if error is None else (type(error), str(error)))
    first = next((v for v in verdicts if v is not None), None)
    if first is None:
        return
    if error is not None and str(error) == first[1]:
        raise mark_collective(error)
    raise mark_collective(_rebuilt(*first))


def replicated(fn: typing.Callable[[], typing.Any], comm=None) -> typing.Any:
    """Collective: fn() on every process (no collective call inside: work
    every process does alike, e.g. reading the scene's files); a
    CracklipError or OSError of any process is raised on all (agree)
    instead of on one alone, which would leave the others waiting in their
    next collective call. In serial: fn()."""
    comm = world() if comm is None else comm
    if comm.size == 1:
        return fn()
    value, error = None, None
    try:
        value = fn()
    except (CracklipError, OSError) as e:
        error = e
    agree(error, comm)
    return value


def total(count: int, comm=None) -> int:
    """Collective: the sum of a count over the processes (count in serial)."""
    comm = world() if comm is None else comm
    return int(count) if comm.size == 1 else int(comm.allreduce(int(count)))


def on_all(flag: bool, comm=None) -> bool:
    """Collective: whether flag holds on every process (flag in serial)."""
    comm = world() if comm is None else comm
    return bool(flag) if comm.size == 1 else bool(comm.allreduce(bool(flag), op=_land()))


def gathered(comm, arrays: list) -> list:
    """Collective: every process's arrays (numpy, same columns) concatenated
    in rank order (the arrays themselves in serial)."""
    if comm.size == 1:
        return arrays
    import numpy as np
    parts = comm.allgather(arrays)
    return [np.concatenate([p[i] for p in parts]) for i in range(len(arrays))]


def reduced(value, op: str, comm=None):
    """Collective: value (a number or a numpy array) reduced over the
    processes by the MPI operation named op ("SUM", "MIN", "MAX", "LOR");
    value itself in serial."""
    comm = world() if comm is None else comm
    if comm.size == 1:
        return value
    from mpi4py import MPI
    if hasattr(value, "shape") and getattr(value, "ndim", 0) > 0:  # a numpy array: element by element
        import numpy as np
        a = np.ascontiguousarray(value)
        out = np.empty_like(a)
        comm.Allreduce(a, out, op=getattr(MPI, op))
        return out
    return comm.allreduce(value, op=getattr(MPI, op))


def _land():
    from mpi4py import MPI
    return MPI.LAND


def not_parallel(what: str, comm=None) -> None:
    """Collective: refuse `what` (a feature, by its scene key or command)
    when running on more than one process."""
    comm = world() if comm is None else comm
    if comm.size > 1:
        raise mark_collective(InputError(
            f"{what} is not available under MPI yet ({comm.size} processes): run it without mpirun"))


def first_error(checks: typing.Iterable[typing.Callable[[], None]]) -> CracklipError | None:
    """The CracklipError the first failing check raises (None if all pass),
    for ``agree``."""
    for check in checks:
        try:
            check()
        except CracklipError as e:
            return e
    return None


#: Environment variables in which MPI launchers give the number of
#: processes (Open MPI, MPICH / Hydra, Slurm).
LAUNCHER_SIZE = ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_NTASKS")


def launched_on_several() -> bool:
    """Whether mpirun (Open MPI, an MPICH-style PMI launcher, or Slurm)
    started this process as one of several, read from the launcher's
    environment (nothing is imported: MPI may not be initialised yet)."""
    import os
    for name in LAUNCHER_SIZE:
        try:
            if int(os.environ.get(name, "1")) > 1:
                return True
        except ValueError:
            pass
    return False


#: Environment variables in which MPI launchers give this process's rank.
LAUNCHER_RANK = ("OMPI_COMM_WORLD_RANK", "PMI_RANK", "SLURM_PROCID")


def launcher_rank() -> int:
    """This process's rank as the launcher's environment gives it (0 when
    not launched by mpirun; nothing is imported: MPI may not be
    initialised yet)."""
    import os
    for name in LAUNCHER_RANK:
        try:
            return int(os.environ[name])
        except (KeyError, ValueError):
            pass
    return 0


def on_rank0(fn: typing.Callable[[], int], comm=None) -> int:
    """Collective: fn() on rank 0 only (work that needs no mesh, writes its
    files once; it must make no collective call over COMM_WORLD); every
    process returns its result, or raises its CracklipError or OSError
    (marked collective)."""
    comm = world() if comm is None else comm
    if comm.size == 1:
        return fn()
    # PETSc's initialisation is collective over COMM_WORLD, and fn may import
    # it (life and check import modules that load petsc4py): initialise it on
    # every process first, or rank 0 would wait in it while the others wait
    # in the broadcast below (mismatched collectives crash MPI).
    import petsc4py.PETSc  # noqa: F401
    outcome, error = None, None
    if comm.rank == 0:
        try:
            outcome = ("ok", fn())
        except (CracklipError, OSError) as e:
            error = e
            outcome = ("error", (type(e), str(e)))
    kind, value = comm.bcast(outcome, root=0)
    if kind == "ok":
        return value
    if error is not None:
        raise mark_collective(error)
    raise mark_collective(_rebuilt(*value))


def _rebuilt(cls: type, message: str) -> BaseException:
    """Another process's error (its class and message) on this one."""
    try:
        return cls(message)
    except Exception:  # a class whose constructor takes more than the message
        return CracklipError(message)
