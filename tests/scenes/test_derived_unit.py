"""Unit tests of :mod:`mechanics.scenes.derived` on hand-built engines and trajectories
(issue 16): which rows a scene gets, their exact values from textbook closed forms
computed here independently (Landau's period of the free top, the heavy top's cubic by
its roots and quadratures in mpmath, Tsiolkovsky's rocket), and the measured values
from series whose crossings and maxima are known by hand.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import mpmath
import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.scenes.derived import _crossings, _spacing, _vertex, derived_quantities
from mechanics.scenes.spec import Body
from mechanics.scenes.state import Layout
from mechanics.scenes.trajectory import Event, Trajectory

#: a sum or difference of a few O(1) numbers, each rounded once
FEW_ROUNDINGS = 8 * EPS
#: the tops' closed forms (elliptic K by the AGM, roots polished by Newton) against
#: mpmath at 30 digits: a few dozen roundings of O(1) terms
CLOSED_FORM_RTOL = 64 * EPS


def body(shape="custom", mass=1.0, initial=None, **dims) -> Body:
    return Body("b", shape, mass, dims, {} if initial is None else initial)


def effect(kind, *, moment_on=(), **attrs):
    """A listed effect: its type, which bodies it exerts a moment on, its fields."""
    return SimpleNamespace(type=kind, exerts_moment=lambda i: i in moment_on, **attrs)


def gravity(g=2.0, direction=(0.0, 0.0, -1.0)):
    d = np.array(direction, float)
    return effect("gravity", g=g, direction=d, vector=g * d)


def engine(bodies, effects, *, w0, pins=None, names=None, duration=10.0):
    lay = Layout.of(bodies, pins=pins)
    n = len(bodies)
    return SimpleNamespace(
        layout=lay,
        names=names or [f"b{i}" for i in range(n)],
        n=n,
        effects=effects,
        w0=np.array(w0, float).reshape(n, 3),
        R0=np.tile(np.eye(3), (n, 1, 1)),
        m0=np.array([b.mass for b in bodies], float),
        scene=SimpleNamespace(bodies=bodies, duration=duration),
        # the model's effects by role: here all are loads (none is an impact pair)
        model=SimpleNamespace(forces=effects, impacts=[], impacts_of={}),
    )


def traj(t, series=None, events=(), state_at=None) -> Trajectory:
    return Trajectory(
        t=np.asarray(t, float),
        series=series or {},
        events=list(events),
        method="test",
        state_at=state_at or (lambda tt: {}),
    )


# ---------------------------------------------------------------- the measuring helpers


def test_crossings_are_interpolated_linearly_between_samples_of_opposite_sign() -> None:
    t = np.array([0.0, 2.0, 4.0, 6.0, 8.0])
    # 1 → −1 halfway: 1; −1 → 3 a quarter of the way: 4.5; 3 → 3: none
    x = np.array([1.0, -1.0, -1.0, 3.0, 3.0])
    np.testing.assert_array_equal(_crossings(t, x), [1.0, 4.5])
    # touching zero is not a change of sign
    assert _crossings(t, np.array([1.0, 0.0, -0.0, 0.0, 2.0])).size == 0


def test_the_vertex_of_the_parabola_through_three_samples() -> None:
    t = np.array([10.0, 10.5, 11.0, 11.5])
    # 0, 1, 0.5 at dt = ½: the parabola's vertex is dt · ½ (0 − 0.5)/(0 − 2 + 0.5) =
    # dt/6 after t[1]
    assert _vertex(t, np.array([0.0, 1.0, 0.5, 0.0]), 1) == pytest.approx(
        10.5 + 0.5 / 6, rel=FEW_ROUNDINGS, abs=0.0
    )
    # symmetric samples: the middle one; collinear ones (no curvature): the sample itself
    assert _vertex(t, np.array([5.0, 2.0, 3.0, 2.0]), 2) == 11.0
    assert _vertex(t, np.array([0.0, 1.0, 2.0, 3.0]), 2) == 11.0
    assert type(_vertex(t, np.array([0.0, 1.0, 2.0, 3.0]), 2)) is float


def test_the_spacing_is_the_mean_difference_of_at_least_two_times() -> None:
    assert _spacing([1.0, 3.0, 7.0]) == 3.0
    assert _spacing([1.0, 2.5]) == 1.5
    assert _spacing([4.0]) is None
    assert _spacing([]) is None


# ---------------------------------------------------------------- the free top


def landau_period(J, w) -> float:
    """The period of ω of a free asymmetric top, 4K(k²)/λ (Landau & Lifshitz §37), J
    sorted ascending, in mpmath."""
    with mpmath.workdps(30):
        J1, J2, J3 = (mpmath.mpf(x) for x in J)
        w1, w2, w3 = (mpmath.mpf(x) for x in w)
        E2 = J1 * w1**2 + J2 * w2**2 + J3 * w3**2  # 2E
        L2 = (J1 * w1) ** 2 + (J2 * w2) ** 2 + (J3 * w3) ** 2
        if L2 > E2 * J2:  # ω circulates the axis of the largest moment
            lam = mpmath.sqrt((J3 - J2) * (L2 - E2 * J1) / (J1 * J2 * J3))
            k2 = (J2 - J1) * (E2 * J3 - L2) / ((J3 - J2) * (L2 - E2 * J1))
        else:
            lam = mpmath.sqrt((J2 - J1) * (E2 * J3 - L2) / (J1 * J2 * J3))
            k2 = (J3 - J2) * (L2 - E2 * J1) / ((J2 - J1) * (E2 * J3 - L2))
        return float(4 * mpmath.ellipk(k2) / lam)


#: ω about the middle axis changes sign at 0.5 and 2.5 (linear interpolation): half a
#: period 2, a period 4
OMEGA_MID = np.array([1.0, -1.0, -1.0, 1.0, 1.0])
T5 = np.arange(5.0)


@pytest.mark.parametrize(
    ("w0", "regime"),
    [
        ((0.2, 0.3, 2.0), "axis3"),  # close to the largest moment's axis (index 0)
        ((0.02, 2.0, 0.3), "axis1"),  # close to the smallest's axis (index 1)
    ],
)
def test_a_torque_free_top_reports_its_regime_and_the_period_of_its_omega(w0, regime) -> None:
    # J = (3, 1, 2): the middle moment is body axis 3, whose ω is sampled
    eng = engine([body(inertia=[3.0, 1.0, 2.0])], [gravity()], w0=w0)
    rows = derived_quantities(eng, traj(T5, {"omega3": OMEGA_MID}))
    assert len(rows) == 2
    assert rows[0] == (f"regime: {regime}", None, None)
    name, exact, measured = rows[1]
    assert name == "period of ω (two flips)"
    # sorted: J (1, 2, 3), ω (w0[1], w0[2], w0[0])
    assert exact == pytest.approx(
        landau_period((1.0, 2.0, 3.0), (w0[1], w0[2], w0[0])), rel=CLOSED_FORM_RTOL, abs=0
    )
    assert type(exact) is float
    assert measured == 4.0


def test_each_of_several_tops_is_named_and_read_from_its_own_series() -> None:
    eng = engine(
        [body(inertia=[3.0, 1.0, 2.0]), body(inertia=[1.0, 3.0, 2.0])],
        [],
        w0=[(0.2, 0.3, 2.0), (0.2, 0.3, 2.0)],
        names=["left", "right"],
    )
    series = {
        "left.omega3": OMEGA_MID,
        # the right top's middle axis is also 3; its ω changes sign at 0.5, 1.5, 2.5
        "right.omega3": np.array([1.0, -1.0, 1.0, -1.0, -1.0]),
    }
    rows = derived_quantities(eng, traj(T5, series))
    assert [(n, m) for n, _, m in rows] == [
        ("left.regime: axis3", None),
        ("left.period of ω (two flips)", 4.0),
        ("right.regime: axis3", None),
        ("right.period of ω (two flips)", 2.0),
    ]


def test_a_top_seen_to_flip_fewer_than_twice_has_no_measured_period() -> None:
    eng = engine([body(inertia=[3.0, 1.0, 2.0])], [], w0=[(0.2, 0.3, 2.0)])
    rows = derived_quantities(eng, traj(T5, {"omega3": np.array([1.0, -1.0, -1.0, -2.0, -1.0])}))
    assert rows[1][0] == "period of ω (two flips)"
    assert rows[1][2] is None


def test_a_steady_spin_has_no_finite_flip_period() -> None:
    eng = engine([body(inertia=[3.0, 1.0, 2.0])], [], w0=[(0.0, 0.0, 5.0)])
    rows = derived_quantities(eng, traj(T5, {"omega3": np.full(5, 5.0)}))
    assert rows == [("regime: steady", None, None), ("period of ω (two flips)", None, None)]


@pytest.mark.parametrize(
    ("bodies", "effects", "w0", "pins"),
    [
        ([body(inertia=[3.0, 1.0, 2.0])], [effect("spring", moment_on={0})], (0.2, 0.3, 2.0), None),
        ([body(inertia=[3.0, 1.0, 2.0])], [], (0.0, 0.0, 0.0), None),  # at rest
        ([body("rod", 12.0, length=2.0)], [], (0.2, 0.3, 2.0), None),  # J3 = 0
        ([body("point")], [], (0.2, 0.3, 2.0), None),  # no spin
        ([body(inertia=[3.0, 1.0, 2.0])], [], (0.2, 0.3, 2.0), {0: ([0, 0, 0], [0, 0, 1])}),
        # within 1e-160 of a spin about the middle axis: m1 underflows, no closed form
        ([body(inertia=[1.0, 2.0, 3.0])], [], (1e-160, 1.0, 0.0), None),
    ],
)
def test_no_free_top_row_unless_a_rigid_body_spins_free_of_moments(
    bodies, effects, w0, pins
) -> None:
    eng = engine(bodies, effects, w0=w0, pins=pins)
    rows = derived_quantities(eng, traj(T5, {"omega3": OMEGA_MID, "omega2": OMEGA_MID}))
    assert not any("regime" in n or "period of ω" in n for n, _, _ in rows)


@pytest.mark.parametrize(
    ("first", "w_first", "effects"),
    [
        (body(inertia=[3.0, 1.0, 2.0]), (0.2, 0.3, 2.0), [effect("spring", moment_on={0})]),
        (body(inertia=[3.0, 1.0, 2.0]), (0.0, 0.0, 0.0), []),  # at rest
        (body(inertia=[1.0, 2.0, 3.0]), (1e-160, 1.0, 0.0), []),  # no closed form
    ],
)
def test_a_free_top_after_a_body_without_rows_still_has_its_rows(first, w_first, effects) -> None:
    eng = engine(
        [first, body(inertia=[3.0, 1.0, 2.0])],
        effects,
        w0=[w_first, (0.2, 0.3, 2.0)],
        names=["first", "top"],
    )
    series = {"first.omega3": OMEGA_MID, "first.omega2": OMEGA_MID, "top.omega3": OMEGA_MID}
    rows = derived_quantities(eng, traj(T5, series))
    assert [(n, m) for n, _, m in rows] == [
        ("top.regime: axis3", None),
        ("top.period of ω (two flips)", 4.0),
    ]


# ---------------------------------------------------------------- the heavy top


def heavy_top_reference(J1, J3, mgl, theta, theta_dot, psi_dot, w3):
    """θ min, θ max, the nutation period and the mean precession rate of a heavy
    symmetric top at θ with rates θ̇, ψ̇ and spin component ω3, from the energy and the
    two angular momenta (5.53), (5.55), (5.66), in mpmath:

    u = cos θ, u̇² = f(u) = (e − βu)(1 − u²) − (a − bu)², β = 2mgℓ/J1, a = L_z/J1,
    b = L3/J1, e = (2E − L3²/J3)/J1; θ swings between the roots u1 ≤ u2 of f in
    [−1, 1] (u3 > 1), where f = β (u − u1)(u2 − u)(u3 − u).  With u = u1 + (u2 − u1)
    sin²χ, du/√f = 2 dχ/√(β (u3 − u)), smooth: T = 2 ∫ du/√f over [u1, u2] =
    4 ∫₀^{π/2} dχ/√(β (u3 − u)); ψ̇ = (a − bu)/(1 − u²), Δψ likewise with ψ̇ inside.
    """
    with mpmath.workdps(30):
        J1, J3, mgl = mpmath.mpf(J1), mpmath.mpf(J3), mpmath.mpf(mgl)
        u0 = mpmath.cos(mpmath.mpf(theta))
        s2 = 1 - u0**2
        L3 = J3 * w3
        Lz = J1 * s2 * psi_dot + L3 * u0
        E = J1 * (theta_dot**2 + psi_dot**2 * s2) / 2 + L3**2 / (2 * J3) + mgl * u0
        beta, a, b = 2 * mgl / J1, Lz / J1, L3 / J1
        e = (2 * E - L3**2 / J3) / J1
        # f(u) = β u³ − (e + b²) u² + (2ab − β) u + (e − a²)
        coefs = [beta, -(e + b * b), 2 * a * b - beta, e - a * a]
        u1, u2, u3 = sorted(mpmath.re(r) for r in mpmath.polyroots(coefs, extraprec=30))

        def u(chi):
            return u1 + (u2 - u1) * mpmath.sin(chi) ** 2

        def dt(chi):  # dt/dχ
            return 2 / mpmath.sqrt(beta * (u3 - u(chi)))

        T = 2 * mpmath.quad(dt, [0, mpmath.pi / 2])
        dpsi = 2 * mpmath.quad(
            lambda c: (a - b * u(c)) / (1 - u(c) ** 2) * dt(c), [0, mpmath.pi / 2]
        )
        return (
            float(mpmath.acos(u2)),
            float(mpmath.acos(u1)),
            float(T),
            float(dpsi / T),
        )


#: a series of cos θ (dt = 1) with maxima at samples 3 (a plateau 1, 1 after 0.5:
#: the vertex ½ (0.5 − 1)/(0.5 − 2 + 1) = ½ after), 7 and 11 (0, 1, 0.5: the vertex
#: ½ (0 − 0.5)/(0 − 2 + 0.5) = ⅙ after); not at the rise 0, 0.5, 1 (sample 2) nor at
#: the start (0.25 then 0: no sample before it); spacings 3⅔ and 4, mean 23/6
COS_THETA = np.array([0.25, 0.0, 0.5, 1.0, 1.0, 0.0, 0.0, 1.0, 0.5, 0.0, 0.0, 1.0, 0.5, 0.0])
T14 = np.arange(14.0)
PEAKS = (3.5, 7.0 + 1.0 / 6.0, 11.0 + 1.0 / 6.0)


def heavy_engine(*, initial=None, w0=(0.3, 0.5, 6.0), effects=None, g_arm=0.5, J=None):
    # a top of mass 1 with J_G = (1, 1, 1.5), G at ½ up its axis from the pin: about
    # the pin J1 = 1 + 1 · ¼ = 1.25, J3 = 1.5; under g = 2: m g ℓ = 1
    top = body(inertia=J or [1.0, 1.0, 1.5], initial={"theta": 1.0} if initial is None else initial)
    return engine(
        [top],
        [effect("fixed_point"), gravity(2.0)] if effects is None else effects,
        w0=w0,
        pins={0: ([0.0, 0.0, 0.0], [0.0, 0.0, g_arm])},
    )


def sampled(t, cos_theta):
    return traj(t, {"theta": np.ones(t.size), "cos_theta": cos_theta, "psi": 0.5 * t})


def test_a_heavy_top_reports_its_nutation_and_precession_exact_and_measured() -> None:
    # φ = 0 (not given): ω_A = (θ̇, ψ̇ sin θ, ψ̇ cos θ + φ̇) (2.69), so ω_A = (0.3, 0.5, 6)
    # is θ̇ = 0.3, ψ̇ = 0.5 / sin 1, ω3 = 6
    theta = 1.0
    th_min, th_max, period, rate = heavy_top_reference(
        1.25, 1.5, 1.0, theta, 0.3, 0.5 / math.sin(theta), 6.0
    )
    assert th_min < theta < th_max  # moving at the start: between its turning points
    # θ over the samples; ψ = 0.75 t − 2, read at the first and last maximum
    theta_s = np.linspace(0.9, 1.3, 14)[::-1]
    psi = 0.75 * T14 - 2.0
    series = {"theta": theta_s, "cos_theta": COS_THETA, "psi": psi}
    rows = derived_quantities(heavy_engine(), traj(T14, series))
    names = [n for n, _, _ in rows]
    assert names == [
        "θ min (rad)",
        "θ max (rad)",
        "nutation period",
        "mean precession rate ψ̇ (rad/s)",
    ]
    (_, x_min, m_min), (_, x_max, m_max), (_, x_T, m_T), (_, x_rate, m_rate) = rows
    assert x_min == pytest.approx(th_min, rel=CLOSED_FORM_RTOL, abs=0)
    assert x_max == pytest.approx(th_max, rel=CLOSED_FORM_RTOL, abs=0)
    assert (m_min, m_max) == (0.9, 1.3)
    assert x_T == pytest.approx(period, rel=CLOSED_FORM_RTOL, abs=0)
    assert x_rate == pytest.approx(rate, rel=CLOSED_FORM_RTOL, abs=0)
    # the mean spacing of the maxima, (11 + 1/6 − 3.5)/2 = 23/6, and ψ's slope between
    assert m_T == pytest.approx((PEAKS[-1] - PEAKS[0]) / 2, rel=FEW_ROUNDINGS, abs=0)
    assert m_rate == pytest.approx(0.75, rel=FEW_ROUNDINGS, abs=0)


def test_a_heavy_top_seen_at_two_maxima_has_a_measured_period_and_rate() -> None:
    # maxima at 1 + 1/6 and 5 + 1/6: period 4; ψ = 0.5 t: rate 0.5
    c = np.array([0.0, 1.0, 0.5, 0.0, 0.0, 1.0, 0.5])
    rows = derived_quantities(heavy_engine(), sampled(np.arange(7.0), c))
    by_name = {n: m for n, _, m in rows}
    assert by_name["nutation period"] == pytest.approx(4.0, rel=FEW_ROUNDINGS, abs=0)
    assert by_name["mean precession rate ψ̇ (rad/s)"] == pytest.approx(0.5, rel=FEW_ROUNDINGS, abs=0)


def test_a_heavy_top_seen_at_one_maximum_has_no_measured_period_or_rate() -> None:
    c = np.array([0.0, 1.0, 0.5, 0.25, 0.0])
    rows = derived_quantities(heavy_engine(), sampled(T5, c))
    by_name = {n: (x, m) for n, x, m in rows}
    assert by_name["nutation period"][1] is None
    assert by_name["mean precession rate ψ̇ (rad/s)"][1] is None
    assert by_name["nutation period"][0] > 0


def test_a_heavy_top_turned_about_its_axis_reads_its_rates_through_phi() -> None:
    # at φ = π/2: ω_A = (ψ̇ sin θ, −θ̇, ψ̇ cos θ + φ̇): (0.5, −0.3, 6) is the top of
    # ω_A = (0.3, 0.5, 6) at φ = 0
    theta = 1.0
    th_min, th_max, period, rate = heavy_top_reference(
        1.25, 1.5, 1.0, theta, 0.3, 0.5 / math.sin(theta), 6.0
    )
    eng = heavy_engine(initial={"theta": theta, "phi": math.pi / 2}, w0=(0.5, -0.3, 6.0))
    exact = [x for _, x, _ in derived_quantities(eng, sampled(T14, COS_THETA))]
    np.testing.assert_allclose(
        exact, [th_min, th_max, period, rate], rtol=CLOSED_FORM_RTOL * 4, atol=0
    )


@pytest.mark.parametrize(
    "change",
    [
        {"effects": [effect("fixed_point"), gravity(2.0), effect("drag")]},
        {"effects": [effect("fixed_point"), gravity(2.0), gravity(1.0)]},
        {"effects": [effect("fixed_point"), gravity(2.0, direction=(0.0, 0.0, 1.0))]},
        {"effects": [effect("fixed_point"), gravity(2.0, direction=(0.0, -1.0, 0.0))]},
        {"effects": [gravity(2.0)]},
        {"J": [1.0, 1.25, 1.5]},  # not symmetric about the pin
        {"g_arm": -1.0},  # G below the pin
        {"g_arm": 0.0},  # G at the pin
        {"initial": {"theta": 0.0}},  # upright: the Euler angles are singular
        {"initial": {}},  # upright by default
        {"initial": {"theta": math.pi}},
        {"initial": {"theta": -0.5}},
    ],
)
def test_no_heavy_top_rows_outside_a_symmetric_top_under_gravity_along_minus_z(change) -> None:
    rows = derived_quantities(heavy_engine(**change), sampled(T14, COS_THETA))
    assert not any(n.startswith(("θ", "nutation", "mean precession")) for n, _, _ in rows)


def test_no_heavy_top_rows_for_a_pinned_body_among_others() -> None:
    top = body(inertia=[1.0, 1.0, 1.5], initial={"theta": 1.0})
    eng = engine(
        [top, body("point")],
        [effect("fixed_point"), gravity(2.0)],
        w0=[(0.0, 0.5, 6.0), (0.0, 0.0, 0.0)],
        pins={0: ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])},
    )
    series = {"b0.theta": np.ones(14), "b0.cos_theta": COS_THETA, "b0.psi": T14}
    assert derived_quantities(eng, traj(T14, series)) == []


# ---------------------------------------------------------------- impacts and rockets


def test_impacts_report_the_formulas_loss_beside_the_kinetic_energy_lost() -> None:
    events = [
        Event(
            1.0,
            "impact",
            {"kinetic_energy_before": 4.0, "kinetic_energy_after": 3.0, "energy_loss": 0.75},
        ),
        Event(2.0, "rolling", {"kinetic_energy_before": 9.0}),  # no loss recorded: not counted
        Event(
            3.0,
            "impact",
            {"kinetic_energy_before": 2.0, "kinetic_energy_after": 1.5, "energy_loss": 0.5},
        ),
    ]
    eng = engine([body("point")], [], w0=[(0, 0, 0)])
    assert derived_quantities(eng, traj(T5, events=events)) == [
        # 0.75 + 0.5 from (6.41); (4 − 3) + (2 − 1.5) from the velocities
        ("kinetic energy lost in impacts (6.41)", 1.25, 1.5)
    ]


def thrust(**attrs):
    base = dict(
        i=0, u=3.0, q=1.0, burn_out=2.0, body_frame=False, direction=np.array([0.0, 0.0, 1.0])
    )
    return effect("thrust", **{**base, **attrs})


def rocket_state(at, velocity, prefix=""):
    def state_at(t):
        assert t == at, "the speed is read at burn-out"
        return {f"{prefix}v{c}": x for c, x in zip("xyz", velocity, strict=True)}

    return state_at


def test_a_rocket_reports_tsiolkovskys_speed_at_burn_out() -> None:
    # m0 = 4, q = 1, t_b = 2: m_f = 2; u = 3; gravity 2 down against the thrust up:
    # Δv = u ln(m0/m_f) − g t_b = 3 ln 2 − 4; measured: v(t_b) − v0 along the thrust
    rocket = body("point", 4.0, initial={"velocity": [5.0, 0.0, 1.0]})
    eng = engine([rocket], [gravity(2.0), thrust()], w0=[(0, 0, 0)], duration=2.0)
    rows = derived_quantities(eng, traj(T5, state_at=rocket_state(2.0, [7.0, 1.0, 0.25])))
    ((name, exact, measured),) = rows
    assert name == "speed gained by burn-out (7.30)"
    assert exact == pytest.approx(3.0 * math.log(2.0) - 4.0, rel=FEW_ROUNDINGS, abs=0)
    assert measured == -0.75  # 0.25 − 1 along e3


def test_a_rocket_among_bodies_reads_its_own_named_velocity_and_every_gravity() -> None:
    # thrust along e1 for the second body; gravities (0, 0, −2) and (−1, 0, 0): along
    # the thrust −1 per second; m0 = 8, q = 2, t_b = 3: m_f = 2, Δv = u ln 4 − 3
    rocket = body("point", 8.0)
    d = np.array([1.0, 0.0, 0.0])
    eng = engine(
        [body("point"), rocket],
        [
            gravity(2.0),
            gravity(1.0, direction=(-1.0, 0.0, 0.0)),
            thrust(i=1, q=2.0, burn_out=3.0, direction=d),
        ],
        w0=[(0, 0, 0), (0, 0, 0)],
        names=["ball", "rocket"],
        duration=5.0,
    )
    rows = derived_quantities(eng, traj(T5, state_at=rocket_state(3.0, [2.5, 9.0, 9.0], "rocket.")))
    ((_name, exact, measured),) = rows
    assert exact == pytest.approx(3.0 * math.log(4.0) - 3.0, rel=FEW_ROUNDINGS, abs=0)
    assert measured == 2.5  # from rest


def test_a_rocket_in_free_space_gains_u_ln_of_its_mass_ratio() -> None:
    # no gravity: Δv = u ln(m0/m_f) = 3 ln 2
    eng = engine([body("point", 4.0)], [thrust()], w0=[(0, 0, 0)], duration=3.0)
    rows = derived_quantities(eng, traj(T5, state_at=rocket_state(2.0, [0.0, 0.0, 2.0])))
    ((_, exact, measured),) = rows
    assert exact == pytest.approx(3.0 * math.log(2.0), rel=FEW_ROUNDINGS, abs=0)
    assert measured == 2.0


@pytest.mark.parametrize(
    "attrs",
    [{"body_frame": True}, {"burn_out": 2.5}],
)
def test_no_rocket_row_for_a_thrust_turning_with_the_body_or_burning_past_the_end(attrs) -> None:
    eng = engine([body("point", 4.0)], [thrust(**attrs)], w0=[(0, 0, 0)], duration=2.0)
    assert derived_quantities(eng, traj(T5, state_at=rocket_state(2.0, [0, 0, 0]))) == []
