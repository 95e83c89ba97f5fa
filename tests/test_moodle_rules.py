"""Moodle's own rules, built into checks that the quiz of every shipped file must pass.

How Moodle (4.x, 5.x) imports and grades an embedded-answers (Cloze) question, read in
its source (question/type/multianswer, question/type/numerical) and confirmed on a real
site:

- marks: the question's mark is the sum of its boxes' weights (the ``defaultgrade`` of
  the XML is not read for this type), and a mark is stored in a numeric field that
  must stay below 100 000;
- numbers: answers and tolerances are floats kept to PHP's 14 significant digits;
  a response r scores the fraction of the first answer a, in order, with
  ``|r - a| <= tol + 1e-14 max(1, |a|)``;
- files: a question's ``@@PLUGINFILE@@/...`` link is a URL, decoded part by part to
  the name of the stored file.

Each rule is checked here on every shipped file (one export each, with a stand-in
figure, so that drawing does not cost the suite), and on the cases that broke it.
"""
from __future__ import annotations

import os
import sys
import urllib.parse
import xml.etree.ElementTree as ET

import pytest

sys.path.insert(0, os.path.dirname(__file__))

from quizzes import SHIPPED, boxes as _boxes, digit as _digit, export as _export  # noqa: E402
from quizzes import names as _names, questions as _cloze, shipped  # noqa: E402
from linkcli.runs.check import check_file  # noqa: E402
from linkcli.answers.quantities import angle_period  # noqa: E402
from linkcli.errors import InputError  # noqa: E402
from linkcli.exports import moodle  # noqa: E402
from linkcli.input.document import build  # noqa: E402
from linkcli.input.source import load_file, load_text  # noqa: E402

MARK_LIMIT = 100_000                          # Moodle's numeric field of a question's mark
PHP_DIGITS = 14                               # PHP's float precision


@pytest.fixture(scope="module")
def quizzes():
    """{path: XML root} of every shipped file's quiz (every digit for a file with k)."""
    return shipped()


def _raw(answer):
    """(value text, tolerance text) as written in the box."""
    value, _, tolerance = answer.raw_text.partition(":")
    return value, tolerance or "0"


def _stored(text: str) -> float:
    """A number as Moodle keeps it: PHP's float at 14 significant digits."""
    return float(f"{float(text.replace(',', '.')):.{PHP_DIGITS}g}")


def moodle_grade(box, response: float) -> float:
    """The fraction (0-100) Moodle gives ``response`` in a NUMERICAL box: that of the first
    answer whose interval a +- (tol + 1e-14 max(1, |a|)) holds it, 0 when none does."""
    for answer in box.answers:
        if answer.value is None:
            return answer.fraction
        text, tol = _raw(answer)
        a, t = _stored(text), _stored(tol)
        if abs(response - a) <= t + 10.0 ** -PHP_DIGITS * max(1.0, abs(a)):
            return answer.fraction
    return 0.0


def _each(quizzes):
    """(path, question, boxes) of every question; a failed export raises."""
    for path, root in quizzes.items():
        if isinstance(root, Exception):
            raise AssertionError(f"{os.path.basename(path)}: {root}")
        for q in _cloze(root):
            yield path, q, _boxes(q)


# --- marks -----------------------------------------------------------------------------------
def test_the_mark_is_the_sum_of_the_weights_and_fits_moodle(quizzes):
    wrong = []
    for path, q, boxes in _each(quizzes):
        total = sum(b.weight for b in boxes)
        grade = float(q.find("defaultgrade").text)
        if total != grade or not total < MARK_LIMIT:
            wrong.append(f"{os.path.basename(path)} {q.find('idnumber').text}: weights sum to "
                         f"{total}, defaultgrade {grade}")
    assert not wrong, wrong


THIRDS = """
title: thirds
frame: {A: [0, 0], D: [100, 0]}
points: {B: [0, 40], C: [90, 60]}
links: {AB: {points: [A, B], length: 40}, BC: {points: [B, C], length: 100},
        CD: {points: [C, D], length: 60}}
driver: {angle: [A, B], value: 90, rate: 10}
loads: {F: {type: force, at: C, x: 10}, M: {type: driver, value: unknown}}
quantities: {phi2: {angle: [B, C]}, phi3: {angle: [C, D]}, a: {length: [A, C]},
             b: {length: [B, D]}, c: {x: C}, d: {y: C}}
report: {position: [phi2, phi3, a, b, c, d], velocity: [phi2dot, phi3dot, adot, bdot, cdot,
         ddot], statics: [F, M]}
quiz: {points: {position: 33.33, velocity: 33.33, statics: 33.34}}
"""


