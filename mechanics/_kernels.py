"""numba-compiled inner loops of :mod:`mechanics.integrators` (issue 15).

Private: :mod:`mechanics.integrators` validates every input, imports this module on the
first compiled call (so ``import mechanics`` never pays for numba) and falls back to its
pure-numpy reference path, with one warning, if numba is missing or a compilation fails.

Conventions
-----------
- **One source of truth.**  No coefficient is written here: the Dormand–Prince tableau
  (scipy's, as the reference uses it), the splitting schedules (Strang and the triple
  jumps of :func:`mechanics.integrators._splitting._schedule`) and the step-control constants are
  passed in as arguments by :mod:`mechanics.integrators`.
- **The known problem.**  The right-hand side compiled here is the torque-free rigid
  body of :func:`mechanics.integrators.free_rigid_body_rhs` (state (L_A, rows of
  ^A R^O), 12 numbers per body, moments ``J`` per body), written out as the
  reference's gathers: dL_i = L_{i+1} ω_{i+2} − L_{i+2} ω_{i+1}, row r of dR is
  ω_{r+2} R_{r+1} − ω_{r+1} R_{r+2}.  A Python right-hand side is not compiled.
- **Arrays.**  States are flat float64 arrays of 12 · bodies numbers; ``J`` is
  (bodies, 3).  The adaptive step is common to the batch: the error norm is the RMS
  norm over each of ``groups`` equal consecutive slices (the members) and its
  maximum over them, as the reference.
- **Status codes** instead of exceptions (their messages need the reference's
  context): 0 done; 1 a non-finite state or rate; 2 the step fell below 10 ulp(t);
  3 ``max_steps`` reached.  On any code but 0 the caller re-runs the reference path,
  which raises the error naming the time, so a compiled run never returns a wrong
  result.
- Compiled with ``njit(cache=True, error_model="numpy")``: the machine code is cached in
  ``mechanics/__pycache__`` (numba's per-file index, safe under concurrent writers).
  Applied after each definition (``f = _compile(f)``), not as a decorator, so that
  mutmut mutates the kernels: under mutation (``docs/mutation.md``) numba's JIT is off
  (``NUMBA_DISABLE_JIT=1``), ``_compile`` returns the Python function, and the kernels
  run as plain Python against the same tests.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from numba import njit

STATUS_OK = 0
STATUS_NONFINITE = 1
STATUS_STEP_TOO_SMALL = 2
STATUS_MAX_STEPS = 3

#: how every kernel is compiled (lazily, on its first call; cached on disk)
_compile = njit(cache=True, error_model="numpy")


def _frb_rhs(
    J: npt.NDArray[np.float64], y: npt.NDArray[np.float64], out: npt.NDArray[np.float64]
) -> None:  # pragma: no cover (compiled; tested against the reference)
    """out = the free rigid body's dy/dt for every body of the flat state y."""
    for b in range(J.shape[0]):
        o = 12 * b
        w0 = y[o] / J[b, 0]
        w1 = y[o + 1] / J[b, 1]
        w2 = y[o + 2] / J[b, 2]
        out[o] = y[o + 1] * w2 - y[o + 2] * w1
        out[o + 1] = y[o + 2] * w0 - y[o] * w2
        out[o + 2] = y[o] * w1 - y[o + 1] * w0
        for c in range(3):
            r0 = y[o + 3 + c]
            r1 = y[o + 6 + c]
            r2 = y[o + 9 + c]
            out[o + 3 + c] = r1 * w2 - r2 * w1
            out[o + 6 + c] = r2 * w0 - r0 * w2
            out[o + 9 + c] = r0 * w1 - r1 * w0


_frb_rhs = _compile(_frb_rhs)


def _all_finite(v: npt.NDArray[np.float64]) -> bool:  # pragma: no cover
    for x in v:  # noqa: SIM110 (a loop numba compiles to a plain loop)
        if not math.isfinite(x):
            return False
    return True


