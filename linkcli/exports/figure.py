"""The figure of a file, as bytes or SVG text, for documents that embed it."""
from __future__ import annotations

import os
import tempfile

from linkcli.pictures.plotting import draw


def figure_bytes(mech, ext: str = "png", dpi: int = 90) -> bytes:
    """The picture of ``draw`` (the mechanism, its vector polygon and loads) as bytes."""
    with tempfile.TemporaryDirectory(prefix="linkcli-figure-") as folder:
        path = os.path.join(folder, f"figure.{ext}")
        draw(mech, path, dpi=dpi)
        with open(path, "rb") as f:
            return f.read()
