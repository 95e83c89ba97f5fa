"""A Moodle XML question bank: one embedded-answers (Cloze) question per digit k.

Each question states the problem with that digit's data (title, the file's
``statement``, the numbers), embeds the figure, and asks every reported
quantity in one NUMERICAL box, in the order and sections of the exam's table:

    {w:NUMERICAL:=value:tolerance}

with the value at the file's decimals, the tolerance half a unit of the last
printed decimal unless ``quiz.tolerance`` (or the caller) says otherwise, and
integer weights w in proportion to ``quiz.points`` per section (Moodle's
Cloze weights are whole numbers; the question's grade is the sum of the
points).  The questions sit in a category named after the file.  Text from
the file is escaped for HTML, and braces become entities so that nothing but
the answer boxes reads as Cloze; the XML writer escapes the rest.

Moodle's formats: the XML question format (``question type="cloze"``, the
``questiontext`` with its ``file`` elements, ``@@PLUGINFILE@@`` links) and the
embedded answers syntax, as Moodle's question importer reads them.
"""
from __future__ import annotations

import base64
import html
import math
import os
import xml.etree.ElementTree as ET
from fractions import Fraction

import numpy as np

from linkcli.answers.formats import fmt
from linkcli.answers.formats import heading as section_heading
from linkcli.answers.quantities import report_names
from linkcli.answers.sheet import evaluate
from linkcli.errors import InputError, LinkcliError, SolveError
from linkcli.exports.text import refuse_unfit, visible
from linkcli.input.document import build
from linkcli.model.mechanism import REPORT_SECTIONS


def text(value) -> str:
    """File text for HTML inside a Cloze question: escaped, braces as entities."""
    return html.escape(str(value)).replace("{", "&#123;").replace("}", "&#125;")


def tolerance_for(mech, decimals: int, given: float | None) -> float:
    if given is not None:
        if not 0 < given < math.inf:
            raise InputError(f"a tolerance must be a positive finite number, got {given!r}",
                             key="--tolerance")
        return given
    if mech.quiz.tolerance is not None:
        return mech.quiz.tolerance
    return 0.5 * 10.0 ** (-decimals)


def weights(mech) -> tuple[dict, float]:
    """({section: integer weight of each of its boxes}, the question's total points)."""
    sections = [s for s in REPORT_SECTIONS if mech.report.get(s)]
    counts = {s: len(mech.report[s]) for s in sections}
    points = mech.quiz.points or {s: counts[s] for s in sections}
    per_box = {s: Fraction(points.get(s, 0)).limit_denominator(1000) / counts[s]
               for s in sections}
    scale = math.lcm(*(f.denominator for f in per_box.values())) if per_box else 1
    out = {s: int(f * scale) for s, f in per_box.items()}
    return out, float(sum(points.get(s, 0) for s in sections))


def cloze_number(value: float, decimals: int) -> str:
    """A number as Moodle's NUMERICAL reads it (plain decimal, no thousands separator)."""
    return fmt(value, decimals)


def data_lines(mech) -> list[str]:
    """The problem's numbers as the exams list them: parameters, links, driver, loads."""
    units = mech.units
    l_unit, lf = units.display("length", 0)
    lines = []
    params = {n: v for n, v in mech.params.items() if n != "k"}
    if params:
        lines.append(", ".join(f"{n} = {v:.6g}" for n, v in params.items()))
    lengths = []
    for body in mech.bodies.values():
        if body.kind == "link" and len(body.points) == 2:
            a, b = body.points
            lengths.append(f"{a}{b} = {abs(body.local[b] - body.local[a]) / lf:.6g} {l_unit}")
    if lengths:
        lines.append(", ".join(lengths))
    fixed = [f"{p} = ({z.real / lf:.6g}, {z.imag / lf:.6g})" for p, z in mech.fixed.items()
             if not p.startswith("~")]
    if fixed:
        lines.append(", ".join(fixed) + f" {l_unit}")
    if mech.elements is None:
        d = mech.driver
        base = d.base
        u0, f0 = units.display(base, 0)
        u1, f1 = units.display(base, 1)
        lines.append(f"q = {d.value / f0:.6g} {u0}, q' = {d.rate / f1:.6g} {u1}" +
                     (f", q'' = {d.accel / units.display(base, 2)[1]:.6g} "
                      f"{units.display(base, 2)[0]}" if d.accel else ""))
    known = [load for load in mech.loads.values() if load.value is not None]
    for load in known:
        kind = mech.load_unit_kind(load)
        lines.append(f"{load.name} = {load.value / units.factor(kind):.6g} {units.names[kind]}")
    return lines


