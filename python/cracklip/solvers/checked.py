"""Checked direct solves with MUMPS, and which BLAS they run on.

The stiffness and the saddle-point system of frictionless contact are
symmetric, and their solvers ask for MUMPS LDL^T (PETSc's "cholesky" with the
matrix flagged symmetric: MUMPS sym = 2, symmetric indefinite, which also
covers the saddle point): half the flops and memory of LU. MUMPS can meet a
singular saddle-point or stiffness matrix (a piece of the domain cut free by a
crack, a constraint missing) and return an arbitrary solution with only a
warning. Every solve here reads the factorisation status,
the number of null pivots and the relative residual, and raises SolverError
naming the likely cause.
"""
from __future__ import annotations

import contextlib
import functools
import logging
import os
import pathlib

import numpy as np
import scipy.sparse as sp
from petsc4py import PETSc

from ..errors import SolverError
from ..scene.processes import on_all


logger = logging.getLogger(__name__)


#: Records of the checked solves inside a ``record_solves()`` block (else None).
_SOLVE_RECORDS: list | None = None


@contextlib.contextmanager
def record_solves():
    """Collect one record per checked solve inside the block (also those made
    by the contact active set): {"what", "size", "relative_residual",
    "solver" ("direct" or "iterative"), "method", "iterations"} (iterative
    solves add "band" and "setup_reused", see cracklip.solvers)."""
    global _SOLVE_RECORDS
    outer, _SOLVE_RECORDS = _SOLVE_RECORDS, []
    try:
        yield _SOLVE_RECORDS
    finally:
        _SOLVE_RECORDS = outer


def petsc_from_scipy(A: sp.spmatrix) -> PETSc.Mat:
    """A sequential PETSc AIJ copy of a scipy sparse matrix."""
    A = A.tocsr()
    A.sort_indices()
    return PETSc.Mat().createAIJ(A.shape, csr=(A.indptr.astype(PETSc.IntType), A.indices.astype(PETSc.IntType),
                                               A.data), comm=PETSc.COMM_SELF)


def scipy_from_petsc(A: PETSc.Mat) -> sp.csr_matrix:
    """A scipy CSR copy of an assembled sequential PETSc AIJ matrix."""
    indptr, indices, data = A.getValuesCSR()
    return sp.csr_matrix((data, indices, indptr), shape=A.getSize())


def record_solve(record: dict) -> None:
    """Append a solve record to the open record_solves() block, if any."""
    if _SOLVE_RECORDS is not None:
        _SOLVE_RECORDS.append(record)


def create_lu_solver(A: PETSc.Mat, detect_null_pivots: bool = True, symmetric: bool = False) -> PETSc.KSP:
    """KSP preonly + MUMPS on A: LU, or LDL^T (symmetric: A must be
    symmetric; it is flagged so, which makes MUMPS use sym = 2).

    The ordering is MUMPS' own choice (ICNTL(7) = 7): with Debian's MUMPS
    (no METIS, no SCOTCH) it picks PORD, which has the fewest factor entries
    and flops of AMD, AMF, PORD and QAMD on cracklip's matrices
    (demos/bench_solvers.py --orderings records them)."""
    ksp = PETSc.KSP().create(A.getComm())  # (a distributed A: parallel MUMPS)
    if symmetric:
        A.setOption(PETSc.Mat.Option.SYMMETRIC, True)
        A.setOption(PETSc.Mat.Option.SYMMETRY_ETERNAL, True)
    ksp.setOperators(A)
    ksp.setType("preonly")
    pc = ksp.getPC()
    pc.setType("cholesky" if symmetric else "lu")
    pc.setFactorSolverType("mumps")
    pc.setFactorSetUpSolverType()
    F = pc.getFactorMatrix()
    if detect_null_pivots:
        F.setMumpsIcntl(24, 1)  # null pivot detection
    F.setMumpsIcntl(4, 0)  # silent
    F.destroy()  # our handle only (see factor_call); the PC keeps its own
    return ksp


