"""Chapter 5.3: the free asymmetric top — the inertia ellipsoid and the Poinsot
construction (5.85)-(5.90), Euler's equations of the free top and the steady rotations
about principal axes (5.91)-(5.93), and the stability of those rotations (5.94)-(5.102).

Space-fixed tensors are built from a *general* rotation (``general_rotation``: a rational
function of four free parameters, exactly orthogonal), so the identities hold for every
attitude.  The numeric routes integrate Euler's equations
(:func:`mechanics.dynamics.euler_equations_rhs`) with scipy and compare with the exact
elliptic-function top :class:`mechanics.tops.FreeAsymmetricTop` and with
:func:`mechanics.tops.principal_axis_stability`.

The constants C1 and C3 of (5.96) are printed with the wrong sign (their stated signs
< 0 belong to the corrected fractions): an erratum.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, functions_of_time, general_rotation, t, vec
from mechanics import dynamics as dyn
from mechanics import tops
from mechanics._floats import EPS

#: float evaluation of a few products and quotients of O(1) numbers: 64 eps.
CODE_ATOL = 64 * EPS
#: scipy DOP853 at rtol = atol = 1e-12 over ~10 time units of O(1) motion: global error
#: measured ≤ 1e-10; 2^24 eps ≈ 3.7e-9 leaves a margin and rejects any O(1e-4) error.
SIM_ATOL = 2**24 * EPS
#: the linearised perturbation (5.102) against the full equations at amplitude ≤ 1e-4:
#: the neglected terms are relative O(δω²/ω0²) ≲ 1e-8, plus the integration error
#: relative to 1e-4; 2^-20 ≈ 9.5e-7 relative.
LINEAR_RTOL = 2.0**-20

J1, J2, J3 = sp.symbols("J_1 J_2 J_3", positive=True)
Jd = sp.diag(J1, J2, J3)
w = vec(*functions_of_time("omega_1", "omega_2", "omega_3"))
wd = sp.diff(w, t)


def printed_free_euler() -> sp.Matrix:
    """(5.91): J1ω̇1 + (J3 − J2)ω2ω3, J2ω̇2 + (J1 − J3)ω3ω1, J3ω̇3 + (J2 − J1)ω1ω2."""
    return vec(
        J1 * wd[0] + (J3 - J2) * w[1] * w[2],
        J2 * wd[1] + (J1 - J3) * w[2] * w[0],
        J3 * wd[2] + (J2 - J1) * w[0] * w[1],
    )


def euler_rates() -> dict:
    """ω̇ solved from (5.91) = 0."""
    pr = printed_free_euler()
    return {wd[i]: sp.solve(pr[i], wd[i])[0] for i in range(3)}


def _simulate(J, w0, T, n=11):
    """scipy integration of Euler's equations (mechanics.dynamics) and dR/dt = −[ω]× R."""
    J = np.asarray(J, float)

    def rhs(_t, y):
        om, R = y[:3], y[3:].reshape(3, 3)
        W = np.array([[0, -om[2], om[1]], [om[2], 0, -om[0]], [-om[1], om[0], 0]])
        return np.concatenate([dyn.euler_equations_rhs(J, om, np.zeros(3)), (-W @ R).ravel()])

    times = np.linspace(0.0, T, n)
    sol = solve_ivp(
        rhs,
        (0, T),
        np.concatenate([w0, np.eye(3).ravel()]),
        t_eval=times,
        rtol=1e-12,
        atol=1e-12,
        method="DOP853",
    )
    return times, sol.y[:3].T, sol.y[3:].T.reshape(-1, 3, 3)


