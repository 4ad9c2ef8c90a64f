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
origin: in 2D its z component x R_y - y R_x, in 3D the vector x x R.

Under mpirun (a distributed model) each process integrates its owned cells
and facets (its point forces), so its rows and loads are parts that add up:
forces and moments are summed over the processes, and what is not linear in
the loads (the sizes of nodal loads) is taken on the owned nodes of the
loads summed over the processes (model.distributed.summed).
"""
from __future__ import annotations

import typing

import numpy as np

from ..model.boundary import tag_facets
from ..model.constraints import condition_dofs, is_point_condition
from ..model.distributed import summed
from ..model.loads import (assemble_body_force, assemble_initial_stress, assemble_loads, assemble_point_forces,
                           assemble_tractions, traction_values)
from ..scene.material import strain, stress
from ..scene.processes import reduced
from ..scene.stress_field import evaluate_stress


class _Parts:
    """What the processes' parts add up to (identity in serial): sums of
    linear parts, nodal loads made whole on the owned nodes."""

    def __init__(self, model):
        self.model = model
        self.on = model.distributed
        self.owned = model.V.dofmap.index_map.size_local if self.on else model.x.shape[0]

    def sum(self, value):
        if not self.on:
            return value
        return reduced(np.asarray(value, dtype=float), "SUM", self.model.V.mesh.comm)

    def nodal(self, f: np.ndarray) -> np.ndarray:
        """(owned nodes, d) standard part of a load vector, whole."""
        m = self.model
        N, d = m.x.shape
        whole = summed(m.dofs, f) if self.on else f
        return whole[: d * N].reshape(N, d)[:self.owned]


def _load_vector(solution) -> np.ndarray:
    """The load f (num_dofs,) at this state's factors."""
    m = solution.model
    f = np.zeros(m.num_dofs)
    for group, b in assemble_loads(m).items():
        f += solution.factor(group) * b
    return f


def load_items(solution) -> list[dict[str, typing.Any]]:
    """The resultant (F_x, F_y[, F_z]) of every point force and every
    traction of the scene at this state's factors, with its kind ("point
    force", "traction") and where it acts (a traction's resultant: its value
    at the centroids of its tag's facets times their lengths or areas)."""
    m = solution.model
    sc = m.scene
    parts = _Parts(m)
    out = []
    for pf in sc.point_forces:
        out.append({"kind": "point force", "where": f"point {list(pf.point)}",
                    "resultant": solution.factor(pf.group) * np.asarray(pf.value, dtype=float)})
    for tr in sc.tractions:
        centroid, size, normal = tag_facets(sc.mesh, tr.where, owned=parts.on)
        t = traction_values(tr, centroid, lambda p: evaluate_stress(tr.stress, p, f"traction on {tr.where!r}"),
                            lambda p: normal)
        out.append({"kind": "traction", "where": f"tag {tr.where!r}",
                    "resultant": solution.factor(tr.group) * parts.sum((t * size[:, None]).sum(axis=0))})
    return out


def _load_magnitude(solution) -> float:
    """Sum of |nodal load| of every kind of load on its own (tractions, point
    forces, body force, initial stress), before they add up: the scale of
    the loads even where they cancel node by node (an initial stress against
    the tractions it puts on the boundary)."""
    m = solution.model
    sc = m.scene
    whole = _Parts(m)
    parts = []
    for group in {t.group for t in sc.tractions} | {p.group for p in sc.point_forces}:
        parts.append(solution.factor(group) * (assemble_tractions(m, group) + assemble_point_forces(m, group)))
    if sc.body_force is not None and np.any(sc.body_force):
        parts.append(solution.factor(sc.body_force_group) * assemble_body_force(m, sc.body_force))
    if sc.initial_stress is not None:
        parts.append(solution.factor(sc.initial_stress_group) * assemble_initial_stress(m, sc.initial_stress))
    return float(whole.sum(sum(np.linalg.norm(whole.nodal(b), axis=1).sum() for b in parts)))


