"""The formulas of a vibration problem (``--symbolic``), as solve, explain and export
print them.

The file is read twice by the one parser: as always (the numbers of every answer)
and with its parameters as symbols (``input.symbols``), whose model carries each
number's formula.  From that model, ``forces.symbolic`` gives T, V, D, Lagrange's
equations, the equilibrium, the stability conditions, the linearised M, K, R, F and
the characteristic polynomial, and the numeric equilibrium of ``forces.vibration``
chooses among roots or stands where no formula exists (said so).  Every parameter
is its own symbol in SI (``l: 800`` in mm is the symbol l = 0.8 m), g is gravity,
the coordinates are the file's (angles in rad), ``--numbers`` gives some parameters
their numbers.

An item that has no formula (a closed loop, whose position is the root of its closure
equations) is named with the reason instead; no number is ever printed as a formula.

The numeric twin is ``answers.quantities.vibration`` (the same problem's answers); the
formulas are written within the processor time of ``texts.budget``.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from linkcli.errors import InputError

ITEMS = ("T", "V", "D", "equations", "equilibrium", "stability", "M", "K", "R", "F",
         "characteristic")

WORDS = {
    "en": {"title": "Formulas", "symbols": "symbols", "coordinates": "coordinates",
           "energies": "Kinetic energy T, potential energy V, dissipation D",
           "equations": "Lagrange's equations (nonlinear, each = 0)",
           "equilibrium": {"figure": "Static equilibrium: the figure",
                           "solved": "Static equilibrium (Q = -dV/dq = 0)",
                           "numeric": "Static equilibrium: no closed form, the numeric one"},
           "preloads": "preloads (tension > 0) that make the figure the equilibrium",
           "stability": "Stability: the leading principal minors of [K], each > 0",
           "linear": "Linearised about the equilibrium: [M] x'' + [R] x' + [K] x = {F} "
                     "e^(i Omega t)",
           "characteristic": "Characteristic equation det([K] - omega^2 [M]) = 0",
           "roots": "roots", "missing": "not available", "imposed": "imposed",
           "closures": "Closure equations (complex numbers), in the solving order",
           "velocities": "velocities", "accelerations": "accelerations"},
    "it": {"title": "Formule", "symbols": "simboli", "coordinates": "coordinate",
           "energies": "Energia cinetica T, energia potenziale V, funzione dissipativa D",
           "equations": "Equazioni di Lagrange (non lineari, ciascuna = 0)",
           "equilibrium": {"figure": "Equilibrio statico: la configurazione della figura",
                           "solved": "Equilibrio statico (Q = -dV/dq = 0)",
                           "numeric": "Equilibrio statico: nessuna forma chiusa, quello "
                                      "numerico"},
           "preloads": "precarichi (trazione > 0) che rendono la figura l'equilibrio",
           "stability": "Stabilità: i minori principali di testa di [K], ciascuno > 0",
           "linear": "Linearizzato nell'equilibrio: [M] x'' + [R] x' + [K] x = {F} "
                     "e^(i Omega t)",
           "characteristic": "Equazione caratteristica det([K] - omega^2 [M]) = 0",
           "roots": "radici", "missing": "non disponibile", "imposed": "imposta",
           "closures": "Equazioni di chiusura (numeri complessi), nell'ordine di soluzione",
           "velocities": "velocità", "accelerations": "accelerazioni"},
}


@dataclass
class Formulas:
    """The formulas of one vibration file, and what could not be given (``missing``:
    item -> reason)."""

    mech: object                      # the numeric model
    coordinates: list                 # free coordinates' names (rows of M, K, R, F)
    imposed: list                     # imposed coordinates' names
    units: dict                       # coordinate -> SI unit
    symbols: dict                     # name -> SI unit (None: not told)
    kinds: dict                       # name -> kind, for the order of factors
    values: dict = field(default_factory=dict)       # item -> sympy object
    how: str = ""                     # the equilibrium's: figure | solved | numeric
    stated: dict = field(default_factory=dict)       # numeric equilibrium symbol -> value
    preloads: dict = field(default_factory=dict)     # spring -> N formula
    roots: list | None = None
    missing: dict = field(default_factory=dict)
    numbers: dict = field(default_factory=dict)      # symbol -> its value in the file (SI)
    loop: object = None               # LinkageFormulas: the closures, where a loop refuses

    def ranking(self):
        from linkcli.texts.notation import Ranking
        return Ranking(self.kinds, [c.name for c in self.mech.coordinates])


def parse_numbers(text) -> tuple:
    """``--numbers M,L``: the names, checked later against the file's parameters."""
    if text is None:
        return ()
    names = tuple(n.strip() for n in text.split(",") if n.strip())
    if not names:
        raise InputError("--numbers names no parameter", key="--numbers",
                         hint="give parameter names separated by commas, e.g. --numbers M,L")
    return names


