"""One fuzz entry per public callable of :mod:`mechanics`: a valid call and what to break.

An :class:`Entry` gives a valid call as keyword arguments and says, per parameter, what
it is: a numeric array whose trailing shape is ``arrays[name]`` (scalars have ``()``), a
string option (``opts``: an unknown value must raise ``UnknownOptionError``), or
something the fuzzer leaves alone (``skip``, with the reason). ``bad`` lists unphysical
values per parameter (negative mass, e = 1.5, zero radius, a field that returns NaN):
each must be refused with a ``MechanicsValueError`` naming the parameter.

A callable that is not fuzzed has a line in :data:`EXEMPT` saying why (hypothesis
strategies, whose contract is hypothesis' ``InvalidArgument``; result records that the
library builds itself; scene plumbing that takes an engine, reached through the scene
loader's fuzz in ``test_scene_fuzz.py``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

# ----------------------------------------------------------------- valid building blocks
V = (0.3, -0.2, 0.5)
V2 = (-0.1, 0.4, 0.2)
JT = ((2.0, 0.1, 0.0), (0.1, 3.0, 0.0), (0.0, 0.0, 4.0))  # symmetric, positive, triangle
JP = (2.0, 3.0, 4.0)
PTS = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (1.0, 1.0, 1.0))
M4 = (1.0, 2.0, 3.0, 4.0)
V4 = ((0.1, 0.0, 0.2), (0.0, -0.3, 0.1), (0.2, 0.2, 0.0), (-0.1, 0.1, 0.1))
F4 = ((0.0, 1.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, -1.0), (-1.0, -1.0, 1.0))
Z = (0.0, 0.0, 1.0)


def _rot(a: float, b: float) -> tuple:
    """R3(a) R1(b), written out (the passive matrices of ARCHITECTURE.md)."""
    ca, sa, cb, sb = math.cos(a), math.sin(a), math.cos(b), math.sin(b)
    r3 = np.array([[ca, sa, 0.0], [-sa, ca, 0.0], [0.0, 0.0, 1.0]])
    r1 = np.array([[1.0, 0.0, 0.0], [0.0, cb, sb], [0.0, -sb, cb]])
    return tuple(map(tuple, r3 @ r1))


R = _rot(0.3, 0.4)
R_B = _rot(-0.7, 1.1)
Q = (math.cos(0.2), math.sin(0.2) * 0.6, 0.0, math.sin(0.2) * 0.8)
Q2 = (math.cos(0.5), 0.0, math.sin(0.5), 0.0)
#: ω × R for ω = (0, 0, 1) in the passive convention: Ṙ = −[ω]× R
RDOT = tuple(map(tuple, -np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]) @ R))


def _field_v(r, t):
    return np.stack([-r[..., 1], r[..., 0], 0.0 * r[..., 2]], axis=-1)


def _field_s(r, t):
    return 2.0 * r[..., 0] - r[..., 2] + t


def _nan_field(r, t):
    return np.full(np.shape(r), np.nan)


def _nan_scalar_field(r, t):
    return np.full(np.shape(r)[:-1], np.nan)


def _rhs_decay(t, y):
    return -y


def _rhs_nan(t, y):
    return np.full_like(y, np.nan)


@dataclass(frozen=True)
class Entry:
    """A valid call of one public callable and the parameters the fuzzer breaks."""

    kw: dict[str, Any]
    arrays: dict[str, tuple[int, ...]] = field(default_factory=dict)
    bad: dict[str, list[Any]] = field(default_factory=dict)
    opts: tuple[str, ...] = ()
    skip: dict[str, str] = field(default_factory=dict)
    #: called on the result (an object): returns the numbers to check for finiteness
    post: Callable[[Any], Any] | None = None
    #: parameters the fuzzer substitutes: all of ``kw`` except options and skipped ones
    only: tuple[str, ...] | None = None
    #: False where a new leading axis is not a batch (mass_rate: the last axis lists flows)
    batch: bool = True

    def numeric(self) -> list[str]:
        names = self.only if self.only is not None else tuple(self.kw)
        return [
            n
            for n in names
            if n not in self.opts and n not in self.skip and not callable(self.kw.get(n))
        ]

    def tail(self, name: str) -> tuple[int, ...]:
        return self.arrays.get(name, ())


NEG = [-1.0]
NONPOS = [0.0, -1.0]
E_BAD = [1.5, -0.1]
ZERO3 = [(0.0, 0.0, 0.0)]
FLAG = "a boolean flag, not a number"
FIELD = "a field (callable); its non-finite output is a listed bad value"
NAME = "the name used in error messages (a string, not data)"
ATOL = "a tolerance of the check itself"

ENTRIES: dict[str, Entry] = {}


def _add(name: str, entry: Entry) -> None:
    assert name not in ENTRIES, name
    ENTRIES[name] = entry


# ------------------------------------------------------------------------------ dynamics
_d = "mechanics.dynamics."
_add(
    _d + "angular_momentum_rigid",
    Entry({"J": JT, "omega": V}, {"J": (3, 3), "omega": (3,)}, skip={"allow_singular": FLAG}),
)
_add(
    _d + "axis_reaction",
    Entry(
        {"m": 2.0, "h": 0.3, "phidot": 1.2, "phiddot": -0.4, "F_a_rho": 1.0, "F_a_phi": 0.5},
        bad={"m": NEG},
    ),
)
_add(
    _d + "bearing_reactions",
    Entry(
        {
            "J_O": JT,
            "m": 2.0,
            "r_G": V,
            "phidot": 1.0,
            "phiddot": 0.2,
            "z_A": 0.5,
            "F_a": V2,
            "M_a": V,
            "axial_at": "O",
        },
        {"J_O": (3, 3), "r_G": (3,), "F_a": (3,), "M_a": (3,)},
        bad={"m": NEG, "z_A": [0.0]},
        opts=("axial_at",),
    ),
)
_add(
    _d + "euler_equations_rhs",
    Entry(
        {"J_principal": JP, "omega": V, "M": V2},
        {"J_principal": (3,), "omega": (3,), "M": (3,)},
        bad={"J_principal": [(0.0, 3.0, 4.0), (-2.0, 3.0, 4.0)]},
    ),
)
_add(
    _d + "fixed_axis_angular_acceleration",
    Entry({"J_axis": 2.0, "M_axis": 0.5}, bad={"J_axis": NONPOS}),
)
_PEND = {"J_axis": 0.5, "m": 1.0, "g": 9.81, "h": 0.3}
_add(
    _d + "pendulum_angular_velocity_at",
    Entry(
        {"theta": 0.2, **_PEND, "theta_0": 0.5},
        bad={"J_axis": NONPOS, "m": NONPOS, "h": NONPOS, "g": NONPOS, "theta_0": [4.0]},
    ),
)
_add(
    _d + "pendulum_axis_reaction",
    Entry({"phi": 0.3, **_PEND, "E": 1.0}, bad={"J_axis": NONPOS, "m": NEG}),
)
_add(
    _d + "pendulum_motion",
    Entry(
        {"t": 0.7, **_PEND, "theta_0": 0.5},
        bad={"J_axis": NONPOS, "m": NONPOS, "h": NONPOS, "g": NONPOS, "theta_0": [4.0]},
    ),
)
_add(
    _d + "pendulum_period",
    Entry(
        {**_PEND, "theta_0": 0.5},
        bad={"J_axis": NONPOS, "m": NONPOS, "h": NONPOS, "g": NONPOS, "theta_0": [4.0]},
    ),
)
_add(
    _d + "pendulum_small_period",
    Entry(dict(_PEND), bad={"J_axis": NONPOS, "m": NONPOS, "h": NONPOS, "g": NONPOS}),
)
_add(
    _d + "reduced_length",
    Entry({"J_axis": 0.5, "m": 1.0, "h": 0.3}, bad={"J_axis": NONPOS, "m": NONPOS, "h": NONPOS}),
)
_add(
    _d + "rotational_kinetic_energy",
    Entry({"J": JT, "omega": V}, {"J": (3, 3), "omega": (3,)}, skip={"allow_singular": FLAG}),
)

# ------------------------------------------------------------------------------ elliptic
_e = "mechanics.elliptic."
_add(_e + "ellipe", Entry({"m": 0.5}, bad={"m": [1.5]}, only=("m",)))
_add(_e + "ellipk", Entry({"m": 0.5}, bad={"m": [1.5]}, only=("m",)))  # K(1) = inf, documented
# m > 1: the reciprocal-modulus transformation (documented), so 1.5 is valid there
_add(_e + "ellipf", Entry({"phi": 0.7, "m": 0.5}, only=("phi", "m")))
_add(_e + "ellipj", Entry({"u": 0.7, "m": 0.5}, only=("u", "m")))
_add(
    _e + "ellippi",
    Entry({"n": 0.3, "phi": 0.7, "m": 0.5}, only=("n", "phi", "m")),
)
_add(
    _e + "ellippi_jacobi",
    Entry({"u": 0.7, "n": 0.3, "m": 0.5}, bad={"m": [1.5]}, only=("u", "n", "m")),
)

# -------------------------------------------------------------------------------- energy
_g = "mechanics.energy."
_add(
    _g + "contact_point_velocity",
    Entry({"v_G": V, "omega": V2, "r_GC": Z}, {"v_G": (3,), "omega": (3,), "r_GC": (3,)}),
)
_add(
    _g + "contact_power",
    Entry(
        {"F_contact": V, "v_G": V2, "omega": V, "r_GC": Z},
        {"F_contact": (3,), "v_G": (3,), "omega": (3,), "r_GC": (3,)},
    ),
)
_add(
    _g + "rolling_contact_power",
    Entry(
        {"F_contact": V, "v_G": V2, "omega": V, "r_GC": Z},
        {"F_contact": (3,), "v_G": (3,), "omega": (3,), "r_GC": (3,)},
    ),
)
_add(
    _g + "gravity_potential",
    Entry(
        {"m": (2.0,), "r": (V,), "g": (0.0, 0.0, -9.81)},
        {"m": (1,), "r": (1, 3), "g": (3,)},
        bad={"m": [(-1.0,)]},
    ),
)
_add(_g + "kinetic_energy_fixed_axis", Entry({"J_axis": 2.0, "omega": 1.5}, bad={"J_axis": NEG}))
_add(
    _g + "kinetic_energy_rigid",
    Entry(
        {"m": 2.0, "v_G": V, "omega": V2, "J_G": JT},
        {"v_G": (3,), "omega": (3,), "J_G": (3, 3)},
        bad={"m": NEG},
    ),
)
_add(_g + "pair_power", Entry({"N": V, "v_1": V2, "v_2": V}, {"N": (3,), "v_1": (3,), "v_2": (3,)}))
_add(_g + "power", Entry({"F": (V,), "v": (V2,)}, {"F": (1, 3), "v": (1, 3)}))  # N forces
_add(
    _g + "rigid_body_power",
    Entry(
        {"F": V, "M_A": V2, "v_A": V, "omega": V2},
        {"F": (3,), "M_A": (3,), "v_A": (3,), "omega": (3,)},
    ),
)
_add(
    _g + "spring_force",
    Entry(
        {"k": 10.0, "ell_0": 0.5, "r_1": V, "r_2": V2},
        {"r_1": (3,), "r_2": (3,)},
        bad={"k": NEG, "ell_0": NEG},
        skip={"tension_only": FLAG},
    ),
)
_add(
    _g + "spring_potential",
    Entry(
        {"k": 10.0, "ell_0": 0.5, "r_1": V, "r_2": V2},
        {"r_1": (3,), "r_2": (3,)},
        bad={"k": NEG, "ell_0": NEG},
        skip={"tension_only": FLAG},
    ),
)
_add(_g + "torsion_moment", Entry({"tau_0": 2.0, "phi": 0.3}, bad={"tau_0": NEG}))
_add(_g + "torsion_potential", Entry({"tau_0": 2.0, "phi": 0.3}, bad={"tau_0": NEG}))
_add(_g + "work_along_path", Entry({"F": V4, "r": PTS}, {"F": (4, 3), "r": (4, 3)}))
_add(
    _g + "work_from_power",
    Entry(
        {"P": (1.0, 2.0, 0.5, 0.0), "t": (0.0, 0.5, 1.0, 2.0)},
        {"P": (4,), "t": (4,)},
        bad={"t": [(0.0, 1.0, 0.5, 2.0)]},
    ),
)
_add(_g + "work_of_couple", Entry({"M": V, "dphi": V2}, {"M": (3,), "dphi": (3,)}))

# -------------------------------------------------------------------------------- fluids
_f = "mechanics.fluids."
_add(
    _f + "bernoulli_constant",
    Entry(
        {"v": V, "p": 1e5, "z": 1.0, "rho_0": 1000.0, "g": 9.81}, {"v": (3,)}, bad={"rho_0": NONPOS}
    ),
)
_FS = {"f": FIELD, "v": FIELD, "p": FIELD, "rho": FIELD}
_add(
    _f + "continuity_residual",
    Entry(
        {"rho": _field_s, "v": _field_v, "r": V, "t": 0.0},
        {"r": (3,)},
        bad={"v": [_nan_field], "rho": [_nan_scalar_field]},
        skip=_FS,
        only=("r", "t", "v", "rho"),
    ),
)
_add(
    _f + "curl",
    Entry(
        {"v": _field_v, "r": V, "t": 0.0},
        {"r": (3,)},
        bad={"v": [_nan_field]},
        only=("r", "t", "v"),
    ),
)
_add(
    _f + "divergence",
    Entry(
        {"v": _field_v, "r": V, "t": 0.0},
        {"r": (3,)},
        bad={"v": [_nan_field]},
        only=("r", "t", "v"),
    ),
)
_add(
    _f + "velocity_gradient",
    Entry(
        {"v": _field_v, "r": V, "t": 0.0},
        {"r": (3,)},
        bad={"v": [_nan_field]},
        only=("r", "t", "v"),
    ),
)
_add(
    _f + "gradient",
    Entry(
        {"f": _field_s, "r": V, "t": 0.0},
        {"r": (3,)},
        bad={"f": [_nan_scalar_field]},
        only=("r", "t", "f"),
    ),
)
_add(
    _f + "partial_time_derivative",
    Entry(
        {"f": _field_s, "r": V, "t": 0.0},
        {"r": (3,)},
        bad={"f": [_nan_scalar_field]},
        only=("r", "t", "f"),
    ),
)
_add(
    _f + "material_derivative",
    Entry(
        {"f": _field_s, "v": _field_v, "r": V, "t": 0.0},
        {"r": (3,)},
        bad={"f": [_nan_scalar_field], "v": [_nan_field]},
        only=("r", "t", "f", "v"),
    ),
)
_add(
    _f + "euler_residual",
    Entry(
        {"v": _field_v, "p": _field_s, "r": V, "t": 0.0, "rho": 1000.0, "g": 9.81},
        {"r": (3,)},
        bad={"rho": NONPOS, "v": [_nan_field], "p": [_nan_scalar_field]},
        only=("r", "t", "rho", "g", "v", "p"),
    ),
)
_add(
    _f + "drain_time",
    Entry(
        {"h_0": 1.0, "g": 9.81, "area_ratio": 0.1},
        bad={"h_0": NEG, "g": NONPOS, "area_ratio": [1.0, -0.1]},
    ),
)
_add(
    _f + "rigid_velocity_field",
    Entry(
        {"v_0": V, "omega": V2}, {"v_0": (3,), "omega": (3,)}, post=lambda f: f(np.array(V), 0.0)
    ),
)
_add(
    _f + "streamline",
    Entry(
        {"v": _field_v, "r_0": V, "s": (0.0, 0.5, 1.0), "rtol": 1e-10},
        {"r_0": (3,), "s": (3,)},
        bad={"v": [_nan_field], "s": [(0.0, 1.0, 0.5)], "rtol": [0.0, -1.0, 1e-20, 1.5]},
        only=("r_0", "s", "v", "rtol"),
    ),
)
_add(
    _f + "tank_level",
    Entry(
        {"t": 0.3, "h_0": 1.0, "g": 9.81, "area_ratio": 0.1},
        bad={"h_0": NEG, "g": NONPOS, "area_ratio": [1.0, -0.1]},
    ),
)
_add(
    _f + "torricelli_speed",
    Entry(
        {"h": 1.0, "g": 9.81, "area_ratio": 0.1},
        bad={"h": NEG, "g": NONPOS, "area_ratio": [1.0, -0.1]},
    ),
)

# -------------------------------------------------------------------------------- impact
_i = "mechanics.impact."
_DIRECT = {"m_1": 1.0, "m_2": 2.0, "v_1": 1.0, "v_2": -0.5, "e": 0.7, "separating": "raise"}
_DBAD = {"m_1": NEG, "m_2": NEG, "e": E_BAD}
for _n in (
    "compression_restitution_impulses",
    "direct_impact",
    "energy_loss_direct",
    "impulse_direct",
):
    _add(_i + _n, Entry(dict(_DIRECT), bad=_DBAD, opts=("separating",)))
_add(
    _i + "centre_of_percussion",
    Entry(
        {"m": 2.0, "J_A": JT, "r_G": (0.5, 0.0, 0.0), "axis_point": (0.0, 0.0, 0.0), "axis": Z},
        {"J_A": (3, 3), "r_G": (3,), "axis_point": (3,), "axis": (3,)},
        bad={"m": NONPOS, "axis": ZERO3},
        post=lambda c: vars(c) if hasattr(c, "__dict__") else tuple(c),
    ),
)
_add(
    _i + "effective_mass",
    Entry(
        {"m_1": 2.0, "J_1": JT, "r_1": V, "n": Z},
        {"J_1": (3, 3), "r_1": (3,), "n": (3,)},
        bad={"m_1": NONPOS, "n": ZERO3},
    ),
)
_add(
    _i + "hinged_effective_mass",
    Entry(
        {
            "J_A": JT,
            "r_P": (0.5, 0.2, 0.0),
            "n": (0.0, 1.0, 0.0),
            "axis_point": (0, 0, 0),
            "axis": Z,
        },
        {"J_A": (3, 3), "r_P": (3,), "n": (3,), "axis_point": (3,), "axis": (3,)},
        bad={"n": ZERO3, "axis": ZERO3},
    ),
)
_add(
    _i + "hinged_impact",
    Entry(
        {
            "m": 2.0,
            "J_A": JT,
            "r_G": (0.5, 0.0, 0.0),
            "axis_point": (0.0, 0.0, 0.0),
            "axis": Z,
            "omega": 1.0,
            "r_P": (0.8, 0.0, 0.0),
            "S_P": (0.0, 1.0, 0.0),
        },
        {"J_A": (3, 3), "r_G": (3,), "axis_point": (3,), "axis": (3,), "r_P": (3,), "S_P": (3,)},
        bad={"m": NONPOS, "axis": ZERO3},
        post=lambda h: [getattr(h, k) for k in vars(h)] if hasattr(h, "__dict__") else tuple(h),
    ),
)


def _body(**kw):
    from mechanics.impact import RigidBody

    args = {
        "m": 1.0,
        "J_G": JT,
        "r_G": (0.0, 0.0, 0.0),
        "v_G": (0.0, 0.0, -1.0),
        "omega": (0.0, 0.0, 0.0),
    }
    return RigidBody(**(args | kw))


_add(
    _i + "RigidBody",
    Entry(
        {"m": 1.0, "J_G": JT, "r_G": V, "v_G": V2, "omega": V},
        {"J_G": (3, 3), "r_G": (3,), "v_G": (3,), "omega": (3,)},
        bad={"m": NONPOS, "J_G": [((1.0, 0, 0), (0, 1.0, 0), (0, 0, 3.0))]},
        post=lambda b: (b.m, b.J_G, b.r_G, b.v_G, b.omega),
    ),
)
_add(
    _i + "normal_relative_velocity",
    Entry(
        {"body_1": "body", "r_S": (0.0, 0.0, -0.5), "n": Z},
        {"r_S": (3,), "n": (3,)},
        bad={"n": ZERO3},
        skip={"body_1": "a RigidBody, fuzzed as RigidBody"},
        only=("r_S", "n"),
    ),
)
_add(
    _i + "rigid_impact",
    Entry(
        {"body_1": "body", "r_S": (0.0, 0.0, -0.5), "n": Z, "e": 0.5, "separating": "raise"},
        {"r_S": (3,), "n": (3,)},
        bad={"n": ZERO3, "e": E_BAD},
        opts=("separating",),
        skip={"body_1": "a RigidBody, fuzzed as RigidBody"},
        post=lambda r: [getattr(r, k) for k in vars(r)] if hasattr(r, "__dict__") else tuple(r),
    ),
)

# ------------------------------------------------------------------------------- inertia
_n = "mechanics.inertia."
_add(
    _n + "box",
    Entry({"m": 2.0, "a": 1.0, "b": 2.0, "c": 3.0}, bad={"m": NEG, "a": NEG, "b": NEG, "c": NEG}),
)
_add(_n + "cylinder", Entry({"m": 2.0, "R": 0.5, "h": 1.0}, bad={"m": NEG, "R": NEG, "h": NEG}))
_add(
    _n + "cylindrical_shell",
    Entry({"m": 2.0, "R": 0.5, "h": 1.0}, bad={"m": NEG, "R": NEG, "h": NEG}),
)
_add(_n + "solid_cone", Entry({"m": 2.0, "R": 0.5, "h": 1.0}, bad={"m": NEG, "R": NEG, "h": NEG}))
for _s in ("disc", "hollow_sphere", "ring", "solid_sphere"):
    _add(_n + _s, Entry({"m": 2.0, "R": 0.5}, bad={"m": NEG, "R": NEG}))
_add(
    _n + "rectangular_plate",
    Entry({"m": 2.0, "a": 1.0, "b": 2.0}, bad={"m": NEG, "a": NEG, "b": NEG}),
)
_add(_n + "rod", Entry({"m": 2.0, "ell": 1.0}, bad={"m": NEG, "ell": NEG}))
_NONPHYS = [((1.0, 0, 0), (0, 1.0, 0), (0, 0, 3.0)), ((1.0, 0.5, 0), (0, 1.0, 0), (0, 0, 1.0))]
_add(
    _n + "check_inertia",
    Entry(
        {"J": JT},
        {"J": (3, 3)},
        bad={"J": _NONPHYS},
        skip={"about_centre_of_mass": FLAG, "allow_singular": FLAG, "name": NAME},
    ),
)
_add(
    _n + "four_particle_realisation",
    Entry({"m": 2.0, "J": JT}, {"J": (3, 3)}, bad={"m": NONPOS, "J": _NONPHYS}),
)
_add(
    _n + "inertia_A_from_O",
    Entry(
        {"J_O": JT, "R_A_O": R},
        {"J_O": (3, 3), "R_A_O": (3, 3)},
        bad={"R_A_O": [((1.0, 0, 0), (0, 1.0, 0), (0, 0, 2.0))]},
    ),
)
_add(
    _n + "rotate_inertia",
    Entry(
        {"J_A": JT, "R_A_O": R},
        {"J_A": (3, 3), "R_A_O": (3, 3)},
        bad={"R_A_O": [((1.0, 0, 0), (0, 1.0, 0), (0, 0, 2.0))]},
    ),
)
_add(
    _n + "inertia_tensor",
    Entry(
        {"m": M4, "r": PTS, "about": (0.0, 0.0, 0.0)},
        {"m": (4,), "r": (4, 3), "about": (3,)},
        bad={"m": [(1.0, -2.0, 3.0, 4.0)]},
    ),
)
_add(_n + "is_physical_inertia", Entry({"J": JT}, {"J": (3, 3)}, skip={"allow_singular": FLAG}))
_add(
    _n + "parallel_axis",
    Entry(
        {"J_G": JT, "m": 2.0, "d": V},
        {"J_G": (3, 3), "d": (3,)},
        bad={"m": NEG, "J_G": _NONPHYS},
        skip={"allow_singular": FLAG},
    ),
)
_add(
    _n + "principal_axes",
    Entry({"J": JT}, {"J": (3, 3)}, bad={"J": _NONPHYS}, skip={"allow_singular": FLAG}),
)
_add(
    _n + "principal_subspaces",
    Entry({"J": JT}, {"J": (3, 3)}, bad={"J": _NONPHYS}, skip={"rtol": ATOL}),
)

# --------------------------------------------------------------------------- integrators
_t = "mechanics.integrators."
_add(
    _t + "free_rigid_body_rhs",
    Entry(
        {"J": JP},
        {"J": (3,)},
        bad={"J": [(0.0, 1.0, 1.0)]},
        post=lambda f: f(0.0, np.r_[V, np.eye(3).ravel()]),
    ),
)
_add(
    _t + "free_rigid_body_splitting",
    Entry(
        {"J": JP, "L0": V, "R0": R, "t": (0.0, 0.5), "h": 0.1},
        {"J": (3,), "L0": (3,), "R0": (3, 3), "t": (2,)},
        bad={"J": [(0.0, 1.0, 1.0), (1.0, 1.0, 3.0)], "h": NONPOS, "order": [3]},
        skip={"compiled": FLAG},
        post=lambda s: (s.t, s.y),
    ),
)
_add(
    _t + "integrate",
    Entry(
        {"rhs": _rhs_decay, "y0": 1.0, "t": (0.0, 1.0), "method": "rk4", "h": 0.1},
        {"t": (2,)},
        bad={"h": NONPOS, "rhs": [_rhs_nan], "t": [(1.0, 0.0)]},
        opts=("method",),
        skip={
            "rhs": "a callable; its NaN output is a listed bad value",
            "kahan": FLAG,
            "compiled": FLAG,
        },
        only=("y0", "t", "h", "method", "rhs"),
        post=lambda s: (s.t, s.y),
    ),
)
_add(_t + "rigid_body_parts", Entry({"y": np.r_[V, np.eye(3).ravel()]}, {"y": (12,)}))
_add(_t + "rigid_body_state", Entry({"L_A": V, "R_A_O": R}, {"L_A": (3,), "R_A_O": (3, 3)}))
_add(_t + "so3_exp_step", Entry({"R_A_O": R, "w_A": V, "h": 0.1}, {"R_A_O": (3, 3), "w_A": (3,)}))
_add(_t + "time_grid", Entry({"t0": 0.0, "h": 0.1, "n": 10}, bad={"h": NONPOS, "n": [-1, 2.5]}))
_add(
    _t + "DOP853Stepper",
    Entry(
        {
            "rhs": _rhs_decay,
            "t0": 0.0,
            "y0": (1.0, 2.0),
            "t_bound": 1.0,
            "rtol": 1e-10,
            "atol": 1e-10,
        },
        {"y0": (2,)},
        bad={"rtol": NONPOS, "atol": [-1.0]},
        skip={"rhs": "a callable"},
        only=("t0", "y0", "t_bound", "rtol", "atol"),
        post=lambda s: (s.step(), s.t, s.y),
    ),
)

# ---------------------------------------------------------------------------- kinematics
_k = "mechanics.kinematics."
_add(
    _k + "angular_velocity_from_euler_rates",
    Entry({"psi": 0.1, "theta": 0.5, "phi": 0.2, "psidot": 1.0, "thetadot": 0.3, "phidot": -0.2}),
)
_add(
    _k + "angular_velocity_from_matrix_rate",
    Entry(
        {"R_A_O": R, "Rdot_A_O": RDOT, "basis": "A"},
        {"R_A_O": (3, 3), "Rdot_A_O": (3, 3)},
        opts=("basis",),
        bad={"R_A_O": [((1.0, 0, 0), (0, 1.0, 0), (0, 0, 2.0))]},
    ),
)
_add(
    _k + "euler_rates_from_angular_velocity",
    Entry({"theta": 0.5, "phi": 0.2, "w_A": V}, {"w_A": (3,)}, bad={"theta": [0.0, math.pi]}),
)
_add(
    _k + "instantaneous_axis",
    Entry({"v_A": V, "omega": V2}, {"v_A": (3,), "omega": (3,)}, bad={"omega": ZERO3}),
)
_add(
    _k + "instantaneous_centre_plane",
    Entry(
        {"r_A": (1.0, 2.0), "v_A": (0.3, -0.1), "omega_z": 0.5},
        {"r_A": (2,), "v_A": (2,)},
        bad={"omega_z": [0.0]},
    ),
)
_add(_k + "omega_matrix_from_vector", Entry({"w_A": V}, {"w_A": (3,)}))
_add(
    _k + "point_velocity",
    Entry({"v_A": V, "omega": V2, "r_AB": Z}, {"v_A": (3,), "omega": (3,), "r_AB": (3,)}),
)
_add(
    _k + "rigid_velocity_from_points",
    Entry(
        {"r": PTS[:3], "v": ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))},
        {"r": (3, 3), "v": (3, 3)},
        bad={"r": [((0.0, 0, 0), (1.0, 0, 0), (2.0, 0, 0))]},
    ),
)
_add(
    _k + "vector_from_omega_matrix",
    Entry(
        {"Omega": ((0.0, -0.5, 0.2), (0.5, 0.0, -0.3), (-0.2, 0.3, 0.0))}, {"Omega": (3, 3)}
    ),  # reads the antisymmetric part: documented,
)

# -------------------------------------------------------------------------- open systems
_o = "mechanics.open_systems."
_add(
    _o + "angular_momentum_rate",
    Entry(
        {"M_e": V, "about": (0.0, 0.0, 0.0), "q_out": 0.5, "r_out": V2, "v_out": V},
        {"M_e": (3,), "about": (3,), "r_out": (3,), "v_out": (3,)},
        bad={"q_out": NEG},
    ),
)
_add(_o + "burn_out_time", Entry({"m_f": 10.0, "q": 2.0}, bad={"m_f": NEG, "q": NONPOS}))
_CAR = {"J_0": 10.0, "q": 0.5, "v": 2.0, "r": 0.5, "R": 1.0}
_add(
    _o + "carousel_angular_acceleration",
    Entry({"t": 1.0, **_CAR}, bad={"J_0": NONPOS, "q": NEG, "R": NONPOS}),
)
_add(
    _o + "carousel_angular_velocity",
    Entry({"t": 1.0, **_CAR}, bad={"J_0": NONPOS, "q": NEG, "R": NONPOS}),
)
_add(
    _o + "carousel_limit_angular_velocity", Entry({"v": 2.0, "r": 0.5, "R": 1.0}, bad={"R": NONPOS})
)
_add(
    _o + "falling_chain_table_force",
    Entry(
        {"x": 0.3, "lam": 0.2, "h": 0.0, "g": 9.81, "ell": 1.0},
        bad={"lam": NEG, "ell": NONPOS, "x": [-0.1, 2.0]},
    ),
)
_add(
    _o + "jet_velocity",
    Entry({"t": 0.5, "m": 10.0, "q": 1.0, "w": 3.0, "v_0": 0.0}, bad={"m": NONPOS, "q": NEG}),
)
_add(
    _o + "mass_rate",
    Entry({"q_out": 0.5, "q_in": 0.2}, bad={"q_out": NEG, "q_in": NEG}, batch=False),
)
_add(
    _o + "momentum_rate",
    Entry({"F_e": V, "q_out": 0.5, "v_out": V2}, {"F_e": (3,), "v_out": (3,)}, bad={"q_out": NEG}),
)
_add(
    _o + "open_system_acceleration",
    Entry(
        {"m": 2.0, "F_e": V, "q_out": 0.5, "u_out": V2},
        {"F_e": (3,), "u_out": (3,)},
        bad={"m": NONPOS, "q_out": NEG},
    ),
)
_add(_o + "pipe_bend_force", Entry({"q": 2.0, "v": 3.0, "angle": 0.5}, bad={"q": NEG}))
_add(_o + "pipe_bend_force_magnitude", Entry({"q": 2.0, "v": 3.0, "angle": 0.5}, bad={"q": NEG}))
_RIM = {"J_0": 2.0, "q": 0.1, "u": 50.0, "r": 0.5}
_add(
    _o + "rim_rocket_angular_velocity",
    Entry({"t": 1.0, **_RIM}, bad={"J_0": NONPOS, "q": NEG, "r": NONPOS}),
)
_add(
    _o + "rim_rocket_spin_up_time",
    Entry({"omega": 1.0, **_RIM}, bad={"J_0": NONPOS, "q": NEG, "r": NONPOS}),
)
_ROCK = {"m_0": 10.0, "q": 1.0, "u": 100.0, "m_f": 4.0, "g": 9.81, "after_burn_out": "raise"}
_add(
    _o + "rocket_height",
    Entry(
        {"t": 1.0, **_ROCK},
        opts=("after_burn_out",),
        bad={"m_0": NONPOS, "q": NEG, "m_f": [-1.0, 20.0], "t": [-1.0]},
    ),
)
_add(
    _o + "rocket_velocity",
    Entry(
        {"t": 1.0, **_ROCK},
        opts=("after_burn_out",),
        bad={"m_0": NONPOS, "q": NEG, "m_f": [-1.0, 20.0], "t": [-1.0]},
    ),
)
_add(
    _o + "rocket_mass",
    Entry(
        {"t": 1.0, "m_0": 10.0, "q": 1.0, "m_f": 4.0, "after_burn_out": "raise"},
        opts=("after_burn_out",),
        bad={"m_0": NONPOS, "q": NEG, "m_f": [-1.0, 20.0]},
    ),
)
_add(_o + "thrust", Entry({"q": 2.0, "u_rel": V}, {"u_rel": (3,)}, bad={"q": NEG}))

# ----------------------------------------------------------------------------- particles
_p = "mechanics.particles."
_MR = {"m": M4, "r": PTS}
_A_MR = {"m": (4,), "r": (4, 3)}
_MBAD = {"m": [(1.0, -2.0, 3.0, 4.0)]}
_add(
    _p + "angular_momentum",
    Entry(
        {**_MR, "v": V4, "about": (0.0, 0.0, 0.0)}, {**_A_MR, "v": (4, 3), "about": (3,)}, bad=_MBAD
    ),
)
_add(
    _p + "angular_momentum_decomposition",
    Entry(
        {**_MR, "v": V4, "about": (0.0, 0.0, 0.0)},
        {**_A_MR, "v": (4, 3), "about": (3,)},
        bad={"m": [(1.0, -2.0, 3.0, 4.0), (0.0, 0.0, 0.0, 0.0)]},
    ),
)
_add(
    _p + "angular_momentum_rate",
    Entry(
        {**_MR, "v": V4, "a": F4, "about": (0.0, 0.0, 0.0), "about_velocity": V},
        {**_A_MR, "v": (4, 3), "a": (4, 3), "about": (3,), "about_velocity": (3,)},
        bad=_MBAD,
    ),
)
_add(
    _p + "average_angular_velocity",
    Entry(
        {**_MR, "v": V4, "about": (0.0, 0.0, 0.0), "axis": Z},
        {**_A_MR, "v": (4, 3), "about": (3,), "axis": (3,)},
        bad={"m": [(1.0, -2.0, 3.0, 4.0)], "axis": ZERO3},
    ),
)
_add(
    _p + "axial_component",
    Entry({"x": V, "axis": Z}, {"x": (3,), "axis": (3,)}, bad={"axis": ZERO3}),
)
_add(
    _p + "centre_of_mass",
    Entry(dict(_MR), dict(_A_MR), bad={"m": [(1.0, -2.0, 3.0, 4.0), (0.0, 0.0, 0.0, 0.0)]}),
)
_add(
    _p + "centre_of_mass_velocity",
    Entry(
        {"m": M4, "v": V4},
        {"m": (4,), "v": (4, 3)},
        bad={"m": [(1.0, -2.0, 3.0, 4.0), (0.0, 0.0, 0.0, 0.0)]},
    ),
)
_add(_p + "check_masses", Entry({"m": M4}, {"m": (4,)}, bad=_MBAD, skip={"name": NAME}))
_RHO = (1.0, 2.0, 3.0, 4.0)
_add(
    _p + "continuous_angular_momentum",
    Entry(
        {"rho": _RHO, "points": PTS, "velocity": V4, "cell_volume": 0.1, "about": (0.0, 0.0, 0.0)},
        {"rho": (4,), "points": (4, 3), "velocity": (4, 3), "about": (3,)},
        bad={"rho": [(1.0, -2.0, 3.0, 4.0)], "cell_volume": NONPOS},
    ),
)
_add(
    _p + "continuous_centre_of_mass",
    Entry(
        {"rho": _RHO, "points": PTS, "cell_volume": 0.1},
        {"rho": (4,), "points": (4, 3)},
        bad={"rho": [(1.0, -2.0, 3.0, 4.0), (0.0,) * 4], "cell_volume": NONPOS},
    ),
)
_add(
    _p + "continuous_momentum",
    Entry(
        {"rho": _RHO, "velocity": V4, "cell_volume": 0.1},
        {"rho": (4,), "velocity": (4, 3)},
        bad={"rho": [(1.0, -2.0, 3.0, 4.0)], "cell_volume": NONPOS},
    ),
)
_add(
    _p + "cylindrical_components",
    Entry(
        {"r": V, "v": V2, "about": (0.0, 0.0, 0.0), "axis": Z},
        {"r": (3,), "v": (3,), "about": (3,), "axis": (3,)},
        bad={"axis": ZERO3},
        post=lambda c: tuple(c),
    ),
)
_F44 = np.zeros((4, 4, 3))
_F44[0, 1] = (1.0, 0.0, 0.0)
_F44[1, 0] = (-1.0, 0.0, 0.0)
_add(_p + "internal_forces", Entry({"f": _F44}, {"f": (4, 4, 3)}))
_add(_p + "internal_moment", Entry({"r": PTS, "f": _F44}, {"r": (4, 3), "f": (4, 4, 3)}))
_add(_p + "kinetic_energy", Entry({"m": M4, "v": V4}, {"m": (4,), "v": (4, 3)}, bad=_MBAD))
_add(
    _p + "kinetic_energy_decomposition",
    Entry(
        {"m": M4, "v": V4}, {"m": (4,), "v": (4, 3)}, bad={"m": [(1.0, -2.0, 3.0, 4.0), (0.0,) * 4]}
    ),
)
_add(
    _p + "masses_from_density",
    Entry(
        {"rho": _RHO, "cell_volume": 0.1},
        {"rho": (4,)},
        bad={"rho": [(1.0, -2.0, 3.0, 4.0)], "cell_volume": NONPOS},
    ),
)
_add(
    _p + "moment_of_forces",
    Entry({"r": PTS, "F": F4, "about": (0.0, 0.0, 0.0)}, {"r": (4, 3), "F": (4, 3), "about": (3,)}),
)
_add(
    _p + "moment_of_inertia_about_axis",
    Entry(
        {**_MR, "about": (0.0, 0.0, 0.0), "axis": Z},
        {**_A_MR, "about": (3,), "axis": (3,)},
        bad={"m": [(1.0, -2.0, 3.0, 4.0)], "axis": ZERO3},
    ),
)
_add(_p + "momentum", Entry({"m": M4, "v": V4}, {"m": (4,), "v": (4, 3)}, bad=_MBAD))
_add(
    _p + "moving_base_point_term",
    Entry(
        {"m": M4, "v": V4, "about_velocity": V},
        {"m": (4,), "v": (4, 3), "about_velocity": (3,)},
        bad=_MBAD,
    ),
)
_add(_p + "total_mass", Entry({"m": M4}, {"m": (4,)}, bad=_MBAD))

# ------------------------------------------------------------------------------ rotation
_r = "mechanics.rotation."
_NOTROT = [((1.0, 0, 0), (0, 1.0, 0), (0, 0, 2.0)), ((1.0, 0, 0), (0, 1.0, 0), (0, 0, -1.0))]
for _a in ("R1", "R2", "R3"):
    _add(_r + _a, Entry({"alpha": 0.4}))
_add(_r + "active_from_passive", Entry({"R_A_O": R}, {"R_A_O": (3, 3)}, bad={"R_A_O": _NOTROT}))
_add(
    _r + "passive_from_active",
    Entry({"R_active": R}, {"R_active": (3, 3)}, bad={"R_active": _NOTROT}),
)
_add(
    _r + "check_rotation",
    Entry(
        # name: the message names what the caller calls the matrix (default "R_A_O")
        {"R": R, "atol": 1e-12, "name": "R"},
        {"R": (3, 3)},
        bad={"R": _NOTROT, "atol": NEG},
        skip={"name": NAME},
    ),
)
_add(
    _r + "components_A_from_O",
    Entry({"R_A_O": R, "r_O": V}, {"R_A_O": (3, 3), "r_O": (3,)}, bad={"R_A_O": _NOTROT}),
)
_add(
    _r + "rotate_vector",
    Entry({"R_A_O": R, "r_O": V}, {"R_A_O": (3, 3), "r_O": (3,)}, bad={"R_A_O": _NOTROT}),
)
_add(
    _r + "compose",
    Entry(
        {"R_B_A": R_B, "R_A_O": R},
        {"R_B_A": (3, 3), "R_A_O": (3, 3)},
        bad={"R_B_A": _NOTROT, "R_A_O": _NOTROT},
    ),
)
_add(
    _r + "compose_quat",
    Entry(
        {"q_B_A": Q2, "q_A_O": Q},
        {"q_B_A": (4,), "q_A_O": (4,)},
        bad={"q_B_A": [(0.0,) * 4], "q_A_O": [(0.0,) * 4]},
    ),
)
_add(_r + "euler_from_matrix", Entry({"R_A_O": R}, {"R_A_O": (3, 3)}, bad={"R_A_O": _NOTROT}))
_add(_r + "euler_near_gimbal_lock", Entry({"theta": 0.3, "atol": 1e-6}, bad={"atol": NEG}))
_add(_r + "is_rotation", Entry({"R": R, "atol": 1e-12}, {"R": (3, 3)}, bad={"atol": NEG}))
_add(
    _r + "matrix_from_axis_angle",
    Entry({"axis": Z, "angle": 0.3}, {"axis": (3,)}, bad={"axis": ZERO3}),
)
_add(_r + "matrix_from_euler", Entry({"psi": 0.1, "theta": 0.2, "phi": 0.3}))
_add(_r + "matrix_from_quat", Entry({"q": Q}, {"q": (4,)}, bad={"q": [(0.0,) * 4]}))
_add(_r + "matrix_from_rotvec", Entry({"rotvec": V}, {"rotvec": (3,)}))
_add(_r + "nearest_rotation", Entry({"M": R}, {"M": (3, 3)}, bad={"M": [np.zeros((3, 3))]}))
_add(_r + "quat_from_matrix", Entry({"R_A_O": R}, {"R_A_O": (3, 3)}, bad={"R_A_O": _NOTROT}))
_add(_r + "quat_from_rotvec", Entry({"rotvec": V}, {"rotvec": (3,)}))
_add(_r + "quat_multiply", Entry({"p": Q2, "q": Q}, {"p": (4,), "q": (4,)}))
_add(_r + "rotvec_from_matrix", Entry({"R_A_O": R}, {"R_A_O": (3, 3)}, bad={"R_A_O": _NOTROT}))
_add(_r + "rotvec_from_quat", Entry({"q": Q}, {"q": (4,)}, bad={"q": [(0.0,) * 4]}))

# ---------------------------------------------------------------------------------- tops
_o3 = "mechanics.tops."
_add(
    _o3 + "FreeAsymmetricTop",
    Entry(
        {"J": JP, "omega_0": (0.3, 1.0, 0.2), "R_A_O_0": R},
        {"J": (3,), "omega_0": (3,), "R_A_O_0": (3, 3)},
        bad={
            "J": [(0.0, 3.0, 4.0), (-2.0, 3.0, 4.0), (1.0, 1.0, 3.0)],
            "R_A_O_0": _NOTROT,
        },
        post=lambda top: (top.omega(1.3), top.attitude(1.3), top.precession_angle(1.3)),
    ),
)
_add(
    _o3 + "FreeSymmetricTop",
    Entry(
        {"J1": 2.0, "J3": 3.0, "omega_0": V, "R_A_O_0": R},
        {"omega_0": (3,), "R_A_O_0": (3, 3)},
        bad={"J1": NONPOS, "J3": [0.0, -1.0, 5.0], "R_A_O_0": _NOTROT},
        post=lambda top: (top.omega(1.3), top.attitude(1.3)),
    ),
)
_add(
    _o3 + "FreeTopBatch",
    Entry(
        {"J": (JP, (1.0, 2.0, 2.5)), "omega_0": ((0.3, 1.0, 0.2), V), "R_A_O_0": (R, R_B)},
        {"J": (3,), "omega_0": (3,), "R_A_O_0": (3, 3)},
        bad={
            "J": [((0.0, 3.0, 4.0), JP), ((-2.0, 3.0, 4.0), JP), ((1.0, 1.0, 3.0), JP)],
            "R_A_O_0": [(R, _NOTROT[0])],
        },
        post=lambda batch: batch.state(1.3),
    ),
)
_HEAVY = {
    "J_1": 2.0,
    "J_3": 1.0,
    "m_g_ell": 3.0,
    "theta": 0.5,
    "psi": 0.1,
    "phi": 0.2,
    "theta_dot": 0.1,
    "psi_dot": 1.0,
    "phi_dot": 8.0,
}
_add(
    _o3 + "HeavySymmetricTop",
    Entry(
        dict(_HEAVY),
        bad={"J_1": NONPOS, "J_3": [0.0, -1.0, 5.0], "m_g_ell": NEG, "theta": [0.0, 4.0]},
        post=lambda top: (top.theta(0.7), top.psi(0.7), top.phi(0.7), top.nutation_period()),
    ),
)
_add(
    _o3 + "check_principal_moments",
    Entry(
        {"J": JP}, {"J": (3,)}, bad={"J": [(0.0, 3.0, 4.0), (1.0, 1.0, 3.0)]}, skip={"name": NAME}
    ),
)
_add(
    _o3 + "principal_axis_stability",
    Entry(
        {"J": JP, "axis": 1, "omega": 1.0},
        {"J": (3,)},
        bad={"J": [(0.0, 3.0, 4.0), (1.0, 1.0, 3.0)], "axis": [0, 4, 1.5]},
        post=lambda s: (s.rate, s.CiCk),
    ),
)
_add(
    _o3 + "sleeping_top_is_stable",
    Entry({"J_1": 2.0, "L_3": 5.0, "m_g_ell": 3.0}, bad={"J_1": NONPOS, "m_g_ell": NEG}),
)
_add(
    _o3 + "steady_precession_rates",
    Entry(
        {"J_1": 2.0, "L_3": 5.0, "m_g_ell": 3.0, "theta": 0.5}, bad={"J_1": NONPOS, "m_g_ell": NEG}
    ),
)
_add(
    _o3 + "spherical_top_on_incline",
    Entry(
        {"t": 0.5, "m": 1.0, "R": 0.1, "J": 0.004, "beta": 0.3, "g": 9.81},
        bad={"m": NONPOS, "R": NONPOS, "J": NONPOS, "g": NEG},
    ),
)

_PLUMBING = "scene plumbing (engine, effect specs, dense segments): no numeric user input; "
_PLUMBING += "reached through the scene loader's fuzz (test_scene_fuzz.py)"
_RECORD = "a record the library builds and returns (its fields are computed, not user input)"
_STRAT = "a hypothesis strategy: bad bounds raise hypothesis' InvalidArgument, tested in "
_STRAT += "tests/theorems/test_*strategy_quality.py"

#: public callables that are not fuzzed, and why
EXEMPT: dict[str, str] = {
    "mechanics.conformance.protocol.Adapter": "a Protocol an outside engine implements",
    "mechanics.conformance.protocol.check_trajectory": (
        "validates an adapter's answer against its scenario: its own fuzz is the "
        "conformance battery's (ConformanceError naming scenario and field)"
    ),
    "mechanics.particles.Cylindrical": _RECORD,
    "mechanics.impact.CentreOfPercussion": _RECORD,
    "mechanics.impact.HingedImpact": _RECORD,
    "mechanics.impact.RigidImpact": _RECORD,
    "mechanics.tops.StabilityResult": _RECORD,
    "mechanics.integrators.Solution": _RECORD,
    "mechanics.integrators.DenseStep": _RECORD,
    "mechanics.pytest_plugin.EpsClose": "a pytest fixture's helper (tolerances in eps)",
    "mechanics.pytest_plugin.register_profiles": "takes no arguments",
    "mechanics.testing.assert_allclose_eps": "a test assertion: raises AssertionError by design",
    "mechanics.testing.assert_quaternions_close": "a test assertion",
    "mechanics.testing.assert_rotations_close": "a test assertion",
    "mechanics.scenes.builtin_path": "takes a built-in scene's name; fuzzed by the CLI's demo",
    "mechanics.scenes.builtin_scenes": "takes no arguments",
    "mechanics.scenes.reference.scene_file_reference": "takes no arguments",
    "mechanics.scenes.spec.load_scene": "fuzzed in test_scene_fuzz.py",
    "mechanics.scenes.spec.parse_scene": "fuzzed in test_scene_fuzz.py",
    "mechanics.scenes.spec.Body": "built by parse_scene (fuzzed in test_scene_fuzz.py)",
    "mechanics.scenes.spec.EffectSpec": "built by parse_scene (fuzzed in test_scene_fuzz.py)",
    "mechanics.scenes.spec.Scene": "built by parse_scene (fuzzed in test_scene_fuzz.py)",
    "mechanics.scenes.result.run_scene": "runs a parsed Scene: fuzzed in test_scene_fuzz.py",
    "mechanics.scenes.simulate.simulate": "runs a parsed Scene: fuzzed in test_scene_fuzz.py",
    "mechanics.scenes.simulate.validate": "validates a parsed Scene: test_scene_fuzz.py",
    "mechanics.scenes.engine.validate": "validates a parsed Scene: test_scene_fuzz.py",
    "mechanics.scenes.model.check": "validates a parsed Scene (engine.validate): "
    "test_scene_fuzz.py",
    "mechanics.scenes.budget.Clock": "a parsed Scene's run clock: test_whole_scene_fuzz.py",
    "mechanics.scenes.budget.check_memory": "takes a parsed Scene: test_whole_scene_fuzz.py",
    "mechanics.scenes.budget.check_steps": "takes a parsed Scene: test_whole_scene_fuzz.py",
    "mechanics.scenes.budget.memory_estimate": "takes a parsed Scene: test_whole_scene_fuzz.py",
    "mechanics.scenes.budget.sample_limit": "takes a parsed Scene: test_whole_scene_fuzz.py",
    "mechanics.scenes.budget.fastest_rate": "takes a parsed Scene: test_whole_scene_fuzz.py",
    "mechanics.scenes.budget.step_estimate": "takes a parsed Scene: test_whole_scene_fuzz.py",
    "mechanics.scenes.domain.check_angle": "the parser's domain check: every scene number of "
    "test_whole_scene_fuzz.py and test_scene_fuzz.py passes through it",
    "mechanics.scenes.domain.check_magnitude": "the parser's domain check: every scene number "
    "of test_whole_scene_fuzz.py and test_scene_fuzz.py passes through it",
    "mechanics.scenes.domain.domain_of": "takes a unit's name (the reference's text)",
    "mechanics.scenes.contacts.chebyshev_fit": "takes a trajectory segment's callable; "
    + _PLUMBING,
    "mechanics.scenes.contacts.first_downward_crossing": "takes Chebyshev coefficients of a "
    "gap; " + _PLUMBING,
}
for _name in (
    "scenes.derived.derived_quantities",
    "scenes.effects.build_effects",
    "scenes.effects.base.Context",
    "scenes.effects.base.Effect",
    "scenes.effects.base.Loads",
    "scenes.effects.base.Snapshot",
    "scenes.effects.base.check_joint_body",
    "scenes.effects.base.check_on_fixed_axis",
    "scenes.effects.base.gravity_vector",
    "scenes.effects.base.keeps_for_force_along",
    "scenes.effects.base.register",
    "scenes.effects.capabilities.AddsInertia",
    "scenes.effects.capabilities.ChangesMass",
    "scenes.effects.capabilities.Compiles",
    # protocols of what the effects read of a scene, a spec and a body (types, not called)
    "scenes.effects.base.BodyLike",
    "scenes.effects.base.SceneLike",
    "scenes.effects.base.SpecLike",
    "scenes.effects.capabilities.GuidesBody",
    "scenes.effects.capabilities.HasModes",
    "scenes.effects.capabilities.HasPotential",
    "scenes.effects.rolling.check_round_on_slope",
    "scenes.engine.Engine",
    # the engine's rooms: each takes the model compiled from a parsed, validated scene
    "scenes.bodies.Body",
    "scenes.bodies.Fixed",
    "scenes.bodies.Guided",
    "scenes.bodies.Pinned",
    "scenes.bodies.Point",
    "scenes.bodies.Rigid",
    "scenes.bodies.Tank",
    "scenes.model.Model",
    "scenes.model.initial_attitude",
    "scenes.model.initial_omega",
    "scenes.forward.Forward",
    "scenes.compiled.CompiledRhs",
    "scenes.compiled.CompiledStepper",
    "scenes.compiled.build",
    "scenes.compiled.program",
    "scenes.compiled.stepper",
    # (and two that take no argument: loading the kernels; the reference path's block)
    "scenes.compiled.warm",
    "scenes.compiled.reference_path",
    "scenes.flows.Calendar",
    "scenes.flows.Flow",
    "scenes.flows.find",
    "scenes.flows.free_flight",
    "scenes.flows.free_flight_flow",
    "scenes.flows.guided_flow",
    "scenes.flows.pinned_flow",
    "scenes.flows.rocket_flow",
    "scenes.flows.tank_flow",
    "scenes.collision.Collision",
    "scenes.collision.Hit",
    "scenes.collision.StepFit",
    "scenes.collision.check_initial_overlap",
    "scenes.impacts.Resolver",
    "scenes.impacts.falls_in",
    "scenes.impacts.zeno",
    "scenes.modes.Modes",
    "scenes.support.Rest",
    "scenes.support.Support",
    "scenes.integrate.integrate",
    "scenes.integrate.rows",
    "scenes.report.finish",
    "scenes.report.top_angles",
    "scenes.splitting.check",
    "scenes.splitting.run",
    "scenes.state.Guide",
    "scenes.state.Hinge",
    "scenes.state.Layout",
    "scenes.state.body_inertia",
    "scenes.state.body_radius",
    "scenes.state.body_vertices",
    "scenes.trajectory.Event",
    "scenes.trajectory.Trajectory",
    "scenes.trajectory.dense_from_segments",
    "scenes.trajectory.sample_dense",
    "scenes.trajectory.sample_segments",
    "scenes.trajectory.vectorized",
    "scenes.result.Comparison",
    "scenes.result.ConservedReport",
    "scenes.result.SceneResult",
    "scenes.result.SelfCheck",
):
    EXEMPT["mechanics." + _name] = _PLUMBING
_KERNEL = (
    "an engine kernel called on state that parse_scene and the engine already validated "
    "(hot path, no re-validation by design); reached through the scene loader's fuzz"
)
for _name in (
    "scenes.contacts.plane_contact_time",
    "scenes.contacts.plane_contact_times",
    "scenes.contacts.quadratic_roots",
    "scenes.contacts.sphere_contact_time",
    "scenes.contacts.sphere_contact_times",
    "scenes.impacts.solve_lcp",
    "scenes.effects.base.unit",
    "scenes.effects.rolling.slope_frame",
    "scenes.trajectory.energy_scale",
    "scenes.trajectory.tolerance_scale",
    "scenes.vectors.cross",
    "scenes.vectors.cross3",
    "scenes.state.point_acceleration",
    "scenes.state.turned",
):
    EXEMPT["mechanics." + _name] = _KERNEL
_EFFECT = (
    "an effect, built from a scene file's [[effects]] table: every field is fuzzed "
    "through the loader (test_scene_fuzz.py)"
)
for _name in (
    "buoyancy.Buoyancy",
    "coulomb_friction.CoulombFriction",
    "coulomb_friction.Slide",
    "drag.Drag",
    "fixed_axis.FixedAxis",
    "fixed_point.FixedPoint",
    "force.Force",
    "force.Torque",
    "gravity.Gravity",
    "impact.Impact",
    "mass_flow.MassFlow",
    "newton_gravity.NewtonGravity",
    "rolling.Incline",
    "rolling.Rolling",
    "rolling.Track",
    "spring.Damper",
    "spring.Spring",
    "tank_outflow.TankOutflow",
    "thrust.Thrust",
    "torsion.Torsion",
):
    EXEMPT[f"mechanics.scenes.effects.{_name}"] = _EFFECT
for _name in (
    "impact.Contact",
    "impact.HingedBody",
    "impact.contact_normals",
    "impact.contacts",
    "impact.direct_velocities",
    "impact.hinged_bodies",
    "impact.impact_bodies",
    "impact.impact_inertia_tensors",
    "impact.impact_masses",
    "impact.mass_pairs",
    "impact.restitution_coefficients",
    "inertia.RigidBody",
    "inertia.inertia_tensors",
    "inertia.principal_moments",
    "inertia.rigid_bodies",
    "particles.ParticleSystem",
    "particles.masses",
    "particles.pair_forces",
    "particles.particle_systems",
    "rotation.euler_angles",
    "rotation.quaternions",
    "rotation.rotation_angles",
    "rotation.rotation_matrices",
    "rotation.rotvecs",
    "rotation.unit_vectors",
    "batching.batches",
    "conformance.body_states",
    "conformance.scenarios",
):
    EXEMPT[f"mechanics.strategies.{_name}"] = _STRAT
_CONFORMANCE = (
    "a record of the conformance protocol (issue 19): a scenario the battery builds, or "
    "an adapter's answer, validated by check_trajectory (ConformanceError naming the field)"
)
for _name in ("Body", "Event", "Ground", "Pivot", "Scenario", "Shape", "Thrust", "Trajectory"):
    EXEMPT[f"mechanics.conformance.protocol.{_name}"] = _CONFORMANCE

# ---------------------------------------------------------------- conformance (issue 19)
# the restitution maps of the engine adapters are plain functions of numbers
_mj = "mechanics.conformance.adapters.mujoco."
_add(_mj + "restitution_without_tension", Entry({"zeta": 0.3}, bad={"zeta": [-0.1, 1.5]}))
_add(_mj + "zeta_without_tension", Entry({"e": 0.8}, bad={"e": [-0.1, 1.5]}))
_add(_mj + "zeta_textbook", Entry({"e": 0.8}, bad={"e": [-0.1, 1.5]}))
_add(
    "mechanics.conformance.adapters.drake.hunt_crossley_dissipation",
    Entry({"e": 0.8, "v_ref": 2.0}, bad={"e": [-0.1, 1.5], "v_ref": [0.0, -1.0]}),
)
_ADAPTER = (
    "an engine adapter or its variants: constructed from option strings (an unknown one is "
    "an UnknownOptionError, tests/conformance/test_engines.py), run on Scenarios"
)
for _name in (
    "dart.DartAdapter",
    "dart.variants",
    "drake.DrakeAdapter",
    "drake.variants",
    "mujoco.MuJoCoAdapter",
    "mujoco.variants",
    "pybullet.PyBulletAdapter",
    "pybullet.variants",
    "siconos.SiconosAdapter",
    "siconos.variants",
    "reference.ExactAdapter",
    "reference.SceneEngineAdapter",
):
    EXEMPT[f"mechanics.conformance.adapters.{_name}"] = _ADAPTER
EXEMPT["mechanics.conformance.adapters.dart.contact_coefficients"] = (
    "reads a Scenario (a record validated where it is built); a scenario no per-body "
    "coefficients express is a reason returned, not an error (tests/conformance/test_dart.py)"
)
EXEMPT["mechanics.conformance.adapters.require"] = (
    "imports a module by name; a missing one is a MissingExtraError naming the extra "
    "(tests/conformance/test_battery.py, test_engines.py)"
)
EXEMPT["mechanics.conformance.adapters.reference.scene_from_scenario"] = (
    "takes a Scenario of the battery (built by the battery, not by a user)"
)
_BATTERY = (
    "the battery's machinery: takes an adapter, Scenarios or Trajectories, whose bad "
    "answers are ConformanceErrors naming scenario and field, and thresholds, profiles "
    "and thresholds files, whose bad keys and values are ThresholdErrors naming them "
    "(tests/conformance/test_battery.py, test_thresholds.py)"
)
for _name in (
    "battery.Figure",
    "battery.Report",
    "battery.Run",
    "battery.ScenarioResult",
    "battery.run_battery",
    "battery.state_errors",
    "compare.Comparison",
    "compare.compare",
    "compare.engine_adapters",
    "diagnosis.diagnose",
    "laws.law_violations",
    "parametrize.conformance_tests",
    "scenarios.Reference",
    "scenarios.body_sizes",
    "scenarios.bounce_apexes",
    "scenarios.check_scenario",
    "scenarios.crossings",
    "scenarios.figure_names",
    "scenarios.get_scenario",
    "scenarios.interpolate",
    "scenarios.invariant_names",
    "scenarios.invariants",
    "scenarios.measure",
    "scenarios.reference",
    "thresholds.Config",
    "thresholds.Profile",
    "thresholds.baseline",
    "thresholds.find_config",
    "thresholds.get_profile",
    "thresholds.load_config",
    "thresholds.known_threshold_keys",
    "thresholds.resolve_thresholds",
):
    EXEMPT[f"mechanics.conformance.{_name}"] = _BATTERY
