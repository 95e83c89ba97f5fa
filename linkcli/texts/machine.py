"""A machine's data and questions in words: the periodic regime asked (its mean speed, a
turning-moment diagram's areas and scales, the flywheel's coefficient of fluctuation, the
turns of a cycle) and what each answer of the motion is (a speed at a time, the turns to
reach a speed, the reduced inertia ...), with the numbers the solver reads, in the file's
units.  Speeds and angles are the driver's: counter-clockwise positive for an angle.
"""
from __future__ import annotations

import math

WORDS = {
    "en": {
        "mean_speed": "mean speed of the driver: {speed}",
        "areas": "turning-moment diagram: the areas between the curve and its mean line, in "
                 "order (positive above): {areas}; one unit of the drawing's length is "
                 "{torque} of torque and {angle} of the driver's angle",
        "fluctuation": "the flywheel keeps the coefficient of fluctuation of the speed "
                       "(w_max - w_min) / w_mean = {delta}",
        "turns": "a cycle is {turns} turns of the driver",
        "speed": "speed of the driver", "acceleration": "acceleration of the driver",
        "turned": "motion of the driver from the start", "turns_": "turns of the driver",
        "time_": "time from the start",
        "at_time": "{what} at t = {at}", "at_speed": "{what} when its speed reaches {at}",
        "at_turned": "{what} after a motion of {at}", "at_turns": "{what} after {at} turns",
        "at_stop": "{what} when it stops",
        "reduced_inertia": "reduced inertia J* at the driver",
        "reduced_inertia_slope": "derivative dJ*/dq of the reduced inertia",
        "reduced_torque": "reduced torque Q of every load at the driver",
        "regime": "periodic regime: {what}", "flywheel": "flywheel inertia ({how})",
        "flywheel_mass": "flywheel mass at a radius of gyration of {radius} ({how})",
    },
    "it": {
        "mean_speed": "velocità media del movente: {speed}",
        "areas": "diagramma del momento motore: aree tra la curva e la sua retta media, in "
                 "ordine (positive sopra): {areas}; un'unità di lunghezza del disegno vale "
                 "{torque} di coppia e {angle} di angolo del movente",
        "fluctuation": "il volano mantiene il coefficiente di irregolarità della velocità "
                       "(w_max - w_min) / w_media = {delta}",
        "turns": "un ciclo è di {turns} giri del movente",
        "speed": "velocità del movente", "acceleration": "accelerazione del movente",
        "turned": "spostamento del movente dall'avvio", "turns_": "giri del movente",
        "time_": "tempo dall'avvio",
        "at_time": "{what} all'istante t = {at}",
        "at_speed": "{what} quando la sua velocità raggiunge {at}",
        "at_turned": "{what} dopo uno spostamento di {at}", "at_turns": "{what} dopo {at} giri",
        "at_stop": "{what} all'arresto",
        "reduced_inertia": "momento d'inerzia ridotto J* al movente",
        "reduced_inertia_slope": "derivata dJ*/dq del momento d'inerzia ridotto",
        "reduced_torque": "coppia ridotta Q di tutti i carichi al movente",
        "regime": "regime periodico: {what}", "flywheel": "momento d'inerzia del volano ({how})",
        "flywheel_mass": "massa del volano a un raggio d'inerzia di {radius} ({how})",
    },
}


def regime_lines(w) -> list:
    """The regime's data lines (none when the file asks no regime)."""
    motion = getattr(w.mech, "motion", None)
    spec = getattr(motion, "extra", {}).get("regime") if motion is not None else None
    if spec is None:
        return []
    words, lines = WORDS[w.lang], []
    if spec.mean_speed is not None:
        lines.append(words["mean_speed"].format(speed=_speed(w, spec.mean_speed)))
    if spec.areas:
        torque, angle = spec.scale
        lines.append(words["areas"].format(areas=", ".join(w.num(a) for a in spec.areas),
                                           torque=w.amount(torque, "torque"),
                                           angle=w.angle(angle)))
    if spec.fluctuation is not None:
        lines.append(words["fluctuation"].format(delta=w.num(spec.fluctuation)))
    if spec.turns != 1:
        lines.append(words["turns"].format(turns=w.num(spec.turns)))
    return lines


def describe_machine(w, q) -> str:
    """What a machine answer is, with the event's number in the file's units."""
    words = WORDS[w.lang]
    if q.kind in ("reduced_inertia", "reduced_inertia_slope", "reduced_torque"):
        return words[q.kind]
    if q.kind == "regime":
        return words["regime"].format(what=q.a.replace("_", " "))
    if q.kind == "flywheel":
        if getattr(q, "radius", None) is not None:
            return words["flywheel_mass"].format(radius=w.length(q.radius), how=q.a)
        return words["flywheel"].format(how=q.a)
    what = words.get(q.a) or words[q.a + "_"]
    if q.b == "stop":
        return words["at_stop"].format(what=what)
    at = {"time": lambda t: f"{w.num(t / w.units.factor('time'))} {w.units.names['time']}",
          "speed": lambda v: _speed(w, v),
          "turned": lambda d: w.angle(d) if w.mech.driver.base == "angle" else w.length(d),
          "turns": lambda n: w.num(n / (2 * math.pi))}[q.b](q.time)
    return words["at_" + q.b].format(what=what, at=at)


def _speed(w, si: float) -> str:
    unit, factor = w.units.display(w.mech.driver.base, 1)
    return f"{w.num(si / factor)} {unit}"
