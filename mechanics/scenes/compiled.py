"""The compiled forward dynamics of a scene (issue 30, item 1): which models run their
right-hand side in :mod:`mechanics.scenes._kernels`, the program written for them, and
the loader.

- A model compiles when every body is a point, a free rigid body, a pinned body, a body
  on a fixed axis or a fixed one, no mass changes, and every listed load declares
  :class:`~mechanics.scenes.effects.capabilities.Compiles` (gravity, applied forces and
  couples, springs, dampers, drag, Newtonian gravity, a fixed point).  Otherwise, and
  while bodies rest on a plane (:mod:`.support` adds their support forces), the Python
  right-hand side of :class:`~mechanics.scenes.forward.Forward` runs: it is the
  reference, which the tests hold the kernel to.
- :func:`program` writes the kernel's arrays once per model; nothing is compiled per
  scene (the kernel reads the program: numba compiles it once per machine and caches
  it).
- numba is the ``fast`` extra.  Without it the Python path runs, silently: it gives the
  same results (the conformance battery runs under a lean install with warnings as
  errors), and the run's ``how`` says which path ran and which extra compiles it.  A
  kernel that numba fails to load or compile gives one
  :class:`~mechanics.integrators.CompiledPathWarning` and the Python path for the
  rest of the process.
"""

from __future__ import annotations

import contextlib
import importlib
import warnings
from collections.abc import Callable, Iterator
from types import ModuleType
from typing import TYPE_CHECKING, Literal, NoReturn, TypeAlias, cast

import numpy as np
import numpy.typing as npt

from .vectors import FloatArray, IntArray

if TYPE_CHECKING:  # for annotations only
    from mechanics.integrators import DOP853Stepper
    from mechanics.integrators._dop853 import DenseStep

    from .effects.capabilities import Compiles
    from .model import Model
    from .state import Hinge

#: the kernel's arrays (bi, bf, ops, fp, pairs), see :mod:`mechanics.scenes._kernels`
Program: TypeAlias = tuple[IntArray, FloatArray, IntArray, FloatArray, IntArray]
#: builds the reference stepper: ``reference(t, y, first_step)``
Reference: TypeAlias = "Callable[[float, FloatArray, float | None], DOP853Stepper]"

__all__ = [
    "CompiledRhs",
    "CompiledStepper",
    "build",
    "program",
    "reference_path",
    "stepper",
    "warm",
]

# the module mechanics.scenes._kernels once imported; False when it cannot be
_KERNELS: ModuleType | Literal[False] | None = None
# set inside reference_path(): the engines built there run the Python path
_REFERENCE_ONLY = False


def _reference_only() -> Iterator[None]:
    """The body of :func:`reference_path`'s block."""
    global _REFERENCE_ONLY
    before, _REFERENCE_ONLY = _REFERENCE_ONLY, True
    try:
        yield
    finally:
        _REFERENCE_ONLY = before


_reference_block = contextlib.contextmanager(_reference_only)


def reference_path() -> contextlib.AbstractContextManager[None]:
    """``with reference_path(): ...``: the scene engines built inside the block run in Python.

    They run the Python right-hand side (the reference), compiled or not, for comparing
    the two paths on whole runs: inside the block :func:`program` and :func:`build` give
    the reason instead of the kernel's arrays.  Blocks nest; the path before the block
    is restored when it ends.

    Returns
    -------
    contextlib.AbstractContextManager
        The context manager (it yields None).

    Examples
    --------
    >>> from mechanics.scenes.model import Model
    >>> from mechanics.scenes.spec import parse_scene
    >>> md = Model(parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...                         "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}],
    ...                         "effects": [{"type": "gravity", "g": 9.81}]}))
    >>> with reference_path():
    ...     why = build(md)
    >>> why == "the reference path was asked for (compiled.reference_path)"
    True
    """
    return _reference_block()


