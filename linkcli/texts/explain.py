"""The answer to an exam's Assur question: Grübler's count and the solving order."""
from __future__ import annotations

from linkcli.kinematics.solvers import solver_for
from linkcli.errors import LinkcliError
from linkcli.kinematics.grubler import driver_text, grubler
from linkcli.model.mechanism import FRAME


def explain(mech, method: str = "closed") -> str:
    """Grübler's count, then what ``method`` solves: the Assur decomposition in its solving
    order ('closed'), or the constraint equations Newton solves together ('newton'), and
    the statics or dynamics equation."""
    from linkcli.runs import design
    from linkcli.runs.sheet import evaluate, refuse_driving
    refuse_driving(mech, method=method)
    asked, mech = mech, design.resolved(mech, evaluate)     # a design question: its solution's
    solver = solver_for(mech, method)
    count = grubler(mech)
    lines = [mech.title, "", "Grübler's count (planar)",
             f"  bodies m = {count.m}: " + ", ".join(count.bodies),
             f"  revolute pairs R = {count.r}: " + ", ".join(
                 f"{p} ({'-'.join(b)})" if len(b) == 2 else f"{p} x{len(b) - 1} ({'-'.join(b)})"
                 for p, b in count.revolutes),
             f"  prismatic pairs P = {count.p}: " + (", ".join(
                 f"{name} ({b1}-{b2})" for name, b1, b2 in count.prismatics) or "none")] + (
                [f"  higher pairs H = {count.h}: " + ", ".join(
                    f"{n} ({mech.rolling[n].disc}, {'cord' if mech.rolling[n].kind in ('cord', 'belt') else 'rolling'})"
                    for n in count.higher)] if count.h else []) + [f"  {count.formula()}", ""]
    lines += _newton_lines(mech, solver) if method == "newton" else \
        _order_lines(mech, solver, asked)
    if any(b.kind == "block" and _turns(mech, b.guide.carrier) for b in mech.bodies.values()):
        lines.append("  (sliders on turning guides add Coriolis terms to the accelerations)")
    if mech.elements is not None:
        from linkcli.answers.quantities.vibration import explain_lines
        lines += [""] + explain_lines(mech)
    elif mech.dynamics is not None:
        from linkcli.forces.balance import balance_lines
        lines += [""] + balance_lines(mech)
    else:
        lines += ["", "Statics by virtual work: sum of load powers = 0"] + _statics_terms(mech)
    return "\n".join(lines + design.explain_lines(asked, evaluate))


def _order_lines(mech, solver, asked) -> list:
    """The closed form's decomposition and solving order, with the cautions of the figure
    (of ``asked``: the file's values, before a design question is solved)."""
    lines = ["Decomposition and solving order"]
    if len(mech.coordinates) > 1 or mech.elements is not None:
        for c in mech.coordinates:
            lines.append(f"  coordinate {c.name} = {driver_text(c)}")
        lines += [f"  {line}" for line in getattr(solver, "substitution", lambda: [])()]
    else:
        lines.append(f"  driver q = {driver_text(mech.driver)}")
    step = 0
    for group in solver.groups:
        if group.kind == "place":
            lines.append(f"       then {group.describe()}")
            continue
        step += 1
        drawn = "as in the figure" if not solver.undetermined else "not determined by the figure"
        branch = f"  (branch {'+' if group.branch > 0 else '-'} {drawn})" \
            if group.kind in ("RRR", "RRP", "PRR", "RPR") else ""
        lines.append(f"  {step}. {group.describe()}{branch}")
    from linkcli.kinematics.solvers import figure_cautions
    return lines + [f"  {c}" for c in figure_cautions(asked)]


def _newton_lines(mech, solver) -> list:
    """What Newton-Raphson solves: the unknown coordinates of the moving points, every
    constraint equation at once (g(x, q) = 0, as many as unknowns), from the figure's
    positions; then J v = -g_q qdot and J a = (right-hand side) for the rates."""
    system = solver.system
    equations = [r.label for r in system.rows] + [f"{rel.name}: rolling without slipping"
                                                  for rel, _ in system.contacts]
    lines = ["Newton-Raphson on the constraint equations (--method newton), no decomposition",
             f"  driver q = {driver_text(mech.driver)}",
             f"  unknowns: x and y of the {system.nm} moving points "
             f"{', '.join(system.moving)} ({system.n})",
             f"  equations g(x, q) = 0, all {len(equations)} solved together at each q:"]
    lines += [f"    {i}. {label}" for i, label in enumerate(equations, 1)]
    lines += ["  positions: from the figure's points at the file's q (its branch as drawn), "
              "continued along q in halved steps without jumping branches",
              "  velocities and accelerations: J xdot = -dg/dq qdot, J xddot = rhs, with J = "
              "dg/dx the Jacobian"]
    return lines + [f"  (closed form: {_closed_form_reach(mech)})"]


def _closed_form_reach(mech) -> str:
    """Whether the closed form would solve the same file: its groups, or where it stops."""
    try:
        groups = solver_for(mech).groups
    except LinkcliError as exc:
        return f"not available: {exc.detail}"
    dyads = sum(g.kind != "place" for g in groups)
    return f"{dyads} group{'s' if dyads != 1 else ''} solved in order, as 'linkcli explain' " \
        "without --method lists them"


def _statics_terms(mech) -> list:
    """sum L v = 0 in words; with several drivers once per driver's motion (the others at
    rest), a driver's own load working on its driver only."""
    several = len(mech.coordinates) > 1 and mech.elements is None
    if not mech.loads:
        return ["  (no loads)"]
    if not several:
        return ["  " + _power_sum(mech, None) + " = 0"]
    return [f"  motion of {d.name} alone: " + _power_sum(mech, d.name) + " = 0"
            for d in mech.coordinates]


def _power_sum(mech, driver) -> str:
    """' + '-joined L * v terms of the loads for the motion of ``driver`` (None: q's)."""
    terms = []
    for load in mech.loads.values():
        if load.kind == "driver" and driver is not None:
            if load.target == driver:
                terms.append(f"{load.name} * {driver}dot")
            continue
        target = {"force": f"v_{load.target}", "torque": f"omega_{load.target}",
                  "axial": f"d|{load.target}|/dt", "driver": "qdot"}[load.kind]
        terms.append(f"{load.name} * {target}")
    return " + ".join(terms)


def _turns(mech, carrier: str) -> bool:
    """Whether a guide's carrier turns: the frame does not, nor a slider block that runs on a
    guide that does not turn (a Scotch yoke's block translates: no Coriolis term)."""
    if carrier == FRAME:
        return False
    body = mech.bodies[carrier]
    return body.kind != "block" or _turns(mech, body.guide.carrier)
