"""The Lie–Poisson splitting of the free rigid body into exact axis rotations
(Strang, Yoshida's triple jumps), reference and compiled.

Part of :mod:`mechanics.integrators` (its docstring states the conventions).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from typing import Any, TypeAlias

import numpy as np
import numpy.typing as npt

from .._floats import Floats
from .._validate import as_float_array, broadcast_checked
from ..errors import ResultOverflowError, UnknownOptionError
from ..rotation import check_rotation
from ._compiled import _run_compiled
from ._grid import (
    MAX_STEPS,
    _check_step_budget,
    _check_times,
    _positive_scalar,
    _substep_counts,
    _substeps,
)
from ._rigid_body import _check_moments, rigid_body_state
from ._solution import FloatArray, Solution, _solution

#: Orders of :func:`free_rigid_body_splitting` (Strang, Yoshida 4, 6, 8).
SPLITTING_ORDERS = (2, 4, 6, 8)

#: Sub-flows (axis, duration or fraction of h) in order.
Flows: TypeAlias = list[tuple[int, float]]


def _merge(seq: Iterable[tuple[int, float]]) -> Flows:
    out: list[list[Any]] = []
    for axis, c in seq:
        if out and out[-1][0] == axis:
            out[-1][1] += c
        else:
            out.append([axis, c])
    return [(a, c) for a, c in out]


def _strang(tau: float) -> Flows:
    return [(0, tau / 2), (1, tau / 2), (2, tau), (1, tau / 2), (0, tau / 2)]


def _triple_jump(step: Callable[[float], Flows], p: int) -> Callable[[float], Flows]:
    """Yoshida's symmetric composition Φ(γ1 τ) Φ(γ2 τ) Φ(γ1 τ), order p → p + 2."""
    g1 = 1.0 / (2.0 - 2.0 ** (1.0 / (p + 1)))
    g2 = 1.0 - 2.0 * g1

    def composed(tau: float) -> Flows:
        return step(g1 * tau) + step(g2 * tau) + step(g1 * tau)

    return composed


def _schedule(order: int) -> Flows:
    """(axis, fraction of h) of one step, adjacent same-axis flows merged."""
    step: Callable[[float], Flows] = _strang
    for p in range(2, order, 2):
        step = _triple_jump(step, p)
    return _merge(step(1.0))


_SCHEDULES = {p: _schedule(p) for p in SPLITTING_ORDERS}

#: Steps between two removals of the rounding drift of the splitting.  A steady
#: rotation repeats one rounded (cos, sin) pair, whose c² + s² − 1 (up to ~1 eps)
#: then adds up linearly: |L| and R Rᵀ would drift by up to 1 eps per sub-flow
#: (measured: 293 eps after 4050 flows of a spherical top).  Every this many steps
#: |L| is rescaled to |L0| and R takes one Newton–Schulz step
#: R ← R − ½ (R Rᵀ − 1) R (as :func:`mechanics.rotation.nearest_rotation`), which
#: moves them by their rounding drift only (≤ 64 × 36 eps), never by the method's
#: truncation error, since the exact sub-flows keep both.
PROJECT_EVERY = 64


def _project_scalar(L: list[float], R: list[list[float]], norm0: float) -> None:
    # |L| by hypot, as norm0: a sum of squares overflows from |L| ~ 1.3e154, and L would
    # then be scaled to 0 (norm0 / inf), silently
    n = float(np.hypot(np.hypot(L[0], L[1]), L[2]))
    if n > 0.0:
        f = norm0 / n
        L[:] = [L[0] * f, L[1] * f, L[2] * f]
    M = np.array(R)
    M = M - 0.5 * ((M @ M.T - np.eye(3)) @ M)
    R[:] = M.tolist()


def _project_batch(L: list[FloatArray], R: list[FloatArray], norm0: FloatArray) -> None:
    n = np.hypot(np.hypot(L[0], L[1]), L[2])  # (see _project_scalar)
    f = np.where(n > 0.0, norm0 / np.where(n > 0.0, n, 1.0), 1.0)
    L[:] = [L[0] * f, L[1] * f, L[2] * f]
    M = np.stack(R, axis=-2)
    M = M - 0.5 * ((M @ np.swapaxes(M, -1, -2) - np.eye(3)) @ M)
    R[:] = [M[..., 0, :], M[..., 1, :], M[..., 2, :]]


