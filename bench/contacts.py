"""Issue 27's contact cases against Siconos and MuJoCo (item 5): each case's exact
answer (derived here, in closed form), and the figure the scene engine, Siconos and
MuJoCo give for it, through the conformance battery's adapters.

    python -m bench.contacts            # the table (about a minute)
    python -m bench.contacts --markdown # the same as a Markdown table (docs/guide/engines.md's)

Engines: the scene engine (:class:`~mechanics.conformance.adapters.SceneEngineAdapter`,
its default method); Siconos 4.5, Moreau–Jean θ = 1/2 at h = 2⁻¹³ s (Debian's
``python3-siconos``: :class:`~mechanics.conformance.adapters.siconos.SiconosAdapter`);
MuJoCo RK4 with the tuned contact at h = 2⁻¹³ s (the ``mujoco`` extra). An engine that
is missing or cannot express a case prints why in its column.

Each figure is read off the trajectory's samples (every 2⁻⁷ s) by one function for
every engine; the exact column applies the closed form:

- *flat box / plate / cylinder* (e = 1/2, dropped 0.7 m, flat): after landing,
  v_z + g (t − t₁) = e √(2 g h) at every later sample (the rebound, t₁ = √(2h/g)), no
  spin, no sideways motion; smooth and with μ = 0.8.
- *cradle* (three equal balls, e = 1, the first striking the two touching): the
  textbook answer (0, 0, v): the first two stop and the third leaves with v.
- *bounce to rest* (a ball, e = 1/2, dropped 0.5 m): at rest (|v| ≤ 1 mm/s from then
  on) from the first sample after the impact whose rebound is below 1 mm/s, 0.3 ms
  before t∞ = t₁ (1 + e)/(1 − e) (named in the case); then resting on the ground
  (depth 0).
- *box sliding* (on its face, v₀ = 2 m/s, μ = 1/2): stops after v₀/(μ g) at
  v₀²/(2 μ g).
- *ball rolling* (a solid ball sliding at v₀ = 2 m/s with no spin, μ = 0.3): rolls from
  2 v₀/(7 μ g) at 5 v₀/7, ω r = v.
- *ball placed on the floor*: stays, depth 0 over 1 s.
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from mechanics.conformance.protocol import Body, Ground, Scenario, Shape

G = 9.81
STEP = 2.0**-13
SAMPLE = 2.0**-7
#: at rest: speeds below this (m/s) from a sample on
REST_SPEED = 1e-3


def _times(duration):
    return tuple(k * SAMPLE for k in range(round(duration / SAMPLE) + 1))


def _box(a, b, c, m=1.0):
    """A box of half extents (a, b, c): its principal moments."""
    return (m * (b * b + c * c) / 3, m * (a * a + c * c) / 3, m * (a * a + b * b) / 3)


def _scenario(name, bodies, duration, *, ground, pairs=(), gravity=True):
    return Scenario(
        name,
        name,
        "issue 27",
        tuple(bodies),
        duration=duration,
        sample_times=_times(duration),
        gravity=(0.0, 0.0, -G) if gravity else (0.0, 0.0, 0.0),
        ground=ground,
        pair_restitution=tuple(pairs),
        steps=(STEP,),
    )


# ------------------------------------------------------------------ the cases


def _landing(label, shape, dims, J, low, mu):
    """A body dropped flat from 0.7 m above the ground (its lowest point ``low`` below
    G), e = 1/2: (scenario, exact figures, reader)."""
    e, h = 0.5, 0.7
    body = Body(shape, 1.0, J, Shape(shape, dims), position=(0.0, 0.0, low + h))
    sc = _scenario(f"{label} landing flat", [body], 0.5, ground=Ground(e, friction=mu))
    t1 = math.sqrt(2 * h / G)
    exact = {
        "rebound v_z (m/s)": e * math.sqrt(2 * G * h),
        "max abs omega (rad/s)": 0.0,
        "max abs v_xy (m/s)": 0.0,
    }

    def read(tr):
        t = tr.t
        after = t > t1 + 0.05
        vz = tr.velocity[after, 0, 2] + G * (t[after] - t1)
        return {
            "rebound v_z (m/s)": float(np.median(vz)),
            "max abs omega (rad/s)": float(np.abs(tr.omega).max()),
            "max abs v_xy (m/s)": float(np.abs(tr.velocity[:, 0, :2]).max()),
        }

    return sc, exact, read


def _cradle():
    r, v = 0.1, 1.0
    J = (0.4 * r * r,) * 3
    balls = [
        Body("b0", 1.0, J, Shape("sphere", (r,)), position=(-0.5, 0.0, 0.0), velocity=(v, 0, 0)),
        Body("b1", 1.0, J, Shape("sphere", (r,)), position=(0.2, 0.0, 0.0)),
        Body("b2", 1.0, J, Shape("sphere", (r,)), position=(0.4, 0.0, 0.0)),
    ]
    sc = _scenario(
        "Newton's cradle", balls, 1.0, ground=None, pairs=[(0, 1, 1.0), (1, 2, 1.0)], gravity=False
    )
    exact = {"final v_x (m/s)": (0.0, 0.0, v)}

    def read(tr):
        return {"final v_x (m/s)": tuple(float(x) for x in tr.velocity[-1, :, 0])}

    return sc, exact, read


def _rest_time(t, speed):
    """The first sample from which the speed stays at most REST_SPEED."""
    moving = np.nonzero(speed > REST_SPEED)[0]
    if moving.size == 0:
        return float(t[0])
    k = moving[-1] + 1
    return float(t[k]) if k < t.size else math.inf


def _bounce():
    r, h, e = 0.1, 0.5, 0.5
    J = (0.4 * r * r,) * 3
    ball = Body("ball", 1.0, J, Shape("sphere", (r,)), position=(0.0, 0.0, r + h))
    t1 = math.sqrt(2 * h / G)
    t_inf = t1 * (1 + e) / (1 - e)
    sc = _scenario(f"ball bouncing to rest (t_inf {t_inf:.4f} s)", [ball], 1.5, ground=Ground(e))
    v1 = G * t1
    # impact k at t1 (1 + 2e + ... + 2e^{k-1}) rebounds at e^k v1; at rest from the first
    # whose rebound is below REST_SPEED (the speeds after it are smaller)
    k = math.ceil(math.log(REST_SPEED / v1) / math.log(e))
    tk = t1 * (1 + 2 * e * (1 - e ** (k - 1)) / (1 - e))
    t = np.asarray(sc.sample_times)
    exact = {
        "at rest from (s)": float(t[np.searchsorted(t, tk, side="right")]),
        "final depth (m)": 0.0,
    }

    def read(tr):
        speed = np.linalg.norm(tr.velocity[:, 0], axis=-1)
        return {
            "at rest from (s)": _rest_time(tr.t, speed),
            "final depth (m)": float(r - tr.position[-1, 0, 2]),
        }

    return sc, exact, read


def _sliding():
    a, b, c, v0, mu = 0.3, 0.2, 0.1, 2.0, 0.5
    box = Body(
        "box",
        1.0,
        _box(a, b, c),
        Shape("box", (a, b, c)),
        position=(0.0, 0.0, c),
        velocity=(v0, 0.0, 0.0),
    )
    sc = _scenario("box sliding to a stop", [box], 0.75, ground=Ground(0.5, friction=mu))
    exact = {"stop distance (m)": v0 * v0 / (2 * mu * G), "stopped by (s)": v0 / (mu * G)}

    def read(tr):
        speed = np.linalg.norm(tr.velocity[:, 0], axis=-1)
        return {
            "stop distance (m)": float(tr.position[-1, 0, 0]),
            "stopped by (s)": _rest_time(tr.t, speed),
        }

    exact["stopped by (s)"] = float(
        np.asarray(sc.sample_times)[np.searchsorted(sc.sample_times, v0 / (mu * G))]
    )
    return sc, exact, read


def _rolling():
    r, v0, mu = 0.1, 2.0, 0.3
    ball = Body(
        "ball",
        1.0,
        (0.4 * r * r,) * 3,
        Shape("sphere", (r,)),
        position=(0.0, 0.0, r),
        velocity=(v0, 0.0, 0.0),
    )
    sc = _scenario("ball sliding into rolling", [ball], 0.5, ground=Ground(0.5, friction=mu))
    exact = {"final v_x (m/s)": 5 * v0 / 7, "final omega_y r (m/s)": 5 * v0 / 7}

    def read(tr):
        w_space = np.einsum("ji,j->i", tr.R_A_O[-1, 0], tr.omega[-1, 0])
        return {
            "final v_x (m/s)": float(tr.velocity[-1, 0, 0]),
            "final omega_y r (m/s)": float(w_space[1] * r),
        }

    return sc, exact, read


def _placed():
    r = 0.1
    ball = Body("ball", 1.0, (0.4 * r * r,) * 3, Shape("sphere", (r,)), position=(0.0, 0.0, r))
    sc = _scenario("ball placed on the floor", [ball], 1.0, ground=Ground(0.5))
    exact = {"max depth (m)": 0.0}

    def read(tr):
        return {"max depth (m)": float(np.max(np.abs(tr.position[:, 0, 2] - r)))}

    return sc, exact, read


def cases():
    """[(scenario, exact figures, reader of a trajectory's figures)]."""
    a, b, c = 0.1, 0.2, 0.3
    plate = (0.2, 0.2, 0.01)
    cases = []
    for mu in (0.0, 0.8):
        cases.append(_landing("box 0.2 x 0.4 x 0.6", "box", (a, b, c), _box(a, b, c), c, mu))
        cases.append(_landing("plate 0.4 x 0.4 x 0.02", "box", plate, _box(*plate), plate[2], mu))
        cyl = (0.2, 0.05)
        Jc = (
            (3 * cyl[0] ** 2 + 4 * cyl[1] ** 2) / 12,
            (3 * cyl[0] ** 2 + 4 * cyl[1] ** 2) / 12,
            cyl[0] ** 2 / 2,
        )
        cases.append(_landing("cylinder r 0.2, h 0.1", "cylinder", cyl, Jc, cyl[1], mu))
    cases += [_cradle(), _bounce(), _sliding(), _rolling(), _placed()]
    return cases


# ------------------------------------------------------------------ the engines


def engines():
    """[(label, adapter or the reason it is missing)]."""
    from mechanics.conformance.adapters import MissingExtraError, SceneEngineAdapter

    out = [("scene engine", SceneEngineAdapter())]
    for label, make in (("Siconos", _siconos), ("MuJoCo", _mujoco)):
        try:
            out.append((label, make()))
        except MissingExtraError as exc:
            out.append((label, str(exc)))
    return out


def _siconos():
    from mechanics.conformance.adapters.siconos import SiconosAdapter

    return SiconosAdapter(0.5)


def _mujoco():
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

    return MuJoCoAdapter("RK4", "tuned")


def _fmt(x):
    if isinstance(x, str):
        return x
    if isinstance(x, tuple):
        return "(" + ", ".join(_fmt(v) for v in x) + ")"
    return f"{x:.6g}"


def table():
    """The header and the rows: per case and figure, the exact value and each engine's."""
    rows = []
    engs = engines()
    for sc, exact, read in cases():
        mu = sc.ground.friction if sc.ground is not None else 0.0
        name = sc.name + (f", mu {mu:g}" if mu else "")
        got = {}
        for label, eng in engs:
            if isinstance(eng, str):
                got[label] = {k: "missing" for k in exact}
                continue
            why = eng.supports(sc)
            if why is not None:
                got[label] = {k: "not mapped" for k in exact}
                continue
            try:
                figs = read(eng.run(sc, STEP))
            except Exception as exc:  # an engine's refusal or failure: its one line
                msg = str(exc).splitlines()[0]
                figs = {k: f"refused: {msg[-80:]}" for k in exact}
            got[label] = figs
        for k, want in exact.items():
            rows.append([name, k, _fmt(want)] + [_fmt(got[label][k]) for label, _ in engs])
    return ["case", "figure", "exact"] + [label for label, _ in engs], rows


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--markdown", action="store_true")
    args = p.parse_args(argv)
    head, rows = table()
    if args.markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for r in rows:
            print("| " + " | ".join(r) + " |")
    else:
        for r in [head, *rows]:
            print("  ".join(f"{x:<28.28}" for x in r))
    return 0


if __name__ == "__main__":
    sys.exit(main())
