"""[[dirichlet]], [[symmetry]], [loads] and [[load_path]]: the keys
(DIRICHLET_KEYS, SYMMETRY_KEYS, LOAD_KEYS) and what they build: Dirichlet
conditions on a tag, a box of nodes or a point (a value, or the exact
Williams field), symmetry planes, tractions (a
value, sigma n of a stress, the Williams or Kirsch field; in 3D a value or
a uniform stress), pressures, point forces, each with a line in the
scene's notes saying what it became."""
from __future__ import annotations

import math

import numpy as np

from ...errors import BoundaryConditionError, InputError
from ...scene.conditions import Dirichlet, LoadStep, PointForce, Traction
from ...scene.crack import Crack
from ...scene.material import Material
from ...scene.mesh import MeshData
from ...scene.stress_field import LinearStress
from ...scene.processes import mark_collective, reduced
from ...scene.symmetry import Symmetry
from .mesh import check_tag, nearest_node
from .schema import (REQUIRED, UNSET, Key, p_choice, p_factors, p_float, p_gradient, p_group, p_point, p_point_any,
                     p_region, p_str, p_stress_any, p_tag, p_value, p_vector_any)


_WILLIAMS = [
    ("K_I", "float", 0.0, "mode I stress intensity factor of the exact Williams field", p_float()),
    ("K_II", "float", 0.0, "mode II stress intensity factor of the exact Williams field", p_float()),
    ("tip", "[x, y]", REQUIRED, "crack tip of the Williams field (an end of one of the cracks)", p_point),
    ("angle", "float", 0.0, "crack direction at the tip, degrees from the x axis", p_float()),
]


DIRICHLET_KEYS: list[Key] = [
    Key("dirichlet[].tag", "string or integer", UNSET,
        "boundary tag the displacement is prescribed on (one of tag, box, point)", p_tag),
    Key("dirichlet[].box", "[x0, y0, x1, y1]", UNSET,
        "every mesh node inside the box, edges included; it may be flat (x0 = x1: the nodes on a "
        "line); standard dofs only, like a point (3D: [x0, y0, z0, x1, y1, z1])", p_region),
    Key("dirichlet[].point", "[x, y] or [x, y, z]", UNSET,
        "the mesh node nearest to the point (within one mean edge length); a generated rectangle, "
        "plate or box has a node at its corners; 2D: not on a crack (to hold a lip, a point just off it on "
        "that side)", p_point_any),
    Key("dirichlet[].component", "string", "all", "`x`, `y`, `z` (3D) or `all` (`both` in 2D means all)",
        p_choice("x", "y", "z", "all", "both")),
    Key("dirichlet[].value", "float or [x, y]", 0.0,
        "prescribed displacement ([x, y], 3D [x, y, z], with component = all)", p_value),
    Key("dirichlet[].group", "string", "default", "load group of the prescribed value (see load_path); the "
        "values of conditions of different groups on one node add up", p_group),
] + [Key(f"dirichlet[].williams.{n}", t, d, m + " (displacement prescribed; replaces value)", p)
     for n, t, d, m, p in _WILLIAMS]


SYMMETRY_KEYS: list[Key] = [
    Key("symmetry[].tag", "string or integer", REQUIRED,
        "boundary tag that is a plane of symmetry of the problem (3D; a straight line in 2D): the displacement "
        "normal to it is 0 there (the plane must be normal to x, y or z); a crack meeting it must meet it at right "
        "angles, and a front end on it is an interior point (K on the domain and its mirror image, no free-surface "
        "flag; docs/sifs.md)", p_tag),
]


