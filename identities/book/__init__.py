"""The book's checks, one room per chapter (``ch01`` … ``ch08``: each chapter's
equations, examples and problems) and ``scenes`` (the built-in scenes against the
book's numbers).  Each module registers catalogue checks with
:func:`identities.verify.catalogue.check`; it may import :mod:`mechanics` and
:mod:`identities.verify`, never :mod:`identities.cli`, matplotlib or argparse.
"""
