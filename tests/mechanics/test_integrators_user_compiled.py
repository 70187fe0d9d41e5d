"""A user's numba-compiled right-hand side (issue 30, item 2): the whole stepper compiled,
with dense output, the PI step control and terminal events, against the reference path.

The reference path (``compiled=False``) calls the same compiled functions from Python, so
the two differ only in the stepper's own arithmetic: RK4 is the same operations in the
same order (bit for bit); DOP853's stage sums are a loop in the kernel and a BLAS dot in
the reference (the bound of ``test_integrators_compiled``).  The kernels are also run
directly (``_dop853_user``, ``_rk4_user``), so that under mutation, where numba's JIT is
off and ``njit`` returns the plain function, they still run (as Python) against the
reference.  Every compiled run here fails if it silently fell back to the reference.
"""

from __future__ import annotations

import math
import re
import warnings

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from numba import njit

from mechanics import _kernels_rhs as kernels_rhs
from mechanics._floats import EPS
from mechanics.errors import (
    NonFiniteError,
    OutOfDomainError,
    ShapeError,
    StepSizeError,
    UnknownOptionError,
)
from mechanics.integrators import CompiledPathWarning, DOP853Stepper, integrate
from mechanics.integrators import _compiled as compiled_path
from mechanics.integrators._compiled import is_numba_function
from mechanics.integrators._dop853 import _KERNEL_TABLEAU, _dop853_user
from mechanics.integrators._events import EVENT_XTOL, bracket_step, crosses
from mechanics.integrators._rk4 import _rk4_user

pytestmark = pytest.mark.filterwarnings("error::mechanics.integrators.CompiledPathWarning")

#: DOP853's kernel against the reference on the same compiled functions.  The stage sums
#: are a loop there and a BLAS dot here; with DOP853's large coefficients (row sums of
#: |a| up to 96) they round apart by hundreds of eps in a long step, and the step control
#: answers to its error estimate's rounding (a cancelling sum), so the two runs may take
#: steps of other sizes, even other numbers of steps.  Both are then DOP853 solutions,
#: each within about 1.5 rtol of the truth on the oscillator (the integrators' docstring),
#: outputs inside a step from interpolants of the same order: apart by at most their two
#: errors, 4 rtol.  Measured over 1500 random runs: 0.06 rtol at most at the steps' ends,
#: 0.26 at an interpolated output (hypothesis, y0 = (0, 1e-12), rtol 1e-12, β = 0.04).
DOP853_RTOL_MULTIPLE = 4
#: where both take the same steps, measured at most 5.5e3 eps per step at rtol 1e-6
#: (large steps), 180 at 1e-9, 10 at 1e-12 over the same 900 runs
DOP853_EPS_PER_STEP = 2**13
#: an event's time, kernel against reference: each brackets the crossing to EVENT_XTOL
#: (4 eps) relative on its own interpolant, which differ by rounding: 4 + 4 + slack
EVENT_EPS = 16


@pytest.fixture(autouse=True)
def _kernels_loadable(monkeypatch):
    """Each test starts with both kernel modules loadable (a test of a failure gives the
    path up for the process)."""
    monkeypatch.setattr(compiled_path, "_KERNELS", None)
    monkeypatch.setattr(compiled_path, "_RHS_KERNELS", None)


def _forced(t, y):
    """A damped, forced oscillator with a time-dependent term (stage times matter)."""
    return np.array([y[1], -y[0] - 0.1 * y[1] + 0.3 * math.cos(1.3 * t)])


def _pendulum(t, y):
    return np.array([y[1], -math.sin(y[0])])


def _oscillator(t, y):
    return np.array([y[1], -y[0]])


def _first(t, y):
    return y[0]


def _speed(t, y):
    return y[1]


forced, pendulum, oscillator = njit(_forced), njit(_pendulum), njit(_oscillator)
first, speed = njit(_first), njit(_speed)
#: numba's JIT is on (off under mutation, NUMBA_DISABLE_JIT=1: njit returns the plain
#: function, integrate runs the reference path, and only the direct kernel runs compare)
JIT = is_numba_function(forced)
needs_jit = pytest.mark.skipif(not JIT, reason="numba's JIT is off (NUMBA_DISABLE_JIT=1)")


def _eps_diff(a, b) -> float:
    return float(np.abs(a - b).max() / (EPS * max(1.0, float(np.abs(b).max()))))


def _reference(rhs, y0, t, **kw):
    return integrate(rhs, y0, t, compiled=False, **kw)


states = st.tuples(
    st.floats(-2.0, 2.0, allow_nan=False), st.floats(-2.0, 2.0, allow_nan=False)
).map(np.array)


