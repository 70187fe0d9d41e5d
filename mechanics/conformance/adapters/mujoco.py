"""MuJoCo under the conformance battery: ``MuJoCoAdapter(integrator, contact)``.

``pip install 'bodycheck[mujoco]'``.  The model is an MJCF string built from the
:class:`~mechanics.conformance.protocol.Scenario`; this module imports without MuJoCo,
constructing the adapter without it raises :class:`MissingExtraError` naming the extra.

Conventions (MuJoCo against the book)
-------------------------------------
- **Attitude.**  A body's quaternion (``qpos[3:7]`` of a free joint, ``qpos`` of a ball
  joint, ``xquat``) is scalar first, (w, x, y, z), and *active*: it turns the space
  axes onto the body axes, so its matrix ``xmat`` (row-major, columns = body axes in
  space components) is (^A R^O)ᵀ.  The adapter writes ``quat_from_matrix(R_A_O)`` and
  reads ``matrix_from_quat(q)`` (:mod:`mechanics.rotation`, whose quaternions are the
  same active scalar-first ones).
- **Velocities.**  A free joint's ``qvel`` is (v of the body origin in *space*
  components, ω in *body* components); a ball joint's ``qvel`` is ω in body
  components.  The body origin is put at G with the body axes along the principal axes
  (``<inertial pos="0 0 0" diaginertia="J1 J2 J3">``), so v is v_G and ω is the book's
  ω of (4.47) with no conversion.
- **Mass and inertia** are the scenario's, not MuJoCo's shape-derived ones: an explicit
  ``<inertial>`` makes MuJoCo ignore the geoms' masses; :meth:`MuJoCoAdapter.build`
  checks ``body_mass``, ``body_inertia``, ``body_ipos`` and ``body_iquat`` against the
  scenario (a body MuJoCo would re-diagonalise or move fails loudly).
- **Shapes**: ``sphere`` (r), ``box`` (half extents) and ``cylinder`` (r, half length
  along the body's axis 3) are MuJoCo's own geoms with the same numbers.  The ground is
  an infinite ``plane`` whose ``zaxis`` is the scenario's normal.
- **Pivot**: a ``ball`` joint (quaternion, no singularity) at the pivot point; the body
  frame is at G, the joint at ``point`` in body components, ``qpos`` starts at the
  initial attitude (the parent is the world, whose frame is the space frame).
- **Contacts**: every geom has ``contype = conaffinity = 0``; only the scenario's
  contacts are declared, as explicit ``<pair>``s (the ground with each body that has a
  shape, and ``pair_restitution``), each with ``condim = 1``: frictionless, the
  scenario's smooth contact; the ground's with ``Ground.friction`` μ > 0 has
  ``condim = 3`` and ``friction = "μ μ 0 0 0"`` under the elliptic cone (Coulomb's
  circular cone; MuJoCo's default is a pyramid), a soft contact like the normal one.

Restitution: MuJoCo's contact is a spring-damper, not Newton's law (6.6)
-------------------------------------------------------------------------
A contact row obeys a_c = d·a_ref + (1 − d)·a_u with a_ref = −b v − k x and, for
``solref = (τ, ζ)``, b = 2/(d_max τ), k = d/(d_max τ ζ)² (MuJoCo's "Solver
parameters").  With d held constant the depth x obeys an oscillator of frequency
ω = 1/(τζ) and damping ratio ζ while pressed.

- ``contact="default"``: MuJoCo's default impedance (``solimp = 0.9 0.95 0.001 0.5 2``)
  and time constant (τ = 0.02 s), with the damping ratio of the issue's mapping,
  ζ = −ln e/√(π² + ln² e): the textbook value for a spring-damper that may pull.
- ``contact="tuned"``: constant impedance (``solimp = 0.9999 0.9999 0.001 0.5 2``,
  mjMAXIMP), τ = max(2 ms, 20 h) (a tenth of the default, a stiffer contact and a
  shallower dent, as long as the step resolves it: with fewer than ~20 steps per τ the
  rebound is not the oscillator's; at h = 1 ms and τ = 2 ms a ball dropped at 4.4 m/s
  came back at 5.9 times its speed), and the ζ of the no-tension law: the contact
  force k x + b ẋ cannot pull, so the body lets go at ω_d t = π − 2 arcsin ζ with

      e(ζ) = exp(−ζ (π − 2 arcsin ζ) / √(1 − ζ²)),

  solved for ζ by bisection (:func:`zeta_without_tension`).  e(ζ) falls from 1 at ζ = 0
  to e⁻² ≈ 0.135 at critical damping (ζ = 1: x = −v t e^(−ωt) lets go at ωt = 2 with
  speed v e⁻²), so a restitution below e⁻² has no ζ ≤ 1: the tuned contact does not
  support it (:meth:`MuJoCoAdapter.supports` says so).  The numbers and their
  measured rebounds come from ``tests/scenes/test_mujoco_reference.py`` (issue 14):
  e(1 − 1.8e-4) at a 1 µs step; what is left is the climb out of the dent,
  2 g τ ζ²/(e v), and a step error of about 2h/τ (≤ 0.1 at the floor τ = 20 h).
- e = 1 has ζ = 0, an infinite stiffness in (τ, ζ); it is written in MuJoCo's direct
  form ``solref = (−1/τ², 0)`` (a spring of frequency 1/τ and no damping, which lets go
  at the speed it came in).  e = 0 is ζ = 1 (critical damping) in the default setting.

Integrators and steps (:func:`variants`)
----------------------------------------
``integrator`` is MuJoCo's ``"Euler"`` (semi-implicit), ``"implicitfast"`` or ``"RK4"``;
all take the battery's fixed step (``takes_step = True``).  MuJoCo ≥ 4.0's RK4 is
fourth order for the attitudes of free and ball joints (its changelog: the
Runge–Kutta–Munthe–Kaas correction); Euler and implicitfast are first order.

What MuJoCo cannot express here
-------------------------------
A :class:`~mechanics.conformance.protocol.Thrust` (a body's mass is fixed in the
model; a constant-mass force is not the rocket of (7.30)).  Everything else in the
protocol maps.
"""

