"""The book's objects as sympy expressions, built from the book's definitions.

These are written from the text, not from :mod:`mechanics`, so that a proof about
them and a comparison with the numeric code are two independent statements.

- ``R1, R2, R3``: (2.30); ``euler_matrix``: (2.35); ``rotvec_matrix``: (2.29).
- ``general_rotation``: a *general* rotation matrix as a rational function of four
  free real parameters (the Euler–Rodrigues form of an unnormalised quaternion).
  Every rotation has this form, and it is exactly orthogonal as a rational
  function, so proofs about it reduce with ``cancel`` (no trigonometry) and hold
  for all rotations.
- ``unit_vector``: a unit vector as a rational function of two parameters (inverse
  stereographic projection): every direction but one, and polynomial identities
  that hold on a dense set of the sphere hold on all of it.
- ``omega_matrix``: the book's angular-velocity matrix (2.52).
"""

from __future__ import annotations

import sympy as sp

__all__ = [
    "R1",
    "R2",
    "R3",
    "cross",
    "euler_matrix",
    "floats",
    "general_rotation",
    "omega_matrix",
    "omega_vector",
    "rotvec_matrix",
    "rotvec_matrix_explicit",
    "unit_vector",
    "vec",
]

t = sp.Symbol("t", real=True)


def vec(*xs) -> sp.Matrix:
    """A column vector."""
    return sp.Matrix(xs)


def cross(a: sp.Matrix, b: sp.Matrix) -> sp.Matrix:
    return sp.Matrix(a).cross(sp.Matrix(b))


def R1(a) -> sp.Matrix:
    return sp.Matrix([[1, 0, 0], [0, sp.cos(a), sp.sin(a)], [0, -sp.sin(a), sp.cos(a)]])


def R2(a) -> sp.Matrix:
    return sp.Matrix([[sp.cos(a), 0, -sp.sin(a)], [0, 1, 0], [sp.sin(a), 0, sp.cos(a)]])


def R3(a) -> sp.Matrix:
    return sp.Matrix([[sp.cos(a), sp.sin(a), 0], [-sp.sin(a), sp.cos(a), 0], [0, 0, 1]])


def euler_matrix(psi, theta, phi) -> sp.Matrix:
    """^A R^O(ψ, θ, φ) = R3(φ) R1(θ) R3(ψ) (2.35)."""
    return R3(phi) * R1(theta) * R3(psi)


def rotvec_matrix(phi, c) -> sp.Matrix:
    """(2.29): cos φ 1 + sin φ [antisymmetric] + (1 − cos φ) c cᵀ, c = direction cosines."""
    c1, c2, c3 = c
    anti = sp.Matrix([[0, c3, -c2], [-c3, 0, c1], [c2, -c1, 0]])
    return (
        sp.cos(phi) * sp.eye(3)
        + sp.sin(phi) * anti
        + (1 - sp.cos(phi)) * sp.Matrix(c) * sp.Matrix(c).T
    )


def rotvec_matrix_explicit(phi, c) -> sp.Matrix:
    """(2.28), entry by entry as printed."""
    c1, c2, c3 = c
    C, S = sp.cos(phi), sp.sin(phi)
    return sp.Matrix(
        [
            [(1 - C) * c1**2 + C, (1 - C) * c1 * c2 + S * c3, (1 - C) * c1 * c3 - S * c2],
            [(1 - C) * c2 * c1 - S * c3, (1 - C) * c2**2 + C, (1 - C) * c2 * c3 + S * c1],
            [(1 - C) * c3 * c1 + S * c2, (1 - C) * c3 * c2 - S * c1, (1 - C) * c3**2 + C],
        ]
    )


def general_rotation(a, b, c, d) -> sp.Matrix:
    """A general passive rotation matrix, rational in (a, b, c, d) ≠ 0.

    The transpose of the Euler–Rodrigues matrix of the quaternion a + bi + cj + dk
    divided by its squared norm.
    """
    n = a**2 + b**2 + c**2 + d**2
    active = sp.Matrix(
        [
            [a**2 + b**2 - c**2 - d**2, 2 * (b * c - a * d), 2 * (b * d + a * c)],
            [2 * (b * c + a * d), a**2 - b**2 + c**2 - d**2, 2 * (c * d - a * b)],
            [2 * (b * d - a * c), 2 * (c * d + a * b), a**2 - b**2 - c**2 + d**2],
        ]
    )
    return active.T / n


def unit_vector(u, v) -> sp.Matrix:
    """(2u, 2v, 1 − u² − v²)/(1 + u² + v²): a unit vector for all real u, v."""
    n = 1 + u**2 + v**2
    return sp.Matrix([2 * u / n, 2 * v / n, (1 - u**2 - v**2) / n])


def omega_matrix(w) -> sp.Matrix:
    """The book's angular-velocity matrix (2.52) of the components w."""
    w1, w2, w3 = w
    return sp.Matrix([[0, w3, -w2], [-w3, 0, w1], [w2, -w1, 0]])


def omega_vector(Omega: sp.Matrix) -> sp.Matrix:
    """Components read off an antisymmetric matrix of the form (2.52)."""
    return sp.Matrix([Omega[1, 2], Omega[2, 0], Omega[0, 1]])


def floats(M, subs: dict | None = None):
    """A sympy matrix (or vector) at a point, evaluated to 30 digits, as a float64 array."""
    import numpy as np

    M = sp.Matrix(M)
    if subs:
        M = M.subs(subs)
    return np.array(M.evalf(30).tolist(), dtype=float)


def functions_of_time(*names: str):
    """Undefined real functions of t, e.g. Euler angles ψ(t), θ(t), φ(t)."""
    return [sp.Function(n, real=True)(t) for n in names]
