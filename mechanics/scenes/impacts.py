"""Contact resolution: the impact law applied at a contact found by :mod:`.collision`
(or in closed form), and what follows at that instant.

- :meth:`Resolver.resolve` applies the Chapter 6 impulse
  (:meth:`~mechanics.scenes.effects.impact.Impact.apply`) at the contact, then resolves
  every *simultaneous* contact by sequential impulses: after each impulse every feature
  touching within rounding and still closing is resolved in turn, the fastest approach
  first, until none closes (at most :data:`MAX_SWEEPS` rounds; for a row of equal elastic
  spheres this passes the momentum down the row).
- A touch at zero approach speed (up to :data:`CLOSING_ROUNDING`) is no impact
  (:meth:`Resolver.touch`).
- A pair pressed together whose rebound can no longer be followed (the impacts
  accumulate, or e = 0) stops the run (:meth:`Resolver.stalls`, :func:`zeno`).
- :meth:`Resolver.contact_time` is the closed-form time to a sphere's or point's next
  contact under uniform gravity (the exact flows' free flight).
"""

from __future__ import annotations

import math

import numpy as np

from . import contacts
from .effects.impact import EnergyGainError
from .errors import SceneError
from .trajectory import EPS, Event

__all__ = [
    "CLOSING_ROUNDING",
    "GAP_ROUNDING",
    "MAX_EVENTS",
    "MAX_SWEEPS",
    "ZENO_SPEED",
    "Resolver",
    "falls_in",
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


class Resolver:
    """The impact law at the contacts of a :class:`~mechanics.scenes.model.Model`,
    through its :class:`~mechanics.scenes.forward.Forward` dynamics."""

    def __init__(self, model, forward) -> None:
        self.model = model
        self.forward = forward

    def touch(self, imp, ft, s) -> bool:
        """Touching with an approach speed that is zero up to rounding: no impact."""
        return imp.approach(s, ft) <= CLOSING_ROUNDING * imp.speed_scale(s, ft)

    def resolve(self, t, y, imp, ft, events) -> np.ndarray:
        """Resolve the impact found at t, then every simultaneous one (sequential
        impulses, see the module's docstring); record the events; return the new state."""
        from mechanics.errors import SeparatingContactError

        scene, fwd = self.model.scene, self.forward
        s = fwd.snapshot(t, y)
        for _ in range(MAX_SWEEPS):
            try:
                detail = imp.apply(s, ft)
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
            events.append(Event(t, "impact", detail))
            if len(events) > MAX_EVENTS:
                raise zeno(scene, t, imp.label)
            y = fwd.pack(s)
            if self.stalls(imp, ft, t, y, detail):
                raise zeno(scene, t, imp.label)
            nxt = self.closing_now(s)
            if nxt is None:
                return y
            imp, ft = nxt
        raise scene.error(
            "effects", f"more than {MAX_SWEEPS} rounds of simultaneous impacts at t = {t:.6g} s"
        )

    def closing_now(self, s):
        """The touching feature that closes fastest (sequential impulses), or None."""
        best, speed = None, 0.0
        for imp in self.model.impacts:
            for ft in imp.features:
                scale = np.abs(imp.feature_point(s, ft)).sum() + imp.point @ imp.point + ft.a
                if abs(float(imp.gap(s, ft))) > GAP_ROUNDING * 4 * max(scale, ft.a + ft.a_s):
                    continue
                v = imp.approach(s, ft)
                if v > CLOSING_ROUNDING * imp.speed_scale(s, ft) and v > speed:
                    best, speed = (imp, ft), v
        return best

    def pressed(self, imp, ft, t, y) -> float:
        """How hard the loads push the pair together: the inward normal relative
        acceleration of the contact points (> 0 pressed, ≤ 0 not)."""
        fwd = self.forward
        s = fwd.snapshot(t, y)
        if ft.support is not None:  # the gap of a rim circle against the plane
            g2 = fwd.rim_gap_acceleration(t, y, s, imp, ft)
            if g2 is not None:
                return -g2
        S, n = imp.contact(s, ft)
        a = fwd.point_accelerations(t, y, s, {imp.i: S, imp.j: S})
        return -float(n @ (a.get(imp.i, 0.0) - a.get(imp.j, 0.0)))

    def stalls(self, imp, ft, t, y, detail) -> bool:
        """Do the impacts accumulate here?  Pressed together, the pair rebounds too slowly
        to be followed: slower than ``ZENO_SPEED`` (relative), or so slowly that its hop,
        v²/(2a), stays below the rounding of the gap (``GAP_ROUNDING`` × the positions'
        size), where no next contact can be told from this one."""
        a = self.pressed(imp, ft, t, y)
        if not a > 0:
            return False
        v = detail["normal_speed_after"]
        if v < ZENO_SPEED * (1.0 + abs(detail["normal_speed_before"])):
            return True
        return v * v <= 2.0 * a * GAP_ROUNDING * 4 * detail["gap_scale"]

    def contact_time(self, imp, ft, s, g) -> float:
        """Closed-form time to the next contact of a sphere or point (inf if none): under
        uniform gravity a plane gap is quadratic in τ, and the relative motion of two
        bodies is uniform (gravity cancels), so |d + w τ| = a_i + a_j is a quadratic."""
        fwd = self.forward
        i = imp.i
        if imp.j is None:
            tau = contacts.plane_contact_time(
                float(imp.gap(s, ft)), float(s.v[i] @ imp.normal), float(g @ imp.normal)
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


def falls_in(scene, imp, ft, t) -> SceneError:
    """The error of a pair that touches and then falls in (a resting contact)."""
    return scene.error(
        imp.where,
        f"{ft.label} touch at t = {t:.17g} s and then fall in, with no separation that "
        "float64 can resolve: a resting contact, which no effect provides (shorten the "
        "duration)",
    )


def zeno(scene, t, who="the bodies") -> SceneError:
    """The error of impacts that accumulate (or events beyond :data:`MAX_EVENTS`)."""
    return scene.error(
        "scene.duration",
        f"{who} come to rest in contact (the impacts accumulate, or e = 0) near "
        f"t = {t:.6g} s before the end {scene.duration:g} s: shorten the duration "
        "(impacts do not become a resting contact; a round body resting or rolling on a "
        "plane is the coulomb_friction joint's)",
    )
