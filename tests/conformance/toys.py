"""Toy adapters for the battery's tests: a fourth-order one, wrong ones, broken ones.

The first-order toy (semi-implicit Euler on free bodies and a ground bounce) is the
example adapter of docs/conformance.md; :func:`doc_example_source` reads it out of the
document, so that the example users copy is the one under test.
"""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import numpy as np

from mechanics.conformance import Trajectory
from mechanics.conformance.adapters import ExactAdapter, require
from mechanics.rotation import nearest_rotation

DOC = Path(__file__).resolve().parents[2] / "docs" / "conformance.md"


def doc_example_source() -> str:
    """The code block that follows the marker ``<!-- example adapter -->`` in the doc."""
    text = DOC.read_text(encoding="utf-8")
    m = re.search(r"<!-- example adapter -->\s*```python\n(.*?)```", text, re.S)
    assert m is not None, f"{DOC} has no example adapter block"
    return m.group(1)


def doc_example():
    """The doc's example module, executed: its namespace."""
    ns: dict = {"__name__": "toy_engine"}
    exec(compile(doc_example_source(), str(DOC), "exec"), ns)
    return ns


# -- four bugs planted in the doc's first-order toy, as in issue 29's outside trial

#: each bug: the line of the doc's toy it replaces, and what with
BUGS = {
    "world-frame inertia in the gyroscopic term": (
        "w = w + step * np.cross(J * w, w) / J",
        "w = w + step * np.cross(np.einsum('nji,nj,njk,nk->ni', R, J, R, w), w) / J",
    ),
    "gyroscopic term dropped": ("w = w + step * np.cross(J * w, w) / J", "w = w"),
    "restitution squared": ("(1.0 + e) * vn", "(1.0 + e * e) * vn"),
    "attitude untransposed": (
        "(x, v, R_out, w)):",
        "(x, v, np.swapaxes(R_out, -1, -2), w)):",
    ),
}
#: the scenarios each bug breaks (the others it passes: a bug in a law the scenario
#: does not exercise is invisible there, as it should be)
BROKEN = {
    "world-frame inertia in the gyroscopic term": ["free_top_axis1"],
    "gyroscopic term dropped": ["free_top_axis3"],
    "restitution squared": ["bouncing_ball"],
    "attitude untransposed": ["parabola"],
}


def planted_source(bug: str | None = None) -> str:
    """The doc's semi-implicit Euler's module, with ``bug`` planted (None: as documented)."""
    src = doc_example_source()
    if bug is not None:
        old, new = BUGS[bug]
        assert src.count(old) == 1, f"the doc's toy no longer has the line {old!r}"
        src = src.replace(old, new)
    return src


def planted_toy(bug: str | None = None):
    """The doc's semi-implicit Euler, with ``bug`` planted (None: as documented)."""
    ns: dict = {"__name__": "toy_engine"}
    exec(compile(planted_source(bug), "toy_engine", "exec"), ns)
    return ns["SemiImplicitEuler"]()


