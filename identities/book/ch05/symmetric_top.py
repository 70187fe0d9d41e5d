"""Chapter 5.2: the symmetric top, free (5.2.1) and heavy (5.2.2–5.2.5), and the Resal frame.

Everything is built from the Euler-angle definitions: ^A R^O = R3(φ) R1(θ) R3(ψ) (2.35)
with ψ(t), θ(t), φ(t) undefined functions of time, the frame B of figures 5.2–5.3 is
^B R^O = R1(θ) R3(ψ), and angular velocities are read off Ṙ Rᵀ (2.46), (2.52).  The
kinetic energy ½ ωᵀ J ω and the Lagrangian follow from these; the book's equations of
motion (5.50)–(5.52) are compared with the Euler–Lagrange equations (a second route) and
integrated with scipy against the exact elliptic motion of
:class:`mechanics.tops.HeavySymmetricTop`.

Book symbols: J'1 → ``J_1p`` (the transverse moment about the fixed point C),
ℓ → ``ell``, L_z, L_3, E, E' → ``L_z``, ``L_3``, ``E``, ``E_p``, Ω → ``Omega``.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import (
    R1,
    R3,
    cross,
    euler_matrix,
    floats,
    functions_of_time,
    omega_vector,
    t,
    vec,
)
from mechanics import inertia as inr
from mechanics import tops
from mechanics._floats import EPS

#: float evaluation of a few products and quotients of O(1) numbers: 64 eps.
CODE_ATOL = 64 * EPS
#: scipy DOP853 at rtol = atol = 1e-12 over a few periods of O(1) motion: global error
#: measured ≤ 3e-11; 2^22 eps ≈ 9.3e-10 leaves a margin and still rejects an O(1e-3) error.
SIM_ATOL = 2**22 * EPS
#: the exact heavy-top motion (elliptic functions, third-kind integrals) conserves its
#: integrals to a few hundred ulps of E (mechanics.tops accuracy claim): 1024 eps relative.
EXACT_RTOL = 1024 * EPS
#: steady precession is a double root of the cubic: a rounding δ ~ eps in its coefficients
#: splits it by O(√δ), so θ(t) may wobble by ~1e-8; 2^-24 ≈ 6e-8 (still rejects a real
#: nutation, which is O(Ω²) ~ 1e-2 here).
STEADY_ATOL = 2.0**-24

psi, theta, phi = functions_of_time("psi", "theta", "phi")
pd, td, fd = (sp.diff(x, t) for x in (psi, theta, phi))
J_1, J_3, J_1p, m, g, ell, L = sp.symbols("J_1 J_3 J_1p m g ell L", positive=True)
L_3, L_z, Omega = sp.symbols("L_3 L_z Omega", real=True)
s, c = sp.sin(theta), sp.cos(theta)


def R_B_O() -> sp.Matrix:
    """^B R^O = R1(θ) R3(ψ): the frame B of figures 5.2-5.3 (A without the spin φ)."""
    return R1(theta) * R3(psi)


def omega_A_in_B_raw() -> sp.Matrix:
    """^Oω^A in B components, unsimplified, from ^A R^O (2.35) by (2.46): ω_B = ^B R^A ω_A."""
    R = euler_matrix(psi, theta, phi)
    return R3(phi).T * omega_vector(sp.diff(R, t) * R.T)


def omega_B_in_B_raw() -> sp.Matrix:
    """^Oω^B in B components, unsimplified, read off d/dt ^B R^O (2.46)."""
    R = R_B_O()
    return omega_vector(sp.diff(R, t) * R.T)


def book_omega() -> sp.Matrix:
    """(5.30): ω = θ̇ e^B_1 + ψ̇ sin θ e^B_2 + (ψ̇ cos θ + φ̇) e^B_3 (proved in eq5.30 from
    the Euler matrix; the other checks build on it)."""
    return vec(td, pd * s, pd * c + fd)


def heavy_L_B() -> sp.Matrix:
    """(5.48): L = J'1(θ̇ e1 + ψ̇ sin θ e2) + J3(ψ̇ cos θ + φ̇) e3 (B components)."""
    return sp.diag(J_1p, J_1p, J_3) * book_omega()


def heavy_eom_printed() -> sp.Matrix:
    """LHS − RHS of the printed (5.50)-(5.52)."""
    return vec(
        sp.diff(J_1p * td, t)
        + ((J_3 - J_1p) * pd**2 * s * c + J_3 * pd * fd * s)
        - m * g * ell * s,
        sp.diff(J_1p * pd * s, t) - ((J_3 - J_1p) * pd * td * c + J_3 * td * fd),
        sp.diff(J_3 * (pd * c + fd), t),
    )


