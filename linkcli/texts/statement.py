"""The problem's data as an exam states them: every number the solution uses, with its unit.

Written from the model, not from the file's text, so that a quiz or a worked solution
states what is solved: the frame, each link with its shape, the actuators, each slider
with its guide, the rolling contacts and cords, the driver (or the coordinates of a
vibration problem), the loads with their directions, masses and inertias, gravity,
friction, springs, dampers and the excitation.  Each datum is stated once, in the
file's display units, in Italian or English (``lang``).  Numbers are written with up
to ten significant digits and the decimal separator of the language (a comma in
Italian, where the two coordinates of a point are then separated by a semicolon).

A rigid body's shape is stated as the exam would: its base side (first point to
second) and every other point by its distance from a placed point and the angle from
the base direction, or by its distances from two placed points; of the ways that
give the same shape, the one with the fewest digits (an exam's round numbers).  A
slider's pin offsets are stated in the frame's axes or the guide's, whichever is
rounder.

:func:`describe` says in words what each reported quantity is, for the answer table.
"""
from __future__ import annotations

import cmath
import math
import weakref
from decimal import Decimal

from linkcli.model.mechanism import FRAME, split_rate

SIGNIFICANT = 10        # digits of a stated number
CLOSE = 1e-9            # relative agreement of a stated number with the model's

