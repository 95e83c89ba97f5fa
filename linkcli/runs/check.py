"""Compare solutions with the answer keys stored in mechanism files.

A computed value agrees with a printed one when it rounds to it at the
printed precision: ``|computed - printed| <= 0.5 * 10**-decimals`` (angles
compared modulo a full turn), the decimals of scientific notation being those
of the mantissa less the exponent (``3.35e3`` is printed to tens).  Printed
values marked ``wrong`` in the file are reported as known key problems, never
as failures; keys of the rates of loads are refused (loads are solved, their
rates are not).

A key may widen the agreement with a tolerance (the key's ``tolerance`` for all
its values, ``tolerances`` for one): ``|computed - printed| <= t`` for an
absolute ``t`` in the value's display unit, ``<= t |printed|`` for a
percentage, a point's x and y each on its own.  A value that agrees only
within the tolerance passes, and its outcome says so (``within``).
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np

from linkcli.answers.quantities import angle_period
from linkcli.runs.sheet import evaluate
from linkcli.runs.sweep.names import load_rate_error
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
    tolerance: str = ""    # the tolerance of the key entry, with its unit ('2%', '0.05 ft/s')
    within: bool = False   # passed within the tolerance, not at the printed precision


@dataclass
class FileReport:
    file: str
    outcomes: list = field(default_factory=list)
    error: str | None = None
    keys: int = 0

    def count(self, status):
        return sum(o.status == status for o in self.outcomes)

    def count_within(self) -> int:
        return sum(o.status == "pass" and o.within for o in self.outcomes)


def _gap(computed: float, printed: float, period: float | None) -> float:
    """|computed - printed|, modulo a turn ``period`` for an angle."""
    diff = computed - printed
    if period:
        diff = (diff + period / 2) % period - period / 2
    return abs(diff)


def agrees(computed: float, printed: float, decimals: int, period: float | None) -> bool:
    return _gap(computed, printed, period) <= 0.5 * 10.0 ** -decimals + ROUND_SLACK * max(1.0, abs(printed))


def within(computed: float, printed: float, tolerance, period: float | None) -> bool:
    """Whether ``computed`` lies within ``tolerance`` (a model Tolerance) of ``printed``:
    ``|computed - printed| <= t`` (absolute, display unit) or ``<= t |printed|``
    (relative); angles compared modulo a full turn."""
    if tolerance is None:
        return False
    bound = tolerance.value * abs(printed) if tolerance.relative else tolerance.value
    return _gap(computed, printed, period) <= bound * (1.0 + ROUND_SLACK) + ROUND_SLACK * max(1.0, abs(printed))


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
    """Every key of the file at ``path`` compared: the mechanism is built once per digit,
    and each digit's values are solved at once (linear in the number of keys)."""
    report = FileReport("<stdin>" if path == "-" else path)
    try:
        doc = load_file(path)
        base = build(doc)
    except LinkcliError as exc:
        report.error = str(exc.located(path))
        return report
    report.keys = len(base.keys)
    digits: dict = {}            # k -> (mechanism, error)
    for key in base.keys:
        k = base.k if key.k is None else key.k
        if k not in digits:
            try:
                digits[k] = (base if k == base.k else build(doc, key.k), None)
            except LinkcliError as exc:
                digits[k] = (None, exc)
    solved = {k: _solve(mech, [e for key in base.keys if (base.k if key.k is None else key.k)
                                == k for e in key.entries])
              for k, (mech, error) in digits.items() if error is None}
    for key in base.keys:
        k = base.k if key.k is None else key.k
        mech, error = digits[k]
        where = "" if key.k is None else f"k = {key.k}: "
        try:
            if error is not None:
                raise error
            entries = [e for e in key.entries if not _load_rate(mech, e)]
            for entry in key.entries:
                if _load_rate(mech, entry):     # refused, located; the others compared
                    report.error = where + str(load_rate_error(
                        entry.name, split_rate(entry.name, mech.quantities)[0],
                        file=mech.file or path, line=entry.line, key=f"keys.values.{entry.name}"))
            report.outcomes += _check_key(mech, entries, solved[k])
        except LinkcliError as exc:
            report.error = where + str(exc.located(path))
    return report


def _load_rate(mech, entry) -> bool:
    """Whether ``entry`` is the rate of a load, which linkcli does not compute."""
    base, order = split_rate(entry.name, mech.quantities)
    quantity = mech.quantities.get(base)
    return bool(order) and quantity is not None and quantity.kind == "load" and \
        not _is_point(mech, entry)


def _names(mech, entries) -> list:
    """The names to solve for ``entries``: a point's key is its x and y."""
    names = []
    for entry in entries:
        if _load_rate(mech, entry):
            continue                      # refused by check_file, where it is located
        names += ["x" + entry.name, "y" + entry.name] if _is_point(mech, entry) else [entry.name]
    return list(dict.fromkeys(names))


def _solve(mech, entries):
    """The values of every name of ``entries`` at once, or the error (then each key is solved
    alone, so that a name that fails only fails the keys that hold it)."""
    try:
        return evaluate(mech, names=_names(mech, entries))
    except LinkcliError as exc:
        return exc


