"""Coulomb friction on the crack lips: open, stick and slip by a semi-smooth Newton method.

Unknowns: the displacement u, the normal multipliers lambda_n and the
tangential multipliers lambda_t, both on the stable multiplier space (the
same reduced space, the same P0 multipliers at tips and fronts). The
contact pressure is p = -lambda_n (>= 0); the shear traction on the + lip
is tau = -lambda_t, one component per tangent of the crack: in 2D along
its direction t (n turned by -90 degrees), in 3D along t1 and t2 (the
tangent basis of cpp/contact/contact_kernels_3d.h; Bt and lambda_t hold
the t1 rows, then the t2 rows). Per multiplier k the shear tau_k, the
weighted slip s_k = (B_t u - g_t)_k and the slip direction sigma_k have
d - 1 components (2D: one, sigma = +-1). With the weighted normal gap g_k
= (B_n u - g_n)_k and the lumped multiplier mass m_k (g_k / m_k, s_k /
m_k are means over multiplier k's support), c = E / h, the friction bound
b_k = mu (p_k - c g_k / m_k), the slip increment ds_k = s_k - s_old,k and
the trial shear xi_k = tau_k - c ds_k / m_k (Alart and Curnier's, as
Hueber, Stadler and Wohlmuth use it in 3D), each iteration classifies
every multiplier from the last iterate:

    closed   if p_k - c g_k / m_k > 0 (always with bilateral contact), else open;
    slip     if it stuck and |tau_k| > b_k (one that was open: |xi_k| > b_k),
             along sigma_k = xi_k / |xi_k|; if it slipped, while its
             increment opposes its friction (sigma_k . ds_k <= 0), along
             xi_k / |xi_k| (in 2D that is its sign);
    stick    otherwise (a slip that would run along its friction stops),

and solves one linear saddle system (unsymmetric through the slip rows):

    K u + B_n^T lambda_n + B_t^T lambda_t = f
    closed: B_n u = g_n                  open: lambda_n = 0
    stick:  B_t u = g_t + s_old          open: lambda_t = 0
    slip:   (I - beta Q) tau + beta c Q ds / m - mu sigma p = 0,

the slip rows the Newton linearisation of tau = b xi / |xi| at the last
iterate: Q = I - sigma sigma^T, beta = b / |xi| (<= 1). Along sigma the
shear is mu p; across it (3D only: in 2D Q = 0 and the row is lambda_t -
mu sigma lambda_n = 0) the slip and the shear are tied by the projection's
derivative, so the slip direction is found by Newton, not by a fixed
point on it. s_old is the slip of the previous increment of the load path:
friction is path-dependent. The iteration stops when the states repeat
with the same slip directions (2D: the same signs; 3D: within
DIRECTION_TOLERANCE); a set of states met before is a cycle, reported as a
ContactError naming the multipliers whose state flips. Every decision is
elementwise on the reduced multipliers, so it does not depend on the order
they are numbered in.
"""
from __future__ import annotations

import logging
import typing

import numpy as np
import scipy.sparse as sp

from ..solvers.checked import petsc_from_scipy, solve_checked
from ..solvers.saddle import bordered_matrix, multiplier_block
from .frictionless import ContactError, ContactSystem, owned_product, solve_bordered
if typing.TYPE_CHECKING:
    from petsc4py import PETSc
    from ..solvers.direct import LinearSolver


logger = logging.getLogger(__name__)


#: State codes of a multiplier.
OPEN, STICK, SLIP = 0, 1, 2


STATE_NAMES = {OPEN: "open", STICK: "stick", SLIP: "slip"}


#: In 3D the iteration has settled when the states repeat and no slipping
#: multiplier's direction sigma (a unit vector) moves by more than this:
#: the friction traction's direction is then right to this fraction of mu p.
DIRECTION_TOLERANCE = 1e-6


