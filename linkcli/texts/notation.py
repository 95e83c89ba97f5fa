"""Formulas written as the exam writes them: plain text, LaTeX and MathML.

A sympy expression is laid out once (:func:`layout`: sums, products with their
fraction, powers, roots, calls, symbols) and rendered three ways.  A product
orders its factors as the exam does, the number first, then masses and inertias,
stiffnesses and dampings, forces, gravity g, frequencies, lengths, the coordinates
and their functions (2 m g L, 4 k L^2, m L^2 cos(phi - theta)); a sum of the
product's factors goes by its first symbol ((3M + 2m)(R - r)^2).  A coordinate's
rate ``x_dot`` is written x' (text) or with a dot (LaTeX, MathML), its second rate
x''.  Numbers are exact fractions; a rounded number (a Float, only where a formula
holds a numeric value stated as such) is printed with 6 significant digits.
"""
from __future__ import annotations

import html
import re

import sympy as sp

#: the order of a product's factors by the kind of their symbols
RANKS = {"mass": 0, "inertia": 1, "stiffness": 2, "torsional_stiffness": 2, "damping": 3,
         "torsional_damping": 3, "force": 4, "torque": 4, "gravity": 5, "frequency": 6,
         "angular_rate": 6, "speed": 6, "length": 7, "angle": 8}
OTHER, COORDINATE, RATE = 9, 10, 11

GREEK = {"alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε",
         "zeta": "ζ", "eta": "η", "theta": "θ", "iota": "ι", "kappa": "κ", "lambda": "λ",
         "mu": "μ", "nu": "ν", "xi": "ξ", "pi": "π", "rho": "ρ", "sigma": "σ", "tau": "τ",
         "upsilon": "υ", "phi": "φ", "chi": "χ", "psi": "ψ", "omega": "ω",
         "Gamma": "Γ", "Delta": "Δ", "Theta": "Θ", "Lambda": "Λ", "Xi": "Ξ", "Pi": "Π",
         "Sigma": "Σ", "Phi": "Φ", "Psi": "Ψ", "Omega": "Ω"}
FUNCTIONS = {"sin": "sin", "cos": "cos", "tan": "tan", "atan2": "atan2", "exp": "exp",
             "re": "Re", "im": "Im", "asin": "asin", "acos": "acos", "atan": "atan"}


class Ranking:
    """The rank of every symbol: its kind's (``kinds``: name -> kind) or a
    coordinate's or a rate's."""

    def __init__(self, kinds=None, coordinates=()):
        self.kinds = dict(kinds or {})
        self.coordinates = set(coordinates)

    def symbol(self, s) -> int:
        name = s.name
        if name.endswith("_dot") or name.endswith("_ddot"):
            return RATE
        if name in self.coordinates:
            return COORDINATE
        return RANKS.get(self.kinds.get(name), OTHER)

    def factor(self, f) -> tuple:
        """A product's factors: numbers, symbols (and their powers) by rank, then sums,
        then functions (m L^2 phi' theta' cos(phi - theta))."""
        if not f.free_symbols:
            return (0, -1, str(f))
        base = f.base if isinstance(f, sp.Pow) else f
        if isinstance(base, sp.Symbol):
            return (1, self.symbol(base), base.name)
        symbols = sorted(f.free_symbols, key=lambda s: (self.symbol(s), s.name))
        kind = 3 if isinstance(base, sp.Function) else 2
        return (kind, self.symbol(symbols[0]), str(f))


# --- layout ----------------------------------------------------------------------------
# nodes: ("sum", [(negative, node)]), ("product", [node]), ("fraction", num, den),
# ("power", base, exponent), ("root", node), ("call", name, [node]), ("abs", node),
# ("symbol", name, primes), ("number", text), ("i",), ("pi",), ("group", node)

SUM, PRODUCT, POWER, ATOM = 1, 2, 3, 4


