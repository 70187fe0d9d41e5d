"""API, validation and identities of :mod:`mechanics.elliptic`.

The mpmath comparisons over the hard parameter ranges are in
``tests/stability/test_elliptic_stability.py``; here: shapes, validation, the
special values (m = 0: trigonometric, m = 1: hyperbolic), the algebraic
identities sn² + cn² = 1 and dn² + m sn² = 1, the addition of a period, the
transformations m ↔ 1/m and m ↔ −m/(1 − m) checked against scipy at ordinary
parameters, the derivative sn' = cn dn by a complex-free finite difference, and
F as the inverse of am.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
import scipy.special as sc

from mechanics import _floats
from mechanics import elliptic as el
from mechanics._floats import EPS
from mechanics.errors import NonFiniteError, OutOfDomainError, ResultOverflowError, ShapeError

from ._naming import cases, check_refusal, valid_kwargs

# An identity such as sn² + cn² − 1 formed from values each within a few ulps:
# two squares and a sum, each rounded, of numbers of size ≤ 1.
IDENTITY_ATOL = 8 * EPS

# scipy's ellipj at ordinary parameters (0.1 ≤ m ≤ 0.9, |u| ≤ 10) is accurate to a
# few tens of eps (measured ≤ 20 eps), ours to a few: their difference.
SCIPY_ORDINARY_ATOL = 64 * EPS

# A fourth-order central difference with step h = 1e-3: truncation h⁴/30 |f⁽⁵⁾| ≈ 3e-14
# for |f⁽⁵⁾| ≲ 10 and rounding eps/h ≈ 2e-13.
FD_ATOL = 1e-12
FD_STEP = 1e-3

SEED = 20261122

#: Π = F + the R_J tail: F to a few eps, scipy's elliprj to about ten; their sum
THIRD_KIND_RTOL = 16 * EPS


def _close(actual, desired, atol, what=""):
    """|actual − desired| ≤ atol elementwise (atol may be an array); report in eps."""
    a, d = np.broadcast_arrays(np.asarray(actual, float), np.asarray(desired, float))
    tol = np.broadcast_to(np.asarray(atol, float), a.shape)
    err = np.abs(a - d)
    bad = ~(err <= tol)
    if bad.any():
        i = np.unravel_index(np.argmax(np.where(bad, err / tol, 0)), a.shape)
        raise AssertionError(
            f"{what}: |{a[i]!r} − {d[i]!r}| = {err[i] / EPS:.3g} eps > {tol[i] / EPS:.3g} eps at {i}"
        )


def test_ellipj_returns_four_arrays_of_the_broadcast_shape():
    u = np.linspace(-3, 3, 12).reshape(3, 4)
    out = el.ellipj(u, np.array([0.2, 0.5, 0.9, 1.5]))
    assert len(out) == 4
    assert all(a.shape == (3, 4) for a in out)


def test_ellipj_at_m_zero_is_trigonometric():
    u = np.linspace(-20, 20, 101)
    sn, cn, dn, am = el.ellipj(u, 0.0)
    _close(sn, np.sin(u), 8 * EPS * (1 + np.abs(u)))
    _close(cn, np.cos(u), 8 * EPS * (1 + np.abs(u)))
    np.testing.assert_array_equal(dn, 1.0)
    np.testing.assert_allclose(am, u, rtol=4 * EPS)


def test_ellipj_at_m_one_is_hyperbolic_for_large_arguments_without_nan():
    u = np.array([-800.0, -20.0, -1.0, 0.0, 0.5, 3.0, 30.0, 800.0])
    sn, cn, dn, am = el.ellipj(u, 1.0)
    np.testing.assert_allclose(sn, np.tanh(u), rtol=4 * EPS)
    with np.errstate(over="ignore"):
        sech = 1 / np.cosh(u)
    _close(cn, sech, 8 * EPS * (1 + np.abs(u)) * sech, "cn")
    np.testing.assert_array_equal(dn, cn)
    np.testing.assert_allclose(am, np.arctan(np.sinh(np.clip(u, -700, 700))), rtol=4 * EPS)
    assert np.isfinite(np.stack([sn, cn, dn, am])).all()


@pytest.mark.parametrize("m", [-50.0, -1.0, 0.3, 0.7, 1 - 1e-9, 1.0, 1.2, 30.0])
def test_ellipj_satisfies_the_quadratic_identities(m):
    u = np.random.default_rng(SEED).uniform(-40, 40, 200)
    sn, cn, dn, _ = el.ellipj(u, m)
    _close(sn**2 + cn**2, 1.0, IDENTITY_ATOL * max(1, abs(m)))
    _close(dn**2 + m * sn**2, 1.0, IDENTITY_ATOL * max(1, abs(m)))


@pytest.mark.parametrize("m", [0.1, 0.5, 0.9])
def test_ellipj_agrees_with_scipy_at_ordinary_parameters(m):
    u = np.random.default_rng(SEED + 1).uniform(-10, 10, 300)
    ours = el.ellipj(u, m)
    theirs = sc.ellipj(u, m)
    for a, b in zip(ours, theirs, strict=True):
        _close(a, b, SCIPY_ORDINARY_ATOL * (1 + np.abs(u)))


@pytest.mark.parametrize("m", [0.2, 0.8, 1 - 1e-12])
def test_adding_the_period_four_K_changes_nothing_and_two_K_flips_sn_and_cn(m):
    K = float(el.ellipk(m))
    u = np.linspace(-1.3, 1.3, 9)
    sn, cn, dn, am = el.ellipj(u, m)
    sn2, cn2, dn2, am2 = el.ellipj(u + 2 * K, m)
    tol = 16 * EPS * (1 + 2 * K)
    _close(sn2, -sn, tol)
    _close(cn2, -cn, tol)
    _close(dn2, dn, tol)
    _close(am2, am + np.pi, tol)


@pytest.mark.parametrize("m", [1.5, 4.0, 100.0])
def test_reciprocal_parameter_transformation_matches_scipy_on_the_other_side(m):
    u = np.linspace(-5, 5, 41)
    sn, cn, dn, _ = el.ellipj(u, m)
    k = np.sqrt(m)
    ssn, scn, sdn, _ = sc.ellipj(k * u, 1 / m)
    tol = SCIPY_ORDINARY_ATOL * (1 + k * np.abs(u))
    _close(sn, ssn / k, tol)
    _close(cn, sdn, tol)
    _close(dn, scn, tol)


@pytest.mark.parametrize("m", [-0.5, -3.0, -200.0])
def test_negative_parameter_transformation_matches_scipy_on_the_other_side(m):
    u = np.linspace(-4, 4, 33)
    sn, cn, dn, _ = el.ellipj(u, m)
    mu = -m / (1 - m)
    v = np.sqrt(1 - m) * u
    ssn, scn, sdn, _ = sc.ellipj(v, mu)
    tol = SCIPY_ORDINARY_ATOL * (1 + np.abs(v)) * np.sqrt(1 - m) / sdn**2
    _close(sn, ssn / (sdn * np.sqrt(1 - m)), tol)
    _close(cn, scn / sdn, tol)
    _close(dn, 1 / sdn, tol)


@pytest.mark.parametrize("m", [-2.0, 0.3, 0.999, 1.0, 3.0])
def test_derivatives_are_cn_dn_and_minus_sn_dn_and_minus_m_sn_cn(m):
    u = np.linspace(-2.1, 2.3, 23)
    h = FD_STEP

    def d(i):
        f = [el.ellipj(u + k * h, m)[i] for k in (-2, -1, 1, 2)]
        return (f[0] - 8 * f[1] + 8 * f[2] - f[3]) / (12 * h)

    sn, cn, dn, _ = el.ellipj(u, m)
    _close(d(0), cn * dn, FD_ATOL * (1 + abs(m)) ** 3)
    _close(d(1), -sn * dn, FD_ATOL * (1 + abs(m)) ** 3)
    _close(d(2), -m * sn * cn, FD_ATOL * (1 + abs(m)) ** 3)
    if m <= 1:
        _close(d(3), dn, FD_ATOL * (1 + abs(m)) ** 3)


@pytest.mark.parametrize("m", [-3.0, 0.0, 0.5, 0.99, 1 - 1e-14])
def test_ellipf_inverts_the_amplitude(m):
    u = np.linspace(-7, 7, 29)
    am = el.ellipj(u, m)[3]
    _close(el.ellipf(am, m), u, 32 * EPS * (1 + np.abs(u)))


def test_ellipk_and_ellipe_agree_with_scipy_and_take_m1():
    m = np.array([-5.0, 0.0, 0.3, 0.9])
    np.testing.assert_allclose(el.ellipk(m), sc.ellipk(m), rtol=4 * EPS)
    np.testing.assert_allclose(el.ellipe(m), sc.ellipe(m), rtol=8 * EPS)
    # with m1 = 1e-200, K = ln(4/√m1) + O(m1 ln m1)
    assert abs(el.ellipk(1.0, m1=1e-200) - np.log(4.0) - 100 * np.log(10.0)) < 1e-12
    assert el.ellipk(1.0) == np.inf
    assert el.ellipe(1.0) == 1.0


def test_ellippi_at_n_zero_is_ellipf_and_jacobi_form_agrees_with_legendre_form():
    phi = np.array([-5.0, -0.4, 0.9, 1.5, 3.0, 8.0])
    np.testing.assert_allclose(el.ellippi(0.0, phi, 0.6), el.ellipf(phi, 0.6), rtol=0, atol=0)
    u = np.linspace(-9, 9, 19)
    for n in (-4.0, 0.3):
        am = el.ellipj(u, 0.6)[3]
        _close(el.ellippi_jacobi(u, n, 0.6), el.ellippi(n, am, 0.6), 64 * EPS * (1 + abs(u)))


def test_ellippi_jacobi_on_the_separatrix_is_the_elementary_closed_form():
    u = np.array([0.0, 0.5, 5.0, 50.0, 900.0])
    n = -2.0
    want = (u + np.sqrt(2.0) * np.arctan(np.sqrt(2.0) * np.tanh(u))) / 3.0
    np.testing.assert_allclose(el.ellippi_jacobi(u, n, 1.0), want, rtol=8 * EPS)
    # and just off it, continuity
    off = el.ellippi_jacobi(u[:4], n, 1.0, m1=1e-300)
    np.testing.assert_allclose(off, want[:4], rtol=64 * EPS)


@pytest.mark.parametrize(
    ("call", "err"),
    [
        (lambda: el.ellipj(np.nan, 0.5), NonFiniteError),
        (lambda: el.ellipj(1.0, np.inf), NonFiniteError),
        (lambda: el.ellipj(1.0, 0.5, m1=np.nan), NonFiniteError),
        (lambda: el.ellipj(1.0, 0.5, m1=0.4), OutOfDomainError),
        (lambda: el.ellipj(1.0 + 0j, 0.5), ShapeError),
        (lambda: el.ellipk(1.5), OutOfDomainError),
        (lambda: el.ellipe(2.0), OutOfDomainError),
        (lambda: el.ellipf(1.4, 2.0), OutOfDomainError),
        (lambda: el.ellipf(np.nan, 0.3), NonFiniteError),
        (lambda: el.ellippi(2.0, 1.0, 0.3), OutOfDomainError),
        (lambda: el.ellippi(0.5, 4.0, 0.3, m1=0.7), None),
        (lambda: el.ellippi_jacobi(1.0, 1.5, 0.3), OutOfDomainError),
        (lambda: el.ellippi_jacobi(1.0, 0.5, 1.3), OutOfDomainError),
    ],
)
def test_bad_input_raises_a_specific_error(call, err):
    if err is None:
        assert np.isfinite(call())
        return
    with pytest.raises(err):
        call()


def test_m1_mismatch_message_names_both_values():
    with pytest.raises(OutOfDomainError, match=r"m = 0\.5, m1 = 0\.4"):
        el.ellipj(1.0, 0.5, m1=0.4)


def test_huge_arguments_stay_finite_or_raise_a_specific_error():
    u = np.array([0.0, 1e10, 1e200, 1e300, -1e300])
    for m in (0.0, 0.7, 1.0):
        assert all(np.isfinite(a).all() for a in el.ellipj(u, m))
    with pytest.raises(OutOfDomainError, match=r"1\.8e308"):
        el.ellipj(1e300, -1e300)
    with pytest.raises(OutOfDomainError, match=r"1\.8e308"):
        el.ellipj(1e300, 1e300)


# ------------------------------------------- every parameter named, every overflow named
#: the condition an unphysical value of each fuzz entry violates (tests.fuzz.entries)
_CONDITIONS = {
    ("ellipe", "m"): r"^ellipe needs m ≤ 1; got m = 1\.5$",
    ("ellipk", "m"): r"^ellipk needs m ≤ 1; got m = 1\.5$",
    ("ellippi_jacobi", "m"): r"^ellippi_jacobi needs 0 ≤ m ≤ 1$",
}


@pytest.mark.parametrize(
    ("fname", "param", "value", "error", "condition"), list(cases("elliptic", _CONDITIONS))
)
def test_every_parameter_of_every_function_is_named_with_the_condition_it_breaks(
    fname, param, value, error, condition
):
    kw = valid_kwargs("elliptic", fname) | {param: value}
    check_refusal(getattr(el, fname), kw, param, error, condition)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        # the first offending value of a batch, printed as a plain float
        (lambda: el.ellipk([0.5, 2.0]), "ellipk needs m ≤ 1; got m = 2.0"),
        (lambda: el.ellipe([0.5, 3.0]), "ellipe needs m ≤ 1; got m = 3.0"),
        (
            lambda: el.ellippi([0.5, 2.0], 1.0, 0.3),
            "the characteristic n must satisfy n sin²φ < 1 (and n < 1 beyond |φ| = π/2); "
            "got n = 2.0",
        ),
        (
            lambda: el.ellippi_jacobi(1.0, [0.5, 1.5], 0.3),
            "the characteristic n must satisfy n sin²φ < 1 (and n < 1 beyond |φ| = π/2); "
            "got n = 1.5",
        ),
    ],
)
def test_a_domain_message_reports_the_first_offending_value_plainly(call, message):
    with pytest.raises(OutOfDomainError) as info:
        call()
    assert str(info.value) == message


@pytest.mark.parametrize(
    ("name", "call"),
    [
        # F ~ φ 2K/π: 1.7e308 · 2K(0.9)/π is beyond float64, though φ itself is not
        ("ellipf", lambda: el.ellipf(1.7e308, 0.9)),
        # F(1e308 | 0.9) = 1.6e308 is finite; Π(0.9; φ | 0.9) > F is not
        ("ellippi", lambda: el.ellippi(0.9, 1.0e308, 0.9)),
    ],
)
def test_an_integral_beyond_float64_is_an_overflow_error_naming_the_function(name, call):
    with pytest.raises(ResultOverflowError) as info:
        call()
    assert str(info.value) == (
        f"{name}: the integral exceeds float64's range (~1.8e308) for an argument this large"
    )


@pytest.mark.parametrize("phi", [0.5, 1.2, -0.7, 1e-3])
def test_ellippi_at_n_one_and_m_zero_is_tan_phi(phi):
    # Π(1; φ | 0) = ∫₀^φ dθ/(1 − sin²θ) = ∫₀^φ sec²θ dθ = tan φ (|φ| < π/2): the R_J tail
    # at n = 1 is the whole difference tan φ − φ
    got = float(el.ellippi(1.0, phi, 0.0))
    assert got == pytest.approx(np.tan(phi), rel=THIRD_KIND_RTOL, abs=0)


def test_two_prod_is_exact_for_the_period_multiples_of_the_argument_reduction():
    # the product elliptic's argument reduction takes from mechanics._floats:
    # a·b = p + e exactly (Dekker), checked in rational arithmetic: a an integer count of
    # periods j (up to 2^40) and b a period 2K or π, as _reduced and _amplitude form them
    rng = np.random.default_rng(SEED)
    a = rng.integers(1, 2**40, size=200).astype(float)
    b = rng.uniform(np.pi, 20.0, size=200)
    p, e = _floats.two_prod_or_zero(a, b)
    wrong = [
        (x, y)
        for x, y, pp, ee in zip(a, b, p, e, strict=True)
        if Fraction(pp) + Fraction(ee) != Fraction(x) * Fraction(y)
    ]
    assert not wrong, wrong[:3]
    for x, y in zip(a[:50], b[:50], strict=True):
        ps, es = _floats.two_prod_or_zero_scalar(float(x), float(y))
        assert Fraction(ps) + Fraction(es) == Fraction(float(x)) * Fraction(float(y)), (x, y)


# -------------------------------------------- one number in, one number out, against mpmath
#
# Python floats and 0-d arrays, as a user calls the functions for one value: each result is
# a float64 of shape () equal, within the stated accuracy, to mpmath at 40 digits (and more
# where m = 1 − m1 must be resolved), in the hard regions: m near 1 through m1, m < 0 and
# m > 1, tiny and large amplitudes, negative amplitudes, n near 1.

#: F, E, K, Π: Carlson's R_F/R_G/R_J (scipy, a few eps each) plus the amplitude reduction
#: φ − jπ, which costs eps·|φ| absolutely (tests/stability: measured ≤ 3 eps)
INTEGRAL_EPS = 64


def _mp_digits(m1):
    return 40 if m1 is None or m1 == 0 or m1 > 1e-20 else 50 + int(-np.log10(m1))


def _scalar_forms(x):
    """A Python float and a 0-d array of it."""
    return (float(x), np.array(float(x)))


def _assert_near(got, ref, phi=0.0, what=""):
    assert np.shape(got) == (), np.shape(got)
    assert np.asarray(got).dtype == np.float64
    err = abs(mpmath.mpf(float(got)) - ref)
    assert err <= INTEGRAL_EPS * EPS * (abs(ref) + abs(phi)), (what, float(got), ref)


#: (φ, m, m1): small and large |φ|, negative φ, m < 0 (down to −1e10), m > 1 (|φ| below
#: asin(1/√m)), m near 1 with and without m1, m = 1 within |φ| < π/2, and the float ±π/2,
#: whose sine rounds to exactly ±1 (F = ±K there, to the rounding of π/2)
ELLIPF_CASES = [
    (1e-8, 0.5, None),
    (0.3, 0.0, None),
    (-0.9, 0.7, None),
    (1.2, -5.0, None),
    (0.8, -1e10, None),
    (7.0, 0.5, None),
    (-100.3, 0.9, None),
    (1e5, 0.2, None),
    (0.5, 2.5, None),
    (-0.6, 1.5, None),
    (1.5, 1.0 - 1e-12, None),
    (1.5707963, 1.0, 1e-300),
    (4.0, 1.0, 1e-300),
    (1.3, 1.0, 0.0),
    (np.pi / 2, 0.5, None),
    (-np.pi / 2, 0.3, None),
    (np.pi / 2, 0.999, None),
]


@pytest.mark.parametrize(("phi", "m", "m1"), ELLIPF_CASES)
def test_ellipf_of_scalars_agrees_with_mpmath(phi, m, m1):
    with mpmath.workdps(_mp_digits(m1)):
        M = mpmath.mpf(m) if m1 is None else 1 - mpmath.mpf(m1)
        ref = mpmath.ellipf(mpmath.mpf(phi), M)
        for p, mm in zip(_scalar_forms(phi), _scalar_forms(m), strict=True):
            kw = {} if m1 is None else {"m1": m1}
            _assert_near(el.ellipf(p, mm, **kw), ref, phi, (phi, m, m1))


@pytest.mark.parametrize(
    ("m", "m1"),
    [(0.0, None), (0.5, None), (-3.0, None), (-1e10, None), (1 - 1e-12, None), (1.0, 1e-300)],
)
def test_ellipk_and_ellipe_of_scalars_agree_with_mpmath(m, m1):
    kw = {} if m1 is None else {"m1": m1}
    with mpmath.workdps(_mp_digits(m1)):
        M = mpmath.mpf(m) if m1 is None else 1 - mpmath.mpf(m1)
        for mm in _scalar_forms(m):
            _assert_near(el.ellipk(mm, **kw), mpmath.ellipk(M), what=("K", m, m1))
            _assert_near(el.ellipe(mm, **kw), mpmath.ellipe(M), what=("E", m, m1))


#: (n, φ, m, m1): n near 1 inside |φ| < π/2 and beyond it (Π(n|m) ~ 1/√(1 − n) large),
#: n ≪ 0, n sin²φ just below 1, φ large and negative with j ≠ 0, m < 0 (down to −1e300,
#: where R_J's arguments are scaled into its range), m > 1, m near 1, m = 1
ELLIPPI_CASES = [
    (1 - 1e-9, 1.2, 0.5, None),
    (1 - 1e-9, 4.0, 0.5, None),
    (0.99, -7.5, 0.3, None),
    (-50.0, 2.0, 0.5, None),
    (-0.5, -30.0, 0.8, None),
    (1.0, 0.7, 0.2, None),
    (1.5, 0.6, 0.3, None),
    (0.4, 1.1, -4.0, None),
    (-2.0, 0.5, 2.0, None),
    (0.5, 1.3, 1.0 - 1e-12, None),
    (-3.0, 5.0, 1.0, 1e-300),
    (0.7, 1e-6, 0.6, None),
    (0.0, 0.5, 1.0, None),
    (-2.0, 1.2, 1.0, None),
    (0.4, 1.1, -1e300, None),
    (-3.0, -0.7, -1e200, None),
    (0.5, -1.0, 1.0, None),
]


@pytest.mark.parametrize(("n", "phi", "m", "m1"), ELLIPPI_CASES)
def test_ellippi_of_scalars_agrees_with_mpmath(n, phi, m, m1):
    kw = {} if m1 is None else {"m1": m1}
    with mpmath.workdps(_mp_digits(m1)):
        M = mpmath.mpf(m) if m1 is None else 1 - mpmath.mpf(m1)
        ref = mpmath.ellippi(mpmath.mpf(n), mpmath.mpf(phi), M)
        for nn, p in zip(_scalar_forms(n), _scalar_forms(phi), strict=True):
            _assert_near(el.ellippi(nn, p, m, **kw), ref, phi, (n, phi, m, m1))


def _separatrix_excess(u, n):
    """∫₀^u n tanh²v / (1 − n tanh²v) dv by mpmath's quadrature (sn = tanh at m = 1)."""
    f = lambda v: n * mpmath.tanh(v) ** 2 / (1 - n * mpmath.tanh(v) ** 2)  # noqa: E731
    pts = [0, u] if abs(u) <= 5 else [0, mpmath.sign(u) * 5, u]
    return mpmath.quad(f, pts)


