#include "rolling.hpp"

namespace trackwheel {

// Without a profile T = S and every "lift" term below vanishes; the S parts keep the element's
// block structure (loops over the four shape functions) and the lift adds T's x-column terms.

Vec10 contact_parameter_gradient(const ContactPoint& pt) {
  // f(q, s) = d . p_s, d = R_A - p(s):  f_q = p_s^T G + d^T [0, T_s],  f_s = -p_s.p_s + d.p_ss
  const Eigen::Vector2d d = pt.rho * pt.n;
  const double fs = -pt.ps.squaredNorm() + d.dot(pt.pss);
  Vec10 fq;
  fq.head<2>() = pt.ps;
  for (int a = 0; a < 4; ++a) fq.segment<2>(2 + 2 * a) = -pt.mp.h.n[a] * pt.ps + pt.mp.h.ns[a] * d;
  if (pt.lifted) {
    const Mat28 T = surface_jacobian(pt), Ts = surface_jacobian_s(pt);
    for (int a = 0; a < 4; ++a) fq(2 + 2 * a) += -T(1, 2 * a) * pt.ps.y() + Ts(1, 2 * a) * d.y();
  }
  return -fq / fs;
}

RollingKinematics rolling_kinematics(const ContactPoint& pt, const Vec10& grad_rho,
                                     const Vec10& qdot, double thetadot, bool want_jacobian) {
  return rolling_kinematics(pt, pt.rho, grad_rho, qdot, thetadot, want_jacobian);
}

RollingKinematics rolling_kinematics(const ContactPoint& pt, double rho, const Vec10& grad_rho,
                                     const Vec10& qdot, double thetadot, bool want_jacobian) {
  RollingKinematics k;
  const Eigen::Vector2d& t = pt.t;
  // T(s*) edot and T_s(s*) edot
  Eigen::Vector2d Se = Eigen::Vector2d::Zero(), Sse = Eigen::Vector2d::Zero();
  for (int a = 0; a < 4; ++a) {
    Se += pt.mp.h.n[a] * qdot.segment<2>(2 + 2 * a);
    Sse += pt.mp.h.ns[a] * qdot.segment<2>(2 + 2 * a);
  }
  const ProfileValue& R = pt.profile;
  if (pt.lifted) {  // x-velocities lift the surface point through R'(x)
    const double xdot = Se.x(), xsdot = Sse.x();
    Se.y() += R.rx * xdot;
    Sse.y() += R.rxx * pt.rs.x() * xdot + R.rx * xsdot;
  }
  const Eigen::Vector2d u = qdot.head<2>() - Se;
  k.g = t.dot(u) - rho * thetadot;
  k.b.head<2>() = t;
  for (int a = 0; a < 4; ++a) k.b.segment<2>(2 + 2 * a) = -pt.mp.h.n[a] * t;
  if (pt.lifted)
    for (int a = 0; a < 4; ++a) k.b(2 + 2 * a) -= R.rx * pt.mp.h.n[a] * t.y();
  k.b(10) = -rho;
  k.ds_dq = contact_parameter_gradient(pt);
  k.s_dot = k.ds_dq.dot(qdot);
  if (!want_jacobian) return k;
  // dt/dq = P_t/|p_s| (D + p_ss ds^T),  D = d p_s/dq at fixed s = [0, T_s]
  const double nps = pt.ps.norm();
  const Eigen::Matrix2d Pt = (Eigen::Matrix2d::Identity() - t * t.transpose()) / nps;
  Mat2x10 D = Mat2x10::Zero();
  D.rightCols<8>() = surface_jacobian_s(pt);
  const Mat2x10 dt = Pt * (D + pt.pss * k.ds_dq.transpose());
  // g = t.u - rho thetadot,  du/dq = -(T_s edot) ds^T - d(T edot)/de at fixed s
  k.dg_dq = dt.transpose() * u - (t.dot(Sse)) * k.ds_dq - thetadot * grad_rho;
  // b = [t; -T^T t; -rho]
  const Mat28 T = surface_jacobian(pt);
  k.db_dq.topRows<2>() = dt;
  for (int a = 0; a < 4; ++a)
    k.db_dq.middleRows<2>(2 + 2 * a) =
        -(pt.mp.h.n[a] * dt + pt.mp.h.ns[a] * t * k.ds_dq.transpose());
  k.db_dq.row(10) = -grad_rho.transpose();
  if (pt.lifted) {
    const Mat28 Ts = surface_jacobian_s(pt);
    Vec8 Sx = Vec8::Zero();  // d x(s*)/d e_el
    for (int a = 0; a < 4; ++a) Sx(2 * a) = pt.mp.h.n[a];
    for (int a = 0; a < 4; ++a)
      k.db_dq.row(2 + 2 * a) -=
          T(1, 2 * a) * dt.row(1) + Ts(1, 2 * a) * t.y() * k.ds_dq.transpose();
    // T depends on e through R'(x(e)): d(T v)/de = e_y R'' (S_x v) S_x at fixed s
    k.dg_dq.tail<8>() -= t.y() * R.rxx * Sx.dot(qdot.tail<8>()) * Sx;
    k.db_dq.block<8, 8>(2, 2) -= t.y() * R.rxx * Sx * Sx.transpose();
  }
  return k;
}

}  // namespace trackwheel
