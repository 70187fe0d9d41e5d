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

import importlib
import itertools
import math
import warnings
from dataclasses import dataclass
from numbers import Integral

import numpy as np
from scipy.integrate._ivp import dop853_coefficients as _d853

from ._validate import (
    as_float_array,
    as_float_scalar,
    as_positive_scalar,
    broadcast_checked,
    finite_result,
)
from .errors import (
    NonFiniteError,
    NonPhysicalInertiaError,
    NonPositiveParameterError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
    StepSizeError,
    UnknownOptionError,
)
from .rotation import EPS, check_rotation, matrix_from_rotvec

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

#: The methods of :func:`integrate`.
METHODS = ("rk4", "dop853")

#: Orders of :func:`free_rigid_body_splitting` (Strang, Yoshida 4, 6, 8).
SPLITTING_ORDERS = (2, 4, 6, 8)

#: Step control of ``"dop853"``: the values of Hairer's DOP853 and of scipy.
DOP853_SAFETY = 0.9
DOP853_MIN_FACTOR = 0.2
DOP853_MAX_FACTOR = 10.0
_DOP853_EXPONENT = -1.0 / 8.0  # −1/(q + 1), q = 7 the order of the error estimator

#: An interval of n·h that rounds to slightly above n steps still takes n steps:
#: the quotient (t_{k+1} − t_k)/h carries a few roundings (8 eps relative covers
#: them), and the grid points themselves half an ulp each (see :func:`_substeps`).
_GRID_RTOL = 8 * EPS

_N_STAGES = _d853.N_STAGES  # 12
_A = _d853.A[:_N_STAGES, :_N_STAGES]
_A_ROWS = [np.ascontiguousarray(_A[s, :s]) for s in range(_N_STAGES)]
_B = np.ascontiguousarray(_d853.B)
_C = [float(c) for c in _d853.C[:_N_STAGES]]
# The compiled path's copies of the same tableau (extended: 16 stages, and D)
_A_FULL = np.ascontiguousarray(_d853.A[:16, :16])
_C_ARRAY = np.ascontiguousarray(_d853.C[:16])
_E3 = np.ascontiguousarray(_d853.E3)
_E5 = np.ascontiguousarray(_d853.E5)
# Dense output (Hairer's contd8, as scipy's ``DOP853._dense_output_impl``): three
# extra stages K[13:16] (rows 13–15 of A, which also use K[12] = f(t_new, y_new)),
# then the 4 × 16 matrix D that gives the rows F_3 … F_6 of the interpolant.
_N_STAGES_EXTENDED = _d853.N_STAGES_EXTENDED  # 16
_A_EXTRA_ROWS = [
    np.ascontiguousarray(_d853.A[s, :s]) for s in range(_N_STAGES + 1, _N_STAGES_EXTENDED)
]
_C_EXTRA = [float(c) for c in _d853.C[_N_STAGES + 1 :]]
_D = _d853.D
_D_ARRAY = np.ascontiguousarray(_D)
_INTERPOLATOR_POWER = _d853.INTERPOLATOR_POWER  # 7
_TINY = np.finfo(np.float64).tiny
# The free rigid body's right-hand side as one gather per factor, dy = y[IA] w[WA] − y[IB] w[WB]:
# (L × ω)_i = L_{i+1} ω_{i+2} − L_{i+2} ω_{i+1}, and row r of Ω R (2.52) is
# ω_{r+2} R_{r+1} − ω_{r+1} R_{r+2} (indices mod 3; R's rows stored flat after L).
_P1, _P2 = (1, 2, 0), (2, 0, 1)
_IA = np.array([*_P1, *(3 + 3 * _P1[r] + c for r in range(3) for c in range(3))])
_IB = np.array([*_P2, *(3 + 3 * _P2[r] + c for r in range(3) for c in range(3))])
_WA = np.array([*_P2, *(_P2[r] for r in range(3) for _ in range(3))])
_WB = np.array([*_P1, *(_P1[r] for r in range(3) for _ in range(3))])


@dataclass(frozen=True)
class Solution:
    """States at the output times and the work it took.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Output times (the grid that was asked for, unchanged).
    y : ndarray, shape (n, *y0.shape)
        The state at each output time; ``y[0]`` is the initial state.
    method : str
        ``"rk4"``, ``"dop853"`` or ``"splitting-<order>"``.
    steps : int
        Accepted steps.
    rhs_evals : int
        Right-hand-side calls (for the splitting: exact sub-flows, one sine and
        cosine each).
    rejected_steps : int
        Steps the adaptive method rejected (0 for fixed-step methods).
    """

    t: np.ndarray
    y: np.ndarray
    method: str
    steps: int
    rhs_evals: int
    rejected_steps: int


# ---------------------------------------------------------------- compiled path


class CompiledPathWarning(RuntimeWarning):
    """The compiled path is unavailable (numba missing or a compilation failed): the
    pure-numpy reference path runs instead, with the same results, only slower."""


_KERNELS = None  # the module mechanics._kernels once imported; False after a failure


def _kernels():
    """mechanics._kernels, imported on first use (numba's import is not paid by
    ``import mechanics``), or None with one CompiledPathWarning if that fails."""
    global _KERNELS
    if _KERNELS is None:
        try:
            kernels = importlib.import_module(f"{__package__}._kernels")
        except Exception as exc:  # numba missing or broken: the reference path
            _compiled_failed(exc)
        else:
            _KERNELS = kernels
    return _KERNELS or None


def _compiled_failed(exc: BaseException) -> None:
    """Give up the compiled path for this process, saying why once."""
    global _KERNELS
    _KERNELS = False
    warnings.warn(
        f"the compiled steppers are unavailable ({type(exc).__name__}: {exc}); "
        f"mechanics.integrators runs its pure-numpy reference path instead (same "
        f"results, slower)",
        CompiledPathWarning,
        stacklevel=3,
    )


def _run_compiled(name: str, *args):
    """kernels.<name>(*args), or None (after one warning) if the kernel cannot be
    compiled or loaded: the caller then runs the reference path."""
    k = _kernels()
    if k is None:
        return None
    try:
        return getattr(k, name)(*args)
    except Exception as exc:  # a failed JIT (numba's errors are not one class)
        _compiled_failed(exc)
        return None


# --------------------------------------------------------------------- validation


_positive_scalar = as_positive_scalar


def _check_times(t) -> np.ndarray:
    tt = as_float_array(t, "t")
    if tt.ndim != 1 or tt.shape[0] < 2:
        raise ShapeError(
            f"t must be a 1-D grid of at least two output times (a span (t0, t1)); "
            f"got shape {tt.shape}"
        )
    steps = np.diff(tt)
    if not (steps > 0).all():
        k = int(np.argmax(~(steps > 0)))
        a, b = float(tt[k + 1]), float(tt[k])
        raise OutOfDomainError(
            f"t must be strictly increasing; t[{k + 1}] = {a!r} ≤ t[{k}] = {b!r}"
        )
    return tt


def _substeps(ta: float, tb: float, h: float) -> int:
    """Equal steps of at most h (up to the rounding of ta and tb) covering [ta, tb].

    On a grid t0 + k h each point is rounded once, so tb − ta = h within an ulp of
    each end; that slack is forgiven, so the grid takes exactly one step per point.
    """
    slack = math.ulp(ta) + math.ulp(tb)
    return max(1, math.ceil((tb - ta) / h * (1.0 - _GRID_RTOL) - slack / h))


#: the fixed-step methods' default budget of steps (the adaptive one's max_steps default)
MAX_STEPS = 10**7


def _check_step_budget(t: np.ndarray, h: float, max_steps: int) -> None:
    """StepSizeError before a fixed-step run that would take more than max_steps steps
    (a span of 1e300 at h = 0.1 would otherwise run for ever, or overflow the count)."""
    n = (float(t[-1]) - float(t[0])) / h
    if not n <= max_steps:  # also catches n = inf
        raise StepSizeError(
            f"h = {h!r} over t = [{float(t[0])!r}, {float(t[-1])!r}] takes {n:.3g} steps, "
            f"more than max_steps = {max_steps}; raise h (or max_steps) or shorten the span"
        )


