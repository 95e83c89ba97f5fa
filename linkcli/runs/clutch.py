"""The transient of two shafts coupled by a clutch (or a shaft and a brake) in time: the
slip integrated until the speeds are equal, then the shafts turning together.

The equations are those of :mod:`linkcli.forces.clutch`, with torques that may depend on
the speed and the time (a motor's characteristic, a user's load growing with its speed):

    slipping:  J1 w1' = M1(w1, t) - s C,   J2 w2' = M2(w2, t) + s C,   E' = C |w1 - w2|
    locked:    (J1 + J2) w' = M1(w, t) + M2(w, t)

integrated by scipy's solve_ivp (RK45, imported when first needed) with the engagement
w1 - w2 = 0 as a terminal event, and, once locked, the clutch's transmitted torque
reaching its capacity (|C_t| = C) as another.  Constant torques take the closed form of
``forces.clutch.engagement`` instead, exactly.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from linkcli.errors import ClutchError
from linkcli.forces import clutch as physics

#: relative tolerance of the integration; the absolute one is this times the speeds' scale
RTOL = 1e-10
#: a slip is given up when it has lasted HORIZON times its initial time scale
#: |w1 - w2|_0 / (initial closing rate) without the speeds becoming equal
HORIZON = 200.0


@dataclass
class Torques:
    """The applied torques as functions of (speed rad/s, time s) -> N m, and whether both
    are constant (the closed form applies)."""

    m1: object
    m2: object
    constant: bool = False


@dataclass
class Transient:
    """The clutch's transient: the slip's answers and the motion in time.

    ``slip_time`` (s), ``speed`` the common speed (rad/s), ``energy`` dissipated (J); the
    speeds at any time through both phases from :meth:`speeds_at`."""

    shafts: physics.Shafts
    torques: Torques
    slip_time: float
    speed: float
    energy: float
    file: str | None = None
    #: the slip's dense solution (integrated torques), the locked phase's once integrated
    _dense: object = field(default=None, repr=False)
    _locked: object = field(default=None, repr=False)

    def speeds_at(self, t: float) -> tuple[float, float, float, float]:
        """(w1, w2, w1', w2') at time ``t`` (s) after the clutch starts to slip."""
        if t <= self.slip_time:
            return _slip_state(self, t)
        w, a = _locked_state(self, t)
        return w, (0.0 if self.shafts.brake else w), a, (0.0 if self.shafts.brake else a)

    def time_to(self, speed: float, side: int = 2) -> float:
        """The first time (s) shaft ``side`` reaches ``speed`` (rad/s), through both
        phases; refused when it does not within the integration's reach."""
        return _time_to(self, speed, side)


def transient(shafts: physics.Shafts, torques: Torques, file=None) -> Transient:
    """The slip of ``shafts`` under ``torques`` to the common speed (``shafts.m1``, ``m2``
    the torques at the start), refused (exit 3) where the speeds never become equal."""
    if torques.constant:
        done = physics.engagement(shafts, file)
        return Transient(shafts, torques, done.time, done.speed, done.energy, file=file)
    return _integrated(shafts, torques, file)


def heat_rate(capacity, w1, w2):
    """E' = C |w1 - w2|: the power the slipping clutch turns into heat (W)."""
    return capacity * abs(w1 - w2)


def _closing(shafts, torques, w1, w2, t, sense):
    """-s d(w1 - w2)/dt while slipping: > 0 where the relative speed closes."""
    a1 = (torques.m1(w1, t) - sense * shafts.capacity) / shafts.j1
    a2 = 0.0 if shafts.brake else (torques.m2(w2, t) + sense * shafts.capacity) / shafts.j2
    return -sense * (a1 - a2), a1, a2


def _integrated(shafts, torques, file):
    """The slip integrated to the engagement event."""
    from scipy.integrate import solve_ivp
    gap = shafts.w1 - shafts.w2
    sense = 1.0 if gap >= 0 else -1.0
    closing, a1, a2 = _closing(shafts, torques, shafts.w1, shafts.w2, 0.0, sense)
    if gap == 0:
        return Transient(shafts, torques, 0.0, shafts.w1, 0.0, file=file)
    if closing <= 0:
        raise physics.never_engages(shafts, a1, a2, file)

    def rhs(t, y):
        _, b1, b2 = _closing(shafts, torques, y[0], y[1], t, sense)
        return [b1, b2, heat_rate(shafts.capacity, y[0], y[1])]

    def engaged(t, y):
        return y[0] - y[1]
    engaged.terminal, engaged.direction = True, -sense
    scale = max(abs(shafts.w1), abs(shafts.w2))
    end = HORIZON * abs(gap) / closing
    sol = solve_ivp(rhs, (0.0, end), [shafts.w1, shafts.w2, 0.0], events=engaged,
                    rtol=RTOL, atol=RTOL * scale, dense_output=True)
    if not sol.t_events[0].size:
        _, b1, b2 = _closing(shafts, torques, sol.y[0, -1], sol.y[1, -1], sol.t[-1], sense)
        raise physics.never_engages(
            physics.Shafts(shafts.j1, shafts.j2, float(sol.y[0, -1]), float(sol.y[1, -1]),
                           shafts.m1, shafts.m2, shafts.capacity), b1, b2, file)
    t_s = float(sol.t_events[0][0])
    y = sol.y_events[0][0]
    return Transient(shafts, torques, t_s, float(y[1] if not shafts.brake else 0.0),
                     float(y[2]), file=file, _dense=sol.sol)


