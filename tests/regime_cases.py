"""Machines whose periodic regime the tests and the benchmark solve: a crankshaft under a
turning moment T0 + A sin(n q) (closed forms), a crank-slider's reduced equation driven by a
motor, and the transient of either integrated in time by a hand-written solve_ivp."""
import math

import numpy as np

from linkcli.forces import regime as rg

T0, A, N = 5000.0, 1500.0, 3
W_MEAN = 300 * math.pi / 30


def const(value):
    return lambda q: np.full(np.shape(q), float(value))


def crankshaft(J=0.0, A=A, n=N, resisting=-T0):
    """T = T0 + A sin(n q) against a constant resisting torque, on a constant inertia."""
    return rg.Cycle(0.0, 2 * math.pi, const(J), const(0.0),
                    (rg.Load("T", lambda q, w: T0 + A * np.sin(n * q)),
                     rg.Load("R", lambda q, w: np.full(np.shape(q), resisting))))


def slider_crank(motor=True, flywheel=0.0):
    """A crank-slider's reduced inertia J0 + m (r s(q))^2, s = sin q + r/(2l) sin 2q (the
    piston's speed ratio to first order), driven by a linear motor (or, ``motor`` False, a
    constant torque equal to the mean load) against a gas-like load over half the cycle and a
    constant load."""
    m, r, lam, J0 = 20.0, 0.1, 0.25, 0.4

    def s(q):
        return r * (np.sin(q) + 0.5 * lam * np.sin(2 * q))

    def ds(q):
        return r * (np.cos(q) + lam * np.cos(2 * q))

    drive = (rg.Load("motor", lambda q, w: 2000.0 * (1 - w / 80.0), True) if motor else
             rg.Load("drive", lambda q, w: np.full(np.shape(q), 110.0)))
    loads = (drive,
             rg.Load("piston", lambda q, w: -4000.0 * np.maximum(np.sin(q), 0.0) * s(q)),
             rg.Load("load", lambda q, w: np.full(np.shape(q), -10.0)))
    return rg.Cycle(0.0, 2 * math.pi, lambda q: J0 + m * s(q) ** 2,
                    lambda q: 2 * m * s(q) * ds(q), loads, flywheel=flywheel)


def integrate(cycle, q0, w0, cycles):
    """The transient from (q0, w0) in time, solve_ivp of J q'' + 1/2 J' w^2 = Q; the speeds
    over the last cycle (max, min, average: the period over the cycle's time)."""
    from scipy.integrate import solve_ivp

    def rhs(t, y):
        q, w = y
        qa = np.array([q])
        Q = cycle.Q(qa, np.array([w]))[0]
        return [w, (Q - 0.5 * cycle.dJ(qa)[0] * w * w) / cycle.J(qa)[0]]

    def turned(t, y):
        return y[0] - q0 - cycles * cycle.period
    turned.terminal = True
    sol = solve_ivp(rhs, (0, 1e4), [q0, w0], rtol=1e-10, atol=1e-10, events=turned,
                    dense_output=True, method="DOP853")
    t_end = sol.t_events[0][0]
    # the last cycle: from the time q passed q0 + (cycles - 1) P
    from scipy.optimize import brentq
    t_start = brentq(lambda t: sol.sol(t)[0] - q0 - (cycles - 1) * cycle.period, 0, t_end)
    t = np.linspace(t_start, t_end, 20001)
    w = sol.sol(t)[1]
    return w.max(), w.min(), cycle.period / (t_end - t_start)
