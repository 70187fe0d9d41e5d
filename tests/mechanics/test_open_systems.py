"""API, conventions, validation and edge cases of :mod:`mechanics.open_systems`.

Reference values come from the book (Examples 7.1–7.3), from hand computation
(stated beside each), and from limits of the closed forms.
"""

from __future__ import annotations

import math
import re
from fractions import Fraction

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from mechanics import open_systems as osys
from mechanics._floats import EPS
from mechanics.errors import (
    MechanicsValueError,
    NegativeMassError,
    NonFiniteError,
    NonPositiveParameterError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
    UnknownOptionError,
)

from ._naming import cases, check_refusal, valid_kwargs

#: scipy's quad asked for epsrel = 1e-13 (its own error estimate): 2^12 eps = 9e-13
QUAD_RTOL = 2**12 * EPS
#: a central difference with h = 1e-3 at t = 100 of a smooth rate: truncation
#: h² |f'''|/6 ~ 1e-10 relative, rounding eps/h ~ 2e-13; 2^27 eps = 3e-8
FD_RTOL = 2**27 * EPS
#: a few roundings of O(1) factors in the compared closed forms
FORM_RTOL = 8 * EPS

ROCKET = dict(m_0=1000.0, q=10.0, u=2000.0, m_f=800.0)


# ------------------------------------------------------------ momentum principle


def test_thrust_points_against_the_exhaust():
    assert_array_equal(osys.thrust(2.0, [0.0, 0.0, -3.0]), [-0.0, -0.0, 6.0])


def test_thrust_broadcasts_over_leading_axes():
    out = osys.thrust(np.array([1.0, 2.0]), np.array([[1.0, 0, 0], [0, 1.0, 0]]))
    assert_array_equal(out, [[-1.0, -0.0, -0.0], [-0.0, -2.0, -0.0]])


def test_momentum_rate_without_flows_is_the_force():
    assert_array_equal(osys.momentum_rate([1.0, 2.0, 3.0]), [1.0, 2.0, 3.0])


def test_momentum_rate_of_example_7_1_balances():
    rate = osys.momentum_rate(
        [-1.0, -1.0, 0.0], q_out=1.0, v_out=[-1.0, 0, 0], q_in=1.0, v_in=[0, 1.0, 0]
    )
    assert_array_equal(rate, [0.0, 0.0, 0.0])


def test_momentum_rate_sums_several_flows():
    # hand: F − (1·(1,0,0) + 2·(0,1,0)) + 3·(0,0,1) = (0 − 1, 0 − 2, 0 + 3)
    rate = osys.momentum_rate(
        [0.0, 0.0, 0.0],
        q_out=[1.0, 2.0],
        v_out=[[1.0, 0, 0], [0, 1.0, 0]],
        q_in=3.0,
        v_in=[0, 0, 1.0],
    )
    assert_array_equal(rate, [-1.0, -2.0, 3.0])


def test_momentum_rate_batched_matches_loop():
    rng = np.random.default_rng(1)
    F, q, v = rng.normal(size=(5, 3)), rng.uniform(0, 2, (5, 4)), rng.normal(size=(5, 4, 3))
    batched = osys.momentum_rate(F, q_out=q, v_out=v)
    for k in range(5):
        assert_allclose(
            batched[k], osys.momentum_rate(F[k], q_out=q[k], v_out=v[k]), rtol=0, atol=8 * EPS
        )


def test_mass_rate_is_in_minus_out():
    assert float(osys.mass_rate(q_out=[1.0, 0.5], q_in=[2.0, 0.25])) == 0.75
    assert float(osys.mass_rate()) == 0.0


def test_open_system_acceleration_is_galilean_invariant_in_relative_form():
    # (7.25) uses relative velocities only: the same u's give the same a_o in any frame
    a = osys.open_system_acceleration(2.0, [0, 0, -19.62], q_out=0.5, u_out=[0, 0, -100.0])
    assert_allclose(a, [0, 0, (0.5 * 100.0 - 19.62) / 2.0], rtol=FORM_RTOL)


def test_angular_momentum_rate_requires_the_point():
    with pytest.raises(TypeError):
        osys.angular_momentum_rate([0, 0, 0], q_in=1.0, r_in=[0, 1.0, 0], v_in=[1.0, 0, 0])


