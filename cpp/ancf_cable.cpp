#include "ancf_cable.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "limits.hpp"

namespace trackwheel {

HermiteValues hermite(double xi, double l) {
  HermiteValues h;
  const double x2 = xi * xi, x3 = x2 * xi;
  h.n[0] = 1.0 - 3.0 * x2 + 2.0 * x3;
  h.n[1] = l * (xi - 2.0 * x2 + x3);
  h.n[2] = 3.0 * x2 - 2.0 * x3;
  h.n[3] = l * (x3 - x2);
  // d/ds = (1/l) d/dxi
  h.ns[0] = (-6.0 * xi + 6.0 * x2) / l;
  h.ns[1] = 1.0 - 4.0 * xi + 3.0 * x2;
  h.ns[2] = (6.0 * xi - 6.0 * x2) / l;
  h.ns[3] = 3.0 * x2 - 2.0 * xi;
  h.nss[0] = (-6.0 + 12.0 * xi) / (l * l);
  h.nss[1] = (-4.0 + 6.0 * xi) / l;
  h.nss[2] = (6.0 - 12.0 * xi) / (l * l);
  h.nss[3] = (6.0 * xi - 2.0) / l;
  return h;
}

Mat28 shape_matrix(const double n[4]) {
  Mat28 S = Mat28::Zero();
  for (int i = 0; i < 4; ++i) {
    S(0, 2 * i) = n[i];
    S(1, 2 * i + 1) = n[i];
  }
  return S;
}

namespace {
struct GaussTable {
  double xi[11][10];
  double w[11][10];
  GaussTable() {
    // Newton on the Legendre polynomial P_n (Numerical Recipes "gauleg"), mapped to [0, 1].
    for (int n = 1; n <= 10; ++n) {
      for (int i = 0; i < n; ++i) {
        double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), pp = 1.0;
        for (int it = 0; it < 100; ++it) {
          double p1 = 1.0, p2 = 0.0;
          for (int j = 1; j <= n; ++j) {
            const double p3 = p2;
            p2 = p1;
            p1 = ((2.0 * j - 1.0) * z * p2 - (j - 1.0) * p3) / j;
          }
          pp = n * (z * p1 - p2) / (z * z - 1.0);
          const double dz = p1 / pp;
          z -= dz;
          if (std::abs(dz) < 1e-15) break;
        }
        xi[n][i] = 0.5 * (1.0 - z);
        w[n][i] = 1.0 / ((1.0 - z * z) * pp * pp);  // 2/((1-z^2)P'^2), halved for [0, 1]
      }
    }
  }
};
const GaussTable& gauss_table() {
  static const GaussTable table;
  return table;
}
}  // namespace

void check_gauss(int n) {
  if (n < limits::kMinGauss || n > limits::kMaxGauss)
    throw std::invalid_argument("n_gauss must be in [" + std::to_string(limits::kMinGauss) + ", " +
                                std::to_string(limits::kMaxGauss) + "]");
}

void gauss_points(int n, double* xi, double* w) {
  if (n < 1 || n > limits::kMaxGauss)
    throw std::invalid_argument("n_gauss must be in [1, " + std::to_string(limits::kMaxGauss) +
                                "] (the quadrature table)");
  const GaussTable& t = gauss_table();
  for (int i = 0; i < n; ++i) {
    xi[i] = t.xi[n][i];
    w[i] = t.w[n][i];
  }
}

CableQuadrature make_quadrature(const CableSection& c) {
  check_gauss(c.n_gauss);
  CableQuadrature q;
  q.n = c.n_gauss;
  double xi[10];
  gauss_points(c.n_gauss, xi, q.w);
  for (int g = 0; g < q.n; ++g) q.h[g] = hermite(xi[g], c.length);
  return q;
}

Mat8 cable_mass(const CableSection& c) {
  double xi[10], w[10];
  gauss_points(4, xi, w);  // integrand of degree 6: 4 points are exact
  Mat8 M = Mat8::Zero();
  for (int g = 0; g < 4; ++g) {
    const HermiteValues h = hermite(xi[g], c.length);
    const Mat28 S = shape_matrix(h.n);
    M.noalias() += (c.rhoA * c.length * w[g]) * S.transpose() * S;
  }
  return M;
}