@pytest.mark.parametrize("n", [-3.0, -1.0, -0.25, 0.5, 0.9])
@pytest.mark.parametrize("u", [0.7, -2.5, 40.0, -300.0])
def test_ellippi_jacobi_on_the_separatrix_agrees_with_quadrature_for_either_sign_of_n(u, n):
    # m = 1: the closed form takes atan for n < 0 and atanh for 0 < n < 1 (both evaluated:
    # at n = −1 and tanh u = ±1 exactly, the unused atanh(±1) is infinite, without a warning)
    with mpmath.workdps(40):
        ref = mpmath.mpf(u) + _separatrix_excess(mpmath.mpf(u), mpmath.mpf(n))
        for uu, nn in zip(_scalar_forms(u), _scalar_forms(n), strict=True):
            got = el.ellippi_jacobi(uu, nn, 1.0)
            assert np.shape(got) == ()
            # the formula adds n u and √|n| atan(√|n| tanh u), each within an ulp, over 1 − n
            tol = 8 * EPS * (abs(ref) + abs(u * n / (1 - n)))
            assert abs(mpmath.mpf(float(got)) - ref) <= tol, (u, n, float(got), ref)


@pytest.mark.parametrize("n", [-2.0, -0.25, 0.0, 0.5])
def test_ellippi_at_m_one_beyond_a_quarter_turn_is_infinite_with_the_sign_of_phi(n):
    # Π(n|1) = ∫₀^{π/2} dθ / ((1 − n sin²θ) cos θ) = +inf for every n < 1, so by
    # Π(φ + jπ) = Π(φ) + 2jΠ(n|1) the value beyond |φ| = π/2 is ±inf: not NaN (for n < 0,
    # Π − K = −inf against F's +inf), and without a warning (the suite turns one into an error)
    phi = np.array([4.0, -4.0, 10.0, 1.2])
    got = el.ellippi(n, phi, 1.0)
    np.testing.assert_array_equal(got[:3], [np.inf, -np.inf, np.inf])
    with mpmath.workdps(40):
        ref = mpmath.ellippi(n, 1.2, 1)
    assert abs(mpmath.mpf(float(got[3])) - ref) <= INTEGRAL_EPS * EPS * abs(ref)
    np.testing.assert_array_equal(el.ellipf(phi[:3], 1.0), [np.inf, -np.inf, np.inf])


