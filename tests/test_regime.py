"""The periodic regime and the flywheel (linkcli.forces.regime, linkcli.forces.flywheel).

Closed forms (a turning moment T0 + A sin(n q) on a constant inertia), the regime against
the transient integrated in time by solve_ivp, the books' flywheel against the exact one,
and the refusals with their numbers.
"""
import math

import numpy as np
import pytest

from linkcli.errors import RegimeError
from linkcli.forces import flywheel as fw
from linkcli.forces import regime as rg

from regime_cases import A, N, W_MEAN, const, crankshaft, integrate, slider_crank


def test_closed_form_turning_moment():
    """T0 + A sin(n q): DeltaE = 2 A / n, fastest at q = pi / n, slowest at 0, the largest
    acceleration A / J; and 1/2 J (w_max^2 - w_min^2) = DeltaE on the orbit."""
    J = 500.0
    reg = rg.regime(crankshaft(J), W_MEAN)
    assert reg.energy_fluctuation == pytest.approx(2 * A / N, rel=1e-9)
    lobe = 2 * math.pi / N          # the n equal maxima and minima are each an answer
    assert reg.at_max_speed % lobe == pytest.approx(math.pi / N, abs=1e-7)
    assert min(reg.at_min_speed % lobe, lobe - reg.at_min_speed % lobe) == pytest.approx(
        0, abs=1e-7)
    assert reg.max_acceleration == pytest.approx(A / J, rel=1e-9)
    assert reg.min_acceleration == pytest.approx(-A / J, rel=1e-9)
    assert 0.5 * J * (reg.max_speed ** 2 - reg.min_speed ** 2) == pytest.approx(
        reg.energy_fluctuation, rel=1e-9)
    assert 0.5 * (reg.max_speed + reg.min_speed) == pytest.approx(W_MEAN, rel=1e-13)
    assert reg.mean_speed == pytest.approx(W_MEAN, rel=1e-13)
    assert reg.average_speed < reg.mean_speed    # the time spent slow weighs more


@pytest.mark.parametrize("delta", [0.2, 0.02, 0.002])
def test_flywheel_books_and_exact_constant_inertia(delta):
    """Constant J, loads free of the speed: DeltaE = 1/2 J (w_max^2 - w_min^2) = J w_m^2 delta
    with w_m = (w_max + w_min) / 2, so the books' flywheel is the exact one."""
    fly = fw.flywheel(crankshaft(), delta, W_MEAN)
    assert fly.regime.fluctuation == pytest.approx(delta, rel=1e-9)
    assert fly.regime.mean_speed == pytest.approx(W_MEAN, rel=1e-12)
    assert fly.approximate == pytest.approx(2 * A / N / (W_MEAN ** 2 * delta), rel=1e-9)
    assert fly.exact == pytest.approx(fly.approximate, rel=1e-8)


def test_flywheel_books_and_exact_agree_to_order_delta():
    """A varying J*: the books' flywheel (from the diagram with the reciprocating masses'
    inertia torque) and the exact one differ by a fraction that falls with delta."""
    gaps = []
    for delta in (0.04, 0.004):
        fly = fw.flywheel(slider_crank(motor=False), delta, 40.0)
        assert fly.regime.fluctuation == pytest.approx(delta, rel=1e-8)
        assert fly.regime.mean_speed == pytest.approx(40.0, rel=1e-12)
        gaps.append(abs(fly.exact / fly.approximate - 1))
    assert gaps[0] < 0.1 and gaps[1] < 0.2 * gaps[0]


def test_shooting_against_transient_integrated_in_time():
    """The orbit found by shooting against the transient integrated from rest-speed for 60
    cycles: the same largest, smallest and mean speeds."""
    cyc = slider_crank(flywheel=0.3)
    reg = rg.regime(cyc)
    assert reg.method == "shooting" and reg.multiplier < 1
    w_max, w_min, average = integrate(cyc, 0.0, 60.0, 25)
    assert reg.max_speed == pytest.approx(w_max, rel=1e-6)
    assert reg.min_speed == pytest.approx(w_min, rel=1e-6)
    assert reg.average_speed == pytest.approx(average, rel=1e-7)


def test_exact_flywheel_against_transient():
    """The exact flywheel for delta = 0.03, put on the machine and integrated in time from
    near rest: the last cycle's coefficient of fluctuation is 0.03."""
    fly = fw.flywheel(slider_crank(), 0.03)
    w_max, w_min, _ = integrate(slider_crank(flywheel=fly.exact), 0.0, 60.0, 25)
    assert 2 * (w_max - w_min) / (w_max + w_min) == pytest.approx(0.03, rel=1e-4)


def test_energy_method_orbit_is_periodic_in_time():
    """The energy method's orbit, started at its speed at q0 and integrated in time for one
    cycle, has the same extremes and the same cycle time."""
    cyc = slider_crank(motor=False, flywheel=0.5)
    reg = rg.regime(cyc, 40.0)
    w_max, w_min, average = integrate(cyc, 0.0, float(reg.speed(np.array([0.0]))[0]), 1)
    assert (w_max, w_min, average) == pytest.approx(
        (reg.max_speed, reg.min_speed, reg.average_speed), rel=1e-6)
    assert reg.mean_speed == pytest.approx(40.0, rel=1e-12)


