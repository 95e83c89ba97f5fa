"""Closed-form positions of the dyads, vectorised over driver values.

Points are complex arrays.  ``cross(a, b) = Im(conj(a) b)``.  A line is the
set of P with ``cross(C - B, P - B) = value``: direction ``u = (C - B)/|C - B|``
and signed offset ``e = value/|C - B|`` to the left of B->C.

Each solver returns ``(P, short)``: ``short`` is the length by which the
links fail to close (> 0 means the dyad cannot be assembled there; the
position returned is then the nearest, toggle-like one).  A discriminant that is
negative only by rounding is treated as zero, so a toggle position returns a
clean point, never NaN.
"""
from __future__ import annotations

import numpy as np

EPS = np.finfo(float).eps
ROUNDING = 64 * EPS


def cross(a, b):
    return (a.conjugate() * b).imag


def _root(disc, scale2):
    """sqrt of a discriminant; rounding-level negatives are a toggle (zero)."""
    gap = np.where(disc < -ROUNDING * scale2, -disc / scale2, 0.0)
    return np.sqrt(np.maximum(disc, 0.0)), gap


def circle_circle(a, r1, b, r2, branch):
    """P with |P - A| = r1, |P - B| = r2; branch +1 puts P left of A->B.

    a = (r1^2 - r2^2 + d^2) / 2d along A->B, h = sqrt(r1^2 - a^2) across it.
    """
    d_vec = b - a
    d = np.abs(d_vec)
    d_safe = np.where(d > 0, d, 1.0)
    along = (r1 * r1 - r2 * r2 + d * d) / (2 * d_safe)
    h, gap = _root(r1 * r1 - along * along, np.maximum(r1 * r1, along * along))
    unit = d_vec / d_safe
    p = a + (along + 1j * branch * h) * unit
    short = np.where(gap > 0, np.maximum(d - (r1 + r2), np.abs(r1 - r2) - d), 0.0)
    return p, short


def line_frame(b, c, value):
    """Direction u and left offset e of the line cross(C - B, P - B) = value."""
    bc = c - b
    n = np.abs(bc)
    return bc / n, value / n


def circle_line(a, r, b, c, value, branch):
    """P with |P - A| = r on the line (B, C, value); branch +1 is ahead along u.

    P = B + i e u + (t0 + branch sqrt(r^2 - d^2)) u, with t0 the foot of A and
    d the distance of A from the line.
    """
    u, e = line_frame(b, c, value)
    rel = (a - b) * u.conjugate()
    dist = rel.imag - e
    s, gap = _root(r * r - dist * dist, np.maximum(r * r, dist * dist))
    p = b + (1j * e + rel.real + branch * s) * u
    return p, np.where(gap > 0, np.abs(dist) - r, 0.0)


def line_line(b1, u1, e1, b2, u2, e2):
    """Intersection of two lines given as (point B, unit direction u, left offset e)."""
    start = b1 + 1j * e1 * u1
    det = cross(u2, u1)
    parallel = np.abs(det) < ROUNDING
    t = (e2 - cross(u2, start - b2)) / np.where(parallel, 1.0, det)
    return start + t * u1, parallel


def slotted(b, length, a, value, branch):
    """RPR: C with |C - B| = length and A on the line cross(C - B, A - B) = value.

    With A - B = rho e^{i psi} and C - B = length e^{i theta}:
    sin(psi - theta) = value / (length rho); branch +1 has A ahead of B along
    B->C (theta = psi - asin s), branch -1 behind it.
    """
    w = a - b
    rho = np.abs(w)
    s = value / (length * np.where(rho > 0, rho, 1.0))
    short = np.where(np.abs(s) > 1 + ROUNDING, np.abs(value) / length - rho, 0.0)
    alpha = np.arcsin(np.clip(s, -1.0, 1.0))
    psi = np.angle(w)
    theta = psi - alpha if branch > 0 else psi - np.pi + alpha
    return b + length * np.exp(1j * theta), short