#: Inexact Newton on the iterative path: a linear solve whose states or
#: slip directions will still change is an inner step, solved to this
#: relative Krylov residual instead of KRYLOV_RTOL (None: every solve to
#: KRYLOV_RTOL). Once the states repeat, the next solve's tolerance is
#: FORCING x (the last turn of the slip directions)^2, the error Newton's
#: quadratic convergence makes next anyway (Eisenstat and Walker's forcing
#: term, on the directions); exact (EXACT_BELOW) from a turn of 0.03 on.
#: Only a solve to KRYLOV_RTOL ends the iteration: an inexact iterate whose
#: states and directions repeat is solved once more to KRYLOV_RTOL, which
#: must repeat them in turn, so the answer, its states and its residual
#: check are the exact iteration's; where inexact iterates cycle, the
#: iteration starts again with exact solves. Closed penny at 1e5 dofs
#: (mu 0.3, all slipping): GMRES iterations 27 + 22 + 12 + 2 + 0 exact,
#: 11 + 5 + 16 + 4 + 0 so (1e-3: 9 + 2 + 19 + 11 + 1; 1e-2: 6 + 1 + 12 +
#: 6 + 8 + 1, the directions of a looser start turn more).
INEXACT_RTOL: float | None = 1e-4


#: The forcing term's factor: a solve to 4.6e-8 left the directions 1.3e-5
#: off (~300 rtol) at 5e4 dofs, where Newton's next turn was below 1e-6.
FORCING = 1e-5


#: A forcing term below this solves exactly: from a warm start the last
#: decades cost a few Krylov iterations, less than one more solve's set-up.
EXACT_BELOW = 1e-8


#: A sticking multiplier slips when its shear exceeds the friction bound by
#: more than this fraction of the largest shear or bound: the multipliers of
#: an accepted solve carry round-off of about this order, so a shear "above"
#: the bound by less is at it (|tau| = mu p, where stick and slip are the
#: same solution and the stick solution is exact). At 1e-12 the closed crack
#: under tau = mu p (biaxial p = 1, tau = 0.5, mu = 0.5; 2D, 1.2e4 dofs)
#: whose sticking start is exact had shears 5e-11 above the bound: 14 of its
#: 48 multipliers slipped on round-off, the states wandered 20 iterations and
#: the run stopped with a ContactError (tests/test_friction.py).
LIMIT_TOLERANCE = 1e-8


def tangent_components(cs: ContactSystem) -> int:
    """Components of the shear per multiplier: 1 in 2D, 2 in 3D (the rows
    of cs.Bt per multiplier)."""
    return cs.Bt.shape[0] // max(cs.num_multipliers, 1) if cs.num_multipliers else 1


def per_multiplier(v: np.ndarray, k: int) -> np.ndarray:
    """(m, k) per multiplier from the stacked (k m,) layout of Bt's rows
    (the rows of t1, then of t2)."""
    return np.asarray(v).reshape(k, -1).T


def stacked(v: np.ndarray) -> np.ndarray:
    """(k m,) in Bt's row layout from (m, k) per multiplier."""
    return np.asarray(v).T.ravel()


