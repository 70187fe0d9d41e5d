"""API, validation and special cases of :mod:`mechanics.tops`.

Independent routes: scipy's DOP853 on Euler's equations (4.47) and the attitude
equation dR/dt = −[ω]× R; the free symmetric top's uniform closed form (5.34)–(5.45)
against the elliptic solution at m = 0; Example 5.1's kinematics and energy (5.27);
the heavy top against DOP853 on the book's equations (5.50)–(5.52); the steady
precession and sleeping-top conditions (5.60), (5.72) against the cubic f(u).
"""

from __future__ import annotations

import math
import re
from fractions import Fraction

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from mechanics import tops
from mechanics._floats import EPS, ulps
from mechanics.errors import (
    GimbalLockError,
    NonFiniteError,
    NonPhysicalInertiaError,
    NonPositiveParameterError,
    NotARotationError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
    UnknownOptionError,
)
from mechanics.rotation import matrix_from_euler

from ._naming import cases, check_refusal, valid_kwargs

#: L_O = R^T J ω at the separatrix: ω and R each to a few eps (the module's worst measured
#: 0.51 eps of |ω| on the attitude), a product and a sum of three: 16 eps of |L|
SEPARATRIX_L_ATOL = 16 * EPS
#: ω·Jω − 2E: three products of values each to a few eps, summed
POINSOT_RTOL = 32 * EPS
#: central differences of the incline trajectory (quadratic in t: no truncation error)
#: with rounding ~ eps |x| / h for |x| ~ 1: 2^23 eps = 1.9e-9
FD_ATOL = 2**23 * EPS

# DOP853 at rtol = 1e-13 over t ≤ 10 (a few rotations): its global error stays below
# ~1e-12 of the state scale; the exact solution is within 100 eps of the truth.
ODE_ATOL = 2e-11
ODE_RTOL = 1e-13

R0 = matrix_from_euler(0.3, 1.1, -0.7)


def _euler_rhs(J):
    J = np.asarray(J, float)

    def f(t, y):
        w = y[:3]
        R = y[3:].reshape(3, 3)
        dw = np.array(
            [
                (J[1] - J[2]) * w[1] * w[2] / J[0],
                (J[2] - J[0]) * w[2] * w[0] / J[1],
                (J[0] - J[1]) * w[0] * w[1] / J[2],
            ]
        )
        S = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        return np.concatenate([dw, (-S @ R).ravel()])

    return f


def _integrate(J, w0, ts):
    sol = solve_ivp(
        _euler_rhs(J),
        (0, ts[-1]),
        np.concatenate([w0, R0.ravel()]),
        method="DOP853",
        rtol=ODE_RTOL,
        atol=1e-15,
        t_eval=ts,
    )
    return sol.y[:3].T, sol.y[3:].T.reshape(-1, 3, 3)


CASES = {
    "near axis 1": ([1.0, 2.0, 3.0], [1.0, 0.1, 0.5], "axis1"),
    "near axis 3": ([1.0, 2.0, 3.0], [0.2, 0.1, 1.5], "axis3"),
    "unsorted moments": ([3.0, 1.0, 2.5], [0.1, 1.0, 0.3], "axis1"),
    "unsorted, odd permutation": ([2.0, 1.0, 2.5], [0.4, 1.0, 0.3], None),
    "near the middle axis (Dzhanibekov)": ([1.0, 2.0, 3.0], [1e-3, 1.0, 1e-3], "axis3"),
    "separatrix to 1e-16": ([1.0, 2.0, 3.0], [1.0, 0.0, 0.5773502691896257], "axis1"),
    "on the separatrix": ([3.0, 4.0, 6.0], [2.0, 0.5, 1.0], "separatrix"),
    "on the separatrix, ω1 < 0": ([3.0, 4.0, 6.0], [-2.0, 0.5, 1.0], "separatrix"),
    # D = 6·2·ω3² − 3·1·ω1² = 0 exactly with 0 < ω1 < 1 (the sign of ω1, not its size)
    "on the separatrix, 0 < ω1 < 1": ([3.0, 4.0, 6.0], [0.5, 0.3, 0.25], "separatrix"),
    # J2 near J1: |n3| = J3(J2 − J1)/(J1(J3 − J2)) ≈ 2e-3 below |n1| ≈ 0.77, so ψ is
    # measured about pole 3 (the other cases' poles are 1)
    "about pole 3": ([1.0, 1.001, 1.9], [1.0, 0.0, 0.6], "axis3"),
    # J2 four ulps below J3 (issue 16): |n1| ≈ 1.3e-18 against |n3| ≈ 3.4e15, pole 1 (about
    # pole 3 the two terms of ψ cancel, to ~3e-9 of a turn)
    "J2 four ulps below J3": ([1.0, 3.0 - 4 * 2.0**-51, 3.0], [0.0, 0.1, 1.5], "axis3"),
    "prolate symmetric": ([1.0, 1.0, 2.0], [0.3, 0.4, 1.0], "axis3"),
    "oblate symmetric": ([1.0, 2.0, 2.0], [0.3, 0.4, 1.0], "axis1"),
    "spherical": ([2.0, 2.0, 2.0], [0.3, 0.4, 1.0], "steady"),
    "about the middle axis": ([1.0, 2.0, 3.0], [0.0, 1.0, 0.0], "steady"),
    "in a degenerate plane": ([1.0, 1.0, 2.0], [0.3, 0.4, 0.0], "steady"),
    "at rest": ([1.0, 2.0, 3.0], [0.0, 0.0, 0.0], "rest"),
    "flat body J1 + J2 = J3": ([1.0, 2.0, 3.0], [0.5, 0.5, 0.5], None),
}


@pytest.mark.parametrize("case", list(CASES))
def test_free_top_matches_dop853_for_omega_and_attitude(case):
    J, w0, regime = CASES[case]
    top = tops.FreeAsymmetricTop(J, w0, R0)
    if regime is not None:
        assert top.regime == regime
    ts = np.linspace(0, 10, 11)
    w_ref, R_ref = _integrate(J, np.asarray(w0), ts)
    w, R = top.omega(ts), top.attitude(ts)
    assert np.isfinite(w).all()
    assert np.isfinite(R).all()
    scale = max(1.0, float(np.abs(w0).max()))
    assert np.abs(w - w_ref).max() <= ODE_ATOL * scale
    assert np.abs(R - R_ref).max() <= ODE_ATOL * scale * 10


def test_omega_and_attitude_broadcast_over_time_shape():
    top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [1.0, 0.1, 0.5])
    t = np.linspace(0, 3, 6).reshape(2, 3)
    assert top.omega(t).shape == (2, 3, 3)
    assert top.attitude(t).shape == (2, 3, 3, 3)
    assert top.omega(1.0).shape == (3,)
    assert top.attitude(1.0).shape == (3, 3)
    np.testing.assert_array_equal(top.omega(t)[1, 2], top.omega(t[1, 2]))


def test_free_top_starts_at_its_initial_condition():
    top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [0.3, -0.8, 0.5], R0)
    assert np.abs(top.omega(0.0) - [0.3, -0.8, 0.5]).max() <= 8 * EPS
    assert np.abs(top.attitude(0.0) - R0).max() <= 16 * EPS


def test_flip_period_is_the_period_of_omega_and_inf_for_steady_motion():
    top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [0.05, 1.0, 0.05])
    T = top.flip_period()
    w = top.omega(np.array([0.37, 0.37 + T]))
    assert np.abs(w[1] - w[0]).max() <= 64 * EPS * (1 + T)
    half = top.omega(0.37 + T / 2)
    assert half[1] == pytest.approx(-w[0, 1], rel=64 * EPS * (1 + T))  # ω2 reverses in T/2
    assert tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [0.0, 1.0, 0.0]).flip_period() == math.inf


def test_flip_period_diverges_logarithmically_toward_the_separatrix():
    # T ≈ (4/λ) ln(4/√m1) near m = 1: halving log10 m1 roughly doubles T's log part
    Ts = [
        tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [e, 1.0, e]).flip_period()
        for e in (1e-2, 1e-4, 1e-8)
    ]
    assert Ts[0] < Ts[1] < Ts[2]
    assert (Ts[2] - Ts[1]) == pytest.approx(2 * (Ts[1] - Ts[0]), rel=0.05)


def test_poinsot_residuals_vanish():
    top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [1.0, 0.1, 0.5], R0)
    ell, plane = top.poinsot_residuals(np.linspace(0, 50, 101))
    assert np.abs(ell).max() <= 32 * EPS * top.energy
    assert np.abs(plane).max() <= 256 * EPS * top.energy


def test_free_symmetric_top_closed_form_matches_the_general_solution():
    for w0 in ([0.3, 0.4, 1.0], [0.3, 0.4, -2.0], [0.3, 0.4, 0.0], [0.0, 0.0, 1.0]):
        sym = tops.FreeSymmetricTop(1.0, 2.0, w0, R0)
        gen = tops.FreeAsymmetricTop([1.0, 1.0, 2.0], w0, R0)
        ts = np.linspace(0, 20, 9)
        assert np.abs(sym.omega(ts) - gen.omega(ts)).max() <= 64 * EPS * 20
        assert np.abs(sym.attitude(ts) - gen.attitude(ts)).max() <= 256 * EPS * 20


def test_free_symmetric_top_rates_are_the_books():
    J1, J3, w0 = 2.0, 1.0, np.array([0.3, 0.1, 1.5])
    top = tops.FreeSymmetricTop(J1, J3, w0)
    L = np.linalg.norm([J1 * w0[0], J1 * w0[1], J3 * w0[2]])
    assert top.body_precession_rate == pytest.approx((J3 - J1) * w0[2] / J1, rel=4 * EPS)  # 5.40
    assert top.space_precession_rate == pytest.approx(L / J1, rel=4 * EPS)  # 5.34
    cos_t = J3 * w0[2] / L
    assert top.spin_rate == pytest.approx(L / J1 * cos_t * (J1 - J3) / J3, rel=8 * EPS)  # 5.35


#: φ̇ = ω3 (J1 − J3)/J1 = −β: a difference (exact, Sterbenz or a ≥ 2 ratio's few roundings), a
#: product and a quotient of the scaled moments; measured 0 eps on the cases below
SPIN_RTOL = 4 * EPS
#: J ω(t) against ^A R^O(t) L_O: two rotations R3 of rounded angles, the products of three
#: matrices and a vector; measured ≤ 0.4 eps of |L| on the cases below
SPIN_L_RTOL = 8 * EPS


@pytest.mark.parametrize(
    ("J1", "J3", "w0"),
    [
        # cos θ0 = J3 ω3/|L| ≈ 5e-11: cos(atan2(...)) of θ0 ≈ π/2 kept only the rounding of
        # π/2 (1.3e-6 relative off before the fix)
        (1.0, 0.5, [1e10, 0.0, 1.0]),
        (1.0, 0.5, [3.0, 4.0, 1e-9]),  # 7e-7 off before
        # cos θ0 ≈ 1e-310 rounded to the float nearest π/2's cosine: 6.1e283 for 1e-10 before
        (1.0, 1e-300, [1.0, 0.0, 1e-10]),
        (2.0**600, 2.0**599, [2.0**-600, 0.0, 2.0**-610]),
    ],
)
def test_free_symmetric_top_spin_rate_near_a_flat_nutation_against_mpmath(J1, J3, w0):
    """φ̇ = (|L|/J1) cos θ0 (J1 − J3)/J3 (5.35) = ω3 (J1 − J3)/J1: the cosine of a nutation angle
    near π/2 taken through atan2 lost its digits; the attitude, turning at φ̇, took L off."""
    import mpmath

    top = tops.FreeSymmetricTop(J1, J3, w0)
    with mpmath.workdps(50):
        exact = mpmath.mpf(w0[2]) * (mpmath.mpf(J1) - J3) / J1
        assert float(abs(top.spin_rate / exact - 1)) <= SPIN_RTOL
    # L_A(t) = ^A R^O(t) L_O = J ω(t): the space-fixed L seen in the body at t = 1/|ω|
    t = 1.0 / max(abs(x) for x in w0)
    L_A = top.attitude(t) @ top.angular_momentum_space
    want = np.array([J1, J1, J3]) * top.omega(t)
    assert np.abs(L_A - want).max() <= SPIN_L_RTOL * top.angular_momentum_norm


@pytest.mark.parametrize(
    ("J", "match"),
    [
        ([0.0, 1.0, 1.0], "J1 = 0.0 ≤ 0"),
        ([1.0, -2.0, 2.0], "J2 = -2.0 ≤ 0"),
        ([1.0, 2.0, 3.5], r"J1 \+ J2 ≥ J3: J3 exceeds J1 \+ J2 by 0.5"),
        ([4.0, 1.0, 2.0], r"J2 \+ J3 ≥ J1: J1 exceeds J2 \+ J3 by 1"),
    ],
)
def test_non_physical_moments_name_the_condition_and_the_excess(J, match):
    with pytest.raises(NonPhysicalInertiaError, match=match):
        tops.FreeAsymmetricTop(J, [1.0, 0.0, 0.0])


