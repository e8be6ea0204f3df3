#include "rail.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "limits.hpp"

namespace trackwheel {

namespace {
void require(bool ok, const std::string& msg) {
  if (!ok) throw std::invalid_argument(msg);
}

// The sleeper and ballast layer: all three vectors empty (single springs) or one entry each
// per support.
void check_layers(const SupportParams& s) {
  const size_t ns = s.position.size();
  require(s.void_gap.empty() || s.void_gap.size() == ns,
          "void_gap must be empty or have one entry per support");
  for (size_t j = 0; j < s.void_gap.size(); ++j)
    require(std::isfinite(s.void_gap[j]) && s.void_gap[j] >= 0,
            "void_gap must be >= 0 m (support " + std::to_string(j) + ")");
  if (s.sleeper_mass.empty() && s.ballast_stiffness.empty() && s.ballast_damping.empty()) {
    require(!s.any_unilateral(),
            "void_gap > 0 and tensionless need layered supports (sleeper_mass, "
            "ballast_stiffness and ballast_damping given)");
    return;
  }
  require(s.sleeper_mass.size() == ns && s.ballast_stiffness.size() == ns &&
              s.ballast_damping.size() == ns,
          "sleeper_mass, ballast_stiffness and ballast_damping must be empty or have one entry "
          "per support");
  for (size_t j = 0; j < ns; ++j) {
    require(std::isfinite(s.sleeper_mass[j]) && s.sleeper_mass[j] > 0,
            "sleeper_mass must be > 0 kg");
    require(std::isfinite(s.ballast_stiffness[j]) && s.ballast_stiffness[j] >= 0,
            "ballast_stiffness must be >= 0 N/m");
    require(std::isfinite(s.ballast_damping[j]) && s.ballast_damping[j] >= 0,
            "ballast_damping must be >= 0 N s/m");
    // a sleeper off its ballast (a void, tensionless, or none: k_b = 0) hangs on its pad
    if (s.unilateral(j) || s.ballast_stiffness[j] == 0.0)
      require(s.stiffness[j] > 0,
              "support " + std::to_string(j) +
                  ": a sleeper that can lose its ballast (void_gap > 0, tensionless or "
                  "ballast_stiffness = 0) needs a pad stiffness > 0 N/m to hang on");
  }
}
// Every rail and support parameter in range, in the order a message names the first one out.
void check_inputs(const RailParams& p, const SupportParams& sup) {
  require(std::isfinite(p.length) && p.length > 0, "rail length must be > 0 m");
  require(p.n_elements >= 1 && p.n_elements <= limits::kMaxElements,
          "n_elements must be in [1, " + std::to_string(limits::kMaxElements) + "]");
  require(std::isfinite(p.EA) && p.EA > 0, "EA must be > 0 N");
  require(std::isfinite(p.EI) && p.EI > 0, "EI must be > 0 N m^2");
  require(std::isfinite(p.rhoA) && p.rhoA > 0, "rho A must be > 0 kg/m");
  require(p.n_gauss >= limits::kMinGauss && p.n_gauss <= limits::kMaxGauss,
          "n_gauss must be in [" + std::to_string(limits::kMinGauss) + ", " +
              std::to_string(limits::kMaxGauss) + "]");
  require(std::isfinite(p.gravity), "gravity must be finite");
  require(std::isfinite(p.absorbing_length) && p.absorbing_length >= 0 &&
              2.0 * p.absorbing_length <= p.length,
          "absorbing_length must be in [0, L/2] m");
  require(std::isfinite(p.absorbing_damping) && p.absorbing_damping >= 0,
          "absorbing_damping must be >= 0 N s/m^2");
  const size_t ns = sup.position.size();
  require(
      ns <= static_cast<size_t>(limits::kMaxSupports),
      "at most " + std::to_string(limits::kMaxSupports) + " supports, got " + std::to_string(ns));
  require(sup.stiffness.size() == ns && sup.damping.size() == ns,
          "support position, stiffness and damping must have the same length");
  for (size_t j = 0; j < ns; ++j) {
    require(std::isfinite(sup.position[j]) && sup.position[j] >= 0 && sup.position[j] <= p.length,
            "support positions must lie in [0, L]");
    require(std::isfinite(sup.stiffness[j]) && sup.stiffness[j] >= 0,
            "support stiffness must be >= 0 N/m");
    require(std::isfinite(sup.damping[j]) && sup.damping[j] >= 0,
            "support damping must be >= 0 N s/m");
  }
  check_layers(sup);
  require(std::isfinite(p.shear_stiffness) && p.shear_stiffness >= 0,
          "shear_stiffness must be >= 0 N (0: Euler-Bernoulli)");
  require(std::isfinite(p.rotary_inertia) && p.rotary_inertia >= 0,
          "rotary_inertia must be >= 0 kg m");
  require(p.shear() || p.rotary_inertia == 0.0,
          "rotary_inertia must be 0 kg m with shear_stiffness = 0 (the Euler-Bernoulli rail "
          "has no rotary inertia)");
}

}  // namespace

bool SupportParams::any_unilateral() const {
  for (size_t j = 0; j < position.size(); ++j)
    if (unilateral(j)) return true;
  return false;
}

RailModel::RailModel(const RailParams& rail, const SupportParams& supports, Profile profile)
    : p_(rail), sup_(supports), profile_(std::move(profile)) {
  check_inputs(p_, sup_);
  const size_t ns = sup_.position.size();

  sec_.length = p_.length / p_.n_elements;
  sec_.EA = p_.EA;
  sec_.EI = p_.EI;
  sec_.rhoA = p_.rhoA;
  sec_.exact_curvature = p_.exact_curvature;
  sec_.n_gauss = p_.n_gauss;
  if (p_.shear()) {
    shear_sec_ = ShearSection{sec_.length,        p_.EA,     p_.EI,
                              p_.shear_stiffness, p_.rhoA,   p_.rotary_inertia,
                              p_.exact_curvature, p_.n_gauss};
    Me_ = shear_mass(shear_sec_);
    shear_quad_ = make_shear_quadrature(shear_sec_);
  } else {
    Me_ = cable_mass(sec_);
    quad_ = make_quadrature(sec_);
  }

  // boundary conditions
  const int nd = n_dof();
  full_to_free_.assign(nd, 0);
  full_to_free_[0] = -1;           // x(0) = 0
  full_to_free_[1] = -1;           // y(0) = 0
  full_to_free_[nd - 4 + 1] = -1;  // y(L) = 0
  if (p_.pin_far_end) full_to_free_[nd - 4] = -1;
  for (int i = 0; i < nd; ++i) {
    if (full_to_free_[i] == 0) {
      full_to_free_[i] = static_cast<int>(free_to_full_.size());
      free_to_full_.push_back(i);
    }
  }

  // mass
  M_.resize(n_free(), kHalfBandwidth);
  for (int el = 0; el < p_.n_elements; ++el) add_element_block(el, Me_, 1.0, M_);

  for (size_t j = 0; j < ns; ++j) support_points_.push_back(locate(sup_.position[j]));
  assemble_supports();

  // consistent gravity load -int rhoA g S_y^T ds (the shear element's w functions have the
  // same integrals as the Hermite functions: the phi terms integrate to zero)
  Qg_ = Eigen::VectorXd::Zero(nd);
  const double l = sec_.length;
  const double nint[4] = {0.5 * l, l * l / 12.0, 0.5 * l, -l * l / 12.0};
  for (int el = 0; el < p_.n_elements; ++el)
    for (int a = 0; a < 4; ++a) Qg_(4 * el + 2 * a + 1) -= p_.rhoA * p_.gravity * nint[a];
}

// supports: k_s S_y^T S_y at X_j (on or between nodes), then the end zones' dampers
void RailModel::assemble_supports() {
  Ks_.resize(n_free(), kHalfBandwidth);
  Cs_.resize(n_free(), kHalfBandwidth);
  absorbing_.clear();
  for (size_t j = 0; j < support_points_.size(); ++j) {
    const MeshPoint& mp = support_points_[j];
    Mat8 Sy = Mat8::Zero();
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) Sy(2 * a + 1, 2 * b + 1) = mp.h.n[a] * mp.h.n[b];
    add_element_block(mp.element, Sy, sup_.stiffness[j], Ks_);
    add_element_block(mp.element, Sy, sup_.damping[j], Cs_);
  }
  add_absorbing_ends();
}