def solve_saddle_friction(K: sp.csr_matrix, f: np.ndarray, cs: ContactSystem, g_n: np.ndarray,
                          g_t: np.ndarray, s_old: np.ndarray, state: np.ndarray, sign: np.ndarray,
                          mu: float, residual_tol: float, bound: np.ndarray | None = None,
                          linear: "LinearSolver | None" = None, x0: np.ndarray | None = None,
                          beta: np.ndarray | None = None, c: float = 0.0, rtol: float | None = None
                          ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One linear solve for given states (module doc); sign: the slip
    directions (m, k) (2D: k = 1, +-1); beta (m,) and c the slip rows'
    Newton terms across the direction (3D; None: 0, the direction held).
    With `bound` (Tresca: a given friction bound b_k per multiplier) the
    slip rows take b instead of mu p. linear: the solver path
    (cracklip.solvers; default MUMPS LU), x0 an initial guess (u, lambda_n,
    lambda_t) for an iterative one, rtol its Krylov tolerance for an
    inexact solve (LinearSolver.solve). Returns (u, lambda_n, lambda_t (k m,))."""
    m = cs.num_multipliers
    rows_n, rows_t, rhs_rows = friction_rows(cs, g_n, g_t, s_old, state, sign, mu, bound, beta, c)
    rhs = np.concatenate([f, rhs_rows])
    if linear is None:
        A = petsc_from_scipy(sp.bmat([[K, cs.B.T, cs.Bt.T], rows_n, rows_t], format="csr"))
    else:  # (by the solver path: the direct one assembles it, the iterative one applies it around K)
        n = len(f)
        C = sp.vstack([cs.B, cs.Bt], format="csr")
        rows = sp.bmat([rows_n, rows_t], format="csr")
        if rows.shape[1] < n + C.shape[0]:
            rows.resize((rows.shape[0], n + C.shape[0]))
        # The closed normal rows keep the iterative path's coarse space
        # closed (with the sticking tangential rows too: the same GMRES
        # iterations at 1e5 dofs, and a larger SVD).
        A = linear.bordered_matrix(K, C, rows, (sp.diags((state != OPEN).astype(float)) @ cs.B).tocsr())
    b = A.createVecRight()
    b.array[:] = rhs
    # Unsymmetric: open and slipping rows are masked while B^T, B_t^T are whole,
    # and the Coulomb slip rows couple lambda_t to lambda_n.
    if linear is None:
        x = solve_checked(A, b, residual_tol, what=WHAT, symmetric=False)
    else:
        x = linear.solve(A, b, residual_tol, what=WHAT, x0=x0, symmetric=False, contact_points=m, rtol=rtol)
    sol = x.array.copy()
    for obj in (A, b, x):
        obj.destroy()
    n = len(f)
    return sol[:n], sol[n:n + m], sol[n + m:]


WHAT = "frictional contact system"


def friction_rows(cs: ContactSystem, g_n: np.ndarray, g_t: np.ndarray, s_old: np.ndarray, state: np.ndarray,
                  sign: np.ndarray, mu: float, bound: np.ndarray | None = None, beta: np.ndarray | None = None,
                  c: float = 0.0) -> tuple[list, list, np.ndarray]:
    """The multipliers' rows of one linear solve for given states (module
    doc; the arguments solve_saddle_friction's): the normal rows and the
    tangential rows as block rows [u, lambda_n, lambda_t], each a list of
    sparse blocks (None: zero), and their right-hand side. The rows above
    them are [K B^T B_t^T] (B and B_t whole, unmasked)."""
    m = cs.num_multipliers
    k = tangent_components(cs)
    sign = np.reshape(sign, (m, k))
    closed = state != OPEN
    stick = state == STICK
    slip = state == SLIP
    stick_k, slip_k = np.tile(stick, k), np.tile(slip, k)
    Bn = sp.diags(closed.astype(float)) @ cs.B
    Bt = sp.diags(stick_k.astype(float)) @ cs.Bt
    T = sp.diags((~stick_k).astype(float))
    rhs_t = np.where(stick_k, g_t + s_old, 0.0)
    if bound is not None:  # Tresca: the shear along sigma is the given bound
        rhs_t = rhs_t + np.where(slip_k, stacked(-sign * np.reshape(bound, (m, 1))), 0.0)
    if k > 1 and beta is not None and np.any(slip & (beta > 0.0)):
        # Across sigma: -beta Q lambda_t - (beta c / m) Q (B_t u - g_t - s_old).
        lumped = np.asarray(cs.M.sum(axis=1)).ravel()
        bq = np.where(slip, beta, 0.0)
        W = sp.bmat([[sp.diags(bq * ((a == b) - sign[:, a] * sign[:, b])) for b in range(k)] for a in range(k)])
        T = T - W
        Bt = Bt - sp.diags(np.tile(c / lumped, k)) @ W @ cs.Bt
        rhs_t = rhs_t - np.tile(c / lumped, k) * (W @ (g_t + s_old))
    coulomb = -mu * sign if bound is None else np.zeros((m, k))
    blocks = [sp.diags(np.where(slip, coulomb[:, c_], 0.0)) for c_ in range(k)]
    rows_n = [Bn, multiplier_block(closed, cs.S(closed)), None]
    rows_t = [Bt, blocks[0] if k == 1 else sp.vstack(blocks), T]
    return rows_n, rows_t, np.concatenate([np.where(closed, g_n, 0.0), rhs_t])


def friction_saddle(K: "sp.csr_matrix | PETSc.Mat", f: np.ndarray, cs: ContactSystem, g_n: np.ndarray,
                    g_t: np.ndarray, s_old: np.ndarray, mu: float, c: float, residual_tol: float,
                    linear: "LinearSolver | None" = None, distributed: bool = False):
    """The linear solve of the state iteration, solve(state, sign, bound,
    beta, x0, rtol) -> (u, lambda_n, lambda_t, B u, B_t u) (rtol: None, or
    the Krylov tolerance of an inexact solve on the iterative path). Serial: by
    solve_saddle_friction on the scipy K. distributed (mpirun: K the
    distributed PETSc stiffness, f this process's owned entries, cs whole
    on every process): friction_rows border K as one distributed matrix
    (solvers/saddle.py bordered_matrix, the rows on the last process) solved
    by parallel MUMPS, or by linear if it is the iterative path
    (frictionless.solve_bordered): u this process's owned dofs, the
    multipliers broadcast by the process holding their rows, B u
    and B_t u summed over the processes' owned dofs and broadcast by rank 0
    (owned_product), so every process classifies the same numbers and takes
    the same states and slip directions."""
    if not distributed:
        def solve(state, sign, bound, beta, x0, rtol=None):
            u, lam_n, lam_t = solve_saddle_friction(K, f, cs, g_n, g_t, s_old, state, sign, mu, residual_tol,
                                                    bound, linear, x0, beta, c, rtol)
            return u, lam_n, lam_t, cs.B @ u, cs.Bt @ u
        return solve
    m = cs.num_multipliers
    C = sp.vstack([cs.B, cs.Bt], format="csr")
    iterative = linear is not None and linear.name == "iterative"  # (else parallel MUMPS LU)

    def solve_distributed(state, sign, bound, beta, x0, rtol=None):
        rows_n, rows_t, rhs = friction_rows(cs, g_n, g_t, s_old, state, sign, mu, bound, beta, c)
        S = bordered_matrix(K, C, sp.bmat([rows_n, rows_t], format="csr"), symmetric=False)
        u, lam = solve_bordered(S, f, rhs, residual_tol, WHAT, linear=linear if iterative else None, x0=x0,
                                contact_points=m, rtol=rtol)
        Cu = owned_product(K, C, u)
        return u, lam[:m], lam[m:], Cu[:m], Cu[m:]
    return solve_distributed


def classify(p: np.ndarray, tau: np.ndarray, gap: np.ndarray, dslip: np.ndarray, lumped: np.ndarray,
             c: float, mu: float, bilateral: bool, state: np.ndarray, sign: np.ndarray,
             bound: np.ndarray | None = None, newton: bool = False
             ) -> tuple[np.ndarray, np.ndarray] | tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The states and slip directions (m, k) of the multipliers after an
    iterate that was solved with (state, sign) (module doc); tau, dslip,
    sign: (m, k), k the shear's components (2D: 1). Closed by the normal
    test; a closed multiplier that stuck slips when |tau| exceeds the bound
    (along tau), one that was open when xi = tau - c ds / m does (along
    xi); one that slipped keeps slipping (2D: while its increment opposes
    its friction, sigma . ds <= 0: in 2D with its sign, in 3D along xi)
    and else sticks. `bound`: a given friction bound
    (Tresca) instead of mu (p - c g / m). newton: also return beta (m,) =
    bound / |xi| (at most 1) on slipping multipliers, 0 elsewhere (the slip
    rows' Newton terms)."""
    m = len(p)
    k = int(np.shape(tau)[1]) if np.ndim(tau) == 2 else 1
    tau, dslip, sign = (np.reshape(v, (m, k)) for v in (tau, dslip, sign))
    normal = p - c * gap / lumped
    closed = np.ones(len(p), dtype=bool) if bilateral else normal > 0.0
    if bound is None:
        bound = mu * np.maximum(normal, 0.0)
    was_slip = state == SLIP
    # A sticking multiplier has no slip increment: xi = tau. One that was
    # open closes sliding when its increment beats the bound, one that
    # slipped goes on while it does (3D): xi = tau - c ds / m.
    ds = dslip / lumped[:, None]
    xi = np.where((state == STICK)[:, None] | ((state == SLIP)[:, None] & (k == 1)), tau, tau - c * ds)
    xi_size = np.linalg.norm(xi, axis=1) if k > 1 else np.abs(xi[:, 0])
    scale = max(float(xi_size.max(initial=0.0)), float(bound.max(initial=0.0)), 1e-300)
    starts = ~was_slip & (xi_size > bound + LIMIT_TOLERANCE * scale)
    ds_size = np.linalg.norm(ds, axis=1) if k > 1 else np.abs(ds[:, 0])
    ds_scale = max(float(ds_size.max(initial=0.0)), 1e-300)
    keeps = was_slip & (np.einsum("mk,mk->m", sign, ds) <= 1e-12 * ds_scale)
    slip = closed & (starts | keeps)
    along_xi = xi / np.where(xi_size > 0.0, xi_size, 1.0)[:, None]
    new_sign = along_xi if k > 1 else np.where(starts[:, None], along_xi, sign)
    state = np.where(closed, np.where(slip, SLIP, STICK), OPEN).astype(np.int8)
    new_sign = np.where(slip[:, None], new_sign, 0.0)
    if not newton:
        return state, new_sign
    beta = np.where(slip, np.minimum(bound / np.where(xi_size > 0.0, xi_size, 1.0), 1.0), 0.0)
    return state, new_sign, beta


def solve_friction(K: sp.csr_matrix, f: np.ndarray, cs: ContactSystem, g_n: np.ndarray, g_t: np.ndarray,
                   s_old: np.ndarray, opts, c: float, state: np.ndarray | None = None,
                   sign: np.ndarray | None = None, linear: "LinearSolver | None" = None,
                   distributed: bool = False) -> tuple[np.ndarray, dict]:
    """Frictional contact for one load increment: stiffness K (constraints
    applied), load f, constraint right-hand sides g_n, g_t (prescribed
    values), s_old the weighted slip B_t u_old - g_t,old of the previous
    increment. state, sign: the starting states and slip directions (m,
    k) (default from options.active_set_start: all closed and sticking, or
    all open).

    The semi-smooth Newton iteration on the Coulomb law (module doc) settles
    in a few iterations; where the law is at its limit (|tau| = mu p: stick
    and slip give the same solution) it can cycle between the two. It then
    falls back on a fixed point on the friction bound (as code_aster does):
    the bound b = mu p is frozen at the last pressure, the Tresca problem
    with that bound is solved by the same iteration (a convex problem: its
    states settle), and the bound is updated until it changes by less than
    1e-10 of its size. linear: the solver path of every linear solve
    (cracklip.solvers; default MUMPS LU). distributed: K is the distributed
    stiffness of an mpirun, f and the returned u this process's owned dofs
    (friction_saddle; every decision is taken on numbers that are the same
    on every process). Returns (u, info: lambda,
    lambda_t, state, sign, active, iterations, history, method)."""
    mu = float(opts.friction)
    m = cs.num_multipliers
    bilateral = opts.contact == "bilateral"
    k = tangent_components(cs)
    if state is None:
        state = np.full(m, STICK if bilateral or opts.active_set_start == "closed" else OPEN, dtype=np.int8)
        sign = None
    sign = np.zeros((m, k)) if sign is None else np.reshape(sign, (m, k))
    history: list[dict[str, int]] = []
    saddle = friction_saddle(K, f, cs, g_n, g_t, s_old, mu, c, opts.residual_tol, linear, distributed)
    # Inexact inner solves (INEXACT_RTOL) where they save work: on the iterative path.
    loose = INEXACT_RTOL if linear is not None and linear.name == "iterative" else None
    try:
        u, info = _StateIteration(saddle, cs, g_n, g_t, s_old, opts, c, state, sign, history, None, loose).run()
        info["method"] = "coulomb"
        return u, info
    except _Cycle as cycle:
        logger.info("friction: %s; fixed point on the friction bound", cycle)
        first_cycle = str(cycle)
        lam_n, state, sign = cycle.lam_n, cycle.state, cycle.sign
    bound = mu * np.maximum(-lam_n, 0.0)
    for outer in range(1, opts.max_active_set_iterations + 1):
        try:
            u, info = _StateIteration(saddle, cs, g_n, g_t, s_old, opts, c, state, sign, history, bound,
                                          loose).run()
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
    above the bound on sticking ones, c times a slip along the friction or
    across its direction on slipping ones. tau, dslip, sign: (m, k)."""
    m = len(p)
    k = int(np.shape(tau)[1]) if np.ndim(tau) == 2 else 1
    tau, dslip, sign = (np.reshape(v, (m, k)) for v in (tau, dslip, sign))
    closed = state != OPEN
    b = mu * np.maximum(p, 0.0) if bound is None else bound
    v = np.zeros(len(p))
    v[closed] = np.maximum(-p[closed], 0.0)
    v[~closed] = c * np.maximum(-gap[~closed] / lumped[~closed], 0.0)
    stick, slip = state == STICK, state == SLIP
    tau_size = np.linalg.norm(tau, axis=1) if k > 1 else np.abs(tau[:, 0])
    v[stick] = np.maximum(v[stick], tau_size[stick] - b[stick])
    ds = dslip / lumped[:, None]
    along = np.einsum("mk,mk->m", sign, ds)
    across = np.linalg.norm(ds - along[:, None] * sign, axis=1) if k > 1 else np.zeros(m)
    v[slip] = np.maximum(v[slip], c * (np.maximum(along[slip], 0.0) + across[slip]))
    return float(v.max(initial=0.0) / max(float(np.abs(p).max(initial=0.0)), 1e-300))


class _Iterate(typing.NamedTuple):
    """One solve of the state iteration and what it classifies: the
    solution (u, lam_n, lam_t), whether it was solved exactly, the next
    states, directions and Newton terms, and whether they repeat."""
    u: np.ndarray
    lam_n: np.ndarray
    lam_t: np.ndarray
    exact: bool
    state: np.ndarray
    sign: np.ndarray
    beta: np.ndarray
    same_states: bool
    settled: bool


class _StateIteration:
    """The state iteration (Coulomb, or Tresca with a given bound) from the
    given states, each linear solve by saddle (friction_saddle): solve,
    classify (step), and either stop (settled on an exact solve), go on with
    the new states, or deal with a set of states met before (cycle). When a set of states comes back, the
    iterate of least violation in the cycle is taken if its violation is
    below CYCLE_TOLERANCE (info["note"] says so), else _Cycle is raised.
    loose: the Krylov tolerance of the inexact inner solves (INEXACT_RTOL;
    None: every solve exact). An inexact iterate never ends the iteration
    nor decides a cycle: where its states and directions repeat, they are
    solved again exactly; where its states cycle, the iteration goes on
    from there with exact solves only, and if these cycle too, it starts
    again from the given states with exact solves."""

    def __init__(self, saddle, cs, g_n, g_t, s_old, opts, c, state, sign, history, bound, loose=None):
        self.saddle, self.cs, self.g_n, self.g_t, self.s_old = saddle, cs, g_n, g_t, s_old
        self.opts, self.c, self.bound, self.history = opts, c, bound, history
        self.mu = float(opts.friction)
        self.bilateral = opts.contact == "bilateral"
        self.lumped = np.asarray(cs.M.sum(axis=1)).ravel()
        self.k = tangent_components(cs)
        self.first = (state, sign)
        self.state, self.sign = state, sign
        self.beta = None  # the slip rows' Newton terms across sigma (3D), from the last iterate
        self.loose = self.rtol = loose  # the inner solves' and this solve's Krylov tolerance (None: exact)
        self.x0 = None
        self.went_on = False  # (exact solves from where an inexact cycle was met)
        self._forget()

    def key(self, state: np.ndarray, sign: np.ndarray) -> bytes:
        """What identifies an iterate: the states and (2D) the slip signs; a
        3D direction varies continuously (its fixed point settles within
        DIRECTION_TOLERANCE), so there the states alone."""
        if self.k == 1:
            return state.tobytes() + np.sign(sign).astype(np.int8).tobytes()
        return state.tobytes()

    def _forget(self) -> None:
        """Start the record of states met (and of the iterates a cycle
        chooses from) at the current states."""
        self.seen = {self.key(self.state, self.sign): len(self.history)}
        self.iterates: dict[int, tuple] = {}
        self.start = len(self.history)

    def run(self) -> tuple[np.ndarray, dict]:
        for _ in range(self.opts.max_active_set_iterations):
            it = self.step()
            if it.settled and not it.exact:  # checked by an exact solve from here
                logger.info("friction iteration %d: settled on an inexact solve; solved again exactly",
                            len(self.history))
                self.state, self.sign, self.beta, self.rtol = it.state, it.sign, it.beta, None
                continue
            if it.settled:
                return it.u, {"lambda": it.lam_n, "lambda_t": it.lam_t, "state": self.state, "sign": self.sign,
                              "active": self.state != OPEN, "iterations": len(self.history),
                              "history": self.history}
            if it.same_states and self.k > 1:  # the same states, the directions still turning: not a cycle
                self.sign, self.beta = it.sign, it.beta
                continue
            this = self.key(it.state, it.sign)
            if this in self.seen:
                done = self.cycle(it, this)
                if done is not None:
                    return done
                continue
            self.seen[this] = len(self.history)
            self.state, self.sign, self.beta = it.state, it.sign, it.beta
        raise ContactError(f"the friction states did not settle in {self.opts.max_active_set_iterations} "
                           f"iterations (states per iteration: {self.history}); if the counts were still moving "
                           "toward a settled set, raise options.max_active_set_iterations; if they wander, split "
                           "the load into more increments (options.load_steps)")

    def step(self) -> _Iterate:
        """One linear solve with the current states, its iterate recorded
        (with its violation) and classified; sets the next solve's Krylov
        tolerance (loose, or the forcing term once the states repeat)."""
        cs, k = self.cs, self.k
        u, lam_n, lam_t, Bu, Btu = self.saddle(self.state, self.sign, self.bound, self.beta, self.x0, self.rtol)
        exact, self.rtol = self.rtol is None, self.loose  # (the next solve's: loose unless said otherwise below)
        self.x0 = np.concatenate([u, lam_n, lam_t])
        gap = cs.stabilized_gap(Bu - self.g_n, self.state != OPEN, lam_n)
        dslip = per_multiplier(Btu - self.g_t - self.s_old, k)
        tau = per_multiplier(-lam_t, k)
        self.iterates[len(self.history)] = (u, lam_n, lam_t, self.state, self.sign,
                                            violation(-lam_n, tau, gap, dslip, self.lumped, self.c, self.mu,
                                                      self.state, self.sign, self.bound))
        new_state, new_sign, new_beta = classify(-lam_n, tau, gap, dslip, self.lumped, self.c, self.mu,
                                                 self.bilateral, self.state, self.sign, self.bound, newton=True)
        counts = {name: int(np.count_nonzero(new_state == code)) for code, name in STATE_NAMES.items()}
        self.history.append(counts)
        logger.info("friction iteration %d: %d open, %d stick, %d slip", len(self.history), counts["open"],
                    counts["stick"], counts["slip"])
        same_states = bool(np.array_equal(new_state, self.state))
        if k == 1:
            settled = same_states and np.array_equal(np.sign(new_sign), np.sign(self.sign))
        else:
            turn = float(np.abs(new_sign - self.sign).max(initial=0.0))
            settled = same_states and turn <= DIRECTION_TOLERANCE
            if same_states and not settled:
                logger.info("friction iteration %d: slip directions turned by up to %.2g", len(self.history), turn)
                if self.rtol is not None:  # Newton on the directions: the forcing term
                    forcing = FORCING * turn ** 2
                    self.rtol = None if forcing <= EXACT_BELOW else min(self.rtol, forcing)
        return _Iterate(u, lam_n, lam_t, exact, new_state, new_sign, new_beta, same_states, bool(settled))

    def cycle(self, it: _Iterate, this: bytes) -> tuple[np.ndarray, dict] | None:
        """The states of `it` were met before: go on exactly (an inexact
        cycle), start again from the first states exactly (the exact solves
        went on from an inexact cycle and cycle too), or settle the cycle by
        its iterate of least violation (returned) or raise _Cycle. None: the
        iteration goes on."""
        n = len(self.history)
        if not it.exact:
            # A cycle met with inexact solves: the iteration goes on with exact
            # ones from the states it has reached (warm); where they settle,
            # that is a fixed point of the exact iteration. (Starting again
            # from the first states replayed the whole iteration: the corner
            # crack of demos/scenes/corner_crack_closure.toml at half its sizes
            # took 10 more solves, not 4.)
            logger.info("friction iteration %d: the states came back on an inexact solve; the iteration goes on "
                        "with exact solves", n)
            self.loose = self.rtol = None
            self.state, self.sign, self.beta = it.state, it.sign, it.beta
            self._forget()
            self.went_on = True
            return None
        if self.went_on:
            # They cycle too: which iterate of a cycle is taken depends on the
            # path, so the iteration starts again from the first states with
            # exact solves, and takes the exact iteration's.
            logger.info("friction iteration %d: the states cycle; the iteration starts again from the first "
                        "states with exact solves", n)
            (self.state, self.sign), self.beta = self.first, None
            self._forget()
            self.went_on = False
            return None
        first = self.seen[this]
        flips = np.flatnonzero(self.state != it.state)
        best = min((i for i in self.iterates if i >= first), key=lambda i: self.iterates[i][5])
        bu, bn, bt, bs, bg, bv = self.iterates[best]
        logger.debug("cycle violations: %s", {i: self.iterates[i][5] for i in self.iterates if i >= first})
        if bv <= CYCLE_TOLERANCE:
            note = (f"the friction states cycled (period {n - first}, multipliers {flips[:8].tolist()}); the "
                    "iterate of least violation of the contact and friction laws was taken: "
                    f"{bv:.1e} of the largest pressure")
            logger.info("friction: %s", note)
            return bu, {"lambda": bn, "lambda_t": bt, "state": bs, "sign": bg, "active": bs != OPEN,
                        "iterations": n, "history": self.history, "note": note, "violation": bv}
        raise _Cycle(f"the friction states cycle: iteration {n} gives the states of "
                     f"{'the start' if first == self.start else f'iteration {first}'} again (period "
                     f"{n - first}); multipliers {flips[:8].tolist()} flip between "
                     + ", ".join(f"{STATE_NAMES[int(a)]}/{STATE_NAMES[int(b)]}" for a, b in
                                 zip(self.state[flips[:8]], it.state[flips[:8]])), it.lam_n, it.state, it.sign)
