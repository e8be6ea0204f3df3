"""Sphinx configuration of trackwheel's documentation.

Build (offline, nothing fetched, notebooks not executed):
    pip install ".[docs]" && sphinx-build -W --keep-going -b html docs docs/_build/html

MathJax is not taken from a CDN: the ``jupyter-server-mathjax`` package (a ``docs`` extra) ships
MathJax 2.7, whose files are copied into the built site's ``_static/mathjax``, so the pages
render their equations without a network.
"""

import importlib.util
import re
import shutil
import sys
from pathlib import Path

import trackwheel

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(DOCS / "_ext"))  # the project's own extensions (docs/_ext)

project = "trackwheel"
author = "the trackwheel developers"
copyright = "2026, the trackwheel developers"
release = trackwheel.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "tw_text",  # napoleon without its attribute-type split; --options kept as code
    "tw_validation",  # the Validation page's table from docs/validation.json
    "tw_gallery",  # the landing page's notebook gallery, figures from the stored outputs
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "myst_nb",
    "sphinxarg.ext",
]

# The notebooks live in notebooks/ at the repository root (the test suite runs them there);
# Sphinx reads sources below docs/ only, so they are mirrored into docs/notebooks/ (ignored by
# git). copy2 keeps the modification time, so an unchanged notebook is not re-read.
_NB_SRC = ROOT / "notebooks"
_NB_DST = DOCS / "notebooks"
_NB_DST.mkdir(exist_ok=True)
for _nb in sorted(_NB_SRC.glob("*.ipynb")):
    _target = _NB_DST / _nb.name
    if not _target.exists() or _target.read_bytes() != _nb.read_bytes():
        shutil.copy2(_nb, _target)

exclude_patterns = ["_build", "_generated", "_scripts", "Thumbs.db", ".DS_Store",
                    "**.ipynb_checkpoints"]

# notebooks are shown as stored, never executed by the docs build
nb_execution_mode = "off"
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
suppress_warnings = ["myst.header"]

autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_default_options = {"members": True, "show-inheritance": False}
napoleon_numpy_docstring = True
napoleon_google_docstring = True

# MathJax 2.7 from the jupyter-server-mathjax package, served from the site itself
_MATHJAX_SPEC = importlib.util.find_spec("jupyter_server_mathjax")
if _MATHJAX_SPEC is None or not _MATHJAX_SPEC.submodule_search_locations:
    raise RuntimeError("the docs need the `docs` extra: pip install \".[docs]\" "
                       "(jupyter-server-mathjax provides MathJax offline)")
_MATHJAX_DIR = Path(list(_MATHJAX_SPEC.submodule_search_locations)[0]) / "static"
mathjax_path = "mathjax/MathJax.js?config=TeX-AMS-MML_HTMLorMML-full"
mathjax2_config = {
    # MyST marks its pages tex2jax_ignore and its math spans "math": typeset only those
    "tex2jax": {"inlineMath": [["\\(", "\\)"]], "displayMath": [["\\[", "\\]"]],
                "processRefs": False, "processEnvironments": False,
                "processClass": "tex2jax_process|mathjax_process|math|output_area"},
    "HTML-CSS": {"availableFonts": ["STIX-Web"], "preferredFont": "STIX-Web",
                 "webFont": "STIX-Web", "imageFont": None},
}

html_theme = "pydata_sphinx_theme"
html_title = f"trackwheel {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "header_links_before_dropdown": 5,
    "show_toc_level": 2,
    "navbar_end": ["navbar-icon-links"],
    # no "On this page" column beside the wide Validation table
    "secondary_sidebar_items": {"**": ["page-toc"], "validation": []},
}
html_show_sourcelink = False
html_static_path = ["_static"]
html_css_files = ["trackwheel.css"]
# no empty "Section Navigation" column on the top-level pages (they have no sub-pages), and none
# on the user guide's pages either, whose code lines need the width (the guide's index lists its
# pages, and each page links the next); the notebooks keep it, to move between them
html_sidebars = {"*": [], "guide/*": []}


def _copy_mathjax(app, exception):
    """Ship MathJax with the built site (``_static/mathjax``) after an HTML build."""
    if exception is None and app.builder.format == "html":
        shutil.copytree(_MATHJAX_DIR, Path(app.outdir) / "_static" / "mathjax",
                        dirs_exist_ok=True)


# The docstrings are written to be read as plain text too: |d| means an absolute value there,
# not a reStructuredText substitution. Escape every | outside ``literals``.
_LITERAL_OR_BAR = re.compile(r"(``.*?``)|\|")


def _escape_bars(app, what, name, obj, options, lines):
    lines[:] = [_LITERAL_OR_BAR.sub(lambda m: m.group(1) or r"\|", line) for line in lines]


def setup(app):
    app.connect("autodoc-process-docstring", _escape_bars)
    app.connect("build-finished", _copy_mathjax)
