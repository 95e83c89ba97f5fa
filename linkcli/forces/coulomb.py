"""Coulomb losses in the joint forces: the answer reached by raising the losses from zero,
the other answers they admit, and the friction that locks the mechanism.

With losses the Newton-Euler matrix A depends on the sign s of each slider's and disc's
normal force N (|N| = s N) and on the direction e of each friction circle's pin force R
(|R| = e . R): A(t, s, e) = A_0 + sum_j c_j D_j, each loss factor c_j (a slider's
T/N = -mu t sgn(v_rel) s, a disc's M/N = -u_r t sgn(omega) s, a friction circle's couple
-rho t sgn(omega_rel) e_x or e_y per unit component of R) in one column, t the fraction
of the losses (:class:`LossMatrix`).

Coulomb friction may admit several consistent answers (a rod that wedges a slider: both
signs of N agree with the solution).  The answer given is the one reached by raising the
losses from zero (:func:`continued`): t from 0 (frictionless: one answer, whatever the
signs) to 1, keeping at each step the signs and directions of the last until the solution
says otherwise.  A normal force that passes zero changes its sign there, where its loss is
zero, so the answer is continuous in t; where det A at the same signs passes zero, the
answer goes through infinity and the losses lock the mechanism before they reach their
values (self-locking, refused at those driver values with the fraction where it locks).
With one loss and no friction circle the path is exact in two solves: N(t) = N_0 / (1 + t g s)
keeps its sign, and det A is linear in t.  The other consistent answers (:func:`others`,
every set of signs of up to SIGNS_SEARCHED normal forces) are named in a warning with
their numbers (:func:`other_caution`).
"""
from __future__ import annotations

import itertools
from dataclasses import replace

import numpy as np

from linkcli.errors import Caution, SelfLockingError
from linkcli.forces import friction
from linkcli.kinematics.refusals import where_text

#: the losses' iterate has converged when no unknown changes by more than this fraction of
#: the largest (scaled); the error left is of the order of its square
CONVERGED = 1e-10
#: iterates of the signs and directions at one fraction before they are declared inconsistent
MAX_ITERATIONS = 60
#: the losses are raised from zero to their values in STEPS equal steps
STEPS = 8
#: other consistent answers are looked for among every set of signs of at most this many
#: normal forces with a loss (2^6 solves)
SIGNS_SEARCHED = 6
#: the fraction where the friction locks the mechanism is found to LOCK_TOL
LOCK_TOL = 1e-6


class _Unit:
    """Loss factors of 1 in the one column ``target`` and 0 elsewhere: a column of A per unit
    factor, with what ``System.column`` reads of a ``friction.Losses``."""

    def __init__(self, target, pins):
        self.target, self.pins = target, pins

    def slider_factor(self, name):
        return 1.0 if self.target == ("pair", name, 0) else 0.0

    def disc_factor(self, name):
        return 1.0 if self.target == ("pair", name, 1) else 0.0

    def pin_factor(self, point, body, part):
        pin = self.pins.get(point)
        if pin is None or pin.other != body:
            return None
        return 1.0 if self.target == ("pin", (point, body), part) else 0.0


class LossMatrix:
    """The scaled matrix R A(losses) C = R (A_0 + sum_j c_j(losses) D_j) C (``System.scaled``),
    with A_0 (every factor 0) and the column terms D_j of a unit factor built and scaled
    once for a system: each matrix then costs a few array operations instead of assembling
    every column again."""

    def __init__(self, system, losses):
        self.system = system
        zero = _Unit(None, losses.pins)
        self.base = system.scaled(system.matrix(zero))
        rows, cols = system.scales()
        self.terms = []             # (column index, the factor of a Losses, R D_j C_j)
        for j, column in enumerate(system.columns):
            factor = _factor_of(system, column, losses)
            if factor is None:
                continue
            term = system.column(column, _Unit(column, losses.pins)) - \
                system.column(column, zero)
            self.terms.append((j, factor, term * rows * cols[j]))

    def __call__(self, losses, at=None):
        """A at every driver value, or at the one of index ``at``."""
        if at is not None:
            a = self.base[at].copy()
            for j, factor, term in self.terms:
                a[:, j] += np.broadcast_to(factor(losses), self.system.shape)[at] * term[at]
            return a
        a = self.base.copy()
        for j, factor, term in self.terms:
            a[..., :, j] += np.asarray(factor(losses))[..., None] * term
        return a


