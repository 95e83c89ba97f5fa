"""``plot --motion``: the machine's speed and motion in time.  The samples are checked
against the answers of the same file (the speed at a time, the turns at a time) and against
each other (the motion's finite differences are the speed); bad spans are refused."""
import os

import numpy as np
import pytest

import linkcli
from linkcli.errors import InputError
from linkcli.pictures.motion import samples

from cli_helpers import run

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PRESS = os.path.join(ROOT, "docs", "examples", "machine-press.yaml")


def test_samples_are_the_answers_of_the_motion_at_their_times():
    mech = linkcli.load(PRESS).model
    t, moved, w = samples(mech, "0:1:4")          # t = 0, 0.25, 0.5, 0.75, 1 s
    values = linkcli.load(PRESS).solve(names=["w1", "n1"]).values
    rpm = 2 * np.pi / 60
    assert w[2] / rpm == pytest.approx(values["w1"], rel=1e-8)
    assert moved[2] / (2 * np.pi) == pytest.approx(values["n1"], rel=1e-8)
    assert w[0] == 0 and moved[0] == 0


def test_the_motion_grows_at_the_speed():
    mech = linkcli.load(PRESS).model
    t, moved, w = samples(mech, "0:1:2000")
    h = t[1] - t[0]
    rate = (moved[2:] - moved[:-2]) / (2 * h)
    assert np.max(np.abs(rate - w[1:-1])) <= 1e-3 * np.max(np.abs(w))


def test_plot_motion_writes_a_picture(tmp_path):
    out = tmp_path / "w.png"
    code, _, err = run(["plot", PRESS, "--motion", "0:1:50", "-o", str(out)])
    assert code == 0, err
    assert out.stat().st_size > 1000


@pytest.mark.parametrize("span, words", [("1:3:10", "from 0 up to a positive end"),
                                         ("0:1:30000", "more than 20000")])
def test_bad_spans_are_refused_by_name(span, words):
    with pytest.raises(InputError, match=words):
        samples(linkcli.load(PRESS).model, span)


def test_a_file_without_masses_is_refused_with_exit_2(tmp_path):
    code, _, err = run(["plot", os.path.join(ROOT, "mechanisms", "padova-2020-02.yaml"),
                        "--motion", "0:1:10", "-o", str(tmp_path / "x.png")])
    assert code == 2 and "needs the masses" in err
