"""Small vibration problems with textbook closed forms, shared by the tests.

Each case is YAML text and the closed-form natural frequencies (rad/s) of its
linearised motion, written from the textbook formula, not from linkcli.
"""
from __future__ import annotations

import math
import os

G = 9.81

# compound pendulum: a uniform rod of mass m, length L about one end
# omega^2 = m g (L/2) / (m L^2 / 3)
PENDULUM = """
title: compound pendulum
units: {length: m, angle: deg}
params: {L: 1.2, m: 3}
frame: {O: [0, 0]}
points: {A: [0.3, -1.16]}
links: {rod: {points: [O, A], length: L}}
coordinates: {theta: {angle: [O, A]}}
dynamics:
  gravity: 9.81
  bodies: {rod: {mass: m, inertia: m*L**2/12, center: [L/2, 0]}}
quantities:
  w1: {natural_frequency: 1}
  th: {equilibrium: theta}
report: {vibration: [w1, th]}
"""
PENDULUM_OMEGA = [math.sqrt(3 * G / (2 * 1.2))]

# a uniform disc (mass m, radius R) rolling on the floor, its centre held by a
# horizontal spring k to a wall: omega^2 = k / (m + J / R^2) = 2 k / (3 m)
DISC = """
title: disc rolling on a spring
units: {length: m, angle: deg}
params: {R: 0.25, m: 4, kk: 600}
frame: {W: [-1, 0.25]}
points: {C: [0.1, 0.25]}
sliders: {wheel: {point: C, guide: {y: 0.25}}}
coordinates: {x: {x: C}}
springs: {k: {between: [W, C], k: kk, free_length: 1.05}}
dynamics:
  gravity: 9.81
  discs: {disc: {center: C, radius: R, mass: m, inertia: m*R**2/2}}
quantities:
  w1: {natural_frequency: 1}
  xe: {equilibrium: x}
report: {vibration: [w1, xe]}
"""
DISC_OMEGA = [math.sqrt(2 * 600 / (3 * 4))]

# two pendulums (point masses m at length l) coupled by a spring k at distance a
# from the pivots: omega1^2 = g / l, omega2^2 = g / l + 2 k a^2 / (m l^2)
COUPLED = """
title: two pendulums coupled by a spring
units: {length: m, angle: deg}
params: {l: 0.8, a: 0.5, m: 1.5, kk: 40}
frame: {O1: [0, 0], O2: [0.6, 0]}
points: {S1: [0, -a], A1: [0, -l], S2: [0.6, -a], A2: [0.6, -l]}
links:
  p1: {points: [O1, S1, A1], shape: {S1: {length: a}, A1: {length: l}}}
  p2: {points: [O2, S2, A2], shape: {S2: {length: a}, A2: {length: l}}}
coordinates: {t1: {angle: [O1, A1]}, t2: {angle: [O2, A2]}}
springs: {k: {between: [S1, S2], k: kk}}
dynamics:
  gravity: 9.81
  masses: {A1: m, A2: m}
quantities:
  w1: {natural_frequency: 1}
  w2: {natural_frequency: 2}
  u1: {mode_shape: [1, t2]}
  u2: {mode_shape: [2, t2]}
report: {vibration: [w1, w2, u1, u2]}
"""
COUPLED_OMEGA = [math.sqrt(G / 0.8), math.sqrt(G / 0.8 + 2 * 40 * 0.5 ** 2 / (1.5 * 0.8 ** 2))]

# a rigid bar (mass m, inertia J about its centre G) on two vertical springs
# k1 at a left of G and k2 at b right of G, in a horizontal plane (no gravity):
# det([k1 + k2 - m w^2, k2 b - k1 a], [k2 b - k1 a, k1 a^2 + k2 b^2 - J w^2]) = 0
BAR = """
title: bar on two springs (bounce and pitch)
units: {length: m, angle: deg}
params: {a: 0.9, b: 1.4, m: 30, J: 9, k1: 5000, k2: 3000}
frame: {F1: [-a, -1], F2: [b, -1]}
points: {G: [0, 0], P1: [-a, 0], P2: [b, 0]}
sliders: {hub: {point: G, guide: {x: 0}}}
links:
  bar: {points: [G, P2, P1], shape: {P2: {length: b}, P1: {length: a, angle: 180}}}
coordinates: {y: {y: G}, pitch: {angle: [G, P2]}}
springs:
  s1: {between: [F1, P1], k: k1, along: y}
  s2: {between: [F2, P2], k: k2, along: y}
dynamics:
  bodies: {bar: {mass: m, inertia: J, center: G}}
quantities:
  w1: {natural_frequency: 1}
  w2: {natural_frequency: 2}
report: {vibration: [w1, w2]}
"""


