"""numba-compiled forward dynamics of a scene (issue 30, item 1): the state's rate of
:meth:`mechanics.scenes.forward.Forward.rhs` for the scenes whose bodies and loads all
have a kernel here.

Private: :mod:`mechanics.scenes.compiled` decides whether a model can run here, writes
its *program* (the arrays below) once per run, imports this module on the first
compiled scene (so ``import mechanics.scenes`` never pays for numba) and keeps the
Python path of :class:`~mechanics.scenes.forward.Forward` as the reference, which
the tests hold this one to.

Conventions
-----------
- **The state** is :mod:`mechanics.scenes.state`'s flat vector; the kinds of body here
  are a point (r, v), a free rigid body (r, v, L_A, rows of R_A_O), a pinned one
  (L_C, rows of R_A_O), one on a fixed axis (φ, φ̇: the guide a ``Hinge``) and a fixed
  body (nothing).  Rolling and sliding bodies, tanks and masses that change run on the
  Python path.
- **The program.**  ``bi`` (n, 2) int: each body's kind (:data:`KINDS`) and offset in
  the state; ``bf`` (n, 45) float: its mass, principal moments J (3), the fixed
  position (3), a pinned body's pivot C (3), G from the pivot g_A (3), J_C (9, row by
  row) and J_C⁻¹ (9), a hinged body's axis a, u0, u1 (3 each), its body axes k, j, l,
  h and J_a (its point C in the pivot's columns); ``ops`` (k, 4) int: each effect's
  opcode (:data:`OPCODES`), its bodies i and j (−1: none) and the start p of its
  numbers in ``fp`` (float); ``pairs`` (P, 2) int: the pairs of a ``newton_gravity``
  (its ``i`` the first row, ``j`` their count).  The numbers of each effect are listed
  by its kernel below.
- **The same arithmetic as the reference**, in the reference's order (the effects in
  the model's order, each adding to the forces F at G in space components and the
  moments M_A about G in body components): the tests allow the rounding of the sums.
- Compiled with ``njit(cache=True, error_model="numpy")``, applied after each definition
  so that mutmut mutates the kernels (under mutation numba's JIT is off and they run as
  Python, as :mod:`mechanics._kernels`).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from numba import njit

from .._kernels import (
    STATUS_NONFINITE,
    STATUS_OK,
    STATUS_STEP_TOO_SMALL,
    _all_finite,
    _error_norm,
)

#: the kinds of body with a kernel, by the name :class:`~mechanics.scenes.state.Layout`
#: gives them
KINDS = {"point": 0, "rigid": 1, "pinned": 2, "fixed": 3, "guided": 4}
_POINT, _RIGID, _PINNED, _FIXED, _GUIDED = 0, 1, 2, 3, 4

#: the effects with a kernel, by type (``fixed_point`` makes its body pinned and adds no
#: load)
OPCODES = {
    "fixed_point": 0,
    "gravity": 1,
    "force": 2,
    "torque": 3,
    "spring": 4,
    "damper": 5,
    "drag": 6,
    "newton_gravity": 7,
    "fixed_axis": 0,
    "torsion": 8,
}
_NOOP, _GRAVITY, _FORCE, _TORQUE, _SPRING, _DAMPER, _DRAG, _NEWTON = 0, 1, 2, 3, 4, 5, 6, 7
_TORSION = 8

#: the columns of ``bf``
BF_M, BF_J, BF_RFIX, BF_C, BF_G, BF_JC, BF_JCINV = 0, 1, 4, 7, 10, 13, 22
#: a hinged body's (a guided one on a fixed axis, its C in BF_C): the axis a, u0, u1,
#: its body axes k, j, l (as floats), the distance h of G from the axis and J_a
BF_A, BF_U0, BF_U1, BF_HK, BF_H, BF_JA, BF_SIZE = 31, 34, 37, 40, 43, 44, 45

_compile = njit(cache=True, error_model="numpy")

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]


def _snapshot(y: F64, bi: I64, bf: F64, r: F64, v: F64, L: F64, R: F64, w: F64) -> None:
    """The bodies at the state y (:meth:`Forward.snapshot`): r, v of G (space), L_A
    about G and ω_A (body components), the rows of R_A_O; ω_A = L_A / J (0 on a zero
    moment); a pinned body's ω from J_C⁻¹ L_C, its G and velocity from its attitude."""
    for b in range(bi.shape[0]):
        kind, o = bi[b, 0], bi[b, 1]
        for a in range(3):
            for c in range(3):
                R[b, a, c] = 1.0 if a == c else 0.0
        if kind == _FIXED:
            for c in range(3):
                r[b, c] = bf[b, BF_RFIX + c]
            continue
        if kind == _GUIDED:
            _hinged(y[o], y[o + 1], bf, b, r, v, L, R, w)
            continue
        if kind in (_POINT, _RIGID):
            for c in range(3):
                r[b, c] = y[o + c]
                v[b, c] = y[o + 3 + c]
        if kind == _RIGID:
            for c in range(3):
                L[b, c] = y[o + 6 + c]
                Jc = bf[b, BF_J + c]
                w[b, c] = L[b, c] / Jc if Jc > 0 else 0.0
            for a in range(3):
                for c in range(3):
                    R[b, a, c] = y[o + 9 + 3 * a + c]
        elif kind == _PINNED:
            for a in range(3):
                for c in range(3):
                    R[b, a, c] = y[o + 3 + 3 * a + c]
            for a in range(3):
                w[b, a] = (
                    bf[b, BF_JCINV + 3 * a] * y[o]
                    + bf[b, BF_JCINV + 3 * a + 1] * y[o + 1]
                    + bf[b, BF_JCINV + 3 * a + 2] * y[o + 2]
                )
                L[b, a] = bf[b, BF_J + a] * w[b, a]
            rho = np.empty(3)
            wO = np.empty(3)
            for c in range(3):
                rho[c] = R[b, 0, c] * bf[b, BF_G] + R[b, 1, c] * bf[b, BF_G + 1]
                rho[c] += R[b, 2, c] * bf[b, BF_G + 2]
                wO[c] = R[b, 0, c] * w[b, 0] + R[b, 1, c] * w[b, 1] + R[b, 2, c] * w[b, 2]
            for c in range(3):
                r[b, c] = bf[b, BF_C + c] + rho[c]
            v[b, 0] = wO[1] * rho[2] - wO[2] * rho[1]
            v[b, 1] = wO[2] * rho[0] - wO[0] * rho[2]
            v[b, 2] = wO[0] * rho[1] - wO[1] * rho[0]


