"""Long arrays are solved with freed working memory kept (answers.memory): repeated solves
of 16384 positions take no fresh pages from the kernel, where with malloc's default
thresholds each one faults in thousands.  Counted (minor page faults), not timed."""
from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FILE = os.path.join(ROOT, "mechanisms", "padova-2020-07.yaml")

SCRIPT = """
import json, resource, sys
import numpy as np
import linkcli
from linkcli.answers import memory
linkage = linkcli.load(sys.argv[1])
driver = linkage.model.driver
base = "angle" if driver.kind == "angle" else "length"
value = driver.value / linkage.model.units.display(base, 0)[1]
q = value * np.linspace(0.99, 1.01, int(sys.argv[2]))
linkage.solve(q)                       # plans, solvers and the kept memory in place
before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
for _ in range(10):
    linkage.solve(q)
faults = (resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before) / 10
print(json.dumps({"kept": memory._state.get("set"), "faults": faults}))
"""

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="page faults counted with glibc's malloc")


def _run(size, **env):
    out = subprocess.run([sys.executable, "-c", SCRIPT, FILE, str(size)], capture_output=True,
                         text=True, check=True, cwd=ROOT, env={**os.environ, **env})
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_long_solves_reuse_their_memory():
    kept = _run(16384)
    if kept["kept"] is not True:
        pytest.skip("this C library has no mallopt")
    default = _run(16384, LINKCLI_KEEP_MEMORY="0")
    assert default["kept"] is False
    # each solve of 16384 positions makes about 8 MB of temporaries (2000 pages)
    assert kept["faults"] < 50, kept
    assert default["faults"] > 20 * max(kept["faults"], 1.0), (kept, default)


def test_short_solves_leave_malloc_alone():
    assert _run(360)["kept"] is None
