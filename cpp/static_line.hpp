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

// The entries Z_ij = (A^-1)_ij with |i - j| <= m of a symmetric band matrix A of half bandwidth
// b <= m, from lu, A's in-place band LU without pivoting (BandMatrix::factorize). For symmetric
// A the LU is A = L D L^T with U = D L^T, and Z = A^-1 = U^-1 L^-1 satisfies U Z = L^-1, whose
// upper triangle gives
//   Z_ij = (delta_ij - sum_{k = i+1}^{i+b} U_ik Z_kj) / U_ii   for i <= j <= i + m,
// every Z_kj on the right within distance m of the diagonal (Z_kj = Z_jk for k > j): rows from
// the last to the first, in each row j from i + m down to i (Takahashi, Fagan & Chin 1973;
// Erisman & Tinney 1975). O(n m b) operations, O(n m) memory.
class BandInverse {
 public:
  BandInverse(const BandMatrix& lu, int m);
  int width() const { return m_; }
  bool covers(int i, int j) const { return i - j <= m_ && j - i <= m_; }
  double at(int i, int j) const { return i <= j ? up_(j - i, i) : up_(i - j, j); }

 private:
  int m_;
  Eigen::MatrixXd up_;  // (m + 1) x n: up_(j - i, i) = Z_ij, j >= i
};

// The quasi-static line of the linear track in all its coordinates, as linear_static_line with
// n_modes = 0 (same arguments and result, equal to rounding), in O(1) per position after an
// O(n) set-up. A unilateral ballast (no superposition: an active set per load) falls back to
// linear_static_line's solve per position.
Eigen::VectorXd linear_static_line_selected(const RailModel& rail, const BeamParams& beam,
                                            double load, const std::vector<double>& x,
                                            bool element_compliance = false);

// The linear track's static flexibility between pairs of positions, s(xa_k)^T K^-1 s(xb_k)
// [m/N] for each k (K with the sleepers condensed at rest, as linear_static_line's; the
// receptance at 0 Hz): from the entries of K^-1 within the largest coordinate distance of a
// pair (BandInverse), O(n m) once and O(1) per pair; where that band would hold more than
// kMaxInverseEntries entries, one band solve per pair instead.
Eigen::VectorXd linear_static_flexibility(const RailModel& rail, const BeamParams& beam,
                                          const std::vector<double>& xa,
                                          const std::vector<double>& xb);

constexpr double kMaxInverseEntries = 2e7;  // 160 MB of doubles

}  // namespace trackwheel
