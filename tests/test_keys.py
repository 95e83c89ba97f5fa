"""Every shipped example reproduces its printed answer key at the printed precision."""
import glob
import os

import pytest

from linkcli.runs.check import check_file
from conftest import MECHANISMS

FILES = sorted(glob.glob(os.path.join(MECHANISMS, "*.yaml")))


@pytest.mark.parametrize("path", FILES, ids=os.path.basename)
def test_key_reproduced(path):
    report = check_file(path)
    assert report.error is None, report.error
    failures = [o for o in report.outcomes if o.status == "fail"]
    assert not failures, [(o.k, o.name, o.printed, o.computed) for o in failures]
    if report.keys:
        assert report.count("pass") > 0
