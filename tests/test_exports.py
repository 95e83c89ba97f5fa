"""Exports: the Moodle question bank and the worked solution.

The XML is read with the standard library's parser; every answer box is read
with an independent Cloze parser written from Moodle's grammar
(``cloze_grammar``) and compared with ``batch`` for its digit."""
from __future__ import annotations

import html
import os
import sys
import xml.etree.ElementTree as ET
from html.parser import HTMLParser

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))

import linkcli  # noqa: E402
from cloze_grammar import parse as parse_cloze  # noqa: E402
from linkcli.runs.batch import run as batch  # noqa: E402
from linkcli.errors import InputError  # noqa: E402
from linkcli.exports import moodle, worked  # noqa: E402
from linkcli.input.source import load_file, load_text  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MECH = os.path.join(ROOT, "mechanisms")


def _questions(xml_text):
    root = ET.fromstring(xml_text)
    assert root.tag == "quiz"
    return root, [q for q in root if q.get("type") == "cloze"]


def _boxes(question):
    text = question.find("questiontext/text").text
    return text, parse_cloze(text)


def test_padova_2020_02_has_one_question_per_digit_with_batch_values():
    doc = load_file(os.path.join(MECH, "padova-2020-02.yaml"))
    root, questions = _questions(moodle.export(doc, list(range(10)), figure=False))
    category = root.find("question[@type='category']/category/text").text
    assert category == "$course$/top/linkcli/padova-2020-02"
    assert len(questions) == 10
    columns, _, rows, _, failures = batch(doc, list(range(10)))
    assert not failures
    for k, q in enumerate(questions):
        assert q.find("name/text").text.endswith(f"(k = {k})")
        _, boxes = _boxes(q)
        mech = linkcli.loads(open(os.path.join(MECH, "padova-2020-02.yaml")).read(), k=k).model
        names = [n for s in ("position", "velocity", "acceleration", "statics", "vibration")
                 for n in mech.report.get(s, [])]
        assert len(boxes) == len(names)
        for name, box in zip(names, boxes):
            assert box.qtype == "NUMERICAL"
            answer = box.answers[0]
            assert all(a.fraction == 100 for a in box.answers)
            assert len(box.answers) == (2 if name.startswith("phi") and
                                        not name.endswith("dot") else 1)
            expected = round(rows[k][1 + columns.index(name)], 1)
            assert answer.value == pytest.approx(expected, abs=1e-9), (k, name)
            assert answer.tolerance == pytest.approx(0.05)


def test_points_per_section_become_integer_weights():
    doc = load_file(os.path.join(MECH, "padova-2023-01.yaml"))
    _, (q,) = _questions(moodle.export(doc, None, figure=False))
    _, boxes = _boxes(q)
    assert float(q.find("defaultgrade").text) == sum(b.weight for b in boxes)
    mech = linkcli.load(os.path.join(MECH, "padova-2023-01.yaml")).model
    shares = {}
    for section in ("position", "velocity", "statics"):
        n = len([x for x in mech.report[section] if x not in mech.quiz.not_asked])
        shares[section] = sum(b.weight for b in boxes[:n])
        boxes = boxes[n:]
    total = sum(shares.values())
    assert shares["position"] / total == pytest.approx(9 / 15)
    assert shares["velocity"] / total == pytest.approx(4 / 15)
    assert shares["statics"] / total == pytest.approx(2 / 15)


def test_figure_is_embedded_as_a_plugin_file():
    pytest.importorskip("matplotlib")
    doc = load_file(os.path.join(MECH, "padova-2020-07.yaml"))
    _, (q,) = _questions(moodle.export(doc, None))
    text = q.find("questiontext/text").text
    f = q.find("questiontext/file")
    assert f.get("encoding") == "base64" and f.get("path") == "/"
    assert f'@@PLUGINFILE@@/{f.get("name")}' in text
    import base64
    assert base64.b64decode(f.text)[:8] == b"\x89PNG\r\n\x1a\n"


HOSTILE = """
title: "<script>alert(1)</script> ]]> {1:NUMERICAL:=666} & co"
statement: "a statement with <b>tags</b>, braces {} and ]]>"
frame: {A: [0, 0], D: [100, 0]}
points: {B: [0, 40], C: [90, 60]}
links: {AB: {points: [A, B], length: 40}, BC: {points: [B, C], length: 100},
        CD: {points: [C, D], length: 60}}
driver: {angle: [A, B], value: 90, rate: 10}
quantities: {phi: {angle: [B, C]}}
report: {position: [phi]}
"""


