"""The study's problems, each with its exact reference from :mod:`mechanics`: the free
top, the heavy top, the physical pendulum and the pendulum striking a wall; the
records of one run and of one problem.

Part of :mod:`bench.workprecision` (its docstring states the conventions).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from mechanics._floats import EPS
from mechanics.dynamics import pendulum_motion, pendulum_period
from mechanics.impact import direct_impact
from mechanics.integrators import (
    free_rigid_body_rhs,
    free_rigid_body_splitting,
    integrate,
    rigid_body_parts,
    rigid_body_state,
    time_grid,
)
from mechanics.tops import FreeAsymmetricTop, HeavySymmetricTop

from .settings import FINAL_PHASE, FREE_TOP_ROTATIONS, SCIPY_METHODS, SCIPY_STAGES, TARGET_ERROR


@dataclass
class Run:
    """One solve: its error and work (time is added by the sweep)."""

    error: float
    steps: int | None
    rhs_evals: int | None
    rejected_steps: int | None
    parts: dict = field(default_factory=dict)


@dataclass
class Problem:
    """A reference problem: its methods as ``{name: (param_name, [params], runner)}``.

    ``runner(param) -> Run`` solves the problem once.  ``exact`` has no parameter.
    """

    name: str
    title: str
    description: str
    horizon: float
    error_measure: str
    methods: dict[str, tuple[str | None, list, Callable[..., Run]]]
    #: If set, each method whose sweep brackets this error gets one more run at the
    #: parameter interpolated (log-log) to reach it, nudged 10 % to the accurate side.
    target: float | None = None
    #: The initial state and the error of a final state (``score(y) -> Run``), for
    #: methods added from outside (the tests add deliberately broken ones).
    y0: np.ndarray | None = None
    score: Callable[..., Run] | None = None


@functools.cache
def compiled(f):
    """``f`` compiled by numba (the ``[fast]`` extra), so that :func:`integrate` runs it on
    its compiled path, or ``f`` itself without numba (integrate's pure-numpy reference path
    then runs it, as any Python function: the study's "ours" are then that path's).  scipy
    gets the Python ``f``: it calls its right-hand side from Python either way.

    One numba function per ``f``, kept: the pendulum's right-hand side serves two
    problems (the pendulum and the impact), and numba compiles each new function object
    afresh at its first call (~1.1 s measured), however often the problems are built."""
    try:
        from numba import njit
    except ImportError:
        return f
    return njit(f)


#: The PI step control's gain of the ``dop853-pi`` runs (Hairer's DOPRI5 default; the
#: value measured best of 0.04 and 0.08 on the heavy top and the pendulum).
PI_BETA = 0.04


def _warm(rhs, y0, event=None) -> None:
    """One tiny run of each compiled method on ``rhs`` (and its event), so that numba's
    conversion of a new function is paid before anything is timed."""
    integrate(rhs, y0, (0.0, 1e-3), method="rk4", h=1e-3)
    integrate(rhs, y0, (0.0, 1e-3), method="dop853", rtol=1e-6, beta=PI_BETA)
    if event is not None:
        integrate(rhs, y0, (0.0, 1e-3), method="dop853", rtol=1e-6, event=event)


def _scipy_work(sol, method: str) -> tuple[int, int, int | None]:
    steps = len(sol.t) - 1
    if method in SCIPY_STAGES:
        attempts = (sol.nfev - 2) // SCIPY_STAGES[method]
        return steps, int(sol.nfev), max(attempts - steps, 0)
    return steps, int(sol.nfev), None


def _our_options(method: str, period: float, p: float) -> dict:
    """integrate's options for one of our runs: rk4's step (p steps per period), dop853's
    rtol = p, and the PI control's β for ``dop853-pi``."""
    if method == "rk4":
        return {"h": period / p}
    return {"rtol": p, "beta": PI_BETA if method.endswith("-pi") else 0.0}


def _sweeps(quick: bool, n_quick: list, n_full: list) -> tuple[list, list, list]:
    """(rk4's steps per period, our rtols, scipy's rtols): the quick run's two points, or
    the full sweep.  Ours reach 1e-16 (the compiled runs are cheap there, and the
    pendulum near its separatrix needs it for 1e-9); scipy's stop at 1e-13, near its
    floor of 100 eps (below it solve_ivp raises rtol to 2.2e-14)."""
    if quick:
        return n_quick, [1e-8, 1e-11], [1e-6, 1e-9]
    return n_full, [1e-7, 1e-9, 1e-11, 1e-13, 1e-15, 1e-16], [1e-6, 1e-8, 1e-10, 1e-12, 1e-13]