#: [a]× row by row is a @ SKEW: the coefficients of a₀, a₁, a₂ in
#: (0, −a₂, a₁, a₂, 0, −a₀, −a₁, a₀, 0)
SKEW = np.array(
    [
        [0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    ]
)


def _skew(a):
    """[a]× of each row of ``a`` (shape (n, 3)): shape (n, 3, 3), [a]× b = a × b."""
    return (a @ SKEW).reshape(-1, 3, 3)


class RK4:
    """Classical Runge-Kutta on free bodies (no contacts, joints or thrust): x, v, the
    nine entries of R (Ṙ = −[ω]× R, passive) and ω (Euler's equations 4.47); R is
    projected on SO(3) only where sampled.  Order 4.

    The state is one array per step, shape (n, 18): x, v, R row by row, ω; the cross
    products are products with [·]× (:data:`SKEW`), so a stage is a few array
    operations (``np.cross``'s set-up costs ten times its arithmetic on one body, and the
    battery takes ~6,000 steps per free top); R is projected once per run."""

    name = "toy RK4"
    takes_step = True

    def supports(self, scenario):
        if scenario.pivot or scenario.thrust or scenario.pair_restitution or scenario.ground:
            return "free bodies only"
        return None

    def run(self, scenario, step):
        b = scenario.bodies
        J = np.array([x.inertia for x in b])
        g = np.array(scenario.gravity, dtype=float)
        y = np.concatenate(
            [
                np.array([x.position for x in b], dtype=float),
                np.array([x.velocity for x in b], dtype=float),
                np.array([x.R_A_O for x in b], dtype=float).reshape(len(b), 9),
                np.array([x.omega for x in b], dtype=float),
            ],
            axis=1,
        )

        def f(s):
            R, w = s[:, 6:15].reshape(-1, 3, 3), s[:, 15:18]
            d = np.empty_like(s)
            d[:, 0:3] = s[:, 3:6]
            d[:, 3:6] = g
            d[:, 6:15] = (-_skew(w) @ R).reshape(-1, 9)
            d[:, 15:18] = (_skew(J * w) @ w[:, :, None])[:, :, 0] / J  # (J ω) × ω / J
            return d

        def add(s, k, c):
            return s + c * k

        out, n = [], 0
        for t in scenario.sample_times:
            while n < round(t / step):
                y = self._step(f, add, y, step)
                n += 1
            out.append(y)
        Y = np.array(out)  # (m, n, 18)
        R = nearest_rotation(Y[..., 6:15].reshape(*Y.shape[:2], 3, 3))
        return Trajectory(
            np.array(scenario.sample_times), Y[..., 0:3], Y[..., 3:6], R, Y[..., 15:18]
        )

    @staticmethod
    def _step(f, add, y, h):
        k1 = f(y)
        k2 = f(add(y, k1, h / 2))
        k3 = f(add(y, k2, h / 2))
        k4 = f(add(y, k3, h))
        return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


class Midpoint(RK4):
    """The explicit midpoint rule (a two-stage Runge-Kutta method) on the same free
    bodies: order 2."""

    name = "toy midpoint"

    @staticmethod
    def _step(f, add, y, h):
        return add(y, f(add(y, f(y), h / 2)), h)


class Wrapped(ExactAdapter):
    """The exact adapter with its answer (or its scenario) spoiled by ``spoil``."""

    def __init__(self, name, *, scenario=None, answer=None, only=None):
        self.name = name
        self._scenario, self._answer, self._only = scenario, answer, only

    def run(self, scenario, step):
        if self._only is not None and scenario.name not in self._only:
            return super().run(scenario, step)
        s = self._scenario(scenario) if self._scenario else scenario
        tr = super().run(s, step)
        return self._answer(scenario, tr) if self._answer else tr


def ignores_restitution():
    """Every contact elastic, whatever e says."""

    def elastic(s):
        ground = s.ground and dataclasses.replace(s.ground, restitution=1.0)
        pairs = tuple((i, j, 1.0) for i, j, _ in s.pair_restitution)
        return dataclasses.replace(s, ground=ground, pair_restitution=pairs)

    return Wrapped("e ignored", scenario=elastic)


def active_attitudes():
    """Returns the engine's active matrix (body-to-world) instead of ^A R^O."""
    return Wrapped(
        "active attitudes",
        answer=lambda s, tr: dataclasses.replace(tr, R_A_O=np.swapaxes(tr.R_A_O, -1, -2)),
    )


def gravity_sign_error():
    """The doc's first-order toy with gravity pointing up."""
    base = doc_example()["SemiImplicitEuler"]

    class Up(base):
        name = "gravity up"

        def run(self, scenario, step):
            flipped = dataclasses.replace(scenario, gravity=tuple(-x for x in scenario.gravity))
            return super().run(flipped, step)

    return Up()


def _field(name, f):
    return lambda s, tr: dataclasses.replace(tr, **{name: f(getattr(tr, name))})


def _nan_at_3(v):
    v = v.copy()
    v[3, 0, 1] = np.nan
    return v


def _swap_2_3(t):
    t = t.copy()
    t[[2, 3]] = t[[3, 2]]
    return t


BAD_ANSWERS = {
    # case: (spoil, what the message must name)
    "wrong shape": (_field("position", lambda x: x[:, :, :2]), ("'position'", "shape")),
    "NaN": (_field("velocity", _nan_at_3), ("'velocity'", "finite", "got nan at index (3, 0, 1)")),
    "non-orthogonal attitude": (
        _field("R_A_O", lambda R: R * 1.001),
        ("'R_A_O'", "rotations", "off by"),
    ),
    "times out of order": (_field("t", _swap_2_3), ("'t'", "increase strictly")),
    "not a trajectory": (lambda s, tr: {"t": tr.t}, ("Trajectory", "got dict")),
}


class Crashes(ExactAdapter):
    """Raises in ``run`` for the listed scenarios."""

    name = "crashes"

    def __init__(self, crash_on):
        self.crash_on = set(crash_on)

    def run(self, scenario, step):
        if scenario.name in self.crash_on:
            raise RuntimeError(f"boom in {scenario.name}")
        return super().run(scenario, step)


class NeedsMissingEngine(ExactAdapter):
    """An engine adapter whose engine is not installed."""

    name = "missing engine"

    def run(self, scenario, step):
        require("bodycheck_no_such_engine", "mujoco", engine="MuJoCo")
        raise AssertionError("unreachable")
