"""The paper exam and the solutions booklet of padova-2020-02 for the digits 0-9.

Without a browser: each document has ten digit sections in order, each starting a new
printed page by the print style; each exam section states its own digit's data (the
actuator's length q = 200 + 10 k mm and the force Fx = -(200 + 50 k) N, as the file's
``params`` give them, computed here), embeds its own figure (ten different SVG images)
and asks the quiz's boxes; each booklet section holds its digit's worked solution and
results, digit 5's equal to the published key at its printed precision.

With headless Chromium (skipped, naming the package, where it is not installed): both
documents printed to PDF; the text of each page (pdftotext, poppler-utils) shows each
digit's title '(k = N)' once, opening a page of its own, in order: ten statements and ten
solutions.
The checks are shown to bite: a document whose sections all hold the file's own digit,
and an exam printed without the page breaks, are reported.
"""
from __future__ import annotations

import base64
import os
import re
import shutil
import subprocess
import sys

import pytest

sys.path.insert(0, os.path.dirname(__file__))

import browser  # noqa: E402
from linkcli.exports import booklet  # noqa: E402
from linkcli.input.document import build  # noqa: E402
from linkcli.input.source import load_file  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PATH = os.path.join(ROOT, "mechanisms", "padova-2020-02.yaml")
DIGITS = list(range(10))
SECTION = re.compile(r'<section class="digit" data-k="(\d+)">(.*?)</section>', re.S)
KEY_5 = {"a1": "250,0", "phi1": "52,2", "phi2": "314,8", "phi3": "44,8", "phi4": "15,5",
         "xE": "428,9", "a1dot": "100,0", "phi1dot": "-3,0", "phi2dot": "-32,1",
         "phi4dot": "-9,6", "xEdot": "116,9", "Fx": "-450,0", "Q": "526,0"}   # the file's key


def _data(k) -> tuple:
    """(q in mm, Fx in N) of digit k, as the file's params write them, Italian numbers."""
    return f"{200 + 10 * k} mm", f"{-(200 + 50 * k)} N"


@pytest.fixture(scope="module")
def documents():
    doc = load_file(PATH)
    return booklet.exam(doc, DIGITS), booklet.booklet(doc, DIGITS)


def exam_problems(page) -> list:
    """What is wrong with the exam ``page``: digits missing or out of order, a section
    without its digit's data, figure or answer table, two digits with one figure."""
    sections = SECTION.findall(page)
    out = [] if [int(k) for k, _ in sections] == DIGITS else ["digits: " + str(
        [k for k, _ in sections])]
    figures = set()
    for k, body in sections:
        q, force = _data(int(k))
        if f"lunghezza AB = {q}" not in body or f"forza Fx = {force}" not in body:
            out.append(f"k = {k}: not its data")
        images = re.findall(r'<img src="data:image/svg\+xml;base64,([^"]+)"', body)
        if len(images) != 1 or b"<svg" not in base64.b64decode(images[0]):
            out.append(f"k = {k}: {len(images)} figures")
        figures.update(images)
        if f"(k = {k})" not in body or '<td class="box">' not in body:
            out.append(f"k = {k}: no title or no answers")
    if len(figures) != len(sections):
        out.append(f"{len(figures)} different figures for {len(sections)} digits")
    return out


def booklet_problems(page) -> list:
    """What is wrong with the booklet ``page``: digits missing or out of order, a section
    whose results are not its digit's (a1, Fx from the params; digit 5's the key)."""
    sections = SECTION.findall(page)
    out = [] if [int(k) for k, _ in sections] == DIGITS else ["digits"]
    for k, body in sections:
        rows = dict(re.findall(r"<tr><td>(\w+)</td><td>([^<]*)</td><td>", body))
        q, force = _data(int(k))
        if rows.get("a1") != q.split()[0] + ",0" or rows.get("Fx") != force.split()[0] + ",0":
            out.append(f"k = {k}: results {rows.get('a1')}, {rows.get('Fx')}")
        if int(k) == 5 and {n: rows.get(n) for n in KEY_5} != KEY_5:
            out.append("k = 5: not the key")
        if "<pre>" not in body or "(k = " + k + ")" not in body:
            out.append(f"k = {k}: no worked solution")
    return out


def test_exam_and_booklet_hold_each_digit(documents):
    exam, solutions = documents
    assert exam_problems(exam) == []
    assert booklet_problems(solutions) == []
    for page in documents:
        assert "section.digit{break-before:page}" in page and "@page{size:A4" in page


def test_the_checks_find_a_document_of_one_digit(monkeypatch):
    """Planted: every section built for the file's own digit (k = 5)."""
    monkeypatch.setattr(booklet, "build", lambda doc, k: build(doc, None))
    doc = load_file(PATH)
    assert exam_problems(booklet.exam(doc, [4, 5], figure=False))
    assert booklet_problems(booklet.booklet(doc, [4, 5], figure=False))


def _pages(pdf, folder) -> list:
    """The text of each page of the PDF bytes ``pdf`` (pdftotext, pages split at form
    feeds)."""
    path = folder / "printed.pdf"
    path.write_bytes(pdf)
    text = subprocess.run(["pdftotext", "-layout", str(path), "-"], capture_output=True,
                          text=True, timeout=120).stdout
    return text.split("\f")[:-1] if text.endswith("\f") else text.split("\f")


def _first_pages(pages) -> list:
    """The page (index) that each digit's title opens (the title's first words the page's
    first), or None where the title is missing, printed twice or within a page."""
    opening = load_file(PATH).data["title"].split(" - ")[0]
    where = []
    for k in DIGITS:
        found = [i for i, text in enumerate(pages) if f"(k = {k})" in text]
        where.append(found[0] if len(found) == 1 and pages[found[0]].lstrip().startswith(
            opening) else None)
    return where


def test_printed_to_pdf_ten_statements_and_ten_solutions(documents, tmp_path):
    if browser.browser() is None:
        pytest.skip(browser.SKIP)
    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext is not installed (Debian: apt-get install poppler-utils)")
    counts = []
    for name, page in zip(("exam", "booklet"), documents):
        html = tmp_path / f"{name}.html"
        html.write_text(page, encoding="utf-8")
        pdf = browser.print_pdf(html, tmp_path)
        pages = _pages(pdf, tmp_path)
        assert len(pages) == len(re.findall(rb"/Type\s*/Page\b", pdf)), name
        first = _first_pages(pages)
        # each digit's title on one page, a page of its own, in order
        assert None not in first and first == sorted(first) and len(set(first)) == 10, \
            (name, first)
        counts.append(len(pages))
    assert min(counts) >= 10, counts
    # planted: the exam without its page breaks puts two digits on one page
    html = tmp_path / "together.html"
    html.write_text(documents[0].replace("section.digit{break-before:page}", ""),
                    encoding="utf-8")
    first = _first_pages(_pages(browser.print_pdf(html, tmp_path), tmp_path))
    assert None in first, "the exam without page breaks still opens a page per digit"
