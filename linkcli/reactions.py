"""Joint reactions by Newton-Euler, and the inverse-dynamics power balance.

For every moving body (d'Alembert form, moments about the body's first point O)

    sum F + m (g - a_G) = 0,      sum (r - O) x F + M - J alpha = 0,

and for every pin p (a massless point where bodies meet; point masses and
forces applied at p act on it)

    - sum_b R_pb + F_p + m_p (g - a_p) = 0,

with unknowns: ``R_pb`` the force pin p exerts on body b (the frame included
at fixed pivots); per slider the normal force N (on the block, along the left
normal n = i u of the guide direction u) and the moment M (on the block), the
friction force ``T = -mu sgn(v_rel) |N|`` along u; per actuator N and M of its
sliding pair; per rolling disc the contact forces T (along u) and N (along the
normal from the ground to the centre) at the contact point; and the one unknown
load.  Grübler's count n = 1 makes the system square.  It is solved at every
driver value at once (stacked matrices).  With friction the sign of N is found by
iteration (assume, solve, check).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import dynamics as dyn_mod
from .dyads import cross
from .errors import SingularError, SolveError
from .model import FRAME
from .statics import unknown_load

COND_LIMIT = 1e12


@dataclass
class PairForce:
    """Forces of one sliding pair (slider, actuator) or rolling contact, on the moving part."""

    name: str
    kind: str             # 'slider' | 'actuator' | 'disc'
    normal: object        # N (N), along ``n``
    moment: object        # M (N m), on the block / rod; 0 for a disc contact
    friction: object      # T (N), along ``u``
    u: object             # unit direction of the guide / actuator (complex)
    n: object             # unit normal direction (complex)
    at: object            # point of application (complex, m)
    on: str = ""          # body that receives these forces
    carrier: str = ""     # body that receives the opposite


@dataclass
class Reactions:
    """Solved joint forces (SI); arrays over the driver values."""

    mech: object
    kin: object
    pins: dict = field(default_factory=dict)     # (point, body) -> force of the pin on the body
    pairs: dict = field(default_factory=dict)    # name -> PairForce
    unknown: object = None                       # value of the unknown load (SI)
    loads: dict = field(default_factory=dict)    # every load's value (SI)


# --- the equations -------------------------------------------------------------------
class _System:
    def __init__(self, mech, dyn, kin):
        self.mech, self.dyn, self.kin = mech, dyn, kin
        self.pos = kin.pos
        self.shape = np.shape(kin.q)
        self.bodies = list(mech.bodies)
        self.rows = {}
        row = 0
        for b in self.bodies:
            self.rows[b] = row
            row += 3
        self.pin_bodies = _pin_bodies(mech)
        for p in self.pin_bodies:
            self.rows[("pin", p)] = row
            row += 2
        self.n_rows = row
        self.columns = []          # (kind, key, part)
        for p, bodies in self.pin_bodies.items():
            for b in bodies:
                self.columns += [("pin", (p, b), 0), ("pin", (p, b), 1)]
        self.pairs = _pairs(mech, dyn)
        for name, _ in self.pairs:
            self.columns += [("pair", name, 0), ("pair", name, 1)]
        self.columns.append(("unknown", None, 0))
        self.index = {c: i for i, c in enumerate(self.columns)}
        self.length = _length_scale(mech, self.pos)

    # building blocks: each adds a force or moment to a column of A or to the known part
    def new(self):
        return np.zeros(self.shape + (self.n_rows,))

    def body_force(self, vec, body, force, at):
        if body == FRAME:
            return
        r = self.rows[body]
        origin = self.pos[self.mech.bodies[body].points[0]]
        force = np.broadcast_to(force + 0j, self.shape)
        vec[..., r] += force.real
        vec[..., r + 1] += force.imag
        vec[..., r + 2] += np.broadcast_to(cross(at - origin + 0j, force), self.shape)

    def body_moment(self, vec, body, moment):
        if body != FRAME:
            vec[..., self.rows[body] + 2] += np.broadcast_to(moment, self.shape)

    def pin_force(self, vec, point, force):
        if ("pin", point) not in self.rows:      # a fixed point of no body: held by the frame
            return
        r = self.rows[("pin", point)]
        force = np.broadcast_to(force + 0j, self.shape)
        vec[..., r] += force.real
        vec[..., r + 1] += force.imag

    def apply_load(self, vec, load, value):
        """Add the effect of ``load`` with ``value`` (SI) to ``vec``."""
        mech, pos = self.mech, self.pos
        if load.kind == "force":
            self.pin_force(vec, load.target, load.direction * value)
        elif load.kind == "torque":
            target = load.target + ".cylinder" if load.target in mech.actuators else load.target
            self.body_moment(vec, target, value)
        elif load.kind == "axial":
            self.axial(vec, mech.actuators[load.target], value)
        else:
            d = mech.driver
            if d.kind == "angle":
                crank = next(b.name for b in mech.bodies.values()
                             if b.kind == "link" and d.a in b.points and d.b in b.points)
                self.body_moment(vec, crank, value)
            elif d.kind == "length":
                act = next((a for a in mech.actuators.values() if {a.a, a.b} == {d.a, d.b}), None)
                if act is not None:        # q = |AB| either way: Q pushes the ends apart
                    self.axial(vec, act, value)
                else:
                    z = pos[d.b] - pos[d.a]
                    u = z / np.abs(z)
                    self.pin_force(vec, d.b, u * value)
                    self.pin_force(vec, d.a, -u * value)
            else:
                self.pin_force(vec, d.a, (1.0 if d.kind == "x" else 1j) * value)

    def axial(self, vec, act, value):
        z = self.pos[act.b] - self.pos[act.a]
        u = z / np.abs(z)
        at = self.pos[act.b]
        self.body_force(vec, act.name + ".rod", u * value, at)
        self.body_force(vec, act.name + ".cylinder", -u * value, at)

    # the matrix --------------------------------------------------------------------------
    def matrix(self, fcoef):
        """A (shape + (n, n)): column j holds the equations' terms per unit unknown j.

        ``fcoef`` maps each slider with friction to -mu sgn(v_rel) s (s the assumed sign of N).
        """
        mech, pos = self.mech, self.pos
        n = len(self.columns)
        a = np.zeros(self.shape + (self.n_rows, n))
        for j, (kind, key, part) in enumerate(self.columns):
            vec = self.new()
            unit = 1.0 if part == 0 else 1j
            if kind == "pin":
                p, b = key
                self.body_force(vec, b, unit, pos[p])
                self.pin_force(vec, p, -unit)
            elif kind == "pair":
                pf = dict(self.pairs)[key]
                self.pair_column(vec, key, pf, part, fcoef.get(key, 0.0))
            else:
                self.apply_load(vec, mech.unknown_load(), 1.0)
            a[..., :, j] = vec
        return a

    def pair_column(self, vec, name, pf, part, fcoef):
        if pf.kind == "disc":
            force = pf.u if part == 0 else pf.n
            self.body_force(vec, pf.on, force, pf.at)
            return
        if part == 0:        # normal force (with its friction)
            force = pf.n + fcoef * pf.u
            self.body_force(vec, pf.on, force, pf.at)
            self.body_force(vec, pf.carrier, -force, pf.at)
        else:                # moment
            self.body_moment(vec, pf.on, 1.0)
            self.body_moment(vec, pf.carrier, -1.0)

    def known(self):
        """Terms of the known loads, gravity and inertia (moved to the right-hand side)."""
        mech, dyn, kin = self.mech, self.dyn, self.kin
        vec = self.new()
        for load in mech.loads.values():
            if load.value is not None:
                self.apply_load(vec, load, load.value)
        if dyn is None:
            return vec
        for mb in dyn.bodies.values():
            g, _, acc = dyn_mod.rigid_point(mech, mb.body, mb.center, kin.pos, kin.vel, kin.acc)
            _, alpha = dyn_mod.rotation(mech, mb.body, kin.pos, kin.vel, kin.acc)
            self.body_force(vec, mb.body, mb.mass * (dyn.gravity - acc), g)
            self.body_moment(vec, mb.body, -mb.inertia * alpha)
        for disc in dyn.discs.values():
            _, alpha = dyn_mod.disc_spin(mech, disc, kin.pos, kin.vel, kin.acc)
            c = kin.pos[disc.center]
            self.body_force(vec, disc.slider, disc.mass * (dyn.gravity - kin.acc.get(disc.center,
                                                                                       0.0)), c)
            self.body_moment(vec, disc.slider, -disc.inertia * alpha)
        for p, mass in dyn.masses.items():
            if p in self.pin_bodies:
                self.pin_force(vec, p, mass * (dyn.gravity - kin.acc.get(p, 0.0)))
        return vec

    def scales(self):
        """Row and column scales making the matrix dimensionless (moments / length)."""
        rows = np.ones(self.n_rows)
        for b in self.bodies:
            rows[self.rows[b] + 2] = 1.0 / self.length
        cols = np.ones(len(self.columns))
        for j, (kind, key, part) in enumerate(self.columns):
            moment = (kind == "pair" and part == 1 and dict(self.pairs)[key].kind != "disc") or \
                (kind == "unknown" and _unknown_is_moment(self.mech))
            if moment:
                cols[j] = self.length
        return rows, cols


def _unknown_is_moment(mech):
    load = mech.unknown_load()
    return load.kind == "torque" or (load.kind == "driver" and mech.driver.kind == "angle")


def _pin_bodies(mech) -> dict:
    """Point -> bodies meeting there (frame first at fixed pivots); points on moving bodies only."""
    out = {}
    for body in mech.bodies.values():
        for p in body.points:
            out.setdefault(p, [])
            out[p].append(body.name)
    pins = {}
    for p in sorted(out):
        bodies = out[p]
        pins[p] = ([FRAME] if p in mech.fixed else []) + bodies
    return pins


def _pairs(mech, dyn):
    """(name, PairForce template) of every sliding pair and rolling contact."""
    out = []
    for body in mech.bodies.values():
        if body.kind == "block":
            disc = dyn.disc_on(body.name) if dyn is not None else None
            out.append((body.name, PairForce(body.name, "disc" if disc else "slider", None, None,
                                             None, None, None, None, on=body.name,
                                             carrier=body.guide.carrier)))
    for act in mech.actuators.values():
        out.append((act.name, PairForce(act.name, "actuator", None, None, None, None, None, None,
                                        on=act.name + ".rod", carrier=act.name + ".cylinder")))
    return out


def _length_scale(mech, pos) -> float:
    """The mechanism's size: the largest distance of a point from the first one (m)."""
    first = pos[mech.points[0]]
    scale = max(float(np.max(np.abs(np.asarray(pos[p] - first)))) for p in mech.points)
    return scale if scale > 0 else 1.0