@settings(max_examples=40, deadline=None)
@given(
    y0=states,
    n_out=st.integers(2, 40),
    span=st.floats(0.5, 20.0),
    rtol=st.sampled_from([1e-6, 1e-9, 1e-12]),
    beta=st.sampled_from([0.0, 0.04, 0.08]),
)
# found on Python 3.13 (the CI's matrix leg): an interpolated output 0.26 rtol apart
@example(y0=np.array([0.0, 1e-12]), n_out=3, span=14.0, rtol=1e-12, beta=0.04)
def test_the_dop853_kernel_is_the_reference_method(y0, n_out, span, rtol, beta):
    t = np.linspace(0.0, span, n_out)
    ref = _reference(forced, y0, t, method="dop853", rtol=rtol, beta=beta)
    (ys, *_), hit = _dop853_user(forced, y0, t, None, rtol, rtol, 1, 10**7, beta, None, 0.0)
    bound = DOP853_RTOL_MULTIPLE * rtol * max(1.0, float(np.abs(ref.y).max()))
    assert hit is None
    assert np.abs(ys - ref.y).max() <= bound
    run = integrate(forced, y0, t, method="dop853", rtol=rtol, beta=beta)
    assert np.abs(run.y - ref.y).max() <= bound


@pytest.mark.parametrize("beta", [0.0, 0.04, 0.08])
@pytest.mark.parametrize("rtol", [1e-6, 1e-9, 1e-12])
def test_the_dop853_kernel_takes_the_reference_steps(rtol, beta):
    """A run whose error estimates stay clear of their rounding: the same steps, rejections
    and evaluations, and states apart by the stage sums' rounding only."""
    t = np.linspace(0.0, 10.0, 21)
    y0 = np.array([1.0, 0.5])
    ref = _reference(forced, y0, t, method="dop853", rtol=rtol, beta=beta)
    (ys, steps, evals, rej), _ = _dop853_user(
        forced, y0, t, None, rtol, rtol, 1, 10**7, beta, None, 0.0
    )
    assert (steps, evals, rej) == (ref.steps, ref.rhs_evals, ref.rejected_steps)
    assert _eps_diff(ys, ref.y) <= DOP853_EPS_PER_STEP * steps
    if JIT:  # integrate runs this same kernel
        run = integrate(forced, y0, t, method="dop853", rtol=rtol, beta=beta)
        assert (run.steps, run.rhs_evals, run.rejected_steps) == (steps, evals, rej)
        np.testing.assert_array_equal(run.y, ys)


@settings(max_examples=20, deadline=None)
@given(y0=states, n_out=st.integers(2, 12), h=st.floats(0.01, 0.5))
def test_the_rk4_kernel_is_the_reference_to_the_bit(y0, n_out, h):
    t = np.linspace(0.0, 3.0, n_out)
    ref = _reference(forced, y0, t, method="rk4", h=h)
    ys, steps, evals, _ = _rk4_user(forced, y0, t, h)
    assert (steps, evals) == (ref.steps, ref.rhs_evals)
    np.testing.assert_array_equal(ys, ref.y)
    np.testing.assert_array_equal(integrate(forced, y0, t, method="rk4", h=h).y, ref.y)


def test_the_compiled_run_meets_the_exact_solution():
    """Independent of the reference: y'' = −y from (1, 0) is (cos t, −sin t)."""
    t = np.linspace(0.0, 10.0, 101)
    run = integrate(oscillator, np.array([1.0, 0.0]), t, method="dop853", rtol=1e-12)
    exact = np.stack([np.cos(t), -np.sin(t)], axis=1)
    # DOP853's global error is about 1.5 rtol on the oscillator (integrators' docstring)
    assert np.abs(run.y - exact).max() <= 16 * 1e-12


def test_the_pi_control_rejects_fewer_steps_near_the_separatrix():
    """The pendulum from 3 rad (measured: 809 rejections at β = 0, 67 at β = 0.08 over
    100 periods at rtol 1e-9): a step control that ignored β would reject as many."""
    y0 = np.array([3.0, 0.0])
    std = integrate(pendulum, y0, (0.0, 400.0), method="dop853", rtol=1e-9)
    pi = integrate(pendulum, y0, (0.0, 400.0), method="dop853", rtol=1e-9, beta=0.08)
    ref = _reference(pendulum, y0, (0.0, 400.0), method="dop853", rtol=1e-9, beta=0.08)
    assert (pi.steps, pi.rejected_steps) == (ref.steps, ref.rejected_steps)
    assert pi.rejected_steps * 4 < std.rejected_steps, (pi.rejected_steps, std.rejected_steps)
    # the kernel itself, rejections and all (integrate runs the reference under mutation)
    t = np.array([0.0, 400.0])
    for beta in (0.0, 0.08):
        (ys, steps, evals, rej), _ = _dop853_user(
            pendulum, y0, t, None, 1e-9, 1e-9, 1, 10**7, beta, None, 0.0
        )
        ref = _reference(pendulum, y0, t, method="dop853", rtol=1e-9, beta=beta)
        assert (steps, evals, rej) == (ref.steps, ref.rhs_evals, ref.rejected_steps), beta
        assert rej > 0
        assert np.abs(ys - ref.y).max() <= DOP853_RTOL_MULTIPLE * 1e-9 * np.abs(ref.y).max()


