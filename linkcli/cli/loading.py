"""The model of a command's FILE argument: read, validated, its design question solved.

A file that asks a design question (``find:``) is built with its solution unless the
command asks for the question as stated (``designed=False``: the exam's figure, a
parameter varied).  With ``--symbolic`` the document is read once and kept, since
standard input cannot be read twice.
"""
from __future__ import annotations

from linkcli.cli.options import check_symbolic
from linkcli.errors import LinkcliError


def load(path, k, designed=True, method="closed", tol=None, clutch=None):
    """The validated model of ``path`` for digit ``k``; where the file asks a design question
    (``find:``), built with its solution (each trial solved by ``method``) unless
    ``designed`` is False.  A clutch problem (``shafts:``, no linkage) is refused unless
    ``clutch`` is True; ``clutch`` a text names what the command would do with a linkage."""
    from linkcli.api import load as load_linkage
    model = load_linkage(path, k).model
    if model.clutch is not None and clutch is not True:
        refuse_clutch(path, clutch or "solve a linkage")
    if designed and model.design is not None:
        from linkcli.runs.design import resolved
        from linkcli.runs.sheet import evaluate
        try:
            model = resolved(model, evaluate, method, tol)
        except LinkcliError as exc:
            raise exc.located(path)
    return model


def refuse_clutch(path, what: str):
    """Refuse a command that needs a linkage on a clutch problem (exit 2)."""
    from linkcli.errors import InputError
    raise InputError(f"this is a clutch problem (shafts and a clutch, no linkage): there is "
                     f"no mechanism to {what}", file=path, key="shafts",
                     hint="linkcli solve, batch and check answer it; linkcli plot --clutch "
                     "draws the two speeds in time")


def symbolic_load(file, k, symbolic, numbers, seconds, designed=True, method="closed",
                  tol=None, clutch=None):
    """(model, formulas' source) of ``file``: the document is read once when the formulas
    are asked for (standard input cannot be read twice); a design question answered (by
    ``method``) unless ``designed`` is False."""
    check_symbolic(symbolic, numbers, seconds)
    if not symbolic:
        return load(file, k, designed, method, tol, clutch), None
    from linkcli.input.document import build
    from linkcli.input.source import load_file
    doc = load_file(file)
    model = build(doc, k)
    if model.clutch is not None:
        refuse_clutch(file, "write as formulas")
    return model, doc