def heavy_lagrangian():
    """T − V with T = ½ ωᵀ J_C ω, ω from the Euler matrix, V = m g ℓ cos θ."""
    w = book_omega()
    T = sp.Rational(1, 2) * (w.T * sp.diag(J_1p, J_1p, J_3) * w)[0, 0]
    return T - m * g * ell * c


# ----------------------------------------------------------------------------- 5.28-5.30
@check(
    "eq5.30",
    "Angular velocities of the frame B and of the body in the basis B",
    kind="proof",
    covers=("eq5.28", "eq5.29", "eq5.30"),
    statement="^Bω^A = φ̇ e^B_3 (5.28), ^Oω^B = θ̇ e^B_1 + ψ̇(sin θ e^B_2 + cos θ e^B_3) (5.29), "
    "ω = θ̇ e^B_1 + ψ̇ sin θ e^B_2 + (ψ̇ cos θ + φ̇) e^B_3 (5.30)",
)
def symmetric_top_omega(d: Derivation) -> None:
    R_BA = R3(phi).T  # ^B R^A: ^A R^B = R3(φ)
    w_BA = omega_vector(sp.diff(R_BA.T, t) * R_BA)  # ω of A relative to B, A components
    d.prove_equal(w_BA, vec(0, 0, fd), strategy="trigsimp", claim="(5.28): ^Bω^A = φ̇ e_3")
    w_OB = vec(td, pd * s, pd * c)
    d.prove_equal(omega_B_in_B_raw(), w_OB, strategy="tan_half", claim="(5.29) from d/dt ^B R^O")
    d.prove_equal(
        R_B_O() * vec(0, 0, 1),
        vec(0, s, c),
        strategy="expand",
        claim="e^O_3 = sin θ e^B_2 + cos θ e^B_3 (second form of 5.29)",
    )
    d.prove_equal(
        omega_A_in_B_raw(),
        book_omega(),
        strategy="tan_half",
        claim="(5.30) from d/dt ^A R^O (2.35)",
    )
    d.prove_equal(
        w_OB + vec(0, 0, fd),
        book_omega(),
        strategy="expand",
        claim="(5.30) = (5.29) + (5.28): additivity of angular velocities",
    )
    d.reject(
        omega_B_in_B_raw() + vec(0, 0, fd),
        vec(td, pd * c, pd * s + fd),
        strategy="tan_half",
        claim="sin θ and cos θ swapped",
    )
    ang, rates = (0.4, 1.1, -0.7), (0.3, -0.8, 2.1)
    sub = dict(zip((psi, theta, phi), ang, strict=True))
    subd = dict(zip((pd, td, fd), rates, strict=True))
    w_A_code = tops_omega_A(*ang, *rates)
    d.confirm(
        floats(R3(phi).T, sub) @ w_A_code[:, None],
        floats(book_omega().subs(subd), sub),
        atol=CODE_ATOL,
        route="mechanics.kinematics Euler rates → ω_A, rotated to B by R3(φ)ᵀ",
    )


def tops_omega_A(psi_, theta_, phi_, psid, thetad, phid) -> np.ndarray:
    from mechanics import kinematics as kin

    return kin.angular_velocity_from_euler_rates(psi_, theta_, phi_, psid, thetad, phid)


