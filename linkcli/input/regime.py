"""The periodic regime and the flywheel in a machine file (a mixin of the Parser;
docs/machines.md, "The periodic regime and the flywheel"):

    motion:
      regime: {mean_speed: 300}          # the driver's rate unit; left out where a motor's
                                         # characteristic sets the speed
      flywheel: {fluctuation: 0.02}      # the delta the flywheel keeps (+-1 % is 0.02)
      turns_per_cycle: 2                 # a four-stroke engine (default 1)
      # a turning-moment diagram drawn in a book, as its areas (mm^2) above (+) and below
      # (-) the mean line in order, and the scales of the drawing (per mm):
      # regime: {mean_speed: 600, areas: [52, -124, 92, -140, 85, -72, 107],
      #          scale: {torque: 600, angle: 3}}
    quantities:
      wm: {regime: mean_speed}           # and the other answers of model.regime.REGIME
      If: {flywheel: exact}              # or approximate
      mf: {flywheel: approximate, radius: 0.5}   # its mass at that radius of gyration

The flywheel is the driver's link's own inertia (``dynamics: bodies: LINK: inertia``).
"""
from __future__ import annotations

import math

from linkcli.model.mechanism import Quantity
from linkcli.model.regime import FLYWHEEL, KINDS, REGIME, RegimeSpec

#: the keys of ``motion:`` read here
MOTION_KEYS = {"regime", "flywheel", "turns_per_cycle"}


class RegimeSection:
    """``motion:``'s regime keys and the ``regime:`` / ``flywheel:`` quantities."""

    def regime_spec(self, spec, path, units, driver) -> RegimeSpec | None:
        """The regime asked in ``motion:`` (``spec`` its mapping), None when it asks none."""
        if not any(key in spec for key in MOTION_KEYS):
            return None
        base = driver.base if driver is not None else "angle"
        regime = self.mapping(spec.get("regime") or {}, path + ("regime",),
                              {"mean_speed", "areas", "scale"})
        mean = None
        if "mean_speed" in regime:
            where = path + ("regime", "mean_speed")
            mean = self.number(regime["mean_speed"], where) * units.display(base, 1)[1]
            if not (mean > 0 and math.isfinite(mean)):
                raise self.error(where, f"the mean speed is a positive speed, got "
                                 f"{regime['mean_speed']!r}")
        areas, energy, scale = self.diagram(regime, path + ("regime",), units, mean)
        fluctuation = None
        if "flywheel" in spec:
            where = path + ("flywheel",)
            fly = self.mapping(spec["flywheel"], where, {"fluctuation"}, ("fluctuation",))
            fluctuation = self.number(fly["fluctuation"], where + ("fluctuation",))
            if not (0 < fluctuation < 2):
                raise self.error(where + ("fluctuation",), "the coefficient of fluctuation "
                                 f"(w_max - w_min) / w_mean is a number in (0, 2), got "
                                 f"{fly['fluctuation']!r}", hint="+-1 % of the mean is 0.02")
        turns = 1.0
        if "turns_per_cycle" in spec:
            where = path + ("turns_per_cycle",)
            turns = self.number(spec["turns_per_cycle"], where)
            if turns not in (1, 2, 3, 4) or base != "angle":
                raise self.error(where, "a cycle is 1, 2, 3 or 4 turns of an angle driver, "
                                 f"got {spec['turns_per_cycle']!r}")
        return RegimeSpec(mean, fluctuation, float(turns), areas, energy, scale)

    def diagram(self, regime, path, units, mean) -> tuple:
        """(areas, J per unit area, (torque, angle) of a unit of the drawing's length) of a
        turning-moment diagram given by its areas."""
        if "areas" not in regime and "scale" not in regime:
            return (), 0.0, ()
        areas = regime.get("areas")
        if not isinstance(areas, list) or len(areas) < 2:
            raise self.error(path + ("areas",), "the areas between the turning moment and "
                             "its mean line are a list (two at least), in order, positive "
                             "above the line")
        values = tuple(float(self.number(v, path + ("areas", i))) for i, v in enumerate(areas))
        scale = self.mapping(self.get(regime, path, "scale"), path + ("scale",),
                             {"torque", "angle"}, ("torque", "angle"))
        torque = self.number(scale["torque"], path + ("scale", "torque"), "torque", units)
        angle = self.number(scale["angle"], path + ("scale", "angle"), "angle", units)
        if not (torque > 0 and angle > 0):
            raise self.error(path + ("scale",), "the scales of the drawing are positive: the "
                             "torque and the angle of one unit of length")
        if mean is None:
            raise self.error(path, "a diagram of areas needs the mean speed",
                             hint="add mean_speed")
        total = sum(values)
        if abs(total) > 1e-9 * sum(abs(v) for v in values):
            raise self.error(path + ("areas",), f"the areas add up to {total:g}, not 0: over a "
                             "cycle the turning moment's mean is the mean line",
                             hint="check their signs: above the line positive")
        return values, torque * angle, (torque, angle)

    def regime_quantity(self, name, value, path) -> Quantity:
        """``{regime: ANSWER}`` or ``{flywheel: approximate | exact}``, with ``unit``."""
        value = self.mapping(value, path, set(KINDS) | {"unit", "radius"})
        kind, where, arg = self.one_kind(value, path, KINDS)
        answers = REGIME if kind == "regime" else FLYWHEEL
        if arg not in answers:
            raise self.error(where, f"a {kind} answer is one of {', '.join(answers)}, got "
                             f"{arg!r}")
        radius = None
        if "radius" in value:
            if kind != "flywheel":
                raise self.error(path + ("radius",), "'radius' is a flywheel's (its mass at "
                                 "that radius of gyration)")
            radius = self.number(value["radius"], path + ("radius",), "length", self.file_units)
            if not radius > 0:
                raise self.error(path + ("radius",), "a radius of gyration is positive")
        unit = self.answer_unit(value, path)
        return Quantity(name, kind, arg, unit=unit, line=self.doc.line(path), radius=radius)
