// Linear eigenvalue analysis of the coupled wheel/rail/support system (docs: Model § Eigen
// analysis).
//
// The rail is linearised about the straight reference: the tangent of the ANCF element there is
// exactly an Euler-Bernoulli Hermite beam in y plus a cubic bar in x, and the two decouple, so the
// vertical problem uses the y-coordinates (y, y_s) only and the axial modes are reported apart.
// The wheel is a mass M on the contact spring k attached to the rail at X through the shape
// functions: V = k/2 (Y_w - S_y(X) e)^2. Layered supports append one DOF z_j per sleeper
// (mass m_s, pad k_p to the rail, ballast k_b to the ground). Solves K x = omega^2 M x
// (symmetric-definite).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "rail.hpp"

namespace trackwheel {

struct ModalResult {
  Eigen::MatrixXd frequencies;          // (n_positions, n_modes) [Hz], ascending
  std::vector<Eigen::MatrixXd> shapes;  // per position: (n_dof + 1 + n_sleepers, n_modes), rail
                                        // full coords, the wheel's Y_w, then the sleepers' z_j
                                        // (layered supports); mass-normalised
};

// wheel_mass <= 0: the bare rail on its supports (positions then must hold one dummy entry).
ModalResult vertical_modes(const RailModel& rail, double wheel_mass, double contact_stiffness,
                           const std::vector<double>& positions, int n_modes);

// Axial (x) modes of the bare rail: (n_modes) [Hz] and shapes (n_dof, n_modes).
ModalResult axial_modes(const RailModel& rail, int n_modes);

}  // namespace trackwheel
