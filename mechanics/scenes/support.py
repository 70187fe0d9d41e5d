"""Resting contact: bodies supported by the plane of an ``impact``, the support forces that
hold them there, and when they let go.

- **When a body rests.**  At t = 0, the contacts of a free body (a point or a rigid
  body) touching a plane (gap within rounding) with no approach speed, pressed on it by
  the loads (:meth:`Support.begin`); or when its impacts accumulate
  (:meth:`Support.rest`, called by :meth:`.impacts.Resolver.resolve` where an impact
  stalls): the rebound left (below the rest threshold, :meth:`.impacts.Resolver.stalls`)
  is removed by the impulse that stops the touching contacts' normal motion (either
  sign: the least change of the kinetic energy, its energy in the event), and the
  ``rest`` event is dated at the accumulation time t∞ = t_k + 2 v_k / (a (1 − e)), the
  sum of the remaining bounces under the press a at the last impact t_k (exact under
  a constant press: the sphere's t∞ = t₁ (1 + e)/(1 − e)); from t_k to t∞ the hops,
  below the gap's rounding, are followed as rest.
- **The support forces** (added to the loads by :meth:`Support.add`, from the other
  loads): at each active contact a force f at the contact point S such that the gap's
  second derivative is zero (the feature's point X: G for a sphere, the corner for a
  polyhedron: n·a_X = 0), with Coulomb friction per pair: *smooth* (f = λ n), *stick*
  (the contact point's slip does not change: f free, ȧ_slip = 0; for a sphere the slip
  velocity v_G + ω × ρ_S with ρ_S = −a n fixed in space, so rolling), or *slip*
  (f = λ (n − μ ŝ), ŝ the slip's direction).  These are linear equations in the
  unknowns (the response of a point's acceleration to a force at S is the contact's
  inverse mass matrix K, as for an impulse); several contacts of one body (a box on its
  face: four corners) make them singular, and the least-norm solution is taken (the
  accelerations are the same for every solution where the forces' directions are the
  same, a box that does not turn about the normal; a box that spins while sliding has
  forces that depend on the distribution: the least-norm one is the model's choice).
- **Modes and switches** (located on each step like a contact, :meth:`Support.first_switch`):
  an active contact's normal force falls through zero (it lets go: the contacts are
  chosen again, :meth:`Support.switch`); sticking, the friction needed reaches μ λ
  (it slips the way its friction force pointed: the force is continuous, and the slip
  begins with zero rate); slipping, the slip's component along
  its direction when the slip began falls through zero (it sticks if static friction
  suffices, else slips on).  The contacts and the mode are chosen as the largest set of
  the touching contacts whose forces are pressing (λ ≥ 0) while the others' gaps do not
  fall (their normal acceleration ≥ 0); none: the body leaves the plane (``lift_off``).
  A contact that cannot stick by a finite margin (where it comes to rest, after an
  impact, at a load's switch) begins to slip in the direction ŝ its slip's rate points
  along, ȧ_slip = k ŝ with k > 0 (:meth:`Support._onset`: the force sticking would
  need points elsewhere where the inverse mass is not isotropic); several such
  contacts slip the ways their stick forces pushed where each one's slip rate agrees.
- **Struck while resting** (another contact of the pair hits, :meth:`Support.after_impact`):
  the resting contacts take part in the impact problem (they are in contact whatever the
  integration's drift of their gaps), and after it the ones that separate leave the
  support; the others are chosen again.
- **Refused with one line** (a :class:`~mechanics.scenes.errors.SceneError`): a rest
  that cannot be resolved: Painlevé's paradox (a slipping contact whose normal
  acceleration falls as its support force grows, n·K (n − μ ŝ) ≤ 0), no set of
  pressing contacts, contacts of one pair that partly stick and partly slip, a slip
  from rest whose direction is not exactly one (one contact) or not found (several);
  and a
  rest this model does not treat: two bodies resting on each other, a rim (disc,
  cylinder) resting on its edge or face, a body held by a joint.
- **Series**: each resting body's total support force, ``support_x``, ``_y``, ``_z``
  (zero while it does not rest), from the record of the modes (:attr:`Support.timeline`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from itertools import combinations
from typing import TYPE_CHECKING, Any, TypeAlias, cast

import numpy as np
import numpy.typing as npt

from . import contacts
from .bodies import Kinematics, Point
from .collision import Hit, StepFit
from .impacts import CLOSING_ROUNDING, GAP_ROUNDING
from .state import point_acceleration
from .trajectory import EPS, Event, tolerance_scale
from .vectors import FloatArray, cross3

if TYPE_CHECKING:  # for annotations only
    from .effects import Loads, Snapshot
    from .effects.impact import Feature, Impact
    from .errors import SceneError
    from .forward import Forward
    from .model import Model

__all__ = ["FORCE_ROUNDING", "Rest", "Support"]

#: a support force (or a friction margin, a slip) within this multiple of eps × the size
#: of its terms is zero: the solve of a few dozen rounded products, at a switch just made
FORCE_ROUNDING = 2**8 * EPS
#: a slip that has come to its end (located on the step) is zero up to the integration's
#: error of the velocities: this × the contact speeds when it began, × the scene's
#: rtol / 1e-12 where looser (DOP853's worst measured drift at rtol 1e-12, as for the
#: conserved quantities; a box sliding to a stop leaves 1e-13 of its 1 m/s across)
SLIP_END_RTOL = 2**20 * EPS
#: switches of the resting contacts at one instant before the run stops (each choice
#: is made once per contact set and mode: a few suffice)
MAX_SWITCHES = 16
#: a rank of the support's equations: a singular value below this × the largest (× the
#: number of unknowns) is a dependency of the contacts (four corners of one face)
RANK_RTOL = 2**6 * EPS
#: a stick found at its switch needs friction within this × its force of the cone's
#: limit (the switch's location on the step, of a margin whose terms are the forces:
#: FORCE_ROUNDING × the steps of a Brent search's rounding); a stick that needs more
#: at a switch is broken, not left
CONE_ROUNDING = 2**20 * EPS
#: the angles searched for the direction a contact begins to slip in from rest (a sign
#: change of the slip rate's turn between two of them is refined with Brent's method):
#: 5.6 degrees apart, finer than the turn of an inverse mass's anisotropy can bend twice
ONSET_ANGLES = 64


@dataclass(frozen=True)
class Rest:
    """A body resting on the plane of the impact ``imp``: its contacts and friction mode.

    The features (indices into ``imp.features``) that carry it, the friction mode
    ("smooth", "stick" or "slip") and, slipping, each contact's slip direction when the
    slip began (``ref``: what its switch watches; the friction follows the slip's
    current direction).  :class:`Support` builds it; the constructor stores what it is
    given and checks nothing.

    Parameters
    ----------
    imp : Impact
        The impact effect whose plane carries the body
        (:class:`mechanics.scenes.effects.impact.Impact`).
    active : tuple[int, ...]
        The carrying features, indices into ``imp.features``.
    friction : str
        The mode: ``"smooth"``, ``"stick"`` or ``"slip"``.
    ref : tuple[ndarray, ...], each of shape (3,), optional
        Slipping: each active contact's unit slip direction when the slip began (not
        compared). Default none.
    speed : float, optional
        Slipping: the size of the contacts' speeds when the slip began, m/s (what a slip
        that has come to its end is zero relative to; not compared). Default 0.

    Examples
    --------
    A ball placed on a smooth floor rests on its one contact from t = 0:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "rest", "duration": 1.0, "samples": 3},
    ...     "bodies": [{"name": "ball", "shape": "solid_sphere", "mass": 2.0, "radius": 0.5,
    ...                 "initial": {"position": [0.0, 0.0, 0.5]}}],
    ...     "effects": [{"type": "gravity", "g": 8.0}, {"type": "impact", "body": "ball",
    ...         "plane_point": [0.0, 0.0, 0.0], "plane_normal": [0.0, 0.0, 1.0],
    ...         "restitution": 0.5}]}))
    >>> tr = eng.run()
    >>> (imp, rest), = eng.support.at(0.5).items()
    >>> rest == Rest(imp, (0,), "smooth"), eng.support.active(imp, imp.features[0])
    (True, True)
    """

    imp: Impact
    active: tuple[int, ...]
    friction: str
    ref: tuple[FloatArray, ...] = field(default=(), compare=False)
    #: slipping: the size of the contacts' speeds when the slip began (what a slip that
    #: has come to its end is zero relative to)
    speed: float = field(default=0.0, compare=False)


#: the resting pairs: impact -> its :class:`Rest`
Rests: TypeAlias = dict["Impact", Rest]
#: a support force: (rest, feature index, f), f in space components on the body at its
#: contact point
SupportForce: TypeAlias = tuple[Rest, int, FloatArray]
#: the support's equations A x = b with their blocks (rest, feature, B, c0, c1): the
#: force f = B x[c0:c1]
Equations: TypeAlias = tuple[FloatArray, FloatArray, list[tuple[Rest, int, FloatArray, int, int]]]
#: one contact of the equations: (rest, feature, body, X, S, n, stick?, force direction
#: d, round?)
_Contact: TypeAlias = tuple[
    Rest, int, int, FloatArray, FloatArray, FloatArray, bool, FloatArray, bool
]


class Support:
    """The resting contacts of a :class:`~mechanics.scenes.model.Model`.

    When a body rests, the support forces that hold it and when it lets go: see the
    module's docstring.  The engine builds it (:class:`mechanics.scenes.engine.Engine`);
    the constructor stores its model and forward dynamics and checks nothing (the
    methods raise a :class:`~mechanics.scenes.errors.SceneError` for a rest they cannot
    resolve).

    Parameters
    ----------
    model : Model
        The scene compiled (:class:`mechanics.scenes.model.Model`).
    forward : Forward
        Its forward dynamics (:class:`mechanics.scenes.forward.Forward`), the loads
        and accelerations the support forces are solved from.

    Examples
    --------
    A ball of 2 kg resting on the floor under g = 8 m/s² is held by m g = 16 N at
    every sample:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "rest", "duration": 1.0, "samples": 3},
    ...     "bodies": [{"name": "ball", "shape": "solid_sphere", "mass": 2.0, "radius": 0.5,
    ...                 "initial": {"position": [0.0, 0.0, 0.5]}}],
    ...     "effects": [{"type": "gravity", "g": 8.0}, {"type": "impact", "body": "ball",
    ...         "plane_point": [0.0, 0.0, 0.0], "plane_normal": [0.0, 0.0, 1.0],
    ...         "restitution": 0.5}]}))
    >>> tr = eng.run()
    >>> tr.series["support_z"].tolist(), 2.0 * 8.0, eng.support.model is eng.model
    ([16.0, 16.0, 16.0], 16.0, True)
    """

    def __init__(self, model: Model, forward: Forward) -> None:
        self.model = model
        self.forward = forward
        #: impact -> its :class:`Rest` (the resting pairs now)
        self.rests: Rests = {}
        #: [(t, rests from t on)]: the modes over the run, for the report
        self.timeline: list[tuple[float, Rests]] = []
        #: the time of the last switch (a mode just chosen starts at its limit)
        self.switched: float | None = None
        #: (time, switches at it): a choice that never holds is stopped
        self._same: tuple[float | None, int] = (None, 0)

    # -------------------------------------------------------------- the record
    def clear(self) -> None:
        self.rests, self.timeline, self.switched = {}, [], None
        self._same = (None, 0)

    def _set(self, t: float, rests: Mapping[Impact, Rest]) -> None:
        self.rests = dict(rests)
        self.timeline.append((float(t), dict(self.rests)))
        self.switched = float(t)

    def at(self, t: float) -> Rests:
        """The resting pairs at time t (the last record at or before t)."""
        out: Rests = {}
        for t0, rests in self.timeline:
            if t0 <= t:
                out = rests
        return out

    def active(self, imp: Impact, ft: Feature) -> bool:
        """Does the feature ``ft`` of ``imp`` carry a support now (its gap is held at zero,
        not searched for a contact)?"""
        rest = self.rests.get(imp)
        return rest is not None and any(imp.features[b] is ft for b in rest.active)

    # ------------------------------------------------------------- the forces
    def add(self, t: float, s: Snapshot, out: Loads) -> None:
        """Add the support forces of the resting pairs to the loads ``out`` (the other
        loads already summed)."""
        for rest, b, f in self.forces(t, s, out)[0]:
            imp = rest.imp
            ft = imp.features[b]
            S, _ = imp.contact(s, ft)
            out.force(imp.i, f, s.to_body(imp.i, S - s.r[imp.i]))

    def forces(self, t: float, s: Snapshot, out: Loads) -> tuple[list[SupportForce], float]:
        """The support forces ``[(rest, feature index, f)]`` (space components, on the
        body at its contact point) from the loads ``out``, and the size of their terms."""
        rows, scale = self._equations(t, s, out, self.rests)
        if not rows:
            return [], scale
        A, b, blocks = rows
        x = _solve(A, b)
        if x is None:
            raise self._unresolved(
                t,
                next(iter(self.rests.values())).imp,
                "no support forces hold the body on the plane (the equations have no solution)",
            )
        forces = [(rest, k, B @ x[c0:c1]) for rest, k, B, c0, c1 in blocks]
        return forces, float(np.abs(A).max() * np.abs(x).max() + np.abs(b).max())

    def _equations(
        self, t: float, s: Snapshot, out: Loads, rests: Mapping[Impact, Rest]
    ) -> tuple[Equations | None, float]:
        """The linear equations A x = b of the support forces (see the module's docstring),
        with the blocks ``(rest, feature, B, c0, c1)``: the force f = B x[c0:c1]."""
        fwd = self.forward
        cons: list[_Contact] = []  # (rest, feature, body, X, S, n, stick?, direction d, round?)
        for rest in rests.values():
            imp = rest.imp
            for b in rest.active:
                ft = imp.features[b]
                S, n = imp.contact(s, ft)
                X = imp.feature_point(s, ft)
                if rest.friction == "slip":
                    # the slip's direction; past its zero along the direction it began
                    # with (where the switch is searched), that direction: the friction
                    # continues smoothly to the switch, which the step can then contain
                    ref = rest.ref[rest.active.index(b)]
                    u = imp._relative_velocity(s, S)
                    u = u - (u @ n) * n
                    # (a slip within its end's rounding has no direction of its own)
                    moving = u @ ref > 0 and np.linalg.norm(u) > self._slip_end(rest.speed)
                    # (moving: |u| > 0, so it has a direction)
                    shat = cast("FloatArray", _unit(u)) if moving else ref
                    d = n - imp.mu_f * shat
                else:
                    d = n
                cons.append((rest, b, imp.i, X, S, n, rest.friction == "stick", d, ft.at is None))
        if not cons:
            return None, 0.0
        dy = fwd.layout.derivative(s, out.F, out.M_A, out.rates)
        kin: dict[int, Kinematics] = {}
        rows_b: list[FloatArray] = []
        row_of: list[tuple[int, int]] = []
        col_of: list[tuple[int, int, FloatArray]] = []
        nrow = ncol = 0
        for _, _, k, X, S, n, stick, d, round_ in cons:
            if k not in kin:
                kin[k] = fwd.kinematics(s, dy, k)
            origin, base, w, alpha = kin[k]
            rx, rs = X - origin, S - origin
            a_X = point_acceleration(base, alpha, w, rx)
            if stick:  # the slip's rate: a sphere's contact point is not a material one
                a_S = base + cross3(alpha, rs)
                if not round_:
                    a_S = a_S + cross3(w, cross3(w, rs))
                rows_b.append(-(a_S - (a_S @ n) * n) - (a_X @ n) * n)
                row_of.append((nrow, nrow + 3))
                nrow += 3
                col_of.append((ncol, ncol + 3, np.eye(3)))
                ncol += 3
            else:
                rows_b.append(np.array([-(a_X @ n)]))
                row_of.append((nrow, nrow + 1))
                nrow += 1
                col_of.append((ncol, ncol + 1, d[:, None]))
                ncol += 1
        A = np.zeros((nrow, ncol))
        for a, (rest_a, _, ka, Xa, Sa, na, stick_a, _, _) in enumerate(cons):
            r0, r1 = row_of[a]
            for c, (_, _, kc, _, Sc, _, _, _, _) in enumerate(cons):
                if kc != ka:
                    continue
                imp = rest_a.imp
                c0, c1, B = col_of[c]
                if stick_a:  # normal row from X, tangential rows from S
                    Kn = imp.inverse_mass(s, ka, Xa, Sc)
                    Kt = imp.inverse_mass(s, ka, Sa, Sc)
                    P = np.outer(na, na)
                    M = P @ Kn + (np.eye(3) - P) @ Kt
                    A[r0:r1, c0:c1] = M @ B
                else:
                    A[r0:r1, c0:c1] = na @ imp.inverse_mass(s, ka, Xa, Sc) @ B
        rhs = np.concatenate(rows_b)
        blocks = [
            (c[0], c[1], col_of[i][2], col_of[i][0], col_of[i][1]) for i, c in enumerate(cons)
        ]
        # the size of the forces' terms: each body's mass × its free acceleration
        scale = float(sum(s.m[k] * np.abs(kin[k][1]).sum() for k in kin))
        return (A, rhs, blocks), scale

    # ---------------------------------------------------------- begin and rest
    def begin(self) -> list[Event]:
        """At t = 0: every free body touching a plane with no approach speed, pressed on
        it, rests (see the module's docstring)."""
        self.clear()
        md, fwd = self.model, self.forward
        s = fwd.snapshot(0.0, md.y0)
        found: dict[Impact, tuple[int, ...]] = {}
        for imp in md.impacts:
            if imp.j is not None or not self._free(imp.i):
                continue
            touching = tuple(
                b
                for b, ft in enumerate(imp.features)
                if ft.support is None
                and self._touching(s, imp, ft)
                and abs(imp.approach(s, ft)) <= CLOSING_ROUNDING * imp.speed_scale(s, ft)
            )
            if touching:
                found[imp] = touching
        if not found:
            return []
        rests: Rests = {}
        for imp, feats in found.items():
            press = self._press(0.0, s, imp)
            rest = self._choose(0.0, s, imp, feats, dict(rests), self._speed(s, imp, feats, press))
            if rest is not None:
                rests[imp] = rest
        if rests:
            self._set(0.0, rests)
        return [self._event(0.0, r, "rest") for r in rests.values()]

    def _press(self, t: float, s: Snapshot, imp: Impact) -> float:
        """How hard the loads alone press the body along −n (its G's acceleration)."""
        out = self.forward.loads_without_support(t, s)
        return max(-float(out.F[imp.i] @ imp.normal) / float(s.m[imp.i]), 0.0)

    def _speed(self, s: Snapshot, imp: Impact, feats: Sequence[int], press: float) -> float:
        """The speed a resting body's slip is zero relative to: the speed the press
        gives over the body's size, √(a L) (its velocities were formed on that scale: a
        slip of their rounding is none), or the contacts' own speeds if larger."""
        L = max(imp.gap_scale(s, imp.features[b]) for b in feats)
        return max(
            math.sqrt(max(press, 0.0) * L), *(imp.speed_scale(s, imp.features[b]) for b in feats)
        )

    def _free(self, k: int) -> bool:
        """A free body: a point or a rigid body (not pinned, guided, fixed or a tank)."""
        return isinstance(self.model.layout.bodies[k], Point)

    def _touching(self, s: Snapshot, imp: Impact, ft: Feature) -> bool:
        scale = imp.gap_scale(s, ft)
        return abs(float(imp.gap(s, ft))) <= GAP_ROUNDING * 4 * scale

    def can_rest(self, imp: Impact, ft: Feature) -> str | None:
        """Why the pair cannot rest in this model (None: it can)."""
        if imp.j is not None:
            return "two bodies resting on each other are not modelled"
        if not self._free(imp.i):
            return "a body held by a joint resting on a plane is not modelled"
        if ft.support is not None:
            return "a rim (disc, ring, cylinder) resting on a plane is not modelled"
        return None

    def rest(
        self,
        t: float,
        y: FloatArray,
        imp: Impact,
        ft: Feature,
        detail: Mapping[str, Any],
        press: float,
        events: list[Event],
    ) -> FloatArray:
        """The impacts of ``imp`` accumulate at t (``detail``: the last impact's, ``press``
        the loads' push there): the touching contacts rest from now on (see the module's
        docstring); the ``rest`` event; the new state."""
        fwd = self.forward
        s = fwd.snapshot(t, y)
        # the contact just found (its event located there: at contact, whatever the
        # rounding of its gap), those touching with it, and those already resting
        held = self.rests[imp].active if imp in self.rests else ()
        feats = tuple(
            b
            for b, f in enumerate(imp.features)
            if f.support is None and (f is ft or self._touching(s, imp, f) or b in held)
        )
        why = self.can_rest(imp, ft) or (None if feats else "no contact touches")
        if why is not None:
            raise self._unresolved(t, imp, why)
        # stop the touching contacts' normal motion: the least-energy change (either sign)
        pts = [imp.contact(s, imp.features[b]) for b in feats]
        u = np.array([-imp.approach(s, imp.features[b]) for b in feats])
        W = np.array(
            [[na @ imp.inverse_mass(s, imp.i, Sa, Sb) @ nb for Sb, nb in pts] for Sa, na in pts]
        )
        P = _least_norm(0.5 * (W + W.T), -u)
        T0 = _kinetic(s, imp.i)
        for (S, n), p in zip(pts, P, strict=True):
            imp.kick(s, imp.i, p * n, S)
        removed = T0 - _kinetic(s, imp.i)
        # the last hop began at the last impact t_k with the rebound v_k (``detail``: the
        # impact that stalls, or the last one before a touch that falls in)
        t_k = float(detail.get("t", t))
        v = max(float(detail.get("normal_speed_after", 0.0)), 0.0)
        t_inf = t_k + (2.0 * v / (press * (1.0 - imp.e)) if v > 0 and imp.e < 1 else 0.0)
        t_inf = max(t_inf, float(t))
        y = fwd.pack(s)
        rests = dict(self.rests)
        rest = self._choose(t, s, imp, feats, rests, self._speed(s, imp, feats, press))
        if rest is None:
            raise self._unresolved(t, imp, "the loads do not press it on the plane")
        rests[imp] = rest
        self._set(t, rests)
        ev = self._event(t_inf, rest, "rest")
        ev.detail.update(
            last_impact=t_k,
            rebound_removed=v,
            energy_removed=float(removed),
            press=float(press),
            accumulation_time=float(t_inf),
        )
        events.append(ev)
        return y

    def after_impact(
        self, t: float, y: FloatArray, imp: Impact, events: list[Event], floor: float = 0.0
    ) -> FloatArray:
        """After an impulse on a resting pair (another of its contacts struck, the
        resting ones in its problem): the contacts that now separate (beyond the
        rounding of the contact speeds, or of ``floor``, those the instant began with)
        leave the support, the others are chosen again (``lift_off`` where the body
        leaves); the state."""
        s = self.forward.snapshot(t, y)
        old = self.rests[imp]
        keep = tuple(
            b
            for b in old.active
            if -imp.approach(s, imp.features[b])
            <= CLOSING_ROUNDING * max(imp.speed_scale(s, imp.features[b]), floor)
        )
        others = {k: r for k, r in self.rests.items() if k is not imp}
        rest = self._choose(t, s, imp, keep, others, old.speed) if keep else None
        if rest is None:
            events.append(self._event(t, old, "lift_off"))
        else:
            others[imp] = rest
        self._set(t, others)
        return y

    # ----------------------------------------------------------------- choice
    def _choose(
        self,
        t: float,
        s: Snapshot,
        imp: Impact,
        feats: tuple[int, ...],
        others: Rests,
        floor: float = 0.0,
        leaving: bool = False,
    ) -> Rest | None:
        """The largest set of ``feats`` that presses (λ ≥ 0) while the others' gaps do
        not fall, with its friction mode (``floor``, ``leaving``: see :meth:`_mode`);
        None if no contact presses."""
        for size in range(len(feats), 0, -1):
            for sub in combinations(feats, size):
                rest = self._mode(t, s, imp, sub, others, floor, leaving)
                if rest is None:
                    continue
                if self._holds(t, s, imp, rest, feats, others):
                    return rest
        return None

    def _mode(
        self,
        t: float,
        s: Snapshot,
        imp: Impact,
        sub: tuple[int, ...],
        others: Rests,
        floor: float = 0.0,
        leaving: bool = False,
    ) -> Rest | None:
        """The friction mode of the contacts ``sub`` (see the module's docstring); a slip
        within rounding of the contact speeds (or of ``floor``, those of a slip just
        ended) is none.  ``leaving``: the contacts stuck until this switch, so a stick at
        the limit of its cone (within :data:`CONE_ROUNDING`) is leaving it, and slips the
        way its friction force pointed (the force is continuous); a cone broken by more
        (after an impact, a load switched on) slips in the direction of
        :meth:`_onset`."""
        if imp.mu_f == 0:
            return Rest(imp, sub, "smooth")
        slips = [self._slip(s, imp, imp.features[b]) for b in sub]
        # a stick's slip drifts by the integration's error of the velocities too: zero
        # up to a slip's end relative to the contact speeds now (or to ``floor``)
        size = max(size for _, size in slips)
        zero = max(FORCE_ROUNDING * size, self._slip_end(max(floor, size)))
        moving = [float(np.linalg.norm(u)) > zero for u, _ in slips]
        if all(moving):
            speed = max(size for _, size in slips)
            # (each moving: |u| > zero > 0, so each has a direction)
            dirs = tuple(cast("FloatArray", _unit(u)) for u, _ in slips)
            return Rest(imp, sub, "slip", dirs, speed)
        if any(moving):
            raise self._unresolved(
                t, imp, "some of its contacts stick while others slip (not modelled)"
            )
        stick = Rest(imp, sub, "stick")
        forces = self._trial(t, s, {**others, imp: stick})
        if forces is None:
            return None
        pushed: list[FloatArray | None] = []
        excess = -math.inf  # the friction needed beyond the cone, relative to the force
        for rest, b, f in forces:
            if rest is not stick:
                continue
            n = imp.contact(s, imp.features[b])[1]
            lam = float(f @ n)
            ft_ = f - lam * n
            over = float(np.linalg.norm(ft_)) - imp.mu_f * lam
            excess = max(excess, over / max(float(np.linalg.norm(f)), 1e-300))
            pushed.append(_unit(-ft_))
        if excess <= (-FORCE_ROUNDING if leaving else FORCE_ROUNDING):
            return stick
        if any(d is None for d in pushed):  # pragma: no cover - a cone broken with no push
            return None
        driven = cast("list[FloatArray]", pushed)  # (none is None)
        speed = max(floor, max(s_ for _, s_ in slips))
        if leaving and excess <= CONE_ROUNDING:
            return Rest(imp, sub, "slip", tuple(driven), speed)
        if len(sub) == 1:  # one contact: the direction Coulomb's law makes it slip in
            return self._onset(t, s, imp, sub, others, driven[0], speed)
        slip = Rest(imp, sub, "slip", tuple(driven), speed)
        rates = self._slip_rates(t, s, imp, slip, others)
        if rates is not None and all(
            float(a @ d) > FORCE_ROUNDING * size for (a, size), d in zip(rates, driven, strict=True)
        ):
            return slip
        raise self._unresolved(
            t,
            imp,
            "its contacts begin to slip with friction, and the loads do not drive each "
            "along the way its friction opposes (the directions of a slip from rest at "
            "several contacts are not modelled)",
        )

    def _slip_rates(
        self, t: float, s: Snapshot, imp: Impact, rest: Rest, others: Rests
    ) -> list[tuple[FloatArray, float]] | None:
        """The rate of each of ``rest``'s contacts' slip (its tangential acceleration,
        space components) with the support forces ``rest`` would have, with the size of
        its terms; None where those forces have no solution or one lets go."""
        fwd = self.forward
        forces = self._trial(t, s, {**others, imp: rest})
        if forces is None:
            return None
        out = fwd.loads_without_support(t, s)
        for r, b, f in forces:
            if r is rest and float(f @ imp.contact(s, imp.features[b])[1]) < 0.0:
                return None  # a slip pulling its contact down: not this mode
            S, _ = r.imp.contact(s, r.imp.features[b])
            out.force(r.imp.i, f, s.to_body(r.imp.i, S - s.r[r.imp.i]))
        dy = fwd.layout.derivative(s, out.F, out.M_A, out.rates)
        origin, base, w, alpha = fwd.kinematics(s, dy, imp.i)
        n = imp.normal
        rates: list[tuple[FloatArray, float]] = []
        for b in rest.active:
            ft = imp.features[b]
            rs = imp.contact(s, ft)[0] - origin
            a = base + cross3(alpha, rs)
            if ft.at is not None:  # a material point (a corner): a sphere's is not
                a = a + cross3(w, cross3(w, rs))
            size = float(np.abs(base).sum() + (np.abs(alpha).sum() + w @ w) * np.abs(rs).sum())
            rates.append((a - (a @ n) * n, size + 1e-300))
        return rates

    def _onset(
        self,
        t: float,
        s: Snapshot,
        imp: Impact,
        sub: tuple[int, ...],
        others: Rests,
        driven: FloatArray,
        speed: float,
    ) -> Rest:
        """A contact that cannot stick begins to slip in a direction ŝ its own slip's
        rate points along (ȧ_slip = k ŝ, k > 0, with the friction −μ λ ŝ): with an
        inverse mass that is not isotropic, not the direction of the force sticking
        would need (``driven``).  The angle of ŝ in the plane is searched on
        :data:`ONSET_ANGLES` points and refined with Brent's method; more than one such
        direction is refused with one line (Coulomb's law does not choose)."""
        from scipy.optimize import brentq

        n = imp.normal
        e1 = driven - (driven @ n) * n
        e1 = e1 / np.linalg.norm(e1)
        e2 = cross3(n, e1)

        def at(th: float) -> tuple[float, float] | None:
            shat = math.cos(th) * e1 + math.sin(th) * e2
            rates = self._slip_rates(t, s, imp, Rest(imp, sub, "slip", (shat,), speed), others)
            if rates is None:
                return None
            a, size = rates[0]
            return float(n @ cross3(shat, a)) / size, float(shat @ a) / size

        def turn(th: float) -> float:
            v = at(th)
            if v is None:
                raise _NoSlip
            return v[0]

        grid = np.linspace(-math.pi, math.pi, ONSET_ANGLES + 1)
        vals = [at(th) for th in grid]
        found: list[float] = []
        for k in range(ONSET_ANGLES):
            va, vb = vals[k], vals[k + 1]
            if va is None or vb is None or (va[0] > 0) == (vb[0] > 0):
                continue
            if va[0] == 0.0:
                th = grid[k]
            else:
                try:
                    th = brentq(turn, grid[k], grid[k + 1], xtol=EPS, rtol=4 * EPS)
                except _NoSlip:  # a direction within where the slip lets go: not a root
                    continue
            v = at(th)
            if v is not None and v[1] > FORCE_ROUNDING:
                found.append(th)
        if len(found) != 1:
            raise self._unresolved(
                t,
                imp,
                f"its contact cannot stick, and Coulomb's law lets it begin to slip in "
                f"{len(found)} directions (a slip's rate along its friction's direction: "
                "not modelled where not exactly one)",
            )
        shat = math.cos(found[0]) * e1 + math.sin(found[0]) * e2
        return Rest(imp, sub, "slip", (shat,), speed)

    def _trial(
        self, t: float, s: Snapshot, rests: Mapping[Impact, Rest]
    ) -> list[SupportForce] | None:
        """The support forces that ``rests`` would have at (t, s) (as :meth:`forces`), or
        None where their equations have no solution."""
        out = self.forward.loads_without_support(t, s)
        rows, _ = self._equations(t, s, out, rests)
        if rows is None:
            return []
        A, b, blocks = rows
        x = _solve(A, b)
        if x is None:
            return None
        return [(rest, k, B @ x[c0:c1]) for rest, k, B, c0, c1 in blocks]

    def _holds(
        self,
        t: float,
        s: Snapshot,
        imp: Impact,
        rest: Rest,
        feats: tuple[int, ...],
        others: Rests,
    ) -> bool:
        """Do ``rest``'s forces press (λ ≥ 0 within rounding), and do the touching
        contacts outside it not fall in?  A slipping contact with n·K (n − μ ŝ) ≤ 0 is
        Painlevé's paradox: refused."""
        if rest.friction == "slip":
            for b, shat in zip(rest.active, rest.ref, strict=True):
                ft = imp.features[b]
                S, n = imp.contact(s, ft)
                X = imp.feature_point(s, ft)
                K = imp.inverse_mass(s, imp.i, X, S)
                if float(n @ K @ (n - imp.mu_f * shat)) <= 0.0:
                    raise self._unresolved(
                        t,
                        imp,
                        f"Painlevé's paradox at {ft.label}: with friction {imp.mu_f:g} its "
                        "normal acceleration falls as the support force grows "
                        "(n·K (n − μ ŝ) ≤ 0): no support force, or not a unique one",
                    )
        forces = self._trial(t, s, {**others, imp: rest})
        if forces is None:
            return False
        size = sum(float(np.linalg.norm(f)) for _, _, f in forces) + 1e-300
        for r, b, f in forces:
            n = r.imp.contact(s, r.imp.features[b])[1]
            if float(f @ n) < -FORCE_ROUNDING * size:
                return False
        # the touching contacts outside the set: their gaps must not fall
        out = self.forward.loads_without_support(t, s)
        for r, b, f in forces:
            S, _ = r.imp.contact(s, r.imp.features[b])
            out.force(r.imp.i, f, s.to_body(r.imp.i, S - s.r[r.imp.i]))
        dy = self.forward.layout.derivative(s, out.F, out.M_A, out.rates)
        origin, base, w, alpha = self.forward.kinematics(s, dy, imp.i)
        for b in feats:
            if b in rest.active:
                continue
            ft = imp.features[b]
            rx = imp.feature_point(s, ft) - origin
            a_n = float(imp.normal @ (point_acceleration(base, alpha, w, rx)))
            if a_n < -FORCE_ROUNDING * (float(np.abs(base).sum()) + 1e-300):
                return False
        return True

    def _slip_end(self, speed: float) -> float:
        """The size of a slip that has come to its end, from ``speed`` (see
        :data:`SLIP_END_RTOL`)."""
        return SLIP_END_RTOL * speed * tolerance_scale(self.model.scene)

    def _slip(self, s: Snapshot, imp: Impact, ft: Feature) -> tuple[FloatArray, float]:
        """The contact's slip velocity (across the normal) and the size of its terms."""
        S, n = imp.contact(s, ft)
        u = imp._relative_velocity(s, S)
        return u - (u @ n) * n, imp.speed_scale(s, ft) + 1e-300

    # -------------------------------------------------------------- switches
    def values(self, t: float, y: npt.ArrayLike) -> FloatArray:
        """The switch functions of the resting pairs at (t, y) (see the module's
        docstring), each divided by the size of its terms."""
        fwd = self.forward
        s = fwd.snapshot(t, np.asarray(y, dtype=float))
        if fwd.phase is not None:
            s.phase = fwd.phase
        out = fwd.loads_without_support(t, s)
        forces, size = self.forces(t, s, out)
        size = max(size, sum(float(np.linalg.norm(f)) for _, _, f in forces), 1e-300)
        vals: list[float] = []
        for rest, b, f in forces:
            imp = rest.imp
            ft = imp.features[b]
            n = imp.contact(s, ft)[1]
            lam = float(f @ n)
            vals.append(lam / size)
            if rest.friction == "stick":
                vals.append((imp.mu_f * lam - float(np.linalg.norm(f - lam * n))) / size)
            elif rest.friction == "slip":
                u, scale = self._slip(s, imp, ft)
                vals.append(float(u @ rest.ref[rest.active.index(b)]) / scale)
        return np.array(vals)

    def first_switch(self, fit: StepFit) -> Hit | None:
        """The earliest switch of a resting pair within one step (a :class:`Hit` whose
        effect is the :class:`Support`), or None."""
        if not self.rests or fit.t_b <= fit.t_a:
            return None
        dense = fit.dense

        def g(tt: FloatArray) -> FloatArray:
            return np.array([self.values(float(x), dense(float(x))) for x in tt])

        coef = contacts.chebyshev_fit(g, fit.t_a, fit.t_b, ends=True)
        best: float | None = None
        after = -1.0 if self.switched == fit.t_a else None
        for c in range(coef.shape[1]):

            def refine(xx: float, c: int = c) -> float:
                tt = fit.time(xx)
                return float(self.values(tt, dense(tt))[c])

            try:
                xc = contacts.first_downward_crossing(
                    coef[:, c], start_tol=FORCE_ROUNDING, refine=refine, after=after
                )
            except contacts.ContactError as exc:  # pragma: no cover - a switch missed
                raise self.model.scene.error(
                    "effects",
                    f"a resting contact's switch was missed before t = {fit.t_a:.17g} s ({exc})",
                ) from None
            if xc is not None:
                tc = fit.t_a if xc == -1.0 else min(fit.time(xc), fit.t_b)
                if best is None or tc < best:
                    best = tc
        return None if best is None else Hit(best, self)

    def switch(self, t: float, y: FloatArray, events: list[Event]) -> FloatArray:
        """Choose the resting pairs' contacts and modes again at a switch found at t;
        record the events (``lift_off``, ``stick``, ``slip``); the new state."""
        fwd = self.forward
        s = fwd.snapshot(t, y)
        if fwd.phase is not None:
            s.phase = fwd.phase
        self._same = (t, self._same[1] + 1) if self._same[0] == t else (t, 1)
        if self._same[1] > MAX_SWITCHES:
            imp = next(iter(self.rests))
            raise self._unresolved(
                t,
                imp,
                f"its contacts and modes switch more than {MAX_SWITCHES} times at "
                "this instant (no choice holds: a configuration the resting contact cannot "
                "treat)",
            )
        rests: Rests = {}
        for imp, old in self.rests.items():
            feats = tuple(old.active)
            if old.friction == "slip":  # the slip ends: its contacts stop sliding
                self._stop_slip(s, imp, feats, old.speed)
            rest = self._choose(t, s, imp, feats, rests, old.speed, old.friction == "stick")
            if rest is None:
                events.append(self._event(t, old, "lift_off"))
                continue
            rests[imp] = rest
            if rest.friction != old.friction:
                events.append(self._event(t, rest, rest.friction))
            elif rest.active != old.active:
                events.append(self._event(t, rest, "lift_off"))
        self._set(t, rests)
        return fwd.pack(s)

    def _stop_slip(self, s: Snapshot, imp: Impact, feats: tuple[int, ...], speed: float) -> None:
        """At the end of a slip the slip is zero up to the location's rounding (relative
        to ``speed``, the contact speeds when it began): make it zero (the least change
        of the kinetic energy), where every contact's is that small."""
        for b in feats:
            u, scale = self._slip(s, imp, imp.features[b])
            if float(np.linalg.norm(u)) > max(FORCE_ROUNDING * scale, self._slip_end(speed)):
                return
        pts = [imp.contact(s, imp.features[b])[0] for b in feats]
        T = np.eye(3) - np.outer(imp.normal, imp.normal)
        m = len(pts)
        A = np.zeros((3 * m, 3 * m))
        u = np.concatenate([self._slip(s, imp, imp.features[b])[0] for b in feats])
        for a_, Sa in enumerate(pts):
            for c, Sc in enumerate(pts):
                A[3 * a_ : 3 * a_ + 3, 3 * c : 3 * c + 3] = (
                    T @ imp.inverse_mass(s, imp.i, Sa, Sc) @ T
                )
        P = _least_norm(A, -u)
        for c, S in enumerate(pts):
            imp.kick(s, imp.i, T @ P[3 * c : 3 * c + 3], S)

    # ------------------------------------------------------------------ report
    def _event(self, t: float, rest: Rest, kind: str) -> Event:
        imp = rest.imp
        return Event(
            float(t),
            kind,
            {
                **imp.who(),
                "support": imp.label,
                "contacts": [imp.features[b].label for b in rest.active],
                "friction": rest.friction,
            },
        )

    def acts_until(self, events: Sequence[Event] = (), quantity: str | None = None) -> float:
        """Until when the supports may change ``quantity`` (0: never; inf: to the end):
        a smooth support keeps the energy and what a force along its normal keeps; a
        rough one, the energy while it sticks."""
        from .effects.base import keeps_for_force_along

        until = 0.0
        for _, t1, rests in self.spans():
            for rest in rests.values():
                imp = rest.imp
                if quantity == "E":
                    breaks = rest.friction == "slip"
                elif quantity is None:  # a moment about G
                    breaks = True
                else:
                    breaks = rest.friction != "smooth" or not keeps_for_force_along(
                        imp.normal, quantity
                    )
                if breaks:
                    until = max(until, t1)
        return until

    def spans(self) -> list[tuple[float, float, Rests]]:
        """[(t0, t1, rests)] over the run where some body rests (t1 = inf for the last)."""
        out: list[tuple[float, float, Rests]] = []
        for k, (t0, rests) in enumerate(self.timeline):
            t1 = self.timeline[k + 1][0] if k + 1 < len(self.timeline) else math.inf
            if rests:
                out.append((t0, t1, rests))
        return out

    def series(
        self, t: FloatArray, Y: FloatArray
    ) -> tuple[dict[int, FloatArray], dict[int, float]]:
        """Each resting body's total support force at the samples (t, Y) (zero while it
        does not rest), by body index, and the size of its terms."""
        bodies = sorted({r.imp.i for _, rests in self.timeline for r in rests.values()})
        if not bodies:
            return {}, {}
        F = {k: np.zeros((len(t), 3)) for k in bodies}
        size = dict.fromkeys(bodies, 0.0)
        saved = self.rests
        try:
            for m, (tt, y) in enumerate(zip(t, Y, strict=True)):
                self.rests = self.at(float(tt))
                if not self.rests:
                    continue
                s = self.forward.snapshot(float(tt), y)
                out = self.forward.loads_without_support(float(tt), s)
                forces, sz = self.forces(float(tt), s, out)
                for rest, _, f in forces:
                    F[rest.imp.i][m] += f
                for k in bodies:
                    size[k] = max(size[k], sz + float(np.linalg.norm(out.F[k])))
        finally:
            self.rests = saved
        return F, size

    def _unresolved(self, t: float, imp: Impact, why: str) -> SceneError:
        return self.model.scene.error(
            imp.where, f"{imp.label} come to rest at t = {float(t):.6g} s: {why}"
        )


class _NoSlip(Exception):
    """A trial slip direction whose support forces have no solution or let go."""


def _least_norm(A: FloatArray, b: FloatArray) -> FloatArray:
    """The least-norm least-squares solution of A x = b (singular values below
    RANK_RTOL × the largest × the size are a dependency)."""
    rcond = RANK_RTOL * max(A.shape)
    # (numpy types lstsq's solution as floats of any precision: float64 here)
    return cast("FloatArray", np.linalg.lstsq(A, b, rcond=rcond)[0])


def _solve(A: FloatArray, b: FloatArray) -> FloatArray | None:
    """The least-norm solution of the support's equations, or None where it leaves a
    residual beyond the rounding of its terms (FORCE_ROUNDING × their size × the number
    of equations): no forces satisfy them."""
    x = _least_norm(A, b)
    size = float(np.abs(A).max() * np.abs(x).max() + np.abs(b).max())
    if float(np.abs(A @ x - b).max()) > FORCE_ROUNDING * max(size, 1e-300) * len(b):
        return None
    return x


def _unit(x: FloatArray) -> FloatArray | None:
    n = float(np.linalg.norm(x))
    return None if n == 0.0 else x / n


def _kinetic(s: Snapshot, k: int) -> float:
    return 0.5 * float(s.m[k]) * float(s.v[k] @ s.v[k]) + 0.5 * float(s.L_A[k] @ s.omega[k])
