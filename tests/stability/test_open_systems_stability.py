"""The rocket of :mod:`mechanics.open_systems` against mpmath at 50 digits.

How the errors are measured
---------------------------
The oracle takes the float64 inputs (t, m_0, q, u, g) as exact binary numbers and
evaluates (7.30) and its integral directly at 50 digits (50 digits carry the
16 of float64 and leave 34 for the cancellation of 1 + (1 − x) log(1 − x)/x at
x = 1e-15):

    v = −u log(1 − x) − g t,   z = u t (1 + (1 − x) log(1 − x)/x) − g t²/2,  x = q t/m_0.

The error is |float − exact| divided by the size of the terms, u L + g t for the
velocity and u t φ + g t²/2 for the height (a relative error when g = 0; with
gravity, the conditioning of the difference: a relative change of eps in g moves
the result by eps g t), in units of eps.  The promise is ``ROCKET_RTOL`` = 4 eps
for burnt fractions x ≤ 1/2.

Mass ratios m/m_0 = 1 − x with x = 1e-15 … 1e-3 burned are swept on a grid and
searched by hypothesis (``target`` pushes toward the worst case).  To print the
worst errors found::

    .venv/bin/python -m pytest tests/stability/test_open_systems_stability.py -q -s

Measured worst (grids of 3 × 1000 log-spaced x and the hypothesis search): velocity
1.32 eps, height 2.10 eps for x ≤ 1e-3 (and within ROCKET_RTOL up to x = 1/2).
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from hypothesis import example, given, target
from hypothesis import strategies as st

from mechanics import open_systems as osys
from mechanics._floats import EPS

MP_DPS = 50
BOUND = osys.ROCKET_RTOL / EPS  # in eps


def _exact(t, m_0, q, u, g):
    with mpmath.workdps(MP_DPS):
        t, m_0, q, u, g = (mpmath.mpf(float(a)) for a in (t, m_0, q, u, g))
        x = q * t / m_0
        L = -mpmath.log(1 - x)
        phi = 1 + (1 - x) * mpmath.log(1 - x) / x if x else mpmath.mpf(0)
        return (
            u * L - g * t,
            u * t * phi - g * t * t / 2,
            u * L + g * t,
            u * t * phi + g * t * t / 2,
        )


def _errors(x, m_0, q, u, g_frac):
    """Errors (velocity, height) in eps at burnt fraction ≈ x, g = g_frac × lift-off limit."""
    t = x * m_0 / q
    g = g_frac * q * u / m_0
    while m_0 * g > q * u:  # at the lift-off limit, rounding may put g an ulp above it
        g = float(np.nextafter(g, 0.0))
    kw = dict(m_0=m_0, q=q, u=u, m_f=0.999 * m_0, g=g)
    v, z = osys.rocket_velocity(t, **kw), osys.rocket_height(t, **kw)
    ve, ze, sv, sz = _exact(t, m_0, q, u, g)
    with mpmath.workdps(MP_DPS):
        ev = float(abs(mpmath.mpf(float(v)) - ve) / sv) / EPS
        ez = float(abs(mpmath.mpf(float(z)) - ze) / sz) / EPS
    return ev, ez


WORST: dict[str, float] = {}


def _record(name: str, err: float) -> None:
    WORST[name] = max(WORST.get(name, 0.0), err)


@pytest.mark.parametrize("g_frac", [0.0, 0.5, 1.0])
def test_rocket_grid_of_mass_ratios_near_one(g_frac):
    rng = np.random.default_rng(20240730)
    xs = np.logspace(-15, -3, 1000)
    for x in xs:
        m_0, q, u = 10 ** rng.uniform(0, 6), 10 ** rng.uniform(-1, 3), 10 ** rng.uniform(2, 4)
        ev, ez = _errors(x, m_0, q, u, g_frac)
        _record("velocity", ev)
        _record("height", ez)
        assert ev <= BOUND, f"velocity error {ev:.2f} eps at x = {x:.3g}"
        assert ez <= BOUND, f"height error {ez:.2f} eps at x = {x:.3g}"


def test_rocket_up_to_half_burnt():
    for x in np.linspace(1e-3, 0.5, 400):
        ev, ez = _errors(x, 1234.5, 7.25, 2961.0, 0.0)
        assert ev <= BOUND
        assert ez <= BOUND


@given(
    log_x=st.floats(-15.0, -3.0),
    m_0=st.floats(1e-3, 1e9),
    q=st.floats(1e-3, 1e4),
    u=st.floats(1.0, 1e5),
    g_frac=st.sampled_from([0.0, 0.25, 0.999, 1.0]),
)
@example(log_x=-15.0, m_0=1.0, q=1.0, u=1.0, g_frac=0.0)
@example(log_x=-3.0, m_0=1e9, q=1e-3, u=1e5, g_frac=1.0)
def test_rocket_error_within_promise(log_x, m_0, q, u, g_frac):
    ev, ez = _errors(10.0**log_x, m_0, q, u, g_frac)
    target(ev, label="velocity error (eps)")
    target(ez, label="height error (eps)")
    _record("velocity", ev)
    _record("height", ez)
    assert ev <= BOUND
    assert ez <= BOUND


def test_naive_formulas_fail_the_same_measure():
    """Negative control: the measure sees the cancellation that log1p and the series avoid."""
    x, m_0, q, u = 1e-12, 1.0, 1.0, 1.0
    t = x * m_0 / q
    ve, ze, sv, sz = _exact(t, m_0, q, u, 0.0)
    naive_v = u * math.log(m_0 / (m_0 - q * t))
    naive_phi = 1 + (1 - x) * math.log1p(-x) / x  # log1p, but the direct form of φ
    naive_z = u * t * naive_phi
    with mpmath.workdps(MP_DPS):
        assert float(abs(mpmath.mpf(naive_v) - ve) / sv) / EPS > 1e3
        assert float(abs(mpmath.mpf(naive_z) - ze) / sz) / EPS > 1e3


def test_report_worst_errors():
    """Prints the worst errors recorded by the tests above (run with -s)."""
    if WORST:
        print(
            "\nrocket worst error vs mpmath (eps): "
            + ", ".join(f"{k} {v:.2f}" for k, v in sorted(WORST.items()))
        )
    assert all(v <= BOUND for v in WORST.values())


@pytest.mark.parametrize("power", [-1060, -1000, -600, 0, 600, 1000])
@pytest.mark.parametrize("g_frac", [0.0, 0.5])
def test_rocket_of_any_mass_scale_is_within_its_promise(power, g_frac):
    """m_0, q (and m_f) scaled together by 2**power leave x = q t/m_0 alone: the error stays
    within ROCKET_RTOL.  The plain q t underflowed at 2**-1000 and 2**-1060 for a burnt
    fraction x = 1e-30 (q t ≈ 1e-329: v = z = 0, errors of 1/eps; the hunt, 29 Nov 2026)."""
    m_0, q, u = np.ldexp(1000.0, power), np.ldexp(4.0, power), 3000.0
    t, g = 1e-30 * 250.0, g_frac * 0.004 * u  # x m_0/q and g_frac q u/m_0 (ratios exact)
    kw = dict(m_0=m_0, q=q, u=u, m_f=0.999 * m_0, g=g)
    v, z = osys.rocket_velocity(t, **kw), osys.rocket_height(t, **kw)
    ve, ze, sv, sz = _exact(t, m_0, q, u, g)
    with mpmath.workdps(MP_DPS):
        ev = float(abs(mpmath.mpf(float(v)) - ve) / sv) / EPS
        ez = float(abs(mpmath.mpf(float(z)) - ze) / sz) / EPS
    assert ev <= BOUND, ev
    assert ez <= BOUND, ez


@pytest.mark.parametrize("power", [-1000, 0, 1000])
def test_jet_velocity_of_any_mass_scale_matches_mpmath(power):
    """v = w + (v_0 − w) e^{−q t/m} from rest, k = q t/m = 2**-100 for masses scaled by
    2**power: the plain q t underflowed to 0 at 2**-1000 (v = 0 for the exact w 2**-100).
    Rounded in k (exact here), exp, expm1 and two products: within 4 eps."""
    m, q, w, t = np.ldexp(3.0, power), np.ldexp(3.0, power), 1.5, 2.0**-100
    with mpmath.workdps(MP_DPS):
        k = mpmath.mpf(q) * t / mpmath.mpf(m)
        exact = w - w * mpmath.exp(-k)
        got = osys.jet_velocity(t, m=m, q=q, w=w, v_0=0.0)
        assert float(abs(mpmath.mpf(float(got)) - exact) / exact) <= 4 * EPS


@pytest.mark.parametrize(
    ("q", "r", "t", "J_0"),
    [
        # q r² = 2**1040 beyond float64, q r² t = 2**980 and x = 0.05: a valid wheel
        (2.0**900, 2.0**70, 2.0**-60, 20.0 * 2.0**980),
        # q r² t ~ 0.05 · 2**-1030, subnormal: x = 0.05 to the last bit
        (2.0**-1070, 1.0, 0.05 * 2.0**40, 2.0**-1030),
        (2.0, 50.0, 10.0, 1e6),  # the docstring's wheel
    ],
)
def test_rim_rocket_of_any_scale_matches_mpmath(q, r, t, J_0):
    """ω = −(u/r) log(1 − q r² t/J_0) (7.46) with x = q r² t/J_0 formed on the mantissas:
    the plain q r² overflowed for the first wheel (x = 0.05 refused as ≥ 1) and q r² t
    lost ~10 bits as a subnormal for the second (500 eps).  Rounded in x (one quotient of
    four products), log1p and a product: within 4 eps (the hunt, 29 Nov 2026)."""
    u = 3000.0
    got = osys.rim_rocket_angular_velocity(t, J_0=J_0, q=q, u=u, r=r)
    with mpmath.workdps(MP_DPS):
        x = mpmath.mpf(q) * mpmath.mpf(r) ** 2 * mpmath.mpf(t) / mpmath.mpf(J_0)
        exact = -(mpmath.mpf(u) / mpmath.mpf(r)) * mpmath.log(1 - x)
        assert float(abs(mpmath.mpf(float(got)) - exact) / exact) <= 4 * EPS
