"""What accuracy costs in time: a work-precision study of the integrators (issue 6).

Conventions
-----------
- **Problems** (each with an exact reference from :mod:`mechanics`):

  ``free_top``
      The free asymmetric top J = (1, 2, 3), ω0 = (0.4, 0.2, 1.0) (it circulates the
      axis of largest moment), identity attitude, over :data:`FREE_TOP_ROTATIONS`
      rotations (one rotation = 2π/|ω0|; ``--quick``: 20).  Error: the larger of
      max |ω_A − ω_A^exact| / |ω0| and max |^A R^O − ^A R^O_exact| at the final time,
      against :class:`mechanics.tops.FreeAsymmetricTop`.  State: the 12-vector
      (L_A, rows of ^A R^O) of :func:`mechanics.integrators.rigid_body_state`.
  ``heavy_top``
      The heavy symmetric top J'1 = 1, J3 = 0.5, mgℓ = 1 from θ = 1, θ̇ = 0,
      ψ̇ = 0.3, φ̇ = 3 (nutation between the roots u1, u2), over 100.3 nutation
      periods (``--quick``: 10.3; see :data:`FINAL_PHASE`).  State (θ, ψ, φ, θ̇) with the conserved momenta
      L_z, L3 of the cyclic angles (5.53), (5.55): ψ̇ = (L_z − L3 cos θ)/(J'1 sin²θ),
      φ̇ = L3/J3 − ψ̇ cos θ, J'1 θ̈ = −dΦ_eff/dθ = mgℓ sin θ − (L_z − L3 cos θ)
      (L3 − L_z cos θ)/(J'1 sin³θ).  Error: max of |Δθ|, |Δψ|, |Δφ| at the final time
      against :class:`mechanics.tops.HeavySymmetricTop`.
  ``pendulum``
      The physical pendulum J = m = g = h = 1 (ω0 = 1) released from rest at
      θ0 = 3.0 rad, over 100.3 periods (``--quick``: 10.3).  Error |Δφ| at the final
      time against :func:`mechanics.dynamics.pendulum_motion`.
  ``impact``
      The same pendulum released from θ0 = 2.5 against a rigid wall at φ = 0
      (restitution e = 0.9), over 30 impacts (``--quick``: 6).  Each impact is an
      event φ = 0, φ̇ < 0, located by the stepper; the wall is a body of infinite
      mass, so :func:`mechanics.impact.direct_impact` with m_1 = 0 gives φ̇ → −e φ̇.
      The exact motion: the first impact at T(θ0)/4, after impact n the amplitude
      θ_n has sin(θ_n/2) = |φ̇_n|/2ω0 (energy (4.74)), the next impact comes T(θ_n)/2
      later (:func:`mechanics.dynamics.pendulum_period`) and the flight in between
      is ``pendulum_motion`` shifted by T(θ_n)/4.  Error: the larger of the worst
      impact-time error (× ω0) and |Δφ| at a final time T(θ_N)/8 after the last
      impact.  (A ball bouncing on a floor was the first choice, but its flight is a
      parabola that RK4 and DOP853 integrate exactly: the study would time only the
      root finder.)
- **Methods.**  ``exact`` (the closed form evaluated at the final time; for the free
  top one ``FreeAsymmetricTop.state`` call on a top built beforehand, its construction
  timed apart in :func:`exact_evaluation`; its "error" is an independent residual: the
  invariants of the exact motion, or for the impact scene |φ| at the closed-form impact
  times), ``rk4`` (fixed step h), ``dop853`` (ours, rtol = atol), ``splitting-2/4/6/8``
  and ``splitting-6/8-kahan`` (compensated summation; free top only,
  :func:`mechanics.integrators.free_rigid_body_splitting`), and scipy's ``solve_ivp``
  with ``RK45``, ``DOP853``, ``LSODA``, ``Radau`` (rtol = atol) on the same right-hand
  side.  On the free top ours run compiled (numba; :func:`warm_compiled` loads every
  kernel before anything is timed).  The splitting runs in the body frame relabelled (a
  proper signed permutation) to the axis order (J_mid, J_max, J_min): of the six orders
  this one was measured best for this top (order 6, 40 steps per flip period, 100
  periods: 2.2e-4 against 1.3e-3 for (J_min, J_mid, J_max) and 6e-2 for the worst).
  The sweeps cover 1e-3 … 1e-12 on the free top (below, the exact solution's own error
  at 1000 rotations, up to 5e-12 by its measured bound, is as large as the methods').
- **Time** is ``time.perf_counter`` around the whole solve (setup and validation
  included), the median of ``repeats`` runs; a run longer than :data:`LONG_RUN_S`
  is timed once (its spread is small against its length; the JSON records
  ``runs``).  A method's sweep stops when a run exceeds its budget
  (:data:`BUDGET_S`), so the full run stays within a few minutes; skipped points
  are listed in the JSON.
- **Work**: accepted ``steps``, ``rhs_evals`` (sub-flows for the splitting) and
  ``rejected_steps``; for scipy's Runge–Kutta methods the rejections are
  (nfev − 2)/stages − steps (scipy counts f(t0) and the initial-step probe),
  for LSODA they are unknown (``null``).
- **Outputs** (in ``out_dir``): ``workprecision.json``, ``workprecision.md``,
  ``workprecision.png`` (log-log error against time, one panel per problem) and
  ``energy_drift.png`` (relative energy error of the free top against the horizon,
  10 to 10⁴ rotations).  Matplotlib is imported lazily with the Agg backend.
  Errors below :data:`ERROR_FLOOR` are plotted at the floor.

Headline (``headline`` in the JSON, every ratio of two times measured in the same run;
:func:`headline`): issue 15's targets as rows with a status ("met", "must met, goal
not", "NOT MET", "not measured"): our fastest stepper at scipy DOP853's most accurate
error (goal ≥ 10, must ≥ 3); the exact solution's one evaluation against that DOP853
run (≥ 1e5); at each error 1e-4 … 1e-12 (:data:`DECADES`) our fastest run reaching it
against scipy's fastest (at least as fast); :func:`batched_vs_scipy` (≥ 50); and
:func:`mujoco_peer` (MuJoCo's RK4 at dt 1e-3 against our fastest at its error; without
``mujoco`` the row names the extra).  Also the energy drift's growth and the batch
against one body (issue 6).
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import os
import platform
import statistics
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

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
from mechanics.rotation import EPS
from mechanics.tops import FreeAsymmetricTop, HeavySymmetricTop

__all__ = [
    "BUDGET_S",
    "ERROR_FLOOR",
    "FREE_TOP_ROTATIONS",
    "LONG_RUN_S",
    "SCHEMA",
    "TARGET_ERROR",
    "Problem",
    "heavy_top_rhs",
    "main_bench",
    "pendulum_rhs",
    "reference_problems",
    "run_study",
    "summary_lines",
]

SCHEMA = "bodycheck.workprecision/2"
#: The error of the headline comparison on the free top (issue 6).
TARGET_ERROR = 1e-10
#: The error levels of the per-decade comparison (issue 15): ours at least as fast as
#: scipy's best at each.
DECADES = tuple(10.0**-k for k in range(4, 13))
#: Issue 15's targets, as (goal, must) ratios of scipy's time to ours.
STEPPER_GOAL, STEPPER_MUST = 10.0, 3.0
EXACT_GOAL = 1e5
BATCH_GOAL = 50.0
#: The batch of free bodies against scipy body by body (full run, quick run): bodies,
#: bodies scipy runs (its time is scaled to the batch), tolerance, horizon (one
#: rotation at |ω| = 1).
BATCH_BODIES = {False: 10**4, True: 200}
BATCH_SCIPY_SAMPLE = {False: 20, True: 3}
BATCH_RTOL = 1e-9
BATCH_SEED = 20261125
#: The compiled-engine peer (issue 15): MuJoCo's run quoted in the issue.
MUJOCO_J = (1.0, 2.0, 3.0)
MUJOCO_W0 = (0.02, 1.0, 0.01)
MUJOCO_T = 20.0
MUJOCO_DT = 1e-3
MUJOCO_EXTRA = "pip install -e '.[mujoco]'"
#: Errors are plotted no lower than this (a few eps: the exact references' own accuracy).
ERROR_FLOOR = 4 * EPS
#: Runs longer than this are timed once (seconds).
LONG_RUN_S = 2.0
#: A method's sweep stops after a run longer than this (seconds): full, quick.
BUDGET_S = {False: 30.0, True: 0.6}
#: Rotations of the free top (full run, quick run).
FREE_TOP_ROTATIONS = {False: 1000, True: 20}
SCIPY_METHODS = ("RK45", "DOP853", "LSODA", "Radau")
#: Periodic problems end this fraction of a period past a whole number of periods,
#: so that a method that never moves (the initial state) is not exactly right there.
FINAL_PHASE = 0.3
_SCIPY_STAGES = {"RK45": 6, "DOP853": 12}


# ------------------------------------------------------------------------ records


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


def _scipy_work(sol, method: str) -> tuple[int, int, int | None]:
    steps = len(sol.t) - 1
    if method in _SCIPY_STAGES:
        attempts = (sol.nfev - 2) // _SCIPY_STAGES[method]
        return steps, int(sol.nfev), max(attempts - steps, 0)
    return steps, int(sol.nfev), None


def _scipy_solve(rhs, y0, t1, method, rtol, **kw):
    sol = solve_ivp(rhs, (0.0, t1), y0, method=method, rtol=rtol, atol=rtol, **kw)
    if sol.status < 0:
        raise RuntimeError(f"solve_ivp {method} rtol={rtol}: {sol.message}")
    return sol


# ------------------------------------------------------------------------ free top

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
            "splitting-2": [200, 800, 3200, 12800],
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


# ------------------------------------------------------------------------ heavy top

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
    y0 = np.array(
        [HEAVY_INIT["theta"], HEAVY_INIT["psi"], HEAVY_INIT["phi"], HEAVY_INIT["theta_dot"]]
    )

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
            kw = {"h": Tn / p} if method == "rk4" else {"rtol": p}
            s = integrate(rhs, y0, (0.0, T), method=method, **kw)
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

    if quick:
        n, tols, stols = [25, 50], [1e-8, 1e-11], [1e-6, 1e-9]
    else:
        n, tols, stols = (
            [25, 50, 100, 200, 400],
            [1e-7, 1e-9, 1e-11, 1e-13],
            [1e-6, 1e-8, 1e-10, 1e-12],
        )
    methods = {
        "exact": (None, [None], exact),
        "rk4": ("steps per nutation", n, ours("rk4")),
        "dop853": ("rtol", tols, ours("dop853")),
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


# ------------------------------------------------------------------------ pendulum

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

    def exact(_=None) -> Run:
        phi = float(pendulum_motion(T, *PEND, th0))
        # independent residual: the same phase a whole number of periods earlier
        back = float(pendulum_motion(T - periods * float(pendulum_period(*PEND, th0)), *PEND, th0))
        return Run(abs(phi - back), 0, 0, 0, {"kind": "periodicity residual"})

    def ours(method):
        def run(p) -> Run:
            kw = {"h": P / p} if method == "rk4" else {"rtol": p}
            s = integrate(pendulum_rhs, y0, (0.0, T), method=method, **kw)
            return Run(abs(float(s.y[-1][0]) - ex), s.steps, s.rhs_evals, s.rejected_steps)

        return run

    def sp(method):
        def run(rtol) -> Run:
            sol = _scipy_solve(pendulum_rhs, y0, T, method, rtol)
            return Run(abs(float(sol.y[0, -1]) - ex), *_scipy_work(sol, method))

        return run

    if quick:
        n, tols, stols = [100, 200], [1e-8, 1e-11], [1e-6, 1e-9]
    else:
        n, tols, stols = (
            [100, 200, 400, 800, 1600],
            [1e-7, 1e-9, 1e-11, 1e-13],
            [1e-6, 1e-8, 1e-10, 1e-12],
        )
    methods = {
        "exact": (None, [None], exact),
        "rk4": ("steps per period", n, ours("rk4")),
        "dop853": ("rtol", tols, ours("dop853")),
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


# ------------------------------------------------------------------------ impact scene

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


def _impact_ours(method: str, p: float, n_impacts: int, t_end: float):
    """Our stepper with event location: outputs every step (rk4) or every Δ (dop853),
    the first output with φ ≤ 0 brackets the impact, Newton refines it by re-stepping."""
    rhs = pendulum_rhs
    work = {"steps": 0, "rhs": 0, "rej": 0}

    def advance(y, t, s):
        if method == "rk4":
            sol = integrate(rhs, y, (t, t + s), method="rk4", h=s)
        else:
            sol = integrate(rhs, y, (t, t + s), method="dop853", rtol=p)
        work["steps"] += sol.steps
        work["rhs"] += sol.rhs_evals
        work["rej"] += sol.rejected_steps
        return sol.y[-1]

    h = 2 * math.pi / p if method == "rk4" else 2 * math.pi / 16  # Δ of the output grid
    chunk = 64 if method == "rk4" else 8
    y = np.array([IMPACT_THETA0, 0.0])
    t = 0.0
    times = []
    while len(times) < n_impacts:
        grid = time_grid(t, h, chunk)
        kw = {"h": h} if method == "rk4" else {"rtol": p}
        sol = integrate(rhs, y, grid, method=method, **kw)
        work["steps"] += sol.steps
        work["rhs"] += sol.rhs_evals
        work["rej"] += sol.rejected_steps
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
    kw = {"h": h} if method == "rk4" else {"rtol": p}
    sol = integrate(rhs, y, (t, t_end), method=method, **kw)
    work["steps"] += sol.steps
    work["rhs"] += sol.rhs_evals
    work["rej"] += sol.rejected_steps
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

    def ours(method):
        def run(p) -> Run:
            return score(*_impact_ours(method, p, n_imp, t_end))

        return run

    def sp(method):
        def run(rtol) -> Run:
            return score(*_impact_scipy(method, rtol, n_imp, t_end))

        return run

    if quick:
        n, tols, stols = [50, 100], [1e-8, 1e-11], [1e-6, 1e-9]
    else:
        n, tols, stols = [50, 100, 200, 400], [1e-7, 1e-9, 1e-11, 1e-13], [1e-6, 1e-8, 1e-10, 1e-12]
    methods = {
        "exact": (None, [None], exact),
        "rk4": ("steps per 2π/ω0", n, ours("rk4")),
        "dop853": ("rtol", tols, ours("dop853")),
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


# ------------------------------------------------------------------------ progress


class _Progress:
    """A one-line progress bar on stderr (nothing when disabled)."""

    def __init__(self, total: int, enabled: bool):
        self.total, self.done, self.enabled = max(total, 1), 0, enabled
        self.t0 = time.perf_counter()

    def step(self, label: str) -> None:
        self.done += 1
        if not self.enabled:
            return
        width = 30
        fill = int(width * self.done / self.total)
        el = time.perf_counter() - self.t0
        sys.stderr.write(
            f"\r[{'#' * fill}{'.' * (width - fill)}] {self.done}/{self.total} "
            f"{el:6.1f}s {label[:48]:<48}"
        )
        sys.stderr.flush()

    def close(self) -> None:
        if self.enabled:
            sys.stderr.write("\n")
            sys.stderr.flush()


# ------------------------------------------------------------------------ sweeps


def _timed(fn: Callable[[], Run], repeats: int) -> tuple[Run, float, int]:
    times = []
    run = None
    for i in range(max(repeats, 1)):
        t0 = time.perf_counter()
        run = fn()
        times.append(time.perf_counter() - t0)
        if i == 0 and times[0] > LONG_RUN_S:
            break
    return run, statistics.median(times), len(times)


def _finite_or_none(x):
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def warm_compiled() -> None:
    """Run each compiled kernel once on a tiny problem before anything is timed: the
    first call in a process compiles it (or loads numba's on-disk cache), which costs up
    to seconds on a fresh clone and is not the method's cost (the JIT's cold and warm
    figures are in the README; ``tools/jit_cost.py`` measures them)."""
    J = np.array([1.0, 2.0, 3.0])
    y0 = rigid_body_state(J * np.array([0.4, 0.2, 1.0]), np.eye(3))
    for method, kw in (("rk4", {"h": 0.05}), ("dop853", {"rtol": 1e-6})):
        integrate(free_rigid_body_rhs(J), y0, (0.0, 0.1), method=method, **kw)
    L0, R0 = rigid_body_parts(y0)
    for order in (2, 4, 6, 8):
        for comp in (False, True):
            free_rigid_body_splitting(J, L0, R0, (0.0, 0.1), 0.05, order=order, compensated=comp)
            free_rigid_body_splitting(J, L0[None], R0, (0.0, 0.1), 0.05, order=order)
    integrate(
        free_rigid_body_rhs(J), y0[None], (0.0, 0.1), method="dop853", rtol=1e-6, batch_ndim=1
    )


def sweep(problem: Problem, *, repeats: int, budget: float, progress: _Progress) -> dict:
    """Run every method of ``problem`` over its parameters; records and skipped points."""
    records, skipped = [], []
    for name, (pname, params, runner) in problem.methods.items():
        over = False
        for p in params:
            label = f"{problem.name} {name} {'' if p is None else p}"
            if over:
                skipped.append({"method": name, "param": p, "reason": f"budget {budget} s"})
                progress.step(label + " (skipped)")
                continue
            run, t, nruns = _timed(lambda p=p, runner=runner: runner(p), repeats)
            records.append(
                {
                    "method": name,
                    "family": "exact"
                    if name == "exact"
                    else ("scipy" if name.startswith("scipy-") else "ours"),
                    "param_name": pname,
                    "param": p,
                    "error": float(run.error),
                    "error_parts": run.parts,
                    "time_s": t,
                    "runs": nruns,
                    "steps": run.steps,
                    "rhs_evals": run.rhs_evals,
                    "rejected_steps": run.rejected_steps,
                }
            )
            progress.step(label)
            over = t > budget
        p_new = None if over or problem.target is None else _refine(records, name, problem.target)
        if p_new is not None:
            run, t, nruns = _timed(lambda p=p_new, f=runner: f(p), repeats)
            records.append(
                {
                    **records[-1],
                    "param": p_new,
                    "error": float(run.error),
                    "error_parts": run.parts,
                    "time_s": t,
                    "runs": nruns,
                    "steps": run.steps,
                    "rhs_evals": run.rhs_evals,
                    "rejected_steps": run.rejected_steps,
                    "refined": True,
                }
            )
            progress.step(f"{problem.name} {name} {p_new:.3g} (refined)")
    return {
        "title": problem.title,
        "description": problem.description,
        "horizon": problem.horizon,
        "error_measure": problem.error_measure,
        "records": records,
        "skipped": skipped,
    }


def _refine(records, method, target):
    """The parameter at which ``method``'s error reaches ``target``, by log-log
    interpolation between the two sweep points that bracket it (None if none do)."""
    rs = [r for r in records if r["method"] == method and r["param"] is not None]
    for a, b in itertools.pairwise(rs):
        if a["error"] > target >= b["error"] and a["error"] > 0 and b["error"] > 0:
            la, lb = math.log(a["param"]), math.log(b["param"])
            ea, eb = math.log(a["error"]), math.log(b["error"])
            lp = la + (math.log(target) - ea) * (lb - la) / (eb - ea)
            lp += 0.1 * (1 if lb > la else -1)  # 10 % toward the accurate side
            p = math.exp(lp)
            return math.ceil(p) if isinstance(a["param"], int) else float(f"{p:.2g}")
    return None


# ------------------------------------------------------------------------ energy drift


def _energy(L, J):
    return 0.5 * (L * L / J).sum(-1)


def energy_drift(quick: bool, progress: _Progress) -> dict:
    """Max relative energy error of the free top up to each horizon (10 … 10⁴ rotations).

    RK4, our DOP853 (rtol = atol = 1e-8), scipy DOP853 (rtol = atol = 1e-8) and the
    splittings of order 2 and 6 at 50 steps per rotation, every one to the longest
    horizon (the slowest, scipy's, takes ~20 s for 10⁴ rotations); the energy is
    sampled 8 times per rotation."""
    J, w0 = FREE_J, FREE_W0
    rot = 2 * math.pi / float(np.linalg.norm(w0))
    horizons = [10, 30] if quick else [10, 100, 1000, 10000]
    n_out = 8 * horizons[-1]
    grid = time_grid(0.0, rot / 8, n_out)
    L0 = J * w0
    E0 = float(_energy(L0, J))
    y0 = rigid_body_state(L0, np.eye(3))
    h = rot / 50
    curves, seconds = {}, {}

    def timed(name, fn):
        t0 = time.perf_counter()
        curves[name] = fn()
        seconds[name] = time.perf_counter() - t0
        progress.step(f"energy drift {name}")

    timed(
        "rk4 (h = rotation/50)",
        lambda: np.abs(
            _energy(integrate(free_rigid_body_rhs(J), y0, grid, method="rk4", h=h).y[:, :3], J) / E0
            - 1
        ),
    )
    timed(
        "dop853 (rtol = 1e-8)",
        lambda: np.abs(
            _energy(
                integrate(free_rigid_body_rhs(J), y0, grid, method="dop853", rtol=1e-8).y[:, :3],
                J,
            )
            / E0
            - 1
        ),
    )

    def scipy_curve():
        sp = solve_ivp(
            free_rigid_body_rhs(J),
            (0.0, float(grid[-1])),
            y0,
            method="DOP853",
            rtol=1e-8,
            atol=1e-8,
            t_eval=grid,
        )
        return np.abs(_energy(sp.y[:3].T, J) / E0 - 1)

    timed("scipy-DOP853 (rtol = 1e-8)", scipy_curve)
    for order in (2, 6):

        def split_curve(order=order):
            s = free_rigid_body_splitting(J[[1, 2, 0]], _PERM @ L0, _PERM, grid, h, order=order)
            return np.abs(_energy(s.y[:, :3], J[[1, 2, 0]]) / E0 - 1)

        timed(f"splitting-{order} (h = rotation/50)", split_curve)
    out = {"horizons_rotations": horizons, "curves": {}, "time_s": seconds}
    for name, c in curves.items():
        running = np.maximum.accumulate(c)
        out["curves"][name] = [float(max(running[8 * n], 0.0)) for n in horizons]
    return out


# ------------------------------------------------------------------------ batched


def batched(quick: bool, repeats: int, progress: _Progress) -> dict:
    """1000 bodies as one array against one body, RK4 and the splitting (order 4)."""
    J = FREE_J
    rot = 2 * math.pi / float(np.linalg.norm(FREE_W0))
    n_bodies = 1000
    steps = 20 if quick else 200
    h = rot / 50
    span = (0.0, steps * h)
    rng = np.random.default_rng(20240919)
    d = rng.normal(size=(n_bodies, 3))
    w = d / np.linalg.norm(d, axis=-1, keepdims=True)
    L = J * w
    yb = rigid_body_state(L, np.eye(3))
    rhs = free_rigid_body_rhs(J)
    out = {"bodies": n_bodies, "steps": steps}
    cases = {
        "rk4": (
            lambda: integrate(rhs, yb[0], span, method="rk4", h=h),
            lambda: integrate(rhs, yb, span, method="rk4", h=h, batch_ndim=1),
        ),
        "splitting-4": (
            lambda: free_rigid_body_splitting(J, L[0], np.eye(3), span, h, order=4),
            lambda: free_rigid_body_splitting(J, L, np.eye(3), span, h, order=4),
        ),
    }
    for name, (one, many) in cases.items():
        res = {}
        for key, fn in (("one_s", one), ("batch_s", many)):
            fn()  # untimed: the first call in a process loads the kernel
            times = []
            for _ in range(max(repeats, 1)):
                t0 = time.perf_counter()
                sol = fn()
                times.append(time.perf_counter() - t0)
            res[key] = statistics.median(times)
            res[key + "_sol"] = sol
        # the batch's first member is the single body's run
        diff = float(np.abs(res["batch_s_sol"].y[-1][0] - res["one_s_sol"].y[-1]).max())
        out[name] = {
            "one_body_s": res["one_s"],
            "batch_s": res["batch_s"],
            "batch_over_one": res["batch_s"] / res["one_s"],
            "member_0_max_diff": diff,
        }
        progress.step(f"batched {name}")
    return out


def batched_vs_scipy(quick: bool, repeats: int, progress: _Progress) -> dict:
    """:data:`BATCH_BODIES` free bodies (J = (1, 2, 3), random unit ω0, identity
    attitude) over one rotation at |ω| = 1: compiled ``"dop853"`` on the whole batch
    (``batch_ndim=1``, one common step) against scipy's DOP853 run body by body, both at
    rtol = atol = :data:`BATCH_RTOL`.  scipy runs the first :data:`BATCH_SCIPY_SAMPLE`
    bodies; its time per body is scaled to the batch.  Errors against the exact top."""
    n, k = BATCH_BODIES[quick], BATCH_SCIPY_SAMPLE[quick]
    rng = np.random.default_rng(BATCH_SEED)
    d = rng.normal(size=(n, 3))
    w0 = d / np.linalg.norm(d, axis=-1, keepdims=True)
    J = FREE_J
    y0 = rigid_body_state(J * w0, np.eye(3))
    rhs = free_rigid_body_rhs(J)
    t1 = 2 * math.pi

    def ours():
        return integrate(rhs, y0, (0.0, t1), method="dop853", rtol=BATCH_RTOL, batch_ndim=1)

    def theirs():
        return [_scipy_solve(rhs, y0[i], t1, "DOP853", BATCH_RTOL).y[:, -1] for i in range(k)]

    ours()  # untimed: the first call in a process loads the kernel (README: JIT cost)
    sol, t_ours, _ = _timed(ours, repeats)
    progress.step("batch vs scipy: ours")
    ys, t_sample, _ = _timed(theirs, repeats)
    progress.step("batch vs scipy: scipy")
    err_ours = err_scipy = 0.0
    for i in range(k):
        top = FreeAsymmetricTop(J, w0[i])
        wt, Rt = top.state(t1)
        for y, which in ((sol.y[-1, i], "ours"), (ys[i], "scipy")):
            L, R = rigid_body_parts(y)
            e = max(float(np.abs(L / J - wt).max()), float(np.abs(R - Rt).max()))
            if which == "ours":
                err_ours = max(err_ours, e)
            else:
                err_scipy = max(err_scipy, e)
    t_scipy = t_sample / k * n
    return {
        "bodies": n,
        "scipy_bodies_run": k,
        "rtol": BATCH_RTOL,
        "ours_s": t_ours,
        "ours_steps": sol.steps,
        "scipy_sample_s": t_sample,
        "scipy_s": t_scipy,
        "ratio": t_scipy / t_ours,
        "worst_error_ours": err_ours,
        "worst_error_scipy": err_scipy,
    }


def exact_evaluation(repeats: int) -> dict:
    """The exact free top at the free-top problem's horizon: one evaluation of
    ``FreeAsymmetricTop.state`` (the median over ``repeats`` batches of 200 calls, per
    call) and the construction (its elliptic parameters, once per body)."""
    T = FREE_TOP_ROTATIONS[False] * 2 * math.pi / float(np.linalg.norm(FREE_W0))
    top = FreeAsymmetricTop(FREE_J, FREE_W0)
    calls, per_call, build = 200, [], []
    for _ in range(max(repeats, 3)):
        t0 = time.perf_counter()
        for _ in range(calls):
            top.state(T)
        per_call.append((time.perf_counter() - t0) / calls)
        t0 = time.perf_counter()
        FreeAsymmetricTop(FREE_J, FREE_W0)
        build.append(time.perf_counter() - t0)
    return {
        "rotations": FREE_TOP_ROTATIONS[False],
        "evaluation_s": statistics.median(per_call),
        "construction_s": statistics.median(build),
    }


def _mujoco_model(integrator: str):
    import mujoco

    xml = (
        '<mujoco><option gravity="0 0 0" timestep="{dt!r}" integrator="{integ}"/>'
        '<worldbody><body name="top"><freejoint/><inertial pos="0 0 0" mass="1" '
        'diaginertia="{J}"/></body></worldbody></mujoco>'
    ).format(dt=MUJOCO_DT, integ=integrator, J=" ".join(repr(x) for x in MUJOCO_J))
    return mujoco.MjModel.from_xml_string(xml)


def mujoco_peer(quick: bool, repeats: int, progress: _Progress) -> dict:
    """MuJoCo's RK4 and Euler on the torque-free body :data:`MUJOCO_J`, ω0 =
    :data:`MUJOCO_W0` over :data:`MUJOCO_T` s at dt = :data:`MUJOCO_DT` (issue 15), and
    the project's methods on the same run: the fastest that reaches MuJoCo RK4's error.

    MuJoCo runs a ``freejoint`` body with ``diaginertia`` J and no gravity; ``qvel[3:6]``
    is ω in body components and ``xmat = (^A R^O)ᵀ`` (``mj_forward`` after the last
    step makes ``xmat`` that of the final state).  Error, as the free-top problem's:
    max(|Δω_A|/|ω0|, |Δ ^A R^O|) at t = 20 s against :class:`FreeAsymmetricTop`.  The
    MuJoCo time is ``mj_step(model, data, nstep=20000)`` (no Python loop).  Without
    ``mujoco`` the result says which extra to install."""
    try:
        import mujoco
    except ImportError:
        progress.step("mujoco peer (not installed)")
        return {"available": False, "install": MUJOCO_EXTRA}
    J, w0 = np.array(MUJOCO_J), np.array(MUJOCO_W0)
    T = MUJOCO_T
    top = FreeAsymmetricTop(J, w0)
    wT, RT = top.state(T)
    wn = float(np.linalg.norm(w0))

    def err(w, R):
        return max(float(np.abs(w - wT).max()) / wn, float(np.abs(R - RT).max()))

    out: dict = {"available": True, "version": mujoco.__version__, "peers": {}, "ours": []}
    nstep = round(T / MUJOCO_DT)
    for integ in ("RK4", "Euler"):
        model = _mujoco_model(integ)
        data = mujoco.MjData(model)

        def run(model=model, data=data):
            mujoco.mj_resetData(model, data)
            data.qvel[3:6] = w0
            mujoco.mj_step(model, data, nstep=nstep)
            mujoco.mj_forward(model, data)
            return np.array(data.qvel[3:6]), np.array(data.xmat[1]).reshape(3, 3).T

        (w, R), t, _ = _timed(run, repeats)
        out["peers"][f"mujoco-{integ}"] = {"dt": MUJOCO_DT, "error": err(w, R), "time_s": t}
        progress.step(f"mujoco {integ}")
    rhs = free_rigid_body_rhs(J)
    y0 = rigid_body_state(J * w0, np.eye(3))
    cands = [("dop853", "rtol", r) for r in (1e-12, 1e-13, 1e-14, 1e-15)]
    cands += [("rk4", "h", h) for h in (4e-3, 2e-3, 1e-3)]
    cands += [(f"splitting-{o}", "h", h) for o in (6, 8) for h in (0.1, 0.05, 0.025)]
    for name, pname, p in cands:

        def go(name=name, p=p):
            if name == "dop853":
                y = integrate(rhs, y0, (0.0, T), method="dop853", rtol=p).y[-1]
            elif name == "rk4":
                y = integrate(rhs, y0, (0.0, T), method="rk4", h=p).y[-1]
            else:
                order = int(name.split("-")[1])
                y = free_rigid_body_splitting(J, J * w0, np.eye(3), (0.0, T), p, order=order).y[-1]
            L, R = rigid_body_parts(y)
            return L / J, R

        (w, R), t, _ = _timed(go, max(repeats, 5))  # sub-millisecond runs: 5 at least
        out["ours"].append(
            {"method": name, "param_name": pname, "param": p, "error": err(w, R), "time_s": t}
        )
    progress.step("mujoco peer: ours")
    ref = out["peers"]["mujoco-RK4"]
    ok = [r for r in out["ours"] if r["error"] <= ref["error"]]
    best = min(ok, key=lambda r: r["time_s"]) if ok else None
    out["best_at_mujoco_rk4_error"] = best
    out["ratio"] = ref["time_s"] / best["time_s"] if best else None
    return out


# ------------------------------------------------------------------------ headline


def _fastest(records, method, target):
    ok = [r for r in records if r["method"] == method and r["error"] <= target]
    return min(ok, key=lambda r: r["time_s"]) if ok else None


def target_status(value, goal, must=None) -> str:
    """``"met"``, ``"must met, goal not"`` or ``"NOT MET"`` for a ratio against its goal
    (and its required minimum), ``"not measured"`` when there is no value."""
    if value is None:
        return "not measured"
    if value >= goal:
        return "met"
    if must is not None and value >= must:
        return "must met, goal not"
    return "NOT MET"


def _fastest_of(records, family, target):
    ok = [r for r in records if r["family"] == family and r["error"] <= target]
    return min(ok, key=lambda r: r["time_s"]) if ok else None


def headline(study: dict) -> dict:
    """Issue 15's targets (and issue 6's ratios), from the records of this one run.

    ``targets`` is a list of rows ``{name, measured, goal, status, detail}``; a target
    that is not met says so (``status`` "NOT MET"), one that could not be measured says
    why."""
    recs = study["problems"]["free_top"]["records"]
    steppers = sorted({r["method"] for r in recs if r["family"] == "ours"})
    h: dict = {"target_error": TARGET_ERROR}
    # -- the fastest stepper at scipy DOP853's error (its most accurate run)
    dop_recs = [r for r in recs if r["method"] == "scipy-DOP853"]
    ref = min(dop_recs, key=lambda r: r["error"]) if dop_recs else None
    h["scipy_dop853"] = _brief(ref)
    best = _fastest_of(recs, "ours", ref["error"]) if ref else None
    h["best_stepper"] = _brief(best)
    h["best_stepper_vs_scipy_dop853"] = ref["time_s"] / best["time_s"] if ref and best else None
    h["per_stepper"] = {}
    for m in steppers:
        r = _fastest(recs, m, ref["error"]) if ref else None
        h["per_stepper"][m] = (
            None if r is None else {**_brief(r), "vs_scipy_dop853": ref["time_s"] / r["time_s"]}
        )
    # -- the exact solution: one evaluation (construction apart)
    ex = study.get("exact_evaluation")
    h["exact"] = ex
    h["exact_vs_scipy_dop853"] = ref["time_s"] / ex["evaluation_s"] if ref and ex else None
    h["exact_with_construction_vs_scipy_dop853"] = (
        ref["time_s"] / (ex["evaluation_s"] + ex["construction_s"]) if ref and ex else None
    )
    # -- every decade: our best against scipy's best
    h["decades"] = []
    for e in DECADES:
        o, sc = _fastest_of(recs, "ours", e), _fastest_of(recs, "scipy", e)
        if o is None:
            status = "NOT MET" + (" (neither reaches it)" if sc is None else "")
        elif sc is None:
            status = "met (scipy does not reach it)"
        else:
            status = "met" if o["time_s"] <= sc["time_s"] else "NOT MET"
        h["decades"].append(
            {
                "error": e,
                "ours": _brief(o),
                "scipy": _brief(sc),
                "scipy_over_ours": sc["time_s"] / o["time_s"] if o and sc else None,
                "status": status,
            }
        )
    dec_ok = all(d["status"].startswith("met") for d in h["decades"])
    # -- energy drift, batches, the MuJoCo peer
    ed = study["energy_drift"]
    h["energy_drift_growth"] = {
        name: (c[-1] / c[0] if c[0] > 0 else None) for name, c in ed["curves"].items()
    }
    h["energy_drift_horizons"] = [ed["horizons_rotations"][0], ed["horizons_rotations"][-1]]
    b = study["batched"]
    h["batched_1000_over_1"] = {k: b[k]["batch_over_one"] for k in ("rk4", "splitting-4")}
    bv = study.get("batched_vs_scipy")
    h["batched_vs_scipy"] = None if bv is None else bv["ratio"]
    mj = study.get("mujoco")
    h["mujoco"] = mj
    # -- the rows
    rows = []
    r = h["best_stepper_vs_scipy_dop853"]
    rows.append(
        {
            "name": "fastest stepper at scipy DOP853's error / DOP853's time",
            "measured": r,
            "goal": f"≥ {STEPPER_GOAL:g} (must ≥ {STEPPER_MUST:g})",
            "status": target_status(r, STEPPER_GOAL, STEPPER_MUST),
            "detail": (
                f"scipy DOP853 rtol {ref['param']:g}: error {ref['error']:.2e} in "
                f"{ref['time_s']:.3g} s; ours: {best['method']} ({best['param_name']} "
                f"{best['param']:g}): {best['error']:.2e} in {best['time_s']:.3g} s"
                if ref and best
                else "no project stepper reaches scipy DOP853's error in this sweep"
            ),
        }
    )
    r = h["exact_vs_scipy_dop853"]
    rows.append(
        {
            "name": "exact solution (one evaluation) / scipy DOP853's time",
            "measured": r,
            "goal": f"≥ {EXACT_GOAL:.0e}",
            "status": target_status(r, EXACT_GOAL),
            "detail": (
                f"state(t) at {ex['rotations']} rotations {1e6 * ex['evaluation_s']:.3g} µs; "
                f"with the construction ({1e3 * ex['construction_s']:.3g} ms) the ratio is "
                f"{h['exact_with_construction_vs_scipy_dop853']:.3g}"
                if ex and ref
                else "not measured"
            ),
        }
    )
    n_ok = sum(d["status"].startswith("met") for d in h["decades"])
    rows.append(
        {
            "name": "our best ≤ scipy's best time at every decade 1e-4 … 1e-12",
            "measured": f"{n_ok} of {len(DECADES)} decades",
            "goal": "all",
            "status": "met" if dec_ok else "NOT MET",
            "detail": "; ".join(
                f"{d['error']:.0e}: {d['status']}"
                for d in h["decades"]
                if not d["status"].startswith("met")
            )
            or "every decade met",
        }
    )
    r = h["batched_vs_scipy"]
    rows.append(
        {
            "name": f"batch of {bv['bodies'] if bv else '—'} free bodies: scipy DOP853 body "
            "by body / ours",
            "measured": r,
            "goal": f"≥ {BATCH_GOAL:g}",
            "status": target_status(r, BATCH_GOAL),
            "detail": (
                f"ours {bv['ours_s']:.3g} s (worst error {bv['worst_error_ours']:.1e}), "
                f"scipy {bv['scipy_s']:.3g} s ({bv['scipy_bodies_run']} bodies run, scaled; "
                f"worst error {bv['worst_error_scipy']:.1e}), rtol {bv['rtol']:g}"
                if bv
                else "not measured"
            ),
        }
    )
    if mj is None or not mj.get("available"):
        rows.append(
            {
                "name": "MuJoCo RK4 (dt 1e-3) / our best at its error",
                "measured": None,
                "goal": "≥ 1",
                "status": "not measured",
                "detail": "mujoco is not installed: " + MUJOCO_EXTRA,
            }
        )
    else:
        pk, eu, bb = (
            mj["peers"]["mujoco-RK4"],
            mj["peers"]["mujoco-Euler"],
            mj["best_at_mujoco_rk4_error"],
        )
        rows.append(
            {
                "name": "MuJoCo RK4 (dt 1e-3) / our best at its error",
                "measured": mj["ratio"],
                "goal": "≥ 1",
                "status": target_status(mj["ratio"], 1.0),
                "detail": (
                    f"MuJoCo {mj['version']} RK4 {pk['error']:.2e} in {pk['time_s']:.3g} s, "
                    f"Euler {eu['error']:.2e} in {eu['time_s']:.3g} s; ours: "
                    + (
                        f"{bb['method']} ({bb['param_name']} {bb['param']:g}) "
                        f"{bb['error']:.2e} in {bb['time_s']:.3g} s"
                        if bb
                        else "no method reaches it"
                    )
                ),
            }
        )
    h["targets"] = rows
    h["goals"] = {
        "fastest stepper vs scipy DOP853 >= 10 (must 3)": rows[0]["status"],
        "exact vs scipy DOP853 >= 1e5": rows[1]["status"],
        "every decade 1e-4 … 1e-12": rows[2]["status"],
        "batch vs scipy >= 50": rows[3]["status"],
        "MuJoCo peer": rows[4]["status"],
        "splitting energy error bounded (growth <= 2)": _le(
            next(
                (v for k, v in h["energy_drift_growth"].items() if k.startswith("splitting")), None
            ),
            2.0,
        ),
    }
    return h


def _time_at(rs, e):
    """Time to reach error ``e``, interpolated log-log between the sweep points."""
    pts = sorted(((r["error"], r["time_s"]) for r in rs if r["error"] > 0), reverse=True)
    for (ea, ta), (eb, tb) in itertools.pairwise(pts):
        if ea >= e >= eb:
            if ea == eb:
                return min(ta, tb)
            f = (math.log(e) - math.log(ea)) / (math.log(eb) - math.log(ea))
            return math.exp(math.log(ta) + f * (math.log(tb) - math.log(ta)))
    return None


def _ge(x, y):
    return None if x is None else bool(x >= y)


def _le(x, y):
    return None if x is None else bool(x <= y)


def _brief(r):
    if r is None:
        return None
    return {k: r[k] for k in ("method", "param_name", "param", "error", "time_s", "steps")}


# ------------------------------------------------------------------------ writers


def format_value(x, spec=".2e"):
    """A number for the tables, or an em dash when it was not measured."""
    if x is None:
        return "—"
    if isinstance(x, float):
        return format(x, spec)
    return str(x)


def write_markdown(study: dict, path: Path) -> None:
    lines = [
        "# Work-precision study",
        "",
        f"`{study['command']}` — {'quick' if study['quick'] else 'full'} run, "
        f"wall time the median of {study['repeats']} run(s) (runs over {LONG_RUN_S} s once), "
        f"total {study['total_time_s']:.1f} s on {study['machine']['cpus']} CPU(s).",
        "",
        "## Headline: issue 15's targets (free asymmetric top)",
        "",
    ]
    h = study["headline"]
    lines += [
        "Issue 15's targets on the free asymmetric top J = (1, 2, 3), ω0 = (0.4, 0.2, 1.0), "
        f"{FREE_TOP_ROTATIONS[study['quick']]} rotations, error against the exact solution; "
        "every ratio is scipy's (or MuJoCo's) time over ours, both measured in this run.",
        "",
        "| target | measured | goal | status | detail |",
        "|---|---|---|---|---|",
    ]
    for r in h["targets"]:
        m = r["measured"]
        m = format_value(m, ".3g") if not isinstance(m, str) else m
        lines.append(f"| {r['name']} | {m} | {r['goal']} | **{r['status']}** | {r['detail']} |")
    lines += [
        "",
        "### Every decade: the fastest run of ours and of scipy that reaches the error",
        "",
        "(the fastest sweep point with error ≤ the level; a method between two sweep "
        "points counts at the more accurate one, alike for both sides)",
        "",
        "| error ≤ | ours: method (parameter) | time [s] | scipy: method (rtol) | time [s] "
        "| scipy / ours | status |",
        "|---|---|---|---|---|---|---|",
    ]

    def who(r):
        return "—" if r is None else f"{r['method']} ({r['param_name']} {r['param']:g})"

    for d in h["decades"]:
        o, sc = d["ours"], d["scipy"]
        lines.append(
            f"| {d['error']:.0e} | {who(o)} | {format_value(o and o['time_s'], '.3g')} | "
            f"{who(sc)} | {format_value(sc and sc['time_s'], '.3g')} | "
            f"{format_value(d['scipy_over_ours'], '.3g')} | {d['status']} |"
        )
    lines += [
        "",
        "### Each of our steppers at scipy DOP853's error "
        + (f"({h['scipy_dop853']['error']:.2e})" if h["scipy_dop853"] else ""),
        "",
    ]
    for m, r in h["per_stepper"].items():
        lines.append(
            f"- {m}: "
            + (
                "does not reach it in this sweep"
                if r is None
                else f"{r['time_s']:.3g} s ({r['param_name']} {r['param']:g}, error "
                f"{r['error']:.2e}), scipy DOP853 / this: {format_value(r['vs_scipy_dop853'], '.3g')}"
            )
        )
    mj = h.get("mujoco")
    if mj and mj.get("available"):
        lines += [
            "",
            f"### The compiled-engine peer: MuJoCo {mj['version']}",
            "",
            f"Torque-free body J = {MUJOCO_J}, ω0 = {MUJOCO_W0}, {MUJOCO_T:g} s; error "
            "max(|Δω_A|/|ω0|, |Δ ^A R^O|) at the end against the exact solution; MuJoCo "
            "timed as one `mj_step(model, data, nstep)` call.",
            "",
            "| run | parameter | error | time [s] |",
            "|---|---|---|---|",
        ]
        for k, v in mj["peers"].items():
            lines.append(f"| {k} | dt = {v['dt']:g} | {v['error']:.2e} | {v['time_s']:.3g} |")
        for v in mj["ours"]:
            lines.append(
                f"| {v['method']} | {v['param_name']} = {v['param']:g} | {v['error']:.2e} | "
                f"{v['time_s']:.3g} |"
            )
    elif mj is not None:
        lines += ["", f"MuJoCo peer: not measured, mujoco is not installed ({mj['install']}).", ""]
    lines += ["", "Goals: " + ", ".join(f"{k}: {v}" for k, v in h["goals"].items()), ""]
    for name, p in study["problems"].items():
        lines += [
            f"## {p['title']} (`{name}`)",
            "",
            f"{p['description']}. Error: {p['error_measure']}. Horizon t = {p['horizon']:.6g}.",
            "",
            "| method | parameter | error | time [s] | steps | rhs evals | rejected |",
            "|---|---|---|---|---|---|---|",
        ]
        for r in p["records"]:
            par = "—" if r["param"] is None else f"{r['param_name']} = {r['param']:g}"
            lines.append(
                f"| {r['method']} | {par} | {r['error']:.2e} | {r['time_s']:.4g} | "
                f"{format_value(r['steps'])} | {format_value(r['rhs_evals'])} | {format_value(r['rejected_steps'])} |"
            )
        for s in p["skipped"]:
            lines.append(f"| {s['method']} | {s['param']} | skipped ({s['reason']}) | | | | |")
        lines.append("")
    ed = study["energy_drift"]
    lines += [
        "## Energy drift (free top, max relative energy error up to each horizon)",
        "",
        "| method | " + " | ".join(f"{n} rot." for n in ed["horizons_rotations"]) + " |",
        "|---|" + "---|" * len(ed["horizons_rotations"]),
    ]
    for name, c in ed["curves"].items():
        lines.append(f"| {name} | " + " | ".join(f"{v:.2e}" for v in c) + " |")
    if "time_s" in ed:
        lines += [
            "",
            "Each run to the longest horizon: "
            + ", ".join(f"{k} {v:.3g} s" for k, v in ed["time_s"].items())
            + ".",
        ]
    b = study["batched"]
    lines += [
        "",
        f"## Batched ({b['bodies']} bodies, {b['steps']} steps)",
        "",
        "| method | one body [s] | batch [s] | batch / one |",
        "|---|---|---|---|",
    ]
    for k in ("rk4", "splitting-4"):
        lines.append(
            f"| {k} | {b[k]['one_body_s']:.4g} | {b[k]['batch_s']:.4g} | "
            f"{b[k]['batch_over_one']:.3g} |"
        )
    bv = study.get("batched_vs_scipy")
    if bv:
        lines += [
            "",
            f"## Batch of {bv['bodies']} free bodies against scipy body by body "
            f"(one rotation, rtol {bv['rtol']:g})",
            "",
            f"Ours (compiled dop853, one common step, {bv['ours_steps']} steps): "
            f"{bv['ours_s']:.4g} s, worst error {bv['worst_error_ours']:.2e}. scipy DOP853: "
            f"{bv['scipy_sample_s']:.4g} s for {bv['scipy_bodies_run']} bodies, "
            f"{bv['scipy_s']:.4g} s scaled to the batch, worst error "
            f"{bv['worst_error_scipy']:.2e}. Ratio {bv['ratio']:.3g}.",
        ]
    ex = study.get("exact_evaluation")
    if ex:
        lines += [
            "",
            f"Exact top at {ex['rotations']} rotations: one `state(t)` "
            f"{1e6 * ex['evaluation_s']:.3g} µs, construction {1e3 * ex['construction_s']:.3g} ms.",
        ]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


_STYLE = {
    "exact": ("k", "*"),
    "rk4": ("C0", "o"),
    "dop853": ("C1", "s"),
    "splitting-2": ("C2", "^"),
    "splitting-4": ("C4", "v"),
    "splitting-6": ("C6", "D"),
    "scipy-RK45": ("C7", "x"),
    "scipy-DOP853": ("C3", "P"),
    "scipy-LSODA": ("C8", "+"),
    "splitting-8": ("C5", "<"),
    "splitting-6-kahan": ("C6", "d"),
    "splitting-8-kahan": ("C5", ">"),
    "scipy-Radau": ("C9", "1"),
}


def write_plots(study: dict, out_dir: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    probs = study["problems"]
    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    for ax, (name, p) in zip(axes.ravel(), probs.items(), strict=False):
        for m in dict.fromkeys(r["method"] for r in p["records"]):
            rs = sorted((r for r in p["records"] if r["method"] == m), key=lambda r: r["time_s"])
            c, mk = _STYLE.get(m, ("C9", "."))
            ax.loglog(
                [r["time_s"] for r in rs],
                [max(r["error"], ERROR_FLOOR) for r in rs],
                color=c,
                marker=mk,
                ls="--" if m.startswith("scipy") else (":" if m.endswith("kahan") else "-"),
                label=m,
            )
        if name == "free_top":
            for e in (DECADES[0], DECADES[-1]):
                ax.axhline(e, color="grey", lw=0.8, ls=":")
        ax.set_title(p["title"], fontsize=10)
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel("error")
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out_dir / "workprecision.png", dpi=90)
    plt.close(fig)

    ed = study["energy_drift"]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for name, c in ed["curves"].items():
        ax.loglog(
            ed["horizons_rotations"], [max(v, ERROR_FLOOR) for v in c], marker="o", label=name
        )
    ax.set_xlabel("horizon [rotations]")
    ax.set_ylabel("max |E/E0 − 1| up to the horizon")
    ax.set_title("Free asymmetric top: energy error against the horizon", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out_dir / "energy_drift.png", dpi=90)
    plt.close(fig)


# ------------------------------------------------------------------------ driver


def run_study(
    *,
    quick: bool,
    out_dir: Path,
    repeats: int,
    progress: bool = True,
    problems: list[Problem] | None = None,
) -> dict:
    """Run the whole study, write its four files into ``out_dir``, return the JSON dict.

    ``problems`` replaces the reference problems (tests inject a broken method this
    way); by default the four problems of the module docstring."""
    t_start = time.perf_counter()
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    if problems is None:
        problems = reference_problems(quick)
    total = (
        sum(len(ps) + (p.target is not None) for p in problems for _, ps, _ in p.methods.values())
        + 5  # energy drift
        + 2  # batched
        + 2  # batch against scipy
        + 3  # the MuJoCo peer
    )
    bar = _Progress(total, progress)
    budget = BUDGET_S[quick]
    study: dict = {
        "schema": SCHEMA,
        "quick": quick,
        "repeats": repeats,
        "command": "bodycheck bench" + (" --quick" if quick else "") + f" --repeats {repeats}",
        "machine": {
            "python": platform.python_version(),
            "platform": platform.platform(),
            "cpus": os.cpu_count(),
            "numpy": np.__version__,
        },
        "problems": {},
    }
    warm_compiled()
    try:
        for p in problems:
            study["problems"][p.name] = sweep(p, repeats=repeats, budget=budget, progress=bar)
        study["energy_drift"] = energy_drift(quick, bar)
        study["batched"] = batched(quick, repeats, bar)
        study["batched_vs_scipy"] = batched_vs_scipy(quick, repeats, bar)
        study["exact_evaluation"] = exact_evaluation(repeats)
        study["mujoco"] = mujoco_peer(quick, repeats, bar)
    finally:
        bar.close()
    study["total_time_s"] = time.perf_counter() - t_start
    if "free_top" in study["problems"]:
        study["headline"] = headline(study)
    (out_dir / "workprecision.json").write_text(
        json.dumps(_jsonable(study), indent=1, allow_nan=False), encoding="utf-8"
    )
    if "headline" in study:
        write_markdown(study, out_dir / "workprecision.md")
    write_plots(study, out_dir)
    return study


def _jsonable(x):
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_jsonable(v) for v in x]
    if isinstance(x, float | np.floating):
        return _finite_or_none(x)
    if isinstance(x, np.integer):
        return int(x)
    return x


def main_bench(argv=None) -> int:
    """``bodycheck bench [--quick] [--out DIR] [--repeats N]``."""
    ap = argparse.ArgumentParser(prog="bodycheck bench", description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="short horizons, few points (<30 s)")
    ap.add_argument("--out", default="bench-results", help="output directory")
    ap.add_argument(
        "--repeats",
        type=int,
        default=None,
        help="timing repeats, median taken (default 3; 1 with --quick)",
    )
    args = ap.parse_args(argv)
    repeats = args.repeats if args.repeats is not None else (1 if args.quick else 3)
    if repeats < 1:
        ap.error(f"--repeats must be ≥ 1; got {repeats}")
    study = run_study(quick=args.quick, out_dir=Path(args.out), repeats=repeats, progress=True)
    print("\n".join(summary_lines(study, args.out)))
    return 0


def summary_lines(study: dict, out) -> list[str]:
    """What ``bodycheck bench`` prints when the study is done: where it wrote, and each
    target's status, measured value and goal."""
    lines = [
        f"wrote {out}/workprecision.{{json,md,png}} and energy_drift.png "
        f"in {study['total_time_s']:.1f} s"
    ]
    for r in study["headline"]["targets"]:
        m = r["measured"]
        m = format_value(m, ".3g") if not isinstance(m, str) else m
        lines.append(f"{r['status']:>20}: {r['name']}: {m} (goal {r['goal']})")
    return lines


if __name__ == "__main__":
    raise SystemExit(main_bench(sys.argv[1:]))