#: each phrase in English and in Italian, with the places of its numbers and names
PHRASES = {
    "frame": ("Frame (fixed points)", "Telaio (punti fissi)"),
    "links": ("Links", "Membri"),
    "link": ("link", "membro"),
    "body": ("rigid body {name}", "corpo rigido {name}"),
    "base": ("{a}{b} = {length}", "{a}{b} = {length}"),
    "polar": (
        "{p} at {length} from {f}, at {angle} from {a}→{b}",
        "{p} a {length} da {f}, a {angle} da {a}→{b}",
    ),
    "two": (
        "{p} at {d1} from {p1} and {d2} from {p2}, to the {side} of {p1}→{p2}",
        "{p} a {d1} da {p1} e a {d2} da {p2}, a {side} di {p1}→{p2}",
    ),
    "left": ("left", "sinistra"),
    "right": ("right", "destra"),
    "actuator": (
        "linear actuator {name}: cylinder pivoted at {a}, rod at {b} (variable length)",
        "attuatore lineare {name}: cilindro incernierato in {a}, stelo in {b} (lunghezza "
        "variabile)",
    ),
    "slider": ("slider {name}: {p} {guide}", "pattino {name}: {p} {guide}"),
    "fixed_x": (
        "on the fixed vertical guide x = {x} (direction +y)",
        "sulla guida fissa verticale x = {x} (verso +y)",
    ),
    "fixed_y": (
        "on the fixed horizontal guide y = {y} (direction +x)",
        "sulla guida fissa orizzontale y = {y} (verso +x)",
    ),
    "fixed_line": (
        "on the fixed guide through {point} at {angle}",
        "sulla guida fissa per {point} a {angle}",
    ),
    "slot": (
        "on a guide of {carrier} along {b}→{c}, {offset} to its left",
        "su una guida di {carrier} lungo {b}→{c}, a {offset} alla sua sinistra",
    ),
    "slot_on": (
        "on a guide of {carrier} along {b}→{c}",
        "su una guida di {carrier} lungo {b}→{c}",
    ),
    "actuator_line": (
        "on the line of actuator {name} ({b}→{c})",
        "sulla retta dell'attuatore {name} ({b}→{c})",
    ),
    "carries": ("carries {p} at {pair} from {o} ({axes})", "porta {p} in {pair} da {o} ({axes})"),
    "frame_axes": ("x, y", "x, y"),
    "guide_axes": ("along the guide, to its left", "lungo la guida, alla sua sinistra"),
    "rolls_line": (
        "disc {disc} (centre {c}, radius {r}) rolls without slipping on a fixed line along "
        "{dir}, the centre on its {side}",
        "disco {disc} (centro {c}, raggio {r}) rotola senza strisciare su una retta fissa "
        "lungo {dir}, con il centro alla sua {side}",
    ),
    "rolls_circle": (
        "disc {disc} (centre {c}, radius {r}) rolls without slipping {where} the fixed "
        "circle of centre {t} and radius {R}",
        "disco {disc} (centro {c}, raggio {r}) rotola senza strisciare {where} la "
        "circonferenza fissa di centro {t} e raggio {R}",
    ),
    "rolls_disc": (
        "disc {disc} (centre {c}, radius {r}) rolls without slipping {where} disc {other} "
        "(centre {t}, radius {R})",
        "disco {disc} (centro {c}, raggio {r}) rotola senza strisciare {where} il disco "
        "{other} (centro {t}, raggio {R})",
    ),
    "inside": ("inside", "dentro"),
    "outside": ("outside", "fuori"),
    "cord": (
        "a taut cord leaves pulley {disc} (centre {c}, radius {r}) from its {side} along "
        "{dir}, to {p}",
        "una fune tesa lascia la puleggia {disc} (centro {c}, raggio {r}) dalla sua {side} "
        "lungo {dir}, fino a {p}",
    ),
    "belt": (
        "a taut belt leaves pulley {disc} (centre {c}, radius {r}) from its {side} along "
        "{dir}, to disc {other} (centre {t}, radius {R}), on its {oside}",
        "una cinghia tesa lascia la puleggia {disc} (centro {c}, raggio {r}) dalla sua "
        "{side} lungo {dir}, fino al disco {other} (centro {t}, raggio {R}), sulla sua "
        "{oside}",
    ),
    "driver": ("driver: q = {what} = {value}", "movente: q = {what} = {value}"),
    "rate": ("q' = {rate}", "q' = {rate}"),
    "accel": ("q'' = {accel}", "q'' = {accel}"),
    "ccw": ("counter-clockwise", "antiorario"),
    "cw": ("clockwise", "orario"),
    "longer": ("lengthening", "in allungamento"),
    "shorter": ("shortening", "in accorciamento"),
    "angle_of": ("angle of {a}→{b}", "angolo di {a}→{b}"),
    "length_of": ("length {a}{b}", "lunghezza {a}{b}"),
    "x_of": ("x of {a}", "x di {a}"),
    "y_of": ("y of {a}", "y di {a}"),
    "coordinates": ("coordinates: {names}", "coordinate: {names}"),
    "figure_is": ("in the figure {values}", "in figura {values}"),
    "figure_points": ("position in the figure: {points}", "posizione in figura: {points}"),
    "force": (
        "force {name} = {value} at {at}, {direction}",
        "forza {name} = {value} in {at}, {direction}",
    ),
    "force_xy": (
        "force {name} at {at}: x component {x}, y component {y}",
        "forza {name} in {at}: componente x {x}, componente y {y}",
    ),
    "unknown_force": (
        "force {name} at {at}, {direction}: unknown",
        "forza {name} in {at}, {direction}: incognita",
    ),
    "along_x": ("along x", "lungo x"),
    "along_y": ("along y", "lungo y"),
    "at_angle": ("at {angle} from +x", "a {angle} da +x"),
    "torque": (
        "torque {name} = {value} on {on} (counter-clockwise positive)",
        "coppia {name} = {value} su {on} (positiva antioraria)",
    ),
    "unknown_torque": (
        "torque {name} on {on} (counter-clockwise positive): unknown",
        "coppia {name} su {on} (positiva antioraria): incognita",
    ),
    "axial": (
        "axial force {name} = {value} in actuator {on} (positive pushes its ends apart)",
        "forza assiale {name} = {value} nell'attuatore {on} (positiva se allontana gli "
        "estremi)",
    ),
    "unknown_axial": (
        "axial force {name} in actuator {on} (positive pushes its ends apart): unknown",
        "forza assiale {name} nell'attuatore {on} (positiva se allontana gli estremi): "
        "incognita",
    ),
    "driver_load": (
        "{name}: the generalised force on q ({what}), unknown",
        "{name}: la forza generalizzata su q ({what}), incognita",
    ),
    "driver_load_known": (
        "{name} = {value}: the generalised force on q ({what})",
        "{name} = {value}: la forza generalizzata su q ({what})",
    ),
    "q_torque": ("a torque, positive counter-clockwise", "una coppia, positiva antioraria"),
    "q_force": ("a force, positive where it makes q grow", "una forza, positiva se fa crescere q"),
    "q_actuator": (
        "the actuator's force, positive in compression",
        "la forza dell'attuatore, positiva se di compressione",
    ),
    "pressure": (
        "pressure {name} = {p} on {what} of {size}, on {on} {direction}",
        "pressione {name} = {p} su {what} di {size}, su {on} {direction}",
    ),
    "bore": ("a bore", "un alesaggio"),
    "area": ("an area", "un'area"),
    "along_guide": ("along its guide", "lungo la sua guida"),
    "pushes_apart": ("(positive pushes its ends apart)", "(positiva se allontana gli estremi)"),
    "gravity": ("gravity g = {g} {direction}", "gravità g = {g} {direction}"),
    "down": ("along -y", "lungo -y"),
    "mass": ("{body}: m = {m}, J_G = {J}, G {where}", "{body}: m = {m}, J_G = {J}, G {where}"),
    "mass_only": ("{body}: m = {m}, G {where}", "{body}: m = {m}, G {where}"),
    "inertia_only": ("{body}: J_G = {J}, G {where}", "{body}: J_G = {J}, G {where}"),
    "at_point": ("at {p}", "in {p}"),
    "in_frame": (
        "at ({x}, {y}) in its frame (origin {a}, x along {a}→{b})",
        "in ({x}; {y}) nel suo riferimento (origine {a}, x lungo {a}→{b})",
    ),
    "in_block": (
        "at ({x}, {y}) from {p} (along the guide, to its left)",
        "in ({x}; {y}) da {p} (lungo la guida, alla sua sinistra)",
    ),
    "on_actuator": (
        "at ({x}, {y}) from {p} (along {a}→{b}, to its left)",
        "in ({x}; {y}) da {p} (lungo {a}→{b}, alla sua sinistra)",
    ),
    "of_link": ("link {name}", "membro {name}"),
    "of_slider": ("slider {name}", "pattino {name}"),
    "of_cylinder": ("cylinder of actuator {name}", "cilindro dell'attuatore {name}"),
    "of_rod": ("rod of actuator {name}", "stelo dell'attuatore {name}"),
    "point_mass": ("point mass {m} at {p}", "massa concentrata {m} in {p}"),
    "friction": (
        "Coulomb friction between slider {name} and its guide: mu = {mu}",
        "attrito coulombiano tra il pattino {name} e la sua guida: mu = {mu}",
    ),
    "disc": (
        "disc {name} rolling without slipping: centre {c}, radius {r}, m = {m}, J = {J}, "
        "centre on the {side} of its guide",
        "disco {name} che rotola senza strisciare: centro {c}, raggio {r}, m = {m}, J = "
        "{J}, centro alla {side} della sua guida",
    ),
    "resistance": (
        "rolling resistance (shift of the normal force) {u}",
        "attrito volvente (spostamento della reazione normale) {u}",
    ),
    "pin": (
        "friction circle of pin {p}: rho = {rho}",
        "circolo d'attrito della cerniera {p}: rho = {rho}",
    ),
    "spring": (
        "spring {name} {between}: k = {k}, {free}",
        "molla {name} {between}: k = {k}, {free}",
    ),
    "damper": ("damper {name} {between}: c = {c}", "smorzatore {name} {between}: c = {c}"),
    "between_points": ("between {a} and {b}", "tra {a} e {b}"),
    "between_along": (
        "between {a} and {b}, deforming only {direction}",
        "tra {a} e {b}, che si deforma solo {direction}",
    ),
    "between_bodies": ("between {a} and {b} (torsional)", "tra {a} e {b} (torsionale)"),
    "unstretched": ("unstretched in the figure", "scarica nella posizione della figura"),
    "free_length": ("free length {value}", "lunghezza libera {value}"),
    "free_angle": ("free angle {value}", "angolo libero {value}"),
    "preload": (
        "force in the figure {value} (tension positive)",
        "forza nella posizione della figura {value} (positiva se di trazione)",
    ),
    "static": (
        "preloaded so that the figure is a static equilibrium",
        "precaricata in modo che la figura sia di equilibrio statico",
    ),
    "frequency": (
        "excitation frequency Omega = {value}",
        "pulsazione della forzante Omega = {value}",
    ),
    "harmonic_force": (
        "harmonic force {name} = {value} cos(Omega t + {phase}) at {at}, {direction}",
        "forzante {name} = {value} cos(Omega t + {phase}) in {at}, {direction}",
    ),
    "harmonic_torque": (
        "harmonic torque {name} = {value} cos(Omega t + {phase}) on {on}",
        "coppia forzante {name} = {value} cos(Omega t + {phase}) su {on}",
    ),
    "support": (
        "imposed motion of {coordinate}: {value} cos(Omega t + {phase}) about its figure "
        "value",
        "moto imposto di {coordinate}: {value} cos(Omega t + {phase}) attorno al valore "
        "della figura",
    ),
    "road": (
        "road profile of amplitude {value}, wavelength {wavelength}, travelled at {speed}",
        "profilo stradale di ampiezza {value}, lunghezza d'onda {wavelength}, percorso a "
        "{speed}",
    ),
    "initial": (
        "initial conditions (from the equilibrium): {values}",
        "condizioni iniziali (dall'equilibrio): {values}",
    ),
    "initial_figure": (
        "initial conditions (from the figure): {values}",
        "condizioni iniziali (dalla figura): {values}",
    ),
    "initial_unstretched": (
        "initial conditions (from where {springs} unstretched): {values}",
        "condizioni iniziali (da dove {springs} a riposo): {values}",
    ),
    "design": (
        "find {unknowns} such that {targets}",
        "trovare {unknowns} tali che {targets}",
    ),
    "design_one": (
        "find {unknowns} such that {targets}",
        "trovare {unknowns} tale che {targets}",
    ),
    "depends": ("depends on {name}", "dipende da {name}"),
    "equilibrium_figure": (
        "the figure is a static equilibrium",
        "la figura è una posizione di equilibrio statico",
    ),
    "frame_body": ("frame", "telaio"),
}
LANGS = ("en", "it")
WORDS = {lang: {key: pair[i] for key, pair in PHRASES.items()} for i, lang in enumerate(LANGS)}


