"""Hard cases of :mod:`mechanics.elliptic` against mpmath (50 digits), errors in eps.

How the errors are measured
---------------------------
The reference takes the float inputs u, m (and m1 where given) as exact binary
numbers.  For f ∈ {sn, cn, dn, am} the error is

    |f − f*| / (eps · (|f*| + |u · f*'(u)|) + 2⁻¹⁰²²),

the size of the change of f when u is rounded: a relative error where f is
well conditioned, the unavoidable phase error u·eps at large u, and absolute
below the underflow threshold.  (f' = cn dn, −sn dn, −m sn cn, dn.)  The promise
is :data:`mechanics.elliptic.ELLIPJ_EPS` = 64 eps for every m.

Data: ``tests/data/elliptic_reference.json`` from ``tools/make_elliptic_reference.py``
(m from −1e10 to 1e10, m1 down to 1e-300, u up to 1e4), and a hypothesis search
with in-test mpmath values that targets the worst error.  Measured worst: see
the module :mod:`mechanics.elliptic` and the report printed by
``pytest -s tests/stability/test_elliptic_stability.py``.

scipy's ``ellipj`` is measured in the same metric in 1 − 1e-4 ≤ m < 1 (where it
returns values off by far more than 64 eps: the documented problem this module
avoids) and is undefined (NaN) outside 0 ≤ m ≤ 1.
"""

from __future__ import annotations

import importlib.util
import json
import math
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
import pytest
import scipy.special as sc
from hypothesis import example, given, target
from hypothesis import strategies as st

from mechanics import _floats
from mechanics import elliptic as el
from mechanics._floats import EPS
from mechanics.errors import OutOfDomainError

TINY = 2.0**-1022
DATA = Path(__file__).resolve().parent.parent / "data" / "elliptic_reference.json"
TOOL = Path(__file__).resolve().parent.parent.parent / "tools" / "make_elliptic_reference.py"

# Complete integrals: scipy's ellipkm1 and Carlson's R_G each round a handful of
# operations; measured ≤ 1 eps relative.
COMPLETE_RTOL_EPS = 8.0

# Incomplete integrals: R_F/R_J rounding plus the amplitude reduction φ − jπ, which
# costs eps·|φ| absolutely (|dF/dφ| ≤ 1/k' ... measured ≤ 3 eps on this grid).
INCOMPLETE_EPS = 64.0


def _load():
    return json.loads(DATA.read_text())


def _err_eps(f, ref, u, dref):
    """Error in the conditioned metric of the module docstring (mpmath arithmetic)."""
    scale = EPS * (abs(ref) + abs(mpmath.mpf(u) * dref)) + TINY
    return float(abs(mpmath.mpf(float(f)) - ref) / scale)


def _errors(u, m, m1, fs, refs):
    sn, cn, dn, _ = refs
    M = 1 - mpmath.mpf(m1) if m1 is not None else mpmath.mpf(m)
    derivs = (cn * dn, -sn * dn, -M * sn * cn, dn)
    return [_err_eps(f, r, u, d) for f, r, d in zip(fs, refs, derivs, strict=True)]


def test_reference_file_is_what_the_committed_script_writes():
    """Recompute a slice of the ellipj table with the script and compare the strings."""
    spec = importlib.util.spec_from_file_location("make_elliptic_reference", TOOL)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    data = _load()
    with mpmath.workdps(mod.DPS):
        for case in data["ellipj"][::23]:
            m1 = None if case["m1"] is None else float(case["m1"])
            again = mod._ellipj_case(float(case["u"]), float(case["m"]), m1)
            assert again == case


def test_ellipj_within_64_eps_of_mpmath_for_every_parameter_range():
    data = _load()
    worst = {}
    with mpmath.workdps(60):
        for case in data["ellipj"]:
            u, m = float(case["u"]), float(case["m"])
            m1 = None if case["m1"] is None else float(case["m1"])
            refs = [mpmath.mpf(case[k]) for k in ("sn", "cn", "dn", "am")]
            fs = el.ellipj(u, m, m1=m1)
            errs = _errors(u, m, m1, fs, refs)
            key = f"m={case['m']}" + ("" if m1 is None else f", m1={case['m1']}")
            worst[key] = max(worst.get(key, 0.0), *errs)
    print("\nellipj worst error (eps, conditioned) per parameter:")  # shown with -s
    for k, v in worst.items():
        print(f"  {k:28s} {v:7.2f}")
    assert max(worst.values()) <= el.ELLIPJ_EPS, worst


