"""Solve one exam for several matricola digits k: the class answer sheet."""
from __future__ import annotations

import numpy as np

from linkcli.answers.quantities import report_names
from linkcli.answers.sheet import evaluate
from linkcli.errors import InputError, LinkcliError
from linkcli.input.document import build


def parse_k(text: str) -> list[int]:
    """'0-9' -> [0..9]; '1,3,5' -> [1, 3, 5]; ranges and lists may be mixed."""
    ks: list[int] = []
    for part in str(text).split(","):
        part = part.strip()
        try:
            if "-" in part:
                lo, hi = (int(x) for x in part.split("-", 1))
                ks += list(range(lo, hi + 1)) if lo <= hi else []
                if lo > hi:
                    raise ValueError
            else:
                ks.append(int(part))
        except ValueError:
            raise InputError(f"cannot read k list '{text}'", key="--k",
                             hint="use a digit, a range such as 0-9, or a list such as 1,3,5") \
                from None
    bad = [k for k in ks if not 0 <= k <= 9]
    if bad:
        raise InputError(f"k must be a digit 0-9, got {bad[0]}", key="--k")
    return ks


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
            result = evaluate(mech, )
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
