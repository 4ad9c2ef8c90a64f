"""The contact multipliers' stabilization: a penalty on each multiplier
group's departure from the linear fit of its neighbours, in the saddle
point's multiplier block (D = -S on the closed multipliers).

Why (issue 36, docs/contact.md): on tetrahedra the stable P1- groups
(cpp/contact/multiplier_space_3d.h) leave a checkerboard of the group
values that a slipping crack excites: the closed penny under shear (a/h 10
and 14, beta 30, mu 0) had pressures 7.1-7.3 % off the exact uniform one,
not falling with h, and K_I along the front took it through the lip term
(0.49, 0.67 % of the K_II scale; 0.21, 0.10 % with the exact pressure put
in the lip term).

What: for every group g, the residual r_g = lambda_g - l_g(x_g), l_g the
least-squares linear function (in the crack's local tangent plane) of the
values of g and of the groups sharing multiplier mass with it (M_gk =
int phi_g phi_k != 0) at their points on the crack (BandSpace.group_x);
S = gamma R^T W R, R the rows of r, W = diag(h_g m_g / E) (m_g = int phi_g,
h_g the group's element size, BandSpace.group_h): a pressure over a patch
of size h opens the crack by about p h / E, so W is the scale of the
Schur complement B K^-1 B^T. S is symmetric positive semi-definite and
vanishes on every linear pressure (a constant one: the patch test stays
exact; the linear pressure of a crack closed in bending, up to its edges),
so it is consistent to second order and costs nothing where the pressure
is smooth; a checkerboard has r_g of its own size. The saddle point stays
symmetric (energy -1/2 lambda^T S lambda).

A first form, the lumped-minus-consistent mass (M_L - M, vanishing on
constants only), damped the checkerboard as well but pulled the pressure of
the bending closure at the edges of the closed part and at the closed front
(K_I there -0.75 -> -1.16 % of the open front's at gamma = 1).

Default gamma by space dimension (DEFAULT_GAMMA): 2D keeps the paper's
stable space without it (its pressures are smooth); 3D takes 8, measured
(docs/contact.md): what is left of the penny's pressure error scales with
1 / gamma (beta 45, mu 0, a/h 14: 1.49 % at gamma 2, 0.79 % at 8; at 4
1.07 / 1.00 % at a/h 14 / 20), and the bending closure keeps its overlap
(0.38 % up to 8 with whole rim rows, 0.72 % at 16); the rows at the rim of
the closed part take a quarter of it (RIM_WEIGHT).
options.multiplier_stabilization overrides it (0: none).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

#: gamma by space dimension (module doc; docs/contact.md).
DEFAULT_GAMMA = {2: 0.0, 3: 8.0}

#: The rows of the groups at the rim of the closed part (a closed group with
#: an open neighbour) take this fraction of gamma: there the pressure has a
#: kink (it falls to 0 like a square root), not a checkerboard, and a stiff
#: fit holds it back from it. Measured (docs/contact.md) with gamma 8: the
#: corner crack's overlap at tip_h 0.1 1.88 % with whole rim rows, 1.44 %
#: with a quarter (gamma 2 everywhere: 1.49 %); on the small corner-crack
#: mesh of tests/test_scenes_3d.py the friction states cycle with whole rim
#: rows from gamma 6 on and settle with a quarter; the bending closure's
#: overlap 0.375 -> 0.363 %. A closed penny (no rim) does not see it.
RIM_WEIGHT = 0.25


def stabilization_gamma(option: float | None, gdim: int) -> float:
    """The scene's gamma: options.multiplier_stabilization, or DEFAULT_GAMMA."""
    return DEFAULT_GAMMA[gdim] if option is None else float(option)


def _fit_row(g: int, nb: np.ndarray, points: np.ndarray) -> np.ndarray:
    """The coefficients c (len(nb)) of the value at points[g] of the
    least-squares linear function of values at points[nb] (nb holds g),
    in the neighbourhood's tangent directions (its points' principal axes,
    at most gdim - 1 of them); too few or too flat a neighbourhood for a
    plane takes a line, then the mean."""
    d = points.shape[1]
    dx = points[nb] - points[g]
    _, sv, vt = np.linalg.svd(dx - dx.mean(axis=0), full_matrices=False)
    k = int(np.count_nonzero(sv[:d - 1] > 1e-6 * max(sv[0] if sv.size else 0.0, 1e-300)))
    while True:
        A = np.column_stack([np.ones(len(nb)), dx @ vt[:k].T]) if k else np.ones((len(nb), 1))
        if k == 0 or np.linalg.matrix_rank(A) == k + 1:
            break
        k -= 1
    if len(nb) <= k + 1:
        # The fit interpolates: its value at x_g is lambda_g exactly (no
        # residual; computed, it would leave round-off, and a diagonal of
        # round-off in the saddle point wrecks its Jacobi scaling).
        return (nb == g).astype(float)
    return np.linalg.pinv(A)[0]