def question_html(mech, result, decimals, tolerance, box_weights, lang, figure_name):
    parts = [f"<p><b>{text(mech.title)}</b></p>"]
    if mech.statement:
        parts += [f"<p>{text(p.strip())}</p>" for p in mech.statement.split("\n\n") if p.strip()]
    data = data_lines(mech)
    if data:
        parts.append("<ul>" + "".join(f"<li>{text(line)}</li>" for line in data) + "</ul>")
    if figure_name:
        parts.append(f'<p><img src="@@PLUGINFILE@@/{figure_name}" alt="{text(mech.title)}" '
                     'style="max-width: 100%"></p>')
    for section in REPORT_SECTIONS:
        names = mech.report.get(section) or []
        if not names:
            continue
        heading = section_heading(mech, section, lang)
        rows = []
        for name in names:
            value = float(np.asarray(result.values[name]).reshape(-1)[0])
            box = (f"{{{box_weights[section]}:NUMERICAL:="
                   f"{cloze_number(value, decimals)}:{tolerance:g}}}")
            rows.append(f"<tr><td>{text(name)}</td><td>{box}</td>"
                        f"<td>{text(result.units[name])}</td></tr>")
        parts.append(f"<p><b>{text(heading)}</b></p><table>{''.join(rows)}</table>")
    return "".join(parts)


def export(doc, ks, decimals=None, tolerance=None, lang="it", figure=True) -> str:
    """The Moodle XML text for the document ``doc`` at digits ``ks`` (None: the file's own)."""
    from linkcli.exports.figure import figure_bytes
    refuse_unfit(doc)
    base = build(doc, None)
    if not report_names(base):
        raise InputError("the file has no report to ask", file=base.file, key="report",
                         hint="list the quantities the answer sheet asks for under 'report'")
    if ks is not None and len(ks) > 1 and doc.data.get("k") is None:
        raise InputError(f"the file does not depend on k (it sets no default 'k'), so the "
                         f"digits {', '.join(str(k) for k in ks)} would be one question",
                         file=base.file, key="--k", hint="leave --k out for one question")
    quiz = ET.Element("quiz")
    category = ET.SubElement(ET.SubElement(quiz, "question", type="category"), "category")
    name = os.path.splitext(os.path.basename(base.file))[0]
    ET.SubElement(category, "text").text = f"$course$/top/linkcli/{name}"
    for k in (ks if ks is not None else [None]):
        mech = build(doc, k)
        try:
            result = evaluate(mech)
        except LinkcliError as exc:
            cls = SolveError if isinstance(exc, SolveError) else InputError
            raise cls(f"digit k = {mech.k}: {exc.detail}", file=exc.file, key=exc.key,
                      line=exc.line, hint=exc.hint) from None
        places = mech.report.get("decimals", 1) if decimals is None else decimals
        box_weights, total = weights(mech)
        tol = tolerance_for(mech, places, tolerance)
        figure_name = f"{name}-k{mech.k}.png" if mech.k is not None else f"{name}.png"
        q = ET.SubElement(quiz, "question", type="cloze")
        ET.SubElement(ET.SubElement(q, "name"), "text").text = \
            f"{mech.title}" + (f" (k = {mech.k})" if mech.k is not None else "")
        qt = ET.SubElement(q, "questiontext", format="html")
        ET.SubElement(qt, "text").text = question_html(
            mech, result, places, tol, box_weights, lang, figure_name if figure else None)
        if figure:
            f = ET.SubElement(qt, "file", name=figure_name, path="/", encoding="base64")
            f.text = base64.b64encode(figure_bytes(mech, "png")).decode("ascii")
        gf = ET.SubElement(q, "generalfeedback", format="html")
        ET.SubElement(gf, "text").text = ""
        ET.SubElement(q, "penalty").text = "0.3333333"
        ET.SubElement(q, "hidden").text = "0"
        ET.SubElement(q, "idnumber").text = f"{name}-k{mech.k}" if mech.k is not None else name
        ET.SubElement(q, "defaultgrade").text = f"{total:g}"
    ET.indent(quiz)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + \
        visible(ET.tostring(quiz, encoding="unicode")) + "\n"
