"""The joint reactions as a report: rows, a text table, a dict, and the ``--reactions``
addition to ``solve``'s output.

Pins: the force the pin exerts on the body, in frame axes and along / normal (left) to
the body's own x axis (link: first -> second point; block: the guide direction;
actuator parts: a -> b).  Sliding pairs: the force of the guide on the block
(along = friction T, normal = N) and its moment M; discs: the ground contact force.
"""
from __future__ import annotations

import json

import numpy as np

from linkcli.forces import motion as dyn_mod
from linkcli.forces.joint_forces import contact_normal, solve
from linkcli.model.mechanism import FRAME
from linkcli.forces.pairs import contact_actions, unit
from linkcli.answers.formats import fmt
from linkcli.kinematics.solvers import state
from linkcli.model.units import FORCE, TORQUE

NOTE = ("Pins: force the pin exerts on the body, in frame axes and along/normal to the "
        "body's axis (first -> second point; the guide direction for sliders), M its friction "
        "couple on the body (friction circles). Sliding pairs: force of the guide on the block "
        "(along = friction T, normal = N), M its moment about the slider point; discs: ground "
        "contact force (along the line, normal), M the rolling resistance couple. Cords: "
        "the tension (along the strand); rolling contacts: the force of what the disc rolls "
        "on (along = friction T, normal = N of the slider on the line's parallel).")
COMPONENTS = ("Fx", "Fy", "magnitude", "along", "normal", "moment")


def rows(reactions, index=None) -> list[tuple]:
    """(name, Fx, Fy, |F|, along, normal) per pin and (..., M) per pair, in SI units at
    driver value number ``index`` (default the first)."""
    out = [_pin_row(reactions, key, force, index) for key, force in reactions.pins.items()]
    out += [_pair_row(reactions, name, pf, index) for name, pf in reactions.pairs.items()]
    return out + [_contact_row(reactions, name, index) for name in reactions.contacts]


def _pick(value, index):
    """One driver value's entry of a scalar or an array, as a complex number."""
    arr = np.asarray(value)
    return complex(arr.reshape(-1)[0 if index is None else index]) if arr.ndim else complex(arr)


def _pin_row(reactions, key, force, index) -> tuple:
    """A pin's force on a body; along / normal to the body's axis u: F . u, F . (i u); and
    the friction couple of a friction circle on that body (on the holder, minus the one on
    the turning body)."""
    p, b = key
    f = _pick(force, index)
    along = normal = None
    if b != FRAME:
        u = _pick(unit(dyn_mod.axis_vector(reactions.mech, b, reactions.kin.pos)), index)
        along, normal = dyn_mod.dot(u, f), dyn_mod.dot(1j * u, f)
    what = "slider " if b != FRAME and reactions.mech.bodies[b].kind == "block" else ""
    row = (f"{p} on {what}{b}", f.real, f.imag, abs(f), along, normal)
    if p not in reactions.pin_couples:
        return row
    pin = reactions.mech.dynamics.pins[p]
    couple = _pick(reactions.pin_couples[p], index).real
    return row + (couple if b == pin.other else -couple if b == pin.holder else None,)


def _pair_row(reactions, name, pf, index) -> tuple:
    """A pair's force N n + T u, with along = T, normal = F . (i u) and M (for a disc its
    rolling resistance couple, None without one)."""
    u = _pick(pf.u, index)
    n_val, t_val = _pick(pf.normal, index).real, _pick(pf.friction, index).real
    force = n_val * _pick(pf.n, index) + t_val * u
    label = {"slider": f"slider {name} (guide on {pf.carrier})",
             "actuator": f"actuator {name} (rod on cylinder)",
             "disc": f"disc {name} (ground contact)"}[pf.kind]
    moment = _pick(pf.moment, index).real if pf.kind != "disc" else \
        _pick(reactions.resistances[name], index).real if name in reactions.resistances else None
    return (label, force.real, force.imag, abs(force), t_val, dyn_mod.dot(1j * u, force), moment)


