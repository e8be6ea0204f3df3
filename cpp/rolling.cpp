#include "rolling.hpp"

namespace trackwheel {

Vec10 contact_parameter_gradient(const ContactPoint& pt) {
  // f(q, s) = d . r_s, d = R_A - r(s):  f_q = r_s^T G + d^T [0, S_s],  f_s = -r_s.r_s + d.r_ss
  const Eigen::Vector2d d = pt.rho * pt.n;
  const double fs = -pt.rs.squaredNorm() + d.dot(pt.rss);
  Vec10 fq;
  fq.head<2>() = pt.rs;
  for (int a = 0; a < 4; ++a) fq.segment<2>(2 + 2 * a) = -pt.mp.h.n[a] * pt.rs + pt.mp.h.ns[a] * d;
  return -fq / fs;
}

RollingKinematics rolling_kinematics(const ContactPoint& pt, const Vec10& grad_rho,
                                     const Vec10& qdot, double thetadot, bool want_jacobian) {
  RollingKinematics k;
  const Eigen::Vector2d& t = pt.t;
  // S(s*) edot and S_s(s*) edot
  Eigen::Vector2d Se = Eigen::Vector2d::Zero(), Sse = Eigen::Vector2d::Zero();
  for (int a = 0; a < 4; ++a) {
    Se += pt.mp.h.n[a] * qdot.segment<2>(2 + 2 * a);
    Sse += pt.mp.h.ns[a] * qdot.segment<2>(2 + 2 * a);
  }
  const Eigen::Vector2d u = qdot.head<2>() - Se;
  k.g = t.dot(u) - pt.rho * thetadot;
  k.b.head<2>() = t;
  for (int a = 0; a < 4; ++a) k.b.segment<2>(2 + 2 * a) = -pt.mp.h.n[a] * t;
  k.b(10) = -pt.rho;
  k.ds_dq = contact_parameter_gradient(pt);
  k.s_dot = k.ds_dq.dot(qdot);
  if (!want_jacobian) return k;
  // dt/dq = P_t/|r_s| (R + r_ss ds^T),  R = d r_s/dq at fixed s = [0, 0, Ns_a I]
  const double nrs = pt.rs.norm();
  const Eigen::Matrix2d Pt = (Eigen::Matrix2d::Identity() - t * t.transpose()) / nrs;
  Mat2x10 R = Mat2x10::Zero();
  for (int a = 0; a < 4; ++a) {
    R(0, 2 + 2 * a) = pt.mp.h.ns[a];
    R(1, 2 + 2 * a + 1) = pt.mp.h.ns[a];
  }
  const Mat2x10 dt = Pt * (R + pt.rss * k.ds_dq.transpose());
  // g = t.u - rho thetadot,  du/dq = -(S_s edot) ds^T
  k.dg_dq = dt.transpose() * u - (t.dot(Sse)) * k.ds_dq - thetadot * grad_rho;
  // b = [t; -S^T t; -rho]
  k.db_dq.topRows<2>() = dt;
  for (int a = 0; a < 4; ++a)
    k.db_dq.middleRows<2>(2 + 2 * a) =
        -(pt.mp.h.n[a] * dt + pt.mp.h.ns[a] * t * k.ds_dq.transpose());
  k.db_dq.row(10) = -grad_rho.transpose();
  return k;
}

}  // namespace trackwheel
