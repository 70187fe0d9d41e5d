"""DART under the conformance battery: ``DartAdapter(solver)``.

``pip install 'bodycheck[dart]'`` (the ``dartpy`` package).  Each run builds its own
``dartpy.simulation.World`` from the :class:`~mechanics.conformance.protocol.Scenario`:
one ``Skeleton`` per body; the module imports without dartpy, constructing the adapter
without it raises :class:`MissingExtraError` naming the extra.

Conventions (DART against the book)
-----------------------------------
- **Attitude.**  ``BodyNode.getWorldTransform()`` is the isometry T_WB; its
  ``rotation()`` is the *active* matrix whose columns are the body axes in world
  (space) components: ``rotation() = (^A R^O)ᵀ``.  The adapter writes
  ``FreeJoint.setTransform`` with (^A R^O)ᵀ and returns its transpose.
- **Velocities.**  The body frame is put at G with its axes along the principal axes
  (``Inertia(mass, localCOM = 0, diag(J))``), so ``getCOMLinearVelocity()`` (relative
  to the world, world components) is v_G and ``getAngularVelocity(World, body)`` is ω
  relative to the world in *body* components, the book's ω of (4.47) with no
  conversion.  Initial velocities are written with ``FreeJoint.setLinearVelocity`` and
  ``setAngularVelocity`` (relative to and in the world).
- **Mass and inertia** are the scenario's: DART does not derive them from the shapes;
  :meth:`DartAdapter.build` reads back ``getMass``, ``getInertia().getMoment()`` and
  ``getLocalCOM`` and fails loudly if they differ.
- **Shapes**: ``SphereShape(r)``, ``BoxShape(2a, 2b, 2c)`` (full widths),
  ``CylinderShape(r, 2h)`` along the body's axis 3, each on a ``ShapeNode`` with
  collision and dynamics aspects.  The ground is a welded ``BoxShape`` of
  :data:`GROUND_HALF_SIZE` whose top face is the scenario's plane (its z axis along the
  normal).  Contacts are found by DART's default FCL collision detector.
- **Pivot**: a ``BallJoint`` (rotation vector, exponential map: no gimbal lock) whose
  parent frame is the world translated to the anchor and whose child frame is the body
  frame translated to ``point``; its velocity is ω in the child frame, i.e. body
  components.
- **Time stepping**: ``World.step`` is semi-implicit Euler (velocities first, then the
  positions by the exponential map of the new velocity): first order.
- **No sleeping**: DART 6.20 puts a body whose speed stays below 1 cm/s for 0.5 s to
  sleep (``DeactivationOptions``, on by default); the adapter switches it off, so a
  slow body keeps its laws.

Restitution and friction: DART's per-shape coefficients
-------------------------------------------------------
DART's ``DefaultContactSurfaceHandler`` gives a contact the *product* of the two shapes'
``restitution`` coefficients and the *minimum* of their ``friction`` coefficients
(``ContactSurface.cpp``); a restitution at or below 1e-3 switches bouncing off, and a
bounce is only applied above a relative normal speed of 0.1 m/s
(``DART_BOUNCING_VELOCITY_THRESHOLD``), so that resting contacts settle.  The ground gets
restitution 1 and each body with a shape the ground's e; for contacts between bodies each
body gets √e (as for PyBullet, whose Bullet also multiplies).  Friction: the ground gets
the scenario's μ, and the bodies μ too when the ground is rough, else 0 (smooth
contacts between bodies, the protocol's).  A scenario whose pairs and ground need values
no per-body assignment gives (a body in two pairs of different e, pairs beside a ground
of another e, or pairs beside a rough ground, whose μ the bodies would share) is
unsupported, with that reason.  DART's friction is a boxed LCP: a bound μ f_n on each
of two tangent directions (a pyramid, not Coulomb's circular cone); a body sliding along
one of them feels μ f_n exactly.  Penetration is pushed out by an error-reduction
velocity capped at 1 mm/s (DART's defaults), which the rebound carries.

Variants (:func:`variants`)
---------------------------
``solver`` is the boxed LCP solver of DART's ``BoxedLcpConstraintSolver``:
``"dantzig"`` (DART's default pivoting solver, with PGS as its fallback) or ``"pgs"``
(projected Gauss–Seidel alone).  Both take the battery's fixed step
(``takes_step = True``).

What DART cannot express here
-----------------------------
A :class:`~mechanics.conformance.protocol.Thrust` (a body's mass is a fixed property of
its ``Inertia``; a constant-mass force is not the rocket of (7.30)); pair and ground
coefficients that no per-body product and minimum reproduce (above).
"""

