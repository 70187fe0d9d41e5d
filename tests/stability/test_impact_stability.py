"""Direct central impact against an exact rational oracle, errors in ulps.

How the errors are measured
---------------------------
The oracle takes the float64 inputs (m_1, m_2, ẋ_1, ẋ_2, e) as exact binary
numbers and evaluates the book's closed forms in exact rational arithmetic
(:class:`fractions.Fraction`).  mpmath at 50 digits is not enough as an oracle
here: hypothesis found e = 1.1e-123 with equal masses and opposite
velocities, where ẋ_1f = e ẋ_1 ≈ 1e-129 but 1 + e rounds to 1 at 50 digits
and the "exact" value came out 0 (the code was right).  The closed forms:
μ = m_1 m_2/(m_1 + m_2), Δẋ = ẋ_2 − ẋ_1 and

- ẋ_1f = ẋ_1 + (1 + e) m_2 Δẋ/(m_1 + m_2), ẋ_2f = ẋ_2 − (1 + e) m_1 Δẋ/(m_1 + m_2)
  (from (6.37)–(6.38));
- S_12 = (1 + e) μ Δẋ (6.19); Q = ½ μ (1 − e²) Δẋ² (6.41); the compression and
  restitution impulses μ Δẋ and e μ Δẋ (Example 6.3).

The error of a float result x against the exact value X is |x − X| in units of
the spacing of float64 at |X| (ulps), or, where X cancels to below
:data:`CANCEL_FLOOR` times the input velocities, in units of that floor times
the velocities (the double-double intermediates carry about 2^-104 relative to
their inputs; see :mod:`mechanics.impact`).  An exactly zero X must come out
exactly zero.

The promise under test is :data:`mechanics.impact.DIRECT_ULPS` = 2 ulps, over a
grid of mass ratios 1e-15 … 1e15 (both ways, several absolute scales), e in
{0, 1e-15, 1e-6, ¼, ½, 0.9, 1 − 1e-6, 1 − 1e-12, 1 − 2^-53, 1} and velocity pairs
head-on, chasing, with one at rest and with a relative velocity 1e-10 of the
velocities; and by hypothesis, pushed toward the worst case by
:func:`hypothesis.target`.  Measured worst (this grid, and the explore profile
with 1000 examples per test): 0.50 ulp for every quantity, i.e. correctly
rounded in every case met.  To see it::

    HYPOTHESIS_PROFILE=explore .venv/bin/python -m pytest \\
        tests/stability/test_impact_stability.py --hypothesis-show-statistics -s

Also here: the naive forms (1 − e*e, m_1*m_2/(m_1 + m_2), T_i − T_f) measured
failing in the same regimes, as the documented problems the module avoids.
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import example, given, target

from mechanics import impact as im
from mechanics import strategies as ms

#: The promise of mechanics.impact for the direct-impact functions.
PROMISE_ULPS = im.DIRECT_ULPS

#: Below this fraction of the input velocities a result is a cancellation
#: beyond the double-double intermediates (2^-104 relative): errors there are
#: measured against the floor, not against the tiny result.
CANCEL_FLOOR = 2.0**-100

QUANTITIES = ("v_1f", "v_2f", "S_12", "Q", "S_1", "S_2")

RATIOS = [10.0**k for k in range(-15, 16, 3)] + [1.0, 3.0, 1 / 3]
SCALES = [1.0, 1e-200, 1e200]
ES = [0.0, 1e-15, 1e-6, 0.25, 0.5, 0.9, 1 - 1e-6, 1 - 1e-12, 1 - 2.0**-53, 1.0]
VELOCITIES = [(3.0, -1.25), (7.0, 6.0), (2.5, 0.0), (1.0 + 1e-10, 1.0), (-1.0, -1.0 - 1e-10)]


def _exact(m1, m2, v1, v2, e) -> dict[str, Fraction]:
    """The closed forms in exact rational arithmetic on the float inputs."""
    m1, m2, v1, v2, e = (Fraction(float(x)) for x in (m1, m2, v1, v2, e))
    M = m1 + m2
    mu = m1 * m2 / M
    d = v2 - v1
    return {
        "v_1f": v1 + (1 + e) * m2 * d / M,
        "v_2f": v2 - (1 + e) * m1 * d / M,
        "S_12": (1 + e) * mu * d,
        "Q": mu * (1 - e * e) * d * d / 2,
        "S_1": mu * d,
        "S_2": e * mu * d,
    }


def _ours(m1, m2, v1, v2, e) -> dict[str, np.ndarray]:
    v1f, v2f = im.direct_impact(m1, m2, v1, v2, e)
    S1, S2 = im.compression_restitution_impulses(m1, m2, v1, v2, e)
    return {
        "v_1f": v1f,
        "v_2f": v2f,
        "S_12": im.impulse_direct(m1, m2, v1, v2, e),
        "Q": im.energy_loss_direct(m1, m2, v1, v2, e),
        "S_1": S1,
        "S_2": S2,
    }


def _floor(name: str, m1, m2, v1, v2) -> float:
    """CANCEL_FLOOR in the units of the quantity: velocities, impulses, energies."""
    v = max(abs(v1), abs(v2))
    if name in ("v_1f", "v_2f"):
        return CANCEL_FLOOR * v
    mu = min(m1, m2)
    return CANCEL_FLOOR * (mu * v * v if name == "Q" else mu * v)


def error_ulps(got, exact, floor: float = 0.0) -> float:
    """|got − exact| in ulps of the exact value (or of ``floor``, if larger)."""
    got = float(got)
    exact = Fraction(exact)
    if exact == 0:
        return 0.0 if got == 0.0 else math.inf
    unit = max(math.ulp(abs(float(exact))), floor)
    if unit == 0.0:  # the exact value underflows below the smallest subnormal
        return 0.0 if got == 0.0 else math.inf
    return float(abs(Fraction(got) - exact) / Fraction(unit))


def _worst_over(cases) -> dict[str, float]:
    m1, m2, v1, v2, e = (np.array(c) for c in zip(*cases, strict=True))
    ours = _ours(m1, m2, v1, v2, e)
    worst = dict.fromkeys(QUANTITIES, 0.0)
    for i, case in enumerate(cases):
        exact = _exact(*case)
        for name in QUANTITIES:
            err = error_ulps(ours[name][i], exact[name], _floor(name, *case[:4]))
            worst[name] = max(worst[name], err)
    return worst


@pytest.fixture(scope="module")
def grid_cases() -> list[tuple[float, ...]]:
    cases = []
    for ratio, scale, e, (v1, v2) in itertools.product(RATIOS, SCALES, ES, VELOCITIES):
        m2 = 1.7 * scale
        cases.append((m2 * ratio, m2, v1, v2, e))
    return cases


def test_direct_impact_within_promise_over_the_grid_of_mass_ratios_and_e(grid_cases):
    worst = _worst_over(grid_cases)
    assert len(grid_cases) == len(RATIOS) * len(SCALES) * len(ES) * len(VELOCITIES)
    for name, err in worst.items():
        assert err <= PROMISE_ULPS, (name, err)


def test_e_one_ulp_below_one_and_1e_minus_12_below_one_give_the_exact_loss():
    # 1 − e is exact here (Sterbenz); (1 − e)(1 + e) in double-double.
    for e in (1 - 1e-12, 1 - 2.0**-53):
        for ratio in (1e-15, 1.0, 1e15):
            case = (ratio, 1.0, 2.0, -3.0, e)
            Q = im.energy_loss_direct(*case)
            assert error_ulps(Q, _exact(*case)["Q"]) <= PROMISE_ULPS


@given(ms.mass_pairs(), ms.direct_velocities(), ms.restitution_coefficients())
@example((1e-15, 1.0), (1.0, -1.0), 1 - 1e-12)
@example((1e15, 1.0), (1.0 + 1e-12, 1.0), 0.5)
@example((1.0, 3.0), (1.0, 1.0 - 2.0**-52), 1.0)
@example((0.0011405754127707586,) * 2, (1.2923555258910033e-06, -1.2923555258910033e-06), 1.09e-123)
def test_direct_impact_is_within_a_few_ulps_of_the_exact_value(masses, velocities, e):
    (m1, m2), (v1, v2) = masses, velocities
    ours = _ours(m1, m2, v1, v2, e)
    exact = _exact(m1, m2, v1, v2, e)
    errs = {n: error_ulps(ours[n], exact[n], _floor(n, m1, m2, v1, v2)) for n in QUANTITIES}
    worst = max(errs.values())
    target(min(worst, 1e6), label="worst error in ulps")
    assert worst <= PROMISE_ULPS, errs


#: Speeds up to this reach the top of the float range while v_1f, v_2f (at most
#: 3 max|ẋ|) stay finite.
HUGE_SPEED = 1e302


@given(
    ms.mass_pairs(),
    ms.direct_velocities(max_speed=HUGE_SPEED, regimes=["mixed-magnitude"]),
    ms.restitution_coefficients(),
)
@example((1.0, 1.0), (0.0, -1e302), 0.5)
@example((1.0, 1.0), (1e302, 0.0), 0.5)
@example((1.0, 3.0), (1e-300, -1e302), 1.0)
@example((1e15, 1.0), (1e302, 1e-300), 0.25)
@example((1e-150, 3e-150), (5e301, -1e-200), 0.0)
@example((3e140, 1e150), (1e-250, -7e301), 1.0)
@example((1.7e308, 1e-300), (1.0, -1.0), 0.5)
@example((1e-300, 1.7e308), (3.0, -1.0), 0.25)
def test_direct_impact_velocities_exact_when_the_velocities_span_the_float_range(
    masses, velocities, e
):
    # The internal scaling must follow both velocities (and both masses): scaled
    # by the smaller one, the larger overflows in the double-double products.
    (m1, m2), (v1, v2) = masses, velocities
    v1f, v2f = im.direct_impact(m1, m2, v1, v2, e)
    exact = _exact(m1, m2, v1, v2, e)
    for name, got in (("v_1f", v1f), ("v_2f", v2f)):
        err = error_ulps(got, exact[name], _floor(name, m1, m2, v1, v2))
        target(min(err, 1e6), label=f"{name} error in ulps")
        assert err <= PROMISE_ULPS, (name, float(got), float(exact[name]), err)


def test_direct_impact_of_a_huge_velocity_against_one_at_rest_is_exact():
    # the case of issue 16: a scaling that ignores ẋ_2 overflows here
    for v1, v2, want in ((0.0, -1e302, (-0.75, -0.25)), (1e302, 0.0, (0.25, 0.75))):
        got = im.direct_impact(1.0, 1.0, v1, v2, 0.5)
        big = Fraction(1e302)
        for g, w in zip(got, want, strict=True):
            assert error_ulps(g, Fraction(w) * big) <= PROMISE_ULPS, (float(g), w)


# ------------------------------------------- the problems the module avoids


def test_naive_one_minus_e_squared_loses_digits_near_one():
    # Measurement, not a promise: at e = 1 − 1e-12, 1 − e*e rounds e² first;
    # measured 2.5e3 ulps (three digits lost); (1 − e)(1 + e) is within 1 ulp.
    e = 1 - 1e-12
    exact = 1 - Fraction(e) ** 2
    naive = error_ulps(1 - e * e, exact)
    factored = error_ulps((1 - e) * (1 + e), exact)
    assert naive > 1e3
    assert factored <= 1.0


def test_naive_reduced_mass_overflows_and_underflows():
    with np.errstate(over="ignore", under="ignore"):
        big = np.float64(1e300)
        tiny = np.float64(1e-300)
        assert not np.isfinite(big * big / (big + big))
        assert tiny * tiny / (tiny + tiny) == 0.0
    assert math.isclose(float(im.energy_loss_direct(1e300, 1e300, 1.0, -1.0, 0.0)), 1e300)
    assert math.isclose(float(im.energy_loss_direct(1e-300, 1e-300, 1.0, -1.0, 0.0)), 1e-300)


def test_naive_energy_difference_cancels_where_the_loss_is_small():
    # Fast bodies, small relative velocity: T_i − T_f is a difference of two
    # energies of size 1e12 for a loss of size 1e-8; the factored form is exact.
    m1, m2, v1, v2, e = 1.0, 2.0, 1e6 + 1e-4, 1e6, 0.3
    v1f, v2f = im.direct_impact(m1, m2, v1, v2, e)
    naive = (0.5 * m1 * v1**2 + 0.5 * m2 * v2**2) - (0.5 * m1 * v1f**2 + 0.5 * m2 * v2f**2)
    exact = _exact(m1, m2, v1, v2, e)["Q"]
    assert error_ulps(naive, exact) > 1e6
    assert error_ulps(im.energy_loss_direct(m1, m2, v1, v2, e), exact) <= PROMISE_ULPS


# ------------------------------- one rounding: just above a power of two


#: m_1 = m_2 = 2 (1 + 2^-52): μ = 1 + 2^-52 exactly, the mass fractions exactly ½.
M_ABOVE_ONE = 2.0 + 2.0**-51

#: e ≈ √5 2^-27.5: (1 + 2^-52)(1 − e²) = 1 + (3/8) 2^-52 + O(2^-104).
E_Q = math.sqrt(5.0) * 2.0**-27.5


@pytest.mark.parametrize(
    ("name", "case"),
    [
        # Δẋ = −(1 − 2^-53): S_12 = μ Δẋ = −(1 + 2^-53 − 2^-105) at e = 0
        pytest.param("S_12", (M_ABOVE_ONE, M_ABOVE_ONE, 1 - 2.0**-53, 0.0, 0.0), id="S_12"),
        # the same S_1, and S_2 = ½ S_1 at e = ½
        pytest.param("S_1", (M_ABOVE_ONE, M_ABOVE_ONE, 1 - 2.0**-53, 0.0, 0.5), id="S_1"),
        pytest.param("S_2", (M_ABOVE_ONE, M_ABOVE_ONE, 1 - 2.0**-53, 0.0, 0.5), id="S_2"),
        # Δẋ = −1: Q = ½ μ (1 − e²) = ½ (1 + (3/8) 2^-52 + ...)
        pytest.param("Q", (M_ABOVE_ONE, M_ABOVE_ONE, 1.0, 0.0, E_Q), id="Q"),
    ],
)
def test_a_result_just_above_a_power_of_two_is_rounded_once(name, case):
    # Here every factor is exact in double-double (μ, the fractions ½, 1 ± e and Δẋ), so the
    # exact value is carried to ~2^-104 and only the final rounding remains (DIRECT_ULPS'
    # reason): the result is the correctly rounded value, within ½ ulp.  The exact value lies
    # between ¼ and ½ ulp above a power of two, where that one rounding goes down to it; a
    # result that dropped or negated the low part of the double-double would be an ulp off.
    exact = _exact(*case)[name]
    power = 2.0 ** math.frexp(abs(float(exact)))[1] / 2
    above = (abs(exact) - Fraction(power)) / Fraction(math.ulp(power))
    assert abs(float(exact)) == power
    assert Fraction(1, 4) < above < Fraction(1, 2), float(above)
    got = _ours(*case)[name]
    assert float(got) == float(exact)  # float(Fraction) rounds to nearest
    assert error_ulps(got, exact) <= 0.5


@pytest.mark.parametrize("e", [1.0, 0.5, 1 - 2.0**-53, 1e-300, 2.0**-1022])
@pytest.mark.parametrize(
    "dv", [1e299, 7e299, 2.0**996 * (1 - 2.0**-53), 2.0**996, 1.4e300, 1e305, 1.7e308]
)
def test_the_restitution_impulse_of_a_huge_compression_impulse_rounds_e_mu_dv_once(e, dv):
    """S_2 = e μ Δẋ for |S_1| on both sides of SPLIT_LIMIT = 2**996 (and at it), where the product with e is made
    2**64 lower (Dekker's split overflowed above ~1.34e300 before, issue 35), against
    exact rationals: within the promised ulps, never a false overflow."""
    m1, m2, v1, v2 = 2.0, 2.0, dv, 0.0  # μ = 1, Δẋ = −dv: S_1 = −dv exactly
    S1, S2 = im.compression_restitution_impulses(m1, m2, v1, v2, e)
    exact = _exact(m1, m2, v1, v2, e)
    assert float(S1) == -dv
    assert error_ulps(S2, exact["S_2"]) <= PROMISE_ULPS, (float(S2), float(exact["S_2"]))