def factor_call(ksp: PETSc.KSP, method: str, *args):
    """Call a method of the KSP's factor matrix and release the handle.

    petsc4py's getFactorMatrix() takes a reference that is not given back
    when the Python object is collected once the factorisation exists: every
    checked solve leaked the MUMPS factors (~4 GB over a 1e6-dof benchmark
    size). Destroying the handle drops that reference only."""
    F = ksp.getPC().getFactorMatrix()
    try:
        return getattr(F, method)(*args)
    finally:
        F.destroy()


#: MUMPS' workspace relaxation ICNTL(14) (per cent) tried in turn while a
#: factorisation runs out of workspace (INFOG(1) = -8, -9: delayed pivots
#: of ill-conditioned enriched dofs).
WORKSPACE_RELAXATIONS = (20, 100, 400)


def factor_relaxed(M: PETSc.Mat, symmetric: bool) -> tuple[PETSc.KSP, "PETSc.Error | None", int]:
    """The MUMPS factorisation of M (create_lu_solver), retried with a
    larger workspace (WORKSPACE_RELAXATIONS) while it runs out of it:
    (its KSP, the PETSc error of the last try or None, its INFOG(1)). The
    caller checks the outcome (and destroys the KSP)."""
    for relax in WORKSPACE_RELAXATIONS:
        ksp = create_lu_solver(M, symmetric=symmetric)
        try:
            factor_call(ksp, "setMumpsIcntl", 14, relax)
            error = None
            try:
                ksp.setUp()
            except PETSc.Error as e:
                error = e
            info = factor_call(ksp, "getMumpsInfog", 1)
        except BaseException:
            ksp.destroy()
            raise
        if info in (-8, -9) and relax < WORKSPACE_RELAXATIONS[-1]:
            ksp.destroy()  # workspace too small: retry with more
            continue
        return ksp, error, info
    raise AssertionError("unreachable")  # pragma: no cover


def solve_checked(A: PETSc.Mat, b: PETSc.Vec, residual_tol: float = 1e-8,
                  what: str = "system", scale: bool = True, symmetric: bool = False) -> PETSc.Vec:
    """Solve A x = b by MUMPS; raise SolverError on any sign of failure.

    symmetric: A is symmetric (the stiffness, the frictionless saddle point;
    not the frictional system, whose slip rows are not): LDL^T (MUMPS
    sym = 2, half the work of LU; only one triangle of A is read, so a
    non-symmetric A gives a wrong answer that the residual check reports);
    else LU.

    scale: solve the symmetrically Jacobi-scaled system D A D y = D b, x = D y
    (D = |diag A|^-1/2): enriched dofs with small supports make the raw matrix
    badly scaled, which costs MUMPS delayed pivots, time and memory. If MUMPS
    runs out of workspace (INFOG(1) = -8, -9) the factorisation is retried
    with more (ICNTL(14)). The residual is checked on the unscaled system.
    """
    M, rhs, d = A, b, None
    if scale:
        d = A.getDiagonal()
        arr = np.abs(d.array)
        arr[arr == 0.0] = 1.0
        d.array[:] = 1.0 / np.sqrt(arr)
        M = A.duplicate(copy=True)
        M.diagonalScale(d, d)
        rhs = b.duplicate()
        rhs.pointwiseMult(b, d)
    x = b.duplicate()
    ksp = None
    try:
        ksp, error, info = factor_relaxed(M, symmetric)
        oom = out_of_memory(ksp, error, what, M.getSize()[0])
        if oom is not None:
            raise oom
        if error is not None:
            raise SolverError(f"MUMPS factorisation of the {what} failed ({error}); the matrix is "
                              "probably singular: check that every piece of the domain (a crack may "
                              "cut it in two) has Dirichlet conditions fixing its rigid motion") from None
        if info < 0:
            raise SolverError(f"MUMPS failed on the {what}: INFOG(1) = {info}, INFOG(2) = "
                              f"{factor_call(ksp, 'getMumpsInfog', 2)}")
        null_pivots = factor_call(ksp, "getMumpsInfog", 28)
        if null_pivots > 0:
            raise SolverError(
                f"the {what} is singular: MUMPS found {null_pivots} null pivot(s). Likely cause: a "
                "piece of the domain separated by a crack has no Dirichlet condition fixing its rigid "
                "motion, or an enriched dof sees no stiffness")
        ksp.solve(rhs, x)
    finally:
        if ksp is not None:
            ksp.destroy()
        if scale:
            M.destroy()
            rhs.destroy()
    if scale:
        x.pointwiseMult(x, d)
        d.destroy()
    r = b.duplicate()
    A.mult(x, r)
    r.axpy(-1.0, b)
    bnorm = b.norm()
    rel = r.norm() / bnorm if bnorm > 0 else r.norm()
    r.destroy()
    record_solve({"what": what, "size": A.getSize()[0], "relative_residual": float(rel), "solver": "direct",
                  "method": f"MUMPS {'LDL^T' if symmetric else 'LU'}", "iterations": 1})
    if not on_all(np.all(np.isfinite(x.array)), x.getComm().tompi4py()) or not rel <= residual_tol:
        raise SolverError(f"the solve of the {what} is inaccurate: relative residual {rel:.3g} "
                          f"> {residual_tol:g}; the matrix is singular or very ill-conditioned")
    return x


