"""Randomised invariants of rotation matrices (Essén 2.2–2.4) for :mod:`mechanics.rotation`.

Every way the library builds an attitude (Euler angles z-x-z (2.30), rotation vectors,
quaternions, and the composition of two attitudes (2.25)) gives an orthogonal matrix
with determinant +1: ^A R^O (^A R^O)ᵀ = 1 (2.15, 2.16).  The drawn inputs are those of
:mod:`mechanics.strategies` (Euler angles at and near gimbal lock, rotation vectors at
tiny, generic, near-π and π angles, quaternions of half turns).
"""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from identities.verify.catalogue import check
from mechanics import rotation as rot
from mechanics import strategies as ms
from mechanics._floats import EPS

#: A rotation matrix entry from sin/cos products carries ≲ 8 eps (measured 6.3 eps
#: against an 80-bit reference); a product of two such matrices doubles it.
MATRIX_ATOL = 16 * EPS

#: Examples per property in the catalogue (a draw and a check take ~0.2 ms).
EXAMPLES = 500

__all__ = ["MATRIX_ATOL", "attitudes_are_rotations", "is_orthogonal_with_det_one"]


def is_orthogonal_with_det_one(R, what: str = "R") -> None:
    """R Rᵀ = 1 and det R = +1 within :data:`MATRIX_ATOL` (2.15, 2.16)."""
    R = np.asarray(R, dtype=float)
    off = float(np.abs(R @ R.T - np.eye(3)).max())
    assert off <= MATRIX_ATOL, f"{what}: |R Rᵀ − 1| = {off / EPS:.3g} eps"
    det = float(np.linalg.det(R))
    assert abs(det - 1.0) <= MATRIX_ATOL, f"{what}: det R − 1 = {(det - 1.0) / EPS:.3g} eps"


def attitudes_are_rotations(euler, rotvec, quat, *, build=None) -> None:
    """The attitudes built from ``euler``, ``rotvec`` and ``quat``, and their products, are
    rotations.  ``build(R_a, R_b)`` replaces the composition (the negative control)."""
    R_e = rot.matrix_from_euler(*euler)
    R_v = rot.matrix_from_rotvec(rotvec)
    R_q = rot.matrix_from_quat(quat)
    for R, what in ((R_e, "from Euler angles"), (R_v, "from a rotation vector"), (R_q, "from a quaternion")):  # fmt: skip
        is_orthogonal_with_det_one(R, what)
    combine = rot.compose if build is None else build
    # a product of two: each factor's ≲ 8 eps error adds, within MATRIX_ATOL
    is_orthogonal_with_det_one(combine(R_e, R_v), "a composition (2.25)")
    is_orthogonal_with_det_one(combine(R_q, R_e), "a composition (2.25)")


def _mean(R_a, R_b):
    """A wrong 'composition': the entrywise mean of two attitudes."""
    return 0.5 * (R_a + R_b)


_ATTITUDES = st.tuples(ms.euler_angles(), ms.rotvecs(), ms.quaternions())


@check(
    "thm.rotation-orthogonal",
    "Every attitude the library builds is an orthogonal matrix with determinant +1",
    kind="property",
    covers=("eq2.15", "eq2.16"),
    statement="^A R^O (^A R^O)ᵀ = 1, det ^A R^O = +1 for matrices from Euler angles, "
    "rotation vectors, quaternions and their compositions",
)
def _orthogonal(d) -> None:
    d.holds_for_examples(
        attitudes_are_rotations,
        _ATTITUDES,
        examples=EXAMPLES,
        claim="(2.15), (2.16): R Rᵀ = 1 and det R = +1 within 16 eps",
    )
    d.reject_property(
        lambda e, v, q: attitudes_are_rotations(e, v, q, build=_mean),
        _ATTITUDES,
        examples=EXAMPLES,
        claim="the entrywise mean of two attitudes is an attitude",
    )
