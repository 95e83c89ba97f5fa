"""Speed and accuracy of the vibration analysis (run by `make bench`).

For two-coordinate problems shipped in mechanisms/ it times, best of several
runs: the equilibrium and linearisation (jets, M, K, R), the natural
frequencies, and a 10^4-point frequency response; and the error of the
frequencies against the closed form of the 18 Sep 2001 double pendulum,
omega^2 = 2k/m + (2 -+ sqrt 2) g / L.

    python benchmarks/vibration.py

Writes benchmarks/out/vibration.{txt,json}.
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

import linkcli  # noqa: E402
from linkcli.forces import vibration as vib  # noqa: E402
from linkcli.forces.lagrange import Lagrangian  # noqa: E402
from linkcli.kinematics.solvers import solver_for  # noqa: E402

OUT = os.path.join(HERE, "out")
CASES = ["polimi-2001-09-18-vibration.yaml", "polimi-2001-01-24-vibration.yaml",
         "polimi-2001-07-17-vibration.yaml"]


def best(func, repeat=7):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        out = func()
        times.append(time.perf_counter() - start)
    return min(times), out


def measure(name):
    path = os.path.join(ROOT, "mechanisms", name)
    mech = linkcli.load(path).model

    def linearise():
        return vib.linearise(Lagrangian(mech, solver_for(mech)))

    t_lin, lin = best(linearise)
    t_modes, modes = best(lambda: vib.modes(lin))
    omega = np.linspace(0.1, 3 * float(modes.omega[-1]), 10_000)
    if lin.forces.any() or lin.supports.any():
        t_frf, _ = best(lambda: vib.response(lin, omega + 1e-3), repeat=5)
    else:
        lin.forces = np.ones(len(lin.free), dtype=complex)     # unit force on each coordinate
        t_frf, _ = best(lambda: vib.response(lin, omega + 1e-3), repeat=5)
    return {"file": name, "coordinates": len(mech.coordinates), "linearise_ms": 1e3 * t_lin,
            "modes_ms": 1e3 * t_modes, "frf_1e4_ms": 1e3 * t_frf,
            "frf_us_per_point": 1e6 * t_frf / omega.size,
            "omega": [float(w) for w in modes.omega]}


def accuracy():
    path = os.path.join(ROOT, "mechanisms", "polimi-2001-09-18-vibration.yaml")
    mech = linkcli.load(path).model
    lin = vib.linearise(Lagrangian(mech, solver_for(mech)))
    got = vib.modes(lin).omega
    m, L, k, g = 2.0, 0.5, 100.0, 9.81
    exact = np.sqrt(2 * k / m + (2 - np.array([1, -1]) * math.sqrt(2)) * g / L)
    return float(np.max(np.abs(got - exact) / exact))


def main():
    rows = [measure(name) for name in CASES]
    err = accuracy()
    lines = ["Vibration analysis: best of 7 runs (frequency response: best of 5)", "",
             f"{'file':<36} {'n':>2} {'linearise ms':>13} {'modes ms':>9} "
             f"{'FRF 1e4 ms':>11} {'us/point':>9}"]
    for r in rows:
        lines.append(f"{r['file']:<36} {r['coordinates']:>2} {r['linearise_ms']:>13.2f} "
                     f"{r['modes_ms']:>9.3f} {r['frf_1e4_ms']:>11.2f} "
                     f"{r['frf_us_per_point']:>9.3f}")
    lines += ["", f"double pendulum (18 Sep 2001): largest relative error of the natural "
              f"frequencies against the closed form: {err:.1e}"]
    text = "\n".join(lines)
    print(text)
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, "vibration.txt"), "w") as f:
        f.write(text + "\n")
    with open(os.path.join(OUT, "vibration.json"), "w") as f:
        json.dump({"rows": rows, "closed_form_error": err}, f, indent=2)


if __name__ == "__main__":
    main()
