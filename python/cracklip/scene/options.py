"""Numerical options of a solve: enrichment, quadrature, contact, SIF domains, solver."""
from __future__ import annotations

import dataclasses
import math
import numbers

from ..errors import InputError, checked_keywords


ENRICHMENTS = ("none", "scalar", "vector")


#: Integer options and their largest accepted value (quadrature degrees and
#: point counts beyond these cost time without adding accuracy).
INTEGER_OPTIONS = {"quadrature_degree": 60, "degree": 60, "facet_degree": 60, "tip_radial": 60,
                   "tip_angular": 60, "contact_points": 60, "max_active_set_iterations": 10000,
                   "load_steps": 10000, "accuracy_levels": 6, "sif_points": 1000}


TIP_QUADRATURES = ("collapsed", "gauss")


SOLVERS = ("auto", "direct", "iterative")

#: Options.sif_smoothing: K along 3D fronts as computed, or fitted along them.
SIF_SMOOTHINGS = ("none", "fit")


def check_ring(ring, what: str = "ring") -> tuple[float, float]:
    """A SIF ring (r_in, r_out) as two floats with 0 <= r_in <= r_out, r_out > 0."""
    ok = (isinstance(ring, (list, tuple)) and len(ring) == 2
          and all(isinstance(v, numbers.Real) and not isinstance(v, bool) and math.isfinite(v) for v in ring))
    if not ok or not (0.0 <= ring[0] <= ring[1] and ring[1] > 0.0):
        raise InputError(f"{what} must be two radii [r_in, r_out] with 0 <= r_in <= r_out and r_out > 0 (q = 1 "
                         f"within r_in, 0 beyond r_out, linear between), got {ring!r}")
    return float(ring[0]), float(ring[1])


