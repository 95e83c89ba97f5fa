"""Machine dynamics in the file (a mixin of the Parser; docs/machines.md):

    loads:
      motor: {type: motor, on: crank, stall: 400, no_load: 1500}     # M = stall (1 - w/no_load)
      table: {type: motor, on: crank, speeds: [0, 1500], torques: [400, 0]}
      expr:  {type: motor, on: crank, torque: "400 - 0.25*w"}        # w, q, t in file units
      brake: {type: brake, on: crank, value: 5}                      # against the turning
      punch: {type: force, at: B, x: -3000, over: [0, 120]}           # a window of q
    motion: {until: 20}
    quantities:
      J: {reduced_inertia: q}
      w1: {motion: speed, when: {time: 0.5}}
      ts: {motion: time, when: stop}

A file with a motor or brake load, a ``motion:`` section or one of these quantities is a
machine-dynamics file: every load is known (none is ``unknown``).
"""
from __future__ import annotations

import math

import numpy as np

from linkcli.errors import ExpressionError
from linkcli.input import expressions
from linkcli.model.machine import Characteristic, MotionSpec
from linkcli.input.regime import MOTION_KEYS as REGIME_KEYS
from linkcli.model.mechanism import MACHINE, Quantity
from linkcli.model.regime import KINDS as REGIME_KINDS

#: what ``motion:`` answers, and the events ``when:`` names (or ``stop``)
ANSWERS = ("speed", "acceleration", "turned", "turns", "time")
EVENTS = ("time", "speed", "turned", "turns")
MOTION_KEYS = {"until"} | REGIME_KEYS
MOTOR_KEYS = {"stall", "no_load", "speeds", "torques", "torque"}
#: the names a motor's expression reads besides the params: speed, driver value, time
MOTOR_NAMES = ("w", "q", "t")


def rate_factor(units) -> float:
    """The SI value of one unit of a motor's speed: the file's angular rate (rpm: 2 pi/60)."""
    return units.display("angle", 1)[1]


def is_machine(data) -> bool:
    """Whether the file asks for the motion under given loads (or the reduced torque of
    every load): then every load is known.  J* and dJ*/dq alone may be asked in any file
    with a driver and masses."""
    if not isinstance(data, dict):
        return False
    loads = data.get("loads") if isinstance(data.get("loads"), dict) else {}
    quantities = data.get("quantities") if isinstance(data.get("quantities"), dict) else {}
    return "motion" in data or any(
        isinstance(v, dict) and v.get("type") in ("motor", "brake") for v in loads.values()) \
        or any(isinstance(v, dict) and any(k in v for k in ("motion", "reduced_torque"))
               for v in quantities.values())