def _geometry(system):
    """Fill the direction, normal and point of application of every pair."""
    mech, dyn, pos = system.mech, system.dyn, system.pos
    filled = []
    for name, pf in system.pairs:
        if pf.kind == "actuator":
            act = mech.actuators[name]
            z = pos[act.b] - pos[act.a]
            u = z / np.abs(z)
            at = pos[act.b]
            n = 1j * u
        else:
            block = mech.bodies[name]
            z = dyn_mod.guide_axis(mech, block.guide, pos)
            u = z / np.abs(z)
            at = pos[block.points[0]]
            n = 1j * u
            if pf.kind == "disc":
                disc = dyn.disc_on(name)
                n = disc.side * 1j * u
                at = at - disc.radius * n
        filled.append((name, PairForce(name, pf.kind, None, None, None, u, n, at, pf.on,
                                       pf.carrier)))
    system.pairs = filled


# --- solving -------------------------------------------------------------------------
def solve(mech, kin) -> Reactions:
    """Joint reactions and the unknown load at the positions of ``kin``.

    ``kin`` needs positions; velocities with friction; accelerations with masses.
    """
    dyn = dyn_mod.model(mech)
    system = _System(mech, dyn, kin)
    _geometry(system)
    rhs = -system.known()
    friction = {} if dyn is None else {s: mu for s, mu in dyn.friction.items() if mu > 0}
    sigma = {s: np.sign(dyn_mod.sliding_velocity(mech, s, kin.pos, kin.vel)) for s in friction}
    signs = {s: np.ones(system.shape) for s in friction}
    x = None
    for attempt in range(2 + 2 * len(friction)):
        fcoef = {s: -friction[s] * sigma[s] * signs[s] for s in friction}
        x = _solve_stack(system, system.matrix(fcoef), rhs)
        if not friction:
            break
        new = {s: np.where(_normal(system, x, s) < 0, -1.0, 1.0) for s in friction}
        if all(np.array_equal(new[s], signs[s]) for s in friction):
            break
        signs = new                 # positions whose sign was right keep it
    else:
        raise SolveError("Coulomb friction at the sliders admits no consistent normal force "
                         "here (self-locking)", file=mech.file,
                         hint="reduce the friction coefficient or check the directions")
    return _unpack(system, x, friction, sigma, signs)


