"""One class per kind of body: its slice of the flat state, its rate, its kinematics, and
the path of its points along a step.

The kinds (see :mod:`.state` for the state's conventions):

- :class:`Point`: (r, v) of G;
- :class:`Rigid`: (r, v, L_A, R_A_O), Euler's equations and Ṙ = −[ω]× R;
- :class:`Pinned`: (L_C, R_A_O) about its fixed pivot C (a ``fixed_point`` joint);
- :class:`Guided`: its joint's coordinates (q, q̇) (a fixed axis, rolling, sliding);
- :class:`Tank`: (√h, the volume run out), moved by its outflow's rates;
- :class:`Fixed`: nothing; it stays where it is.

:class:`~mechanics.scenes.state.Layout` holds one object per body and gathers the
per-body arrays by index (no loop over bodies); the right-hand side, the accelerations of
body points and the contact search ask each body's object for what depends on its kind.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar, TypeAlias, cast

import numpy as np

from .vectors import FloatArray, IntArray, cross

if TYPE_CHECKING:  # for annotations only: these are layers above
    from .collision import Collision, StepFit
    from .effects import Snapshot
    from .state import Guide

#: (origin, its acceleration, ω, α) of a body, space components
Kinematics: TypeAlias = tuple[FloatArray, FloatArray, FloatArray, FloatArray]

__all__ = ["KINDS", "Body", "Fixed", "Guided", "Pinned", "Point", "Rigid", "Tank"]

ZERO = np.zeros(3)


class Body:
    """A body of the layout: its index ``i`` and where its slice starts (``o``).

    The base of the kinds: each kind overrides what it has (its :meth:`size`, its
    :meth:`rate`, its :meth:`kinematics`, the paths of its points along a step).

    Parameters
    ----------
    i : int
        The body's index in the scene (≥ 0).
    o : int
        The offset of its slice in the flat state (≥ 0).

    Raises
    ------
    NotImplementedError
        From ``size``, ``kinematics``, ``point_coef`` and ``frame_coef``
        where a kind does not override them (the constructor checks nothing).

    Examples
    --------
    >>> b = Body(1, 6)
    >>> b.i, b.o, b.moves, b.turns
    (1, 6, True, False)
    >>> b.size()
    Traceback (most recent call last):
    ...
    NotImplementedError
    """

    kind: ClassVar[str] = ""
    #: does it move (not fixed, not a tank whose water level is all)?
    moves: ClassVar[bool] = True
    #: does it turn (a rigid, pinned or guided body)?
    turns: ClassVar[bool] = False

    def __init__(self, i: int, o: int) -> None:
        self.i, self.o = i, o

    def size(self) -> int:
        """The numbers it carries in the flat state."""
        raise NotImplementedError

    def slots(
        self, ir: IntArray, iv: IntArray, iL: IntArray, iR: IntArray, fixed_at: dict[int, int]
    ) -> None:
        """Point its rows of the index arrays (r, v, L, R) at its slice of the state
        (rows left alone read the constants: zero, the identity)."""

    def rate(
        self,
        s: Snapshot,
        F: FloatArray,
        M_A: FloatArray,
        rates: dict[int, FloatArray] | None,
        out: FloatArray,
    ) -> None:
        """Write its slice of dy/dt into ``out`` for the snapshot s, the force F (space,
        at G) and moment M_A (body components, about G) on it, and ``rates`` (a tank's)."""

    def kinematics(self, s: Snapshot, dy: FloatArray, dv: FloatArray, dL: FloatArray) -> Kinematics:
        """(origin, its acceleration, ω, α), space components, at the snapshot s with
        state rates dy (dv, dL: its gathered rows)."""
        raise NotImplementedError

    def point_coef(self, collision: Collision, fit: StepFit, at: FloatArray | None) -> FloatArray:
        """Chebyshev coefficients (K, 3) of its point ``at`` (body components about G;
        None: G) along the step ``fit``."""
        raise NotImplementedError

    def frame_coef(self, collision: Collision, fit: StepFit) -> tuple[FloatArray, FloatArray]:
        """Chebyshev coefficients of its centre (K, 3) and R_A_O (K, 3, 3) along the step."""
        raise NotImplementedError


class Fixed(Body):
    """A fixed body: nothing in the state; its centre stays at ``r``.

    Parameters
    ----------
    i : int
        The body's index in the scene (≥ 0).
    o : int
        The offset of its (empty) slice in the flat state (≥ 0).
    r : ndarray, shape (3,)
        Its centre, m (space components).

    Raises
    ------
    NotImplementedError
        From ``kinematics`` and ``frame_coef``: a fixed body is asked for
        neither (the constructor checks nothing).

    Examples
    --------
    The path of a point 0.5 m above its centre along a step is a constant, r + at:

    >>> from mechanics.scenes.collision import StepFit
    >>> fit = StepFit(lambda t: np.stack([np.asarray(t)]), 0.0, 1.0)
    >>> c = Fixed(0, 0, np.array([1.0, 2.0, 3.0])).point_coef(None, fit, np.array([0, 0, 0.5]))
    >>> c[0].tolist(), bool(np.all(c[1:] == 0.0))
    ([1.0, 2.0, 3.5], True)
    """

    kind = "fixed"
    moves = False

    def __init__(self, i: int, o: int, r: FloatArray) -> None:
        super().__init__(i, o)
        self.r = r

    def size(self) -> int:
        return 0

    def slots(
        self, ir: IntArray, iv: IntArray, iL: IntArray, iR: IntArray, fixed_at: dict[int, int]
    ) -> None:
        ir[self.i] = fixed_at[self.i] + np.arange(3)

    def point_coef(self, collision: Collision, fit: StepFit, at: FloatArray | None) -> FloatArray:
        c = np.zeros((fit.coef.shape[0], 3))
        c[0] = self.r + (at if at is not None else 0.0)
        return c


class Tank(Body):
    """A tank: its state is (√h, the volume run out), moved at the rates its outflow gives.

    Parameters
    ----------
    i : int
        The body's index in the scene (≥ 0).
    o : int
        The offset of its slice in the flat state (≥ 0).

    Raises
    ------
    AssertionError
        From :meth:`rate` without ``rates`` (a tank's state changes at the rates its
        loads give).
    NotImplementedError
        From ``kinematics``, ``point_coef`` and ``frame_coef``: a tank does not
        move (the constructor checks nothing).

    Examples
    --------
    Its slice of dy/dt is the rates its outflow gives it:

    >>> tank, out = Tank(0, 0), np.zeros(2)
    >>> tank.rate(None, None, None, {0: np.array([-0.5, 0.25])}, out)
    >>> out.tolist(), tank.size() == Tank.SIZE == 2
    ([-0.5, 0.25], True)
    """

    kind = "tank"
    moves = False
    #: √h (its water level's square root) and the volume run out
    SIZE = 2

    def size(self) -> int:
        return self.SIZE

    def rate(
        self,
        s: Snapshot,
        F: FloatArray,
        M_A: FloatArray,
        rates: dict[int, FloatArray] | None,
        out: FloatArray,
    ) -> None:
        assert rates is not None, "a tank's state changes at the rates its loads give"
        out[self.o : self.o + self.SIZE] = rates[self.i]


class Point(Body):
    """A point mass: its state is (r, v) of G, and v̇ = F/m.

    Parameters
    ----------
    i : int
        The body's index in the scene (≥ 0).
    o : int
        The offset of its slice in the flat state (≥ 0).

    Raises
    ------
    NotImplementedError
        From ``frame_coef``: a point has no attitude (the constructor checks
        nothing).

    Examples
    --------
    Its rate is (v, F/m): 19.62 N down on 2 kg gives 9.81 m/s² down:

    >>> from types import SimpleNamespace
    >>> s = SimpleNamespace(v=np.array([[1.0, 0.0, 0.0]]), m=np.array([2.0]))
    >>> out = np.zeros(Point.SIZE)
    >>> Point(0, 0).rate(s, np.array([[0.0, 0.0, -19.62]]), np.zeros((1, 3)), None, out)
    >>> out.tolist()
    [1.0, 0.0, 0.0, 0.0, 0.0, -9.81]
    """

    kind = "point"
    SIZE = 6

    def size(self) -> int:
        return self.SIZE

    def slots(
        self, ir: IntArray, iv: IntArray, iL: IntArray, iR: IntArray, fixed_at: dict[int, int]
    ) -> None:
        ir[self.i] = self.o + np.arange(3)
        iv[self.i] = self.o + 3 + np.arange(3)

    def rate(
        self,
        s: Snapshot,
        F: FloatArray,
        M_A: FloatArray,
        rates: dict[int, FloatArray] | None,
        out: FloatArray,
    ) -> None:
        o, i = self.o, self.i
        out[o : o + 3] = s.v[i]
        out[o + 3 : o + 6] = F[i] / s.m[i]

    def kinematics(self, s: Snapshot, dy: FloatArray, dv: FloatArray, dL: FloatArray) -> Kinematics:
        return s.r[self.i], dv, ZERO, ZERO

    def point_coef(self, collision: Collision, fit: StepFit, at: FloatArray | None) -> FloatArray:
        return fit.coef[:, self.o : self.o + 3].copy()


class Rigid(Point):
    """A free rigid body: its state is (r, v, L_A, R_A_O), Euler's equations and Ṙ = −[ω]× R.

    L_A and ω are body components about G; L̇_A = L_A × ω + M_A.

    Parameters
    ----------
    i : int
        The body's index in the scene (≥ 0).
    o : int
        The offset of its slice in the flat state (≥ 0).

    Examples
    --------
    Spinning at 2 rad/s about a principal axis with no moment, L stays put and R turns
    at Ṙ = −[ω]× R:

    >>> from types import SimpleNamespace
    >>> w = np.array([0.0, 0.0, 2.0])
    >>> s = SimpleNamespace(v=np.zeros((1, 3)), m=np.ones(1), omega=w[None],
    ...                     L_A=(3.0 * w)[None], R=np.eye(3)[None])
    >>> out = np.zeros(Rigid.SIZE)
    >>> Rigid(0, 0).rate(s, np.zeros((1, 3)), np.zeros((1, 3)), None, out)
    >>> out[6:9].tolist()
    [0.0, 0.0, 0.0]
    >>> wx = np.array([[0.0, -2.0, 0.0], [2.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    >>> bool(np.array_equal(out[9:].reshape(3, 3), -wx @ np.eye(3)))
    True
    """

    kind = "rigid"
    turns = True
    SIZE = 18

    def slots(
        self, ir: IntArray, iv: IntArray, iL: IntArray, iR: IntArray, fixed_at: dict[int, int]
    ) -> None:
        super().slots(ir, iv, iL, iR, fixed_at)
        iL[self.i] = self.o + 6 + np.arange(3)
        iR[self.i] = (self.o + 9 + np.arange(9)).reshape(3, 3)

    def rate(
        self,
        s: Snapshot,
        F: FloatArray,
        M_A: FloatArray,
        rates: dict[int, FloatArray] | None,
        out: FloatArray,
    ) -> None:
        o, i = self.o, self.i
        out[o : o + 3] = s.v[i]
        out[o + 3 : o + 6] = F[i] / s.m[i]
        wi, Li, Mi = s.omega[i], s.L_A[i], M_A[i]
        # L̇_A = L_A × ω_A + M_A, written out (np.cross costs more than the sums)
        out[o + 6] = Li[1] * wi[2] - Li[2] * wi[1] + Mi[0]
        out[o + 7] = Li[2] * wi[0] - Li[0] * wi[2] + Mi[1]
        out[o + 8] = Li[0] * wi[1] - Li[1] * wi[0] + Mi[2]
        # Ṙ = −[ω]× R: row k of Ṙ is −(ω × column)ᵀ, i.e. Ṙ[a] = R[a+1] w[a+2] − ...
        Ri = s.R[i]
        out[o + 9 : o + 12] = wi[2] * Ri[1] - wi[1] * Ri[2]
        out[o + 12 : o + 15] = wi[0] * Ri[2] - wi[2] * Ri[0]
        out[o + 15 : o + 18] = wi[1] * Ri[0] - wi[0] * Ri[1]

    def kinematics(self, s: Snapshot, dy: FloatArray, dv: FloatArray, dL: FloatArray) -> Kinematics:
        k = self.i
        safe = np.where(s.J[k] > 0, s.J[k], 1.0)
        wdot = np.where(s.J[k] > 0, dL / safe, 0.0)
        return s.r[k], dv, s.to_space(k, s.omega[k]), s.to_space(k, wdot)

    def point_coef(self, collision: Collision, fit: StepFit, at: FloatArray | None) -> FloatArray:
        c = super().point_coef(collision, fit, at)
        if at is not None:
            R = fit.coef[:, self.o + 9 : self.o + 18].reshape(-1, 3, 3)
            c += np.einsum("kic,i->kc", R, at)
        return c

    def frame_coef(self, collision: Collision, fit: StepFit) -> tuple[FloatArray, FloatArray]:
        o = self.o
        return fit.coef[:, o : o + 3], fit.coef[:, o + 9 : o + 18].reshape(-1, 3, 3)


class Pinned(Body):
    """A body pinned at a fixed point C: its state is (L_C, R_A_O) about the pivot.

    G lies at g_A from C (body components); J_C is its inertia about C (body components),
    J_C⁻¹ worked out once.

    Parameters
    ----------
    i : int
        The body's index in the scene (≥ 0).
    o : int
        The offset of its slice in the flat state (≥ 0).
    C : ndarray, shape (3,)
        The pivot, m (space components).
    g : ndarray, shape (3,)
        g_A: G from the pivot, m (body components).
    JC : ndarray, shape (3, 3)
        J_C: the inertia about the pivot, kg m² (body components; invertible).

    Raises
    ------
    ValueError
        numpy's ``LinAlgError`` (a ValueError) if ``JC`` is singular.

    Examples
    --------
    A pivot 0.1 m from G along the symmetry axis of a top with J_C = diag(2, 2, 1):

    >>> top = Pinned(0, 0, np.zeros(3), np.array([0.0, 0.0, 0.1]), np.diag([2.0, 2.0, 1.0]))
    >>> C, g, JC, JCinv = top.pin()
    >>> (JCinv @ JC).tolist() == np.eye(3).tolist(), top.size()
    (True, 12)
    """

    kind = "pinned"
    turns = True
    SIZE = 12

    def __init__(self, i: int, o: int, C: FloatArray, g: FloatArray, JC: FloatArray) -> None:
        super().__init__(i, o)
        self.C, self.g, self.JC = C, g, JC
        #: J_C⁻¹ (numpy types inv's result as a float of any precision: float64 here)
        self.JCinv = cast("FloatArray", np.linalg.inv(JC))

    def pin(self) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """(C, g_A, J_C, J_C⁻¹)."""
        return self.C, self.g, self.JC, self.JCinv

    def size(self) -> int:
        return self.SIZE

    def slots(
        self, ir: IntArray, iv: IntArray, iL: IntArray, iR: IntArray, fixed_at: dict[int, int]
    ) -> None:
        # r, v derived (zeros here); L_C and R stored
        iL[self.i] = self.o + np.arange(3)
        iR[self.i] = (self.o + 3 + np.arange(9)).reshape(3, 3)

    def rate(
        self,
        s: Snapshot,
        F: FloatArray,
        M_A: FloatArray,
        rates: dict[int, FloatArray] | None,
        out: FloatArray,
    ) -> None:
        """(L̇_C, Ṙ): L̇_C = L_C × ω + M_C, the moment about the pivot M_C = M_G +
        g_A × (R F) (body components)."""
        i, o = self.i, self.o
        w, Ri = s.omega[i], s.R[i]
        L = self.JC @ w
        M = M_A[i] + cross(self.g, Ri @ F[i])
        out[o : o + 3] = cross(L, w) + M
        out[o + 3 : o + 6] = w[2] * Ri[1] - w[1] * Ri[2]
        out[o + 6 : o + 9] = w[0] * Ri[2] - w[2] * Ri[0]
        out[o + 9 : o + 12] = w[1] * Ri[0] - w[0] * Ri[1]

    def kinematics(self, s: Snapshot, dy: FloatArray, dv: FloatArray, dL: FloatArray) -> Kinematics:
        k = self.i
        wdot = self.JCinv @ dL
        return self.C, ZERO, s.to_space(k, s.omega[k]), s.to_space(k, wdot)

    def point_coef(self, collision: Collision, fit: StepFit, at: FloatArray | None) -> FloatArray:
        R = fit.coef[:, self.o + 3 : self.o + 12].reshape(-1, 3, 3)
        c: FloatArray = np.einsum("kic,i->kc", R, self.g + (at if at is not None else 0.0))
        c[0] += self.C
        return c

    def frame_coef(self, collision: Collision, fit: StepFit) -> tuple[FloatArray, FloatArray]:
        R = fit.coef[:, self.o + 3 : self.o + 12].reshape(-1, 3, 3)
        return self.point_coef(collision, fit, None), R


class Guided(Body):
    """A body on a joint (a fixed axis, rolling, sliding): its state is the joint's (q, q̇).

    Parameters
    ----------
    i : int
        The body's index in the scene (≥ 0).
    o : int
        The offset of its slice in the flat state (≥ 0).
    gd : Guide
        Its joint's :class:`~mechanics.scenes.state.Guide` (``nq`` coordinates q).

    Examples
    --------
    The rod pendulum of Examples 4.3-4.4 turns on a hinge: one angle and its rate:

    >>> from mechanics.scenes import builtin_path, load_scene
    >>> from mechanics.scenes.engine import Engine
    >>> rod = Engine(load_scene(builtin_path("physical_pendulum"))).layout.bodies[0]
    >>> type(rod).__name__, type(rod.gd).__name__, rod.size() == 2 * rod.gd.nq == 2
    ('Guided', 'Hinge', True)
    """

    kind = "guided"
    turns = True

    def __init__(self, i: int, o: int, gd: Guide) -> None:
        super().__init__(i, o)
        self.gd = gd

    def size(self) -> int:
        return 2 * self.gd.nq

    def rate(
        self,
        s: Snapshot,
        F: FloatArray,
        M_A: FloatArray,
        rates: dict[int, FloatArray] | None,
        out: FloatArray,
    ) -> None:
        i, o, gd = self.i, self.o, self.gd
        q, qd = s.coords[i]
        out[o : o + gd.nq] = qd
        out[o + gd.nq : o + 2 * gd.nq] = gd.rate(q, F[i], s.R[i].T @ M_A[i], s.inertia.get(i))

    def kinematics(self, s: Snapshot, dy: FloatArray, dv: FloatArray, dL: FloatArray) -> Kinematics:
        """a_G = Σ E_k q̈_k + the bend; ω = Σ W_k q̇_k, α = Σ W_k q̈_k."""
        gd, o = self.gd, self.o
        q, qd = s.coords[self.i]
        qdd = dy[o + gd.nq : o + 2 * gd.nq]
        _, E, _ = gd.place(q)
        return s.r[self.i], qdd @ E + gd.bend(q, qd), qd @ gd.W, qdd @ gd.W

    def point_coef(self, collision: Collision, fit: StepFit, at: FloatArray | None) -> FloatArray:
        """Fitted at the step's Chebyshev nodes (a hinge's points are trigonometric in
        φ: for a turn of 0.3 rad per step the fit's error is ~(0.15)⁹/9! ≈ 1e-13 of the
        arm; the crossing is refined on the exact gap)."""
        k = self.i
        return collision.fit_snapshots(fit, lambda ss: ss.point(k, at))

    def frame_coef(self, collision: Collision, fit: StepFit) -> tuple[FloatArray, FloatArray]:
        k = self.i
        c = collision.fit_snapshots(
            fit, lambda ss: np.concatenate([ss.r[:, k], ss.R[:, k].reshape(-1, 9)], axis=-1)
        )
        return c[:, :3], c[:, 3:].reshape(-1, 3, 3)


#: every kind, by name
KINDS = {c.kind: c for c in (Point, Rigid, Pinned, Guided, Tank, Fixed)}