_NEXT = ((1, 2), (2, 0), (0, 1))  # (j, k) of the turn about axis i


def _interval_flows(seq_h: Flows, head: float, join: float, n: int) -> tuple[Flows, Flows, Flows]:
    """The sub-flows of n steps, as (first step, inner step, last step) lists: the
    closing H1 half-flow of a step and the opening one of the next are one flow."""
    if n == 1:
        return [(0, head), *seq_h, (0, head)], [], []
    return [(0, head), *seq_h, (0, join)], [*seq_h, (0, join)], [*seq_h, (0, head)]


def _split_run_scalar(
    J: list[float],
    L: list[float],
    R: list[list[float]],
    seq_h: Flows,
    head: float,
    join: float,
    n: int,
) -> int:
    """One body in Python floats (math.cos/sin): n steps of the schedule."""
    cos, sin = math.cos, math.sin
    first, inner, last = _interval_flows(seq_h, head, join, n)
    for j in range(n):
        this = first if j == 0 else (inner if j < n - 1 else last)
        for i, c in this:
            a, b = _NEXT[i]
            ang = c * (L[i] / J[i])
            co, si = cos(ang), sin(ang)
            La, Lb = L[a], L[b]
            L[a] = co * La + si * Lb
            L[b] = co * Lb - si * La
            Ra, Rb = R[a], R[b]
            R[a] = [co * Ra[0] + si * Rb[0], co * Ra[1] + si * Rb[1], co * Ra[2] + si * Rb[2]]
            R[b] = [co * Rb[0] - si * Ra[0], co * Rb[1] - si * Ra[1], co * Rb[2] - si * Ra[2]]
    return len(first) + max(n - 2, 0) * len(inner) + (len(last) if n > 1 else 0)


def _kahan_add(x: Floats, d: Floats, c: Floats) -> tuple[Floats, Floats]:
    """x + d by Kahan summation with the running compensation c: (sum, new c)."""
    y = d - c
    s = x + y
    return s, (s - x) - y


def _split_run_compensated(
    J: list[Floats],
    L: list[Floats],
    R: list[list[Floats]],
    cL: list[Floats],
    cR: list[list[Floats]],
    seq_h: Flows,
    head: float,
    join: float,
    n: int,
    sin: Callable[[Any], Any],
) -> int:
    """n steps of the schedule, each turn added as an increment by Kahan summation
    (the compiled ``_flow_compensated``): L, cL lists of 3, R, cR lists of 3 rows;
    floats (``sin = math.sin``) or arrays of a batch (``np.sin``)."""
    first, inner, last = _interval_flows(seq_h, head, join, n)
    for j in range(n):
        this = first if j == 0 else (inner if j < n - 1 else last)
        for i, c in this:
            a, b = _NEXT[i]
            ang = c * (L[i] / J[i])
            s2 = sin(0.5 * ang)
            cm = -2.0 * s2 * s2
            si = sin(ang)
            La, Lb = L[a], L[b]
            L[a], cL[a] = _kahan_add(La, cm * La + si * Lb, cL[a])
            L[b], cL[b] = _kahan_add(Lb, cm * Lb - si * La, cL[b])
            for m in range(3):
                Ra, Rb = R[a][m], R[b][m]
                R[a][m], cR[a][m] = _kahan_add(Ra, cm * Ra + si * Rb, cR[a][m])
                R[b][m], cR[b][m] = _kahan_add(Rb, cm * Rb - si * Ra, cR[b][m])
    return len(first) + max(n - 2, 0) * len(inner) + (len(last) if n > 1 else 0)


