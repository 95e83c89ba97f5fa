"""One language per worked solution: the Italian one has no English block and no decimal point.

Every shipped file's worked solution is made in English and in Italian (as blocks, no
figure).  The English words of a file are those of its English solution's headings, lines
and tables, less what both languages write alike: the file's own names (the words of its
Italian data lines, its answers' names, its sections' names), the units, the symbols of the
formulas (:data:`SYMBOLS`) and a few words that Italian shares (:data:`SHARED`).  The
Italian solution must use none of them, and no number in it may have a decimal point
(the title and the statement are the file's own text and are left out; formulas in MathML
or LaTeX under ``--symbolic`` keep the point, see ``linkcli.texts.italian``).
"""
from __future__ import annotations

import glob
import os
import re

import pytest

from linkcli.errors import LinkcliError
from linkcli.exports import worked
from linkcli.input.document import build
from linkcli.input.source import load_file
from linkcli.texts import italian

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
#: a clutch problem (shafts:) has no worked solution: export refuses it (docs/machines.md)
FILES = sorted(p for p in glob.glob(os.path.join(ROOT, "mechanisms", "*.yaml"))
               if "shafts" not in load_file(p).data)
#: the documentation's examples: cautions, design searches, friction circles, instability
EXAMPLES = sorted(glob.glob(os.path.join(ROOT, "docs", "examples", "*.yaml")))
METHOD = {"triad-class3.yaml": "newton"}      # a class-III group: the closed form refuses it
WORD = re.compile(r"[^\W\d_]\w*")      # a word, a name (rope9) or a symbol (omega_d)
OPTION = re.compile(r"--[\w-]+(?: \w+)?")   # a command's option and its value: '--method newton'
PLAIN = re.compile(r"[^\W\d_]{3,}")    # a word that can be English: letters only, three or more
DECIMAL_POINT = re.compile(r"\d\.\d")
#: the notation of the formulas, the same in both languages
SYMBOLS = {"conj", "sum", "cos", "sin", "omega", "Omega", "alpha", "beta", "gamma", "delta",
           "phi", "theta", "zeta", "psi", "rho", "qdot", "xdot", "xddot", "RRR", "RRP",
           "PRR", "PRP", "RPP", "RPR", "cross", "rel", "dOmega"}
#: words Italian writes as English does (a plural, a preposition, the names of people)
SHARED = {"per", "guide", "Coriolis", "Brent", "Grübler", "Lagrange", "Newton", "Raphson", "initial",
          "find", "file", "smallest", "nearest", "largest"}   # (choose: the file's words)
UNITS = {"deg", "rad", "rpm", "Nm", "Nms", "kNm", "slug", "Hz", "kg", "lb", "lbf", "ft"}
#: the sections of a file whose keys are names (points, bodies, loads, quantities...)
NAMED = ("frame", "points", "links", "sliders", "actuators", "loads", "quantities",
         "springs", "dampers", "rolling", "cords", "params", "coordinates", "excitation")


def _own_text(mech) -> set:
    """The title and the statement's paragraphs: the file's own words."""
    return {mech.title} | {p.strip() for p in (mech.statement or "").split("\n\n")}


def _lines(items, mech):
    """(data lines, the other lines, the answers' names) of a worked solution's blocks."""
    own, data, rest, names, section = _own_text(mech), [], [], set(), None
    for b in items:
        if b.kind in ("heading", "text"):
            section = b.content if b.kind == "heading" else section
            if str(b.content).strip() not in own:
                rest.append(str(b.content))
        elif b.kind == "lines":
            (data if section in ("Data", "Dati") else rest).extend(str(x) for x in b.content)
        elif b.kind == "table":
            rest.append(" ".join(map(str, b.header)))
            for row in b.content:
                names.add(str(row[0]))
                rest.append(" ".join(map(str, row[1:-1])))
                names.update(WORD.findall(str(row[-1])))           # the unit
    return data, [OPTION.sub("", line) for line in rest], names


