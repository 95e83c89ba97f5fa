"""A Moodle XML question bank: one embedded-answers (Cloze) question per digit k.

Each question states the problem with that digit's data: the title, the file's
``statement`` (added to, not instead of, the data), every datum of the model in words
(:mod:`linkcli.texts.data`), the exam's figure (:mod:`linkcli.pictures.exam`:
the data drawn, no answer), how to write the answers, and one NUMERICAL box per
reported quantity, in the order and sections of the exam's table::

    {w:NUMERICAL:=value:tolerance~=equivalent angle:tolerance}

written for the way Moodle grades them (question/type/multianswer and
question/type/numerical of Moodle 4 and 5):

- the question's mark is the sum of its boxes' weights (Moodle does not read
  ``defaultgrade`` for this type; it is written equal to the sum).  The weights are
  whole numbers in the ratio of ``quiz.points`` per section: the points themselves
  when every section's points divide among its boxes, else the smallest weights that
  keep each section's share of the mark within SHARE of the points' share, with a mark
  of at most MAX_MARK (Moodle stores a mark below 100 000);
- a response r scores the fraction of the first answer a with
  ``|r - a| <= tol + 1e-14 max(1, |a|)``, a and tol kept to 14 significant digits.
  A value or tolerance that needs more digits, or whose tolerance Moodle would widen
  by more than WIDEN of itself, is refused with the decimals that work;
- an angle box (an angle, a rotation, the angle between two vectors: what ``check``
  compares modulo a turn) has a second full-credit answer, the value less one turn
  (or plus one turn for a negative value): 330 and -30 deg both score;
- the tolerance is half a unit of the last decimal, ``quiz.tolerance`` or
  ``--tolerance``, widened where the file's key prints the value with fewer decimals or
  with a tolerance, so that every printed value ``check`` accepts scores: the key's
  bound (half a unit of its last printed decimal, or its tolerance) plus half a unit of
  the box's last decimal;
- the response's decimal separator is that of the student's Moodle language (Italian:
  a comma, with '.' between thousands; English: a point, with ','): the question says
  which one its language expects;
- the figure is a file of the question, linked as ``@@PLUGINFILE@@/`` and its name
  URL-encoded;
- a box whose value the question states as data (:func:`given`: the driver's quantity
  and the rates the statement gives, a known load) is asked back unless ``no_given``
  leaves it out; the weights are then those of the boxes that remain.

Text from the file is escaped for HTML, and braces become entities so that nothing but
the answer boxes reads as Cloze; the XML writer escapes the rest.  The questions sit in
a category named after the file.
"""
from __future__ import annotations

import base64
import html
import math
import os
import urllib.parse
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from decimal import ROUND_CEILING, Decimal
from fractions import Fraction

import numpy as np

from linkcli.runs import design
from linkcli.runs.design import asked
from linkcli.answers.formats import fmt, without_noise
from linkcli.answers.formats import heading as section_heading
from linkcli.answers.quantities import angle_period, report_names
from linkcli.runs.sheet import evaluate
from linkcli.texts.amounts import number
from linkcli.texts.data import data_lines
from linkcli.texts.quantities import describe
from linkcli.errors import InputError, LinkcliError, SolveError
from linkcli.exports.text import refuse_unfit, visible
from linkcli.input.document import build
from linkcli.model.mechanism import REPORT_SECTIONS, split_rate

SHARE = Fraction(1, 1000)       # a section's share of the mark: within 0.1 % of its points'
MAX_MARK = 10_000               # the largest mark written (Moodle's field holds < 100 000)
PHP_DIGITS = 14                 # significant digits of Moodle's floats
SLACK = 1e-14                   # Moodle widens each interval by SLACK max(1, |a|) ...
WIDEN = 0.01                    # ... which must stay within 1 % of the tolerance

