"""The one-degree-of-freedom models: a body on a fixed axis with mass flowing onto it (the
carousel), rolling, sliding with Coulomb friction, and the draining tank.  Each has its
own coordinates and takes only the effects written for it; scenes of free, pinned and
hinged bodies go to the engine (:mod:`mechanics.scenes.engine`).  (To be folded into
the engine as contact and mass-flow effects: issue 14.)

Conventions
-----------
- **Models.**  ``tank_outflow`` → :class:`TankModel`; ``fixed_axis`` with ``mass_flow``
  → :class:`AxisModel` (φ, φ̇; a fixed axis or point otherwise is a joint of the engine,
  which has the pendulum's and the tops' exact flows);
  ``rolling`` → :class:`RollingModel` (s on an incline, ψ in a track);
  ``coulomb_friction`` → :class:`SlidingModel` (s, v, ω).
- **Exact flows** (``method = "auto"`` or ``"exact"``): the pendulum released from
  rest (:func:`mechanics.dynamics.pendulum_motion`), also for the cylinder in a track
  (an equivalent pendulum); uniform acceleration when rolling down an incline, and for
  each phase of sliding with the switch solved exactly; the carousel (7.39); the
  draining tank (:func:`mechanics.fluids.tank_level`).
- **Integration** otherwise (or ``method = "integrate"``): scipy's DOP853 at the
  scene's ``rtol``/``atol`` with terminal ``events=`` (the switch from sliding to
  rolling), restarted after them.
- The result holds the samples (evenly spaced over ``[0, duration]``), a dense
  ``state_at(t)`` for locating features exactly, the events, and the quantities the
  effects conserve, each with the segments (between events) over which it is conserved.
"""

from __future__ import annotations

import math

import numpy as np

from . import effects as fx
from .state import ROUND_SHAPES, body_inertia
from .trajectory import Event, Trajectory, energy_scale, sample_dense, vectorized
from .trajectory import dense_from_segments as _dense_from_segments

__all__ = ["CONSTRAINTS", "MODELS", "integrate_segments", "select_model"]

#: events per run before it is declared Zeno (accumulating events)
MAX_EVENTS = 2000


# ------------------------------------------------------------------ integration helper


def integrate_segments(rhs, y0, t_end, *, rtol, atol, events=(), on_event=None, t0=0.0):
    """Integrate with DOP853 from t0 to t_end, restarting after terminal events.

    ``events`` are functions g(t, y) (terminal, direction −1 unless they carry their own
    ``direction``); ``on_event(k, t, y)`` returns the new state (or None to stop the
    run) and may record the event.  Returns a list of (t_a, t_b, dense) segments.
    """
    from scipy.integrate import solve_ivp

    for ev in events:
        ev.terminal = True
        if not hasattr(ev, "direction"):
            ev.direction = -1
    segs = []
    t, y, n = t0, np.asarray(y0, dtype=float), 0
    while t < t_end:
        sol = solve_ivp(
            rhs,
            (t, t_end),
            y,
            method="DOP853",
            rtol=rtol,
            atol=atol,
            dense_output=True,
            events=list(events) or None,
        )
        if sol.status == -1:
            raise RuntimeError(f"integration failed at t = {t}: {sol.message}")
        segs.append((t, float(sol.t[-1]), sol.sol))
        if sol.status != 1:
            break
        k = next(i for i, te in enumerate(sol.t_events) if len(te))
        t = float(sol.t_events[k][0])
        y = sol.y_events[k][0].copy()
        n += 1
        if n > MAX_EVENTS:
            raise RuntimeError("too many events")
        y = on_event(k, t, y)
        if y is None:
            break
    return segs


# ------------------------------------------------------------------ models


class Model:
    """Base: the scene, its bodies and the effect objects built from the listed effects."""

    name = ""
    constraint = ""
    allowed: frozenset[str] = frozenset()

    def __init__(self, scene) -> None:
        self.scene = scene
        self.bodies = scene.bodies
        self.effects = fx.build_effects(scene, None)
        self.by_type: dict[str, list[fx.Effect]] = {}
        for e in self.effects:
            self.by_type.setdefault(e.type, []).append(e)

    @classmethod
    def validate(cls, scene) -> None:
        for e in scene.effects:
            if e.type not in cls.allowed and e.type != cls.constraint:
                raise scene.error(
                    f"{e.where}.type",
                    f"a {e.type!r} effect cannot act in a {cls.name} scene "
                    f"(it takes: {', '.join(sorted(cls.allowed)) or 'nothing else'})",
                )

    def one(self, kind):
        lst = self.by_type.get(kind, [])
        return lst[0] if lst else None

    def others(self) -> set[str]:
        return {e.type for e in self.effects} - {self.constraint}

    def exact_flow(self) -> str | None:  # pragma: no cover - overridden
        return None

    def run(self) -> Trajectory:
        s = self.scene
        t = np.linspace(0.0, s.duration, s.samples)
        exact = self.exact_flow()
        if s.method == "exact" and exact is None:
            raise s.error(
                "scene.method",
                f"'exact' requested but the effects {sorted(self.others())} of this "
                f"{self.name} scene have no exact flow here; use 'auto' or 'integrate'",
            )
        if exact is not None and s.method != "integrate":
            return self.run_exact(t, exact)
        return self.run_integrated(t)