def formulas(doc, k=None, numbers=(), seconds=None):
    """The formulas of ``doc`` for digit ``k``: a vibration problem's (Formulas) or a
    linkage's closures (LinkageFormulas); ``numbers`` the parameters given numbers; those
    not written within ``seconds`` of processor time (``texts.budget``, SECONDS by
    default) are named instead."""
    from linkcli.texts.budget import SECONDS, Budget
    from linkcli.input.document import build
    budget = Budget(SECONDS if seconds is None else seconds)
    from linkcli.input.symbols import Symbolic
    mech = build(doc, k)
    if mech.clutch is not None:
        raise InputError("a clutch problem (shafts and a clutch) has no linkage to write as "
                         "formulas", file=mech.file, key="--symbolic",
                         hint="its closed forms are in docs/machines.md")
    known = set(mech.params) | ({"g"} if mech.dynamics is not None else set())
    unknown = [n for n in numbers if n not in known]
    if unknown:
        raise InputError(f"{', '.join(unknown)} is not a parameter of the file",
                         file=mech.file, key="--numbers",
                         hint="parameters: " + (", ".join(sorted(known)) or "none"))
    reading = Symbolic(frozenset(numbers))
    traced = build(doc, k, symbolic=reading)
    if mech.elements is None:
        return closures(mech, traced, reading, budget)
    return vibration(mech, traced, reading, budget, numbers)


def _gravity(mech, numbers):
    """The symbol g of gravity's magnitude; None where it is a number (``--numbers g``, no
    gravity) or a parameter named g is the file's own (gravity is then as written)."""
    import sympy as sp
    if mech.dynamics is None or mech.dynamics.gravity == 0 or "g" in mech.params \
            or "g" in numbers:
        return None
    return sp.Symbol("g", positive=True)


def _table(reading, gravity) -> tuple:
    """({name: kind}, {name: SI unit}) of the parameters, and of g."""
    kinds, units = {}, {}
    for name in reading.parameters:
        kinds[name], units[name] = reading.unit(name)
    if gravity is not None:
        kinds["g"], units["g"] = "gravity", "m/s^2"
    return kinds, units


def vibration(mech, traced, reading, budget, numbers=()) -> Formulas:
    """The formulas of the vibration problem ``traced`` (``mech`` its numeric model), written
    within ``budget`` (``texts.budget``); those not reached are named."""
    from linkcli.kinematics.symbolic import NoClosedForm, Symbols
    gravity = _gravity(mech, numbers)
    values = reading.values()
    if gravity is not None:
        values[gravity] = abs(mech.dynamics.gravity)
    s = Symbols.of(traced, reading.si(), values, gravity)
    kinds, symbols = _table(reading, gravity)
    imposed = set(mech.elements.imposed)
    out = Formulas(mech, [c.name for j, c in enumerate(mech.coordinates) if j not in imposed],
                   [c.name for j, c in enumerate(mech.coordinates) if j in imposed],
                   {c.name: ("rad" if c.base == "angle" else "m") for c in mech.coordinates},
                   symbols, kinds, numbers=dict(values))
    numeric = _numeric_equilibrium(mech)
    try:
        found = budget.run(lambda: _steps(s, numeric, budget))
    except NoClosedForm as exc:
        out.missing = {item: exc.detail for item in ITEMS}
        out.loop = closures(mech, traced, reading, budget)
        return out
    _fill(out, found, budget)
    used = set().union(*({x.name for x in _free(out.values.get(item))} for item in ITEMS))
    out.symbols = {n: u for n, u in out.symbols.items() if n in used}
    return out


def _numeric_equilibrium(mech):
    """The coordinates of the numeric equilibrium (SI): it chooses among roots, and stands
    where the equilibrium has no formula."""
    from linkcli.forces.lagrange import Lagrangian
    from linkcli.forces.vibration import linearise
    from linkcli.kinematics.solvers import solver_for
    return linearise(Lagrangian(mech, solver_for(mech))).eq.q