_snapshot = _compile(_snapshot)


def _hinged(
    phi: float, phid: float, bf: F64, b: int, r: F64, v: F64, L: F64, R: F64, w: F64
) -> None:
    """A body on a fixed axis at the angle φ turning at φ̇ (:class:`Hinge`): R_A_O's
    rows e_k = a, e_j = cos φ u0 + sin φ u1, e_l = cos φ u1 − sin φ u0; G = C + h e_j,
    v = φ̇ h e_l; ω_A = R (φ̇ a), L_A = J ω_A."""
    k, j, l = int(bf[b, BF_HK]), int(bf[b, BF_HK + 1]), int(bf[b, BF_HK + 2])
    co, si = math.cos(phi), math.sin(phi)
    h = bf[b, BF_H]
    wO = np.empty(3)
    for c in range(3):
        a, u0, u1 = bf[b, BF_A + c], bf[b, BF_U0 + c], bf[b, BF_U1 + c]
        R[b, k, c] = a
        R[b, j, c] = co * u0 + si * u1
        R[b, l, c] = co * u1 - si * u0
        wO[c] = phid * a
    for c in range(3):
        r[b, c] = bf[b, BF_C + c] + h * R[b, j, c]
        v[b, c] = phid * (h * R[b, l, c])
    for c in range(3):
        w[b, c] = R[b, c, 0] * wO[0] + R[b, c, 1] * wO[1] + R[b, c, 2] * wO[2]
        L[b, c] = bf[b, BF_J + c] * w[b, c]


_hinged = _compile(_hinged)