WORDS = {
    "en": {"data": "Data", "figure": "Figure",
           "separator": "Write each result with a decimal point (12.5), without a thousands "
                        "separator, to {places}.",
           "places": ("no decimal places", "one decimal place", "{n} decimal places"),
           "angles": "An angle may be given in [0, {turn}) or as the equivalent angle one turn "
                     "less ({example}).",
           "or": "or"},
    "it": {"data": "Dati", "figure": "Figura",
           "separator": "Scrivere ogni risultato con la virgola decimale (12,5), senza "
                        "separatore delle migliaia, con {places}.",
           "places": ("nessuna cifra decimale", "una cifra decimale", "{n} cifre decimali"),
           "angles": "Un angolo si può dare in [0, {turn}) o come l'angolo equivalente di un "
                     "giro in meno ({example}).",
           "or": "o"},
}


def text(value) -> str:
    """File text for HTML inside a Cloze question: escaped, braces as entities."""
    return html.escape(str(value)).replace("{", "&#123;").replace("}", "&#125;")


# --- marks --------------------------------------------------------------------------------------
def weights(mech, left_out=frozenset()) -> tuple[dict, int]:
    """({section: the whole weight of each of its boxes}, the question's mark = their sum).

    One per box without ``quiz.points``; the points per box when they are whole numbers
    (the mark is then the sum of the points); else the smallest weights whose sections
    keep their share of ``quiz.points`` within SHARE (see the module).  The boxes are
    those the question asks, less ``left_out``."""
    sections = [s for s in REPORT_SECTIONS if _asked(mech, s, left_out)]
    counts = {s: len(_asked(mech, s, left_out)) for s in sections}
    points = mech.quiz.points
    if not points:
        return {s: 1 for s in sections}, sum(counts.values())
    missing = [s for s in sections if s not in points]
    if missing:
        raise InputError(f"quiz.points gives no points to the report's {', '.join(missing)} "
                         f"section{'s' if len(missing) > 1 else ''}", file=mech.file,
                         key="quiz.points", hint="give every section of the report its "
                         "points, or leave quiz.points out for one point per answer")
    exact = {s: Fraction(repr(float(points[s]))) / counts[s] for s in sections}
    if all(f.denominator == 1 for f in exact.values()):
        chosen = {s: int(f) for s, f in exact.items()}
        if _mark(chosen, counts) <= MAX_MARK:
            return chosen, _mark(chosen, counts)
    total = sum(exact[s] * counts[s] for s in sections)
    shares = {s: exact[s] * counts[s] / total for s in sections}
    for scale in range(1, MAX_MARK + 1):
        chosen = {s: round(scale * shares[s] / counts[s]) for s in sections}
        mark = _mark(chosen, counts)
        if mark > MAX_MARK:
            break
        if min(chosen.values()) >= 1 and all(
                abs(Fraction(chosen[s] * counts[s], mark) - shares[s]) <= SHARE
                for s in sections):
            return chosen, mark
    small = min(sections, key=lambda s: shares[s] / counts[s])
    shown = ", ".join(f"{s}: {points[s]:g}" for s in sections)
    raise InputError(f"quiz.points ({shown}) cannot be kept by whole weights of the answer "
                     f"boxes with a mark of at most {MAX_MARK}, each section's share within "
                     f"{float(SHARE) * 100:g} %", file=mech.file, key="quiz.points",
                     hint=f"the {counts[small]} boxes of {small} share "
                     f"{float(shares[small]) * 100:.2g} % of the points: give each box at "
                     f"least 1/{MAX_MARK} of them, or leave quiz.points out for one point per "
                     "box")


def _mark(chosen, counts) -> int:
    return sum(chosen[s] * counts[s] for s in chosen)


# --- numbers as Moodle stores them --------------------------------------------------------------
def _decimal(value: float) -> Decimal:
    return Decimal(repr(float(value)))


def half_unit(places: int) -> Decimal:
    """Half a unit of the last of ``places`` decimals."""
    return Decimal(5).scaleb(-places - 1)


