"""The motion of a machine in time: J*(q) q'' + 1/2 dJ*/dq q'^2 = Q(q, q', t) integrated
from the driver's state (its value and rate at t = 0) by scipy's solve_ivp, with the events
the answers ask for (docs/machines.md).

Speed.  For an angle driver whose mechanism turns through a whole turn, J*, dJ*/dq, the
smooth part of Q (gravity, springs, loads without a window) and each load's lever are
periodic in q: they are sampled once on a grid of the turn and interpolated by periodic
cubic splines (:class:`Table`), the grid doubled until the splines agree with the direct
evaluation at the midpoints of the grid to SPLINE_TOL of each column's scale (measured,
and kept in ``Table.error``).  A window's switch and the motors' and brakes' torques are
evaluated exactly at each step.  Otherwise (a length driver, a driver that cannot turn
through a whole turn) every step solves the kinematics (:class:`Direct`), and a position
the mechanism cannot pass (a dead centre where J* is undefined) stops the motion with its
time and position.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from linkcli.answers.quantities.machine import display, machine_for
from linkcli.errors import LinkcliError, SolveError
from linkcli.forces.machine import require_known
from linkcli.model.machine import TURN, inside

#: the splines' largest error at the grid's midpoints, relative to each column's scale
SPLINE_TOL = 1e-10
GRID = 256
#: a point more than PERIODIC of the mechanism's size away from where it was a turn before:
#: the mechanism does not repeat over a turn of the driver
PERIODIC = 1e-9
GRID_MOST = 16384
#: solve_ivp's relative tolerance (the absolute one is 1e-2 of it, in rad and rad/s or m and
#: m/s) and method
RTOL = 1e-11
METHOD = "DOP853"
STAGES = 12             # its evaluations of the equation per step
#: J* beyond LIMIT times its value at the start: the motion is at a dead centre of the driver
#: (a singular position, where the members the driver moves turn without bound)
LIMIT = 1e8
#: how far ahead (a fraction of a turn, or of a metre) a window is looked at from a stretch's
#: start: the start of a stretch that begins on an edge is not inside or outside by rounding
EDGE = 1e-9
#: the first stretch of time integrated when an event is pending (s), doubled after
FIRST = 0.5


class Direct:
    """J*, dJ*/dq, the smooth Q and the levers solved at each q (the kinematics per step)."""

    def __init__(self, machine):
        self.machine = machine
        self.names = [load.name for load in machine.windowed + machine.turning]
        self.error = 0.0

    def __call__(self, q) -> np.ndarray:
        c = self.machine.coefficients(np.array([q]))
        return np.array([c.J[0], c.dJ[0], c.smooth[0]] + [c.levers[n][0] for n in self.names])


class Table(Direct):
    """The same columns as periodic cubic splines over a turn of an angle driver."""

    def __init__(self, machine):
        super().__init__(machine)
        self.require_periodic()
        n = GRID
        while True:
            h = TURN / n
            values = self.columns(np.arange(n) * h)
            coefficients = periodic_spline(values, h)
            exact = self.columns((np.arange(n) + 0.5) * h)
            d = 0.5 * h
            mid = ((coefficients[:, 0] * d + coefficients[:, 1]) * d + coefficients[:, 2]) * d \
                + coefficients[:, 3]
            scale = np.maximum(np.max(np.abs(values), axis=0), 1e-300)
            self.error = float(np.max(np.abs(mid - exact) / scale))
            if self.error <= SPLINE_TOL or 2 * n > GRID_MOST:
                break
            n *= 2
        self.n, self.h = n, h
        #: per interval, the four rows of the cubic's coefficients (lists: a step of the
        #: integration evaluates one interval, where Python's floats beat small arrays)
        self.rows = coefficients.tolist()                                  # (n, 4, k)

    def require_periodic(self) -> None:
        """Refuse (:class:`NotPeriodic`) a mechanism that is not where it was after a turn of
        the driver (a cord wound on a drum, a disc rolling away): its coefficients need
        not repeat."""
        jt = self.machine.jet(np.array([0.0, TURN]))
        size = self.machine.lag.size
        if any(np.any(np.abs(np.diff(np.broadcast_to(z, (2,)))) > PERIODIC * size)
               for z in jt.pos.values()):
            raise NotPeriodic()

    def columns(self, q) -> np.ndarray:
        c = self.machine.coefficients(q)
        return np.column_stack([c.J, c.dJ, c.smooth] + [c.levers[n] for n in self.names])

    def __call__(self, q) -> np.ndarray:
        x = q % TURN
        i = min(int(x / self.h), self.n - 1)
        d = x - i * self.h
        a, b, c, e = self.rows[i]
        return [((ai * d + bi) * d + ci) * d + ei for ai, bi, ci, ei in zip(a, b, c, e)]


def periodic_spline(y, h) -> np.ndarray:
    """The periodic cubic spline through the columns of ``y`` (n x k) at x_i = i h: per
    interval the coefficients (a, b, c, e) of a d^3 + b d^2 + c d + e, d = x - x_i.  Its
    second derivatives M solve the circulant system M_i-1 + 4 M_i + M_i+1 =
    6 (y_i-1 - 2 y_i + y_i+1) / h^2, diagonal in Fourier space (eigenvalues 4 + 2 cos(2 pi j/n))."""
    n = y.shape[0]
    ahead = np.roll(y, -1, axis=0)
    rhs = 6.0 * (np.roll(y, 1, axis=0) - 2 * y + ahead) / (h * h)
    eig = 4.0 + 2.0 * np.cos(2 * np.pi * np.arange(n) / n)
    M = np.real(np.fft.ifft(np.fft.fft(rhs, axis=0) / eig[:, None], axis=0))
    M1 = np.roll(M, -1, axis=0)
    return np.stack([(M1 - M) / (6 * h), M / 2, (ahead - y) / h - h * (2 * M + M1) / 6, y],
                    axis=1)


class NotPeriodic(Exception):
    """The mechanism is not where it was after a turn of the driver."""


def table_for(machine):
    """A :class:`Table` where the driver turns through a whole turn and the mechanism comes
    back to where it was, else :class:`Direct`."""
    if machine.angular:
        try:
            return Table(machine)
        except (SolveError, NotPeriodic):
            pass                # no whole turn, or not the same mechanism after one
    return Direct(machine)


class _Blocked(Exception):
    def __init__(self, t, q, error):
        super().__init__(str(error))
        self.t, self.q, self.error = t, q, error


@dataclass
class Equation:
    """q'' of the state (t, q, w) from the table's columns."""

    machine: object
    table: object
    blocked_at: list = field(default_factory=list)

    def __post_init__(self):
        m = self.machine
        self.windowed = [(3 + i, load.value, load.window) for i, load in enumerate(m.windowed)]
        #: whether each windowed load acts: decided at the start of a stretch and held over
        #: it (a stretch ends at the next edge), so that every step sees a smooth equation
        self.acting = None
        k = 3 + len(m.windowed)
        self.turning = [(k + i, load) for i, load in enumerate(m.turning)]
        self.limit = math.inf

    def parts(self, t, q, w) -> tuple:
        """(J*, dJ*/dq, Q without brakes, the brakes' holding torque B |theta_q|)."""
        try:
            v = self.table(q)
        except LinkcliError as exc:
            raise _Blocked(t, q, exc) from None
        Q = float(v[2])
        acting = self.acting if self.acting is not None else self.modes(q, 0.0)
        for (i, value, _), on in zip(self.windowed, acting):
            if on:
                Q += value * v[i]
        hold = 0.0
        for i, load in self.turning:
            c = float(v[i])
            if load.kind == "motor":
                if load.motor.outside(c * w) is not None:
                    raise _Blocked(t, q, SolveError(
                        f"motor {load.name} runs at {c * w:.6g} rad/s, outside its table of "
                        f"speeds ({load.motor.speeds[0]:.6g} to {load.motor.speeds[-1]:.6g} "
                        "rad/s)"))
                Q += load.motor.scalar(c * w, q, t) * c
            else:
                hold += load.value * abs(c)
        return float(v[0]), float(v[1]), Q, hold

    def modes(self, q, w) -> list:
        """Which windowed loads act just after the driver value q, moving at w: inside the
        window a step EDGE of a turn ahead in the sense of the motion."""
        ahead = q + math.copysign(EDGE * TURN, w) if w else q
        return [inside(ahead, window, self.machine.angular) for _, _, window in self.windowed]

    def accel(self, t, q, w) -> float:
        J, dJ, Q, hold = self.parts(t, q, w)
        if not 0 < J < self.limit:
            raise _Blocked(t, q, SolveError(
                "the reduced inertia J* is zero: nothing with mass moves with the driver"
                if J <= 0 else f"the reduced inertia J* grows without bound (beyond {LIMIT:g} "
                "times its value at the start)"))
        if hold:
            Q -= hold * math.copysign(1.0, w) if w else max(-hold, min(hold, Q))
        return (Q - 0.5 * dJ * w * w) / J

    def rhs(self, t, y):
        return (y[1], self.accel(t, y[0], y[1]))