class MachineSection:
    """Motors, brakes, windows of loads, ``motion:`` and the machine's quantities."""

    def motion_section(self, data, units) -> MotionSpec | None:
        if "motion" not in data:
            return None
        path = ("motion",)
        spec = self.mapping(data["motion"] or {}, path, MOTION_KEYS)
        until = 60.0
        if "until" in spec:
            until = self.number(spec["until"], path + ("until",), "time", units)
            if not until > 0 or not math.isfinite(until):
                raise self.error(path + ("until",), f"'until' is a positive time, got "
                                 f"{spec['until']!r}")
        regime = self.regime_spec(spec, path, units, self.driver_of_file)
        return MotionSpec(until, {"regime": regime} if regime is not None else {})

    def window(self, value, path, units, driver):
        """``over: [q1, q2]``: the driver's window a load acts in (SI), None without one."""
        if "over" not in value:
            return None
        where = path + ("over",)
        span = value["over"]
        if not isinstance(span, list) or len(span) != 2:
            raise self.error(where, f"'over' is the driver's window [from, to], got {span!r}")
        base = driver.base if driver is not None else "angle"
        lo, hi = (self.number(v, where + (i,), base, units) for i, v in enumerate(span))
        if base != "angle" and not lo < hi:
            raise self.error(where, "the window's 'from' must be below its 'to'")
        return (lo, hi)

    def motor(self, value, path, units, driver) -> Characteristic:
        """A motor's characteristic: linear, tabulated or an expression (file units)."""
        given = [k for k in ("stall", "speeds", "torque") if k in value]
        if len(given) != 1:
            raise self.error(path, "a motor needs one characteristic: stall and no_load, "
                             "speeds and torques, or torque (an expression of w)")
        kind = given[0]
        torque_f = units.factor("torque")
        rate = rate_factor(units)
        if kind == "stall":
            for key in ("speeds", "torques", "torque"):
                if key in value:
                    raise self.error(path + (key,), f"'{key}' is of another characteristic")
            stall = self.number(value["stall"], path + ("stall",), "torque", units)
            no_load = self.number(self.get(value, path, "no_load"), path + ("no_load",)) * rate
            if not no_load > 0:
                raise self.error(path + ("no_load",), "the no-load speed must be positive")
            return Characteristic("linear", stall=stall, no_load=no_load,
                                  text=f"stall {value['stall']}, no_load {value['no_load']}")
        if kind == "speeds":
            where = path + ("speeds",)
            speeds = [self.number(v, where + (i,)) * rate
                      for i, v in enumerate(self.numbers(value["speeds"], where))]
            where_t = path + ("torques",)
            raw = self.numbers(self.get(value, path, "torques"), where_t)
            torques = [self.number(v, where_t + (i,), "torque", units) for i, v in enumerate(raw)]
            if len(speeds) != len(torques) or len(speeds) < 2:
                raise self.error(path, "speeds and torques are two lists of one length (two "
                                 "points at least)")
            if any(b <= a for a, b in zip(speeds, speeds[1:])):
                raise self.error(where, "the speeds of a table must increase")
            return Characteristic("table", speeds=tuple(speeds), torques=tuple(torques),
                                  text="table")
        return self.motor_expression(value["torque"], path + ("torque",), units, driver,
                                     torque_f, rate)

    def numbers(self, value, path) -> list:
        if not isinstance(value, list):
            raise self.error(path, f"expected a list of numbers, got {value!r}")
        return value

    def motor_expression(self, text, path, units, driver, torque_f, rate) -> Characteristic:
        """M(w, q, t): the expression in the file's torque unit, of w (the body's speed in
        units.angular_rate), q (the driver, its unit) and t (s), with the params."""
        try:
            expr = expressions.Expression(text)
        except ExpressionError as exc:
            raise self.error(path, exc.detail, exc.hint) from None
        unknown = [n for n in expr.names if n not in MOTOR_NAMES and n not in self.names]
        if unknown:
            raise self.error(path, f"undefined name '{unknown[0]}' in the motor's torque",
                             hint="it reads w (the speed), q (the driver), t (s) and the params")
        params = {n: v for n, v in self.names.items() if n not in MOTOR_NAMES}
        q_f = units.display(driver.base if driver is not None else "angle", 0)[1]
        time_f = units.factor("time")

        def function(w, q, t):
            names = dict(params, w=np.asarray(w, float) / rate, q=np.asarray(q, float) / q_f,
                         t=np.asarray(t, float) / time_f)
            return np.asarray(expr.value(names), dtype=float) * torque_f

        try:
            function(np.zeros(1), np.zeros(1), np.zeros(1))
        except ExpressionError as exc:
            raise self.error(path, exc.detail, exc.hint) from None
        return Characteristic("expression", function=function, text=str(text))

    def machine_quantity(self, name, value, path) -> Quantity:
        """``reduced_inertia: q`` and the like, or ``{motion: ANSWER, when: EVENT}``."""
        if isinstance(value, dict) and any(k in value for k in REGIME_KINDS):
            return self.regime_quantity(name, value, path)
        value = self.mapping(value, path, set(MACHINE) | {"when", "unit"})
        kind, where, arg = self.one_kind(value, path, MACHINE)
        line = self.doc.line(path)
        unit = self.answer_unit(value, path)
        if kind != "motion":
            if arg != "q":
                raise self.error(where, f"{kind} is reduced to the driver: write {kind}: q")
            if "when" in value:
                raise self.error(path + ("when",), "'when' is for motion answers")
            return Quantity(name, kind, "q", unit=unit, line=line)
        if arg not in ANSWERS:
            raise self.error(where, f"a motion answer is one of {', '.join(ANSWERS)}, got "
                             f"{arg!r}")
        event, at = self.event(self.get(value, path, "when"), path + ("when",))
        if arg == "time" and event == "time":
            raise self.error(path + ("when",), "the time at a time is the time itself")
        return Quantity(name, "motion", arg, event, time=at, unit=unit, line=line)

    def event(self, value, path) -> tuple:
        """(event, its value in SI): ``stop``, or {time | speed | turned | turns: value}."""
        if value == "stop":
            return "stop", 0.0
        units = self.file_units
        if not isinstance(value, dict) or len(value) != 1 or next(iter(value)) not in EVENTS:
            raise self.error(path, f"'when' is stop or one of {{time: t}}, {{speed: w}}, "
                             f"{{turned: d}}, {{turns: n}}, got {value!r}")
        event, raw = next(iter(value.items()))
        base = self.driver_base
        if event == "time":
            at = self.number(raw, path + (event,), "time", units)
            if not at >= 0:
                raise self.error(path + (event,), "a time from the start is >= 0")
        elif event == "speed":
            at = self.number(raw, path + (event,)) * units.display(base, 1)[1]
        elif event == "turned":
            at = self.number(raw, path + (event,), base, units)
        else:
            at = self.number(raw, path + (event,)) * 2 * math.pi
            if base != "angle":
                raise self.error(path, "turns are of an angle driver: use turned")
        return event, float(at)
