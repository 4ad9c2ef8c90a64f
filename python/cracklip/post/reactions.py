"""Reaction forces: what every Dirichlet condition and point support carries.

The reaction at a constrained standard dof i is r_i = (K u - f)_i: the
stiffness row (int sigma(u_h) : eps(N_i) over the cells around the node,
with the stiffness's own quadrature, enriched cells included) minus the
load there. A constant translation e_k has no strain and no jump, so
sum_i r_i e_k = -f . e_k: the reactions of all conditions sum to minus the
applied load (to the solver's residual; contact and lip pressures are
internal and drop out). Only cells around constrained nodes are touched.

Each condition gets its own dofs (a dof shared by two conditions, a corner
of two tagged sides, goes to the first); conditions with the same label
(the nodes of a scene file's box) are summed. The moment is about the
origin (z component, x R_y - y R_x).
"""
from __future__ import annotations

import typing

import numpy as np

from ..model.constraints import condition_dofs, is_point_condition
from ..model.loads import (assemble_body_force, assemble_initial_stress, assemble_loads, assemble_point_forces,
                           assemble_tractions)
from ..scene.material import strain, stress


def _load_vector(solution) -> np.ndarray:
    """The load f (num_dofs,) at this state's factors."""
    m = solution.model
    f = np.zeros(m.num_dofs)
    for group, b in assemble_loads(m).items():
        f += solution.factor(group) * b
    return f


def load_items(solution) -> list[dict[str, typing.Any]]:
    """The resultant (F_x, F_y) of every point force and every traction of
    the scene at this state's factors, with its kind ("point force",
    "traction") and where it acts (a traction's resultant: its value at the
    midpoints of its tag's facets times their lengths)."""
    import dolfinx.cpp.mesh
    from ..model.loads import _traction_values
    m = solution.model
    sc = m.scene
    out = []
    for pf in sc.point_forces:
        out.append({"kind": "point force", "where": f"point {list(pf.point)}",
                    "resultant": solution.factor(pf.group) * np.asarray(pf.value, dtype=float)})
    msh = sc.mesh.mesh
    x = msh.geometry.x[:, :2]
    for tr in sc.tractions:
        facets = sc.mesh.facets(tr.where)
        g = dolfinx.cpp.mesh.entities_to_geometry(msh._mesh, 1, facets, False)
        a, b = x[g[:, 0]], x[g[:, 1]]
        t = _traction_values(m, tr, 0.5 * (a + b))
        out.append({"kind": "traction", "where": f"tag {tr.where!r}",
                    "resultant": solution.factor(tr.group) * (t * np.linalg.norm(b - a, axis=1)[:, None]).sum(axis=0)})
    return out


def _load_magnitude(solution) -> float:
    """Sum of |nodal load| of every kind of load on its own (tractions, point
    forces, body force, initial stress), before they add up: the scale of
    the loads even where they cancel node by node (an initial stress against
    the tractions it puts on the boundary)."""
    m = solution.model
    sc = m.scene
    N = m.x.shape[0]
    parts = []
    for group in {t.group for t in sc.tractions} | {p.group for p in sc.point_forces}:
        parts.append(solution.factor(group) * (assemble_tractions(m, group) + assemble_point_forces(m, group)))
    if sc.body_force is not None and np.any(sc.body_force):
        parts.append(solution.factor(sc.body_force_group) * assemble_body_force(m, sc.body_force))
    if sc.initial_stress is not None:
        parts.append(solution.factor(sc.initial_stress_group) * assemble_initial_stress(m, sc.initial_stress))
    return float(sum(np.linalg.norm(b[: 2 * N].reshape(N, 2), axis=1).sum() for b in parts))


