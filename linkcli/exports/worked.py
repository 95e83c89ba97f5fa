"""A worked solution: the page a teaching assistant hands out after the exam.

The data, Grübler's count and the Assur decomposition, each group's closure
equations in solving order with the numbers, the velocity and acceleration
systems of each dyad with their coefficients and results, the statics by
virtual work (each load's virtual power) or the power balance, the results
table as the exam prints it, and the figure with its vector polygon.  A
vibration problem gets its energies, equilibrium and linearised system.

The content is built once as a list of blocks (heading, paragraph, lines of
equations, table, figure) and rendered as one self-contained HTML page (inline
SVG figure, no network, no external file) or as Markdown.  Every number comes
from the same evaluation as ``solve``.
"""
from __future__ import annotations

import html
from dataclasses import dataclass, field

import numpy as np

from linkcli.runs import design
from linkcli.texts.explain import explain
from linkcli.answers.formats import fmt, heading, without_noise
from linkcli.runs.sheet import evaluate
from linkcli.texts.data import data_lines
from linkcli.exports.text import fence, markdown, refuse_unfit, visible
from linkcli.input.document import build
from linkcli.kinematics.closed_form import unit_rates
from linkcli.kinematics.solvers import solver_for
from linkcli.model.mechanism import REPORT_SECTIONS
from linkcli.model.rounding import noise_free
from linkcli.texts.italian import italian

WORDS = {
    "en": {"data": "Data", "structure": "Mobility and Assur decomposition",
           "positions": "Position analysis: closure of each group in solving order",
           "velocities": "Velocity analysis: the linear system of each dyad",
           "accelerations": "Acceleration analysis: the linear system of each dyad",
           "statics": "Statics by virtual work", "results": "Results",
           "figure": "Figure and vector polygon", "solution": "Worked solution",
           "system": "Re(conj(G_i) v) = r_i: G_i the gradient of each constraint (m), "
                     "r_i its known part (m^2/s, m^2/s^2)", "load": "load", "coefficient":
           "virtual power per unit driver rate", "value": "value", "quantity": "quantity",
           "unit": "unit", "vibration": "Vibrations",
           "motion": "Machine dynamics"},
    "it": {"data": "Dati", "structure": "Mobilità e scomposizione in diadi",
           "positions": "Analisi di posizione: chiusura di ogni gruppo nell'ordine di soluzione",
           "velocities": "Analisi di velocità: il sistema lineare di ogni diade",
           "accelerations": "Analisi di accelerazione: il sistema lineare di ogni diade",
           "statics": "Analisi statica con il principio dei lavori virtuali",
           "results": "Risultati", "figure": "Figura e poligono dei vettori",
           "solution": "Soluzione", "system": "Re(conj(G_i) v) = r_i: G_i il gradiente di ogni "
           "vincolo (m), r_i la sua parte nota (m^2/s, m^2/s^2)", "load": "carico",
           "coefficient": "potenza virtuale per velocità unitaria del movente",
           "value": "valore", "quantity": "grandezza", "unit": "unità",
           "vibration": "Vibrazioni",
           "motion": "Dinamica della macchina"},
}


@dataclass
class Block:
    kind: str                    # heading | text | lines | table | figure
    content: object
    header: list = field(default_factory=list)


def _xy(z, f, scale=0.0):
    """A point or vector z (SI) as '(x, y)' in the display unit ``f``; a component under
    NOISE (``model.rounding``) of the larger of |z| and ``scale`` (SI: the size of the
    values it sits among) is 0."""
    z = complex(np.ravel(z)[0])
    top = max(abs(z), scale)
    x, y = (noise_free(part, top) / f for part in (z.real, z.imag))
    return f"({x + 0.0:.6g}, {y + 0.0:.6g})"


def _number(value, scale) -> str:
    """A scalar (SI) to six digits, 0 where it is the rounding noise beside ``scale``."""
    return f"{noise_free(float(np.ravel(value)[0]), scale):.6g}"


def _largest(values) -> float:
    """The largest magnitude among ``values`` (complex, SI), 0 for none."""
    return max((float(np.max(np.abs(v))) for v in values), default=0.0)