_all_finite = _compile(_all_finite)


def rk4_free_body(
    J: npt.NDArray[np.float64],
    y0: npt.NDArray[np.float64],
    t: npt.NDArray[np.float64],
    ns: npt.NDArray[np.int64],
    ys: npt.NDArray[np.float64],
) -> tuple[int, int]:  # pragma: no cover
    """RK4 on the free rigid body: ns[k] equal steps over [t[k], t[k+1]]; the states
    at the output times go into ys (len(t), size).  Returns (status, steps)."""
    n = y0.size
    y = y0.copy()
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    tmp = np.empty(n)
    ys[0] = y
    steps = 0
    for k in range(t.size - 1):
        m = ns[k]
        hk = (t[k + 1] - t[k]) / m
        half = 0.5 * hk
        sixth = hk / 6.0
        for _ in range(m):
            _frb_rhs(J, y, k1)
            for i in range(n):
                tmp[i] = y[i] + half * k1[i]
            _frb_rhs(J, tmp, k2)
            for i in range(n):
                tmp[i] = y[i] + half * k2[i]
            _frb_rhs(J, tmp, k3)
            for i in range(n):
                tmp[i] = y[i] + hk * k3[i]
            _frb_rhs(J, tmp, k4)
            for i in range(n):
                y[i] = y[i] + sixth * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i])
        steps += m
        if not _all_finite(y):
            return STATUS_NONFINITE, steps
        ys[k + 1] = y
    return STATUS_OK, steps


rk4_free_body = _compile(rk4_free_body)


def _error_norm(
    K: npt.NDArray[np.float64],
    E5: npt.NDArray[np.float64],
    E3: npt.NDArray[np.float64],
    h: float,
    y: npt.NDArray[np.float64],
    y_new: npt.NDArray[np.float64],
    rtol: float,
    atol: float,
    groups: int,
) -> float:  # pragma: no cover
    """The DOP853 error norm (the reference's ``_dop853_error``), max over members."""
    n = y.size
    gs = n // groups
    worst = 0.0
    for g in range(groups):
        e5n = 0.0
        e3n = 0.0
        for i in range(g * gs, (g + 1) * gs):
            scale = atol + max(abs(y[i]), abs(y_new[i])) * rtol
            s5 = 0.0
            s3 = 0.0
            for s in range(K.shape[0]):
                s5 += K[s, i] * E5[s]
                s3 += K[s, i] * E3[s]
            s5 /= scale
            s3 /= scale
            e5n += s5 * s5
            e3n += s3 * s3
        if e5n == 0.0:
            continue
        err = abs(h) * e5n / math.sqrt((e5n + 0.01 * e3n) * gs)
        if not err <= worst:  # NaN propagates
            worst = err
    return worst


_error_norm = _compile(_error_norm)


def _member_rms_min_max(
    v: npt.NDArray[np.float64], scale: npt.NDArray[np.float64], groups: int, want_max: bool
) -> float:  # pragma: no cover
    n = v.size
    gs = n // groups
    out = -1.0
    for g in range(groups):
        acc = 0.0
        for i in range(g * gs, (g + 1) * gs):
            x = v[i] / scale[i]
            acc += x * x
        r = math.sqrt(acc / gs)
        if out < 0.0 or (want_max and r > out) or (not want_max and r < out):
            out = r
    return out


_member_rms_min_max = _compile(_member_rms_min_max)