@pytest.mark.parametrize("outputs", [41, 1001])
@pytest.mark.parametrize("direction", [-1, 0, 1])
def test_an_event_stops_the_run_at_the_crossing_on_both_paths(direction, outputs):
    """y = cos t: y[0] falls through 0 at π/2, rises at 3π/2.  With 1001 outputs, some
    lie inside the event's step, before the event (kept) and after it (dropped)."""
    t = np.linspace(0.0, 10.0, outputs)
    y0 = np.array([1.0, 0.0])
    kw = {"method": "dop853", "rtol": 1e-13, "event": first, "event_direction": direction}
    run = integrate(oscillator, y0, t, **kw)
    ref = _reference(oscillator, y0, t, **kw)
    want = 1.5 * math.pi if direction == 1 else 0.5 * math.pi
    for r in (run, ref):
        assert r.t_event is not None
        assert r.y_event is not None
        assert abs(r.t_event - want) <= 64 * 1e-13  # DOP853's error (~1.5 rtol), spared
        assert r.t[-1] < r.t_event <= r.t[-1] + 0.25  # the outputs before it, all of them
        np.testing.assert_array_equal(r.t, t[t < r.t_event])
        assert r.y.shape == (r.t.size, 2)
        # the bracket's right end is on or past the crossing
        assert r.y_event[0] * (1.0 if direction == 1 else -1.0) >= 0.0
    assert abs(run.t_event - ref.t_event) <= EVENT_EPS * EPS * run.t_event
    assert _eps_diff(run.y, ref.y) <= DOP853_EPS_PER_STEP * ref.steps
    assert _eps_diff(run.y_event, ref.y_event) <= DOP853_EPS_PER_STEP * ref.steps
    # the kernel itself (integrate runs the reference under mutation): its outputs before
    # the event, and the event's state on the step's extension
    (ys, steps, *_), hit = _dop853_user(
        oscillator, y0, t, None, 1e-13, 1e-13, 1, 10**7, 0.0, first, float(direction)
    )
    assert hit is not None
    assert abs(hit[0] - ref.t_event) <= EVENT_EPS * EPS * ref.t_event
    assert steps == ref.steps
    assert ys.shape == ref.y.shape
    assert _eps_diff(ys, ref.y) <= DOP853_EPS_PER_STEP * ref.steps
    assert _eps_diff(hit[1], ref.y_event) <= DOP853_EPS_PER_STEP * ref.steps


def test_an_event_not_met_leaves_the_whole_grid():
    t = np.linspace(0.0, 1.0, 11)
    kw = {"method": "dop853", "rtol": 1e-10, "event": first, "event_direction": -1}
    for r in (
        integrate(oscillator, np.array([1.0, 0.0]), t, **kw),
        _reference(oscillator, np.array([1.0, 0.0]), t, **kw),
    ):
        assert r.t_event is None
        assert r.y_event is None
        np.testing.assert_array_equal(r.t, t)
        assert r.y.shape == (11, 2)


def test_a_run_that_starts_on_the_event_does_not_stop_there():
    """The bounce: φ = 0 at the start, rising; the next fall through 0 is half a period on."""
    y0 = np.array([0.0, 1.0])
    run = integrate(
        oscillator,
        y0,
        (0.0, 10.0),
        method="dop853",
        rtol=1e-12,
        event=first,
        event_direction=-1,
    )
    assert run.t_event is not None
    assert abs(run.t_event - math.pi) <= 64 * 1e-12