def _stiffness_rows(solution, dofs: np.ndarray) -> np.ndarray:
    """(K u)_i at standard dofs i: int sigma(u_h) : eps(N_i) over the cells
    around their nodes."""
    m = solution.model
    nodes = np.unique(dofs // 2)
    touched = np.flatnonzero(np.isin(m.cells, nodes).any(axis=1)).astype(np.int32)
    out = np.zeros(2 * m.x.shape[0])
    if touched.size == 0:
        return out[dofs]
    f = solution.field_points(touched)
    sig = stress(strain(f["grad_u"]), m.scene.material)            # (q, 2, 2)
    cells = m.cells[f["cell"]]                                        # (q, 3)
    xv = m.x[cells]
    e1, e2 = xv[:, 1] - xv[:, 0], xv[:, 2] - xv[:, 0]
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    inv = np.stack([np.stack([e2[:, 1], -e2[:, 0]], axis=1), np.stack([-e1[:, 1], e1[:, 0]], axis=1)],
                   axis=1) / det[:, None, None]
    grads = np.stack([-inv[:, 0] - inv[:, 1], inv[:, 0], inv[:, 1]], axis=1)   # (q, 3 nodes, 2)
    # int sigma : eps(N_a e_d) = int sigma_dj dN_a/dx_j
    contrib = np.einsum("q,qdj,qaj->qad", f["weight"], sig, grads)   # (q, 3, 2)
    np.add.at(out, (2 * cells[:, :, None] + np.arange(2)[None, None, :]).ravel(), contrib.ravel())
    return out[dofs]


def compute_reactions(solution) -> dict[str, typing.Any]:
    """Reactions per condition (label, kind: tag, point or box, nodes,
    force [R_x, R_y], moment about the origin), their sum, the applied load
    (the sum of every load on the standard dofs: tractions, point forces,
    body force; lip pressures and initial stresses are self-equilibrated)
    and the balance |sum + applied| / (sum of |nodal loads|); gross_load is
    that sum of |nodal loads|, load_magnitude the same of every kind of load
    on its own (before they add up)."""
    m = solution.model
    per = condition_dofs(m)
    every = np.unique(np.concatenate(per)) if per else np.zeros(0, dtype=np.int64)
    f = _load_vector(solution)
    N = m.x.shape[0]
    r = np.zeros(2 * N)
    if every.size:
        r[every] = _stiffness_rows(solution, every) - f[every]
    groups: dict[str, dict[str, typing.Any]] = {}
    for k, (bc, dofs) in enumerate(zip(m.scene.dirichlet, per)):
        label = bc.label or f"condition {k}: " + (f"tag {bc.where!r}" if not is_point_condition(bc)
                                                   else f"point {list(bc.where)}")
        g = groups.setdefault(label, {"condition": label, "kind": "point" if is_point_condition(bc) else "tag",
                                      "nodes": set(), "force": np.zeros(2), "moment": 0.0})
        nodes, comps = dofs // 2, dofs % 2
        g["nodes"].update(int(n) for n in nodes)
        np.add.at(g["force"], comps, r[dofs])
        xy = m.x[nodes]
        g["moment"] += float(np.sum(np.where(comps == 1, xy[:, 0] * r[dofs], -xy[:, 1] * r[dofs])))
    f_std = f[: 2 * N].reshape(N, 2)
    applied = f_std.sum(axis=0)
    total = np.sum([g["force"] for g in groups.values()], axis=0) if groups else np.zeros(2)
    gross = float(np.linalg.norm(f_std, axis=1).sum())
    for g in groups.values():  # several nodes under one label of point conditions: a scene file's box
        if g["kind"] == "point" and len(g["nodes"]) > 1:
            g["kind"] = "box"
    rows = [{"condition": g["condition"], "kind": g["kind"], "nodes": len(g["nodes"]),
             "force": g["force"].tolist(), "moment": g["moment"]} for g in groups.values()]
    moment_applied = float(np.sum(m.x[:, 0] * f_std[:, 1] - m.x[:, 1] * f_std[:, 0]))
    return {"conditions": rows, "sum": total.tolist(), "applied_load": applied.tolist(),
            "applied_moment": moment_applied, "gross_load": gross, "load_magnitude": _load_magnitude(solution),
            "load_items": [{**item, "resultant": item["resultant"].tolist()} for item in load_items(solution)],
            "balance": float(np.linalg.norm(total + applied) / gross) if gross > 0 else float(np.linalg.norm(total)),
            "load_components": {"positive": np.maximum(f_std, 0.0).sum(axis=0).tolist(),
                                "negative": np.minimum(f_std, 0.0).sum(axis=0).tolist()}}
