"""Builders of the scene tests' inputs: a scene's tables (``scene_data``) and the parsed
scene (``scene``), its bodies (``body``, ``point``, ``ball``, ``box``, ``cylinder``) and
the engine's snapshots (``snap``, ``snapshot_of``, ``bare_snap``), with the strategies of
random snapshots (``snapshots``).

Every builder returns a fresh dict or array (nothing is shared between calls or tests);
vectors given as tuples or arrays are written as lists, as a TOML file would give them.
A test file whose defaults differ (its scene's name and source file, its samples, a
body's mass) passes them, or keeps a one-line ``functools.partial`` of a builder."""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import numpy as np

from mechanics.scenes import parse_scene
from mechanics.scenes.effects import Snapshot

# ------------------------------------------------------------------ scenes


def scene_data(bodies: Iterable, effects: Iterable = (), *, name: str = "scene", **fields) -> dict:
    """The tables of a scene file: ``[scene]`` (its name, then ``fields`` such as
    duration, samples, method, in the order given), ``[[bodies]]`` and ``[[effects]]``."""
    return {"scene": {"name": name, **fields}, "bodies": list(bodies), "effects": list(effects)}


def scene(
    bodies: Iterable,
    effects: Iterable = (),
    *,
    name: str = "scene",
    source: str | None = None,
    **fields,
):
    """The scene parsed from ``scene_data(bodies, effects, name=name, **fields)``, as read
    from the file ``source`` (default ``{name}.toml``: the file a refusal names first)."""
    data = scene_data(bodies, effects, name=name, **fields)
    return parse_scene(data, source=f"{name}.toml" if source is None else source)


# ------------------------------------------------------------------ bodies


def _listed(value):
    """A vector as a TOML array (a list); a number or a string as it is."""
    return list(value) if isinstance(value, tuple | list | np.ndarray) else value


def body(name: str, shape: str, initial: Mapping | None = None, **fields) -> dict:
    """A ``[[bodies]]`` table: name, shape, then ``fields`` (mass, radius, a, b, c, fixed,
    ...) as given; ``initial`` (its vectors as lists) only when given."""
    out = {"name": name, "shape": shape, **fields}
    if initial is not None:
        out["initial"] = {k: _listed(v) for k, v in initial.items()}
    return out


def _initial(position, velocity, rest: dict) -> dict:
    """The initial table: position and velocity when given, then the other keys."""
    given = {"position": position, "velocity": velocity}
    return {k: v for k, v in given.items() if v is not None} | rest


def point(name: str = "p", position=None, velocity=None, *, mass: float = 1.0, **initial) -> dict:
    """A point mass; its initial table holds position and velocity when given and the
    other keyword arguments (an empty table when none)."""
    return body(name, "point", _initial(position, velocity, initial), mass=mass)


def ball(
    name: str = "ball",
    position=None,
    velocity=None,
    *,
    mass: float = 1.0,
    radius: float = 0.1,
    shape: str = "solid_sphere",
    **initial,
) -> dict:
    """A solid sphere (or another round ``shape``: hollow_sphere) of the given radius;
    its initial table as ``point``'s."""
    return body(name, shape, _initial(position, velocity, initial), mass=mass, radius=radius)


def box(
    name: str = "box",
    position=None,
    velocity=None,
    *,
    mass: float = 1.0,
    a: float = 0.2,
    b: float = 0.4,
    c: float = 0.6,
    **initial,
) -> dict:
    """A homogeneous box of edges a, b, c; its initial table as ``point``'s."""
    return body(name, "box", _initial(position, velocity, initial), mass=mass, a=a, b=b, c=c)


def cylinder(
    name: str = "c",
    position=None,
    velocity=None,
    *,
    mass: float = 1.0,
    radius: float = 0.1,
    height: float = 0.2,
    **initial,
) -> dict:
    """A homogeneous cylinder of the given radius and height; its initial table as
    ``point``'s."""
    init = _initial(position, velocity, initial)
    return body(name, "cylinder", init, mass=mass, radius=radius, height=height)


# ------------------------------------------------------------------ snapshots


def snap(r, v, R, omega, m, J, *, t: float = 0.0, **kw) -> Snapshot:
    """A snapshot of bodies at r moving at v, turned by R (passive, R_A_O) and turning at
    omega (body components), of masses m and principal moments J (so L_A = J omega);
    ``kw`` (phase, angle, ...) as Snapshot takes them.  Each argument is copied into a
    float array."""
    r, v, R, omega = (np.array(a, dtype=float) for a in (r, v, R, omega))
    m, J = np.array(m, dtype=float), np.array(J, dtype=float)
    return Snapshot(t, r, v, J * omega, R, omega, m, J, **kw)


def bare_snap(m, *, t=0.0, **kw) -> Snapshot:
    """A snapshot with masses m only (no positions, velocities or attitudes): for the
    effects that read nothing else (a tank's level, a switch's angle in ``kw``)."""
    return Snapshot(t, None, None, None, None, None, m, None, **kw)


def snapshot_of(lay, y, m, J, coords=None, inertia=None) -> Snapshot:
    """The snapshot of the engine's state vector y under the layout ``lay``: its bodies'
    r, v, L and R gathered from y, omega = J⁻¹ L, with the guides' coordinates and the
    grown moments of inertia (both empty by default)."""
    r, v, L, R = lay.gather(y)
    s = Snapshot(0.0, r, v, L, R, lay.omega(L, J), np.asarray(m, float), J)
    s.coords = coords or {}
    s.inertia = inertia or {}
    return s


# ------------------------------------------------------------------ strategies


def snapshots(n: int, *, centres=None, spread: float = 2.0, phase: float = 0.5):
    """A strategy of snapshots of n bodies (``snap``'s, at t = phase = ``phase``): each
    body's position within ``spread`` of its row of ``centres`` (default the origin) in
    each component, velocity and spin components of size 0.5 to 2 (either sign: never a
    zero spin, whose axis a turn along the motion needs), an attitude from
    :func:`mechanics.strategies.rotation_matrices`, mass and principal moments in
    [0.5, 2].  Bodies kept apart (a pair force's singularity) are given far-apart
    centres: the bound is in the strategy, no draw is rejected."""
    from hypothesis import strategies as st
    from hypothesis.extra.numpy import arrays

    from mechanics.strategies import rotation_matrices

    at = np.zeros((n, 3)) if centres is None else np.array(centres, dtype=float)
    offsets = arrays(float, (n, 3), elements=st.floats(-spread, spread))
    sizes = st.floats(0.5, 2.0)
    signed = st.tuples(sizes, st.sampled_from((1.0, -1.0))).map(lambda x: x[0] * x[1])
    vectors = arrays(float, (n, 3), elements=signed)
    turns = st.lists(rotation_matrices(), min_size=n, max_size=n)

    @st.composite
    def draw_snapshot(draw) -> Snapshot:
        r = at + draw(offsets)
        v, omega = draw(vectors), draw(vectors)
        m = draw(arrays(float, (n,), elements=sizes))
        J = draw(arrays(float, (n, 3), elements=sizes))
        return snap(r, v, draw(turns), omega, m, J, t=phase, phase=phase)

    return draw_snapshot()
