"""Hard cases of :mod:`mechanics.inertia` and the pendulum of :mod:`mechanics.dynamics`.

The oracle is mpmath at :data:`MP_DPS` digits, fed the float64 inputs as exact
binary numbers (so the error measured is that of the float code, not of the
input's rounding):

- **parallel-axis shift** at offset/size 1e6 … 1e10 (and ordinary offsets):
  every entry of J_G + m(|d|² 1 − d dᵀ) against the exact value, in ulps of
  the exact entry (a relative error, even for an off-diagonal entry where
  J_G and the shift cancel);
- **principal moments** of near-degenerate, flat and thin tensors against
  mpmath's symmetric eigen-solver on the same float tensor, in eps of J3, and
  the projectors onto the eigen-subspaces (coincident moments grouped) in eps
  of J3/gap;
- **pendulum period** for amplitudes up to fl(π), relative, in eps;
- **pendulum motion** near the separatrix, in units of eps·(|φ| + |t φ̇|), the
  change of φ when the time is rounded.

Each property calls :func:`hypothesis.target` with its error, so the search
pushes toward the worst case.  Measured worst (``HYPOTHESIS_PROFILE=explore``,
1000 examples each, ``--hypothesis-show-statistics``): see the constants.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
from hypothesis import example, given, target
from hypothesis import strategies as st

from mechanics import dynamics as D
from mechanics import inertia as I
from mechanics import strategies as ms
from mechanics._floats import ulps
from mechanics.rotation import EPS

MP_DPS = 50

#: Each entry of the shifted tensor is formed with error-free products and sums
#: and rounded once at the end: within 1 ulp of the exact entry (the tail of
#: the double-double adds far below 2**-100).  Measured worst 0.50 ulp
#: (explore profile, 1000 examples).
SHIFT_ULPS = 1.0

#: Jacobi's moments against the exact eigenvalues of the float tensor, in eps
#: of J3: each rotation perturbs the diagonal by about an eps of J3, a few
#: sweeps do that a dozen times, and they do not align.  Measured worst 1.2 eps
#: (explore profile).
MOMENT_EPS = 8.0

#: Projectors onto eigen-subspaces, in eps·J3/gap (first-order perturbation
#: theory: an eps·J3 perturbation turns a subspace by eps·J3/gap).  Measured
#: worst 4.4 (explore profile).
PROJECTOR_EPS = 16.0

#: K(k'²) by scipy's ``ellipkm1`` (cephes, within about an ulp) of k'² computed
#: to about an ulp; 4 / ω0 adds one rounding.  Measured worst 1.2 eps
#: (explore profile), amplitudes 0 … fl(π).
PERIOD_EPS = 4.0

#: φ(t) in units of eps·(|φ| + |t φ̇|) (see the module docstring), via
#: mechanics.elliptic.ellipj.  Measured worst 1.05 (explore profile).
MOTION_EPS = 8.0


def _mp(x) -> mpmath.mpf:
    return mpmath.mpf(float(x))


# -------------------------------------------------------------- parallel axis

#: |d|/size: 1e6 … 1e10 (the shift dominates), 1e-3 … 10 (comparable), or 0.
#: Offsets so small that m d_i d_j is subnormal are left out: there float64
#: itself has only absolute precision (2**-1074), and the ulp measure is moot.
offsets = st.tuples(
    st.floats(1e6, 1e10) | st.floats(1e-3, 10.0) | st.just(0.0),
    st.floats(-1.0, 1.0).map(lambda z: z if abs(z) > 1e-100 else 0.0),
    st.floats(-math.pi, math.pi).map(lambda a: a if abs(a) > 1e-100 else 0.0),
)


@given(ms.inertia_tensors(), st.floats(1e-3, 1e3), offsets)
@example(np.diag([1.0, 2.0, 2.5]), 1.0, (1e8, 0.3, 1.1))
@example(np.diag([1.0, 1.0, 1.0]), 3.0, (1e8, 1.0, 0.0))  # d along e3: zeros off-diagonal
def test_parallel_axis_shift_is_within_an_ulp_of_mpmath(J_G, m, offset):
    ratio, z, az = offset
    size = math.sqrt(np.trace(J_G) / (2 * m))
    rho = math.sqrt((1 - z) * (1 + z))
    d = ratio * size * np.array([rho * math.cos(az), rho * math.sin(az), z])
    J_C = I.parallel_axis(J_G, m, d)
    worst = 0.0
    with mpmath.workdps(MP_DPS):
        dd = [_mp(x) for x in d]
        d2 = sum(x * x for x in dd)
        for i in range(3):
            for j in range(3):
                exact = _mp(0.5 * (J_G[i, j] + J_G[j, i])) + _mp(m) * (
                    (d2 if i == j else 0) - dd[i] * dd[j]
                )
                worst = max(worst, ulps(J_C[i, j], exact))
    target(worst, label="parallel-axis ulps")
    assert worst <= SHIFT_ULPS


# ----------------------------------------------------------- principal moments

hard_moments = ms.principal_moments(
    min_scale=1e-3, max_scale=1e3, regimes=["near-degenerate", "flat", "near-flat", "thin", "equal"]
)


@given(hard_moments, ms.rotation_matrices())
@example(np.array([1.0, 1.0 + 2 * EPS, 1.5]), np.eye(3)[[1, 2, 0]])
def test_principal_moments_and_subspaces_match_mpmath(moments, R):
    J = I.rotate_inertia(np.diag(moments), R)
    got, axes = I.principal_axes(J)
    with mpmath.workdps(MP_DPS):
        E, Q = mpmath.eigsy(mpmath.matrix(J.tolist()))
        order = sorted(range(3), key=lambda k: E[k])
        exact = [E[k] for k in order]
        vecs = [[Q[i, k] for i in range(3)] for k in order]
        J3 = exact[2]
        err = max(abs(_mp(got[k]) - exact[k]) for k in range(3)) / (J3 * EPS)
        # Groups by the exact gaps; the error of a projector is measured
        # against the gap that separates its group from the others.
        groups = [[0]]
        for k in (1, 2):
            if exact[k] - exact[k - 1] <= I.SUBSPACE_RTOL * J3:
                groups[-1].append(k)
            else:
                groups.append([k])
        proj_err = 0.0
        for g in groups:
            others = [k for k in range(3) if k not in g]
            if not others:
                continue
            gap = min(abs(exact[a] - exact[b]) for a in g for b in others)
            for a in range(3):
                for b in range(3):
                    P_exact = sum(vecs[k][a] * vecs[k][b] for k in g)
                    P_got = sum(_mp(axes[k, a]) * _mp(axes[k, b]) for k in g)
                    proj_err = max(proj_err, abs(P_got - P_exact) * gap / (J3 * EPS))
    err, proj_err = float(err), float(proj_err)
    target(err, label="moment eps")
    target(proj_err, label="projector eps*J3/gap")
    assert err <= MOMENT_EPS
    assert proj_err <= PROJECTOR_EPS


# -------------------------------------------------------------------- pendulum

near_pi = st.floats(1e-300, 1.0).map(lambda x: 10.0 ** (-16 * x))  # π − θ0 in 1e-16 … 1


@given(st.one_of(near_pi.map(lambda d: math.pi - d), st.floats(0.0, math.pi)))
@example(math.pi)
@example(math.nextafter(math.pi, 0.0))
@example(1e-300)
def test_pendulum_period_matches_mpmath_up_to_pi(theta_0):
    T = D.pendulum_period(1.0, 1.0, 1.0, 1.0, theta_0)
    with mpmath.workdps(MP_DPS):
        k2 = mpmath.sin(_mp(theta_0) / 2) ** 2
        exact = 4 * mpmath.ellipk(k2)
        err = float(abs(_mp(T) - exact) / exact / EPS)
    target(err, label="period eps")
    assert err <= PERIOD_EPS


@given(
    st.one_of(near_pi.map(lambda d: math.pi - d), st.floats(0.1, math.pi)),
    st.floats(0.0, 2.0),
)
@example(math.pi - 1e-12, 0.125)
@example(math.nextafter(math.pi, 0.0), 0.25)
def test_pendulum_motion_matches_mpmath_near_the_separatrix(theta_0, periods):
    T = float(D.pendulum_period(1.0, 1.0, 1.0, 1.0, theta_0))
    t = periods * T
    phi = float(D.pendulum_motion(t, 1.0, 1.0, 1.0, 1.0, theta_0))
    with mpmath.workdps(MP_DPS):
        h = _mp(theta_0) / 2
        k, kp = mpmath.sin(h), mpmath.cos(h)
        cn = mpmath.ellipfun("cn", _mp(t), m=k * k)
        exact = 2 * mpmath.atan2(k * cn, kp)  # tan(φ/2) = k cn / k'
        phidot = 2 * mpmath.sqrt(max(k**2 - mpmath.sin(exact / 2) ** 2, 0))
        scale = abs(exact) + abs(_mp(t)) * phidot + _mp(EPS)  # eps: φ = 0 exactly
        err = float(abs(_mp(phi) - exact) / (scale * EPS))
    target(err, label="motion eps")
    assert err <= MOTION_EPS


def test_inertia_tensor_of_a_heavy_and_a_light_particle_keeps_its_digits():
    """Mass ratio 1e12, the light particle first and 1e4 times farther from G than the
    heavy one, all near the origin after a naive centring: with the first particle as
    reference G came out as a difference of large numbers (658 eps); the heaviest
    particle as reference keeps the error at a few eps (exact rational reference)."""
    from fractions import Fraction

    m = np.array([1e-6, 1e6])
    r = np.array([[3.0e-5, -1.0e-5, 2.0e-5], [1.1e-8, 0.7e-8, -1.3e-8]])
    J = I.inertia_tensor(m, r, about=np.zeros(3))
    exact = np.zeros((3, 3))
    for a in range(3):
        for b in range(3):
            s = Fraction(0)
            for mi, ri in zip(m, r, strict=True):
                q = [Fraction(x) for x in ri]
                n2 = sum(x * x for x in q)
                s += Fraction(mi) * ((n2 if a == b else 0) - q[a] * q[b])
            exact[a, b] = float(s)
    scale = float((m * (r * r).sum(-1)).sum())
    assert np.abs(J - exact).max() <= 4 * EPS * scale
