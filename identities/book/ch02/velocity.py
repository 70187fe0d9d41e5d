"""Chapter 2.5–2.6: angular velocity, time derivatives in rotating frames, Euler's
kinematic equations, velocities of body points, the instantaneous axis and centre.
Equations (2.45)–(2.80) and (2.94)–(2.96).

Rotations are general: the Euler–Rodrigues matrix of four free parameters
(:func:`identities.verify.symbolic.general_rotation`).  Antisymmetry (2.51) is proved for
an arbitrary motion R(t) built from four arbitrary functions of time.  The later
statements involve only R and dR/dt at one instant; by (2.51) every motion has
dR/dt = K R with K antisymmetric, and every antisymmetric K occurs (R(t) =
exp(K t) R0), so they are proved for R general and dR/dt = K R with K general.
That keeps every proof a rational identity that ``cancel`` settles in a second.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import (
    cross,
    euler_matrix,
    floats,
    functions_of_time,
    general_rotation,
    omega_matrix,
    omega_vector,
    t,
    vec,
)
from mechanics import kinematics as kin
from mechanics import rotation as rot
from mechanics._floats import EPS

#: mechanics against a float evaluation of the same closed form (a few products
#: and sums of O(1) numbers): well within 16 eps.
CODE_ATOL = 16 * EPS


def _rotation_of_time(*names: str) -> sp.Matrix:
    return general_rotation(*functions_of_time(*names))


def _motion(tag: str) -> tuple[sp.Matrix, sp.Matrix]:
    """A general rotation R and a general rate dR/dt = K R, K antisymmetric (by (2.51))."""
    R = general_rotation(*sp.symbols(f"a_{tag} b_{tag} c_{tag} d_{tag}", real=True))
    k = sp.symbols(f"k1_{tag} k2_{tag} k3_{tag}", real=True)
    return R, omega_matrix(k) * R


def _omega_of(R: sp.Matrix, Rdot: sp.Matrix) -> sp.Matrix:
    """Body components of ω read from Ω = Rdot R^T, (2.46) and (2.52)."""
    return omega_vector(Rdot * R.T)


def _book_omega(w) -> np.ndarray:
    """The book's matrix (2.52) of numeric components, from the symbolic definition."""
    return floats(omega_matrix(sp.Matrix(w)))


def _omega_A(R: sp.Matrix) -> sp.Matrix:
    """Body components of ω of a motion R(t), (2.46) and (2.52)."""
    return _omega_of(R, sp.diff(R, t))


@check(
    "eq2.51",
    "The angular-velocity matrix is antisymmetric",
    kind="proof",
    covers=("eq2.47", "eq2.48", "eq2.49", "eq2.50", "eq2.51"),
    defines=("eq2.46",),
    statement="^O Ω^A = (d/dt ^A R^O) ^O R^A satisfies Ω = -Ω^T for every motion",
)
def omega_antisymmetric(d: Derivation) -> None:
    R = _rotation_of_time("a", "b", "c", "d")
    Rdot = sp.diff(R, t)
    d.prove_equal(
        sp.diff(R * R.T, t), sp.zeros(3), strategy="numerator", claim="d/dt (R R^T) = 0 (2.47)"
    )
    Omega = Rdot * R.T
    d.prove_equal(
        Omega, -(R * Rdot.T), strategy="numerator", claim="(dR/dt) R^T = -R (dR^T/dt) (2.48)-(2.49)"
    )
    d.prove_equal(
        Omega + Omega.T, sp.zeros(3), strategy="numerator", claim="Ω + Ω^T = 0 (2.50)-(2.51)"
    )
    wrong = Rdot * R
    d.reject(
        wrong + wrong.T,
        sp.zeros(3),
        strategy="numerator",
        claim="(dR/dt) R (no transpose) is antisymmetric",
    )
    R0 = rot.matrix_from_euler(0.3, 1.0, -0.4)
    w = np.array([0.5, -1.0, 2.0])
    Rdot0 = _book_omega(w) @ R0  # (2.45) with the book's (2.52), not the code's
    d.confirm(
        kin.angular_velocity_from_matrix_rate(R0, Rdot0),
        w,
        atol=CODE_ATOL,
        route="mechanics.angular_velocity_from_matrix_rate inverts dR/dt = Ω R",
    )


