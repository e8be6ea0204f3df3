#include "linear_beam.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "ancf_cable.hpp"

namespace trackwheel {

namespace {

// 4-point Gauss-Legendre on [0, 1]: exact for the degree-6 products of the cubic w functions.
constexpr double kGx[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281,
                           0.9305681557970263};
constexpr double kGw[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731,
                           0.1739274225687269};

double shear_parameter(double EI, double kGA, double l) { return 12.0 * EI / (kGA * l * l); }

// The rail's absorbing end zones (RailModel::add_absorbing_ends: c(d) = c_max (1 - d/L_z)^2 at
// distance d from the nearer end) through the Timoshenko w functions: C += int c N_w^T N_w dX,
// 5 Gauss points over each element's overlap with a zone (the integrand is a polynomial there).
void add_absorbing_ends(const RailModel& r, const BeamParams& b, const std::vector<int>& y_of_full,
                        BandMatrix& C) {
  const RailParams& p = r.params();
  const double Lz = p.absorbing_length, cmax = p.absorbing_damping, l = r.element_length();
  if (Lz <= 0.0 || cmax <= 0.0) return;
  double gx[5], gw[5];
  gauss_points(5, gx, gw);
  for (int el = 0; el < p.n_elements; ++el) {
    const double x0 = el * l, x1 = x0 + l;
    const std::pair<double, double> parts[2] = {{x0, std::min(x1, Lz)},
                                                {std::max(x0, p.length - Lz), x1}};
    for (const auto& [lo, hi] : parts)
      for (int g = 0; g < 5 && hi > lo; ++g) {
        const double X = lo + (hi - lo) * gx[g], d = std::min(X, p.length - X);
        const double w = (hi - lo) * gw[g] * cmax * std::pow(std::max(1.0 - d / Lz, 0.0), 2);
        // the element's own shapes at X (an element end may belong to the neighbour in locate)
        const BeamShapes s =
            timoshenko_shapes((X - x0) / l, l, shear_parameter(p.EI, b.shear_stiffness, l));
        for (int a = 0; a < 4; ++a) {
          const int i = y_of_full[4 * el + 2 * a + 1];
          if (i < 0) continue;
          for (int c = 0; c < 4; ++c) {
            const int j = y_of_full[4 * el + 2 * c + 1];
            if (j >= 0) C.add(i, j, w * s.w[a] * s.w[c]);
          }
        }
      }
  }
}

// Timoshenko: element matrices, supports through the w shape functions, consistent gravity.
void timoshenko_beam(const RailModel& r, const BeamParams& b, const std::vector<int>& y_of_full,
                     BandMatrix& M, BandMatrix& C, BandMatrix& K, Eigen::VectorXd& Qg) {
  const RailParams& p = r.params();
  const double l = r.element_length(), phi = shear_parameter(p.EI, b.shear_stiffness, l);
  const Eigen::Matrix4d Ke = timoshenko_stiffness(p.EI, b.shear_stiffness, l);
  const Eigen::Matrix4d Me = timoshenko_mass(p.rhoA, b.rotary_inertia, p.EI, b.shear_stiffness, l);
  Eigen::Vector4d nint = Eigen::Vector4d::Zero();  // int N_w dx over an element
  for (int g = 0; g < 4; ++g) {
    const BeamShapes s = timoshenko_shapes(kGx[g], l, phi);
    for (int a = 0; a < 4; ++a) nint(a) += kGw[g] * l * s.w[a];
  }
  for (int el = 0; el < p.n_elements; ++el)
    for (int a = 0; a < 4; ++a) {
      const int i = y_of_full[4 * el + 2 * a + 1];
      if (i < 0) continue;
      Qg(i) -= p.rhoA * p.gravity * nint(a);
      for (int c = 0; c < 4; ++c) {
        const int j = y_of_full[4 * el + 2 * c + 1];
        if (j < 0) continue;
        M.add(i, j, Me(a, c));
        K.add(i, j, Ke(a, c));
      }
    }
  const SupportParams& sup = r.supports();
  for (size_t s = 0; s < sup.position.size(); ++s) {
    const BeamPoint bp = beam_point(r, b, sup.position[s]);
    for (int a = 0; a < 4; ++a) {
      const int i = y_of_full[4 * bp.element + 2 * a + 1];
      if (i < 0) continue;
      for (int c = 0; c < 4; ++c) {
        const int j = y_of_full[4 * bp.element + 2 * c + 1];
        if (j < 0) continue;
        K.add(i, j, sup.stiffness[s] * bp.n[a] * bp.n[c]);
        C.add(i, j, sup.damping[s] * bp.n[a] * bp.n[c]);
      }
    }
  }
  add_absorbing_ends(r, b, y_of_full, C);
}

}  // namespace

BeamShapes timoshenko_shapes(double xi, double l, double phi) {
  const double mu = 1.0 / (1.0 + phi), x2 = xi * xi, x3 = x2 * xi;
  BeamShapes s;
  s.w[0] = mu * (1.0 - 3.0 * x2 + 2.0 * x3 + phi * (1.0 - xi));
  s.w[1] = l * mu * (xi - 2.0 * x2 + x3 + 0.5 * phi * (xi - x2));
  s.w[2] = mu * (3.0 * x2 - 2.0 * x3 + phi * xi);
  s.w[3] = l * mu * (-x2 + x3 - 0.5 * phi * (xi - x2));
  s.ws[0] = mu * (-6.0 * xi + 6.0 * x2 - phi) / l;
  s.ws[1] = mu * (1.0 - 4.0 * xi + 3.0 * x2 + 0.5 * phi * (1.0 - 2.0 * xi));
  s.ws[2] = mu * (6.0 * xi - 6.0 * x2 + phi) / l;
  s.ws[3] = mu * (-2.0 * xi + 3.0 * x2 - 0.5 * phi * (1.0 - 2.0 * xi));
  s.wss[0] = mu * (-6.0 + 12.0 * xi) / (l * l);
  s.wss[1] = mu * (-4.0 + 6.0 * xi - phi) / l;
  s.wss[2] = mu * (6.0 - 12.0 * xi) / (l * l);
  s.wss[3] = mu * (-2.0 + 6.0 * xi + phi) / l;
  s.psi[0] = 6.0 * mu * (x2 - xi) / l;
  s.psi[1] = mu * (1.0 - 4.0 * xi + 3.0 * x2 + phi * (1.0 - xi));
  s.psi[2] = 6.0 * mu * (xi - x2) / l;
  s.psi[3] = mu * (-2.0 * xi + 3.0 * x2 + phi * xi);
  s.psis[0] = 6.0 * mu * (2.0 * xi - 1.0) / (l * l);
  s.psis[1] = mu * (-4.0 + 6.0 * xi - phi) / l;
  s.psis[2] = 6.0 * mu * (1.0 - 2.0 * xi) / (l * l);
  s.psis[3] = mu * (-2.0 + 6.0 * xi + phi) / l;
  return s;
}

Eigen::Matrix4d timoshenko_stiffness(double EI, double kGA, double l) {
  const double phi = shear_parameter(EI, kGA, l), c = EI / ((1.0 + phi) * l * l * l);
  Eigen::Matrix4d K;
  K << 12.0, 6.0 * l, -12.0, 6.0 * l,                               //
      6.0 * l, (4.0 + phi) * l * l, -6.0 * l, (2.0 - phi) * l * l,  //
      -12.0, -6.0 * l, 12.0, -6.0 * l,                              //
      6.0 * l, (2.0 - phi) * l * l, -6.0 * l, (4.0 + phi) * l * l;
  return c * K;
}

Eigen::Matrix4d timoshenko_mass(double rhoA, double rhoI, double EI, double kGA, double l) {
  const double phi = shear_parameter(EI, kGA, l);
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  for (int g = 0; g < 4; ++g) {
    const BeamShapes s = timoshenko_shapes(kGx[g], l, phi);
    const Eigen::Map<const Eigen::Vector4d> w(s.w), psi(s.psi);
    M += kGw[g] * l * (rhoA * w * w.transpose() + rhoI * psi * psi.transpose());
  }
  return M;
}

double timoshenko_energy(double EI, double kGA, double l, const Eigen::Vector4d& q) {
  const double phi = shear_parameter(EI, kGA, l);
  double U = 0.0;
  for (int g = 0; g < 4; ++g) {
    const BeamShapes s = timoshenko_shapes(kGx[g], l, phi);
    const Eigen::Map<const Eigen::Vector4d> ws(s.ws), psi(s.psi), psis(s.psis);
    const double kappa = psis.dot(q), gamma = ws.dot(q) - psi.dot(q);
    U += 0.5 * kGw[g] * l * (EI * kappa * kappa + kGA * gamma * gamma);
  }
  return U;
}

ElementCompliance fixed_end_compliance(double EI, double shear_compliance, double l, double a) {
  a = std::min(std::max(a, 0.0), l);
  const double cs = shear_compliance, l3 = l * l * l;
  const double mu = 1.0 / (1.0 + 12.0 * EI * cs / (l * l));  // 1 / (1 + phi)
  const double p = a * (l - a), pa = l - 2.0 * a;            // p and dp/da (d2p/da2 = -2)
  // G(p) = c3 p^3 + c2 p^2 + c1 p
  const double c3 = mu / (3.0 * EI * l3), c2 = cs * mu / l3, c1 = cs / l;
  const double Gp = (3.0 * c3 * p + 2.0 * c2) * p + c1, Gpp = 6.0 * c3 * p + 2.0 * c2;
  ElementCompliance g;
  g.G = ((c3 * p + c2) * p + c1) * p;
  g.Ga = Gp * pa;
  g.Gaa = Gpp * pa * pa - 2.0 * Gp;
  return g;
}

BeamPoint beam_point(const RailModel& rail, const BeamParams& beam, double X) {
  const MeshPoint mp = rail.locate(X);
  BeamPoint bp;
  bp.element = mp.element;
  bp.xi = mp.xi;
  if (!beam.timoshenko()) {
    std::copy(mp.h.n, mp.h.n + 4, bp.n);
    std::copy(mp.h.ns, mp.h.ns + 4, bp.ns);
    std::copy(mp.h.nss, mp.h.nss + 4, bp.nss);
    return bp;
  }
  const double l = rail.element_length();
  const BeamShapes s =
      timoshenko_shapes(mp.xi, l, shear_parameter(rail.params().EI, beam.shear_stiffness, l));
  std::copy(s.w, s.w + 4, bp.n);
  std::copy(s.ws, s.ws + 4, bp.ns);
  std::copy(s.wss, s.wss + 4, bp.nss);
  return bp;
}

void linear_beam(const RailModel& r, const BeamParams& beam, const std::vector<int>& full_of_y,
                 const std::vector<int>& y_of_full, BandMatrix& My, BandMatrix& Cy, BandMatrix& Ky,
                 Eigen::VectorXd& Qgy) {
  const int ny = static_cast<int>(full_of_y.size());
  My.resize(ny, 3);
  Cy.resize(ny, 3);
  Ky.resize(ny, 3);
  Qgy = Eigen::VectorXd::Zero(ny);
  if (beam.timoshenko()) {
    if (!std::isfinite(beam.shear_stiffness) || !std::isfinite(beam.rotary_inertia) ||
        beam.rotary_inertia < 0.0)
      throw std::invalid_argument(
          "Timoshenko beam: shear stiffness must be finite > 0 N, rotary inertia >= 0 kg m");
    timoshenko_beam(r, beam, y_of_full, My, Cy, Ky, Qgy);
    return;
  }
  // y blocks of the free-coordinate band matrices at the straight reference
  const auto& f2f = r.full_to_free();
  BandMatrix Kf(r.n_free(), kHalfBandwidth);
  r.add_tangent(r.reference(), 1.0, Kf);
  for (int a = 0; a < ny; ++a)
    for (int b = std::max(0, a - 3); b <= std::min(ny - 1, a + 3); ++b) {
      const int i = f2f[full_of_y[a]], j = f2f[full_of_y[b]];
      if (!r.mass().in_band(i, j)) continue;
      My.at(a, b) = r.mass().at(i, j);
      Cy.at(a, b) = r.support_damping().at(i, j);
      Ky.at(a, b) = Kf.at(i, j);
    }
  for (int a = 0; a < ny; ++a) Qgy(a) = r.gravity_force()(full_of_y[a]);
}

}  // namespace trackwheel