def test_triangle_inequality_excess_is_measured_exactly():
    # J3 = J1 + J2 + 1 ulp: exact rational arithmetic sees the ulp
    J3 = math.nextafter(3.0, 4.0)
    with pytest.raises(NonPhysicalInertiaError, match=r"4\.44089e-16"):
        tops.check_principal_moments([1.0, 2.0, J3])
    tops.check_principal_moments([1.0, 2.0, 3.0])  # the flat body is allowed


@pytest.mark.parametrize(
    ("args", "err"),
    [
        (([1.0, 2.0, np.nan], [1.0, 0, 0]), NonFiniteError),
        (([1.0, 2.0, 3.0], [1.0, np.inf, 0]), NonFiniteError),
        (([1.0, 2.0], [1.0, 0, 0]), ShapeError),
        (([1.0, 2.0, 3.0], [1.0, 0, 0], np.diag([1.0, 1.0, -1.0])), NotARotationError),
    ],
)
def test_free_top_bad_input(args, err):
    with pytest.raises(err):
        tops.FreeAsymmetricTop(*args)


def test_free_top_at_rest_is_trivial_not_nan():
    top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [0.0, 0.0, 0.0], R0)
    t = np.linspace(0, 5, 4)
    np.testing.assert_array_equal(top.omega(t), 0.0)
    np.testing.assert_array_equal(top.attitude(t), np.broadcast_to(R0, (4, 3, 3)))
    assert top.energy == 0.0
    assert top.flip_period() == math.inf


def test_free_top_time_must_be_finite():
    top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [1.0, 0.1, 0.5])
    with pytest.raises(NonFiniteError):
        top.omega([0.0, np.nan])


def test_principal_axis_stability_middle_axis_unstable_others_oscillate():
    J = [1.0, 2.0, 4.0 - 1.0]
    w = 2.0
    s1, s2, s3 = (tops.principal_axis_stability(J, a, omega=w) for a in (1, 2, 3))
    assert (s1.kind, s2.kind, s3.kind) == ("stable", "unstable", "stable")
    # (5.102) with Ci = (Jj − Jk)/Ji written out by hand
    assert s2.rate == pytest.approx(w * math.sqrt((3 - 2) / 1 * (2 - 1) / 3), rel=4 * EPS)
    assert s1.rate == pytest.approx(w * math.sqrt((3 - 1) / 2 * (3 - 2) / 3), rel=4 * EPS)
    assert s3.rate == pytest.approx(w * math.sqrt((3 - 1) / 2 * (2 - 1) / 1), rel=4 * EPS)
    assert tops.principal_axis_stability([1.0, 1.0, 2.0], 1).kind == "neutral"
    with pytest.raises(UnknownOptionError):
        tops.principal_axis_stability(J, 4)


#: rate = |ω| √|C_i C_k|: C_i, C_k and their product (three roundings), a square root halving
#: them, one product with |ω|; measured ≤ 0.52 eps below
STABILITY_RTOL = 4 * EPS
#: C_i C_k ω²: C_i, C_k, their product, ω's mantissa squared (two roundings), scaled once;
#: measured ≤ 0.52 ulps below
STABILITY_ULPS = 6


@pytest.mark.parametrize(
    ("J", "axis", "omega", "kind"),
    [
        # ω² = 1e320 overflowed although C_i C_k ω² ≈ -1.1e304 (refused as an overflow before)
        ([1.0, 1.0 + 2.0**-52, 2.0], 1, 1e160, "stable"),
        ([1.0, 2.0, 3.0], 2, 1e-160, "unstable"),  # C_i C_k ω² subnormal: the rate 2.4e-4 off
        # C_i C_k ω² ≈ 1e-332 rounded to 0: called neutral before, for a rate of 2.7e-166
        ([1.0, 1.0 + 2.0**-52, 1.0 + 2.0**-51], 2, 1e-150, "unstable"),
        ([1.0, 2.0, 3.0], 1, -(2.0**-540), "stable"),  # ω² = 0: neutral, rate 0 before
    ],
)
def test_principal_axis_stability_at_any_rate_against_exact_rationals(J, axis, omega, kind):
    import mpmath

    r = tops.principal_axis_stability(J, axis, omega=omega)
    j = axis - 1
    i, k = (j + 1) % 3, (j + 2) % 3
    Jf = [Fraction(x) for x in J]
    c = (Jf[j] - Jf[k]) / Jf[i] * ((Jf[i] - Jf[j]) / Jf[k]) * Fraction(omega) ** 2
    assert r.kind == kind
    assert ulps(r.CiCk, c) <= STABILITY_ULPS
    with mpmath.workdps(50):
        exact = mpmath.sqrt(abs(mpmath.mpf(c.numerator) / c.denominator))
        assert float(abs(r.rate / exact - 1)) <= STABILITY_RTOL


def test_middle_axis_growth_rate_matches_the_exact_free_top():
    # a perturbation of 1e-12 about axis 2 grows like e^{rate t}: by t = 12 the decaying
    # mode is down by e^{-2 rate t} ≈ 1e-6, and at t = 20 the amplitude is still ~1e-7
    J, eps0 = [1.0, 2.0, 3.0], 1e-12
    top = tops.FreeAsymmetricTop(J, [eps0, 1.0, eps0])
    rate = tops.principal_axis_stability(J, 2).rate
    t = np.array([12.0, 20.0])
    w1 = np.abs(top.omega(t)[:, 0])
    # the linear growth rate holds up to the decaying mode's share e^{-2 rate t} at t = 12
    # and the nonlinear terms ~ amplitude² ≈ 1e-14: allow ten times the former
    assert math.log(w1[1] / w1[0]) / 8.0 == pytest.approx(rate, rel=10 * math.exp(-2 * rate * 12))


def test_spherical_top_on_incline_example_5_1():
    m, R, J, beta, g = 2.0, 0.3, 0.4 * 2.0 * 0.09, 0.4, 9.81
    w0 = np.array([0.5, -1.0, 3.0])
    t = np.linspace(0, 2, 5)
    x, _, w = tops.spherical_top_on_incline(
        t, m=m, R=R, J=J, beta=beta, g=g, x0=1.0, y0=-1.0, omega_0=w0
    )
    alpha = R * m * g * np.sin(beta) / (J + m * R * R)
    assert alpha == pytest.approx(5 / 7 * g * np.sin(beta) / R, rel=4 * EPS)  # solid sphere
    np.testing.assert_allclose(w[:, 1], w0[1] + alpha * t, rtol=4 * EPS)
    # rolling: ẋ = R ω_y (5.6), ẏ = −R ω_x (5.7), by finite difference of the trajectory
    h = 1e-4
    xp, yp, _ = tops.spherical_top_on_incline(
        t + h, m=m, R=R, J=J, beta=beta, g=g, x0=1.0, y0=-1.0, omega_0=w0
    )
    xm, ym, _ = tops.spherical_top_on_incline(
        t - h, m=m, R=R, J=J, beta=beta, g=g, x0=1.0, y0=-1.0, omega_0=w0
    )
    np.testing.assert_allclose((xp - xm) / (2 * h), R * w[:, 1], atol=FD_ATOL)
    np.testing.assert_allclose((yp - ym) / (2 * h), -R * w[:, 0], atol=FD_ATOL)
    # energy (5.24)–(5.26) conserved
    T = 0.5 * ((J + m * R * R) * (w[:, 0] ** 2 + w[:, 1] ** 2) + J * w[:, 2] ** 2)
    E = T - m * g * x * np.sin(beta)
    np.testing.assert_allclose(E, E[0], rtol=0, atol=64 * EPS * abs(T).max())
    with pytest.raises(NonPositiveParameterError):
        tops.spherical_top_on_incline(t, m=-1.0, R=R, J=J, beta=beta, g=g)
    with pytest.raises(OutOfDomainError):
        tops.spherical_top_on_incline(t, m=m, R=R, J=J, beta=2.0, g=g)


# ----------------------------------------------------------------- heavy top


def _heavy_rhs(J1, J3, mgl):
    def f(t, y):
        th, _, _, thd, psd, phd = y
        s, c = np.sin(th), np.cos(th)
        # (5.50)–(5.52) solved for the second derivatives
        thdd = (mgl * s - ((J3 - J1) * psd**2 * s * c + J3 * psd * phd * s)) / J1
        psdd = ((J3 - J1) * psd * thd * c + J3 * thd * phd - J1 * psd * thd * c) / (J1 * s)
        phdd = -(psdd * c - psd * thd * s)
        return [thd, psd, phd, thdd, psdd, phdd]

    return f


HEAVY = {
    "nutating": dict(theta=1.0, psi=0.2, phi=0.1, theta_dot=0.3, psi_dot=0.3, phi_dot=8.0),
    "from rest in θ": dict(theta=0.6, theta_dot=0.0, psi_dot=0.0, phi_dot=12.0),
    "looping": dict(theta=1.2, theta_dot=0.0, psi_dot=-1.5, phi_dot=6.0),
    "slow spin": dict(theta=0.8, theta_dot=-0.5, psi_dot=0.7, phi_dot=1.0),
    # horizontal, L3 = J3 ψ̇ cos(π/2) ≈ 3e-17: (L_z ∓ L3)/J'1 = 1 ∓ 3e-17 round to 1.0 exactly
    "horizontal, a ∓ b = 1": dict(theta=math.pi / 2, theta_dot=0.2, psi_dot=1.0, phi_dot=0.0),
}


@pytest.mark.parametrize("case", list(HEAVY))
def test_heavy_top_matches_dop853_on_the_books_equations(case):
    J1, J3, mgl = 1.0, 0.5, 1.0
    kw = HEAVY[case]
    top = tops.HeavySymmetricTop(J1, J3, mgl, **kw)
    ts = np.linspace(0, 8, 9)
    y0 = [
        kw["theta"],
        kw.get("psi", 0.0),
        kw.get("phi", 0.0),
        kw["theta_dot"],
        kw["psi_dot"],
        kw["phi_dot"],
    ]
    sol = solve_ivp(
        _heavy_rhs(J1, J3, mgl), (0, 8), y0, method="DOP853", rtol=1e-13, atol=1e-13, t_eval=ts
    )
    assert np.abs(top.theta(ts) - sol.y[0]).max() <= 1e-10
    assert np.abs(top.psi(ts) - sol.y[1]).max() <= 1e-10
    assert np.abs(top.phi(ts) - sol.y[2]).max() <= 1e-10
    assert np.abs(np.array(top.rates(ts)) - sol.y[3:]).max() <= 1e-10


def _axis_rhs(J1, mgl):
    """The symmetric top as its axis k and angular momentum L (no Euler angles, so no
    singularity at the vertical): L = J1 k × k̇ + L3 k gives k̇ = L × k / J1, and gravity
    on the centre of mass at ℓk gives L̇ = ℓk × (−mg ẑ)."""

    def f(t, y):
        k, L = y[:3], y[3:]
        return np.r_[np.cross(L, k) / J1, -mgl * np.cross(k, [0.0, 0.0, 1.0])]

    return f


#: tops whose axis reaches the vertical u = 1 (L_z = L3): u = 1 a root of f, and the largest
#: one (the top turns there) or not (it swings over)
VERTICAL = {
    # no spin, energy above the vertical's: a pendulum going over the top (found by
    # hypothesis: the root search lost u3 = 1.02 in the cubic's rounding at u = 1)
    "over the top": dict(theta=1.625, theta_dot=1.96875),
    # no spin, energy below the vertical's: it cannot pass u = 1 (u = 1 is then u3)
    "short of it": dict(theta=1.625, theta_dot=1.5),
    # spinning with L_z = L3 to rounding: the axis passes (nearly) through the vertical
    "spinning through": dict(theta=2.0, theta_dot=2.5, phi_dot=1.0, psi_dot=None),
}


@pytest.mark.parametrize("case", list(VERTICAL))
def test_heavy_top_through_the_vertical_matches_its_axis_integrated(case):
    J1, J3, mgl = 1.1875, 0.5, 2.140625
    kw = dict(VERTICAL[case])
    th, thd, phd = kw["theta"], kw["theta_dot"], kw.get("phi_dot", 0.0)
    u0, S = math.cos(th), math.sin(th)
    if kw.get("psi_dot", 0.0) is None:  # L_z = J1 S² ψ̇ + L3 u0 = L3 = J3(ψ̇ u0 + φ̇)
        kw["psi_dot"] = J3 * phd / (J1 * (1 + u0) - J3 * u0)
    psd = kw.get("psi_dot", 0.0)
    top = tops.HeavySymmetricTop(J1, J3, mgl, **kw)
    # the axis (z-x-z, ψ = 0) and its rate, and L, from the initial data alone
    k0 = np.array([0.0, -S, u0])
    kdot0 = np.array([S * psd, -u0 * thd, -S * thd])
    L0 = J1 * np.cross(k0, kdot0) + J3 * (psd * u0 + phd) * k0
    ts = np.linspace(0, 8, 33)
    sol = solve_ivp(
        _axis_rhs(J1, mgl),
        (0, 8),
        np.r_[k0, L0],
        method="DOP853",
        rtol=ODE_RTOL,
        atol=ODE_RTOL,
        t_eval=ts,
    )
    assert sol.success
    u = top.u(ts)
    assert np.abs(u - sol.y[2]).max() <= ODE_ATOL
    # the axis's speed² |k̇|² = θ̇² + ψ̇² sin²θ (sign-free where θ reflects at the vertical)
    thd_t, psd_t, _ = top.rates(ts)
    kdot = np.cross(sol.y[3:].T, sol.y[:3].T) / J1
    speed2 = (kdot**2).sum(axis=1)
    assert np.abs(thd_t**2 + psd_t**2 * (1 - u) * (1 + u) - speed2).max() <= ODE_ATOL * (
        1 + speed2.max()
    )
    # the search the bug lived in: u3 is a root of f, at or above 1
    u3 = top.roots[2]
    assert u3 >= 1.0
    scale = np.abs(top.f(np.array([-1.0, 1.0, 2.0]))).max() + 1
    assert abs(float(top.f(u3))) <= 64 * EPS * scale