def _steps(s, numeric, budget) -> None:
    """The formulas step by step, the most asked first, each kept as it is finished: T, V,
    D; the equilibrium; M, K, R; F; the stability conditions; the characteristic polynomial
    (or why it is not written); Lagrange's equations."""
    from linkcli.errors import FormulaLimit
    from linkcli.forces import symbolic as fs
    lag = fs.Lagrangian(s, budget.check)
    budget.keep(T=lag.T, V=lag.V, D=lag.D)
    eq = lag.equilibrium(numeric)
    budget.keep(equilibrium=eq)
    M, K, R = lag.matrices(eq)
    budget.keep(M=M, K=K, R=R)
    budget.keep(F=lag.load(eq))
    budget.check()
    budget.keep(stability=fs.stability(K))
    try:
        budget.keep(characteristic=fs.characteristic(K, M, budget.check))
    except FormulaLimit as exc:
        if exc.reason != "terms":
            raise
        budget.keep(characteristic=exc)
    budget.keep(equations=lag.equations())


def _fill(out: Formulas, found: dict, budget) -> None:
    """``out`` from the steps' ``found`` items; those not found named, with the reason."""
    from linkcli.errors import FormulaLimit
    for item in ITEMS:
        value = found.get(item)
        if value is None:
            out.missing[item] = budget.exceeded().detail
        elif isinstance(value, FormulaLimit):
            out.missing[item] = value.detail
        elif item == "equilibrium":
            out.how, out.stated, out.preloads = value.how, value.stated, value.preloads
            _stated(out, value)
            out.values[item] = {q.name: v for q, v in value.values.items()
                                if q.name in out.coordinates}
        elif item == "characteristic":
            out.values[item], out.roots = value
        else:
            out.values[item] = value


def _stated(out: Formulas, eq) -> None:
    """The numeric equilibrium's symbols q_e: their values, units and kinds."""
    out.numbers.update(eq.stated)
    for symbol in eq.stated:
        unit = out.units[symbol.name[:-2]]
        out.symbols[symbol.name] = unit
        out.kinds[symbol.name] = "angle" if unit == "rad" else "length"


@dataclass
class LinkageFormulas:
    """The closure equations of a linkage, group by group in the solving order."""

    mech: object
    closures: list                    # kinematics.symbolic.Closure
    values: dict                      # symbol -> its formula or number (SI)
    symbols: dict                     # parameter -> SI unit
    kinds: dict

    def ranking(self):
        from linkcli.texts.notation import Ranking
        return Ranking(self.kinds)


def closures(mech, traced, reading, budget) -> LinkageFormulas:
    """The closures of the linkage ``traced`` (its numbers exact), written within ``budget``
    (``texts.budget``): a group not reached is named."""
    from linkcli.kinematics.symbolic import Closure, Closures, Symbols
    s = Symbols(traced, reading.si(), reading.values())
    found = Closures(s, write=False)
    budget.run(lambda: found.write(budget.check))
    written = list(found.closures)
    written += [Closure(g.describe(), missing=budget.exceeded().detail)
                for g in found.groups[len(written):]]
    kinds, symbols = _table(reading, None)
    used = set()
    for c in written:
        for x in (c.left, c.right):
            used |= {v.name for v in _free(x)}
    used |= {v.name for v in _free(list(found.values.values()))}
    return LinkageFormulas(mech, written, dict(found.values),
                           {n: u for n, u in symbols.items() if n in used}, kinds)


def _free(value) -> set:
    if value is None:
        return set()
    if isinstance(value, dict):
        return set().union(*(_free(v) for v in value.values())) if value else set()
    if isinstance(value, (list, tuple)):
        return set().union(*(_free(v) for v in value)) if value else set()
    return set(value.free_symbols)


# --- text --------------------------------------------------------------------------------
def equation_terms(f: Formulas):
    """Terms of an equation: accelerations, rates, the rest, the forcing in t."""
    def key(term):
        names = {s.name for s in term.free_symbols}
        if any(n.endswith("_ddot") for n in names):
            return 0
        if any(n.endswith("_dot") for n in names):
            return 1
        return 3 if "t" in names else 2
    return key


@dataclass
class Entry:
    """One written formula: ``label``, the sympy object (expression or matrix) and how
    it reads: 'is' (label = value), 'zero' (value = 0), 'positive' (value > 0)."""

    label: str
    value: object
    reads: str = "is"
    terms: object = None


