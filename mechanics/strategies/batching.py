"""Batches: independent draws of a strategy stacked on leading axes.

Conventions
-----------
- Every public function of :mod:`mechanics` promises to broadcast over leading axes:
  an input of shape ``(..., 3)`` (a vector), ``(..., 3, 3)`` (a tensor) or ``(...)``
  (a scalar) is a stack of independent problems, and row ``i`` of the answer is the
  answer to row ``i``.  :func:`batches` draws such stacks from any strategy of
  arrays or floats, so that a property test can check the promise on the hard
  regimes of that strategy (a tiny and a huge rotation vector in one batch take
  different branches of one call).
- Regimes (:data:`BATCH_REGIMES`), drawn first: ``one`` (a single row, shape
  ``(1, ...)``), ``rows`` (2 to ``max_rows`` rows, shape ``(k, ...)``), ``grid``
  (a 2-D leading shape ``(k1, k2, ...)``, k1, k2 ≥ 2).  Shrinks toward ``one``.
- Bounds are keyword-only; bad arguments raise
  :class:`hypothesis.errors.InvalidArgument` quoting the value.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
from hypothesis import event
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from ._common import check_int

__all__ = ["BATCH_REGIMES", "batches"]

#: Regimes of :func:`batches`: one row; several rows; a 2-D grid of rows.
BATCH_REGIMES = ("one", "rows", "grid")


def batches(
    elements: st.SearchStrategy[npt.ArrayLike], *, max_rows: int = 6
) -> st.SearchStrategy[npt.NDArray[np.float64]]:
    """float64 arrays of independent draws of ``elements`` on leading axes.

    ``elements`` draws floats or arrays of one fixed shape ``e``; the result has
    shape ``(1, *e)``, ``(k, *e)`` with 2 ≤ k ≤ ``max_rows``, or ``(k1, k2, *e)``
    with k1 k2 ≤ ``max_rows`` (:data:`BATCH_REGIMES`).

    Parameters
    ----------
    elements : SearchStrategy
        Draws floats, or arrays of one fixed shape ``e``.
    max_rows : int
        The largest number of draws in a batch, ≥ 4.

    Returns
    -------
    SearchStrategy of ndarray, shape ``(1, *e)``, ``(k, *e)`` or ``(k1, k2, *e)``
        float64 stacks of independent draws.

    Raises
    ------
    InvalidArgument
        ``elements`` not a hypothesis strategy, or ``max_rows`` not an integer ≥ 4; when
        drawing, ``elements`` drawing arrays of different shapes.

    Examples
    --------
    Each row is one draw of ``elements``: the norms of a batch of unit vectors are 1.

    >>> from hypothesis import given, settings
    >>> from mechanics.strategies import unit_vectors
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(batches(unit_vectors()))
    ... def test_rows(u):
    ...     assert u.shape[-1] == 3 and u.size // 3 <= 6
    ...     assert np.allclose(np.linalg.norm(u, axis=-1), 1.0, rtol=0, atol=1e-15)
    >>> test_rows()
    """
    if not isinstance(elements, st.SearchStrategy):
        raise InvalidArgument(f"elements={elements!r} must be a hypothesis strategy")
    top = check_int(max_rows, "max_rows", 4)

    @st.composite
    def draw_batch(draw: st.DrawFn) -> npt.NDArray[np.float64]:
        regime = draw(st.sampled_from(BATCH_REGIMES))
        event(f"batches: {regime}")
        if regime == "one":
            shape: tuple[int, ...] = (1,)
        elif regime == "rows":
            shape = (draw(st.integers(2, top)),)
        else:
            k1 = draw(st.integers(2, top // 2))
            shape = (k1, draw(st.integers(2, top // k1)))
        rows = [np.asarray(draw(elements), dtype=np.float64) for _ in range(int(np.prod(shape)))]
        if len({r.shape for r in rows}) != 1:
            raise InvalidArgument(f"elements={elements!r} drew arrays of different shapes")
        return np.stack(rows).reshape(*shape, *rows[0].shape)

    return draw_batch()