def _kernels() -> ModuleType | None:
    """mechanics.scenes._kernels, imported on first use, or None: numba is not installed
    (silently), or it failed (one CompiledPathWarning)."""
    global _KERNELS
    if _KERNELS is None:
        try:
            _KERNELS = importlib.import_module("._kernels", __package__)
        except ModuleNotFoundError as exc:
            if exc.name != "numba":
                raise
            _KERNELS = False
        except Exception as exc:  # numba present but broken
            _failed(exc)
    return _KERNELS or None


def _failed(exc: BaseException) -> None:
    """Give up the compiled scene dynamics for this process, saying why once."""
    from mechanics.integrators import CompiledPathWarning

    global _KERNELS
    _KERNELS = False
    warnings.warn(
        f"the compiled scene dynamics are unavailable ({type(exc).__name__}: {exc}); the "
        "scenes run their Python right-hand side instead (same results, slower)",
        CompiledPathWarning,
        stacklevel=4,
    )


def program(model: Model) -> Program | str:
    """The kernel's arrays (bi, bf, ops, fp, pairs) for ``model``, or why it has none.

    The arrays are those :mod:`mechanics.scenes._kernels` reads: per body its kind and
    offset (bi) and its numbers (bf: mass, inertia, pivot, hinge), per load its opcode and
    the indices into its numbers (ops, fp) and body pairs (pairs).  None are written
    inside :func:`reference_path`, without numba, or for a model that does not compile
    (see the module's docstring).

    Parameters
    ----------
    model : Model
        The scene's model (:class:`mechanics.scenes.model.Model`).

    Returns
    -------
    Program or str
        The five arrays (bi, bf, ops, fp, pairs): int64 of shape (n, 2), float of shape
        (n, BF_SIZE), int64 of shape (loads, 4), float of shape (numbers,), int64 of shape
        (pairs, 2) for n bodies; or the reason the model has no compiled right-hand side.

    Raises
    ------
    ModuleNotFoundError
        If importing the kernels fails for a missing module other than numba (a broken
        install); numba missing gives the reason instead.

    Examples
    --------
    >>> from mechanics.scenes.model import Model
    >>> from mechanics.scenes.spec import parse_scene
    >>> md = Model(parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...                         "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}],
    ...                         "effects": [{"type": "gravity", "g": 9.81}]}))
    >>> arrays = program(md)
    >>> isinstance(arrays, str) or [a.shape for a in arrays][::2] == [(1, 2), (1, 4), (0, 2)]
    True
    >>> with reference_path():
    ...     program(md)
    'the reference path was asked for (compiled.reference_path)'
    """
    if _REFERENCE_ONLY:
        return "the reference path was asked for (compiled.reference_path)"
    k = _kernels()
    if k is None:
        return "numba is not installed: pip install 'bodycheck[fast]'"
    lay = model.layout
    why = _why_not(model, k)
    if why is not None:
        return why
    n = model.n
    bi = np.zeros((n, 2), dtype=np.int64)
    bf = np.zeros((n, k.BF_SIZE))
    for b, (kind, o) in enumerate(zip(lay.kinds, lay.offsets, strict=True)):
        bi[b] = k.KINDS[kind], o
        bf[b, k.BF_M] = model.m0[b]
        bf[b, k.BF_J : k.BF_J + 3] = lay.J[b]
        bf[b, k.BF_RFIX : k.BF_RFIX + 3] = lay.r_fixed[b]
        if b in lay.pins:
            C, g, JC, JCinv = lay.pins[b]
            bf[b, k.BF_C : k.BF_C + 3] = C
            bf[b, k.BF_G : k.BF_G + 3] = g
            bf[b, k.BF_JC : k.BF_JC + 9] = np.ravel(JC)
            bf[b, k.BF_JCINV : k.BF_JCINV + 9] = np.ravel(JCinv)
        hinge = cast("Hinge | None", lay.guides.get(b))  # (_why_not found no other guide)
        if hinge is not None:
            bf[b, k.BF_C : k.BF_C + 3] = hinge.C
            bf[b, k.BF_A : k.BF_A + 3] = hinge.a
            bf[b, k.BF_U0 : k.BF_U0 + 3] = hinge.u0
            bf[b, k.BF_U1 : k.BF_U1 + 3] = hinge.u1
            bf[b, k.BF_HK : k.BF_HK + 3] = hinge.k, hinge.j, hinge.l
            bf[b, k.BF_H], bf[b, k.BF_JA] = hinge.h, hinge.J_a
    ops: list[tuple[int, int, int, int]] = []
    fp: list[float] = []
    pairs: list[tuple[int, int]] = []
    for e in model.forces:
        # (every force compiles: _why_not found none that does not)
        i, j, numbers, its_pairs = cast("Compiles", e).kernel_args()
        if its_pairs:
            i, j = len(pairs), len(its_pairs)
            pairs.extend(its_pairs)
        ops.append((k.OPCODES[e.type], i, j, len(fp)))
        fp.extend(float(x) for x in numbers)
    return (
        bi,
        bf,
        np.array(ops, dtype=np.int64).reshape(-1, 4),
        np.array(fp, dtype=float),
        np.array(pairs, dtype=np.int64).reshape(-1, 2),
    )


