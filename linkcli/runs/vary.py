"""Parameter sweeps: a file's answers as one of its ``params`` runs over a range.

``linkcli sweep FILE --vary NAME=FROM:TO:STEPS`` solves the file at STEPS + 1 values of the
parameter NAME (as the file writes it, in the unit it is written in), each the whole answer
sheet: the kinematics at the file's driver value, statics and dynamics, the limits of the
motion, a vibration problem's equilibrium and modes, a design's unknowns.  What depends on
the parameter is built again for each value (input.document.rebuild); values where nothing
can be answered (a mechanism that does not assemble, a negative stiffness) are left out and
reported as ranges with the reason, never printed as numbers.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

from linkcli.answers.quantities import report_names
from linkcli.runs.sweep import Block, MAX_POSITIONS, check_names, listing
from linkcli.errors import InputError, LinkcliError
from linkcli.model.dimensions import param_unit_name

MAX_VALUES = 10 ** 6
SPEC = re.compile(r"^\s*([A-Za-z][A-Za-z0-9_]*)\s*=\s*([^:]+):([^:]+):([^:]+)\s*$")


def parse_vary(text: str, key: str = "--vary") -> tuple[str, np.ndarray]:
    """'NAME=FROM:TO:STEPS' -> (NAME, STEPS + 1 values FROM + i (TO - FROM) / STEPS)."""
    match = SPEC.match(str(text))
    try:
        if match is None:
            raise ValueError
        name = match.group(1)
        start, stop, steps = float(match.group(2)), float(match.group(3)), int(match.group(4))
    except ValueError:
        raise InputError(f"cannot read '{text}'", key=key, hint="write NAME=FROM:TO:STEPS, e.g. "
                         "ks=100:1000:90: a parameter of the file, its values as the file "
                         "writes it, STEPS intervals") from None
    if not (math.isfinite(start) and math.isfinite(stop)) or not 1 <= steps <= MAX_VALUES:
        raise InputError(f"'{text}': need finite FROM and TO and 1 <= STEPS <= {MAX_VALUES}",
                         key=key)
    values = start + np.arange(steps + 1) * ((stop - start) / steps)
    values[-1] = stop
    return name, values


@dataclass
class Gap:
    """A range of the parameter's values where the file has no answers, and why."""

    name: str
    lo: float
    hi: float
    count: int
    reason: str
    unit: str = ""
    end: int = field(default=-1, repr=False)    # the index of its last value
    kind: tuple = field(default=(), repr=False)  # the error's class and key

    def text(self) -> str:
        unit = f" {self.unit}" if self.unit else ""
        if self.count == 1:
            return f"no answers at {self.name} = {self.lo:.6g}{unit}: {self.reason}; row left out"
        return (f"no answers for {self.name} in [{self.lo:.6g}, {self.hi:.6g}]{unit} "
                f"({self.count} values; at {self.lo:.6g}: {self.reason}); rows left out")

    def as_dict(self) -> dict:
        return {"kind": "no answers", "parameter": self.name, "from": self.lo, "to": self.hi,
                "values": self.count, "message": self.text()}


@dataclass
class Varied:
    """The answers (display units) at each solved value of the parameter: the fields of a
    sweep over the driver (runs.sweep.Sweep), ``q`` the parameter's values."""

    mechanism: object
    name: str
    q: np.ndarray                         # every value of the parameter asked
    solved: np.ndarray                    # the mask of the rows answered
    names: list
    values: dict = field(default_factory=dict)    # name -> array over the solved rows
    units: dict = field(default_factory=dict)
    unit: str = ""                        # the parameter's
    issues: list = field(default_factory=list)


def check_parameter(mech, name, key="--vary"):
    """Refuse a name that is not one of the file's params."""
    declared = mech.source.doc.data.get("params") if mech.source is not None else None
    declared = declared if isinstance(declared, dict) else {}
    if name == "k":
        raise InputError("the digit k is not varied here: it is the matricola's", key=key,
                         file=mech.file, hint="use 'linkcli batch FILE --k 0-9'")
    if name not in declared:
        raise InputError(f"'{name}' is not a parameter of this file", key=key, file=mech.file,
                         hint="params: " + (listing(sorted(map(str, declared))) or "none"))
    if mech.design is not None and name in mech.design.names:
        raise InputError(f"'{name}' is an unknown of the file's design question: it is "
                         "solved, not varied", key=key, file=mech.file,
                         hint="vary another parameter: the design is solved at each value")


def vary(mech, name, values, names=None, key="--vary", method="closed", tol=None) -> Varied:
    """The answers ``names`` (default: the report's) at each of ``values`` of the parameter
    ``name`` (by ``method`` for a file with a driver); raises the error of the first value
    when no value has answers."""
    from linkcli.input.document import rebuild
    from linkcli.runs.sheet import evaluate
    check_parameter(mech, name, key)
    names = check_names(mech, names or None, "--names") if names else report_names(mech)
    values = np.asarray(values, dtype=float)
    if values.size > MAX_POSITIONS:
        raise InputError(f"{values.size} values is more than the limit of {MAX_POSITIONS}",
                         key=key)
    out = Varied(mech, name, values, np.zeros(values.size, bool), names,
                 unit=param_unit_name(mech, name))
    rows = {n: np.full(values.size, np.nan) for n in names}
    first_error = None
    from linkcli.runs.coefficients import sweep as at_once
    fast = at_once(mech, name, values, names, evaluate) if method == "closed" else None
    if fast is not None:        # the values the linear system answers, all at once
        answers, done, units = fast
        out.units.update(units)
        for n in names:
            rows[n][done] = answers[n][done]
        out.solved |= done
    for i, value in enumerate(values):
        if out.solved[i]:
            continue
        try:
            variant = rebuild(mech, {name: float(value)})
            result = evaluate(variant, names=names) if variant.elements is not None else \
                evaluate(variant, names=names, method=method, tol=tol)
        except LinkcliError as exc:
            first_error = first_error or exc
            _gap(out, i, value, exc)
            continue
        out.solved[i] = True
        out.units.update(result.units)
        for n in names:
            rows[n][i] = float(np.asarray(result.values[n], dtype=float))
    if not out.solved.any():
        raise first_error
    out.values = {n: v[out.solved] for n, v in rows.items()}
    return out


def _gap(out: Varied, i, value, exc) -> None:
    """Report the value ``i`` left out, joined to the previous range for the same kind of
    error (its class and key); the range keeps the message of its first value."""
    kind = (type(exc).__name__, exc.key)
    last = out.issues[-1] if out.issues else None
    if last is not None and last.kind == kind and last.end == i - 1:
        last.hi, last.count, last.end = float(value), last.count + 1, i
        return
    out.issues.append(Gap(out.name, float(value), float(value), 1, exc.detail, out.unit, i,
                          kind))


def blocks(varied: Varied):
    """The varied answers as the one block of a sweep (runs.sweep.Block), the parameter's
    values in the place of the driver's."""
    yield Block(varied.q, varied.solved, varied.values)


def write(varied: Varied, form: str, decimals: int | None, put) -> list:
    """Print ``varied`` through ``put`` as CSV, JSON or a table (the formats of a sweep over
    the driver, the parameter's column first); returns the reports."""
    from linkcli.runs.sweep import _write
    label = f"{varied.name}"
    _write(blocks(varied), varied.mechanism, "closed", varied.names, varied.units,
           varied.unit, lambda: varied.issues, form, 1, decimals, put, first=label)
    return varied.issues