def test_heavy_top_roots_bracket_the_motion_and_are_roots_of_f():
    top = tops.HeavySymmetricTop(1.0, 0.5, 1.0, **HEAVY["nutating"])
    u1, u2, u3 = top.roots
    assert -1 <= u1 <= math.cos(1.0) <= u2 <= 1 < u3
    scale = np.abs(top.f(np.array([-1.0, 1.0]))).max() + 1
    assert np.abs(top.f(np.array(top.roots))).max() <= 64 * EPS * scale
    u = top.u(np.linspace(0, 20, 200))
    assert u.min() >= u1 - 4 * EPS
    assert u.max() <= u2 + 4 * EPS


def test_steady_precession_gives_a_double_root_and_constant_theta():
    J1, J3, mgl, th = 1.0, 0.5, 1.0, 0.9
    phid = 10.0
    # choose Ω from (5.60) with L3 = J3(Ω cos θ + φ̇): J1 cosθ Ω² − L3 Ω + mgl = 0 → solve by
    # fixed point on the slow root
    om = 0.0
    for _ in range(60):
        L3 = J3 * (om * math.cos(th) + phid)
        om = tops.steady_precession_rates(J1, L3, mgl, th)[0]
    top = tops.HeavySymmetricTop(J1, J3, mgl, theta=th, theta_dot=0.0, psi_dot=om, phi_dot=phid)
    u1, u2, _ = top.roots
    # the roots are refined to rounding; θ then stays at th to rounding
    assert abs(u2 - u1) <= 64 * EPS
    ts = np.linspace(0, 30, 31)
    assert np.abs(top.theta(ts) - th).max() <= 64 * EPS
    # om is a rounded float, so the exact motion nutates between u1 and u2 (measured: 8.9e-16
    # apart; a root search that lands one ulp elsewhere makes them exactly equal): its mean
    # ψ̇ moves from om by up to |dψ̇/du| (u2 − u1), ψ̇ = (a − bu)/(1 − u²) (5.67) with a, b
    # from the initial data; over t that adds to the rounding of om t
    u = math.cos(th)
    L3 = J3 * (om * u + phid)
    a, b = (J1 * (1 - u * u) * om + L3 * u) / J1, L3 / J1
    dpsid_du = (-b * (1 - u * u) + 2 * u * (a - b * u)) / (1 - u * u) ** 2
    slack = abs(dpsid_du) * (u2 - u1) * ts
    assert np.all(np.abs(top.psi(ts) - om * ts) <= 64 * EPS * (1 + np.abs(om * ts)) + slack)


def test_sleeping_top_condition_and_motion():
    assert tops.sleeping_top_is_stable(1.0, 2.0 + 1e-9, 1.0)
    assert not tops.sleeping_top_is_stable(1.0, 2.0 - 1e-9, 1.0)
    top = tops.HeavySymmetricTop(1.0, 0.5, 1.0, theta=0.0, psi_dot=0.5, phi_dot=3.0)
    assert top.sleeping
    u = top.u(np.array([0.0, 5.0]))
    assert u.shape == (2,)
    np.testing.assert_array_equal(u, 1.0)
    # its rates stay put, one value per time asked for
    thd, psd, phd = top.rates(np.array([[0.0, 1.0, 2.0]]))
    assert thd.shape == psd.shape == phd.shape == (1, 3)
    np.testing.assert_array_equal([thd, psd, phd], [[[0.0] * 3], [[0.5] * 3], [[3.0] * 3]])
    with pytest.raises(GimbalLockError):
        tops.HeavySymmetricTop(1.0, 0.5, 1.0, theta=0.0, theta_dot=1.0)


def test_effective_potential_turning_points_are_the_roots():
    top = tops.HeavySymmetricTop(1.0, 0.5, 1.0, **HEAVY["nutating"])
    u1, u2, _ = top.roots
    th = np.arccos([u1, u2])
    # E' − Φ_eff(θ) = 0 at the turning points (5.71)
    gap = top.reduced_energy - top.effective_potential(th)
    assert np.abs(gap).max() <= 1e-12 * abs(top.energy)


def test_heavy_top_bad_input():
    with pytest.raises(NonPositiveParameterError):
        tops.HeavySymmetricTop(-1.0, 0.5, 1.0, theta=1.0)
    with pytest.raises(NonPositiveParameterError):
        tops.HeavySymmetricTop(1.0, 0.5, 0.0, theta=1.0)
    with pytest.raises(NonFiniteError):
        tops.HeavySymmetricTop(1.0, 0.5, 1.0, theta=np.nan)
    with pytest.raises(OutOfDomainError):
        tops.HeavySymmetricTop(1.0, 0.5, 1.0, theta=4.0)
    with pytest.raises(OutOfDomainError):
        tops.steady_precession_rates(1.0, 0.1, 1.0, 0.2)


@pytest.mark.parametrize("tiny", [5.33528311524476e-224, 1e-300, 5e-324])
def test_a_spin_too_close_to_the_separatrix_is_refused_with_a_clear_error(tiny) -> None:
    """Found by the scene engine's random test: ω = (0, 1, tiny) about the middle axis
    of a box makes m1 underflow; the refusal must name it (it once overflowed while
    formatting its own message)."""
    J = np.array([0.52, 0.40, 0.20]) / 12.0  # a 0.2 × 0.4 × 0.6 m box of 1 kg: ω along e2
    with pytest.raises(OutOfDomainError, match=r"m1 ≈ 2\^-\d+ of the separatrix"):
        tops.FreeAsymmetricTop(J, [0.0, 1.0, tiny])


def test_a_subnormal_spin_keeps_its_direction() -> None:
    """J ω of ω = (0, 5e-324, 5e-324) underflows to 0 in float64; the pole vector is the
    direction of L and must be formed on ω scaled first (found by the scene engine's
    random test: the attitude was NaN)."""
    J = np.array([0.52, 0.40, 0.20]) / 12.0
    top = tops.FreeAsymmetricTop(J, [0.0, 5e-324, 5e-324])
    R = top.attitude(np.array([0.0, 1.0]))
    assert np.all(np.isfinite(R))
    np.testing.assert_allclose(R[1] @ R[1].T, np.eye(3), rtol=0, atol=8 * 2.0**-52)


# ------------------------------------------------ one instant (issue 15, part 4)

# A Python float t takes the one-instant path (math functions on floats, the array
# path's steps in its order); it differs from the array path only by the rounding of
# libm's against numpy's sin/asin/... and the order of the 3×3 products: measured
# 5.9 eps (relative to |ω|, and absolute in R) on 37 tops × 6 times, t up to 1000
# rotations.  Both paths meet the mpmath oracles with the same worst errors
# (tests/stability/test_tops_stability.py, parametrised over the path).
ONE_INSTANT_EPS = 32


def _free_tops():
    rng = np.random.default_rng(20261125)
    cases = [
        ((1.0, 2.0, 3.0), (0.4, 0.2, 1.0)),  # issue 15's top
        ((1.0, 2.0, 3.0), (1.0, 0.1, 0.5)),
        ((3.0, 1.0, 2.0), (0.3, 1.0, 0.01)),  # axis 1, unsorted moments
        ((1.0, 1.0, 2.0), (0.3, 0.2, 1.0)),  # symmetric: uniform precession
        ((1.0, 2.0, 2.0), (1.0, 0.3, 0.1)),
        ((1.0, 2.0, 3.0), (1.0, 0.0, 0.5773502691896258)),  # near the separatrix
    ]
    cases += [(tuple(rng.uniform(1, 2, 3)), tuple(rng.normal(size=3))) for _ in range(12)]
    return cases


@pytest.mark.parametrize(("J", "w0"), _free_tops())
def test_one_instant_path_agrees_with_the_array_path(J, w0):
    top = tops.FreeAsymmetricTop(J, w0)
    for t in (0.0, 0.3, 7.5, -3.0, 100.0, 6283.0):
        w, R = top.omega(t), top.attitude(t)
        w_arr, R_arr = top.omega(np.array([t]))[0], top.attitude(np.array([t]))[0]
        assert w.shape == (3,)
        assert R.shape == (3, 3)
        assert np.abs(w - w_arr).max() <= ONE_INSTANT_EPS * EPS * np.abs(w_arr).max()
        assert np.abs(R - R_arr).max() <= ONE_INSTANT_EPS * EPS
        ws, Rs = top.state(t)
        np.testing.assert_array_equal(ws, w)
        np.testing.assert_array_equal(Rs, R)


def test_state_is_omega_and_attitude_over_any_time_shape():
    top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [0.4, 0.2, 1.0])
    t = np.linspace(0.0, 50.0, 12).reshape(3, 4)
    w, R = top.state(t)
    np.testing.assert_array_equal(w, top.omega(t))
    np.testing.assert_array_equal(R, top.attitude(t))
    for steady in ([0.0, 0.0, 0.0], [0.0, 0.0, 1.5]):  # rest and a steady spin
        top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], steady)
        w, R = top.state(2.0)
        np.testing.assert_array_equal(w, top.omega(2.0))
        np.testing.assert_array_equal(R, top.attitude(2.0))


def test_one_instant_path_refuses_what_the_array_path_refuses():
    top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [0.4, 0.2, 1.0])
    for bad in (math.nan, math.inf):
        for fn in (top.omega, top.attitude, top.state):
            with pytest.raises(NonFiniteError):
                fn(bad)


def test_the_heavy_tops_nutation_period_returns_u_to_itself():
    """u(t + T) = u(t), while u at T/2 is the other turning point (sn² runs 0 → 1 → 0)."""
    top = tops.HeavySymmetricTop(
        1.0, 0.5, 1.0, theta=1.0, psi=0.0, phi=0.0, theta_dot=0.0, psi_dot=0.3, phi_dot=20.0
    )
    T = top.nutation_period()
    t = np.linspace(0.0, 3.0, 7)
    np.testing.assert_allclose(top.u(t + T), top.u(t), rtol=0, atol=64 * EPS)
    # released with θ̇ = 0: u0 is one turning point, half a period later u is the other
    u1, u2, _ = top.roots
    ends = sorted([float(top.u(0.0)), float(top.u(0.5 * T))])
    np.testing.assert_allclose(ends, [u1, u2], rtol=0, atol=64 * EPS)
    assert u2 - u1 > 0.01  # the two turning points are apart: a real test
    sleeping = tops.HeavySymmetricTop(1.0, 0.5, 1.0, theta=0.0, phi_dot=20.0)
    assert sleeping.nutation_period() == math.inf


def test_separatrix_distance_is_in_the_units_given_and_refuses_overflow():
    # L² − 2EJ2 scales as s² for J → s J (ω fixed); exact for s a power of two
    J, w = np.array([1.0, 2.0, 3.0]), np.array([0.4, 0.2, 1.0])
    d = tops.FreeAsymmetricTop(J, w).separatrix_distance
    L2 = float(((J * w) ** 2).sum())
    E2J2 = float((J * w * w).sum()) * J[1]
    assert d == pytest.approx(L2 - E2J2, rel=16 * EPS)
    assert tops.FreeAsymmetricTop(2.0**100 * J, w).separatrix_distance == d * 2.0**200
    with pytest.raises(
        ResultOverflowError,
        match=r"^separatrix_distance: L² − 2 E J_mid overflows float64 for these moments "
        r"\(\|L² − 2 E J_mid\| ≥ 2\^1330, \|L\| = 3\.05\d*e\+200\)$",
    ):
        # L² − 2EJ2 = (9.32 − 6.48)e400 ≈ 2^1330.9, |L| = √9.32e200 (the message showed the
        # scaled value and 4^k before)
        _ = tops.FreeAsymmetricTop(1e200 * J, w).separatrix_distance


#: (log2 of the moments' scale, log2 of ω's): E = ½ J ω², |L| and L² − 2EJ2 fit float64 but the
#: scaled moments' E (~ω²) did not: J = 2^990, ω = 2^-600 gave E = 0 and L² − 2EJ2 = 0 (the
#: regime's sign lost) for 5.4e-64 and -1.6e234; J = 2^-990, ω = 2^600 (E = 1.5e63) and
#: ω = 2^1000 (E = 9.7e303) were refused as overflows
_SCALED_TOPS = [(990, -600), (990, -1000), (-990, 600), (-990, 1000), (-600, 600), (600, -520)]


