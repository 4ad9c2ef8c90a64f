"""Coulomb friction on the crack lips: open, stick and slip by a semi-smooth Newton method.

Unknowns: the displacement u, the normal multipliers lambda_n and the
tangential multipliers lambda_t, both on the stable multiplier space (the
same reduced space, the same P0 multiplier in a tip cell). The contact
pressure is p = -lambda_n (>= 0), the shear traction on the + lip along the
crack's direction t (n turned by -90 degrees) is tau = -lambda_t. With the
weighted normal gap g_k = (B_n u - g_n)_k, the weighted slip s_k = (B_t u -
g_t)_k and the lumped multiplier mass m_k (g_k / m_k, s_k / m_k are means
over multiplier k's support), each iteration classifies every multiplier
from the last iterate (Hueber, Stadler and Wohlmuth's complementarity
functions for the normal part) with c = E / h, b_k = mu (p_k - c g_k / m_k)
and the slip increment ds_k = s_k - s_old,k:

    closed   if p_k - c g_k / m_k > 0 (always with bilateral contact), else open;
    slip     if it stuck and |tau_k| > b_k (sign sigma_k = sign(tau_k)), or if it
             slipped with sigma_k and its increment still opposes the
             friction (sigma_k ds_k <= 0: tau = mu p sigma opposes the slip);
    stick    otherwise (a slip that would run along its friction stops),

and solves one linear saddle system (unsymmetric through the slip rows):

    K u + B_n^T lambda_n + B_t^T lambda_t = f
    closed: B_n u = g_n                  open: lambda_n = 0
    stick:  B_t u = g_t + s_old          slip: lambda_t - mu sigma lambda_n = 0     open: lambda_t = 0

s_old is the slip of the previous increment of the load path: friction is
path-dependent. The iteration stops when the states repeat; a set of states
met before is a cycle, reported as a ContactError naming the multipliers
whose state flips.
"""
from __future__ import annotations

import logging
import typing

import numpy as np
import scipy.sparse as sp

from ..solvers.checked import petsc_from_scipy, solve_checked
from .frictionless import ContactError, ContactSystem
if typing.TYPE_CHECKING:
    from ..solvers.direct import LinearSolver


logger = logging.getLogger(__name__)


#: State codes of a multiplier.
OPEN, STICK, SLIP = 0, 1, 2


STATE_NAMES = {OPEN: "open", STICK: "stick", SLIP: "slip"}


