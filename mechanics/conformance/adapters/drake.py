"""Drake under the conformance battery: ``DrakeAdapter(mode, contact)``.

``pip install 'bodycheck[drake]'``.  The model is a ``MultibodyPlant`` built in code
from the :class:`~mechanics.conformance.protocol.Scenario` and run by a ``Simulator``;
this module imports without Drake, constructing the adapter without it raises
:class:`MissingExtraError` naming the extra.

Conventions (Drake against the book)
------------------------------------
- **Attitude.**  ``EvalBodyPoseInWorld`` gives the ``RigidTransform`` X_WB; its
  ``rotation()`` is R_WB, the *active* matrix whose columns are the body axes in world
  (space) components: R_WB = (^A R^O)ᵀ.  Drake's ``Quaternion`` (a free body's
  ``q[0:4]``) is scalar first (w, x, y, z) and active, like :mod:`mechanics.rotation`'s.
- **Velocities.**  ``EvalBodySpatialVelocityInWorld`` gives V_WB = (w_WB, v_WBo), both
  in *world* components; the body origin Bo is put at G (``SpatialInertia.
  MakeFromCentralInertia`` with p_BoBcm = 0 and the scenario's principal moments about
  G in body axes), so v_WBo = v_G, and the adapter returns ω_A = ^A R^O w_WB.  Drake
  uses the scenario's mass and inertia as given (no shape-derived inertia); the
  adapter reads back ``default_mass`` and ``default_rotational_inertia`` and fails
  loudly if they differ.
- **Free bodies** float on Drake's default ``QuaternionFloatingJoint`` (no
  singularity), set by ``SetFreeBodyPose`` and ``SetFreeBodySpatialVelocity``.
- **Shapes**: ``Sphere(r)``, ``Box(2a, 2b, 2c)`` (full widths), ``Cylinder(r, 2h)``
  along the body's axis 3; the ground a ``HalfSpace`` posed by ``HalfSpace.MakePose``
  (its normal is the scenario's).
- **Pivot**: Drake 1.51 has no quaternion ball joint, only ``BallRpyJoint``:
  R_FM = Rz(y) Ry(p) Rx(r), singular where the pitch is ±π/2, i.e. where M's x axis
  lies along F's z axis.  The adapter puts F at the anchor with its z axis along
  gravity (space z without gravity) and M at the pivot with its x axis along the line
  from the pivot to G, so the singular configurations are the line vertical: a top
  upright or hanging straight down.  A scenario that starts there is unsupported; a
  motion that passes near it loses the joint's accuracy there (a top nutating between
  0 < θ₁ ≤ θ ≤ θ₂ < π never does).  A pivot at G itself takes body axis 1 as M's x.

Restitution: Hunt–Crossley dissipation, where no e exists
---------------------------------------------------------
Drake's compliant contact presses with f = k x (1 + d ẋ) (point contact, x the
penetration; the hydroelastic pressure has the same factor (1 + d ẋ)), smooth here
(``CoulombFriction(0, 0)``).  A Hunt–Crossley contact has no coefficient of restitution
of its own: for the linear spring of point contact, with no other force during the
contact, the phase plane u du/dx = −ω² x (1 + d u) integrates to
c u − ln(1 + c u) = const (c = d v, u = ẋ/v), so the body leaves at −e v with

    ln((1 + c)/(1 − c e)) = c (1 + e),     c = d v        (to first order c = (3/2)(1 − e)),

whatever k and m (:func:`hunt_crossley_dissipation` solves it for c).  The restitution
thus depends on the impact speed v; the adapter sets d = c(e)/v_ref with v_ref the
scenario's nominal approach speed (the speed at which a body falling from its initial
state reaches the ground, or the initial relative speed of a pair; 1 m/s where that is
zero), and the battery reports the effective e *measured*: gravity acting during the
contact, another impact speed, or the hydroelastic force law (not linear in x) move it.
Drake combines the d of the two geometries in contact; each geometry gets the mean d
of the contacts it takes part in (exact for one body on the ground).

Stiffness: ``point_stiffness`` is left to the plant, which derives it from its
``penetration_allowance`` (1 mm); the hydroelastic modulus is :data:`HYDRO_MODULUS`
(a hard rubber), the ground rigid (Drake refuses compliant-against-compliant contact
with a half space, and falls back to point contact without saying so).

Modes (:func:`variants`)
------------------------
- ``mode="discrete"``: ``time_step`` = the battery's step (``takes_step = True``),
  Drake's default discrete contact approximation (``"lagged"``, which keeps the
  Hunt–Crossley dissipation); the discrete multibody update is first order.
- ``mode="continuous"``: ``time_step = 0``, integrated by the ``Simulator``'s default
  error-controlled integrator (Runge–Kutta 3 with an embedded second-order error
  estimate) at target accuracy :data:`CONTINUOUS_ACCURACY`; ``takes_step = False``.
- ``contact="point"`` or ``"hydroelastic"`` (``contact_model =
  "hydroelastic_with_fallback"``).

What Drake cannot express here
------------------------------
A :class:`~mechanics.conformance.protocol.Thrust` (masses are fixed parameters of the
plant; a constant-mass force is not the rocket of (7.30)); a pivot whose line to G
starts along gravity (the RPY joint's singularity).
"""

