"""Rotation matrices, Euler angles, rotation vectors and unit quaternions.

Conventions (Essén 1996, ch. 2.2–2.4)
-------------------------------------
- **Passive (basis) matrices, as the book writes them.**  ``R_A_O`` is the book's
  ^A R^O: its rows are the new basis vectors e^A_i in old (O) components, so that
  E_A = ^A R^O E_O (2.10).  Every function named ``matrix_*`` returns or takes this
  matrix.  Frame-subscripted names read target first: ``R_A_O`` maps O to A.
- The basic matrices (2.30) are R3(ψ) = [[cos ψ, sin ψ, 0], [−sin ψ, cos ψ, 0],
  [0, 0, 1]] and likewise ``R1``, ``R2``: a *positive* turn of the basis about the
  axis.
- **Euler angles z-x-z**, ^A R^O(ψ, θ, φ) = R3(φ) R1(θ) R3(ψ) (2.35), with
  ψ, φ in (−π, π] and θ in [0, π] on output.  Gimbal lock is at θ ∈ {0, π}.
- **Rotation vector** φ = φ e_a (2.4): the turn of the basis by φ about e_a in the
  positive (right-hand) sense; ``matrix_from_rotvec`` returns ^A R^O(φ) of
  (2.28)–(2.29).  ``rotvec_from_matrix`` returns φ in [0, π].
- **Active operator.**  The operator that turns a vector with the basis,
  R_{O→A} of (2.21), has the matrix (in O components, acting on columns) equal to
  the *transpose* of ^A R^O: :func:`active_from_passive` and
  :func:`passive_from_active` say so by name; :func:`rotate_vector` applies it and
  :func:`components_A_from_O` applies (2.20).
- **Quaternions are scalar first**, q = (w, x, y, z) = (cos φ/2, sin φ/2 e_a),
  and describe the active operator: R_{O→A} r = q r q*.  q and −q are the same
  rotation; functions return w ≥ 0.  (scipy's ``Rotation`` is scalar *last*.)
- **Composition** follows the book's chain rule (2.34): ^B R^O = ^B R^A ^A R^O,
  :func:`compose`.
- Everything is float64 and vectorised over leading axes: angles ``(...)``,
  vectors ``(..., 3)``, quaternions ``(..., 4)``, matrices ``(..., 3, 3)``.

Accuracy (measured by ``tests/stability/test_rotation_stability.py`` against
mpmath at 50 digits): every round trip between matrix, rotation vector,
quaternion and Euler angles reproduces the matrix within ``ROUNDTRIP_ATOL``
(4 eps, max-abs), the gimbal-lock band included; the rotation angle extracted
from a matrix is within a few ulps relative for angles from 1e-300 to π.
"""

from __future__ import annotations

import numpy as np

from ._validate import as_float_array
from .errors import NotARotationError, ZeroAxisError

__all__ = [
    "EPS",
    "ROTATION_ATOL",
    "ROUNDTRIP_ATOL",
    "R1",
    "R2",
    "R3",
    "active_from_passive",
    "check_rotation",
    "components_A_from_O",
    "compose",
    "compose_quat",
    "euler_from_matrix",
    "euler_near_gimbal_lock",
    "is_rotation",
    "matrix_from_axis_angle",
    "matrix_from_euler",
    "matrix_from_quat",
    "matrix_from_rotvec",
    "nearest_rotation",
    "passive_from_active",
    "quat_from_matrix",
    "quat_from_rotvec",
    "quat_multiply",
    "rotate_vector",
    "rotvec_from_matrix",
    "rotvec_from_quat",
]

EPS = float(np.finfo(np.float64).eps)

#: Accepted deviation of a rotation matrix from orthogonality, max |R Rᵀ − 1| and
#: |det R − 1|.  A product of n float64 rotations drifts by about sqrt(n) · 2 eps
#: (measured: 10^4 products stay below 200 eps); 256 eps accepts such matrices and
#: still rejects anything visibly non-orthogonal.  Repair larger drift with
#: :func:`nearest_rotation`.
ROTATION_ATOL = 256 * EPS

#: Round-trip accuracy promised for every conversion pair, as a max-abs matrix
#: difference.  Each matrix entry is a sum of at most three products of numbers
#: with relative error ≤ 1 ulp, so 4 eps bounds it; the stability tests enforce it.
ROUNDTRIP_ATOL = 4 * EPS

_QUAT_NORM_ATOL = 64 * EPS  # |q| − 1 accepted before "not a unit quaternion" is raised


