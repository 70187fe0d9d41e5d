"""Chapter 5.1: the free spherical top, J = J1 1: ω = L/J1 is constant (5.1).

Example 5.1 (the sphere rolling on an incline) is in :mod:`identities.book.ch05.examples`.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, functions_of_time, t, vec
from mechanics import dynamics as dyn
from mechanics import tops
from mechanics._floats import EPS

#: float evaluation of a few products and quotients of O(1) numbers: 64 eps.
CODE_ATOL = 64 * EPS


@check(
    "eq5.1",
    "The free spherical top spins at constant ω = L/J1",
    kind="proof",
    covers=("eq5.1",),
    statement="J = J1 1, M = 0: L̇ = 0 with L = J1 ω gives ω̇ = 0, ω = L/J1 = const.",
)
def free_spherical_top(d: Derivation) -> None:
    J1, J2 = sp.symbols("J_1 J_2", positive=True)
    w = vec(*functions_of_time("omega_1", "omega_2", "omega_3"))
    wd = sp.diff(w, t)

    def euler_residual(J):
        """Body components of L̇ = J ω̇ + ω × J ω (4.47) with M = 0."""
        return J * wd + cross(w, J * w)

    d.prove_equal(
        euler_residual(J1 * sp.eye(3)),
        J1 * wd,
        claim="for J = J1 1 Euler's equations reduce to J1 ω̇ = 0, so ω = L/J1 is constant",
    )
    d.reject(
        euler_residual(sp.diag(J1, J2, J1)),
        J1 * wd,
        claim="the same with J2 ≠ J1 (gyroscopic terms survive)",
    )
    w0 = np.array([0.3, -1.2, 0.8])
    d.confirm(
        dyn.euler_equations_rhs([1.7, 1.7, 1.7], w0, [0.0, 0.0, 0.0]),
        np.zeros(3),
        atol=CODE_ATOL,
        route="mechanics.dynamics.euler_equations_rhs for equal moments",
    )
    top = tops.FreeAsymmetricTop([1.7, 1.7, 1.7], w0)
    d.confirm(
        top.omega(np.array([0.0, 5.0, 40.0])),
        np.tile(w0, (3, 1)),
        atol=CODE_ATOL,
        route="mechanics.tops.FreeAsymmetricTop with J1 = J2 = J3: ω(t) = ω(0)",
    )