def test_scipy_ellipj_fails_just_below_m_one_where_ours_holds():
    """The measurement behind the complementary-parameter route (issue 4)."""
    with mpmath.workdps(60):
        u = np.array([0.3, 5.0, 12.0, 25.0])
        worst_scipy = worst_ours = 0.0
        for m1 in (1e-6, 1e-9, 1e-10, 1e-12, 1e-13, 1e-15):
            m = 1.0 - m1
            m1 = 1.0 - m  # the exact complement of the float m
            ss = sc.ellipj(u, m)
            oo = el.ellipj(u, m, m1=m1)
            for i, uu in enumerate(u):
                M = mpmath.mpf(m)
                refs = [mpmath.ellipfun(f, mpmath.mpf(uu), m=M) for f in ("sn", "cn", "dn")]
                K = mpmath.ellipk(M)
                a = mpmath.atan2(refs[0], refs[1])
                refs.append(
                    a
                    + 2 * mpmath.pi * mpmath.nint((mpmath.pi * uu / (2 * K) - a) / (2 * mpmath.pi))
                )
                worst_scipy = max(worst_scipy, *_errors(uu, m, None, [f[i] for f in ss], refs))
                worst_ours = max(worst_ours, *_errors(uu, m, None, [f[i] for f in oo], refs))
    print(  # shown with -s
        f"\n1-1e-6 ≥ m ≥ 1-1e-15: scipy ellipj worst {worst_scipy:.3g} eps, ours "
        f"{worst_ours:.3g} eps"
    )
    assert worst_ours <= el.ELLIPJ_EPS
    assert worst_scipy > 1e3 * el.ELLIPJ_EPS


def test_complete_integrals_against_mpmath():
    for case in _load()["complete"]:
        m = float(case["m"])
        m1 = None if case["m1"] is None else float(case["m1"])
        K, E = el.ellipk(m, m1=m1), el.ellipe(m, m1=m1)
        for got, ref in ((K, case["K"]), (E, case["E"])):
            r = mpmath.mpf(ref)
            assert float(abs(mpmath.mpf(float(got)) - r) / (EPS * r)) <= COMPLETE_RTOL_EPS, case


def test_incomplete_integrals_against_mpmath():
    worst = 0.0
    for case in _load()["incomplete"]:
        phi, n, m = float(case["phi"]), float(case["n"]), float(case["m"])
        m1 = None if case["m1"] is None else float(case["m1"])
        F = el.ellipf(phi, m, m1=m1)
        P = el.ellippi(n, phi, m, m1=m1)
        for got, ref in ((F, case["F"]), (P, case["Pi"])):
            r = mpmath.mpf(ref)
            # relative, plus the eps·|φ|·Δ⁻¹ of the rounded amplitude (Δ ≥ k' ≥ 1e-150 here
            # only at φ ≈ π/2, where the reference φ is the same float)
            e = float(abs(mpmath.mpf(float(got)) - r) / (EPS * (abs(r) + abs(phi))))
            worst = max(worst, e)
    assert worst <= INCOMPLETE_EPS


M1_EXPONENTS = st.integers(min_value=1, max_value=300)


@st.composite
def hard_parameters(draw):
    """(u, m, m1) over the regimes: near m = 1 through m1, large |m| both signs, ordinary."""
    regime = draw(st.sampled_from(["near one", "ordinary", "large negative", "above one"]))
    # |u| ≥ 1e-8: mpmath's theta-function route has an absolute error ~10^-dps, which
    # a relative measure at |u| → 0 would charge to us (u = 1e-10 is in the data file)
    u = draw(st.sampled_from([-1.0, 1.0])) * draw(st.floats(min_value=1e-8, max_value=200.0))
    if regime == "near one":
        k = draw(M1_EXPONENTS)
        mant = draw(st.floats(min_value=1.0, max_value=9.99))
        m1 = mant * 10.0**-k
        return u, 1.0 - m1, m1
    if regime == "ordinary":
        return u, draw(st.floats(min_value=0.0, max_value=1.0)), None
    if regime == "large negative":
        return u, -(10.0 ** draw(st.floats(min_value=-15, max_value=8))), None
    return u, 1.0 + 10.0 ** draw(st.floats(min_value=-15, max_value=8)), None


@given(hard_parameters())
@example((25.0, 1.0 - 1e-12, 1e-12))
@example((-173.0, 1.0, 1e-300))
@example((0.5, -1e8, None))
@example((3.0, 1.0 + 1e-15, None))
def test_ellipj_hypothesis_search_stays_within_64_eps(params):
    u, m, m1 = params
    m1v = 1.0 - m if m1 is None else m1
    dps = 40 if m1v == 0 or abs(m1v) > 1e-20 else 40 + int(-np.log10(abs(m1v))) + 10
    with mpmath.workdps(dps):
        M = 1 - mpmath.mpf(m1) if m1 is not None else mpmath.mpf(m)
        U = mpmath.mpf(u)
        refs = [mpmath.re(mpmath.ellipfun(f, U, m=M)) for f in ("sn", "cn", "dn")]
        fs = el.ellipj(u, m, m1=m1)[:3]
        errs = [
            _err_eps(f, r, u, d)
            for f, r, d in zip(
                fs,
                refs,
                (refs[1] * refs[2], -refs[0] * refs[2], -M * refs[0] * refs[1]),
                strict=True,
            )
        ]
    target(max(errs), label="ellipj error in eps")
    assert max(errs) <= el.ELLIPJ_EPS, (params, errs)


