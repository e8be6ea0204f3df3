"""The package's imports flow one way, layer by layer, with no cycle and no private name taken
from another module.

The layers, lowest first (docs/development.md): ``base`` (limits, units, checks) ->
``excitation`` -> ``scene`` -> ``run`` (the only one that calls the compiled ``_core``) ->
``study`` -> ``plots`` -> ``reproduce`` -> ``cli``. A module may import its own layer and the
layers below it, never one above.

The graph is built from the source with ``ast``: an edge a -> b for every import in module a
that names module b -- ``import trackwheel.b``, ``from .b import x``, ``from . import b`` (b a
submodule), relative or absolute -- at module level *and* inside functions (lazy imports load a
heavy dependency late, but they still make a dependency, and a cycle through them is a cycle);
only ``if TYPE_CHECKING:`` blocks, which never run, are left out.
"""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

import trackwheel

PACKAGE = Path(__file__).resolve().parents[1] / "python" / "trackwheel"
#: the layers, lowest first
LAYERS = ("base", "excitation", "scene", "run", "study", "plots", "reproduce", "cli")
#: modules outside the layer folders and the layer each belongs to (the package's own
#: __init__, the public API, sits above every layer)
TOP = {"_version": "base", "_core": "run", "__init__": None}


def module_names(package: Path = PACKAGE) -> set[str]:
    """Dotted names of the package's modules relative to it ("run.simulate", "scene" for
    scene/__init__.py, "__init__" for the package itself), the compiled module included."""
    names = set()
    for path in package.rglob("*.py"):
        parts = list(path.relative_to(package).with_suffix("").parts)
        if parts[-1] == "__init__" and len(parts) > 1:
            parts = parts[:-1]
        names.add(".".join(parts))
    names |= {p.name.split(".")[0] for p in package.glob("*.pyi")}
    return names


def _is_package(name: str, package: Path) -> bool:
    return name == "__init__" or (package / name.replace(".", "/") / "__init__.py").is_file()


def _imports(tree: ast.Module):
    """Every import statement of ``tree`` except those under ``if TYPE_CHECKING:``."""
    skip = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            skip |= {id(n) for child in node.body for n in ast.walk(child)}
    for node in ast.walk(tree):
        if isinstance(node, (ast.Import, ast.ImportFrom)) and id(node) not in skip:
            yield node


def _base(name: str, level: int, package: Path) -> list[str]:
    """The package a relative import of ``level`` in module ``name`` starts from."""
    parts = [] if name == "__init__" else name.split(".")
    if not _is_package(name, package):
        parts = parts[:-1]
    return parts[:len(parts) - (level - 1)] if level > 1 else parts


def _targets(node, name: str, names: set[str], package: Path) -> set[tuple[str, str]]:
    """(module imported, name taken from it or "") for one import statement of ``name``."""
    out = set()
    if isinstance(node, ast.Import):
        for a in node.names:
            parts = a.name.split(".")
            if parts[0] == "trackwheel":
                out.add((".".join(parts[1:]) or "__init__", ""))
        return out
    if node.level == 0:
        parts = (node.module or "").split(".")
        if parts[0] != "trackwheel":
            return out
        parts = parts[1:]
    else:
        parts = _base(name, node.level, package) + (node.module.split(".") if node.module else [])
    module = ".".join(parts) or "__init__"
    for a in node.names:
        sub = ".".join([*parts, a.name])
        if sub in names:  # from pkg import submodule
            out.add((sub, ""))
        else:
            out.add((module, a.name))
    return out


def import_graph(package: Path = PACKAGE) -> dict[str, set[tuple[str, str]]]:
    """module -> {(imported module, name taken or "")}, every import counted (lazy ones too)."""
    names = module_names(package)
    graph = {}
    for path in sorted(package.rglob("*.py")):
        parts = list(path.relative_to(package).with_suffix("").parts)
        if parts[-1] == "__init__" and len(parts) > 1:
            parts = parts[:-1]
        name = ".".join(parts)
        edges = set()
        for node in _imports(ast.parse(path.read_text(encoding="utf-8"))):
            edges |= _targets(node, name, names, package)
        graph[name] = {(m, n) for m, n in edges if m != name}
    return graph


