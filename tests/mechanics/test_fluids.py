"""mechanics.fluids: API, accuracy of the difference stencils, validation."""

from __future__ import annotations

import re

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from mechanics import fluids
from mechanics.errors import (
    NonFiniteError,
    NonPositiveParameterError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
    StepSizeError,
)
from mechanics.rotation import EPS

from ._naming import FIELD_NONFINITE, cases, check_refusal, valid_kwargs, word

#: The fourth-order stencil is exact for cubic fields; what is left is rounding,
#: about 1.5 eps |f| / h per derivative with h = H_REL (1 + |r|): for |f| ~ 10 and
#: h ~ 7e-4 that is ~2e4 eps.  2^16 eps leaves a factor three.
STENCIL_ATOL = 2**16 * EPS
#: closed forms evaluated in float64 (a square root, a few products).
CLOSED_RTOL = 8 * EPS


def cubic_field(r, t=0.0):
    x, y, z = np.moveaxis(r, -1, 0)
    return np.stack([x**3 - y * z + t * x, x * y**2 + z, z**2 * x - 2 * t * y], axis=-1)


def cubic_gradient(r, t=0.0):
    x, y, z = np.moveaxis(r, -1, 0)
    one, zero = np.ones_like(x), np.zeros_like(x)
    return (
        np.stack(
            [
                np.stack([3 * x**2 + t, -z, -y], axis=-1),
                np.stack([y**2, 2 * x * y, one], axis=-1),
                np.stack([z**2, -2 * t * one, 2 * z * x], axis=-1),
            ],
            axis=-2,
        )
        + 0 * zero[..., None, None]
    )


def test_velocity_gradient_is_exact_for_cubic_fields_up_to_rounding():
    r = np.array([[0.3, -1.2, 0.7], [1.5, 0.2, -0.4], [0.0, 0.0, 0.0]])
    G = fluids.velocity_gradient(cubic_field, r, 0.5)
    assert G.shape == (3, 3, 3)
    np.testing.assert_allclose(G, cubic_gradient(r, 0.5), rtol=0, atol=STENCIL_ATOL)


def test_divergence_and_curl_read_the_gradient():
    r = np.array([0.3, -1.2, 0.7])
    G = cubic_gradient(r, 0.5)
    assert fluids.divergence(cubic_field, r, 0.5) == pytest.approx(np.trace(G), abs=STENCIL_ATOL)
    expected = [G[2, 1] - G[1, 2], G[0, 2] - G[2, 0], G[1, 0] - G[0, 1]]
    np.testing.assert_allclose(
        fluids.curl(cubic_field, r, 0.5), expected, rtol=0, atol=STENCIL_ATOL
    )


def test_gradient_and_time_derivative_of_a_scalar_field():
    def f(r, t):
        return r[..., 0] * r[..., 1] ** 2 + t**3 * r[..., 2]

    r = np.array([1.0, 2.0, -1.0])
    np.testing.assert_allclose(
        fluids.gradient(f, r, 2.0), [4.0, 4.0, 8.0], rtol=0, atol=STENCIL_ATOL
    )
    assert fluids.partial_time_derivative(f, r, 2.0) == pytest.approx(-12.0, abs=STENCIL_ATOL)


def test_material_derivative_of_a_vector_field_is_the_particle_acceleration():
    # rigid rotation about e_z: the acceleration is centripetal, −ω² (x, y, 0)
    w = 1.7
    v = fluids.rigid_velocity_field([0.0, 0.0, 0.0], [0.0, 0.0, w])
    r = np.array([[0.4, -0.9, 2.0]])
    acc = fluids.material_derivative(v, v, r, 0.0)
    np.testing.assert_allclose(acc, [[-(w**2) * 0.4, w**2 * 0.9, 0.0]], rtol=0, atol=STENCIL_ATOL)


def test_a_user_step_is_used():
    G = fluids.velocity_gradient(cubic_field, [0.3, 0.2, 0.1], 0.0, h=1e-2)
    np.testing.assert_allclose(G, cubic_gradient(np.array([0.3, 0.2, 0.1])), atol=STENCIL_ATOL)


