"""Exact flows: the scenes whose motion has a closed form, each provider saying when it
applies (``method = "auto"`` or ``"exact"``).

Each provider takes the model (and the forward dynamics and the impact law where it
needs them) and returns a :class:`Flow`, or None where it does not apply.  At most one
applies to a scene; :func:`find` returns it.

- :func:`tank_flow`: a lone tank under gravity: Torricelli
  (:meth:`~mechanics.scenes.effects.tank_outflow.TankOutflow.exact`).
- :func:`guided_flow`: a lone guided body: its guide's
  (:meth:`~mechanics.scenes.state.Guide.exact`: the pendulum from rest, the torsion
  pendulum, the carousel, rolling, the sliding phases).
- :func:`pinned_flow`: a lone top on its fixed point with nothing else, the torque-free
  top about C; with gravity along −z, J1 = J2 and 0 < θ0 < π, the heavy symmetric top
  (:class:`mechanics.tops.HeavySymmetricTop`, 5.2).
- :func:`free_flight_flow`: free bodies with only uniform gravity and impacts of spheres
  and points (smooth, through the centres): free flight between impacts at closed-form
  instants (:meth:`~.impacts.Resolver.contact_time`); a body resting on a plane
  (:mod:`.support`) slides on it under the part of gravity along it.  A resting body
  whose pair with a flying one would need the relative motion's quartic, or a body
  resting on two planes, is not followed (:class:`NotExact`: the engine integrates).
- :func:`rocket_flow`: free bodies with only gravity and space-fixed thrust: the rocket
  (7.30).

In the last two each spinning rigid body turns by the torque-free Jacobi-elliptic flow
of :class:`mechanics.tops.FreeAsymmetricTop`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeAlias, cast

import numpy as np
import numpy.typing as npt

from mechanics import kinematics as kin
from mechanics.errors import GimbalLockError, OutOfDomainError

from . import contacts
from .effects.capabilities import GuidesBody
from .trajectory import Dense, Event, Segment, vectorized
from .vectors import FloatArray, IntArray, Times

if TYPE_CHECKING:  # for annotations only
    from mechanics.tops import FreeAsymmetricTop

    from .effects import Snapshot
    from .effects.gravity import Gravity
    from .effects.impact import Feature, Impact
    from .effects.thrust import Thrust
    from .forward import Forward
    from .impacts import Resolver
    from .model import Model
    from .support import Support

#: each spinning rigid body's (J, its torque-free top)
Tops: TypeAlias = "dict[int, tuple[FloatArray, FreeAsymmetricTop]]"

__all__ = [
    "PROVIDERS",
    "Calendar",
    "Flow",
    "NotExact",
    "find",
    "free_flight",
    "free_flight_flow",
    "guided_flow",
    "pinned_flow",
    "rocket_flow",
    "tank_flow",
]


@dataclass(frozen=True)
class Flow:
    """An exact flow: how it is computed, and a function returning its segments and events.

    A record (a frozen dataclass): its constructor stores its fields and checks nothing.

    Parameters
    ----------
    how : str
        How the flow is computed (a run's ``how``, e.g. ``"exact: free flight under
        uniform gravity"``).
    run : Callable[[], tuple[list[Segment], list[Event]]]
        Returns the segments ``[(t0, t1, state_at)]`` (``state_at`` the flat state(s) at
        any time(s) in [t0, t1]) and the events, in time order.

    Examples
    --------
    >>> flow = Flow("exact: at rest", lambda: ([], []))
    >>> flow.how, flow.run()
    ('exact: at rest', ([], []))
    """

    how: str
    run: Callable[[], tuple[list[Segment], list[Event]]]


def tank_flow(model: Model, forward: Forward, resolver: Resolver) -> Flow | None:
    """The exact flow of a lone tank with gravity and its outflow only: Torricelli (8.37).

    The level and the volume out in closed form
    (:meth:`~mechanics.scenes.effects.tank_outflow.TankOutflow.exact`), with an ``empty``
    event at the drain time if it falls within the duration.

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`).
    forward : Forward
        Its forward dynamics (:class:`mechanics.scenes.forward.Forward`): not read here.
    resolver : Resolver
        Its impact law (:class:`mechanics.scenes.impacts.Resolver`): not read here.

    Returns
    -------
    Flow or None
        The exact flow, or None where it does not apply.

    Raises
    ------
    ResultOverflowError
        Where the drain time exceeds float64's range (a hole of 1e-320 m² in a tank of
        1 m²: :func:`mechanics.fluids.drain_time`).

    Examples
    --------
    The tank empties at the drain time of :func:`mechanics.fluids.drain_time`:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 100.0},
    ...     "bodies": [{"name": "tank", "shape": "tank", "area": 1.0, "initial": {"level": 2.0}}],
    ...     "effects": [{"type": "gravity", "g": 9.81},
    ...                 {"type": "tank_outflow", "body": "tank", "hole_area": 0.01}]}))
    >>> segs, events = tank_flow(eng.model, eng.forward, eng.resolver).run()
    >>> from mechanics.fluids import drain_time
    >>> events[0].kind, events[0].t == float(drain_time(2.0, g=9.81, area_ratio=0.01))
    ('empty', True)
    """
    if not model.layout.tanks:
        return None
    if model.n != 1 or not model.kinds <= {"gravity", "tank_outflow"}:
        return None
    T = model.scene.duration
    how, f, events = model.outflows[0].exact(T)
    segs = [(0.0, T, vectorized(f))]
    return Flow(how, lambda: (segs, list(events)))


def guided_flow(model: Model, forward: Forward, resolver: Resolver) -> Flow | None:
    """The exact flow of a lone guided body whose guide has one for the listed effects.

    The guide's (:meth:`~mechanics.scenes.state.Guide.exact`): the pendulum from rest,
    the torsion pendulum, the carousel, rolling, the sliding phases.

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`).
    forward : Forward
        Its forward dynamics (:class:`mechanics.scenes.forward.Forward`): not read here.
    resolver : Resolver
        Its impact law (:class:`mechanics.scenes.impacts.Resolver`): not read here.

    Returns
    -------
    Flow or None
        The exact flow, or None where it does not apply.

    Examples
    --------
    A rod released from rest on a fixed axis: the pendulum's flow starts at the initial
    state.

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...     "bodies": [{"name": "rod", "shape": "rod", "mass": 1.0, "length": 1.2,
    ...                 "initial": {"angle": 1.0}}],
    ...     "effects": [{"type": "gravity", "g": 9.81},
    ...                 {"type": "fixed_axis", "body": "rod", "axis": [0.0, 1.0, 0.0],
    ...                  "distance": 0.6, "body_axis": "x"}]}))
    >>> flow = guided_flow(eng.model, eng.forward, eng.resolver)
    >>> flow.how
    'exact: pendulum released from rest, Jacobi elliptic functions (4.50)'
    >>> segs, events = flow.run()
    >>> bool(np.allclose(segs[0][2](0.0), eng.model.y0)), events
    (True, [])
    """
    lay = model.layout
    if not lay.guides or model.n != 1:
        return None
    ((i, gd),) = lay.guides.items()
    o, nq = lay.offsets[i], gd.nq
    q0, qd0 = model.y0[o : o + nq].copy(), model.y0[o + nq : o + 2 * nq].copy()
    others = [e for e in model.effects if not isinstance(e, GuidesBody)]
    found = gd.exact(others, float(model.m0[i]), q0, qd0, model.scene.duration)
    if found is None:
        return None
    how, f, events = found

    @vectorized
    def at(t: Times) -> FloatArray:
        tt = np.asarray(t, dtype=float)
        y = np.zeros((*tt.shape, lay.size))
        q, qd = f(tt)
        y[..., o : o + nq] = np.broadcast_to(q, (*tt.shape, nq))
        y[..., o + nq : o + 2 * nq] = np.broadcast_to(qd, (*tt.shape, nq))
        return y

    return Flow(how, lambda: ([(0.0, model.scene.duration, at)], list(events)))


def pinned_flow(model: Model, forward: Forward, resolver: Resolver) -> Flow | None:
    """The exact flow of a lone top on its fixed point: torque-free, or the heavy symmetric top.

    Torque-free: the elliptic flow about C (:class:`mechanics.tops.FreeAsymmetricTop`,
    5.3); with gravity, the heavy symmetric top (J1 = J2 about C, gravity along −z, θ0
    in (0, π): :class:`mechanics.tops.HeavySymmetricTop`, 5.2).

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`).
    forward : Forward
        Its forward dynamics (:class:`mechanics.scenes.forward.Forward`): not read here.
    resolver : Resolver
        Its impact law (:class:`mechanics.scenes.impacts.Resolver`): not read here.

    Returns
    -------
    Flow or None
        The exact flow, or None where it does not apply.

    Raises
    ------
    OutOfDomainError, ResultOverflowError
        Where :class:`~mechanics.tops.HeavySymmetricTop` refuses the top's values (g =
        1e-300 m/s² against θ̇0 = 1e24 rad/s: its turning points of θ overflow).
    ValueError
        Instead of ResultOverflowError where θ̇0² J'1/mgℓ exceeds float64
        (:class:`~mechanics.tops.HeavySymmetricTop`'s known defect).

    Examples
    --------
    L_3 = J3 ω3 about the symmetry axis is conserved (5.2): the third component of the
    stored L_C (body components, the inertia about C diagonal) stays at its start.

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...     "bodies": [{"name": "top", "shape": "cylinder", "mass": 1.0, "radius": 0.05,
    ...                 "height": 0.02, "initial": {"theta": 0.5, "phi_dot": 100.0}}],
    ...     "effects": [{"type": "gravity", "g": 9.81},
    ...                 {"type": "fixed_point", "body": "top", "distance": 0.1}]}))
    >>> flow = pinned_flow(eng.model, eng.forward, eng.resolver)
    >>> segs, events = flow.run()
    >>> y = segs[0][2](np.array([0.0, 0.5, 1.0]))
    >>> bool(np.allclose(y[0], eng.model.y0)), bool(np.allclose(y[:, 2], eng.model.y0[2]))
    (True, True)
    """
    from mechanics.rotation import matrix_from_euler
    from mechanics.tops import FreeAsymmetricTop, HeavySymmetricTop

    lay, kinds = model.layout, model.kinds
    if not lay.pins or lay.guides or model.n != 1 or not kinds <= {"fixed_point", "gravity"}:
        return None
    ((i, (_, g, JC, _)),) = lay.pins.items()
    Jc = np.diag(JC).copy()  # diagonal: the pivot lies on the principal axis e3
    top: FreeAsymmetricTop | HeavySymmetricTop
    if kinds == {"fixed_point"}:
        try:
            top = FreeAsymmetricTop(Jc, model.w0[i], model.R0[i])
        except OutOfDomainError:
            return None
        how = "exact: torque-free top about C, Jacobi elliptic functions (5.3)"
    else:
        grav = [cast("Gravity", e) for e in model.effects if e.type == "gravity"]
        ini = model.scene.bodies[i].initial
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
            psd, thd, phd = kin.euler_rates_from_angular_velocity(th, ph, model.w0[i])
        except GimbalLockError:  # sin θ0 within rounding of 0: the rates are undefined
            return None
        top = HeavySymmetricTop(
            Jc[0],
            Jc[2],
            model.m0[i] * grav[0].g * g[2],
            theta=th,
            psi=float(ini.get("psi", 0.0)),
            phi=ph,
            theta_dot=thd,
            psi_dot=psd,
            phi_dot=phd,
        )
        how = "exact: heavy symmetric top, elliptic integrals (5.2.2–5.2.5)"
    o = lay.offsets[i]

    @vectorized
    def at(t: Times) -> FloatArray:  # flat states (L_C, R_A_O)
        tt = np.asarray(t, dtype=float)
        if isinstance(top, FreeAsymmetricTop):
            R, w = top.attitude(tt), top.omega(tt)
        else:
            th, ps, ph = top.theta(tt), top.psi(tt), top.phi(tt)
            thd, psd, phd = top.rates(tt)
            R = matrix_from_euler(ps, th, ph)
            w = kin.angular_velocity_from_euler_rates(ps, th, ph, psd, thd, phd)
        y = np.zeros((*tt.shape, lay.size))
        y[..., o : o + 3] = np.einsum("ij,...j->...i", JC, w)
        y[..., o + 3 : o + 12] = np.asarray(R).reshape(*tt.shape, 9)
        return y

    return Flow(how, lambda: ([(0.0, model.scene.duration, at)], []))


def _free_bodies(model: Model) -> bool:
    lay = model.layout
    return not (lay.tanks or lay.guides or lay.pins or lay.fixed_bodies)


def _rotation(model: Model) -> Tops | None:
    """Per spinning rigid body, (J, its torque-free top); None where one cannot be
    followed exactly (a zero moment, within float64's reach of the separatrix, or a
    circulating amplitude below float64's normal range)."""
    from mechanics.tops import FreeAsymmetricTop

    for i in model.rigid:  # torque-free rotation by elliptic functions needs J > 0
        if model.w0[i].any() and not np.all(model.layout.J[i] > 0):
            return None
    out: Tops = {}
    try:
        for i in model.spinning():
            J = model.layout.J[i]
            out[i] = (J, FreeAsymmetricTop(J, model.w0[i], model.R0[i]))
    except OutOfDomainError:  # beyond float64's reach (module docstring): integrate
        return None
    return out


def _spin_note(model: Model) -> str:
    return "; torque-free rotation (Jacobi elliptic functions)" if model.spinning() else ""


def _with_rotation(model: Model, y_trans: npt.ArrayLike, t: Times, tops: Tops) -> FloatArray:
    """Flat states (..., size) whose translation comes from y_trans and rotation from
    the tops, at the time(s) t."""
    y = np.array(y_trans, dtype=float)
    tt = np.asarray(t, dtype=float)
    for i, (J, top) in tops.items():
        o = model.layout.offsets[i]
        y[..., o + 6 : o + 9] = J * top.omega(tt)
        y[..., o + 9 : o + 18] = top.attitude(tt).reshape(*tt.shape, 9)
    return y


def free_flight(model: Model, t0: float, y0: FloatArray, g: FloatArray, tops: Tops) -> Dense:
    """The flat states at any times of free flight under uniform gravity from (t0, y0).

    r = r0 + v0 τ + g τ²/2, v = v0 + g τ (τ = t − t0); each spinning body turned by its
    torque-free top.

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`): its layout.
    t0 : float
        The start time, s.
    y0 : ndarray, shape (size,)
        The flat state at t0 (the layout's ``size``).
    g : ndarray, shape (3,) or (n, 3)
        The uniform gravity, m/s², or each body's acceleration (a resting body's: along
        its plane).
    tops : dict
        Per spinning rigid body (its index), the pair (J, top): its principal moments J
        (kg m², an array of shape (3,)) and its torque-free top
        (:class:`mechanics.tops.FreeAsymmetricTop`); {} for none.

    Returns
    -------
    Dense
        A vectorised function of the time(s) t (s, shape (k,) or scalar) returning the
        flat states, shape (k, size) or (size,); it raises ValueError where ``g`` does
        not broadcast against the bodies' positions (n, 3).

    Raises
    ------
    IndexError
        Where ``y0`` is shorter than the layout's size.

    Examples
    --------
    Two hops of free flight make one: from (1 s, y(1 s)) to 2 s is y(2 s).

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 2.0},
    ...     "bodies": [{"name": "ball", "shape": "point", "mass": 1.0,
    ...                 "initial": {"position": [0.0, 0.0, 5.0]}}]}))
    >>> g = np.array([0.0, 0.0, -2.0])
    >>> at = free_flight(eng.model, 0.0, eng.model.y0, g, {})
    >>> at(2.0).tolist(), free_flight(eng.model, 1.0, at(1.0), g, {})(2.0).tolist()
    ([0.0, 0.0, 1.0, 0.0, 0.0, -4.0], [0.0, 0.0, 1.0, 0.0, 0.0, -4.0])
    """
    lay = model.layout
    r0, v0, L0, R0 = lay.gather(y0)

    @vectorized
    def at(t: Times) -> FloatArray:
        tau = (np.asarray(t, dtype=float) - t0)[..., None, None]
        r = r0 + v0 * tau + 0.5 * g * tau * tau
        v = v0 + g * tau
        L, R = np.broadcast_to(L0, v.shape), np.broadcast_to(R0, (*v.shape, 3))
        return _with_rotation(model, lay.pack(r, v, L, R), t, tops)

    return at


def free_flight_flow(model: Model, forward: Forward, resolver: Resolver) -> Flow | None:
    """The exact flow of free bodies under uniform gravity with smooth impacts of spheres.

    Spheres and points, impacts through their centres: free flight between impacts at
    closed-form instants (:class:`Calendar`, :meth:`~.impacts.Resolver.contact_time`);
    a body resting on a plane slides on it under the part of gravity along it.

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`).
    forward : Forward
        Its forward dynamics (:class:`mechanics.scenes.forward.Forward`).
    resolver : Resolver
        Its impact law (:class:`mechanics.scenes.impacts.Resolver`) and its ``support``
        (the resting contacts).

    Returns
    -------
    Flow or None
        The exact flow, or None where it does not apply.  Its ``run`` raises
        :class:`NotExact` where a body rests on two planes, or rests while its pair
        flies (the engine then integrates), and a SceneError where an impact cannot be
        resolved.

    Raises
    ------
    NonPhysicalInertiaError
        Where :class:`~mechanics.tops.FreeAsymmetricTop` refuses a spinning body's
        moments that the parser accepted (J = (1e-300, 2e-300, 3e-300) kg m²: J1 + J2
        rounds below J3).

    Examples
    --------
    A ball 5 m above the floor under g = 10 m/s² lands after √(2h/g) = 1 s at 10 m/s and
    leaves it at e × 10 = 5 m/s:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 2.0},
    ...     "bodies": [{"name": "ball", "shape": "solid_sphere", "mass": 1.0, "radius": 0.5,
    ...                 "initial": {"position": [0.0, 0.0, 5.5]}}],
    ...     "effects": [{"type": "gravity", "g": 10.0},
    ...                 {"type": "impact", "body": "ball", "plane_point": [0.0, 0.0, 0.0],
    ...                  "plane_normal": [0.0, 0.0, 1.0], "restitution": 0.5}]}))
    >>> segs, events = free_flight_flow(eng.model, eng.forward, eng.resolver).run()
    >>> [(ev.t, ev.detail["normal_speed_after"]) for ev in events], (2 * 5.0 / 10.0) ** 0.5
    ([(1.0, 5.0)], 1.0)
    """
    kinds = model.kinds
    if not _free_bodies(model) or not kinds <= {"gravity", "impact"}:
        return None
    if not all(
        ft.at is None and ft.support is None and imp.mu_f == 0
        for imp in model.impacts
        for ft in imp.features
    ):
        return None
    tops = _rotation(model)
    if tops is None:
        return None
    what = "free flight under uniform gravity" if "gravity" in kinds else "uniform motion"
    if "impact" in kinds:
        what += ", impacts solved in closed form"
    T_end = model.scene.duration
    support = resolver.support

    def run() -> tuple[list[Segment], list[Event]]:
        g0 = model.uniform_gravity()
        segs: list[Segment] = []
        events: list[Event] = []
        t0, y = 0.0, model.y0.copy()
        cal = Calendar(model, resolver)
        among: IntArray | None = None  # the pairs whose next contact is to be computed (None: all)
        rests: set[Impact] | None = None
        while True:
            held = set(support.rests) if support is not None else set()
            g = _resting_gravity(model, support, g0)
            s = forward.snapshot(t0, y)
            if held != rests:  # a body began or ceased to rest: its motion changed
                among, rests = None, held
                cal.uniform(g)
            cal.refresh(t0, s, g, among, held)
            while True:  # the earliest contact that is no mere touch
                a, t1 = cal.earliest()
                if t1 == math.inf:
                    break
                imp = model.impacts[a]
                ft = imp.features[0]
                tau = resolver.contact_time(imp, ft, s, g)  # its touch test, from now
                if tau < math.inf:
                    t1 = t0 + tau
                    break
                cal.times[a] = math.inf  # touches only (no approach there): no impact
            segs.append((t0, min(t1, T_end), free_flight(model, t0, y, g, tops)))
            if t1 >= T_end:
                break
            y = segs[-1][2](t1)
            before = np.concatenate(model.layout.gather(y)[:2], axis=-1)
            y = resolver.resolve(t1, y, imp, ft, events, _flight_scale(imp, ft, s, g, t1 - t0))
            # the bodies whose motion the instant changed: their pairs' next contacts
            after = np.concatenate(model.layout.gather(y)[:2], axis=-1)
            moved = np.nonzero(np.any(after != before, axis=-1))[0]
            among = cal.pairs_of(moved)
            t0 = t1
        return segs, events

    return Flow(f"exact: {what}{_spin_note(model)}", run)


class Calendar:
    """The next contact time of every impact pair in free flight, kept between events.

    Spheres and points, smooth.  An impact changes only its bodies' motion, so after
    one only the pairs of the bodies it moved are computed again (vectorised:
    :func:`.contacts.plane_contact_times`, :func:`.contacts.sphere_contact_times`), the
    others' times stand.  Per event that is O(n) pairs for n bodies, not O(n²); the
    earliest is found by one argmin over all of them.  The constructor arranges the
    model's impacts into arrays (every time inf until :meth:`refresh`).

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`) whose ``impacts``
        (spheres and points, one feature each) are followed.
    resolver : Resolver
        Its impact law (:class:`mechanics.scenes.impacts.Resolver`): not read here.

    Examples
    --------
    A ball 5 m above the floor under g = 10 m/s² touches it after √(2h/g) = 1 s:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 2.0},
    ...     "bodies": [{"name": "ball", "shape": "solid_sphere", "mass": 1.0, "radius": 0.5,
    ...                 "initial": {"position": [0.0, 0.0, 5.5]}}],
    ...     "effects": [{"type": "gravity", "g": 10.0},
    ...                 {"type": "impact", "body": "ball", "plane_point": [0.0, 0.0, 0.0],
    ...                  "plane_normal": [0.0, 0.0, 1.0], "restitution": 0.5}]}))
    >>> cal = Calendar(eng.model, eng.resolver)
    >>> s0 = eng.forward.snapshot(0.0, eng.model.y0)
    >>> cal.refresh(0.0, s0, np.array([[0.0, 0.0, -10.0]]), None, set())
    >>> cal.earliest(), (2 * 5.0 / 10.0) ** 0.5
    ((0, 1.0), 1.0)
    """

    def __init__(self, model: Model, resolver: Resolver) -> None:
        self.model = model
        imps = model.impacts
        self.times = np.full(len(imps), math.inf)
        plane = [a for a, imp in enumerate(imps) if imp.j is None]
        pair = [a for a, imp in enumerate(imps) if imp.j is not None]
        self.plane, self.pair = np.array(plane, dtype=int), np.array(pair, dtype=int)
        self.p_body = np.array([imps[a].i for a in plane], dtype=int)
        self.p_normal = np.array([imps[a].normal for a in plane]).reshape(-1, 3)
        self.p_point = np.array([imps[a].point for a in plane]).reshape(-1, 3)
        self.p_radius = np.array([imps[a].features[0].a for a in plane])
        self.q_i = np.array([imps[a].i for a in pair], dtype=int)
        self.q_j = np.array([imps[a].j for a in pair], dtype=int)
        self.q_size = np.array([imps[a].features[0].a + imps[a].features[0].a_s for a in pair])
        #: impact position -> its row in the plane or the pair arrays
        self.row = np.zeros(len(imps), dtype=int)
        self.row[self.plane] = np.arange(len(plane))
        self.row[self.pair] = np.arange(len(pair))
        self.is_pair = np.zeros(len(imps), dtype=bool)
        self.is_pair[self.pair] = True
        self.position = {id(imp): a for a, imp in enumerate(imps)}

    def uniform(self, g: FloatArray) -> None:
        """A pair's relative motion must be uniform (the same g on both): else, one of
        them resting on a plane while the other flies, it is not followed."""
        bad = np.any(g[self.q_i] != g[self.q_j], axis=-1)
        if bad.any():
            imp = self.model.impacts[self.pair[np.argmax(bad)]]
            raise NotExact(
                f"{imp.label}: one of them rests on a plane while the other flies "
                "(their relative motion is no longer uniform)"
            )

    def pairs_of(self, bodies: IntArray) -> IntArray:
        """The positions of the impacts of these bodies."""
        of = self.model.impacts_of
        return np.array(sorted({a for k in bodies for a in of.get(int(k), ())}), dtype=int)

    def refresh(
        self, t0: float, s: Snapshot, g: FloatArray, among: IntArray | None, held: set[Impact]
    ) -> None:
        """The next contact times, from the snapshot ``s`` at t0, of the impacts
        ``among`` (None: all); a resting pair (``held``) has none."""
        among = np.arange(len(self.times)) if among is None else among
        planes = among[~self.is_pair[among]]
        pairs = among[self.is_pair[among]]
        r, v = s.r, s.v
        if planes.size:
            k = self.row[planes]
            b, n = self.p_body[k], self.p_normal[k]
            gap = np.einsum("ij,ij->i", r[b] - self.p_point[k], n) - self.p_radius[k]
            tau = contacts.plane_contact_times(
                gap, np.einsum("ij,ij->i", v[b], n), np.einsum("ij,ij->i", g[b], n)
            )
            self.times[planes] = t0 + tau
        if pairs.size:
            k = self.row[pairs]
            i, j = self.q_i[k], self.q_j[k]
            tau = contacts.sphere_contact_times(r[i] - r[j], v[i] - v[j], self.q_size[k])
            self.times[pairs] = t0 + tau
        for imp in held:  # resting: held on its plane
            self.times[self.position[id(imp)]] = math.inf

    def earliest(self) -> tuple[int, float]:
        """The impact with the earliest next contact and its time."""
        a = int(np.argmin(self.times)) if self.times.size else 0
        return a, float(self.times[a]) if self.times.size else math.inf


class NotExact(Exception):
    """An exact flow meets, on its way, what it cannot follow in closed form (the
    engine integrates instead, where the scene's method allows)."""


def _flight_scale(imp: Impact, ft: Feature, s: Snapshot, g: FloatArray, tau: float) -> float:
    """The size the gap of ``ft`` is rounded relative to after a free flight of ``tau``
    from the snapshot s: its size at the start (:meth:`.effects.impact.Impact.gap_scale`)
    plus each body's terms v τ and ½ g τ² (a point reaching the floor z = 0 from z₀ has a
    gap rounded relative to z₀, not to its own size there, found by the rigid-motion
    property: a gap of 1.1e-16 against a size of 2.2e-16)."""
    moved = sum(
        float(np.abs(s.v[k]).sum()) * tau + 0.5 * float(np.abs(g[k]).sum()) * tau * tau
        for k in imp.bodies()
    )
    return imp.gap_scale(s, ft) + moved


def _resting_gravity(model: Model, support: Support | None, g0: FloatArray) -> FloatArray:
    """Each body's acceleration (n, 3): g, or for a body resting on a smooth plane of
    normal n its part along the plane, g − (g·n) n (the support takes the rest)."""
    g = np.broadcast_to(g0, (model.n, 3)).copy()
    held: dict[int, int] = {}
    for imp in support.rests if support is not None else ():
        held[imp.i] = held.get(imp.i, 0) + 1
        if held[imp.i] > 1:
            raise NotExact(f"body {model.names[imp.i]!r} rests on two planes")
        g[imp.i] -= (g0 @ imp.normal) * imp.normal
    return g


def rocket_flow(model: Model, forward: Forward, resolver: Resolver) -> Flow | None:
    """The exact flow of free bodies with only gravity and space-fixed thrust: the rocket (7.30).

    The thrust's height and speed (:func:`mechanics.open_systems.rocket_height`,
    :func:`~mechanics.open_systems.rocket_velocity`, coasting after burn-out) added to
    the free flight; a ``burn_out`` event at each burn-out within the duration.  Not for
    a thrust in body axes.

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`).
    forward : Forward
        Its forward dynamics (:class:`mechanics.scenes.forward.Forward`): not read here.
    resolver : Resolver
        Its impact law (:class:`mechanics.scenes.impacts.Resolver`): not read here.

    Returns
    -------
    Flow or None
        The exact flow, or None where it does not apply.

    Raises
    ------
    NonPhysicalInertiaError
        Where :class:`~mechanics.tops.FreeAsymmetricTop` refuses a spinning body's
        moments that the parser accepted (J = (1e-300, 2e-300, 3e-300) kg m²: J1 + J2
        rounds below J3).

    Examples
    --------
    800 kg of fuel burnt at 10 kg/s: the burn-out comes at m_f/q = 80 s.

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 100.0},
    ...     "bodies": [{"name": "rocket", "shape": "point", "mass": 1000.0}],
    ...     "effects": [{"type": "gravity", "g": 9.81},
    ...                 {"type": "thrust", "body": "rocket", "mass_flow": 10.0,
    ...                  "exhaust_speed": 2000.0, "fuel_mass": 800.0,
    ...                  "direction": [0.0, 0.0, 1.0]}]}))
    >>> segs, events = rocket_flow(eng.model, eng.forward, eng.resolver).run()
    >>> [(ev.kind, ev.t) for ev in events], 800.0 / 10.0
    ([('burn_out', 80.0)], 80.0)
    """
    from mechanics.open_systems import rocket_height, rocket_velocity

    kinds = model.kinds
    if not _free_bodies(model) or not kinds <= {"gravity", "thrust"}:
        return None
    burns = cast("list[Thrust]", [e for e in model.effects if e.type == "thrust"])
    thrusts = {th.i: th for th in burns}
    if any(th.body_frame for th in thrusts.values()):
        return None
    tops = _rotation(model)
    if tops is None:
        return None
    lay = model.layout

    def run() -> tuple[list[Segment], list[Event]]:
        g = model.uniform_gravity()
        r0, v0, L0, R0 = lay.gather(model.y0)

        @vectorized
        def at(t: Times) -> FloatArray:
            tt = np.asarray(t, dtype=float)
            tau = tt[..., None, None]
            r = r0 + v0 * tau + 0.5 * g * tau * tau
            v = v0 + g * tau
            for i, th in thrusts.items():
                kw = dict(
                    m_0=model.m0[i], q=th.q, u=th.u, m_f=th.m_f, g=0.0, after_burn_out="coast"
                )
                r[..., i, :] += np.asarray(rocket_height(tt, **kw))[..., None] * th.direction
                v[..., i, :] += np.asarray(rocket_velocity(tt, **kw))[..., None] * th.direction
            L, R = np.broadcast_to(L0, v.shape), np.broadcast_to(R0, (*v.shape, 3))
            return _with_rotation(model, lay.pack(r, v, L, R), t, tops)

        events = [
            Event(th.burn_out, "burn_out", {"body": model.names[th.i]})
            for th in thrusts.values()
            if th.burn_out <= model.scene.duration
        ]
        return [(0.0, model.scene.duration, at)], events

    return Flow(f"exact: rocket flight (7.30) with uniform gravity{_spin_note(model)}", run)


#: the providers, each applying to scenes none of the others does
PROVIDERS = (tank_flow, guided_flow, pinned_flow, free_flight_flow, rocket_flow)


def find(model: Model, forward: Forward, resolver: Resolver) -> Flow | None:
    """The exact flow of the scene, or None where it has none here.

    The first of :data:`PROVIDERS` that applies (at most one does).

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`).
    forward : Forward
        Its forward dynamics (:class:`mechanics.scenes.forward.Forward`).
    resolver : Resolver
        Its impact law (:class:`mechanics.scenes.impacts.Resolver`).

    Returns
    -------
    Flow or None
        The exact flow, or None where no provider applies.

    Raises
    ------
    MechanicsValueError
        Where a provider's closed form refuses the scene's values (:func:`tank_flow`,
        :func:`pinned_flow`, :func:`free_flight_flow`, :func:`rocket_flow` say which);
        :func:`mechanics.scenes.simulate.simulate` reports it as a SceneError.
    ValueError
        Instead of ResultOverflowError from :func:`pinned_flow` (the known defect there).

    Examples
    --------
    A point under gravity has the free flight; with quadratic drag it has none:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> def engine(*effects):
    ...     return Engine(parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...         "bodies": [{"name": "ball", "shape": "point", "mass": 1.0}],
    ...         "effects": [{"type": "gravity", "g": 9.81}, *effects]}))
    >>> eng = engine()
    >>> find(eng.model, eng.forward, eng.resolver).how
    'exact: free flight under uniform gravity'
    >>> eng = engine({"type": "drag", "body": "ball", "quadratic": 0.01})
    >>> find(eng.model, eng.forward, eng.resolver) is None
    True
    """
    for provider in PROVIDERS:
        flow = provider(model, forward, resolver)
        if flow is not None:
            return flow
    return None