# ------------------------------------------ the kernels one float at a time (issue 15)
#
# The free top evaluates one instant through the scalar kernels (``_*_scalar``), the
# hyperbolic amplitude recurrence through ``_asinh_r_sinh``.  Each is checked here on
# its own against mpmath, in every branch: ψ on both sides of 350 and of the overflow
# of cosh, r = 0, both AGM forms and their stopping rule, the period reduction with
# j ≠ 0 and the quarter-period flip, and the separatrix m = 1 (K = inf) in closed form.

#: asinh(r sinh ψ) formed directly (ψ ≤ 350): sinh (1 ulp), the product (½ ulp), asinh
#: (1 ulp; its condition number x asinh'(x)/asinh(x) is ≤ 1): within 4 eps relative
ASINH_DIRECT_EPS = 4.0
#: ψ > 350 through log y = log r + ψ − log 2: three roundings of terms of size ≤ |log r| + ψ,
#: an absolute error of log y that exp turns into a relative one (f < 1) and that
#: log y + log 2 keeps absolute (f > 1): 2 eps (|log r| + ψ + 1) min(1, f), plus the final rounding
ASINH_LOG_EPS = 2.0
#: a_N: six arithmetic-geometric means, each a mean of values already within a few ulps
#: (a mean does not amplify a relative error), one rounding each: within 8 eps
AGM_A_EPS = 8.0
#: c_{n+1} = c_n²/(4 a_{n+1}) doubles the relative error of c_n and adds 2 roundings, so
#: c_n/a_n is within (2^n · 3 + 1) eps: 4 · 2^n eps bounds it
AGM_RATIO_EPS = 4.0


def _mpf(x):
    return mpmath.mpf(float(x))


def _asinh_tolerance(r, psi, ref):
    """The error bound of _asinh_r_sinh's branch for (r, ψ), in mpmath."""
    if psi <= 350.0:
        return ASINH_DIRECT_EPS * EPS * abs(ref)
    log_r = abs(mpmath.log(r)) if r > 0 else 0
    return ASINH_LOG_EPS * EPS * ((log_r + psi + 1) * min(1, abs(ref)) + abs(ref)) + TINY


#: (r, ψ): the direct branch up to ψ = 350 (its boundary), tiny r where the log route would
#: cost 20–30 eps; beyond it the huge branch (log y > 40) and the small one (asinh(e^{log y})),
#: and r = 0, as the AGM gives at m = 1
ASINH_CASES = [
    (0.3, 1.0),
    (1e-3, 20.0),
    (0.7, 1e-9),
    (1.0, 0.0),
    (0.9, 349.5),
    (0.3, 350.0),
    (1e-160, 350.0),
    (3e-160, 350.0),
    (0.3, 350.5),
    (0.3, 400.0),
    (1e-12, 700.0),
    (1e-140, 360.0),
    (2e-149, 390.0),
    (1e-300, 351.0),
    (0.0, 400.0),
    # log y = 40.5, between the huge branch's switch (40) and 41: log y + log 2 there
    (3.5e-139, 360.0),
    # log y ≈ 799, beyond exp's range (709.8): only the huge branch can evaluate it
    (0.5, 800.0),
]


def _asinh_reference(r, psi):
    with mpmath.workdps(60):
        return mpmath.asinh(_mpf(r) * mpmath.sinh(_mpf(psi)))


@pytest.mark.parametrize(("r", "psi"), ASINH_CASES)
def test_asinh_r_sinh_of_one_float_is_within_its_branch_bound_of_mpmath(r, psi):
    ref = _asinh_reference(r, psi)
    got = el._asinh_r_sinh_scalar(r, psi)
    assert isinstance(got, float)
    assert abs(mpmath.mpf(got) - ref) <= _asinh_tolerance(r, psi, ref), (r, psi, got, ref)


def test_asinh_r_sinh_of_arrays_mixing_both_branches_is_within_their_bounds_of_mpmath():
    # one call with ψ on both sides of 350 (np.where picks per element), and one with
    # every ψ ≤ 350 (the early return)
    for cases in (ASINH_CASES, [c for c in ASINH_CASES if c[1] <= 350.0]):
        r = np.array([c[0] for c in cases])
        psi = np.array([c[1] for c in cases])
        got = el._asinh_r_sinh(r, psi)
        assert got.shape == r.shape
        for (rr, pp), g in zip(cases, got, strict=True):
            ref = _asinh_reference(rr, pp)
            assert abs(mpmath.mpf(float(g)) - ref) <= _asinh_tolerance(rr, pp, ref), (rr, pp, g)


