"""Reporting: the headline (issue 15's targets as met or not), the Markdown tables and
the plots.

Part of :mod:`bench.workprecision` (its docstring states the conventions).
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path

from .settings import (
    BATCH_GOAL,
    DECADES,
    ERROR_FLOOR,
    EXACT_GOAL,
    FREE_TOP_ROTATIONS,
    LONG_RUN_S,
    MUJOCO_EXTRA,
    MUJOCO_J,
    MUJOCO_T,
    MUJOCO_W0,
    STEPPER_GOAL,
    STEPPER_MUST,
    TARGET_ERROR,
)


def _fastest(records, method, target):
    ok = [r for r in records if r["method"] == method and r["error"] <= target]
    return min(ok, key=lambda r: r["time_s"]) if ok else None


def target_status(value, goal, must=None) -> str:
    """``"met"``, ``"must met, goal not"`` or ``"NOT MET"`` for a ratio against its goal
    (and its required minimum), ``"not measured"`` when there is no value."""
    if value is None:
        return "not measured"
    if value >= goal:
        return "met"
    if must is not None and value >= must:
        return "must met, goal not"
    return "NOT MET"


def _fastest_of(records, family, target):
    ok = [r for r in records if r["family"] == family and r["error"] <= target]
    return min(ok, key=lambda r: r["time_s"]) if ok else None


def decades(recs: list[dict]) -> list[dict]:
    """At each error level of :data:`DECADES`, our fastest run that reaches it against
    scipy's fastest: "met" (ours at most scipy's time), "met (scipy does not reach it)",
    "NOT MET", or "NOT MET (neither reaches it)"."""
    rows = []
    for e in DECADES:
        o, sc = _fastest_of(recs, "ours", e), _fastest_of(recs, "scipy", e)
        if o is None:
            status = "NOT MET" + (" (neither reaches it)" if sc is None else "")
        elif sc is None:
            status = "met (scipy does not reach it)"
        else:
            status = "met" if o["time_s"] <= sc["time_s"] else "NOT MET"
        rows.append(
            {
                "error": e,
                "ours": _brief(o),
                "scipy": _brief(sc),
                "scipy_over_ours": sc["time_s"] / o["time_s"] if o and sc else None,
                "status": status,
            }
        )
    return rows


def _reached_decades_met(rows: list[dict]) -> bool:
    """Every decade that either side reaches is met (a level neither reaches, below
    the problem's conditioning floor in float64, compares nothing)."""
    return all(
        d["status"].startswith("met") or d["status"] == "NOT MET (neither reaches it)" for d in rows
    )


def headline(study: dict) -> dict:
    """Issue 15's targets (and issue 6's ratios), from the records of this one run.

    ``targets`` is a list of rows ``{name, measured, goal, status, detail}``; a target
    that is not met says so (``status`` "NOT MET"), one that could not be measured says
    why."""
    recs = study["problems"]["free_top"]["records"]
    steppers = sorted({r["method"] for r in recs if r["family"] == "ours"})
    h: dict = {"target_error": TARGET_ERROR}
    # -- the fastest stepper at scipy DOP853's error (its most accurate run)
    dop_recs = [r for r in recs if r["method"] == "scipy-DOP853"]
    ref = min(dop_recs, key=lambda r: r["error"]) if dop_recs else None
    h["scipy_dop853"] = _brief(ref)
    best = _fastest_of(recs, "ours", ref["error"]) if ref else None
    h["best_stepper"] = _brief(best)
    h["best_stepper_vs_scipy_dop853"] = ref["time_s"] / best["time_s"] if ref and best else None
    h["per_stepper"] = {}
    for m in steppers:
        r = _fastest(recs, m, ref["error"]) if ref else None
        h["per_stepper"][m] = (
            None if r is None else {**_brief(r), "vs_scipy_dop853": ref["time_s"] / r["time_s"]}
        )
    # -- the exact solution: one evaluation (construction apart)
    ex = study.get("exact_evaluation")
    h["exact"] = ex
    h["exact_vs_scipy_dop853"] = ref["time_s"] / ex["evaluation_s"] if ref and ex else None
    h["exact_with_construction_vs_scipy_dop853"] = (
        ref["time_s"] / (ex["evaluation_s"] + ex["construction_s"]) if ref and ex else None
    )
    # -- every decade: our best against scipy's best, on the free top and on the others
    h["decades"] = decades(recs)
    dec_ok = all(d["status"].startswith("met") for d in h["decades"])
    h["decades_by_problem"] = {
        name: decades(p["records"]) for name, p in study["problems"].items() if name != "free_top"
    }
    # -- energy drift, batches, the MuJoCo peer
    ed = study["energy_drift"]
    h["energy_drift_growth"] = {
        name: (c[-1] / c[0] if c[0] > 0 else None) for name, c in ed["curves"].items()
    }
    h["energy_drift_horizons"] = [ed["horizons_rotations"][0], ed["horizons_rotations"][-1]]
    b = study["batched"]
    h["batched_1000_over_1"] = {k: b[k]["batch_over_one"] for k in ("rk4", "splitting-4")}
    bv = study.get("batched_vs_scipy")
    h["batched_vs_scipy"] = None if bv is None else bv["ratio"]
    mj = study.get("mujoco")
    h["mujoco"] = mj
    # -- the rows
    rows = []
    r = h["best_stepper_vs_scipy_dop853"]
    rows.append(
        {
            "name": "fastest stepper at scipy DOP853's error / DOP853's time",
            "measured": r,
            "goal": f"≥ {STEPPER_GOAL:g} (must ≥ {STEPPER_MUST:g})",
            "status": target_status(r, STEPPER_GOAL, STEPPER_MUST),
            "detail": (
                f"scipy DOP853 rtol {ref['param']:g}: error {ref['error']:.2e} in "
                f"{ref['time_s']:.3g} s; ours: {best['method']} ({best['param_name']} "
                f"{best['param']:g}): {best['error']:.2e} in {best['time_s']:.3g} s"
                if ref and best
                else "no project stepper reaches scipy DOP853's error in this sweep"
            ),
        }
    )
    r = h["exact_vs_scipy_dop853"]
    rows.append(
        {
            "name": "exact solution (one evaluation) / scipy DOP853's time",
            "measured": r,
            "goal": f"≥ {EXACT_GOAL:.0e}",
            "status": target_status(r, EXACT_GOAL),
            "detail": (
                f"state(t) at {ex['rotations']} rotations {1e6 * ex['evaluation_s']:.3g} µs; "
                f"with the construction ({1e3 * ex['construction_s']:.3g} ms) the ratio is "
                f"{h['exact_with_construction_vs_scipy_dop853']:.3g}"
                if ex and ref
                else "not measured"
            ),
        }
    )
    n_ok = sum(d["status"].startswith("met") for d in h["decades"])
    rows.append(
        {
            "name": "our best ≤ scipy's best time at every decade 1e-4 … 1e-12",
            "measured": f"{n_ok} of {len(DECADES)} decades",
            "goal": "all",
            "status": "met" if dec_ok else "NOT MET",
            "detail": "; ".join(
                f"{d['error']:.0e}: {d['status']}"
                for d in h["decades"]
                if not d["status"].startswith("met")
            )
            or "every decade met",
        }
    )
    r = h["batched_vs_scipy"]
    rows.append(
        {
            "name": f"batch of {bv['bodies'] if bv else '—'} free bodies: scipy DOP853 body "
            "by body / ours",
            "measured": r,
            "goal": f"≥ {BATCH_GOAL:g}",
            "status": target_status(r, BATCH_GOAL),
            "detail": (
                f"ours {bv['ours_s']:.3g} s (worst error {bv['worst_error_ours']:.1e}), "
                f"scipy {bv['scipy_s']:.3g} s ({bv['scipy_bodies_run']} bodies run, scaled; "
                f"worst error {bv['worst_error_scipy']:.1e}), rtol {bv['rtol']:g}"
                if bv
                else "not measured"
            ),
        }
    )
    if mj is None or not mj.get("available"):
        rows.append(
            {
                "name": "MuJoCo RK4 (dt 1e-3) / our best at its error",
                "measured": None,
                "goal": "≥ 1",
                "status": "not measured",
                "detail": "mujoco is not installed: " + MUJOCO_EXTRA,
            }
        )
    else:
        pk, eu, bb = (
            mj["peers"]["mujoco-RK4"],
            mj["peers"]["mujoco-Euler"],
            mj["best_at_mujoco_rk4_error"],
        )
        rows.append(
            {
                "name": "MuJoCo RK4 (dt 1e-3) / our best at its error",
                "measured": mj["ratio"],
                "goal": "≥ 1",
                "status": target_status(mj["ratio"], 1.0),
                "detail": (
                    f"MuJoCo {mj['version']} RK4 {pk['error']:.2e} in {pk['time_s']:.3g} s, "
                    f"Euler {eu['error']:.2e} in {eu['time_s']:.3g} s; ours: "
                    + (
                        f"{bb['method']} ({bb['param_name']} {bb['param']:g}) "
                        f"{bb['error']:.2e} in {bb['time_s']:.3g} s"
                        if bb
                        else "no method reaches it"
                    )
                ),
            }
        )
    others = h["decades_by_problem"]
    if others:
        bad = {
            name: [d for d in rs if not _reached_decades_met([d])] for name, rs in others.items()
        }
        unreached = {
            name: [d["error"] for d in rs if d["status"] == "NOT MET (neither reaches it)"]
            for name, rs in others.items()
        }
        n_ok = sum(not v for v in bad.values())
        rows.append(
            {
                "name": "our best ≤ scipy's best at every decade reached, on every other problem",
                "measured": f"{n_ok} of {len(others)} problems",
                "goal": "all",
                "status": "met" if n_ok == len(others) else "NOT MET",
                "detail": "; ".join(
                    f"{name}: "
                    + (
                        ", ".join(f"{d['error']:.0e} {d['status']}" for d in bad[name])
                        or "every reached decade met"
                    )
                    + (
                        f" (neither reaches {', '.join(f'{e:.0e}' for e in unreached[name])})"
                        if unreached[name]
                        else ""
                    )
                    for name in others
                ),
            }
        )
    h["targets"] = rows
    h["goals"] = {
        "fastest stepper vs scipy DOP853 >= 10 (must 3)": rows[0]["status"],
        "exact vs scipy DOP853 >= 1e5": rows[1]["status"],
        "every decade 1e-4 … 1e-12": rows[2]["status"],
        "batch vs scipy >= 50": rows[3]["status"],
        "MuJoCo peer": rows[4]["status"],
        "splitting energy error bounded (growth <= 2)": _le(
            next(
                (v for k, v in h["energy_drift_growth"].items() if k.startswith("splitting")), None
            ),
            2.0,
        ),
    }
    if len(rows) > 5:
        h["goals"]["every reached decade on every other problem"] = rows[5]["status"]
    return h


def _time_at(rs, e):
    """Time to reach error ``e``, interpolated log-log between the sweep points."""
    pts = sorted(((r["error"], r["time_s"]) for r in rs if r["error"] > 0), reverse=True)
    for (ea, ta), (eb, tb) in itertools.pairwise(pts):
        if ea >= e >= eb:
            if ea == eb:
                return min(ta, tb)
            f = (math.log(e) - math.log(ea)) / (math.log(eb) - math.log(ea))
            return math.exp(math.log(ta) + f * (math.log(tb) - math.log(ta)))
    return None


def _ge(x, y):
    return None if x is None else bool(x >= y)


def _le(x, y):
    return None if x is None else bool(x <= y)


def _brief(r):
    if r is None:
        return None
    return {k: r[k] for k in ("method", "param_name", "param", "error", "time_s", "steps")}


def format_value(x, spec=".2e"):
    """A number for the tables, or an em dash when it was not measured."""
    if x is None:
        return "—"
    if isinstance(x, float):
        return format(x, spec)
    return str(x)


def _decade_rows(rows: list[dict]) -> list[str]:
    """The Markdown rows of one every-decade table."""

    def who(r):
        return "—" if r is None else f"{r['method']} ({r['param_name']} {r['param']:g})"

    out = []
    for d in rows:
        o, sc = d["ours"], d["scipy"]
        out.append(
            f"| {d['error']:.0e} | {who(o)} | {format_value(o and o['time_s'], '.3g')} | "
            f"{who(sc)} | {format_value(sc and sc['time_s'], '.3g')} | "
            f"{format_value(d['scipy_over_ours'], '.3g')} | {d['status']} |"
        )
    return out


def write_markdown(study: dict, path: Path) -> None:
    lines = [
        "# Work-precision study",
        "",
        f"`{study['command']}` — {'quick' if study['quick'] else 'full'} run, "
        f"wall time the median of {study['repeats']} run(s) (runs over {LONG_RUN_S} s once), "
        f"total {study['total_time_s']:.1f} s on {study['machine']['cpus']} CPU(s).",
        "",
        "## Headline: issue 15's targets (free asymmetric top)",
        "",
    ]
    h = study["headline"]
    lines += [
        "Issue 15's targets on the free asymmetric top J = (1, 2, 3), ω0 = (0.4, 0.2, 1.0), "
        f"{FREE_TOP_ROTATIONS[study['quick']]} rotations, error against the exact solution; "
        "every ratio is scipy's (or MuJoCo's) time over ours, both measured in this run. "
        "The last row is issue 30's: the same every-decade comparison on the other problems, "
        "where ours run the right-hand side compiled by numba.",
        "",
        "| target | measured | goal | status | detail |",
        "|---|---|---|---|---|",
    ]
    for r in h["targets"]:
        m = r["measured"]
        m = format_value(m, ".3g") if not isinstance(m, str) else m
        lines.append(f"| {r['name']} | {m} | {r['goal']} | **{r['status']}** | {r['detail']} |")
    lines += [
        "",
        "### Every decade: the fastest run of ours and of scipy that reaches the error",
        "",
        "(the fastest sweep point with error ≤ the level; a method between two sweep "
        "points counts at the more accurate one, alike for both sides)",
        "",
        "| error ≤ | ours: method (parameter) | time [s] | scipy: method (rtol) | time [s] "
        "| scipy / ours | status |",
        "|---|---|---|---|---|---|---|",
    ]

    lines += _decade_rows(h["decades"])
    for name, rows in h.get("decades_by_problem", {}).items():
        lines += [
            "",
            f"### Every decade on `{name}` (issue 30): {study['problems'][name]['title']}",
            "",
            "| error ≤ | ours: method (parameter) | time [s] | scipy: method (rtol) | time [s] "
            "| scipy / ours | status |",
            "|---|---|---|---|---|---|---|",
            *_decade_rows(rows),
        ]
    lines += [
        "",
        "### Each of our steppers at scipy DOP853's error "
        + (f"({h['scipy_dop853']['error']:.2e})" if h["scipy_dop853"] else ""),
        "",
    ]
    for m, r in h["per_stepper"].items():
        lines.append(
            f"- {m}: "
            + (
                "does not reach it in this sweep"
                if r is None
                else f"{r['time_s']:.3g} s ({r['param_name']} {r['param']:g}, error "
                f"{r['error']:.2e}), scipy DOP853 / this: {format_value(r['vs_scipy_dop853'], '.3g')}"
            )
        )
    mj = h.get("mujoco")
    if mj and mj.get("available"):
        lines += [
            "",
            f"### The compiled-engine peer: MuJoCo {mj['version']}",
            "",
            f"Torque-free body J = {MUJOCO_J}, ω0 = {MUJOCO_W0}, {MUJOCO_T:g} s; error "
            "max(|Δω_A|/|ω0|, |Δ ^A R^O|) at the end against the exact solution; MuJoCo "
            "timed as one `mj_step(model, data, nstep)` call.",
            "",
            "| run | parameter | error | time [s] |",
            "|---|---|---|---|",
        ]
        for k, v in mj["peers"].items():
            lines.append(f"| {k} | dt = {v['dt']:g} | {v['error']:.2e} | {v['time_s']:.3g} |")
        for v in mj["ours"]:
            lines.append(
                f"| {v['method']} | {v['param_name']} = {v['param']:g} | {v['error']:.2e} | "
                f"{v['time_s']:.3g} |"
            )
    elif mj is not None:
        lines += ["", f"MuJoCo peer: not measured, mujoco is not installed ({mj['install']}).", ""]
    lines += ["", "Goals: " + ", ".join(f"{k}: {v}" for k, v in h["goals"].items()), ""]
    for name, p in study["problems"].items():
        lines += [
            f"## {p['title']} (`{name}`)",
            "",
            f"{p['description']}. Error: {p['error_measure']}. Horizon t = {p['horizon']:.6g}.",
            "",
            "| method | parameter | error | time [s] | steps | rhs evals | rejected |",
            "|---|---|---|---|---|---|---|",
        ]
        for r in p["records"]:
            par = "—" if r["param"] is None else f"{r['param_name']} = {r['param']:g}"
            lines.append(
                f"| {r['method']} | {par} | {r['error']:.2e} | {r['time_s']:.4g} | "
                f"{format_value(r['steps'])} | {format_value(r['rhs_evals'])} | {format_value(r['rejected_steps'])} |"
            )
        for s in p["skipped"]:
            lines.append(f"| {s['method']} | {s['param']} | skipped ({s['reason']}) | | | | |")
        lines.append("")
    ed = study["energy_drift"]
    lines += [
        "## Energy drift (free top, max relative energy error up to each horizon)",
        "",
        "| method | " + " | ".join(f"{n} rot." for n in ed["horizons_rotations"]) + " |",
        "|---|" + "---|" * len(ed["horizons_rotations"]),
    ]
    for name, c in ed["curves"].items():
        lines.append(f"| {name} | " + " | ".join(f"{v:.2e}" for v in c) + " |")
    if "time_s" in ed:
        lines += [
            "",
            "Each run to the longest horizon: "
            + ", ".join(f"{k} {v:.3g} s" for k, v in ed["time_s"].items())
            + ".",
        ]
    b = study["batched"]
    lines += [
        "",
        f"## Batched ({b['bodies']} bodies, {b['steps']} steps)",
        "",
        "| method | one body [s] | batch [s] | batch / one |",
        "|---|---|---|---|",
    ]
    for k in ("rk4", "splitting-4"):
        lines.append(
            f"| {k} | {b[k]['one_body_s']:.4g} | {b[k]['batch_s']:.4g} | "
            f"{b[k]['batch_over_one']:.3g} |"
        )
    bv = study.get("batched_vs_scipy")
    if bv:
        lines += [
            "",
            f"## Batch of {bv['bodies']} free bodies against scipy body by body "
            f"(one rotation, rtol {bv['rtol']:g})",
            "",
            f"Ours (compiled dop853, one common step, {bv['ours_steps']} steps): "
            f"{bv['ours_s']:.4g} s, worst error {bv['worst_error_ours']:.2e}. scipy DOP853: "
            f"{bv['scipy_sample_s']:.4g} s for {bv['scipy_bodies_run']} bodies, "
            f"{bv['scipy_s']:.4g} s scaled to the batch, worst error "
            f"{bv['worst_error_scipy']:.2e}. Ratio {bv['ratio']:.3g}.",
        ]
    ex = study.get("exact_evaluation")
    if ex:
        lines += [
            "",
            f"Exact top at {ex['rotations']} rotations: one `state(t)` "
            f"{1e6 * ex['evaluation_s']:.3g} µs, construction {1e3 * ex['construction_s']:.3g} ms.",
        ]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


_STYLE = {
    "exact": ("k", "*"),
    "rk4": ("C0", "o"),
    "dop853": ("C1", "s"),
    "splitting-2": ("C2", "^"),
    "splitting-4": ("C4", "v"),
    "splitting-6": ("C6", "D"),
    "scipy-RK45": ("C7", "x"),
    "scipy-DOP853": ("C3", "P"),
    "scipy-LSODA": ("C8", "+"),
    "splitting-8": ("C5", "<"),
    "splitting-6-kahan": ("C6", "d"),
    "splitting-8-kahan": ("C5", ">"),
    "scipy-Radau": ("C9", "1"),
}


def write_plots(study: dict, out_dir: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    probs = study["problems"]
    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    for ax, (name, p) in zip(axes.ravel(), probs.items(), strict=False):
        for m in dict.fromkeys(r["method"] for r in p["records"]):
            rs = sorted((r for r in p["records"] if r["method"] == m), key=lambda r: r["time_s"])
            c, mk = _STYLE.get(m, ("C9", "."))
            ax.loglog(
                [r["time_s"] for r in rs],
                [max(r["error"], ERROR_FLOOR) for r in rs],
                color=c,
                marker=mk,
                ls="--" if m.startswith("scipy") else (":" if m.endswith("kahan") else "-"),
                label=m,
            )
        if name == "free_top":
            for e in (DECADES[0], DECADES[-1]):
                ax.axhline(e, color="grey", lw=0.8, ls=":")
        ax.set_title(p["title"], fontsize=10)
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel("error")
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out_dir / "workprecision.png", dpi=90)
    plt.close(fig)

    ed = study["energy_drift"]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for name, c in ed["curves"].items():
        ax.loglog(
            ed["horizons_rotations"], [max(v, ERROR_FLOOR) for v in c], marker="o", label=name
        )
    ax.set_xlabel("horizon [rotations]")
    ax.set_ylabel("max |E/E0 − 1| up to the horizon")
    ax.set_title("Free asymmetric top: energy error against the horizon", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out_dir / "energy_drift.png", dpi=90)
    plt.close(fig)
