"""Engine conformance: hold another engine to the book's laws (issue 19).

- :mod:`mechanics.conformance.protocol`: the scenario, the trajectory, the adapter
  protocol a user implements, and the validation of an adapter's answer.
"""

from .protocol import (
    ORTHOGONALITY_ATOL,
    SAMPLE_TIME_RTOL,
    Adapter,
    Body,
    ConformanceError,
    Event,
    Ground,
    Pivot,
    Scenario,
    Shape,
    Thrust,
    Trajectory,
    check_trajectory,
)

__all__ = [
    "ORTHOGONALITY_ATOL",
    "SAMPLE_TIME_RTOL",
    "Adapter",
    "Body",
    "ConformanceError",
    "Event",
    "Ground",
    "Pivot",
    "Scenario",
    "Shape",
    "Thrust",
    "Trajectory",
    "check_trajectory",
]
