"""The exact free top near the separatrix against mpmath, errors in eps.

Two oracles, both taking the float inputs (J, ω0, R0) as exact binary numbers:

- ``tests/data/elliptic_reference.json`` (``tools/make_elliptic_reference.py``):
  mpmath's Taylor-series ODE solver on Euler's equations (4.47) and
  dR/dt = −[ω]× R at 40 digits, to t = 20, near the separatrix from both sides
  (|L² − 2EJ2|/L² from 1e-3 to 1e-16) and exactly on it.  No elliptic function
  and no formula of ``mechanics.tops`` is involved.
- In-test, for the hypothesis search closer to the separatrix than an ODE
  solver can follow (m1 down to 1e-280): the book's/Landau's elliptic solution
  evaluated by mpmath at 60+ digits with its parameters computed from the exact
  inputs (the formulas are pinned by the ODE oracles; this one measures rounding).

Error measure: max over components |ω − ω*| / (eps · |ω0| · (1 + λ t)), the
relative error allowed the unavoidable phase error of a float time t (λ t is
the elliptic argument, about 2π per quarter flip).  Bound: :data:`TOP_EPS`.
Attitude: max-abs matrix error / (eps · (1 + λ t)).
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import mpmath
import numpy as np
import pytest
from hypothesis import example, given, target
from hypothesis import strategies as st

from mechanics import tops
from mechanics._floats import EPS
from mechanics.errors import OutOfDomainError
from mechanics.rotation import matrix_from_euler

DATA = Path(__file__).resolve().parent.parent / "data" / "elliptic_reference.json"

# ω(t) = amplitude × (sn, cn, dn)(λt + u0): the amplitudes and λ are rounded once from
# exact rationals, u0 is an R_F value within a few eps, the functions within
# ELLIPJ_EPS (measured ≤ 1.1 conditioned eps): a few tens of eps per unit of phase,
# plus the sensitivity dω/du·δu of the phase itself near the separatrix.
TOP_EPS = 64.0

# The attitude adds the precession angle's closed form (R_J, ≤ a few eps per term)
# and a product of three rotation matrices.
ATTITUDE_EPS = 256.0


def _reference():
    return json.loads(DATA.read_text())["free_top"]


def _at(fn, t: float, path: str):
    """fn at one float time by the one-instant path (a Python float) or the array path."""
    return fn(t) if path == "instant" else fn(np.array([t]))[0]


@pytest.mark.parametrize("path", ["instant", "array"])
def test_free_top_near_separatrix_against_the_mpmath_ode_solution(path):
    lines = []
    worst_w = worst_R = 0.0
    for case in _reference():
        J = [float(x) for x in case["J"]]
        w0 = np.array([float(x) for x in case["omega_0"]])
        R0 = matrix_from_euler(*(float(x) for x in case["euler_0"]))
        top = tops.FreeAsymmetricTop(J, w0, R0)
        lam = getattr(top, "_lam", 0.0)
        ew = eR = 0.0
        for s in case["samples"]:
            t = float(s["t"])
            scale = 1 + lam * t
            ref = [mpmath.mpf(x) for x in s["omega"]]
            w = _at(top.omega, t, path)
            e = max(abs(mpmath.mpf(float(a)) - r) for a, r in zip(w, ref, strict=True))
            ew = max(ew, float(e / (EPS * np.linalg.norm(w0) * scale)))
            if s["R"] is not None:
                R = _at(top.attitude, t, path).ravel()
                e = max(
                    abs(mpmath.mpf(float(a)) - mpmath.mpf(r))
                    for a, r in zip(R, s["R"], strict=True)
                )
                eR = max(eR, float(e / (EPS * scale)))
        worst_w, worst_R = max(worst_w, ew), max(worst_R, eR)
        lines.append(
            f"  J={J} ω0={w0.tolist()} {top.regime:10s} m1={top.m1:.3g}: "
            f"ω {ew:.3g} eps, R {eR:.3g} eps"
        )
    print(f"\nfree top vs mpmath odefun, {path} path (eps, per unit of phase):")  # shown with -s
    print("\n".join(lines))
    assert worst_w <= TOP_EPS
    assert worst_R <= ATTITUDE_EPS


def _mp_omega(J, w0, t):
    """The elliptic solution in mpmath for sorted J1 < J2 < J3 (Landau §37)."""
    J1, J2, J3 = (mpmath.mpf(x) for x in J)
    w1, w2, w3 = (mpmath.mpf(x) for x in w0)
    E2 = J1 * w1**2 + J2 * w2**2 + J3 * w3**2
    L2 = J1**2 * w1**2 + J2**2 * w2**2 + J3**2 * w3**2
    A, B = E2 * J3 - L2, L2 - E2 * J1
    D = L2 - E2 * J2
    if D > 0:
        m = (J2 - J1) * A / ((J3 - J2) * B)
        lam = mpmath.sqrt((J3 - J2) * B / (J1 * J2 * J3))
        a = [
            mpmath.sqrt(A / (J1 * (J3 - J1))),
            mpmath.sqrt(A / (J2 * (J3 - J2))),
            mpmath.sqrt(B / (J3 * (J3 - J1))),
        ]
        s = mpmath.sign(w3)
        sn0, cn0 = s * w2 / a[1], w1 / a[0]
    else:
        m = (J3 - J2) * B / ((J2 - J1) * A)
        lam = mpmath.sqrt((J2 - J1) * A / (J1 * J2 * J3))
        a = [
            mpmath.sqrt(A / (J1 * (J3 - J1))),
            mpmath.sqrt(B / (J2 * (J2 - J1))),
            mpmath.sqrt(B / (J3 * (J3 - J1))),
        ]
        s = mpmath.sign(w1)
        sn0, cn0 = s * w2 / a[1], w3 / a[2]
    u0 = mpmath.ellipf(mpmath.atan2(sn0, cn0), m)
    u = lam * mpmath.mpf(t) + u0
    sn, cn, dn = (mpmath.ellipfun(f, u, m=m) for f in ("sn", "cn", "dn"))
    if D > 0:
        return [a[0] * cn, s * a[1] * sn, s * a[2] * dn], lam
    return [s * a[0] * dn, s * a[1] * sn, a[2] * cn], lam


@st.composite
def near_separatrix(draw):
    """Sorted J and ω0 with L² − 2EJ2 = δ · J1(J2 − J1)ω1², |δ| from 1e-2 to 1e-280."""
    J1 = draw(st.floats(0.5, 2.0))
    J2 = J1 * draw(st.floats(1.05, 2.0))
    J3 = J2 + (J1 + J2 - J2) * draw(st.floats(0.1, 0.95))
    k = draw(st.integers(2, 280))
    sign = draw(st.sampled_from([-1, 1]))
    w1 = draw(st.floats(0.1, 1.0))
    w2 = draw(st.floats(-1.0, 1.0))
    # ω3² = J1(J2−J1)ω1²(1 + δ)/(J3(J3−J2)) with δ = ±10^−k, in mpmath then rounded: the
    # float rounding moves δ by ~eps, so small k keep the side, large k land anywhere
    # within ~1e-16 of the separatrix on either side (both are wanted)
    with mpmath.workdps(30):
        w3 = float(
            w1 * mpmath.sqrt(J1 * (J2 - J1) * (1 + sign * mpmath.mpf(10) ** -k) / (J3 * (J3 - J2)))
        )
    t = draw(st.floats(0.0, 30.0))
    return (J1, J2, J3), (w1, w2, w3), t


@given(near_separatrix())
@example(((1.0, 2.0, 3.0), (1.0, 0.001, 0.5773502691896257), 20.0))
@example(((1.0, 2.0, 3.0), (1.0, 1e-9, 0.5773502691896258), 29.0))
def test_free_top_near_separatrix_against_mpmath_elliptic_functions(case):
    J, w0, t = case
    top = tops.FreeAsymmetricTop(J, w0)
    if top.regime not in ("axis1", "axis3"):
        return  # exactly on the separatrix: covered by the ODE oracle
    dps = 60 + int(-math.log10(top.m1)) if top.m1 > 0 else 60
    with mpmath.workdps(dps):
        ref, lam = _mp_omega(J, w0, t)
        w = top.omega(t)
        e = max(abs(mpmath.mpf(float(a)) - r) for a, r in zip(w, ref, strict=True))
        err = float(e / (EPS * math.sqrt(sum(x * x for x in w0)) * (1 + lam * t)))
    target(err, label="free top ω error in eps per unit phase")
    assert err <= TOP_EPS, (case, err)


# ----------------------------------------------------------------- heavy top


# The nutation limits u1 ≤ u0 ≤ u2 come from a quadratic whose roots have opposite
# signs (no cancellation) and a Newton polish; measured ≤ 4.2 eps absolute, also at
# the double root of steady precession.  u3 ≥ 1 by bracketing, measured ≤ 28 eps
# absolute for u3 up to ~40 (a relative 1 eps of u3 plus the deflation).
NUTATION_ROOT_EPS = 8.0
LARGE_ROOT_REL_EPS = 8.0


def _mp_roots(J1, J3, mgl, th, thd, psd, phd):
    """Roots of f(u) (5.66)–(5.71) from the exact inputs, by mpmath's polyroots."""
    J1, J3, mgl, th, thd, psd, phd = (mpmath.mpf(x) for x in (J1, J3, mgl, th, thd, psd, phd))
    u0, S = mpmath.cos(th), mpmath.sin(th)
    L3 = J3 * (psd * u0 + phd)
    Lz = J1 * S**2 * psd + L3 * u0
    E = J1 / 2 * (thd**2 + psd**2 * S**2) + L3**2 / (2 * J3) + mgl * u0
    beta, a, b = 2 * mgl / J1, Lz / J1, L3 / J1
    e = (2 * E - L3**2 / J3) / J1
    r = mpmath.polyroots(
        [beta, -(e + b * b), 2 * a * b - beta, e - a * a], maxsteps=200, extraprec=300
    )
    return sorted(mpmath.re(x) for x in r)