@check(
    "eq5.90",
    "The inertia ellipsoid and the invariable plane (Poinsot)",
    kind="proof",
    covers=("eq5.85", "eq5.86", "eq5.87", "eq5.88", "eq5.89", "eq5.90"),
    statement="2E = J1ω1² + J2ω2² + J3ω3² (5.85) = Σ J_αβ(t) ω_α ω_β = f(ω, t) (5.86)-(5.87); "
    "∂f/∂ω_α = 2 Σ_β J_αβ ω_β = 2L_α (5.88)-(5.89); 2E = L·ω (5.90); E, L conserved",
)
def poinsot(d: Derivation) -> None:
    R = general_rotation(*sp.symbols("a b c e", real=True))  # ^A R^O, a general rotation
    wA = vec(*sp.symbols("w_1 w_2 w_3", real=True))
    J_O = R.T * Jd * R  # space components of the inertia tensor
    w_O = R.T * wA
    f = (w_O.T * J_O * w_O)[0, 0]  # (5.86)
    two_E = J1 * wA[0] ** 2 + J2 * wA[1] ** 2 + J3 * wA[2] ** 2  # (5.85)
    d.prove_equal(f, two_E, strategy="cancel", claim="(5.86)-(5.87): f(ω, t) = 2E in any attitude")
    Js = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"J_{min(i, j) + 1}{max(i, j) + 1}", real=True))
    wo = vec(*sp.symbols("w_x w_y w_z", real=True))
    fs = (wo.T * Js * wo)[0, 0]
    grad = vec(*(sp.diff(fs, x) for x in wo))
    d.prove_equal(grad, 2 * Js * wo, claim="(5.88)-(5.89): ∂f/∂ω_α = 2 Σ J_αβ ω_β = 2L_α")
    d.reject(grad, Js * wo, claim="the gradient without the factor 2")
    d.prove_equal((wA.T * Jd * wA)[0, 0], two_E, claim="(5.90): L·ω = 2E")
    # conservation of E and L² on Euler's equations (5.91)
    rates = euler_rates()
    dE = sp.diff(J1 * w[0] ** 2 + J2 * w[1] ** 2 + J3 * w[2] ** 2, t).subs(rates)
    dL2 = sp.diff((Jd * w).dot(Jd * w), t).subs(rates)
    d.prove_zero(vec(dE, dL2), strategy="expand", claim="d(2E)/dt = 0 and d|L|²/dt = 0 on (5.91)")
    d.reject(
        sp.diff(J1 * w[0] ** 2 + J2 * w[1] ** 2 + J3 * w[2] ** 2, t).subs(rates),
        sp.diff(J1 * w[0] ** 2, t).subs(rates),
        claim="one term of the energy conserved by itself",
    )
    # numeric: ω stays on the ellipsoid and on the invariable plane; L fixed in space
    Jn, w0 = np.array([1.0, 2.0, 3.0]), np.array([0.4, 1.1, -0.6])
    times, ws, Rs = _simulate(Jn, w0, 10.0)
    E0 = 0.5 * float(Jn @ w0**2)
    L_O = np.einsum("nji,nj->ni", Rs, Jn * ws)
    w_Os = np.einsum("nji,nj->ni", Rs, ws)
    d.confirm(
        np.concatenate([(Jn * ws**2).sum(-1) - 2 * E0, w_Os @ (Jn * w0) - 2 * E0]),
        np.zeros(2 * len(times)),
        atol=SIM_ATOL,
        route="scipy integration of Euler's equations: ω(t) on the inertia ellipsoid (5.85) "
        "and on the fixed invariable plane L·ω = 2E (5.90)",
    )
    d.confirm(L_O, np.tile(Jn * w0, (len(times), 1)), atol=SIM_ATOL, route="L fixed in space")
    top = tops.FreeAsymmetricTop(Jn, w0)
    ell_res, plane_res = top.poinsot_residuals(times)
    d.confirm(
        np.concatenate([ell_res, plane_res]) / (2 * E0),
        np.zeros(2 * len(times)),
        atol=2**10 * EPS,  # exact elliptic solution: a few hundred ulps (mechanics.tops)
        route="mechanics.tops.FreeAsymmetricTop.poinsot_residuals (exact elliptic motion)",
    )
    d.confirm(
        top.omega(times), ws, atol=SIM_ATOL, route="exact elliptic ω(t) = the scipy integration"
    )


@check(
    "eq5.91",
    "Euler's equations of the free top; steady rotation about any principal axis",
    kind="proof",
    covers=("eq5.91", "eq5.92", "eq5.93"),
    statement="L̇ = 0 in the principal body frame gives (5.91); ω = ω_i(t) e^A_i (5.92) solves it "
    "iff J_i ω̇_i = 0 (5.93)",
)
def free_euler(d: Derivation) -> None:
    resid = Jd * wd + cross(w, Jd * w)  # ^A dL/dt + ω × L, (2.61)
    d.prove_equal(resid, printed_free_euler(), claim="(5.91)")
    d.reject(
        resid,
        printed_free_euler() + vec(0, 2 * (J1 - J3) * w[2] * w[0], 0),
        claim="(5.91b) with (J3 − J1)",
    )
    for i in range(3):
        ansatz = {w[k]: 0 for k in range(3) if k != i}
        ansatz.update({wd[k]: 0 for k in range(3) if k != i})
        expected = sp.zeros(3, 1)
        expected[i] = Jd[i, i] * wd[i]
        d.prove_equal(
            printed_free_euler().subs(ansatz),
            expected,
            claim=f"(5.92)-(5.93) for i = {i + 1}: two equations 0 = 0, the third J_i ω̇_i = 0",
        )
    Jn, wn = np.array([1.0, 2.0, 3.0]), np.array([0.4, 1.1, -0.6])
    sub = {J1: 1.0, J2: 2.0, J3: 3.0, **{w[k]: wn[k] for k in range(3)}}
    rates = euler_rates()
    d.confirm(
        dyn.euler_equations_rhs(Jn, wn, np.zeros(3)),
        np.array([float(rates[wd[k]].subs(sub)) for k in range(3)]),
        atol=CODE_ATOL,
        route="mechanics.dynamics.euler_equations_rhs",
    )
    top = tops.FreeAsymmetricTop(Jn, [0.0, 1.3, 0.0])
    d.confirm(
        top.omega(np.array([0.0, 7.0, 70.0])),
        np.tile([0.0, 1.3, 0.0], (3, 1)),
        atol=CODE_ATOL,
        route="mechanics.tops.FreeAsymmetricTop: exact rotation about a principal axis is steady",
    )


