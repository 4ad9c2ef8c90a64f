"""Scene input: mesh, material, cracks, boundary conditions, loads, options."""
from __future__ import annotations

import dataclasses
import math
import numbers
import typing

import numpy as np

from .errors import BoundaryConditionError, CrackGeometryError, InputError, MaterialError
from .mesh import MeshData

Value = typing.Union[float, typing.Callable[[np.ndarray], np.ndarray]]
VectorValue = typing.Union[typing.Sequence[float], typing.Callable[[np.ndarray], np.ndarray]]


PLANES = ("strain", "stress")


@dataclasses.dataclass(frozen=True)
class Material:
    """Linear elastic, isotropic, in plane strain (default) or plane stress.

    Attributes:
        E: Young's modulus (> 0).
        nu: Poisson's ratio (-1 < nu < 0.5 in plane strain, <= 0.5 in plane stress).
        plane: "strain" (thick parts: eps_zz = 0) or "stress" (thin plates:
            sigma_zz = 0).

    Plane stress with (E, nu) has the in-plane response of plane strain with
    (E_strain, nu_strain) = (E (1 + 2 nu) / (1 + nu)^2, nu / (1 + nu)): the
    kernels, the Williams fields (kappa = (3 - nu) / (1 + nu)) and K = sqrt(E* G)
    (E* = E) all follow from that pair, exactly.
    """
    E: float
    nu: float
    plane: str = "strain"

    def __post_init__(self):
        if self.plane not in PLANES:
            raise MaterialError(f"plane must be 'strain' or 'stress', got {self.plane!r}")
        if not (isinstance(self.E, numbers.Real) and math.isfinite(self.E) and self.E > 0.0):
            raise MaterialError(f"Young's modulus E must be positive, got {self.E}")
        ok = isinstance(self.nu, numbers.Real) and math.isfinite(self.nu) and -1.0 < self.nu <= 0.5
        if not ok or (self.plane == "strain" and self.nu == 0.5):
            raise MaterialError(
                f"Poisson's ratio nu must lie in (-1, 0.5) for plane strain, got {self.nu} (nu = 0.5 is "
                "incompressible: not supported)" if self.plane == "strain" else
                f"Poisson's ratio nu must lie in (-1, 0.5] for plane stress, got {self.nu}")

    @property
    def E_strain(self) -> float:
        """Young's modulus of the plane-strain material with the same in-plane response."""
        return self.E if self.plane == "strain" else self.E * (1.0 + 2.0 * self.nu) / (1.0 + self.nu) ** 2

    @property
    def nu_strain(self) -> float:
        """Poisson's ratio of the plane-strain material with the same in-plane response."""
        return self.nu if self.plane == "strain" else self.nu / (1.0 + self.nu)

    @property
    def mu(self) -> float:
        return self.E / (2.0 * (1.0 + self.nu))

    @property
    def kappa(self) -> float:
        """Kolosov's constant: 3 - 4 nu (plane strain), (3 - nu) / (1 + nu) (plane stress)."""
        return 3.0 - 4.0 * self.nu_strain

    @property
    def E_star(self) -> float:
        """E' of G = K^2 / E': E / (1 - nu^2) (plane strain), E (plane stress)."""
        return self.E_strain / (1.0 - self.nu_strain ** 2)

    @property
    def sigma_zz_ratio(self) -> float:
        """sigma_zz / (sigma_xx + sigma_yy): nu (plane strain), 0 (plane stress)."""
        return self.nu if self.plane == "strain" else 0.0

    def scaled(self, E: float) -> "Material":
        """The same material with Young's modulus E."""
        return Material(E, self.nu, self.plane)


