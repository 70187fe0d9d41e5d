"""Rolling without slipping (3.77, 4.60): a round body on an incline or inside a
cylindrical track, a joint that guides its body (one coordinate).

Conventions
-----------
- **Incline** (``surface = "incline"``, slope ``angle`` α in [0, π/2)): the plane
  through the origin with the outward normal n = (sin α, 0, cos α), descending along
  t̂ = (cos α, 0, −sin α); the coordinate s is the distance rolled down the slope, G at
  r n + s t̂.  The body's ``body_axis`` (default z) lies along a = n × t̂ = e_y and turns
  by s/r about it (ω = (ṡ/r) a: the contact point is at rest, v_G + ω × (−r n) = 0).
  Initial keys ``distance`` and ``speed``.  Series s, v, omega (= v/r), drop (s sin α).
- **Track** (``surface = "track"``, radius R > r): the inside of a cylinder about the
  horizontal axis a = −e_y through the origin; the coordinate ψ is the angle of G from
  the direction u0 of gravity across the axis (the lowest line), G at (R − r) ρ̂(ψ),
  ρ̂ = cos ψ u0 + sin ψ (a × u0) (with gravity along −z: x_G = (R − r) sin ψ,
  z_G = −(R − r) cos ψ).  The body turns by −((R − r)/r) ψ about a (the contact point
  G + r ρ̂ is at rest).  Initial keys ``angle`` and ``angular_velocity``.  Series psi,
  psidot, phi (= ψ R/r), x_G, z_G.
- **Equation of motion**: T = ½ (m + J/r²) ẋ² with x the distance G travels (3.79),
  J the moment about ``body_axis``; every load enters through its generalised force
  (:class:`~mechanics.scenes.state.Guide`).  The contact force (normal and friction)
  is the reaction m a_G − Σ F (series ``reaction_*``); it does no work (E is kept).
- **Exact flows**: under uniform gravity alone, uniform acceleration down the incline
  (3.80); in a track, released from rest at |ψ0| ≤ π, the equivalent pendulum (4.64,
  Jacobi elliptic functions); uniform rolling with no other effect.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar, cast

import numpy as np

from ..state import ROUND_SHAPES, Guide, body_inertia, pendulum_from_rest, turned
from ..vectors import cross
from .base import (
    Context,
    CoordFlow,
    Effect,
    ExactCoords,
    FloatArray,
    SceneLike,
    Schema,
    SpecLike,
    Times,
    check_joint_body,
    register,
)
from .capabilities import GuidesBody

if TYPE_CHECKING:
    from .gravity import Gravity

__all__ = ["Incline", "Rolling", "Track", "check_round_on_slope", "slope_frame"]

E_Y = np.array([0.0, 1.0, 0.0])


def slope_frame(alpha: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The frame (n, t̂, a) of the incline of slope α: normal, down-slope, horizontal.

    The outward normal n = (sin α, 0, cos α), the down-slope direction
    t̂ = (cos α, 0, −sin α) and the horizontal a = n × t̂ = e_y.

    Parameters
    ----------
    alpha : float
        The slope α, rad (the scenes take [0, π/2)).

    Returns
    -------
    n : ndarray, shape (3,)
        The outward unit normal.
    t : ndarray, shape (3,)
        The unit down-slope direction.
    a : ndarray, shape (3,)
        e_y, a new array each call.

    Raises
    ------
    TypeError
        If ``alpha`` is not a real number (:func:`math.sin`).

    Examples
    --------
    >>> n, t, a = slope_frame(0.5)
    >>> bool(np.allclose(np.cross(n, t), a)), a.tolist()
    (True, [0.0, 1.0, 0.0])
    """
    n = np.array([math.sin(alpha), 0.0, math.cos(alpha)])
    t = np.array([math.cos(alpha), 0.0, -math.sin(alpha)])
    return n, t, E_Y.copy()