def _check_key(mech, entries, solved=None) -> list[Outcome]:
    """The outcome of each of ``entries`` (a key's), with the values ``solved`` for the whole
    digit, or solved here for these entries alone."""
    if not entries:
        return []
    result = solved if solved is not None and not isinstance(solved, LinkcliError) else \
        evaluate(mech, names=_names(mech, entries))
    out = []
    for entry in entries:
        decimals = _precision(entry)
        shown = max(decimals, 1) if entry.value is None or entry.wrong else max(decimals, 0)
        tolerance = entry.tolerance
        if _is_point(mech, entry):
            computed = [float(result.values["x" + entry.name]), float(result.values["y" + entry.name])]
            unit = result.units["x" + entry.name]
            printed = entry.value if entry.value is not None else (None, None)
            exact = [p is not None and agrees(c, p, decimals, None)
                     for c, p in zip(computed, printed)]
            near = [p is not None and within(c, p, tolerance, None)
                    for c, p in zip(computed, printed)]
        else:
            computed = [float(np.asarray(result.values[entry.name]))]
            unit = result.units[entry.name]
            period = angle_period(mech, entry.name, unit)
            exact = [entry.value is not None and agrees(computed[0], entry.value, decimals,
                                                        period)]
            near = [entry.value is not None and within(computed[0], entry.value, tolerance,
                                                       period)]
        ok = all(e or n for e, n in zip(exact, near))
        widened = ok and not all(exact)
        digits = shown + 1 if widened else shown
        texts = [f"{c:.{digits}f}" for c in computed]
        text = "(" + ", ".join(texts) + ")" if len(texts) == 2 else texts[0]
        status = "known" if entry.wrong else ("pass" if ok else "fail")
        out.append(Outcome(mech.file, mech.k, entry.name, entry.printed, text, status,
                           entry.wrong or "", _tolerance_text(tolerance, unit),
                           widened and not entry.wrong))
    return out


def _tolerance_text(tolerance, unit: str) -> str:
    """'2%', '0.05 ft/s' (an absolute tolerance with the value's display unit), or ''."""
    if tolerance is None:
        return ""
    if tolerance.relative or not unit or unit == "-":
        return tolerance.text
    return f"{tolerance.text} {unit}"


def _precision(entry) -> int:
    """The decimals a printed value is exact to: those of its mantissa less its exponent
    (2.22e1: 1; 4e-1: 1; 3.35e3: -1, i.e. tens); for a point, the coarser of x and y."""
    text = str(entry.printed).strip()
    if isinstance(entry.value, tuple) and text.startswith("(") and text.endswith(")"):
        parts = [p for p in text[1:-1].split(",")]
        if len(parts) == 4:              # decimal commas: '(1,5, 2,25)'
            parts = [parts[0] + "." + parts[1], parts[2] + "." + parts[3]]
        found = [_printed_decimals(p) for p in parts if p.strip()]
        return min(found) if found and len(found) == 2 and None not in found else \
            entry.decimals
    found = _printed_decimals(text)
    return entry.decimals if found is None else found


def _printed_decimals(text: str) -> int | None:
    text = text.strip().replace(",", ".")
    mantissa, _, exponent = text.lower().partition("e")
    try:
        shift = int(exponent) if exponent else 0
    except ValueError:
        return None
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return decimals - shift


def _is_point(mech, entry) -> bool:
    if isinstance(entry.value, tuple):
        return True
    return entry.value is None and entry.name in mech.points and entry.name not in mech.quantities


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
                             f"computed {o.computed}" + (f" (not within {o.tolerance})"
                                                         if o.tolerance else ""))
            elif o.status == "known":
                lines.append(f"KNOWN {o.file} k={k} {o.name}: printed {o.printed}, "
                             f"computed {o.computed} ({o.reason})")
            elif verbose:
                lines.append(f"ok {o.file} k={k} {o.name}: {o.printed}" + (
                    f" (computed {o.computed}, within {o.tolerance})" if o.within else ""))
        p, f, kn = rep.count("pass"), rep.count("fail"), rep.count("known")
        near = rep.count_within()
        passed, failed, known = passed + p, failed + f, known + kn
        if rep.keys:
            lines.append(f"{rep.file}: {p} passed" + (f" ({near} within tolerance)" if near
                                                       else "") + f", {f} failed" +
                         (f", {kn} known key problems" if kn else ""))
    lines.append(f"{known} known key problems, {nokey} files without key, {errors} files with "
                 "errors")
    lines.append(f"{passed} passed, {failed + errors} failed")
    return lines, failed == 0 and errors == 0


def as_dict(reports: list[FileReport]) -> dict:
    """The reports as data for a course's CI: every compared value with its status
    ('pass', 'fail', 'known'), the files that could not be solved, and the totals."""
    files = []
    for rep in reports:
        files.append({"file": rep.file, "error": rep.error, "keys": rep.keys,
                      "values": [{"k": o.k, "name": o.name, "printed": o.printed,
                                  "computed": o.computed, "status": o.status,
                                  "reason": o.reason or None, "tolerance": o.tolerance or None,
                                  "within_tolerance": o.within} for o in rep.outcomes]})
    total = {s: sum(r.count(s) for r in reports) for s in ("pass", "fail", "known")}
    errors = sum(r.error is not None for r in reports)
    return {"files": files, "passed": total["pass"], "failed": total["fail"] + errors,
            "known": total["known"], "errors": errors,
            "without_key": sum(not r.keys and r.error is None for r in reports),
            "ok": total["fail"] == 0 and errors == 0}
