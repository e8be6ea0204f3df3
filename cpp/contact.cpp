#include "contact.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace trackwheel {

namespace {
// Centre line and running surface at s; the profile read at x + profile_shift.
void surface_at(const RailModel& rail, const Eigen::VectorXd& e, double s, double profile_shift,
                ContactPoint& pt) {
  pt.mp = rail.locate(s);
  pt.r = rail.position(e, pt.mp);
  pt.rs = rail.slope(e, pt.mp);
  pt.rss = rail.curvature_vector(e, pt.mp);
  pt.p = pt.r;
  pt.ps = pt.rs;
  pt.pss = pt.rss;
  pt.lifted = !rail.profile().empty();
  if (!pt.lifted) return;
  pt.profile = rail.profile()(pt.r.x() + profile_shift);
  const ProfileValue& R = pt.profile;
  pt.p.y() += R.r;
  pt.ps.y() += R.rx * pt.rs.x();
  pt.pss.y() += R.rxx * pt.rs.x() * pt.rs.x() + R.rx * pt.rss.x();
}
}  // namespace

ContactPoint find_contact_point(const RailModel& rail, const Eigen::VectorXd& e,
                                const Eigen::Vector2d& RA, double s_guess, double profile_shift) {
  ContactPoint pt;
  const double L = rail.params().length;
  double s = std::min(std::max(s_guess, 0.0), L);
  const double tol = 1e-13 * L;
  for (int it = 0; it < 50; ++it) {
    surface_at(rail, e, s, profile_shift, pt);
    const Eigen::Vector2d d = RA - pt.p;
    const double f = d.dot(pt.ps);
    const double fs = -pt.ps.squaredNorm() + d.dot(pt.pss);
    pt.iterations = it + 1;
    if (!(fs < 0.0) || !std::isfinite(f)) break;  // not a minimum of the distance
    const double ds = -f / fs;
    const double s_new = std::min(std::max(s + ds, 0.0), L);
    const bool done = std::abs(s_new - s) <= tol;
    s = s_new;
    if (done) {
      pt.converged = true;
      break;
    }
  }
  if (!pt.converged) {
    std::ostringstream msg;
    msg << "contact-point search did not converge (wheel centre at X = " << RA.x()
        << " m, Y = " << RA.y() << " m)";
    throw std::runtime_error(msg.str());
  }
  pt.s = s;
  surface_at(rail, e, s, profile_shift, pt);
  const Eigen::Vector2d d = RA - pt.p;
  pt.rho = d.norm();
  pt.n = d / pt.rho;
  pt.t = pt.ps.normalized();
  pt.phi = std::atan2(pt.rs.y(), pt.rs.x());
  return pt;
}

Mat28 surface_jacobian(const ContactPoint& pt) {
  Mat28 T = shape_matrix(pt.mp.h.n);
  if (pt.lifted)
    for (int a = 0; a < 4; ++a) T(1, 2 * a) = pt.profile.rx * pt.mp.h.n[a];
  return T;
}

Mat28 surface_jacobian_s(const ContactPoint& pt) {
  Mat28 Ts = shape_matrix(pt.mp.h.ns);
  if (pt.lifted)
    for (int a = 0; a < 4; ++a)
      Ts(1, 2 * a) = pt.profile.rxx * pt.rs.x() * pt.mp.h.n[a] + pt.profile.rx * pt.mp.h.ns[a];
  return Ts;
}

void distance_derivatives(const ContactPoint& pt, Vec10& grad, Mat10* hess) {
  // G = [I2, -T(s*)] (2 x 10)
  Eigen::Matrix<double, 2, 10> G;
  G.leftCols<2>().setIdentity();
  G.rightCols<8>() = -surface_jacobian(pt);
  grad = G.transpose() * pt.n;
  if (!hess) return;
  const Eigen::Vector2d d = pt.rho * pt.n;
  const double fs = -pt.ps.squaredNorm() + d.dot(pt.pss);
  Vec10 w = G.transpose() * pt.ps / pt.rho;
  for (int a = 0; a < 4; ++a) w.segment<2>(2 + 2 * a) += pt.mp.h.ns[a] * pt.n;
  const Mat28 Ts = surface_jacobian_s(pt);
  if (pt.lifted)
    for (int a = 0; a < 4; ++a) w(2 + 2 * a) += Ts(1, 2 * a) * pt.n.y();
  const Eigen::Matrix2d P = Eigen::Matrix2d::Identity() - pt.n * pt.n.transpose();
  *hess = G.transpose() * P * G / pt.rho + (pt.rho / fs) * w * w.transpose();
  if (pt.lifted) {  // the surface is curved in e through R(x(e))
    Vec8 Sx = Vec8::Zero();
    for (int a = 0; a < 4; ++a) Sx(2 * a) = pt.mp.h.n[a];
    hess->bottomRightCorner<8, 8>() -= pt.n.y() * pt.profile.rxx * Sx * Sx.transpose();
  }
}

double elastic_normal_force(ContactLaw law, double k, double delta, double& slope) {
  if (law == ContactLaw::Linear) {
    slope = k;
    return k * delta;
  }
  if (delta <= 0.0) {
    slope = 0.0;
    return 0.0;
  }
  const double sq = std::sqrt(delta);
  slope = 1.5 * k * sq;
  return k * delta * sq;
}

double contact_potential(ContactLaw law, double k, double delta) {
  if (law == ContactLaw::Linear) return 0.5 * k * delta * delta;
  return delta > 0.0 ? 0.4 * k * delta * delta * std::sqrt(delta) : 0.0;
}

double static_compression(ContactLaw law, double k, double P) {
  return law == ContactLaw::Linear ? P / k : std::pow(P / k, 2.0 / 3.0);
}

double linearised_stiffness(ContactLaw law, double k, double P) {
  return law == ContactLaw::Linear ? k : 1.5 * std::pow(k, 2.0 / 3.0) * std::cbrt(P);
}

ContactForce contact_force(const ContactParams& cp, const ContactPoint& pt, const Vec10& qdot,
                           bool want_jacobian, double radius_rate) {
  ContactForce out;
  Mat10 H;
  distance_derivatives(pt, out.grad_rho, want_jacobian ? &H : nullptr);
  out.delta = cp.radius - pt.rho;
  out.F.setZero();
  out.K.setZero();
  out.C.setZero();
  if (out.delta <= 0.0) return out;
  double dNe;  // derivative of the elastic force with respect to delta
  const double Ne = elastic_normal_force(cp.law, cp.stiffness, out.delta, dNe);
  const double delta_dot = radius_rate - out.grad_rho.dot(qdot);
  const double N = Ne + cp.damping * delta_dot;
  if (N <= 0.0) return out;  // a damper cannot pull
  out.N = N;
  out.active = true;
  out.dN_ddelta = dNe;
  out.F = N * out.grad_rho;
  if (want_jacobian) {
    // dF/dq = N H + grad (dN/dq), dN/dq = -dNe grad^T
    out.K = -(N * H) + dNe * out.grad_rho * out.grad_rho.transpose();
    out.C = cp.damping * out.grad_rho * out.grad_rho.transpose();
  }
  return out;
}

}  // namespace trackwheel