def test_angular_momentum_rate_of_example_7_3_is_minus_r_q_v():
    # bullets along +e_x on the line y = r, any x: −r q v e_z
    for x in (-5.0, 0.0, 3.0):
        out = osys.angular_momentum_rate(
            [0, 0, 0], about=[0, 0, 0], q_in=0.1, r_in=[x, 1.5, 0.0], v_in=[400.0, 0, 0]
        )
        assert_allclose(out, [0, 0, -60.0], rtol=FORM_RTOL, atol=0)


def test_angular_momentum_rate_about_a_point_on_the_line_is_the_moment():
    out = osys.angular_momentum_rate(
        [1.0, 2.0, 3.0], about=[7.0, 1.5, 0.0], q_in=0.1, r_in=[-2.0, 1.5, 0.0], v_in=[400.0, 0, 0]
    )
    assert_allclose(out, [1.0, 2.0, 3.0], rtol=0, atol=64 * EPS)


@pytest.mark.parametrize(
    ("kwargs", "error"),
    [
        (dict(q_out=-1.0, v_out=[1.0, 0, 0]), NegativeMassError),
        (dict(q_out=1.0), ShapeError),
        (dict(q_in=1.0, v_in=[1.0, 0]), ShapeError),
        (dict(q_in=[1.0, 2.0, 3.0], v_in=[[1.0, 0, 0], [0, 1.0, 0]]), ShapeError),
        (dict(q_in=math.nan, v_in=[1.0, 0, 0]), NonFiniteError),
    ],
)
def test_momentum_rate_rejects_bad_flows(kwargs, error):
    with pytest.raises(error):
        osys.momentum_rate([0.0, 0.0, 0.0], **kwargs)


def test_errors_name_the_value():
    with pytest.raises(NegativeMassError, match=r"q_out must be ≥ 0.*-2\.5"):
        osys.momentum_rate([0, 0, 0], q_out=-2.5, v_out=[1.0, 0, 0])


# -------------------------------------------------------------------- the rocket


def test_rocket_velocity_without_gravity_is_u_ln_mass_ratio():
    v = osys.rocket_velocity(50.0, m_0=1000.0, q=10.0, u=3000.0, m_f=800.0, g=0.0)
    assert_allclose(v, 3000.0 * math.log(2.0), rtol=FORM_RTOL)


def test_rocket_velocity_with_gravity_matches_7_30():
    t = np.array([0.0, 10.0, 79.0])
    v = osys.rocket_velocity(t, g=9.81, **ROCKET)
    expect = -9.81 * t + 2000.0 * np.log(1000.0 / (1000.0 - 10.0 * t))
    assert_allclose(v, expect, rtol=64 * EPS, atol=0)


def test_rocket_velocity_at_t0_is_zero_and_mass_is_m0():
    assert float(osys.rocket_velocity(0.0, g=9.81, **ROCKET)) == 0.0
    assert float(osys.rocket_height(0.0, g=9.81, **ROCKET)) == 0.0
    assert float(osys.rocket_mass(0.0, m_0=1000.0, q=10.0, m_f=800.0)) == 1000.0


def test_rocket_velocity_keeps_digits_at_mass_ratio_near_one():
    # −log(1 − x) = x + x²/2 + …; at x = 1e-15 the naive log(m_0/m) returns 1.11e-15
    v = osys.rocket_velocity(1e-15, m_0=1.0, q=1.0, u=1.0, m_f=0.5, g=0.0)
    assert_allclose(v, 1e-15 + 0.5e-30, rtol=2 * EPS)


def test_rocket_height_series_and_direct_forms_join_continuously():
    # x = 2/3 is the switch from the series in s to the direct form
    x = np.array([2 / 3 * (1 - 4 * EPS), 2 / 3, 2 / 3 * (1 + 4 * EPS)])
    z = osys.rocket_height(x, m_0=1.0, q=1.0, u=1.0, m_f=0.9, g=0.0)
    assert np.all(np.abs(np.diff(z)) < 16 * EPS)
    assert np.all(np.diff(z) >= -2 * EPS)


def test_rocket_height_is_the_integral_of_the_velocity():
    from scipy.integrate import quad

    kw = dict(g=9.81, **ROCKET)
    for t in (0.5, 30.0, 79.9):
        integral = quad(
            lambda s: float(osys.rocket_velocity(s, **kw)), 0.0, t, epsabs=0, epsrel=1e-13
        )[0]
        assert_allclose(osys.rocket_height(t, **kw), integral, rtol=QUAD_RTOL)