# --- numbers --------------------------------------------------------------------------------
def number(value: float, lang: str = "en") -> str:
    """``value`` with up to ten significant digits, without exponent between 1e-6 and 1e12,
    with the language's decimal separator; never '-0'."""
    value = float(value)
    if value == 0 or not math.isfinite(value):
        return "0" if value == 0 else str(value)
    text = f"{value:.{SIGNIFICANT}g}"
    if 1e-6 <= abs(value) < 1e12:
        text = format(Decimal(text), "f")
        if "." in text:
            text = text.rstrip("0").rstrip(".")
    if text in ("-0", "0"):
        text = "0"
    return text.replace(".", ",") if lang == "it" else text


def digits(value: float) -> int:
    """How many significant digits ``value`` needs (a measure of roundness: 90 needs 1,
    228.035 needs 6); SIGNIFICANT + 1 when ten are not enough."""
    value = float(value)
    if value == 0:
        return 1
    for n in range(1, SIGNIFICANT + 1):
        if abs(float(f"{value:.{n}g}") - value) <= CLOSE * abs(value):
            return n
    return SIGNIFICANT + 1


class Writer:
    """Numbers of one mechanism in its display units, in one language."""

    def __init__(self, mech, lang="en"):
        self.mech, self.lang, self.units = mech, lang, mech.units
        self.w = WORDS[lang]

    def num(self, value) -> str:
        return number(value, self.lang)

    def amount(self, si: float, kind: str) -> str:
        """An SI value in the file's unit of ``kind``, with the unit."""
        return f"{self.num(si / self.units.factor(kind))} {self.units.names[kind]}"

    def length(self, si: float) -> str:
        return self.amount(si, "length")

    def angle(self, si: float) -> str:
        value = si / self.units.factor("angle")
        unit = self.units.names["angle"]
        return f"{self.num(value)}°" if unit == "deg" else f"{self.num(value)} {unit}"

    def signed_angle(self, si: float) -> str:
        """An angle in (-half turn, half turn]."""
        return self.angle(math.remainder(si, 2 * math.pi))

    def pair(self, a: float, b: float) -> str:
        sep = "; " if self.lang == "it" else ", "
        return f"({self.num(a)}{sep}{self.num(b)})"

    def point(self, z: complex) -> str:
        f = self.units.factor("length")
        return f"{self.pair(z.real / f, z.imag / f)} {self.units.names['length']}"

    def direction(self, u: complex) -> str:
        """'along x', 'along y' or 'at 205° from +x' for a unit vector (its sense signed by
        the value it multiplies)."""
        if abs(u - 1) < CLOSE:
            return self.w["along_x"]
        if abs(u - 1j) < CLOSE:
            return self.w["along_y"]
        return self.w["at_angle"].format(angle=self.angle(math.atan2(u.imag, u.real) %
                                                          (2 * math.pi)))

    def axis(self, u: complex) -> str:
        """+x, -x, +y, -y or an angle, for a direction along which something runs."""
        for name, v in (("+x", 1), ("-x", -1), ("+y", 1j), ("-y", -1j)):
            if abs(u - v) < CLOSE:
                return name
        return self.angle(math.atan2(u.imag, u.real) % (2 * math.pi))


