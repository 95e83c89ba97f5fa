"""The solving lines of a worked solution in Italian, and numbers with the Italian comma.

The lines that ``explain`` and the analysis blocks write (Grübler's count, the Assur
decomposition, the closure of each group, the statics, the power balance, the energies and
modes of a vibration, a design question's search) are made in English by the layers that
solve (kinematics, forces, answers), which know no language.  :func:`italian` rewrites one
such line in Italian by :data:`RULES`: each an English phrase (a regular expression whose
groups are the names and numbers it carries) and its Italian wording; names (points, bodies,
loads) and formulas pass through unchanged.  A phrase the table lacks stays English, and
``tests/test_language.py`` finds it in every shipped file's Italian worked solution.

:func:`comma` writes the numbers of a line with the Italian decimal separator: a decimal
point between two digits becomes a comma, and the two coordinates of a point or vector
'(x, y)' are then separated by a semicolon, as the data lines write them
(:mod:`linkcli.texts.amounts`).  Formulas in MathML or LaTeX (``--symbolic``) keep the
point: they are the notation a reader copies into a computer algebra system.
"""
from __future__ import annotations

import re

_NUM = r"-?[0-9][0-9.]*(?:e[-+]?[0-9]+)?"
_PAIR = re.compile(rf"\(\s*({_NUM}), ({_NUM})\)")
_POINT = re.compile(r"(?<=[0-9])\.(?=[0-9])")


def comma(text: str) -> str:
    """``text`` with a decimal comma between digits, and '(x; y)' for a pair of numbers."""
    return _POINT.sub(",", _PAIR.sub(r"(\1; \2)", text))