@dataclasses.dataclass
class Crack:
    """A crack as a polyline.

    An end point inside the domain is a crack tip; an end point on or outside
    the boundary makes an edge crack (the polyline must then cross the
    boundary). Tips are found by the model from the mesh.

    Attributes:
        points: (k, 2) polyline vertices, k >= 2.
        name: label used in messages and outputs.
        pressure: pressure on both lips (> 0 pushes them apart: a pressurised
            crack), a number or a callable p(x) of points (n, 2) returning
            (n,); 0 for traction-free lips. With contact the lips carry it
            besides the contact pressure.
        pressure_group: load group whose factor (Scene.load_path) scales
            the pressure.
    """
    points: np.ndarray
    name: str = ""
    pressure: Value = 0.0
    pressure_group: str = "default"

    def __post_init__(self):
        pts = np.asarray(self.points, dtype=np.float64)
        label = self.name or "crack"
        if not callable(self.pressure) and not (isinstance(self.pressure, numbers.Real)
                                                and math.isfinite(self.pressure)):
            raise CrackGeometryError(f"{label}: the lip pressure must be a finite number or a callable "
                                     f"p(x), got {self.pressure!r}")
        if pts.ndim != 2 or pts.shape[1] != 2 or pts.shape[0] < 2:
            raise CrackGeometryError(f"{label}: points must be an array of shape (k, 2), k >= 2; "
                                     f"got shape {pts.shape}")
        if not np.all(np.isfinite(pts)):
            k = int(np.flatnonzero(~np.all(np.isfinite(pts), axis=1))[0])
            raise CrackGeometryError(f"{label}: point {k} is {pts[k].tolist()}; crack points must be "
                                     "finite numbers (no NaN or infinity)")
        lengths = np.linalg.norm(np.diff(pts, axis=0), axis=1)
        scale = max(np.ptp(pts, axis=0).max(), 1e-300)
        bad = np.flatnonzero(lengths <= 1e-12 * scale)
        if bad.size:
            k = int(bad[0])
            raise CrackGeometryError(f"{label}: segment {k} from {pts[k].tolist()} to "
                                     f"{pts[k + 1].tolist()} has zero length; remove the repeated point")
        hit = self_intersection(pts)
        if hit is not None:
            i, j, q = hit
            how = "folds back onto" if j == i + 1 else "meets"
            raise CrackGeometryError(
                f"{label}: segment {i} ({pts[i].tolist()} to {pts[i + 1].tolist()}) {how} segment {j} "
                f"({pts[j].tolist()} to {pts[j + 1].tolist()}) at {np.round(q, 12).tolist()}; a crack must "
                "be a simple polyline (no self-intersection, no point visited twice)")
        self.points = pts


def self_intersection(pts: np.ndarray) -> typing.Optional[tuple[int, int, np.ndarray]]:
    """First pair of segments (i < j) of a polyline that meet other than at
    the point shared by consecutive segments (or that overlap there: the
    polyline folds back), with a point they share; None for a simple polyline."""
    a, b = pts[:-1], pts[1:]
    d = b - a
    m = len(a)
    scale = max(float(np.ptp(pts, axis=0).max()), 1e-300)
    tol = 1e-12 * scale * scale

    def cross(u, v):
        return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]
    # Consecutive segments: only a fold back (collinear, opposite directions).
    if m >= 2:
        fold = (np.abs(cross(d[:-1], d[1:])) <= tol) & (np.einsum("ij,ij->i", d[:-1], d[1:]) < 0.0)
        if fold.any():
            i = int(np.flatnonzero(fold)[0])
            return i, i + 1, b[i]
    for i0 in range(0, max(m - 2, 0), 512):
        i = np.arange(i0, min(i0 + 512, m - 2))[:, None]
        j = np.arange(m)[None, :]
        ai, di, aj, dj = a[i], d[i], a[j], d[j]
        o1, o2 = cross(di, aj - ai), cross(di, aj + dj - ai)
        o3, o4 = cross(dj, ai - aj), cross(dj, ai + di - aj)
        o1, o2, o3, o4 = (np.where(np.abs(o) <= tol, 0.0, o) for o in (o1, o2, o3, o4))
        meet = (o1 * o2 <= 0.0) & (o3 * o4 <= 0.0) & (j >= i + 2)
        collinear = (o1 == 0.0) & (o2 == 0.0)
        # Collinear pairs meet only if their projections on segment i overlap.
        dd = np.einsum("...k,...k->...", di, di)
        s0 = np.einsum("...k,...k->...", aj - ai, di) / dd
        s1 = np.einsum("...k,...k->...", aj + dj - ai, di) / dd
        overlap = (np.maximum(s0, s1) >= -1e-12) & (np.minimum(s0, s1) <= 1.0 + 1e-12)
        meet &= ~collinear | overlap
        if meet.any():
            r, c = np.argwhere(meet)[0]
            ii, jj = int(i[r, 0]), int(c)
            den = cross(d[ii], d[jj])
            if abs(den) > tol:
                t = cross(a[jj] - a[ii], d[jj]) / den
                q = a[ii] + np.clip(t, 0.0, 1.0) * d[ii]
            else:
                q = a[jj] if 0.0 <= s0[r, c] <= 1.0 else a[ii]
            return ii, jj, q
    return None


