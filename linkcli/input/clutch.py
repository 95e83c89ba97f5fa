"""Reading of a clutch problem: two shafts (or a shaft and the frame) and the clutch between
them, and the answers of its transient (``runs.clutch``).

    units: {angular_rate: rpm, torque: Nm, inertia: kg m^2, length: mm, force: N, time: s}
    shafts:
      motor: {inertia: 32, speed: 1250, torque: 0}        # J, the speed at t = 0, a torque
      rotor: {inertia: 42.12, speed: 0, resisting: 10}    # a torque against its turning
      # drive: {inertia: 2, speed: 0, motor: {stall: 60, no_load: 1500}}   # M = stall (1 - w/no_load)
    clutch:
      between: [motor, rotor]          # the driving shaft first; [drum, frame]: a brake
      torque: 37.9                     # the friction torque while they slip, or
      # plate: {mu: 0.35, force: 570, outer: 110, inner: 80, pairs: 2, wear: uniform}
    quantities:
      ts: {clutch: slip_time}
      wc: {clutch: common_speed}
      E:  {clutch: energy, unit: kJ}
      C:  {clutch: torque}                              # the friction torque
      Ct: {clutch: transmitted}                         # the torque passed once locked
      w:  {clutch: speed, shaft: rotor, time: 100}      # at t = 100 s
      a:  {clutch: acceleration, shaft: rotor, time: 100}
      t1: {clutch: time, shaft: rotor, speed: 500}      # when the shaft first reaches 500 rpm
    report:
      motion: [ts, wc, E]

A file with ``shafts:`` is a clutch problem: it has no frame, points, links or driver.  Values
are in the file's units (``units.angular_rate``, ``torque``, ``inertia``, ``time``, ``length``
and ``force`` for a plate).  Torques are counter-clockwise positive along the shafts' axis.

Errors, each an :class:`~linkcli.errors.InputError` at its YAML path and line (exit 2): a
shaft without inertia or with a negative one, a negative resisting torque, a motor's
no-load speed that is not positive; a clutch between a shaft and itself or an undefined
one, both or neither of ``torque`` and ``plate``, a negative torque, a plate whose inner
radius is not below the outer one; an unknown clutch answer, a shaft answer without its
shaft, time or speed; a unit of another dimension.
"""
from __future__ import annotations

import dataclasses

from linkcli.model.clutch import ANSWERS, Clutch, ClutchProblem, Plate, Shaft
from linkcli.model.mechanism import Mechanism, Quantity, Quiz
from linkcli.model.units import parse_unit
from linkcli.input.reader import InputErrors
#: the answers of one shaft, and the key each needs besides ``shaft``
OF_SHAFT = {"speed": "time", "acceleration": "time", "time": "speed"}
FRAME = "frame"
#: the sections of a mechanism a clutch problem has not
LINKAGE = ("frame", "points", "links", "actuators", "sliders", "driver", "coordinates", "loads",
           "dynamics", "springs", "dampers", "excitation", "initial", "equilibrium", "rolling",
           "cords", "find", "motion")


def is_clutch(data) -> bool:
    """Whether a document is a clutch problem (it has ``shafts:``)."""
    return isinstance(data, dict) and "shafts" in data