def _to_space(R: F64, b: int, x: F64, out: F64) -> None:
    """out = R_A_Oᵀ x: the space components of body b's vector with body components x."""
    for c in range(3):
        out[c] = R[b, 0, c] * x[0] + R[b, 1, c] * x[1] + R[b, 2, c] * x[2]


_to_space = _compile(_to_space)


def _to_body(R: F64, b: int, x: F64, out: F64) -> None:
    """out = R_A_O x: the body components of a vector with space components x."""
    for a in range(3):
        out[a] = R[b, a, 0] * x[0] + R[b, a, 1] * x[1] + R[b, a, 2] * x[2]


_to_body = _compile(_to_body)


def _cross(a: F64, b: F64, out: F64) -> None:
    """out = a × b."""
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


_cross = _compile(_cross)


def _force(R: F64, F: F64, M: F64, i: int, f: F64, has_at: bool, at: F64) -> None:
    """Add the force f (space) on body i at its point ``at`` (body components about G):
    F_i += f, and off G the moment at × (R f) about G (:meth:`Loads.force`)."""
    for c in range(3):
        F[i, c] += f[c]
    if has_at:
        fb = np.empty(3)
        m = np.empty(3)
        _to_body(R, i, f, fb)
        _cross(at, fb, m)
        for c in range(3):
            M[i, c] += m[c]


_force = _compile(_force)


def _gravity(fp: F64, p: int, bf: F64, F: F64) -> None:
    """``gravity``, fp[p:p+3] = g·d: the force m g d at every centre of mass."""
    for b in range(F.shape[0]):
        for c in range(3):
            F[b, c] += bf[b, BF_M] * fp[p + c]


_gravity = _compile(_gravity)


def _applied(op: int, phase: float, i: int, fp: F64, p: int, R: F64, F: F64, M: F64) -> None:
    """``force`` and ``torque`` while start ≤ phase < end: fp[p:] = start, end, body
    frame (1) or space (0), the value (3), and a force's point: has one (1), at (3)."""
    if not (fp[p] <= phase < fp[p + 1]):
        return
    value = fp[p + 3 : p + 6]
    body_frame = fp[p + 2] != 0.0
    if op == _FORCE:
        f = np.empty(3)
        if body_frame:
            _to_space(R, i, value, f)
        else:
            f[:] = value
        _force(R, F, M, i, f, fp[p + 6] != 0.0, fp[p + 7 : p + 10])
    elif body_frame:
        for c in range(3):
            M[i, c] += value[c]
    else:
        m = np.empty(3)
        _to_body(R, i, value, m)
        for c in range(3):
            M[i, c] += m[c]


_applied = _compile(_applied)


def _end(b: int, has_at: bool, at: F64, r: F64, v: F64, R: F64, w: F64, P: F64, vP: F64) -> None:
    """Body b's point ``at`` (body components about G; G if not has_at) and its
    velocity v_G + ω × (R_A_Oᵀ at), space components (:meth:`Snapshot.point`)."""
    for c in range(3):
        P[c] = r[b, c]
        vP[c] = v[b, c]
    if has_at:
        arm = np.empty(3)
        wO = np.empty(3)
        u = np.empty(3)
        _to_space(R, b, at, arm)
        _to_space(R, b, w[b], wO)
        _cross(wO, arm, u)
        for c in range(3):
            P[c] += arm[c]
            vP[c] += u[c]


_end = _compile(_end)