def _slip_state(tr: Transient, t: float):
    """(w1, w2, w1', w2') at ``t`` while slipping."""
    sh = tr.shafts
    sense = 1.0 if sh.w1 >= sh.w2 else -1.0
    dense = tr._dense
    if dense is None:
        a1, a2 = physics.slip_rates(sh, sense)
        return sh.w1 + a1 * t, sh.w2 + a2 * t, a1, a2
    w1, w2, _ = dense(t)
    _, a1, a2 = _closing(sh, tr.torques, w1, w2, t, sense)
    return float(w1), float(w2), a1, a2


def _locked_state(tr: Transient, t: float):
    """(w, w') of the locked shafts at ``t`` > slip time; refused where the clutch would slip
    again before ``t``."""
    sh = tr.shafts
    if sh.brake:
        _require_hold(tr, tr.speed, tr.slip_time)
        return 0.0, 0.0
    if tr.torques.constant:
        accel, torque = physics.transmitted(sh)
        if not physics.holds(sh, torque):
            raise physics.slips_again(sh, torque, tr.slip_time, tr.file)
        return tr.speed + accel * (t - tr.slip_time), accel
    sol = _locked_solution(tr, t)
    w = float(sol.sol(t)[0])
    return w, _locked_rate(tr, w, t)[0]


def locked_torque(tr, w, t):
    """C_t the clutch passes between the locked shafts at speed ``w`` and time ``t``."""
    return _locked_rate(tr, w, t)[1]


def _locked_rate(tr, w, t):
    """(w', C_t) of the locked shafts at speed ``w`` and time ``t``."""
    sh = tr.shafts
    m1, m2 = tr.torques.m1(w, t), tr.torques.m2(w, t)
    total = sh.j1 + sh.j2
    return (m1 + m2) / total, (sh.j2 * m1 - sh.j1 * m2) / total


def _require_hold(tr, w, t):
    """Refuse where the clutch (brake) cannot hold the torque it must pass at ``t``."""
    sh = tr.shafts
    torque = tr.torques.m1(w, t) if sh.brake else _locked_rate(tr, w, t)[1]
    if not physics.holds(sh, torque):
        raise physics.slips_again(sh, torque, t, tr.file)


def _locked_solution(tr, t_end):
    """The locked motion integrated from the engagement to ``t_end``, stopped (and refused)
    where the transmitted torque reaches the capacity."""
    from scipy.integrate import solve_ivp
    _require_hold(tr, tr.speed, tr.slip_time)
    cache = tr._locked
    if cache is not None and cache.t[-1] >= t_end:
        return cache

    def rhs(t, y):
        return [_locked_rate(tr, y[0], t)[0]]

    def slips(t, y):
        return tr.shafts.capacity - abs(_locked_rate(tr, y[0], t)[1])
    slips.terminal = True
    scale = max(abs(tr.speed), abs(tr.shafts.w1), abs(tr.shafts.w2), 1e-300)
    sol = solve_ivp(rhs, (tr.slip_time, t_end), [tr.speed], events=slips, rtol=RTOL,
                    atol=RTOL * scale, dense_output=True)
    if sol.t_events[0].size:
        t_slip = float(sol.t_events[0][0])
        w = float(sol.y_events[0][0][0])
        raise physics.slips_again(tr.shafts, _locked_rate(tr, w, t_slip)[1], t_slip, tr.file)
    tr._locked = sol
    return sol


def _time_to(tr: Transient, speed: float, side: int) -> float:
    """The first time shaft ``side`` reaches ``speed``: in the slip (where it lies between
    its start and the common speed) or in the locked phase."""
    sh = tr.shafts
    start = sh.w1 if side == 1 else sh.w2
    if (start - speed) * (tr.speed - speed) <= 0:       # reached while slipping
        return _root(lambda t: _slip_state(tr, t)[side - 1] - speed, 0.0, tr.slip_time)
    if sh.brake:
        raise _not_reached(tr, speed, side)
    _require_hold(tr, tr.speed, tr.slip_time)
    accel = _locked_rate(tr, tr.speed, tr.slip_time)[0]
    if (speed - tr.speed) * accel <= 0:
        raise _not_reached(tr, speed, side)
    if tr.torques.constant:
        return tr.slip_time + (speed - tr.speed) / accel
    span = abs(speed - tr.speed) / abs(accel)
    end = tr.slip_time + span
    for _ in range(12):                     # widen until the speed is passed
        w_end = float(_locked_solution(tr, end).sol(end)[0])
        if (w_end - speed) * (tr.speed - speed) <= 0:
            sol = _locked_solution(tr, end)
            return _root(lambda t: float(sol.sol(t)[0]) - speed, tr.slip_time, end)
        end = tr.slip_time + 2 * (end - tr.slip_time)
    raise _not_reached(tr, speed, side)


def _root(f, lo, hi):
    from scipy.optimize import brentq
    if f(lo) == 0:
        return lo
    return float(brentq(f, lo, hi, xtol=1e-14 * max(hi, 1.0), rtol=1e-14))


def _not_reached(tr, speed, side):
    return ClutchError(f"shaft {side} never reaches {speed:.6g} rad/s: it goes from "
                       f"{tr.shafts.w1 if side == 1 else tr.shafts.w2:.6g} rad/s to the common "
                       f"speed {tr.speed:.6g} rad/s and then "
                       + ("stays at rest (the brake holds it)" if tr.shafts.brake else
                          "moves away from it or tends to a steady speed short of it"),
                       file=tr.file, reason="never reaches", values={"speed": speed},
                       hint="ask for a speed the shaft passes")