def modules(graph) -> dict[str, set[str]]:
    return {a: {m for m, _ in edges} for a, edges in graph.items()}


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


def layer(module: str) -> str | None:
    """The layer of a module: its top folder, or TOP's entry."""
    head = module.split(".")[0]
    return TOP[head] if head in TOP else head


def test_every_module_is_in_a_layer():
    graph = import_graph()
    assert {"run.simulate", "study.analysis", "scene.scene", "base.limits", "cli.main"} <= set(
        graph)
    unknown = {m for m in graph if m != "__init__" and layer(m) not in LAYERS}
    assert unknown == set()


def test_the_import_graph_has_no_cycle_lazy_imports_included():
    cycle = find_cycle(modules(import_graph()))
    assert cycle is None, " -> ".join(cycle)


def test_a_layer_never_imports_a_higher_one():
    rank = {name: i for i, name in enumerate(LAYERS)}
    upward = []
    for a, targets in modules(import_graph()).items():
        if a == "__init__":
            continue
        for b in targets:
            if layer(b) is None or rank[layer(b)] > rank[layer(a)]:
                upward.append(f"{a} -> {b}")
    assert upward == []


def test_only_the_run_layer_calls_the_kernel():
    callers = {a for a, targets in modules(import_graph()).items() if "_core" in targets}
    assert callers and all(layer(a) == "run" for a in callers), sorted(callers)


def test_no_private_name_is_taken_from_another_module():
    private = sorted(f"{a}: {name} from {m}" for a, edges in import_graph().items()
                     for m, name in edges if name.startswith("_") and not name.startswith("__"))
    assert private == []


def test_internal_imports_use_the_layered_paths():
    """The old flat module paths (trackwheel.simulate, ...) are aliases for users: inside the
    package every import names a module that is a file of the tree."""
    names = module_names()
    stale = sorted(f"{a} -> {m}" for a, edges in import_graph().items() for m, _ in edges
                   if m not in names)
    assert stale == []


@pytest.mark.parametrize("old, new", sorted(trackwheel.FLAT_MODULES.items()))
def test_the_flat_module_paths_still_import(old, new):
    """``import trackwheel.<old>`` gives the module that now lives at ``<new>`` (its names,
    its globals)."""
    assert importlib.import_module(f"trackwheel.{old}") is importlib.import_module(
        f"trackwheel.{new}")


# ---- the check itself ------------------------------------------------------------------------
def _tree(tmp_path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return tmp_path


@pytest.mark.parametrize("source, cycle", [
    ({"a.py": "from . import b\n", "b.py": "from .c import x\n", "c.py": "from .a import y\n"},
     ["a", "b", "c", "a"]),
    ({"a.py": "import trackwheel.b\n", "b.py": "from trackwheel.a import z\n"},
     ["a", "b", "a"]),
    ({"a.py": "try:\n    from .b import q\nexcept ImportError:\n    pass\n",
      "b.py": "from . import a\n"}, ["a", "b", "a"]),
    ({"a.py": "def f():\n    from .b import q\n", "b.py": "from . import a\n"}, ["a", "b", "a"]),
    ({"p/__init__.py": "from .x import y\n", "p/x.py": "def f():\n    from ..q import z\n",
      "q.py": "from .p import y\n"}, ["p", "p.x", "q", "p"]),
])
def test_the_check_finds_an_added_cycle(tmp_path, source, cycle):
    assert find_cycle(modules(import_graph(_tree(tmp_path, source)))) == cycle


def test_the_check_ignores_type_checking_imports(tmp_path):
    package = _tree(tmp_path, {"a.py": "from . import b\n", "b.py": (
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from . import a\n")})
    assert modules(import_graph(package)) == {"a": {"b"}, "b": set()}


def test_the_check_sees_private_names_and_submodules(tmp_path):
    package = _tree(tmp_path, {"p/__init__.py": "", "p/x.py": "from . import y\n",
                               "p/y.py": "from .x import _hidden\nfrom ..q import z\n",
                               "q.py": ""})
    graph = import_graph(package)
    assert graph["p.x"] == {("p.y", "")}
    assert graph["p.y"] == {("p.x", "_hidden"), ("q", "z")}