def test_lift_off_threshold():
    # q u = 2e4 N; m_0 g = 2e4 N exactly at g = 20: lifts off (v ≥ 0 after)
    v = osys.rocket_velocity([0.0, 1.0, 50.0], g=20.0, **ROCKET)
    assert np.all(v >= 0)
    with pytest.raises(OutOfDomainError, match=r"no lift-off.*q u = 20000.0.*m_0 g = 20010.0"):
        osys.rocket_velocity(1.0, g=20.01, **ROCKET)
    with pytest.raises(OutOfDomainError, match="no lift-off"):
        osys.rocket_height(1.0, g=20.01, **ROCKET)


def test_burn_out_raises_by_default():
    assert float(osys.burn_out_time(m_f=800.0, q=10.0)) == 80.0
    for f in (osys.rocket_velocity, osys.rocket_height):
        with pytest.raises(OutOfDomainError, match=r"beyond burn-out T = m_f/q = 80.0"):
            f(80.5, g=9.81, **ROCKET)
    with pytest.raises(OutOfDomainError, match="beyond burn-out"):
        osys.rocket_mass(80.5, m_0=1000.0, q=10.0, m_f=800.0)
    # T itself is allowed
    osys.rocket_velocity(80.0, g=9.81, **ROCKET)


def test_coasting_after_burn_out_is_ballistic():
    kw = dict(g=9.81, after_burn_out="coast", **ROCKET)
    vT = float(osys.rocket_velocity(80.0, **kw))
    zT = float(osys.rocket_height(80.0, **kw))
    assert_allclose(osys.rocket_velocity(100.0, **kw), vT - 9.81 * 20.0, rtol=FORM_RTOL)
    assert_allclose(
        osys.rocket_height(100.0, **kw), zT + vT * 20.0 - 0.5 * 9.81 * 400.0, rtol=FORM_RTOL
    )
    assert (
        float(osys.rocket_mass(100.0, m_0=1000.0, q=10.0, m_f=800.0, after_burn_out="coast"))
        == 200.0
    )


def test_coasting_without_gravity_keeps_the_burn_out_velocity():
    kw = dict(g=0.0, after_burn_out="coast", **ROCKET)
    assert float(osys.rocket_velocity(1e6, **kw)) == float(osys.rocket_velocity(80.0, **kw))


@pytest.mark.parametrize(
    ("kwargs", "error"),
    [
        (dict(t=-1.0), OutOfDomainError),
        (dict(m_0=0.0), NonPositiveParameterError),
        (dict(q=-1.0), NonPositiveParameterError),
        (dict(u=0.0), NonPositiveParameterError),
        (dict(m_f=1000.0), OutOfDomainError),
        (dict(m_f=-1.0), NegativeMassError),
        (dict(g=-9.81), OutOfDomainError),
        (dict(g=math.inf), NonFiniteError),
        (dict(t=math.nan), NonFiniteError),
        (dict(after_burn_out="stop"), UnknownOptionError),
    ],
)
def test_rocket_rejects_bad_input(kwargs, error):
    args = dict(t=1.0, g=9.81, **ROCKET)
    args.update(kwargs)
    t = args.pop("t")
    with pytest.raises(error):
        osys.rocket_velocity(t, **args)
    with pytest.raises(error):
        osys.rocket_height(t, **args)


def test_rocket_requires_gravity_and_fuel_explicitly():
    with pytest.raises(TypeError):
        osys.rocket_velocity(1.0, m_0=1.0, q=1.0, u=1.0, m_f=0.5)  # no g
    with pytest.raises(TypeError):
        osys.rocket_velocity(1.0, m_0=1.0, q=1.0, u=1.0, g=0.0)  # no m_f


def test_rocket_vectorises_over_parameters():
    q = np.array([5.0, 10.0, 20.0])
    v = osys.rocket_velocity(1.0, m_0=1000.0, q=q, u=2000.0, m_f=800.0, g=9.81)
    for k in range(3):
        assert float(v[k]) == float(
            osys.rocket_velocity(1.0, m_0=1000.0, q=q[k], u=2000.0, m_f=800.0, g=9.81)
        )


def test_all_errors_are_value_errors():
    with pytest.raises(ValueError):  # noqa: PT011 - the point is the base class
        osys.rocket_velocity(-1.0, g=0.0, **ROCKET)
    assert issubclass(OutOfDomainError, MechanicsValueError)


