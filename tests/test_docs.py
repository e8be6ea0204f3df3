"""The documentation's sources (docs/): what the code and notebooks cite exists in them, and the
API reference lists the whole public API. The HTML build itself runs in .ci/run
(`sphinx-build -W`, warnings are errors)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import trackwheel as tw

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
#: the texts that cite the model: the package, its tests, the notebooks, the README, the guide
CITING = [*sorted((ROOT / "python" / "trackwheel").rglob("*.py")),
          *sorted((ROOT / "tests").glob("*.py")),
          *sorted((ROOT / "notebooks").glob("*.ipynb")),
          ROOT / "README.md",
          *sorted((ROOT / "docs" / "guide").glob("*.md"))]

pytestmark = pytest.mark.skipif(not (DOCS / "model.md").exists(),
                                reason="docs/ is not part of this tree")


def _sections() -> set[str]:
    text = (DOCS / "model.md").read_text(encoding="utf-8")
    return {m.group(1).strip() for m in re.finditer(r"^#{2,3} (.+)$", text, re.MULTILINE)}


def test_nothing_cites_a_file_outside_the_repository():
    this = Path(__file__).resolve()
    offenders = [p.name for p in CITING
                 if p.resolve() != this and "MODEL" + ".md" in p.read_text(encoding="utf-8")]
    assert offenders == []


def test_every_cited_model_section_exists():
    """Each section a citation of the model names (after "Model §", and every further "§" of a
    list on the same line) is a heading of docs/model.md."""
    sections = _sections()
    cited = set()
    for p in CITING:
        text = p.read_text(encoding="utf-8")
        for m in re.finditer(r"Model §[^\n]*", text):
            cited |= {c for c in re.findall(r"§ ([A-Z][a-z]+(?: [a-z]+)*)", m.group(0))}
    assert cited, "no citations found"
    unknown = {c for c in cited
               if not any(c == s or c.startswith(s + " ") for s in sections)}
    assert unknown == set(), f"not a section of docs/model.md: {unknown}; sections: {sections}"


def test_api_reference_lists_the_public_api():
    api = (DOCS / "api.md").read_text(encoding="utf-8")
    directive = r"^\.\. auto(?:class|function|exception|data):: trackwheel\.(\w+)$"
    documented = set(re.findall(directive, api, re.MULTILINE))
    public = set(tw.__all__) - {"__version__"}
    assert public - documented == set()
    assert documented - public == set()  # nothing documented that is not public


# Sphinx's own napoleon reads autodoc's options as a mapping (deprecated in Sphinx 9)
@pytest.mark.filterwarnings("ignore:The mapping interface for autodoc options")
def test_built_pages_keep_option_names_and_attribute_docstrings(tmp_path):
    """The API and command-line references as Sphinx builds them (a one-page project with the
    docs' own extension, docs/_ext/tw_text.py): an attribute docstring with a colon renders
    whole (napoleon would split it into a "Type" field at the colon), and ``--out`` in the help
    texts stays two hyphens in inline code (smart quotes would make it an en dash, which fails
    when pasted into a shell). The full site runs the same check after every HTML build."""
    pytest.importorskip("sphinx")
    pytest.importorskip("sphinxarg")
    import sys

    from sphinx.application import Sphinx

    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        import tw_text
    finally:
        sys.path.remove(str(DOCS / "_ext"))
    (tmp_path / "conf.py").write_text(
        f"import sys\nsys.path.insert(0, {str(DOCS / '_ext')!r})\n"
        "extensions = ['sphinx.ext.autodoc', 'sphinxarg.ext', 'tw_text']\n", encoding="utf-8")
    (tmp_path / "index.rst").write_text(
        "Page\n====\n\n.. autoclass:: trackwheel.Supports\n   :members:\n\n"
        ".. argparse::\n   :module: trackwheel.cli\n   :func: build_parser\n"
        "   :prog: trackwheel\n", encoding="utf-8")
    out = tmp_path / "html"
    app = Sphinx(str(tmp_path), str(tmp_path), str(out), str(tmp_path / "doctrees"), "html",
                 status=None, warning=None, freshenv=True)
    app.build()
    html = (out / "index.html").read_text(encoding="utf-8")
    assert tw_text.glitches(html) == []
    assert "vertical stiffness of each support [N/m] (layered: pad k_p)" in html
    assert '<span class="pre">--out</span></code>' in html
    # and the check finds what it is for
    assert tw_text.glitches("<p>into \u2013out. Steps</p>")
    assert tw_text.glitches('<dl><dt class="field-odd">Type<span class="colon">')
    assert tw_text.split_options("a --out DIR, not x--y or ---z") == [
        ("a ", False), ("--out", True), (" DIR, not x--y or ---z", False)]


def test_validation_records_are_complete_and_name_existing_tests():
    """docs/validation.json (the Validation page's data, written by ``pytest tests
    --refresh-validation``): at least 30 checks, every level of the model and every kind of
    reference represented, ids unique, each measured error within its tolerance, and each
    record's test still exists (a renamed or deleted test would leave its record behind; its
    own run compares the values, tests/conftest.py)."""
    import json

    from conftest import KINDS, LEVELS

    records = json.loads((DOCS / "validation.json").read_text(encoding="utf-8"))["records"]
    assert len(records) >= 30
    assert {r["level"] for r in records} == set(LEVELS)
    assert {r["kind"] for r in records} == set(KINDS)
    ids = [r["id"] for r in records]
    assert len(ids) == len(set(ids))
    for r in records:
        assert 0.0 <= r["measured"] <= r["tolerance"], r["id"]
        path, name = r["test"].split("::", 1)
        function = name.split("[", 1)[0]
        source = ROOT / path
        assert source.exists(), f"{r['id']}: {path} does not exist"
        assert re.search(rf"^def {function}\(", source.read_text(encoding="utf-8"),
                         re.MULTILINE), f"{r['id']}: no test {function} in {path}"


def test_pages_that_count_the_validation_checks_count_them_right():
    """The README and the landing page say how many checks the Validation page holds."""
    import json

    n = len(json.loads((DOCS / "validation.json").read_text(encoding="utf-8"))["records"])
    for page in (ROOT / "README.md", DOCS / "index.md"):
        counts = re.findall(r"(\d+) checks against", page.read_text(encoding="utf-8"))
        assert counts, page.name
        assert {int(c) for c in counts} == {n}, (page.name, counts, n)