LOAD_KEYS: list[Key] = [
    Key("loads.body_force", "[x, y] or [x, y, z]", [0.0, 0.0], "constant body force, force per unit area "
        "(3D: per unit volume)", p_vector_any),
    Key("loads.body_force_group", "string", "default", "load group of the body force (see load_path)", p_group),
    Key("loads.tractions[].tag", "string or integer", REQUIRED, "boundary tag loaded", p_tag),
    Key("loads.tractions[].group", "string", "default", "load group (see load_path)", p_group),
    Key("loads.tractions[].value", "[x, y] or [x, y, z]", UNSET, "constant traction, force per unit length "
        "(3D: per unit area) (one of value, stress, williams, kirsch)", p_vector_any),
    Key("loads.tractions[].stress", "[sxx, syy, sxy] or [sxx, syy, szz, syz, sxz, sxy]", UNSET,
        "stress at `origin`: the traction is sigma n on the tag (n the outward facet normal)", p_stress_any),
    Key("loads.tractions[].stress_gradient", "[[3 numbers], [3 numbers]] or 3 rows of 6", UNSET,
        "with stress: d sigma/dx, d sigma/dy (3D: and d sigma/dz) of a linear stress field "
        "sigma(x) = stress + (x - origin) gradient, each row in the order of stress (bending: sxx varying "
        "with y)", p_gradient),
    Key("loads.tractions[].origin", "[x, y] or [x, y, z]", UNSET, "with stress_gradient: where sigma = stress "
        "(default: 0)", p_point_any),
] + [Key(f"loads.tractions[].williams.{n}", t, d, m + " (traction sigma n)", p) for n, t, d, m, p in _WILLIAMS] + [
    Key("loads.tractions[].kirsch.remote_stress", "float", REQUIRED,
        "Kirsch field of a hole under remote stress along x (< 0: compression); traction sigma n",
        p_float()),
    Key("loads.tractions[].kirsch.hole_radius", "float", REQUIRED, "Kirsch field: hole radius",
        p_float(positive=True)),
    Key("loads.tractions[].kirsch.center", "[x, y]", [0.0, 0.0], "Kirsch field: hole centre", p_point),
    Key("loads.pressures[].tag", "string or integer", REQUIRED, "boundary tag under pressure", p_tag),
    Key("loads.pressures[].group", "string", "default", "load group (see load_path)", p_group),
    Key("loads.pressures[].value", "float", REQUIRED,
        "pressure (> 0 pushes on the part): traction -p n", p_float()),
    Key("loads.point_forces[].point", "[x, y] or [x, y, z]", REQUIRED,
        "a concentrated force at the mesh node nearest to the point (within one element); a generated "
        "rectangle or plate has a node there; 2D: not on a crack (to load a lip, a point just off it on "
        "that side)", p_point_any),
    Key("loads.point_forces[].value", "[x, y] or [x, y, z]", REQUIRED, "the force (per unit thickness in 2D)",
        p_vector_any),
    Key("loads.point_forces[].group", "string", "default", "load group (see load_path)", p_group),
    Key("loads.initial_stress.value", "[sxx, syy, sxy] or [sxx, syy, szz, syz, sxz, sxy]", REQUIRED,
        "initial (residual) stress sigma_0 at `origin`: the stress is C eps(u) + sigma_0, its "
        "equivalent loads open or close the cracks", p_stress_any),
    Key("loads.initial_stress.gradient", "[[3 numbers], [3 numbers]] or 3 rows of 6", UNSET,
        "d sigma_0 / dx, d sigma_0 / dy (3D: and d sigma_0 / dz) of a linear initial stress, each row in the "
        "order of value (default: uniform)", p_gradient),
    Key("loads.initial_stress.origin", "[x, y] or [x, y, z]", UNSET, "where sigma_0 = value (default: 0)",
        p_point_any),
    Key("loads.initial_stress.group", "string", "default", "load group of the initial stress (see load_path)",
        p_group),
    Key("load_path[].name", "string", "", "label of the step in outputs (default: step k)", p_str),
    Key("load_path[].factors", "table of group = factor", REQUIRED,
        "the factor of each named load group at the end of the step (a group not named keeps its factor "
        "from the step before; all are 0 before the first step); without load_path one step takes every "
        "group to 1", p_factors),
]


def _williams(w: dict, material: Material, cracks: list[Crack], where: str):
    from ...exact.williams import WilliamsField
    tip = np.asarray(w["tip"], dtype=float)
    a = math.radians(w["angle"])
    # Orientation: theta -> +pi on the crack's + side (left of the polyline's
    # direction) when the tip is the polyline's last point, else on its - side.
    orientation, best = 1, math.inf
    for c in cracks:
        for end, sign in ((c.points[-1], 1), (c.points[0], -1)):
            d = float(np.linalg.norm(end - tip))
            if d < best:
                best, orientation = d, sign
    scale = max((float(np.ptp(c.points, axis=0).max()) for c in cracks), default=1.0)
    if best > 1e-6 * scale:
        raise InputError(f"{where}.tip {tip.tolist()} is not an end point of any crack")
    return WilliamsField(material, K_I=w["K_I"], K_II=w["K_II"], tip=tuple(tip),
                         e1=(math.cos(a), math.sin(a)), orientation=orientation)


_COMPONENT = {"x": 0, "y": 1, "z": 2, "both": None, "all": None}