# --- the data -------------------------------------------------------------------------------
def data_lines(mech, lang: str = "en", solution=None) -> list[str]:
    """Every datum of ``mech`` as lines of text (see the module's docstring).  Where it asks
    a design question, a datum that depends on an unknown is stated as the unknown, not at
    the value the file gives it for the figure, and the last line asks the unknowns, each
    named by what it is, with the targets in their units (those of ``solution``,
    runs.design's, where the file gives none)."""
    w = Writer(mech, lang)
    lines = _lines(w)
    if mech.design is not None and not mech.design.fixed:
        lines = _unknowns_stated(mech, lines, lang)
    return lines + _design(w, solution)


def _lines(w) -> list:
    lines = []
    for part in (_frame, _links, _actuators, _sliders, _contacts, _motion, _loads, _dynamics,
                 _elements):
        lines += part(w)
    return [line for line in lines if line]


# --- a design question ------------------------------------------------------------------------
#: where a file writes an unknown parameter (a key path, '*' any name) and what it is there
ROLES = (
    (("links", "*", "length"), ("the length of {}", "la lunghezza di {}"),
     ("the lengths of {}", "le lunghezze di {}")),
    (("springs", "*", "k"), ("the stiffness of spring {}", "la rigidezza della molla {}"),
     ("the stiffness of springs {}", "la rigidezza delle molle {}")),
    (("springs", "*", "free_length"), ("the free length of spring {}",
                                       "la lunghezza libera della molla {}"),
     ("the free length of springs {}", "la lunghezza libera delle molle {}")),
    (("dampers", "*", "c"), ("the damping coefficient of damper {}",
                             "il coefficiente di smorzamento dello smorzatore {}"),
     ("the damping coefficient of dampers {}",
      "il coefficiente di smorzamento degli smorzatori {}")),
    (("dynamics", "masses", "*"), ("the mass at {}", "la massa in {}"),
     ("the masses at {}", "le masse in {}")),
    (("dynamics", "inertias", "*"), ("the moment of inertia of {}",
                                     "il momento d'inerzia di {}"),
     ("the moments of inertia of {}", "i momenti d'inerzia di {}")),
    (("loads", "*", "value"), ("the value of load {}", "il valore del carico {}"),
     ("the value of loads {}", "il valore dei carichi {}")),
    (("driver", "value"), ("the driver's value", "il valore del movente"), None),
    (("driver", "rate"), ("the driver's rate", "la velocità del movente"), None),
)
#: a value of the unknown for the data stated at another one (a ratio, not a round number)
OTHER = 1.2345678


def unknown_role(mech, name: str, lang: str = "en") -> str:
    """What the parameter ``name`` is where the file writes it on its own ('the length of
    OA'), each place once; '' where no key says."""
    data = mech.source.doc.data if mech.source is not None else None
    found = {}
    for path in _written_at(data, name):
        for role in ROLES:
            pattern = role[0]
            if len(path) == len(pattern) and all(p in ("*", q) for p, q in zip(pattern, path)):
                found.setdefault(role, []).extend(q for p, q in zip(pattern, path) if p == "*")
    i = LANGS.index(lang)
    return ", ".join((role[2] if len(names) > 1 and role[2] else role[1])[i].format(
        ", ".join(names)) for role, names in found.items())


def _written_at(data, name, path=()) -> list:
    """The key paths of ``data`` whose value is the text ``name``."""
    if isinstance(data, dict):
        return [p for key, value in data.items() for p in _written_at(value, name,
                                                                       path + (str(key),))]
    if isinstance(data, str) and data.strip() == name and path and path[0] != "params":
        return [path]
    return []


NUMBER = r"-?\d+(?:[.,]\d+)?(?:e[-+]?\d+)?"


def variants(mech) -> list:
    """(name, start, other value, the mechanism built with it) of each unknown of ``mech``'s
    design question that can be built at another value (kept per mechanism)."""
    from linkcli.errors import LinkcliError
    from linkcli.input.document import rebuild
    kept = _VARIANTS
    if mech not in kept:
        out = []
        for u in mech.design.unknowns:
            start = float(mech.params[u.name])
            other = start * OTHER if start else OTHER
            try:
                out.append((u.name, start, other, rebuild(mech, {u.name: other})))
            except LinkcliError:
                continue
        kept[mech] = out
    return kept[mech]


