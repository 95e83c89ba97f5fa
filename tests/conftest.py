import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MECHANISMS = os.path.join(ROOT, "mechanisms")
sys.path.insert(0, ROOT)


# --- fuzzing: how many cases ran (tests/test_fuzz.py, tests/test_schema.py) ------------
import collections  # noqa: E402

import pytest  # noqa: E402

_FUZZ_COUNTS: dict = collections.defaultdict(collections.Counter)


@pytest.fixture(scope="session")
def fuzz_counter():
    """Counters by fuzz test group: 'cases' and the exit codes seen."""
    return _FUZZ_COUNTS


def pytest_terminal_summary(terminalreporter):
    if _INVARIANCE:
        terminalreporter.write_sep("-", f"invariance: {sum(_INVARIANCE.values())} cases")
        for group, count in sorted(_INVARIANCE.items()):
            terminalreporter.write_line(f"  {group}: {count}")
    if not _FUZZ_COUNTS:
        return
    total = sum(c["cases"] for c in _FUZZ_COUNTS.values())
    terminalreporter.write_sep("-", f"fuzzing: {total} cases")
    for group, counts in sorted(_FUZZ_COUNTS.items()):
        detail = ", ".join(f"{k} {v}" for k, v in sorted(counts.items()) if k != "cases")
        terminalreporter.write_line(f"  {group}: {counts['cases']} cases"
                                    + (f" ({detail})" if detail else ""))


# with pytest-xdist (`make test` runs `pytest -n auto`) the counts are made in the workers:
# each hands its own to the controller, which adds them up for the summary
def pytest_sessionfinish(session):
    output = getattr(session.config, "workeroutput", None)
    if output is not None:
        output["fuzz_counts"] = {group: dict(c) for group, c in _FUZZ_COUNTS.items()}
        output["invariance_counts"] = dict(_INVARIANCE)


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    for group, counts in getattr(node, "workeroutput", {}).get("fuzz_counts", {}).items():
        _FUZZ_COUNTS[group].update(counts)
    _INVARIANCE.update(getattr(node, "workeroutput", {}).get("invariance_counts", {}))


# --- invariance: how many files x rewritings were compared (tests/test_invariance_*.py) ---
_INVARIANCE = collections.Counter()


@pytest.fixture(scope="session")
def invariance_counter():
    """Counters of the invariance tests: file-and-digit cases compared, by rewriting."""
    return _INVARIANCE
