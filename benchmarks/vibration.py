"""Speed and accuracy of the vibration analysis (run by `make bench`).

For two-coordinate problems shipped in mechanisms/ it times, best of several
runs: the equilibrium and linearisation (jets, M, K, R), the natural
frequencies, and a 10^4-point frequency response; and the error of the
frequencies against the closed form of the 18 Sep 2001 double pendulum,
omega^2 = 2k/m + (2 -+ sqrt 2) g / L.

Then the size of problem it takes: `linkcli solve` in a fresh process (wall time, peak
resident memory) of a chain of n masses between two walls (each point moves with one
coordinate) and of n pendulums hanging end to end (the last point moves with all n), with
their lowest and highest frequencies against the closed forms (tests/vibration_cases.py).

Where the time went (cProfile, chain of 50 masses, before): the second derivatives were
n (n + 1) / 2 rate solves of the mechanism, one Python pass each (2550 passes, 6 s), each
point's Hessian a dict of n^2 entries read one by one by every spring and mass (1.0 M
calls, 9 s), and M, K assembled in Python loops over i and j per element (5.5 s): O(n^3)
Python steps and O(n^3) stored numbers (2.6 GB at n = 200).  Now the rates for every
unit rate, and for every pair in blocks of 4096, are one array each through the solver
(NumPy's loops), each point keeps its Hessian only where it is not zero (a Block over the
coordinates it moves with), and M, K, R are summed as arrays.

Before (commit 5616181) and after, `linkcli solve` of a chain of n masses in a fresh
process, on the same 2-core machine under the load of other work (load average 11-13, so
wall times are upper bounds; before, n = 200 took 386 s on an idle machine; about a
second of each run is importing):

    chain of n masses      before                  after
    n =  10                6.3 s      83 MB        4.9 s     81 MB
    n =  50               34.3 s     127 MB        3.6 s     82 MB
    n = 200             1630   s    2554 MB       11.3 s    141 MB
    n = 500              not run                  44.4 s    272 MB
    n pendulums end to end (every second derivative non-zero), after:
    n =  10, 30, 60        4.3 s, 5.2 s, 5.7 s;  81, 83, 90 MB

The lowest and highest frequencies agree with the closed forms to 3e-12 (relative).
linkcli refuses more than 500 coordinates (answers.quantities.vibration.MAX_COORDINATES).

    python benchmarks/vibration.py [--sizes]

--sizes runs only the second part (benchmarks/out/vibration-sizes.json).  Writes
benchmarks/out/vibration.{txt,json}.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

import linkcli  # noqa: E402
from linkcli.forces import vibration as vib  # noqa: E402
from linkcli.forces.lagrange import Lagrangian  # noqa: E402
from linkcli.kinematics.solvers import solver_for  # noqa: E402

sys.path.insert(0, os.path.join(ROOT, "tests"))
from vibration_cases import chain, chain_omega, pendulums, pendulums_omega  # noqa: E402

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


SIZES = {"chain": (chain, chain_omega, (10, 50, 200, 500)),
         "pendulums": (pendulums, pendulums_omega, (10, 30, 60))}
CODE = "import sys; from linkcli.cli import main; sys.exit(main(sys.argv[1:]))"


def solve_in_child(path):
    """(seconds, peak MB, exit status, stdout) of `linkcli solve --format json PATH`."""
    args = [sys.executable, "-c", CODE, "solve", path, "--format", "json"]
    env = dict(os.environ, PYTHONPATH=ROOT + os.pathsep + os.environ.get("PYTHONPATH", ""))
    start = time.perf_counter()
    with tempfile.TemporaryFile() as out:
        proc = subprocess.Popen(args, stdout=out, stderr=subprocess.DEVNULL, env=env)
        _, status, usage = os.wait4(proc.pid, 0)
        seconds = time.perf_counter() - start
        out.seek(0)
        text = out.read().decode()
    kb = usage.ru_maxrss if sys.platform != "darwin" else usage.ru_maxrss / 1024
    return seconds, kb / 1024, os.waitstatus_to_exitcode(status), text


def sizes():
    """Wall time, peak memory and accuracy of `linkcli solve` against the number of
    coordinates, for the two families of SIZES."""
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for family, (text, exact, counts) in SIZES.items():
            for n in counts:
                path = os.path.join(folder, f"{family}-{n}.yaml")
                with open(path, "w") as f:
                    f.write(text(n))
                seconds, mb, status, out = solve_in_child(path)
                error = None
                if status == 0:
                    values = json.loads(out)["values"]
                    error = max(abs(values[k] - w) / w for k, w in zip(("w1", "wn"), exact(n)))
                rows.append({"family": family, "n": n, "seconds": seconds, "peak_mb": mb,
                             "exit": status, "relative_error": error})
                print(f"{family:<10} n = {n:>3}: {seconds:7.2f} s {mb:7.0f} MB exit {status}"
                      + (f"  error {error:.1e}" if error is not None else ""), flush=True)
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", action="store_true", help="only the sizes of problems")
    args = parser.parse_args()
    size_rows = sizes() if args.sizes else None
    if args.sizes:
        os.makedirs(OUT, exist_ok=True)
        with open(os.path.join(OUT, "vibration-sizes.json"), "w") as f:
            json.dump(size_rows, f, indent=2)
        return
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
    size_rows = sizes()
    lines += ["", "Size: linkcli solve in a fresh process (lowest and highest frequency against "
              "the closed form)", f"{'family':<10} {'n':>4} {'seconds':>8} {'peak MB':>8} "
              f"{'exit':>4} {'rel. error':>10}"]
    for r in size_rows:
        error = "-" if r["relative_error"] is None else f"{r['relative_error']:.1e}"
        lines.append(f"{r['family']:<10} {r['n']:>4} {r['seconds']:>8.2f} {r['peak_mb']:>8.0f} "
                     f"{r['exit']:>4} {error:>10}")
    text = "\n".join(lines)
    print(text)
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, "vibration.txt"), "w") as f:
        f.write(text + "\n")
    with open(os.path.join(OUT, "vibration.json"), "w") as f:
        json.dump({"rows": rows, "closed_form_error": err, "sizes": size_rows}, f, indent=2)


if __name__ == "__main__":
    main()