@pytest.mark.parametrize(
    ("call", "message"),
    [
        # the first offending element of a batch, its values printed as plain floats
        (
            lambda: el.ellipj([1.0, 1e300], 1e300),
            "ellipj needs |u|·√max(|m|, 1 − m) < 1.8e308 for the modulus transformation; "
            "got u = 1e+300 with scale 1e+150",
        ),
        (
            lambda: el.ellipj([1.0, 1e300], -1e300),
            "ellipj needs |u|·√max(|m|, 1 − m) < 1.8e308 for the modulus transformation; "
            "got u = 1e+300 with scale 1e+150",
        ),
        (
            lambda: el.ellipk([0.5, 0.25], m1=[0.5, 0.5]),
            "m1 must equal 1 − m to rounding; got m = 0.25, m1 = 0.5 (m + m1 − 1 = 0.25)",
        ),
        (
            lambda: el.ellipf([0.1, 1.4], 2.0),
            "ellipf needs m sin²φ ≤ 1 (real integrand); got m = 2.0, φ = 1.4",
        ),
        (
            lambda: el.ellippi(0.1, [0.2, 1.4], [2.0, 1.5]),
            "ellippi needs m sin²φ ≤ 1 (real integrand); got m = 1.5, φ = 1.4",
        ),
        (
            lambda: el.ellipf(3.0, 1.5),
            "ellipf for m > 1 needs |φ| ≤ asin(1/√m) < π/2; got larger φ",
        ),
        (
            lambda: el.ellippi(-1.0, -3.0, 1.5),
            "ellippi for m > 1 needs |φ| ≤ asin(1/√m) < π/2; got larger φ",
        ),
        (lambda: el.ellippi_jacobi(1.0, 0.5, -0.5), "ellippi_jacobi needs 0 ≤ m ≤ 1"),
        (
            # the documented domain n < 1, at its edge
            lambda: el.ellippi_jacobi(0.5, [0.5, 1.0], 0.3),
            "the characteristic n must satisfy n sin²φ < 1 (and n < 1 beyond |φ| = π/2); "
            "got n = 1.0",
        ),
        (
            lambda: el.ellippi([0.5, 1.0], 4.0, 0.3),
            "the characteristic n must satisfy n sin²φ < 1 (and n < 1 beyond |φ| = π/2); "
            "got n = 1.0",
        ),
    ],
)
def test_each_domain_refusal_names_its_condition_and_the_offending_values(call, message):
    with pytest.raises(OutOfDomainError) as info:
        call()
    assert str(info.value) == message