from __future__ import annotations

import math

import numpy as np

from ..._floats import EPS
from ...errors import MechanicsValueError, OutOfDomainError, RestitutionRangeError
from ...rotation import matrix_from_quat, quat_from_matrix
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
    "DEFAULT_SOLIMP",
    "DEFAULT_TIMECONST",
    "E_MIN_WITHOUT_TENSION",
    "INTEGRATORS",
    "TUNED_SOLIMP",
    "TUNED_STEPS_PER_TIMECONST",
    "TUNED_TIMECONST",
    "MissingExtraError",
    "MuJoCoAdapter",
    "restitution_without_tension",
    "variants",
    "zeta_textbook",
    "zeta_without_tension",
]

INTEGRATORS = ("RK4", "Euler", "implicitfast")
CONTACTS = ("default", "tuned")
#: MuJoCo's defaults (its XML reference, ``geom/solref`` and ``geom/solimp``)
DEFAULT_TIMECONST = 0.02
DEFAULT_SOLIMP = "0.9 0.95 0.001 0.5 2"
#: the tuned contact of tests/scenes/test_mujoco_reference.py: impedance held at
#: mjMAXIMP, a time constant a tenth of the default
TUNED_SOLIMP = "0.9999 0.9999 0.001 0.5 2"
TUNED_TIMECONST = 2e-3
#: the tuned time constant is at least this many steps: the damping force b v switches
#: on inside a step, a relative rebound error ~ 2h/τ (test_mujoco_reference), 0.1 here
TUNED_STEPS_PER_TIMECONST = 20
#: the scenario's inertia must come back as written: MJCF is printed with repr (exact
#: round trip), MuJoCo stores doubles; 4 eps relative leaves room for one conversion
INERTIA_RTOL = 4 * EPS