def _agm_reference(p1_exact, hyper, ymax):
    """a_n and c_n/a_n of AGM(1, √p1) (trig, c₀ = √p) or AGM(1, √p) (hyperbolic, c₀ = √p1),
    by the definition c_{n+1} = (a_n − b_n)/2, at a precision that resolves p = 1 − p1;
    and the number of steps the documented rule takes: the first n with
    (c_n/a_n) · exp(min(2ⁿ a_n y_max, 700)) < 2⁻⁶⁴ (the exp only in hyperbolic form), ≤ 6."""
    digits = 1300  # resolves (a − b)/2 down to the 1e-1200 of the deepest step compared
    with mpmath.workdps(digits):
        p1 = mpmath.mpf(p1_exact)
        p = 1 - p1
        a, b = mpmath.mpf(1), mpmath.sqrt(p if hyper else p1)
        a_s, ratios = [], []
        for _ in range(el._N_AGM):
            a, b, c = (a + b) / 2, mpmath.sqrt(a * b), (a - b) / 2
            a_s.append(a)
            ratios.append(c / a)
        steps = el._N_AGM
        for n in range(1, el._N_AGM + 1):
            grow = mpmath.exp(min(2**n * a_s[n - 1] * ymax, 700)) if hyper else 1
            if ratios[n - 1] * grow < mpmath.mpf(2) ** -64:
                steps = n
                break
    return a_s, ratios, steps


#: (p, p1, hyperbolic, y_max) with p1 = 1 − p exact (dyadic, or p = 1 to rounding with the
#: tiny p1 authoritative); hyperbolic form for p > 1/2, where it takes longer for large y_max
AGM_CASES = [
    (0.3125, 0.6875, False, 0.0),
    (0.5, 0.5, False, 0.0),
    (0.0, 1.0, False, 0.0),
    (0.75, 0.25, True, 0.4),
    (0.75, 0.25, True, 3.0),
    (1 - 2.0**-30, 2.0**-30, True, 10.0),
    (1.0, 2.0**-996, True, 170.0),
    (0.5009765625, 0.4990234375, True, 300.0),
    # y_max where the growth e^{2ⁿ a_n y_max} decides between 5 and 6 steps (2 bits of margin)
    (0.625, 0.375, True, 0.325),
    (0.75, 0.25, True, 0.575),
    # p1 = 2⁻¹⁰⁷²: a₁ = 1 and c₁ = p1/4 = 2⁻¹⁰⁷⁴ (the smallest subnormal), and 2 a₁ y_max = 800
    # caps the growth at e^700: 2⁻¹⁰⁷⁴ e^700 = 5.0e-20 < 2⁻⁶⁴ = 5.4e-20 stops after one step
    # (e^701 would not)
    (1.0, 2.0**-1072, True, 400.0),
]


def _check_agm(a, ratios, case):
    _, p1, hyper, ymax = case
    a_s, refs, steps = _agm_reference(p1, hyper, ymax)
    assert len(ratios) == steps, (case, len(ratios), steps)
    assert abs(mpmath.mpf(float(a)) - a_s[steps - 1]) <= AGM_A_EPS * EPS * a_s[steps - 1], case
    for n, (got, ref) in enumerate(zip(ratios, refs, strict=False), start=1):
        tol = AGM_RATIO_EPS * 2**n * EPS * ref + TINY
        assert abs(mpmath.mpf(float(got)) - ref) <= tol, (case, n, got, ref)


@pytest.mark.parametrize("case", AGM_CASES)
def test_agm_ratios_of_one_parameter_follow_the_mean_and_stop_by_the_documented_rule(case):
    p, p1, hyper, ymax = case
    a, ratios = el._agm_ratios_scalar(p, p1, hyper, ymax)
    _check_agm(a, ratios, case)


@pytest.mark.parametrize("case", AGM_CASES)
def test_agm_ratios_of_a_constant_parameter_array_are_those_of_the_parameter(case):
    p, p1, hyper, ymax = case
    a, ratios = el._agm_ratios(np.full(5, p), np.full(5, p1), hyper, ymax)
    _check_agm(a, ratios, case)


def test_agm_ratios_of_mixed_parameters_are_each_parameters_own():
    # two parameters in one array: every element iterates until the slowest stops
    cases = [(0.75, 0.25, True, 3.0), (1 - 2.0**-30, 2.0**-30, True, 3.0)]
    a, ratios = el._agm_ratios(
        np.array([c[0] for c in cases]), np.array([c[1] for c in cases]), True, 3.0
    )
    steps = max(_agm_reference(c[1], True, 3.0)[2] for c in cases)
    assert len(ratios) == steps
    for i, case in enumerate(cases):
        a_s, refs, _ = _agm_reference(case[1], True, 3.0)
        assert abs(mpmath.mpf(float(a[i])) - a_s[steps - 1]) <= AGM_A_EPS * EPS, case
        for n, r in enumerate(ratios, start=1):
            assert (
                abs(mpmath.mpf(float(r[i])) - refs[n - 1])
                <= AGM_RATIO_EPS * 2**n * EPS * refs[n - 1] + TINY
            ), (case, n)