def layout(expr, ranking: Ranking, terms=None):
    """The layout tree of ``expr``; ``terms`` orders a sum's terms (default sympy's)."""
    expr = sp.sympify(expr)
    if isinstance(expr, sp.Add):
        args = list(expr.as_ordered_terms())
        if terms is not None:
            args.sort(key=terms)
        out = []
        for a in args:
            negative = a.could_extract_minus_sign()
            out.append((negative, layout(-a if negative else a, ranking)))
        return ("sum", out)
    if isinstance(expr, sp.Mul) or (isinstance(expr, sp.Rational) and not expr.is_Integer):
        return _product(expr, ranking)
    if isinstance(expr, sp.Pow):
        if expr.exp == sp.Rational(1, 2):
            return ("root", layout(expr.base, ranking))
        if expr.exp.is_negative:
            return _product(expr, ranking)
        base = expr.base
        if expr.exp.is_even and isinstance(base, sp.Add) and base.could_extract_minus_sign():
            base = -base                    # (R - r)^2, not (-R + r)^2
        return ("power", _factor(base, ranking), layout(expr.exp, ranking))
    if isinstance(expr, sp.Symbol):
        name = expr.name
        for suffix, primes in (("_ddot", 2), ("_dot", 1)):
            if name.endswith(suffix):
                return ("symbol", name[:-len(suffix)], primes)
        return ("symbol", name, 0)
    if expr is sp.I:
        return ("i",)
    if expr is sp.pi:
        return ("pi",)
    if isinstance(expr, sp.Integer):
        return ("number", str(expr))
    if isinstance(expr, sp.Float):
        return ("number", f"{float(expr):.6g}")
    if isinstance(expr, sp.Abs):
        return ("abs", layout(expr.args[0], ranking))
    if isinstance(expr, sp.exp):                   # e^(i alpha), as the closures write it
        return ("power", ("symbol", "e", 0), layout(expr.args[0], ranking))
    if isinstance(expr, sp.Function):
        name = FUNCTIONS.get(expr.func.__name__, expr.func.__name__)
        return ("call", name, [layout(a, ranking) for a in expr.args])
    if expr.is_Number:
        return ("number", str(expr))
    return ("symbol", str(expr), 0)


def _product(expr, ranking):
    """A product as its numerator and denominator factors, each in the exam's order."""
    coeff, rest = expr.as_coeff_Mul()
    negative = coeff < 0
    coeff = -coeff if negative else coeff
    num, den = [], []
    for f in sp.Mul.make_args(rest):
        if f == 1:
            continue
        if isinstance(f, sp.Pow) and f.exp.is_negative:
            den.append(f.base if f.exp == -1 else sp.Pow(f.base, -f.exp))
        else:
            num.append(f)
    num.sort(key=ranking.factor)
    den.sort(key=ranking.factor)
    p, q = sp.fraction(sp.Rational(coeff)) if coeff.is_Rational else (coeff, 1)
    top = ([("number", str(p))] if p != 1 or not num else []) + \
        [_factor(f, ranking) for f in num]
    bottom = ([("number", str(q))] if q != 1 else []) + [_factor(f, ranking) for f in den]
    node = top[0] if len(top) == 1 else ("product", top)
    if bottom:
        node = ("fraction", node, bottom[0] if len(bottom) == 1 else ("product", bottom))
    return ("sum", [(True, node)]) if negative else node


def _factor(f, ranking):
    node = layout(f, ranking)
    return ("group", node) if node[0] == "sum" else node


def precedence(node) -> int:
    kind = node[0]
    if kind == "sum":
        return SUM if len(node[1]) > 1 or node[1][0][0] else ATOM
    if kind in ("product", "fraction"):
        return PRODUCT
    if kind == "power":
        return POWER
    if kind == "number" and node[1].startswith("-"):
        return SUM
    return ATOM


def parenthesised(node, level) -> bool:
    """Whether ``node`` needs parentheses where ``level`` binds: a sum in a product, a
    product or fraction as a power's base or a denominator."""
    return precedence(node) < level or (level >= POWER and node[0] in ("product", "fraction"))


class Writer:
    """Renders a layout tree; a format gives its pieces (``sum_term``, ``wrap`` ...)."""

    times = " "

    def write(self, node) -> str:
        return getattr(self, node[0])(node)

    def paren(self, node, level) -> str:
        body = self.write(node)
        return self.wrap(body) if parenthesised(node, level) else body

    def sum(self, node) -> str:
        return self.terms([(negative, self.write(term) if not negative else
                            self.paren(term, SUM + 1)) for negative, term in node[1]])

    def group(self, node) -> str:
        return self.wrap(self.write(node[1]))

    def product(self, node) -> str:
        return self.join([self.paren(f, PRODUCT) for f in node[1]])

    def unwrapped(self, node):
        return node[1] if node[0] == "group" else node


class TextWriter(Writer):
    def terms(self, terms) -> str:
        out = ""
        for i, (negative, body) in enumerate(terms):
            out += (("-" if negative else "") if i == 0 else
                    (" - " if negative else " + ")) + body
        return out

    def wrap(self, body) -> str:
        return f"({body})"

    def join(self, parts) -> str:
        return " ".join(parts)

    def fraction(self, node) -> str:
        return f"{self.paren(node[1], PRODUCT)}/{self.paren(node[2], POWER)}"

    def power(self, node) -> str:
        return f"{self.paren(node[1], ATOM)}^{self.paren(node[2], ATOM)}"

    def root(self, node) -> str:
        return f"sqrt({self.write(node[1])})"

    def call(self, node) -> str:
        return f"{node[1]}(" + ", ".join(self.write(a) for a in node[2]) + ")"

    def abs(self, node) -> str:
        return f"|{self.write(node[1])}|"

    def symbol(self, node) -> str:
        return node[1] + "'" * node[2]

    def i(self, node) -> str:
        return "i"

    def pi(self, node) -> str:
        return "pi"

    def number(self, node) -> str:
        return node[1]