def test_the_event_helpers_decide_and_shrink_as_documented():
    assert crosses(1.0, -1.0, -1)
    assert crosses(1.0, 0.0, -1)
    assert crosses(1.0, -1.0, 0)
    assert not crosses(0.0, -1.0, -1)  # a start on zero is not a crossing
    assert not crosses(1.0, -1.0, 1)
    assert crosses(-1.0, 2.0, 1)
    assert not crosses(-1.0, 2.0, -1)
    assert not crosses(1.0, 2.0, 0)
    # the secant's point, the bisection every fourth step, kept tol/2 inside the ends
    assert bracket_step(0.0, -1.0, 1.0, 3.0, 1e-3, 0) == 0.25
    assert bracket_step(0.0, -1.0, 1.0, 3.0, 1e-3, 3) == 0.5
    assert bracket_step(0.0, -1.0, 1.0, 1e12, 0.1, 0) == 0.05
    assert bracket_step(0.0, -1e12, 1.0, 1.0, 0.1, 0) == 0.95
    assert EVENT_XTOL == 4 * EPS


def test_bad_options_are_refused_by_name():
    y0 = np.array([1.0, 0.0])
    for beta in (-0.01, 0.081, 0.2, float("nan"), True, "0.1"):
        with pytest.raises(OutOfDomainError, match="beta"):
            integrate(oscillator, y0, (0, 1), method="dop853", rtol=1e-6, beta=beta)
    with pytest.raises(UnknownOptionError, match="rk4"):
        integrate(oscillator, y0, (0, 1), method="rk4", h=0.1, event=first)
    with pytest.raises(UnknownOptionError, match="rk4"):
        integrate(oscillator, y0, (0, 1), method="rk4", h=0.1, beta=0.04)
    with pytest.raises(UnknownOptionError, match="batch_ndim=1"):
        integrate(_oscillator, y0, (0, 1), method="dop853", rtol=1e-6, event=_first, batch_ndim=1)
    with pytest.raises(UnknownOptionError, match="callable"):
        integrate(oscillator, y0, (0, 1), method="dop853", rtol=1e-6, event=3.0)
    for d in (2, -0.5, True, "down"):
        with pytest.raises(OutOfDomainError, match="event_direction"):
            integrate(
                oscillator, y0, (0, 1), method="dop853", rtol=1e-6, event=first, event_direction=d
            )


@pytest.mark.parametrize("compiled", [True, False])
def test_a_bad_event_value_is_named_with_its_time(compiled):
    y0 = np.array([1.0, 0.0])

    def vector(t, y):
        return y

    def nan(t, y):
        return math.nan if t > 0.5 else 1.0

    def nan_at_start(t, y):
        return math.nan

    with pytest.raises(ShapeError, match=r"event returned .* at t=0\.0; expected one real"):
        integrate(
            _oscillator, y0, (0, 1), method="dop853", rtol=1e-6, event=vector, compiled=compiled
        )
    # NaN events: compiled, the kernel hands over and the reference names the time
    rhs = oscillator if compiled else _oscillator
    late, early = (njit(nan), njit(nan_at_start)) if compiled else (nan, nan_at_start)
    with pytest.raises(NonFiniteError, match=r"event returned nan at t=(0\.[5-9]|1\.0)"):
        integrate(rhs, y0, (0, 1), method="dop853", rtol=1e-6, event=late, compiled=compiled)
    with pytest.raises(NonFiniteError, match=r"event returned nan at t=0\.0"):
        integrate(rhs, y0, (0, 1), method="dop853", rtol=1e-6, event=early, compiled=compiled)


def test_a_rhs_of_the_wrong_length_is_named_with_its_time():
    @njit
    def short(t, y):
        return y[:1].copy()

    for method, kw in (("dop853", {"rtol": 1e-6}), ("rk4", {"h": 0.1})):
        with pytest.raises(ShapeError, match=r"shape \(1,\) at t=0\.0; expected y0's shape \(2,\)"):
            integrate(short, np.array([1.0, 0.0]), (0, 1), method=method, **kw)


@pytest.mark.parametrize("compiled", [True, False])
def test_rates_beyond_float64_give_a_step_size_error_not_a_division_by_zero(compiled):
    """f0 = 1e300 against rtol = atol = 1e-9: the scaled rates overflow, Hairer's starting
    step underflows to 0 (a ZeroDivisionError before)."""

    @njit
    def huge(t, y):
        return y * y * 1e300

    with pytest.raises(StepSizeError, match=r"starting step at t=0\.0 underflows"):
        integrate(huge, np.array([1.0, 0.0]), (0, 1), method="dop853", rtol=1e-9, compiled=compiled)


def test_a_state_overflow_in_the_kernel_is_reported_as_the_reference_reports_it():
    @njit
    def blowup(t, y):
        return y * y

    kw = {"method": "dop853", "rtol": 1e-6}
    # y' = y² from 1 blows up at t = 1: the step control gives up just before
    with pytest.raises(StepSizeError, match=r"below the rounding of t=1\.0") as compiled_err:
        integrate(blowup, np.array([1.0]), (0.0, 2.0), **kw)
    with pytest.raises(StepSizeError) as reference_err:
        integrate(blowup, np.array([1.0]), (0.0, 2.0), compiled=False, **kw)
    assert str(compiled_err.value) == str(reference_err.value)


