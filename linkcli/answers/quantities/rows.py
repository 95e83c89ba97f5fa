"""The rows of the plan's table: angles, lengths and coordinates of the kinematics (and
their rates) written straight into one preallocated (names x positions) array, the angles
all together (:class:`Angles`), each other row by a kernel of its own."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkcli.answers.quantities.geometry import TWO_PI, override_unit, vector_rate, \
    vector_rates, _wrap_principal
from linkcli.answers.quantities.textbook import TEXTBOOK
from linkcli.kinematics.compiled import ANGLE as ANGLE_PROBE, LENGTH as LENGTH_PROBE, \
    X as X_PROBE, Y as Y_PROBE
from linkcli.model.mechanism import split_rate


def row_of(mech, name):
    """(kernel, display unit) of ``name``: ``kernel(kin, out)`` writes the value in display
    units into ``out`` (an array of the driver values' shape); for an angle or its rates an
    :class:`AngleRow` instead, evaluated with the plan's other angles (:class:`Angles`);
    (None, None): the value and its unit come from :func:`value_of` (the driver, textbook
    kinds, loads)."""
    base_name, order = split_rate(name, mech.quantities)
    quantity = mech.quantities.get(base_name)
    if quantity is None or quantity.kind not in ("angle", "length", "x", "y") \
            or quantity.kind in TEXTBOOK:
        return None, None
    base = "angle" if quantity.kind == "angle" else "length"
    unit, factor = mech.units.display(base, order)
    if quantity.unit:
        unit, factor = override_unit(quantity.unit, base, order)
    a, b = quantity.a, quantity.b
    if quantity.kind in ("x", "y"):
        return CoordRow(a, quantity.kind == "x", order, factor), unit
    if base == "angle":
        return AngleRow(a, b, order, factor, quantity.signed and order == 0), unit
    return LengthRow(a, b, order, factor), unit


@dataclass(frozen=True)
class LengthRow:
    """A name that is the length of z = P_b - P_a (``order`` 0) or one of its rates (1, 2),
    in display units (SI over ``factor``): ``row(kin, out)`` writes it (:func:`vector`)."""

    a: str
    b: str
    order: int
    factor: float

    def __call__(self, kin, out):
        if self.order == 0:
            value = np.abs(vector_rates(kin, self.a, self.b, rate=False)[0])
        else:
            value = vector_rate(kin, self.a, self.b, self.order, False)
        _put(value, self.factor, kin, out)


@dataclass(frozen=True)
class CoordRow:
    """A name that is the x (``real``) or y of point ``a`` (``order`` 0) or one of its rates
    (1, 2), in display units (SI over ``factor``): ``row(kin, out)`` writes it."""

    a: str
    real: bool
    order: int
    factor: float

    def __call__(self, kin, out):
        z = (kin.pos, kin.vel, kin.acc)[self.order].get(self.a, 0j)
        _put(np.real(z) if self.real else np.imag(z), self.factor, kin, out)


def probe_of(row):
    """(kind, a, b, order, factor, signed) of a compiled solve's probe for a name's row
    (:class:`AngleRow`, :class:`CoordRow`, :class:`LengthRow`), None for another."""
    if isinstance(row, AngleRow):
        return ANGLE_PROBE, row.a, row.b, row.order, row.factor, row.signed
    if isinstance(row, CoordRow):
        return X_PROBE if row.real else Y_PROBE, row.a, None, row.order, row.factor, False
    if isinstance(row, LengthRow):
        return LENGTH_PROBE, row.a, row.b, row.order, row.factor, False
    return None


class _Row:
    """A name's own kernel(kin, out) writing row ``i`` of the table."""

    __slots__ = ("i", "fn")

    def __init__(self, i, fn):
        self.i, self.fn = i, fn

    def __call__(self, kin, table):
        self.fn(kin, table[self.i, ...])


@dataclass(frozen=True)
class AngleRow:
    """A name that is the angle of z = P_b - P_a (``order`` 0) or one of its rates (1, 2), in
    display units (SI over ``factor``); ``signed``: in (-pi, pi] instead of [0, 2 pi)."""

    a: str
    b: str
    order: int
    factor: float
    signed: bool = False


class Angles:
    """Every :class:`AngleRow` of a plan, evaluated together: the vectors z = P_b - P_a
    stacked in one (vectors x positions) array, their rates z', z'' likewise, so each
    operation below is one pass over all the angles at once.

    Angles: arctan2 in (-pi, pi], those <= 0 gaining 2 pi, those within 1e-12 rad of
    2 pi (+-0 included) being 0 (:func:`wrap_angle`).  Rates, with w = z'/z:
    phi' = Im w, phi'' = Im(z''/z) - 2 Re w Im w.  A -0.0 is written as 0.0.  Element by
    element these are the operations of :func:`value_of`, so the values are the same.
    """

    def __init__(self, rows: dict):
        """``rows``: table row -> AngleRow."""
        pairs = list(dict.fromkeys((r.a, r.b) for r in rows.values()))
        self.pairs = pairs
        self.slots = []                 # (order, table rows, vector indices, factors, signed)
        for order in (0, 1, 2):
            mine = [(i, r) for i, r in rows.items() if r.order == order]
            if not mine:
                continue
            index = [pairs.index((r.a, r.b)) for _, r in mine]
            if index == list(range(len(pairs))):
                index = slice(None)         # every vector, in order: no gather
            factors = np.array([r.factor for _, r in mine])
            signed = np.array([r.signed for _, r in mine])
            at = [i for i, _ in mine]
            if at == list(range(at[0], at[-1] + 1)):
                at = slice(at[0], at[-1] + 1)     # written in place, no scatter
            self.slots.append((order, at, index, None if np.all(factors == 1) else factors,
                               signed if signed.any() else None))
        self.rates = max(order for order, *_ in self.slots)

    def __call__(self, kin, table):
        shape = table.shape[1:]
        z = self._stack(kin.pos, shape)
        w = zz = None
        if self.rates >= 1:
            w = self._stack(kin.vel, shape)
            w /= z
        if self.rates >= 2:
            zz = self._stack(kin.acc, shape)
            zz /= z
        column = (-1,) + (1,) * len(shape)      # a value per vector, down the table
        for order, rows, index, factors, signed in self.slots:
            if factors is not None:
                factors = factors.reshape(column)
            out = table[rows] if type(rows) is slice else \
                np.empty((len(rows),) + shape)
            if order == 0:
                v = z[index]
                np.arctan2(v.imag, v.real, out=out)
                _wrap_principal(out)
                if signed is not None:
                    np.subtract(out, TWO_PI, out=out, where=(out > math.pi) & signed.reshape(column))
            elif order == 1:
                v = w[index].imag
                if factors is None:
                    np.add(v, 0.0, out=out)
                else:
                    np.divide(v, factors, out=out)
            else:
                v = w[index]
                np.multiply(v.real, v.imag, out=out)
                out *= -2.0
                out += zz[index].imag
                if factors is not None:
                    out /= factors
                else:
                    out += 0.0
            if order == 0 and factors is not None:
                out /= factors
            if type(rows) is not slice:
                table[rows] = out

    def _stack(self, points, shape):
        """(P_b - P_a) of every pair, stacked; an absent point (fixed: no rates) is 0."""
        out = np.empty((len(self.pairs),) + shape, complex)
        for i, (a, b) in enumerate(self.pairs):
            row = out[i, ...]
            pa, pb = points.get(a), points.get(b)
            if pa is None:
                row[...] = 0j if pb is None else pb
            elif pb is None:
                np.negative(pa, out=row)
            else:
                np.subtract(pb, pa, out=row)
        return out


def _put(value, factor, kin, out):
    """``value`` (SI) in display units into ``out``; -0.0 becomes 0.0 as in :func:`value_of`."""
    if getattr(value, "shape", ()) != out.shape:
        out[...] = value / factor + 0 * kin.q
    elif factor != 1:
        np.divide(value, factor, out=out)
    else:
        np.add(value, 0.0, out=out)