def document(doc, k=None, target="html", lang="en", figure=True, formulas=None,
             method="closed") -> str:
    """The worked solution of the loaded document ``doc`` at digit ``k`` (None: the file's
    own) as one HTML page (``target`` 'html', with the figure) or Markdown, its positions
    solved by ``method`` ('closed' or 'newton'); ``formulas`` (``texts.symbolic.formulas``)
    adds the answers in symbols."""
    refuse_unfit(doc)
    items = blocks(build(doc, k), lang, figure=figure and target == "html", method=method)
    if formulas is not None:
        items = with_formulas(items, formulas, lang)
    return to_html(items, lang) if target == "html" else to_markdown(items)


def blocks(mech, lang="en", figure=True, method="closed") -> list:
    """The worked solution of ``mech`` (at its own digit and driver value) as blocks; a
    design question's data state its unknowns and targets, its analysis and figure are
    those of the mechanism built with the unknowns' solution, and its results give the
    unknowns, not the targets back.  By the closed form ('closed') the solution shows each
    group's systems; by 'newton' it states the unknowns and the equations Newton solves
    together (as ``explain --method newton``).  The results are those ``solve`` prints:
    a value that is the rounding noise of a zero is 0."""
    w = WORDS[lang]
    say = _language(lang)
    result = without_noise(evaluate(mech, method=method))
    solution = design.solve(mech, evaluate, method) if design.unsolved(mech) else None
    solved = solution.mech if solution is not None else mech
    out = [Block("heading", mech.title)]
    if mech.statement:
        out += [Block("text", p.strip()) for p in mech.statement.split("\n\n") if p.strip()]
    out += [Block("heading", w["data"]), Block("lines", data_lines(mech, lang, solution))]
    out += [Block("heading", w["structure"]),
            Block("lines", [say(x) for x in explain(mech, method).splitlines()[2:]])]
    if mech.elements is None and method == "closed" and len(mech.coordinates) == 1:
        out += _kinematics(solved, w, say)
    out.append(Block("heading", w["results"]))
    decimals = mech.report.get("decimals", 1)
    for section in REPORT_SECTIONS:
        names = design.asked(mech, mech.report.get(section) or [])
        if names:
            rows = [[n, say(fmt(np.ravel(result.values[n])[0], decimals)), result.units[n]]
                    for n in names]
            title = heading(mech, section, lang)
            out.append(Block("table", rows, [title, w["value"], w["unit"]]))
    if figure:
        from linkcli.exports.figure import figure_bytes
        out += [Block("heading", w["figure"]),
                Block("figure", figure_bytes(solved, "svg", method=method).decode("utf-8"))]
    return out


def _language(lang):
    """The function that writes a solving line (English, as the solvers make it) in
    ``lang``: Italian words and decimal comma for 'it' (``texts.italian``)."""
    return italian if lang == "it" else str


def _kinematics(mech, w, say=str) -> list:
    """Closure, velocity and acceleration systems of each group, and the statics, each line
    written by ``say`` (``_language``)."""
    solver = solver_for(mech)
    value, rate, accel = mech.inputs
    unit, f = mech.units.display("length", 0)
    kin = solver.positions(value)
    solver.check(kin, velocities=False)
    solver.velocities(kin, rate)
    solver.check(kin, velocities=True)
    vel_systems = _systems(solver, kin, 1)
    solver.accelerations(kin, accel, keep=True)
    acc_systems = _systems(solver, kin, 2)
    kin.linear.clear()
    lines = []
    size = _largest(kin.pos.values())
    for group in solver.groups:
        if group.point is None:
            lines.append(f"{group.describe()}")
            continue
        lines.append(f"{group.describe()}: {_shown(group.point)} = "
                     f"{_xy(kin.pos[group.point], f, size)} {unit}")
        for c in group.constraints:
            text = _constraint_text(c, mech, f, unit)
            if text:
                lines.append(f"    {text}")
    out = [Block("heading", w["positions"]), Block("lines", [say(x) for x in lines])]
    for key, systems, suffix in (("velocities", vel_systems, "/s"),
                                 ("accelerations", acc_systems, "/s^2")):
        rows = []
        top = _largest(s[5] for s in systems)       # the largest rate of the block
        for point, g1, g2, r1, r2, value in systems:
            g = _largest((g1, g2))
            rows.append(f"{point}: G1 = {_xy(g1, 1, g)}, G2 = {_xy(g2, 1, g)}, "
                        f"r1 = {_number(r1, _largest([g1]) * top)}, "
                        f"r2 = {_number(r2, _largest([g2]) * top)}"
                        f"  ->  {point}{chr(39) * (1 if suffix == '/s' else 2)} = "
                        f"{_xy(value, f, top)} {unit}{suffix}")
        if rows:
            out += [Block("heading", w[key]), Block("lines", [w["system"]] +
                                                    [say(x) for x in rows])]
    if mech.loads and mech.dynamics is None and any(ld.value is None for ld in mech.loads.values()):
        out += _statics(mech, solver, kin, w, say)
    return out