@needs_jit
@pytest.mark.filterwarnings("default::mechanics.integrators.CompiledPathWarning")
def test_what_the_kernel_cannot_take_runs_on_the_reference_with_one_warning_that_says_why():
    @njit
    def listed(t, y):
        return [y[1], -y[0]]  # a list: numba types it list(float64), not float64[::1]

    @njit
    def decay(t, y):
        return -y

    y0 = np.array([1.0, 0.0])
    cases = [
        (listed, y0, {}, "does not compile as rhs"),
        (decay, np.ones((2, 2)), {}, r"takes a state of shape \(n,\); y0 has shape \(2, 2\)"),
        (oscillator, y0, {"event": _first}, "event function is not numba-compiled"),
    ]
    for rhs, y, kw, why in cases:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            run = integrate(rhs, y, (0.0, 1.0), method="dop853", rtol=1e-8, **kw)
        ours = [w for w in caught if issubclass(w.category, CompiledPathWarning)]
        assert len(ours) == 1, [str(w.message) for w in caught]
        assert ours[0].filename == __file__  # it points at the caller's line
        assert re.search(why, str(ours[0].message)), str(ours[0].message)
        ref = _reference(rhs, y, (0.0, 1.0), method="dop853", rtol=1e-8, **kw)
        np.testing.assert_array_equal(run.y, ref.y)


@needs_jit
@pytest.mark.filterwarnings("default::mechanics.integrators.CompiledPathWarning")
def test_kernels_that_fail_to_load_leave_the_reference_with_one_warning_naming_the_extra(
    monkeypatch,
):
    real = compiled_path.importlib.import_module

    def no_numba(name, package=None):
        if name == ".._kernels_rhs":
            raise ModuleNotFoundError("No module named 'numba'", name="numba")
        return real(name, package)

    monkeypatch.setattr(compiled_path.importlib, "import_module", no_numba)
    y0 = np.array([1.0, 0.5])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = integrate(forced, y0, (0.0, 2.0), method="dop853", rtol=1e-9)
        again = integrate(forced, y0, (0.0, 2.0), method="rk4", h=0.1)
    said = [str(w.message) for w in caught if issubclass(w.category, CompiledPathWarning)]
    assert len(said) == 2, said  # one per call: the second says the load failed earlier
    assert "bodycheck[fast]" in said[0], said[0]
    assert "failed to load earlier" in said[1], said[1]
    np.testing.assert_array_equal(
        run.y, _reference(forced, y0, (0.0, 2.0), method="dop853", rtol=1e-9).y
    )
    np.testing.assert_array_equal(
        again.y, _reference(forced, y0, (0.0, 2.0), method="rk4", h=0.1).y
    )


@needs_jit
@pytest.mark.filterwarnings("default::mechanics.integrators.CompiledPathWarning")
def test_an_event_numba_cannot_type_is_named_in_the_warning():
    @njit
    def text_event(t, y):
        return "x"  # not a float64

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with pytest.raises(ShapeError, match="event returned 'x'"):
            integrate(
                oscillator,
                np.array([1.0, 0.0]),
                (0.0, 1.0),
                method="dop853",
                rtol=1e-8,
                event=text_event,
            )
    said = [str(w.message) for w in caught if issubclass(w.category, CompiledPathWarning)]
    assert len(said) == 1, said
    assert "(or its event as event(t, y) -> float64)" in said[0], said[0]


# --- The DOP853 kernel run directly, on problems whose every step is known beforehand ----
#
# At rest (y' = 0) every stage is 0 and the error estimate exactly 0; on a drift (y' = c,
# c = (1/2, -2)) the stages are c, exact, and the estimate is the rounding of Σ e_j c
# (~1e-16 / (rtol |y|)), far below 0.09^8: either way every accepted step is the previous
# one times Hairer's largest factor, 10.  From a first step of 1 at t = 0 the steps end at
# 1, 11, 111, ... (cut at t[-1]).  Under mutation (NUMBA_DISABLE_JIT=1) the kernel runs
# as Python; compiled, the same tests run the compiled kernel.