void RailModel::set_support_properties(const SupportParams& s) {
  require(s.position == sup_.position,
          "set_support_properties: the supports must keep their positions");
  check_inputs(p_, s);
  sup_ = s;
  assemble_supports();
}

// C_e = int (c(X) S_y^T S_y + c_x(X) S_x^T S_x) dX over the part of each element inside an end
// zone, c(d) = c_max (1 - d/L_z)^2 and c_x(d) = c_max,x (1 - d/L_z)^2 at distance d from the
// nearer end. Integrated by Gauss over the overlap only, so the integrand (degree 2 + 6) is a
// polynomial there and 5 points are exact.
void RailModel::add_absorbing_ends() {
  const double Lz = p_.absorbing_length, cy = p_.absorbing_damping, cx = p_.absorbing_axial_damping;
  require(std::isfinite(cx) && cx >= 0, "absorbing_axial_damping must be >= 0 N s/m^2");
  if (Lz <= 0.0 || (cy <= 0.0 && cx <= 0.0)) return;
  double gx[5], gw[5];
  gauss_points(5, gx, gw);
  const double l = sec_.length;
  for (int el = 0; el < p_.n_elements; ++el) {
    const double x0 = el * l, x1 = x0 + l;
    // the overlaps with [0, Lz] and [L - Lz, L] (one of them at most, unless the zones meet)
    const std::pair<double, double> parts[2] = {{x0, std::min(x1, Lz)},
                                                {std::max(x0, p_.length - Lz), x1}};
    Mat8 Ce = Mat8::Zero();
    for (const auto& [a, b] : parts) {
      if (b <= a) continue;
      for (int g = 0; g < 5; ++g) {
        const double X = a + (b - a) * gx[g];
        const double d = std::min(X, p_.length - X);
        const double grade = std::pow(std::max(1.0 - d / Lz, 0.0), 2);
        const double c = cy * grade, c_x = cx * grade;
        const HermiteValues h = centre_line((X - x0) / l);
        for (int i = 0; i < 4; ++i)
          for (int k = 0; k < 4; ++k) {
            Ce(2 * i + 1, 2 * k + 1) += (b - a) * gw[g] * c * h.n[i] * h.n[k];
            Ce(2 * i, 2 * k) += (b - a) * gw[g] * c_x * h.n[i] * h.n[k];
          }
      }
    }
    if (Ce.isZero(0.0)) continue;
    absorbing_.emplace_back(el, Ce);
    add_element_block(el, Ce, 1.0, Cs_);
  }
}

