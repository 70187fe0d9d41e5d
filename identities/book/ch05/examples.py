"""Chapter 5 worked examples: 5.1 (a sphere rolling on a rough incline), 5.2 (Euler's
equations of the free symmetric top), 5.3 (the sleeping top), 5.4 (a bicycle wheel on a
rotating axis, by the Resal equations).

Each is re-derived from the book's principles and compared with the printed results.
Example 5.1 prints (5.27) with + signs where the energy balance needs −: an erratum.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from identities.book.ch05.symmetric_top import phi_eff
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, functions_of_time, t, vec
from mechanics import dynamics as dyn
from mechanics import tops
from mechanics._floats import EPS

#: float evaluation of a few products and quotients of O(1) numbers: 64 eps.
CODE_ATOL = 64 * EPS
#: scipy DOP853 at rtol = atol = 1e-12 over ~10 time units of O(1) motion: global error
#: measured ≤ 1e-10; 2^24 eps ≈ 3.7e-9 leaves a margin and rejects any O(1e-4) error.
SIM_ATOL = 2**24 * EPS
#: Example 5.1 positions ~1 m from a handful of float products: 2^10 eps absolute.
INCLINE_ATOL = 2**10 * EPS
#: the sleeping top started at θ = 1e-3: stable nutation stays within a few times the start
#: (θ_max ≈ 1.8e-3 at L3 = 1.2 × threshold), unstable falls to O(1); 1e-2 separates them.
SLEEPING_BOUND = 1e-2

ex, ey, ez = vec(1, 0, 0), vec(0, 1, 0), vec(0, 0, 1)
m, R, J, g, ell, d_ = sp.symbols("m R J g ell d", positive=True)
beta = sp.Symbol("beta", positive=True)


# ----------------------------------------------------------------------------- Example 5.1
@check(
    "E5.1",
    "Example 5.1: a sphere rolling on a rough incline",
    kind="derivation",
    covers=("E5.1", *(f"eq5.{n}" for n in range(2, 28))),
    errata=("eq5.27",),
    statement="J_C = J + mR² (5.2); L_C = R e_z × m v_G + Jω (5.3), M_C = Rmg sin β e_y (5.4); "
    "v_G = ω × R e_z (5.5)-(5.8); (J + mR²)ω̇_x = 0, (J + mR²)ω̇_y = Rmg sin β, Jω̇_z = 0 "
    "(5.9)-(5.14); α = Rmg sin β/(J + mR²) (5.15); x(t), y(t) (5.16)-(5.23); T (5.24), "
    "Φ = −mgx sin β (5.25), E = T + Φ conserved (5.26)-(5.27)",
    printed="const. = (E + ½(J + mR²)ω_x² + ½Jω_z²) = ½(J + mR²)(ẋ/R)² − mgx sin β",
    corrected="E − ½(J + mR²)ω_x² − ½Jω_z² = ½(J + mR²)(ẋ/R)² − mgx sin β",
    reading="L̇_C = M_C about the moving contact point C holds because C moves with v_G, "
    "parallel to p (v_C × p = 0).",
)
def example_5_1(d: Derivation) -> None:
    wx, wy, wz = functions_of_time("omega_x", "omega_y", "omega_z")
    w = vec(wx, wy, wz)
    d.prove_equal(
        J * sp.eye(3) + m * ((R**2) * sp.eye(3) - R**2 * ez * ez.T),
        sp.diag(J + m * R**2, J + m * R**2, J),
        claim="(5.2): J_C = J + mR² for axes in the plane through C (parallel axes, 4.38)",
    )
    vG = cross(w, R * ez)  # (5.5), v_C = 0
    d.prove_equal(vG, vec(R * wy, -R * wx, 0), claim="(5.5)-(5.8)")
    W = -m * g * (sp.cos(beta) * ez - sp.sin(beta) * ex)
    M = cross(R * ez, W)
    d.prove_equal(M, R * m * g * sp.sin(beta) * ey, claim="(5.4): M_C = CG × W")
    L_C = cross(R * ez, m * vG) + J * w  # (5.3)
    d.prove_equal(L_C, vec((J + m * R**2) * wx, (J + m * R**2) * wy, J * wz), claim="(5.9)-(5.10)")
    eqs = sp.diff(L_C, t) - M  # (5.11)-(5.14)
    d.reject(
        L_C,
        vec((J + m * R**2) * wx, (J + m * R**2) * wy, (J + m * R**2) * wz),
        claim="J + mR² also about the normal",
    )
    alpha = R * m * g * sp.sin(beta) / (J + m * R**2)  # (5.15)
    x0, y0, wx0, wy0, wz0 = sp.symbols("x_0 y_0 omega_x0 omega_y0 omega_z0", real=True)
    sol_w = vec(wx0, wy0 + alpha * t, wz0)  # (5.16)-(5.18)
    d.prove_zero(
        eqs.subs({wx: sol_w[0], wy: sol_w[1], wz: sol_w[2]}).doit(),
        strategy="cancel",
        claim="(5.15)-(5.18) solve (5.11)-(5.14)",
    )
    x_t = x0 + R * wy0 * t + sp.Rational(1, 2) * R * alpha * t**2  # (5.22)
    y_t = y0 - R * wx0 * t  # (5.23)
    d.prove_equal(
        vec(sp.diff(x_t, t), sp.diff(y_t, t)),
        vec(R * sol_w[1], -R * sol_w[0]),
        claim="(5.19)-(5.23): ẋ = Rω_y, ẏ = −Rω_x integrated",
    )
    T_ = sp.Rational(1, 2) * m * (vG.T * vG)[0, 0] + sp.Rational(1, 2) * J * (w.T * w)[0, 0]
    T_book = sp.Rational(1, 2) * ((J + m * R**2) * (wx**2 + wy**2) + J * wz**2)  # (5.24)
    d.prove_equal(T_, T_book, claim="(5.24) from T = ½mv_G² + ½Jω² (König, 3.21)")
    x = sp.Function("x", real=True)(t)
    E = T_book - m * g * x * sp.sin(beta)  # (5.25)-(5.26)
    on_sol = {wx: sol_w[0], wy: sol_w[1], wz: sol_w[2], x: x_t}
    d.prove_zero(sp.diff(E.subs(on_sol), t), strategy="cancel", claim="(5.26): E conserved")
    xd = sp.diff(x, t)
    rhs_27 = sp.Rational(1, 2) * (J + m * R**2) * (xd / R) ** 2 - m * g * x * sp.sin(beta)
    with_rolling = {wy: xd / R}
    d.prove_equal(
        (E - sp.Rational(1, 2) * (J + m * R**2) * wx**2 - sp.Rational(1, 2) * J * wz**2).subs(
            with_rolling
        ),
        rhs_27,
        claim="(5.27) corrected: E − ½(J + mR²)ω_x² − ½Jω_z²",
    )
    d.refute(
        (E + sp.Rational(1, 2) * (J + m * R**2) * wx**2 + sp.Rational(1, 2) * J * wz**2).subs(
            with_rolling
        ),
        rhs_27,
        claim="(5.27) as printed, with + signs",
    )
    # second route: Newton–Euler about G with an unknown friction force F at C
    F1, F2, N = sp.symbols("F_1 F_2 N", real=True)
    a_w = sp.symbols("a_x a_y a_z", real=True)  # ω̇
    F = vec(F1, F2, N)
    aG = cross(vec(*a_w), R * ez)  # derivative of the rolling constraint (5.5)
    sol = sp.solve(
        list(m * aG - W - F) + list(J * vec(*a_w) - cross(-R * ez, F)), [*a_w, F1, F2, N], dict=True
    )[0]
    d.confirm_exact(
        sol[a_w[1]],
        alpha,
        route="Newton–Euler about G with the friction force solved from the rolling constraint",
        strategy="cancel",
    )
    sub = {
        m: 1.3,
        R: 0.2,
        J: 0.4 * 1.3 * 0.04,
        g: 9.81,
        beta: 0.5,
        x0: 0.1,
        y0: -0.3,
        wx0: 0.7,
        wy0: -1.1,
        wz0: 2.0,
    }
    tn = 1.7
    xn, yn, wn = tops.spherical_top_on_incline(
        tn,
        m=1.3,
        R=0.2,
        J=0.4 * 1.3 * 0.04,
        beta=0.5,
        g=9.81,
        x0=0.1,
        y0=-0.3,
        omega_0=(0.7, -1.1, 2.0),
    )
    d.confirm(
        [xn, yn, *np.ravel(wn)],
        [float(e.subs(sub).subs(t, tn)) for e in (x_t, y_t, *sol_w)],
        atol=INCLINE_ATOL,
        route="mechanics.tops.spherical_top_on_incline",
    )


# ----------------------------------------------------------------------------- Example 5.2
@check(
    "E5.2",
    "Example 5.2: Euler's equations of the free symmetric top solved",
    kind="derivation",
    covers=("E5.2", *(f"eq5.{n}" for n in range(36, 46))),
    statement="(5.36) with J2 = J1: ω3 = const. (5.37); ω̇1 + βω2 = 0, ω̇2 − βω1 = 0 "
    "(5.38)-(5.39), β = (J3 − J1)ω3(0)/J1 (5.40); ζ = ω1 + iω2 (5.41), ζ̇ − iβζ = 0 (5.42), "
    "ζ = A e^{iβt} (5.43); ω1 = |A| cos(βt + α), ω2 = |A| sin(βt + α) (5.44)-(5.45)",
)
def example_5_2(d: Derivation) -> None:
    J1, J3 = sp.symbols("J_1 J_3", positive=True)
    w = vec(*functions_of_time("omega_1", "omega_2", "omega_3"))
    wd = sp.diff(w, t)
    Jd = sp.diag(J1, J1, J3)
    printed = vec(
        J1 * wd[0] + (J3 - J1) * w[1] * w[2], J1 * wd[1] - (J3 - J1) * w[0] * w[2], J3 * wd[2]
    )
    d.prove_equal(Jd * wd + cross(w, Jd * w), printed, claim="(5.36) from (4.47), M = 0")
    w30, A, al = sp.symbols("omega_30 A alpha", real=True)
    b = (J3 - J1) / J1 * w30  # (5.40)
    d.prove_equal(
        vec(printed[0] / J1, printed[1] / J1).subs(w[2], w30),
        vec(wd[0] + b * w[1], wd[1] - b * w[0]),
        claim="(5.38)-(5.40)",
    )
    zeta = w[0] + sp.I * w[1]  # (5.41)
    d.prove_equal(
        sp.diff(zeta, t) - sp.I * b * zeta,
        (wd[0] + b * w[1]) + sp.I * (wd[1] - b * w[0]),
        claim="(5.42) = (5.38) + i (5.39)",
    )
    sol = {w[0]: A * sp.cos(b * t + al), w[1]: A * sp.sin(b * t + al), w[2]: w30}  # (5.44)-(5.45)
    d.prove_zero(
        printed.subs(sol).doit(), strategy="expand", claim="(5.37), (5.43)-(5.45) solve (5.36)"
    )
    d.prove_equal(
        (sol[w[0]] + sp.I * sol[w[1]]).rewrite(sp.exp),
        A * sp.exp(sp.I * (b * t + al)),
        strategy="expand",
        claim="(5.43): ζ = |A| e^{iα} e^{iβt}",
    )
    bad = {w[0]: A * sp.cos(-b * t + al), w[1]: A * sp.sin(-b * t + al), w[2]: w30}
    d.reject(printed.subs(bad).doit(), sp.zeros(3, 1), claim="rotation at −β")
    J1n, J3n, w0 = 2.0, 0.7, np.array([0.6, -0.2, 1.3])
    times = np.linspace(0.0, 10.0, 11)
    num = solve_ivp(
        lambda _t, y: dyn.euler_equations_rhs([J1n, J1n, J3n], y, np.zeros(3)),
        (0, 10.0),
        w0,
        t_eval=times,
        rtol=1e-12,
        atol=1e-12,
        method="DOP853",
    ).y.T
    bn = (J3n - J1n) / J1n * w0[2]
    An, aln = np.hypot(w0[0], w0[1]), np.arctan2(w0[1], w0[0])
    closed = np.stack(
        [An * np.cos(bn * times + aln), An * np.sin(bn * times + aln), np.full_like(times, w0[2])],
        -1,
    )
    d.confirm(num, closed, atol=SIM_ATOL, route="scipy integration of Euler's equations")
    d.confirm(
        tops.FreeSymmetricTop(J1n, J3n, w0).omega(times),
        closed,
        atol=CODE_ATOL * 4,
        route="mechanics.tops.FreeSymmetricTop.omega",
    )


# ----------------------------------------------------------------------------- Example 5.3
@check(
    "E5.3",
    "Example 5.3: the sleeping top is stable iff L3² > 4J'1 mgℓ",
    kind="derivation",
    covers=("E5.3", "eq5.72"),
    statement="at θ = 0, L3 = L_z and E' = 0; Φ_eff(θ) ≈ (L3²/(8J'1) − mgℓ/2) θ² (5.72): a "
    "minimum, so stable, when L3² > 4J'1 mgℓ",
)
def example_5_3(d: Derivation) -> None:
    J1p, L3 = sp.symbols("J_1p L_3", positive=True)
    th = sp.Symbol("theta", real=True)
    from identities.book.ch05.symmetric_top import J_1p
    from identities.book.ch05.symmetric_top import ell as ell_s
    from identities.book.ch05.symmetric_top import g as g_s
    from identities.book.ch05.symmetric_top import m as m_s

    pe = phi_eff(th, L3, L3).subs({J_1p: J1p, m_s: m, g_s: g, ell_s: ell})
    ser = sp.series(pe, th, 0, 3).removeO()
    d.prove_equal(
        ser, (L3**2 / (8 * J1p) - m * g * ell / 2) * th**2, strategy="cancel", claim="(5.72)"
    )
    d.reject(
        ser,
        (L3**2 / (4 * J1p) - m * g * ell / 2) * th**2,
        strategy="cancel",
        claim="(5.72) with L3²/(4J'1)",
    )
    from identities.book.ch05.symmetric_top import J_3, L_3_of_rates, L_z_of_rates, energy_of_rates
    from identities.book.ch05.symmetric_top import theta as th_f

    at_zero = {th_f: 0}
    d.prove_equal(
        L_z_of_rates().subs(at_zero), L_3_of_rates().subs(at_zero), claim="L_z = L3 at θ = 0"
    )
    Ep = energy_of_rates() - L_3_of_rates() ** 2 / (2 * J_3) - m_s * g_s * ell_s
    d.prove_zero(Ep.subs(sp.diff(th_f, t), 0).subs(at_zero), claim="E' = 0 at θ = 0 with θ̇ = 0")
    # numeric: just above / below the threshold, the exact motion started at θ = 1e-3
    J1n, mgl = 1.0, 1.0
    for factor, stable in ((1.2, True), (0.8, False)):
        L3n = factor * np.sqrt(4 * J1n * mgl)
        top = tops.HeavySymmetricTop(J1n, 0.5, mgl, theta=1e-3, phi_dot=L3n / 0.5)
        th_max = float(np.arccos(top.roots[0]))
        d.confirm(
            [th_max < SLEEPING_BOUND, tops.sleeping_top_is_stable(J1n, L3n, mgl)],
            [stable, stable],
            atol=0,
            route=f"L3 = {factor}·√(4J'1 mgℓ): the exact mechanics.tops.HeavySymmetricTop "
            f"started at θ = 1e-3 nutates to θ_max = {th_max:.3g} (bounded iff stable), and "
            "sleeping_top_is_stable agrees",
        )


# ----------------------------------------------------------------------------- Example 5.4
@check(
    "E5.4",
    "Example 5.4: the force at the ring on a rotating bicycle-wheel axis",
    kind="derivation",
    covers=("E5.4", *(f"eq5.{n}" for n in range(78, 85))),
    statement="Ω = Ω e^B_2 (5.78); (5.77) gives JΩφ̇ = M1, 0 = M2, Jφ̈ = M3 (5.79); "
    "M = OB × (−mg e^B_2) + OA × F (5.80), F = F1 e^B_1 + F2 e^B_2 (5.81) → "
    "M = (mgℓ − F2 d) e^B_1 + F1 d e^B_2 (5.82); (5.83); F = (mgℓ − JΩφ̇)/d e^B_2 (5.84)",
)
def example_5_4(d: Derivation) -> None:
    Om, F1, F2 = sp.symbols("Omega F_1 F_2", real=True)
    phi = functions_of_time("phi")[0]
    fd = sp.diff(phi, t)
    J1p = J / 2 + m * ell**2  # thin wheel, about O
    Ov = vec(0, Om, 0)  # (5.78)
    L_B = sp.diag(J1p, J1p, J) * (Ov + vec(0, 0, fd))
    Mreq = sp.diff(L_B, t) + cross(Ov, L_B)  # (5.77) with constant Ω
    d.prove_equal(Mreq, vec(J * Om * fd, 0, J * sp.diff(phi, t, 2)), claim="(5.79)")
    F = vec(F1, F2, 0)  # (5.81)
    M = cross(ell * vec(0, 0, 1), -m * g * vec(0, 1, 0)) + cross(d_ * vec(0, 0, 1), F)  # (5.80)
    d.prove_equal(M, vec(m * g * ell - F2 * d_, F1 * d_, 0), claim="(5.82)")
    sol = sp.solve(list(Mreq.subs(sp.diff(phi, t, 2), 0) - M)[:2], [F1, F2], dict=True)[0]
    printed = (m * g * ell - J * Om * fd) / d_
    d.quantity("F_2", sol[F2])
    d.prove_equal(vec(sol[F1], sol[F2]), vec(0, printed), strategy="cancel", claim="(5.83)-(5.84)")
    d.reject(sol[F2], (m * g * ell + J * Om * fd) / d_, strategy="cancel", claim="(5.84) with +JΩφ̇")
    # second route: L about O in the space frame, differentiated in time
    u_r = vec(sp.cos(Om * t), sp.sin(Om * t), 0)  # e^B_3 (along OB), horizontal, turning
    u_z = vec(0, 0, 1)  # e^B_2 (vertical)
    u_t = cross(u_z, u_r)  # e^B_1 = e^B_2 × e^B_3
    w_s = Om * u_z + fd * u_r
    L_O = J1p * Om * u_z + J * fd * u_r
    d.prove_equal(
        L_O,
        J1p * (w_s - (w_s.T * u_r)[0, 0] * u_r) + J * (w_s.T * u_r)[0, 0] * u_r,
        strategy="trigsimp",
        claim="L_O = J'1 ω⊥ + J ω∥ in space components",
    )
    Fs = F1 * u_t + F2 * u_z
    Ms = cross(ell * u_r, -m * g * u_z) + cross(d_ * u_r, Fs)
    bal = (sp.diff(L_O, t) - Ms).subs(sp.diff(phi, t, 2), 0)
    sol2 = sp.solve(
        [sp.trigsimp(bal.dot(u_t)), sp.trigsimp(bal.dot(cross(u_r, u_t)))], [F1, F2], dict=True
    )[0]
    d.confirm_exact(
        sol2[F2], printed, route="dL_O/dt in the space frame (no Resal frame)", strategy="cancel"
    )
