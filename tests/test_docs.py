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
#: the texts that cite the model: the package, its tests, the notebooks, the README
CITING = [*sorted((ROOT / "python" / "trackwheel").rglob("*.py")),
          *sorted((ROOT / "tests").glob("*.py")),
          *sorted((ROOT / "notebooks").glob("*.ipynb")),
          ROOT / "README.md"]

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