class LatexWriter(TextWriter):
    def wrap(self, body) -> str:
        return f"\\left({body}\\right)"

    def fraction(self, node) -> str:
        num, den = (self.unwrapped(n) for n in node[1:3])
        return f"\\frac{{{self.write(num)}}}{{{self.write(den)}}}"

    def power(self, node) -> str:
        base, exponent = node[1], self.write(node[2])
        if base[0] == "call" and base[1] in ("sin", "cos", "tan"):
            return f"\\{base[1]}^{{{exponent}}}" \
                f"\\left({', '.join(self.write(a) for a in base[2])}\\right)"
        return f"{self.paren(base, ATOM)}^{{{exponent}}}"

    def root(self, node) -> str:
        return f"\\sqrt{{{self.write(node[1])}}}"

    def call(self, node) -> str:
        name = f"\\{node[1]}" if node[1] in ("sin", "cos", "tan", "exp") else \
            f"\\operatorname{{{node[1]}}}"
        return f"{name}\\left(" + ", ".join(self.write(a) for a in node[2]) + "\\right)"

    def abs(self, node) -> str:
        return f"\\left|{self.write(node[1])}\\right|"

    def symbol(self, node) -> str:
        name = latex_name(node[1])
        return {0: name, 1: f"\\dot{{{name}}}", 2: f"\\ddot{{{name}}}"}[node[2]]

    def pi(self, node) -> str:
        return "\\pi"


class MathMLWriter(Writer):
    def terms(self, terms) -> str:
        out = []
        for i, (negative, body) in enumerate(terms):
            if negative:
                out.append("<mo>&#x2212;</mo>")
            elif i:
                out.append("<mo>+</mo>")
            out.append(body)
        return "<mrow>" + "".join(out) + "</mrow>"

    def wrap(self, body) -> str:
        return f"<mrow><mo>(</mo>{body}<mo>)</mo></mrow>"

    def join(self, parts) -> str:
        return "<mrow>" + "<mo>&#x2062;</mo>".join(parts) + "</mrow>"

    def fraction(self, node) -> str:
        num, den = (self.unwrapped(n) for n in node[1:3])
        return f"<mfrac>{self.write(num)}{self.write(den)}</mfrac>"

    def power(self, node) -> str:
        base = node[1]
        if base[0] == "call" and base[1] in ("sin", "cos", "tan"):     # cos^2(phi)
            args = "<mo>,</mo>".join(self.write(a) for a in base[2])
            return f"<mrow><msup><mi>{base[1]}</mi>{self.write(node[2])}</msup>" \
                f"<mo>&#x2061;</mo>{self.wrap(args)}</mrow>"
        return f"<msup>{self.paren(base, ATOM)}{self.write(node[2])}</msup>"

    def root(self, node) -> str:
        return f"<msqrt>{self.write(node[1])}</msqrt>"

    def call(self, node) -> str:
        args = "<mo>,</mo>".join(self.write(a) for a in node[2])
        return f"<mrow><mi>{html.escape(node[1])}</mi><mo>&#x2061;</mo>{self.wrap(args)}</mrow>"

    def abs(self, node) -> str:
        return f"<mrow><mo>|</mo>{self.write(node[1])}<mo>|</mo></mrow>"

    def symbol(self, node) -> str:
        name = mml_name(node[1])
        if node[2]:        # plain dots: an accent's glyph is lost over a tall letter
            return f"<mover>{name}<mo>{'.' * node[2]}</mo></mover>"
        return name

    def i(self, node) -> str:
        return "<mi>i</mi>"

    def pi(self, node) -> str:
        return "<mi>&#x3C0;</mi>"

    def number(self, node) -> str:
        return f"<mn>{html.escape(node[1])}</mn>"


def _name_parts(name: str) -> tuple:
    """(base, subscript) of a symbol's name: Greek letters by name, a trailing number, a
    part after '_' or the letters after the first as a subscript (l1, theta_e, ks, JL)."""
    match = re.fullmatch(r"([A-Za-z]+?)(\d+|_[A-Za-z0-9_]+)?", name)
    base, sub = (match.group(1), match.group(2)) if match else (name, None)
    if match and base not in GREEK and sub is None and len(base) > 1:
        base, sub = base[0], base[1:]
    return base, (sub.lstrip("_").replace("_", ",") if sub else None)


def latex_name(name: str) -> str:
    """A symbol's LaTeX (phi as varphi): l1 -> l_{1}, theta_e -> \\theta_{e}, ks -> k_{s}."""
    base, sub = _name_parts(name)
    head = "\\varphi" if base == "phi" else f"\\{base}" if base in GREEK else base
    return f"{head}_{{{sub}}}" if sub else head


