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
    """A body of the layout: its index ``i`` and where its slice starts (``o``)."""

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
    """Pinned at the space point C, G at g_A from it (body components); J_C its inertia
    about C (body components) and J_C⁻¹."""

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
    """Its joint's :class:`~mechanics.scenes.state.Guide` ``gd``: the state is (q, q̇)."""

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
