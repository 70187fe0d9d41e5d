"""Randomised restitution invariants of Essén ch. 6 for :mod:`mechanics.impact`.

For hypothesis-drawn masses (ratios up to 1e15), inertia tensors (spheres,
laminae, near-degenerate and rod-like, turned by drawn rotations), contact
points, contact_normals, approaching velocities and e (0, 1, interior, within 1e-15 of
0 and of 1):

- the normal relative velocity after is −e times the one before (6.36);
- total linear momentum is conserved (6.16); angular momentum about any fixed
  point is conserved for free bodies (6.18); for a hinged body struck by a ball
  the angular momentum about the axis is conserved;
- kinetic energy never increases (6.35); the loss equals ½ μ (1 − e²) v_n² with
  the effective mass μ of the contact (6.41), hence conservation when e = 1;
- e = 0 leaves no normal separation velocity;
- the same procedure rejects a wrong loss formula, ½ μ (1 − e) v_n².

The rigid-impact invariants (restitution, momentum, angular momentum, energy loss) are
stated once, in :mod:`identities.properties.impact`, which also runs them as catalogue
checks of kind ``property``; here they run under ``@given`` with the profile's examples.
Every invariant is evaluated from the returned velocities by the book's
definitions (momentum m v_G, angular momentum r_G × m v_G + J_G ω, energy
½ m v² + ½ ωᵀ J ω), never from the impulse the code used.  Tolerances are
named multiples of eps times the magnitudes of the terms that are summed,
each with its reason.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import Phase, example, find, given, settings
from hypothesis import strategies as st

from identities.properties.impact import (
    ENERGY_RTOL,
    SUM_RTOL,
    angular_momentum_about_contact_point_is_conserved,
    angular_momentum_is_conserved,
    check_energy_loss,
    contact_normal_velocity,
    loss_6_41,
    loss_wrong,
    momentum_is_conserved,
    restitution_law_holds,
    solve_error_scale,
)
from mechanics import impact as im
from mechanics import strategies as ms
from mechanics._floats import EPS

#: The direct-impact functions are within 2 ulps (DIRECT_ULPS) of the exact
#: values; an invariant formed from them by a few more products and sums
#: stays within 16 eps of its magnitudes.
DIRECT_RTOL = 16 * EPS

#: Products that land in the subnormal range (e down to 5e-324 is drawn) are
#: rounded to multiples of 2^-1074, whatever their relative accuracy: two such
#: roundings (the code's and the test's) allow this much absolutely.
SUBNORMAL_ATOL = 2 * math.ulp(0.0)

#: Rigid-body examples are slow to draw (composite strategies, a rotation per
#: tensor); 60 % of the profile's examples (60 under ``ci``, 600 under
#: ``explore``) keep this file at a few seconds.
RIGID = settings(max_examples=max(10, int(0.6 * settings.default.max_examples)))


def _norm(v) -> float:
    return float(np.linalg.norm(v))


# ------------------------------------------------------------ restitution


@RIGID
@given(ms.contacts())
def test_normal_relative_velocity_after_is_minus_e_times_before(c):
    restitution_law_holds(c)


@RIGID
@given(ms.contacts(restitution=st.just(0.0)))
def test_plastic_impact_leaves_no_normal_separation_velocity(c):
    out = im.rigid_impact(c.body_1, c.body_2, r_S=c.r_S, n=c.n, e=0.0)
    v_after, scale_after = contact_normal_velocity(c, out.body_1, out.body_2)
    _, scale_before = contact_normal_velocity(c, c.body_1, c.body_2)
    tol = SUM_RTOL * (scale_before + scale_after + abs(out.S) / out.mu) + 4 * EPS * (
        solve_error_scale(c, out)
    )
    assert abs(v_after) <= tol


@pytest.mark.parametrize("e", [0.0, 0.3, 1.0])
def test_direct_impact_restitution_by_the_definition_6_36(e):
    v1f, v2f = im.direct_impact(2.0, 7.0, 3.0, -1.5, e)
    assert abs((v2f - v1f) - (-e) * (-1.5 - 3.0)) <= DIRECT_RTOL * 4.5


# --------------------------------------------------------------- momentum


@RIGID
@given(ms.contacts())
def test_total_linear_momentum_is_conserved_6_16(c):
    momentum_is_conserved(c)


@RIGID
@given(ms.contacts(regimes=["free-free", "central", "planar", "mass-ratio"]), ms.impact_bodies())
def test_angular_momentum_about_any_fixed_point_is_conserved_6_18(c, anywhere):
    angular_momentum_is_conserved(c, anywhere.r_G)  # about a drawn fixed point


@RIGID
@given(ms.contacts(regimes=["fixed-body-2"]))
def test_angular_momentum_about_the_contact_point_is_conserved_6_22(c):
    angular_momentum_about_contact_point_is_conserved(c)


@RIGID
@given(ms.hinged_bodies(), ms.restitution_coefficients(), st.data())
def test_angular_momentum_about_the_axis_is_conserved_for_a_struck_hinged_body(body, e, data):
    # A ball of mass m_b moving along −b hits the body at P; the axis reaction
    # has no moment about the axis, so a · L_A of body + ball is conserved.
    a = body.axis
    m_b = data.draw(ms.impact_masses(min_value=1e-3, max_value=1e3), label="m_ball")
    AG = body.r_G - body.axis_point
    u = AG - (AG @ a) * a
    u = u / np.linalg.norm(u)
    b = np.cross(a, u)
    P = body.axis_point + data.draw(st.floats(0.2, 3.0)) * u + data.draw(st.floats(-1, 1)) * a
    omega = data.draw(st.floats(-5.0, 5.0), label="omega")
    speed = data.draw(st.floats(0.1, 10.0), label="ball speed")
    v_ball = -speed * b
    # Normal into the hinged body (body 1): n = −b; v_n = n·(v_P − v_ball).
    n = -b
    v_P = omega * np.cross(a, P - body.axis_point)
    v_n = float(n @ (v_P - v_ball))
    if v_n >= 0:  # the body outruns the ball: no impact (not a failure of the law)
        return
    mu_body = im.hinged_effective_mass(body.J_A, P, n, axis_point=body.axis_point, axis=a)
    mu = 1.0 / (1.0 / mu_body + 1.0 / m_b)
    S = -(1.0 + e) * mu * v_n
    out = im.hinged_impact(
        body.m,
        body.J_A,
        body.r_G,
        axis_point=body.axis_point,
        axis=a,
        omega=omega,
        r_P=P,
        S_P=S * n,
    )
    v_ball_after = v_ball - S * n / m_b
    J_aa = float(a @ body.J_A @ a)
    AP = P - body.axis_point
    L_before = J_aa * omega + float(a @ np.cross(AP, m_b * v_ball))
    L_after = J_aa * float(out.omega) + float(a @ np.cross(AP, m_b * v_ball_after))
    scale = J_aa * (abs(omega) + abs(float(out.omega))) + _norm(AP) * m_b * (
        _norm(v_ball) + _norm(v_ball_after)
    )
    assert abs(L_after - L_before) <= SUM_RTOL * scale
    # And restitution holds at P along n.
    v_P_after = float(out.omega) * np.cross(a, AP)
    v_n_after = float(n @ (v_P_after - v_ball_after))
    vscale = _norm(v_P) + _norm(v_P_after) + _norm(v_ball) + _norm(v_ball_after)
    assert abs(v_n_after + e * v_n) <= SUM_RTOL * vscale


@RIGID
@given(ms.hinged_bodies(), st.data())
def test_hinged_reactions_obey_the_momentum_principles_6_19_6_21(body, data):
    a = body.axis
    P = data.draw(ms.impact_bodies()).r_G
    S_P = data.draw(ms.impact_bodies()).v_G
    omega = data.draw(st.floats(-5.0, 5.0))
    out = im.hinged_impact(
        body.m, body.J_A, body.r_G, axis_point=body.axis_point, axis=a, omega=omega, r_P=P, S_P=S_P
    )
    AG, AP = body.r_G - body.axis_point, P - body.axis_point
    # Δω from the returned ω' = fl(ω + Δω) carries the rounding of ω': the
    # scales include |ω| + |ω'| times what Δω multiplies.
    dw = float(out.omega) - omega
    w_sum = abs(omega) + abs(float(out.omega))
    # Momentum: m Δv_G = S_P + S_axis, with v_G = ω a × AG.
    lhs = body.m * dw * np.cross(a, AG)
    scale = body.m * w_sum * _norm(AG) + _norm(S_P) + _norm(out.S_axis)
    assert _norm(lhs - (S_P + out.S_axis)) <= SUM_RTOL * scale
    # Angular momentum about A: J_A Δω a = AP × S_P + M_axis, and a · M_axis = 0.
    lhs = dw * (body.J_A @ a)
    scale = w_sum * np.linalg.norm(body.J_A, 2) + _norm(AP) * _norm(S_P) + _norm(out.M_axis)
    assert _norm(lhs - (np.cross(AP, S_P) + out.M_axis)) <= SUM_RTOL * scale
    assert abs(float(a @ out.M_axis)) <= SUM_RTOL * scale


@RIGID
@given(ms.hinged_bodies(), st.floats(0.1, 10.0), st.data())
def test_a_blow_at_the_centre_of_percussion_loads_the_axis_with_no_impulse(body, S, data):
    point, direction = im.centre_of_percussion(
        body.m, body.J_A, body.r_G, axis_point=body.axis_point, axis=body.axis
    )
    omega = data.draw(st.floats(-5.0, 5.0))
    out = im.hinged_impact(
        body.m,
        body.J_A,
        body.r_G,
        axis_point=body.axis_point,
        axis=body.axis,
        omega=omega,
        r_P=point,
        S_P=S * direction,
    )
    # S_axis = m Δω a × AG − S b: two terms of size S that cancel.
    assert _norm(out.S_axis) <= SUM_RTOL * S
    # The moment about û vanishes; about b = a × û it is Δω bᵀ J_A a (zero when
    # the plane of the axis and G is a symmetry plane, as in the planar regime).
    dw = float(out.omega) - omega  # carries the rounding of ω' (see above)
    u = np.cross(direction, body.axis)
    w_sum = abs(omega) + abs(float(out.omega))
    scale = w_sum * np.linalg.norm(body.J_A, 2) + _norm(point - body.axis_point) * S
    assert abs(float(u @ out.M_axis)) <= SUM_RTOL * scale
    expected_b = dw * float(direction @ body.J_A @ body.axis)
    assert abs(float(direction @ out.M_axis) - expected_b) <= SUM_RTOL * scale


@RIGID
@given(ms.hinged_bodies(regimes=["planar"]), st.floats(0.1, 10.0))
def test_in_the_plane_the_centre_of_percussion_leaves_the_axis_entirely_free(body, S):
    point, direction = im.centre_of_percussion(
        body.m, body.J_A, body.r_G, axis_point=body.axis_point, axis=body.axis
    )
    out = im.hinged_impact(
        body.m,
        body.J_A,
        body.r_G,
        axis_point=body.axis_point,
        axis=body.axis,
        omega=0.0,
        r_P=point,
        S_P=S * direction,
    )
    scale = S * (1.0 + _norm(point - body.axis_point))
    assert _norm(out.S_axis) <= SUM_RTOL * S
    assert _norm(out.M_axis) <= SUM_RTOL * scale
    # It lies on the line through the axis and G, at J_A/(m h) from the axis.
    h = _norm(body.r_G - body.axis_point)
    J_zz = float(body.J_A[2, 2])
    assert abs(_norm(point - body.axis_point) - J_zz / (body.m * h)) <= SUM_RTOL * J_zz / (
        body.m * h
    )


# ---------------------------------------------------------------- energy


@RIGID
@given(ms.contacts())
def test_energy_loss_equals_half_mu_one_minus_e_squared_vn_squared_6_41(c):
    check_energy_loss(loss_6_41, c)


@RIGID
@given(ms.contacts(restitution=st.just(1.0)))
def test_kinetic_energy_is_conserved_when_e_is_one(c):
    check_energy_loss(lambda mu, e, v_n: 0.0, c)


def _example_contact(e: float) -> ms.Contact:
    rod = im.RigidBody(1.0, np.diag([0.01, 1 / 3, 1 / 3]), np.zeros(3), np.zeros(3), np.zeros(3))
    ball = im.RigidBody(
        0.5, 0.002 * np.eye(3), np.array([-1.0, 1.0, 0.0]), np.array([0, -2.0, 0]), np.zeros(3)
    )
    return ms.Contact(ball, rod, np.array([-1.0, 1.0, 0.0]), np.array([0.0, 1.0, 0.0]), e)


def test_the_energy_procedure_rejects_the_loss_with_one_minus_e():
    # The negative control: the same procedure, a wrong formula, an interior e.
    check_energy_loss(loss_6_41, _example_contact(0.5))
    with pytest.raises(AssertionError):
        check_energy_loss(loss_wrong, _example_contact(0.5))

    # And hypothesis finds a drawn contact that rejects it.
    def rejects(c) -> bool:
        try:
            check_energy_loss(loss_wrong, c)
        except AssertionError:
            return True
        return False

    find(
        ms.contacts(),
        rejects,
        settings=settings(max_examples=200, database=None, phases=[Phase.generate]),
    )


# ------------------------------------------------- direct central impact


@given(ms.mass_pairs(), ms.direct_velocities(), ms.restitution_coefficients())
@example((1.0, 1.0), (1.0, -1.0), 1.0)  # equal masses, elastic: velocities swap
@example((1e-15, 1.0), (1.0, 0.0), 1.0 - 1e-12)
def test_direct_impact_conserves_momentum_and_restitutes_6_37_6_38(masses, velocities, e):
    (m1, m2), (v1, v2) = masses, velocities
    v1f, v2f = im.direct_impact(m1, m2, v1, v2, e)
    S = im.impulse_direct(m1, m2, v1, v2, e)
    scale = abs(m1 * v1) + abs(m2 * v2) + abs(m1 * v1f) + abs(m2 * v2f)
    assert abs((m1 * v1f + m2 * v2f) - (m1 * v1 + m2 * v2)) <= DIRECT_RTOL * scale
    vscale = abs(v1) + abs(v2) + abs(v1f) + abs(v2f)
    assert abs((v2f - v1f) + e * (v2 - v1)) <= DIRECT_RTOL * vscale
    # The impulse is the change of momentum of body 1 (6.19).
    assert abs(m1 * (v1f - v1) - S) <= DIRECT_RTOL * (m1 * (abs(v1f) + abs(v1)) + abs(S))


@given(ms.mass_pairs(), ms.direct_velocities(), ms.restitution_coefficients())
def test_direct_energy_loss_is_the_drop_of_kinetic_energy_6_39_6_41(masses, velocities, e):
    (m1, m2), (v1, v2) = masses, velocities
    v1f, v2f = im.direct_impact(m1, m2, v1, v2, e)
    Q = im.energy_loss_direct(m1, m2, v1, v2, e)
    T_i = 0.5 * m1 * v1 * v1 + 0.5 * m2 * v2 * v2
    T_f = 0.5 * m1 * v1f * v1f + 0.5 * m2 * v2f * v2f
    assert Q >= 0.0
    # below float64's normal range the test's own T_i and T_f (four rounded products, one
    # subtraction) lose relative precision: each rounding is off by up to half a subnormal
    # ulp, so the comparison allows 4 of them on top of the relative tolerance
    assert abs((T_i - T_f) - Q) <= ENERGY_RTOL * (T_i + T_f) + 2 * SUBNORMAL_ATOL
    if e == 1.0:
        assert Q == 0.0


@given(ms.mass_pairs(), ms.direct_velocities(), ms.restitution_coefficients())
# e at the smallest normal float: e S1 was once formed in scaled units and lost its digits
@example(
    masses=(1000.0, 0.001),
    velocities=(499999.99999999994, -499999.99999999994),
    e=2.2250738585072014e-308,
)
@example(  # m1 (v_G − v1) ≈ -1.15e-314 is subnormal in the test's own arithmetic
    masses=(2.3713737056616553e-138, 2.3713737056616553e-144),
    velocities=(0.0, -4.869675251658631e-171),
    e=0.0,
)
def test_compression_and_restitution_impulses_have_ratio_e_6_42(masses, velocities, e):
    (m1, m2), (v1, v2) = masses, velocities
    S1, S2 = im.compression_restitution_impulses(m1, m2, v1, v2, e)
    # The compression impulse brings body 1 to the centre-of-mass velocity.
    v_G = (m1 * v1 + m2 * v2) / (m1 + m2)
    # (the test's own v_G and m1 (v_G − v1) may land in the subnormal range: SUBNORMAL_ATOL)
    assert abs(S1 - m1 * (v_G - v1)) <= DIRECT_RTOL * m1 * (abs(v_G) + abs(v1)) + SUBNORMAL_ATOL
    # Together they are the whole impulse; their ratio is e (6.42).
    S = im.impulse_direct(m1, m2, v1, v2, e)
    assert abs((S1 + S2) - S) <= DIRECT_RTOL * (abs(S1) + abs(S2)) + SUBNORMAL_ATOL
    assert abs(S2 - e * S1) <= DIRECT_RTOL * abs(S2) + SUBNORMAL_ATOL


def test_the_direct_procedure_rejects_a_wrong_restitution_sign():
    # Negative control for the direct checks: velocities from the wrong
    # restitution law Δẋ_f = +e Δẋ_i conserve momentum but fail (6.36).
    m1, m2, v1, v2, e = 1.0, 3.0, 5.0, -3.0, 0.5
    M = m1 + m2
    P = m1 * v1 + m2 * v2
    d_f = e * (v2 - v1)  # wrong sign
    v1f, v2f = (P - m2 * d_f) / M, (P + m1 * d_f) / M
    assert math.isclose(m1 * v1f + m2 * v2f, P)
    assert abs((v2f - v1f) + e * (v2 - v1)) > DIRECT_RTOL * 16