@check(
    "eq2.53",
    "The body basis turns with ω: d/dt E^A = ω × E^A",
    kind="proof",
    covers=("eq2.45", "eq2.53", "eq2.54"),
    defines=("eq2.52",),
    statement="with ω = ω^A_i e^A_i read from Ω by (2.52), d e^A_i/dt = ω × e^A_i; "
    "so in dt the basis turns by δφ = ω dt (2.54)",
)
def basis_turns_with_omega(d: Derivation) -> None:
    R, Rdot = _motion("A")
    d.prove_equal(Rdot, (Rdot * R.T) * R, strategy="numerator", claim="d/dt E^A = Ω E^A (2.45)")
    w_O = R.T * _omega_of(R, Rdot)  # ω in O components
    lhs = sp.Matrix.hstack(*[Rdot[i, :].T for i in range(3)])
    rhs = sp.Matrix.hstack(*[cross(w_O, R[i, :].T) for i in range(3)])
    d.prove_equal(
        lhs, rhs, strategy="numerator", claim="d e^A_i/dt = ω × e^A_i (2.53), components in O"
    )
    rhs_wrong = sp.Matrix.hstack(*[cross(R[i, :].T, w_O) for i in range(3)])
    d.reject(lhs, rhs_wrong, strategy="numerator", claim="d e^A_i/dt = e^A_i × ω")
    d.note(
        "(2.54): the first-order change of E^A in dt is (Ω dt) E^A, the matrix (2.39) of δφ = ω dt"
    )
    w = np.array([0.2, 0.7, -1.3])
    R0 = rot.matrix_from_euler(1.0, 0.5, 2.0)
    h = 1e-6
    R1 = rot.matrix_from_rotvec(h * w) @ R0
    d.confirm(
        (R1 - R0) / h,
        _book_omega(w) @ R0,
        atol=4 * h,
        route="mechanics: a turn by δφ = ω dt (body components) advances E^A by Ω E^A dt",
    )


@check(
    "eq2.61",
    "Time derivatives in relatively rotating frames",
    kind="proof",
    covers=("eq2.60", "eq2.61"),
    defines=("eq2.59",),
    statement="^O d/dt r = ^A d/dt r + ^O ω^A × r for every vector r(t)",
)
def rotating_frame_derivative(d: Derivation) -> None:
    R, Rdot = _motion("A")
    rA = vec(*sp.symbols("x1 x2 x3", real=True))  # components in A at the instant
    rA_dot = vec(*sp.symbols("xdot1 xdot2 xdot3", real=True))  # their rates, ^A d/dt r
    lhs = Rdot.T * rA + R.T * rA_dot  # d/dt of r^O = R^T r^A (2.60)
    w = _omega_of(R, Rdot)
    rhs = R.T * (rA_dot + cross(w, rA))
    d.prove_equal(
        lhs,
        rhs,
        strategy="numerator",
        claim="^O d/dt r = ^A d/dt r + ω × r (2.61), in O components",
    )
    d.reject(
        lhs,
        R.T * (rA_dot - cross(w, rA)),
        strategy="numerator",
        claim="^O d/dt r = ^A d/dt r - ω × r",
    )
    w = np.array([0.0, 0.0, 2.0])
    r = np.array([1.0, 0.0, 0.0])
    d.confirm(
        kin.point_velocity(np.zeros(3), w, r),
        [0.0, 2.0, 0.0],
        atol=CODE_ATOL,
        route="mechanics.point_velocity: a body point at e1 turning about e3 moves along e2",
    )


@check(
    "eq2.62",
    "Velocities of translating frames add",
    kind="proof",
    covers=("eq2.62",),
    statement="^O v^A = ^O v^B + ^B v^A for frames without relative rotation",
)
def velocities_add(d: Derivation) -> None:
    rB = sp.Matrix(functions_of_time("X1", "X2", "X3"))
    rBA = sp.Matrix(functions_of_time("y1", "y2", "y3"))
    d.prove_equal(
        sp.diff(rB + rBA, t),
        sp.diff(rB, t) + sp.diff(rBA, t),
        strategy="expand",
        claim="d/dt (OB + BA) = ^O v^B + ^B v^A (2.62)",
    )
    d.reject(
        sp.diff(rB + rBA, t),
        sp.diff(rB, t) - sp.diff(rBA, t),
        strategy="expand",
        claim="^O v^A = ^O v^B - ^B v^A",
    )