_VARIANTS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def unknown_datum(mech, measure, si_factor=1.0) -> str | None:
    """The unknown a datum ``measure(mech)`` (SI; ``si_factor`` of the unknown's unit, as
    the file writes it) depends on: its name where the datum is the unknown, 'name?' where
    it depends on it otherwise; None where it is data (or no design question is asked)."""
    if mech.design is None or mech.design.fixed:
        return None
    here = measure(mech)
    for name, start, other, varied in variants(mech):
        there = measure(varied)
        if math.isclose(here, there, rel_tol=CLOSE, abs_tol=CLOSE * abs(here)):
            continue
        if math.isclose(here, start * si_factor, rel_tol=CLOSE) and \
                math.isclose(there, other * si_factor, rel_tol=CLOSE):
            return name
        return f"{name}?"
    return None


def _unknowns_stated(mech, lines, lang) -> list:
    """``lines`` with every number that changes with an unknown's value (the data stated
    again at another value, number by number) written as the unknown's name."""
    import re
    split = [re.split(f"({NUMBER})", line) for line in lines]
    for name, start, other, varied_mech in variants(mech):
        varied = _lines(Writer(varied_mech, lang))
        if len(varied) != len(lines):
            continue
        for parts, line in zip(split, varied):
            there = re.split(f"({NUMBER})", line)
            if len(there) != len(parts) or there[::2] != parts[::2]:
                continue
            for i in range(1, len(parts), 2):
                if parts[i] != there[i]:
                    parts[i] = _as_unknown(parts, i, there[i], name, start, other, lang)
    return ["".join(parts) for parts in split]


def _as_unknown(parts, i, there, name, start, other, lang) -> str:
    """The number ``parts[i]`` (``there`` at the other value) as the unknown ``name``: its
    own name where the datum is the unknown as the file writes it, a multiple of it ('8 ks')
    where it is proportional, else '?' and that it depends on it; never its number."""
    import re

    def read(text):
        return float(text.replace(",", ".")) if lang == "it" else float(text)
    here, varied = read(parts[i]), read(there)
    ratio = here / start if start else math.nan
    if not math.isclose(varied / other, ratio, rel_tol=1e-6):
        return f"? ({WORDS[lang]['depends'].format(name=name)})"
    parts[i + 1] = re.sub(r"^(°| [^\s,;()]+)", "", parts[i + 1])    # the unknown's unit
    if math.isclose(ratio, 1.0, rel_tol=CLOSE):
        return name
    return f"{number(ratio, lang)} {name}"


def _design(w, solution=None) -> list:
    """A design question: the unknowns, each with what it is, and the targets' values with
    their units."""
    design = w.mech.design
    if design is None:
        return []
    units = solution.units if solution is not None else {}
    targets = ", ".join(f"{t.name} = {w.num(t.value)}" + (f" {u}" if (u := t.unit or
                                                                   units.get(t.name)) else "")
                        + (f" ({what})" if (what := describe(w.mech, t.name, w.lang)) else "")
                        for t in design.targets)
    unknowns = ", ".join(f"{n} ({role})" if (role := unknown_role(w.mech, n, w.lang)) else n
                         for n in design.names)
    key = "design_one" if len(design.names) == 1 else "design"
    return [w.w[key].format(unknowns=unknowns, targets=targets)]


def _frame(w) -> list:
    fixed = [f"{p} = {w.point(z)}" for p, z in w.mech.fixed.items() if not p.startswith("~")]
    return [f"{w.w['frame']}: " + ", ".join(fixed)] if fixed else []


def _links(w) -> list:
    binary, bodies = [], []
    rolling = {r.disc for r in w.mech.rolling.values()}
    for body in w.mech.bodies.values():
        if body.kind != "link":
            continue
        if len(body.points) == 2:
            a, b = body.points
            text = w.w["base"].format(a=a, b=b, length=w.length(abs(body.local[b] -
                                                                    body.local[a])))
            named = body.name not in (a + b, b + a) and body.name not in rolling
            binary.append(f"{body.name} {text}" if named else text)
        else:
            bodies.append(w.w["body"].format(name=body.name) + ": " + "; ".join(_shape(w, body)))
    out = [f"{w.w['links']}: " + ", ".join(binary)] if binary else []
    return out + bodies


def _shape(w, body) -> list:
    """The base side and each further point by its roundest description."""
    p, local = body.points, body.local
    base = local[p[1]] - local[p[0]]
    parts = [w.w["base"].format(a=p[0], b=p[1], length=w.length(abs(base)))]
    for i in range(2, len(p)):
        parts.append(_place_point(w, p, i, local, base))
    return parts


def _place_point(w, p, i, local, base) -> str:
    """Point p[i] from earlier ones: by distance and angle from the base direction, or by
    two distances; the description with the fewest digits."""
    f = w.units.factor("length")
    fa = w.units.factor("angle")
    target = local[p[i]]
    options = []
    for j in range(i):                 # polar from p[j]
        z = target - local[p[j]]
        angle = math.remainder(cmath.phase(z / base), 2 * math.pi)
        cost = digits(abs(z) / f) + digits(angle / fa) + (0 if j == 0 else 0.5)
        options.append((cost, len(options), w.w["polar"].format(
            p=p[i], length=w.length(abs(z)), f=p[j], angle=w.angle(angle), a=p[0], b=p[1])))
    for j in range(i):                 # two distances from p[j], p[m]
        for m in range(j + 1, i):
            d1, d2 = abs(target - local[p[j]]), abs(target - local[p[m]])
            along = local[p[m]] - local[p[j]]
            cross = (along.conjugate() * (target - local[p[j]])).imag
            if abs(cross) <= CLOSE * abs(along) * max(d1, d2):
                continue                # on the line: the side is undefined
            side = w.w["left"] if cross > 0 else w.w["right"]
            cost = digits(d1 / f) + digits(d2 / f) + 1
            options.append((cost, len(options), w.w["two"].format(
                p=p[i], d1=w.length(d1), p1=p[j], d2=w.length(d2), p2=p[m], side=side)))
    return min(options)[2]