def _why_not(model: Model, k: ModuleType) -> str | None:
    """Why ``model`` has no compiled right-hand side, or None."""
    from .effects.capabilities import Compiles
    from .state import Hinge

    for b, (name, kind) in enumerate(zip(model.names, model.layout.kinds, strict=True)):
        if kind not in k.KINDS:
            return (
                f"body {name!r} is {kind}: only points, free, pinned, fixed and hinged bodies "
                "compile"
            )
        if kind == "guided" and not isinstance(model.layout.guides[b], Hinge):
            return f"body {name!r} rolls or slides: only a fixed axis of the joints compiles"
    for e in model.forces:
        if e.type not in k.OPCODES or not isinstance(e, Compiles):
            return f"the effect {e.type!r} ({e.where}) has no compiled loads"
    if model.losing or model.growing:  # (thrust and mass flow do not compile: belt and braces)
        return "a mass changes"
    return None


class CompiledRhs:
    """The compiled right-hand side of one model: ``rhs(t, phase, y)``.

    Called, it gives dy/dt, or None after one
    :class:`~mechanics.integrators.CompiledPathWarning` if numba fails to compile the
    kernel (:attr:`broken` is then set and the caller runs the Python path);
    :meth:`accelerations` gives the bodies' accelerations and forces at samples.
    :func:`build` makes one for a model.

    Parameters
    ----------
    kernels : module
        The kernels (:mod:`mechanics.scenes._kernels`): its ``scene_rhs``,
        ``scene_accelerations`` and ``scene_step``.
    arrays : Program
        The model's program (:func:`program`): the five arrays (bi, bf, ops, fp, pairs).

    Examples
    --------
    With a stand-in for the kernels (the real ones need numba) whose rate is y' = −y:

    >>> from types import SimpleNamespace
    >>> decay = SimpleNamespace(scene_rhs=lambda t, phase, y, *arrays: -y)
    >>> rhs = CompiledRhs(decay, ())
    >>> rhs(0.0, 0.0, [1.0, 2.0]).tolist(), rhs.broken
    ([-1.0, -2.0], False)
    """

    def __init__(self, kernels: ModuleType, arrays: Program) -> None:
        self.kernel, self.arrays = kernels.scene_rhs, arrays
        self.kernels = kernels
        #: numba failed on one of its kernels (warned once): the Python path from then on
        self.broken = False

    def __call__(self, t: float, phase: float, y: npt.ArrayLike) -> FloatArray | None:
        """dy/dt, or None after one warning if numba fails to compile the kernel (the
        caller runs the Python path)."""
        y = np.ascontiguousarray(y, dtype=float)
        try:
            out: FloatArray = self.kernel(float(t), float(phase), y, *self.arrays)
        except Exception as exc:  # a failed JIT (numba's errors are not one class)
            self._fail(exc)
            return None
        return out

    def _fail(self, exc: BaseException) -> None:
        self.broken = True
        _failed(exc)

    def accelerations(
        self, t: npt.ArrayLike, Y: npt.ArrayLike
    ) -> tuple[FloatArray, FloatArray] | None:
        """At the samples (t, Y), the loads on by each t: the acceleration of each
        body's G and the loads' force on it, shapes (k, n, 3); None after one warning
        if numba fails to compile the kernel."""
        T = np.ascontiguousarray(t, dtype=float)
        Y = np.ascontiguousarray(Y, dtype=float)
        try:
            A, F = self.kernels.scene_accelerations(T, Y, *self.arrays)
        except Exception as exc:  # a failed JIT
            self._fail(exc)
            return None
        return A, F


