"""The command line (``bodycheck``, :mod:`.main`) and its presentation (tables, plots:
:mod:`.scene_plots`).  The only room that imports argparse and matplotlib; nothing
imports it but the entry point.
"""

from .main import main

__all__ = ["main"]