#: MUMPS' INFOG(1) codes of a factorisation out of memory: -8, -9 (a
#: workspace too small even after the retries with a larger ICNTL(14)),
#: -13 (an allocation failed: the machine's memory is exhausted), -19
#: (ICNTL(23) too small), -17 / -20 (communication buffers).
MUMPS_OUT_OF_MEMORY = (-8, -9, -13, -17, -19, -20)

#: PETSc's error code for a failed allocation (PETSC_ERR_MEM).
PETSC_ERR_MEM = 55


def out_of_memory(ksp: PETSc.KSP, error: Exception | None, what: str, size: int) -> SolverError | None:
    """The SolverError to raise when a MUMPS factorisation ran out of memory
    (MUMPS_OUT_OF_MEMORY, or PETSc's allocation error), naming the size of
    the system and MUMPS' own estimate of what it needed, with the fix;
    None otherwise."""
    info = factor_call(ksp, "getMumpsInfog", 1)
    petsc_mem = isinstance(error, PETSc.Error) and getattr(error, "ierr", None) == PETSC_ERR_MEM
    if info not in MUMPS_OUT_OF_MEMORY and not petsc_mem:
        return None
    detail = f"INFOG(1) = {info}" if info in MUMPS_OUT_OF_MEMORY else "PETSc could not allocate memory"
    if info == -13:
        detail += f": an allocation failed, INFOG(2) = {factor_call(ksp, 'getMumpsInfog', 2)}"
    needed = factor_call(ksp, "getMumpsInfog", 17)  # MB the factorisation was estimated to need (all processes)
    from ..scene.mesh_estimate import available_memory
    free = available_memory()
    return SolverError(
        f"MUMPS ran out of memory factoring the {what} ({size} unknowns; {detail}; it estimated "
        f"{needed / 1e3:.3g} GB for the factors, the machine has {free / 1e9:.3g} GB available now): the model is "
        "too large for a direct solve on this machine. Coarsen the mesh (mesh.h, mesh.tip_h, mesh.crack_h: the "
        "factors of a 3D mesh grow faster than its dofs), use options.solver = \"iterative\" (AMG, a few KB per "
        "dof), or run where there is more memory")


def estimate_inverse_1norm(ksp: PETSc.KSP, A: PETSc.Mat, max_iter: int = 5) -> float:
    """Estimate ||A^-1||_1 by Hager's method with Higham's refinements (the
    LAPACK xLACON algorithm), from solves with the factorised A and A^T; the
    inverse is never formed."""
    n = A.getSize()[0]
    x, y, z = A.createVecRight(), A.createVecRight(), A.createVecRight()
    x.set(1.0 / n)
    est = 0.0
    j_old = -1
    for it in range(max_iter):
        ksp.solve(x, y)
        new_est = y.norm(PETSc.NormType.NORM_1)
        if it > 0 and new_est <= est:
            break
        est = new_est
        xi = np.sign(y.array)
        xi[xi == 0] = 1.0
        x.array[:] = xi
        ksp.solveTranspose(x, z)
        j = int(np.argmax(np.abs(z.array)))
        if it > 0 and (j == j_old or np.abs(z.array).max() <= z.array[j_old]):
            break
        j_old = j
        x.set(0.0)
        x.array[j] = 1.0
    # Higham's alternating-sign test vector guards against underestimates.
    alt = np.array([(-1) ** i * (1.0 + i / max(n - 1, 1)) for i in range(n)])
    x.array[:] = alt
    ksp.solve(x, y)
    est = max(est, 2.0 * y.norm(PETSc.NormType.NORM_1) / (3.0 * n))
    for v in (x, y, z):
        v.destroy()
    return float(est)