# --------------------------------------------------------------------------- basics


def _trig(alpha, name: str) -> tuple[np.ndarray, np.ndarray]:
    a = as_float_array(alpha, name)
    return np.cos(a), np.sin(a)


def _stack(rows) -> np.ndarray:
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def R1(alpha) -> np.ndarray:
    """Basis rotation by ``alpha`` about the first axis, (2.30).

    Examples
    --------
    >>> import numpy as np
    >>> bool(np.allclose(R1(0.3) @ R1(0.3).T, np.eye(3), atol=1e-15, rtol=0))
    True
    """
    c, s = _trig(alpha, "alpha")
    o, z = np.ones_like(c), np.zeros_like(c)
    return _stack([(o, z, z), (z, c, s), (z, -s, c)])


def R2(alpha) -> np.ndarray:
    """Basis rotation by ``alpha`` about the second axis, (2.30)."""
    c, s = _trig(alpha, "alpha")
    o, z = np.ones_like(c), np.zeros_like(c)
    return _stack([(c, z, -s), (z, o, z), (s, z, c)])


def R3(alpha) -> np.ndarray:
    """Basis rotation by ``alpha`` about the third axis, (2.11) and (2.30).

    Examples
    --------
    The first row is e^A_1 = cos ψ e^O_1 + sin ψ e^O_2 (Example 2.1):

    >>> R3(np.pi / 2)[0].round(12).tolist()
    [0.0, 1.0, 0.0]
    """
    c, s = _trig(alpha, "alpha")
    o, z = np.ones_like(c), np.zeros_like(c)
    return _stack([(c, s, z), (-s, c, z), (z, z, o)])


def active_from_passive(R_A_O) -> np.ndarray:
    """The active operator R_{O→A} (2.21) in O components: the transpose of ^A R^O."""
    return np.swapaxes(check_rotation(R_A_O), -1, -2)


def passive_from_active(R_active) -> np.ndarray:
    """The book's basis matrix ^A R^O of an active operator: its transpose."""
    return np.swapaxes(check_rotation(R_active, name="R_active"), -1, -2)


def rotate_vector(R_A_O, r_O) -> np.ndarray:
    """Turn ``r`` with the basis, r' = R_{O→A} r (2.21); components in O in and out.

    Examples
    --------
    Turning the basis by +90° about e3 carries e1 to e2:

    >>> rotate_vector(R3(np.pi / 2), [1.0, 0.0, 0.0]).round(12).tolist()
    [0.0, 1.0, 0.0]
    """
    R = check_rotation(R_A_O)
    r = as_float_array(r_O, "r_O", (3,))
    return np.einsum("...ji,...j->...i", R, r)


def components_A_from_O(R_A_O, r_O) -> np.ndarray:
    """Components in the basis A of a vector given in O: r^A = ^A R^O r^O (2.20)."""
    R = check_rotation(R_A_O)
    r = as_float_array(r_O, "r_O", (3,))
    return np.einsum("...ij,...j->...i", R, r)


def compose(R_B_A, R_A_O) -> np.ndarray:
    """^B R^O = ^B R^A ^A R^O, the chain of basis changes (2.34)."""
    return check_rotation(R_B_A, name="R_B_A") @ check_rotation(R_A_O, name="R_A_O")


# ---------------------------------------------------------------------- validation


