// The linear track in the frequency domain (docs: Model § Receptance and decay rate).
//
// Steady harmonic motion q(t) = Re(q e^{i w t}) of the linear track (linear_rail.hpp, either
// beam theory, no wheel) under a unit force at x_e solves Z(w) q = s(x_e),
//   Z(w) = K + i w C - w^2 M + sum_j (k_dyn,j(w) - s_p,j) s_j s_j^T,
// the last term only for layered supports (SupportParams' sleeper vectors): the rail pad
// s_p = k_p + i w c_p in series with the sleeper mass m_s on the ballast s_b = k_b + i w c_b,
// k_dyn = s_p (s_b - m_s w^2) / (s_p + s_b - m_s w^2), replaces the pad spring (K, C hold the
// pads, s_j are the w shape functions at support j). The receptance is alpha(x_r, x_e, w) =
// s(x_r)^T q [m/N]. Z is banded (half bandwidth 3): one pivoted band LU per frequency, O(n).
#pragma once

#include <Eigen/Core>
#include <complex>
#include <vector>

#include "linear_beam.hpp"
#include "rail.hpp"

namespace trackwheel {

// Receptances (n_freq, n_force * n_resp) [m/N] at x_resp [m] for a unit force at each of
// x_force [m] (column e * n_resp + r: response r to force e), at each of freqs [Hz] (>= 0): one
// factorisation of Z per frequency, one solve per force. Throws std::invalid_argument on a
// position outside [0, L], a negative or non-finite frequency, or inconsistent sleeper vectors;
// std::runtime_error where Z(w) is singular (an undamped resonance hit exactly).
Eigen::MatrixXcd receptance(const RailModel& rail, const BeamParams& beam,
                            const std::vector<double>& x_force, const std::vector<double>& x_resp,
                            const std::vector<double>& freqs);

// Vertical natural frequencies (n_pos, n_modes) [Hz] of the linear track with the wheel (mass M
// [kg] on the contact spring k [N/m], attached at each of positions [m] through the w shape
// functions; wheel_mass <= 0: the bare track, one row) and the mass-normalised shapes per
// position, (ny + 1, n_modes) over the y coordinates then the wheel. Dense symmetric-definite
// eigensolver, O(n^3).
Eigen::MatrixXd track_modes(const RailModel& rail, const BeamParams& beam, double wheel_mass,
                            double contact_stiffness, const std::vector<double>& positions,
                            int n_modes, std::vector<Eigen::MatrixXd>* shapes = nullptr);

}  // namespace trackwheel