def _scipy_solve(rhs, y0, t1, method, rtol, **kw):
    sol = solve_ivp(rhs, (0.0, t1), y0, method=method, rtol=rtol, atol=rtol, **kw)
    if sol.status < 0:
        raise RuntimeError(f"solve_ivp {method} rtol={rtol}: {sol.message}")
    return sol


FREE_J = np.array([1.0, 2.0, 3.0])
FREE_W0 = np.array([0.4, 0.2, 1.0])
# proper signed permutation to the axis order (J_mid, J_max, J_min) for the splitting
_PERM = np.eye(3)[[1, 2, 0]]  # a cyclic permutation: det = +1


def _free_top_problem(quick: bool) -> Problem:
    J, w0 = FREE_J, FREE_W0
    rot = 2 * math.pi / float(np.linalg.norm(w0))
    T = FREE_TOP_ROTATIONS[quick] * rot
    top = FreeAsymmetricTop(J, w0)
    w_T, R_T = top.omega(T), top.attitude(T)
    wn = float(np.linalg.norm(w0))
    L0 = J * w0
    y0 = rigid_body_state(L0, np.eye(3))
    rhs = free_rigid_body_rhs(J)

    def err_state(y) -> Run:
        L, R = rigid_body_parts(np.asarray(y))
        ew = float(np.abs(L / J - w_T).max()) / wn
        eR = float(np.abs(R - R_T).max())
        return Run(max(ew, eR), None, None, None, {"omega": ew, "attitude": eR})

    def exact(_=None) -> Run:
        # one evaluation of the exact motion (the top's construction, its elliptic
        # parameters, is setup: it is timed apart, see exact_evaluation)
        t = top
        w, R = t.state(float(T))
        # independent residuals: energy and |L| of ω(T), and L_O = Rᵀ J ω fixed in space
        E = 0.5 * float((J * w * w).sum())
        L_O = R.T @ (J * w)
        res = max(
            abs(E / t.energy - 1),
            float(np.abs(L_O - t.angular_momentum_space).max()) / t.angular_momentum_norm,
            float(np.abs(R @ R.T - np.eye(3)).max()),
        )
        return Run(res, 0, 0, 0, {"kind": "residual of the invariants"})

    def rk4(n) -> Run:
        s = integrate(rhs, y0, (0.0, T), method="rk4", h=rot / n)
        r = err_state(s.y[-1])
        r.steps, r.rhs_evals, r.rejected_steps = s.steps, s.rhs_evals, s.rejected_steps
        return r

    def dop(rtol) -> Run:
        s = integrate(rhs, y0, (0.0, T), method="dop853", rtol=rtol)
        r = err_state(s.y[-1])
        r.steps, r.rhs_evals, r.rejected_steps = s.steps, s.rhs_evals, s.rejected_steps
        return r

    def split(order, compensated=False):
        def run(n) -> Run:
            s = free_rigid_body_splitting(
                J[[1, 2, 0]],
                _PERM @ L0,
                _PERM,
                (0.0, T),
                rot / n,
                order=order,
                compensated=compensated,
            )
            L, R = rigid_body_parts(s.y[-1])
            r = err_state(rigid_body_state(_PERM.T @ L, _PERM.T @ R))
            r.steps, r.rhs_evals, r.rejected_steps = s.steps, s.rhs_evals, 0
            return r

        return run

    def sp(method):
        def run(rtol) -> Run:
            sol = _scipy_solve(rhs, y0, T, method, rtol)
            r = err_state(sol.y[:, -1])
            r.steps, r.rhs_evals, r.rejected_steps = _scipy_work(sol, method)
            return r

        return run

    if quick:
        sw = {
            "rk4": [25, 50],
            "dop853": [1e-8, 1e-11, 1e-13],
            "splitting-2": [100, 200],
            "splitting-4": [25, 50],
            "splitting-6": [25, 50],
            "splitting-8": [25, 50],
            "splitting-6-kahan": [25, 50],
            "splitting-8-kahan": [25, 50],
            "RK45": [1e-6, 1e-8],
            "DOP853": [1e-8, 1e-11],
            "LSODA": [1e-6, 1e-8],
            "Radau": [1e-4, 1e-6],
        }
    else:  # each method over its part of 1e-3 … 1e-13 (the compiled ones are cheap)
        sw = {
            "rk4": [50, 100, 200, 400, 800, 1600, 3200, 6400],
            "dop853": [1e-6, 1e-8, 1e-10, 1e-12, 1e-13, 1e-14, 1e-15, 1e-16],
            # (10⁴ per rotation over 1000 rotations is the splitting's step budget, 10⁷)
            "splitting-2": [200, 800, 3200, 10000],
            "splitting-4": [50, 100, 200, 400, 800, 1600],
            "splitting-6": [50, 100, 200, 400, 800, 1600],
            "splitting-8": [25, 50, 100, 200, 400, 800],
            # compensated: where rounding, not truncation, sets the error
            "splitting-6-kahan": [400, 800, 1600, 3200],
            "splitting-8-kahan": [100, 200, 400, 800],
            "RK45": [1e-6, 1e-8, 1e-10],
            "DOP853": [1e-6, 1e-8, 1e-10, 1e-12, 1e-13, 1e-14],
            "LSODA": [1e-6, 1e-8, 1e-10, 1e-12],
            "Radau": [1e-4, 1e-6, 1e-8],
        }
    methods = {
        "exact": (None, [None], exact),
        "rk4": ("steps per rotation", sw["rk4"], rk4),
        "dop853": ("rtol", sw["dop853"], dop),
    }
    for order in (2, 4, 6, 8):
        methods[f"splitting-{order}"] = (
            "steps per rotation",
            sw[f"splitting-{order}"],
            split(order),
        )
    for order in (6, 8):
        methods[f"splitting-{order}-kahan"] = (
            "steps per rotation",
            sw[f"splitting-{order}-kahan"],
            split(order, compensated=True),
        )
    for m in SCIPY_METHODS:
        methods[f"scipy-{m}"] = ("rtol", sw[m], sp(m))
    return Problem(
        "free_top",
        f"Free asymmetric top, {FREE_TOP_ROTATIONS[quick]} rotations",
        "J = (1, 2, 3), ω0 = (0.4, 0.2, 1.0), identity attitude; rotation = 2π/|ω0|",
        T,
        "max(|Δω_A|/|ω0|, |Δ ^A R^O|) at the final time",
        methods,
        target=TARGET_ERROR,
        y0=y0,
        score=err_state,
    )