def condition_number_1norm(A: PETSc.Mat) -> dict[str, float]:
    """1-norm condition number (paper eq. 42), estimated from MUMPS solves:
    raw, and after symmetric Jacobi scaling D^-1/2 A D^-1/2."""
    out = {}
    for name, scaled in (("cond_1norm", False), ("cond_1norm_jacobi", True)):
        M = A
        if scaled:
            M = A.duplicate(copy=True)
            d = M.getDiagonal()
            d.sqrtabs()
            d.reciprocal()
            M.diagonalScale(d, d)
            d.destroy()
        ksp = create_lu_solver(M, detect_null_pivots=False)
        ksp.setUp()
        out[name] = float(M.norm(PETSc.NormType.NORM_1) * estimate_inverse_1norm(ksp, M))
        ksp.destroy()
        if scaled:
            M.destroy()
    return out


def _mapped_libraries(marker: str) -> list[str]:
    """Paths of the shared libraries mapped into this process whose file name contains marker."""
    try:
        maps = pathlib.Path("/proc/self/maps").read_text()
    except OSError:
        return []
    return sorted({line.split()[-1] for line in maps.splitlines()
                   if "/" in line and marker in line.rsplit("/", 1)[-1]})


def limit_blas_threads(threads: int = 1) -> None:
    """Run OpenBLAS (if that is the BLAS loaded) on `threads` threads,
    unless OPENBLAS_NUM_THREADS or OMP_NUM_THREADS says otherwise. A second
    thread does not speed up MUMPS here (the two cores share the memory
    bandwidth; demos/bench_solvers.py --threads measures it) and its
    spinning slows down everything else running on the machine."""
    if os.environ.get("OPENBLAS_NUM_THREADS") or os.environ.get("OMP_NUM_THREADS"):
        return
    import ctypes
    for lib in _mapped_libraries("libopenblas"):
        try:
            ctypes.CDLL(lib).openblas_set_num_threads(int(threads))
        except (OSError, AttributeError):  # pragma: no cover - not an OpenBLAS after all
            logger.debug("cannot set the threads of %s", lib)


limit_blas_threads()


@functools.lru_cache(maxsize=None)
def blas_library() -> str:
    """The BLAS library this process runs (PETSc's and MUMPS'), as loaded:
    "openblas-pthread 0.3.21 (/usr/lib/...)" or "reference (netlib) (...)",
    read from /proc/self/maps after PETSc is loaded (so it reports what
    Debian's alternatives or LD_LIBRARY_PATH actually resolved)."""
    libs = sorted(set(_mapped_libraries("blas") + _mapped_libraries("lapack")))
    if not libs:
        return "unknown (no BLAS library mapped)"
    for lib in libs:
        name = os.path.basename(lib)
        if name.startswith("libopenblas"):
            version = name.split("-r", 1)[1].rsplit(".so", 1)[0] if "-r" in name else ""
            flavour = os.path.basename(os.path.dirname(lib))
            return f"openblas {version} ({flavour}; {lib})".replace("  ", " ")
    for lib in libs:
        for marker, label in (("libmkl", "mkl"), ("libblis", "blis"), ("atlas", "atlas")):
            if marker in lib:
                return f"{label} ({lib})"
    blas = [lib for lib in libs if os.path.basename(lib).startswith("libblas")]
    return f"reference (netlib) ({(blas or libs)[0]})"
