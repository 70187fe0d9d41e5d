"""Time-steppers with one interface: RK4, an 8th-order adaptive Runge–Kutta, a Lie–Poisson
splitting for the free rigid body and an SO(3) exponential step.

Conventions
-----------
- **One interface.**  :func:`integrate` ``(rhs, y0, t, *, method, h, rtol, atol, kahan)``
  and :func:`free_rigid_body_splitting` both return a frozen :class:`Solution`
  holding the output times ``t``, the states ``y`` (shape ``(len(t), *y0.shape)``) and
  the work done: accepted ``steps``, ``rhs_evals`` (calls of the right-hand side;
  exact sub-flows for the splitting) and ``rejected_steps``.
- **Right-hand side.**  ``rhs(t, y)`` takes a float ``t`` and an array of ``y0``'s
  shape and returns dy/dt of the same shape.  A returned array of another shape
  raises :class:`~mechanics.errors.ShapeError`, a non-finite value
  :class:`~mechanics.errors.NonFiniteError`, both naming the time.
- **Batches.**  Many initial conditions are a leading axis of ``y0``: the right-hand
  side is called once per stage for the whole batch, so Python's overhead is paid
  once per step, not once per body.  Fixed-step methods give each member exactly
  the result of its own run.  The adaptive method takes *one common step* for the
  batch: its error norm is the RMS norm over each member's components (the
  ``batch_ndim`` leading axes of ``y0`` index the members) and then the **maximum
  over the batch**, so every member meets the tolerance and the step is set by the
  hardest one.
- **Output times.**  ``t`` is a strictly increasing grid of at least two output
  times (``(t0, t1)`` is a span).  Fixed-step methods take between t_k and t_{k+1}
  n_k = ⌈(t_{k+1} − t_k)/h⌉ equal steps h_k ≤ h (``h`` is the largest step, up to
  the rounding of the grid points), and the
  stage times are t_k + (j + c) h_k: **time is never accumulated** as t += h.  On
  the grid :func:`time_grid` (t0 + n h) each output is one step of exactly h.  The
  adaptive method's steps are set by its error control alone (issue 15): it steps
  towards t[-1] (the last step ends on it exactly) and evaluates the outputs inside
  a step by DOP853's 7th-order continuous extension (:class:`DenseStep`, 3 more
  evaluations for a step that holds outputs, counted in ``rhs_evals``); an output on
  a step's end is that step's state.  So a dense grid no longer caps the step: 2001
  outputs over 20 s of the oscillator take 19, 33 and 101 steps at rtol 1e-6, 1e-8
  and 1e-12 (2000 each before), and the same steps as the span (t0, t1), to the bit.
- **Kahan.**  ``kahan=True`` adds each step's increment with compensated
  summation, so over N fixed steps the rounding of the state grows like eps
  instead of like N eps (``tests/mechanics/test_integrators.py`` measures it).
- **Compensated splitting** (issue 15, part 3).  ``free_rigid_body_splitting(...,
  compensated=True)`` writes each exact turn as an increment, x ← x + ((cos θ − 1) x
  + sin θ y) with cos θ − 1 = −2 sin²(θ/2), and adds it by Kahan summation, the
  compensations of L and R carried from flow to flow; no projection is needed (a
  turn's rounding changes |L| and R Rᵀ by ~eps θ², not eps).  Measured
  (``python -m bench.roundoff``, ``docs/bench/roundoff.md``: order 8, 1000 steps per
  rotation, truncation below rounding): the RMS energy rounding near 1e4, 1e5, 1e6
  steps 0.77, 1.4, 6.3 eps against 10, 36, 139 eps plain (both grow about like √n,
  n^0.46 and n^0.57: the projection already removes the systematic part; the
  compensation lowers the constant 13–25×), and the state's error after 1e6 steps
  (1000 rotations) 1.0e-12 against 6.2e-11 (growing like n^0.9 against n^1.6: an
  energy error shifts the phase, which then grows with time).  At long horizons the
  splitting's accuracy is set by rounding, and this lowers it.  Off by default (the
  default's results are unchanged).  Both paths, the same arithmetic.
- **Rigid-body state.**  A free rigid body is the 12-vector ``(L_A, R_A_O)``:
  L_A the body components of the angular momentum about G, then the rows of the
  book's passive matrix ^A R^O (see :mod:`mechanics.rotation`);
  :func:`rigid_body_state` and :func:`rigid_body_parts` convert.  Torque-free
  Euler equations (4.47): dL_A/dt = L_A × ω_A with ω_i = L_i/J_i, and the attitude
  obeys dR_A_O/dt = Ω R_A_O with the book's Ω (2.46), (2.52) (=
  :func:`mechanics.kinematics.omega_matrix_from_vector`, minus the usual hat).
  For constant ω over h this integrates to R ← ^A R^O(h ω_A) R with ^A R^O of the
  rotation vector h ω_A (2.29): :func:`so3_exp_step`.
- **Compiled path** (issue 15).  The free rigid body of :func:`free_rigid_body_rhs`
  (recognised by the ``free_body_moments`` attribute of the function it returns) is
  integrated by numba kernels (:mod:`mechanics._kernels`, ``@njit(cache=True)``) for
  ``"rk4"`` and ``"dop853"`` without Kahan summation, one body or a batch, and so is
  every :func:`free_rigid_body_splitting`: the same validation, steps, work counts and
  errors, the coefficients passed in from this module (one source of truth).  A
  Python ``rhs`` cannot be compiled and keeps the pure-numpy **reference path**, which
  ``compiled=False`` forces and which the compiled one is tested against
  (``tests/mechanics/test_integrators_compiled.py``): RK4 to the bit, DOP853 and the
  splitting within 256 eps (the stage sums and the projection are summed in another
  order than BLAS's).  numba is imported on the first compiled call, not by ``import
  mechanics``; if it is missing or a compilation fails, one
  :class:`CompiledPathWarning` says so and the reference path runs (same results).  A
  kernel that meets a non-finite state hands over to the reference path, which raises
  the error naming the time.  Cost of the first call in a process (warm on-disk
  cache): 0.67 s, numba's import; with no cache, compiling DOP853's kernel 3.5–3.9 s,
  RK4's 0.4 s, the splitting's 0.8 s (``tools/jit_cost.py [--cold]``).
- **A compiled right-hand side** (issue 30).  A ``rhs`` compiled by numba
  (``@numba.njit``, the ``[fast]`` extra) with a state of shape (n,) runs the whole
  stepper compiled (:mod:`mechanics._kernels_rhs`): RK4 and DOP853 with its dense output,
  the PI control and events, the right-hand side called at the stage times.  Write it as
  ``rhs(t: float, y: float64[::1]) -> float64[::1]``, returning a new array of y's
  length (``np.array([y[1], -math.sin(y[0])])``, or ``out = np.empty_like(y)``, fill,
  return); parameters are closed over (numba freezes them) or module constants.  It
  is converted at each :func:`integrate` call (about 0.1 ms), so many short runs pay
  that each time.  The reference path's results, which calls the compiled function from
  Python: RK4 to the bit; DOP853 its steps where the error estimates stay clear of their
  rounding, within 4 rtol always (its stage sums in another order; 0.26 rtol measured,
  ``tests/mechanics/test_integrators_user_compiled.py``).  What the
  kernel cannot take runs on the reference path with one :class:`CompiledPathWarning`
  saying why: a function numba cannot type for that signature, a state of another shape,
  an event function that is not compiled.
- **Step control** (issue 30).  ``beta`` = β in (0, 0.08] makes ``"dop853"``'s control
  Gustafsson's PI control as in Hairer's DOP853, h ← h · 0.9 err^(−1/8 + 0.2 β)
  err_prev^β (err_prev the last accepted step's error, at least 1e-4), which rejects
  fewer steps: on the pendulum from 3 rad at rtol 1e-9, 809 rejections of 5024 attempts
  at β = 0, 604 at 0.04, 67 at 0.08 — but more steps, so the evaluations are about the
  same (``docs/bench/workprecision.md``, ``dop853-pi``).  β = 0, the default, is scipy's
  control to the bit.
- **Events** (issue 30).  ``integrate(..., event=g, event_direction=d)`` stops ``"dop853"``
  at the first zero crossing of g(t, y) in direction d (−1 falling, 1 rising, 0 either):
  checked at each accepted step's end (a step from g_old strictly on one side to g_new on
  zero or past it), then bracketed on the step's continuous extension by Illinois' regula
  falsi with a bisection every fourth iteration, to 4 ulps of its time
  (:data:`~mechanics.integrators._events.EVENT_XTOL`); the event is the bracket's right
  end, so g(t_event) is on or past zero.  :class:`Solution` then holds the outputs before
  it and ``t_event``, ``y_event``.  A run that starts on zero does not stop there (an
  impact's rebound), and two crossings inside one step are not seen.
- Everything float64 numpy; no sympy.

Methods
-------
``"rk4"``: classical Runge–Kutta, order 4, 4 evaluations per step.
``"dop853"``: Dormand–Prince 8(5,3) (Hairer, Nørsett & Wanner, *Solving ODEs I*,
2nd ed., II.10), the tableau of scipy's ``DOP853`` (imported from
``scipy.integrate._ivp.dop853_coefficients``), 12 evaluations per attempted step;
step control as scipy: safety 0.9, factor in [0.2, 10], exponent −1/8, no growth
right after a rejection, and Hairer's initial step (2 evaluations) unless ``h``
is given.  :func:`free_rigid_body_splitting`: the Lie–Poisson splitting of
H = Σ L_i²/(2 J_i) into three exact rotations about the body axes (McLachlan
1993; Touma & Wisdom 1994), composed symmetrically (Strang, order 2) or by
Yoshida's triple jump (orders 4, 6 and 8: 3, 9 and 27 Strang steps).

:class:`DOP853Stepper` is the same method one accepted step at a time, for a
caller that inspects every step (a scene engine locating contacts): scipy's
``DOP853`` stepping interface (``step()``, ``dense_output()``, ``t``, ``y``,
``t_old``, ``status``), a 1-D state, the same step control with scipy's
``max_step`` cap, and the step code shared with :func:`integrate`.  Its
:class:`DenseStep` is Hairer's 7th-order continuous extension ``contd8`` over
[t_old, t]: 3 more evaluations (the rows 13–15 of the same scipy tableau), then
its matrix ``D``; scalar t gives shape (n,), k times shape (n, k), as scipy.

Layout
------
One private module per job (issue 35); this package re-exports the public names.
``_solution`` (:class:`Solution`, the shared type aliases), ``_events`` (when an event
function crosses zero, the bracket that locates it), ``_grid`` (output times,
fixed steps, the step budget, :func:`time_grid`), ``_rhs`` (a user's right-hand side
checked), ``_compiled`` (the compiled path's loader and :class:`CompiledPathWarning`),
``_rk4``, ``_dop853`` (tableau, step, error control, batched run, :class:`DenseStep`),
``_stepper`` (:class:`DOP853Stepper`), ``_integrate`` (:func:`integrate`), ``_rigid_body``
(the free body's state, right-hand side and SO(3) step) and ``_splitting``
(:func:`free_rigid_body_splitting`).  Imports point down that list, never back.

Accuracy and cost (``tests/mechanics/test_integrators.py``,
``tests/theorems/test_integrator_properties.py``, ``tests/benchmarks/test_bench_integrators.py``):
RK4 error falls 15.8–15.9× when h halves, the splitting 4.0×, 15.9×, 63.5×, 252× (orders
2, 4, 6, 8, against the elliptic-function top); ``"dop853"`` reproduces scipy's DOP853
step for step (same steps and evaluations; for one body the same arithmetic,
operation for operation, so the same states to the bit, and the stepper's dense
output too, ``tests/mechanics/test_dop853_stepper.py``) and its global error is
about 1.5 rtol on the oscillator.  The splitting keeps |L| within 1 eps
and R Rᵀ within 1.5 eps of exact at any length of run, and its energy error stays
below 0.1 (h ω_max)² over 1000 rotations while RK4's grows.  Kahan: 2¹⁴ steps of
y' = c, 2623 eps plain, 1.15 eps compensated.  Speed (loaded 2-core machine): the
splitting 3.6 µs per order-2 step of one body (plain floats), a batch of 1000 bodies
65× one body per step; RK4 on the 12-component rigid body 36 µs per step;
:class:`DOP853Stepper` there 54 µs per step, 75 µs with its dense output, 0.99
and 1.02 times scipy's ``DOP853`` measured in the same run (those figures are the
reference path's).  The compiled path (``tests/benchmarks/test_bench_compiled.py``,
issue 15): ``"dop853"`` 0.44 µs per step of one free body, reaching scipy DOP853's
error over 1000 rotations 135× faster (same steps); a batch of 10⁴ bodies 108× scipy
run body by body; the order-6 splitting 11× scipy's time at 400 steps per rotation.
"""

from __future__ import annotations

from ._compiled import CompiledPathWarning
from ._dop853 import DOP853_MAX_FACTOR, DOP853_MIN_FACTOR, DOP853_SAFETY, DenseStep
from ._grid import time_grid
from ._integrate import METHODS, integrate
from ._rigid_body import free_rigid_body_rhs, rigid_body_parts, rigid_body_state, so3_exp_step
from ._solution import Solution
from ._splitting import PROJECT_EVERY, SPLITTING_ORDERS, free_rigid_body_splitting
from ._stepper import DOP853Stepper

__all__ = [
    "DOP853_MAX_FACTOR",
    "DOP853_MIN_FACTOR",
    "DOP853_SAFETY",
    "METHODS",
    "PROJECT_EVERY",
    "SPLITTING_ORDERS",
    "CompiledPathWarning",
    "DOP853Stepper",
    "DenseStep",
    "Solution",
    "free_rigid_body_rhs",
    "free_rigid_body_splitting",
    "integrate",
    "rigid_body_parts",
    "rigid_body_state",
    "so3_exp_step",
    "time_grid",
]