HEAVY = {"J_1": 1.0, "J_3": 0.5, "m_g_ell": 1.0}
HEAVY_INIT = {
    "theta": 1.0,
    "psi": 0.0,
    "phi": 0.0,
    "theta_dot": 0.0,
    "psi_dot": 0.3,
    "phi_dot": 3.0,
}


def heavy_top_rhs(J_1: float, J_3: float, m_g_ell: float, L_z: float, L_3: float):
    """rhs(t, y) of the heavy symmetric top in y = (θ, ψ, φ, θ̇), cyclic momenta fixed."""

    def rhs(t, y):
        th = y[0]
        s, c = math.sin(th), math.cos(th)
        a = L_z - L_3 * c
        psid = a / (J_1 * s * s)
        thdd = (m_g_ell * s - a * (L_3 - L_z * c) / (J_1 * s * s * s)) / J_1
        return np.array([y[3], psid, L_3 / J_3 - psid * c, thdd])

    return rhs


def _heavy_top_problem(quick: bool) -> Problem:
    from scipy.special import ellipk

    top = HeavySymmetricTop(**HEAVY, **HEAVY_INIT)
    Tn = 2.0 * float(ellipk(top._m)) / top._kappa  # sn² has period 2K in its argument
    periods = 10 if quick else 100
    T = (periods + FINAL_PHASE) * Tn
    ex = np.array([float(top.theta(T)), float(top.psi(T)), float(top.phi(T))])
    rhs = heavy_top_rhs(HEAVY["J_1"], HEAVY["J_3"], HEAVY["m_g_ell"], top.L_z, top.L_3)
    rhs_c = compiled(rhs)
    y0 = np.array(
        [HEAVY_INIT["theta"], HEAVY_INIT["psi"], HEAVY_INIT["phi"], HEAVY_INIT["theta_dot"]]
    )
    _warm(rhs_c, y0)

    def err(y) -> Run:
        d = np.abs(np.asarray(y)[:3] - ex)
        return Run(
            float(d.max()),
            None,
            None,
            None,
            {"theta": float(d[0]), "psi": float(d[1]), "phi": float(d[2])},
        )

    def exact(_=None) -> Run:
        t = HeavySymmetricTop(**HEAVY, **HEAVY_INIT)
        t.theta(T), t.psi(T), t.phi(T)
        Lz, L3, E = t.integrals_at(np.array([T]))
        res = max(abs(float(Lz[0]) - t.L_z), abs(float(L3[0]) - t.L_3), abs(float(E[0]) - t.energy))
        return Run(res, 0, 0, 0, {"kind": "residual of the integrals L_z, L3, E"})

    def ours(method):
        def run(p) -> Run:
            kw = _our_options(method, Tn, p)
            s = integrate(rhs_c, y0, (0.0, T), method=method.removesuffix("-pi"), **kw)
            r = err(s.y[-1])
            r.steps, r.rhs_evals, r.rejected_steps = s.steps, s.rhs_evals, s.rejected_steps
            return r

        return run

    def sp(method):
        def run(rtol) -> Run:
            sol = _scipy_solve(rhs, y0, T, method, rtol)
            r = err(sol.y[:, -1])
            r.steps, r.rhs_evals, r.rejected_steps = _scipy_work(sol, method)
            return r

        return run

    n, tols, stols = _sweeps(quick, [25, 50], [25, 50, 100, 200, 400])
    methods = {
        "exact": (None, [None], exact),
        "rk4": ("steps per nutation", n, ours("rk4")),
        "dop853": ("rtol", tols, ours("dop853")),
        "dop853-pi": ("rtol", tols, ours("dop853-pi")),
    }
    for m in SCIPY_METHODS:
        methods[f"scipy-{m}"] = ("rtol", stols, sp(m))
    return Problem(
        "heavy_top",
        f"Heavy symmetric top, {periods + FINAL_PHASE} nutation periods",
        "J'1 = 1, J3 = 0.5, mgℓ = 1; θ0 = 1, θ̇0 = 0, ψ̇0 = 0.3, φ̇0 = 3",
        T,
        "max(|Δθ|, |Δψ|, |Δφ|) at the final time",
        methods,
        y0=y0,
        score=err,
    )