from __future__ import annotations

import logging
import math
from typing import Any

import numpy as np

from ..._floats import EPS
from ..._validate import as_positive_scalar
from ...errors import (
    MechanicsValueError,
    NonPositiveParameterError,
    RestitutionRangeError,
    ResultOverflowError,
)
from ..protocol import ConformanceError, Scenario, Trajectory
from ._engines import (
    MissingExtraError,
    body_rows,
    check_option,
    common_unsupported,
    require,
    step_counts,
    unit_interval,
)

__all__ = [
    "CONTACTS",
    "CONTINUOUS_ACCURACY",
    "E_FLOOR",
    "HYDRO_MODULUS",
    "MODES",
    "DrakeAdapter",
    "MissingExtraError",
    "hunt_crossley_dissipation",
    "variants",
]

MODES = ("discrete", "continuous")
CONTACTS = ("point", "hydroelastic")
#: the continuous mode's target accuracy (Drake's default is 1e-3 for RK3; 1e-8 makes
#: the smooth scenarios comparable with the fixed-step engines at fine steps)
CONTINUOUS_ACCURACY = 1e-8
#: hydroelastic modulus of every body (Pa): a hard rubber
HYDRO_MODULUS = 1e7
#: the resolution hint of the bodies' compliant meshes (m)
RESOLUTION_HINT = 0.01
#: the pivot's line to G may not start closer than this to gravity's direction (rad):
#: the RPY joint's pitch would start within 1e-3 of ±π/2
PIVOT_SINGULAR_ANGLE = 1e-3
#: e = 0 needs an infinite dissipation; it is given the d of this e (c ≈ 1/e = 2^20)
E_FLOOR = 2.0**-20
#: the inertia read back from the plant: stored as given, 4 eps for one conversion
INERTIA_RTOL = 4 * EPS


def hunt_crossley_dissipation(e: float, v_ref: float) -> float:
    """The Hunt–Crossley dissipation d (s/m) with which a contact hit at v_ref lets go at e·v_ref.

    The contact is a linear spring f = k x (1 + d ẋ); d = c/v_ref with
    ln((1 + c)/(1 − c e)) = c (1 + e), c in (0, 1/e) (module docstring), solved by
    bisection to the last bit.  e = 0 would need d = ∞: it is given the d of
    e = :data:`E_FLOOR`.

    Domain: e in [0, 1], v_ref > 0 and finite (each refused by name otherwise); a
    v_ref so small that d overflows is a ResultOverflowError.

    Parameters
    ----------
    e : float
        The coefficient of restitution, in [0, 1].
    v_ref : float
        The approach speed the contact is tuned for, m/s, > 0, finite.

    Returns
    -------
    float
        d, s/m, ≥ 0 (0 at e = 1).

    Raises
    ------
    RestitutionRangeError
        Where e is outside [0, 1].
    NonPositiveParameterError
        Where v_ref ≤ 0.
    NonFiniteError
        Where e or v_ref is a NaN or an infinity.
    ShapeError
        Where e or v_ref is not a scalar.
    ResultOverflowError
        Where v_ref is so small that d = c/v_ref overflows.

    Examples
    --------
    The first order, c = (3/2)(1 − e), near e = 1; and the law itself:

    >>> c = hunt_crossley_dissipation(0.999, 1.0)
    >>> abs(c / (1.5 * 0.001) - 1) < 2e-3
    True
    >>> c, e = hunt_crossley_dissipation(0.5, 1.0), 0.5
    >>> abs(math.log((1 + c) / (1 - c * e)) - c * (1 + e)) < 1e-15
    True
    """
    e = unit_interval(e, "e", "a coefficient of restitution", error=RestitutionRangeError)
    v_ref = as_positive_scalar(v_ref, "v_ref")
    if e == 1.0:
        return 0.0
    e = max(e, E_FLOOR)
    lo, hi = 0.0, 1.0 / e  # φ(c) = ln((1 + c)/(1 − c e)) − c (1 + e): < 0 near 0, → ∞ at 1/e
    while True:
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            d = mid / v_ref
            if not math.isfinite(d):
                raise ResultOverflowError(
                    f"hunt_crossley_dissipation: d = c/v_ref overflows for v_ref = {v_ref!r}"
                )
            return d
        if math.log1p(mid) - math.log1p(-mid * e) - mid * (1.0 + e) < 0.0:
            lo = mid
        else:
            hi = mid