def significant(number_text: str) -> int:
    """Significant digits written in a plain or scientific number ('250.0' has 4)."""
    mantissa = number_text.lower().split("e")[0].lstrip("-+").replace(".", "")
    return max(len(mantissa.lstrip("0")), 1)


def written(tolerance: Decimal) -> str:
    """A tolerance with all its digits, rounded up to 14 significant digits if longer."""
    tolerance = tolerance.normalize()
    if len(tolerance.as_tuple().digits) > PHP_DIGITS:
        quantum = Decimal(1).scaleb(tolerance.adjusted() - PHP_DIGITS + 1)
        tolerance = tolerance.quantize(quantum, rounding=ROUND_CEILING).normalize()
    return format(tolerance, "f")


def quiz_tolerance(mech, places: int, given: float | None) -> Decimal:
    """``given`` (--tolerance), else ``quiz.tolerance``, else half a unit of the last
    decimal."""
    if given is not None:
        if not (given > 0 and math.isfinite(given)):
            raise InputError(f"a tolerance must be positive, got {given!r}", key="--tolerance")
        return _decimal(given)
    if mech.quiz.tolerance is not None:
        return _decimal(mech.quiz.tolerance)
    return half_unit(places)


def key_bound(mech, name: str, file_k, value: float, places: int) -> Decimal | None:
    """How far from the computed value ``check`` accepts a printed key of ``name``, when
    that reaches past a box of ``places`` decimals: a key printed with fewer decimals (half
    a unit of its last one) or with a tolerance (absolute, or relative to the printed
    value; for another digit's key, to ``value``).  None when the box needs no widening.
    The keys of this digit decide; without one, those of other digits."""
    entries = [(file_k if key.k is None else key.k, e) for key in mech.keys
               for e in key.entries if e.name == name and not e.wrong
               and not isinstance(e.value, tuple)]
    here = [(k, e) for k, e in entries if k == mech.k] or entries
    bounds = []
    for k, e in here:
        bound = half_unit(e.decimals)
        if e.tolerance is not None:
            t = _decimal(e.tolerance.value)
            if e.tolerance.relative:
                t *= abs(_decimal(e.value if k == mech.k else value))
            bound = max(bound, t)
        if e.tolerance is not None or e.decimals < places:
            bounds.append(bound)
    return max(bounds) if bounds else None


@dataclass
class Box:
    """One NUMERICAL box: its quantity, weight, answers (the value first) and tolerance."""

    name: str
    weight: int
    answers: list
    tolerance: Decimal

    def cloze(self) -> str:
        tol = written(self.tolerance)
        return "{" + f"{self.weight}:NUMERICAL:" + "~".join(f"={a}:{tol}" for a in self.answers) \
            + "}"

    def refusal(self) -> str | None:
        """Why Moodle would not grade this box as written, or None."""
        for a in self.answers:
            if significant(a) > PHP_DIGITS:
                return f"'{self.name}' = {a} needs {significant(a)} significant digits"
            if float(self.tolerance) * WIDEN < SLACK * max(1.0, abs(float(a))):
                return (f"'{self.name}' = {a} has a tolerance of {written(self.tolerance)}, "
                        f"under {1 / WIDEN:g} times Moodle's rounding of the value")
        return None


def box(mech, result, name, weight, places, tolerance, file_k) -> Box:
    """The box of ``name``: its value at ``places`` decimals, the equivalent angle of an
    angle, the tolerance widened to the printed keys ``check`` accepts."""
    value = float(np.asarray(result.values[name]).reshape(-1)[0])
    shown = fmt(value, places)
    answers = [shown]
    period = angle_period(mech, name, result.units[name])
    if period is not None:
        stated = float(shown)
        answers.append(fmt(stated - period if stated >= 0 else stated + period, places))
    bound = key_bound(mech, name, file_k, value, places)
    if bound is not None:
        tolerance = max(tolerance, bound + half_unit(places))
    return Box(name, weight, answers, tolerance)


