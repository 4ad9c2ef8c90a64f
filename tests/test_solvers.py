"""Solver paths (issue 15): the phantom-node basis, the iterative (AMG) path
giving the direct path's answers to 1e-8 on the representative scenes
(patch test, Westergaard, block, hole, hard cases 1-5), the automatic
choice, failures reported, and the BLAS report. No timings: speed is
demos/bench_solvers.py's business."""
import dataclasses
import pathlib
import subprocess
import sys

import cracklip as cl
import numpy as np
import pytest
import scipy.sparse as sp
from cracklip.model.assembly import assemble_system
from cracklip.solvers import checked, choice, iterative, near_nullspace, phantom, saddle, schwarz, sweep_blocks
from cracklip.errors import SolverError
from cracklip.solvers.checked import blas_library, petsc_from_scipy, scipy_from_petsc
from scipy.sparse.csgraph import connected_components

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
import block_uniform_pressure as block  # noqa: E402
import hard_cases as hc  # noqa: E402
import hole_crack  # noqa: E402
import westergaard  # noqa: E402

#: The issue's bar: iterative answers equal the direct ones to this, relative.
MATCH = 1e-8


def with_solver(scene: cl.Scene, solver: str) -> cl.Scene:
    return dataclasses.replace(scene, options=dataclasses.replace(scene.options, solver=solver))


def answers(sol: cl.Solution, sif_radius: float | None) -> dict[str, np.ndarray]:
    """What a user reads off a solve: energy, SIFs at every tip, contact pressure."""
    out = {"energy": np.array([sol.strain_energy()])}
    sifs = [[k["K_I"], k["K_II"]] for ci, c in enumerate(sol.model.cracks) if np.asarray(c.geometry.tips).size
            for k in sol.stress_intensity_factors(ci, radius=sif_radius)]
    if sifs:
        out["sif"] = np.array(sifs)
    if sol.contact:
        out["pressure"] = np.concatenate([sol.contact_pressure(ci)["pressure"] for ci in range(len(sol.model.cracks))])
        out["active"] = sol.contact["active"].astype(float)
    return out


def sif_scale(sol: cl.Solution) -> float:
    """E* max|u| / sqrt(L): the size a SIF has on this scene (some exact SIFs are 0)."""
    m = sol.model
    return m.scene.material.E_star * float(np.abs(sol.standard_displacement).max()) / np.sqrt(np.ptp(m.x, axis=0).max())


def assert_same_answers(scene: cl.Scene, sif_radius: float | None = None) -> tuple[cl.Solution, cl.Solution]:
    direct = cl.solve(with_solver(scene, "direct"))
    iterative = cl.solve(with_solver(scene, "iterative"))
    assert direct.solver["solver"] == "direct" and iterative.solver["solver"] == "iterative"
    for rec in iterative.solver["solves"]:
        assert rec["solver"] == "iterative" and rec["iterations"] > 1
        assert rec["relative_residual"] <= scene.options.residual_tol
    a, b = answers(direct, sif_radius), answers(iterative, sif_radius)
    assert a.keys() == b.keys()
    assert abs(b["energy"][0] - a["energy"][0]) <= MATCH * abs(a["energy"][0])
    if "sif" in a:
        scale = max(np.abs(a["sif"]).max(), sif_scale(direct))
        assert np.abs(b["sif"] - a["sif"]).max() <= MATCH * scale, (a["sif"], b["sif"])
    if "pressure" in a:
        assert np.array_equal(a["active"], b["active"])
        assert np.abs(b["pressure"] - a["pressure"]).max() <= MATCH * np.abs(a["pressure"]).max()
    return direct, iterative


# -- the phantom-node basis --------------------------------------------------------------------------

def _through_crack_model(md):
    """A crack through the square, held at two corners on each side away from the crack."""
    pins = [md.nearest_node(p) for p in ([-1, -1], [1, -1], [-1, 1], [1, 1])]
    scene = cl.Scene(md, cl.Material(1.0, 0.3), cracks=[cl.Crack([[-1.5, 0.013], [1.5, 0.013]])],
                     dirichlet=[cl.Dirichlet(pins[0]), cl.Dirichlet(pins[1], 1), cl.Dirichlet(pins[2]),
                                cl.Dirichlet(pins[3], 1)],
                     tractions=[cl.Traction("top", (0.0, 1.0)), cl.Traction("bottom", (0.0, -1.0))],
                     options=cl.Options(enrichment="none"))
    return scene, cl.create_model(scene)


