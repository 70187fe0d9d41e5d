"""Collision: each contact feature's gap along an integration step, and the first
contact on the step.

Positions and attitudes are state components, so along a step's dense polynomial
(fitted once per step, :class:`StepFit`) a feature's gap is a polynomial too, one per
geometry:

- a point or sphere against a plane: the signed distance minus the radius;
- two spheres: |d|² − s² (the sign of the gap);
- a rim circle (a cylinder's or disc's edge) against a plane: w² − a² ρ², and w itself
  for a face landing flat (see :mod:`.effects.impact`).

:func:`contacts.first_downward_crossing` finds each one's first fall through zero,
refined on the exact gap; :meth:`Collision.first_contact` returns the earliest as a
:class:`Hit`.  The rounding allowed at the step's start (a contact just resolved) is
:data:`~.impacts.GAP_ROUNDING` × the largest size the feature's positions (and the
plane's point) have had so far in the run (:attr:`Collision.reach`).  A crossing with
zero approach speed (up to rounding) is a touch, not an impact.

A feature that rested (its gap held at zero by :mod:`.support`, to the drift of the
constraint's integration, which the run checks at every sample) and has just been let
go, by an impact elsewhere or a lift-off, starts its first free step with the gap that
drift left: that depth below zero is allowed at the step's start too
(:attr:`Collision.released`), until the feature's gap is seen at or above zero at a
step's start; a fall beyond it is still refused as a missed contact.  The depth allowed
is at most what the run's own check of its resting contacts allows
(:data:`~.trajectory.CONSERVED_RTOL_INTEGRATED` × the feature's reach, × the scene's
:func:`~.trajectory.tolerance_scale`): a deeper one is refused as before.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any, NoReturn, TypeAlias, cast

import numpy as np
import numpy.typing as npt
from numpy.polynomial import chebyshev as C

from . import contacts
from .effects.impact import centre_gaps
from .impacts import GAP_ROUNDING, falls_in
from .trajectory import CONSERVED_RTOL_INTEGRATED, EPS, Dense, tolerance_scale
from .vectors import FloatArray

if TYPE_CHECKING:  # for annotations only
    from .effects import Snapshot
    from .effects.impact import Feature, Impact
    from .forward import Forward
    from .impacts import Resolver
    from .model import Model
    from .spec import Scene

#: a feature's gap polynomials along a step: (p, units, terms) each
Polys: TypeAlias = list[tuple[FloatArray, float, float]]

__all__ = ["Collision", "Hit", "StepFit", "check_initial_overlap"]


@dataclass
class StepFit:
    """One integration step [t_a, t_b] and its dense output ``dense``.

    :attr:`coef` holds the Chebyshev coefficients of the whole state along the step,
    fitted once (at ``contacts.STEP_NODES`` nodes) when first read; the step's
    variable x ∈ [−1, 1] maps to the time :meth:`time`.

    Parameters
    ----------
    dense : Dense
        The step's continuous extension, scipy's convention: ``dense(t)`` of shape
        (size,) at a time, (size, k) at k times.
    t_a : float
        The step's start, s.
    t_b : float
        The step's end, s (≥ t_a).

    Examples
    --------
    The state t² on [0, 2] is 1.5 T₀ + 2 T₁ + 0.5 T₂ in x = t − 1; its series at x
    equals the dense output at the time of x:

    >>> from numpy.polynomial import chebyshev as C
    >>> fit = StepFit(lambda t: np.stack([np.asarray(t) ** 2]), 0.0, 2.0)
    >>> bool(np.allclose(fit.coef[:3, 0], [1.5, 2.0, 0.5], rtol=0, atol=32 * EPS))
    True
    >>> fit.time(0.5), fit.state(fit.time(0.5)).tolist()
    (1.5, [2.25])
    >>> bool(np.isclose(C.chebval(0.5, fit.coef[:, 0]), 2.25, rtol=32 * EPS))
    True
    """

    dense: Dense
    t_a: float
    t_b: float

    def time(self, xx: float) -> float:
        """The time at the step's Chebyshev coordinate xx in [−1, 1]."""
        return 0.5 * (self.t_a + self.t_b) + 0.5 * (self.t_b - self.t_a) * xx

    def state(self, t: float) -> FloatArray:
        return np.asarray(self.dense(t), dtype=float)

    def _get_coef(self) -> FloatArray:
        """Chebyshev coefficients (K, size) of the whole state along the step (fitted
        once, when first read)."""
        return contacts.chebyshev_fit(lambda tt: np.asarray(self.dense(tt)).T, self.t_a, self.t_b)

    coef = cached_property(_get_coef)


