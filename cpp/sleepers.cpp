#include "sleepers.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace trackwheel {

bool is_layered(const SupportParams& s) { return !s.sleeper_mass.empty(); }

Sleepers::Sleepers(const RailModel& rail, bool unilateral) {
  const SupportParams& s = rail.supports();
  if (!is_layered(s)) return;
  for (size_t j = 0; j < s.position.size(); ++j) pt_.push_back(rail.locate(s.position[j]));
  m_ = s.sleeper_mass;
  kp_ = s.stiffness;
  cp_ = s.damping;
  kb_ = s.ballast_stiffness;
  cb_ = s.ballast_damping;
  g_ = rail.params().gravity;  // the track's weight: switched with the rail's
  const int n = size();
  gap_.assign(n, 0.0);
  uni_.assign(n, 0);
  closed_.assign(n, 1);
  flips_.assign(n, 0);
  for (int j = 0; j < n; ++j) {
    if (!s.void_gap.empty()) gap_[j] = s.void_gap[j];
    uni_[j] = s.unilateral(j) ? 1 : 0;
    any_unilateral_ |= uni_[j] != 0;
    closed_[j] = gap_[j] == 0.0;  // at rest: a sleeper over a void hangs
  }
  any_unilateral_ |= unilateral;
  committed_ = closed_;
  contact_time_.assign(n, 0.0);
}

double Sleepers::ballast(int j, double z, double zdot) const {
  if (!uni_[j]) return -kb_[j] * z - cb_[j] * zdot;
  return closed_[j] ? kb_[j] * (-z - gap_[j]) - cb_[j] * zdot : 0.0;
}

int Sleepers::update_states(const Eigen::VectorXd& z, const Eigen::VectorXd* zdot, bool freeze) {
  if (!any_unilateral_) return 0;
  int changed = 0;
  for (int j = 0; j < size(); ++j) {
    if (!uni_[j]) continue;
    const double d = -z(j) - gap_[j];
    const double f = kb_[j] * d - (zdot ? cb_[j] * (*zdot)(j) : 0.0);
    const unsigned char want = d > 0.0 && f > 0.0 ? 1 : 0;
    if (want == closed_[j]) continue;
    if (freeze && flips_[j] >= kMaxFlips) continue;  // chattering at the threshold: frozen
    if (freeze && ++flips_[j] == kMaxFlips) ++frozen_;
    closed_[j] = want;
    set_coefficient(j);
    ++changed;
  }
  version_ += changed;
  return changed;
}

void Sleepers::take_properties(const RailModel& rail) {
  const SupportParams& s = rail.supports();
  if (!is_layered(s) || static_cast<int>(s.sleeper_mass.size()) != size())
    throw std::logic_error("Sleepers::take_properties: another set of supports");
  m_ = s.sleeper_mass;
  kp_ = s.stiffness;
  cp_ = s.damping;
  kb_ = s.ballast_stiffness;
  cb_ = s.ballast_damping;
  for (int j = 0; j < size(); ++j) {
    const double g = s.void_gap.empty() ? 0.0 : s.void_gap[j];
    const unsigned char uni = s.unilateral(j) ? 1 : 0;
    if (uni && !any_unilateral_)
      throw std::logic_error(
          "Sleepers::take_properties: a unilateral ballast in a run set up "
          "without one");
    // the linear ballast is always on its bed; a sleeper whose void changed (the fresh one at
    // the front) stands as at rest without weight until join_at_rest(), so that the matrix
    // factorised with the new properties is mostly the one of its state at rest
    const unsigned char want = !uni || g == 0.0 ? 1 : 0;
    if ((uni != uni_[j] || g != gap_[j]) && want != closed_[j]) {
      closed_[j] = committed_[j] = want;
      ++version_;
    }
    gap_[j] = g;
    uni_[j] = uni;
    set_coefficient(j);
  }
}

void Sleepers::shift(int k) {
  if (k <= 0) return;
  const int n = size();
  first_ += k;
  fresh_ = std::min(fresh_ + k, n);
  contact_time_.resize(static_cast<std::size_t>(first_ + n), 0.0);
  if (!any_unilateral_) return;
  for (int j = 0; j < n; ++j) {
    if (j + k < n) {
      closed_[j] = closed_[j + k];
      committed_[j] = committed_[j + k];
      flips_[j] = flips_[j + k];
      gap_[j] = gap_[j + k];
      uni_[j] = uni_[j + k];
    } else {
      closed_[j] = committed_[j] = gap_[j] == 0.0;
      flips_[j] = 0;
    }
    set_coefficient(j);
  }
  ++version_;
}

