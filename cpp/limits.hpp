// Validation limits, defined once for the kernel and exported to Python (_core.MAX_ELEMENTS,
// _core.GAUSS_RANGE, _core.MAX_SPEED), so the Scene layer and the kernel accept the same inputs.
#pragma once

namespace trackwheel::limits {

// Most rail elements [-]: 2.5 mm elements on the 5 m rail. The static Newton (tolerance
// 1e-13 L on the corrections) stops converging in round-off beyond ~3000, and the dense eigen
// analysis costs O(n^3) per wheel position (~25 s at 1000 elements).
constexpr int kMaxElements = 2000;
// Gauss points per element [-]: one point under-integrates the bending stiffness (singular,
// zero-frequency modes); ten integrate the exact-curvature forces to round-off.
constexpr int kMinGauss = 2;
constexpr int kMaxGauss = 10;
// Highest forward speed [m/s] (1080 km/h): far beyond the paper's 300 km/h; the contact search
// and the derived time steps are not meant for faster runs.
constexpr double kMaxSpeed = 300.0;

}  // namespace trackwheel::limits
