"""Check mechanism files without solving them: every problem at once.

A file is read (YAML, size and structure bounds), parsed (every input
problem is collected with its YAML path and line, see
:class:`~linkcli.parsing.InputErrors`; the ``dynamics:`` section too) and,
when the input is valid, its topology is analysed (Grübler's count and the Assur decomposition).  When the
file sets a default ``k`` its expressions are also evaluated for every other
digit, so a value that fails only for some students is found too.

Exit status of a file: 0 valid (a structure that does not decompose into
dyads is valid when ``--method newton`` assembles it), 2 invalid input, 3 valid
input that cannot be solved (mobility, a structure neither method solves).
"""
from __future__ import annotations

from dataclasses import dataclass, field

from linkcli.errors import InputError, LinkcliError, StructureError

DIGITS = range(10)


@dataclass
class Validation:
    """The outcome for one file."""

    file: str
    problems: list = field(default_factory=list)   # message lines
    exit_code: int = 0
    summary: str = ""


def _errors(exc: LinkcliError) -> list:
    return list(getattr(exc, "errors", None) or [exc])


def _lines(errors: list, digits: dict | None = None) -> list[str]:
    """One line per error, in file order; ``digits`` marks errors of other k."""
    digits = digits or {}
    ordered = sorted(errors, key=lambda e: e.line or 0)
    out = []
    for e in ordered:
        text = InputError.__str__(e)
        if id(e) in digits:
            text += " [k = " + ", ".join(str(d) for d in digits[id(e)]) + "]"
        out.append(text)
    return out


def validate_file(path: str, k: int | None = None) -> Validation:
    """Validate ``path`` ('-' for standard input) for digit ``k`` (default: the file's)."""
    from linkcli.input.document import build
    from linkcli.input.source import load_file

    name = "<stdin>" if path == "-" else path
    result = Validation(name)
    try:
        doc = load_file(path)
    except InputError as exc:
        result.problems, result.exit_code = _lines(_errors(exc.located(name))), 2
        return result
    errors, mech = [], None
    try:
        mech = build(doc, k)     # core sections, then masses, inertias, gravity, friction
    except InputError as exc:
        errors = _errors(exc.located(name))
    digits = _other_digits(doc, mech.k if mech else None, errors) if k is None else {}
    if errors:
        result.problems, result.exit_code = _lines(errors, digits), 2
        return result
    if mech.clutch is not None:
        clutch = mech.clutch.clutch
        result.summary = f"a clutch between {clutch.driving} and {clutch.driven or 'the frame'}"
        return result
    from linkcli.kinematics.solvers import figure_cautions, solver_for
    try:
        topology = solver_for(mech).topology
    except StructureError as exc:   # valid, if the numerical method solves it
        return _newton_only(result, mech, exc, name)
    except LinkcliError as exc:
        result.problems, result.exit_code = _lines(_errors(exc.located(name))), exc.exit_code
        return result
    dyads = sum(1 for g in topology.groups if g.is_dyad or g.kind == "RPR-actuator")
    plural = "s" if dyads != 1 else ""
    result.summary = f"Grübler n = {topology.grubler.dof}, {dyads} dyad{plural}"
    cautions = figure_cautions(mech)
    result.problems = [str(c.located(name)) for c in cautions]
    if any(c.kind == "unassembled" for c in cautions):
        result.exit_code = 3          # solve cannot answer at the file's own position
    elif result.problems:
        result.summary += f", {len(result.problems)} warning{'s' if len(result.problems) != 1 else ''}"
    return result


def _newton_only(result, mech, exc, name) -> Validation:
    """A structure the closed form does not decompose: valid when Newton assembles it at
    the file's position (it solves one coordinate); else what ``solve`` will say (exit 3)."""
    from linkcli.kinematics.solvers import solver_for
    if len(mech.coordinates) == 1 and mech.elements is None:
        try:
            solver_for(mech, "newton")
        except LinkcliError as newton:
            result.problems = _lines(_errors(newton.located(name)))
            result.exit_code = newton.exit_code
            return result
        result.summary = f"valid; {exc.detail}: solve it with --method newton"
        return result
    result.problems, result.exit_code = _lines(_errors(exc.located(name))), exc.exit_code
    return result


def _other_digits(doc, default_k, errors: list) -> dict:
    """Add to ``errors`` those that appear only for other digits k (files that set k).

    An error at the same key and line for several digits is listed once;
    returns ``{id(error): [digits]}`` for the added ones.
    """
    from linkcli.input.document import build
    if not isinstance(doc.data, dict) or doc.data.get("k") is None:
        return {}
    seen = {(e.line, e.key) for e in errors}
    added: dict = {}
    first: dict = {}
    tried = [d for d in DIGITS if d != default_k]
    for digit in tried:
        try:
            build(doc, digit)
        except InputError as exc:
            for e in _errors(exc):
                where = (e.line, e.key)
                if where in first:
                    added[id(first[where])].append(digit)
                elif where not in seen:
                    first[where] = e
                    added[id(e)] = [digit]
                    errors.append(e)
    # a problem of every digit does not depend on k: no digits to list
    return {key: digits for key, digits in added.items() if digits != tried}