# ------------------------------------------------------------ jets, bends, chains


def test_jet_velocity_limits():
    kw = dict(m=2e4, q=150.0, w=700.0)
    assert float(osys.jet_velocity(0.0, v_0=60.0, **kw)) == 60.0
    assert_allclose(osys.jet_velocity(1e7, v_0=60.0, **kw), 700.0, rtol=FORM_RTOL)
    assert float(osys.jet_velocity(5.0, v_0=700.0, **kw)) == pytest.approx(700.0, rel=FORM_RTOL)


def test_jet_velocity_small_time_is_linear():
    # v ≈ v_0 + (q/m)(w − v_0) t for tiny t: expm1 keeps it
    v = osys.jet_velocity(1e-12, m=1.0, q=1.0, w=1.0, v_0=0.0)
    assert_allclose(v, 1e-12 - 0.5e-24, rtol=2 * EPS)


@pytest.mark.parametrize("angle", [0.0, 1e-9, np.pi / 3, np.pi / 2, 2.0, np.pi])
def test_pipe_bend_force_is_q_times_velocity_change(angle):
    F = osys.pipe_bend_force(2.0, 3.0, angle)
    v_in, v_out = np.array([3.0, 0, 0]), 3.0 * np.array([np.cos(angle), np.sin(angle), 0])
    assert_allclose(F, 2.0 * (v_out - v_in), rtol=0, atol=32 * EPS)
    assert_allclose(
        np.linalg.norm(F),
        osys.pipe_bend_force_magnitude(2.0, 3.0, angle),
        rtol=4 * EPS,
        atol=1e-300,
    )


def test_pipe_bend_force_small_angle_has_no_cancellation():
    F = osys.pipe_bend_force(1.0, 1.0, 1e-9)
    assert_allclose(F[0], -0.5e-18, rtol=4 * EPS)  # cos α − 1 = −α²/2


def test_pipe_bend_of_example_7_1():
    F = osys.pipe_bend_force(1.0, 1.0, np.pi / 2)
    assert_allclose(
        [-F[1], F[0]], [-1.0, -1.0], rtol=FORM_RTOL
    )  # book basis: e_1 = e_y, e_2 = −e_x
    assert_allclose(
        osys.pipe_bend_force_magnitude(1.0, 1.0, np.pi / 2), math.sqrt(2), rtol=FORM_RTOL
    )


def test_falling_chain_force_and_domain():
    assert float(osys.falling_chain_table_force(0.0, lam=1.0, h=0.5, g=10.0, ell=1.0)) == 10.0
    assert float(osys.falling_chain_table_force(1.0, lam=1.0, h=0.0, g=10.0, ell=1.0)) == 30.0
    with pytest.raises(OutOfDomainError):
        osys.falling_chain_table_force(1.5, lam=1.0, h=0.0, g=10.0, ell=1.0)
    with pytest.raises(OutOfDomainError):
        osys.falling_chain_table_force(0.5, lam=1.0, h=-0.1, g=10.0, ell=1.0)


# ------------------------------------------------------------------- rotating


CAROUSEL = dict(J_0=500.0, q=0.1, v=400.0, r=1.5, R=2.0)


def test_carousel_starts_at_rest_and_tends_to_the_limit():
    assert float(osys.carousel_angular_velocity(0.0, **CAROUSEL)) == 0.0
    lim = osys.carousel_limit_angular_velocity(v=400.0, r=1.5, R=2.0)
    assert float(lim) == -150.0
    w = osys.carousel_angular_velocity(np.array([1e3, 1e6, 1e9]), **CAROUSEL)
    assert np.all(np.diff(w) < 0)
    assert np.all(w > lim)


@pytest.mark.parametrize("scale", [2.0**-530, 2.0**-1000, 2.0**500, 1.0])
def test_carousel_limit_keeps_its_accuracy_for_a_tiny_or_huge_carousel(scale):
    # −r v/R² for r, R → s r, s R is (−r v/R²)/s; R² would underflow below R ≈ 1e-154
    # (to a subnormal, losing digits, or to 0): the limit must stay within two roundings
    # (r/R, then /R) of the exact Fraction, at every scale a power of two (exact)
    r, R, v = 0.7 * scale, 1.1 * scale, 400.0  # R² with all 53 bits set in its mantissa
    exact = -Fraction(r) * Fraction(v) / Fraction(R) ** 2
    got = float(osys.carousel_limit_angular_velocity(v=v, r=r, R=R))
    assert abs(Fraction(got) - exact) <= 2 * Fraction(EPS) * abs(exact)


