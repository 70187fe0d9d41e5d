"""Every registered effect declares exactly the capabilities it has
(:mod:`mechanics.scenes.effects.capabilities`): the engine's model groups effects by
these declarations, so an effect that defines a potential without declaring it would
drop out of E, and one that declares modes without a switch function would fail late."""

from __future__ import annotations

import inspect

import pytest

from mechanics.scenes.effects import EFFECT_CLASSES
from mechanics.scenes.effects.base import Effect
from mechanics.scenes.effects.capabilities import (
    CAPABILITIES,
    AddsInertia,
    ChangesMass,
    Compiles,
    GuidesBody,
    HasModes,
    HasPotential,
)

#: what each effect contributes beyond loads, from its physics: a conservative force
#: has a potential; stick and slip and an emptying tank have modes; thrust takes mass;
#: mass flowing onto a body adds inertia; a joint that leaves coordinates guides; the
#: loads of free, pinned and fixed bodies that the scene kernel computes compile
#: (issue 30: gravity, Newtonian gravity, springs, dampers, drag, applied loads, a pivot)
EXPECTED = {
    "gravity": {HasPotential, Compiles},
    "newton_gravity": {HasPotential, Compiles},
    "spring": {HasPotential, Compiles},
    "damper": {Compiles},
    "drag": {Compiles},
    "force": {Compiles},
    "torque": {Compiles},
    "fixed_point": {Compiles},
    "torsion": {HasPotential, Compiles},
    "buoyancy": {HasPotential},
    "coulomb_friction": {HasModes, GuidesBody},
    "tank_outflow": {HasModes},
    "thrust": {ChangesMass},
    "mass_flow": {AddsInertia},
    "fixed_axis": {GuidesBody, Compiles},
    "rolling": {GuidesBody},
}


def _members(proto) -> list[str]:
    return [n for n in vars(proto) if not n.startswith("_")]


def mismatches(cls) -> list[str]:
    """The protocols ``cls`` declares without defining their methods, or defines
    without declaring."""
    out = []
    for proto in CAPABILITIES:
        declared = proto in cls.__mro__
        own = [inspect.getattr_static(cls, n, None) for n in _members(proto)]
        defined = all(
            x is not None and x is not vars(proto)[n]
            for x, n in zip(own, _members(proto), strict=True)
        )
        if declared != defined:
            verb = "declares" if declared else "defines the methods of"
            out.append(
                f"{cls.__name__} {verb} {proto.__name__} but does not "
                f"{'define its methods' if declared else 'declare it'}"
            )
    return out


@pytest.mark.parametrize("name", sorted(EFFECT_CLASSES))
def test_each_effect_declares_what_it_defines(name) -> None:
    assert mismatches(EFFECT_CLASSES[name]) == []


@pytest.mark.parametrize("name", sorted(EFFECT_CLASSES))
def test_each_effect_has_the_capabilities_of_its_physics(name) -> None:
    cls = EFFECT_CLASSES[name]
    assert {p for p in CAPABILITIES if p in cls.__mro__} == EXPECTED.get(name, set())


def test_every_capability_is_declared_by_some_effect() -> None:
    assert set().union(*EXPECTED.values()) == set(CAPABILITIES)


def test_a_capability_defined_but_not_declared_or_declared_but_not_defined_is_found() -> None:
    """Negative controls of :func:`mismatches`."""

    class Sneaky(Effect):
        def potential(self, s):
            return 0.0

    class Empty(Effect, HasModes):
        def begin(self, t, s, loads):
            pass

    assert mismatches(Sneaky) == [
        "Sneaky defines the methods of HasPotential but does not declare it"
    ]
    assert mismatches(Empty) == ["Empty declares HasModes but does not define its methods"]
    assert mismatches(Effect) == []
