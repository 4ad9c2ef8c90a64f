"""The friction iteration's inexact inner solves (contact/friction.py
INEXACT_RTOL) change nothing but the work: on the iterative path the
closed penny of demos/contact_3d.py (uniaxial compression at 30 degrees,
mu = 0.3: every multiplier slips) ends on the same states, slip
directions, multipliers and K along the front with loose early solves as
with every solve to KRYLOV_RTOL, and as on the direct path; and the
iterative path's bordered operator (no copy of the stiffness) is the
saddle point the direct path assembles."""
import pathlib
import sys

import numpy as np
import pytest
import scipy.sparse as sp

import cracklip as cl
from cracklip.contact import friction
from cracklip.solvers import iterative, saddle
from cracklip.solvers.checked import petsc_from_scipy, scipy_from_petsc

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))


def _penny(solver: str, n: int, stabilization: float | None = None) -> cl.Scene:
    import contact_3d
    scene = contact_3d.build("beta30_mu0.3", n, solver=solver, radius=2.0 / n)
    scene.options.multiplier_stabilization = stabilization
    return scene


def _answers(sol: cl.Solution) -> dict:
    rows = sol.stress_intensity_factors(0)
    c = sol.contact
    return {"K": np.array([[r["K_I"], r["K_II"], r["K_III"]] for r in rows]), "state": c["state"].copy(),
            "sign": np.asarray(c["sign"]).copy(), "lambda": np.concatenate([c["lambda"], c["lambda_t"]]),
            "solves": sol.solver["solves"], "note": c.get("note")}


@pytest.mark.slow
@pytest.mark.parametrize("n, cycles, stabilization", [(4, False, None), (7, False, None), (7, True, 0.0)])
def test_inexact_friction_iteration_keeps_the_answer(monkeypatch, n, cycles, stabilization):
    """K (every component at every front point) equal to 1e-8 of the
    largest |K|, multipliers to 1e-8 of the largest, the same states and
    slip directions to friction.DIRECTION_TOLERANCE: loose early solves
    (the default) against exact ones (INEXACT_RTOL = None) and the direct
    path. The loose run did solve loosely (a Krylov tolerance above
    KRYLOV_RTOL) and ended on a solve to KRYLOV_RTOL whose residual passed
    the check. a / h = 4 settles (every multiplier slips); at a / h = 7 one
    multiplier at the Coulomb limit flips between stick and slip and the
    iteration takes the cycle's iterate of least violation, which is not a
    fixed point: the inexact iteration, meeting the cycle, starts again
    with exact solves and takes the same iterate (before that it took
    another, 2e-4 away in the multipliers). That cycle is a fact of the
    unstabilized multipliers (options.multiplier_stabilization = 0: the
    pressure's checkerboard put one multiplier at the limit); with the 3D
    default stabilization (contact/stabilization.py) a / h = 7 settles too."""
    default = friction.INEXACT_RTOL
    loose = _answers(cl.solve(_penny("iterative", n, stabilization)))
    monkeypatch.setattr(friction, "INEXACT_RTOL", None)
    exact = _answers(cl.solve(_penny("iterative", n, stabilization)))
    direct = _answers(cl.solve(_penny("direct", n, stabilization)))
    assert all((a["note"] is not None) == cycles for a in (loose, exact, direct)), loose["note"]
    rtols = [s["rtol"] for s in loose["solves"]]
    assert rtols[0] == default and rtols[0] > 1e3 * iterative.KRYLOV_RTOL, rtols
    assert rtols[-1] == iterative.KRYLOV_RTOL, rtols
    assert all(s["rtol"] == iterative.KRYLOV_RTOL for s in exact["solves"])
    assert loose["solves"][-1]["relative_residual"] <= cl.Options().residual_tol
    # The penny slips (mu = 0.3 < tan 30 degrees).
    assert np.count_nonzero(direct["state"] == friction.SLIP) >= direct["state"].size - 1
    for other in (exact, direct):
        assert np.array_equal(loose["state"], other["state"])
        assert np.abs(loose["sign"] - other["sign"]).max() <= 10 * friction.DIRECTION_TOLERANCE
        scale = np.abs(other["K"]).max()
        assert np.abs(loose["K"] - other["K"]).max() <= 1e-8 * scale
        assert np.abs(loose["lambda"] - other["lambda"]).max() <= 1e-8 * np.abs(other["lambda"]).max()
    # The last Newton turns of the slip directions (every multiplier's rows
    # change by < STALE_CHANGE) are preconditioned by the kept band's
    # factorisation (solvers/band_update.py), and the answer is still the
    # direct path's (above).
    assert cycles or any(s.get("band_stale") for s in loose["solves"]), [s.get("band_stale") for s in loose["solves"]]
    # Fewer Krylov iterations in all where it settles (the reason for the loose solves).
    its = lambda a: sum(s["iterations"] for s in a["solves"])  # noqa: E731
    assert cycles or its(loose) < its(exact), (its(loose), its(exact))


def test_bordered_operator_equals_the_block_matrix():
    """Friction's [K C^T; rows] applied block by block around K: its
    products (and transposed products), its assembled copy (the MUMPS
    fallback) and the band's blocks (the Schwarz sweep's) equal the block
    matrix's."""
    n, m = 50, 12
    K = sp.random(n, n, 0.2, random_state=1, format="csr")
    K = (K + K.T).tocsr()
    C = sp.random(m, n, 0.3, random_state=2, format="csr")
    rows = sp.random(m, n + m, 0.3, random_state=4, format="csr")
    ref = sp.vstack([sp.hstack([K, C.T]), rows], format="csr")
    rng = np.random.default_rng(3)
    band = np.sort(np.concatenate([rng.choice(n, 15, replace=False), n + np.arange(m)]))
    op = saddle.BorderedOperator(petsc_from_scipy(K), C, rows, C[:4])
    A = iterative.IterativeSolver.bordered_matrix(None, op.K, C, rows, C[:4])
    x = rng.standard_normal(n + m)
    xv, yv = (A.createVecRight() for _ in range(2))
    xv.array[:] = x
    A.mult(xv, yv)
    assert np.abs(yv.array - ref @ x).max() <= 1e-13 * np.abs(ref @ x).max()
    A.multTranspose(xv, yv)
    assert np.abs(yv.array - ref.T @ x).max() <= 1e-13 * np.abs(ref.T @ x).max()
    assert abs(scipy_from_petsc(op.assembled()) - ref).max() == 0.0
    A1, A01, A11 = (scipy_from_petsc(M) for M in op.band_blocks(band))
    assert abs(A1 - ref[band]).max() == 0.0 and A1.shape == (band.size, n + m)
    assert abs(A01 - ref[:n][:, band]).max() == 0.0
    assert abs(A11 - ref[band][:, band]).max() == 0.0
