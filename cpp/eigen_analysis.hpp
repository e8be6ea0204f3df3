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

// One direction's K and M (and the dampers' C) at the straight reference, as sparse triplets over
// local coordinates: the free coordinates of that direction in full order (dofs), then, for the
// vertical pencil, the wheel's Y_w (with a wheel) and the sleepers' z_j (layered supports). Built
// from the band matrices: O(n) memory, for the partial (shift-invert) eigen solver in
// trackwheel.eigen and for the reflection tests.
struct SparsePencil {
  int n = 0;
  std::vector<int> dofs;        // local -> full ANCF index (rail coordinates only)
  std::vector<int> row, col;    // triplet indices, local
  std::vector<double> K, M, C;  // [N/m], [kg], [N s/m] at (row, col)
};

// Which sleepers stand on their ballast in the linearisation (sleepers.hpp): all for the linear
// ballast; a unilateral ballast's states at the track's static state under its own weight (no
// wheel; a sleeper touching its bed counts as closed), so that a sleeper hanging over a void has
// no ballast in the modes and receptances.
std::vector<bool> ballast_states(const RailModel& rail);

// component 0: axial (x) of the bare rail; 1: vertical (y), with the wheel mass on its contact
// spring at X = position if wheel_mass > 0; the ballast in the states of ballast_states().
SparsePencil direction_pencil(const RailModel& rail, int component, double wheel_mass,
                              double contact_stiffness, double position);

// wheel_mass <= 0: the bare rail on its supports (positions then must hold one dummy entry).
ModalResult vertical_modes(const RailModel& rail, double wheel_mass, double contact_stiffness,
                           const std::vector<double>& positions, int n_modes);

// Dense paths: at most limits::kMaxDenseEigenDof coordinates (std::invalid_argument beyond).
// Axial (x) modes of the bare rail: (n_modes) [Hz] and shapes (n_dof, n_modes).
ModalResult axial_modes(const RailModel& rail, int n_modes);

}  // namespace trackwheel
