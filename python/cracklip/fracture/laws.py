"""Fatigue crack growth laws: da/dN from the range and level of one load cycle.

Every law is a pure function of (Delta K, R, K_max, a) and its constants,
vectorised over numpy arrays (one entry per counted cycle), in whatever
consistent units its constants are in (cracklip.scene.fatigue converts a
material's constants into the scene's units first). A rate is 0 where the
law gives no growth (below a threshold, Delta K <= 0); it is +inf at or
beyond the law's critical K (final failure: the caller stops there).

    Paris            C Delta K^m
    Walker           C [Delta K / (1 - R)^(1 - gamma)]^m
    Forman           C Delta K^n / ((1 - R) K_f - Delta K)
    NASGRO           C [((1 - f) / (1 - R)) Delta K]^n (1 - Delta K_th / Delta K)^p
                       / (1 - K_max / K_crit)^q, with Newman's opening function f
                       and the threshold Delta K_th(R, a) (small-crack term)
    Hartman-Schijve  D [(Delta K - Delta K_thr) / sqrt(1 - K_max / A)]^alpha
    tabular          da/dN against Delta K for several R: log-log in Delta K
                     along each curve, linear in R between curves

Sources (docs/life.md has the full list): the NASGRO equation, Newman's f
and the threshold as written in the NASGRO/AFGROW manuals and implemented by
easigrow (`src/dadn.rs`, which cites Harter's AFGROW manual
AFRL-VA-WP-TR-1999-3016), the same form as the project's research notes
(shared/notes/damage_tolerance.md, gap 2); K_c(t) = K_Ic [1 + B_k exp(-(A_k t /
t0)^2)], t0 = 2.5 (K_Ic / sigma_ys)^2 (NASGRO's fit). Closure: NASGRO's f
is its own; the other laws take Delta K as given (contact closure gives an
effective Delta K already), and with closure "newman" a Paris or
Hartman-Schijve law gets U Delta K, U = (1 - f) / (1 - R)
(cracklip.fracture.life decides which).
"""
from __future__ import annotations

import dataclasses
import math
import typing

import numpy as np

from ..errors import InputError


ArrayLike = typing.Union[float, np.ndarray]


def _arr(x: ArrayLike) -> np.ndarray:
    return np.asarray(x, dtype=float)


# -- single laws ----------------------------------------------------------------------------------------

def paris_rate(delta_K: ArrayLike, C: float, m: float) -> np.ndarray:
    """C Delta K^m (0 where Delta K <= 0)."""
    dk = _arr(delta_K)
    return np.where(dk > 0.0, C * np.maximum(dk, 0.0) ** m, 0.0)


def walker_rate(delta_K: ArrayLike, R: ArrayLike, C: float, m: float, gamma: float) -> np.ndarray:
    """C [Delta K / (1 - R)^(1 - gamma)]^m; gamma = 1 is Paris. R >= 1 (no
    range) takes Delta K as it is (written as cracklip's growth loop always
    did, so constant-amplitude runs give the same numbers to the last bit;
    scalars are computed with Python's own power, as it was)."""
    if np.ndim(delta_K) == 0 and np.ndim(R) == 0:
        dk0, r0 = float(delta_K), float(R)
        k0 = dk0 / (1.0 - r0) ** (1.0 - gamma) if r0 < 1 else dk0
        return np.asarray(C * k0 ** m if dk0 > 0.0 else 0.0)
    dk, r = np.broadcast_arrays(_arr(delta_K), _arr(R))
    safe = np.where(r < 1.0, 1.0 - r, 1.0)
    k = np.where(r < 1.0, dk / safe ** (1.0 - gamma), dk)
    return np.where(dk > 0.0, C * np.maximum(k, 0.0) ** m, 0.0)


def forman_rate(delta_K: ArrayLike, R: ArrayLike, C: float, n: float, K_f: float) -> np.ndarray:
    """C Delta K^n / ((1 - R) K_f - Delta K): +inf once K_max = Delta K / (1 -
    R) reaches K_f (the denominator (1 - R) (K_f - K_max) vanishes, for any R,
    negative ones too), 0 for Delta K <= 0."""
    dk, r = np.broadcast_arrays(_arr(delta_K), _arr(R))
    den = (1.0 - r) * K_f - dk
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = C * np.maximum(dk, 0.0) ** n / den
    return np.where(dk <= 0.0, 0.0, np.where(den <= 0.0, np.inf, rate))