# ----------------------------------------------------------------------------- 5.31-5.35
@check(
    "eq5.34",
    "The free symmetric top: constant nutation, precession L/J1, spin L cos θ0 (J1−J3)/(J1 J3)",
    kind="proof",
    covers=("eq5.31", "eq5.32", "eq5.33", "eq5.34", "eq5.35"),
    statement="L_B = w_B J_B (5.31) with L = L e^O_3, L_B = (0, L sin θ, L cos θ) (5.32) gives "
    "(5.33); ψ̇ = L/J1 (5.34), φ̇ = (L/J1) cos θ0 (J1 − J3)/J3 (5.35)",
)
def free_symmetric_top(d: Derivation) -> None:
    L_B = sp.diag(J_1, J_1, J_3) * book_omega()  # (5.31), ω from (5.30)
    d.prove_equal(R_B_O() * vec(0, 0, L), vec(0, L * s, L * c), strategy="expand", claim="(5.32)")
    eqs = vec(0, L * s, L * c) - L_B
    d.prove_equal(
        eqs,
        vec(-J_1 * td, L * s - J_1 * pd * s, L * c - J_3 * (pd * c + fd)),
        strategy="expand",
        claim="(5.33): the components of L_B = w_B J_B",
    )
    th0 = sp.Symbol("theta_0", positive=True)
    psid = L / J_1
    phid = L / J_1 * sp.cos(th0) * (J_1 - J_3) / J_3
    sol = {theta: th0, td: 0, pd: psid, fd: phid}
    d.quantity("psi_dot", psid)
    d.quantity("phi_dot", phid)
    d.prove_zero(eqs.subs(sol), strategy="cancel", claim="(5.34), (5.35) with θ = θ0 solve (5.33)")
    d.reject(
        eqs.subs({**sol, fd: L / J_1 * sp.cos(th0) * (J_3 - J_1) / J_3}),
        sp.zeros(3, 1),
        strategy="cancel",
        claim="(5.35) with (J3 − J1) in place of (J1 − J3)",
    )
    # second route: φ̇ = −β of Example 5.2 (body-frame rate), since L cos θ0 = J3 ω3
    w3 = sp.Symbol("omega_3", real=True)
    d.confirm_exact(
        phid.subs(sp.cos(th0), J_3 * w3 / L),
        -(J_3 - J_1) / J_1 * w3,
        route="φ̇ = −β (5.40): the spin relative to B is minus the body-frame precession rate",
        strategy="cancel",
    )
    # numeric: integrate the attitude ODE dR/dt = −[ω]× R with ω_A(t) from Euler's equations;
    # the symmetry axis must precess about L at L/J1.
    J1n, J3n, w0 = 2.0, 0.7, np.array([0.6, -0.2, 1.3])
    Jv = np.array([J1n, J1n, J3n])

    def rhs(_t, y):
        w, R = y[:3], y[3:].reshape(3, 3)
        wdot = (
            np.array([(Jv[1] - Jv[2]), (Jv[2] - Jv[0]), (Jv[0] - Jv[1])])
            * np.roll(w, -1)
            * np.roll(w, -2)
        ) / Jv
        W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        return np.concatenate([wdot, (-W @ R).ravel()])

    T = 3.0
    sol_ = solve_ivp(
        rhs,
        (0, T),
        np.concatenate([w0, np.eye(3).ravel()]),
        rtol=1e-12,
        atol=1e-12,
        method="DOP853",
    )
    R_T = sol_.y[3:, -1].reshape(3, 3)
    L_O = Jv * w0  # R(0) = 1
    Lm = float(np.linalg.norm(L_O))
    e3_T = R_T[2]  # body axis 3 in space components: row 3 of ^A R^O
    d.confirm(
        e3_T,
        _rotate(np.array([0, 0, 1.0]), L_O / Lm, Lm / J1n * T),
        atol=SIM_ATOL,
        route="scipy integration of Euler's equations and dR/dt = −[ω]× R: the symmetry axis "
        "turns about L by (L/J1) t (5.34)",
    )
    top = tops.FreeSymmetricTop(J1n, J3n, w0)
    th0n = float(np.arctan2(J1n * np.hypot(w0[0], w0[1]), J3n * w0[2]))
    d.confirm(
        [top.space_precession_rate, top.spin_rate],
        [
            float(psid.subs({L: Lm, J_1: J1n})),
            float(phid.subs({L: Lm, J_1: J1n, J_3: J3n, th0: th0n})),
        ],
        atol=CODE_ATOL,
        route="mechanics.tops.FreeSymmetricTop rates",
    )


def _rotate(v, n, angle):
    """Rodrigues: v turned by ``angle`` about the unit vector n (active)."""
    return v * np.cos(angle) + np.cross(n, v) * np.sin(angle) + n * (n @ v) * (1 - np.cos(angle))


# ----------------------------------------------------------------------------- heavy top
def _state_symbols():
    """Plain symbols for (ψ, θ, φ), their rates and accelerations (for lambdify / solve)."""
    q = sp.symbols("q_psi q_theta q_phi", real=True)
    v = sp.symbols("v_psi v_theta v_phi", real=True)
    a = sp.symbols("a_psi a_theta a_phi", real=True)
    return q, v, a


def _to_state(expr):
    q, v, a = _state_symbols()
    fs = (psi, theta, phi)
    expr = expr.subs({sp.diff(f, t, 2): ai for f, ai in zip(fs, a, strict=True)})
    expr = expr.subs({sp.diff(f, t): vi for f, vi in zip(fs, v, strict=True)})
    return expr.subs(dict(zip(fs, q, strict=True)))


def printed_accelerations():
    """(ψ̈, θ̈, φ̈) solved from the printed (5.50)-(5.52), as sympy expressions of the state."""
    _q, _v, a = _state_symbols()
    sol = sp.solve(list(_to_state(heavy_eom_printed())), a, dict=True)[0]
    return [sp.simplify(sol[ai]) for ai in a]


def simulate_printed_eom(params, y0, times):
    """scipy integration of the printed (5.50)-(5.52); returns (ψ, θ, φ) at ``times``."""
    q, v, _ = _state_symbols()
    acc = sp.lambdify((*q, *v, J_1p, J_3, m, g, ell), printed_accelerations(), "numpy")

    def rhs(_t, y):
        return [y[3], y[4], y[5], *acc(*y, *params)]

    sol = solve_ivp(rhs, (0, times[-1]), y0, t_eval=times, rtol=1e-12, atol=1e-12, method="DOP853")
    return sol.y[:3]


