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
mpmath at 50 digits): every conversion between matrix, rotation vector,
quaternion and Euler angles is within ``ROUNDTRIP_ATOL`` (4 eps, max-abs) of the
matrix, measured both ways (forward: the float matrix against the exact matrix
of the float parameters; backward: the exact matrix of the converted value
against the input), the gimbal-lock band included; measured worst 2.5 eps.
The rotation angle extracted from a matrix is within 4 ulps relative (measured
worst 3.0) for angles from 1e-300 to π.  To get there, norms of rotation vectors
and ratios are carried in double-double (error-free transformations, see
:func:`_scaled_norm`), and no formula rounds a quantity where the book's form
would cancel.  The matrices are unbiased: products of many rotations drift from
orthogonality like a random walk.
"""

from __future__ import annotations

import numpy as np

from ._validate import as_float_array
from .errors import NotARotationError, ZeroAxisError

__all__ = [
    "EPS",
    "R1",
    "R2",
    "R3",
    "ROTATION_ATOL",
    "ROUNDTRIP_ATOL",
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
#: |det R − 1|.  A product of n different float64 rotations drifts like a random
#: walk (measured: 10^3, 10^4, 10^5 products of random rotations 18, 77, 400 eps);
#: 256 eps accepts such matrices and still rejects anything visibly
#: non-orthogonal.  The n-th power of one matrix S drifts like n ‖S Sᵀ − 1‖, up to
#: about n eps (tests/stability).  Repair larger drift with :func:`nearest_rotation`.
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
    >>> check_rotation(np.diag([1.0, 1.0, -1.0]))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.errors.NotARotationError: R_A_O is not a rotation: |det R - 1| = 2 ... a reflection
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

    Notes
    -----
    U Vᵀ from the SVD is orthogonal only to the accuracy of LAPACK's factors
    (measured: max |Q Qᵀ − 1| up to 13 eps); one Newton–Schulz step
    Q ← Q − ½ (Q Qᵀ − 1) Q, which converges quadratically to the polar factor,
    brings it to 2 eps (``tests/stability``) and moves Q by a few eps only.
    """
    a = as_float_array(M, "M", (3, 3))
    U, _, Vt = np.linalg.svd(a)
    d = np.sign(np.linalg.det(U @ Vt))
    d = np.where(d == 0, 1.0, d)
    U = U.copy()
    U[..., :, 2] *= d[..., None]
    Q = U @ Vt
    E = Q @ np.swapaxes(Q, -1, -2) - np.eye(3)
    return Q - 0.5 * (E @ Q)


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