@pytest.mark.parametrize("ymax", [0.0, 1.0, 300.0])
def test_agm_stopping_rule_at_its_threshold_in_trigonometric_form(ymax):
    # the trigonometric form has no growth factor (|sin φ_n| ≤ 1), whatever y_max is, and a
    # ratio stops the iteration only when strictly below 2⁻⁶⁴. By hand, with p1 = 1 (the
    # rounded complement of a tiny p): a₁ = (1 + √1)/2 = 1, b₁ = 1, c₁ = c₀²/(4 a₁) = p/4.
    # p = 2⁻⁶²: c₀ = 2⁻³¹ and c₁ = 2⁻⁶⁴ exactly, not below: a second step, c₂ = 2⁻¹³⁰
    # (the exact ratio (1 − √(1 − p))/(1 + √(1 − p)) is above 2⁻⁶⁴ too)
    # p = 1.5 · 2⁻⁶³: c₁ ≈ 1.5 · 2⁻⁶⁵ (two roundings), below 2⁻⁶⁴: one step
    cases = [(2.0**-62, [2.0**-64, 2.0**-130]), (1.5 * 2.0**-63, [1.5 * 2.0**-65])]
    for p, want in cases:
        a, ratios = el._agm_ratios_scalar(p, 1.0, False, ymax)
        aa, rr = el._agm_ratios(np.full(3, p), np.full(3, 1.0), False, ymax)
        for got_a, got in ((a, ratios), (aa, rr)):
            assert got_a == 1.0
            assert len(got) == len(want), (p, ymax, got)
            np.testing.assert_allclose(np.array(got, dtype=float), want, rtol=4 * EPS)


def _scalar_kernel_args(p, p1):
    """(K, trig_agm) as the free top forms them once per parameter, K from mpmath (inf at
    p1 = 0) and the trigonometric AGM (checked above) for p ≤ 1/2."""
    with mpmath.workdps(_dps(p1)):
        K = float(mpmath.ellipk(1 - mpmath.mpf(p1))) if p1 > 0 else math.inf
    return K, (el._agm_ratios_scalar(p, p1, False, 0.0) if p <= 0.5 else None)


def _dps(p1):
    """Digits that resolve m = 1 − p1 and leave 40 over."""
    return 40 if p1 == 0 or p1 > 1e-20 else 50 + int(-math.log10(p1))


#: (p, p1) with p1 = 1 − p exact: m = 0, the trigonometric AGM up to its boundary 1/2, the
#: hyperbolic one just above it and near m = 1, m = 1 to rounding with p1 = 1e-300, and the
#: separatrix p1 = 0 (K = inf: no reduction, sn = tanh, cn = dn = sech)
SCALAR_PARAMETERS = [
    (0.0, 1.0),
    (0.3125, 0.6875),
    (0.5, 0.5),
    (0.5009765625, 0.4990234375),
    (0.8125, 0.1875),
    (1 - 2.0**-30, 2.0**-30),
    (1.0, 1e-300),
    (1.0, 0.0),
]
#: arguments in units of K: tiny, below and above the flip at K/2, K itself, beyond the
#: half period (j = 1, sign flips), negative, several periods out
SCALAR_ARGUMENTS_IN_K = [1e-9, 0.37, -0.37, 0.49, 0.51, 1.0, 1.7, 2.3, -3.1, 7.6]
#: at p1 = 0 in plain units: up to and beyond 710, where cosh overflows and sech underflows
SEPARATRIX_ARGUMENTS = [1e-9, 0.5, -3.0, 20.0, -30.0, 709.5, 710.5, 800.0]


def _scalar_cases():
    for p, p1 in SCALAR_PARAMETERS:
        K, _ = _scalar_kernel_args(p, p1)
        us = SEPARATRIX_ARGUMENTS if math.isinf(K) else [x * K for x in SCALAR_ARGUMENTS_IN_K]
        for u in us:
            yield pytest.param(u, p, p1, id=f"m1={p1:.3g}-u={u:.4g}")


@pytest.mark.parametrize(("u", "p", "p1"), list(_scalar_cases()))
def test_ellipj_of_one_float_is_within_64_eps_of_mpmath_in_every_branch(u, p, p1):
    K, trig = _scalar_kernel_args(p, p1)
    got = el._ellipj_scalar(u, p, p1, K, trig)
    assert all(isinstance(x, float) for x in got)
    with mpmath.workdps(_dps(p1)):
        M = 1 - mpmath.mpf(p1)
        refs = [mpmath.ellipfun(f, _mpf(u), m=M) for f in ("sn", "cn", "dn")]
        sn, cn, dn = refs
        errs = [
            _err_eps(f, r, u, d)
            for f, r, d in zip(got, refs, (cn * dn, -sn * dn, -M * sn * cn), strict=True)
        ]
    assert max(errs) <= el.ELLIPJ_EPS, (u, p, p1, got, errs)


#: G(u) = ∫₀^u n sn²/(1 − n sn²) dv adds the R_J tail (scipy, ~10 eps) to 2j(Π(n|m) − K)
#: and the reduced argument's phase error: within 32 eps of the size of the terms,
#: |G| + |u n/(1 − n)| (the integrand is at most |n|/(1 − n) in size, for n < 1)
THIRD_KIND_SCALAR_EPS = 32.0


