"""The Python examples of the README and of the documentation's guide pages run as written.

Each page's ```python blocks are executed in order in one namespace (a reader pasting them one
after the other), in a temporary working directory, with warnings as errors like the rest of the
suite. A block that raises fails the test naming the page and the block. The blocks are kept
fast (seconds per page); what they print in comments is checked by reading, not here: the
physics behind each number is asserted by the tests of its module.
"""

from __future__ import annotations

import re
import traceback
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
#: a fenced block that starts with ```python at the start of a line and ends at the next ```
FENCE = re.compile(r"^```python\n(.*?)^```", re.DOTALL | re.MULTILINE)
PAGES = [ROOT / "README.md", ROOT / "docs" / "getting-started.md",
         *sorted((ROOT / "docs" / "guide").glob("*.md"))]


def python_blocks(text: str) -> list[str]:
    return FENCE.findall(text)


def test_the_fence_pattern_finds_blocks_and_only_python_ones():
    text = "a\n```python\nx = 1\n```\n```bash\nls\n```\n  ```python\nindented\n```\n" \
           "```python\ny = 2\nz = 3\n```\n"
    assert python_blocks(text) == ["x = 1\n", "y = 2\nz = 3\n"]


@pytest.mark.parametrize("page", [p for p in PAGES if p.exists()],
                         ids=lambda p: p.relative_to(ROOT).as_posix())
def test_python_blocks_run_as_written(page, tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    monkeypatch.chdir(tmp_path)
    blocks = python_blocks(page.read_text(encoding="utf-8"))
    if page.name == "README.md":
        assert blocks, "the README has Python examples"
    namespace = {"__name__": "doc_example"}
    for i, block in enumerate(blocks, start=1):
        try:
            exec(compile(block, f"{page.name}, python block {i}", "exec"), namespace)
        except Exception:
            pytest.fail(f"{page.relative_to(ROOT)}, Python block {i} fails as written:\n"
                        f"{block}\n{traceback.format_exc()}", pytrace=False)