def _line(
    op: int, i: int, j: int, fp: F64, p: int, r: F64, v: F64, R: F64, w: F64, F: F64, M: F64
) -> None:
    """``spring`` and ``damper`` from P (body i, at) to Q (body j, other_at; j < 0: the
    ground anchor): fp[p:] = stiffness k, rest length ℓ0, damping c, P's point (has one,
    at (3)), Q's point (has one, other_at (3)), the anchor (3).  A spring pulls P toward
    Q with −(k (ℓ − ℓ0) + c (v_P − v_Q)·u) u, u = (P − Q)/ℓ; at ℓ = 0 with −k d − c
    (v_P − v_Q); a damper's force is −c ((v_P − v_Q)·u) u, none at ℓ = 0."""
    k, ell0, c = fp[p], fp[p + 1], fp[p + 2]
    has_at, at = fp[p + 3] != 0.0, fp[p + 4 : p + 7]
    has_other, other_at = fp[p + 7] != 0.0, fp[p + 8 : p + 11]
    P = np.empty(3)
    vP = np.empty(3)
    Q = np.empty(3)
    vQ = np.zeros(3)
    _end(i, has_at, at, r, v, R, w, P, vP)
    if j < 0:
        Q[:] = fp[p + 11 : p + 14]
    else:
        _end(j, has_other, other_at, r, v, R, w, Q, vQ)
    d = P - Q
    dv = vP - vQ
    ell = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
    f = np.empty(3)
    if ell > 0:
        u = d / ell
        rate = dv[0] * u[0] + dv[1] * u[1] + dv[2] * u[2]
        pull = c * rate if op == _DAMPER else k * (ell - ell0) + c * rate
        for a in range(3):
            f[a] = -pull * u[a]
    elif op == _DAMPER:
        f[:] = 0.0
    else:
        for a in range(3):
            f[a] = -k * d[a] - c * dv[a]
    _force(R, F, M, i, f, has_at, at)
    if j >= 0:
        _force(R, F, M, j, -f, has_other, other_at)


_line = _compile(_line)


def _drag(i: int, fp: F64, p: int, v: F64, R: F64, w: F64, F: F64, M: F64) -> None:
    """``drag``: fp[p:p+4] = b₁, b₂, c₁, c₂; −(b₁ + b₂ |v|) v at G, and the moment
    −(c₁ + c₂ |ω|) ω (space components) where c₁ or c₂ is not 0."""
    b1, b2, c1, c2 = fp[p], fp[p + 1], fp[p + 2], fp[p + 3]
    speed = math.sqrt(v[i, 0] * v[i, 0] + v[i, 1] * v[i, 1] + v[i, 2] * v[i, 2])
    for a in range(3):
        F[i, a] += -(b1 + b2 * speed) * v[i, a]
    if c1 != 0.0 or c2 != 0.0:
        wO = np.empty(3)
        _to_space(R, i, w[i], wO)
        spin = math.sqrt(wO[0] * wO[0] + wO[1] * wO[1] + wO[2] * wO[2])
        m = np.empty(3)
        _to_body(R, i, -(c1 + c2 * spin) * wO, m)
        for a in range(3):
            M[i, a] += m[a]


_drag = _compile(_drag)


def _newton(first: int, count: int, G: float, pairs: I64, bf: F64, r: F64, F: F64) -> None:
    """``newton_gravity`` over its pairs (i, j): −G m_i m_j d/|d|³ on i, d = r_i − r_j,
    the opposite on j (all the i's first, then the j's, as the reference adds them)."""
    f = np.empty((count, 3))
    for q in range(count):
        i, j = pairs[first + q, 0], pairs[first + q, 1]
        d = r[i] - r[j]
        dist = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
        s = G * bf[i, BF_M] * bf[j, BF_M] / dist**3
        for c in range(3):
            f[q, c] = -s * d[c]
    for q in range(count):
        for c in range(3):
            F[pairs[first + q, 0], c] += f[q, c]
    for q in range(count):
        for c in range(3):
            F[pairs[first + q, 1], c] -= f[q, c]


_newton = _compile(_newton)


def _torsion(i: int, fp: F64, p: int, phi: float, R: F64, M: F64) -> None:
    """``torsion``: fp[p:p+4] = τ0, the axis a (3); the couple −τ0 φ a (space) on the
    hinged body i at its angle φ."""
    s = -fp[p] * phi
    MO = np.empty(3)
    for c in range(3):
        MO[c] = s * fp[p + 1 + c]
    m = np.empty(3)
    _to_body(R, i, MO, m)
    for c in range(3):
        M[i, c] += m[c]


_torsion = _compile(_torsion)


