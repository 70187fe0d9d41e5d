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

from mechanics._floats import EPS
from mechanics.errors import (
    NonFiniteError,
    OutOfDomainError,
    ShapeError,
    StepSizeError,
    UnknownOptionError,
)
from mechanics.integrators import CompiledPathWarning, integrate
from mechanics.integrators import _compiled as compiled_path
from mechanics.integrators._compiled import is_numba_function
from mechanics.integrators._dop853 import _dop853_user
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
