"""The textbook's quantities (docs/schema.md, "quantities"), from the same positions,
velocities and accelerations as the angles: speeds |v|, tangential and normal accelerations
``Re(conj(v) a)/|v|`` and ``|Im(conj(v) a)|/|v|``, projections ``Re(conj(u) P)`` with rates
``Re(conj(u) v_P)``, rotations of bodies (``forces.motion``), instant centres
``I = P + i v_P / omega`` and velocity ratios (rates at a unit driver rate).  Where one is
undefined (a point at rest, a body that translates) it is a located SolveError, never NaN.
"""
from __future__ import annotations

import numpy as np

from linkcli.answers.quantities.geometry import override_unit, relative, signed_angle, \
    vector, wrap_angle
from linkcli.errors import SolveError
from linkcli.forces import motion
from linkcli.kinematics.branches import own_coordinates
from linkcli.kinematics.closed_form import unit_rates
from linkcli.kinematics.refusals import where_text
from linkcli.kinematics.solvers import solver_for
from linkcli.model.mechanism import FRAME, Quantity
from linkcli.input.quantities import LEVEL

#: a point is at rest (its velocity has no direction) where its speed is at most AT_REST
#: times the largest speed of the mechanism's points; a body translates where its angular
#: velocity is at most AT_REST times the largest rate of the mechanism (the largest angular
#: velocity of its bodies, or its largest speed over its size)
AT_REST = 1e-9
#: the kinds of docs/schema.md's textbook quantities (speeds, projections, rotations ...)
TEXTBOOK = ("speed", "acceleration", "tangential_acceleration", "normal_acceleration",
            "along", "normal_to", "relative", "relative_speed", "relative_acceleration",
            "rotation", "between", "instant_centre", "instant_centre_distance", "reaction",
            "slider_force", "velocity_ratio", "least_speed", "least_speed_at", "tension",
            "contact_force")




class Context:
    """What several quantities of one evaluation share, computed once when first asked:
    the joint forces, the velocities per unit driver rate, the figure's positions, the
    mechanism's largest speed, size and angular velocity."""

    def __init__(self, mech, solver, kin):
        self.mech, self.solver, self.kin = mech, solver, kin
        self._cache = {}
        #: notes of the answers themselves (a mechanism that locks itself)
        self.notes = []

    def _once(self, key, make):
        if key not in self._cache:
            self._cache[key] = make()
        return self._cache[key]

    def _solver(self):
        return self.solver if self.solver is not None else solver_for(self.mech)

    def reactions(self):
        from linkcli.forces.joint_forces import solve
        return self._once("reactions", lambda: solve(self.mech, self.kin))

    def cautions(self) -> list:
        """The warnings of what was solved: the joint forces' (a contact that lifts off,
        another answer the friction admits), when they were."""
        reactions = self._cache.get("reactions")
        return (list(reactions.cautions) if reactions is not None else []) + self.notes

    def unit(self, j: int = 0):
        """The velocities for a unit rate of driver ``j`` (q' = 1; the others at rest) at the
        same positions."""
        return self._once(("unit", j), lambda: unit_rates(self._solver(), self.kin, j))

    def figure(self) -> dict:
        """The positions of the figure: solved at the file's own driver value."""
        return self._once("figure", lambda: self._solver().positions(
            own_coordinates(self.mech)).pos)

    def speed(self):
        """The largest speed of the mechanism's points, at each position (m/s)."""
        def make():
            top = 0.0
            for v in self.kin.vel.values():
                top = np.maximum(top, np.abs(v))
            return top
        return self._once("speed", make)

    def size(self) -> float:
        """The largest distance of a point from the first one (m), over the positions."""
        def make():
            pos = self.kin.pos
            first = pos[self.mech.points[0]]
            size = max(float(np.max(np.abs(np.asarray(pos[p] - first))))
                       for p in self.mech.points)
            return size if size > 0 else 1.0
        return self._once("size", make)

    def spin(self):
        """The largest rate of the mechanism: its bodies' angular velocities and its
        largest speed over its size (1/s), at each position."""
        def make():
            mech, kin = self.mech, self.kin
            top = self.speed() / self.size()
            for name in mech.bodies:
                top = np.maximum(top, np.abs(motion.rotation(mech, name, kin.pos, kin.vel)[0]))
            for disc in (mech.dynamics.discs.values() if mech.dynamics is not None else ()):
                top = np.maximum(top, np.abs(motion.disc_spin(mech, disc, kin.pos, kin.vel)[0]))
            return top
        return self._once("spin", make)


def textbook_value(quantity, order, kin, context):
    """(value, unit) of a textbook quantity's rate of ``order``, in display units."""
    mech = context.mech
    units = mech.units
    kind = quantity.kind
    if kind == "velocity_ratio":
        return velocity_ratio(quantity, context)
    value, base, level = si_value(quantity, order, kin, context)
    unit, factor = units.display(base, level)
    if quantity.unit:
        unit, factor = override_unit(quantity.unit, base, level)
    return np.asarray(value / factor + 0 * kin.q) + 0.0, unit