@dataclass(frozen=True)
class Hit:
    """An event found on a step: at time ``t``, the ``effect``'s contact ``feature``.

    With ``feature`` None, a switch of the effect's mode.  A record: its constructor
    checks nothing.

    Parameters
    ----------
    t : float
        The event's time, s.
    effect : Impact or effect with modes
        An impact (:class:`~mechanics.scenes.effects.impact.Impact`), or an effect with
        modes (:class:`~mechanics.scenes.effects.capabilities.HasModes`).
    feature : Feature or None, optional
        The impact's contact feature; None (the default) for a switch of mode.
    rest : bool, optional
        The feature touches with no approach speed and then falls in: it comes to rest
        (default False).

    Examples
    --------
    The earliest of the hits found on a step is the one the run stops at:

    >>> hits = [Hit(0.5, "impact"), Hit(0.25, "switch"), Hit(0.75, "impact", rest=True)]
    >>> first = min(hits, key=lambda h: h.t)
    >>> (first.t, first.effect, first.feature, first.rest) == (0.25, "switch", None, False)
    True
    """

    t: float
    effect: Any  # an impact, or an effect with modes (.effects.capabilities.HasModes)
    feature: Feature | None = None
    #: the feature touches with no approach speed and then falls in: it comes to rest
    rest: bool = False


def check_initial_overlap(model: Model, forward: Forward) -> None:
    """No two features overlap at t = 0 beyond the rounding of their positions.

    The centres of spheres and points are checked all at once
    (``effects.impact.centre_gaps``), the other features one by one; the rounding
    allowed is :data:`~.impacts.GAP_ROUNDING` × the size of the positions and the
    features.  :func:`mechanics.scenes.spec.parse_scene` runs it on every scene with
    impacts.

    Parameters
    ----------
    model : Model
        The scene's model (:class:`mechanics.scenes.model.Model`).
    forward : Forward
        Its forward dynamics (:class:`mechanics.scenes.forward.Forward`): the bodies at
        t = 0.

    Raises
    ------
    SceneError
        If two features overlap at t = 0 beyond the rounding (naming the impact's field,
        the features and the gap, m).

    Examples
    --------
    A ball of radius 0.1 m resting on the floor passes; one whose centre is 0.05 m up
    overlaps it by z − r = −0.05 m (the parser runs the same check):

    >>> from mechanics.scenes.forward import Forward
    >>> from mechanics.scenes.model import Model
    >>> from mechanics.scenes.spec import parse_scene
    >>> def ball(z):
    ...     return parse_scene({
    ...         "scene": {"name": "x", "duration": 1.0},
    ...         "bodies": [{"name": "ball", "shape": "solid_sphere", "mass": 0.5,
    ...                     "radius": 0.1, "initial": {"position": [0.0, 0.0, z]}}],
    ...         "effects": [{"type": "impact", "body": "ball", "plane_point": [0.0, 0.0, 0.0],
    ...                      "plane_normal": [0.0, 0.0, 1.0], "restitution": 0.5}]})
    >>> md = Model(ball(0.1))
    >>> check_initial_overlap(md, Forward(md))
    >>> ball(0.05)
    Traceback (most recent call last):
    ...
    mechanics.scenes.errors.SceneError: <scene>: effects[0]: ... overlap ... (gap -0.05 m < 0)
    """
    scene = model.scene
    s = forward.snapshot(0.0, model.y0)
    imps = model.impacts
    rows, G = centre_gaps(imps, s)
    if rows:
        fts = [imps[a].features[0] for a in rows]
        x = np.abs(s.r[[ft.body for ft in fts]]).sum(-1)
        other = np.array([np.abs(imps[a].point).sum() for a in rows])
        size = np.array([ft.a + ft.a_s for ft in fts])
        bad = np.nonzero(-GAP_ROUNDING * (x + other + size) > G)[0]
        if bad.size:
            c = int(bad[0])
            _overlap(scene, imps[rows[c]], fts[c], float(G[c]))
    done = set(rows)
    for a, imp in enumerate(imps):
        if a in done:
            continue
        for ft in imp.features:
            gap = float(imp.gap(s, ft))
            reach = np.abs(imp.feature_point(s, ft)).sum() + np.abs(imp.point).sum()
            if gap < -GAP_ROUNDING * (reach + ft.a + ft.a_s):  # beyond the rounding
                _overlap(scene, imp, ft, gap)