def check_round_on_slope(spec: SpecLike, scene: SceneLike, *, slope: bool = True) -> None:
    """Refuse a rolling or sliding body that is not round, or an incline not in [0, π/2).

    Parameters
    ----------
    spec : SpecLike
        The joint (its fields ``body`` and, on an incline, ``angle`` in rad, default 0).
    scene : SceneLike
        The scene.
    slope : bool, optional
        Check the ``angle`` too (default True; False for a track).

    Raises
    ------
    SceneError
        The exception ``scene.error`` makes (a :class:`SceneError` for a parsed scene):
        for a body not of :data:`~mechanics.scenes.state.ROUND_SHAPES`, or an ``angle``
        outside [0, π/2).

    Examples
    --------
    >>> from mechanics.scenes.spec import EffectSpec, parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...     "bodies": [{"name": "cyl", "shape": "cylinder", "mass": 2.0, "radius": 0.5,
    ...                 "height": 0.2}]})
    >>> check_round_on_slope(EffectSpec("rolling", 0, {"body": "cyl", "angle": 0.5}), sc)
    >>> check_round_on_slope(EffectSpec("rolling", 0, {"body": "cyl", "angle": 2.0}), sc)
    Traceback (most recent call last):
    ...
    mechanics.scenes.errors.SceneError: <scene>: effects[0].angle: must lie in [0, π/2); got 2.0
    """
    b = scene.body(spec.fields["body"])
    if b.shape not in ROUND_SHAPES:
        raise scene.error(
            f"{spec.where}.body",
            f"only round bodies roll ({', '.join(ROUND_SHAPES)}); {b.name!r} is a {b.shape}",
        )
    a = spec.fields.get("angle", 0.0)
    if slope and not 0 <= a < math.pi / 2:
        raise scene.error(f"{spec.where}.angle", f"must lie in [0, π/2); got {a!r}")


def _uniform(q0: FloatArray, qd0: FloatArray, acc: float | FloatArray) -> CoordFlow:
    def f(t: Times) -> tuple[FloatArray, FloatArray]:
        t = np.asarray(t, dtype=float)[..., None]
        return q0 + qd0 * t + 0.5 * acc * t * t, qd0 + acc * t

    return f


def _gravity_only(effects: Sequence[Effect]) -> bool:
    return bool(effects) and all(e.type == "gravity" for e in effects)