@pytest.mark.parametrize("theta", [0.3, 1.0, 2.0])
@pytest.mark.parametrize("delta", [1e-2, 1e-6, 1e-10, 1e-14, 0.0])
@pytest.mark.parametrize("theta_dot", [0.0, 1e-9])
def test_heavy_top_roots_near_steady_precession_against_mpmath(theta, delta, theta_dot):
    """ψ̇0 = Ω_slow (1 + δ): the nutation band closes to a double root as δ → 0."""
    J1, J3, mgl, phd = 1.0, 0.5, 1.0, 10.0
    om = 0.0
    for _ in range(80):  # the slow steady rate (5.60) at this θ, by fixed point in L3
        L3 = J3 * (om * math.cos(theta) + phd)
        om = tops.steady_precession_rates(J1, L3, mgl, theta)[0]
    psd = om * (1 + delta)
    top = tops.HeavySymmetricTop(
        J1, J3, mgl, theta=theta, theta_dot=theta_dot, psi_dot=psd, phi_dot=phd
    )
    with mpmath.workdps(60):
        ex = _mp_roots(J1, J3, mgl, theta, theta_dot, psd, phd)
        errs = [float(abs(mpmath.mpf(a) - b) / EPS) for a, b in zip(top.roots, ex, strict=True)]
        u3 = float(ex[2])
    assert max(errs[:2]) <= NUTATION_ROOT_EPS, errs
    assert errs[2] <= LARGE_ROOT_REL_EPS * abs(u3), errs


