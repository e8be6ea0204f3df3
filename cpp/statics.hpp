// Static equilibrium of the rail + wheel on its contact spring (docs: Model § Outputs, quasi-static
// line).
//
// Unknowns: the free rail coordinates and the wheel height Y_A; the wheel centre is held at
// X_A = x_wheel. Equations: rail  Q_elastic(e) + Q_support(e) - Q_gravity - Q_contact = 0,
// wheel  N n_y - (F + M g) = 0. Newton on the analytic Jacobian with the bordered banded solver.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.hpp"
#include "model.hpp"
#include "rail.hpp"

namespace trackwheel {

struct StaticResult {
  Eigen::VectorXd e;                 // rail coordinates, full [m, m, -, -]
  double x_wheel = 0.0;              // X_A [m]
  double y_wheel = 0.0;              // Y_A [m]
  double contact_s = 0.0;            // s* [m]
  double y_contact = 0.0;            // y(s*), the contact-point displacement y_B [m]
  double normal_force = 0.0;         // N [N]
  double horizontal_reaction = 0.0;  // force holding X_A [N]
  int iterations = 0;
  Eigen::VectorXd z;  // sleeper heights z_j [m] (layered supports; else empty)
  // the ballast's compression under sleeper j [N]: -k_b z_j, or the unilateral law's (0 open)
  Eigen::VectorXd ballast_force;
  std::vector<bool> closed;  // sleeper j on its ballast (always, for the linear ballast)
};

// e_guess may be empty (starts from the straight rail).
StaticResult solve_static(const RailModel& rail, const WheelParams& wheel,
                          const ContactParams& contact, double x_wheel,
                          const Eigen::VectorXd& e_guess = Eigen::VectorXd(), double y_guess = NAN);

// Static equilibrium of several wheels on the rail, wheel w at X_A = x_wheels[w] under its
// load F_w + M_w g (a vehicle: the loads of its weight distribution) on its contact law
// contacts[w] (with its radius); one result per wheel (the same rail e in each).
std::vector<StaticResult> solve_static_wheels(const RailModel& rail,
                                              const std::vector<WheelParams>& wheels,
                                              const std::vector<ContactParams>& contacts,
                                              const std::vector<double>& x_wheels);
// Static equilibrium of the rail alone under gravity (no wheel).
Eigen::VectorXd solve_rail_static(const RailModel& rail);
// The same with the sleepers' heights and ballast forces.
StaticResult solve_track_static(const RailModel& rail);

// y_qs(X) at each position, warm-starting each solve from the previous one.
std::vector<StaticResult> solve_quasi_static(const RailModel& rail, const WheelParams& wheel,
                                             const ContactParams& contact,
                                             const std::vector<double>& positions);

}  // namespace trackwheel
