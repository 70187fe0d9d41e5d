"""Every public strategy validates its arguments, keeps its defaults and labels its regimes.

Across :mod:`mechanics.strategies`: a bad argument raises
:class:`hypothesis.errors.InvalidArgument` whose message names the argument as a word of
its own (``max_ratio=``, not ``XXmax_ratioXX=`` or ``MAX_RATIO=``), quotes the value and
states the violated condition; an unknown regime names the strategy that refused it;
equal lower and upper bounds are accepted (the interval is closed); the documented
defaults hold (the widest draw reaches them and never passes them); each strategy
records ``"<strategy>: <regime>"`` with :func:`hypothesis.event` for exactly its
documented regimes.  Every strategy is built inside its test, so that the test is the
one that calls the factory.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from hypothesis import Phase, find, settings
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument, NoSuchExample

from mechanics import strategies as ms
from mechanics._floats import EPS
from mechanics.strategies import _common, batching, impact, inertia, particles
from tests.strategies.sampling import drawn_from, found, never, shared

#: Draws for a search that must find (or must not find) a value: regimes are branches
#: among at most eight, so every branch is drawn dozens of times in 1000 draws.
FIND_SETTINGS = settings(max_examples=1000, database=None, phases=[Phase.generate])
#: the far ends of a log-uniform exponent band (J3 within a factor 2 of 1e±100 when the
#: exponent is drawn in [20, 100]) are under 1 % of the regime's draws: 1000 draws found
#: none once on Python 3.13 (make test-matrix); 10^4 leave a miss probability below e^-50,
#: as test_inertia_strategy_quality's joint budget does for the same bands
FIND_SETTINGS_FAR = settings(FIND_SETTINGS, max_examples=10**4)

#: Draws for collecting the event labels: each label is met within a few dozen draws.
EVENT_SETTINGS = settings(max_examples=300, database=None, phases=[Phase.generate])

#: What a drawn value shrinks to.
SHRINK_SETTINGS = settings(max_examples=200, database=None)


R2 = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])


def _factory(name):
    """The strategy factory ``name``; ``pair_forces`` is given two particles first."""
    f = getattr(ms, name)
    if name == "pair_forces":
        return lambda **kw: f(R2, **kw)
    return f


def _never(strategy, predicate) -> None:
    """No draw among FIND_SETTINGS' satisfies ``predicate``."""
    never(strategy, predicate, FIND_SETTINGS.max_examples)


def _found(strategy, predicate, budget=FIND_SETTINGS):
    return found(strategy, predicate, budget.max_examples)


def _tensors():
    """Inertia tensors for a rigid body whose mass or position is what a test asks
    about: picked among the first draws of the default :func:`ms.inertia_tensors`
    (``drawn_from``; the shared sample the regime tests of ``inertia_tensors`` read).
    ``rigid_bodies`` draws its mass first and from its own strategy, and J_G is the
    drawn tensor itself, so the masses drawn are those of the default tensors; a tensor
    costs 2 of the ~4 ms a body takes to draw (hypothesis' rotation and moments), one
    choice when picked."""
    return drawn_from(ms.inertia_tensors())


def _impact_tensors():
    """:func:`_tensors` for ``impact_bodies``: picked among the default
    :func:`ms.impact_inertia_tensors`' first draws (J_G = m J, the mass drawn apart)."""
    return drawn_from(ms.impact_inertia_tensors())


# --------------------------------------------------------- numeric arguments

#: (strategy, argument, kind): kind "real" is any finite real, "positive" a finite
#: real > 0 (check_positive), "int" an integer with a minimum.
NUMERIC_ARGUMENTS = [
    ("impact_masses", "min_value", "real"),
    ("impact_masses", "max_value", "real"),
    ("mass_pairs", "max_ratio", "real"),
    ("direct_velocities", "max_speed", "real"),
    ("impact_bodies", "max_position", "real"),
    ("impact_bodies", "max_speed", "real"),
    ("principal_moments", "min_scale", "positive"),
    ("principal_moments", "max_scale", "positive"),
    ("rigid_bodies", "min_mass", "positive"),
    ("rigid_bodies", "max_mass", "positive"),
    ("masses", "min_value", "real"),
    ("masses", "max_value", "real"),
    ("masses", "min_particles", "int"),
    ("masses", "max_particles", "int"),
    ("particle_systems", "min_mass", "real"),
    ("particle_systems", "max_mass", "real"),
    ("particle_systems", "min_particles", "int"),
    ("particle_systems", "max_particles", "int"),
    ("pair_forces", "max_magnitude", "real"),
    ("rotation_angles", "min_value", "real"),
    ("rotation_angles", "max_value", "real"),
]