def _single(cls, scene) -> None:
    if len(scene.bodies) != 1:
        raise scene.error("bodies", f"a {cls.name} scene has exactly one body")


def _round_body(scene, e) -> None:
    """The single body of a rolling or sliding scene must be round."""
    b = scene.bodies[0]
    if b.shape not in ROUND_SHAPES:
        raise scene.error(
            f"{e.where}.body",
            f"only round bodies roll ({', '.join(ROUND_SHAPES)}); {b.name!r} is a {b.shape}",
        )


def _plane_angle(scene, e) -> None:
    """An incline's angle must lie in [0, π/2)."""
    a = e.fields.get("angle", 0.0)
    if not 0 <= a < math.pi / 2:
        raise scene.error(f"{e.where}.angle", f"must lie in [0, π/2); got {a!r}")


# ---------------------------------------------------------------- fixed axis


class AxisModel(Model):
    """Rotation about a fixed axis: J(t) φ̈ = Σ moments (4.48), J(t) with mass inflow."""

    name = "fixed-axis"
    constraint = "fixed_axis"
    allowed = frozenset({"gravity", "torsion", "mass_flow"})

    @classmethod
    def validate(cls, scene):
        super().validate(scene)
        _single(cls, scene)
        b = scene.bodies[0]
        if b.shape == "tank":
            raise scene.error("bodies[0].shape", "a tank cannot turn about an axis")
        for k in b.initial:
            if k not in ("angle", "angular_velocity"):
                raise scene.error(
                    f"bodies[0].initial.{k}", "a fixed-axis body takes angle and angular_velocity"
                )
        ax = scene.effects_of("fixed_axis")
        if len(ax) > 1:
            raise scene.error(f"{ax[1].where}.type", "only one fixed_axis per scene")
        J = fx.FixedAxis(ax[0]).moment_of_inertia(b.mass, np.diag(body_inertia(b)))
        if J <= 0:
            raise scene.error(
                f"{ax[0].where}.body_axis",
                f"the moment of inertia about this axis is zero for a {b.shape}",
            )

    def __init__(self, scene):
        super().__init__(scene)
        b = self.bodies[0]
        self.m = b.mass
        self.axis_fx = self.one("fixed_axis")
        self.J0 = self.axis_fx.moment_of_inertia(self.m, np.diag(body_inertia(b)))
        self.h, self.axis = self.axis_fx.h, self.axis_fx.axis
        self.phi0 = float(b.initial.get("angle", 0.0))
        self.phidot0 = float(b.initial.get("angular_velocity", 0.0))
        self.torques = [e for e in self.effects if e.type in ("gravity", "torsion")]
        self.flows = self.by_type.get("mass_flow", [])

    def J(self, t):
        return self.J0 + sum(f.inertia_added(t) for f in self.flows)

    def rhs(self, t, y):
        phi, w = y
        M = 0.0
        for e in self.torques:
            M += e.axis_torque(self.m, self.h, self.axis, phi)
        for f in self.flows:
            M += f.axis_torque_flux(w)
        return [w, M / self.J(t)]

    def exact_flow(self):
        k = self.others()
        if not k:
            return "exact: uniform rotation"
        if k == {"gravity"} and self.phidot0 == 0 and abs(self.phi0) <= math.pi:
            g = self.one("gravity")
            if len(self.by_type["gravity"]) == 1 and g.axis_g_perp(self.axis) > 0 and self.h > 0:
                return "exact: pendulum released from rest, Jacobi elliptic functions (4.50)"
        if k == {"torsion"} and len(self.by_type["torsion"]) == 1:
            return "exact: harmonic torsion oscillation"
        if k == {"mass_flow"} and len(self.flows) == 1:
            return "exact: carousel under fire, solution of (7.39)"
        return None

    def _exact_fn(self, how):
        phi0, w0, J0 = self.phi0, self.phidot0, self.J0
        if "uniform" in how:
            return lambda t: (phi0 + w0 * t, w0 + 0.0 * t)
        if "pendulum" in how:
            from mechanics.dynamics import pendulum_motion
            from mechanics.elliptic import ellipj

            gp = self.one("gravity").axis_g_perp(self.axis)
            om0 = math.sqrt(self.m * gp * self.h / J0)
            k, kp = math.sin(abs(phi0) / 2), math.cos(abs(phi0) / 2)
            sgn = 1.0 if phi0 >= 0 else -1.0

            def f(t):
                phi = pendulum_motion(t, J0, self.m, gp, self.h, phi0)
                sn, _, dn, _ = ellipj(om0 * np.asarray(t, float), k * k, m1=kp * kp)
                return phi, -sgn * 2.0 * k * kp * om0 * sn / dn  # φ̇ = −2kk'ω0 sd(ω0 t)

            return f
        if "torsion" in how:
            om = math.sqrt(self.one("torsion").tau_0 / J0)
            return lambda t: (
                phi0 * np.cos(om * t) + w0 / om * np.sin(om * t),
                -phi0 * om * np.sin(om * t) + w0 * np.cos(om * t),
            )
        from mechanics.open_systems import carousel_angular_velocity

        f = self.flows[0]
        c, b = f.q * f.R**2, f.r * f.q * f.v

        def fc(t):
            t = np.asarray(t, float)
            w = carousel_angular_velocity(t, J_0=J0, q=f.q, v=f.v, r=f.r, R=f.R, phidot_0=w0)
            if c == 0:
                return phi0 + w0 * t, w
            phi = phi0 - (b / c) * t + (J0 * w0 + b * J0 / c) / c * np.log1p(c * t / J0)
            return phi, w

        return fc

    def run_exact(self, t, how):
        f = self._exact_fn(how)

        @vectorized
        def dense(tt):
            return np.stack(np.broadcast_arrays(*f(tt)), axis=-1)

        return self._finish(t, dense, [], how)

    def run_integrated(self, t):
        s = self.scene
        segs = integrate_segments(
            self.rhs, [self.phi0, self.phidot0], s.duration, rtol=s.rtol, atol=s.atol
        )
        return self._finish(
            t, _dense_from_segments(segs), [], "integrated: DOP853 (scipy solve_ivp)"
        )

    def _finish(self, t, dense, events, how):
        Y = sample_dense(dense, t)
        phi, w = Y[:, 0], Y[:, 1]
        series, scales = {"phi": phi, "phidot": w}, {}
        if self.h > 0:
            series["x_G"], series["y_G"] = self.h * np.sin(phi), -self.h * np.cos(phi)
        conserved = {}
        if not self.flows:
            E = KE = 0.5 * self.J0 * w * w
            for e in self.torques:
                E = E + e.axis_potential(self.m, self.h, self.axis, phi)
            series["E"] = conserved["E"] = E
            scales["E"] = energy_scale(KE, E)
        else:
            L = self.J(t) * w
            series["L_axis"] = L
            if not self.torques:
                flux = sum(f.r * f.q * f.v for f in self.flows) * t
                series["L_axis + r q v t"] = conserved["L_axis + r q v t"] = L + flux
                scales["L_axis + r q v t"] = float(np.max(np.abs(L)) + np.max(np.abs(flux)))

        def state_at(tt):
            y = dense(tt)
            return {"phi": float(y[0]), "phidot": float(y[1])}

        traj = Trajectory(t, series, events, how, state_at, conserved)
        traj.extra["scales"] = scales
        return traj