def _third_kind_reference(u, n, p1):
    """G(u) in mpmath: by quadrature of n tanh²/(1 − n tanh²) at p1 = 0; otherwise from
    Legendre's form, u = 2jK + r with |r| ≤ K, am u = jπ + asin sn(r):
    G = 2jΠ(n|m) + Π(n; asin sn(r) | m) − u.  Also Π(n|m) − K, the caller's ``full``."""
    with mpmath.workdps(_dps(p1)):
        U, N = _mpf(u), _mpf(n)
        if p1 == 0:
            t2 = lambda v: mpmath.tanh(v) ** 2  # noqa: E731
            pts = [0, U] if abs(U) <= 5 else [0, mpmath.sign(U) * 5, U]
            return mpmath.quad(lambda v: N * t2(v) / (1 - N * t2(v)), pts), None
        M = 1 - mpmath.mpf(p1)
        K = mpmath.ellipk(M)
        j = mpmath.nint(U / (2 * K))
        r = U - 2 * j * K
        phi = mpmath.asin(mpmath.ellipfun("sn", r, m=M))
        full = mpmath.ellippi(N, M)
        G = 2 * j * full + mpmath.ellippi(N, phi, M) - U
        return G, full - K


def _third_kind_cases():
    for p, p1 in SCALAR_PARAMETERS:
        K, _ = _scalar_kernel_args(p, p1)
        if math.isinf(K):
            us = [0.5, -3.0, 20.0, 700.0]
        elif p1 < 1e-160:
            # not the flipped quarter (K/2 < |r| ≤ K): scipy's R_J is wrong there (below)
            us = [x * K for x in (0.37, -0.45, 2.3, 7.6)]
        else:
            us = [x * K for x in (0.37, 0.8, -1.3, 2.3, 7.6)]
        for n in (-3.0, -0.25, 0.5, 0.9):
            for u in us:
                yield pytest.param(u, n, p, p1, id=f"m1={p1:.3g}-n={n}-u={u:.4g}")


@pytest.mark.parametrize(("u", "n", "p", "p1"), list(_third_kind_cases()))
def test_third_kind_excess_of_one_float_agrees_with_mpmath(u, n, p, p1):
    K, trig = _scalar_kernel_args(p, p1)
    ref, full = _third_kind_reference(u, n, p1)
    full = 0.0 if full is None else float(full)
    got = el._third_kind_excess_scalar(u, n, p, p1, K, trig, full)
    assert isinstance(got, float)
    scale = abs(ref) + abs(u * n / (1 - n))
    assert abs(mpmath.mpf(got) - ref) <= THIRD_KIND_SCALAR_EPS * EPS * scale, (got, ref)


#: R_J by one duplication step, then scipy's R_J and R_C: measured 2.0 eps at worst on
#: the grid below against mpmath (scipy alone: 7e12 eps at x = y/2 = 1e-170)
RJ_EPS = 4


@pytest.mark.parametrize("p", [0.5, 4.0, 1e-10, 0.999])
@pytest.mark.parametrize(
    ("x", "y"),
    [
        (1e-160, 2e-160),
        (1e-170, 2e-170),
        (1e-300, 1e-300),
        (5e-324, 1e-200),  # the smallest subnormal beside a tiny normal
        (2.0**-401, 2.0**-401),  # just below the switch to the duplication
        (2.0**-400, 2.0**-400),  # at it: scipy's own R_J
        (0.0, 1e-200),  # a zero argument: duplicated too (scipy is right here as well)
        (0.0, 5e-324),  # a zero beside the smallest subnormal: scipy's R_J is inf
        # both subnormal: one duplication step lands them near 1e-160, where scipy's R_J is
        # off (measured 3.3e9 eps at p = 0.5, 6.9e9 eps at p = 4 with one step; 0.8 eps with
        # two)
        (1.43e-322, 9.63e-322),
        (8.4e-323, 5.43e-322),
        (1e-170, 0.5),  # one tiny argument only: scipy's own R_J
        (0.3, 0.7),
    ],
)
def test_rj_is_accurate_where_both_first_arguments_are_tiny(x, y, p):
    # scipy 1.17's elliprj(x, y, 1, p) is off by ~2e-3 relative for 1e-300 ≤ x, y ≤
    # 1e-160 (found by the flipped-quarter test below); el._rj lifts x and y by one step
    # of Carlson's duplication theorem there
    ref = mpmath.elliprj(x, y, 1, p)
    got = el._rj(np.array([x, 0.3]), np.array([y, 0.7]), 1.0, p)[0]
    got_scalar = el._rj_scalar(x, y, 1.0, p)
    got_0d = el._rj(x, y, 1.0, p)
    for g in (got, got_scalar, float(got_0d)):
        assert abs(mpmath.mpf(g) - ref) <= RJ_EPS * EPS * abs(ref), (g, ref)


@pytest.mark.parametrize("kernel", ["array", "scalar"])
@pytest.mark.parametrize(("x", "y"), [(0.0, 1e-310), (1e-310, 0.0)])
def test_rj_with_a_zero_beside_a_subnormal_first_argument(x, y, kernel):
    p = 0.5
    ref = mpmath.elliprj(x, y, 1, p)
    got = el._rj(x, y, 1.0, p) if kernel == "array" else el._rj_scalar(x, y, 1.0, p)
    assert abs(mpmath.mpf(float(got)) - ref) <= RJ_EPS * EPS * abs(ref), (float(got), ref)


