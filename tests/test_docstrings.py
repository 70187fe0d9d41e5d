"""Every public callable's docstring, checked like code (issue 34, item 2).

The surface is the fuzz suite's (:func:`tests.fuzz.surface.public_callables`: every
callable in the ``__all__`` of a public module of :mod:`mechanics`), so a new public
name is checked at once.  Each docstring must pass

- numpydoc's own validation (:func:`numpydoc.validate.validate`), for the checks in
  :data:`NUMPYDOC`: a docstring, a summary of one line, every parameter documented with
  a type and a description and none that is not a parameter, a ``Returns`` section where
  a value is returned, an ``Examples`` section (its examples run as doctests:
  ``--doctest-modules`` in pyproject);
- and the library's own rules (:func:`own_errors`): a callable that takes arguments has a
  ``Raises`` section; every exception it names is one (of the library or a builtin);
  every error the ``Domain:`` paragraph names (the fuzz suite's contract: "else
  ShapeError") is in it; a parameter or return value typed ``array_like`` or ``ndarray``
  states its shape (``array_like, shape (..., 3)``).

A failure names the callable, the check and numpydoc's message.  An exemption names the
callable, the check and its reason (:data:`EXEMPT`).  To list what fails under some modules:
``python -m tests.test_docstrings mechanics.rotation mechanics.scenes.effects``.
"""

from __future__ import annotations

import builtins
import importlib
import inspect
import re

import pytest

from tests.fuzz.surface import public_callables

validate = pytest.importorskip(
    "numpydoc.validate", reason="numpydoc is missing: pip install 'bodycheck[test]'"
)

#: numpydoc's checks every public callable passes (codes of numpydoc.validate.ERROR_MSGS)
NUMPYDOC = {
    "GL08": "a docstring",
    "SS01": "a summary",
    "SS06": "a summary of one line",
    "PR01": "every parameter documented",
    "PR02": "no parameter documented that the signature does not have",
    "PR04": "every parameter with a type",
    "PR07": "every parameter with a description",
    "RT01": "a Returns section where a value is returned",
    "EX01": "an Examples section",
}

#: (callable, check) → why it is exempt
EXEMPT: dict[tuple[str, str], str] = {
    ("mechanics.particles.Cylindrical", "BC01"): "a NamedTuple of the coordinates: its "
    "constructor checks nothing and raises nothing of its own",
    **{
        (f"mechanics.{record}", "BC01"): "a result record (NamedTuple or frozen dataclass) "
        "that a function returns: its constructor checks nothing and raises nothing of its own"
        for record in (
            "impact.RigidImpact",
            "impact.HingedImpact",
            "impact.CentreOfPercussion",
            "tops.StabilityResult",
        )
    },
    **{
        (f"mechanics.{record}", "BC01"): "a record or a container (a dataclass, a NamedTuple, "
        "a class that keeps its options): its constructor stores what it is given, checks "
        "nothing and raises nothing of its own"
        for record in (
            "conformance.battery.Figure",
            "conformance.battery.Report",
            "conformance.battery.Run",
            "conformance.battery.ScenarioResult",
            "conformance.compare.Comparison",
            "conformance.protocol.Body",
            "conformance.protocol.Event",
            "conformance.protocol.Pivot",
            "conformance.protocol.Scenario",
            "conformance.protocol.Shape",
            "conformance.protocol.Thrust",
            "conformance.protocol.Trajectory",
            "conformance.scenarios.Reference",
            "conformance.thresholds.Config",
            "conformance.thresholds.Profile",
            "integrators.Solution",
            "scenes.effects.base.Context",
            "scenes.effects.base.Effect",
            "scenes.effects.base.Snapshot",
            "scenes.effects.coulomb_friction.Slide",
            "scenes.effects.rolling.Incline",
            "scenes.effects.rolling.Track",
            "strategies.impact.Contact",
            "strategies.impact.HingedBody",
            "strategies.inertia.RigidBody",
            "strategies.particles.ParticleSystem",
            "scenes.result.Comparison",
            "scenes.result.ConservedReport",
            "scenes.result.SelfCheck",
            "scenes.result.SceneResult",
            "scenes.spec.Body",
            "scenes.spec.EffectSpec",
            "scenes.spec.Scene",
            "scenes.state.Hinge",
            "scenes.state.Layout",
            "scenes.support.Rest",
            "scenes.support.Support",
            "scenes.trajectory.Event",
            "scenes.trajectory.Trajectory",
            "scenes.bodies.Rigid",
            "scenes.bodies.Guided",
            "scenes.collision.Hit",
            "scenes.collision.StepFit",
            "scenes.compiled.CompiledRhs",
            "scenes.flows.Flow",
            "scenes.flows.Calendar",
            "scenes.forward.Forward",
            "scenes.modes.Modes",
            "scenes.impacts.Resolver",
        )
    },
    **{
        (f"mechanics.scenes.{name}", "BC01"): why
        for name, why in {
            "budget.memory_estimate": "integer arithmetic on a parsed scene: nothing to refuse",
            "budget.sample_limit": "integer arithmetic on a parsed scene: nothing to refuse",
            "contacts.quadratic_roots": "float arithmetic only (a NaN in gives NaN out)",
            "domain.domain_of": "string comparisons only: nothing to refuse",
            "impacts.falls_in": "builds and returns a SceneError for its caller to raise",
            "impacts.zeno": "builds and returns a SceneError for its caller to raise",
            "integrate.rows": "wraps a function: nothing to refuse",
            "flows.guided_flow": "the closed form of a guided body the parser has already "
            "checked: nothing of its own to refuse (extreme valid scenes tried)",
        }.items()
    },
    ("mechanics.scenes.trajectory.tolerance_scale", "BC01"): "the largest of three floats: "
    "nothing to refuse",
    ("mechanics.scenes.trajectory.dense_from_segments", "BC01"): "builds a function and "
    "checks nothing (the function it returns raises IndexError on no pieces, said there)",
    **{
        (f"mechanics.{protocol}", code): "a typing.Protocol: a type to check against, never "
        "called (numpydoc reads its signature as (*args, **kwargs))"
        for protocol in (
            "conformance.protocol.Adapter",
            "scenes.effects.base.BodyLike",
            "scenes.effects.base.SceneLike",
            "scenes.effects.base.SpecLike",
            "scenes.effects.capabilities.AddsInertia",
            "scenes.effects.capabilities.ChangesMass",
            "scenes.effects.capabilities.Compiles",
            "scenes.effects.capabilities.GuidesBody",
            "scenes.effects.capabilities.HasModes",
            "scenes.effects.capabilities.HasPotential",
        )
        for code in ("PR01", "BC01")
    },
}