@dataclasses.dataclass
class Dirichlet:
    """Prescribed displacement.

    Attributes:
        where: a boundary tag name or number, or a point (x, y) that is a mesh node.
        component: 0 (x), 1 (y) or None (both).
        value: a number, or a callable f(x) with x of shape (n, 2) returning
            (n,) for one component or (n, 2) for both; a callable f(x, side)
            also receives the crack side (n,) of each point (+1 / -1) and may
            jump across a crack (an exact crack field on a cut boundary).
        group: load group whose factor (Scene.load_path) scales the value.
    """
    where: typing.Union[str, int, tuple[float, float]]
    component: typing.Optional[int] = None
    value: Value = 0.0
    group: str = "default"

    def __post_init__(self):
        _check_group(self.group, f"Dirichlet condition on {self.where!r}")
        if self.component not in (None, 0, 1):
            raise BoundaryConditionError(f"Dirichlet component must be 0 (x), 1 (y) or None (both), "
                                         f"got {self.component!r}")


@dataclasses.dataclass
class Traction:
    """Surface traction (force per length) on a tagged boundary.

    Attributes:
        where: boundary tag name or number.
        value: (t_x, t_y), or a callable f(x) with x (n, 2) returning (n, 2).
        stress: instead of value, a stress field whose traction sigma n (n
            the outward normal) loads the boundary: (sxx, syy, sxy), a
            stress_field.LinearStress (e.g. bending), or a callable sigma(x)
            returning (n, 2, 2).
        group: load group whose factor (Scene.load_path) scales it.
    """
    where: typing.Union[str, int]
    value: typing.Optional[VectorValue] = None
    stress: typing.Any = None
    group: str = "default"

    def __post_init__(self):
        _check_group(self.group, f"traction on {self.where!r}")
        if (self.value is None) == (self.stress is None):
            raise InputError(f"traction on {self.where!r}: give exactly one of value (a traction) or stress "
                             "(a stress field whose sigma n is applied)")
        if self.stress is not None:
            from .stress_field import as_stress_field
            self.stress = as_stress_field(self.stress, f"traction on {self.where!r}")
        elif not callable(self.value):
            v = np.asarray(self.value, dtype=float)
            if v.shape != (2,) or not np.all(np.isfinite(v)):
                raise InputError(f"traction on {self.where!r}: a constant value must be two finite numbers "
                                 f"(t_x, t_y), got {self.value!r}")