def test_phantom_basis_splits_a_through_crack(square_h01):
    """In the phantom basis a through crack leaves two uncoupled pieces (the
    graph of the matrix without its Dirichlet dofs has two components); in
    the shifted-Heaviside basis it is one. A wrong side sign couples them."""
    scene, model = _through_crack_model(square_h01)
    basis = phantom.phantom_basis(model)
    n = model.num_dofs
    assert basis.heaviside.size > 0
    assert abs(basis.T_inv @ basis.T - sp.identity(n)).max() <= 1e-15
    A, b, _ = assemble_system(model)
    free = np.setdiff1d(np.arange(n), model.bc_dofs)

    def pieces(M: sp.csr_matrix) -> int:
        M = M[free][:, free]
        strong = abs(M) > 1e-12 * abs(M).max()
        return connected_components(strong, directed=False)[0]
    K = scipy_from_petsc(A)
    assert pieces(K) == 1
    assert pieces((basis.T.T @ K @ basis.T).tocsr()) == 2
    At, bt = phantom.transform_system(basis, A, b)  # in place: A is At now
    assert At.getBlockSize() == 2
    assert pieces(scipy_from_petsc(At)) == 2
    # The row-wise update equals the full product T^T K T, and T^T b.
    KT = (basis.T.T @ K @ basis.T).tocsr()
    assert abs(scipy_from_petsc(At) - KT).max() <= 1e-14 * abs(KT).max()
    assert np.allclose(bt.array, basis.T.T @ b.array, rtol=0, atol=1e-15 * np.abs(b.array).max())
    wrong = basis.T.tolil()
    e = 2 * (model.layout.num_std_nodes + basis.heaviside)
    wrong[e, :] = -wrong[e, :]
    assert pieces((wrong.T @ K @ wrong).tocsr()) == 1
    # The near-nullspace (a rigid motion on both copies) has zero energy:
    # K' R = 0 on every row away from the pins (whose columns are eliminated).
    R = near_nullspace.rigid_modes(model)
    assert np.allclose(R.T @ R, np.eye(3), atol=1e-12)
    lay = model.layout
    node = np.concatenate([np.arange(lay.num_std_nodes), np.asarray(lay.node)]).repeat(2)
    pins = model.x[np.unique(model.bc_dofs // 2)]
    far = np.linalg.norm(model.x[node][:, None, :] - pins[None], axis=2).min(axis=1) > 0.35
    Kt = (basis.T.T @ K @ basis.T).tocsr()
    assert far.sum() > 0.8 * n
    assert np.abs((Kt @ R)[far]).max() <= 1e-12 * abs(Kt).max() * np.abs(R).max()
    assert np.abs((K @ R)[far]).max() > 1e-3 * abs(K).max() * np.abs(R).max()  # not so in the old basis
    for obj in (A, b, At, bt):
        obj.destroy()


def test_band_rings_follow_the_multipliers_in_2d_only():
    """One ring without contact; in 2D ceil(0.07 m) rings for m multipliers
    (at most MAX_BAND_RINGS), in 3D CONTACT_BAND_RINGS_3D whatever m."""
    rings = sweep_blocks.band_rings
    assert rings(2, 0) == rings(3, 0) == 1
    assert rings(2, 1) == 1 and rings(2, 15) == 2 and rings(2, 212) == 15
    assert rings(2, 10 ** 6) == sweep_blocks.MAX_BAND_RINGS
    assert rings(3, 1) == rings(3, 10 ** 6) == sweep_blocks.CONTACT_BAND_RINGS_3D


def _out_of_workspace(monkeypatch, tries: int) -> list[int]:
    """Make the first `tries` MUMPS factorisations report INFOG(1) = -9 (out
    of workspace); returns the ICNTL(14) values set, in order."""
    relaxations: list[int] = []
    real = checked.factor_call

    def fake(ksp, method, *args):
        if method == "setMumpsIcntl" and args[0] == 14:
            relaxations.append(args[1])
        out = real(ksp, method, *args)
        return -9 if method == "getMumpsInfog" and args == (1,) and len(relaxations) <= tries else out
    monkeypatch.setattr(checked, "factor_call", fake)
    return relaxations


def _spd(n: int = 60) -> sp.csr_matrix:
    return (sp.diags([-1.0, 2.5, -1.0], [-1, 0, 1], shape=(n, n)) + sp.eye(n)).tocsr()


def test_factorisation_out_of_workspace_is_retried_with_more(monkeypatch):
    """checked.factor_relaxed (solve_checked's and the crack band's
    factorisation): a factorisation out of workspace (INFOG(1) = -9) is
    factored again with ICNTL(14) 20 -> 100 -> 400, and the one that
    succeeds solves; out of workspace at 400 the band's factor_band raises
    naming it, and solve_checked names the memory it needed."""
    A = _spd()
    relaxations = _out_of_workspace(monkeypatch, 1)
    M = petsc_from_scipy(A)
    ksp, error, info = checked.factor_relaxed(M, symmetric=False)
    assert relaxations == [20, 100] and error is None and info == 0
    b, x = M.createVecs()
    b.array[:] = np.arange(A.shape[0], dtype=float)
    ksp.solve(b, x)
    assert np.abs(A @ x.array - b.array).max() <= 1e-12 * np.abs(b.array).max()
    ksp.destroy()
    relaxations = _out_of_workspace(monkeypatch, 3)
    with pytest.raises(SolverError, match=r"could not be factored.*ICNTL\(14\) = 400"):
        schwarz.factor_band(M, symmetric=False)
    assert relaxations == list(checked.WORKSPACE_RELAXATIONS) == [20, 100, 400]
    relaxations = _out_of_workspace(monkeypatch, 3)
    with pytest.raises(SolverError, match="ran out of memory"):
        checked.solve_checked(M, b, what="test system")
    assert relaxations == [20, 100, 400]
    for obj in (M, b, x):
        obj.destroy()


def test_crack_band_holds_every_enriched_dof_and_a_ring(square_h01):
    scene = block.scene_for(10)
    model = cl.create_model(scene)
    band = sweep_blocks.crack_band(model)
    lay = model.layout
    nstd = lay.num_std_nodes
    assert np.array_equal(band[band >= 2 * nstd], np.arange(2 * nstd, model.num_dofs))
    enriched = np.unique(np.asarray(lay.node))
    std_nodes = np.unique(band[band < 2 * nstd] // 2)
    assert set(enriched.tolist()) < set(std_nodes.tolist())
    # Exactly the enriched nodes and their neighbours through a cell.
    touching = model.cells[np.isin(model.cells, enriched).any(axis=1)]
    assert np.array_equal(std_nodes, np.unique(touching))
    # Grown by rings through the stiffness's graph: the next ring of cells.
    from cracklip.model.assembly import assemble_system
    A, b, _ = assemble_system(model)
    wider = sweep_blocks.grow_band(A, band, 1)
    nodes2 = np.unique(wider[wider < 2 * nstd] // 2)
    ring2 = np.unique(model.cells[np.isin(model.cells, std_nodes).any(axis=1)])
    assert np.array_equal(nodes2, ring2)
    assert np.array_equal(wider, sweep_blocks.crack_band(model, rings=2))
    A.destroy()
    b.destroy()


# -- the iterative path gives the direct path's answers ----------------------------------------------

def test_patch_test_iterative(square_h01):
    from test_patch import YC, check_through_crack, through_crack_scene
    scene, exact = through_crack_scene(square_h01, YC, cl.Material(2.0, 0.3), 0.7)
    d, it = assert_same_answers(scene)
    check_through_crack(d, exact, YC, 1e-10)
    # The iterative path stops at a relative residual of KRYLOV_RTOL = 1e-10,
    # so it is exact to the bar (1e-8), not to the direct path's 1e-10.
    check_through_crack(it, exact, YC, MATCH)
    assert it.solver["solves"][0]["method"].startswith("CG + ")  # the stiffness alone is SPD: CG


def test_westergaard_iterative():
    scene, _ = westergaard.scene_for(20)
    d, it = assert_same_answers(scene)
    assert it.solver["solves"][0]["band"] > 0  # tip dofs: the Schwarz path
    assert abs(it.stress_intensity_factors(0)[0]["K_I"] - 1.0) < 0.02


@pytest.mark.parametrize("contact", ["bilateral", "unilateral"])
def test_block_iterative(contact):
    d, it = assert_same_answers(block.scene_for(20, contact=contact))
    # CG on the saddle point (the band's exact solve keeps the constraints).
    assert all(s["method"].startswith("CG + ") for s in it.solver["solves"])
    p = it.contact_pressure(0)["pressure"]
    assert np.abs(p - block.PRESSURE).max() <= 0.03 * block.PRESSURE


def test_hole_iterative():
    d, it = assert_same_answers(hole_crack.scene_for(0.25))
    assert it.contact["iterations"] == d.contact["iterations"]


@pytest.mark.parametrize("key", ["1", "2", "3", "4", "5"])
def test_hard_cases_iterative(key):
    case = hc.CASE_BY_KEY[key]
    built = hc._bind(case, case.n0_small)(case.n0_small)
    d, it = assert_same_answers(built.scene, built.sif_radius)
    if built.quantities is not None:
        qd, qi = np.asarray(built.quantities(d)), np.asarray(built.quantities(it))
        assert np.abs(qi - qd).max() <= MATCH * np.abs(qd).max()


def small_penny(solver: str) -> cl.Scene:
    """A penny of radius 1 at a/h = 12 with the geometric enrichment radius
    0.25 a (3 front elements: 26 % of the band's dofs lie beyond 2 of them)
    in a box of half side 1.5: 4.8e4 dofs."""
    from cracklip.scene.crack_surface import EllipticalCrack
    from cracklip.scene.mesh_3d import create_box, crack_refinements
    L = 1.5
    crack = EllipticalCrack((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 1.0, axis=(0.0, 1.0, 0.0), name="penny")
    mesh = create_box(-L, -L, -L, L, L, L, 0.5, fronts=crack_refinements([crack], 1.0 / 12, 0.5, growth=0.1))
    return cl.Scene(mesh, cl.Material(1.0, 0.3), cracks=[crack],
                    dirichlet=[cl.Dirichlet((-L, -L, -L)), cl.Dirichlet((L, -L, -L), 1),
                               cl.Dirichlet((L, -L, -L), 2), cl.Dirichlet((-L, L, -L), 2)],
                    tractions=[cl.Traction("zmax", (0.0, 0.0, 1.0)), cl.Traction("zmin", (0.0, 0.0, -1.0))],
                    options=cl.Options(enrichment="vector", radius=0.25, solver=solver, sif_points=8))


def test_gamg_leaves_the_tip_dofs_out_in_3d():
    """3D (TIP_DOFS_OUT_OF_GAMG): GAMG's operator is the transformed
    stiffness K' on the dofs that are not tip dofs, exactly its rows and
    columns (no stored zeros, no isolated tip rows), in whole nodes (block
    size 3, as GAMG aggregates them); every tip dof is held by the exact band
    or the outer block, so the sweep stays a symmetric Schwarz method (the
    answers: test_outer_torus_block_gives_the_direct_answers)."""
    model = cl.create_model(small_penny("iterative"))
    A, _, _ = assemble_system(model)
    it = iterative.IterativeSolver(model)
    K, _ = it.transform(A)
    amg, _ = it._block0_pc(K)
    tip = sweep_blocks.tip_dofs(model)
    keep = np.setdiff1d(np.arange(it.n), tip)
    assert tip.size > 1000 and np.array_equal(it._block0, keep)
    Kg = amg.getOperators()[0]
    assert Kg.getSize() == (keep.size, keep.size) and Kg.getBlockSize() == 3 and it._n_amg == keep.size
    Ks = scipy_from_petsc(K).tocsr()
    ref = Ks[keep][:, keep]
    got = scipy_from_petsc(Kg)
    assert abs(got - ref).max() == 0.0 and got.nnz == ref.nnz
    assert np.isin(tip, np.union1d(it._band_inner, it._outer)).all()
    it.destroy()


def test_outer_torus_block_gives_the_direct_answers():
    """3D, enrichment radius 0.25 a: the front-enriched nodes farther than
    INNER_BAND_RADIUS_H front elements from the front leave the exact band
    for the sweep's inexact block; energy and K_I, K_II, K_III along the
    front equal the direct path's to 1e-8, and CG needs no more than a few
    iterations more than with the whole band exact (measured: 27 against
    26; band 9 882 dofs instead of 19 764, outer block 15 036 with its
    nodes' standard dofs)."""
    direct = cl.solve(small_penny("direct"))
    split = cl.solve(small_penny("iterative"))
    rec = split.solver["solves"][-1]
    assert rec["outer"] > 0 and rec["band"] > 0
    whole = sweep_blocks.crack_band(split.model, sweep_blocks.BAND_RINGS[3])
    assert rec["band"] < whole.size < rec["band"] + rec["outer"]  # (they overlap)
    outer = sweep_blocks.outer_torus(split.model, sweep_blocks.OUTER_FROM_H, sweep_blocks.OUTER_WITH_STANDARD)
    assert rec["outer"] == outer.size
    assert rec["amg_dofs"] == rec["size"] - sweep_blocks.tip_dofs(split.model).size  # (TIP_DOFS_OUT_OF_GAMG)
    assert rec["relative_residual"] <= split.model.scene.options.residual_tol
    assert rec["iterations"] <= 30
    assert abs(split.strain_energy() - direct.strain_energy()) <= MATCH * abs(direct.strain_energy())
    K = [np.array([[r["K_I"], r["K_II"], r["K_III"]] for r in s.stress_intensity_factors(0)]) for s in (direct, split)]
    assert np.abs(K[1] - K[0]).max() <= MATCH * np.abs(K[0]).max(), K


def test_friction_load_path_iterative():
    """Friction and load paths take Options.solver too: the shipped
    frictional scene (clamp, shear up, shear removed) gives every step's
    direct answers, friction states and slip included, by GMRES on the
    unsymmetric saddle point."""
    sf = cl.load_scene_file(pathlib.Path(__file__).resolve().parents[1] / "demos" / "scenes" / "frictional_crack.toml")
    direct = cl.solve(with_solver(sf.scene, "direct"))
    iterative = cl.solve(with_solver(sf.scene, "iterative"))
    assert direct.solver["solver"] == "direct" and iterative.solver["solver"] == "iterative"
    recs = iterative.solver["solves"]
    assert recs and all(r["solver"] == "iterative" and r["method"].startswith("GMRES") for r in recs)
    # The friction iteration's inexact inner solves (contact/friction.py
    # INEXACT_RTOL) are checked at their own tolerance; every solve to
    # KRYLOV_RTOL, each step's last among them, at residual_tol.
    from cracklip.solvers.iterative import KRYLOV_RTOL
    tol = sf.scene.options.residual_tol
    assert all(r["relative_residual"] <= (tol if r["rtol"] == KRYLOV_RTOL else 10 * r["rtol"]) for r in recs)
    assert all(r["relative_residual"] <= tol for r in recs if r["rtol"] == KRYLOV_RTOL)
    assert recs[-1]["rtol"] == KRYLOV_RTOL
    for step in iterative.steps:
        assert step.solver["solves"][-1]["rtol"] == KRYLOV_RTOL
    assert len(direct.steps) == len(iterative.steps) == 3
    for d, it in zip(direct.steps, iterative.steps):
        a, b = answers(d, None), answers(it, None)
        assert abs(b["energy"][0] - a["energy"][0]) <= MATCH * abs(a["energy"][0])
        scale = max(np.abs(a["sif"]).max(), sif_scale(d))
        assert np.abs(b["sif"] - a["sif"]).max() <= MATCH * scale
        pd, pi = d.contact_pressure(0), it.contact_pressure(0)
        assert list(pd["state"]) == list(pi["state"])
        top = max(np.abs(pd["pressure"]).max(), 1e-300)
        for key in ("pressure", "shear"):
            assert np.abs(pi[key] - pd[key]).max() <= MATCH * top, key
        # (0 to round-off while the crack sticks: the displacement sets the scale)
        u_scale = max(np.abs(pd["slip"]).max(), float(np.abs(d.standard_displacement).max()))
        assert np.abs(pi["slip"] - pd["slip"]).max() <= MATCH * u_scale


def test_load_path_with_nodal_rescaling_without_contact():
    """A load path without contact solves the rescaled system when
    rescale = "nodal" (it used to solve the unscaled matrix with the
    rescaled load: K_I 0.408 instead of 1.0008 on Westergaard), and the
    phantom-basis system on the iterative path."""
    sc = dataclasses.replace(westergaard.scene_for(20)[0], load_path=[cl.LoadStep({"default": 0.5}), cl.LoadStep({"default": 1.0})])
    k = {}
    for rescale, solver in (("none", "direct"), ("nodal", "direct"), ("none", "iterative")):
        sol = cl.solve(dataclasses.replace(sc, options=dataclasses.replace(sc.options, rescale=rescale, solver=solver)))
        assert sol.solver["solver"] == solver
        k[rescale, solver] = np.array([[r["K_I"], r["K_II"]] for r in sol.stress_intensity_factors()])
        assert [s.step["factors"]["default"] for s in sol.steps] == [0.5, 1.0]
    assert abs(k["none", "direct"][0, 0] - 1.0) < 0.01
    assert np.abs(k["nodal", "direct"] - k["none", "direct"]).max() <= 1e-8
    assert np.abs(k["none", "iterative"] - k["none", "direct"]).max() <= MATCH


def test_active_set_reuses_the_amg_hierarchy():
    """Open-closed-open contact needs several active sets: every saddle solve
    after the first reuses block 0's GAMG hierarchy, and only the band
    (which holds all multipliers) is factored again."""
    scene = hc.open_closed_open_scene(20)
    d, it = assert_same_answers(scene)
    solves = it.solver["solves"]
    assert len(solves) == it.contact["iterations"] >= 3
    assert [s["setup_reused"] for s in solves] == [False] + [True] * (len(solves) - 1)
    nmult = it.contact["system"].num_multipliers
    assert all(s["band"] > nmult and s["size"] == it.model.num_dofs + nmult for s in solves)


def clamped_square_contact_model(n: int) -> "cl.XfemModel":
    """The solver benchmark's bilateral-contact scene (demos/bench_solvers.py)
    on an n x n structured square: interior crack, bottom clamped, top pressed."""
    return cl.create_model(cl.Scene(hc.structured_square(n), cl.Material(1.0, 0.3),
                                    cracks=[cl.Crack([[-0.3, 0.0123], [0.3, 0.0123]])],
                                    dirichlet=[cl.Dirichlet("bottom")], tractions=[cl.Traction("top", (0.0, -1.0))],
                                    options=cl.Options(contact="bilateral", enrichment="vector", radius=0.0)))


def test_constrained_coarse_solve_is_the_constrained_minimiser():
    """GAMG's coarsest solve, constrained by the multipliers: its output
    minimises the coarse energy under C y = 0 (the KKT system's answer), it
    is symmetric (CG needs a symmetric V-cycle), and clear() restores the
    plain coarse solve."""
    from cracklip.contact.frictionless import create_contact_system
    model = clamped_square_contact_model(100)  # three levels, a nonsingular coarse operator
    A, _, _ = assemble_system(model)
    it = iterative.IterativeSolver(model)
    K, T = it.transform(A)
    amg, _ = it._block0_pc(K)
    coarse = it._coarse
    Ac = scipy_from_petsc(coarse.Ac).toarray()
    nc = Ac.shape[0]
    B = (create_contact_system(model).B @ T).tocsr()
    op = saddle.SaddleOperator(K, B, np.ones(B.shape[0], bool))
    coarse.constrain(op.Ba_petsc)
    assert amg.getMGLevels() >= 2 and 0 < coarse.rank < nc
    rng = np.random.default_rng(0)
    r, s = rng.standard_normal(nc), rng.standard_normal(nc)

    def apply(v):
        x, y = coarse.Ac.createVecs()
        x.array[:] = v
        coarse.apply(None, x, y)
        return y.array.copy()
    y = apply(r)
    C = coarse.C
    kkt = np.block([[Ac, C.T], [C, np.zeros((coarse.rank, coarse.rank))]])
    ref = np.linalg.solve(kkt, np.concatenate([r, np.zeros(coarse.rank)]))[:nc]
    assert np.abs(C @ y).max() <= 1e-10 * np.abs(y).max()
    assert np.abs(y - ref).max() <= 1e-8 * np.abs(ref).max()
    assert abs(s @ y - r @ apply(s)) <= 1e-10 * abs(s @ y)
    coarse.clear()
    y0 = apply(r)
    assert np.abs(C @ y0).max() > 1e-3 * np.abs(y0).max()
    assert np.abs(y0 - np.linalg.solve(Ac, r)).max() <= 1e-8 * np.abs(y0).max()
    op.destroy(None)
    it.destroy()


def test_iterative_solves_release_the_stiffness():
    """After an iterative solve (stiffness, then a contact saddle point) and
    destroy(), nothing in PETSc holds the stiffness any more: a PC wrapper
    alive across ksp.destroy(), or PETSc objects held by a Python PC's
    context, kept K' and its hierarchy (0.2-0.4 GB per solve at 1e6 dofs)."""
    from cracklip.contact.frictionless import create_contact_system
    model = clamped_square_contact_model(60)
    A, b, _ = assemble_system(model)
    it = iterative.IterativeSolver(model)
    K, T = it.transform(A)
    b.array[:] = T.T @ b.array
    it.solve(K, b, 1e-8, what="stiffness").destroy()
    B = (create_contact_system(model).B @ T).tocsr()
    S = it.saddle_matrix(K, B, np.ones(B.shape[0], bool))
    rhs = S.createVecRight()
    rhs.array[:K.getSize()[0]] = b.array
    it.solve(S, rhs, 1e-8, what="saddle").destroy()
    S.destroy()
    it.destroy()
    assert K.getRefCount() == 1


# -- choice, failures, reporting ---------------------------------------------------------------------

def test_auto_choice_by_size():
    opts = cl.Options()
    assert opts.solver == "auto"
    n0 = choice.AUTO_ITERATIVE_DOFS  # a tip-enrichment disk of 3 % of the dofs: iterative from n0 on
    assert choice.choose_solver(opts, n0 - 1, int(0.03 * n0)) == "direct"
    assert choice.choose_solver(opts, n0, int(0.03 * n0)) == "iterative"
    n = 10 ** 6  # few enriched dofs (a small crack): MUMPS is faster, up to AUTO_DIRECT_MAX_DOFS
    assert choice.choose_solver(opts, n, int(choice.AUTO_MIN_ENRICHED_FRACTION * n) - 1) == "direct"
    assert choice.choose_solver(opts, n, int(choice.AUTO_MIN_ENRICHED_FRACTION * n)) == "iterative"
    assert choice.choose_solver(opts, n, int(choice.AUTO_MAX_ENRICHED_FRACTION * n)) == "iterative"
    assert choice.choose_solver(opts, n, int(choice.AUTO_MAX_ENRICHED_FRACTION * n) + 1) == "direct"
    big = choice.AUTO_DIRECT_MAX_DOFS  # the direct path's memory: iterative whatever the enrichment
    assert choice.choose_solver(opts, big - 1, 0) == "direct"
    assert choice.choose_solver(opts, big, 0) == choice.choose_solver(opts, big, big // 4) == "iterative"
    assert choice.choose_solver(cl.Options(solver="direct"), 10 ** 8) == "direct"
    assert choice.choose_solver(cl.Options(solver="iterative"), 10) == "iterative"
    assert choice.choose_solver(cl.Options(rescale="nodal"), 10 ** 8) == "direct"
    with pytest.raises(cl.InputError, match="rescale = 'nodal'.*solver = 'iterative'"):
        choice.choose_solver(cl.Options(solver="iterative", rescale="nodal"), 10)
    with pytest.raises(cl.InputError, match="solver must be one of"):
        cl.Options(solver="amg")


def test_iterative_reports_a_singular_saddle_point_system():
    """Naive P1 multipliers: B loses rank and the saddle-point system is
    singular. The iterative path must not return a solution either: the
    naive space's active constraints are checked for rank before either path
    solves (the message then names the multiplier space)."""
    scene = with_solver(block.scene_for(10, enrichment="vector", multipliers="naive"), "iterative")
    with pytest.raises(cl.SolverError, match="singular"):
        cl.solve(scene)


def test_auto_falls_back_to_direct(monkeypatch):
    """solver = "auto" on a large system takes the iterative path; if that
    fails (here: an iteration limit of 3) the same system is solved by MUMPS
    and the answer is the direct one; solver = "iterative" raises instead."""
    scene = block.scene_for(10, contact="bilateral")
    direct = cl.solve(with_solver(scene, "direct"))
    monkeypatch.setattr(choice, "AUTO_ITERATIVE_DOFS", 0)
    monkeypatch.setattr(choice, "AUTO_MIN_ENRICHED_FRACTION", 0.0)
    monkeypatch.setattr(choice, "AUTO_MAX_ENRICHED_FRACTION", 1.0)
    monkeypatch.setattr(iterative, "MAX_ITERATIONS", 3)
    sol = cl.solve(scene)
    assert [(s["solver"], s["iterations"]) for s in sol.solver["solves"]] == [("iterative", 3), ("direct", 1)]
    assert sol.solver["solves"][0]["relative_residual"] > scene.options.residual_tol
    p0, p1 = direct.contact_pressure(0)["pressure"], sol.contact_pressure(0)["pressure"]
    assert np.abs(p1 - p0).max() <= MATCH * np.abs(p0).max()
    with pytest.raises(cl.SolverError, match=r"inaccurate.*after 3 iterations.*iteration limit.*solver = 'direct'"):
        cl.solve(with_solver(scene, "iterative"))


def test_direct_records_ldlt():
    sol = cl.solve(block.scene_for(10))
    rec = sol.solver["solves"]
    assert sol.solver["solver"] == "direct"
    assert [r["method"] for r in rec] == ["MUMPS LDL^T"] and rec[0]["iterations"] == 1


def test_blas_is_reported():
    from cracklip.io.outputs import versions
    blas = blas_library()
    assert blas.startswith(("openblas", "reference", "mkl", "blis", "atlas"))
    assert versions()["blas"] == blas


def test_saddle_matrix_equals_the_block_matrix():
    """contact.saddle_matrix builds [K B_a^T; B_a D] from CSR arrays; it must
    equal scipy's block product for any active set."""
    from cracklip.solvers.saddle import saddle_matrix
    n, m = 60, 9
    K = sp.random(n, n, 0.2, random_state=1, format="csr")
    K = (K + K.T).tocsr()
    B = sp.random(m, n, 0.3, random_state=2, format="csr")
    rng = np.random.default_rng(3)
    for active in (np.ones(m, bool), np.zeros(m, bool), rng.random(m) > 0.5):
        Da = sp.diags(active.astype(float))
        ref = sp.bmat([[K, (Da @ B).T], [Da @ B, sp.diags((~active).astype(float))]], format="csr")
        S = scipy_from_petsc(saddle_matrix(K, B, active))
        assert S.shape == ref.shape and abs(S - ref).max() == 0.0


def test_iterative_saddle_operator_equals_the_block_matrix():
    """The iterative path applies [K B_a^T; B_a D] block by block around K
    (no copy); its products, its assembled copy (the MUMPS fallback) and the
    band's blocks (the Schwarz sweep's) must equal the block matrix's."""
    from cracklip.solvers.checked import petsc_from_scipy
    n, m = 60, 9
    K = sp.random(n, n, 0.2, random_state=1, format="csr")
    K = (K + K.T).tocsr()
    B = sp.random(m, n, 0.3, random_state=2, format="csr")
    rng = np.random.default_rng(3)
    band = np.sort(np.concatenate([rng.choice(n, 20, replace=False), n + np.arange(m)]))
    for active in (np.ones(m, bool), np.zeros(m, bool), rng.random(m) > 0.5):
        Da = sp.diags(active.astype(float))
        ref = sp.bmat([[K, (Da @ B).T], [Da @ B, sp.diags((~active).astype(float))]], format="csr")
        op = saddle.SaddleOperator(petsc_from_scipy(K), B, active)
        A = iterative.IterativeSolver.saddle_matrix(None, op.K, B, active)
        x = rng.standard_normal(n + m)
        xv, yv = (A.createVecRight() for _ in range(2))
        xv.array[:] = x
        A.mult(xv, yv)
        assert np.abs(yv.array - ref @ x).max() <= 1e-13 * np.abs(ref @ x).max()
        assert abs(scipy_from_petsc(op.assembled()) - ref).max() == 0.0
        A1, A01, A11 = (scipy_from_petsc(M) for M in op.band_blocks(band))
        assert abs(A1 - ref[band]).max() == 0.0 and A1.shape == (band.size, n + m)
        assert abs(A01 - ref[:n][:, band]).max() == 0.0
        assert abs(A11 - ref[band][:, band]).max() == 0.0


def test_bench_solvers_demo_tiny(tmp_path):
    """The benchmark at a tiny size: one row per solver with the table's keys,
    the X-FEM rows against plain GAMG, the untuned row on the reference BLAS."""
    import json
    import subprocess
    out = tmp_path / "bench.json"
    demo = pathlib.Path(__file__).resolve().parents[1] / "demos" / "bench_solvers.py"
    subprocess.run([sys.executable, str(demo), "--sizes", "3e3", "--repeats", "1", "--cases", "open",
                    "--untuned", "--json", str(out), "--quiet"], check=True, timeout=300)
    doc = json.loads(out.read_text())
    rows = {r["solver"]: r for r in doc["rows"]}
    assert set(rows) == {"plain-gamg", "plain-mumps", "xfem-direct", "xfem-iterative",
                         "xfem-direct-untuned (netlib BLAS, LU)"}
    for r in rows.values():
        assert r["status"] == "ok"
        assert {"case", "ndofs", "solver", "t_solve", "t_total", "iterations", "peak_rss_gb"} <= r.keys()
        assert r["t_solve"] > 0 and 0 < r["peak_rss_gb"] < 24
    for s in ("xfem-direct", "xfem-iterative"):
        assert rows[s]["ratio_to_plain_gamg"] == pytest.approx(rows[s]["t_solve"] / rows[s]["t_plain_gamg"])
    assert rows["xfem-iterative"]["iterations"] > 1 and rows["xfem-direct"]["iterations"] == 1
    assert rows["xfem-direct-untuned (netlib BLAS, LU)"]["blas"].startswith("reference")
    assert rows["xfem-direct-untuned (netlib BLAS, LU)"]["method"] == "MUMPS LU"
    assert rows["xfem-direct"]["method"] == "MUMPS LDL^T"
    assert doc["auto_choice"][0]["auto"] == "direct"
    assert (tmp_path / "bench.png").stat().st_size > 0
    table = subprocess.run([sys.executable, str(demo), "--table", str(out)], check=True, timeout=60,
                           capture_output=True, text=True).stdout.splitlines()
    assert table[0].startswith("| case | dofs |") and len(table) == 3
    assert table[2].startswith(f"| open | {rows['xfem-direct']['ndofs']} |")


def test_openblas_runs_on_one_thread_after_import():
    """Importing the checked solves limits OpenBLAS to one thread (its
    module-level limit_blas_threads(): a second thread does not speed MUMPS
    up on two cores and changed results at round-off, which the unstable DCB
    growth path amplified to 5e-4 when the call was lost in a move)."""
    import os
    code = ("import ctypes, cracklip.solvers.checked as c; "
            "libs = c._mapped_libraries('libopenblas'); "
            "print(ctypes.CDLL(libs[0]).openblas_get_num_threads() if libs else 'none')")
    env = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS")}
    env["PYTHONPATH"] = str(pathlib.Path(__file__).resolve().parents[1] / "python")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env).stdout
    assert out.strip() in ("1", "none")


def test_phantom_transform_in_place_checked_for_symmetry(monkeypatch, caplog):
    """The in-place phantom transform (solvers/phantom.py) is checked for
    symmetry before it is used (changed_symmetric): right, it equals PtAP
    to round-off and is kept in A's storage; with one changed row dropped
    (the distributed transform's old mistake: a row coupled to a Heaviside
    dof left as it was) the check sees it, takes the change back and the
    result is PtAP's T^T A T all the same, with a warning."""
    from cracklip.solvers import phantom
    model = clamped_square_contact_model(12)
    basis = phantom.phantom_basis(model)
    A, _, _ = assemble_system(model)
    Tp = basis.petsc()
    ref = scipy_from_petsc(A.PtAP(Tp))
    Tp.destroy()
    scale = abs(ref).max()
    A1 = A.duplicate(copy=True)
    right = phantom.transform_matrix(basis, A1)
    assert right is A1 and abs(scipy_from_petsc(right) - ref).max() <= 1e-13 * scale
    change = phantom.phantom_change

    def dropped(S, ST, R, J, T_JJ):  # the row off J with the largest change left as it was
        delta, order, fits = change(S, ST, R, J, T_JJ)
        off = ~np.isin(order, J)
        k = int(np.flatnonzero(off)[np.argmax(abs(delta[np.flatnonzero(off)]).max(axis=1).toarray().ravel())])
        delta = delta.tolil()
        delta[k, :] = 0.0
        return delta.tocsr(), order, fits
    monkeypatch.setattr(phantom, "phantom_change", dropped)
    A2 = A.duplicate(copy=True)
    with caplog.at_level("WARNING", logger="cracklip.solvers.phantom"):
        wrong = phantom.transform_matrix(basis, A2)
    assert wrong is not A2 and "not symmetric" in caplog.text
    assert abs(scipy_from_petsc(wrong) - ref).max() <= 1e-13 * scale
    assert abs(scipy_from_petsc(A2) - scipy_from_petsc(A)).max() <= 1e-14 * scale  # (the change taken back)
