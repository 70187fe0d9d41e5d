"""Engine conformance: hold another engine to the book's laws (issue 19).

- :mod:`mechanics.conformance.protocol`: the scenario, the trajectory, the adapter
  protocol a user implements, and the validation of an adapter's answer.
- :mod:`mechanics.conformance.scenarios`: the battery's scenarios (:data:`SCENARIOS`:
  torque-free tops in each regime and near the separatrix, the heavy top, the parabola,
  a two-body impact, a bouncing ball, a rocket) with their exact references.
- :mod:`mechanics.conformance.battery`: :func:`run_battery` and its :class:`Report`
  (Markdown, JSON); :data:`DEFAULT_THRESHOLDS`.
- :mod:`mechanics.conformance.adapters`: the reference adapters (``ExactAdapter``,
  ``SceneEngineAdapter``) and :func:`~mechanics.conformance.adapters.require` for an
  optional engine's extra.
- :mod:`mechanics.conformance.compare`: the battery on every adapter (the references and
  each installed engine's variants) into one table (``bodycheck conform all``).
- :mod:`mechanics.conformance.parametrize`: :func:`conformance_tests`, the battery as a
  pytest parametrisation (imports pytest only when called).

See docs/conformance.md.
"""

from .battery import (
    DEFAULT_RTOL,
    DEFAULT_THRESHOLDS,
    Figure,
    Report,
    Run,
    ScenarioResult,
    ThresholdError,
    run_battery,
)
from .laws import LAW_EQUATIONS, law_violations
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
from .scenarios import (
    SCENARIOS,
    Reference,
    ScenarioRangeError,
    UnknownScenarioError,
    check_scenario,
    get_scenario,
    reference,
)

__all__ = [
    "DEFAULT_RTOL",
    "DEFAULT_THRESHOLDS",
    "LAW_EQUATIONS",
    "ORTHOGONALITY_ATOL",
    "SAMPLE_TIME_RTOL",
    "SCENARIOS",
    "Adapter",
    "Body",
    "ConformanceError",
    "Event",
    "Figure",
    "Ground",
    "Pivot",
    "Reference",
    "Report",
    "Run",
    "Scenario",
    "ScenarioRangeError",
    "ScenarioResult",
    "Shape",
    "ThresholdError",
    "Thrust",
    "Trajectory",
    "UnknownScenarioError",
    "check_scenario",
    "check_trajectory",
    "conformance_tests",
    "get_scenario",
    "law_violations",
    "reference",
    "run_battery",
]


def __getattr__(name: str):
    if name == "conformance_tests":  # imports pytest when called, not here
        from .parametrize import conformance_tests

        return conformance_tests
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