def _stored_places(boxes_of, places) -> int | None:
    """The most decimals (below ``places``) at which every box is graded as written."""
    for fewer in range(places - 1, -1, -1):
        if all(b.refusal() is None for b in boxes_of(fewer)):
            return fewer
    return None


# --- the question -------------------------------------------------------------------------------
def plugin_link(path: str) -> str:
    """``@@PLUGINFILE@@/`` and the file's path, each part URL-encoded as Moodle does."""
    return "@@PLUGINFILE@@/" + "/".join(urllib.parse.quote(part, safe="")
                                        for part in path.split("/"))


def instructions(mech, result, places, lang, left_out=frozenset()) -> str:
    """How to write the answers: the decimal separator, the decimals, and for angles the
    two equivalent values that score (where a box, not one ``left_out``, asks one)."""
    words = WORDS[lang]
    counted = words["places"][min(places, 2)].format(n=places)
    lines = [words["separator"].format(places=counted)]
    units = {result.units[n] for n in asked(mech, report_names(mech))
             if n not in left_out and angle_period(mech, n, result.units[n]) is not None}
    if units:
        turn, example = ("360", (330, -30)) if "deg" in units else \
            ("2π", (5.5, 5.5 - 2 * math.pi))
        shown = [number(round(v, 2), lang) for v in example]
        lines.append(words["angles"].format(turn=turn, example=f"{shown[0]} {words['or']} "
                                                                f"{shown[1]}"))
    return "<p>" + " ".join(text(line) for line in lines) + "</p>"


def question_html(mech, result, places, boxes, lang, figure_name, solution=None,
                  left_out=frozenset()) -> str:
    """The question's text: the data (a design question's unknowns and targets as
    ``solution`` states them), the figure, how to answer, and the boxes by section."""
    words = WORDS[lang]
    parts = [f"<p><b>{text(mech.title)}</b></p>"]
    if mech.statement:
        parts += [f"<p>{text(p.strip())}</p>" for p in mech.statement.split("\n\n") if p.strip()]
    parts.append(f"<p><b>{words['data']}</b></p><ul>" +
                 "".join(f"<li>{text(line)}</li>" for line in data_lines(mech, lang, solution))
                 + "</ul>")
    if figure_name:
        parts.append(f'<p><img src="{plugin_link(figure_name)}" alt="{text(words["figure"])}" '
                     'style="max-width: 100%"></p>')
    parts.append(instructions(mech, result, places, lang, left_out))
    for section in REPORT_SECTIONS:
        names = _asked(mech, section, left_out)
        if not names:
            continue
        heading = section_heading(mech, section, lang)
        rows = [f"<tr><td>{text(b.name)}</td><td>{text(describe(mech, b.name, lang))}</td>"
                f"<td>{b.cloze()}</td><td>{text(result.units[b.name])}</td></tr>"
                for b in boxes if b.name in names]
        parts.append(f"<p><b>{text(heading)}</b></p><table>{''.join(rows)}</table>")
    return "".join(parts)


def _asked(mech, section, left_out=frozenset()) -> list:
    """The boxes of a section of the report: a design question's targets are data, not
    asked back; nor are the names in ``left_out``."""
    return [n for n in asked(mech, mech.report.get(section) or []) if n not in left_out]


# --- boxes that repeat the statement's data -----------------------------------------------------
def given(mech) -> set:
    """The report's names whose value the question states as data: the driver's quantity
    (``q``, or a quantity measuring what the driver measures), its rate, and its
    acceleration when the statement gives it (a nonzero one, or one of a file that asks
    accelerations or dynamics: :mod:`linkcli.texts.loads`); a load with a known value, or a
    component of one.  A vibration problem's coordinates are unknowns, not data."""
    out = set()
    for name in asked(mech, report_names(mech)):
        base, order = split_rate(name, mech.quantities)
        quantity = mech.quantities.get(base)
        if quantity is None:
            continue
        if quantity.kind == "load":
            if mech.loads[quantity.a].value is not None:
                out.add(name)
        elif _measures_driver(mech, quantity) and (order < 2 or _accel_stated(mech)):
            out.add(name)
    return out