SURFACE = public_callables()


def _under(key: str, room: str) -> bool:
    """Is the callable ``key`` one of the module (or package) ``room``?"""
    if room.endswith(".__init__"):
        return key.rpartition(".")[0] == room.removesuffix(".__init__")
    return key.startswith(room + ".")


def _object(key: str):
    module, _, name = key.rpartition(".")
    return getattr(importlib.import_module(module), name)


def _section(doc: str, title: str) -> str | None:
    """The text of a numpydoc section (``title`` underlined by dashes), or None."""
    m = re.search(
        rf"^{title}\n-{{{len(title)}}}\n(.*?)(?=^\S[^\n]*\n-{{3,}}\n|\Z)", doc, re.S | re.M
    )
    return None if m is None else m.group(1)


def _exception(name: str, home) -> bool:
    """Is ``name`` (as written in a Raises section) an exception class where ``home``
    lives, in :mod:`mechanics` (errors of any of its modules) or a builtin?"""
    module, _, leaf = name.rpartition(".")
    if module:  # a dotted name: hypothesis.errors.InvalidArgument
        try:
            obj = getattr(importlib.import_module(module), leaf, None)
        except ImportError:
            obj = None
        if inspect.isclass(obj) and issubclass(obj, BaseException):
            return True
    for space in (vars(home), vars(builtins)):
        obj = space.get(leaf)
        if inspect.isclass(obj) and issubclass(obj, BaseException):
            return True
    for key in ("mechanics.errors", "mechanics.scenes.errors", "mechanics.conformance"):
        try:
            obj = getattr(importlib.import_module(key), leaf, None)
        except ImportError:
            continue
        if inspect.isclass(obj) and issubclass(obj, BaseException):
            return True
    return False


def _takes_arguments(obj) -> bool:
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return False
    return any(p.name not in ("self", "cls") for p in sig.parameters.values())


def own_errors(key: str, obj) -> list[tuple[str, str]]:
    """The library's own docstring rules (the module's docstring lists them)."""
    doc = inspect.getdoc(obj) or ""
    out = []
    raises = _section(doc, "Raises")
    if raises is None:
        if _takes_arguments(obj):
            out.append(("BC01", "no Raises section (a callable that takes arguments)"))
        raises = ""
    # each unindented line names one or more exceptions ("ShapeError, NonFiniteError")
    named = [n.strip() for line in re.findall(r"^\S.*$", raises, re.M) for n in line.split(",")]
    home = importlib.import_module(getattr(obj, "__module__", None) or key.rpartition(".")[0])
    for name in named:
        if not _exception(name, home):
            out.append(("BC02", f"Raises names {name}, which is not an exception class"))
    domain = re.search(r"^Domain:(.*?)(?:\n\n|\Z)", doc, re.S | re.M)
    if domain is not None:
        leaves = {n.rsplit(".", 1)[-1] for n in named}
        for err in sorted(set(re.findall(r"\b([A-Z]\w*(?:Error|Warning))\b", domain.group(1)))):
            if err not in leaves:
                out.append(
                    ("BC03", f"the Domain paragraph names {err}, the Raises section does not")
                )
    for title in ("Parameters", "Returns", "Yields", "Other Parameters", "Attributes"):
        text = _section(doc, title) or ""
        for line in re.findall(r"^\S.*$", text, re.M):
            if re.search(r"\b(array_like|ndarray)\b", line) and "shape" not in line:
                out.append(("BC04", f"{title}: {line.strip()!r} states no shape"))
    return out