def _bad_numeric_cases():
    for name, arg, kind in NUMERIC_ARGUMENTS:
        tag = f"{name}-{arg}"
        if kind == "int":
            yield pytest.param(name, arg, 2.5, r"=2\.5 must be an integer", id=f"{tag}-float")
            yield pytest.param(name, arg, True, r"=True must be an integer", id=f"{tag}-bool")
            yield pytest.param(name, arg, 0, r"=0 must be >= 1", id=f"{tag}-zero")
            continue
        yield pytest.param(name, arg, "3", r"='3' must be a real number", id=f"{tag}-str")
        yield pytest.param(name, arg, None, r"=None must be a real number", id=f"{tag}-none")
        yield pytest.param(name, arg, True, r"=True must be a real number", id=f"{tag}-bool")
        yield pytest.param(name, arg, math.nan, r"=nan must be finite", id=f"{tag}-nan")
        yield pytest.param(name, arg, -math.inf, r"=-inf must be finite", id=f"{tag}-inf")
        if kind == "positive":
            yield pytest.param(name, arg, -1.0, r"=-1\.0 must be finite and > 0", id=f"{tag}-neg")
            yield pytest.param(name, arg, 0.0, r"=0\.0 must be finite and > 0", id=f"{tag}-zero")


@pytest.mark.parametrize(("name", "arg", "value", "condition"), list(_bad_numeric_cases()))
def test_a_bad_numeric_argument_is_refused_naming_it_and_the_condition(name, arg, value, condition):
    with pytest.raises(InvalidArgument, match=rf"(?<![\w.]){arg}{condition}"):
        _factory(name)(**{arg: value})


