"""bodycheck's pytest plugin: hypothesis profiles, a seeded numpy generator, eps assertions.

Installed with the distribution (entry point ``pytest11``, plugin name ``bodycheck``),
so every pytest run in an environment with ``pip install bodycheck`` has it;
``-p no:bodycheck`` turns it off.

Conventions
-----------
- Nothing changes unless asked.  The hypothesis profiles ``bodycheck-ci``
  (derandomised, the same examples every run, a ``@reproduce_failure`` blob on
  failure), ``bodycheck-dev`` (random) and ``bodycheck-explore`` (ten times the
  examples, random) are loaded only by ``--bodycheck-profile NAME`` or the ini setting
  ``bodycheck_profile = NAME``; the command line wins over the ini (hypothesis' own
  ``--hypothesis-profile`` too; with ``--bodycheck-profile`` it is a usage error).
  Without either the project's own hypothesis settings stand.
- The profiles derive from hypothesis' ``default`` profile, not from whatever is
  loaded, so a name means the same in every project.  None has a deadline or the
  ``too_slow`` health check: a first call that imports or sets up something is slow.
- Importing the plugin imports neither hypothesis nor numpy (as hypothesis' own plugin
  takes care not to), so a pytest run that uses neither pays nothing.  The profiles are
  registered when one is asked for, or at configure time when hypothesis is already
  imported (by a conftest, say); :func:`register_profiles` registers them from
  anywhere.  Never sympy, matplotlib or :mod:`identities`.
- ``bodycheck_rng``: a ``numpy.random.Generator`` seeded from the test's node id
  (relative to the rootdir) and ``--bodycheck-seed`` (default 0): the same numbers for
  the same test on every run, on every xdist worker and in any order, different ones
  for different tests (each parametrisation is a test).  Its seed is printed, so a
  failure shows ``numpy.random.default_rng(<seed>)`` to reproduce it anywhere.  It is
  for plain tests (function-scoped); in a ``@given`` test, let hypothesis draw.
- ``eps_close``: the assertions of :mod:`mechanics.testing`, tolerances as multiples of
  float64 eps, failures naming the worst index and its error in eps.
"""

from __future__ import annotations

import argparse
import hashlib
import sys
from typing import TYPE_CHECKING

import pytest

if TYPE_CHECKING:  # for annotations only: importing the plugin imports no numpy
    import numpy as np
    import numpy.typing as npt

__all__ = ["PROFILE_NAMES", "EpsClose", "register_profiles"]

#: The profiles this plugin registers; prefixed so that they cannot clash with a
#: project's own (hypothesis itself registers ``default`` and ``ci``).
PROFILE_NAMES = ("bodycheck-ci", "bodycheck-dev", "bodycheck-explore")

_LOADED = pytest.StashKey[str]()


def register_profiles() -> None:
    """Register the ``bodycheck-*`` hypothesis profiles (idempotent; loads none).

    Each derives from hypothesis' ``default`` profile, without a deadline or the
    ``too_slow`` health check: ``bodycheck-ci`` derandomised, 100 examples, the
    ``@reproduce_failure`` blob printed; ``bodycheck-dev`` random, 100 examples;
    ``bodycheck-explore`` random, 1000 examples.  Imports hypothesis.

    Examples
    --------
    >>> register_profiles()
    >>> from hypothesis import settings
    >>> ci = settings.get_profile("bodycheck-ci")
    >>> ci.derandomize, ci.deadline, settings.get_profile("bodycheck-explore").max_examples
    (True, None, 1000)
    """
    from hypothesis import HealthCheck, settings

    base = settings(
        settings.get_profile("default"),
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow],
    )
    settings.register_profile(
        "bodycheck-ci", base, derandomize=True, max_examples=100, print_blob=True
    )
    settings.register_profile("bodycheck-dev", base, max_examples=100)
    settings.register_profile("bodycheck-explore", base, max_examples=1000)