def _substep_counts(t: np.ndarray, h: float) -> np.ndarray:
    """:func:`_substeps` of every interval of the grid t, as int64."""
    return np.array([_substeps(a, b, h) for a, b in itertools.pairwise(t.tolist())], np.int64)


def time_grid(t0, h, n) -> np.ndarray:
    """The grid t0 + k h, k = 0 … n (each entry rounded once, never accumulated).

    Domain: finite scalars t0 and h > 0, an integer n ≥ 1 (else NonPositiveParameterError); the grid
    has n + 1 entries in memory.

    Examples
    --------
    Ten million steps of 0.1 end where they should; a running sum does not:

    >>> float(time_grid(0.0, 0.1, 10**7)[-1])
    1000000.0
    >>> s = 0.0
    >>> for _ in range(10**5):
    ...     s += 0.1
    >>> s == 10000.0
    False
    """
    t0f = as_float_scalar(t0, "t0")
    hf = _positive_scalar(h, "h")
    if isinstance(n, bool) or not isinstance(n, Integral) or n < 1:
        raise NonPositiveParameterError(f"n must be an integer ≥ 1; got {n!r}")
    return t0f + hf * np.arange(int(n) + 1, dtype=np.float64)


time_grid = finite_result(time_grid)


# ------------------------------------------------------------ right-hand sides


def _wrap_rhs(rhs, shape: tuple[int, ...]):
    """rhs with its output's shape checked on every call (a cheap attribute test)."""

    def f(t, y):
        k = rhs(t, y)
        if getattr(k, "shape", None) != shape:
            try:
                k = np.asarray(k, dtype=np.float64)
            except (TypeError, ValueError) as exc:
                raise ShapeError(f"rhs returned a non-numeric value at t={t!r}: {exc}") from None
            if k.shape != shape:
                raise ShapeError(
                    f"rhs returned shape {k.shape} at t={t!r}; expected y0's shape {shape}"
                )
        return k

    return f


def _checked(f):
    """f that raises NonFiniteError naming the time where it returns NaN or inf."""

    def g(t, y):
        k = f(t, y)
        if not np.isfinite(k).all():
            idx = tuple(int(i) for i in np.argwhere(~np.isfinite(k))[0])
            raise NonFiniteError(
                f"rhs returned a non-finite value at t={float(t)!r}: "
                f"{float(np.asarray(k)[idx])!r} at index {idx}"
            )
        return k

    return g


# -------------------------------------------------------------------------- RK4


def _rk4_run(f, tk: float, hk: float, n: int, y, comp, kahan: bool, check: bool):
    """n RK4 steps of hk from tk; stage times tk + (j + c) hk."""
    half = 0.5 * hk
    sixth = hk / 6.0
    for j in range(n):
        ts = tk + j * hk
        tm = tk + (j + 0.5) * hk
        k1 = f(ts, y)
        k2 = f(tm, y + half * k1)
        k3 = f(tm, y + half * k2)
        k4 = f(tk + (j + 1) * hk, y + hk * k3)
        dy = sixth * (k1 + 2.0 * (k2 + k3) + k4)
        if kahan:
            z = dy - comp
            y_new = y + z
            comp = (y_new - y) - z
            y = y_new
        else:
            y = y + dy
        if check and not np.isfinite(y).all():
            raise ResultOverflowError(
                f"the state overflowed in the RK4 step from t={ts!r} to "
                f"t={tk + (j + 1) * hk!r}; the solution leaves float64 there"
            )
    return y, comp


def _integrate_rk4(f, y0, t, h, kahan):
    ys = np.empty((t.shape[0], *y0.shape))
    ys[0] = y0
    y = y0.copy()
    comp = np.zeros_like(y0)
    steps = 0
    for k in range(t.shape[0] - 1):
        tk = float(t[k])
        d = float(t[k + 1]) - tk
        n = _substeps(tk, float(t[k + 1]), h)
        y_start, c_start = y, comp
        y, comp = _rk4_run(f, tk, d / n, n, y, comp, kahan, check=False)
        if not np.isfinite(y).all():  # find the step and the stage, then raise
            _rk4_run(_checked(f), tk, d / n, n, y_start, c_start, kahan, check=True)
            raise ResultOverflowError(
                f"the state became non-finite between t={tk!r} and t={float(t[k + 1])!r}"
            )  # pragma: no cover
        ys[k + 1] = y
        steps += n
    return ys, steps, 4 * steps, 0


# ----------------------------------------------------------------------- DOP853


def _member_norms(v, nb: int) -> np.ndarray:
    """RMS norm of each batch member (rows of v reshaped to (nb, -1)); one member
    in scipy's arithmetic (``common.norm``), so that the steps agree to the bit."""
    if nb == 1:
        return np.array([np.linalg.norm(v) / v.size**0.5])
    r = v.reshape(nb, -1)
    return np.sqrt((r * r).sum(axis=1) / r.shape[1])


def _dop853_step(f, t, y, f0, h, K, Kv, shape):
    """The 12 stages of one Dormand–Prince 8(5,3) step of h from (t, y): K[:12]
    filled (11 evaluations; K[0] = f0), the increment h Σ b_i k_i returned."""
    K[0] = f0.reshape(-1)
    for s in range(1, _N_STAGES):  # np.dot(K.T, a): scipy's ``rk_step``, the same sums
        dy = np.dot(K[:s].T, _A_ROWS[s])
        Kv[s] = f(t + _C[s] * h, (y + h * dy).reshape(shape))
    return h * np.dot(K[:_N_STAGES].T, _B)


def _dop853_error(K, h, y, y_new, rtol, atol, nb):
    """The error norm of a step (K its 12 stages and f_new): scipy's
    ``DOP853._estimate_error_norm``, and for a batch the largest member's."""
    scale = atol + np.maximum(np.abs(y), np.abs(y_new)) * rtol
    e5 = np.dot(K.T, _E5) / scale
    e3 = np.dot(K.T, _E3) / scale
    if nb == 1:  # scipy's arithmetic, operation for operation: the steps agree to the bit
        e5n = np.linalg.norm(e5) ** 2
        e3n = np.linalg.norm(e3) ** 2
        if e5n == 0:  # (scipy tests both for 0; with e3n tiny, 0.01 e3n underflows: 0/0)
            return 0.0
        return float(abs(h) * e5n / np.sqrt((e5n + 0.01 * e3n) * e5.size))
    e5 = e5.reshape(nb, -1)
    e3 = e3.reshape(nb, -1)
    e5n = (e5 * e5).sum(axis=1)
    e3n = (e3 * e3).sum(axis=1)
    denom = np.maximum(e5n + 0.01 * e3n, _TINY)  # e5n = 0 there, so the ratio is 0
    return float((abs(h) * e5n / np.sqrt(denom * e5.shape[1])).max())


def _dop853_initial_step(f, t0, y, f0, t_end, rtol, atol, nb, max_step=math.inf):
    """Hairer's starting step (as scipy's ``select_initial_step``), batch-aware:
    the state's size by its smallest member, the rates by their largest; at most
    the span t_end − t0 and ``max_step``."""
    scale = atol + np.abs(y) * rtol
    d0 = float(_member_norms(y / scale, nb).min())
    d1 = float(_member_norms(f0.reshape(-1) / scale, nb).max())
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, t_end - t0)
    f1 = f(t0 + h0, (y + h0 * f0.reshape(-1)).reshape(f0.shape))
    d2 = float(_member_norms((f1.reshape(-1) - f0.reshape(-1)) / scale, nb).max()) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100 * h0, h1, t_end - t0, max_step)


