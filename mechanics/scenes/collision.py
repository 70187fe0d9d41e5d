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
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
from numpy.polynomial import chebyshev as C

from . import contacts
from .impacts import GAP_ROUNDING, falls_in

__all__ = ["Collision", "Hit", "StepFit", "check_initial_overlap"]


@dataclass
class StepFit:
    """One integration step [t_a, t_b] and its dense output ``dense`` (scipy's
    convention: (size,) at a time, (size, k) at k times)."""

    dense: Any
    t_a: float
    t_b: float

    def time(self, xx):
        """The time at the step's Chebyshev coordinate xx in [−1, 1]."""
        return 0.5 * (self.t_a + self.t_b) + 0.5 * (self.t_b - self.t_a) * xx

    def state(self, t) -> np.ndarray:
        return np.asarray(self.dense(t), dtype=float)

    def coef(self) -> np.ndarray:
        """Chebyshev coefficients (K, size) of the whole state along the step (fitted
        once, when first read)."""
        return contacts.chebyshev_fit(lambda tt: np.asarray(self.dense(tt)).T, self.t_a, self.t_b)

    coef = cached_property(coef)


@dataclass(frozen=True)
class Hit:
    """An event found on a step: at time ``t``, the ``effect``'s contact ``feature``, or
    (``feature`` None) a switch of the effect's mode."""

    t: float
    effect: Any
    feature: Any = None
    #: the feature touches with no approach speed and then falls in: it comes to rest
    rest: bool = False


def check_initial_overlap(model, forward) -> None:
    """No two features overlap at t = 0 beyond the rounding of their positions."""
    scene = model.scene
    s = forward.snapshot(0.0, model.y0)
    for imp in model.impacts:
        for ft in imp.features:
            gap = float(imp.gap(s, ft))
            reach = np.abs(imp.feature_point(s, ft)).sum() + np.abs(imp.point).sum()
            if gap < -GAP_ROUNDING * (reach + ft.a + ft.a_s):  # beyond the rounding
                raise scene.error(imp.where, f"{ft.label} overlap at t = 0 s (gap {gap:.3g} m < 0)")


class Collision:
    """The contact search of a :class:`~mechanics.scenes.model.Model` on each step."""

    def __init__(self, model, forward, resolver) -> None:
        self.model = model
        self.forward = forward
        self.resolver = resolver
        #: (impact, feature) index -> the largest size of its positions so far
        self.reach: dict[tuple[int, int], float] = {}

    # ------------------------------------------------------- the features' paths
    def fit_snapshots(self, fit: StepFit, f):
        """Chebyshev coefficients along the step of ``f`` of the snapshots at the
        step's nodes (its ends included)."""
        return contacts.chebyshev_fit(
            lambda tt: f(self.forward.snapshot(tt, np.asarray(fit.dense(tt)).T)),
            fit.t_a,
            fit.t_b,
            ends=True,
        )

    def frame_coef(self, fit: StepFit, k):
        """Chebyshev coefficients of body k's centre (K, 3) and R_A_O (K, 3, 3) along
        the step (:meth:`.bodies.Body.frame_coef`: a guided body's fitted at the step's
        nodes)."""
        return self.model.layout.bodies[k].frame_coef(self, fit)

    def rim_poly(self, fit: StepFit, imp, ft):
        """w² − a² (d₁² + d₂²) along the step, with the sign of the rim circle's gap
        w − a |(d₁, d₂)| where w ≥ 0 (see :mod:`.effects.impact`), w itself (the gap
        is negative where w is), and the centre's coefficients."""
        r, R = self.frame_coef(fit, ft.body)
        a, zc = ft.support
        n = imp.normal
        d = -np.einsum("kij,j->ki", R, n)  # R_A_O (−n): body components, linear in R
        w = r @ n - zc * d[:, 2]
        w[0] -= imp.point @ n
        rho2 = C.chebadd(C.chebmul(d[:, 0], d[:, 0]), C.chebmul(d[:, 1], d[:, 1]))
        return C.chebsub(C.chebmul(w, w), a * a * rho2), w, r

    def point_coef(self, fit: StepFit, k, at):
        """Chebyshev coefficients (K, 3) of the body point ``at`` (body components about
        G; None: G) along the step (:meth:`.bodies.Body.point_coef`): r + R_A_Oᵀ at,
        linear in the state; for a pinned body C + R_A_Oᵀ (g_A + at); a guided body's
        points fitted at the step's Chebyshev nodes."""
        return self.model.layout.bodies[k].point_coef(self, fit, at)

    def _polys(self, fit: StepFit, imp, ft):
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
            p = C.chebadd(
                C.chebadd(*(C.chebmul(rel[:, c], rel[:, c]) for c in (0, 1))),
                C.chebmul(rel[:, 2], rel[:, 2]),
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
        for a, imp in enumerate(model.impacts):
            for b, ft in enumerate(imp.features):
                if support is not None and support.active(imp, ft):
                    continue  # resting: its gap is held at zero (.support)
                polys, x, other, size = self._polys(fit, imp, ft)
                # positions round relative to their own size, not to their difference
                reach = np.abs(x).sum() + other + size
                self.reach[a, b] = max(self.reach.get((a, b), 0.0), reach)

                def gap_at(xx, imp=imp, ft=ft):
                    tt = fit.time(xx)
                    return float(imp.gap(fwd.snapshot(tt, np.asarray(fit.dense(tt))), ft))

                for p, units, terms in polys:  # a rim circle: q, and w for a face flat
                    after = None
                    for _ in range(3):  # a touch (zero approach speed) is searched past once
                        try:
                            xc = contacts.first_downward_crossing(
                                p,
                                start_tol=GAP_ROUNDING * (self.reach[a, b] * units + terms),
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

    def _falls_in(self, best, imp, ft, tc) -> Hit:
        """A feature that touches and then falls in comes to rest there (a :class:`Hit`
        with ``rest``), where the pair can rest (:mod:`.support`); else the run stops."""
        support = self.resolver.support
        if support is None or support.can_rest(imp, ft) is not None:
            raise falls_in(self.model.scene, imp, ft, tc)
        if best is None or tc < best.t:
            return Hit(tc, imp, ft, rest=True)
        return best