# ---------------------------------------------------------------- tank


class TankModel(Model):
    """A prismatic tank draining through a small hole (Example 8.1)."""

    name = "tank"
    constraint = "tank_outflow"
    allowed = frozenset({"gravity"})

    @classmethod
    def validate(cls, scene):
        super().validate(scene)
        _single(cls, scene)
        b = scene.bodies[0]
        e = scene.effects_of("tank_outflow")[0]
        if b.shape != "tank":
            raise scene.error(f"{e.where}.body", f"tank_outflow needs a tank body; got a {b.shape}")
        if e.fields["hole_area"] >= b.dims["area"]:
            raise scene.error(
                f"{e.where}.hole_area",
                f"must be smaller than the tank's area {b.dims['area']!r}; "
                f"got {e.fields['hole_area']!r}",
            )
        if not scene.effects_of("gravity"):
            raise scene.error(
                f"{e.where}.type", "tank_outflow is driven by gravity: list a gravity effect"
            )
        if "level" not in b.initial:
            raise scene.error("bodies[0].initial.level", "missing required field for a tank")
        for k in b.initial:
            if k != "level":
                raise scene.error(f"bodies[0].initial.{k}", "a tank takes only level")

    def __init__(self, scene):
        super().__init__(scene)
        b = self.bodies[0]
        self.A = b.dims["area"]
        self.h0 = float(b.initial["level"])
        self.out = self.one("tank_outflow")
        self.g = sum(gr.g * -gr.direction[2] for gr in self.by_type["gravity"])
        if self.g <= 0:
            raise scene.error("effects", "gravity must point down (−z) to drain the tank")

    def exact_flow(self):
        return "exact: Torricelli outflow, level (√h0 − c t)² (8.37)"

    def rhs(self, t, y):
        """State (√h, volume out): the level is integrated as √h (see
        :meth:`~mechanics.scenes.effects.TankOutflow.sqrt_level_rate`)."""
        w = y[0]
        return [
            self.out.sqrt_level_rate(self.g, self.A),
            self.out.a * self.out.outflow_speed(w * w, self.g, self.A),
        ]

    def run_exact(self, t, how):
        from mechanics.fluids import drain_time, tank_level

        ratio = self.out.a / self.A
        T = float(drain_time(self.h0, g=self.g, area_ratio=ratio))
        c = math.sqrt(self.h0) / T
        k = math.sqrt(2 * self.g / ((1 - ratio) * (1 + ratio)))

        def dense(tt):
            h = float(tank_level(tt, h_0=self.h0, g=self.g, area_ratio=ratio))
            tc = min(tt, T)
            return np.array([h, self.out.a * k * c * (T * tc - 0.5 * tc * tc)])

        events = [Event(T, "empty", {})] if self.scene.duration >= T else []
        return self._finish(t, dense, events, how)

    def run_integrated(self, t):
        s = self.scene

        def empty(tt, y):
            return y[0]

        events = []

        def on_event(k, tt, y):
            events.append(Event(tt, "empty", {}))
            return None

        segs = integrate_segments(
            self.rhs,
            [math.sqrt(self.h0), 0.0],
            s.duration,
            rtol=s.rtol,
            atol=s.atol,
            events=[empty],
            on_event=on_event,
        )
        if events:
            yT = segs[-1][2](events[0].t)
            empty_state = np.array([0.0, yT[1]])
            segs.append((events[0].t, math.inf, lambda t: empty_state))
        dense_w = _dense_from_segments(segs)

        def dense(tt):
            y = dense_w(tt)
            return np.array([y[0] * y[0], y[1]])

        return self._finish(t, dense, events, "integrated: DOP853 (scipy solve_ivp), level as √h")

    def _finish(self, t, dense, events, how):
        Y = sample_dense(dense, t)
        h, vout = np.maximum(Y[:, 0], 0.0), Y[:, 1]
        ratio = self.out.a / self.A
        u = np.sqrt(2 * self.g * h / ((1 - ratio) * (1 + ratio)))
        vol = self.A * h + vout
        series = {"h": h, "u": u, "volume_out": vout, "volume_total": vol}

        def state_at(tt):
            y = dense(tt)
            return {"h": float(max(y[0], 0.0)), "volume_out": float(y[1])}

        return Trajectory(t, series, events, how, state_at, {"volume_total": vol})


