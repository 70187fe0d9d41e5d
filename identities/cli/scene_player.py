"""A scene's run as a page that plays it (issue 31, item 2): the bodies drawn from their
shapes and attitudes, play, pause and a time slider, the events marked on the timeline,
and beside them the invariants and the derived quantities.

Conventions
-----------
- **What is drawn.**  Each body from its shape, at its centre r and attitude ^A R^O at a
  sample (the rows of R are its axes in space): a sphere as its outline and the point
  of its first body axis on it (so that the spin shows), a box or plate as its twelve
  edges, a rod as its two ends, a round body (cylinder, disc, ring, shell) as its two
  rims and four sides, a point as a dot, a body without a shape (``custom``) as its
  three principal axes; a plane the bodies strike as a square patch of it.  Fixed bodies
  and tanks are drawn where they stay (a tank's level is its series, not a motion).
- **The projection** is orthographic, seen from :data:`VIEW` (the space z axis up on
  the screen): lengths across the view are kept, so a sphere's outline is its radius.
  Python projects every frame once (:func:`player_data`); the page's script
  (``identities/data/scene_player.js``) only moves the shapes: it draws without any
  library and reads no file, so a saved page plays on its own.
- **Frames**: at most :data:`MAX_FRAMES` of the run's samples, evenly chosen, the last
  sample always among them; the events at their own times on the timeline.
- ``?frame=N`` in the page's address opens every player of the page at its frame N (the
  browser tests read two frames so).
"""

from __future__ import annotations

import html
import json
import math
from pathlib import Path

import numpy as np

__all__ = ["MAX_FRAMES", "VIEW", "player_data", "player_page", "player_section"]

#: the direction the scene is seen from (towards the viewer), space components
VIEW = np.array([1.0, -1.6, 0.9])
#: the most frames a player holds (a 2001-sample run is shown every 9th sample)
MAX_FRAMES = 240
#: the drawing's size in SVG units, and its margin
WIDTH, HEIGHT, MARGIN = 480.0, 320.0, 16.0
#: points on a round body's rim
RIM_POINTS = 24

_SCRIPT = Path(__file__).resolve().parents[1] / "data" / "scene_player.js"


def _screen_axes() -> tuple[np.ndarray, np.ndarray]:
    """(right, up) on the screen, unit vectors in space, for the view :data:`VIEW`."""
    v = VIEW / np.linalg.norm(VIEW)
    right = np.cross([0.0, 0.0, 1.0], v)
    right /= np.linalg.norm(right)
    return right, np.cross(v, right)