void Sleepers::join_at_rest(const Eigen::VectorXd& z_rest) {
  const int n = size();
  const int k = fresh_;
  fresh_ = 0;
  if (!any_unilateral_) return;
  for (int j = n - k; j < n; ++j) {
    const unsigned char want = !uni_[j] || -z_rest(j) - gap_[j] >= 0.0 ? 1 : 0;
    if (want == closed_[j]) continue;
    closed_[j] = committed_[j] = want;
    set_coefficient(j);
    ++version_;
  }
}

void Sleepers::begin_step() { std::fill(flips_.begin(), flips_.end(), 0); }

void Sleepers::init_states(const Eigen::VectorXd& z) {
  if (!any_unilateral_) return;
  int changed = 0;
  for (int j = 0; j < size(); ++j) {
    if (!uni_[j]) continue;
    const unsigned char want = -z(j) - gap_[j] >= 0.0 ? 1 : 0;
    if (want == closed_[j]) continue;
    closed_[j] = want;
    set_coefficient(j);
    ++changed;
  }
  version_ += changed;
}

void Sleepers::reset_record() {
  committed_ = closed_;
  events_ = frozen_ = 0;
  first_ = 0;
  fresh_ = 0;
  contact_time_.assign(size(), 0.0);
}

void Sleepers::commit(double dt) {
  double* time = contact_time_.data() + first_;
  for (int j = 0; j < size(); ++j) {
    events_ += committed_[j] != closed_[j];
    committed_[j] = closed_[j];
    if (closed_[j]) time[j] += dt;
  }
}

double Sleepers::rail_y(int j, const Eigen::VectorXd& u, const std::vector<int>& map) const {
  double y = 0.0;
  for (int a = 0; a < 4; ++a) {
    const int i = map[index(j, a)];
    if (i >= 0) y += weight(j, a) * u(i);
  }
  return y;
}

double Sleepers::force(int j, double y, double ydot, double z, double zdot) const {
  if (!uni_[j])
    return kp_[j] * (y - z) + cp_[j] * (ydot - zdot) - kb_[j] * z - cb_[j] * zdot - m_[j] * g_;
  return kp_[j] * (y - z) + cp_[j] * (ydot - zdot) + ballast(j, z, zdot) - m_[j] * g_;
}

void Sleepers::forces(const Eigen::VectorXd& u, const Eigen::VectorXd* udot,
                      const std::vector<int>& map, const Eigen::VectorXd& z,
                      const Eigen::VectorXd* zdot, Eigen::VectorXd& F) const {
  F.resize(size());
  for (int j = 0; j < size(); ++j) {
    const double y = rail_y(j, u, map), yd = udot ? rail_y(j, *udot, map) : 0.0;
    F(j) = force(j, y, yd, z(j), zdot ? (*zdot)(j) : 0.0);
  }
}

void Sleepers::residual(const Eigen::VectorXd& u, const Eigen::VectorXd* udot,
                        const std::vector<int>& map, const Eigen::VectorXd& z,
                        const Eigen::VectorXd* zdot, const Eigen::VectorXd& zdd,
                        Eigen::VectorXd& rs) const {
  forces(u, udot, map, z, zdot, rs);
  for (int j = 0; j < size(); ++j) rs(j) -= m_[j] * zdd(j);
}

void Sleepers::accelerations(const Eigen::VectorXd& u, const Eigen::VectorXd* udot,
                             const std::vector<int>& map, const Eigen::VectorXd& z,
                             const Eigen::VectorXd* zdot, Eigen::VectorXd& zdd) const {
  forces(u, udot, map, z, zdot, zdd);
  for (int j = 0; j < size(); ++j) zdd(j) /= m_[j];
}

void Sleepers::add_rail_force(const Eigen::VectorXd& z, const Eigen::VectorXd* zdot,
                              const std::vector<int>& map, Eigen::VectorXd& Q, double sign) const {
  for (int j = 0; j < size(); ++j) {
    const double f = sign * (kp_[j] * z(j) + (zdot ? cp_[j] * (*zdot)(j) : 0.0));
    for (int a = 0; a < 4; ++a) {
      const int i = map[index(j, a)];
      if (i >= 0) Q(i) += weight(j, a) * f;
    }
  }
}

Eigen::VectorXd Sleepers::static_z(const Eigen::VectorXd& e) const {
  Eigen::VectorXd z(size());
  for (int j = 0; j < size(); ++j) {
    double y = 0.0;
    for (int a = 0; a < 4; ++a) y += weight(j, a) * e(index(j, a));
    if (!uni_[j]) {
      z(j) = (kp_[j] * y - m_[j] * g_) / (kp_[j] + kb_[j]);
      continue;
    }
    // hanging on the pad, unless that presses it into its bed (the force is monotone in z: one
    // of the two is consistent)
    z(j) = (kp_[j] * y - m_[j] * g_) / kp_[j];
    if (-z(j) - gap_[j] > 0.0)
      z(j) = (kp_[j] * y - kb_[j] * gap_[j] - m_[j] * g_) / (kp_[j] + kb_[j]);
  }
  return z;
}

