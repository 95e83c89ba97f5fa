"""Speed of the questions a book asks (run by `make bench`).

- A parameter sweep: `linkcli sweep FILE --vary ks=20:400:9999` (10^4 values of a
  stiffness) on the two-coordinate double pendulum of 18 Sep 2001, its whole report, as a
  command (wall and processor time of the process, imports included) and in the process
  (warm); beside it the time per value of the file built and solved again at each value,
  what the sweep costs without the all-at-once path (runs.coefficients).
- Design questions of one unknown: the evaluations of the file the search takes (scan and
  Brent's method) and its time, for the files of docs/examples and mechanisms/ that ask one.
- A parameter sweep of a linkage: `Linkage.vary("b", ...)` over the rod's length of
  mechanisms/polimi-crank-slider.yaml (every value a file built and solved again), the
  processor time a value with the straight-line solve (``kinematics.straight``) and without
  it, times 10^4, and of the file built again alone.

    python benchmarks/questions.py

Writes benchmarks/out/questions.{txt,json}.
"""
from __future__ import annotations

import glob
import json
import math
import os
import resource
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

import linkcli  # noqa: E402
from linkcli.runs import coefficients, design  # noqa: E402
from linkcli.runs.sheet import evaluate  # noqa: E402
from linkcli.input.document import rebuild  # noqa: E402

OUT = os.path.join(HERE, "out")
FILE = os.path.join(ROOT, "mechanisms", "polimi-2001-09-18-vibration.yaml")
VALUES = 10_000


def command(args):
    """(wall seconds, processor seconds) of linkcli ARGS in a child process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    code = "import sys; from linkcli.cli import main; sys.exit(main(sys.argv[1:]))"
    subprocess.run([sys.executable, "-c", code] + args, check=True, cwd=ROOT,
                   stdout=subprocess.DEVNULL, env=dict(os.environ, PYTHONPATH=ROOT))
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def sweep():
    out = os.path.join(OUT, "questions-sweep.csv")
    runs = [command(["sweep", FILE, "--vary", f"ks=20:400:{VALUES - 1}", "-o", out])
            for _ in range(3)]
    wall, cpu = min(r[0] for r in runs), min(r[1] for r in runs)
    linkage = linkcli.load(FILE)
    values = np.linspace(20, 400, VALUES)
    linkage.vary("ks", values[:10])                 # imports and first-time costs
    start = time.perf_counter()
    varied = linkage.vary("ks", values)
    warm = time.perf_counter() - start
    names = linkage.model.report["vibration"]
    start = time.perf_counter()
    for v in values[:20]:
        evaluate(rebuild(linkage.model, {"ks": float(v)}), names=names)
    per_value = (time.perf_counter() - start) / 20
    fast = coefficients.sweep(linkage.model, "ks", values, names, evaluate) is not None
    return {"values": VALUES, "answers": len(names), "solved": int(varied.solved.sum()),
            "command_wall_s": wall, "command_cpu_s": cpu, "in_process_s": warm,
            "all_at_once": fast, "one_value_again_ms": per_value * 1e3,
            "without_all_at_once_s": per_value * VALUES}


LINKAGE = os.path.join(ROOT, "mechanisms", "polimi-crank-slider.yaml")


def _best(run, repeat=3) -> float:
    """The least processor seconds of ``repeat`` calls of ``run`` (the machine is shared:
    the least is the one least slowed by the others' work)."""
    best = math.inf
    for _ in range(repeat):
        start = time.process_time()
        run()
        best = min(best, time.process_time() - start)
    return best


def linkage_sweep(count=400):
    """Processor seconds a value of ``vary`` over a length of a linkage file (best of 3), by
    the default path and with the straight-line solve switched off (each value is a new
    mechanism, solved once), and of building the file again alone
    (``input.document.rebuild``)."""
    from linkcli.answers.quantities import plan
    linkage = linkcli.load(LINKAGE)
    values = np.linspace(1.3, 1.6, count)
    linkage.vary("b", values[:10])
    out = {"file built again": _best(lambda: [rebuild(linkage.model, {"b": float(v)})
                                              for v in values]) / count}
    for label, off in (("default", False), ("general path only", True)):
        real = plan.straight_of
        if off:
            plan.straight_of = lambda *args: None
        try:
            out[label] = _best(lambda: linkage.vary("b", values)) / count
        finally:
            plan.straight_of = real
    return out


def finds():
    out = []
    paths = sorted(glob.glob(os.path.join(ROOT, "mechanisms", "*.yaml")) +
                   glob.glob(os.path.join(ROOT, "docs", "examples", "design-*.yaml")))
    for path in paths:
        model = linkcli.load(path).model
        if model.design is None or len(model.design.unknowns) != 1 or \
                not model.design.unknowns[0].interval:
            continue
        start = time.perf_counter()
        try:
            found = design.solve(model, evaluate)
        except linkcli.LinkcliError as exc:
            out.append({"file": os.path.relpath(path, ROOT), "error": exc.detail[:60]})
            continue
        out.append({"file": os.path.relpath(path, ROOT), "evaluations": found.evaluations,
                    "roots": len(found.roots), "seconds": time.perf_counter() - start})
    return out


def main():
    os.makedirs(OUT, exist_ok=True)
    data = {"sweep": sweep(), "find": finds(), "linkage_sweep": linkage_sweep()}
    s = data["sweep"]
    lines = [f"sweep --vary ks over {s['values']} values of a 2-coordinate file "
             f"({s['answers']} answers, {s['solved']} values solved):",
             f"  command: {s['command_wall_s']:.2f} s wall, {s['command_cpu_s']:.2f} s "
             f"processor (best of 3, imports included)",
             f"  in the process: {s['in_process_s'] * 1e3:.0f} ms (all at once: "
             f"{s['all_at_once']})",
             f"  the file built and solved again at each value: {s['one_value_again_ms']:.1f} ms "
             f"a value, {s['without_all_at_once_s']:.0f} s for the sweep", "",
             "find, one unknown in an interval (scan of 9 samples, Brent's method):"]
    for f in data["find"]:
        lines.append(f"  {f['file']}: " + (f"{f['evaluations']} evaluations, {f['roots']} "
                                           f"root(s), {f['seconds']:.2f} s"
                                           if "evaluations" in f else f"error {f['error']}"))
    counts = [f["evaluations"] for f in data["find"] if "evaluations" in f]
    if counts:
        lines.append(f"  median {int(np.median(counts))}, largest {max(counts)} evaluations")
    lines += ["", "vary over the rod's length of mechanisms/polimi-crank-slider.yaml (each value "
              "a file built and solved again):"]
    for label, seconds in data["linkage_sweep"].items():
        lines.append(f"  {label}: {seconds * 1e3:.2f} ms a value, {seconds * 1e4:.1f} s for "
                     "10^4 values")
    text = "\n".join(lines)
    print(text)
    with open(os.path.join(OUT, "questions.txt"), "w", encoding="utf-8") as handle:
        handle.write(text + "\n")
    with open(os.path.join(OUT, "questions.json"), "w", encoding="utf-8") as handle:
        json.dump(data, handle, indent=1)


if __name__ == "__main__":
    main()
