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
//
// Unilateral ballast (docs: Model § Voids and unilateral ballast): under a sleeper with a void
// g_j > 0, or every sleeper with tensionless ballast, the ballast force is
//   F_b,j = k_b d_j + c_b d_j'  while the sleeper is closed (on its bed), 0 while open,
//   d_j = -z_j - g_j,
// the state being a per-sleeper flag: update_states() sets it by the law at an iterate (closed
// when d_j > 0 and k_b d_j + c_b d_j' > 0: the force criterion), and every force, residual and
// condensation coefficient uses the stored flag, so that the Jacobian is exact for the state the
// residual is evaluated in (open: k_b, c_b drop out of D_j). A sleeper whose state flipped
// kMaxFlips times within one step (begin_step()) is frozen for the rest of that step: Newton
// then converges in that state, and the residual it converges is the frozen state's. The other
// sleepers (g_j = 0, not tensionless) keep the linear ballast and its arithmetic.
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
  // State flips of one sleeper within a step before it is frozen for the rest of the step.
  static constexpr int kMaxFlips = 4;

  // The sleepers of rail's supports. unilateral: the run's sleepers can lose their ballast even
  // if none of rail's can yet (a travelling window streams voids in, window.hpp): the steppers
  // decide their code paths by unilateral() once, at the start.
  explicit Sleepers(const RailModel& rail, bool unilateral = false);
  int size() const { return static_cast<int>(m_.size()); }  // 0: single springs
  bool empty() const { return m_.empty(); }

  // Unilateral ballast: any sleeper's (one that can lose contact: g_j > 0 or tensionless).
  bool unilateral() const { return any_unilateral_; }
  bool is_unilateral(int j) const { return uni_[j] != 0; }
  double gap(int j) const { return gap_[j]; }  // g_j [m]
  // Sleeper j on its ballast (always true for the linear ballast).
  bool closed(int j) const { return closed_[j] != 0; }
  // The ballast's upward force on sleeper j [N] at z, z' in the stored state: -k_b z - c_b z'
  // for the linear ballast, k_b d + c_b d' (d = -z - g) closed, 0 open.
  double ballast(int j, double z, double zdot) const;
  // Sets every unilateral sleeper's state by the law at (z, z') (zdot null: at rest, the
  // criterion d > 0), a sleeper frozen after kMaxFlips flips since begin_step() excepted (freeze
  // false: none is frozen); the condensation coefficients follow. Returns how many changed.
  int update_states(const Eigen::VectorXd& z, const Eigen::VectorXd* zdot, bool freeze = true);
  // The start of a Newton solve (a time step, a static solve): no sleeper is frozen.
  void begin_step();
  // States at the start of a static solve: closed where the sleeper touches or presses its bed,
  // d_j >= 0 (a touching sleeper counts as closed: the linearisation's convention).
  void init_states(const Eigen::VectorXd& z);
  // A changed state changes the condensation: the count of changes so far (a matrix factorised
  // at another count is stale).
  long version() const { return version_; }
  // A travelling window streamed new properties into the rail's supports (the same
  // positions, after shift()): the sleepers take them, their voids and unilateral flags too,
  // keeping their states and record (a sleeper whose void or flag changed stands as at rest
  // without weight, closed where g = 0 or linear, until join_at_rest()).
  void take_properties(const RailModel& rail);
  // The travelling window moved k bays back: sleeper j takes the state, flips, void and
  // unilateral flag of sleeper j + k (the same physical sleeper); the k fresh sleepers at the
  // front stand provisionally as if at rest without weight (closed where they touch their bed)
  // until join_at_rest(). The record stays with the physical sleepers.
  void shift(int k);
  // The fresh sleepers of the shifts since the last call take their states at the window's rest
  // z_rest (the window's own rest after its properties streamed in): closed where the sleeper
  // touches or presses its bed, -z_j - g_j >= 0 (init_states' convention), no event.
  void join_at_rest(const Eigen::VectorXd& z_rest);
  // The run's record: events (state changes between committed steps), how many sleepers were
  // frozen, and each physical sleeper's time on its ballast [s].
  void reset_record();  // at the start state
  void commit(double dt);
  long events() const { return events_; }
  long frozen() const { return frozen_; }
  // Per physical sleeper in the order the run met them: the rail's sleepers on a fixed rail;
  // on a travelling window the start window's, then one per shift (the envelope's order,
  // output.hpp), each counting its time in the window only.
  Eigen::VectorXd contact_time() const {
    return Eigen::Map<const Eigen::VectorXd>(contact_time_.data(),
                                             static_cast<Eigen::Index>(contact_time_.size()));
  }

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
  // Static sleeper heights under the rail e: F_j = 0 at rest, z_j = (k_p y_j - m_s g)/(k_p + k_b)
  // (a unilateral ballast: on its bed (k_p y_j - k_b g_j - m_s g)/(k_p + k_b) if that presses
  // it, else hanging on the pad, (k_p y_j - m_s g)/k_p).
  Eigen::VectorXd static_z(const Eigen::VectorXd& e) const;
  // Ballast forces [N] (positive: compression) at z, z' (zdot null: at rest) in the stored
  // states: -k_b z_j - c_b z_j' for the linear ballast, 0 for an open sleeper.
  Eigen::VectorXd ballast_force(const Eigen::VectorXd& z,
                                const Eigen::VectorXd* zdot = nullptr) const;
  // Energy beyond RailModel's (1/2) k_p y_j^2 [J]: the kinetic energy (1/2) m_s z'^2, the pad's
  // correction (1/2) k_p (y - z)^2 - (1/2) k_p y^2, the ballast's (1/2) k_b z^2 (unilateral:
  // (1/2) k_b max(d, 0)^2, whatever the state) and the sleepers' weight m_s g z.
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
  // a_j, D_j of sleeper j in its state for the stored (cm, cv, cq)
  void set_coefficient(int j);
  std::vector<double> m_, kp_, cp_, kb_, cb_, gap_;
  std::vector<unsigned char> uni_, closed_, committed_;
  std::vector<int> flips_;
  bool any_unilateral_ = false;
  long version_ = 0, events_ = 0, frozen_ = 0;
  long first_ = 0;  // the physical index of sleeper 0: the window's shifts since reset_record()
  int fresh_ = 0;   // the front sleepers that joined since the last join_at_rest()
  std::vector<double> contact_time_;  // per physical sleeper, sleeper j's at first_ + j
  double g_ = 0.0;
  double cm_ = 0.0, cv_ = 0.0, cq_ = 0.0;
  Eigen::VectorXd a_, D_;
};

// The run's ballast record into its output (time_loop.hpp's SimOutput).
template <class Output>
void record_ballast(const Sleepers& sl, Output& out) {
  out.ballast_events = sl.events();
  out.ballast_frozen = sl.frozen();
  out.ballast_contact_time = sl.contact_time();
}

}  // namespace trackwheel