#: the no-tension restitution at critical damping, e(1) = e⁻²: the least e(ζ) for ζ ≤ 1
E_MIN_WITHOUT_TENSION = math.exp(-2.0)


def restitution_without_tension(zeta: float) -> float:
    """Speed ratio at which a spring-damper of damping ratio ζ ∈ [0, 1] that cannot pull lets go.

    e(ζ) = exp(−ζ (π − 2 arcsin ζ)/√(1 − ζ²)); e⁻² at ζ = 1 (its limit, and the
    critically damped contact's own value: it lets go at ωt = 2 with speed v e⁻²).

    Domain: ζ in [0, 1] (a NaN, an infinity or a value outside is refused naming
    ``zeta``); the result is in [0, 1].

    Parameters
    ----------
    zeta : float
        The damping ratio ζ, in [0, 1].

    Returns
    -------
    float
        The coefficient of restitution e(ζ), in [e⁻², 1].

    Raises
    ------
    OutOfDomainError
        Where ζ is outside [0, 1].
    NonFiniteError
        Where ζ is a NaN or an infinity.
    ShapeError
        Where ζ is not a scalar.

    Examples
    --------
    >>> restitution_without_tension(0.0), restitution_without_tension(1.0) == math.exp(-2)
    (1.0, True)
    >>> round(restitution_without_tension(0.06), 4)  # ζ = 0.060 for e = 5/6 (issue 14)
    0.8339
    """
    zeta = unit_interval(zeta, "zeta", "a damping ratio")
    c = math.sqrt((1.0 - zeta) * (1.0 + zeta))
    if c == 0.0:
        return E_MIN_WITHOUT_TENSION
    # π − 2 arcsin ζ = 2 atan2(c, ζ): no cancellation as ζ → 1, where the ratio
    # atan2(c, ζ)/c → 1/ζ and e → e⁻²
    return math.exp(-2.0 * zeta * math.atan2(c, zeta) / c)


def zeta_without_tension(e: float) -> float:
    """The damping ratio ζ whose no-tension restitution is ``e``, by bisection to the last bit.

    e(ζ) (:func:`restitution_without_tension`) decreases from 1 at ζ = 0 to e⁻² at ζ = 1.

    Domain: e in [e⁻², 1] (:data:`E_MIN_WITHOUT_TENSION`: below it no ζ ≤ 1 rebounds so
    little, an OutOfDomainError says so; outside [0, 1] a RestitutionRangeError names
    ``e``); the result is in [0, 1].

    Parameters
    ----------
    e : float
        The coefficient of restitution, in [e⁻², 1].

    Returns
    -------
    float
        ζ in [0, 1] (0 at e = 1, 1 at e = e⁻²).

    Raises
    ------
    OutOfDomainError
        Where e is in [0, e⁻²): no ζ ≤ 1 rebounds so little.
    RestitutionRangeError
        Where e is outside [0, 1].
    NonFiniteError
        Where e is a NaN or an infinity.
    ShapeError
        Where e is not a scalar.

    Examples
    --------
    >>> z = zeta_without_tension(0.8)
    >>> abs(restitution_without_tension(z) - 0.8) < 1e-15
    True
    """
    e = unit_interval(e, "e", "a coefficient of restitution", error=RestitutionRangeError)
    if e >= 1.0:
        return 0.0
    if e < E_MIN_WITHOUT_TENSION:
        raise OutOfDomainError(
            f"e = {e!r} is below e^-2 = {E_MIN_WITHOUT_TENSION:.6g}: a spring-damper that "
            "cannot pull rebounds at least that fast for any damping ratio zeta <= 1"
        )
    if e == E_MIN_WITHOUT_TENSION:
        return 1.0
    lo, hi = 0.0, 1.0
    while True:
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            return mid
        if restitution_without_tension(mid) > e:
            lo = mid
        else:
            hi = mid


