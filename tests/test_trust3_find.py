"""Design unknowns (``find:``) at the edges: a sign change across a jump (an angle's wrap, a
pole) is no root; an interval of hundreds of decades is sampled by decades and each root
refined relative to its size; the samples met next to values that cannot be solved bracket
roots too; ``choose: {nearest: V}`` is read in the interval's unit; the trials are solved by
the method asked.  Each file of tests/data/trust3/ states what is right in its header."""
from __future__ import annotations

import math
import os
import re

import numpy as np
import pytest
from scipy.optimize import brentq, fsolve

from cli_helpers import run

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data", "trust3")


def path(name):
    return os.path.join(DATA, name)


def crank_roots(target=1.9, b2=2.0):
    """The cranks a of the centred crank-slider (rod^2 = b2) at 45 deg with the slider at
    ``target``: with s = a / sqrt 2, s + sqrt(b2 - s^2) = c gives 2 s^2 - 2 c s + c^2 - b2
    = 0."""
    disc = math.sqrt(4 * target ** 2 - 8 * (target ** 2 - b2))
    return sorted(math.sqrt(2) * (2 * target + sign * disc) / 4 for sign in (-1, 1))


def printed(out, name):
    """The value of ``name`` on its line of linkcli's exam table."""
    found = re.search(rf"^\s*{name}\s*=\s*(-?[\d.]+)", out, re.M)
    assert found, out
    return found.group(1)


def test_the_closed_form_roots():
    small, large = crank_roots()
    assert f"{small:.4f}" == "0.9019" and f"{large:.4f}" == "1.7851"      # the headers'


def test_an_angle_wrap_is_no_root():
    """phi = th + 360 for th in [-180, 0] runs over [180, 360]: no th gives phi = 80; the
    difference phi - 80 wraps at phi = 260 (th = -100), which was taken as a root."""
    code, out, err = run(["solve", path("find-angle-antipode.yaml")])
    assert code == 3 and not out, out
    assert "no value of th in [-180, 0] gives phi = 80 deg" in err, err
    assert "wraps" in err and "th = -100 deg" in err, err


def test_a_pole_is_no_root():
    """r = 1/(c - 2a) is never 0; it changes sign through its pole at c = 2a."""
    code, out, err = run(["solve", path("find-unreachable-pole.yaml")])
    assert code == 3 and not out, out
    assert "no value of a in [0.5, 1.5] gives r = 0 1/m" in err, err
    assert "a pole" in err, err
    # the pole's place: c(a) = 2a, a / sqrt 2 + sqrt(2 - a^2 / 2) = 2a
    pole = brentq(lambda a: a / math.sqrt(2) + math.sqrt(2 - a * a / 2) - 2 * a, 0.5, 1.5)
    assert f"a = {pole:.6g} m" in err, err


@pytest.mark.parametrize("name", ["find-wide-interval.yaml", "find-false-no-root.yaml"])
def test_a_wide_interval_finds_the_smallest_root(name):
    """[0.1, 1e300] m and [0.1, 1e10] m: the mechanism assembles for a < 2 m only; the two
    roots lie there and 'smallest' takes 0.9019 m."""
    code, out, err = run(["solve", path(name)])
    assert code == 0, err
    assert printed(out, "a") == f"{crank_roots()[0]:.4f}" == "0.9019"
    assert printed(out, "c") == "1.9000"


def test_nearest_is_read_in_the_intervals_unit():
    """The interval in mm, nearest: 900 is 900 mm (0.9019 m, not 1.7851 m); a value with its
    own unit is converted from it; one of another dimension is refused."""
    text = open(path("find-nearest-unit.yaml"), encoding="utf-8").read()
    small, large = crank_roots()
    code, out, err = run(["solve", path("find-nearest-unit.yaml")])
    assert code == 0 and printed(out, "a") == f"{small:.4f}", err
    for nearest, expected in (("1700", large), ("1.7 m", large), ("1000 mm", small),
                              ("0.95 m", small)):
        code, out, err = run(["solve", "-"], stdin=text.replace("nearest: 900",
                                                                 f"nearest: {nearest}"))
        assert code == 0 and printed(out, "a") == f"{expected:.4f}", (nearest, out, err)
    code, out, err = run(["solve", "-"], stdin=text.replace("nearest: 900", "nearest: 1 kg"))
    assert code == 2 and "key 'find.choose.nearest'" in err and "'kg' is a mass" in err, err