Eigen::VectorXd RailModel::reference() const {
  Eigen::VectorXd e = Eigen::VectorXd::Zero(n_dof());
  for (int i = 0; i < n_nodes(); ++i) {
    e(4 * i) = i * sec_.length;
    e(4 * i + 2) = 1.0;
  }
  return e;
}

MeshPoint RailModel::locate(double s) const {
  MeshPoint mp;
  s = std::isnan(s) ? 0.0 : std::min(std::max(s, 0.0), p_.length);  // NaN: no UB in the cast
  int el = static_cast<int>(std::floor(s / sec_.length));
  el = std::min(std::max(el, 0), p_.n_elements - 1);
  mp.element = el;
  mp.xi = std::min(std::max((s - el * sec_.length) / sec_.length, 0.0), 1.0);
  mp.h = centre_line(mp.xi);
  return mp;
}

Eigen::Vector2d RailModel::position(const Eigen::VectorXd& e, const MeshPoint& p) const {
  Eigen::Vector2d r = Eigen::Vector2d::Zero();
  for (int a = 0; a < 4; ++a) r += p.h.n[a] * e.segment<2>(p.dof0() + 2 * a);
  return r;
}
Eigen::Vector2d RailModel::slope(const Eigen::VectorXd& e, const MeshPoint& p) const {
  Eigen::Vector2d r = Eigen::Vector2d::Zero();
  for (int a = 0; a < 4; ++a) r += p.h.ns[a] * e.segment<2>(p.dof0() + 2 * a);
  return r;
}
Eigen::Vector2d RailModel::curvature_vector(const Eigen::VectorXd& e, const MeshPoint& p) const {
  Eigen::Vector2d r = Eigen::Vector2d::Zero();
  for (int a = 0; a < 4; ++a) r += p.h.nss[a] * e.segment<2>(p.dof0() + 2 * a);
  return r;
}

HermiteValues RailModel::centre_line(double xi) const {
  return p_.shear() ? shear_centre_line(shear_sec_, xi) : hermite(xi, sec_.length);
}

