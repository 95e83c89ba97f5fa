"""Closed-form positions of the dyads, vectorised over driver values.

Points are complex arrays.  ``cross(a, b) = Im(conj(a) b)``.  A line is the
set of P with ``cross(C - B, P - B) = value``: direction ``u = (C - B)/|C - B|``
and signed offset ``e = value/|C - B|`` to the left of B->C.

Each solver returns ``(P, short)``: ``short`` is the length by which the
links fail to close (> 0 means the dyad cannot be assembled there; the
position returned is then the nearest, toggle-like one), the number 0.0 where
every position closes.  A discriminant that is
negative only by rounding is treated as zero, so a toggle position returns a
clean point, never NaN.

With ``flat=True`` they also return where the discriminant is zero within the
rounding it carries (TOGGLE times the magnitudes its terms and the points'
coordinates bring): an exact toggle, whose computed square root is rounding
noise of order sqrt(eps) and must not be mistaken for a regular position; the
value False when no discriminant comes near.
"""
from __future__ import annotations

import math

import numpy as np

# a discriminant within TOGGLE of zero, relative to the rounding it carries, is a toggle:
# ``toggles.negligible``, the one rule of "zero up to rounding" (limits use it too)
from linkcli.kinematics.toggles import EPS, TOGGLE, negligible  # noqa: F401 (compiled's)

ROUNDING = 64 * EPS


def cross(a, b):
    return (a.conjugate() * b).imag


def _root(disc, scale2):
    """sqrt of a discriminant; rounding-level negatives are a toggle (zero)."""
    gap = np.where(disc < -ROUNDING * scale2, -disc / scale2, 0.0)
    return np.sqrt(np.maximum(disc, 0.0)), gap


def _complex(re, im):
    """re + i im as a complex array, without the temporaries of ``re + 1j * im``."""
    out = np.empty(np.broadcast(re, im).shape, complex)
    out.real = re
    out.imag = im
    return out


def cis(angle):
    """e^{i angle} = cos + i sin (written straight into the complex result)."""
    angle = np.asarray(angle, dtype=float)
    out = np.empty(angle.shape, complex)
    np.cos(angle, out=out.real)
    np.sin(angle, out=out.imag)
    return out


def circle_circle(a, r1, b, r2, branch, flat=False):
    """P with |P - A| = r1, |P - B| = r2; branch +1 puts P left of A->B.

    a = (r1^2 - r2^2 + d^2) / 2d along A->B, h = sqrt(r1^2 - a^2) across it;
    computed as P = A + (B - A)(t + i branch s) with t = a/d, s = h/d.
    """
    d_vec = b - a
    d2 = np.asarray(d_vec.real * d_vec.real + d_vec.imag * d_vec.imag)
    least = d2.min()                    # NaN if any is NaN
    if least == 0:
        p, short = _circle_circle_safe(a, r1, b, r2, branch)
        return (p, short, np.abs(d2) == 0) if flat else (p, short)
    r1sq = r1 * r1
    t = (r1sq - r2 * r2 + d2) / (2.0 * d2)
    along2, across2 = t * t, r1sq / d2          # (a/d)^2 and (r1/d)^2
    e = across2 - along2
    lowest = e.min()
    negative = bool(lowest < 0)
    if negative:
        s, gap = _root(e, np.maximum(across2, along2))
        d = np.sqrt(d2)
        short = np.where(gap > 0, np.maximum(d - (r1 + r2), np.abs(r1 - r2) - d), 0.0)
    else:
        s, short = np.sqrt(e), 0.0
    p = a + d_vec * _complex(t, s if branch > 0 else -s)
    if not flat:
        return p, short
    if not negative:                    # e >= 0: the noise is below this bound everywhere
        least = float(least)
        top = _top(r1)
        if _clear(lowest, TOGGLE * top * top / least * (1.0 + _reach(a, b, d2) /
                                                    math.sqrt(least))):
            return p, short, False
    reach = (np.abs(a) + np.abs(b)) / np.sqrt(d2)          # coordinates against the span
    return p, short, negligible(e, np.maximum(across2, along2) * (1.0 + reach))


def _reach(a, b, d2) -> float:
    """A bound of max|A| + max|B|: where one centre is fixed, from it and the largest span
    (|B| <= |A| + |B - A|), which spares the magnitudes of the moving one."""
    if type(a) is np.ndarray and type(b) is np.ndarray:
        return _top(a) + _top(b)
    return 2.0 * (_top(b) if type(a) is np.ndarray else _top(a)) + math.sqrt(float(d2.max()))


def _circle_circle_safe(a, r1, b, r2, branch):
    """circle_circle where the centres may coincide (no intersection is defined there)."""
    d_vec = b - a
    d = np.abs(d_vec)
    d_safe = np.where(d > 0, d, 1.0)
    along = (r1 * r1 - r2 * r2 + d * d) / (2 * d_safe)
    h, gap = _root(r1 * r1 - along * along, np.maximum(r1 * r1, along * along))
    unit = d_vec / d_safe
    p = a + (along + 1j * branch * h) * unit
    short = np.where(gap > 0, np.maximum(d - (r1 + r2), np.abs(r1 - r2) - d), 0.0)
    short = np.where(d > 0, short, np.where(np.abs(r1 - r2) > 0, np.abs(r1 - r2), np.inf))
    return p, short