def solve_saddle_friction(K: sp.csr_matrix, f: np.ndarray, cs: ContactSystem, g_n: np.ndarray,
                          g_t: np.ndarray, s_old: np.ndarray, state: np.ndarray, sign: np.ndarray,
                          mu: float, residual_tol: float, bound: np.ndarray | None = None,
                          linear: "LinearSolver | None" = None, x0: np.ndarray | None = None
                          ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One linear solve for given states (module doc). With `bound` (Tresca:
    a given friction bound b_k per multiplier) the slip rows are
    lambda_t = -sigma b instead of lambda_t - mu sigma lambda_n = 0.
    linear: the solver path (cracklip.solvers; default MUMPS LU), x0 an
    initial guess (u, lambda_n, lambda_t) for an iterative one.
    Returns (u, lambda_n, lambda_t)."""
    m = cs.num_multipliers
    closed = state != OPEN
    stick = state == STICK
    slip = state == SLIP
    Bn = sp.diags(closed.astype(float)) @ cs.B
    Bt = sp.diags(stick.astype(float)) @ cs.Bt
    coulomb = -mu * sign if bound is None else np.zeros(m)
    rows_n = [Bn, sp.diags((~closed).astype(float)), None]
    rows_t = [Bt, sp.diags(np.where(slip, coulomb, 0.0)), sp.diags((~stick).astype(float))]
    S = sp.bmat([[K, cs.B.T, cs.Bt.T], rows_n, rows_t], format="csr")
    slip_rhs = np.zeros(m) if bound is None else -sign * bound
    rhs = np.concatenate([f, np.where(closed, g_n, 0.0), np.where(stick, g_t + s_old, np.where(slip, slip_rhs, 0.0))])
    A = petsc_from_scipy(S)
    b = A.createVecRight()
    b.array[:] = rhs
    what = "frictional contact system"
    # Unsymmetric: open and slipping rows are masked while B^T, B_t^T are whole,
    # and the Coulomb slip rows couple lambda_t to lambda_n.
    if linear is None:
        x = solve_checked(A, b, residual_tol, what=what, symmetric=False)
    else:
        x = linear.solve(A, b, residual_tol, what=what, x0=x0, symmetric=False, contact_points=m)
    sol = x.array.copy()
    for obj in (A, b, x):
        obj.destroy()
    n = K.shape[0]
    return sol[:n], sol[n:n + m], sol[n + m:]


def classify(p: np.ndarray, tau: np.ndarray, gap: np.ndarray, dslip: np.ndarray, lumped: np.ndarray,
             c: float, mu: float, bilateral: bool, state: np.ndarray, sign: np.ndarray,
             bound: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The states and slip signs of the multipliers after an iterate that
    was solved with (state, sign) (module doc): closed by the normal test;
    a closed multiplier that stuck slips when |tau| exceeds the bound (the
    sign of tau), one that was open when tau - c ds / m does (its sign);
    one that slipped keeps slipping while its slip increment opposes its
    friction (sigma ds < 0), and sticks when the increment turns along it
    (a slip the friction would drive). `bound`: a given friction
    bound (Tresca) instead of mu (p - c g / m)."""
    normal = p - c * gap / lumped
    closed = np.ones(len(p), dtype=bool) if bilateral else normal > 0.0
    if bound is None:
        bound = mu * np.maximum(normal, 0.0)
    was_slip = state == SLIP
    # A sticking multiplier has no slip increment: xi = tau. One that was
    # open closes sliding when its increment beats the bound (xi = tau - c ds / m).
    xi = np.where(state == OPEN, tau - c * dslip / lumped, tau)
    scale = max(float(np.abs(xi).max(initial=0.0)), float(bound.max(initial=0.0)), 1e-300)
    starts = ~was_slip & (np.abs(xi) > bound + 1e-12 * scale)
    ds_scale = max(float(np.abs(dslip / lumped).max(initial=0.0)), 1e-300)
    keeps = was_slip & (sign * dslip / lumped <= 1e-12 * ds_scale)
    slip = closed & (starts | keeps)
    new_sign = np.where(starts, np.sign(xi), sign)
    state = np.where(closed, np.where(slip, SLIP, STICK), OPEN).astype(np.int8)
    return state, np.where(slip, new_sign, 0.0)


def solve_friction(K: sp.csr_matrix, f: np.ndarray, cs: ContactSystem, g_n: np.ndarray, g_t: np.ndarray,
                   s_old: np.ndarray, opts, c: float, state: np.ndarray | None = None,
                   sign: np.ndarray | None = None, linear: "LinearSolver | None" = None
                   ) -> tuple[np.ndarray, dict]:
    """Frictional contact for one load increment: stiffness K (constraints
    applied), load f, constraint right-hand sides g_n, g_t (prescribed
    values), s_old the weighted slip B_t u_old - g_t,old of the previous
    increment. state, sign: the starting states (default from
    options.active_set_start: all closed and sticking, or all open).

    The semi-smooth Newton iteration on the Coulomb law (module doc) settles
    in a few iterations; where the law is at its limit (|tau| = mu p: stick
    and slip give the same solution) it can cycle between the two. It then
    falls back on a fixed point on the friction bound (as code_aster does):
    the bound b = mu p is frozen at the last pressure, the Tresca problem
    with that bound is solved by the same iteration (a convex problem: its
    states settle), and the bound is updated until it changes by less than
    1e-10 of its size. linear: the solver path of every linear solve
    (cracklip.solvers; default MUMPS LU). Returns (u, info: lambda,
    lambda_t, state, sign, active, iterations, history, method)."""
    mu = float(opts.friction)
    m = cs.num_multipliers
    bilateral = opts.contact == "bilateral"
    if state is None:
        state = np.full(m, STICK if bilateral or opts.active_set_start == "closed" else OPEN, dtype=np.int8)
        sign = np.zeros(m)
    sign = np.zeros(m) if sign is None else sign
    history: list[dict[str, int]] = []
    try:
        u, info = _iterate(K, f, cs, g_n, g_t, s_old, opts, c, state, sign, history, None, linear)
        info["method"] = "coulomb"
        return u, info
    except _Cycle as cycle:
        logger.info("friction: %s; fixed point on the friction bound", cycle)
        first_cycle = str(cycle)
        lam_n, state, sign = cycle.lam_n, cycle.state, cycle.sign
    bound = mu * np.maximum(-lam_n, 0.0)
    for outer in range(1, opts.max_active_set_iterations + 1):
        try:
            u, info = _iterate(K, f, cs, g_n, g_t, s_old, opts, c, state, sign, history, bound, linear)
        except _Cycle as e:
            raise ContactError(f"{first_cycle}; the fixed point on the friction bound cycles too ({e}); split "
                               "the load into more increments (options.load_steps), or lower the friction "
                               "coefficient") from None
        new_bound = mu * np.maximum(-info["lambda"], 0.0)
        change = float(np.abs(new_bound - bound).max(initial=0.0))
        bound = new_bound
        state, sign = info["state"], info["sign"]
        if change <= 1e-10 * max(float(bound.max(initial=0.0)), 1e-300):
            info["method"] = f"fixed point on the bound ({outer} updates)"
            info["iterations"] = len(history)
            info["history"] = history
            return u, info
    raise ContactError(f"{first_cycle}; the fixed point on the friction bound did not settle in "
                       f"{opts.max_active_set_iterations} updates; split the load into more increments "
                       "(options.load_steps), or lower the friction coefficient")


class _Cycle(Exception):
    """The states came back: the last iterate, for a fallback to start from."""

    def __init__(self, message: str, lam_n: np.ndarray, state: np.ndarray, sign: np.ndarray):
        super().__init__(message)
        self.lam_n, self.state, self.sign = lam_n, state, sign


#: A cycle of states is settled by its iterate of least complementarity
#: violation when that violation is below this fraction of the pressure scale.
CYCLE_TOLERANCE = 1e-2


def violation(p: np.ndarray, tau: np.ndarray, gap: np.ndarray, dslip: np.ndarray, lumped: np.ndarray, c: float,
              mu: float, state: np.ndarray, sign: np.ndarray, bound: np.ndarray | None = None) -> float:
    """How far an iterate solved with (state, sign) is from the contact and
    friction laws, as a traction relative to the largest pressure: tension
    on closed multipliers, c times the interpenetration of open ones, shear
    above the bound on sticking ones, c times a slip along the friction on
    slipping ones."""
    closed = state != OPEN
    b = mu * np.maximum(p, 0.0) if bound is None else bound
    v = np.zeros(len(p))
    v[closed] = np.maximum(-p[closed], 0.0)
    v[~closed] = c * np.maximum(-gap[~closed] / lumped[~closed], 0.0)
    stick, slip = state == STICK, state == SLIP
    v[stick] = np.maximum(v[stick], np.abs(tau[stick]) - b[stick])
    v[slip] = np.maximum(v[slip], c * np.maximum(sign[slip] * dslip[slip] / lumped[slip], 0.0))
    return float(v.max(initial=0.0) / max(float(np.abs(p).max(initial=0.0)), 1e-300))


def _iterate(K, f, cs, g_n, g_t, s_old, opts, c, state, sign, history, bound, linear=None):
    """The state iteration (Coulomb, or Tresca with a given bound) from the
    given states. When a set of states comes back, the iterate of least
    violation in the cycle is taken if its violation is below
    CYCLE_TOLERANCE (info["note"] says so), else _Cycle is raised."""
    mu = float(opts.friction)
    bilateral = opts.contact == "bilateral"
    lumped = np.asarray(cs.M.sum(axis=1)).ravel()
    key = lambda st, sg: st.tobytes() + np.sign(sg).astype(np.int8).tobytes()  # noqa: E731
    seen = {key(state, sign): len(history)}
    start = len(history)
    iterates: dict[int, tuple] = {}
    x0 = None
    for it in range(1, opts.max_active_set_iterations + 1):
        u, lam_n, lam_t = solve_saddle_friction(K, f, cs, g_n, g_t, s_old, state, sign, mu, opts.residual_tol,
                                                bound, linear, x0)
        x0 = np.concatenate([u, lam_n, lam_t])
        gap = cs.B @ u - g_n
        dslip = cs.Bt @ u - g_t - s_old
        iterates[len(history)] = (u, lam_n, lam_t, state, sign,
                                  violation(-lam_n, -lam_t, gap, dslip, lumped, c, mu, state, sign, bound))
        new_state, new_sign = classify(-lam_n, -lam_t, gap, dslip, lumped, c, mu, bilateral, state, sign, bound)
        counts = {name: int(np.count_nonzero(new_state == code)) for code, name in STATE_NAMES.items()}
        history.append(counts)
        logger.info("friction iteration %d: %d open, %d stick, %d slip", len(history), counts["open"],
                    counts["stick"], counts["slip"])
        if np.array_equal(new_state, state) and np.array_equal(np.sign(new_sign), np.sign(sign)):
            return u, {"lambda": lam_n, "lambda_t": lam_t, "state": state, "sign": sign,
                       "active": state != OPEN, "iterations": len(history), "history": history}
        k = key(new_state, new_sign)
        if k in seen:
            first = seen[k]
            flips = np.flatnonzero(state != new_state)
            best = min((i for i in iterates if i >= first), key=lambda i: iterates[i][5])
            bu, bn, bt, bs, bg, bv = iterates[best]
            logger.debug("cycle violations: %s", {i: iterates[i][5] for i in iterates if i >= first})
            if bv <= CYCLE_TOLERANCE:
                note = (f"the friction states cycled (period {len(history) - first}, multipliers "
                        f"{flips[:8].tolist()}); the iterate of least violation of the contact and friction laws "
                        f"was taken: {bv:.1e} of the largest pressure")
                logger.info("friction: %s", note)
                return bu, {"lambda": bn, "lambda_t": bt, "state": bs, "sign": bg, "active": bs != OPEN,
                            "iterations": len(history), "history": history, "note": note, "violation": bv}
            raise _Cycle(f"the friction states cycle: iteration {len(history)} gives the states of "
                         f"{'the start' if first == start else f'iteration {first}'} again (period "
                         f"{len(history) - first}); multipliers {flips[:8].tolist()} flip between "
                         + ", ".join(f"{STATE_NAMES[int(a)]}/{STATE_NAMES[int(b)]}" for a, b in
                                     zip(state[flips[:8]], new_state[flips[:8]])), lam_n, new_state, new_sign)
        seen[k] = len(history)
        state, sign = new_state, new_sign
    raise ContactError(f"the friction states did not settle in {opts.max_active_set_iterations} iterations "
                       f"(states per iteration: {history}); raise max_active_set_iterations or split the "
                       "load into more increments (options.load_steps)")