def _dop853_advance(f, tc, y, f0, h_abs, t_end, max_step, K, Kv, shape, rtol, atol, nb, comp):
    """One accepted DOP853 step from ``tc`` towards ``t_end``, rejected attempts inside.

    The step control of scipy's ``RungeKutta._step_impl``: the proposed ``h_abs`` is
    capped at ``max_step`` and raised to 10 ulp(tc), each attempt is truncated so
    that it ends exactly on ``t_end``, a rejected attempt shrinks the step by
    max(0.2, 0.9 err^(−1/8)) and an accepted one proposes hh · min(10, 0.9 err^(−1/8))
    (at most hh right after a rejection).  ``comp`` is the Kahan compensation (or
    None): the increment added is then z = incr − comp.

    Returns
    -------
    t_new, y_new, f_new, hh, h_next, evals, rejected, z
        The accepted step hh = t_new − tc (K holds its 12 stages and K[12] =
        f_new), the next proposal, the evaluations and rejections it took, and z
        (None without compensation).
    """
    min_step = 10.0 * math.ulp(tc)
    if max_step < min_step:  # scipy fails here only if the proposal exceeds max_step
        raise StepSizeError(
            f"dop853: max_step={max_step!r} is below the rounding of t={tc!r} "
            f"(10 ulp = {min_step!r})"
        )
    if h_abs > max_step:
        h_abs = max_step
    elif h_abs < min_step:
        h_abs = min_step
    was_rejected = False
    evals = rejected = 0
    z = None
    while True:
        t_new = tc + h_abs
        if t_new >= t_end:
            t_new = t_end
        hh = t_new - tc
        incr = _dop853_step(f, tc, y, f0, hh, K, Kv, shape)
        evals += _N_STAGES
        if comp is None:
            y_new = y + incr
        else:
            z = incr - comp
            y_new = y + z
        f_new = f(t_new, y_new.reshape(shape))
        K[_N_STAGES] = f_new.reshape(-1)
        err = _dop853_error(K, hh, y, y_new, rtol, atol, nb)
        if not math.isfinite(err):
            _dop853_step(_checked(f), tc, y, f0, hh, K, Kv, shape)
            _checked(f)(t_new, y_new.reshape(shape))
            raise ResultOverflowError(
                f"dop853: the state overflowed in the step from t={tc!r} to t={t_new!r}"
            )
        if err < 1.0:
            if err == 0.0:
                factor = DOP853_MAX_FACTOR
            else:
                factor = min(DOP853_MAX_FACTOR, DOP853_SAFETY * err**_DOP853_EXPONENT)
            if was_rejected:
                factor = min(1.0, factor)
            # An infinite y_new makes its scale infinite and so the error norm 0, which
            # would pass (scipy accepts such a step): refuse it.
            if not np.isfinite(y_new).all():
                raise ResultOverflowError(
                    f"dop853: the state overflowed in the step from t={tc!r} to t={t_new!r} "
                    f"(|y| beyond the float64 range, the rates finite)"
                )
            return t_new, y_new, f_new, hh, hh * factor, evals, rejected, z
        rejected += 1
        was_rejected = True
        h_abs = hh * max(DOP853_MIN_FACTOR, DOP853_SAFETY * err**_DOP853_EXPONENT)
        if h_abs < min_step:
            raise StepSizeError(
                f"dop853: the step fell to {h_abs!r}, below the rounding of t={tc!r}; "
                f"rtol={rtol!r}, atol={atol!r} cannot be met there"
            )


def _integrate_dop853(f, y0, t, h, rtol, atol, kahan, batch_ndim, max_steps):
    """Steps chosen by the error control alone, towards t[-1]; the outputs inside a
    step come from its 7th-order continuous extension (3 more evaluations for a
    step that holds any), an output on a step's end is that step's state."""
    shape = y0.shape
    nb = int(np.prod(shape[:batch_ndim], dtype=np.int64)) if batch_ndim else 1
    nt = t.shape[0]
    ys = np.empty((nt, *shape))
    ys[0] = y0
    y = y0.reshape(-1).copy()
    comp = np.zeros_like(y) if kahan else None
    K_ext = np.empty((_N_STAGES_EXTENDED, y.size))
    K = K_ext[: _N_STAGES + 1]
    Kv = K.reshape(_N_STAGES + 1, *shape)
    tc = float(t[0])
    t_final = float(t[-1])
    f0 = _checked(f)(tc, y0)
    evals = 1
    if h is None:
        h_abs = _dop853_initial_step(f, tc, y, f0, t_final, rtol, atol, nb)
        evals += 1
    else:
        h_abs = h
    tl = t.tolist()

    def f_flat(tt, yy):
        return f(tt, yy.reshape(shape)).reshape(-1)

    steps = rejected = 0
    k = 1  # the next output
    while k < nt:
        t_new, y_new, f0, hh, h_abs, ev, rej, z = _dop853_advance(
            f, tc, y, f0, h_abs, t_final, math.inf, K, Kv, shape, rtol, atol, nb, comp
        )
        evals += ev
        rejected += rej
        steps += 1
        j = k
        while j < nt and tl[j] < t_new:
            j += 1
        if j > k:  # outputs strictly inside the step: its continuous extension
            F = _dop853_dense(f_flat, tc, y, y_new, hh, K_ext)
            evals += _N_STAGES_EXTENDED - _N_STAGES - 1
            if not np.isfinite(F).all():
                _dop853_dense(_checked(f_flat), tc, y, y_new, hh, K_ext)
                raise ResultOverflowError(
                    f"dop853: the dense output of the step from t={tc!r} to t={t_new!r} overflowed"
                )
            ys[k:j] = DenseStep(tc, t_new, y, F)(t[k:j]).T.reshape(j - k, *shape)
        if j < nt and tl[j] == t_new:
            ys[j] = y_new.reshape(shape)
            j += 1
        k = j
        if comp is not None:
            comp = (y_new - y) - z
        y, tc = y_new, t_new
        if steps >= max_steps and k < nt:
            raise StepSizeError(
                f"dop853: {steps} steps reached t={tc!r} of {t_final!r}; "
                f"raise max_steps={max_steps} or loosen rtol={rtol!r}"
            )
    return ys, steps, evals, rejected


# -------------------------------------------------------------- DOP853 stepper


def _scalar(x, name: str) -> float:
    a = as_float_array(x, name)
    if a.shape != ():
        raise ShapeError(f"{name} must be a scalar; got shape {a.shape}")
    return float(a)


def _check_max_step(max_step) -> float:
    """max_step > 0, +inf allowed (no cap); NaN, −inf, arrays and non-numbers refused."""
    try:
        a = np.asarray(max_step, dtype=np.float64)
    except (TypeError, ValueError):
        raise ShapeError(f"max_step must be a real number; got {max_step!r}") from None
    if a.shape != ():
        raise ShapeError(f"max_step must be a scalar; got shape {a.shape}")
    v = float(a)
    if not v > 0:
        raise NonPositiveParameterError(f"max_step must be > 0 (inf for no cap); got {v!r}")
    return v