def _overlap(scene: Scene, imp: Impact, ft: Feature, gap: float) -> NoReturn:
    raise scene.error(imp.where, f"{ft.label} overlap at t = 0 s (gap {gap:.3g} m < 0)")


#: the broad phase's margin, relative to the size of the positions: its boxes enclose the
#: step's polynomials exactly (|T_k| ≤ 1 on the step), so the margin covers rounding
#: only, with room (the narrow phase's own rounding is GAP_ROUNDING = 64 eps)
BROAD_RTOL = 2**10 * EPS


class Collision:
    """The contact search of a :class:`~mechanics.scenes.model.Model` on each step.

    :meth:`first_contact` returns the earliest contact on a step (a :class:`Hit`), after
    the broad phase (:meth:`near`) has left out the impacts that cannot touch on it.
    The constructor gathers each body's reach about G (:attr:`ext`: the radius of a
    ball about its centre holding all its contact features) and the impacts by plane
    and by pair of bodies.

    Parameters
    ----------
    model : Model
        The scene's model (:class:`mechanics.scenes.model.Model`): its impacts.
    forward : Forward
        Its forward dynamics (:class:`mechanics.scenes.forward.Forward`).
    resolver : Resolver
        Its impact resolver (:class:`mechanics.scenes.impacts.Resolver`): touches, and
        the resting contacts of its support.

    Raises
    ------
    SceneError
        From :meth:`first_contact`: where a feature's gap starts a step below zero
        beyond the rounding allowed (a contact missed before the step), or a pair
        touches and then falls in where it cannot rest.  The constructor checks nothing.

    Examples
    --------
    The engine's contact search for a ball of radius 0.1 m and the floor: the ball's
    reach about G is its radius, and its one impact is with a plane:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({
    ...     "scene": {"name": "x", "duration": 1.0},
    ...     "bodies": [{"name": "ball", "shape": "solid_sphere", "mass": 0.5, "radius": 0.1,
    ...                 "initial": {"position": [0.0, 0.0, 1.0]}}],
    ...     "effects": [{"type": "impact", "body": "ball", "plane_point": [0.0, 0.0, 0.0],
    ...                  "plane_normal": [0.0, 0.0, 1.0], "restitution": 0.5}]})
    >>> col = Engine(sc).collision
    >>> col.ext.tolist() == [sc.bodies[0].dims["radius"]], col.plane.tolist(), col.pairs
    (True, [0], {})
    """

    def __init__(self, model: Model, forward: Forward, resolver: Resolver) -> None:
        self.model = model
        self.forward = forward
        self.resolver = resolver
        #: (impact, feature) index -> the largest size of its positions so far
        self.reach: dict[tuple[int, int], float] = {}
        #: (impact, feature) index -> the depth its gap had when its support let it go
        #: (the resting constraint's drift), allowed at a step's start until it is ≥ 0
        self.released: dict[tuple[int, int], float] = {}
        #: the (impact, feature) indices held by the support on the last step searched
        self.held: set[tuple[int, int]] = set()
        imps = model.impacts
        #: the bodies of the impacts, and each one's reach about G: the radius of a
        #: ball about its centre that holds every contact feature of it
        self.ext = np.zeros(model.n)
        for imp in imps:
            for ft in imp.features:
                if ft.support is not None:
                    arm = math.hypot(*ft.support)
                else:
                    arm = (0.0 if ft.at is None else float(np.linalg.norm(ft.at))) + ft.a
                self.ext[ft.body] = max(self.ext[ft.body], arm)
                if ft.sphere is not None:
                    self.ext[ft.sphere] = max(self.ext[ft.sphere], ft.a_s)
        self.bodies = sorted({k for imp in imps for k in (imp.i, imp.j) if k is not None})
        plane = [a for a, imp in enumerate(imps) if imp.j is None]
        self.plane = np.array(plane, dtype=int)
        self.plane_body = np.array([imps[a].i for a in plane], dtype=int)
        self.plane_normal = np.array([imps[a].normal for a in plane]).reshape(-1, 3)
        self.plane_point = np.array([imps[a].point for a in plane]).reshape(-1, 3)
        #: a pair of bodies (lower index first) -> the positions of its impacts
        self.pairs: dict[tuple[int, int], list[int]] = {}
        for a, imp in enumerate(imps):
            if imp.j is not None:
                self.pairs.setdefault((min(imp.i, imp.j), max(imp.i, imp.j)), []).append(a)
        self.other = [float(np.abs(imp.point).sum()) for imp in imps]

    # ----------------------------------------------------------- broad phase
    def near(self, fit: StepFit) -> tuple[npt.NDArray[np.bool_], dict[int, float]]:
        """Which impacts may touch on the step (a bool per impact), and each body's
        Σ|centre's coefficients| (the size its positions round relative to).

        Broad phase: each body's centre along the step lies in the box c₀ ± Σ_{k≥1}|c_k|
        of its Chebyshev coefficients (|T_k| ≤ 1 there), so each of its features in that
        box grown by its reach about G (:attr:`ext`).  A body and a plane may touch only
        where the box reaches the plane; two bodies only where their boxes overlap,
        found by sorting the boxes along x and sweeping (O(n log n) for n bodies, plus
        the pairs that overlap).  Conservative: an impact left out cannot touch on the
        step, so the narrow phase (:meth:`first_contact`) sees every contact."""
        n = self.model.n
        mid, half, size = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n)
        sums: dict[int, float] = {}
        for k in self.bodies:
            c = self.point_coef(fit, k, None)
            mid[k], half[k] = c[0], np.abs(c[1:]).sum(axis=0)
            sums[k] = float(np.abs(c).sum())
            size[k] = sums[k]
        grow = half + (self.ext + BROAD_RTOL * (size + self.ext))[:, None]
        lo, hi = mid - grow, mid + grow
        near = np.zeros(len(self.model.impacts), dtype=bool)
        if self.plane.size:
            b, nrm = self.plane_body, self.plane_normal
            # the box's lowest point over the plane, against the rounding of both
            low = np.einsum("ij,ij->i", mid[b] - self.plane_point, nrm) - np.einsum(
                "ij,ij->i", grow[b], np.abs(nrm)
            )
            room = BROAD_RTOL * np.abs(self.plane_point).sum(axis=-1)
            near[self.plane] = low <= room
        if self.pairs:
            ks = np.array(self.bodies, dtype=int)
            order = ks[np.argsort(lo[ks, 0], kind="stable")]
            starts = lo[order, 0]
            ends = np.searchsorted(starts, hi[order, 0], side="right")
            for p, k in enumerate(order):  # each box against those starting inside it on x
                others = order[p + 1 : ends[p]]
                if not others.size:
                    continue
                over = np.all((lo[others] <= hi[k]) & (lo[k] <= hi[others]), axis=-1)
                for m in others[over]:
                    for a in self.pairs.get((min(k, m), max(k, m)), ()):
                        near[a] = True
        return near, sums

    def _keep_reach(self, fit: StepFit, a: int, imp: Impact, sums: dict[int, float]) -> None:
        """The reach of the features of an impact the broad phase left out (the same
        sums :meth:`first_contact` takes of the positions it searches)."""
        support = self.resolver.support
        for b, ft in enumerate(imp.features):
            if support is not None and support.active(imp, ft):
                continue  # resting (as in first_contact)
            if ft.support is not None:
                _, x, other, size = self._polys(fit, imp, ft)
                xs = float(np.abs(x).sum())
            else:
                if ft.at is None:
                    xs = sums[ft.body]
                else:
                    xs = float(np.abs(self.point_coef(fit, ft.body, ft.at)).sum())
                if ft.sphere is None:
                    other, size = self.other[a], ft.a
                else:
                    other, size = sums[ft.sphere], ft.a + ft.a_s
            reach = xs + other + size
            self.reach[a, b] = max(self.reach.get((a, b), 0.0), reach)

    # ------------------------------------------------------- the features' paths
    def fit_snapshots(self, fit: StepFit, f: Callable[[Snapshot], npt.ArrayLike]) -> FloatArray:
        """Chebyshev coefficients along the step of ``f`` of the snapshots at the
        step's nodes (its ends included)."""
        return contacts.chebyshev_fit(
            lambda tt: f(self.forward.snapshot(tt, np.asarray(fit.dense(tt)).T)),
            fit.t_a,
            fit.t_b,
            ends=True,
        )

    def frame_coef(self, fit: StepFit, k: int) -> tuple[FloatArray, FloatArray]:
        """Chebyshev coefficients of body k's centre (K, 3) and R_A_O (K, 3, 3) along
        the step (:meth:`.bodies.Body.frame_coef`: a guided body's fitted at the step's
        nodes)."""
        return self.model.layout.bodies[k].frame_coef(self, fit)

    def rim_poly(
        self, fit: StepFit, imp: Impact, ft: Feature
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """w² − a² (d₁² + d₂²) along the step, with the sign of the rim circle's gap
        w − a |(d₁, d₂)| where w ≥ 0 (see :mod:`.effects.impact`), w itself (the gap
        is negative where w is), and the centre's coefficients."""
        r, R = self.frame_coef(fit, ft.body)
        a, zc = cast("tuple[float, float]", ft.support)  # (a rim circle: its support is set)
        n = imp.normal
        d = -np.einsum("kij,j->ki", R, n)  # R_A_O (−n): body components, linear in R
        w = r @ n - zc * d[:, 2]
        w[0] -= imp.point @ n
        rho2 = C.chebadd(C.chebmul(d[:, 0], d[:, 0]), C.chebmul(d[:, 1], d[:, 1]))
        return C.chebsub(C.chebmul(w, w), a * a * rho2), w, r

    def point_coef(self, fit: StepFit, k: int, at: FloatArray | None) -> FloatArray:
        """Chebyshev coefficients (K, 3) of the body point ``at`` (body components about
        G; None: G) along the step (:meth:`.bodies.Body.point_coef`): r + R_A_Oᵀ at,
        linear in the state; for a pinned body C + R_A_Oᵀ (g_A + at); a guided body's
        points fitted at the step's Chebyshev nodes."""
        return self.model.layout.bodies[k].point_coef(self, fit, at)

    def _polys(
        self, fit: StepFit, imp: Impact, ft: Feature
    ) -> tuple[Polys, FloatArray, float, float]:
        """The feature's gap polynomials along the step, each (p, units, terms), with its
        positions' coefficients x, their other size and the feature's size."""
        if ft.support is not None:  # a rim circle: w² − a² ρ², as a sphere pair
            q, w, x = self.rim_poly(fit, imp, ft)
            size, other = ft.support[0] + abs(ft.support[1]), np.abs(imp.point).sum()
            # q = (w − a ρ)(w + a ρ): the gap's rounding at the step's start
            # (a contact just resolved) times w + a ρ there (plus its own
            # rounding); q ≥ 0 where w < 0 too, so w's own fall below zero (a face
            # landing flat) is searched as well
            w0 = float(C.chebval(-1.0, w))
            units = max(w0, 0.0) + math.sqrt(max(w0 * w0 - float(C.chebval(-1.0, q)), 0.0))
            # (q's own rounding is relative to its terms, Σ|q_k|, as w → 0 too)
            polys = [(q, units + GAP_ROUNDING * size, np.abs(q).sum()), (w, 1.0, 0.0)]
        elif ft.sphere is None:
            x = self.point_coef(fit, ft.body, ft.at)
            p = x @ imp.normal  # the plane's offset is a constant: the 0th term only
            p[0] -= imp.point @ imp.normal + ft.a
            size, other = ft.a, np.abs(imp.point).sum()
            polys = [(p, 1.0, 0.0)]
        else:
            x = self.point_coef(fit, ft.body, ft.at)
            centre = self.point_coef(fit, ft.sphere, None)
            rel = x - centre
            # (numpy types the series' coefficients as floats of any precision: float64)
            p = cast(
                "FloatArray",
                C.chebadd(
                    C.chebadd(*(C.chebmul(rel[:, c], rel[:, c]) for c in (0, 1))),
                    C.chebmul(rel[:, 2], rel[:, 2]),
                ),
            )
            size = ft.a + ft.a_s
            p[0] -= size * size
            # |d|² − s² ≈ 2 s × gap near contact
            polys = [(p, 2.0 * size, 0.0)]
            other = np.abs(centre).sum()
        return polys, x, other, size

    def first_contact(self, fit: StepFit) -> Hit | None:
        """The earliest contact of any feature within one step, or None (see the
        module's docstring)."""
        model, fwd = self.model, self.forward
        t_a, t_b = fit.t_a, fit.t_b
        if not model.impacts or t_b <= t_a:
            return None
        best = None
        support = self.resolver.support
        near, sums = self.near(fit)
        held, self.held = self.held, set()
        for a, imp in enumerate(model.impacts):
            if not near[a]:  # cannot touch on this step (broad phase)
                self._keep_reach(fit, a, imp, sums)
                continue
            for b, ft in enumerate(imp.features):
                if support is not None and support.active(imp, ft):
                    self.held.add((a, b))
                    continue  # resting: its gap is held at zero (.support)
                polys, x, other, size = self._polys(fit, imp, ft)
                # positions round relative to their own size, not to their difference
                reach = np.abs(x).sum() + other + size
                self.reach[a, b] = max(self.reach.get((a, b), 0.0), reach)
                slack = self._released(fit, imp, ft, (a, b), (a, b) in held)

                def gap_at(xx: float, imp: Impact = imp, ft: Feature = ft) -> float:
                    tt = fit.time(xx)
                    return float(imp.gap(fwd.snapshot(tt, np.asarray(fit.dense(tt))), ft))

                for p, units, terms in polys:  # a rim circle: q, and w for a face flat
                    after = None
                    for _ in range(3):  # a touch (zero approach speed) is searched past once
                        try:
                            xc = contacts.first_downward_crossing(
                                p,
                                start_tol=GAP_ROUNDING * (self.reach[a, b] * units + terms)
                                + slack * units,
                                refine=gap_at,
                                after=after,
                            )
                        except contacts.ContactError as exc:
                            raise model.scene.error(
                                imp.where,
                                f"{ft.label} interpenetrate at t = {t_a:.17g} s ({exc}): "
                                "a contact was missed before this step",
                            ) from None
                        if xc is None:
                            break
                        tc = t_a if xc == -1.0 else min(fit.time(xc), t_b)
                        s_c = fwd.snapshot(tc, fit.state(tc))
                        if not self.resolver.touch(imp, ft, s_c):
                            if best is None or tc < best.t:
                                best = Hit(tc, imp, ft)
                            break
                        # zero approach speed: the pair touches here (a plastic pair moving on
                        # together, the top of a tiny hop); it may still fall in later
                        if after is not None and xc <= after:
                            best = self._falls_in(best, imp, ft, tc)
                            break
                        after = xc
                    else:  # touch after touch within one step: never passed over silently
                        best = self._falls_in(best, imp, ft, tc)
        return best

    def _released(
        self, fit: StepFit, imp: Impact, ft: Feature, key: tuple[int, int], was_held: bool
    ) -> float:
        """The depth below zero allowed at this step's start to a feature its support
        has let go (see the module's docstring): the gap's at the first free step,
        kept until a step starts with the gap ≥ 0; 0 for any other feature."""
        if not was_held and key not in self.released:
            return 0.0
        gap = float(imp.gap(self.forward.snapshot(fit.t_a, fit.state(fit.t_a)), ft))
        if gap >= 0.0:
            self.released.pop(key, None)
            return 0.0
        if was_held:
            # at most the drift the run allows its resting gaps (result.self_checks)
            allowed = CONSERVED_RTOL_INTEGRATED * tolerance_scale(self.model.scene)
            if -gap > allowed * self.reach[key]:
                return 0.0  # deeper than a resting gap may drift: refused as missed
            self.released[key] = -gap
        return self.released[key]

    def _falls_in(self, best: Hit | None, imp: Impact, ft: Feature, tc: float) -> Hit:
        """A feature that touches and then falls in comes to rest there (a :class:`Hit`
        with ``rest``), where the pair can rest (:mod:`.support`); else the run stops."""
        support = self.resolver.support
        if support is None or support.can_rest(imp, ft) is not None:
            raise falls_in(self.model.scene, imp, ft, tc)
        if best is None or tc < best.t:
            return Hit(tc, imp, ft, rest=True)
        return best
