"""Trust, second round: the command line's bounds and messages, the exports' text, the
display of numbers and the drawings' labels.  Each test failed before its fix."""
from __future__ import annotations

import os
import re
import subprocess
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import CODE, FOURBAR, run  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data", "trust")   # repro files of this round


@pytest.fixture
def fourbar(tmp_path):
    path = tmp_path / "fourbar.yaml"
    path.write_text(FOURBAR, encoding="utf-8")
    return path


# --- -o never writes onto the input, --force or not -----------------------------------------
@pytest.mark.parametrize("link", ["none", "symbolic", "hard"])
@pytest.mark.parametrize("target", ["moodle", "markdown"])
def test_export_force_never_replaces_the_input(fourbar, tmp_path, link, target):
    output = fourbar
    if link == "symbolic":
        output = tmp_path / "link.xml"
        os.symlink(fourbar, output)
    elif link == "hard":
        output = tmp_path / "same.xml"
        os.link(fourbar, output)
    code, out, err = run(["export", fourbar, "--to", target, "--no-figure", "--force",
                          "-o", output])
    assert code == 2, out + err
    assert "key '-o'" in err and f"is the input file {fourbar}" in err
    assert fourbar.read_text(encoding="utf-8") == FOURBAR


def test_dash_o_onto_the_file_read_on_standard_input_is_refused(fourbar):
    with open(fourbar, "rb") as stdin:
        proc = subprocess.run([sys.executable, "-c", CODE, "solve", "-", "-o", str(fourbar)],
                              stdin=stdin, capture_output=True, cwd=ROOT,
                              env=dict(os.environ, PYTHONPATH=ROOT), timeout=120)
    assert proc.returncode == 2, proc.stderr
    assert b"the file read on standard input" in proc.stderr
    assert fourbar.read_text(encoding="utf-8") == FOURBAR


# --- the file's text in XML, HTML and Markdown ----------------------------------------------
# characters XML 1.0 forbids or discourages, one of each class: C0 controls, DEL and C1,
# a lone surrogate, the noncharacters of the BMP and of a supplementary plane
UNFIT = ["\x01", "\x0b", "\x1b", "\x7f", "\x85", "\ud800", "\ufdd0", "\ufffe", "\uffff",
         "\U0001fffe", "\U0010ffff"]
# characters a document may carry, awkward for markup: escaped, never interpreted
AWKWARD = ('<b>&amp; </b> ]]> {1:NUMERICAL:=3} "q" \'s\' \t tab \u2028 line \u202e rtl '
           "e\u0301 \U0001f600 \ufffd $x$ <!-- --> ` *")


def _document(title, statement=""):
    from linkcli.input.source import load_text
    text = FOURBAR.replace(FOURBAR.splitlines()[0], "title: " + _quoted(title))
    if statement:
        text += "statement: " + _quoted(statement) + "\n"
    return load_text(text, "awkward.yaml")


def _quoted(text):
    """A YAML double-quoted scalar holding ``text`` (escapes for what YAML cannot hold)."""
    out = []
    for ch in text:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ch.isprintable() or ch == " ":
            out.append(ch)
        else:
            out.append(f"\\U{ord(ch):08x}" if ord(ch) > 0xFFFF else f"\\u{ord(ch):04x}")
    return '"' + "".join(out) + '"'


def test_a_title_xml_cannot_carry_is_refused_with_its_key_and_line():
    code, out, err = run(["export", os.path.join(DATA, "fffe_title.yaml"), "--to", "moodle",
                          "--no-figure", "-o", os.devnull, "--force"])
    assert code == 2, out + err
    assert "fffe_title.yaml:1, key 'title'" in err and "U+FFFE" in err


