"""Speed and accuracy of the periodic regime found directly (run by `make bench`).

A crank-slider's reduced equation J*(q) q'' + 1/2 dJ*/dq q'^2 = Q(q, q') driven by a linear
motor (tests/regime_cases.py): its regime found by shooting in q (linkcli.forces.regime),
against a hand-written solve_ivp of the same equation in time (and the crank press of
docs/examples/machine-press.yaml from its file: loaded, read over a cycle, shot), from 0.8 of the balance
speed, integrated until the speeds of two cycles agree to 1e-9 (the transient is then
over); the same with a constant driving torque by the energy method (against one cycle
integrated in time from the orbit's speed at q0); the flywheel for delta = 0.01, books'
and exact, the exact one checked by integrating the transient with it.  Best of several
runs; the machine is shared, so times are upper bounds.

    python benchmarks/regime.py

Writes benchmarks/out/regime.{txt,json}.
"""
from __future__ import annotations

import json
import math
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, os.path.join(ROOT, "tests"))

from linkcli.forces import flywheel as fw  # noqa: E402
from linkcli.forces import regime as rg  # noqa: E402
from regime_cases import slider_crank  # noqa: E402

OUT = os.path.join(HERE, "out")


def best(func, repeat=5):
    """(least wall time, least processor time, the result) over ``repeat`` runs: on a shared
    machine the processor time is the cost, the wall time an upper bound."""
    times, cpu = [], []
    for _ in range(repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        out = func()
        times.append(time.perf_counter() - start)
        cpu.append(time.process_time() - start_cpu)
    return min(times), min(cpu), out


def transient(cycle, w0, settle=1e-9, most=400):
    """solve_ivp of the equation in time, one cycle at a time, until the largest and
    smallest speeds of a cycle repeat to ``settle``: (cycles, max, min, average)."""
    from scipy.integrate import solve_ivp

    def rhs(t, y):
        q, w = y
        qa = np.array([q])
        Q = cycle.Q(qa, np.array([w]))[0]
        return [w, (Q - 0.5 * cycle.dJ(qa)[0] * w * w) / cycle.J(qa)[0]]

    y, t, last = [0.0, w0], 0.0, None
    for n in range(1, most + 1):
        def turned(t, y, n=n):
            return y[0] - n * cycle.period
        turned.terminal = True
        sol = solve_ivp(rhs, (t, t + 1e3), y, rtol=1e-10, atol=1e-10, method="DOP853",
                        events=turned, dense_output=True)
        t1 = sol.t_events[0][0]
        w = sol.sol(np.linspace(t, t1, 4001))[1]
        now = (w.max(), w.min(), cycle.period / (t1 - t))
        if last is not None and abs(now[0] - last[0]) <= settle * now[0] \
                and abs(now[1] - last[1]) <= settle * now[0]:
            return n, now
        last, y, t = now, sol.y_events[0][0], t1
    return most, now


def press_text():
    """docs/examples/machine-press.yaml (a crank press driven by an induction motor, a punch
    over a third of the turn) asked for its regime and its flywheel."""
    text = open(os.path.join(ROOT, "docs", "examples", "machine-press.yaml")).read()
    text = text.replace("motion: {until: 20}", "motion:\n  until: 20\n  flywheel: {fluctuation: 0.02}")
    head = text[:text.index("quantities:")]
    return head + ("quantities:\n  wm: {regime: mean_speed}\n  delta: {regime: fluctuation}\n"
                   "  Ie: {flywheel: exact}\nreport:\n  motion: [wm, delta, Ie]\n")


def from_file():
    """The regime of the press from its file: loaded, its machine read over a cycle, shot."""
    import linkcli
    from linkcli.runs import machine_regime

    return machine_regime.solved(linkcli.loads(press_text(), None, "press.yaml").model)


def main():
    os.makedirs(OUT, exist_ok=True)
    rows = {}
    t_file, c_file, reg_f = best(from_file)
    rows["from the file"] = {"direct_s": t_file, "direct_cpu_s": c_file, "shots": reg_f.shots,
                             "delta": reg_f.fluctuation}
    cyc = slider_crank(flywheel=0.3)
    t_direct, c_direct, reg = best(lambda: rg.regime(cyc))
    t_ivp, c_ivp, (cycles, (w_max, w_min, w_mean)) = best(
        lambda: transient(cyc, 0.8 * rg.balance_speed(cyc)), repeat=1)
    rows["shooting"] = {
        "direct_s": t_direct, "direct_cpu_s": c_direct, "transient_s": t_ivp,
        "transient_cpu_s": c_ivp, "transient_cycles": cycles,
        "shots": reg.shots, "multiplier": reg.multiplier,
        "delta": reg.fluctuation, "delta_transient": 2 * (w_max - w_min) / (w_max + w_min),
        "rel_err_max_speed": abs(reg.max_speed / w_max - 1),
        "rel_err_min_speed": abs(reg.min_speed / w_min - 1),
        "rel_err_average_speed": abs(reg.average_speed / w_mean - 1)}
    flat = slider_crank(motor=False, flywheel=0.3)
    t_energy, c_energy, reg_e = best(lambda: rg.regime(flat, 40.0))
    rows["energy method"] = {"direct_s": t_energy, "direct_cpu_s": c_energy,
                             "delta": reg_e.fluctuation}
    t_fly, c_fly, fly = best(lambda: fw.flywheel(slider_crank(), 0.01), repeat=2)
    _, _, (cycles_f, (a, b, m)) = best(
        lambda: transient(slider_crank(flywheel=fly.exact), 0.8 * fly.regime.mean_speed),
        repeat=1)
    rows["flywheel delta 0.01"] = {
        "direct_s": t_fly, "direct_cpu_s": c_fly, "books": fly.approximate, "exact": fly.exact,
        "delta_transient_with_exact": 2 * (a - b) / (a + b), "transient_cycles": cycles_f}
    text = ["periodic regime of a crank-slider (reduced equation), best of runs; "
            "processor time (wall time)",
            f"{'case':22s} {'direct [s]':>16s} {'transient [s]':>16s} {'cycles':>7s}  accuracy"]
    s = rows["shooting"]
    text.append(f"{'shooting (motor)':22s} {_pair(s, 'direct'):>16s} {_pair(s, 'transient'):>16s} "
                f"{s['transient_cycles']:7d}  speeds vs transient: max {s['rel_err_max_speed']:.1e},"
                f" min {s['rel_err_min_speed']:.1e}, average {s['rel_err_average_speed']:.1e}")
    text.append(f"{'energy method':22s} {_pair(rows['energy method'], 'direct'):>16s}")
    r = rows["from the file"]
    text.append(f"{'press file (shooting)':22s} {_pair(r, 'direct'):>16s} {'':16s} {'':7s}  "
                f"loaded, read over a cycle and shot ({r['shots']} shots), delta "
                f"{r['delta']:.6g}")
    f = rows["flywheel delta 0.01"]
    text.append(f"{'flywheel (exact)':22s} {_pair(f, 'direct'):>16s} {'':16s} "
                f"{f['transient_cycles']:7d}  books {f['books']:.6g}, exact {f['exact']:.6g} "
                f"kg m^2; delta of the transient with it {f['delta_transient_with_exact']:.6g}")
    with open(os.path.join(OUT, "regime.json"), "w") as fh:
        json.dump(rows, fh, indent=2)
    with open(os.path.join(OUT, "regime.txt"), "w") as fh:
        fh.write("\n".join(text) + "\n")
    print("\n".join(text))


def _pair(row, what):
    return f"{row[what + '_cpu_s']:.3f} ({row[what + '_s']:.3f})"


if __name__ == "__main__":
    main()