def _actuators(w) -> list:
    return [w.w["actuator"].format(name=a.name, a=a.a, b=a.b)
            for a in w.mech.actuators.values()]


def _sliders(w) -> list:
    out = []
    for body in w.mech.bodies.values():
        if body.kind != "block":
            continue
        g = body.guide
        text = w.w["slider"].format(name=body.name, p=body.points[0], guide=_guide(w, g))
        carried = [_carried(w, body, other) for other in body.points[1:]]
        out.append(text + ("; " + "; ".join(carried) if carried else ""))
    return out


def fixed_line(mech, g):
    """(a point of the line, its unit direction) of guide ``g`` of the frame (SI)."""
    b, c = mech.fixed[g.b], mech.fixed[g.c]
    u = (c - b) / abs(c - b)
    return b + g.offset * 1j * u, u


def _guide(w, g) -> str:
    if g.carrier == FRAME:
        p0, u = fixed_line(w.mech, g)
        f = w.units.factor("length")
        if abs(u - 1) < CLOSE:
            return w.w["fixed_y"].format(y=w.length(p0.imag))
        if abs(u - 1j) < CLOSE:
            return w.w["fixed_x"].format(x=w.length(p0.real))
        named = [p for p, z in w.mech.fixed.items() if not p.startswith("~")
                 and abs(((z - p0) * u.conjugate()).imag) <= CLOSE * max(abs(z), abs(p0), f)]
        point = named[0] if named else w.point(p0)
        return w.w["fixed_line"].format(point=point, angle=w.angle(cmath.phase(u) %
                                                                    (2 * math.pi)))
    if g.carrier.endswith(".cylinder"):
        return w.w["actuator_line"].format(name=g.carrier[:-len(".cylinder")], b=g.b, c=g.c)
    carrier = g.carrier
    if g.offset == 0:
        return w.w["slot_on"].format(carrier=carrier, b=g.b, c=g.c)
    return w.w["slot"].format(carrier=carrier, b=g.b, c=g.c, offset=w.length(g.offset))


def _carried(w, body, other) -> str:
    """A pin on a block: in the frame's axes on a fixed guide when rounder, else in the
    guide's (along, left normal)."""
    f = w.units.factor("length")
    local = body.local[other] - body.local[body.points[0]]
    axes = w.w["guide_axes"]
    u, v = local.real, local.imag
    if body.guide.carrier == FRAME:
        _, direction = fixed_line(w.mech, body.guide)
        frame = local * direction
        if digits(frame.real / f) + digits(frame.imag / f) <= digits(u / f) + digits(v / f):
            u, v, axes = frame.real, frame.imag, w.w["frame_axes"]
    pair = f"{w.pair(u / f, v / f)} {w.units.names['length']}"
    return w.w["carries"].format(p=other, pair=pair, o=body.points[0], axes=axes)


def _contacts(w) -> list:
    out = []
    for r in w.mech.rolling.values():
        common = dict(disc=r.disc, c=r.center, r=w.length(r.radius))
        side = w.w["left"] if r.side > 0 else w.w["right"]
        if r.kind == "line":            # the contact's side: the centre is on the other
            side = w.w["left"] if r.side < 0 else w.w["right"]
            out.append(w.w["rolls_line"].format(dir=w.axis(r.direction), side=side, **common))
        elif r.kind == "circle":
            out.append(w.w["rolls_circle"].format(
                where=w.w["inside" if r.inside else "outside"], t=r.track,
                R=w.length(r.track_radius), **common))
        elif r.kind == "disc":
            out.append(w.w["rolls_disc"].format(
                where=w.w["inside" if r.inside else "outside"], other=r.other, t=r.track,
                R=w.length(r.track_radius), **common))
        elif r.kind == "cord":
            out.append(w.w["cord"].format(side=side, dir=w.axis(r.direction), p=r.point,
                                          **common))
        else:
            out.append(w.w["belt"].format(
                side=side, dir=w.axis(r.direction), other=r.other, t=r.track,
                R=w.length(r.track_radius),
                oside=w.w["left"] if r.other_side > 0 else w.w["right"], **common))
    return out


# --- driver and coordinates -------------------------------------------------------------------
def _what(w, d) -> str:
    key = {"angle": "angle_of", "length": "length_of", "x": "x_of", "y": "y_of"}[d.kind]
    return w.w[key].format(a=d.a, b=d.b)


def _coordinate_value(w, d) -> str:
    return w.angle(d.value) if d.kind == "angle" else w.length(d.value)


def _motion(w) -> list:
    mech = w.mech
    if mech.elements is not None:
        return _coordinates(w)
    d = mech.driver
    base = d.base
    rate_unit, rate_f = w.units.display(base, 1)
    acc_unit, acc_f = w.units.display(base, 2)
    text = w.w["driver"].format(what=_what(w, d), value=_coordinate_value(w, d))
    sense = ""
    if d.rate:
        words = ("ccw", "cw") if d.kind == "angle" else ("longer", "shorter") \
            if d.kind == "length" else (None, None)
        word = words[0] if d.rate > 0 else words[1]
        sense = f" ({w.w[word]})" if word else ""
    text += ", " + w.w["rate"].format(rate=f"{w.num(d.rate / rate_f)} {rate_unit}") + sense
    if d.accel or mech.report.get("acceleration") or mech.dynamics is not None:
        text += ", " + w.w["accel"].format(accel=f"{w.num(d.accel / acc_f)} {acc_unit}")
    return [text]


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
    return [_load(w, load) for load in w.mech.loads.values()]


