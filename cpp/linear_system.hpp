// The system workspace of the linear path, beside the full path's System (docs: Model § Rail
// (linearised)): the linear track's constant matrices and their iteration matrix, factorised
// once, the wheels' couplings and contact laws, the vehicle's and the sleepers' rows, and the
// Newton pieces over one bordered system.
//
// Unknowns: the track's q'' (band, linear_rail.hpp; the sleepers' z'' condensed into it,
// sleepers.hpp) and the border x = [Y_A'', N] per wheel, then [z_b'', phi_b''] per vehicle body
// (BorderLayout of layout()). Equations, with y(X_A) = s(X_A) . q:
//   track   M q'' + C q' + K q = Q_g - sum_w s_w N_w (+ the sleepers' pull)
//   wheel w M Y_A'' = N - (F + M g) + f_u,w (the suspensions, vehicle.hpp), and its contact row:
//     MovingForce  N = F + M g (the wheel follows the rail);
//     MovingMass   Y_A = y(X_A) + rho0 + e - G N (rigid contact; G the element compliance);
//     Sprung/Hertz N = N_e(delta) + c delta', delta = rho0 + e - Y_A + y(X_A)
//   (e = r(X_A) + Delta rho(theta): the rail profile and the wheel's out-of-roundness).
// A Newton correction solves the band once (A = M + cv C + cq K) and the border by its Schur
// complement, with Z_w = A^-1 s_w from a cache of the element's columns.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <utility>
#include <vector>

#include "banded.hpp"
#include "ga_scheme.hpp"
#include "linear_rail.hpp"
#include "linear_track.hpp"
#include "model.hpp"
#include "sleepers.hpp"
#include "state.hpp"
#include "vehicle.hpp"

namespace trackwheel {

// The linear track at rest: K q = Q_g + f with the sleepers condensed at rest ((cm, cv, cq) =
// (0, 0, 1), sleepers.hpp), K factorised once. The window's rest state, the start state and the
// quasi-static line all stand on it.
class LinearRest {
 public:
  // The sleepers' unilateral ballast starts in the states of `sleepers`.
  LinearRest(const LinearTrack& track, const Sleepers& sleepers);
  // q = K^-1 (rhs + the sleepers' pull at rest), with z the sleepers' heights under it; rhs is
  // Q_g less the loads, over q. A unilateral ballast: an active set (the states at the
  // solution, K refactorised in the new ones, until no state changes).
  void solve(Eigen::VectorXd& q, Eigen::VectorXd& z);
  // u = K^-1 s (the track under a unit upward load through s; K in the present states).
  void solve_in_place(Eigen::VectorXd& u) const { K_.solve_in_place(u); }
  const Sleepers& sleepers() const { return sl_; }

 private:
  void factorize();
  const LinearTrack& tr_;
  Sleepers sl_;
  BandMatrix K_;
};

// One wheel's coupling to the linear track at its rail coordinate. Over the y coordinates s(X)
// has the four non-zeros of the element under X (its shape functions), kept as such so that
// its products cost O(1) per wheel, not O(n); with modes it is dense (Phi^T s).
struct WheelCoupling {
  Eigen::VectorXd s, ss, sss;                 // s(X), s_s(X), s_ss(X) over q: with modes only
  bool sparse = false;                        // the four non-zeros below hold them (no modes)
  int idx[4] = {-1, -1, -1, -1};              // their y coordinates (-1: fixed)
  double n[4] = {}, ns[4] = {}, nss[4] = {};  // s, s_s and s_ss there [-, 1/m, 1/m^2]
  // sets s(X), s_s(X), s_ss(X) at the point bp of X on the track
  void set(const LinearTrack& tr, const BeamPoint& bp, double X);
  using Vec = Eigen::Ref<const Eigen::VectorXd>;
  double dot(const Vec& x) const;                   // s . x
  double dot_s(const Vec& x) const;                 // s_s . x
  double dot_ss(const Vec& x) const;                // s_ss . x
  void add_to(double a, Eigen::VectorXd& r) const;  // r += a s
  // the contact row's dependence on q'' through y(X_A) = s.q (and, for the damper, s.q' and
  // the convected s_s.q v): u = cs s + css s_s
  double cs = 0.0, css = 0.0;
  Eigen::MatrixXd W;  // A^-1 of the four y basis vectors of the element (cached)
  // Z = A^-1 s(X) = W zn, never formed: its products go through W's four columns. A^-1 decays
  // away from the element (A is mass-dominated at a time step's scale), so W's rows beyond
  // [lo, hi), where every column is below kNegligible of its largest entry, are left out of
  // x -= a Z: a change below round-off, and O(1) per wheel instead of O(n).
  static constexpr double kNegligible = 1e-17;
  double zn[4] = {};
  int lo = 0, hi = 0;
  int cache_el = -1;
  // the element's fixed-end compliance under the load at X_A (zero unless
  // ContactParams::element_compliance; contact.hpp)
  ElementCompliance g;
  double u_dot(const Vec& x) const;                // u . x
  double u_dot_z(const WheelCoupling& v) const;    // u . Z_v
  void sub_z(double a, Eigen::VectorXd& x) const;  // x -= a Z
  void set_support();                              // lo, hi of a new W
};

class LinearSystem {
 public:
  LinearSystem(const Model& model, const SimSettings& settings, const LinearOptions& options);

