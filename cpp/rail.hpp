// The rail: planar ANCF cable elements (Euler-Bernoulli) or shear-deformable ANCF elements
// (ancf_shear.hpp, Timoshenko) on discrete elastic supports (docs: Model § Scene, § Rail, and
// the section "Shear-deformable rail (Timoshenko)").
//
// RailModel is immutable after construction (mesh, section, constant mass matrix, supports,
// gravity load, boundary conditions). Algorithms take it by const reference together with
// state vectors; mutable buffers live in the caller's workspace.
//
// Coordinates: full vector e (n_dof = 4 (n_elements + 1)), node-major [x, y, x_s, y_s] (the
// shear element: [x, y, d_x, d_y], d the cross-section's director).
// Boundary conditions (simply supported ends): x = 0 and y = 0 at s = 0, y = 0 at s = L; the far
// end is a roller in x unless pin_far_end. Fixed coordinates keep their reference values; all
// matrices used in solves are over the free coordinates (numbered in the same order, so an
// element still couples indices within a half bandwidth of 7).
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "ancf_cable.hpp"
#include "ancf_shear.hpp"
#include "banded.hpp"
#include "profile.hpp"

namespace trackwheel {

// No physics defaults (they live in trackwheel.Scene): an unset field fails validation.
struct RailParams {
  double length = 0.0;          // L [m]
  double EA = 0.0;              // axial stiffness E A [N]
  double EI = 0.0;              // bending stiffness E I [N m^2]
  double rhoA = 0.0;            // mass per length rho A [kg/m]
  int n_elements = 0;           // number of ANCF elements [-], 1..limits::kMaxElements
  bool exact_curvature = true;  // kappa = (r_s x r_ss)/|r_s|^3 (true) or r_s x r_ss (false)
  int n_gauss = 0;              // Gauss points per element for the elastic forces [-], 2..10
  double gravity = 0.0;         // g acting on the rail [m/s^2] (0 switches rail weight off)
  bool pin_far_end = false;     // fix x at s = L too
  // Absorbing end zones (docs: Model § Long tracks and absorbing ends): viscous dampers from the
  // rail to the ground over the last absorbing_length of each end, c(d) = absorbing_damping
  // (1 - d / absorbing_length)^2 per length at distance d from the end. 0: none.
  double absorbing_length = 0.0;   // L_z [m], 0 <= 2 L_z <= L
  double absorbing_damping = 0.0;  // c_max at the rail ends [N s/m^2]
  // Shear deformation (Timoshenko): kappa G A > 0 selects the shear-deformable element, whose
  // nodal d is the cross-section's director; 0 is the Euler-Bernoulli cable (d = r_s).
  double shear_stiffness = 0.0;  // kappa G A [N], >= 0
  double rotary_inertia = 0.0;   // rho I [kg m], >= 0; 0 unless shear_stiffness > 0
  bool shear() const { return shear_stiffness > 0.0; }
  // The same zones' dampers on the rail's axial motion x, graded alike: c_x(d) =
  // absorbing_axial_damping (1 - d / absorbing_length)^2 per length. 0: the zones damp y only.
  double absorbing_axial_damping = 0.0;  // c_max,x at the rail ends [N s/m^2]
};

struct SupportParams {
  std::vector<double> position;   // X_j along the undeformed rail [m]
  std::vector<double> stiffness;  // k_s per support [N/m]
  std::vector<double> damping;    // c_s per support [N s/m] (layered: the pad's k_p, c_p)
  // Layered supports (sleepers.hpp): all three per support, or all empty for single springs.
  std::vector<double> sleeper_mass;       // m_s, the sleeper's share of one rail [kg]
  std::vector<double> ballast_stiffness;  // k_b [N/m]
  std::vector<double> ballast_damping;    // c_b [N s/m]
  // Unilateral ballast (sleepers.hpp): a void g_j >= 0 [m] between sleeper j's underside at
  // rest and the ballast bed, one per support or empty (none). A sleeper with g_j > 0, or every
  // sleeper with tensionless, rests on a ballast that pushes only: F_b = max(0, k_b d + c_b d')
  // with d = -z_j - g_j > 0, else 0. g_j = 0 without tensionless: the linear ballast.
  std::vector<double> void_gap;  // g_j [m]
  bool tensionless = false;
  // The ballast under support j can lose contact (or is absent: k_b = 0).
  bool unilateral(size_t j) const {
    return tensionless || (!void_gap.empty() && void_gap[j] > 0.0);
  }
  bool any_unilateral() const;
};

// f(v) for every per-support property vector of s (every field but the positions and the
// run-wide tensionless switch): the fields a travelling window streams (window.hpp). A new
// per-support field is added here too.
template <class S, class F>
void for_each_support_property(S& s, F f) {
  f(s.stiffness);
  f(s.damping);
  f(s.sleeper_mass);
  f(s.ballast_stiffness);
  f(s.ballast_damping);
  f(s.void_gap);
}

// Where a material point s lies in the mesh.
struct MeshPoint {
  int element = 0;  // element index
  double xi = 0.0;  // local coordinate in [0, 1]
  HermiteValues h;  // the centre line's shape functions at xi (r = sum h.n[a] e_a)
  int dof0() const { return 4 * element; }
};

constexpr int kHalfBandwidth = 7;

class RailModel {
 public:
  // profile: the running-surface irregularity r(X) (none by default).
  RailModel(const RailParams& rail, const SupportParams& supports, Profile profile = Profile());