def hartman_schijve_rate(delta_K: ArrayLike, K_max: ArrayLike, D: float, dK_thr: float, A: float,
                         alpha: float) -> np.ndarray:
    """D [(Delta K - Delta K_thr) / sqrt(1 - K_max / A)]^alpha: 0 below the
    threshold, +inf at K_max >= A (A: the apparent cyclic toughness)."""
    dk, km = np.broadcast_arrays(_arr(delta_K), _arr(K_max))
    room = 1.0 - km / A
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = D * (np.maximum(dk - dK_thr, 0.0) / np.sqrt(np.maximum(room, 1e-300))) ** alpha
    return np.where(dk <= dK_thr, 0.0, np.where(room <= 0.0, np.inf, rate))


# -- NASGRO ---------------------------------------------------------------------------------------------

def newman_coefficients(alpha: float, smax_over_flow: float) -> tuple[float, float, float, float]:
    """A0, A1, A2, A3 of Newman's crack opening function (alpha: constraint,
    1 plane stress .. 3 plane strain; smax_over_flow: S_max / sigma_0)."""
    A0 = (0.825 - 0.34 * alpha + 0.05 * alpha ** 2) * math.cos(math.pi * smax_over_flow / 2.0) ** (1.0 / alpha)
    A1 = (0.415 - 0.071 * alpha) * smax_over_flow
    A3 = 2.0 * A0 + A1 - 1.0
    A2 = 1.0 - A0 - A1 - A3
    return A0, A1, A2, A3


def newman_f(R: ArrayLike, alpha: float, smax_over_flow: float) -> np.ndarray:
    """Newman's f = K_op / K_max: max(R, A0 + A1 R + A2 R^2 + A3 R^3) for R >=
    0, A0 + A1 R for -2 <= R < 0, A0 - 2 A1 below -2."""
    A0, A1, A2, A3 = newman_coefficients(alpha, smax_over_flow)
    r = _arr(R)
    cubic = np.maximum(r, A0 + A1 * r + A2 * r ** 2 + A3 * r ** 3)
    return np.where(r >= 0.0, cubic, np.where(r >= -2.0, A0 + A1 * r, A0 - 2.0 * A1))


@dataclasses.dataclass(frozen=True)
class NasgroConstants:
    """The NASGRO equation's constants (in one consistent unit system).

    Attributes:
        C, n, p, q: the rate constants.
        dK1: the long-crack threshold at R = 0 (Delta K_1 of the threshold form).
        C_th_plus, C_th_minus: the threshold's R exponent for R >= 0 and R < 0.
        alpha: Newman's constraint factor (1 plane stress .. 3 plane strain).
        smax_over_flow: S_max / sigma_0 of Newman's f.
        a0: the intrinsic crack length of the small-crack term
            sqrt(a / (a + a0)) (NASGRO: 0.0015 in = 0.0381 mm); 0: none.
        K_crit: the critical K of the denominator (K_c(t); inf: none).
    """
    C: float
    n: float
    p: float
    q: float
    dK1: float
    C_th_plus: float
    C_th_minus: float
    alpha: float = 2.0
    smax_over_flow: float = 0.3
    a0: float = 0.0
    K_crit: float = math.inf


def nasgro_threshold(R: ArrayLike, a: ArrayLike, c: NasgroConstants, f: ArrayLike | None = None) -> np.ndarray:
    """Delta K_th = dK1 sqrt(a / (a + a0)) / [(1 - f) / ((1 - A0) (1 - R))]^(1 + C_th R),
    C_th = C_th_plus for R >= 0, C_th_minus below; f: Newman's unless given
    (with contact closure f = R)."""
    r = _arr(R)
    A0 = newman_coefficients(c.alpha, c.smax_over_flow)[0]
    ff = newman_f(r, c.alpha, c.smax_over_flow) if f is None else _arr(f)
    cth = np.where(r >= 0.0, c.C_th_plus, c.C_th_minus)
    small = np.sqrt(_arr(a) / (_arr(a) + c.a0)) if c.a0 > 0.0 else 1.0
    return c.dK1 * small / ((1.0 - ff) / ((1.0 - A0) * (1.0 - r))) ** (1.0 + cth * r)