def test_carousel_angular_acceleration_is_the_derivative():
    t, h = 100.0, 1e-3
    fd = (
        osys.carousel_angular_velocity(t + h, **CAROUSEL)
        - osys.carousel_angular_velocity(t - h, **CAROUSEL)
    ) / (2 * h)
    assert_allclose(osys.carousel_angular_acceleration(t, **CAROUSEL), fd, rtol=FD_RTOL)


def test_carousel_initial_spin_at_the_limit_stays():
    lim = float(osys.carousel_limit_angular_velocity(v=400.0, r=1.5, R=2.0))
    w = osys.carousel_angular_velocity(np.array([0.0, 10.0, 1e4]), phidot_0=lim, **CAROUSEL)
    assert_allclose(w, lim, rtol=FORM_RTOL)


def test_carousel_rejects_missing_bullets_and_negative_time():
    with pytest.raises(OutOfDomainError, match="miss"):
        osys.carousel_angular_velocity(1.0, **{**CAROUSEL, "r": 2.5})
    with pytest.raises(OutOfDomainError):
        osys.carousel_angular_velocity(-1.0, **CAROUSEL)
    with pytest.raises(NegativeMassError):
        osys.carousel_angular_velocity(1.0, **{**CAROUSEL, "q": -0.1})


def test_rim_rockets_round_trip_and_domain():
    kw = dict(J_0=1e6, q=2.0, u=3000.0, r=50.0)
    t = osys.rim_rocket_spin_up_time(np.array([1e-9, 0.2, 5.0]), **kw)
    assert_allclose(osys.rim_rocket_angular_velocity(t, **kw), [1e-9, 0.2, 5.0], rtol=4 * EPS)
    with pytest.raises(OutOfDomainError):
        osys.rim_rocket_angular_velocity(1e6 / (2.0 * 2500.0), **kw)  # all inertia expelled
    with pytest.raises(OutOfDomainError):
        osys.rim_rocket_spin_up_time(-0.1, **kw)


# ------------------------------------------- every parameter named, every overflow named
_POS = r"must be > 0; got (0\.0|-1\.0)"
_NONNEG = r"must be ≥ 0 \(mass flows are non-negative\); got -1\.0"
_M_F = r"m_f must be ≥ 0 .*got -1\.0|m_f must be < m_0 .*got m_f = 20\.0 with m_0 = 10\.0"
#: the condition an unphysical value of each fuzz entry violates (tests.fuzz.entries)
_CONDITIONS = {
    ("angular_momentum_rate", "q_out"): _NONNEG,
    ("burn_out_time", "m_f"): _NONNEG,
    ("burn_out_time", "q"): _POS,
    ("carousel_angular_acceleration", "J_0"): _POS,
    ("carousel_angular_acceleration", "q"): _NONNEG,
    ("carousel_angular_acceleration", "R"): _POS,
    ("carousel_angular_velocity", "J_0"): _POS,
    ("carousel_angular_velocity", "q"): _NONNEG,
    ("carousel_angular_velocity", "R"): _POS,
    ("carousel_limit_angular_velocity", "R"): _POS,
    ("falling_chain_table_force", "lam"): _POS,
    ("falling_chain_table_force", "ell"): _POS,
    ("falling_chain_table_force", "x"): r"x must lie in \[0, ell\]; got (-0\.1|2\.0)",
    ("jet_velocity", "m"): _POS,
    ("jet_velocity", "q"): _POS,
    ("mass_rate", "q_out"): _NONNEG,
    ("mass_rate", "q_in"): _NONNEG,
    ("momentum_rate", "q_out"): _NONNEG,
    ("open_system_acceleration", "m"): _POS,
    ("open_system_acceleration", "q_out"): _NONNEG,
    ("pipe_bend_force", "q"): _NONNEG,
    ("pipe_bend_force_magnitude", "q"): _NONNEG,
    ("rim_rocket_angular_velocity", "J_0"): _POS,
    ("rim_rocket_angular_velocity", "q"): _POS,
    ("rim_rocket_angular_velocity", "r"): _POS,
    ("rim_rocket_spin_up_time", "J_0"): _POS,
    ("rim_rocket_spin_up_time", "q"): _POS,
    ("rim_rocket_spin_up_time", "r"): _POS,
    ("rocket_height", "m_0"): _POS,
    ("rocket_height", "q"): _POS,
    ("rocket_height", "m_f"): _M_F,
    ("rocket_height", "t"): r"t must be ≥ 0 \(the burn starts at t = 0\); got -1\.0",
    ("rocket_velocity", "m_0"): _POS,
    ("rocket_velocity", "q"): _POS,
    ("rocket_velocity", "m_f"): _M_F,
    ("rocket_velocity", "t"): r"t must be ≥ 0 \(the burn starts at t = 0\); got -1\.0",
    ("rocket_mass", "m_0"): _POS,
    ("rocket_mass", "q"): _POS,
    ("rocket_mass", "m_f"): _M_F,
    ("thrust", "q"): _NONNEG,
}