class DenseStep:
    """The 7th-order continuous extension of one DOP853 step over [t_old, t].

    Hairer's ``contd8`` as scipy's ``Dop853DenseOutput``: with x = (τ − t_old)/h,
    h = t − t_old, and the rows F_0 … F_6 of :attr:`F`,

    y(τ) = y_old + x (F_0 + (1 − x) (F_1 + x (F_2 + (1 − x) (F_3 + x (F_4 + (1 − x)
    (F_5 + x F_6)))))),

    evaluated in that order (so that it agrees with scipy's to the last bit).  At
    x = 0 it is y_old exactly; at x = 1 it is y_old + (y − y_old), within one
    rounding of y.  Evaluation outside [t_old, t] extrapolates (not accurate).

    Attributes
    ----------
    t_old, t : float
        The step's ends.
    y_old : ndarray, shape (n,)
        The state at ``t_old`` (read-only).
    F : ndarray, shape (7, n)
        The interpolant's coefficients (read-only).
    """

    __slots__ = ("F", "_rev", "h", "t", "t_old", "y_old")

    def __init__(self, t_old: float, t: float, y_old: np.ndarray, F: np.ndarray):
        self.t_old, self.t = float(t_old), float(t)
        self.h = self.t - self.t_old
        self.y_old = np.array(y_old, dtype=np.float64)
        self.F = np.array(F, dtype=np.float64)
        self.y_old.flags.writeable = False
        self.F.flags.writeable = False
        self._rev = list(reversed(self.F))

    def __call__(self, t) -> np.ndarray:
        """The interpolated state: shape (n,) for a scalar ``t``, (n, k) for a 1-D
        array of k times (scipy's convention)."""
        if type(t) is float and math.isfinite(t):  # the event search's hot path
            x = (t - self.t_old) / self.h
            y = self._rev[0] * x
            for i, f in enumerate(self._rev[1:], start=1):
                y += f
                y *= x if i % 2 == 0 else 1.0 - x
            return y + self.y_old
        ta = as_float_array(t, "t")
        if ta.ndim > 1:
            raise ShapeError(f"t must be a scalar or a 1-D array of times; got shape {ta.shape}")
        if ta.ndim == 0:
            return self(float(ta))
        x = (ta - self.t_old) / self.h
        y = np.zeros((self.y_old.shape[0], ta.shape[0]))
        for i, f in enumerate(self._rev):
            y += f[:, None]
            y *= x if i % 2 == 0 else 1.0 - x
        return y + self.y_old[:, None]

    def __repr__(self) -> str:
        return f"DenseStep(t_old={self.t_old!r}, t={self.t!r}, n={self.y_old.shape[0]})"


def _dop853_dense(f, t_old, y_old, y, h, K) -> np.ndarray:
    """The coefficients F (7, n) of the interpolant over the step of h from (t_old,
    y_old) to y, K (16, n) holding its 12 stages and K[12] = f(t_old + h, y): the
    3 extra stages (3 evaluations) go into K[13:16] (scipy's ``_dense_output_impl``)."""
    for j, s in enumerate(range(_N_STAGES + 1, _N_STAGES_EXTENDED)):
        dy = _A_EXTRA_ROWS[j] @ K[:s]
        K[s] = f(t_old + _C_EXTRA[j] * h, y_old + h * dy)
    F = np.empty((_INTERPOLATOR_POWER, y.shape[0]))
    f_old, f_new = K[0], K[_N_STAGES]
    delta_y = y - y_old
    F[0] = delta_y
    F[1] = h * f_old - delta_y
    F[2] = 2 * delta_y - h * (f_new + f_old)
    F[3:] = h * (_D @ K)
    return F


class DOP853Stepper:
    """Dormand–Prince 8(5,3) one accepted step at a time, with dense output.

    Domain: finite t0 < t_bound, y0 1-D finite with n ≥ 1 entries, rtol > 0 and atol > 0,
    first_step > 0 and max_step > 0 (inf allowed) (else a MechanicsValueError naming
    them); rhs must return finite arrays of y0's shape.

    The stepping interface of scipy's ``scipy.integrate.DOP853`` (``step``,
    ``dense_output``, ``t``, ``y``, ``t_old``, ``status``) on this module's tableau
    and step control, for a caller that inspects every step, such as a scene
    engine locating contact events on each step's polynomial.  The steps are
    scipy's (same initial step, acceptance, factors, ``max_step`` cap), up to the
    rounding of the dot products and norms.

    Parameters
    ----------
    rhs : callable
        ``rhs(t, y)``: float and array of shape (n,) → array of shape (n,).
    t0 : float
        Initial time.
    y0 : array_like, shape (n,)
        Initial state, 1-D (flatten a structured state), finite, n ≥ 1.
    t_bound : float, > t0
        The end: no step passes it, and the last one ends on it exactly.
    rtol, atol : float, > 0
        Error per step at most atol + rtol·|y| in the RMS norm (as
        :func:`integrate`).  Unlike scipy, rtol below 100 eps is kept, not raised
        to 100 eps.
    first_step : float, > 0, optional
        The first attempted step; default Hairer's estimate (2 evaluations).
    max_step : float, > 0
        Cap on every step (``inf``: none).

    Attributes
    ----------
    t, y : float, ndarray (n,)
        The current time and state (``y`` a new array after every step; the
        stepper never writes into it).
    t_old : float or None
        The start of the last step (None before the first).
    t_bound : float
    status : {"running", "finished"}
        "finished" once ``t == t_bound``.
    steps, rhs_evals, rejected_steps : int
        Accepted steps, right-hand-side calls (including the initial-step
        estimate and the 3 of each dense output), rejected attempts.
    h_abs : float
        The next step proposed by the controller (before the ``max_step`` cap
        and the truncation at ``t_bound``).

    Raises
    ------
    UnknownOptionError
        ``rhs`` not callable.
    ShapeError, NonFiniteError
        ``y0`` not 1-D or not finite, ``t0``/``t_bound`` not finite scalars, or
        ``rhs`` returning the wrong shape or NaN/inf at ``t0``.
    OutOfDomainError
        ``t_bound ≤ t0``.
    NonPositiveParameterError
        ``rtol``, ``atol``, ``first_step`` or ``max_step`` ≤ 0.

    Examples
    --------
    Step q'' = −q to t = 1 and read the solution half-way through the last step:

    >>> osc = lambda t, y: np.array([y[1], -y[0]])
    >>> s = DOP853Stepper(osc, 0.0, [1.0, 0.0], 1.0, rtol=1e-10, atol=1e-10)
    >>> while s.status == "running":
    ...     s.step()
    >>> s.t, s.steps
    (1.0, 4)
    >>> dense = s.dense_output()
    >>> tm = 0.5 * (dense.t_old + dense.t)
    >>> bool(np.abs(dense(tm) - [np.cos(tm), -np.sin(tm)]).max() < 1e-10)
    True
    """

    def __init__(
        self,
        rhs,
        t0,
        y0,
        t_bound,
        *,
        rtol=1e-12,
        atol=1e-12,
        first_step=None,
        max_step=math.inf,
    ):
        if not callable(rhs):
            raise UnknownOptionError(f"rhs must be callable rhs(t, y); got {type(rhs).__name__}")
        y = np.array(as_float_array(y0, "y0"), dtype=np.float64, copy=True)
        if y.ndim != 1 or y.shape[0] == 0:
            raise ShapeError(f"y0 must be a non-empty 1-D state (flatten it); got shape {y.shape}")
        t0f = _scalar(t0, "t0")
        tb = _scalar(t_bound, "t_bound")
        if not tb > t0f:
            raise OutOfDomainError(f"t_bound must be > t0; got t_bound={tb!r} ≤ t0={t0f!r}")
        self.rtol = _positive_scalar(rtol, "rtol")
        self.atol = _positive_scalar(atol, "atol")
        self.max_step = _check_max_step(max_step)
        h0 = None if first_step is None else _positive_scalar(first_step, "first_step")
        self._f = _wrap_rhs(rhs, y.shape)
        self.t, self.y, self.t_bound = t0f, y, tb
        self.t_old: float | None = None
        self.status = "running"
        self.steps = self.rejected_steps = 0
        self._K_ext = np.empty((_N_STAGES_EXTENDED, y.shape[0]))
        self._K = self._K_ext[: _N_STAGES + 1]
        self._y_old = y
        self._h = 0.0
        self._dense: DenseStep | None = None
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            self._fy = np.array(_checked(self._f)(t0f, y), dtype=np.float64)
            self.rhs_evals = 1
            if h0 is None:
                h0 = _dop853_initial_step(
                    self._f, t0f, y, self._fy, tb, self.rtol, self.atol, 1, self.max_step
                )
                self.rhs_evals += 1
        self.h_abs = h0

    def step(self) -> None:
        """Take one accepted step (rejected attempts inside), never past ``t_bound``.

        Raises
        ------
        OutOfDomainError
            The stepper has finished (``t == t_bound``).
        StepSizeError
            The step fell below 10 ulp(t) (the tolerance cannot be met there) or
            ``max_step`` is below it; the state is left unchanged.
        ResultOverflowError, NonFiniteError
            The state overflowed, or ``rhs`` returned NaN/inf (naming the time).
        """
        if self.status != "running":
            raise OutOfDomainError(
                f"the stepper has finished: t = t_bound = {self.t!r}; step() needs t < t_bound"
            )
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            t_new, y_new, _, hh, h_next, evals, rejected, _ = _dop853_advance(
                self._f,
                self.t,
                self.y,
                self._fy,
                self.h_abs,
                self.t_bound,
                self.max_step,
                self._K,
                self._K,
                self.y.shape,
                self.rtol,
                self.atol,
                1,
                None,
            )
        self.rhs_evals += evals
        self.rejected_steps += rejected
        self.steps += 1
        self.t_old, self._y_old, self._h = self.t, self.y, hh
        self.t, self.y, self.h_abs = t_new, y_new, h_next
        # f(t, y) from K[12], not the array rhs returned: an rhs that reuses its
        # output buffer would overwrite that one in the dense output's evaluations
        self._fy = self._K[_N_STAGES].copy()
        self._dense = None
        if t_new >= self.t_bound:
            self.status = "finished"

    def dense_output(self) -> DenseStep:
        """The continuous extension over the last step [t_old, t] (3 evaluations the
        first time it is asked for after a step, none after that).

        Raises
        ------
        OutOfDomainError
            No step has been taken yet.
        NonFiniteError, ResultOverflowError
            ``rhs`` returned NaN/inf in an extra stage (naming the time), or the
            interpolant's coefficients overflowed.
        """
        if self.t_old is None:
            raise OutOfDomainError("dense_output() needs a step: t_old is None, call step() first")
        if self._dense is None:
            args = (self.t_old, self._y_old, self.y, self._h, self._K_ext)
            with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                F = _dop853_dense(self._f, *args)
                if not np.isfinite(F).all():  # find the stage and name its time, else:
                    _dop853_dense(_checked(self._f), *args)
                    raise ResultOverflowError(
                        f"dop853: the dense output of the step from t={self.t_old!r} to "
                        f"t={self.t!r} overflowed"
                    )
            self.rhs_evals += _N_STAGES_EXTENDED - _N_STAGES - 1
            self._dense = DenseStep(self.t_old, self.t, self._y_old, F)
        return self._dense

    def __repr__(self) -> str:
        return (
            f"DOP853Stepper(t={self.t!r}, t_bound={self.t_bound!r}, status={self.status!r}, "
            f"steps={self.steps}, rhs_evals={self.rhs_evals})"
        )