@dataclass
class Motion:
    """The motion found: the start state, the states at the times asked, the first state
    of each event asked, and when the machine came to rest for good."""

    q0: float
    w0: float
    at_times: dict              # t -> (q, w)
    events: dict                # (kind, value) -> (t, q, w)
    rest: tuple | None          # (t, q) from which the machine stays at rest
    equation: Equation
    table_error: float
    steps: int = 0

    def state(self, t) -> tuple:
        """(q, w, q'') at a time asked."""
        if self.rest is not None and t >= self.rest[0]:
            return self.rest[1], 0.0, 0.0
        q, w = self.at_times[t]
        return q, w, self.accel(t, q, w)

    def accel(self, t, q, w) -> float:
        """q'' at a state, the windows' loads as they act from there on."""
        self.equation.acting = self.equation.modes(q, w)
        return self.equation.accel(t, q, w)

    def event_state(self, event) -> tuple:
        """(t, q, w, q'') at an event asked."""
        t, q, w = self.events[event]
        if self.rest is not None and t >= self.rest[0]:
            return t, self.rest[1], 0.0, 0.0
        return t, q, w, self.accel(t, q, w)


def start(mech):
    """(q0, w0): the driver's value and rate, SI."""
    return float(mech.driver.value), float(mech.driver.rate)