def linear_fit_residual(M: sp.spmatrix, points: np.ndarray, among: np.ndarray | None = None,
                        rows: np.ndarray | None = None) -> sp.csr_matrix:
    """R (m, m): (R lambda)_g = lambda_g minus, at x_g, the least-squares
    linear function (_fit_row) of the values of g and of its neighbours in
    M's graph among the groups `among` (bool mask; default all) at their
    points (m, gdim). R vanishes on values linear in the points. rows: the
    groups whose rows are computed (default: among); the others' are empty."""
    M = sp.csr_matrix(M)
    m = points.shape[0]
    among = np.ones(m, dtype=bool) if among is None else np.asarray(among, dtype=bool)
    todo = np.flatnonzero(among) if rows is None else np.asarray(rows)
    r, c, v = [], [], []
    for g in todo:
        nb = M.indices[M.indptr[g]:M.indptr[g + 1]]
        nb = np.union1d(nb[among[nb]], [g])
        r.append(np.full(len(nb), g))
        c.append(nb)
        v.append(np.where(nb == g, 1.0, 0.0) - _fit_row(int(g), nb, points))
    if not r:
        return sp.csr_matrix((m, m))
    R = sp.csr_matrix((np.concatenate(v), (np.concatenate(r), np.concatenate(c))), shape=(m, m))
    R.eliminate_zeros()
    return R


class Stabilization:
    """S of the module doc for a set of closed (active) groups: the fits
    among the closed groups only (an open group's multiplier is held at 0,
    not a pressure to fit: across the edge of the closed part the pressure
    has a kink), the rows at that edge weighted by RIM_WEIGHT. The rows of
    groups whose neighbours are all closed are computed once; those at the
    edge of the closed part per active set."""

    def __init__(self, M: sp.spmatrix, points: np.ndarray, group_h: np.ndarray, E: float, gamma: float):
        self.M = sp.csr_matrix(M)
        self.points = np.asarray(points, dtype=float)
        mass = np.asarray(self.M.sum(axis=1)).ravel()
        self.weight = gamma * np.asarray(group_h) * mass / E
        self._R_all = linear_fit_residual(self.M, self.points)
        self._cache: dict[bytes, sp.csr_matrix] = {}

    def matrix(self, active: np.ndarray) -> sp.csr_matrix:
        """S (m, m) for the closed groups `active` (rows and columns of the
        others empty)."""
        a = np.asarray(active, dtype=bool)
        key = a.tobytes()
        if key not in self._cache:
            if len(self._cache) > 8:
                self._cache.clear()
            # Groups with an open neighbour: their fits among the closed ones.
            open_nb = np.asarray((self.M @ sp.diags((~a).astype(float))).sum(axis=1)).ravel() != 0.0
            edge = np.flatnonzero(a & open_nb)
            inner = a & ~open_nb
            # (the rows are disjoint: S = R_in^T W R_in + RIM_WEIGHT R_edge^T W R_edge)
            R = (sp.diags(inner.astype(float)) @ self._R_all
                 + np.sqrt(RIM_WEIGHT) * linear_fit_residual(self.M, self.points, a, edge))
            S = (R.T @ sp.diags(self.weight) @ R).tocsr()
            S = (0.5 * (S + S.T)).tocsr()
            S.sort_indices()
            self._cache[key] = S
        return self._cache[key]


def create_stabilization(M: sp.spmatrix, points: np.ndarray, group_h: np.ndarray, E: float,
                         gamma: float) -> Stabilization | None:
    """The groups' Stabilization, or None for gamma = 0."""
    return None if gamma == 0.0 else Stabilization(M, points, group_h, E, gamma)


def stabilization_matrix(M: sp.spmatrix, points: np.ndarray, group_h: np.ndarray, E: float,
                         gamma: float) -> sp.csr_matrix | None:
    """S (m, m) with every group closed; None for gamma = 0."""
    st = create_stabilization(M, points, group_h, E, gamma)
    return None if st is None else st.matrix(np.ones(M.shape[0], dtype=bool))


__all__ = ["DEFAULT_GAMMA", "RIM_WEIGHT", "Stabilization", "create_stabilization", "linear_fit_residual",
           "stabilization_gamma", "stabilization_matrix"]