def _factor_of(system, column, losses):
    """The function giving ``column``'s loss factor from a Losses, None without a loss."""
    kind, key, part = column
    if kind == "pair":
        if system.pair[key].kind == "disc":
            return (lambda held: held.disc_factor(key)) if part == 1 and key in losses.discs \
                else None
        return (lambda held: held.slider_factor(key)) if part == 0 and key in losses.sliders \
            else None
    if kind == "pin":
        point, body = key
        pin = losses.pins.get(point)
        if pin is not None and pin.other == body:
            return lambda held: held.pin_factor(point, body, part)
    return None


# --- the answer raised from no friction ------------------------------------------------------
def continued(system, rhs, losses, matrix):
    """(x, losses): the joint forces reached by raising every loss from zero to its value,
    with the signs and directions that agree with them (module docstring), ``matrix`` the
    system's :class:`LossMatrix`; raises SelfLockingError naming the driver values where
    the losses lock the mechanism."""
    losses = losses.scaled(0.0)
    x = system.solve_scaled(matrix(losses), rhs)
    losses, _ = friction.update(losses, normals(system, x, losses), pin_forces(system, x, losses))
    if len(matrix.terms) == 1 and not losses.pins:
        done = _one_loss(system, rhs, losses, matrix, x)
        if done is not None:
            return done
    return _stepped(system, rhs, losses, matrix)


def _one_loss(system, rhs, losses, matrix, frictionless):
    """One loss, no friction circle: A(t) = A_0 + t c D e_j^T changes one column, so
    (Sherman-Morrison) N(t) = N_0 / (1 + t c g) and det A(t) = det A_0 (1 + t c g), g the
    j-th component of A_0^-1 D.  The answer at t = 1 with the frictionless signs is the one
    continued to where N(1) keeps N_0's sign; where it flips, 1 + t c g passed zero: the
    friction locks the mechanism.  None where rounding leaves the signs in doubt (the
    stepped path decides)."""
    at_one = losses.scaled(1.0)
    scaled = matrix(at_one)
    x = system.solve_scaled(scaled, rhs, check=False)
    (key,) = losses.signs
    n0, n1 = normals(system, frictionless, losses)[key], normals(system, x, at_one)[key]
    locked = np.broadcast_to((n0 * n1 < 0) | ~np.isfinite(n1), system.shape)
    if locked.any():
        raise locking(system, matrix, losses, locked, np.where(locked, 0.0, np.nan), 1.0)
    _, kept = friction.update(at_one, normals(system, x, at_one), {})
    if not kept:
        return None
    system.require_regular(scaled)
    return x, at_one


def _stepped(system, rhs, losses, matrix):
    """The path in STEPS steps of t: at each, the signs and directions iterated to agree
    (:func:`_consistent`).  Driver values where det A (the last signs) changes sign across
    a step, or whose signs find no agreement, stay at the last fraction reached while the
    others go on, and are refused together at the end."""
    shape = system.shape
    side = system.side(matrix(losses))
    reached = np.full(shape, np.nan)          # the fraction a locked driver value reached
    locked = np.zeros(shape, bool)
    x = None
    for step in range(1, STEPS + 1):
        t = np.where(locked, reached, step / STEPS)
        through = (system.side(matrix(losses.scaled(t))) != side) & ~locked
        reached[through] = (step - 1) / STEPS
        locked |= through
        t = np.where(locked, reached, step / STEPS)
        x, losses, failed = _consistent(system, rhs, losses.scaled(t), matrix, locked,
                                        final=step == STEPS)
        locked |= failed
        side = system.side(matrix(losses))
    if locked.any():
        raise locking(system, matrix, losses, locked, reached, 1.0 / STEPS)
    return x, losses


