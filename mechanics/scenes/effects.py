"""The effects a scene may list: one class per effect, each contributing forces, moments,
potentials, events or an exact flow to the model the scene's constraints select.

Conventions
-----------
- An effect object is built only for an effect the scene lists (:func:`build_effects`);
  a model sums the contributions of the objects it was given and nothing else.  There is
  no default gravity, no damping and no position correction anywhere.
- Free bodies: forces act at the centre of mass G (so they exert no moment about G);
  ``R``, ``V`` are the positions and velocities of the centres, shape ``(n, 3)``; ``M``
  the masses, shape ``(n,)``.
- Fixed axis: φ is the angle about the axis, measured from the direction of gravity's
  component perpendicular to the axis (the book's ϕ of the physical pendulum, 4.3).
- Rolling / sliding on a plane: s is the distance of G down the slope (angle α with the
  horizontal), v = ṡ, ω the spin in the rolling sense (rolling: v = ω r).  On a track of
  radius R the coordinate is ψ, the angle of the line from the track's centre to G with
  the downward vertical (Example 4.5).
- Gravity is g·d with g > 0 and the unit direction d (default (0, 0, −1)).
"""

from __future__ import annotations

import math

import numpy as np

from .spec import EffectSpec

__all__ = [
    "EFFECT_CLASSES",
    "CoulombFriction",
    "Effect",
    "FixedAxis",
    "FixedPoint",
    "Gravity",
    "Impact",
    "MassFlow",
    "Rolling",
    "Spring",
    "TankOutflow",
    "Thrust",
    "Torsion",
    "build_effects",
]


def _unit(v) -> np.ndarray:
    a = np.asarray(v, dtype=float)
    return a / np.linalg.norm(a)


class Effect:
    """Base class: holds the effect's spec (its type, index and validated fields)."""

    type = ""

    def __init__(self, spec: EffectSpec) -> None:
        self.spec = spec
        self.fields = spec.fields

    @property
    def where(self) -> str:
        return self.spec.where

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.fields})"


class Gravity(Effect):
    """Uniform gravity g·d (the book's g = −g e_z with d = (0, 0, −1))."""

    type = "gravity"

    def __init__(self, spec: EffectSpec) -> None:
        super().__init__(spec)
        self.g = float(self.fields["g"])
        self.direction = _unit(self.fields.get("direction", [0.0, 0.0, -1.0]))
        self.vector = self.g * self.direction

    # free bodies
    def free_force(self, t, R, V, M, F) -> None:
        F += M[:, None] * self.vector

    def free_potential(self, R, M) -> np.ndarray:
        return -(M * (R @ self.vector))

    # fixed axis: torque −m g⊥ h sin φ
    def axis_g_perp(self, axis) -> float:
        gp = self.vector - (self.vector @ axis) * axis
        return float(np.linalg.norm(gp))

    def axis_torque(self, m, h, axis, phi) -> np.ndarray:
        return -m * self.axis_g_perp(axis) * h * np.sin(phi)

    def axis_potential(self, m, h, axis, phi) -> np.ndarray:
        return m * self.axis_g_perp(axis) * h * 2.0 * np.sin(0.5 * phi) ** 2

    # fixed point: G at ℓ e3 of the body; moment about C, body components
    def point_torque(self, m, ell, R_A_O) -> np.ndarray:
        g_A = R_A_O @ self.vector
        return ell * m * np.array([-g_A[1], g_A[0], 0.0])  # ℓ e3 × m g_A

    def point_potential(self, m, ell, R_A_O) -> np.ndarray:
        e3_O = R_A_O[..., 2, :]
        return -m * ell * (e3_O @ self.vector)

    # rolling / sliding: generalised force on the coordinate and the potential
    def slope_force(self, m, alpha) -> float:
        return m * self.g * math.sin(alpha)

    def slope_potential(self, m, alpha, s) -> np.ndarray:
        return -m * self.g * math.sin(alpha) * s

    def normal_force(self, m, alpha) -> float:
        return m * self.g * math.cos(alpha)

    def track_force(self, m, R_minus_r, psi) -> np.ndarray:
        return -m * self.g * R_minus_r * np.sin(psi)

    def track_potential(self, m, R_minus_r, psi) -> np.ndarray:
        return m * self.g * R_minus_r * 2.0 * np.sin(0.5 * psi) ** 2