def dop853_free_body(
    J: npt.NDArray[np.float64],
    y0: npt.NDArray[np.float64],
    t: npt.NDArray[np.float64],
    h0: float,
    rtol: float,
    atol: float,
    groups: int,
    max_steps: int,
    A: npt.NDArray[np.float64],
    B: npt.NDArray[np.float64],
    C: npt.NDArray[np.float64],
    E3: npt.NDArray[np.float64],
    E5: npt.NDArray[np.float64],
    D: npt.NDArray[np.float64],
    ctrl: npt.NDArray[np.float64],
    ys: npt.NDArray[np.float64],
) -> tuple[int, int, int, int]:  # pragma: no cover
    """DOP853 on the free rigid body (the reference's ``_integrate_dop853``): steps
    set by the error control towards t[-1], outputs inside a step from its 7th-order
    continuous extension.  A (16, 16), C (16,) the extended tableau, D (4, 16) the
    interpolant's matrix.  h0 ≤ 0: Hairer's initial step.  ctrl = (safety, min
    factor, max factor, exponent).  Returns (status, steps, evals, rejected)."""
    n = y0.size
    ns = B.size  # 12 stages
    n_ext = A.shape[0]  # 16: the dense output's 3 extra stages after f_new
    F = np.empty((7, n))
    safety, min_factor, max_factor, exponent = ctrl[0], ctrl[1], ctrl[2], ctrl[3]
    y = y0.copy()
    y_new = np.empty(n)
    tmp = np.empty(n)
    K = np.empty((n_ext, n))
    f0 = np.empty(n)
    ys[0] = y
    _frb_rhs(J, y, f0)
    evals = 1
    if not _all_finite(f0):
        return STATUS_NONFINITE, 0, evals, 0
    tc = t[0]
    if h0 > 0.0:
        h_abs = h0
    else:  # Hairer's starting step, batch-aware as the reference's
        scale = np.empty(n)
        for i in range(n):
            scale[i] = atol + abs(y[i]) * rtol
        d0 = _member_rms_min_max(y, scale, groups, False)
        d1 = _member_rms_min_max(f0, scale, groups, True)
        hs = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
        hs = min(hs, t[t.size - 1] - tc)
        for i in range(n):
            tmp[i] = y[i] + hs * f0[i]
        f1 = np.empty(n)
        _frb_rhs(J, tmp, f1)
        evals += 1
        for i in range(n):
            f1[i] = f1[i] - f0[i]
        d2 = _member_rms_min_max(f1, scale, groups, True) / hs
        if d1 <= 1e-15 and d2 <= 1e-15:
            h1 = max(1e-6, hs * 1e-3)
        else:
            h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
        h_abs = min(100 * hs, h1, t[t.size - 1] - tc)
    steps = 0
    rejected = 0
    nt = t.size
    t_end = t[nt - 1]
    k = 1  # the next output
    while k < nt:
        min_step = 10.0 * (np.nextafter(abs(tc), np.inf) - abs(tc))
        if h_abs < min_step:
            h_abs = min_step
        was_rejected = False
        while True:
            t_new = tc + h_abs
            if t_new >= t_end:
                t_new = t_end
            hh = t_new - tc
            for i in range(n):
                K[0, i] = f0[i]
            for s in range(1, ns):
                for i in range(n):
                    acc = 0.0
                    for j in range(s):
                        acc += K[j, i] * A[s, j]
                    tmp[i] = y[i] + hh * acc
                _frb_rhs(J, tmp, K[s])
            for i in range(n):
                acc = 0.0
                for j in range(ns):
                    acc += K[j, i] * B[j]
                y_new[i] = y[i] + hh * acc
            _frb_rhs(J, y_new, K[ns])
            evals += ns
            err = _error_norm(K[: ns + 1], E5, E3, hh, y, y_new, rtol, atol, groups)
            if not math.isfinite(err):
                return STATUS_NONFINITE, steps, evals, rejected
            if err < 1.0:
                factor = max_factor if err == 0.0 else min(max_factor, safety * err**exponent)
                if was_rejected:
                    factor = min(1.0, factor)
                if not _all_finite(y_new):
                    return STATUS_NONFINITE, steps, evals, rejected
                h_abs = hh * factor
                break
            rejected += 1
            was_rejected = True
            h_abs = hh * max(min_factor, safety * err**exponent)
            if h_abs < min_step:
                return STATUS_STEP_TOO_SMALL, steps, evals, rejected
        steps += 1
        j = k
        while j < nt and t[j] < t_new:
            j += 1
        if j > k:  # outputs inside the step: its continuous extension
            for q in range(ns + 1, n_ext):
                for i in range(n):
                    acc = 0.0
                    for r in range(q):
                        acc += K[r, i] * A[q, r]
                    tmp[i] = y[i] + hh * acc
                _frb_rhs(J, tmp, K[q])
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
                return STATUS_NONFINITE, steps, evals, rejected
            for m in range(k, j):
                x = (t[m] - tc) / hh
                for i in range(n):
                    v = 0.0
                    for r in range(7):
                        v += F[6 - r, i]
                        v *= x if r % 2 == 0 else 1.0 - x
                    ys[m, i] = v + y[i]
        if j < nt and t[j] == t_new:
            for i in range(n):
                ys[j, i] = y_new[i]
            j += 1
        k = j
        for i in range(n):
            y[i] = y_new[i]
            f0[i] = K[ns, i]
        tc = t_new
        if steps >= max_steps and k < nt:
            return STATUS_MAX_STEPS, steps, evals, rejected
    return STATUS_OK, steps, evals, rejected