void RailModel::element_elastic(const Vec8& ee, Vec8* Q, Mat8* K, double* U) const {
  if (p_.shear())
    shear_elastic(shear_sec_, ee, Q, K, U, &shear_quad_);
  else
    cable_elastic(sec_, ee, Q, K, U, &quad_);
}

void RailModel::add_element_block(int el, const Mat8& Ke, double scale, BandMatrix& K) const {
  if (scale == 0.0) return;
  for (int a = 0; a < 8; ++a) {
    const int i = full_to_free_[4 * el + a];
    if (i < 0) continue;
    for (int b = 0; b < 8; ++b) {
      const int j = full_to_free_[4 * el + b];
      if (j < 0) continue;
      K.add(i, j, scale * Ke(a, b));
    }
  }
}

void RailModel::internal_force(const Eigen::VectorXd& e, const Eigen::VectorXd* edot,
                               Eigen::VectorXd& Q, double* energy) const {
  Q.setZero(n_dof());  // reuses Q's storage when it has the size already
  double U = 0.0;
  Vec8 Qe;
  for (int el = 0; el < p_.n_elements; ++el) {
    double Ue = 0.0;
    const Vec8 ee = e.segment<8>(4 * el);
    element_elastic(ee, &Qe, nullptr, energy ? &Ue : nullptr);
    Q.segment<8>(4 * el) += Qe;
    U += Ue;
  }
  for (size_t j = 0; j < support_points_.size(); ++j) {
    const MeshPoint& mp = support_points_[j];
    double y = 0.0, ydot = 0.0;
    for (int a = 0; a < 4; ++a) {
      y += mp.h.n[a] * e(mp.dof0() + 2 * a + 1);
      if (edot) ydot += mp.h.n[a] * (*edot)(mp.dof0() + 2 * a + 1);
    }
    const double f = sup_.stiffness[j] * y + sup_.damping[j] * ydot;
    for (int a = 0; a < 4; ++a) Q(mp.dof0() + 2 * a + 1) += mp.h.n[a] * f;
    U += 0.5 * sup_.stiffness[j] * y * y;
  }
  if (edot)
    for (const auto& [el, Ce] : absorbing_) Q.segment<8>(4 * el) += Ce * edot->segment<8>(4 * el);
  if (energy) *energy = U;
}

void RailModel::add_tangent(const Eigen::VectorXd& e, double scale, BandMatrix& K) const {
  Mat8 Ke;
  for (int el = 0; el < p_.n_elements; ++el) {
    const Vec8 ee = e.segment<8>(4 * el);
    element_elastic(ee, nullptr, &Ke, nullptr);
    add_element_block(el, Ke, scale, K);
  }
  K.add_scaled(scale, Ks_);
}

Eigen::MatrixXd RailModel::tangent_dense(const Eigen::VectorXd& e) const {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n_dof(), n_dof());
  Mat8 Ke;
  for (int el = 0; el < p_.n_elements; ++el) {
    const Vec8 ee = e.segment<8>(4 * el);
    element_elastic(ee, nullptr, &Ke, nullptr);
    K.block<8, 8>(4 * el, 4 * el) += Ke;
  }
  for (size_t j = 0; j < support_points_.size(); ++j) {
    const MeshPoint& mp = support_points_[j];
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        K(mp.dof0() + 2 * a + 1, mp.dof0() + 2 * b + 1) +=
            sup_.stiffness[j] * mp.h.n[a] * mp.h.n[b];
  }
  return K;
}

Eigen::MatrixXd RailModel::mass_dense() const {
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n_dof(), n_dof());
  for (int el = 0; el < p_.n_elements; ++el) M.block<8, 8>(4 * el, 4 * el) += Me_;
  return M;
}

Eigen::VectorXd RailModel::to_free(const Eigen::VectorXd& full) const {
  Eigen::VectorXd f;
  to_free(full, f);
  return f;
}

void RailModel::to_free(const Eigen::VectorXd& full, Eigen::VectorXd& free) const {
  free.resize(n_free());
  for (int i = 0; i < n_free(); ++i) free(i) = full(free_to_full_[i]);
}

void RailModel::add_from_free(const Eigen::VectorXd& free, Eigen::VectorXd& full) const {
  for (int i = 0; i < n_free(); ++i) full(free_to_full_[i]) += free(i);
}

}  // namespace trackwheel
