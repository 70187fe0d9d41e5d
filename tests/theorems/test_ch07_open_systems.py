"""Chapter 7 as properties: the rocket equation, the discrete origin of the
continuous rocket, the angular momentum balance of the carousel, and the frame
and point independence of the open-system principles (7.19), (7.25), (7.35).

Each property is checked by a route independent of the closed form under test:
a high-accuracy scipy integration of the equation of motion, or exact momentum
bookkeeping of a discrete model.  Strategies are local (valid by construction:
the lift-off condition is built in by drawing g as a fraction of q u/m_0).
"""

from __future__ import annotations

import numpy as np
from hypothesis import example, given
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

from mechanics import open_systems as osys
from mechanics._floats import EPS

#: solve_ivp DOP853 at rtol = atol·scale = 1e-12: smooth non-stiff ODEs over at most
#: a few e-folding times; global error within 1e3 times the local tolerance.
IVP_RTOL = 1e-12
IVP_CHECK_RTOL = 1e3 * IVP_RTOL
#: sums of a handful of products of O(1) vectors
SUM_ATOL = 64 * EPS


@st.composite
def rockets(draw):
    """(m_0, q, u, m_f, g): lift-off guaranteed, burn-out fraction 0.05 … 0.95."""
    m_0 = draw(st.floats(1.0, 1e6))
    q = m_0 * draw(st.floats(1e-4, 1e-1))  # burns 1e-4 … 1e-1 of m_0 per unit time
    u = draw(st.floats(10.0, 5e3))
    m_f = m_0 * draw(st.floats(0.05, 0.95))
    g_frac = draw(st.sampled_from([0.0, 0.3, 0.9, 1.0]) | st.floats(0.0, 1.0))
    g = g_frac * q * u / m_0
    while m_0 * g > q * u:  # the lift-off limit, rounded down
        g = float(np.nextafter(g, 0.0))
    return m_0, q, u, m_f, g


@given(rockets())
@example((1000.0, 10.0, 2000.0, 800.0, 9.81))
def test_rocket_velocity_solves_m_dv_dt_equals_q_u_minus_m_g(rocket):
    m_0, q, u, m_f, g = rocket
    T = m_f / q
    ts = np.linspace(0.0, T, 7)
    scale_v = u * -np.log1p(-m_f / m_0) + g * T
    sol = solve_ivp(
        lambda t, y: [(q * u - (m_0 - q * t) * g) / (m_0 - q * t), y[0]],
        (0.0, T),
        [0.0, 0.0],
        method="DOP853",
        t_eval=ts,
        rtol=IVP_RTOL,
        atol=[IVP_RTOL * scale_v, IVP_RTOL * scale_v * T],
    )
    kw = dict(m_0=m_0, q=q, u=u, m_f=m_f, g=g)
    v, z = osys.rocket_velocity(ts, **kw), osys.rocket_height(ts, **kw)
    assert_allclose(v, sol.y[0], rtol=0, atol=IVP_CHECK_RTOL * scale_v)
    assert_allclose(z, sol.y[1], rtol=0, atol=IVP_CHECK_RTOL * scale_v * T)
    assert np.all(v >= 0)


@given(rockets())
def test_wrong_sign_of_the_relative_velocity_is_rejected(rocket):
    """Negative control: the same comparison rejects v = −g t − u log(m_0/m)."""
    m_0, q, u, m_f, g = rocket
    T = m_f / q
    sol = solve_ivp(
        lambda t, y: [(q * u - (m_0 - q * t) * g) / (m_0 - q * t)],
        (0.0, T),
        [0.0],
        method="DOP853",
        rtol=IVP_RTOL,
        atol=IVP_RTOL * u,
    )
    wrong = -g * T + u * np.log1p(-m_f / m_0)
    scale_v = u * -np.log1p(-m_f / m_0) + g * T
    assert abs(wrong - sol.y[0, -1]) > IVP_CHECK_RTOL * scale_v


def _discrete_velocity(t, m_0, q, u, g, n):
    """n ejections of δm = q t/n; momentum conserved in each: Δv = u δm/m_before − g Δt."""
    dm = q * t / n
    return u * np.sum(dm / (m_0 - dm * np.arange(n))) - g * t


@given(rockets(), st.floats(0.1, 1.0))
def test_discrete_ejections_converge_to_the_rocket_equation(rocket, frac):
    m_0, q, u, m_f, g = rocket
    t = frac * m_f / q
    exact = float(osys.rocket_velocity(t, m_0=m_0, q=q, u=u, m_f=m_f, g=g))
    errs = []
    for n in (100, 1000, 10000):
        vd = _discrete_velocity(t, m_0, q, u, g, n)
        # the left Riemann sum of ∫ dm/m is below the integral by at most δm (1/m − 1/m_0)
        bound = u * (q * t / n) * (1 / (m_0 - q * t) - 1 / m_0)
        assert (
            -SUM_ATOL * (exact + 2 * g * t)
            <= exact - vd
            <= bound * (1 + 1e-9) + SUM_ATOL * (exact + 2 * g * t)
        )
        errs.append(exact - vd)
    # first order: ten times the ejections, a tenth of the error
    if errs[0] > 1e-9 * (exact + g * t):
        assert errs[2] < 0.15 * errs[1] + SUM_ATOL * (exact + g * t)


