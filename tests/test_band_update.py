"""The crack band's kept factorisation updated by Sherman-Morrison-Woodbury
(solvers/band_update.py): a band that changed in a few multiplier rows (a
friction state or slip direction), or in a few multipliers' rows and columns
(a symmetric saddle point's active set), is solved exactly from the earlier
band's factorisation; a large change, other dofs or the other symmetry are
factored again."""
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg  # noqa: F401  (sp.linalg)
from petsc4py import PETSc

from cracklip.solvers import band_update
from cracklip.solvers.band_update import KeptBand, low_rank_change
from cracklip.solvers.checked import petsc_from_scipy
from cracklip.solvers.schwarz import factor_band

N, M = 400, 40  # stiffness dofs of the band, multipliers (rows N .. N + M - 1)


def _band(rows: dict | None = None, symmetric: bool = False) -> sp.csr_matrix:
    """[K C^T; C -D] (symmetric): K a 2D Laplacian-like SPD block, C a
    sparse coupling, D small; `rows` replace multiplier rows (index in
    0..M-1 -> (C row, D row)), and with symmetric their columns too."""
    K = sp.diags([-1.0, -1.0, 4.5, -1.0, -1.0], [-20, -1, 0, 1, 20], shape=(N, N), format="csr")
    C = sp.random(M, N, density=0.02, random_state=1, format="csr") + sp.eye(M, N, k=3)
    D = sp.diags(np.full(M, 1e-3))
    A = sp.bmat([[K, C.T], [C, -D]], format="lil")
    for i, (c, d) in (rows or {}).items():
        A[N + i, :N] = c
        A[N + i, N:] = d
        if symmetric:
            A[:N, N + i] = np.asarray(c).reshape(-1, 1)
    return A.tocsr()


def _solve(bs, rhs: np.ndarray) -> np.ndarray:
    b = PETSc.Vec().createWithArray(rhs.copy(), comm=PETSc.COMM_SELF)
    x = b.duplicate()
    bs.solve(b, x)
    return x.getArray().copy()


def _kept():
    return KeptBand(factor_band, first_multiplier=N)


def test_few_changed_multiplier_rows_are_solved_exactly_from_the_kept_factorisation():
    """Friction: 5 multiplier rows changed (new coupling and diagonal): the
    update's solution equals scipy's of the new band to 1e-12, with one
    factorisation in all and an update of rank 5."""
    dofs = np.arange(N + M)
    A0 = _band()
    kept = _kept()
    first = kept.factor(dofs, petsc_from_scipy(A0), False)
    rng = np.random.default_rng(3)
    rhs = rng.standard_normal(N + M)
    exact0 = sp.linalg.spsolve(A0.tocsc(), rhs)
    assert np.abs(_solve(first, rhs) - exact0).max() <= 1e-12 * np.abs(exact0).max()
    first.destroy()
    rows = {i: (rng.standard_normal(N) * (rng.random(N) < 0.05), np.eye(M)[i] * 2.0) for i in (0, 7, 8, 20, 39)}
    A1 = _band(rows=rows)
    bs = kept.factor(dofs, petsc_from_scipy(A1), False)
    x = _solve(bs, rhs)
    exact = sp.linalg.spsolve(A1.tocsc(), rhs)
    assert np.abs(x - exact).max() <= 1e-12 * np.abs(exact).max()
    assert (kept.factorisations, kept.updates, bs.rank) == (1, 1, 5)
    bs.destroy()
    kept.free()


def test_symmetric_change_rows_and_columns():
    """A symmetric saddle point's multiplier changed in its row and column:
    the change is split into the rows and the remaining columns (rank 2 per
    multiplier) and solved to 1e-12 from the kept LDL^T factorisation."""
    dofs = np.arange(N + M)
    rng = np.random.default_rng(5)
    c = rng.standard_normal(N) * (rng.random(N) < 0.05)
    A0 = _band()
    A1 = _band(rows={4: (c, np.eye(M)[4] * -1e-3)}, symmetric=True)
    E = (A1 - A0).tocsr()
    E.eliminate_zeros()
    R, ER, C, EC = low_rank_change(E, np.arange(N, N + M))
    assert list(R) == [N + 4] and 1 <= len(C) <= np.count_nonzero(c) + 1
    recon = sp.csr_matrix((np.ones(1), ([0], R)), shape=(1, N + M)).T @ ER + EC @ sp.csr_matrix(
        (np.ones(len(C)), (np.arange(len(C)), C)), shape=(len(C), N + M))
    assert abs(recon - E).max() == 0.0
    kept = _kept()
    kept.factor(dofs, petsc_from_scipy(A0), True).destroy()  # (LDL^T, as a symmetric saddle point's band)
    bs = kept.factor(dofs, petsc_from_scipy(A1), True)
    rhs = rng.standard_normal(N + M)
    exact = sp.linalg.spsolve(A1.tocsc(), rhs)
    assert np.abs(_solve(bs, rhs) - exact).max() <= 1e-12 * np.abs(exact).max()
    assert kept.updates == 1 and bs.rank == len(R) + len(C)
    bs.destroy()
    kept.free()


