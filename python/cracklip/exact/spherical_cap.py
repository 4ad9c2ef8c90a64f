"""The spherical-cap ("lens") crack under hydrostatic tension: the curved
crack surface with a reference K (issue 39).

The crack is the cap of a sphere of radius R cut by a plane at the polar
angle alpha from the cap's pole: its front is a circle of radius a = R sin
alpha (the cap's base radius). A hydrostatic tension sigma in an infinite
body (or, the same K, a pressure sigma on both lips of an unloaded one)
gives K_I, K_II constant along the front and K_III = 0. It is the only
non-planar crack with an exact solution (P. A. Martin, The spherical-cap
crack revisited, Int. J. Solids Struct. 38 (2001) 4759-4776); its series
are not evaluated here. References used instead:

- an axisymmetric P2 finite-element computation (research note
  curved_crack_and_estimate.md section 1.3, rerun for issue 39: meridian
  half-disc of radius 40 a and 80 a, tip elements 1e-4 a to 5e-5 a, P2 and
  P3, K from the crack-opening jump extrapolated to the front and, as a
  second extraction, from the stresses ahead of it): at alpha = 45 deg and
  nu = 0.22, K_I = 0.8890 K0 and K_II = 0.2453 K0 (+- 0.0003 over meshes,
  outer radii, degrees and the two extractions), K0 = 2 sigma sqrt(a / pi)
  (the penny's K_I);
- a first-order closed form (same note, section 1.2) for shallow caps,
  K_II / K0 = (1 + 4 nu) sin(alpha) / 6, K_I / K0 = 1 + O(alpha^2), which
  the same finite-element model meets within 0.1 % at alpha = 2 and 5 deg
  (K_II / K0 = 0.01094 and 0.02731 against 0.010936 and 0.027309).

code_aster's benchmark SSLV155 (V3.04.155, after Pereira, Duarte, Duarte,
Guoy, Jiao, IJNME 77 (2009) 601-633) gives K_I = 0.877 K0 and K_II = 0.235
K0 for this case: 1.35 % and 4.2 % below the computation above (no Poisson
ratio reconciles both); the tests use the computation.

Convention (cracklip's front frame): e1 out of the crack in the surface,
e2 the surface's normal toward the sphere's centre (the concave side, the +
side of the triangulation below), e3 = e1 x e2; K_II > 0 when the concave
side's lip moves along +e1 relative to the other: here K_II > 0.
"""
from __future__ import annotations

import math

import numpy as np

#: K / K0 of the cap at alpha = 45 deg, nu = 0.22 (module doc).
REFERENCE_ALPHA_DEG = 45.0
REFERENCE_NU = 0.22
REFERENCE_K_I = 0.8890
REFERENCE_K_II = 0.2453
#: SSLV155's published values at the same case, for comparison.
SSLV155_K_I = 0.877
SSLV155_K_II = 0.235


def penny_scale(sigma: float, a: float) -> float:
    """K0 = 2 sigma sqrt(a / pi): the penny's K_I under the same tension."""
    return 2.0 * sigma * math.sqrt(a / math.pi)


def cap_k(sigma: float, a: float, alpha_deg: float = REFERENCE_ALPHA_DEG, nu: float = REFERENCE_NU
          ) -> tuple[float, float, float]:
    """(K_I, K_II, K_III) of the cap with base radius a at the reference
    case (alpha = 45 deg, nu = 0.22: the finite-element values of the module
    doc); raises ValueError for another case."""
    if abs(alpha_deg - REFERENCE_ALPHA_DEG) > 1e-9 or abs(nu - REFERENCE_NU) > 1e-9:
        raise ValueError(f"the spherical cap's reference K is known at alpha = {REFERENCE_ALPHA_DEG:g} deg, nu = "
                         f"{REFERENCE_NU:g} only; for shallow caps use cap_k_shallow")
    k0 = penny_scale(sigma, a)
    return REFERENCE_K_I * k0, REFERENCE_K_II * k0, 0.0