# ------------------------------------------------------------------- integrate


def integrate(
    rhs,
    y0,
    t,
    *,
    method: str,
    h=None,
    rtol=None,
    atol=None,
    kahan: bool = False,
    batch_ndim: int = 0,
    max_steps: int = 10**7,
    compiled: bool = True,
) -> Solution:
    """Integrate dy/dt = rhs(t, y) from y(t[0]) = y0, returning y at the times ``t``.

    Domain: finite y0, t strictly increasing with n ≥ 2 entries, method "rk4" (h > 0, at most
    max_steps steps: else StepSizeError before any work) or "dop853" (rtol > 0, atol > 0;
    StepSizeError beyond max_steps or below the rounding of t); rhs finite.

    Parameters
    ----------
    rhs : callable
        ``rhs(t, y)``: float and array of ``y0``'s shape → array of that shape.
    y0 : array_like
        Initial state, any shape; leading axes may be a batch.
    t : array_like, shape (n,), n ≥ 2
        Strictly increasing output times; ``(t0, t1)`` is a span.
    method : {"rk4", "dop853"}
    h : float, optional
        Largest step of ``"rk4"`` (required); initial step of ``"dop853"``
        (optional, else Hairer's estimate).
    rtol, atol : float, optional
        Tolerances of ``"dop853"`` (``rtol`` required, ``atol`` defaults to
        ``rtol``, i.e. components are measured against max(|y|, 1)); the error
        per step is at most atol + rtol·|y| in the RMS norm, as in scipy.
    kahan : bool
        Compensated (Kahan) addition of each step's increment.
    batch_ndim : int
        Leading axes of ``y0`` that index independent members of a batch
        (``"dop853"``: the error norm is the max over members).
    max_steps : int
        ``"dop853"`` raises :class:`~mechanics.errors.StepSizeError` beyond it.
    compiled : bool
        Run :func:`free_rigid_body_rhs`'s problem on the compiled path (the default;
        see the module Conventions); False forces the pure-numpy reference path.

    Returns
    -------
    Solution

    Raises
    ------
    UnknownOptionError
        An unknown ``method`` (naming the choices) or an option the method lacks.
    NonPositiveParameterError
        ``h``, ``rtol`` or ``atol`` ≤ 0, or a required one missing.
    NonFiniteError, ShapeError
        Bad ``y0``/``t``, or ``rhs`` returning NaN/inf or the wrong shape (naming t).
    ResultOverflowError, StepSizeError
        The state overflowed; the adaptive step cannot meet the tolerance.

    Examples
    --------
    y' = −y to t = 1 by RK4 with h = 0.01: error ≈ h⁴/120 e⁻¹ ≈ 3e-11.

    >>> sol = integrate(lambda t, y: -y, 1.0, (0.0, 1.0), method="rk4", h=0.01)
    >>> bool(abs(sol.y[-1] - np.exp(-1.0)) < 1e-10), sol.steps, sol.rhs_evals
    (True, 100, 400)
    >>> sol = integrate(lambda t, y: -y, 1.0, (0.0, 1.0), method="dop853", rtol=1e-12)
    >>> bool(abs(sol.y[-1] - np.exp(-1.0)) < 1e-11)
    True
    """
    if method not in METHODS:
        raise UnknownOptionError(f"method must be one of {METHODS}; got {method!r}")
    if not callable(rhs):
        raise UnknownOptionError(f"rhs must be callable rhs(t, y); got {type(rhs).__name__}")
    y0a = np.array(as_float_array(y0, "y0"), dtype=np.float64, copy=True)
    tt = _check_times(t)
    if isinstance(batch_ndim, bool) or not isinstance(batch_ndim, Integral):
        raise ShapeError(f"batch_ndim must be an integer; got {batch_ndim!r}")
    if not 0 <= batch_ndim <= y0a.ndim:
        raise ShapeError(f"batch_ndim={batch_ndim} must lie in [0, y0.ndim = {y0a.ndim}]")
    if isinstance(max_steps, bool) or not isinstance(max_steps, Integral) or max_steps < 1:
        raise NonPositiveParameterError(f"max_steps must be an integer ≥ 1; got {max_steps!r}")
    f = _wrap_rhs(rhs, y0a.shape)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        if method == "rk4":
            if rtol is not None or atol is not None:
                raise UnknownOptionError(
                    "rtol/atol are options of the adaptive method 'dop853'; "
                    "'rk4' takes a fixed step h"
                )
            if h is None:
                raise NonPositiveParameterError("method 'rk4' needs a step h > 0; got None")
            hh = _positive_scalar(h, "h")
            _check_step_budget(tt, hh, max_steps)
            out = _rk4_compiled(rhs, y0a, tt, hh) if compiled and not kahan else None
            if out is None:
                out = _integrate_rk4(f, y0a, tt, hh, bool(kahan))
        else:
            if rtol is None:
                raise NonPositiveParameterError("method 'dop853' needs rtol > 0; got None")
            r = _positive_scalar(rtol, "rtol")
            a = r if atol is None else _positive_scalar(atol, "atol")
            hh = None if h is None else _positive_scalar(h, "h")
            out = None
            if compiled and not kahan:
                out = _dop853_compiled(rhs, y0a, tt, hh, r, a, int(batch_ndim), int(max_steps))
            if out is None:
                out = _integrate_dop853(
                    f, y0a, tt, hh, r, a, bool(kahan), int(batch_ndim), int(max_steps)
                )
    ys, steps, evals, rej = out
    return _solution(tt, ys, method, steps, evals, rej)


# ------------------------------------------------------------- compiled drivers