PEND = (1.0, 1.0, 1.0, 1.0)  # J_axis, m, g, h: ω0 = 1


def pendulum_rhs(t, y):
    """φ̈ = −(m g h/J) sin φ with ω0 = 1, y = (φ, φ̇)."""
    return np.array([y[1], -math.sin(y[0])])


def _pendulum_problem(quick: bool) -> Problem:
    th0 = 3.0
    P = float(pendulum_period(*PEND, th0))
    periods = 10 if quick else 100
    T = (periods + FINAL_PHASE) * P
    ex = float(pendulum_motion(T, *PEND, th0))
    y0 = np.array([th0, 0.0])
    rhs_c = compiled(pendulum_rhs)
    _warm(rhs_c, y0)

    def exact(_=None) -> Run:
        phi = float(pendulum_motion(T, *PEND, th0))
        # independent residual: the same phase a whole number of periods earlier
        back = float(pendulum_motion(T - periods * float(pendulum_period(*PEND, th0)), *PEND, th0))
        return Run(abs(phi - back), 0, 0, 0, {"kind": "periodicity residual"})

    def ours(method):
        def run(p) -> Run:
            kw = _our_options(method, P, p)
            s = integrate(rhs_c, y0, (0.0, T), method=method.removesuffix("-pi"), **kw)
            return Run(abs(float(s.y[-1][0]) - ex), s.steps, s.rhs_evals, s.rejected_steps)

        return run

    def sp(method):
        def run(rtol) -> Run:
            sol = _scipy_solve(pendulum_rhs, y0, T, method, rtol)
            return Run(abs(float(sol.y[0, -1]) - ex), *_scipy_work(sol, method))

        return run

    n, tols, stols = _sweeps(quick, [100, 200], [100, 200, 400, 800, 1600])
    methods = {
        "exact": (None, [None], exact),
        "rk4": ("steps per period", n, ours("rk4")),
        "dop853": ("rtol", tols, ours("dop853")),
        "dop853-pi": ("rtol", tols, ours("dop853-pi")),
    }
    for m in SCIPY_METHODS:
        methods[f"scipy-{m}"] = ("rtol", stols, sp(m))
    return Problem(
        "pendulum",
        f"Physical pendulum, θ0 = 3.0, {periods + FINAL_PHASE} periods",
        "J = m = g = h = 1 (ω0 = 1), released from rest at θ0 = 3.0 rad",
        T,
        "|Δφ| at the final time",
        methods,
        y0=y0,
        score=lambda y: Run(abs(float(y[0]) - ex), None, None, None),
    )


