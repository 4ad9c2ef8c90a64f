"""One crack on the mesh, whatever the dimension: the interface through which
the model, its constraints, assembly, checks, the solvers and the
post-processing see a crack.

A crack on a mesh (``CrackModel``) has

- level sets at the nodes: ``phi`` (normal: the signed distance to the
  crack, > 0 on its + side) and ``psi`` (tangential: < 0 behind the tip or
  the front);
- cell classes (``cell_class``, codes in ``CELL_CLASSES``; ``CROSSED``:
  the classes of the cells the crack splits into two sides);
- sub-cells of the cells it splits (``subcell_fields``) and lip facets,
  points on the crack inside the cells with weights and normals
  (``lip_points``, ``lip_samples``);
- its front with the local frames (e1 along the propagation, e2 the
  crack's normal): in 2D the tips, each a front of one point; in 3D the
  front polylines (cracklip.fracture.sif and sif_3d place the SIF points on
  it and give both the same row schema);
- the enrichment selection of all cracks of the model together
  (``enrichment_layout``).

Two implementations: ``CurveCrackModel`` (cracks.curve: a polyline on
triangles, ending at tips) and ``SurfaceCrackModel`` (cracks.surface: a
surface on tetrahedra, ending at fronts). A model's cracks are all of the
type of its mesh (``crack_model_type(gdim)``), and that type also carries
the C++ entry points of its cells (sparsity, enriched stiffness, enrichment
layout, facet basis, lip points and loads, cell loads, displacement
evaluation: one binding each for both dimensions, which takes the dimension
from the mesh arrays; the quadrature options, which differ: tip rules in
2D, front rules in 3D): the callers write one line whatever the dimension,
and a model without cracks has the type too (``XfemModel.crack_type``).
"""
from __future__ import annotations

import abc
import typing

import numpy as np

from ... import _cracklip
from ...scene.stress_field import evaluate_stress, tensor_to_voigt