@pytest.mark.parametrize("key", ["title", "statement"])
@pytest.mark.parametrize("char", UNFIT, ids=lambda c: f"U+{ord(c):04X}")
def test_every_export_refuses_a_character_xml_cannot_carry(key, char):
    from linkcli.errors import InputError
    from linkcli.exports import moodle, worked
    doc = _document(f"four-bar {char} end" if key == "title" else "four-bar",
                    f"a statement {char} end" if key == "statement" else "")
    for make in (lambda: moodle.export(doc, None, figure=False),
                 lambda: worked.document(doc, None, "html", figure=False),
                 lambda: worked.document(doc, None, "markdown")):
        with pytest.raises(InputError) as caught:
            make()
        assert caught.value.key == key and caught.value.line is not None
        assert f"U+{ord(char):04X}" in str(caught.value)


def test_awkward_text_gives_well_formed_xml_that_says_it_verbatim():
    import html
    import xml.etree.ElementTree as ET
    from linkcli.exports import moodle
    doc = _document(AWKWARD, AWKWARD)
    root = ET.fromstring(moodle.export(doc, None, figure=False).encode("utf-8"))  # strict
    question = root.findall("question")[1]
    assert question.find("name/text").text == AWKWARD
    body = question.find("questiontext/text").text       # HTML, the file's text escaped
    assert "<b>&amp;" not in body and "<!--" not in body
    assert html.unescape(body).count(AWKWARD) >= 2      # the title and the statement
    assert len(re.findall(r"\{\d+:NUMERICAL:", body)) == len(doc.data["report"]["position"]) + \
        len(doc.data["report"]["velocity"]) + len(doc.data["report"]["statics"])


def _tags(page):
    """Every (tag, attributes) an HTML parser finds in ``page``."""
    from html.parser import HTMLParser
    found = []

    class Collect(HTMLParser):
        def handle_starttag(self, tag, attrs):
            found.append((tag, attrs))

    Collect().feed(page)
    return found


def _fences(text):
    """(the Markdown ``text`` outside its fenced code blocks, the text inside them)."""
    out, inside, fence = [], [], None
    for line in text.splitlines():
        stripped = line.lstrip()
        if fence is None and stripped.startswith("```"):
            fence = stripped[:len(stripped) - len(stripped.lstrip("`"))]
        elif fence is not None and stripped.startswith(fence) and not stripped.strip("`"):
            fence = None
        else:
            (out if fence is None else inside).append(line)
    return "\n".join(out), "\n".join(inside)


def _unescaped(text, chars):
    """The characters of ``chars`` in ``text`` that no backslash escapes (CommonMark)."""
    found, i = [], 0
    while i < len(text):
        if text[i] == "\\":
            i += 2
            continue
        if text[i] in chars:
            found.append(text[i])
        i += 1
    return found


@pytest.mark.parametrize("source", ["md_title.yaml", "awkward"])
def test_markdown_and_html_carry_no_markup_of_the_file(source, tmp_path):
    """CommonMark forms raw HTML and autolinks only from '<', links only from '['; the
    fenced blocks are linkcli's own lines."""
    from linkcli.exports import worked
    from linkcli.input.source import load_file
    doc = load_file(os.path.join(DATA, source)) if source.endswith(".yaml") else \
        _document(AWKWARD + " [a](javascript:alert(1)) <javascript:x>", AWKWARD + "\n# h")
    page = worked.document(doc, None, "markdown")
    prose, fenced = _fences(page)
    assert _unescaped(prose, "<[`") == [], prose
    assert "script" not in fenced and "javascript" not in fenced
    html_page = worked.document(doc, None, "html", figure=False)
    tags = _tags(html_page)
    assert {t for t, _ in tags} <= {"html", "head", "meta", "title", "style", "body", "h1",
                                    "h2", "p", "pre", "table", "thead", "tbody", "tr", "th",
                                    "td"}, tags
    assert not any("javascript:" in (v or "") for _, attrs in tags for _, v in attrs)


# --- bounds of the options ------------------------------------------------------------------
@pytest.mark.parametrize("value", ["inf", "-inf", "nan", "0", "-1"])
def test_export_tolerance_must_be_positive_and_finite(fourbar, value):
    code, out, err = run(["export", fourbar, "--to", "moodle", "--no-figure",
                          f"--tolerance={value}", "-o", os.devnull, "--force"])
    assert code == 2, out + err
    assert "key '--tolerance'" in err and "tolerance must be positive" in err


