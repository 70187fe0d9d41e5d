"""The errors raised by :mod:`mechanics` on bad input.

Every error is a ``ValueError`` subclass, so ``except ValueError`` keeps working,
and its message names the offending value and the condition it violates.
"""

from __future__ import annotations

__all__ = [
    "CollinearPointsError",
    "GimbalLockError",
    "MechanicsValueError",
    "NonFiniteError",
    "NotARotationError",
    "ResultOverflowError",
    "ShapeError",
    "UnknownOptionError",
    "ZeroAngularVelocityError",
    "ZeroAxisError",
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
