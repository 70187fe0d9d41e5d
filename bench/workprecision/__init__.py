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
  times), ``rk4`` (fixed step h), ``dop853`` (ours, rtol = atol), ``dop853-pi`` (the
  same with the PI step control, β = :data:`PI_BETA`; not on the free top, whose kernel
  has scipy's control), ``splitting-2/4/6/8``
  and ``splitting-6/8-kahan`` (compensated summation; free top only,
  :func:`mechanics.integrators.free_rigid_body_splitting`), and scipy's ``solve_ivp``
  with ``RK45``, ``DOP853``, ``LSODA``, ``Radau`` (rtol = atol) on the same right-hand
  side.  Ours run compiled (numba): on the free top the free body's kernels, on the
  others the right-hand side (and the impact's event φ) compiled by :func:`compiled`
  and run by :func:`mechanics.integrators.integrate`'s compiled path (issue 30);
  :func:`warm_compiled` and each problem's construction load every kernel and convert
  every function before anything is timed.  The impact's ``dop853`` runs stop at the
  wall by ``integrate``'s terminal event, one run per flight; ``rk4`` (no events)
  locates each impact by Newton on its own step map.  scipy gets the Python functions
  (it calls them from Python either way).  The splitting runs in the body frame relabelled (a
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

Layout (issue 35): :mod:`~bench.workprecision.settings` (targets, error levels,
budgets), :mod:`~bench.workprecision.problems` (the four problems and their exact
references), :mod:`~bench.workprecision.sweeps` (timing every method over its error
levels, the energy drift, the batches, the peers), :mod:`~bench.workprecision.report`
(the headline, tables and plots) and :mod:`~bench.workprecision.study` (the driver);
each imports only those before it.  ``python -m bench.workprecision`` runs the study.

Headline (``headline`` in the JSON, every ratio of two times measured in the same run;
:func:`headline`): issue 15's targets as rows with a status ("met", "must met, goal
not", "NOT MET", "not measured"): our fastest stepper at scipy DOP853's most accurate
error (goal ≥ 10, must ≥ 3); the exact solution's one evaluation against that DOP853
run (≥ 1e5); at each error 1e-4 … 1e-12 (:data:`DECADES`) our fastest run reaching it
against scipy's fastest (at least as fast; :func:`decades`), on the free top and (issue
30, the last row) on each other problem, where a level neither side reaches compares
nothing (the pendulum from 3 rad, near its separatrix: one ulp of θ0 moves φ at the end
by 4.8e3 ulps, 2.1e-12, and our best run, at rtol 1e-16, reaches 2.5e-10: 1e-10 …
1e-12 ask the rounding of some 30000 steps to stay within 50 ulps of the start's);
:func:`batched_vs_scipy` (≥ 50); and
:func:`mujoco_peer` (MuJoCo's RK4 at dt 1e-3 against our fastest at its error; without
``mujoco`` the row names the extra).  Also the energy drift's growth and the batch
against one body (issue 6).
"""

from __future__ import annotations

from .problems import (
    FREE_J,
    FREE_W0,
    HEAVY,
    HEAVY_INIT,
    IMPACT_E,
    IMPACT_THETA0,
    PEND,
    PI_BETA,
    Problem,
    compiled,
    heavy_top_rhs,
    pendulum_rhs,
    reference_problems,
)
from .report import decades, headline
from .settings import (
    BATCH_BODIES,
    BUDGET_S,
    DECADES,
    ERROR_FLOOR,
    FREE_TOP_ROTATIONS,
    LONG_RUN_S,
    MUJOCO_EXTRA,
    SCHEMA,
    TARGET_ERROR,
)
from .study import main_bench, run_study, summary_lines
from .sweeps import mujoco_peer

__all__ = [
    "BATCH_BODIES",
    "BUDGET_S",
    "DECADES",
    "ERROR_FLOOR",
    "FREE_J",
    "FREE_TOP_ROTATIONS",
    "FREE_W0",
    "HEAVY",
    "HEAVY_INIT",
    "IMPACT_E",
    "IMPACT_THETA0",
    "LONG_RUN_S",
    "MUJOCO_EXTRA",
    "PEND",
    "PI_BETA",
    "SCHEMA",
    "TARGET_ERROR",
    "Problem",
    "compiled",
    "decades",
    "headline",
    "heavy_top_rhs",
    "main_bench",
    "mujoco_peer",
    "pendulum_rhs",
    "reference_problems",
    "run_study",
    "summary_lines",
]
