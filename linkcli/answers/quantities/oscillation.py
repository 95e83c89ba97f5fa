"""What vibration chapters print besides frequencies and modes (docs/vibrations.md, "What
books ask"), each from the same analysis as the other vibration answers (the modes, the
damping and the steady state of ``answers.quantities.vibration.Analysis``):

- the natural and damped periods 2 pi / omega, the ratio Omega / omega_N of the forcing
  frequency to a natural one, each omega_N^2, the beat period 2 pi / |omega_b - omega_a|;
- the coefficients of det(K - omega^2 M) = sum_i c_i omega^(2i), as they are or divided by
  the leading one (``monic``; forces.oscillation.characteristic);
- the real and imaginary parts of a complex response (the amplitude of a coordinate or of
  a point, a force amplitude, a receptance); the response is Re(X e^{i Omega t});
- the peak of a frequency response |X(Omega)| of a coordinate or a point (the Omega where
  d|X|^2/dOmega = 0 and |X| there); where |X| only falls from its static value, the
  largest amplitude is at Omega = 0, and the answer says so;
- the largest value of a coordinate, of a point's displacement (their magnitude) or of a
  spring's force (the force of largest magnitude, tension positive) in the free vibration
  from ``initial:`` (by linear superposition of the modes).

Each is computed in SI with its dimension (model.dimensions) and shown in the file's units
(``Units.show``), or in its own ``unit``.
"""
from __future__ import annotations

import numpy as np

from linkcli.errors import Caution, InputError, SolveError
from linkcli.forces import oscillation as osc
from linkcli.kinematics import jacobian as jac

def si_value(analysis, quantity) -> float:
    """One of the answers above in SI (its dimension: model.dimensions)."""
    kind = quantity.kind
    lin = analysis.lin
    if kind in ("natural_period", "damped_period", "frequency_ratio", "eigenvalue"):
        k = _mode(analysis, quantity, quantity.a)
        if kind == "eigenvalue":
            return float(analysis.modes().eigenvalues[k])
        if kind == "frequency_ratio":
            if lin.frequency is None:
                raise InputError(f"'{quantity.name}': no excitation frequency in this file",
                                 file=analysis.mech.file, key=f"quantities.{quantity.name}",
                                 line=quantity.line, hint="give excitation: {frequency: ...}")
            return lin.frequency / _positive(analysis, quantity, k, "natural_frequency")
        which = "natural_frequency" if kind == "natural_period" else "damped_frequency"
        return 2 * np.pi / _positive(analysis, quantity, k, which)
    if kind == "beat_period":
        a, b = (_mode(analysis, quantity, m) for m in (quantity.a, quantity.b))
        omega = analysis.modes().omega
        gap = abs(float(omega[b] - omega[a]))
        if gap == 0:
            raise SolveError(f"'{quantity.name}': modes {a + 1} and {b + 1} share their "
                             "frequency, so they do not beat", file=analysis.mech.file,
                             key=f"quantities.{quantity.name}", line=quantity.line)
        return 2 * np.pi / gap
    if kind == "characteristic":
        c = analysis.cache.get("characteristic")
        if c is None:
            c = analysis.cache["characteristic"] = osc.characteristic(lin.M, lin.K)
        i = int(quantity.a)
        return float(c[i] / c[-1]) if quantity.form == "monic" else float(c[i])
    if kind == "receptance":
        H = osc.receptance(lin.M, lin.K, lin.R, _forcing(analysis, quantity))
        i, j = (_free_index(analysis, quantity, c) for c in (quantity.a, quantity.b))
        return _part(H[i, j], quantity.form)
    if kind in ("amplitude", "force_amplitude"):
        return _part(complex_amplitude(analysis, quantity), quantity.form)
    if kind in ("peak_frequency", "peak_amplitude"):
        frequency, amplitude = peak(analysis, quantity)
        return frequency if kind == "peak_frequency" else amplitude
    found = largest(analysis, quantity).value
    return found if quantity.of == "spring" else abs(found)


def _part(value: complex, form) -> float:
    if form == "real":
        return float(np.real(value))
    if form == "imaginary":
        return float(np.imag(value))
    return float(abs(value))


def _mode(analysis, quantity, text) -> int:
    k = int(text) - 1
    count = len(analysis.lin.free)
    if k >= count:
        raise InputError(f"mode {k + 1} asked, but the problem has {count} free coordinate"
                         f"{'s' if count != 1 else ''}", file=analysis.mech.file,
                         key=f"quantities.{quantity.name}", line=quantity.line)
    return k


