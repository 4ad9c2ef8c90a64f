"""The contact multipliers' stabilization (contact/stabilization.py): the
penalty on neighbouring groups' differences, and the saddle point's
multiplier block D = 1 (inactive) / -S (active) on every assembly path."""
import numpy as np
import pytest
import scipy.sparse as sp

from cracklip.contact.stabilization import (DEFAULT_GAMMA, linear_fit_residual, stabilization_gamma,
                                           stabilization_matrix)
from cracklip.solvers.checked import scipy_from_petsc
from cracklip.solvers.saddle import multiplier_block, saddle_matrix


def _planar_groups(m: int, seed: int = 0) -> tuple[sp.csr_matrix, np.ndarray]:
    """m group points on a tilted plane in 3D and a mass coupling the
    groups within 0.35 of each other (positive, symmetric)."""
    rng = np.random.default_rng(seed)
    uv = rng.uniform(0.0, 1.0, size=(m, 2))
    t1, t2 = np.array([1.0, 0.0, 0.3]), np.array([0.0, 1.0, -0.2])
    x = np.array([0.1, 0.2, 0.3]) + uv[:, :1] * t1 + uv[:, 1:] * t2
    dist = np.linalg.norm(x[:, None] - x[None], axis=2)
    M = sp.csr_matrix(np.where(dist < 0.35, 1.0 / (1.0 + dist), 0.0))
    return M, x


def test_stabilization_matrix_vanishes_on_linear_pressures_and_is_positive_semidefinite():
    M, x = _planar_groups(40)
    h = np.linspace(0.1, 0.3, 40)
    S = stabilization_matrix(M, x, h, E=200.0, gamma=2.0).toarray()
    assert np.abs(S - S.T).max() <= 1e-15 * np.abs(S).max()
    assert np.linalg.eigvalsh(S).min() >= -1e-12 * np.abs(S).max()
    scale = np.abs(S).max()
    for lam in (np.ones(40), 3.0 + x @ np.array([0.5, -1.0, 2.0])):  # constant, linear: no penalty
        assert np.abs(S @ lam).max() <= 1e-11 * scale * np.abs(lam).max()
    # R: the residual of the neighbours' linear fit, exactly zero on linear values.
    R = linear_fit_residual(M, x)
    assert np.abs(R @ (x @ np.array([1.0, 2.0, 3.0]))).max() <= 1e-12
    # A checkerboard (alternate signs by group) is penalised at its own size.
    checker = np.where(np.arange(40) % 2 == 0, 1.0, -1.0)
    r = R @ checker
    assert np.sqrt(np.mean(r ** 2)) > 0.5
    assert checker @ S @ checker > 0.1 * np.sum(2.0 * h * np.asarray(M.sum(axis=1)).ravel() / 200.0)
    assert stabilization_matrix(M, x, h, 200.0, 0.0) is None


def test_stabilization_gamma_defaults_by_dimension():
    assert stabilization_gamma(None, 2) == DEFAULT_GAMMA[2] == 0.0
    assert stabilization_gamma(None, 3) == DEFAULT_GAMMA[3] > 0.0
    assert stabilization_gamma(0.5, 3) == 0.5


def test_saddle_matrix_with_stabilization_matches_its_blocks():
    """The direct path's C++ assembly (saddle_csr) against scipy's blocks:
    D = 1 on inactive multipliers, -S on the active rows and columns."""
    rng = np.random.default_rng(2)
    n, m = 20, 6
    K = sp.random(n, n, density=0.3, random_state=rng)
    K = (K + K.T + n * sp.eye(n)).tocsr()
    B = sp.random(m, n, density=0.4, random_state=rng).tocsr()
    Mg, xg = _planar_groups(m, 3)
    S = stabilization_matrix(Mg, xg, np.full(m, 0.2), 1.0, 2.0)
    active = np.array([1, 0, 1, 1, 0, 1], dtype=bool)
    D = multiplier_block(active, S).toarray()
    assert np.allclose(np.diag(D)[~active], 1.0) and np.allclose(D[~active][:, active], 0.0)
    assert np.allclose(D[np.ix_(active, active)], -S.toarray()[np.ix_(active, active)])
    Ba = sp.diags(active.astype(float)) @ B
    ref = sp.bmat([[K, Ba.T], [Ba, sp.csr_matrix(D)]]).toarray()
    A = saddle_matrix(K, B, active, S)
    got = scipy_from_petsc(A).toarray()
    A.destroy()
    assert np.abs(got - ref).max() <= 1e-15 * np.abs(ref).max()
    A = saddle_matrix(K, B, active)  # without S: the old matrix
    got = scipy_from_petsc(A).toarray()
    A.destroy()
    ref0 = sp.bmat([[K, Ba.T], [Ba, sp.diags((~active).astype(float))]]).toarray()
    assert np.abs(got - ref0).max() == 0.0


def test_stabilization_fits_among_the_closed_groups_only():
    """With some groups open (their multipliers held at 0), a pressure linear
    over the closed ones and 0 on the open ones is not penalised: the edge
    of the closed part is a kink of the pressure, not a checkerboard; S is
    empty on the open groups' rows and columns."""
    from cracklip.contact.stabilization import Stabilization
    M, x = _planar_groups(60, 5)
    st = Stabilization(M, x, np.full(60, 0.2), 1.0, 3.0)
    active = x[:, 0] < 0.6
    lam = np.where(active, 2.0 + x @ np.array([1.0, -0.5, 0.2]), 0.0)
    S = st.matrix(active)
    assert np.abs(S[~active]).max() == 0.0 and np.abs(S[:, ~active]).max() == 0.0
    assert np.abs(S @ lam).max() <= 1e-11 * np.abs(S).max() * np.abs(lam).max()
    # The fit over every group would see the kink.
    S_all = st.matrix(np.ones(60, dtype=bool))
    assert np.abs(S_all @ lam).max() > 1e-3 * np.abs(S_all).max() * np.abs(lam).max()
