"""Headless Chromium (Debian's package ``chromium``) for the tests of the HTML documents.

:func:`browser` finds it (None where it is not installed: the tests skip, naming the
package); :func:`measure` lays out several pages in one browser call and returns, for each,
the elements wider than its column; :func:`print_pdf` prints a page to PDF as a person
would with the browser's print dialog.
"""
from __future__ import annotations

import html
import json
import re
import shutil
import subprocess

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-pdf-header-footer"]
WIDTH = 800                   # the window's width in CSS pixels (the column: 800 less margins)
SKIP = "chromium is not installed (Debian: apt-get install chromium)"

#: appended to the combined page: for each page (a section), every element whose content is
#: wider than its box (scrollWidth > clientWidth) or whose box passes the column's right edge
MEASURE = r"""<script>
(function () {
  var out = [];
  document.querySelectorAll('section.page').forEach(function (page) {
    var column = page.getBoundingClientRect();
    page.querySelectorAll('*').forEach(function (el) {
      var box = el.getBoundingClientRect();
      var over = Math.max(el.scrollWidth - el.clientWidth, box.right - column.right);
      if (over > 1 && !el.closest('svg, math'))
        out.push([page.dataset.name, el.tagName.toLowerCase(), Math.round(box.width),
                  Math.round(Math.max(el.scrollWidth, box.width)), Math.round(column.width)]);
    });
    page.querySelectorAll('math, svg').forEach(function (el) {
      var box = el.getBoundingClientRect();
      if (box.right - column.right > 1)
        out.push([page.dataset.name, el.tagName.toLowerCase(), Math.round(box.width),
                  Math.round(box.width), Math.round(column.width)]);
    });
  });
  var report = document.createElement('pre');
  report.id = 'measured';
  report.textContent = JSON.stringify({page: [document.documentElement.scrollWidth,
                                              document.documentElement.clientWidth],
                                       over: out});
  document.body.appendChild(report);
})();
</script>"""


def browser() -> str | None:
    """The path of Chromium, None where it is not installed."""
    return shutil.which("chromium") or shutil.which("chromium-browser")


def combined(pages) -> str:
    """One page holding the body of each (name, HTML) page in a section of its own, with
    the first page's style (every worked solution has the same) and :data:`MEASURE`."""
    style, parts = "", []
    for name, text in pages:
        style = style or re.search(r"<style>(.*?)</style>", text, re.S).group(1)
        body = re.search(r"<body>(.*)</body>", text, re.S).group(1)
        parts.append(f'<section class="page" data-name="{html.escape(name)}">{body}</section>')
    return (f'<!DOCTYPE html><html><head><meta charset="utf-8"><style>{style}</style></head>'
            "<body>" + "\n".join(parts) + MEASURE + "</body></html>")


def measure(pages, folder) -> dict:
    """Lay out the (name, HTML) ``pages`` in one Chromium call (a window :data:`WIDTH` wide)
    and return {'page': [scrollWidth, clientWidth] of the whole, 'over': [[name, tag, box
    width, content width, column width], ...]} for the elements wider than their column."""
    path = folder / "measured.html"
    path.write_text(combined(pages), encoding="utf-8")
    dom = subprocess.run([browser(), *FLAGS, f"--user-data-dir={folder / 'profile'}",
                          f"--window-size={WIDTH},1000", "--dump-dom", path.as_uri()],
                         capture_output=True, text=True, timeout=300)
    found = re.search(r'<pre id="measured">(.*?)</pre>', dom.stdout, re.S)
    assert found, dom.stderr[-2000:]
    return json.loads(html.unescape(found.group(1)))


def print_pdf(page, folder) -> bytes:
    """The PDF that Chromium prints of the HTML file ``page`` (its print CSS, A4 or Letter
    as the page asks)."""
    pdf = folder / (page.stem + ".pdf")
    done = subprocess.run([browser(), *FLAGS, f"--user-data-dir={folder / 'profile'}",
                           f"--print-to-pdf={pdf}", page.as_uri()], capture_output=True,
                          text=True, timeout=300)
    assert pdf.exists(), done.stderr[-2000:]
    return pdf.read_bytes()
