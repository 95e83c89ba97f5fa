"""A quiz's question states the whole problem, and its figure gives no answer away.

- Every number the solver reads is in the question's own text.  The numbers of a file
  are its YAML's numeric leaves (outside the title, source, notes, statement, report,
  keys, quiz and params), evaluated for the question's digit.  Each must be stated in
  the question's data or in its table's descriptions (as its value, or, for an
  expression, as the numbers it is made of); a number the text leaves out must be one
  the solver does not read: changed by one part in ten thousand, it changes no answer.
- Every number drawn in the exam's figure is stated in the data, and none equals an
  answer that the data do not give.
"""
from __future__ import annotations

import ast
import copy
import os
import re
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))

from quizzes import METHOD, SHIPPED, Parts, boxes, digit, html_of, questions, shipped  # noqa: E402
from linkcli.answers.quantities import report_names  # noqa: E402
from linkcli.runs.sheet import evaluate  # noqa: E402
from linkcli.input import expressions  # noqa: E402
from linkcli.input.document import build  # noqa: E402
from linkcli.input.source import Document, load_file  # noqa: E402

NOT_DATA = {"title", "source", "notes", "statement", "report", "keys", "quiz", "params", "k",
            "units"}
CLOSE = 1e-9                 # relative agreement of a stated number (ten digits are written)
NUMBER = {"it": re.compile(r"(?<![\w.,])-?\d+(?:,\d+)?(?:e[-+]?\d+)?"),
          "en": re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[-+]?\d+)?")}


def numbers(text: str, lang: str) -> list:
    """The sizes of the numbers a reader sees in ``text`` (a name's digits, as in 'B0' or
    'phi1', are not numbers)."""
    return [abs(float(m.group(0).replace(",", "."))) for m in NUMBER[lang].finditer(text)]


def stated(value: float, found) -> bool:
    return any(abs(n - abs(value)) <= CLOSE * abs(value) for n in found)


def printed(texts, lang: str) -> list:
    """(size, decimals) of each number a reader sees in ``texts``."""
    found = [m.group(0) for t in texts for m in NUMBER[lang].finditer(t)]
    return [(abs(float(n.replace(",", "."))), len(re.split(r"[.,]", n + ".")[1]))
            for n in found]


def stated_as_drawn(number, found) -> bool:
    """Whether ``number`` (size, decimals) is a datum of ``found`` at its printed precision:
    a figure draws a length that no short decimal writes rounded (sqrt(2) m as 1.41 m),
    never to a whole number."""
    value, decimals = number
    return stated(value, found) or decimals > 0 and \
        any(abs(round(n, decimals) - value) <= CLOSE * max(value, 1.0) for n in found)


def leaves(node, path=()):
    if isinstance(node, dict):
        for key, value in node.items():
            yield from leaves(value, path + (key,))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from leaves(value, path + (i,))
    else:
        yield path, node


def made_of(leaf, names, found) -> bool:
    """Whether an expression is made of stated numbers: its literals and the parameters it
    names (stated, or made of stated numbers in turn); k is the question's own digit."""
    if not isinstance(leaf, str):
        return False
    for node in ast.walk(ast.parse(leaf.strip(), mode="eval")):
        if isinstance(node, ast.Constant) and not stated(node.value, found):
            return False
        if isinstance(node, ast.Name) and node.id in names and node.id != "k" and \
                not stated(names[node.id], found):
            return False
    return True


def question_text(path, lang="it"):
    """(the mechanism of the file's own digit, its question's data and descriptions)."""
    doc = load_file(path)
    mech = build(doc)
    root = shipped(lang)[path]
    if isinstance(root, Exception):
        raise AssertionError(f"{os.path.basename(path)}: {root}")
    (q,) = [q for q in questions(root) if digit(q) == mech.k]
    parts = Parts(html_of(q))
    described = [row[1] for row in parts.rows if len(row) == 4]
    return doc, mech, q, "\n".join(parts.items + described)


def _answers(doc, method):
    mech = build(doc)
    result = evaluate(mech, method=method) if method != "closed" else evaluate(mech)
    return {n: float(np.ravel(result.values[n])[0]) for n in report_names(mech)}


def _perturbed(doc, path, leaf):
    data = copy.deepcopy(doc.data)
    node = data
    for part in path[:-1]:
        node = node[part]
    node[path[-1]] = f"({leaf}) * 1.0001 + 0.0001" if isinstance(leaf, str) else \
        leaf * 1.0001 + 0.0001
    return Document(doc.name, data, doc.lines, doc.raw)