def test_points_with_two_decimals_give_a_mark_moodle_can_store():
    """The issue's 33.33 / 33.33 / 33.34 made box weights 13332 / 9999 / 26672: a mark of
    over 100 000, which stopped Moodle's import with a numeric field overflow."""
    (q,) = _cloze(ET.fromstring(moodle.export(load_text(THIRDS, "thirds.yaml"), None,
                                              figure=False)))
    boxes = _boxes(q)
    total = sum(b.weight for b in boxes)
    assert total == float(q.find("defaultgrade").text)
    assert total < MARK_LIMIT
    shares = [sum(b.weight for b in boxes[:6]), sum(b.weight for b in boxes[6:12]),
              sum(b.weight for b in boxes[12:])]
    assert [s / total for s in shares] == pytest.approx([1 / 3] * 3, abs=0.001)


# --- numbers Moodle stores exactly -----------------------------------------------------------
def _digits_broken(root):
    bad = []
    for q in _cloze(root):
        for box in _boxes(q):
            for answer in box.answers:
                for text in _raw(answer):
                    if float(text) != _stored(text):
                        bad.append(f"{q.find('idnumber').text}: {answer.raw_text}")
    return bad


def test_every_value_and_tolerance_survives_fourteen_digits(quizzes):
    bad = [f"{os.path.basename(p)} {b}" for p, root in quizzes.items()
           if not isinstance(root, Exception) for b in _digits_broken(root)]
    assert not bad, bad[:10]


def test_the_largest_decimals_are_stored_exactly_or_refused():
    """--decimals 12 wrote 15 or more significant digits, and Moodle graded the exact value
    wrong; now every value is kept or the export says which value needs fewer decimals."""
    bad = []
    for path in SHIPPED:
        try:
            root = ET.fromstring(_export(path, decimals=12))
        except InputError as exc:
            if "14" not in str(exc) and "significant" not in str(exc):
                bad.append(f"{os.path.basename(path)}: refused without the reason: {exc}")
            continue
        bad += [f"{os.path.basename(path)} {b}" for b in _digits_broken(root)]
    assert not bad, bad[:10]


# --- the figure's link -----------------------------------------------------------------------
def test_figure_links_decode_to_the_stored_file_name(quizzes, tmp_path):
    hostile = tmp_path / "esame 26 gennaio #1 è?%20.yaml"
    hostile.write_text(open(SHIPPED[0], encoding="utf-8").read(), encoding="utf-8")
    roots = list(quizzes.values()) + [ET.fromstring(_export(str(hostile)))]
    bad = []
    for root in roots:
        if isinstance(root, Exception):
            continue
        for q in _cloze(root):
            stored = q.find("questiontext/file").get("name")
            text = q.find("questiontext/text").text
            start = text.index("@@PLUGINFILE@@/") + len("@@PLUGINFILE@@/")
            link = text[start:text.index('"', start)]
            decoded = "/".join(urllib.parse.unquote(part) for part in link.split("/"))
            if decoded != stored or any(c in link for c in ' #?'):
                bad.append(f"{link!r} for {stored!r}")
    assert not bad, bad


# --- angles ----------------------------------------------------------------------------------
def test_every_angle_box_accepts_both_equivalent_angles(quizzes):
    bad, count = [], 0
    for path, q, boxes in _each(quizzes):
        mech = build(load_file(path), _digit(q))
        for name, box in zip(_names(mech), boxes):
            unit = _unit_of(q, box)
            period = angle_period(mech, name, unit)
            if period is None:
                continue
            count += 1
            value = box.correct[0].value
            other = value - period if value >= 0 else value + period
            for response in (value, other):
                if moodle_grade(box, response) != 100:
                    bad.append(f"{os.path.basename(path)} {name}: {response:g} scores "
                               f"{moodle_grade(box, response)}")
    assert count > 100                     # the shipped files ask over a hundred angles
    assert not bad, bad[:10]


def _unit_of(question, box):
    """The unit printed after a box in its table row."""
    text = question.find("questiontext/text").text
    row_end = text.index("</tr>", box.end)
    cell = text[box.end:row_end]
    return cell.replace("</td>", "").replace("<td>", "").strip()


# --- printed keys ----------------------------------------------------------------------------
def test_every_printed_key_check_accepts_scores_full_marks(quizzes):
    bad, count = [], 0
    for path, root in quizzes.items():
        if isinstance(root, Exception):
            bad.append(f"{os.path.basename(path)}: {root}")
            continue
        report = check_file(path)
        questions = {_digit(q): q for q in _cloze(root)}
        for outcome in report.outcomes:
            q = questions.get(outcome.k)
            if outcome.status != "pass" or q is None:
                continue
            mech = build(load_file(path), outcome.k)
            names = _names(mech)
            if outcome.name not in names:
                continue
            box = _boxes(q)[names.index(outcome.name)]
            count += 1
            printed = float(outcome.printed)
            if moodle_grade(box, printed) != 100:
                bad.append(f"{os.path.basename(path)} k={outcome.k} {outcome.name}: "
                           f"printed {outcome.printed} scores {moodle_grade(box, printed)} "
                           f"in {box.answers[0].raw_text}")
    assert count > 200                     # the shipped keys print over two hundred answers
    assert not bad, bad[:12]