@check(
    "eq5.46",
    "Inertia tensor of the heavy symmetric top about the fixed point C",
    kind="proof",
    covers=("eq5.46",),
    statement="J_C = J_G + diag(mℓ², mℓ², 0) = diag(J1 + mℓ², J1 + mℓ², J3) with R = (0, 0, ℓ)",
)
def heavy_top_inertia(d: Derivation) -> None:
    J_G = sp.diag(J_1, J_1, J_3)
    R = vec(0, 0, ell)
    J_C = J_G + m * ((R.T * R)[0, 0] * sp.eye(3) - R * R.T)  # (4.38)
    d.prove_equal(J_C, sp.diag(J_1 + m * ell**2, J_1 + m * ell**2, J_3), claim="(5.46) from (4.38)")
    d.reject(J_C, sp.diag(J_1 + m * ell**2, J_1 + m * ell**2, J_3 + m * ell**2), claim="J3 shifted")
    sub = {J_1: 0.3, J_3: 0.5, m: 1.7, ell: 0.9}
    d.confirm(
        inr.parallel_axis(floats(J_G, sub), 1.7, [0.0, 0.0, 0.9]),
        floats(J_C, sub),
        atol=CODE_ATOL,
        route="mechanics.inertia.parallel_axis",
    )


@check(
    "eq5.50",
    "Equations of motion of the heavy symmetric top in the frame B",
    kind="proof",
    covers=("eq5.47", "eq5.48", "eq5.49", "eq5.50", "eq5.51", "eq5.52"),
    statement="L̇ = ^B dL/dt + ^Oω^B × L (5.47), L = J'1(θ̇ e1 + ψ̇ sin θ e2) + J3(ψ̇ cos θ + φ̇) e3 "
    "(5.48), M = mgℓ sin θ e^B_1 (5.49) give (5.50)-(5.52)",
)
def heavy_top_eom(d: Derivation) -> None:
    w_OB = vec(td, pd * s, pd * c)  # (5.29), proved in eq5.30
    L_B = heavy_L_B()
    d.prove_equal(
        sp.diag(J_1p, J_1p, J_3) * (w_OB + vec(0, 0, fd)),
        L_B,
        claim="(5.48): L = J_C(^Oω^B + ^Bω^A)",
    )
    CG = vec(0, 0, ell)
    M = cross(CG, -m * g * R_B_O() * vec(0, 0, 1))  # weight −mg e^O_3 acting at G
    d.prove_equal(M, vec(m * g * ell * s, 0, 0), claim="(5.49): M = CG × (−mg e^O_3)")
    Ldot = sp.diff(L_B, t) + cross(w_OB, L_B)  # (5.47) with (2.61)
    d.prove_equal(Ldot - M, heavy_eom_printed(), claim="(5.50)-(5.52) are L̇ − M = 0 in B")
    d.reject(
        Ldot - M,
        heavy_eom_printed() + vec(2 * J_3 * pd * fd * s, 0, 0),
        claim="(5.50) with −J3 ψ̇ φ̇ sin θ",
    )
    # second route: the Euler–Lagrange equations of T − V, T = ½ ωᵀ J_C ω
    Lag = heavy_lagrangian()
    EL = [sp.diff(sp.diff(Lag, sp.diff(x, t)), t) - sp.diff(Lag, x) for x in (theta, psi, phi)]
    pr = heavy_eom_printed()
    d.confirm_exact(
        vec(EL[0], EL[1], EL[2]),
        vec(pr[0], s * pr[1] + c * pr[2], pr[2]),
        route="Euler–Lagrange: the θ equation is (5.50), the ψ equation sin θ (5.51) + "
        "cos θ (5.52), the φ equation (5.52)",
    )
    # numeric: the printed equations integrated by scipy against the exact elliptic motion
    J1n, J3n, mgl = 1.3, 0.6, 0.8
    ic = dict(theta=0.9, psi=0.2, phi=-0.4, theta_dot=0.35, psi_dot=0.5, phi_dot=6.0)
    top = tops.HeavySymmetricTop(J1n, J3n, mgl, **ic)
    times = np.linspace(0.0, 6.0, 13)
    y0 = [ic["psi"], ic["theta"], ic["phi"], ic["psi_dot"], ic["theta_dot"], ic["phi_dot"]]
    ps, th, ph = simulate_printed_eom((J1n, J3n, mgl, 1.0, 1.0), y0, times)
    d.confirm(
        np.stack([ps, th, ph]),
        np.stack([top.psi(times), top.theta(times), top.phi(times)]),
        atol=SIM_ATOL,
        route="scipy integration of the printed (5.50)-(5.52) against the exact motion of "
        "mechanics.tops.HeavySymmetricTop (ψ, θ, φ at 13 times over 6 s)",
    )


