"""The answer to an exam's Assur question: Grübler's count and the solving order."""
from __future__ import annotations

from linkcli.kinematics.solvers import solver_for
from linkcli.model.mechanism import FRAME


def explain(mech) -> str:
    from linkcli.runs import design
    from linkcli.runs.sheet import evaluate
    asked, mech = mech, design.resolved(mech, evaluate)     # a design question: its solution's
    solver = solver_for(mech)
    count = solver.topology.grubler
    lines = [mech.title, "", "Grübler's count (planar)",
             f"  bodies m = {count.m}: " + ", ".join(count.bodies),
             f"  revolute pairs R = {count.r}: " + ", ".join(
                 f"{p} ({'-'.join(b)})" if len(b) == 2 else f"{p} x{len(b) - 1} ({'-'.join(b)})"
                 for p, b in count.revolutes),
             f"  prismatic pairs P = {count.p}: " + (", ".join(
                 f"{name} ({b1}-{b2})" for name, b1, b2 in count.prismatics) or "none")] + (
                [f"  higher pairs H = {count.h}: " + ", ".join(
                    f"{n} ({mech.rolling[n].disc}, {'cord' if mech.rolling[n].kind in ('cord', 'belt') else 'rolling'})"
                    for n in count.higher)] if count.h else []) + [
             f"  {count.formula()}", "", "Decomposition and solving order"]
    if len(mech.coordinates) > 1 or mech.elements is not None:
        for c in mech.coordinates:
            lines.append(f"  coordinate {c.name} = {_what(c)}")
        lines += [f"  {line}" for line in getattr(solver, "substitution", lambda: [])()]
    else:
        lines.append(f"  driver q = {_what(mech.driver)}")
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
    lines += [f"  {c}" for c in figure_cautions(mech)]
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


def _what(d) -> str:
    return {"angle": f"angle of {d.a}->{d.b}", "length": f"length {d.a}{d.b}",
            "x": f"x of {d.a}", "y": f"y of {d.a}"}[d.kind]


def _statics_terms(mech) -> list:
    terms = []
    for load in mech.loads.values():
        target = {"force": f"v_{load.target}", "torque": f"omega_{load.target}",
                  "axial": f"d|{load.target}|/dt", "driver": "qdot"}[load.kind]
        terms.append(f"{load.name} * {target}")
    return ["  " + " + ".join(terms) + " = 0" if terms else "  (no loads)"]


def _turns(mech, carrier: str) -> bool:
    """Whether a guide's carrier turns: the frame does not, nor a slider block that runs on a
    guide that does not turn (a Scotch yoke's block translates: no Coriolis term)."""
    if carrier == FRAME:
        return False
    body = mech.bodies[carrier]
    return body.kind != "block" or _turns(mech, body.guide.carrier)