@pytest.mark.parametrize("command", ["batch", "export"])
@pytest.mark.parametrize("ks, digit", [("5,5", 5), ("0-9,3", 3), ("2-4,4-6", 4)])
def test_a_digit_given_twice_is_refused(command, ks, digit):
    path = os.path.join(ROOT, "mechanisms", "padova-2020-02.yaml")
    extra = ["--to", "moodle", "--no-figure", "-o", os.devnull, "--force"] \
        if command == "export" else []
    code, out, err = run([command, path, f"--k={ks}"] + extra)
    assert code == 2, out + err
    assert "key '--k'" in err and f"digit {digit} is given twice" in err


def test_a_k_range_is_checked_before_it_is_made():
    from linkcli.runs.batch import parse_k
    from linkcli.errors import InputError
    with pytest.raises(InputError, match="digit 0-9, got 999999999999"):
        parse_k("0-999999999999")       # a range of 10^12 digits was listed, then checked
    assert parse_k("0-2,5,7-9") == [0, 1, 2, 5, 7, 8, 9]


UNDAMPED = os.path.join(DATA, "undamped-forced.yaml")      # omega_n = 10 rad/s


@pytest.mark.parametrize("span, reason", [
    ("-5:20:40", "cannot be negative"),
    ("0:20", "cannot read frf"),
    ("0:inf:10", "need finite FROM"),
])
def test_frf_refuses_negative_frequencies_and_names_its_option(span, reason, tmp_path):
    code, out, err = run(["plot", UNDAMPED, "--frf", span, "-o", tmp_path / "f.png"])
    assert code == 2, out + err
    assert "key '--frf'" in err and reason in err and "--sweep" not in err


def test_frf_names_an_undamped_resonance_it_samples(tmp_path):
    notes = []
    from linkcli.api import load
    from linkcli.pictures import vibration
    said = vibration.frf(load(UNDAMPED).model, "0:20:40", [], str(tmp_path / "f.png"),
                         notify=notes.append)
    assert said == notes and len(notes) == 1        # Omega = 10 rad/s = sqrt(k/m), exactly
    assert "Omega = 10 rad/s is an undamped resonance" in notes[0]
    assert (tmp_path / "f.png").stat().st_size > 0
    said = vibration.frf(load(UNDAMPED).model, "0:20:41", [], str(tmp_path / "g.png"),
                         notify=notes.append)
    assert said == []                               # 10 rad/s is not a sample


@pytest.mark.parametrize("span, reason", [
    ("0:200:100000", "318.3 periods is more than the limit of 200"),   # 200 / (2 pi / 10)
    ("0:5:20", "2.513 samples per period"),        # 20 steps over 5 / 0.6283 periods
    ("0:5:159", "19.98 samples per period"),
    ("1:5:200", "must run from 0"),
])
def test_free_response_is_bounded_and_not_aliased(span, reason, tmp_path):
    code, out, err = run(["plot", UNDAMPED, "--free", span, "-o", tmp_path / "f.png"])
    assert code == 2, out + err
    assert "key '--free'" in err and reason in err


def test_free_response_at_twenty_samples_a_period_is_drawn(tmp_path):
    code, out, err = run(["plot", UNDAMPED, "--free", "0:5:160", "-o", tmp_path / "f.png"])
    assert code == 0, out + err


# --- names and values the file may write --------------------------------------------------
def test_gravity_off_quoted_is_gravity_off():
    from linkcli.api import load
    quoted = load(os.path.join(DATA, "gravity-off-quoted.yaml")).model
    text = open(os.path.join(DATA, "gravity-off-quoted.yaml"), encoding="utf-8").read()
    bare = linkcli_loads(text.replace("gravity: 'off'", "gravity: off"))
    assert quoted.dynamics.gravity == bare.dynamics.gravity == 0j
    on = text.replace("gravity: 'off'", "gravity: 'on'")
    code, out, err = run(["solve", "-"], stdin=on)
    assert code == 2 and "dynamics.gravity" in err and "give gravity's value g" in err