@pytest.mark.parametrize(("ej", "ew"), _SCALED_TOPS)
def test_free_top_constants_at_any_scale_are_the_exact_values_rounded_once(ej, ew):
    import mpmath

    J, w = [1.0, 2.0, 3.0], [1.0, 0.1, 0.5]
    Js, ws = [math.ldexp(x, ej) for x in J], [math.ldexp(x, ew) for x in w]
    top = tops.FreeAsymmetricTop(Js, ws)
    Jf, wf = [Fraction(x) for x in Js], [Fraction(x) for x in ws]
    E = sum(a * b * b for a, b in zip(Jf, wf, strict=True)) / 2
    L2 = sum((a * b) ** 2 for a, b in zip(Jf, wf, strict=True))
    assert top.energy == float(E)  # Fraction → float rounds once
    assert top.separatrix_distance == float(L2 - 2 * E * Jf[1])
    with mpmath.workdps(50):
        L = mpmath.sqrt(mpmath.mpf(L2.numerator) / L2.denominator)
        assert ulps(top.angular_momentum_norm, L) <= 0.5  # the root of an exact value, rounded
    # ω(t) and the attitude are those of the unscaled top at t·2^ew, bit for bit
    base = tops.FreeAsymmetricTop(J, w)
    ts = np.array([0.0, 0.7, 7.5])
    assert np.array_equal(top.omega(np.ldexp(ts, -ew)), np.ldexp(base.omega(ts), ew))
    assert np.array_equal(top.attitude(np.ldexp(ts, -ew)), base.attitude(ts))


# ------------------------------------------- every parameter named, every overflow named
_ROT = r"R_A_O_0 is not a rotation: (max \|R R\^T - 1\| = 3|\|det R - 1\| = 2) exceeds atol"
_POS = r"must be > 0; got (0\.0|-1\.0)"
_TRIANGLE_J = r"J breaks the triangle inequality J1 \+ J2 ≥ J3: J3 exceeds J1 \+ J2 by 1"
_POSITIVE_J = r"J must be positive: J1 = (0\.0|-2\.0) ≤ 0"
#: the condition an unphysical value of each fuzz entry violates (tests.fuzz.entries)
_CONDITIONS = {
    ("FreeAsymmetricTop", "J"): f"{_POSITIVE_J}|{_TRIANGLE_J}",
    ("FreeAsymmetricTop", "R_A_O_0"): _ROT,
    ("FreeSymmetricTop", "J1"): r"^J1 must be positive: J1 = (0\.0|-2\.0|-1\.0) ≤ 0$",
    ("FreeSymmetricTop", "J3"): (
        r"^J3 must be positive: J3 = (0\.0|-2\.0|-1\.0) ≤ 0$|^J3 = \d.* exceeds 2 J1 = .*: the "
        r"moments of a symmetric body obey the triangle inequality J3 ≤ J1 \+ J2 = 2 J1$"
    ),
    ("FreeSymmetricTop", "R_A_O_0"): _ROT,
    # a bad top of a batch is named by its index first: "top (0,): J must be positive..."
    ("FreeTopBatch", "J"): f"^top \\(0,\\): ({_POSITIVE_J}|{_TRIANGLE_J})",
    ("FreeTopBatch", "R_A_O_0"): _ROT,
    ("HeavySymmetricTop", "J_1"): _POS,
    ("HeavySymmetricTop", "J_3"): (
        f"{_POS}|J_3 = 5\\.0 exceeds 2 J_1 = 4\\.0: the moments of a symmetric body obey the "
        "triangle inequality"
    ),
    ("HeavySymmetricTop", "m_g_ell"): _POS,
    ("HeavySymmetricTop", "theta"): (
        r"theta = 0 or π with theta_dot ≠ 0: the Euler angles are singular"
        r"|theta must lie in \[0, π\]; got 4\.0"
    ),
    ("check_principal_moments", "J"): f"{_POSITIVE_J}|{_TRIANGLE_J}",
    ("principal_axis_stability", "J"): f"{_POSITIVE_J}|{_TRIANGLE_J}",
    ("principal_axis_stability", "axis"): r"axis must be 1, 2 or 3; got (0|4|1\.5)$",
    ("sleeping_top_is_stable", "J_1"): _POS,
    ("sleeping_top_is_stable", "m_g_ell"): _POS,
    ("steady_precession_rates", "J_1"): _POS,
    ("steady_precession_rates", "m_g_ell"): _POS,
    ("spherical_top_on_incline", "m"): _POS,
    ("spherical_top_on_incline", "R"): _POS,
    ("spherical_top_on_incline", "J"): _POS,
    ("spherical_top_on_incline", "g"): _POS,
}


#: axis is an option (1, 2 or 3): its NaN and string are unknown options, not bad numbers
_SKIP = frozenset({("principal_axis_stability", "axis", k) for k in ("nan", "str")})


@pytest.mark.parametrize(
    ("fname", "param", "value", "error", "condition"), list(cases("tops", _CONDITIONS, skip=_SKIP))
)
def test_every_parameter_of_every_function_is_named_with_the_condition_it_breaks(
    fname, param, value, error, condition
):
    kw = valid_kwargs("tops", fname) | {param: value}
    check_refusal(getattr(tops, fname), kw, param, error, condition)


def _free():
    return tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [0.4, 0.2, 1.0])


def _sym():
    return tops.FreeSymmetricTop(2.0, 3.0, [0.3, -0.2, 0.5])


def _batch():
    return tops.FreeTopBatch(
        [[1.0, 2.0, 3.0], [2.0, 2.5, 4.0]], [[0.4, 0.2, 1.0], [1.0, -0.3, 0.1]]
    )


def _heavy():
    return tops.HeavySymmetricTop(
        J_1=2.0, J_3=1.0, m_g_ell=3.0, theta=0.5, psi=0.1, phi=0.2,
        theta_dot=0.1, psi_dot=1.0, phi_dot=8.0,
    )  # fmt: skip


@pytest.mark.parametrize(
    ("make", "method", "param"),
    [
        (_free, "omega", "t"),
        (_free, "state", "t"),
        (_free, "angular_momentum_body", "t"),
        (_free, "precession_angle", "t"),
        (_free, "attitude", "t"),
        (_free, "omega_space", "t"),
        (_free, "poinsot_residuals", "t"),
        (_sym, "omega", "t"),
        (_batch, "state", "t"),
        (_batch, "omega", "t"),
        (_sym, "attitude", "t"),
        (_heavy, "f", "u"),
        (_heavy, "effective_potential", "theta"),
        (_heavy, "u", "t"),
        (_heavy, "theta", "t"),
        (_heavy, "psi", "t"),
        (_heavy, "phi", "t"),
        (_heavy, "rates", "t"),
        (_heavy, "energy_at", "t"),
        (_heavy, "integrals_at", "t"),
    ],
)
def test_every_method_names_its_argument_when_it_is_not_finite(make, method, param):
    fn = getattr(make(), method)
    for bad in ([0.5, np.nan], np.inf):
        check_refusal(lambda b=bad: fn(b), {}, param, NonFiniteError, r"must be finite; found")


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda w: tops.FreeAsymmetricTop([1.0, 2.0, 3.0], w), "omega_0"),
        (lambda w: tops.FreeSymmetricTop(1.0, 2.0, w), "omega_0"),
        (
            lambda w: tops.spherical_top_on_incline(
                0.5, m=1.0, R=0.1, J=0.004, beta=0.3, g=9.81, omega_0=w
            ),
            "omega_0",
        ),
    ],
)
def test_a_batch_of_initial_spins_is_refused_naming_the_shape_wanted(call, name):
    with pytest.raises(ShapeError) as info:
        call(np.ones((2, 3)))
    assert str(info.value) == f"{name} must have shape (3,); got (2, 3)"


@pytest.mark.parametrize("scale", [1.0, 2.0**40, 2.0**-40, 1e150])
def test_free_symmetric_tops_L_and_E_are_those_of_the_spin_given_at_any_scale(scale):
    # |L| = |(J1 ω1, J1 ω2, J3 ω3)| and E = ½ Σ J ω², formed directly: the top scales ω by
    # a power of two inside, and must scale the results back by the right powers
    J1, J3 = 2.0, 3.0
    w0 = np.array([0.3, -0.2, 0.5]) * scale
    top = tops.FreeSymmetricTop(J1, J3, w0)
    Jw = np.array([J1, J1, J3]) * w0
    assert top.angular_momentum_norm == pytest.approx(math.hypot(*Jw), rel=4 * EPS)
    assert top.energy == pytest.approx(0.5 * float(Jw @ w0), rel=4 * EPS)
    np.testing.assert_allclose(top.angular_momentum_space, Jw, rtol=4 * EPS)


def test_poinsot_residuals_vanish_at_one_instant_and_over_a_grid_of_times():
    top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [1.0, 0.1, 0.5], R0)
    ell, plane = top.poinsot_residuals(2.5)
    assert np.shape(ell) == ()
    assert np.shape(plane) == ()
    assert abs(ell) <= POINSOT_RTOL * top.energy
    ell, plane = top.poinsot_residuals(np.linspace(0.0, 5.0, 6).reshape(2, 3))
    assert ell.shape == plane.shape == (2, 3)
    assert np.abs(ell).max() <= POINSOT_RTOL * top.energy


def test_on_the_separatrix_one_instant_keeps_the_angular_momentum_fixed_in_space():
    # J = (3, 4, 6), ω = (2, 1/2, 1): L² − 2 E J2 = −3·4 + 6·2·1 = 0 exactly, the separatrix;
    # the attitude of one instant (the scalar path) carries J ω back to L_O
    top = tops.FreeAsymmetricTop([3.0, 4.0, 6.0], [2.0, 0.5, 1.0])
    assert top.regime == "separatrix"
    for t in (0.7, -2.0, 15.0):
        R, w = top.attitude(t), top.omega(t)
        L_O = R.T @ (top.J * w)
        L = np.abs(top.angular_momentum_space).max()
        assert np.abs(L_O - top.angular_momentum_space).max() <= SEPARATRIX_L_ATOL * L


@pytest.mark.parametrize(
    ("kwargs", "name", "shown", "largest"),
    [
        ({"J_1": 1e-300, "L_3": 1e10, "m_g_ell": 1.0}, "J_1", "1e-300", "10000000000.0"),
        ({"J_1": 1.0, "L_3": -1e10, "m_g_ell": 1e-300}, "m_g_ell", "1e-300", "10000000000.0"),
        ({"J_1": 1e300, "L_3": 0.0, "m_g_ell": 1e-10}, "m_g_ell", "1e-10", "1e+300"),
    ],
)
def test_steady_precession_refuses_a_ratio_below_float64s_range_naming_it(
    kwargs, name, shown, largest
):
    # J'1/max or mgℓ/max below 2^-1022: the scaled quadratic would lose that coefficient
    with pytest.raises(OutOfDomainError) as info:
        tops.steady_precession_rates(theta=0.5, **kwargs)
    assert str(info.value) == (
        f"{name} = {shown} is below 1e-308 of the largest of J_1, |L_3|, m_g_ell ({largest}): "
        "the ratio underflows float64 (rescale, or treat the top as free)"
    )


def test_steady_precession_takes_ratios_down_to_float64s_normal_range():
    # J'1 cos θ Ω² − L3 Ω + mgℓ = 0 is homogeneous in (J'1, L3, mgℓ): dividing
    # (2^-1000, 1, 2^-1000) by 2^-1000 gives (1, 2^1000, 1), the same roots Ω; the ratio
    # 2^-1000 is still normal, so both are computed, and agree to a few roundings
    a = tops.steady_precession_rates(2.0**-1000, 1.0, 2.0**-1000, 0.5)
    b = tops.steady_precession_rates(1.0, 2.0**1000, 1.0, 0.5)
    assert a == pytest.approx(b, rel=4 * EPS)
    assert 0 < a[0] < a[1]  # slow and fast, both finite


@pytest.mark.parametrize("w0", [[0.0, 0.0, 2.0], [0.0, 0.0, 0.0], [1.0, 1.0, 0.0]])
def test_a_steady_or_resting_top_has_no_precession_and_turns_as_exp_t_omega(w0):
    """ω along a principal axis, zero, or in the plane of two equal moments: ω ∥ L stays
    put in the body, ψ(t) − ψ(0) = 0 (the turn is all spin) and R(t) = R3-about-ω(|ω| t)."""
    J = [1.0, 1.0, 1.5]
    top = tops.FreeAsymmetricTop(J, w0)
    t = np.array([0.0, 0.5, 2.0])
    psi = top.precession_angle(t)
    assert psi.shape == (3,)
    np.testing.assert_array_equal(psi, [0.0, 0.0, 0.0])
    # Ṙ = −[ω]× R from R(0) = I: R(t) = I − sin(|ω| t) K + (1 − cos(|ω| t)) K², K = [ω̂]×
    w = np.asarray(w0, dtype=float)
    n = w / np.linalg.norm(w) if w.any() else w
    K = np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])
    a = np.linalg.norm(w) * t
    want = np.eye(3) - np.sin(a)[:, None, None] * K + (1 - np.cos(a))[:, None, None] * (K @ K)
    # sines and cosines of O(1) angles and products of unit entries: a few roundings each
    np.testing.assert_allclose(top.attitude(t), want, rtol=0, atol=8 * EPS)


