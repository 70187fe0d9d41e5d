"""The forward dynamics of a model: the bodies seen in a state, the loads on them, the
state's rate, and the accelerations and reactions that follow.

- :meth:`Forward.snapshot` reads a flat state (or many) as a
  :class:`~mechanics.scenes.effects.base.Snapshot`: a pinned body's G and velocity from
  its attitude about the pivot, a guided body's from its joint's coordinates, a tank's
  fluid; :meth:`Forward.pack` writes one back.
- :meth:`Forward.rhs` sums the listed effects' loads (nothing else: no default gravity,
  no damping) and returns the state's rate (:meth:`~mechanics.scenes.state.Layout.derivative`):
  compiled where the model compiles (:mod:`.compiled`), else :meth:`Forward.reference_rhs`,
  the Python path and the reference.
- :meth:`Forward.point_accelerations` gives a body point's acceleration,
  a_G + α × ρ + ω × (ω × ρ); :meth:`Forward.reactions` the joints' reactions
  F = m a_G − Σ F (4.4, 4.71) and a fixed axis's bearing moment.

The one thing that changes during a run is :attr:`Forward.phase`: the middle of the
segment between two switch times being integrated, which a load that switches on or off
there reads (see :class:`~mechanics.scenes.effects.base.Snapshot`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, TypeAlias, cast

import numpy as np
import numpy.typing as npt

from . import compiled
from .bodies import Kinematics
from .compiled import CompiledRhs, CompiledStepper
from .effects import Loads, Snapshot
from .state import Hinge
from .vectors import FloatArray, Times, cross

if TYPE_CHECKING:  # for annotations only
    from mechanics.integrators import DOP853Stepper

    from .effects import Effect
    from .effects.capabilities import HasModes
    from .effects.impact import Feature, Impact
    from .model import Model
    from .support import Support

#: a joint's reactions at the samples (joint -> name -> (k, 3)), and their terms' sizes
Reactions: TypeAlias = tuple[dict[int, dict[str, FloatArray]], dict[int, dict[str, float]]]

__all__ = ["Forward"]

#: why the Python path runs after numba failed to compile the scene kernel
FAILED = "numba failed to compile the scene kernel (see the CompiledPathWarning)"


class Forward:
    """The forward dynamics of a :class:`~mechanics.scenes.model.Model`.

    Its constructor only stores the model (the compiled right-hand side is built on the
    first call of :meth:`rhs`).

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`).

    Examples
    --------
    The state's rate holds v̇ = F/m: a point of 2 kg under g = 2 m/s² (F = −4 N along z):

    >>> from mechanics.scenes.model import Model
    >>> from mechanics.scenes.spec import parse_scene
    >>> md = Model(parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...     "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}],
    ...     "effects": [{"type": "gravity", "g": 2.0}]}))
    >>> fwd = Forward(md)
    >>> F, M_A = fwd.loads(0.0, fwd.snapshot(0.0, md.y0))
    >>> (F / md.m0[:, None]).tolist(), fwd.reference_rhs(0.0, md.y0).tolist()
    ([[0.0, 0.0, -2.0]], [0.0, 0.0, 0.0, 0.0, 0.0, -2.0])
    """

    def __init__(self, model: Model) -> None:
        self.model = model
        self.layout = model.layout
        #: the loads' phase (see the module's docstring); None outside an integration
        self.phase: float | None = None
        #: the resting contacts (:class:`~mechanics.scenes.support.Support`), whose
        #: forces follow the other loads; None: no impacts, nothing can rest (support is
        #: a layer above this module, which imports it for annotations only)
        self.support: Support | None = None
        #: the compiled right-hand side (:mod:`.compiled`), built on the first call of
        #: :meth:`rhs`; a string: why the Python path runs
        self.compiled: CompiledRhs | str | None = None

    # ---------------------------------------------------------------- the state
    def masses(self, t: Times) -> FloatArray:
        m = np.broadcast_to(self.model.m0, (*np.shape(t), self.model.n)).copy()
        for e in self.model.losing:
            m -= e.mass_loss(t)
        return m

    def snapshot(self, t: Times, y: npt.ArrayLike, *, copy: bool = True) -> Snapshot:
        """The bodies at time(s) t from state(s) y (writable copies unless ``copy`` is
        False: the right-hand side only reads them)."""
        md, lay = self.model, self.layout
        r, v, L, R = lay.gather(y)
        if copy:
            r, v, L, R = (np.array(a) for a in (r, v, L, R))
        if md.losing:
            m = self.masses(t)
            J = lay.J * (m / md.m0)[..., None]
        elif np.ndim(t) == 0 and not copy:  # the right-hand side: the shared constants
            m, J = md.m0, lay.J
        else:
            m = np.broadcast_to(md.m0, (*np.shape(t), md.n)).copy()
            J = np.broadcast_to(lay.J, (*np.shape(t), md.n, 3)).copy()
        tanks = lay.tanks
        if not lay.pins and not lay.guides and not tanks:
            return Snapshot(t, r, v, L, R, lay.omega(L, J), m, J)
        if not copy:
            r, v, L, R = r.copy(), v.copy(), L.copy(), R.copy()
        w = lay.omega(L, J)
        angle = np.zeros(np.shape(m))
        y = np.asarray(y, dtype=float)
        coords: dict[int, tuple[FloatArray, FloatArray]] = {}
        inertia: dict[int, FloatArray] = {}
        for i, gd in lay.guides.items():
            o, nq = lay.offsets[i], gd.nq
            q, qd = y[..., o : o + nq].copy(), y[..., o + nq : o + 2 * nq].copy()
            G, E, Ri = gd.place(q)
            angle[..., i] = q[..., 0]
            R[..., i, :, :] = Ri
            r[..., i, :] = G
            v[..., i, :] = np.einsum("...k,...kc->...c", qd, E)
            w[..., i, :] = np.einsum("...ij,...j->...i", Ri, qd @ gd.W)
            L[..., i, :] = J[..., i, :] * w[..., i, :]
            coords[i] = (q, qd)
            grown = [e.inertia_added(t, i) for e in md.growing]
            if grown:
                inertia[i] = gd.M + sum(grown)
        for i, (pivot, g, _, JCinv) in lay.pins.items():
            # the stored L_C gives ω; G and its velocity follow from the attitude
            w[..., i, :] = np.einsum("ij,...j->...i", JCinv, L[..., i, :])
            L[..., i, :] = J[..., i, :] * w[..., i, :]  # about G, as for every body
            rho = np.einsum("...ji,j->...i", R[..., i, :, :], g)  # r_G − C, space
            w_O = np.einsum("...ji,...j->...i", R[..., i, :, :], w[..., i, :])
            r[..., i, :] = pivot + rho
            v[..., i, :] = cross(w_O, rho)
        out = Snapshot(t, r, v, L, R, w, m, J, angle=angle)
        out.coords, out.inertia = coords, inertia
        for i in tanks:
            o = lay.offsets[i]
            out.fluid[i] = y[..., o : o + 2].copy()
        return out

    def pack(self, s: Snapshot) -> FloatArray:
        """The flat state of a snapshot (the inverse of :meth:`snapshot`)."""
        lay = self.layout
        L = s.L_A
        if lay.pins:
            L = np.array(L)
            for i, (_, _, JC, _) in lay.pins.items():
                L[..., i, :] = np.einsum("ij,...j->...i", JC, s.omega[..., i, :])
        y = lay.pack(s.r, s.v, L, s.R)
        for i, gd in lay.guides.items():
            o, (q, qd) = lay.offsets[i], s.coords[i]
            y[..., o : o + gd.nq], y[..., o + gd.nq : o + 2 * gd.nq] = q, qd
        for i, w in s.fluid.items():
            o = lay.offsets[i]
            y[..., o : o + 2] = w
        return y

    # ---------------------------------------------------------------- the loads
    def loads(self, t: float, s: Snapshot) -> tuple[FloatArray, FloatArray]:
        """The listed effects' forces F (n, 3) at G and moments M_A (n, 3) about G (body
        components) on the snapshot s, the resting contacts' support included."""
        out = self.loads_without_support(t, s)
        if self.support is not None and self.support.rests:
            self.support.add(t, s, out)
        return out.F, out.M_A

    def loads_without_support(self, t: float, s: Snapshot) -> Loads:
        """The listed effects' loads on the snapshot s (what the supports hold against)."""
        out = Loads(self.model.n, s)
        for e in self.model.forces:
            e.loads(t, s, out)
        return out

    def loads_before(self, t: float, s: Snapshot, effect: Effect | HasModes) -> Loads:
        """The loads of the effects summed before ``effect`` (all the others, for one
        that comes after the loads)."""
        out = Loads(self.model.n, s)
        for e in self.model.forces:
            if e is effect:
                break
            e.loads(t, s, out)
        return out

    def rhs(self, t: float, y: FloatArray) -> FloatArray:
        """The state's rate at (t, y): compiled where the model compiles, except while a
        body rests on a plane (its support force is the Python path's)."""
        fast = self._compiled()
        if fast is not None:
            dy = fast(t, t if self.phase is None else self.phase, y)
            if dy is not None:
                return dy
            self.compiled = FAILED
        return self.reference_rhs(t, y)

    def _compiled(self) -> CompiledRhs | None:
        """The compiled right-hand side where it runs now (built on the first call);
        None: the Python path (the model does not compile, or a body rests)."""
        if self.compiled is None:
            self.compiled = compiled.build(self.model)
        if not isinstance(self.compiled, str) and self.compiled.broken:
            self.compiled = FAILED
        if isinstance(self.compiled, str) or (self.support is not None and self.support.rests):
            return None
        return self.compiled

    def path(self) -> str:
        """Which right-hand side ran: compiled, or Python and why (a run's ``how``)."""
        if self.compiled is None:
            self.compiled = compiled.build(self.model)
        if isinstance(self.compiled, str):
            return f"right-hand side in Python ({self.compiled})"
        return "right-hand side compiled (numba: mechanics.scenes._kernels)"

    def stepper(
        self, t: float, y: FloatArray, t_bound: float, rtol: float, atol: float
    ) -> CompiledStepper | DOP853Stepper:
        """The DOP853 stepper of the segment from (t, y) to ``t_bound`` (the phase and
        the resting contacts fixed for its life): its steps compiled where the model
        compiles (:class:`.compiled.CompiledStepper`), else
        :class:`mechanics.integrators.DOP853Stepper` on :meth:`rhs`."""
        from mechanics.integrators import DOP853Stepper

        def reference(t0: float, y0: FloatArray, first_step: float | None) -> DOP853Stepper:
            return DOP853Stepper(
                self.rhs, t0, y0, t_bound, rtol=rtol, atol=atol, first_step=first_step
            )

        fast = self._compiled()
        if fast is None:
            return reference(t, y, None)
        phase = t if self.phase is None else self.phase
        return compiled.stepper(fast, phase, t, y, t_bound, rtol, atol, reference)

    def reference_rhs(self, t: float, y: FloatArray) -> FloatArray:
        """The state's rate at (t, y), in Python: the reference of the compiled path."""
        s = self.snapshot(t, y, copy=False)
        if self.phase is not None:
            s.phase = self.phase
        out = Loads(self.model.n, s)
        for e in self.model.forces:
            e.loads(t, s, out)
        if self.support is not None and self.support.rests:
            self.support.add(t, s, out)
        return self.layout.derivative(s, out.F, out.M_A, out.rates)

    # ------------------------------------------------------------ accelerations
    def kinematics(self, s: Snapshot, dy: FloatArray, k: int) -> Kinematics:
        """(origin, its acceleration, ω, α), space components, of body k at the snapshot
        s whose state rates are dy: the origin is G (a pinned body's pivot, which does
        not move); a point has no ω, α (:meth:`.bodies.Body.kinematics`)."""
        _, dv, dL, _ = self.layout.gather(dy)  # raw rates: v̇, and L̇_A (L̇_C if pinned)
        return self.layout.bodies[k].kinematics(s, dy, dv[k], dL[k])

    def point_accelerations(
        self,
        t: float,
        y: FloatArray,
        s: Snapshot,
        points: Mapping[int, FloatArray],
        sizes: dict[int, float] | None = None,
    ) -> dict[int, FloatArray]:
        """Accelerations (space) of the body points ``{body: position}`` at (t, y):
        a_G + α × ρ + ω × (ω × ρ), ρ from G (from the pivot of a pinned body, whose
        pivot does not move); with a dict ``sizes``, each one's terms' size
        |a_G| + |α| |ρ| + |ω|² |ρ| (what its rounding is relative to) goes there."""
        dy = self.rhs(t, y)
        out: dict[int, FloatArray] = {}
        for k, S in points.items():
            if k is None or not self.layout.bodies[k].moves:  # a fixed body
                continue
            origin, base, w, alpha = self.kinematics(s, dy, k)
            rho = S - origin
            out[k] = base + cross(alpha, rho) + cross(w, cross(w, rho))
            if sizes is not None:
                arm = float(np.linalg.norm(rho))
                sizes[k] = float(np.linalg.norm(base) + (np.linalg.norm(alpha) + w @ w) * arm)
        return out

    def rim_gap_acceleration(
        self, t: float, y: FloatArray, s: Snapshot, imp: Impact, ft: Feature
    ) -> float | None:
        """d²/dt² of a rim circle's gap w − a ρ (see :mod:`.effects.impact`) at (t, y),
        or None where the face is flat (ρ = 0).  With c = n·e3 (e3 the circle's axis in
        space, ė3 = ω × e3, ë3 = α × e3 + ω × (ω × e3)): w = (r_G − p)·n + z_c c and
        ρ = √(1 − c²), so w'' = a_G·n + z_c c̈ and ρ'' = −(ċ² + c c̈)/ρ − c² ċ²/ρ³.  The
        support point slides round the rim as the body turns, so this is not the
        acceleration of the material point there."""
        # (a rim circle: its support is set)
        k, (a, zc), n = ft.body, cast("tuple[float, float]", ft.support), imp.normal
        origin, base, w, alpha = self.kinematics(s, self.rhs(t, y), k)
        rho_G = s.r[k] - origin
        a_G = base + cross(alpha, rho_G) + cross(w, cross(w, rho_G))
        e3 = s.R[k, 2]
        c = float(n @ e3)
        rho = math.sqrt(max(1.0 - c * c, 0.0))
        if rho == 0.0:
            return None
        c1 = float(n @ cross(w, e3))
        c2 = float(n @ (cross(alpha, e3) + cross(w, cross(w, e3))))
        rho2 = -(c1 * c1 + c * c2) / rho - c * c * c1 * c1 / rho**3
        return float(a_G @ n) + zc * c2 - a * rho2

    def _compiled_accelerations(
        self, t: FloatArray, Y: FloatArray
    ) -> tuple[FloatArray, FloatArray] | None:
        """The compiled (a_G, F) at the samples, or None where the Python path runs."""
        fast = self._compiled()
        got = None if fast is None else fast.accelerations(t, Y)
        if fast is not None and got is None:
            self.compiled = FAILED
        return got

    def reactions(self, t: FloatArray, Y: FloatArray) -> Reactions:
        """The joints' reactions at the samples (t, Y): the force of a pivot, of the
        bearings or of the surface a body rolls or slides on, F = m a_G − Σ F (4.4,
        4.71), and for a fixed axis the bearings' moment about C, M = J_a φ̈ a − M_C,
        perpendicular to the axis; with the size of their terms (what their rounding is
        relative to).  None where mass flows onto a body (the inflow's momentum is not
        among the loads)."""
        md, lay = self.model, self.layout
        joints = [] if md.growing else [*lay.pins, *lay.guides]
        hinges = {i: g for i, g in lay.guides.items() if isinstance(g, Hinge)}
        out = {i: {"reaction": np.empty((len(t), 3))} for i in joints}
        size = {i: {"reaction": 0.0} for i in joints}
        for i in hinges if joints else ():
            out[i]["bearing_moment"] = np.empty((len(t), 3))
            size[i]["bearing_moment"] = 0.0
        if not out:
            return out, size
        fast = self._compiled_accelerations(t, Y) if not lay.guides else None
        if fast is not None:  # only pins: their reactions from the kernel's a_G and F
            A, F = fast
            for i in out:
                ma = md.m0[i] * A[:, i]
                out[i]["reaction"] = ma - F[:, i]
                terms = np.linalg.norm(ma, axis=-1) + np.linalg.norm(F[:, i], axis=-1)
                size[i]["reaction"] = float(terms.max(initial=0.0))
            return out, size
        for k, (tt, y) in enumerate(zip(t, Y, strict=True)):
            s = self.snapshot(float(tt), y)
            loads = Loads(md.n, s)
            for e in md.forces:
                e.loads(float(tt), s, loads)
            acc = self.point_accelerations(float(tt), y, s, {i: s.r[i] for i in out})
            for i in out:
                out[i]["reaction"][k] = s.m[i] * acc[i] - loads.F[i]
                size[i]["reaction"] = max(
                    size[i]["reaction"],
                    float(np.linalg.norm(s.m[i] * acc[i]) + np.linalg.norm(loads.F[i])),
                )
            for i, hg in hinges.items():
                M_C = hg.moment(s.R[i], s.r[i], loads.F[i], loads.M_A[i])
                phidd = float(hg.a @ M_C) / hg.J_a
                out[i]["bearing_moment"][k] = hg.J_a * phidd * hg.a - M_C
                size[i]["bearing_moment"] = max(
                    size[i]["bearing_moment"], 2.0 * float(np.linalg.norm(M_C))
                )
        return out, size