def si_value(quantity, order, kin, context):
    """(SI value, 'length' or 'angle', display order) of a quantity's rate of ``order``."""
    mech = context.mech
    kind, a, b = quantity.kind, quantity.a, quantity.b
    rates = (kin.pos, kin.vel, kin.acc)
    if kind == "q":
        return [kin.q, kin.qd, kin.qdd][order], mech.driver.base, order
    elif kind in ("x", "y"):
        z = rates[order].get(a, 0j)
        return (np.real(z) if kind == "x" else np.imag(z)), "length", order
    elif kind in ("angle", "length"):
        value, base = vector(quantity, kin, order)
        return value, base, order
    if kind in ("least_speed", "least_speed_at"):
        return _least_speed(quantity, kin, context)
    if kind in ("speed", "relative_speed"):
        v = rates[1].get(a, 0j) if kind == "speed" else relative(kin.vel, a, b)
        if order == 0:
            return np.abs(v), "length", 1
        acc = rates[2].get(a, 0j) if kind == "speed" else relative(kin.acc, a, b)
        _require_moving(quantity, v, kin, context, "its rate (the tangential acceleration)")
        return (np.conj(v) * acc).real / np.abs(v), "length", 2
    if kind in ("acceleration", "relative_acceleration"):
        acc = kin.acc.get(a, 0j) if kind == "acceleration" else relative(kin.acc, a, b)
        return np.abs(acc), "length", 2
    if kind in ("tangential_acceleration", "normal_acceleration"):
        v, acc = kin.vel.get(a, 0j), kin.acc.get(a, 0j)
        _require_moving(quantity, v, kin, context, f"its {kind.replace('_', ' ')}")
        part = (np.conj(v) * acc).real if kind == "tangential_acceleration" else \
            np.abs((np.conj(v) * acc).imag)
        return part / np.abs(v), "length", 2
    if kind in ("along", "normal_to"):
        z = kin.pos[b] - kin.pos[a]
        u = z / np.abs(z) * (1 if kind == "along" else 1j)
        moved = rates[order].get(quantity.c, 0j) if quantity.d is None else \
            relative(rates[order], quantity.c, quantity.d)
        return (np.conj(u) * moved).real, "length", order
    if kind == "relative":
        z = kin.pos[b] - kin.pos[a] if order == 0 else relative(rates[order], a, b)
        return (np.real(z) if quantity.component == "x" else np.imag(z)), "length", order
    if kind == "rotation":
        return _rotation(quantity, order, kin, context), "angle", order
    if kind == "between":
        if order == 0:
            z1, z2 = kin.pos[b] - kin.pos[a], kin.pos[quantity.d] - kin.pos[quantity.c]
            value = wrap_angle(np.angle(z2 * np.conj(z1)), principal=True)
            return (signed_angle(value) if quantity.signed else value), "angle", 0
        first = vector(Quantity("", "angle", a, b), kin, order)[0]
        second = vector(Quantity("", "angle", quantity.c, quantity.d), kin, order)[0]
        return second - first, "angle", order
    centre = _instant_centre(quantity, kin, context)
    if kind == "instant_centre":
        return (centre.real if quantity.component == "x" else centre.imag), "length", 0
    return np.abs(kin.pos[b] - centre), "length", 0


def located(quantity, mech, detail, hint=None, error=SolveError):
    return error(detail, file=mech.file, key=f"quantities.{quantity.name}", line=quantity.line,
                 hint=hint)


def _require_moving(quantity, v, kin, context, what):
    """Refuse a direction of motion where the point (or the relative motion) is at rest."""
    rest = np.abs(v) <= AT_REST * context.speed()
    if not np.any(rest):
        return
    mech = context.mech
    who = f"point {quantity.a}" if quantity.kind != "relative_speed" else \
        f"the motion of {quantity.b} relative to {quantity.a}"
    name = quantity.name + ("dot" if quantity.kind in LEVEL and LEVEL[quantity.kind] == 1 else "")
    raise located(quantity, mech, f"'{name}' is undefined "
                   f"{where_text(mech, kin.q, np.broadcast_to(rest, np.shape(kin.q)))}: {who} "
                   f"is at rest there (its velocity is 0), so {what} has no direction",
                   hint="move the driver away from that position, or give the driver a rate")


def _spinning(quantity, context):
    """(the body's name for forces.motion, or the Disc) of a rotation or an instant centre."""
    mech = context.mech
    if quantity.of == "disc":
        return None, mech.dynamics.discs[quantity.a]
    if quantity.of == "rolling":
        return mech.rolling[quantity.a].disc, None
    if quantity.of == "actuator":
        return quantity.a + ".cylinder", None
    return quantity.a, None