@dataclasses.dataclass
class PointForce:
    """A concentrated force (force, in 2D per unit thickness) at the mesh node
    nearest to a point (which must lie within one element of a node).

    Attributes:
        point: (x, y).
        value: (F_x, F_y).
        group: load group whose factor (Scene.load_path) scales it.
    """
    point: tuple[float, float]
    value: tuple[float, float]
    group: str = "default"

    def __post_init__(self):
        _check_group(self.group, f"point force at {self.point!r}")
        p = np.asarray(self.point, dtype=float)
        v = np.asarray(self.value, dtype=float)
        if p.shape != (2,) or v.shape != (2,) or not (np.all(np.isfinite(p)) and np.all(np.isfinite(v))):
            raise InputError(f"a point force needs a point (x, y) and a value (F_x, F_y) of finite numbers, "
                             f"got point {self.point!r}, value {self.value!r}")
        self.point, self.value = tuple(p.tolist()), tuple(v.tolist())


def _check_group(group, what: str) -> None:
    if not isinstance(group, str) or not group:
        raise InputError(f"{what}: a load group must be a non-empty name, got {group!r}")


@dataclasses.dataclass
class LoadStep:
    """One step of a load path: the factor of each named load group at the
    end of the step. A group not named keeps its factor from the step before
    (0 before the first step: the path starts unloaded).

    Attributes:
        factors: group name -> factor.
        name: label in outputs (default "step k").
    """
    factors: dict[str, float]
    name: str = ""

    def __post_init__(self):
        if not isinstance(self.factors, dict) or not self.factors:
            raise InputError(f"load step {self.name!r}: factors must be a non-empty mapping group -> factor, "
                             f"got {self.factors!r}")
        for g, f in self.factors.items():
            _check_group(g, f"load step {self.name!r}")
            if isinstance(f, bool) or not isinstance(f, numbers.Real) or not math.isfinite(f):
                raise InputError(f"load step {self.name!r}: the factor of group {g!r} must be a finite number, "
                                 f"got {f!r}")


ENRICHMENTS = ("none", "scalar", "vector")
#: Integer options and their largest accepted value (quadrature degrees and
#: point counts beyond these cost time without adding accuracy).
INTEGER_OPTIONS = {"quadrature_degree": 60, "degree": 60, "facet_degree": 60, "tip_radial": 60,
                   "tip_angular": 60, "contact_points": 60, "max_active_set_iterations": 10000,
                   "load_steps": 10000}
TIP_QUADRATURES = ("collapsed", "gauss")
SOLVERS = ("auto", "direct", "iterative")


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
            at that tip. Either way it is clipped to stay inside the part and
            away from other tips, other cracks, kinks of the crack and holes
            (a warning says so).
        friction: Coulomb friction coefficient mu of the crack lips (0:
            frictionless); needs contact "bilateral" or "unilateral". Each
            contact multiplier is then open, stick or slip (semi-smooth
            Newton over the three states, friction.py).
        load_steps: increments per step of the load path (Scene.load_path);
            friction is path-dependent, so a leg in several increments
            follows its slip history more closely.
        solver: linear solver: "direct" (MUMPS LDL^T), "iterative" (AMG in a
            phantom-node basis, a direct solve of the crack band; same
            checked accuracy) or "auto" (chosen by size and enriched
            fraction as measured: cracklip.solvers.choose_solver).
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
    contact_points: int = 6
    active_set_start: str = "closed"
    max_active_set_iterations: int = 20
    snap_tol: float = 1e-6
    facet_degree: int = 4
    residual_tol: float = 1e-8
    rescale: str = "none"
    sif_radius: float = 0.0
    friction: float = 0.0
    load_steps: int = 1
    solver: str = "auto"

    def __post_init__(self):
        if self.enrichment not in ENRICHMENTS:
            raise InputError(f"enrichment must be one of {ENRICHMENTS}, got {self.enrichment!r}")
        if self.blending not in ("corrected", "standard"):
            raise InputError(f"blending must be 'corrected' or 'standard', got {self.blending!r}")
        if self.contact not in ("none", "bilateral", "unilateral"):
            raise InputError(f"contact must be 'none', 'bilateral' or 'unilateral', got {self.contact!r}")
        if self.rescale not in ("none", "nodal"):
            raise InputError(f"rescale must be 'none' or 'nodal', got {self.rescale!r}")
        if self.solver not in SOLVERS:
            raise InputError(f"solver must be one of {SOLVERS}, got {self.solver!r}")
        if self.multipliers not in ("stable", "naive"):
            raise InputError(f"multipliers must be 'stable' or 'naive', got {self.multipliers!r}")
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
        if isinstance(self.friction, bool) or not (isinstance(self.friction, numbers.Real)
                                                   and math.isfinite(self.friction) and self.friction >= 0.0):
            raise InputError(f"friction must be a finite number >= 0 (the Coulomb coefficient mu; 0: "
                             f"frictionless), got {self.friction!r}")
        if self.friction > 0.0 and self.contact == "none":
            raise InputError(f"friction = {self.friction:g} needs contact = 'bilateral' or 'unilateral' (the "
                             "lips must be able to touch to rub)")
        if not (0.05 <= self.tip_max_angle <= 3.2):
            raise InputError(f"tip_max_angle must lie in [0.05, 3.2] radians, got {self.tip_max_angle}")

    def quadrature_options(self):
        """The C++ QuadratureOptions of these options."""
        from . import _cracklip
        q = _cracklip.QuadratureOptions()
        q.degree = int(self.degree)
        q.tip_rule = getattr(_cracklip.TipQuadrature, self.quadrature)
        q.tip_radial = int(self.tip_radial)
        q.tip_angular = int(self.tip_angular)
        q.tip_max_angle = float(self.tip_max_angle)
        q.tip_degree = int(self.quadrature_degree)
        return q