@st.composite
def carousels(draw):
    J_0 = draw(st.floats(1.0, 1e4))
    R = draw(st.floats(0.5, 10.0))
    # the line of fire misses the axis by 1e-6 R … R (either side), or hits it (r = 0);
    # not by a subnormal distance, where scipy's error norm underflows to 0/0
    r = R * draw(st.just(0.0) | st.floats(1e-6, 1.0) | st.floats(-1.0, -1e-6))
    q = draw(st.floats(1e-3, 1.0))
    v = draw(st.floats(10.0, 1e3))
    return dict(J_0=J_0, q=q, v=v, r=r, R=R)


@given(carousels(), st.floats(0.0, 10.0))
def test_carousel_angular_momentum_balance(c, n_tau):
    """J(t) φ̇(t) − J_0 φ̇_0 equals the angular momentum brought in, ∫ −r q v dt (7.38)."""
    tau = c["J_0"] / (c["q"] * c["R"] ** 2)  # time for the bullets to double J
    t = n_tau * tau
    w = osys.carousel_angular_velocity(t, **c)
    J = c["J_0"] + c["q"] * c["R"] ** 2 * t
    brought_in = (
        osys.angular_momentum_rate(
            [0, 0, 0], about=[0, 0, 0], q_in=c["q"], r_in=[0.0, c["r"], 0.0], v_in=[c["v"], 0, 0]
        )[2]
        * t
    )
    scale = abs(c["r"]) * c["q"] * c["v"] * t + 1e-300
    assert abs(J * w - brought_in) <= SUM_ATOL * scale
    lim = osys.carousel_limit_angular_velocity(v=c["v"], r=c["r"], R=c["R"])
    assert abs(w) <= abs(lim) * (1 + SUM_ATOL)


# the initial rate as a fraction of the limit: 0, or 1e-6 … 1 of it either way (not a
# subnormal-scale rate, where scipy's error norm underflows to 0/0)
@given(carousels(), st.just(0.0) | st.floats(1e-6, 1.0) | st.floats(-1.0, -1e-6))
def test_carousel_closed_form_matches_integration_of_7_39(c, w0_frac):
    lim = float(osys.carousel_limit_angular_velocity(v=c["v"], r=c["r"], R=c["R"]))
    w0 = 2 * w0_frac * (abs(lim) + 1.0)
    tau = c["J_0"] / (c["q"] * c["R"] ** 2)
    ts = np.linspace(0.0, 5 * tau, 6)

    def rhs(t, y):  # (7.39): (J_0 + q t R²) φ̈ = −r q v − q R² φ̇
        J = c["J_0"] + c["q"] * c["R"] ** 2 * t
        return [(-c["r"] * c["q"] * c["v"] - c["q"] * c["R"] ** 2 * y[0]) / J]

    scale = abs(lim) + abs(w0) + 1e-12
    sol = solve_ivp(
        rhs, (0.0, ts[-1]), [w0], method="DOP853", t_eval=ts, rtol=IVP_RTOL, atol=IVP_RTOL * scale
    )
    w = osys.carousel_angular_velocity(ts, phidot_0=w0, **c)
    assert_allclose(w, sol.y[0], rtol=0, atol=IVP_CHECK_RTOL * scale)


vectors = st.lists(st.floats(-10.0, 10.0), min_size=3, max_size=3).map(np.array)
flows = st.lists(st.floats(0.0, 5.0), min_size=1, max_size=3)


@given(flows, flows, st.data())
def test_relative_form_is_frame_independent(q_out, q_in, data):
    """(7.25): adding a constant velocity w to every velocity leaves a_o unchanged,
    and it agrees with (7.19) − ṁ v_o (7.20)–(7.21)."""
    v_out = np.array([data.draw(vectors) for _ in q_out])
    v_in = np.array([data.draw(vectors) for _ in q_in])
    v_o, w, F = data.draw(vectors), data.draw(vectors), data.draw(vectors)
    m = data.draw(st.floats(0.5, 10.0))
    a = osys.open_system_acceleration(
        m, F, q_out=q_out, u_out=v_out - v_o, q_in=q_in, u_in=v_in - v_o
    )
    a_boosted = osys.open_system_acceleration(
        m, F, q_out=q_out, u_out=(v_out + w) - (v_o + w), q_in=q_in, u_in=(v_in + w) - (v_o + w)
    )
    via_momentum = (
        osys.momentum_rate(F, q_out=q_out, v_out=v_out, q_in=q_in, v_in=v_in)
        - osys.mass_rate(q_out=q_out, q_in=q_in) * v_o
    ) / m
    scale = (1 + np.sum(q_out) + np.sum(q_in)) * 40.0 / m
    assert_allclose(a, a_boosted, rtol=0, atol=SUM_ATOL * scale)
    assert_allclose(a, via_momentum, rtol=0, atol=SUM_ATOL * scale)


@given(flows, st.data())
def test_angular_momentum_rate_transfers_between_points(q_in, data):
    """(7.35) about A equals (7.35) about O minus A × (7.19), with M_A = M_O − A × F."""
    r_in = np.array([data.draw(vectors) for _ in q_in])
    v_in = np.array([data.draw(vectors) for _ in q_in])
    A, F, M = data.draw(vectors), data.draw(vectors), data.draw(vectors)
    about_A = osys.angular_momentum_rate(
        M - np.cross(A, F), about=A, q_in=q_in, r_in=r_in, v_in=v_in
    )
    about_O = osys.angular_momentum_rate(M, about=[0, 0, 0], q_in=q_in, r_in=r_in, v_in=v_in)
    p_rate = osys.momentum_rate(F, q_in=q_in, v_in=v_in)
    scale = (1 + 5 * len(q_in)) * 400.0
    assert_allclose(about_A, about_O - np.cross(A, p_rate), rtol=0, atol=SUM_ATOL * scale)