def _rates(y: F64, bi: I64, bf: F64, v: F64, L: F64, R: F64, w: F64, F: F64, M: F64) -> F64:
    """dy/dt (:meth:`Layout.derivative`): ṙ = v, v̇ = F/m; L̇_A = L_A × ω_A + M_A, Ṙ =
    −[ω_A]× R for a free body; L̇_C = (J_C ω) × ω + M_A + g_A × (R F), Ṙ alike for a
    pinned one; φ̈ = (E·F + a·M_O)/J_a for a hinged one (E = h e_l, M_O = R_A_Oᵀ M_A)."""
    out = np.empty(y.size)
    for b in range(bi.shape[0]):
        kind, o = bi[b, 0], bi[b, 1]
        if kind == _FIXED:
            continue
        if kind == _GUIDED:
            lrow = int(bf[b, BF_HK + 2])
            EF = 0.0
            aM = 0.0
            for c in range(3):
                MO = R[b, 0, c] * M[b, 0] + R[b, 1, c] * M[b, 1] + R[b, 2, c] * M[b, 2]
                EF += (bf[b, BF_H] * R[b, lrow, c]) * F[b, c]
                aM += bf[b, BF_A + c] * MO
            out[o] = y[o + 1]
            out[o + 1] = (EF + aM) / bf[b, BF_JA]
            continue
        wb = w[b]
        if kind in (_POINT, _RIGID):
            m = bf[b, BF_M]
            for c in range(3):
                out[o + c] = v[b, c]
                out[o + 3 + c] = F[b, c] / m
            if kind == _POINT:
                continue
            Lb = L[b]
            out[o + 6] = Lb[1] * wb[2] - Lb[2] * wb[1] + M[b, 0]
            out[o + 7] = Lb[2] * wb[0] - Lb[0] * wb[2] + M[b, 1]
            out[o + 8] = Lb[0] * wb[1] - Lb[1] * wb[0] + M[b, 2]
            oR = o + 9
        else:  # pinned
            LC = np.empty(3)
            for a in range(3):
                LC[a] = (
                    bf[b, BF_JC + 3 * a] * wb[0]
                    + bf[b, BF_JC + 3 * a + 1] * wb[1]
                    + bf[b, BF_JC + 3 * a + 2] * wb[2]
                )
            Fb = np.empty(3)
            _to_body(R, b, F[b], Fb)
            gF = np.empty(3)
            _cross(bf[b, BF_G : BF_G + 3], Fb, gF)
            out[o] = LC[1] * wb[2] - LC[2] * wb[1] + (M[b, 0] + gF[0])
            out[o + 1] = LC[2] * wb[0] - LC[0] * wb[2] + (M[b, 1] + gF[1])
            out[o + 2] = LC[0] * wb[1] - LC[1] * wb[0] + (M[b, 2] + gF[2])
            oR = o + 3
        for c in range(3):
            R0, R1, R2 = R[b, 0, c], R[b, 1, c], R[b, 2, c]
            out[oR + c] = wb[2] * R1 - wb[1] * R2
            out[oR + 3 + c] = wb[0] * R2 - wb[2] * R0
            out[oR + 6 + c] = wb[1] * R0 - wb[0] * R1
    return out


_rates = _compile(_rates)


def _loads(
    phase: float,
    ops: I64,
    fp: F64,
    pairs: I64,
    bf: F64,
    r: F64,
    v: F64,
    R: F64,
    w: F64,
    F: F64,
    M: F64,
    y: F64,
    bi: I64,
) -> None:
    """Add every effect's loads at the snapshot (r, v, R, ω) of the state y to F and
    M_A, in the model's order; ``phase`` decides which applied loads are on."""
    for e in range(ops.shape[0]):
        op, i, j, p = ops[e, 0], ops[e, 1], ops[e, 2], ops[e, 3]
        if op == _GRAVITY:
            _gravity(fp, p, bf, F)
        elif op in (_FORCE, _TORQUE):
            _applied(op, phase, i, fp, p, R, F, M)
        elif op in (_SPRING, _DAMPER):
            _line(op, i, j, fp, p, r, v, R, w, F, M)
        elif op == _DRAG:
            _drag(i, fp, p, v, R, w, F, M)
        elif op == _NEWTON:
            _newton(i, j, fp[p], pairs, bf, r, F)
        elif op == _TORSION:
            _torsion(i, fp, p, y[bi[i, 1]], R, M)


_loads = _compile(_loads)


