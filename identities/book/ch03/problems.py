"""Chapter 3 problems 3.1–3.6, derived symbolically in the book's symbols and each
confirmed by an independent route: a numeric sum over mass elements through
:mod:`mechanics`, a second derivation (momentum principles against the energy
balance), a scipy simulation of the equations of motion, a limit.  The book's
answers are withheld; these are derived here.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from identities.book.ch02.problems import roller_pyramid
from identities.book.ch03.examples import _cylinder_moment, _disc_moment
from identities.book.ch03.power import EPS, ODE_RTOL
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, vec
from mechanics import energy as en
from mechanics import kinematics as kin
from mechanics import particles as pt

#: closed forms and mechanics evaluated at O(1)–O(1e4) values: 2^8 eps relative.
NUM_RTOL = 2**8 * EPS
#: a quantity read off a DOP853 solution at ODE_RTOL ≈ 1.5e-11: 2^24 eps ≈ 3.7e-9 relative.
SIM_RTOL = 2**24 * EPS

HALF = sp.Rational(1, 2)
ez = vec(0, 0, 1)


def _disc_elements(r: float, n_r: int = 200, n_a: int = 128):
    """Mass fractions and positions (relative to the centre) of a uniform disc, midpoint grid."""
    s = (np.arange(n_r) + 0.5) / n_r * r
    a = 2 * np.pi * np.arange(n_a) / n_a
    S, A = np.meshgrid(s, a, indexing="ij")
    frac = (S * (r / n_r) * (2 * np.pi / n_a) / (np.pi * r**2)).ravel()
    pos = np.stack([S * np.cos(A), S * np.sin(A), 0 * S], axis=-1).reshape(-1, 3)
    return frac, pos


#: the midpoint rule in the radius integrates s³ with relative error 1/(4 n_r²) (the angular
#: sums are exact for these trigonometric polynomials): 1/n_r² with n_r = 200 bounds it.
GRID_RTOL = 1.0 / 200**2


@check(
    "P3.1",
    "Problem 3.1: kinetic energy of the rolling and sliding disc of Problem 2.3",
    kind="derivation",
    covers=("P3.1",),
    statement="top point speed v_1, geometric contact point (and centre) speed v_2: "
    "T = ½ m v_2² + ¼ m (v_1 - v_2)²",
)
def problem_3_1(d: Derivation) -> None:
    m, r = sp.symbols("m r", positive=True)
    v1, v2 = sp.symbols("v_1 v_2", real=True)
    wz = sp.Symbol("omega_z", real=True)
    vG = vec(v2, 0, 0)  # x along the motion, y up: the centre moves with the contact point
    top = vG + cross(wz * ez, vec(0, r, 0))
    omega = d.quantity("omega_z", sp.solve(top[0] - v1, wz)[0])
    J_G = _disc_moment(m, r)
    d.prove_equal(J_G, m * r**2 / 2, strategy="expand", claim="J_G = ½ m r² by integration")
    T = d.quantity("T", HALF * m * v2**2 + HALF * J_G * omega**2)  # König (3.7), (3.26)
    d.prove_equal(
        T,
        HALF * m * v2**2 + m * (v1 - v2) ** 2 / 4,
        strategy="expand",
        claim="T = ½ m v_2² + ¼ m (v_1 - v_2)²",
    )
    d.reject(
        T,
        HALF * m * v2**2 + m * (v1 - v2) ** 2 / 2,
        strategy="expand",
        claim="the disc taken as a ring (J_G = m r²)",
    )
    # second derivation: pure rotation about the instantaneous centre (plane motion)
    dist = v2 / omega  # the centre of zero velocity lies below G at this distance (signed)
    J_C = J_G + m * dist**2  # parallel axes (3.32)
    d.confirm_exact(
        HALF * J_C * omega**2,
        T,
        strategy="cancel",
        route="½ J_C ω² about the instantaneous centre of zero velocity",
    )
    d.confirm_exact(
        T.subs(v1, 2 * v2),
        sp.Rational(3, 4) * m * v2**2,
        route="limit: pure rolling (v_1 = 2 v_2) gives T = ¾ m v_2²",
    )
    mn, rn, v1n, v2n = 2.0, 0.5, 3.0, 1.2
    frac, pos = _disc_elements(rn)
    vel = kin.point_velocity([v2n, 0.0, 0.0], [0.0, 0.0, (v2n - v1n) / rn], pos)
    T_num = pt.kinetic_energy(mn * frac, vel)
    T_exact = float(T.subs({m: mn, r: rn, v1: v1n, v2: v2n}))
    d.confirm(
        T_num / T_exact,
        1.0,
        atol=GRID_RTOL,
        route="mechanics.particles.kinetic_energy over 25600 mass elements of the disc",
    )


@check(
    "P3.2",
    "Problem 3.2: kinetic energy of the pyramid of six rollers",
    kind="derivation",
    covers=("P3.2",),
    statement="six rollers (m, r) of Problem 2.5, centres moving with speed v, rolling on the floor "
    "and on each other: T = (9/2) m v², (a) by König's theorem, (b) by the instantaneous centres",
    reading="the rods are massless; 'each roller has speed v' is the speed of its axis (the "
    "frame translates); (b) applies the centre of zero velocity to each roller's plane motion",
)
def problem_3_2(d: Derivation) -> None:
    m, r, v = sp.symbols("m r v", positive=True)
    _, _, omegas = roller_pyramid(r, v)  # the rollers of Problem 2.5
    vc = vec(v, 0, 0)  # the frame translates
    J_G = _cylinder_moment(m, r)
    d.prove_equal(J_G, m * r**2 / 2, strategy="expand", claim="J_G = ½ m r² by integration")
    T_a = d.quantity(
        "T_a", 6 * HALF * m * v**2 + sum(HALF * J_G * om**2 for om in omegas.values())
    )  # (3.7): ½ (6m) v² + Σ T′
    d.prove_equal(T_a, sp.Rational(9, 2) * m * v**2, strategy="expand", claim="(a) T = (9/2) m v²")
    T_b = sp.S.Zero
    for om in omegas.values():
        ic = cross(om * ez, vc) / om**2  # from the axis to the centre of zero velocity (2.77)
        T_b += HALF * (J_G + m * ic.dot(ic)) * om**2  # ½ J_C ω², parallel axes
    T_b = d.quantity("T_b", T_b)
    d.confirm_exact(T_b, T_a, strategy="cancel", route="(b) Σ ½ J_C ω² about each roller's centre")
    d.quantity("T", sp.Rational(9, 2) * m * v**2)
    d.reject(T_a, 3 * m * v**2, strategy="expand", claim="T = ½ (6m) v² (the rotation forgotten)")
    # numeric: every roller as 25600 mass elements, velocities v_G + ω × r′
    rn, vn, mn = 0.4, 1.5, 2.0
    frac, pos = _disc_elements(rn)
    T_num = sum(
        pt.kinetic_energy(
            mn * frac, kin.point_velocity([vn, 0, 0], [0, 0, float(om.subs({v: vn, r: rn}))], pos)
        )
        for om in omegas.values()
    )
    d.confirm(
        T_num / (4.5 * mn * vn**2),
        1.0,
        atol=GRID_RTOL,
        route="mechanics.particles.kinetic_energy summed over the six discretised rollers",
    )


@check(
    "P3.3",
    "Problem 3.3: braking distance of a steam roller with water- or ice-filled wheels",
    kind="derivation",
    covers=("P3.3",),
    statement="the chock's sliding friction μF does work -μF s (the rim slides past it by the "
    "distance rolled); the ground's static friction and normal forces do none (3.2.2). Empty: "
    "½ M v² = μ F s_0 fixes the effective mass M (frame + shells, rotation included). Liquid "
    "water (mass n m_w, not rotating) adds ½ n m_w v²; the same water frozen (mass n m_w, "
    "turning with the wheels, J = ½ m_w R²) adds ¾ n m_w v², so the ice's rotational energy "
    "½ J ω² = ¼ m_w v² must also be taken by the brake",
    reading="b) is the water of a), frozen: the problem fills the wheels 'with water when the "
    "steam roller is to be used' and then asks for a) liquid water and b) ice, so the mass in "
    "the wheels is the same and the density change on freezing (about 9 %) is neglected; what "
    "changes is that the ice turns with the wheel.  The other reading, the wheels' volume "
    "filled with ice of density 917 kg/m³, is kept below as a labelled variant; the text "
    "gives no density for ice, which supports the first.  Two wheels (front and rear roller) "
    "of diameter 1 m and width 2 m (figure 3.3 is lost); the liquid does not turn with the "
    "shell during the short braking (no friction against the wall), the ice does; "
    "ρ_water = 1000 kg/m³; g = 9.81 m/s²; v = 5 km/h",
)
def problem_3_3(d: Derivation) -> None:
    s0, v, F, mu, D, b, rho_w, rho_i, g = sp.symbols("s_0 v F mu D b rho_w rho_i g", positive=True)
    n = 2
    R = D / 2
    M = 2 * mu * F * s0 / v**2  # empty roller: ½ M v² = μ F s_0
    m_w, m_i = rho_w * sp.pi * R**2 * b, rho_i * sp.pi * R**2 * b

    def distance(m_add, turns: bool):
        """Braking distance with n wheels each holding mass m_add, turning with the wheel
        (a solid cylinder, J = ½ m R², ω = v/R) or not (a liquid)."""
        T_add = HALF * m_add * v**2 + (HALF * HALF * m_add * R**2 * (v / R) ** 2 if turns else 0)
        return sp.expand((HALF * M * v**2 + n * T_add) / (mu * F))

    s_a = d.quantity("s_a", distance(m_w, turns=False))
    s_b = d.quantity("s_b", distance(m_w, turns=True))
    d.prove_equal(
        s_a,
        s0 + n * rho_w * sp.pi * D**2 * b * v**2 / (8 * mu * F),
        strategy="expand",
        claim="(a) s_a = s_0 + n ρ_w π D² b v² / (8 μ F)",
    )
    d.prove_equal(
        s_b,
        s0 + 3 * n * rho_w * sp.pi * D**2 * b * v**2 / (16 * mu * F),
        strategy="expand",
        claim="(b) the same water frozen: s_b = s_0 + 3 n ρ_w π D² b v² / (16 μ F)",
    )
    d.prove_equal(
        (s_b - s0) / (s_a - s0),
        sp.Rational(3, 2),
        strategy="cancel",
        claim="freezing adds half again to the extra distance: the ice's ½ J ω² = ¼ m_w v² "
        "on top of its ½ m_w v²",
    )
    d.reject(
        s_a,
        s0 + 3 * n * rho_w * sp.pi * D**2 * b * v**2 / (16 * mu * F),
        strategy="expand",
        claim="the liquid turning with the wheel like the ice",
    )
    d.reject(
        s_b,
        s_a,
        strategy="expand",
        claim="the ice sliding inside the wheel like the liquid (its rotation forgotten)",
    )
    d.note(
        "variant, not the book's reading: if the wheels' volume is filled with ice of density "
        "ρ_i = 917 kg/m³ (mass n m_i, m_i = ρ_i π R² b), the frozen wheel carries less mass"
    )
    s_b_variant = d.quantity("s_b_variant_ice_917", distance(m_i, turns=True))
    d.prove_equal(
        s_b_variant,
        s0 + 3 * n * rho_i * sp.pi * D**2 * b * v**2 / (16 * mu * F),
        strategy="expand",
        claim="variant: s_b' = s_0 + 3 n ρ_i π D² b v² / (16 μ F)",
    )
    d.prove_equal(
        (s_b_variant - s0) / (s_b - s0),
        rho_i / rho_w,
        strategy="cancel",
        claim="the two readings of b) differ only in the ice's mass: their extra distances "
        "are in the ratio ρ_i/ρ_w",
    )
    data = {
        s0: 2,
        v: sp.Rational(5000, 3600),
        mu: sp.Rational(4, 5),
        D: 1,
        b: 2,
        g: sp.Rational(981, 100),
        rho_w: 1000,
        rho_i: 917,
    }
    data[F] = 125 * data[g]
    d.quantity("s_a_metres", sp.N(s_a.subs(data), 6))
    d.quantity("s_b_metres", sp.N(s_b.subs(data), 6))
    d.quantity("s_b_variant_ice_917_metres", sp.N(s_b_variant.subs(data), 6))
    # second derivation: momentum principle for the whole roller, angular momentum for each
    # wheel about its axle, rolling constraint ẍ = R φ̈; the split of M into frame and shells
    # (J_shell = m_s R²) is arbitrary and must not matter
    xdd, f1, f2, Mf, ms = sp.symbols("xddot f_1 f_2 M_f m_s", real=True)
    for name, m_add, J_add, derived in (
        ("liquid", m_w, 0, s_a),
        ("the same water frozen", m_w, HALF * m_w * R**2, s_b),
        ("variant: ice of 917 kg/m³", m_i, HALF * m_i * R**2, s_b_variant),
    ):
        J = ms * R**2 + J_add
        M_tot = Mf + n * ms + n * m_add
        eqs = [M_tot * xdd - f1 - f2, J * xdd / R + f1 * R + mu * F * R, J * xdd / R + f2 * R]
        a = sp.solve(eqs, [xdd, f1, f2], dict=True)[0][xdd].subs(Mf, M - 2 * n * ms)
        dist = -(v**2) / (2 * a)  # uniform deceleration from v to rest
        d.confirm_exact(
            dist,
            derived,
            strategy="cancel",
            route=f"Newton–Euler ({name}): the frame/shell split m_s drops out, same distance",
        )
        # simulation of the braking with a chosen split, to the stop
        sub = {**data, ms: 150}
        acc = float(a.subs(sub))

        def rhs(_, s, acc=acc):
            return [s[1], acc]

        def stopped(_, s):
            return s[1]

        stopped.terminal = True
        sim = solve_ivp(
            rhs,
            (0, 100),
            [0.0, float(data[v])],
            method="DOP853",
            rtol=ODE_RTOL,
            atol=ODE_RTOL,
            events=stopped,
        )
        d.confirm(
            sim.y_events[0][0][0] / float(derived.subs(data)),
            1.0,
            atol=SIM_RTOL,
            route=f"scipy simulation ({name}, m_s = 150 kg): distance to rest",
        )


@check(
    "P3.4",
    "Problem 3.4: engine power against torque; the two maxima differ",
    kind="derivation",
    covers=("P3.4",),
    statement="P(n) = M(n) ω = 2π n M(n); dP/dn = 2π (M + n M′), at n_max (M′ = 0) "
    "dP/dn = 2π M(n_max) > 0, so the power still grows where the torque is largest",
)
def problem_3_4(d: Derivation) -> None:
    n = sp.Symbol("n", positive=True)
    Mf = sp.Function("M")
    P = d.quantity("P", 2 * sp.pi * n * Mf(n))  # (3.70) per unit time: P = M_z φ̇, φ̇ = 2π n
    dP = sp.diff(P, n)
    d.prove_equal(
        dP,
        2 * sp.pi * (Mf(n) + n * sp.diff(Mf(n), n)),
        strategy="expand",
        claim="dP/dn = 2π (M + n dM/dn)",
    )
    nmax = sp.Symbol("n_max", positive=True)
    at = dP.subs(n, nmax).subs(sp.Subs(sp.Derivative(Mf(n), n), n, nmax), 0)
    at = at.subs(sp.Derivative(Mf(nmax), nmax), 0)
    d.quantity("dP_dn_at_nmax", at)
    d.prove_equal(
        at,
        2 * sp.pi * Mf(nmax),
        strategy="expand",
        claim="at the torque maximum dP/dn = 2π M(n_max) > 0 for a driving torque: not P's maximum",
    )
    d.reject(at, 0, strategy="expand", claim="dP/dn = 0 at n_max")
    d.note("at the power maximum dM/dn = -M/n < 0: the torque is already falling, n_P > n_max")
    # a model torque curve: a parabola with its top at n_max
    Mm, nm, w = sp.symbols("M_max n_m Delta", positive=True)
    Mpar = Mm * (1 - ((n - nm) / w) ** 2)
    Ppar = n * Mpar
    pt_ = {nm: 50, w: 40, Mm: 1}
    roots = [
        x for x in sp.solve(sp.diff(Ppar, n), n) if sp.diff(Ppar, n, 2).subs(n, x).subs(pt_) < 0
    ]
    nP = d.quantity("n_P_parabola", roots[0])
    d.confirm_exact(
        nP,
        (2 * nm + sp.sqrt(nm**2 + 3 * w**2)) / 3,
        strategy="expand",
        route="parabolic torque curve: n_P = (2 n_m + √(n_m² + 3Δ²))/3 > n_m",
    )
    nn = np.linspace(1.0, 90.0, 89001)
    Mn = 250.0 * (1 - ((nn - 50.0) / 40.0) ** 2)
    zeros = np.zeros((nn.size, 3))
    Pn = en.rigid_body_power(
        zeros, Mn[:, None] * [0, 0, 1], zeros, (2 * np.pi * nn)[:, None] * [0, 0, 1]
    )
    i = int(np.argmax(Pn))
    d.confirm(
        nn[i],
        float(nP.subs({nm: 50, w: 40})),
        atol=nn[1] - nn[0],  # grid spacing
        route="mechanics.energy.rigid_body_power (a couple: P = M · ω) maximised on a grid",
    )
    d.confirm(
        nn[i] > 50.0 + 10 * (nn[1] - nn[0]),
        True,
        atol=0,
        route="the power maximum lies well above the torque maximum n_max = 50",
    )


@check(
    "P3.5",
    "Problem 3.5: a friction clutch engaging",
    kind="derivation",
    covers=("P3.5",),
    statement="the friction moment is internal to the two parts: J ω = 2 J ω_f, ω_f = ω/2; "
    "heat Q = ½ J ω² - ½ (2J) ω_f² = ¼ J ω²; with uniform pressure over the annulus "
    "M_f = (2/3) f P (R³ - r³)/(R² - r²) and the slip lasts J ω / (2 M_f)",
)
def problem_3_5(d: Derivation) -> None:
    J, w, P, f, r, R = sp.symbols("J omega P f r R", positive=True)
    wf = sp.Symbol("omega_f", real=True)
    w_f = d.quantity("omega_f", sp.solve(J * w - 2 * J * wf, wf)[0])
    d.prove_equal(w_f, w / 2, strategy="expand", claim="(a) ω_f = ω/2")
    Q = d.quantity("Q", HALF * J * w**2 - HALF * (2 * J) * w_f**2)
    d.prove_equal(Q, J * w**2 / 4, strategy="expand", claim="(b) Q = ¼ J ω²")
    d.reject(Q, 0, strategy="expand", claim="no heat: kinetic energy conserved")
    rho, a = sp.symbols("rho a", positive=True)
    p = P / (sp.pi * (R**2 - r**2))
    Mfr = d.quantity(
        "M_f", sp.integrate(sp.integrate(f * p * rho * rho, (rho, r, R)), (a, 0, 2 * sp.pi))
    )
    d.prove_equal(
        Mfr,
        sp.Rational(2, 3) * f * P * (R**3 - r**3) / (R**2 - r**2),
        strategy="cancel",
        claim="friction moment M_f = ∫ ρ f p dA over the annulus",
    )
    ts = d.quantity("t_slip", J * w / (2 * Mfr))
    d.confirm_exact(
        Mfr * (w / 2) * ts,  # heat = M_f × mean relative rate ω/2 × slip time
        Q,
        strategy="cancel",
        route="second derivation: heat = friction moment × relative turn ∫ (ω_1 - ω_2) dt",
    )
    Jn, wn, Pn, fn, rn, Rn = 0.2, 150.0, 800.0, 0.35, 0.05, 0.12
    Mn = float(Mfr.subs({P: Pn, f: fn, r: rn, R: Rn}))

    def rhs(_, s):  # ω_1, ω_2, heat
        return [-Mn / Jn, Mn / Jn, Mn * (s[0] - s[1])]

    def locked(_, s):
        return s[0] - s[1]

    locked.terminal = True
    sim = solve_ivp(
        rhs, (0, 100), [wn, 0.0, 0.0], method="DOP853", rtol=ODE_RTOL, atol=ODE_RTOL, events=locked
    )
    w1, w2, heat = sim.y_events[0][0]
    d.confirm(
        [w1 / (wn / 2), w2 / (wn / 2), heat / (Jn * wn**2 / 4)],
        [1.0, 1.0, 1.0],
        atol=SIM_RTOL,
        route="scipy simulation of J ω̇_i = ∓M_f to lock-up, heat = ∫ M_f (ω_1 - ω_2) dt",
    )


@check(
    "P3.6",
    "Problem 3.6: two discs on a bar, friction in one bearing",
    kind="derivation",
    covers=("P3.6",),
    statement="L_C is conserved (C fixed, bearings B and C smooth): initially 0; finally disc A "
    "turns with the bar (Ω), disc B keeps -ω; Ω = R² ω/(R² + ℓ²) and the heat in A is "
    "Q = ¼ m R² ω² ℓ²/(R² + ℓ²)",
    reading="the bar is light; disc A spins +ω, disc B -ω about their own axes at first; the "
    "friction at A acts between disc A and the bar only",
)
def problem_3_6(d: Derivation) -> None:
    m, R, ell, w = sp.symbols("m R ell omega", positive=True)
    Om = sp.Symbol("Omega", real=True)
    J = _disc_moment(m, R)
    d.prove_equal(J, m * R**2 / 2, strategy="expand", claim="J = ½ m R² by integration")
    arm = m * (ell / 2) ** 2  # each centre at ℓ/2 from C
    L0 = J * w + J * (-w)  # bar at rest
    L1 = (J * Om + arm * Om) + (J * (-w) + arm * Om)  # A locked to the bar, B still at -ω
    Omega = d.quantity("Omega", sp.solve(L1 - L0, Om)[0])
    d.prove_equal(Omega, R**2 * w / (R**2 + ell**2), strategy="cancel", claim="Ω = R² ω/(R² + ℓ²)")
    T0 = 2 * HALF * J * w**2
    T1 = HALF * J * Omega**2 + HALF * J * w**2 + 2 * HALF * arm * Omega**2
    Q = d.quantity("Q", sp.factor(T0 - T1))
    d.prove_equal(
        Q,
        m * R**2 * w**2 * ell**2 / (4 * (R**2 + ell**2)),
        strategy="cancel",
        claim="Q = ¼ m R² ω² ℓ²/(R² + ℓ²)",
    )
    d.reject(Q, m * R**2 * w**2 / 4, strategy="cancel", claim="disc A simply stops: Q = ½ J ω²")
    d.confirm_exact(
        sp.limit(Q, ell, sp.oo),
        HALF * J * w**2,
        route="limit ℓ → ∞: the bar cannot turn, disc A loses all its spin energy ½ J ω²",
    )
    d.confirm_exact(sp.limit(Q, ell, 0), 0, route="limit ℓ → 0: no heat")
    # simulation: Lagrange in (θ bar, φ_A, φ_B) with a viscous bearing at A
    mn, Rn, elln, wn, c = 1.5, 0.2, 0.6, 30.0, 0.1
    Jn, An = 0.5 * mn * Rn**2, mn * (elln / 2) ** 2

    def rhs(_, s):  # θ̇, φ̇_A, φ̇_B, heat
        tau = c * (s[1] - s[0])  # friction moment on disc A (minus), on the bar (plus)
        return [tau / (2 * An), -tau / Jn, 0.0, tau * (s[1] - s[0])]

    sim = solve_ivp(
        rhs, (0, 60.0), [0.0, wn, -wn, 0.0], method="DOP853", rtol=ODE_RTOL, atol=ODE_RTOL
    )
    th_d, phA_d, phB_d, heat = sim.y[:, -1]
    sub = {m: mn, R: Rn, ell: elln, w: wn}
    d.confirm(
        [th_d / float(Omega.subs(sub)), phA_d / float(Omega.subs(sub)), heat / float(Q.subs(sub))],
        [1.0, 1.0, 1.0],
        atol=SIM_RTOL,
        route="scipy simulation with a viscous bearing at A until the slip has died out "
        "(the slip decays as exp(-c (1/J + 1/(2 m (ℓ/2)²)) t), e^-220 at t = 60)",
    )
    L_end = Jn * phA_d + Jn * phB_d + 2 * An * th_d
    d.confirm(L_end / (Jn * wn), 0.0, atol=SIM_RTOL, route="L_C stays 0 in the simulation")
