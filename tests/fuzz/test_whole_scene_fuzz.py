"""Whole scene files, fuzzed end to end through the CLI (``bodycheck scene``): every
numeric field of every built-in scene over the whole float64 range (and NaN, ±inf,
subnormals, ±0), bodies by the thousand, durations up to 1e300, with the ``--json``,
``--plot`` and ``--method`` variants.

Every run must end in one of two ways:

- a one-line refusal: exit 2, one line on stderr naming the file, nothing on stdout,
  no plot file (not even a partial one);
- a result (exit 0 or 1) with no non-finite number in its JSON and no warning (the
  suite turns warnings into errors), a plot written whole if one was asked for.

Each run is bounded by ``--max-steps`` and ``--max-seconds`` (the budgets of
:mod:`mechanics.scenes.budget`), so the fuzz ends in bounded time.  The example budget is
a quarter of the hypothesis profile's (25 under ``ci``, 250 under ``explore``).
"""

from __future__ import annotations

import copy
import json
import math
import tomllib

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from identities.cli.main import main
from mechanics.scenes import builtin_scenes
from mechanics.scenes.domain import MAGNITUDE_MAX
from mechanics.scenes.spec import METHODS

RAW = {n: tomllib.loads(p.read_text(encoding="utf-8")) for n, p in builtin_scenes().items()}
#: each run's bounds: enough for every built-in scene (≤ 1443 steps, a few seconds)
RUN_BOUNDS = ["--max-steps", "4000", "--max-seconds", "20"]
EXAMPLES = max(settings.default.max_examples // 4, 10)
PNG_START, PNG_END = b"\x89PNG\r\n\x1a\n", b"IEND\xaeB`\x82"

#: the extremes every numeric field is tried at, besides draws over the whole range
EXTREMES = [
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    2.2250738585072014e-308,
    1e-300,
    2.0**-80,
    MAGNITUDE_MAX,
    MAGNITUDE_MAX * 2,
    1e154,
    -1e154,
    1e300,
    -1e300,
    1.7976931348623157e308,
    math.inf,
    -math.inf,
    math.nan,
]
VALUES = st.one_of(st.sampled_from(EXTREMES), st.floats(allow_nan=True, allow_infinity=True))


def _numeric_paths(data, prefix=()):
    """Paths to every number (not a bool) of a scene dict, list items included."""
    if isinstance(data, dict):
        for k, v in data.items():
            yield from _numeric_paths(v, (*prefix, k))
    elif isinstance(data, list):
        for i, v in enumerate(data):
            yield from _numeric_paths(v, (*prefix, i))
    elif isinstance(data, int | float) and not isinstance(data, bool):
        yield prefix


def _set(data, path, value):
    for key in path[:-1]:
        data = data[key]
    data[path[-1]] = value


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(type(v))


def to_toml(data: dict) -> str:
    """A scene dict as TOML: tables, arrays of tables, inline tables for deeper ones."""
    out = []
    for key, value in data.items():
        if isinstance(value, dict):
            out += [f"[{key}]", *(f"{k} = {_toml_value(v)}" for k, v in value.items()), ""]
        else:  # bodies, effects: arrays of tables
            for item in value:
                out += [f"[[{key}]]", *(f"{k} = {_toml_value(v)}" for k, v in item.items()), ""]
    return "\n".join(out)


def test_the_toml_writer_round_trips_every_built_in_scene():
    for name, data in RAW.items():
        assert tomllib.loads(to_toml(data)) == data, name


@st.composite
def hostile_scenes(draw):
    """A built-in scene with one to three numbers replaced by extremes."""
    name = draw(st.sampled_from(sorted(RAW)))
    data = copy.deepcopy(RAW[name])
    data["scene"]["samples"] = draw(st.integers(2, 41))  # bounded, unless drawn below
    paths = sorted(_numeric_paths(data), key=str)
    for path in draw(st.lists(st.sampled_from(paths), min_size=1, max_size=3, unique=True)):
        _set(data, path, draw(VALUES))
    return name, data


@st.composite
def crowds(draw):
    """Up to 3000 points under gravity on a grid (no two closer than 1 m), a duration up
    to 1e300."""
    n = draw(st.integers(1, 3000))
    side = math.ceil(n ** (1 / 3))
    speed = draw(st.sampled_from([0.0, 1.0, 1e10, MAGNITUDE_MAX]))
    bodies = [
        {
            "name": f"p{i}",
            "shape": "point",
            "mass": 1.0,
            "initial": {
                "position": [float(i % side), float(i // side % side), float(i // side**2)],
                "velocity": [speed, 0.0, 0.0],
            },
        }
        for i in range(n)
    ]
    duration = draw(st.sampled_from([1e-3, 1.0, 1e6, MAGNITUDE_MAX, 1e300]))
    samples = draw(st.integers(2, 21))
    return "crowd", {
        "scene": {"name": "crowd", "duration": duration, "samples": samples},
        "bodies": bodies,
        "effects": [{"type": "gravity", "g": 9.81}],
    }


VARIANTS = st.sampled_from(
    [(), ("--json",), ("--plot",), *(("--method", m) for m in METHODS), ("--json", "--plot")]
)


def _non_finite(x, where="") -> str | None:
    if isinstance(x, dict):
        return next((w for k, v in x.items() if (w := _non_finite(v, f"{where}.{k}"))), None)
    if isinstance(x, list):
        return next((w for i, v in enumerate(x) if (w := _non_finite(v, f"{where}[{i}]"))), None)
    if isinstance(x, float) and not math.isfinite(x):
        return where
    if x in ("nan", "inf", "-inf"):
        return where
    return None


def _run_one(tmp_path, capsys, case, variant) -> None:
    name, data = case
    scene = tmp_path / "fuzz.toml"
    scene.write_text(to_toml(data), encoding="utf-8")
    plot = tmp_path / "fuzz.png"
    plot.unlink(missing_ok=True)
    args = ["scene", str(scene), *RUN_BOUNDS]
    for v in variant:
        args += [v, str(plot)] if v == "--plot" else [v]
    code = main(args)
    out, err = capsys.readouterr()
    leftovers = [p.name for p in tmp_path.iterdir() if p.name.endswith(".part")]
    assert not leftovers, f"{name}: a partial output file was left: {leftovers}"
    if code == 2:
        lines = err.strip().splitlines()
        assert len(lines) == 1, f"{name}: a refusal of more than one line:\n{err}"
        assert lines[0].startswith(f"bodycheck: error: {scene}: "), lines[0]
        assert out == "", f"{name}: a refusal printed a result too"
        assert not plot.exists(), f"{name}: a refused run wrote a plot"
        return
    assert code in (0, 1), (name, code, err)
    if "--json" in variant:
        record = json.loads(out)
        where = _non_finite(record)
        assert where is None, f"{name}: a non-finite number at {where} (passed={record['passed']})"
    else:
        verdict = "\nPASSED\n" if code == 0 else "\nFAILED\n"
        assert verdict in out, out[-300:]
        assert "nan" not in out.lower().split(), out
        assert " inf" not in out, out
    if "--plot" in variant:
        blob = plot.read_bytes()
        assert blob.startswith(PNG_START), f"{name}: not a PNG"
        assert blob.endswith(PNG_END), f"{name}: a partial plot"


SETTINGS = settings(
    max_examples=EXAMPLES,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
    deadline=None,
)


@SETTINGS
@given(case=hostile_scenes(), variant=VARIANTS)
def test_a_hostile_scene_file_ends_in_a_refusal_or_a_finite_result(tmp_path, capsys, case, variant):
    _run_one(tmp_path, capsys, case, variant)


@settings(SETTINGS, max_examples=max(EXAMPLES // 5, 4))
@given(case=crowds(), variant=st.sampled_from([(), ("--json",)]))
def test_thousands_of_bodies_end_in_a_refusal_or_a_finite_result(tmp_path, capsys, case, variant):
    _run_one(tmp_path, capsys, case, variant)