class CrackModel(abc.ABC):
    """One crack on the mesh (module doc).

    Attributes:
        crack: its description (scene.crack.Crack in 2D, a crack surface of
            scene.crack_surface in 3D).
        tips: which ends of a 2D polyline are tips inside the part (first,
            last); empty in 3D (the front says where the crack ends).
        geometry: the C++ geometry (_cracklip.CrackGeometry or
            CrackGeometry3D): level sets, cell classes, sub-cells, lip
            facets, tips or front.
    """

    #: Space dimension of the cracks of this type.
    DIM: typing.ClassVar[int]
    #: Cell classes (name -> code of geometry.cell_class).
    CELL_CLASSES: typing.ClassVar[dict[str, int]]
    #: Codes of the classes whose cells the crack splits into two sides.
    CROSSED: typing.ClassVar[tuple[int, ...]]
    #: Codes of the crossed classes whose cells the crack splits whole (not
    #: the cell holding a tip or the front, whose sides meet around it).
    SPLIT: typing.ClassVar[tuple[int, ...]]
    #: What the crack ends at: "tip" (2D) or "front" (3D).
    END: typing.ClassVar[str]
    #: The measure of the crack, as messages name it: "length" (a curve) or "area" (a surface).
    EXTENT: typing.ClassVar[str]
    #: The stress components of the Voigt columns.
    VOIGT: typing.ClassVar[tuple[str, ...]]
    #: The scene Options method giving the C++ quadrature options of these
    #: cells (QuadratureOptions: tip rules; QuadratureOptions3D: front rules).
    QUADRATURE: typing.ClassVar[typing.Callable]
    #: The Gauss degree the body force and initial stress loads of enriched
    #: cells are raised to (None: the stiffness's own rules, loads.py).
    LOAD_DEGREE: typing.ClassVar[int | None]

    def __init__(self, crack, tips: tuple[bool, ...], geometry):
        self.crack = crack
        self.tips = tuple(tips)
        self.geometry = geometry

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.crack.name!r})"

    # -- the crack's own geometry -------------------------------------------
    @property
    def phi(self) -> np.ndarray:
        """Normal level set at the nodes (num_nodes,)."""
        return np.asarray(self.geometry.phi)

    @property
    def psi(self) -> np.ndarray:
        """Tangential level set at the nodes (num_nodes,)."""
        return np.asarray(self.geometry.psi)

    @property
    def cell_class(self) -> np.ndarray:
        """Class of every cell (num_cells,), codes of CELL_CLASSES."""
        return np.asarray(self.geometry.cell_class)

    @abc.abstractmethod
    def ends_inside(self) -> bool:
        """Whether the crack ends inside the part (a tip or a front there);
        a crack that does not can cut the part into pieces."""

    def crossed(self) -> np.ndarray:
        """Mask (num_cells,) of the cells this crack splits into two sides."""
        return np.isin(self.cell_class, self.CROSSED)

    def lip_points(self, model, points: int) -> dict[str, np.ndarray]:
        """Quadrature points on the crack inside the cells: cell (n,), ref
        (n, d), x (n, d), weight (n,), normal (n, d) into the + side;
        `points` per segment (2D) or per facet direction (3D); computed once."""
        cache = self.__dict__.setdefault("_lip_points", {})
        if points not in cache:
            cache[points] = _cracklip.compute_lip_points(model.x, model.cells, self.geometry, int(points))
        return cache[points]

    @abc.abstractmethod
    def lip_samples(self, model, points: int) -> dict[str, np.ndarray]:
        """lip_points ordered for output (2D: along the crack, with the arc
        length s from its first point; 3D: facet by facet, with the
        front_vertices of each point's facet)."""

    @staticmethod
    @abc.abstractmethod
    def slip(jump: np.ndarray, normal: np.ndarray) -> np.ndarray:
        """The tangential part of the jumps (n, d) on lips of normals (n, d):
        2D the signed slip [[u]].t (n,) (t = n turned by -90 degrees), 3D
        the tangential vector (n, 3)."""

    # -- construction and checks (per dimension) ------------------------------
    @classmethod
    @abc.abstractmethod
    def check_scene(cls, scene) -> None:
        """Raise if the scene holds what a part of this dimension cannot model."""

    @classmethod
    @abc.abstractmethod
    def create(cls, scene, crack, x: np.ndarray, cells: np.ndarray) -> "CrackModel":
        """The crack on the mesh (nodes x, cells); CrackGeometryError if it
        does not fit it."""

    @classmethod
    def enrichment_layout(cls, scene, x: np.ndarray, cells: np.ndarray, cracks: list["CrackModel"]):
        """The enriched pseudo-nodes and cells of all cracks (Options.enrichment, radius, blending)."""
        opts = scene.options
        return _cracklip.create_enrichment_layout(x, cells, [c.geometry for c in cracks], opts.enrichment,
                                                  radius=opts.radius, kappa=scene.material.kappa,
                                                  corrected=opts.blending == "corrected")

    @classmethod
    @abc.abstractmethod
    def check_model(cls, model) -> list:
        """Raise on what makes the model unusable; return the model checks'
        warnings (cracklip.model.checks.ModelWarning)."""

    # -- the kernels of the cells (per dimension) -----------------------------
    @classmethod
    @abc.abstractmethod
    def cell_measures(cls, x: np.ndarray, cells: np.ndarray) -> np.ndarray:
        """Area (2D) or volume (3D) of each cell."""

    @classmethod
    @abc.abstractmethod
    def shape_gradients(cls, x: np.ndarray, cells: np.ndarray) -> np.ndarray:
        """Gradients (c, d + 1, d) of the P1 shape functions of cells (c, d + 1)."""

    @classmethod
    @abc.abstractmethod
    def cell_rule(cls, degree: int) -> tuple[np.ndarray, np.ndarray]:
        """A rule on the cell exact to `degree` (1 or 4): barycentric points
        (k, d + 1) and weights (k,) summing to 1."""

    @classmethod
    def quadrature_options(cls, options, degree: int | None = None):
        """The C++ quadrature options of scene Options (the stiffness's), the
        Gauss degree raised to `degree` if given."""
        q = cls.QUADRATURE(options)
        if degree is not None:
            q.degree = max(q.degree, int(degree))
        return q

    @classmethod
    def sparsity(cls, cells: np.ndarray, layout) -> tuple[np.ndarray, np.ndarray]:
        """CSR (indptr, indices) of the blocked matrix with every coupling."""
        return _cracklip.create_sparsity(cells, layout)

    @classmethod
    def assemble_stiffness(cls, A, model, E: float, nu: float) -> int:
        """Add the enriched blocks into the PETSc matrix A; returns the
        number of cells integrated. On a distributed model: the owned
        enriched cells, through A's local-to-global map."""
        if model.distributed:
            return _cracklip.assemble_enriched_stiffness_petsc(
                A.handle, model.x, model.cells, model.layout.with_cells_below(model.num_owned_cells),
                model.geometries, E, nu, cls.quadrature_options(model.scene.options), local=True)
        return _cracklip.assemble_enriched_stiffness_petsc(A.handle, model.x, model.cells, model.layout,
                                                           model.geometries, E, nu,
                                                           cls.quadrature_options(model.scene.options))

    @classmethod
    def facet_basis(cls, model, cells: np.ndarray, local: np.ndarray, degree: int) -> dict[str, np.ndarray]:
        """Quadrature of boundary facets (cell, local facet) with every basis
        function there: points, weights, entry_point, entry_dof, entry_value."""
        return _cracklip.compute_facet_basis(model.x, model.cells, model.layout, model.geometries, cells, local,
                                             degree)

    @classmethod
    @abc.abstractmethod
    def enriched_cell_points(cls, model, cells: np.ndarray, degree: int) -> dict[str, np.ndarray]:
        """The stiffness's quadrature points of enriched cells, at least
        Gauss degree `degree`: cell, ref, x, weight, side."""

    @classmethod
    def assemble_cell_load(cls, model, points: dict, force: np.ndarray, stress: np.ndarray | None) -> np.ndarray:
        """int f . phi_j - int sigma_0 : eps(phi_j) on the enriched dofs
        from values at enriched_cell_points (force (n, d), stress (n, VOIGT)
        or None)."""
        return _cracklip.assemble_cell_load(model.x, model.cells, model.layout, model.geometries, points["cell"],
                                            points["ref"], points["side"], points["weight"], force, stress)

    @classmethod
    def assemble_lip_load(cls, model, crack: int, points: dict, traction: np.ndarray) -> np.ndarray:
        """int t [[phi_j]] over a crack's lip points (traction (n, d) on the + lip)."""
        return _cracklip.assemble_lip_load(model.x, model.cells, model.layout, model.geometries, crack,
                                           points["cell"], points["ref"], points["weight"], traction)

    @classmethod
    def evaluate(cls, model, u: np.ndarray, cells: np.ndarray, ref: np.ndarray,
                 sides: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Displacement (n, d) and gradient (n, d, d) of the dofs u at
        points (cell, ref) on a side (+1 / -1 of a crossing crack, 0 the
        point's own)."""
        return _cracklip.evaluate_displacement(model.x, model.cells, model.layout, model.geometries, u,
                                               np.asarray(cells, dtype=np.int32),
                                               np.ascontiguousarray(ref, dtype=float), np.asarray(sides, dtype=np.int8))

    @classmethod
    @abc.abstractmethod
    def field_points(cls, model, u: np.ndarray, cells: np.ndarray | None, degree: int | None) -> dict[str, np.ndarray]:
        """Quadrature points on cells (all if None) with grad u there: cell,
        x, weight, side, grad_u."""

    @classmethod
    @abc.abstractmethod
    def subcell_fields(cls, solution) -> dict[str, typing.Any]:
        """The solution on the sub-cell mesh (cells split along the cracks,
        vertices not shared across them): points (P, d), displacement (P,
        d), cells (C, d + 1) into points, stress (C, Voigt: VOIGT),
        von_mises (C,), side (C,), parent (C,) and what else the dimension
        has."""


def crack_model_type(gdim: int) -> type[CrackModel]:
    """The CrackModel implementation of a mesh of dimension gdim."""
    from .curve import CurveCrackModel
    from .surface import SurfaceCrackModel
    return {2: CurveCrackModel, 3: SurfaceCrackModel}[gdim]


def with_initial_stress(solution, stress: np.ndarray, points: typing.Callable[[], np.ndarray]) -> np.ndarray:
    """The total stress (n, Voigt) C eps(u) + sigma_0 from C eps(u) at n
    points (stress), the scene's initial stress at its load factor added
    (stress itself if it has none); points() gives the points (n, d), asked
    only then."""
    scene = solution.model.scene
    if scene.initial_stress is None or solution.factor(scene.initial_stress_group) == 0.0 or not len(stress):
        return stress
    return stress + solution.factor(scene.initial_stress_group) * tensor_to_voigt(
        evaluate_stress(scene.initial_stress, points(), "initial stress"))


__all__ = ["with_initial_stress", "CrackModel", "crack_model_type"]