def euler_from_matrix(R_A_O) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Euler angles (ψ, θ, φ) of ^A R^O, the inverse of :func:`matrix_from_euler`.

    Returns ψ, φ in (−π, π] and θ in [0, π].

    Notes
    -----
    Read off the quaternion (w ≥ 0, by Shepperd's method, unnormalised: all
    that follows is scale-free) rather than the matrix entries.  The active
    operator is R_z(ψ) R_x(θ) R_z(φ), so with half angles ψ', θ', φ'

        w = cos θ' cos(ψ' + φ'),  z = cos θ' sin(ψ' + φ'),
        x = sin θ' cos(ψ' − φ'),  y = sin θ' sin(ψ' − φ'),

    and θ = 2 atan2(hypot(x, y), hypot(w, z)), ψ = arg((w + iz)(x + iy)),
    φ = arg((w + iz)(x − iy)): one atan2 per angle, no sum of two rounded
    angles and no wrap into (−π, π].  The complex products are accurate
    relative to their size even where one factor is tiny, which is exactly
    where the matrix does not depend on the split (gimbal lock: θ = 0 leaves
    only ψ + φ, θ = π only ψ − φ).  So the angles reproduce the matrix within
    4 eps at and near gimbal lock too (unlike arccos of R33).  At θ = 0 exactly,
    ψ = φ = half the sum; at θ = π exactly, ψ = −φ = half the difference.

    Examples
    --------
    >>> psi, theta, phi = euler_from_matrix(matrix_from_euler(0.5, 1.0, -2.5))
    >>> [round(float(x), 12) for x in (psi, theta, phi)]
    [0.5, 1.0, -2.5]
    """
    w, x, y, z = np.moveaxis(_shepperd(R_A_O), -1, 0)
    theta = 2.0 * np.arctan2(np.hypot(x, y), np.hypot(w, z))
    # The arguments do not change when a factor is scaled, so scale each to
    # order 1 by a power of two (exact): near gimbal lock one factor is tiny
    # (down to subnormal at θ ~ 1e-311), and its products with the other would
    # underflow and lose the digits that keep ψ + φ (or ψ − φ) exact.
    w, z = _unit_scale(w, z)
    x, y = _unit_scale(x, y)
    psi = np.arctan2(w * y + z * x, w * x - z * y)
    phi = np.arctan2(z * x - w * y, w * x + z * y)
    # Gimbal lock exactly: one factor is 0, so is the product; split evenly.
    half_sum, half_diff = np.arctan2(z, w), np.arctan2(y, x)
    at_zero = (x == 0) & (y == 0)
    at_pi = (w == 0) & (z == 0)
    psi = np.where(at_zero, half_sum, np.where(at_pi, half_diff, psi))
    phi = np.where(at_zero, half_sum, np.where(at_pi, -half_diff, phi))
    return psi, theta, phi


def _unit_scale(a, b):
    """(a, b) / 2**k exactly, with max(|a|, |b|) in [1/2, 1) (zeros stay zero)."""
    _, k = np.frexp(np.maximum(np.abs(a), np.abs(b)))
    return np.ldexp(a, -k), np.ldexp(b, -k)


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


# Double-double helpers.  The classic error-free transformations: with them a
# norm or a ratio costs about one rounding instead of four or five, which is what
# keeps the conversions within 4 eps near π and the extracted angle within a few
# ulps (measured before this: up to 6 eps and 5.4 ulps; see tests/stability).
_SPLIT = 134217729.0  # 2**27 + 1, Dekker's splitter for float64


def _two_sum(a, b):
    """s + e = a + b exactly, with s = fl(a + b) (Knuth)."""
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


def _two_prod(a, b):
    """p + e = a * b exactly, with p = fl(a * b) (Dekker; needs |a|, |b| < 2**996)."""
    p = a * b
    c = _SPLIT * a
    a_hi = c - (c - a)
    a_lo = a - a_hi
    c = _SPLIT * b
    b_hi = c - (c - b)
    b_lo = b - b_hi
    return p, ((a_hi * b_hi - p) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo


def _sum4(a, b, c, d):
    """a + b + c + d with compensation: about one rounding in all."""
    s, e1 = _two_sum(a, b)
    s, e2 = _two_sum(s, c)
    s, e3 = _two_sum(s, d)
    return s + ((e1 + e2) + e3)


def _scaled_norm(v: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(u, r, r_lo): u = v / 2**k exactly, max |u_i| in [1/2, 1), and |u| = r + r_lo.

    |u| is accurate to about eps² relative (a double-double sum of exact
    squares, then one Newton correction of the square root), so the length of a
    rotation vector adds no rounding of its own; the power-of-two scaling keeps
    angles down to 1e-300 free of underflow.  A zero vector gives u = 0 and
    r = r_lo = 0.
    """
    _, k = np.frexp(np.max(np.abs(v), axis=-1))
    u = np.ldexp(v, -k[..., None])
    p, e = _two_prod(u, u)
    s, lo = p[..., 0], e[..., 0]
    for i in range(1, u.shape[-1]):
        s, t = _two_sum(s, p[..., i])
        lo = lo + (t + e[..., i])
    s, lo = _two_sum(s, lo)
    r = np.sqrt(s)
    rr, rr_lo = _two_prod(r, r)
    # r = 0 only for a zero vector, where the numerator is 0 too.
    r_lo = (((s - rr) - rr_lo) + lo) / (2.0 * np.where(r > 0, r, 1.0))
    return u, r, r_lo


def _times_ratio(u: np.ndarray, num, r: np.ndarray, r_lo: np.ndarray) -> np.ndarray:
    """u * num / (r + r_lo) for u (..., n) and the rest (...), about one rounding.

    The ratio is carried as a double-double and multiplied in with an exact
    product, so each entry is within about half an ulp.  r = 0 (u = 0, a zero
    vector) gives 0.
    """
    r_safe = np.where(r > 0, r, 1.0)
    q = num / r_safe
    p, p_lo = _two_prod(q, r)
    q_lo = (((num - p) - p_lo) - q * r_lo) / r_safe
    out, out_lo = _two_prod(u, q[..., None])
    return out + (out_lo + u * q_lo[..., None])


#: Half angles beyond this carry no low part: the first-order correction
#: cos(h + h_lo) ≈ cos h − h_lo sin h is exact to eps only while h_lo² < eps, that
#: is h < 2**26 (h_lo ≤ h eps/2), and beyond it the angle modulo 2π is uncertain
#: by more than the correction anyway.
_HALF_ANGLE_LO_MAX = 2.0**26


