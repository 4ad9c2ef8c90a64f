"""Numerical inf-sup test (paper eqs. 16-17).

beta_min is the smallest eigenvalue of (1/h) B A^-1 B^T w = beta M w on the
reduced multipliers: the generalized eigenproblem of the Schur complement
against the multiplier mass, equivalent to the paper's
(1/h) B^T M^-1 B V = beta A V on its non-zero spectrum. A is the stiffness with
its constraints; its inverse acts through one MUMPS factorisation (one solve
per multiplier), the small dense eigenproblem is solved by LAPACK.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import scipy.linalg

from ..model.assembly import assemble_system
from ..model.model import XfemModel
from ..solvers.checked import create_lu_solver
from .frictionless import create_contact_system


def inf_sup_constant(model: XfemModel, h: float | None = None, max_multipliers: int = 4000,
                     tangential: bool = False) -> float:
    """sqrt(beta_min) of the model's multiplier space (Options.multipliers),
    on triangles or tetrahedra; tangential: of [B_n; B_t] (normal and
    tangential multipliers on the same space, one tangential block in 2D,
    two in 3D, the multiplier mass block-diagonal), the space friction
    uses."""
    if tangential and model.scene.options.friction <= 0.0:
        model = dataclasses.replace(model, scene=dataclasses.replace(
            model.scene, options=dataclasses.replace(model.scene.options, friction=1.0,
                                                     contact=model.scene.options.contact
                                                     if model.scene.options.contact != "none" else "bilateral")))
    cs = create_contact_system(model)
    if tangential:
        import scipy.sparse as sp
        blocks = 1 + cs.Bt.shape[0] // cs.B.shape[0]  # normal + 1 tangent (2D) or 2 (3D)
        cs = dataclasses.replace(cs, B=sp.vstack([cs.B, cs.Bt]).tocsr(), M=sp.block_diag([cs.M] * blocks).tocsr())
    m = cs.B.shape[0]
    if m > max_multipliers:
        raise ValueError(f"{m} multipliers: the dense inf-sup test is limited to {max_multipliers}")
    A, _, _ = assemble_system(model)
    ksp = create_lu_solver(A, detect_null_pivots=False)
    ksp.setUp()
    Bt = cs.B.T.tocsc()
    x, y = A.createVecRight(), A.createVecRight()
    S = np.zeros((m, m))
    for k in range(m):
        x.set(0.0)
        col = Bt[:, k]
        x.array[col.indices] = col.data
        ksp.solve(x, y)
        S[:, k] = cs.B @ y.array
    ksp.destroy()
    A.destroy()
    h = model.h if h is None else h
    S = 0.5 * (S + S.T)
    # The naive space's traces can be linearly dependent on the crack (M
    # singular): work on the range of M, and take the smallest non-zero beta.
    Mm = cs.M.toarray()
    mu, Z = np.linalg.eigh(0.5 * (Mm + Mm.T))
    Z = Z[:, mu > 1e-12 * mu.max()]
    beta = scipy.linalg.eigh(Z.T @ S @ Z / h, Z.T @ Mm @ Z, eigvals_only=True)
    positive = beta[beta > 1e-10 * beta.max()]
    return float(np.sqrt(positive.min()))
