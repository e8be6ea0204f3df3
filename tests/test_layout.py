"""Files that do one job: no source file of the package over MAX_FILE_LINES lines (the generated
stub aside), no function over MAX_FUNCTION_LINES lines of code (its docstring aside: the
reference a user reads is not cut to fit), no "issue N" in the code (comments and docstrings
say what the code does), and docs/development.md's file list is the tree's."""

from __future__ import annotations

import ast
import importlib.util
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "python" / "trackwheel"
MAX_FILE_LINES = 500
MAX_FUNCTION_LINES = 80


def _sources():
    return sorted(PACKAGE.rglob("*.py"))


def test_no_source_file_is_longer_than_the_limit():
    long = {str(p.relative_to(PACKAGE)): n for p in _sources()
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > MAX_FILE_LINES}
    assert long == {}


def _code_lines(node: ast.FunctionDef) -> int:
    """Lines of a function without its docstring."""
    total = node.end_lineno - node.lineno + 1
    first = node.body[0]
    if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(
            first.value.value, str):
        total -= first.end_lineno - first.lineno + 1
    return total


def test_no_function_is_longer_than_the_limit():
    long = {}
    for path in _sources():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                if (n := _code_lines(node)) > MAX_FUNCTION_LINES:
                    long[f"{path.relative_to(PACKAGE)}:{node.name}"] = n
    assert long == {}


def test_the_code_says_what_it_does_not_when_it_arrived():
    pattern = re.compile(r"\bissues? \d+", re.IGNORECASE)
    kernel = sorted(q for q in (ROOT / "cpp").rglob("*") if q.is_file())
    hits = [f"{p.relative_to(ROOT)}:{i}" for p in [*_sources(), *kernel]
            for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
            if pattern.search(line)]
    assert hits == []


def test_the_documented_file_list_is_the_tree():
    spec = importlib.util.spec_from_file_location("file_list", ROOT / "scripts" / "file_list.py")
    file_list = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(file_list)
    assert file_list.documented() == file_list.file_list(), (
        "run `python scripts/file_list.py` and paste its output into docs/development.md")