@pytest.mark.parametrize(
    ("fname", "param", "value", "error", "condition"), list(cases("open_systems", _CONDITIONS))
)
def test_every_parameter_of_every_function_is_named_with_the_condition_it_breaks(
    fname, param, value, error, condition
):
    kw = valid_kwargs("open_systems", fname) | {param: value}
    check_refusal(getattr(osys, fname), kw, param, error, condition)


_V3 = [0.3, -0.2, 0.5]
_RIM = {"J_0": 2.0, "q": 0.1, "u": 50.0, "r": 0.5}
_CAR = {"J_0": 10.0, "q": 0.5, "v": 2.0, "r": 0.5, "R": 1.0}
_ROCK = {"m_0": 10.0, "q": 1.0, "u": 100.0, "m_f": 4.0, "g": 9.81}


@pytest.mark.parametrize(
    ("fname", "kwargs", "param", "error", "condition"),
    [
        # the inflows, which the fuzz entries leave out: each named, not its outflow twin
        (
            "momentum_rate",
            {"F_e": _V3, "q_in": -1.0, "v_in": _V3},
            "q_in",
            NegativeMassError,
            _NONNEG,
        ),
        (
            "momentum_rate",
            {"F_e": _V3, "q_in": 1.0, "v_in": [0, np.nan, 0]},
            "v_in",
            NonFiniteError,
            "must be finite",
        ),
        (
            "momentum_rate",
            {"F_e": _V3, "q_in": 1.0, "v_in": [0, 1.0]},
            "v_in",
            ShapeError,
            r"has shape \(2,\)",
        ),
        (
            "momentum_rate",
            {"F_e": _V3, "q_in": 1.0},
            "v_in",
            ShapeError,
            r"q_in and v_in must be given together",
        ),
        (
            "momentum_rate",
            {"F_e": _V3, "v_out": _V3},
            "q_out",
            ShapeError,
            r"q_out and v_out must be given together",
        ),
        (
            "momentum_rate",
            {"F_e": _V3, "q_in": [1.0, 2.0], "v_in": [_V3] * 3},
            "v_in",
            ShapeError,
            r"q_in has shape \(2,\) and v_in \(3, 3\); expected \(\.\.\., n\) and \(\.\.\., n, 3\)",
        ),
        (
            "open_system_acceleration",
            {"m": 1.0, "F_e": _V3, "q_in": 1.0, "u_in": [np.inf, 0, 0]},
            "u_in",
            NonFiniteError,
            "must be finite",
        ),
        (
            "open_system_acceleration",
            {"m": 1.0, "F_e": _V3, "q_in": -1.0, "u_in": _V3},
            "q_in",
            NegativeMassError,
            _NONNEG,
        ),
        (
            "open_system_acceleration",
            {"m": 1.0, "F_e": _V3, "u_in": _V3},
            "q_in",
            ShapeError,
            r"q_in and u_in must be given together",
        ),
        (
            "open_system_acceleration",
            {"m": 1.0, "F_e": _V3, "q_out": 1.0},
            "u_out",
            ShapeError,
            r"q_out and u_out must be given together",
        ),
        (
            "angular_momentum_rate",
            {"M_e": _V3, "about": _V3, "q_in": 1.0, "r_in": [np.nan, 0, 0], "v_in": _V3},
            "r_in",
            NonFiniteError,
            "must be finite",
        ),
        (
            "angular_momentum_rate",
            {"M_e": _V3, "about": _V3, "q_in": 1.0, "r_in": _V3, "v_in": [np.nan, 0, 0]},
            "v_in",
            NonFiniteError,
            "must be finite",
        ),
        (
            "angular_momentum_rate",
            {"M_e": _V3, "about": _V3, "q_in": -1.0, "r_in": _V3, "v_in": _V3},
            "q_in",
            NegativeMassError,
            _NONNEG,
        ),
        (
            "angular_momentum_rate",
            {"M_e": _V3, "about": _V3, "q_in": 1.0, "v_in": _V3},
            "r_in",
            ShapeError,
            r"q_in, r_in, v_in must be given together",
        ),
        (
            "angular_momentum_rate",
            {"M_e": _V3, "about": _V3, "q_out": 1.0, "r_out": _V3},
            "v_out",
            ShapeError,
            r"q_out, r_out, v_out must be given together",
        ),
        ("mass_rate", {"q_in": [1.0, -2.0]}, "q_in", NegativeMassError, r"got -2\.0"),
        # the value a domain message reports is the first offending one, not the first entry
        (
            "jet_velocity",
            {"t": [0.0, -2.0], "m": 10.0, "q": 1.0, "w": 3.0, "v_0": 0.0},
            "t",
            OutOfDomainError,
            r"t must be ≥ 0; got -2\.0",
        ),
        (
            "jet_velocity",
            {"t": 1.0, "m": 10.0, "q": 1.0, "w": 0.0, "v_0": 0.0},
            "w",
            NonPositiveParameterError,
            _POS,
        ),
        (
            "falling_chain_table_force",
            {"x": 0.3, "lam": 0.2, "h": [0.5, -2.0], "g": 9.81, "ell": 1.0},
            "h",
            OutOfDomainError,
            r"h must be ≥ 0; got -2\.0",
        ),
        (
            "falling_chain_table_force",
            {"x": [0.5, -0.1], "lam": 0.2, "h": 0.0, "g": 9.81, "ell": 1.0},
            "x",
            OutOfDomainError,
            r"got -0\.1",
        ),
        (
            "falling_chain_table_force",
            {"x": 0.3, "lam": 0.2, "h": 0.0, "g": 0.0, "ell": 1.0},
            "g",
            NonPositiveParameterError,
            _POS,
        ),
        (
            "carousel_angular_velocity",
            {"t": [0.0, -1.0], **_CAR},
            "t",
            OutOfDomainError,
            r"t must be ≥ 0 \(shooting starts at t = 0\); got -1\.0",
        ),
        (
            "carousel_angular_acceleration",
            {"t": [0.0, -1.0], **_CAR},
            "t",
            OutOfDomainError,
            r"t must be ≥ 0 \(shooting starts at t = 0\); got -1\.0",
        ),
        (
            "carousel_angular_velocity",
            {"t": 1.0, **_CAR, "phidot_0": np.nan},
            "phidot_0",
            NonFiniteError,
            "must be finite",
        ),
        (
            "carousel_angular_acceleration",
            {"t": 1.0, **_CAR, "phidot_0": np.nan},
            "phidot_0",
            NonFiniteError,
            "must be finite",
        ),
        (
            "carousel_angular_velocity",
            {"t": 1.0, **_CAR | {"r": -1.5}},
            "r",
            OutOfDomainError,
            r"^the bullets miss: \|r\| must be ≤ R$",
        ),
        (
            "carousel_limit_angular_velocity",
            {"v": 2.0, "r": 1.5, "R": 1.0},
            "r",
            OutOfDomainError,
            r"^the bullets miss: \|r\| must be ≤ R$",
        ),
        (
            "rim_rocket_angular_velocity",
            {"t": [0.0, -1.0], **_RIM},
            "t",
            OutOfDomainError,
            r"t must be ≥ 0; got -1\.0",
        ),
        (
            "rim_rocket_angular_velocity",
            {"t": 1.0, **_RIM | {"u": 0.0}},
            "u",
            NonPositiveParameterError,
            _POS,
        ),
        # q r² t = J_0 exactly (0.5 · 2² · 1 = 2): the wheel has no inertia left
        (
            "rim_rocket_angular_velocity",
            {"t": 1.0, **_RIM | {"q": 0.5, "r": 2.0}},
            "J_0",
            OutOfDomainError,
            r"q r² t must be < J_0",
        ),
        (
            "rim_rocket_spin_up_time",
            {"omega": [0.0, -1.0], **_RIM},
            "omega",
            OutOfDomainError,
            r"omega must be ≥ 0 \(the rockets push forward\); got -1\.0",
        ),
        (
            "rim_rocket_spin_up_time",
            {"omega": 1.0, **_RIM | {"u": 0.0}},
            "u",
            NonPositiveParameterError,
            _POS,
        ),
        (
            "rocket_velocity",
            {"t": 1.0, **_ROCK | {"g": -1.0}},
            "g",
            OutOfDomainError,
            r"g is the magnitude of gravity .* must be ≥ 0; got -1\.0",
        ),
        ("rocket_velocity", {"t": 1.0, **_ROCK | {"u": 0.0}}, "u", NonPositiveParameterError, _POS),
        (
            "rocket_height",
            {"t": 1.0, **_ROCK | {"u": 50.0, "g": 100.0}},
            "u",
            OutOfDomainError,
            r"no lift-off: the thrust q u = 50\.0 is less than the weight m_0 g = 1000\.0",
        ),
        (
            "rocket_mass",
            {"t": [1.0, 5.0], "m_0": 10.0, "q": 1.0, "m_f": 4.0},
            "t",
            OutOfDomainError,
            r"t = 5\.0 is beyond burn-out T = m_f/q = 4\.0; pass after_burn_out='coast'",
        ),
    ],
)
def test_each_domain_message_names_the_parameter_the_condition_and_the_offending_value(
    fname, kwargs, param, error, condition
):
    check_refusal(getattr(osys, fname), kwargs, param, error, condition)


