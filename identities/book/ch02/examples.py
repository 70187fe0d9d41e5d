"""Chapter 2 worked examples: 2.1 (R3), 2.2 (angular velocity of R3(ψ(t))), 2.3
(rigid body velocities from three points).  Each is re-derived from the book's
definitions and compared with the printed result; Example 2.3(c) is an erratum.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import R3, cross, floats, functions_of_time, omega_vector, t, vec
from mechanics import kinematics as kin
from mechanics import rotation as rot
from mechanics._floats import EPS

#: float evaluation of a few products of O(1) numbers (exact data): 16 eps.
CODE_ATOL = 16 * EPS


@check(
    "E2.1",
    "Example 2.1: the matrix of a turn ψ about e3",
    kind="derivation",
    covers=("E2.1", "eq2.11"),
    statement="e^A_1 = cos ψ e1 + sin ψ e2, e^A_2 = -sin ψ e1 + cos ψ e2, e^A_3 = e3 give "
    "^A R^O = R3(ψ) as printed in (2.11)",
)
def example_2_1(d: Derivation) -> None:
    psi = sp.Symbol("psi", real=True)
    e = [vec(1, 0, 0), vec(0, 1, 0), vec(0, 0, 1)]
    eA = [sp.cos(psi) * e[0] + sp.sin(psi) * e[1], -sp.sin(psi) * e[0] + sp.cos(psi) * e[1], e[2]]
    direction_cosines = sp.Matrix(3, 3, lambda i, j: eA[i].dot(e[j]))  # (2.9)
    d.quantity("R_A_O", direction_cosines)
    printed = sp.Matrix([[sp.cos(psi), sp.sin(psi), 0], [-sp.sin(psi), sp.cos(psi), 0], [0, 0, 1]])
    d.prove_equal(
        direction_cosines, printed, strategy="expand", claim="(2.9) for this basis = printed (2.11)"
    )
    d.reject(
        direction_cosines, printed.T, strategy="expand", claim="the transposed (active) matrix"
    )
    d.confirm(
        rot.R3(0.8),
        floats(printed, {psi: sp.Rational(4, 5)}),
        atol=CODE_ATOL,
        route="mechanics.R3(0.8) against (2.11)",
    )


@check(
    "E2.2",
    "Example 2.2: angular velocity of R3(ψ(t))",
    kind="derivation",
    covers=("E2.2", "eq2.55", "eq2.56", "eq2.57", "eq2.58"),
    statement="^O Ω^A = (d/dt R3(ψ)) R3(ψ)^T = [[0, ψ̇, 0], [-ψ̇, 0, 0], [0, 0, 0]], ω = ψ̇ e^A_3",
)
def example_2_2(d: Derivation) -> None:
    (psi,) = functions_of_time("psi")
    pd = sp.diff(psi, t)
    R = R3(psi)
    step = sp.Matrix(
        [
            [-pd * sp.sin(psi), pd * sp.cos(psi), 0],
            [-pd * sp.cos(psi), -pd * sp.sin(psi), 0],
            [0, 0, 0],
        ]
    )
    d.prove_equal(
        sp.diff(R, t), step, strategy="expand", claim="the derivative of R3(ψ(t)) in (2.57)"
    )
    Omega = sp.diff(R, t) * R.T
    printed = sp.Matrix([[0, pd, 0], [-pd, 0, 0], [0, 0, 0]])
    d.quantity("Omega", printed)
    d.prove_equal(Omega, printed, strategy="trigsimp", claim="(2.56)-(2.57) as printed")
    d.prove_equal(
        omega_vector(printed), vec(0, 0, pd), strategy="expand", claim="(2.58): ω = ψ̇ e^A_3"
    )
    d.reject(Omega, -printed, strategy="trigsimp", claim="Ω with the opposite sign (ω = -ψ̇ e3)")
    psi0, pd0 = 0.6, -1.7
    Rdot = pd0 * np.array(
        [[-np.sin(psi0), np.cos(psi0), 0], [-np.cos(psi0), -np.sin(psi0), 0], [0, 0, 0]]
    )
    d.confirm(
        kin.angular_velocity_from_matrix_rate(rot.R3(psi0), Rdot),
        [0, 0, pd0],
        atol=CODE_ATOL,
        route="mechanics.angular_velocity_from_matrix_rate of R3(ψ) at ψ = 0.6, ψ̇ = -1.7",
    )


@check(
    "E2.3",
    "Example 2.3: angular velocity and instantaneous axis from three points",
    kind="derivation",
    covers=("E2.3", *(f"eq2.{n}" for n in range(81, 94))),
    errata=("E2.3", "eq2.92"),
    statement="r1 = (0,0,1)ℓ, r2 = (0,2,0)ℓ, r3 = (1,0,1)ℓ; v1 = (1,1,-3)v, v2 = (3,2,-1)v, "
    "v3 = (1,0,-3)v: ω = (1,0,-1)v/ℓ, ω·v_i constant, P1C = (ω × v1)/ω², v_C = 2√2 v",
    printed="(2.92): P1C = (1/2)(1, 0, 1) ℓ, and C = (1, 0, 2) ℓ",
    corrected="P1C = (ω × v1)/ω² = (1/2)(1, 2, 1) ℓ, so C = (1/2, 1, 3/2) ℓ",
)
def example_2_3(d: Derivation) -> None:
    ell, v = sp.symbols("ell v", positive=True)
    r = [vec(0, 0, 1) * ell, vec(0, 2, 0) * ell, vec(1, 0, 1) * ell]
    V = [vec(1, 1, -3) * v, vec(3, 2, -1) * v, vec(1, 0, -3) * v]
    wx, wy, wz = sp.symbols("omega_x omega_y omega_z", real=True)
    w = vec(wx, wy, wz)
    # (2.85)-(2.88): the six component equations, as printed, follow from the connection formula
    eqs = [V[k] - V[0] - cross(w, r[k] - r[0]) for k in (1, 2)]
    printed_eqs = [
        vec(
            3 * v - (v + (wy * -1 - wz * 2) * ell),
            2 * v - (v + (wz * 0 - wx * -1) * ell),
            -v - (-3 * v + (wx * 2 - wy * 0) * ell),
        ),
        vec(
            v - (v + (wy * 0 - wz * 0) * ell),
            0 * v - (v + (wz * 1 - wx * 0) * ell),
            -3 * v - (-3 * v + (wx * 0 - wy * 1) * ell),
        ),
    ]
    d.prove_equal(eqs[0], printed_eqs[0], strategy="expand", claim="(2.85) in components is (2.87)")
    d.prove_equal(eqs[1], printed_eqs[1], strategy="expand", claim="(2.86) in components is (2.88)")
    sol = sp.solve(list(eqs[0]) + list(eqs[1]), [wx, wy, wz], dict=True)
    if len(sol) != 1:
        raise AssertionError(f"expected one solution for ω, got {sol}")
    omega = w.subs(sol[0])
    d.quantity("omega", omega)
    d.prove_equal(
        omega, vec(1, 0, -1) * v / ell, strategy="expand", claim="(2.89): ω = (1, 0, -1) v/ℓ"
    )
    # (2.84), (2.90)-(2.91): ω · v_i is the same for every body point
    vA, AB = vec(*sp.symbols("v1:4", real=True)), vec(*sp.symbols("s1:4", real=True))
    d.prove_equal(
        w.dot(vA + cross(w, AB)), w.dot(vA), strategy="expand", claim="(2.90)-(2.91): ω·v_B = ω·v_A"
    )
    d.reject(
        w.dot(vA + cross(AB, vA)),
        w.dot(vA),
        strategy="expand",
        claim="the same with AB × v_A in place of ω × AB",
    )
    d.prove_equal(
        sp.Matrix([omega.dot(Vk) for Vk in V]),
        sp.Matrix([4 * v**2 / ell] * 3),
        strategy="expand",
        claim="(2.84) for the data: ω·v_i = 4 v²/ℓ for i = 1, 2, 3",
    )
    # (c): the printed P1C is wrong
    P1C = cross(omega, V[0]) / omega.dot(omega)
    d.quantity("P1C", P1C)
    d.refute(P1C, vec(1, 0, 1) * ell / 2, claim="(2.92) as printed: P1C = (1/2)(1, 0, 1) ℓ")
    d.prove_equal(
        P1C, vec(1, 2, 1) * ell / 2, strategy="cancel", claim="corrected: P1C = (1/2)(1, 2, 1) ℓ"
    )
    C = r[0] + P1C
    d.quantity("r_C", C)
    d.refute(C, vec(1, 0, 2) * ell, claim="printed C = (1, 0, 2) ℓ")
    vC = V[0] + cross(omega, P1C)
    d.prove_equal(
        cross(vC, omega),
        sp.zeros(3, 1),
        strategy="cancel",
        claim="the corrected C moves parallel to ω: it is on the instantaneous axis",
    )
    vC_printed = V[0] + cross(omega, vec(1, 0, 1) * ell / 2)
    d.refute(
        cross(vC_printed, omega),
        sp.zeros(3, 1),
        claim="the printed P1C gives a velocity not parallel to ω (not on the axis)",
    )
    # (d): (2.93)
    speed = V[0].dot(omega) / sp.sqrt(omega.dot(omega))
    d.quantity("v_C", speed)
    d.prove_equal(speed, 2 * sp.sqrt(2) * v, strategy="cancel", claim="(2.93): v_C = 2√2 v")
    # independent numeric route through mechanics (ℓ = v = 1)
    rn = np.array([[0, 0, 1], [0, 2, 0], [1, 0, 1]], dtype=float)
    vn = np.array([[1, 1, -3], [3, 2, -1], [1, 0, -3]], dtype=float)
    w_num, _, residual = kin.rigid_velocity_from_points(rn, vn)
    d.confirm(
        w_num,
        [1.0, 0.0, -1.0],
        atol=CODE_ATOL,
        route="mechanics.rigid_velocity_from_points (least squares)",
    )
    d.confirm(
        residual, 0.0, atol=CODE_ATOL, route="the data are an exact rigid motion (residual 0)"
    )
    r_AC, v_C = kin.instantaneous_axis(vn[0], w_num)
    d.confirm(
        r_AC,
        [0.5, 1.0, 0.5],
        atol=CODE_ATOL,
        route="mechanics.instantaneous_axis: P1C = (1/2, 1, 1/2)",
    )
    d.confirm(np.linalg.norm(v_C), 2 * np.sqrt(2), atol=CODE_ATOL, route="mechanics: |v_C| = 2√2")
