"""Reading of the answers of a vibration problem (a file that declares ``coordinates:``).

    quantities:
      w1:  {natural_frequency: 1, unit: Hz}   # also damped_frequency, damping_ratio of a mode
      Om:  {forcing_frequency: true}
      u21: {mode_shape: [2, x1]}              # mode 2's component on coordinate x1
      m12: {mass_matrix: [x1, x2]}            # also stiffness_ and damping_matrix
      x0:  {equilibrium: x1}
      Fk:  {spring_force: k1}
      F:   {force_amplitude: [k1, c1]}        # transmitted by springs and dampers
      xf:  {free_response: x1, time: 0.5}
      X1:  {amplitude: x1}                    # also phase, transmissibility; {x: P}

:class:`VibrationQuantities` (a mixin of the Parser) reads the kind, its mode, coordinate,
point, spring or damper and its unit; the vibration chapters' kinds are in ``oscillation``.

Errors, each an :class:`~linkcli.errors.InputError` at the quantity's YAML path and line
(exit 2): not exactly one kind; a vibration answer in a file without coordinates; a mode
out of 1 to the number of coordinates; an undefined coordinate, point, spring or damper;
'time' other than on a free response or negative; a unit not of the answer's dimension.
"""
from __future__ import annotations

import dataclasses

from linkcli.model.mechanism import VIBRATION, Quantity
from linkcli.input.oscillation import OSCILLATION


class VibrationQuantities:
    """The answers of a vibration problem (a mixin of the Parser)."""

    def one_kind(self, value, path, kinds):
        """(kind, its path, its argument) of a quantity written with exactly one of the
        keys ``kinds``."""
        found = [k for k in kinds if k in value]
        if len(found) != 1:
            raise self.error(path, "give exactly one of " + ", ".join(found))
        return found[0], path + (found[0],), value[found[0]]

    def vibration_quantity(self, name, value, path, pool) -> Quantity:
        """A quantity of the vibration analysis (see docs/vibrations.md)."""
        value = self.mapping(value, path, set(VIBRATION) - set(OSCILLATION) | {"unit", "time"})
        kind, where, arg = self.one_kind(value, path, VIBRATION)
        coords = self.vibration.get("coordinates", [])
        unit = self.answer_unit(value, path)        # its dimension: answer_units
        if "time" in value and kind != "free_response":
            raise self.error(path + ("time",), "'time' is for free_response")
        if not coords:
            raise self.error(path, f"{kind} needs a vibration problem: declare its "
                             "coordinates under 'coordinates:'")
        quantity = self.vibration_kind(name, kind, value, path, where, arg, pool)
        return dataclasses.replace(quantity, unit=unit, line=self.doc.line(path))

    def vibration_kind(self, name, kind, value, path, where, arg, pool) -> Quantity:
        """The quantity of ``kind`` (a key of :data:`VIBRATION`) with its argument ``arg``."""
        coords = self.vibration["coordinates"]
        if kind in ("natural_frequency", "damped_frequency", "damping_ratio"):
            return Quantity(name, kind, str(self.mode(arg, where, len(coords))))
        if kind == "forcing_frequency":
            if arg is not True:
                raise self.error(where, "write 'forcing_frequency: true'")
            return Quantity(name, kind)
        if kind == "mode_shape":
            if not isinstance(arg, list) or len(arg) != 2:
                raise self.error(where, "a mode shape component is [mode, coordinate]")
            mode = self.mode(arg[0], where + (0,), len(coords))
            return Quantity(name, kind, str(mode), self.name(arg[1], where + (1,), coords,
                                                             "coordinate"))
        if kind.endswith("_matrix"):
            a, b = self.pair(arg, where, coords, "coordinate") if not (
                isinstance(arg, list) and len(arg) == 2 and arg[0] == arg[1]) else \
                (self.name(arg[0], where + (0,), coords, "coordinate"),) * 2
            return Quantity(name, kind, a, b)
        if kind == "equilibrium":
            return Quantity(name, kind, self.name(arg, where, coords, "coordinate"))
        if kind == "spring_force":
            return Quantity(name, kind, self.name(arg, where, self.vibration["springs"],
                                                  "spring"))
        if kind == "force_amplitude":
            items = arg if isinstance(arg, list) else [arg]
            pool_e = self.vibration["springs"] | self.vibration["dampers"]
            names = tuple(self.name(e, where + (i,), pool_e, "spring or damper")
                          for i, e in enumerate(items))
            return Quantity(name, kind, elements=names)
        if kind == "free_response":
            time = self.number(value.get("time", 0), path + ("time",), "time", self.file_units)
            if time < 0:
                raise self.error(path + ("time",), f"time must be >= 0, got {time!r}")
            return Quantity(name, kind, self.name(arg, where, coords, "coordinate"), time=time)
        # amplitude, phase, transmissibility: of a coordinate, or {x: P} / {y: P}
        if isinstance(arg, dict):
            spec = self.mapping(arg, where, {"x", "y"})
            if len(spec) != 1:
                raise self.error(where, "give one axis: {x: P} or {y: P}")
            axis = next(iter(spec))
            return Quantity(name, kind, self.name(spec[axis], where + (axis,), pool),
                            component=axis)
        return Quantity(name, kind, self.name(arg, where, coords, "coordinate"))

    def mode(self, value, path, count) -> int:
        if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= count:
            raise self.error(path, f"a mode is numbered 1-{count} (from the lowest frequency), "
                             f"got {value!r}")
        return value