def _free_body_args(rhs, y0):
    """(J per body (bodies, 3), flat y0) if ``rhs`` is :func:`free_rigid_body_rhs`'s and
    its moments broadcast onto y0's bodies; else None (the reference path runs)."""
    Jm = getattr(rhs, "free_body_moments", None)
    if Jm is None or y0.shape[-1:] != (12,):
        return None
    try:
        Jb = np.broadcast_to(Jm, (*y0.shape[:-1], 3))
    except ValueError:
        return None  # the reference raises the ShapeError
    return np.ascontiguousarray(Jb.reshape(-1, 3)), np.ascontiguousarray(y0.reshape(-1))


def _rk4_compiled(rhs, y0, t, h):
    args = _free_body_args(rhs, y0)
    if args is None:
        return None
    ns = _substep_counts(t, h)
    ys = np.empty((t.shape[0], y0.size))
    done = _run_compiled("rk4_free_body", *args, t, ns, ys)
    if done is None or done[0] != 0:  # the reference raises, naming the time
        return None
    return ys.reshape(t.shape[0], *y0.shape), done[1], 4 * done[1], 0


def _dop853_compiled(rhs, y0, t, h, rtol, atol, batch_ndim, max_steps):
    args = _free_body_args(rhs, y0)
    if args is None:
        return None
    nb = int(np.prod(y0.shape[:batch_ndim], dtype=np.int64)) if batch_ndim else 1
    ys = np.empty((t.shape[0], y0.size))
    ctrl = np.array([DOP853_SAFETY, DOP853_MIN_FACTOR, DOP853_MAX_FACTOR, _DOP853_EXPONENT])
    done = _run_compiled(
        "dop853_free_body",
        *args,
        t,
        -1.0 if h is None else h,
        rtol,
        atol,
        nb,
        max_steps,
        _A_FULL,
        _B,
        _C_ARRAY,
        _E3,
        _E5,
        _D_ARRAY,
        ctrl,
        ys,
    )
    if done is None or done[0] != 0:  # the reference raises, naming the time
        return None
    return ys.reshape(t.shape[0], *y0.shape), done[1], done[2], done[3]


def _solution(t, ys, method, steps, evals, rejected) -> Solution:
    t = t.copy()
    t.flags.writeable = False
    ys.flags.writeable = False
    return Solution(t, ys, method, int(steps), int(evals), int(rejected))


# ------------------------------------------------------------------ rigid body


def _check_moments(J) -> np.ndarray:
    Jm = as_float_array(J, "J", (3,))
    if not (Jm > 0).all():
        idx = tuple(int(i) for i in np.argwhere(~(Jm > 0))[0])
        raise NonPhysicalInertiaError(
            f"J (the principal moments) must be > 0; J{idx[-1] + 1} = {float(Jm[idx])!r} "
            f"at index {idx}"
        )
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        bad = Jm[..., i] > Jm[..., j] + Jm[..., k]
        if bad.any():
            idx = tuple(int(x) for x in np.argwhere(bad)[0])
            Ji = Jm[idx] if Jm.ndim > 1 else Jm
            raise NonPhysicalInertiaError(
                f"J breaks the triangle inequality J{j + 1} + J{k + 1} ≥ J{i + 1}: "
                f"moments {Ji.tolist()}"
            )
    return Jm


def rigid_body_state(L_A, R_A_O) -> np.ndarray:
    """The 12-vector (L_A, rows of ^A R^O) of a free rigid body, shape (..., 12).

    Domain: finite L_A (..., 3) and R_A_O (..., 3, 3) that broadcast (R_A_O is not checked for
    orthogonality: a drifted state is a state too).

    Examples
    --------
    >>> y = rigid_body_state([1.0, 2.0, 3.0], np.eye(3))
    >>> y.shape, y[:4].tolist()
    ((12,), [1.0, 2.0, 3.0, 1.0])
    """
    L = as_float_array(L_A, "L_A", (3,))
    R = check_rotation(R_A_O)
    batch = np.broadcast_shapes(L.shape[:-1], R.shape[:-2])
    L = np.broadcast_to(L, (*batch, 3))
    R = np.broadcast_to(R, (*batch, 3, 3)).reshape(*batch, 9)
    return np.concatenate([L, R], axis=-1)


rigid_body_state = broadcast_checked(rigid_body_state)


def rigid_body_parts(y) -> tuple[np.ndarray, np.ndarray]:
    """(L_A, R_A_O) of rigid-body states ``y`` of shape (..., 12) (views, not checked
    for orthogonality: an integrator's R may have drifted, which is the point).

    Domain: any finite y of shape (..., 12) (else ShapeError or NonFiniteError).
    """
    a = as_float_array(y, "y", (12,))
    return a[..., :3], a[..., 3:].reshape(*a.shape[:-1], 3, 3)


def free_rigid_body_rhs(J):
    """The right-hand side rhs(t, y) of the torque-free rigid body for :func:`integrate`.

    Domain: principal moments J > 0 obeying the triangle inequality (else NonPhysicalInertiaError),
    shape (..., 3); the returned rhs takes finite states.

    dL_A/dt = L_A × ω_A (Euler's equations (4.47) with M = 0, ω_i = L_i/J_i) and
    dR_A_O/dt = Ω R_A_O with the book's Ω of ω_A (2.52); ``y`` is the state of
    :func:`rigid_body_state`, shape (..., 12), and ``J`` broadcasts against its
    leading axes.

    Examples
    --------
    d/dt of 2T = Σ L_i²/J_i vanishes:

    >>> J = np.array([1.0, 2.0, 2.5])
    >>> y = rigid_body_state([0.3, -1.0, 0.7], np.eye(3))
    >>> dy = free_rigid_body_rhs(J)(0.0, y)
    >>> bool(abs(np.sum(y[:3] / J * dy[:3])) < 1e-15)
    True
    """
    Jm = _check_moments(J)

    def rhs(t, y):
        if y.shape[-1:] != (12,):
            raise ShapeError(f"rigid-body state must have shape (..., 12); got {y.shape}")
        w = y[..., :3] / Jm
        return y.take(_IA, axis=-1) * w.take(_WA, axis=-1) - y.take(_IB, axis=-1) * w.take(
            _WB, axis=-1
        )

    rhs.free_body_moments = Jm  # what integrate's compiled path recognises
    return rhs


def so3_exp_step(R_A_O, w_A, h) -> np.ndarray:
    """^A R^O after a time h of constant body angular velocity ω_A: exp(h Ω) ^A R^O.

    Domain: finite R_A_O (..., 3, 3), w_A (..., 3) and h that broadcast; any rotation angle h|ω|
    (reduced modulo 2π by :func:`~mechanics.rotation.matrix_from_rotvec`).

    dR/dt = Ω R with the book's Ω (2.46), (2.52) integrates for constant ω_A to
    exp(h Ω) R, and exp(h Ω) is the passive matrix ^A R^O(h ω_A) of the rotation
    vector h ω_A (2.29) (:func:`mechanics.rotation.matrix_from_rotvec`).  The
    result is a rotation to rounding; n steps drift from orthogonality like a
    random walk of n roundings, never secularly.

    Parameters
    ----------
    R_A_O : array_like, shape (..., 3, 3)
    w_A : array_like, shape (..., 3)
        Body components of ω.
    h : float, > 0

    Examples
    --------
    Example 2.2: R3(ψ) turning with ω = ψ̇ e3 is R3(ψ + h ψ̇) after h.

    >>> from mechanics.rotation import R3
    >>> R = so3_exp_step(R3(0.4), [0.0, 0.0, 2.0], 0.1)
    >>> bool(np.abs(R - R3(0.6)).max() < 4 * EPS)
    True
    """
    R = check_rotation(R_A_O)
    w = as_float_array(w_A, "w_A", (3,))
    hf = _positive_scalar(h, "h")
    return matrix_from_rotvec(hf * w) @ R


so3_exp_step = broadcast_checked(so3_exp_step)


# ------------------------------------------------------------------- splitting