#: Custom conditions, each strategy's own: (strategy, kwargs, message pattern).
CONDITIONS = [
    ("impact_masses", {"min_value": 0.0}, r"\bmin_value=0\.0 must be > 0"),
    ("impact_masses", {"min_value": -2.0}, r"\bmin_value=-2\.0 must be > 0"),
    (
        "impact_masses",
        {"min_value": 3.0, "max_value": 2.0},
        r"\bmin_value=3\.0 exceeds max_value=2\.0",
    ),
    (
        "impact_masses",
        {"min_value": 2.0, "max_value": 3.0, "regimes": ["unit", "tiny"]},
        r"regimes=\['unit', 'tiny'\]: none reachable in \[2\.0, 3\.0\]",
    ),
    ("mass_pairs", {"max_ratio": 999_999.0}, r"\bmax_ratio=999999\.0 must be >= 1e6"),
    ("direct_velocities", {"max_speed": 0.999}, r"\bmax_speed=0\.999 must be >= 1"),
    (
        "impact_inertia_tensors",
        {"rotations": 3.0},
        r"\brotations=3\.0 must be a hypothesis strategy",
    ),
    ("contacts", {"restitution": 0.5}, r"\brestitution=0\.5 must be a hypothesis strategy"),
    (
        "principal_moments",
        {"min_scale": 2.0, "max_scale": 1.0},
        r"\bmin_scale=2\.0 exceeds max_scale=1\.0",
    ),
    (
        "rigid_bodies",
        {"min_mass": 2.0, "max_mass": 1.0},
        r"\bmin_mass=2\.0 exceeds max_mass=1\.0",
    ),
    ("rigid_bodies", {"tensors": 1.0}, r"\btensors=1\.0 must be a hypothesis strategy"),
    ("inertia_tensors", {"moments": 1.0}, r"\bmoments=1\.0 must be a hypothesis strategy"),
    ("inertia_tensors", {"rotations": 1.0}, r"\brotations=1\.0 must be a hypothesis strategy"),
    ("masses", {"min_value": 0.0}, r"\bmin_value=0\.0 must be > 0 \(masses are drawn positive"),
    ("masses", {"min_value": 3.0, "max_value": 2.0}, r"\bmin_value=3\.0 exceeds max_value=2\.0"),
    (
        "masses",
        {"min_particles": 3, "max_particles": 2},
        r"\bmin_particles=3 exceeds max_particles=2",
    ),
    (
        "masses",
        {"min_value": 2.0, "max_value": 3.0, "regimes": ["unit"]},
        r"regimes=\['unit'\]: 'unit' needs 1\.0 in \[2\.0, 3\.0\]",
    ),
    ("particle_systems", {"min_mass": 0.0}, r"\bmin_mass=0\.0 must be > 0 \(masses are drawn"),
    (
        "particle_systems",
        {"min_mass": 3.0, "max_mass": 2.0},
        r"\bmin_mass=3\.0 exceeds max_mass=2\.0",
    ),
    (
        "particle_systems",
        {"min_particles": 3, "max_particles": 2},
        r"\bmin_particles=3 exceeds max_particles=2",
    ),
    ("pair_forces", {"max_magnitude": 0.0}, r"\bmax_magnitude=0\.0 must be > 0"),
    ("pair_forces", {"max_magnitude": -1.0}, r"\bmax_magnitude=-1\.0 must be > 0"),
    ("rotvecs", {"axes": 1.0}, r"\baxes=1\.0 must be a hypothesis strategy"),
    ("rotvecs", {"angles": 1.0}, r"\bangles=1\.0 must be a hypothesis strategy"),
    ("rotation_angles", {"min_value": -0.5}, r"\bmin_value=-0\.5 must be >= 0"),
    ("rotation_angles", {"max_value": 4.0}, r"\bmax_value=4\.0 must be <= math\.pi"),
    (
        "rotation_angles",
        {"min_value": 2.0, "max_value": 1.0},
        r"\bmin_value=2\.0 exceeds max_value=1\.0",
    ),
]


@pytest.mark.parametrize(
    ("name", "kwargs", "pattern"),
    [pytest.param(*c, id=f"{c[0]}-{'-'.join(c[1])}") for c in CONDITIONS],
)
def test_each_strategy_refuses_its_own_bad_arguments_naming_value_and_condition(
    name, kwargs, pattern
):
    with pytest.raises(InvalidArgument, match=pattern):
        _factory(name)(**kwargs)


@pytest.mark.parametrize(
    ("r", "pattern"),
    [
        pytest.param(
            np.zeros((2, 2)), r"r with shape \(2, 2\) must be \(N, 3\) with N >= 1", id="2x2"
        ),
        pytest.param(
            np.zeros((0, 3)), r"r with shape \(0, 3\) must be \(N, 3\) with N >= 1", id="0x3"
        ),
        pytest.param(np.zeros(3), r"r with shape \(3,\) must be \(N, 3\)", id="flat"),
        pytest.param([[0.0, math.nan, 0.0]], r"r=\[\[0\.0, nan, 0\.0\]\] must be finite", id="nan"),
    ],
)
def test_pair_forces_refuse_bad_positions_naming_r(r, pattern):
    with pytest.raises(InvalidArgument, match=pattern):
        ms.pair_forces(r)


@pytest.mark.parametrize(
    ("kwargs", "pattern"),
    [
        pytest.param({"max_rows": 3}, r"\bmax_rows=3 must be >= 4", id="three"),
        pytest.param({"max_rows": 4.0}, r"\bmax_rows=4\.0 must be an integer", id="float"),
        pytest.param({"max_rows": "6"}, r"\bmax_rows='6' must be an integer", id="str"),
    ],
)
def test_batches_refuse_a_bad_max_rows_naming_it(kwargs, pattern):
    with pytest.raises(InvalidArgument, match=pattern):
        ms.batches(ms.unit_vectors(), **kwargs)