def _systems(solver, kin, order):
    out = []
    for index, group in enumerate(solver.groups):
        if group.is_dyad and group.point is not None:
            g1, g2, r1, r2, value = solver.rate_system(index, kin, order)
            out.append((_shown(group.point), g1, g2, r1, r2, value))
    return out


def _constraint_text(c, mech, f, unit):
    from linkcli.kinematics.groups import Dist, Line
    if isinstance(c, Dist):
        length = "q" if c.length is None else f"{c.length / f:.6g} {unit}"
        return f"|{_shown(c.p)} - {_shown(c.a)}| = {length}"
    if isinstance(c, Line):
        body = mech.bodies.get(c.body)
        if body is not None and body.guide is not None and c.b.startswith("~"):
            return f"{c.p} on the guide {body.guide.text}"
        b, cc, p = _shown(c.b), _shown(c.c), _shown(c.p)
        return f"cross({cc} - {b}, {p} - {b}) = {c.value / f ** 2 + 0.0:.6g} {unit}^2"
    return None


def _shown(point: str) -> str:
    """A point's printed name: the construction point ``~BLOCK.slot`` of a slot's dyad (a
    point of the line through the pin parallel to the slot) is V_BLOCK."""
    if point.startswith("~") and point.endswith(".slot"):
        return f"V_{point[1:-len('.slot')]}"
    return point


def _statics(mech, solver, kin, w, say=str):
    """The loads' virtual power coefficients c_i (per unit driver rate): with several
    drivers a column c_ij per driver j, its unit rate with the others at rest."""
    from linkcli.forces.inputs import load_coefficient
    drivers = mech.coordinates if mech.elements is None else mech.coordinates[:1]
    units = [unit_rates(solver, kin, j) for j in range(len(drivers))]
    rows = []
    for load in mech.loads.values():
        cs = [float(np.ravel(load_coefficient(mech, load, kin.pos, u.vel, j))[0])
              if len(drivers) > 1 else
              float(np.ravel(load_coefficient(mech, load, kin.pos, u.vel, None))[0])
              for j, u in enumerate(units)]
        kind = mech.load_unit_kind(load)
        value = "?" if load.value is None else f"{load.value / mech.units.factor(kind):.6g}"
        rows.append([load.name, say(value)] + [say(f"{c:.6g}") for c in cs])
    if len(drivers) == 1:
        return [Block("heading", w["statics"]), Block("text", "sum_i L_i c_i = 0"),
                Block("table", rows, [w["load"], w["value"], w["coefficient"]])]
    return [Block("heading", w["statics"]), Block("text", "sum_i L_i c_ij = 0, j = " +
                                                  ", ".join(d.name for d in drivers)),
            Block("table", rows, [w["load"], w["value"]] +
                  [f"{w['coefficient']}: {d.name}" for d in drivers])]


def with_formulas(items, formulas, lang="en") -> list:
    """The worked solution with the formulas of ``formulas`` (``texts.symbolic``) before
    its results: each a 'formula' block, written as MathML (with its LaTeX) in HTML and as
    LaTeX in Markdown."""
    from linkcli.texts.symbolic import Entry, sections
    rank = formulas.ranking()
    out = []
    for title, entries in sections(formulas, lang):
        out.append(Block("heading", title))
        for e in entries:
            out.append(Block("formula", (e, rank)) if isinstance(e, Entry) else Block("text", e))
    at = next((i for i, b in enumerate(items) if b.kind == "heading" and
               b.content == WORDS[lang]["results"]), len(items))
    return items[:at] + out + items[at:]


