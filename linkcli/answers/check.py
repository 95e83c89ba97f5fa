"""Compare solutions with the answer keys stored in mechanism files.

A computed value agrees with a printed one when it rounds to it at the
printed precision: ``|computed - printed| <= 0.5 * 10**-decimals`` (angles
compared modulo a full turn).  Printed values marked ``wrong`` in the file are
reported as known key problems, never as failures.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np

from linkcli.answers.sheet import evaluate
from linkcli.errors import LinkcliError
from linkcli.input.document import build
from linkcli.model.mechanism import split_rate
from linkcli.input.source import load_file

ROUND_SLACK = 1e-9


@dataclass
class Outcome:
    file: str
    k: int | None
    name: str
    printed: str
    computed: str
    status: str            # 'pass' | 'fail' | 'known'
    reason: str = ""


@dataclass
class FileReport:
    file: str
    outcomes: list = field(default_factory=list)
    error: str | None = None
    keys: int = 0

    def count(self, status):
        return sum(o.status == status for o in self.outcomes)


def agrees(computed: float, printed: float, decimals: int, period: float | None) -> bool:
    diff = computed - printed
    if period:
        diff = (diff + period / 2) % period - period / 2
    return abs(diff) <= 0.5 * 10.0 ** -decimals + ROUND_SLACK * max(1.0, abs(printed))


def collect(paths) -> list[str]:
    files = []
    for path in paths:
        if os.path.isdir(path):
            for root, _, names in sorted(os.walk(path)):
                files += [os.path.join(root, n) for n in sorted(names)
                          if n.endswith((".yaml", ".yml"))]
        else:
            files.append(path)
    return files


def check_file(path: str) -> FileReport:
    report = FileReport("<stdin>" if path == "-" else path)
    try:
        doc = load_file(path)
        base = build(doc)
    except LinkcliError as exc:
        report.error = str(exc.located(path))
        return report
    report.keys = len(base.keys)
    for key in base.keys:
        try:
            mech = base if key.k is None or key.k == base.k else build(doc, key.k)
            report.outcomes += _check_key(mech, key)
        except LinkcliError as exc:
            report.error = f"k = {key.k}: {exc.located(path)}"
    return report


def _check_key(mech, key) -> list[Outcome]:
    names = []
    for entry in key.entries:
        if _is_point(mech, entry):
            names += ["x" + entry.name, "y" + entry.name]
        else:
            names.append(entry.name)
    result = evaluate(mech, names=names)
    out = []
    for entry in key.entries:
        shown = max(entry.decimals, 1) if entry.value is None or entry.wrong else entry.decimals
        if _is_point(mech, entry):
            computed = [float(result.values["x" + entry.name]), float(result.values["y" + entry.name])]
            ok = entry.value is not None and all(
                agrees(c, p, entry.decimals, None) for c, p in zip(computed, entry.value))
            text = "(" + ", ".join(f"{c:.{shown}f}" for c in computed) + ")"
        else:
            computed = float(np.asarray(result.values[entry.name]))
            period = _period(mech, entry.name, result.units[entry.name])
            ok = entry.value is not None and agrees(computed, entry.value, entry.decimals, period)
            text = f"{computed:.{shown}f}"
        status = "known" if entry.wrong else ("pass" if ok else "fail")
        out.append(Outcome(mech.file, mech.k, entry.name, entry.printed, text, status,
                           entry.wrong or ""))
    return out


def _is_point(mech, entry) -> bool:
    if isinstance(entry.value, tuple):
        return True
    return entry.value is None and entry.name in mech.points and entry.name not in mech.quantities


def _period(mech, name, unit) -> float | None:
    base, order = split_rate(name)
    quantity = mech.quantities[base]
    is_angle = quantity.kind == "angle" or (quantity.kind == "q" and mech.driver.kind == "angle")
    if order or not is_angle:
        return None
    return 360.0 if unit == "deg" else 2 * math.pi


def summary_lines(reports: list[FileReport], verbose: bool = False) -> tuple[list[str], bool]:
    lines = []
    passed = failed = known = nokey = errors = 0
    for rep in reports:
        if rep.error:
            errors += 1
            lines.append(f"ERROR {rep.error}")
        if not rep.keys and not rep.error:
            nokey += 1
            lines.append(f"{rep.file}: no key")
            continue
        for o in rep.outcomes:
            k = "-" if o.k is None else o.k
            if o.status == "fail":
                lines.append(f"FAIL {o.file} k={k} {o.name}: printed {o.printed}, "
                             f"computed {o.computed}")
            elif o.status == "known":
                lines.append(f"KNOWN {o.file} k={k} {o.name}: printed {o.printed}, "
                             f"computed {o.computed} ({o.reason})")
            elif verbose:
                lines.append(f"ok {o.file} k={k} {o.name}: {o.printed}")
        p, f, kn = rep.count("pass"), rep.count("fail"), rep.count("known")
        passed, failed, known = passed + p, failed + f, known + kn
        if rep.keys:
            lines.append(f"{rep.file}: {p} passed, {f} failed" + (f", {kn} known key problems"
                                                                    if kn else ""))
    lines.append(f"{known} known key problems, {nokey} files without key, {errors} files with "
                 "errors")
    lines.append(f"{passed} passed, {failed + errors} failed")
    return lines, failed == 0 and errors == 0
