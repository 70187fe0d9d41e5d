"""The engine-conformance protocol: what a scenario gives an engine, what it returns.

A user holds *their* engine (a game physics step, a robotics simulator, a student's
integrator) to the book's laws by writing an **adapter**: an object with a ``name``, a
``supports(scenario)`` that says why it cannot run a scenario (or ``None``), and a
``run(scenario, step)`` that returns a :class:`Trajectory` sampled at the scenario's
times.  :mod:`mechanics.conformance.battery` runs the scenarios against it.

Conventions (the same as every module of :mod:`mechanics`)
-----------------------------------------------------------
- SI units; space frame O fixed, z up; gravity is the scenario's vector ``gravity``.
- Each body's axes A are its principal axes through its centre of mass G; ``inertia``
  holds the principal moments J₁, J₂, J₃ about G in those axes.
- Attitudes are **passive** matrices ^A R^O (``R_A_O``): body components of a vector
  are ``R_A_O @ v_O``; the rows of R_A_O are the body axes in space components.  (An
  engine's *active* body-to-world matrix, MuJoCo's ``xmat`` or Drake's
  ``RigidTransform.rotation()``, is its transpose.)
- ``omega`` is the angular velocity in **body** components (the book's ω_i in Euler's
  equations 4.47); ``position`` and ``velocity`` are of G in space components.
- A shape is centred on G with its axes along the body axes: a sphere of radius r, a
  box of half extents (a, b, c) along axes 1, 2, 3, a cylinder of radius r and half
  length h along axis 3.
- A :class:`Ground` is the plane ``normal · x = height`` (bodies above it), ``normal`` a
  unit vector (refused otherwise, so that ``height`` is along it); a contact
  with it, or between two bodies, obeys Newton's law of restitution (6.6) with the
  coefficient given; a contact with the ground has Coulomb friction of coefficient
  ``Ground.friction`` (0 by default: smooth), and contacts between bodies are smooth.
  An adapter whose engine cannot express the friction says so in ``supports``.
- A :class:`Pivot` fixes one point of a body in space (a ball joint to the world):
  ``point`` in body components relative to G, held at ``anchor`` in space.
- A :class:`Thrust` is a rocket's: the body loses mass at ``mass_rate`` and is pushed
  along its body axis ``axis`` by ``mass_rate * exhaust_speed`` (7.30) until
  ``burn_time``; engines with constant masses cannot express it and say so.

Sample times are those of the scenario, exactly: a fixed-step adapter is run with steps
that divide them (the battery only asks for such steps).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Protocol, runtime_checkable

import numpy as np

from .._floats import EPS
from ..errors import MechanicsValueError

__all__ = [
    "ORTHOGONALITY_ATOL",
    "SAMPLE_TIME_RTOL",
    "Adapter",
    "Body",
    "ConformanceError",
    "Event",
    "Ground",
    "Pivot",
    "Scenario",
    "Shape",
    "Thrust",
    "Trajectory",
    "check_trajectory",
]

#: an engine's attitude is a normalised quaternion turned into a matrix, or a matrix
#: re-orthogonalised each step: a few roundings, ~10 eps; 2^10 eps (2.3e-13) also admits
#: single-precision-free engines that normalise every few steps, and still catches any
#: real drift (a 1e-9 shear is 4e6 times larger)
ORTHOGONALITY_ATOL = 2**10 * EPS
#: returned times must equal the scenario's: a fixed step n·h rounds to within a few eps
#: of T; 2^6 eps relative to max(T, 1) allows t accumulated as t0 + n·h, not t += h
SAMPLE_TIME_RTOL = 2**6 * EPS
#: a ground normal written with a few digits, (0.6, 0.8, 0) or normalised in float64, has
#: its length within a few roundings of 1
UNIT_NORMAL_RTOL = 2**4 * EPS


class ConformanceError(MechanicsValueError):
    """An adapter returned something the protocol does not allow; the message names the
    scenario, the field and what was expected."""


@dataclass(frozen=True)
class Shape:
    """A body's collision shape, centred on G with its axes along the body axes.

    ``kind`` is ``"sphere"`` (dims (r,)), ``"box"`` (half extents (a, b, c)) or
    ``"cylinder"`` (dims (r, h), h the half length along axis 3).

    Parameters
    ----------
    kind : {"sphere", "box", "cylinder"}
        The shape's kind.
    dims : tuple of float
        Its dimensions, m, > 0: (r,) for a sphere; the half extents (a, b, c) along body
        axes 1, 2, 3 for a box; (r, h) for a cylinder, h the half length along axis 3.

    Examples
    --------
    The battery's box, whose half extents give J = (2, 3, 4) at 1 kg, J₁ = m (b² + c²)/3:

    >>> a, b, c = Shape("box", (7.5**0.5, 4.5**0.5, 1.5**0.5)).dims
    >>> [round((y * y + z * z) / 3, 12) for y, z in ((b, c), (a, c), (a, b))]
    [2.0, 3.0, 4.0]
    """

    kind: str
    dims: tuple[float, ...]


@dataclass(frozen=True)
class Body:
    """A rigid body: mass m, principal moments about G, optional shape, initial state.

    Parameters
    ----------
    name : str
        How reports and engines' models name the body.
    mass : float
        Its mass m, kg, > 0.
    inertia : tuple of float
        The principal moments (J₁, J₂, J₃) about G, kg m², ≥ 0, in the body axes A.
    shape : Shape or None, optional
        Its collision shape (default None: the body collides with nothing).
    position : tuple of float, optional
        The initial position of G, m, in space components (default the origin).
    velocity : tuple of float, optional
        The initial velocity of G, m/s, in space components (default 0).
    R_A_O : tuple of tuple of float, optional
        The initial passive attitude ^A R^O, a 3×3 tuple of rows (default the identity).
    omega : tuple of float, optional
        The initial angular velocity, rad/s, in body components (default 0).

    Examples
    --------
    A solid sphere's moments are 2/5 m r²; the attitude starts at the identity:

    >>> b = Body("ball", 2.0, (0.8, 0.8, 0.8), Shape("sphere", (1.0,)))
    >>> b.inertia[0] == 0.4 * b.mass * b.shape.dims[0] ** 2
    True
    >>> np.array(b.R_A_O).tolist() == np.eye(3).tolist()
    True
    """

    name: str
    mass: float
    inertia: tuple[float, float, float]
    shape: Shape | None = None
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    velocity: tuple[float, float, float] = (0.0, 0.0, 0.0)
    #: initial ^A R^O, a 3×3 tuple of rows
    R_A_O: tuple[tuple[float, float, float], ...] = (
        (1.0, 0.0, 0.0),
        (0.0, 1.0, 0.0),
        (0.0, 0.0, 1.0),
    )
    #: initial angular velocity, body components
    omega: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Ground:
    """The plane normal · x = height, with restitution e and Coulomb friction μ.

    Contacts with it restitute with ``restitution`` (Newton's law, 6.6) and have Coulomb
    friction ``friction`` (μ ≥ 0; 0: smooth).

    Parameters
    ----------
    restitution : float
        The coefficient of restitution e of a contact with the plane, in [0, 1] (not
        checked here).
    normal : tuple of float, optional
        The plane's unit normal n, space components, pointing to the bodies' side
        (default (0, 0, 1)).
    height : float, optional
        The plane's height along n, m: its points x have n · x = height (default 0).
    friction : float, optional
        Coulomb's coefficient μ, finite, ≥ 0 (default 0: smooth).

    Raises
    ------
    MechanicsValueError
        Where ``friction`` is not a finite number ≥ 0, or ``normal`` is not a unit
        3-vector (its length 1 within ``UNIT_NORMAL_RTOL``).

    Examples
    --------
    (0.6, 0.8, 0) is a unit normal; a normal of length 2 would make ``height`` ambiguous:

    >>> Ground(0.5, normal=(0.6, 0.8, 0.0), height=1.0).height
    1.0
    >>> Ground(0.5, normal=(0.0, 0.0, 2.0))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.errors.MechanicsValueError: Ground.normal must be a unit vector ...
    """

    restitution: float
    normal: tuple[float, float, float] = (0.0, 0.0, 1.0)
    height: float = 0.0
    friction: float = 0.0

    def __post_init__(self) -> None:
        mu = self.friction
        if not (isinstance(mu, (int, float)) and math.isfinite(mu) and mu >= 0):
            raise MechanicsValueError(
                f"Ground.friction (Coulomb's mu) must be a finite number >= 0; got {mu!r}"
            )
        # one plane, one reading: with a unit normal, n · x = height and "height along
        # the normal" agree (issue 16 found the engines' adapters reading the second, the
        # scene engine's the first, for a normal of length 2)
        n = np.asarray(self.normal, dtype=float)
        length = float(np.linalg.norm(n)) if n.shape == (3,) else math.nan
        if not abs(length - 1.0) <= UNIT_NORMAL_RTOL:
            raise MechanicsValueError(
                f"Ground.normal must be a unit vector (3 components, length 1 within "
                f"{UNIT_NORMAL_RTOL / EPS:g} eps); got {self.normal!r} of length {length!r}"
            )


@dataclass(frozen=True)
class Pivot:
    """A frictionless ball joint to the world: a point of one body held fixed in space.

    Body ``body`` (an index) has its point ``point`` (body components, relative to G)
    held at ``anchor`` in space.

    Parameters
    ----------
    body : int
        The index of the pivoted body in ``Scenario.bodies``.
    point : tuple of float
        The pivot point relative to G, m, in body components.
    anchor : tuple of float, optional
        Where the point is held, m, in space components (default the origin).

    Examples
    --------
    The heavy top's pivot 0.5 m below G on axis 3 (|point| = 0.5, on axis 3):

    >>> p = Pivot(0, (0.0, 0.0, -0.5))
    >>> float(np.linalg.norm(p.point)) == -p.point[2], p.anchor
    (True, (0.0, 0.0, 0.0))
    """

    body: int
    point: tuple[float, float, float]
    anchor: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Thrust:
    """A rocket motor on one body: thrust q·u along a body axis until the burn ends (7.30).

    Body ``body`` loses mass at rate q > 0 (kg/s), ejected at exhaust speed u relative to
    the body, which is pushed by q·u along the body axis ``axis`` (a unit 3-vector in body
    components) from t = 0 until ``burn_time``.

    Parameters
    ----------
    body : int
        The index of the rocket in ``Scenario.bodies``.
    mass_rate : float
        q, the mass lost per second, kg/s, > 0.
    exhaust_speed : float
        u, the exhaust's speed relative to the body, m/s, > 0.
    burn_time : float
        When the motor stops, s, > 0 (q · burn_time kg of fuel burn).
    axis : tuple of float, optional
        The thrust's direction, a unit vector in body components (default (0, 0, 1)).

    Examples
    --------
    The thrust q u (7.30) and the fuel burnt, q · burn_time:

    >>> th = Thrust(0, mass_rate=0.5, exhaust_speed=100.0, burn_time=2.0)
    >>> th.mass_rate * th.exhaust_speed, th.mass_rate * th.burn_time
    (50.0, 1.0)
    """

    body: int
    mass_rate: float
    exhaust_speed: float
    burn_time: float
    axis: tuple[float, float, float] = (0.0, 0.0, 1.0)


@dataclass(frozen=True)
class Scenario:
    """One test case of the battery.

    ``bodies`` start in the states they hold; the engine simulates ``duration`` seconds
    and returns the states at ``sample_times`` (which start at 0 and end at
    ``duration``).  ``pair_restitution`` maps a pair of body indices (i < j) to the e of
    their contact; absent pairs do not collide.  ``steps`` are the fixed step sizes the
    battery asks of an adapter that takes one (coarse to fine, each a divisor of every
    sample time), for the order of convergence.  ``book`` names what the reference comes
    from, e.g. ``"(5.85), Essén 5.3"``.

    Parameters
    ----------
    name : str
        The scenario's name (the report's row, a threshold key's prefix).
    description : str
        One line on what it tests.
    book : str
        What the reference comes from, e.g. ``"(5.85), Essén 5.3"``.
    bodies : tuple of Body
        The bodies in their initial states.
    duration : float
        The simulated time, s, > 0.
    sample_times : tuple of float
        The times, s, of the returned states: increasing, from 0 to ``duration``.
    gravity : tuple of float, optional
        The gravitational acceleration g, m/s², space components (default 0).
    ground : Ground or None, optional
        The ground plane (default None: none).
    pair_restitution : tuple of (int, int, float), optional
        (i, j, e) for each pair of body indices i < j that collide, with their e.
    pivot : Pivot or None, optional
        A ball joint to the world (default None).
    thrust : Thrust or None, optional
        A rocket motor (default None).
    steps : tuple of float, optional
        The fixed steps, s, asked of an adapter that takes one, coarse to fine.
    extra : dict, optional
        Free-form facts a reference or a report may need; ``extra["kind"]`` names the
        scenario's kind (its reference and figures).

    Examples
    --------
    The samples start at 0 and end at the duration; each step divides every sample time:

    >>> s = Scenario("still", "a body at rest", "(1.1)", (Body("b", 1.0, (1.0, 1.0, 1.0)),),
    ...              duration=1.0, sample_times=(0.0, 0.5, 1.0), steps=(0.25, 0.125))
    >>> s.sample_times[-1] == s.duration, [t / h for t in s.sample_times for h in s.steps]
    (True, [0.0, 0.0, 2.0, 4.0, 4.0, 8.0])
    """

    name: str
    description: str
    book: str
    bodies: tuple[Body, ...]
    duration: float
    sample_times: tuple[float, ...]
    gravity: tuple[float, float, float] = (0.0, 0.0, 0.0)
    ground: Ground | None = None
    pair_restitution: tuple[tuple[int, int, float], ...] = ()
    pivot: Pivot | None = None
    thrust: Thrust | None = None
    steps: tuple[float, ...] = ()
    #: free-form facts a reference or a report may need (e.g. "apexes": 5)
    extra: dict = field(default_factory=dict, compare=False, hash=False)


@dataclass(frozen=True)
class Event:
    """A contact event an adapter may report: its time, kind and the bodies.

    Parameters
    ----------
    time : float
        When it happened, s.
    kind : {"impact", "separation"}
        What happened.
    bodies : tuple of (int, int)
        The indices of the two bodies; ``-1`` is the ground.

    Examples
    --------
    >>> e = Event(0.5, "impact", (0, -1))
    >>> e.kind, -1 in e.bodies
    ('impact', True)
    """

    time: float
    kind: str
    bodies: tuple[int, int]


@dataclass(frozen=True)
class Trajectory:
    """An engine's samples: the states of n bodies at m times.

    Parameters
    ----------
    t : ndarray, shape (m,)
        The sample times, s (the scenario's).
    position : ndarray, shape (m, n, 3)
        Each body's G, m, in space components.
    velocity : ndarray, shape (m, n, 3)
        Each body's v_G, m/s, in space components.
    R_A_O : ndarray, shape (m, n, 3, 3)
        Each body's passive attitude ^A R^O.
    omega : ndarray, shape (m, n, 3)
        Each body's angular velocity, rad/s, in body components.
    masses : ndarray, shape (m, n), optional
        The masses, kg, only where they change (a rocket); else None.
    events : tuple of Event, optional
        Contact events, if the engine reports them.

    Examples
    --------
    One body at rest at two samples:

    >>> z = np.zeros((2, 1, 3))
    >>> tr = Trajectory(np.array([0.0, 1.0]), z, z, np.broadcast_to(np.eye(3), (2, 1, 3, 3)), z)
    >>> tr.position.shape[:2] == (tr.t.size, 1), tr.masses is None
    (True, True)
    """

    t: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    R_A_O: np.ndarray
    omega: np.ndarray
    masses: np.ndarray | None = None
    events: tuple[Event, ...] = ()


@runtime_checkable
class Adapter(Protocol):
    """What a user writes to put their engine under test.

    ``name``: how the report calls it.  ``takes_step``: ``True`` when ``run`` honours a
    fixed step (then the battery runs each scenario's ``steps`` and measures the order
    of convergence), ``False`` when the engine chooses its own (``step`` is ``None``).
    ``supports(scenario)``: ``None`` when the engine can run it, else one sentence why
    not (the report shows it; a scenario is never passed by omission).
    ``run(scenario, step)``: the trajectory at ``scenario.sample_times``.

    A protocol is not instantiated: a user's class is an ``Adapter`` when it has these
    four members (``isinstance`` checks them, :func:`~.battery.run_battery` too).

    Examples
    --------
    >>> from mechanics.conformance.adapters import ExactAdapter
    >>> isinstance(ExactAdapter(), Adapter), isinstance(object(), Adapter)
    (True, False)
    """

    name: str
    takes_step: bool

    def supports(self, scenario: Scenario) -> str | None: ...

    def run(self, scenario: Scenario, step: float | None) -> Trajectory: ...


def _field(scenario: Scenario, name: str, value, shape: tuple[int, ...]) -> np.ndarray:
    where = f"scenario {scenario.name!r}: trajectory field {name!r}"
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ConformanceError(f"{where} must be a float array of shape {shape}; {exc}") from None
    if a.shape != shape:
        raise ConformanceError(f"{where} must have shape {shape}; got {a.shape}")
    bad = ~np.isfinite(a)
    if bad.any():
        i = tuple(int(k) for k in np.argwhere(bad)[0])
        raise ConformanceError(f"{where} must be finite; got {float(a[i])!r} at index {i}")
    return a


def check_trajectory(scenario: Scenario, trajectory) -> Trajectory:
    """Validate an adapter's answer against the protocol; return it as float64 arrays.

    Parameters
    ----------
    scenario : Scenario
        The scenario the adapter ran.
    trajectory : Trajectory
        The adapter's answer (anything: what is not a :class:`Trajectory` is refused).

    Returns
    -------
    Trajectory
        The same samples as float64 arrays, the events as a tuple.

    Raises
    ------
    ConformanceError
        Naming the scenario, the field and what was expected: a non-``Trajectory``, a
        wrong shape, NaN or infinity, times that are not the scenario's sample times
        (within :data:`SAMPLE_TIME_RTOL`, or out of order), attitudes that are not
        rotations within :data:`ORTHOGONALITY_ATOL`, masses that are not positive, events
        that are not :class:`Event`.

    Examples
    --------
    >>> s = Scenario("still", "a body at rest", "(1.1)", (Body("b", 1.0, (1.0, 1.0, 1.0)),),
    ...              duration=1.0, sample_times=(0.0, 1.0))
    >>> z = np.zeros((2, 1, 3))
    >>> R = np.broadcast_to(np.eye(3), (2, 1, 3, 3))
    >>> check_trajectory(s, Trajectory(np.array([0.0, 1.0]), z, z, R, z)).t.shape
    (2,)
    >>> check_trajectory(s, Trajectory(np.array([0.0, 1.0]), z, z, 2 * R, z))
    ... # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.conformance.protocol.ConformanceError: scenario 'still': ... 'R_A_O' ... off by 7
    """
    where = f"scenario {scenario.name!r}"
    if not isinstance(trajectory, Trajectory):
        raise ConformanceError(
            f"{where}: the adapter must return a mechanics.conformance.Trajectory; "
            f"got {type(trajectory).__name__}"
        )
    T = np.asarray(scenario.sample_times, dtype=float)
    m, n = T.size, len(scenario.bodies)
    t = _field(scenario, "t", trajectory.t, (m,))
    if m > 1 and not np.all(np.diff(t) > 0):
        k = int(np.argmin(np.diff(t) > 0))
        raise ConformanceError(
            f"{where}: trajectory field 't' must increase strictly; t[{k}] = {float(t[k])!r}, "
            f"t[{k + 1}] = {float(t[k + 1])!r}"
        )
    off = np.abs(t - T) > SAMPLE_TIME_RTOL * np.maximum(np.abs(T), 1.0)
    if off.any():
        k = int(np.argmax(off))
        raise ConformanceError(
            f"{where}: trajectory field 't' must be the scenario's sample times; "
            f"t[{k}] = {float(t[k])!r}, expected {float(T[k])!r}"
        )
    pos = _field(scenario, "position", trajectory.position, (m, n, 3))
    vel = _field(scenario, "velocity", trajectory.velocity, (m, n, 3))
    R = _field(scenario, "R_A_O", trajectory.R_A_O, (m, n, 3, 3))
    w = _field(scenario, "omega", trajectory.omega, (m, n, 3))
    err = np.abs(R @ np.swapaxes(R, -1, -2) - np.eye(3)).max(axis=(-1, -2))
    err = np.maximum(err, np.abs(np.linalg.det(R) - 1.0))
    if (err > ORTHOGONALITY_ATOL).any():
        k, b = (int(x) for x in np.unravel_index(np.argmax(err), err.shape))
        raise ConformanceError(
            f"{where}: trajectory field 'R_A_O' must hold rotations (R Rᵀ = I, det R = +1 "
            f"within {ORTHOGONALITY_ATOL:.3g}); sample {k}, body {b} is off by {err[k, b]:.3g}"
        )
    masses = None
    if trajectory.masses is not None:
        masses = _field(scenario, "masses", trajectory.masses, (m, n))
        if (masses <= 0).any():
            k, b = (int(x) for x in np.argwhere(masses <= 0)[0])
            raise ConformanceError(
                f"{where}: trajectory field 'masses' must be > 0; got {float(masses[k, b])!r} "
                f"at sample {k}, body {b}"
            )
    events = tuple(trajectory.events)
    for e in events:
        if not isinstance(e, Event):
            raise ConformanceError(
                f"{where}: trajectory field 'events' must hold mechanics.conformance.Event; "
                f"got {type(e).__name__}"
            )
    return Trajectory(t, pos, vel, R, w, masses, events)