IMPACT_THETA0 = 2.5
IMPACT_E = 0.9


def _rebound(phidot: float) -> float:
    """φ̇ after the pendulum (X = −φ, approaching the wall) strikes the immovable wall."""
    v1f, _ = direct_impact(0.0, 1.0, -phidot, 0.0, IMPACT_E)
    return -float(v1f)


def _impact_exact(n_impacts: int):
    """Closed-form impact times, amplitudes after each impact, final time and φ there."""
    times, amps = [], []
    t = float(pendulum_period(*PEND, IMPACT_THETA0)) / 4
    th = IMPACT_THETA0
    for _ in range(n_impacts):
        times.append(t)
        v_in = -2.0 * math.sin(th / 2)  # ω0 = 1: φ̇ at the bottom, by energy (4.74)
        v_out = _rebound(v_in)
        th = 2.0 * math.asin(v_out / 2.0)
        amps.append(th)
        t = t + float(pendulum_period(*PEND, th)) / 2
    Tn = float(pendulum_period(*PEND, th))
    t_end = times[-1] + Tn / 8
    phi_end = float(pendulum_motion(t_end - times[-1] - Tn / 4, *PEND, th))
    return np.array(times), np.array(amps), t_end, phi_end


def _locate(advance, y, t, s0, tol):
    """Newton on s for φ(t + s) = 0 along ``advance(y, t, s)`` (the stepper's own map)."""
    s = s0
    yk = advance(y, t, s)
    for _ in range(8):
        ds = -yk[0] / yk[1]
        s = s + ds
        yk = advance(y, t, s)
        if abs(ds) <= tol * max(1.0, t):
            break
    return s, yk


def wall(t, y):
    """The wall's event function: φ, which falls through 0 at an impact."""
    return y[0]


def _impact_events(method: str, p: float, n_impacts: int, t_end: float, rhs, event):
    """``dop853`` with :func:`integrate`'s terminal event: one run per flight, stopped
    where φ falls through 0 (located on the step's continuous extension)."""
    kw = _our_options(method, 2 * math.pi, p)
    work = {"steps": 0, "rhs": 0, "rej": 0}
    y = np.array([IMPACT_THETA0, 0.0])
    t = 0.0
    times = []
    while len(times) < n_impacts:
        sol = integrate(
            rhs, y, (t, t + 100.0), method="dop853", event=event, event_direction=-1, **kw
        )
        work["steps"] += sol.steps
        work["rhs"] += sol.rhs_evals
        work["rej"] += sol.rejected_steps
        if sol.t_event is None or sol.y_event is None:
            raise RuntimeError(f"{method}: no impact found after t={t}")
        t = sol.t_event
        times.append(t)
        y = np.array([0.0, _rebound(float(sol.y_event[1]))])
    sol = integrate(rhs, y, (t, t_end), method="dop853", **kw)
    work["steps"] += sol.steps
    work["rhs"] += sol.rhs_evals
    work["rej"] += sol.rejected_steps
    return np.array(times), float(sol.y[-1][0]), work


def _impact_rk4(p: float, n_impacts: int, t_end: float, rhs=pendulum_rhs):
    """RK4 (``p`` steps per 2π/ω0) with the impact located by hand, RK4 having no events:
    outputs every step, the first output with φ ≤ 0 brackets the impact, Newton on the
    step's own map refines it by re-stepping."""
    work = {"steps": 0, "rhs": 0, "rej": 0}

    def advance(y, t, s):
        sol = integrate(rhs, y, (t, t + s), method="rk4", h=s)
        work["steps"] += sol.steps
        work["rhs"] += sol.rhs_evals
        return sol.y[-1]

    h = 2 * math.pi / p
    chunk = 64
    y = np.array([IMPACT_THETA0, 0.0])
    t = 0.0
    times = []
    while len(times) < n_impacts:
        grid = time_grid(t, h, chunk)
        sol = integrate(rhs, y, grid, method="rk4", h=h)
        work["steps"] += sol.steps
        work["rhs"] += sol.rhs_evals
        hit = np.nonzero(sol.y[1:, 0] <= 0.0)[0]
        if hit.size == 0:
            y, t = sol.y[-1].copy(), float(grid[-1])
            continue
        k = int(hit[0])
        yk, tk = sol.y[k], float(grid[k])
        ya, yb = float(yk[0]), float(sol.y[k + 1][0])
        s0 = h * ya / (ya - yb) if ya != yb else h
        s, ye = _locate(advance, yk, tk, s0, 4 * EPS)
        t = tk + s
        times.append(t)
        y = np.array([0.0, _rebound(float(ye[1]))])
    sol = integrate(rhs, y, (t, t_end), method="rk4", h=h)
    work["steps"] += sol.steps
    work["rhs"] += sol.rhs_evals
    return np.array(times), float(sol.y[-1][0]), work