class CompiledStepper:
    """A DOP853 stepper whose steps the compiled kernel ``scene_step`` takes.

    The interface of :class:`mechanics.integrators.DOP853Stepper` that
    :func:`mechanics.scenes.integrate.integrate` uses (``step``, ``dense_output``,
    ``t``, ``t_old``, ``y``, ``status``), each step taken by the kernel
    ``scene_step``: the reference's step control and interpolant, the same
    starting step (Hairer's, the reference's function on the compiled right-hand side).
    A step the kernel cannot finish (a non-finite state, a step below 10 ulp) is taken
    again by the reference stepper from the same state and step, which raises the error
    naming the time (or, should it succeed, gives the step).

    ``reference`` builds that stepper: ``reference(t, y, first_step)``.

    Parameters
    ----------
    fast : CompiledRhs
        The model's compiled right-hand side.
    phase : float
        The phase the loads read (fixed for the stepper's life), s.
    t0 : float
        The start time, s.
    y0 : array_like, shape (size,)
        The state at ``t0``.
    f0 : ndarray, shape (size,)
        The rates at (t0, y0), finite (:func:`stepper` checks them).
    t_bound : float
        The time not to step past, s (> t0).
    rtol, atol : float
        The relative and absolute tolerances (> 0).
    reference : callable
        ``reference(t, y, first_step)``: the reference stepper from (t, y).

    Raises
    ------
    OutOfDomainError
        From :meth:`dense_output` before the first step.  (The constructor raises
        nothing of its own; :meth:`step` raises what the reference stepper raises on a
        step the kernel cannot finish, naming the time.)

    Examples
    --------
    With a stand-in for the kernels whose step always gives up (status 1): every step is
    the reference's, and the state at t = 1 is e⁻¹:

    >>> from types import SimpleNamespace
    >>> from mechanics.integrators import DOP853Stepper
    >>> def reference(t0, y0, first_step):  # y' = −y on [0, 1]
    ...     return DOP853Stepper(lambda t, y: -y, t0, y0, 1.0, rtol=1e-9, atol=1e-12,
    ...                          first_step=first_step)
    >>> giving_up = SimpleNamespace(scene_rhs=lambda t, phase, y, *arrays: -y,
    ...                             scene_step=lambda *args: (1, 0.0, 0.0, 0, 0))
    >>> st = CompiledStepper(CompiledRhs(giving_up, ()), 0.0, 0.0, np.ones(1), -np.ones(1),
    ...                      1.0, 1e-9, 1e-12, reference)
    >>> while st.status == "running":
    ...     st.step()
    >>> st.t, bool(np.isclose(st.y[0], np.exp(-1.0), rtol=1e-8))
    (1.0, True)
    """

    def __init__(
        self,
        fast: CompiledRhs,
        phase: float,
        t0: float,
        y0: npt.ArrayLike,
        f0: FloatArray,
        t_bound: float,
        rtol: float,
        atol: float,
        reference: Reference,
    ) -> None:
        from mechanics.integrators._dop853 import (
            _DOP853_EXPONENT,
            _KERNEL_TABLEAU,
            DOP853_MAX_FACTOR,
            DOP853_MIN_FACTOR,
            DOP853_SAFETY,
            _dop853_initial_step,
        )

        self.fast, self.phase, self.reference = fast, float(phase), reference
        self.t, self.t_bound = float(t0), float(t_bound)
        self.y = np.array(y0, dtype=float)
        self.rtol, self.atol = float(rtol), float(atol)
        self.t_old: float | None = None
        self.status = "running"
        self._tableau = _KERNEL_TABLEAU
        self._ctrl = np.array(
            [DOP853_SAFETY, DOP853_MIN_FACTOR, DOP853_MAX_FACTOR, _DOP853_EXPONENT]
        )
        self._dense: DenseStep | None = None
        self._f0 = f0
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            self.h_abs = _dop853_initial_step(
                lambda t, y: cast(FloatArray, fast(t, self.phase, y)),  # (f0 ran: not None)
                self.t,
                self.y,
                f0,
                self.t_bound,
                self.rtol,
                self.atol,
                1,
            )

    def step(self) -> None:
        """One accepted step (rejected attempts inside), never past ``t_bound``."""
        from mechanics.integrators._dop853 import DenseStep

        n = self.y.size
        y_new, f_new, F = np.empty(n), np.empty(n), np.empty((7, n))
        status = -1  # (numba failed before: the reference's steps)
        try:
            if not self.fast.broken:
                status, t_new, h_next, _, _ = self.fast.kernels.scene_step(
                    self.t, self.y, self._f0, self.h_abs, self.t_bound, self.rtol, self.atol,
                    *self._tableau, self._ctrl, self.phase, *self.fast.arrays, y_new, f_new, F,
                )  # fmt: skip
        except Exception as exc:  # a failed JIT: this step and the rest on the reference
            self.fast._fail(exc)
        if status != 0:  # the reference raises the error naming the time
            solver = self.reference(self.t, self.y, self.h_abs)
            solver.step()
            t_new, y_new, h_next = solver.t, solver.y, solver.h_abs
            f_new, dense = solver._fy, solver.dense_output()
        else:
            dense = DenseStep(self.t, t_new, self.y, F)
        self.t_old, self.t, self.y = self.t, float(t_new), y_new
        self._f0, self.h_abs, self._dense = f_new, float(h_next), dense
        if self.t >= self.t_bound:
            self.status = "finished"

    def dense_output(self) -> DenseStep:
        """The last step's continuous extension (a :class:`DenseStep`)."""
        if self._dense is None:
            from mechanics.errors import OutOfDomainError

            raise OutOfDomainError("dense_output() needs a step: call step() first")
        return self._dense


