"""One state layout for every scene of free bodies: what a body carries, where it sits in
the flat state vector, and the geometry of its shape (moments, radius, vertices).

Conventions
-----------
- **Kinds of body.**  A *point* (shape ``point``) carries the position r and velocity v
  of its centre of mass G.  A *rigid* body (any other shape) carries r, v, its angular
  momentum about G in body components ``L_A`` and its attitude ``R_A_O``, the book's
  passive matrix ^A R^O (rows: the body's basis vectors e^A_i in the space basis O; a
  vector with body components x_A has space components ``R_A_O.T @ x_A``), as
  :mod:`mechanics.integrators` lays out the free rigid body.  A *fixed* body
  (``fixed = true``) carries nothing: it stays at its initial position, at rest, with
  the identity attitude, and acts as an immovable partner of contacts.
- **The flat vector.**  Bodies in file order; a point takes 6 numbers ``(r, v)``, a
  rigid body 18 ``(r, v, L_A, R_A_O row by row)``, a pinned body 12 ``(L_C, R_A_O)``, a
  *guided* body 2 nq ``(q, q̇)`` (a :class:`Guide`: a fixed axis, rolling, sliding on a
  plane), a tank 2 ``(√h, volume out)``, a fixed body 0.  :class:`Layout`
  gathers the per-body arrays from a state of any leading shape ``(..., size)`` in one
  indexing (no Python loop over bodies), so the same code serves one right-hand-side
  evaluation and thousands of samples.
- **Equations of motion** (:meth:`Layout.derivative`, each body's by its kind's class
  in :mod:`.bodies`): ṙ = v, v̇ = F/m (forces in O),
  L̇_A = L_A × ω_A + M_A (Euler's equations (4.47) with the moment M_A about G in body
  components), Ṙ_A_O = −[ω_A]× R_A_O (the book's (2.52), Ω = −[ω]×).  ω_A = L_A / J
  componentwise in the principal frame; a zero principal moment (a thin rod about its
  own axis) has no spin about that axis: its inverse is taken as 0, and no force on the
  rod's points has a moment about it.
- **Masses** may vary with time (a rocket's thrust): ``masses(t)``; a rigid body's
  principal moments then scale with its mass (the fuel is spread like the body).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol, TypeAlias, cast

import numpy as np
import numpy.typing as npt

from .trajectory import Event
from .vectors import FloatArray, IntArray, Times, cross, cross3

if TYPE_CHECKING:  # for annotations only: these are layers above
    from .bodies import Body
    from .effects import Effect, Snapshot
    from .effects.gravity import Gravity
    from .effects.mass_flow import MassFlow
    from .effects.torsion import Torsion
    from .spec import Body as BodySpec

#: t -> (q, q̇) of a guided body, shapes (..., nq)
CoordFlow: TypeAlias = Callable[[Times], tuple[FloatArray, FloatArray]]
#: an exact flow of a guided body's coordinates: (how, f, events)
ExactCoords: TypeAlias = tuple[str, CoordFlow, list[Event]]


class BodyShape(Protocol):
    """What a body's geometry is read from (:class:`mechanics.scenes.spec.Body` has it)."""

    @property
    def shape(self) -> str: ...
    @property
    def mass(self) -> float: ...
    @property
    def dims(self) -> Mapping[str, Any]: ...


#: a pinned body's (C, g_A, J_C, J_C⁻¹)
Pin: TypeAlias = tuple[FloatArray, FloatArray, FloatArray, FloatArray]
#: :meth:`Layout._index`: the rows of r, v, L_A, R_A_O in the padded state, and its constants
_Index: TypeAlias = tuple[IntArray, IntArray, IntArray, IntArray, FloatArray]

__all__ = [
    "ROUND_SHAPES",
    "SPHERICAL_SHAPES",
    "Guide",
    "Hinge",
    "Layout",
    "body_inertia",
    "body_radius",
    "body_vertices",
    "point_acceleration",
    "turned",
]

ROUND_SHAPES = ("ring", "disc", "cylinder", "cylindrical_shell", "solid_sphere", "hollow_sphere")
SPHERICAL_SHAPES = ("point", "solid_sphere", "hollow_sphere")


