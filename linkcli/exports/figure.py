"""The figure of a file, as bytes or SVG text, for documents that embed it."""
from __future__ import annotations

import os
import tempfile

from linkcli.pictures.exam import draw_exam
from linkcli.pictures.plotting import draw


def figure_bytes(mech, ext: str = "png", dpi: int = 90, exam: bool = False, lang: str = "en",
                 method: str = "closed") -> bytes:
    """The picture of ``draw`` (the mechanism, its vector polygon and loads) as bytes, or
    with ``exam`` the exam's figure (the data only, no answer) in language ``lang``; its
    positions solved by ``method`` ('closed' or 'newton')."""
    with tempfile.TemporaryDirectory(prefix="linkcli-figure-") as folder:
        path = os.path.join(folder, f"figure.{ext}")
        if exam:
            draw_exam(mech, path, lang=lang, method=method, dpi=dpi)
        else:
            draw(mech, path, dpi=dpi, method=method)
        with open(path, "rb") as f:
            return f.read()