dop853_free_body = _compile(dop853_free_body)


def _project(
    L: npt.NDArray[np.float64], R: npt.NDArray[np.float64], norm0: float
) -> None:  # pragma: no cover
    """|L| ← norm0 and one Newton–Schulz step R ← R − ½ (R Rᵀ − 1) R (the reference's
    ``_project_batch``, in its order of operations)."""
    nrm = math.hypot(math.hypot(L[0], L[1]), L[2])  # (no overflow before |L| does)
    if nrm > 0.0:
        f = norm0 / nrm
        L[0] *= f
        L[1] *= f
        L[2] *= f
    P = np.empty((3, 3))
    for a in range(3):
        for b in range(3):
            P[a, b] = R[a, 0] * R[b, 0] + R[a, 1] * R[b, 1] + R[a, 2] * R[b, 2]
        P[a, a] -= 1.0
    Q = np.empty((3, 3))
    for a in range(3):
        for b in range(3):
            Q[a, b] = P[a, 0] * R[0, b] + P[a, 1] * R[1, b] + P[a, 2] * R[2, b]
    for a in range(3):
        for b in range(3):
            R[a, b] = R[a, b] - 0.5 * Q[a, b]


_project = _compile(_project)


def _flow(
    J: npt.NDArray[np.float64],
    L: npt.NDArray[np.float64],
    R: npt.NDArray[np.float64],
    i: int,
    c: float,
) -> None:  # pragma: no cover
    """The exact flow of H_i for a time c: L and the rows of R turn about axis i."""
    a = (i + 1) % 3
    b = (i + 2) % 3
    ang = c * (L[i] / J[i])
    co = math.cos(ang)
    si = math.sin(ang)
    La = L[a]
    Lb = L[b]
    L[a] = co * La + si * Lb
    L[b] = co * Lb - si * La
    for m in range(3):
        Ra = R[a, m]
        Rb = R[b, m]
        R[a, m] = co * Ra + si * Rb
        R[b, m] = co * Rb - si * Ra


_flow = _compile(_flow)