def test_the_duplication_step_agrees_with_scipys_rj_where_scipy_is_accurate():
    # the identity R_J = 2 R_J(x + λ, ...) + 3 R_C(α², β²) checked at ordinary arguments
    # (a wrong λ, α or β, or a wrong factor 2 or 3, is far off here)
    # (a wrong λ, α or β, or a wrong factor 2 or 3, is far off here), also with z ≠ 1, where
    # √z = 1 no longer hides a √z put in the wrong place
    for z in (1.0, 4.0, 0.3):
        x, y, p = np.array([0.3, 1e-3, 2.0]), np.array([0.7, 0.5, 3.0]), 0.4
        ref = np.array([float(mpmath.elliprj(a, b, z, p)) for a, b in zip(x, y, strict=True)])
        got = el._rj_duplicated(x, y, z, p)
        np.testing.assert_allclose(got, ref, rtol=RJ_EPS * EPS, atol=0)


@pytest.mark.parametrize("n", [-3.0, 0.5])
def test_third_kind_in_jacobis_form_near_the_separatrix_in_the_flipped_quarter(n):
    # m1 = 1e-300, u = 0.8 K: sn(u) = tanh(u) to 1e-60 (sn departs from tanh only where
    # e^{-2u} ~ m1), so G(u) is the separatrix's closed form to far below eps
    p1 = 1e-300
    K, trig = _scalar_kernel_args(1.0, p1)
    u = 0.8 * K
    ref, full = _third_kind_reference(u, n, p1)
    sep, _ = _third_kind_reference(u, n, 0.0)
    assert abs(ref - sep) <= EPS * abs(ref)  # the reference is sound
    scale = abs(ref) + abs(u * n / (1 - n))
    got_array = float(el.ellippi_jacobi(u, n, 1.0, m1=p1)) - u
    got_scalar = el._third_kind_excess_scalar(u, n, 1.0, p1, K, trig, float(full))
    for got in (got_array, got_scalar):
        assert abs(mpmath.mpf(got) - ref) <= THIRD_KIND_SCALAR_EPS * EPS * scale, (got, ref)


def test_two_prod_drops_the_error_term_where_the_split_would_overflow():
    # Dekker's split multiplies by 2^27 + 1: for |a| ≳ 1.3e300 that overflows and the error
    # term is not computable; it is 0 then (documented), so a · b = p + 0 stays finite
    for a, b in ((1e305, 3.5), (-1.7e308, 0.25), (2.0**1000, 7.0)):
        p, e = _floats.two_prod_or_zero_scalar(a, b)
        assert (p, e) == (a * b, 0.0)
        pa, ea = _floats.two_prod_or_zero(np.array([a, 3.0]), np.array([b, 0.1]))
        assert pa[0] == a * b
        assert ea[0] == 0.0
        assert Fraction(float(pa[1])) + Fraction(float(ea[1])) == Fraction(3.0) * Fraction(0.1)


@pytest.mark.parametrize(("p", "p1"), [(0.3125, 0.6875), (0.8125, 0.1875)])
@pytest.mark.parametrize("u", [1e308, -1.7e308, 1e305])
def test_ellipj_of_one_float_near_float64s_limit_is_finite_and_on_the_unit_circle(u, p, p1):
    # beyond 4K/eps the phase is lost (documented): finite values on sn² + cn² = 1 and
    # dn² + m sn² = 1 (each product within an ulp), never NaN from the period count's split
    K, trig = _scalar_kernel_args(p, p1)
    sn, cn, dn = el._ellipj_scalar(u, p, p1, K, trig)
    assert all(math.isfinite(x) for x in (sn, cn, dn))
    assert abs(sn * sn + cn * cn - 1.0) <= 4 * EPS
    assert abs(dn * dn + p * sn * sn - 1.0) <= 4 * EPS


def test_the_kernels_are_quiet_on_their_own_at_the_edges_of_float64():
    # the kernels are called outside ellipj's error state too (ellippi_jacobi, the free top),
    # so each keeps its own numpy warnings off (the suite turns a warning into an error):
    # m = 1 (K = inf) at |u| ≥ 710, where cosh overflows and the unused flipped quarter
    # divides 0 by 0
    j, s, snx, cnx, dnx, K = el._reduced(np.array([800.0, -900.0]), np.ones(2), np.zeros(2))
    assert K.tolist() == [np.inf, np.inf]
    assert (j == 0).all()
    assert s.tolist() == [1.0, -1.0]
    assert snx.tolist() == [1.0, 1.0]  # tanh
    assert cnx.tolist() == [0.0, 0.0]  # sech, below the smallest subnormal
    assert dnx.tolist() == [0.0, 0.0]  # dn = sech too at m = 1
    # the modulus transformation's scale overflows: a specific error, not a numpy warning
    with pytest.raises(OutOfDomainError, match=r"got u = 1e\+300 with scale 1e\+150"):
        el._scaled(np.array([1.0, 1e300]), np.array([1e150, 1e150]))
    # G(u) ~ u n/(1 − n) beyond float64 for u = 1.7e308: not finite, quietly (the caller raises)
    one = np.ones(1)
    g = el._third_kind_excess(1.7e308 * one, 0.9 * one, 0.5 * one, 0.5 * one)
    assert not np.isfinite(g).any()