def _positive(analysis, quantity, k, which) -> float:
    """Mode k's natural (or damped) frequency, refused where it is 0 (no period)."""
    omega = float(analysis.modes().omega[k] if which == "natural_frequency"
                  else analysis.damped().omega_d[k])
    if omega <= 0:
        what = "does not oscillate (no damped frequency)" if which == "damped_frequency" \
            else "has no stiffness (natural frequency 0)"
        raise SolveError(f"'{quantity.name}': mode {k + 1} {what}, so it has no period or "
                         "frequency ratio", file=analysis.mech.file,
                         key=f"quantities.{quantity.name}", line=quantity.line)
    return omega


def _free_index(analysis, quantity, name) -> int:
    mech = analysis.mech
    j = next(j for j, c in enumerate(mech.coordinates) if c.name == name)
    if j not in analysis.lin.free:
        raise InputError(f"'{quantity.name}': coordinate {name} is imposed (a support motion), "
                         "not free", file=mech.file, key=f"quantities.{quantity.name}",
                         line=quantity.line, hint="ask for a free coordinate")
    return analysis.lin.free.index(j)


def _forcing(analysis, quantity) -> float:
    if analysis.lin.frequency is None:
        raise InputError(f"'{quantity.name}' is at the forcing frequency, and this file has "
                         "no excitation", file=analysis.mech.file,
                         key=f"quantities.{quantity.name}", line=quantity.line,
                         hint="give excitation: {frequency: ...}")
    return analysis.lin.frequency


# --- complex responses --------------------------------------------------------------------
def gradient(analysis, quantity) -> np.ndarray:
    """The row g of y = g . x over every coordinate: a coordinate's (a unit vector), or a
    point's x or y displacement (its first derivatives at the equilibrium)."""
    mech = analysis.mech
    n = len(mech.coordinates)
    if quantity.component is None:
        g = np.zeros(n)
        g[next(j for j, c in enumerate(mech.coordinates) if c.name == quantity.a)] = 1.0
        return g
    direction = 1 + 0j if quantity.component == "x" else 1j
    s = jac.along(analysis.lin.eq.terms.jet, None, quantity.a, direction)
    return np.asarray(s.grad, dtype=float)


def complex_amplitude(analysis, quantity) -> complex:
    """The complex amplitude X of a coordinate or a point (``amplitude``) or of the force
    through springs and dampers (``force_amplitude``): the response is Re(X e^{i Omega t})."""
    mech = analysis.mech
    X = analysis.amplitudes()
    if quantity.kind == "amplitude":
        return complex(gradient(analysis, quantity) @ X)
    omega = analysis.lin.frequency
    total = 0j
    for name in quantity.elements:
        s = analysis.lin.eq.terms.measures[name]
        spring = mech.elements.springs.get(name)
        gain = spring.stiffness if spring is not None else \
            1j * omega * mech.elements.dampers[name].coefficient
        total += gain * complex(np.asarray(s.grad, dtype=float) @ X)
    return total


# --- peaks --------------------------------------------------------------------------------
def peak(analysis, quantity) -> tuple[float, float]:
    """(Omega, |y|) of the asked peak of |y(Omega)|, y a coordinate or a point (SI); the
    static response at Omega = 0 where |y| only falls (a caution says so)."""
    lin = analysis.lin
    mech = analysis.mech
    g = gradient(analysis, quantity)
    if not np.any(g[lin.free]):
        raise SolveError(f"'{quantity.name}': {quantity.a} does not move with the free "
                         "coordinates, so its amplitude has no peak", file=mech.file,
                         key=f"quantities.{quantity.name}", line=quantity.line)
    if not np.any(lin.R):
        omega = analysis.modes().omega
        raise SolveError(f"'{quantity.name}': without damping the amplitude grows without "
                         "bound at each natural frequency (" + ", ".join(
                             f"{w:.6g}" for w in omega) + " rad/s): it has no finite peak",
                         file=mech.file, key=f"quantities.{quantity.name}", line=quantity.line,
                         hint="add the problem's dampers")
    t = lin.eq.terms
    fs = np.ix_(lin.free, lin.imposed)
    response = osc.Response(lin.M, lin.K, lin.R, np.asarray(lin.forces, dtype=complex),
                            t.M[fs], t.K[fs], t.R[fs], np.asarray(lin.supports, complex),
                            g[lin.free], complex(g[lin.imposed] @ lin.supports)
                            if lin.imposed else 0j)
    key = ("peaks", quantity.a, quantity.component)
    found = analysis.cache.get(key)
    if found is None:
        found = analysis.cache[key] = osc.peaks(response, _roots(analysis))
    number = int(quantity.b)
    if not found:
        static = float(response.magnitude(0.0))
        analysis.cache.setdefault("cautions", []).append(Caution(
            "peak", f"'{quantity.name}': the amplitude of {_what(quantity)} has no resonant "
            "peak: it falls from its static value as Omega grows, so its largest value is "
            "the static one, at Omega = 0", mech.file, {quantity.name: static}))
        if number > 1:
            raise SolveError(f"'{quantity.name}': the amplitude of {_what(quantity)} has no "
                             f"peak at all, so no peak {number}", file=mech.file,
                             key=f"quantities.{quantity.name}", line=quantity.line)
        return 0.0, static
    if number > len(found):
        listed = ", ".join(f"{w:.6g}" for w, _ in found)
        raise SolveError(f"'{quantity.name}': the amplitude of {_what(quantity)} has "
                         f"{len(found)} peak{'s' if len(found) != 1 else ''} (at Omega = "
                         f"{listed} rad/s), not {number}", file=mech.file,
                         key=f"quantities.{quantity.name}", line=quantity.line)
    return found[number - 1]