def _stiffness_rows(solution, dofs: np.ndarray) -> np.ndarray:
    """(K u)_i at standard dofs i: int sigma(u_h) : eps(N_i) over the cells
    around their nodes."""
    m = solution.model
    d = m.gdim
    nodes = np.unique(dofs // d)
    touched = np.flatnonzero(np.isin(m.cells, nodes).any(axis=1)).astype(np.int32)
    touched = touched[m.owned_cells_only(touched)]  # (under mpirun each process its owned cells: parts)
    out = np.zeros(d * m.x.shape[0])
    if touched.size == 0:
        return out[dofs]
    f = solution.field_points(touched)
    sig = stress(strain(f["grad_u"]), m.scene.material)            # (q, d, d)
    cells = m.cells[f["cell"]]                                        # (q, d + 1)
    grads = m.crack_type.shape_gradients(m.x, cells)                  # (q, d + 1 nodes, d)
    # int sigma : eps(N_a e_c) = int sigma_cj dN_a/dx_j
    contrib = np.einsum("q,qdj,qaj->qad", f["weight"], sig, grads)   # (q, d + 1, d)
    np.add.at(out, (d * cells[:, :, None] + np.arange(d)[None, None, :]).ravel(), contrib.ravel())
    return out[dofs]


def _moment(x: np.ndarray, comps: np.ndarray, forces: np.ndarray):
    """The moment about the origin of the forces (n,) along components
    `comps` at points x (n, d): in 2D its z component (a float), in 3D the
    vector (3,)."""
    if x.shape[1] == 2:
        return float(np.sum(np.where(comps == 1, x[:, 0] * forces, -x[:, 1] * forces)))
    f = np.zeros_like(x)
    f[np.arange(len(comps)), comps] = forces
    return np.cross(x, f).sum(axis=0)


def compute_reactions(solution) -> dict[str, typing.Any]:
    """Reactions per condition (label, kind: tag, point or box, nodes,
    force [R_x, R_y(, R_z)], moment about the origin), their sum, the applied load
    (the sum of every load on the standard dofs: tractions, point forces,
    body force; lip pressures and initial stresses are self-equilibrated)
    and the balance |sum + applied| / (sum of |nodal loads|); gross_load is
    that sum of |nodal loads|, load_magnitude the same of every kind of load
    on its own (before they add up)."""
    m = solution.model
    N, d = m.x.shape
    parts = _Parts(m)
    per = condition_dofs(m)
    every = np.unique(np.concatenate(per)) if per else np.zeros(0, dtype=np.int64)
    f = _load_vector(solution)
    r = np.zeros(d * N)
    if every.size:
        r[every] = _stiffness_rows(solution, every) - f[every]
    groups: dict[str, dict[str, typing.Any]] = {}
    for k, (bc, dofs) in enumerate(zip(m.scene.dirichlet, per)):
        label = bc.label or f"condition {k}: " + (f"tag {bc.where!r}" if not is_point_condition(bc)
                                                   else f"point {list(bc.where)}")
        g = groups.setdefault(label, {"condition": label, "kind": "point" if is_point_condition(bc) else "tag",
                                      "nodes": set(), "force": np.zeros(d),
                                      "moment": _moment(np.zeros((0, d)), np.zeros(0, int), np.zeros(0))})
        nodes, comps = dofs // d, dofs % d
        g["nodes"].update(int(n) for n in nodes[nodes < parts.owned])
        np.add.at(g["force"], comps, r[dofs])
        g["moment"] = g["moment"] + _moment(m.x[nodes], comps, r[dofs])
    for g in groups.values():  # (the processes' parts added up; each node counted by its owner)
        g["force"], g["moment"] = parts.sum(g["force"]), parts.sum(g["moment"])
        g["count"] = int(parts.sum(len(g["nodes"])))
    f_part = f[: d * N].reshape(N, d)
    f_std = parts.nodal(f)
    applied = parts.sum(f_part.sum(axis=0))
    total = np.sum([g["force"] for g in groups.values()], axis=0) if groups else np.zeros(d)
    gross = float(parts.sum(float(np.linalg.norm(f_std, axis=1).sum())))
    for g in groups.values():  # several nodes under one label of point conditions: a scene file's box
        if g["kind"] == "point" and g["count"] > 1:
            g["kind"] = "box"
    rows = [{"condition": g["condition"], "kind": g["kind"], "nodes": g["count"],
             "force": g["force"].tolist(), "moment": np.asarray(g["moment"]).tolist()} for g in groups.values()]
    if d == 2:  # the z component in the plane
        moment_applied = float(parts.sum(float(np.sum(m.x[:, 0] * f_part[:, 1] - m.x[:, 1] * f_part[:, 0]))))
    else:
        moment_applied = parts.sum(np.cross(m.x, f_part).sum(axis=0)).tolist()
    return {"conditions": rows, "sum": total.tolist(), "applied_load": applied.tolist(),
            "applied_moment": moment_applied, "gross_load": gross, "load_magnitude": _load_magnitude(solution),
            "load_items": [{**item, "resultant": item["resultant"].tolist()} for item in load_items(solution)],
            "balance": float(np.linalg.norm(total + applied) / gross) if gross > 0 else float(np.linalg.norm(total)),
            "load_components": {"positive": parts.sum(np.maximum(f_std, 0.0).sum(axis=0)).tolist(),
                                "negative": parts.sum(np.minimum(f_std, 0.0).sum(axis=0)).tolist()}}
