// Layered supports: rail pad, sleeper, ballast (docs: Model § Layered supports).
//
// Support j at X_j: the pad (k_p, c_p) joins the rail point y_j = s_j . e to the sleeper z_j,
// the sleeper (mass m_s, the share of one rail) rests on the ballast (k_b, c_b) on the ground.
// With z positive upwards like y:
//   sleeper   m_s z_j'' = F_j = k_p (y_j - z_j) + c_p (y_j' - z_j') - k_b z_j - c_b z_j' - m_s g
//   rail      RailModel's pad spring to a fixed point, -s_j (k_p y_j + c_p y_j'), plus the pull
//             of the sleeper +s_j (k_p z_j + c_p z_j') added here.
// The sleeper unknowns enter every solve through the same block structure: with
// a_j = cq k_p + cv c_p and D_j = cm m_s + cv (c_p + c_b) + cq (k_p + k_b),
//   [J       -sum a_j s_j] [dx]   [r ]
//   [-a_j s_j^T      D_j ] [dz] = [rs]
// (J the rail's matrix, rs_j = F_j - m_s z_j'' the negated sleeper residual). The sleeper block
// is diagonal, so it is condensed exactly: (J - sum a_j^2/D_j s_j s_j^T) dx = r + sum
// (a_j/D_j) rs_j s_j, then dz_j = (rs_j + a_j s_j . dx) / D_j. s_j spans the y coordinates of
// one element, so the band keeps its width. (cm, cv, cq) = (1, gamma' h, beta' h^2) for
// generalized-alpha, (0, 0, 1) for statics.
//
// The functions take a map from the rail's full coordinate index to the index of the vector or
// matrix they act on (-1: a fixed coordinate): RailModel::full_to_free() for the full path,
// LinearTrack::y_of_full for the linear path.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "banded.hpp"
#include "rail.hpp"

namespace trackwheel {

// True if the supports carry sleepers (SupportParams::sleeper_mass is given).
bool is_layered(const SupportParams& supports);

class Sleepers {
 public:
  explicit Sleepers(const RailModel& rail);
  int size() const { return static_cast<int>(m_.size()); }  // 0: single springs
  bool empty() const { return m_.empty(); }

  // y_j = s_j . u over u's indexing (map: full index -> index in u).
  double rail_y(int j, const Eigen::VectorXd& u, const std::vector<int>& map) const;
  // Net vertical force F_j on sleeper j [N] at the rail's y_j, y_j' and the sleeper's z, z'.
  double force(int j, double y, double ydot, double z, double zdot) const;
  // F_j for every sleeper from the rail's u, u' over map (udot, zdot may be null: at rest).
  void forces(const Eigen::VectorXd& u, const Eigen::VectorXd* udot, const std::vector<int>& map,
              const Eigen::VectorXd& z, const Eigen::VectorXd* zdot, Eigen::VectorXd& F) const;
  // The sleepers' rows at a generalized-alpha iterate (both paths): the negated residual
  // rs_j = F_j - m_s z_j'' at the state (u, u', z, z') and the sleepers' accelerations zdd.
  void residual(const Eigen::VectorXd& u, const Eigen::VectorXd* udot, const std::vector<int>& map,
                const Eigen::VectorXd& z, const Eigen::VectorXd* zdot, const Eigen::VectorXd& zdd,
                Eigen::VectorXd& rs) const;
  // z_j'' = F_j / m_s: the sleepers carry no mass coupling.
  void accelerations(const Eigen::VectorXd& u, const Eigen::VectorXd* udot,
                     const std::vector<int>& map, const Eigen::VectorXd& z,
                     const Eigen::VectorXd* zdot, Eigen::VectorXd& zdd) const;
  // Q += sign s_j (k_p z_j + c_p z_j') over Q's indexing; sign = -1 adds the sleepers' pull to
  // a vector of internal forces that holds RailModel's pad-to-ground forces.
  void add_rail_force(const Eigen::VectorXd& z, const Eigen::VectorXd* zdot,
                      const std::vector<int>& map, Eigen::VectorXd& Q, double sign = -1.0) const;
  // Static sleeper heights under the rail e: F_j = 0 at rest, z_j = (k_p y_j - m_s g)/(k_p + k_b).
  Eigen::VectorXd static_z(const Eigen::VectorXd& e) const;
  // Ballast forces -k_b z_j [N] (positive: compression) at z.
  Eigen::VectorXd ballast_force(const Eigen::VectorXd& z) const;
  // Energy beyond RailModel's (1/2) k_p y_j^2 [J]: the kinetic energy (1/2) m_s z'^2, the pad's
  // correction (1/2) k_p (y - z)^2 - (1/2) k_p y^2, the ballast's (1/2) k_b z^2 and the
  // sleepers' weight m_s g z.
  double energy(const Eigen::VectorXd& u, const std::vector<int>& map, const Eigen::VectorXd& z,
                const Eigen::VectorXd& zdot) const;
  double kinetic_energy(const Eigen::VectorXd& zdot) const;
  // Highest natural frequency of a sleeper between its pad and ballast with the rail held,
  // sqrt((k_p + k_b)/m_s) [rad/s] (0 without sleepers).
  double highest_frequency() const;

