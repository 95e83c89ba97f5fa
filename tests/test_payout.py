"""A cord's pay-out as the driver: a spool rolling on the floor (end caps R) whose cord,
wound on its core (r), leaves the top or the bottom of the core horizontally.

The pay-out s is the length of cord unwound relative to the spool.  Closed form (written
here, not taken from the solver): the spool rolls, v_C = -omega R; the cord leaves the core
at T = C + side r i, whose material point moves at v_C - side omega r, so relative to the
spool the cord passes T at s' = -side r omega: v_C = side R s' / r, and the cord's end
(P, on the straight cord) runs at v_P = v_C + s', v_C = R / (R + side r) v_P, the book's
v_C = R / (R -/+ r) v_P for a cord from the top / the bottom of the core.  Positions against
the definition (the free length x_P - x_C grows by s), rates against differences of
positions, and the refusal of a pay-out of something that is not a cord.
"""
from __future__ import annotations

import pytest

import linkcli
from linkcli.cli import main

R, r = 15.0, 10.0

SPOOL = """
title: spool paid out
units: {{length: mm, angle: deg}}
frame: {{O: [0, 0]}}
points: {{C: [0, 15], M: [15, 15], P: [60, {y}]}}
links: {{spool: {{points: [C, M], length: 15}}}}
sliders: {{hub: {{point: C, guide: {{y: 15}}}}, hand: {{point: P, guide: {{y: {y}}}}}}}
rolling: {{floor: {{disc: spool, radius: 15, on: {{line: x, side: left}}}}}}
cords: {{rope: {{pulley: spool, radius: 10, to: P, along: x, side: {side}}}}}
driver: {{{driver}: {target}, value: {s}, rate: {rate}, accel: {accel}}}
report: {{position: [xC, xP], velocity: [xCdot, xPdot], acceleration: [xCddot, xPddot]}}
"""
SIDES = {"left": 1, "right": -1}           # the top of the core, the bottom


def _spool(side, s=0.0, rate=250.0, accel=40.0, driver="payout", target="rope"):
    text = SPOOL.format(y=15 + SIDES[side] * r, side=side, s=s, rate=rate, accel=accel,
                        driver=driver, target=target)
    return linkcli.loads(text, name="spool.yaml").solve().values


@pytest.mark.parametrize("side", sorted(SIDES))
@pytest.mark.parametrize("s", [0.0, 7.5])
def test_spool_rates_from_the_closed_form(side, s):
    k = SIDES[side]
    got = _spool(side, s)
    assert got["xCdot"] == pytest.approx(k * R * 250 / r, rel=1e-9)
    assert got["xPdot"] == pytest.approx(got["xCdot"] + 250, rel=1e-9)
    assert got["xCdot"] == pytest.approx(R / (R + k * r) * got["xPdot"], rel=1e-9)
    assert got["xCddot"] == pytest.approx(k * R * 40 / r, rel=1e-9)
    assert got["xPddot"] == pytest.approx(got["xCddot"] + 40, rel=1e-9)


@pytest.mark.parametrize("side", sorted(SIDES))
def test_payout_is_the_free_length_and_its_rates_its_differences(side):
    """x_P - x_C grows by s (the cord's free length); v from central differences in s."""
    h, s = 1e-3, 5.0
    here, plus, minus = (_spool(side, s + d) for d in (0.0, h, -h))
    base = _spool(side, 0.0)
    assert (here["xP"] - here["xC"]) - (base["xP"] - base["xC"]) == pytest.approx(s, rel=1e-9)
    for p in ("xC", "xP"):
        assert here[p + "dot"] == pytest.approx(250 * (plus[p] - minus[p]) / (2 * h),
                                                rel=1e-7)
        assert here[p + "ddot"] == pytest.approx(40 * (plus[p] - minus[p]) / (2 * h), rel=1e-7)


@pytest.mark.parametrize("target, words", [
    ("floor", "'floor' is a rolling contact, not a cord"),
    ("rop", "undefined cord 'rop'")])
def test_a_payout_of_no_cord_is_refused_at_its_line(tmp_path, capsys, target, words):
    path = tmp_path / "spool.yaml"
    path.write_text(SPOOL.format(y=25, side="left", s=0, rate=1, accel=0, driver="payout",
                                 target=target))
    assert main(["solve", str(path)]) == 2
    output = capsys.readouterr().err
    line = 1 + SPOOL.split("\n").index(next(x for x in SPOOL.split("\n")
                                            if x.startswith("driver:")))
    assert f"{path}:{line}, key 'driver.payout': {words}" in output
    assert "Traceback" not in output


def test_payout_beside_another_coordinate_is_refused(tmp_path, capsys):
    path = tmp_path / "spool.yaml"
    path.write_text(SPOOL.format(y=25, side="left", s=0, rate=1, accel=0, driver="x: C, payout",
                                 target="rope"))
    assert main(["solve", str(path)]) == 2
    assert "payout: CORD" in capsys.readouterr().err


def test_the_closed_form_catches_a_payout_read_with_the_wrong_sign(monkeypatch):
    """A planted defect: the pay-out read as s' = +side r omega (the cord's end's motion
    relative to the centre taken the wrong way round) breaks the closed form."""
    from linkcli.input import contacts
    monkeypatch.setattr(contacts, "turn_per_payout", lambda cord: cord.side / cord.radius)
    with pytest.raises(AssertionError):
        test_spool_rates_from_the_closed_form("left", 0.0)