def L_3_of_rates():
    """(5.53): L3 = J3(ψ̇ cos θ + φ̇)."""
    return J_3 * (pd * c + fd)


def L_z_of_rates():
    """(5.55): L_z = (J'1 sin²θ + J3 cos²θ) ψ̇ + J3 φ̇ cos θ."""
    return (J_1p * s**2 + J_3 * c**2) * pd + J_3 * fd * c


def energy_of_rates():
    """E = T + V, T = ½ ωᵀ J_C ω with ω from (5.30), V = mgℓ cos θ (G at ℓ e^B_3 above C)."""
    w = book_omega()
    return sp.Rational(1, 2) * (w.T * sp.diag(J_1p, J_1p, J_3) * w)[0, 0] + m * g * ell * c


def phi_eff(th, Lz, L3):
    """(5.70): Φ_eff(θ) = (L_z − L3 cos θ)²/(2J'1 sin²θ) − mgℓ(1 − cos θ)."""
    return (Lz - L3 * sp.cos(th)) ** 2 / (2 * J_1p * sp.sin(th) ** 2) - m * g * ell * (
        1 - sp.cos(th)
    )


@check(
    "eq5.55",
    "The conserved L_3 and L_z of the heavy symmetric top",
    kind="proof",
    covers=("eq5.53", "eq5.54", "eq5.55"),
    statement="L3 ≡ J3(ψ̇ cos θ + φ̇) (5.53); L·e^O_3 = ψ̇(J'1 sin²θ + J3 cos²θ) + J3 φ̇ cos θ "
    "(5.54) ≡ L_z (5.55); both constant by (5.50)-(5.52)",
)
def heavy_top_integrals(d: Derivation) -> None:
    L_B, pr = heavy_L_B(), heavy_eom_printed()
    d.prove_equal(L_B[2], L_3_of_rates(), claim="(5.53) is the e^B_3 component of (5.48)")
    d.prove_equal(
        (L_B.T * R_B_O() * vec(0, 0, 1))[0, 0],
        L_z_of_rates(),
        claim="(5.54): L · e^O_3 with e^O_3 = sin θ e^B_2 + cos θ e^B_3",
    )
    d.prove_equal(sp.diff(L_3_of_rates(), t), pr[2], claim="dL3/dt is (5.52): conserved")
    d.prove_equal(
        sp.diff(L_z_of_rates(), t),
        s * pr[1] + c * pr[2],
        claim="dL_z/dt = sin θ (5.51) + cos θ (5.52): conserved on every motion",
    )
    d.reject(sp.diff(L_z_of_rates(), t), c * pr[1] + s * pr[2], claim="sin θ and cos θ swapped")
    Lag = heavy_lagrangian()
    d.confirm_exact(
        sp.diff(Lag, pd),
        L_z_of_rates(),
        route="L_z = ∂(T − V)/∂ψ̇, the momentum of the cyclic coordinate ψ",
    )
    d.confirm_exact(sp.diff(Lag, fd), L_3_of_rates(), route="L3 = ∂(T − V)/∂φ̇ (φ cyclic)")
    # numeric: (5.53), (5.55) evaluated along the exact elliptic motion stay constant
    times = np.linspace(0.0, 6.0, 13)
    y0 = [0.2, 0.9, -0.4, 0.5, 0.35, 6.0]
    q, v, _ = _state_symbols()
    f = sp.lambdify((*q, *v, J_1p, J_3), [_to_state(L_3_of_rates()), _to_state(L_z_of_rates())])
    top = tops.HeavySymmetricTop(
        1.3, 0.6, 0.8, theta=0.9, psi=0.2, phi=-0.4, theta_dot=0.35, psi_dot=0.5, phi_dot=6.0
    )
    thd, psd, phd = top.rates(times)
    L3s, Lzs = f(0 * times, top.theta(times), 0 * times, psd, thd, phd, 1.3, 0.6)
    L3_0, Lz_0 = f(*y0, 1.3, 0.6)
    d.confirm(
        np.stack([L3s, Lzs]),
        np.stack([np.full_like(times, L3_0), np.full_like(times, Lz_0)]),
        atol=EXACT_RTOL * 8,  # L3, L_z ~ 4: the relative bound times their size
        route="(5.53), (5.55) evaluated along the exact motion of mechanics.tops.HeavySymmetricTop",
    )


th0 = sp.Symbol("theta_0", positive=True)
phid0 = sp.Symbol("phidot", real=True)


