"""PyBullet under the conformance battery: ``PyBulletAdapter(variant)``.

``pip install 'bodycheck[pybullet]'``.  Each run connects its own physics server with
``p.DIRECT`` (no window, no shared state between runs) and builds the bodies with
``createMultiBody``; the module imports without PyBullet, constructing the adapter
without it raises :class:`MissingExtraError` naming the extra.  PyBullet's build banner,
printed by C code on import, is kept off stdout.

Conventions (PyBullet against the book)
---------------------------------------
- **Attitude.**  PyBullet's quaternions are scalar *last*, (x, y, z, w), and active:
  ``getBasePositionAndOrientation`` gives the rotation that turns the space axes onto
  the body axes, whose matrix (``getMatrixFromQuaternion``, row-major) is (^A R^O)ᵀ.
  The adapter reorders to (w, x, y, z) and uses :func:`mechanics.rotation.matrix_from_quat`
  and :func:`~mechanics.rotation.quat_from_matrix` (active, scalar first).
- **Velocities.**  ``getBaseVelocity`` and ``getLinkState`` give v_G and ω in *space*
  components; the adapter returns ω_A = ^A R^O ω_O (body components, as (4.47)).
- **Mass and inertia** are the scenario's: ``createMultiBody`` computes an inertia from
  the collision shape, which ``changeDynamics(localInertiaDiagonal=J)`` replaces;
  :meth:`PyBulletAdapter.build` reads it back with ``getDynamicsInfo`` and fails loudly
  if PyBullet did not take it.  The inertial frame is at G with the body axes (no
  offset, identity orientation), so PyBullet's base position is G.
- **No hidden damping, no friction**: PyBullet damps every body by default
  (``linearDamping = angularDamping = 0.04``); both are set to 0, as are the lateral,
  rolling and spinning friction (the scenario's contacts are smooth).
- **Shapes**: ``GEOM_SPHERE`` (r), ``GEOM_BOX`` (half extents), ``GEOM_CYLINDER``
  (r, length 2h along the body's axis 3).  The ground is a ``GEOM_PLANE`` with the
  scenario's normal.  Bullet rounds boxes and cylinders by a collision margin
  (``getDynamicsInfo``: 1 mm); a sphere is exact.
- **Pivot**: a ``JOINT_SPHERICAL`` link (reduced coordinates, quaternion: no gimbal
  lock) on a massless fixed base at the anchor; the link frame is at the pivot with the
  body axes, its inertial frame (and shape) at G = −``point``.  PyBullet motorises
  joints by default; the spherical joint's motor is switched off (zero gains and
  force) and its damping set to 0.

Restitution: PyBullet's ``restitution`` dynamics parameter
----------------------------------------------------------
Bullet's sequential-impulse solver applies Newton's law (6.6) at a contact with the
*product* of the two bodies' ``restitution`` values (``btManifoldResult::
calculateCombinedRestitution``).  The ground plane gets 1 and each body with a shape the
ground's e; for contacts between bodies, each body gets √e.  A scenario whose pairs and
ground need values no per-body assignment gives (a body in two pairs of different e, or
pairs besides a ground of different e) is unsupported, with that reason.  Bullet drops
restitution below a relative speed of ``restitutionVelocityThreshold`` (its default,
0.2 m/s, kept) so that resting contacts settle; the first bounces of a drop are far
above it.  Penetration is resolved by split impulses (Bullet's default), which do not
add energy; what is left of it shows as the penetration depth.

Default and tuned contact
-------------------------
Bullet keeps contact points from a distance (its contact breaking threshold, 2 cm by
default) and solves them before the shapes touch — a speculative contact:
the solver makes the body arrive at the surface with zero normal speed, and a body
that arrives at rest has nothing to restitute.  Whether the bounce happens thus depends
on the step: a ball at 4.4 m/s moves 4.4 mm in a 1 ms step and penetrates before the
solver acts (it bounces); at 0.125 ms or with substeps it is caught in front of the
plane and stops dead (measured with ``bench/engines.py``).

- ``contact="default"``: Bullet's settings kept.
- ``contact="tuned"``: ``contactProcessingThreshold = 0`` on every body (only
  penetrating contacts are solved, so the restitution is applied at every step size)
  and ``contactERP = 0`` (no Baumgarte push out of the penetration: Bullet's multibody
  solver has no split impulse, and the push adds up to ERP·v to the rebound — measured
  +0.034 m/s per m/s at its default).  Then Newton's law (6.6) holds at the step of the
  impact, and the rebound at the height of first touch is e within ~g h/v (the speed
  gained within the step, the climb out of at most one step's travel v h).  The price:
  a body stays up to one step's travel deep (4.3 mm for 4.4 m/s at 1 ms).
- Measured oddity, kept as is: at steps of 10 µs and below Bullet loses a further
  0.4 m/s of the rebound, and with substeps there the bounce vanishes
  (``bench/engines.py``).

Variants (:func:`variants`)
---------------------------
- ``"default"``: one Bullet step per battery step (``fixedTimeStep = step``,
  ``numSubSteps = 0``), its default 50 solver iterations.
- ``"fine"``: the same battery step cut into :data:`FINE_SUBSTEPS` internal steps, with
  :data:`FINE_ITERATIONS` solver iterations each.

Both take the battery's fixed step (``takes_step = True``).  Bullet's multibody
integrator is semi-implicit Euler: first order.

What PyBullet cannot express here
---------------------------------
A :class:`~mechanics.conformance.protocol.Thrust` (masses are fixed between
``changeDynamics`` calls and the motor's loss of mass carries no momentum); pair and
ground restitutions that no per-body product reproduces (above).
"""

