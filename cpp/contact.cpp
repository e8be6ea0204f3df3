#include "contact.hpp"

#include <algorithm>
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

// The element's fixed-end compliance at s*, the centre line's (constant) third derivatives
// and p_sss: for the element compliance's Jacobian (contact_parameter_derivatives).
void element_terms(const RailModel& rail, const Eigen::VectorXd& e, ContactPoint& pt) {
  const RailParams& p = rail.params();
  const double l = rail.element_length();
  const double cs = p.shear() ? 1.0 / p.shear_stiffness : 0.0;
  pt.compliance = fixed_end_compliance(p.EI, cs, l, pt.mp.xi * l);
  // the w functions are cubics: their third derivatives are those of the Hermite cubics
  // times 1 / (1 + phi) (linear_beam.cpp: timoshenko_shapes)
  const double mu = p.shear() ? 1.0 / (1.0 + rail.shear_section().phi()) : 1.0;
  const double l2 = l * l, l3 = l2 * l;
  const double c[4] = {12.0 / l3, 6.0 / l2, -12.0 / l3, 6.0 / l2};
  Eigen::Vector2d rsss = Eigen::Vector2d::Zero();
  for (int a = 0; a < 4; ++a) {
    pt.nsss[a] = mu * c[a];
    rsss += pt.nsss[a] * e.segment<2>(pt.mp.dof0() + 2 * a);
  }
  pt.psss = rsss;
  if (!pt.lifted) return;
  const ProfileValue& R = pt.profile;
  const double xs = pt.rs.x(), xss = pt.rss.x();
  pt.psss.y() += R.rxxx * xs * xs * xs + 3.0 * R.rxx * xs * xss + R.rx * rsss.x();
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
  element_terms(rail, e, pt);
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

void contact_parameter_derivatives(const ContactPoint& pt, Vec10& grad, Mat10* hess) {
  // f(s, q) = d.p_s with d = R_A - p(s), q = [X_A, Y_A, e_el]; G = dd/dq = [I, -T].
  //   f_s = -p_s.p_s + d.p_ss,  f_ss = -3 p_s.p_ss + d.p_sss,
  //   f_q = G^T p_s + [0; T_s^T d],  f_sq = G^T p_ss + [0; T_ss^T d - 2 T_s^T p_s],
  //   f_qq = G^T [0, T_s] + [0; T_s^T] G (+ the profile's curvature in e, below);
  // s_q = -f_q / f_s and, from d2/dq2 f(s(q), q) = 0,
  //   s_qq = -(f_qq + f_sq s_q^T + s_q f_sq^T + f_ss s_q s_q^T) / f_s.
  const Eigen::Vector2d d = pt.rho * pt.n;
  const double fs = -pt.ps.squaredNorm() + d.dot(pt.pss);
  const Mat28 T = surface_jacobian(pt), Ts = surface_jacobian_s(pt);
  Vec10 fq;
  fq.head<2>() = pt.ps;
  fq.tail<8>() = -T.transpose() * pt.ps + Ts.transpose() * d;
  grad = -fq / fs;
  if (!hess) return;
  // T_ss = dp_ss/de at fixed s
  Mat28 Tss = shape_matrix(pt.mp.h.nss);
  Vec8 Sx = Vec8::Zero(), Ssx = Vec8::Zero();  // d x/de, d x_s/de
  for (int a = 0; a < 4; ++a) {
    Sx(2 * a) = pt.mp.h.n[a];
    Ssx(2 * a) = pt.mp.h.ns[a];
  }
  const ProfileValue& R = pt.profile;
  const double xs = pt.rs.x(), xss = pt.rss.x();
  if (pt.lifted)
    for (int a = 0; a < 4; ++a)
      Tss(1, 2 * a) = (R.rxxx * xs * xs + R.rxx * xss) * pt.mp.h.n[a] +
                      2.0 * R.rxx * xs * pt.mp.h.ns[a] + R.rx * pt.mp.h.nss[a];
  const double fss = -3.0 * pt.ps.dot(pt.pss) + d.dot(pt.psss);
  Vec10 fsq;
  fsq.head<2>() = pt.pss;
  fsq.tail<8>() = -T.transpose() * pt.pss - 2.0 * Ts.transpose() * pt.ps + Tss.transpose() * d;
  Mat10 Mq = Mat10::Zero();  // G^T [0, T_s]
  Mq.topRightCorner<2, 8>() = Ts;
  Mq.bottomRightCorner<8, 8>() = -T.transpose() * Ts;
  Mat10 fqq = Mq + Mq.transpose();
  if (pt.lifted) {  // T and T_s depend on e through R'(x(e)): d.y d2(p_s)_y/de2 - p_s.y d2p_y/de2
    const Mat8 P2 = R.rxx * Sx * Sx.transpose();
    const Mat8 P2s =
        R.rxxx * xs * Sx * Sx.transpose() + R.rxx * (Sx * Ssx.transpose() + Ssx * Sx.transpose());
    fqq.bottomRightCorner<8, 8>() += d.y() * P2s - pt.ps.y() * P2;
  }
  *hess =
      -(fqq + fsq * grad.transpose() + grad * fsq.transpose() + fss * grad * grad.transpose()) / fs;
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

SeriesForce series_normal_force(ContactLaw law, double k, double G, double delta) {
  SeriesForce f;
  if (law == ContactLaw::Linear) {
    const double c = 1.0 + k * G;
    f.N = k * delta / c;
    f.slope = k / c;
    f.compression = delta / c;
    return f;
  }
  if (delta <= 0.0) return f;
  // x + G C x^1.5 = delta for the compression x: increasing and convex in x, so Newton from
  // x = delta (above the root) falls monotonically onto it (a few steps: G C sqrt(x) ~ 0.1).
  double x = delta;
  for (int it = 0; it < 50; ++it) {
    const double sq = std::sqrt(x);
    const double h = x + G * k * x * sq - delta, dh = 1.0 + 1.5 * G * k * sq;
    const double dx = h / dh;
    x = std::max(x - dx, 0.0);
    if (std::abs(dx) <= 1e-15 * delta) break;
  }
  const double sq = std::sqrt(x), dNl = 1.5 * k * sq;
  f.compression = x;
  f.N = k * x * sq;
  f.slope = dNl / (1.0 + G * dNl);
  return f;
}

double series_potential(ContactLaw law, double k, double G, double delta) {
  const SeriesForce f = series_normal_force(law, k, G, delta);
  return contact_potential(law, k, f.compression) + 0.5 * G * f.N * f.N;
}

double series_static_approach(ContactLaw law, double k, double G, double P) {
  return static_compression(law, k, P) + G * P;
}

namespace {

// The part of contact_force both laws share: the distance's derivatives (its Hessian into H
// when want_jacobian), the approach delta = rho0 + Delta rho - rho and an inactive force.
void start_contact_force(const ContactParams& cp, const ContactPoint& pt, bool want_jacobian,
                         ContactForce& out, Mat10& H) {
  distance_derivatives(pt, out.grad_rho, want_jacobian ? &H : nullptr);
  out.delta = cp.radius - pt.rho;
  out.compression = out.delta;
  out.F.setZero();
  out.K.setZero();
  out.C.setZero();
  out.dNe_dq.setZero();
  out.ddeflection_dq.setZero();
}

// contact_force with the element's compliance in series (contact.hpp).
ContactForce compliant_contact_force(const ContactParams& cp, const ContactPoint& pt,
                                     const Vec10& qdot, bool want_jacobian, double radius_rate) {
  ContactForce out;
  out.compliant = true;
  Mat10 H;
  start_contact_force(cp, pt, want_jacobian, out, H);
  if (out.delta <= 0.0) return out;
  const ElementCompliance& g = pt.compliance;
  const SeriesForce sf = series_normal_force(cp.law, cp.stiffness, g.G, out.delta);
  out.compression = sf.compression;
  out.energy = contact_potential(cp.law, cp.stiffness, sf.compression) + 0.5 * g.G * sf.N * sf.N;
  const double delta_dot = radius_rate - out.grad_rho.dot(qdot);
  const double N = sf.N + cp.damping * delta_dot;
  if (N <= 0.0) return out;  // a damper cannot pull
  out.N = N;
  out.active = true;
  out.Ne = sf.N;
  out.dN_ddelta = sf.slope;
  out.deflection = g.G * sf.N;
  Vec10 sq;
  Mat10 sqq;
  contact_parameter_derivatives(pt, sq, want_jacobian ? &sqq : nullptr);
  const double climb = 0.5 * sf.N * sf.N;  // -dPhi/dG
  const Vec10 u = out.grad_rho + (sf.N * g.Ga) * sq;
  out.dNe_dq = -sf.slope * u;
  out.ddeflection_dq = g.G * out.dNe_dq + (sf.N * g.Ga) * sq;
  out.F = N * out.grad_rho + (climb * g.Ga) * sq;
  if (want_jacobian) {
    out.K =
        sf.slope * u * u.transpose() - N * H - climb * (g.Gaa * sq * sq.transpose() + g.Ga * sqq);
    out.C = cp.damping * out.grad_rho * out.grad_rho.transpose();
  }
  return out;
}

}  // namespace

ContactForce contact_force(const ContactParams& cp, const ContactPoint& pt, const Vec10& qdot,
                           bool want_jacobian, double radius_rate) {
  if (cp.element_compliance)
    return compliant_contact_force(cp, pt, qdot, want_jacobian, radius_rate);
  ContactForce out;
  Mat10 H;
  start_contact_force(cp, pt, want_jacobian, out, H);
  if (out.delta <= 0.0) return out;
  double dNe;  // derivative of the elastic force with respect to delta
  const double Ne = elastic_normal_force(cp.law, cp.stiffness, out.delta, dNe);
  out.energy = contact_potential(cp.law, cp.stiffness, out.delta);
  const double delta_dot = radius_rate - out.grad_rho.dot(qdot);
  const double N = Ne + cp.damping * delta_dot;
  if (N <= 0.0) return out;  // a damper cannot pull
  out.N = N;
  out.active = true;
  out.Ne = Ne;
  out.dN_ddelta = dNe;
  out.dNe_dq = -dNe * out.grad_rho;
  out.F = N * out.grad_rho;
  if (want_jacobian) {
    // dF/dq = N H + grad (dN/dq), dN/dq = -dNe grad^T
    out.K = -(N * H) + dNe * out.grad_rho * out.grad_rho.transpose();
    out.C = cp.damping * out.grad_rho * out.grad_rho.transpose();
  }
  return out;
}

}  // namespace trackwheel
