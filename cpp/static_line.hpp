// The linear track's quasi-static line in O(1) per wheel position (docs: Model § Outputs).
//
// With the wheel load P at X, the linear track's static rail displacement under it is
//   y(X) = s(X) . q_g - P s(X)^T K^-1 s(X)   (+ G(X) P, the element's own compliance),
// q_g = K^-1 Q_g the track under its own weight. s(X) has the four nonzero entries of the
// element under X, which lie inside K's band, so only the entries of K^-1 within the band are
// needed: the selected inverse, from the band factorisation by the Takahashi (Erisman-Tinney)
// recurrence in O(n b^2) for n coordinates and half bandwidth b. One factorisation and one
// selected inversion for the whole rail, then O(1) per position: a passage over a rail of
// length L costs O(L), where one band solve per position (linear_static_line) costs O(L^2).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "banded.hpp"
#include "linear_beam.hpp"
#include "rail.hpp"

namespace trackwheel {

// The entries of A^-1 within the band of A (|i - j| <= b), A symmetric, from lu, A's in-place
// band LU without pivoting (BandMatrix::factorize). For symmetric A the LU is A = L D L^T with
// U = D L^T, and Z = A^-1 = U^-1 L^-1 satisfies U Z = L^-1, whose upper triangle gives
//   Z_ij = (delta_ij - sum_{k = i+1}^{i+b} U_ik Z_kj) / U_ii   for i <= j <= i + b,
// every Z_kj on the right inside the band (Z_kj = Z_jk for k > j); rows from the last to the
// first, in each row j from i + b down to i. Returns Z in the same band storage (both halves).
BandMatrix band_selected_inverse(const BandMatrix& lu);

// The quasi-static line of the linear track in all its coordinates, as linear_static_line with
// n_modes = 0 (same arguments and result, equal to rounding), in O(1) per position after an
// O(n) set-up. A unilateral ballast (no superposition: an active set per load) falls back to
// linear_static_line's solve per position.
Eigen::VectorXd linear_static_line_selected(const RailModel& rail, const BeamParams& beam,
                                            double load, const std::vector<double>& x,
                                            bool element_compliance = false);

}  // namespace trackwheel