def _normal(system, x, slider):
    return x[..., system.index[("pair", slider, 0)]]


def _solve_stack(system, a, rhs):
    rows, cols = system.scales()
    scaled = a * rows[:, None] * cols[None, :]
    if not np.all(np.isfinite(scaled)):
        raise SingularError("the reactions are undefined here (non-finite geometry)",
                            file=system.mech.file)
    cond = np.linalg.cond(scaled)
    if np.any(~np.isfinite(cond) | (cond > COND_LIMIT)):
        worst = float(np.max(np.where(np.isfinite(cond), cond, np.inf)))
        raise SingularError(
            "the joint reactions are not determined at this position (the Newton-Euler system "
            f"is singular: dimensionless condition number {worst:.2e})", file=system.mech.file,
            measure=1.0 / worst if worst > 0 else 0.0,
            hint="a toggle position, or a structure whose forces are statically indeterminate")
    y = np.linalg.solve(scaled, (rhs * rows)[..., None])[..., 0]
    return y * cols


def _unpack(system, x, friction, sigma, signs) -> Reactions:
    mech = system.mech
    out = Reactions(mech, system.kin)
    for j, (kind, key, part) in enumerate(system.columns):
        if kind == "pin" and part == 0:
            out.pins[key] = x[..., j] + 1j * x[..., j + 1]
    for name, pf in system.pairs:
        first = x[..., system.index[("pair", name, 0)]]
        second = x[..., system.index[("pair", name, 1)]]
        if pf.kind == "disc":
            out.pairs[name] = PairForce(name, "disc", second, np.zeros_like(first), first, pf.u,
                                        pf.n, pf.at, pf.on, pf.carrier)
            continue
        fr = -friction[name] * sigma[name] * np.abs(first) if name in friction \
            else np.zeros_like(first)
        out.pairs[name] = PairForce(name, pf.kind, first, second, fr, pf.u, pf.n, pf.at, pf.on,
                                    pf.carrier)
    out.unknown = x[..., system.index[("unknown", None, 0)]]
    out.loads = {n: (load.value if load.value is not None else out.unknown)
                 for n, load in mech.loads.items()}
    return out