def _names(doc) -> set:
    """The file's names: the keys of its named sections."""
    out = set()
    for section in NAMED:
        value = doc.data.get(section) if isinstance(doc.data, dict) else None
        if isinstance(value, dict):
            out.update(str(k) for k in value)
    return out


def english_in_italian(path, blocks=worked.blocks) -> tuple:
    """(English words, lines with a decimal point) of the Italian worked solution of the
    file ``path``."""
    doc = load_file(path)
    mech = build(doc, None)
    method = METHOD.get(os.path.basename(path), "closed")
    en_data, en, _ = _lines(blocks(mech, "en", figure=False, method=method), mech)
    it_data, it, names = _lines(blocks(mech, "it", figure=False, method=method), mech)
    allowed = {w for line in it_data for w in WORD.findall(line)} | names | _names(doc) \
        | set(WORD.findall(path)) | SYMBOLS | SHARED | UNITS
    english = {w for line in en for w in WORD.findall(line) if PLAIN.fullmatch(w)} - allowed
    found = sorted({w for line in it for w in WORD.findall(line) if w in english})
    points = [line for line in it + it_data if DECIMAL_POINT.search(line)]
    return found, points


@pytest.mark.parametrize("path", FILES, ids=os.path.basename)
def test_italian_solution_is_italian(path):
    found, points = english_in_italian(path)
    assert not found, f"English words in the Italian worked solution: {found}"
    assert not points, f"decimal points in the Italian worked solution: {points[:3]}"


def test_examples_italian_solutions_are_italian():
    """The same over the documentation's examples that export (the others are refusals,
    documented as such): the figure check's cautions, design searches, friction circles,
    a frequency response's peaks."""
    checked, wrong = 0, {}
    for path in EXAMPLES:
        try:
            found, points = english_in_italian(path)
        except LinkcliError:
            continue
        checked += 1
        if found or points:
            wrong[os.path.basename(path)] = (found, points[:2])
    assert checked >= 25 and wrong == {}, (checked, wrong)


def test_check_finds_an_english_line(monkeypatch):
    """The check bites: with the translation of the decomposition's heading taken out, the
    Italian solution of padova-2020-02 shows 'Decomposition'; with the decimal comma taken
    out, its results show a decimal point."""
    path = os.path.join(ROOT, "mechanisms", "padova-2020-02.yaml")
    rules = [r for r in italian.RULES if "Decomposition" not in r[0].pattern]
    monkeypatch.setattr(italian, "RULES", rules)
    found, _ = english_in_italian(path)
    assert "Decomposition" in found
    monkeypatch.undo()
    monkeypatch.setattr(italian, "comma", lambda text: text)
    _, points = english_in_italian(path)
    assert points


@pytest.mark.parametrize("english, expected", [
    ("  1. dyad RRR: B from C (BCD, length) and A (AB, q) [BCD, AB] (driven)  "
     "(branch - as in the figure)",
     "  1. diade RRR: B da C (BCD, lunghezza) e A (AB, q) [BCD, AB] (comandata dal movente)  "
     "(ramo - come in figura)"),
    ("dyad RRP: E from D (DE, length) and guide y: 320 (E) [DE, E]: E = (428.881, 320) mm",
     "diade RRP: E da D (DE, lunghezza) e guida y: 320 (E) [DE, E]: E = (428,881; 320) mm"),
    ("    E on the guide y: 320", "    E sulla guida y: 320"),
    ("  revolute pairs R = 2: A (frame-AB.cylinder), B (BCD-AB.rod)",
     "  coppie rotoidali R = 2: A (telaio-AB.cilindro), B (BCD-AB.stelo)"),
    ("B: G1 = (-0.25, 0.255), r1 = 0, r2 = 0.05  ->  B' = (71.5, -7e-05) mm/s",
     "B: G1 = (-0,25; 0,255), r1 = 0, r2 = 0,05  ->  B' = (71,5; -7e-05) mm/s"),
])
def test_italian_line(english, expected):
    """A solving line in Italian: the words by the phrase table, names and formulas kept,
    the decimal comma and '(x; y)' for a pair of numbers."""
    assert italian.italian(english) == expected
