"""Dimensions of answers and the one place that picks their display unit (model.units)."""
from __future__ import annotations

import math

import pytest

from linkcli.errors import InputError
from linkcli.model import units as u
from linkcli.model.units import DIMENSIONS, Dimension, Units


def test_each_kind_is_shown_in_the_files_unit_of_that_kind():
    """A file that declares a unit of every kind sees each kind's values in it."""
    declared = {"length": "in", "force": "lbf", "mass": "slug", "torque": "lbf ft",
                "inertia": "slug ft^2", "stiffness": "lb/in", "damping": "lbf s/in",
                "frequency": "Hz", "speed": "ft/s", "time": "ms", "pressure": "psi"}
    units = Units(declared)
    for kind, name in declared.items():
        shown = units.show(DIMENSIONS[kind], kind)
        assert shown == (name, u.KINDS[kind][name]), kind
    # without naming the kind: a rate of an angle is an angular rate, not a frequency
    assert units.show(DIMENSIONS["frequency"]) == ("deg/s", math.pi / 180)
    assert units.show(DIMENSIONS["frequency"], "frequency") == ("Hz", 2 * math.pi)


def test_composed_units_are_products_of_the_files_units():
    """A dimension no kind has is written with the file's units; the factor is computed
    here by hand from the exact definitions (in = 0.0254 m, lbf = 0.45359237 * 9.80665 N)."""
    units = Units({"length": "in", "force": "lbf", "mass": "lb"})
    deg = math.pi / 180
    assert units.show(Dimension(length=1, angle=-1)) == ("in/deg", pytest.approx(0.0254 / deg))
    name, factor = units.show(Dimension(mass=1, length=1, angle=-1))
    assert name == "lb in/deg" and factor == pytest.approx(0.45359237 * 0.0254 / deg)
    name, factor = units.show(Dimension(1, 1, -2, -1))         # a force per angle
    assert name == "lbf/deg" and factor == pytest.approx(0.45359237 * 9.80665 / deg)
    name, factor = units.show(Dimension(length=-1, angle=-1))
    assert name == "1/(in deg)" and factor == pytest.approx(1 / (0.0254 * deg))
    assert units.show(Dimension()) == ("", 1.0)


def test_comparisons_ignore_angles_as_si_does():
    """2 pi / omega is a time; a stiffness over a mass, square-rooted, a frequency."""
    frequency = DIMENSIONS["frequency"]
    period = Dimension() / frequency
    assert period.agrees(DIMENSIONS["time"]) and period != DIMENSIONS["time"]
    root = (DIMENSIONS["stiffness"] / DIMENSIONS["mass"]) ** 0.5
    assert root.agrees(frequency) and not root.agrees(DIMENSIONS["time"])
    assert DIMENSIONS["torsional_stiffness"].agrees(DIMENSIONS["torque"])
    assert not DIMENSIONS["stiffness"].agrees(DIMENSIONS["force"])
    assert Dimension(angle=1).none and not Dimension(length=1).none


def test_exponents_are_whole_or_halves():
    assert (DIMENSIONS["area"] ** 0.5) == DIMENSIONS["length"]
    assert (DIMENSIONS["length"] ** 0.5).text() == "L^0.5"
    with pytest.raises(InputError):
        DIMENSIONS["length"] ** (1 / 3)


def test_unit_names_give_their_kind_dimension_and_factor():
    assert u.unit_dimension("N/mm") == ("stiffness", DIMENSIONS["stiffness"], 1000.0)
    assert u.unit_dimension("Hz") == ("frequency", DIMENSIONS["frequency"], 2 * math.pi)
    assert u.unit_dimension("%") == (None, Dimension(), 0.01)
    assert u.unit_dimension("furlong") is None


def test_every_unit_in_the_tables_has_its_kinds_dimension():
    """Each table's factors are consistent with its dimension: converting a unit's SI
    factor through the kind's dimension from a file declared in that unit gives back 1."""
    for kind, table in u.KINDS.items():
        for name in table:
            units = Units({kind: name})
            shown, factor = units.show(DIMENSIONS[kind], kind)
            assert (shown, factor) == (name, table[name])