def nasgro_rate(delta_K: ArrayLike, R: ArrayLike, K_max: ArrayLike, a: ArrayLike, c: NasgroConstants,
                newman: bool = True) -> np.ndarray:
    """The NASGRO equation (module doc). newman: Newman's f (the equation as
    published); False: f = R (closure counted elsewhere, by contact, or not
    at all). 0 at or below the threshold, +inf at K_max >= K_crit."""
    dk, r, km, aa = np.broadcast_arrays(_arr(delta_K), _arr(R), _arr(K_max), _arr(a))
    f = newman_f(r, c.alpha, c.smax_over_flow) if newman else r
    th = nasgro_threshold(r, aa, c, f)
    with np.errstate(divide="ignore", invalid="ignore"):
        eff = (1.0 - f) / (1.0 - r) * dk
        above = np.maximum(1.0 - th / dk, 0.0)
        room = 1.0 - km / c.K_crit
        rate = c.C * np.maximum(eff, 0.0) ** c.n * above ** c.p / np.maximum(room, 1e-300) ** c.q
    rate = np.where((dk <= 0.0) | (dk <= th), 0.0, rate)
    return np.where(room <= 0.0, np.inf, rate)


def thickness_toughness(K_Ic: float, t: float, sigma_ys: float, A_k: float, B_k: float) -> float:
    """K_c(t) = K_Ic [1 + B_k exp(-(A_k t / t0)^2)], t0 = 2.5 (K_Ic / sigma_ys)^2
    (NASGRO's fit of the plane-stress rise of toughness in thin sheet)."""
    t0 = 2.5 * (K_Ic / sigma_ys) ** 2
    return K_Ic * (1.0 + B_k * math.exp(-(A_k * t / t0) ** 2))


# -- tabular ----------------------------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class RateTable:
    """da/dN against Delta K at several R (easigrow's layout: one row per rate,
    the Delta K of each R curve in the columns).

    Attributes:
        R: the R of each curve (ascending).
        dadn: the rates (ascending, > 0).
        delta_K: delta_K[i, j]: Delta K giving rate dadn[i] at R[j] (ascending in i).
    Between tabulated points log(da/dN) is linear in log(Delta K); between
    curves linear in R; outside the R range the nearest curve. Below a
    curve's first Delta K no growth (its threshold); above its last the
    last segment is extended.
    """
    R: tuple[float, ...]
    dadn: tuple[float, ...]
    delta_K: tuple[tuple[float, ...], ...]

    def __post_init__(self):
        R, d, K = np.asarray(self.R, float), np.asarray(self.dadn, float), np.asarray(self.delta_K, float)
        if R.ndim != 1 or R.size < 1 or np.any(np.diff(R) <= 0) or not np.all(np.isfinite(R)):
            raise InputError(f"tabular da/dN: the R values must be finite and ascending, got {list(self.R)}")
        if d.ndim != 1 or d.size < 2 or np.any(d <= 0) or np.any(np.diff(d) <= 0):
            raise InputError("tabular da/dN: the rates must be positive and ascending (at least two rows)")
        if K.shape != (d.size, R.size) or np.any(K <= 0) or np.any(np.diff(K, axis=0) <= 0) or \
                not np.all(np.isfinite(K)):
            raise InputError(f"tabular da/dN: every row needs one positive Delta K per R ({R.size}), ascending "
                             "down each column")
        # Converted once (a table of many curves is evaluated at every step of a life).
        object.__setattr__(self, "_log_dk", np.log(K).T.copy())  # (curves, rates)
        object.__setattr__(self, "_log_rate", np.log(d))

    def curve_rate(self, j: int, dk: np.ndarray) -> np.ndarray:
        K, d = self._log_dk[j], self._log_rate
        x = np.log(np.maximum(dk, 1e-300))
        slope = (d[-1] - d[-2]) / (K[-1] - K[-2])
        y = np.where(x <= K[-1], np.interp(x, K, d), d[-1] + slope * (x - K[-1]))
        return np.where(x < K[0], 0.0, np.exp(y))

    def rate(self, delta_K: ArrayLike, R: ArrayLike) -> np.ndarray:
        dk0, r0 = np.broadcast_arrays(_arr(delta_K), _arr(R))
        dk, r = dk0.ravel(), r0.ravel()
        Rs = np.asarray(self.R, float)
        if Rs.size == 1:
            out = np.where(dk > 0, self.curve_rate(0, dk), 0.0)
        else:
            rc = np.clip(r, Rs[0], Rs[-1])
            j = np.clip(np.searchsorted(Rs, rc, side="right") - 1, 0, Rs.size - 2)
            w = (rc - Rs[j]) / (Rs[j + 1] - Rs[j])
            out = np.zeros(dk.size)
            for jj in np.unique(j):  # only the curves around the cycles' R
                sel = j == jj
                out[sel] = (1.0 - w[sel]) * self.curve_rate(jj, dk[sel]) + w[sel] * self.curve_rate(jj + 1, dk[sel])
            out = np.where(dk > 0, out, 0.0)
        return out.reshape(dk0.shape)