  const RailParams& params() const { return p_; }
  const SupportParams& supports() const { return sup_; }
  const CableSection& section() const { return sec_; }
  const ShearSection& shear_section() const { return shear_sec_; }  // if params().shear()
  const Profile& profile() const { return profile_; }
  int n_nodes() const { return p_.n_elements + 1; }
  int n_dof() const { return 4 * n_nodes(); }
  int n_free() const { return static_cast<int>(free_to_full_.size()); }
  double element_length() const { return sec_.length; }
  const std::vector<int>& full_to_free() const { return full_to_free_; }  // -1 if fixed
  const std::vector<int>& free_to_full() const { return free_to_full_; }

  Eigen::VectorXd reference() const;  // straight, undeformed rail [m, m, -, -]
  MeshPoint locate(double s) const;   // s clamped to [0, L]
  Eigen::Vector2d position(const Eigen::VectorXd& e, const MeshPoint& p) const;          // r [m]
  Eigen::Vector2d slope(const Eigen::VectorXd& e, const MeshPoint& p) const;             // r_s [-]
  Eigen::Vector2d curvature_vector(const Eigen::VectorXd& e, const MeshPoint& p) const;  // r_ss

  const Mat8& element_mass() const { return Me_; }
  // The supports' properties replaced by those of s (the same positions; checked as at
  // construction): the spring and damper bands are re-assembled, O(n). Only a run's own copy of
  // the rail changes so, as its travelling window streams the track's properties in
  // (window.hpp); the rail is otherwise immutable.
  void set_support_properties(const SupportParams& s);

  const BandMatrix& mass() const { return M_; }                // free x free [kg]
  const BandMatrix& support_stiffness() const { return Ks_; }  // free x free [N/m]
  // support dampers + absorbing end zones, free x free [N s/m]
  const BandMatrix& support_damping() const { return Cs_; }
  const Eigen::VectorXd& gravity_force() const { return Qg_; }  // full [N]
  double total_mass() const { return p_.rhoA * p_.length; }

  // Elastic (axial + bending) + support spring (+ support and end-zone dampers if edot) forces,
  // full coordinates [N]; energy [J] = elastic + support spring energy (optional).
  void internal_force(const Eigen::VectorXd& e, const Eigen::VectorXd* edot, Eigen::VectorXd& Q,
                      double* energy = nullptr) const;
  // K += scale * d(elastic + support force)/de over the free coordinates.
  void add_tangent(const Eigen::VectorXd& e, double scale, BandMatrix& K) const;
  // Dense full-coordinate tangent (tests and linear analysis).
  Eigen::MatrixXd tangent_dense(const Eigen::VectorXd& e) const;
  Eigen::MatrixXd mass_dense() const;  // full coordinates

  // Gather/scatter between full and free vectors.
  Eigen::VectorXd to_free(const Eigen::VectorXd& full) const;
  void to_free(const Eigen::VectorXd& full, Eigen::VectorXd& free) const;  // into a buffer
  void add_from_free(const Eigen::VectorXd& free, Eigen::VectorXd& full) const;

 private:
  RailParams p_;
  SupportParams sup_;
  Profile profile_;
  CableSection sec_;
  CableQuadrature quad_;
  ShearSection shear_sec_{};
  ShearQuadrature shear_quad_;
  Mat8 Me_;
  std::vector<int> full_to_free_, free_to_full_;
  std::vector<MeshPoint> support_points_;
  std::vector<std::pair<int, Mat8>> absorbing_;  // (element, its end-zone damping matrix)
  BandMatrix M_, Ks_, Cs_;
  Eigen::VectorXd Qg_;
  void add_element_block(int el, const Mat8& Ke, double scale, BandMatrix& K) const;
  void add_absorbing_ends();
  void assemble_supports();                    // Ks_, Cs_ from sup_ and the end zones
  HermiteValues centre_line(double xi) const;  // the element's centre-line functions at xi
  void element_elastic(const Vec8& ee, Vec8* Q, Mat8* K, double* U) const;
};

}  // namespace trackwheel
