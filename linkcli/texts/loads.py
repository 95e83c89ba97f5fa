"""The data lines of the motion and the loads: the driver (its value, rate and
acceleration, or a vibration problem's coordinates with the figure's position) and each load.

A load is stated with its point or body and its direction: a force by value and direction
or by its x and y components, whichever is rounder; a torque counter-clockwise positive;
an actuator's axial force positive when it pushes its ends apart; a pressure on a bore or
an area; the generalised force on the driver (a torque, a force, or the actuator's force)
known or unknown.
"""
from __future__ import annotations

import math

from linkcli.texts.amounts import CLOSE, digits


def motion_and_load_lines(w) -> list:
    """The driver's line (or the coordinates'), then a line per load (``w`` a
    :class:`~linkcli.texts.amounts.Writer`)."""
    return _motion(w) + _loads(w)


# --- driver and coordinates -------------------------------------------------------------------
def _what(w, d) -> str:
    key = {"angle": "angle_of", "length": "length_of", "x": "x_of", "y": "y_of"}[d.kind]
    return w.w[key].format(a=d.a, b=d.b)


def _coordinate_value(w, d) -> str:
    return w.angle(d.value) if d.kind == "angle" else w.length(d.value)


def _motion(w) -> list:
    """The driver's line; with several drivers, a line for each by its name."""
    mech = w.mech
    if mech.elements is not None:
        return _coordinates(w)
    if len(mech.coordinates) == 1:
        return [_driver_line(w, mech.driver, "q")]
    return [_driver_line(w, d, d.name) for d in mech.coordinates]


def _driver_line(w, d, name) -> str:
    """'driver: q = angle of O->A = 30 deg, q' = 2 rad/s (counter-clockwise), q'' = ...',
    the driver called ``name``."""
    mech = w.mech
    base = d.base
    rate_unit, rate_f = w.units.display(base, 1)
    acc_unit, acc_f = w.units.display(base, 2)
    text = w.w["driver"].format(q=name, what=_what(w, d), value=_coordinate_value(w, d))
    sense = ""
    if d.rate:
        words = ("ccw", "cw") if d.kind == "angle" else ("longer", "shorter") \
            if d.kind == "length" else (None, None)
        word = words[0] if d.rate > 0 else words[1]
        sense = f" ({w.w[word]})" if word else ""
    text += ", " + w.w["rate"].format(q=name, rate=f"{w.num(d.rate / rate_f)} {rate_unit}") \
        + sense
    if d.accel or mech.report.get("acceleration") or mech.dynamics is not None:
        text += ", " + w.w["accel"].format(q=name,
                                           accel=f"{w.num(d.accel / acc_f)} {acc_unit}")
    return text


def _coordinates(w) -> list:
    mech = w.mech
    names = ", ".join(f"{c.name} = {_what(w, c)}" for c in mech.coordinates)
    values = ", ".join(f"{c.name} = {_coordinate_value(w, c)}" for c in mech.coordinates)
    out = [w.w["coordinates"].format(names=names) + "; " + w.w["figure_is"].format(
        values=values)]
    moving = [f"{p} = {w.point(z)}" for p, z in mech.moving.items()]
    if moving:
        out.append(w.w["figure_points"].format(points=", ".join(moving)))
    return out


# --- loads ------------------------------------------------------------------------------------
def _loads(w) -> list:
    return [_windowed(w, load, _load(w, load)) for load in w.mech.loads.values()]


def _windowed(w, load, line) -> str:
    """A load's line with the driver's window it acts in (machine dynamics)."""
    if load.window is None:
        return line
    lo, hi = (w.angle(x) if w.mech.driver.base == "angle" else w.length(x)
              for x in load.window)
    return w.w["window"].format(line=line, lo=lo, hi=hi)


