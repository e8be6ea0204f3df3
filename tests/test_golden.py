"""Golden outputs: the kernel redesign of issue 11 must not change any result.

``tests/data/golden.npz`` holds the outputs of a fixed set of runs recorded on the code before
the redesign (commit 618a45c) by ``tests/data/make_golden.py`` (some groups re-recorded since,
for deliberate changes listed there): both integrators on the full
path, the linear levels (incl. a modal run and a sudden start with damped supports), a Hertz law
with contact damping, a sudden drop with damped supports, a run that slides under a torque, a
standing wheel, eigenfrequencies, static solves and the quasi-static line. Every setting is
explicit there, so a changed default does not change what is compared.

Tolerance: every array must equal the stored one to 1e-10 of the array's largest magnitude.
A pure reorganisation executes the same floating-point operations, so the results are
bit-identical; a reordered sum changes them by a few ulp (~1e-16), which the damped dynamics
of these short runs amplify by far less than 1e6. The scale is the array's max |value| (not
each entry) because entries that cross zero (rail slopes, forces at lift-off) have no relative
accuracy of their own. A change above 1e-10 is a change of results (a different Newton
decision, a changed formula), which must be deliberate and explained. Counters (steps, Newton
iterations, state changes) must be equal.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

DATA = Path(__file__).with_name("data")
RTOL = 1e-10
INTEGER_COUNTERS = ("steps", "newton_iterations", "state_changes")


def _generator():
    spec = importlib.util.spec_from_file_location("make_golden", DATA / "make_golden.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def outputs():
    return _generator().golden_arrays()


@pytest.fixture(scope="module")
def golden():
    with np.load(DATA / "golden.npz") as d:
        return {k: d[k] for k in d.files}


def test_same_keys(outputs, golden):
    assert sorted(outputs) == sorted(golden)


@pytest.mark.parametrize("group", sorted({k.split("/")[0] for k in
                                          np.load(DATA / "golden.npz").files}))
def test_outputs_unchanged(outputs, golden, group):
    for key in sorted(k for k in golden if k.split("/")[0] == group):
        new, old = np.asarray(outputs[key], dtype=float), golden[key]
        assert new.shape == old.shape, key
        if key.rsplit("/", 1)[-1] in INTEGER_COUNTERS:
            assert np.array_equal(new, old), key
            continue
        scale = float(np.max(np.abs(old))) if old.size else 0.0
        err = float(np.max(np.abs(new - old))) if old.size else 0.0
        assert err <= RTOL * scale, f"{key}: max |diff| {err:.3g} > {RTOL:g} x {scale:.3g}"
