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
    """A body's collision shape: ``kind`` is ``"sphere"`` (dims (r,)), ``"box"`` (half
    extents (a, b, c)) or ``"cylinder"`` (dims (r, h), h the half length along axis 3)."""

    kind: str
    dims: tuple[float, ...]


@dataclass(frozen=True)
class Body:
    """A rigid body: mass m, principal moments about G, optional shape, initial state."""

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
    """The plane normal · x = height; contacts with it restitute with ``restitution``
    and have Coulomb friction ``friction`` (μ ≥ 0; 0: smooth)."""

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
    """Body ``body`` (an index) has its point ``point`` (body components, relative to G)
    held at ``anchor`` in space: a frictionless ball joint to the world."""

    body: int
    point: tuple[float, float, float]
    anchor: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Thrust:
    """A rocket motor on body ``body``: mass rate q > 0 (kg/s lost), exhaust speed u
    relative to the body, thrust q·u along the body axis ``axis`` (a unit 3-vector in
    body components) from t = 0 until ``burn_time``."""

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
    from, e.g. ``"(5.85), Essén 5.3"``."""

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
    """A contact event an adapter may report: its time, ``kind`` (``"impact"`` or
    ``"separation"``) and the bodies (``-1`` is the ground)."""

    time: float
    kind: str
    bodies: tuple[int, int]


@dataclass(frozen=True)
class Trajectory:
    """An engine's samples: ``t`` shape (m,), ``position`` and ``velocity`` (m, n, 3) of
    each body's G in space components, ``R_A_O`` (m, n, 3, 3) passive attitudes,
    ``omega`` (m, n, 3) in body components; ``masses`` (m, n) only where they change
    (a rocket), else ``None``; ``events`` optional."""

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
    ``run(scenario, step)``: the trajectory at ``scenario.sample_times``."""

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

    Raises :class:`ConformanceError` naming the scenario, the field and what was
    expected: a non-``Trajectory``, a wrong shape, NaN or infinity, times that are not
    the scenario's sample times (or out of order), attitudes that are not rotations
    within :data:`ORTHOGONALITY_ATOL`, masses that are not positive.

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