def scene_rhs(
    t: float, phase: float, y: F64, bi: I64, bf: F64, ops: I64, fp: F64, pairs: I64
) -> F64:  # pragma: no cover (compiled; tested against the reference)
    """The scene's dy/dt at (t, y); ``phase`` decides which applied loads are on (the
    middle of the segment being integrated, or t)."""
    n = bi.shape[0]
    r = np.zeros((n, 3))
    v = np.zeros((n, 3))
    L = np.zeros((n, 3))
    R = np.empty((n, 3, 3))
    w = np.zeros((n, 3))
    _snapshot(y, bi, bf, r, v, L, R, w)
    F = np.zeros((n, 3))
    M = np.zeros((n, 3))
    _loads(phase, ops, fp, pairs, bf, r, v, R, w, F, M, y, bi)
    return _rates(y, bi, bf, v, L, R, w, F, M)


scene_rhs = _compile(scene_rhs)


def scene_accelerations(
    T: F64, Y: F64, bi: I64, bf: F64, ops: I64, fp: F64, pairs: I64
) -> tuple[F64, F64]:  # pragma: no cover (compiled; tested against the reference)
    """At each sample (T[k], Y[k]) (loads on by T[k]): the acceleration of every
    body's G and the loads' force on it, shapes (k, n, 3), space components.  A pinned
    body's a_G = α × ρ + ω × (ω × ρ), ρ = r_G − C, α = R_A_Oᵀ J_C⁻¹ L̇_C
    (:meth:`Forward.point_accelerations`); a fixed body's is zero."""
    k, n = T.size, bi.shape[0]
    A = np.zeros((k, n, 3))
    Fs = np.zeros((k, n, 3))
    r = np.zeros((n, 3))
    v = np.zeros((n, 3))
    L = np.zeros((n, 3))
    R = np.empty((n, 3, 3))
    w = np.zeros((n, 3))
    F = np.zeros((n, 3))
    M = np.zeros((n, 3))
    wO = np.empty(3)
    alpha = np.empty(3)
    wdot = np.empty(3)
    rho = np.empty(3)
    u = np.empty(3)
    u2 = np.empty(3)
    for s in range(k):
        y = np.ascontiguousarray(Y[s])
        r[:] = 0.0
        v[:] = 0.0
        L[:] = 0.0
        w[:] = 0.0
        F[:] = 0.0
        M[:] = 0.0
        _snapshot(y, bi, bf, r, v, L, R, w)
        _loads(T[s], ops, fp, pairs, bf, r, v, R, w, F, M, y, bi)
        dy = _rates(y, bi, bf, v, L, R, w, F, M)
        for b in range(n):
            kind, o = bi[b, 0], bi[b, 1]
            Fs[s, b] = F[b]
            if kind in (_POINT, _RIGID):
                A[s, b] = dy[o + 3 : o + 6]
            elif kind == _PINNED:
                for a in range(3):
                    wdot[a] = (
                        bf[b, BF_JCINV + 3 * a] * dy[o]
                        + bf[b, BF_JCINV + 3 * a + 1] * dy[o + 1]
                        + bf[b, BF_JCINV + 3 * a + 2] * dy[o + 2]
                    )
                _to_space(R, b, w[b], wO)
                _to_space(R, b, wdot, alpha)
                for c in range(3):
                    rho[c] = r[b, c] - bf[b, BF_C + c]
                _cross(alpha, rho, u)
                _cross(wO, rho, u2)
                _cross(wO, u2, rho)
                for c in range(3):
                    A[s, b, c] = u[c] + rho[c]
    return A, Fs


scene_accelerations = _compile(scene_accelerations)


def _stages(
    tc: float,
    y: F64,
    hh: float,
    A: F64,
    C: F64,
    first: int,
    last: int,
    K: F64,
    tmp: F64,
    phase: float,
    bi: I64,
    bf: F64,
    ops: I64,
    fp: F64,
    pairs: I64,
) -> None:
    """K[s] = f(tc + c_s h, y + h Σ_{j<s} a_sj k_j) for s in [first, last)."""
    for s in range(first, last):
        for i in range(y.size):
            acc = 0.0
            for j in range(s):
                acc += K[j, i] * A[s, j]
            tmp[i] = y[i] + hh * acc
        K[s] = scene_rhs(tc + C[s] * hh, phase, tmp, bi, bf, ops, fp, pairs)


