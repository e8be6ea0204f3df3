// The system workspace of the full path (docs: Model § Equations of motion): evaluation of the
// rail, the wheels and their contacts at a state, the equations of motion as residuals, the Newton
// iteration matrix and the index-1 acceleration system, all over one bordered banded system.
//
// Unknowns: the free rail coordinates (band, half bandwidth 7) and, per wheel w, a 3-wide
// border [Y_A'', theta'', lambda] at border index 3 w + {kY, kTheta, kLambda}, then per vehicle
// body b [z_b'', phi_b''] at 3 n_w + 2 b + {0, 1} (vehicle.hpp); with layered supports the
// sleepers' z'' too, condensed exactly into the band (sleepers.hpp). Equations:
//   rail    M e''   = Q_g - Q_kl - Q_kt - Q_s + sum_w (Q_contact,w + lambda_w b_rail,w)
//   wheel w M Y_A'' = -(F + M g) + N n_y + lambda t_y,   J th'' = T - rho lambda - T_b sgn th'
//   (a braked wheel locked: th' = 0 instead),
//   lambda_w: rolling constraint g_w = 0 (stick), sigma mu N (slide) or 0 (no contact),
//   vehicle  M_v u'' = -K_v u - C_v u' - G_v (the suspensions also act on each Y_A row).
// The model is const; every buffer lives here, so a step allocates nothing new.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <vector>

#include "banded.hpp"
#include "body_condensation.hpp"
#include "contact.hpp"
#include "model.hpp"
#include "rolling.hpp"
#include "sleepers.hpp"
#include "state.hpp"

namespace trackwheel {

constexpr int kBorderPerWheel = 3;
constexpr int kY = 0, kTheta = 1, kLambda = 2;
constexpr int kContactCoordinates = 8;  // the rail coordinates of a contact element

// One wheel's contact evaluated at a state.
struct WheelEval {
  double x = 0.0;     // X_A [m]
  ProfileValue drho;  // out-of-roundness Delta rho and its psi-derivatives at psi = theta
  ContactPoint pt;
  ContactForce cf;
  RollingKinematics rk;
  // d rho_r/d theta of the rolling radius rho_r = rho + G N_e (element compliance with an
  // out-of-round wheel: N_e depends on theta through the radius; else 0) [m/rad]
  double drolling_dtheta = 0.0;
};

// Everything evaluated at one (t, state).
struct Eval {
  std::vector<WheelEval> w;
  Eigen::VectorXd Qint;  // elastic + support forces (full) [N]
};

class System {
 public:
  System(const Model& model, const SimSettings& settings);

  const Model& model() const { return model_; }
  const RailModel& rail() const { return model_.rail; }
  const SimSettings& settings() const { return set_; }
  int n_wheels() const { return nw_; }
  int n_free() const { return nf_; }
  int n_bodies() const { return nb_; }
  // Wheel w's static load [N]: F + M g, plus the vehicle's static force on it (the scale of
  // its contact forces, e.g. for Newton's tolerance on lambda).
  double static_load(int w) const { return static_load_[w]; }
  int n_border() const { return kBorderPerWheel * nw_ + 2 * nb_; }
  // The border x = [Y'', theta'', lambda]_w, then [z'', phi''] per body (Accel::x).
  BorderLayout layout() const { return {nw_, nb_, kBorderPerWheel, kTheta, kLambda}; }
  // Wheel w's track coordinate X_A at t [m] (outputs) and its rail coordinate s = X_A - X_w
  // on a travelling window of origin X_w (X_A on a fixed rail) [m].
  double x_at(int w, double t) const { return wheel_x(model_, set_, w, t); }
  double s_at(int w, double t) const { return x_at(w, t) - origin_; }
  // The travelling window's origin X_w [m] (0 on a fixed rail); the rail's profile is given in
  // the rail coordinate of the start window (X_w at t = 0), so it is read shifted by the travel.
  double origin() const { return origin_; }
  void set_origin(double x) { origin_ = x; }

