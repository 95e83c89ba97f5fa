"""linkcli: planar linkage solver driven by YAML.

    >>> import linkcli
    >>> mech = linkcli.load("mechanisms/padova-2020-07.yaml")
    >>> result = mech.solve()
    >>> round(result.values["phi1"], 1)
    28.9
"""
from __future__ import annotations

__version__ = "0.1.0"

from .errors import LinkcliError  # noqa: E402


def load(path: str, k: int | None = None):
    """Load and validate the mechanism file ``path`` for matricola digit ``k``.

    ``k`` overrides the file's default; ``path`` '-' reads standard input.
    """
    from .loading import build
    from .yamlsource import load_file
    try:
        return build(load_file(path), k)
    except LinkcliError as exc:
        raise exc.located(path)


def loads(text: str, k: int | None = None, name: str = "<text>"):
    """Like :func:`load`, from YAML text."""
    from .loading import build
    from .yamlsource import load_text
    return build(load_text(text, name), k)


__all__ = ["load", "loads", "LinkcliError", "__version__"]