#: DOP853 at rtol 1e-13 on the attitude kinematics alone, over 345 time units (about 55
#: turns): measured 4.0e-12 at worst; 2^16 eps = 1.5e-11 allows the integrator's drift
KINEMATICS_ATOL = 2.0**16 * EPS


def test_attitude_through_the_flip_of_a_top_spun_about_its_middle_axis():
    # ω0 = (1e-85, 1, 1e-85) about the middle axis of J = (1, 2, 3): m1 = 2e-170, and the
    # flip (u reaching K, t ≈ K/λ ≈ 341) passes cn², dn² below 1e-160 to R_J, where scipy
    # 1.17's elliprj was off by 2e-3 relative: the attitude was off by 0.18 (issue 16).
    # Independent route: Ṙ = −[ω]× R integrated with the top's own ω(t), which is checked
    # against mpmath above (no Euler equations integrated: no sensitivity to 1e-85)
    from scipy.integrate import solve_ivp

    top = tops.FreeAsymmetricTop([1.0, 2.0, 3.0], [1e-85, 1.0, 1e-85])
    assert top.m1 < 1e-160  # the regime this test is about

    def rhs(t, y):
        w = top.omega(float(t))
        S = np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])
        return (-S @ y.reshape(3, 3)).ravel()

    ts = np.array([100.0, 300.0, 345.0])
    sol = solve_ivp(
        rhs, (0.0, ts[-1]), np.eye(3).ravel(), method="DOP853", rtol=1e-13, atol=1e-14, t_eval=ts
    )
    assert sol.success
    ref = sol.y.T.reshape(-1, 3, 3)
    assert top.omega(345.0)[1] < -0.9  # the flip (near t = 342) has happened: ω2 from +1 to −1
    np.testing.assert_allclose(top.attitude(ts), ref, rtol=0, atol=KINEMATICS_ATOL)
    for t, R in zip(ts, ref, strict=True):  # the one-instant path too
        np.testing.assert_allclose(top.attitude(float(t)), R, rtol=0, atol=KINEMATICS_ATOL)