def rate_table_reach(table: RateTable, delta_K: ArrayLike, R: ArrayLike) -> dict[str, float]:
    """Where cycles (Delta K, R) fall outside a tabular law's data (RateTable
    extends a curve's last log-log segment above its last Delta K and reads
    an R outside the table's span on the nearest curve).

    Returns: ratio, the largest Delta K over the last tabulated Delta K of
    the curve(s) it is read from (> 1: extrapolated), with that cycle's
    delta_K, R and the curve's last Delta K (last); R_min and R_max of the
    cycles and the table's span R_lo, R_hi. Cycles with Delta K <= 0 are left
    out (ratio 0 when none is left)."""
    dk, r = (a.ravel() for a in np.broadcast_arrays(_arr(delta_K), _arr(R)))
    Rs = np.asarray(table.R, float)
    last = np.asarray(table.delta_K, float)[-1]
    out = {"ratio": 0.0, "delta_K": 0.0, "R": 0.0, "last": float(last[0]), "R_min": math.nan, "R_max": math.nan,
           "R_lo": float(Rs[0]), "R_hi": float(Rs[-1])}
    keep = dk > 0.0
    if not np.any(keep):
        return out
    dk, r = dk[keep], r[keep]
    if Rs.size == 1:
        lim = np.full(dk.size, last[0])
    else:
        rc = np.clip(r, Rs[0], Rs[-1])
        j = np.clip(np.searchsorted(Rs, rc, side="right") - 1, 0, Rs.size - 2)
        w = (rc - Rs[j]) / (Rs[j + 1] - Rs[j])
        lim = np.where(w <= 0.0, last[j], np.where(w >= 1.0, last[j + 1], np.minimum(last[j], last[j + 1])))
    ratio = dk / lim
    i = int(np.argmax(ratio))
    out.update(ratio=float(ratio[i]), delta_K=float(dk[i]), R=float(r[i]), last=float(lim[i]), R_min=float(r.min()),
               R_max=float(r.max()))
    return out


# -- the law objects the life integration uses ---------------------------------------------------------

class GrowthLaw:
    """A growth law with its constants: rate(delta_K, R, K_max, a) -> da/dN.

    newman: whether the law applies Newman's closure itself (NASGRO with
    closure "newman"). K_crit: the K at which the law's rate diverges (None:
    it does not)."""
    name = "law"
    newman = False
    K_crit: float | None = None

    def rate(self, delta_K: ArrayLike, R: ArrayLike, K_max: ArrayLike, a: ArrayLike) -> np.ndarray:
        raise NotImplementedError

    def describe(self) -> str:
        return self.name