def cyclic(j):
    """(i, j, k) with i → j → k cyclic, as in (5.94) (zero-based)."""
    return (j - 1) % 3, j, (j + 1) % 3


def C_corrected():
    """ω̇_i = C_i ω_j ω_k from (5.91): C1 = (J2 − J3)/J1, C2 = (J3 − J1)/J2, C3 = (J1 − J2)/J3."""
    return [(J2 - J3) / J1, (J3 - J1) / J2, (J1 - J2) / J3]


@check(
    "eq5.96",
    "Euler's free equations as ω̇_i = C_i ω_j ω_k; the constants C_i for J1 < J2 < J3",
    kind="proof",
    covers=("eq5.94", "eq5.95", "eq5.96"),
    errata=("eq5.96",),
    statement="(5.91) ⇔ ω̇_i = C_i ω_j ω_k, (i, j, k) cyclic (5.94); for J1 < J2 < J3 (5.95): "
    "C1 < 0, C2 > 0, C3 < 0 (5.96)",
    printed="C1 ≡ (J3 − J2)/J1 < 0, C2 ≡ (J3 − J1)/J2 > 0, C3 ≡ (J2 − J1)/J3 < 0",
    corrected="C1 = (J2 − J3)/J1 < 0, C2 = (J3 − J1)/J2 > 0, C3 = (J1 − J2)/J3 < 0 "
    "(the printed C1 and C3 are positive for J1 < J2 < J3, contradicting their stated sign, "
    "and are not the coefficients of (5.91))",
    reading="if the extraction dropped a leading minus sign on the printed C1 and C3 the "
    "book is right; the text as extracted has none.",
)
def euler_constants(d: Derivation) -> None:
    rates = euler_rates()
    C = C_corrected()
    d.prove_equal(
        vec(*(rates[wd[i]] for i in range(3))),
        vec(*(C[i] * w[(i + 1) % 3] * w[(i + 2) % 3] for i in range(3))),
        strategy="cancel",
        claim="(5.94) with the corrected C_i",
    )
    printed_C = [(J3 - J2) / J1, (J3 - J1) / J2, (J2 - J1) / J3]
    d.refute(rates[wd[0]], printed_C[0] * w[1] * w[2], claim="ω̇1 = C1 ω2 ω3 with the printed C1")
    d.refute(rates[wd[2]], printed_C[2] * w[0] * w[1], claim="ω̇3 = C3 ω1 ω2 with the printed C3")
    d.prove_equal(printed_C[1], C[1], claim="the printed C2 is right")
    p, q = sp.symbols("p q", positive=True)  # J2 = J1 + p, J3 = J1 + p + q (5.95)
    order = {J2: J1 + p, J3: J1 + p + q}
    d.prove_equal(
        vec(*(Ci.subs(order) for Ci in C)),
        vec(-q / J1, (p + q) / (J1 + p), -p / (J1 + p + q)),
        strategy="cancel",
        claim="(5.96): with J1 < J2 < J3 the corrected C1 < 0, C2 > 0, C3 < 0",
    )
    d.reject(
        printed_C[0].subs(order), -q / J1, strategy="cancel", claim="the printed C1 is negative"
    )
    Jn = np.array([1.0, 2.0, 3.0])
    Cn = [float(Ci.subs({J1: 1.0, J2: 2.0, J3: 3.0})) for Ci in C]
    d.confirm(
        [tops.principal_axis_stability(Jn, j + 1).CiCk for j in range(3)],
        [Cn[cyclic(j)[0]] * Cn[cyclic(j)[2]] for j in range(3)],
        atol=CODE_ATOL,
        route="mechanics.tops.principal_axis_stability(...).CiCk",
    )


