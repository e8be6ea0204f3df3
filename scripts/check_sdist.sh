#!/usr/bin/env bash
# Release check: the sdist alone is enough. Builds the sdist of this checkout, installs it (with
# its test extra) into a fresh virtual environment -- pip compiles the C++ kernel from the sdist's
# own sources in an isolated build environment -- and runs the test suite from the unpacked sdist,
# so that the tests, their data and the notebooks come from the sdist too, not from the checkout.
#
#   bash scripts/check_sdist.sh                 # the whole suite (tests/ and the notebooks)
#   bash scripts/check_sdist.sh tests -q -x     # arguments go to pytest
#   PYTHON=python3.12 bash scripts/check_sdist.sh
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
python="${PYTHON:-python3}"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/trackwheel-sdist.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT

start=$SECONDS
echo "== build the sdist of $repo"
"$python" -m venv "$tmp/build-venv"
"$tmp/build-venv/bin/pip" install -q build
"$tmp/build-venv/bin/python" -m build --sdist --outdir "$tmp/dist" "$repo"
sdist="$(ls "$tmp"/dist/trackwheel-*.tar.gz)"
echo "== $(basename "$sdist"): $(tar -tzf "$sdist" | wc -l) files, $(du -h "$sdist" | cut -f1)"
built=$SECONDS

echo "== install it alone into a fresh venv"
"$python" -m venv "$tmp/venv"
export VIRTUAL_ENV="$tmp/venv"
export PATH="$VIRTUAL_ENV/bin:$PATH"
unset PYTHONPATH PYTHONHOME
pip install -q "trackwheel[test] @ file://$sdist"
installed=$SECONDS

echo "== pytest $* (from the unpacked sdist; trackwheel imported from the venv)"
mkdir "$tmp/src"
tar -xzf "$sdist" -C "$tmp/src"
cd "$tmp"/src/trackwheel-*
python -c 'import trackwheel, sys; assert "site-packages" in trackwheel.__file__, trackwheel.__file__'
status=0
pytest "$@" || status=$?
echo "== sdist check: build $((built - start)) s, install $((installed - built)) s," \
     "tests $((SECONDS - installed)) s; pytest exit code $status"
exit "$status"
