"""linkcli: planar linkage solver driven by YAML.

    >>> import linkcli
    >>> mech = linkcli.load("mechanisms/padova-2020-07.yaml")
    >>> result = mech.solve()
    >>> round(result.values["phi1"], 1)
    28.9

The package is layered; each folder may import only the layers below it
(``docs/architecture.md``):

    errors                  the exception types (every layer)
    model/                  plain typed data: the mechanism, units, masses and elements
    input/                  YAML text -> validated model
    kinematics/             topology, Assur groups, closed-form and Newton solvers
    forces/                 statics, dynamics, reactions, balance
    answers/                quantities, sweeps, formats, check, batch, explain, validate
    pictures/               drawings, plots, animations (matplotlib, imported lazily)
    api                     the Python facade: load() -> Linkage.solve()
    cli                     the command line

Importing ``linkcli`` imports only the error types; ``load`` pulls the rest in.
"""
from __future__ import annotations

__version__ = "0.1.0"

from linkcli.errors import LinkcliError  # noqa: E402


def load(path: str, k: int | None = None):
    """Load and validate the mechanism file ``path`` for matricola digit ``k``
    (a :class:`linkcli.api.Linkage`); ``path`` '-' reads standard input."""
    from linkcli.api import load as _load
    return _load(path, k)


def loads(text: str, k: int | None = None, name: str = "<text>"):
    """Like :func:`load`, from YAML text."""
    from linkcli.api import loads as _loads
    return _loads(text, k, name)


def jit(on: bool = True) -> bool:
    """Solve arrays of driver values by the compiled loop (``linkcli.kinematics.compiled``)
    from now on in this process, as ``LINKCLI_JIT=1`` does, or by NumPy again (``on``
    False); whether the loop is on: numba must be installed (``pip install linkcli[jit]``).
    The first call compiles the loop (a few seconds, then cached on disk by numba)."""
    from linkcli.api import jit as _jit
    return _jit(on)


__all__ = ["load", "loads", "jit", "LinkcliError", "__version__"]