def test_an_integral_in_jacobis_form_beyond_float64_is_an_overflow_error():
    # u + G(u) ~ u/(1 − n) = 10 u for n = 0.9: beyond float64 for u = ±1.7e308, on and off
    # the separatrix; an error naming the function, not a numpy warning
    for u, m in ((1.7e308, 0.5), (-1.7e308, 1.0)):
        with pytest.raises(ResultOverflowError) as info:
            el.ellippi_jacobi(u, 0.9, m)
        assert str(info.value) == (
            "ellippi_jacobi: the integral exceeds float64's range (~1.8e308) for an argument "
            "this large"
        )


def test_m1_within_8_eps_of_one_minus_m_is_accepted_and_beyond_refused():
    # the tolerance of "m1 = 1 − m to rounding": 8 eps of max(1, |m|, |m1|); at m = 1/2,
    # m1 = 1/2 + 8 eps (exactly 8 eps off, 16 ulps of 1/2) is accepted, 1/2 + 9 eps is not
    ok = 0.5 + 8 * EPS
    assert (0.5 - 1.0) + ok == 8 * EPS
    # accepted: K of m = 1 − m1, to the accuracy of the complete integrals
    with mpmath.workdps(40):
        want = mpmath.ellipk(1 - mpmath.mpf(ok))
    assert abs(mpmath.mpf(float(el.ellipk(0.5, m1=ok))) - want) <= 8 * EPS * want
    with pytest.raises(OutOfDomainError, match=r"m1 must equal 1 − m to rounding"):
        el.ellipk(0.5, m1=0.5 + 9 * EPS)