#: English phrase (regular expression) -> Italian, applied in this order to each line
RULES = [(re.compile(pattern), italian) for pattern, italian in (
    # the cautions of the figure check, written on the line of the group they concern
    (r": warning: the solved position is far from the figure \((\S+) of the mechanism's size "
     r"is (.+?)\): (.+); check the lengths, the shapes and the driver's points",
     r": attenzione: la posizione risolta è lontana dalla figura (il \1 della dimensione del "
     r"meccanismo è \2): \3; controllare le lunghezze, le forme e i punti del movente"),
    (r"(?<=meccanismo è )(.+?\): )(.+)(?=; controllare)",
     lambda m: m.group(1) + m.group(2).replace(" by ", " di ")),
    (r": warning: the figure's (\S+) is nearly as far from both assemblies of (.+) "
     r"\((\S+) and (\S+ \S+)\): the branch may not be the one drawn",
     r": attenzione: il punto \1 della figura è quasi ugualmente lontano dai due assemblaggi di "
     r"\2 (\3 e \4): il ramo potrebbe non essere quello disegnato"),
    (r": warning: ", ": attenzione: "),
    (r": error: ", ": errore: "),
    # Grübler's count
    (r"Grübler's count \(planar\)", "Conteggio di Grübler (moto piano)"),
    (r"\bbodies m = ", "corpi m = "),
    (r"\brevolute pairs R = ", "coppie rotoidali R = "),
    (r"\bprismatic pairs P = ", "coppie prismatiche P = "),
    (r"\bhigher pairs H = ", "coppie superiori H = "),
    (r"(= \d+): none$", r"\1: nessuna"),
    (r", rolling\)", ", rotolamento)"),
    (r", cord\)", ", fune)"),
    (r"\.cylinder\b", ".cilindro"),
    (r"\.rod\b", ".stelo"),
    (r"(?<![A-Za-z])frame\b", "telaio"),
    # Newton-Raphson
    (r"^Newton-Raphson on the constraint equations \(--method newton\), no decomposition$",
     "Newton-Raphson sulle equazioni di vincolo (--method newton), senza scomposizione"),
    (r"\bunknowns: x and y of the (\d+) moving points ",
     r"incognite: x e y dei \1 punti mobili "),
    (r"\bequations g\(x, q\) = 0, all (\d+) solved together at each q:",
     r"equazioni g(x, q) = 0, tutte le \1 risolte insieme a ogni q:"),
    (r"\bpositions: from the figure's points at the file's q \(its branch as drawn\), "
     r"continued along q in halved steps without jumping branches",
     "posizioni: dai punti della figura al q del file (il ramo disegnato), proseguite "
     "lungo q a passi dimezzati senza saltare di ramo"),
    (r"\bvelocities and accelerations: J xdot = -dg/dq qdot, J xddot = rhs, with J = dg/dx "
     r"the Jacobian", "velocità e accelerazioni: J xdot = -dg/dq qdot, J xddot = termine "
     "noto, con J = dg/dx lo jacobiano"),
    (r"\(closed form: not available: (.*)\)$", r"(forma chiusa: non disponibile: \1)"),
    (r"\bthe structure does not decompose into dyads \(([^)]*)\): points (.*) are not reached",
     r"la struttura non si scompone in diadi (\1): i punti \2 non sono raggiunti"),
    (r"\(it may hold a class-III group \(triad\): solve it with --method newton, or check the "
     r"links around them\)", "(può contenere un gruppo di classe III (triade): risolverla con "
     "--method newton, o controllare i membri attorno a quei punti)"),
    (r"\(closed form: (\d+) groups? solved in order, as 'linkcli explain' without "
     r"--method lists them\)",
     r"(forma chiusa: \1 gruppi risolti in ordine, come li elenca 'linkcli explain' senza "
     r"--method)"),
    (r"(\S+) along q$", r"\1 lungo q"),
    (r": (\S+) along$", r": \1 lungo"),
    (r": (\S+) side$", r": \1 lato"),
    # the decomposition and the solving order
    (r"^Decomposition and solving order$", "Scomposizione e ordine di soluzione"),
    (r"\bcoordinate (\S+) = ", r"coordinata \1 = "),
    (r"\bdriver q = ", "movente q = "),
    (r"\bdriver: slider (\S+), ", r"movente: pattino \1, "),
    (r"\bdriver: (\S+) \(crank\), ", r"movente: \1 (manovella), "),
    (r"\bdriver: ", "movente: "),
    (r"\(the pay-out of cord (\S+)\)", r"(lo svolgimento della fune \1)"),
    (r"\bangle of ", "angolo di "),
    (r"\blength (?=[A-Za-z_])", "lunghezza "),
    (r"\b([xy]) of ", r"\1 di "),
    (r"\bdyad RPR: (\S+) \(slot off its pivot\) from ",
     r"diade RPR: \1 (guida fuori dal suo perno) da "),
    (r"\bdyad RPR: actuator (\S+) between known points ",
     r"diade RPR: attuatore \1 tra i punti noti "),
    (r"\bdyad (\w+): (\S+) from ", r"diade \1: \2 da "),
    (r"\(([^()]*), length\)", r"(\1, lunghezza)"),
    (r"\b(\S+) on the guide ", r"\1 sulla guida "),
    (r"\bguid[ae] through: (\[[^\]]*\]|[^,]+), angle: (\S+)", r"guida per \1 ad angolo \2"),
    (r"\bguid[ae] along: (\[[^\]]*\]), offset: (\S+)", r"guida lungo \1, scostata di \2"),
    (r"\bguid[ae] along: ", "guida lungo "),
    (r"\bguide (?=\S*:)", "guida "),
    (r"(?:(?<= da )|(?<= and ))contacts (?=\S)", "contatti "),     # a dyad's side
    (r"(?:(?<= da )|(?<= and ))contact (?=\S)", "contatto "),
    (r" \(driven\)", " (comandata dal movente)"),
    (r"\(branch ([+-]) as in the figure\)", r"(ramo \1 come in figura)"),
    (r"\(branch ([+-]) not determined by the figure\)",
     r"(ramo \1 non determinato dalla figura)"),
    (r"^(\s*)then ", r"\1poi "),
    (r"\bplace (\S+) on (\S+) \(rigid\)", r"\1 posto su \2 (rigido)"),
    (r"\bdraw the line through (\S+) parallel to the slot of (\S+)",
     r"retta per \1 parallela alla guida di \2"),
    (r"\b(\S+) turned by (\S+) \(", r"\1 ruotato da \2 ("),
    (r"\(rolling on a fixed line\)", "(rotolamento su una retta fissa)"),
    (r"\(rolling on a line of (\S+)\)", r"(rotolamento su una retta di \1)"),
    (r"\(the cord to (\S+)\)", r"(la fune fino a \1)"),
    (r"\(the belt from disc (\S+)\)", r"(la cinghia dal disco \1)"),
    (r"\(rolling inside the circle about (\S+)\)",
     r"(rotolamento dentro la circonferenza di centro \1)"),
    (r"\(rolling outside the circle about (\S+)\)",
     r"(rotolamento fuori dalla circonferenza di centro \1)"),
    (r"\(rolling inside disc (\S+)\)", r"(rotolamento dentro il disco \1)"),
    (r"\(rolling outside disc (\S+)\)", r"(rotolamento fuori dal disco \1)"),
    (r"\(sliders on turning guides add Coriolis terms to the accelerations\)",
     "(i pattini su guide che ruotano aggiungono i termini di Coriolis alle accelerazioni)"),
    (r"^(\s*)(\S+) is reached through (.+) \(Newton's method on the angle; the decomposition "
     r"places the substitute; another takes over where it stops\)",
     r"\1\2 si raggiunge attraverso \3 (metodo di Newton sull'angolo; la scomposizione "
     r"colloca il sostituto; un altro subentra dove si ferma)"),
    # statics
    (r"^Statics by virtual work: sum of load powers = 0$",
     "Statica con i lavori virtuali: somma delle potenze dei carichi = 0"),
    (r"\(no loads\)", "(nessun carico)"),
    (r"^  motion of (\S+) alone: ", r"  moto del solo \1: "),
    # power balance (dynamics)
    (r"^Power balance \(inverse dynamics\): ", "Bilancio delle potenze (dinamica inversa): "),
    (r"\bno unknown load in this file$", "nessun carico incognito in questo file"),
    (r"\bat the file's position: ", "nella posizione del file: "),
    (r"\(the unknown load\)", "(il carico incognito)"),
    (r"\brolling disc (\S+): ", r"disco \1 che rotola: "),
    (r"\bfriction circle at (\S+): (.*), (\S+) turning on the pin fixed in (\S+)$",
     r"circolo d'attrito in \1: \2, \3 che ruota sul perno solidale a \4"),
    (r"\brolling resistance of (\S+): ", r"attrito volvente di \1: "),
    # vibrations
    (r"^Energies \(SI units; s is each element's measure, s0 its free value\)$",
     "Energie (unità SI; s è la misura di ogni elemento, s0 il suo valore a riposo)"),
    (r"\(work of the constant load\)", "(lavoro del carico costante)"),
    (r"\) along \(", ") lungo ("),
    (r"^Lagrange's equations, one per coordinate q_i:$",
     "Equazioni di Lagrange, una per ogni coordinata q_i:"),
    (r"^  i\.e\. ", "  cioè "),
    (r"^Static equilibrium \(the figure\)$", "Equilibrio statico (la figura)"),
    (r"^Static equilibrium \(solved from the figure\)$",
     "Equilibrio statico (risolto a partire dalla figura)"),
    (r" \(free\)$", " (libera)"),
    (r" \(imposed\)$", " (imposta)"),
    (r"\bspring (\S+): force N = ", r"molla \1: forza N = "),
    (r" \(chosen so that the figure is an equilibrium\)",
     " (scelta in modo che la figura sia di equilibrio)"),
    (r"\bresidual \|Q\| = (\S+) of the load scale", r"residuo |Q| = \1 della scala dei carichi"),
    (r"^Linearised about the equilibrium: ", "Linearizzate attorno all'equilibrio: "),
    (r"\bone degree of freedom: (.*) \(reduced mass or inertia, stiffness, damping\)",
     r"un grado di libertà: \1 (massa o inerzia ridotta, rigidezza, smorzamento)"),
    (r"^Natural frequencies and modes \((.*); shapes normalised by (.*)\)$",
     r"Frequenze proprie e modi (\1; forme normalizzate con \2)"),
    (r"^  mode (\d+): ", r"  modo \1: "),
    (r"; shape ", "; forma "),
    (r" \((\S+) does not move: scaled to the largest\)",
     r" (\1 non si muove: forma scalata sulla componente maggiore)"),
    (r"^  damped (\d+): ", r"  smorzato \1: "),
    (r"\[(\S+) (\S+) at (\S+) (\S+)\]", r"[\1 \2 a \3 \4]"),
    (r"\((SI); reached\)", r"(\1; raggiunto)"),
    (r"\((SI); approached\)", r"(\1; approssimato)"),
    (r"^Largest values in the free vibration \(linear superposition of the modes from "
     r"'initial:'\):$", "Valori massimi nella vibrazione libera (sovrapposizione lineare dei "
     "modi a partire da 'initial:'):"),
    (r"^  undamped: (.*), largest (.*) \(reached when the modes come into phase; approached "
     r"for incommensurate frequencies\)$",
     r"  non smorzata: \1, massimo \2 (raggiunto quando i modi vanno in fase; approssimato "
     r"per frequenze incommensurabili)"),
    (r"^  damped: the extremes of (.*) where (.*), until the modes' envelope falls below the "
     r"largest found$", r"  smorzata: gli estremi di \1 dove \2, finché l'inviluppo dei modi "
     r"scende sotto il massimo trovato"),
    (r"^Peaks of the frequency response: (.*) by Brent's method between samples where its "
     r"sign changes$", r"Picchi della risposta in frequenza: \1 con il metodo di Brent tra i "
     r"campioni dove cambia segno"),
    (r"\(damping couples the modes: each pair of roots is the undamped mode its motion is "
     r"most made of; shares (.*)\)$", r"(lo smorzamento accoppia i modi: ogni coppia di "
     r"radici è il modo non smorzato di cui il suo moto è fatto di più; quote \1)"),
    (r"\bthe static equilibrium is unstable \(a (maximum|saddle point) of the potential "
     r"energy\): K has the negative eigenvalue (.*) \(mode mostly along (\S+)\), so there is "
     r"no natural frequency", lambda m: "l'equilibrio statico è instabile (un " + (
         "massimo" if m.group(1) == "maximum" else "punto di sella") + " dell'energia "
     "potenziale): K ha l'autovalore negativo " + m.group(2) + " (modo soprattutto lungo "
     + m.group(3) + "), quindi non c'è frequenza propria"),
    # a design question
    (r"^Design \(find\): the unknowns' values that give the targets$",
     "Progetto (find): i valori delle incognite che danno i valori richiesti"),
    (r"^  unknown (\S+) in ", r"  incognita \1 in "),
    (r"^  target ", "  valore richiesto "),
    (r"\bscan and Brent's method: (\S+) evaluations of the file",
     r"scansione e metodo di Brent: \1 valutazioni del file"),
    (r"^  solution: ", "  soluzione: "),
    (r"^  unknown (\S+) from ", r"  incognita \1 da "),
    (r"\bleast squares within the intervals: (\S+) evaluations of the file",
     r"minimi quadrati negli intervalli: \1 valutazioni del file"),
    (r"\bPowell's hybrid method from the start values: (\S+) evaluations of the file",
     r"metodo ibrido di Powell dai valori iniziali: \1 valutazioni del file"),
    (r"^  roots: (.*); chosen by ", r"  radici: \1; scelta con "),
    (r"^  no answer at the (\d+) samples from (.+) to (.+?): ",
     r"  nessuna risposta nei \1 campioni da \2 a \3: "),
    (r"\bcannot assemble (.+) at (q = .+?): the links fall short by ",
     r"non si assembla \1 a \2: i membri non arrivano per "),
    (r"\bW_motor\b", "W_motrice"),
    (r"\bW_resistant\b", "W_resistente"),
    (r"\bW_lost\b", "W_perduta"),
    (r" and ", " e "),
)]


def italian(line: str) -> str:
    """One solving line (English, as ``explain`` and the analysis blocks write it) in Italian,
    its numbers with the decimal comma."""
    for pattern, text in RULES:
        line = pattern.sub(text, line)
    return comma(line)