class Spring(Effect):
    """Linear spring between the centres of two bodies, or a body and an anchor point."""

    type = "spring"

    def __init__(self, spec: EffectSpec, index: dict[str, int]) -> None:
        super().__init__(spec)
        self.i = index[self.fields["body"]]
        self.j = index[self.fields["other"]] if "other" in self.fields else None
        self.anchor = np.asarray(self.fields.get("anchor", [0.0, 0.0, 0.0]), dtype=float)
        self.k = float(self.fields["stiffness"])
        self.ell_0 = float(self.fields.get("rest_length", 0.0))

    def _d(self, R):
        other = R[..., self.j, :] if self.j is not None else self.anchor
        return R[..., self.i, :] - other

    def free_force(self, t, R, V, M, F) -> None:
        d = self._d(R)
        L = math.sqrt(d @ d)
        f = -self.k * (L - self.ell_0) * (d / L) if L > 0 else -self.k * d
        F[self.i] += f
        if self.j is not None:
            F[self.j] -= f

    def free_potential(self, R, M) -> np.ndarray:
        L = np.linalg.norm(self._d(R), axis=-1)
        return 0.5 * self.k * (L - self.ell_0) ** 2


class Torsion(Effect):
    """A torsion spring on a fixed axis: moment −τ0 φ (3.1, the torsion pendulum)."""

    type = "torsion"

    def __init__(self, spec: EffectSpec) -> None:
        super().__init__(spec)
        self.tau_0 = float(self.fields["stiffness"])

    def axis_torque(self, m, h, axis, phi) -> np.ndarray:
        return -self.tau_0 * phi

    def axis_potential(self, m, h, axis, phi) -> np.ndarray:
        return 0.5 * self.tau_0 * phi**2


class Thrust(Effect):
    """A rocket motor: mass flow q out at speed u relative to the body, along a fixed
    direction, until the fuel m_f is burnt (T = m_f/q); Example 7.2."""

    type = "thrust"

    def __init__(self, spec: EffectSpec, index: dict[str, int]) -> None:
        super().__init__(spec)
        self.i = index[self.fields["body"]]
        self.q = float(self.fields["mass_flow"])
        self.u = float(self.fields["exhaust_speed"])
        self.m_f = float(self.fields["fuel_mass"])
        self.direction = _unit(self.fields.get("direction", [0.0, 0.0, 1.0]))
        self.burn_out = self.m_f / self.q

    def mass_loss(self, t) -> np.ndarray:
        return self.q * np.minimum(t, self.burn_out)

    def free_force(self, t, R, V, M, F) -> None:
        if t < self.burn_out:
            F[self.i] += self.q * self.u * self.direction