def test_a_top_without_spin_precesses_steadily_only_hanging_at_plus_minus_root_2_mgl_over_j1():
    """L3 = 0: J'1 cos θ Ω² + m g ℓ = 0 (5.60) has roots only for cos θ < 0; at θ = 2π/3
    (cos θ = −½), J'1 = 1, m g ℓ = 2: Ω = ±√(2 m g ℓ / J'1) = ±2 (a conical pendulum)."""
    slow, fast = tops.steady_precession_rates(1.0, 0.0, 2.0, 2 * math.pi / 3)
    # cos(2π/3) is −½ to one rounding; a square root and a division
    assert abs(slow + 2.0) <= 8 * EPS * 2
    assert abs(fast - 2.0) <= 8 * EPS * 2


def test_a_fast_precession_beyond_float64_is_refused_naming_its_parts():
    """L3 = 1e300 at θ = π/2 (cos θ = 6.1e-17 in float64): L3/(J'1 cos θ) ≈ 1.6e316."""
    with pytest.raises(
        ResultOverflowError,
        match=r"^the fast precession rate L3/\(J'1 cos θ\) exceeds float64's range \(J_1 = "
        r".* scaled, cos θ = 6\.12323399573676\d*e-17\); rescale \(choose units\)$",
    ):
        tops.steady_precession_rates(1.0, 1e300, 1.0, math.pi / 2)


def test_a_motion_within_float64s_reach_of_the_separatrix_is_refused_with_the_remedy():
    with pytest.raises(OutOfDomainError) as info:
        tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [1e-200, 1.0, 1e-200])
    assert str(info.value) == (
        "the motion is within m1 ≈ 2^-1328 of the separatrix: the complementary parameter m1 "
        "underflows float64 (the transverse components are below ~1e-150 of |ω|); set them "
        "to zero for the steady rotation or scale them up"
    )


# -- HeavySymmetricTop: construction and validation (mutation review) --


def test_heavy_top_angle_shape_and_domain_messages():
    with pytest.raises(ShapeError, match=r"^psi_dot must be a scalar; got shape \(2,\)$"):
        tops.HeavySymmetricTop(1.0, 1.0, 1.0, theta=0.5, psi_dot=[1.0, 2.0])
    # the closed interval [0, π]: both ends accepted, one ulp outside refused
    tops.HeavySymmetricTop(1.0, 1.0, 1.0, theta=0.0)
    tops.HeavySymmetricTop(1.0, 1.0, 1.0, theta=math.pi)
    bad = math.nextafter(math.pi, 4.0)
    with pytest.raises(OutOfDomainError, match=r"^theta must lie in \[0, π\]; got "):
        tops.HeavySymmetricTop(1.0, 1.0, 1.0, theta=bad)


def test_heavy_top_conserved_quantities_by_hand():
    # J_1 = 2, J_3 = 1, m g ℓ = 3, θ = π/2, ψ' = 1, φ' = 4, θ' = 0; u0 = cos θ ≈ 6e-17
    # (float π/2), within the tolerance of 0, so the book's formulas at u0 = 0, S = 1:
    # L3 = J3 (ψ' u0 + φ') = 4; Lz = J1 S² ψ' + L3 u0 = 2;
    # E = ½ J1 (θ'² + ψ'² S²) + L3²/(2 J3) + m g ℓ u0 = 1 + 8 + 0 = 9
    t = tops.HeavySymmetricTop(2.0, 1.0, 3.0, theta=math.pi / 2, psi_dot=1.0, phi_dot=4.0)
    tol = 8 * EPS * 10  # a few roundings of terms of size ≤ 10
    assert abs(t.L_3 - 4.0) <= tol
    assert abs(t.L_z - 2.0) <= tol
    assert abs(t.energy - 9.0) <= tol
    assert t.sleeping is False


def test_heavy_top_sleeping_and_gimbal_lock():
    t = tops.HeavySymmetricTop(1.0, 1.0, 1.0, theta=0.0, phi_dot=5.0)
    assert t.sleeping is True
    assert t.roots == (1.0, 1.0, math.inf)
    with pytest.raises(GimbalLockError, match=r"^theta = 0 or π with theta_dot ≠ 0: "):
        tops.HeavySymmetricTop(1.0, 1.0, 1.0, theta=0.0, theta_dot=0.1)


# ------------------------------------------------- mutation review (full run of tops.py)


def test_skew_is_the_cross_product_matrix():
    """[w]× v = w × v for every v (the matrix of the cross product, 4.2): checked on the
    basis vectors, so each column is w × e_i, exactly (a product by 0 or 1 and a sign)."""
    w = np.array([2.0, -3.0, 5.0])
    S = tops._skew(w)
    assert S.shape == (3, 3)
    for i, e in enumerate(np.eye(3)):
        np.testing.assert_array_equal(S[:, i], np.cross(w, e))
    np.testing.assert_array_equal(S, -S.T)


def test_spherical_top_on_incline_exactly_at_the_steepest_and_flattest_slopes():
    """Example 5.1 with numbers that are exact in binary: m = 2, R = ½, J = ½, g = 4 at
    β = π/2 (sin of the float π/2 is 1.0 exactly): α = R m g / (J + m R²) = 4 / 1 = 4
    (5.15); x = x0 + R ω_y0 t + ½ R α t², y = y0 − R ω_x0 t, ω = (ω_x0, ω_y0 + α t, ω_z0)
    (5.16)–(5.23), every term a dyadic rational: exact."""
    t = np.array([0.0, 0.5, 1.0, 2.0])
    w0 = [3.0, -1.0, 7.0]
    x, y, w = tops.spherical_top_on_incline(
        t, m=2.0, R=0.5, J=0.5, beta=math.pi / 2, g=4.0, x0=1.0, y0=-2.0, omega_0=w0
    )
    np.testing.assert_array_equal(x, 1.0 + 0.5 * -1.0 * t + 0.5 * 0.5 * 4.0 * t * t)
    np.testing.assert_array_equal(y, -2.0 - 0.5 * 3.0 * t)
    assert w.shape == (4, 3)
    np.testing.assert_array_equal(w, np.stack([3.0 + 0 * t, -1.0 + 4.0 * t, 7.0 + 0 * t], -1))
    # β = 0, a level floor: no acceleration, uniform rolling; the defaults start at rest
    # at the origin, where the sphere stays
    x, y, w = tops.spherical_top_on_incline(t, m=2.0, R=0.5, J=0.5, beta=0.0, g=4.0, omega_0=w0)
    np.testing.assert_array_equal(x, -0.5 * t)
    np.testing.assert_array_equal(y, -1.5 * t)
    np.testing.assert_array_equal(w, np.tile(w0, (4, 1)))
    x, y, w = tops.spherical_top_on_incline(t, m=2.0, R=0.5, J=0.5, beta=0.0, g=4.0)
    np.testing.assert_array_equal(np.concatenate([x, y, w.ravel()]), 0.0)
    # one instant: scalars and ω of shape (3,)
    x, y, w = tops.spherical_top_on_incline(
        2.0, m=2.0, R=0.5, J=0.5, beta=math.pi / 2, g=4.0, omega_0=w0
    )
    assert (float(x), float(y)) == (-1.0 + 4.0, -3.0)
    np.testing.assert_array_equal(w, [3.0, 7.0, 7.0])
    # a steep slope between π/3 and π/2 is inside the domain: α = (5/7) g sin β / R for
    # a uniform sphere (J = 2 m R²/5), a few roundings
    x, _, _ = tops.spherical_top_on_incline(1.0, m=1.0, R=1.0, J=0.4, beta=1.2, g=1.0)
    assert float(x) == pytest.approx(0.5 * 5 / 7 * math.sin(1.2), rel=8 * EPS)


@pytest.mark.parametrize("beta", [-1e-300, math.nextafter(math.pi / 2, 4.0), 2.0])
def test_spherical_top_on_incline_refuses_a_slope_outside_0_to_pi_over_2_naming_it(beta):
    with pytest.raises(OutOfDomainError) as info:
        tops.spherical_top_on_incline(1.0, m=1.0, R=1.0, J=0.4, beta=beta, g=1.0)
    assert str(info.value) == f"beta must lie in [0, π/2]; got {beta!r}"


@pytest.mark.parametrize("param", ["t", "x0", "y0", "beta"])
def test_spherical_top_on_incline_names_a_non_finite_argument(param):
    kw = {"t": 1.0, "m": 1.0, "R": 1.0, "J": 0.4, "beta": 0.5, "g": 1.0} | {param: math.nan}
    with pytest.raises(NonFiniteError, match=rf"(?<![A-Za-z0-9_]){param}(?![A-Za-z0-9_])"):
        tops.spherical_top_on_incline(**kw)


def test_steady_precession_at_a_double_root_is_l3_over_2_j1():
    """(5.60) J'1 cos θ Ω² − L3 Ω + m g ℓ = 0 at θ = 0 (cos θ = 1 exactly) with L3² = 4 J'1 m g ℓ:
    J'1 = 1, L3 = 2, m g ℓ = 1 gives the double root Ω = L3/(2 J'1) = 1, exact (the edge of
    the domain, L3² − 4 J'1 m g ℓ cos θ = 0, is inside it)."""
    assert tops.steady_precession_rates(1.0, 2.0, 1.0, 0.0) == (1.0, 1.0)
    assert tops.steady_precession_rates(1.0, -2.0, 1.0, 0.0) == (-1.0, -1.0)
    # just inside: L3 = 2 + 2^-51 gives two distinct real roots about 1
    slow, fast = tops.steady_precession_rates(1.0, 2.0 + 2.0**-51, 1.0, 0.0)
    assert slow < 1.0 < fast
    # and at θ = 0 away from the edge, J'1 = 1, L3 = 5, m g ℓ = 4: Ω² − 5 Ω + 4 = 0, Ω = 1, 4
    assert tops.steady_precession_rates(1.0, 5.0, 4.0, 0.0) == (1.0, 4.0)


def test_a_hanging_top_without_spin_is_a_conical_pendulum_of_rate_root_mgl_over_j1():
    """θ = π (cos θ = −1 exactly in float64), L3 = 0: (5.60) is −J'1 Ω² + m g ℓ = 0,
    Ω = ±√(m g ℓ / J'1) = ±2 for J'1 = 1, m g ℓ = 4: exact, the negative one first (the
    documented pair (−r, r))."""
    assert tops.steady_precession_rates(1.0, 0.0, 4.0, math.pi) == (-2.0, 2.0)


@pytest.mark.parametrize(
    ("J1", "L3", "mgl", "shown"),
    [
        (1.0, 1.0, 1.0, "-3"),  # 1 − 4
        (1.0, -1.0, 1.0, "-3"),
        (2.0, 3.0, 1.5, "-3"),  # 9 − 12
    ],
)
def test_no_steady_precession_is_refused_with_the_condition(J1, L3, mgl, shown):
    """θ = 0: L3² − 4 J'1 m g ℓ cos θ < 0.  The message prints the discriminant of the
    values given (the quadratic is solved on them scaled by a power of two, whose
    discriminant −0.75 for the first case the message once showed: a value the user never
    gave); where it leaves float64, the scaled one times its power of two."""
    with pytest.raises(OutOfDomainError) as info:
        tops.steady_precession_rates(J1, L3, mgl, 0.0)
    assert str(info.value) == f"no steady precession: L3² − 4 J'1 m g ℓ cos θ = {shown} < 0"


def test_no_steady_precession_beyond_float64_shows_the_discriminant_by_its_power_of_two():
    """J'1 = |L3| = m g ℓ = 1e200, θ = 0: the discriminant −3e400 is beyond float64; the
    message gives it as a mantissa times a power of two, which (read exactly) is −3e400 to
    the 6 digits shown."""
    with pytest.raises(OutOfDomainError) as info:
        tops.steady_precession_rates(1e200, 1e200, 1e200, 0.0)
    m = re.fullmatch(
        r"no steady precession: L3² − 4 J'1 m g ℓ cos θ = (\S+) × 2\^(\d+) < 0", str(info.value)
    )
    assert m is not None, str(info.value)
    value = Fraction(m.group(1)) * 2 ** int(m.group(2))
    assert abs(value / (-3 * Fraction(10) ** 400) - 1) < Fraction(1, 10**5)


@pytest.mark.parametrize("J1", [2.0**-1021, 2.0**-1022, 1.5e-308, 1e-308])
def test_steady_precession_takes_every_ratio_down_to_the_documented_floor(J1):
    """J'1 down to 1e-308 of |L3| (the documented floor; float64's normal minimum
    2^-1022 ≈ 2.2e-308 of it and below were once refused, by a check on the values scaled
    to [1/2, 1)): taken, and equal to the same top scaled by 2^1022, whose values are
    ordinary (the rates depend on J'1, L3, m g ℓ only through their ratios)."""
    a = tops.steady_precession_rates(J1, 1.0, 2 * J1, 0.5)
    b = tops.steady_precession_rates(J1 * 2.0**1022, 2.0**1022, 2 * J1 * 2.0**1022, 0.5)
    # the same quadratic scaled by a power of two: the roots by a few roundings
    assert a == pytest.approx(b, rel=4 * EPS)


def test_steady_precession_refuses_a_ratio_below_the_documented_floor():
    with pytest.raises(OutOfDomainError, match=r"^J_1 = 5e-309 is below 1e-308 of the largest"):
        tops.steady_precession_rates(5e-309, 1.0, 1e-308, 0.5)


