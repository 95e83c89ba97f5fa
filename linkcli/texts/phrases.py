"""Every phrase of a problem's statement, in English and in Italian.

:data:`PHRASES` pairs each phrase's English and Italian wording, with the places of its
numbers and names (``{length}``, ``{name}``...); :data:`WORDS` is the same by language
(``WORDS["it"]["links"]`` is ``"Membri"``), the words a :class:`~linkcli.texts.amounts.Writer`
writes with.  The data lines (:mod:`linkcli.texts.bodies`, :mod:`linkcli.texts.loads`,
:mod:`linkcli.texts.masses`, :mod:`linkcli.texts.elements`) and the design question
(:mod:`linkcli.texts.data`) fill them in.
"""
from __future__ import annotations

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
    "belt_slip": (
        "the belt slips by {s} %: pulley {disc} turns at {kept} of the speed the belt gives it",
        "la cinghia slitta del {s} %: la puleggia {disc} gira a {kept} della velocità che la "
        "cinghia le darebbe",
    ),
    "gear": (
        "gear {name}: {z} teeth, {pitch} (pitch radius {r}), pressure angle {phi}, addendum "
        "{a}{internal}",
        "ruota {name}: {z} denti, {pitch} (raggio primitivo {r}), angolo di pressione {phi}, "
        "addendum {a}{internal}",
    ),
    "gear_internal": (", teeth cut inside", ", dentatura interna"),
    "driver": ("driver: {q} = {what} = {value}", "movente: {q} = {what} = {value}"),
    "rate": ("{q}' = {rate}", "{q}' = {rate}"),
    "accel": ("{q}'' = {accel}", "{q}'' = {accel}"),
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
    "motor_linear": (
        "motor {name} on {on}: M = {stall} (1 - n / {no_load}), n its speed "
        "(counter-clockwise positive)",
        "motore {name} su {on}: M = {stall} (1 - n / {no_load}), n la sua velocità "
        "(positiva antioraria)",
    ),
    "motor_table": (
        "motor {name} on {on}: the torque {points} against its speed, linear between them",
        "motore {name} su {on}: la coppia {points} in funzione della velocità, lineare tra "
        "i punti",
    ),
    "motor_expression": (
        "motor {name} on {on}: M = {text} ({units}; w its speed, q the driver, t the time)",
        "motore {name} su {on}: M = {text} ({units}; w la sua velocità, q il movente, t il "
        "tempo)",
    ),
    "brake": (
        "brake {name} on {on}: {value} against its turning",
        "freno {name} su {on}: {value} opposta alla rotazione",
    ),
    "window": ("{line}, while q is from {lo} to {hi}", "{line}, per q da {lo} a {hi}"),
    "driver_load": (
        "{name}: the generalised force on {q} ({what}), unknown",
        "{name}: la forza generalizzata su {q} ({what}), incognita",
    ),
    "driver_load_known": (
        "{name} = {value}: the generalised force on {q} ({what})",
        "{name} = {value}: la forza generalizzata su {q} ({what})",
    ),
    "q_torque": ("a torque, positive counter-clockwise", "una coppia, positiva antioraria"),
    "q_force": ("a force, positive where it makes {q} grow",
                "una forza, positiva se fa crescere {q}"),
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
    "initial_mode": (
        "released from rest in mode {mode}, {coordinate} = {value}",
        "rilasciato da fermo nel modo {mode}, {coordinate} = {value}",
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