class Impact(Effect):
    """An impact with restitution e against a plane or between two spherical bodies,
    located as an event (the gap reaches zero while closing), never as a penetration."""

    type = "impact"

    def __init__(self, spec: EffectSpec, index: dict[str, int], radii) -> None:
        super().__init__(spec)
        self.i = index[self.fields["body"]]
        self.j = index[self.fields["other"]] if "other" in self.fields else None
        self.e = float(self.fields["restitution"])
        self.point = np.asarray(self.fields.get("plane_point", [0.0, 0.0, 0.0]), dtype=float)
        self.normal = _unit(self.fields.get("plane_normal", [0.0, 0.0, 1.0]))
        self.r_i = radii[self.i]
        self.r_j = radii[self.j] if self.j is not None else 0.0

    def gap(self, R) -> float:
        if self.j is None:
            return float((R[self.i] - self.point) @ self.normal) - self.r_i
        return float(np.linalg.norm(R[self.i] - R[self.j])) - self.r_i - self.r_j

    def normal_at(self, R) -> np.ndarray:
        """Unit normal of the contact, pointing from the other body (or plane) to body i."""
        if self.j is None:
            return self.normal
        d = R[self.i] - R[self.j]
        return d / np.linalg.norm(d)

    def approach(self, R, V) -> float:
        """Normal speed of approach (positive while closing) at the contact."""
        w = V[self.i] - (V[self.j] if self.j is not None else 0.0)
        return -float(w @ self.normal_at(R))

    def speed_scale(self, V) -> float:
        """|v_i| + |v_j|: the size of the terms whose difference is the approach speed."""
        return float(sum(np.linalg.norm(V[k]) for k in self.bodies()))

    @property
    def label(self) -> str:
        """The pair in words: "bodies 'a' and 'b'" or "body 'a' and the plane"."""
        if self.j is None:
            return f"body {self.fields['body']!r} and the plane"
        return f"bodies {self.fields['body']!r} and {self.fields['other']!r}"

    def bodies(self) -> list[int]:
        """Indices of the bodies the impulse acts on."""
        return [self.i] if self.j is None else [self.i, self.j]

    def apply(self, R, V, M) -> dict:
        """New velocities (in place) by Newton's restitution; returns the event details,
        with the kinetic energy and momentum of the bodies involved before and after
        (read off the velocities, an independent route to the loss formula)."""
        idx = self.bodies()
        before = _kinetic_and_momentum(V[idx], M[idx])
        detail = self._apply(R, V, M)
        after = _kinetic_and_momentum(V[idx], M[idx])
        detail["kinetic_energy_before"], detail["momentum_before"] = before[:2]
        detail["kinetic_energy_after"], detail["momentum_after"] = after[:2]
        detail["momentum_scale"] = before[2]  # Σ m|v| before: the size of the terms
        return detail

    def _apply(self, R, V, M) -> dict:
        from mechanics.impact import direct_impact  # (6.36)–(6.38)

        if self.j is None:
            v_n = float(V[self.i] @ self.normal)
            V[self.i] += -(1.0 + self.e) * v_n * self.normal
            return {
                "body": self.fields["body"],
                "normal_speed_before": -v_n,
                "normal_speed_after": float(V[self.i] @ self.normal),
                "energy_loss": 0.5 * M[self.i] * (1.0 - self.e) * (1.0 + self.e) * v_n * v_n,
            }
        n = (R[self.i] - R[self.j]) / np.linalg.norm(R[self.i] - R[self.j])
        # along the line of centres, body j behind body i when approaching: x = −n·
        v1, v2 = float(V[self.j] @ n), float(V[self.i] @ n)
        v1f, v2f = direct_impact(M[self.j], M[self.i], v1, v2, self.e)
        V[self.j] += (float(v1f) - v1) * n
        V[self.i] += (float(v2f) - v2) * n
        mu = M[self.i] * M[self.j] / (M[self.i] + M[self.j])
        return {
            "bodies": [self.fields["body"], self.fields["other"]],
            "normal_speed_before": v1 - v2,
            "normal_speed_after": float(v2f - v1f),  # separation speed
            "energy_loss": 0.5 * mu * (1.0 - self.e) * (1.0 + self.e) * (v1 - v2) ** 2,
        }


def _kinetic_and_momentum(V, M) -> tuple[float, list[float], float]:
    """½ Σ m v², Σ m v and Σ m |v| of a few bodies (translation: impacts act through G)."""
    T = float(0.5 * (M * (V * V).sum(-1)).sum())
    P = [float(c) for c in (M[:, None] * V).sum(0)]
    return T, P, float((M * np.linalg.norm(V, axis=-1)).sum())


class FixedAxis(Effect):
    """A fixed axis (a hinge) through the body: one degree of freedom φ (4.3)."""

    type = "fixed_axis"

    def __init__(self, spec: EffectSpec) -> None:
        super().__init__(spec)
        self.axis = _unit(self.fields.get("axis", [0.0, 0.0, 1.0]))
        self.h = float(self.fields.get("distance", 0.0))
        self.body_axis = "xyz".index(self.fields.get("body_axis", "z"))

    def moment_of_inertia(self, m, J_G) -> float:
        """J_z = J_G + m h² (parallel axes, 4.54)."""
        return float(J_G[self.body_axis, self.body_axis]) + m * self.h**2


class FixedPoint(Effect):
    """A fixed point C on the body's symmetry (z) axis at distance ℓ from G (5.2)."""

    type = "fixed_point"

    def __init__(self, spec: EffectSpec) -> None:
        super().__init__(spec)
        self.ell = float(self.fields["distance"])

    def moments(self, m, J_G) -> np.ndarray:
        """Principal moments about C: J'1 = J1 + m ℓ², J'2 = J2 + m ℓ², J3 (5.46)."""
        J = np.diag(J_G).astype(float).copy()
        J[:2] += m * self.ell**2
        return J