namespace {

// r_s and r_ss at one Gauss point.
inline void derivatives(const HermiteValues& h, const Vec8& e, Eigen::Vector2d& rs,
                        Eigen::Vector2d& rss) {
  rs.setZero();
  rss.setZero();
  for (int i = 0; i < 4; ++i) {
    rs += h.ns[i] * e.segment<2>(2 * i);
    rss += h.nss[i] * e.segment<2>(2 * i);
  }
}

// S_s^T v and S_ss^T v as 8-vectors.
inline Vec8 spread(const double n[4], const Eigen::Vector2d& v) {
  Vec8 out;
  for (int i = 0; i < 4; ++i) out.segment<2>(2 * i) = n[i] * v;
  return out;
}

// Curvature kappa and the factors of its gradient, dkappa/de = sum_i ns_i (fa a + fb r_s)
// + nss_i fa b with a = dc/dr_s, b = dc/dr_ss (c = r_s x r_ss), exact or simplified curvature.
inline void curvature_terms(const Eigen::Vector2d& rs, double cr, bool exact, double& kappa,
                            double& fa, double& fb) {
  if (exact) {
    const double gg = rs.squaredNorm();
    const double g32 = 1.0 / (gg * std::sqrt(gg));
    kappa = cr * g32;
    fa = g32;
    fb = -3.0 * cr * g32 / gg;
  } else {
    kappa = cr;
    fa = 1.0;
    fb = 0.0;
  }
}

}  // namespace

void cable_axial(const CableSection& c, const Vec8& e, Vec8* Q, Mat8* K, double* U,
                 const CableQuadrature* quad) {
  const CableQuadrature qq = quad ? CableQuadrature() : make_quadrature(c);
  const CableQuadrature& q = quad ? *quad : qq;
  const double* w = q.w;
  if (Q) Q->setZero();
  if (K) K->setZero();
  if (U) *U = 0.0;
  Eigen::Vector2d rs, rss;
  for (int g = 0; g < c.n_gauss; ++g) {
    const HermiteValues& h = q.h[g];
    derivatives(h, e, rs, rss);
    const double eps = 0.5 * (rs.squaredNorm() - 1.0);
    const double wl = w[g] * c.length * c.EA;
    const Vec8 deps = spread(h.ns, rs);  // d eps / de = S_s^T r_s
    if (U) *U += 0.5 * wl * eps * eps;
    if (Q) *Q += wl * eps * deps;
    if (K) {
      K->noalias() += wl * deps * deps.transpose();
      // eps * S_s^T S_s
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          const double v = wl * eps * h.ns[i] * h.ns[j];
          (*K)(2 * i, 2 * j) += v;
          (*K)(2 * i + 1, 2 * j + 1) += v;
        }
    }
  }
}