def test_text_from_the_file_cannot_break_the_xml_or_the_cloze():
    xml_text = moodle.export(load_text(HOSTILE, "hostile.yaml"), None, figure=False)
    _, (q,) = _questions(xml_text)                 # parses: the XML is intact
    text, boxes = _boxes(q)
    assert len(boxes) == 1                          # the title's fake box is not a box
    assert "<script>" not in text and "&lt;script&gt;" in text
    assert q.find("name/text").text.startswith("<script>")   # the name is plain text


@pytest.mark.parametrize("ks, message", [([0, 1], "does not depend on k")])
def test_k_range_on_a_file_without_k(ks, message):
    with pytest.raises(InputError, match=message):
        moodle.export(load_text(HOSTILE, "h.yaml"), ks, figure=False)


def test_tolerance_must_be_positive():
    with pytest.raises(InputError, match="tolerance must be positive"):
        moodle.export(load_text(HOSTILE, "h.yaml"), None, tolerance=0.0, figure=False)


class _Collect(HTMLParser):
    def __init__(self):
        super().__init__()
        self.tags, self.srcs, self.text = [], [], []

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        self.srcs += [v for k, v in attrs if k in ("src", "href") and v]

    def handle_data(self, data):
        self.text.append(data)


@pytest.mark.parametrize("name", ["padova-2020-07.yaml", "fourbar-inverse-dynamics.yaml",
                                  "polimi-2001-09-18-vibration.yaml"])
def test_worked_solution_is_one_self_contained_page(name):
    pytest.importorskip("matplotlib")
    mech = linkcli.load(os.path.join(MECH, name)).model
    page = worked.to_html(worked.blocks(mech, "en"))
    p = _Collect()
    p.feed(page)
    assert "table" in p.tags and "svg" in p.tags
    assert not [s for s in p.srcs if s.startswith(("http", "//"))]
    text = html.unescape("".join(p.text))
    result = linkcli.load(os.path.join(MECH, name)).solve()
    first = (mech.report.get("position") or mech.report.get("vibration"))[0]
    decimals = mech.report.get("decimals", 1)
    assert f"{float(np.ravel(result.values[first])[0]):.{decimals}f}" in text


def test_worked_solution_in_italian_and_markdown():
    mech = linkcli.load(os.path.join(MECH, "padova-2020-07.yaml")).model
    md = worked.to_markdown(worked.blocks(mech, "it", figure=False))
    assert "## Dati" in md and "## Risultati" in md
    assert "| Analisi Cinematica di POSIZIONE | valore | unità |" in md
    assert "Statica" in md or "STATICA" in md


def test_worked_solution_renders_in_a_headless_browser(tmp_path):
    """Chromium (Debian's package) loads the page: no console error, the results table in
    the DOM, and a screenshot saved for a person to look at (tmp_path/solution.png)."""
    import shutil
    import subprocess
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        pytest.skip("chromium is not installed (apt-get install chromium)")
    pytest.importorskip("matplotlib")
    mech = linkcli.load(os.path.join(MECH, "padova-2020-07.yaml")).model
    page = tmp_path / "solution.html"
    page.write_text(worked.to_html(worked.blocks(mech, "it")), encoding="utf-8")
    flags = ["--headless", "--no-sandbox", "--disable-gpu", "--enable-logging=stderr", "--v=0",
             f"--user-data-dir={tmp_path / 'profile'}"]
    dom = subprocess.run([browser, *flags, "--dump-dom", page.as_uri()], capture_output=True,
                         text=True, timeout=120)
    assert dom.returncode == 0, dom.stderr[-2000:]
    assert '<table class="results">' in dom.stdout and "phi1" in dom.stdout
    console = [line for line in dom.stderr.splitlines() if "CONSOLE" in line]
    assert console == [], console
    shot = tmp_path / "solution.png"
    subprocess.run([browser, *flags, f"--screenshot={shot}", "--window-size=1100,2600",
                    page.as_uri()], capture_output=True, timeout=120)
    assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def _with_points(points: str, extra: str = "") -> str:
    return HOSTILE.replace('title: "<script>', 'title: "x').replace(
        "report: {position: [phi]}", "loads: {F: {type: force, at: C, x: 10}, M: {type: driver, "
        "value: unknown}}\nreport: {position: [phi], velocity: [phidot], statics: [M]}\n"
        f"quiz: {{points: {points}{extra}}}")