def linkcli_loads(text):
    import linkcli
    return linkcli.loads(text).model


@pytest.mark.parametrize("section, body", [
    ("sliders", "frame: {point: P, guide: {x: 0}}"),
    ("links", "frame: {points: [B, P], length: 0.5}"),
    ("actuators", "frame: {points: [B, P]}"),
])
def test_the_fixed_body_s_name_is_refused_for_any_body(section, body):
    if section == "sliders":
        code, out, err = run(["validate", os.path.join(DATA, "slider_named_frame.yaml")])
    else:
        text = open(os.path.join(DATA, "slider_named_frame.yaml"), encoding="utf-8").read()
        code, out, err = run(["validate", "-"], stdin=text.replace(
            "sliders:\n  frame: {point: P, guide: {x: 0}}",
            f"sliders:\n  post: {{point: P, guide: {{x: 0}}}}\n{section}:\n  {body}"))
    assert code == 2, out + err
    assert f"key '{section}.frame'" in out and "name of the fixed body" in out
    assert "ring" not in out


def test_k_as_a_parameter_says_it_is_the_matricola_digit():
    code, out, err = run(["validate", "-"], stdin=FOURBAR + "params: {k: 3}\n")
    assert code == 2
    assert "key 'params.k'" in out and "matricola" in out


# --- display ----------------------------------------------------------------------------------
VIB = os.path.join(ROOT, "mechanisms", "polimi-2001-07-04-vibration.yaml")


def test_the_values_column_holds_values_of_thousands_at_many_decimals():
    code, out, err = run(["solve", VIB, "--decimals", "8"])
    assert code == 0, err
    rows = [line for line in out.splitlines() if " = " in line]
    assert any(len(line.split(" = ")[1].split()[0]) > 10 for line in rows)   # k_red 11833.9...
    ends = {line.index(" = ") + 3 + len(line.split(" = ")[1].split()[0]) +
            (len(line.split(" = ")[1]) - len(line.split(" = ")[1].lstrip())) for line in rows}
    assert len(ends) == 1, out               # every value ends in one column


def test_a_unitless_value_has_no_trailing_space():
    code, out, err = run(["solve", VIB])
    assert code == 0, err
    assert [line for line in out.splitlines() if line != line.rstrip()] == []
    assert any(line.strip().startswith("zeta") for line in out.splitlines())


def test_the_dynamics_heading_says_gravity_only_with_gravity():
    code, out, _ = run(["solve", os.path.join(DATA, "gravity-off-quoted.yaml")])
    assert code == 0 and "Dynamics (virtual work with inertia)" in out and "gravity" not in out
    code, out, _ = run(["solve", os.path.join(ROOT, "mechanisms",
                                              "fourbar-inverse-dynamics.yaml")])
    assert code == 0 and "with inertia and gravity" in out


def test_rounding_noise_of_a_zero_is_printed_as_zero():
    """The scale is the largest value of the same unit on the sheet; a value under 1e-12 of
    it is 0 in every format.  A value alone in its unit keeps its value."""
    import json
    from linkcli.answers.formats import render
    from linkcli.runs.sheet import evaluate
    from linkcli.api import load
    result = evaluate(load(VIB).model)
    result.values["N"] = -5.55e-15                   # the zero spring force, with noise
    result.values["Ft"] = 607.35                     # N, its scale
    result.values["zeta"] = 3e-15                    # alone in its unit: kept
    for form in ("exam", "table", "csv"):
        text = render(result, form, 12)
        assert "e-15" not in text.replace("3e-15", "") and "-0.0" not in text, text
    data = json.loads(render(result, "json"))["values"]
    assert data["N"] == 0.0 and data["Ft"] == 607.35 and data["zeta"] == 3e-15
    code, out, _ = run(["solve", os.path.join(ROOT, "mechanisms",
                                              "khurmi-15-7-engine-forces.yaml"), "--format",
                        "json"])
    assert json.loads(out)["points"]["A"][1] == 0.0    # 3.7e-14 mm beside 1144 mm