def formula_latex(entry, rank) -> str:
    """An Entry as one LaTeX equation."""
    import sympy as sp
    from linkcli.texts import notation
    if entry.reads == "equation":
        left, right = entry.value
        return f"{notation.latex(left, rank)} = {notation.latex(right, rank)}"
    if entry.reads == "system":
        A, u, b = entry.value
        return f"\\text{{{entry.label}}} \\quad " + " ".join(
            notation.latex_matrix(x, rank) for x in (A, u)) + " = " + notation.latex_matrix(b, rank)
    value = notation.latex_matrix(entry.value, rank) if isinstance(entry.value, sp.MatrixBase) \
        else notation.latex(entry.value, rank, entry.terms)
    label = notation.label_latex(entry.label) if entry.label else ""
    return {"is": f"{label} = {value}", "zero": f"{label} \\quad {value} = 0" if label
            else f"{value} = 0", "positive": f"{value} > 0"}[entry.reads]


def formula_mathml(entry, rank) -> str:
    """An Entry as MathML: a matrix equation or system as one display <math> element; a
    scalar one as a run of inline <math> pieces, one per term of its sums, that the page
    breaks between terms (``_pieces``).  The first element keeps the whole formula's
    LaTeX as its annotation."""
    import sympy as sp
    from linkcli.texts import notation
    tex = formula_latex(entry, rank)
    if entry.reads == "system":
        A, u, b = (notation.mathml_matrix(x, rank) for x in entry.value)
        label = f"<mtext>{html.escape(entry.label)}</mtext><mspace width=\"1em\"/>"
        return _pieces([f"{label}{A}{u}", f"<mo>=</mo>{b}"], tex)
    if isinstance(entry.value, sp.MatrixBase):
        label = notation.label_mathml(entry.label) if entry.label else ""
        return _math(f"{label}<mo>=</mo>{notation.mathml_matrix(entry.value, rank)}", tex)
    if entry.reads == "equation":
        left, right = (notation.mathml_terms(x, rank) for x in entry.value)
        return _pieces(left[:-1] + [left[-1] + "<mo>=</mo>" + right[0]] + right[1:], tex)
    value = notation.mathml_terms(entry.value, rank, entry.terms)
    label = notation.label_mathml(entry.label) if entry.label else ""
    if entry.reads == "is":
        return _pieces([f"{label}<mo>=</mo>{value[0]}"] + value[1:], tex)
    end = "<mo>&gt;</mo><mn>0</mn>" if entry.reads == "positive" else "<mo>=</mo><mn>0</mn>"
    head = [label + '<mspace width="1em"/>'] if label and entry.reads == "zero" else []
    return _pieces(head + value[:-1] + [value[-1] + end], tex)


def _pieces(pieces, tex) -> str:
    """Inline <math> elements, one per piece, in a 'terms' paragraph: the browser breaks
    the line between two pieces where the column ends (continuation lines indented), so
    that a long equation and its '= 0' stay in the column; the first piece carries the
    LaTeX ``tex`` of the whole."""
    first = _math(pieces[0], tex, display=False)
    rest = [f'<math xmlns="http://www.w3.org/1998/Math/MathML"><mrow>{p}</mrow></math>'
            for p in pieces[1:]]
    return '<span class="terms">' + " ".join([first] + rest) + "</span>"


def _math(body, tex, display=True) -> str:
    """A <math> element of ``body`` (display block, or inline), its LaTeX ``tex`` as the
    annotation."""
    mode = ' display="block"' if display else ""
    return (f'<math xmlns="http://www.w3.org/1998/Math/MathML"{mode}><semantics>'
            f'<mrow>{body}</mrow><annotation encoding="application/x-tex">'
            f'{html.escape(tex)}</annotation></semantics></math>')


