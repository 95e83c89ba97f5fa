"""When a computed value is the rounding noise of a zero.

A value is 0 when its magnitude is under NOISE times the scale of the values it
sits among (both in one unit): the cancellation of terms of that scale leaves a
rounding error of some 1e-16 of it, so 1e-12 leaves four orders of magnitude for
the terms' own rounding and never hides a value an answer prints (a millionth of
the last decimal of a value of that scale is far above it).
"""
from __future__ import annotations

import numpy as np

# a value smaller than this fraction of its scale is the rounding noise of a zero
NOISE = 1e-12


def noise_free(value, scale):
    """``value`` with what is rounding noise of a zero beside ``scale`` (|value| < NOISE
    scale, both in one unit) set to 0 (never -0.0): a float for a scalar, else an array."""
    value = np.asarray(value, dtype=float)
    out = np.where(np.abs(value) < NOISE * np.asarray(scale, dtype=float), 0.0, value) + 0.0
    return float(out) if out.ndim == 0 else out