def _roots(analysis) -> np.ndarray:
    """The roots s of det(M s^2 + R s + K) = 0 with Im s >= 0."""
    lin = analysis.lin
    n = len(lin.free)
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(lin.M, lin.K), -np.linalg.solve(lin.M, lin.R)]])
    s = np.linalg.eigvals(A)
    return s[s.imag >= 0]


def _what(quantity) -> str:
    return f"{quantity.component} of {quantity.a}" if quantity.component else quantity.a


# --- the free vibration ---------------------------------------------------------------------
def initial_state(analysis) -> tuple[np.ndarray, np.ndarray]:
    """(x0, v0) of the free coordinates: the offsets from the equilibrium at t = 0 and the
    rates, from ``initial:`` given from the equilibrium, the figure or the position where a
    spring is unstretched (``from:``)."""
    mech = analysis.mech
    lin = analysis.lin
    elements = mech.elements
    x0 = np.zeros(len(lin.free))
    v0 = np.zeros(len(lin.free))
    if elements.initial_mode is not None:
        return mode_start(analysis), v0
    for c, (dx, dv) in elements.initial.items():
        if c in lin.free:
            x0[lin.free.index(c)], v0[lin.free.index(c)] = dx, dv
    start, springs = elements.initial_from
    if start == "figure":
        x0 += (lin.lag.figure - lin.eq.q)[lin.free]
    elif start == "unstretched":
        x0 += unstretched(analysis, springs) - lin.eq.q[lin.free]
    return x0, v0


def mode_start(analysis) -> np.ndarray:
    """x0 = a u_k / u_jk: mode k's shape scaled so that coordinate j's offset is a
    (``initial: {mode, q: a}``), refused where the shape is not one (modes of one
    frequency) or j does not move in it, or is not free."""
    mech = analysis.mech
    lin = analysis.lin
    k, j, amplitude = mech.elements.initial_mode
    name = mech.coordinates[j].name
    where = dict(file=mech.file, key=f"initial.{name}")
    if j not in lin.free:
        raise InputError(f"the start in mode {k + 1} scales the mode by {name}, whose "
                         "motion is imposed (a support): it is in no mode", **where,
                         hint="give the amplitude of a free coordinate")
    if k >= len(lin.free):
        raise InputError(f"there is no mode {k + 1}: the system has {len(lin.free)} free "
                         "coordinates", **where, hint=f"mode 1-{len(lin.free)}")
    found = analysis.modes()
    i = lin.free.index(j)
    if found.repeated[k]:
        raise SolveError(f"modes {', '.join(str(m + 1) for m in [k] + found.repeated[k])} "
                         "share a natural frequency, so the shape of a start in one of them "
                         "is any combination of theirs", **where,
                         hint="give the initial offsets of every coordinate instead")
    if not found.moves(i, k):
        raise SolveError(f"{name} does not move in mode {k + 1} (less than "
                         f"{found.still[k]:.1e} of its largest component), so its amplitude "
                         "cannot scale the mode", **where,
                         hint=f"give the amplitude of a coordinate that moves in mode {k + 1}")
    shape = np.asarray(found.vectors[:, k], dtype=float)
    return amplitude * shape / shape[i]