def test_tank_level_matches_an_integration_of_the_outflow():
    g, a, h0 = 9.81, 0.05, 2.0

    def rhs(_t, hh):
        return [-a * fluids.torricelli_speed(max(hh[0], 0.0), g=g, area_ratio=a)]

    T = float(fluids.drain_time(h0, g=g, area_ratio=a))
    ts = np.linspace(0.0, 0.9 * T, 10)
    sol = solve_ivp(rhs, (0.0, ts[-1]), [h0], method="DOP853", t_eval=ts, rtol=1e-12, atol=1e-14)
    # DOP853 at rtol 1e-12 over ~10 steps: its own error dominates (≤ 1e-12 h0)
    np.testing.assert_allclose(
        fluids.tank_level(ts, h_0=h0, g=g, area_ratio=a), sol.y[0], rtol=0, atol=2**13 * EPS * h0
    )
    assert fluids.tank_level(2 * T, h_0=h0, g=g, area_ratio=a) == 0.0


def test_torricelli_with_a_moving_surface_satisfies_bernoulli_and_continuity():
    g, h, a = 9.81, 3.0, 0.3
    u = float(fluids.torricelli_speed(h, g=g, area_ratio=a))
    B = fluids.bernoulli_constant(
        [[0.0, 0.0, -a * u], [0.0, 0.0, -u]], [1e5, 1e5], [0.0, -h], rho_0=1.0, g=g
    )
    assert B[0] == pytest.approx(B[1], rel=CLOSED_RTOL)


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        (lambda: fluids.divergence(cubic_field, [0.0, np.nan, 0.0]), NonFiniteError, "r must be"),
        (lambda: fluids.divergence(cubic_field, [0.0, 1.0]), ShapeError, r"\(\.\.\., 3\)"),
        (lambda: fluids.curl(lambda r, t: r[..., 0], [0.0, 1.0, 2.0]), ShapeError, "vector field"),
        (
            lambda: fluids.curl(lambda r, t: r * np.nan, [0.0, 1.0, 2.0]),
            NonFiniteError,
            "v\\(r, t\\)",
        ),
        (lambda: fluids.curl(cubic_field, [0.0, 1.0, 2.0], h=0.0), NonPositiveParameterError, "h"),
        (lambda: fluids.torricelli_speed(-1.0, g=9.8), OutOfDomainError, "depth"),
        (lambda: fluids.torricelli_speed(1.0, g=0.0), NonPositiveParameterError, "g must"),
        (
            lambda: fluids.torricelli_speed(1.0, g=9.8, area_ratio=1.0),
            OutOfDomainError,
            "area_ratio",
        ),
        (lambda: fluids.drain_time(1.0, g=9.8, area_ratio=0.0), OutOfDomainError, "never drains"),
        (
            lambda: fluids.tank_level(-1.0, h_0=1.0, g=9.8, area_ratio=0.1),
            OutOfDomainError,
            "t = 0",
        ),
        (
            lambda: fluids.bernoulli_constant([0, 0, 1], 1.0, 0.0, rho_0=-1.0, g=9.8),
            NonPositiveParameterError,
            "rho_0",
        ),
        (
            lambda: fluids.euler_residual(
                cubic_field, lambda r, t: r[..., 0], [0, 0, 0], rho=0, g=1
            ),
            NonPositiveParameterError,
            "rho",
        ),
        (
            lambda: fluids.streamline(cubic_field, [0, 0, 0], [1.0, 0.5]),
            OutOfDomainError,
            "increasing",
        ),
        (lambda: fluids.streamline(cubic_field, [[0, 0, 0]], [0.0, 1.0]), ShapeError, "one point"),
        (lambda: fluids.rigid_velocity_field([0, 0, 0], [[1, 0, 0]]), ShapeError, "shape \\(3,\\)"),
        (
            lambda: fluids.partial_time_derivative(cubic_field, [0, 0, 0], [0.0, 1.0]),
            ShapeError,
            "scalar time",
        ),
    ],
)
def test_bad_input_is_named(call, error, match):
    with pytest.raises(error, match=match):
        call()