def zeta_textbook(e: float) -> float:
    """ζ = −ln e/√(π² + ln² e), the damping ratio of a spring-damper that may pull.

    A linear spring-damper of this ζ rebounds at e (the issue's mapping, used by the
    default contact).

    Domain: e in [0, 1] (refused naming ``e`` outside); ζ in [0, 1], 1 at e = 0.

    Parameters
    ----------
    e : float
        The coefficient of restitution, in [0, 1].

    Returns
    -------
    float
        ζ in [0, 1]: 0 at e = 1, 1 at e = 0.

    Raises
    ------
    RestitutionRangeError
        Where e is outside [0, 1].
    NonFiniteError
        Where e is a NaN or an infinity.
    ShapeError
        Where e is not a scalar.

    Examples
    --------
    The oscillator's rebound exp(−ζπ/√(1 − ζ²)) gives e back:

    >>> z = zeta_textbook(0.5)
    >>> round(math.exp(-z * math.pi / math.sqrt(1 - z * z)), 12)
    0.5
    """
    e = unit_interval(e, "e", "a coefficient of restitution", error=RestitutionRangeError)
    if e <= 0.0:
        return 1.0
    x = -math.log(e)
    return x / math.hypot(math.pi, x)


def variants() -> list[MuJoCoAdapter]:
    """The variants the battery runs side by side: each integrator with each contact.

    Returns
    -------
    list of Adapter
        One adapter per variant, in the order of the table.

    Raises
    ------
    MissingExtraError
        When the engine is not installed (naming the extra that installs it).

    Examples
    --------
    The variants are the product of the options (checked where the engine is installed):

    >>> try:
    ...     got = [repr(a) for a in variants()]
    ... except MissingExtraError:  # not installed: nothing to compare
    ...     got = None
    >>> got in (None, [f"MuJoCoAdapter({i!r}, {c!r})" for i in INTEGRATORS for c in CONTACTS])
    True
    """
    return [MuJoCoAdapter(i, c) for i in INTEGRATORS for c in CONTACTS]


def _v(x) -> str:
    return " ".join(repr(float(a)) for a in np.ravel(x))