def _errors_of(key: str, obj) -> list[tuple[str, str]]:
    """numpydoc's errors of the checks in :data:`NUMPYDOC` and the library's own, less the
    exemptions."""
    found = [
        (code, msg) for code, msg in validate.validate(key)["errors"] if code in NUMPYDOC
    ] + own_errors(key, obj)
    return [(c, m) for c, m in found if (key, c) not in EXEMPT]


def _errors(key: str) -> list[tuple[str, str]]:
    return _errors_of(key, _object(key))


@pytest.mark.parametrize("key", sorted(SURFACE))
def test_every_public_docstring_passes_numpydocs_and_the_librarys_checks(key):
    errors = _errors(key)
    assert not errors, f"{key}:\n" + "\n".join(f"  {c} {m}" for c, m in errors)


def test_every_exemption_is_of_a_public_callable_and_a_known_check():
    for (key, code), why in EXEMPT.items():
        assert key in SURFACE, key
        assert code in NUMPYDOC or code.startswith("BC"), code
        assert why.strip(), (key, code)


# ------------------------------------------------------------------ negative controls


def _good(m, r):
    """Centre of mass of masses ``m`` at ``r`` (a control: passes every check).

    Domain: masses ≥ 0 (else NegativeMassError).

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg.
    r : array_like, shape (..., N, 3)
        Positions, m.

    Returns
    -------
    ndarray, shape (..., 3)
        The centre of mass, m.

    Raises
    ------
    NegativeMassError
        Where a mass is negative.

    Examples
    --------
    >>> 1 + 1
    2
    """


def _bad(m, r):
    """Centre of mass of masses ``m`` at ``r``
    spread over two lines (a control: fails every check).

    Domain: masses ≥ 0 (else NegativeMassError, or ShapeError).

    Parameters
    ----------
    m : array_like
        Masses, kg.
    q : float
        Not a parameter.

    Raises
    ------
    NotAnError
        Never.
    ShapeError, AlsoNotAnError
        Two on one line, the second not an exception.
    hypothesis.errors.InvalidArgument
        A dotted name, found where it lives.
    hypothesis.errors.NotThere
        A dotted name of nothing.
    """
    return m


def test_a_docstring_that_breaks_each_rule_is_named_with_each_check():
    bad = _errors_of("tests.test_docstrings._bad", _bad)
    codes = {c for c, _ in bad}
    assert codes >= {"SS06", "PR01", "PR02", "RT01", "EX01", "BC02", "BC03", "BC04"}, bad
    assert {m for c, m in bad if c == "BC02"} == {
        "Raises names NotAnError, which is not an exception class",
        "Raises names AlsoNotAnError, which is not an exception class",
        "Raises names hypothesis.errors.NotThere, which is not an exception class",
    }
    # ShapeError is read from the line that names two: only NegativeMassError is missing
    assert {m for c, m in bad if c == "BC03"} == {
        "the Domain paragraph names NegativeMassError, the Raises section does not"
    }
    assert {c for c, _ in _errors_of("tests.test_docstrings._good", _good)} == set()


def test_a_callable_that_takes_arguments_needs_a_raises_section():
    def no_raises(x):
        """Twice ``x``.

        Parameters
        ----------
        x : float
            A number.

        Returns
        -------
        float
            Twice it.
        """
        return 2 * x

    def no_arguments():
        """Two.

        Returns
        -------
        float
            Two.
        """
        return 2.0

    assert ("BC01", "no Raises section (a callable that takes arguments)") in own_errors(
        "x.no_raises", no_raises
    )
    assert own_errors("x.no_arguments", no_arguments) == []


def report(rooms: list[str]) -> int:
    """Print each failing callable under ``rooms`` (modules or packages, or callables;
    all when empty) with its errors; the number of failing callables.
    ``python -m tests.test_docstrings mechanics.rotation mechanics.scenes.effects``."""
    failing = 0
    for key in sorted(SURFACE):
        if rooms and not any(key == r or _under(key, r) for r in rooms):
            continue
        errors = _errors(key)
        if errors:
            failing += 1
            print(key)
            for code, msg in errors:
                print(f"  {code} {msg}")
    print(f"{failing} failing")
    return failing


if __name__ == "__main__":
    import sys

    sys.exit(1 if report(sys.argv[1:]) else 0)
