"""The report: a run's segments and events assembled into its
:class:`~mechanics.scenes.trajectory.Trajectory`.

- **Series**: per body (prefixed ``name.`` when there are several) x, y, z, vx, vy, vz
  (space components), mass (with thrust), and for a rigid body omega1..3 (body
  components) and wx, wy, wz (space components); a top's Euler angles, a guided body's
  coordinates, the joints' reactions (:meth:`.forward.Forward.reactions`), each effect's
  own series; the totals E, and p_*, L_* (about the origin) for several bodies or a
  rigid one.
- **Invariants**: the quantities every listed effect keeps
  (:meth:`~mechanics.scenes.effects.base.Effect.keeps`): the total momentum p_x, p_y,
  p_z, the total angular momentum about the origin L_x, L_y, L_z (orbital r × m v plus
  the spins Rᵀ L_A) and the energy E (kinetic ½ m v² + ½ L_A·ω_A plus the effects'
  potentials), and the spin angular momentum about G of each rigid body no effect
  turns; each with its samples and the size of its terms, checked within the segments
  between impacts, or over the whole run where the impulses keep it too.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, cast

import numpy as np

from .effects.base import CONSERVED
from .effects.impact import centre_gaps
from .state import body_vertices
from .trajectory import (
    Event,
    Segment,
    Trajectory,
    dense_from_segments,
    energy_scale,
    sample_segments,
)
from .vectors import FloatArray, cross

if TYPE_CHECKING:  # for annotations only
    from .effects import Snapshot
    from .forward import Forward
    from .model import Model
    from .support import Support

__all__ = ["finish", "top_angles"]


def finish(
    model: Model,
    forward: Forward,
    t: FloatArray,
    segs: list[Segment],
    events: list[Event],
    how: str,
) -> Trajectory:
    """The run's result from its segments and events, with its series and invariants.

    The series at the sample times t, the conserved quantities with their scales, the
    derived state at any time (see the module's docstring).

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`).
    forward : Forward
        Its forward dynamics (:class:`mechanics.scenes.forward.Forward`), which reads the
        states as bodies.
    t : ndarray, shape (k,)
        The sample times, s, k ≥ 1, increasing.
    segs : list[Segment]
        The run's pieces ``(t0, t1, state_at)`` in time order (at least one), each
        ``state_at`` the flat states at its times.
    events : list[Event]
        The run's events in time order.
    how : str
        How the run was computed (the result's ``method``; one starting
        ``"integrated: DOP853"`` widens the energy's scale by the tolerances).

    Returns
    -------
    Trajectory
        The result (:class:`mechanics.scenes.trajectory.Trajectory`).

    Raises
    ------
    IndexError
        Where ``segs`` is empty, or a segment's states are shorter than the layout's size.
    ValueError
        Where ``t`` holds no sample.

    Examples
    --------
    A point of 2 kg dropped from 5 m under g = 2 m/s²: z = 5 − t², and E = ½ m v² + m g z
    stays 20 J:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...     "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                 "initial": {"position": [0.0, 0.0, 5.0]}}],
    ...     "effects": [{"type": "gravity", "g": 2.0}]}))
    >>> how = eng.exact_flow()
    >>> segs, events = eng.flow.run()
    >>> tr = finish(eng.model, eng.forward, np.array([0.0, 0.5, 1.0]), segs, events, how)
    >>> tr.series["z"].tolist(), tr.series["E"].tolist()
    ([5.0, 4.75, 4.0], [20.0, 20.0, 20.0])
    """
    dense = dense_from_segments(segs)
    Y = cast("FloatArray", sample_segments(segs, t))  # (not None: a scene has 2 samples or more)
    s = forward.snapshot(t, Y)
    n, lay = model.n, model.layout
    moving = list(lay.moving_bodies)
    series: dict[str, FloatArray] = {}
    pre: Callable[[int], str] = (lambda i: f"{model.names[i]}.") if n > 1 else (lambda i: "")
    thrust = bool(model.losing)
    for i in moving:
        p = pre(i)
        for k, c in enumerate("xyz"):
            series[p + c] = s.r[:, i, k]
        for k, c in enumerate("xyz"):
            series[p + "v" + c] = s.v[:, i, k]
        if thrust:
            series[p + "mass"] = s.m[:, i]
        if i in model.rigid:
            for k in range(3):
                series[f"{p}omega{k + 1}"] = s.omega[:, i, k]
            w_O = s.to_space(i, s.omega[:, i])
            for k, c in enumerate("xyz"):
                series[f"{p}w{c}"] = w_O[:, k]
    reactions, reaction_sizes = forward.reactions(t, Y)
    for i, parts in reactions.items():
        for what, F in parts.items():
            for k, c in enumerate("xyz"):
                series[f"{pre(i)}{what}_{c}"] = F[:, k]
    support = forward.support if forward.support is not None and forward.support.timeline else None
    held, held_sizes = support.series(t, Y) if support is not None else ({}, {})
    for i, F in held.items():
        for k, c in enumerate("xyz"):
            series[f"{pre(i)}support_{c}"] = F[:, k]
    for i in lay.pins:
        series.update({pre(i) + k: v for k, v in top_angles(s.R[:, i], s.omega[:, i]).items()})
    for i, gd in lay.guides.items():
        series.update({pre(i) + k: v for k, v in gd.series(*s.coords[i]).items()})
    m = s.m[:, moving]
    v, r = s.v[:, moving], s.r[:, moving]
    KE = 0.5 * (m * (v * v).sum(-1)).sum(-1) + 0.5 * (s.L_A * s.omega).sum((-1, -2))
    for i, M in s.inertia.items():  # the inertia mass flowing in has added
        qd = s.coords[i][1]
        KE = KE + 0.5 * ((M - lay.guides[i].M) * qd * qd).sum(-1)
    E = KE.copy()
    for pot in model.potentials:
        E = E + pot.potential(s)
    if moving:
        series["E"] = E
    P = (m[..., None] * v).sum(-2)
    orb = cross(r, m[..., None] * v)
    spins = np.einsum("...ji,...j->...i", s.R, s.L_A)
    L_O = orb.sum(-2) + spins.sum(-2)
    conserved: dict[str, FloatArray] = {}
    scales: dict[str, float] = {"E": energy_scale(KE, E)}
    across: set[str] = set()
    p_scale = float(np.max((m * np.linalg.norm(v, axis=-1)).sum(-1), initial=0.0))
    if how.startswith("integrated: DOP853"):
        # DOP853 holds each component to atol + rtol |y|: where the speeds are below
        # atol/rtol that is atol, and E moves by Σ |∂E/∂y| atol a step (m|v| per unit of
        # v, |ω| per unit of L_A), which the tolerance, relative to E's size, counts in
        # rtol: E's size is at least (atol/rtol) Σ |∂E/∂y| (found by a property test: a
        # slow pair of bodies, E = 5e-4 J at 0.02 m/s, drifted 7.6e-10 of E, allowed 2.3e-10)
        sc = model.scene
        grad = float(
            np.max(
                (m * np.linalg.norm(v, axis=-1)).sum(-1)
                + np.linalg.norm(s.omega[:, moving], axis=-1).sum(-1),
                initial=0.0,
            )
        )
        scales["E"] = max(scales["E"], sc.atol / sc.rtol * grad)
    # the size of the terms: |r| m |v| bounds each orbital term |r × m v| (a small
    # cross product of large vectors is known only to their size)
    L_scale = float(
        np.max(
            (np.linalg.norm(r, axis=-1) * m * np.linalg.norm(v, axis=-1)).sum(-1)
            + np.linalg.norm(spins, axis=-1).sum(-1),
            initial=0.0,
        )
    )
    values = {"E": E}
    for k, c in enumerate("xyz"):
        values[f"p_{c}"], scales[f"p_{c}"] = P[:, k], p_scale
        values[f"L_{c}"], scales[f"L_{c}"] = L_O[:, k], L_scale
    if len(moving) > 1 or model.rigid:
        for k, c in enumerate("xyz"):
            series[f"p_{c}"], series[f"L_{c}"] = P[:, k], L_O[:, k]
    since: dict[str, float] = {}
    T = model.scene.duration
    # one impact per law (what an impact keeps depends on its kind, law and plane
    # only): a group's many pairs are asked once
    laws = list(
        {
            (imp.j is None, imp.e, imp.mu_f, imp.normal.tobytes() if imp.j is None else b""): imp
            for imp in model.impacts
        }.values()
    )
    for q in CONSERVED if moving else ():
        # what the effects acting throughout keep; an effect that stops acting (a
        # push, a burn) breaks it only until then
        until = max((e.acts_until(events, q) for e in model.forces if not e.keeps(q)), default=0.0)
        if support is not None:  # a support breaks what its forces do not keep
            until = max(until, support.acts_until(events, q))
        if until < T:
            conserved[q] = values[q]
            if until > 0:
                since[q] = until
            if all(imp.keeps(q) for imp in laws):
                across.add(q)
    for e in model.forces:  # what an effect's own physics keeps, and its series
        series.update(e.series(s))
        for name, (vals, size) in e.conserved(s).items():
            series[name] = conserved[name] = vals
            scales[name] = size
            across.add(name)
    kinds = {e.type for e in model.effects}
    for i in lay.pins:
        if lay.J[i, 0] == lay.J[i, 1] and kinds <= {"fixed_point", "gravity"}:
            # the moments of gravity and of the pivot about C are ⟂ to e3 (C on e3)
            name = pre(i) + "L_3"
            series[name] = conserved[name] = lay.J[i, 2] * s.omega[:, i, 2]
            scales[name] = float(np.max(np.linalg.norm(s.L_A[:, i], axis=-1)))
            across.add(name)
    # an impulse through a sphere's centre turns it by the rounding of its arm only,
    # eps × |ρ| |P|: its spin is known to the size of the impacts' moments about the
    # contact point (their angular_momentum_scale), not to its own (found by a property
    # test: a spin of 1e-88 rad/s "drifted" 1.2e-32 at a smooth impact)
    lever: dict[str, float] = {}
    for ev in events:
        if ev.kind == "impact":
            for who in ev.detail.get("bodies", [ev.detail.get("body")]):
                size = ev.detail.get("angular_momentum_scale", 0.0)
                lever[who] = max(lever.get(who, 0.0), size)
    for i in model.rigid:
        until = max((e.acts_until(events) for e in model.forces if e.exerts_moment(i)), default=0.0)
        if support is not None and any(
            r.imp.i == i for _, rs in support.timeline for r in rs.values()
        ):
            until = max(until, support.acts_until(events))
        struck = any(model.impacts[a].exerts_moment(i) for a in model.impacts_of.get(i, ()))
        if until >= T or not (model.w0[i].any() or until > 0 or struck):
            continue  # turned to the end, or never spinning (trivially kept)
        p = pre(i)
        for k, c in enumerate("xyz"):
            name = f"{p}L_{c} (spin about G)"
            conserved[name] = spins[:, i, k]
            spin = float(np.max(np.linalg.norm(spins[:, i], axis=-1)))
            scales[name] = max(spin, lever.get(model.names[i], 0.0))
            if until > 0:
                since[name] = until
            if not struck:
                across.add(name)

    def state_at(tt: float) -> dict[str, float]:
        ss = forward.snapshot(tt, np.asarray(dense(tt), dtype=float))
        out: dict[str, float] = {}
        for i in moving:
            p = pre(i)
            for k, c in enumerate("xyz"):
                out[p + c] = float(ss.r[i, k])
                out[p + "v" + c] = float(ss.v[i, k])
            if i in model.rigid:
                w_O = ss.to_space(i, ss.omega[i])
                for k in range(3):
                    out[f"{p}omega{k + 1}"] = float(ss.omega[i, k])
                    out[f"{p}w{'xyz'[k]}"] = float(w_O[k])
            if i in lay.pins:
                R, w = ss.R[i], ss.omega[i]
                out[p + "cos_theta"] = float(R[2, 2])
                out[p + "cos_theta_dot"] = float(w[1] * R[0, 2] - w[0] * R[1, 2])
            if i in lay.guides:
                for key, x in lay.guides[i].series(*ss.coords[i]).items():
                    out[p + key] = float(x)
        for e in model.forces:
            out.update({k: float(x) for k, x in e.series(ss).items()})
        y = np.asarray(dense(tt), dtype=float)
        if support is not None:
            for i, F in support.series(np.array([tt]), y[None])[0].items():
                for k, c in enumerate("xyz"):
                    out[f"{pre(i)}support_{c}"] = float(F[0, k])
        for i, parts in forward.reactions(np.array([tt]), y[None])[0].items():
            for what, F in parts.items():
                for k, c in enumerate("xyz"):
                    out[f"{pre(i)}{what}_{c}"] = float(F[0, k])
        return out

    for i, size in held_sizes.items():
        for c in "xyz":
            scales[f"{pre(i)}support_{c}"] = size
    for i, sizes in reaction_sizes.items():
        for what, size in sizes.items():
            for c in "xyz":
                scales[f"{pre(i)}{what}_{c}"] = size
    traj = Trajectory(t, series, events, how, state_at, conserved, since, frozenset(across))
    traj.scales = scales
    #: every body's r, v, R_A_O, ω_A and m at the sample times (mechanics.conformance)
    traj.snapshot = s
    traj.gaps, traj.resting_gaps = _gaps(model, support, t, s)
    traj.support_law = _support_law(model, support, t, held, held_sizes)
    forces = model.forces  # (where all conserve, E is a conserved quantity already)
    if (
        "E" in series
        and any(e.dissipative for e in forces)
        and all(e.dissipative or e in model.potentials for e in forces)
    ):
        traj.energy_rise = float(np.max(E - np.minimum.accumulate(E), initial=0.0))
    radii = [ft.a + ft.a_s for imp in model.impacts for ft in imp.features]
    verts = [
        np.abs(corners).max()
        for b in model.scene.bodies
        if (corners := body_vertices(b)) is not None
    ]
    traj.length_scale = float(
        np.max(np.abs(r), initial=0.0) + max(radii, default=0.0) + max(verts, default=0.0)
    )
    if model.rigid:
        Rr = s.R[:, list(model.rigid)]
        dev = np.einsum("...ij,...kj->...ik", Rr, Rr) - np.eye(3)
        traj.orthogonality = float(np.max(np.abs(dev)))
    return traj


def _gaps(
    model: Model, support: Support | None, t: FloatArray, s: Snapshot
) -> tuple[dict[str, FloatArray], dict[str, float]]:
    """Each impact pair's smallest gap at the samples over its features that do not
    rest there (a resting contact's gap is held at zero, up to the integration's
    error), and the largest |gap| of its resting ones (None: it never rests)."""
    gaps: dict[str, FloatArray] = {}
    resting: dict[str, float] = {}
    resting_pairs = {imp for _, _, rests in support.spans() for imp in rests} if support else set()
    imps = model.impacts
    rows, G_all = centre_gaps(imps, s)  # spheres' and points' centres: all at once
    done: set[int] = set()
    for c, a in enumerate(rows):
        if imps[a] not in resting_pairs:
            gaps[imps[a].label] = G_all[:, c]
            done.add(a)
    for a, imp in enumerate(imps):
        if a in done:
            continue
        G = np.array([imp.gap(s, ft) for ft in imp.features])  # (features, samples)
        held = np.zeros(G.shape, dtype=bool)
        if support is not None:
            for t0, t1, rests in support.spans():
                rest = rests.get(imp)
                if rest is not None:
                    on = (t >= t0) & (t < t1)
                    for b in rest.active:
                        held[b] |= on
        gaps[imp.label] = np.min(np.where(held, np.inf, G), axis=0, initial=np.inf)
        gaps[imp.label] = np.where(np.isfinite(gaps[imp.label]), gaps[imp.label], 0.0)
        if held.any():
            resting[imp.label] = float(np.max(np.abs(G[held])))
    return gaps, resting


def _support_law(
    model: Model,
    support: Support | None,
    t: FloatArray,
    held: dict[int, FloatArray],
    sizes: dict[int, float],
) -> dict[str, float]:
    """Each resting pair's worst breach of the support's law at the samples where it
    rests, relative to the size of the forces' terms: the total support force presses
    (F·n ≥ 0) and lies in the friction cone (|F_t| ≤ μ F·n)."""
    out: dict[str, float] = {}
    for t0, t1, rests in support.spans() if support is not None else ():
        on = (t >= t0) & (t < t1)
        for imp in rests:
            F = held[imp.i][on]
            Fn = F @ imp.normal
            Ft = np.linalg.norm(F - Fn[:, None] * imp.normal, axis=-1)
            bad = np.maximum(-Fn, Ft - imp.mu_f * Fn)
            worst = float(np.max(bad, initial=0.0)) / max(sizes[imp.i], 1e-300)
            out[imp.label] = max(out.get(imp.label, 0.0), worst, 0.0)
    return out


def top_angles(R: FloatArray, w: FloatArray) -> dict[str, FloatArray]:
    """The series of a top from samples of its attitude and body ω: Euler angles, axis, cos θ.

    The Euler angles z-x-z (row 3 of ^A R^O is (sθ sψ, −sθ cψ, cθ), column 3 is
    (sφ sθ, cφ sθ, cθ)), ψ and φ unwrapped along the samples; the symmetry axis e3 in
    space components; cos θ and its rate d(cos θ)/dt = (Ṙ)₃₃ with Ṙ = −[ω]× R.

    Parameters
    ----------
    R : ndarray, shape (k, 3, 3)
        The attitudes ^A R^O at k samples.
    w : ndarray, shape (k, 3)
        The angular velocities ω in body components, rad/s.

    Returns
    -------
    dict
        Name to samples of shape (k,): ``theta``, ``psi``, ``phi`` (rad), ``axis_x``,
        ``axis_y``, ``axis_z``, ``cos_theta`` and ``cos_theta_dot`` (1/s).

    Raises
    ------
    IndexError
        Where ``R`` has fewer than three axes or ``w`` fewer than two.

    Examples
    --------
    The angles of R3(φ) R1(θ) R3(ψ) come back, and d(cos θ)/dt = −sin θ θ̇ with θ̇ from
    Euler's kinematic equations (2.69):

    >>> from mechanics.kinematics import euler_rates_from_angular_velocity
    >>> from mechanics.rotation import matrix_from_euler
    >>> R, w = matrix_from_euler(0.3, 0.5, 0.7)[None], np.array([[1.0, 2.0, 3.0]])
    >>> a = top_angles(R, w)
    >>> [round(float(a[k][0]), 12) for k in ("psi", "theta", "phi")]
    [0.3, 0.5, 0.7]
    >>> theta_dot = euler_rates_from_angular_velocity(0.5, 0.7, w[0])[1]
    >>> bool(np.isclose(a["cos_theta_dot"][0], -np.sin(0.5) * theta_dot))
    True
    """
    return {
        "theta": np.arctan2(np.hypot(R[:, 2, 0], R[:, 2, 1]), R[:, 2, 2]),
        "psi": np.unwrap(np.arctan2(R[:, 2, 0], -R[:, 2, 1])),
        "phi": np.unwrap(np.arctan2(R[:, 0, 2], R[:, 1, 2])),
        "axis_x": R[:, 2, 0],
        "axis_y": R[:, 2, 1],
        "axis_z": R[:, 2, 2],
        "cos_theta": R[:, 2, 2],
        "cos_theta_dot": w[:, 1] * R[:, 0, 2] - w[:, 0] * R[:, 1, 2],
    }
