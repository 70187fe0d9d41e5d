"""Chapter 7 worked examples: 7.1 (the force on a pipe bend), 7.2 (the rocket),
7.3 (the carousel under fire).  Each is re-derived from the momentum principles
(7.19), (7.25), (7.35) and compared with the printed result, then confirmed
numerically through :mod:`mechanics.open_systems` (and, for the rocket and the
carousel, by an independent scipy integration or a discrete particle model).
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, t, vec
from mechanics import open_systems as osys
from mechanics._floats import EPS

#: mechanics against a float evaluation of the same closed form (a few products,
#: a log1p): 16 eps relative to the O(1)–O(10³) values compared (scaled below).
CODE_RTOL = 16 * EPS
#: solve_ivp (DOP853) is run at rtol = atol = 1e-12 on smooth, non-stiff ODEs over a
#: few time constants; its global error stays within 1e3 times that (measured ~1e-11
#: relative): the tolerance of a numeric *integration*, not of the formula.
IVP_RTOL = 1e-12
IVP_CHECK_RTOL = 1e3 * IVP_RTOL

ex, ey, ez = vec(1, 0, 0), vec(0, 1, 0), vec(0, 0, 1)


@check(
    "E7.1",
    "Example 7.1: the force that holds a 90° pipe bend",
    kind="derivation",
    covers=("E7.1", "eq7.22", "eq7.23"),
    statement="q = 1 kg/s, v = 1 m/s; inflow v⁺ = v e_y, outflow v⁻ = −v e_x: "
    "F_x = −q v, F_y = −q v, |F| = √2 q v = √2 N",
    reading="from (7.23), the water enters along +e_y (the term +q v e_y is q v⁺) and "
    "leaves along −e_x (−q v⁻ = −(−q v) e_x)",
)
def example_7_1(d: Derivation) -> None:
    q, v = sp.symbols("q v", positive=True)
    Fx, Fy = sp.symbols("F_x F_y", real=True)
    F = vec(Fx, Fy, 0)
    v_in, v_out = v * ey, -v * ex
    eq_7_22 = F - q * v_out + q * v_in  # (7.19) with dp_o/dt = 0
    d.prove_equal(
        eq_7_22,
        F - (-q * v) * ex + q * v * ey,
        strategy="expand",
        claim="(7.22) in components (7.23)",
    )
    sol = sp.solve(list(eq_7_22[:2]), [Fx, Fy], dict=True)[0]
    F_sol = F.subs(sol)
    d.quantity("F", F_sol)
    d.prove_equal(F_sol, vec(-q * v, -q * v, 0), strategy="expand", claim="F_x = F_y = −q v")
    magnitude = sp.sqrt(F_sol.dot(F_sol))
    d.quantity("F_magnitude", magnitude)
    d.prove_equal(magnitude, sp.sqrt(2) * q * v, strategy="expand", claim="|F| = √2 q v")
    book = {q: 1, v: 1}  # kg/s, m/s
    d.prove_equal(
        magnitude.subs(book),
        sp.sqrt(2),
        strategy="expand",
        claim="printed: F = √2 N for q = 1 kg/s, v = 1 m/s",
    )
    d.reject(
        F_sol,
        -q * v_out + q * v_in,
        strategy="expand",
        claim="F = −q v⁻ + q v⁺ (the flux terms taken as the force)",
    )
    d.reject(magnitude, 2 * q * v, strategy="expand", claim="|F| = 2 q v (speeds added)")
    # any bend angle α = 2β: in the inflow frame v_in = v e_1, v_out = v (cos α, sin α, 0)
    beta = sp.Symbol("beta", real=True)
    alpha = 2 * beta
    F_alpha = q * (v * vec(sp.cos(alpha), sp.sin(alpha), 0) - v * ex)
    d.quantity("F_bend", F_alpha)
    d.prove_equal(
        F_alpha.dot(F_alpha),
        (2 * q * v * sp.sin(beta)) ** 2,
        strategy="tan_half",
        claim="any bend α = 2β: |F| = 2 q v |sin(α/2)|",
    )
    d.reject(
        F_alpha.dot(F_alpha),
        (q * v * sp.sin(alpha)) ** 2 + (q * v) ** 2,
        strategy="tan_half",
        claim="|F|² = (q v sin α)² + (q v)² (the 90° components for any angle)",
    )
    d.confirm_exact(
        F_alpha.subs(beta, sp.pi / 4).dot(F_alpha.subs(beta, sp.pi / 4)),
        magnitude**2,
        route="the general bend at α = π/2 is the book's case",
    )
    # mechanics: the inflow frame (e_1 = e_y, e_2 = −e_x, turning left) mapped to the book's
    F_code = osys.pipe_bend_force(1.0, 1.0, np.pi / 2)
    d.confirm(
        [-F_code[1], F_code[0]],
        [-1.0, -1.0],
        atol=CODE_RTOL,
        route="mechanics.pipe_bend_force(1 kg/s, 1 m/s, 90°) in the book's basis: (−1, −1) N",
    )
    d.confirm(
        osys.pipe_bend_force_magnitude(1.0, 1.0, np.pi / 2),
        np.sqrt(2.0),
        atol=CODE_RTOL,
        route="mechanics.pipe_bend_force_magnitude: √2 N",
    )
    d.confirm(
        osys.momentum_rate(
            [-1.0, -1.0, 0.0], q_out=1.0, v_out=[-1.0, 0, 0], q_in=1.0, v_in=[0, 1.0, 0]
        ),
        [0.0, 0.0, 0.0],
        atol=CODE_RTOL,
        route="mechanics.momentum_rate: the printed F leaves dp_o/dt = 0",
    )


def _discrete_rocket_velocity(t, *, m_0, q, u, g, n):
    """n ejections of δm = q t/n, each conserving momentum with relative speed u after it."""
    dm = q * t / n
    m_k = m_0 - dm * np.arange(n)  # mass before the k-th ejection
    return u * np.sum(dm / m_k) - g * t  # Δv_k = u δm/m_k, gravity −g t in total


@check(
    "E7.2",
    "Example 7.2: the velocity of a vertically rising rocket",
    kind="derivation",
    covers=("E7.2", "eq7.26", "eq7.28", "eq7.29", "eq7.30"),
    defines=("eq7.27",),
    statement="m dv_o/dt = m g − q u⁻ with g = −g e_z, u⁻ = −u e_z, m = m_0 − q t gives "
    "v_o(t) = −g t − u ln(m(t)/m_0) = −g t + u ln(m_0/(m_0 − q t)), valid until T = m_f/q",
)
def example_7_2(d: Derivation) -> None:
    m_0, q, u, g, m_f = sp.symbols("m_0 q u g m_f", positive=True)
    m = m_0 - q * t  # (7.27)
    d.prove_equal(-sp.diff(m, t), q, strategy="expand", claim="(7.27): q = −dm/dt")
    v = sp.Function("v_o", real=True)(t)
    a = sp.diff(v, t)
    # (7.25) with F_e = m g and one outflow u⁻: m a_o = m g − q u⁻  (7.26)
    lhs = m * a * ez
    rhs_726 = m * (-g * ez) - q * (-u * ez)
    d.prove_equal(
        (lhs - rhs_726)[2],
        m * a + m * g - q * u,
        strategy="expand",
        claim="(7.26) along e_z: m v̇ = −m g + q u",
    )
    rhs_728 = -m * g - sp.diff(m, t) * u
    d.prove_equal(rhs_726[2], rhs_728, strategy="expand", claim="(7.28): q u = −(dm/dt) u")
    v_730 = -g * t - u * sp.log(m / m_0)  # (7.29) integrated
    v_730b = -g * t + u * sp.log(m_0 / (m_0 - q * t))
    d.quantity("v_o", v_730b)
    d.prove_equal(
        sp.expand_log(v_730, force=True),
        sp.expand_log(v_730b, force=True),
        strategy="expand",
        claim="the two printed forms of (7.30) agree (logs expanded; m_0 − q t > 0 before burn-out)",
    )
    ode = lambda vv: m * sp.diff(vv, t) - rhs_728  # noqa: E731
    d.prove_equal(ode(v_730), 0, strategy="cancel", claim="(7.30) solves (7.28)")
    d.prove_equal(v_730.subs(t, 0), 0, strategy="expand", claim="(7.30): v_o(0) = 0")
    integrand = -g - u * sp.diff(m, t) / m  # (7.29)
    d.prove_equal(
        sp.diff(v_730, t), integrand, strategy="cancel", claim="(7.29): dv_o/dt = −g − u ṁ/m"
    )
    d.reject(
        ode(-g * t - u * sp.log(m_0 / m)),
        0,
        strategy="cancel",
        claim="v = −g t − u ln(m_0/m) (wrong sign of the relative-velocity term)",
    )
    d.reject(
        ode(-g * t + u * q * t / m_0),
        0,
        strategy="cancel",
        claim="v = −g t + u q t/m_0 (mass held fixed)",
    )
    T = m_f / q
    d.quantity("T", T)
    d.prove_equal(q * T, m_f, strategy="expand", claim="burn-out when the fuel m_f = q T is gone")
    # numeric: a rocket m_0 = 1000 kg, q = 10 kg/s, u = 2000 m/s, g = 9.81 m/s², m_f = 800 kg
    num = {m_0: 1000, q: 10, u: 2000, g: sp.Rational(981, 100), m_f: 800}
    tn = np.array([0.0, 1e-9, 1.0, 30.0, 60.0, 79.5])
    kw = dict(m_0=1000.0, q=10.0, u=2000.0, g=9.81, m_f=800.0)
    printed = np.array([float(sp.N(v_730b.subs(num).subs(t, sp.nsimplify(x)), 30)) for x in tn])
    code = osys.rocket_velocity(tn, **kw)
    d.confirm(
        code,
        printed,
        atol=CODE_RTOL * 2000.0 * 2,
        route="mechanics.rocket_velocity against (7.30) at 30 digits, t = 0 … 79.5 s",
    )
    d.confirm(
        osys.burn_out_time(m_f=800.0, q=10.0), 80.0, atol=CODE_RTOL, route="mechanics: T = 80 s"
    )
    sol = solve_ivp(
        lambda _t, y: [(10.0 * 2000.0 - (1000.0 - 10.0 * _t) * 9.81) / (1000.0 - 10.0 * _t)],
        (0.0, 79.5),
        [0.0],
        method="DOP853",
        t_eval=tn,
        rtol=IVP_RTOL,
        atol=IVP_RTOL,
    )
    d.confirm(
        sol.y[0],
        code,
        atol=IVP_CHECK_RTOL * float(np.max(np.abs(code))),
        route="scipy solve_ivp (DOP853, rtol 1e-12) of m v̇ = q u − m g",
    )
    # discrete model: n ejections; the left Riemann sum of ∫dm/m lies below the
    # integral by at most δm (1/m(t) − 1/m_0), an exact bound
    for n in (10**3, 10**5):
        t1 = 60.0
        vd = _discrete_rocket_velocity(t1, m_0=1000.0, q=10.0, u=2000.0, g=9.81, n=n)
        bound = 2000.0 * (10.0 * t1 / n) * (1 / (1000.0 - 600.0) - 1 / 1000.0)
        d.confirm(
            vd + bound / 2,
            osys.rocket_velocity(t1, **kw),
            atol=bound / 2 + CODE_RTOL * 2000.0,
            route=f"momentum bookkeeping of {n} discrete ejections converges to (7.30)",
        )


@check(
    "E7.3",
    "Example 7.3: the carousel under machine-gun fire",
    kind="derivation",
    covers=("E7.3", "eq7.36", "eq7.38", "eq7.39", "eq7.40"),
    defines=("eq7.37",),
    statement="J(t) = J_0 + q⁺ t R², d/dt(J φ̇) = −r q⁺ v⁺, (J_0 + q⁺ t R²) φ̈ = −r q⁺ v⁺ − q⁺ R² φ̇; "
    "φ̈ < 0 at small t; φ̇ → φ̇_lim = −r v⁺/R²",
)
def example_7_3(d: Derivation) -> None:
    J_0, q, v, R = sp.symbols("J_0 q_plus v_plus R", positive=True)
    r, s = sp.symbols("r s", real=True)
    J = J_0 + q * t * R**2
    d.prove_equal(
        sp.diff(J, t),
        q * R**2,
        strategy="expand",
        claim="(7.36): the bullets add q⁺ R² per unit time",
    )
    d.prove_equal(J.subs(t, 0), J_0, strategy="expand", claim="(7.36): J(0) = J_0")
    # bullets along +e_x on the line y = r, at any point s of it
    torque = cross(vec(s, r, 0), q * vec(v, 0, 0))
    d.prove_equal(
        torque,
        -r * q * v * ez,
        strategy="expand",
        claim="(7.38): r⁺ × q⁺ v⁺ = −r q⁺ v⁺ e_z, any point of the line",
    )
    d.reject(torque, r * q * v * ez, strategy="expand", claim="the flux with the opposite sign")
    phi = sp.Function("phi", real=True)(t)
    phid, phidd = sp.diff(phi, t), sp.diff(phi, t, 2)
    L = J * phid  # (7.37)
    ode_739 = J * phidd - (-r * q * v - q * R**2 * phid)
    d.prove_equal(sp.diff(L, t) - torque[2], ode_739, strategy="expand", claim="(7.35) → (7.39)")
    d.quantity("phiddot_equation", sp.Eq(J * phidd, -r * q * v - q * R**2 * phid))
    w = -r * q * v * t / J
    d.quantity("phidot", w)
    res = ode_739.subs(phidd, sp.diff(w, t)).subs(phid, w)
    d.prove_equal(
        res, 0, strategy="cancel", claim="φ̇(t) = −r q v t/(J_0 + q R² t) solves (7.39), φ̇(0) = 0"
    )
    wdot0 = sp.diff(w, t).subs(t, 0)
    d.prove_equal(
        wdot0, -r * q * v / J_0, strategy="cancel", claim="φ̈(0) = −r q v/J_0 (< 0 for r > 0)"
    )
    wlim = sp.limit(w, t, sp.oo)
    d.quantity("phidot_lim", wlim)
    d.prove_equal(wlim, -r * v / R**2, strategy="expand", claim="(7.40): φ̇ → −r v⁺/R²")
    d.confirm_exact(
        sp.solve(ode_739.subs(phidd, 0), phid)[0],
        -r * v / R**2,
        route="the book's route: φ̈ = 0 in (7.39)",
    )
    d.reject(wlim, -r * v / R, strategy="expand", claim="φ̇_lim = −r v/R")
    d.reject(
        ode_739.subs(phidd, sp.diff(-r * q * v * t / J_0, t)).subs(phid, -r * q * v * t / J_0),
        0,
        strategy="cancel",
        claim="φ̇ = −r q v t/J_0 (J held constant: the added bullets' inertia forgotten)",
    )
    # numeric: a carousel J_0 = 500 kg m², R = 2 m, bullets 0.1 kg/s at 400 m/s, r = 1.5 m
    kw = dict(J_0=500.0, q=0.1, v=400.0, r=1.5, R=2.0)
    tn = np.linspace(0.0, 2000.0, 9)

    def rhs(_t, y):  # y = [L_z]; dL/dt from mechanics' (7.35)
        torque_z = osys.angular_momentum_rate(
            [0, 0, 0], about=[0, 0, 0], q_in=0.1, r_in=[-3.0, 1.5, 0.0], v_in=[400.0, 0, 0]
        )[2]
        return [torque_z]

    sol = solve_ivp(
        rhs, (0.0, 2000.0), [0.0], method="DOP853", t_eval=tn, rtol=IVP_RTOL, atol=IVP_RTOL
    )
    phidot_ivp = sol.y[0] / (500.0 + 0.1 * 4.0 * tn)
    code = osys.carousel_angular_velocity(tn, **kw)
    d.confirm(
        code,
        phidot_ivp,
        atol=IVP_CHECK_RTOL * 150.0,
        route="scipy solve_ivp of dL/dt = mechanics.angular_momentum_rate (7.35), φ̇ = L/J(t)",
    )
    d.confirm(
        code,
        [
            float(
                w.subs(
                    {
                        J_0: 500,
                        q: sp.Rational(1, 10),
                        v: 400,
                        r: sp.Rational(3, 2),
                        R: 2,
                        t: sp.nsimplify(x),
                    }
                )
            )
            for x in tn
        ],
        atol=CODE_RTOL * 150.0,
        route="mechanics.carousel_angular_velocity against the derived φ̇(t)",
    )
    big_t = 1e9
    d.confirm(
        osys.carousel_angular_velocity(big_t, **kw),
        osys.carousel_limit_angular_velocity(v=400.0, r=1.5, R=2.0),
        atol=150.0 * 500.0 / (0.1 * 4.0 * big_t) * 1.01 + CODE_RTOL * 150.0,
        route="mechanics: φ̇(t) → φ̇_lim = −150 rad/s, within J_0/(q R² t) relative",
    )
    d.confirm(
        osys.carousel_angular_acceleration(0.0, **kw),
        -1.5 * 0.1 * 400.0 / 500.0,
        atol=CODE_RTOL,
        route="mechanics.carousel_angular_acceleration(0) = −r q v/J_0 < 0",
    )