def test_free_top_omega_space_is_omega_turned_to_space_by_the_integrated_attitude():
    """ω_O = Rᵀ ω_A: from DOP853's ω and R on Euler's equations (4.47) and Ṙ = −[ω]× R,
    over times and at one instant (shape (3,))."""
    J, w0 = [1.0, 2.0, 3.0], np.array([0.4, 0.2, 1.0])
    top = tops.FreeAsymmetricTop(J, w0, R0)
    ts = np.linspace(0, 10, 11)
    w_ref, R_ref = _integrate(J, w0, ts)
    want = np.einsum("nji,nj->ni", R_ref, w_ref)
    got = top.omega_space(ts)
    assert got.shape == (11, 3)
    # ω and R each within the integrator's error, a sum of three products of them
    assert np.abs(got - want).max() <= 4 * ODE_ATOL * 10
    one = top.omega_space(ts[4])
    assert one.shape == (3,)
    assert np.abs(one - want[4]).max() <= 4 * ODE_ATOL * 10
    # at t = 0: R0ᵀ ω0, a sum of three products (a few roundings of |ω0| ~ 1)
    np.testing.assert_allclose(top.omega_space(0.0), R0.T @ w0, rtol=0, atol=8 * EPS)


@pytest.mark.parametrize("w0", [[0.4, 0.0, 0.7], [0.0, 0.4, 0.7]])
def test_free_symmetric_top_with_one_transverse_spin_component_zero_precesses(w0):
    """ω0 with ω1 = 0 or ω2 = 0 (but not both) is not along L: the top precesses
    (5.34)–(5.45); its attitude must follow DOP853 on Euler's equations, not a uniform turn
    about ω0."""
    J1, J3 = 1.0, 1.5
    top = tops.FreeSymmetricTop(J1, J3, w0, R0)
    ts = np.linspace(0, 10, 11)
    w_ref, R_ref = _integrate([J1, J1, J3], np.asarray(w0), ts)
    assert np.abs(top.omega(ts) - w_ref).max() <= ODE_ATOL
    assert np.abs(top.attitude(ts) - R_ref).max() <= ODE_ATOL * 10


def test_free_symmetric_top_refuses_j3_above_2_j1_with_both_values():
    with pytest.raises(NonPhysicalInertiaError) as info:
        tops.FreeSymmetricTop(2.0, 5.0, [0.0, 0.0, 1.0])
    assert str(info.value) == (
        "J3 = 5.0 exceeds 2 J1 = 4.0: the moments of a symmetric body obey the triangle "
        "inequality J3 ≤ J1 + J2 = 2 J1"
    )


def test_free_symmetric_top_refuses_an_angular_momentum_beyond_float64():
    """J3 ω3 = 1e300 · 1e10 = 1e310 > float64's largest (1.8e308): ResultOverflowError."""
    with pytest.raises(ResultOverflowError, match="exceeds float64's range"):
        tops.FreeSymmetricTop(1e300, 1e300, [0.0, 0.0, 1e10])


@pytest.mark.parametrize(("Jscale", "wscale"), [(1e-200, 1e160), (1e200, 1e-170)])
def test_free_symmetric_tops_energy_where_omega_squared_leaves_float64(Jscale, wscale):
    """ω² = 1e320 overflows and 1e-340 underflows float64, yet E = ½ Σ J ω² ≈ 1e120 and
    1e-140 fit: the documented domain (|L| and E within float64).  Expected values from
    exact rationals of the same floats, rounded once."""
    from fractions import Fraction

    import mpmath

    def root(x: Fraction) -> float:  # √x of an exact rational, rounded once (mpmath, 80 digits)
        with mpmath.workdps(80):
            return float(mpmath.sqrt(mpmath.mpf(x.numerator) / x.denominator))

    J1, J3 = 2.0 * Jscale, 3.0 * Jscale
    w0 = [0.3 * wscale, -0.2 * wscale, 0.5 * wscale]
    top = tops.FreeSymmetricTop(J1, J3, w0)
    Js = [Fraction(J1), Fraction(J1), Fraction(J3)]
    E = sum(j * Fraction(w) ** 2 for j, w in zip(Js, w0, strict=True)) / 2
    L2 = sum((j * Fraction(w)) ** 2 for j, w in zip(Js, w0, strict=True))
    # a handful of roundings in the scaled products and sums
    assert top.energy == pytest.approx(float(E), rel=8 * EPS)
    assert top.angular_momentum_norm == pytest.approx(root(L2), rel=8 * EPS)
    # |L|/J1, the precession rate (5.34): of order ω
    assert top.space_precession_rate == pytest.approx(root(L2 / Fraction(J1) ** 2), rel=8 * EPS)


def test_the_sleeping_top_at_the_margin_l3_squared_equal_4_j1_mgl_is_not_stable():
    """(5.72) asks L3² > 4 J'1 m g ℓ, strictly: at L3 = 2, J'1 = m g ℓ = 1 equality holds
    (exact), the sleeping top is not stable (the double root u = 1 of f)."""
    assert not tops.sleeping_top_is_stable(1.0, 2.0, 1.0)
    assert tops.sleeping_top_is_stable(1.0, math.nextafter(2.0, 3.0), 1.0)


def test_principal_axis_stability_neutral_refusals_and_messages():
    """J = (1, 1, 2) about axis 1: C_k = (J_1 − J_2)/J_3 = 0, the linearisation (5.102) is
    neutral (rate 0, C_i C_k = 0); a vector omega and a bool or float axis are refused."""
    assert tops.principal_axis_stability([1.0, 1.0, 2.0], 1) == tops.StabilityResult(
        "neutral", 0.0, 0.0
    )
    assert tops.principal_axis_stability([1.0, 2.0, 3.0], 2, omega=0.0).kind == "neutral"
    with pytest.raises(ShapeError) as info:
        tops.principal_axis_stability([1.0, 2.0, 3.0], 2, omega=[1.0, 2.0])
    assert str(info.value) == "omega must be a scalar"
    for axis in (True, 2.0):
        with pytest.raises(UnknownOptionError) as info:
            tops.principal_axis_stability([1.0, 2.0, 3.0], axis)
        assert str(info.value) == f"axis must be 1, 2 or 3; got {axis!r}"


_HEAVY_UNDERFLOW = (
    "{name} = {shown} is below 1e-308 of the largest of J_1, J_3, m_g_ell ({largest}): the "
    "ratio underflows float64 (for m_g_ell: gravity is negligible, use FreeSymmetricTop)"
)


@pytest.mark.parametrize(
    ("J_1", "J_3", "mgl", "name", "shown", "largest"),
    [
        (1e-310, 1e-310, 1.0, "J_1", "1e-310", "1.0"),  # the largest is m g ℓ
        (1.0, 1.0, 1e-310, "m_g_ell", "1e-310", "1.0"),  # J'1 = J3 the largest
        (1.0, 1e-310, 0.5, "J_3", "1e-310", "1.0"),  # the largest is J'1
        (0.75, 1.0, 1e-310, "m_g_ell", "1e-310", "1.0"),  # the largest is J3
        (1e300, 1e-10, 1e-10, "J_3", "1e-10", "1e+300"),  # J'1 beyond 2^1024 of the others
    ],
)
def test_heavy_top_ratio_underflow_names_the_parameter_and_the_largest(
    J_1, J_3, mgl, name, shown, largest
):
    with pytest.raises(OutOfDomainError) as e:
        tops.HeavySymmetricTop(J_1, J_3, mgl, theta=0.5)
    assert str(e.value) == _HEAVY_UNDERFLOW.format(name=name, shown=shown, largest=largest)


def test_heavy_top_full_messages_for_the_triangle_inequality_and_gimbal_lock():
    # J_3 = 2 J_1 exactly is allowed (a flat disc's limit, J_3 ≤ J_1 + J_2 = 2 J_1); one
    # ulp above is refused as far above is, the message naming both values
    tops.HeavySymmetricTop(1.0, 2.0, 1.0, theta=0.5)
    for J_3 in (math.nextafter(2.0, 3.0), 3.0):
        with pytest.raises(NonPhysicalInertiaError) as e:
            tops.HeavySymmetricTop(1.0, J_3, 1.0, theta=0.5)
        assert str(e.value) == (
            f"J_3 = {J_3!r} exceeds 2 J_1 = 2.0: the moments of a symmetric body obey the "
            "triangle inequality J_3 ≤ J_1 + J_2 = 2 J_1 (about G, and so about any point of "
            "the axis)"
        )
    with pytest.raises(GimbalLockError) as e:
        tops.HeavySymmetricTop(1.0, 1.0, 1.0, theta=0.0, theta_dot=-0.1)
    assert str(e.value) == (
        "theta = 0 or π with theta_dot ≠ 0: the Euler angles are singular; start the top at "
        "a small θ > 0 instead"
    )


def test_a_sleeping_top_turns_uniformly_at_its_initial_rates():
    """θ = 0, θ̇ = 0 and L3² > 4 J'1 m g ℓ (5.72): the top stays upright and ψ, φ advance
    at their initial rates, ψ0 + ψ̇0 t and φ0 + φ̇0 t, exact at dyadic times."""
    top = tops.HeavySymmetricTop(
        1.0, 1.0, 1.0, theta=0.0, psi=0.25, phi=0.5, psi_dot=1.5, phi_dot=5.0
    )
    assert top.sleeping is True
    t = np.array([0.0, 0.5, 2.0, 8.0])
    np.testing.assert_array_equal(top.psi(t), 0.25 + 1.5 * t)
    np.testing.assert_array_equal(top.phi(t), 0.5 + 5.0 * t)
    np.testing.assert_array_equal(top.theta(t), 0.0)


#: the heavy top's rates at t = 0 rebuilt from the roots of f(u) (refined to rounding) and
#: sn, cn, dn of the initial argument: a few roundings of rates of size ≤ 8
HEAVY_RATES_ATOL = 64 * EPS * 8
#: central difference of θ(t) with h = 1e-5: truncation h² θ''' ~ 1e-9, rounding eps/h ~ 2e-11
THETA_FD_ATOL = 2**22 * EPS


@pytest.mark.parametrize("theta_dot", [0.3, -0.3])
def test_heavy_top_rates_start_at_the_initial_rates_and_are_the_derivative_of_theta(theta_dot):
    """(θ̇, ψ̇, φ̇)(0) are the initial rates given, with θ̇'s sign (rising or falling top);
    later θ̇ is dθ/dt of θ(t) (a central difference)."""
    top = tops.HeavySymmetricTop(
        2.0, 1.0, 3.0, theta=0.5, theta_dot=theta_dot, psi_dot=1.0, phi_dot=8.0
    )
    thd, psid, phid = top.rates(0.0)
    assert abs(thd - theta_dot) <= HEAVY_RATES_ATOL
    assert abs(psid - 1.0) <= HEAVY_RATES_ATOL
    assert abs(phid - 8.0) <= HEAVY_RATES_ATOL
    h = 1e-5
    for t in (0.37, 1.3, 2.9):
        fd = (top.theta(t + h) - top.theta(t - h)) / (2 * h)
        assert abs(top.rates(t)[0] - fd) <= THETA_FD_ATOL


#: the flip period 4K(m)/λ: K of a complementary parameter held exactly (m1 ~ 1e-16) and
#: λ a square root, a few roundings each (measured 0 eps against mpmath)
FLIP_PERIOD_RTOL = 16 * EPS


def test_flip_period_within_an_ulp_of_the_separatrix_uses_the_exact_complementary_parameter():
    """J = (1, 2, 3), ω0 = (1, 0, fl(1/√3)): L² − 2E J2 = 3 ω3² − 1 ≈ 1e-16, so
    m1 = 1 − k² ≈ 1.2e-16, below the ulp of 1 (1 − m in float64 would be 1.1e-16 and K off
    by 1e-3).  Period 4K(k²)/λ with λ² and k² of the book's Jacobi solution (5.3.2, the
    standard closed form), from exact rationals of the floats given and mpmath's K."""
    from fractions import Fraction

    import mpmath

    J, w = [1.0, 2.0, 3.0], [1.0, 0.0, 0.5773502691896257]
    J1, J2, J3 = (Fraction(x) for x in J)
    wf = [Fraction(x) for x in w]
    E2 = sum(j * x * x for j, x in zip((J1, J2, J3), wf, strict=True))
    L2 = sum((j * x) ** 2 for j, x in zip((J1, J2, J3), wf, strict=True))
    if L2 > E2 * J2:
        lam2 = (J3 - J2) * (L2 - E2 * J1) / (J1 * J2 * J3)
        k2 = (J2 - J1) * (E2 * J3 - L2) / ((J3 - J2) * (L2 - E2 * J1))
    else:
        lam2 = (J2 - J1) * (E2 * J3 - L2) / (J1 * J2 * J3)
        k2 = (J3 - J2) * (L2 - E2 * J1) / ((J2 - J1) * (E2 * J3 - L2))
    m1 = 1 - k2
    assert 0 < m1 < Fraction(2**-52)
    with mpmath.workdps(60):
        K = mpmath.ellipk(1 - mpmath.mpf(m1.numerator) / m1.denominator)
        want = float(4 * K / mpmath.sqrt(mpmath.mpf(lam2.numerator) / lam2.denominator))
    assert tops.FreeAsymmetricTop(J, w).flip_period() == pytest.approx(want, rel=FLIP_PERIOD_RTOL)