def stepper(
    fast: CompiledRhs,
    phase: float,
    t0: float,
    y0: FloatArray,
    t_bound: float,
    rtol: float,
    atol: float,
    reference: Reference,
) -> CompiledStepper | DOP853Stepper:
    """A :class:`CompiledStepper` from (t0, y0), or the reference stepper where it cannot run.

    The reference stepper ``reference(t0, y0, None)`` is returned where the compiled
    rates at (t0, y0) are not finite (its start raises the error naming the time) or
    numba failed.

    Parameters
    ----------
    fast : CompiledRhs
        The model's compiled right-hand side.
    phase : float
        The phase the loads read (fixed for the stepper's life), s.
    t0 : float
        The start time, s.
    y0 : ndarray, shape (size,)
        The state at ``t0``.
    t_bound : float
        The time not to step past, s (> t0).
    rtol, atol : float
        The relative and absolute tolerances (> 0).
    reference : callable
        ``reference(t, y, first_step)``: the reference stepper from (t, y) (the
        engine's: a :class:`mechanics.integrators.DOP853Stepper` on the Python
        right-hand side).

    Returns
    -------
    CompiledStepper or DOP853Stepper
        The stepper of the segment (whatever ``reference`` returns, in the second case).

    Raises
    ------
    NonFiniteError
        Where the compiled rates at (t0, y0) are not finite, from the engine's reference
        stepper, whose rates there are not finite either (naming the time); in general
        whatever ``reference`` raises.

    Examples
    --------
    With stand-ins for the kernels: finite rates give the compiled stepper, NaN rates the
    reference one:

    >>> from types import SimpleNamespace
    >>> from mechanics.integrators import DOP853Stepper
    >>> def reference(t0, y0, first_step):  # y' = −y on [0, 1]
    ...     return DOP853Stepper(lambda t, y: -y, t0, y0, 1.0, rtol=1e-9, atol=1e-12,
    ...                          first_step=first_step)
    >>> decay = SimpleNamespace(scene_rhs=lambda t, phase, y, *arrays: -y)
    >>> nan = SimpleNamespace(scene_rhs=lambda t, phase, y, *arrays: np.full(y.shape, np.nan))
    >>> [type(stepper(CompiledRhs(k, ()), 0.0, 0.0, np.ones(1), 1.0, 1e-9, 1e-12,
    ...                reference)).__name__ for k in (decay, nan)]
    ['CompiledStepper', 'DOP853Stepper']
    """
    f0 = fast(t0, phase, y0)
    if f0 is None or not np.all(np.isfinite(f0)):
        return reference(t0, y0, None)
    return CompiledStepper(fast, phase, t0, y0, f0, t_bound, rtol, atol, reference)


