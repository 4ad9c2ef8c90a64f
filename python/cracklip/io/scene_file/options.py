"""[options] and [outputs]: the keys of every cracklip.Options field (its
default from the dataclass, its meaning from OPTION_MEANINGS or Options'
docstring) and of the outputs, and the command-line flags of the demos
that set options (``add_option_arguments``)."""
from __future__ import annotations

import dataclasses
import typing

from ...scene.options import ENRICHMENTS, Options, SIF_SMOOTHINGS, SOLVERS, TIP_QUADRATURES
from .schema import (UNSET, Key, docstring_attributes, p_bool, p_choice, p_float, p_int, p_number_list,
                     p_numbers, p_str)


STRESS_COMPONENTS = ("xx", "yy", "xy", "von_mises")


_OPTION_MEANINGS = {
    "enrichment": "crack-tip enrichment: `vector` (the two Williams fields, 2 dofs per node), "
                  "`scalar` (4 branch functions, 8 dofs per node) or `none` (Heaviside only)",
    "radius": "geometric enrichment radius: nodes within it of a tip get tip dofs; 0 enriches "
              "the tip cell's nodes only",
    "blending": "`corrected` (Fries' corrected X-FEM, optimal rate) or `standard` blending",
    "quadrature": "rule where tip functions live: `collapsed` (quasi-polar fan from the tip) "
                  "or `gauss` (the paper's plain rule)",
    "quadrature_degree": "degree p of the `gauss` tip rule ((p + 3) / 2)^2 points per sub-triangle",
    "tip_radial": "`collapsed` rule: points along each ray of a fan triangle",
    "tip_angular": "`collapsed` rule: points across each fan triangle",
    "tip_max_angle": "`collapsed` rule: largest apex angle of a fan triangle (radians)",
    "degree": "Gauss degree in enriched cells without tip functions (1 is exact for P1 x Heaviside)",
    "contact": "crack-lip contact: `none` (traction-free lips), `bilateral` (lips held together, "
               "free to slide) or `unilateral` (gap >= 0, pressure >= 0; active set)",
    "multipliers": "multiplier space: `stable` (P1-, P0 in the tip cell) or `naive` (P1 on every "
                   "node of the cut cells; violates inf-sup)",
    "contact_points": "Gauss points per crack segment (2D) or per lip facet direction (3D) for the contact terms",
    "active_set_start": "initial active set of unilateral contact: `closed` or `open`",
    "multiplier_stabilization": "gamma of the contact multipliers' stabilization (a penalty on each multiplier "
    "group's departure from the linear fit of its closed neighbours; it damps a checkerboard of the 3D pressure "
    "and vanishes on linear pressures; docs/contact.md); default: 0 in 2D, 8 in 3D; 0: none",
    "max_active_set_iterations": "active-set iterations before giving up (a set that comes back stops at once as a cycle)",
    "snap_tol": "a node closer to a crack than snap_tol times its shortest edge is moved onto it",
    "facet_degree": "quadrature degree of boundary tractions",
    "residual_tol": "largest accepted relative residual of a linear solve",
    "rescale": "`none`, or `nodal`: each enriched node's block of standard and enriched dofs "
               "orthonormalised (Cholesky), others Jacobi-scaled; same answer, better conditioned matrix",
    "friction": "Coulomb friction coefficient mu of the lips (0: frictionless); needs contact `bilateral` or "
                "`unilateral`; each multiplier open, stick or slip",
    "load_steps": "increments per step of the load path (friction is path-dependent: more increments "
                  "follow the slip history closely)",
    "sif_radius": "radius of the largest SIF domain at every tip (K also on 1/2 and 3/4 of it; their "
                  "spread is reported); 0: 6 element sizes at that tip (3D: 4 front element sizes at each "
                  "front point); clipped to stay inside the part and away from other tips, cracks, kinks and "
                  "holes (with a warning)",
    "sif_ring": "K on one ring as another code defines it: q = 1 within r_in, 0 beyond r_out, linear between "
                "(code_aster's R_INF / R_SUP, MOOSE's rings; r_in = r_out: the plateau of that radius); NOT clipped: "
                "a ring reaching a hole, kink, tip or the boundary warns and its K is marked unreliable; no spread; "
                "overrides sif_radius (a ring through a hole: docs/growth.md)",
    "sif_points": "3D: at least this many front points (where K is computed) on every front piece, where hats of three "
                  "front elements fit (a shorter piece gets fewer: a penny at a/10, 6.28 a long, gets 15; refine along "
                  "the front, mesh.tip_h); docs/sifs.md",
    "sif_angles": "3D: K also at these parametric angles (degrees) of elliptical cracks' fronts, e.g. [0, 90] for the "
                  "two ends of a corner crack (between front points: interpolated, flagged); docs/sifs.md",
    "sif_angle_step": "3D: K also every this many degrees of parametric angle along elliptical fronts (from 0); 0: off",
    "sif_arc_lengths": "3D: K also at these arc lengths from the start of every front piece (front.csv's s)",
    "accuracy": "target of the estimated discretisation error of every K (3D: at every front point off a free "
                "surface), relative to the K scale (0.01: 1 %); 0: off. Solves similar meshes, every element size "
                "halved (2D) or divided by sqrt(2) (3D) per level, until the estimate is below it; reports the "
                "meshes, the estimate and (2D) the extrapolated K; warns if not reached (docs/guide.md)",
    "accuracy_levels": "at most this many refinement levels for options.accuracy (each about 4 (2D) or 2.8 (3D) "
                       "times the cells of the one before)",
    "sif_smoothing": "3D: `fit` or `none` (K as computed at every front point). `fit`: with the error estimate (or accuracy), "
                     "K reported as its least-squares fit along each front piece (Fourier / Legendre, the size by "
                     "leave-one-out, checked against the estimate's second mesh; a mode no fit passes stays as "
                     "computed; the computed K kept as K_I_unsmoothed ...); the estimate then follows the fitted K "
                     "(docs/guide.md)",
    "solver": "linear solver: `direct` (MUMPS LDL^T), `iterative` (AMG in a phantom-node basis with a "
              "direct solve of the crack band; same checked accuracy) or `auto` (iterative from 5e4 "
              "dofs when 1-5 % of them (3D: 1-30 %) are enriched and from 2e6 dofs always, else direct, and "
              "direct with rescale = nodal: the faster one as measured)",
}


