// Validation limits, defined once for the kernel and exported to Python (_core.MAX_ELEMENTS,
// _core.MAX_DENSE_EIGEN_DOF, _core.GAUSS_RANGE, _core.MAX_SPEED, _core.MAX_SUPPORTS), so the
// Scene layer and the kernel accept the same inputs. python/trackwheel/base/limits.py holds a
// plain copy (a Scene is built without the compiled module); tests/test_limits.py checks it.
#pragma once

namespace trackwheel::limits {

// Most rail elements [-]: a 500 m track at 8 elements per 0.6 m bay needs ~6700; 20000 allows
// 1.5 km at that density (or 0.25 mm elements on the paper's 5 m rail). Everything per element
// is banded, O(n) in memory and time: statics (its tolerance scales with sqrt(n), statics.cpp),
// the time loops and the partial (sparse) eigen solver; only the dense eigen paths are O(n^2)
// in memory and O(n^3) in time, and they are bounded by kMaxDenseEigenDof instead.
constexpr int kMaxElements = 20000;
// Most coordinates of a dense generalised eigenproblem [-] (the dense eigen analysis and the
// linear path's modal reduction): 4000 x 4000 is 128 MB per matrix and about a minute of
// LAPACK; larger meshes use the partial shift-invert solver (trackwheel.eigen, method="sparse").
constexpr int kMaxDenseEigenDof = 4000;
// Gauss points per element for the elastic forces [-] (the rail's and a section's, cable or
// shear-deformable): one point under-integrates the bending stiffness (singular,
// zero-frequency modes); ten integrate the exact-curvature forces to round-off. The quadrature
// table itself (gauss_points) holds the rules of 1 .. kMaxGauss points.
constexpr int kMinGauss = 2;
constexpr int kMaxGauss = 10;
// Highest forward speed [m/s] (1080 km/h): far beyond the paper's 300 km/h; the contact search
// and the derived time steps are not meant for faster runs.
constexpr double kMaxSpeed = 300.0;
// Most supports on one rail [-]: a guard against a tiny spacing exhausting memory (5 m at
// 0.5 m spacing has nine; 1.5 km of sleepers every 0.6 m, 2500).
constexpr int kMaxSupports = 100000;

// Most harmonics n on each side of the periodic level's moving-load receptance matrix
// (harmonics -n..n) [-]: a guard of the kernel's quadrature (its panels grow with n), well above
// what trackwheel.periodic asks for; not a scene limit, so not exported.
constexpr int kMaxPeriodicHarmonics = 200;

}  // namespace trackwheel::limits
