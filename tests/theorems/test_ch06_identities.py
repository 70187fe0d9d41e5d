"""Chapter 6 of Essén (1996): the closed forms of the catalogue checks against an
independent mechanical model, for inputs hypothesis draws.

The model is :func:`identities.book.ch06.restitution.spring_dashpot_collision`: scipy
integrates Newton's equations of two bodies through a linear spring–dashpot contact
whose damping is set to give e from the theory of the damped oscillator only.  The
closed forms are the symbolic results of the checks (6.37)-(6.38), (6.41), (6.42),
evaluated with sympy.  A wrong variant (the loss with (1 − e)) must fail the same test.
"""

from __future__ import annotations

from functools import cache, partial

import numpy as np
import sympy as sp
from hypothesis import example, given, settings
from hypothesis import strategies as st

from identities.book.ch06 import restitution as r6

# The integration runs at rtol 1e-12; velocities come out within ~1e-11 of the velocity
# scale (measured ≤ 1e-13 on the pinned examples): the checks' own bound.
SIM_RTOL = r6.SIM_RTOL

finite = partial(st.floats, allow_nan=False, allow_infinity=False)
masses = finite(0.05, 20.0)
speeds = finite(0.1, 5.0)
restitution = finite(0.05, 1.0)  # e = 0 needs critical damping: no return to δ = 0


@cache
def _closed_forms():
    v1f, v2f = r6.direct_impact_symbolic()
    mu = r6.m_1 * r6.m_2 / (r6.m_1 + r6.m_2)
    dx = r6.xdot_2i - r6.xdot_1i
    args = (r6.m_1, r6.m_2, r6.xdot_1i, r6.xdot_2i, r6.e)
    return {
        "v": sp.lambdify(args, (v1f, v2f)),
        "Q": sp.lambdify(args, (1 - r6.e**2) * mu * dx**2 / 2),
        "Q_wrong": sp.lambdify(args, (1 - r6.e) * mu * dx**2 / 2),
    }


def _kinetic(m1, m2, v1, v2):
    return 0.5 * m1 * v1**2 + 0.5 * m2 * v2**2


def _loss_matches(formula, m1, m2, v1, v2, e) -> bool:
    sim = r6.spring_dashpot_collision(m1, m2, v1, v2, e, 1e-3)
    lost = _kinetic(m1, m2, v1, v2) - _kinetic(m1, m2, sim["v1f"], sim["v2f"])
    return abs(lost - formula(m1, m2, v1, v2, e)) <= SIM_RTOL * _kinetic(m1, m2, v1, v2)


@settings(max_examples=25, deadline=None)
@given(masses, masses, speeds, speeds, restitution)
@example(2.0, 3.0, 1.5, 0.5, 0.6)
@example(1.0, 1.0, 1.0, 1.0, 1.0)
def test_simulated_contact_gives_the_velocities_of_momentum_and_restitution(m1, m2, a, b, e):
    v1, v2 = a, -b  # approaching: body 1 behind, moving faster
    sim = r6.spring_dashpot_collision(m1, m2, v1, v2, e, 1e-3)
    v1f, v2f = _closed_forms()["v"](m1, m2, v1, v2, e)
    scale = max(abs(v1), abs(v2))
    assert abs(sim["v1f"] - v1f) <= SIM_RTOL * scale
    assert abs(sim["v2f"] - v2f) <= SIM_RTOL * scale
    assert abs((sim["v2f"] - sim["v1f"]) + e * (v2 - v1)) <= 2 * SIM_RTOL * scale


@settings(max_examples=25, deadline=None)
@given(masses, masses, speeds, speeds, restitution)
def test_simulated_energy_loss_is_half_mu_one_minus_e_squared_v_rel_squared(m1, m2, a, b, e):
    assert _loss_matches(_closed_forms()["Q"], m1, m2, a, -b, e)


def test_the_loss_with_one_minus_e_is_rejected_by_the_same_procedure():
    wrong = _closed_forms()["Q_wrong"]
    cases = [(2.0, 3.0, 1.5, -0.5, 0.6), (1.0, 7.0, 0.3, -2.0, 0.2), (5.0, 0.5, 2.0, 0.1, 0.9)]
    assert not any(_loss_matches(wrong, *c) for c in cases)
    assert all(_loss_matches(_closed_forms()["Q"], *c) for c in cases)


@settings(max_examples=15, deadline=None)
@given(masses, masses, speeds, speeds, restitution)
def test_restitution_impulse_is_e_times_the_compression_impulse(m1, m2, a, b, e):
    sim = r6.spring_dashpot_collision(m1, m2, a, -b, e, 1e-3)
    assert np.isclose(sim["S_2"] / sim["S_1"], e, rtol=0, atol=100 * SIM_RTOL)