  // Contact search (warm start from each wheel's s), contact forces and rolling kinematics
  // (with their Jacobians if jac), and the rail's internal forces.
  void evaluate(double t, const SimState& st, bool jac, Eval& ev) const;
  // Contact force and rolling kinematics at the found contact points: cheap next to the rail's
  // elastic forces, so a Newton pass that rebuilds its matrix calls this again with jac.
  void contact_terms(const SimState& st, bool jac, Eval& ev) const;

  // Multiplier prescribed by wheel w's slip state, or NaN while it sticks.
  double prescribed_lambda(const SimState& st, const Eval& ev, int w) const;

  // Accelerations and multipliers from the index-1 (acceleration-level) system; the rolling
  // constraint differentiated once, with Baumgarte's g' + alpha g = 0.
  void accelerations(const SimState& st, const Eval& ev, Accel& acc);

  // Generalized-alpha residual (right-hand side -r of J dx = -r) at an iterate; cv = gamma' h
  // scales the velocity-level constraint rows. The sleepers' part is kept for solve().
  void residual(const SimState& st, const Eval& ev, const Accel& acc, double cv,
                Eigen::VectorXd& r1, Eigen::VectorXd& r2);

  // Newton iteration matrix dr/d(e'', x) with cq = beta' h^2, cv = gamma' h, built and
  // factorised for solve(); false if singular. Split form (banded.hpp's SplitBorderedSolver):
  // the rail band M + cv C_s + cq K_t(e) (with the sleepers condensed) is factorised on its
  // own, and every wheel's contact, rolling and slip terms -- the 8 rail coordinates of its
  // contact element, its border rows and columns -- enter through a small dense system, so a
  // new contact block costs no band factorisation. The band is refactorised only with
  // refresh_rail (the rail is nearly linear) or when the sleepers' states changed; a wheel
  // whose contact moved to another element costs 8 band solves.
  bool update_iteration_matrix(const SimState& st, const Eval& ev, const Accel& acc, double cq,
                               double cv, bool refresh_rail);
  // Band factorisations and band solves spent on the iteration matrix so far (diagnostics).
  long band_factorizations() const { return band_factorizations_; }
  long band_solves() const { return split_.band_solves(); }
  // The same matrix assembled in one piece, the contact terms added into the band and its
  // border, then factorised as a whole (the band with them): the form for a matrix kept over
  // many iterations (its results are those of the kernel before the split form, bit for bit).
  void assemble_iteration_matrix(const SimState& st, const Eval& ev, const Accel& acc, double cq,
                                 double cv, bool refresh_rail);
  bool factorize_iteration_matrix();
  // The matrix of assemble_iteration_matrix as a dense (n_free + n_border + n_sleepers)
  // square, the sleepers' block uncondensed (tests).
  Eigen::MatrixXd iteration_matrix_dense() const;
  // The sleepers' negated residual of the last residual() call (tests).
  const Eigen::VectorXd& sleeper_residual() const { return rs_; }

  // Newton correction from the last residual(): rail, border and (layered) sleepers dz.
  void solve(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, Eigen::VectorXd& x1,
             Eigen::VectorXd& x2, Eigen::VectorXd& dz);
  const Sleepers& sleepers() const { return sl_; }
  // The sleepers' unilateral ballast states and their record (sleepers.hpp): residual() sets
  // them at its iterate, accelerations() by the law at its state.
  Sleepers& sleepers() { return sl_; }
  // The rail's supports changed their properties (a travelling window streams them in,
  // window.hpp): the sleepers' rows follow (their ballast states and record kept); the next
  // matrix must refresh its rail part.
  void supports_changed() { sl_.take_properties(rail()); }