def test_ellippi_jacobi_takes_m1_as_authoritative_near_the_separatrix():
    # m = 1.0 as a float with m1 = 1e-300 given: K ≈ 346.8 is finite, and beyond it sn leaves
    # tanh (at u = 2.3 K, sn ≈ −0.8 where tanh ≈ 1): the integral is the one of m = 1 − 1e-300,
    # far from the separatrix's closed form
    p1 = 1e-300
    K, _ = _scalar_kernel_args(1.0, p1)
    for u, n in ((2.3 * K, -3.0), (-1.3 * K, 0.5)):
        ref, _ = _third_kind_reference(u, n, p1)
        got = float(el.ellippi_jacobi(u, n, 1.0, m1=p1)) - u
        scale = abs(ref) + abs(u * n / (1 - n))
        assert abs(mpmath.mpf(got) - ref) <= THIRD_KIND_SCALAR_EPS * EPS * scale, (u, n, got, ref)


def test_third_kind_in_jacobis_form_just_below_k_at_the_smallest_m1():
    # the one-float kernel of the free top takes the same route (_rj_scalar): inf there
    p1 = 5e-324
    u, n = 373.0, 0.5  # K ≈ 373.6: the flipped quarter
    K, trig = _scalar_kernel_args(1.0, p1)
    ref, full = _third_kind_reference(u, n, p1)
    scale = abs(ref) + abs(u * n / (1 - n))
    got_scalar = el._third_kind_excess_scalar(u, n, 1.0, p1, K, trig, float(full))
    assert abs(mpmath.mpf(got_scalar) - ref) <= THIRD_KIND_SCALAR_EPS * EPS * scale, (got_scalar,)
    got = float(el.ellippi_jacobi(u, n, 1.0, m1=p1)) - u
    assert abs(mpmath.mpf(got) - ref) <= THIRD_KIND_SCALAR_EPS * EPS * scale, (got, ref)


@pytest.mark.parametrize("n", [0.5, -3.0])
def test_third_kind_in_jacobis_form_where_cn_and_dn_squared_are_subnormal(n):
    # m1 = 1e-320, u = K − 0.3: cn ~ 1e-161 and dn ~ 1e-160 are normal floats but their
    # squares are subnormal (a few bits left); R_J is taken from cn and dn themselves
    # (_third_kind_tail_of_roots). From the squares, G was off by 1.8e-5 at n = 0.5 (an error
    # of 5e10 eps of the scale below: 737.7531215 for 737.7531393)
    p1 = 1e-320
    K, trig = _scalar_kernel_args(1.0, p1)
    u = K - 0.3
    ref, full = _third_kind_reference(u, n, p1)
    scale = abs(ref) + abs(u * n / (1 - n))
    got_scalar = el._third_kind_excess_scalar(u, n, 1.0, p1, K, trig, float(full))
    got_array = float(el.ellippi_jacobi(u, n, 1.0, m1=p1)) - u
    for got in (got_scalar, got_array):
        assert abs(mpmath.mpf(got) - ref) <= THIRD_KIND_SCALAR_EPS * EPS * scale, (got, ref)


@pytest.mark.parametrize("n", [0.5, -3.0])
def test_third_kind_beyond_a_quarter_period_at_the_smallest_m1_is_finite(n):
    # Π(n|m) − K = (n/3) R_J(0, m1, 1, 1 − n) at m1 = 5e-324: scipy's R_J is inf there (a 0
    # beside a subnormal), which refused both integrals as overflows; _complete_tail takes
    # it through _rj's duplication
    p1 = 5e-324
    K, _ = _scalar_kernel_args(1.0, p1)
    u = 2.3 * K
    ref, full = _third_kind_reference(u, n, p1)
    assert abs(mpmath.mpf(float(el._complete_tail(n, p1))) - full) <= RJ_EPS * EPS * abs(full)
    scale = abs(ref) + abs(u * n / (1 - n))
    got = float(el.ellippi_jacobi(u, n, 1.0, m1=p1)) - u
    assert abs(mpmath.mpf(got) - ref) <= THIRD_KIND_SCALAR_EPS * EPS * scale, (got, ref)
    with mpmath.workdps(_dps(p1)):
        want = mpmath.ellippi(n, 2.0, 1 - mpmath.mpf(p1))
    got = float(el.ellippi(n, 2.0, 1.0, m1=p1))
    assert abs(mpmath.mpf(got) - want) <= INCOMPLETE_EPS * EPS * abs(want), (got, want)