@check(
    "eq5.61",
    "Steady ('pure') precession of the heavy symmetric top",
    kind="proof",
    covers=("eq5.56", "eq5.57", "eq5.58", "eq5.59", "eq5.60", "eq5.61"),
    statement="ψ̇ = Ω, θ = θ0 constant (5.56)-(5.57): φ̇ = L3/J3 − Ω cos θ0 (5.58), "
    "φ̇ = [mgℓ/Ω − Ω(J3 − J'1) cos θ0]/J3 (5.59), L3 = mgℓ/Ω + J'1 Ω cos θ0 (5.60), "
    "Ω = mgℓ/[J3 φ̇ − (J3 − J'1)(φ̇ − L3/J3)] (5.61)",
)
def steady_precession(d: Derivation) -> None:
    c0 = sp.cos(th0)
    steady = {sp.diff(x, t, 2): 0 for x in (psi, theta, phi)}
    pr = heavy_eom_printed().subs(steady).subs({td: 0, pd: Omega, fd: phid0, theta: th0})
    d.prove_zero(vec(pr[1], pr[2]), claim="(5.51), (5.52) hold identically on (5.56)-(5.57)")
    d.prove_equal(
        sp.solve(sp.Eq(L_3, L_3_of_rates().subs({pd: Omega, theta: th0, fd: phid0})), phid0)[0],
        L_3 / J_3 - Omega * c0,
        strategy="cancel",
        claim="(5.58) from (5.53)",
    )
    phid_59 = (m * g * ell / Omega - Omega * (J_3 - J_1p) * c0) / J_3
    d.quantity("phi_dot", phid_59)
    d.prove_zero(
        pr[0].subs(phid0, phid_59) / sp.sin(th0), strategy="cancel", claim="(5.59) solves (5.50)"
    )
    d.reject(
        pr[0].subs(phid0, (m * g * ell / Omega + Omega * (J_3 - J_1p) * c0) / J_3) / sp.sin(th0),
        0,
        strategy="cancel",
        claim="(5.59) with +Ω(J3 − J'1) cos θ0",
    )
    L3_60 = m * g * ell / Omega + J_1p * Omega * c0
    d.prove_equal(
        J_3 * (Omega * c0 + phid_59), L3_60, strategy="cancel", claim="(5.60) = (5.53) with (5.59)"
    )
    d.prove_equal(
        m * g * ell / (J_3 * phid_59 - (J_3 - J_1p) * (phid_59 - L3_60 / J_3)),
        Omega,
        strategy="cancel",
        claim="(5.61) returns Ω given (5.59)-(5.60)",
    )
    # numeric: the exact motion started on (5.59) does not nutate; the rate is a root of (5.60)
    J1n, J3n, mgl, thn, Om = 1.3, 0.6, 0.8, 0.9, 0.15
    phin = float(phid_59.subs({m: 1, g: 1, ell: mgl, Omega: Om, J_3: J3n, J_1p: J1n, th0: thn}))
    top = tops.HeavySymmetricTop(J1n, J3n, mgl, theta=thn, psi_dot=Om, phi_dot=phin)
    times = np.linspace(0.0, 20.0, 9)
    d.confirm(
        top.theta(times),
        np.full_like(times, thn),
        atol=STEADY_ATOL,
        route="mechanics.tops.HeavySymmetricTop started on (5.59): θ(t) stays θ0 "
        "(no nutation; the double root split by rounding only)",
    )
    d.confirm(
        min(tops.steady_precession_rates(J1n, top.L_3, mgl, thn), key=lambda r: abs(r - Om)),
        Om,
        atol=CODE_ATOL,
        route="mechanics.tops.steady_precession_rates at the L3 of that motion",
    )