def _triad_c(a, guess=(80.0, 80.0, 0.0)):
    """x of C in the crank-and-triad of find_structure_error_advice.yaml, solved here by
    its closure: B = a (cos 53, sin 53); the body CDE (local C (0, 0), D (82, -20), E (30,
    50), turned by t) with |BC| = 64, |FD| = 72, |GE| = 71."""
    b = a * np.array([math.cos(math.radians(53)), math.sin(math.radians(53))])
    f, g = np.array([200.0, 0.0]), np.array([100.0, 200.0])

    def turn(t, v):
        return np.array([math.cos(t) * v[0] - math.sin(t) * v[1],
                         math.sin(t) * v[0] + math.cos(t) * v[1]])

    def closure(u):
        c = u[:2]
        d, e = c + turn(u[2], (82, -20)), c + turn(u[2], (30, 50))
        return [np.hypot(*(c - b)) - 64, np.hypot(*(d - f)) - 72, np.hypot(*(e - g)) - 71]
    u, _, ok, _ = fsolve(closure, guess, full_output=True, xtol=1e-13)
    assert ok == 1 and max(map(abs, closure(u))) < 1e-9
    return u[0]


def test_the_trials_are_solved_by_the_method_asked():
    """A class-III group: only --method newton solves it; the design question's trials are
    solved so.  The crank that gives c = 85 mm, by this test's own closure (which gives the
    header's 81.67 mm at a = 50 and 87.83 mm at 55)."""
    assert f"{_triad_c(50):.2f}" == "81.67" and f"{_triad_c(55):.2f}" == "87.83"
    root = brentq(lambda a: _triad_c(a) - 85, 49, 55, xtol=1e-12)
    file = path("find_structure_error_advice.yaml")
    code, out, err = run(["solve", file, "--method", "newton"])
    assert code == 0, err
    assert printed(out, "a") == f"{root:.1f}" and printed(out, "c") == "85.0"
    # the closed form cannot solve it at any value: the structure's own advice, no trial's
    code, out, err = run(["solve", file])
    assert code == 3 and "--method newton" in err and "narrow the search" not in err, err


# --- the documents of a design question ------------------------------------------------------
def _quiz_text(file, lang="en"):
    import html
    import xml.etree.ElementTree as ET
    from linkcli.exports.moodle import export
    from linkcli.input.source import load_file
    root = ET.fromstring(export(load_file(file), None, lang=lang, figure=False))
    (q,) = [q for q in root if q.get("type") == "cloze"]
    return html.unescape(q.find("questiontext/text").text)


def _crank_statement_holds(text):
    """The crank's length is asked, never stated at the file's figure value (OA = 1 m);
    what the unknown is and the target with its unit are said."""
    assert "OA = 1 m" not in text and "OA = a" in text, text
    assert "find a (the length of OA) such that c = 1.9 m (x of B)" in text, text


def test_the_quiz_asks_the_unknown_and_states_the_target():
    file = os.path.join(ROOT, "docs", "examples", "design-crank.yaml")
    text = _quiz_text(file)
    _crank_statement_holds(text)
    boxes = re.findall(r"<tr><td>(\w+)</td><td>([^<]*)</td><td>\{1:NUMERICAL:=([-\d.]+)", text)
    assert [(n, d) for n, d, _ in boxes] == [("a", "the length of OA"),
                                             ("beta", "angle of A→B from +x")], boxes
    assert boxes[0][2] == f"{crank_roots()[0]:.4f}"
    # beta, the rod's angle at the solution, by the closed form: A = a (cos 45, sin 45)
    a = crank_roots()[0]
    beta = math.degrees(math.atan2(-a / math.sqrt(2), 1.9 - a / math.sqrt(2))) % 360
    assert boxes[1][2] == f"{beta:.4f}"


def test_the_worked_solution_is_that_of_the_solution():
    """Its data ask the unknown, its closure is at the solution (A = a (cos 45, sin 45) with
    a = 0.9019 m, B at c = 1.9 m), and its results give a, not c back."""
    from linkcli.exports.worked import document
    from linkcli.input.source import load_file
    text = document(load_file(os.path.join(ROOT, "docs", "examples", "design-crank.yaml")),
                    target="markdown", lang="en", figure=False)
    _crank_statement_holds(text)
    a = crank_roots()[0]
    assert f"A = ({a / math.sqrt(2):.6g}, {a / math.sqrt(2):.6g}) m" in text, text
    assert "B = (1.9, 0) m" in text, text
    results = text[text.index("## Results"):]
    assert re.search(r"^\| a \| 0\\\.9019 \| m \|$", results, re.M), results
    assert not re.search(r"^\| c \|", results, re.M), results


def test_the_exam_figure_names_the_unknown_length():
    from linkcli.api import load
    from linkcli.pictures.exam import exam_figure
    fig = exam_figure(load(os.path.join(ROOT, "docs", "examples", "design-crank.yaml")).model)
    texts = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert "a" in texts and "1 m" not in texts, texts
    assert f"{math.sqrt(2):.4f} m" in texts           # AB, data, at the report's 4 decimals