class MuJoCoAdapter:
    """MuJoCo with one of its integrators and one contact setting (module docstring).

    Parameters
    ----------
    integrator : {"RK4", "Euler", "implicitfast"}
        MuJoCo's integrator (default ``"RK4"``).
    contact : {"default", "tuned"}
        The contact setting (default ``"tuned"``; module docstring).

    Raises
    ------
    UnknownOptionError
        Where ``integrator`` or ``contact`` is not one of the above.
    MissingExtraError
        When the ``mujoco`` package is not installed.

    Examples
    --------
    >>> MuJoCoAdapter("RK5")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.errors.UnknownOptionError: MuJoCo integrator must be one of (...); got 'RK5'
    """

    takes_step = True

    def __init__(self, integrator: str = "RK4", contact: str = "tuned"):
        self.integrator = check_option(integrator, INTEGRATORS, "MuJoCo integrator")
        self.contact = check_option(contact, CONTACTS, "MuJoCo contact")
        self._mj = require("mujoco", "mujoco")
        self.name = f"MuJoCo {self._mj.__version__} {integrator}, {contact} contact"

    def __repr__(self) -> str:
        return f"MuJoCoAdapter({self.integrator!r}, {self.contact!r})"

    # ------------------------------------------------------------------ model

    def supports(self, scenario: Scenario) -> str | None:
        """``None``, or why MuJoCo cannot run ``scenario`` (a Thrust; with the tuned
        contact, a restitution below e⁻²)."""
        why = common_unsupported(scenario, friction=True)
        if why is None and self.contact == "tuned":
            es = [e for *_, e in scenario.pair_restitution]
            if scenario.ground is not None:
                es.append(scenario.ground.restitution)
            low = [e for e in es if e < E_MIN_WITHOUT_TENSION]
            if low:
                why = (
                    f"a restitution e = {min(low)!r} below e^-2 = {E_MIN_WITHOUT_TENSION:.4g}: "
                    "the tuned contact (a spring-damper that cannot pull, zeta <= 1) rebounds "
                    "faster; the default contact takes it"
                )
        return why

    def _solref(self, e: float, step: float) -> tuple[str, str]:
        if self.contact == "default":
            tau, solimp, zeta = DEFAULT_TIMECONST, DEFAULT_SOLIMP, zeta_textbook(e)
        else:
            tau = max(TUNED_TIMECONST, TUNED_STEPS_PER_TIMECONST * step)
            solimp, zeta = TUNED_SOLIMP, zeta_without_tension(e)
        if zeta == 0.0:  # e = 1: a spring of frequency 1/τ, no damping (direct form)
            return f"{-1.0 / tau**2!r} 0", solimp
        return f"{tau!r} {zeta!r}", solimp

    def mjcf(self, scenario: Scenario, step: float) -> str:
        """The MJCF model of ``scenario`` at fixed step ``step``."""
        mu = 0.0 if scenario.ground is None else float(scenario.ground.friction)
        cone = ' cone="elliptic"' if mu > 0 else ""  # Coulomb's circular cone
        parts = [
            "<mujoco>",
            f'  <option integrator="{self.integrator}" timestep="{float(step)!r}" '
            f'gravity="{_v(scenario.gravity)}"{cone}/>',
            "  <worldbody>",
        ]
        if scenario.ground is not None:
            n = np.asarray(scenario.ground.normal, dtype=float)
            n = n / np.linalg.norm(n)
            parts.append(
                f'    <geom name="ground" type="plane" size="0 0 1" '
                f'pos="{_v(scenario.ground.height * n)}" zaxis="{_v(n)}" '
                'contype="0" conaffinity="0"/>'
            )
        pivot = scenario.pivot
        for k, b in enumerate(scenario.bodies):
            q = quat_from_matrix(np.array(b.R_A_O, dtype=float))
            inertial = f'<inertial pos="0 0 0" mass="{b.mass!r}" diaginertia="{_v(b.inertia)}"/>'
            if pivot is not None and pivot.body == k:
                # body frame at the pivot (origin = anchor), G at −point in body axes
                off = -np.asarray(pivot.point, dtype=float)
                parts.append(f'    <body name="b{k}" pos="{_v(pivot.anchor)}">')
                parts.append('      <joint name="pivot" type="ball" pos="0 0 0"/>')
                inertial = inertial.replace('pos="0 0 0"', f'pos="{_v(off)}"')
                geom_pos = f' pos="{_v(off)}"'
            else:
                parts.append(f'    <body name="b{k}" pos="{_v(b.position)}" quat="{_v(q)}">')
                parts.append("      <freejoint/>")
                geom_pos = ""
            parts.append(f"      {inertial}")
            if b.shape is not None:
                dims = _v(b.shape.dims)
                parts.append(
                    f'      <geom name="g{k}" type="{b.shape.kind}" size="{dims}"{geom_pos} '
                    'contype="0" conaffinity="0"/>'
                )
            parts.append("    </body>")
        parts.append("  </worldbody>")
        pairs = []
        if scenario.ground is not None:
            for k, b in enumerate(scenario.bodies):
                if b.shape is not None:
                    pairs.append(("ground", f"g{k}", scenario.ground.restitution, mu))
        pairs += [(f"g{i}", f"g{j}", e, 0.0) for i, j, e in scenario.pair_restitution]
        if pairs:
            parts.append("  <contact>")
            for g1, g2, e, f in pairs:
                solref, solimp = self._solref(e, float(step))
                rough = f' condim="3" friction="{f!r} {f!r} 0 0 0"' if f > 0 else ' condim="1"'
                parts.append(
                    f'    <pair geom1="{g1}" geom2="{g2}"{rough} solref="{solref}" '
                    f'solimp="{solimp}"/>'
                )
            parts.append("  </contact>")
        parts.append("</mujoco>")
        return "\n".join(parts)

    def build(self, scenario: Scenario, step: float):
        """(MjModel, MjData) of ``scenario`` in its initial state; checks that MuJoCo
        holds the scenario's masses and inertias (ConformanceError if not)."""
        mj = self._mj
        model = mj.MjModel.from_xml_string(self.mjcf(scenario, step))
        data = mj.MjData(model)
        r, v, R, w = body_rows(scenario)
        for k, b in enumerate(scenario.bodies):
            bid = k + 1  # body 0 is the world
            J = np.asarray(b.inertia, dtype=float)
            got = (model.body_mass[bid], model.body_inertia[bid], model.body_iquat[bid])
            if (
                abs(got[0] - b.mass) > INERTIA_RTOL * b.mass
                or np.abs(got[1] - J).max() > INERTIA_RTOL * J.max()
                or not np.array_equal(got[2], [1.0, 0.0, 0.0, 0.0])
            ):
                raise ConformanceError(
                    f"scenario {scenario.name!r}: MuJoCo changed body {b.name!r}'s mass or "
                    f"principal inertia: mass {got[0]!r}, inertia {got[1]}, iquat {got[2]}; "
                    f"the scenario's are {b.mass!r}, {J}"
                )
            jnt = model.body_jntadr[bid]
            a, d = model.jnt_qposadr[jnt], model.jnt_dofadr[jnt]
            q = quat_from_matrix(R[k])
            if model.jnt_type[jnt] == mj.mjtJoint.mjJNT_FREE:
                data.qpos[a : a + 3] = r[k]
                data.qpos[a + 3 : a + 7] = q
                data.qvel[d : d + 3] = v[k]
                data.qvel[d + 3 : d + 6] = w[k]
            else:
                data.qpos[a : a + 4] = q
                data.qvel[d : d + 3] = w[k]
        mj.mj_forward(model, data)
        return model, data

    # ------------------------------------------------------------------ run

    def _read(self, scenario: Scenario, model, data):
        mj = self._mj
        n = len(scenario.bodies)
        pos, vel, Rs, ws = (
            np.empty((n, 3)),
            np.empty((n, 3)),
            np.empty((n, 3, 3)),
            np.empty((n, 3)),
        )
        for k in range(n):
            jnt = model.body_jntadr[k + 1]
            a, d = model.jnt_qposadr[jnt], model.jnt_dofadr[jnt]
            if model.jnt_type[jnt] == mj.mjtJoint.mjJNT_FREE:
                R = matrix_from_quat(data.qpos[a + 3 : a + 7])
                pos[k], vel[k], ws[k] = (
                    data.qpos[a : a + 3],
                    data.qvel[d : d + 3],
                    data.qvel[d + 3 : d + 6],
                )
            else:
                p = scenario.pivot
                if p is None:  # build() gives a body a ball joint only for the pivot
                    raise MechanicsValueError(
                        f"scenario {scenario.name!r}: the model's body {k} has a ball joint "
                        "but the scenario has no pivot"
                    )
                R = matrix_from_quat(data.qpos[a : a + 4])
                arm = R.T @ -np.asarray(p.point, dtype=float)  # pivot to G, space components
                ws[k] = data.qvel[d : d + 3]
                pos[k] = np.asarray(p.anchor, dtype=float) + arm
                vel[k] = np.cross(R.T @ ws[k], arm)
            Rs[k] = R
        return pos, vel, Rs, ws

    def run(self, scenario: Scenario, step: float | None) -> Trajectory:
        """The trajectory at ``scenario.sample_times`` with MuJoCo's fixed step ``step``
        (each sample time a whole number of steps)."""
        why = self.supports(scenario)
        if why is not None:
            raise MechanicsValueError(f"scenario {scenario.name!r}: MuJoCo cannot run it: {why}")
        h, counts = step_counts(scenario, step)
        model, data = self.build(scenario, h)
        out = []
        done = 0
        for c in counts:
            if c > done:
                self._mj.mj_step(model, data, nstep=int(c - done))
                done = int(c)
            out.append(self._read(scenario, model, data))
        pos, vel, R, w = (np.array(x) for x in zip(*out, strict=True))
        return Trajectory(np.asarray(scenario.sample_times, dtype=float), pos, vel, R, w)