#: F and Π at large amplitudes: φ = jπ + r with jπ formed exactly (Dekker's product and the
#: tail of π beyond fl(π) carried), so the error stays a few eps of the value, not eps·|φ|
#: (measured ≤ 1.2 eps up to |φ| = 1e15)
LARGE_AMPLITUDE_EPS = 8


@pytest.mark.parametrize("phi", [100.3, -3.3e7, 1e10, -1e15])
@pytest.mark.parametrize("m", [0.2, 0.9, -5.0])
def test_integrals_at_large_amplitudes_keep_their_relative_accuracy(phi, m):
    with mpmath.workdps(60):
        refs = (mpmath.ellipf(mpmath.mpf(phi), m), mpmath.ellippi(0.5, mpmath.mpf(phi), m))
    for got, ref in zip((el.ellipf(phi, m), el.ellippi(0.5, phi, m)), refs, strict=True):
        assert abs(mpmath.mpf(float(got)) - ref) <= LARGE_AMPLITUDE_EPS * EPS * abs(ref), (
            float(got),
            ref,
        )


@pytest.mark.parametrize("j", [3, 1000, 318310])
@pytest.mark.parametrize("m", [-1e10, -1e4])
def test_integrals_at_a_float_multiple_of_pi_keep_the_tail_of_pi(j, m):
    # φ = fl(jπ): the reduced amplitude r = φ − jπ is tiny, where dF/dφ = 1, while
    # F ≈ 2jK is small for m ≪ −1 (K ~ ln(4√−m)/√−m): the 2j·1.2e-16 by which fl(π) misses π
    # is thousands of eps of F here, so it must be carried
    with mpmath.workdps(60):
        phi = float(j * mpmath.pi)
        refs = (mpmath.ellipf(mpmath.mpf(phi), m), mpmath.ellippi(-2.0, mpmath.mpf(phi), m))
    for got, ref in zip((el.ellipf(phi, m), el.ellippi(-2.0, phi, m)), refs, strict=True):
        assert abs(mpmath.mpf(float(got)) - ref) <= LARGE_AMPLITUDE_EPS * EPS * abs(ref), (
            float(got),
            ref,
        )


