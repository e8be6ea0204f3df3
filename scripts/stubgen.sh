#!/usr/bin/env bash
# Regenerate python/trackwheel/_core.pyi, the type stubs of the compiled module, from the built
# extension (tests/test_stubs.py fails when they drift from it). Needs pybind11-stubgen:
#   pip install pybind11-stubgen && bash scripts/stubgen.sh
# The stubs cover the public surface; the submodule _core.testing (the test-only probes and
# benchmark hooks, not public API) is declared as a module without stubs of its own.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
pybind11-stubgen trackwheel._core -o "$out"
python - "$out/trackwheel/_core/__init__.pyi" "$repo/python/trackwheel/_core.pyi" <<'PY'
import sys

src, dst = sys.argv[1:]
text = open(src).read()
assert "from . import testing\n" in text, "expected the submodule testing in the stubs"
text = text.replace("from . import testing\n", "import types\n")
text += ("#: The test-only probes and benchmark hooks of the kernel (not public API, no stubs).\n"
         "testing: types.ModuleType\n")
open(dst, "w").write(text)
PY
echo "wrote $repo/python/trackwheel/_core.pyi"