#: Hairer's DOP853 step control as published (Hairer, Nørsett & Wanner, Solving ODEs I,
#: II.10, and scipy's DOP853): safety 0.9, factors 0.2 to 10, exponent −1/8 (order 7 + 1)
HAIRER_CONTROL = (0.9, 0.2, 10.0, -1.0 / 8.0)
#: each DOP853 step calls f 12 times (f at its start is the last step's f_new), a dense
#: output 3 more, the start once
EVALS_PER_STEP, EVALS_PER_DENSE = 12, 3
DRIFT = np.array([0.5, -2.0])
#: the drift's states, exact but for rounding: Σ b_j in the kernel's order is 1 + 2 eps
#: (b_j c exact, c a power of 2), and y + h Σ b_j c rounds once: 3 eps of |y| per step,
#: 4 with the interpolant's Horner sum, at most 3 steps here (measured: 4.5 eps at most)
DRIFT_EPS = 16


# (states of 2 entries; array literals, which numba compiles in a third of np.zeros' time)
def _rest(t, y):
    return np.array([0.0, 0.0])


def _drift(t, y):
    return np.array([0.5, -2.0])


def _faulty(t, y):
    """Right until t = 1.66, then of the wrong length, from t = 5 on NaN."""
    if t < 1.66:
        return np.array([0.0, 0.0])
    if t < 5.0:
        return np.array([0.0])
    return np.array([math.nan, math.nan])


rest, drift, faulty = njit(_rest), njit(_drift), njit(_faulty)


def _nan_event(t, y):
    return math.nan


def _past_1(t, y):
    return t - 1.0


def _past_1_5(t, y):
    return t - 1.5


def _before_1_5(t, y):
    return 1.5 - t


def _past_minus_1_5(t, y):
    return t + 1.5


def _cube_down(t, y):
    return 7.0 - t * t * t


def _saturating_06(t, y):
    return t / (1.0 + t) - 0.6


def _saturating_08(t, y):
    return t / (1.0 + t) - 0.8


nan_event, past_1, past_1_5, before_1_5, past_minus_1_5 = (
    njit(f) for f in (_nan_event, _past_1, _past_1_5, _before_1_5, _past_minus_1_5)
)
cube_down, saturating_06, saturating_08 = (
    njit(f) for f in (_cube_down, _saturating_06, _saturating_08)
)


def _kernel(rhs, y0, t, h0, *, rtol=1e-3, beta=0.0, max_steps=10**6, event=None, direction=0.0):
    """kernels_rhs.dop853_rhs itself: ((status, steps, evals, rejected, outputs filled),
    the outputs (NaN where none was written), ev = (t_event, y_event...))."""
    y0 = np.asarray(y0, dtype=np.float64)
    t = np.asarray(t, dtype=np.float64)
    ys = np.full((t.size, y0.size), math.nan)
    ev = np.full(y0.size + 1, math.nan)
    done = kernels_rhs.dop853_rhs(
        rhs,
        y0,
        t,
        h0,
        rtol,
        rtol,
        1,
        max_steps,
        *_KERNEL_TABLEAU,
        np.array([*HAIRER_CONTROL, beta]),
        ys,
        kernels_rhs.no_event if event is None else event,
        event is not None,
        direction,
        EVENT_XTOL,
        ev,
    )
    return tuple(int(v) for v in done), ys, ev


def test_a_kernel_that_stops_reports_the_work_done_up_to_there():
    """Status 4 (rhs of another length) or 1 (a non-finite rate or event value), with
    the steps, evaluations (the failing one counted), rejections and outputs (the start)
    done before it."""
    y0 = np.array([1.0, 2.0])
    shape, nonfinite = kernels_rhs.STATUS_SHAPE, kernels_rhs.STATUS_NONFINITE
    # wrong from the start: the one evaluation at t0
    assert _kernel(faulty, y0, np.array([2.0, 3.0]), 0.5)[0] == (shape, 0, 1, 0, 1)
    # wrong from the first stage on (1.65 + c_1 h, c_1 = 0.053, h = 1.35): two evaluations
    assert _kernel(faulty, y0, np.array([1.65, 3.0]), 10.0)[0] == (shape, 0, 2, 0, 1)
    # wrong only at t = 1.66, the step's end: 0.36 + (1.66 − 0.36) rounds to 1 ulp below,
    # so the 12th stage (c = 1) is still right and f_new is the 13th evaluation that fails
    assert 0.36 + (1.66 - 0.36) < 1.66
    done, ys, _ = _kernel(faulty, y0, np.array([0.36, 1.66]), 10.0)
    assert done == (shape, 0, 1 + EVALS_PER_STEP, 0, 1)
    np.testing.assert_array_equal(ys[0], y0)
    # a non-finite rate at the start, a non-finite event value at the start
    assert _kernel(faulty, y0, np.array([5.0, 6.0]), 0.5)[0] == (nonfinite, 0, 1, 0, 1)
    done = _kernel(rest, y0, np.array([0.0, 1.0]), 0.5, event=nan_event)[0]
    assert done == (nonfinite, 0, 1, 0, 1)


