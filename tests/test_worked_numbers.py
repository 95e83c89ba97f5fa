"""The worked solution's numbers: no rounding noise of a zero, and --method newton.

Every shipped file is exported to Markdown and each block (a fenced block of lines,
a table, a paragraph) is read back: no number may be smaller than 1e-9 of the largest
number of its block (a zero printed as its rounding noise, -5.55e-15 N beside
forces of tens of newtons) unless it is a stated residual.  A class-III group is
exported with --method newton and its results tables are compared with
``solve --method newton``.
"""
from __future__ import annotations

import dataclasses
import glob
import os
import re
from html.parser import HTMLParser

import numpy as np
import pytest

from linkcli.cli import main
from linkcli.exports import worked
from linkcli.input.source import load_file
from linkcli.runs import sheet

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MECH = os.path.join(ROOT, "mechanisms")
ALL = sorted(glob.glob(os.path.join(MECH, "*.yaml")))
#: a clutch problem (shafts:) has no worked solution: export refuses it (docs/machines.md,
#: test_a_clutch_problem_has_no_worked_solution_to_check)
CLUTCH = [p for p in ALL if "shafts" in load_file(p).data]
FILES = [p for p in ALL if p not in CLUTCH]
METHOD = {"triad-class3.yaml": "newton"}      # a class-III group: the closed form refuses it
TRIAD = os.path.join(MECH, "triad-class3.yaml")
# a number, its decimal separator '.' or ',' (the Italian data: 'y = 0,1732050808 m')
NUMBER = re.compile(r"(?<![\w.,])[-+]?\d+(?:[.,]\d+)?(?:[eE][-+]?\d+)?(?![\w.,]\d)")
NOISE = 1e-9                                   # of the block's largest number


def _blocks(markdown: str) -> list:
    """The Markdown's blocks: each fenced block whole, else paragraphs between blank
    lines; Markdown escapes ('\\-', '\\.') removed."""
    out, current, fenced = [], [], False
    for line in markdown.replace("\\", "").splitlines():
        if line.startswith("```"):
            if fenced:
                out.append(current)
                current = []
            elif current:
                out.append(current)
                current = []
            fenced = not fenced
        elif not line.strip() and not fenced:
            if current:
                out.append(current)
            current = []
        else:
            current.append(line)
    return out + ([current] if current else [])


def noise(markdown: str) -> list:
    """(number, block's largest) for each nonzero number under NOISE of the largest
    number of its block, lines stating a residual ('residuo' in Italian) left out."""
    found = []
    for block in _blocks(markdown):
        lines = [line for line in block if "residual" not in line and "residuo" not in line]
        numbers = [float(x.replace(",", ".")) for line in lines for x in NUMBER.findall(line)]
        top = max((abs(x) for x in numbers), default=0.0)
        found += [(x, top) for x in numbers if x != 0 and abs(x) < NOISE * top]
    return found


def _export(path, tmp_path, target="markdown", extra=()) -> str:
    out = tmp_path / f"{os.path.basename(path)}.{target}"
    method = METHOD.get(os.path.basename(path), "closed")
    code = main(["export", path, "--to", target, "--no-figure", "--method", method,
                 "--force", "-o", str(out), *extra])
    assert code == 0, path
    return out.read_text(encoding="utf-8")


@pytest.mark.parametrize("path", FILES, ids=os.path.basename)
def test_no_number_of_a_worked_solution_is_the_rounding_noise_of_a_zero(path, tmp_path):
    assert noise(_export(path, tmp_path)) == []


@pytest.mark.parametrize("path", CLUTCH, ids=os.path.basename)
def test_a_clutch_problem_has_no_worked_solution_to_check(path, tmp_path, capsys):
    """The files left out of the noise check are the ones export refuses by name (exit 2)."""
    code = main(["export", path, "--to", "markdown", "--no-figure", "--force",
                 "-o", str(tmp_path / "out.md")])
    assert code == 2 and "clutch problem" in capsys.readouterr().err