_OPTION_CHOICES = {
    "enrichment": ENRICHMENTS, "blending": ("corrected", "standard"), "quadrature": TIP_QUADRATURES,
    "contact": ("none", "bilateral", "unilateral"), "multipliers": ("stable", "naive"),
    "active_set_start": ("closed", "open"), "rescale": ("none", "nodal"),
    "solver": SOLVERS, "sif_smoothing": SIF_SMOOTHINGS,
}


def _option_keys() -> list[Key]:
    """The [options] keys: every field of cracklip.Options (defaults from the
    dataclass itself; the meaning from _OPTION_MEANINGS, else from Options'
    docstring)."""
    keys = []
    documented = docstring_attributes(Options)
    for f in dataclasses.fields(Options):
        default = f.default
        meaning = _OPTION_MEANINGS.get(f.name) or documented.get(f.name, f.name.replace("_", " "))
        if f.name in _OPTION_CHOICES:
            keys.append(Key(f"options.{f.name}", "string", default, meaning, p_choice(*_OPTION_CHOICES[f.name])))
        elif f.name == "sif_ring":
            keys.append(Key(f"options.{f.name}", "[r_in, r_out]", UNSET, meaning,
                            p_numbers(2, "two radii [r_in, r_out]")))
        elif f.name == "multiplier_stabilization":
            keys.append(Key(f"options.{f.name}", "float", UNSET, meaning, p_float(0.0)))
        elif f.name in ("sif_angles", "sif_arc_lengths"):
            keys.append(Key(f"options.{f.name}", "[number, ...]", UNSET, meaning, p_number_list))
        elif isinstance(default, bool):
            keys.append(Key(f"options.{f.name}", "boolean", default, meaning, p_bool))
        elif isinstance(default, int):
            keys.append(Key(f"options.{f.name}", "integer", default, meaning, p_int(1)))
        elif isinstance(default, str):
            keys.append(Key(f"options.{f.name}", "string", default, meaning, p_str))
        else:
            keys.append(Key(f"options.{f.name}", "float", default, meaning, p_float(0.0)))
    return keys



OPTION_KEYS: list[Key] = _option_keys()
_OPTIONS_BY_PATH = {k.path: k for k in OPTION_KEYS}


OUTPUT_KEYS: list[Key] = [
    Key("outputs.vtu", "boolean", True, "write ParaView files solution.vtu and crack_lips.vtu (3D: "
        "solution.vtu, crack_surface.vtu, crack_front.vtu and front_sifs.vtu)", p_bool),
    Key("outputs.png", "boolean", True, "write deformed.png, crack_pressure.png and stress.png (3D: "
        "crack_opening.png, front_sifs.png and with contact crack_contact.png)", p_bool),
    Key("outputs.magnification", "float", 0.0,
        "displacement scale of deformed.png; 0: largest displacement = 5 % of the part", p_float(0.0)),
    Key("outputs.stress_component", "string", "yy", "stress shown in stress.png: `xx`, `yy`, `xy` "
        "or `von_mises`", p_choice(*STRESS_COMPONENTS)),
    Key("outputs.error_estimate", "boolean", True,
        "estimate the discretisation error of every K with one more solve: 2D, every element size halved within 20 "
        "element sizes of each tip; 3D, a similar mesh with every size setting times sqrt(2) (about 1/3 of the "
        "dofs), or times 1/sqrt(2) when mesh.tip_h is above a tenth of the crack size (K not yet asymptotic there; "
        "about 2.5 times the dofs); a .msh file: 2D halved, 3D no estimate; "
        "results.json, sif.csv, front.csv, a warning above 1 % of the K scale); options.accuracy makes its own",
        p_bool),
    Key("outputs.condition_number", "boolean", False,
        "estimate the 1-norm condition number of the stiffness (results.json)", p_bool),
    Key("outputs.crack_points", "integer", 3, "sample points per crack segment in crack.csv (3D: per "
        "direction of each lip facet, for the statistics of results.json)", p_int(1)),
]


# Demo flags named differently from their Options field (the issues' names).
_FLAGS = {"quadrature_degree": "degree"}


def add_option_arguments(parser, choices: dict[str, tuple[str, ...]] | None = None, **defaults) -> None:
    """Add one command-line flag per given Options field to an argparse
    parser, with the scene file's choices and meaning and the caller's
    default: add_option_arguments(ap, enrichment="vector", radius=0.2).
    choices narrows a field's choices (e.g. contact without `none`).
    quadrature_degree is the flag --degree (args.degree)."""
    for name, default in defaults.items():
        key = _OPTIONS_BY_PATH[f"options.{name}"]
        kw: dict[str, typing.Any] = {"default": default,
                                     "help": f"{key.meaning} (default {default})".replace("%", "%%")}
        if name in _OPTION_CHOICES:
            kw["choices"] = (choices or {}).get(name, _OPTION_CHOICES[name])
        else:
            kw["type"] = type(key.default)
        parser.add_argument("--" + _FLAGS.get(name, name).replace("_", "-"), **kw)