def _consistent(system, rhs, losses, matrix, locked, final=True):
    """(x, losses, failed) at the losses' fractions t, the signs s = sgn N and directions
    e = R / |R| iterated from ``losses``' until they agree with the solution (CONVERGED) at
    every driver value but the ``locked`` ones; ``failed`` marks those where they do not
    within MAX_ITERATIONS, kept at the signs they started from."""
    start, previous = losses, None
    changing = np.zeros(system.shape, bool)
    for _ in range(MAX_ITERATIONS):
        x = system.solve_scaled(matrix(losses), rhs, check=final and not locked.any())
        new, _ = friction.update(losses, normals(system, x, losses),
                                 pin_forces(system, x, losses))
        changing = np.zeros(system.shape, bool)
        for k in losses.signs:
            changing |= np.broadcast_to(new.signs[k] != losses.signs[k], system.shape)
        if losses.pins:
            changing |= ~settled(system, x, previous)
        changing &= ~locked
        if not changing.any():
            return x, losses, changing
        losses, previous = new, x
    signs = {k: np.where(changing, start.signs[k], losses.signs[k]) for k in losses.signs}
    losses = replace(losses, signs=signs)
    return system.solve_scaled(matrix(losses), rhs, check=False), losses, changing


def settled(system, x, previous):
    """At each driver value: no unknown changed by more than CONVERGED of the largest, in
    scaled units (False everywhere without a previous solution)."""
    if previous is None:
        return np.zeros(system.shape, bool)
    _, cols = system.scales()
    new, old = x / cols, previous / cols
    size = np.max(np.abs(new), axis=-1)
    return np.max(np.abs(new - old), axis=-1) <= CONVERGED * size


# --- self-locking ----------------------------------------------------------------------------
def locking(system, matrix, losses, rows, reached, step) -> SelfLockingError:
    """The self-locking error at the driver values ``rows``: where ``reached`` (a fraction
    of the losses) is a number, det A passed zero within ``step`` after it, and the first
    such driver value's fraction is found (:func:`_lock_point`); where it is NaN, no signs
    of the normal forces agreed with the solution."""
    mech, kin = system.mech, system.kin
    rows = np.broadcast_to(rows, np.shape(kin.q))
    reached = np.broadcast_to(reached, rows.shape)
    where = where_text(mech, kin.q, rows)
    grew = rows & np.isfinite(reached)
    given = losses.scaled(1.0).describe()
    lo = None
    if grew.any():
        first = np.unravel_index(int(np.argmax(grew)), grew.shape) if grew.shape else ()
        lo = _lock_point(system, matrix, losses, first, float(reached[first]),
                         float(reached[first]) + step)
        why = (f"the friction locks the mechanism {where} (self-locking): raising the losses "
               f"from zero, the joint forces grow without bound at {100 * lo:.4g} % of the "
               f"given values ({losses.scaled(lo).describe()})")
    else:
        why = (f"the friction forces admit no consistent joint forces {where} (self-locking): "
               "no signs of the normal forces agree with the solution")
    return SelfLockingError(f"{why}; given: {given}", file=mech.file, rows=rows, q=kin.q,
                            reached=lo, what=given,
                            hint="reduce the friction coefficients, rolling resistances or "
                            "friction circles, or check the directions")


def _lock_point(system, matrix, losses, at, lo, hi) -> float:
    """The fraction t in [lo, hi] of the losses where det A (the signs held at ``lo``) passes
    zero at the driver value of index ``at``: bisection on its sign, to LOCK_TOL."""
    hi = min(hi, 1.0)

    def sign(t):
        return np.linalg.slogdet(matrix(losses.scaled(t), at))[0]

    side = sign(lo)
    while hi - lo > LOCK_TOL:
        mid = 0.5 * (lo + hi)
        if sign(mid) == side:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


