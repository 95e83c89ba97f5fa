"""The periodic regime of a one-degree-of-freedom machine, found directly.

The equation of motion in the driver's coordinate q, with w = q',

    J*(q) q'' + 1/2 dJ*/dq w^2 = Q(q, w),

is, with the kinetic energy E = 1/2 J* w^2 and q as the independent variable,

    dE/dq = Q(q, w),    w = sqrt(2 E / J*(q)),

because dE/dt = w (J* q'' + 1/2 dJ*/dq w^2) = w Q.  A periodic regime is an orbit whose
energy comes back after one period P of q: E(q0 + P) = E(q0).  Q is positive where it
drives the motion (in the sense of increasing q); J* is the reduced inertia (kg m^2 for an
angle, kg for a length) and Q the reduced torque (N m, or N).

- **Energy method** (Q independent of the speed): E(q) = E0 + W(q), W(q) the work of Q
  from q0.  A regime needs W(q0 + P) = 0 (the mean torque over a cycle is zero, else the
  machine speeds up or slows down every cycle); E0 is then set by the mean speed.
- **Shooting** (Q depends on the speed, a motor's characteristic): E0 is the root of
  E(q0 + P; E0) - E0, found by Newton's method with the variational equation
  dS/dq = dQ/dw S / (J* w), S = dE/dE0, from the start the motor balance gives (the
  speed w_b where the mean of Q(q, w_b) over a cycle is zero, the energy method at w_b).
  The orbit is a regime only if it attracts: the multiplier S(q0 + P) < 1.

The mean speed is the books' w_m = (w_max + w_min) / 2 (Khurmi, Norton and Shigley define
it so, and a given mean speed is that); the average speed P / integral(dq / w), the period
of q over the time of a cycle, is an answer of its own.  The coefficient of fluctuation is
delta = (w_max - w_min) / w_m and the largest fluctuation of energy DeltaE = E_max - E_min
over the cycle (for a constant J*, exactly DeltaE = J* w_m^2 delta).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Callable

import numpy as np

from linkcli.errors import RegimeError

#: samples of q over one period (the integrals of a smooth periodic function on this grid are
#: spectrally accurate; a load over part of the cycle is resolved to P / GRID)
GRID = 2880
#: the largest mean torque, as a fraction of the cycle's largest torque, taken as zero
BALANCED = 1e-6
#: relative tolerance of the shooting's integration and of its root
RTOL = 1e-10
#: Newton iterations of the shooting before it is refused
ITERATIONS = 30
#: the residual of the shooting, as a fraction of the energy, taken as the integration's
#: noise where Newton's steps stop reducing it (a load switched on over part of a cycle)
NOISE = 1e-7


@dataclass(frozen=True)
class Load:
    """One named part of the reduced torque Q(q, w): ``torque(q, w)`` vectorised over arrays;
    ``speed`` says whether it depends on w."""

    name: str
    torque: Callable
    speed: bool = False


@dataclass(frozen=True)
class Cycle:
    """One period [start, start + period] of q of the reduced equation: ``inertia(q)`` J*,
    ``slope(q)`` dJ*/dq (vectorised), the loads whose sum is Q, and a constant inertia
    ``flywheel`` added to J* (on the driver's shaft)."""

    start: float
    period: float
    inertia: Callable
    slope: Callable
    loads: tuple
    flywheel: float = 0.0
    grid: int = GRID

    @property
    def speed_dependent(self) -> bool:
        return any(load.speed for load in self.loads)

    def with_flywheel(self, inertia: float) -> "Cycle":
        """The same machine with a flywheel of ``inertia`` in place of its own."""
        return replace(self, flywheel=float(inertia))

    def q(self, n: int | None = None) -> np.ndarray:
        """n + 1 equally spaced positions over the period, both ends included."""
        n = self.grid if n is None else n
        return self.start + self.period * np.arange(n + 1) / n

    def reduce(self, q):
        """q brought into [start, start + period)."""
        return self.start + np.mod(np.asarray(q, dtype=float) - self.start, self.period)

    def J(self, q):
        return np.asarray(self.inertia(q), dtype=float) + self.flywheel

    def dJ(self, q):
        return np.asarray(self.slope(q), dtype=float)

    def Q(self, q, w):
        q = np.asarray(q, dtype=float)
        w = np.broadcast_to(np.asarray(w, dtype=float), q.shape)
        return sum(np.broadcast_to(np.asarray(ld.torque(q, w), dtype=float), q.shape)
                   for ld in self.loads)

    def means(self, w) -> dict:
        """The mean of each load over the period at the constant speed w (periodic rule)."""
        q = self.q()[:-1]
        ww = np.full(q.shape, float(w))
        return {ld.name: float(np.mean(np.broadcast_to(ld.torque(q, ww), q.shape)))
                for ld in self.loads}


@dataclass
class Regime:
    """A periodic regime: the energy E(q) along it and what the books ask of it.

    ``q``, ``w`` the grid and the speed on it; speeds in rad/s (or m/s), energies in J.
    """

    cycle: Cycle
    energy: Callable = field(repr=False)
    method: str
    q: np.ndarray = field(repr=False)
    w: np.ndarray = field(repr=False)
    mean_speed: float
    average_speed: float
    max_speed: float
    at_max_speed: float
    min_speed: float
    at_min_speed: float
    energy_fluctuation: float
    at_max_energy: float
    at_min_energy: float
    max_acceleration: float
    at_max_acceleration: float
    min_acceleration: float
    at_min_acceleration: float
    cycle_time: float
    multiplier: float = 0.0
    shots: int = 0

    @property
    def fluctuation(self) -> float:
        """The coefficient of fluctuation delta = (w_max - w_min) / w_m."""
        return (self.max_speed - self.min_speed) / self.mean_speed

    def speed(self, q):
        """w(q) = sqrt(2 E(q) / J*(q)), q reduced into the cycle."""
        q = self.cycle.reduce(q)
        return np.sqrt(2.0 * np.maximum(self.energy(q), 0.0) / self.cycle.J(q))

    def acceleration(self, q):
        """q'' = (Q - 1/2 dJ*/dq w^2) / J*."""
        w = self.speed(q)
        c = self.cycle
        return (c.Q(q, w) - 0.5 * c.dJ(q) * w * w) / c.J(q)


def regime(cycle: Cycle, mean_speed: float | None = None) -> Regime:
    """The periodic regime: by the energy method where Q does not depend on the speed (then
    ``mean_speed`` is required), by shooting where it does (``mean_speed`` must be None: the
    motor's characteristic sets it)."""
    _check_inertia(cycle)
    if cycle.speed_dependent:
        if mean_speed is not None:
            raise RegimeError("the mean speed is set by the speed-dependent loads "
                              f"({_speed_names(cycle)}) and cannot also be given",
                              reason="overdetermined")
        return shoot(cycle)
    if mean_speed is None or not mean_speed > 0:
        raise RegimeError("the loads do not depend on the speed, so the regime needs a "
                          "positive mean speed", reason="no mean speed",
                          values=() if mean_speed is None else (mean_speed,))
    return energy_method(cycle, mean_speed)


def _speed_names(cycle):
    return ", ".join(ld.name for ld in cycle.loads if ld.speed)


def _check_inertia(cycle: Cycle) -> None:
    J = cycle.J(cycle.q())
    if not np.all(np.isfinite(J)) or J.min() <= 0.0:
        i = int(np.argmin(np.where(np.isfinite(J), J, -np.inf)))
        raise RegimeError(f"the reduced inertia is {J[i]:.6g} at q = {cycle.q()[i]:.6g}: a "
                          "machine without inertia (or with an undefined one) has no regime "
                          "(give the flywheel or the masses)", reason="no inertia",
                          values=(float(J[i]), float(cycle.q()[i])))


# --- the energy method -------------------------------------------------------------------

def work(cycle: Cycle, w: float = 0.0):
    """W(q) = integral of Q(q, w) dq from the start, as a periodic cubic spline's
    antiderivative of Q sampled on the grid (w held constant); q is taken into the cycle."""
    from scipy.interpolate import CubicSpline

    q = cycle.q()
    Q = cycle.Q(q, np.full(q.shape, float(w)))
    Q[-1] = Q[0]
    W = CubicSpline(q, Q, bc_type="periodic").antiderivative()
    return lambda x: W(cycle.reduce(x))


def check_balance(cycle: Cycle, w: float = 0.0) -> None:
    """Refuse a cycle whose mean torque is not zero: each cycle then adds (or takes) the
    work W(P), so the machine runs away (or stops) and has no periodic regime."""
    q = cycle.q()
    ww = np.full(q.shape, float(w))
    total = float(cycle.Q(q[:-1], ww[:-1]).mean())
    scale = max(float(np.abs(np.broadcast_to(ld.torque(q, ww), q.shape)).max())
                for ld in cycle.loads) if cycle.loads else 0.0
    if abs(total) <= BALANCED * scale:
        return
    means = cycle.means(w)
    parts = ", ".join(f"{name} {value:.6g}" for name, value in means.items())
    fate = "speeds up every cycle (runs away)" if total > 0 else "slows down and stops"
    raise RegimeError(f"no periodic regime: the mean torques over a cycle are {parts}, their "
                      f"sum {total:.6g} is {abs(total) / scale:.3g} of the largest load's "
                      f"{scale:.6g}, not 0: the machine {fate}", reason="unbalanced",
                      values=(total, scale), hint="a regime needs the mean driving torque "
                      "equal to the mean resisting one")


def energy_method(cycle: Cycle, mean_speed: float) -> Regime:
    """E(q) = E0 + W(q) with E0 such that (w_max + w_min) / 2 is ``mean_speed``."""
    check_balance(cycle)
    W = work(cycle)
    E0 = start_energy(cycle, W, mean_speed)
    return orbit(cycle, lambda q: E0 + W(q), "energy")


def cycle_time(cycle: Cycle, E: np.ndarray) -> float:
    """integral of dq / w over the period, E sampled on the grid (periodic rule)."""
    q = cycle.q()[:-1]
    w = np.sqrt(2.0 * E[:-1] / cycle.J(q))
    return float(np.sum(1.0 / w) * cycle.period / q.size)


def start_energy(cycle: Cycle, W, mean_speed: float) -> float:
    """E0 with (w_max + w_min) / 2 = mean_speed, w = sqrt(2 (E0 + W) / J*): Brent's method on
    the grid's extremes, then on the extremes at their refined positions, again until those
    positions hold (at once for a constant J*, whose extremes do not move with E0)."""
    from scipy.optimize import brentq

    q = cycle.q()
    Wq, J = W(q), cycle.J(q)
    low = -float(Wq.min())
    high = low + max(0.5 * float(J.max()) * mean_speed ** 2, float(Wq.max() - Wq.min()), 1e-300)

    def grid_gap(E0):
        w = np.sqrt(2.0 * np.maximum(E0 + Wq, 0.0) / J)
        return 0.5 * (w.max() + w.min()) - mean_speed

    while grid_gap(high) < 0:
        high = low + 4.0 * (high - low)
    E0 = brentq(grid_gap, low, high, xtol=1e-15 * high, rtol=4 * np.finfo(float).eps)
    for _ in range(8):
        at = _extreme_positions(cycle, W, E0)
        w_of = [lambda E, x=x: math.sqrt(2.0 * max(E + float(W(np.array([x]))[0]), 0.0)
                                         / float(cycle.J(np.array([x]))[0])) for x in at]
        E1 = brentq(lambda E: 0.5 * (w_of[0](E) + w_of[1](E)) - mean_speed, low, high,
                    xtol=1e-15 * high, rtol=4 * np.finfo(float).eps)
        if abs(E1 - E0) <= 1e-14 * E1:
            return E1
        E0 = E1
    return E0


def _extreme_positions(cycle: Cycle, W, E0: float):
    """Where w = sqrt(2 (E0 + W) / J*) is largest and smallest, refined from the grid."""
    def speed(x):
        return np.sqrt(2.0 * np.maximum(E0 + W(x), 0.0) / cycle.J(x))

    def slope(x):
        return cycle.Q(x, speed(x)) * cycle.J(x) - (E0 + W(x)) * cycle.dJ(x)

    w = speed(cycle.q())
    return extreme(cycle, speed, w, +1, slope)[0], extreme(cycle, speed, w, -1, slope)[0]


# --- the orbit and its answers -----------------------------------------------------------

def orbit(cycle: Cycle, energy: Callable, method: str, **extra) -> Regime:
    """The answers of the orbit E(q): speeds, their extremes and where, DeltaE, the
    extremes of the acceleration, each refined from the grid by a bounded search."""
    q = cycle.q()
    inner = energy
    energy = lambda x: inner(cycle.reduce(x))     # noqa: E731 (periodic in q)
    E = np.asarray(energy(q), dtype=float)
    w = np.sqrt(2.0 * np.maximum(E, 0.0) / cycle.J(q))
    T = cycle_time(cycle, E)
    reg = Regime(cycle=cycle, energy=energy, method=method, q=q, w=w,
                 mean_speed=0.0, average_speed=cycle.period / T, max_speed=0.0,
                 at_max_speed=0.0,
                 min_speed=0.0, at_min_speed=0.0, energy_fluctuation=0.0,
                 at_max_energy=0.0, at_min_energy=0.0, max_acceleration=0.0,
                 at_max_acceleration=0.0, min_acceleration=0.0, at_min_acceleration=0.0,
                 cycle_time=T, **extra)
    def torque(x):
        return cycle.Q(x, reg.speed(x))

    def speed_slope(x):                 # d(w^2)/dq J^2 / 2 = Q J - E dJ/dq
        return torque(x) * cycle.J(x) - energy(x) * cycle.dJ(x)

    reg.at_max_speed, reg.max_speed = extreme(cycle, reg.speed, w, +1, speed_slope)
    reg.at_min_speed, reg.min_speed = extreme(cycle, reg.speed, w, -1, speed_slope)
    reg.mean_speed = 0.5 * (reg.max_speed + reg.min_speed)
    reg.at_max_energy, top = extreme(cycle, energy, E, +1, torque)
    reg.at_min_energy, bottom = extreme(cycle, energy, E, -1, torque)
    reg.energy_fluctuation = top - bottom
    a = reg.acceleration(q)
    reg.at_max_acceleration, reg.max_acceleration = extreme(cycle, reg.acceleration, a, +1)
    reg.at_min_acceleration, reg.min_acceleration = extreme(cycle, reg.acceleration, a, -1)
    return reg


def extreme(cycle: Cycle, f: Callable, samples: np.ndarray, sense: int, slope=None):
    """(q, f(q)) of the largest (sense +1) or smallest (-1) value of the periodic f, from the
    grid's best sample refined between its neighbours: by Brent's method on the sign of
    ``slope`` (a function of q of the sign of df/dq) where it is given and changes sign
    there, else by a bounded search on f."""
    from scipy.optimize import brentq, minimize_scalar

    q = cycle.q()
    i = int(np.argmax(sense * samples[:-1]))
    h = cycle.period / cycle.grid
    a, b = q[i] - h, q[i] + h
    tol = 1e-13 * max(cycle.period, abs(q[i]))
    if slope is not None and _scalar(slope, a) * _scalar(slope, b) < 0:
        x = brentq(lambda x: _scalar(slope, x), a, b, xtol=tol)
    else:
        x = minimize_scalar(lambda x: -sense * _scalar(f, x), bounds=(a, b),
                            method="bounded", options={"xatol": tol}).x
    best = _scalar(f, x)
    if sense * best < sense * samples[i]:
        return float(q[i]), float(samples[i])
    return float(cycle.reduce(x)), best


def _scalar(f, x):
    return float(np.asarray(f(np.array([float(x)])), dtype=float)[0])


# --- shooting ----------------------------------------------------------------------------

def balance_speed(cycle: Cycle) -> float:
    """The speed w_b where the mean of Q(q, w_b) over a cycle is zero (the motor balance),
    by Brent's method; refused where the loads stop the machine at low speed or keep driving
    it at any speed."""
    from scipy.optimize import brentq

    def mean(w):
        return float(np.mean(cycle.Q(cycle.q()[:-1], np.full(cycle.grid, w))))

    at_rest = mean(0.0)
    high = 1.0
    while (mean(high) > 0.0) == (at_rest > 0.0):
        high *= 2.0
        if high > 1e9 and at_rest > 0.0:
            raise RegimeError(f"no periodic regime: the mean torque over a cycle is still "
                              f"{mean(high):.6g} > 0 at {high:.6g} rad/s: the machine runs "
                              "away", reason="runs away", values=(mean(high), high))
        if high > 1e9:
            parts = ", ".join(f"{k} {v:.6g}" for k, v in cycle.means(0.0).items())
            raise RegimeError(f"no periodic regime: at rest the mean torques over a cycle "
                              f"are {parts}, their sum {at_rest:.6g} <= 0, and no speed up to "
                              f"{high:.6g} rad/s makes it positive: the motor cannot keep the "
                              "machine turning", reason="stalls", values=(at_rest,))
    low = 0.0
    return brentq(mean, low, high, xtol=1e-14 * high)


def shoot(cycle: Cycle) -> Regime:
    """The periodic orbit of a speed-dependent Q: Newton's method on E0 for
    F(E0) = E(q0 + P; E0) - E0, with F' = S(q0 + P) - 1 from the variational equation."""
    wb = balance_speed(cycle)
    frozen = replace(cycle, loads=tuple(Load(ld.name, at_speed(ld.torque, wb))
                                        for ld in cycle.loads))
    W = work(frozen)
    drift = (W(cycle.start + cycle.period) - W(cycle.start)) / cycle.period
    E0 = start_energy(frozen, lambda q: W(q) - drift * (q - cycle.start), wb)
    scale, F, last = E0, math.inf, math.inf
    table = Tabled(cycle)
    for shots in range(1, ITERATIONS + 1):
        end, S, sol = one_period(cycle, E0, table)
        if sol is None:                 # it stopped within the cycle: start it faster
            E0 *= 2.0
            continue
        F, last = end - E0, abs(F)
        # converged, or at the integration's noise (a step no longer halves the residual)
        if abs(F) <= 10 * RTOL * scale or abs(F) <= NOISE * scale and abs(F) > 0.5 * last:
            if S >= 1.0:
                raise RegimeError(f"the periodic orbit (energy {E0:.6g} J at q0) repels: "
                                  f"its multiplier over a cycle is {S:.6g} >= 1, so the "
                                  "machine leaves it (stops or runs away)",
                                  reason="unstable", values=(E0, S))
            return orbit(cycle, lambda q, s=sol: s.sol(np.asarray(q, dtype=float))[0],
                         "shooting", multiplier=S, shots=shots)
        E0 = max(E0 - F / (S - 1.0), 0.5 * E0)
    raise RegimeError(f"the shooting for the periodic orbit did not converge in {ITERATIONS} "
                      f"iterations: the energy after a cycle still differs by {F:.6g} J "
                      f"({abs(F) / scale:.3g} of it)", reason="no convergence",
                      values=(F, abs(F) / scale))


def at_speed(torque, w):
    """torque(q, w) with the speed held at w."""
    return lambda q, _w: torque(q, np.full(np.shape(q), w))


class Tabled:
    """The cycle's J* and the sum of its speed-free loads as periodic cubic splines on the
    grid, read one q at a time in plain floats (the shooting's right-hand side), with the
    speed-dependent loads evaluated as given."""

    def __init__(self, cycle: Cycle):
        from scipy.interpolate import CubicSpline

        q = cycle.q()
        self.start, self.h, self.n = cycle.start, cycle.period / cycle.grid, cycle.grid
        fixed = [ld for ld in cycle.loads if not ld.speed]
        self.speed = [ld for ld in cycle.loads if ld.speed]
        zero = np.zeros(q.shape)
        Q = sum((np.broadcast_to(ld.torque(q, zero), q.shape) for ld in fixed), zero)
        self.J = self._coefficients(CubicSpline, q, cycle.J(q))
        self.Q = self._coefficients(CubicSpline, q, np.array(Q, dtype=float))

    @staticmethod
    def _coefficients(spline, q, y):
        y = np.array(y, dtype=float)
        y[-1] = y[0]
        return spline(q, y, bc_type="periodic").c.T.tolist()

    def at(self, table, q: float) -> float:
        x = (q - self.start) / self.h
        i = math.floor(x)
        t = (x - i) * self.h
        c3, c2, c1, c0 = table[i % self.n]
        return ((c3 * t + c2) * t + c1) * t + c0

    def torque(self, q: float, w: float):
        """(Q, dQ/dw) at (q, w), the derivative by a one-sided difference."""
        Q = self.at(self.Q, q)
        if not self.speed:
            return Q, 0.0
        dw = 1e-7 * max(w, 1e-300)
        both = sum(ld.torque(np.array([q, q]), np.array([w, w + dw])) for ld in self.speed)
        return Q + float(both[0]), float(both[1] - both[0]) / dw


def one_period(cycle: Cycle, E0: float, table: Tabled | None = None):
    """E and S = dE/dE0 after one period from E0 (solve_ivp in q, dense output); the
    solution None where the machine stops within the cycle (E reaches 0)."""
    from scipy.integrate import solve_ivp

    table = Tabled(cycle) if table is None else table

    def rhs(q, y):
        E, S = y
        J = table.at(table.J, q)
        w = math.sqrt(2.0 * max(E, 0.0) / J)
        Q, dQdw = table.torque(q, w)
        return [Q, dQdw * S / (J * w) if w > 0 else 0.0]

    def stops(q, y):
        return y[0]
    stops.terminal = True
    stops.direction = -1

    q0, q1 = cycle.start, cycle.start + cycle.period
    sol = solve_ivp(rhs, (q0, q1), [E0, 1.0], method="DOP853", rtol=RTOL,
                    atol=[RTOL * E0 * 1e-3, 1e-12], dense_output=True, events=stops)
    if sol.status == 1:
        return 0.0, 0.0, None
    return float(sol.y[0, -1]), float(sol.y[1, -1]), sol