def mml_name(name: str) -> str:
    """A symbol as <mi> (Greek by name) with its subscript as latex_name's."""
    base, sub = _name_parts(name)
    head = f"<mi>{html.escape(GREEK.get(base, base))}</mi>"
    if sub:
        tag = "mn" if sub.isdigit() else "mi"
        return f"<msub>{head}<{tag}>{html.escape(sub)}</{tag}></msub>"
    return head


def text(expr, ranking: Ranking | None = None, terms=None) -> str:
    """``expr`` as plain text: 2 m g L + 4 k L^2, m L^2 phi' theta' cos(phi - theta)."""
    return TextWriter().write(layout(expr, ranking or Ranking(), terms))


def latex(expr, ranking: Ranking | None = None, terms=None) -> str:
    """``expr`` in LaTeX: 2 m g L, \\frac{k L^{2}}{2}, \\dot{\\varphi}."""
    return LatexWriter().write(layout(expr, ranking or Ranking(), terms))


def mathml(expr, ranking: Ranking | None = None, terms=None, display=False) -> str:
    """``expr`` as presentation MathML (one <math> element)."""
    body = MathMLWriter().write(layout(expr, ranking or Ranking(), terms))
    mode = ' display="block"' if display else ""
    return f'<math xmlns="http://www.w3.org/1998/Math/MathML"{mode}>{body}</math>'


def latex_matrix(A, ranking: Ranking | None = None) -> str:
    """A matrix (or column) in LaTeX: \\begin{bmatrix} a & b \\\\ c & d \\end{bmatrix}."""
    rows = [" & ".join(latex(A[i, j], ranking) for j in range(A.shape[1]))
            for i in range(A.shape[0])]
    return "\\begin{bmatrix} " + " \\\\ ".join(rows) + " \\end{bmatrix}"


def mathml_matrix(A, ranking: Ranking | None = None) -> str:
    """A matrix (or column) as a MathML table of class 'matrix' (no <math> element): the
    page draws its brackets with CSS, which needs no stretchy glyphs of a math font."""
    writer = MathMLWriter()
    rows = "".join("<mtr>" + "".join(
        f"<mtd>{writer.write(layout(A[i, j], ranking or Ranking()))}</mtd>"
        for j in range(A.shape[1])) + "</mtr>" for i in range(A.shape[0]))
    return f'<mtable class="matrix">{rows}</mtable>'      # its brackets: the page's CSS


def mathml_body(expr, ranking: Ranking | None = None, terms=None) -> str:
    """``expr`` as MathML without the <math> element (to compose an equation)."""
    return MathMLWriter().write(layout(expr, ranking or Ranking(), terms))


def mathml_terms(expr, ranking: Ranking | None = None, terms=None) -> list:
    """``expr`` as MathML pieces (no <math> element), one per term of a sum, each with its
    sign ('+' or '-' before every term but a positive first): a page sets each piece as
    its own inline formula, so that a long sum breaks between terms as words do (MathML
    Core has no line breaking); an expression that is not a sum is one piece."""
    tree = layout(expr, ranking or Ranking(), terms)
    if tree[0] != "sum":
        return [MathMLWriter().write(tree)]
    writer, out = MathMLWriter(), []
    for i, (negative, term) in enumerate(tree[1]):
        body = writer.paren(term, SUM + 1) if negative else writer.write(term)
        form = ' form="infix"' if i else ""          # spaced as between two terms
        sign = "&#x2212;" if negative else "+" if i else ""
        out.append((f"<mo{form}>{sign}</mo>" if sign else "") + body)
    return out


def label_latex(label: str) -> str:
    """A formula's label in LaTeX: [M] -> [M], {F} -> \\{F\\}, N_k1 -> N_{k1}."""
    if label.startswith("{") and label.endswith("}"):
        return "\\{" + label[1:-1] + "\\}"
    if label.startswith("("):
        return f"({latex_name(label[1:-1])})"
    if label.startswith("["):
        return label
    base, _, sub = label.partition("_")
    if label == "omega^2":
        return "\\omega^{2}"
    return f"{base}_{{{sub}}}" if sub else latex_name(label)


def label_mathml(label: str) -> str:
    if label == "omega^2":
        return "<msup><mi>&#x3C9;</mi><mn>2</mn></msup>"
    if label[:1] in "([{":
        return f"<mrow><mo>{html.escape(label[0])}</mo>{mml_name(label[1:-1])}" \
            f"<mo>{html.escape(label[-1])}</mo></mrow>"
    base, _, sub = label.partition("_")
    if sub:
        return f"<msub><mi>{html.escape(base)}</mi><mi>{html.escape(sub)}</mi></msub>"
    return mml_name(label)