def build(model: Model) -> CompiledRhs | str:
    """The compiled right-hand side of ``model``, or why it has none.

    Parameters
    ----------
    model : Model
        The scene's model (:class:`mechanics.scenes.model.Model`).

    Returns
    -------
    CompiledRhs or str
        The right-hand side on the model's :func:`program`, or the reason it has none
        (:func:`program`'s, or a failure to load the kernels since).

    Raises
    ------
    ModuleNotFoundError
        If importing the kernels fails for a missing module other than numba (a broken
        install), as in :func:`program`.

    Examples
    --------
    A falling point compiles where numba is installed; the reason is the same either way
    inside :func:`reference_path`:

    >>> from mechanics.scenes.model import Model
    >>> from mechanics.scenes.spec import parse_scene
    >>> md = Model(parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...                         "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}],
    ...                         "effects": [{"type": "gravity", "g": 9.81}]}))
    >>> fast = build(md)
    >>> isinstance(fast, str) or isinstance(fast, CompiledRhs)
    True
    >>> with reference_path():
    ...     build(md) == program(md)
    True
    """
    arrays = program(model)
    if isinstance(arrays, str):
        return arrays
    k = _kernels()
    if k is None:  # (program found it; a failure since)
        return "the compiled scene dynamics failed to load"
    return CompiledRhs(k, arrays)


def warm() -> bool:
    """Load (or compile, the first time on a machine) the scene kernels now.

    On a free point falling for a step: the start-up cost paid before a timed run.

    Returns
    -------
    bool
        True where the compiled path runs; False where it does not (numba missing, or it
        failed: one :class:`~mechanics.integrators.CompiledPathWarning`).

    Examples
    --------
    The compiled path runs exactly where numba is installed (the ``fast`` extra):

    >>> import importlib.util
    >>> warm() == (importlib.util.find_spec("numba") is not None)
    True
    """
    k = _kernels()
    if k is None:
        return False
    arrays: Program = (
        np.array([[k.KINDS["point"], 0]], dtype=np.int64),
        np.ones((1, k.BF_SIZE)),
        np.array([[k.OPCODES["gravity"], -1, -1, 0]], dtype=np.int64),
        np.array([0.0, 0.0, -1.0]),
        np.zeros((0, 2), dtype=np.int64),
    )
    fast = CompiledRhs(k, arrays)
    if fast.accelerations(np.zeros(1), np.zeros((1, 6))) is None:
        return False

    def reference(  # pragma: no cover (the kernel runs)
        t0: float, y0: FloatArray, first_step: float | None
    ) -> NoReturn:
        raise AssertionError("the scene kernels failed on a falling point")

    stepper(fast, 0.0, 0.0, np.zeros(6), 1.0, 1e-9, 1e-12, reference).step()
    return True