# --- renderers ---------------------------------------------------------------------------
STYLE = ("body{font-family:sans-serif;max-width:60em;margin:2em auto;padding:0 1em}"
         "pre{background:#f6f6f6;padding:.6em;white-space:pre-wrap;overflow-wrap:anywhere}"
         "table{border-collapse:collapse;margin:.5em 0}"
         "td,th{border:1px solid #bbb;padding:.2em .6em;text-align:left}"
         ".figure svg,.figure img{max-width:100%;height:auto}"
         ".formula{margin:.4em 0}"
         ".terms{display:block;padding-left:2em;text-indent:-2em;line-height:2}"
         'math{font-family:"Latin Modern Math","STIX Two Math","DejaVu Math TeX Gyre",math}'
         "mtable.matrix{border:solid currentColor;border-width:0 1.5px;padding:0 .3em;"
         "background:" + ",".join(f"linear-gradient(currentColor,currentColor) {x} {y}/.3em "
                                  "1.5px no-repeat" for x in ("left", "right")
                                  for y in ("top", "bottom")) + "}")


def esc(text) -> str:
    """The file's or our text as HTML text: unfit characters shown as U+FFFD, escaped."""
    return html.escape(visible(text))


def svg_image(svg: str, alt: str) -> str:
    """An SVG document as an <img> of a data URI: a page that holds several figures keeps
    each one's ids to itself."""
    import base64
    data = base64.b64encode(visible(svg).encode("utf-8")).decode("ascii")
    return f'<img src="data:image/svg+xml;base64,{data}" alt="{esc(alt)}">'


def html_body(items, inline=True) -> str:
    """The blocks as HTML elements: the first heading h1, the others h2; the figure as
    inline SVG (``inline``) or as an image of its own (:func:`svg_image`)."""
    body = []
    for b in items:
        if b.kind == "heading":
            tag = "h1" if not body else "h2"
            body.append(f"<{tag}>{esc(str(b.content))}</{tag}>")
        elif b.kind == "text":
            body.append(f"<p>{esc(str(b.content))}</p>")
        elif b.kind == "lines":
            body.append("<pre>" + esc("\n".join(str(x) for x in b.content)) + "</pre>")
        elif b.kind == "table":
            head = "".join(f"<th>{esc(str(h))}</th>" for h in b.header)
            rows = "".join("<tr>" + "".join(f"<td>{esc(str(c))}</td>" for c in row) + "</tr>"
                           for row in b.content)
            body.append(f'<table class="results"><thead><tr>{head}</tr></thead>'
                        f"<tbody>{rows}</tbody></table>")
        elif b.kind == "figure":
            svg = b.content[b.content.find("<svg"):]
            shown = visible(svg) if inline else svg_image(svg, "figure")
            body.append(f'<div class="figure">{shown}</div>')
        elif b.kind == "formula":
            body.append(f'<div class="formula">{formula_mathml(*b.content)}</div>')
    return "\n".join(body)


def page(title, body, lang="en", style=STYLE) -> str:
    """One self-contained HTML page."""
    return (f'<!DOCTYPE html>\n<html lang="{lang}"><head><meta charset="utf-8">'
            f"<title>{esc(title)}</title><style>{style}</style></head><body>"
            + body + "</body></html>\n")


def to_html(items, lang="en") -> str:
    return page(str(items[0].content) if items else "linkcli", html_body(items), lang)


def to_markdown(items) -> str:
    out = []
    first = True
    for b in items:
        if b.kind == "heading":
            out.append(("# " if first else "## ") + _md(b.content))
            first = False
        elif b.kind == "text":
            out.append(markdown(b.content))
        elif b.kind == "lines":
            out.append(fence(str(x) for x in b.content))
        elif b.kind == "table":
            out.append("\n".join(["| " + " | ".join(_md(h) for h in b.header) + " |",
                                  "|" + " --- |" * len(b.header)] +
                                 ["| " + " | ".join(_md(c) for c in row) + " |"
                                  for row in b.content]))
        elif b.kind == "figure":
            out.append("(figure: see the HTML export)")
        elif b.kind == "formula":
            out.append("$$" + formula_latex(*b.content) + "$$")
    return "\n\n".join(out) + "\n"


def _md(value) -> str:
    """One line of Markdown (a heading, a table cell) showing ``value`` as it is."""
    return markdown(" ".join(str(value).splitlines()))