def build_dirichlet(bc: dict, i: int, mesh: MeshData, material: Material, cracks: list[Crack],
               notes: list[str]) -> list[Dirichlet]:
    where = f"dirichlet[{i}]"
    comp = _COMPONENT[bc["component"]]
    if "williams" in bc:
        field = _williams(bc["williams"], material, cracks, f"{where}.williams")

        def value(p, side):
            u = field.displacement(p, side)
            return u if comp is None else u[:, comp]
        entries = [(comp, value)]
        what = f"Williams field K_I = {field.K_I:g}, K_II = {field.K_II:g}"
    elif isinstance(bc["value"], list):
        entries = list(enumerate(bc["value"]))
        what = f"u = {bc['value']}"
    else:
        entries = [(comp, bc["value"])]
        what = f"u_{bc['component']} = {bc['value']:g}" if comp is not None else f"u = {bc['value']:g}"
    gdim = mesh.gdim
    x = mesh.mesh.geometry.x[:, :gdim]
    out: list[Dirichlet] = []
    if "tag" in bc:
        check_tag(mesh, bc["tag"], where)
        targets = [bc["tag"]]
        notes.append(f"{where}: tag {bc['tag']!r} ({mesh.num_facets(bc['tag'])} facets), {what}")
    elif "point" in bc:
        node = nearest_node(mesh, bc["point"], f"{where}.point")
        targets = [node]
        notes.append(f"{where}: point {bc['point']} -> node ({', '.join(f'{v:.6g}' for v in node)}), {what}")
    else:
        lo, hi = np.asarray(bc["box"][:gdim]), np.asarray(bc["box"][gdim:])
        comm = mesh.mesh.comm
        tol = 1e-9 * float((reduced(x.max(axis=0), "MAX", comm) - reduced(x.min(axis=0), "MIN", comm)).max())
        inside = x[np.all((x >= lo - tol) & (x <= hi + tol), axis=1)]
        if comm.size > 1:  # the box's nodes of every process (each holds its part of the mesh), alike on all
            inside = np.unique(np.concatenate(comm.allgather(inside)), axis=0)
        if len(inside) == 0:
            raise mark_collective(BoundaryConditionError(f"{where}.box {bc['box']} holds no mesh node"))
        targets = [tuple(float(v) for v in n) for n in inside]
        notes.append(f"{where}: box {bc['box']} ({len(inside)} nodes), {what}")
    label = f"{where}: " + (f"tag {bc['tag']!r}" if "tag" in bc else f"point {bc['point']}" if "point" in bc
                            else f"box {bc['box']}")
    for target in targets:
        out += [Dirichlet(target, c, v, group=bc["group"], label=label) for c, v in entries]
    return out


def build_traction(tr: dict, i: int, mesh: MeshData, material: Material, cracks: list[Crack],
              notes: list[str]) -> Traction:
    where = f"loads.tractions[{i}]"
    check_tag(mesh, tr["tag"], where)
    tag = tr["tag"]
    nf = mesh.num_facets(tag)
    if "value" in tr:
        notes.append(f"{where}: tag {tag!r} ({nf} facets), traction {tr['value']}")
        return Traction(tag, tuple(tr["value"]), group=tr["group"])
    if "stress" in tr:  # (3D too: a uniform or linear stress of six components)
        field = linear_stress(tr, "stress", "stress_gradient")
        notes.append(f"{where}: tag {tag!r} ({nf} facets), traction sigma n, {describe_stress(field)}")
        return Traction(tag, stress=field, group=tr["group"])
    # A field's traction sigma n is a stress traction: its normals are those
    # of the mesh it is integrated on (the model's, each process's own
    # facets), not this mesh's, which an error estimate's or an accuracy
    # level's finer mesh replaces (and of which under mpirun a process holds
    # only its part).
    if "williams" in tr:
        field = _williams(tr["williams"], material, cracks, f"{where}.williams")
        notes.append(f"{where}: tag {tag!r} ({nf} facets), traction of the Williams field "
                     f"K_I = {field.K_I:g}, K_II = {field.K_II:g}")
        return Traction(tag, stress=field.stress, group=tr["group"])
    from ...exact.kirsch import kirsch_stress
    k = tr["kirsch"]
    center = np.asarray(k["center"], dtype=float)
    notes.append(f"{where}: tag {tag!r} ({nf} facets), traction of the Kirsch field, remote stress "
                 f"{k['remote_stress']:g}, hole radius {k['hole_radius']:g}")
    return Traction(tag, stress=lambda p: kirsch_stress(p - center, k["remote_stress"], k["hole_radius"]),
                    group=tr["group"])


def build_point_force(pf: dict, i: int, mesh: MeshData, notes: list[str]) -> PointForce:
    where = f"loads.point_forces[{i}]"
    node = nearest_node(mesh, pf["point"], f"{where}.point")
    notes.append(f"{where}: force {pf['value']} at node ({', '.join(f'{v:.6g}' for v in node)})")
    return PointForce(node, tuple(pf["value"]), group=pf["group"])


