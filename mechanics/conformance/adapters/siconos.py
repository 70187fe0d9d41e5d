"""Siconos under the conformance battery: ``SiconosAdapter(theta)``.

Siconos (INRIA) is the reference platform for non-smooth mechanics: Moreau–Jean time
stepping with Newton's impact law solved as a complementarity problem at every step.
Debian packages it as ``python3-siconos`` (``apt-get install python3-siconos``; CI
installs it so), for Debian's own ``python3``, which is not bodycheck's interpreter: the
adapter runs each scenario in a worker process under that interpreter
(:mod:`._siconos_worker`, which imports nothing from bodycheck) and exchanges JSON
with it.  The interpreter is ``/usr/bin/python3``, or the one named by the environment
variable ``BODYCHECK_SICONOS_PYTHON``; constructing the adapter probes it, and where it
cannot import Siconos raises :class:`~mechanics.conformance.adapters.MissingExtraError`
naming the Debian package.

Conventions (Siconos against the book)
---------------------------------------
- **Bodies** are ``NewtonEulerDS``: the state q = (x, y, z, q₀, q₁, q₂, q₃), a scalar-first
  quaternion of the active rotation (body to space), so ^A R^O =
  :func:`mechanics.rotation.matrix_from_quat` of it (its length divided out first:
  Siconos keeps it unit to ~1e-14 only, beyond that function's 64 eps); the twist is (v_G in space
  components, Ω in *body* components), as the book's ω in Euler's equations (4.47).
  Mass and principal moments are the scenario's (the body axes are principal).
- **Gravity** is the external force m g on each body.
- **Contacts**: one ``ContactR`` (Siconos's 3-D contact relation of its mechanics
  component) per sphere and per box corner with the ground, and per pair of spheres,
  with Newton's impact law and Coulomb friction (``NewtonImpactFrictionNSL(e, 0, μ, 3)``:
  the ground's μ, zero between bodies; Siconos's exact circular cone), solved by
  ``FrictionContact(3)`` at :data:`SOLVER_TOLERANCE`.  A relation holds its contact
  points in the bodies' frames; on a sphere or a plane the point moves over the
  surface, so the worker sets the points again from the state before every step (what
  Siconos's own collision managers do).
- **Time stepping**: Moreau–Jean (``MoreauJeanOSI(theta)``), fixed steps dividing every
  sample time.  Between impacts, θ = 1/2 is the midpoint rule on velocities (exact
  for a constant force); an impact is resolved at the step it falls in, so times and
  rebound heights err by O(h): first order with impacts.
- **Not mapped** (``supports`` says so): a pivot (a ball joint to the world), a thrust,
  a cylinder touching the ground (its rim is not a finite set of points), contacts
  between two bodies that are not both spheres.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import numpy as np

from ...rotation import matrix_from_quat, quat_from_matrix
from ..protocol import Scenario, Trajectory
from . import MissingExtraError
from ._engines import body_rows, common_unsupported, step_counts, unit_interval

__all__ = ["DEFAULT_PYTHON", "PYTHON_VARIABLE", "SOLVER_TOLERANCE", "SiconosAdapter", "variants"]

#: the interpreter that has Debian's python3-siconos
DEFAULT_PYTHON = "/usr/bin/python3"
#: the environment variable naming another interpreter that imports siconos
PYTHON_VARIABLE = "BODYCHECK_SICONOS_PYTHON"
#: the friction-contact solver's tolerance (its residual, relative): Siconos's default,
#: 1e-4, leaves a spurious spin of 7e-4 rad/s on a box landing flat (issue 29); a few
#: contacts' solve reaches 1e-14, near the rounding of its O(1) terms
SOLVER_TOLERANCE = 1e-14
#: the worker's own file, run by the Siconos interpreter
WORKER = Path(__file__).with_name("_siconos_worker.py")
#: Moreau–Jean's θ of the battery's variants: the midpoint (second order between
#: impacts) and the backward Euler (first order, dissipative)
THETAS = (0.5, 1.0)


def variants() -> list[SiconosAdapter]:
    """The variants the battery runs side by side: Moreau–Jean at each θ of THETAS.

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
    >>> got in (None, [f"SiconosAdapter({t!r})" for t in THETAS])
    True
    """
    return [SiconosAdapter(theta) for theta in THETAS]


def _python() -> str:
    return os.environ.get(PYTHON_VARIABLE) or DEFAULT_PYTHON


class SiconosAdapter:
    """Siconos's Moreau–Jean time stepping (module docstring).

    Parameters
    ----------
    theta : float
        Moreau–Jean's θ, in [1/2, 1] (below 1/2 the scheme is unstable); default 1/2.

    Raises
    ------
    OutOfDomainError
        Where θ is outside [1/2, 1].
    NonFiniteError
        Where θ is a NaN or an infinity.
    ShapeError
        Where θ is not a scalar.
    MissingExtraError
        When the interpreter (``BODYCHECK_SICONOS_PYTHON`` or ``/usr/bin/python3``)
        cannot import Siconos.

    Examples
    --------
    >>> SiconosAdapter(0.25)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.errors.OutOfDomainError: theta (Moreau-Jean's) must lie in [0.5, 1] ...
    """

    takes_step = True

    def __init__(self, theta: float = 0.5):
        t = unit_interval(theta, "theta", "Moreau-Jean's theta")
        if t < 0.5:
            from ...errors import OutOfDomainError

            raise OutOfDomainError(
                f"theta (Moreau-Jean's) must lie in [0.5, 1] (below 0.5 the scheme is "
                f"unstable); got {t!r}"
            )
        self.theta = t
        self.python = _python()
        self.version = _probe(self.python)
        self.name = f"Siconos {self.version} Moreau-Jean, theta {t:g}"

    def __repr__(self) -> str:
        return f"SiconosAdapter({self.theta!r})"

    def supports(self, scenario: Scenario) -> str | None:
        """``None``, or why this adapter cannot run ``scenario`` (module docstring)."""
        why = common_unsupported(scenario, friction=True)
        if why is not None:
            return why
        if scenario.pivot is not None:
            return "a pivot (a ball joint to the world): not mapped by the Siconos adapter"
        if scenario.ground is not None:
            for b in scenario.bodies:
                if b.shape is not None and b.shape.kind == "cylinder":
                    return (
                        f"body {b.name!r} is a cylinder over the ground: its rim is not a "
                        "finite set of contact points, which is what the adapter maps"
                    )
        for i, j, _ in scenario.pair_restitution:
            kinds = set()
            for k in (i, j):
                shape = scenario.bodies[k].shape
                if shape is None:  # common_unsupported refused it above
                    return f"contact pair ({i}, {j}): body {scenario.bodies[k].name!r} has no shape"
                kinds.add(shape.kind)
            if kinds != {"sphere"}:
                return (
                    f"contact pair ({i}, {j}) of a {' and a '.join(sorted(kinds))}: the "
                    "adapter maps contacts of two spheres only"
                )
        return None

    def request(self, scenario: Scenario, step: float) -> dict:
        """The worker's request for ``scenario`` at fixed step ``step`` (JSON-ready)."""
        _, counts = step_counts(scenario, step)
        r, v, R, w = body_rows(scenario)
        bodies = []
        for k, b in enumerate(scenario.bodies):
            shape = None if b.shape is None else {"kind": b.shape.kind, "dims": list(b.shape.dims)}
            bodies.append(
                {
                    "mass": float(b.mass),
                    "inertia": [float(x) for x in b.inertia],
                    "shape": shape,
                    "position": r[k].tolist(),
                    "velocity": v[k].tolist(),
                    "quaternion": quat_from_matrix(R[k]).tolist(),
                    "omega": w[k].tolist(),
                }
            )
        g = scenario.ground
        ground = None
        if g is not None:
            ground = {
                "normal": [float(x) for x in g.normal],
                "height": float(g.height),
                "restitution": float(g.restitution),
                "friction": float(g.friction),
            }
        return {
            "bodies": bodies,
            "gravity": [float(x) for x in scenario.gravity],
            "ground": ground,
            "pairs": [[int(i), int(j), float(e)] for i, j, e in scenario.pair_restitution],
            "step": float(step),
            "counts": [int(c) for c in counts],
            "theta": self.theta,
            "tolerance": SOLVER_TOLERANCE,
        }

    def run(self, scenario: Scenario, step: float | None) -> Trajectory:
        """The trajectory at ``scenario.sample_times`` with Siconos's fixed step ``step``
        (each sample time a whole number of steps)."""
        why = self.supports(scenario)
        if why is not None:
            from ...errors import MechanicsValueError

            raise MechanicsValueError(f"scenario {scenario.name!r}: Siconos cannot run it: {why}")
        h, _ = step_counts(scenario, step)
        answer = _call(self.python, self.request(scenario, h), scenario.name)
        q = np.array(answer["q"], dtype=float)  # (m, n, 7)
        twist = np.array(answer["twist"], dtype=float)  # (m, n, 6)
        quat = q[..., 3:7]  # (normalised by Siconos to ~1e-14 only: read as a direction)
        R = matrix_from_quat(quat / np.linalg.norm(quat, axis=-1, keepdims=True))
        return Trajectory(
            np.asarray(scenario.sample_times, dtype=float),
            q[..., :3],
            twist[..., :3],
            R,
            twist[..., 3:6],
        )


def _missing(python: str, why: str) -> MissingExtraError:
    return MissingExtraError(
        f"the Siconos adapter needs Debian's python3-siconos under {python} "
        f"(apt-get install python3-siconos), or {PYTHON_VARIABLE} naming an interpreter "
        f"that imports siconos: {why}",
        name="siconos",
    )


def _probe(python: str) -> str:
    """Siconos's version as the worker's interpreter reports it, or MissingExtraError."""
    try:
        done = subprocess.run(
            [python, str(WORKER), "--version"], capture_output=True, text=True, timeout=120
        )
    except (OSError, subprocess.TimeoutExpired) as exc:
        raise _missing(python, f"{type(exc).__name__}: {exc}") from None
    if done.returncode != 0:
        last = (done.stderr.strip().splitlines() or ["(no message)"])[-1]
        raise _missing(python, last)
    return done.stdout.strip()


def _call(python: str, request: dict, name: str) -> dict:
    """Run the worker on ``request``; its answer, or RuntimeError with its one line."""
    done = subprocess.run(
        [python, str(WORKER)], input=json.dumps(request), capture_output=True, text=True
    )
    if done.returncode != 0 or not done.stdout:
        last = (done.stderr.strip().splitlines() or [f"exit code {done.returncode}"])[-1]
        raise RuntimeError(f"Siconos failed on scenario {name!r}: {last}")
    answer = json.loads(done.stdout)
    if "error" in answer:
        raise RuntimeError(f"Siconos failed on scenario {name!r}: {answer['error']}")
    return answer