# --- inverse dynamics ------------------------------------------------------------------
def friction_power(mech, dyn, kin, unit_vel, reactions):
    """Power per unit driver rate of the friction forces: sum T v_rel,unit."""
    total = 0.0
    for slider, mu in dyn.friction.items():
        if mu > 0:
            v = dyn_mod.sliding_velocity(mech, slider, kin.pos, unit_vel)
            total = total + reactions.pairs[slider].friction * v
    return total


def dynamic_power(mech, kin, unit_kin):
    """Extra power per unit driver rate for the virtual-power statics: gravity, inertia
    forces and torques, torques on rolling discs and sliding friction."""
    dyn = dyn_mod.model(mech)
    if dyn is None:
        return 0.0
    extra = dyn_mod.inertia_gravity_power(mech, dyn, kin, unit_kin.vel) + \
        dyn_mod.disc_torque_power(mech, dyn, kin, unit_kin.vel)
    if any(mu > 0 for mu in dyn.friction.values()):
        extra = extra + friction_power(mech, dyn, kin, unit_kin.vel, solve(mech, kin))
    return extra


def kinematics(mech, q=None, method="closed", tol=None):
    """Positions, velocities and accelerations at driver value(s) ``q`` (SI; default
    the file's), with the file's rates, plus velocities per unit driver rate."""
    from .results import solver_for
    solver = solver_for(mech, method, tol)
    d = mech.driver
    q = d.value if q is None else q
    kin = solver.positions(q)
    solver.check(kin, velocities=False)
    solver.velocities(kin, d.rate)
    solver.check(kin, velocities=True)
    solver.accelerations(kin, d.accel)
    unit = solver.velocities(type(kin)(kin.q, pos=kin.pos), np.ones_like(kin.q))
    return kin, unit


