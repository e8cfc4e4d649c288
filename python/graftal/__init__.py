"""graftal: L-system files (pfg, LinF, STL, Fractint, cpfg, Smith, gft) read,
checked, derived, drawn and translated, by the library the ``graftal`` command
line uses.

    >>> import graftal
    >>> m = graftal.load("std:koch-island")
    >>> m.check()              # diagnostics, as `graftal check` prints them
    >>> m                      # in a notebook: the picture
    >>> word = m.derive(steps=3)
    >>> png = m.render("png", size=512)
    >>> text, warnings = m.translate("gft")

Every call raises ``GraftalError`` (with ``.diagnostics``) when it cannot do
what it is asked.
"""

from ._graftal import (
    Diagnostic,
    Diagnostics,
    GraftalError,
    Model,
    Picture,
    WordChunks,
    __version__,
    explain,
    load,
    notations,
    parse,
    stdlib,
    targets,
)

__all__ = [
    "Diagnostic",
    "Diagnostics",
    "GraftalError",
    "Model",
    "Picture",
    "WordChunks",
    "explain",
    "load",
    "notations",
    "parse",
    "stdlib",
    "targets",
]