def unstretched(analysis, names) -> np.ndarray:
    """The free coordinates (SI) where the springs ``names`` have their free measures s0:
    Newton's method from the equilibrium on the coordinates they move (as many as the
    springs), the others left at the equilibrium."""
    lin = analysis.lin
    lag = lin.lag
    mech = analysis.mech
    springs = [mech.elements.springs[n] for n in names]
    q = lin.eq.q.copy()
    grads = np.array([np.asarray(lin.eq.terms.measures[n].grad, dtype=float) for n in names])
    moved = [j for j in lin.free if np.any(grads[:, j] != 0)]
    if len(moved) != len(names):
        listed = ", ".join(mech.coordinates[j].name for j in moved) or "none"
        raise InputError(f"the position where {', '.join(names)} {'is' if len(names) == 1 else 'are'}"
                         f" unstretched is not one: {len(names)} spring"
                         f"{'s' if len(names) != 1 else ''} and {len(moved)} free coordinate"
                         f"{'s' if len(moved) != 1 else ''} they move ({listed})",
                         file=mech.file, key="initial.from", hint="name one spring per "
                         "coordinate, or give the initial offsets from the equilibrium or the "
                         "figure")
    for _ in range(50):
        jt = lag.jet(q, second=False)
        rotations = lag.rotations(q, jt)
        measures = [lag.measure(jt, s.measure, rotations) for s in springs]
        miss = np.array([float(m.value) - lag.free[n] for m, n in zip(measures, names)])
        rates = np.array([[float(m.grad[j]) for j in moved] for m in measures])
        try:
            change = np.linalg.solve(rates, miss)
        except np.linalg.LinAlgError:
            break
        q[moved] -= change
        if np.all(np.abs(change) <= 1e-14 * (1 + np.abs(q[moved]))):
            return q[lin.free]
    raise SolveError(f"no position near the equilibrium leaves {', '.join(names)} at "
                     "the free measure", file=mech.file, key="initial.from",
                     hint="give the initial offsets from the equilibrium or the figure")


def largest(analysis, quantity) -> osc.Largest:
    """The value of largest magnitude of a coordinate's offset from the equilibrium, a
    point's displacement (x or y) or a spring's force N = N_e + k ds in the free vibration
    from ``initial:``, by superposition (forces.oscillation.largest)."""
    mech = analysis.mech
    lin = analysis.lin
    if not mech.elements.started:
        raise InputError(f"'{quantity.name}' is of the free vibration from 'initial:', and "
                         "the file has none", file=mech.file, key=f"quantities.{quantity.name}",
                         line=quantity.line, hint="e.g. initial: {x: 10, x_dot: 0}")
    offset = 0.0
    if quantity.of == "spring":
        spring = mech.elements.springs[quantity.a]
        g = spring.stiffness * np.asarray(lin.eq.terms.measures[quantity.a].grad, dtype=float)
        offset = float(lin.eq.terms.forces[quantity.a])
    else:
        g = gradient(analysis, quantity)
        if quantity.of == "coordinate":
            _free_index(analysis, quantity, quantity.a)
    x0, v0 = initial_state(analysis)
    return osc.largest(lin.M, lin.K, lin.R, g[lin.free], x0, v0, offset)


def explain_lines(analysis) -> list:
    """How the answers of this module are found, for ``linkcli explain``."""
    mech = analysis.mech
    kinds = {q.kind for q in mech.quantities.values()}
    lines = []
    if "largest" in kinds:
        lines += ["", "Largest values in the free vibration (linear superposition of the "
                  "modes from 'initial:'):",
                  "  undamped: y(t) = sum_k C_k cos(omega_k t - phi_k), largest sum_k C_k "
                  "(reached when the modes come into phase; approached for incommensurate "
                  "frequencies)",
                  "  damped: the extremes of y(t) where y'(t) = 0, until the modes' envelope "
                  "falls below the largest found"]
        for q in mech.quantities.values():
            if q.kind == "largest":
                found = largest(analysis, q)
                how = "reached" if found.reached else "approached, not reached"
                lines.append(f"  {q.name}: {found.value:.6g} (SI; {how})")
    if kinds & {"peak_frequency", "peak_amplitude"}:
        lines += ["", "Peaks of the frequency response: d|X|^2/dOmega = 0 by Brent's method "
                  "between samples where its sign changes"]
    return lines