class Rolling(Effect):
    """Rolling without slipping of a round body on an incline or inside a cylindrical
    track (3.77, 4.60): one degree of freedom; the contact force does no work."""

    type = "rolling"

    def __init__(self, spec: EffectSpec) -> None:
        super().__init__(spec)
        self.surface = self.fields["surface"]
        self.alpha = float(self.fields.get("angle", 0.0))
        self.track_radius = self.fields.get("track_radius")
        self.body_axis = "xyz".index(self.fields.get("body_axis", "z"))

    def effective_mass(self, m, J_G, r) -> float:
        """m + J/r²: the kinetic energy is ½ (m + J/r²) v² when v = ω r (3.79)."""
        return m + float(J_G[self.body_axis, self.body_axis]) / r**2


class CoulombFriction(Effect):
    """Coulomb friction μN at the contact of a round body with a plane of slope α: while
    the contact point slips, the friction opposes the slip; when the slip velocity
    reaches zero (an event) the body rolls if static friction suffices."""

    type = "coulomb_friction"

    def __init__(self, spec: EffectSpec) -> None:
        super().__init__(spec)
        self.mu = float(self.fields["mu"])
        self.alpha = float(self.fields.get("angle", 0.0))
        self.body_axis = "xyz".index(self.fields.get("body_axis", "z"))

    def friction(self, N, slip) -> float:
        """Friction force on G along the slope: −μ N sign(slip)."""
        return -self.mu * N * math.copysign(1.0, slip) if slip != 0 else 0.0

    def can_roll(self, N, m, J, r, drive) -> bool:
        """Rolling needs |F| = |drive| J/(J + m r²) ≤ μ N (drive: force along the slope)."""
        return abs(drive) * J / (J + m * r * r) <= self.mu * N


class MassFlow(Effect):
    """Mass flow q ≥ 0 *into* a body on a fixed axis (bullets of speed v along a line at
    signed distance r from the axis, stuck at radius R): Example 7.3, (7.36)–(7.39)."""

    type = "mass_flow"

    def __init__(self, spec: EffectSpec) -> None:
        super().__init__(spec)
        self.q = float(self.fields["rate"])
        self.v = float(self.fields["speed"])
        self.r = float(self.fields["offset"])
        self.R = float(self.fields["radius"])

    def inertia_added(self, t) -> np.ndarray:
        return self.q * self.R**2 * np.asarray(t, dtype=float)

    def axis_torque_flux(self, phidot) -> np.ndarray:
        """−r q v − q R² φ̇: the angular momentum flux in, minus the spin-up of new mass."""
        return -self.r * self.q * self.v - self.q * self.R**2 * phidot


class TankOutflow(Effect):
    """Outflow through a small hole of area a in the bottom of a prismatic tank of area A:
    Torricelli's u = √(2gh/(1 − (a/A)²)) (8.37, quasi-steady) and A ḣ = −a u."""

    type = "tank_outflow"

    def __init__(self, spec: EffectSpec) -> None:
        super().__init__(spec)
        self.a = float(self.fields["hole_area"])

    def outflow_speed(self, h, g, A) -> np.ndarray:
        """u = √(2gh/(1 − (a/A)²)) (8.37 with the surface speed kept)."""
        ratio = self.a / A
        return np.sqrt(2.0 * g * np.maximum(h, 0.0) / ((1.0 - ratio) * (1.0 + ratio)))

    def level_rate(self, h, g, A) -> np.ndarray:
        """ḣ = −(a/A) u."""
        return -(self.a / A) * self.outflow_speed(h, g, A)

    def sqrt_level_rate(self, g, A) -> float:
        """d√h/dt = ḣ/(2√h) = −(a/A)√(g/(2(1 − (a/A)²))): regular at h = 0, where
        ḣ ∝ √h is not Lipschitz (an integrator in h cannot locate the emptying)."""
        ratio = self.a / A
        return -ratio * math.sqrt(g / (2.0 * (1.0 - ratio) * (1.0 + ratio)))


EFFECT_CLASSES = {
    c.type: c
    for c in (
        Gravity,
        FixedAxis,
        FixedPoint,
        Rolling,
        CoulombFriction,
        Spring,
        Torsion,
        Impact,
        Thrust,
        MassFlow,
        TankOutflow,
    )
}


def build_effects(scene, radii=None) -> list[Effect]:
    """One effect object per listed effect, in file order; nothing else."""
    index = {b.name: i for i, b in enumerate(scene.bodies)}
    out: list[Effect] = []
    for spec in scene.effects:
        cls = EFFECT_CLASSES[spec.type]
        if cls in (Spring, Thrust):
            out.append(cls(spec, index))
        elif cls is Impact:
            out.append(cls(spec, index, radii))
        else:
            out.append(cls(spec))
    return out