def test_angular_momentum_in_the_body_is_j_omega_and_keeps_its_length():
    """L_A = J ω_A (4.5, principal axes): (0.4, 0.4, 3.0) at t = 0 for J = (1, 2, 3),
    ω0 = (0.4, 0.2, 1.0); later |L_A| = |L| (L fixed in space, 5.3.1) and
    R(t)ᵀ L_A(t) = L_O."""
    top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [0.4, 0.2, 1.0], R0)
    # ω(0) is rebuilt from sn, cn, dn at the initial argument: a few eps of |ω|, times J ≤ 3
    np.testing.assert_allclose(top.angular_momentum_body(0.0), [0.4, 0.4, 3.0], atol=8 * EPS * 3)
    ts = np.linspace(0, 10, 11)
    LA = top.angular_momentum_body(ts)
    assert LA.shape == (11, 3)
    norm = math.hypot(0.4, 0.4, 3.0)
    # products J ω of values to a few eps of |ω| ≤ 1, J ≤ 3
    np.testing.assert_allclose(np.linalg.norm(LA, axis=-1), norm, rtol=0, atol=32 * EPS * 3)
    LO = np.einsum("nji,nj->ni", top.attitude(ts), LA)
    np.testing.assert_allclose(
        LO, np.tile(R0.T @ [0.4, 0.4, 3.0], (11, 1)), atol=SEPARATRIX_L_ATOL * 3
    )


def test_heavy_top_accepts_gravity_whose_scaled_ratio_is_the_smallest_normal():
    # J'1 = J3 = 1 scale to 1/2 (k = 1), so m g ℓ = 2^-1021 scales to 2^-1022, float64's
    # smallest normal: its ratio to the largest (4.5e-308) is above the documented 1e-308,
    # so the top is built (at rest in θ, u0 = cos 0.5 is one of the roots)
    top = tops.HeavySymmetricTop(1.0, 1.0, 2.0**-1021, theta=0.5, phi_dot=1.0)
    assert top.m_g_ell == 2.0**-1021
    assert math.cos(0.5) in top.roots


@pytest.mark.parametrize("mgl", [3e-308, 1e-308])
def test_heavy_top_accepts_gravity_down_to_1e308_of_the_largest(mgl):
    """m g ℓ = 3e-308 and 1e-308 of J'1 = J3 = 1: at or above the documented floor (once
    refused with a message saying it was below it: the check was float64's normal minimum
    on the values scaled to [1/2, 1), 2.2e-308 to 4.5e-308 of the largest).  Built, and
    moving as the same top scaled by 2^600, whose values are ordinary (the motion depends
    on J'1, J3, m g ℓ only through their ratios)."""
    # slow rates: u3 − 1 ~ (θ̇² + b²)/β stays within float64 at β = 2e-308
    kw = dict(theta=0.5, theta_dot=0.01, psi_dot=0.02, phi_dot=0.05)
    top = tops.HeavySymmetricTop(1.0, 1.0, mgl, **kw)
    big = tops.HeavySymmetricTop(2.0**600, 2.0**600, mgl * 2.0**600, **kw)
    ts = np.linspace(0.0, 5.0, 6)
    for name in ("theta", "psi", "phi"):
        # the same computation on values scaled by powers of two (2^-1022 against 2^-423
        # at the smallest): equal to their roundings, a few eps of the angles' size (~5)
        np.testing.assert_allclose(
            getattr(top, name)(ts), getattr(big, name)(ts), rtol=0, atol=64 * EPS * 5
        )


def test_heavy_top_rates_overflowing_against_gravity_are_a_result_overflow():
    """θ̇0² J'1/mgℓ beyond float64 (θ̇0 = 1e150, mgℓ = 2^-1021; the documented domain's
    edge): u3 − 1 ≈ θ̇0² J'1/(2 mgℓ) is beyond float64, a ResultOverflowError naming the
    rate (once scipy's ValueError from the root bracket, then an OutOfDomainError naming
    only ψ̇ and φ̇).  θ̇0 = 1e150 against mgℓ = 1 is ordinary, and built."""
    with pytest.raises(ResultOverflowError, match=r"theta_dot = 1e\+150"):
        tops.HeavySymmetricTop(1.0, 1.0, 2.0**-1021, theta=1.0, theta_dot=1e150)
    top = tops.HeavySymmetricTop(1.0, 1.0, 1.0, theta=1.0, theta_dot=1e150)
    assert math.isfinite(top.roots[2])


@pytest.mark.parametrize(
    ("J", "w0", "regime"),
    [
        ([1.0, 2.0, 3.0], [0.0, 0.0, 0.0], "rest"),
        ([1.0, 2.0, 3.0], [0.0, 1.0, 0.0], "steady"),
        ([2.0, 2.0, 2.0], [0.3, 0.4, 1.0], "steady"),
    ],
)
def test_free_top_at_rest_or_steady_has_the_documented_parameters(J, w0, regime):
    # the class docstring: m, m1 are "0 and 1 for steady motions" (sn = sin, a uniform turn)
    top = tops.FreeAsymmetricTop(J, w0)
    assert (top.regime, top.m, top.m1) == (regime, 0.0, 1.0)


def test_free_top_refuses_a_stack_of_initial_attitudes_by_its_shape():
    with pytest.raises(ShapeError) as e:
        tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [1.0, 2.0, 3.0], np.stack([np.eye(3)] * 2))
    assert str(e.value) == "R_A_O_0 must have shape (3, 3); got (2, 3, 3)"


@pytest.mark.parametrize(
    "omega_0",
    [pytest.param([1.0, 1.0, 1.0], id="precessing"), pytest.param([0.0, 0.0, 1.0], id="steady")],
)
def test_free_symmetric_top_refuses_a_stack_of_initial_attitudes_by_its_shape(omega_0):
    # as FreeAsymmetricTop: one attitude, not numpy's matmul error (precessing) or a
    # stack of attitudes carried into attitude(t) (steady)
    with pytest.raises(ShapeError) as e:
        tops.FreeSymmetricTop(1.0, 1.0, omega_0, np.eye(3)[None])
    assert str(e.value) == "R_A_O_0 must have shape (3, 3); got (1, 3, 3)"


def test_free_top_refuses_m1_between_2_to_the_minus_1023_and_1022():
    # J = (1, 2, 3), ω = (0, 1, 2^-512): D = J3(J3 − J2)ω3² = 3·2^-1024 and
    # B = J2(J2 − J1) + J3(J3 − J1)ω3² = 2 + 6·2^-1024, so m1 = (J3 − J1) D/((J3 − J2) B)
    # = 3·2^-1024/(1 + 3·2^-1024): just below 1.5·2^-1023, under float64's normal range
    # (2^-1022) but not under half of it
    with pytest.raises(OutOfDomainError) as e:
        tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [0.0, 1.0, 2.0**-512])
    assert str(e.value) == (
        "the motion is within m1 ≈ 2^-1023 of the separatrix: the complementary parameter m1 "
        "underflows float64 (the transverse components are below ~1e-150 of |ω|); set them to "
        "zero for the steady rotation or scale them up"
    )


def test_heavy_top_angles_of_a_scalar_time_are_scalars():
    top = tops.HeavySymmetricTop(1.0, 0.5, 1.0, **HEAVY["nutating"])
    assert top.psi(0.5).shape == ()
    assert top.phi(0.5).shape == ()


def test_heavy_top_effective_potential_at_the_poles_is_refused_without_a_warning(recwarn):
    # (5.70): (L_z − L3 cos θ)²/(2J'1 sin²θ) with L_z ≠ ±L3 diverges at θ = 0 and π: one
    # ResultOverflowError, and no floating-point warning on the way
    top = tops.HeavySymmetricTop(1.0, 0.5, 1.0, **HEAVY["nutating"])
    with pytest.raises(ResultOverflowError) as e:
        top.effective_potential(np.array([0.0, math.pi]))
    assert str(e.value) == (
        "effective_potential: the result is not finite for finite inputs: an intermediate "
        "exceeds float64's range (~1.8e308); rescale the inputs (choose units)"
    )
    assert not [w for w in recwarn if issubclass(w.category, RuntimeWarning)]


@pytest.mark.parametrize("rate", ["psi_dot", "phi_dot"])
def test_a_heavy_top_whose_turning_point_search_overflows_is_refused_by_name(rate):
    """Rates whose squares leave float64 (found by the public-surface fuzz at
    psi_dot = 2.6e77): the bracket of the largest root doubles until its function is
    inf − inf, and scipy's brentq raised its own ValueError ("the function value ... is
    NaN"); now the library's OutOfDomainError names the rates.  1e70 still runs."""
    kw = dict(theta=0.5, psi=0.1, phi=0.2, theta_dot=0.1, psi_dot=1.0, phi_dot=8.0)
    with pytest.raises(OutOfDomainError, match=r"turning points of θ are beyond float64.*psi_dot"):
        tops.HeavySymmetricTop(2.0, 1.0, 3.0, **{**kw, rate: 1e100})
    top = tops.HeavySymmetricTop(2.0, 1.0, 3.0, **{**kw, rate: 1e70})
    assert np.isfinite(top.theta(np.array([0.0, 1e-70]))).all()


def _turn_about_e2(t: float) -> np.ndarray:
    """exp(−[e2]× t): ^A R^O of a body turning at ω = e2 from R = 1 (Ṙ = −[ω]× R), by
    Rodrigues' formula."""
    K = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [-1.0, 0.0, 0.0]])  # [e2]×
    return np.eye(3) - math.sin(t) * K + (1.0 - math.cos(t)) * (K @ K)


@pytest.mark.parametrize("e", [2.0**-500, 2.0**-508, 2.0**-510, 2.0**-511, 2.0**-511.5])
def test_a_spin_within_1e_150_of_the_middle_axis_turns_as_the_steady_rotation(e):
    """ω0 = (0, 1, e) for J = (1, 2, 3): m1 ≈ 1e-301 … 5e-308, the separatrix's
    neighbourhood that float64 still holds.  Over t ≤ 40 the transverse components grow
    as e·exp(t/√3) ≤ 1e-140, so ω and the attitude are the steady rotation about e2 to
    float64's resolution.  Once, for e ≤ 2^-511, scipy's R_J(0, m1, 1, 1 − n) was inf at
    m1 ≲ 7e-308 (and cn², dn² lost their digits as subnormals near u = K): the top was
    refused as an overflow."""
    top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [0.0, 1.0, e])
    ts = np.array([0.0, 0.5, 3.0, 17.0, 40.0])
    w, R = top.state(ts)
    np.testing.assert_allclose(w, np.tile([0.0, 1.0, 0.0], (len(ts), 1)), rtol=0, atol=4 * EPS)
    # the angle t: rounded once (ψ ~ 40 carries ~40 eps), the rotation's entries to that
    want = np.array([_turn_about_e2(float(t)) for t in ts])
    np.testing.assert_allclose(R, want, rtol=0, atol=64 * EPS * 40)
    batch = tops.FreeTopBatch([[1.0, 2.0, 3.0]] * len(ts), [[0.0, 1.0, e]] * len(ts))
    wb, Rb = batch.state(ts)
    np.testing.assert_allclose(wb, w, rtol=0, atol=4 * EPS)
    np.testing.assert_allclose(Rb, want, rtol=0, atol=64 * EPS * 40)


def test_the_heavy_tops_root_search_is_newtons_from_above_in_a_few_steps():
    """The search for u3 (``_root_from_above``) is Newton's method, quadratic near the
    root: on 0.25 x + x³ (x = y − 0.3, slope 0.25 at its root) from the bracket [0, 4] it
    evaluates the function at most 12 times and ends within an ulp of 0.3; a bisection of
    the same bracket needs ~55 (2^-53 of its width)."""
    calls = []

    def rising(y):
        calls.append(y)
        x = y - 0.3
        return 0.25 * x + x**3, 0.25 + 3.0 * x * x

    root = tops._root_from_above(rising, 0.0, 4.0)
    assert abs(root - 0.3) <= math.ulp(0.3)
    assert len(calls) <= 12, len(calls)


def test_the_heavy_tops_root_search_bisects_where_the_slope_is_flat():
    """A slope of 0 (or one that does not rise) gives no Newton step: the bracket is
    halved instead (never a division by the slope)."""

    def rising(y):
        return y - 0.3, 0.0 if y == 4.0 else 1.0  # flat at the bracket's top only

    assert tops._root_from_above(rising, 0.0, 4.0) == pytest.approx(0.3, abs=4 * EPS)


# ---------------------------- free tops whose moments differ by more than float64's exponent range
@pytest.mark.xfail(
    strict=True,
    reason="bug: the moments scaled by 2^-k (largest in [1/2, 1)) underflow the smallest for a "
    "ratio beyond 2^1074 (J = (1e200, 1e200, 1e-200), each in the documented 1e-300..1e300): its "
    "scaled moment is 0 and the elliptic parameter's denominator (J3 − J2) B or (J2 − J1) A is 0 "
    "(bare ZeroDivisionError); a ratio beyond 2^1022 leaves it subnormal",
)
def test_a_free_top_with_moments_1e400_apart_is_followed():
    top = tops.FreeAsymmetricTop([1e200, 1e200, 1e-200], [1e-10, 0.0, 1.0])
    # E = ½ (1e200 · 1e-20 + 1e-200): the exact value rounded once
    assert top.energy == float((Fraction(1e200) * Fraction(1e-10) ** 2 + Fraction(1e-200)) / 2)