# ------------------------------------------- every parameter named, every overflow named
_POS = r"must be > 0; got (0\.0|-1\.0)"
_AREA = r"area_ratio = \(hole area\)/\(surface area\) must lie in \[0, 1\); got (1\.0|-0\.1)"
#: the condition an unphysical value of each fuzz entry violates (tests.fuzz.entries)
_CONDITIONS = {
    ("bernoulli_constant", "rho_0"): _POS,
    ("euler_residual", "rho"): _POS,
    ("drain_time", "h_0"): r"the initial level h_0 must be ≥ 0; got -1\.0",
    ("drain_time", "g"): _POS,
    ("drain_time", "area_ratio"): _AREA,
    ("tank_level", "h_0"): r"the initial level h_0 must be ≥ 0; got -1\.0",
    ("tank_level", "g"): _POS,
    ("tank_level", "area_ratio"): _AREA,
    ("torricelli_speed", "h"): r"the depth h must be ≥ 0; got -1\.0",
    ("torricelli_speed", "g"): _POS,
    ("torricelli_speed", "area_ratio"): _AREA,
    ("streamline", "s"): r"s must be strictly increasing",
    ("streamline", "rtol"): r"rtol must lie in \[2\.22e-14, 1\) .*; got (0\.0|-1\.0|1e-20|1\.5)",
}
#: s is a 1-D array of any length: its wrong shape is 2-D (a case of its own below)
_SKIP = frozenset({("streamline", "s", "shape")})


@pytest.mark.parametrize(
    ("fname", "param", "value", "error", "condition"),
    list(cases("fluids", _CONDITIONS, skip=_SKIP)),
)
def test_every_parameter_of_every_function_is_named_with_the_condition_it_breaks(
    fname, param, value, error, condition
):
    kw = valid_kwargs("fluids", fname) | {param: value}
    check_refusal(getattr(fluids, fname), kw, param, error, condition)


def _nan_scalar(r, t):
    return np.full(np.shape(r)[:-1], np.nan)


def _scalar_of_vector_shape(r, t):
    return np.asarray(r)[..., 0] * 0.0


