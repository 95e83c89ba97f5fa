"""What vibration chapters print (a mixin of the Parser; docs/vibrations.md, "What books ask"):

    quantities:
      T1: {natural_period: 1}                # 2 pi / omega_1 (s)
      Td: {damped_period: 1}                 # 2 pi / omega_d1
      r1: {frequency_ratio: 1}               # Omega / omega_1
      l2: {eigenvalue: 2}                    # omega_2^2
      c1: {characteristic: 1}                # coefficient of omega^2 in det(K - omega^2 M)
      c1m: {characteristic: 1, monic: true}  # ... divided by that of omega^2n
      H12: {receptance: [x1, x2], part: real}
      Xr: {amplitude: x1, part: imaginary}   # also force_amplitude
      wp: {peak_frequency: x1}               # of |X(Omega)|, {x: P} for a point; peak: 2
      Xp: {peak_amplitude: x1}
      Tb: {beat_period: [1, 2]}              # 2 pi / |omega_2 - omega_1|
      xm: {largest: x1}                      # of a free vibration: {x: P}, {spring: k}

``unit`` gives a period, a frequency or another answer its own unit (of its dimension).
"""
from __future__ import annotations

from linkcli.model.mechanism import Quantity
from linkcli.model.units import fitting, parse_unit

#: the new quantities' kinds, each the YAML key that asks for it
OSCILLATION = ("natural_period", "damped_period", "frequency_ratio", "eigenvalue",
               "characteristic", "receptance", "peak_frequency", "peak_amplitude",
               "beat_period", "largest")
#: of a mode, numbered from the lowest frequency
OF_MODE = ("natural_period", "damped_period", "frequency_ratio", "eigenvalue")
#: the complex answers whose real and imaginary parts may be asked (``part``)
COMPLEX = ("amplitude", "force_amplitude", "receptance")
PARTS = ("real", "imaginary")


