"""Two shafts coupled by a friction clutch, or a shaft stopped by a brake (the frame as its
second side): the equations while they slip and once they turn together.

Shaft 1 (the motor's side) has the inertia J1 and the applied torque M1(w1, t); shaft 2
(the user's side) J2 and M2(w2, t).  Torques are counter-clockwise positive along the
shafts' common axis, so a motor drives with M1 > 0 and a user resists with M2 < 0 while
w2 > 0.  While the shafts slip the clutch passes its friction torque C (>= 0) from the
faster to the slower one, s = sgn(w1 - w2):

    J1 w1' = M1 - s C,        J2 w2' = M2 + s C.

The relative speed w1 - w2 closes when s (M1/J1 - M2/J2 - C (1/J1 + 1/J2)) < 0.  With
constant torques every rate is constant (:func:`engagement`): the slip time
t_s = |w1 - w2|_0 / r with r = C (1/J1 + 1/J2) - s (M1/J1 - M2/J2) > 0, the common speed
w_c = w1_0 + w1' t_s, and the energy the clutch turns into heat
E = C integral |w1 - w2| dt = C |w1 - w2|_0 t_s / 2 (the relative speed falls linearly).
The energy balance is E = (work of M1 and M2) - (change of kinetic energy).

Once engaged the shafts turn together:

    (J1 + J2) w' = M1 + M2,    the clutch passing C_t = (J2 M1 - J1 M2) / (J1 + J2),

and they stay together while |C_t| <= C (the clutch's capacity, its friction torque);
above it the clutch slips again (:func:`transmitted`).

A brake is the same with shaft 2 the frame (J2 infinite, w2 = 0): J1 w1' = M1 - s C.

The friction torque of a plate clutch (:func:`plate_torque`) of n pairs of surfaces of
radii r_o > r_i pressed by the axial force F with the coefficient mu:

    uniform wear:      C = n mu F (r_o + r_i) / 2
    uniform pressure:  C = n mu F (2/3) (r_o^3 - r_i^3) / (r_o^2 - r_i^2)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from linkcli.errors import ClutchError
from linkcli.model.clutch import Plate


def plate_torque(mu: float, force: float, outer: float, inner: float, pairs: int = 1,
                 wear: str = "uniform") -> float:
    """The friction torque (N m) of a plate clutch: ``pairs`` pairs of surfaces, radii
    ``outer`` > ``inner`` >= 0 (m), axial force ``force`` (N); ``wear`` 'uniform' (uniform
    wear, the mean radius) or 'pressure' (uniform pressure) (``model.clutch.Plate``)."""
    return Plate(mu, force, outer, inner, pairs, wear).torque


@dataclass(frozen=True)
class Shafts:
    """Two shafts and the clutch between them, constant torques (SI): ``j2`` None for a
    brake (the second side is the frame, at rest)."""

    j1: float
    j2: float | None
    w1: float               # initial speeds (rad/s)
    w2: float
    m1: float               # applied torques (N m), counter-clockwise positive
    m2: float
    capacity: float         # the clutch's friction torque C (N m)

    @property
    def brake(self) -> bool:
        return self.j2 is None


@dataclass(frozen=True)
class Engagement:
    """What a slip with constant torques gives: the slip time (s), the common speed (rad/s),
    the energy dissipated (J), the shafts' accelerations while slipping (rad/s^2), the
    acceleration of the locked shafts and the torque the clutch passes then (N m)."""

    time: float
    speed: float
    energy: float
    accel1: float
    accel2: float
    locked_accel: float
    locked_torque: float


def slip_rates(shafts: Shafts, sense: float) -> tuple[float, float]:
    """(w1', w2') while slipping with the sense s = sgn(w1 - w2) (rad/s^2)."""
    a1 = (shafts.m1 - sense * shafts.capacity) / shafts.j1
    a2 = 0.0 if shafts.brake else (shafts.m2 + sense * shafts.capacity) / shafts.j2
    return a1, a2


def engagement(shafts: Shafts, file=None) -> Engagement:
    """Slip time, common speed, dissipated energy and locked motion of constant torques
    (the closed form of the module's docstring).  Refused (:class:`ClutchError`, exit 3) when
    the speeds never become equal: the relative speed does not close."""
    gap = shafts.w1 - shafts.w2
    sense = 1.0 if gap >= 0 else -1.0
    a1, a2 = slip_rates(shafts, sense)
    closing = -sense * (a1 - a2)
    if gap == 0:
        closing = math.inf
    if closing <= 0:
        raise never_engages(shafts, a1, a2, file)
    time = abs(gap) / closing
    speed = shafts.w1 + a1 * time
    energy = shafts.capacity * abs(gap) * time / 2
    accel, torque = transmitted(shafts)
    return Engagement(time, speed, energy, a1, a2, accel, torque)


def transmitted(shafts: Shafts) -> tuple[float, float]:
    """(w', C_t) of the locked shafts: (M1 + M2) / (J1 + J2) and the torque the clutch
    passes, (J2 M1 - J1 M2) / (J1 + J2); for a brake, w' = 0 and C_t = M1 (the brake holds
    the shaft)."""
    if shafts.brake:
        return 0.0, shafts.m1
    total = shafts.j1 + shafts.j2
    return (shafts.m1 + shafts.m2) / total, (shafts.j2 * shafts.m1 - shafts.j1 * shafts.m2) / total


def holds(shafts: Shafts, torque: float) -> bool:
    """Whether the clutch holds the torque ``torque`` it must pass: |C_t| <= C (to 1e-12 of
    C, the rounding of the quotients)."""
    return abs(torque) <= shafts.capacity * (1 + 1e-12)


def never_engages(shafts: Shafts, a1: float, a2: float, file=None) -> ClutchError:
    """The refusal of a slip that cannot end: the speeds' rates with their numbers."""
    what = "brake" if shafts.brake else "clutch"
    side = "the shaft" if shafts.brake else "the two shafts"
    detail = (f"the {what} torque C = {shafts.capacity:.6g} N m can never equalise the speeds "
              f"of {side}: slipping, w1' = {a1:.6g} rad/s^2" +
              ("" if shafts.brake else f" and w2' = {a2:.6g} rad/s^2") +
              f" from w1 = {shafts.w1:.6g} rad/s" +
              ("" if shafts.brake else f", w2 = {shafts.w2:.6g} rad/s") +
              ", so the relative speed does not close")
    hint = ("the load on the driven side exceeds the clutch torque, or the motor side "
            "decelerates faster: raise the clutch torque or lower the loads") if not \
        shafts.brake else "the torque on the shaft exceeds the brake torque: raise the brake torque"
    return ClutchError(detail, file=file, hint=hint, reason="never engages",
                       values={"C": shafts.capacity, "a1": a1, "a2": a2})


def slips_again(shafts: Shafts, torque: float, time: float, file=None) -> ClutchError:
    """The refusal of a locked motion whose transmitted torque exceeds the capacity."""
    what = "brake" if shafts.brake else "clutch"
    return ClutchError(
        f"after engagement at t = {time:.6g} s the {what} would pass C_t = {torque:.6g} N m, "
        f"above its capacity C = {shafts.capacity:.6g} N m: it slips again, and the shafts do "
        "not turn together", file=file, reason="slips again",
        hint=f"raise the {what} torque above |C_t|, or ask only for the slip",
        values={"C": shafts.capacity, "C_t": torque, "t": time})