def sections(f, lang="en") -> list:
    """[(heading, [Entry or text line])]: the formulas as every format writes them."""
    import sympy as sp
    from linkcli.forces.symbolic import OMEGA
    w = WORDS[lang]
    if isinstance(f, LinkageFormulas):
        return linkage_sections(f, lang)
    symbols = ", ".join(f"{n} ({u})" if u else f"{n}" for n, u in sorted(f.symbols.items()))
    coords = ", ".join(f"{n} ({f.units[n]})" for n in f.coordinates)
    if f.imposed:
        coords += f"; {w['imposed']}: " + ", ".join(f"{n} ({f.units[n]})" for n in f.imposed)
    out = [(w["title"], [f"{w['symbols']}: {symbols or '-'}", f"{w['coordinates']}: {coords}"])]
    for reason in sorted(set(f.missing.values())):
        items = ", ".join(i for i in ITEMS if f.missing.get(i) == reason)
        out.append((f"{items}: {w['missing']}", [reason]))
    if f.loop is not None:
        return out + linkage_sections(f.loop, lang)
    v = f.values
    if "T" in v:
        out.append((w["energies"], [Entry(item, v[item]) for item in ("T", "V", "D")]))
    if "equations" in v:
        out.append((w["equations"], [Entry(f"({n})", e, "zero", equation_terms(f))
                                     for n, e in zip(f.coordinates, v["equations"])]))
    if "equilibrium" in v:
        out.append((w["equilibrium"][f.how], _equilibrium_entries(f, w)))
    if "stability" in v:
        out.append((w["stability"], [Entry("", m, "positive") for m in v["stability"]]))
    if "M" in v:
        out.append((w["linear"], [f"x = {{{', '.join(f.coordinates)}}}"] +
                    [Entry(f"[{item}]", v[item]) for item in ("M", "K", "R")] +
                    ([Entry("{F}", sp.Matrix(v["F"]))] if "F" in v else [])))
    if "characteristic" in v:
        characteristic = [Entry("", v["characteristic"], "zero", _powers(OMEGA))]
        if f.roots is not None:
            characteristic += [Entry("omega^2", r) for r in f.roots]
        out.append((w["characteristic"], characteristic))
    return out


def _equilibrium_entries(f: Formulas, w) -> list:
    """q_e of each free coordinate (a numeric one as its symbol's value), the preloads."""
    import sympy as sp
    out = []
    for name, value in f.values["equilibrium"].items():
        if isinstance(value, sp.Symbol) and value in f.stated:
            out.append(f"{value.name} = {f.stated[value]:.10g} {f.units[name]}")
        else:
            out.append(Entry(name, value))
    if f.preloads:
        out.append(w["preloads"] + ":")
        out += [Entry(f"N_{n}", x) for n, x in f.preloads.items()]
    return out


def linkage_sections(f: LinkageFormulas, lang="en") -> list:
    import sympy as sp
    w = WORDS[lang]
    symbols = ", ".join(f"{n} ({u})" if u else f"{n}" for n, u in sorted(f.symbols.items()))
    out = [(w["closures"], [f"{w['symbols']}: {symbols or '-'}"] +
            [Entry(x.name, v) for x, v in f.values.items()])]
    for i, c in enumerate(f.closures, 1):
        entries = []
        if c.missing:
            entries.append(c.missing)
        elif c.right is None and c.left is not None:
            entries.append(Entry("", (sp.Symbol(c.point), c.left), "equation"))
        elif c.left is not None:
            entries.append(Entry("", (c.left, c.right), "equation"))
            rates = [sp.Symbol(f"{u.name}_dot") for u in c.unknowns]
            accels = [sp.Symbol(f"{u.name}_ddot") for u in c.unknowns]
            entries.append(Entry(w["velocities"], (c.matrix, sp.Matrix(rates), c.velocity),
                                 "system"))
            entries.append(Entry(w["accelerations"], (c.matrix, sp.Matrix(accels),
                                                      c.acceleration), "system"))
        out.append((f"{i}. {c.text}", entries))
    return out


def to_text(f, lang="en") -> str:
    """The formulas in exam notation."""
    import sympy as sp
    from linkcli.texts.notation import text
    rk = f.ranking()
    lines = []
    for i, (heading, entries) in enumerate(sections(f, lang)):
        lines += ([""] if i else []) + [heading]
        for e in entries:
            if not isinstance(e, Entry):
                lines.append(f"  {e}")
            elif isinstance(e.value, sp.MatrixBase):
                lines += matrix_lines(e.label, e.value, lambda x: text(x, rk))
            elif e.reads == "equation":
                lines.append(f"  {text(e.value[0], rk)} = {text(e.value[1], rk)}")
            elif e.reads == "system":
                lines += system_lines(e.label, *e.value, lambda x: text(x, rk))
            else:
                body = text(e.value, rk, e.terms)
                lines.append("  " + {"is": f"{e.label} = {body}",
                                     "zero": f"{e.label} {body} = 0".strip(),
                                     "positive": f"{body} > 0"}[e.reads])
    return "\n".join(lines)


