"""The load vector of a tetrahedral model: every load of a 3D scene against
every basis function (the 3D counterpart of loads.py).

- Tractions on tagged boundary faces (constant, f(x), or sigma(x) n), one
  facet quadrature for standard and enriched dofs, the facets split where a
  crack crosses them (C++ compute_facet_basis_3d).
- Point forces on the standard dofs of the nearest node.
- A constant body force: per cell on the standard dofs, on the enriched
  cells' quadrature for the enriched ones (C++ assemble_cell_load_3d).
- A pressure on a crack's lips: int p [[phi_j]] . n over its lip facets
  (C++ assemble_lip_load_3d on the lip points).
An initial stress is not supported in 3D yet (the scene refuses it).
"""
from __future__ import annotations

import numpy as np

from .. import _cracklip
from ..errors import InputError
from .loads import lip_pressure, traction_values

#: Gauss degree of the lip points (points per facet of the collapsed rules).
LIP_POINTS_3D = 6


def _facets(model, where) -> tuple[np.ndarray, np.ndarray]:
    """(cells, local facet indices) of the boundary facets of a tag."""
    msh = model.scene.mesh.mesh
    facets = model.scene.mesh.facets(where)
    if facets.size == 0:
        raise InputError(f"traction boundary {where!r} has no facets")
    msh.topology.create_connectivity(2, 3)
    msh.topology.create_connectivity(3, 2)
    f2c = msh.topology.connectivity(2, 3)
    c2f = msh.topology.connectivity(3, 2).array.reshape(-1, 4)
    fcells = f2c.array[f2c.offsets[facets]].astype(np.int32)
    flocal = np.argmax(c2f[fcells] == facets[:, None], axis=1).astype(np.int32)
    return fcells, flocal


def _stress_3d(tr, points: np.ndarray) -> np.ndarray:
    """sigma (n, 3, 3) of a Traction given by a stress, checked."""
    sig = np.asarray(tr.stress(points), dtype=float)
    if sig.shape != (len(points), 3, 3):
        raise InputError(f"traction on {tr.where!r}: its stress function returned shape {sig.shape} for points "
                         f"of shape {points.shape}; it must return (n, 3, 3)")
    return sig


def assemble_tractions_3d(model, group: str | None = None) -> np.ndarray:
    """int t . phi_j dA over the loaded faces (only the tractions of `group` if given)."""
    b = np.zeros(model.num_dofs)
    for tr in model.scene.tractions:
        if group is not None and tr.group != group:
            continue
        fcells, flocal = _facets(model, tr.where)
        fb = _cracklip.compute_facet_basis_3d(model.x, model.cells, model.layout, model.geometries, fcells, flocal,
                                              model.scene.options.facet_degree)
        t = traction_values(tr, fb["points"], lambda p: _stress_3d(tr, p), lambda p: fb["normals"])
        q = fb["entry_point"]
        np.add.at(b, fb["entry_dof"], fb["weights"][q] * np.einsum("ij,ij->i", fb["entry_value"], t[q]))
    return b


def assemble_point_forces_3d(model, group: str | None = None) -> np.ndarray:
    b = np.zeros(model.num_dofs)
    for k, pf in enumerate(model.scene.point_forces):
        if group is not None and pf.group != group:
            continue
        d = np.linalg.norm(model.x - np.asarray(pf.point), axis=1)
        node = int(np.argmin(d))
        cells = model.cells[np.any(model.cells == node, axis=1)]
        edge = float(np.linalg.norm(model.x[cells[:, [1, 2, 3, 2, 3, 3]]] - model.x[cells[:, [0, 0, 0, 1, 1, 2]]],
                                    axis=2).max())
        if d[node] > edge:
            raise InputError(f"point force {k} at {list(pf.point)}: the nearest mesh node {model.x[node].tolist()} is "
                             f"{d[node]:.3g} away, more than an element ({edge:.3g}); put the point on the part")
        b[3 * node:3 * node + 3] += pf.value
    return b


def assemble_body_force_3d(model, force) -> np.ndarray:
    """int f . phi_j dV for a constant body force f (3,)."""
    f = np.asarray(force, dtype=float).reshape(3)
    b = np.zeros(model.num_dofs)
    xv = model.x[model.cells]
    vol = np.abs(np.einsum("ci,ci->c", xv[:, 1] - xv[:, 0], np.cross(xv[:, 2] - xv[:, 0], xv[:, 3] - xv[:, 0]))) / 6
    for d in range(3):
        np.add.at(b, 3 * model.cells.ravel() + d, np.repeat(f[d] * vol / 4.0, 4))
    if model.layout.num_enriched:
        q = _cracklip.compute_enriched_cell_quadrature_3d(model.x, model.cells, model.layout, model.geometries,
                                                          np.asarray(model.layout.cells, dtype=np.int32),
                                                          model.scene.options.quadrature_options_3d())
        force_at = np.broadcast_to(f, (len(q["weight"]), 3)).copy()
        b += _cracklip.assemble_cell_load_3d(model.x, model.cells, model.layout, model.geometries, q["cell"], q["ref"],
                                             q["side"], q["weight"], force_at)
    return b


def lip_points_3d(model, crack: int) -> dict:
    """Quadrature points on a crack's lip facets (cell, ref, x, weight, normal), computed once."""
    cache = model.__dict__.setdefault("_lip_points_3d", {})
    if crack not in cache:
        cache[crack] = _cracklip.compute_lip_points_3d(model.x, model.cells, model.geometries[crack], LIP_POINTS_3D)
    return cache[crack]


def assemble_lip_pressure_3d(model, crack: int) -> np.ndarray:
    """int p [[phi_j]] . n over a crack's lip facets."""
    pts = lip_points_3d(model, crack)
    t = lip_pressure(model.cracks[crack].crack, pts["x"])[:, None] * pts["normal"]
    return _cracklip.assemble_lip_load_3d(model.x, model.cells, model.layout, model.geometries, crack, pts["cell"],
                                          pts["ref"], pts["weight"], t)


def assemble_loads_3d(model) -> dict[str, np.ndarray]:
    """The load vector (num_dofs,) of each load group."""
    scene = model.scene
    out: dict[str, np.ndarray] = {}

    def add(group: str, b: np.ndarray) -> None:
        out[group] = out[group] + b if group in out else b
    for group in sorted({t.group for t in scene.tractions} | {p.group for p in scene.point_forces}):
        add(group, assemble_tractions_3d(model, group) + assemble_point_forces_3d(model, group))
    if scene.body_force is not None and np.any(scene.body_force):
        add(scene.body_force_group, assemble_body_force_3d(model, scene.body_force))
    for ci, cm in enumerate(model.cracks):
        if callable(cm.crack.pressure) or cm.crack.pressure != 0.0:
            add(cm.crack.pressure_group, assemble_lip_pressure_3d(model, ci))
    return out


__all__ = ["assemble_loads_3d", "assemble_tractions_3d", "assemble_body_force_3d", "assemble_lip_pressure_3d",
           "lip_points_3d"]
