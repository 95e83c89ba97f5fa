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
from linkcli.runs.sheet import refuse_driving
from linkcli.runs.sweep.blocks import Block
from linkcli.runs.sweep.driver_range import MAX_POSITIONS
from linkcli.runs.sweep.names import check_names, listing
from linkcli.errors import InputError, LinkcliError
from linkcli.model.dimensions import param_unit_name

MAX_VALUES = 10 ** 6
#: values solved (and printed) together: the rows of a block are kept until printed, and the
#: all-at-once solution of a vibration's coefficients checks three of each block's values
BLOCK = 4096
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
    sweep over the driver (runs.sweep.blocks.Sweep), ``q`` the parameter's values."""

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


class Variation:
    """The answers ``names`` (default: the report's) at each of ``values`` of the parameter
    ``name`` (by ``method`` for a file with a driver), solved a block of ``block`` values at
    a time (:meth:`blocks`), so that memory does not grow with the values: each value's
    variant of the file is dropped once answered.  ``issues`` (the values without answers)
    are complete once the blocks are; when no value has answers, the first value's error is
    raised at the end of the blocks."""

    def __init__(self, mech, name, values, names=None, key="--vary", method="closed", tol=None,
                 block: int = BLOCK):
        check_parameter(mech, name, key)
        refuse_driving(mech, method=method)     # a vibration problem: its equilibrium's
        self.names = check_names(mech, names or None, "--names") if names else \
            report_names(mech)
        self.values = np.asarray(values, dtype=float).ravel()
        if self.values.size > MAX_POSITIONS:
            raise InputError(f"{self.values.size} values is more than the limit of "
                             f"{MAX_POSITIONS}", key=key)
        self.mech, self.name, self.method, self.tol = mech, name, method, tol
        self.block = max(1, int(block))
        self.unit = param_unit_name(mech, name)
        self.units: dict = {}
        self.issues: list = []
        self.solved_rows = 0
        self.first_error = None

    def blocks(self):
        """The answers a block at a time (runs.sweep.blocks.Block, the parameter's values in the
        place of the driver's)."""
        for lo in range(0, self.values.size, self.block):
            yield self._solve(lo, self.values[lo:lo + self.block])
        if not self.solved_rows:
            raise self.first_error

    def _solve(self, offset, values) -> Block:
        """The block of ``values``, the first of them the ``offset``-th value: the ones the
        linear system answers all at once (vibration coefficients), the others one by one."""
        from linkcli.runs.coefficients import sweep as at_once
        from linkcli.runs.sheet import evaluate
        from linkcli.input.document import rebuild
        rows = {n: np.full(values.size, np.nan) for n in self.names}
        solved = np.zeros(values.size, bool)
        fast = at_once(self.mech, self.name, values, self.names, evaluate) \
            if self.method == "closed" else None
        if fast is not None:
            answers, solved, units = fast
            self.units.update(units)
            for n in self.names:
                rows[n][solved] = answers[n][solved]
        for i in np.nonzero(~solved)[0]:
            try:
                variant = rebuild(self.mech, {self.name: float(values[i])})
                result = evaluate(variant, names=self.names, method=self.method, tol=self.tol)
            except LinkcliError as exc:
                self.first_error = self.first_error or exc
                _gap(self, offset + i, values[i], exc)
                continue
            solved[i] = True
            self.units.update(result.units)
            for n in self.names:
                rows[n][i] = float(np.asarray(result.values[n], dtype=float))
        self.solved_rows += int(np.count_nonzero(solved))
        return Block(values, solved, {n: v[solved] for n, v in rows.items()})


def vary(mech, name, values, names=None, key="--vary", method="closed", tol=None) -> Varied:
    """The answers ``names`` (default: the report's) at each of ``values`` of the parameter
    ``name`` (by ``method`` for a file with a driver), gathered (:class:`Variation` solves
    them a block at a time); raises the error of the first value when no value has
    answers."""
    variation = Variation(mech, name, values, names, key, method, tol)
    parts = list(variation.blocks())
    solved = np.concatenate([p.solved for p in parts])
    out = Varied(mech, name, variation.values, solved, variation.names,
                 unit=variation.unit, units=variation.units, issues=variation.issues)
    out.values = {n: np.concatenate([p.values[n] for p in parts]) for n in variation.names}
    return out


def _gap(out, i, value, exc) -> None:
    """Report the value ``i`` left out, joined to the previous range for the same kind of
    error (its class and key); the range keeps the message of its first value."""
    kind = (type(exc).__name__, exc.key)
    last = out.issues[-1] if out.issues else None
    if last is not None and last.kind == kind and last.end == i - 1:
        last.hi, last.count, last.end = float(value), last.count + 1, i
        return
    out.issues.append(Gap(out.name, float(value), float(value), 1, exc.detail, out.unit, i,
                          kind))


def write(variation: Variation, form: str, decimals: int | None, put) -> list:
    """Print ``variation`` through ``put`` as CSV, JSON or a table (the formats of a sweep
    over the driver, the parameter's column first), a block at a time as it is solved;
    returns the reports."""
    from linkcli.runs.sweep.output import write_rows
    write_rows(variation.blocks(), variation.mech, "closed", variation.names, variation.units,
               variation.unit, lambda: variation.issues, form, 1, decimals, put,
               first=variation.name)
    return variation.issues
