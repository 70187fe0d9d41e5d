"""Moments of inertia from 1e-300 to 1e300 (issue 16, part 4): scale invariance, exactly.

A rigid body's motion depends on its moments only through their ratios (Euler's
equations are homogeneous in J), and a heavy top's on J'1, J3, m g ℓ only through
theirs. So for every scale s the results for s·J must equal the results for J, with the
dimensional ones (L, E, an inertia tensor) multiplied by s:

- for s a power of two the scaling is exact in float64, and so must the results be:
  **bit for bit** (the tops scale their moments by an exact power of two inside);
- for s = 1e±300 the scaled moments are rounded once each, so the results agree within
  a few eps (``SCALE_RTOL``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechanics import inertia, tops
from mechanics._floats import EPS
from mechanics.errors import NonPhysicalInertiaError

#: s·J rounds each moment once (≤ eps/2 relative); the motion's sensitivity to the
#: moments' ratios near these test points is O(1), and the closed forms add their own
#: ~10 eps: 64 eps bounds both
SCALE_RTOL = 64 * EPS

#: exact scales (powers of two: s·J is exact) and rounded ones, 1e-300 … 1e300
EXACT = [2.0**-996, 2.0**-500, 2.0**500, 2.0**996]
ROUNDED = [1e-300, 1e-150, 1e150, 1e300]
T = np.array([0.0, 0.37, 1.3, 11.0])

J = np.array([1.0, 2.0, 2.5])
W0 = np.array([0.3, -1.0, 0.7])
JT = np.array([[2.0, 0.1, 0.0], [0.1, 3.0, 0.0], [0.0, 0.0, 4.0]])
HEAVY = {"theta": 0.5, "psi": 0.1, "phi": 0.2, "theta_dot": 0.3, "psi_dot": 1.0, "phi_dot": 8.0}


def _close(a, b, exact: bool) -> None:
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if exact:
        np.testing.assert_array_equal(a, b)
    else:
        np.testing.assert_allclose(a, b, rtol=SCALE_RTOL, atol=SCALE_RTOL * np.abs(b).max())


SCALES = [pytest.param(s, True, id=f"2^{math.frexp(s)[1] - 1}") for s in EXACT] + [
    pytest.param(s, False, id=f"{s:g}") for s in ROUNDED
]


@pytest.mark.parametrize(("s", "exact"), SCALES)
def test_free_asymmetric_top_of_s_J_moves_as_that_of_J_with_L_and_E_times_s(s, exact):
    ref, top = tops.FreeAsymmetricTop(J, W0), tops.FreeAsymmetricTop(s * J, W0)
    _close(top.omega(T), ref.omega(T), exact)
    _close(top.attitude(T), ref.attitude(T), exact)
    _close(top.precession_angle(T), ref.precession_angle(T), exact)
    _close(top.flip_period(), ref.flip_period(), exact)
    _close(top.angular_momentum_norm, s * ref.angular_momentum_norm, exact)
    _close(top.energy, s * ref.energy, exact)
    _close(top.angular_momentum_space, s * ref.angular_momentum_space, exact)
    assert top.regime == ref.regime


@pytest.mark.parametrize(("s", "exact"), SCALES)
def test_free_symmetric_top_of_s_J_moves_as_that_of_J_with_L_and_E_times_s(s, exact):
    ref, top = tops.FreeSymmetricTop(2.0, 3.0, W0), tops.FreeSymmetricTop(2.0 * s, 3.0 * s, W0)
    _close(top.omega(T), ref.omega(T), exact)
    _close(top.attitude(T), ref.attitude(T), exact)
    _close(top.angular_momentum_norm, s * ref.angular_momentum_norm, exact)
    _close(top.energy, s * ref.energy, exact)


@pytest.mark.parametrize(("s", "exact"), SCALES)
def test_heavy_top_of_s_J_and_s_mgl_moves_as_that_of_J_with_L_and_E_times_s(s, exact):
    ref = tops.HeavySymmetricTop(2.0, 1.0, 3.0, **HEAVY)
    top = tops.HeavySymmetricTop(2.0 * s, 1.0 * s, 3.0 * s, **HEAVY)
    for f in ("theta", "psi", "phi"):
        _close(getattr(top, f)(T), getattr(ref, f)(T), exact)
    _close(top.nutation_period(), ref.nutation_period(), exact)
    _close([top.L_3, top.L_z, top.energy], [s * ref.L_3, s * ref.L_z, s * ref.energy], exact)
    _close(top.energy_at(T), s * ref.energy_at(T), exact)
    # E' = E − L3²/(2J3) − mgℓ cancels: its error is relative to the terms, not to E'
    terms = abs(ref.energy) + ref.L_3**2 / (2 * ref.J_3) + ref.m_g_ell
    if exact:
        assert top.reduced_energy == s * ref.reduced_energy
    else:
        assert abs(top.reduced_energy - s * ref.reduced_energy) <= SCALE_RTOL * s * terms
    _close(top.effective_potential(T + 0.2), s * ref.effective_potential(T + 0.2), exact)


@pytest.mark.parametrize(("s", "exact"), SCALES)
def test_top_criteria_and_rates_are_invariant_under_scaling(s, exact):
    _close(
        tops.steady_precession_rates(2.0 * s, 5.0 * s, 3.0 * s, 0.5),
        tops.steady_precession_rates(2.0, 5.0, 3.0, 0.5),
        exact,
    )
    for L3 in (5.0, 4.8):  # L3² = 25 > 24 = 4 J1 mgl: stable; 23.04 < 24: not
        assert tops.sleeping_top_is_stable(2.0 * s, L3 * s, 3.0 * s) == (L3 * L3 > 24.0)
    for axis in (1, 2, 3):
        a, b = tops.principal_axis_stability(s * J, axis), tops.principal_axis_stability(J, axis)
        assert a.kind == b.kind
        _close([a.rate, a.CiCk], [b.rate, b.CiCk], exact)


@pytest.mark.parametrize(("s", "exact"), SCALES)
def test_inertia_of_s_J_is_s_times_that_of_J(s, exact):
    _close(inertia.check_inertia(s * JT), s * JT, exact)
    assert bool(inertia.is_physical_inertia(s * JT))
    vals, vecs = inertia.principal_axes(s * JT)
    vals1, vecs1 = inertia.principal_axes(JT)
    _close(vals, s * vals1, exact)
    _close(np.abs(vecs), np.abs(vecs1), exact)
    _close(
        inertia.parallel_axis(s * JT, s, [0.3, 0.2, 0.1]),
        s * inertia.parallel_axis(JT, 1.0, [0.3, 0.2, 0.1]),
        exact,
    )
    R = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    _close(inertia.rotate_inertia(s * JT, R), s * inertia.rotate_inertia(JT, R), exact)


@pytest.mark.parametrize(
    "moments",
    [(1.0, 1e308, 1e308), (1e308, 1e308, 1e308), (1.7e308, 1.5e308, 1.7e308)],
    ids=["1, 1e308, 1e308", "1e308 x3", "1.7e308, 1.5e308, 1.7e308"],
)
def test_check_inertia_takes_moments_up_to_float64s_limit(moments):
    """The checks run on J scaled by a power of two, so J1 + J2 near 2e308 cannot overflow:
    the tensor is taken (a moment of 1 beside 1e308 is zero to rounding, a near line mass,
    taken with ``allow_singular``) and its principal moments are the diagonal."""
    J = np.diag(moments)
    singular = min(moments) / max(moments) <= inertia.INERTIA_ATOL
    np.testing.assert_array_equal(inertia.check_inertia(J, allow_singular=singular), J)
    assert bool(inertia.is_physical_inertia(J, allow_singular=singular))
    vals, _ = inertia.principal_axes(J, allow_singular=singular)
    np.testing.assert_array_equal(vals, np.sort(moments))


def test_a_moment_zero_to_rounding_beside_1e308_is_refused_as_not_positive_definite():
    with pytest.raises(NonPhysicalInertiaError, match=r"^J is not positive definite: .* J1 = 1 "):
        inertia.check_inertia(np.diag([1.0, 1e308, 1e308]))


def test_check_inertia_messages_give_values_beyond_1e154_in_the_callers_units():
    with pytest.raises(
        NonPhysicalInertiaError,
        match=r"principal moments \[1e\+300, 1e\+300, 3e\+300\] give J1 \+ J2 - J3 = -1e\+300 ",
    ):
        inertia.check_inertia(np.diag([1e300, 1e300, 3e300]))
