"""Chapter 7 problems 7.1–7.4, derived from the open-system principles (7.19),
(7.25), (7.35) in the book's symbols, each confirmed by an independent route: a
scipy integration whose right-hand side is :mod:`mechanics.open_systems`, a
discrete-particle model, a second derivation, or a limit.  The book's answers
are withheld; these are derived here.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import quad, solve_ivp

from identities.verify.catalogue import check
from identities.verify.proof import CheckFailure, Derivation
from identities.verify.symbolic import cross, t, vec
from mechanics import open_systems as osys
from mechanics._floats import EPS

#: mechanics against a float evaluation of the same closed form: a few products,
#: an exp/log1p/expm1, 16 eps relative to the size of the values (scaled below).
CODE_RTOL = 16 * EPS
#: solve_ivp (DOP853) at rtol = atol = 1e-12 on smooth non-stiff ODEs: global error
#: within 1e3 times that (measured ~1e-11 relative).  An integration tolerance.
IVP_RTOL = 1e-12
IVP_CHECK_RTOL = 1e3 * IVP_RTOL

ex, ez = vec(1, 0, 0), vec(0, 0, 1)


def _num(expr, subs) -> float:
    return float(sp.N(sp.sympify(expr).subs(subs), 30))


@check(
    "P7.1",
    "Problem 7.1: the speed of a jet plane",
    kind="derivation",
    covers=("P7.1",),
    statement="mass m, air flow q through the engine at w relative, v(0) = v_0, no fuel use "
    "or drag: m v̇ = q (w − v), v(t) = w + (v_0 − w) e^{−q t/m}",
)
def problem_7_1(d: Derivation) -> None:
    m, q, w = sp.symbols("m q w", positive=True)
    v_0 = sp.Symbol("v_0", real=True)
    v = sp.Function("v", real=True)(t)
    # (7.19): still air enters at v⁺ = 0, leaves at v⁻ = (v − w) e_x; m constant (7.21)
    pdot = -q * (v - w) * ex + q * 0 * ex
    d.prove_equal(
        (sp.diff(m * v, t) * ex - pdot)[0],
        m * sp.diff(v, t) - q * (w - v),
        strategy="expand",
        claim="(7.19): m v̇ = q (w − v)",
    )
    # the same from (7.25) with relative velocities u⁻ = −w e_x, u⁺ = 0 − v e_x
    d.confirm_exact(
        (-q * (-w * ex) + q * (-v * ex))[0],
        q * (w - v),
        route="(7.25) with u⁻ = −w, u⁺ = −v gives the same force",
    )
    sol = sp.dsolve(sp.Eq(m * sp.diff(v, t), q * (w - v)), v, ics={v.subs(t, 0): v_0}).rhs
    d.quantity("v", sol)
    book_form = w + (v_0 - w) * sp.exp(-q * t / m)
    d.prove_equal(sol, book_form, strategy="expand", claim="v(t) = w + (v_0 − w) e^{−q t/m}")
    d.prove_equal(
        m * sp.diff(book_form, t) - q * (w - book_form),
        0,
        strategy="expand",
        claim="solves m v̇ = q (w − v)",
    )
    d.prove_equal(book_form.subs(t, 0), v_0, strategy="expand", claim="v(0) = v_0")
    d.reject(
        m * sp.diff(v_0 + q * w * t / m, t) - q * (w - (v_0 + q * w * t / m)),
        0,
        strategy="expand",
        claim="v = v_0 + q w t/m (the intake's momentum forgotten: rocket-like thrust q w)",
    )
    d.confirm_exact(sp.limit(sol, t, sp.oo), w, route="limit t → ∞: the plane tends to v = w")
    kw = dict(m=2.0e4, q=150.0, w=700.0, v_0=60.0)
    tn = np.linspace(0.0, 600.0, 7)
    subs = {m: 20000, q: 150, w: 700, v_0: 60}
    d.confirm(
        osys.jet_velocity(tn, **kw),
        [_num(sol, {**subs, t: sp.nsimplify(x)}) for x in tn],
        atol=CODE_RTOL * 700.0,
        route="mechanics.jet_velocity against the derived v(t)",
    )

    def rhs(_t, y):  # (7.25) evaluated by mechanics
        return [
            osys.open_system_acceleration(
                2.0e4, [0, 0, 0], q_out=150.0, u_out=[-700.0, 0, 0], q_in=150.0, u_in=[-y[0], 0, 0]
            )[0]
        ]

    ivp = solve_ivp(
        rhs, (0.0, 600.0), [60.0], method="DOP853", t_eval=tn, rtol=IVP_RTOL, atol=IVP_RTOL
    )
    d.confirm(
        ivp.y[0],
        osys.jet_velocity(tn, **kw),
        atol=IVP_CHECK_RTOL * 700.0,
        route="scipy solve_ivp of mechanics.open_system_acceleration (7.25)",
    )


@check(
    "P7.2",
    "Problem 7.2: a vehicle driven by water running out of its tank",
    kind="derivation",
    covers=("P7.2",),
    statement="tank area A, hole a ≪ A, water height h, outflow u = √(2 g h) relative: "
    "the acceleration 2 ρ a g h/(M + ρ A h) is less than 2 (a/A) g",
    reading="the printed bound '(a/A)2g' is read as (a/A)·2g = 2 a g/A, the sharp bound "
    "(approached as the vehicle's dry mass M → 0).  Read as (a/A)²g it would be false: "
    "the check shows the derived acceleration exceeding (a/A)²g.  M is the mass of the "
    "vehicle without water (not named in the problem); a ≪ A lets the water's own flow "
    "inside the tank be neglected",
)
def problem_7_2(d: Derivation) -> None:
    A, a, g, h, rho, M = sp.symbols("A a g h rho M", positive=True)
    u = sp.sqrt(2 * g * h)
    q = rho * a * u  # mass flow through the hole
    m = M + rho * A * h  # vehicle with its water
    # (7.25), no horizontal external force, one outflow at u⁻ = −u e_x relative
    acc = ((-q * (-u * ex)) / m)[0]
    d.quantity("acceleration", acc)
    d.prove_equal(
        acc,
        2 * rho * a * g * h / (M + rho * A * h),
        strategy="expand",
        claim="a_v = 2 ρ a g h/(M + ρ A h)",
    )
    bound = 2 * a * g / A
    d.quantity("acceleration_bound", bound)
    gap = bound - acc
    d.prove_equal(
        gap,
        2 * a * g * M / (A * (M + rho * A * h)),
        strategy="cancel",
        claim="2 (a/A) g − a_v = 2 a g M/(A (M + ρ A h)) > 0: the acceleration is below 2 (a/A) g",
    )
    if not (2 * a * g * M / (A * (M + rho * A * h))).is_positive:
        raise CheckFailure("the gap is not positive for positive symbols")
    d.confirm_exact(sp.limit(acc, M, 0), bound, route="limit M → 0: the bound is sharp")
    d.reject(
        acc,
        2 * rho * a * g * h / (rho * A * h),
        strategy="cancel",
        claim="a_v with the vehicle's dry mass dropped",
    )
    # the squared reading fails: M = ρ A h/10, a/A = 1/100 gives 0.018 g > 1e-4 g
    pt = {A: 1, a: sp.Rational(1, 100), g: 1, h: 1, rho: 1, M: sp.Rational(1, 10)}
    if not acc.subs(pt) > ((a / A) ** 2 * g).subs(pt):
        raise CheckFailure("the (a/A)² g reading was expected to fail here")
    d.note(
        f"the reading (a/A)² g fails: at a/A = 1/100, M = ρAh/10, a_v = {acc.subs(pt)} g > 1/10000 g"
    )
    # numeric: the draining vehicle, h(t) from dh/dt = −(a/A) u, a_v(t) from mechanics' (7.25)
    An, an, gn, rhon, Mn, h0 = 2.0, 0.01, 9.81, 1000.0, 300.0, 1.5

    def rhs(_t, y):
        hh = max(y[0], 0.0)
        un = np.sqrt(2 * gn * hh)
        acc_v = osys.open_system_acceleration(
            Mn + rhon * An * hh, [0, 0, 0], q_out=rhon * an * un, u_out=[-un, 0, 0]
        )[0]
        return [-an / An * un, acc_v]

    # the tank empties at t = (A/a) √(2 h_0/g) = 110.6 s: sample before that
    tn = np.linspace(0.0, 100.0, 11)
    ivp = solve_ivp(
        rhs, (0.0, 100.0), [h0, 0.0], method="DOP853", t_eval=tn, rtol=IVP_RTOL, atol=IVP_RTOL
    )
    acc_code = np.array([rhs(0, y)[1] for y in ivp.y.T])
    acc_formula = [
        _num(
            acc,
            {
                A: 2,
                a: sp.Rational(1, 100),
                g: sp.Rational(981, 100),
                rho: 1000,
                M: 300,
                h: sp.Rational(hh),
            },
        )
        for hh in ivp.y[0]
    ]
    d.confirm(
        acc_code,
        acc_formula,
        atol=CODE_RTOL * 2 * an / An * gn,
        route="mechanics.open_system_acceleration along a simulated draining (scipy) = the derived a_v",
    )
    d.confirm(
        max(0.0, float(np.max(acc_code)) - 2 * an / An * gn),
        0.0,
        atol=0.0,
        route="the simulated acceleration stays below 2 (a/A) g at every sampled time",
    )


@check(
    "P7.3",
    "Problem 7.3: spinning up a toroidal space station with two rim rockets",
    kind="derivation",
    covers=("P7.3",),
    statement="radius r, mass m, radius of gyration d, two tangential rockets (q, u each) on "
    "the rim; target r ω² = g.  (m d² − 2 q r² t) ω̇ = 2 q r u, so "
    "t = (m d²/(2 q r²)) (1 − e^{−√(g r)/u})",
    reading="the expelled mass leaves from radius r with the rim velocity ω r minus u, "
    "tangentially; J(t) = m d² − 2 q r² t",
)
def problem_7_3(d: Derivation) -> None:
    r, m, dd, g, q, u = sp.symbols("r m d g q u", positive=True)
    omega = sp.Function("omega", real=True)(t)
    J = m * dd**2 - 2 * q * r**2 * t
    # (7.35) about the centre; rockets at ±r e_x, pushing the station anticlockwise
    pos = [r * ex, -r * ex]
    e_phi = [vec(0, 1, 0), vec(0, -1, 0)]
    lost = sum(
        (cross(p, q * (omega * r - u) * e) for p, e in zip(pos, e_phi, strict=True)), sp.zeros(3, 1)
    )
    balance = sp.diff(J * omega, t) + lost[2]  # dL/dt = −Σ r⁻ × q⁻ v⁻
    d.prove_equal(
        balance,
        J * sp.diff(omega, t) - 2 * q * r * u,
        strategy="expand",
        claim="(7.35): d(J ω)/dt = −2 q r (ω r − u), i.e. J ω̇ = 2 q r u",
    )
    d.reject(
        balance,
        J * sp.diff(omega, t) - 2 * q * r * (u - omega * r),
        strategy="expand",
        claim="J ω̇ = 2 q r (u − ω r) (the exhaust's absolute velocity used as the thrust)",
    )
    w_t = (u / r) * sp.log(m * dd**2 / J)
    d.quantity("omega", w_t)
    d.prove_equal(
        J * sp.diff(w_t, t) - 2 * q * r * u,
        0,
        strategy="cancel",
        claim="ω(t) = (u/r) ln(m d²/(m d² − 2 q r² t))",
    )
    d.prove_equal(w_t.subs(t, 0), 0, strategy="expand", claim="ω(0) = 0")
    omega_g = sp.sqrt(g / r)
    d.quantity("omega_target", omega_g)
    d.prove_equal(r * omega_g**2, g, strategy="expand", claim="r ω² = g")
    T = m * dd**2 / (2 * q * r**2) * (1 - sp.exp(-sp.sqrt(g * r) / u))
    d.quantity("t", T)
    d.prove_equal(
        J.subs(t, T),
        m * dd**2 * sp.exp(-sp.sqrt(g * r) / u),
        strategy="expand",
        claim="J(t) = m d² e^{−√(g r)/u} at the derived t",
    )
    d.prove_equal(
        w_t.subs(t, T), omega_g, strategy="expand", claim="ω(t) = √(g/r) at the derived t"
    )
    d.confirm_exact(
        sp.limit(T * u, u, sp.oo),
        m * dd**2 * omega_g / (2 * q * r),
        strategy="cancel",
        route="limit u → ∞: t ≈ J_0 ω/(2 q r u), constant torque 2 q r u on constant J_0",
    )
    d.reject(
        T,
        m * dd**2 * omega_g / (2 * q * r * u),
        strategy="cancel",
        claim="t = J_0 ω/(2 q r u) exactly (the inertia of the expelled mass kept)",
    )
    # numbers: r = 100 m, m = 1e6 kg, d = 90 m, q = 10 kg/s, u = 3000 m/s, g = 9.81 m/s²
    num = {r: 100, m: 10**6, dd: 90, g: sp.Rational(981, 100), q: 10, u: 3000}
    T_num = _num(T, num)
    d.note(f"for r = 100 m, m = 1e6 kg, d = 90 m, q = 10 kg/s, u = 3000 m/s: t = {T_num:.6g} s")
    J0, wg = 1e6 * 90.0**2, np.sqrt(9.81 / 100.0)
    d.confirm(
        osys.rim_rocket_spin_up_time(wg, J_0=J0, q=20.0, u=3000.0, r=100.0),
        T_num,
        atol=CODE_RTOL * T_num,
        route="mechanics.rim_rocket_spin_up_time (two rockets: q = 2 × 10 kg/s)",
    )

    def rhs(_t, y):  # y = [L_z]; two outflows at ±r e_x, absolute velocity (ω r − u) e_φ
        Jt = J0 - 20.0 * 100.0**2 * _t
        w = y[0] / Jt
        rate = osys.angular_momentum_rate(
            [0, 0, 0],
            about=[0, 0, 0],
            q_out=[10.0, 10.0],
            r_out=[[100.0, 0, 0], [-100.0, 0, 0]],
            v_out=[[0, w * 100.0 - 3000.0, 0], [0, -(w * 100.0 - 3000.0), 0]],
        )
        return [rate[2]]

    def reached(_t, y):
        return y[0] / (J0 - 20.0 * 100.0**2 * _t) - wg

    reached.terminal = True
    ivp = solve_ivp(
        rhs, (0.0, 2 * T_num), [0.0], method="DOP853", events=reached, rtol=IVP_RTOL, atol=IVP_RTOL
    )
    d.confirm(
        ivp.t_events[0][0],
        T_num,
        atol=IVP_CHECK_RTOL * T_num,
        route="scipy solve_ivp of mechanics.angular_momentum_rate (7.35) until r ω² = g",
    )


@check(
    "P7.4",
    "Problem 7.4: the force of a falling chain on a table",
    kind="derivation",
    covers=("P7.4",),
    statement="chain λ per length, lower end at height h, released from rest: F(x) = λ g x + λ v² "
    "with v² = 2 g (h + x), i.e. F(x) = λ g (3 x + 2 h) while the chain lands",
    reading="the chain is perfectly flexible and the landed part comes to rest at once; the "
    "chain's length ℓ bounds x (F = λ g ℓ once all has landed)",
)
def problem_7_4(d: Derivation) -> None:
    lam, g, h, ell = sp.symbols("lambda g h ell", positive=True)
    x = sp.Symbol("x", nonnegative=True)
    v = sp.Symbol("v", positive=True)
    # the hanging part: outflow at its bottom leaves with the part's own velocity, u⁻ = 0,
    # so (7.25) gives m a = m g: free fall, and after falling h + x, v² = 2 g (h + x)
    m_hang = lam * (ell - x)
    acc = ((m_hang * (-g * ez) - lam * v * (0 * ez)) / m_hang)[2]
    d.prove_equal(acc, -g, strategy="cancel", claim="(7.25): the hanging part falls freely")
    v2 = 2 * g * (h + x)
    # the landed part: an open system at rest (m = λ x), inflow λ v at −v e_z, (7.19):
    # 0 = (N − λ x g) e_z + λ v (−v e_z)
    N = sp.Symbol("N", real=True)
    eq = ((N - lam * x * g) * ez + lam * v * (-v * ez))[2]
    N_sol = sp.solve(eq, N)[0].subs(v**2, v2)
    F = sp.expand(N_sol)
    d.quantity("F", F)
    d.prove_equal(F, lam * g * (3 * x + 2 * h), strategy="expand", claim="F(x) = λ g (3 x + 2 h)")
    d.reject(
        F,
        lam * g * (x + 2 * h),
        strategy="expand",
        claim="F = λ g x + λ v²/2 (half the momentum flux)",
    )
    # second derivation: the whole chain (closed): p = −λ (ℓ − x) v e_z, dx/dt = v, dv/dt = g
    xs, vs = sp.Function("x")(t), sp.Function("v")(t)
    p = -lam * (ell - xs) * vs
    pdot = sp.diff(p, t).subs({sp.Derivative(xs, t): vs, sp.Derivative(vs, t): g})
    N_closed = pdot + lam * ell * g  # dp/dt = N − λ ℓ g
    d.confirm_exact(
        N_closed.subs({vs: sp.sqrt(v2.subs(x, xs))}).subs(xs, x),
        F,
        route="second derivation: the momentum principle for the whole chain (a closed system)",
    )
    d.confirm_exact(F.subs(h, 0), 3 * lam * g * x, route="limit h = 0: the classic 3 λ g x")
    # numeric: n discrete links landing one by one (impulse μ v_k, then weight μ g each),
    # total table impulse up to x = X, against ∫ F dt through mechanics
    lamn, gn, hn, elln, X = 0.8, 9.81, 0.5, 2.0, 1.6
    t0, tX = np.sqrt(2 * hn / gn), np.sqrt(2 * (hn + X) / gn)
    continuous = quad(
        lambda tt: osys.falling_chain_table_force(
            min(max(gn * tt**2 / 2 - hn, 0.0), elln), lam=lamn, h=hn, g=gn, ell=elln
        ),
        t0,
        tX,
        epsabs=1e-13,
        epsrel=1e-13,
    )[0]
    for n in (400, 40000):
        delta = elln / n
        xk = delta * np.arange(n)
        xk = xk[xk <= X]
        vk, tk = np.sqrt(2 * gn * (hn + xk)), np.sqrt(2 * (hn + xk) / gn)
        discrete = np.sum(lamn * delta * vk + lamn * delta * gn * (tX - tk))
        # Riemann sums of ∫ λ v dx (increasing) and ∫ λ g (t_X − t(x)) dx (decreasing)
        bound = lamn * delta * (2 * np.sqrt(2 * gn * (hn + X)) + gn * tX)
        d.confirm(
            discrete,
            continuous,
            atol=bound,
            route=f"{n} discrete links: the table's total impulse matches ∫ F dt (mechanics)",
        )
    d.confirm(
        osys.falling_chain_table_force(X, lam=lamn, h=hn, g=gn, ell=elln),
        _num(
            F,
            {lam: sp.nsimplify(lamn), g: sp.nsimplify(gn), h: sp.nsimplify(hn), x: sp.nsimplify(X)},
        ),
        atol=CODE_RTOL * 50,
        route="mechanics.falling_chain_table_force against the derived F(x)",
    )