@pytest.mark.parametrize("points, weights", [
    ("{position: 9, velocity: 9, statics: 2}", {"position": 9, "velocity": 9, "statics": 2}),
    ("{position: 1, velocity: 1, statics: 2}", {"position": 1, "velocity": 1, "statics": 2}),
])
def test_whole_points_one_per_box_are_the_weights(points, weights):
    """Points that fall whole on each box are the weights, and the mark is their sum."""
    mech = linkcli.loads(_with_points(points)).model
    assert moodle.weights(mech) == (weights, sum(weights.values()))


@pytest.mark.parametrize("points", ["{position: 0.5, velocity: 0.5, statics: 1}",
                                    "{position: 1, velocity: 2, statics: 3.3}",
                                    "{position: 33.33, velocity: 33.33, statics: 33.34}",
                                    "{position: 7, velocity: 0.1, statics: 1}"])
def test_other_points_become_the_smallest_weights_that_keep_their_ratio(points):
    """Each section's share of the mark within 0.1 % of its share of the points, and no
    smaller mark does it (every smaller triple of whole weights tried: one box each)."""
    import itertools
    mech = linkcli.loads(_with_points(points)).model
    given = mech.quiz.points
    target = [given[s] / sum(given.values()) for s in ("position", "velocity", "statics")]
    chosen, mark = moodle.weights(mech)
    found = [chosen[s] for s in ("position", "velocity", "statics")]
    assert sum(found) == mark

    def keeps(w):
        return all(abs(x / sum(w) - t) <= 0.001 + 1e-12 for x, t in zip(w, target))
    assert keeps(found)
    smaller = [w for w in itertools.product(range(1, mark), repeat=3)
               if sum(w) < mark and keeps(w)]
    assert smaller == []


def test_points_must_cover_every_section_of_the_report():
    mech = linkcli.loads(_with_points("{position: 9, statics: 2}")).model
    with pytest.raises(InputError, match="no points to the report's velocity section"):
        moodle.weights(mech)


def test_tolerances_are_written_with_all_their_digits():
    """:g wrote six digits (0.0123457 for 0.0123456789); a tolerance longer than Moodle's
    14 digits is rounded up, never down."""
    from decimal import Decimal
    doc = load_text(HOSTILE.replace("report:", "quiz: {tolerance: 0.0123456789}\nreport:"),
                    "t.yaml")
    _, (q,) = _questions(moodle.export(doc, None, figure=False))
    _, (box,) = _boxes(q)
    assert {a.raw_text.split(":")[1] for a in box.answers} == {"0.0123456789"}
    assert moodle.written(Decimal("0.12345678901234567")) == "0.12345678901235"
    assert moodle.written(Decimal("5E-13")) == "0.0000000000005"


@pytest.mark.parametrize("lang, words, number", [("it", "virgola decimale", "12,5"),
                                                 ("en", "decimal point", "12.5")])
def test_the_question_says_which_decimal_separator_the_boxes_read(lang, words, number):
    doc = load_file(os.path.join(MECH, "padova-2020-07.yaml"))
    _, (q,) = _questions(moodle.export(doc, None, lang=lang, figure=False))
    text = html.unescape(q.find("questiontext/text").text)
    assert words in text and f"({number})" in text


def test_draw_exam_and_export_newton_from_the_command_line(tmp_path):
    pytest.importorskip("matplotlib")
    from linkcli.cli import main
    picture = tmp_path / "esame.png"
    assert main(["draw", os.path.join(MECH, "triad-class3.yaml"), "--exam", "--method",
                 "newton", "-o", str(picture)]) == 0
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    quiz = tmp_path / "triad.xml"
    assert main(["export", os.path.join(MECH, "triad-class3.yaml"), "--to", "moodle",
                 "--no-figure", "-o", str(quiz)]) == 3       # the closed form refuses a triad
    assert main(["export", os.path.join(MECH, "triad-class3.yaml"), "--to", "moodle",
                 "--method", "newton", "--no-figure", "-o", str(quiz)]) == 0
    _, (q,) = _questions(quiz.read_text(encoding="utf-8"))
    assert len(_boxes(q)[1]) == 15
