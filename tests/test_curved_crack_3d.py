"""K along the front of a curved crack surface (issue 39 item 2): the
spherical-cap crack under hydrostatic tension, given as a triangulation.

The cap of a sphere of radius R = sqrt(2) cut at alpha = 45 degrees (base
radius a = 1, the front a circle), nu = 0.22, tension 1 on all six faces of
a box of half-width 4, a / h_front = 6 (3.6e4 dofs, 9 front points).
Reference (cracklip.exact.spherical_cap): K_I = 0.8890 K0, K_II = 0.2453
K0, K_III = 0, K0 = 2 sigma sqrt(a / pi); the K scale |K| = 0.9222 K0.
Measured here: error vector max 1.50 %, RMS 1.10 % of the K scale (K_I
0.895-0.903 K0: the small box raises K by about 0.6 %, as for the penny in
tests/test_sif_3d.py; K_II 0.2415-0.2458 K0). Without the surface's
curvature terms (kappa_11, kappa_33, tau dropped from the auxiliary
fields, the front's kappa_f kept) the same solution gives 13.2 % (K_I
0.97-0.98 K0, K_II 0.30-0.33 K0). demos/front_sifs.py --full --cases
spherical_cap converges the case in a box of half-width 10 (docs/sifs.md).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import cracklip as cl
from cracklip.exact import spherical_cap as sc
from cracklip.fracture import front_points, sif_3d
from cracklip.scene.crack_surface import SurfaceCrack
from cracklip.scene.mesh_3d import create_box, crack_refinements

L, N = 4.0, 6
ALPHA = sc.REFERENCE_ALPHA_DEG
REF = np.array(sc.cap_k(1.0, 1.0))
SCALE = float(np.linalg.norm(REF))


def cap_scene() -> cl.Scene:
    depth = (1.0 - math.cos(math.radians(ALPHA))) / math.sin(math.radians(ALPHA))
    v, t = sc.cap_triangulation(1.0, ALPHA, 0.5 / N, pole=(0.0, 0.0, -0.5 * depth))
    crack = SurfaceCrack(v, t, name="cap")
    mesh = create_box(-L, -L, -L, L, L, L, 1.0, fronts=crack_refinements([crack], 1.0 / N, 1.0, growth=0.1))
    tractions = []
    for i, ax in enumerate("xyz"):
        e = np.zeros(3)
        e[i] = 1.0
        tractions += [cl.Traction(f"{ax}max", tuple(e)), cl.Traction(f"{ax}min", tuple(-e))]
    return cl.Scene(mesh, cl.Material(1.0, sc.REFERENCE_NU), cracks=[crack],
                    dirichlet=[cl.Dirichlet((-L, -L, -L)), cl.Dirichlet((L, -L, -L), 1),
                               cl.Dirichlet((L, -L, -L), 2), cl.Dirichlet((-L, L, -L), 2)],
                    tractions=tractions, options=cl.Options(enrichment="vector", radius=0.25, solver="iterative",
                                            sif_points=8))


def _k(rows) -> np.ndarray:
    return np.array([[r["K_I"], r["K_II"], r["K_III"]] for r in rows])


def test_cap_triangulation_and_references():
    """The triangulation lies on the sphere, its boundary is the circle of
    radius a, its normals point to the centre; the shallow-cap closed form
    is the penny's K at alpha -> 0 and the reference case is refused for
    another angle."""
    a, R = 1.0, math.sqrt(2.0)
    v, t = sc.cap_triangulation(a, ALPHA, 0.1)
    c = np.array([0.0, 0.0, R])
    assert np.allclose(np.linalg.norm(v - c, axis=1), R, atol=1e-12)
    crack = SurfaceCrack(v, t)
    b = np.unique(crack.boundary_edges())
    assert np.allclose(np.hypot(v[b, 0], v[b, 1]), a, atol=1e-12) and len(b) >= 2 * math.pi * a / 0.1 - 1
    n = np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]])
    assert np.all(np.einsum("ij,ij->i", n, c - v[t].mean(axis=1)) > 0.0)
    k0 = sc.penny_scale(1.0, a)
    assert sc.cap_k_shallow(1.0, a, 0.0, 0.3) == pytest.approx((k0, 0.0, 0.0))
    assert sc.cap_k_shallow(1.0, a, 5.0, 0.22)[1] / k0 == pytest.approx(0.027309, rel=1e-3)
    with pytest.raises(ValueError, match="alpha"):
        sc.cap_k(1.0, a, alpha_deg=30.0)


def test_spherical_cap_k_needs_the_surface_curvature():
    """K along the cap's front within 2.5 % of the K scale at every point
    (measured 0.94 %; 1.50 % with the earlier front fit), K_II within 3 % of its reference (measured 1.5 %
    low at worst) and K_III below 0.5 % of K0; with the surface's curvature
    dropped from the auxiliary fields the same solution is off by more than
    8 % (measured 13.2 % with the earlier front fit). Front points at the front elements' own spacing
    (sif_points = 8, 9 points): 16 points asked on this a/6 front make hats
    of about two elements, whose K_II scatters to 3.1 % of its reference
    (the error vector's max 1.82 %)."""
    sol = cl.solve(cap_scene())
    rows = sol.stress_intensity_factors(0)
    K = _k(rows)
    assert len(rows) >= 8 and not any(r["free_surface"] for r in rows)
    err = np.linalg.norm(K - REF, axis=1) / SCALE
    assert err.max() < 0.025, err
    assert np.abs(K[:, 1] / REF[1] - 1.0).max() < 0.03, K[:, 1] / REF[1]
    assert np.abs(K[:, 2]).max() < 0.005 * sc.penny_scale(1.0, 1.0)

    orig = sif_3d.project

    def planar_surface(*args, **kwargs):
        p = orig(*args, **kwargs)
        p["curvatures"][:, 1:] = 0.0
        return p

    sol._sif_cache.clear()
    sol._front_sifs.clear()  # (the raw front integrals are kept on the solution too)
    mp = pytest.MonkeyPatch()
    mp.setattr(sif_3d, "project", planar_surface)  # (the integral's)
    mp.setattr(front_points, "project", planar_surface)  # (the domains' radii)
    try:
        err_flat = np.linalg.norm(_k(sol.stress_intensity_factors(0)) - REF, axis=1) / SCALE
    finally:
        mp.undo()
    assert err_flat.max() > 0.08, err_flat