@check(
    "eq5.102",
    "Stability of rotation about the principal axes: the middle axis is unstable",
    kind="proof",
    covers=("eq5.97", "eq5.98", "eq5.99", "eq5.100", "eq5.101", "eq5.102"),
    statement="ω = ω0_j e_j + δω (5.97) in (5.94) gives (5.98)-(5.100) exactly, (5.101) on "
    "differentiation and δω̈_i ≈ C_i C_k (ω0_j)² δω_i (5.102): oscillation about axes 1 and 3, "
    "exponential growth about axis 2",
)
def principal_axis_stability(d: Derivation) -> None:
    C = C_corrected()
    Cs = sp.symbols("C_1 C_2 C_3", real=True)
    w0 = sp.Symbol("omega_0", real=True)
    dw = vec(*functions_of_time("delta_1", "delta_2", "delta_3"))
    eps_ = sp.Symbol("epsilon", positive=True)
    for j in range(3):
        i, _, k = cyclic(j)
        om = vec(*((w0 if n == j else 0) + dw[n] for n in range(3)))  # (5.97)
        rhs = vec(*(Cs[n] * om[(n + 1) % 3] * om[(n + 2) % 3] for n in range(3)))  # (5.94)
        printed = [
            Cs[j] * dw[i] * dw[k],
            Cs[i] * (w0 + dw[j]) * dw[k],
            Cs[k] * (w0 + dw[j]) * dw[i],
        ]
        d.prove_equal(
            vec(rhs[j], rhs[i], rhs[k]),
            vec(*printed),
            claim=f"(5.98)-(5.100) for j = {j + 1}",
        )
        ddot = sp.diff(printed[1], t).subs(
            {sp.diff(dw[k], t): printed[2], sp.diff(dw[j], t): sp.diff(dw[j], t)}
        )
        book_101 = (
            Cs[i] * sp.diff(dw[j], t) * dw[k] + Cs[i] * (w0 + dw[j]) * Cs[k] * (w0 + dw[j]) * dw[i]
        )
        d.prove_equal(ddot, book_101, claim=f"(5.101) for j = {j + 1}")
        small = sp.symbols("x_i x_j x_k xdot_j", real=True)
        plain = book_101.xreplace({sp.diff(dw[j], t): small[3]}).xreplace(
            {dw[i]: small[0], dw[j]: small[1], dw[k]: small[2]}
        )
        lin = sp.expand(plain.xreplace({x: eps_ * x for x in small}))
        d.prove_equal(
            lin.coeff(eps_, 1), Cs[i] * Cs[k] * w0**2 * small[0], claim=f"(5.102) for j = {j + 1}"
        )
    d.reject(lin.coeff(eps_, 1), Cs[i] * Cs[j] * w0**2 * small[0], claim="(5.102) with C_i C_j")
    p, q = sp.symbols("p q", positive=True)
    order = {J2: J1 + p, J3: J1 + p + q}
    prods = [C[cyclic(j)[0]] * C[cyclic(j)[2]] for j in range(3)]
    d.prove_equal(
        vec(*(x.subs(order) for x in prods)),
        vec(
            -p * (p + q) / ((J1 + p) * (J1 + p + q)),
            p * q / (J1 * (J1 + p + q)),
            -q * (p + q) / (J1 * (J1 + p)),
        ),
        strategy="cancel",
        claim="C2C3 < 0 (j = 1), C1C3 > 0 (j = 2), C1C2 < 0 (j = 3): only the middle axis grows",
    )
    # numeric: the full equations against the linear solution cosh/cos, and mechanics
    Jn, wn, amp = np.array([1.0, 2.0, 3.0]), 1.5, 1e-9
    Cn = [float(x.subs({J1: 1.0, J2: 2.0, J3: 3.0})) for x in C]
    for j in range(3):
        i, _, k = cyclic(j)
        lam2 = Cn[i] * Cn[k] * wn**2
        res = tops.principal_axis_stability(Jn, j + 1, omega=wn)
        d.confirm(
            res.rate,
            np.sqrt(abs(lam2)),
            atol=CODE_ATOL,
            route=f"mechanics.tops.principal_axis_stability rate, axis {j + 1}",
        )
        x0 = np.zeros(3)
        x0[j], x0[i] = wn, amp
        T = 8.0 if lam2 > 0 else 10.0
        times = np.linspace(0.0, T, 9)
        sol = solve_ivp(
            lambda _t, y: dyn.euler_equations_rhs(Jn, y, np.zeros(3)),
            (0, T),
            x0,
            t_eval=times,
            rtol=1e-13,
            atol=1e-20,
            method="DOP853",
        )
        lin = np.cosh(np.sqrt(lam2) * times) if lam2 > 0 else np.cos(np.sqrt(-lam2) * times)
        d.confirm(
            sol.y[i] / (amp * lin) if lam2 > 0 else sol.y[i] / amp,
            np.ones_like(times) if lam2 > 0 else lin,
            atol=LINEAR_RTOL,
            route=f"scipy integration of Euler's equations, axis {j + 1}: δω_i/δω_i(0) follows "
            f"{'cosh' if lam2 > 0 else 'cos'}(√|C_iC_k| ω0 t) of (5.102)",
        )