@dataclasses.dataclass(frozen=True)
class Paris(GrowthLaw):
    C: float
    m: float
    name: typing.ClassVar[str] = "paris"

    def rate(self, delta_K, R, K_max, a):
        return paris_rate(delta_K, self.C, self.m)

    def describe(self) -> str:
        return f"Paris: da/dN = {self.C:.4g} dK^{self.m:g}"


@dataclasses.dataclass(frozen=True)
class Walker(GrowthLaw):
    C: float
    m: float
    gamma: float
    name: typing.ClassVar[str] = "walker"

    def rate(self, delta_K, R, K_max, a):
        return walker_rate(delta_K, R, self.C, self.m, self.gamma)

    def describe(self) -> str:
        return f"Walker: da/dN = {self.C:.4g} [dK / (1 - R)^(1 - {self.gamma:g})]^{self.m:g}"


@dataclasses.dataclass(frozen=True)
class Forman(GrowthLaw):
    C: float
    n: float
    K_f: float
    name: typing.ClassVar[str] = "forman"

    @property
    def K_crit(self) -> float:  # type: ignore[override]
        return self.K_f

    def rate(self, delta_K, R, K_max, a):
        return forman_rate(delta_K, R, self.C, self.n, self.K_f)

    def describe(self) -> str:
        return f"Forman: da/dN = {self.C:.4g} dK^{self.n:g} / ((1 - R) {self.K_f:g} - dK)"


@dataclasses.dataclass(frozen=True)
class Nasgro(GrowthLaw):
    constants: NasgroConstants
    newman: bool = True  # type: ignore[misc]
    name: typing.ClassVar[str] = "nasgro"

    @property
    def K_crit(self) -> float | None:  # type: ignore[override]
        return self.constants.K_crit if math.isfinite(self.constants.K_crit) else None

    def rate(self, delta_K, R, K_max, a):
        return nasgro_rate(delta_K, R, K_max, a, self.constants, self.newman)

    def threshold(self, R, a):
        f = None if self.newman else _arr(R)
        return nasgro_threshold(R, a, self.constants, f)

    def describe(self) -> str:
        c = self.constants
        return (f"NASGRO: C = {c.C:.4g}, n = {c.n:g}, p = {c.p:g}, q = {c.q:g}, dK1 = {c.dK1:g}, "
                f"C_th+ = {c.C_th_plus:g}, C_th- = {c.C_th_minus:g}, K_crit = {c.K_crit:.5g}, "
                + (f"Newman f (alpha {c.alpha:g}, S_max/sigma_0 {c.smax_over_flow:g})" if self.newman else "f = R"))


@dataclasses.dataclass(frozen=True)
class HartmanSchijve(GrowthLaw):
    D: float
    dK_thr: float
    A: float
    alpha: float
    name: typing.ClassVar[str] = "hartman_schijve"

    @property
    def K_crit(self) -> float:  # type: ignore[override]
        return self.A

    def rate(self, delta_K, R, K_max, a):
        return hartman_schijve_rate(delta_K, K_max, self.D, self.dK_thr, self.A, self.alpha)

    def describe(self) -> str:
        return (f"Hartman-Schijve: da/dN = {self.D:.4g} [(dK - {self.dK_thr:g}) / sqrt(1 - K_max / "
                f"{self.A:g})]^{self.alpha:g}")


@dataclasses.dataclass(frozen=True)
class Tabular(GrowthLaw):
    table: RateTable
    name: typing.ClassVar[str] = "tabular"

    def rate(self, delta_K, R, K_max, a):
        return self.table.rate(delta_K, R)

    def describe(self) -> str:
        return f"tabular da/dN at R = {list(self.table.R)} ({len(self.table.dadn)} rates)"


__all__ = ["paris_rate", "walker_rate", "forman_rate", "hartman_schijve_rate", "newman_coefficients", "newman_f",
           "NasgroConstants", "nasgro_threshold", "nasgro_rate", "thickness_toughness", "RateTable",
           "rate_table_reach", "GrowthLaw",
           "Paris", "Walker", "Forman", "Nasgro", "HartmanSchijve", "Tabular"]
