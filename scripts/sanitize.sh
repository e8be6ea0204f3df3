#!/usr/bin/env bash
# Build trackwheel's C++ extension with AddressSanitizer + UndefinedBehaviorSanitizer
# (CMake option TRACKWHEEL_SANITIZE=ON) and run the fast test suite against it.
#
#   bash scripts/sanitize.sh                  # tests/ without the slow marker
#   bash scripts/sanitize.sh tests/test_kernel_guards.py -x   # any pytest arguments instead
#
# The extension is built with CMake + Ninja into $SANITIZE_BUILD_DIR (default
# ${TMPDIR:-/tmp}/trackwheel-sanitize, reused between runs) and put next to a copy of the Python
# package in that folder, which goes first on PYTHONPATH, so neither the repository nor an
# installed trackwheel is touched. Python is not instrumented, so the ASan runtime is preloaded
# (LD_PRELOAD) and leak detection is off (CPython's own allocations would be reported). Every
# ASan or UBSan report aborts the process: the run is clean only if pytest passes. The Ctrl-C,
# thread and hypothesis tests run too (the hypothesis deadline is generous enough for the ~3x
# slower instrumented kernel).
#
# Needs g++ (or clang) with libasan; installs the build requirements (pybind11, cmeel-eigen,
# cmake, ninja) into the current Python environment with pip if they are missing. PYTHON names
# the interpreter (default python3); it must not have trackwheel installed in editable mode,
# whose import hook would shadow the sanitized copy.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
python="${PYTHON:-python3}"
build="${SANITIZE_BUILD_DIR:-${TMPDIR:-/tmp}/trackwheel-sanitize}"
start=$SECONDS

# ---- build requirements -----------------------------------------------------------------------
missing=()
"$python" -c "import pybind11" 2>/dev/null || missing+=(pybind11)
"$python" -c "import cmeel_eigen" 2>/dev/null \
  || "$python" -c "import os,sys; sys.exit(not any(os.path.isdir(os.path.join(p, 'cmeel.prefix')) for p in sys.path))" \
  || missing+=(cmeel-eigen)
command -v cmake >/dev/null || missing+=(cmake)
command -v ninja >/dev/null || missing+=(ninja)
if ((${#missing[@]})); then
  echo "== installing build requirements: ${missing[*]}"
  "$python" -m pip install --quiet "${missing[@]}"
  hash -r
fi
cxx="${CXX:-g++}"
libasan="$("$cxx" -print-file-name=libasan.so)"
if [[ ! -e "$libasan" ]]; then
  echo "sanitize.sh: $cxx has no libasan.so (install the compiler's ASan runtime)" >&2
  exit 2
fi

# ---- sanitized build --------------------------------------------------------------------------
echo "== configuring and building the sanitized extension in $build"
cmake -S "$repo" -B "$build" -G Ninja \
  -DSKBUILD_PROJECT_NAME=trackwheel -DSKBUILD_PROJECT_VERSION=0.1.0 \
  -Dpybind11_DIR="$("$python" -c 'import pybind11; print(pybind11.get_cmake_dir())')" \
  -DPython_EXECUTABLE="$(command -v "$python")" \
  -DCMAKE_CXX_COMPILER="$(command -v "$cxx")" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTRACKWHEEL_SANITIZE=ON >"$build.cmake.log" 2>&1 \
  || { cat "$build.cmake.log" >&2; exit 1; }
ninja -C "$build" -j "${SANITIZE_JOBS:-2}" _core

# a copy of the Python package with the sanitized extension in it
pkg="$build/pkg/trackwheel"
rm -rf "$build/pkg"
mkdir -p "$pkg"
cp "$repo"/python/trackwheel/*.py "$repo"/python/trackwheel/*.pyi "$pkg/"
cp "$build"/_core*.so "$pkg/"

# ---- tests ------------------------------------------------------------------------------------
# libstdc++ is preloaded too, so that ASan intercepts C++ exceptions thrown by other extension
# modules (matplotlib's) as well
libstdcxx="$("$cxx" -print-file-name=libstdc++.so)"
export LD_PRELOAD="$libasan:$libstdcxx${LD_PRELOAD:+:$LD_PRELOAD}"
export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1:strict_init_order=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export PYTHONPATH="$build/pkg"
export PYTHONDONTWRITEBYTECODE=1

core="$("$python" -c 'import trackwheel._core as c; print(c.__file__)')"
case "$core" in
  "$pkg"/*) echo "== testing against $core" ;;
  *) echo "sanitize.sh: imported $core instead of the sanitized build" >&2; exit 1 ;;
esac

cd "$repo"
if (($# == 0)); then
  set -- tests -m "not slow" -q
fi
status=0
"$python" -m pytest -p no:cacheprovider "$@" || status=$?
if ((status != 0)); then
  echo "== sanitizer run FAILED (pytest exit code $status) after $((SECONDS - start)) s" >&2
  exit "$status"
fi
echo "== sanitizer run clean (ASan + UBSan, no reports, tests passed) in $((SECONDS - start)) s"