def _measures_driver(mech, quantity) -> bool:
    """Whether ``quantity`` is the driver's coordinate: ``q``, or the angle of the same
    vector, the length between the same points, the same coordinate of the same point."""
    d = mech.driver
    if mech.elements is not None or d is None:
        return False
    if quantity.kind == "q":
        return True
    if quantity.kind != d.kind or quantity.a is None:
        return False
    if d.kind == "length":
        return {quantity.a, quantity.b} == {d.a, d.b}
    return quantity.a == d.a and (d.kind != "angle" or quantity.b == d.b)


def _accel_stated(mech) -> bool:
    """Whether the statement gives the driver's acceleration (as :mod:`linkcli.texts.loads`
    words the driver)."""
    return bool(mech.driver.accel or mech.report.get("acceleration")
                or mech.dynamics is not None)


def left_out_boxes(mech, no_given=False) -> frozenset:
    """The report's names the quiz does not ask: those the question gives (:func:`given`)
    under ``no_given`` (``--no-given``) or the file's ``quiz.ask_given: false``, and the
    names of ``quiz.not_asked`` (the statement does not ask them)."""
    out = set(mech.quiz.not_asked)
    if no_given or not mech.quiz.ask_given:
        out |= given(mech)
    return frozenset(out)


def repeated(doc) -> tuple[int, int, bool]:
    """(boxes whose value the question gives, boxes, whether the file's quiz asks them) of
    a question of ``doc``: the report's names less ``quiz.not_asked``, the same for every
    digit."""
    mech = build(doc, None)
    names = [n for n in asked(mech, [n for s in REPORT_SECTIONS for n in
                                     mech.report.get(s) or []]) if n not in mech.quiz.not_asked]
    return len(given(mech) & set(names)), len(names), mech.quiz.ask_given


def _solved(mech, method):
    """(the answers of ``mech`` by ``method``, a zero's rounding noise 0 as solve prints
    it; its design question's solution or None)."""
    try:
        result = evaluate(mech) if method == "closed" else evaluate(mech, method=method)
        return without_noise(result), (design.solve(mech, evaluate, method)
                                       if design.unsolved(mech) else None)
    except LinkcliError as exc:
        cls = SolveError if isinstance(exc, SolveError) else InputError
        raise cls(_digit(mech) + exc.detail, file=exc.file, key=exc.key, line=exc.line,
                  hint=exc.hint) from None


def _digit(mech) -> str:
    """'digit k = 3: ' before a message about one question, '' for a file without k."""
    return f"digit k = {mech.k}: " if mech.k is not None else ""


def _boxes(mech, result, places, tolerance, file_k, left_out=frozenset()) -> list:
    chosen, _ = weights(mech, left_out)
    base = quiz_tolerance(mech, places, tolerance)
    return [box(mech, result, name, chosen[section], places, base, file_k)
            for section in REPORT_SECTIONS for name in _asked(mech, section, left_out)]


def _checked(mech, result, places, tolerance, file_k, decimals, left_out=frozenset()) -> list:
    """The boxes, or a refusal naming the box Moodle would not grade as written."""
    boxes = _boxes(mech, result, places, tolerance, file_k, left_out)
    for b in boxes:
        reason = b.refusal()
        if reason is None:
            continue
        fewer = _stored_places(lambda p: _boxes(mech, result, p, tolerance, file_k, left_out),
                               places)
        key = "--decimals" if decimals is not None else "report.decimals"
        hint = (f"use {key} {fewer} or fewer" if fewer is not None and tolerance is None
                and mech.quiz.tolerance is None else "give a larger tolerance or fewer "
                "decimals")
        raise InputError(f"{_digit(mech)}{reason}; Moodle keeps {PHP_DIGITS} significant "
                         f"digits and widens each tolerance by {SLACK:g} of the value, so it "
                         "would not grade this box as written",
                         file=mech.file, key=key, hint=hint)
    return boxes


