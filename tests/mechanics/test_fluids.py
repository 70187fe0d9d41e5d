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
        (
            lambda: fluids.partial_time_derivative(cubic_field, [0, 0, 0], [0.0, 1.0]),
            ShapeError,
            "scalar time",
        ),
        # a scalar field that returns a vector is named, as a scalar field
        (
            lambda: fluids.gradient(_vector_of, _R),
            ShapeError,
            r"^f\(r, t\) returned shape \(4, 3, 3\) for r of shape \(4, 3, 3\); "
            r"a scalar field must return \(4, 3\)$",
        ),
        # a field of either kind that returns neither shape is judged as a scalar one
        (
            lambda: fluids.partial_time_derivative(lambda r, t: np.zeros(2), _R),
            ShapeError,
            r"^f\(r, t\) returned shape \(2,\) for r of shape \(3,\); "
            r"a scalar field must return \(\)$",
        ),
        (
            lambda: fluids.continuity_residual(_vector_of, _vector_of, _R),
            ShapeError,
            r"^rho\(r, t\) returned shape .*a scalar field must return",
        ),
        (
            lambda: fluids.continuity_residual(_scalar_of, _scalar_of, _R),
            ShapeError,
            r"^v\(r, t\) returned shape .*a vector field must return",
        ),
        (
            lambda: fluids.euler_residual(_zero_vector, _vector_of, _R, rho=1.0, g=1.0),
            ShapeError,
            r"^p\(r, t\) returned shape .*a scalar field must return",
        ),
        (
            lambda: fluids.material_derivative(_zero_scalar, _scalar_of, _R),
            ShapeError,
            r"^v\(r, t\) returned shape \(\) for r of shape \(3,\); a vector field must return",
        ),
        # finite at r for every t (the time stencil) but not at r ± h e_x: named f
        (
            lambda: fluids.material_derivative(_off_the_point_nan, _vector_of, _R),
            NonFiniteError,
            r"^f\(r, t\) returned a non-finite value at t = 0\.0$",
        ),
        (
            lambda: fluids.gradient(_scalar_of, _R, h=np.nan),
            NonFiniteError,
            r"^h must be finite",
        ),
        (
            lambda: fluids.partial_time_derivative(_scalar_of, _R, h=np.nan),
            NonFiniteError,
            r"^h must be finite",
        ),
        (
            lambda: fluids.rigid_velocity_field([0, 0, 0], [[1, 0, 0]]),
            ShapeError,
            r"^v_0 and omega of a rigid velocity field must have shape \(3,\)$",
        ),
        (
            lambda: fluids.streamline(_vector_of, [1.0, 0.0, 0.0], [0.0, 1.0], rtol=1.0),
            OutOfDomainError,
            r"^rtol must lie in \[2\.22e-14, 1\) .*; got 1\.0$",
        ),
        # dr/ds = x² from x = 1 blows up at s = 1: the integrator gives up and says why
        (
            lambda: fluids.streamline(_x_squared, [1.0, 0.0, 0.0], [0.0, 2.0]),
            OutOfDomainError,
            r"^streamline integration failed: Required step size",
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
    assert msg == (
        "streamline: more than 3 evaluations of v over s = [0.0, 3.0] at "
        "rtol = 1e-12; shorten s or loosen rtol"
    ), msg


@pytest.mark.parametrize(
    ("fname", "call"),
    [
        (
            "bernoulli_constant",
            lambda: fluids.bernoulli_constant([1e300, 0, 0], 1.0, 1.0, rho_0=1.0, g=1.0),
        ),
        # u = √(2 g h/(1 − a²)) ≈ 1.3e316 and T = √(2 h0 (1 − a²)/g)/a ≈ 1.2e310: beyond float64
        # (the cases before, u(1e300, g=1e300) = 1.4e300 and T = 2.4e300, are ordinary floats)
        (
            "torricelli_speed",
            lambda: fluids.torricelli_speed(1e308, g=1e308, area_ratio=1 - 2.0**-53),
        ),
        ("drain_time", lambda: fluids.drain_time(1e300, g=1e-300, area_ratio=1e-10)),
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


# ------------------------------------------- mutation review: step choice, defaults, messages
#: a quintic's fifth derivative is constant, so the fourth-order stencil's truncation error
#: -h⁴ f⁽⁵⁾/30 is exact: d/dx x⁵ comes out as 5x⁴ - 4h⁴; with h = 1/8 (a power of two) every
#: stencil value is exact or rounded once, leaving a few eps of the values (~10 at x = 1)
QUINTIC_ATOL = 2**8 * EPS


def _recording(field, seen):
    """The field, recording the points and times it is called at."""

    def f(r, t):
        seen.append((np.array(r, copy=True), t))
        return field(r, t)

    return f


def _linear_in_x(r, t):
    return r[..., 0] + 0.0 * t


def test_the_default_spatial_step_is_h_rel_times_one_plus_the_largest_component_of_each_point():
    # two points of different size: each gets its own step, H_REL (1 + |r|∞)
    r = np.array([[0.5, -3.0, 1.0], [0.25, 0.0, -0.125]])
    seen = []
    fluids.gradient(_recording(_linear_in_x, seen), r, 0.0)
    (pts, _t), *_ = seen
    assert pts.shape == (4, 3, 2, 3)  # offsets, directions, points, components
    h = fluids.H_REL * np.array([1.0 + 3.0, 1.0 + 0.25])
    for k, o in enumerate([-2.0, -1.0, 1.0, 2.0]):
        for j in range(3):
            expected = r + o * h[:, None] * np.eye(3)[j]
            np.testing.assert_array_equal(pts[k, j], expected)


def test_the_default_time_step_is_h_rel_times_one_plus_abs_t():
    seen = []
    fluids.partial_time_derivative(_recording(_linear_in_x, seen), [0.1, 0.2, 0.3], -3.0)
    h = fluids.H_REL * (1.0 + 3.0)
    assert [t for _r, t in seen] == [-3.0 + o * h for o in (-2.0, -1.0, 1.0, 2.0)]


def test_a_step_per_point_is_used_for_each_point():
    # h may be an array over the points: d/dx x⁵ = 5x⁴ - 4h⁴ for each point's own h
    def quintic(r, t):
        return r[..., 0] ** 5

    r = np.array([[[1.0, 0.0, 0.0], [0.5, 2.0, 0.0]], [[-1.0, 0.0, 1.0], [2.0, 0.0, 0.0]]])
    h = np.array([[1 / 8, 1 / 4], [1 / 16, 1 / 8]])
    g = fluids.gradient(quintic, r, 0.0, h=h)
    expected = np.zeros_like(r)
    expected[..., 0] = 5 * r[..., 0] ** 4 - 4 * h**4
    # values up to 2⁵ = 32 (x = 2) rather than 1: the rounding scales with them
    np.testing.assert_allclose(g, expected, rtol=0, atol=QUINTIC_ATOL * 32)


def _quintic_v(r, t):
    x = r[..., 0]
    return np.stack([x**5, 0.0 * x, 0.0 * x], axis=-1)


def test_a_user_step_reaches_every_spatial_derivative():
    # with h = 1/8 each x-derivative of x⁵ at x = 1 is 5 - 4h⁴, not 5 - 4 H_REL⁴ (1 + 1)⁴
    h = 1 / 8
    d = 5.0 - 4 * h**4
    r = [1.0, 0.0, 0.0]
    assert fluids.divergence(_quintic_v, r, h=h) == pytest.approx(d, abs=QUINTIC_ATOL)

    def one(x, t):
        return 1.0 + 0.0 * x[..., 0]

    res = fluids.continuity_residual(one, _quintic_v, r, h=h)
    assert res == pytest.approx(d, abs=QUINTIC_ATOL)
    # steady: ∂f/∂t = 0; (v·∇) f = v_x ∂f/∂x = 1 (5 - 4h⁴)
    assert fluids.material_derivative(_quintic_v, _quintic_v, r, h=h)[0] == pytest.approx(
        d, abs=QUINTIC_ATOL
    )

    # Euler: (v·∇)v = x⁵ (5 - 4h⁴) and ∇p/ρ = 5 - 4h⁴ for p = x⁵, ρ = 1; -g_vec = (0, 0, g)
    def p(x, t):
        return x[..., 0] ** 5

    res = fluids.euler_residual(_quintic_v, p, r, rho=1.0, g=2.0, h=h)
    np.testing.assert_allclose(res, [2 * d, 0.0, 2.0], rtol=0, atol=QUINTIC_ATOL)


def test_a_user_time_step_may_exceed_one():
    # f = t⁵: the stencil gives 5t⁴ - 4h⁴ exactly; h = 1/2 at t = 1 gives 5 - 1/4
    def f(r, t):
        return t**5 + 0.0 * r[..., 0]

    d = fluids.partial_time_derivative(f, [0.0, 0.0, 0.0], 1.0, h=0.5)
    assert d == pytest.approx(5.0 - 0.25, abs=QUINTIC_ATOL)


def _grows(r, t):
    """v = (1 + t) r: div v = 3 (1 + t), curl 0, ∂v/∂t = r."""
    return (1.0 + t) * np.asarray(r)


def _spins(r, t):
    """v = (1 + t) e_z × r: curl v = 2 (1 + t) e_z."""
    x, y, _z = np.moveaxis(np.asarray(r), -1, 0)
    return (1.0 + t) * np.stack([-y, x, 0.0 * x], axis=-1)


def test_the_default_time_is_zero():
    r = np.array([0.5, -1.0, 2.0])
    np.testing.assert_allclose(
        fluids.velocity_gradient(_grows, r), np.eye(3), rtol=0, atol=STENCIL_ATOL
    )
    assert fluids.divergence(_grows, r) == pytest.approx(3.0, abs=STENCIL_ATOL)
    np.testing.assert_allclose(fluids.curl(_spins, r), [0, 0, 2.0], rtol=0, atol=STENCIL_ATOL)

    def f(x, t):  # ∇f = (1 + t + t², 0, 0); ∂f/∂t = (1 + 2t) x
        return (1.0 + t) * x[..., 0] + t**2 * x[..., 0]

    np.testing.assert_allclose(fluids.gradient(f, r), [1.0, 0, 0], rtol=0, atol=STENCIL_ATOL)
    assert fluids.partial_time_derivative(f, r) == pytest.approx(0.5, abs=STENCIL_ATOL)

    def still(x, t):
        return 0.0 * np.asarray(x)

    # still fluid: df/dt = ∂f/∂t = (1 + 2t) x = x at t = 0
    assert fluids.material_derivative(f, still, r) == pytest.approx(0.5, abs=STENCIL_ATOL)

    def rho(x, t):  # ∂ρ/∂t = 2 t
        return 1.0 + t**2 + 0.0 * x[..., 0]

    assert fluids.continuity_residual(rho, still, r) == pytest.approx(0.0, abs=STENCIL_ATOL)
    # and at t = 1.5 the density changes at 2t = 3, read at the time asked
    assert fluids.continuity_residual(rho, still, r, 1.5) == pytest.approx(3.0, abs=STENCIL_ATOL)

    def v(x, t):  # ∂v/∂t = (2t, 0, 0), (v·∇)v = 0
        return np.stack([t**2 + 0.0 * x[..., 0], 0.0 * x[..., 1], 0.0 * x[..., 2]], axis=-1)

    def p0(x, t):
        return 0.0 * x[..., 0]

    res = fluids.euler_residual(v, p0, r, rho=1.0, g=1.0)
    np.testing.assert_allclose(res, [0.0, 0.0, 1.0], rtol=0, atol=STENCIL_ATOL)
    # and at t = 1.5 the local acceleration 2t = 3 is there, read at the time asked
    res = fluids.euler_residual(v, p0, r, 1.5, rho=1.0, g=1.0)
    np.testing.assert_allclose(res, [3.0, 0.0, 1.0], rtol=0, atol=STENCIL_ATOL)


def test_material_derivative_reads_the_time_derivative_at_the_time_asked():
    # f = t² x, still fluid: df/dt = 2 t x = 8 at t = 2, x = 2
    def f(x, t):
        return t**2 * x[..., 0]

    def still(x, t):
        return 0.0 * np.asarray(x)

    d = fluids.material_derivative(f, still, [2.0, 0.0, 0.0], 2.0)
    assert d == pytest.approx(8.0, abs=STENCIL_ATOL)


def test_material_derivative_of_a_scalar_field_adds_the_convective_rate():
    # f = x y + t z in the uniform flow v = (1, 2, 3): df/dt = z + (y·1 + x·2 + t·3)
    def f(x, t):
        return x[..., 0] * x[..., 1] + t * x[..., 2]

    def v(x, t):
        return np.broadcast_to([1.0, 2.0, 3.0], np.shape(x)).copy()

    r = np.array([[0.5, -1.0, 2.0], [1.0, 1.0, 1.0]])
    t = 0.25
    expected = r[:, 2] + r[:, 1] + 2 * r[:, 0] + 3 * t
    d = fluids.material_derivative(f, v, r, t)
    assert d.shape == (2,)
    np.testing.assert_allclose(d, expected, rtol=0, atol=STENCIL_ATOL)


def _vector_of(r, t):
    return np.asarray(r) * 1.0


def _scalar_of(r, t):
    return np.asarray(r)[..., 0] * 1.0


def _zero_scalar(r, t):
    return 0.0 * np.asarray(r)[..., 0]


def _off_the_point_nan(r, t):
    # finite (zero) at x = 0.1 exactly, NaN at every other x: the spatial stencil's x-offsets
    return np.where(np.asarray(r)[..., 0] == 0.1, 0.0, np.nan)


_R = [0.1, 0.2, 0.3]


def _zero_vector(r, t):
    return 0.0 * np.asarray(r)


def _x_squared(r, t):
    x = np.asarray(r)[..., 0]
    return np.stack([x**2, 0.0 * x, 0.0 * x], axis=-1)


def test_fields_returning_float32_are_read_as_float64():
    # ρ = 1e20 and v = (1e20, 0, 0) in float32: the flux ρ v = 1e40 is beyond float32 but not
    # float64; the float32 values are exact in float64, so the residual is the float64 one
    # (a uniform steady flow: zero up to the stencil's rounding of a constant 1e40)
    def fields(dtype):
        def rho(r, t):
            return np.full(np.shape(r)[:-1], 1e20, dtype=dtype)

        def v(r, t):
            out = np.zeros(np.shape(r), dtype=dtype)
            out[..., 0] = 1e20
            return out

        return rho, v

    big = float(np.float32(1e20))  # the float32 value, exact in float64
    assert big != 1e20

    def rho64(r, t):
        return np.full(np.shape(r)[:-1], big)

    def v64(r, t):
        out = np.zeros(np.shape(r))
        out[..., 0] = big
        return out

    r = [0.1, 0.2, 0.3]
    res = fluids.continuity_residual(*fields(np.float32), r)
    assert res == fluids.continuity_residual(rho64, v64, r)


def test_a_rigid_field_reads_any_integer_point_as_float():
    # an integer beyond int64 is a finite point; v = ω × r with ω = e_z, r = 2⁷⁰ e_x
    v = fluids.rigid_velocity_field([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    out = v([2**70, 0, 0], 0.0)
    assert out.dtype == np.float64
    assert out.tolist() == [0.0, 2.0**70, 0.0]


def test_a_streamline_reads_the_field_at_the_frozen_time():
    # v = (1 + t) e_x frozen at t: r(s) = r_0 + (1 + t) s e_x; the default t is 0
    def v(r, t):
        return np.array([1.0 + t, 0.0, 0.0])

    s = np.linspace(0.0, 1.0, 7)
    r0 = np.array([0.5, 1.0, -1.0])
    pts = fluids.streamline(v, r0, s)
    assert pts.shape == (7, 3)
    np.testing.assert_allclose(pts, r0 + np.outer(s, [1.0, 0, 0]), rtol=0, atol=STENCIL_ATOL)
    pts = fluids.streamline(v, r0, s, t=2.0)
    np.testing.assert_allclose(pts, r0 + np.outer(s, [3.0, 0, 0]), rtol=0, atol=STENCIL_ATOL)


def test_a_streamline_at_one_parameter_value_is_the_start_point():
    pts = fluids.streamline(_zero_vector, [0.5, 1.0, -1.0], [0.25])
    assert pts.tolist() == [[0.5, 1.0, -1.0]]
    with pytest.raises(ShapeError, match=r"got shape \(0,\)$"):
        fluids.streamline(_zero_vector, [0.5, 1.0, -1.0], [])


def test_the_smallest_rtol_is_allowed():
    v = fluids.rigid_velocity_field([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    pts = fluids.streamline(v, [1.0, 0.0, 0.0], [0.0, 1.0], rtol=fluids.STREAMLINE_MIN_RTOL)
    # the circle through (1, 0, 0): (cos 1, sin 1, 0); DOP853 at rtol = 100 eps over one
    # radian stays within a few times its rtol
    np.testing.assert_allclose(pts[1], [np.cos(1.0), np.sin(1.0), 0.0], rtol=0, atol=2**8 * EPS)


def test_a_streamline_may_take_exactly_streamline_max_evals_evaluations(monkeypatch):
    n = [0]

    def v(r, t):
        n[0] += 1
        return np.array([-r[1], r[0], 0.0])

    s = [0.0, 1.0, 2.0]
    fluids.streamline(v, [1.0, 0.0, 0.0], s)
    needed = n[0]
    monkeypatch.setattr(fluids, "STREAMLINE_MAX_EVALS", needed)
    fluids.streamline(v, [1.0, 0.0, 0.0], s)
    monkeypatch.setattr(fluids, "STREAMLINE_MAX_EVALS", needed - 1)
    with pytest.raises(StepSizeError, match=rf"^streamline: more than {needed - 1} evaluations"):
        fluids.streamline(v, [1.0, 0.0, 0.0], s)


def test_a_streamline_is_integrated_by_an_eighth_order_method(monkeypatch):
    # DOP853 follows a rotation for about three turns at rtol 1e-12 in ~1100 evaluations of v
    # (RK45, fifth order, would need ~7000): 2000 is enough only for the eighth order
    monkeypatch.setattr(fluids, "STREAMLINE_MAX_EVALS", 2000)
    v = fluids.rigid_velocity_field([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    pts = fluids.streamline(v, [1.0, 0.0, 0.0], [0.0, 20.0])
    np.testing.assert_allclose(np.hypot(pts[:, 0], pts[:, 1]), 1.0, rtol=0, atol=2**16 * EPS)


def test_an_empty_tank_and_a_surface_hole_are_allowed():
    # h = 0: the hole is at the surface, nothing flows out; an empty tank drains in no time
    assert fluids.torricelli_speed(0.0, g=9.8) == 0.0
    assert fluids.drain_time(0.0, g=9.8, area_ratio=0.1) == 0.0
    # a level below one unit: T = √h0 / c with c = a √(g / (2 (1 - a²))), c² = 0.01·9.8/1.98
    c = 0.1 * np.sqrt(9.8 / (2 * 0.99))
    drain = fluids.drain_time(0.25, g=9.8, area_ratio=0.1)
    assert drain == pytest.approx(0.5 / c, rel=CLOSED_RTOL)


# ------------------------------------------- Torricelli's tank at any scale (against mpmath)
#: u, T and h from a few roundings each: the constant's (1 − a)(1 + a), a quotient, the mantissas'
#: product, a square root (halving the error before it), a square; measured ≤ 0.5 eps below
TANK_RTOL = 8 * EPS

#: (h, g, a): products 2 g h, 2 h/g or a² beyond float64 although u, T and h(t) are ordinary
#: floats.  Before the fix: u(1e300, 1e300) refused as an overflow, u(1e-300, 1e-300) = 0, T(1e300,
#: 1e-300) refused, T(1e-300, 1e300) = 0, h(0) = 0 for a = 1e-200 and h(0) = 1.00003 h0 for a =
#: 1e-160 (a² subnormal), h = 0 for h0 = 5e-324
_TANKS = [
    (1e300, 1e300, 0.0),
    (1e-300, 1e-300, 0.5),
    (5e-324, 1.0, 0.0),
    (1e300, 1e-300, 0.5),
    (1e-300, 1e300, 0.5),
    (1.0, 9.8, 1e-200),
    (1.0, 9.8, 1e-160),
    (5e-324, 9.8, 0.5),
    (2.0, 9.8, 0.3),
]


def _tank_exact(h, g, a, t):
    import mpmath

    with mpmath.workdps(50):
        h, g, a, t = (mpmath.mpf(x) for x in (h, g, a, t))
        u = mpmath.sqrt(2 * g * h / (1 - a * a))
        T = mpmath.sqrt(2 * h * (1 - a * a) / g) / a if a else mpmath.inf
        level = h * (1 - t / T) ** 2 if a else h
        return u, T, level


def _rel(got, exact):
    """The relative error; a subnormal result's within half its spacing 2⁻¹⁰⁷⁴ counts as 0."""
    import mpmath

    if abs(mpmath.mpf(got) - exact) <= mpmath.ldexp(1, -1075):
        return 0.0
    return float(abs(mpmath.mpf(got) / exact - 1))


@pytest.mark.parametrize(("h", "g", "a"), _TANKS)
def test_torricelli_speed_at_any_scale_against_mpmath(h, g, a):
    u, _, _ = _tank_exact(h, g, a, 0.0)
    assert _rel(float(fluids.torricelli_speed(h, g=g, area_ratio=a)), u) <= TANK_RTOL


@pytest.mark.parametrize(("h", "g", "a"), [c for c in _TANKS if c[2] > 0])
def test_drain_time_and_tank_level_at_any_scale_against_mpmath(h, g, a):
    T = float(fluids.drain_time(h, g=g, area_ratio=a))
    _, T_exact, level_0 = _tank_exact(h, g, a, 0.0)
    assert _rel(T, T_exact) <= TANK_RTOL
    assert _rel(float(fluids.tank_level(0.0, h_0=h, g=g, area_ratio=a)), level_0) <= TANK_RTOL
    # at a time T/4 exactly representable: h0 (1 − t/T)² with T exact, against the rounded T's
    t = T / 4
    _, _, level = _tank_exact(h, g, a, t)
    assert _rel(float(fluids.tank_level(t, h_0=h, g=g, area_ratio=a)), level) <= TANK_RTOL


#: ½ ρ0 |v|² + ρ0 g z + p from the mantissas: |v|² of the scaled v (three products and two
#: sums), ρ0's and g's mantissas (a product each), the two additions; measured ≤ 0.5 eps below
BERNOULLI_RTOL = 8 * EPS


@pytest.mark.parametrize(
    ("v", "p", "z", "rho_0", "g"),
    [
        # |v|² = 1e320 overflowed for B = 5e219: refused as an overflow before
        ([1e160, 0.0, 0.0], 0.0, 0.0, 1e-100, 1.0),
        ([3e-170, -4e-170, 0.0], 0.0, 0.0, 1e100, 1.0),  # |v|² underflowed: B = 0 for 1.25e-239
        ([0.0, 0.0, 0.0], 1.0, 1e-200, 1e200, 1e200),  # ρ0 g = 1e400 for ρ0 g z = 1e200: refused
        # |v|² = 10·2^-1200 = 0: B = 2^-900 for 6·2^-900 before
        ([2.0**-600, 0.0, 3 * 2.0**-600], 2.0**-900, 0.0, 2.0**300, 9.81),
        ([1.5, -2.0, 0.25], 1e5, -3.0, 1000.0, 9.81),
    ],
)
def test_bernoulli_constant_at_any_scale_against_mpmath(v, p, z, rho_0, g):
    import mpmath

    got = float(fluids.bernoulli_constant(v, p, z, rho_0=rho_0, g=g))
    with mpmath.workdps(50):
        vv = sum(mpmath.mpf(x) ** 2 for x in v)
        exact = mpmath.mpf(rho_0) * vv / 2 + mpmath.mpf(rho_0) * g * z + p
    assert _rel(got, exact) <= BERNOULLI_RTOL