@check(
    "eq2.63",
    "Angular velocities add: ω_OA = ω_OB + ω_BA",
    kind="proof",
    covers=("eq2.63", "eq2.64"),
    statement="for ^A R^O = ^A R^B ^B R^O, the angular velocities add as vectors (2.63), "
    "and over several intermediate frames (2.64)",
)
def angular_velocities_add(d: Derivation) -> None:
    R_BO, Rdot_BO = _motion("B")
    R_AB, Rdot_AB = _motion("A")
    R_AO = R_AB * R_BO
    Rdot_AO = Rdot_AB * R_BO + R_AB * Rdot_BO  # product rule
    w_OA = _omega_of(R_AO, Rdot_AO)  # A components
    w_OB = _omega_of(R_BO, Rdot_BO)  # B components
    w_BA = _omega_of(R_AB, Rdot_AB)  # A components
    d.prove_equal(
        w_OA,
        R_AB * w_OB + w_BA,
        strategy="numerator",
        claim="^O ω^A = ^O ω^B + ^B ω^A (2.63), all in A components",
    )
    d.reject(
        w_OA,
        w_OB + w_BA,
        strategy="numerator",
        claim="adding the components without turning ^O ω^B into the basis A",
    )
    d.note("(2.64) follows by applying (2.63) twice; the Euler-angle case is checked in eq2.69")


@check(
    "eq2.69",
    "Euler's kinematic equations",
    kind="proof",
    covers=("eq2.65", "eq2.66", "eq2.67", "eq2.68", "eq2.69"),
    statement="ω^A = (ψ̇ sin θ sin φ + θ̇ cos φ, ψ̇ sin θ cos φ - θ̇ sin φ, ψ̇ cos θ + φ̇)",
)
def euler_kinematic(d: Derivation) -> None:
    psi, theta, phi = functions_of_time("psi", "theta", "phi")
    R = euler_matrix(psi, theta, phi)
    pd, td, fd = (sp.diff(x, t) for x in (psi, theta, phi))
    printed = vec(
        pd * sp.sin(theta) * sp.sin(phi) + td * sp.cos(phi),
        pd * sp.sin(theta) * sp.cos(phi) - td * sp.sin(phi),
        pd * sp.cos(theta) + fd,
    )
    d.quantity("omega_A", printed)
    from identities.verify.symbolic import R1, R3

    eC3 = (R3(phi) * R1(theta))[:, 2]  # e^C_3 in A components: third column of ^A R^C
    eB1 = R3(phi)[:, 0]  # e^B_1 in A components
    d.prove_equal(
        eC3,
        vec(sp.sin(theta) * sp.sin(phi), sp.sin(theta) * sp.cos(phi), sp.cos(theta)),
        strategy="expand",
        claim="(2.66): e^C_3 in the basis A",
    )
    d.prove_equal(
        eB1,
        vec(sp.cos(phi), -sp.sin(phi), 0),
        strategy="expand",
        claim="(2.67): e^B_1 in the basis A",
    )
    d.prove_equal(
        pd * eC3 + td * eB1 + fd * vec(0, 0, 1),
        printed,
        strategy="expand",
        claim="(2.65) with (2.66)-(2.67) gives (2.68)-(2.69)",
    )
    d.prove_equal(
        _omega_A(R),
        printed,
        strategy="trigsimp",
        claim="(2.69) equals ω read from (d/dt ^A R^O) ^O R^A: an independent route via (2.46)",
    )
    wrong = vec(pd * sp.sin(theta) * sp.cos(phi) + td * sp.cos(phi), printed[1], printed[2])
    d.reject(_omega_A(R), wrong, strategy="trigsimp", claim="ω1 with cos φ in place of sin φ")
    # mechanics: Euler rates -> ω against ω from the exact matrix rate
    ang = (0.7, 1.1, -0.3)
    rates = (0.4, -1.2, 2.5)
    pt = dict(zip((psi, theta, phi), ang, strict=True))
    ptd = dict(zip((pd, td, fd), rates, strict=True))
    Rdot_num = floats(sp.diff(R, t).subs(ptd), pt)
    d.confirm(
        kin.angular_velocity_from_euler_rates(*ang, *rates),
        kin.angular_velocity_from_matrix_rate(rot.matrix_from_euler(*ang), Rdot_num),
        atol=CODE_ATOL,
        route="mechanics: (2.69) rates against Ω = dR/dt R^T from the exact matrix rate",
    )


