#include "ancf_shear.hpp"

#include <algorithm>
#include <cmath>

#include "linear_beam.hpp"

namespace trackwheel {

ShearShapes shear_shapes(const ShearSection& c, double xi) {
  // the linear path's IIE functions: one definition of the interpolation for both paths
  const BeamShapes b = timoshenko_shapes(xi, c.length, c.phi());
  ShearShapes s;
  std::copy(b.w, b.w + 4, s.w);
  std::copy(b.ws, b.ws + 4, s.ws);
  std::copy(b.wss, b.wss + 4, s.wss);
  std::copy(b.psi, b.psi + 4, s.psi);
  std::copy(b.psis, b.psis + 4, s.psis);
  return s;
}

HermiteValues shear_centre_line(const ShearSection& c, double xi) {
  const ShearShapes s = shear_shapes(c, xi);
  HermiteValues h;
  std::copy(s.w, s.w + 4, h.n);
  std::copy(s.ws, s.ws + 4, h.ns);
  std::copy(s.wss, s.wss + 4, h.nss);
  return h;
}

ShearQuadrature make_shear_quadrature(const ShearSection& c) {
  check_gauss(c.n_gauss);
  ShearQuadrature q;
  q.n = c.n_gauss;
  double xi[10];
  gauss_points(c.n_gauss, xi, q.w);
  for (int g = 0; g < q.n; ++g) q.s[g] = shear_shapes(c, xi[g]);
  return q;
}

Mat8 shear_mass(const ShearSection& c) {
  double xi[10], w[10];
  gauss_points(4, xi, w);  // integrands of degree <= 6: 4 points are exact
  Mat8 M = Mat8::Zero();
  for (int g = 0; g < 4; ++g) {
    const ShearShapes s = shear_shapes(c, xi[g]);
    const Mat28 N = shape_matrix(s.w), P = shape_matrix(s.psi);
    M.noalias() += (c.length * w[g]) * (c.rhoA * N.transpose() * N + c.rhoI * P.transpose() * P);
  }
  return M;
}

namespace {

// sum_k f_k e_k (e_k the k-th 2-block of e)
inline Eigen::Vector2d combine(const double f[4], const Vec8& e) {
  Eigen::Vector2d v = Eigen::Vector2d::Zero();
  for (int k = 0; k < 4; ++k) v += f[k] * e.segment<2>(2 * k);
  return v;
}

// [f_0 v; f_1 v; f_2 v; f_3 v]: the gradient of (sum f_k e_k).v for fixed v
inline Vec8 spread(const double f[4], const Eigen::Vector2d& v) {
  Vec8 out;
  for (int k = 0; k < 4; ++k) out.segment<2>(2 * k) = f[k] * v;
  return out;
}

// Hessian of U x V (constant: the cross product is bilinear), blocks u_i v_j J + v_i u_j J^T
// with J = [[0, 1], [-1, 0]].
Mat8 cross_hessian(const double u[4], const double v[4]) {
  Mat8 H = Mat8::Zero();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const double p = u[i] * v[j] - v[i] * u[j];
      H(2 * i, 2 * j + 1) += p;
      H(2 * i + 1, 2 * j) -= p;
    }
  return H;
}

// f = (U x V) / (D.D)^p with U = sum u_k e_k, V = sum v_k e_k, D = sum t_k e_k (p = 0, 1 or
// 3/2): the curvature (U = D = d, V = d_s) and the shear angle (U = D = d, V = r_s). Returns f,
// its gradient df and, if d2f is not null, its Hessian.
double cross_ratio(const double u[4], const double v[4], const double t[4], double p, const Vec8& e,
                   Vec8& df, Mat8* d2f) {
  const Eigen::Vector2d U = combine(u, e), V = combine(v, e);
  const double c = U.x() * V.y() - U.y() * V.x();
  const Vec8 dc =
      spread(u, Eigen::Vector2d(V.y(), -V.x())) + spread(v, Eigen::Vector2d(-U.y(), U.x()));
  if (p == 0.0) {
    df = dc;
    if (d2f) *d2f = cross_hessian(u, v);
    return c;
  }
  const Eigen::Vector2d D = combine(t, e);
  const double g = D.squaredNorm(), gp = p == 1.0 ? 1.0 / g : 1.0 / (g * std::sqrt(g));
  const Vec8 dg = 2.0 * spread(t, D);
  df = gp * dc - (p * c * gp / g) * dg;
  if (d2f) {
    Mat8 d2g = Mat8::Zero();
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) d2g(2 * i, 2 * j) = d2g(2 * i + 1, 2 * j + 1) = 2.0 * t[i] * t[j];
    *d2f = gp * cross_hessian(u, v) - (p * gp / g) * (dc * dg.transpose() + dg * dc.transpose()) +
           (p * (p + 1.0) * c * gp / (g * g)) * dg * dg.transpose() - (p * c * gp / g) * d2g;
  }
  return c * gp;
}