def bar_omega(a=0.9, b=1.4, m=30.0, J=9.0, k1=5000.0, k2=3000.0):
    """Roots of the bounce-pitch determinant (a quadratic in w^2)."""
    A = m * J
    B = -(m * (k1 * a ** 2 + k2 * b ** 2) + J * (k1 + k2))
    C = (k1 + k2) * (k1 * a ** 2 + k2 * b ** 2) - (k2 * b - k1 * a) ** 2
    disc = math.sqrt(B * B - 4 * A * C)
    return [math.sqrt((-B - disc) / (2 * A)), math.sqrt((-B + disc) / (2 * A))]


BAR_OMEGA = bar_omega()

CASES = {"pendulum": (PENDULUM, PENDULUM_OMEGA), "disc": (DISC, DISC_OMEGA),
         "coupled": (COUPLED, COUPLED_OMEGA), "bar": (BAR, BAR_OMEGA)}

# a mass m on a vertical guide, spring k and damper c to the ground, in gravity;
# harmonic force F0 at Omega, or (SUPPORT) the ground point moved by Y cos(Omega t)
SDOF = """
title: mass, spring and damper
units: {{length: m, angle: deg}}
params: {{m: {m}, kk: {k}, c: {c}}}
frame: {{B: [0, 0]}}
points: {{P: [0, 0.5]}}
sliders: {{block: {{point: P, guide: {{x: 0}}}}}}
coordinates: {{y: {{y: P}}}}
springs: {{k: {{between: [B, P], k: kk, free_length: 0.5}}}}
dampers: {{r: {{between: [B, P], c: c}}}}
dynamics: {{gravity: 9.81, masses: {{P: m}}}}
excitation: {{frequency: {Omega}, forces: {{F: {{at: P, y: {F}}}}}}}
quantities:
  w1: {{natural_frequency: 1}}
  wd: {{damped_frequency: 1}}
  z1: {{damping_ratio: 1}}
  X: {{amplitude: y}}
  ph: {{phase: y}}
  Ft: {{force_amplitude: [k, r]}}
  ye: {{equilibrium: y}}
  N: {{spring_force: k}}
report: {{vibration: [w1, wd, z1, X, ph, Ft, ye, N]}}
"""

SUPPORT = """
title: base excitation
units: {{length: m, angle: deg}}
params: {{m: {m}, kk: {k}, c: {c}}}
frame: {{O: [0, -1]}}
points: {{B: [0, 0], P: [0, 0.5]}}
sliders: {{block: {{point: P, guide: {{x: 0}}}}, base: {{point: B, guide: {{x: 0}}}}}}
coordinates: {{y: {{y: P}}, s: {{y: B}}}}
springs: {{k: {{between: [B, P], k: kk, free_length: 0.5}}}}
dampers: {{r: {{between: [B, P], c: c}}}}
dynamics: {{gravity: 9.81, masses: {{P: m}}}}
excitation: {{frequency: {Omega}, supports: {{ground: {{coordinate: s, amplitude: {Y}}}}}}}
quantities:
  w1: {{natural_frequency: 1}}
  X: {{amplitude: y}}
  T: {{transmissibility: y}}
report: {{vibration: [w1, X, T]}}
"""


def chain(n, k=1000.0, m=1.0) -> str:
    """n masses m on a line, n + 1 springs k between two walls (mm): omega_j =
    2 sqrt(k / m) sin(j pi / (2 (n + 1))).  Each point depends on one coordinate."""
    points = ["W0"] + [f"P{i}" for i in range(1, n + 1)] + ["W1"]
    lines = [f"title: a chain of {n} masses on springs between two walls",
             "units: {length: mm, angle: deg}",
             f"frame: {{W0: [0, 0], W1: [{100 * (n + 1)}, 0]}}", "points:"]
    lines += [f"  P{i}: [{100 * i}, 0]" for i in range(1, n + 1)]
    lines += ["sliders:"] + [f"  b{i}: {{point: P{i}, guide: {{y: 0}}}}" for i in range(1, n + 1)]
    lines += ["coordinates:"] + [f"  x{i}: {{x: P{i}}}" for i in range(1, n + 1)]
    lines += ["springs:"] + [f"  s{i}: {{between: [{points[i]}, {points[i + 1]}], k: {k}}}"
                             for i in range(n + 1)]
    lines += ["dynamics:", "  masses: {" + ", ".join(f"P{i}: {m}" for i in range(1, n + 1)) + "}",
              "quantities:", "  w1: {natural_frequency: 1}", f"  wn: {{natural_frequency: {n}}}",
              "report: {vibration: [w1, wn], decimals: 6}"]
    return "\n".join(lines) + "\n"