# --- the other consistent answers ------------------------------------------------------------
def others(system, rhs, losses, matrix, given):
    """[(rows, x, losses)]: the other sets of signs of the normal forces (each of the 2^n,
    n <= SIGNS_SEARCHED) with joint forces consistent with them at some driver values, the
    friction circles' directions iterated with them; ``rows`` marks those values.  Joint
    forces equal to the ``given`` answer to CONVERGED (:func:`settled`) are no other answer:
    a normal force of zero (no load across the guide) is consistent with either sign and
    its loss is zero with both."""
    keys = list(losses.signs)
    if not keys or len(keys) > SIGNS_SEARCHED:
        return []
    shape = system.shape
    found = []
    for combo in itertools.product((1.0, -1.0), repeat=len(keys)):
        same = np.ones(shape, bool)
        for k, c in zip(keys, combo):
            same &= np.broadcast_to(losses.signs[k] == c, shape)
        if same.all():
            continue
        trial = replace(losses, signs={k: np.full(shape, c) for k, c in zip(keys, combo)})
        solved = _with_signs(system, rhs, trial, matrix)
        if solved is None:
            continue
        x, trial, regular = solved
        normal = normals(system, x, trial)
        ok = ~same & regular & ~settled(system, x, given)
        for k, c in zip(keys, combo):
            ok &= np.broadcast_to(normal[k] * c >= 0, shape)
        if ok.any():
            found.append((ok, x, trial))
    return found


def _with_signs(system, rhs, losses, matrix):
    """(x, losses, regular rows) with the signs of ``losses`` kept and the friction circles'
    directions iterated to the solution; None where they do not settle."""
    previous = None
    for _ in range(MAX_ITERATIONS if losses.pins else 1):
        scaled = matrix(losses)
        x = system.solve_scaled(scaled, rhs, check=False)
        if not losses.pins or settled(system, x, previous).all():
            return x, losses, system.regular(scaled)
        losses = replace(losses, directions=friction.update(
            losses, {k: losses.signs[k] for k in losses.signs},
            pin_forces(system, x, losses))[0].directions)
        previous = x
    return None


def other_caution(system, x, losses, rows, other, other_losses) -> Caution:
    """The warning that names another consistent answer, with its numbers at the first
    driver value where there is one, next to the answer given."""
    mech, kin = system.mech, system.kin
    rows = np.broadcast_to(rows, np.shape(kin.q))
    first = np.unravel_index(int(np.argmax(rows)), rows.shape) if rows.shape else ()
    answer, alternative = (_answer_text(system, y, held, first) for y, held in
                           ((x, losses), (other, other_losses)))
    detail = (f"another set of joint forces is consistent with the friction "
              f"{where_text(mech, kin.q, rows)}: {alternative}, where raising the friction "
              f"from zero gives {answer} (the answer given): the friction can also wedge the "
              "mechanism, and which one happens depends on how the motion started")
    return Caution("friction", detail, mech.file)


def _answer_text(system, x, losses, at) -> str:
    """'T = ... N m, N = ... N at slider S' of a solution at the index ``at``, in the file's
    units."""
    mech = system.mech
    units = mech.units
    parts = []
    unknown = mech.unknown_load()
    if unknown is not None:
        kind = mech.load_unit_kind(unknown)
        value = float(np.asarray(system.value(x, ("unknown", None, 0)))[at])
        parts.append(f"{unknown.name} = {value / units.factor(kind):.6g} {units.names[kind]}")
    normal = normals(system, x, losses)
    for kind, name in losses.signs:
        value = float(np.asarray(normal[(kind, name)])[at])
        parts.append(f"N = {value / units.factor('force'):.6g} {units.names['force']} at "
                     f"{kind} {name}")
    return ", ".join(parts)


# --- reading the solution --------------------------------------------------------------------
def normals(system, x, losses) -> dict:
    """(kind, name) -> the normal force N of every slider and disc with a loss."""
    return {k: system.value(x, ("pair", k[1], 1 if k[0] == "disc" else 0)) for k in losses.signs}


def pin_forces(system, x, losses) -> dict:
    """point -> R, the force of every friction circle's pin on its ``other`` body."""
    return {p: pin_force(system, x, p, pin.other) for p, pin in losses.pins.items()}


def pin_force(system, x, point, body):
    """R: the force of pin ``point`` on ``body``."""
    return system.value(x, ("pin", (point, body), 0)) + \
        1j * system.value(x, ("pin", (point, body), 1))
