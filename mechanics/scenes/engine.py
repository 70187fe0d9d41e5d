"""The one engine of every scene: it assembles exactly the listed effects, uses the exact
flow where their set has one, integrates otherwise, and finds every contact and switch.

Conventions
-----------
- **State**: :mod:`mechanics.scenes.state` (points, rigid bodies with L_A and ^A R^O,
  pinned bodies with L_C and ^A R^O, guided bodies with the coordinates (q, q̇) of
  their joint's :class:`~mechanics.scenes.state.Guide`, tanks, fixed bodies).  A rigid
  body starts with the attitude ^A R^O = R3(φ) R1(θ) R3(ψ) of its initial Euler angles
  ``psi``, ``theta``, ``phi`` (z-x-z, default 0: the body axes along the space axes)
  and the angular velocity ``omega`` in body components (a pinned body: or the Euler
  rates).
- **Effects**: :mod:`mechanics.scenes.effects`; the right-hand side sums the
  :meth:`~mechanics.scenes.effects.base.Effect.loads` of the listed effects and
  nothing else (no default gravity, no damping, no position correction).
- **Exact flows** (``method = "auto"`` or ``"exact"``): with only uniform gravity and
  impacts of spheres and points (smooth, through the centres): free flight between
  impacts, the impact instants in closed form (a quadratic for a plane; for two
  spheres, whose relative motion is uniform, a quadratic formed without cancellation,
  :func:`contacts.sphere_contact_time`); with only gravity and space-fixed thrust: the
  rocket (7.30); in both, each spinning rigid body turns by the torque-free
  Jacobi-elliptic flow of :class:`mechanics.tops.FreeAsymmetricTop`.  A lone pinned
  body (a top on a ``fixed_point``) with nothing else: the torque-free top about C;
  with gravity along −z, J1 = J2 and 0 < θ0 < π: the heavy symmetric top
  (:class:`mechanics.tops.HeavySymmetricTop`, 5.2).  A lone guided body: its guide's
  (:meth:`~mechanics.scenes.state.Guide.exact`: the pendulum from rest, the torsion
  pendulum, the carousel, rolling, the sliding phases).  A lone tank: Torricelli.
- **Integration** otherwise (or ``method = "integrate"``): the project's adaptive
  Dormand–Prince 8(5,3) stepper (:class:`mechanics.integrators.DOP853Stepper`) at the
  scene's ``rtol``/``atol``.  After every step each contact feature's gap is searched
  along the step's dense polynomial (:func:`contacts.first_downward_crossing`), so a
  contact is found whatever the step size; switch times (burn-out, the window of an
  applied load) are step boundaries.  An effect with modes (stick and slip, a tank that
  empties) has a switch function, searched along each step's dense output like a gap;
  at its zero the effect switches (an event) and the integration restarts; at a step
  boundary where a load switches, a mode beyond its limit switches at once.
- **Contacts**: a contact is a gap reaching zero while closing, resolved by the
  Chapter 6 impulse (:mod:`mechanics.scenes.effects.impact`).  *Simultaneous
  contacts* (a Newton's cradle) are resolved by sequential impulses: after each
  impulse every feature touching within rounding and still closing is resolved in
  turn, the fastest approach first, until none closes (at most ``MAX_SWEEPS`` rounds;
  for a row of equal elastic spheres this passes the momentum down the row).  A touch
  at zero approach speed (up to rounding) is no impact.  A contact found on the exit
  side, a pair interpenetrating at a step's start, or a pair that comes to rest under a
  pressing force (accumulating impacts, or e = 0) stops the run with a
  :class:`~mechanics.scenes.errors.SceneError` naming the pair and the time.
- **Series**: per body (prefixed ``name.`` when there are several) x, y, z, vx, vy, vz
  (space components), mass (with thrust), and for a rigid body omega1..3 (body
  components) and wx, wy, wz (space components); the totals E, and p_*, L_* (about the
  origin) for several bodies or a rigid one.
- **Invariants**: the result names the quantities every listed effect keeps
  (:meth:`~mechanics.scenes.effects.base.Effect.keeps`): the total momentum p_x, p_y,
  p_z, the total angular momentum about the origin L_x, L_y, L_z (orbital r × m v plus
  the spins Rᵀ L_A) and the energy E (kinetic ½ m v² + ½ L_A·ω_A plus the effects'
  potentials), and the spin angular momentum about G of each rigid body no effect
  turns; each with its samples, checked within the segments between impacts, or over
  the whole run where the impulses keep it too.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from numpy.polynomial import chebyshev as C

from mechanics import kinematics as kin
from mechanics.errors import GimbalLockError, OutOfDomainError

from . import budget, contacts
from .effects import REGISTRY, Context, Loads, Snapshot, build_effects
from .effects.base import CONSERVED, Effect, gravity_vector
from .effects.impact import EnergyGainError, Impact
from .errors import SceneError
from .state import Guide, Hinge, Layout, body_vertices
from .trajectory import (
    EPS,
    Event,
    Trajectory,
    dense_from_segments,
    energy_scale,
    sample_segments,
    vectorized,
)

__all__ = ["Engine", "validate"]

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
#: a switch function (stick and slip) within this multiple of eps × the size of its
#: terms at a step's start is zero: the rounding of the switch just made there
SWITCH_ROUNDING = 64 * EPS

FREE_INITIAL = ("position", "velocity", "omega", "psi", "theta", "phi")
#: the effects that hold a body (one per body)
JOINTS = ("fixed_point", "fixed_axis", "rolling", "coulomb_friction")
#: a pinned body may give its initial ω as the Euler angles' rates instead
RATES = ("theta_dot", "psi_dot", "phi_dot")


def _attitude(initial) -> np.ndarray:
    from mechanics.rotation import matrix_from_euler

    e = [float(initial.get(k, 0.0)) for k in ("psi", "theta", "phi")]
    return matrix_from_euler(*e) if any(e) else np.eye(3)


def _omega(initial) -> np.ndarray:
    """Initial body ω: ``omega``, or from the z-x-z Euler rates by Euler's kinematic
    equations (2.69) (:func:`mechanics.kinematics.angular_velocity_from_euler_rates`)."""
    if "omega" in initial:
        return np.asarray(initial["omega"], dtype=float)
    th, ph = float(initial.get("theta", 0.0)), float(initial.get("phi", 0.0))
    thd, psd, phd = (float(initial.get(k, 0.0)) for k in RATES)
    return kin.angular_velocity_from_euler_rates(0.0, th, ph, psd, thd, phd)


def _pins(scene, index) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """The pinned bodies (a fixed_point joint) -> (C, g_A)."""
    from .effects.fixed_point import FixedPoint

    return {
        index[spec.fields["body"]]: FixedPoint(spec).pin()
        for spec in scene.effects_of("fixed_point")
    }


def _guides(scene, index) -> dict[int, Guide]:
    """The guided bodies (a fixed axis, rolling, sliding on a plane) -> their Guide."""
    g = gravity_vector(scene)
    out = {}
    for spec in scene.effects:
        make = REGISTRY[spec.type].make_guide
        if make is not None:
            out[index[spec.fields["body"]]] = make(spec, scene, g)
    return out


def validate(scene) -> None:
    """Check a scene of free bodies as a whole (each field is checked by the parser)."""
    index = {b.name: i for i, b in enumerate(scene.bodies)}
    held: dict[str, object] = {}  # body -> the joint that holds it
    for spec in scene.effects:
        if spec.type not in JOINTS:
            continue
        other = held.setdefault(spec.fields["body"], spec)
        if other is not spec:
            why = (
                f"{spec.type!r} is listed twice for body {spec.fields['body']!r}"
                if other.type == spec.type
                else f"{spec.type!r} cannot be combined with {other.type!r} ({other.where}) "
                f"on body {spec.fields['body']!r}: one joint per body"
            )
            raise scene.error(f"{spec.where}.type", why)
    tanks = {b.name for b in scene.bodies if b.shape == "tank"}
    for spec in scene.effects:
        named = [spec.fields.get(k) for k in ("body", "other")]
        if spec.type != "tank_outflow" and tanks.intersection(named):
            raise scene.error(
                f"{spec.where}.type",
                f"a tank's only effect is its tank_outflow; a {spec.type!r} cannot act on it",
            )
    pinned = _pins(scene, index)
    guided = {index[e.fields["body"]] for e in scene.effects if REGISTRY[e.type].make_guide}
    drained = {e.fields["body"] for e in scene.effects_of("tank_outflow")}
    for i, b in enumerate(scene.bodies):
        where = f"bodies[{i}]"
        if b.shape == "tank":
            if b.name not in drained:
                raise scene.error(f"{where}.shape", "a tank needs a tank_outflow effect")
            continue  # its initial keys: the outflow's check
        if i in guided:
            continue  # its initial keys: its joint's check
        keys = FREE_INITIAL + (RATES if i in pinned else ())
        for k in b.initial:
            if k not in keys:
                raise scene.error(f"{where}.initial.{k}", f"a free body takes {', '.join(keys)}")
        if "omega" in b.initial and any(k in b.initial for k in RATES):
            raise scene.error(f"{where}.initial.omega", "give either omega or the Euler rates")
        w = _omega(b.initial)
        if b.fixed:
            for k in ("velocity", "omega"):
                if any(b.initial.get(k, [0.0])):
                    raise scene.error(f"{where}.initial.{k}", "a fixed body stays at rest")
        elif b.shape == "point":
            if w.any() or any(b.initial.get(k, 0.0) for k in ("psi", "theta", "phi")):
                key = "omega" if w.any() else "psi"
                raise scene.error(
                    f"{where}.initial.{key}", "a point has no attitude and no rotation"
                )
        else:
            from .state import body_inertia

            J = body_inertia(b)
            if np.any((J <= 0) & (w != 0)):
                raise scene.error(
                    f"{where}.initial.omega",
                    f"a {b.shape} has a zero principal moment {J.tolist()}: it cannot spin "
                    f"about that axis; got omega = {w.tolist()}",
                )
    for spec in scene.effects:
        REGISTRY[spec.type].check(spec, scene, index)
    if scene.effects_of("impact"):
        eng = Engine(scene)
        s = eng.snapshot(0.0, eng.y0)
        for imp in eng.impacts:
            for ft in imp.features:
                gap = float(imp.gap(s, ft))
                reach = np.abs(imp.feature_point(s, ft)).sum() + np.abs(imp.point).sum()
                if gap < -GAP_ROUNDING * (reach + ft.a + ft.a_s):  # beyond the rounding
                    raise scene.error(
                        imp.where, f"{ft.label} overlap at t = 0 s (gap {gap:.3g} m < 0)"
                    )


class Engine:
    """A scene, assembled from its listed effects."""

    def __init__(self, scene) -> None:
        self.scene = scene
        index = {b.name: i for i, b in enumerate(scene.bodies)}
        self.layout = Layout.of(scene.bodies, _pins(scene, index), _guides(scene, index))
        self.n = self.layout.n
        self.names = [b.name for b in scene.bodies]
        ctx = Context(scene, index, self.layout.kinds, self.layout.pins, self.layout.guides)
        self.effects = build_effects(scene, ctx)
        self.impacts: list[Impact] = [e for e in self.effects if e.type == "impact"]
        # an effect that reads the others' loads comes after them (a stable sort)
        self.forces = sorted(
            (e for e in self.effects if e.type != "impact"), key=lambda e: e.after_loads
        )
        self.switching = [e for e in self.forces if e.switch_function is not None]
        self.potentials = [e for e in self.forces if e.potential is not None]
        self.losing = [e for e in self.forces if type(e).mass_loss is not Effect.mass_loss]
        self.growing = [e for e in self.forces if hasattr(e, "inertia_added")]
        self.m0 = np.array([b.mass for b in scene.bodies], dtype=float)
        b0 = scene.bodies
        r0 = np.array([b.initial.get("position", [0.0] * 3) for b in b0], float)
        v0 = np.array([b.initial.get("velocity", [0.0] * 3) for b in b0], float)
        w0 = np.array([_omega(b.initial) for b in b0], float)
        R0 = np.array([_attitude(b.initial) for b in b0])
        self.w0, self.R0 = w0, R0
        L0 = self.layout.J * w0
        for i, (_, _, JC, _) in self.layout.pins.items():
            L0[i] = JC @ w0[i]  # a pinned body stores its angular momentum about C
        self.y0 = self.layout.pack(r0, v0, L0, R0)
        for i, gd in self.layout.guides.items():
            o = self.layout.offsets[i]
            self.y0[o : o + 2 * gd.nq] = np.concatenate(gd.start(b0[i].initial))
        self.outflows = [e for e in self.effects if e.type == "tank_outflow"]
        for e in self.outflows:
            o = self.layout.offsets[e.i]
            self.y0[o : o + 2] = e.start()
        self.rigid = self.layout.rigid_bodies
        self._phase: float | None = None  # see Snapshot.phase

    # ---------------------------------------------------------------- the state
    def masses(self, t) -> np.ndarray:
        m = np.broadcast_to(self.m0, (*np.shape(t), self.n)).copy()
        for e in self.losing:
            m -= e.mass_loss(t)
        return m

    def snapshot(self, t, y, *, copy: bool = True) -> Snapshot:
        """The bodies at time(s) t from state(s) y (writable copies unless ``copy`` is
        False: the right-hand side only reads them)."""
        r, v, L, R = self.layout.gather(y)
        if copy:
            r, v, L, R = (np.array(a) for a in (r, v, L, R))
        if self.losing:
            m = self.masses(t)
            J = self.layout.J * (m / self.m0)[..., None]
        elif np.ndim(t) == 0 and not copy:  # the right-hand side: the shared constants
            m, J = self.m0, self.layout.J
        else:
            m = np.broadcast_to(self.m0, (*np.shape(t), self.n)).copy()
            J = np.broadcast_to(self.layout.J, (*np.shape(t), self.n, 3)).copy()
        tanks = self.layout.tanks
        if not self.layout.pins and not self.layout.guides and not tanks:
            return Snapshot(t, r, v, L, R, self.layout.omega(L, J), m, J)
        if not copy:
            r, v, L, R = r.copy(), v.copy(), L.copy(), R.copy()
        w = self.layout.omega(L, J)
        angle = np.zeros(np.shape(m))
        y = np.asarray(y, dtype=float)
        coords, inertia = {}, {}
        for i, gd in self.layout.guides.items():
            o, nq = self.layout.offsets[i], gd.nq
            q, qd = y[..., o : o + nq].copy(), y[..., o + nq : o + 2 * nq].copy()
            G, E, Ri = gd.place(q)
            angle[..., i] = q[..., 0]
            R[..., i, :, :] = Ri
            r[..., i, :] = G
            v[..., i, :] = np.einsum("...k,...kc->...c", qd, E)
            w[..., i, :] = np.einsum("...ij,...j->...i", Ri, qd @ gd.W)
            L[..., i, :] = J[..., i, :] * w[..., i, :]
            coords[i] = (q, qd)
            grown = [e.inertia_added(t, i) for e in self.growing]
            if grown:
                inertia[i] = gd.M + sum(grown)
        for i, (pivot, g, _, JCinv) in self.layout.pins.items():
            # the stored L_C gives ω; G and its velocity follow from the attitude
            w[..., i, :] = np.einsum("ij,...j->...i", JCinv, L[..., i, :])
            L[..., i, :] = J[..., i, :] * w[..., i, :]  # about G, as for every body
            rho = np.einsum("...ji,j->...i", R[..., i, :, :], g)  # r_G − C, space
            w_O = np.einsum("...ji,...j->...i", R[..., i, :, :], w[..., i, :])
            r[..., i, :] = pivot + rho
            v[..., i, :] = np.cross(w_O, rho)
        out = Snapshot(t, r, v, L, R, w, m, J, angle=angle)
        out.coords, out.inertia = coords, inertia
        for i in tanks:
            o = self.layout.offsets[i]
            out.fluid[i] = y[..., o : o + 2].copy()
        return out

    def loads(self, t, s) -> tuple[np.ndarray, np.ndarray]:
        """The listed effects' forces F (n, 3) at G and moments M_A (n, 3) about G (body
        components) on the snapshot s."""
        out = Loads(self.n, s)
        for e in self.forces:
            e.loads(t, s, out)
        return out.F, out.M_A

    def rhs(self, t, y) -> np.ndarray:
        s = self.snapshot(t, y, copy=False)
        if self._phase is not None:
            s.phase = self._phase
        out = Loads(self.n, s)
        for e in self.forces:
            e.loads(t, s, out)
        return self.layout.derivative(s, out.F, out.M_A, out.rates)

    def pack(self, s: Snapshot) -> np.ndarray:
        L = s.L_A
        if self.layout.pins:
            L = np.array(L)
            for i, (_, _, JC, _) in self.layout.pins.items():
                L[..., i, :] = np.einsum("ij,...j->...i", JC, s.omega[..., i, :])
        y = self.layout.pack(s.r, s.v, L, s.R)
        for i, gd in self.layout.guides.items():
            o, (q, qd) = self.layout.offsets[i], s.coords[i]
            y[..., o : o + gd.nq], y[..., o + gd.nq : o + 2 * gd.nq] = q, qd
        for i, w in s.fluid.items():
            o = self.layout.offsets[i]
            y[..., o : o + 2] = w
        return y

    # ------------------------------------------------------------- exact flows
    def exact_flow(self) -> str | None:
        kinds = {e.type for e in self.effects}
        if self.layout.tanks:
            if self.n != 1 or not kinds <= {"gravity", "tank_outflow"}:
                return None
            how, f, self._tank_events = self.outflows[0].exact(self.scene.duration)
            self._tank = vectorized(f)
            return how
        if self.layout.guides:
            return self._guided_exact_flow()
        if self.layout.pins:
            return self._pinned_exact_flow(kinds)
        if self.layout.fixed_bodies:
            return None
        ballistic = kinds <= {"gravity", "impact"} and all(
            ft.at is None and ft.support is None and imp.mu_f == 0
            for imp in self.impacts
            for ft in imp.features
        )
        rocket = kinds <= {"gravity", "thrust"} and not any(
            e.body_frame for e in self.effects if e.type == "thrust"
        )
        if not (ballistic or rocket):
            return None
        for i in self.rigid:  # torque-free rotation by elliptic functions needs J > 0
            if self.w0[i].any() and not np.all(self.layout.J[i] > 0):
                return None
        try:
            self._tops = self._rotation()
        except OutOfDomainError:  # within float64's reach of the separatrix: integrate
            return None
        spin = "; torque-free rotation (Jacobi elliptic functions)" if self._spinning() else ""
        if ballistic:
            what = "free flight under uniform gravity" if "gravity" in kinds else "uniform motion"
            if "impact" in kinds:
                what += ", impacts solved in closed form"
            return f"exact: {what}{spin}"
        return f"exact: rocket flight (7.30) with uniform gravity{spin}"

    def _guided_exact_flow(self) -> str | None:
        """A lone guided body: its guide's exact flow for the listed effects, if any
        (:meth:`~mechanics.scenes.state.Guide.exact`)."""
        if self.n != 1:
            return None
        ((i, gd),) = self.layout.guides.items()
        o = self.layout.offsets[i]
        q0, qd0 = self.y0[o : o + gd.nq].copy(), self.y0[o + gd.nq : o + 2 * gd.nq].copy()
        others = [e for e in self.effects if e.make_guide is None]
        found = gd.exact(others, float(self.m0[i]), q0, qd0, self.scene.duration)
        if found is None:
            return None
        how, self._axis, self._axis_events = found
        return how

    def _guided_exact(self):
        ((i, gd),) = self.layout.guides.items()
        o, f, nq = self.layout.offsets[i], self._axis, gd.nq

        @vectorized
        def at(t):
            tt = np.asarray(t, dtype=float)
            y = np.zeros((*tt.shape, self.layout.size))
            q, qd = f(tt)
            y[..., o : o + nq] = np.broadcast_to(q, (*tt.shape, nq))
            y[..., o + nq : o + 2 * nq] = np.broadcast_to(qd, (*tt.shape, nq))
            return y

        return [(0.0, self.scene.duration, at)], list(self._axis_events)

    def _pinned_exact_flow(self, kinds) -> str | None:
        """A lone top on its fixed point: torque-free (the elliptic flow about C), or the
        heavy symmetric top (J1 = J2 about C, gravity along −z, θ0 in (0, π))."""
        from mechanics.tops import FreeAsymmetricTop, HeavySymmetricTop

        if self.n != 1 or not kinds <= {"fixed_point", "gravity"}:
            return None
        ((i, (_, g, JC, _)),) = self.layout.pins.items()
        Jc = np.diag(JC).copy()  # diagonal: the pivot lies on the principal axis e3
        if kinds == {"fixed_point"}:
            try:
                self._top = ("free", FreeAsymmetricTop(Jc, self.w0[i], self.R0[i]))
            except OutOfDomainError:
                return None
            return "exact: torque-free top about C, Jacobi elliptic functions (5.3)"
        grav = [e for e in self.effects if e.type == "gravity"]
        ini = self.scene.bodies[i].initial
        th, ph = float(ini.get("theta", 0.0)), float(ini.get("phi", 0.0))
        if not (
            len(grav) == 1
            and Jc[0] == Jc[1]
            and g[2] > 0
            and np.array_equal(grav[0].direction, [0.0, 0.0, -1.0])
            and 0.0 < th < math.pi
        ):
            return None
        try:
            psd, thd, phd = kin.euler_rates_from_angular_velocity(th, ph, self.w0[i])
        except GimbalLockError:  # sin θ0 within rounding of 0: the rates are undefined
            return None
        top = HeavySymmetricTop(
            Jc[0],
            Jc[2],
            self.m0[i] * grav[0].g * g[2],
            theta=th,
            psi=float(ini.get("psi", 0.0)),
            phi=ph,
            theta_dot=thd,
            psi_dot=psd,
            phi_dot=phd,
        )
        self._top = ("heavy", top)
        return "exact: heavy symmetric top, elliptic integrals (5.2.2–5.2.5)"

    def _pinned_exact(self):
        """The lone top's exact flow as flat states (L_C, R_A_O) at any times."""
        from mechanics.rotation import matrix_from_euler

        kind, top = self._top
        ((i, (_, _, JC, _)),) = self.layout.pins.items()
        o = self.layout.offsets[i]

        @vectorized
        def at(t):
            tt = np.asarray(t, dtype=float)
            if kind == "free":
                R, w = top.attitude(tt), top.omega(tt)
            else:
                th, ps, ph = top.theta(tt), top.psi(tt), top.phi(tt)
                thd, psd, phd = top.rates(tt)
                R = matrix_from_euler(ps, th, ph)
                w = kin.angular_velocity_from_euler_rates(ps, th, ph, psd, thd, phd)
            y = np.zeros((*tt.shape, self.layout.size))
            y[..., o : o + 3] = np.einsum("ij,...j->...i", JC, w)
            y[..., o + 3 : o + 12] = np.asarray(R).reshape(*tt.shape, 9)
            return y

        return [(0.0, self.scene.duration, at)], []

    def _spinning(self) -> list[int]:
        return [i for i in self.rigid if self.w0[i].any()]

    def _rotation(self):
        """Per spinning rigid body, t -> (L_A, R_A_O) by the torque-free flow."""
        from mechanics.tops import FreeAsymmetricTop

        out = {}
        for i in self._spinning():
            J = self.layout.J[i]
            top = FreeAsymmetricTop(J, self.w0[i], self.R0[i])
            out[i] = (J, top)
        return out

    def _gvec(self) -> np.ndarray:
        g = np.zeros(3)
        for e in self.effects:
            if e.type == "gravity":
                g = g + e.vector
        return g

    def _with_rotation(self, y_trans, t, tops) -> np.ndarray:
        """Flat states (..., size) whose translation comes from y_trans and rotation from
        the tops, at the time(s) t."""
        y = np.array(y_trans, dtype=float)
        tt = np.asarray(t, dtype=float)
        for i, (J, top) in tops.items():
            o = self.layout.offsets[i]
            y[..., o + 6 : o + 9] = J * top.omega(tt)
            y[..., o + 9 : o + 18] = top.attitude(tt).reshape(*tt.shape, 9)
        return y

    def _ballistic(self, T_end, tops):
        """Free flight under uniform gravity between impacts at closed-form instants."""
        g = self._gvec()
        segs, events = [], []
        t0, y = 0.0, self.y0.copy()
        while True:
            s = self.snapshot(t0, y)
            best = (math.inf, None, None)
            for imp in self.impacts:
                ft = imp.features[0]
                tau = self._contact_time(imp, ft, s, g)
                if tau < best[0]:
                    best = (tau, imp, ft)
            t1 = t0 + best[0]
            segs.append((t0, min(t1, T_end), self._flight(t0, y, g, tops)))
            if t1 >= T_end:
                break
            y = segs[-1][2](t1)
            y = self._resolve(t1, y, best[1], best[2], events)
            t0 = t1
        return segs, events

    def _flight(self, t0, y0, g, tops):
        r0, v0, L0, R0 = self.layout.gather(y0)

        @vectorized
        def at(t):
            tau = (np.asarray(t, dtype=float) - t0)[..., None, None]
            r = r0 + v0 * tau + 0.5 * g * tau * tau
            v = v0 + g * tau
            L, R = np.broadcast_to(L0, v.shape), np.broadcast_to(R0, (*v.shape, 3))
            return self._with_rotation(self.layout.pack(r, v, L, R), t, tops)

        return at

    def _contact_time(self, imp, ft, s, g) -> float:
        """Closed-form time to the next contact of a sphere or point (inf if none): under
        uniform gravity a plane gap is quadratic in τ, and the relative motion of two
        bodies is uniform (gravity cancels), so |d + w τ| = a_i + a_j is a quadratic."""
        i = imp.i
        if imp.j is None:
            tau = contacts.plane_contact_time(
                float(imp.gap(s, ft)), float(s.v[i] @ imp.normal), float(g @ imp.normal)
            )
        else:
            j = imp.j
            tau = contacts.sphere_contact_time(s.r[i] - s.r[j], s.v[i] - s.v[j], ft.a + ft.a_s)
        if tau < math.inf:
            s2 = self.snapshot(s.t + tau, self.pack(s))
            s2.r += s.v * tau + 0.5 * g * tau * tau
            s2.v += g * tau
            if self._touch(imp, ft, s2):
                return math.inf
        return tau

    def _rocket(self, tops):
        from mechanics.open_systems import rocket_height, rocket_velocity

        g = self._gvec()
        thrusts = {e.i: e for e in self.effects if e.type == "thrust"}
        r0, v0, L0, R0 = self.layout.gather(self.y0)

        @vectorized
        def at(t):
            tt = np.asarray(t, dtype=float)
            tau = tt[..., None, None]
            r = r0 + v0 * tau + 0.5 * g * tau * tau
            v = v0 + g * tau
            for i, th in thrusts.items():
                kw = dict(m_0=self.m0[i], q=th.q, u=th.u, m_f=th.m_f, g=0.0, after_burn_out="coast")
                r[..., i, :] += np.asarray(rocket_height(tt, **kw))[..., None] * th.direction
                v[..., i, :] += np.asarray(rocket_velocity(tt, **kw))[..., None] * th.direction
            L, R = np.broadcast_to(L0, v.shape), np.broadcast_to(R0, (*v.shape, 3))
            return self._with_rotation(self.layout.pack(r, v, L, R), t, tops)

        events = [
            Event(th.burn_out, "burn_out", {"body": self.names[th.i]})
            for th in thrusts.values()
            if th.burn_out <= self.scene.duration
        ]
        return [(0.0, self.scene.duration, at)], events

    # ------------------------------------------------------------------- run
    def run(self) -> Trajectory:
        s = self.scene
        t = np.linspace(0.0, s.duration, s.samples)
        self._begin()
        if s.method == "splitting":
            return self._split(t)
        exact = self.exact_flow()
        if s.method == "exact" and exact is None:
            kinds = sorted({e.type for e in self.effects})
            raise s.error(
                "scene.method",
                f"'exact' requested but the effects {kinds} of this scene have no "
                "exact flow here; use 'auto' or 'integrate'",
            )
        if exact is not None and s.method != "integrate":
            if self.layout.tanks:
                return self._finish(t, [(0.0, s.duration, self._tank)], self._tank_events, exact)
            if self.layout.guides:
                segs, events = self._guided_exact()
                return self._finish(t, segs, events, exact)
            if self.layout.pins:
                segs, events = self._pinned_exact()
                return self._finish(t, segs, events, exact)
            tops = self._tops
            if "rocket" in exact:
                segs, events = self._rocket(tops)
            else:
                segs, events = self._ballistic(s.duration, tops)
            return self._finish(t, segs, events, exact)
        segs, events = self._integrate(s.duration)
        how = (
            "integrated: DOP853 (mechanics.integrators), contacts located on each step's "
            "dense polynomial"
        )
        return self._finish(t, segs, events, how)

    def _split(self, t) -> Trajectory:
        """The splitting (:mod:`.splitting`), run again at half the step: the energy's
        drift must shrink by the method's order."""
        from . import splitting

        s = self.scene
        splitting.check(self)
        gap = s.duration / (s.samples - 1)  # splitting.run's steps: k per sample interval
        k = max(1, math.ceil(gap / s.step)) if s.step is not None else 1
        # the run at the step and at half of it: three times its steps
        budget.check_steps(
            s, 3 * k * (s.samples - 1), f"a splitting at step {gap / k:.3g} s, and at half of it"
        )
        segs, h = splitting.run(self, s.order, s.step)
        how = (
            f"integrated: splitting of order {s.order} (kicks of the loads, exact free "
            f"flight and torque-free rotation), step {h:.6g} s"
        )
        traj = self._finish(t, segs, [], how)
        half, _ = splitting.run(self, s.order, 0.5 * h)
        E = self._finish(t, half, [], how).series["E"]
        traj.extra["splitting"] = {"order": s.order, "step": h, "E_drift_half": float(np.ptp(E))}
        return traj

    def _integrate(self, t_end):
        from mechanics.errors import StepSizeError
        from mechanics.integrators import DOP853Stepper

        s = self.scene
        self._reach: dict[tuple[int, int], float] = {}
        self._switched: dict = {}  # effect -> the time of its last switch
        switches = sorted({x for e in self.forces for x in e.switch_times() if 0 < x < t_end})
        segs, events = [], []
        t, y = 0.0, self.y0.copy()
        rate = budget.fastest_rate(s, self.w0)
        budget.check_steps(
            s,
            budget.step_estimate(s, self.w0),
            f"{budget.STEPS_PER_RADIAN:g} per radian of the fastest rate {rate:.3g} 1/s at "
            f"rtol 1e-12, over {t_end:g} s",
        )
        clock = budget.Clock(s)
        for start, stop in itertools.pairwise([0.0, *switches, t_end]):
            self._phase = 0.5 * (start + stop)
            if start > 0:  # a load switched on or off: a mode may have to switch with it
                y = self._switch_now(t, y, events)
            while t < stop:
                solver = DOP853Stepper(self.rhs, t, y, stop, rtol=s.rtol, atol=s.atol)
                hit = None
                while solver.status == "running" and hit is None:
                    clock.step(solver.t)
                    try:
                        solver.step()
                    except StepSizeError as exc:
                        raise self.scene.error(
                            "scene.rtol",
                            f"the integration stalled at t = {solver.t:.17g} s (a singular "
                            f"force, e.g. bodies meeting under newton_gravity?): {exc}",
                        ) from None
                    dense = solver.dense_output()
                    hit = self._first_contact_on_step(dense, solver.t_old, solver.t)
                    sw = self._first_switch_on_step(dense, solver.t_old, solver.t)
                    if sw is not None and (hit is None or sw[0] < hit[0]):
                        hit = sw
                    segs.append((solver.t_old, solver.t if hit is None else hit[0], _rows(dense)))
                if hit is None:
                    t, y = float(solver.t), np.array(solver.y, dtype=float)
                    break
                t, what, ft = hit
                y = np.asarray(dense(t), dtype=float)
                if ft is None:  # an effect switches its mode (stick and slip)
                    sn = self.snapshot(t, y)
                    sn.phase = self._phase
                    events.append(what.switch(t, sn, self._loads_before(t, sn, what)))
                    self._switched[what] = t
                    if len(events) > MAX_EVENTS:
                        raise _zeno(self.scene, t, what.where)
                    y = self.pack(sn)
                    continue
                y = self._resolve(t, y, what, ft, events)
            for e in self.forces:
                if e.type == "thrust" and e.burn_out == stop and stop < t_end:
                    events.append(Event(stop, "burn_out", {"body": self.names[e.i]}))
        self._phase = None
        return segs, events

    # ---------------------------------------------------------------- switches
    def _loads_before(self, t, s, effect) -> Loads:
        """The loads of the effects summed before ``effect`` (all the others, for one
        that comes after the loads)."""
        out = Loads(self.n, s)
        for e in self.forces:
            if e is effect:
                break
            e.loads(t, s, out)
        return out

    def _begin(self) -> None:
        """Let the effects with modes choose theirs from the initial state."""
        if self.switching:
            s = self.snapshot(0.0, self.y0)
            for e in self.switching:
                e.begin(0.0, s, self._loads_before(0.0, s, e))

    def _switch_now(self, t, y, events) -> np.ndarray:
        """At a switch time of the loads: switch every mode whose switch function is
        below zero beyond its rounding (a push that starts makes a rolling body slip)."""
        for e in self.switching:
            g, size = self._switch_value(e, t, y)
            if g < -SWITCH_ROUNDING * size:
                sn = self.snapshot(t, y)
                sn.phase = self._phase
                events.append(e.switch(t, sn, self._loads_before(t, sn, e)))
                self._switched[e] = t
                y = self.pack(sn)
        return y

    def _switch_value(self, e, t, y) -> tuple[float, float]:
        s = self.snapshot(t, np.asarray(y, dtype=float))
        if self._phase is not None:  # the loads of the segment being integrated
            s.phase = self._phase
        return e.switch_function(t, s, self._loads_before(t, s, e))

    def _first_switch_on_step(self, dense, t_a, t_b):
        """The earliest switch of an effect's mode within one step, (t, effect, None), or
        None: its switch function along the step's dense output, fitted at the
        Chebyshev nodes, searched for a fall through zero as a gap is
        (:func:`contacts.first_downward_crossing`, refined on the function itself); a
        value within ``SWITCH_ROUNDING`` × its terms' size at the step's start is zero."""
        best = None
        for e in self.switching if t_b > t_a else ():
            sizes: list[float] = []

            def g(tt, e=e, sizes=sizes):
                vals = [self._switch_value(e, float(x), dense(float(x))) for x in tt]
                sizes.extend(size for _, size in vals)
                return np.array([[v] for v, _ in vals])

            def refine(xx, e=e):
                tt = 0.5 * (t_a + t_b) + 0.5 * (t_b - t_a) * xx
                return self._switch_value(e, tt, dense(tt))[0]

            coef = contacts.chebyshev_fit(g, t_a, t_b, ends=True)[:, 0]
            # just switched here: the new mode starts at its limit (a slip that starts
            # from zero speed), so only a fall beyond the rounding switches it back
            after = -1.0 if self._switched.get(e) == t_a else None
            try:
                xc = contacts.first_downward_crossing(
                    coef, start_tol=SWITCH_ROUNDING * max(sizes), refine=refine, after=after
                )
            except contacts.ContactError as exc:  # pragma: no cover - a switch was missed
                raise self.scene.error(
                    e.where, f"a switch of its mode was missed before t = {t_a:.17g} s ({exc})"
                ) from None
            if xc is not None:
                tc = t_a if xc == -1.0 else min(0.5 * (t_a + t_b) + 0.5 * (t_b - t_a) * xc, t_b)
                if best is None or tc < best[0]:
                    best = (tc, e, None)
        return best

    # ---------------------------------------------------------------- contacts
    def _feature_coef(self, coef_y, imp, ft):
        """Chebyshev coefficients (k, 3) of a feature's position along the step."""
        return self._point_coef(coef_y, ft.body, ft.at)

    def _frame_coef(self, coef_y, k):
        """Chebyshev coefficients of body k's centre (K, 3) and R_A_O (K, 3, 3) along
        the step (a guided body's fitted at the step's nodes)."""
        kind, o = self.layout.kinds[k], self.layout.offsets[k]
        if kind == "rigid":
            return coef_y[:, o : o + 3], coef_y[:, o + 9 : o + 18].reshape(-1, 3, 3)
        if kind == "pinned":
            return self._point_coef(coef_y, k, None), coef_y[:, o + 3 : o + 12].reshape(-1, 3, 3)
        dense, t_a, t_b = self._step

        def frame(tt):
            ss = self.snapshot(tt, np.asarray(dense(tt)).T)
            return np.concatenate([ss.r[:, k], ss.R[:, k].reshape(-1, 9)], axis=-1)

        c = contacts.chebyshev_fit(frame, t_a, t_b, ends=True)
        return c[:, :3], c[:, 3:].reshape(-1, 3, 3)

    def _rim_poly(self, coef_y, imp, ft):
        """w² − a² (d₁² + d₂²) along the step, with the sign of the rim circle's gap
        w − a |(d₁, d₂)| where w ≥ 0 (see :mod:`.effects.impact`), w itself (the gap
        is negative where w is), and the centre's coefficients."""
        r, R = self._frame_coef(coef_y, ft.body)
        a, zc = ft.support
        n = imp.normal
        d = -np.einsum("kij,j->ki", R, n)  # R_A_O (−n): body components, linear in R
        w = r @ n - zc * d[:, 2]
        w[0] -= imp.point @ n
        rho2 = C.chebadd(C.chebmul(d[:, 0], d[:, 0]), C.chebmul(d[:, 1], d[:, 1]))
        return C.chebsub(C.chebmul(w, w), a * a * rho2), w, r

    def _centre_coef(self, coef_y, k):
        return self._point_coef(coef_y, k, None)

    def _point_coef(self, coef_y, k, at):
        """Chebyshev coefficients (k, 3) of the body point ``at`` (body components about
        G; None: G) along the step: r + R_A_Oᵀ at, linear in the state; for a pinned body
        C + R_A_Oᵀ (g_A + at); a guided body's points (a hinge's are trigonometric in φ)
        are fitted at the step's Chebyshev nodes (for a turn of 0.3 rad per step the fit's error is
        ~(0.15)⁹/9! ≈ 1e-13 of the arm; the crossing is refined on the exact gap)."""
        kind, o = self.layout.kinds[k], self.layout.offsets[k]
        if kind == "guided":
            dense, t_a, t_b = self._step

            def pos(tt):
                ss = self.snapshot(tt, np.asarray(dense(tt)).T)
                return ss.point(k, at)

            return contacts.chebyshev_fit(pos, t_a, t_b, ends=True)
        if kind == "fixed":
            c = np.zeros((coef_y.shape[0], 3))
            c[0] = self.layout.r_fixed[k] + (at if at is not None else 0.0)
            return c
        if kind == "pinned":
            pivot, g, _, _ = self.layout.pins[k]
            R = coef_y[:, o + 3 : o + 12].reshape(-1, 3, 3)
            c = np.einsum("kic,i->kc", R, g + (at if at is not None else 0.0))
            c[0] += pivot
            return c
        c = coef_y[:, o : o + 3].copy()
        if at is not None:
            R = coef_y[:, o + 9 : o + 18].reshape(-1, 3, 3)
            c += np.einsum("kic,i->kc", R, at)
        return c

    def _first_contact_on_step(self, dense, t_a, t_b):
        """The earliest contact of any feature within one step, or None.

        Each feature's gap (the plane's) or |d|² − s² (a sphere's pair, the sign of the
        gap) is a polynomial along the step (positions and attitudes are state
        components, so a corner's position is linear in them);
        :func:`contacts.first_downward_crossing` finds its first crossing.  The
        rounding allowed at the step's start (a contact just resolved) is
        ``GAP_ROUNDING`` × the largest size the feature's positions (and the plane's
        point) and their change over a step have had so far.  A crossing with zero
        approach speed (up to ``CLOSING_ROUNDING``) is a touch, not an impact.
        """
        if not self.impacts or t_b <= t_a:
            return None
        coef_y = contacts.chebyshev_fit(lambda tt: np.asarray(dense(tt)).T, t_a, t_b)
        self._step = (dense, t_a, t_b)
        best = None
        for a, imp in enumerate(self.impacts):
            for b, ft in enumerate(imp.features):
                if ft.support is not None:  # a rim circle: w² − a² ρ², as a sphere pair
                    q, w, x = self._rim_poly(coef_y, imp, ft)
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
                    x = self._feature_coef(coef_y, imp, ft)
                    p = x @ imp.normal  # the plane's offset is a constant: the 0th term only
                    p[0] -= imp.point @ imp.normal + ft.a
                    size, units, other = ft.a, 1.0, np.abs(imp.point).sum()
                    polys = [(p, units, 0.0)]
                else:
                    x = self._feature_coef(coef_y, imp, ft)
                    rel = x - self._centre_coef(coef_y, ft.sphere)
                    p = C.chebadd(
                        C.chebadd(*(C.chebmul(rel[:, c], rel[:, c]) for c in (0, 1))),
                        C.chebmul(rel[:, 2], rel[:, 2]),
                    )
                    size = ft.a + ft.a_s
                    p[0] -= size * size
                    units = 2.0 * size  # |d|² − s² ≈ 2 s × gap near contact
                    other = np.abs(self._centre_coef(coef_y, ft.sphere)).sum()
                    polys = [(p, units, 0.0)]
                # positions round relative to their own size, not to their difference
                reach = np.abs(x).sum() + other + size
                self._reach[a, b] = max(self._reach.get((a, b), 0.0), reach)

                def gap_at(xx, imp=imp, ft=ft):
                    tt = 0.5 * (t_a + t_b) + 0.5 * (t_b - t_a) * xx
                    return float(imp.gap(self.snapshot(tt, np.asarray(dense(tt))), ft))

                for p, units, terms in polys:  # a rim circle: q, and w for a face flat
                    after = None
                    for _ in range(3):  # a touch (zero approach speed) is searched past once
                        try:
                            xc = contacts.first_downward_crossing(
                                p,
                                start_tol=GAP_ROUNDING * (self._reach[a, b] * units + terms),
                                refine=gap_at,
                                after=after,
                            )
                        except contacts.ContactError as exc:
                            raise self.scene.error(
                                imp.where,
                                f"{ft.label} interpenetrate at t = {t_a:.17g} s ({exc}): "
                                "a contact was missed before this step",
                            ) from None
                        if xc is None:
                            break
                        tc = (
                            t_a
                            if xc == -1.0
                            else min(0.5 * (t_a + t_b) + 0.5 * (t_b - t_a) * xc, t_b)
                        )
                        s_c = self.snapshot(tc, np.asarray(dense(tc), dtype=float))
                        if not self._touch(imp, ft, s_c):
                            if best is None or tc < best[0]:
                                best = (tc, imp, ft)
                            break
                        # zero approach speed: the pair touches here (a plastic pair moving on
                        # together, the top of a tiny hop); it may still fall in later
                        if after is not None and xc <= after:
                            raise _falls_in(self.scene, imp, ft, tc)
                        after = xc
                    else:  # touch after touch within one step: never passed over silently
                        raise _falls_in(self.scene, imp, ft, tc)
        return best

    def _touch(self, imp, ft, s) -> bool:
        """Touching with an approach speed that is zero up to rounding: no impact."""
        return imp.approach(s, ft) <= CLOSING_ROUNDING * imp.speed_scale(s, ft)

    def _pressed(self, imp, ft, t, y) -> float:
        """How hard the loads push the pair together: the inward normal relative
        acceleration of the contact points (> 0 pressed, ≤ 0 not)."""
        s = self.snapshot(t, y)
        if ft.support is not None:  # the gap of a rim circle against the plane
            g2 = self._rim_gap_acceleration(t, y, s, imp, ft)
            if g2 is not None:
                return -g2
        S, n = imp.contact(s, ft)
        a = self._point_accelerations(t, y, s, {imp.i: S, imp.j: S})
        return -float(n @ (a.get(imp.i, 0.0) - a.get(imp.j, 0.0)))

    def _stalls(self, imp, ft, t, y, detail) -> bool:
        """Do the impacts accumulate here?  Pressed together, the pair rebounds too slowly
        to be followed: slower than ``ZENO_SPEED`` (relative), or so slowly that its hop,
        v²/(2a), stays below the rounding of the gap (``GAP_ROUNDING`` × the positions'
        size), where no next contact can be told from this one."""
        a = self._pressed(imp, ft, t, y)
        if not a > 0:
            return False
        v = detail["normal_speed_after"]
        if v < ZENO_SPEED * (1.0 + abs(detail["normal_speed_before"])):
            return True
        return v * v <= 2.0 * a * GAP_ROUNDING * 4 * detail["gap_scale"]

    def _kinematics(self, s, dy, k):
        """(origin, its acceleration, ω, α), space components, of body k at the snapshot
        s whose state rates are dy: the origin is G (a pinned body's pivot, which does
        not move); a point has no ω, α."""
        _, dv, dL, _ = self.layout.gather(dy)  # raw rates: v̇, and L̇_A (L̇_C if pinned)
        kind, zero = self.layout.kinds[k], np.zeros(3)
        if kind == "point":
            return s.r[k], dv[k], zero, zero
        if kind == "guided":  # a_G = Σ E_k q̈_k + the bend; ω = Σ W_k q̇_k, α = Σ W_k q̈_k
            gd, o = self.layout.guides[k], self.layout.offsets[k]
            q, qd = s.coords[k]
            qdd = dy[o + gd.nq : o + 2 * gd.nq]
            _, E, _ = gd.place(q)
            return s.r[k], qdd @ E + gd.bend(q, qd), qd @ gd.W, qdd @ gd.W
        if kind == "pinned":
            pivot, _, _, JCinv = self.layout.pins[k]
            origin, base, wdot = pivot, zero, JCinv @ dL[k]
        else:
            safe = np.where(s.J[k] > 0, s.J[k], 1.0)
            origin, base, wdot = s.r[k], dv[k], np.where(s.J[k] > 0, dL[k] / safe, 0.0)
        return origin, base, s.to_space(k, s.omega[k]), s.to_space(k, wdot)

    def _point_accelerations(self, t, y, s, points) -> dict[int, np.ndarray]:
        """Accelerations (space) of the body points ``{body: position}`` at (t, y):
        a_G + α × ρ + ω × (ω × ρ), ρ from G (from the pivot of a pinned body, whose
        pivot does not move)."""
        dy = self.rhs(t, y)
        out = {}
        for k, S in points.items():
            if k is None or self.layout.kinds[k] == "fixed":
                continue
            origin, base, w, alpha = self._kinematics(s, dy, k)
            rho = S - origin
            out[k] = base + np.cross(alpha, rho) + np.cross(w, np.cross(w, rho))
        return out

    def _rim_gap_acceleration(self, t, y, s, imp, ft) -> float | None:
        """d²/dt² of a rim circle's gap w − a ρ (see :mod:`.effects.impact`) at (t, y),
        or None where the face is flat (ρ = 0).  With c = n·e3 (e3 the circle's axis in
        space, ė3 = ω × e3, ë3 = α × e3 + ω × (ω × e3)): w = (r_G − p)·n + z_c c and
        ρ = √(1 − c²), so w'' = a_G·n + z_c c̈ and ρ'' = −(ċ² + c c̈)/ρ − c² ċ²/ρ³.  The
        support point slides round the rim as the body turns, so this is not the
        acceleration of the material point there."""
        k, (a, zc), n = ft.body, ft.support, imp.normal
        origin, base, w, alpha = self._kinematics(s, self.rhs(t, y), k)
        rho_G = s.r[k] - origin
        a_G = base + np.cross(alpha, rho_G) + np.cross(w, np.cross(w, rho_G))
        e3 = s.R[k, 2]
        c = float(n @ e3)
        rho = math.sqrt(max(1.0 - c * c, 0.0))
        if rho == 0.0:
            return None
        c1 = float(n @ np.cross(w, e3))
        c2 = float(n @ (np.cross(alpha, e3) + np.cross(w, np.cross(w, e3))))
        rho2 = -(c1 * c1 + c * c2) / rho - c * c * c1 * c1 / rho**3
        return float(a_G @ n) + zc * c2 - a * rho2

    def _reactions(self, t, Y):
        """The joints' reactions at the samples (t, Y): the force of a pivot, of the
        bearings or of the surface a body rolls or slides on, F = m a_G − Σ F (4.4,
        4.71), and for a fixed axis the bearings' moment about C, M = J_a φ̈ a − M_C,
        perpendicular to the axis; with the size of their terms (what their rounding is
        relative to).  None where mass flows onto a body (the inflow's momentum is not
        among the loads)."""
        joints = [] if self.growing else [*self.layout.pins, *self.layout.guides]
        hinges = {i: g for i, g in self.layout.guides.items() if isinstance(g, Hinge)}
        out = {i: {"reaction": np.empty((len(t), 3))} for i in joints}
        size = {i: {"reaction": 0.0} for i in joints}
        for i in hinges if joints else ():
            out[i]["bearing_moment"] = np.empty((len(t), 3))
            size[i]["bearing_moment"] = 0.0
        if not out:
            return out, size
        for k, (tt, y) in enumerate(zip(t, Y, strict=True)):
            s = self.snapshot(float(tt), y)
            loads = Loads(self.n, s)
            for e in self.forces:
                e.loads(float(tt), s, loads)
            acc = self._point_accelerations(float(tt), y, s, {i: s.r[i] for i in out})
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

    def _resolve(self, t, y, imp, ft, events) -> np.ndarray:
        """Resolve the impact found at t, then every simultaneous one (sequential
        impulses, see the Conventions); record the events; return the new state."""
        from mechanics.errors import SeparatingContactError

        s = self.snapshot(t, y)
        for _ in range(MAX_SWEEPS):
            try:
                detail = imp.apply(s, ft)
            except SeparatingContactError as exc:
                raise self.scene.error(
                    imp.where,
                    f"{ft.label}: the contact at t = {t:.17g} s was found on the exit side "
                    f"(the bodies separate there): {exc}",
                ) from None
            except EnergyGainError as exc:
                raise self.scene.error(
                    f"{imp.where}.friction", f"{ft.label} at t = {t:.6g} s: {exc}"
                ) from None
            events.append(Event(t, "impact", detail))
            if len(events) > MAX_EVENTS:
                raise _zeno(self.scene, t, imp.label)
            y = self.pack(s)
            if self._stalls(imp, ft, t, y, detail):
                raise _zeno(self.scene, t, imp.label)
            nxt = self._closing_now(s)
            if nxt is None:
                return y
            imp, ft = nxt
        raise self.scene.error(
            "effects", f"more than {MAX_SWEEPS} rounds of simultaneous impacts at t = {t:.6g} s"
        )

    def _closing_now(self, s):
        """The touching feature that closes fastest (sequential impulses), or None."""
        best, speed = None, 0.0
        for imp in self.impacts:
            for ft in imp.features:
                scale = np.abs(imp.feature_point(s, ft)).sum() + imp.point @ imp.point + ft.a
                if abs(float(imp.gap(s, ft))) > GAP_ROUNDING * 4 * max(scale, ft.a + ft.a_s):
                    continue
                v = imp.approach(s, ft)
                if v > CLOSING_ROUNDING * imp.speed_scale(s, ft) and v > speed:
                    best, speed = (imp, ft), v
        return best

    # ------------------------------------------------------------------ result
    def keeps(self, quantity: str, effects) -> bool:
        return all(e.keeps(quantity) for e in effects)

    def _finish(self, t, segs, events, how) -> Trajectory:
        dense = dense_from_segments(segs)
        Y = sample_segments(segs, t)
        s = self.snapshot(t, Y)
        n, lay = self.n, self.layout
        moving = list(lay.moving_bodies)
        series: dict[str, np.ndarray] = {}
        pre = (lambda i: f"{self.names[i]}.") if n > 1 else (lambda i: "")
        thrust = bool(self.losing)
        for i in moving:
            p = pre(i)
            for k, c in enumerate("xyz"):
                series[p + c] = s.r[:, i, k]
            for k, c in enumerate("xyz"):
                series[p + "v" + c] = s.v[:, i, k]
            if thrust:
                series[p + "mass"] = s.m[:, i]
            if i in self.rigid:
                for k in range(3):
                    series[f"{p}omega{k + 1}"] = s.omega[:, i, k]
                w_O = s.to_space(i, s.omega[:, i])
                for k, c in enumerate("xyz"):
                    series[f"{p}w{c}"] = w_O[:, k]
        reactions, reaction_sizes = self._reactions(t, Y)
        for i, parts in reactions.items():
            for what, F in parts.items():
                for k, c in enumerate("xyz"):
                    series[f"{pre(i)}{what}_{c}"] = F[:, k]
        for i in lay.pins:
            series.update({pre(i) + k: v for k, v in _top_angles(s.R[:, i], s.omega[:, i]).items()})
        for i, gd in lay.guides.items():
            series.update({pre(i) + k: v for k, v in gd.series(*s.coords[i]).items()})
        m = s.m[:, moving]
        v, r = s.v[:, moving], s.r[:, moving]
        KE = 0.5 * (m * (v * v).sum(-1)).sum(-1) + 0.5 * (s.L_A * s.omega).sum((-1, -2))
        for i, M in s.inertia.items():  # the inertia mass flowing in has added
            qd = s.coords[i][1]
            KE = KE + 0.5 * ((M - lay.guides[i].M) * qd * qd).sum(-1)
        E = KE.copy()
        for e in self.potentials:
            E = E + e.potential(s)
        if moving:
            series["E"] = E
        P = (m[..., None] * v).sum(-2)
        orb = np.cross(r, m[..., None] * v)
        spins = np.einsum("...ji,...j->...i", s.R, s.L_A)
        L_O = orb.sum(-2) + spins.sum(-2)
        conserved, scales, across = {}, {"E": energy_scale(KE, E)}, set()
        p_scale = float(np.max((m * np.linalg.norm(v, axis=-1)).sum(-1), initial=0.0))
        # the size of the terms: |r| m |v| bounds each orbital term |r × m v| (a small
        # cross product of large vectors is known only to their size)
        L_scale = float(
            np.max(
                (np.linalg.norm(r, axis=-1) * m * np.linalg.norm(v, axis=-1)).sum(-1)
                + np.linalg.norm(spins, axis=-1).sum(-1),
                initial=0.0,
            )
        )
        values = {"E": E}
        for k, c in enumerate("xyz"):
            values[f"p_{c}"], scales[f"p_{c}"] = P[:, k], p_scale
            values[f"L_{c}"], scales[f"L_{c}"] = L_O[:, k], L_scale
        if len(moving) > 1 or self.rigid:
            for k, c in enumerate("xyz"):
                series[f"p_{c}"], series[f"L_{c}"] = P[:, k], L_O[:, k]
        since: dict[str, float] = {}
        T = self.scene.duration
        for q in CONSERVED if moving else ():
            # what the effects acting throughout keep; an effect that stops acting (a
            # push, a burn) breaks it only until then
            until = max(
                (e.acts_until(events, q) for e in self.forces if not e.keeps(q)), default=0.0
            )
            if until < T:
                conserved[q] = values[q]
                if until > 0:
                    since[q] = until
                if self.keeps(q, self.impacts):
                    across.add(q)
        for e in self.forces:  # what an effect's own physics keeps, and its series
            series.update(e.series(s))
            for name, (vals, size) in e.conserved(s).items():
                series[name] = conserved[name] = vals
                scales[name] = size
                across.add(name)
        kinds = {e.type for e in self.effects}
        for i in lay.pins:
            if lay.J[i, 0] == lay.J[i, 1] and kinds <= {"fixed_point", "gravity"}:
                # the moments of gravity and of the pivot about C are ⟂ to e3 (C on e3)
                name = pre(i) + "L_3"
                series[name] = conserved[name] = lay.J[i, 2] * s.omega[:, i, 2]
                scales[name] = float(np.max(np.linalg.norm(s.L_A[:, i], axis=-1)))
                across.add(name)
        for i in self.rigid:
            until = max(
                (e.acts_until(events) for e in self.forces if e.exerts_moment(i)), default=0.0
            )
            struck = any(imp.exerts_moment(i) for imp in self.impacts)
            if until >= T or not (self.w0[i].any() or until > 0 or struck):
                continue  # turned to the end, or never spinning (trivially kept)
            p = pre(i)
            for k, c in enumerate("xyz"):
                name = f"{p}L_{c} (spin about G)"
                conserved[name] = spins[:, i, k]
                scales[name] = float(np.max(np.linalg.norm(spins[:, i], axis=-1)))
                if until > 0:
                    since[name] = until
                if not struck:
                    across.add(name)

        def state_at(tt):
            ss = self.snapshot(tt, np.asarray(dense(tt), dtype=float))
            out = {}
            for i in moving:
                p = pre(i)
                for k, c in enumerate("xyz"):
                    out[p + c] = float(ss.r[i, k])
                    out[p + "v" + c] = float(ss.v[i, k])
                if i in self.rigid:
                    w_O = ss.to_space(i, ss.omega[i])
                    for k in range(3):
                        out[f"{p}omega{k + 1}"] = float(ss.omega[i, k])
                        out[f"{p}w{'xyz'[k]}"] = float(w_O[k])
                if i in lay.pins:
                    R, w = ss.R[i], ss.omega[i]
                    out[p + "cos_theta"] = float(R[2, 2])
                    out[p + "cos_theta_dot"] = float(w[1] * R[0, 2] - w[0] * R[1, 2])
                if i in lay.guides:
                    for k, x in lay.guides[i].series(*ss.coords[i]).items():
                        out[p + k] = float(x)
            for e in self.forces:
                out.update({k: float(x) for k, x in e.series(ss).items()})
            y = np.asarray(dense(tt), dtype=float)
            for i, parts in self._reactions(np.array([tt]), y[None])[0].items():
                for what, F in parts.items():
                    for k, c in enumerate("xyz"):
                        out[f"{pre(i)}{what}_{c}"] = float(F[0, k])
            return out

        for i, sizes in reaction_sizes.items():
            for what, size in sizes.items():
                for c in "xyz":
                    scales[f"{pre(i)}{what}_{c}"] = size
        traj = Trajectory(t, series, events, how, state_at, conserved, since, {}, frozenset(across))
        traj.extra["scales"] = scales
        #: every body's r, v, R_A_O, ω_A and m at the sample times (mechanics.conformance)
        traj.extra["snapshot"] = s
        traj.extra["gaps"] = {
            imp.label: np.min([imp.gap(s, ft) for ft in imp.features], axis=0)
            for imp in self.impacts
        }
        radii = [ft.a + ft.a_s for imp in self.impacts for ft in imp.features]
        verts = [
            np.abs(body_vertices(b)).max()
            for b in self.scene.bodies
            if body_vertices(b) is not None
        ]
        traj.extra["length_scale"] = float(
            np.max(np.abs(r), initial=0.0) + max(radii, default=0.0) + max(verts, default=0.0)
        )
        if self.rigid:
            Rr = s.R[:, list(self.rigid)]
            dev = np.einsum("...ij,...kj->...ik", Rr, Rr) - np.eye(3)
            traj.extra["orthogonality"] = float(np.max(np.abs(dev)))
        return traj