def _impact_scipy(method: str, rtol: float, n_impacts: int, t_end: float):
    def wall(t, y):
        return y[0]

    wall.terminal = True
    wall.direction = -1
    y = np.array([IMPACT_THETA0, 0.0])
    t = 0.0
    times = []
    steps = nfev = 0
    rej: int | None = 0
    while len(times) < n_impacts:
        sol = solve_ivp(
            pendulum_rhs, (t, t + 100.0), y, method=method, rtol=rtol, atol=rtol, events=wall
        )
        st, nf, rj = _scipy_work(sol, method)
        steps, nfev = steps + st, nfev + nf
        rej = None if rj is None or rej is None else rej + rj
        if sol.status != 1:
            raise RuntimeError(f"solve_ivp {method}: no impact found after t={t}")
        t = float(sol.t_events[0][0])
        times.append(t)
        y = np.array([0.0, _rebound(float(sol.y_events[0][0][1]))])
    sol = solve_ivp(pendulum_rhs, (t, t_end), y, method=method, rtol=rtol, atol=rtol)
    st, nf, rj = _scipy_work(sol, method)
    rej = None if rj is None or rej is None else rej + rj
    return np.array(times), float(sol.y[0, -1]), {"steps": steps + st, "rhs": nfev + nf, "rej": rej}


def _impact_problem(quick: bool) -> Problem:
    n_imp = 6 if quick else 30
    ex_times, _, t_end, phi_end = _impact_exact(n_imp)

    def score(times, phi, work) -> Run:
        dt = float(np.abs(times - ex_times).max())
        dphi = abs(phi - phi_end)
        return Run(
            max(dt, dphi),
            work["steps"],
            work["rhs"],
            work["rej"],
            {"impact_times": dt, "final_angle": dphi},
        )

    def exact(_=None) -> Run:
        _, amps, _, _ = _impact_exact(n_imp)
        # independent residual: φ of each closed-form flight vanishes at the next impact
        before = np.concatenate([[IMPACT_THETA0], amps[:-1]])
        periods = np.array([float(pendulum_period(*PEND, a)) for a in before])
        res = float(np.abs(pendulum_motion(periods / 4, *PEND, before)).max())
        return Run(res, 0, 0, 0, {"kind": "|φ| of the closed form at the impact times"})

    rhs_c, wall_c = compiled(pendulum_rhs), compiled(wall)
    _warm(rhs_c, np.array([IMPACT_THETA0, 0.0]), wall_c)

    def ours(method):
        def run(p) -> Run:
            if method == "rk4":
                return score(*_impact_rk4(p, n_imp, t_end, rhs_c))
            return score(*_impact_events(method, p, n_imp, t_end, rhs_c, wall_c))

        return run

    def sp(method):
        def run(rtol) -> Run:
            return score(*_impact_scipy(method, rtol, n_imp, t_end))

        return run

    n, tols, stols = _sweeps(quick, [50, 100], [50, 100, 200, 400])
    methods = {
        "exact": (None, [None], exact),
        "rk4": ("steps per 2π/ω0", n, ours("rk4")),
        "dop853": ("rtol", tols, ours("dop853")),
        "dop853-pi": ("rtol", tols, ours("dop853-pi")),
    }
    for m in SCIPY_METHODS:
        methods[f"scipy-{m}"] = ("rtol", stols, sp(m))
    return Problem(
        "impact",
        f"Pendulum striking a wall, e = {IMPACT_E}, {n_imp} impacts",
        f"J = m = g = h = 1, released from θ0 = {IMPACT_THETA0}; wall at φ = 0; "
        "impacts located as events",
        t_end,
        "max(worst |Δt_impact|·ω0, |Δφ| at T(θ_N)/8 after the last impact)",
        methods,
    )


def reference_problems(quick: bool) -> list[Problem]:
    """The four problems of the study (module Conventions), in report order."""
    return [
        _free_top_problem(quick),
        _heavy_top_problem(quick),
        _pendulum_problem(quick),
        _impact_problem(quick),
    ]
