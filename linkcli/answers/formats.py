"""Format solved results: the exam answer sheet, a table, JSON or CSV."""
from __future__ import annotations

import csv
import io
import json
import math

import numpy as np

from linkcli.model.mechanism import REPORT_SECTIONS
from linkcli.model.rounding import noise_free

HEADINGS = {
    "en": {"design": "Design (solved parameters)", "position": "Position analysis", "velocity": "Velocity analysis",
           "acceleration": "Acceleration analysis", "statics": "Statics (virtual work)",
           "points": "Coordinates of notable points", "driver": "Driver",
           "dynamics": "Dynamics (virtual work with inertia and gravity)",
           "dynamics_no_gravity": "Dynamics (virtual work with inertia)",
           "vibration": "Vibrations (linearised about the static equilibrium)",
           "motion": "Machine dynamics (the motion under the given loads)"},
    "it": {"design": "Progetto (parametri ricavati)",
           "position": "Analisi Cinematica di POSIZIONE",
           "velocity": "Analisi Cinematica di VELOCITA'",
           "acceleration": "Analisi Cinematica di ACCELERAZIONE",
           "statics": "Analisi STATICA",
           "points": "Coordinate di punti notevoli", "driver": "Movente",
           "dynamics": "Analisi DINAMICA", "dynamics_no_gravity": "Analisi DINAMICA",
           "vibration": "Analisi delle VIBRAZIONI (linearizzata nell'equilibrio statico)",
           "motion": "DINAMICA della macchina (il moto sotto i carichi dati)"},
}


def heading(mech, section: str, lang: str = "en") -> str:
    """The heading of a report section: statics with masses is dynamics, said with gravity
    only where the file has gravity."""
    words = HEADINGS[lang]
    if section != "statics" or mech.dynamics is None or mech.elements is not None:
        return words[section]
    return words["dynamics" if mech.dynamics.gravity else "dynamics_no_gravity"]


def fmt(value, decimals: int) -> str:
    value = float(value)
    if not math.isfinite(value):
        return str(value)
    text = f"{value:.{decimals}f}"
    if float(text) == 0 and value != 0 and abs(value) >= 10.0 ** -(decimals + 6):
        # too small for these decimals but not the rounding noise of a zero (under a
        # millionth of the last decimal): two significant digits instead of a bare 0.0
        return f"{value:.2g}"
    if text.startswith("-") and float(text) == 0:
        text = text[1:]
    return text


def without_noise(result):
    """``result`` with every value that is rounding noise of a zero printed as 0.

    A value's scale is the largest magnitude among the sheet's values in the same display
    unit (a point's coordinates count among the lengths): a value under NOISE
    (``model.rounding``) times that
    scale is 0 (a coordinate of 3.7e-14 mm in a mechanism 1144 mm across, a spring force of
    -5.6e-15 N beside a transmitted force of 607 N).  A value alone in its unit keeps what
    it has; ``fmt`` still prints a value under a millionth of the last decimal as 0."""
    import dataclasses
    scales: dict = {}

    def see(unit, value):
        top = np.max(np.abs(value), initial=0.0, where=np.isfinite(value))
        scales[unit] = max(scales.get(unit, 0.0), float(top))

    values = {n: np.asarray(v, dtype=float) for n, v in result.values.items()}
    points = {p: (np.asarray(x, dtype=float), np.asarray(y, dtype=float))
              for p, (x, y) in result.points.items()}
    for name, value in values.items():
        see(result.units.get(name), value)
    for p, (x, y) in points.items():
        see(result.units.get(p), x)
        see(result.units.get(p), y)

    def clean(unit, value):
        return noise_free(value, scales[unit])

    return dataclasses.replace(
        result, values={n: clean(result.units.get(n), v) for n, v in values.items()},
        points={p: (clean(result.units.get(p), x), clean(result.units.get(p), y))
                for p, (x, y) in points.items()})


def _scalar(result, name):
    value = np.asarray(result.values[name])
    return float(value) if value.ndim == 0 else float(value.reshape(-1)[0])


def exam(result, decimals: int = 1, lang: str = "en") -> str:
    mech = result.mechanism
    words = HEADINGS[lang]
    lines = [mech.title]
    if mech.k is not None:
        lines.append(f"k = {mech.k}")
    shown = {n: fmt(_scalar(result, n), decimals) for n in result.values}
    column = max([10] + [len(text) for text in shown.values()])   # one column for the sheet
    for section in REPORT_SECTIONS:
        names = mech.report.get(section) or []
        if not names:
            continue
        lines += ["", heading(mech, section, lang)]
        width = max(len(n) for n in names)
        for name in names:
            lines.append(f"  {name:<{width}} = {shown[name]:>{column}} "
                         f"{result.units[name]}".rstrip())
        if section == "position" and result.points:
            lines += ["", words["points"]]
            for p, (x, y) in result.points.items():
                lines.append(f"  {p} = ({fmt(np.ravel(x)[0], decimals)}, "
                             f"{fmt(np.ravel(y)[0], decimals)}) {result.units[p]}")
    return "\n".join(lines)


def table(result, decimals: int = 1) -> str:
    from tabulate import tabulate
    rows = [(name, fmt(_scalar(result, name), decimals), result.units[name])
            for name in result.values]
    rows += [(p, f"({fmt(np.ravel(x)[0], decimals)}, {fmt(np.ravel(y)[0], decimals)})",
              result.units[p]) for p, (x, y) in result.points.items()]
    return tabulate(rows, headers=["quantity", "value", "unit"], disable_numparse=True)


def as_dict(result) -> dict:
    mech = result.mechanism
    values = {}
    for name, value in result.values.items():
        arr = np.asarray(value, dtype=float)
        values[name] = float(arr) if arr.ndim == 0 else arr.tolist()
    points = {p: [np.asarray(x, float).tolist(), np.asarray(y, float).tolist()]
              for p, (x, y) in result.points.items()}
    return {"title": mech.title, "file": mech.file, "k": mech.k, "values": values,
            "units": dict(result.units), "points": points}


def to_json(result) -> str:
    return json.dumps(as_dict(result), indent=2, allow_nan=True)


def to_csv(result, decimals: int | None = None) -> str:
    rows = [[name, repr(_scalar(result, name)) if decimals is None else
             fmt(_scalar(result, name), decimals), result.units[name]] for name in result.values]
    return csv_text(["quantity", "value", "unit"], rows)


def csv_text(header, rows) -> str:
    """``header`` and ``rows`` as CSV text, one line each, ending with a newline."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(header)
    writer.writerows(rows)
    return out.getvalue()


def render(result, form: str, decimals: int = 1, lang: str = "en") -> str:
    result = without_noise(result)
    if form == "exam":
        return exam(result, decimals, lang)
    if form == "table":
        return table(result, decimals)
    if form == "json":
        return to_json(result)
    return to_csv(result, decimals).rstrip("\n")