def _merge(seq):
    out: list[list] = []
    for axis, c in seq:
        if out and out[-1][0] == axis:
            out[-1][1] += c
        else:
            out.append([axis, c])
    return [(a, c) for a, c in out]


def _strang(tau: float):
    return [(0, tau / 2), (1, tau / 2), (2, tau), (1, tau / 2), (0, tau / 2)]


def _triple_jump(step, p: int):
    """Yoshida's symmetric composition Φ(γ1 τ) Φ(γ2 τ) Φ(γ1 τ), order p → p + 2."""
    g1 = 1.0 / (2.0 - 2.0 ** (1.0 / (p + 1)))
    g2 = 1.0 - 2.0 * g1

    def composed(tau):
        return step(g1 * tau) + step(g2 * tau) + step(g1 * tau)

    return composed


def _schedule(order: int):
    """(axis, fraction of h) of one step, adjacent same-axis flows merged."""
    step = _strang
    for p in range(2, order, 2):
        step = _triple_jump(step, p)
    return _merge(step(1.0))


_SCHEDULES = {p: _schedule(p) for p in SPLITTING_ORDERS}

#: Steps between two removals of the rounding drift of the splitting.  A steady
#: rotation repeats one rounded (cos, sin) pair, whose c² + s² − 1 (up to ~1 eps)
#: then adds up linearly: |L| and R Rᵀ would drift by up to 1 eps per sub-flow
#: (measured: 293 eps after 4050 flows of a spherical top).  Every this many steps
#: |L| is rescaled to |L0| and R takes one Newton–Schulz step
#: R ← R − ½ (R Rᵀ − 1) R (as :func:`mechanics.rotation.nearest_rotation`), which
#: moves them by their rounding drift only (≤ 64 × 36 eps), never by the method's
#: truncation error, since the exact sub-flows keep both.
PROJECT_EVERY = 64


def _project_scalar(L, R, norm0):
    n = math.sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2])
    if n > 0.0:
        f = norm0 / n
        L[:] = [L[0] * f, L[1] * f, L[2] * f]
    M = np.array(R)
    M = M - 0.5 * ((M @ M.T - np.eye(3)) @ M)
    R[:] = M.tolist()


def _project_batch(L, R, norm0):
    n = np.sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2])
    f = np.where(n > 0.0, norm0 / np.where(n > 0.0, n, 1.0), 1.0)
    L[:] = [L[0] * f, L[1] * f, L[2] * f]
    M = np.stack(R, axis=-2)
    M = M - 0.5 * ((M @ np.swapaxes(M, -1, -2) - np.eye(3)) @ M)
    R[:] = [M[..., 0, :], M[..., 1, :], M[..., 2, :]]


_NEXT = ((1, 2), (2, 0), (0, 1))  # (j, k) of the turn about axis i


def _interval_flows(seq_h, head, join, n):
    """The sub-flows of n steps, as (first step, inner step, last step) lists: the
    closing H1 half-flow of a step and the opening one of the next are one flow."""
    if n == 1:
        return [(0, head), *seq_h, (0, head)], [], []
    return [(0, head), *seq_h, (0, join)], [*seq_h, (0, join)], [*seq_h, (0, head)]


def _split_run_scalar(J, L, R, seq_h, head, join, n):
    """One body in Python floats (math.cos/sin): n steps of the schedule."""
    cos, sin = math.cos, math.sin
    first, inner, last = _interval_flows(seq_h, head, join, n)
    for j in range(n):
        this = first if j == 0 else (inner if j < n - 1 else last)
        for i, c in this:
            a, b = _NEXT[i]
            ang = c * (L[i] / J[i])
            co, si = cos(ang), sin(ang)
            La, Lb = L[a], L[b]
            L[a] = co * La + si * Lb
            L[b] = co * Lb - si * La
            Ra, Rb = R[a], R[b]
            R[a] = [co * Ra[0] + si * Rb[0], co * Ra[1] + si * Rb[1], co * Ra[2] + si * Rb[2]]
            R[b] = [co * Rb[0] - si * Ra[0], co * Rb[1] - si * Ra[1], co * Rb[2] - si * Ra[2]]
    return len(first) + max(n - 2, 0) * len(inner) + (len(last) if n > 1 else 0)


def _kahan_add(x, d, c):
    """x + d by Kahan summation with the running compensation c: (sum, new c)."""
    y = d - c
    s = x + y
    return s, (s - x) - y


def _split_run_compensated(J, L, R, cL, cR, seq_h, head, join, n, sin):
    """n steps of the schedule, each turn added as an increment by Kahan summation
    (the compiled ``_flow_compensated``): L, cL lists of 3, R, cR lists of 3 rows;
    floats (``sin = math.sin``) or arrays of a batch (``np.sin``)."""
    first, inner, last = _interval_flows(seq_h, head, join, n)
    for j in range(n):
        this = first if j == 0 else (inner if j < n - 1 else last)
        for i, c in this:
            a, b = _NEXT[i]
            ang = c * (L[i] / J[i])
            s2 = sin(0.5 * ang)
            cm = -2.0 * s2 * s2
            si = sin(ang)
            La, Lb = L[a], L[b]
            L[a], cL[a] = _kahan_add(La, cm * La + si * Lb, cL[a])
            L[b], cL[b] = _kahan_add(Lb, cm * Lb - si * La, cL[b])
            for m in range(3):
                Ra, Rb = R[a][m], R[b][m]
                R[a][m], cR[a][m] = _kahan_add(Ra, cm * Ra + si * Rb, cR[a][m])
                R[b][m], cR[b][m] = _kahan_add(Rb, cm * Rb - si * Ra, cR[b][m])
    return len(first) + max(n - 2, 0) * len(inner) + (len(last) if n > 1 else 0)


def _split_run_batch(J, L, R, seq_h, head, join, n):
    """A batch: L a list of 3 arrays (batch), R a list of 3 row arrays (batch, 3)."""
    first, inner, last = _interval_flows(seq_h, head, join, n)
    for j in range(n):
        this = first if j == 0 else (inner if j < n - 1 else last)
        for i, c in this:
            a, b = _NEXT[i]
            ang = c * (L[i] / J[i])
            co, si = np.cos(ang), np.sin(ang)
            La, Lb = L[a], L[b]
            L[a] = co * La + si * Lb
            L[b] = co * Lb - si * La
            co3, si3 = co[..., None], si[..., None]
            Ra, Rb = R[a], R[b]
            R[a] = co3 * Ra + si3 * Rb
            R[b] = co3 * Rb - si3 * Ra
    return len(first) + max(n - 2, 0) * len(inner) + (len(last) if n > 1 else 0)


def _splitting_compiled(Jm, L, R, tt, hf, batch, scalar, middle, head, compensated=False):
    """The splitting's compiled run: (ys (n, bodies, 12), steps, flows), or None (the
    reference path then runs, and raises if the state overflowed)."""
    Jb = np.ascontiguousarray(np.broadcast_to(Jm, (*batch, 3)).reshape(-1, 3))
    Lb = np.ascontiguousarray(np.broadcast_to(L, (*batch, 3)).reshape(-1, 3))
    Rb = np.ascontiguousarray(np.broadcast_to(R, (*batch, 3, 3)).reshape(-1, 3, 3))
    if scalar:  # the reference's norms: math.hypot for one body, nested np.hypot for many
        norm0 = np.array([math.hypot(*Lb[0].tolist())])
    else:
        norm0 = np.hypot(np.hypot(Lb[:, 0], Lb[:, 1]), Lb[:, 2])
    ns = _substep_counts(tt, hf)
    axes = np.array([i for i, _ in middle], dtype=np.int64)
    fracs = np.array([c for _, c in middle], dtype=np.float64)
    ys = np.empty((tt.shape[0], Jb.shape[0], 12))
    done = _run_compiled(
        "splitting_free_body",
        Jb,
        Lb,
        Rb,
        norm0,
        tt,
        ns,
        axes,
        fracs,
        float(head),
        PROJECT_EVERY,
        bool(compensated),
        ys,
    )
    if done is None or done[0] != 0:
        return None
    return ys, int(ns.sum()), done[1] // Jb.shape[0]


