"""Toggles: when a computed number is zero up to rounding, and where a group's conditioning
touches zero between two driver values.

Zero up to rounding.  A number computed from terms of magnitude S carries a rounding error
of a few eps S (eps = 2.2e-16, the spacing of doubles at 1); one rule says when it is
indistinguishable from zero: |x| <= TOGGLE S, TOGGLE = 1024 eps = 2.3e-13.  The caller
states S, the rounding the number carries, in the number's own unit:

- a dyad's discriminant (``dyads``): S from the magnitudes of its terms and of the points'
  coordinates; zero is an exact toggle, whose square root is rounding noise;
- a quantity's rate over the driver (``runs.limits.search``): S = the quantity's scale per
  radian of the driver, times the amplification 1 / m^(k + 1) the solve gives the rounding
  of a rate of order k at a position whose conditioning is m; zero at every sample is a
  quantity constant up to rounding, whose extremes are the constant itself.

Locating a toggle.  A group's conditioning m(q) (the sine of the angle between its
constraint normals; for Newton |det J| over the product of the row norms) falls to zero at
a toggle like c |q - q*|, on either branch that leaves it (at a change point the two
branches' conditionings are mirror images).  :func:`locate` samples the interval again,
REFINE times closer around the smallest m, until the interval is narrower than TIP (rad
of an angle driver, or of the mechanism's size for a length driver): bisection on the
conditioning itself, whatever path a solver took to each sample, so the answer does not
depend on the processor's rounding.  The tip is then known to within the rounding of m
near it: m below its noise floor (about 1e-8 for Newton, which finds a toggle's position
only to about sqrt(eps); 0 within the dyads' flat band of about 5e-7 rad, whose middle is
taken) spans |q - q*| <~ 1e-8 / c.  docs/errors.md states the accuracy: 1e-6 rad.
"""
from __future__ import annotations

import numpy as np

EPS = float(np.finfo(float).eps)
#: a number within TOGGLE of zero, relative to the rounding it carries, is zero
TOGGLE = 1024 * EPS
#: a located toggle's interval is narrower than TIP (rad, or of the mechanism's size)
TIP = 1e-9
#: each zoom samples the interval REFINE times closer; MOST_ZOOMS bounds the zooms
REFINE = 16
MOST_ZOOMS = 40


def negligible(value, scale):
    """Whether ``value`` is zero up to the rounding it carries: |value| <= TOGGLE scale,
    ``scale`` the magnitude of the terms it is computed from (elementwise)."""
    return np.abs(value) <= TOGGLE * scale


def locate(measure_at, lo: float, hi: float, width: float, threshold: float):
    """The driver value (between ``lo`` and ``hi``) where the conditioning touches zero, or
    None where it does not: a smooth minimum above ``threshold``, a smallest conditioning at
    an end of the interval, or a value that cannot be solved.

    ``measure_at(q)`` gives the conditioning at the driver values ``q`` (an array), None
    when one of them cannot be solved; ``width`` is TIP in the units of q; ``threshold``
    the solver's singular conditioning, above the rounding of its positions next to a
    toggle.  Each zoom keeps the samples next to the smallest conditioning; a V tip passes
    the test of :func:`v_tip` at every zoom, a smooth minimum m* + a x^2 fails it once the
    samples are closer than sqrt(m*/a).  Where the conditioning falls below ``threshold``
    it is rounding: the zooms go on until that band spans half the samples, and its middle
    is the toggle (the band is symmetric about it to first order: m = c |q - q*|), found to
    a sixteenth of the band's width."""
    lo, hi = float(lo), float(hi)
    for _ in range(MOST_ZOOMS):
        q = np.linspace(lo, hi, REFINE + 1)
        m = measure_at(q)
        if m is None:
            return None
        below = np.nonzero(m < threshold)[0]
        if below.size:
            i, j = int(below[0]), int(below[-1])
            if 0 < i and j < REFINE and j - i >= REFINE // 2:
                return float(0.5 * (q[i] + q[j]))
        else:
            least = float(np.min(m))
            at = np.nonzero(m == least)[0]
            i, j = int(at[0]), int(at[-1])
            if i == 0 or j == REFINE or not v_tip(m[i - 1], least, m[j + 1]):
                return None
        lo, hi = float(q[max(i - 1, 0)]), float(q[min(j + 1, REFINE)])
        if abs(hi - lo) <= width:
            return float(0.5 * (q[i] + q[j]))
    return float(0.5 * (lo + hi))


def v_tip(m0, m1, m2) -> bool:
    """Whether three samples m0 > m1 <= m2, equally spaced, dip in a V towards zero.

    Near a toggle m behaves like c |q - q*|; then m1 <= (m0 + m2) / 4 (m1 = 0 at q*); the
    bound used, (m0 + m2) / 3, also flags a smooth minimum m* + a x^2 whose depth m* is
    under 2 a step^2, i.e. zero within the sampling."""
    total = m0 + m2
    return bool(total > 0 and m1 <= total / 3)