def cap_k_shallow(sigma: float, a: float, alpha_deg: float, nu: float) -> tuple[float, float, float]:
    """First-order (shallow-cap) K: K_I = K0, K_II = (1 + 4 nu) sin(alpha)
    K0 / 6, K_III = 0 (module doc; 0.3 % of K_II at 5 deg, 1.2 % at 15)."""
    k0 = penny_scale(sigma, a)
    return k0, (1.0 + 4.0 * nu) * math.sin(math.radians(alpha_deg)) * k0 / 6.0, 0.0


def cap_triangulation(a: float, alpha_deg: float, edge: float, pole: tuple[float, float, float] = (0.0, 0.0, 0.0)
                      ) -> tuple[np.ndarray, np.ndarray]:
    """A triangulation (vertices (nv, 3), triangles (nt, 3)) of the cap with
    base radius a and half-angle alpha whose pole (lowest point) is `pole`
    and whose sphere's centre lies above it at pole + (0, 0, R): rings of
    vertices on the sphere at equal polar steps of about `edge`, the front's
    ring (on the sphere, radius a) with about 2 pi a / edge points. The
    triangles' normals point to the centre (the + side)."""
    al = math.radians(alpha_deg)
    if not (a > 0.0 and 0.0 < al < math.pi and edge > 0.0):
        raise ValueError(f"cap_triangulation needs a > 0, 0 < alpha < 180 deg and edge > 0, got {a!r}, "
                         f"{alpha_deg!r}, {edge!r}")
    R = a / math.sin(al)
    rings = max(2, int(math.ceil(R * al / edge)))
    c = np.asarray(pole, dtype=float) + np.array([0.0, 0.0, R])
    verts = [np.asarray(pole, dtype=float)[None]]
    counts = [1]
    for i in range(1, rings + 1):
        th = al * i / rings
        n = max(6, int(round(2.0 * math.pi * R * math.sin(th) / edge)))
        ph = 2.0 * math.pi * np.arange(n) / n
        verts.append(c + R * np.column_stack([math.sin(th) * np.cos(ph), math.sin(th) * np.sin(ph),
                                              -math.cos(th) * np.ones(n)]))
        counts.append(n)
    offsets = np.concatenate([[0], np.cumsum(counts)])
    tris = []
    for i in range(rings):
        lo, hi = offsets[i], offsets[i + 1]
        na, nb = counts[i], counts[i + 1]
        # Walk both rings by azimuth, always advancing the one behind.
        ja = jb = 0
        while ja < na or jb < nb:
            a0, b0 = lo + ja % na, hi + jb % nb
            ta = (ja + 1) / na if na > 1 else 2.0
            tb = (jb + 1) / nb
            if na == 1:
                tris.append((a0, hi + (jb + 1) % nb, b0))
                jb += 1
                if jb == nb:
                    break
                continue
            if (ta <= tb and ja < na) or jb >= nb:
                tris.append((a0, lo + (ja + 1) % na, b0))
                ja += 1
            else:
                tris.append((a0, hi + (jb + 1) % nb, b0))
                jb += 1
    v = np.vstack(verts)
    t = np.asarray(tris, dtype=np.int32)
    # Orient toward the centre.
    nrm = np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]])
    flip = np.einsum("ij,ij->i", nrm, c - v[t].mean(axis=1)) < 0.0
    t[flip] = t[flip][:, ::-1]
    return v, t


def write_stl(path, vertices: np.ndarray, triangles: np.ndarray, name: str = "crack") -> None:
    """A binary STL of the triangles (their right-handed normals)."""
    v, t = np.asarray(vertices, dtype=float), np.asarray(triangles)
    P = v[t]
    nrm = np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0])
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    rec = np.zeros(len(t), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    rec["n"], rec["v"] = nrm, P
    with open(path, "wb") as f:
        f.write(name.encode()[:80].ljust(80, b" "))
        f.write(np.uint32(len(t)).tobytes())
        f.write(rec.tobytes())


__all__ = ["REFERENCE_K_I", "REFERENCE_K_II", "SSLV155_K_I", "SSLV155_K_II", "penny_scale", "cap_k",
           "cap_k_shallow", "cap_triangulation", "write_stl"]