  const Model& model() const { return model_; }
  const SimSettings& settings() const { return set_; }
  const LinearOptions& options() const { return opt_; }
  const LinearTrack& track() const { return tr_; }
  const Sleepers& sleepers() const { return sl_; }
  const VehicleRows& vehicle() const { return vehicle_; }
  int n_wheels() const { return nw_; }
  int n_bodies() const { return nb_; }
  // The border x = [Y'', N]_w, then [z'', phi''] per body (Accel::x).
  BorderLayout layout() const { return {nw_, nb_, 2, -1, 1}; }
  double static_load(int w) const { return static_load_[w]; }
  // Wheel w's track coordinate X_A at t [m] and its rail coordinate s = X_A - X_w on a
  // travelling window of origin X_w (X_A on a fixed rail) [m].
  double x_at(int w, double t) const { return wheel_x(model_, set_, w, t); }
  double s_at(int w, double t) const { return x_at(w, t) - origin_; }
  double origin() const { return origin_; }
  void set_origin(double x) { origin_ = x; }
  // MovingForce or MovingMass: no contact law between wheel and rail.
  bool rigid() const;
  // The contact law of the wheel model: the bilateral linear spring or Hertz.
  ContactLaw law() const;

  // The element's fixed-end compliance at the rail coordinate s (zero without
  // ContactParams::element_compliance): the law acts in series with it (contact.hpp).
  ElementCompliance compliance_at(double s) const;
  // The running surfaces' excitation of wheel w at t: e = r(X_A) + Delta rho(psi), the profile
  // under the wheel centre plus the out-of-roundness at psi = theta = v t / rho0 (the linear
  // path rolls without slip) [m], and its rate [m/s].
  double excitation(int w, double t, double& rate) const;
  // Contact force of a sprung/Hertz wheel at the state and t: N = N_e(delta) + c delta';
  // dN = dN_e/d delta (0 where the contact is open).
  double contact_force(int w, double t, const SimState& st, double& dN) const;

  // The start: static equilibrium under the wheels (or the track under its own weight for a
  // sudden start, options.sudden), the wheels on it (lifted by options.drop_height), the bodies
  // where their springs carry the static loads, and the accelerations with the initial contact
  // forces (acc.x holds N per wheel).
  void start(SimState& st, Accel& acc);
  // The wheels' couplings at t and their Z = A^-1 s(X_A) (as W zn), the columns W cached per
  // element.
  void couple(double t);
  const WheelCoupling& coupling(int w) const { return wc_[w]; }
  // After the window moved: the element caches are stale.
  void drop_cached_columns();
  // The rail's supports changed their properties (a travelling window streams them in,
  // window.hpp): the track's matrices, the sleepers' rows and the iteration matrix are built
  // and factorised again, O(n).
  void supports_changed();
  // The constant part of the rail's residual at the predictor p: K q_p + C q'_p - Q_g.
  void begin_step(const SimState& p);
  // The negated residual -r of the Newton iteration `it` (it = 0: at x.edd = 0) at the iterate
  // x and its state s1 over the track's rows, the sleepers' rows condensed into them.
  void residual(int it, const SimState& s1, const Accel& x, Eigen::VectorXd& r1);
  // The Newton correction from r1: the track's dq'' (x1), the border's dx (xb) and the
  // sleepers' dz''; false if the border's Schur complement is singular.
  bool solve(double t, const SimState& s1, const Accel& x, const Eigen::VectorXd& r1,
             Eigen::VectorXd& x1, Eigen::VectorXd& xb, Eigen::VectorXd& dz);
  // A unilateral ballast's sleepers (sleepers.hpp): their states set by the law at s1 (a sleeper
  // frozen in this step excepted); if any changed, the iteration matrix is refactorised in the
  // new states and the wheels' cached columns dropped (couple() again). Returns the changes.
  int update_ballast(const SimState& s1);
  // The travelling window moved the sleepers' states with it (Sleepers::shift, join_at_rest):
  // if any changed since the iteration matrix was factorised, it is refactorised in them (and
  // the wheels' cached columns dropped). True if it was.
  bool sync_ballast();
  Sleepers& sleepers() { return sl_; }

 private:
  // Wheel w's border rows: D [dY''; dN] + u^T x1 e_1 = r2 (track rows: A x1 + s dN = r1).
  void border(int w, double t, const SimState& s1, const Accel& x, Eigen::Matrix2d& D,
              Eigen::Vector2d& r2);
  void refactorize_ballast();  // A_ in the sleepers' present states
  bool solve_border(double t, const SimState& s1, const Accel& x, const Eigen::VectorXd& x1,
                    Eigen::VectorXd& xb);
  void factorize_iteration_matrix();  // A_ = M + cv C + cq K, the sleepers condensed
  // The supports' springs and dampers over q: K = K_beam + sum k_j s_j s_j^T (C alike), the
  // track without them and each support's s_j (its nonzero entries) kept from the first call.
  void assemble_supports();

  const Model& model_;
  const SimSettings& set_;
  const LinearOptions opt_;
  LinearTrack tr_;  // rebuilt when the supports change (supports_changed)
  const GACoefficients c_;
  const int nw_, nb_;
  Sleepers sl_;    // layered supports (sleepers.hpp): z'' condensed into A_
  BandMatrix A_;   // M + cv C + cq K, factorised once (again when a ballast state changes)
  BandMatrix A0_;  // M + cv C + cq K unfactorised, kept for a unilateral ballast
  long ballast_version_ = -1;  // the sleepers' states A_ was factorised in (Sleepers::version)
  bool damped_;
  VehicleRows vehicle_;
  std::vector<double> static_load_;  // [N]
  std::vector<WheelCoupling> wc_;
  double origin_ = 0.0;  // window origin X_w [m]
  // per-step buffers (no allocation in the time loop)
  Eigen::VectorXd g_, Cq_, Kq_, tmp_, rs_, rhs_;
  Eigen::MatrixXd S_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  // a streamed window's track without its supports' springs and dampers (assemble_supports)
  BandMatrix Kbeam_, Cbeam_;
  std::vector<std::vector<std::pair<int, double>>> support_s_;
};

}  // namespace trackwheel