def _turning(w, load) -> str:
    """A motor's characteristic or a brake's torque, in the file's units."""
    if load.kind == "brake":
        return w.w["brake"].format(name=load.name, on=load.target,
                                   value=w.amount(load.value, "torque"))
    c = load.motor
    names = dict(name=load.name, on=load.target)
    if c.kind == "linear":
        return w.w["motor_linear"].format(stall=w.amount(c.stall, "torque"),
                                          no_load=w.amount(c.no_load, "angular_rate"), **names)
    if c.kind == "table":
        at = " at " if w.lang == "en" else " a "
        points = ", ".join(f"{w.amount(m, 'torque')}{at}{w.amount(n, 'angular_rate')}"
                           for n, m in zip(c.speeds, c.torques))
        return w.w["motor_table"].format(points=points, **names)
    units = w.mech.units.names
    return w.w["motor_expression"].format(text=c.text, units=f"{units['torque']}, w in "
                                          f"{units['angular_rate']}", **names)


def _load(w, load) -> str:
    mech = w.mech
    if load.kind in ("motor", "brake"):
        return _turning(w, load)
    if load.pressure is not None:
        return _pressure(w, load, load.pressure)
    if load.kind == "force":
        if load.value is None:
            return w.w["unknown_force"].format(name=load.name, at=load.target,
                                               direction=w.direction(load.direction))
        return _force(w, load)
    if load.kind == "torque":
        key = "unknown_torque" if load.value is None else "torque"
        value = None if load.value is None else w.amount(load.value, "torque")
        return w.w[key].format(name=load.name, value=value, on=load.target)
    if load.kind == "axial":
        key = "unknown_axial" if load.value is None else "axial"
        value = None if load.value is None else w.amount(load.value, "force")
        return w.w[key].format(name=load.name, value=value, on=load.target)
    d = next((c for c in mech.coordinates if c.name == load.target), mech.driver)
    q = "q" if len(mech.coordinates) == 1 else d.name     # several drivers: the one it is on
    what = w.w["q_torque"] if d.kind == "angle" else w.w["q_actuator"] \
        if d.kind == "length" and _actuator_of(mech, d) else w.w["q_force"].format(q=q)
    if load.value is None:
        return w.w["driver_load"].format(name=load.name, what=what, q=q)
    return w.w["driver_load_known"].format(
        name=load.name, what=what, q=q, value=w.amount(load.value, mech.load_unit_kind(load)))


def _actuator_of(mech, d) -> bool:
    return any({a.a, a.b} == {d.a, d.b} for a in mech.actuators.values())


def force_by_components(w, load) -> bool:
    """Whether a known force is stated by its x and y components: when they are rounder
    than its value and direction (a force along x or y never is)."""
    u, value = load.direction, load.value
    f = w.units.factor("force")
    if abs(u - 1) < CLOSE or abs(u - 1j) < CLOSE:
        return False
    angle = math.atan2(u.imag, u.real) % (2 * math.pi)
    polar = digits(value / f) + digits(angle / w.units.factor("angle"))
    return digits(value * u.real / f) + digits(value * u.imag / f) < polar


def _force(w, load) -> str:
    """A known force by value and direction, or by its x and y components when rounder."""
    u, value = load.direction, load.value
    if force_by_components(w, load):
        return w.w["force_xy"].format(name=load.name, at=load.target,
                                      x=w.amount(value * u.real, "force"),
                                      y=w.amount(value * u.imag, "force"))
    return w.w["force"].format(name=load.name, value=w.amount(value, "force"), at=load.target,
                               direction=w.direction(u))


def _pressure(w, load, pressure) -> str:
    p, area, bore = pressure
    size = w.length(bore) if bore is not None else w.amount(area, "area")
    what = w.w["bore"] if bore is not None else w.w["area"]
    direction = w.w["pushes_apart"] if load.kind == "axial" else w.w["along_guide"]
    on = load.target
    return w.w["pressure"].format(name=load.name, p=w.amount(p, "pressure"), what=what,
                                  size=size, on=on, direction=direction)