@dataclass(frozen=True, eq=False)
class Incline(Guide):
    """A round body of radius r rolling on the incline (n, t̂, a); q = (s,).

    G is at r n + s t̂; the body turns by s/r about a (3.77).  Made by
    :meth:`Rolling.make_guide`.

    Parameters
    ----------
    n : ndarray, shape (3,)
        The incline's outward unit normal (:func:`slope_frame`).
    t : ndarray, shape (3,)
        The unit down-slope direction t̂.
    a : ndarray, shape (3,)
        The horizontal a = n × t̂, the axis the body turns about.
    r : float
        The body's radius, m (> 0).
    m : float
        Its mass, kg.
    k : int
        The body axis (0, 1, 2: x, y, z) along a.
    M : ndarray, shape (1,)
        The inertia of the coordinate s, m + J/r² (kg, 3.79).
    alpha : float
        The slope α, rad.

    Examples
    --------
    The drop s sin α (a series) is the fall of G:

    >>> from mechanics.scenes.spec import parse_scene
    >>> cyl = {"name": "cyl", "shape": "cylinder", "mass": 2.0, "radius": 0.5, "height": 0.2}
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [cyl],
    ...     "effects": [{"type": "gravity", "g": 9.75},
    ...                 {"type": "rolling", "body": "cyl", "surface": "incline", "angle": 0.5}]})
    >>> slope = Rolling.make_guide(sc.effects[1], sc, np.array([0.0, 0.0, -9.75]))
    >>> fall = slope.place(np.array([0.0]))[0][2] - slope.place(np.array([2.0]))[0][2]
    >>> slope.M.tolist(), bool(np.isclose(fall, slope.series(np.array([2.0]), np.ones(1))["drop"]))
    ([3.0], True)
    """

    n: FloatArray
    t: FloatArray
    a: FloatArray
    r: float
    m: float
    k: int
    M: FloatArray
    alpha: float

    def _get_W(self) -> FloatArray:
        return (self.a / self.r)[None, :]

    W = property(_get_W)

    def place(self, q: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        s = q[..., 0]
        G = self.r * self.n + s[..., None] * self.t
        E = np.broadcast_to(self.t, (*s.shape, 1, 3))
        return G, E, turned(self.a, self.n, self.k, s / self.r)

    def start(self, initial: Mapping[str, Any]) -> tuple[FloatArray, FloatArray]:
        return (
            np.array([float(initial.get("distance", 0.0))]),
            np.array([float(initial.get("speed", 0.0))]),
        )

    def series(self, q: FloatArray, qd: FloatArray) -> dict[str, FloatArray]:
        s, v = q[..., 0], qd[..., 0]
        return {"s": s, "v": v, "omega": v / self.r, "drop": s * math.sin(self.alpha)}

    def exact(
        self,
        effects: Sequence[Effect],
        m: float,
        q0: FloatArray,
        qd0: FloatArray,
        duration: float,
    ) -> ExactCoords | None:
        if not effects:
            return "exact: uniform rolling", _uniform(q0, qd0, 0.0), []
        if _gravity_only(effects):
            acc = sum(m * float(cast("Gravity", e).vector @ self.t) for e in effects) / self.M
            return "exact: uniform acceleration down the incline (3.80)", _uniform(q0, qd0, acc), []
        return None


@dataclass(frozen=True, eq=False)
class Track(Guide):
    """A round body of radius r rolling inside a track of radius R about a; q = (ψ,).

    The axis a passes through the origin; ψ is measured from u0 (u1 = a × u0), G is at
    (R − r) (cos ψ u0 + sin ψ u1) (4.60).  Made by :meth:`Rolling.make_guide`.

    Parameters
    ----------
    a : ndarray, shape (3,)
        The track's unit axis (−e_y).
    u0 : ndarray, shape (3,)
        The unit direction across a where ψ = 0 (gravity's, the lowest line).
    u1 : ndarray, shape (3,)
        a × u0.
    r : float
        The body's radius, m (0 < r < R).
    R : float
        The track's radius, m.
    m : float
        The body's mass, kg.
    k : int
        The body axis (0, 1, 2: x, y, z) along a.
    M : ndarray, shape (1,)
        The inertia of the coordinate ψ, M_eff (R − r)² (kg m²).
    M_eff : float
        m + J/r², kg (3.79).

    Examples
    --------
    >>> from mechanics.scenes.spec import parse_scene
    >>> cyl = {"name": "cyl", "shape": "cylinder", "mass": 2.0, "radius": 0.5, "height": 0.2}
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [cyl],
    ...     "effects": [{"type": "gravity", "g": 9.75},
    ...                 {"type": "rolling", "body": "cyl", "surface": "track",
    ...                  "track_radius": 2.5}]})
    >>> track = Rolling.make_guide(sc.effects[1], sc, np.array([0.0, 0.0, -9.75]))
    >>> track.M_eff * (2.5 - 0.5) ** 2, track.M.tolist()
    (12.0, [12.0])
    >>> track.place(np.array([0.0]))[0].tolist()  # at ψ = 0, G is R − r below the axis
    [0.0, 0.0, -2.0]
    """

    a: FloatArray
    u0: FloatArray
    u1: FloatArray
    r: float
    R: float
    m: float
    k: int
    M: FloatArray
    M_eff: float

    def _get_W(self) -> FloatArray:
        return (-(self.R - self.r) / self.r * self.a)[None, :]

    W = property(_get_W)

    def _rho(self, psi: FloatArray) -> tuple[FloatArray, FloatArray]:
        c, s = np.cos(psi)[..., None], np.sin(psi)[..., None]
        return c * self.u0 + s * self.u1, c * self.u1 - s * self.u0

    def place(self, q: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        psi = q[..., 0]
        rho, tau = self._rho(psi)
        d = self.R - self.r
        return d * rho, (d * tau)[..., None, :], turned(self.a, self.u0, self.k, -d / self.r * psi)

    def bend(self, q: FloatArray, qd: FloatArray) -> FloatArray:
        rho, _ = self._rho(q[..., 0])
        return -(self.R - self.r) * (qd[..., 0] ** 2)[..., None] * rho

    def start(self, initial: Mapping[str, Any]) -> tuple[FloatArray, FloatArray]:
        return (
            np.array([float(initial.get("angle", 0.0))]),
            np.array([float(initial.get("angular_velocity", 0.0))]),
        )

    def series(self, q: FloatArray, qd: FloatArray) -> dict[str, FloatArray]:
        psi, d = q[..., 0], self.R - self.r
        return {
            "psi": psi,
            "psidot": qd[..., 0],
            "phi": psi * self.R / self.r,
            "x_G": d * np.sin(psi),
            "z_G": -d * np.cos(psi),
        }

    def exact(
        self,
        effects: Sequence[Effect],
        m: float,
        q0: FloatArray,
        qd0: FloatArray,
        duration: float,
    ) -> ExactCoords | None:
        psi0, w0 = float(q0[0]), float(qd0[0])
        if not effects:
            return "exact: uniform rolling round the track", _uniform(q0, qd0, 0.0), []
        if len(effects) == 1 and _gravity_only(effects) and w0 == 0 and abs(psi0) <= math.pi:
            g = cast("Gravity", effects[0]).vector
            gp = float(np.linalg.norm(g - (g @ self.a) * self.a))
            if gp > 0 and float(g @ self.u0) > 0:
                f = pendulum_from_rest(
                    self.M_eff * (self.R - self.r) ** 2, m, gp, self.R - self.r, psi0
                )
                how = "exact: equivalent pendulum released from rest (4.64), elliptic functions"
                return how, f, []
        return None


@register
class Rolling(Effect, GuidesBody):
    """Rolling without slipping of a round body on an incline or in a track (3.77, 4.60).

    One degree of freedom (:class:`Incline`, :class:`Track`); the contact force does no
    work.

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body`` (round), ``surface`` (``"incline"`` or
        ``"track"``), ``angle`` (the incline's slope α, rad, in [0, π/2); default 0),
        ``track_radius`` R (m, > the body's radius; a track's) and ``body_axis`` (``"x"``,
        ``"y"`` or ``"z"``, the axis it turns about; default ``"z"``).
    ctx : Context or None, optional
        The scene's context (the body's index; None: an effect built for its fields alone).

    Raises
    ------
    ValueError
        If ``body_axis`` is not one of x, y, z (the parser refuses it first).

    Examples
    --------
    The inertia of rolling, m + J/r² (3.79): 3/2 m for a solid cylinder (J = m r²/2):

    >>> from mechanics.scenes.spec import EffectSpec
    >>> roll = Rolling(EffectSpec("rolling", 0, {"body": "cyl", "surface": "incline"}))
    >>> roll.effective_mass(2.0, np.diag([0.5, 0.5, 0.25]), 0.5), 1.5 * 2.0
    (3.0, 3.0)
    """

    type = "rolling"
    dissipative = True
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "surface": ("str", True),
        "angle": ("number", False),
        "track_radius": ("positive", False),
        "body_axis": ("axis_name", False),
    }
    units: ClassVar[dict[str, str]] = {
        "body": "",
        "surface": "",
        "angle": "rad",
        "track_radius": "m",
        "body_axis": "",
    }
    example: ClassVar[dict[str, Any]] = {
        "type": "rolling",
        "body": "ball",
        "surface": "incline",
        "angle": 0.3,
    }

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        f, b = spec.fields, scene.body(spec.fields["body"])
        surf = f["surface"]
        check_round_on_slope(spec, scene, slope=surf == "incline")
        if surf == "incline":
            keys = ("distance", "speed")
        elif surf == "track":
            R = f.get("track_radius")
            if R is None:
                raise scene.error(
                    f"{spec.where}.track_radius", "missing required field for a track"
                )
            if b.dims["radius"] >= R:
                raise scene.error(
                    f"{spec.where}.track_radius",
                    f"must exceed the body's radius {b.dims['radius']!r} (R > r); got {R!r}",
                )
            keys = ("angle", "angular_velocity")
        else:
            raise scene.error(
                f"{spec.where}.surface", f"expected 'incline' or 'track'; got {surf!r}"
            )
        check_joint_body(spec, scene, index, what="it cannot roll", keys=keys)

    @classmethod
    def make_guide(cls, spec: SpecLike, scene: SceneLike, g_vector: FloatArray) -> Guide:
        f, b = spec.fields, scene.body(spec.fields["body"])
        k = "xyz".index(f.get("body_axis", "z"))
        r, m = float(b.dims["radius"]), float(b.mass)
        M_eff = cls(spec).effective_mass(m, np.diag(body_inertia(b)), r)
        if f["surface"] == "incline":
            alpha = float(f.get("angle", 0.0))
            n, t, a = slope_frame(alpha)
            return Incline(n, t, a, r, m, k, np.array([M_eff]), alpha)
        a = -E_Y
        g = np.asarray(g_vector, dtype=float)
        across = g - (g @ a) * a
        u0 = across / np.linalg.norm(across) if across.any() else np.array([0.0, 0.0, -1.0])
        R = float(f["track_radius"])
        return Track(a, u0, cross(a, u0), r, R, m, k, np.array([M_eff * (R - r) ** 2]), M_eff)

    def __init__(self, spec: SpecLike, ctx: Context | None = None) -> None:
        super().__init__(spec, ctx)
        self.body_axis = "xyz".index(self.fields.get("body_axis", "z"))

    def effective_mass(self, m: float, J_G: FloatArray, r: float) -> float:
        """m + J/r²: the kinetic energy is ½ (m + J/r²) v² when v = ω r (3.79)."""
        return m + float(J_G[self.body_axis, self.body_axis]) / r**2

    def keeps(self, quantity: str) -> bool:
        return quantity == "E"  # the contact point is at rest: the contact force does no work

    def exerts_moment(self, k: int) -> bool:
        return k == self.ctx.index[self.fields["body"]] if self.ctx else True
