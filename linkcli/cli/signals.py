"""SIGINT and SIGTERM while a command runs: unwound like KeyboardInterrupt, so that
``finally`` blocks and the pictures' temporary files are cleaned up; main() then exits
128 + the signal (Ctrl-C 130, SIGTERM 143) with nothing printed.
"""
from __future__ import annotations

import contextlib
import signal
import threading


class Signalled(BaseException):
    """SIGINT or SIGTERM: unwinds like KeyboardInterrupt (so that ``finally`` blocks and
    the pictures' temporary files are cleaned up), and main() exits 128 + the signal."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


_RECEIVED: list = []      # the signals received while main() runs, in order


def _raise_signal(signum, frame):
    _RECEIVED.append(signum)
    raise Signalled(signum)


def signal_received():
    """The last signal received while main() runs, as a Signalled to raise, or None.

    An error raised after a signal came is the signal's doing, whatever it looks like: a
    writer's ``finally`` that fails when the signal cut it short (a GIF closed before its
    first frame), or a library's compiled code that turned the handler's exception into
    its own error (matplotlib's 'Invalid bounding box')."""
    return Signalled(_RECEIVED[-1]) if _RECEIVED else None


@contextlib.contextmanager
def signals():
    """SIGINT and SIGTERM raise Signalled while main() runs (in the main thread, and
    unless the signal is ignored, as for a background job)."""
    saved = {}
    _RECEIVED.clear()
    if threading.current_thread() is threading.main_thread():
        for signum in (signal.SIGINT, signal.SIGTERM):
            try:
                if signal.getsignal(signum) is not signal.SIG_IGN:
                    saved[signum] = signal.signal(signum, _raise_signal)
            except (ValueError, OSError):   # pragma: no cover - no signals here
                pass
    try:
        yield
    finally:
        for signum, handler in saved.items():
            signal.signal(signum, handler if handler is not None else signal.SIG_DFL)