@check(
    "eq5.65",
    "Fast top: the gyroscopic precession rate mℓg/(J3 φ̇)",
    kind="proof",
    covers=("eq5.62", "eq5.63", "eq5.64", "eq5.65"),
    statement="with L ≈ J3 φ̇ e^B_3, dL/dt + (mℓ/L) g × L = 0 (5.62): L rotates about e^O_3 at "
    "Ω = mℓg/(J3 φ̇) (5.63)-(5.65); exact at θ0 = π/2 and the slow root of (5.60) as L3 → ∞",
)
def gyroscopic_precession(d: Derivation) -> None:
    Lx, Ly, Lz_ = sp.symbols("L_x L_y L_z", real=True)
    Lv = vec(Lx, Ly, Lz_)
    Lm = sp.sqrt(Lx**2 + Ly**2 + Lz_**2)
    gvec = vec(0, 0, -g)
    d.prove_equal(
        cross(ell * Lv / Lm, m * gvec),
        -(m * ell / Lm) * cross(gvec, Lv),
        claim="(5.62): the moment of the weight with the arm ℓ L/L is −(mℓ/L) g × L",
    )
    th_ = sp.Symbol("theta_0", positive=True)
    Om = m * ell * g / L  # (5.64)-(5.65) with L = |L|
    Lt = L * vec(sp.sin(th_) * sp.cos(Om * t), sp.sin(th_) * sp.sin(Om * t), sp.cos(th_))
    d.prove_zero(
        sp.diff(Lt, t) + (m * ell / L) * cross(gvec, Lt),
        strategy="expand",
        claim="(5.63)-(5.65): L turning about e^O_3 at mℓg/L solves (5.62)",
    )
    Lt_bad = Lt.subs(t, -t)
    d.reject(
        sp.diff(Lt_bad, t) + (m * ell / L) * cross(gvec, Lt_bad),
        sp.zeros(3, 1),
        claim="the opposite sense of precession",
    )
    d.quantity("Omega", m * ell * g / (J_3 * phid0))
    # exact at θ0 = π/2: (5.61) with cos θ0 = 0 and (5.58)
    L3_pi2 = J_3 * phid0
    d.prove_equal(
        m * g * ell / (J_3 * phid0 - (J_3 - J_1p) * (phid0 - L3_pi2 / J_3)),
        m * ell * g / (J_3 * phid0),
        claim="(5.61) at θ0 = π/2 (L3 = J3 φ̇ by (5.58)) is (5.65)",
    )
    # the slow root of (5.60): Ω = mgℓ/L3 + O(L3⁻³)
    eps_ = sp.Symbol("epsilon", positive=True)
    c0 = sp.Symbol("c_0", real=True)
    slow = (1 / eps_ - sp.sqrt(1 / eps_**2 - 4 * J_1p * m * g * ell * c0)) / (2 * J_1p * c0)
    ser = sp.series(slow, eps_, 0, 3).removeO()
    d.confirm_exact(
        ser,
        m * g * ell * eps_,
        route="the slow root of J'1 cos θ0 Ω² − L3 Ω + mgℓ = 0 (5.60) is mgℓ/L3 + O(L3⁻³), "
        "L3 = 1/ε",
        strategy="expand",
    )
    J1n, mgl, L3n = 1.3, 0.8, 12.0
    d.confirm(
        min(tops.steady_precession_rates(J1n, L3n, mgl, np.pi / 2), key=abs),
        mgl / L3n,
        atol=CODE_ATOL,
        route="mechanics.tops.steady_precession_rates at θ0 = π/2",
    )


@check(
    "eq5.70",
    "Energy, effective potential and turning points of the nutation",
    kind="proof",
    covers=("eq5.66", "eq5.67", "eq5.68", "eq5.69", "eq5.70", "eq5.71"),
    statement="E = ½J'1(θ̇² + ψ̇² sin²θ) + L3²/(2J3) + mgℓ cos θ (5.66); ψ̇ = (L_z − L3 cos θ)/"
    "(J'1 sin²θ) (5.67); E' = ½J'1 θ̇² + Φ_eff(θ) (5.68) with E' ≡ E − L3²/(2J3) − mgℓ "
    "(5.69), Φ_eff = (L_z − L3 cos θ)²/(2J'1 sin²θ) − mgℓ(1 − cos θ) (5.70); turning points "
    "E' = Φ_eff (5.71)",
)
def heavy_top_energy(d: Derivation) -> None:
    E = energy_of_rates()
    L3, Lz = L_3_of_rates(), L_z_of_rates()
    printed_E = (
        sp.Rational(1, 2) * J_1p * (td**2 + pd**2 * s**2) + L3**2 / (2 * J_3) + (m * g * ell * c)
    )
    d.prove_equal(E, printed_E, claim="(5.66) from T = ½ ωᵀ J_C ω and V = mgℓ cos θ")
    d.prove_equal(
        (Lz - L3 * c) / (J_1p * s**2), pd, strategy="tan_half", claim="(5.67) from (5.53), (5.55)"
    )
    E_p = E - L3**2 / (2 * J_3) - m * g * ell  # (5.69)
    d.prove_equal(
        E_p,
        sp.Rational(1, 2) * J_1p * td**2 + phi_eff(theta, Lz, L3),
        strategy="tan_half",
        claim="(5.68) with (5.69)-(5.70)",
    )
    d.reject(
        E_p,
        sp.Rational(1, 2) * J_1p * td**2 + phi_eff(theta, Lz, L3) + m * g * ell * (1 - c) * 2,
        strategy="tan_half",
        claim="Φ_eff with +mgℓ(1 − cos θ)",
    )
    # (5.71) as the cubic in u = cos θ: u̇² = sin²θ θ̇² = (2/J'1)(1 − u²)(E' − Φ_eff)
    u, Es, Lzs, L3s = sp.symbols("u E L_z L_3", real=True)
    Ep = Es - L3s**2 / (2 * J_3) - m * g * ell
    phi_u = (Lzs - L3s * u) ** 2 / (2 * J_1p * (1 - u**2)) - m * g * ell * (1 - u)
    beta, a_, b_ = 2 * m * g * ell / J_1p, Lzs / J_1p, L3s / J_1p
    e_ = (2 * Es - L3s**2 / J_3) / J_1p
    f_code = (e_ - beta * u) * (1 - u**2) - (a_ - b_ * u) ** 2
    d.prove_equal(
        2 / J_1p * (1 - u**2) * (Ep - phi_u),
        f_code,
        strategy="cancel",
        claim="(5.71) ⇔ f(u) = (e − βu)(1 − u²) − (a − bu)² = 0 (the cubic of mechanics.tops)",
    )
    # numeric: the exact elliptic motion conserves (5.66); its roots solve (5.71)
    J1n, J3n, mgl = 1.3, 0.6, 0.8
    ic = dict(theta=0.9, psi=0.2, phi=-0.4, theta_dot=0.35, psi_dot=0.5, phi_dot=6.0)
    top = tops.HeavySymmetricTop(J1n, J3n, mgl, **ic)
    sub0 = {J_1p: J1n, J_3: J3n, m: 1, g: 1, ell: mgl}
    rates = {td: ic["theta_dot"], pd: ic["psi_dot"], fd: ic["phi_dot"]}
    vals0 = [float(x.subs(rates).subs(theta, ic["theta"]).subs(sub0)) for x in (E, Lz, L3)]
    times = np.linspace(0.0, 50.0, 21)
    d.confirm(
        top.energy_at(times) / vals0[0],
        np.ones_like(times),
        atol=EXACT_RTOL,
        route="mechanics.tops.HeavySymmetricTop.energy_at: the exact u(t) conserves E (5.66), "
        "relative to E from this check's formula",
    )
    pe = sp.lambdify(theta, phi_eff(theta, vals0[1], vals0[2]).subs(sub0))
    Epn = vals0[0] - vals0[2] ** 2 / (2 * J3n) - mgl
    u1, u2, _ = top.roots
    d.confirm(
        [Epn - pe(np.arccos(u1)), Epn - pe(np.arccos(u2))],
        [0.0, 0.0],
        atol=EXACT_RTOL * abs(Epn),
        route="the nutation limits u1, u2 of mechanics.tops are roots of E' − Φ_eff (5.71)",
    )
    thn = top.theta(times)
    d.confirm(
        [thn.min() >= np.arccos(u2) - SIM_ATOL, thn.max() <= np.arccos(u1) + SIM_ATOL],
        [True, True],
        atol=0,
        route="θ(t) stays between the turning points",
    )