from __future__ import annotations

import numpy as np

from ..._floats import EPS
from ...errors import MechanicsValueError
from ..protocol import ConformanceError, Scenario, Trajectory
from . import require
from ._engines import (
    MissingExtraError,
    body_rows,
    check_option,
    common_unsupported,
    product_restitutions,
    step_counts,
)

__all__ = [
    "GROUND_HALF_SIZE",
    "SOLVERS",
    "DartAdapter",
    "MissingExtraError",
    "contact_coefficients",
    "variants",
]

SOLVERS = ("dantzig", "pgs")
#: the ground box: 100 m each way from the origin of its top face, 1 m thick (far larger
#: than any scenario's travel: the bouncing ball moves 1.2 m sideways)
GROUND_HALF_SIZE = (100.0, 100.0, 1.0)
#: DART stores the inertia as given (doubles); 4 eps relative for one conversion
INERTIA_RTOL = 4 * EPS


def variants() -> list[DartAdapter]:
    """The variants the battery runs side by side: DART's Dantzig and PGS boxed LCP.

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
    >>> got in (None, [f"DartAdapter({s!r})" for s in SOLVERS])
    True
    """
    return [DartAdapter(s) for s in SOLVERS]


def contact_coefficients(
    scenario: Scenario,
) -> tuple[list[float], list[float], str | None]:
    """Per-body restitution and friction coefficients that give the scenario's contacts.

    Bodies in order: their products (restitution) and minimum (friction) with the
    ground's 1 and μ give the scenario's contacts, and ``None``; or empty lists and the
    reason no assignment does.

    Parameters
    ----------
    scenario : Scenario
        The scenario to express in DART.

    Returns
    -------
    restitution : list of float
        Each body's restitution coefficient (empty where none works).
    friction : list of float
        Each body's friction coefficient (empty where none works).
    why : str or None
        None, or why no per-body assignment gives the scenario's contacts.

    Raises
    ------
    IndexError
        Where a pair of ``pair_restitution`` names a body the scenario does not have (the
        scenario is not validated here).

    Examples
    --------
    >>> from mechanics.conformance.scenarios import get_scenario
    >>> r, mu, why = contact_coefficients(get_scenario("two_body_impact"))
    >>> why is None and mu == [0.0, 0.0]
    True
    >>> r[0] == r[1] and round(r[0] * r[1], 12)  # √e each: their product is e to rounding
    0.6
    """
    n = len(scenario.bodies)
    mu_ground = 0.0 if scenario.ground is None else float(scenario.ground.friction)
    if mu_ground > 0 and scenario.pair_restitution:
        return (
            [],
            [],
            (
                f"DART gives a contact the least of the two bodies' friction coefficients: "
                f"the rough ground (mu = {mu_ground!r}) needs the bodies' at least mu, the "
                "smooth contacts between bodies need them 0"
            ),
        )
    r, why = product_restitutions(scenario, "DART")
    if r is None:
        return [], [], why
    return r, [mu_ground] * n, None


def _isometry(dm, R_active: np.ndarray, p) -> object:
    T = dm.Isometry3()
    T.set_rotation(np.asarray(R_active, dtype=float))
    T.set_translation(np.asarray(p, dtype=float))
    return T


def _frame_with_z(n: np.ndarray) -> np.ndarray:
    """A rotation (columns: x, y, z axes) whose z axis is the unit vector ``n``."""
    n = np.asarray(n, dtype=float) / np.linalg.norm(n)
    helper = np.eye(3)[int(np.argmin(np.abs(n)))]
    x = np.cross(helper, n)
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(n, x), n])