def _falls_in(scene, imp, ft, t) -> SceneError:
    return scene.error(
        imp.where,
        f"{ft.label} touch at t = {t:.17g} s and then fall in, with no separation that "
        "float64 can resolve: a resting contact, which no effect provides (shorten the "
        "duration)",
    )


def _zeno(scene, t, who="the bodies") -> SceneError:
    return scene.error(
        "scene.duration",
        f"{who} come to rest in contact (the impacts accumulate, or e = 0) near "
        f"t = {t:.6g} s before the end {scene.duration:g} s: shorten the duration "
        "(impacts do not become a resting contact; a round body resting or rolling on a "
        "plane is the coulomb_friction joint's)",
    )


def _rows(dense):
    """A step's dense output (scipy's convention: (size, k) for k times) as a vectorised
    function returning (k, size), (size,) for one time."""

    @vectorized
    def at(t):
        return np.asarray(dense(t)).T

    return at


def _top_angles(R, w) -> dict[str, np.ndarray]:
    """The series of a top (samples of R_A_O and body ω): the Euler angles z-x-z (row 3
    of ^A R^O is (sθ sψ, −sθ cψ, cθ), column 3 is (sφ sθ, cφ sθ, cθ)), the symmetry axis
    e3 in space components, cos θ and its rate d(cos θ)/dt = (Ṙ)₃₃ with Ṙ = −[ω]× R."""
    return {
        "theta": np.arctan2(np.hypot(R[:, 2, 0], R[:, 2, 1]), R[:, 2, 2]),
        "psi": np.unwrap(np.arctan2(R[:, 2, 0], -R[:, 2, 1])),
        "phi": np.unwrap(np.arctan2(R[:, 0, 2], R[:, 1, 2])),
        "axis_x": R[:, 2, 0],
        "axis_y": R[:, 2, 1],
        "axis_z": R[:, 2, 2],
        "cos_theta": R[:, 2, 2],
        "cos_theta_dot": w[:, 1] * R[:, 0, 2] - w[:, 0] * R[:, 1, 2],
    }