def _load(w, load) -> str:
    mech = w.mech
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
    d = mech.driver
    what = w.w["q_torque"] if d.kind == "angle" else w.w["q_actuator"] \
        if d.kind == "length" and _actuator_of(mech, d) else w.w["q_force"]
    if load.value is None:
        return w.w["driver_load"].format(name=load.name, what=what)
    return w.w["driver_load_known"].format(
        name=load.name, what=what, value=w.amount(load.value, mech.load_unit_kind(load)))


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


# --- masses, friction, discs ------------------------------------------------------------------
def _dynamics(w) -> list:
    dyn = w.mech.dynamics
    if dyn is None:
        return []
    out = []
    if dyn.gravity:
        g = abs(dyn.gravity)
        direction = w.w["at_angle"].format(angle=w.angle(cmath.phase(dyn.gravity) %
                                                         (2 * math.pi)))
        if abs(dyn.gravity / g + 1j) < CLOSE:
            direction = f"{w.w['down']} ({direction})"
        out.append(w.w["gravity"].format(g=f"{w.num(g)} m/s^2", direction=direction))
    for mb in dyn.bodies.values():
        out.append(_mass_body(w, mb))
    out += [w.w["point_mass"].format(m=w.amount(m, "mass"), p=p) for p, m in dyn.masses.items()]
    out += [w.w["friction"].format(name=s, mu=w.num(mu)) for s, mu in dyn.friction.items()]
    for disc in dyn.discs.values():
        text = w.w["disc"].format(name=disc.name, c=disc.center, r=w.length(disc.radius),
                                  m=w.amount(disc.mass, "mass"),
                                  J=w.amount(disc.inertia, "inertia"),
                                  side=w.w["left"] if disc.side > 0 else w.w["right"])
        if disc.resistance:
            text += ", " + w.w["resistance"].format(u=w.length(disc.resistance))
        out.append(text)
    out += [w.w["pin"].format(p=p, rho=w.length(pin.radius)) for p, pin in dyn.pins.items()]
    return out


def _mass_body(w, mb) -> str:
    mech = w.mech
    body = mech.bodies[mb.body]
    if body.kind == "link":
        owner = w.w["of_link"].format(name=body.name)
    elif body.kind == "block":
        owner = w.w["of_slider"].format(name=body.name)
    else:
        name, half = body.name.rsplit(".", 1)
        owner = w.w["of_" + half].format(name=name)
    key = "mass" if mb.mass and mb.inertia else "mass_only" if mb.mass else "inertia_only"
    return w.w[key].format(body=owner, m=w.amount(mb.mass, "mass"),
                           J=w.amount(mb.inertia, "inertia"), where=_centre(w, body, mb.center))


def _centre(w, body, centre) -> str:
    """Where G is: a point of the body, or coordinates in the body's own frame."""
    f = w.units.factor("length")
    size = max([abs(z) for z in body.local.values()] + [f])
    for p, z in body.local.items():
        if abs(z - centre) <= CLOSE * size:
            return w.w["at_point"].format(p=p)
    x, y = w.num(centre.real / f), w.num(centre.imag / f)
    unit = w.units.names["length"]
    if body.kind == "link":
        a, b = body.points[0], body.points[1]
        return w.w["in_frame"].format(x=x, y=y, a=a, b=b).replace(")", f") {unit}", 1)
    if body.kind == "block":
        return w.w["in_block"].format(x=x, y=y, p=body.points[0]).replace(")", f") {unit}", 1)
    act = w.mech.actuators[body.name.rsplit(".", 1)[0]]
    return w.w["on_actuator"].format(x=x, y=y, p=body.points[0], a=act.a,
                                     b=act.b).replace(")", f") {unit}", 1)


# --- springs, dampers, excitation --------------------------------------------------------------
def _elements(w) -> list:
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


# --- what a quantity is -------------------------------------------------------------------------
def describe(mech, name: str, lang: str = "en") -> str:
    """What the reported quantity ``name`` is, in words ('' when it says nothing more than
    its name)."""
    base, order = split_rate(name, mech.quantities)
    quantity = mech.quantities.get(base)
    if quantity is None:
        return ""
    text = _DESCRIBE.get(quantity.kind, lambda w, q: "")(Writer(mech, lang), quantity)
    if order and text:
        rate = {"en": ("rate of", "second rate of"), "it": ("derivata di",
                                                              "derivata seconda di")}[lang]
        text = f"{rate[order - 1]} {text}"
    return text


def _limit_text(w, q) -> str:
    words = {"en": {"maximum": "maximum of {a}", "minimum": "minimum of {a}",
                    "at_maximum": "driver value at the maximum of {a}",
                    "at_minimum": "driver value at the minimum of {a}",
                    "stroke": "stroke of {a}", "time_ratio": "time ratio of the strokes of {a}",
                    "stroke_time": "time of the {c} stroke of {a}",
                    "span": " for q from {f} to {t}"},
             "it": {"maximum": "massimo di {a}", "minimum": "minimo di {a}",
                    "at_maximum": "valore del movente al massimo di {a}",
                    "at_minimum": "valore del movente al minimo di {a}",
                    "stroke": "corsa di {a}", "time_ratio": "rapporto dei tempi delle corse "
                    "di {a}", "stroke_time": "durata della corsa di {c} di {a}",
                    "span": " per q da {f} a {t}"}}[w.lang]
    component = {"working": {"en": "working", "it": "lavoro"},
                 "return": {"en": "return", "it": "ritorno"}}.get(q.component, {})
    text = words[q.kind].format(a=q.a, c=component.get(w.lang, q.component or ""))
    if q.span is not None:
        unit = w.units.display(w.mech.driver.base, 0)[0]
        f, t = q.span
        text += words["span"].format(f=f"{w.num(f)} {unit}", t=f"{w.num(t)} {unit}")
    return text


