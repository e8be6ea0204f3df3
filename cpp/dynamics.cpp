#include "dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "banded.hpp"
#include "rolling.hpp"

namespace trackwheel {

std::string format3(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

namespace {

constexpr int kBorder = 3;  // wheel Y, theta, lambda
constexpr int kY = 0, kTheta = 1, kLambda = 2;

std::string fmt(double x) { return format3(x); }

// Everything evaluated at one (t, state).
struct Eval {
  double x = 0.0;        // X_A [m]
  ContactPoint pt;
  ContactForce cf;
  RollingKinematics rk;
  Eigen::VectorXd Qint;  // elastic + support forces (full)
};

// The mutable workspace of one simulation: the model is const, buffers live here.
class System {
 public:
  System(const RailModel& rail, const WheelParams& wheel, const ContactParams& contact,
         const SimSettings& set)
      : rail_(rail), wheel_(wheel), contact_(contact), set_(set), nf_(rail.n_free()),
        P_(wheel.total_load()) {
    Mfac_ = rail.mass();
    if (!Mfac_.factorize()) throw std::runtime_error("rail mass matrix is singular");
    Bb_.resize(nf_, kBorder);
    Cb_.resize(kBorder, nf_);
    Db_.resize(kBorder, kBorder);
    J_.resize(nf_, kHalfBandwidth);
  }

  double x_at(double t) const { return set_.x_start + set_.speed * t; }

  void evaluate(double t, const SimState& st, bool jac, Eval& ev) const {
    ev.x = x_at(t);
    ev.pt = find_contact_point(rail_, st.e, Eigen::Vector2d(ev.x, st.y), st.s);
    contact_terms(st, jac, ev);
    rail_.internal_force(st.e, &st.edot, ev.Qint);
  }

  // Contact force and rolling kinematics at the found contact point (with their Jacobians if
  // jac): cheap next to the rail's elastic forces, so a Newton iteration that rebuilds its
  // matrix calls this again with jac rather than evaluating Jacobians every iteration.
  void contact_terms(const SimState& st, bool jac, Eval& ev) const {
    const int d0 = ev.pt.mp.dof0();
    Vec10 qdot;
    qdot(0) = set_.speed;
    qdot(1) = st.ydot;
    qdot.tail<8>() = st.edot.segment<8>(d0);
    ev.cf = contact_force(contact_, ev.pt, qdot, jac);
    ev.rk = rolling_kinematics(ev.pt, ev.cf.grad_rho, qdot, st.thetadot, jac);
  }

  // Multiplier prescribed by the slip state (Slip, Free), or NaN for Stick.
  double prescribed_lambda(const SimState& st, const Eval& ev) const {
    if (!set_.rolling || st.state == SlipState::Free || !ev.cf.active) return 0.0;
    if (st.state == SlipState::Slip) return st.sigma * set_.friction * ev.cf.N;
    return NAN;
  }
  bool sticking(const SimState& st, const Eval& ev) const {
    return set_.rolling && st.state == SlipState::Stick && ev.cf.active;
  }

  // Forces without inertia at multiplier lambda: rail (full), wheel Y, theta.
  void forces(const Eval& ev, double lambda, Eigen::VectorXd& fr, double& fy, double& fth) const {
    fr = rail_.gravity_force() - ev.Qint;
    const int d0 = ev.pt.mp.dof0();
    fr.segment<8>(d0) += ev.cf.F.tail<8>() + lambda * ev.rk.b.segment<8>(2);
    fy = -P_ + ev.cf.F(1) + lambda * ev.rk.b(1);
    fth = wheel_.torque + lambda * ev.rk.b(10);
  }

  // Accelerations and multiplier from the index-1 (acceleration-level) system.
  void accelerations(const SimState& st, const Eval& ev, Eigen::VectorXd& edd, double& ydd,
                     double& thdd, double& lambda) {
    const double lam_p = prescribed_lambda(st, ev);
    const bool stick = std::isnan(lam_p);
    Eigen::VectorXd fr;
    double fy, fth;
    forces(ev, stick ? 0.0 : lam_p, fr, fy, fth);
    Bb_.setZero();
    Cb_.setZero();
    Db_.setZero();
    Eigen::VectorXd r1 = rail_.to_free(fr), r2 = Eigen::VectorXd::Zero(kBorder);
    Db_(kY, kY) = wheel_.mass;
    Db_(kTheta, kTheta) = wheel_.inertia;
    r2(kY) = fy;
    r2(kTheta) = fth;
    if (stick) {
      const auto& f2f = rail_.full_to_free();
      const int d0 = ev.pt.mp.dof0();
      for (int a = 0; a < 8; ++a) {
        const int i = f2f[d0 + a];
        if (i < 0) continue;
        Bb_(i, kLambda) = -ev.rk.b(2 + a);
        Cb_(kLambda, i) = ev.rk.b(2 + a);
      }
      Db_(kY, kLambda) = -ev.rk.b(1);
      Db_(kTheta, kLambda) = -ev.rk.b(10);
      Db_(kLambda, kY) = ev.rk.b(1);
      Db_(kLambda, kTheta) = ev.rk.b(10);
      // d/dt g = b . qdd + dg/dq . qdot = -alpha g   (X_A'' = 0, X_A' = v)
      Vec10 qdot;
      qdot(0) = set_.speed;
      qdot(1) = st.ydot;
      qdot.tail<8>() = st.edot.segment<8>(d0);
      r2(kLambda) = -ev.rk.dg_dq.dot(qdot) - set_.baumgarte * ev.rk.g;
    } else {
      Db_(kLambda, kLambda) = 1.0;
      r2(kLambda) = lam_p;
    }
    if (!solver_.factorize_border(Mfac_, Bb_, Cb_, Db_))
      throw std::runtime_error("acceleration system is singular");
    Eigen::VectorXd x1, x2;
    solver_.solve(r1, r2, x1, x2);
    edd = Eigen::VectorXd::Zero(rail_.n_dof());
    rail_.add_from_free(x1, edd);
    ydd = x2(kY);
    thdd = x2(kTheta);
    lambda = x2(kLambda);
  }

  // Generalized-alpha residual (right-hand side -r of J dx = -r) at an iterate.
  // cv = gamma' h scales the velocity-level constraint row.
  void residual(const SimState& st, const Eval& ev, const Eigen::VectorXd& edd, double ydd,
                double thdd, double lambda, double cv, Eigen::VectorXd& r1, Eigen::VectorXd& r2) {
    const double lam_p = prescribed_lambda(st, ev);
    const bool stick = std::isnan(lam_p);
    forces(ev, lambda, fr_, fy_, fth_);
    rail_.mass().multiply(rail_.to_free(edd), Medd_);
    r1 = rail_.to_free(fr_) - Medd_;
    r2.resize(kBorder);
    r2(kY) = -(wheel_.mass * ydd - fy_);
    r2(kTheta) = -(wheel_.inertia * thdd - fth_);
    r2(kLambda) = stick ? -ev.rk.g / cv : -(lambda - lam_p);
  }

  // Newton iteration matrix dr/d(qdd, lambda), factorised; false if singular.
  // cq = beta' h^2, cv = gamma' h.
  // The rail part M + cv C_s + cq K_t(e) is cached and rebuilt only when refresh_rail is set
  // (the rail is nearly linear; the contact and constraint parts are rebuilt every time).
  bool jacobian(const SimState& st, const Eval& ev, double lambda, double cq, double cv,
                bool refresh_rail) {
    const bool stick = sticking(st, ev);
    if (refresh_rail || Jrail_.size() != nf_) {
      Jrail_.resize(nf_, kHalfBandwidth);
      Jrail_.set_linear_combination(1.0, rail_.mass(), cv, rail_.support_damping());
      rail_.add_tangent(st.e, cq, Jrail_);
    }
    J_ = Jrail_;
    Bb_.setZero();
    Cb_.setZero();
    Db_.setZero();
    Db_(kY, kY) = wheel_.mass;
    Db_(kTheta, kTheta) = wheel_.inertia;
    const auto& f2f = rail_.full_to_free();
    const int d0 = ev.pt.mp.dof0();
    // local index 1 -> Y, 2..9 -> rail, 10 -> theta (rows only); -1 skip
    auto glob = [&](int a) -> int {
      if (a == 1) return nf_ + kY;
      if (a >= 2 && a <= 9) return f2f[d0 + a - 2];
      if (a == 10) return nf_ + kTheta;
      return -1;
    };
    auto add = [&](int i, int j, double v) {
      if (i < 0 || j < 0 || v == 0.0) return;
      if (i < nf_ && j < nf_) J_.add(i, j, v);
      else if (i < nf_) Bb_(i, j - nf_) += v;
      else if (j < nf_) Cb_(i - nf_, j) += v;
      else Db_(i - nf_, j - nf_) += v;
    };
    for (int a = 1; a <= 10; ++a) {
      const int i = glob(a);
      for (int c = 1; c <= 9; ++c) {
        const int j = glob(c);
        double v = -lambda * ev.rk.db_dq(a, c) * cq;
        if (a <= 9) v += cq * ev.cf.K(a, c) + cv * ev.cf.C(a, c);
        add(i, j, v);
      }
      add(i, nf_ + kLambda, -ev.rk.b(a));  // d r / d lambda
    }
    if (stick) {
      // row: (cq dg/dq + cv b) / cv
      for (int c = 1; c <= 10; ++c) {
        const double v = (c <= 9 ? cq * ev.rk.dg_dq(c) : 0.0) / cv + ev.rk.b(c);
        add(nf_ + kLambda, glob(c), v);
      }
    } else {
      Db_(kLambda, kLambda) = 1.0;
      if (set_.rolling && st.state == SlipState::Slip && ev.cf.active) {
        // lambda - sigma mu N(q, qdot):  dN/dq = -dNe grad_rho, dN/dqdot = -c grad_rho
        const double sm = st.sigma * set_.friction;
        for (int c = 1; c <= 9; ++c)
          add(nf_ + kLambda, glob(c),
              sm * ev.cf.grad_rho(c) * (ev.cf.dN_ddelta * cq + contact_.damping * cv));
      }
    }
    return solver_.factorize(J_, Bb_, Cb_, Db_);
  }

  void solve(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, Eigen::VectorXd& x1,
             Eigen::VectorXd& x2) const {
    solver_.solve(r1, r2, x1, x2);
  }

  const RailModel& rail() const { return rail_; }

 private:
  const RailModel& rail_;
  const WheelParams& wheel_;
  const ContactParams& contact_;
  const SimSettings& set_;
  int nf_;
  double P_;
  BandMatrix Mfac_, J_, Jrail_;
  Eigen::MatrixXd Bb_, Cb_, Db_;
  Eigen::VectorXd fr_, Medd_;
  double fy_ = 0.0, fth_ = 0.0;
  BorderedSolver solver_;
};

// Decide the contact/slip state from an evaluated state; returns true if it changed.
bool update_state(const SimSettings& set, SimState& st, const Eval& ev, double lambda) {
  const SlipState old = st.state;
  const double old_sigma = st.sigma;
  if (!ev.cf.active) {
    st.state = SlipState::Free;
  } else if (!set.rolling) {
    st.state = SlipState::Slip;  // frictionless: lambda = 0 via mu = 0 handled by caller
  } else if (st.state == SlipState::Free) {
    // landing: slide until the slip velocity changes sign (stick at once if it is ~0)
    if (std::abs(ev.rk.g) < 1e-9 * std::max(1.0, std::abs(set.speed))) {
      st.state = SlipState::Stick;
    } else {
      st.state = SlipState::Slip;
      st.sigma = ev.rk.g > 0 ? -1.0 : 1.0;
    }
  } else if (st.state == SlipState::Stick) {
    if (std::abs(lambda) > set.friction * ev.cf.N) {
      st.state = SlipState::Slip;
      st.sigma = lambda > 0 ? 1.0 : -1.0;
    }
  } else {  // Slip: friction force sigma mu N opposes the slip velocity; stick when it reverses
    if (ev.rk.g * st.sigma > 0.0) st.state = SlipState::Stick;
  }
  return st.state != old || st.sigma != old_sigma;
}

// Total mechanical energy [J]: kinetic + elastic + support springs + contact potential
// + potentials of gravity on the rail, of the wheel load P Y_A and of the torque -T theta.
double total_energy(const RailModel& rail, const WheelParams& wheel, const ContactParams& cp,
                    const SimState& st, const Eval& ev) {
  const Eigen::VectorXd v = rail.to_free(st.edot);
  Eigen::VectorXd Mv, Q;
  rail.mass().multiply(v, Mv);
  double U = 0.0;
  rail.internal_force(st.e, nullptr, Q, &U);
  const double d = std::max(ev.cf.delta, 0.0);
  const double Vc = cp.law == ContactLaw::Linear ? 0.5 * cp.stiffness * d * d
                                                 : 0.4 * cp.stiffness * d * d * std::sqrt(d);
  return 0.5 * v.dot(Mv) + 0.5 * wheel.mass * st.ydot * st.ydot +
         0.5 * wheel.inertia * st.thetadot * st.thetadot + U + Vc -
         rail.gravity_force().dot(st.e - rail.reference()) + wheel.total_load() * st.y -
         wheel.torque * st.theta;
}

struct Recorder {
  SimOutput& out;
  const SimSettings& set;
  const WheelParams& wheel;
  const RailModel& rail;
  const ContactParams& contact;
  void reserve(size_t n) {
    for (auto* v : {&out.t, &out.x_wheel, &out.y_wheel, &out.ydot_wheel, &out.theta,
                    &out.thetadot, &out.contact_s, &out.y_contact, &out.normal_force,
                    &out.tangential_force, &out.slip, &out.v_error, &out.phi, &out.acc_contact,
                    &out.acc_A, &out.acc_B, &out.acc_C, &out.acc_D, &out.acc_E, &out.reaction,
                    &out.penetration})
      v->reserve(n);
    out.state.reserve(n);
  }
  void record(double t, const SimState& st, const Eval& ev, const Eigen::VectorXd& edd,
              double lambda) {
    const ContactPoint& pt = ev.pt;
    out.t.push_back(t);
    out.x_wheel.push_back(ev.x);
    out.y_wheel.push_back(st.y);
    out.ydot_wheel.push_back(st.ydot);
    out.theta.push_back(st.theta);
    out.thetadot.push_back(st.thetadot);
    out.contact_s.push_back(pt.s);
    out.y_contact.push_back(pt.r.y());
    out.normal_force.push_back(ev.cf.N);
    out.tangential_force.push_back(lambda);
    out.slip.push_back(ev.rk.g);
    out.state.push_back(static_cast<int>(st.state));
    out.penetration.push_back(ev.cf.delta);
    if (set.record_energy) out.energy.push_back(total_energy(rail, wheel, contact, st, ev));
    const double v = set.speed;
    out.v_error.push_back(v != 0.0 ? (v - pt.rho * st.thetadot) / v * 100.0 : 0.0);
    // obliquity phi = atan2(y_s, x_s), its slope along s and its rate at fixed s
    Eigen::Vector2d Sse = Eigen::Vector2d::Zero(), Se_dd = Eigen::Vector2d::Zero();
    Eigen::Vector2d Ssedot = Eigen::Vector2d::Zero();
    for (int a = 0; a < 4; ++a) {
      Ssedot += pt.mp.h.ns[a] * st.edot.segment<2>(pt.mp.dof0() + 2 * a);
      Se_dd += pt.mp.h.n[a] * edd.segment<2>(pt.mp.dof0() + 2 * a);
    }
    (void)Sse;
    const double gg = pt.rs.squaredNorm();
    const double phi_s = (pt.rs.x() * pt.rss.y() - pt.rs.y() * pt.rss.x()) / gg;
    const double phi_t = (pt.rs.x() * Ssedot.y() - pt.rs.y() * Ssedot.x()) / gg;
    const double rc = pt.rho * std::cos(pt.phi);
    out.phi.push_back(pt.phi);
    out.acc_A.push_back(rc * st.thetadot * v * phi_s);
    out.acc_B.push_back(rc * st.thetadot * phi_t);
    out.acc_C.push_back(rc * v * v * phi_s * phi_s);
    out.acc_D.push_back(rc * phi_t * phi_t);
    out.acc_E.push_back(2.0 * rc * phi_t * v * phi_s);
    // total vertical acceleration of the contact point y_B(t) = y(s*(t), t), with s'' ~ 0
    const double sd = ev.rk.s_dot;
    out.acc_contact.push_back(Se_dd.y() + 2.0 * sd * Ssedot.y() + sd * sd * pt.rss.y());
    // driving reaction holding X_A: M X'' = 0 = R + N n_x + lambda t_x
    out.reaction.push_back(-(ev.cf.F(0) + lambda * ev.rk.b(0)));
  }
};

double vibration_energy(const RailModel& rail, const WheelParams& wheel, const SimState& st) {
  const Eigen::VectorXd v = rail.to_free(st.edot);
  Eigen::VectorXd Mv;
  rail.mass().multiply(v, Mv);
  return 0.5 * v.dot(Mv) + 0.5 * wheel.mass * st.ydot * st.ydot;
}

bool finite_state(const SimState& st) {
  return st.e.allFinite() && st.edot.allFinite() && std::isfinite(st.y) &&
         std::isfinite(st.ydot) && std::isfinite(st.theta) && std::isfinite(st.thetadot);
}

}  // namespace

double highest_frequency(const RailModel& rail, const WheelParams& wheel,
                         const ContactParams& contact, const Eigen::VectorXd& e, double x_wheel,
                         double y_wheel) {
  const int nf = rail.n_free();
  BandMatrix K(nf, kHalfBandwidth), M = rail.mass();
  rail.add_tangent(e, 1.0, K);
  if (!M.factorize()) throw std::runtime_error("rail mass matrix is singular");
  // contact spring couples Y and the rail
  const ContactPoint pt = find_contact_point(rail, e, Eigen::Vector2d(x_wheel, y_wheel), x_wheel);
  const ContactForce cf = contact_force(contact, pt, Vec10::Zero(), true);
  Mat10 Kc = cf.K;
  if (!cf.active) {  // use the linear stiffness at the static load
    ContactParams c2 = contact;
    Kc = (c2.law == ContactLaw::Linear ? c2.stiffness
                                       : 1.5 * std::pow(c2.stiffness, 2.0 / 3.0) *
                                             std::cbrt(wheel.total_load())) *
         cf.grad_rho * cf.grad_rho.transpose();
  }
  const auto& f2f = rail.full_to_free();
  const int d0 = pt.mp.dof0();
  Eigen::VectorXd x = Eigen::VectorXd::Ones(nf + 1);
  for (int i = 0; i < nf + 1; ++i) x(i) = 1.0 + 0.37 * std::sin(1.3 * i);  // deterministic
  double lam = 0.0;
  auto applyK = [&](const Eigen::VectorXd& u, Eigen::VectorXd& out) {
    Eigen::VectorXd ur = u.head(nf), kr;
    K.multiply(ur, kr);
    out = Eigen::VectorXd::Zero(nf + 1);
    out.head(nf) = kr;
    for (int a = 1; a < 10; ++a) {
      const int i = a == 1 ? nf : f2f[d0 + a - 2];
      if (i < 0) continue;
      for (int c = 1; c < 10; ++c) {
        const int j = c == 1 ? nf : f2f[d0 + c - 2];
        if (j >= 0) out(i) += Kc(a, c) * u(j);
      }
    }
  };
  Eigen::VectorXd Kx, y;
  for (int it = 0; it < 400; ++it) {
    applyK(x, Kx);
    y = Kx;
    M.solve_in_place(y.head(nf));
    y(nf) /= wheel.mass;
    // Rayleigh quotient x^T K x / x^T M x
    Eigen::VectorXd Mx;
    rail.mass().multiply(x.head(nf), Mx);
    const double xMx = x.head(nf).dot(Mx) + wheel.mass * x(nf) * x(nf);
    lam = x.dot(Kx) / xMx;
    x = y / y.norm();
  }
  return std::sqrt(std::max(lam, 0.0));
}

double explicit_stability_limit(double omega_max) { return 2.0 * std::sqrt(2.0) / omega_max; }

void check_settings(const SimSettings& set) {
  if (!(set.dt > 0.0) || !std::isfinite(set.dt)) throw std::invalid_argument("dt must be > 0 s");
  if (!(set.t_end >= 0.0) || !std::isfinite(set.t_end))
    throw std::invalid_argument("t_end must be >= 0 s");
  if (set.output_every < 1) throw std::invalid_argument("output_every must be >= 1");
  if (!(set.rho_inf >= 0.0 && set.rho_inf <= 1.0))
    throw std::invalid_argument("rho_inf must be in [0, 1]");
}

SimOutput simulate(const RailModel& rail, const WheelParams& wheel, const ContactParams& contact,
                   const SimSettings& set, const SimState& initial, const ProgressFn& progress) {
  check_settings(set);
  if (initial.e.size() != rail.n_dof() || initial.edot.size() != rail.n_dof())
    throw std::invalid_argument("initial rail state has the wrong size");

  System sys(rail, wheel, contact, set);
  SimOutput out;
  Recorder rec{out, set, wheel, rail, contact};
  const long n_steps = static_cast<long>(std::llround(set.t_end / set.dt));
  rec.reserve(static_cast<size_t>(n_steps / set.output_every + 2));
  const double h = set.dt;

  SimState st = initial;
  Eval ev;
  sys.evaluate(0.0, st, true, ev);
  st.s = ev.pt.s;
  Eigen::VectorXd edd;
  double ydd = 0, thdd = 0, lambda = 0;
  // consistent initial state and accelerations
  for (int k = 0; k < 3; ++k) {
    sys.accelerations(st, ev, edd, ydd, thdd, lambda);
    if (!update_state(set, st, ev, lambda)) break;
  }
  rec.record(0.0, st, ev, edd, lambda);

  const double omega_max =
      highest_frequency(rail, wheel, contact, st.e, sys.x_at(0.0), st.y);
  out.stability_limit = explicit_stability_limit(omega_max);
  const double E_cap = 100.0 * std::max(wheel.total_load(), 1.0) * wheel.radius;
  const double y0 = st.y;

  auto diverge = [&](long step, const std::string& what, const std::string& cause) {
    const double t = step * h;
    std::ostringstream msg;
    msg << "simulation diverged at t = " << fmt(t) << " s (step " << step << ", X_A = "
        << fmt(sys.x_at(t)) << " m): " << what << ". Likely cause: " << cause;
    throw DivergenceError(msg.str(), t, step, cause);
  };
  auto stability_cause = [&]() -> std::string {
    if (set.integrator == Integrator::ExplicitRK4 && h > 0.9 * out.stability_limit)
      return "time step " + fmt(h) + " s is above the explicit stability limit of about " +
             fmt(out.stability_limit) + " s (highest frequency " +
             fmt(omega_max / (2 * M_PI)) + " Hz)";
    if (set.integrator == Integrator::ExplicitRK4)
      return "numerical instability of the explicit scheme (time step " + fmt(h) +
             " s, predicted limit " + fmt(out.stability_limit) + " s)";
    return "the time step " + fmt(h) + " s is too large for the contact or slip transitions, "
           "or the scene is unstable (e.g. the wheel left the rail)";
  };

  // generalized-alpha parameters (Chung & Hulbert 1993)
  const double ri = set.rho_inf;
  const double am = (2.0 * ri - 1.0) / (ri + 1.0), af = ri / (ri + 1.0);
  const double gam = 0.5 - am + af, bet = 0.25 * (1.0 - am + af) * (1.0 - am + af);
  const double bp = bet * (1.0 - af) / (1.0 - am), gp = gam * (1.0 - af) / (1.0 - am);
  const double cq = bp * h * h, cv = gp * h;
  // algorithmic accelerations a_n (start equal to the true accelerations)
  Eigen::VectorXd a_e = edd;
  double a_y = ydd, a_th = thdd;

  Eigen::VectorXd r1, r2, x1, x2, dedd = Eigen::VectorXd::Zero(rail.n_dof());
  bool have_jac = false, have_prev = false;
  bool start_ready = false;  // explicit: ev/edd/lambda already evaluated at the current state
  Eigen::VectorXd edd_prev = edd;
  double ydd_prev = ydd, thdd_prev = thdd, lambda_prev = lambda;
  int jac_element = -1;
  SlipState jac_state = SlipState::Free;
  double jac_sigma = 0.0, jac_s = 0.0;
  for (long n = 1; n <= n_steps; ++n) {
    const double t1 = n * h;
    try {
    if (set.integrator == Integrator::GeneralizedAlpha) {
      // predictors (the parts of q_{n+1}, v_{n+1} known at t_n)
      const SimState s0 = st;
      const Eigen::VectorXd edd0 = edd;
      const double ydd0 = ydd, thdd0 = thdd;
      auto alg = [&](double qdd1, double qdd0, double a0) {
        return (af * qdd0 - am * a0 + (1.0 - af) * qdd1) / (1.0 - am);
      };
      bool done = false;
      for (int attempt = 0; attempt < 4 && !done; ++attempt) {
        // Newton on (qdd_{n+1}, lambda) from the previous accelerations. The iteration matrix
        // is reused across iterations and steps (modified Newton) while the contact stays in
        // the same element and slip state and the iterations contract fast; it is rebuilt
        // otherwise, so every converged step satisfies the full residual to newton_tol.
        // predictor: linear extrapolation of the accelerations (constant on the first step
        // and after a state change)
        const bool extrap = have_prev && attempt == 0;
        Eigen::VectorXd edd1 = extrap ? Eigen::VectorXd(2.0 * edd0 - edd_prev) : edd0;
        double ydd1 = extrap ? 2.0 * ydd0 - ydd_prev : ydd0;
        double thdd1 = extrap ? 2.0 * thdd0 - thdd_prev : thdd0;
        double lam1 = extrap ? 2.0 * lambda - lambda_prev : lambda;
        bool conv = false;
        SimState s1 = st;  // carries the slip state of this attempt
        Eigen::VectorXd ae;
        double ay = 0, ath = 0, prev_dq = INFINITY;
        for (int it = 0; it < set.max_newton; ++it) {
          // q_{n+1}, v_{n+1} from qdd_{n+1}
          ae = (af * edd0 - am * a_e + (1.0 - af) * edd1) / (1.0 - am);
          s1.e = s0.e + h * s0.edot + h * h * ((0.5 - bet) * a_e + bet * ae);
          s1.edot = s0.edot + h * ((1.0 - gam) * a_e + gam * ae);
          ay = alg(ydd1, ydd0, a_y);
          ath = alg(thdd1, thdd0, a_th);
          s1.y = s0.y + h * s0.ydot + h * h * ((0.5 - bet) * a_y + bet * ay);
          s1.ydot = s0.ydot + h * ((1.0 - gam) * a_y + gam * ay);
          s1.theta = s0.theta + h * s0.thetadot + h * h * ((0.5 - bet) * a_th + bet * ath);
          s1.thetadot = s0.thetadot + h * ((1.0 - gam) * a_th + gam * ath);
          if (!finite_state(s1)) diverge(n, "non-finite state in Newton", stability_cause());
          if (conv) break;  // the state at the converged iterate (ev is one correction old)
          sys.evaluate(t1, s1, false, ev);
          s1.s = ev.pt.s;
          sys.residual(s1, ev, edd1, ydd1, thdd1, lam1, cv, r1, r2);
          const bool stale = jac_element != ev.pt.mp.element || jac_state != s1.state ||
                             jac_sigma != s1.sigma || it >= 4 ||
                             std::abs(ev.pt.s - jac_s) > 0.05 * rail.element_length();
          if (!have_jac || stale || !set.reuse_jacobian) {
            const bool refresh_rail = !have_jac || it >= 3 || out.factorizations % 64 == 0;
            sys.contact_terms(s1, true, ev);
            if (!sys.jacobian(s1, ev, lam1, cq, cv, refresh_rail))
              diverge(n, "singular Newton matrix", stability_cause());
            have_jac = true;
            jac_element = ev.pt.mp.element;
            jac_s = ev.pt.s;
            jac_state = s1.state;
            jac_sigma = s1.sigma;
            ++out.factorizations;
          }
          sys.solve(r1, r2, x1, x2);
          ++out.newton_iterations;
          dedd.setZero();
          rail.add_from_free(x1, dedd);
          edd1 += dedd;
          ydd1 += x2(kY);
          thdd1 += x2(kTheta);
          lam1 += x2(kLambda);
          const double dq = cq * std::max({x1.lpNorm<Eigen::Infinity>(), std::abs(x2(kY)),
                                           wheel.radius * std::abs(x2(kTheta))});
          const double dl = std::abs(x2(kLambda));

          // converged: displacement corrections below newton_tol and the tangential force
          // correction below 1e-6 of the wheel load
          if (dq <= set.newton_tol && dl <= 1e-6 * std::max(1.0, wheel.total_load())) {
            conv = true;
            it = -1;  // one more pass to set s1 from the final accelerations
            continue;
          }
          if (it >= 1 && dq > 0.25 * prev_dq) have_jac = false;  // slow: rebuild
          prev_dq = dq;
        }
        if (!conv)
          diverge(n, "Newton did not converge in " + std::to_string(set.max_newton) +
                         " iterations", stability_cause());
        SimState trial = s1;
        const bool changed = update_state(set, trial, ev, lam1);
        if (changed && attempt < 3) {
          ++out.state_changes;
          st.state = trial.state;  // redo the step in the new state
          st.sigma = trial.sigma;
          continue;
        }
        have_prev = !changed && attempt == 0;
        edd_prev = edd0;
        ydd_prev = ydd0;
        thdd_prev = thdd0;
        lambda_prev = lambda;
        st = s1;
        st.state = trial.state;
        st.sigma = trial.sigma;
        a_e = ae;
        a_y = ay;
        a_th = ath;
        edd = edd1;
        ydd = ydd1;
        thdd = thdd1;
        lambda = lam1;
        done = true;
      }
    } else {
      // explicit RK4 on (q, qdot), the slip state frozen over the step
      auto deriv = [&](double t, const SimState& s, Eigen::VectorXd& ea, double& ya,
                       double& tha, double& lam) {
        Eval e2;
        sys.evaluate(t, s, true, e2);
        sys.accelerations(s, e2, ea, ya, tha, lam);
      };
      if (!start_ready) {  // else ev, edd, ... hold this state's evaluation from the output
        sys.evaluate(t1 - h, st, true, ev);
        sys.accelerations(st, ev, edd, ydd, thdd, lambda);
      }
      start_ready = false;
      st.s = ev.pt.s;
      if (update_state(set, st, ev, lambda)) {
        ++out.state_changes;
        sys.accelerations(st, ev, edd, ydd, thdd, lambda);
      }
      const double t0 = t1 - h;
      SimState k = st;
      Eigen::VectorXd e1 = edd, e2a, e3, e4;
      double y1 = ydd, y2, y3, y4, th1 = thdd, th2, th3, th4, lm;
      auto stage = [&](double c, const Eigen::VectorXd& ea, double ya, double tha,
                       const SimState& from_rate) {
        k.e = st.e + c * h * from_rate.edot;
        k.edot = st.edot + c * h * ea;
        k.y = st.y + c * h * from_rate.ydot;
        k.ydot = st.ydot + c * h * ya;
        k.theta = st.theta + c * h * from_rate.thetadot;
        k.thetadot = st.thetadot + c * h * tha;
      };
      const SimState k1 = st;
      stage(0.5, e1, y1, th1, k1);
      const SimState k2 = k;
      deriv(t0 + 0.5 * h, k2, e2a, y2, th2, lm);
      stage(0.5, e2a, y2, th2, k2);
      const SimState k3 = k;
      deriv(t0 + 0.5 * h, k3, e3, y3, th3, lm);
      stage(1.0, e3, y3, th3, k3);
      const SimState k4 = k;
      deriv(t1, k4, e4, y4, th4, lm);
      const double w = h / 6.0;
      st.e += w * (k1.edot + 2.0 * k2.edot + 2.0 * k3.edot + k4.edot);
      st.edot += w * (e1 + 2.0 * e2a + 2.0 * e3 + e4);
      st.y += w * (k1.ydot + 2.0 * k2.ydot + 2.0 * k3.ydot + k4.ydot);
      st.ydot += w * (y1 + 2.0 * y2 + 2.0 * y3 + y4);
      st.theta += w * (k1.thetadot + 2.0 * k2.thetadot + 2.0 * k3.thetadot + k4.thetadot);
      st.thetadot += w * (th1 + 2.0 * th2 + 2.0 * th3 + th4);
      if (!finite_state(st)) diverge(n, "non-finite state", stability_cause());
    }
    out.steps = n;
    if (!finite_state(st)) diverge(n, "non-finite state", stability_cause());
    if (n % 16 == 0 || n == n_steps) {
      const double Ev = vibration_energy(rail, wheel, st);
      if (!(Ev <= E_cap))
        diverge(n, "vibration energy " + fmt(Ev) + " J exceeds 100 (F + M g) rho0 = " +
                       fmt(E_cap) + " J (energy runaway)", stability_cause());
      if (std::abs(st.y - y0) > 10.0 * wheel.radius)
        diverge(n, "the wheel centre moved " + fmt(st.y - y0) + " m from its start",
                stability_cause());
    }
    if (n % set.output_every == 0) {
      if (set.integrator == Integrator::ExplicitRK4) {
        // accelerations and multiplier at the recorded state; the next step starts from them
        sys.evaluate(t1, st, true, ev);
        sys.accelerations(st, ev, edd, ydd, thdd, lambda);
        start_ready = true;
      }
      rec.record(t1, st, ev, edd, lambda);
    }
    } catch (const DivergenceError&) {
      throw;
    } catch (const std::runtime_error& err) {  // contact search, singular systems
      diverge(n, err.what(), stability_cause());
    }
    if (progress && set.progress_every > 0 && n % set.progress_every == 0) progress(n, n_steps);
  }
  out.final_state = st;
  return out;
}

}  // namespace trackwheel