@checked_keywords
@dataclasses.dataclass
class Options:
    """Numerical options.

    Attributes:
        enrichment: crack-tip enrichment: "vector" (the two Williams fields,
            2 dofs per node), "scalar" (4 branch functions x 2 components, 8
            dofs per node) or "none" (Heaviside only; the crack then ends at
            the edge of the tip cell).
        radius: geometric enrichment radius: nodes within it of a tip get tip
            dofs. 0 enriches only the nodes of the cell holding the tip.
        blending: "corrected" (tip functions times the ramp of the enriched
            nodes' partition of unity, also on the blending cells' nodes:
            Fries' corrected X-FEM, optimal convergence) or "standard".
        quadrature: rule where tip functions live: "collapsed" (quasi-polar
            fan from the tip, exact for the 1/r singularity) or "gauss" (the
            paper's plain ((p + 3) / 2)^2-point rule on sub-triangles).
        quadrature_degree: p of the "gauss" rule.
        tip_radial, tip_angular, tip_max_angle: the collapsed rule's points
            along and across each fan triangle, and its largest apex angle.
        degree: Gauss degree in cells without tip functions (1 is exact for
            P1 x Heaviside).
        contact: crack-lip contact: "none" (traction-free lips), "bilateral"
            (normal gap held at 0, lips slide freely) or "unilateral" (gap >= 0,
            pressure >= 0, complementarity; primal-dual active set).
        multipliers: "stable" (P1-, Bechet-Moes-Wohlmuth, P0 in the tip
            cell) or "naive" (P1 on every node of the cut cells).
        multiplier_stabilization: gamma of the penalty on neighbouring
            multiplier groups' differences (contact/stabilization.py);
            default (None) 0 in 2D, DEFAULT_GAMMA[3] in 3D; 0: none.
        contact_points: Gauss points per crack segment (tau^2 toward a tip).
        active_set_start: "closed" or "open" initial active set.
        max_active_set_iterations: active-set iterations before giving up (a set
            that comes back stops at once as a cycle).
        snap_tol: a node closer to a crack (or tip line) than snap_tol times
            its shortest edge is moved onto it (level set set to 0).
        facet_degree: degree of the rule for tractions on boundary facets.
        residual_tol: largest accepted relative residual of the linear solve.
        rescale: "none" (the solver still Jacobi-scales internally) or
            "nodal": every node with enriched dofs has its block of standard
            and enriched dofs orthonormalised in the energy (Cholesky), other
            dofs Jacobi-scaled; same answer, a better conditioned matrix
            (Solution.condition then reports the rescaled matrix).
        sif_radius: radius of the largest SIF interaction-integral domain at
            every tip; K is also computed on domains of 1/2 and 3/4 of it,
            whose spread is reported. 0 chooses it per tip: 6 element sizes
            at that tip (3D: 4 front element sizes at each front point). Either way it is clipped to stay inside the part and
            away from other tips, other cracks, kinks of the crack and holes
            (a warning says so).
        sif_ring: the SIF domain as another code defines it, (r_in, r_out):
            K on that one annulus, q = 1 within r_in, 0 beyond r_out, linear
            between (code_aster's R_INF / R_SUP, MOOSE's geometric rings;
            r_in = r_out: cracklip's plateau q of that radius). Taken as
            given, NOT clipped: a ring that reaches a hole, a kink, another
            tip or the boundary warns (sif_domain) and its K is marked
            unreliable (domain_clear false); one domain, so no spread.
            Overrides sif_radius. None: cracklip's domains.
        sif_points: 3D: at least this many front points (where K is
            computed) on every front piece, where hats of three front
            elements fit (front_points.COUNT_HAT_ELEMENTS; a shorter piece
            gets fewer: refine along the front, mesh.tip_h);
            cracklip.fracture.front_sampling.
        sif_angles: 3D: K also at these parametric angles (degrees) of
            elliptical cracks' fronts (e.g. [0, 90]: the two ends of a
            corner crack); None: none.
        sif_angle_step: 3D: K also every this many degrees of parametric
            angle along elliptical fronts (from 0); 0: off.
        sif_arc_lengths: 3D: K also at these arc lengths from the start of
            every front piece (front.csv's s); None: none.
        friction: Coulomb friction coefficient mu of the crack lips (0:
            frictionless); needs contact "bilateral" or "unilateral". Each
            contact multiplier is then open, stick or slip (semi-smooth
            Newton over the three states, cracklip.contact.friction).
        load_steps: increments per step of the load path (Scene.load_path);
            friction is path-dependent, so a leg in several increments
            follows its slip history more closely.
        solver: linear solver: "direct" (MUMPS LDL^T), "iterative" (AMG in a
            phantom-node basis, a direct solve of the crack band; same
            checked accuracy) or "auto" (chosen by size and enriched
            fraction as measured: cracklip.solvers.choose_solver).
        accuracy: target of the estimated discretisation error of every K,
            relative to the K scale (0.01: 1 %); 0: off. Similar meshes,
            every element size halved (2D) or divided by sqrt(2) (3D) per
            level, are solved until the estimate is below it
            (cracklip.analysis.accuracy); a warning if not reached.
        accuracy_levels: at most this many refinement levels for accuracy.
        sif_smoothing: 3D: "fit" (default) or "none" (K as computed at every
            front point). "fit": with the error estimate (or accuracy), K reported as its
            least-squares fit along each front piece (Fourier on a loop,
            Legendre on an open piece, the size by leave-one-out, checked
            against the estimate's second mesh; a mode no fit passes is
            reported as computed), its error estimated from the same fit on
            both meshes (cracklip.analysis.accuracy.fitted_along).
    """
    enrichment: str = "vector"
    radius: float = 0.0
    blending: str = "corrected"
    quadrature: str = "collapsed"
    quadrature_degree: int = 5
    tip_radial: int = 6
    tip_angular: int = 6
    tip_max_angle: float = 0.6
    degree: int = 1
    contact: str = "none"
    multipliers: str = "stable"
    multiplier_stabilization: float | None = None
    contact_points: int = 6
    active_set_start: str = "closed"
    max_active_set_iterations: int = 20
    snap_tol: float = 1e-6
    facet_degree: int = 4
    residual_tol: float = 1e-8
    rescale: str = "none"
    sif_radius: float = 0.0
    sif_ring: tuple[float, float] | None = None
    sif_points: int = 16
    sif_angles: list[float] | None = None
    sif_angle_step: float = 0.0
    sif_arc_lengths: list[float] | None = None
    friction: float = 0.0
    load_steps: int = 1
    solver: str = "auto"
    accuracy: float = 0.0
    accuracy_levels: int = 3
    sif_smoothing: str = "fit"

    def __post_init__(self):
        if self.enrichment not in ENRICHMENTS:
            raise InputError(f"enrichment must be one of {ENRICHMENTS}, got {self.enrichment!r}")
        if self.blending not in ("corrected", "standard"):
            raise InputError(f"blending must be 'corrected' or 'standard', got {self.blending!r}")
        if self.contact not in ("none", "bilateral", "unilateral"):
            raise InputError(f"contact must be 'none', 'bilateral' or 'unilateral', got {self.contact!r}")
        if self.rescale not in ("none", "nodal"):
            raise InputError(f"rescale must be 'none' or 'nodal', got {self.rescale!r}")
        if self.sif_smoothing not in SIF_SMOOTHINGS:
            raise InputError(f"sif_smoothing must be one of {SIF_SMOOTHINGS}, got {self.sif_smoothing!r}")
        if self.solver not in SOLVERS:
            raise InputError(f"solver must be one of {SOLVERS}, got {self.solver!r}")
        if self.multipliers not in ("stable", "naive"):
            raise InputError(f"multipliers must be 'stable' or 'naive', got {self.multipliers!r}")
        if self.multiplier_stabilization is not None and not (
                isinstance(self.multiplier_stabilization, numbers.Real)
                and math.isfinite(self.multiplier_stabilization) and self.multiplier_stabilization >= 0.0):
            raise InputError("multiplier_stabilization must be a number >= 0 (0: none), got "
                             f"{self.multiplier_stabilization!r}")
        if self.active_set_start not in ("closed", "open"):
            raise InputError(f"active_set_start must be 'closed' or 'open', got {self.active_set_start!r}")
        if self.quadrature not in TIP_QUADRATURES:
            raise InputError(f"quadrature must be one of {TIP_QUADRATURES}, got {self.quadrature!r}")
        if not (isinstance(self.radius, numbers.Real) and math.isfinite(self.radius) and self.radius >= 0.0):
            raise InputError(f"enrichment radius must be a finite number >= 0 (0: the tip cell's nodes "
                             f"only), got {self.radius!r}")
        for name, top in INTEGER_OPTIONS.items():
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, numbers.Integral) or not 1 <= v <= top:
                raise InputError(f"{name} must be an integer in [1, {top}], got {v!r}")
        if not (isinstance(self.snap_tol, numbers.Real) and 0.0 <= self.snap_tol < 0.5):
            raise InputError(f"snap_tol must lie in [0, 0.5) (a fraction of the shortest edge at a "
                             f"node), got {self.snap_tol!r}")
        if not (isinstance(self.residual_tol, numbers.Real) and 0.0 < self.residual_tol < 1.0):
            raise InputError(f"residual_tol must lie in (0, 1), got {self.residual_tol!r}")
        if not (isinstance(self.sif_radius, numbers.Real) and math.isfinite(self.sif_radius)
                and self.sif_radius >= 0.0):
            raise InputError(f"sif_radius must be a finite number >= 0 (0: chosen per tip), got "
                             f"{self.sif_radius!r}")
        if self.sif_ring is not None:
            self.sif_ring = check_ring(self.sif_ring, "sif_ring")
        for name in ("sif_angles", "sif_arc_lengths"):
            self._check_positions(name)
        if isinstance(self.sif_angle_step, bool) or not (isinstance(self.sif_angle_step, numbers.Real)
                                                         and 0.0 <= self.sif_angle_step <= 360.0):
            raise InputError(f"sif_angle_step must be a number of degrees in [0, 360] (0: off), got "
                             f"{self.sif_angle_step!r}")
        if isinstance(self.friction, bool) or not (isinstance(self.friction, numbers.Real)
                                                   and math.isfinite(self.friction) and self.friction >= 0.0):
            raise InputError(f"friction must be a finite number >= 0 (the Coulomb coefficient mu; 0: "
                             f"frictionless), got {self.friction!r}")
        if self.friction > 0.0 and self.contact == "none":
            raise InputError(f"friction = {self.friction:g} needs contact = 'bilateral' or 'unilateral' (the "
                             "lips must be able to touch to rub)")
        if isinstance(self.accuracy, bool) or not (isinstance(self.accuracy, numbers.Real)
                                                   and 0.0 <= self.accuracy < 1.0):
            raise InputError(f"accuracy must be a number in [0, 1) (the target of K's estimated error relative to "
                             f"the K scale, e.g. 0.01 for 1 %; 0: off), got {self.accuracy!r}")
        if not (0.05 <= self.tip_max_angle <= 3.2):
            raise InputError(f"tip_max_angle must lie in [0.05, 3.2] radians, got {self.tip_max_angle}")

    def _check_positions(self, name: str) -> None:
        v = getattr(self, name)
        if v is None:
            return
        ok = isinstance(v, (list, tuple)) and all(isinstance(e, numbers.Real) and not isinstance(e, bool)
                                                  and math.isfinite(e) for e in v)
        if not ok or (name == "sif_arc_lengths" and any(e < 0.0 for e in v)):
            raise InputError(f"{name} must be a list of finite numbers{' >= 0' if name == 'sif_arc_lengths' else ''}"
                             f", got {v!r}")
        setattr(self, name, [float(e) for e in v])

    def quadrature_options(self):
        """The C++ QuadratureOptions of these options."""
        from .. import _cracklip
        q = _cracklip.QuadratureOptions()
        q.degree = int(self.degree)
        q.tip_rule = getattr(_cracklip.TipQuadrature, self.quadrature)
        q.tip_radial = int(self.tip_radial)
        q.tip_angular = int(self.tip_angular)
        q.tip_max_angle = float(self.tip_max_angle)
        q.tip_degree = int(self.quadrature_degree)
        return q

    def quadrature_options_3d(self):
        """The C++ QuadratureOptions3D of these options (tetrahedra): the
        front rule ("collapsed": edge- and point-collapsed rules on the
        sub-tetrahedra touching the front; "gauss": plain Gauss of degree
        quadrature_degree there), Gauss of degree at least 2 elsewhere, the
        collapsed rules' points at their C++ defaults (4 x 6 x 2)."""
        from .. import _cracklip
        q = _cracklip.QuadratureOptions3D()
        q.degree = max(int(self.degree), 2)
        q.front_rule = self.quadrature
        q.front_degree = int(self.quadrature_degree)
        return q