// Force and energy only, in one pass of 2-vectors per Gauss point: the time loop's hot path
// (the formulas of shear_elastic with the chain rule through r_s, d and d_s written out).
void shear_force(const ShearSection& c, const Vec8& e, Vec8& Q, double* U,
                 const ShearQuadrature& q) {
  Q.setZero();
  if (U) *U = 0.0;
  for (int g = 0; g < q.n; ++g) {
    const ShearShapes& s = q.s[g];
    const Eigen::Vector2d rs = combine(s.ws, e), d = combine(s.psi, e), ds = combine(s.psis, e);
    const double dd = d.squaredNorm(), eps = 0.5 * (rs.squaredNorm() - 1.0);
    const Eigen::Vector2d perp(-d.y(), d.x());  // d(d x v)/dv
    const double cb = d.x() * ds.y() - d.y() * ds.x(), cs = d.x() * rs.y() - d.y() * rs.x();
    const double gb = c.exact_curvature ? 1.0 / (dd * std::sqrt(dd)) : 1.0;
    const double pb = c.exact_curvature ? 1.5 : 0.0;
    const double kappa = cb * gb, gamma = cs / dd;
    const double stretch = 0.5 * (dd - rs.squaredNorm());  // the director's, against r_s's
    const double wl = q.w[g] * c.length;
    const double fa = wl * c.EA * eps, fb = wl * c.EI * kappa, fs = wl * c.kGA * gamma;
    const double ft = wl * c.kGA * stretch;
    if (U) *U += 0.5 * (fa * eps + fb * kappa + fs * gamma + ft * stretch);
    // dkappa/dd = gb (d_s.y, -d_s.x) - 2 p kappa d / dd, dkappa/dd_s = gb perp;
    // dgamma/dd = (r_s.y, -r_s.x) / dd - 2 gamma d / dd, dgamma/dr_s = perp / dd
    const Eigen::Vector2d vr = (fa - ft) * rs + (fs / dd) * perp;
    const Eigen::Vector2d vd =
        fb * (gb * Eigen::Vector2d(ds.y(), -ds.x()) - (2.0 * pb * kappa / dd) * d) +
        fs * (Eigen::Vector2d(rs.y(), -rs.x()) / dd - (2.0 * gamma / dd) * d) + ft * d;
    const Eigen::Vector2d vds = (fb * gb) * perp;
    for (int k = 0; k < 4; ++k)
      Q.segment<2>(2 * k) += s.ws[k] * vr + s.psi[k] * vd + s.psis[k] * vds;
  }
}

}  // namespace

void shear_elastic(const ShearSection& c, const Vec8& e, Vec8* Q, Mat8* K, double* U,
                   const ShearQuadrature* quad) {
  const ShearQuadrature qq = quad ? ShearQuadrature() : make_shear_quadrature(c);
  const ShearQuadrature& q = quad ? *quad : qq;
  if (Q && !K) {
    shear_force(c, e, *Q, U, q);
    return;
  }
  if (Q) Q->setZero();
  if (K) K->setZero();
  if (U) *U = 0.0;
  const double pk = c.exact_curvature ? 1.5 : 0.0;
  Vec8 dk, dgam;
  Mat8 d2k, d2gam;
  for (int g = 0; g < q.n; ++g) {
    const ShearShapes& s = q.s[g];
    const Eigen::Vector2d rs = combine(s.ws, e);
    const double eps = 0.5 * (rs.squaredNorm() - 1.0);
    const Vec8 deps = spread(s.ws, rs);
    const double kappa = cross_ratio(s.psi, s.psis, s.psi, pk, e, dk, K ? &d2k : nullptr);
    const double gamma = cross_ratio(s.psi, s.ws, s.psi, 1.0, e, dgam, K ? &d2gam : nullptr);
    const Eigen::Vector2d d = combine(s.psi, e);
    const double stretch = 0.5 * (d.squaredNorm() - rs.squaredNorm());
    const Vec8 dstretch = spread(s.psi, d) - deps;
    const double wl = q.w[g] * c.length;
    const double sa = wl * c.EA, sb = wl * c.EI, ss = wl * c.kGA;
    if (U)
      *U +=
          0.5 * (sa * eps * eps + ss * stretch * stretch + sb * kappa * kappa + ss * gamma * gamma);
    if (Q)
      *Q += (sa * eps) * deps + (ss * stretch) * dstretch + (sb * kappa) * dk + (ss * gamma) * dgam;
    if (K) {
      K->noalias() += sa * deps * deps.transpose() + ss * dstretch * dstretch.transpose() +
                      sb * dk * dk.transpose() + ss * dgam * dgam.transpose();
      *K += (sb * kappa) * d2k + (ss * gamma) * d2gam;
      // the Hessians of eps and of the stretch: ws_i ws_j and psi_i psi_j - ws_i ws_j on both
      // components
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          const double v =
              (sa * eps - ss * stretch) * s.ws[i] * s.ws[j] + ss * stretch * s.psi[i] * s.psi[j];
          (*K)(2 * i, 2 * j) += v;
          (*K)(2 * i + 1, 2 * j + 1) += v;
        }
    }
  }
}

}  // namespace trackwheel