@pytest.mark.parametrize(
    ("fname", "kwargs"),
    [
        ("thrust", {"q": 1e300, "u_rel": [1e300, 0, 0]}),
        ("momentum_rate", {"F_e": _V3, "q_out": 1e300, "v_out": [1e300, 0, 0]}),
        ("mass_rate", {"q_out": [1e308, 1e308]}),
        ("open_system_acceleration", {"m": 1e-300, "F_e": [1e300, 0, 0]}),
        (
            "angular_momentum_rate",
            {"M_e": _V3, "about": _V3, "q_in": 1e300, "r_in": [0, 1e300, 0], "v_in": [1e300, 0, 0]},
        ),
        ("burn_out_time", {"m_f": 1e300, "q": 1e-300}),
        ("pipe_bend_force", {"q": 1e300, "v": 1e300, "angle": 1.0}),
        ("pipe_bend_force_magnitude", {"q": 1e300, "v": 1e300, "angle": 1.0}),
        ("falling_chain_table_force", {"x": 0.3, "lam": 1e300, "h": 0.0, "g": 1e300, "ell": 1.0}),
        ("carousel_limit_angular_velocity", {"v": 1e300, "r": 1e-10, "R": 1e-10}),
    ],
)
def test_a_result_beyond_float64_is_an_overflow_error_naming_the_function(fname, kwargs):
    with pytest.raises(ResultOverflowError, match=rf"^{fname}: .*float64"):
        getattr(osys, fname)(**kwargs)