 private:
  // Forces without inertia at the multipliers lam (one per wheel): rail (full) and the
  // border forces fb = [F_Y, F_theta, 0]_w.
  void forces(const SimState& st, const Eval& ev, const Eigen::VectorXd& lam, Eigen::VectorXd& fr,
              Eigen::VectorXd& fb) const;
  // The bordered factorisation of [A B; C D] (A factorised here if factor_band). The vehicle's
  // bodies touch no rail coordinate (their B columns and C rows are zero), so they are
  // condensed out of the border exactly: D_ww - D_wb D_bb^-1 D_bw on the wheels' 3 n_w
  // unknowns; the solve recovers them by back-substitution. Without bodies: the plain solver.
  bool factorize_bordered(BandMatrix& A, bool factor_band);
  // Solve with the factorisation of factorize_bordered (bodies back-substituted).
  void solve_bordered(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, Eigen::VectorXd& x1,
                      Eigen::VectorXd& x2) const;
  // Wheel w's contact, rolling and slip terms, through add_local: indices in the contact
  // layout, rail coordinate a of wheel w's contact element at 8 w + a, border entry k at
  // 8 n_w + k (local_ maps them to the full system's indices, -1 for a fixed coordinate).
  void add_wheel_block(const SimState& st, const Eval& ev, const Accel& acc, int w, double cq,
                       double cv);
  bool refresh_rail_matrix(const SimState& st, double cq, double cv, bool refresh_rail);
  void solve_split(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, Eigen::VectorXd& x1,
                   Eigen::VectorXd& x2) const;
  // The solve of `solver` (a factorisation with the wheels' border), the vehicle's bodies
  // back-substituted through `bodies` when there are any.
  template <class Solver>
  void solve_condensed(const Solver& solver, const BodyCondensation& bodies,
                       const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, Eigen::VectorXd& x1,
                       Eigen::VectorXd& x2) const;
  void add_entry(int i, int j, double v);
  // Into the split blocks (split_mode_) or through local_ into the assembled matrix.
  void add_local(int li, int lj, double v);
  void set_local_map(const Eval& ev);
  // C: the border-rail block whose rows a locked wheel clears (Cb_ or Cs_).
  void lock_theta_rows(const SimState& st, Eigen::VectorXd* r2, Eigen::MatrixXd& C);
  // g: the local row/column of wheel-local index 1..10 (-1: none)
  void add_out_of_round_block(const WheelEval& we, const int* g, int o, double cq, double cv);
  // The contact and border blocks (D in Db_) for the rebuilt Jrail_ and sleepers' states.
  void add_contact_blocks(const SimState& st, const Eval& ev, const Accel& acc, double cq,
                          double cv);

  const Model& model_;
  const SimSettings& set_;
  double origin_ = 0.0;  // window origin X_w [m]
  int nf_, nw_, nb_;
  VehicleRows vehicle_;  // the vehicle's rows of the border
  std::vector<double> static_load_;
  BandMatrix Mfac_, J_, Jrail_;
  Eigen::MatrixXd Bb_, Cb_, Db_;
  Eigen::VectorXd fr_, fb_, lam_, lam_p_, Medd_, r1_, r2_, x1_, free_;
  BorderedSolver solver_;
  BodyCondensation bodies_;  // the bodies condensed out of the assembled border
  // The split iteration matrix: the factorised rail band A0_, the contact blocks E (Es_), F
  // (Fs_), G (Cs_) over the wheels' contact elements, the border D in Db_, bodies condensed.
  SplitBorderedSolver split_;
  BandMatrix A0_;
  bool a0_valid_ = false;
  long a0_version_ = -1;  // the sleepers' states condensed into A0_
  long band_factorizations_ = 0;
  bool split_mode_ = false;
  bool split_solve_ = false;  // solve() with the split factorisation (else the assembled one)
  std::vector<int> local_;    // contact layout -> full system index (-1: a fixed coordinate)
  Eigen::MatrixXd Es_, Fs_, Cs_;
  BodyCondensation bodies_split_;  // the same for the split factorisation
  Sleepers sl_;
  std::vector<int> identity_;  // full index -> itself
  Eigen::VectorXd rs_, r1c_;
};

// Total mechanical energy [J]: kinetic + elastic + support springs + contact potentials
// + potentials of gravity on the rail, of the wheel loads P Y_A and of the torques -T theta
// + the vehicle's bodies and suspensions.
double total_energy(const Model& model, const SimState& st, const Eval& ev);
// Energy of the vehicle's bodies and suspensions (vehicle_energy over the state) [J].
double vehicle_energy_of(const Model& model, const SimState& st);
// Kinetic energy of the rail and the wheels' vertical motion [J] (the runaway watchdog's).
double vibration_energy(const Model& model, const SimState& st);

}  // namespace trackwheel
