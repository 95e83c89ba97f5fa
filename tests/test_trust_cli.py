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
DATA = os.path.join(ROOT, "tests", "data")


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