#: the attitude's distance from orthogonal: a frame built from one unit vector and a
#: rotation about it, a few roundings of O(1) entries
ORTHOGONAL_ATOL = 4 * EPS


@pytest.mark.parametrize("w2", [1e-300, 1e-280, 2.0**-1000])
def test_a_pole_a_tiny_angle_off_its_axis_gives_the_attitude_to_rounding(w2):
    """ω0 = (1, w2, 0) on a body with J2 = J3 (the scene engine's reversal property drew
    w2 = 2.2e-313): the pole is w2 J2/J1 off body axis 1.  Its offset's hypot and
    direction quotients, were they left in the subnormal range, would carry fewer than
    53 bits (the frame was 3e-11 off orthogonal): scaled first, the attitude is
    orthogonal and equals the steady spin about axis 1 (the independent route: a
    rotation vector; the motions differ by O(w2) rad, below float64 here), array and
    one-instant paths."""
    J = np.array([0.3125, 0.1953125, 0.1953125]) / 30.0  # the box 0.125 x 0.25 x 0.25
    top = tops.FreeAsymmetricTop(J, np.array([1.0, w2, 0.0]))
    steady = tops.FreeAsymmetricTop(J, np.array([1.0, 0.0, 0.0]))
    assert (top.regime, steady.regime) == ("axis3", "steady")
    ts = np.linspace(0.0, 0.5, 11)
    for R in [*top.attitude(ts), *(top.attitude(float(t)) for t in ts)]:
        assert np.abs(R @ R.T - np.eye(3)).max() <= ORTHOGONAL_ATOL
    np.testing.assert_allclose(top.attitude(ts), steady.attitude(ts), rtol=0, atol=16 * EPS)
    for t in ts:  # the one-instant path (its own scaling of the pole's offset) alike
        np.testing.assert_allclose(
            top.attitude(float(t)), steady.attitude(float(t)), rtol=0, atol=16 * EPS
        )
    # the frame of a subnormal offset without the scaling: off by more than the bound
    nx, ny = 1.39067116e-313, 4.17138772e-315
    s = np.hypot(nx, ny)
    assert abs(np.hypot(nx / s, ny / s) - 1.0) > ORTHOGONAL_ATOL