def integrate(mech, times=(), events=(), until=None, tabled=True, rtol=None) -> Motion:
    """The motion of ``mech`` from its driver's state, integrated at least to every time of
    ``times`` and until every event of ``events`` ((kind, value) pairs, SI) is found.

    The integration is cut at every edge of a load's window (a terminal event), so that no
    step straddles the jump of the load; it stops where the brakes hold the machine."""
    machine = machine_for(mech)
    require_known(mech)
    table = table_for(machine) if tabled else Direct(machine)
    equation = Equation(machine, table)
    q0, w0 = start(mech)
    until = until if until is not None else (mech.motion.until if mech.motion else 60.0)
    require_start(mech, equation, q0, w0)
    equation.limit = LIMIT * equation.parts(0.0, q0, w0)[0]
    run = _Run(equation, q0, sorted(set(times)), list(dict.fromkeys(events)), until,
               rtol or RTOL)
    run.go(mech, w0)
    return Motion(q0, w0, run.at_times, run.found, run.rest, equation, table.error, run.steps)


class _Run:
    """The stretches of solve_ivp between the windows' edges."""

    def __init__(self, equation, q0, times, events, until, rtol):
        self.eq, self.q0, self.times, self.events = equation, q0, times, events
        self.until, self.rtol = until, rtol
        self.at_times, self.found, self.rest, self.steps = {}, {}, None, 0
        m = equation.machine
        edges = sorted({e for load in m.windowed for e in load.window})
        self.edges = [edge_function(e, m.angular) for e in edges]
        self.brakes = any(load.kind == "brake" for load in m.turning)

    def pending(self, t) -> bool:
        return self.rest is None and (any(x > t for x in self.times) or
                                      len(self.found) < len(self.events))

    def go(self, mech, w0):
        from scipy.integrate import solve_ivp
        t, y, skip, stretch = 0.0, np.array([self.q0, w0]), None, FIRST
        slipped, step = False, None
        self.sense = math.copysign(1.0, w0 if w0 else self.eq.accel(0.0, self.q0, 0.0))
        for x in self.times:
            if x == 0:
                self.at_times[x] = (self.q0, w0)
        while self.pending(t):
            if t >= self.until:
                missing = [e for e in self.events if e not in self.found]
                raise not_reached(mech, missing[0] if missing else ("time", self.times[-1]),
                                  t, y)
            horizon = max([x for x in self.times if x > t], default=t)
            wanted = [e for e in self.events if e not in self.found]
            t1 = min(self.until, max(t + stretch, horizon) if wanted else horizon)
            stop = event_function(("stop", 0.0), self.q0, self.sense)
            stop.terminal = self.brakes and not slipped
            edges = [g for i, g in enumerate(self.edges) if i != skip]
            for g in edges:
                g.terminal = True
            fns = [event_function(e, self.q0, self.sense) for e in wanted] + [stop] + edges
            t_eval = [x for x in self.times if t < x < t1] + [t1]   # the end: the next start
            self.eq.acting = None
            self.eq.acting = self.eq.modes(float(y[0]), float(y[1]) or self.sense)
            try:
                sol = solve_ivp(self.eq.rhs, (t, t1), y, method=METHOD, rtol=self.rtol,
                                atol=self.rtol * 1e-2, events=fns, t_eval=t_eval,
                                first_step=step)
            except _Blocked as exc:
                raise blocked(mech, exc) from None
            self.steps += sol.nfev
            end = t1 if sol.status == 0 else self.terminal_time(sol)
            if end > t:     # the next stretch starts with the mean step of this one
                step = min(t1 - end, (end - t) * STAGES / max(sol.nfev, STAGES)) or None
            for x, yq, yw in zip(sol.t, *sol.y):
                if x <= end and x in self.times:
                    self.at_times[float(x)] = (float(yq), float(yw))
            for e, te, ye in zip(wanted, sol.t_events, sol.y_events):
                hits = [(float(a), float(b[0]), float(b[1])) for a, b in zip(te, ye) if a <= end]
                if hits:
                    self.found[e] = hits[0]
            y_end = self.state_at(sol, end)
            skip, slipped = None, False
            k = len(wanted)
            if sol.status == 1 and len(sol.t_events[k]) and sol.t_events[k][-1] == end \
                    and self.brakes:
                if holds(self.eq, end, y_end):
                    self.rest = (end, float(y_end[0]))
                    for e in wanted:
                        if e[0] == "stop" and e not in self.found:
                            self.found[e] = (end, float(y_end[0]), 0.0)
                y_end, slipped = np.array([y_end[0], 0.0]), True
            elif sol.status == 1:
                skip = next(i for i, g in enumerate(self.edges)
                            if g in edges and len(sol.t_events[k + 1 + edges.index(g)])
                            and sol.t_events[k + 1 + edges.index(g)][-1] == end)
            t, y = end, y_end
            if sol.status == 0:
                stretch *= 2

    @staticmethod
    def terminal_time(sol) -> float:
        return float(max(te[-1] for te in sol.t_events if len(te)))

    @staticmethod
    def state_at(sol, t):
        for te, ye in zip(sol.t_events, sol.y_events):
            for a, b in zip(te, ye):
                if a == t:
                    return np.array(b, dtype=float)
        return np.array(sol.y[:, -1], dtype=float)


