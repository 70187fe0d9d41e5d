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
    """A conservative effect: it has a potential energy, added to the kinetic energy in E.

    ``potential(s)``: the potential energy (J) at the snapshots s, of the shape of s's
    samples.

    Examples
    --------
    A class declares the protocol among its bases; the runtime check agrees:

    >>> from mechanics.scenes.effects.gravity import Gravity
    >>> from mechanics.scenes.effects.drag import Drag
    >>> HasPotential in Gravity.__mro__, issubclass(Gravity, HasPotential)
    (True, True)
    >>> HasPotential in Drag.__mro__, issubclass(Drag, HasPotential)
    (False, False)
    """

    def potential(self, s: Snapshot) -> FloatArray: ...


@runtime_checkable
class HasModes(Protocol):
    """An effect with modes (stick and slip, a tank that empties), switched at events.

    ``loads`` holds the loads of the effects summed before it; its next switch is where
    the switch function g falls through zero (located by :mod:`mechanics.scenes.modes`).

    Examples
    --------
    >>> from mechanics.scenes.effects.tank_outflow import TankOutflow
    >>> HasModes in TankOutflow.__mro__, issubclass(TankOutflow, HasModes)
    (True, True)
    """

    def begin(self, t: float, s: Snapshot, loads: Loads) -> None:
        """Choose the mode from the initial state."""

    def switch_function(self, t: float, s: Snapshot, loads: Loads) -> tuple[float, float]:
        """(g, the size of its terms) at (t, s)."""

    def switch(self, t: float, s: Snapshot, loads: Loads) -> Event:
        """Switch the mode at (t, s) (the snapshot may be changed); return the Event."""


@runtime_checkable
class ChangesMass(Protocol):
    """An effect that takes mass from a body (thrust).

    ``mass_loss(t)``: the mass (kg) each body has lost by the time(s) t, shape (..., n).

    Examples
    --------
    >>> from mechanics.scenes.effects.thrust import Thrust
    >>> ChangesMass in Thrust.__mro__, issubclass(Thrust, ChangesMass)
    (True, True)
    """

    def mass_loss(self, t: Times) -> FloatArray:
        """The mass lost by each body by time(s) t, shape (..., n)."""


@runtime_checkable
class AddsInertia(Protocol):
    """An effect that adds inertia to a guided body (mass flowing onto it).

    ``inertia_added(t, i)``: the inertia (kg m²) added to body i's coordinates by time t.

    Examples
    --------
    >>> from mechanics.scenes.effects.mass_flow import MassFlow
    >>> AddsInertia in MassFlow.__mro__, issubclass(MassFlow, AddsInertia)
    (True, True)
    """

    def inertia_added(self, t: Times, i: int) -> FloatArray | float:
        """The inertia added to body i's coordinates by time t."""


@runtime_checkable
class GuidesBody(Protocol):
    """A joint that leaves its body a few coordinates q (a fixed axis, rolling, sliding).

    The body's state is the :class:`~mechanics.scenes.state.Guide`'s (q, q̇), made by
    the class method ``make_guide(spec, scene, g_vector)``.

    Examples
    --------
    >>> from mechanics.scenes.effects.fixed_axis import FixedAxis
    >>> GuidesBody in FixedAxis.__mro__, issubclass(FixedAxis, GuidesBody)
    (True, True)
    """

    @classmethod
    def make_guide(cls, spec: SpecLike, scene: SceneLike, g_vector: FloatArray) -> Guide:
        """The Guide of the joint ``spec`` in ``scene`` under the gravity ``g_vector``."""


@runtime_checkable
class Compiles(Protocol):
    """An effect whose loads have a compiled kernel, chosen by the effect's type.

    The kernels are in :mod:`mechanics.scenes._kernels` (run by
    :mod:`mechanics.scenes.compiled`); ``kernel_args()`` gives the numbers they read.

    Examples
    --------
    >>> from mechanics.scenes.effects.spring import Spring
    >>> from mechanics.scenes.effects.thrust import Thrust
    >>> issubclass(Spring, Compiles), issubclass(Thrust, Compiles)
    (True, False)
    """

    def kernel_args(self) -> tuple[int, int, list[float], list[tuple[int, int]]]:
        """Its bodies i and j (−1: none), its numbers in the order its kernel reads
        them, and the pairs of bodies it acts between (Newtonian gravity)."""


#: every capability an effect may declare
CAPABILITIES = (HasPotential, HasModes, ChangesMass, AddsInertia, GuidesBody, Compiles)