def _split_run_batch(
    J: list[FloatArray],
    L: list[FloatArray],
    R: list[FloatArray],
    seq_h: Flows,
    head: float,
    join: float,
    n: int,
) -> int:
    """A batch: L a list of 3 arrays (batch), R a list of 3 row arrays (batch, 3)."""
    first, inner, last = _interval_flows(seq_h, head, join, n)
    for j in range(n):
        this = first if j == 0 else (inner if j < n - 1 else last)
        for i, c in this:
            a, b = _NEXT[i]
            ang = c * (L[i] / J[i])
            co, si = np.cos(ang), np.sin(ang)
            La, Lb = L[a], L[b]
            L[a] = co * La + si * Lb
            L[b] = co * Lb - si * La
            co3, si3 = co[..., None], si[..., None]
            Ra, Rb = R[a], R[b]
            R[a] = co3 * Ra + si3 * Rb
            R[b] = co3 * Rb - si3 * Ra
    return len(first) + max(n - 2, 0) * len(inner) + (len(last) if n > 1 else 0)


def _splitting_compiled(
    Jm: FloatArray,
    L: FloatArray,
    R: FloatArray,
    tt: FloatArray,
    hf: float,
    batch: tuple[int, ...],
    scalar: bool,
    middle: Flows,
    head: float,
    compensated: bool = False,
) -> tuple[FloatArray, int, int] | None:
    """The splitting's compiled run: (ys (n, bodies, 12), steps, flows), or None (the
    reference path then runs, and raises if the state overflowed)."""
    Jb = np.ascontiguousarray(np.broadcast_to(Jm, (*batch, 3)).reshape(-1, 3))
    Lb = np.ascontiguousarray(np.broadcast_to(L, (*batch, 3)).reshape(-1, 3))
    Rb = np.ascontiguousarray(np.broadcast_to(R, (*batch, 3, 3)).reshape(-1, 3, 3))
    if scalar:  # the reference's norms: math.hypot for one body, nested np.hypot for many
        norm0 = np.array([math.hypot(*Lb[0].tolist())])
    else:
        norm0 = np.hypot(np.hypot(Lb[:, 0], Lb[:, 1]), Lb[:, 2])
    ns = _substep_counts(tt, hf)
    axes = np.array([i for i, _ in middle], dtype=np.int64)
    fracs = np.array([c for _, c in middle], dtype=np.float64)
    ys = np.empty((tt.shape[0], Jb.shape[0], 12))
    done = _run_compiled(
        "splitting_free_body",
        Jb,
        Lb,
        Rb,
        norm0,
        tt,
        ns,
        axes,
        fracs,
        float(head),
        PROJECT_EVERY,
        bool(compensated),
        ys,
    )
    if done is None or done[0] != 0:
        return None
    return ys, int(ns.sum()), done[1] // Jb.shape[0]