MODELS = (TankModel, AxisModel)
#: the engine's joints (:mod:`mechanics.scenes.effects`)
CONSTRAINT_JOINTS = ("fixed_point", "rolling", "coulomb_friction")
#: the effect types that select a one-degree-of-freedom model
CONSTRAINTS = (*(m.constraint for m in MODELS), *CONSTRAINT_JOINTS)


def select_model(scene):
    """The model the scene's constraint calls for (validated), or None: free bodies and
    pinned ones (a fixed point) are the engine's (:mod:`mechanics.scenes.engine`)."""
    cons = [e for e in scene.effects if e.type in CONSTRAINTS]
    kinds = {e.type for e in cons}
    if len(kinds) > 1:
        a, b = cons[0], next(e for e in cons if e.type != cons[0].type)
        raise scene.error(
            f"{b.where}.type",
            f"{b.type!r} cannot be combined with {a.type!r} ({a.where}): list one constraint",
        )
    if len(cons) > 1:
        raise scene.error(f"{cons[1].where}.type", f"{cons[1].type!r} is listed twice")
    if not kinds:
        return None
    if kinds <= set(CONSTRAINT_JOINTS) or (
        kinds == {"fixed_axis"} and not scene.effects_of("mass_flow")
    ):
        return None  # a pinned or hinged body: the engine's (the carousel's inflow is not)
    cls = next(m for m in MODELS if m.constraint in kinds)
    cls.validate(scene)
    return cls
