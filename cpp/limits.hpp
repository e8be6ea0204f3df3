// Validation limits, defined once for the kernel and exported to Python (_core.MAX_ELEMENTS,
// _core.GAUSS_RANGE, _core.MAX_SPEED), so the Scene layer and the kernel accept the same inputs.
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
// Gauss points per element [-]: one point under-integrates the bending stiffness (singular,
// zero-frequency modes); ten integrate the exact-curvature forces to round-off.
constexpr int kMinGauss = 2;
constexpr int kMaxGauss = 10;
// Highest forward speed [m/s] (1080 km/h): far beyond the paper's 300 km/h; the contact search
// and the derived time steps are not meant for faster runs.
constexpr double kMaxSpeed = 300.0;

}  // namespace trackwheel::limits
