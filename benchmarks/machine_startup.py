"""Machine dynamics: the start-up of a crank press to its regime, 100 turns of the crank.

The press of docs/examples/machine-press.yaml (crank 100 mm, rod 400 mm, a flywheel of
2 kg m^2, a linear motor 400 Nm at stall and 1500 rpm at no load, a punch of 3 kN over
0-120 deg, 5 Nm of bearing losses) is started from rest and integrated until the crank has
made 100 turns:

- by linkcli (runs.machine_motion.integrate: J*, dJ*/dq and the loads' levers from the
  kinematics, tabled once on periodic splines; solve_ivp cut at the punch's edges), timed
  with the table's construction and without it;
- by a hand-written solve_ivp of the same equation, J*(q) and dJ*/dq written out in closed
  form for this crank-slider, the punch switched on and off inside the right-hand side.

Both at the same relative tolerance; the table gives the processor time (CPU seconds of this
process, so that other processes on the machine do not count), the number of evaluations of
the equation, and the speed after 100 turns of each, with their relative difference.

    python benchmarks/machine_startup.py

Writes benchmarks/out/machine_startup.txt (the table, also printed).
"""
from __future__ import annotations

import math
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
OUT = os.path.join(HERE, "out")
FILE = os.path.join(ROOT, "docs", "examples", "machine-press.yaml")
TURNS = 100
R, L = 0.1, 0.4                     # crank, rod (m)
J_CRANK, M_ROD, J_ROD, M_RAM = 2.0, 3.0, 0.05, 5.0
STALL, NO_LOAD = 400.0, 1500 * math.pi / 30
PUNCH, WINDOW, BRAKE = 3000.0, (0.0, 2 * math.pi / 3), 5.0


def by_hand(q, w):
    """q'' of the press from its closed form: J* q'' + 1/2 dJ*/dq w^2 = Q."""
    s, c = math.sin(q), math.cos(q)
    sp = -R * s / L                                # sin(phi): the rod's angle, B on y = 0
    cp = math.sqrt(1 - sp * sp)
    p1 = -R * c / (L * cp)                         # phi'
    p2 = (R * s + L * sp * p1 * p1) / (L * cp)     # phi''
    g1 = complex(-R * s, R * c) + 1j * 0.5 * L * p1 * complex(cp, sp)
    g2 = complex(-R * c, -R * s) + (1j * 0.5 * L * p2 - 0.5 * L * p1 * p1) * complex(cp, sp)
    x1 = -R * s - L * sp * p1                      # x_B'
    x2 = -R * c - L * cp * p1 * p1 - L * sp * p2   # x_B''
    J = J_CRANK + M_ROD * abs(g1) ** 2 + J_ROD * p1 * p1 + M_RAM * x1 * x1
    dJ = 2 * (M_ROD * (g1.conjugate() * g2).real + J_ROD * p1 * p2 + M_RAM * x1 * x2)
    Q = STALL * (1 - w / NO_LOAD) - math.copysign(BRAKE, w) if w else STALL
    if (q % (2 * math.pi)) <= WINDOW[1]:
        Q += PUNCH * x1
    return (Q - 0.5 * dJ * w * w) / J


def hand_written(rtol):
    from scipy.integrate import solve_ivp
    count = [0]

    def rhs(t, y):
        count[0] += 1
        return (y[1], by_hand(y[0], y[1]))

    def turns(t, y):
        return y[0] - TURNS * 2 * math.pi
    turns.terminal = True
    start = time.process_time()
    sol = solve_ivp(rhs, (0, 60), (0.0, 0.0), method="DOP853", rtol=rtol, atol=rtol * 1e-2,
                    events=turns)
    seconds = time.process_time() - start
    return seconds, count[0], float(sol.y_events[0][0][1]), float(sol.t_events[0][0])


def by_linkcli(rtol):
    import linkcli
    from linkcli.answers.quantities.machine import machine_for
    from linkcli.runs import machine_motion as mm
    mech = linkcli.load(FILE).model
    event = ("turns", TURNS * 2 * math.pi)
    start = time.process_time()
    machine = machine_for(mech)
    table = mm.table_for(machine)
    tabled = time.process_time() - start
    start = time.process_time()
    motion = mm.integrate(mech, events=[event], rtol=rtol)
    seconds = time.process_time() - start
    t, _, w, _ = motion.event_state(event)
    return tabled, seconds, motion.steps, w, t, table.n, table.error


def main():
    os.makedirs(OUT, exist_ok=True)
    rows = [f"{'rtol':>7} {'linkcli table CPU s':>19} {'linkcli solve CPU s':>19} {'evals':>7} "
            f"{'hand-written CPU s':>18} {'evals':>7} {'w after 100 turns (rad/s)':>26} "
            f"{'relative difference':>20}"]
    for rtol in (1e-8, 1e-11):
        tabled, seconds, evals, w, t, n, error = by_linkcli(rtol)
        h_seconds, h_evals, h_w, h_t = hand_written(rtol)
        rows.append(f"{rtol:7.0e} {tabled:19.3f} {seconds:19.3f} {evals:7d} {h_seconds:18.3f} "
                    f"{h_evals:7d} {w:26.10f} {abs(w - h_w) / abs(h_w):20.2e}")
    rows.append(f"periodic splines: {n} points a turn, largest error at the midpoints "
                f"{error:.2e} of each column's scale; 100 turns take {t:.3f} s of motion")
    text = "\n".join(rows)
    print(text)
    with open(os.path.join(OUT, "machine_startup.txt"), "w", encoding="utf-8") as f:
        f.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