# --- the power balance, written out --------------------------------------------------------
def balance(mech, q=None) -> dict:
    """Terms of dE/dt = W_motor - W_resistant - W_lost (W) at the file's position."""
    from .statics import coefficient
    dyn = dyn_mod.model(mech)
    kin, unit = kinematics(mech, q)
    extra = dynamic_power(mech, kin, unit)
    value = unknown_load(mech, kin.pos, unit.vel, extra_power=extra)
    rate = mech.driver.rate
    unknown = mech.unknown_load()
    motor = value * coefficient(mech, unknown, kin.pos, unit.vel) * rate
    known = 0.0
    for load in mech.loads.values():
        if load.value is not None:
            known = known + load.value * coefficient(mech, load, kin.pos, unit.vel) * rate
    known = known + dyn_mod.disc_torque_power(mech, dyn, kin, unit.vel) * rate
    lost = 0.0
    if any(mu > 0 for mu in dyn.friction.values()):
        lost = -friction_power(mech, dyn, kin, kin.vel, solve(mech, kin))
    return {"dEdt": dyn_mod.energy_rate(mech, dyn, kin), "motor": motor,
            "resistant": -(known + dyn_mod.gravity_power(mech, dyn, kin)), "lost": lost,
            "unknown": value, "E": dyn_mod.kinetic_energy(mech, dyn, kin.pos, kin.vel)}


