"""API, validation, convergence orders and work counts of :mod:`mechanics.integrators`.

References are independent of the code under test: exp(λt) and (cos t, −sin t) in
closed form, the Jacobi-elliptic motion of :class:`mechanics.tops.FreeAsymmetricTop`,
Euler's equations from :func:`mechanics.dynamics.euler_equations_rhs` and the book's
Ω from :func:`mechanics.kinematics.omega_matrix_from_vector`.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import warnings

import numpy as np
import pytest

from mechanics import integrators
from mechanics._floats import EPS
from mechanics.dynamics import euler_equations_rhs
from mechanics.errors import (
    NonFiniteError,
    NonPhysicalInertiaError,
    NonPositiveParameterError,
    NotARotationError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
    StepSizeError,
    UnknownOptionError,
)
from mechanics.integrators import (
    METHODS,
    SPLITTING_ORDERS,
    Solution,
    free_rigid_body_rhs,
    free_rigid_body_splitting,
    integrate,
    rigid_body_parts,
    rigid_body_state,
    so3_exp_step,
    time_grid,
)
from mechanics.integrators import _splitting as splitting
from mechanics.kinematics import angular_velocity_from_matrix_rate, omega_matrix_from_vector
from mechanics.rotation import R1, R3, ROTATION_ATOL, matrix_from_rotvec
from mechanics.tops import FreeAsymmetricTop

from ._naming import cases, check_refusal, valid_kwargs

J_TOP = np.array([1.0, 2.0, 2.5])
W_TOP = np.array([0.3, -1.0, 0.7])


def decay(t, y):
    return -y


def oscillator(t, y):
    """q' = p, p' = −q; exact (cos t, −sin t) from (1, 0)."""
    return np.stack([y[..., 1], -y[..., 0]], axis=-1)


class Counting:
    """A right-hand side that counts its own calls and records the times."""

    def __init__(self, f):
        self.f, self.calls, self.times = f, 0, []

    def __call__(self, t, y):
        self.calls += 1
        self.times.append(t)
        return self.f(t, y)


def _osc_error(sol):
    t = sol.t[-1]
    return float(np.abs(sol.y[-1] - [np.cos(t), -np.sin(t)]).max())


# ------------------------------------------------------------------------ API


def test_solution_holds_times_states_and_work_and_is_frozen():
    sol = integrate(decay, [1.0, 2.0], [0.0, 0.5, 1.0], method="rk4", h=0.1)
    assert isinstance(sol, Solution)
    assert sol.t.tolist() == [0.0, 0.5, 1.0]
    assert sol.y.shape == (3, 2)
    assert sol.y[0].tolist() == [1.0, 2.0]
    assert (sol.method, sol.steps, sol.rhs_evals, sol.rejected_steps) == ("rk4", 10, 40, 0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        sol.steps = 3
    with pytest.raises(ValueError, match="read-only"):
        sol.y[0, 0] = 5.0


def test_states_keep_the_shape_of_y0():
    y0 = np.ones((4, 3, 2))
    for method, kw in (("rk4", {"h": 0.1}), ("dop853", {"rtol": 1e-8})):
        sol = integrate(decay, y0, (0.0, 1.0), method=method, **kw)
        assert sol.y.shape == (2, 4, 3, 2)
    scalar = integrate(decay, 1.0, (0.0, 1.0), method="rk4", h=0.5)
    assert scalar.y.shape == (2,)


# ----------------------------------------------------------------- validation


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_initial_state_is_rejected(bad):
    with pytest.raises(NonFiniteError, match="y0"):
        integrate(decay, [1.0, bad], (0.0, 1.0), method="rk4", h=0.1)


@pytest.mark.parametrize("h", [0.0, -0.1])
def test_non_positive_step_is_rejected(h):
    with pytest.raises(NonPositiveParameterError, match="h must be > 0"):
        integrate(decay, 1.0, (0.0, 1.0), method="rk4", h=h)
    with pytest.raises(NonPositiveParameterError, match="h must be > 0"):
        free_rigid_body_splitting(J_TOP, J_TOP * W_TOP, np.eye(3), (0.0, 1.0), h)
    with pytest.raises(NonPositiveParameterError, match="h must be > 0"):
        so3_exp_step(np.eye(3), [0.0, 0.0, 1.0], h)


@pytest.mark.parametrize("name", ["rtol", "atol"])
@pytest.mark.parametrize("value", [0.0, -1e-8])
def test_non_positive_tolerance_is_rejected(name, value):
    kw = {"rtol": 1e-8, name: value}
    with pytest.raises(NonPositiveParameterError, match=f"{name} must be > 0"):
        integrate(decay, 1.0, (0.0, 1.0), method="dop853", **kw)


def test_missing_step_or_tolerance_is_named():
    with pytest.raises(NonPositiveParameterError, match="'rk4' needs a step h"):
        integrate(decay, 1.0, (0.0, 1.0), method="rk4")
    with pytest.raises(NonPositiveParameterError, match="'dop853' needs rtol"):
        integrate(decay, 1.0, (0.0, 1.0), method="dop853")
    with pytest.raises(UnknownOptionError, match="rtol/atol"):
        integrate(decay, 1.0, (0.0, 1.0), method="rk4", h=0.1, rtol=1e-6)


def test_unknown_method_names_the_choices():
    with pytest.raises(UnknownOptionError) as info:
        integrate(decay, 1.0, (0.0, 1.0), method="rk45", h=0.1)
    for m in METHODS:
        assert repr(m) in str(info.value)
    with pytest.raises(UnknownOptionError, match=r"\(2, 4, 6, 8\)"):
        free_rigid_body_splitting(J_TOP, J_TOP * W_TOP, np.eye(3), (0.0, 1.0), 0.1, order=3)


def test_bad_time_grids_are_rejected():
    with pytest.raises(OutOfDomainError, match=r"t\[2\] = 0.5"):
        integrate(decay, 1.0, [0.0, 1.0, 0.5], method="rk4", h=0.1)
    with pytest.raises(OutOfDomainError, match="strictly increasing"):
        integrate(decay, 1.0, [0.0, 0.0], method="rk4", h=0.1)
    with pytest.raises(ShapeError, match="at least two"):
        integrate(decay, 1.0, [0.0], method="rk4", h=0.1)
    with pytest.raises(NonFiniteError, match="t must be finite"):
        integrate(decay, 1.0, [0.0, np.inf], method="rk4", h=0.1)


@pytest.mark.parametrize("method", METHODS)
def test_rhs_of_the_wrong_shape_is_named_with_its_time(method):
    kw = {"h": 0.1} if method == "rk4" else {"rtol": 1e-6}
    with pytest.raises(ShapeError, match=r"shape \(3,\) at t=0\.0.*\(2,\)"):
        integrate(lambda t, y: np.ones(3), [1.0, 1.0], (0.0, 1.0), method=method, **kw)


@pytest.mark.parametrize("method", METHODS)
def test_rhs_returning_nan_is_named_with_its_time(method):
    def f(t, y):
        return np.full_like(y, np.nan) if t > 0.45 else -y

    kw = {"h": 0.1} if method == "rk4" else {"rtol": 1e-6, "h": 0.05}
    g = Counting(f)
    with pytest.raises(NonFiniteError, match=r"non-finite value at t=") as info:
        integrate(g, [1.0, 1.0], [0.0, 0.3, 1.0], method=method, **kw)
    first_bad = next(t for t in g.times if t > 0.45)  # rk4: 0.5, a stage time
    assert f"at t={first_bad!r}:" in str(info.value)


def test_blow_up_is_reported_not_returned():
    with pytest.raises((NonFiniteError, ResultOverflowError), match="t="):
        integrate(lambda t, y: y * y, 1.0, (0.0, 2.0), method="rk4", h=0.01)
    with pytest.raises((NonFiniteError, ResultOverflowError, StepSizeError), match="t="):
        integrate(lambda t, y: y * y, 1.0, (0.0, 2.0), method="dop853", rtol=1e-8)


def test_too_many_adaptive_steps_raise():
    with pytest.raises(StepSizeError, match="max_steps=5"):
        integrate(oscillator, [1.0, 0.0], (0.0, 100.0), method="dop853", rtol=1e-10, max_steps=5)


def test_rigid_body_inputs_are_validated():
    L0 = J_TOP * W_TOP
    with pytest.raises(NonPhysicalInertiaError, match="> 0"):
        free_rigid_body_splitting([1.0, -2.0, 2.5], L0, np.eye(3), (0.0, 1.0), 0.1)
    with pytest.raises(NonPhysicalInertiaError, match="triangle inequality J1 \\+ J2 ≥ J3"):
        free_rigid_body_splitting([1.0, 2.0, 4.0], L0, np.eye(3), (0.0, 1.0), 0.1)
    with pytest.raises(NotARotationError):
        free_rigid_body_splitting(J_TOP, L0, 2 * np.eye(3), (0.0, 1.0), 0.1)
    with pytest.raises(NonFiniteError, match="L0"):
        free_rigid_body_splitting(J_TOP, [np.nan, 0, 0], np.eye(3), (0.0, 1.0), 0.1)
    with pytest.raises(NotARotationError):
        so3_exp_step(np.ones((3, 3)), [0.0, 0.0, 1.0], 0.1)
    with pytest.raises(ShapeError, match=r"\(\.\.\., 12\)"):
        free_rigid_body_rhs(J_TOP)(0.0, np.ones(9))


# ----------------------------------------------------- orders of convergence


def test_rk4_error_falls_16_fold_when_h_halves_on_exponential_decay():
    errs = [
        abs(integrate(decay, 1.0, (0.0, 2.0), method="rk4", h=h).y[-1] - math.exp(-2.0))
        for h in (0.2, 0.1, 0.05)
    ]
    ratios = [errs[0] / errs[1], errs[1] / errs[2]]
    assert all(14.0 < r < 18.0 for r in ratios), ratios


def test_rk4_error_falls_16_fold_when_h_halves_on_the_oscillator():
    errs = [
        _osc_error(integrate(oscillator, [1.0, 0.0], (0.0, 10.0), method="rk4", h=h))
        for h in (0.2, 0.1, 0.05)
    ]
    ratios = [errs[0] / errs[1], errs[1] / errs[2]]
    assert all(14.0 < r < 18.0 for r in ratios), ratios


def test_dop853_global_error_tracks_rtol():
    # Measured: error/rtol between 1.43 and 1.49 for rtol = 1e-6 … 1e-12 over 10
    # time units; "tracks" = within a factor 10 of rtol and falling with it.
    errs = []
    for rtol in (1e-6, 1e-8, 1e-10, 1e-12):
        sol = integrate(oscillator, [1.0, 0.0], (0.0, 10.0), method="dop853", rtol=rtol)
        errs.append(_osc_error(sol))
        assert errs[-1] <= 10 * rtol
        assert errs[-1] >= 0.01 * rtol  # not a fluke of a step far finer than needed
    assert all(a > 30 * b for a, b in itertools.pairwise(errs))


def test_dop853_is_of_order_eight_on_exponential_decay():
    # One step of the given h (the span ends there, a huge rtol accepts it): the
    # local error of an 8th-order method is O(h⁹), so it falls about 2⁹ = 512-fold
    # when h halves (measured 431 from h = 0.5, 349 from 1, 165 from 2: the higher
    # terms fade).  (The output grid no longer sets the steps: issue 15.)
    errs = []
    for h in (0.5, 0.25):
        sol = integrate(decay, 1.0, (0.0, h), method="dop853", rtol=1e3, h=h)
        assert sol.steps == 1
        assert sol.rejected_steps == 0
        errs.append(abs(sol.y[-1] - math.exp(-h)))
    assert 360.0 < errs[0] / errs[1] < 720.0


@pytest.mark.parametrize(
    ("order", "lo", "hi"),
    [(2, 3.6, 4.4), (4, 14.0, 18.0), (6, 55.0, 72.0), (8, 220.0, 290.0)],  # 8: 252 measured
)
def test_splitting_converges_at_its_order_to_the_exact_top(order, lo, hi):
    top = FreeAsymmetricTop(J_TOP, W_TOP)
    T = 20.0
    L_ex, R_ex = J_TOP * top.omega(T), top.attitude(T)
    errs = []
    for h in (0.1, 0.05, 0.025):
        sol = free_rigid_body_splitting(J_TOP, J_TOP * W_TOP, np.eye(3), (0.0, T), h, order=order)
        L, R = rigid_body_parts(sol.y[-1])
        errs.append(max(np.abs(L - L_ex).max(), np.abs(R - R_ex).max()))
    ratios = [errs[0] / errs[1], errs[1] / errs[2]]
    assert all(lo < r < hi for r in ratios), ratios


# ------------------------------------------------------------------ time grid


def test_time_grid_is_t0_plus_n_h_where_a_running_sum_drifts():
    n = 10**6
    t = time_grid(0.0, 0.1, n)
    assert t[-1] == 100000.0
    assert np.array_equal(t, 0.1 * np.arange(n + 1))
    assert np.cumsum(np.full(n, 0.1))[-1] != 100000.0  # what t += h would give


def test_rk4_on_the_grid_steps_once_per_output_at_the_grid_times():
    t = time_grid(0.3, 0.1, 50)
    f = Counting(decay)
    sol = integrate(f, 1.0, t, method="rk4", h=0.1)
    assert sol.steps == 50
    assert np.array_equal(sol.t, t)
    assert f.times[0::4] == t[:-1].tolist()  # the first stage of each step


def test_long_rk4_run_reaches_the_end_time_without_accumulating():
    n, h = 10**4, 0.1
    f = Counting(lambda t, y: np.zeros_like(y))
    sol = integrate(f, 0.0, (0.0, n * h), method="rk4", h=h)
    assert sol.steps == n
    t_last = f.times[-1]  # the last stage: t0 + n h_eff
    assert abs(t_last - n * h) <= math.ulp(n * h)
    acc = 0.0
    for _ in range(n):
        acc += h
    assert abs(acc - n * h) > 100 * math.ulp(n * h)  # the running sum is visibly off


# ---------------------------------------------------------------------- Kahan


def test_kahan_summation_removes_the_rounding_walk_of_a_long_fixed_step_run():
    # y' = c for 200 values of c over 2¹⁴ steps of h = 2⁻¹⁰: the exact end value
    # 1 + 16 c is a float (a power-of-2 multiple).  Measured: plain addition 2623
    # eps worst (1018 median), compensated 1.15 eps worst.
    c = np.random.default_rng(20240919).uniform(0.1, 1.0, 200)
    n, h = 2**14, 2.0**-10
    exact = 1.0 + c * (n * h)

    def run(kahan):
        sol = integrate(lambda t, y: c, np.ones(200), (0.0, n * h), method="rk4", h=h, kahan=kahan)
        return float((np.abs(sol.y[-1] - exact) / exact).max())

    plain, compensated = run(False), run(True)
    assert compensated <= 4 * EPS
    assert plain >= 100 * EPS
    dop = integrate(
        lambda t, y: c, np.ones(200), (0.0, n * h), method="dop853", rtol=1e-6, kahan=True
    )
    assert float((np.abs(dop.y[-1] - exact) / exact).max()) <= 4 * EPS


# The compensated splitting (issue 15, part 3): order 8 at 1000 steps per rotation of
# the top J = (1, 2, 3), ω0 = (0.4, 0.2, 1.0), where its energy error (h ω)^8 ~ 2e-18 is
# far below rounding; the RMS of |E/E0 − 1| over steps 3e4 … 1e5 measured 41 eps plain
# (projected every 64 steps) and 1.6 eps compensated (bench/roundoff.py, over 1e4 … 1e6
# steps: the state's error at 1e6 steps 1.0e-12 compensated against 6.2e-11 plain).
COMPENSATED_ENERGY_EPS = 8  # the RMS energy rounding after 1e5 steps, 5x the measurement
COMPENSATED_GAIN = 4  # plain / compensated, measured 25


def test_compensated_splitting_keeps_the_energy_rounding_near_eps():
    J, w0 = np.array([2.0, 3.0, 1.0]), np.array([0.2, 1.0, 0.4])  # (J_mid, J_max, J_min)
    L0 = J * w0
    E0 = 0.5 * float(np.sum(L0 * L0 / J))
    h = 2 * np.pi / float(np.linalg.norm(w0)) / 1000
    k = np.unique(np.round(np.geomspace(3e4, 1e5, 60)).astype(int))
    t = np.concatenate([[0.0], k * h])

    def rms_energy_error(compensated):
        sol = free_rigid_body_splitting(J, L0, np.eye(3), t, h, order=8, compensated=compensated)
        L = sol.y[1:, :3]
        dE = 0.5 * np.sum(L * L / J, axis=1) / E0 - 1
        return float(np.sqrt(np.mean(dE * dE))) / EPS

    plain, compensated = rms_energy_error(False), rms_energy_error(True)
    assert compensated <= COMPENSATED_ENERGY_EPS, compensated
    assert plain >= COMPENSATED_GAIN * compensated, (plain, compensated)


def test_compensated_splitting_rejects_a_non_boolean():
    with pytest.raises(UnknownOptionError, match="compensated must be True or False"):
        free_rigid_body_splitting(
            np.ones(3), np.ones(3), np.eye(3), (0.0, 1.0), 0.1, compensated="yes"
        )


# --------------------------------------------------------------------- batches


@pytest.mark.parametrize("kahan", [False, True])
def test_batched_rk4_equals_stacked_single_runs_bitwise(kahan):
    rng = np.random.default_rng(1)
    y0 = rng.normal(size=(7, 2))
    t = [0.0, 1.3, 5.0]
    batch = integrate(oscillator, y0, t, method="rk4", h=0.1, kahan=kahan)
    singles = np.stack(
        [integrate(oscillator, y, t, method="rk4", h=0.1, kahan=kahan).y for y in y0], axis=1
    )
    assert np.array_equal(batch.y, singles)
    assert batch.rhs_evals == integrate(oscillator, y0[0], t, method="rk4", h=0.1).rhs_evals


def test_batched_splitting_equals_stacked_single_runs():
    rng = np.random.default_rng(2)
    L0 = J_TOP * rng.normal(size=(5, 3))
    R0 = matrix_from_rotvec(rng.normal(size=(5, 3)))
    t = time_grid(0.0, 0.7, 10)
    batch = free_rigid_body_splitting(J_TOP, L0, R0, t, 0.1, order=4)
    singles = np.stack(
        [
            free_rigid_body_splitting(J_TOP, L, R, t, 0.1, order=4).y
            for L, R in zip(L0, R0, strict=True)
        ],
        axis=1,
    )
    # One body runs in Python floats (math.cos), a batch in numpy (np.cos): the
    # two libraries may round a cosine differently by an ulp; measured equal.
    assert np.abs(batch.y - singles).max() <= 64 * EPS * np.abs(singles).max()
    assert batch.steps == 70


def test_batched_dop853_takes_one_step_for_all_and_keeps_each_within_tolerance():
    J = np.array([[1.0, 2.0, 2.5], [1.0, 1.5, 2.0], [2.0, 2.0, 3.0]])
    w0 = np.array([[0.3, -1.0, 0.7], [1.0, 0.2, -0.5], [0.1, 0.1, 2.0]])
    y0 = rigid_body_state(J * w0, np.eye(3))
    T, rtol = 8.0, 1e-9
    batch = integrate(
        free_rigid_body_rhs(J), y0, (0.0, T), method="dop853", rtol=rtol, batch_ndim=1
    )
    singles = [
        integrate(free_rigid_body_rhs(J[i]), y0[i], (0.0, T), method="dop853", rtol=rtol)
        for i in range(3)
    ]
    assert batch.steps >= max(s.steps for s in singles)
    for i, s in enumerate(singles):
        top = FreeAsymmetricTop(J[i], w0[i])
        L_b, _ = rigid_body_parts(batch.y[-1, i])
        L_s, _ = rigid_body_parts(s.y[-1])
        L_ex = J[i] * top.omega(T)
        assert np.abs(L_b - L_ex).max() <= 100 * rtol * np.abs(L_ex).max()
        assert np.abs(L_b - L_ex).max() <= 2 * np.abs(L_s - L_ex).max() + 10 * rtol


# ------------------------------------------------------------------ work counts


def test_rk4_work_is_four_evaluations_per_step():
    f = Counting(oscillator)
    sol = integrate(f, [1.0, 0.0], [0.0, 0.25, 1.0], method="rk4", h=0.1)
    assert sol.steps == 3 + 8  # ⌈0.25/0.1⌉ + ⌈0.75/0.1⌉
    assert sol.rhs_evals == f.calls == 4 * sol.steps


@pytest.mark.parametrize("h0", [None, 10.0])
def test_dop853_work_counts_every_evaluation_and_rejection(h0):
    f = Counting(oscillator)
    sol = integrate(f, [1.0, 0.0], (0.0, 20.0), method="dop853", rtol=1e-10, h=h0)
    assert sol.rhs_evals == f.calls
    start = 2 if h0 is None else 1  # f(t0), and Hairer's trial evaluation
    assert f.calls == start + 12 * (sol.steps + sol.rejected_steps)
    if h0 is not None:  # a first step of 10 (1.6 periods) cannot meet 1e-10
        assert sol.rejected_steps >= 1


# The reference path sums as scipy does (np.dot): 64 eps.  The compiled path sums the
# stages in its own order, a few eps per step apart; measured 96 eps here (|y| ~ 2.3).
SCIPY_AGREEMENT_EPS = {False: 64, True: 512}


@pytest.mark.parametrize("compiled", [False, True])
def test_dop853_matches_scipy_step_for_step(compiled):
    from scipy.integrate import solve_ivp

    rhs = free_rigid_body_rhs(J_TOP)
    y0 = rigid_body_state(J_TOP * W_TOP, np.eye(3))
    ours = integrate(rhs, y0, (0.0, 20.0), method="dop853", rtol=1e-9, atol=1e-9, compiled=compiled)
    ref = solve_ivp(rhs, (0.0, 20.0), y0, method="DOP853", rtol=1e-9, atol=1e-9)
    assert ours.steps == ref.t.size - 1
    assert ours.rhs_evals == ref.nfev
    bound = SCIPY_AGREEMENT_EPS[compiled] * EPS
    assert np.abs(ours.y[-1] - ref.y[:, -1]).max() <= bound


def test_splitting_work_counts_merged_sub_flows():
    L0 = J_TOP * W_TOP
    span = free_rigid_body_splitting(J_TOP, L0, np.eye(3), (0.0, 1.0), 0.1)
    assert span.steps == 10
    assert span.rhs_evals == 4 * 10 + 1  # H1 half-flows of adjacent steps merge
    grid = free_rigid_body_splitting(J_TOP, L0, np.eye(3), time_grid(0.0, 0.1, 10), 0.1)
    assert grid.rhs_evals == 5 * 10  # an output between steps keeps them apart
    assert np.abs(grid.y[-1] - span.y[-1]).max() <= 64 * EPS


# --------------------------------------------------------- rigid-body pieces


def test_free_rigid_body_rhs_is_eulers_equations_and_the_books_omega():
    rng = np.random.default_rng(3)
    L = rng.normal(size=(6, 3))
    R = matrix_from_rotvec(rng.normal(size=(6, 3)))
    dy = free_rigid_body_rhs(J_TOP)(0.0, rigid_body_state(L, R))
    dL, dR = dy[..., :3], dy[..., 3:].reshape(6, 3, 3)
    w = L / J_TOP
    assert np.abs(dL - J_TOP * euler_equations_rhs(J_TOP, w, np.zeros(3))).max() <= 8 * EPS * 10
    assert np.abs(dR - omega_matrix_from_vector(w) @ R).max() <= 8 * EPS * 10


def test_rigid_body_state_round_trips():
    L, R = np.array([1.0, -2.0, 0.5]), R1(0.3) @ R3(1.1)
    L2, R2 = rigid_body_parts(rigid_body_state(L, R))
    assert np.array_equal(L2, L)
    assert np.array_equal(R2, R)


def test_so3_exp_step_has_the_rate_of_the_books_omega():
    rng = np.random.default_rng(4)
    R = matrix_from_rotvec(rng.normal(size=3))
    w = rng.normal(size=3)
    h = 1e-6
    rate = (so3_exp_step(R, w, h) - R) / h  # forward difference: O(h |ω|²) off
    assert np.abs(rate - omega_matrix_from_vector(w) @ R).max() <= 10 * h * (w @ w)
    w_back = angular_velocity_from_matrix_rate(R, omega_matrix_from_vector(w) @ R)
    assert np.abs(w_back - w).max() <= 16 * EPS


def test_so3_exp_steps_compose_and_stay_orthogonal_where_euler_steps_drift():
    rng = np.random.default_rng(5)
    w, h, n = rng.normal(size=3), 1e-3, 10**3
    R = R_euler = np.eye(3)
    for _ in range(n):
        R = so3_exp_step(R, w, h)
        R_euler = R_euler + h * omega_matrix_from_vector(w) @ R_euler
    # n steps of constant ω are one turn by n h ω (2.29)
    assert np.abs(R - matrix_from_rotvec(n * h * w)).max() <= 8 * EPS * math.sqrt(n) * 4
    assert np.abs(R @ R.T - np.eye(3)).max() <= ROTATION_ATOL
    assert np.abs(R_euler @ R_euler.T - np.eye(3)).max() > 1e3 * ROTATION_ATOL


def test_so3_exp_step_broadcasts_over_a_batch():
    rng = np.random.default_rng(6)
    R = matrix_from_rotvec(rng.normal(size=(4, 3)))
    w = rng.normal(size=(4, 3))
    out = so3_exp_step(R, w, 0.2)
    assert out.shape == (4, 3, 3)
    for i in range(4):
        assert np.array_equal(out[i], so3_exp_step(R[i], w[i], 0.2))


def test_so3_exp_step_names_h_and_w_A_where_the_rotation_vector_is_beyond_float64():
    # row 1: h ω3 = 1e10 · 1e300 = 1e310 is beyond float64 (row 0, 1e10 · 1 rad, is fine):
    # a ResultOverflowError naming the arguments of that row, and no RuntimeWarning
    # (pytest turns warnings into errors)
    with pytest.raises(ResultOverflowError) as info:
        so3_exp_step(np.eye(3), [[0.0, 0.0, 1.0], [0.0, 0.0, 1e300]], 1e10)
    assert str(info.value) == (
        "the rotation vector h w_A of h = 10000000000.0, w_A = [0.0, 0.0, 1e+300] "
        "(index (1,)) is beyond float64: |h w_A_i| exceeds 1.8e308"
    )


# ------------------------------------------------ dense output (issue 15, part 2)

DENSE_GRID = np.linspace(0.0, 20.0, 2001)  # the grid: 2001 outputs over 20 s
# max error over the grid / rtol, measured: oscillator 3.7, 4.2, 4.4 and the free top
# 13.9, 11.2, 9.7 at rtol 1e-6, 1e-8, 1e-12 (the interpolant adds little to the
# global error of the steps); bounds about 2.5× those.
DENSE_OSCILLATOR_RTOLS = 10
DENSE_TOP_RTOLS = 35


@pytest.mark.parametrize("rtol", [1e-6, 1e-8, 1e-12])
def test_dop853_steps_do_not_follow_the_output_grid(rtol):
    f = Counting(oscillator)
    grid = integrate(f, [1.0, 0.0], DENSE_GRID, method="dop853", rtol=rtol)
    span = integrate(oscillator, [1.0, 0.0], (0.0, 20.0), method="dop853", rtol=rtol)
    assert grid.steps == span.steps < 200  # was 2000 at every rtol: one per output
    assert grid.rejected_steps == span.rejected_steps
    np.testing.assert_array_equal(grid.y[-1], span.y[-1])  # the same steps, to the bit
    assert grid.rhs_evals == f.calls  # 3 more for each step that holds outputs
    assert grid.rhs_evals <= span.rhs_evals + 3 * span.steps


def test_dop853_step_count_falls_with_the_tolerance_on_a_dense_grid():
    steps = [
        integrate(oscillator, [1.0, 0.0], DENSE_GRID, method="dop853", rtol=r).steps
        for r in (1e-6, 1e-8, 1e-12)
    ]
    assert steps[0] < steps[1] < steps[2]


@pytest.mark.parametrize("rtol", [1e-6, 1e-8, 1e-12])
def test_dop853_dense_output_meets_the_exact_oscillator(rtol):
    sol = integrate(oscillator, [1.0, 0.0], DENSE_GRID, method="dop853", rtol=rtol)
    exact = np.stack([np.cos(DENSE_GRID), -np.sin(DENSE_GRID)], axis=-1)
    assert np.abs(sol.y - exact).max() <= DENSE_OSCILLATOR_RTOLS * rtol


@pytest.mark.parametrize("compiled", [True, False])
@pytest.mark.parametrize("rtol", [1e-6, 1e-8, 1e-12])
def test_dop853_dense_output_meets_the_exact_free_top(rtol, compiled):
    J = np.array([1.0, 2.0, 3.0])
    w0 = np.array([0.4, 0.2, 1.0])
    top = FreeAsymmetricTop(J, w0)
    y0 = rigid_body_state(J * w0, np.eye(3))
    sol = integrate(
        free_rigid_body_rhs(J), y0, DENSE_GRID, method="dop853", rtol=rtol, compiled=compiled
    )
    L, R = rigid_body_parts(sol.y)
    err = max(
        np.abs(L - J * top.omega(DENSE_GRID)).max(), np.abs(R - top.attitude(DENSE_GRID)).max()
    )
    assert err <= DENSE_TOP_RTOLS * rtol
    assert sol.steps < 200


def test_dop853_output_on_a_step_end_is_that_steps_state():
    # the grid's last point ends the last step: no interpolation there, and an
    # output grid that is a superset of another gives the same values on the common
    # points (the steps are the same)
    coarse = integrate(oscillator, [1.0, 0.0], DENSE_GRID[::100], method="dop853", rtol=1e-9)
    fine = integrate(oscillator, [1.0, 0.0], DENSE_GRID, method="dop853", rtol=1e-9)
    np.testing.assert_array_equal(coarse.y, fine.y[::100])


# ------------------------------------------- every parameter named, every overflow named
_POS = r"must be > 0; got (0\.0|-1\.0)"
#: the condition an unphysical value of each fuzz entry violates (tests.fuzz.entries)
_CONDITIONS = {
    ("free_rigid_body_rhs", "J"): r"J \(the principal moments\) must be > 0; J1 = 0\.0 at index",
    ("free_rigid_body_splitting", "J"): (
        r"J \(the principal moments\) must be > 0; J1 = 0\.0 at index"
        r"|J breaks the triangle inequality J1 \+ J2 ≥ J3: moments \[1\.0, 1\.0, 3\.0\]"
    ),
    ("free_rigid_body_splitting", "h"): _POS,
    ("free_rigid_body_splitting", "order"): r"order must be one of \(2, 4, 6, 8\); got 3$",
    ("integrate", "h"): _POS,
    ("integrate", "t"): r"t must be strictly increasing; t\[1\] = 0\.0 ≤ t\[0\] = 1\.0",
    ("time_grid", "h"): _POS,
    ("time_grid", "n"): r"n must be an integer ≥ 1; got (-1|2\.5)$",
    ("DOP853Stepper", "rtol"): _POS,
    ("DOP853Stepper", "atol"): r"must be > 0; got -1\.0",
}
_GRID = r"t must be a 1-D grid of at least two output times \(a span \(t0, t1\)\); got shape \(1,\)"
_OTHER = {
    ("free_rigid_body_splitting", "t", "shape"): _GRID,
    ("integrate", "t", "shape"): _GRID,
    ("integrate", "rhs", "bad0"): r"^rhs returned a non-finite value at t=0\.0: nan at index",
}
#: n counts steps (an integer, refused as such below); y0 is 1-D of any length
_SKIP = frozenset(
    {("time_grid", "n", "nan"), ("time_grid", "n", "str"), ("DOP853Stepper", "y0", "shape")}
)


@pytest.mark.parametrize(
    ("fname", "param", "value", "error", "condition"),
    list(cases("integrators", _CONDITIONS, skip=_SKIP, other=_OTHER)),
)
def test_every_parameter_of_every_function_is_named_with_the_condition_it_breaks(
    fname, param, value, error, condition
):
    kw = valid_kwargs("integrators", fname) | {param: value}
    check_refusal(getattr(integrators, fname), kw, param, error, condition)


@pytest.mark.parametrize("n", [math.nan, "1.0", 0])
def test_a_step_count_that_is_not_a_positive_integer_is_refused_naming_it(n):
    with pytest.raises(NonPositiveParameterError) as info:
        time_grid(0.0, 0.1, n)
    assert str(info.value) == f"n must be an integer ≥ 1; got {n!r}"


def test_the_step_budget_counts_the_whole_grid_not_its_first_interval():
    # t = [0, 1, 100] at h = 0.1: 1000 steps over the whole grid (10 in its first interval)
    with pytest.raises(StepSizeError) as info:
        integrators.integrate(
            lambda t, y: -y, [1.0], [0.0, 1.0, 100.0], method="rk4", h=0.1, max_steps=50
        )
    msg = str(info.value)
    assert msg.startswith("h = 0.1 over t = [0.0, 100.0] takes 1e+03 steps, more than "), msg
    assert "max_steps = 50" in msg, msg


#: a schedule's fractions, each a product of at most three triple-jump coefficients and
#: summed over up to 109 sub-flows: 2^7 eps
SCHEDULE_ATOL = 2**7 * EPS


@pytest.mark.parametrize("order", SPLITTING_ORDERS)
def test_each_splitting_order_is_yoshidas_triple_jump_of_strang(order):
    # Strang (5 sub-flows, head τ/2) composed p/2 − 1 times by Yoshida's triple jump
    # γ1 = 1/(2 − 2^(1/(q+1))), q = 2, 4, ..., order − 2: 3 copies, 2 merges at each joint
    sched = splitting._schedule(order)
    assert sched == splitting._SCHEDULES[order]  # the one the solver runs
    jumps = range(2, order, 2)
    assert len(sched) == 4 * 3 ** len(jumps) + 1
    head = 0.5 * math.prod(1.0 / (2.0 - 2.0 ** (1.0 / (q + 1))) for q in jumps)
    assert sched[0] == (0, pytest.approx(head, rel=SCHEDULE_ATOL))
    assert sched[-1] == sched[0]  # symmetric
    for axis in (0, 1, 2):  # consistent: each axis turns for the whole step
        total = math.fsum(c for a, c in sched if a == axis)
        assert abs(total - 1.0) <= SCHEDULE_ATOL


def test_the_package_modules_import_only_those_before_them_in_the_layout():
    # the order the package docstring's "Layout" states; a module may import only
    # modules listed before it (a back-arrow would be a cycle in waiting)
    import ast
    from pathlib import Path

    layout = ["_solution", "_events", "_grid", "_rhs", "_compiled", "_rk4", "_dop853", "_stepper"]
    layout += ["_integrate", "_rigid_body", "_splitting"]
    folder = Path(integrators.__file__).parent
    assert sorted(p.stem for p in folder.glob("_*.py") if p.stem != "__init__") == sorted(layout)
    back = []
    for pos, name in enumerate(layout):
        tree = ast.parse((folder / f"{name}.py").read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            is_sibling = isinstance(node, ast.ImportFrom) and node.level == 1
            if is_sibling and layout.index(node.module) >= pos:
                back.append(f"{name} imports {node.module}")
    assert not back, back
    assert "Imports point down that list" in integrators.__doc__


#: The splitting at another scale of J and L: ω = L/J rounds differently there, by an ulp
#: per sub-flow, over 10³ steps of a bounded rotation (measured 19 eps): 2^8 eps
SCALED_SPLITTING_RTOL = 2**8 * EPS


@pytest.mark.parametrize("compiled", [True, False])
@pytest.mark.parametrize("scale", [1e160, 1e-160, 1e300])
def test_the_splitting_keeps_an_angular_momentum_whose_squares_overflow(scale, compiled):
    """|L| = 1e160 has |L|² = inf: the projection measured |L| by a sum of squares and set
    L to 0 (norm0 / inf), silently; at 1e-160 the squares are subnormal and lost digits.
    J and L scaled together leave ω, and so the motion, unchanged."""
    want = free_rigid_body_splitting(J_TOP, J_TOP * W_TOP, np.eye(3), (0.0, 10.0), 0.01)
    got = free_rigid_body_splitting(
        J_TOP * scale, J_TOP * W_TOP * scale, np.eye(3), (0.0, 10.0), 0.01, compiled=compiled
    )
    L, R = rigid_body_parts(got.y[-1])
    L1, R1_ = rigid_body_parts(want.y[-1])
    np.testing.assert_allclose(L / scale, L1, rtol=0, atol=SCALED_SPLITTING_RTOL)
    np.testing.assert_allclose(R, R1_, rtol=0, atol=SCALED_SPLITTING_RTOL)


@pytest.mark.parametrize("compensated", [False, True])
@pytest.mark.parametrize("compiled", [False, True])
def test_a_splitting_turn_beyond_float64_is_the_librarys_overflow_error(compiled, compensated):
    """ω = L/J ~ 1e310 makes each turn's angle infinite: math.cos raised its own bare
    ValueError ("math domain error") on the one-body path; now the overflow is named
    with its interval, on every path (the compiled one hands a non-finite run over)."""
    J, L0 = [1e-300, 2e-300, 2.5e-300], [1e10, -1e10, 1e10]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", integrators.CompiledPathWarning)
        with pytest.raises(ResultOverflowError, match=r"between t=0\.0 and t=1\.0"):
            free_rigid_body_splitting(
                J, L0, np.eye(3), (0.0, 1.0), 0.1, compiled=compiled, compensated=compensated
            )


def test_the_dop853_tableau_is_scipys_read_without_importing_scipy_integrate():
    """``mechanics.integrators`` reads scipy's DOP853 tableau from its module's file, so
    that importing it does not import ``scipy.integrate`` (0.75 s of its 0.9 s import):
    a fresh interpreter has imported neither, and every array of the tableau is
    scipy's, bit for bit."""
    import subprocess
    import sys

    from scipy.integrate._ivp import dop853_coefficients as scipy_tableau

    from mechanics.integrators import _dop853

    code = (
        "import sys, mechanics.integrators; "
        "print(sorted(m for m in sys.modules if m.startswith('scipy.integrate')))"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert run.stdout.strip() == "[]"
    for name in ("A", "B", "C", "E3", "E5", "D"):
        assert np.array_equal(getattr(_dop853._d853, name), getattr(scipy_tableau, name)), name
    for name in ("N_STAGES", "N_STAGES_EXTENDED", "INTERPOLATOR_POWER"):
        assert getattr(_dop853._d853, name) == getattr(scipy_tableau, name), name


def test_the_dop853_tableau_is_imported_as_usual_where_its_file_is_not_found(monkeypatch):
    """Another layout of scipy (no file where it is looked for), or the module already
    imported: the tableau comes from ``import scipy.integrate._ivp``'s module."""
    import importlib.util
    import sys

    from scipy.integrate._ivp import dop853_coefficients as scipy_tableau

    from mechanics.integrators import _dop853

    assert _dop853._scipy_dop853_tableau() is scipy_tableau  # imported by now
    monkeypatch.delitem(sys.modules, _dop853._SCIPY_TABLEAU)
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None)
    imported = _dop853._scipy_dop853_tableau()  # imported again, as the package's own
    assert imported.__name__ == _dop853._SCIPY_TABLEAU
    assert sys.modules[_dop853._SCIPY_TABLEAU] is imported
    assert np.array_equal(imported.A, scipy_tableau.A)
