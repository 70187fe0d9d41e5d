"""``python -m bench.workprecision``: the study (as ``bodycheck bench``)."""

import sys

from .study import main_bench

raise SystemExit(main_bench(sys.argv[1:]))