def test_an_amplitude_on_the_edge_of_the_real_domain_is_accepted_for_m_above_one():
    # m > 1: the integrand is real up to sin φ = 1/√m, where Δ = 0. This (φ, m) pair of floats
    # has cos²φ + (1 − m) sin²φ = 0 exactly in float arithmetic: on the edge, inside the domain.
    # There F = K(1/m)/√m (reciprocal modulus, DLMF 19.7.4 with β = π/2).
    phi, m = 0.3, 11.450531251495654
    s, c = math.sin(phi), math.cos(phi)
    assert c * c + (1.0 - m) * (s * s) == 0.0
    with mpmath.workdps(40):
        want = mpmath.ellipk(1 / mpmath.mpf(m)) / mpmath.sqrt(mpmath.mpf(m))
    got = el.ellipf(phi, m)
    assert abs(mpmath.mpf(float(got)) - want) <= INTEGRAL_EPS * EPS * want
    assert np.isfinite(el.ellippi(0.3, phi, m))


# ------------------------------------------------ edges of the domains and of float64
@pytest.mark.parametrize(
    ("call", "message"),
    [
        # m1 is named in its own refusal (not "m", not another name)
        (lambda: el.ellipj(1.0, 0.5, m1=np.nan), "m1 must be finite; found nan at index ()"),
        (lambda: el.ellipk(0.5, m1=[0.5, np.inf]), "m1 must be finite; found inf at index (1,)"),
        # the batch's offending element is the one beyond its own tolerance: m = −1e10 with
        # m1 = 1e10 + 1 is exact (its tolerance, 8 eps · 1e10 ≈ 1.8e-5, is the larger), the
        # second pair is 1e-10 off where 8 eps ≈ 1.8e-15 is allowed
        (
            lambda: el.ellipk([-1e10, 0.5], m1=[1e10 + 1.0, 0.5 + 1e-10]),
            "m1 must equal 1 − m to rounding; got m = 0.5, m1 = 0.5000000001 (m + m1 − 1 = 1e-10)",
        ),
        # m = 1 is inside the domain: the message names the first m > 1, not the first m ≥ 1
        (lambda: el.ellipk([1.0, 2.0]), "ellipk needs m ≤ 1; got m = 2.0"),
        (lambda: el.ellipe([1.0, 3.0]), "ellipe needs m ≤ 1; got m = 3.0"),
        # n sin²φ = 1 exactly (sin(fl(π/2)) rounds to 1): the integrand's pole, refused
        (
            lambda: el.ellippi(1.0, np.pi / 2, 0.3),
            "the characteristic n must satisfy n sin²φ < 1 (and n < 1 beyond |φ| = π/2); "
            "got n = 1.0",
        ),
    ],
)
def test_refusals_at_the_edges_name_the_right_parameter_and_element(call, message):
    with pytest.raises((OutOfDomainError, NonFiniteError)) as info:
        call()
    assert str(info.value) == message