def _geometry(key_en, key_it):
    def text(w, q):
        template = key_en if w.lang == "en" else key_it
        return template.format(a=q.a, b=q.b, c=q.c, d=q.d, component=q.component or "",
                               elements=", ".join(q.elements), time=f"{w.num(q.time)} s")
    return text


_DESCRIBE = {
    "design": lambda w, q: unknown_role(w.mech, q.a, w.lang),
    "angle": _geometry("angle of {a}→{b} from +x", "angolo di {a}→{b} da +x"),
    "length": _geometry("length {a}{b}", "lunghezza {a}{b}"),
    "x": _geometry("x of {a}", "x di {a}"),
    "y": _geometry("y of {a}", "y di {a}"),
    "q": _geometry("the driver q", "il movente q"),
    "load": lambda w, q: _geometry(
        "{component} component of load {a}" if q.component else "load {a}",
        "componente {component} del carico {a}" if q.component else "carico {a}")(w, q),
    "speed": _geometry("speed of {a}", "velocità di {a}"),
    "acceleration": _geometry("acceleration of {a}", "accelerazione di {a}"),
    "tangential_acceleration": _geometry("tangential acceleration of {a}",
                                         "accelerazione tangenziale di {a}"),
    "normal_acceleration": _geometry("normal acceleration of {a}",
                                     "accelerazione normale di {a}"),
    "along": _geometry("component along {a}→{b}", "componente lungo {a}→{b}"),
    "normal_to": _geometry("component normal to {a}→{b}", "componente normale a {a}→{b}"),
    "relative": _geometry("{component} of {b} - {a}", "{component} di {b} - {a}"),
    "relative_speed": _geometry("speed of {b} relative to {a}", "velocità di {b} rispetto a {a}"),
    "relative_acceleration": _geometry("acceleration of {b} relative to {a}",
                                       "accelerazione di {b} rispetto a {a}"),
    "rotation": _geometry("angle of body {a}", "angolo del corpo {a}"),
    "between": _geometry("angle from {a}→{b} to {c}→{d}", "angolo da {a}→{b} a {c}→{d}"),
    "instant_centre": _geometry("{component} of the instant centre of {a}",
                                "{component} del centro di istantanea rotazione di {a}"),
    "instant_centre_distance": _geometry("distance of {b} from the instant centre of {a}",
                                         "distanza di {b} dal centro di istantanea rotazione "
                                         "di {a}"),
    "reaction": _geometry("force of the pin {a} on {b}, {component}",
                          "forza della cerniera {a} su {b}, {component}"),
    "slider_force": _geometry("force of the guide on slider {a}, {component}",
                              "forza della guida sul pattino {a}, {component}"),
    "velocity_ratio": _geometry("d{a}/dq", "d{a}/dq"),
    "least_speed": _geometry("least speed of the points of line {a}{b}",
                             "minima velocità dei punti della retta {a}{b}"),
    "least_speed_at": _geometry("distance from {a} of the point of line {a}{b} of least speed",
                                "distanza da {a} del punto della retta {a}{b} di minima "
                                "velocità"),
    "maximum": _limit_text, "minimum": _limit_text, "at_maximum": _limit_text,
    "at_minimum": _limit_text, "stroke": _limit_text, "time_ratio": _limit_text,
    "stroke_time": _limit_text,
    "natural_frequency": _geometry("natural frequency {a}", "frequenza propria {a}"),
    "damped_frequency": _geometry("damped frequency {a}", "frequenza smorzata {a}"),
    "damping_ratio": _geometry("damping ratio of mode {a}", "fattore di smorzamento del modo {a}"),
    "mode_shape": _geometry("{b} in mode {a} (first coordinate 1)",
                            "{b} nel modo {a} (prima coordinata 1)"),
    "mass_matrix": _geometry("mass matrix, entry {a}, {b}", "matrice di massa, termine {a}, {b}"),
    "stiffness_matrix": _geometry("stiffness matrix, entry {a}, {b}",
                                  "matrice di rigidezza, termine {a}, {b}"),
    "damping_matrix": _geometry("damping matrix, entry {a}, {b}",
                                "matrice di smorzamento, termine {a}, {b}"),
    "equilibrium": _geometry("{a} at the static equilibrium", "{a} all'equilibrio statico"),
    "spring_force": _geometry("force of spring {a} at equilibrium (tension positive)",
                              "forza della molla {a} all'equilibrio (positiva di trazione)"),
    "amplitude": _geometry("steady-state amplitude of {a}", "ampiezza a regime di {a}"),
    "phase": _geometry("steady-state phase of {a}", "fase a regime di {a}"),
    "transmissibility": _geometry("transmissibility of {a}", "trasmissibilità di {a}"),
    "force_amplitude": _geometry("amplitude of the force through {elements}",
                                 "ampiezza della forza trasmessa da {elements}"),
    "free_response": _geometry("{a} at t = {time} (free response)",
                               "{a} a t = {time} (risposta libera)"),
    "forcing_frequency": _geometry("forcing frequency", "frequenza della forzante"),
}
