"""The HTML worked solution fits its column: nothing scrolls sideways, in a real browser.

Every shipped file's worked solution (Italian, the export's default; without its figure,
which the page scales to the column) and the formulas of ``--symbolic`` of a vibration
problem (its Lagrange equations) and of a linkage (its rate systems) are laid out by
headless Chromium in one call, in a window 800 pixels wide: no element may be wider than
its column nor hold content wider than its box (a preformatted block wraps its lines; a
formula breaks between the terms of its sums, its '= 0' on the last line).  The same call
lays out two pages with the defects planted back (a preformatted block that does not wrap,
a Lagrange equation as one formula) and the check must report them.  Skipped, naming the
package, where Chromium is not installed.
"""
from __future__ import annotations

import glob
import os
import re

import pytest

import browser
from linkcli.exports import worked
from linkcli.input.clutch import is_clutch
from linkcli.input.source import load_file
from linkcli.texts.symbolic import formulas

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MECH = os.path.join(ROOT, "mechanisms")
#: the files that have a worked solution: the export refuses a clutch problem (shafts and a
#: clutch, no linkage to work out; docs/errors.md), so it has no page to lay out
FILES = sorted(p for p in glob.glob(os.path.join(MECH, "*.yaml"))
               if not is_clutch(load_file(p).data))
METHOD = {"triad-class3.yaml": "newton"}      # a class-III group: the closed form refuses it
SYMBOLIC = ("polimi-2001-09-18-vibration.yaml", "padova-2020-02.yaml")


def _page(path, symbolic=False) -> str:
    doc = load_file(path)
    found = formulas(doc, None, (), 10.0) if symbolic else None
    return worked.document(doc, None, "html", "it", figure=False, formulas=found,
                           method=METHOD.get(os.path.basename(path), "closed"))


def _one_formula(page) -> str:
    """``page`` with each formula's pieces set as one formula again (the defect)."""
    return re.sub(r'<span class="terms">(.*?)</span>',
                  lambda m: "<math display=\"block\"><mrow>" + "".join(
                      re.findall(r"<mrow>(.*?)</mrow>(?:<annotation|</math>)", m.group(1)))
                  + "</mrow></math>", page)


def test_lagrange_equation_is_set_in_pieces_with_its_zero():
    """Without a browser: a Lagrange equation is a run of inline formulas, one per term,
    the last ending in '= 0', in one 'terms' paragraph; preformatted blocks wrap."""
    page = _page(os.path.join(MECH, SYMBOLIC[0]), symbolic=True)
    runs = re.findall(r'<span class="terms">(.*?)</span>', page)
    lagrange = [r for r in runs if "\\ddot{\\varphi}" in r and r.count("<math") > 4]
    assert lagrange, "the Lagrange equations are not set in pieces"
    assert all(r.endswith("<mo>=</mo><mn>0</mn></mrow></math>") for r in lagrange)
    assert "white-space:pre-wrap" in page


def test_every_worked_solution_fits_its_column(tmp_path):
    if browser.browser() is None:
        pytest.skip(browser.SKIP)
    pages = [(os.path.basename(p), _page(p)) for p in FILES]
    pages += [(f"{name} --symbolic", _page(os.path.join(MECH, name), symbolic=True))
              for name in SYMBOLIC]
    lagrange = pages[-2][1]
    planted = [("planted pre", pages[0][1].replace("<pre>", '<pre style="white-space:pre">')),
               ("planted formula", _one_formula(lagrange))]
    measured = browser.measure(pages + planted, tmp_path)
    over = [row for row in measured["over"] if not row[0].startswith("planted")]
    assert over == [], f"wider than the column (page, tag, box, content, column): {over[:10]}"
    caught = {row[0] for row in measured["over"]} - {row[0] for row in over}
    assert caught == {"planted pre", "planted formula"}, measured["over"]