def test_refused_without_balance():
    """A mean driving torque above the resisting one: no regime, the means named."""
    with pytest.raises(RegimeError) as err:
        rg.regime(crankshaft(500.0, resisting=-4900.0), W_MEAN)
    assert err.value.reason == "unbalanced" and err.value.exit_code == 3
    assert err.value.values[0] == pytest.approx(100.0, rel=1e-9)
    assert "T 5000, R -4900" in str(err.value) and "runs away" in str(err.value)
    with pytest.raises(RegimeError, match="stops"):
        rg.regime(crankshaft(500.0, resisting=-5100.0), W_MEAN)


def test_refused_motor_too_weak_or_runaway():
    weak = rg.Cycle(0.0, 2 * math.pi, const(1.0), const(0.0),
                    (rg.Load("motor", lambda q, w: 10 * (1 - w / 100), True),
                     rg.Load("load", lambda q, w: np.full(np.shape(q), -12.0))))
    with pytest.raises(RegimeError, match=r"sum -2 <= 0") as err:
        rg.regime(weak)
    assert err.value.reason == "stalls"
    runaway = rg.Cycle(0.0, 2 * math.pi, const(1.0), const(0.0),
                       (rg.Load("motor", lambda q, w: 10 + 0 * w, True),))
    with pytest.raises(RegimeError) as err:
        rg.regime(runaway)
    assert err.value.reason == "runs away"


def test_refused_repelling_orbit():
    """A torque rising with the speed (balanced at 50 rad/s) has a periodic orbit that
    repels: named with its multiplier, never given as a regime."""
    cyc = rg.Cycle(0.0, 2 * math.pi, const(2.0), const(0.0),
                   (rg.Load("fan", lambda q, w: 0.5 * (w - 50.0) + 5 * np.sin(q), True),))
    with pytest.raises(RegimeError) as err:
        rg.regime(cyc)
    assert err.value.reason == "unstable" and err.value.values[1] > 1


def test_refused_shooting_without_convergence(monkeypatch):
    monkeypatch.setattr(rg, "ITERATIONS", 1)
    with pytest.raises(RegimeError) as err:
        rg.regime(slider_crank(flywheel=0.3))
    assert err.value.reason == "no convergence"
    assert all(math.isfinite(v) for v in err.value.values)


def test_refused_fluctuation_no_flywheel_gives():
    """The machine alone fluctuates by delta0: a larger delta needs a negative flywheel."""
    alone = rg.regime(slider_crank()).fluctuation
    with pytest.raises(RegimeError) as err:
        fw.flywheel(slider_crank(), 2 * alone)
    assert err.value.reason == "no flywheel"
    assert err.value.values == pytest.approx((2 * alone, alone), rel=1e-9)
    for bad in (0.0, -0.01, math.nan):
        with pytest.raises(RegimeError, match="positive number"):
            fw.flywheel(crankshaft(), bad, W_MEAN)


@pytest.mark.parametrize("case", ["constant", "slider-crank"])
def test_picture_shades_areas_that_sum_to_delta_e(case):
    """The turning-moment diagram's darker lobes: their outlines, integrated here by the
    trapezoidal rule, add up to DeltaE; every lobe's outline has the area it is labelled
    with; the picture is drawn."""
    from linkcli.pictures import regime as pr

    reg = (rg.regime(crankshaft(500.0), W_MEAN) if case == "constant"
           else rg.regime(slider_crank(flywheel=0.3)))
    shaded = pr.lobes(reg)
    sizing = [lobe for lobe in shaded if lobe.sizing]
    assert sizing and len(sizing) < len(shaded)
    total = sum(np.trapezoid(lobe.Q, lobe.q) for lobe in sizing)
    assert total == pytest.approx(reg.energy_fluctuation, rel=1e-4)
    for lobe in shaded:
        assert np.trapezoid(lobe.Q, lobe.q) == pytest.approx(lobe.area, rel=1e-4)
    assert sum(lobe.end - lobe.start for lobe in shaded) == pytest.approx(2 * math.pi)
    fig = pr.picture(reg, ("deg", math.pi / 180, "rpm", math.pi / 30, "N m", 1.0), case)
    assert len(fig.axes) == 2


def test_picture_sizing_lobes_catch_a_wrong_run(monkeypatch):
    """A planted defect: the run of lobes taken from the most energy instead of the least
    gives areas that do not add up to DeltaE, and the check above sees it."""
    from linkcli.pictures import regime as pr

    reg = rg.regime(slider_crank(flywheel=0.3))
    good = pr._sizing
    monkeypatch.setattr(pr, "_sizing", lambda E, dE: good(-E, dE))
    total = sum(np.trapezoid(lobe.Q, lobe.q) for lobe in pr.lobes(reg) if lobe.sizing)
    assert total != pytest.approx(reg.energy_fluctuation, rel=1e-4)
