"""Planar part or solid: which keys a 2D or a 3D scene takes.

A scene is 3D when its part is a solid: mesh.kind ``box`` or ``cylinder``,
or a geometry (.geo, STEP, BREP) or .msh file holding volumes. Before the
file is read, a geometry or file scene is taken to be 3D when its cracks
are crack surfaces (``ellipse``, ``polygon``, ``surface``) and 2D when they
are polylines (``points``, ``arc``); the mesh made must agree.

``check_dimension`` names the first key that does not fit the scene's
dimension (a 2D key in a 3D scene, a 3D one in a 2D scene, a point or
vector with the wrong number of components) and says what to give
instead. It runs on the parsed settings, before any meshing when the
dimension is known from mesh.kind or the cracks, else right after.
"""
from __future__ import annotations

import typing

from ...errors import InputError
from .cracks import CRACK_KINDS


#: mesh.kind values that fix the dimension.
KIND_DIMENSION = {"rectangle": 2, "plate_with_hole": 2, "plate_with_holes": 2, "half_annulus": 2, "box": 3,
                  "cylinder": 3}


#: [growth] keys a 3D front does not take (key -> why).
GROWTH_2D_ONLY = {
    "growth.corrections": "the corrector turns a 2D tip's last increment; 3D fronts advance by the explicit kink "
                          "(leave it 0)",
    "growth.corrector_tolerance": "it belongs to growth.corrections, a 2D corrector",
    "growth.max_kink_change": "it stops a 2D tip whose kink turns between steps; a 3D front's points are "
                              "re-sampled every step (no point to follow from step to step) and take half their kink "
                              "(fracture.kink.front_kinks), so it was never applied: remove it",
}


def _parts(doc: dict, path: str):
    """The values of a dotted path in the raw document (arrays of tables
    expanded), as (where, value) pairs: ('loads.tractions[1].stress', ...)."""
    out = [("", doc)]
    for part in path.split("."):
        nxt = []
        for where, node in out:
            if not isinstance(node, dict) or part not in node:
                continue
            v = node[part]
            sub = f"{where}.{part}" if where else part
            if isinstance(v, list) and v and all(isinstance(e, dict) for e in v):
                nxt += [(f"{sub}[{i}]", e) for i, e in enumerate(v)]
            else:
                nxt.append((sub, v))
        out = nxt
    return out


def scene_dimension(settings: dict) -> tuple[int | None, str]:
    """(dimension, why) of parsed settings before meshing: from mesh.kind,
    else from the cracks' kinds (None when neither tells: a geometry or
    .msh file without cracks, read to know)."""
    kind = settings["mesh"]["kind"]
    if kind in KIND_DIMENSION:
        return KIND_DIMENSION[kind], f"mesh.kind = {kind!r}"
    found = {2: [], 3: []}
    for i, c in enumerate(settings["cracks"]):
        for d, keys in CRACK_KINDS.items():
            found[d] += [f"cracks[{i}].{k}" for k in keys if k in c]
    if found[2] and found[3]:
        raise InputError(f"{found[3][0]} is a 3D crack surface but {found[2][0]} is a 2D crack (a polyline): a scene "
                         "is 2D (points, arc) or 3D (ellipse, polygon, surface), not both")
    for d in (3, 2):
        if found[d]:
            return d, f"{found[d][0]} is a {'crack surface' if d == 3 else '2D crack'}"
    return None, ""


def _length(value) -> int | None:
    return len(value) if isinstance(value, list) else None


