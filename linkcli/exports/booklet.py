"""The paper exam and the solutions booklet of a set of digits, as pages to print.

``exam`` writes, for each digit k, the statement a student receives on paper: the title
with the digit, the statement's words, the data, the exam's figure of that digit (the
data only, no answer) and a table of the answers to write (the boxes the quiz asks, see
:func:`linkcli.exports.moodle.left_out_boxes`), each with its unit.  ``booklet`` writes
each digit's worked solution (:mod:`linkcli.exports.worked`) with its results table, the
key of that digit.

Both are one self-contained HTML page: each digit is a ``section class="digit"`` that the
print style (:data:`PRINT`) starts on a new page, so that Chromium's (or any browser's)
print to PDF gives each digit its own pages as the page stands.  The figures are SVG
images of their own (data URIs), sharp on paper, their ids kept to each.
"""
from __future__ import annotations

from linkcli.answers.formats import heading as section_heading
from linkcli.exports import worked
from linkcli.exports.moodle import left_out_boxes, refuse_one_question
from linkcli.exports.text import refuse_unfit
from linkcli.exports.worked import Block, esc, svg_image
from linkcli.input.document import build
from linkcli.model.mechanism import REPORT_SECTIONS
from linkcli.runs import design
from linkcli.runs.sheet import evaluate
from linkcli.texts.data import data_lines
from linkcli.texts.quantities import describe

#: the print style: A4 pages, each digit from a new page, blocks kept whole where they fit
PRINT = ("@page{size:A4;margin:14mm}"
         "section.digit{break-before:page}"
         "section.digit:first-of-type{break-before:auto}"
         "h1,h2{break-after:avoid}"
         "table,.figure,.formula{break-inside:avoid}"
         ".figure img{max-width:100%;max-height:120mm}"
         "table.answers td.box{width:9em;border-bottom:1px solid #000}"
         "@media print{body{max-width:none;margin:0;padding:0}"
         "pre{background:none;border:1px solid #bbb}}")

WORDS = {
    "en": {"exam": "Exam", "booklet": "Solutions", "data": "Data", "figure": "Figure",
           "answers": "Answers", "name": "quantity", "what": "what it is", "value": "value",
           "unit": "unit", "digit": "k = {k}"},
    "it": {"exam": "Compito", "booklet": "Soluzioni", "data": "Dati", "figure": "Figura",
           "answers": "Risposte", "name": "grandezza", "what": "che cosa è", "value": "valore",
           "unit": "unità", "digit": "k = {k}"},
}


def _digits(doc, ks) -> list:
    """The digits to write: ``ks``, or the file's own (None)."""
    refuse_one_question(doc, ks)
    return list(ks) if ks is not None else [None]


def _title(mech, lang) -> str:
    """The title with the digit: 'TITLE (k = 3)'; the title alone for a file without k."""
    if mech.k is None:
        return mech.title
    return f"{mech.title} ({WORDS[lang]['digit'].format(k=mech.k)})"


def _document(doc, sections, kind, lang) -> str:
    """The page of ``sections`` (HTML of each digit), its title the file's and ``kind``."""
    base = build(doc, None)
    body = "\n".join(f'<section class="digit" data-k="{k}">{html}</section>'
                     for k, html in sections)
    return worked.page(f"{WORDS[lang][kind]}: {base.title}", body, lang,
                       worked.STYLE + PRINT)


def exam(doc, ks=None, lang="it", figure=True, method="closed", no_given=False) -> str:
    """The paper exam of the loaded document ``doc`` at digits ``ks`` (None: the file's
    own): each digit's statement, data, exam figure and answer table on its own pages;
    ``no_given`` leaves out of the table the values the question gives."""
    refuse_unfit(doc)
    sections = []
    for k in _digits(doc, ks):
        mech = build(doc, k)
        sections.append((mech.k, _statement(mech, lang, figure, method, no_given)))
    return _document(doc, sections, "exam", lang)


def _statement(mech, lang, figure, method, no_given) -> str:
    """One digit's statement as HTML: title, words, data, figure, answers to write."""
    w = WORDS[lang]
    result = evaluate(mech, method=method)
    solution = design.solve(mech, evaluate, method) if design.unsolved(mech) else None
    parts = [f"<h1>{esc(_title(mech, lang))}</h1>"]
    parts += [f"<p>{esc(p.strip())}</p>" for p in mech.statement.split("\n\n") if p.strip()]
    parts.append(f"<h2>{w['data']}</h2><ul>" + "".join(
        f"<li>{esc(line)}</li>" for line in data_lines(mech, lang, solution)) + "</ul>")
    if figure:
        from linkcli.exports.figure import figure_bytes
        svg = figure_bytes(mech, "svg", exam=True, lang=lang, method=method).decode("utf-8")
        parts.append(f'<div class="figure">{svg_image(svg[svg.find("<svg"):], w["figure"])}'
                     "</div>")
    left_out = left_out_boxes(mech, no_given)
    parts.append(f"<h2>{w['answers']}</h2>")
    for section in REPORT_SECTIONS:
        names = [n for n in design.asked(mech, mech.report.get(section) or [])
                 if n not in left_out]
        if names:
            rows = "".join(f"<tr><td>{esc(n)}</td><td>{esc(describe(mech, n, lang))}</td>"
                           f'<td class="box"></td><td>{esc(result.units[n])}</td></tr>'
                           for n in names)
            parts.append(f'<table class="answers"><thead><tr><th>'
                         f"{esc(section_heading(mech, section, lang))}</th><th>{w['what']}"
                         f"</th><th>{w['value']}</th><th>{w['unit']}</th></tr></thead>"
                         f"<tbody>{rows}</tbody></table>")
    return "\n".join(parts)


def booklet(doc, ks=None, lang="it", figure=True, method="closed") -> str:
    """The solutions booklet of ``doc`` at digits ``ks`` (None: the file's own): each
    digit's worked solution and results table (its key) on its own pages."""
    refuse_unfit(doc)
    sections = []
    for k in _digits(doc, ks):
        mech = build(doc, k)
        items = worked.blocks(mech, lang, figure=figure, method=method)
        items[0] = Block("heading", _title(mech, lang))
        sections.append((mech.k, worked.html_body(items, inline=False)))
    return _document(doc, sections, "booklet", lang)