_stages = _compile(_stages)


def scene_step(
    tc: float,
    y: F64,
    f0: F64,
    h_abs: float,
    t_end: float,
    rtol: float,
    atol: float,
    A: F64,
    B: F64,
    C: F64,
    E3: F64,
    E5: F64,
    D: F64,
    ctrl: F64,
    phase: float,
    bi: I64,
    bf: F64,
    ops: I64,
    fp: F64,
    pairs: I64,
    y_new: F64,
    f_new: F64,
    F: F64,
) -> tuple[int, float, float, int, int]:  # pragma: no cover (compiled; tested)
    """One accepted DOP853 step of the scene from (tc, y), f0 = f(tc, y), towards t_end,
    rejected attempts inside, and its continuous extension: the step control of the
    reference's ``_dop853_advance`` (β = 0, no max_step) and the interpolant of its
    ``_dop853_dense`` (3 extra stages), as :mod:`mechanics._kernels_rhs`'s DOP853 loop.
    y_new, f_new = f(t_new, y_new) and F (7, n) are filled.  Returns (status, t_new,
    h_next, evals, rejected); status as :mod:`mechanics._kernels` (0 done; 1 non-finite;
    2 the step fell below 10 ulp(tc))."""
    n = y.size
    ns = B.size
    n_ext = A.shape[0]
    safety, min_factor, max_factor, exponent = ctrl[0], ctrl[1], ctrl[2], ctrl[3]
    K = np.empty((n_ext, n))
    tmp = np.empty(n)
    min_step = 10.0 * (np.nextafter(abs(tc), np.inf) - abs(tc))
    if h_abs < min_step:
        h_abs = min_step
    was_rejected = False
    evals = 0
    rejected = 0
    while True:
        t_new = tc + h_abs
        if t_new >= t_end:
            t_new = t_end
        hh = t_new - tc
        K[0] = f0
        _stages(tc, y, hh, A, C, 1, ns, K, tmp, phase, bi, bf, ops, fp, pairs)
        for i in range(n):
            acc = 0.0
            for j in range(ns):
                acc += K[j, i] * B[j]
            y_new[i] = y[i] + hh * acc
        K[ns] = scene_rhs(t_new, phase, y_new, bi, bf, ops, fp, pairs)
        evals += ns
        err = _error_norm(K[: ns + 1], E5, E3, hh, y, y_new, rtol, atol, 1)
        if not math.isfinite(err):
            return STATUS_NONFINITE, t_new, h_abs, evals, rejected
        if err < 1.0:
            factor = max_factor if err == 0.0 else min(max_factor, safety * err**exponent)
            if was_rejected:
                factor = min(1.0, factor)
            if not _all_finite(y_new):
                return STATUS_NONFINITE, t_new, h_abs, evals, rejected
            h_abs = hh * factor
            break
        rejected += 1
        was_rejected = True
        h_abs = hh * max(min_factor, safety * err**exponent)
        if h_abs < min_step:
            return STATUS_STEP_TOO_SMALL, t_new, h_abs, evals, rejected
    f_new[:] = K[ns]
    _stages(tc, y, hh, A, C, ns + 1, n_ext, K, tmp, phase, bi, bf, ops, fp, pairs)
    evals += n_ext - ns - 1
    for i in range(n):
        dlt = y_new[i] - y[i]
        F[0, i] = dlt
        F[1, i] = hh * K[0, i] - dlt
        F[2, i] = 2 * dlt - hh * (K[ns, i] + K[0, i])
        for r in range(D.shape[0]):
            acc = 0.0
            for q in range(n_ext):
                acc += D[r, q] * K[q, i]
            F[3 + r, i] = hh * acc
    if not _all_finite(F.ravel()):
        return STATUS_NONFINITE, t_new, h_abs, evals, rejected
    return STATUS_OK, t_new, h_abs, evals, rejected


scene_step = _compile(scene_step)
