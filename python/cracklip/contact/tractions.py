"""The contact tractions on a crack's lips at any points of it: the
pressure and the friction shear of a solved contact problem, in the
tangent basis the tangential multipliers act in.

The same for both dimensions: the multiplier field is evaluated at points
(cell, reference coordinates) of the crack (P1 on the stable groups, P0 at
tips and fronts), the pressure p = -lambda_n (>= 0 in compression), the
shear tau_c = -lambda_t,c along each tangent t_c of the crack (2D: t = n
turned by -90 degrees; 3D: t1, t2 of cpp/contact/contact_kernels_3d.h,
from the crack's reference axis). The traction on the + lip is p n + sum_c
tau_c t_c; the - lip carries the opposite. The SIFs' lip terms (2D and 3D)
and the lip samples of a solution take it from here.
"""
from __future__ import annotations

import numpy as np

from .. import _cracklip


def tangent_basis(model, crack: int, normal: np.ndarray) -> np.ndarray:
    """(n, k, d) the unit tangents of the contact coupling at points of a
    crack with unit normals (n, d): k = 1 in 2D (n turned by -90 degrees),
    k = 2 in 3D (t1, t2, (t1, t2, n) right-handed)."""
    normal = np.ascontiguousarray(normal, dtype=float)
    if model.gdim == 2:
        return np.stack([normal[:, 1], -normal[:, 0]], axis=1)[:, None, :]
    t1, t2 = _cracklip.tangent_basis_3d(model.geometries[crack], normal)
    return np.stack([t1, t2], axis=1)


def multiplier_values(model, space, crack: int, cells: np.ndarray, ref: np.ndarray, full: np.ndarray) -> np.ndarray:
    """Values (n,) of a full multiplier field at points (cell, ref) of a crack."""
    evaluate = _cracklip.evaluate_multipliers if model.gdim == 2 else _cracklip.evaluate_multipliers_3d
    return np.asarray(evaluate(space, crack, np.asarray(cells, dtype=np.int32),
                               np.ascontiguousarray(ref, dtype=float), full))


def contact_tractions(model, contact: dict, crack: int, cells: np.ndarray, ref: np.ndarray,
                      normal: np.ndarray) -> dict[str, np.ndarray]:
    """The contact tractions of a solved contact problem (contact: the
    solution's contact dict, with "system", "lambda" and with friction
    "lambda_t") at points (cell (n,), ref (n, d)) of a crack with unit
    normals (n, d) into its + side:

    pressure (n,) >= 0 in compression; shear (n, k) the friction traction
    on the + lip along each tangent (zeros without friction); tangents (n,
    k, d) (tangent_basis); traction (n, d) on the + lip, p n + sum_c
    shear_c t_c."""
    cs = contact["system"]
    normal = np.asarray(normal, dtype=float)
    n = len(normal)
    pressure = -multiplier_values(model, cs.space, crack, cells, ref, cs.R @ contact["lambda"])
    traction = pressure[:, None] * normal
    tangents = tangent_basis(model, crack, normal)
    k = tangents.shape[1]
    shear = np.zeros((n, k))
    if "lambda_t" in contact:
        lam_t = np.asarray(contact["lambda_t"]).reshape(k, -1)
        for c in range(k):
            shear[:, c] = -multiplier_values(model, cs.space, crack, cells, ref, cs.R @ lam_t[c])
            traction = traction + shear[:, c, None] * tangents[:, c]
    return {"pressure": pressure, "shear": shear, "tangents": tangents, "traction": traction}


__all__ = ["tangent_basis", "multiplier_values", "contact_tractions"]
