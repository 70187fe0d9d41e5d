"""The built-in scenes as catalogue checks (kind ``scene``): each simulates only the
effects its file lists and compares what it measures on the motion with the book's
closed form; the conserved quantities its effects imply must hold.

The label is ``numeric``: a simulation is evidence, not a proof.  The comparisons and
their tolerances (with reasons) live in :mod:`identities.book.scenes.compare`.
"""

from __future__ import annotations

import dataclasses

from identities.book.scenes.compare import run_book_scene
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from mechanics.scenes import builtin_path, load_scene

#: built-in scene → the book items it reproduces
SCENES = {
    "bouncing_ball": ("E6.1",),
    "rolling_incline": ("E3.6",),
    "physical_pendulum": ("E4.4", "eq4.71"),
    "physical_pendulum_small": ("E4.3",),
    "cylinder_in_track": ("E4.5",),
    "heavy_top": ("eq5.70",),
    "free_top_flip": ("eq5.102",),
    "rocket": ("E7.2",),
    "carousel": ("E7.3",),
    "tank_draining": ("E8.1",),
    "sliding_ball": ("P5.1",),
    "rod_struck": ("E6.2",),
    "newtons_cradle": ("eq6.38",),
    "flip_after_push": ("eq5.102",),
    "rocket_drag": ("eq7.25",),
    "box_drop": ("eq6.21", "eq6.41"),
    "box_drop_friction": ("eq6.19", "eq6.21"),
    "top_hits_floor": ("eq5.70",),
}


def _run(d: Derivation, name: str, method: str) -> None:
    scene = load_scene(builtin_path(name))
    if method != scene.method:
        scene = dataclasses.replace(scene, method=method)
    result = run_book_scene(scene)
    d.note(f"{name} ({result.method}): {len(result.trajectory.t)} samples")
    if not result.comparisons:
        raise AssertionError(f"scene {name} compared nothing with the book")
    for c in result.comparisons:
        d.numeric_close(
            c.relative_difference,
            0.0,
            atol=c.tolerance,
            claim=f"{method}: {c.name} = {c.simulated:.12g} vs the book's {c.book}: "
            f"{c.closed_form:.12g} (relative; {c.reason})",
        )
    for q in result.conserved:
        d.numeric_close(
            q.drift, 0.0, atol=q.tolerance, claim=f"{method}: {q.name} conserved (relative drift)"
        )


def _register(name: str, items: tuple[str, ...]) -> None:
    def scene_check(d: Derivation) -> None:
        _run(d, name, "auto")
        if load_scene(builtin_path(name)).method != "integrate":
            _run(d, name, "integrate")

    scene_check.__name__ = scene_check.__qualname__ = f"scene_{name}"
    check(
        f"thm.scene-{name.replace('_', '-')}",
        f"Scene {name}: simulated (exact flow, then integrated) against the book",
        kind="scene",
        covers=items,
        statement=f"`bodycheck demo {name}` reproduces {', '.join(items)} and conserves what "
        "its effects imply, by the exact flow and by integration",
    )(scene_check)


for _name, _items in SCENES.items():
    _register(_name, _items)
