"""Sphinx extension: a gallery of the notebooks, one figure each, taken from their stored outputs.

The notebooks are never executed by the docs build (``nb_execution_mode = "off"``): the figure
of each card is the ``index``-th PNG output stored in the notebook, shrunk to a thumbnail and
written to ``docs/_generated/gallery/`` (ignored by git), so the gallery shows what the
notebook pages show and changes when a notebook is re-run and committed.

Directive ``notebook-gallery``; each line of its content is ``NAME INDEX CAPTION``::

    ```{notebook-gallery}
    01_eigen 0 Natural frequencies against the wheel position (Fig. 3), the mode shapes.
    ```

NAME is a notebook under ``docs/notebooks/`` (conf.py mirrors ``notebooks/`` there), INDEX
counts its PNG outputs from 0. Each card links to the notebook's page and is titled by it.
"""

from __future__ import annotations

import base64
import io
import json
import posixpath
from pathlib import Path

from docutils import nodes
from sphinx import addnodes
from sphinx.errors import ExtensionError
from sphinx.util.docutils import SphinxDirective

THUMBNAIL = (640, 420)  # largest thumbnail size [px]


def stored_pngs(notebook: Path) -> list[bytes]:
    """The PNG outputs stored in ``notebook``, in order."""
    data = json.loads(notebook.read_text(encoding="utf-8"))
    pngs = []
    for cell in data.get("cells", []):
        for output in cell.get("outputs", []):
            png = output.get("data", {}).get("image/png")
            if png:
                pngs.append(base64.b64decode("".join(png) if isinstance(png, list) else png))
    return pngs


def thumbnail(png: bytes) -> bytes:
    from PIL import Image  # a dependency of matplotlib, hence of trackwheel

    image = Image.open(io.BytesIO(png))
    image.thumbnail(THUMBNAIL)
    out = io.BytesIO()
    image.save(out, format="PNG", optimize=True)
    return out.getvalue()


class NotebookGallery(SphinxDirective):
    has_content = True

    def run(self):
        srcdir = Path(self.env.srcdir)
        outdir = srcdir / "_generated" / "gallery"
        outdir.mkdir(parents=True, exist_ok=True)
        here = posixpath.dirname(self.env.docname)
        suffix = getattr(self.config, "html_file_suffix", None) or ".html"
        gallery = nodes.container(classes=["tw-gallery"])
        for line in self.content:
            if not line.strip():
                continue
            try:
                name, index, caption = line.split(maxsplit=2)
                index = int(index)
            except ValueError as exc:
                raise ExtensionError(f"notebook-gallery: expected 'NAME INDEX CAPTION', got "
                                     f"{line!r}") from exc
            notebook = srcdir / "notebooks" / f"{name}.ipynb"
            if not notebook.exists():
                raise ExtensionError(f"notebook-gallery: no notebook {notebook}")
            self.env.note_dependency(str(notebook))
            pngs = stored_pngs(notebook)
            if not 0 <= index < len(pngs):
                raise ExtensionError(f"notebook-gallery: {name} stores {len(pngs)} figures, "
                                     f"no figure {index}")
            thumb = outdir / f"{name}.png"
            data = thumbnail(pngs[index])
            if not thumb.exists() or thumb.read_bytes() != data:
                thumb.write_bytes(data)

            docname = f"notebooks/{name}"
            card = nodes.container(classes=["tw-card"])
            link = nodes.reference("", "", internal=True,
                                   refuri=posixpath.relpath(docname, here or ".") + suffix)
            link += nodes.image(uri=f"/_generated/gallery/{name}.png", alt=caption)
            card += link
            title = nodes.paragraph(classes=["tw-card-title"])
            xref = addnodes.pending_xref("", refdomain="std", reftype="doc",
                                         reftarget="/" + docname, refdoc=self.env.docname,
                                         refexplicit=False, refwarn=True)
            xref += nodes.inline(text=name)
            title += xref
            card += title
            card += nodes.paragraph(text=caption)
            gallery += card
        return [gallery]


def setup(app):
    app.add_directive("notebook-gallery", NotebookGallery)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