@pytest.mark.parametrize(
    ("q", "u", "m_0", "g", "grounded"),
    [
        # q u = 1e309 < m_0 g = 1.1e309: both overflowed to inf, inf < inf was False and the
        # grounded rocket flew (v = -4.6e6 returned)
        (1e300, 1e9, 1e300, 1.1e9, True),
        (1e300, 1.1e9, 1e300, 1e9, False),
        # q u = 1e-400 < m_0 g = 1.1e-400: both underflowed to 0
        (1e-200, 1e-200, 1e-300, 1.1e-100, True),
        (1e-200, 1.1e-200, 1e-300, 1e-100, False),
    ],
)
def test_lift_off_is_decided_beyond_float64s_range(q, u, m_0, g, grounded):
    """q u ≥ m_0 g decided on the products as they are, not as they round: the message
    shows the factors where a product is no float (the hunt, 29 Nov 2026)."""
    kw = {"m_0": m_0, "q": q, "u": u, "m_f": 0.5 * m_0, "g": g}
    t = 0.25 * m_0 / q  # a quarter of the fuel burnt
    if grounded:
        want = re.escape(f"the thrust q u = {q!r} * {u!r} is less than the weight m_0 g = ")
        with pytest.raises(OutOfDomainError, match=f"^no lift-off: {want}"):
            osys.rocket_velocity(t, **kw)
    else:  # lifts off: v = u L(1/4) − g t > 0 (its accuracy: tests/stability)
        assert float(osys.rocket_velocity(t, **kw)) > 0