def refuse_one_question(doc, ks) -> None:
    """Refuse several digits ``ks`` of a file that does not depend on k: they would all be
    the same question."""
    if ks is not None and len(ks) > 1 and doc.data.get("k") is None:
        raise InputError(f"the file does not depend on k (it sets no default 'k'), so the "
                         f"digits {', '.join(str(k) for k in ks)} would be one question",
                         file=doc.name, key="--k", hint="leave --k out for one question")


def export(doc, ks, decimals=None, tolerance=None, lang="it", figure=True,
           method="closed", no_given=False) -> str:
    """The Moodle XML text for the document ``doc`` at digits ``ks`` (None: the file's own).

    ``figure``: True for the exam's figure, False for none, or a function of the
    mechanism giving the PNG's bytes.  ``method``: 'closed' or 'newton' (a class-III
    group needs Newton).  ``no_given``: leave out the boxes whose value the question
    states (:func:`given`)."""
    refuse_unfit(doc)
    base = build(doc, None)
    if not report_names(base):
        raise InputError("the file has no report to ask", file=base.file, key="report",
                         hint="list the quantities the answer sheet asks for under 'report'")
    refuse_one_question(doc, ks)
    picture = figure if callable(figure) else _exam_picture(lang, method) if figure else None
    quiz = ET.Element("quiz")
    category = ET.SubElement(ET.SubElement(quiz, "question", type="category"), "category")
    name = os.path.splitext(os.path.basename(base.file))[0]
    ET.SubElement(category, "text").text = f"$course$/top/linkcli/{name}"
    for k in (ks if ks is not None else [None]):
        mech = build(doc, k)
        result, solution = _solved(mech, method)
        places = mech.report.get("decimals", 1) if decimals is None else decimals
        left_out = left_out_boxes(mech, no_given)
        boxes = _checked(mech, result, places, tolerance, base.k, decimals, left_out)
        if not boxes:
            raise InputError(f"{_digit(mech)}every box of the report asks a value the "
                             "question gives or one that quiz.not_asked lists, so the quiz "
                             "has no question", file=mech.file,
                             key="--no-given" if no_given else "quiz",
                             hint="ask the given values (no --no-given, quiz.ask_given: "
                             "true), list fewer names in quiz.not_asked, or report a "
                             "quantity to find")
        figure_name = f"{name}-k{mech.k}.png" if mech.k is not None else f"{name}.png"
        q = ET.SubElement(quiz, "question", type="cloze")
        ET.SubElement(ET.SubElement(q, "name"), "text").text = \
            f"{mech.title}" + (f" (k = {mech.k})" if mech.k is not None else "")
        qt = ET.SubElement(q, "questiontext", format="html")
        ET.SubElement(qt, "text").text = question_html(
            mech, result, places, boxes, lang, figure_name if picture else None, solution,
            left_out)
        if picture:
            f = ET.SubElement(qt, "file", name=figure_name, path="/", encoding="base64")
            f.text = base64.b64encode(picture(mech)).decode("ascii")
        gf = ET.SubElement(q, "generalfeedback", format="html")
        ET.SubElement(gf, "text").text = ""
        ET.SubElement(q, "penalty").text = "0.3333333"
        ET.SubElement(q, "hidden").text = "0"
        ET.SubElement(q, "idnumber").text = f"{name}-k{mech.k}" if mech.k is not None else name
        ET.SubElement(q, "defaultgrade").text = str(sum(b.weight for b in boxes))
    ET.indent(quiz)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + \
        visible(ET.tostring(quiz, encoding="unicode")) + "\n"


def _exam_picture(lang, method):
    from linkcli.exports.figure import figure_bytes

    def picture(mech) -> bytes:
        return figure_bytes(mech, "png", exam=True, lang=lang, method=method)
    return picture