def line_frame(b, c, value):
    """Direction u and left offset e of the line cross(C - B, P - B) = value."""
    bc = c - b
    n = np.abs(bc)
    return bc / n, value / n


def circle_line(a, r, b, c, value, branch, flat=False, frame=None):
    """P with |P - A| = r on the line (B, C, value); branch +1 is ahead along u.

    P = B + i e u + (t0 + branch sqrt(r^2 - d^2)) u, with t0 the foot of A and
    d the distance of A from the line.  ``frame``: the line's (u, e), when known.
    """
    u, e = line_frame(b, c, value) if frame is None else frame
    level = is_number(u, 1.0)                 # a guide along +x (no rotation to undo) ...
    rel = a if is_number(b, 0.0) else a - b   # ... through the origin (no shift)
    if not level:
        rel = rel * u.conjugate()
    dist = rel.imag if is_number(e, 0.0) else rel.imag - e
    disc = dist * dist
    if writable(disc, r):
        np.subtract(r * r, disc, out=disc)
    else:
        disc = r * r - disc
    lowest = disc.min() if type(disc) is np.ndarray else disc
    negative = bool(lowest < 0)
    if negative:
        s, gap = _root(disc, np.maximum(r * r, dist * dist))
        short = np.where(gap > 0, np.abs(dist) - r, 0.0)
    else:
        s, short = np.sqrt(disc), 0.0
    if writable(s, rel):
        along = np.add(rel.real, s, out=s) if branch > 0 else np.subtract(rel.real, s, out=s)
    else:
        along = rel.real + s if branch > 0 else rel.real - s
    p = _complex(along, e)
    if not level:
        p = p * u
    if not is_number(b, 0.0):
        p = b + p
    if not flat:
        return p, short
    if not negative:                    # |d| <= r: every noise below the bound
        top = _top(r)
        if _clear(lowest, TOGGLE * (top * top + top * (_top(a) + _top(b) + _top(e) + top))):
            return p, short, False
    # the rounding carried, r^2 + |d| (|A| + |B| + |e| + r), with the operations in place
    scale = np.abs(a)
    if writable(scale, b, e, r, dist):
        scale += np.abs(b)
        scale += np.abs(e)
        scale += r
        scale *= np.abs(dist)
        scale += r * r
    else:
        scale = r * r + np.abs(dist) * (scale + np.abs(b) + np.abs(e) + r)
    return p, short, negligible(disc, scale)


def is_number(x, value) -> bool:
    """Whether ``x`` is the number ``value`` (not an array): an operation with it may be
    skipped (multiplying by 1, adding 0 change no finite value)."""
    return type(x) in (float, complex) and x == value


def _top(x) -> float:
    """The largest magnitude of ``x`` (an array or a number)."""
    return float(np.abs(x).max()) if type(x) is np.ndarray else abs(x)


def _clear(lowest, bound) -> bool:
    """Whether no discriminant (all >= 0, the least being ``lowest``) is within ``bound``,
    a bound of the rounding each carries: then none is a toggle.  Twice the bound covers
    the rounding of the bound itself; NaN anywhere says no (the exact test decides)."""
    return bool(lowest > 2.0 * bound)


def writable(x, *others) -> bool:
    """Whether an operation of ``x`` with the ``others`` can be written into ``x``: it is
    an array (not a number) whose shape each of them broadcasts into.  The caller
    passes only arrays it has just made."""
    if type(x) is not np.ndarray or not x.ndim:
        return False
    for o in others:
        if type(o) is not float and type(o) is not complex:
            shape = getattr(o, "shape", ())
            if shape and shape != x.shape:
                return False
    return True


def line_line(b1, u1, e1, b2, u2, e2):
    """Intersection of two lines given as (point B, unit direction u, left offset e)."""
    start = b1 + 1j * e1 * u1
    det = cross(u2, u1)
    parallel = np.abs(det) < ROUNDING
    t = (e2 - cross(u2, start - b2)) / np.where(parallel, 1.0, det)
    return start + t * u1, parallel


def slotted(b, length, a, value, branch, flat=False):
    """RPR: C with |C - B| = length and A on the line cross(C - B, A - B) = value.

    With A - B = rho e^{i psi} and C - B = length e^{i theta}:
    sin(psi - theta) = value / (length rho); branch +1 has A ahead of B along
    B->C (theta = psi - asin s), branch -1 behind it.  e^{i theta} is formed
    algebraically: e^{i psi} (c - i s) or -e^{i psi} (c + i s), c = sqrt(1 - s^2).
    """
    w = a - b
    rho = np.abs(w)
    rho_safe = np.where(rho > 0, rho, 1.0)
    s = value / (length * rho_safe)
    short = np.where(np.abs(s) > 1 + ROUNDING, np.abs(value) / length - rho, 0.0)
    s = np.clip(s, -1.0, 1.0)
    c = np.sqrt((1.0 - s) * (1.0 + s))
    unit = np.where(rho > 0, w / rho_safe, 1.0)
    rot = _complex(c, -s) if branch > 0 else _complex(-c, -s)
    p = b + length * (unit * rot)
    if not flat:
        return p, short
    reach = (np.abs(a) + np.abs(b)) / rho_safe
    return p, short, negligible(1.0 - np.abs(s), 1.0 + reach)
