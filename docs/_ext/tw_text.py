"""Sphinx extension: text that can be copied from the built pages as written.

Two repairs and a check, for the API reference (autodoc + napoleon) and the command-line
reference (sphinx-argparse):

- **Attribute docstrings are not split at a colon.** Napoleon reads the first line of an
  attribute's or property's docstring as ``type: description`` and splits it at the first colon,
  so ``k_s, vertical stiffness [N/m] (layered: pad k_p)`` rendered as "pad k_p) **Type:** k_s,
  vertical stiffness ... (layered". trackwheel's types are the annotations (autodoc shows them in
  the signature) and its attribute docstrings are plain text, so napoleon is kept for functions
  and classes (their NumPy "Parameters"/"Returns" sections) and skipped for attributes,
  properties and module data.
- **Option names stay two hyphens.** Docutils' smart quotes turn ``--`` into an en dash, so an
  option named in prose (``--out``, ``--track``: the argparse help texts and the docstrings)
  rendered as "–out" and failed when pasted into a shell. Each ``--option`` token in running text
  becomes inline code before the smart quotes run; prose dashes (" -- ") keep their typography.
- **The check**: after an HTML build, no page may contain an en or em dash directly before a
  letter after a space (the option glitch) or a napoleon "Type" field; the build fails naming the
  page (``.ci/run`` builds with ``-W``, so CI catches a regression).
"""

from __future__ import annotations

import re
from pathlib import Path

from docutils import nodes
from sphinx.ext.napoleon import _process_docstring
from sphinx.transforms import SphinxTransform
from sphinx.util.nodes import is_smartquotable

#: an option name: two hyphens and a letter, not inside a word or after another hyphen
OPTION = re.compile(r"(?<![\w\-])--[A-Za-z][\w\-]*")
#: the glitch in built HTML: a space, an en/em dash, a letter ("–out")
DASHED_OPTION = re.compile(r"(?:\s|\()[\u2013\u2014][A-Za-z]")
#: napoleon's inline attribute type, rendered as a field named "Type"
TYPE_FIELD = re.compile(r'<dt class="field-[a-z]+">Type<')


def split_options(text: str) -> list[tuple[str, bool]]:
    """``text`` as pieces ``(piece, is_option)``: each ``--option`` token separate."""
    pieces, pos = [], 0
    for m in OPTION.finditer(text):
        if m.start() > pos:
            pieces.append((text[pos:m.start()], False))
        pieces.append((m.group(0), True))
        pos = m.end()
    if pos < len(text):
        pieces.append((text[pos:], False))
    return pieces


class OptionsAsLiterals(SphinxTransform):
    """Wrap ``--option`` tokens of running text in literal nodes (before SmartQuotes, 750)."""

    default_priority = 740

    def apply(self, **kwargs) -> None:
        for text in list(self.document.findall(nodes.Text)):
            if "--" not in text or text.parent is None or not is_smartquotable(text):
                continue
            pieces = split_options(str(text))
            if not any(is_option for _, is_option in pieces):
                continue
            new = [nodes.literal(piece, piece) if is_option else nodes.Text(piece)
                   for piece, is_option in pieces]
            text.parent.replace(text, new)


def napoleon_except_attributes(app, what, name, obj, options, lines):
    """Napoleon for functions, classes and methods; attribute docstrings as written."""
    if what in ("attribute", "property", "data"):
        return
    _process_docstring(app, what, name, obj, options, lines)


def glitches(html: str) -> list[str]:
    """The copy-breaking glitches in one built page (see the module docstring)."""
    found = []
    for m in DASHED_OPTION.finditer(html):
        found.append("a dash before a letter: " + repr(html[max(0, m.start() - 40):m.end() + 20]))
    if TYPE_FIELD.search(html):
        found.append("a napoleon 'Type' field (an attribute docstring split at a colon)")
    return found


def _check_pages(app, exception):
    if exception is not None or app.builder.format != "html":
        return
    problems = []
    out = Path(app.outdir)
    for page in sorted(out.rglob("*.html")):
        if page.relative_to(out).parts[0] in ("_modules", "_static", "_sources"):
            continue  # highlighted source code, not prose
        html = page.read_text(encoding="utf-8")
        problems += [f"{page.relative_to(out)}: {g}" for g in glitches(html)]
    if problems:
        raise RuntimeError("built pages that cannot be copied as written:\n  "
                           + "\n  ".join(problems))


def setup(app):
    app.setup_extension("sphinx.ext.napoleon")
    for listener in list(app.events.listeners.get("autodoc-process-docstring", [])):
        if listener.handler is _process_docstring:
            app.disconnect(listener.id)
    app.connect("autodoc-process-docstring", napoleon_except_attributes)
    app.add_transform(OptionsAsLiterals)
    app.connect("build-finished", _check_pages)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