class OscillationSection:
    """The quantities of :data:`OSCILLATION`, and ``part`` of the complex ones."""

    def oscillation_quantity(self, name, value, path, pool) -> Quantity:
        value = self.mapping(value, path, set(OSCILLATION) | {"unit", "part", "monic", "peak"})
        kind, where, arg = self.one_kind(value, path, OSCILLATION)
        coords = sorted(self.vibration.get("coordinates", []))
        if not coords:
            raise self.error(path, f"{kind} needs a vibration problem: declare its "
                             "coordinates under 'coordinates:'")
        for option, owner in (("part", "receptance"), ("monic", "characteristic"),
                              ("peak", "peak_")):
            if option in value and not kind.startswith(owner):
                raise self.error(path + (option,), f"'{option}' is not an option of {kind}")
        line = self.doc.line(path)
        unit = self.answer_unit(value, path)
        base = dict(name=name, kind=kind, unit=unit, line=line)
        if kind in OF_MODE:
            return Quantity(a=str(self.mode(arg, where, len(coords))), **base)
        if kind == "beat_period":
            if not isinstance(arg, list) or len(arg) != 2:
                raise self.error(where, "a beat period is of two modes: [1, 2]")
            first, second = (self.mode(m, where + (i,), len(coords)) for i, m in enumerate(arg))
            if first == second:
                raise self.error(where, "the two modes of a beat period must differ")
            return Quantity(a=str(first), b=str(second), **base)
        if kind == "characteristic":
            if isinstance(arg, bool) or not isinstance(arg, int) or \
                    not 0 <= arg <= len(coords):
                raise self.error(where, "the characteristic polynomial's coefficient is of "
                                 f"omega^(2i), i = 0-{len(coords)}, got {arg!r}")
            monic = value.get("monic", False)
            if not isinstance(monic, bool):
                raise self.error(path + ("monic",), f"monic is true or false, got {monic!r}")
            return Quantity(a=str(arg), form="monic" if monic else None, **base)
        if kind == "receptance":
            if not isinstance(arg, list) or len(arg) != 2:
                raise self.error(where, "a receptance is [response coordinate, forced "
                                 "coordinate]")
            a, b = (self.name(c, where + (i,), coords, "coordinate") for i, c in enumerate(arg))
            return Quantity(a=a, b=b, form=self.part(value, path), **base)
        if kind.startswith("peak_"):
            peak = value.get("peak", 1)
            if isinstance(peak, bool) or not isinstance(peak, int) or peak < 1:
                raise self.error(path + ("peak", ), f"peak is a number 1, 2, ... (from the "
                                 f"lowest frequency), got {peak!r}")
            return self.response_of(arg, where, coords, pool, Quantity(b=str(peak), **base))
        # largest: a coordinate, {x: P}, {y: P} or {spring: NAME}
        if isinstance(arg, dict) and "spring" in arg:
            spec = self.mapping(arg, where, {"spring"})
            return Quantity(a=self.name(spec["spring"], where + ("spring",),
                                        self.vibration["springs"], "spring"), of="spring",
                            **base)
        return self.response_of(arg, where, coords, pool, Quantity(**base))

    def response_of(self, arg, where, coords, pool, quantity) -> Quantity:
        """A response of a coordinate (its name) or of a point's x or y ({x: P})."""
        import dataclasses
        if isinstance(arg, dict):
            spec = self.mapping(arg, where, {"x", "y"})
            if len(spec) != 1:
                raise self.error(where, "give one axis: {x: P} or {y: P}")
            axis = next(iter(spec))
            return dataclasses.replace(quantity, a=self.name(spec[axis], where + (axis,), pool),
                                       component=axis, of="point")
        return dataclasses.replace(quantity, a=self.name(arg, where, coords, "coordinate"),
                                   of="coordinate")

    def with_part(self, name, value, path, pool) -> Quantity:
        """A quantity of the vibration analysis (input.vibration), with the ``part`` of a
        complex one."""
        import dataclasses
        if not isinstance(value, dict) or "part" not in value:
            return self.vibration_quantity(name, value, path, pool)
        quantity = self.vibration_quantity(name, {k: v for k, v in value.items()
                                                  if k != "part"}, path, pool)
        if quantity.kind not in COMPLEX:
            raise self.error(path + ("part",), f"'part' is of a complex answer ("
                             f"{', '.join(COMPLEX)}), not of {quantity.kind}")
        return dataclasses.replace(quantity, form=self.part(value, path))

    def answer_units(self, mech) -> None:
        """The ``unit`` of each quantity of a vibration problem has its dimension (angles
        aside: model.units.show); else a located error naming the units that have it."""
        from linkcli.input.derived import words
        from linkcli.model.dimensions import dimension
        from linkcli.model.mechanism import MACHINE, VIBRATION
        for name, q in mech.quantities.items():
            if q.kind in VIBRATION + MACHINE and q.unit is not None:
                try:
                    dim = dimension(mech, name)
                except (KeyError, AttributeError, StopIteration):
                    continue            # a section it reads failed: reported already
                given = parse_unit(q.unit, dim)[0]
                if not given.agrees(dim):
                    self.error(("quantities", name, "unit"), f"{name} is {words(dim)} and "
                               f"the unit '{q.unit}' is {words(given, q.unit)}",
                               hint="give one of " + ", ".join(fitting(mech.units, dim)))

    def part(self, value, path):
        """``part``: real or imaginary (None: the magnitude)."""
        part = value.get("part")
        if part is not None and part not in PARTS:
            raise self.error(path + ("part",), f"part is real or imaginary, got {part!r}",
                             hint="without 'part' the answer is the magnitude")
        return part

    def answer_unit(self, value, path):
        """``unit``: a unit name parse_unit reads (its dimension is checked once the
        mechanism is built: input.derived)."""
        unit = value.get("unit")
        if unit is not None and (not isinstance(unit, str) or parse_unit(unit) is None):
            raise self.error(path + ("unit",), f"unknown unit {unit!r}",
                             hint="a unit of the tables (s, ms, Hz, rpm, mm ...) or a product "
                             "of them")
        return unit