def test_batches_refuse_elements_that_are_not_a_strategy_naming_them():
    with pytest.raises(InvalidArgument, match=r"\belements=\[1\.0\] must be a hypothesis strategy"):
        ms.batches([1.0])


def test_batches_refuse_elements_of_different_shapes_when_drawn():
    ragged = st.sampled_from((np.zeros(2), np.zeros(3)))
    with pytest.raises(InvalidArgument, match=r"\belements=.* drew arrays of different shapes"):
        find(ms.batches(ragged), lambda b: False, settings=FIND_SETTINGS)


# ------------------------------------------------------------------ regimes

#: Every strategy that takes ``regimes``, with its documented tuple.
REGIME_TABLES = [
    ("impact_masses", ms.IMPACT_MASS_REGIMES),
    ("mass_pairs", ms.MASS_PAIR_REGIMES),
    ("restitution_coefficients", ms.RESTITUTION_REGIMES),
    ("direct_velocities", ms.DIRECT_VELOCITY_REGIMES),
    ("impact_inertia_tensors", ms.IMPACT_INERTIA_REGIMES),
    ("contacts", ms.CONTACT_REGIMES),
    ("hinged_bodies", ms.HINGED_REGIMES),
    ("principal_moments", ms.PRINCIPAL_MOMENT_REGIMES),
    ("rigid_bodies", ms.CENTRE_REGIMES),
    ("masses", ms.MASS_REGIMES),
    ("particle_systems", ms.SYSTEM_REGIMES),
    ("pair_forces", ms.PAIR_FORCE_REGIMES),
    ("rotation_angles", ms.ANGLE_REGIMES),
    ("rotvecs", ms.ROTVEC_REGIMES),
    ("euler_angles", ms.EULER_REGIMES),
]


@pytest.mark.parametrize(("name", "allowed"), REGIME_TABLES, ids=[t[0] for t in REGIME_TABLES])
def test_an_unknown_regime_is_refused_naming_the_strategy_and_its_regimes(name, allowed):
    pattern = rf"regimes=\['nope'\]: unknown \['nope'\]; {name} has {re.escape(repr(allowed))}"
    with pytest.raises(InvalidArgument, match=pattern):
        _factory(name)(regimes=["nope"])


@pytest.mark.parametrize(("name", "allowed"), REGIME_TABLES, ids=[t[0] for t in REGIME_TABLES])
def test_regimes_given_as_one_string_or_none_at_all_are_refused(name, allowed):
    with pytest.raises(InvalidArgument, match=r"regimes='x' must be a collection of names, not a"):
        _factory(name)(regimes="x")
    with pytest.raises(
        InvalidArgument, match=rf"regimes=\[\] is empty; choose from {re.escape(repr(allowed))}"
    ):
        _factory(name)(regimes=[])


#: (module, strategy, documented regimes, the regimes drawn by default): every label
#: recorded is "<strategy>: <regime>" for a documented regime, and all are recorded.
EVENT_TABLES = [
    (impact, "impact_masses", ms.IMPACT_MASS_REGIMES),
    (impact, "mass_pairs", ms.MASS_PAIR_REGIMES),
    (impact, "restitution_coefficients", ms.RESTITUTION_REGIMES),
    (impact, "direct_velocities", ms.DIRECT_VELOCITY_REGIMES),
    (impact, "impact_inertia_tensors", ms.IMPACT_INERTIA_REGIMES),
    (impact, "contacts", ms.CONTACT_REGIMES),
    (impact, "hinged_bodies", ms.HINGED_REGIMES),
    (inertia, "principal_moments", ms.PRINCIPAL_MOMENT_REGIMES),
    (inertia, "rigid_bodies", ms.CENTRE_REGIMES),
    (particles, "masses", ms.MASS_REGIMES),
    (particles, "particle_systems", ms.SYSTEM_REGIMES),
    (particles, "pair_forces", ms.PAIR_FORCE_REGIMES),
    (batching, "batches", ms.BATCH_REGIMES),
]