def _powers(symbol):
    """Terms of a polynomial in ``symbol`` by descending power."""
    def key(term):
        return -sum(e for b, e in term.as_powers_dict().items() if b == symbol)
    return key


def system_lines(label, A, u, b, t) -> list:
    """A u = b as aligned rows: [ a  b ] { u1 } = { b1 }."""
    cells = [[t(A[i, j]) for j in range(A.shape[1])] for i in range(A.shape[0])]
    widths = [max(len(r[j]) for r in cells) for j in range(A.shape[1])]
    us, bs = [t(x) for x in u], [t(x) for x in b]
    wu, wb = max(map(len, us)), max(map(len, bs))
    out = [f"  {label}:"]
    for i, row in enumerate(cells):
        middle = " = " if i == len(cells) // 2 else "   "
        out.append("    [ " + "   ".join(c.ljust(widths[j]) for j, c in enumerate(row)) +
                   f" ] {{ {us[i].ljust(wu)} }}{middle}{{ {bs[i].ljust(wb)} }}")
    return out


def matrix_lines(name, A, t) -> list:
    """A matrix as aligned rows: M = [ a  b ] / [ c  d ]."""
    cells = [[t(A[i, j]) for j in range(A.shape[1])] for i in range(A.shape[0])]
    widths = [max(len(cells[i][j]) for i in range(len(cells))) for j in range(A.shape[1])]
    out = []
    for i, row in enumerate(cells):
        body = "   ".join(c.ljust(widths[j]) for j, c in enumerate(row))
        lead = f"  {name} = " if i == 0 else " " * (len(name) + 5)
        out.append(f"{lead}[ {body} ]")
    return out


# --- JSON --------------------------------------------------------------------------------
def as_dict(f) -> dict:
    """The formulas as strings sympy.sympify reads (with the coordinates and symbols as
    local names: sympify(text, locals=...)), SI, rates as NAME_dot and NAME_ddot."""
    import sympy as sp

    def s(expr):
        return sp.sstr(expr)

    if isinstance(f, LinkageFormulas):
        groups = []
        for c in f.closures:
            item = {"group": c.text, "missing": c.missing or None}
            if c.left is not None:
                item["closure"] = [s(c.left), None if c.right is None else s(c.right)]
            if c.matrix is not None:
                item["unknowns"] = [u.name for u in c.unknowns]
                item["matrix"] = [[s(x) for x in row] for row in c.matrix.tolist()]
                item["velocity"] = [s(x) for x in c.velocity]
                item["acceleration"] = [s(x) for x in c.acceleration]
            groups.append(item)
        return {"symbols": dict(sorted(f.symbols.items())),
                "values": {x.name: s(v) for x, v in f.values.items()}, "groups": groups}

    out = {"coordinates": list(f.coordinates), "imposed": list(f.imposed),
           "units": {n: f.units[n] for n in f.coordinates + f.imposed},
           "symbols": dict(sorted(f.symbols.items())), "missing": dict(f.missing)}
    if f.loop is not None:
        out["closures"] = as_dict(f.loop)
    v = f.values
    for item in ("T", "V", "D", "characteristic"):
        if item in v:
            out[item] = s(v[item])
    for item in ("M", "K", "R"):
        if item in v:
            out[item] = [[s(x) for x in row] for row in v[item].tolist()]
    for item in ("F", "equations", "stability"):
        if item in v:
            out[item] = [s(x) for x in v[item]]
    if "characteristic" in v:
        out["roots"] = None if f.roots is None else [s(r) for r in f.roots]
    if "equilibrium" in v:
        out.update({"equilibrium": {n: s(x) for n, x in v["equilibrium"].items()},
                    "equilibrium_kind": f.how,
                    "equilibrium_values": {sym.name: val for sym, val in f.stated.items()},
                    "preloads": {n: s(x) for n, x in f.preloads.items()}})
    return out


def append(text, form, doc, k=None, numbers=None, lang="en", seconds=None) -> str:
    """``text`` (a report in ``form``) with the formulas of ``doc``: a "symbolic" key of
    the JSON object, else the formulas' text after it."""
    f = formulas(doc, k, parse_numbers(numbers), seconds)
    if form == "json":
        import json
        data = json.loads(text)
        data["symbolic"] = as_dict(f)
        return json.dumps(data, indent=2, allow_nan=True)
    return text.rstrip("\n") + "\n\n" + to_text(f, lang)