@dataclasses.dataclass
class Scene:
    """Everything a solve needs."""
    mesh: MeshData
    material: Material
    cracks: list[Crack] = dataclasses.field(default_factory=list)
    dirichlet: list[Dirichlet] = dataclasses.field(default_factory=list)
    tractions: list[Traction] = dataclasses.field(default_factory=list)
    options: Options = dataclasses.field(default_factory=Options)
    #: Constant body force (f_x, f_y), force per unit area, or None.
    body_force: typing.Optional[typing.Sequence[float]] = None
    #: Concentrated forces at nodes.
    point_forces: list[PointForce] = dataclasses.field(default_factory=list)
    #: Initial (residual) stress sigma_0 of the part, or None: the stress is
    #: sigma = C eps(u) + sigma_0, so sigma_0 acts through its equivalent
    #: loads (-div sigma_0 inside, sigma_0 n on the boundary and the lips).
    #: (sxx, syy, sxy), a stress_field.LinearStress or a callable sigma_0(x).
    initial_stress: typing.Any = None
    #: Load groups of the body force and the initial stress.
    body_force_group: str = "default"
    initial_stress_group: str = "default"
    #: The load path: steps of factors per load group (LoadStep), solved in
    #: order with Options.load_steps increments per step; friction is
    #: path-dependent, so its slip and states carry over. None: one step
    #: with every group at factor 1.
    load_path: typing.Optional[list] = None

    def __post_init__(self):
        if self.load_path is not None:
            self.load_path = [st if isinstance(st, LoadStep) else LoadStep(dict(st), name=f"step {k + 1}")
                              for k, st in enumerate(self.load_path)]
            for k, st in enumerate(self.load_path):
                st.name = st.name or f"step {k + 1}"
            if not self.load_path:
                raise InputError("load_path is empty: give at least one step, or None for one step at factor 1")
        if self.initial_stress is not None:
            from .stress_field import as_stress_field
            self.initial_stress = as_stress_field(self.initial_stress, "initial stress")
        for i, c in enumerate(self.cracks):
            if not isinstance(c, Crack):
                self.cracks[i] = Crack(np.asarray(c), name=f"crack {i}")
            elif not c.name:
                c.name = f"crack {i}"
        if not self.dirichlet:
            raise BoundaryConditionError("the scene has no Dirichlet condition: rigid body motion "
                                         "is free; fix at least u_x and u_y somewhere and one more "
                                         "component elsewhere")
