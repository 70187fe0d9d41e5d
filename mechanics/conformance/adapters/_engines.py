"""What the engine adapters share: the optional import, the fixed-step sampling plan,
the features no engine here can express, and a quiet stdout.

Private to :mod:`mechanics.conformance.adapters`; each adapter's own module documents
its engine's conventions.
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
from collections.abc import Iterator

import numpy as np

from ..._floats import EPS
from ..._validate import as_float_scalar, check_option
from ...errors import (
    MechanicsValueError,
    NonPositiveParameterError,
    OutOfDomainError,
)
from ..protocol import SAMPLE_TIME_RTOL, Scenario
from . import MissingExtraError

__all__ = [
    "MissingExtraError",  # re-exported from the package
    "body_rows",
    "check_option",
    "common_unsupported",
    "product_restitutions",
    "quiet_stdout",
    "require",
    "step_counts",
    "unit_interval",
]


def require(module: str, extra: str, *, quiet: bool = False):
    """:func:`mechanics.conformance.adapters.require` (import ``module`` or raise
    :class:`~mechanics.conformance.adapters.MissingExtraError` naming ``extra``; each
    engine's extra is named after its PyPI package: ``mujoco``, ``pybullet``, ``drake``).

    ``quiet`` keeps what the module prints on import (pybullet's build banner, written
    by C code) off stdout and stderr."""
    from . import require as _require

    if quiet:
        with quiet_stdout():
            return _require(module, extra, package=extra)
    return _require(module, extra, package=extra)


def _quiet_stdout() -> Iterator[None]:
    """Send file descriptors 1 and 2 to the null device for the duration (C code's
    printf included: pybullet's build banner goes to stderr); a stream without a
    descriptor (a notebook's) is left alone.  Only for an import, whose failure is an
    exception, not text."""
    saved: list[tuple[int, int]] = []
    for stream in (sys.stdout, sys.stderr):
        try:
            fd = stream.fileno()
        except (AttributeError, OSError, ValueError):
            continue
        stream.flush()
        saved.append((fd, os.dup(fd)))
    try:
        with open(os.devnull, "wb") as null:
            for fd, _ in saved:
                os.dup2(null.fileno(), fd)
        yield
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        _flush_c_stdio()  # C's buffered printf, before the descriptors are restored
        for fd, copy in saved:
            os.dup2(copy, fd)
            os.close(copy)


# applied after the definition, so that mutmut mutates the function (it skips decorated ones)
quiet_stdout = contextlib.contextmanager(_quiet_stdout)


def _flush_c_stdio() -> None:
    try:
        import ctypes

        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError):  # no C library to call (not a POSIX build)
        pass


def step_counts(scenario: Scenario, step) -> tuple[float, np.ndarray]:
    """The step (``step``, or the scenario's finest when ``None``) and the number of
    fixed steps from 0 to each sample time, shape (m,).

    Raises :class:`NonPositiveParameterError` for a step that is not a positive finite
    number and :class:`MechanicsValueError` when a sample time is not a whole number of
    steps (within :data:`SAMPLE_TIME_RTOL`): a fixed-step engine can only stop there."""
    if step is None and scenario.steps:
        step = min(scenario.steps)
    if step is None or not np.isfinite(step) or step <= 0:
        raise NonPositiveParameterError(
            f"scenario {scenario.name!r}: a fixed-step engine needs a step > 0; got {step!r}"
        )
    T = np.asarray(scenario.sample_times, dtype=float)
    n = np.rint(T / step)
    off = np.abs(n * step - T) > SAMPLE_TIME_RTOL * np.maximum(np.abs(T), 1.0)
    if off.any():
        k = int(np.argmax(off))
        raise MechanicsValueError(
            f"scenario {scenario.name!r}: sample time {float(T[k])!r} is not a whole number "
            f"of steps {float(step)!r}"
        )
    return float(step), n.astype(np.int64)


def common_unsupported(scenario: Scenario, *, friction: bool = False) -> str | None:
    """The reason no engine here can run ``scenario``, or ``None``.

    - A :class:`~mechanics.conformance.protocol.Thrust`: MuJoCo, PyBullet and Drake hold
      each body's mass constant during a run, so the rocket's loss of mass (7.30) has no
      expression; a constant thrust would be another problem, not Tsiolkovsky's.
    - A contact pair naming a body without a shape: nothing could touch.
    - Friction with the ground, unless the adapter maps it (``friction=True``)."""
    if not friction and scenario.ground is not None and scenario.ground.friction > 0:
        return (
            f"friction with the ground (mu = {scenario.ground.friction!r}): not mapped by "
            "this adapter"
        )
    if scenario.thrust is not None:
        return (
            "a body's mass changes during the run (Thrust, the rocket of 7.30); the "
            "engine holds masses constant, and a constant-mass thrust is not Tsiolkovsky"
        )
    for i, j, _ in scenario.pair_restitution:
        for k in (i, j):
            if not 0 <= k < len(scenario.bodies):
                return f"contact pair ({i}, {j}) names no body {k}"
            if scenario.bodies[k].shape is None:
                return f"contact pair ({i}, {j}): body {scenario.bodies[k].name!r} has no shape"
    for b in scenario.bodies:
        if b.shape is not None and b.shape.kind not in ("sphere", "box", "cylinder"):
            return f"body {b.name!r} has a shape {b.shape.kind!r} the adapter does not know"
    return None


def body_rows(scenario: Scenario) -> tuple[np.ndarray, ...]:
    """The bodies' initial states as arrays: positions, velocities (n, 3), attitudes
    ^A R^O (n, 3, 3), ω in body components (n, 3)."""
    b = scenario.bodies
    return (
        np.array([x.position for x in b], dtype=float).reshape(-1, 3),
        np.array([x.velocity for x in b], dtype=float).reshape(-1, 3),
        np.array([x.R_A_O for x in b], dtype=float).reshape(-1, 3, 3),
        np.array([x.omega for x in b], dtype=float).reshape(-1, 3),
    )


def unit_interval(x, name: str, what: str, *, error=OutOfDomainError) -> float:
    """``x`` as a float in [0, 1]; a :class:`~mechanics.errors.MechanicsValueError`
    naming ``name`` (a NaN, an infinity, a non-scalar), or ``error`` for a value outside
    (:class:`~mechanics.errors.RestitutionRangeError` for a coefficient of restitution)."""
    v = as_float_scalar(x, name)
    if not 0.0 <= v <= 1.0:
        raise error(f"{name} ({what}) must lie in [0, 1]; got {v!r}")
    return v


#: per-body coefficients whose product must give a pair's e: a square root and a
#: product, a few roundings
PRODUCT_RTOL = 4 * EPS


def product_restitutions(scenario: Scenario, engine: str) -> tuple[list[float] | None, str | None]:
    """Per-body restitution coefficients (bodies in order) for an engine that restitutes a
    contact with the *product* of the two bodies' coefficients (PyBullet's Bullet,
    DART): a body that meets the ground gets the ground's e (the ground 1), a pair of
    free bodies √e each, a body paired with a fixed one e over the other's; ``(values,
    None)``, or ``(None, the reason)`` when no per-body values give every contact its e."""
    n = len(scenario.bodies)
    r: list[float | None] = [None] * n
    if scenario.ground is not None:
        for k, b in enumerate(scenario.bodies):
            if b.shape is not None:
                r[k] = float(scenario.ground.restitution)
    for i, j, e in scenario.pair_restitution:
        ri, rj = r[i], r[j]
        if ri is None:
            ri = math.sqrt(e) if rj is None else (e / rj if rj > 0 else 0.0)
            if rj is None:
                rj = ri
        elif rj is None:
            rj = e / ri if ri > 0 else 0.0
        r[i], r[j] = ri, rj
        if not (0 <= ri <= 1 and 0 <= rj <= 1) or abs(ri * rj - e) > PRODUCT_RTOL:
            return None, (
                f"{engine} restitutes a contact with the product of the two bodies' "
                f"coefficients; no per-body values give pair ({i}, {j}) its e = {e!r} "
                "together with the scenario's other contacts"
            )
    return [1.0 if x is None else x for x in r], None