def _outline(body, r: np.ndarray, R: np.ndarray) -> list[tuple[str, np.ndarray, float]]:
    """The body's shapes at one sample: ("line", points (k, 3), 0) polylines and
    ("circle", centre (1, 3), radius) outlines, in space."""
    d, shape = body.dims, body.shape
    axes = R  # rows: the body axes in space
    if shape in ("solid_sphere", "hollow_sphere"):
        a = float(d["radius"])
        return [("circle", r[None], a), ("line", np.stack([r, r + a * axes[0]]), 0.0)]
    if shape in ("point", "tank"):
        return [("dot", r[None], 0.0)]
    if shape in ("box", "rectangular_plate"):
        h = 0.5 * np.array([d["a"], d["b"], d.get("c", 0.0)])
        c = [np.array([i, j, k]) * h for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)]
        P = [r + p @ axes for p in c]  # corners in space
        loops = [(0, 2, 6, 4, 0), (1, 3, 7, 5, 1)]  # the faces z = ∓c/2
        out = [("line", np.array([P[i] for i in loop]), 0.0) for loop in loops]
        return out + [("line", np.stack([P[i], P[i + 1]]), 0.0) for i in (0, 2, 4, 6)]
    if shape == "rod":
        half = 0.5 * float(d["length"]) * axes[2]
        return [("line", np.stack([r - half, r + half]), 0.0)]
    if shape in ("cylinder", "disc", "ring", "cylindrical_shell"):
        a = float(d["radius"])
        half = 0.5 * float(d.get("height", 0.0)) * axes[2]
        phi = np.linspace(0.0, 2.0 * math.pi, RIM_POINTS + 1)
        ring = a * (np.cos(phi)[:, None] * axes[0] + np.sin(phi)[:, None] * axes[1])
        out = [("line", r + half + ring, 0.0)]
        if half.any():
            out.append(("line", r - half + ring, 0.0))
            for k in range(0, RIM_POINTS, RIM_POINTS // 4):
                out.append(("line", np.stack([r - half + ring[k], r + half + ring[k]]), 0.0))
        return out
    # a body without a shape: its principal axes, a tenth of the scene's size (set later)
    return [("axes", np.stack([r, r + axes[0], r + axes[1], r + axes[2]]), 0.0)]


def _planes(scene) -> list[tuple[np.ndarray, np.ndarray]]:
    """(point, unit normal) of every plane the bodies strike."""
    out = []
    for e in scene.effects:
        if e.type != "impact" or "other" in e.fields or "bodies" in e.fields:
            continue
        p = np.asarray(e.fields.get("plane_point", [0.0, 0.0, 0.0]), dtype=float)
        n = np.asarray(e.fields.get("plane_normal", [0.0, 0.0, 1.0]), dtype=float)
        key = (tuple(p), tuple(n / np.linalg.norm(n)))
        if key not in [(tuple(a), tuple(b)) for a, b in out]:
            out.append((p, n / np.linalg.norm(n)))
    return out


def _frames(t: np.ndarray) -> np.ndarray:
    """The samples shown: at most MAX_FRAMES, evenly chosen, the first and last kept."""
    k = t.size
    if k <= MAX_FRAMES:
        return np.arange(k)
    return np.unique(np.round(np.linspace(0, k - 1, MAX_FRAMES)).astype(int))


def player_data(result) -> dict:
    """What the player draws (see the Conventions): the frames' times, each frame's
    shapes projected to the drawing (``c``: circles (x, y, r), ``p``: polylines as flat
    x, y lists), the static planes, the events and the run's length."""
    tr, scene = result.trajectory, result.scene
    snap = tr.snapshot
    r_all = np.asarray(snap.r, dtype=float)  # (k, n, 3)
    R_all = np.asarray(snap.R, dtype=float)  # (k, n, 3, 3)
    idx = _frames(np.asarray(tr.t))
    right, up = _screen_axes()
    span = float(np.ptp(r_all.reshape(-1, 3), axis=0).max()) if r_all.size else 0.0
    size = max(span, *(_extent(b) for b in scene.bodies), 1e-9)
    raw = []  # per frame: [(kind, points (k, 2), radius)]
    for f in idx:
        shapes = []
        for i, body in enumerate(scene.bodies):
            for kind, pts, rad in _outline(body, r_all[f, i], R_all[f, i]):
                if kind == "axes":
                    g, ends = pts[0], pts[1:]
                    for e in ends:
                        q = np.stack([g, g + 0.1 * size * (e - g)])
                        shapes.append(("line", np.stack([q @ right, q @ up], axis=-1), 0.0))
                    continue
                shapes.append((kind, np.stack([pts @ right, pts @ up], axis=-1), rad))
        raw.append(shapes)
    planes = []
    centre = r_all.reshape(-1, 3).mean(axis=0) if r_all.size else np.zeros(3)
    for p, n in _planes(scene):
        t1 = np.cross(n, [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0])
        t1 /= np.linalg.norm(t1)
        t2 = np.cross(n, t1)
        o = centre - ((centre - p) @ n) * n
        s = 0.75 * size
        quad = np.array(
            [o + a * s * t1 + b * s * t2 for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        )
        planes.append(np.stack([quad @ right, quad @ up], axis=-1))
    pts = [s[1] for shapes in raw for s in shapes] + planes
    lo = np.min([p.min(axis=0) for p in pts], axis=0)
    hi = np.max([p.max(axis=0) for p in pts], axis=0)
    pad = max((s[2] for shapes in raw for s in shapes), default=0.0)
    lo, hi = lo - pad, hi + pad
    scale = min((WIDTH - 2 * MARGIN) / max(hi[0] - lo[0], 1e-12),
                (HEIGHT - 2 * MARGIN) / max(hi[1] - lo[1], 1e-12))  # fmt: skip
    mid = 0.5 * (lo + hi)

    def to_svg(p: np.ndarray) -> list[float]:
        x = WIDTH / 2 + (p[:, 0] - mid[0]) * scale
        y = HEIGHT / 2 - (p[:, 1] - mid[1]) * scale  # SVG's y points down
        return [round(float(v), 2) for xy in zip(x, y, strict=True) for v in xy]

    frames = []
    for shapes in raw:
        out = []
        for kind, p, rad in shapes:
            if kind == "circle":
                out.append({"c": [*to_svg(p), round(rad * scale, 2)]})
            elif kind == "dot":
                out.append({"c": [*to_svg(p), 3.0]})
            else:
                out.append({"p": to_svg(p)})
        frames.append(out)
    events = [
        {"t": float(e.t), "kind": e.kind, "label": f"{e.kind} at t = {e.t:.6g} s"}
        for e in tr.events
    ]
    return {
        "name": scene.name,
        "t": [float(tr.t[f]) for f in idx],
        "duration": float(scene.duration),
        "frames": frames,
        "planes": [to_svg(p) for p in planes],
        "events": events,
        "size": [WIDTH, HEIGHT],
    }


def _extent(body) -> float:
    """The body's largest dimension (0 for a point)."""
    vals = [float(v) for k, v in body.dims.items() if k != "inertia"]
    return max(vals, default=0.0) * (2.0 if "radius" in body.dims else 1.0)


def _tables(result) -> str:
    """The invariants (conserved quantities and their drift) and the derived quantities
    (exact and measured), as HTML tables."""
    rows = [
        "<table class='invariants'><caption>conserved</caption>"
        "<tr><th>quantity</th><th>value</th><th>drift</th><th>tolerance</th></tr>"
    ]
    for c in result.conserved:
        rows.append(
            f"<tr><td>{html.escape(c.name)}</td><td>{c.value:.12g}</td>"
            f"<td>{c.drift:.2e}</td><td>{c.tolerance:.1e}</td></tr>"
        )
    rows.append("</table>")
    derived = result.trajectory.derived
    if derived:
        rows.append(
            "<table class='derived'><caption>derived quantities</caption>"
            "<tr><th>quantity</th><th>exact</th><th>from the motion</th></tr>"
        )
        for name, exact, measured in derived:
            e = "-" if exact is None else f"{exact:.10g}"
            m = "-" if measured is None else f"{measured:.10g}"
            rows.append(f"<tr><td>{html.escape(name)}</td><td>{e}</td><td>{m}</td></tr>")
        rows.append("</table>")
    return "\n".join(rows)


def player_section(result, key: str) -> str:
    """One player (the drawing, its controls, its data) and its tables, as an HTML
    section whose id is ``key``."""
    data = json.dumps(player_data(result), separators=(",", ":")).replace("</", "<\\/")
    verdict = "PASSED" if result.passed else "FAILED"
    title = html.escape(result.scene.title or result.scene.name)
    return (
        f"<section class='scene' id='{html.escape(key)}'><h2>{title}</h2>"
        f"<p>{verdict}; {html.escape(result.trajectory.method)}</p>"
        "<div class='player'>"
        f"<svg class='stage' viewBox='0 0 {WIDTH:g} {HEIGHT:g}' role='img' "
        f"aria-label='the bodies of the scene {html.escape(result.scene.name)}'></svg>"
        "<div class='controls'><button type='button' class='play'>play</button> "
        "<label>time <input type='range' class='slider' min='0' value='0' step='1'></label> "
        "<output class='time'>t = 0 s</output></div>"
        f"<svg class='timeline' viewBox='0 0 {WIDTH:g} 24' role='img' "
        "aria-label='the events of the run on its timeline'></svg>"
        f"<script type='application/json' class='scene-data'>{data}</script></div>"
        f"<div class='tables'>{_tables(result)}</div></section>"
    )


def player_script() -> str:
    """The players' script (``identities/data/scene_player.js``)."""
    return _SCRIPT.read_text(encoding="utf-8")


#: the players' look (the site's pages share it; a standalone page inlines it)
PLAYER_CSS = """
.player { display: inline-block; vertical-align: top; margin-right: 1em; }
.stage { width: 480px; height: 320px; border: 1px solid #ccc; background: #fbfbfb; }
.stage .body { fill: none; stroke: #1f4e9a; stroke-width: 1.5; }
.stage .plane { fill: #e8e3d8; stroke: #b8ad96; }
.timeline { width: 480px; height: 24px; }
.timeline .mark { stroke: #a01010; stroke-width: 2; }
.timeline .now { fill: #1f4e9a; }
.tables { display: inline-block; vertical-align: top; }
"""


def player_page(result) -> str:
    """A standalone page that plays ``result`` (script and style inline)."""
    title = html.escape(result.scene.title or result.scene.name)
    return (
        "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
        f"<title>{title}</title><style>{PLAYER_CSS}</style></head>\n<body><main>"
        f"<h1>{title}</h1>\n{player_section(result, result.scene.name)}\n"
        f"<script>{player_script()}</script></main></body></html>\n"
    )