  // The condensation for (cm, cv, cq), stored for the calls below.
  void set_coefficients(double cm, double cv, double cq);
  // K -= sum a_j^2/D_j s_j s_j^T.
  void condense_matrix(const std::vector<int>& map, BandMatrix& K) const;
  // r += sum (a_j/D_j) rs_j s_j.
  void condense_rhs(const Eigen::VectorXd& rs, const std::vector<int>& map,
                    Eigen::VectorXd& r) const;
  // dz_j = (rs_j + a_j s_j . dx) / D_j.
  void back_substitute(const Eigen::VectorXd& rs, const Eigen::VectorXd& dx,
                       const std::vector<int>& map, Eigen::VectorXd& dz) const;
  // The uncondensed blocks (tests): -a_j s_j as the column j of B (over map), D = diag(D_j).
  void coupling_blocks(const std::vector<int>& map, int n, Eigen::MatrixXd& B,
                       Eigen::VectorXd& D) const;
  // Adds back the condensation to a dense matrix over map: K += sum a_j^2/D_j s_j s_j^T.
  void uncondense_dense(const std::vector<int>& map, Eigen::MatrixXd& K) const;

  double mass(int j) const { return m_[j]; }
  double pad_stiffness(int j) const { return kp_[j]; }
  double ballast_stiffness(int j) const { return kb_[j]; }
  double pad_damping(int j) const { return cp_[j]; }
  double ballast_damping(int j) const { return cb_[j]; }
  const MeshPoint& point(int j) const { return pt_[j]; }
  // full index of the a-th y coordinate of s_j and its weight
  int index(int j, int a) const { return pt_[j].dof0() + 2 * a + 1; }
  double weight(int j, int a) const { return pt_[j].h.n[a]; }

 private:
  // f(i, k, w_a, w_b) for the rail unknowns i, k (over map) of sleeper j's pad and their
  // shape-function weights: the 4 x 4 block of the rank-one term s_j s_j^T.
  template <class F>
  void for_each_pad_pair(int j, const std::vector<int>& map, F f) const {
    for (int a = 0; a < 4; ++a) {
      const int i = map[index(j, a)];
      if (i < 0) continue;
      for (int b = 0; b < 4; ++b) {
        const int k = map[index(j, b)];
        if (k >= 0) f(i, k, weight(j, a), weight(j, b));
      }
    }
  }
  std::vector<MeshPoint> pt_;
  std::vector<double> m_, kp_, cp_, kb_, cb_;
  double g_ = 0.0;
  Eigen::VectorXd a_, D_;
};

}  // namespace trackwheel