@pytest.mark.parametrize(
    ("call", "name", "error", "condition"),
    [
        # each field is named by the name it has in the caller's call
        (lambda: fluids.gradient(_nan_scalar, [0.1, 0.2, 0.3]), "f", NonFiniteError, "_FIELD"),
        (
            lambda: fluids.partial_time_derivative(_nan_scalar, [0.1, 0.2, 0.3]),
            "f",
            NonFiniteError,
            "_FIELD",
        ),
        (
            lambda: fluids.material_derivative(_nan_scalar, cubic_field, [0.1, 0.2, 0.3]),
            "f",
            NonFiniteError,
            "_FIELD",
        ),
        (
            lambda: fluids.velocity_gradient(_scalar_of_vector_shape, [0.1, 0.2, 0.3]),
            "v",
            ShapeError,
            r"returned shape \(4, 3\) for r of shape \(4, 3, 3\); a vector field must return "
            r"\(4, 3, 3\)",
        ),
        # a scalar for a streamline's velocity is refused as a vector field's wrong shape
        (
            lambda: fluids.streamline(_scalar_of_vector_shape, [0.1, 0.2, 0.3], [0.0, 1.0]),
            "v",
            ShapeError,
            r"v\(r, t\) returned shape \(\) for r of shape \(3,\); a vector field must return "
            r"\(3,\)",
        ),
        # rho and v finite, their product beyond float64: the flux is named as such
        (
            lambda: fluids.continuity_residual(
                lambda r, t: 1e300 + 0.0 * r[..., 0], lambda r, t: 1e300 + 0.0 * r, [0.1, 0, 0]
            ),
            "rho*v",
            NonFiniteError,
            "_FIELD",
        ),
        (
            lambda: fluids.streamline(cubic_field, [0.1, 0.2, 0.3], [[0.0], [1.0]]),
            "s",
            ShapeError,
            r"s must be a 1-D array of parameter values; got shape \(2, 1\)",
        ),
        (
            lambda: fluids.gradient(_nan_scalar, [0.1, 0.2, 0.3], h=-1.0),
            "h",
            NonPositiveParameterError,
            r"the step h must be > 0; got -1\.0",
        ),
        (
            lambda: fluids.partial_time_derivative(_nan_scalar, [0.1, 0.2, 0.3], h=0.0),
            "h",
            NonPositiveParameterError,
            r"the step h must be > 0; got 0\.0",
        ),
        (
            lambda: fluids.drain_time(1.0, g=9.8, area_ratio=0.0),
            "area_ratio",
            OutOfDomainError,
            r"^area_ratio = 0 \(no hole\): the tank never drains$",
        ),
        (
            lambda: fluids.tank_level(-1.0, h_0=1.0, g=9.8, area_ratio=0.1),
            "t",
            OutOfDomainError,
            r"times must be ≥ 0 \(t = 0 is the start\); got -1\.0",
        ),
        (
            lambda: fluids.torricelli_speed(1.0, g=9.8, area_ratio=[0.1, 0.2]),
            "area_ratio",
            ShapeError,
            r"area_ratio must be a scalar; got shape \(2,\)",
        ),
    ],
)
def test_each_field_and_step_is_named_as_the_caller_named_it(call, name, error, condition):
    cond = FIELD_NONFINITE if condition == "_FIELD" else condition
    with pytest.raises(error) as info:
        call()
    msg = str(info.value)
    assert msg.startswith(name) or re.search(word(name), msg), msg
    assert re.search(cond, msg), msg


def test_continuity_residual_evaluates_the_velocity_at_the_time_asked():
    # rho = 1 + x (steady), v = (t, 0, 0): ∂ρ/∂t + ∇·(ρ v) = ∂x((1 + x) t) = t, exactly
    # representable for the fourth-order stencil (the flux is linear in x)
    def rho(r, t):
        return 1.0 + r[..., 0]

    def v(r, t):
        return np.stack([t + 0.0 * r[..., 0], 0.0 * r[..., 1], 0.0 * r[..., 2]], axis=-1)

    res = fluids.continuity_residual(rho, v, [[0.5, 0.0, 0.0], [2.0, 1.0, 0.0]], t=3.0)
    np.testing.assert_allclose(res, [3.0, 3.0], rtol=0, atol=STENCIL_ATOL)


def test_a_streamline_that_needs_too_many_evaluations_reports_the_whole_interval(monkeypatch):
    monkeypatch.setattr(fluids, "STREAMLINE_MAX_EVALS", 3)
    v = fluids.rigid_velocity_field([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    with pytest.raises(StepSizeError) as info:
        fluids.streamline(v, [1.0, 0.0, 0.0], [0.0, 1.0, 2.0, 3.0])
    msg = str(info.value)
    assert "more than 3 evaluations of v over s = [0.0, 3.0] at rtol = 1e-12" in msg, msg


@pytest.mark.parametrize(
    ("fname", "call"),
    [
        (
            "bernoulli_constant",
            lambda: fluids.bernoulli_constant([1e300, 0, 0], 1.0, 1.0, rho_0=1.0, g=1.0),
        ),
        ("torricelli_speed", lambda: fluids.torricelli_speed(1e300, g=1e300)),
        ("drain_time", lambda: fluids.drain_time(1e300, g=1e-300, area_ratio=0.5)),
        (
            "material_derivative",
            lambda: fluids.material_derivative(
                lambda r, t: 1e200 * r, lambda r, t: 1e200 * r, [1e100, 0, 0]
            ),
        ),
    ],
)
def test_a_result_beyond_float64_is_an_overflow_error_naming_the_function(fname, call):
    with pytest.raises(ResultOverflowError, match=rf"^{fname}: .*float64"):
        call()