def point_acceleration(
    base: FloatArray, alpha: FloatArray, w: FloatArray, r: FloatArray
) -> FloatArray:
    """base + α × r + ω × (ω × r): the acceleration of a body point at r from an origin.

    The rigid body's acceleration field: the origin (a point of the body) has
    acceleration ``base``; the inputs are 3-vectors in one basis and are not checked.

    Parameters
    ----------
    base : ndarray, shape (3,)
        The acceleration of the origin, m/s².
    alpha : ndarray, shape (3,)
        The angular acceleration α = ω̇, rad/s².
    w : ndarray, shape (3,)
        The angular velocity ω, rad/s.
    r : ndarray, shape (3,)
        The point, from the origin, m.

    Returns
    -------
    ndarray, shape (3,)
        The point's acceleration, m/s².

    Raises
    ------
    IndexError
        Where a vector has fewer than 3 components (:func:`~.vectors.cross3`).

    Examples
    --------
    Uniform rotation about e3: the centripetal ω × (ω × r) = −ω² r for r ⟂ ω, and
    α × r adds the tangential part:

    >>> w, r = np.array([0.0, 0.0, 2.0]), np.array([3.0, 0.0, 0.0])
    >>> a = point_acceleration(np.zeros(3), np.zeros(3), w, r)
    >>> a.tolist(), bool(np.array_equal(a, -(2.0**2) * r))
    ([-12.0, 0.0, 0.0], True)
    >>> point_acceleration(np.zeros(3), np.array([0.0, 0.0, 1.0]), w, r).tolist()
    [-12.0, 3.0, 0.0]
    """
    return base + cross3(alpha, r) + cross3(w, cross3(w, r))


def turned(a: FloatArray, u0: FloatArray, k: int, theta: Times) -> FloatArray:
    """The rows of R_A_O of a body turned by θ about the space axis a (any shape of θ).

    Body axis k along a, axis j = (k + 1) % 3 along u0 at θ = 0 and axis l = (k + 2) % 3
    along u1 = a × u0; at θ, e_j = cos θ u0 + sin θ u1, e_l = cos θ u1 − sin θ u0.
    Nothing is checked: a and u0 are taken as orthonormal.

    Parameters
    ----------
    a : ndarray, shape (3,)
        The unit axis in space components.
    u0 : ndarray, shape (3,)
        A unit vector ⟂ a: body axis j at θ = 0.
    k : int
        The body axis along a: 0, 1 or 2.
    theta : float or ndarray, shape (...)
        The angle(s) of the turn, rad.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        R_A_O at each θ: its rows the body's basis vectors in space components.

    Raises
    ------
    ValueError
        Where ``a`` or ``u0`` does not end in 3 (:func:`~.vectors.cross`).
    IndexError
        Where ``k`` is not 0, 1 or 2.

    Examples
    --------
    About e3 with u0 = e1: the identity at θ = 0, and at θ the body's e1 at
    (cos θ, sin θ, 0); each attitude orthogonal:

    >>> e = np.eye(3)
    >>> R = turned(e[2], e[0], 2, np.array([0.0, 0.5]))
    >>> R[0].tolist() == e.tolist(), bool(np.allclose(R[1, 0], [np.cos(0.5), np.sin(0.5), 0]))
    (True, True)
    >>> bool(np.allclose(R @ np.swapaxes(R, -1, -2), e))
    True
    """
    u1 = cross(a, u0)
    c, s = np.cos(theta)[..., None], np.sin(theta)[..., None]
    R = np.empty((*np.shape(theta), 3, 3))
    R[..., k, :] = a
    R[..., (k + 1) % 3, :] = c * u0 + s * u1
    R[..., (k + 2) % 3, :] = c * u1 - s * u0
    return R