def test_large_change_other_dofs_or_symmetry_factor_again(monkeypatch):
    """More changed rows than the rank limit, other band dofs or the other
    symmetry: a new factorisation, which is kept instead; the same matrix
    again: the kept one as it is (rank 0)."""
    monkeypatch.setattr(band_update, "MIN_RANK", 4)
    dofs = np.arange(N + M)
    rng = np.random.default_rng(7)
    kept = _kept()
    A0 = _band()
    kept.factor(dofs, petsc_from_scipy(A0), False).destroy()
    again = kept.factor(dofs, petsc_from_scipy(A0), False)
    assert (kept.factorisations, kept.updates, again.rank) == (1, 1, 0)
    again.destroy()
    rows = {i: (rng.standard_normal(N) * (rng.random(N) < 0.05), np.eye(M)[i]) for i in range(6)}
    A1 = _band(rows=rows)
    bs = kept.factor(dofs, petsc_from_scipy(A1), False)
    assert kept.factorisations == 2 and bs.rank == 0
    rhs = rng.standard_normal(N + M)
    exact = sp.linalg.spsolve(A1.tocsc(), rhs)
    assert np.abs(_solve(bs, rhs) - exact).max() <= 1e-12 * np.abs(exact).max()
    bs.destroy()
    kept.factor(dofs + 1000, petsc_from_scipy(A1), False).destroy()
    assert kept.factorisations == 3
    kept.factor(dofs + 1000, petsc_from_scipy(A0), True).destroy()  # (A0 is symmetric: LDL^T)
    assert kept.factorisations == 4
    kept.free()


def test_small_change_of_many_multiplier_rows_is_preconditioned_by_the_kept_factorisation(monkeypatch):
    """Friction's last solves turn every slip direction a little: all M
    multiplier rows change (beyond the rank limit) by at most STALE_CHANGE
    of each row's largest entry, nothing else: the kept factorisation is
    used as it is (stale, no factorisation; GMRES needs no exact block), so
    its solve is A0's. A change of 5 % in them, a change of 1e-6 in one
    stiffness row or another pattern is factored again; a symmetric band
    (CG, whose sweep needs the exact block) never goes stale."""
    monkeypatch.setattr(band_update, "MIN_RANK", 4)
    dofs = np.arange(N + M)
    rng = np.random.default_rng(11)
    A0 = _band()
    rhs = rng.standard_normal(N + M)

    def turned(A: sp.csr_matrix, by: float) -> sp.csr_matrix:
        A = A.tocsr(copy=True)
        for i in range(N, N + M):
            lo, hi = A.indptr[i], A.indptr[i + 1]
            A.data[lo:hi] *= 1.0 + by * rng.choice([-1.0, 1.0], hi - lo)
        return A

    kept = _kept()
    kept.factor(dofs, petsc_from_scipy(A0), False).destroy()
    A1 = turned(A0, 0.5 * band_update.STALE_CHANGE)
    bs = kept.factor(dofs, petsc_from_scipy(A1), False)
    assert (kept.factorisations, kept.updates, bs.stale, bs.rank) == (1, 1, True, 0)
    exact0 = sp.linalg.spsolve(A0.tocsc(), rhs)
    assert np.abs(_solve(bs, rhs) - exact0).max() <= 1e-12 * np.abs(exact0).max()
    exact1 = sp.linalg.spsolve(A1.tocsc(), rhs)
    assert np.abs(exact1 - exact0).max() > 1e-6 * np.abs(exact0).max()  # (a preconditioner, not A1's solve)
    bs.destroy()
    bs = kept.factor(dofs, petsc_from_scipy(turned(A0, 5.0 * band_update.STALE_CHANGE)), False)
    assert kept.factorisations == 2 and not bs.stale
    bs.destroy()
    # Measured against the band factored last (now the 5 % one): the small
    # turn again, and a change in a stiffness row.
    A2 = turned(kept._A0_csr(), 0.5 * band_update.STALE_CHANGE)
    A2.data[A2.indptr[3]] *= 1.0 + 1e-6
    assert not kept.factor(dofs, petsc_from_scipy(A2), False).stale
    assert kept.factorisations == 3
    kept.free()
    sym = _kept()
    sym.factor(dofs, petsc_from_scipy(A0), True).destroy()
    A3 = A0.tolil()
    for i in range(M):  # (rows and columns alike, as a symmetric saddle point's)
        A3[N + i, N + i] *= 1.0 + 0.5 * band_update.STALE_CHANGE
    bs = sym.factor(dofs, petsc_from_scipy(A3.tocsr()), True)
    assert not bs.stale and sym.factorisations == 2
    bs.destroy()
    sym.free()