def _rotation_deviation(R: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    gram = R @ np.swapaxes(R, -1, -2)
    ortho = np.abs(gram - np.eye(3)).max(axis=(-1, -2))
    det = np.abs(np.linalg.det(R) - 1.0)
    return ortho, det


def check_rotation(R, *, atol: float = ROTATION_ATOL, name: str = "R_A_O") -> np.ndarray:
    """Validate a rotation matrix and return it as a float64 array.

    Raises :class:`~mechanics.errors.NotARotationError` naming the measured
    deviation when max |R Rᵀ − 1| or |det R − 1| exceeds ``atol``.

    Examples
    --------
    >>> check_rotation(np.diag([1.0, 1.0, -1.0]))
    Traceback (most recent call last):
    ...
    mechanics.errors.NotARotationError: R_A_O is not a rotation: |det R - 1| = 2 exceeds atol = 5.68e-14 (index ()); it is a reflection
    """
    a = as_float_array(R, name, (3, 3))
    ortho, det = _rotation_deviation(a)
    bad = (ortho > atol) | (det > atol)
    if bad.any():
        idx = tuple(int(i) for i in np.argwhere(bad)[0]) if bad.ndim else ()
        o, d = float(ortho[idx]), float(det[idx])
        if o > atol:
            what = f"max |R R^T - 1| = {o:.3g} exceeds atol = {atol:.3g}"
        else:
            what = f"|det R - 1| = {d:.3g} exceeds atol = {atol:.3g}"
        hint = (
            "; it is a reflection"
            if d > 1.5 and o <= atol
            else "; use nearest_rotation() to project it"
        )
        raise NotARotationError(f"{name} is not a rotation: {what} (index {idx}){hint}")
    return a


def is_rotation(R, *, atol: float = ROTATION_ATOL) -> np.ndarray:
    """Elementwise predicate: orthogonal with det +1 within ``atol``."""
    a = as_float_array(R, "R", (3, 3))
    ortho, det = _rotation_deviation(a)
    return (ortho <= atol) & (det <= atol)


def nearest_rotation(M) -> np.ndarray:
    """The rotation closest to ``M`` in the Frobenius norm (polar factor, by SVD).

    Repairs the drift of long products of rotation matrices.  A matrix whose
    determinant is not positive has no unique nearest rotation; the result then
    flips the direction of the smallest singular value (the standard choice).
    """
    a = as_float_array(M, "M", (3, 3))
    U, _, Vt = np.linalg.svd(a)
    d = np.sign(np.linalg.det(U @ Vt))
    d = np.where(d == 0, 1.0, d)
    U = U.copy()
    U[..., :, 2] *= d[..., None]
    return U @ Vt


# ---------------------------------------------------------------------- Euler angles


def matrix_from_euler(psi, theta, phi) -> np.ndarray:
    """^A R^O(ψ, θ, φ) = R3(φ) R1(θ) R3(ψ), written out as in (2.36).

    Examples
    --------
    The explicit form equals the product of (2.35):

    >>> a = (0.3, 1.1, -2.0)
    >>> bool(np.allclose(matrix_from_euler(*a), R3(a[2]) @ R1(a[1]) @ R3(a[0]),
    ...                  atol=4 * EPS, rtol=0))
    True
    """
    cps, sps = _trig(psi, "psi")
    cth, sth = _trig(theta, "theta")
    cph, sph = _trig(phi, "phi")
    cps, sps, cth, sth, cph, sph = np.broadcast_arrays(cps, sps, cth, sth, cph, sph)
    return _stack(
        [
            (cph * cps - sph * cth * sps, cph * sps + sph * cth * cps, sph * sth),
            (-sph * cps - cph * cth * sps, -sph * sps + cph * cth * cps, cph * sth),
            (sth * sps, -sth * cps, cth),
        ]
    )


# 2π split into a float64 head and tail: a − 2π_HI is exact for a in [π, 4π]
# (Sterbenz), so the wrap below adds no rounding beyond the tail's.
_TWO_PI_HI = 6.283185307179586
_TWO_PI_LO = 2.4492935982947064e-16


def _wrap(a: np.ndarray) -> np.ndarray:
    """Angle in (−π, π] for inputs in (−3π, 3π], without the rounding of mod 2π."""
    a = np.asarray(a, dtype=float)
    up = np.where(a > np.pi, (a - _TWO_PI_HI) - _TWO_PI_LO, a)
    return np.where(up <= -np.pi, (up + _TWO_PI_HI) + _TWO_PI_LO, up)


def euler_from_matrix(R_A_O) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Euler angles (ψ, θ, φ) of ^A R^O, the inverse of :func:`matrix_from_euler`.

    Returns ψ, φ in (−π, π] and θ in [0, π].

    Notes
    -----
    Read off the unit quaternion (w ≥ 0, by Shepperd's method) rather than the
    matrix entries.  The active operator is R_z(ψ) R_x(θ) R_z(φ), so with half
    angles ψ', θ', φ'

        w = cos θ' cos(ψ' + φ'),  z = cos θ' sin(ψ' + φ'),
        x = sin θ' cos(ψ' − φ'),  y = sin θ' sin(ψ' − φ'),

    and θ = 2 atan2(hypot(x, y), hypot(w, z)), ψ + φ = 2 atan2(z, w),
    ψ − φ = 2 atan2(y, x).  Each atan2 is well conditioned except where its pair
    vanishes, which is exactly where the matrix does not depend on that
    combination (gimbal lock: θ = 0 leaves only ψ + φ, θ = π only ψ − φ).  So the
    angles reproduce the matrix within 4 eps at and near gimbal lock too (unlike
    arccos of R33).  At θ = 0 exactly, ψ = φ = half the sum.

    Examples
    --------
    >>> psi, theta, phi = euler_from_matrix(matrix_from_euler(0.5, 1.0, -2.5))
    >>> [round(float(x), 12) for x in (psi, theta, phi)]
    [0.5, 1.0, -2.5]
    """
    q = quat_from_matrix(R_A_O)
    w, x, y, z = np.moveaxis(q, -1, 0)
    theta = 2.0 * np.arctan2(np.hypot(x, y), np.hypot(w, z))
    half_sum = np.arctan2(z, w)
    half_diff = np.arctan2(y, x)
    return _wrap(half_sum + half_diff), theta, _wrap(half_sum - half_diff)


def euler_near_gimbal_lock(theta, *, atol: float = 1e-6) -> np.ndarray:
    """True where sin θ < ``atol``: Euler-angle rates are ill-conditioned there.

    The default 1e-6 is where (2.69) inverted amplifies a rate error by 1e6.
    """
    t = as_float_array(theta, "theta")
    return np.abs(np.sin(t)) < atol


# ------------------------------------------------------------------- quaternions


def _norm3(v: np.ndarray) -> np.ndarray:
    """Euclidean norm of (..., 3) without underflow or overflow (tiny angles)."""
    return np.hypot(np.hypot(v[..., 0], v[..., 1]), v[..., 2])


def _divide(num, den, *, limit) -> np.ndarray:
    """num / den where den != 0, else ``limit`` (the analytic limit at den = 0)."""
    num, den = np.broadcast_arrays(np.asarray(num, float), np.asarray(den, float))
    out = np.array(np.broadcast_to(limit, num.shape), dtype=float)
    return np.divide(num, den, out=out, where=den != 0)


def _check_quat(q, name: str = "q") -> np.ndarray:
    a = as_float_array(q, name, (4,))
    n = np.hypot(_norm3(a[..., 1:]), a[..., 0])
    if (n == 0).any():
        raise ZeroAxisError(f"{name} has zero length; a unit quaternion is required")
    bad = np.abs(n - 1.0) > _QUAT_NORM_ATOL
    if bad.any():
        idx = tuple(int(i) for i in np.argwhere(bad)[0]) if bad.ndim else ()
        raise NotARotationError(
            f"{name} is not a unit quaternion: |q| = {float(n[idx])!r} at index {idx} "
            f"(|q| - 1 must be within {_QUAT_NORM_ATOL:.3g}); normalise it first"
        )
    return a / n[..., None]


def quat_multiply(p, q) -> np.ndarray:
    """Hamilton product p ⊗ q (scalar first); the operator of p after that of q."""
    p = as_float_array(p, "p", (4,))
    q = as_float_array(q, "q", (4,))
    pw, px, py, pz = np.moveaxis(p, -1, 0)
    qw, qx, qy, qz = np.moveaxis(q, -1, 0)
    return np.stack(
        [
            pw * qw - px * qx - py * qy - pz * qz,
            pw * qx + px * qw + py * qz - pz * qy,
            pw * qy - px * qz + py * qw + pz * qx,
            pw * qz + px * qy - py * qx + pz * qw,
        ],
        axis=-1,
    )


def compose_quat(q_B_A, q_A_O) -> np.ndarray:
    """Quaternion of ^B R^O from those of ^B R^A and ^A R^O (as :func:`compose`).

    The active operators compose in the opposite order to the basis matrices:
    R_{O→B} = R_{O→A} R_{A→B}, so q_B_O = q_A_O ⊗ q_B_A; returned with w ≥ 0.
    """
    q = quat_multiply(_check_quat(q_A_O, "q_A_O"), _check_quat(q_B_A, "q_B_A"))
    return _canonical(q)


def _canonical(q: np.ndarray) -> np.ndarray:
    return np.where(q[..., :1] < 0, -q, q)


def matrix_from_quat(q) -> np.ndarray:
    """^A R^O of the unit quaternion ``q`` = (w, x, y, z) of the active operator."""
    w, x, y, z = np.moveaxis(_check_quat(q), -1, 0)
    # Rows are e^A_i in O components: the transpose of the familiar active matrix.
    return _stack(
        [
            (1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)),
            (2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)),
            (2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)),
        ]
    )


def quat_from_matrix(R_A_O) -> np.ndarray:
    """Unit quaternion (w ≥ 0) of ^A R^O, by Shepperd's largest-pivot method."""
    A = np.swapaxes(check_rotation(R_A_O), -1, -2)  # the active matrix
    a = [[A[..., i, j] for j in range(3)] for i in range(3)]
    tr = a[0][0] + a[1][1] + a[2][2]
    pivots = np.stack(
        [
            1 + tr,
            1 + a[0][0] - a[1][1] - a[2][2],
            1 - a[0][0] + a[1][1] - a[2][2],
            1 - a[0][0] - a[1][1] + a[2][2],
        ],
        axis=-1,
    )
    k = np.argmax(pivots, axis=-1)
    big = 0.5 * np.sqrt(np.take_along_axis(pivots, k[..., None], axis=-1)[..., 0])
    inv = 0.25 / big
    s_x, s_y, s_z = a[2][1] - a[1][2], a[0][2] - a[2][0], a[1][0] - a[0][1]
    p_xy, p_xz, p_yz = a[0][1] + a[1][0], a[0][2] + a[2][0], a[1][2] + a[2][1]
    cand = [
        (big, s_x * inv, s_y * inv, s_z * inv),
        (s_x * inv, big, p_xy * inv, p_xz * inv),
        (s_y * inv, p_xy * inv, big, p_yz * inv),
        (s_z * inv, p_xz * inv, p_yz * inv, big),
    ]
    q = np.select([(k == i)[..., None] for i in range(4)], [np.stack(c, axis=-1) for c in cand])
    n = np.hypot(_norm3(q[..., 1:]), q[..., 0])
    return _canonical(q / n[..., None])


def quat_from_rotvec(rotvec) -> np.ndarray:
    """Unit quaternion (cos φ/2, sin φ/2 e_a) of the rotation vector φ e_a (2.4).

    Returned as computed (w may be negative for φ > π; q ≡ −q).
    """
    v = as_float_array(rotvec, "rotvec", (3,))
    angle = _norm3(v)
    half = 0.5 * angle
    # sin(φ/2)/φ, exact in the limit φ → 0 (value 1/2); no division by zero.
    scale = _divide(np.sin(half), angle, limit=0.5)
    return np.concatenate([np.cos(half)[..., None], v * scale[..., None]], axis=-1)


def rotvec_from_quat(q) -> np.ndarray:
    """Rotation vector φ e_a with φ in [0, π] of the unit quaternion ``q``."""
    q = _canonical(_check_quat(q))
    w, v = q[..., 0], q[..., 1:]
    n = _norm3(v)
    angle = 2.0 * np.arctan2(n, w)
    # φ / |v|, with the limit 2 / w as |v| → 0 (w ≥ 1/√2 there, never zero).
    scale = _divide(angle, n, limit=2.0 / np.maximum(w, 0.5))
    return v * scale[..., None]


def matrix_from_rotvec(rotvec) -> np.ndarray:
    """^A R^O(φ) of the rotation vector φ = φ e_a, (2.28)–(2.29).

    Computed through the quaternion, so that tiny angles (down to 1e-300) keep
    full relative accuracy in the off-diagonal entries.

    Examples
    --------
    (2.29) for e_a = e3 is R3 (Example 2.1):

    >>> bool(np.allclose(matrix_from_rotvec([0, 0, 0.7]), R3(0.7), atol=2 * EPS, rtol=0))
    True
    """
    return matrix_from_quat(quat_from_rotvec(rotvec))


def rotvec_from_matrix(R_A_O) -> np.ndarray:
    """Rotation vector φ e_a, φ in [0, π], of ^A R^O (inverse of (2.28)).

    At φ = π both ±π e_a describe the rotation; either may be returned.
    """
    return rotvec_from_quat(quat_from_matrix(R_A_O))


def matrix_from_axis_angle(axis, angle) -> np.ndarray:
    """^A R^O for a turn ``angle`` about the direction ``axis`` (2.29).

    ``axis`` is a direction: its length is divided out; a zero axis raises
    :class:`~mechanics.errors.ZeroAxisError`.
    """
    a = as_float_array(axis, "axis", (3,))
    n = _norm3(a)
    if (n == 0).any():
        idx = tuple(int(i) for i in np.argwhere(n == 0)[0]) if n.ndim else ()
        raise ZeroAxisError(f"axis has zero length at index {idx}; a direction is required")
    phi = as_float_array(angle, "angle")
    return matrix_from_rotvec(a / n[..., None] * phi[..., None])
