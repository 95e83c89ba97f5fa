"""Parsing of what the answer sheet asks: quantities, the report and the answer keys."""
from __future__ import annotations

import math

from linkcli.model.mechanism import VIBRATION, AnswerKey, KeyEntry, Quantity, split_rate
from linkcli.model.units import ANGLE, FORCE, FREQUENCY, LENGTH, TORQUE

SECTIONS = ("position", "velocity", "acceleration", "statics", "vibration", "points")


class AnswersSection:
    """``quantities``, ``report`` and ``keys`` (a mixin of the Parser)."""

    def quantities(self, data, pool, loads, driver) -> dict:
        spec = self.mapping(self.get(data, (), "quantities", required=False, default={}) or {},
                            ("quantities",))
        quantities = {"q": Quantity("q", "q")}
        for p in pool:
            quantities["x" + p] = Quantity("x" + p, "x", p)
            quantities["y" + p] = Quantity("y" + p, "y", p)
        for name, load in loads.items():
            quantities[name] = Quantity(name, "load", name)
        self.failed = set()
        for name, value in spec.items():
            q = self.block(self.quantity, name, value, pool, loads, driver)
            if q is not None:
                quantities[name] = q
            else:
                self.failed.add(name)
        return quantities

    def quantity(self, name, value, pool, loads, driver=None) -> Quantity:
        path = ("quantities", name)
        self.name(name, path, what="quantity")
        if name.endswith("dot"):
            raise self.error(path, "quantity names must not end in 'dot'",
                             hint="rates are named automatically: phi1 -> phi1dot, phi1ddot")
        if isinstance(value, dict) and any(k in value for k in VIBRATION):
            return self.vibration_quantity(name, value, path, pool)
        value = self.mapping(value, path, {"angle", "length", "x", "y", "load", "component",
                                           "unit"})
        kinds = [k for k in ("angle", "length", "x", "y", "load") if k in value]
        if len(kinds) != 1:
            raise self.error(path, "give exactly one of angle, length, x, y, load")
        kind = kinds[0]
        unit = value.get("unit")
        if unit is not None and not isinstance(unit, str):
            raise self.error(path + ("unit",), f"unit is a unit name, got {unit!r}")
        table = {"angle": ANGLE, "load": None}.get(kind, LENGTH)
        if kind == "load" and isinstance(value["load"], str) and value["load"] in loads:
            load = loads[value["load"]]   # the unit the results use for this load
            torque = load.kind == "torque" or load.kind == "driver" and (
                driver is None or driver.kind == "angle")
            table = TORQUE if torque else FORCE
        if unit is not None and table is not None and unit not in table:
            raise self.error(path + ("unit",), f"unknown unit {unit!r} for a {kind} quantity",
                             hint="use one of " + ", ".join(table))
        if kind in ("angle", "length"):
            a, b = self.pair(value[kind], path + (kind,), pool)
            return Quantity(name, kind, a, b, unit=unit)
        if kind in ("x", "y"):
            return Quantity(name, kind, self.name(value[kind], path + (kind,), pool), unit=unit)
        load = self.name(value["load"], path + ("load",), loads, "load")
        component = value.get("component")
        if component not in (None, "x", "y"):
            raise self.error(path + ("component",), "component is x or y")
        if component and loads[load].kind != "force":
            raise self.error(path + ("component",), "only forces have x and y components")
        return Quantity(name, "load", load, component=component, unit=unit)

    def vibration_quantity(self, name, value, path, pool) -> Quantity:
        """A quantity of the vibration analysis (see docs/vibrations.md)."""
        value = self.mapping(value, path, set(VIBRATION) | {"unit", "time"})
        kinds = [k for k in VIBRATION if k in value]
        if len(kinds) != 1:
            raise self.error(path, "give exactly one of " + ", ".join(kinds))
        kind = kinds[0]
        where = path + (kind,)
        arg = value[kind]
        coords = self.vibration.get("coordinates", [])
        unit = value.get("unit")
        if unit is not None and not isinstance(unit, str):
            raise self.error(path + ("unit",), f"unit is a unit name, got {unit!r}")
        if unit is not None:
            if kind not in ("natural_frequency", "damped_frequency", "forcing_frequency"):
                raise self.error(path + ("unit",), f"{kind} is given in fixed units",
                                 hint="'unit' is for frequencies: rad/s, Hz or rpm")
            if unit not in FREQUENCY:
                raise self.error(path + ("unit",), f"unknown frequency unit {unit!r}",
                                 hint="use one of " + ", ".join(FREQUENCY))
        if "time" in value and kind != "free_response":
            raise self.error(path + ("time",), "'time' is for free_response")
        if not coords:
            raise self.error(path, f"{kind} needs a vibration problem: declare its "
                             "coordinates under 'coordinates:'")
        if kind in ("natural_frequency", "damped_frequency", "damping_ratio"):
            return Quantity(name, kind, str(self.mode(arg, where, len(coords))), unit=unit)
        if kind == "forcing_frequency":
            if arg is not True:
                raise self.error(where, "write 'forcing_frequency: true'")
            return Quantity(name, kind, unit=unit)
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

    def report(self, data, quantities, loads, pool) -> dict:
        spec = self.mapping(self.get(data, (), "report"), ("report",), set(SECTIONS) | {"decimals"})
        report = {}
        decimals = spec.get("decimals", 1)
        if isinstance(decimals, bool) or not isinstance(decimals, int) or not 0 <= decimals <= 12:
            self.error(("report", "decimals"), f"decimals is a whole number 0-12, got {decimals!r}")
        else:
            report["decimals"] = decimals
        for section in SECTIONS:
            names = spec.get(section) or []
            path = ("report", section)
            if not isinstance(names, list):
                self.error(path, "expected a list of names")
                continue
            report[section] = []
            for i, name in enumerate(names):
                if self.block(self.report_name, section, name, path + (i,), quantities,
                              loads, pool):
                    report[section].append(name)
        return report

    def report_name(self, section, name, path, quantities, loads, pool) -> bool:
        if not isinstance(name, str):
            raise self.error(path, f"expected a name, got {name!r}")
        if section == "points":
            self.name(name, path, pool)
            return True
        if split_rate(name)[0] in getattr(self, "failed", ()):
            return False            # its definition's error is reported already
        order = {"position": 0, "velocity": 1, "acceleration": 2, "statics": 0,
                 "vibration": 0}[section]
        base = split_rate(name)
        vibration = name in quantities and quantities[name].kind in VIBRATION
        if section == "vibration" or vibration:
            if not vibration or section != "vibration":
                raise self.error(path, f"'{name}' is {'' if vibration else 'not '}a quantity of "
                                 "the vibration analysis", hint="the 'vibration' section lists "
                                 "natural frequencies, modes, matrices, equilibrium, amplitudes")
            return True
        if section == "statics":
            if name not in quantities or quantities[name].kind != "load":
                raise self.error(path, f"'{name}' is not a load", hint="statics lists loads")
            return True
        if base is None or base[1] != order or base[0] not in quantities \
                or quantities[base[0]].kind == "load":
            suffix = ["", "dot", "ddot"][order]
            raise self.error(path, f"'{name}' is not a defined quantity{' rate' if order else ''}",
                             hint=f"define it under 'quantities' and name it <quantity>{suffix}")
        return True

    def keys(self, data, quantities, loads, pool, report) -> tuple:
        spec = data.get("keys")
        if spec is None:
            return ()
        if not isinstance(spec, list):
            raise self.error(("keys",), "expected a list of answer keys")
        keys = []
        for i, item in enumerate(spec):
            key = self.block(self.key, item, ("keys", i), quantities, pool)
            if key is not None:
                keys.append(key)
        return tuple(keys)

    def key(self, item, path, quantities, pool) -> AnswerKey:
        item = self.mapping(item, path, {"k", "values", "wrong", "source"}, ("values",))
        k = item.get("k")
        if k is not None and (isinstance(k, bool) or not isinstance(k, int) or not 0 <= k <= 9):
            raise self.error(path + ("k",), f"k must be a digit 0-9, got {k!r}")
        values = self.mapping(item["values"], path + ("values",))
        wrong = self.mapping(item.get("wrong") or {}, path + ("wrong",))
        for name in wrong:
            if name not in values:
                self.error(path + ("wrong", name), f"'{name}' has no printed value in this key")
        entries = []
        for name, printed in values.items():
            vpath = path + ("values", name)
            entry = self.block(self.key_entry, name, printed, vpath, quantities, pool,
                               wrong.get(name))
            if entry is not None:
                entries.append(entry)
        return AnswerKey(k, tuple(entries))

    def key_entry(self, name, printed, path, quantities, pool, wrong) -> KeyEntry:
        line = self.doc.line(path)
        is_point = name in pool and (isinstance(printed, list) or name not in quantities)
        if not is_point:
            base = split_rate(name)
            if base is None or base[0] not in quantities:
                raise self.error(path, f"the key names '{name}', which the file does not define",
                                 hint="define it under 'quantities' or fix the name")
        if wrong and not _readable(printed, is_point):
            # a garbled printed value: kept as printed, reported, never compared
            return KeyEntry(name, str(self.doc.raw.get(path, printed)), None, 0, wrong, line)
        if is_point:
            if not isinstance(printed, list) or len(printed) != 2:
                raise self.error(path, f"a point's key is [x, y], got {printed!r}")
            texts = [self.doc.raw.get(path + (i,), str(v)) for i, v in enumerate(printed)]
            nums = tuple(self.printed_number(t, path + (i,)) for i, t in enumerate(texts))
            return KeyEntry(name, f"({texts[0]}, {texts[1]})", nums,
                            min(_decimals(t) for t in texts), wrong, line)
        text = self.doc.raw.get(path, str(printed))
        return KeyEntry(name, text, self.printed_number(text, path), _decimals(text), wrong, line)

    def printed_number(self, text, path) -> float:
        try:
            value = float(str(text).replace(",", "."))
        except ValueError:
            raise self.error(path, f"cannot read printed value {text!r} as a number") from None
        if not math.isfinite(value):
            raise self.error(path, f"printed value {text!r} is not finite")
        return value


def _readable(printed, is_point: bool) -> bool:
    """Whether a printed key value can be read as a number (or [x, y] for a point)."""
    values = printed if is_point and isinstance(printed, list) and len(printed) == 2 else (
        None if is_point else [printed])
    if values is None:
        return False
    try:
        return all(math.isfinite(float(str(v).replace(",", "."))) for v in values)
    except ValueError:
        return False


def _decimals(text: str) -> int:
    text = str(text).strip().replace(",", ".")
    return len(text.split(".")[1]) if "." in text else 0