def build_pressure(pr: dict, i: int, mesh: MeshData, notes: list[str]) -> Traction:
    where = f"loads.pressures[{i}]"
    check_tag(mesh, pr["tag"], where)
    p = pr["value"]
    notes.append(f"{where}: tag {pr['tag']!r} ({mesh.num_facets(pr['tag'])} facets), pressure {p:g}")
    # -p n as the traction of the stress -p I (2D or 3D): the normals of the
    # mesh it is integrated on (as a field's traction, build_traction)
    d = mesh.gdim
    return Traction(pr["tag"], stress=LinearStress((-p,) * d + (0.0,) * (2 * d - 3)), group=pr["group"])


def linear_stress(st: dict, value: str, gradient: str) -> LinearStress:
    """The LinearStress of a table's value, gradient and origin keys (the
    scene's dimension already checked: dimension.check_dimension)."""
    g = st.get(gradient)
    return LinearStress(tuple(st[value]), None if g is None else tuple(map(tuple, g)),
                        None if st.get("origin") is None else tuple(st["origin"]))


def describe_stress(field: LinearStress, name: str = "sigma") -> str:
    """A note's words for a uniform or linear stress field called `name`."""
    names = "xx, yy, xy" if field.dim == 2 else "xx, yy, zz, yz, xz, xy"
    if field.is_uniform:
        return f"uniform {name} = {list(field.value)} ({names})"
    return (f"linear {name} = {list(field.value)} ({names}) at {list(field.origin)}, gradient "
            f"{[list(r) for r in field.gradient]}")


def build_conditions(s: dict, mesh: MeshData, material: Material, cracks: list, notes: list[str]) -> list[Dirichlet]:
    """The Dirichlet conditions of the [[dirichlet]] settings."""
    dirichlet = []
    for i, bc in enumerate(s["dirichlet"]):
        dirichlet += build_dirichlet(bc, i, mesh, material, cracks, notes)
    return dirichlet


def build_symmetry(s: dict, mesh: MeshData, notes: list[str]) -> list[Symmetry]:
    """The symmetry planes of the [[symmetry]] settings."""
    out = []
    for i, sym in enumerate(s["symmetry"]):
        where = f"symmetry[{i}]"
        check_tag(mesh, sym["tag"], where)
        out.append(Symmetry(sym["tag"], label=where))
        notes.append(f"{where}: tag {sym['tag']!r} ({mesh.num_facets(sym['tag'])} facets), a plane of symmetry: "
                     "normal displacement 0")
    return out


def build_loads(s: dict, mesh: MeshData, material: Material, cracks: list, notes: list[str]) -> dict:
    """The loads of the [loads] settings: tractions (pressures among them),
    body_force (None if zero), point_forces, initial_stress (or None), and
    the lip pressures' notes. A 2D part takes a value, a stress, a Williams
    or a Kirsch field as a traction, a 3D one a value or a stress."""
    gdim = mesh.gdim
    # (A 3D scene has no Williams or Kirsch traction: check_dimension refused them.)
    tractions = [build_traction(tr, i, mesh, material, cracks, notes) for i, tr in enumerate(s["loads"]["tractions"])]
    tractions += [build_pressure(p, i, mesh, notes) for i, p in enumerate(s["loads"]["pressures"])]
    body_force = s["loads"]["body_force"]
    if any(body_force):
        notes.append(f"loads.body_force: {body_force} per unit {'volume' if gdim == 3 else 'area'}")
    else:
        body_force = None
    point_forces = []
    for i, pf in enumerate(s["loads"]["point_forces"]):
        point_forces.append(build_point_force(pf, i, mesh, notes))
    initial_stress = None
    if "initial_stress" in s["loads"]:
        st = s["loads"]["initial_stress"]
        initial_stress = linear_stress(st, "value", "gradient")
        notes.append(f"loads.initial_stress: {describe_stress(initial_stress, 'sigma_0')}")
    for c, cs in zip(cracks, s["cracks"]):
        if cs["pressure"] != 0.0:
            notes.append(f"{c.name}: lip pressure {cs['pressure']:g}")
    return {"tractions": tractions, "body_force": body_force, "point_forces": point_forces,
            "initial_stress": initial_stress}


def build_load_path(s: dict, options, notes: list[str]) -> list[LoadStep] | None:
    """The load path of the [[load_path]] settings (None without steps)."""
    if not s["load_path"]:
        return None
    load_path = [LoadStep(st["factors"], st["name"] or f"step {k + 1}") for k, st in enumerate(s["load_path"])]
    notes.append("load path: " + "; ".join(f"{st.name}: " + ", ".join(f"{g} = {f:g}" for g, f in st.factors.items())
                                           for st in load_path)
                 + f" ({options.load_steps} increment(s) per step)")
    return load_path
