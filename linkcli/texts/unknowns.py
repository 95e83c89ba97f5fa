"""The unknowns of a design question as the statement names them.

:func:`unknown_role` says what an unknown parameter is from where the file writes it on
its own ('the length of OA', :data:`ROLES`); :func:`variants` builds the mechanism again
at another value of each unknown (:data:`OTHER` times its start, a ratio that is no
round number), so that :func:`unknown_datum` can tell a datum that is an unknown, or
depends on one, from a datum of the problem.
"""
from __future__ import annotations

import math
import weakref

from linkcli.texts.amounts import CLOSE
from linkcli.texts.phrases import LANGS

#: where a file writes an unknown parameter (a key path, '*' any name) and what it is there
ROLES = (
    (("links", "*", "length"), ("the length of {}", "la lunghezza di {}"),
     ("the lengths of {}", "le lunghezze di {}")),
    (("springs", "*", "k"), ("the stiffness of spring {}", "la rigidezza della molla {}"),
     ("the stiffness of springs {}", "la rigidezza delle molle {}")),
    (("springs", "*", "free_length"), ("the free length of spring {}",
                                       "la lunghezza libera della molla {}"),
     ("the free length of springs {}", "la lunghezza libera delle molle {}")),
    (("dampers", "*", "c"), ("the damping coefficient of damper {}",
                             "il coefficiente di smorzamento dello smorzatore {}"),
     ("the damping coefficient of dampers {}",
      "il coefficiente di smorzamento degli smorzatori {}")),
    (("dynamics", "masses", "*"), ("the mass at {}", "la massa in {}"),
     ("the masses at {}", "le masse in {}")),
    (("dynamics", "inertias", "*"), ("the moment of inertia of {}",
                                     "il momento d'inerzia di {}"),
     ("the moments of inertia of {}", "i momenti d'inerzia di {}")),
    (("loads", "*", "value"), ("the value of load {}", "il valore del carico {}"),
     ("the value of loads {}", "il valore dei carichi {}")),
    (("driver", "value"), ("the driver's value", "il valore del movente"), None),
    (("driver", "rate"), ("the driver's rate", "la velocità del movente"), None),
)
#: a value of the unknown for the data stated at another one (a ratio, not a round number)
OTHER = 1.2345678


def unknown_role(mech, name: str, lang: str = "en") -> str:
    """What the parameter ``name`` is where the file writes it on its own ('the length of
    OA'), each place once; '' where no key says."""
    data = mech.source.doc.data if mech.source is not None else None
    found = {}
    for path in _written_at(data, name):
        for role in ROLES:
            pattern = role[0]
            if len(path) == len(pattern) and all(p in ("*", q) for p, q in zip(pattern, path)):
                found.setdefault(role, []).extend(q for p, q in zip(pattern, path) if p == "*")
    i = LANGS.index(lang)
    return ", ".join((role[2] if len(names) > 1 and role[2] else role[1])[i].format(
        ", ".join(names)) for role, names in found.items())


def _written_at(data, name, path=()) -> list:
    """The key paths of ``data`` whose value is the text ``name``."""
    if isinstance(data, dict):
        return [p for key, value in data.items() for p in _written_at(value, name,
                                                                       path + (str(key),))]
    if isinstance(data, str) and data.strip() == name and path and path[0] != "params":
        return [path]
    return []


def variants(mech) -> list:
    """(name, start, other value, the mechanism built with it) of each unknown of ``mech``'s
    design question that can be built at another value (kept per mechanism)."""
    from linkcli.errors import LinkcliError
    from linkcli.input.document import rebuild
    kept = _VARIANTS
    if mech not in kept:
        out = []
        for u in mech.design.unknowns:
            start = float(mech.params[u.name])
            other = start * OTHER if start else OTHER
            try:
                out.append((u.name, start, other, rebuild(mech, {u.name: other})))
            except LinkcliError:
                continue
        kept[mech] = out
    return kept[mech]


_VARIANTS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def unknown_datum(mech, measure, si_factor=1.0) -> str | None:
    """The unknown a datum ``measure(mech)`` (SI; ``si_factor`` of the unknown's unit, as
    the file writes it) depends on: its name where the datum is the unknown, 'name?' where
    it depends on it otherwise; None where it is data (or no design question is asked)."""
    if mech.design is None or mech.design.fixed:
        return None
    here = measure(mech)
    for name, start, other, varied in variants(mech):
        there = measure(varied)
        if math.isclose(here, there, rel_tol=CLOSE, abs_tol=CLOSE * abs(here)):
            continue
        if math.isclose(here, start * si_factor, rel_tol=CLOSE) and \
                math.isclose(there, other * si_factor, rel_tol=CLOSE):
            return name
        return f"{name}?"
    return None