from __future__ import annotations

import numpy as np

from ..._floats import EPS
from ...errors import MechanicsValueError
from ...rotation import matrix_from_quat, quat_from_matrix
from ..protocol import ConformanceError, Scenario, Trajectory
from ._engines import (
    MissingExtraError,
    body_rows,
    check_option,
    common_unsupported,
    product_restitutions,
    require,
    step_counts,
)

__all__ = [
    "CONTACTS",
    "FINE_ITERATIONS",
    "FINE_SUBSTEPS",
    "VARIANTS",
    "MissingExtraError",
    "PyBulletAdapter",
    "variants",
]

VARIANTS = ("default", "fine")
CONTACTS = ("default", "tuned")
#: the fine variant: eight internal steps per battery step and four times Bullet's
#: default 50 solver iterations (pybullet's quickstart guide suggests both knobs for
#: stiffer, more accurate contact)
FINE_SUBSTEPS = 8
FINE_ITERATIONS = 200
#: PyBullet stores the inertia as given (doubles); 4 eps relative for one conversion
INERTIA_RTOL = 4 * EPS


def variants() -> list[PyBulletAdapter]:
    """The variants the battery runs side by side: default and fine, each with each contact.

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
    >>> got in (None, [f"PyBulletAdapter({v!r}, {c!r})" for v in VARIANTS for c in CONTACTS])
    True
    """
    return [PyBulletAdapter(v, c) for v in VARIANTS for c in CONTACTS]


def pybullet_version() -> str:
    """The installed pybullet's version (the module has no ``__version__``)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("pybullet")
    except PackageNotFoundError:
        return "(version unknown)"


def _xyzw(q_wxyz) -> list[float]:
    w, x, y, z = (float(a) for a in q_wxyz)
    return [x, y, z, w]


def _R_A_O(q_xyzw) -> np.ndarray:
    x, y, z, w = q_xyzw
    return matrix_from_quat(np.array([w, x, y, z]))


def _restitutions(scenario: Scenario) -> tuple[list[float] | None, str | None]:
    """Per-body restitution values whose products give the scenario's e, or a reason."""
    return product_restitutions(scenario, "PyBullet")