@pytest.mark.parametrize(
    ("module", "name", "regimes"), EVENT_TABLES, ids=[t[1] for t in EVENT_TABLES]
)
def test_each_strategy_records_exactly_its_documented_regimes_as_events(
    module, name, regimes, monkeypatch
):
    labels: list[str] = []
    monkeypatch.setattr(module, "event", labels.append)
    strategy = ms.batches(ms.unit_vectors()) if name == "batches" else shared(_factory(name))
    with pytest.raises(NoSuchExample):
        find(strategy, lambda x: False, settings=EVENT_SETTINGS)
    recorded = {label for label in labels if label.startswith(f"{name}: ")}
    assert recorded == {f"{name}: {r}" for r in regimes}


# ------------------------------------------------------------- closed bounds


@pytest.mark.parametrize(
    ("name", "kwargs", "value_of"),
    [
        pytest.param("impact_masses", {"min_value": 5.0, "max_value": 5.0}, float, id="impact"),
        pytest.param(
            "principal_moments",
            {"min_scale": 5.0, "max_scale": 5.0, "regimes": ["equal"]},
            lambda J: J[2],
            id="moments",
        ),
        pytest.param(
            "rigid_bodies",
            {"min_mass": 5.0, "max_mass": 5.0, "tensors": _tensors},
            lambda b: b.m,
            id="rb",
        ),
        pytest.param("masses", {"min_value": 5.0, "max_value": 5.0}, lambda m: m.max(), id="m"),
        pytest.param(
            "particle_systems", {"min_mass": 5.0, "max_mass": 5.0}, lambda s: s.m.max(), id="ps"
        ),
    ],
)
def test_equal_lower_and_upper_bounds_are_accepted_and_drawn(name, kwargs, value_of):
    """Every draw is at the one bound.  A rigid body's tensor, which its mass never
    depends on, is picked among drawn ones (:func:`_tensors`, given as a function so that
    it is drawn when the test runs): the masses are drawn as with the default tensors,
    at under half the cost."""
    kwargs = {k: v() if callable(v) else v for k, v in kwargs.items()}
    strategy = _factory(name)(**kwargs)
    _never(strategy, lambda x: value_of(x) != 5.0)


@pytest.mark.parametrize("name", ["masses", "particle_systems"])
def test_equal_particle_counts_are_accepted_and_drawn(name):
    strategy = _factory(name)(min_particles=3, max_particles=3)
    _never(strategy, lambda x: len(x if name == "masses" else x.m) != 3)


@pytest.mark.parametrize("max_rows", [4, 5, 6, 9])
def test_batches_take_max_rows_from_four_and_never_exceed_it(max_rows):
    strategy = ms.batches(st.just(0.0), max_rows=max_rows)
    _found(strategy, lambda b: b.size == max_rows)
    _found(strategy, lambda b: b.shape == (2, 2))
    _never(strategy, lambda b: b.size > max_rows)


# ----------------------------------------------------------------- defaults


def test_batches_default_to_at_most_six_rows():
    strategy = ms.batches(st.just(0.0))
    _found(strategy, lambda b: b.shape == (6,))
    _found(strategy, lambda b: b.shape in ((2, 3), (3, 2)))
    _never(strategy, lambda b: b.size > 6)


def test_batches_shrink_to_one_row():
    b = find(ms.batches(ms.unit_vectors()), lambda b: True, settings=SHRINK_SETTINGS)
    assert b.shape == (1, 3)


@pytest.mark.parametrize("name", ["masses", "particle_systems"])
def test_particle_counts_default_to_one_through_fifty(name):
    strategy = shared(_factory(name))
    size = len if name == "masses" else (lambda s: len(s.m))
    _found(strategy, lambda x: size(x) == 1)
    _found(strategy, lambda x: size(x) == 50)
    _never(strategy, lambda x: not 1 <= size(x) <= 50)


def test_masses_shrink_to_one_unit_mass():
    m = find(ms.masses(), lambda m: True, settings=SHRINK_SETTINGS)
    assert m.tolist() == [1.0]