def _seed_arg(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value < 0:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer >= 0")
    return value


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("bodycheck", "bodycheck (mechanics testing)")
    names = ", ".join(PROFILE_NAMES)
    group.addoption(
        "--bodycheck-profile",
        metavar="NAME",
        help=f"load a bodycheck hypothesis profile: {names} (overrides the ini "
        "setting bodycheck_profile)",
    )
    group.addoption(
        "--bodycheck-seed",
        metavar="N",
        type=_seed_arg,
        default=0,
        help="an integer >= 0 mixed into every bodycheck_rng seed (default 0)",
    )
    parser.addini(
        "bodycheck_profile",
        help=f"a bodycheck hypothesis profile to load: {names}",
        default="",
    )


def pytest_configure(config: pytest.Config) -> None:
    cli = config.getoption("bodycheck_profile")
    ini = config.getini("bodycheck_profile") or None  # `-o bodycheck_profile=` unsets it
    theirs = config.getoption("hypothesis_profile", None)
    given = [(cli, "--bodycheck-profile"), (ini, "the ini setting bodycheck_profile")]
    for value, source in given:
        if value is not None and value not in PROFILE_NAMES:
            raise pytest.UsageError(
                f"{source} is {value!r}, which is not a bodycheck profile; choose one of "
                + ", ".join(PROFILE_NAMES)
            )
    if cli is not None and theirs:
        raise pytest.UsageError(
            f"--bodycheck-profile={cli!r} and --hypothesis-profile={theirs!r} were both "
            "given; give one"
        )
    # the command line wins: ours, then hypothesis' own option, then the ini
    name, source = given[0] if cli is not None or theirs else given[1]
    if name is not None or theirs or "hypothesis" in sys.modules:
        register_profiles()
    if name is not None:
        from hypothesis import settings

        settings.load_profile(name)
        config.stash[_LOADED] = f"bodycheck: hypothesis profile {name!r} (from {source})"


# tryfirst: before hypothesis' plugin, whose options then apply on top
pytest_configure = pytest.hookimpl(tryfirst=True)(pytest_configure)


def pytest_report_header(config: pytest.Config) -> str | None:
    return config.stash.get(_LOADED, None)


def _seed(nodeid: str, base: int) -> int:
    """A 64-bit seed from a node id: the same on every run, machine and xdist worker."""
    digest = hashlib.sha256(f"{base}:{nodeid}".encode()).digest()
    return int.from_bytes(digest[:8], "little")


def bodycheck_rng(request: pytest.FixtureRequest) -> np.random.Generator:
    """A ``numpy.random.Generator`` seeded from this test's node id and ``--bodycheck-seed``."""
    import numpy as np

    base = request.config.getoption("bodycheck_seed")
    seed = _seed(request.node.nodeid, base)
    print(f"bodycheck_rng: numpy.random.default_rng({seed}) (--bodycheck-seed={base})")
    return np.random.default_rng(seed)


bodycheck_rng = pytest.fixture(bodycheck_rng)


class EpsClose:
    """Assertions with tolerances in eps: ``eps_close(actual, desired, eps=8)``.

    A thin front to :mod:`mechanics.testing`, whose messages name the worst index and
    its error in eps.  ``eps`` is the allowed error as a multiple of float64 eps (the
    same keyword as :func:`~mechanics.testing.assert_allclose_eps`); left out, each
    assertion's documented default applies (4 eps for all three).  The first also takes
    ``rtol``, the error as a fraction (``rtol=1e-2``: 1 %, reported as a fraction).

    Examples
    --------
    The ``eps_close`` fixture is one of these; outside pytest, build it:

    >>> eps_close = EpsClose()
    >>> eps_close(0.1 + 0.2, 0.3)
    >>> eps_close.quaternions([1.0, 0.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0])  # q ≡ −q
    >>> eps_close(1.0 + 2.0**-40, 1.0, eps=8)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    AssertionError: not close: relative error 4.1e+03 eps at index () exceeds 8 eps ...
    """

    def __call__(
        self,
        actual: npt.ArrayLike,
        desired: npt.ArrayLike,
        *,
        eps: float | None = None,
        rtol: float | None = None,
        scale: npt.ArrayLike | None = None,
        err_msg: str = "",
    ) -> None:
        """:func:`~mechanics.testing.assert_allclose_eps`: relative, or against ``scale``;
        the tolerance in eps (``eps=8``) or as a fraction (``rtol=1e-2``)."""
        __tracebackhide__ = True
        from .testing import assert_allclose_eps

        assert_allclose_eps(actual, desired, eps=eps, rtol=rtol, scale=scale, err_msg=err_msg)

    def rotations(
        self, R1: npt.ArrayLike, R2: npt.ArrayLike, *, eps: float | None = None, err_msg: str = ""
    ) -> None:
        """:func:`~mechanics.testing.assert_rotations_close`: matrices, max-abs."""
        __tracebackhide__ = True
        from .testing import EPS, ROTATIONS_CLOSE_ATOL, assert_rotations_close

        atol = ROTATIONS_CLOSE_ATOL if eps is None else _multiple(eps) * EPS
        assert_rotations_close(R1, R2, atol=atol, err_msg=err_msg)

    def quaternions(
        self, q1: npt.ArrayLike, q2: npt.ArrayLike, *, eps: float | None = None, err_msg: str = ""
    ) -> None:
        """:func:`~mechanics.testing.assert_quaternions_close`: q ≡ −q, max-abs."""
        __tracebackhide__ = True
        from .testing import EPS, QUATERNIONS_CLOSE_ATOL, assert_quaternions_close

        atol = QUATERNIONS_CLOSE_ATOL if eps is None else _multiple(eps) * EPS
        assert_quaternions_close(q1, q2, atol=atol, err_msg=err_msg)


def _multiple(eps: float) -> float:
    from .testing import _check_tolerance

    return _check_tolerance(eps, "eps")


def eps_close() -> EpsClose:
    """Assertions in eps: ``eps_close(a, b, eps=8)``, ``.rotations``, ``.quaternions``."""
    return EpsClose()


eps_close = pytest.fixture(scope="session")(eps_close)