class PyBulletAdapter:
    """PyBullet, default or fine (module docstring).

    Parameters
    ----------
    variant : {"default", "fine"}
        One step of 50 solver iterations, or substeps and more iterations (module
        docstring); default ``"default"``.
    contact : {"default", "tuned"}
        The contact setting (default ``"tuned"``).

    Raises
    ------
    UnknownOptionError
        Where ``variant`` or ``contact`` is not one of the above.
    MissingExtraError
        When the ``pybullet`` package is not installed.

    Examples
    --------
    >>> PyBulletAdapter("coarse")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.errors.UnknownOptionError: PyBullet variant must be one of (...); got 'coarse'
    """

    takes_step = True

    def __init__(self, variant: str = "default", contact: str = "tuned"):
        self.variant = check_option(variant, VARIANTS, "PyBullet variant")
        self.contact = check_option(contact, CONTACTS, "PyBullet contact")
        self._p = require("pybullet", "pybullet", quiet=True)
        detail = (
            "one step, 50 iterations"
            if variant == "default"
            else f"{FINE_SUBSTEPS} substeps, {FINE_ITERATIONS} iterations"
        )
        self.name = f"PyBullet {pybullet_version()} {variant} ({detail}), {contact} contact"

    def __repr__(self) -> str:
        return f"PyBulletAdapter({self.variant!r}, {self.contact!r})"

    def supports(self, scenario: Scenario) -> str | None:
        """``None``, or why PyBullet cannot run ``scenario``."""
        why = common_unsupported(scenario)
        if why is None:
            why = _restitutions(scenario)[1]
        return why

    # ------------------------------------------------------------------ model

    def _shape(self, cid, shape, offset=(0.0, 0.0, 0.0)) -> int:
        p = self._p
        if shape is None:
            return -1
        kw = {"collisionFramePosition": list(offset), "physicsClientId": cid}
        if shape.kind == "sphere":
            return p.createCollisionShape(p.GEOM_SPHERE, radius=shape.dims[0], **kw)
        if shape.kind == "box":
            return p.createCollisionShape(p.GEOM_BOX, halfExtents=list(shape.dims), **kw)
        r, h = shape.dims
        return p.createCollisionShape(p.GEOM_CYLINDER, radius=r, height=2 * h, **kw)

    def build(self, scenario: Scenario, step: float) -> tuple[int, list[tuple[int, int]]]:
        """Connect a DIRECT server and build ``scenario`` in it at fixed step ``step``:
        returns the client id and, per body, (multibody id, link index: -1 for a free
        base, 0 for the pivoted link).  The caller disconnects."""
        p = self._p
        restitution, why = _restitutions(scenario)
        if restitution is None:  # then why says why
            raise MechanicsValueError(f"scenario {scenario.name!r}: {why}")
        cid = p.connect(p.DIRECT)
        kw = {"physicsClientId": cid}
        p.setGravity(*scenario.gravity, **kw)
        fine = self.variant == "fine"
        p.setPhysicsEngineParameter(
            fixedTimeStep=float(step),
            numSubSteps=FINE_SUBSTEPS if fine else 0,
            numSolverIterations=FINE_ITERATIONS if fine else 50,
            **kw,
        )
        if self.contact == "tuned":
            p.setPhysicsEngineParameter(contactERP=0.0, **kw)
        ground = None
        if scenario.ground is not None:
            g = scenario.ground
            n = np.asarray(g.normal, dtype=float)
            n = n / np.linalg.norm(n)
            plane = p.createCollisionShape(p.GEOM_PLANE, planeNormal=list(n), **kw)
            ground = p.createMultiBody(0.0, plane, -1, list(g.height * n), [0, 0, 0, 1], **kw)
            p.changeDynamics(ground, -1, restitution=1.0, lateralFriction=0.0, **kw)
            if self.contact == "tuned":
                p.changeDynamics(ground, -1, contactProcessingThreshold=0.0, **kw)
        r, v, R, w = body_rows(scenario)
        ids: list[tuple[int, int]] = []
        pivot = scenario.pivot
        for k, b in enumerate(scenario.bodies):
            q = _xyzw(quat_from_matrix(R[k]))
            if pivot is not None and pivot.body == k:
                off = [-float(x) for x in pivot.point]
                uid = p.createMultiBody(
                    0.0,
                    -1,
                    -1,
                    list(pivot.anchor),
                    [0, 0, 0, 1],
                    linkMasses=[b.mass],
                    linkCollisionShapeIndices=[self._shape(cid, b.shape, off)],
                    linkVisualShapeIndices=[-1],
                    linkPositions=[[0, 0, 0]],
                    linkOrientations=[q],
                    linkInertialFramePositions=[off],
                    linkInertialFrameOrientations=[[0, 0, 0, 1]],
                    linkParentIndices=[0],
                    linkJointTypes=[p.JOINT_SPHERICAL],
                    linkJointAxis=[[0, 0, 1]],
                    **kw,
                )
                link = 0
                p.setJointMotorControlMultiDof(
                    uid,
                    0,
                    p.POSITION_CONTROL,
                    targetPosition=[0, 0, 0, 1],
                    positionGain=0,
                    velocityGain=0,
                    force=[0, 0, 0],
                    **kw,
                )
                p.changeDynamics(uid, 0, jointDamping=0.0, **kw)
            else:
                uid = p.createMultiBody(b.mass, self._shape(cid, b.shape), -1, list(r[k]), q, **kw)
                link = -1
            p.changeDynamics(
                uid,
                link,
                localInertiaDiagonal=list(b.inertia),
                linearDamping=0.0,
                angularDamping=0.0,
                lateralFriction=0.0,
                rollingFriction=0.0,
                spinningFriction=0.0,
                restitution=restitution[k],
                **kw,
            )
            if self.contact == "tuned":
                p.changeDynamics(uid, link, contactProcessingThreshold=0.0, **kw)
            info = p.getDynamicsInfo(uid, link, **kw)
            J = np.asarray(b.inertia, dtype=float)
            if (
                abs(info[0] - b.mass) > INERTIA_RTOL * b.mass
                or np.abs(np.asarray(info[2]) - J).max() > INERTIA_RTOL * J.max()
            ):
                p.disconnect(cid)
                raise ConformanceError(
                    f"scenario {scenario.name!r}: PyBullet holds body {b.name!r} with mass "
                    f"{info[0]!r} and inertia {info[2]}, not the scenario's {b.mass!r}, {J}"
                )
            w_O = R[k].T @ w[k]
            if link == -1:
                p.resetBaseVelocity(uid, list(v[k]), list(w_O), **kw)
            else:
                # a spherical joint's velocity is ω of the link relative to its parent,
                # in the link frame: the body components (checked in the tests)
                p.resetJointStateMultiDof(uid, 0, [0, 0, 0, 1], list(w[k]), **kw)
            ids.append((uid, link))
        # only the scenario's contacts: the ground with every body, the listed pairs
        listed = {(i, j) for i, j, _ in scenario.pair_restitution}
        for i in range(len(ids)):
            for j in range(i + 1, len(ids)):
                if (i, j) not in listed:
                    (a, la), (c, lc) = ids[i], ids[j]
                    p.setCollisionFilterPair(a, c, la, lc, 0, **kw)
        return cid, ids

    # ------------------------------------------------------------------ run

    def _read(self, cid, ids):
        p = self._p
        out = []
        for uid, link in ids:
            if link == -1:
                x, q = p.getBasePositionAndOrientation(uid, physicsClientId=cid)
                v, w_O = p.getBaseVelocity(uid, physicsClientId=cid)
            else:
                s = p.getLinkState(
                    uid,
                    link,
                    computeLinkVelocity=1,
                    computeForwardKinematics=1,
                    physicsClientId=cid,
                )
                x, q, v, w_O = s[0], s[1], s[6], s[7]
            R = _R_A_O(q)
            out.append((x, v, R, R @ np.asarray(w_O)))
        return [np.array(c) for c in zip(*out, strict=True)]

    def run(self, scenario: Scenario, step: float | None) -> Trajectory:
        """The trajectory at ``scenario.sample_times``, PyBullet stepping ``step``."""
        why = self.supports(scenario)
        if why is not None:
            raise MechanicsValueError(f"scenario {scenario.name!r}: PyBullet cannot run it: {why}")
        h, counts = step_counts(scenario, step)
        cid, ids = self.build(scenario, h)
        try:
            samples, done = [], 0
            for c in counts:
                for _ in range(int(c) - done):
                    self._p.stepSimulation(physicsClientId=cid)
                done = max(done, int(c))
                samples.append(self._read(cid, ids))
        finally:
            self._p.disconnect(cid)
        pos, vel, R, w = (np.array(x) for x in zip(*samples, strict=True))
        return Trajectory(np.asarray(scenario.sample_times, dtype=float), pos, vel, R, w)