def balance_lines(mech) -> list[str]:
    """The power balance of ``explain``: symbols, then numbers at the file's position."""
    dyn = dyn_mod.model(mech)
    if dyn is None:
        return []
    energy, rate, gravity = [], [], []
    for mb in dyn.bodies.values():
        b = mb.body
        if mb.mass:
            energy.append(f"1/2 m_{b} |v_G({b})|^2")
            rate.append(f"m_{b} a_G({b}) . v_G({b})")
            gravity.append(f"m_{b} g . v_G({b})")
        if mb.inertia:
            energy.append(f"1/2 J_{b} omega_{b}^2")
            rate.append(f"J_{b} alpha_{b} omega_{b}")
    for disc in dyn.discs.values():
        c, n = disc.center, disc.name
        energy.append(f"1/2 m_{n} |v_{c}|^2 + 1/2 J_{n} omega_{n}^2")
        rate.append(f"m_{n} a_{c} . v_{c} + J_{n} alpha_{n} omega_{n}")
        gravity.append(f"m_{n} g . v_{c}")
    for p, m in dyn.masses.items():
        energy.append(f"1/2 m_{p} |v_{p}|^2")
        rate.append(f"m_{p} a_{p} . v_{p}")
        gravity.append(f"m_{p} g . v_{p}")
    if not any(ld.value is None for ld in mech.loads.values()):
        return ["Power balance (inverse dynamics): no unknown load in this file",
                "  E = " + (" + ".join(energy) or "0"), "  dE/dt = " + (" + ".join(rate) or "0")]
    unknown = mech.unknown_load()
    loads = [ld for ld in mech.loads.values() if ld.value is not None]
    terms = {"force": lambda ld: f"{ld.name} . v_{ld.target}",
             "torque": lambda ld: f"{ld.name} omega_{ld.target}",
             "axial": lambda ld: f"{ld.name} d|{ld.target}|/dt",
             "driver": lambda ld: f"{ld.name} qdot"}
    resistant = [terms[ld.kind](ld) for ld in loads]
    if dyn.gravity:
        resistant += gravity
    lost = [f"mu_{s} |N_{s}| |v_{s},rel|" for s, mu in dyn.friction.items() if mu > 0]
    lines = ["Power balance (inverse dynamics): dE/dt = W_motor - W_resistant - W_lost",
             "  E = " + (" + ".join(energy) or "0"),
             "  dE/dt = " + (" + ".join(rate) or "0"),
             f"  W_motor = {terms[unknown.kind](unknown)}   (the unknown load)",
             "  W_resistant = -(" + (" + ".join(resistant) or "0") + ")",
             "  W_lost = " + (" + ".join(lost) or "0")]
    for disc in dyn.discs.values():
        lines.append(f"  rolling disc {disc.name}: omega_{disc.name} = "
                     f"{'-' if disc.side > 0 else '+'}(v_{disc.center} . u)/R, R = "
                     f"{disc.radius:g} m")
    if dyn.gravity:
        g = dyn.gravity
        lines.append(f"  g = ({g.real:.6g}, {g.imag:.6g}) m/s^2")
    terms_at = balance(mech)
    value = _display_load(mech, unknown, float(np.asarray(terms_at["unknown"])))
    watts = {k: f"{float(np.asarray(terms_at[k])) + 0.0:.6g} W"
             for k in ("dEdt", "motor", "resistant", "lost")}
    lines += [f"  at the file's position: dE/dt = {watts['dEdt']}, W_motor = {watts['motor']}, "
              f"W_resistant = {watts['resistant']}, W_lost = {watts['lost']}",
              f"  {unknown.name} = {value}"]
    return lines


def _display_load(mech, load, value) -> str:
    from .results import _load_unit_kind
    from .units import FORCE, TORQUE
    kind = _load_unit_kind(mech, load)
    unit = mech.units.names[kind]
    table = FORCE if kind == "force" else TORQUE
    return f"{value / table[unit]:.6g} {unit}"


# --- display --------------------------------------------------------------------------
def rows(reactions, index=None) -> list[tuple]:
    """(name, Fx, Fy, |F|, along, normal, unit note) rows in SI units at one position."""
    mech = reactions.mech
    pos = reactions.kin.pos
    out = []

    def pick(v):
        arr = np.asarray(v)
        return complex(arr.reshape(-1)[0 if index is None else index]) if arr.ndim else complex(arr)

    for (p, b), force in reactions.pins.items():
        f = pick(force)
        axis = _axis(mech, b, pos)
        along = normal = None
        if axis is not None:
            u = pick(axis)
            along, normal = (np.conj(u) * f).real, (np.conj(1j * u) * f).real
        kind = mech.bodies[b].kind if b != FRAME else "frame"
        what = {"block": "slider ", "cylinder": "", "rod": ""}.get(kind, "")
        out.append((f"{p} on {what}{b}", f.real, f.imag, abs(f), along, normal))
    for name, pf in reactions.pairs.items():
        u = pick(pf.u)
        n_val, t_val = pick(pf.normal).real, pick(pf.friction).real
        force = n_val * pick(pf.n) + t_val * u
        label = {"slider": f"slider {name} (guide on {pf.carrier})",
                 "actuator": f"actuator {name} (rod on cylinder)",
                 "disc": f"disc {name} (ground contact)"}[pf.kind]
        normal_along_n = (np.conj(1j * u) * force).real
        out.append((label, force.real, force.imag, abs(force), t_val, normal_along_n,
                    pick(pf.moment).real if pf.kind != "disc" else None))
    return out


