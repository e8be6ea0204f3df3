"""The package's internal imports flow one way (Scene -> kernel -> Result -> analysis -> plots).

The graph is built from the source with ``ast``: an edge a -> b for every module-level
``from . import b`` / ``from .b import ...`` / ``import trackwheel.b`` in module a (imports inside
functions are left out: they are how optional heavy dependencies are loaded late, and they cannot
hide a cycle at import time). The test fails as soon as someone adds a cycle.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "python" / "trackwheel"


def _targets(node: ast.stmt, names: set[str]) -> set[str]:
    """Sibling modules that one module-level import statement imports."""
    if isinstance(node, ast.ImportFrom) and node.level == 1:
        if node.module is None:  # from . import a, b
            return {a.name for a in node.names if a.name in names}
        return {node.module.split(".")[0]} & names
    if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
        parts = node.module.split(".")
        if parts[0] == "trackwheel" and len(parts) > 1:
            return {parts[1]} & names
    if isinstance(node, ast.Import):
        return {a.name.split(".")[1] for a in node.names
                if a.name.startswith("trackwheel.")} & names
    return set()


def _module_level(tree: ast.Module):
    """Module-level statements, including those under ``if`` / ``try`` (but not under
    ``if TYPE_CHECKING:``, which never runs)."""
    for node in tree.body:
        if isinstance(node, ast.If):
            test = ast.unparse(node.test)
            if "TYPE_CHECKING" not in test:
                yield from node.body
            yield from node.orelse
        elif isinstance(node, ast.Try):
            yield from node.body
        else:
            yield node


def import_graph(package: Path = PACKAGE) -> dict[str, set[str]]:
    names = {p.stem for p in package.glob("*.py")} | {p.stem for p in package.glob("*.pyi")}
    graph = {}
    for path in sorted(package.glob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        edges = set()
        for node in _module_level(tree):
            edges |= _targets(node, names)
        graph[path.stem] = edges - {path.stem}
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle [a, b, ..., a] of the directed graph, or None (depth-first search)."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return path[path.index(nxt):] + [nxt]
            if nxt not in state and (found := visit(nxt)):
                return found
        path.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state and (found := visit(node)):
            return found
    return None


def test_the_package_import_graph_has_no_cycle():
    graph = import_graph()
    assert {"simulate", "analysis", "convergence", "results", "defaults"} <= set(graph)
    assert find_cycle(graph) is None, " -> ".join(find_cycle(graph))


def test_data_flows_one_way():
    """The layers named in issue 11: results and defaults know nothing of the runs that use
    them; simulate knows nothing of analysis; analysis nothing of simulate."""
    graph = import_graph()
    assert "simulate" not in graph["analysis"] and "convergence" not in graph["analysis"]
    assert not graph["simulate"] & {"analysis", "convergence", "sweep", "fidelity", "cli"}
    assert not graph["results"] & {"simulate", "analysis", "defaults"}


@pytest.mark.parametrize("source, cycle", [
    ({"a": "from . import b\n", "b": "from .c import x\n", "c": "from .a import y\n"},
     ["a", "b", "c", "a"]),
    ({"a": "import trackwheel.b\n", "b": "from trackwheel.a import z\n"}, ["a", "b", "a"]),
    ({"a": "try:\n    from .b import q\nexcept ImportError:\n    pass\n",
      "b": "from . import a\n"}, ["a", "b", "a"]),
])
def test_the_check_finds_an_added_cycle(tmp_path, source, cycle):
    for name, text in source.items():
        (tmp_path / f"{name}.py").write_text(text)
    assert find_cycle(import_graph(tmp_path)) == cycle


def test_the_check_ignores_function_level_and_type_checking_imports(tmp_path):
    (tmp_path / "a.py").write_text("from . import b\n")
    (tmp_path / "b.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from . import a\n"
        "def f():\n    from . import a\n    return a\n")
    assert import_graph(tmp_path) == {"a": {"b"}, "b": set()}
    assert find_cycle(import_graph(tmp_path)) is None