def chain_omega(n, k=1000.0, m=1.0):
    return [2 * math.sqrt(k / m) * math.sin(j * math.pi / (2 * (n + 1))) for j in (1, n)]


def pendulums(n, L=1.0, m=1.0) -> str:
    """n rods of length L hanging end to end, a mass m at each joint (m): the last point
    depends on every coordinate.  Linearised: M_ij = m L^2 (n + 1 - max(i, j)),
    K = diag(m g L (n + 1 - i)) (i, j from 1)."""
    names = ["O"] + [f"A{i}" for i in range(1, n + 1)]
    lines = [f"title: {n} pendulums hanging end to end", "units: {length: m, angle: deg}",
             "frame: {O: [0, 0]}", "points:"]
    lines += [f"  A{i}: [0.01, {-i * L}]" for i in range(1, n + 1)]
    lines += ["links:"] + [f"  l{i}: {{points: [{names[i - 1]}, {names[i]}], length: {L}}}"
                           for i in range(1, n + 1)]
    lines += ["coordinates:"] + [f"  t{i}: {{angle: [{names[i - 1]}, {names[i]}]}}"
                                 for i in range(1, n + 1)]
    lines += ["dynamics:", f"  gravity: {G}",
              "  masses: {" + ", ".join(f"A{i}: {m}" for i in range(1, n + 1)) + "}",
              "quantities:", "  w1: {natural_frequency: 1}", f"  wn: {{natural_frequency: {n}}}",
              "report: {vibration: [w1, wn], decimals: 6}"]
    return "\n".join(lines) + "\n"


def pendulums_omega(n, L=1.0, m=1.0):
    import numpy as np
    from scipy.linalg import eigh
    i = np.arange(1, n + 1)
    M = m * L ** 2 * (n + 1 - np.maximum.outer(i, i))
    K = np.diag(m * G * L * (n + 1 - i))
    values = np.sqrt(eigh(K, M, eigvals_only=True))
    return [float(values[0]), float(values[-1])]


def solve_file(path, extra=None, params=None, report=None, **sections):
    """Values of the mechanism file ``path`` (keys left out); ``extra`` quantities are
    added to its vibration report, ``params`` override its parameters, ``report``
    replaces the vibration report, other sections replace the file's."""
    import numpy as np
    import yaml

    import linkcli
    with open(path) as handle:
        data = yaml.safe_load(handle)
    for contact in (data.get("rolling") or {}).values():     # YAML 1.1 reads 'on:' as True
        if True in contact:
            contact["on"] = contact.pop(True)
    data.pop("keys", None)
    data["params"].update(params or {})
    data.update(sections)
    if extra:
        data["quantities"].update(extra)
        data["report"]["vibration"] = list(data["report"]["vibration"]) + list(extra)
    if report is not None:
        data["report"]["vibration"] = report
    values = linkcli.loads(yaml.safe_dump(data, sort_keys=False)).solve().values
    return {name: float(np.asarray(v)) for name, v in values.items()}


#: the relative tolerance of the textbook vibration tests against their closed forms
RTOL = 1e-9
MECHANISMS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                          "mechanisms")


def shipped(name):
    """The path of the shipped mechanism file ``name``."""
    return os.path.join(MECHANISMS, name)


def close(got, expected, rtol=RTOL, atol=0.0):
    import pytest
    assert got == pytest.approx(expected, rel=rtol, abs=atol), (got, expected)


def keys_agree(path):
    """``check`` of the file ``path``: it solves and no printed value fails (the report)."""
    from linkcli.runs.check import check_file
    report = check_file(path)
    assert report.error is None, report.error
    assert not [o for o in report.outcomes if o.status == "fail"]
    return report
