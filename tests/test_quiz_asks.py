"""The quiz asks what the statement asks, by the file: ``quiz.ask_given`` and ``quiz.not_asked``.

- ``quiz: {ask_given: false}`` writes the same quiz as ``export --no-given``, and the count
  line on standard error says that the file leaves the given values out.
- padova-2023-01's statement asks the velocities of the first loop only (the actuator BC
  and the rocker ACD, D on it): the quiz's velocity boxes are exactly the report's names
  whose points the first group of the decomposition solves (read from the solver's groups,
  not from the file's list), while ``solve`` still prints the second loop's phi4dot and
  phi5dot and ``check`` compares them with the published key.
- A name of ``quiz.not_asked`` that the report does not list, or an ``ask_given`` that is
  not true or false, is refused with the key and its line.
"""
from __future__ import annotations

import os
import re
import sys
import xml.etree.ElementTree as ET

import pytest

sys.path.insert(0, os.path.dirname(__file__))

from cli_helpers import run  # noqa: E402
from quizzes import Parts, export, html_of, questions  # noqa: E402
from linkcli.input.document import build  # noqa: E402
from linkcli.input.source import load_file  # noqa: E402
from linkcli.kinematics.solvers import solver_for  # noqa: E402
from linkcli.model.mechanism import split_rate  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
P2023 = os.path.join(ROOT, "mechanisms", "padova-2023-01.yaml")
P2020 = os.path.join(ROOT, "mechanisms", "padova-2020-02.yaml")


def _with_quiz(path, tmp_path, line) -> str:
    """A copy of ``path`` whose quiz section gains ``line`` (a 'quiz:' section added where
    the file has none)."""
    text = open(path, encoding="utf-8").read()
    if re.search(r"^quiz:", text, re.M):
        text = re.sub(r"^quiz:.*$", lambda m: m.group(0) + "\n  " + line, text, count=1,
                      flags=re.M)
    else:
        text += f"quiz:\n  {line}\n"
    out = tmp_path / os.path.basename(path)
    out.write_text(text, encoding="utf-8")
    return str(out)


def test_ask_given_false_is_no_given(tmp_path):
    path = _with_quiz(P2020, tmp_path, "ask_given: false")
    assert export(path) == export(P2020, no_given=True)
    code, _, err = run(["export", path, "--to", "moodle", "--no-figure", "-o",
                        str(tmp_path / "q.xml")])
    assert code == 0, err
    assert "3 of 14 boxes ask a value the question gives (left out by the file's " \
        "quiz.ask_given: false)" in err


def _points_of(mech, name) -> set:
    """The points a report name is measured on: its quantity's points, or the point P of
    a derived xP, yP."""
    base, _ = split_rate(name, mech.quantities)
    q = mech.quantities.get(base)
    if q is not None:
        return {p for p in (q.a, q.b) if p is not None}
    return {base[1:]}


def _first_loop(mech) -> set:
    """The points known once the decomposition's first dyad (and what is placed on it) is
    solved: the fixed points and those the groups up to the second dyad solve."""
    known, dyads = set(mech.fixed), 0
    for group in solver_for(mech).groups:
        dyads += group.is_dyad
        if dyads > 1:
            break
        if group.point is not None:
            known.add(group.point)
    return known


def test_padova_2023_01_asks_the_first_loops_velocities():
    mech = build(load_file(P2023), None)
    first = _first_loop(mech)
    velocity = mech.report["velocity"]
    expected = {n for n in velocity if _points_of(mech, n) <= first}
    assert set(velocity) - expected == {"phi4dot", "phi5dot"}       # the second loop's
    question = questions(ET.fromstring(export(P2023)))[0]
    asked = {row[0] for row in Parts(html_of(question)).rows} & set(velocity)
    assert asked == expected


def test_padova_2023_01_still_prints_and_checks_the_second_loop(tmp_path):
    code, out, _ = run(["solve", P2023])
    assert code == 0 and "phi4dot" in out and "phi5dot" in out
    code, out, _ = run(["check", P2023])
    assert code == 0 and re.search(r"\d+ passed, 0 failed", out), out


@pytest.mark.parametrize("line, key", [
    ("not_asked: [phi9dot]", "quiz.not_asked[0]"),
    ("ask_given: 'no'", "quiz.ask_given"),
])
def test_a_wrong_quiz_setting_is_refused_with_its_key(tmp_path, line, key):
    path = _with_quiz(P2020, tmp_path, line)
    code, out, err = run(["validate", path])
    assert code == 2 and re.search(rf"\.yaml:\d+, key '{re.escape(key)}'", out + err), out + err