# --- pictures (every shipped figure's labels: tests/test_figures.py) ----------------------------
def _body_points(ax):
    """Points every pixel along the mechanism's lines and outlines (gid 'body'), in pixels,
    with half each line's width: (points, pads)."""
    import numpy as np
    from linkcli.pictures.drawing import BODY
    points, pads = [], []
    for artist in list(ax.lines) + list(ax.patches):
        if artist.get_gid() != BODY:
            continue
        data = artist.get_xydata() if hasattr(artist, "get_xydata") else \
            artist.get_path().vertices
        xy = artist.get_transform().transform(data)
        for a, b in zip(xy[:-1], xy[1:]):
            n = int(np.hypot(*(b - a))) + 2
            points.append(a + np.linspace(0, 1, n)[:, None] * (b - a))
            pads.append(np.full(n, 0.5 * artist.get_linewidth() * ax.figure.dpi / 72))
    return np.vstack(points), np.concatenate(pads)


def test_draw_names_a_pendulum_s_angle_as_solve_does():
    """theta: {angle: [O, B]} of a hanging rod: solve's convention, 270 deg, not 90."""
    from linkcli.api import load
    from linkcli.pictures.plotting import drawn
    fig = drawn(load(os.path.join(ROOT, "mechanisms", "vib-hibbeler-22-12-rod.yaml")).model)
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert "θ = 270.0°" in texts and not any(t.endswith("= 90.0°") for t in texts), texts


# --- units ------------------------------------------------------------------------------------
def _rows(text, first, last):
    """The cells of the Markdown table rows between the lines ``first`` and ``last``."""
    block = text[text.index(first):text.index(last)]
    return [[cell.strip().strip("`") for cell in line.strip().strip("|").split("|")]
            for line in block.splitlines() if line.startswith("| `")]


def test_the_units_table_is_the_code_s():
    """docs/schema.md lists every unit of linkcli/model/units.py with its exact factor."""
    from linkcli.input.expressions import evaluate
    from linkcli.model import units
    text = open(os.path.join(ROOT, "docs", "schema.md"), encoding="utf-8").read()
    rows = _rows(text, "<!-- units:", "<!-- end of units -->")
    assert sorted((kind, unit) for kind, unit, _, _ in rows) == \
        sorted((kind, unit) for kind, table in units.KINDS.items() for unit in table)
    for kind, unit, exact, value in rows:
        factor = units.KINDS[kind][unit]
        assert evaluate(exact.replace("^", "**")) == pytest.approx(factor, rel=4e-16), unit
        assert float(value.split()[0]) == pytest.approx(factor, rel=1e-11), unit
    defaults = _rows(text, "| kind | default |", "Every unit accepted")
    named = {k.strip().strip("`"): d.strip().strip("`").split("`")[0]
             for kinds, given in defaults
             for k, d in zip(kinds.split(","), given.split(","))}
    for kind, unit in units.DEFAULTS.items():
        assert named[kind] == unit, kind


def test_point_masses_are_read_in_the_file_s_mass_unit():
    """1000 g on 100 N/m is 1 kg: omega_n = 10 rad/s, as docs/dynamics.md says."""
    from linkcli.runs.sheet import evaluate
    text = open(os.path.join(DATA, "undamped-forced.yaml"), encoding="utf-8").read()
    grams = linkcli_loads(text.replace("units: {length: m, angle: deg}",
                                       "units: {length: m, angle: deg, mass: g}")
                          .replace("masses: {P: 1}", "masses: {P: 1000}")
                          .replace("report:\n  vibration: [X]",
                                   "  wn: {natural_frequency: 1}\nreport:\n  vibration: [wn]"))
    assert grams.dynamics.masses["P"] == pytest.approx(1.0, rel=1e-15)
    assert evaluate(grams).values["wn"] == pytest.approx(10.0, rel=1e-12)
    doc = open(os.path.join(ROOT, "docs", "dynamics.md"), encoding="utf-8").read()
    row = next(line for line in doc.splitlines() if line.startswith("| `masses.POINT`"))
    assert "units.mass" in row and " in kg " not in row