def _half_angle(v: np.ndarray):
    """For rotation vectors v: (u, r, r_lo) of :func:`_scaled_norm` and φ/2 = h + h_lo."""
    u, r, r_lo = _scaled_norm(v)
    k = np.frexp(np.max(np.abs(v), axis=-1))[1]
    h, h_lo = np.ldexp(r, k - 1), np.ldexp(r_lo, k - 1)
    return u, r, r_lo, h, np.where(h < _HALF_ANGLE_LO_MAX, h_lo, 0.0)


def _check_quat_raw(q, name: str = "q") -> np.ndarray:
    """Validate a unit quaternion and return it as given (not renormalised)."""
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
    return a


def _check_quat(q, name: str = "q") -> np.ndarray:
    """Validate a unit quaternion and return it normalised."""
    a = _check_quat_raw(q, name)
    return a / np.hypot(_norm3(a[..., 1:]), a[..., 0])[..., None]


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


def _matrix_from_parts(w, x, y, z, S=None) -> np.ndarray:
    """^A R^O from quaternion parts; ``S`` = sin φ e_a if known more accurately.

    The quaternion's own length is divided out as 1/|q|² = 1 − δ/(1 + δ), with
    δ = |q|² − 1 from exact squares and a compensated sum.  Dividing by a rounded
    |q|² instead biases the matrix: its rows come out long by 0.09 eps on
    average (measured over 2e5 rotation vectors), so a product of n different
    rotations drifts from orthogonality like 0.1 n eps instead of like sqrt(n).
    """
    q = np.stack([w, x, y, z], axis=-1)
    p, e = _two_prod(q, q)
    n2, lo = p[..., 0], e[..., 0]
    for i in range(1, 4):
        n2, t = _two_sum(n2, p[..., i])
        lo = lo + (t + e[..., i])
    delta = (n2 - 1.0) + lo  # n2 - 1 is exact (Sterbenz) for |q|² in [1/2, 2]
    f = delta / (1.0 + delta)

    def unit(t):
        return t - t * f

    ww, xx, yy, zz = p[..., 0], p[..., 1], p[..., 2], p[..., 3]
    if S is None:  # 2 w x_k = sin φ e_a,k
        S = np.stack([unit(2 * (w * x)), unit(2 * (w * y)), unit(2 * (w * z))], axis=-1)
    S1, S2, S3 = np.moveaxis(S, -1, 0)
    xy, xz, yz = unit(2 * (x * y)), unit(2 * (x * z)), unit(2 * (y * z))
    # Rows are e^A_i in O components: the transpose of the familiar active matrix.
    return _stack(
        [
            (unit((ww + xx) - (yy + zz)), xy + S3, xz - S2),
            (xy - S3, unit((ww + yy) - (xx + zz)), yz + S1),
            (xz + S2, yz - S1, unit((ww + zz) - (xx + yy))),
        ]
    )


def matrix_from_quat(q) -> np.ndarray:
    """^A R^O of the unit quaternion ``q`` = (w, x, y, z) of the active operator.

    Notes
    -----
    The diagonal is (w² + x² − y² − z²)/|q|² and its like, rather than
    1 − 2(y² + z²): near a half turn that form loses 1.5 eps in entries near −1.
    Dividing out |q|² (accurately, see :func:`_matrix_from_parts`) rounds less
    than normalising q first.  Measured forward error at most 1.2 eps
    (``tests/stability``).
    """
    w, x, y, z = np.moveaxis(_check_quat_raw(q), -1, 0)
    return _matrix_from_parts(w, x, y, z)


def _shepperd(R_A_O) -> np.ndarray:
    """A positive multiple of the quaternion of ^A R^O (w ≥ 0), not normalised.

    For an exact rotation the symmetric matrix K with diagonal (1 + tr,
    1 + 2 a_11 − tr, ...) and off-diagonal sums and differences of the active
    matrix a equals 4 q qᵀ; its row with the largest diagonal entry is 4 q_k q,
    a multiple of q with q_k² ≥ 1/4 (Shepperd's pivot).  So no square root and
    no division is needed, and each entry costs one rounding (the diagonal is
    summed with compensation).
    """
    A = np.swapaxes(check_rotation(R_A_O), -1, -2)  # the active matrix
    a = [[A[..., i, j] for j in range(3)] for i in range(3)]
    one = np.ones_like(a[0][0])
    P0 = _sum4(one, a[0][0], a[1][1], a[2][2])
    P1 = _sum4(one, a[0][0], -a[1][1], -a[2][2])
    P2 = _sum4(one, -a[0][0], a[1][1], -a[2][2])
    P3 = _sum4(one, -a[0][0], -a[1][1], a[2][2])
    k = np.argmax(np.stack([P0, P1, P2, P3], axis=-1), axis=-1)
    s_x, s_y, s_z = a[2][1] - a[1][2], a[0][2] - a[2][0], a[1][0] - a[0][1]
    p_xy, p_xz, p_yz = a[0][1] + a[1][0], a[0][2] + a[2][0], a[1][2] + a[2][1]
    rows = [
        (P0, s_x, s_y, s_z),
        (s_x, P1, p_xy, p_xz),
        (s_y, p_xy, P2, p_yz),
        (s_z, p_xz, p_yz, P3),
    ]
    q = np.select([(k == i)[..., None] for i in range(4)], [np.stack(r, axis=-1) for r in rows])
    return _canonical(q)


