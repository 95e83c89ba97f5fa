"""The quantities a sweep reports: the names asked for, each checked against the file.

A sweep reports the file's ``report:`` names unless ``--names`` chooses others; each
must be a quantity of the file, at any rate except that of a load (loads are solved,
their rates are not).  Messages list at most ``LISTED`` names.
"""
from __future__ import annotations

from linkcli.answers.quantities import report_names
from linkcli.errors import InputError
from linkcli.model.mechanism import split_rate

#: names listed at most in a message (then '... and N more')
LISTED = 10


def listing(names, limit: int = LISTED) -> str:
    """'a, b, c' for at most ``limit`` names, then '... and N more' (never quadratic text)."""
    names = list(names)
    shown = ", ".join(names[:limit])
    return shown + (f" ... and {len(names) - limit} more" if len(names) > limit else "")


def check_names(mech, names, key: str = "--names") -> list:
    """The report's names, or ``names`` after checking that each is defined (and that
    none is the rate of a load: loads are solved, their rates are not)."""
    if not names:
        return report_names(mech)
    for name in names:
        base, order = split_rate(name, mech.quantities)
        if base not in mech.quantities:
            raise InputError(f"'{name}' is not a quantity of this file", key=key,
                             hint="defined: " + listing(sorted(mech.quantities)))
        if order and mech.quantities[base].kind == "load":
            raise load_rate_error(name, base, key=key)
    return list(names)


def load_rate_error(name, base, **where) -> InputError:
    """``name`` asks for the rate of the load ``base``, which linkcli does not compute."""
    return InputError(f"'{name}' is a rate of the load '{base}': linkcli solves loads, not "
                      "their rates", hint=f"ask for '{base}' itself", **where)

