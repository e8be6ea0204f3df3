#!/usr/bin/env bash
# Regenerate python/trackwheel/_core.pyi, the type stubs of the compiled module, from the built
# extension (tests/test_stubs.py fails when they drift from it). Needs pybind11-stubgen:
#   pip install pybind11-stubgen && bash scripts/stubgen.sh
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
pybind11-stubgen trackwheel._core -o "$out"
cp "$out/trackwheel/_core.pyi" "$repo/python/trackwheel/_core.pyi"
echo "wrote $repo/python/trackwheel/_core.pyi"