def _axis(mech, body, pos):
    """Unit vector of a body's own x axis: link first -> second point, guide direction."""
    if body == FRAME:
        return None
    kind = mech.bodies[body].kind
    if kind == "link":
        b = mech.bodies[body]
        z = pos[b.points[1]] - pos[b.points[0]]
    elif kind == "block":
        z = dyn_mod.guide_axis(mech, mech.bodies[body].guide, pos)
    else:
        act = mech.actuators[body.rsplit(".", 1)[0]]
        z = pos[act.b] - pos[act.a]
    return z / np.abs(z)


def render(reactions, decimals: int = 1) -> str:
    """A text table of the joint reactions at the first driver value."""
    from tabulate import tabulate
    from .report import fmt
    mech = reactions.mech
    force_unit = mech.units.names["force"]
    torque_unit = mech.units.names["torque"]
    from .units import FORCE, TORQUE
    ff, tf = FORCE[force_unit], TORQUE[torque_unit]

    def num(v, factor):
        return "" if v is None else fmt(v / factor, decimals)

    body = []
    for row in rows(reactions):
        name, fx, fy, mag, along, normal = row[:6]
        moment = row[6] if len(row) > 6 else None
        body.append([name, num(fx, ff), num(fy, ff), num(mag, ff), num(along, ff),
                     num(normal, ff), num(moment, tf)])
    header = ["force on", f"Fx [{force_unit}]", f"Fy [{force_unit}]",
              f"|F| [{force_unit}]", "along", "normal", f"M [{torque_unit}]"]
    table = tabulate(body, headers=header, disable_numparse=True, stralign="right")
    note = ("Pins: force the pin exerts on the body, in frame axes and along/normal to the "
            "body's axis (first -> second point; the guide direction for sliders). Sliding pairs: "
            "force of the guide on the block (along = friction T, normal = N), M its moment "
            "about the slider point; discs: ground contact force (along the line, normal).")
    return "Joint reactions\n" + table + "\n" + note


def as_dict(reactions) -> dict:
    """Reactions at the first driver value in the file's force and torque units."""
    from .units import FORCE, TORQUE
    names = reactions.mech.units.names
    ff, tf = FORCE[names["force"]], TORQUE[names["torque"]]
    out = {}
    for row in rows(reactions):
        name, fx, fy, mag, along, normal = row[:6]
        entry = {"Fx": fx / ff, "Fy": fy / ff, "magnitude": mag / ff,
                 "along": None if along is None else along / ff,
                 "normal": None if normal is None else normal / ff}
        if len(row) > 6:
            entry["moment"] = None if row[6] is None else row[6] / tf
        out[name] = entry
    return {"force_unit": names["force"], "torque_unit": names["torque"], "joints": out}


def append_report(text: str, mech, form: str, decimals: int, method="closed", tol=None) -> str:
    """``text`` (a rendered report) with the joint reactions at the file's position added."""
    import json
    kin, _ = kinematics(mech, method=method, tol=tol)
    reactions = solve(mech, kin)
    if form == "json":
        data = json.loads(text)
        data["reactions"] = as_dict(reactions)
        return json.dumps(data, indent=2, allow_nan=True)
    if form == "csv":
        data = as_dict(reactions)
        lines = [text]
        for joint, entry in data["joints"].items():
            for part, value in entry.items():
                if value is not None:
                    unit = data["torque_unit"] if part == "moment" else data["force_unit"]
                    lines.append(f"{joint} {part},{value!r},{unit}")
        return "\n".join(lines)
    return text + "\n\n" + render(reactions, decimals)