def _contact_row(reactions, name, index) -> tuple:
    """A cord's pull on its pulley (along = the tension), or the force of what a disc rolls
    on (along = friction T along the line or the track's tangent, normal = N where a slider
    holds the centre on the line, else None)."""
    mech = reactions.mech
    r = mech.rolling[name]
    (_, u, _), *_ = contact_actions(mech, r, reactions.kin.pos)
    u = _pick(u, index)
    t_val = _pick(reactions.contacts[name], index).real
    if r.kind in ("cord", "belt"):
        force = t_val * u
        return (f"cord {name} (tension, on {r.disc})", force.real, force.imag, abs(force),
                t_val, None, None)
    normal = contact_normal(reactions, name)
    n_val = None if normal is None else _pick(normal, index).real
    n = -r.side * 1j * u if r.kind == "line" else -1j * u
    force = t_val * u + (n_val or 0.0) * n
    on = "ground" if r.kind == "circle" or r.kind == "line" and r.carrier == FRAME else \
        r.other if r.kind == "disc" else r.carrier
    return (f"disc {r.disc} on {on} ({name})", force.real, force.imag, abs(force), t_val,
            n_val, None)


def _entries(reactions) -> list[tuple[str, dict]]:
    """(name, components) at the first driver value in the file's force and torque units;
    pairs have a moment (None for discs), pins none."""
    names = reactions.mech.units.names
    ff, tf = FORCE[names["force"]], TORQUE[names["torque"]]
    out = []
    for row in rows(reactions):
        values = [None if v is None else v / ff for v in row[1:6]]
        if len(row) > 6:
            values.append(None if row[6] is None else row[6] / tf)
        out.append((row[0], dict(zip(COMPONENTS, values))))
    return out


def render(reactions, decimals: int = 1) -> str:
    """A text table of the joint reactions at the first driver value."""
    from tabulate import tabulate
    names = reactions.mech.units.names
    force_unit, torque_unit = names["force"], names["torque"]
    body = [[name] + ["" if entry.get(k) is None else fmt(entry[k], decimals)
                      for k in COMPONENTS] for name, entry in _entries(reactions)]
    header = ["force on", f"Fx [{force_unit}]", f"Fy [{force_unit}]",
              f"|F| [{force_unit}]", "along", "normal", f"M [{torque_unit}]"]
    table = tabulate(body, headers=header, disable_numparse=True, stralign="right")
    return "Joint reactions\n" + table + "\n" + NOTE


def as_dict(reactions) -> dict:
    """Reactions at the first driver value in the file's force and torque units."""
    names = reactions.mech.units.names
    return {"force_unit": names["force"], "torque_unit": names["torque"],
            "joints": dict(_entries(reactions))}


def append_report(text: str, mech, form: str, decimals: int, method="closed", tol=None) -> str:
    """``text`` (a rendered report) with the joint reactions at the file's position added."""
    kin, _ = state(mech, method=method, tol=tol)
    reactions = solve(mech, kin)
    if form == "json":
        data = json.loads(text)
        data["reactions"] = as_dict(reactions)
        data["warnings"] = [c.detail for c in reactions.cautions]
        return json.dumps(data, indent=2, allow_nan=True)
    if form == "csv":
        return "\n".join([text] + _csv_lines(as_dict(reactions)))
    notes = "".join(f"\nwarning: {c.detail}" for c in reactions.cautions)
    return text + "\n\n" + render(reactions, decimals) + notes


def _csv_lines(data) -> list[str]:
    """``joint component,value,unit`` lines of ``as_dict``'s data (None left out)."""
    lines = []
    for joint, entry in data["joints"].items():
        for part, value in entry.items():
            if value is not None:
                unit_name = data["torque_unit"] if part == "moment" else data["force_unit"]
                lines.append(f"{joint} {part},{float(value)!r},{unit_name}")
    return lines
