"""Plots of a scene run, as a teacher would show them: the motion, the conserved
quantities over time (as relative drift), and a phase picture (the polhode of a top,
the path of a top's axis, a trajectory or a phase portrait).

matplotlib is imported lazily, with the non-interactive Agg backend.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

__all__ = ["plot_result"]

#: series drawn in the motion panel, in order of preference (at most three)
_MOTION = (
    "z",
    "phi",
    "psi",
    "s",
    "theta",
    "h",
    "omega1",
    "omega2",
    "omega3",
    "v",
    "vz",
    "phidot",
    "psidot",
    "u",
    "omega",
)


def _bodies(series: dict) -> list[str]:
    """The prefixes of the free bodies' series ("" for a single body)."""
    if "x" in series and "vx" in series:
        return [""]
    return [k[:-1] for k in series if k.endswith(".x") and k[:-1] + "vx" in series]


def _dominant_axes(series: dict, prefixes: list[str]) -> list[str]:
    """The space axes ordered by how far the bodies move along them."""
    reach = {c: sum(float(np.ptp(series[f"{p}{c}"])) for p in prefixes) for c in "xyz"}
    top = max(reach.values())
    # a reach at the rounding's level (1e-16 of a motion) is no motion: ties keep x, y, z
    return sorted("xyz", key=lambda c: -reach[c] if reach[c] > 1e-9 * top else 0.0)


def _motion_keys(series: dict) -> list[str]:
    if "axis_x" in series:  # a top: nutation and precession (the spin would dwarf them)
        return ["theta", "psi"]
    if "omega1" in series and "vz" in series and not np.ptp(series["vz"]):
        return ["omega1", "omega2", "omega3"]  # a free top: the translation is trivial
    prefixes = _bodies(series)
    if len(prefixes) > 1:  # several free bodies: along the axis they move most on
        c = _dominant_axes(series, prefixes)[0]
        return [f"{p}{c}" for p in prefixes][:5]
    keys = [k for k in _MOTION if k in series]
    return keys[:3]


def plot_result(result, path) -> Path:
    """Write a PNG of ``result`` (a :class:`mechanics.scenes.SceneResult`) to ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    tr, scene = result.trajectory, result.scene
    t, S = tr.t, tr.series
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4), constrained_layout=True)
    title = scene.title or scene.name
    fig.suptitle(
        f"{title}" + (f" — {scene.book}" if scene.book else "") + f"\n{tr.method}", fontsize=10
    )

    ax = axes[0]
    for k in _motion_keys(S):
        ax.plot(t, S[k], label=k)
    for e in tr.events:
        ax.axvline(e.t, color="0.8", lw=0.6, zorder=0)
    ax.set_xlabel("t [s]")
    ax.set_title("motion" + (f" ({len(tr.events)} events)" if tr.events else ""))
    ax.legend(fontsize=8)

    ax = axes[1]
    scales = tr.scales
    for c in result.conserved:
        v = np.asarray(tr.conserved[c.name], dtype=float)
        scale = max(float(np.max(np.abs(v))), scales.get(c.name, 0.0), 1e-300)
        # drift relative to the value at the start of each segment between events
        ref = np.empty_like(v)
        for a, b in tr.segments(c.name):
            m = (t >= max(a, c.since)) & (t < b)
            if m.any():
                ref[m] = v[m][0]
        m = t >= c.since
        ax.plot(t[m], (v[m] - ref[m]) / scale, label=f"{c.name} ({'ok' if c.ok else 'FAIL'})")
    ax.set_xlabel("t [s]")
    ax.set_title("conserved quantities: relative drift")
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 3))
    if result.conserved:
        ax.legend(fontsize=8)

    ax = axes[2]
    if "axis_x" in S:
        ax.plot(S["axis_x"], S["axis_y"], lw=0.8)
        ax.set_aspect("equal")
        ax.set_xlabel("axis x")
        ax.set_ylabel("axis y")
        ax.set_title("path of the symmetry axis (precession, nutation)")
    elif "omega1" in S:
        ax.remove()
        ax = fig.add_subplot(1, 3, 3, projection="3d")
        ax.plot(S["omega1"], S["omega2"], S["omega3"], lw=0.8)
        ax.plot(S["omega1"][:1], S["omega2"][:1], S["omega3"][:1], "o")
        ax.set_xlabel("ω1")
        ax.set_ylabel("ω2")
        ax.set_zlabel("ω3")
        ax.set_title("polhode: ω in the body frame [rad/s]")
    elif _bodies(S) and any(np.ptp(S[f"{p}{c}"]) > 0 for p in _bodies(S) for c in "xyz"):
        prefixes = _bodies(S)
        a, b = sorted(_dominant_axes(S, prefixes)[:2])
        for p in prefixes:
            ax.plot(S[f"{p}{a}"], S[f"{p}{b}"], label=p.rstrip(".") or None)
            ax.plot(S[f"{p}{a}"][:1], S[f"{p}{b}"][:1], "o", color=ax.lines[-1].get_color())
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(f"{a} [m]")
        ax.set_ylabel(f"{b} [m]")
        ax.set_title("paths of the centres of mass (start: dot)")
        if len(prefixes) > 1:
            ax.legend(fontsize=8)
    else:
        keys = _motion_keys(S)
        pairs = {"phi": "phidot", "psi": "psidot", "s": "v", "z": "vz", "h": "u"}
        q = next((k for k in keys if k in pairs), keys[0] if keys else None)
        if q is not None:
            p = pairs.get(q)
            if p in S:
                ax.plot(S[q], S[p])
                ax.set_xlabel(q)
                ax.set_ylabel(p)
                ax.set_title("phase portrait")
            else:
                ax.plot(t, S[q])
                ax.set_title(q)
    lines = [
        f"{'ok' if c.ok else 'FAIL'} {c.name}: rel. diff {c.relative_difference:.1e}"
        for c in result.comparisons
    ]
    if lines:
        fig.text(
            0.67,
            0.01,
            "\n".join(lines),
            fontsize=7,
            va="bottom",
            bbox={"facecolor": "white", "alpha": 0.8, "lw": 0},
        )
    out = Path(path)
    # written whole or not at all: into a temporary file beside it, then renamed
    tmp = out.with_name(f".{out.name}.{os.getpid()}.part")
    try:
        fig.savefig(tmp, dpi=100, format=out.suffix.lstrip(".").lower() or "png")
        os.replace(tmp, out)
    finally:
        plt.close(fig)
        tmp.unlink(missing_ok=True)
    return out
