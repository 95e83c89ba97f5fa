"""Solve one exam for several matricola digits k: the class answer sheet."""
from __future__ import annotations

import numpy as np

from linkcli.answers.formats import without_noise
from linkcli.answers.quantities import report_names
from linkcli.runs.sheet import evaluate
from linkcli.errors import InputError, LinkcliError
from linkcli.input.document import build


def parse_k(text: str) -> list[int]:
    """'0-9' -> [0..9]; '1,3,5' -> [1, 3, 5]; ranges and lists may be mixed.  Each digit
    is one row (one question), so a digit given twice is refused: the list holds at most
    the ten digits, whatever its length."""
    ks: list[int] = []
    for part in str(text).split(","):
        lo, hi = _bounds(part.strip(), text)
        for k in range(lo, hi + 1):
            if k in ks:
                raise InputError(f"the digit {k} is given twice in '{text}'", key="--k",
                                 hint="each digit is one row or question: give it once")
            ks.append(k)
    return ks


def _bounds(part: str, text: str) -> tuple[int, int]:
    """The first and last digit of one item of a k list ('3' or '2-5'), each checked to
    be a digit before any range is made."""
    try:
        lo, hi = (int(x) for x in part.split("-", 1)) if "-" in part else (int(part),) * 2
        if lo > hi:
            raise ValueError
    except ValueError:
        raise InputError(f"cannot read k list '{text}'", key="--k",
                         hint="use a digit, a range such as 0-9, or a list such as 1,3,5") \
            from None
    bad = [k for k in (lo, hi) if not 0 <= k <= 9]
    if bad:
        raise InputError(f"k must be a digit 0-9, got {bad[0]}", key="--k")
    return lo, hi


def run(doc, ks: list[int]):
    """Return (columns, units, rows, decimals, failures): a row per k with every report
    value, and (k, error) for each digit that cannot be built or solved (the other
    digits' rows are kept).  An error that every digit meets alike is raised instead:
    it is the file's, not one student's data."""
    rows = []
    failures: list[tuple[int, LinkcliError]] = []
    decimals = 1
    columns: list[str] = []
    units: dict = {}
    for k in ks:
        try:
            mech = build(doc, k)
            result = without_noise(evaluate(mech))      # a zero's rounding noise: 0, as solve
        except LinkcliError as exc:
            failures.append((k, exc.located(doc.name)))
            continue
        if not columns:
            decimals = mech.report.get("decimals", 1)
            names = report_names(mech)
            columns = names + [f"{c}{p}" for p in result.points for c in "xy"
                               if f"{c}{p}" not in names]
            units = dict(result.units)
            for p in result.points:
                units["x" + p] = units["y" + p] = result.units[p]
        values = dict(result.values)
        for p, (x, y) in result.points.items():
            values["x" + p], values["y" + p] = x, y
        rows.append([k] + [float(np.asarray(values[c])) for c in columns])
    if not rows and len({str(e) for _, e in failures}) == 1:
        raise failures[0][1]        # the same error for every digit: the file's, once
    return columns, units, rows, decimals, failures


def failure_text(k: int, exc: LinkcliError) -> str:
    """One failing digit's line: the file (line, key), the digit, what is wrong."""
    where = ", ".join(part for part in (exc.where(), f"k={k}") if part)
    text = f"{where}: {exc.detail}" + (f" ({exc.hint})" if exc.hint else "")
    errors = getattr(exc, "errors", None)
    if errors and len(errors) > 1:      # several input problems for this digit
        text = f"{where}: {len(errors)} problems:\n" + "\n".join(
            "  " + InputError.__str__(e) for e in errors)
    return text
