"""The processor time the formulas of ``--symbolic`` may take.

The formulas are written in steps (T, V and D; the equilibrium; M, K, R; ...), in a thread
of their own, while the caller waits.  :meth:`Budget.check`, called between steps and
inside their loops, raises FormulaLimit (reason 'time') once ``seconds`` of this process's
processor time have passed since the start; what each step finished is kept
(:meth:`Budget.keep`).  Where one step runs on past the bound (a single operation of the
algebra that does not return to a check), the caller stops waiting ``GRACE`` seconds
later and takes what was kept: the formulas not reached are named, the numbers stand.
The thread is then told to stop at its next check and nothing it finishes is kept.

Processor time, not the clock's: the bound is the same on a loaded machine, and the
caller, which only waits, adds nothing to it.
"""
from __future__ import annotations

import threading
import time

from linkcli.errors import FormulaLimit

#: the processor time (s) the formulas of one file may take, unless told otherwise
SECONDS = 10.0
#: after the bound, the seconds the caller still waits for the step under way
GRACE = 1.0
#: how often (s) the caller looks at the time spent
POLL = 0.02


class Budget:
    """``seconds`` of processor time from now for the formulas; ``found`` holds what the
    steps finished."""

    def __init__(self, seconds: float = SECONDS):
        self.seconds = float(seconds)
        self.start = time.process_time()
        self.found: dict = {}
        self.stopped = False
        self._lock = threading.Lock()

    def spent(self) -> float:
        return time.process_time() - self.start

    def check(self) -> None:
        """Raise FormulaLimit (reason 'time') once the bound is passed or the caller stopped."""
        if self.stopped or self.spent() > self.seconds:
            raise self.exceeded()

    def exceeded(self) -> FormulaLimit:
        return FormulaLimit(f"not reached within the {self.seconds:g} s of processor time the "
                            "formulas may take (--seconds gives more)", reason="time",
                            limit=self.seconds, size=self.spent(),
                            hint="the numbers are the answers")

    def keep(self, **items) -> None:
        """Keep the finished ``items`` (name -> value), unless the caller has stopped."""
        with self._lock:
            if not self.stopped:
                self.found.update(items)

    def run(self, work) -> dict:
        """Run ``work()`` in a thread and wait until it ends, or the bound and GRACE pass;
        the items kept by then.  An error of ``work`` other than the bound's is raised here."""
        box = {}

        def target():
            try:
                work()
            except FormulaLimit as exc:
                if exc.reason != "time":
                    box["error"] = exc
            except BaseException as exc:         # re-raised in the caller's thread
                box["error"] = exc

        worker = threading.Thread(target=target, name="linkcli-formulas", daemon=True)
        worker.start()
        while worker.is_alive():
            worker.join(POLL)
            if worker.is_alive() and self.spent() > self.seconds + GRACE:
                break
        with self._lock:
            self.stopped = worker.is_alive()      # its later steps are not kept
            found = dict(self.found)
        if "error" in box:
            raise box["error"]
        return found
