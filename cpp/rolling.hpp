// Rolling constraint and slip kinematics at the contact point (docs: Model § Rolling and slip).
//
// Slip velocity of the wheel's material point Q against the rail's material point B along the
// tangent t = r_s/|r_s| at s*:
//   g = t . (V_A - S(s*) edot) - rho thetadot.
// Without slip g = 0 is a non-holonomic constraint; its multiplier lambda (tangential contact
// force) enters the equations as lambda b, with b = dg/dqdot:
//   b = [t (on V_A); -S^T t (on edot); -rho (on thetadot)].
// Local coordinate order: q = [X_A, Y_A, e_el(8)] (10), theta separately.
#pragma once

#include <Eigen/Core>

#include "contact.hpp"

namespace trackwheel {

using Mat2x10 = Eigen::Matrix<double, 2, 10>;
using Vec11 = Eigen::Matrix<double, 11, 1>;
using Mat11x10 = Eigen::Matrix<double, 11, 10>;

// d s*/dq from the implicit contact condition (R_A - r(s)).r_s(s) = 0.
Vec10 contact_parameter_gradient(const ContactPoint& pt);

struct RollingKinematics {
  double g = 0.0;      // slip velocity [m/s] (= the constraint value)
  Vec11 b;             // dg/dqdot over [V_A(2), edot_el(8), thetadot]
  Vec10 dg_dq;         // dg/dq at fixed velocities (q = [X_A, Y_A, e_el])
  Mat11x10 db_dq;      // d b/dq (geometric stiffness of the tangential force)
  Vec10 ds_dq;         // d s*/dq
  double s_dot = 0.0;  // ds*/dt [m/s]
};

// qdot = [V_A(2), edot_el(8)], thetadot [rad/s]; grad_rho = d rho/dq. The rolling radius is
// rho = |R_A - p(s*)|.
RollingKinematics rolling_kinematics(const ContactPoint& pt, const Vec10& grad_rho,
                                     const Vec10& qdot, double thetadot, bool want_jacobian);
// The same with the rolling radius rho_r [m] and its gradient d rho_r/dq given: with the
// element compliance (contact.hpp) the distance from the wheel centre to the rail under the
// load, rho + G N_e = rho0 - delta_c, not to the interpolated rail.
RollingKinematics rolling_kinematics(const ContactPoint& pt, double rolling_radius,
                                     const Vec10& grad_rolling_radius, const Vec10& qdot,
                                     double thetadot, bool want_jacobian);

}  // namespace trackwheel