def variants() -> list[DrakeAdapter]:
    """The variants the battery runs side by side: both modes, both contact models.

    Returns
    -------
    list of Adapter
        One adapter per variant, in the order of the table.

    Raises
    ------
    MissingExtraError
        When the engine is not installed (naming what installs it).

    Examples
    --------
    The variants are the product of the options (checked where the engine is installed):

    >>> try:
    ...     got = [repr(a) for a in variants()]
    ... except MissingExtraError:  # not installed: nothing to compare
    ...     got = None
    >>> got in (None, [f"DrakeAdapter({m!r}, {c!r})" for m in MODES for c in CONTACTS])
    True
    """
    return [DrakeAdapter(m, c) for m in MODES for c in CONTACTS]


def _support_distance(shape, R_A_O: np.ndarray, n: np.ndarray) -> float:
    """How far the shape reaches from G along −n (its lowest point over a plane of
    normal n): the support function of the shape in direction n."""
    nb = R_A_O @ n  # the normal in body components
    if shape.kind == "sphere":
        return float(shape.dims[0])
    if shape.kind == "box":
        return float(np.abs(nb) @ np.asarray(shape.dims, dtype=float))
    r, h = shape.dims
    return float(r * math.sqrt(max(0.0, 1.0 - nb[2] ** 2)) + h * abs(nb[2]))


def _approach_speeds(scenario: Scenario) -> list[tuple[int, int, float, float]]:
    """(i, j, e, v_ref) for every contact: j = -1 for the ground."""
    out = []
    r, v, R, _ = body_rows(scenario)
    g = np.asarray(scenario.gravity, dtype=float)
    if scenario.ground is not None:
        n = np.asarray(scenario.ground.normal, dtype=float)
        n = n / np.linalg.norm(n)
        gn = max(0.0, -float(g @ n))  # gravity's pull toward the ground
        for k, b in enumerate(scenario.bodies):
            if b.shape is None or (scenario.pivot is not None and scenario.pivot.body == k):
                continue
            gap = max(0.0, float(n @ r[k]) - scenario.ground.height)
            gap = max(0.0, gap - _support_distance(b.shape, R[k], n))
            vn = float(v[k] @ n)
            v2 = vn * vn + 2 * gn * gap if vn < 0 or gn > 0 else 0.0
            out.append((k, -1, scenario.ground.restitution, math.sqrt(v2)))
    for i, j, e in scenario.pair_restitution:
        out.append((i, j, e, float(np.linalg.norm(v[i] - v[j]))))
    return [(i, j, e, s if s > 0 else 1.0) for i, j, e, s in out]


#: Drake logs this on every half space registered with proximity properties: it concerns
#: deformable bodies, which no scenario has; every other message of Drake's stays
_DEFORMABLE_NOTICE = "half spaces are not currently supported for deformable contact"


class _DropDeformableNotice(logging.Filter):
    def filter(self, record: logging.LogRecord) -> bool:
        return _DEFORMABLE_NOTICE not in record.getMessage()