@pytest.mark.parametrize("w2", [2.2250738585e-313, 5e-324])
def test_a_circulating_amplitude_below_the_normal_range_is_refused(w2):
    """Subnormal amplitudes carry the pole's azimuth to fewer than 53 bits (measured: the
    attitude 3e-11 off for 2.2e-313, 0.24 rad off for 5e-324): refused, naming the
    amplitude and what to do, where the attitude would be wrong."""
    J = np.array([0.3125, 0.1953125, 0.1953125]) / 30.0
    with pytest.raises(OutOfDomainError) as e:
        tops.FreeAsymmetricTop(J, np.array([1.0, w2, 0.0]))
    # the whole message, but the amplitude shown (after the module's scaling of J)
    assert re.fullmatch(
        "a component of ω circulates with an amplitude below float64's normal range "
        r"\([0-9.e+-]+ rad/s after scaling; subnormal floats carry fewer than 53 bits, and "
        "the pole's azimuth with them: an attitude 3e-11 off for 2e-313, 0.24 rad off for "
        r"5e-324\); set it to zero for the steady rotation, or choose units that scale ω up",
        str(e.value),
    ), str(e.value)


#: the polished roots measured within 1.06 eps of mpmath on every case below (u3 relative
#: to |u3|); 2 eps: the last rounding of u0 + x on top of the polished x's
ROOT_EPS = 2.0

#: tops across the root search's branches: (J1, J3, mgl, theta, theta_dot, psi_dot, phi_dot)
ROOT_CASES = {
    "nutating": (1.1875, 0.5, 2.140625, 1.0, 0.3, 0.3, 8.0),
    "nutating, falling": (1.1875, 0.5, 2.140625, 1.0, -0.3, 0.3, 8.0),
    "near the bottom": (1.1875, 0.5, 2.140625, 3.125, 0.015625, 0.25, 0.5),
    "near the vertical": (1.1875, 0.5, 2.140625, 0.03125, 0.015625, 0.0, 20.0),
    # a = b = 0: a pendulum in a vertical plane, short of the vertical (u3 = 1) or over it
    "planar, short of it": (1.1875, 0.5, 2.140625, 1.625, 1.5, 0.0, 0.0),
    "planar, over the top": (1.1875, 0.5, 2.140625, 1.625, 1.96875, 0.0, 0.0),
    # energy far above the vertical's: u3 far above 1 (the bracket doubles many times)
    "fast swing": (1.1875, 0.5, 2.140625, 1.0, 50.0, 0.75, 3.0),
    "weak gravity": (1.1875, 0.5, 2.0**-20, 1.0, 0.25, 0.5, 4.0),
}


@pytest.mark.parametrize("case", list(ROOT_CASES))
def test_heavy_top_roots_across_the_search_branches_against_mpmath(case):
    """u1 ≤ u2 ≤ u3 against mpmath's polyroots of the book's cubic at 60 digits."""
    J1, J3, mgl, th, thd, psd, phd = ROOT_CASES[case]
    top = tops.HeavySymmetricTop(J1, J3, mgl, theta=th, theta_dot=thd, psi_dot=psd, phi_dot=phd)
    with mpmath.workdps(60):
        ex = _mp_roots(J1, J3, mgl, th, thd, psd, phd)
        errs = [float(abs(mpmath.mpf(a) - b) / EPS) for a, b in zip(top.roots, ex, strict=True)]
        u3 = float(ex[2])
    assert max(errs[:2]) <= ROOT_EPS, errs
    assert errs[2] <= ROOT_EPS * abs(u3), errs


def _mp_roots_at_rest_in_theta(J1, J3, mgl, th, psd, phd):
    """θ̇0 = 0: u0 is a root of f exactly, and the other two those of f/(u − u0), a
    quadratic (at 700 digits: β is far below the other coefficients)."""
    with mpmath.workdps(700):
        J1, J3, mgl, th, psd, phd = (mpmath.mpf(x) for x in (J1, J3, mgl, th, psd, phd))
        u0, S = mpmath.cos(th), mpmath.sin(th)
        L3 = J3 * (psd * u0 + phd)
        Lz = J1 * S**2 * psd + L3 * u0
        E = J1 / 2 * psd**2 * S**2 + L3**2 / (2 * J3) + mgl * u0
        beta, a, b = 2 * mgl / J1, Lz / J1, L3 / J1
        e = (2 * E - L3**2 / J3) / J1
        c3, c2, c1 = beta, -(e + b * b), 2 * a * b - beta
        q1, q2 = c2 + u0 * c3, c1 + u0 * (c2 + u0 * c3)  # synthetic division by u − u0
        d = mpmath.sqrt(q1 * q1 - 4 * c3 * q2)
        return sorted([u0, (-q1 - d) / (2 * c3), (-q1 + d) / (2 * c3)])