class Guide:
    """What a joint makes of a body it guides: coordinates q, the centre G(q), R_A_O(q).

    ``nq`` coordinates q (the state holds q, then q̇), the centre G(q) and attitude
    R_A_O(q), the derivatives E_k = ∂G/∂q_k, the angular velocity W_k (space) per unit
    q̇_k (constant), and the constant inertias M_k of the kinetic energy
    T = ½ Σ M_k q̇_k² (m E_j·E_k + W_jᵀ J W_k = 0 for j ≠ k and |E_k| constant along the
    path, so Lagrange's equations read M_k q̈_k = Q_k, with the generalised force
    Q_k = F·E_k + M·W_k of a force F at G and a moment M about G).

    Subclasses set ``nq``, ``W`` (nq, 3), ``M`` (nq,), ``k`` (the body axis the turn is
    about, for the series) and give :meth:`place` and :meth:`bend`.

    Examples
    --------
    A fixed axis (:class:`Hinge`) is a guide: its q̈ = (E·F + W·M) / M of a force F at
    G and a moment M about it:

    >>> e = np.eye(3)
    >>> hinge = Hinge(np.zeros(3), e[2], -e[1], e[0], k=2, j=0, l=1, h=0.5, J_a=2.0)
    >>> q, F, M = np.array([0.0]), np.array([4.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])
    >>> hinge.rate(q, F, M).tolist(), ((hinge.place(q)[1] @ F + hinge.W @ M) / hinge.M).tolist()
    ([1.5], [1.5])
    """

    nq = 1
    W: FloatArray
    M: FloatArray
    k: int

    def place(self, q: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """G (..., 3), E (..., nq, 3) and R_A_O (..., 3, 3) at the coordinates q (..., nq)."""
        raise NotImplementedError

    def bend(self, q: FloatArray, qd: FloatArray) -> FloatArray:
        """The part of a_G that the rates make on a curved path, a_G − Σ E_k q̈_k (..., 3)."""
        return np.zeros((*np.shape(q)[:-1], 3))

    def start(self, initial: Mapping[str, Any]) -> tuple[FloatArray, FloatArray]:
        """(q0, q̇0) from a body's ``initial`` table."""
        raise NotImplementedError

    def exact(
        self,
        effects: Sequence[Effect],
        m: float,
        q0: FloatArray,
        qd0: FloatArray,
        duration: float,
    ) -> ExactCoords | None:
        """For a lone guided body under ``effects`` (the other listed effects): (how,
        f, events) with f(t) -> (q, q̇) of shapes (..., nq) where the motion has an
        exact flow, else None."""
        return None

    def series(self, q: FloatArray, qd: FloatArray) -> dict[str, FloatArray]:
        """The named series of the coordinates (samples q, q̇ of shape (k, nq))."""
        return {}

    def rate(
        self, q: FloatArray, F: FloatArray, M_O: FloatArray, M: FloatArray | None = None
    ) -> FloatArray:
        """q̈ (nq,) from the force F at G and the moment M_O about G (space components);
        ``M`` replaces the inertias (a body whose inertia grows, 7.39)."""
        _, E, _ = self.place(q)
        return (E @ F + self.W @ M_O) / (self.M if M is None else M)

    def point_rate(self, q: FloatArray, S: FloatArray) -> FloatArray:
        """u_k (nq, 3): the velocity of the body point at S per unit q̇_k, E_k + W_k × (S − G)."""
        G, E, _ = self.place(q)
        return E + cross(self.W, S - G)


@dataclass(frozen=True, eq=False)
class Hinge(Guide):
    """A fixed axis (4.3): the body turns about the unit axis a through C; q = (φ,).

    The point C and unit axis a in space, the reference u0 (where φ = 0) and
    u1 = a × u0, the body axes (k along a, j toward G, l), the distance h of G from the
    axis and the moment of inertia J_a about it.  The constructor stores what it is
    given and checks nothing (the joint's effect builds it:
    :meth:`mechanics.scenes.effects.fixed_axis.FixedAxis.make_guide`).

    Parameters
    ----------
    C : ndarray, shape (3,)
        A point of the axis, m, in space components.
    a : ndarray, shape (3,)
        The axis, a unit vector in space components.
    u0 : ndarray, shape (3,)
        The unit vector ⟂ a toward G at φ = 0 (gravity's direction for a pendulum).
    u1 : ndarray, shape (3,)
        a × u0.
    k : int
        The body axis along a (0, 1 or 2).
    j : int
        The body axis toward G, (k + 1) % 3.
    l : int
        The third body axis, (k + 2) % 3.
    h : float
        The distance of G from the axis, m, ≥ 0.
    J_a : float
        The moment of inertia about the axis, kg m², > 0.

    Examples
    --------
    A pendulum about e3 hanging along −e2 at φ = 0: G = h (sin φ, −cos φ, 0), the
    book's picture that its series report:

    >>> e = np.eye(3)
    >>> hinge = Hinge(np.zeros(3), e[2], -e[1], e[0], k=2, j=0, l=1, h=0.5, J_a=2.0)
    >>> G, E, R = hinge.place(np.array([0.0]))
    >>> G.tolist(), E.tolist()
    ([0.0, -0.5, 0.0], [[0.5, 0.0, 0.0]])
    >>> q = np.array([[0.3]])
    >>> s = hinge.series(q, q)
    >>> bool(np.allclose(hinge.place(q)[0][0, :2], [s["x_G"][0], s["y_G"][0]]))
    True
    """

    C: FloatArray
    a: FloatArray
    u0: FloatArray
    u1: FloatArray
    k: int
    j: int
    l: int
    h: float
    J_a: float

    def _get_W(self) -> FloatArray:
        return self.a[None, :]

    W = property(_get_W)

    def _get_M(self) -> FloatArray:
        return np.array([self.J_a])

    M = property(_get_M)

    def frame(self, phi: Times) -> tuple[FloatArray, FloatArray, FloatArray]:
        """r̂, a × r̂ and the rows of R_A_O at the angle(s) φ: shapes (..., 3), (..., 3, 3)."""
        R = turned(self.a, self.u0, self.k, phi)
        return R[..., self.j, :], R[..., self.l, :], R

    def place(self, q: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        rhat, tang, R = self.frame(q[..., 0])
        return self.C + self.h * rhat, (self.h * tang)[..., None, :], R

    def bend(self, q: FloatArray, qd: FloatArray) -> FloatArray:
        rhat = self.frame(q[..., 0])[0]
        return -self.h * (qd[..., 0] ** 2)[..., None] * rhat

    def start(self, initial: Mapping[str, Any]) -> tuple[FloatArray, FloatArray]:
        return (
            np.array([float(initial.get("angle", 0.0))]),
            np.array([float(initial.get("angular_velocity", 0.0))]),
        )

    def series(self, q: FloatArray, qd: FloatArray) -> dict[str, FloatArray]:
        phi = q[..., 0]
        out = {"phi": phi, "phidot": qd[..., 0]}
        if self.h > 0:  # the book's picture: G at h (sin φ, −cos φ) in the plane ⟂ a
            out["x_G"], out["y_G"] = self.h * np.sin(phi), -self.h * np.cos(phi)
        return out

    def exact(
        self,
        effects: Sequence[Effect],
        m: float,
        q0: FloatArray,
        qd0: FloatArray,
        duration: float,
    ) -> ExactCoords | None:
        """Uniform rotation; the pendulum released from rest (gravity across the axis, G
        off it, |φ0| ≤ π: Jacobi elliptic functions, 4.50); the harmonic torsion
        pendulum (3.76); the carousel under fire (mass flowing in, 7.39)."""
        phi0, w0 = float(q0[0]), float(qd0[0])
        kinds = [e.type for e in effects]
        if not kinds:
            return "exact: uniform rotation", lambda t: _col(phi0 + w0 * t, w0 + 0.0 * t), []
        if kinds == ["torsion"]:
            om = math.sqrt(cast("Torsion", effects[0]).tau_0 / self.J_a)

            def f(t: Times) -> tuple[FloatArray, FloatArray]:
                c, s = np.cos(om * t), np.sin(om * t)
                return _col(phi0 * c + w0 / om * s, -phi0 * om * s + w0 * c)

            return "exact: harmonic torsion oscillation", f, []
        if kinds == ["mass_flow"]:
            return _carousel(cast("MassFlow", effects[0]), self.J_a, phi0, w0)
        if kinds == ["gravity"] and w0 == 0 and abs(phi0) <= math.pi:
            gp = cast("Gravity", effects[0]).axis_g_perp(self.a)
            if gp > 0 and self.h > 0:
                fall = pendulum_from_rest(self.J_a, m, gp, self.h, phi0)
                return (
                    "exact: pendulum released from rest, Jacobi elliptic functions (4.50)",
                    fall,
                    [],
                )
        return None

    def moment(self, R: FloatArray, r: FloatArray, F: FloatArray, M_A: FloatArray) -> FloatArray:
        """The loads' moment about C in space components: R_A_Oᵀ M_A + (r_G − C) × F, for a
        force F at G and a moment M_A about G in body components."""
        return R.T @ M_A + cross(r - self.C, F)


def _col(q: npt.ArrayLike, qd: npt.ArrayLike) -> tuple[FloatArray, FloatArray]:
    """(q, q̇) of a one-coordinate guide as shapes (..., 1)."""
    return np.asarray(q, dtype=float)[..., None], np.asarray(qd, dtype=float)[..., None]


def pendulum_from_rest(J: float, m: float, g: float, h: float, q0: float) -> CoordFlow:
    """t -> (q, q̇) of J q̈ = −m g h sin q released from rest at |q0| ≤ π (4.50):
    :func:`mechanics.dynamics.pendulum_motion`, and q̇ = −2 k k' ω0 sd(ω0 t) with
    k = sin(|q0|/2), ω0 = √(m g h/J)."""
    from mechanics.dynamics import pendulum_motion
    from mechanics.elliptic import ellipj

    om0 = math.sqrt(m * g * h / J)
    k, kp = math.sin(abs(q0) / 2), math.cos(abs(q0) / 2)
    sgn = 1.0 if q0 >= 0 else -1.0

    def f(t: Times) -> tuple[FloatArray, FloatArray]:
        q = pendulum_motion(t, J, m, g, h, q0)
        sn, _, dn, _ = ellipj(om0 * np.asarray(t, float), k * k, m1=kp * kp)
        return _col(q, -sgn * 2.0 * k * kp * om0 * sn / dn)

    return f


def _carousel(flow: MassFlow, J0: float, phi0: float, w0: float) -> ExactCoords:
    """The carousel under fire (7.39): J(t) = J0 + q R² t, d(J φ̇)/dt = −r q v, so
    φ̇ = (J0 φ̇0 − r q v t)/J(t) (:func:`mechanics.open_systems.carousel_angular_velocity`)
    and φ = φ0 − (b/c) t + (J0 φ̇0 + b J0/c)/c · ln(1 + c t/J0), c = q R², b = r q v."""
    from mechanics.open_systems import carousel_angular_velocity

    c, b = flow.q * flow.R**2, flow.r * flow.q * flow.v

    def f(t: Times) -> tuple[FloatArray, FloatArray]:
        t = np.asarray(t, float)
        kw = dict(J_0=J0, q=flow.q, v=flow.v, r=flow.r, R=flow.R, phidot_0=w0)
        w = carousel_angular_velocity(t, **kw)
        if c == 0:
            return _col(phi0 + w0 * t, w)
        phi = phi0 - (b / c) * t + (J0 * w0 + b * J0 / c) / c * np.log1p(c * t / J0)
        return _col(phi, w)

    return "exact: carousel under fire, solution of (7.39)", f, []


def body_inertia(body: BodyShape) -> FloatArray:
    """Principal moments about G, shape (3,), from the inertia catalogue.

    The catalogue is :mod:`mechanics.inertia` (its principal axes are the body's axes
    e1, e2, e3); a custom body's moments are its ``inertia``; a point or a tank has 0.

    Parameters
    ----------
    body : BodyShape
        A body's ``shape``, ``mass`` (kg) and ``dims`` (m; a custom body's
        ``inertia``, kg m²), as :class:`mechanics.scenes.spec.Body` has them.

    Returns
    -------
    ndarray, shape (3,)
        The principal moments J1, J2, J3 about G, kg m².

    Raises
    ------
    KeyError
        Where the shape is not in the catalogue, or ``dims`` lacks a dimension it needs.
    NegativeMassError
        Where the mass is negative.
    NonPositiveParameterError
        Where a dimension is not > 0.
    NonFiniteError
        Where the mass or a dimension is NaN or infinite.

    Examples
    --------
    A solid sphere: J = 2/5 m R² about every axis; a box's J1 = m (b² + c²)/12:

    >>> from mechanics.scenes.spec import Body
    >>> body_inertia(Body("ball", "solid_sphere", 5.0, {"radius": 1.0}, {})).tolist()
    [2.0, 2.0, 2.0]
    >>> box = Body("box", "box", 12.0, {"a": 1.0, "b": 2.0, "c": 4.0}, {})
    >>> float(body_inertia(box)[0]) == 12.0 * (2.0**2 + 4.0**2) / 12
    True
    """
    from mechanics import inertia as I

    m, d, s = body.mass, body.dims, body.shape
    if s in ("point", "tank"):
        return np.zeros(3)
    if s == "custom":
        return np.asarray(d["inertia"], dtype=float)
    catalogue: dict[str, Callable[[], FloatArray]] = {
        "rod": lambda: I.rod(m, d["length"]),
        "ring": lambda: I.ring(m, d["radius"]),
        "disc": lambda: I.disc(m, d["radius"]),
        "cylinder": lambda: I.cylinder(m, d["radius"], d["height"]),
        "cylindrical_shell": lambda: I.cylindrical_shell(m, d["radius"], d["height"]),
        "solid_sphere": lambda: I.solid_sphere(m, d["radius"]),
        "hollow_sphere": lambda: I.hollow_sphere(m, d["radius"]),
        "rectangular_plate": lambda: I.rectangular_plate(m, d["a"], d["b"]),
        "box": lambda: I.box(m, d["a"], d["b"], d["c"]),
    }
    f = catalogue[s]
    return np.diag(f()).astype(float)


def body_radius(body: BodyShape) -> float | None:
    """Radius of a spherical body (0 for a point), None for any other shape.

    Parameters
    ----------
    body : BodyShape
        A body's ``shape`` and ``dims`` (m), as :class:`mechanics.scenes.spec.Body` has
        them.

    Returns
    -------
    float or None
        The radius, m: 0 for a point, ``dims["radius"]`` for a solid or hollow sphere;
        None for a shape that is not spherical.

    Raises
    ------
    KeyError
        Where a sphere's ``dims`` has no ``"radius"``.

    Examples
    --------
    >>> from mechanics.scenes.spec import Body
    >>> [body_radius(Body("b", s, 1.0, {"radius": 0.25}, {})) for s in SPHERICAL_SHAPES]
    [0.0, 0.25, 0.25]
    >>> body_radius(Body("b", "disc", 1.0, {"radius": 0.25}, {})) is None
    True
    """
    if body.shape == "point":
        return 0.0
    if body.shape in SPHERICAL_SHAPES:
        return float(body.dims["radius"])
    return None


def body_vertices(body: BodyShape) -> FloatArray | None:
    """The corners of a polyhedral body in body components about G, shape (k, 3).

    The 8 corners of a box (edges a, b, c along e1, e2, e3), the 4 of a rectangular
    plate (a, b in the e1e2-plane), the 2 ends of a rod (along e3); None for other
    shapes.

    Parameters
    ----------
    body : BodyShape
        A body's ``shape`` and ``dims`` (m), as :class:`mechanics.scenes.spec.Body` has
        them.

    Returns
    -------
    ndarray, shape (k, 3), or None
        The corners, m, from G in body components: k = 8 (box), 4 (plate) or 2 (rod);
        None for any other shape.

    Raises
    ------
    KeyError
        Where ``dims`` lacks a dimension the shape needs.

    Examples
    --------
    A box's corners are (±a, ±b, ±c)/2: their centre is G, and the diagonal from the
    first to the last is √(a² + b² + c²):

    >>> from mechanics.scenes.spec import Body
    >>> X = body_vertices(Body("box", "box", 1.0, {"a": 2.0, "b": 4.0, "c": 4.0}, {}))
    >>> X.shape, X.mean(axis=0).tolist(), float(np.linalg.norm(X[-1] - X[0]))
    ((8, 3), [0.0, 0.0, 0.0], 6.0)
    """
    d = body.dims
    if body.shape == "box":
        h = 0.5 * np.array([d["a"], d["b"], d["c"]])
        s = np.array([[i, j, k] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)], float)
        return s * h
    if body.shape == "rectangular_plate":
        h = 0.5 * np.array([d["a"], d["b"], 0.0])
        s = np.array([[i, j, 0] for i in (-1, 1) for j in (-1, 1)], float)
        return s * h
    if body.shape == "rod":
        return np.array([[0.0, 0.0, -0.5 * d["length"]], [0.0, 0.0, 0.5 * d["length"]]])
    return None


@dataclass(frozen=True)
class Layout:
    """Where each body's quantities sit in the flat state; gathers and scatters them.

    ``bodies[i]`` is body i's object (:mod:`.bodies`: its kind's slice, rate and
    kinematics) and ``kinds[i]`` its kind's name, ``"point"``, ``"rigid"``, ``"pinned"``,
    ``"guided"``, ``"tank"`` or ``"fixed"``; ``J`` the principal moments about G (n, 3)
    at the initial masses; ``r_fixed`` the positions of the fixed bodies; ``pins[i]`` =
    (C, g_A, J_C, J_C⁻¹) of a pinned body; ``guides[i]`` the :class:`Guide` of a guided
    one.  Built by :meth:`Layout.of`; the constructor stores what it is given and checks
    nothing.

    Parameters
    ----------
    kinds : tuple[str, ...]
        Each body's kind, in file order.
    J : ndarray, shape (n, 3)
        The principal moments about G, kg m², at the initial masses (0 for points).
    r_fixed : ndarray, shape (n, 3)
        The positions of the fixed bodies, m (0 in the other rows).
    size : int
        The length of the flat state.
    offsets : tuple[int, ...]
        Where each body's slice of the state begins.
    pins : dict[int, Pin], optional
        Pinned bodies: index -> (C, g_A, J_C, J_C⁻¹). Default none.
    guides : dict[int, Guide], optional
        Guided bodies: index -> its :class:`Guide`. Default none.
    bodies : tuple[Body, ...], optional
        Each body's object of :mod:`.bodies`. Default none.

    Examples
    --------
    A point takes (r, v), 6 numbers; a free rigid body 18: packing what is gathered
    gives the state back:

    >>> from mechanics.scenes.spec import Body
    >>> lay = Layout.of([Body("p", "point", 1.0, {}, {}),
    ...                  Body("s", "solid_sphere", 5.0, {"radius": 1.0}, {})])
    >>> lay.kinds, lay.size, lay.offsets, lay.J[1].tolist()
    (('point', 'rigid'), 24, (0, 6), [2.0, 2.0, 2.0])
    >>> y = np.arange(24.0)
    >>> bool(np.array_equal(lay.pack(*lay.gather(y)), y))
    True
    """

    kinds: tuple[str, ...]
    J: FloatArray
    r_fixed: FloatArray
    size: int
    offsets: tuple[int, ...]
    pins: dict[int, Pin] = field(default_factory=dict)
    guides: dict[int, Guide] = field(default_factory=dict)
    bodies: tuple[Body, ...] = ()

    @classmethod
    def of(
        cls,
        bodies: Sequence[BodySpec],
        pins: Mapping[int, tuple[npt.ArrayLike, npt.ArrayLike]] | None = None,
        guides: Mapping[int, Guide] | None = None,
    ) -> Layout:
        """The layout of ``bodies``; ``pins`` maps a body's index to (C, g_A): the space
        point it is pinned at and the vector from that point to G in body components;
        ``guides`` to the :class:`Guide` its joint makes of it (a fixed axis, rolling)."""
        from .bodies import Fixed, Guided, Pinned, Point, Rigid, Tank

        pins, guides = pins or {}, guides or {}
        objs, size = [], 0
        J = np.zeros((len(bodies), 3))
        r_fixed = np.zeros((len(bodies), 3))
        obj: Body
        for i, b in enumerate(bodies):
            if b.fixed:
                r_fixed[i] = b.initial.get("position", [0.0, 0.0, 0.0])
                obj = Fixed(i, size, r_fixed[i])
            elif b.shape == "tank":
                obj = Tank(i, size)
            elif b.shape == "point":
                obj = Point(i, size)
            else:
                J[i] = body_inertia(b)
                if i in pins:
                    C, g = (np.asarray(x, dtype=float) for x in pins[i])
                    JC = np.diag(J[i]) + b.mass * ((g @ g) * np.eye(3) - np.outer(g, g))
                    obj = Pinned(i, size, C, g, JC)
                elif i in guides:
                    obj = Guided(i, size, guides[i])
                else:
                    obj = Rigid(i, size)
            objs.append(obj)
            size += obj.size()
        return cls(
            tuple(o.kind for o in objs),
            J,
            r_fixed,
            size,
            tuple(o.o for o in objs),
            {o.i: o.pin() for o in objs if isinstance(o, Pinned)},
            dict(guides),
            tuple(objs),
        )

    def _get_n(self) -> int:
        return len(self.kinds)

    n = property(_get_n)

    def _index(self) -> _Index:
        """Index arrays into the padded state (state, then the constants block)."""
        cached = cast("_Index | None", self.__dict__.get("_idx"))
        if cached is not None:
            return cached
        n, N = self.n, self.size
        # constants block: 0, 1, then the fixed positions
        zero, one = N, N + 1
        fixed_at = {i: N + 2 + 3 * k for k, i in enumerate(self.fixed_bodies)}
        ir = np.full((n, 3), zero)
        iv = np.full((n, 3), zero)
        iL = np.full((n, 3), zero)
        iR = np.tile(np.where(np.eye(3, dtype=bool), one, zero), (n, 1, 1))
        for b in self.bodies:  # a guided body's r, v, ... are derived by the engine
            b.slots(ir, iv, iL, iR, fixed_at)
        consts = np.concatenate([[0.0, 1.0], self.r_fixed[list(self.fixed_bodies)].ravel()])
        idx = (ir, iv, iL, iR, consts)
        object.__setattr__(self, "_idx", idx)
        return idx

    def _get_fixed_bodies(self) -> tuple[int, ...]:
        return tuple(i for i, k in enumerate(self.kinds) if k == "fixed")

    fixed_bodies = property(_get_fixed_bodies)

    def _get_rigid_bodies(self) -> tuple[int, ...]:
        """The bodies that turn: free rigid bodies, pinned and guided ones."""
        return tuple(b.i for b in self.bodies if b.turns)

    rigid_bodies = property(_get_rigid_bodies)

    def _get_moving_bodies(self) -> tuple[int, ...]:
        """The bodies that move (not fixed ones, nor tanks, whose water level is all)."""
        return tuple(b.i for b in self.bodies if b.moves)

    moving_bodies = property(_get_moving_bodies)

    def _get_tanks(self) -> tuple[int, ...]:
        return tuple(i for i, k in enumerate(self.kinds) if k == "tank")

    tanks = property(_get_tanks)

    def gather(self, y: npt.ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """(r, v, L_A, R_A_O) of every body from states of shape (..., size): shapes
        (..., n, 3), (..., n, 3), (..., n, 3), (..., n, 3, 3); fixed bodies and points
        get their constants (rest, zero spin, identity attitude)."""
        ir, iv, iL, iR, consts = self._index()
        y = np.asarray(y, dtype=float)
        yp = np.concatenate([y, np.broadcast_to(consts, (*y.shape[:-1], consts.size))], -1)
        return yp[..., ir], yp[..., iv], yp[..., iL], yp[..., iR]

    def pack(
        self, r: npt.ArrayLike, v: npt.ArrayLike, L_A: npt.ArrayLike, R_A_O: npt.ArrayLike
    ) -> FloatArray:
        """The flat state(s) (..., size) from per-body arrays (..., n, 3) and (..., n, 3, 3)
        (the inverse of :meth:`gather` on the moving bodies; a pinned body's row of
        ``L_A`` must hold its L_C)."""
        ir, iv, iL, iR, _ = self._index()
        r = np.asarray(r, dtype=float)
        lead = r.shape[:-2]
        y = np.empty((*lead, self.size))
        mov = [i for i, k in enumerate(self.kinds) if k in ("point", "rigid")]
        rig = [i for i, k in enumerate(self.kinds) if k in ("rigid", "pinned")]
        # (for a pinned body the caller gives L_C as L_A; a guided one: Forward.pack)
        y[..., ir[mov].ravel()] = r[..., mov, :].reshape(*lead, -1)
        y[..., iv[mov].ravel()] = np.asarray(v, dtype=float)[..., mov, :].reshape(*lead, -1)
        if rig:
            L_A, R_A_O = np.asarray(L_A, dtype=float), np.asarray(R_A_O, dtype=float)
            y[..., iL[rig].ravel()] = L_A[..., rig, :].reshape(*lead, -1)
            y[..., iR[rig].ravel()] = R_A_O[..., rig, :, :].reshape(*lead, -1)
        return y

    def omega(self, L_A: FloatArray, J: FloatArray) -> FloatArray:
        """Body components ω_A = L_A / J (0 on a zero moment), any leading shape."""
        safe = np.where(J > 0, J, 1.0)
        return np.where(J > 0, L_A / safe, 0.0)

    def derivative(
        self,
        s: Snapshot,
        F: FloatArray,
        M_A: FloatArray,
        rates: dict[int, FloatArray] | None = None,
    ) -> FloatArray:
        """dy/dt for one snapshot ``s`` (its v, L_A, R_A_O, ω_A, masses), forces F (n, 3)
        in O at G and moments M_A (n, 3) about G in body components (see the
        Conventions), each body's slice by its kind (:mod:`.bodies`); a tank's state
        changes at ``rates[i]``."""
        out = np.empty(self.size)
        for b in self.bodies:
            b.rate(s, F, M_A, rates, out)
        return out