class DartAdapter:
    """DART with its Dantzig or PGS boxed LCP solver (module docstring).

    Parameters
    ----------
    solver : {"dantzig", "pgs"}
        The boxed LCP solver (default ``"dantzig"``; module docstring).

    Raises
    ------
    UnknownOptionError
        Where ``solver`` is not one of the above.
    MissingExtraError
        When the ``dartpy`` package is not installed.

    Examples
    --------
    >>> DartAdapter("lemke")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.errors.UnknownOptionError: DART solver must be one of (...); got 'lemke'
    """

    takes_step = True

    def __init__(self, solver: str = "dantzig"):
        self.solver = check_option(solver, SOLVERS, "DART solver")
        self._d = require("dartpy", "dart", engine="DART", package="dartpy")
        detail = "Dantzig boxed LCP" if solver == "dantzig" else "PGS boxed LCP"
        self.name = f"DART {_version()} {detail}"

    def __repr__(self) -> str:
        return f"DartAdapter({self.solver!r})"

    def supports(self, scenario: Scenario) -> str | None:
        """``None``, or why DART cannot run ``scenario``."""
        why = common_unsupported(scenario, friction=True)
        if why is None:
            why = contact_coefficients(scenario)[2]
        return why

    # ------------------------------------------------------------------ model

    def _shape(self, shape):
        dd = self._d.dynamics
        if shape.kind == "sphere":
            return dd.SphereShape(float(shape.dims[0]))
        if shape.kind == "box":
            return dd.BoxShape(2.0 * np.asarray(shape.dims, dtype=float))
        r, h = shape.dims
        return dd.CylinderShape(float(r), 2.0 * float(h))

    def _attach(self, body_node, shape, restitution: float, friction: float, offset=None):
        node = body_node.createShapeNode(self._shape(shape))
        if offset is not None:
            node.setRelativeTranslation(np.asarray(offset, dtype=float))
        node.createCollisionAspect()
        node.createDynamicsAspect()
        aspect = node.getDynamicsAspect()
        aspect.setRestitutionCoeff(float(restitution))
        aspect.setFrictionCoeff(float(friction))
        return node

    def build(self, scenario: Scenario, step: float):
        """(world, body nodes, joints) of ``scenario`` in its initial state at fixed step
        ``step``; checks that DART holds the scenario's masses and inertias
        (ConformanceError if not)."""
        d = self._d
        dd, dm = d.dynamics, d.math
        restitution, friction, why = contact_coefficients(scenario)
        if why is not None:
            raise MechanicsValueError(f"scenario {scenario.name!r}: {why}")
        world = d.simulation.World()
        world.setTimeStep(float(step))
        world.setGravity(np.asarray(scenario.gravity, dtype=float))
        sleep = world.getDeactivationOptions()
        sleep.mEnabled = False  # a slow body must keep moving by its laws
        world.setDeactivationOptions(sleep)
        solver = world.getConstraintSolver()
        if self.solver == "pgs":
            # dartpy constructs no LCP solver: the world's PGS fallback becomes the solver
            pgs = solver.getSecondaryBoxedLcpSolver()
            solver.setSecondaryBoxedLcpSolver(None)
            solver.setBoxedLcpSolver(pgs)
        if scenario.ground is not None:
            g = scenario.ground
            n = np.asarray(g.normal, dtype=float)
            n = n / np.linalg.norm(n)
            ground = dd.Skeleton("ground")
            _, gnode = ground.createWeldJointAndBodyNodePair()
            # the box's centre one half thickness below the plane, its z axis along n
            half = np.asarray(GROUND_HALF_SIZE, dtype=float)
            centre = (float(g.height) - half[2]) * n
            joint = gnode.getParentJoint()
            joint.setTransformFromParentBodyNode(_isometry(dm, _frame_with_z(n), centre))
            gshape = gnode.createShapeNode(dd.BoxShape(2.0 * half))
            gshape.createCollisionAspect()
            gshape.createDynamicsAspect()
            gshape.getDynamicsAspect().setRestitutionCoeff(1.0)
            gshape.getDynamicsAspect().setFrictionCoeff(float(g.friction))
            world.addSkeleton(ground)
        r, v, R, w = body_rows(scenario)
        nodes, joints = [], []
        pivot = scenario.pivot
        for k, b in enumerate(scenario.bodies):
            skel = dd.Skeleton(f"b{k}")
            if pivot is not None and pivot.body == k:
                props = dd.BallJointProperties()
                joint, node = skel.createBallJointAndBodyNodePair(None, props)
                joint.setTransformFromParentBodyNode(_isometry(dm, np.eye(3), pivot.anchor))
                joint.setTransformFromChildBodyNode(_isometry(dm, np.eye(3), pivot.point))
            else:
                joint, node = skel.createFreeJointAndBodyNodePair(None, dd.FreeJointProperties())
            node.setInertia(dd.Inertia(float(b.mass), np.zeros(3), np.diag(b.inertia)))
            if b.shape is not None:
                self._attach(node, b.shape, restitution[k], friction[k])
            world.addSkeleton(skel)
            mass = node.getMass()
            J_got = np.asarray(node.getInertia().getMoment(), dtype=float)
            com = np.asarray(node.getLocalCOM(), dtype=float)
            J = np.diag(np.asarray(b.inertia, dtype=float))
            if (
                abs(mass - b.mass) > INERTIA_RTOL * b.mass
                or np.abs(J_got - J).max() > INERTIA_RTOL * J.max()
                or np.abs(com).max() != 0.0
            ):
                raise ConformanceError(
                    f"scenario {scenario.name!r}: DART holds body {b.name!r} with mass "
                    f"{mass!r}, inertia {np.diag(J_got)} and centre of mass {com}, not the "
                    f"scenario's {b.mass!r}, {np.diag(J)} at the body origin"
                )
            if pivot is not None and pivot.body == k:
                joint.setPositions(dd.BallJoint.convertToPositions(R[k].T))
                joint.setVelocities(w[k])  # ω relative to the world, child (body) frame
            else:
                world_frame = dd.Frame.World()
                joint.setTransform(_isometry(dm, R[k].T, r[k]))
                joint.setLinearVelocity(v[k], world_frame, world_frame)
                joint.setAngularVelocity(R[k].T @ w[k], world_frame, world_frame)
            nodes.append(node)
            joints.append(joint)
        # only the scenario's contacts: the ground with every body, the listed pairs
        listed = {(i, j) for i, j, _ in scenario.pair_restitution}
        blacklist = solver.getCollisionOption().collisionFilter
        for i in range(len(nodes)):
            for j in range(i + 1, len(nodes)):
                if (i, j) not in listed:
                    blacklist.addBodyNodePairToBlackList(nodes[i], nodes[j])
        return world, nodes, joints

    # ------------------------------------------------------------------ run

    def _read(self, nodes):
        world_frame = self._d.dynamics.Frame.World()
        out = []
        for node in nodes:
            R_A_O = np.asarray(node.getWorldTransform().rotation(), dtype=float).T
            x = np.asarray(node.getCOM(), dtype=float).ravel()
            v = np.asarray(node.getCOMLinearVelocity(), dtype=float).ravel()
            w_A = np.asarray(node.getAngularVelocity(world_frame, node), dtype=float).ravel()
            out.append((x, v, R_A_O, w_A))
        return [np.array(c) for c in zip(*out, strict=True)]

    def run(self, scenario: Scenario, step: float | None) -> Trajectory:
        """The trajectory at ``scenario.sample_times`` with DART's fixed step ``step``
        (each sample time a whole number of steps)."""
        why = self.supports(scenario)
        if why is not None:
            raise MechanicsValueError(f"scenario {scenario.name!r}: DART cannot run it: {why}")
        h, counts = step_counts(scenario, step)
        world, nodes, _ = self.build(scenario, h)
        samples, done = [], 0
        for c in counts:
            for _ in range(int(c) - done):
                world.step()
            done = max(done, int(c))
            samples.append(self._read(nodes))
        pos, vel, R, w = (np.array(x) for x in zip(*samples, strict=True))
        return Trajectory(np.asarray(scenario.sample_times, dtype=float), pos, vel, R, w)


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("dartpy")
    except PackageNotFoundError:
        return "(version unknown)"