def free_rigid_body_splitting(
    J, L0, R0, t, h, *, order: int = 2, compiled: bool = True, compensated: bool = False
) -> Solution:
    """Torque-free rigid body by the Lie–Poisson splitting into exact axis rotations.

    Domain: J as :func:`free_rigid_body_rhs`, finite L0, R0 a rotation, t strictly increasing, h > 0
    with at most ``MAX_STEPS`` steps (else StepSizeError before any work), order in
    ``SPLITTING_ORDERS`` (else UnknownOptionError).

    H = Σ L_i²/(2 J_i) = H1 + H2 + H3.  The flow of H_i alone keeps L_i and
    ω = (L_i/J_i) e_i constant, so over a time τ it turns both L_A and the
    attitude by the basic matrix R_i(τ L_i/J_i) of (2.30): L_A ← R_i L_A and
    ^A R^O ← R_i ^A R^O (L_O = (^A R^O)ᵀ L_A stays fixed).  One step is the
    symmetric composition (Strang) H1(h/2) H2(h/2) H3(h) H2(h/2) H1(h/2), order 2,
    or its Yoshida triple jump (order 4, and again for orders 6 and 8); the half-steps
    of H1 that meet between steps are merged.  Every sub-flow is an exact
    rotation, so |L| is kept to rounding, each L_i is kept exactly by its own
    sub-flow, the attitude stays on SO(3) to rounding, and the map is a
    Lie–Poisson map: the energy error stays bounded (O(h^order)) for all times.
    The rounding drift of |L| and of R Rᵀ is removed every :data:`PROJECT_EVERY`
    steps and at each output time (a steady rotation would otherwise repeat one
    rounded cosine–sine pair and drift linearly).

    Parameters
    ----------
    J : array_like, shape (..., 3)
        Principal moments (J1, J2, J3) about G, > 0, triangle inequality.
    L0 : array_like, shape (..., 3)
        Initial angular momentum, body components.
    R0 : array_like, shape (..., 3, 3)
        Initial attitude ^A R^O.
    t : array_like, shape (n,)
        Output times, strictly increasing (see the module Conventions).
    h : float
        Largest step.
    order : {2, 4, 6, 8}
    compiled : bool
        The compiled kernel (default) or, with False, the pure-numpy reference path
        (see the module Conventions).
    compensated : bool
        Add each turn to the state as an increment ((cos θ − 1) x + sin θ y, with
        cos θ − 1 = −2 sin²(θ/2)) by Kahan summation, the compensations carried from
        flow to flow and across outputs; no projection (a turn's rounding then changes
        |L| and R Rᵀ by ~eps θ², not eps).  The rounding error of the state then grows
        like √n instead of n (module Conventions, "Compensated splitting").

    Returns
    -------
    Solution
        ``y`` of shape (n, *batch, 12): the state of :func:`rigid_body_state`
        (split it with :func:`rigid_body_parts`); ``rhs_evals`` counts sub-flows.

    Examples
    --------
    |L| and the energy after 1000 steps:

    >>> J, L0 = np.array([1.0, 2.0, 2.5]), np.array([0.3, -1.0, 0.7])
    >>> sol = free_rigid_body_splitting(J, L0, np.eye(3), (0.0, 100.0), 0.1)
    >>> L, R = rigid_body_parts(sol.y[-1])
    >>> bool(abs(np.linalg.norm(L) / np.linalg.norm(L0) - 1) < 1e-14)
    True
    >>> E = lambda L: 0.5 * np.sum(L**2 / J)
    >>> bool(abs(E(L) / E(L0) - 1) < 1e-2), sol.steps
    (True, 1000)
    """
    if isinstance(order, bool) or order not in SPLITTING_ORDERS:
        raise UnknownOptionError(f"order must be one of {SPLITTING_ORDERS}; got {order!r}")
    if not isinstance(compensated, bool | np.bool_):
        raise UnknownOptionError(f"compensated must be True or False; got {compensated!r}")
    Jm = _check_moments(J)
    L = as_float_array(L0, "L0", (3,))
    R = check_rotation(R0, name="R0")
    tt = _check_times(t)
    hf = _positive_scalar(h, "h")
    _check_step_budget(tt, hf, MAX_STEPS)
    batch = np.broadcast_shapes(Jm.shape[:-1], L.shape[:-1], R.shape[:-2])
    sched = _SCHEDULES[order]
    head = sched[0][1]  # the schedule is symmetric: it starts and ends with (0, head)
    middle = sched[1:-1]
    ys = np.empty((tt.shape[0], *batch, 12))
    ys[0] = rigid_body_state(np.broadcast_to(L, (*batch, 3)), np.broadcast_to(R, (*batch, 3, 3)))
    scalar = batch == ()
    if compiled:
        out = _splitting_compiled(Jm, L, R, tt, hf, batch, scalar, middle, head, compensated)
        if out is not None:
            ys[1:] = out[0][1:].reshape(tt.shape[0] - 1, *batch, 12)
            return _solution(tt, ys, f"splitting-{order}", out[1], out[2], 0)
    if scalar:
        Js = [float(x) for x in Jm]
        Ls = [float(x) for x in L]
        Rs = [[float(x) for x in row] for row in R]
        norm0 = math.hypot(*Ls)
        run, project = _split_run_scalar, _project_scalar
    else:
        Jb = np.broadcast_to(Jm, (*batch, 3))
        Js = [np.ascontiguousarray(Jb[..., i]) for i in range(3)]
        Lb = np.broadcast_to(L, (*batch, 3))
        Ls = [np.array(Lb[..., i]) for i in range(3)]
        Rb = np.broadcast_to(R, (*batch, 3, 3))
        Rs = [np.array(Rb[..., i, :]) for i in range(3)]
        norm0 = np.hypot(np.hypot(Ls[0], Ls[1]), Ls[2])
        run, project = _split_run_batch, _project_batch
    if compensated:
        zero = 0.0 if scalar else np.zeros(batch)
        cL = [zero] * 3
        cR = [[zero] * 3 for _ in range(3)]
        Rs = [list(row) if scalar else [row[..., m] for m in range(3)] for row in Rs]
        sin = math.sin if scalar else np.sin

        def run(Js, Ls, Rs, seq_h, head, join, m):
            return _split_run_compensated(Js, Ls, Rs, cL, cR, seq_h, head, join, m, sin)

        def project(Ls, Rs, norm0):
            return None

    steps = flows = 0
    with np.errstate(over="ignore", invalid="ignore"):
        for k in range(tt.shape[0] - 1):
            d = float(tt[k + 1]) - float(tt[k])
            n = _substeps(float(tt[k]), float(tt[k + 1]), hf)
            hk = d / n
            seq_h = [(i, c * hk) for i, c in middle]
            for first in range(0, n, PROJECT_EVERY):
                m = min(PROJECT_EVERY, n - first)
                flows += run(Js, Ls, Rs, seq_h, head * hk, 2.0 * head * hk, m)
                project(Ls, Rs, norm0)
            steps += n
            if scalar:
                ys[k + 1] = [*Ls, *Rs[0], *Rs[1], *Rs[2]]
            elif compensated:  # rows kept as lists of components
                ys[k + 1, ..., :3] = np.stack(Ls, axis=-1)
                ys[k + 1, ..., 3:] = np.stack([x for row in Rs for x in row], axis=-1)
            else:
                ys[k + 1, ..., :3] = np.stack(Ls, axis=-1)
                ys[k + 1, ..., 3:] = np.concatenate(Rs, axis=-1)
            if not np.isfinite(ys[k + 1]).all():
                raise ResultOverflowError(
                    f"the splitting overflowed between t={float(tt[k])!r} and "
                    f"t={float(tt[k + 1])!r}: |L|·h/J too large for float64"
                )
    return _solution(tt, ys, f"splitting-{order}", steps, flows, 0)


free_rigid_body_splitting = broadcast_checked(free_rigid_body_splitting)