class ClutchSection:
    """``shafts``, ``clutch`` and the clutch's answers (a mixin of the Parser)."""

    def clutch_file(self, data, units) -> Mechanism:
        """The whole clutch problem: shafts, clutch, quantities, report and keys."""
        for key in data:
            if key in LINKAGE:
                self.error((key,), f"a clutch problem (shafts:) has no '{key}'",
                           hint="a file is either a mechanism or two shafts and a clutch")
        if "clutch" not in data:
            self.error((), "a file with 'shafts' needs its 'clutch'",
                       hint="clutch: {between: [motor, rotor], torque: 40}")
        self.file_units = units
        problem = self.block(self.clutch_problem, data, units)
        quantities = self.block(self.quantities, data, set(), {}, None) or {}
        report = self.block(self.report, data, quantities, {}, set()) or {}
        keys = self.block(self.keys, data, quantities, {}, set(), report) or ()
        self.large_enough(units)
        if self.errors:
            raise InputErrors(self.errors)
        mech = Mechanism(title=str(data.get("title", self.doc.name)), file=self.doc.name,
                         k=self.k, units=units, fixed={}, moving={}, bodies={}, actuators={},
                         driver=None, loads={}, quantities=quantities, report=report, keys=keys,
                         as_drawn=self.k_override is None or self.k_override == data.get("k"),
                         statement=self.block(self.statement, data) or "",
                         quiz=self.block(self.quiz, data, report) or Quiz(),
                         params=dict(self.names), clutch=problem)
        mech.param_kinds = self.param_kinds()
        self.expression_dimensions(mech)
        self.answer_units(mech)
        if self.errors:
            raise InputErrors(self.errors)
        return mech

    def clutch_problem(self, data, units) -> ClutchProblem:
        shafts = {}
        spec = self.mapping(self.get(data, (), "shafts"), ("shafts",))
        for name, value in spec.items():
            shafts[name] = self.block(self.shaft, name, value, units)
        shafts = {n: s for n, s in shafts.items() if s is not None}
        clutch = self.block(self.clutch, data, units, set(spec))
        return ClutchProblem(shafts, clutch)

    def shaft(self, name, value, units) -> Shaft:
        path = ("shafts", name)
        self.name(name, path, what="shaft")
        value = self.mapping(value, path, {"inertia", "speed", "torque", "resisting", "motor"},
                             ("inertia",))
        inertia = self.number(value["inertia"], path + ("inertia",), "inertia", units)
        if not inertia > 0:
            raise self.error(path + ("inertia",), f"a shaft's inertia is positive, got "
                             f"{inertia:g}")
        speed = self.number(value.get("speed", 0), path + ("speed",), "angular_rate", units)
        torque = self.number(value.get("torque", 0), path + ("torque",), "torque", units)
        resisting = self.number(value.get("resisting", 0), path + ("resisting",), "torque",
                                units)
        if resisting < 0:
            raise self.error(path + ("resisting",), f"a resisting torque is >= 0 (it acts "
                             f"against the turning), got {resisting:g}",
                             hint="give a signed 'torque' for one that keeps its sense")
        stall = no_load = None
        if "motor" in value:
            where = path + ("motor",)
            motor = self.mapping(value["motor"], where, {"stall", "no_load"},
                                 ("stall", "no_load"))
            stall = self.number(motor["stall"], where + ("stall",), "torque", units)
            no_load = self.number(motor["no_load"], where + ("no_load",), "angular_rate",
                                  units)
            if not no_load > 0:
                raise self.error(where + ("no_load",), "a motor's no-load speed is positive",
                                 hint="M = stall (1 - w / no_load)")
        return Shaft(name, inertia, speed, torque, resisting, stall, no_load)

    def clutch(self, data, units, names) -> Clutch:
        path = ("clutch",)
        spec = self.mapping(self.get(data, (), "clutch"), path, {"between", "torque", "plate"},
                            ("between",))
        driving, driven = self.pair(spec["between"], path + ("between",), names | {FRAME},
                                    "shaft")
        if driving == FRAME or driving == driven:
            raise self.error(path + ("between",), "a clutch is between two shafts, the driving "
                             "one first, or a shaft and the frame (a brake)",
                             hint="between: [motor, rotor] or between: [drum, frame]")
        if ("torque" in spec) == ("plate" in spec):
            raise self.error(path, "give the clutch's friction torque 'torque' or its 'plate'",
                             hint="torque: 37.9, or plate: {mu, force, outer, inner, pairs}")
        plate = None
        if "plate" in spec:
            plate = self.plate(spec["plate"], path + ("plate",), units)
            torque = plate.torque
        else:
            torque = self.number(spec["torque"], path + ("torque",), "torque", units)
            if torque < 0:
                raise self.error(path + ("torque",), f"a friction torque is >= 0, got "
                                 f"{torque:g}")
        return Clutch(driving, None if driven == FRAME else driven, torque, plate)

    def plate(self, value, path, units) -> Plate:
        value = self.mapping(value, path, {"mu", "force", "outer", "inner", "pairs", "wear"},
                             ("mu", "force", "outer", "inner"))
        mu = self.number(value["mu"], path + ("mu",))
        force = self.number(value["force"], path + ("force",), "force", units)
        outer = self.number(value["outer"], path + ("outer",), "length", units)
        inner = self.number(value["inner"], path + ("inner",), "length", units)
        pairs = value.get("pairs", 1)
        wear = value.get("wear", "uniform")
        if mu < 0 or force < 0:
            raise self.error(path, "a plate's mu and axial force are >= 0")
        if not 0 <= inner < outer:
            raise self.error(path + ("inner",), f"the inner radius is below the outer one, got "
                             f"{inner:g} and {outer:g} m")
        if isinstance(pairs, bool) or not isinstance(pairs, int) or pairs < 1:
            raise self.error(path + ("pairs",), f"pairs of surfaces is a whole number >= 1, "
                             f"got {pairs!r}")
        if wear not in ("uniform", "pressure"):
            raise self.error(path + ("wear",), f"wear is 'uniform' (uniform wear) or "
                             f"'pressure' (uniform pressure), got {wear!r}")
        return Plate(mu, force, outer, inner, pairs, wear)

    def clutch_quantity(self, name, value, path) -> Quantity:
        value = self.mapping(value, path, {"clutch", "shaft", "time", "speed", "unit"})
        answer = value["clutch"]
        if answer not in ANSWERS:
            raise self.error(path + ("clutch",), f"unknown clutch answer {answer!r}",
                             hint="one of " + ", ".join(ANSWERS))
        needs = OF_SHAFT.get(answer)
        for key in ("shaft", "time", "speed"):
            if key in value and (needs is None or key not in ("shaft", needs)):
                raise self.error(path + (key,), f"'{key}' is not a key of the clutch's "
                                 f"{answer.replace('_', ' ')}")
        unit = value.get("unit")
        if unit is not None:
            parsed = parse_unit(unit, ANSWERS[answer])
            if parsed is None or parsed[0] != ANSWERS[answer]:
                raise self.error(path + ("unit",), f"unit {unit!r} is not one of a clutch's "
                                 f"{answer.replace('_', ' ')}")
        quantity = Quantity(name, "clutch", answer, unit=unit, line=self.doc.line(path))
        if needs is None:
            return quantity
        shafts = self.doc.data.get("shafts") if isinstance(self.doc.data, dict) else None
        names = set(shafts) if isinstance(shafts, dict) else set()
        for key in ("shaft", needs):
            if key not in value:
                raise self.error(path, f"the clutch's {answer} needs '{key}'",
                                 hint="e.g. {clutch: speed, shaft: rotor, time: 10}")
        shaft = self.name(value["shaft"], path + ("shaft",), names, "shaft")
        units = self.file_units
        kind = "time" if needs == "time" else "angular_rate"
        at = self.number(value[needs], path + (needs,), kind, units)
        if needs == "time" and at < 0:
            raise self.error(path + ("time",), f"a time from the start is >= 0, got {at:g}")
        return dataclasses.replace(quantity, b=shaft, time=at)