@pytest.mark.parametrize("name", ["masses", "particle_systems"])
def test_particle_masses_default_to_1e_minus_6_through_1e6(name):
    strategy = shared(_factory(name))
    mass = (lambda m: m) if name == "masses" else (lambda s: s.m)
    _found(strategy, lambda x: mass(x).min() == 1e-6)
    _found(strategy, lambda x: mass(x).max() == 1e6)
    _never(strategy, lambda x: not np.all((mass(x) >= 1e-6) & (mass(x) <= 1e6)))


def test_impact_masses_default_to_1e_minus_15_through_1e15():
    strategy = shared(ms.impact_masses)
    _found(strategy, lambda m: m <= 1e-14)
    _found(strategy, lambda m: m >= 1e14)
    _never(strategy, lambda m: not 1e-15 <= m <= 1e15)


def test_mass_pairs_default_to_a_ratio_of_at_most_1e15():
    strategy = shared(ms.mass_pairs)
    _never(strategy, lambda p: not 1e-15 * (1 - 1e-15) <= p[0] / p[1] <= 1e15 * (1 + 1e-15))


def test_direct_velocities_default_to_speeds_up_to_1e6():
    strategy = shared(ms.direct_velocities)
    _found(strategy, lambda v: max(abs(v[0]), abs(v[1])) >= 1e5)
    _never(strategy, lambda v: max(abs(v[0]), abs(v[1])) > 1e6)


def test_impact_bodies_default_to_masses_1e_minus_6_through_1e6_within_ten():
    """The masses, positions and speeds of the defaults: their bounds are reached and
    never passed.  The tensor, not asked about (J_G is the mass times it, the mass
    drawn apart), is picked among drawn ones (:func:`_impact_tensors`); every argument
    this test is about keeps its default."""
    strategy = ms.impact_bodies(tensors=_impact_tensors())
    _found(strategy, lambda b: b.m <= 1e-5)
    _found(strategy, lambda b: b.m >= 1e5)
    _found(strategy, lambda b: np.abs(b.r_G).max() >= 9.0)
    _found(strategy, lambda b: np.abs(b.v_G).max() >= 9.0)
    _found(strategy, lambda b: np.abs(b.omega).max() >= 9.0)
    _never(
        strategy,
        lambda b: (
            not 1e-6 <= b.m <= 1e6
            or max(np.abs(b.r_G).max(), np.abs(b.v_G).max(), np.abs(b.omega).max()) > 10.0
        ),
    )


def test_impact_bodies_keep_positions_and_speeds_within_their_bounds():
    """r_G, v_G and ω stay within the bounds given, and reach them.  They are drawn
    apart from the mass and the tensor (``impact_bodies`` is ``st.builds`` of the five),
    which are picked among draws of their default strategies (:func:`_impact_tensors`):
    the same positions and speeds, at half the cost of drawing a whole body."""
    strategy = ms.impact_bodies(
        masses_=drawn_from(ms.impact_masses(min_value=1e-6, max_value=1e6)),
        tensors=_impact_tensors(),
        max_position=0.5,
        max_speed=0.25,
    )
    _found(strategy, lambda b: np.abs(b.r_G).max() >= 0.45)
    _found(strategy, lambda b: np.abs(b.v_G).max() >= 0.2)
    _never(
        strategy,
        lambda b: (
            np.abs(b.r_G).max() > 0.5 or max(np.abs(b.v_G).max(), np.abs(b.omega).max()) > 0.25
        ),
    )


def test_impact_bodies_take_the_mass_and_tensor_strategies_given():
    strategy = ms.impact_bodies(masses_=st.just(2.0), tensors=st.just(np.diag([1.0, 2.0, 2.5])))
    body = find(strategy, lambda b: True, settings=SHRINK_SETTINGS)
    assert body.m == 2.0
    assert body.J_G.tolist() == np.diag([2.0, 4.0, 5.0]).tolist()  # J_G = m J


def test_rigid_bodies_default_to_masses_1e_minus_3_through_1e3():
    """The default mass bounds are reached and never passed; the tensor, which the mass
    never depends on, is picked among drawn ones (:func:`_tensors`)."""
    strategy = ms.rigid_bodies(tensors=_tensors())
    _found(strategy, lambda b: b.m <= 2e-3)
    _found(strategy, lambda b: b.m >= 5e2)
    _never(strategy, lambda b: not 1e-3 <= b.m <= 1e3)