@pytest.mark.xfail(
    strict=True,
    reason="bug: FreeSymmetricTop scales J1 = 1e300, J3 = 1e-300 (the documented extremes) by "
    "2^-997: j3 = 1e-600 underflows to 0, so E = 0 and |L| = 0 for the exact 5e-301 and 1e-300 "
    "(ω = e3), and E = 0 for 1e-300 at ω = (1e-300, 0, 1)",
)
def test_a_free_symmetric_top_with_the_extreme_moments_keeps_its_energy():
    top = tops.FreeSymmetricTop(1e300, 1e-300, [0.0, 0.0, 1.0])
    assert top.energy == 1e-300 / 2  # ½ J3 ω3², exact
    assert top.angular_momentum_norm == 1e-300


def test_a_heavy_top_given_ints_and_numpy_scalars_is_the_top_given_floats():
    """The angles and rates may be any real scalar (ints, numpy scalars, 0-d arrays):
    converted to the same floats, the top is the same to the bit as the one given
    Python floats (the floats take a fast path, the others numpy's conversion)."""
    J1, J3, mgl = 1.0, 0.5, 1.0
    given = dict(
        theta=np.float64(1.0), psi=0, phi=np.array(0.25), theta_dot=np.float32(0.5),
        psi_dot=1, phi_dot=np.int64(5),
    )  # fmt: skip
    top = tops.HeavySymmetricTop(J1, J3, mgl, **given)
    ref = tops.HeavySymmetricTop(J1, J3, mgl, **{k: float(v) for k, v in given.items()})
    ts = np.array([0.0, 0.7, 2.5])
    assert top.roots == ref.roots
    assert (top.theta0, top.psi0, top.phi0) == (1.0, 0.0, 0.25)
    for name in ("theta", "psi", "phi"):
        assert np.array_equal(getattr(top, name)(ts), getattr(ref, name)(ts)), name


@pytest.mark.parametrize(("J3", "refused"), [(2.0, True), (1.0, False)])
def test_the_heavy_tops_gravity_floor_is_against_the_largest_moment_j3_included(J3, refused):
    """m g ℓ = 1.5e-308 against J'1 = 1: 1.5e-308 of J'1, above the documented floor,
    but J3 = 2 (= 2 J'1, allowed) is the largest, and 0.75e-308 of it is below: refused,
    naming m_g_ell and the largest, 2.0.  With J3 = 1 the largest is 1.0: built."""
    if not refused:
        top = tops.HeavySymmetricTop(1.0, J3, 1.5e-308, theta=0.5, phi_dot=1e-150)
        assert top.m_g_ell == 1.5e-308
        return
    with pytest.raises(OutOfDomainError) as e:
        tops.HeavySymmetricTop(1.0, J3, 1.5e-308, theta=0.5, phi_dot=1e-150)
    assert str(e.value).startswith(
        "m_g_ell = 1.5e-308 is below 1e-308 of the largest of J_1, J_3, m_g_ell (2.0)"
    )


def test_the_overflowing_turning_point_is_refused_with_its_whole_message():
    # θ̇0 = 1e150 against m g ℓ = 2^-1021 (the test above): the bracket doubles to inf
    with pytest.raises(ResultOverflowError) as e:
        tops.HeavySymmetricTop(1.0, 1.0, 2.0**-1021, theta=1.0, theta_dot=1e150)
    assert str(e.value) == (
        "the largest turning point of cos θ exceeds float64's range (theta_dot = 1e+150, "
        "psi_dot = 0.0, phi_dot = 0.0, m_g_ell = 4.450147717014403e-308): a rate's square "
        "times J_1/m_g_ell is beyond ~1.8e308; rescale (choose units)"
    )


def test_the_overflowing_root_search_is_refused_with_its_whole_message():
    # as test_a_heavy_top_whose_turning_point_search_overflows_is_refused_by_name
    with pytest.raises(OutOfDomainError) as e:
        tops.HeavySymmetricTop(
            2.0, 1.0, 3.0, theta=0.5, psi=0.1, phi=0.2, theta_dot=0.1, psi_dot=1e100, phi_dot=8.0
        )
    assert re.fullmatch(
        r"the turning points of θ are beyond float64: the search for the largest root "
        r"overflows at 1 − u = \S+ \(theta_dot = 0\.1, psi_dot = 1e\+100, phi_dot = 8\.0, "
        r"m_g_ell = 3\.0\); rescale \(choose units\) so that the rates' squares stay within "
        r"float64",
        str(e.value),
    ), str(e.value)


@pytest.mark.parametrize("theta", [1.0, 2.0])
@pytest.mark.parametrize("over", [5e-5, 5e-4, 1e-2, 0.5])
def test_a_pendulum_swinging_over_the_top_has_u2_exactly_one(theta, over):
    """ψ̇ = φ̇ = 0: a = b = 0, so f(u) = (e − βu)(1 − u²) has the roots −1, 1 and e/β, and
    with energy above the vertical's (e/β = 1 + over) the top passes the vertical: the
    nutation band is [−1, 1], u2 = 1 exactly (1 − u2 = (a − b)²/(...) = 0, the class's
    form without cancellation), however little u3 exceeds 1."""
    # θ̇0² = β(1 + over − u0), β = 2 m g ℓ/J'1 = 2
    thd = math.sqrt(2.0 * (1.0 + over - math.cos(theta)))
    top = tops.HeavySymmetricTop(1.0, 0.5, 1.0, theta=theta, theta_dot=thd)
    assert top.roots[1] == 1.0, top.roots
    assert top.roots[0] == -1.0, top.roots
    assert abs(top.roots[2] - (1.0 + over)) <= 4 * EPS * (1.0 + over), top.roots


#: the pendulum short of the top: u1 = −1 and u3 = 1 are exact roots, u3 = u0 + (1 − u0)
#: rounded twice (cos θ0 and 2 sin²(θ0/2)): 2 eps
PENDULUM_U3_EPS = 2.0


@pytest.mark.parametrize("short", [5e-4, 5e-6])
def test_a_pendulum_swinging_just_short_of_the_top_is_built_with_its_exact_roots(short):
    """a = b = 0 with e/β = 1 − short: u = 1 is the largest root (h(0) ≤ 0 in the class's
    factored form: the search is skipped, u3 − 1 = 0), u = −1 the smallest; u2 = e/β in
    between (its accuracy: the strict xfail below).  The top starts at u0."""
    th = math.pi / 2
    thd = math.sqrt(2.0 * (1.0 - short - math.cos(th)))
    top = tops.HeavySymmetricTop(1.0, 0.5, 1.0, theta=th, theta_dot=thd)
    u1, u2, u3 = top.roots
    assert u1 == -1.0
    assert abs(u3 - 1.0) <= PENDULUM_U3_EPS * EPS
    assert math.cos(th) < u2 < 1.0
    assert abs(float(top.u(0.0)) - math.cos(th)) <= 4 * EPS


#: central differences of the search function at a step of 2^-20 (relative to max(1, y)):
#: truncation ~ |g'''| 2^-40 and rounding ~ eps |g| 2^20 ≈ 2e-10 |g|, both far below 1e-6
SLOPE_RTOL = 1e-6
SLOPE_STEP = 2.0**-20

#: tops whose search for u3 runs on each form of its function: F (u3 − 1 ≤ 1), F/y²
#: (u3 − 1 > 1, a ≠ b) and h (a = b, the pendulum over the top)
SEARCH_FORMS = {
    "F": dict(theta=2.0, theta_dot=1.0, psi_dot=0.5, phi_dot=0.2),  # u3 = 1.022
    "F/y²": dict(theta=1.0, theta_dot=0.3, psi_dot=0.3, phi_dot=8.0),
    "F/y², fast": dict(theta=1.0, theta_dot=4.0, psi_dot=0.75, phi_dot=3.0),
    "h": dict(theta=1.0, theta_dot=2.5),
}


@pytest.mark.parametrize("form", list(SEARCH_FORMS))
def test_the_heavy_tops_root_search_is_given_the_slope_of_its_function(monkeypatch, form):
    """Newton's method needs the slope of the function whose root it seeks: at every
    point the search evaluates, the slope the top passes agrees with a central difference
    of the values it passes (a wrong slope still ends at the root, by bisection, but in
    many more steps), and the search ends in a few Newton steps."""
    seen = []
    search = tops._root_from_above

    def recording(rising, lo, hi):
        def probe(y):
            seen.append((y, rising))
            return rising(y)

        return search(probe, lo, hi)

    monkeypatch.setattr(tops, "_root_from_above", recording)
    tops.HeavySymmetricTop(1.1875, 0.5, 2.140625, **SEARCH_FORMS[form])
    monkeypatch.undo()
    assert 2 <= len(seen) <= 12, len(seen)
    checked = 0
    for y, rising in seen:
        step = SLOPE_STEP * max(1.0, y)
        if y - step <= 0.0 or abs(y - 1.0) <= step:  # the forms switch at y = 1
            continue
        value, slope = rising(y)
        fd = (rising(y + step)[0] - rising(y - step)[0]) / (2.0 * step)
        assert abs(slope - fd) <= SLOPE_RTOL * max(abs(fd), abs(value), 1.0), (y, slope, fd)
        checked += 1
    assert checked >= 2, seen


#: ψ̇ = (a − b u)/(1 − u²) at the fixed u = u0 and φ̇ = L3/J3 − ψ̇ u0, each a few roundings
#: from the given rates (measured ≤ 2 eps of the rate), over t ≤ 10: 64 eps of |rate| t
STEADY_ANGLE_EPS = 64.0


@pytest.mark.parametrize(
    ("theta", "phi_dot", "psi_dot"),
    [(0.3, 5.0, 0.4363853630175805), (0.3, 20.0, 0.10048228681709957)],
)
def test_a_top_started_on_its_steady_precession_precesses_uniformly(theta, phi_dot, psi_dot):
    """θ̇0 = 0 and ψ̇0 the slow steady rate (5.60) to the ulp at which the computed nutation
    band closes (u2 − u1 = 0 exactly, a double root at u0): the top stays at θ0 and its ψ
    and φ turn uniformly at the rates given (the book's steady precession)."""
    import mpmath

    # the input is the slow root of (5.60) with L3 = J3 (ψ̇ cos θ + φ̇), i.e. of
    # (J'1 − J3) cos θ Ω² − J3 φ̇ Ω + m g ℓ = 0, to within 2 ulps (mpmath, not the library)
    with mpmath.workdps(50):
        a, b = (1 - mpmath.mpf(0.5)) * mpmath.cos(theta), -mpmath.mpf(0.5) * phi_dot
        slow = 2 / (-b + mpmath.sqrt(b * b - 4 * a))  # the root of smaller magnitude
        assert abs(mpmath.mpf(psi_dot) - slow) <= 2 * math.ulp(psi_dot)
    top = tops.HeavySymmetricTop(1.0, 0.5, 1.0, theta=theta, psi_dot=psi_dot, phi_dot=phi_dot)
    assert top.roots[0] == top.roots[1] == math.cos(theta)  # the closed band
    ts = np.array([0.0, 0.5, 3.0, 10.0])
    assert np.array_equal(top.u(ts), np.full(4, math.cos(theta)))
    np.testing.assert_allclose(top.theta(ts), theta, rtol=4 * EPS)
    for name, rate in (("psi", psi_dot), ("phi", phi_dot)):
        np.testing.assert_allclose(
            getattr(top, name)(ts), rate * ts, rtol=0, atol=STEADY_ANGLE_EPS * EPS * abs(rate) * 10
        )


def test_the_heavy_tops_root_search_by_bisection_alone_ends_at_the_root():
    """With no Newton step (a slope of 0 everywhere) the search is a bisection of the
    bracket: it ends within its two floats about the root (0.3: the bracket's lower end
    moves too), and at a point whose value is exactly 0 (1.0, after 2.0 where the value
    is 1.0) it returns that point."""
    root = tops._root_from_above(lambda y: (y - 0.3, 0.0), 0.0, 4.0)
    assert abs(root - 0.3) <= math.ulp(0.3), root
    assert tops._root_from_above(lambda y: (y - 1.0, 0.0), 0.0, 4.0) == 1.0


@pytest.mark.parametrize(
    ("largest", "smallest"),
    [(1.0, 1e-308), (1.0, 1.5e-308), (2.0**600, 2.0**600 * 1e-308), (1.0, 0.5), (3.0, 3.0)],
)
def test_the_scale_keeps_the_smallest_parameter_a_normal_float(largest, smallest):
    """_scale_exponent's k: the largest scaled into [1/2, 1) unless the smallest would
    then be subnormal (its digits lost); then the smallest at [2^-1022, 2^-1021), float64's
    smallest binade of normal numbers, and the largest below 8 (ratio ≥ 1e-308)."""
    k = tops._scale_exponent(largest, smallest)
    assert math.ldexp(smallest, -k) >= 2.0**-1022
    assert math.ldexp(largest, -k) < 8.0
    if smallest / largest > 2.0**-1020:
        assert 0.5 <= math.ldexp(largest, -k) < 1.0
    else:
        assert math.ldexp(smallest, -k) < 2.0**-1021