Eigen::VectorXd Sleepers::ballast_force(const Eigen::VectorXd& z,
                                        const Eigen::VectorXd* zdot) const {
  Eigen::VectorXd f(size());
  for (int j = 0; j < size(); ++j)
    f(j) = uni_[j] ? ballast(j, z(j), zdot ? (*zdot)(j) : 0.0)
                   : -kb_[j] * z(j) - (zdot ? cb_[j] * (*zdot)(j) : 0.0);
  return f;
}

double Sleepers::energy(const Eigen::VectorXd& u, const std::vector<int>& map,
                        const Eigen::VectorXd& z, const Eigen::VectorXd& zdot) const {
  double E = kinetic_energy(zdot);
  for (int j = 0; j < size(); ++j) {
    const double y = rail_y(j, u, map);
    if (!uni_[j]) {
      E += -kp_[j] * y * z(j) + 0.5 * (kp_[j] + kb_[j]) * z(j) * z(j) + m_[j] * g_ * z(j);
      continue;
    }
    const double d = std::max(-z(j) - gap_[j], 0.0);
    E += -kp_[j] * y * z(j) + 0.5 * kp_[j] * z(j) * z(j) + 0.5 * kb_[j] * d * d + m_[j] * g_ * z(j);
  }
  return E;
}

double Sleepers::kinetic_energy(const Eigen::VectorXd& zdot) const {
  double E = 0.0;
  for (int j = 0; j < size(); ++j) E += 0.5 * m_[j] * zdot(j) * zdot(j);
  return E;
}

double Sleepers::highest_frequency() const {
  double w2 = 0.0;
  for (int j = 0; j < size(); ++j) w2 = std::max(w2, (kp_[j] + kb_[j]) / m_[j]);
  return std::sqrt(w2);
}

void Sleepers::set_coefficients(double cm, double cv, double cq) {
  cm_ = cm;
  cv_ = cv;
  cq_ = cq;
  a_.resize(size());
  D_.resize(size());
  for (int j = 0; j < size(); ++j) set_coefficient(j);
}

// An open sleeper's ballast is absent: its k_b and c_b drop out (adding 0.0 for them would give
// the same bits; the branch says what is meant).
void Sleepers::set_coefficient(int j) {
  if (a_.size() != size()) return;  // coefficients not set yet
  a_(j) = cq_ * kp_[j] + cv_ * cp_[j];
  if (closed_[j])
    D_(j) = cm_ * m_[j] + cv_ * (cp_[j] + cb_[j]) + cq_ * (kp_[j] + kb_[j]);
  else
    D_(j) = cm_ * m_[j] + cv_ * cp_[j] + cq_ * kp_[j];
}

void Sleepers::condense_matrix(const std::vector<int>& map, BandMatrix& K) const {
  for (int j = 0; j < size(); ++j) {
    const double c = a_(j) * a_(j) / D_(j);
    for_each_pad_pair(j, map,
                      [&](int i, int k, double wa, double wb) { K.add(i, k, -c * wa * wb); });
  }
}

void Sleepers::condense_rhs(const Eigen::VectorXd& rs, const std::vector<int>& map,
                            Eigen::VectorXd& r) const {
  for (int j = 0; j < size(); ++j) {
    const double c = a_(j) / D_(j) * rs(j);
    for (int a = 0; a < 4; ++a) {
      const int i = map[index(j, a)];
      if (i >= 0) r(i) += c * weight(j, a);
    }
  }
}

void Sleepers::back_substitute(const Eigen::VectorXd& rs, const Eigen::VectorXd& dx,
                               const std::vector<int>& map, Eigen::VectorXd& dz) const {
  dz.resize(size());
  for (int j = 0; j < size(); ++j) dz(j) = (rs(j) + a_(j) * rail_y(j, dx, map)) / D_(j);
}

void Sleepers::coupling_blocks(const std::vector<int>& map, int n, Eigen::MatrixXd& B,
                               Eigen::VectorXd& D) const {
  B = Eigen::MatrixXd::Zero(n, size());
  for (int j = 0; j < size(); ++j)
    for (int a = 0; a < 4; ++a) {
      const int i = map[index(j, a)];
      if (i >= 0) B(i, j) -= a_(j) * weight(j, a);
    }
  D = D_;
}

void Sleepers::uncondense_dense(const std::vector<int>& map, Eigen::MatrixXd& K) const {
  for (int j = 0; j < size(); ++j) {
    const double c = a_(j) * a_(j) / D_(j);
    for_each_pad_pair(j, map, [&](int i, int k, double wa, double wb) { K(i, k) += c * wa * wb; });
  }
}

}  // namespace trackwheel