@pytest.mark.parametrize("mgl", [1e-100, 1e-200, 1e-300, 1e-6])
def test_heavy_top_roots_with_negligible_gravity_against_mpmath(mgl):
    """m g ℓ far below J'1 ψ̇² (down to 1e-300 of it; documented down to 1e-308): u3 − u0
    ~ 1/mgℓ, and the deflated quadratic's p = c2/β + x3 once cancelled to nothing (u2 came
    out as u0, the nutation band lost, or u1 > u2: 0.79, 0.54 against the exact 0.5403,
    0.7905); p now comes from Vieta's product where x3 is large."""
    top = tops.HeavySymmetricTop(1.0, 0.5, mgl, theta=1.0, psi_dot=1.0, phi_dot=1.0)
    ex = _mp_roots_at_rest_in_theta(1.0, 0.5, mgl, 1.0, 1.0, 1.0)
    # u1, u2 absolute (|u| ≤ 1), u3 ~ 1/mgℓ relative
    errs = [float(abs(mpmath.mpf(a) - b) / EPS) for a, b in zip(top.roots[:2], ex[:2], strict=True)]
    errs.append(float(abs(mpmath.mpf(top.roots[2]) / ex[2] - 1) / EPS))
    assert max(errs) <= ROOT_EPS, errs


@pytest.mark.xfail(
    strict=True,
    reason="u2 of a pendulum just short of the vertical (a = b, u3 = 1 exactly) comes from "
    "the deflated quadratic, 1 − u2 = 2 sin²(θ0/2) − x2 with cancellation: measured 498 eps "
    "at 1 − u2 = 5e-4, 4.9e4 eps at 5e-6 (the 1 − u2 form of the class divides 0 by 0 there)",
)
@pytest.mark.parametrize("short", [5e-4, 5e-6])
def test_a_pendulum_just_short_of_the_top_has_u2_to_rounding(short):
    """ψ̇ = φ̇ = 0: f(u) = (e − βu)(1 − u²), u2 = e/β exactly (mpmath from the float inputs)."""
    th = math.pi / 2
    thd = math.sqrt(2.0 * (1.0 - short - math.cos(th)))
    top = tops.HeavySymmetricTop(1.0, 0.5, 1.0, theta=th, theta_dot=thd)
    with mpmath.workdps(50):
        e = mpmath.mpf(thd) ** 2 + 2 * mpmath.cos(mpmath.mpf(th))  # β = 2, e = θ̇² + βu0
        err = float(abs(mpmath.mpf(top.roots[1]) - e / 2) / EPS)
    assert err <= NUTATION_ROOT_EPS, err


@pytest.mark.xfail(
    strict=True,
    reason="1 − u2 of a top at rest in θ just off the vertical (θ̇0 = 0: u2 = u0, 1 − u2 = "
    "2 sin²(θ0/2)) from (a − b)²/(β(1 − u1)(u3 − 1)): 4.99999935e-13 for 5e-13 at θ0 = 1e-6 "
    "(1.3e-7 relative), 6.2e-21 for 5e-19 at θ0 = 1e-9; it enters ψ and φ through n+",
)
@pytest.mark.parametrize("theta", [1e-6, 1e-9])
def test_one_minus_u2_of_a_top_at_rest_just_off_the_vertical_to_rounding(theta):
    top = tops.HeavySymmetricTop(1.0, 0.5, 1.0, theta=theta, phi_dot=5.0)
    with mpmath.workdps(50):
        exact = 2 * mpmath.sin(mpmath.mpf(theta) / 2) ** 2
        err = float(abs(mpmath.mpf(top._omu2) / exact - 1) / EPS)
    assert err <= NUTATION_ROOT_EPS, err
