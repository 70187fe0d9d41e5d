"""The errors raised by :mod:`mechanics` on bad input.

Every error is a ``ValueError`` subclass, so ``except ValueError`` keeps working,
and its message names the offending value and the condition it violates.
"""

from __future__ import annotations

__all__ = [
    "CollinearPointsError",
    "GimbalLockError",
    "MechanicsValueError",
    "NegativeMassError",
    "NonFiniteError",
    "NonPhysicalInertiaError",
    "NonPositiveParameterError",
    "NotARotationError",
    "OutOfDomainError",
    "RestitutionRangeError",
    "ResultOverflowError",
    "SeparatingContactError",
    "ShapeError",
    "StepSizeError",
    "UnknownOptionError",
    "ZeroAngularVelocityError",
    "ZeroAxisError",
    "ZeroNormalError",
    "ZeroTotalMassError",
]


class MechanicsValueError(ValueError):
    """Base class: an input violates a stated condition."""


class NonFiniteError(MechanicsValueError):
    """An input holds NaN or an infinity."""


class ShapeError(MechanicsValueError):
    """An input does not have the documented shape."""


class NotARotationError(MechanicsValueError):
    """A matrix is not orthogonal with determinant +1 within the stated tolerance."""


class ZeroAxisError(MechanicsValueError):
    """A rotation axis (or quaternion) of zero length was given."""


class GimbalLockError(MechanicsValueError):
    """Euler-angle rates are undefined at sin θ = 0 (the middle Euler angle)."""


class ZeroAngularVelocityError(MechanicsValueError):
    """An instantaneous axis or centre was asked for a body that does not rotate."""


class CollinearPointsError(MechanicsValueError):
    """Points that are (nearly) collinear cannot fix a rigid body's angular velocity."""


class UnknownOptionError(MechanicsValueError):
    """A keyword option (such as ``basis=``) is not one of its documented values."""


class ResultOverflowError(MechanicsValueError):
    """The exact result is too large for float64 (finite input, beyond ~1.8e308)."""


class NegativeMassError(MechanicsValueError):
    """A mass (or density) is negative."""


class ZeroTotalMassError(MechanicsValueError):
    """A centre of mass (or anything divided by the total mass) of a massless system."""


class NonPositiveParameterError(MechanicsValueError):
    """A parameter that must be > 0 (a length, radius, period, step size) is not."""


class OutOfDomainError(MechanicsValueError):
    """A parameter lies outside the domain where the stated formula holds."""


class NonPhysicalInertiaError(MechanicsValueError):
    """An inertia tensor is not symmetric, not positive definite, or breaks the
    triangle inequality J1 + J2 ≥ J3; the message names the condition and by how much."""


class RestitutionRangeError(MechanicsValueError):
    """A coefficient of restitution lies outside [0, 1]."""


class SeparatingContactError(MechanicsValueError):
    """An impact was asked for bodies whose contact points already separate."""


class ZeroNormalError(MechanicsValueError):
    """A contact normal (or a fixed axis of a hinged body) of zero length was given."""


class StepSizeError(MechanicsValueError):
    """An adaptive integrator cannot go on: its step fell below the rounding of t (the
    tolerance cannot be met there) or it needed more than the allowed number of steps."""
