"""The data lines of a vibration problem's elements: the springs (linear, along a
direction or torsional, with their free length, preload or static preload), the dampers,
the excitation (its frequency, harmonic forces and torques, imposed motions, a road
profile), the initial conditions and a figure that is a static equilibrium.
"""
from __future__ import annotations

from linkcli.model.mechanism import FRAME


def element_lines(w) -> list:
    """The springs, dampers, excitation and initial conditions, a line each (``w`` a
    :class:`~linkcli.texts.amounts.Writer`; none without elements)."""
    el = w.mech.elements
    if el is None:
        return []
    out = []
    for s in el.springs.values():
        out.append(w.w["spring"].format(name=s.name, between=_between(w, s.measure),
                                        k=_stiffness(w, s), free=_free(w, s)))
    for d in el.dampers.values():
        kind = "torsional_damping" if d.measure.kind == "angle" else "damping"
        out.append(w.w["damper"].format(name=d.name, between=_between(w, d.measure),
                                        c=w.amount(d.coefficient, kind)))
    if el.frequency is not None and "road" not in el.supports:
        out.append(w.w["frequency"].format(value=w.amount(el.frequency, "frequency")))
    for h in el.forces.values():
        if h.kind == "torque":
            out.append(w.w["harmonic_torque"].format(name=h.name,
                                                     value=w.amount(h.amplitude, "torque"),
                                                     phase=w.angle(h.phase), on=h.target))
        else:
            out.append(w.w["harmonic_force"].format(
                name=h.name, value=w.amount(h.amplitude, "force"), phase=w.angle(h.phase),
                at=h.target, direction=w.direction(h.direction)))
    for s in el.supports.values():
        c = w.mech.coordinates[s.coordinate]
        amplitude = w.angle(s.amplitude) if c.kind == "angle" else w.length(s.amplitude)
        if s.road is not None:
            wavelength, speed = s.road
            out.append(w.w["road"].format(value=amplitude, wavelength=w.length(wavelength),
                                          speed=w.amount(speed, "speed")) +
                       f" ({c.name})")
        else:
            out.append(w.w["support"].format(coordinate=c.name, value=amplitude,
                                             phase=w.angle(s.phase)))
    if el.initial:
        values = []
        for j, (x0, v0) in el.initial.items():
            c = w.mech.coordinates[j]
            rate_unit, rate_f = w.units.display(c.base, 1)
            values.append(f"{c.name} = {_coordinate_offset(w, c, x0)}, {c.name}' = "
                          f"{w.num(v0 / rate_f)} {rate_unit}")
        start, springs = el.initial_from
        key = {"equilibrium": "initial", "figure": "initial_figure"}.get(start,
                                                                          "initial_unstretched")
        verb = {"en": ("is", "are"), "it": ("è", "sono")}[w.lang][len(springs or ()) > 1]
        out.append(w.w[key].format(values=", ".join(values),
                                   springs=f"{', '.join(springs or ())} {verb}"))
    if el.initial_mode is not None:
        k, j, amplitude = el.initial_mode
        c = w.mech.coordinates[j]
        out.append(w.w["initial_mode"].format(mode=k + 1, coordinate=c.name,
                                              value=_coordinate_offset(w, c, amplitude)))
    if el.equilibrium == "figure":
        out.append(w.w["equilibrium_figure"])
    return out


def _coordinate_offset(w, c, value) -> str:
    return w.angle(value) if c.kind == "angle" else w.length(value)


def _between(w, m) -> str:
    if m.kind == "angle":
        names = [w.w["frame_body"] if b == FRAME else b for b in (m.a, m.b)]
        return w.w["between_bodies"].format(a=names[0], b=names[1])
    if m.kind == "along":
        return w.w["between_along"].format(a=m.a, b=m.b, direction=w.direction(m.direction))
    return w.w["between_points"].format(a=m.a, b=m.b)


def _stiffness(w, s) -> str:
    return w.amount(s.stiffness, "torsional_stiffness" if s.measure.kind == "angle"
                    else "stiffness")


def _free(w, s) -> str:
    torsional = s.measure.kind == "angle"
    if s.mode == "free":
        if torsional:
            return w.w["free_angle"].format(value=w.angle(s.value))
        return w.w["free_length"].format(value=w.length(s.value))
    if s.mode == "preload":
        return w.w["preload"].format(value=w.amount(s.value, "torque" if torsional
                                                     else "force"))
    if s.mode == "static":
        return w.w["static"]
    return w.w["unstretched"]