@pytest.mark.parametrize("path", SHIPPED, ids=os.path.basename)
def test_every_number_the_solver_reads_is_in_the_question(path):
    doc, mech, _, text = question_text(path)
    found = numbers(text, "it")
    names = {**mech.params, "k": mech.k or 0}
    method = METHOD.get(os.path.basename(path), "closed")
    unknowns = set(mech.design.names) if mech.design is not None else set()
    before, unstated = None, []
    for where, leaf in leaves(doc.data):
        if where[0] in NOT_DATA:
            continue
        if isinstance(leaf, str) and leaf.strip() in unknowns and \
                re.search(rf"= {re.escape(leaf.strip())}\b", text):
            continue        # a design question's unknown: stated by its name, and asked
        try:
            value = expressions.evaluate(leaf, names)
        except Exception:            # noqa: BLE001 - a name, a word: not a number
            continue
        if stated(value, found) or made_of(leaf, names, found):
            continue
        before = before or _answers(doc, method)
        try:
            after = _answers(_perturbed(doc, where, leaf), method)
        except Exception:            # noqa: BLE001 - a count or an index: not a measure
            continue
        if any(abs(after[n] - before[n]) > 1e-7 * max(abs(before[n]), abs(after[n]), 1e-6)
               for n in before):
            unstated.append(".".join(map(str, where)) + f" = {leaf!r}")
    assert not unstated, f"read by the solver, not in the question: {unstated}"


def test_the_data_are_worded_in_english_too():
    path = os.path.join(os.path.dirname(SHIPPED[0]), "padova-2020-02.yaml")
    _, _, _, text = question_text(path, "en")
    assert "driver: q = length AB = 250 mm, q' = 100 mm/s (lengthening)" in text
    assert "force Fx = -450 N at E, along x" in text
    assert "D at 90 mm from B, at 90° from B→C" in text


# --- the exam's figure ------------------------------------------------------------------------
def _figure_numbers(mech, lang, method):
    from matplotlib.text import Text

    from linkcli.pictures.exam import exam_figure
    fig = exam_figure(mech, lang, method)
    texts = [t.get_text() for t in fig.findobj(Text)]
    return texts, numbers("\n".join(texts), lang)


@pytest.mark.parametrize("path", SHIPPED, ids=os.path.basename)
def test_the_exam_figure_draws_data_and_no_answer(path):
    pytest.importorskip("matplotlib")
    _, mech, q, text = question_text(path)
    data = numbers(text, "it")
    texts, drawn = _figure_numbers(mech, "it", METHOD.get(os.path.basename(path), "closed"))
    assert all(stated_as_drawn(n, data) for n in printed(texts, "it")), (texts, data)
    answers = [abs(a.value) for b in boxes(q) for a in b.answers if a.value is not None]
    given = [a for a in answers if stated(a, data)]
    solved = [a for a in answers if a not in given]
    assert not [n for n in drawn if stated(n, solved)], texts


def _svg_texts(draw, mech, tmp_path):
    """The texts of a picture written as SVG with its text kept as text."""
    import matplotlib
    import xml.etree.ElementTree as ET
    out = tmp_path / "figure.svg"
    with matplotlib.rc_context({"svg.fonttype": "none"}):
        draw(mech, str(out))
    return [t.text or "" for t in ET.parse(out).iter() if t.tag.endswith("text")] + \
        [t.text or "" for t in ET.parse(out).iter() if t.tag.endswith("tspan")]


def test_the_check_finds_the_answers_draw_labels(tmp_path):
    """draw's figure (the vector polygon with its solved angles, the solved load) is what
    the quiz embedded before: the check above flags it; the exam's figure, written by
    `draw --exam`, passes it."""
    pytest.importorskip("matplotlib")
    from linkcli.pictures.exam import draw_exam
    from linkcli.pictures.plotting import draw
    path = os.path.join(os.path.dirname(SHIPPED[0]), "padova-2020-02.yaml")
    _, mech, q, text = question_text(path)
    data = numbers(text, "it")
    answers = [abs(a.value) for b in boxes(q) for a in b.answers if a.value is not None]
    solved = [a for a in answers if not stated(a, data)]
    shown = numbers("\n".join(_svg_texts(draw, mech, tmp_path)), "en")
    assert {52.2, 314.8, 44.8, 15.5, 526.0} <= {round(n, 1) for n in shown if stated(n, solved)}
    exam = _svg_texts(lambda m, o: draw_exam(m, o, lang="it"), mech, tmp_path)
    drawn = numbers("\n".join(exam), "it")
    assert {250, 100, 450, 220, 320} <= set(drawn)
    assert all(stated(n, data) for n in drawn) and not [n for n in drawn if stated(n, solved)]