def _flow_compensated(
    J: npt.NDArray[np.float64],
    L: npt.NDArray[np.float64],
    R: npt.NDArray[np.float64],
    cL: npt.NDArray[np.float64],
    cR: npt.NDArray[np.float64],
    i: int,
    c: float,
) -> None:  # pragma: no cover
    """The reference's ``_flow_compensated``: the turn about axis i as an increment
    ((cos − 1) x + sin y, cos − 1 = −2 sin²(θ/2)) added by Kahan summation, the
    compensations cL (3,), cR (3, 3) carried from flow to flow."""
    a = (i + 1) % 3
    b = (i + 2) % 3
    ang = c * (L[i] / J[i])
    s2 = math.sin(0.5 * ang)
    cm = -2.0 * s2 * s2
    si = math.sin(ang)
    La = L[a]
    Lb = L[b]
    y = (cm * La + si * Lb) - cL[a]
    s = La + y
    cL[a] = (s - La) - y
    L[a] = s
    y = (cm * Lb - si * La) - cL[b]
    s = Lb + y
    cL[b] = (s - Lb) - y
    L[b] = s
    for m in range(3):
        Ra = R[a, m]
        Rb = R[b, m]
        y = (cm * Ra + si * Rb) - cR[a, m]
        s = Ra + y
        cR[a, m] = (s - Ra) - y
        R[a, m] = s
        y = (cm * Rb - si * Ra) - cR[b, m]
        s = Rb + y
        cR[b, m] = (s - Rb) - y
        R[b, m] = s


_flow_compensated = _compile(_flow_compensated)


def splitting_free_body(
    J: npt.NDArray[np.float64],
    L0: npt.NDArray[np.float64],
    R0: npt.NDArray[np.float64],
    norm0: npt.NDArray[np.float64],
    t: npt.NDArray[np.float64],
    ns: npt.NDArray[np.int64],
    axes: npt.NDArray[np.int64],
    fracs: npt.NDArray[np.float64],
    head: float,
    every: int,
    compensated: bool,
    ys: npt.NDArray[np.float64],
) -> tuple[int, int]:  # pragma: no cover
    """The Lie–Poisson splitting of each body (the reference's run and projection):
    axes/fracs the schedule's middle flows, head its opening H1 fraction; ns[k]
    steps over [t[k], t[k+1]], the drift removed every ``every`` steps and at each
    output (``compensated``: the flows added by Kahan summation, no projection).
    ys (len(t), bodies, 12).  Returns (status, flows)."""
    nb = J.shape[0]
    flows = 0
    L = np.empty(3)
    R = np.empty((3, 3))
    cL = np.zeros(3)
    cR = np.zeros((3, 3))
    Jb = np.empty(3)
    status = STATUS_OK
    for b in range(nb):
        for i in range(3):
            L[i] = L0[b, i]
            Jb[i] = J[b, i]
            cL[i] = 0.0
            for m in range(3):
                R[i, m] = R0[b, i, m]
                cR[i, m] = 0.0
        for k in range(t.size - 1):
            n = ns[k]
            hk = (t[k + 1] - t[k]) / n
            hh = head * hk
            join = 2.0 * head * hk
            for first in range(0, n, every):
                m = min(every, n - first)
                for j in range(m):
                    if compensated:
                        if j == 0:
                            _flow_compensated(Jb, L, R, cL, cR, 0, hh)
                        for q in range(axes.size):
                            _flow_compensated(Jb, L, R, cL, cR, axes[q], fracs[q] * hk)
                        _flow_compensated(Jb, L, R, cL, cR, 0, join if j < m - 1 else hh)
                    else:
                        if j == 0:
                            _flow(Jb, L, R, 0, hh)
                        for q in range(axes.size):
                            _flow(Jb, L, R, axes[q], fracs[q] * hk)
                        _flow(Jb, L, R, 0, join if j < m - 1 else hh)
                    flows += axes.size + 1 + (j == 0)
                if not compensated:
                    _project(L, R, norm0[b])
            ys[k + 1, b, 0] = L[0]
            ys[k + 1, b, 1] = L[1]
            ys[k + 1, b, 2] = L[2]
            for i in range(3):
                for m in range(3):
                    ys[k + 1, b, 3 + 3 * i + m] = R[i, m]
            for i in range(12):
                if not math.isfinite(ys[k + 1, b, i]):
                    status = STATUS_NONFINITE
    return status, flows


splitting_free_body = _compile(splitting_free_body)
