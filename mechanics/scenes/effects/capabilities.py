"""What an effect contributes beyond loads, declared by the protocols its class lists.

Every effect adds loads (:meth:`~.base.Effect.loads`, possibly none).  An effect that
does more says so by listing the protocol among its bases (``class Thrust(Effect,
ChangesMass)``), and defines the protocol's methods; the engine's model groups the
effects by these declarations (:class:`mechanics.scenes.model.Model`), never by an
effect's name or by probing for attributes.  A test holds every registered effect to
its declarations: a class that defines a protocol's methods declares the protocol, and
one that declares it defines them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol, runtime_checkable

if TYPE_CHECKING:
    from ..state import Guide
    from ..trajectory import Event
    from .base import FloatArray, Loads, SceneLike, Snapshot, SpecLike, Times

__all__ = [
    "CAPABILITIES",
    "AddsInertia",
    "ChangesMass",
    "Compiles",
    "GuidesBody",
    "HasModes",
    "HasPotential",
]


@runtime_checkable
class HasPotential(Protocol):
    """A conservative effect: its potential energy at the snapshots s (shape of s's
    samples), added to the kinetic energy in E."""

    def potential(self, s: Snapshot) -> FloatArray: ...


@runtime_checkable
class HasModes(Protocol):
    """An effect with modes (stick and slip, a tank that empties).  ``loads`` holds the
    loads of the effects summed before it; its next switch is where the switch function
    g falls through zero (located by :mod:`mechanics.scenes.modes`)."""

    def begin(self, t: float, s: Snapshot, loads: Loads) -> None:
        """Choose the mode from the initial state."""

    def switch_function(self, t: float, s: Snapshot, loads: Loads) -> tuple[float, float]:
        """(g, the size of its terms) at (t, s)."""

    def switch(self, t: float, s: Snapshot, loads: Loads) -> Event:
        """Switch the mode at (t, s) (the snapshot may be changed); return the Event."""


@runtime_checkable
class ChangesMass(Protocol):
    """An effect that takes mass from a body (thrust)."""

    def mass_loss(self, t: Times) -> FloatArray:
        """The mass lost by each body by time(s) t, shape (..., n)."""


@runtime_checkable
class AddsInertia(Protocol):
    """An effect that adds inertia to a guided body (mass flowing onto it)."""

    def inertia_added(self, t: Times, i: int) -> FloatArray | float:
        """The inertia added to body i's coordinates by time t."""


@runtime_checkable
class GuidesBody(Protocol):
    """A joint that leaves its body a few coordinates q: the body's state is the
    :class:`~mechanics.scenes.state.Guide`'s (q, q̇) (a fixed axis, rolling, sliding)."""

    @classmethod
    def make_guide(cls, spec: SpecLike, scene: SceneLike, g_vector: FloatArray) -> Guide:
        """The Guide of the joint ``spec`` in ``scene`` under the gravity ``g_vector``."""


@runtime_checkable
class Compiles(Protocol):
    """An effect whose loads have a compiled kernel (:mod:`mechanics.scenes._kernels`,
    chosen by the effect's type; :mod:`mechanics.scenes.compiled`)."""

    def kernel_args(self) -> tuple[int, int, list[float], list[tuple[int, int]]]:
        """Its bodies i and j (−1: none), its numbers in the order its kernel reads
        them, and the pairs of bodies it acts between (Newtonian gravity)."""


#: every capability an effect may declare
CAPABILITIES = (HasPotential, HasModes, ChangesMass, AddsInertia, GuidesBody, Compiles)