def test_the_sections_table_lists_every_section():
    from linkcli.input.document import TOP_KEYS
    text = open(os.path.join(ROOT, "docs", "schema.md"), encoding="utf-8").read()
    rows = _rows(text, "| section | required |", "### units")
    listed = {name.strip().strip("`") for row in rows for name in row[0].split(",")}
    assert listed == set(TOP_KEYS)


def test_a_torque_on_an_actuator_and_a_driver_force_follow_docs_conventions():
    """docs/conventions.md: a torque on an actuator has the power M omega_AB, and a length
    driver's load Q the power Q dq/dt: Q = -M omega_AB / (dq/dt), with B on the circle
    |B - O| = 40 mm at |B - A| = q = 130 mm (the branch of the figure)."""
    import cmath
    import math
    from linkcli.runs.sheet import evaluate
    from linkcli.api import load
    result = evaluate(load(os.path.join(DATA, "torque-on-actuator.yaml")).model)
    a, r, q, qdot, moment = complex(-0.1, 0.03), 0.04, 0.13, 0.01, 2.0
    d = abs(a)      # B from the triangle O, A, B: the angle at O between OA and OB
    gamma = math.acos((r * r + d * d - q * q) / (2 * r * d))
    b = min((r * cmath.exp(1j * (cmath.phase(a) + s * gamma)) for s in (1, -1)),
            key=lambda z: abs(z - complex(0.028284, 0.028284)))
    # dq/dt = Re(conj(B - A) i w B) / q for the crank's rate w
    w = qdot * q / (1j * b * (b - a).conjugate()).real
    omega_ab = (1j * w * b / (b - a)).imag
    assert result.values["Q"] == pytest.approx(-moment * omega_ab / qdot, rel=1e-9)


def test_a_title_with_dollar_signs_is_drawn_as_text(tmp_path):
    """matplotlib read '$...$' of a title as mathtext: an unbalanced '\\frac{' was an
    internal error."""
    path = tmp_path / "dollar.yaml"
    path.write_text(FOURBAR.replace(FOURBAR.splitlines()[0],
                                    'title: "price $\\\\frac{ and $ more"'), encoding="utf-8")
    code, out, err = run(["draw", path, "-o", tmp_path / "d.png"])
    assert code == 0, out + err


def test_the_modes_labels_are_apart_and_off_the_mechanism():
    """The modes plot's names (points, springs) lay on the blocks and on each other ('P1'
    over its block and spring s1's zigzag)."""
    import linkcli
    from linkcli.pictures import vibration as pictures
    from linkcli.pictures.labels import label_boxes
    mech = linkcli.load(os.path.join(ROOT, "tests", "data", "vibration",
                                     "symmetric_chain_mode.yaml")).model
    fig = pictures.modes_figure(mech)
    fig.canvas.draw()                   # measured as saved: an equal aspect applied
    for ax in fig.axes:
        boxes = label_boxes(ax)
        assert {t.get_text() for t, _ in boxes} >= {"P1", "P2", "P3", "s1", "s4"}
        points, pads = _body_points(ax)
        for i, (text, box) in enumerate(boxes):
            assert not [o.get_text() for o, b in boxes[:i] if b.overlaps(box)], text.get_text()
            inside = ((points[:, 0] >= box.x0 - pads) & (points[:, 0] <= box.x1 + pads) &
                      (points[:, 1] >= box.y0 - pads) & (points[:, 1] <= box.y1 + pads))
            assert not inside.any(), f"{text.get_text()!r} over the mechanism's lines"
    from legibility import defects
    assert defects(fig) == []           # every stroke, as tests/test_figures.py measures
