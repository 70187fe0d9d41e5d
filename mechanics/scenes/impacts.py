"""Contact resolution: the impact law applied at a contact found by :mod:`.collision`
(or in closed form), and what follows at that instant.

- :meth:`Resolver.resolve` resolves the contact found and every one that closes at the
  same instant.  The model depends on the configuration, and each impact event says
  which it used (``impact_model``):

  * **one body's several contacts with one plane or body** (a box landing flat on its
    face: four corners of one pair touching together) are *simultaneous*: one impact
    problem over every touching contact of the pair, Newton's law at all of them at
    once, a linear complementarity problem in the normal impulses P ≥ 0
    (:meth:`Resolver.together`): with the Delassus matrix W (W_kl = n_k·K(S_k, S_l) n_l,
    the change of contact k's normal velocity per unit impulse at l) and the normal
    velocities u⁻ before, u⁺ = u⁻ + W P ≥ t, P ≥ 0 and P·(u⁺ − t) = 0, with the
    target t = −e u⁻ where a contact approaches and 0 where it does not (an impulse at
    one corner may make a merely touching one close).  W is positive semi-definite and
    singular (several contacts of one rigid body are dependent: the impulses are not
    unique, the velocity after is); :func:`solve_lcp` solves it exactly by its
    complementary bases.  One restitution e per pair, so this is Newton's law per
    contact.  With friction, the smooth solution is accepted only where no contact
    slides before or after (the zero tangential impulse then sticks, inside every
    cone); contacts that slide together are refused with one line (not modelled yet);
  * **contacts of different pairs** at one instant (a Newton's cradle: a chain of
    distinct bodies) are *sequential*: after each impulse every feature touching within
    rounding and still closing is resolved in turn, the fastest approach first, until
    none closes (at most :data:`MAX_SWEEPS` rounds; for a row of equal elastic spheres
    this passes the momentum down the row, the textbook answer);
  * an ``impact`` effect with ``model = "sequential"`` resolves its own contacts one at a
    time too (the model chosen explicitly; each impulse obeys the law at its contact);
  * a lone contact is ``single``: the Chapter 6 impulse
    (:meth:`~mechanics.scenes.effects.impact.Impact.apply`), with friction.

  After each impulse the impact law is checked at every contact that took one: the
  separation speed e times the approach speed (equal where an impulse acts, not less
  where none does), its residual relative to the contact speeds' size in the event
  (``law_residual``), which the run's self-checks hold to :data:`LAW_RTOL`.
- A touch at zero approach speed (up to :data:`CLOSING_ROUNDING`) is no impact
  (:meth:`Resolver.touch`).
- A pair pressed together whose rebound can no longer be followed (the impacts
  accumulate, or e = 0; :meth:`Resolver.stalls`) comes to rest: a body on a plane is
  supported from then on (:meth:`.support.Support.rest`); a pair the resting contact
  does not treat stops the run with one line.
- :meth:`Resolver.contact_time` is the closed-form time to a sphere's or point's next
  contact under uniform gravity (the exact flows' free flight).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from . import contacts
from .effects.impact import EnergyGainError, totals
from .errors import SceneError
from .trajectory import EPS, Event
from .vectors import FloatArray, Times

if TYPE_CHECKING:  # for annotations only
    from .effects import Snapshot
    from .effects.impact import Feature, Impact
    from .forward import Forward
    from .model import Model
    from .spec import Scene
    from .support import Support

__all__ = [
    "CLOSING_ROUNDING",
    "GAP_ROUNDING",
    "LAW_RTOL",
    "MAX_EVENTS",
    "MAX_SWEEPS",
    "ZENO_SPEED",
    "Resolver",
    "falls_in",
    "solve_lcp",
    "zeno",
]

#: a gap within this multiple of eps × the positions' size over a step is the rounding
#: of a contact just resolved (the contact time is refined to 4 eps of the step, the
#: positions are sums of a few dozen rounded terms), not an interpenetration
GAP_ROUNDING = 64 * EPS
#: an approach speed within this multiple of eps × the contact speeds' size is the
#: rounding of zero: a touch (two bodies moving together after a plastic impact)
CLOSING_ROUNDING = 64 * EPS
#: a rebound slower than this (m/s, relative to 1 + the approach speed) under a pressing
#: force means the impacts accumulate (Zeno); the bouncing ball reaches it after ~150
#: bounces at e = 5/6
ZENO_SPEED = 1e-9
#: impacts per run before it is declared Zeno
MAX_EVENTS = 2000
#: rounds of sequential impulses at one instant (a row of k touching bodies needs k)
MAX_SWEEPS = 1000
#: Newton's law at a contact after the instant (separation speed − e × approach speed),
#: relative to the contact speeds' size: the velocities after are sums of a few impulses,
#: each a product of a dozen rounded terms (the eigen-factor of W adds a few eps × its
#: condition on the range, O(10) for the bodies here)
LAW_RTOL = 2**8 * EPS
#: an eigenvalue of the Delassus matrix W below this × its largest (× the number of
#: contacts) is a dependency of the contacts (zero in exact arithmetic), not a stiffness
RANK_RTOL = 2**6 * EPS


class Resolver:
    """The impact law at the contacts of a :class:`~mechanics.scenes.model.Model`.

    It acts through the model's :class:`~mechanics.scenes.forward.Forward` dynamics; its
    constructor only stores what it is given.

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`); its ``impacts`` are
        the contacts resolved.
    forward : Forward
        The model's forward dynamics (:class:`mechanics.scenes.forward.Forward`).
    support : Support or None, optional
        The resting contacts (:class:`mechanics.scenes.support.Support`) a pair whose
        impacts accumulate passes to; None (the default): such a pair stops the run
        (:func:`zeno`).

    Examples
    --------
    Newton's law at a lone contact: a ball reaching the floor at 4 m/s with e = 1/2 leaves
    it at e × 4 = 2 m/s (Chapter 6):

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...     "bodies": [{"name": "ball", "shape": "solid_sphere", "mass": 1.0, "radius": 0.5,
    ...                 "initial": {"position": [0.0, 0.0, 0.5], "velocity": [0.0, 0.0, -4.0]}}],
    ...     "effects": [{"type": "impact", "body": "ball", "plane_point": [0.0, 0.0, 0.0],
    ...                  "plane_normal": [0.0, 0.0, 1.0], "restitution": 0.5}]}))
    >>> imp, events = eng.model.impacts[0], []
    >>> y = eng.resolver.resolve(0.0, eng.model.y0, imp, imp.features[0], events)
    >>> events[0].detail["impact_model"], eng.model.layout.gather(y)[1].tolist(), 0.5 * 4.0
    ('single', [[0.0, 0.0, 2.0]], 2.0)
    """

    def __init__(self, model: Model, forward: Forward, support: Support | None = None) -> None:
        self.model = model
        self.forward = forward
        #: the resting contacts (:class:`~mechanics.scenes.support.Support`) a pair whose
        #: impacts accumulate passes to; None: such a pair stops the run (:func:`zeno`)
        self.support = support

    def touch(self, imp: Impact, ft: Feature, s: Snapshot) -> bool:
        """Touching with an approach speed that is zero up to rounding: no impact."""
        return imp.approach(s, ft) <= CLOSING_ROUNDING * imp.speed_scale(s, ft)

    def resolve(
        self,
        t: float,
        y: FloatArray,
        imp: Impact,
        ft: Feature,
        events: list[Event],
        gap_scale: float = 0.0,
    ) -> FloatArray:
        """Resolve the impact found at t, then every simultaneous one (sequential
        impulses, see the module's docstring); record the events; return the new state.
        ``gap_scale``: the size the contact search's rounding was relative to (the gap
        is zero within it; a hop below it cannot be followed)."""
        from mechanics.errors import SeparatingContactError

        scene, fwd = self.model.scene, self.forward
        s = fwd.snapshot(t, y)
        first = True
        # zero is judged against the speeds the instant starts with (a plastic impact
        # stops its contacts: the speeds after are rounding of that zero)
        floor = imp.speed_scale(s, ft)
        moved: set[int] = set()  # the bodies the instant's impulses have struck so far
        for _ in range(MAX_SWEEPS):
            group = self.closing_with(s, imp, ft, floor)
            try:
                if len(group) > 1:
                    detail = self.together(s, imp, group)
                else:
                    detail = imp.apply(s, ft)
                    detail["impact_model"] = "single" if first else "sequential"
                    speed = detail["normal_speed_before"]
                    law = abs(detail["normal_speed_after"] - imp.e * speed)
                    detail["law_residual"] = law / max(imp.speed_scale(s, ft), speed, 1e-300)
                    detail["law_worst_contact"] = ft.label
                self._still_closing(s, imp, group, detail)
            except SeparatingContactError as exc:
                raise scene.error(
                    imp.where,
                    f"{ft.label}: the contact at t = {t:.17g} s was found on the exit side "
                    f"(the bodies separate there): {exc}",
                ) from None
            except EnergyGainError as exc:
                raise scene.error(
                    f"{imp.where}.friction", f"{ft.label} at t = {t:.6g} s: {exc}"
                ) from None
            detail["gap_scale"] = max(detail["gap_scale"], gap_scale)
            events.append(Event(t, "impact", detail))
            if len(events) > MAX_EVENTS:
                raise zeno(scene, t, imp.label)
            y = fwd.pack(s)
            if self.stalls(imp, ft, t, y, detail):
                if self.support is None:
                    raise zeno(scene, t, imp.label)
                press = self.pressed(imp, ft, t, y, abs(detail["normal_speed_before"]))
                y = self.support.rest(t, y, imp, ft, detail, press, events)
                s = fwd.snapshot(t, y)
            elif self.support is not None and imp in self.support.rests:
                y = self.support.after_impact(t, y, imp, events, floor)  # who still rests
                s = fwd.snapshot(t, y)
            moved.update(imp.bodies())
            nxt = self.closing_now(s, floor, moved)
            if nxt is None:
                return y
            imp, ft = nxt
            first = False
        raise scene.error(
            "effects", f"more than {MAX_SWEEPS} rounds of simultaneous impacts at t = {t:.6g} s"
        )

    def touching(self, s: Snapshot, imp: Impact, ft: Feature) -> bool:
        """Is the feature's gap zero within the rounding of a contact just resolved?"""
        scale: float = np.abs(imp.feature_point(s, ft)).sum() + imp.point @ imp.point + ft.a
        return abs(float(imp.gap(s, ft))) <= GAP_ROUNDING * 4 * max(scale, ft.a + ft.a_s)

    def closing_now(
        self, s: Snapshot, floor: float = 0.0, moved: set[int] | None = None
    ) -> tuple[Impact, Feature] | None:
        """The touching feature that closes fastest (sequential impulses), or None; an
        approach within rounding of the contact speeds (or of ``floor``, the speeds the
        instant started with) is no closing.  With ``moved`` (body indices), only the
        pairs of those bodies are looked at: an impulse changes no other pair's approach,
        and a pair of other bodies closing at this instant is a contact of its own, found
        as the next event at the same time (the contact search takes a gap within
        rounding that falls as a contact now)."""
        best: tuple[Impact, Feature] | None
        best, speed = None, 0.0
        impacts = self.model.impacts
        among: Sequence[int]
        if moved is None:
            among = range(len(impacts))
        else:
            among = sorted({a for k in moved for a in self.model.impacts_of.get(k, ())})
        for imp in (impacts[a] for a in among):
            for ft in imp.features:
                if self._held(imp, ft) or not self.touching(s, imp, ft):
                    continue  # (a resting contact is the support's)
                v = imp.approach(s, ft)
                if v > CLOSING_ROUNDING * max(imp.speed_scale(s, ft), floor) and v > speed:
                    best, speed = (imp, ft), v
        return best

    def closing_with(
        self, s: Snapshot, imp: Impact, ft: Feature, floor: float = 0.0
    ) -> list[Feature]:
        """The contact ``ft`` of ``imp`` and every other feature of the same pair touching
        it at this instant, closing or not (an impulse at one may make another close):
        one impact problem; only ``ft`` where the pair's ``model`` is "sequential"."""
        if imp.model == "sequential":
            return [ft]
        return [ft] + [
            f
            for f in imp.features
            if f is not ft and (self.touching(s, imp, f) or self._held(imp, f))
        ]

    def _held(self, imp: Impact, ft: Feature) -> bool:
        """Does ``ft`` rest (its gap held at zero by a support: in contact whatever the
        integration's drift of its gap)?"""
        return self.support is not None and self.support.active(imp, ft)

    def together(self, s: Snapshot, imp: Impact, feats: list[Feature]) -> dict[str, Any]:
        """Newton's law at the contacts ``feats`` of one pair at once (see the module's
        docstring): the impulses applied to the snapshot in place; the event's details,
        as :meth:`~mechanics.scenes.effects.impact.Impact.apply` gives for one."""
        e = imp.e
        labels = [f.label for f in feats]
        idx = imp.bodies()
        sign = {imp.i: 1.0, imp.j: -1.0}
        points = [imp.contact(s, f) for f in feats]
        slide = max(imp.tangential_speed(s, f) for f in feats)
        scale = max(imp.speed_scale(s, f) for f in feats)
        if imp.mu_f > 0 and slide > CLOSING_ROUNDING * scale:
            raise self._slides(imp, labels, s.t, slide)
        before = totals(s, idx, points[0][0])
        u0 = np.array([-imp.approach(s, f) for f in feats])  # < 0: approaching
        m = len(feats)
        W = np.empty((m, m))
        for a, (Sa, na) in enumerate(points):
            for b, (Sb, nb) in enumerate(points):
                W[a, b] = na @ sum(imp.inverse_mass(s, k, Sa, Sb) for k in idx) @ nb
        W = 0.5 * (W + W.T)  # symmetric in exact arithmetic
        # Newton's law per contact: u⁺ ≥ −e u⁻ where it approaches, u⁺ ≥ 0 where not
        target = -e * np.minimum(u0, 0.0)
        P = solve_lcp(W, u0 - target)
        if P is None:  # pragma: no cover - an infeasible problem: normals that cancel
            raise self.model.scene.error(
                imp.where,
                f"{len(feats)} contacts of {imp.label} at t = {s.t:.6g} s: no impulses "
                "satisfy Newton's law at all of them together (a configuration the impact "
                "model cannot treat)",
            )
        for (S, n), p in zip(points, P, strict=True):
            for k in idx:
                imp.kick(s, k, sign[k] * p * n, S)
        after = totals(s, idx, points[0][0])
        u1 = np.array([-imp.approach(s, f) for f in feats])  # > 0: separating
        if imp.mu_f > 0:
            slide = max(imp.tangential_speed(s, f) for f in feats)
            if slide > CLOSING_ROUNDING * scale:
                raise self._slides(imp, labels, s.t, slide)
        # Newton's law at each contact, from the velocities after (not from W P)
        law = np.where(P > 0, np.abs(u1 - target), np.maximum(target - u1, 0.0))
        worst = int(np.argmax(law))
        u1_alg = u0 + W @ P  # the LCP's own normal velocities after: the loss's route
        detail: dict[str, Any] = {  # the contact found first: the one whose rebound is followed
            "normal_speed_before": float(-u0[0]),
            "normal_speed_after": float(u1[0]),
        }
        detail.update(imp.who())
        detail["feature"] = f"{len(feats)} contacts at once: " + "; ".join(labels)
        detail["features"] = labels
        detail["impact_model"] = "simultaneous"
        detail["contact_point"], detail["normal"] = points[0][0].tolist(), points[0][1].tolist()
        detail["contact_points"] = [S.tolist() for S, _ in points]
        detail["normals"] = [n.tolist() for _, n in points]
        detail["impulses"] = P.tolist()
        detail["normal_speeds_before"], detail["normal_speeds_after"] = (-u0).tolist(), u1.tolist()
        # the gap where the impulses act: of the contacts that do not rest (a resting
        # one's is held at zero to the integration's error: the run's resting check)
        free = [f for f in feats if not self._held(imp, f)] or feats
        gaps = [float(imp.gap(s, f)) for f in free]
        g = int(np.argmax(np.abs(gaps)))
        detail["gap"], detail["gap_scale"] = gaps[g], imp.gap_scale(s, free[g])
        detail["friction"] = "smooth" if imp.mu_f == 0 else "stick (no contact slides)"
        detail.update(imp.outcome(s, before, after, -0.5 * float(P @ (u0 + u1_alg))))
        detail["law_residual"] = float(law[worst]) / max(scale, float(np.max(np.abs(u0))), 1e-300)
        detail["law_worst_contact"] = labels[worst]
        return detail

    def _still_closing(
        self, s: Snapshot, imp: Impact, group: list[Feature], detail: dict[str, Any]
    ) -> None:
        """No other contact of the pair may still close after its impulses: a touching
        feature approaching beyond rounding counts against the law (``law_residual``;
        the contacts of one body were not resolved together).  Not where the scene
        asked for the sequential model: its law is each impulse's own."""
        if imp.model == "sequential":
            return
        for f in imp.features:
            if any(f is g for g in group) or not (self.touching(s, imp, f) or self._held(imp, f)):
                continue
            scale = max(imp.speed_scale(s, f), detail["normal_speed_before"], 1e-300)
            closing = imp.approach(s, f) / scale
            if closing > detail["law_residual"]:
                detail["law_residual"], detail["law_worst_contact"] = closing, f.label

    def _slides(self, imp: Impact, labels: list[str], t: Times, slide: float) -> SceneError:
        return self.model.scene.error(
            f"{imp.where}.friction",
            f"{len(labels)} contacts of {imp.label} meet at once at t = {t:.6g} s while "
            f"sliding ({slide:.3g} m/s across the normal): simultaneous impacts with "
            "friction that slides are not modelled; set friction = 0, or tilt the body so "
            "that its contacts come one at a time",
        )

    def pressed(
        self, imp: Impact, ft: Feature, t: float, y: FloatArray, speed: float = 0.0
    ) -> float:
        """How hard the loads push the pair together: minus the gap's second derivative
        (> 0 pressed, ≤ 0 not; within
        ``CLOSING_ROUNDING`` × the size of its terms, 0: the rounding of no push, as for
        a spinning body whose contact points accelerate along the plane).  ``speed``: the
        contact speeds just before (an impulse leaves ω rounded relative to them over
        the arm, which a spin ω turns into an acceleration of that rounding × ω)."""
        fwd = self.forward
        s = fwd.snapshot(t, y)
        if ft.support is not None:  # the gap of a rim circle against the plane
            g2 = fwd.rim_gap_acceleration(t, y, s, imp, ft)
            if g2 is not None:
                return -g2
        _, n = imp.contact(s, ft)
        # the gap's second derivative is that of the feature's point X (a sphere's
        # centre, a corner) against the plane or the other sphere's centre: a spinning
        # sphere's material contact point has a centripetal part that is not the gap's
        X = imp.feature_point(s, ft)
        pts = {ft.body: X} if ft.sphere is None else {ft.body: X, ft.sphere: s.r[ft.sphere]}
        sizes: dict[int, float] = {}
        a = fwd.point_accelerations(t, y, s, pts, sizes)
        push = -float(n @ (a.get(imp.i, 0.0) - a.get(imp.j, 0.0)))  # type: ignore[arg-type]  # j None (a plane): no entry, the default 0
        curve = 0.0
        if ft.sphere is not None:  # |d| curves: + |ḋ across d|² / |d| (it opens the gap)
            d = X - s.r[ft.sphere]
            w = s.point_velocity(ft.body, ft.at) - s.v[ft.sphere]
            dd = float(d @ d)
            push -= float(w @ w - (w @ d) ** 2 / dd) / math.sqrt(dd)
            curve = float(w @ w) / math.sqrt(dd)  # the size of that difference's terms
        spin = sum(float(np.linalg.norm(s.omega[k])) for k in imp.bodies())
        size = sum(sizes.values()) + spin * speed + curve
        return push if abs(push) > CLOSING_ROUNDING * size else 0.0

    def stalls(
        self, imp: Impact, ft: Feature, t: float, y: FloatArray, detail: dict[str, Any]
    ) -> bool:
        """Do the impacts accumulate here?  Pressed together, the pair rebounds too slowly
        to be followed: slower than ``ZENO_SPEED`` (relative), or so slowly that its hop,
        v²/(2a), stays below the rounding of the gap (``GAP_ROUNDING`` × the positions'
        size), where no next contact can be told from this one."""
        a = self.pressed(imp, ft, t, y, abs(detail["normal_speed_before"]))
        if not a > 0:
            return False
        v: float = detail["normal_speed_after"]
        if v < ZENO_SPEED * (1.0 + abs(detail["normal_speed_before"])):
            return True
        below: bool = v * v <= 2.0 * a * GAP_ROUNDING * 4 * detail["gap_scale"]
        return below

    def contact_time(self, imp: Impact, ft: Feature, s: Snapshot, g: npt.ArrayLike) -> float:
        """Closed-form time to the next contact of a sphere or point (inf if none): under
        uniform gravity a plane gap is quadratic in τ, and the relative motion of two
        bodies is uniform (gravity cancels), so |d + w τ| = a_i + a_j is a quadratic."""
        fwd = self.forward
        i = imp.i
        g = np.broadcast_to(g, s.r.shape)  # each body's (a resting one's: along its plane)
        if imp.j is None:
            tau = contacts.plane_contact_time(
                float(imp.gap(s, ft)), float(s.v[i] @ imp.normal), float(g[i] @ imp.normal)
            )
        else:
            j = imp.j
            tau = contacts.sphere_contact_time(s.r[i] - s.r[j], s.v[i] - s.v[j], ft.a + ft.a_s)
        if tau < math.inf:
            s2 = fwd.snapshot(s.t + tau, fwd.pack(s))
            s2.r += s.v * tau + 0.5 * g * tau * tau
            s2.v += g * tau
            if self.touch(imp, ft, s2):
                return math.inf
        return tau


def solve_lcp(W: FloatArray, q: FloatArray) -> FloatArray | None:
    """The linear complementarity problem P ≥ 0, w = W P + q ≥ 0, P·w = 0, solved exactly.

    For a small symmetric positive semi-definite W (m ≤ 8 contacts): by its
    complementary bases, the supports S in order of size whose W_SS is invertible
    (condition below 1/(m RANK_RTOL)), P_S solving W_SS P_S = −q_S; the first with
    P_S ≥ 0 and w ≥ 0 off S, within the rounding of their terms (2^6 eps m × the size of
    W P and q).  A PSD LCP that is feasible (here: a body against a plane or a body,
    whose normal impulses cannot cancel) has such a basic solution; the w of every
    solution is the same, so the velocity after is unique where the impulses are not.

    Parameters
    ----------
    W : ndarray, shape (m, m)
        The Delassus matrix (W_kl = n_k·K(S_k, S_l) n_l, the change of contact k's normal
        velocity per unit impulse at l), 1/kg, symmetric positive semi-definite, m ≥ 1;
        an ndarray (it is indexed by lists of indices).
    q : ndarray, shape (m,)
        The normal velocities before less their targets (u⁻ − t), m/s; an ndarray.

    Returns
    -------
    P : ndarray, shape (m,) or None
        The normal impulses P ≥ 0, N s, or None where there is no basic solution (an
        infeasible problem).

    Raises
    ------
    ValueError
        Where the shapes of ``W`` and ``q`` do not match (numpy's matmul).
    ZeroDivisionError
        Where m = 0 (no contacts).
    TypeError
        Where ``W`` or ``q`` is a list rather than an ndarray and a support S is tried
        (q has a negative entry).

    Examples
    --------
    Two dependent contacts (W singular): the impulses are one basic solution, the
    velocities after, w = W P + q, are zero at both, as every solution's:

    >>> W, q = np.ones((2, 2)), np.array([-2.0, -2.0])
    >>> P = solve_lcp(W, q)
    >>> P.tolist(), (W @ P + q).tolist()
    ([2.0, 0.0], [0.0, 0.0])
    >>> solve_lcp(np.array([[2.0, 1.0], [1.0, 2.0]]), np.array([-3.0, -3.0])).tolist()
    [1.0, 1.0]
    """
    from itertools import combinations

    m = len(q)
    rnd = 2**6 * EPS * m
    limit = 1.0 / (RANK_RTOL * m)
    for size in range(m + 1):
        for S in combinations(range(m), size):
            P = np.zeros(m)
            if S:
                WS = W[np.ix_(S, S)]
                if np.linalg.cond(WS) > limit:
                    continue
                P[list(S)] = np.linalg.solve(WS, -q[list(S)])
            big = float(np.abs(P).max(initial=0.0))
            if np.any(-rnd * big > P):
                continue
            w = W @ P + q
            size_w = float(np.abs(W).max()) * big + float(np.abs(q).max())
            if np.any(w < -rnd * size_w):
                continue
            return np.maximum(P, 0.0)
    return None


def falls_in(scene: Scene, imp: Impact, ft: Feature, t: float) -> SceneError:
    """The error of a pair that touches and then falls in where it cannot rest.

    A pair cannot rest (:meth:`.support.Support.can_rest`) where it is two bodies on each
    other, a rim, or a body held by a joint.  The error is returned, not raised.

    Parameters
    ----------
    scene : Scene
        The scene (:class:`mechanics.scenes.spec.Scene`) whose file the error names.
    imp : Impact
        The impact effect of the pair (its ``where`` is the field named).
    ft : Feature
        The contact feature that touches.
    t : float
        The time of the touch, s.

    Returns
    -------
    SceneError
        The error to raise, naming the impact effect, the feature and t.

    Examples
    --------
    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...     "bodies": [{"name": "ball", "shape": "solid_sphere", "mass": 1.0, "radius": 0.5,
    ...                 "initial": {"position": [0.0, 0.0, 0.5]}}],
    ...     "effects": [{"type": "impact", "body": "ball", "plane_point": [0.0, 0.0, 0.0],
    ...                  "plane_normal": [0.0, 0.0, 1.0], "restitution": 0.5}]})
    >>> imp = Engine(sc).model.impacts[0]
    >>> err = falls_in(sc, imp, imp.features[0], 0.25)
    >>> type(err).__name__, err.field == imp.where == "effects[0]", "0.25 s" in err.reason
    ('SceneError', True, True)
    """
    return scene.error(
        imp.where,
        f"{ft.label} touch at t = {t:.17g} s and then fall in, with no separation that "
        "float64 can resolve: a resting contact, which this pair cannot have (two bodies "
        "on each other, a rim, or a body held by a joint; shorten the duration)",
    )


def zeno(scene: Scene, t: float, who: str = "the bodies") -> SceneError:
    """The error of impacts that accumulate (or of events beyond :data:`MAX_EVENTS`).

    The error is returned, not raised; it names ``scene.duration`` (the remedy: shorten
    it).

    Parameters
    ----------
    scene : Scene
        The scene (:class:`mechanics.scenes.spec.Scene`) whose file and duration the
        error names.
    t : float
        The time the impacts accumulate near, s.
    who : str, optional
        Who comes to rest (an impact pair's label, or an effect's place in the file).

    Returns
    -------
    SceneError
        The error to raise.

    Examples
    --------
    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 4.0},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 1.0}]})
    >>> err = zeno(sc, 2.5, "the ball")
    >>> err.field, err.reason.startswith("the ball come to rest"), f"{MAX_EVENTS}" in err.reason
    ('scene.duration', True, True)
    """
    return scene.error(
        "scene.duration",
        f"{who} come to rest in contact (the impacts accumulate, or e = 0) near "
        f"t = {t:.6g} s before the end {scene.duration:g} s, in more events than "
        f"{MAX_EVENTS} that it can follow: shorten the duration",
    )