void cable_bending(const CableSection& c, const Vec8& e, Vec8* Q, Mat8* K, double* U,
                   const CableQuadrature* quad) {
  const CableQuadrature qq = quad ? CableQuadrature() : make_quadrature(c);
  const CableQuadrature& q = quad ? *quad : qq;
  const double* w = q.w;
  if (Q) Q->setZero();
  if (K) K->setZero();
  if (U) *U = 0.0;
  Eigen::Vector2d rs, rss;
  for (int g = 0; g < c.n_gauss; ++g) {
    const HermiteValues& h = q.h[g];
    derivatives(h, e, rs, rss);
    // c = r_s x r_ss = r_s^T J r_ss with J = [[0, 1], [-1, 0]]
    const double cr = rs.x() * rss.y() - rs.y() * rss.x();
    const Eigen::Vector2d a(rss.y(), -rss.x());  // dc/dr_s
    const Eigen::Vector2d b(-rs.y(), rs.x());    // dc/dr_ss
    const Vec8 dc = spread(h.ns, a) + spread(h.nss, b);
    // d2c/de2 = S_s^T J S_ss + S_ss^T J^T S_s, blocks (i,j): ns_i nss_j J + nss_i ns_j J^T
    Mat8 d2c = Mat8::Zero();
    if (K) {
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          const double p = h.ns[i] * h.nss[j] - h.nss[i] * h.ns[j];
          d2c(2 * i, 2 * j + 1) += p;  // J(0,1) = 1
          d2c(2 * i + 1, 2 * j) -= p;  // J(1,0) = -1
        }
    }
    double kappa;
    Vec8 dk;
    Mat8 d2k;
    if (c.exact_curvature) {
      const double gg = rs.squaredNorm();
      const double g32 = 1.0 / (gg * std::sqrt(gg)), g52 = g32 / gg, g72 = g52 / gg;
      const Vec8 dg = 2.0 * spread(h.ns, rs);
      kappa = cr * g32;
      dk = g32 * dc - 1.5 * cr * g52 * dg;
      if (K) {
        Mat8 d2g = Mat8::Zero();
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j) {
            d2g(2 * i, 2 * j) = 2.0 * h.ns[i] * h.ns[j];
            d2g(2 * i + 1, 2 * j + 1) = 2.0 * h.ns[i] * h.ns[j];
          }
        d2k = g32 * d2c - 1.5 * g52 * (dc * dg.transpose() + dg * dc.transpose()) +
              3.75 * cr * g72 * dg * dg.transpose() - 1.5 * cr * g52 * d2g;
      }
    } else {
      kappa = cr;
      dk = dc;
      if (K) d2k = d2c;
    }
    const double wl = w[g] * c.length * c.EI;
    if (U) *U += 0.5 * wl * kappa * kappa;
    if (Q) *Q += wl * kappa * dk;
    if (K) K->noalias() += wl * (dk * dk.transpose() + kappa * d2k);
  }
}

void cable_elastic(const CableSection& c, const Vec8& e, Vec8* Q, Mat8* K, double* U,
                   const CableQuadrature* quad) {
  if (!K && Q && quad) {
    // force (and energy) only, axial and bending in one pass over the Gauss points: the hot
    // path of the time loop (same formulas as cable_axial and cable_bending)
    Q->setZero();
    if (U) *U = 0.0;
    Eigen::Vector2d rs, rss;
    for (int g = 0; g < quad->n; ++g) {
      const HermiteValues& h = quad->h[g];
      derivatives(h, e, rs, rss);
      const double gg = rs.squaredNorm();
      const double eps = 0.5 * (gg - 1.0);
      const double cr = rs.x() * rss.y() - rs.y() * rss.x();
      double kappa, fa, fb;
      curvature_terms(rs, cr, c.exact_curvature, kappa, fa, fb);
      const double wl = quad->w[g] * c.length;
      if (U) *U += 0.5 * wl * (c.EA * eps * eps + c.EI * kappa * kappa);
      const double sb = wl * c.EI * kappa, sa = wl * c.EA * eps;
      const Eigen::Vector2d a(rss.y(), -rss.x()), b(-rs.y(), rs.x());
      const Eigen::Vector2d va = sb * (fa * a + fb * rs) + sa * rs, vb = (sb * fa) * b;
      for (int i = 0; i < 4; ++i) Q->segment<2>(2 * i) += h.ns[i] * va + h.nss[i] * vb;
    }
    return;
  }
  Vec8 Qa, Qb;
  Mat8 Ka, Kb;
  double Ua = 0.0, Ub = 0.0;
  const CableQuadrature qq = quad ? CableQuadrature() : make_quadrature(c);
  const CableQuadrature& q = quad ? *quad : qq;
  cable_axial(c, e, Q ? &Qa : nullptr, K ? &Ka : nullptr, U ? &Ua : nullptr, &q);
  cable_bending(c, e, Q ? &Qb : nullptr, K ? &Kb : nullptr, U ? &Ub : nullptr, &q);
  if (Q) *Q = Qa + Qb;
  if (K) *K = Ka + Kb;
  if (U) *U = Ua + Ub;
}

}  // namespace trackwheel