def test_the_noise_check_finds_a_spring_force_printed_as_its_rounding_noise(tmp_path,
                                                                           monkeypatch):
    """Planted: the equilibrium's spring forces printed as computed (no rounding
    cleaned): -5.55e-15 N beside the stiffnesses' 100 N/m is reported."""
    from linkcli.answers.quantities import vibration
    monkeypatch.setattr(vibration, "noise_free", lambda value, scale: value)
    found = noise(_export(os.path.join(MECH, "polimi-2001-09-18-vibration.yaml"), tmp_path))
    assert found and all(abs(x) < 1e-12 for x, _ in found)


def test_the_noise_check_keeps_zeros_and_residuals():
    text = "```\n  force = 0 N\n  k = 100 N/m\n  residual |Q| = 1.20e-16 of the load scale\n```\n"
    assert noise(text) == []
    assert noise("| a | 5.6e-15 | N |\n| b | 607.0 | N |\n") == [(5.6e-15, 607.0)]


# --- --method newton ----------------------------------------------------------------------
def _solve_rows(capsys) -> dict:
    """name -> (value, unit) of the scalar lines of ``solve --method newton``."""
    assert main(["solve", TRIAD, "--method", "newton"]) == 0
    rows = {}
    for line in capsys.readouterr().out.splitlines():
        found = re.fullmatch(r"\s+(\w+)\s+=\s+(-?[\d.]+)\s*(\S*)", line)
        if found:
            rows[found.group(1)] = (found.group(2), found.group(3))
    return rows


def _markdown_rows(text) -> dict:
    rows = {}
    for line in text.replace("\\", "").splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if line.startswith("| ") and len(cells) == 3 and NUMBER.fullmatch(cells[1]):
            rows[cells[0]] = (cells[1], cells[2])
    return rows


class _Cells(HTMLParser):
    def __init__(self):
        super().__init__()
        self.rows, self.cell, self.table = [], None, False

    def handle_starttag(self, tag, attrs):
        if tag == "table" and ("class", "results") in attrs:
            self.table = True
        elif self.table and tag == "tr":
            self.rows.append([])
        elif self.table and tag == "td":
            self.cell = ""

    def handle_endtag(self, tag):
        if tag == "table":
            self.table = False
        elif tag == "td" and self.cell is not None:
            self.rows[-1].append(self.cell.strip())
            self.cell = None

    def handle_data(self, data):
        if self.cell is not None:
            self.cell += data


def _html_rows(text) -> dict:
    parser = _Cells()
    parser.feed(text)
    return {r[0]: (r[1], r[2]) for r in parser.rows if len(r) == 3}


def _newton_tables(tmp_path, capsys):
    md = _export(TRIAD, tmp_path, "markdown", ("--lang", "en"))      # solve's language
    page = _export(TRIAD, tmp_path, "html", ("--lang", "en"))
    return md, page, _solve_rows(capsys)


def test_worked_solution_by_newton_has_the_results_of_solve_by_newton(tmp_path, capsys):
    md, page, solved = _newton_tables(tmp_path, capsys)
    assert len(solved) >= 10
    assert _markdown_rows(md) == solved
    assert _html_rows(page) == solved
    assert "Newton-Raphson on the constraint equations" in md
    assert "unknowns: x and y of the 4 moving points B, C, D, E (8)" in md


def test_the_newton_comparison_finds_results_not_those_of_solve(tmp_path, capsys,
                                                                monkeypatch):
    """Planted: the worked solution's results scaled by 1.01 (not solve's) are reported."""
    def off(mech, **kw):
        result = sheet.evaluate(mech, **kw)
        return dataclasses.replace(result, values={n: np.asarray(v) * 1.01 for n, v in
                                                   result.values.items()})
    monkeypatch.setattr(worked, "evaluate", off)
    md, page, solved = _newton_tables(tmp_path, capsys)
    assert _markdown_rows(md) != solved and _html_rows(page) != solved