def _quiet_deformable_notice() -> None:
    """Drop :data:`_DEFORMABLE_NOTICE` from Drake's Python logger (once)."""
    log = logging.getLogger("drake")
    if not any(isinstance(f, _DropDeformableNotice) for f in log.filters):
        log.addFilter(_DropDeformableNotice())


class DrakeAdapter:
    """Drake's MultibodyPlant, discrete or continuous, point or hydroelastic contact.

    Parameters
    ----------
    mode : {"discrete", "continuous"}
        Drake's plant: discrete at the battery's step, or continuous (module docstring);
        default ``"discrete"``.
    contact : {"point", "hydroelastic"}
        The contact model (default ``"point"``).

    Raises
    ------
    UnknownOptionError
        Where ``mode`` or ``contact`` is not one of the above.
    MissingExtraError
        When the ``drake`` package is not installed.

    Examples
    --------
    >>> DrakeAdapter("implicit")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.errors.UnknownOptionError: Drake mode must be one of (...); got 'implicit'
    """

    def __init__(self, mode: str = "discrete", contact: str = "point"):
        self.mode = check_option(mode, MODES, "Drake mode")
        self.contact = check_option(contact, CONTACTS, "Drake contact")
        self._pd = require("pydrake.all", "drake")
        _quiet_deformable_notice()
        self.takes_step = mode == "discrete"
        how = (
            "discrete (lagged)"
            if mode == "discrete"
            else f"continuous (RK3, accuracy {CONTINUOUS_ACCURACY:g})"
        )
        self.name = f"Drake {_version()} {how}, {contact} contact"

    def __repr__(self) -> str:
        return f"DrakeAdapter({self.mode!r}, {self.contact!r})"

    def supports(self, scenario: Scenario) -> str | None:
        """``None``, or why Drake cannot run ``scenario``."""
        why = common_unsupported(scenario)
        if why is not None or scenario.pivot is None:
            return why
        p = scenario.pivot
        arm = -np.asarray(p.point, dtype=float)
        if np.linalg.norm(arm) > 0:
            R = np.asarray(scenario.bodies[p.body].R_A_O, dtype=float)
            arm_O = R.T @ arm
            down = self._down(scenario)
            c = abs(float(arm_O @ down)) / float(np.linalg.norm(arm_O))
            s = math.sqrt(max(0.0, 1.0 - c * c))
            if math.atan2(s, c) < PIVOT_SINGULAR_ANGLE:
                return (
                    "the pivot's line to G starts along gravity, where Drake's only ball "
                    "joint (BallRpyJoint, roll-pitch-yaw) is singular"
                )
        return None

    @staticmethod
    def _down(scenario: Scenario) -> np.ndarray:
        g = np.asarray(scenario.gravity, dtype=float)
        if np.linalg.norm(g) > 0:
            return g / np.linalg.norm(g)
        return np.array([0.0, 0.0, 1.0])

    # ------------------------------------------------------------------ model

    def _properties(self, d: float, *, half_space: bool = False):
        pd = self._pd
        props = pd.ProximityProperties()
        pd.AddContactMaterial(
            dissipation=d,
            point_stiffness=None,
            friction=pd.CoulombFriction(0.0, 0.0),
            properties=props,
        )
        if self.contact == "hydroelastic":
            if half_space:  # compliant against compliant is refused for a half space
                pd.AddRigidHydroelasticProperties(props)
            else:
                pd.AddCompliantHydroelasticProperties(RESOLUTION_HINT, HYDRO_MODULUS, props)
        return props

    def _geometry(self, shape):
        pd = self._pd
        if shape.kind == "sphere":
            return pd.Sphere(shape.dims[0])
        if shape.kind == "box":
            a, b, c = shape.dims
            return pd.Box(2 * a, 2 * b, 2 * c)
        r, h = shape.dims
        return pd.Cylinder(r, 2 * h)

    def build(self, scenario: Scenario, step: float | None):
        """(simulator, plant, bodies) of ``scenario`` in its initial state."""
        pd = self._pd
        builder = pd.DiagramBuilder()
        if self.mode != "discrete":
            time_step = 0.0
        elif step is None:
            raise NonPositiveParameterError(
                f"scenario {scenario.name!r}: the discrete plant needs a step > 0; got None"
            )
        else:
            time_step = float(step)
        config = pd.MultibodyPlantConfig(
            time_step=time_step,
            contact_model="point" if self.contact == "point" else "hydroelastic_with_fallback",
        )
        plant, scene_graph = pd.AddMultibodyPlant(config, builder)
        plant.mutable_gravity_field().set_gravity_vector(np.asarray(scenario.gravity, float))
        # one dissipation per body (and the ground): Drake combines a pair's two values,
        # equal ones give that value; a body in contacts of different d takes the mean
        per_body: dict[int, list[float]] = {}
        for i, j, e, v_ref in _approach_speeds(scenario):
            d = hunt_crossley_dissipation(e, v_ref)
            for k in (i, j):
                per_body.setdefault(k, []).append(d)
        bodies = []
        for k, b in enumerate(scenario.bodies):
            J = pd.RotationalInertia(*(float(x) for x in b.inertia))
            M = pd.SpatialInertia.MakeFromCentralInertia(float(b.mass), np.zeros(3), J)
            body = plant.AddRigidBody(f"b{k}", M)
            if b.shape is not None:
                d = float(np.mean(per_body.get(k, [0.0])))
                plant.RegisterCollisionGeometry(
                    body, pd.RigidTransform(), self._geometry(b.shape), f"g{k}", self._properties(d)
                )
            bodies.append(body)
        if scenario.ground is not None:
            n = np.asarray(scenario.ground.normal, dtype=float)
            n = n / np.linalg.norm(n)
            X = pd.HalfSpace.MakePose(n, scenario.ground.height * n)
            d = float(np.mean(per_body.get(-1, [0.0])))
            plant.RegisterCollisionGeometry(
                plant.world_body(),
                X,
                pd.HalfSpace(),
                "ground",
                self._properties(d, half_space=True),
            )
        # the pivot's body, its BallRpyJoint and the joint's frames R_WF, R_BM
        ball: tuple[int, Any, np.ndarray, np.ndarray] | None = None
        r, v, R, w = body_rows(scenario)
        if scenario.pivot is not None:
            ball = (scenario.pivot.body, *self._ball_joint(pd, plant, scenario, bodies))
        # only the scenario's contacts: filter the pairs it does not list
        listed = {(i, j) for i, j, _ in scenario.pair_restitution}
        shaped = [k for k, b in enumerate(scenario.bodies) if b.shape is not None]
        plant.Finalize()
        sgi = scene_graph.collision_filter_manager()
        for x in shaped:
            for y in shaped:
                if x < y and (x, y) not in listed:
                    ids = [plant.GetBodyFrameIdOrThrow(bodies[z].index()) for z in (x, y)]
                    sgi.Apply(pd.CollisionFilterDeclaration().ExcludeWithin(pd.GeometrySet(ids)))
        diagram = builder.Build()
        sim = pd.Simulator(diagram)
        ctx = plant.GetMyMutableContextFromRoot(sim.get_mutable_context())
        for k, b in enumerate(scenario.bodies):
            mass = bodies[k].default_mass()
            Jd = np.diag(bodies[k].default_rotational_inertia().CopyToFullMatrix3())
            J = np.asarray(b.inertia, dtype=float)
            if (
                abs(mass - b.mass) > INERTIA_RTOL * b.mass
                or np.abs(Jd - J).max() > INERTIA_RTOL * J.max()
            ):
                raise ConformanceError(
                    f"scenario {scenario.name!r}: Drake holds body {b.name!r} with mass "
                    f"{mass!r} and inertia {Jd}, not the scenario's {b.mass!r}, {J}"
                )
            if ball is not None and ball[0] == k:
                _, joint, R_WF, R_BM = ball
                R_FM = R_WF.T @ R[k].T @ R_BM
                joint.set_angles(ctx, pd.RollPitchYaw(pd.RotationMatrix(R_FM)).vector())
                joint.set_angular_velocity(ctx, R_WF.T @ (R[k].T @ w[k]))
            else:
                X_WB = pd.RigidTransform(pd.RotationMatrix(R[k].T), r[k])
                plant.SetFreeBodyPose(ctx, bodies[k], X_WB)
                plant.SetFreeBodySpatialVelocity(
                    ctx, bodies[k], pd.SpatialVelocity(R[k].T @ w[k], v[k])
                )
        if self.mode == "continuous":
            sim.get_mutable_integrator().set_target_accuracy(CONTINUOUS_ACCURACY)
        sim.Initialize()
        return sim, plant, bodies

    def _ball_joint(self, pd, plant, scenario, bodies):
        """A BallRpyJoint whose singular pitch is the pivot-to-G line along gravity."""
        p = scenario.pivot
        arm_B = -np.asarray(p.point, dtype=float)  # pivot to G, body components
        x_B = arm_B / np.linalg.norm(arm_B) if np.linalg.norm(arm_B) > 0 else np.eye(3)[0]
        R_BM = _frame_with_axis(x_B, 0)  # columns: M's axes in body components
        R_WF = _frame_with_axis(self._down(scenario), 2)
        F = plant.AddFrame(
            pd.FixedOffsetFrame(
                "pivot_F",
                plant.world_frame(),
                pd.RigidTransform(pd.RotationMatrix(R_WF), np.asarray(p.anchor, float)),
            )
        )
        M = plant.AddFrame(
            pd.FixedOffsetFrame(
                "pivot_M",
                bodies[p.body].body_frame(),
                pd.RigidTransform(pd.RotationMatrix(R_BM), np.asarray(p.point, float)),
            )
        )
        joint = plant.AddJoint(pd.BallRpyJoint("pivot", F, M))
        return joint, R_WF, R_BM

    # ------------------------------------------------------------------ run

    def _read(self, plant, ctx, bodies):
        out = []
        for body in bodies:
            X = plant.EvalBodyPoseInWorld(ctx, body)
            V = plant.EvalBodySpatialVelocityInWorld(ctx, body)
            R_A_O = X.rotation().matrix().T
            out.append((X.translation(), V.translational(), R_A_O, R_A_O @ V.rotational()))
        return [np.array(c) for c in zip(*out, strict=True)]

    def run(self, scenario: Scenario, step: float | None) -> Trajectory:
        """The trajectory at ``scenario.sample_times``: the discrete plant with
        ``time_step = step``, or the continuous one (``step`` ignored).

        The discrete plant updates at t = n·h; its state between n·h − h and n·h is the
        state at n·h, read at (n − ½)·h so that no update is due at the stop."""
        why = self.supports(scenario)
        if why is not None:
            raise MechanicsValueError(f"scenario {scenario.name!r}: Drake cannot run it: {why}")
        h = None
        if self.mode == "discrete":
            h, _ = step_counts(scenario, step)
        sim, plant, bodies = self.build(scenario, h)
        ctx = plant.GetMyContextFromRoot(sim.get_context())
        samples = []
        if h is None:
            stops = [float(T) for T in scenario.sample_times]
        else:  # between updates: n·h would leave the update due at n·h to rounding
            stops = [(n - 0.5) * h for n in step_counts(scenario, h)[1]]
        for T in stops:
            if sim.get_context().get_time() < T:
                sim.AdvanceTo(T)
            samples.append(self._read(plant, ctx, bodies))
        pos, vel, R, w = (np.array(x) for x in zip(*samples, strict=True))
        self.last_stats = _stats(sim, self.mode)
        return Trajectory(np.asarray(scenario.sample_times, dtype=float), pos, vel, R, w)


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("drake")
    except PackageNotFoundError:
        return "(version unknown)"


def _stats(sim, mode: str) -> dict:
    """The integrator's work of the last run (steps, derivative evaluations)."""
    if mode != "continuous":
        return {}
    integ = sim.get_integrator()
    return {
        "steps": integ.get_num_steps_taken(),
        "derivative_evaluations": integ.get_num_derivative_evaluations(),
    }


def _frame_with_axis(a: np.ndarray, k: int) -> np.ndarray:
    """A right-handed orthonormal frame (columns) whose axis ``k`` is the unit ``a``."""
    a = np.asarray(a, dtype=float) / np.linalg.norm(a)
    helper = np.eye(3)[int(np.argmin(np.abs(a)))]
    b = np.cross(a, helper)
    b /= np.linalg.norm(b)
    c = np.cross(a, b)
    cols = {k: a, (k + 1) % 3: b, (k + 2) % 3: c}  # by column index
    return np.column_stack([cols[0], cols[1], cols[2]])
