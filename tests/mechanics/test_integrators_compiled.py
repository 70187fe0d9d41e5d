"""The compiled path of :mod:`mechanics.integrators` (issue 15) against its reference.

The pure-numpy path (``compiled=False``) is the reference; the numba kernels of
:mod:`mechanics._kernels` must give the same steps and work counts and the same states,
bit for bit where the arithmetic is the same (RK4), else within a named eps bound (the
stage sums and the drift projection are summed in another order).  Bad input raises the
same error on both paths; a failed compilation falls back to the reference with one
warning; a state that overflows in a kernel is reported by the reference's error.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import mechanics.integrators as integrators
from mechanics._floats import EPS
from mechanics.errors import (
    NonFiniteError,
    NonPhysicalInertiaError,
    NonPositiveParameterError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
    StepSizeError,
    UnknownOptionError,
)
from mechanics.integrators import (
    CompiledPathWarning,
    free_rigid_body_rhs,
    free_rigid_body_splitting,
    integrate,
    rigid_body_state,
)
from mechanics.integrators import _compiled as compiled_path
from mechanics.integrators import _dop853 as dop853_module
from mechanics.integrators import _rk4 as rk4_module
from mechanics.integrators import _splitting as splitting_module
from mechanics.strategies.inertia import principal_moments
from mechanics.strategies.rotation import rotation_matrices

#: a test of the compiled path fails if the compiled path did not run: a kernel that
#: raises makes the integrators fall back to the reference path with a
#: CompiledPathWarning (same results), which would let "compiled equals reference" pass
#: without the compiled path (the two tests of the fallback itself catch the warning)
pytestmark = pytest.mark.filterwarnings("error::mechanics.integrators.CompiledPathWarning")


@pytest.fixture(autouse=True)
def _compiled_path_not_given_up(monkeypatch):
    """Each test starts with the compiled path loadable, whatever ran before it in the
    process: a kernel that raised earlier (a test of the fallback, or under mutation
    mutmut's forced-failure run in the process its mutants fork from) gives the path
    up for the whole process, and every later "compiled" run would be the reference."""
    monkeypatch.setattr(compiled_path, "_KERNELS", None)


#: the tests in which a kernel may stop short and hand over to the reference path (which
#: then raises the error naming the time), or not run at all: every other test of the
#: compiled path fails if a kernel did not finish its run
HANDS_OVER = {
    "test_an_overflow_in_a_kernel_is_reported_as_the_reference_reports_it",
    "test_both_paths_refuse_bad_input_with_the_same_error",
    "test_a_failed_jit_falls_back_to_the_reference_with_one_warning",
    "test_a_missing_numba_falls_back_to_the_reference_with_one_warning",
    "test_compiled_dop853_refuses_one_step_beyond_max_steps_as_the_reference",
}


@pytest.fixture(autouse=True)
def _kernels_finish_their_runs(monkeypatch, request):
    """A kernel that returns a status other than 0 hands its run over to the reference
    path silently, with the reference's result: "compiled equals reference" would then
    pass without the kernel (under mutation, a kernel that writes NaN into its state
    did, 7 mutants of RK4 alone).  Outside :data:`HANDS_OVER`, every kernel call must
    finish (status 0)."""
    if request.node.originalname in HANDS_OVER:
        return
    real = compiled_path._run_compiled

    def finished(name, *args):
        done = real(name, *args)
        assert done is not None, f"the kernel {name} did not run"
        assert done[0] == 0, f"the kernel {name} stopped with status {done[0]}"
        return done

    for module in (rk4_module, dop853_module, splitting_module):
        monkeypatch.setattr(module, "_run_compiled", finished)


J_TOP = np.array([1.0, 2.0, 3.0])
W_TOP = np.array([0.4, 0.2, 1.0])

# Compiled vs reference, max |Δy| / (eps · max(1, |y|)), on runs of ≤ 2000 steps:
# RK4 is the same arithmetic in the same order (0 measured).  DOP853's stage sums
# K·a are a loop here, a BLAS dot there: measured 36 eps after 77 steps, 31 for a
# batch of 7.  The splitting's projection R Rᵀ is a BLAS product in the reference:
# measured 20 eps after 1000 steps of order 6 when the bound was set (and 5.1 eps over
# the 1002 steps of orders 2 and 4 on 29 Nov 2026: a BLAS product rounds as the
# machine's BLAS does).  Each bound is ~8× the largest measurement.
RK4_EPS = 0
DOP853_EPS = 256
SPLITTING_EPS = 256


def _rel_diff_eps(a, b) -> float:
    return float(np.abs(a - b).max() / (EPS * max(1.0, np.abs(b).max())))


def _random_bodies(n: int, seed: int = 15) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return J_TOP * rng.normal(size=(n, 3))


@pytest.mark.parametrize("t", [(0.0, 20.0), np.linspace(0.0, 20.0, 11)], ids=["span", "grid"])
@pytest.mark.parametrize("bodies", [0, 7])
def test_compiled_rk4_is_the_reference_to_the_bit(t, bodies):
    L0 = J_TOP * W_TOP if bodies == 0 else _random_bodies(bodies)
    y0 = rigid_body_state(L0, np.eye(3))
    rhs = free_rigid_body_rhs(J_TOP)
    fast = integrate(rhs, y0, t, method="rk4", h=0.01)
    ref = integrate(rhs, y0, t, method="rk4", h=0.01, compiled=False)
    assert (fast.steps, fast.rhs_evals) == (ref.steps, ref.rhs_evals)
    assert _rel_diff_eps(fast.y, ref.y) <= RK4_EPS


@pytest.mark.parametrize("t", [(0.0, 20.0), np.linspace(0.0, 20.0, 11)], ids=["span", "grid"])
@pytest.mark.parametrize(("bodies", "batch_ndim"), [(0, 0), (7, 0), (7, 1)])
@pytest.mark.parametrize("h", [None, 0.3])
def test_compiled_dop853_takes_the_reference_steps(t, bodies, batch_ndim, h):
    L0 = J_TOP * W_TOP if bodies == 0 else _random_bodies(bodies)
    y0 = rigid_body_state(L0, np.eye(3))
    rhs = free_rigid_body_rhs(J_TOP)
    kw = {"method": "dop853", "rtol": 1e-10, "h": h, "batch_ndim": batch_ndim}
    fast = integrate(rhs, y0, t, **kw)
    ref = integrate(rhs, y0, t, **kw, compiled=False)
    work = ("steps", "rhs_evals", "rejected_steps")
    assert [getattr(fast, w) for w in work] == [getattr(ref, w) for w in work]
    assert _rel_diff_eps(fast.y, ref.y) <= DOP853_EPS


def _splitting_outputs(order: int) -> tuple[np.ndarray, int]:
    """The output times of the splitting's comparisons at h = 0.05, and their steps.

    Orders 2 and 4: six outputs of 167 steps (three runs each, of 64, 64 and 39 steps
    between projections), 1002 steps.  Over that many steps a kernel that rounds
    otherwise than the reference drifts beyond the bounds (measured by planting two
    such kernels: one projecting only at the outputs, 415 and 974 eps projected; one
    resetting its compensations at each output, 27.5 eps compensated at order 4), and
    the paths agree within 5.1 eps (0 compensated).

    Orders 6 and 8 take 36 and 108 sub-flows a step, 3 and 9 times order 4's (the batch
    reference runs each in Python: 1.8 s, and 4 to 5 s compensated, over 1002 steps of
    order 8), so they check their own schedules over two outputs of 103 steps (5.12 s,
    rounded up), each a full run of 64 and a short one of 39: every branch of the
    kernel's loop (the opening, merged and closing H1 half-flows of a full and of a
    short run, the projection after each, the compensations carried across runs and
    outputs, an output starting from the one before).  A wrong flow moves the state by
    the method's error, not by roundings (a planted wrong closing flow of the short
    run: 4e13 eps and more here, at every order); the two planted rounding kernels
    above drift by 64 and 5 eps over these 206 steps, under the bounds: the long runs
    of orders 2 and 4 are their test (at orders 6 and 8 they were caught as well)."""
    if order <= 4:
        return np.linspace(0.0, 50.0, 7), 6 * 167
    return np.linspace(0.0, 10.24, 3), 2 * 103


@pytest.mark.parametrize("order", integrators.SPLITTING_ORDERS)
@pytest.mark.parametrize("bodies", [0, 7])
def test_compiled_splitting_is_the_reference_within_eps(order, bodies):
    """The kernel's steps, sub-flow count and states are the reference's (projected
    runs), for one body and a batch of 7, over :func:`_splitting_outputs`."""
    L0 = J_TOP * W_TOP if bodies == 0 else _random_bodies(bodies)
    t, steps = _splitting_outputs(order)
    fast = free_rigid_body_splitting(J_TOP, L0, np.eye(3), t, 0.05, order=order)
    ref = free_rigid_body_splitting(J_TOP, L0, np.eye(3), t, 0.05, order=order, compiled=False)
    assert (fast.steps, fast.rhs_evals, fast.method) == (ref.steps, ref.rhs_evals, ref.method)
    assert fast.steps == steps
    assert _rel_diff_eps(fast.y, ref.y) <= SPLITTING_EPS


# The compensated splitting: the same arithmetic in the same order on both paths
# (no BLAS product, no projection), measured 0 eps for one body and for a batch of 7
COMPENSATED_EPS = 16


@pytest.mark.parametrize("order", integrators.SPLITTING_ORDERS)
@pytest.mark.parametrize("bodies", [0, 7])
def test_compiled_compensated_splitting_is_the_reference_within_eps(order, bodies):
    """As the projected runs above, compensated, over :func:`_splitting_outputs`."""
    L0 = J_TOP * W_TOP if bodies == 0 else _random_bodies(bodies)
    t, steps = _splitting_outputs(order)
    kw = {"order": order, "compensated": True}
    fast = free_rigid_body_splitting(J_TOP, L0, np.eye(3), t, 0.05, **kw)
    ref = free_rigid_body_splitting(J_TOP, L0, np.eye(3), t, 0.05, **kw, compiled=False)
    assert (fast.steps, fast.rhs_evals, fast.method) == (ref.steps, ref.rhs_evals, ref.method)
    assert fast.steps == steps
    assert _rel_diff_eps(fast.y, ref.y) <= COMPENSATED_EPS


# The thin and near-degenerate regimes are left out: there J1 ≪ |L| or J1 ≈ J2 make
# the motion amplify any rounding by 1e3 and more over a few rotations (measured
# 2400 eps between the paths for J = (1e-3, 1, 1.001)), which two reference runs with
# differently ordered sums would show as well; the bound is about the kernels.
ORDINARY_MOMENTS = ("equal", "general", "symmetric", "flat", "near-flat")


def _amplification(run, y0, seed: int = 0) -> float:
    """How many eps of the output one ulp of the initial state becomes: the reference
    run from y0 with every component moved by one ulp (random signs, two draws), against
    the run from y0.  A flat body such as J = (1/32, 1/2, 17/32) is nearly symmetric
    (J2 ≈ J3) and amplifies rounding by 430 over 3 s: two runs that round differently
    (the kernels sum in another order) differ by that factor times their own roundings."""
    base = run(y0)
    rng = np.random.default_rng(seed)
    worst = 0.0
    for _ in range(2):
        moved = np.where(
            rng.random(y0.shape) < 0.5, np.nextafter(y0, np.inf), np.nextafter(y0, -np.inf)
        )
        worst = max(worst, _rel_diff_eps(run(moved), base))
    return worst


@settings(max_examples=20, deadline=None)
@given(
    J=principal_moments(min_scale=0.1, max_scale=10.0, regimes=ORDINARY_MOMENTS),
    R0=rotation_matrices(),
    w=st.lists(st.floats(-2.0, 2.0), min_size=3, max_size=3),
    order=st.sampled_from(integrators.SPLITTING_ORDERS),
)
# found by hypothesis (dev profile): a flat body near J2 = J3, where one ulp of the
# initial state grows to 430 eps in the reference itself; the paths differed by 1270 eps
@example(J=np.array([0.03125, 0.5, 0.53125]), R0=np.eye(3), w=[1.0, 2.0, -1.0], order=2)
def test_compiled_and_reference_agree_on_any_free_body(J, R0, w, order):
    L0 = J * np.array(w)
    t = (0.0, 3.0)
    fast = free_rigid_body_splitting(J, L0, R0, t, 0.1, order=order)
    ref = free_rigid_body_splitting(J, L0, R0, t, 0.1, order=order, compiled=False)
    assert _rel_diff_eps(fast.y, ref.y) <= SPLITTING_EPS
    y0 = rigid_body_state(L0, R0)
    rhs = free_rigid_body_rhs(J)
    fast = integrate(rhs, y0, t, method="dop853", rtol=1e-9)
    ref = integrate(rhs, y0, t, method="dop853", rtol=1e-9, compiled=False)
    assert fast.steps == ref.steps
    # the kernels' roundings, amplified as the motion amplifies one ulp of the start
    amp = _amplification(
        lambda y: integrate(rhs, y, t, method="dop853", rtol=1e-9, compiled=False).y, y0
    )
    assert _rel_diff_eps(fast.y, ref.y) <= DOP853_EPS * max(1.0, amp)


def test_moments_per_body_broadcast_on_the_compiled_path():
    Js = np.array([[1.0, 2.0, 3.0], [2.0, 2.5, 4.0]])
    y0 = rigid_body_state(Js * W_TOP, np.eye(3))
    rhs = free_rigid_body_rhs(Js)
    fast = integrate(rhs, y0, (0.0, 5.0), method="dop853", rtol=1e-10, batch_ndim=1)
    for i in range(2):  # each body alone, on the reference path, within the step's rounding
        alone = integrate(free_rigid_body_rhs(Js[i]), y0[i], (0.0, 5.0), method="rk4", h=1e-3)
        assert np.abs(fast.y[-1, i] - alone.y[-1]).max() < 1e-9


def _bad_calls():
    y0 = rigid_body_state(J_TOP * W_TOP, np.eye(3))
    rhs = free_rigid_body_rhs(J_TOP)
    return {
        "rtol<=0": (lambda c: integrate(rhs, y0, (0, 1), method="dop853", rtol=-1.0, compiled=c)),
        "h missing": (lambda c: integrate(rhs, y0, (0, 1), method="rk4", compiled=c)),
        "h nan": (lambda c: integrate(rhs, y0, (0, 1), method="rk4", h=np.nan, compiled=c)),
        "t decreasing": (
            lambda c: integrate(rhs, y0, (1, 0), method="dop853", rtol=1e-6, compiled=c)
        ),
        "y0 shape": (lambda c: integrate(rhs, y0[:5], (0, 1), method="rk4", h=0.1, compiled=c)),
        "J broadcast": (
            lambda c: integrate(
                free_rigid_body_rhs([J_TOP, J_TOP]), y0, (0, 1), method="rk4", h=0.1, compiled=c
            )
        ),
        "method": (lambda c: integrate(rhs, y0, (0, 1), method="rk45", compiled=c)),
        "order": (
            lambda c: free_rigid_body_splitting(J_TOP, W_TOP, np.eye(3), (0, 1), 0.1, order=3)
        ),
        "J triangle": (
            lambda c: free_rigid_body_splitting(
                [1.0, 2.0, 4.0], W_TOP, np.eye(3), (0, 1), 0.1, compiled=c
            )
        ),
        "L0 nan": (
            lambda c: free_rigid_body_splitting(
                J_TOP, [np.nan, 0, 0], np.eye(3), (0, 1), 0.1, compiled=c
            )
        ),
    }


BAD = _bad_calls()


@pytest.mark.parametrize("case", list(BAD))
def test_both_paths_refuse_bad_input_with_the_same_error(case):
    errors = (
        NonFiniteError,
        NonPhysicalInertiaError,
        NonPositiveParameterError,
        ShapeError,
        UnknownOptionError,
        OutOfDomainError,
    )
    raised = []
    for compiled in (True, False):
        with pytest.raises(errors) as info:
            BAD[case](compiled)
        raised.append((type(info.value), str(info.value)))
    assert raised[0] == raised[1]


@pytest.mark.parametrize("method", ["rk4", "dop853"])
def test_an_overflow_in_a_kernel_is_reported_as_the_reference_reports_it(method):
    # |L| h / J ~ 1e200: the rates overflow in the first step
    y0 = rigid_body_state(1e200 * J_TOP * W_TOP, np.eye(3))
    rhs = free_rigid_body_rhs(J_TOP)
    kw = {"h": 0.1} if method == "rk4" else {"rtol": 1e-6}
    raised = []
    for compiled in (True, False):
        with pytest.raises((NonFiniteError, ResultOverflowError, StepSizeError)) as e:
            integrate(rhs, y0, (0.0, 1.0), method=method, compiled=compiled, **kw)
        raised.append((type(e.value), str(e.value)))
    assert raised[0] == raised[1]
    assert "t=" in raised[0][1]


def test_a_python_rhs_runs_the_reference_path(monkeypatch):
    def no_kernels():
        raise AssertionError("a Python rhs must not reach the compiled kernels")

    monkeypatch.setattr(compiled_path, "_kernels", no_kernels)
    sol = integrate(lambda t, y: -y, 1.0, (0.0, 1.0), method="dop853", rtol=1e-10)
    assert abs(sol.y[-1] - np.exp(-1.0)) < 1e-9


class _BrokenKernels:
    """Stands for a numba whose compilation fails; counts its calls (per instance, so that
    no run of a test sees another's count)."""

    def __init__(self):
        self.calls = 0

    def __getattr__(self, name):
        def fail(*args):
            self.calls += 1
            raise RuntimeError(f"simulated JIT failure in {name}")

        return fail


def test_a_failed_jit_falls_back_to_the_reference_with_one_warning(monkeypatch):
    broken = _BrokenKernels()
    monkeypatch.setattr(compiled_path, "_KERNELS", broken)
    y0 = rigid_body_state(J_TOP * W_TOP, np.eye(3))
    rhs = free_rigid_body_rhs(J_TOP)
    with pytest.warns(CompiledPathWarning, match="simulated JIT failure") as record:
        sol = integrate(rhs, y0, (0.0, 5.0), method="dop853", rtol=1e-10)
    assert len(record) == 1
    ref = integrate(rhs, y0, (0.0, 5.0), method="dop853", rtol=1e-10, compiled=False)
    np.testing.assert_array_equal(sol.y, ref.y)  # the reference's result, to the bit
    with warnings.catch_warnings():  # given up for the process: no second warning
        warnings.simplefilter("error")
        again = free_rigid_body_splitting(J_TOP, J_TOP * W_TOP, np.eye(3), (0.0, 5.0), 0.1)
    assert broken.calls == 1
    assert again.steps == 50


def test_a_missing_numba_falls_back_to_the_reference_with_one_warning(monkeypatch):
    import sys

    monkeypatch.setattr(compiled_path, "_KERNELS", None)
    monkeypatch.setitem(sys.modules, "mechanics._kernels", None)  # import fails
    with pytest.warns(CompiledPathWarning, match="ModuleNotFoundError") as record:
        sol = free_rigid_body_splitting(J_TOP, J_TOP * W_TOP, np.eye(3), (0.0, 5.0), 0.1)
    assert len(record) == 1
    ref = free_rigid_body_splitting(
        J_TOP, J_TOP * W_TOP, np.eye(3), (0.0, 5.0), 0.1, compiled=False
    )
    np.testing.assert_array_equal(sol.y, ref.y)


# ---------------------------------------------------------------- the kernels' corners
# (issue 35: the survivors of the kernels' full mutation run; each test says which
# behaviour of the reference the kernel must share there)


def _dop853_both(y0, t, **kw):
    """The compiled and the reference run of the free body of moments J_TOP."""
    rhs = free_rigid_body_rhs(J_TOP)
    fast = integrate(rhs, y0, t, method="dop853", **kw)
    ref = integrate(rhs, y0, t, method="dop853", **kw, compiled=False)
    return fast, ref


def _same_work(fast, ref) -> None:
    work = ("steps", "rhs_evals", "rejected_steps")
    assert [getattr(fast, w) for w in work] == [getattr(ref, w) for w in work]


def _steps_growing_tenfold(h0: float, span: float) -> int:
    """Steps of h0, 10 h0, 100 h0, ... (DOP853's largest factor, taken on every step
    whose error is 0) until they cover ``span``."""
    steps, covered, h = 0, 0.0, h0
    while covered < span:
        covered += h
        h *= 10.0
        steps += 1
    return steps


# A body at rest (L = 0): every rate is 0, so the state stays y0 exactly and every
# error estimate is 0.  Hairer's starting step is then max(1e-6, 1e-3 · 1e-6) = 1e-6
# (the rates d1 = 0 and their change d2 = 0), each step is accepted with the largest factor, 10, and the run
# takes the steps of the geometric series that covers the span.  From t0 = 2^30 s the
# step is floored at 10 ulp(t0) = 10 · 2^-22 s first.  The spans sit between two sums
# of the series (1.1111 < 1.1115 < 1.1122 s, 2.65 < 2.8 < 2.91 s), so that a starting
# step 0.1 % or 10 % off would take one step fewer.
@pytest.mark.parametrize(
    ("t0", "span", "h0"),
    [(0.0, 1.1115, 1e-6), (2.0**30, 2.8, 10 * 2.0**-22)],
    ids=["t0=0", "t0=2^30"],
)
def test_compiled_dop853_on_a_body_at_rest_takes_the_steps_of_the_geometric_series(t0, span, h0):
    y0 = rigid_body_state(np.zeros(3), np.eye(3))
    fast, ref = _dop853_both(y0, (t0, t0 + span), rtol=1e-8)
    _same_work(fast, ref)
    assert fast.steps == _steps_growing_tenfold(h0, span)
    assert fast.rejected_steps == 0
    np.testing.assert_array_equal(fast.y, np.stack([y0, y0]))  # rates 0: y stays y0


# A batch whose first member is at the origin (y = 0, a fixed point of the free body's
# equations: no rate, no error) and whose second turns: the step is the batch's, set by
# the largest error and the smallest state, so the member at rest must neither stop
# the search for the largest error nor stand for the smallest state by its norm 0 alone
# (Hairer's start: the smallest member's size d0 = 0 gives the 1e-6 start).
@pytest.mark.parametrize("first", ["origin", "rest"])
def test_compiled_dop853_batch_with_a_member_at_rest_takes_the_reference_steps(first):
    still = np.zeros(12) if first == "origin" else rigid_body_state(np.zeros(3), np.eye(3))
    y0 = np.stack([still, rigid_body_state(J_TOP * W_TOP, np.eye(3))])
    fast, ref = _dop853_both(y0, (0.0, 3.0), rtol=1e-8, batch_ndim=1)
    _same_work(fast, ref)
    assert _rel_diff_eps(fast.y, ref.y) <= DOP853_EPS
    np.testing.assert_array_equal(fast.y[:, 0], np.stack([still, still]))


# Hairer's starting step clipped to the span, from a start time other than 0: t = (-1, 1)
# (a span of 2 s about t = 0) and a short span (0.05, 0.175] whose end is not
# t0 + (t_end - t0) in float64 (that rounds one ulp, 2^-55, below), so that the first
# step, clipped to the span, ends short of t_end by that ulp and a second step follows.
@pytest.mark.parametrize("t", [(-1.0, 1.0), (0.05, 0.17500000000000002)], ids=["-1..1", "short"])
def test_compiled_dop853_clips_the_starting_step_to_the_span_as_the_reference(t):
    y0 = rigid_body_state(J_TOP * W_TOP, np.eye(3))
    fast, ref = _dop853_both(y0, t, rtol=1e-4)  # Hairer's start 0.195 s > 0.125 s
    _same_work(fast, ref)
    assert _rel_diff_eps(fast.y, ref.y) <= DOP853_EPS


# The step budget: a run that needs exactly max_steps steps finishes on the compiled
# path; one step fewer allowed and both paths refuse it with the same StepSizeError.
def test_compiled_dop853_finishes_in_exactly_max_steps():
    y0 = rigid_body_state(J_TOP * W_TOP, np.eye(3))
    needed = _dop853_both(y0, (0.0, 5.0), rtol=1e-8)[1].steps
    fast, ref = _dop853_both(y0, (0.0, 5.0), rtol=1e-8, max_steps=needed)
    _same_work(fast, ref)
    assert fast.steps == needed


def test_compiled_dop853_refuses_one_step_beyond_max_steps_as_the_reference():
    y0 = rigid_body_state(J_TOP * W_TOP, np.eye(3))
    needed = _dop853_both(y0, (0.0, 5.0), rtol=1e-8)[1].steps
    raised = []
    for compiled in (True, False):
        with pytest.raises(StepSizeError) as info:
            integrate(
                free_rigid_body_rhs(J_TOP),
                y0,
                (0.0, 5.0),
                method="dop853",
                rtol=1e-8,
                max_steps=needed - 1,
                compiled=compiled,
            )
        raised.append(str(info.value))
    assert raised[0] == raised[1]


# Loose tolerances (rtol = 1e-3, atol = 1): the error norm's 3rd-order term 0.01 |e3|^2
# is then of the order of |e5|^2 (with tight ones it is 1e10 times larger), and the
# absolute tolerance sets the scale of the state (|R| = 1), so that Hairer's start,
# d0/d1 at most, takes the batch's smallest state d0 and largest rate d1 (a slow body
# and a fast one, either first); for a body of middle speed the start is Hairer's
# (0.01 / d2)^(1/8), d2 the change of the rates over a trial step forward (the change
# over a step backward differs in its second-order term, 4e-4 of it here).
@pytest.mark.parametrize("order", ["small first", "large first"])
def test_compiled_dop853_at_loose_tolerances_takes_the_reference_steps(order):
    small = rigid_body_state(1e-3 * J_TOP * W_TOP, np.eye(3))
    large = rigid_body_state(20.0 * J_TOP * W_TOP, np.eye(3))
    y0 = np.stack([small, large] if order == "small first" else [large, small])
    rhs = free_rigid_body_rhs(J_TOP)
    middle = rigid_body_state(5.0 * J_TOP * W_TOP, np.eye(3))  # start h1 = (0.01/d2)^(1/8)
    for y, bn in ((y0, 1), (y0[1], 0), (middle, 0)):
        kw = {"rtol": 1e-3, "atol": 1.0, "batch_ndim": bn}
        fast, ref = _dop853_both(y, (0.0, 2.0), **kw)
        _same_work(fast, ref)
        # steps of ~1 rad amplify the kernels' roundings (measured 45771 eps between the
        # paths for the batch, 13 steps, where one ulp of the start grows to 284133 eps):
        # bounded as the motion amplifies one ulp of the start
        amp = _amplification(
            lambda z, kw=kw: integrate(rhs, z, (0.0, 2.0), method="dop853", **kw, compiled=False).y,
            y,
        )
        assert _rel_diff_eps(fast.y, ref.y) <= DOP853_EPS * max(1.0, amp)


# The splitting's work: its flows are counted per run of at most PROJECT_EVERY steps
# between projections, the opening half-flow of H1 once per run; runs of one step
# (one step per output, or 65 = 64 + 1 steps) count it as well.
@pytest.mark.parametrize("steps_per_output", [1, 65])
@pytest.mark.parametrize("compensated", [False, True])
def test_compiled_splitting_counts_the_reference_flows(steps_per_output, compensated):
    assert splitting_module.PROJECT_EVERY == 64
    t = np.linspace(0.0, 0.3, 4)
    h = 0.1 / steps_per_output
    kw = {"order": 4, "compensated": compensated}
    fast = free_rigid_body_splitting(J_TOP, J_TOP * W_TOP, np.eye(3), t, h, **kw)
    ref = free_rigid_body_splitting(J_TOP, J_TOP * W_TOP, np.eye(3), t, h, **kw, compiled=False)
    assert (fast.steps, fast.rhs_evals) == (ref.steps, ref.rhs_evals)
    assert fast.steps == 3 * steps_per_output
    assert _rel_diff_eps(fast.y, ref.y) <= SPLITTING_EPS


def _off_orthogonal_rotation(size: float) -> np.ndarray:
    """A rotation moved off orthogonality by ``size`` in a symmetric direction with nine
    different entries (max |R Rᵀ − 1| ≈ 2 size), within check_rotation's 256 eps."""
    S = np.array([[3.0, 1.0, -2.0], [1.0, -1.5, 0.5], [-2.0, 0.5, 2.5]]) / 3.0
    from mechanics.rotation import matrix_from_rotvec

    return (np.eye(3) + size * S) @ matrix_from_rotvec(np.array([0.3, -0.2, 0.5]))


# The projection (Hairer-Lubich-Wanner IV.4) at every output: |L| is the Casimir of the
# free body, restored to |L0| (one product and one square root: a few eps), and one
# Newton-Schulz step R - ½ (R Rᵀ - 1) R takes R Rᵀ - 1 from δ to O(δ²) plus roundings.
# Measured on both paths: ||L| - |L0|| ≤ 0.7 eps |L0|, max |R Rᵀ - 1| ≤ 1 eps, from
# R0 off by 100 eps and |L0| < 1 (the norm must be restored below 1 as above it:
# unprojected, the 108 flows of a step of order 8 let |L| drift by 84 eps in 20 s).
CASIMIR_EPS = 4
ORTHOGONALITY_EPS = 8


@pytest.mark.parametrize("compiled", [True, False])
def test_splitting_restores_the_casimir_and_orthogonality_at_every_output(compiled):
    R0 = _off_orthogonal_rotation(50 * EPS)
    L0 = 0.25 * J_TOP * W_TOP  # |L0| = 0.77
    t = np.linspace(0.0, 20.0, 5)
    sol = free_rigid_body_splitting(J_TOP, L0, R0, t, 0.05, order=8, compiled=compiled)
    L = sol.y[1:, :3]
    R = sol.y[1:, 3:].reshape(-1, 3, 3)
    norm0 = np.linalg.norm(L0)
    assert np.abs(np.linalg.norm(L, axis=-1) - norm0).max() <= CASIMIR_EPS * EPS * norm0
    off = np.abs(R @ np.swapaxes(R, -1, -2) - np.eye(3)).max()
    assert off <= ORTHOGONALITY_EPS * EPS


# The kernels' status protocol, on the kernel itself: a state that is not finite at an
# output (here from a NaN momentum of the second body, which the public functions refuse
# before any kernel runs) stops with status 1, whichever output and body it is: the
# check reads the rows just written (of three outputs, the first is the caller's and
# the other two are written by the kernel; ys starts as zeros, all finite).
def test_the_splitting_kernel_reports_a_non_finite_state_with_status_1():
    from mechanics import _kernels

    sched = splitting_module._SCHEDULES[2]
    axes = np.array([i for i, _ in sched[1:-1]], dtype=np.int64)
    fracs = np.array([c for _, c in sched[1:-1]], dtype=np.float64)
    J = np.ascontiguousarray(np.stack([J_TOP, J_TOP]))
    L0 = np.array([J_TOP * W_TOP, [np.nan, 0.0, 0.0]])
    R0 = np.stack([np.eye(3), np.eye(3)])
    t = np.linspace(0.0, 1.0, 3)
    for compensated in (False, True):
        ys = np.zeros((t.size, 2, 12))
        status, _ = _kernels.splitting_free_body(
            J,
            L0,
            R0,
            np.array([np.linalg.norm(L0[0]), np.nan]),
            t,
            np.array([10, 10], dtype=np.int64),
            axes,
            fracs,
            float(sched[0][1]),
            64,
            compensated,
            ys,
        )
        assert status == _kernels.STATUS_NONFINITE


# Hairer's start where the rates vanish and their Jacobian does not: a spin of 1000 rad/s
# about the axis of the smallest moment, 7e-27 of momentum off it, momentum only (R = 0,
# a solution of the linear equations of R that stays 0).  The rates (L × ω, ~3e-24) scaled
# by atol are d1 ~ 1e-16 ≤ 1e-15, but one trial step moves them by ω times as much,
# d2 ~ 7e-14 > 1e-15: the start is (0.01 / d2)^(1/8), not the 1e-6 of a state at rest.
def test_compiled_dop853_starts_a_spin_about_a_principal_axis_as_the_reference():
    y0 = np.concatenate([[1000.0, 7e-27, 0.0], np.zeros(9)])
    fast, ref = _dop853_both(y0, (0.0, 0.01), rtol=1e-8, atol=1e-8)
    _same_work(fast, ref)
    assert _rel_diff_eps(fast.y, ref.y) <= DOP853_EPS