@check(
    "eq2.74",
    "The connection formula for velocities in a rigid body",
    kind="proof",
    covers=("eq2.72", "eq2.73", "eq2.74"),
    defines=("eq2.70", "eq2.71"),
    statement="v_B = v_A + ω × AB = v_A + BA × ω for body points A, B",
)
def connection_formula(d: Derivation) -> None:
    R, Rdot = _motion("A")
    vA = vec(*sp.symbols("vA1 vA2 vA3", real=True))  # d/dt r_A
    aA = vec(*sp.symbols("a1 a2 a3", real=True))  # body components of AB: constant
    v_i = vA + Rdot.T * aA  # d/dt of (2.71), r_i = r_A + (^A R^O)^T a^A, in O components
    w_O = R.T * _omega_of(R, Rdot)
    AB = R.T * aA
    d.prove_equal(
        v_i, vA + cross(w_O, AB), strategy="numerator", claim="(2.72)-(2.73): v_B = v_A + ω × AB"
    )
    d.prove_equal(
        cross(w_O, AB), cross(-AB, w_O), strategy="expand", claim="(2.74): ω × AB = BA × ω"
    )
    d.reject(v_i, vA + cross(AB, w_O), strategy="numerator", claim="v_B = v_A + AB × ω")
    d.confirm(
        kin.point_velocity([1.0, 2.0, 3.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
        [1.0, 3.0, 3.0],
        atol=CODE_ATOL,
        route="mechanics.point_velocity by hand: v_A + e3 × e1 = v_A + e2",
    )


@check(
    "eq2.80",
    "The instantaneous axis of rotation",
    kind="proof",
    covers=("eq2.77", "eq2.78", "eq2.79", "eq2.80"),
    defines=("eq2.75", "eq2.76"),
    statement="for AC = (ω × v_A)/ω², v_C = v_A + CA × ω = (v_A · e_ω) e_ω is parallel to ω",
)
def instantaneous_axis(d: Derivation) -> None:
    w = vec(*sp.symbols("w1 w2 w3", real=True))
    vA = vec(*sp.symbols("v1 v2 v3", real=True))
    w2 = w.dot(w)
    AC = cross(w, vA) / w2
    vC = vA + cross(-AC, w)
    d.prove_equal(
        vC, vA.dot(w) * w / w2, strategy="cancel", claim="v_C = (v_A·ω) ω/ω² = v_A∥ (2.78)-(2.80)"
    )
    AC_wrong = cross(vA, w) / w2
    d.reject(
        vA + cross(-AC_wrong, w),
        vA.dot(w) * w / w2,
        strategy="cancel",
        claim="AC = (v_A × ω)/ω² (the cross product reversed)",
    )
    r_AC, v_C = kin.instantaneous_axis([1.0, 1.0, -3.0], [1.0, 0.0, -1.0])
    d.confirm(
        np.cross(v_C, [1.0, 0.0, -1.0]),
        np.zeros(3),
        atol=CODE_ATOL,
        route="mechanics.instantaneous_axis: v_C parallel to ω",
    )
    d.confirm(
        kin.point_velocity([1.0, 1.0, -3.0], [1.0, 0.0, -1.0], r_AC),
        v_C,
        atol=CODE_ATOL,
        route="mechanics.point_velocity at A + AC equals v_C",
    )


@check(
    "eq2.95",
    "Plane motion: the instantaneous centre of zero velocity",
    kind="proof",
    covers=("eq2.94", "eq2.95", "eq2.96"),
    statement="x_C = x_A - ẏ_A/ω, y_C = y_A + ẋ_A/ω has zero velocity, and v_A = AC × ω",
    reading="The extraction drops the time dots: '(x_A e_x + y_A e_y)' in (2.94) and 'y_A/ω', "
    "'x_A/ω' in (2.95) are ẋ_A, ẏ_A, as (2.77) with v_A = ẋ_A e_x + ẏ_A e_y requires.",
)
def instantaneous_centre(d: Derivation) -> None:
    xA, yA, xd, yd = sp.symbols("x_A y_A xdot_A ydot_A", real=True)
    w = sp.Symbol("omega", nonzero=True, real=True)
    C = vec(xA - yd / w, yA + xd / w, 0)
    A = vec(xA, yA, 0)
    vA = vec(xd, yd, 0)
    W = vec(0, 0, w)
    d.prove_equal(
        C - A, cross(W, vA) / w**2, strategy="cancel", claim="(2.94): AC = ω e_z × v_A / ω²"
    )
    d.prove_equal(
        vA + cross(A - C, W),
        sp.zeros(3, 1),
        strategy="cancel",
        claim="the body point at C has zero velocity (2.95)",
    )
    d.prove_equal(vA, cross(C - A, W), strategy="cancel", claim="(2.96): v_A = AC × ω")
    C_wrong = vec(xA + yd / w, yA + xd / w, 0)
    d.reject(
        vA + cross(A - C_wrong, W),
        sp.zeros(3, 1),
        strategy="cancel",
        claim="x_C = x_A + ẏ_A/ω (sign of the first component flipped)",
    )
    c = kin.instantaneous_centre_plane([1.0, 2.0], [3.0, -1.0], 2.0)
    d.confirm(
        kin.point_velocity([3.0, -1.0, 0.0], [0.0, 0.0, 2.0], [c[0] - 1.0, c[1] - 2.0, 0.0]),
        np.zeros(3),
        atol=CODE_ATOL,
        route="mechanics.instantaneous_centre_plane has zero velocity",
    )
