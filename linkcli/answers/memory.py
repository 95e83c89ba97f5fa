"""Keep freed working memory in the process while long arrays are solved.

Solving N positions makes a few dozen temporary arrays of N values each, alive together
and freed together at the end of the call.  With glibc's default malloc, arrays of more
than 128 KB (8192 complex values) come from fresh pages of the kernel, and freed memory
at the top of the heap beyond twice that is given back at once: every call of 16384 to
65536 positions then pays page faults for all its temporaries, and runs at half the speed
of the same solve with its pages kept (228 against 100 ns per position for the
seed-000 crank-slider, ``Linkage.solve`` on 16384 positions at a time; 2144 against 0.1 page
faults per call for padova-2020-07, ``tests/test_memory.py``).  Long sweeps are solved in
such blocks.

:func:`keep_freed_memory` raises the two thresholds once per process (``mallopt``:
M_MMAP_THRESHOLD 32 MB, M_TRIM_THRESHOLD 64 MB): arrays below 32 MB come from the heap
and up to 64 MB of freed heap is kept for the next call.  The peak memory does not grow
(the kept memory is what the last call used).  Where the C library has no ``mallopt``
(not glibc) nothing is done.  The first solve of at least :data:`LONG` positions calls it;
``LINKCLI_KEEP_MEMORY=0`` in the environment turns it off.
"""
from __future__ import annotations

import os

#: arrays of this many positions and more are solved with the freed memory kept
LONG = 4096
#: glibc's mallopt parameters (malloc.h) and the values set
M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3
TRIM, MMAP = 64 << 20, 32 << 20

_state: dict = {}


def keep_freed_memory() -> bool:
    """Raise malloc's thresholds once per process (see the module); whether they are set."""
    if "set" not in _state:
        _state["set"] = _mallopt()
    return _state["set"]


def _mallopt() -> bool:
    if os.environ.get("LINKCLI_KEEP_MEMORY", "1") == "0":
        return False
    try:
        import ctypes
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):
        return False
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    return bool(mallopt(M_MMAP_THRESHOLD, MMAP)) and bool(mallopt(M_TRIM_THRESHOLD, TRIM))