def free_rigid_body_splitting(
    J: npt.ArrayLike,
    L0: npt.ArrayLike,
    R0: npt.ArrayLike,
    t: npt.ArrayLike,
    h: float,
    *,
    order: int = 2,
    compiled: bool = True,
    compensated: bool = False,
) -> Solution:
    """Torque-free rigid body by the Lie–Poisson splitting into exact axis rotations.

    Domain: J as :func:`free_rigid_body_rhs`, finite L0, R0 a rotation, t strictly increasing, h > 0
    with at most ``MAX_STEPS`` steps (else StepSizeError before any work), order in
    ``SPLITTING_ORDERS`` (else UnknownOptionError).

    H = Σ L_i²/(2 J_i) = H1 + H2 + H3.  The flow of H_i alone keeps L_i and
    ω = (L_i/J_i) e_i constant, so over a time τ it turns both L_A and the
    attitude by the basic matrix R_i(τ L_i/J_i) of (2.30): L_A ← R_i L_A and
    ^A R^O ← R_i ^A R^O (L_O = (^A R^O)ᵀ L_A stays fixed).  One step is the
    symmetric composition (Strang) H1(h/2) H2(h/2) H3(h) H2(h/2) H1(h/2), order 2,
    or its Yoshida triple jump (order 4, and again for orders 6 and 8); the half-steps
    of H1 that meet between steps are merged.  Every sub-flow is an exact
    rotation, so |L| is kept to rounding, each L_i is kept exactly by its own
    sub-flow, the attitude stays on SO(3) to rounding, and the map is a
    Lie–Poisson map: the energy error stays bounded (O(h^order)) for all times.
    The rounding drift of |L| and of R Rᵀ is removed every :data:`PROJECT_EVERY`
    steps and at each output time (a steady rotation would otherwise repeat one
    rounded cosine–sine pair and drift linearly).

    Parameters
    ----------
    J : array_like, shape (..., 3)
        Principal moments (J1, J2, J3) about G, > 0, triangle inequality.
    L0 : array_like, shape (..., 3)
        Initial angular momentum, body components.
    R0 : array_like, shape (..., 3, 3)
        Initial attitude ^A R^O.
    t : array_like, shape (n,)
        Output times, strictly increasing (see the module Conventions).
    h : float
        Largest step.
    order : {2, 4, 6, 8}
    compiled : bool
        The compiled kernel (default) or, with False, the pure-numpy reference path
        (see the module Conventions).
    compensated : bool
        Add each turn to the state as an increment ((cos θ − 1) x + sin θ y, with
        cos θ − 1 = −2 sin²(θ/2)) by Kahan summation, the compensations carried from
        flow to flow and across outputs; no projection (a turn's rounding then changes
        |L| and R Rᵀ by ~eps θ², not eps).  The rounding error of the state then grows
        like √n instead of n (module Conventions, "Compensated splitting").

    Returns
    -------
    Solution
        ``y`` of shape ``(n, *batch, 12)``: the state of :func:`rigid_body_state`
        (split it with :func:`rigid_body_parts`); ``rhs_evals`` counts sub-flows.

    Raises
    ------
    UnknownOptionError
        ``order`` not in ``SPLITTING_ORDERS``, or ``compensated`` not a bool.
    NonPhysicalInertiaError
        A moment ≤ 0, or one larger than the sum of the other two.
    NotARotationError
        ``R0`` is not a rotation within 256 eps.
    OutOfDomainError
        ``t`` not strictly increasing.
    NonPositiveParameterError
        ``h`` ≤ 0.
    StepSizeError
        The run would take more than ``MAX_STEPS`` steps (raised before any work).
    ShapeError
        Wrong trailing shapes, leading axes that do not broadcast, ``t`` not 1-D with at
        least two entries, or an ``h`` that is not a scalar.
    NonFiniteError
        NaN or an infinity in an input.
    ResultOverflowError
        The state overflowed (|L| h/J beyond float64's range).

    Examples
    --------
    |L| and the energy after 1000 steps:

    >>> from mechanics.integrators import rigid_body_parts
    >>> J, L0 = np.array([1.0, 2.0, 2.5]), np.array([0.3, -1.0, 0.7])
    >>> sol = free_rigid_body_splitting(J, L0, np.eye(3), (0.0, 100.0), 0.1)
    >>> L, R = rigid_body_parts(sol.y[-1])
    >>> bool(abs(np.linalg.norm(L) / np.linalg.norm(L0) - 1) < 1e-14)
    True
    >>> E = lambda L: 0.5 * np.sum(L**2 / J)
    >>> bool(abs(E(L) / E(L0) - 1) < 1e-2), sol.steps
    (True, 1000)
    """
    if isinstance(order, bool) or order not in SPLITTING_ORDERS:
        raise UnknownOptionError(f"order must be one of {SPLITTING_ORDERS}; got {order!r}")
    if not isinstance(compensated, bool | np.bool_):
        raise UnknownOptionError(f"compensated must be True or False; got {compensated!r}")
    Jm = _check_moments(J)
    L = as_float_array(L0, "L0", (3,))
    R = check_rotation(R0, name="R0")
    tt = _check_times(t)
    hf = _positive_scalar(h, "h")
    _check_step_budget(tt, hf, MAX_STEPS)
    batch = np.broadcast_shapes(Jm.shape[:-1], L.shape[:-1], R.shape[:-2])
    sched = _SCHEDULES[order]
    head = sched[0][1]  # the schedule is symmetric: it starts and ends with (0, head)
    middle = sched[1:-1]
    ys = np.empty((tt.shape[0], *batch, 12))
    ys[0] = rigid_body_state(np.broadcast_to(L, (*batch, 3)), np.broadcast_to(R, (*batch, 3, 3)))
    scalar = batch == ()
    if compiled:
        out = _splitting_compiled(Jm, L, R, tt, hf, batch, scalar, middle, head, compensated)
        if out is not None:
            ys[1:] = out[0][1:].reshape(tt.shape[0] - 1, *batch, 12)
            return _solution(tt, ys, f"splitting-{order}", out[1], out[2], 0)
    # one body runs on lists of Python floats, a batch on lists of arrays
    Js: list[Any]
    Ls: list[Any]
    Rs: list[Any]
    norm0: Any  # a float for one body, an array for a batch
    run: Callable[[list[Any], list[Any], list[Any], Flows, float, float, int], int]
    project: Callable[[list[Any], list[Any], Any], None]
    if scalar:
        Js = [float(x) for x in Jm]
        Ls = [float(x) for x in L]
        Rs = [[float(x) for x in row] for row in R]
        norm0 = math.hypot(*Ls)
        run, project = _split_run_scalar, _project_scalar
    else:
        Jb = np.broadcast_to(Jm, (*batch, 3))
        Js = [np.ascontiguousarray(Jb[..., i]) for i in range(3)]
        Lb = np.broadcast_to(L, (*batch, 3))
        Ls = [np.array(Lb[..., i]) for i in range(3)]
        Rb = np.broadcast_to(R, (*batch, 3, 3))
        Rs = [np.array(Rb[..., i, :]) for i in range(3)]
        norm0 = np.hypot(np.hypot(Ls[0], Ls[1]), Ls[2])
        run, project = _split_run_batch, _project_batch
    if compensated:
        zero: Floats = 0.0 if scalar else np.zeros(batch)
        cL = [zero] * 3
        cR = [[zero] * 3 for _ in range(3)]
        Rs = [list(row) if scalar else [row[..., m] for m in range(3)] for row in Rs]
        sin = math.sin if scalar else np.sin

        def run(
            Js: list[Any],
            Ls: list[Any],
            Rs: list[Any],
            seq_h: Flows,
            head: float,
            join: float,
            m: int,
        ) -> int:
            return _split_run_compensated(Js, Ls, Rs, cL, cR, seq_h, head, join, m, sin)

        def project(Ls: list[Any], Rs: list[Any], norm0: Any) -> None:
            return None

    steps = flows = 0
    with np.errstate(over="ignore", invalid="ignore"):
        for k in range(tt.shape[0] - 1):
            d = float(tt[k + 1]) - float(tt[k])
            n = _substeps(float(tt[k]), float(tt[k + 1]), hf)
            hk = d / n
            seq_h = [(i, c * hk) for i, c in middle]
            blown = False  # math.cos/sin of an infinite turn (one body's Python floats)
            for first in range(0, n, PROJECT_EVERY):
                m = min(PROJECT_EVERY, n - first)
                try:
                    flows += run(Js, Ls, Rs, seq_h, head * hk, 2.0 * head * hk, m)
                except ValueError:
                    blown = True
                    break
                project(Ls, Rs, norm0)
            steps += n
            if blown:
                ys[k + 1] = np.inf
            elif scalar:
                ys[k + 1] = [*Ls, *Rs[0], *Rs[1], *Rs[2]]
            elif compensated:  # rows kept as lists of components
                ys[k + 1, ..., :3] = np.stack(Ls, axis=-1)
                ys[k + 1, ..., 3:] = np.stack([x for row in Rs for x in row], axis=-1)
            else:
                ys[k + 1, ..., :3] = np.stack(Ls, axis=-1)
                ys[k + 1, ..., 3:] = np.concatenate(Rs, axis=-1)
            if not np.isfinite(ys[k + 1]).all():
                raise ResultOverflowError(
                    f"the splitting overflowed between t={float(tt[k])!r} and "
                    f"t={float(tt[k + 1])!r}: |L|·h/J too large for float64"
                )
    return _solution(tt, ys, f"splitting-{order}", steps, flows, 0)


free_rigid_body_splitting = broadcast_checked(free_rigid_body_splitting)