def test_the_first_step_is_raised_to_ten_ulps_of_t_and_grows_tenfold_as_scipys():
    """At rest from t0 = 1 with a first step of 1e-300: raised to 10 ulp(1) (scipy's
    floor), then ×10 per step, the error estimate being 0: steps of 10, 100 and (cut)
    5 ulp to 1 + 115 ulp, as the stepper that takes scipy's steps takes them (scipy's
    solve_ivp: the same ends, 37 evaluations)."""
    ulp = 2.0**-52
    t_end = 1.0 + 115 * ulp
    y0 = np.array([1.0, -1.0])
    stepper = DOP853Stepper(_rest, 1.0, y0, t_end, rtol=1e-9, atol=1e-9, first_step=1e-300)
    ends = []
    while stepper.status == "running":
        stepper.step()
        ends.append(stepper.t)
    assert ends == [1.0 + 10 * ulp, 1.0 + 110 * ulp, t_end]
    done, ys, _ = _kernel(rest, y0, np.array([1.0, t_end]), 1e-300, rtol=1e-9)
    assert done == (0, len(ends), 1 + EVALS_PER_STEP * len(ends), 0, 2)
    np.testing.assert_array_equal(ys, [y0, y0])


def test_a_drift_is_followed_at_step_ends_inside_steps_and_at_the_end():
    """y' = c from y0 (steps ending at 1, 11 and 20): an output on a step's end (t = 1),
    one inside a step (5, from its interpolant: 3 more evaluations), the end; y0 + c t."""
    t = np.array([0.0, 1.0, 5.0, 20.0])
    y0 = np.array([1.0, 2.0])
    done, ys, _ = _kernel(drift, y0, t, 1.0)
    assert done == (0, 3, 1 + 3 * EVALS_PER_STEP + EVALS_PER_DENSE, 0, t.size)
    exact = y0 + t[:, None] * DRIFT
    assert _eps_diff(ys, exact) <= DRIFT_EPS


def test_max_steps_counts_the_steps_taken_and_a_run_may_end_on_its_last():
    """At rest over [0, 11] from a first step of 1: two steps (to 1, to 11).  Two allowed:
    done; one: status 3 after it, at the output t = 11 not reached (the reference's
    StepSizeError, '1 steps reached t=1.0')."""
    y0 = np.array([1.0, 2.0])
    t = np.array([0.0, 11.0])
    assert _kernel(rest, y0, t, 1.0, max_steps=2)[0] == (0, 2, 1 + 2 * EVALS_PER_STEP, 0, 2)
    done = _kernel(rest, y0, t, 1.0, max_steps=1)[0]
    assert done == (kernels_rhs.STATUS_MAX_STEPS, 1, 1 + EVALS_PER_STEP, 0, 1)
    with pytest.raises(StepSizeError, match=r"1 steps reached t=1\.0"):
        _reference(_rest, y0, t, method="dop853", rtol=1e-3, h=1.0, max_steps=1)


@pytest.mark.parametrize(
    ("event", "direction", "t0"),
    [(past_1_5, 1.0, 0.0), (before_1_5, -1.0, 0.0), (past_minus_1_5, 1.0, -3.0)],
)
def test_a_clock_event_is_met_exactly_where_it_is_zero(event, direction, t0):
    """g = ±(t − t_e) on the drift, t_e = t0 + 1.5, steps t0 → t0 + 1 → t0 + 2.5: the
    secant through the step's ends lands on t_e exactly (t0 = 0: (1·g(2.5) − 2.5·g(1)) /
    (g(2.5) − g(1)) = 2.25/1.5; t0 = −3, times below 0: (−2·1 − 0.25)/1.5), where g = 0,
    which is the crossing (a zero counts as crossed, as in ``crosses``): the event is t_e
    to the bit, the output at t_e is dropped (outputs from the event on are), the state
    is y0 + 1.5 c."""
    t = t0 + np.array([0.0, 0.5, 1.5, 2.5])
    y0 = np.array([1.0, 2.0])
    done, ys, ev = _kernel(drift, y0, t, 1.0, event=event, direction=direction)
    # both steps hold an output (t0 + 0.5, then t_e and the event): two dense outputs
    assert done == (0, 2, 1 + 2 * (EVALS_PER_STEP + EVALS_PER_DENSE), 0, 2)
    assert ev[0] == t0 + 1.5
    assert _eps_diff(ev[1:], y0 + 1.5 * DRIFT) <= DRIFT_EPS
    assert _eps_diff(ys[:2], y0 + (t[:2, None] - t0) * DRIFT) <= DRIFT_EPS
    assert np.isnan(ys[2:]).all()