def event_function(event, q0, sense=1.0):
    """g(t, y) zero at the event; a stop is the speed passing zero against ``sense``, the
    sense of the motion from the start."""
    kind, value = event
    if kind == "speed":
        def g(t, y):
            return y[1] - value
    elif kind in ("turned", "turns"):
        def g(t, y):
            return y[0] - q0 - value
    else:                       # stop: the speed passes zero
        def g(t, y):
            return y[1]
        g.direction = -sense
    return g


def edge_function(edge, angular):
    """Zero where q passes a window's edge (every turn for an angle driver)."""
    if angular:
        def g(t, y):
            return math.sin(0.5 * (y[0] - edge))
    else:
        def g(t, y):
            return y[0] - edge
    return g


def holds(equation, t, y) -> bool:
    """Whether the brakes hold the machine at rest at (t, y): |Q| <= B |theta_q|."""
    _, _, Q, hold = equation.parts(t, float(y[0]), 0.0)
    return abs(Q) <= hold


def require_start(mech, equation, q0, w0) -> None:
    """Refuse a start from rest that the motors cannot make: their torque at rest does not
    overcome the loads and the brakes' holding torque there."""
    if w0 != 0 or not any(load.kind == "motor" for load in equation.machine.mech.loads.values()):
        return
    J, _, Q, hold = equation.parts(0.0, q0, 0.0)
    motors = sum(float(load.motor.torque(equation.table(q0)[i] * 0.0, q0, 0.0))
                 * equation.table(q0)[i] for i, load in equation.turning if load.kind == "motor")
    if abs(Q) > hold and motors * Q > 0:
        return
    unit, factor = display(mech, _torque_quantity())
    brakes = f", with brakes holding up to {hold / factor:.6g} {unit}" if hold else ""
    raise SolveError(f"the motor cannot start the machine: at rest (q = "
                     f"{_driver_text(mech, q0)}) it gives {motors / factor:.6g} {unit} reduced "
                     f"to the driver, and the other loads {((Q - motors) / factor):.6g} {unit}"
                     f"{brakes}",
                     file=mech.file, key="loads",
                     hint="a larger stall torque, smaller loads at rest, or start at a speed")


