"""The step-by-step DOP853 of :mod:`mechanics.integrators`: :class:`DOP853Stepper`
and its dense output :class:`DenseStep`.

References are independent of the code under test: scipy's
``scipy.integrate.DOP853`` stepped side by side (its own ``rk_step``, step control
and ``Dop853DenseOutput``), and the closed-form oscillator (cos t, −sin t).  A
negative control proves that the agreement helper catches a wrong dense-output
coefficient.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from scipy.integrate import DOP853

from mechanics._floats import EPS
from mechanics.errors import (
    NonFiniteError,
    NonPositiveParameterError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
    StepSizeError,
    UnknownOptionError,
)
from mechanics.integrators import (
    DenseStep,
    DOP853Stepper,
    free_rigid_body_rhs,
    rigid_body_state,
)
from mechanics.integrators import _dop853 as dop853

#: Times after each step against scipy's: the stepper computes t + h from the same h
#: by scipy's arithmetic (the same dot products, norms and factors; measured: equal
#: to the bit); 2 eps of |t| allows one rounding should a BLAS order a sum otherwise.
TIME_RTOL = 2 * EPS
#: States after each step, relative to the largest component: the same operations
#: (measured: equal to the bit); 4 eps allows a few roundings of a reordered sum.
STATE_RTOL = 4 * EPS
#: Dense output against scipy's at interior points, relative to the largest
#: component: the same F and the same nested evaluation (measured: equal to the
#: bit); 8 eps allows one rounding in each of its 7 multiply-adds.
DENSE_RTOL = 8 * EPS
#: dense(t) = y_old + (y − y_old): two roundings of half an ulp, of |y − y_old| and of
#: |y|, so |dense(t) − y| ≤ eps (|y| + |y − y_old|) / 2 + O(eps²); 1 eps of that sum.
ENDPOINT_RTOL = 1 * EPS
#: Global error of the dense output on the oscillator over [0, T]: DOP853 keeps each
#: step's error within tol and the neutral flow adds them up, so the error at any
#: point of any step is ≤ C tol (1 + t); measured C ≤ 2.5 for tol = 2^16 … 2^36 eps
#: and T = 10, 100: C = 8.
ORACLE_C = 8
#: The tolerances of the oracle test, as multiples of eps (1.5e-11, 3.7e-9, 9.5e-7).
ORACLE_TOLS = (2.0**16 * EPS, 2.0**24 * EPS, 2.0**32 * EPS)
#: A step ends at t + max_step, rounded once: the step t − t_old may exceed max_step
#: by half an ulp of t (from t + h) plus half an ulp of the difference; 1 ulp of t.
MAX_STEP_ULPS = 1
#: The relative change of one coefficient in the negative control: a typo in the
#: seventh significant digit, 2^-20 ≈ 1e-6, far above rounding and far below a
#: change that would also break the step-end values.
PERTURBATION = 2.0**-20

#: Interior fractions of a step where dense outputs are compared.
INTERIOR = np.array([0.1, 0.25, 0.5, 0.77, 0.9])

J_TOP = np.array([1.0, 2.0, 2.5])
W_TOP = np.array([0.3, -1.0, 0.7])
KEPLER_E = 0.9


def oscillator(t, y):
    """q' = p, p' = −q; exact (cos t, −sin t) from (1, 0)."""
    return np.array([y[1], -y[0]])


def forced(t, y):
    """A driven oscillator q'' = −q + cos 2t: the right-hand side depends on t."""
    return np.array([y[1], -y[0] + math.cos(2.0 * t)])


def kepler(t, y):
    """Planar Kepler problem, GM = 1: r'' = −r/|r|³ (state (x, y, vx, vy))."""
    r = y[:2]
    d = math.hypot(r[0], r[1])
    return np.concatenate([y[2:], -r / d**3])


def kepler_start(e):
    """Pericentre of the orbit of eccentricity e, semi-major axis 1 (period 2π)."""
    return np.array([1.0 - e, 0.0, 0.0, math.sqrt((1.0 + e) / (1.0 - e))])


PROBLEMS = {
    "oscillator": (oscillator, np.array([1.0, 0.0]), 20.0),
    "free rigid body": (
        free_rigid_body_rhs(J_TOP),
        rigid_body_state(J_TOP * W_TOP, np.eye(3)),
        20.0,
    ),
    "kepler e=0.9": (kepler, kepler_start(KEPLER_E), 2 * 2 * math.pi),
    "driven oscillator": (forced, np.array([1.0, 0.0]), 20.0),
}
OPTIONS = {
    "rtol 1e-9": {"rtol": 1e-9, "atol": 1e-9},
    "rtol 1e-12": {"rtol": 1e-12, "atol": 1e-12},
    "loose, atol < rtol": {"rtol": 1e-6, "atol": 1e-8},
    "first step 1 (rejections)": {"rtol": 1e-10, "atol": 1e-10, "first_step": 1.0},
    "max step 0.05": {"rtol": 1e-10, "atol": 1e-10, "max_step": 0.05},
}


class Counting:
    """A right-hand side that counts its own calls."""

    def __init__(self, f):
        self.f, self.calls = f, 0

    def __call__(self, t, y):
        self.calls += 1
        return self.f(t, y)


def run_to_end(stepper, max_steps=10**5):
    """Step until finished; the list of dense outputs, one per step."""
    dense = []
    while stepper.status == "running":
        stepper.step()
        dense.append(stepper.dense_output())
        assert len(dense) <= max_steps
    return dense


def step_to_end(stepper, max_steps=10**5):
    """Step until finished, without dense output."""
    while stepper.status == "running":
        stepper.step()
        assert stepper.steps <= max_steps


# ------------------------------------------------------------- agreement helper


def assert_steps_agree_with_scipy(rhs, y0, t_bound, *, fractions=INTERIOR, **options):
    """Step :class:`DOP853Stepper` and scipy's ``DOP853`` side by side to ``t_bound``.

    After every step: the same t (``TIME_RTOL``), the same y (``STATE_RTOL`` of the
    largest component), the same status and evaluations, and the two dense outputs
    agree (``DENSE_RTOL``) at ``fractions`` of the step and at its ends.  Returns the
    number of steps.
    """
    ours = DOP853Stepper(rhs, 0.0, y0, t_bound, **options)
    ref = DOP853(rhs, 0.0, np.asarray(y0, dtype=float), t_bound, **options)
    assert ours.h_abs == pytest.approx(ref.h_abs, rel=TIME_RTOL, abs=0.0), "initial step"
    n = 0
    while ref.status == "running":
        ref.step()
        ours.step()
        n += 1
        assert ours.status == ref.status, f"status at step {n}"
        assert abs(ours.t - ref.t) <= TIME_RTOL * abs(ref.t), f"t at step {n}"
        assert ours.t_old == pytest.approx(ref.t_old, rel=TIME_RTOL, abs=0.0)
        size = np.abs(ref.y).max()
        assert np.abs(ours.y - ref.y).max() <= STATE_RTOL * size, f"y at step {n}"
        tt = ref.t_old + (ref.t - ref.t_old) * np.concatenate([[0.0], fractions, [1.0]])
        d_ours, d_ref = ours.dense_output(), ref.dense_output()
        worst = np.abs(d_ours(tt) - d_ref(tt)).max()
        assert worst <= DENSE_RTOL * size, f"dense output at step {n}: {worst / EPS:.3g} eps"
        assert ours.rhs_evals == ref.nfev, f"evaluations at step {n}"
    assert ours.status == "finished"
    return n


@pytest.mark.parametrize("options", OPTIONS.values(), ids=OPTIONS.keys())
@pytest.mark.parametrize("problem", PROBLEMS.values(), ids=PROBLEMS.keys())
def test_steps_times_states_and_dense_output_agree_with_scipy_dop853(problem, options):
    rhs, y0, t_bound = problem
    n = assert_steps_agree_with_scipy(rhs, y0, t_bound, **options)
    assert n >= 10


@settings(max_examples=20)
@given(
    w=st.tuples(*[st.floats(-2.0, 2.0) for _ in range(3)]),
    rtol=st.sampled_from([1e-7, 1e-10, 1e-13]),
)
@example(w=tuple(W_TOP), rtol=1e-10)
@example(w=(0.0, 0.0, 0.0), rtol=1e-10)  # a body at rest: zero error norms, factor 10
def test_free_rigid_body_agrees_with_scipy_for_any_spin(w, rtol):
    y0 = rigid_body_state(J_TOP * np.array(w), np.eye(3))
    assert_steps_agree_with_scipy(free_rigid_body_rhs(J_TOP), y0, 5.0, rtol=rtol, atol=rtol)


# The negative control: a wrong dense-output coefficient (one entry of D, of the
# extra stages' A rows, or of their nodes C) must be caught by the helper, while
# the step-end values, which these coefficients do not touch, still agree.
def _perturbed_d(i, j):
    D = np.array(dop853._D)
    assert D[i, j] != 0.0
    D[i, j] *= 1.0 + PERTURBATION
    return D


def _perturbed_a_extra(row, col):
    rows = [np.array(r) for r in dop853._A_EXTRA_ROWS]
    assert rows[row][col] != 0.0
    rows[row][col] *= 1.0 + PERTURBATION
    return rows


def _perturbed_c_extra(k):
    c = list(dop853._C_EXTRA)
    c[k] *= 1.0 + PERTURBATION
    return c


WRONG_COEFFICIENTS = {
    "D[0, 0]": ("_D", lambda: _perturbed_d(0, 0)),
    "D[1, 7]": ("_D", lambda: _perturbed_d(1, 7)),
    "D[3, 15]": ("_D", lambda: _perturbed_d(3, 15)),
    "A[15, 13]": ("_A_EXTRA_ROWS", lambda: _perturbed_a_extra(2, 13)),
}


@pytest.mark.parametrize("wrong", WRONG_COEFFICIENTS.values(), ids=WRONG_COEFFICIENTS.keys())
@pytest.mark.parametrize("problem", PROBLEMS.values(), ids=PROBLEMS.keys())
def test_agreement_helper_catches_a_wrong_dense_output_coefficient(problem, wrong, monkeypatch):
    rhs, y0, t_bound = problem
    name, make = wrong
    monkeypatch.setattr(dop853, name, make())
    with pytest.raises(AssertionError, match=r"dense output at step \d+:"):
        assert_steps_agree_with_scipy(rhs, y0, t_bound, rtol=1e-10, atol=1e-10)


@pytest.mark.parametrize("k", range(3))
def test_agreement_helper_catches_a_wrong_extra_stage_node(k, monkeypatch):
    # the nodes c only enter through t, so only a driven (non-autonomous) problem sees them
    rhs, y0, t_bound = PROBLEMS["driven oscillator"]
    monkeypatch.setattr(dop853, "_C_EXTRA", _perturbed_c_extra(k))
    with pytest.raises(AssertionError, match=r"dense output at step \d+:"):
        assert_steps_agree_with_scipy(rhs, y0, t_bound, rtol=1e-10, atol=1e-10)


def test_agreement_helper_passes_with_the_coefficients_restored():
    # the control of the control: the same call without the perturbation passes
    rhs, y0, t_bound = PROBLEMS["kepler e=0.9"]
    assert assert_steps_agree_with_scipy(rhs, y0, t_bound, rtol=1e-10, atol=1e-10) > 0


# -------------------------------------------------------------- dense output


@pytest.mark.parametrize("problem", PROBLEMS.values(), ids=PROBLEMS.keys())
def test_dense_output_hits_both_ends_of_every_step(problem):
    rhs, y0, t_bound = problem
    s = DOP853Stepper(rhs, 0.0, y0, t_bound, rtol=1e-10, atol=1e-10)
    y_old = s.y
    while s.status == "running":
        s.step()
        d = s.dense_output()
        assert (d.t_old, d.t) == (s.t_old, s.t)
        # x = 0 zeroes every term of the polynomial, then y_old is added to 0: exact
        np.testing.assert_array_equal(d(s.t_old), y_old)
        np.testing.assert_array_equal(d([s.t_old])[:, 0], y_old)
        bound = ENDPOINT_RTOL * (np.abs(s.y) + np.abs(s.y - y_old))
        assert (np.abs(d(s.t) - s.y) <= bound).all()
        assert (np.abs(d([s.t_old, s.t])[:, 1] - s.y) <= bound).all()
        y_old = s.y


@pytest.mark.parametrize("tol", ORACLE_TOLS, ids=[f"tol={t:.2g}" for t in ORACLE_TOLS])
def test_dense_output_follows_the_exact_oscillator_within_the_tolerance(tol):
    s = DOP853Stepper(oscillator, 0.0, [1.0, 0.0], 100.0, rtol=tol, atol=tol)
    for d in run_to_end(s):
        tt = np.linspace(d.t_old, d.t, 33)
        err = np.abs(d(tt) - np.array([np.cos(tt), -np.sin(tt)])).max(axis=0)
        assert (err <= ORACLE_C * tol * (1.0 + tt)).all()


def test_dense_output_shapes_follow_scipy():
    rhs, y0, t_bound = PROBLEMS["free rigid body"]
    s = DOP853Stepper(rhs, 0.0, y0, t_bound)
    s.step()
    d = s.dense_output()
    tm = 0.5 * (d.t_old + d.t)
    assert isinstance(d, DenseStep)
    for t in (tm, np.float64(tm), np.array(tm), 0):
        assert d(t).shape == (12,)
    assert d([tm, tm, d.t]).shape == (12, 3)
    np.testing.assert_array_equal(d([tm])[:, 0], d(tm))
    assert d(np.array([])).shape == (12, 0)
    assert s.dense_output() is d  # computed once per step
    with pytest.raises(ShapeError, match=r"shape \(1, 2\)"):
        d([[tm, tm]])
    with pytest.raises(NonFiniteError, match="nan"):
        d(float("nan"))
    with pytest.raises(ValueError, match="read-only"):
        d.F[0, 0] = 1.0


# ------------------------------------------------------------ steps and work


@pytest.mark.parametrize("max_step", [0.05, 0.3, 2.0])
def test_max_step_caps_every_step_including_the_first(max_step):
    rhs, y0, t_bound = PROBLEMS["kepler e=0.9"]
    s = DOP853Stepper(rhs, 0.0, y0, t_bound, rtol=1e-9, atol=1e-9, max_step=max_step)
    free = DOP853Stepper(rhs, 0.0, y0, t_bound, rtol=1e-9, atol=1e-9)
    steps = []
    while s.status == "running":
        s.step()
        steps.append(s.t - s.t_old)
        assert s.t - s.t_old <= max_step + MAX_STEP_ULPS * math.ulp(s.t)
    run_to_end(free)
    if max_step < 0.3:  # the cap binds: more steps than the free run, many at the cap
        assert s.steps > free.steps
        assert sum(h >= max_step * (1 - 1e3 * EPS) for h in steps) >= s.steps // 2


def test_max_step_caps_hairers_initial_estimate():
    s = DOP853Stepper(oscillator, 0.0, [1.0, 0.0], 10.0, rtol=1e-6, atol=1e-6, max_step=1e-3)
    assert s.h_abs == 1e-3
    s.step()
    assert s.t == 1e-3


@settings(max_examples=50)
@given(
    t0=st.floats(-1e3, 1e3),
    span=st.floats(1e-6, 30.0),
    first=st.one_of(st.none(), st.floats(1e-8, 100.0)),
)
@example(t0=0.0, span=0.1 * 3, first=None)  # 0.30000000000000004
@example(t0=1e3, span=1e-6, first=None)  # a span of ~10⁷ ulps of t0
@example(t0=0.0, span=1.0, first=100.0)  # a first step beyond t_bound is cut to it
def test_the_last_step_ends_exactly_on_t_bound(t0, span, first):
    t_bound = t0 + span  # > t0: span ≥ 1e-6 is far above ulp(1e3) ≈ 1.1e-13
    s = DOP853Stepper(oscillator, t0, [1.0, 0.0], t_bound, rtol=1e-9, atol=1e-9, first_step=first)
    while s.status == "running":
        t = s.t
        s.step()
        assert t < s.t <= t_bound
        assert s.t_old == t
        assert (s.status == "finished") == (s.t == t_bound)
    assert s.t == t_bound
    with pytest.raises(OutOfDomainError, match="finished"):
        s.step()


def test_work_counts_every_evaluation_and_rejection():
    f = Counting(oscillator)
    s = DOP853Stepper(f, 0.0, [1.0, 0.0], 20.0, rtol=1e-10, atol=1e-10, first_step=10.0)
    assert s.rhs_evals == f.calls == 1  # f(t0) only: no initial-step estimate
    s.step()
    assert s.rejected_steps >= 1  # 10 (1.6 periods) cannot meet 1e-10
    assert f.calls == 1 + 12 * (s.steps + s.rejected_steps)
    s.dense_output()
    s.dense_output()  # cached: no more evaluations
    assert s.rhs_evals == f.calls == 1 + 12 * (s.steps + s.rejected_steps) + 3
    g = Counting(oscillator)
    t = DOP853Stepper(g, 0.0, [1.0, 0.0], 20.0, rtol=1e-10, atol=1e-10)
    run_to_end(t)
    assert t.rhs_evals == g.calls == 2 + 12 * (t.steps + t.rejected_steps) + 3 * t.steps


def test_state_is_a_copy_and_an_rhs_that_reuses_its_buffer_changes_nothing():
    out = np.empty(2)

    def in_place(t, y):
        out[0], out[1] = y[1], -y[0]
        return out

    y0 = np.array([1.0, 0.0])
    a = DOP853Stepper(in_place, 0.0, y0, 10.0, rtol=1e-10, atol=1e-10, first_step=0.1)
    b = DOP853Stepper(oscillator, 0.0, y0, 10.0, rtol=1e-10, atol=1e-10, first_step=0.1)
    y0[0] = 99.0  # the stepper holds its own copy
    assert a.y[0] == 1.0
    for da, db in zip(run_to_end(a), run_to_end(b), strict=True):
        tt = da.t_old + INTERIOR * (da.t - da.t_old)
        np.testing.assert_array_equal(da(tt), db(tt))
    np.testing.assert_array_equal(a.y, b.y)
    assert a.y.dtype == np.float64
    assert a.y.shape == (2,)


# ---------------------------------------------------------------- bad inputs

BASE = {"rhs": oscillator, "t0": 0.0, "y0": [1.0, 0.0], "t_bound": 1.0}
BAD_INPUTS = {
    "rhs not callable": ({"rhs": 3.0}, UnknownOptionError, "rhs must be callable.*float"),
    "y0 NaN": (
        {"y0": [1.0, math.nan]},
        NonFiniteError,
        r"y0 must be finite; found .*nan.* at index \(1,\)",
    ),
    "y0 inf": (
        {"y0": [math.inf, 0.0]},
        NonFiniteError,
        r"y0 must be finite; found .*inf.* at index \(0,\)",
    ),
    "y0 2-D": ({"y0": np.eye(2)}, ShapeError, r"1-D.*shape \(2, 2\)"),
    "y0 scalar": ({"y0": 1.0}, ShapeError, r"1-D.*shape \(\)"),
    "y0 empty": ({"y0": []}, ShapeError, r"non-empty.*shape \(0,\)"),
    "y0 complex": ({"y0": [1j, 0.0]}, ShapeError, "y0 is complex"),
    "t0 NaN": ({"t0": math.nan}, NonFiniteError, "t0 must be finite; found .*nan"),
    "t0 array": ({"t0": [0.0, 1.0]}, ShapeError, r"t0 must be a scalar; got shape \(2,\)"),
    "t_bound inf": ({"t_bound": math.inf}, NonFiniteError, "t_bound must be finite; found .*inf"),
    "t_bound = t0": (
        {"t_bound": 0.0},
        OutOfDomainError,
        r"t_bound must be > t0; got t_bound=0.0 ≤ t0=0.0",
    ),
    "t_bound < t0": ({"t0": 2.0}, OutOfDomainError, r"t_bound=1.0 ≤ t0=2.0"),
    "rtol 0": ({"rtol": 0.0}, NonPositiveParameterError, r"rtol must be > 0; got 0.0"),
    "atol < 0": ({"atol": -1e-9}, NonPositiveParameterError, r"atol must be > 0; got -1e-09"),
    "rtol NaN": ({"rtol": math.nan}, NonFiniteError, "rtol must be finite; found .*nan"),
    "first_step 0": (
        {"first_step": 0.0},
        NonPositiveParameterError,
        "first_step must be > 0; got 0.0",
    ),
    "max_step 0": (
        {"max_step": 0.0},
        NonPositiveParameterError,
        r"max_step must be > 0 \(inf for no cap\); got 0.0",
    ),
    "max_step -inf": (
        {"max_step": -math.inf},
        NonPositiveParameterError,
        "max_step must be > 0.*got -inf",
    ),
    "max_step NaN": (
        {"max_step": math.nan},
        NonPositiveParameterError,
        "max_step must be > 0.*got nan",
    ),
    "max_step array": (
        {"max_step": [1.0]},
        ShapeError,
        r"max_step must be a scalar; got shape \(1,\)",
    ),
    "max_step text": ({"max_step": "big"}, ShapeError, "max_step must be a real number; got 'big'"),
    "rhs wrong shape": (
        {"rhs": lambda t, y: np.zeros(3)},
        ShapeError,
        r"rhs returned shape \(3,\) at t=0.0; expected y0's shape \(2,\)",
    ),
    "rhs NaN at t0": (
        {"rhs": lambda t, y: np.array([math.nan, 0.0])},
        NonFiniteError,
        r"rhs returned a non-finite value at t=0.0: nan at index \(0,\)",
    ),
}


@pytest.mark.parametrize("case", BAD_INPUTS.values(), ids=BAD_INPUTS.keys())
def test_bad_inputs_raise_errors_that_name_the_value(case):
    change, error, match = case
    kw = {**BASE, **change}
    with pytest.raises(error, match=match):
        DOP853Stepper(kw.pop("rhs"), kw.pop("t0"), kw.pop("y0"), kw.pop("t_bound"), **kw)


def test_dense_output_before_the_first_step_is_refused():
    s = DOP853Stepper(oscillator, 0.0, [1.0, 0.0], 1.0)
    with pytest.raises(OutOfDomainError, match="t_old is None, call step"):
        s.dense_output()


def test_a_step_below_the_rounding_of_t_raises_and_leaves_the_state():
    # y' = y², y(0) = 1 blows up at t = 1: the step shrinks to the rounding of t
    s = DOP853Stepper(lambda t, y: y * y, 0.0, [1.0], 2.0, rtol=1e-8, atol=1e-8)
    with pytest.raises(
        StepSizeError,
        match=r"the step fell to .* below the rounding of t=1\.0000000\d+; rtol=1e-08",
    ):
        run_to_end(s)
    t, y = s.t, s.y.copy()
    with pytest.raises(StepSizeError):
        s.step()
    assert (s.t, s.status) == (t, "running")
    np.testing.assert_array_equal(s.y, y)


def test_max_step_below_the_rounding_of_t_raises_naming_it():
    s = DOP853Stepper(oscillator, 1e6, [1.0, 0.0], 1e6 + 1.0, max_step=1e-12)
    with pytest.raises(StepSizeError, match=r"max_step=1e-12 is below the rounding of t=1000000.0"):
        s.step()


def test_an_overflowing_state_raises_instead_of_passing_as_infinity():
    # finite rates carry y past 1.8e308; an infinite y makes the error norm 0
    s = DOP853Stepper(lambda t, y: np.full_like(y, 1e307), 0.0, [1e308], 100.0)
    with pytest.raises(ResultOverflowError, match=r"overflowed in the step from t=[\d.e+-]+ to t="):
        step_to_end(s)
    # the interpolant's coefficients (sums of 16 rates of 1e307 times D up to ~500)
    # overflow first: refused too, not returned as inf
    s = DOP853Stepper(lambda t, y: np.full_like(y, 1e307), 0.0, [1e308], 100.0)
    s.step()
    with pytest.raises(ResultOverflowError, match=r"dense output of the step from t=0\.0 to t="):
        s.dense_output()


def test_a_non_finite_rate_inside_a_step_names_its_time():
    def rhs(t, y):
        return np.array([y[1], -y[0]]) if t < 0.5 else np.array([math.nan, 0.0])

    s = DOP853Stepper(rhs, 0.0, [1.0, 0.0], 1.0, rtol=1e-8, atol=1e-8)
    with pytest.raises(NonFiniteError, match=r"rhs returned a non-finite value at t=0\.[5-9]"):
        run_to_end(s)


def test_a_non_finite_rate_in_an_extra_stage_of_the_dense_output_names_its_time():
    # y' = 0 takes a first step of exactly 1 (error 0); the rhs fails only at
    # t = 0.1, the node of the first extra stage and of no step stage
    def rhs(t, y):
        return np.array([math.nan]) if t == 0.1 else np.zeros(1)

    s = DOP853Stepper(rhs, 0.0, [1.0], 2.0, first_step=1.0)
    s.step()
    assert s.t == 1.0
    with pytest.raises(NonFiniteError, match=r"non-finite value at t=0\.1:"):
        s.dense_output()


def test_an_error_norm_whose_parts_underflow_is_zero_not_nan() -> None:
    """Stages whose 5th-order error estimate is 0 and whose 3rd-order one squares to a
    subnormal: 0.01 e3² underflows, and 0/0 made the step look like an overflow (a
    pinned top with a spin of 1e-167, found by the scene engine's random test)."""
    E5, E3 = np.asarray(dop853._E5, float), np.asarray(dop853._E3, float)
    k = E3 - (E3 @ E5) / (E5 @ E5) * E5  # along E3, across E5
    K = (1e-174 * k)[:, None]  # one component, 13 stages
    err = dop853._dop853_error(K, 0.01, np.zeros(1), np.zeros(1), 1e-12, 1e-12, 1)
    e3 = float(np.dot(K.T, E3)[0]) / 1e-12
    assert 0.0 < e3 * e3 < 2.4e-322, "the case: e3² subnormal, 0.01 e3² rounds to 0"
    assert err == 0.0
