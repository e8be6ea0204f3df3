"""Sphinx extension: the Validation page's table, rendered from ``docs/validation.json``.

The test suite writes that file (``pytest tests --refresh-validation``; the fixture
``validation`` of ``tests/conftest.py``) and checks it on every run: each test that records a
check compares what it measured with the committed copy and fails when it has moved. This
extension only reads it, so the docs build needs neither the tests nor the compiled kernel's
results.

Directive ``validation-table`` (no arguments): a summary paragraph and one table, a header row
per model level, then quantity, reference (with its kind), measured error, tolerance and the
test that measured it.
"""

from __future__ import annotations

import json
from collections import Counter
from pathlib import Path

from docutils import nodes
from sphinx.util.docutils import SphinxDirective

JSON = Path(__file__).resolve().parent.parent / "validation.json"
COLUMNS = (("quantity", 29), ("reference", 30), ("measured", 8), ("tolerance", 12),
           ("test", 21))


def number(x: float) -> str:
    """Two significant digits: 0.0026 -> "0.0026", 2.6e-10 -> "2.6e-10", 0 -> "0"."""
    if x == 0.0:
        return "0"
    if 1e-3 <= abs(x) < 1e3:
        return f"{x:.2g}"
    mantissa, exponent = f"{x:.1e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def load(path: Path = JSON) -> list[dict]:
    return json.loads(path.read_text(encoding="utf-8"))["records"]


def summary(records: list[dict]) -> str:
    kinds = Counter(r["kind"] for r in records)
    levels = list(dict.fromkeys(r["level"] for r in records))
    worst = max(records, key=lambda r: r["measured"] / r["tolerance"])
    parts = ", ".join(f"{n} against {k}" for k, n in kinds.most_common())
    return (f"{len(records)} checks over {len(levels)} levels of the model ({parts}). "
            f"Every measured error is within its tolerance; the closest is "
            f"{worst['id']} at {worst['measured'] / worst['tolerance']:.0%} of it.")


def _cell(content) -> nodes.entry:
    entry = nodes.entry()
    if isinstance(content, nodes.Node):
        entry += content
    else:
        entry += nodes.paragraph(text=content)
    return entry


def _row(cells) -> nodes.row:
    row = nodes.row()
    for c in cells:
        row += _cell(c)
    return row


def table(records: list[dict]) -> nodes.table:
    tab = nodes.table(classes=["tw-validation", "colwidths-given"])
    group = nodes.tgroup(cols=len(COLUMNS))
    tab += group
    for _, width in COLUMNS:
        group += nodes.colspec(colwidth=width)
    head = nodes.thead()
    head += _row([name for name, _ in COLUMNS])
    group += head
    body = nodes.tbody()
    level = None
    for r in records:
        if r["level"] != level:
            level = r["level"]
            row = nodes.row(classes=["tw-validation-level"])
            entry = nodes.entry(morecols=len(COLUMNS) - 1)
            entry += nodes.paragraph("", "", nodes.strong(text=level[0].upper() + level[1:]))
            row += entry
            body += row
        reference = nodes.paragraph()
        reference += nodes.emphasis(text=r["kind"] + ": ")
        reference += nodes.Text(r["reference"])
        test = r["test"].split("/", 1)[-1]  # tests/test_x.py::name -> test_x.py::name
        test_node = nodes.literal(text=test)  # wraps anywhere: docs/_static/trackwheel.css
        body += _row([r["quantity"], reference, number(r["measured"]),
                      f"{number(r['tolerance'])} {r['metric']}", nodes.paragraph("", "", test_node)])
    group += body
    return tab


class ValidationTable(SphinxDirective):
    has_content = False

    def run(self):
        self.env.note_dependency(str(JSON))
        records = load()
        return [nodes.paragraph(text=summary(records)), table(records)]


def setup(app):
    app.add_directive("validation-table", ValidationTable)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
