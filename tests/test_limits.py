"""Every limit once: cpp/limits.hpp is the source, the kernel exports it, and the plain-Python
copy in trackwheel.base.limits (which lets a Scene be built without the compiled module) is the
same; the scene layer and the kernel refuse the same inputs."""

from __future__ import annotations

import subprocess
import sys

import pytest

import trackwheel as tw
from trackwheel import _core
from trackwheel.base import limits


@pytest.mark.parametrize("name", ["MAX_ELEMENTS", "MAX_DENSE_EIGEN_DOF", "GAUSS_RANGE",
                                  "MAX_SPEED", "MAX_SUPPORTS"])
def test_the_python_copy_is_the_kernels(name):
    assert getattr(limits, name) == (tuple(getattr(_core, name)) if name == "GAUSS_RANGE"
                                     else getattr(_core, name))


def test_a_scene_is_built_without_the_compiled_module():
    """Importing the scene layer (base, excitation, scene) and building a scene never loads
    trackwheel._core."""
    code = ("import sys, importlib.util; sys.modules['trackwheel'] = type(sys)('trackwheel'); "
            "sys.modules['trackwheel'].__path__ = [sys.argv[1]]; "
            "from trackwheel.scene import Scene; Scene.ballasted_track(); "
            "assert 'trackwheel._core' not in sys.modules, 'the scene layer loaded _core'")
    package = str(tw.__path__[0])
    subprocess.run([sys.executable, "-c", code, package], check=True)


@pytest.mark.parametrize("n_gauss", [limits.GAUSS_RANGE[0] - 1, limits.GAUSS_RANGE[1] + 1])
def test_the_scene_and_the_kernel_refuse_the_same_gauss_points(n_gauss, section, make_rail):
    """One range for an element's Gauss points: the Rail, the kernel's rail model and an
    element section (cable or shear-deformable) all refuse outside GAUSS_RANGE."""
    with pytest.raises(ValueError, match="n_gauss"):
        tw.Rail(n_gauss=n_gauss)
    with pytest.raises(ValueError, match="n_gauss"):
        make_rail(n_gauss=n_gauss)
    with pytest.raises(ValueError, match="n_gauss"):
        _core.testing.cable_elastic(section(n_gauss=n_gauss), _e0())
    shear = _core.testing.ShearSection()
    shear.length, shear.EA, shear.EI, shear.kGA, shear.rhoA = 0.25, 1e9, 6e6, 5e8, 60.0
    shear.n_gauss = n_gauss
    with pytest.raises(ValueError, match="n_gauss"):
        _core.testing.shear_mass(shear)


def _e0():
    import numpy as np

    return np.array([0.0, 0.0, 1.0, 0.0, 0.25, 0.0, 1.0, 0.0])


def test_the_scene_and_the_kernel_refuse_too_many_supports(make_rail):
    n = limits.MAX_SUPPORTS + 1
    with pytest.raises(ValueError, match="supports"):
        tw.Supports(spacing=1.0 / (n + 2)).resolve(1.0)
    with pytest.raises(ValueError, match=f"at most {limits.MAX_SUPPORTS} supports"):
        make_rail(supports=[0.5] * n, stiffness=1e8)
