"""Every input limit of trackwheel, defined once.

The first group mirrors the C++ kernel's ``cpp/limits.hpp`` (the source: the kernel checks
them too and exports them as ``_core.MAX_ELEMENTS`` ...); this plain-Python copy lets the scene
layer validate without importing the compiled module, and ``tests/test_limits.py`` checks that
the two agree. The second group are limits of the Python side only.
"""

from __future__ import annotations

# --- mirrored from cpp/limits.hpp (tests/test_limits.py checks them against _core) ----------
#: Most rail elements a scene or a call may use [-]: 20000 allows 1.5 km at 8 elements per
#: 0.6 m bay; everything per element is banded, O(n) (the dense eigen paths are bounded by
#: MAX_DENSE_EIGEN_DOF instead).
MAX_ELEMENTS: int = 20000
#: Most coordinates of a dense generalised eigenproblem [-] (the dense eigen analysis and the
#: linear path's modal reduction); larger ones take the partial sparse solver.
MAX_DENSE_EIGEN_DOF: int = 4000
#: Gauss points per element for the elastic forces, (lowest, highest) [-]: one point
#: under-integrates the bending stiffness (singular, zero-frequency modes); ten integrate the
#: exact-curvature forces to round-off.
GAUSS_RANGE: tuple[int, int] = (2, 10)
#: Highest forward speed of a run [m/s] (1080 km/h): far above any railway speed; the contact
#: search and the derived time steps are not meant for faster runs.
MAX_SPEED: float = 300.0
#: Most supports a rail may carry [-] (a guard against a tiny ``Supports.spacing`` exhausting
#: memory; 5 m at 0.5 m spacing has nine).
MAX_SUPPORTS: int = 100_000

# --- the Python side's own limits ------------------------------------------------------------
#: Most time steps one run may take [-] (10^12: far beyond any practical run; keeps the step and
#: decimation counts inside the kernel's integer types).
MAX_STEPS: int = 10**12
#: Output arrays of a run larger than this raise before it starts [bytes].
MAX_OUTPUT_BYTES: int = 2 * 1024**3
#: Largest seed of a random irregularity or a sweep's realisation [-] (numpy's 63-bit range).
MAX_SEED: int = 2**63 - 1
#: Most whole sleeper bays on either side of the vehicle in a travelling window [-].
MAX_WINDOW_BAYS: int = 1000