def test_the_m1_tolerance_scales_with_the_size_of_m():
    # "m1 = 1 − m to rounding": within 8 eps · max(1, |m|, |m1|). At m = −1000, m1 = 1001:
    # 8 eps · 1001 = 15.6 ulps of 1001 (ulp = 2⁻⁴³), so 15 ulps off is accepted, 16 refused
    ulp = math.ulp(1001.0)
    assert 15 * ulp <= 8 * EPS * 1001 < 16 * ulp
    with mpmath.workdps(40):
        want = mpmath.ellipk(1 - (mpmath.mpf(1001) + 15 * mpmath.mpf(ulp)))
    got = el.ellipk(-1000.0, m1=1001.0 + 15 * ulp)
    assert abs(mpmath.mpf(float(got)) - want) <= INTEGRAL_EPS * EPS * want
    with pytest.raises(OutOfDomainError, match=r"m1 must equal 1 − m to rounding"):
        el.ellipk(-1000.0, m1=1001.0 + 16 * ulp)


@pytest.mark.parametrize("u", [0.3, -1.2, 1.5])
@pytest.mark.parametrize("n", [-2.0, 0.5])
def test_ellippi_jacobi_at_m_zero_is_the_elementary_integral(u, n):
    # m = 0 is inside the domain 0 ≤ m ≤ 1: sn = sin, and for |u| < π/2
    # ∫₀^u dv/(1 − n sin²v) = atan(√(1 − n) tan u)/√(1 − n) (substitute t = tan v)
    with mpmath.workdps(40):
        k = mpmath.sqrt(1 - mpmath.mpf(n))
        want = mpmath.atan(k * mpmath.tan(mpmath.mpf(u))) / k
    got = el.ellippi_jacobi(u, n, 0.0)
    assert abs(mpmath.mpf(float(got)) - want) <= INTEGRAL_EPS * EPS * abs(want)


