"""What each reported quantity is, in words, for the answer table.

:func:`describe` says it from the quantity's kind and its points, bodies or elements
('angle of O→A from +x', 'force of the pin A on AB, x'), in English or Italian; a rate
adds 'rate of', an extreme over the driver's range its span, a design target what its
unknown is (:func:`linkcli.texts.unknowns.unknown_role`).
"""
from __future__ import annotations

from linkcli.model.mechanism import split_rate
from linkcli.texts.amounts import Writer
from linkcli.texts.machine import describe_machine
from linkcli.texts.unknowns import unknown_role


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
    **{kind: describe_machine for kind in ("motion", "reduced_inertia", "reduced_inertia_slope",
                                           "reduced_torque", "regime", "flywheel")},
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
    "centre_distance": _geometry("centre distance of gears {a} and {b}",
                                 "interasse delle ruote {a} e {b}"),
    "contact_ratio": _geometry("contact ratio of gears {a} and {b}",
                               "rapporto di condotta delle ruote {a} e {b}"),
    "min_teeth": lambda w, q: _geometry(
        "fewest teeth of {a} without interference with {b}" if q.b else
        "fewest teeth of {a} without interference with a rack",
        "minimo numero di denti di {a} senza interferenza con {b}" if q.b else
        "minimo numero di denti di {a} senza interferenza con una dentiera")(w, q),
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