def test_an_event_on_the_first_steps_end_is_met_there_with_that_steps_state():
    """g = t − 1 rising, the first step 0 → 1 ends on its zero: the event is t = 1 and its
    state the step's own, y0 + c (no search: g is already 0 at the bracket's end)."""
    y0 = np.array([1.0, 2.0])
    done, ys, ev = _kernel(drift, y0, np.array([0.0, 0.5, 3.0]), 1.0, event=past_1, direction=1.0)
    assert done == (0, 1, 1 + EVALS_PER_STEP + EVALS_PER_DENSE, 0, 2)
    assert ev[0] == 1.0
    assert _eps_diff(ev[1:], y0 + DRIFT) <= DRIFT_EPS
    assert _eps_diff(ys[:2], y0 + np.array([[0.0], [0.5]]) * DRIFT) <= DRIFT_EPS


@pytest.mark.parametrize(
    ("event", "direction", "root"),
    [(saturating_06, 1.0, 1.5), (saturating_08, 1.0, 4.0), (cube_down, -1.0, 7.0 ** (1 / 3))],
)
def test_the_kernel_brackets_an_event_as_the_reference_does_to_the_bit(event, direction, root):
    """At rest from Hairer's start (1e-6, then ×10 per step) each crossing lies in the step
    1.111111 → 11.111111, a lopsided bracket that the Illinois rule and the bisection
    every fourth iteration shrink to EVENT_XTOL · 11.1 in 10 to 20 iterations:
    t/(1 + t) − c, concave, puts the first secant point past the root, 7 − t³ (|g| 5.6
    against 1365, falling) before it, and each of the three takes the two ends' halvings
    and the bisections in another order.  The event depends on t alone and both paths take the same steps
    (every stage 0), so the kernel and the reference's search, documented as the kernel's
    loop step for step, evaluate the same g at the same points: the same event time to
    the bit, on or past the root and within the bracket's width of it."""
    y0 = np.array([1.0, 2.0])
    t = np.array([0.0, 20.0])
    ref = _reference(
        _rest, y0, t, method="dop853", rtol=1e-9, event=event, event_direction=direction
    )
    (_, steps, _, _), hit = _dop853_user(
        rest, y0, t, None, 1e-9, 1e-9, 1, 10**6, 0.0, event, direction
    )
    assert hit is not None
    assert ref.t_event is not None
    assert steps == ref.steps == 8  # 1e-6 · (1 + 10 + ... + 10^7) = 11.111111 passes the root
    assert hit[0] == ref.t_event
    assert direction * event(hit[0], y0) >= 0.0
    assert abs(hit[0] - root) <= EVENT_XTOL * 11.111111


def test_the_kernels_compile_settings_give_back_what_computes_as_the_function():
    """The kernels are compiled as their module is imported, before mutmut activates a
    mutant: the two settings are applied again here, to the module's own functions.  What
    comes back is called as the function (with the JIT off, numba hands the function
    back): the interpolant at x = 1/2 of F = (0, 1, ..., 13), exact in binary, against
    its nested form y + x (F0 + (1 − x) (F1 + x (F2 + ...))) (Hairer's contd8).
    Compiled, both carry the documented options: numpy's error model, the disk cache, and
    for ``_compile`` the signature compiled eagerly (here loaded from that cache)."""

    def py(f):
        return getattr(f, "py_func", f)

    y = np.array([1.0, 2.0])
    event = kernels_rhs._compile(kernels_rhs.EVENT_SIGNATURE)(py(kernels_rhs.no_event))
    assert event(0.5, y) == py(kernels_rhs.no_event)(0.5, y)
    interpolate = kernels_rhs._helper(py(kernels_rhs._interpolate))
    F = np.arange(14.0).reshape(7, 2)
    x = 0.5
    want = F[6].copy()
    for r in range(5, -1, -1):  # from the innermost bracket out: F5 + x F6, then (1 − x) ...
        want = F[r] + (x if r % 2 == 1 else 1.0 - x) * want
    want = y + x * want
    out = np.empty(2)
    interpolate(F, y, x, out)
    np.testing.assert_array_equal(out, want)
    if JIT:
        assert event.signatures == [kernels_rhs.EVENT_SIGNATURE.args]
        for dispatcher in (event, interpolate):
            assert dispatcher.targetoptions["error_model"] == "numpy"
            assert type(dispatcher._cache).__name__ == "FunctionCache"  # not NullCache