def check_dimension(doc: dict, settings: dict, dim: int, why: str) -> None:
    """Raise InputError at the first key that does not fit a `dim`-D scene
    (module doc); `why` says what makes the scene that dimension."""
    other = 5 - dim
    part = f"the part is {dim}D ({why})"
    s = settings

    def wrong(where: str, value, what2: str, what3: str) -> InputError:
        n = _length(value)
        return InputError(f"{where} = {value} has {n} components but {part}: give {what3 if dim == 3 else what2}")

    # Cracks of the other dimension.
    for i, c in enumerate(s["cracks"]):
        for k in CRACK_KINDS[other]:
            if k in c:
                if dim == 3:
                    raise InputError(f"cracks[{i}].{k} is a 2D crack (a polyline) but {part}: give cracks[{i}].ellipse "
                                     f"(center, normal, a, b, a_direction), cracks[{i}].polygon or cracks[{i}].surface")
                raise InputError(f"cracks[{i}].{k} is a 3D crack surface but {part}: give cracks[{i}].points (a "
                                 f"polyline) or cracks[{i}].arc, or make the part a solid (mesh.kind 'box', "
                                 "'cylinder', or a geometry or .msh file with volumes)")
    coords = "[x, y, z]" if dim == 3 else "[x, y]"
    checks: list[tuple[str, typing.Any]] = []
    checks += [(w, v) for w, v in _parts(doc, "mesh.refine.point")]
    checks += [(w, v) for w, v in _parts(doc, "dirichlet.point")]
    checks += [(w, v) for w, v in _parts(doc, "loads.point_forces.point")]
    checks += [(w, v) for w, v in _parts(doc, "loads.point_forces.value")]
    checks += [(w, v) for w, v in _parts(doc, "loads.body_force")]
    checks += [(w, v) for w, v in _parts(doc, "loads.tractions.value")]
    checks += [(w, v) for w, v in _parts(doc, "dirichlet.value") if isinstance(v, list)]
    for where, v in checks:
        if _length(v) != dim:
            raise wrong(where, v, "[x, y]", "[x, y, z]")
    for where, v in _parts(doc, "mesh.refine.segment"):
        if isinstance(v, list) and any(_length(p) != dim for p in v):
            raise InputError(f"{where} = {v}: {part}: give its ends as {coords}")
    for where, v in _parts(doc, "dirichlet.box"):
        if _length(v) != 2 * dim:
            raise wrong(where, v, "[x0, y0, x1, y1]", "[x0, y0, z0, x1, y1, z1]")
    for key in ("loads.tractions.stress", "loads.initial_stress.value"):
        for where, v in _parts(doc, key):
            if _length(v) != (6 if dim == 3 else 3):
                raise wrong(where, v, "[sxx, syy, sxy]", "[sxx, syy, szz, syz, sxz, sxy]")
    for key in ("loads.tractions.stress_gradient", "loads.initial_stress.gradient"):
        for where, v in _parts(doc, key):
            if _length(v) != dim or any(_length(r) != 3 * dim - 3 for r in v):
                raise InputError(f"{where} = {v}: {part}: give {dim} rows (d/dx, d/dy{', d/dz' if dim == 3 else ''}) "
                                 f"of {3 * dim - 3} numbers each, in the order of the stress "
                                 f"({'sxx, syy, szz, syz, sxz, sxy' if dim == 3 else 'sxx, syy, sxy'})")
    for key in ("loads.tractions.origin", "loads.initial_stress.origin"):
        for where, v in _parts(doc, key):
            if _length(v) != dim:
                raise wrong(where, v, "[x, y]", "[x, y, z]")
    for where, v in _parts(doc, "dirichlet.component"):
        if dim == 3 and v == "both":
            raise InputError(f"{where} = 'both' names the two components of a 2D part but {part}: give 'all' (x, "
                             "y and z) or one of 'x', 'y', 'z'")
        if dim == 2 and v == "z":
            raise InputError(f"{where} = 'z': {part}, it has components 'x' and 'y' only")
    if dim == 2:
        for where, _ in _parts(doc, "mesh.crack_h"):
            raise InputError(f"{where} refines over 3D crack surfaces but {part}: use mesh.refine or mesh.tip_h")
        for where, _ in _parts(doc, "mesh.refine.box"):
            raise InputError(f"{where} refines a box of a solid but {part}: use mesh.refine[].point or segment")
        for where, _ in _parts(doc, "growth.da_fraction"):
            raise InputError(f"{where} sizes the steps of 3D fronts but {part}: a 2D tip advances growth.da")
        return
    # dim == 3: the 2D-only keys.
    two_d = {
        "material.plane": "plane strain or stress is the setting of a 2D section; a 3D part is plain 3D "
                          "elasticity: remove it",
        "dirichlet.williams": "the Williams field is the 2D field of a straight tip; prescribe values or use a "
                              "2D part",
        "loads.tractions.williams": "the Williams field is the 2D field of a straight tip",
        "loads.tractions.kirsch": "the Kirsch field is the 2D field of a hole in a plate",
        "outputs.magnification": "deformed.png is a 2D picture; in 3D warp solution.vtu by `displacement` in "
                                 "ParaView (Warp By Vector)",
        "outputs.stress_component": "stress.png is a 2D picture; in 3D color solution.vtu by a stress_* array "
                                    "in ParaView",
    }
    for key, text in two_d.items():
        for where, _ in _parts(doc, key):
            raise InputError(f"{where} is a 2D setting but {part}: {text}")
    for key, text in GROWTH_2D_ONLY.items():
        for where, _ in _parts(doc, key):
            raise InputError(f"{where} is a 2D growth setting but {part}: {text}")
    g = doc.get("growth")
    if isinstance(g, dict):
        if g.get("criterion") == "max_energy_release":
            raise InputError(f"growth.criterion = 'max_energy_release' is a 2D criterion but {part}: 3D fronts kink by "
                             "the maximum hoop stress generalised with K_III (`max_hoop`, the default)")
        if g.get("da") and g.get("da_fraction"):
            raise InputError(f"growth.da = {g['da']!r} and growth.da_fraction = {g['da_fraction']!r} both size the "
                             "step's largest advance (da_fraction would win: the fastest point's crack size times it, "
                             "growth.da ignored): give one")
        fatigue = isinstance(doc.get("material"), dict) and "fatigue" in doc["material"]
        if "paris_C" not in g and not fatigue:
            raise InputError(f"[growth] without a growth law but {part}: a 3D front advances each point by its own "
                             "rate, growth.da being the largest advance in a step; give growth.paris_C, paris_m with "
                             "growth.R (or cycle_min), or [material.fatigue] with a [spectrum] or growth.R")
    o = s["options"]
    if s["mesh"]["kind"] == "file":
        if o["accuracy"] != 0.0:
            raise InputError(f"options.accuracy = {o['accuracy']:g} refines the mesh, which a 3D .msh file cannot be "
                             f"({part}): give the part as a geometry (mesh.kind = 'geometry' with a .geo, STEP or "
                             "BREP file) or a box or cylinder, or remove options.accuracy")
        for key in ("tip_h", "crack_h"):
            if s["mesh"].get(key, 0.0) > 0.0:
                raise InputError(f"mesh.{key} = {s['mesh'][key]:g}: a 3D .msh file is used as it is ({part}); "
                                 "refine it in gmsh, or give the part as a geometry (mesh.kind = 'geometry' with a "
                                 ".geo, STEP or BREP file) that cracklip meshes with tip_h and crack_h")
        if s["mesh"]["refine"]:
            raise InputError(f"mesh.refine: a 3D .msh file is used as it is ({part}); refine it in gmsh, or give "
                             "the part as a geometry (mesh.kind = 'geometry')")


