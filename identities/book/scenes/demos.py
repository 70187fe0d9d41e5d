"""Lecture demos: six built-in scenes a lecturer can run in class, each with its book
reference, a paragraph saying what to watch, the command for its plot and the
catalogue check that backs it (``bodycheck demo --list``).  Each paragraph says only
what the scene's comparison with the book checks (:mod:`.compare`)."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["LECTURE_DEMOS", "Demo"]


@dataclass(frozen=True)
class Demo:
    name: str  # the built-in scene
    topic: str
    paragraph: str

    @property
    def check(self) -> str:
        """The catalogue check that runs this scene against the book."""
        return "thm.scene-" + self.name.replace("_", "-")


LECTURE_DEMOS = (
    Demo(
        "free_top_flip",
        "the tennis-racket (Dzhanibekov) flip",
        "A free body with moments J1 < J2 < J3 = 1, 2, 3, spun almost exactly about its "
        "intermediate axis, turns over again and again: rotation about the axes of least "
        "and greatest moment is stable, about the middle one unstable (5.3.3). Watch ω2 "
        "reverse its sign; the check compares the reversals with the period 4K(m)/λ of the "
        "Jacobi-elliptic solution of Euler's equations (5.91).",
    ),
    Demo(
        "heavy_top",
        "the Lagrange top: precession and nutation",
        "A heavy symmetric top on a fixed point, released at θ = 0.5 with spin only, "
        "precesses about the vertical and nutates: θ swings between the turning points "
        "where the cubic f(cos θ) of 5.2.4 vanishes. Watch θ(t) and the axis' trace; the "
        "check compares the turning points and the nutation period with the closed forms.",
    ),
    Demo(
        "rod_struck",
        "the centre of percussion",
        "A bat (a thin rod) at rest on a frictionless table is struck at one end, "
        "perpendicular to it. Just after the blow one point of the rod is momentarily at "
        "rest, 2ℓ/3 from the struck end (6.28)-(6.29): held there, the bat would not sting "
        "the hand. The check reads the point at rest and the rod's energy 2S²/m (6.26) off "
        "the motion.",
    ),
    Demo(
        "newtons_cradle",
        "Newton's cradle",
        "A row of equal, touching elastic balls is struck by one more: the contacts are "
        "simultaneous, resolved one after another, and with e = 1 a direct impact of equal "
        "masses exchanges their velocities (6.36)-(6.38), so the momentum runs down the row "
        "and only the last ball flies off. The check compares every ball's final velocity.",
    ),
    Demo(
        "rocket",
        "the rocket equation (Tsiolkovsky, with gravity)",
        "A rocket burns fuel at a constant rate q with exhaust speed u while rising "
        "against gravity: v(t) = u ln(m0/(m0 − q t)) − g t (7.30), then it coasts after "
        "burn-out. Watch the mass and the speed; the check compares the speed with the "
        "closed form.",
    ),
    Demo(
        "tank_draining",
        "Bernoulli and Torricelli: a draining tank",
        "Water runs out of a wide tank through a small hole: Bernoulli's theorem along a "
        "streamline gives Torricelli's u = √(2gh) (8.34)-(8.37), and with continuity the "
        "level falls as (√h0 − (a/A)√(g/2) t)². The check compares the outflow speed and "
        "the level with these forms, allowing the (a/A)² the surface's own speed adds.",
    ),
)