def test_principal_moments_default_to_scales_1e_minus_100_through_1e100():
    # J3 is within a factor 2 of the drawn scale (the docstring's "up to a factor 2").
    strategy = ms.principal_moments(regimes=["wide-scales"])
    _found(strategy, lambda J: J[2] >= 1e99, FIND_SETTINGS_FAR)
    _found(strategy, lambda J: J[2] <= 1e-99, FIND_SETTINGS_FAR)
    _never(strategy, lambda J: not 0.5e-100 <= J[2] <= 2e100)


def test_pair_forces_default_to_a_magnitude_of_at_most_1e3():
    strategy = ms.pair_forces(R2)
    _found(strategy, lambda f: np.linalg.norm(f, axis=-1).max() >= 1e2)
    _never(strategy, lambda f: np.linalg.norm(f, axis=-1).max() > 1e3)


# ------------------------------------------------------------ log_uniform


def test_log_uniform_refuses_a_shrink_direction_other_than_lo_or_hi():
    for bad in (None, "HI", "low", "XXhiXX"):
        with pytest.raises(
            ValueError, match=rf"shrink_to={re.escape(repr(bad))} must be 'lo' or 'hi'"
        ):
            _common.log_uniform(1.0, 2.0, shrink_to=bad)


@pytest.mark.parametrize(("shrink_to", "end"), [("lo", 1e-3), ("hi", 1e3)])
def test_log_uniform_shrinks_to_the_end_it_is_told(shrink_to, end):
    x = find(_common.log_uniform(1e-3, 1e3, shrink_to=shrink_to), lambda x: True)
    assert x == end


@pytest.mark.parametrize(
    ("name", "kwargs", "holds"),
    [
        pytest.param(
            "mass_pairs",
            {"max_ratio": 1e6, "regimes": ["heavy-1"]},
            lambda p: p[0] / p[1] == pytest.approx(1e6, rel=4 * EPS),
            id="max_ratio-1e6",
        ),
        pytest.param(
            "direct_velocities",
            {"max_speed": 1.0},
            lambda v: max(abs(v[0]), abs(v[1])) <= 1.0,
            id="max_speed-1",
        ),
        pytest.param("masses", {"min_particles": 1, "max_particles": 1}, lambda m: len(m) == 1),
        pytest.param("pair_forces", {"max_magnitude": 1e-300}, lambda f: np.abs(f).max() <= 1e-300),
    ],
)
def test_the_smallest_allowed_bound_is_accepted_and_kept(name, kwargs, holds):
    strategy = _factory(name)(**kwargs)
    _never(strategy, lambda x: not holds(x))


def test_a_factory_keeps_one_strategy_per_distinct_plain_arguments():
    """``_common.memoised``: the same plain arguments give the same object (building one
    parses each composite's source, milliseconds); arguments a factory could tell apart
    never share one: -0.0 and 0.0, 1 and 1.0, a list and a tuple; a strategy or an array
    as an argument builds afresh; a refused call is refused again."""
    assert ms.rotation_matrices() is ms.rotation_matrices()
    assert ms.masses(min_value=1e-3, max_value=2.0) is ms.masses(min_value=1e-3, max_value=2.0)
    assert ms.rotvecs(regimes=["huge"]) is ms.rotvecs(regimes=["huge"])
    assert ms.rotvecs(regimes=["huge"]) is not ms.rotvecs(regimes=("huge",))
    assert ms.rotation_angles(min_value=-0.0) is not ms.rotation_angles(min_value=0.0)
    assert ms.masses(max_value=2) is not ms.masses(max_value=2.0)
    e = st.just(0.5)
    assert ms.contacts(restitution=e) is not ms.contacts(restitution=e)
    r = np.zeros((2, 3))
    assert ms.pair_forces(r) is not ms.pair_forces(r)
    for _ in range(2):
        with pytest.raises(InvalidArgument, match=re.escape("min_value=-1.0")):
            ms.masses(min_value=-1.0)