@pytest.mark.parametrize("u", [400.0, -500.0, 700.0])
def test_ellipj_at_m_one_where_sech_squared_underflows_is_quiet_and_hyperbolic(u):
    # m = 1, 373 ≲ |u| < 710: sech u (~1e-162 … 1e-305) is a normal float but sech²u underflows,
    # so dn = √(m1 + m cn²) is 0 and the unused branch cn/dn divides by zero: no warning (the
    # suite turns one into an error), sn = tanh u, cn = sech u to the stated accuracy
    sn, cn, _, am = el.ellipj(u, 1.0)
    with mpmath.workdps(40):
        sech = mpmath.sech(mpmath.mpf(u))
        # the conditioned error scale of cn: eps (|cn| + |u cn'|), cn' = −sn dn = −tanh·sech
        scale = EPS * (sech + abs(u) * sech)
    assert float(sn) == math.copysign(1.0, u)
    assert abs(mpmath.mpf(float(cn)) - sech) <= el.ELLIPJ_EPS * scale
    assert float(am) == pytest.approx(math.copysign(math.pi / 2, u), rel=4 * EPS)


def test_dn_at_m_one_is_sech_where_sech_squared_underflows():
    # DLMF 22.5.ii: at m = 1, cn = dn = sech u (the docstring of ellipj says so)
    # (a library bug until issue 35's elliptic review: dn = √(m1 + m cn²) underflowed to 0
    # once sech²u left float64's range, |u| ≳ 355)
    for u in (300.0, 360.0, 500.0, 700.0, -650.0):
        _, cn, dn, _ = el.ellipj(u, 1.0)
        with mpmath.workdps(40):
            sech = mpmath.sech(mpmath.mpf(u))
        assert abs(mpmath.mpf(float(dn)) - sech) <= el.ELLIPJ_EPS * EPS * (1 + abs(u)) * sech, u
        assert float(dn) == float(cn), u


def test_third_kind_at_n_zero_is_the_first_kind_where_scipys_rj_fails():
    # Π(0; φ|m) = F(φ|m) and ∫₀^u dv = u (n = 0), also where the R_J of the tail is not
    # finite and only its factor n = 0 makes the tail 0:
    # - m = −1e300, beyond |φ| = π/2: the complete tail's R_J(0, 1e300, 1, 1) is NaN in scipy;
    # - m1 = 5e-324 at u = 373, just below K ≈ 373.6: cn² and dn² underflow, R_J(0, 0, 1, 1) = inf
    for phi in (2.0, 4.0, -7.0):
        assert el.ellippi(0.0, phi, -1e300) == el.ellipf(phi, -1e300)
    assert el.ellippi_jacobi(373.0, 0.0, 1.0, m1=5e-324) == 373.0
    assert el.ellippi_jacobi(-373.0, 0.0, 1.0, m1=1e-320) == -373.0


def test_ellippi_of_a_hugely_negative_parameter_beyond_a_quarter_turn_is_finite():
    with mpmath.workdps(40):
        want = mpmath.ellippi(0.5, 4.0, -1e300)  # 1.0413e-147
    got = el.ellippi(0.5, 4.0, -1e300)
    assert abs(mpmath.mpf(float(got)) - want) <= INTEGRAL_EPS * EPS * abs(want)


@pytest.mark.parametrize("m", [-1e200, -1e250, -1.7e308])
@pytest.mark.parametrize("n", [-3.0, 0.9])
@pytest.mark.parametrize("phi", [2.0, -7.0])
def test_ellippi_beyond_a_quarter_turn_across_the_hugely_negative_parameters(m, n, phi):
    # the complete tail scales R_J's arguments by 1/√m1 (homogeneity, degree −3/2); unscaled,
    # scipy's elliprj(0, m1, 1, 1 − n) is NaN from m1 ~ 1e200 and the value was refused as
    # an overflow (measured after: 1.4 eps at worst over m ∈ {−1e200, −1e250, −1e300,
    # −1.7e308}, n ∈ {−3, 0.5, 0.9}, φ ∈ {2, 4, −7})
    with mpmath.workdps(40):
        want = mpmath.ellippi(n, phi, m)
    got = el.ellippi(n, phi, m)
    assert abs(mpmath.mpf(float(got)) - want) <= INTEGRAL_EPS * EPS * abs(want)
