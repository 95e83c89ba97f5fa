"""The problem's data as an exam states them: every number the solution uses, with its unit.

Written from the model, not from the file's text, so that a quiz or a worked solution
states what is solved: the bodies and their guides (:mod:`linkcli.texts.bodies`), the
driver or the coordinates of a vibration problem and the loads (:mod:`linkcli.texts.loads`),
masses, inertias, gravity and friction (:mod:`linkcli.texts.masses`), springs, dampers and
the excitation (:mod:`linkcli.texts.elements`).  Each datum is stated once, in the file's
display units (:mod:`linkcli.texts.amounts`), in Italian or English (``lang``).

Where the file asks a design question, a datum that depends on an unknown is stated as
the unknown (:mod:`linkcli.texts.unknowns`), never at the figure's value, and a last line
asks the unknowns, each named by what it is, with the targets and their units.
"""
from __future__ import annotations

import math

from linkcli.texts.amounts import CLOSE, Writer, number
from linkcli.texts.bodies import body_lines
from linkcli.texts.elements import element_lines
from linkcli.texts.loads import motion_and_load_lines
from linkcli.texts.machine import regime_lines
from linkcli.texts.masses import mass_lines
from linkcli.texts.phrases import WORDS
from linkcli.texts.quantities import describe
from linkcli.texts.unknowns import unknown_role, variants


def data_lines(mech, lang: str = "en", solution=None) -> list[str]:
    """Every datum of ``mech`` as lines of text (see the module's docstring).  Where it asks
    a design question, a datum that depends on an unknown is stated as the unknown, not at
    the value the file gives it for the figure, and the last line asks the unknowns, each
    named by what it is, with the targets in their units (those of ``solution``,
    runs.design's, where the file gives none)."""
    w = Writer(mech, lang)
    lines = _lines(w)
    if mech.design is not None and not mech.design.fixed:
        lines = _unknowns_stated(mech, lines, lang)
    return lines + _design(w, solution)


def _lines(w) -> list:
    lines = []
    for part in (body_lines, motion_and_load_lines, regime_lines, mass_lines, element_lines):
        lines += part(w)
    return [line for line in lines if line]


#: a number as a data line writes it (either decimal separator)
NUMBER = r"-?\d+(?:[.,]\d+)?(?:e[-+]?\d+)?"


def _unknowns_stated(mech, lines, lang) -> list:
    """``lines`` with every number that changes with an unknown's value (the data stated
    again at another value, number by number) written as the unknown's name."""
    import re
    split = [re.split(f"({NUMBER})", line) for line in lines]
    for name, start, other, varied_mech in variants(mech):
        varied = _lines(Writer(varied_mech, lang))
        if len(varied) != len(lines):
            continue
        for parts, line in zip(split, varied):
            there = re.split(f"({NUMBER})", line)
            if len(there) != len(parts) or there[::2] != parts[::2]:
                continue
            for i in range(1, len(parts), 2):
                if parts[i] != there[i]:
                    parts[i] = _as_unknown(parts, i, there[i], name, start, other, lang)
    return ["".join(parts) for parts in split]


def _as_unknown(parts, i, there, name, start, other, lang) -> str:
    """The number ``parts[i]`` (``there`` at the other value) as the unknown ``name``: its
    own name where the datum is the unknown as the file writes it, a multiple of it ('8 ks')
    where it is proportional, else '?' and that it depends on it; never its number."""
    import re

    def read(text):
        return float(text.replace(",", ".")) if lang == "it" else float(text)
    here, varied = read(parts[i]), read(there)
    ratio = here / start if start else math.nan
    if not math.isclose(varied / other, ratio, rel_tol=1e-6):
        return f"? ({WORDS[lang]['depends'].format(name=name)})"
    parts[i + 1] = re.sub(r"^(°| [^\s,;()]+)", "", parts[i + 1])    # the unknown's unit
    if math.isclose(ratio, 1.0, rel_tol=CLOSE):
        return name
    return f"{number(ratio, lang)} {name}"


def _design(w, solution=None) -> list:
    """A design question: the unknowns, each with what it is, and the targets' values with
    their units."""
    design = w.mech.design
    if design is None:
        return []
    units = solution.units if solution is not None else {}
    targets = ", ".join(f"{t.name} = {w.num(t.value)}" + (f" {u}" if (u := t.unit or
                                                                   units.get(t.name)) else "")
                        + (f" ({what})" if (what := describe(w.mech, t.name, w.lang)) else "")
                        for t in design.targets)
    unknowns = ", ".join(f"{n} ({role})" if (role := unknown_role(w.mech, n, w.lang)) else n
                         for n in design.names)
    key = "design_one" if len(design.names) == 1 else "design"
    return [w.w[key].format(unknowns=unknowns, targets=targets)]