def _rotation(quantity, order, kin, context):
    """The body's angle (its axis: first to second point, the guide of a slider, a to b of
    an actuator; a disc of dynamics: discs: from the figure) and its rates omega, alpha."""
    mech = context.mech
    body, disc = _spinning(quantity, context)
    if disc is None:
        if order == 0:
            z = motion.axis_vector(mech, body, kin.pos)
            value = wrap_angle(np.angle(z), principal=True)
            return signed_angle(value) if quantity.signed else value
        omega, alpha = motion.rotation(mech, body, kin.pos, kin.vel,
                                       kin.acc if order == 2 else None)
        return omega if order == 1 else alpha
    if order == 0:
        guide = mech.bodies[disc.slider].guide
        z = motion.guide_axis(mech, guide, kin.pos)
        travel = (np.conj(z / np.abs(z)) * (kin.pos[disc.center] -
                                             context.figure()[disc.center])).real
        value = wrap_angle(-disc.side / disc.radius * travel)
        return signed_angle(value) if quantity.signed else value
    omega, alpha = motion.disc_spin(mech, disc, kin.pos, kin.vel,
                                    kin.acc if order == 2 else None)
    return omega if order == 1 else alpha


def _instant_centre(quantity, kin, context):
    """I = P + i v_P / omega of the body, P any of its points; relative to another body
    (``quantity.b``, Kennedy's I_jk), I = P + i (v_P - v'_P) / (omega - omega') with v'_P the
    velocity of the other body's point at P; refused where the relative motion translates."""
    mech = context.mech
    point, omega = _spin_at(mech, *_spinning(quantity, context), kin)
    moving = kin.vel.get(point, 0j)
    relative = quantity.kind == "instant_centre" and quantity.b not in (None, FRAME)
    if relative:                     # (the b of an instant_centre_distance is its point)
        other = Quantity("", "instant_centre", quantity.b, of=quantity.c)
        anchor, turn = _spin_at(mech, *_spinning(other, context), kin)
        moving = moving - kin.vel.get(anchor, 0j) - 1j * turn * (kin.pos[point] -
                                                                  kin.pos[anchor])
        omega = omega - turn
    still = np.abs(omega) <= AT_REST * context.spin()
    if np.any(still):
        what = f"body {quantity.a}" + (f" relative to {quantity.b}" if relative else "")
        raise located(quantity, mech, f"'{quantity.name}' is undefined "
                       f"{where_text(mech, kin.q, np.broadcast_to(still, np.shape(kin.q)))}: "
                       f"{what} does not turn there (omega = 0: it translates, or the "
                       "mechanism is at rest), so it has no instant centre",
                       hint="ask for a body that turns, or move the driver")
    return kin.pos[point] + 1j * moving / omega


def _least_speed(quantity, kin, context):
    """The point of least speed on the line through points a, b of one body, P(t) = A + t u
    (u the unit vector of A -> B): v(t) = v_A + i omega t u, omega = Im((v_B - v_A)/(B - A)),
    least at t* = -Re(conj(v_A) i omega u) / omega^2 (the foot of the perpendicular from
    the instant centre); 'least_speed' is |v(t*)| (|v_A| for a body that translates),
    'least_speed_at' is t*, refused where the body translates (every point moves alike)."""
    mech = context.mech
    a, b = quantity.a, quantity.b
    z = kin.pos[b] - kin.pos[a]
    u = z / np.abs(z)
    v_a = kin.vel.get(a, 0j)
    omega = (relative(kin.vel, a, b) / z).imag
    still = np.abs(omega) <= AT_REST * context.spin()
    safe = np.where(still, 1.0, omega)
    t = -(np.conj(v_a) * 1j * safe * u).real / (safe * safe)
    if quantity.kind == "least_speed":
        return np.where(still, np.abs(v_a), np.abs(v_a + 1j * omega * t * u)), "length", 1
    if np.any(still):
        raise located(quantity, mech, f"'{quantity.name}' is undefined "
                       f"{where_text(mech, kin.q, np.broadcast_to(still, np.shape(kin.q)))}: "
                       f"the body of {a} and {b} does not turn there, so all its points move "
                       "alike and none has the least speed",
                       hint="move the driver, or ask for least_speed alone")
    return t, "length", 0


def _spin_at(mech, body, disc, kin):
    """(a point of the body, its angular velocity): a link's first point, a disc's centre."""
    if disc is None:
        return mech.bodies[body].points[0], motion.rotation(mech, body, kin.pos, kin.vel)[0]
    return disc.center, motion.disc_spin(mech, disc, kin.pos, kin.vel)[0]


def velocity_ratio(quantity, context):
    """d(NAME)/dq = NAMEdot / qdot: NAME's rate at a unit driver rate, in NAME's unit per
    driver unit; of the driver named ``b`` (the others at rest) with several drivers."""
    mech = context.mech
    units = mech.units
    target = mech.quantities[quantity.a]
    j = mech.driver_index(quantity.b)
    value, base, _ = si_value(target, 1, context.unit(j), context)
    unit, factor = units.display(base, 0)
    if target.unit:
        unit, factor = override_unit(target.unit, base, 0)
    q_unit, q_factor = units.display(mech.coordinates[j].base, 0)
    return np.asarray(value * q_factor / factor + 0 * context.kin.q) + 0.0, f"{unit}/{q_unit}"