@check(
    "eq5.77",
    "The Resal frame: equations connecting φ(t) and the moment M when ^Oω^B = Ω is known",
    kind="proof",
    covers=("eq5.73", "eq5.74", "eq5.75", "eq5.76", "eq5.77"),
    statement="ω = Ω + φ̇ e^B_3 (5.73), L_B = (J1Ω1, J1Ω2, J3(Ω3 + φ̇)) (5.74), L̇ = ^B dL/dt + "
    "Ω × L = M (5.75)-(5.76) give J1Ω̇1 + (J3 − J1)Ω2Ω3 + J3Ω2φ̇ = M1, J1Ω̇2 − (J3 − J1)Ω1Ω3 "
    "− J3Ω1φ̇ = M2, J3Ω̇3 + J3φ̈ = M3 (5.77)",
)
def resal(d: Derivation) -> None:
    O1, O2, O3 = functions_of_time("Omega_1", "Omega_2", "Omega_3")
    Ov = vec(O1, O2, O3)
    w = Ov + vec(0, 0, fd)  # (5.73)
    L_B = sp.diag(J_1, J_1, J_3) * w
    d.prove_equal(L_B, vec(J_1 * O1, J_1 * O2, J_3 * (O3 + fd)), claim="(5.74)")
    lhs = sp.diff(L_B, t) + cross(Ov, L_B)  # (5.75)-(5.76)
    printed = vec(
        J_1 * sp.diff(O1, t) + (J_3 - J_1) * O2 * O3 + J_3 * O2 * fd,
        J_1 * sp.diff(O2, t) - (J_3 - J_1) * O1 * O3 - J_3 * O1 * fd,
        J_3 * sp.diff(O3, t) + J_3 * sp.diff(phi, t, 2),
    )
    d.prove_equal(lhs, printed, claim="(5.77)")
    d.reject(lhs, printed.subs(J_3 * O1 * fd, -J_3 * O1 * fd), claim="(5.77b) with +J3 Ω1 φ̇")
    sub = {O1: td, O2: pd * s, O3: pd * c, J_1: J_1p}
    d.confirm_exact(
        printed.subs(sub).doit(),
        heavy_eom_printed() + vec(m * g * ell * s, 0, 0),
        route="with Ω = ^Oω^B of (5.29) and J1 → J'1, (5.77) is the left side of (5.50)-(5.52)",
    )
