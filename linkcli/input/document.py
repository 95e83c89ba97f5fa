"""From a YAML document to a validated :class:`~linkcli.model.mechanism.Mechanism`.

Every problem found is collected with its YAML path and line, so that
``linkcli validate`` can report them all at once; loading raises the first
batch as one :class:`InputErrors`.  The sections are read by one parser
assembled from a reader per concern: bodies, driver and loads, quantities (by their
kinds), report and keys; the ``dynamics:`` section last, on the mechanism the others built.

With a ``Symbolic`` reading (``input.symbols``, its twin for ``--symbolic``) the same
readers build the model with every parameter an exact number that carries its formula.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from linkcli.errors import InputError
from linkcli.model.mechanism import Body, Mechanism, Quiz, split_rate
from linkcli.model.units import Units
from linkcli.input.source import Document
from linkcli.input.quantities import FORCES, QuantitiesSection
from linkcli.input.textbook import TextbookQuantities
from linkcli.input.forces import ForceQuantities
from linkcli.input.efficiency import EfficiencyQuantities
from linkcli.input.clutch import ClutchSection, is_clutch
from linkcli.input.limits import LimitsSection
from linkcli.input.vibration import VibrationQuantities
from linkcli.input.report import SECTIONS, ReportSection
from linkcli.input.keys import KeysSection
from linkcli.input.bodies import BodiesSection
from linkcli.input.contacts import ContactsSection
from linkcli.input.gears import GearsSection
from linkcli.input.derived import DerivedSection
from linkcli.input.find import FindSection
from linkcli.input.oscillation import OscillationSection
from linkcli.input.dynamics import DynamicsReader
from linkcli.input.elements import ElementsReader
from linkcli.input.loads import LoadsSection
from linkcli.input.machine import MachineSection, is_machine
from linkcli.input.regime import RegimeSection
from linkcli.input.reader import (NAME, UNKNOWN, InputErrors, Reader, _kind, _Skip,
                                  reserved_parameter)

TOP_KEYS = {"title", "source", "notes", "units", "k", "params", "frame", "points", "links",
            "actuators", "sliders", "driver", "drivers", "coordinates", "loads", "quantities",
            "report",
            "keys", "dynamics", "springs", "dampers", "excitation", "initial", "equilibrium",
            "rolling", "cords", "statement", "quiz", "find", "motion", "gears", "shafts",
            "clutch"}
VIBRATION_KEYS = ("springs", "dampers", "excitation", "initial", "equilibrium")

__all__ = ["InputErrors", "Parser", "build", "split_rate", "SECTIONS", "TOP_KEYS", "UNKNOWN",
           "NAME", "_Skip"]


class Parser(Reader, BodiesSection, ContactsSection, LoadsSection, QuantitiesSection,
             TextbookQuantities, ForceQuantities, EfficiencyQuantities, LimitsSection,
             VibrationQuantities, ReportSection, KeysSection, DerivedSection,
             OscillationSection, FindSection, MachineSection, RegimeSection, GearsSection,
             ClutchSection):
    """The whole document: units, params, frame and points, then each section."""

    def parse(self) -> Mechanism:
        data = self.doc.data
        if not isinstance(data, dict):
            self.error((), f"a mechanism file is a mapping of sections, got {_kind(data)}")
            raise InputErrors(self.errors)
        for key in data:
            if key not in TOP_KEYS:
                self.error((key,), f"unknown section '{key}'",
                           hint="sections: " + ", ".join(sorted(TOP_KEYS)))
        units = self.block(self.units, data.get("units")) or Units()
        self.block(self.params, data)
        if is_clutch(data):
            return self.clutch_file(data, units)
        fixed = self.block(self.frame, data, units) or {}
        moving = self.block(self.moving, data, units, fixed) or {}
        pool = set(fixed) | set(moving)
        bodies: dict[str, Body] = {}
        self.block(self.links, data, units, pool, bodies)
        actuators = self.block(self.actuators, data, pool, bodies) or {}
        self.block(self.sliders, data, units, pool, bodies, fixed)
        self.gear_table = self.block(self.gears, data, units) or {}
        rolling = self.block(self.contacts, data, units, pool, bodies, fixed, moving) or {}
        coordinates = ()
        self.file_units = units
        self.inputs_declared(data)
        if "coordinates" in data:
            coordinates = self.block(self.coordinates, data, units, pool, fixed, moving) or ()
            driver = coordinates[0] if coordinates else None
        else:
            if "drivers" in data:
                coordinates = self.block(self.drivers, data, units, pool) or ()
                driver = coordinates[0] if coordinates else None
            else:
                driver = self.block(self.driver, data, units, pool, actuators)
            for key in VIBRATION_KEYS:
                if key in data:
                    self.error((key,), f"'{key}' belongs to a vibration problem, which declares "
                               "its coordinates", hint="replace 'driver:' by 'coordinates:', "
                               "e.g. coordinates: {theta: {angle: [O, A]}}")
        self.driver_base = driver.base if driver is not None else "angle"
        self.driver_of_file = driver
        machine = self.machine = is_machine(data)
        if machine and "coordinates" in data:
            self.error(("coordinates",), "the motion under given loads is of a mechanism with "
                       "one driver", hint="replace 'coordinates:' by 'driver:'")
        loads = self.block(self.loads, data, units, pool, bodies, actuators, driver,
                           "coordinates" not in data and not machine,
                           coordinates if "drivers" in data else ()) or {}
        motion = self.block(self.motion_section, data, units)
        self.vibration = {"coordinates": {c.name for c in coordinates}
                          if "coordinates" in data else set(),
                          "springs": self.element_names(data, "springs"),
                          "dampers": self.element_names(data, "dampers")}
        quantities = self.block(self.quantities, data, pool, loads, driver,
                                coordinates if "drivers" in data else ()) or {}
        design = self.block(self.find, data, quantities)
        report = self.block(self.report, data, quantities, loads, pool) or {}
        if design is not None:
            report["design"] = design.names
        keys = self.block(self.keys, data, quantities, loads, pool, report) or ()
        self.block(self.slipping_forces, data, rolling, loads, quantities)
        self.check_points_used(pool, bodies, actuators, fixed)
        self.large_enough(units)
        if self.errors:
            raise InputErrors(self.errors)
        title = str(data.get("title", self.doc.name))
        mech = Mechanism(title=title, file=self.doc.name, k=self.k, units=units,
                         fixed=fixed, moving=moving, bodies=bodies, actuators=actuators,
                         driver=driver, loads=loads, quantities=quantities, report=report,
                         keys=keys, coordinates=coordinates, rolling=rolling,
                         as_drawn=self.k_override is None or self.k_override == data.get("k"),
                         statement=self.block(self.statement, data) or "",
                         quiz=self.block(self.quiz, data, report) or Quiz(),
                         params={n: v for n, v in self.names.items()}, design=design,
                         motion=motion, gears=self.gear_table)
        if "dynamics" in data:
            mech.dynamics = DynamicsReader(self, mech, _Skip).run(data["dynamics"])
        if "coordinates" in data:   # after the dynamics: an element may name a rolling disc
            mech.elements = ElementsReader(self, mech, _Skip).run(data)
            for load in loads.values():
                if load.kind == "driver":
                    self.error(("loads", load.name), "a 'driver' load needs a driver; with "
                               "coordinates, give forces, torques or axial loads")
        mech.param_kinds = self.param_kinds()
        self.expression_dimensions(mech)
        self.answer_units(mech)
        self.find_units(mech)
        if self.errors:
            raise InputErrors(self.errors)
        return mech

    def inputs_declared(self, data) -> None:
        """A file declares its inputs once: ``driver`` (one), ``drivers`` (several, each
        driven) or ``coordinates`` (a vibration problem's); the second one in the file's
        order is the one refused, at its line."""
        given = [k for k in data if k in ("driver", "drivers", "coordinates")]
        if len(given) > 1:
            self.error((given[1],), f"a file has one of 'driver' (one degree of freedom), "
                       f"'drivers' (several, each with its rates) and 'coordinates' "
                       f"(vibrations), not both '{given[0]}' and '{given[1]}'",
                       hint=f"remove one of '{given[0]}' and '{given[1]}'")

    def slipping_forces(self, data, rolling, loads, quantities):
        """Refuse forces where a belt slips: its slip loses power, so the torques are not in
        the ratio of the speeds and virtual work (and the joint forces' contacts) do not
        hold; its speeds are answers."""
        slipping = [r.name for r in rolling.values() if r.slip]
        forces = [n for n, q in quantities.items() if q.kind in FORCES and q.kind != "load"]
        asked = ([f"loads ({', '.join(loads)})"] if loads else []) + \
            ([f"forces ({', '.join(forces)})"] if forces else []) + \
            (["dynamics"] if "dynamics" in data else [])
        if slipping and asked:
            raise self.error(("cords", slipping[0], "slip"), f"the belt {slipping[0]} slips, "
                             f"and the file asks {' and '.join(asked)}: a slipping belt loses "
                             "power, so its torques are not in the ratio of its speeds and "
                             "virtual work does not hold", hint="ask the speeds of a slipping "
                             "belt drive; its forces need the belt's tensions (not modelled)")

    def statement(self, data) -> str:
        value = data.get("statement", "")
        if value is None:
            return ""
        if not isinstance(value, str):
            raise self.error(("statement",), f"the statement is text, got {_kind(value)}")
        return value

    def quiz(self, data, report) -> Quiz:
        """``quiz: {points: {position: 9, velocity: 9, statics: 2}, tolerance: 0.05,
        ask_given: false, not_asked: [phi4dot, phi5dot]}``."""
        spec = data.get("quiz")
        if spec is None:
            return Quiz()
        spec = self.mapping(spec, ("quiz",), {"points", "tolerance", "ask_given", "not_asked"})
        points = None
        if "points" in spec:
            path = ("quiz", "points")
            given = self.mapping(spec["points"], path, set(SECTIONS) - {"points"})
            points = {}
            for section, value in given.items():
                number = self.number(value, path + (section,))
                if not number > 0:
                    raise self.error(path + (section,), f"points must be positive, got {value!r}")
                if report and not report.get(section):
                    raise self.error(path + (section,), f"the report has no {section} section "
                                     "to score", hint="remove it or list its names in 'report'")
                points[section] = number
        tolerance = None
        if "tolerance" in spec:
            tolerance = self.number(spec["tolerance"], ("quiz", "tolerance"))
            if not tolerance > 0:
                raise self.error(("quiz", "tolerance"), f"a tolerance must be positive, got "
                                 f"{spec['tolerance']!r}", hint="in the answers' display units")
        ask_given = spec.get("ask_given", True)
        if not isinstance(ask_given, bool):
            raise self.error(("quiz", "ask_given"), f"expected true or false, got {ask_given!r}",
                             hint="false leaves out the boxes whose value the question gives")
        return Quiz(points, tolerance, ask_given, self.not_asked(spec, report))

    def not_asked(self, spec, report) -> tuple:
        """``quiz.not_asked``: report names the quiz leaves out (the statement does not ask
        them); each must be a name of the report."""
        path = ("quiz", "not_asked")
        value = spec.get("not_asked", [])
        if not isinstance(value, list):
            raise self.error(path, f"expected a list of the report's names, got {value!r}")
        listed = {n for section in SECTIONS for n in (report or {}).get(section) or []
                  if isinstance(n, str)}
        return tuple(self.name(n, path + (i,), listed, "name of the report")
                     for i, n in enumerate(value))

    @staticmethod
    def element_names(data, key) -> set:
        value = data.get(key)
        return {n for n in value if isinstance(n, str)} if isinstance(value, dict) else set()

    def units(self, value) -> Units:
        if value is None:
            return Units()
        self.mapping(value, ("units",))
        try:
            return Units(value)
        except InputError as exc:
            raise self.error(("units", exc.key.split(".")[-1]) if exc.key else ("units",),
                             exc.detail, exc.hint) from None

    def params(self, data):
        k = data.get("k")
        if self.k_override is not None:
            k = self.k_override
        if k is not None:
            if isinstance(k, bool) or not isinstance(k, int) or not 0 <= k <= 9:
                raise self.error(("k",), f"k must be a digit 0-9, got {k!r}",
                                 hint="k is the last digit of the matricola")
            self.names["k"] = float(k)
            self.k = k
        params = data.get("params") or {}
        self.mapping(params, ("params",))
        for key, value in params.items():
            reason = reserved_parameter(key) if isinstance(key, str) else None
            if not isinstance(key, str) or not NAME.match(key) or reason:
                self.error(("params", key), f"'{key}' cannot be a parameter name" +
                           (f": {reason}" if reason else ""),
                           hint="rename the parameter" if reason else None)
                continue
            try:
                self.names[key] = self.number(value, ("params", key)) \
                    if key not in self.overrides else float(self.overrides[key])
            except _Skip:
                continue
            if self.symbolic is not None:
                self.names[key] = self.symbolic.param(key, self.names[key])

    def frame(self, data, units) -> dict:
        frame = self.mapping(self.get(data, (), "frame"), ("frame",))
        fixed = {}
        for name, value in frame.items():
            path = ("frame", name)
            if self.block(self.name, name, path) is None:
                continue
            xy = self.block(self.xy, value, path, units)
            if xy is not None:
                fixed[name] = xy
        if not fixed:
            raise self.error(("frame",), "the frame needs at least one fixed point")
        return fixed

    def moving(self, data, units, fixed) -> dict:
        points = self.mapping(self.get(data, (), "points"), ("points",))
        moving = {}
        for name, value in points.items():
            path = ("points", name)
            if self.block(self.name, name, path) is None:
                continue
            if name in fixed:
                self.error(path, f"point '{name}' is both fixed (frame) and moving")
                continue
            xy = self.block(self.xy, value, path, units)
            if xy is not None:
                moving[name] = xy
        return moving

    def check_points_used(self, pool, bodies, actuators, fixed):
        if any((e.key or "").startswith(("links", "actuators", "sliders")) for e in self.errors):
            return   # a body that failed to parse would make its points look unused
        used = {p for body in bodies.values() for p in body.points}
        for point in sorted(pool - used - set(fixed)):
            self.error(("points", point), f"moving point '{point}' belongs to no link, slider or "
                       "actuator", hint="add it to a link or remove it")


@dataclass(frozen=True)
class Source:
    """What a mechanism was built from: the document, the digit asked (None: the file's) and
    the parameters given other values than the file's (name, value) pairs."""

    doc: Document
    k: int | None = None
    params: tuple = ()
    #: path -> (text, unit kind) of every value the file writes as an expression
    written: dict = field(default_factory=dict, compare=False)


def build(doc: Document, k: int | None = None, params: dict | None = None,
          symbolic=None) -> Mechanism:
    """The validated mechanism of ``doc`` for matricola digit ``k`` (None: the file's), its
    ``params`` given these values (numbers as the file writes them) instead of the file's;
    with ``symbolic`` (an ``input.symbols.Symbolic``) its numbers carry their formulas in
    the parameters (``model.exact``)."""
    params = dict(params or {})
    if params:
        declared = doc.data.get("params") if isinstance(doc.data, dict) else None
        declared = declared if isinstance(declared, dict) else {}
        for name, value in params.items():
            if name not in declared:
                listed = ", ".join(sorted(map(str, declared))[:10]) or "none"
                raise InputError(f"'{name}' is not a parameter of this file (params: {listed})",
                                 file=doc.name, key="params", hint="a varied or unknown "
                                 "value is one of the file's params")
            if isinstance(value, bool) or not isinstance(value, (int, float)) or \
                    not math.isfinite(value):
                raise InputError(f"parameter '{name}' must be a finite number, got {value!r}",
                                 file=doc.name, key=f"params.{name}")
    parser = Parser(doc, k, symbolic)
    parser.overrides = params
    mech = parser.parse()
    mech.source = Source(doc, k, tuple(sorted(params.items())), parser.written)
    return mech


def rebuild(mech: Mechanism, params: dict) -> Mechanism:
    """``mech`` built again from its document, its digit and these ``params`` (on top of the
    ones it was built with)."""
    source = mech.source
    return build(source.doc, source.k, {**dict(source.params), **params})
