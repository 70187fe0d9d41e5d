"""Impacts with restitution (Chapter 6): a body against a plane, or two bodies, located as
events where a gap closes, resolved by the rigid-body impulse at the contact point.

Conventions
-----------
- **Contact features.**  A spherical body (``point``, ``solid_sphere``,
  ``hollow_sphere``) touches with its surface about G (radius a; 0 for a point); a
  polyhedral body (``box``, ``rectangular_plate``, ``rod``) with its corners (the rod's
  two ends), :func:`mechanics.scenes.state.body_vertices`; a round body that is not a
  sphere with its rim circles (``disc``, ``ring``: one, radius a in the e1e2-plane;
  ``cylinder``, ``cylindrical_shell`` of height h: two, at ±(h/2) e3), each touching
  with its *support point* toward the plane, the point of the circle furthest along
  −n: a (d₁, d₂)/|(d₁, d₂)| + z_c e3 for d = −n in body components (lying flat,
  d₁ = d₂ = 0, the whole face is lowest: the point that approaches fastest stands for
  it, along ω × n, or the face's centre z_c e3 if the body does not turn so).  A
  plane is given by a point p and a normal n (toward the side the body is on).
  Pairs: sphere–sphere and sphere–corner; two polyhedra, and a rim against a body (not
  a plane), are not modelled and are refused when the scene is read.
- **Gaps** (positive apart): plane: (x − p)·n − a for a feature at x of radius a; pair:
  |x_f − r_s| − a_s − a_f for a sphere s and a feature f (a corner has a_f = 0).  Each
  is linear in the state (plane) or the square root of a quadratic (pair), so along a
  step's dense polynomial it is searched exactly (:mod:`mechanics.scenes.contacts`).  A
  rim circle's gap is w − a |(d₁, d₂)| with the height w = (r_G − p)·n − z_c d₃ of its
  centre: it has a kink where the face is flat, so its sign is searched as that of
  w² − a² (d₁² + d₂²), a polynomial along the step (d is linear in R_A_O), as a
  sphere pair's is.
- **The impulse** (6.16)–(6.21), (6.36): the normal n points into ``body`` (from the
  plane or ``other``); the contact point S; the arms ρ_k = S − r_Gk; the effective mass
  1/μ = Σ_k 1/m_k + (ρ_k × n)·J_k⁻¹(ρ_k × n) (a fixed body or the plane: no term);
  v_n = n·(v_S,body − v_S,other) < 0 while approaching; the impulse S n on ``body``
  (−S n on ``other``) with S = −(1 + e) μ v_n, so that v_n' = −e v_n, and the energy
  lost ½ μ (1 − e)(1 + e) v_n² (6.41).  Smooth by default: no tangential impulse.  Where
  both arms are along n (spheres and points), the impulse passes through the centres
  and :func:`mechanics.impact.direct_impact` gives the velocities to 2 ulps.
- **Friction of the impulse** (``friction = μ``, Coulomb): with the contact's inverse
  mass matrix K = Σ_k (1/m_k − [ρ_k]× J_k⁻¹ [ρ_k]×) a total impulse P (on ``body``)
  changes the relative contact velocity u by K P.  *Stick*: P = K⁻¹(−e v_n n − u), the
  contact point stops sliding and the normal velocity restitutes, accepted when P lies
  in the friction cone |P_t| ≤ μ P_n.  *Slip* otherwise: P = P_n (n − μ t̂) against the
  initial slip direction t̂, with P_n fixed by n·(u + K P) = −e v_n.  The energy lost
  is the impulse's work −(P·u + ½ P·K P).  Newton's kinematic e with friction can
  *gain* energy where the contact's normal and tangential motions are coupled (Kane's
  paradox; a tilted box on a very rough floor meets it): such an impulse is refused
  with ``EnergyGainError`` (the engine stops with one line) rather than applied.
  An energetically consistent law (Stronge's energetic coefficient with the slip
  integrated through the impact) is not modelled yet.
- A contact found while *separating* is the exit side of an interpenetration: a bug,
  reported as a :class:`~mechanics.scenes.errors.SceneError`, never resolved.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any, ClassVar, TypeAlias, cast

import numpy as np

from ..._floats import EPS
from ..state import SPHERICAL_SHAPES, body_radius, body_vertices
from ..vectors import cross, cross3
from .base import (
    BodyLike,
    Context,
    Effect,
    FloatArray,
    SceneLike,
    Schema,
    Snapshot,
    SpecLike,
    keeps_for_force_along,
    register,
    unit,
)

POLYHEDRA = ("box", "rectangular_plate", "rod")
#: round bodies that touch a plane with a point of their rim (support point)
RIMS = ("disc", "ring", "cylinder", "cylindrical_shell")
#: an impulse may lose this fraction of the kinetic energy's rounding below zero (the
#: loss is the work of the impulse, a sum of a dozen products)
GAIN_RTOL = 64 * EPS
#: ``totals``: the kinetic energy, momentum, Σ m|v|, the angular momentum about the
#: contact point, the size of its terms, and each body's record
Totals: TypeAlias = tuple[float, list[float], float, list[float], float, list[dict[str, Any]]]


_ORIGIN = np.zeros(3)
_ORIGIN.flags.writeable = False
_EZ = np.array([0.0, 0.0, 1.0])
_EZ.flags.writeable = False


class EnergyGainError(ValueError):
    """The impact law would add kinetic energy (Newton's e with friction, Kane)."""


@dataclass(frozen=True)
class Feature:
    """One contact feature of an impact: the corner ``at`` (body components about G; None
    for the centre of a sphere) of ``body`` with radius ``a``, against the plane or the
    sphere ``sphere`` (index) of radius ``a_s``.  ``flip``: the sphere is ``body`` and
    the feature belongs to ``other`` (the normal into ``body`` is then reversed)."""

    body: int
    at: FloatArray | None
    a: float
    sphere: int | None
    a_s: float
    flip: bool
    label: str
    #: a rim circle's (radius a, height z_c on e3): its point is the support point
    support: tuple[float, float] | None = None


@register
class Impact(Effect):
    """Impacts of ``body`` with a plane or with ``other``, with the restitution e (Chapter 6).

    The pair's contacts touching at one instant are one problem, Newton's law at each at
    once (``model = "auto"``), or are resolved one at a time (``"sequential"``).  Or of
    a ``group`` of bodies: every pair of them, and each with every plane of ``planes``,
    by the same law (a pair of two fixed bodies, a fixed body and a plane, or two points,
    never meets and is left out; two points listed as a pair are refused).  A pair is
    listed once: two effects (or a group and an effect) naming the same two bodies, or
    one body and the same plane, are refused.  An effect object is one pair: a group is
    expanded first (:meth:`expand`).

    Parameters
    ----------
    spec : SpecLike
        One pair; its fields: ``body``, and ``other`` (a body) or the plane
        ``plane_point`` (m; default the origin) and ``plane_normal`` (nonzero, toward
        ``body``; default (0, 0, 1)); ``restitution`` e (in [0, 1]), ``friction`` μ
        (≥ 0; default 0: smooth) and ``model`` (``"auto"`` or ``"sequential"``).
    ctx : Context
        The scene's context (the bodies' indices and shapes, the fixed, pinned and guided bodies).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        a body is not a body of ``ctx``.
    AttributeError
        If ``ctx`` is None (the body's index is read from it).

    Examples
    --------
    A ball hits the floor at 4 m/s with e = 0.75: it leaves at e·4 = 3 m/s, and loses
    ½ m (1 − e)(1 + e) v_n² (6.41), the drop of its kinetic energy:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> ball = {"name": "ball", "shape": "solid_sphere", "mass": 2.0, "radius": 0.5,
    ...         "initial": {"position": [0.0, 0.0, 0.5], "velocity": [1.0, 0.0, -4.0]}}
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [ball],
    ...     "effects": [{"type": "impact", "body": "ball", "restitution": 0.75}]}))
    >>> hit, s = eng.effects[0], eng.snapshot(0.0, eng.y0)
    >>> out = hit.apply(s, hit.features[0])  # the new velocities written into s
    >>> s.v[0].tolist(), out["energy_loss"], 0.5 * 2.0 * (1 - 0.75) * (1 + 0.75) * 4.0**2
    ([1.0, 0.0, 3.0], 7.0, 7.0)
    >>> out["kinetic_energy_before"] - out["kinetic_energy_after"]
    7.0
    """

    type = "impact"
    schema: ClassVar[Schema] = {
        "body": ("body", False),
        "other": ("body", False),
        "plane_point": ("vector", False),
        "plane_normal": ("vector", False),
        "group": ("bodies", False),
        "planes": ("planes", False),
        "restitution": ("restitution", True),
        "friction": ("nonnegative", False),
        "model": ("impact_model", False),
    }
    units: ClassVar[dict[str, str]] = {
        "body": "",
        "other": "",
        "plane_point": "m",
        "plane_normal": "1",
        "restitution": "1",
        "friction": "1",
        "model": "",
        "group": "",
        "planes": "",
    }
    example: ClassVar[dict[str, Any]] = {"type": "impact", "body": "ball", "restitution": 0.8}

    @classmethod
    def expand(cls, spec: SpecLike, scene: SceneLike) -> list[SpecLike]:
        """The pairs a ``group`` names, each as a one-pair spec (same index and law):
        every two bodies of the group, then each body with each plane, in the group's
        order; a pair that never meets (two fixed bodies, a fixed body and a plane, two
        points) left out.  A spec without a group is its own only pair."""
        f = spec.fields
        if "group" not in f:
            return [spec]
        law: dict[str, Any] = {k: f[k] for k in ("restitution", "friction", "model") if k in f}
        fixed = {b.name for b in scene.bodies if b.fixed}
        points = {b.name for b in scene.bodies if b.shape == "point"}
        names = f["group"]
        # the spec's class, EffectSpec(type, index, fields) (dataclasses.replace costs 5 µs
        # a pair: too much for 500 000)
        one = cast("Callable[[str, int, dict[str, Any]], SpecLike]", type(spec))
        out = [
            one(spec.type, spec.index, {"body": a, "other": b, **law})
            for k, a in enumerate(names)
            for b in names[k + 1 :]
            if not (a in fixed and b in fixed) and not (a in points and b in points)
        ]
        out += [
            one(
                spec.type,
                spec.index,
                {
                    "body": a,
                    "plane_point": pl["point"],
                    "plane_normal": pl["normal"],
                    **law,
                    "group_plane": k,
                },
            )
            for a in names
            if a not in fixed
            for k, pl in enumerate(f.get("planes", ()))
        ]
        return out

    @classmethod
    def _check_group(cls, spec: SpecLike, scene: SceneLike) -> None:
        f, where = spec.fields, spec.where
        for key in ("body", "other", "plane_point", "plane_normal"):
            if key in f:
                also = "planes" if key.startswith("plane") else "group"
                raise scene.error(
                    f"{where}.{key}",
                    f"give a group (with its {also}) or a single pair ({key}), not both",
                )
        names = f["group"]
        for k, a in enumerate(names):
            if a in names[:k]:
                raise scene.error(
                    f"{where}.group[{k}]",
                    f"body {a!r} is listed twice (first at group[{names.index(a)}])",
                )
        if len(names) < 2 and "planes" not in f:
            raise scene.error(
                f"{where}.group",
                f"a group of one body ({names[0]!r}) and no planes meets nothing: list two "
                "bodies or more, or planes",
            )
        bodies = [scene.body(a) for a in names]
        for k, b in enumerate(bodies):
            if b.shape not in SPHERICAL_SHAPES + POLYHEDRA + RIMS:
                raise scene.error(
                    f"{where}.group[{k}]",
                    f"contacts of a {b.shape} are not modelled (only "
                    f"{', '.join(SPHERICAL_SHAPES + POLYHEDRA + RIMS)}); body {b.name!r}",
                )
            for m, c in enumerate(bodies[:k]):
                why = None
                if b.shape in RIMS or c.shape in RIMS:
                    rim = b if b.shape in RIMS else c
                    why = f"the rim of a {rim.shape} ({rim.name!r}) meets only a plane, not a body"
                elif b.shape in POLYHEDRA and c.shape in POLYHEDRA:
                    why = (
                        f"contacts between two polyhedral bodies ({c.name!r}, a {c.shape}, and "
                        f"{b.name!r}, a {b.shape}) are not modelled: every pair of a group "
                        "needs a sphere or a point"
                    )
                if why is not None and not (b.fixed and c.fixed):
                    raise scene.error(f"{where}.group[{k}]", f"{why} (with group[{m}])")
        if "planes" in f and all(b.fixed for b in bodies):
            raise scene.error(
                f"{where}.planes", "the group's bodies are all fixed: none meets a plane"
            )

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        f = spec.fields
        if "group" in f:
            cls._check_group(spec, scene)
            return
        if "planes" in f:
            raise scene.error(
                f"{spec.where}.planes",
                "planes go with a group; a single body's plane is plane_point and plane_normal",
            )
        if "body" not in f:
            raise scene.error(
                f"{spec.where}.body", "missing required field (an impact needs a body or a group)"
            )
        if f.get("other") == f["body"]:
            raise scene.error(f"{spec.where}.other", "a body cannot hit itself")
        if "other" in f and ("plane_point" in f or "plane_normal" in f):
            raise scene.error(
                f"{spec.where}.other", "give either another body or a plane, not both"
            )
        shapes = []
        for key in ("body", "other"):
            if key in f:
                b = scene.body(f[key])
                if b.shape not in SPHERICAL_SHAPES + POLYHEDRA + RIMS:
                    raise scene.error(
                        f"{spec.where}.{key}",
                        f"contacts of a {b.shape} are not modelled (only "
                        f"{', '.join(SPHERICAL_SHAPES + POLYHEDRA + RIMS)}); body {b.name!r}",
                    )
                if b.shape in RIMS and "other" in f:
                    raise scene.error(
                        f"{spec.where}.{key}",
                        f"the rim of a {b.shape} ({b.name!r}) meets only a plane, not a body",
                    )
                shapes.append(b.shape)
        if shapes == ["point", "point"]:
            raise scene.error(
                f"{spec.where}.other",
                "two points meet only where their paths cross exactly, a contact their gap "
                "|r1 - r2| (zero there, never negative) cannot locate to rounding: give one "
                "of them a radius (a solid_sphere)",
            )
        if len(shapes) == 2 and all(s in POLYHEDRA for s in shapes):
            raise scene.error(
                f"{spec.where}.other",
                f"contacts between two polyhedral bodies ({shapes[0]}, {shapes[1]}) are not "
                "modelled: one of the pair must be a sphere or a point",
            )
        if "other" not in f:
            fixed = scene.body(f["body"]).fixed
            if fixed:
                raise scene.error(f"{spec.where}.body", "a fixed body cannot hit a plane")
        elif all(scene.body(f[k]).fixed for k in ("body", "other")):
            raise scene.error(f"{spec.where}.other", "two fixed bodies never meet")

    def __init__(self, spec: SpecLike, ctx: Context) -> None:
        super().__init__(spec, ctx)
        f = self.fields
        self.i = ctx.index[f["body"]]
        self.j = ctx.index[f["other"]] if "other" in f else None
        self.e = float(f["restitution"])
        self.mu_f = float(f.get("friction", 0.0))
        #: "auto": the contacts of this pair at one instant are one problem (several
        #: touching together: simultaneous); "sequential": one at a time, fastest first
        self.model = f.get("model", "auto")
        if "plane_point" in f or "plane_normal" in f:
            self.point = np.asarray(f.get("plane_point", [0.0, 0.0, 0.0]), dtype=float)
            self.normal = unit(f.get("plane_normal", [0.0, 0.0, 1.0]))
        else:  # the default plane z = 0 (shared, read-only: a group's pairs are many)
            self.point, self.normal = _ORIGIN, _EZ
        bodies = ctx.scene.bodies
        self.fixed = ctx.fixed
        self.pins = ctx.pins  # pinned bodies: the pivot takes an impulse too
        self.guides = ctx.guides  # guided ones: the bearings or the track do
        self.carried = ctx.carried  # (shared by every pair: a body's kicks from all)
        self.features = self._features(bodies)

    # ----------------------------------------------------------------- geometry
    def _features(self, bodies: Sequence[BodyLike]) -> list[Feature]:
        label = self.label

        def feats(k: int) -> list[tuple[FloatArray | None, float, str]]:
            a = body_radius(bodies[k])
            if a is not None:
                return [(None, a, label)]
            name = bodies[k].name
            corners = body_vertices(bodies[k])
            assert corners is not None, "a body with no radius is a polyhedron: it has corners"
            return [(v, 0.0, f"{label} (corner {c} of {name!r})") for c, v in enumerate(corners)]

        b = bodies[self.i]
        if b.shape in RIMS:  # against a plane (the check refuses a rim against a body)
            a, hh = float(b.dims["radius"]), 0.5 * float(b.dims.get("height", 0.0))
            ends = [(0.0, "")] if hh == 0 else [(hh, ", its +e3 end"), (-hh, ", its −e3 end")]
            return [
                Feature(
                    self.i,
                    None,
                    0.0,
                    None,
                    0.0,
                    False,
                    f"{label} (the rim of {b.name!r}{w})",
                    (a, z),
                )
                for z, w in ends
            ]
        if self.j is None:
            return [Feature(self.i, at, a, None, 0.0, False, lab) for at, a, lab in feats(self.i)]
        if body_radius(bodies[self.j]) is not None:  # other is the sphere
            s, f, flip = self.j, self.i, False
        else:  # body is the sphere, the corners are the other's
            s, f, flip = self.i, self.j, True
        a_s = body_radius(bodies[s])
        assert a_s is not None, "a pair's features meet a sphere (check refuses two polyhedra)"
        return [Feature(f, at, a, s, a_s, flip, lab) for at, a, lab in feats(f)]

    def _get_label(self) -> str:
        """The pair in words: "bodies 'a' and 'b'" or "body 'a' and the plane"."""
        if self.j is None and "group_plane" in self.fields:  # one of a group's planes
            k = self.fields["group_plane"]
            return f"body {self.fields['body']!r} and {self.where}.planes[{k}]"
        if self.j is None:
            return f"body {self.fields['body']!r} and the plane"
        return f"bodies {self.fields['body']!r} and {self.fields['other']!r}"

    label = cached_property(_get_label)  # (the fields do not change)

    def bodies(self) -> list[int]:
        """Indices of the moving bodies the impulse acts on."""
        ks = [self.i] if self.j is None else [self.i, self.j]
        return [k for k in ks if k not in self.fixed]

    def feature_point(self, s: Snapshot, ft: Feature) -> FloatArray:
        """World position of the feature's centre, corner or support point (any leading
        shape)."""
        if ft.support is None:
            return s.point(ft.body, ft.at)
        a, zc = ft.support
        d = s.to_body(ft.body, -self.normal)  # toward the plane, body components
        across = np.sqrt(d[..., 0] ** 2 + d[..., 1] ** 2)
        flat = across == 0.0
        # lying flat, every point of the circle is lowest: the one that approaches
        # fastest, along ω × n (the face's centre if it does not turn that way)
        turn = cross(s.omega[..., ft.body, :], -d)
        spin = np.sqrt(turn[..., 0] ** 2 + turn[..., 1] ** 2)
        u = np.where(flat[..., None], turn, d)[..., :2]
        size = np.where(flat, spin, across)
        safe = np.where(size == 0.0, 1.0, size)
        at = np.concatenate([a * u / safe[..., None], np.full((*np.shape(across), 1), zc)], axis=-1)
        return s.point(ft.body, at)

    def gap(self, s: Snapshot, ft: Feature) -> FloatArray:
        x = self.feature_point(s, ft)
        if ft.sphere is None:
            g: FloatArray = (x - self.point) @ self.normal - ft.a
            return g
        d = x - s.r[..., ft.sphere, :]
        g = np.sqrt((d * d).sum(-1)) - ft.a - ft.a_s
        return g

    def contact(self, s: Snapshot, ft: Feature) -> tuple[FloatArray, FloatArray]:
        """The contact point S and the unit normal n into ``body``, at one time."""
        x = self.feature_point(s, ft)
        if ft.sphere is None:
            return x - ft.a * self.normal, self.normal
        u = unit(x - s.r[ft.sphere])  # from the sphere toward the feature
        S = s.r[ft.sphere] + ft.a_s * u
        return S, (-u if ft.flip else u)

    def approach(self, s: Snapshot, ft: Feature) -> float:
        """Normal speed of approach at the contact (> 0 closing)."""
        S, n = self.contact(s, ft)
        return -float(n @ self._relative_velocity(s, S))

    def _relative_velocity(self, s: Snapshot, S: FloatArray) -> FloatArray:
        def vel(k: int | None) -> FloatArray:
            if k is None or k in self.fixed:
                return np.zeros(3)
            w_O = s.to_space(k, s.omega[k])
            v_S: FloatArray = s.v[k] + cross3(w_O, S - s.r[k])
            return v_S

        return vel(self.i) - vel(self.j)

    def speed_scale(self, s: Snapshot, ft: Feature) -> float:
        """Σ |v_S,k| plus the speeds the run's impulses have changed the bodies' by (the
        model's ``carried``): the size of the terms whose difference is the approach
        speed, and of those the velocities were summed from (an impulse leaves one
        rounding of itself in them: a box landing flat on four corners at once keeps a
        spin of ~1e-14 rad/s from its impulses' rounding, which its later, slower
        bounces must not read as sliding)."""
        S, _ = self.contact(s, ft)
        tot = 0.0
        for k in self.bodies():
            w_O = s.to_space(k, s.omega[k])
            tot += float(np.linalg.norm(s.v[k]) + np.linalg.norm(cross3(w_O, S - s.r[k])))
            tot += float(self.carried[k]) if self.carried.size else 0.0
        return tot

    def gap_scale(self, s: Snapshot, ft: Feature) -> float:
        """The size the feature's gap is rounded relative to at one time: its point, its
        body's centre and arm (a corner's or a rim's position is G plus an arm: it rounds
        relative to both), the plane's point and the radii."""
        arm = (
            sum(abs(x) for x in ft.support)
            if ft.support is not None
            else (float(np.abs(ft.at).sum()) if ft.at is not None else 0.0)
        )
        return float(
            np.abs(self.feature_point(s, ft)).sum()
            + np.abs(s.r[ft.body]).sum()
            + arm
            + np.abs(self.point).sum()
            + ft.a
            + ft.a_s
        )

    def tangential_speed(self, s: Snapshot, ft: Feature) -> float:
        """|the relative velocity of the contact points across the normal| (sliding)."""
        S, n = self.contact(s, ft)
        u = self._relative_velocity(s, S)
        return float(np.linalg.norm(u - (u @ n) * n))

    # ------------------------------------------------------------------ impulse
    def apply(self, s: Snapshot, ft: Feature) -> dict[str, Any]:
        """Resolve the impact at this feature: new v and L_A written into the snapshot's
        arrays (in place); returns the event's details, with the kinetic energy, momentum
        and angular momentum (about the contact point) of the bodies involved before and
        after, read off the velocities: an independent route to the loss formula."""
        from mechanics.errors import SeparatingContactError

        S, n = self.contact(s, ft)
        idx = self.bodies()
        before = totals(s, idx, S)
        v_n = -self.approach(s, ft)
        if not v_n < 0:
            raise SeparatingContactError(f"the contact separates (v_n = {v_n!r} ≥ 0)")
        self._mode = "smooth"
        saved = (s.v.copy(), s.L_A.copy(), s.omega.copy())
        self._apply(s, S, n, v_n)
        if self._loss < -GAIN_RTOL * before[0]:
            s.v[...], s.L_A[...], s.omega[...] = saved
            raise EnergyGainError(
                f"the {self._mode} impulse with friction {self.mu_f:g} and e = {self.e:g} "
                f"would add {-self._loss:.3g} J of kinetic energy (Newton's restitution with "
                "friction, Kane's paradox); lower the friction or e"
            )
        after = totals(s, idx, S)
        detail: dict[str, Any] = {
            "normal_speed_before": -v_n,
            "normal_speed_after": self.approach(s, ft) * -1,
        }
        detail.update(self.who())
        detail["feature"] = ft.label
        detail["contact_point"], detail["normal"] = S.tolist(), n.tolist()
        # the gap at the instant of the impact, and the size it is rounded relative to
        detail["gap"] = float(self.gap(s, ft))
        detail["gap_scale"] = self.gap_scale(s, ft)
        detail["friction"] = self._mode
        detail.update(self.outcome(s, before, after, self._loss))
        return detail

    def who(self) -> dict[str, Any]:
        """The event's ``body`` (against the plane) or ``bodies`` (a pair)."""
        if self.j is None:
            return {"body": self.fields["body"]}
        return {"bodies": [self.fields["body"], self.fields["other"]]}

    def outcome(self, s: Snapshot, before: Totals, after: Totals, loss: float) -> dict[str, Any]:
        """The event's record of an impact's effect on the bodies (``totals`` before
        and after, read off the velocities) beside the law's energy ``loss``: what the
        run's self-checks compare."""
        idx = self.bodies()
        out: dict[str, Any] = {"bodies_before": before[5], "bodies_after": after[5]}
        # the impulse and the energies use the attitudes: an integrated R_A_O is
        # orthonormal only to the integration's tolerance
        out["attitude_defect"] = max(
            (float(np.abs(s.R[k] @ s.R[k].T - np.eye(3)).max()) for k in idx), default=0.0
        )
        if any(k in self.pins or k in self.guides for k in idx):
            out["external_impulse"] = "the pivot, bearings or track of a joint"
        elif self.j is not None and len(idx) < 2:  # a fixed body takes the other's impulse
            out["external_impulse"] = "a fixed body"
        out["energy_loss"] = loss
        out["kinetic_energy_before"], out["momentum_before"] = before[0], before[1]
        out["kinetic_energy_after"], out["momentum_after"] = after[0], after[1]
        # the sizes of the terms on either side: a body struck from rest at the contact
        # point has no moment about it before, and the others' after (found by the
        # mirror property: 6e-66 of rounding after, against a size of 0 before)
        out["momentum_scale"] = max(before[2], after[2])
        out["angular_momentum_before"], out["angular_momentum_after"] = before[3], after[3]
        out["angular_momentum_scale"] = max(before[4], after[4])
        return out

    def _apply(self, s: Snapshot, S: FloatArray, n: FloatArray, v_n: float) -> None:
        """The impulse (see the Conventions); sets ``self._loss``."""
        if self.mu_f > 0:
            self._apply_with_friction(s, S, n, v_n)
            return
        e, moving = self.e, self.bodies()
        sign = {self.i: 1.0, self.j: -1.0}
        central = not any(k in self.pins or k in self.guides for k in moving) and all(
            not np.any(cross(S - s.r[k], n)) for k in moving
        )
        if central and len(moving) == 2:  # through both centres: the direct impact, 2 ulps
            from mechanics.impact import direct_impact

            i, j = self.i, self.j
            m_i, m_j = s.m[i], s.m[j]
            v1, v2 = float(s.v[j] @ n), float(s.v[i] @ n)  # j behind i along n
            v1f, v2f = direct_impact(m_j, m_i, v1, v2, e)
            s.v[j] += (float(v1f) - v1) * n
            s.v[i] += (float(v2f) - v2) * n
            mu = m_i * m_j / (m_i + m_j)
        else:
            K = sum(self.inverse_mass(s, k, S) for k in moving)
            mu = 1.0 / float(n @ K @ n)
            P = -(1.0 + e) * mu * v_n * n
            for k in moving:
                self.kick(s, k, sign[k] * P, S)
        self._loss = 0.5 * mu * (1.0 - e) * (1.0 + e) * v_n * v_n

    def inverse_mass(
        self, s: Snapshot, k: int, S: FloatArray, S2: FloatArray | None = None
    ) -> FloatArray:
        """Body k's part of the contact's inverse mass matrix (space components): the
        change of the velocity of the point S per unit impulse at the point S2 (default
        S), 1/m − [ρ]× J⁻¹ [ρ₂]× with ρ, ρ₂ from G; for a pinned body from the pivot,
        with its inertia about the pivot and no 1/m (the pivot takes the translation)."""
        S2 = S if S2 is None else S2
        gd = self.guides.get(k)
        if gd is not None:  # only along the guide: Δv_S = Σ u_k(S) (u_k(S2)·P)/M_k
            q = s.coords[k][0]
            u, u2 = gd.point_rate(q, S), gd.point_rate(q, S2)
            Kk: FloatArray = (u.T / s.inertia.get(k, gd.M)) @ u2
            return Kk
        pin = self.pins.get(k)
        if pin is None:
            origin, inv_m = s.r[k], 1.0 / s.m[k]
            Jinv = np.diag(np.where(s.J[k] > 0, 1.0 / np.where(s.J[k] > 0, s.J[k], 1.0), 0.0))
        else:
            origin, inv_m, Jinv = pin[0], 0.0, pin[3]
        Kk = inv_m * np.eye(3) - _cross(S - origin) @ (s.R[k].T @ Jinv @ s.R[k]) @ _cross(
            S2 - origin
        )
        return Kk

    def kick(self, s: Snapshot, k: int, P: FloatArray, S: FloatArray) -> None:
        """Apply the impulse P (space components) at the point S to body k, in place;
        add the speeds it changed to the model's ``carried`` (see :meth:`speed_scale`)."""
        v0, w0 = np.array(s.v[k]), np.array(s.omega[k])
        self._kick(s, k, P, S)
        if self.carried.size:
            arm = float(np.linalg.norm(S - s.r[k]))
            self.carried[k] += float(
                np.linalg.norm(s.v[k] - v0) + np.linalg.norm(s.omega[k] - w0) * arm
            )

    def _kick(self, s: Snapshot, k: int, P: FloatArray, S: FloatArray) -> None:
        gd = self.guides.get(k)
        if gd is not None:  # M_k Δq̇_k = u_k·P (a hinge: J_a Δφ̇ = a·((S − C) × P))
            q, qd = s.coords[k]
            _, E, _ = gd.place(q)
            qd = qd + gd.point_rate(q, S) @ P / s.inertia.get(k, gd.M)
            s.coords[k] = (q, qd)
            s.v[k] = qd @ E
            s.omega[k] = s.R[k] @ (qd @ gd.W)
            s.L_A[k] = s.J[k] * s.omega[k]
            return
        pin = self.pins.get(k)
        if pin is None:
            s.v[k] += P / s.m[k]
            s.L_A[k] += s.to_body(k, cross(S - s.r[k], P))
            safe = np.where(s.J[k] > 0, s.J[k], 1.0)
            s.omega[k] = np.where(s.J[k] > 0, s.L_A[k] / safe, 0.0)
            return
        C, _, _, JCinv = pin  # ΔL_C = (S − C) × P; G's velocity follows from ω
        s.omega[k] = s.omega[k] + JCinv @ s.to_body(k, cross(S - C, P))
        s.L_A[k] = s.J[k] * s.omega[k]
        s.v[k] = cross(s.to_space(k, s.omega[k]), s.r[k] - C)

    def _apply_with_friction(self, s: Snapshot, S: FloatArray, n: FloatArray, v_n: float) -> None:
        """Stick or slip (see the Conventions); sets ``self._loss`` and ``self._mode``."""
        e, mu, moving = self.e, self.mu_f, self.bodies()
        sign = {self.i: 1.0, self.j: -1.0}
        # (a sum of arrays: ``moving`` is never empty, two fixed bodies never meet)
        K = cast("FloatArray", sum(self.inverse_mass(s, k, S) for k in moving))
        u = self._relative_velocity(s, S)
        # stick (numpy types a solve as floating[Any]: it is float64, as K and the right side)
        P = cast("FloatArray", np.linalg.solve(K, -e * v_n * n - u))
        P_n = float(P @ n)
        P_t = P - P_n * n
        self._mode = "stick"
        if np.linalg.norm(P_t) > mu * P_n:
            t_hat = _direction(u - (u @ n) * n)  # the slip, or where sticking would push
            if t_hat is None:
                t_hat = _direction(-P_t)
                # no tangential slip: the stick impulse presses (P_n > 0), so |P_t| > μ P_n ≥ 0
                assert t_hat is not None, "a slip with no tangential impulse"
            d = n - mu * t_hat
            P = (-(1.0 + e) * v_n / float(n @ K @ d)) * d
            self._mode = "slip"
        for k in moving:
            self.kick(s, k, sign[k] * P, S)
        self._loss = -float(P @ u + 0.5 * P @ K @ P)

    # ---------------------------------------------------------------- invariants
    def keeps(self, quantity: str) -> bool:
        if self.j is None:  # against the plane: along its normal (with friction: nothing)
            return (
                quantity != "E" and self.mu_f == 0 and keeps_for_force_along(self.normal, quantity)
            )
        if self.fixed:
            return False
        return quantity != "E" or (self.e == 1.0 and self.mu_f == 0)

    def exerts_moment(self, k: int) -> bool:
        """On a body struck at a corner; on a sphere only with friction (a smooth
        impulse along the normal passes through its centre)."""
        if self.mu_f > 0:
            return k in self.bodies()
        return any(
            (ft.at is not None or ft.support is not None) and ft.body == k for ft in self.features
        )


def centre_gaps(impacts: Sequence[Impact], s: Snapshot) -> tuple[list[int], FloatArray]:
    """The gaps of the impacts whose one contact feature is a sphere's or a point's
    centre, all at once (a group's pairs are many): their positions in ``impacts`` and
    the gaps (..., k) at the snapshot(s) ``s``, as :meth:`Impact.gap` gives them one by
    one (plane: (r − p)·n − a; pair: |r_f − r_s| − a − a_s)."""
    rows = [
        a
        for a, imp in enumerate(impacts)
        if len(imp.features) == 1 and imp.features[0].at is None and imp.features[0].support is None
    ]
    fts = [impacts[a].features[0] for a in rows]
    body = np.array([ft.body for ft in fts], dtype=int)
    x = s.r[..., body, :]
    out = np.zeros(x.shape[:-1])
    plane = np.array([ft.sphere is None for ft in fts], dtype=bool)
    if plane.any():
        k = np.nonzero(plane)[0]
        P = np.array([impacts[rows[c]].point for c in k])
        N = np.array([impacts[rows[c]].normal for c in k])
        a = np.array([fts[c].a for c in k])
        out[..., k] = ((x[..., k, :] - P) * N).sum(-1) - a
    if (~plane).any():
        k = np.nonzero(~plane)[0]
        other = np.array([fts[c].sphere for c in k], dtype=int)
        d = x[..., k, :] - s.r[..., other, :]
        a = np.array([fts[c].a for c in k])
        a_s = np.array([fts[c].a_s for c in k])
        out[..., k] = np.sqrt((d * d).sum(-1)) - a - a_s
    return rows, out


def _cross(rho: FloatArray) -> FloatArray:
    """[ρ]×: the matrix of x ↦ ρ × x."""
    return np.array([[0.0, -rho[2], rho[1]], [rho[2], 0.0, -rho[0]], [-rho[1], rho[0], 0.0]])


def _direction(x: FloatArray) -> FloatArray | None:
    """x/|x|, formed on x scaled by its largest component (|x| of a subnormal vector
    underflows to 0); None for the zero vector."""
    big = float(np.abs(x).max())
    if big == 0.0:
        return None
    y = x / big
    return y / np.linalg.norm(y)


def totals(s: Snapshot, idx: Iterable[int], S: FloatArray) -> Totals:
    """Kinetic energy ½ m v² + ½ L_A·ω_A, momentum Σ m v, Σ m|v|, the angular momentum
    about the point S, Σ (ρ × m v) + Rᵀ L_A, the size of its terms, and each body's
    mass, centre, inertia tensor about G in space components (Rᵀ J R), v and ω (space)."""
    T, P, Pabs = 0.0, np.zeros(3), 0.0
    L, Labs = np.zeros(3), 0.0
    for k in idx:
        m, v = float(s.m[k]), s.v[k]
        T += 0.5 * m * float(v @ v) + 0.5 * float(s.L_A[k] @ s.omega[k])
        P += m * v
        Pabs += m * float(np.linalg.norm(v))
        arm = s.r[k] - S
        spin = s.to_space(k, s.L_A[k])
        L += cross(arm, m * v) + spin
        # |ρ| m |v| bounds the orbital term: the size its rounding is relative to
        Labs += float(np.linalg.norm(arm) * m * np.linalg.norm(v) + np.linalg.norm(spin))
    bodies = [
        {
            "index": int(k),
            "m": m_k,
            "r_G": s.r[k].tolist(),
            "J_G": (s.R[k].T @ np.diag(s.J[k]) @ s.R[k]).tolist(),
            "v_G": s.v[k].tolist(),
            "omega": s.to_space(k, s.omega[k]).tolist(),
        }
        for k in idx
        for m_k in [float(s.m[k])]
    ]
    return T, P.tolist(), Pabs, L.tolist(), Labs, bodies