def _torque_quantity():
    from linkcli.model.mechanism import Quantity
    return Quantity("Q", "reduced_torque", "q")


def _driver_text(mech, q, digits=6) -> str:
    unit, factor = mech.units.display(mech.driver.base, 0)
    return f"{q / factor:.{digits}g} {unit}"


def blocked(mech, exc: _Blocked) -> SolveError:
    detail = getattr(exc.error, "detail", str(exc.error))
    if detail.startswith("motor "):
        return SolveError(f"at t = {exc.t:.4g} s, q = {_driver_text(mech, exc.q, 4)}: {detail}",
                          file=mech.file, hint="extend the motor's table to the speeds the "
                          "machine reaches")
    return SolveError(f"the motion reaches a position the mechanism cannot pass at t = "
                      f"{exc.t:.4g} s, q = {_driver_text(mech, exc.q, 4)}: {detail}",
                      file=mech.file, hint="a singular position (a dead centre of the "
                      "driver): start elsewhere, or drive the mechanism from another member")


def not_reached(mech, event, t, y, rest=False) -> SolveError:
    kind, value = event
    what = {"stop": "the machine does not stop", "time": f"the time {value:.6g} s is not "
            "reached"}.get(kind, f"the event {kind} = {value:.6g} (SI) is not reached")
    where = "it comes to rest" if rest else f"the motion is integrated to t = {t:.6g} s " \
        "('motion: until')"
    return SolveError(f"{what}: {where}; there q = {_driver_text(mech, float(y[0]))}, "
                      f"q' = {float(y[1]):.6g} (SI)", file=mech.file,
                      hint="check the event's value, or give a longer 'motion: until'")


# --- the answers ---------------------------------------------------------------------------
def asks_motion(mech, names) -> bool:
    return any(getattr(mech.quantities.get(n), "kind", None) == "motion" for n in names)


def motion_values(mech, names) -> dict:
    """name -> (value in display units, unit) of every motion answer among ``names``."""
    quantities = [mech.quantities[n] for n in names
                  if getattr(mech.quantities.get(n), "kind", None) == "motion"]
    times = [q.time for q in quantities if q.b == "time"]
    events = [(q.b, q.time) for q in quantities if q.b != "time"]
    motion = integrate(mech, times, events)
    out = {}
    for q in quantities:
        if q.b == "time":
            t = q.time
            pos, w, acc = motion.state(t)
        else:
            t, pos, w, acc = motion.event_state((q.b, q.time))
        value = {"speed": w, "acceleration": acc, "turned": pos - motion.q0,
                 "turns": (pos - motion.q0) / TURN, "time": t}[q.a]
        unit, factor = display(mech, q)
        out[q.name] = (value / factor, unit)
    return out