def quat_from_matrix(R_A_O) -> np.ndarray:
    """Unit quaternion (w ≥ 0) of ^A R^O, by Shepperd's largest-pivot method."""
    u, r, r_lo = _scaled_norm(_shepperd(R_A_O))
    return _times_ratio(u, np.ones_like(r), r, r_lo)


def quat_from_rotvec(rotvec) -> np.ndarray:
    """Unit quaternion (cos φ/2, sin φ/2 e_a) of the rotation vector φ e_a (2.4).

    Returned as computed (w may be negative for φ > π; q ≡ −q).  The angle
    φ = |φ e_a| is formed in double-double, so it adds no rounding of its own,
    and tiny angles (down to 1e-300) keep full relative accuracy.
    """
    v = as_float_array(rotvec, "rotvec", (3,))
    u, r, r_lo, h, h_lo = _half_angle(v)
    c, s = np.cos(h), np.sin(h)
    w = c - s * h_lo
    # x_i = sin(φ/2) u_i / |u|; a zero vector gives x = 0.
    return np.concatenate([w[..., None], _times_ratio(u, s + c * h_lo, r, r_lo)], axis=-1)


def _rotvec_from_unnormalised(q: np.ndarray) -> np.ndarray:
    """φ e_a of a quaternion with w ≥ 0 of any length (every step is scale-free)."""
    u, r, r_lo = _scaled_norm(q[..., 1:])
    k = np.frexp(np.max(np.abs(q[..., 1:]), axis=-1))[1]
    angle = 2.0 * np.arctan2(np.ldexp(r, k), q[..., 0])
    # φ e_a = φ u / |u|; a zero vector part is the identity, φ e_a = 0.
    return _times_ratio(u, angle, r, r_lo)


def rotvec_from_quat(q) -> np.ndarray:
    """Rotation vector φ e_a with φ in [0, π] of the unit quaternion ``q``."""
    return _rotvec_from_unnormalised(_canonical(_check_quat_raw(q)))


def matrix_from_rotvec(rotvec) -> np.ndarray:
    """^A R^O(φ) of the rotation vector φ = φ e_a, (2.28)–(2.29).

    Computed through the quaternion (the symmetric part, 2 x_i x_j and the
    diagonal), with the antisymmetric part sin φ e_a formed directly from the
    double-double angle, so that tiny angles (down to 1e-300) keep full
    relative accuracy in the off-diagonal entries and the angle survives the
    round trip through :func:`rotvec_from_matrix` within a few ulps.

    Examples
    --------
    (2.29) for e_a = e3 is R3 (Example 2.1):

    >>> bool(np.allclose(matrix_from_rotvec([0, 0, 0.7]), R3(0.7), atol=2 * EPS, rtol=0))
    True
    """
    v = as_float_array(rotvec, "rotvec", (3,))
    u, r, r_lo, h, h_lo = _half_angle(v)
    c, s = np.cos(h), np.sin(h)
    w = c - s * h_lo
    x, y, z = np.moveaxis(_times_ratio(u, s + c * h_lo, r, r_lo), -1, 0)
    phi, phi_lo = 2.0 * h, 2.0 * h_lo
    S = _times_ratio(u, np.sin(phi) + np.cos(phi) * phi_lo, r, r_lo)  # sin φ e_a
    return _matrix_from_parts(w, x, y, z, S)


def rotvec_from_matrix(R_A_O) -> np.ndarray:
    """Rotation vector φ e_a, φ in [0, π], of ^A R^O (inverse of (2.28)).

    At φ = π both ±π e_a describe the rotation; either may be returned.
    Read off the unnormalised Shepperd quaternion: for φ < π/2 that is
    (1 + tr, a_32 − a_23, ...), so φ = 2 atan2(|s|, 1 + tr) with no square root.
    """
    return _rotvec_from_unnormalised(_shepperd(R_A_O))


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
