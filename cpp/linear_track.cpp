#include "linear_track.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "banded.hpp"
#include "generalized_alpha.hpp"
#include "linear_rail.hpp"
#include "sleepers.hpp"
#include "window.hpp"

namespace trackwheel {

namespace {

// The track at rest under its own weight, no wheel: K q = Q_g with the sleepers condensed (q over
// the linear track's coordinates, z the sleeper heights) [m].
void own_weight_state(const LinearTrack& tr, Sleepers& sl, Eigen::VectorXd& q, Eigen::VectorXd& z) {
  sl.set_coefficients(0.0, 0.0, 1.0);
  BandMatrix K = tr.K;
  sl.condense_matrix(tr.y_of_full, K);
  if (!K.factorize()) throw std::runtime_error("rail stiffness is singular");
  Eigen::VectorXd rs;
  q = tr.Qg;
  z = Eigen::VectorXd::Zero(sl.size());
  sl.forces(Eigen::VectorXd::Zero(tr.nq), nullptr, tr.y_of_full, z, nullptr, rs);
  sl.condense_rhs(rs, tr.y_of_full, q);
  K.solve_in_place(q);
  sl.back_substitute(rs, q, tr.y_of_full, z);
}

// One wheel on the linear track: its coupling at X_A, state and 2-wide border [Y'', N].
struct LinearWheel {
  Eigen::VectorXd s, ss, sss;  // s(X), s_s(X), s_ss(X) over q at the current X_A
  // d(N - N_contact)/d q'' of the border's force row = cs s + css s_s
  double cs = 0.0, css = 0.0;
  Eigen::MatrixXd W;  // A^-1 of the four y basis vectors of the element (cached)
  Eigen::VectorXd Z;  // A^-1 s(X)
  int cache_el = -1;
  // the element's fixed-end compliance under the load at X_A (zero unless
  // ContactParams::element_compliance; contact.hpp)
  ElementCompliance g;
  double Y = 0.0, Yd = 0.0, Ydd = 0.0, aY = 0.0, N = 0.0;
};

// u . x for the border's force row u = cs s + css s_s of wheel lw
double u_dot(const LinearWheel& lw, const Eigen::VectorXd& x) {
  const double a = lw.cs * lw.s.dot(x);
  return lw.css == 0.0 ? a : a + lw.css * lw.ss.dot(x);
}

class LinearStepper : public Stepper {
 public:
  LinearStepper(const Model& model, const SimSettings& set, const LinearOptions& opt,
                SimOutput& out, const Divergence& div);
  void step(long n) override;
  bool finite() const override;
  double vibration_energy() const override;
  double wheel_height(int w) const override { return wh_[w].Y; }
  void record(long n) override { record_sample(n * set_.dt); }
  void record_sample(double t);

 private:
  // The track coordinate of wheel w at t [m] (outputs, excitation), and its rail coordinate
  // s = X - X_w in the window (couplings; X on a fixed rail).
  double X(int w, double t) const {
    return set_.x_start + model_.wheels[w].x_offset + set_.speed * t;
  }
  double Xl(int w, double t) const { return X(w, t) - origin_; }
  bool rigid() const {
    return opt_.wheel_model == WheelModel::MovingForce ||
           opt_.wheel_model == WheelModel::MovingMass;
  }
  // the contact law of the wheel model: the bilateral linear spring or Hertz
  ContactLaw law() const {
    return opt_.wheel_model == WheelModel::Sprung ? ContactLaw::Linear : ContactLaw::Hertz;
  }
  // The element's fixed-end compliance at the rail coordinate s (zero without
  // ContactParams::element_compliance): the law acts in series with it (contact.hpp).
  ElementCompliance compliance_at(double s) const;
  // The running surfaces' excitation of wheel w at t: e = r(X_A) + Delta rho(psi), the
  // profile under the wheel centre plus the out-of-roundness at psi = theta = v t / rho0 (the
  // linear path rolls without slip) [m], and its rate [m/s].
  double excitation(int w, double t, double& rate) const;
  // Contact force of a sprung/Hertz wheel at the current state and t: N = N_e(delta) + c delta',
  // delta = rho0 + e - Y + y(X_A); dN = dN_e/d delta (0 where the contact is open).
  double contact_force(int w, double t, double& dN) const;
  void initial_state();
  void couple(double t1);
  void border(int w, double t, double cq, double cv, Eigen::Matrix2d& D, Eigen::Vector2d& r2);
  void solve_border(long n, double t, double cq, double cv, int m);
  // The vehicle (vehicle.hpp): the static wheel loads of its weight distribution, the bodies'
  // rows and the suspensions' terms of the wheels' force rows in the border system S_ [dx] =
  // rhs_, the bodies' predictor and update.
  double static_load(int w) const;
  void add_vehicle_rows(double cq, double cv);
  void predict_bodies(double h);
  void update_bodies(double cq, double cv);
  void predict_sleepers(double h);
  void start_window();
  void shift_window(double t1);
  void add_sleeper_residual();
  void correct_sleepers();

  const Model& model_;
  const SimSettings& set_;
  const LinearOptions opt_;
  const LinearTrack tr_;
  SimOutput& out_;
  const Divergence& div_;
  const GACoefficients c_;
  const int nw_;
  Sleepers sl_;   // layered supports (sleepers.hpp): z'' condensed into A_
  BandMatrix A_;  // M + cv C + cq K, factorised once
  bool damped_;
  Eigen::VectorXd q_, qd_, qdd_, a_;
  Eigen::VectorXd z_, zd_, zdd_, az_, zh_, zdh_, azh_, zdd1_, rs_, dz_;  // sleepers
  std::vector<LinearWheel> wh_;
  const int nb_;  // vehicle bodies
  const VehicleMatrices vm_;
  Eigen::VectorXd Pst_;                              // static wheel loads [N]
  Eigen::VectorXd zb_, zbd_, zbdd_, zba_;            // bodies: [z, phi], rates, accel., algorithmic
  Eigen::VectorXd zbh_, zbdh_, zbah_, u_, ud_, fu_;  // predictors and suspension buffers
  // per-step buffers (no allocation in the time loop)
  Eigen::VectorXd ah_, qh_, qdh_, g_, Cq_, Kq_, r1_, x1_, tmp_, qdd1_, rhs_, xb_;
  std::vector<double> aYh_, Yh_, Ydh_;
  Eigen::MatrixXd S_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  // the travelling window: origin X_w, shift maps, the fresh bay's rail and sleeper heights
  double origin_ = 0.0;
  WindowShift win_;
  Eigen::VectorXd q_st_, z_st_;
};

LinearStepper::LinearStepper(const Model& model, const SimSettings& set, const LinearOptions& opt,
                             SimOutput& out, const Divergence& div)
    : model_(model),
      set_(set),
      opt_(opt),
      tr_(model.rail, opt.n_modes, opt.beam),
      out_(out),
      div_(div),
      c_(set.rho_inf),
      nw_(model.n_wheels()),
      sl_(model.rail),
      damped_(!tr_.C.is_zero()),
      wh_(nw_),
      nb_(model.n_bodies()),
      vm_(vehicle_matrices(model.vehicle, model.n_wheels())) {
  if (tr_.modal && !sl_.empty())
    throw std::invalid_argument(
        "n_modes (modal superposition) does not take layered supports (sleeper_mass given); "
        "with sleepers use all coordinates (n_modes=None in trackwheel.simulate)");
  start_window();
  initial_state();
  const double h = set.dt, cq = c_.bp * h * h, cv = c_.gp * h;
  A_.resize(tr_.nq, tr_.bw);
  A_.set_linear_combination(1.0, tr_.M, cv, tr_.C);
  A_.add_scaled(cq, tr_.K);
  sl_.set_coefficients(1.0, cv, cq);
  sl_.condense_matrix(tr_.y_of_full, A_);
  if (!A_.factorize()) throw std::runtime_error("iteration matrix is singular");
}

double LinearStepper::excitation(int w, double t, double& rate) const {
  const WheelParams& p = model_.wheels[w];
  const double v = set_.speed;
  const ProfileValue r = model_.rail.profile()(X(w, t));
  const ProfileValue d = p.radius_change(v * t / p.radius);
  rate = r.rx * v + d.rx * v / p.radius;
  return r.r + d.r;
}

ElementCompliance LinearStepper::compliance_at(double s) const {
  if (!model_.contact.element_compliance) return ElementCompliance();
  const double cs = opt_.beam.timoshenko() ? 1.0 / opt_.beam.shear_stiffness : 0.0;
  const double l = model_.rail.element_length();
  return fixed_end_compliance(model_.rail.params().EI, cs, l, tr_.point(s).xi * l);
}

double LinearStepper::contact_force(int w, double t, double& dN) const {
  const LinearWheel& lw = wh_[w];
  const WheelParams& p = model_.wheels[w];
  double rate;
  const double e = excitation(w, t, rate);
  const double delta = p.radius + e - lw.Y + lw.s.dot(q_);
  double Ne;
  if (model_.contact.element_compliance) {
    const SeriesForce sf = series_normal_force(law(), model_.contact.stiffness, lw.g.G, delta);
    Ne = sf.N;
    dN = sf.slope;
  } else {
    Ne = elastic_normal_force(law(), model_.contact.stiffness, delta, dN);
  }
  const double c = model_.contact.damping;
  if (c == 0.0) return Ne;
  const double delta_dot = rate - lw.Yd + lw.s.dot(qd_) + set_.speed * lw.ss.dot(q_);
  const double N = Ne + c * delta_dot;
  if (law() == ContactLaw::Hertz && (delta <= 0.0 || N <= 0.0)) {  // open, or a pulling damper
    dN = 0.0;
    return 0.0;
  }
  return N;
}

// Static equilibrium under the wheels (or the rail's own weight for a sudden start) and the
// accelerations with the initial contact forces.
void LinearStepper::initial_state() {
  const int nq = tr_.nq;
  const int ns = sl_.size();
  const std::vector<int>& map = tr_.y_of_full;
  // the sleepers at rest condensed (their residual at z = 0 is -m_s g), z from the rail
  BandMatrix Kf = tr_.K;
  sl_.set_coefficients(0.0, 0.0, 1.0);
  sl_.condense_matrix(map, Kf);
  if (!Kf.factorize()) throw std::runtime_error("rail stiffness is singular");
  Pst_.resize(nw_);
  const Eigen::VectorXd fv =
      nb_ > 0 ? static_wheel_forces(vm_, Eigen::VectorXd::Zero(nw_)) : Eigen::VectorXd();
  for (int w = 0; w < nw_; ++w) Pst_(w) = model_.wheels[w].total_load() - (nb_ > 0 ? fv(w) : 0.0);
  q_ = tr_.Qg;
  for (int w = 0; w < nw_; ++w) {
    tr_.coupling(Xl(w, 0.0), wh_[w].s, wh_[w].ss, wh_[w].sss);
    wh_[w].g = compliance_at(Xl(w, 0.0));
    if (!opt_.sudden) q_ -= static_load(w) * wh_[w].s;
  }
  z_ = Eigen::VectorXd::Zero(ns);
  sl_.forces(Eigen::VectorXd::Zero(nq), nullptr, map, z_, nullptr, rs_);
  sl_.condense_rhs(rs_, map, q_);
  Kf.solve_in_place(q_);
  sl_.back_substitute(rs_, q_, map, z_);
  zd_ = Eigen::VectorXd::Zero(ns);
  qd_ = Eigen::VectorXd::Zero(nq);
  Eigen::VectorXd rhs = tr_.Qg, Kq;
  for (int w = 0; w < nw_; ++w) {
    LinearWheel& lw = wh_[w];
    const WheelParams& p = model_.wheels[w];
    const double P = static_load(w), k = model_.contact.stiffness;
    // the approach under P: the law's compression, the element's own deflection G P in series
    // (rigid contact: G P alone)
    double compression = 0.0;
    if (!opt_.sudden)
      compression = rigid() ? (opt_.wheel_model == WheelModel::MovingMass ? lw.g.G * P : 0.0)
                    : model_.contact.element_compliance
                        ? series_static_approach(law(), k, lw.g.G, P)
                        : static_compression(law(), k, P);
    double rate;
    const double e = opt_.wheel_model == WheelModel::MovingForce ? 0.0 : excitation(w, 0.0, rate);
    lw.Y = lw.s.dot(q_) + p.radius + e + opt_.drop_height - compression;
    lw.Yd = 0.0;
    double dN;
    if (opt_.wheel_model == WheelModel::MovingForce)
      lw.N = P;
    else if (opt_.wheel_model == WheelModel::MovingMass)
      lw.N = opt_.sudden ? 0.0 : P;
    else
      lw.N = contact_force(w, 0.0, dN);
    rhs -= lw.N * lw.s;
  }
  tr_.K.multiply(q_, Kq);
  sl_.add_rail_force(z_, &zd_, map, Kq);
  rhs -= Kq;
  sl_.forces(q_, &qd_, map, z_, &zd_, zdd_);
  for (int j = 0; j < ns; ++j) zdd_(j) /= sl_.mass(j);
  az_ = zdd_;
  BandMatrix Mf = tr_.M;
  if (!Mf.factorize()) throw std::runtime_error("rail mass matrix is singular");
  Mf.solve_in_place(rhs);
  qdd_ = rhs;
  a_ = qdd_;
  for (int w = 0; w < nw_; ++w) {
    LinearWheel& lw = wh_[w];
    lw.Ydd = rigid() ? lw.s.dot(qdd_) : (lw.N - static_load(w)) / model_.wheels[w].mass;
    lw.aY = lw.Ydd;
    lw.W.resize(nq, 4);
  }
  if (nb_ > 0) {  // the bodies where their springs carry the static loads, at rest
    Eigen::VectorXd Y(nw_);
    for (int w = 0; w < nw_; ++w) Y(w) = wh_[w].Y;
    zb_ = static_bodies(vm_, Y);
    zbd_ = zbdd_ = zba_ = Eigen::VectorXd::Zero(2 * nb_);
  }
}

double LinearStepper::static_load(int w) const { return Pst_(w); }

// Couplings at t1 and Z = A^-1 s(X) = sum_a N_a A^-1 s_a, the columns cached per element.
void LinearStepper::couple(double t1) {
  for (int w = 0; w < nw_; ++w) {
    LinearWheel& lw = wh_[w];
    const double X1 = Xl(w, t1);
    tr_.coupling(X1, lw.s, lw.ss, lw.sss);
    lw.g = compliance_at(X1);
    const BeamPoint bp = tr_.point(X1);
    if (bp.element != lw.cache_el) {
      for (int k = 0; k < 4; ++k) {
        lw.W.col(k) = tr_.basis(4 * bp.element + 2 * k + 1);
        if (!lw.W.col(k).isZero(0.0)) A_.solve_in_place(lw.W.col(k));
      }
      lw.cache_el = bp.element;
    }
    lw.Z = bp.n[0] * lw.W.col(0) + bp.n[1] * lw.W.col(1) + bp.n[2] * lw.W.col(2) +
           bp.n[3] * lw.W.col(3);
  }
}

// Wheel w's border rows: D [dY''; dN] + u^T x1 e_1 = r2 (rail rows: A x1 + s dN = r1), with
// u = cs s + css s_s the force row's dependence on q'' (through y(X_A) = s.q and, for the
// damper, s.q' and the convected s_s.q v).
void LinearStepper::border(int w, double t, double cq, double cv, Eigen::Matrix2d& D,
                           Eigen::Vector2d& r2) {
  LinearWheel& lw = wh_[w];
  const WheelParams& p = model_.wheels[w];
  const double P = p.total_load();
  D.setZero();
  switch (opt_.wheel_model) {
    case WheelModel::MovingForce:
      r2(0) = -lw.Ydd;  // dummy: the 'wheel' follows nothing
      r2(1) = -(lw.N - P);
      D(0, 0) = 1.0;
      D(1, 1) = 1.0;
      lw.cs = lw.css = 0.0;
      break;
    case WheelModel::MovingMass: {
      double rate;
      const double e = excitation(w, t, rate);
      // Y_A = y(X_A) + rho0 + e - G N: the rail under the load, the element's own deflection
      // included (G = 0 without element compliance)
      r2(0) = -(p.mass * lw.Ydd - lw.N + P);
      r2(1) = -(lw.Y - lw.s.dot(q_) - p.radius - e + lw.g.G * lw.N) / cq;
      D(0, 0) = p.mass;
      D(0, 1) = -1.0;
      D(1, 0) = 1.0;
      D(1, 1) = lw.g.G / cq;
      lw.cs = -1.0;
      lw.css = 0.0;
      break;
    }
    default: {
      double dN;
      const double Nd = contact_force(w, t, dN);
      const double c = Nd == 0.0 && law() == ContactLaw::Hertz ? 0.0 : model_.contact.damping;
      const double k = dN * cq + c * cv;  // d N_contact / d(-Y'') = d N_contact / d(s.q'')
      r2(0) = -(p.mass * lw.Ydd - lw.N + P);
      r2(1) = -(lw.N - Nd);
      D(0, 0) = p.mass;
      D(0, 1) = -1.0;
      D(1, 1) = 1.0;
      D(1, 0) = k;
      lw.cs = -k;
      lw.css = -c * set_.speed * cq;
    }
  }
}

// The Schur complement S [dY''; dN]_w = rhs on the 2-wide borders; xb_ gets the solution. One
// wheel takes a fixed-size 2x2 solve (the common case; a dynamic LU costs more than the rest of
// the border work).
void LinearStepper::solve_border(long n, double t, double cq, double cv, int m) {
  Eigen::Matrix2d D;
  Eigen::Vector2d r2;
  if (nw_ == 1 && nb_ == 0) {
    border(0, t, cq, cv, D, r2);
    D(1, 1) -= u_dot(wh_[0], wh_[0].Z);
    const Eigen::Vector2d rhs(r2(0), r2(1) - u_dot(wh_[0], x1_));
    const double det = D.determinant();
    if (!std::isfinite(det) || det == 0.0) div_.fail(n, "singular iteration matrix");
    xb_ = D.partialPivLu().solve(rhs);
    return;
  }
  S_.setZero(m, m);
  rhs_.setZero(m);
  for (int w = 0; w < nw_; ++w) {
    border(w, t, cq, cv, D, r2);
    S_.block<2, 2>(2 * w, 2 * w) = D;
    for (int v = 0; v < nw_; ++v) S_(2 * w + 1, 2 * v + 1) -= u_dot(wh_[w], wh_[v].Z);
    rhs_(2 * w) = r2(0);
    rhs_(2 * w + 1) = r2(1) - u_dot(wh_[w], x1_);
  }
  if (nb_ > 0) add_vehicle_rows(cq, cv);
  lu_.compute(S_);
  const double det = lu_.determinant();
  if (!std::isfinite(det) || det == 0.0) div_.fail(n, "singular iteration matrix");
  xb_ = lu_.solve(rhs_);
}

// Border rows of the vehicle: wheel w's force row (2 w) gains the suspension force f_u,w, the
// bodies' rows (2 n_w + k) are M_v z'' - f_u = 0; both depend on u'' through cq K_v + cv C_v.
void LinearStepper::add_vehicle_rows(double cq, double cv) {
  const int nu = nw_ + 2 * nb_;
  u_.resize(nu);
  ud_.resize(nu);
  for (int w = 0; w < nw_; ++w) {
    u_(w) = wh_[w].Y;
    ud_(w) = wh_[w].Yd;
  }
  u_.tail(2 * nb_) = zb_;
  ud_.tail(2 * nb_) = zbd_;
  fu_ = vehicle_forces(vm_, u_, ud_);
  auto row = [&](int i) { return i < nw_ ? 2 * i : 2 * nw_ + i - nw_; };
  for (int i = 0; i < nu; ++i) {
    const double inertia = i < nw_ ? 0.0 : vm_.mass(i) * zbdd_(i - nw_);
    rhs_(row(i)) += fu_(i) - inertia;
    if (i >= nw_) S_(row(i), row(i)) += vm_.mass(i);
    for (int j = 0; j < nu; ++j) S_(row(i), row(j)) += cq * vm_.K(i, j) + cv * vm_.C(i, j);
  }
}

void LinearStepper::predict_bodies(double h) {
  const double am = c_.am, af = c_.af, gam = c_.gam, bet = c_.bet;
  zbah_ = (af * zbdd_ - am * zba_) / (1.0 - am);
  zbh_ = zb_ + h * zbd_ + h * h * ((0.5 - bet) * zba_ + bet * zbah_);
  zbdh_ = zbd_ + h * ((1.0 - gam) * zba_ + gam * zbah_);
}

void LinearStepper::update_bodies(double cq, double cv) {
  zb_ = zbh_ + cq * zbdd_;
  zbd_ = zbdh_ + cv * zbdd_;
}

void LinearStepper::step(long n) {
  const double h = set_.dt, t1 = n * h, am = c_.am, af = c_.af, gam = c_.gam, bet = c_.bet;
  const double cq = c_.bp * h * h, cv = c_.gp * h;
  shift_window(t1);
  couple(t1);
  // predictors: q_{n+1} = qh + cq qdd_{n+1}, qd_{n+1} = qdh + cv qdd_{n+1}
  ah_ = (af * qdd_ - am * a_) / (1.0 - am);  // a_{n+1} minus qdd part
  qh_ = q_ + h * qd_ + h * h * ((0.5 - bet) * a_ + bet * ah_);
  qdh_ = qd_ + h * ((1.0 - gam) * a_ + gam * ah_);
  aYh_.resize(nw_);
  Yh_.resize(nw_);
  Ydh_.resize(nw_);
  for (int w = 0; w < nw_; ++w) {
    const LinearWheel& lw = wh_[w];
    aYh_[w] = (af * lw.Ydd - am * lw.aY) / (1.0 - am);
    Yh_[w] = lw.Y + h * lw.Yd + h * h * ((0.5 - bet) * lw.aY + bet * aYh_[w]);
    Ydh_[w] = lw.Yd + h * ((1.0 - gam) * lw.aY + gam * aYh_[w]);
  }
  predict_sleepers(h);
  // g = C qdh + K qh - Q_g: r_q(qdd) = (M + cv C + cq K) qdd + g + sum_w s_w N_w
  tr_.K.multiply(qh_, g_);
  if (damped_) {
    tr_.C.multiply(qdh_, Cq_);
    g_ += Cq_;
  }
  g_ -= tr_.Qg;
  // Newton from qdd_{n+1} = 0: exact in one iteration for the linear wheel models
  qdd1_.setZero(tr_.nq);
  for (LinearWheel& lw : wh_) lw.Ydd = 0.0;
  const int m = 2 * nw_ + 2 * nb_;
  if (nb_ > 0) {
    predict_bodies(h);
    zbdd_.setZero();
  }
  for (int it = 0; it < std::max(set_.max_newton, 1); ++it) {
    q_ = qh_ + cq * qdd1_;
    qd_ = qdh_ + cv * qdd1_;
    for (int w = 0; w < nw_; ++w) {
      wh_[w].Y = Yh_[w] + cq * wh_[w].Ydd;
      wh_[w].Yd = Ydh_[w] + cv * wh_[w].Ydd;
    }
    if (nb_ > 0) update_bodies(cq, cv);
    if (!sl_.empty()) {
      z_ = zh_ + cq * zdd1_;
      zd_ = zdh_ + cv * zdd1_;
    }
    // residuals r = inertia + internal - external (solve J dx = -r)
    if (it == 0) {
      tmp_ = g_;
    } else {
      tr_.M.multiply(qdd1_, r1_);
      tr_.K.multiply(qdd1_, Kq_);
      tmp_ = cq * Kq_ + g_;
    }
    for (const LinearWheel& lw : wh_) tmp_ += lw.N * lw.s;
    if (it == 0) {
      r1_ = -tmp_;
    } else {
      r1_ += tmp_;
      if (damped_) {
        tr_.C.multiply(qdd1_, Cq_);
        r1_ += cv * Cq_;
      }
      r1_ = -r1_;
    }
    add_sleeper_residual();
    // Schur complement on the 2-wide borders with Z_w = A^-1 s_w from the element cache
    x1_ = r1_;
    A_.solve_in_place(x1_);
    solve_border(n, t1, cq, cv, m);
    for (int v = 0; v < nw_; ++v) x1_ -= xb_(2 * v + 1) * wh_[v].Z;
    ++out_.newton_iterations;
    qdd1_ += x1_;
    double dq = x1_.lpNorm<Eigen::Infinity>();
    if (!sl_.empty()) {
      sl_.back_substitute(rs_, x1_, tr_.y_of_full, dz_);
      zdd1_ += dz_;
      dq = std::max(dq, dz_.lpNorm<Eigen::Infinity>());
    }
    bool small_force = true;
    for (int w = 0; w < nw_; ++w) {
      wh_[w].Ydd += xb_(2 * w);
      wh_[w].N += xb_(2 * w + 1);
      dq = std::max(dq, std::abs(xb_(2 * w)));
      small_force &= std::abs(xb_(2 * w + 1)) <= 1e-6 * std::max(1.0, static_load(w));
    }
    if (nb_ > 0) {
      zbdd_ += xb_.tail(2 * nb_);
      dq = std::max(dq, xb_.tail(2 * nb_).lpNorm<Eigen::Infinity>());
    }
    dq *= cq;
    if (opt_.wheel_model != WheelModel::Hertz || (dq <= set_.newton_tol && small_force)) {
      if (nb_ > 0) {
        update_bodies(cq, cv);
        zba_ = zbah_ + ((1.0 - af) / (1.0 - am)) * zbdd_;
      }
      q_ = qh_ + cq * qdd1_;  // the state at the final accelerations
      qd_ = qdh_ + cv * qdd1_;
      a_ = ah_ + ((1.0 - af) / (1.0 - am)) * qdd1_;
      qdd_ = qdd1_;
      correct_sleepers();
      for (int w = 0; w < nw_; ++w) {
        LinearWheel& lw = wh_[w];
        lw.Y = Yh_[w] + cq * lw.Ydd;
        lw.Yd = Ydh_[w] + cv * lw.Ydd;
        lw.aY = aYh_[w] + ((1.0 - af) / (1.0 - am)) * lw.Ydd;
        if (opt_.wheel_model == WheelModel::MovingForce) {
          lw.Y = lw.s.dot(q_) + model_.wheels[w].radius;  // follows the rail, for the record
          lw.Yd = 0.0;
        }
      }
      return;
    }
  }
  div_.fail(n, "Newton did not converge in " + std::to_string(std::max(set_.max_newton, 1)) +
                   " iterations");
}

// The window's shift maps and its rest state: the window's rail at rest under its own weight (no
// wheel), computed once.
void LinearStepper::start_window() {
  const WindowParams& wp = set_.window;
  if (!wp.active()) return;
  if (tr_.modal)
    throw std::invalid_argument("the travelling window needs all coordinates, not n_modes");
  win_ = WindowShift(model_.rail, wp, tr_.y_of_full, tr_.nq, sl_.size());
  origin_ = wp.origin;
  own_weight_state(tr_, sl_, q_st_, z_st_);
}

// Moves the state one bay back in the window while the rearmost wheel at t1 is past the hold
// point. What shifts is the departure from the rest state q_st (the track is linear, so the
// departure obeys the same equations in every window position): q <- q_st + shift(q - q_st),
// likewise z; the generalized-alpha history (q', q'', a and the sleepers') shifts as it is.
// The fresh bay joins at rest (zero departure), and the rest state keeps the window's ends as
// they are (a shift of the state itself would move their end effects into the track). The
// wheels' element caches are invalid after the shift.
void LinearStepper::shift_window(double t1) {
  if (!win_.active()) return;
  const WindowParams& wp = win_.params();
  for (;;) {
    double rear = Xl(0, t1);
    for (int w = 1; w < nw_; ++w) rear = std::min(rear, Xl(w, t1));
    if (rear < wp.hold) return;
    win_.shift(q_, &q_st_);
    win_.shift(qd_);
    win_.shift(qdd_);
    win_.shift(a_);
    if (!sl_.empty()) {
      win_.shift_sleepers(z_, &z_st_);
      win_.shift_sleepers(zd_);
      win_.shift_sleepers(zdd_);
      win_.shift_sleepers(az_);
    }
    for (LinearWheel& lw : wh_) lw.cache_el = -1;
    origin_ += wp.bay;
  }
}

// The sleepers' generalized-alpha predictors (as the rail's in step) and z''_{n+1} = 0.
void LinearStepper::predict_sleepers(double h) {
  if (sl_.empty()) return;
  const double am = c_.am, af = c_.af, gam = c_.gam, bet = c_.bet;
  azh_ = (af * zdd_ - am * az_) / (1.0 - am);
  zh_ = z_ + h * zd_ + h * h * ((0.5 - bet) * az_ + bet * azh_);
  zdh_ = zd_ + h * ((1.0 - gam) * az_ + gam * azh_);
  zdd1_.setZero(sl_.size());
}

// The sleepers' pull on the rail into -r (r1_), their own negated residual rs_ and its
// condensation into r1_.
void LinearStepper::add_sleeper_residual() {
  if (sl_.empty()) return;
  const std::vector<int>& map = tr_.y_of_full;
  sl_.add_rail_force(z_, &zd_, map, r1_, 1.0);
  sl_.forces(q_, &qd_, map, z_, &zd_, rs_);
  for (int j = 0; j < sl_.size(); ++j) rs_(j) -= sl_.mass(j) * zdd1_(j);
  sl_.condense_rhs(rs_, map, r1_);
}

// The sleepers' state at the converged z''_{n+1}.
void LinearStepper::correct_sleepers() {
  if (sl_.empty()) return;
  const double h = set_.dt, cq = c_.bp * h * h, cv = c_.gp * h;
  z_ = zh_ + cq * zdd1_;
  zd_ = zdh_ + cv * zdd1_;
  az_ = azh_ + ((1.0 - c_.af) / (1.0 - c_.am)) * zdd1_;
  zdd_ = zdd1_;
}

bool LinearStepper::finite() const {
  if (!q_.allFinite() || !z_.allFinite()) return false;
  if (nb_ > 0 && !zb_.allFinite()) return false;
  for (const LinearWheel& lw : wh_)
    if (!std::isfinite(lw.Y)) return false;
  return true;
}

double LinearStepper::vibration_energy() const {
  Eigen::VectorXd Mqd;
  tr_.M.multiply(qd_, Mqd);
  double E = 0.5 * qd_.dot(Mqd);
  for (int w = 0; w < nw_; ++w) E += 0.5 * model_.wheels[w].mass * wh_[w].Yd * wh_[w].Yd;
  for (int b = 0; b < nb_; ++b)
    E += 0.5 * model_.vehicle.bodies[b].mass * zbd_(2 * b) * zbd_(2 * b);
  if (!sl_.empty()) E += sl_.kinetic_energy(zd_);
  return E;
}

void LinearStepper::record_sample(double t) {
  Recording& rec = out_.rec;
  const double v = set_.speed;
  rec.push(Field::t, t);
  Eigen::VectorXd s, ss, sss;
  std::vector<double> delta(nw_);
  for (int w = 0; w < nw_; ++w) {
    const LinearWheel& lw = wh_[w];
    const double r0 = model_.wheels[w].radius, Xw = X(w, t);
    tr_.coupling(Xw - origin_, s, ss, sss);
    const ElementCompliance g = compliance_at(Xw - origin_);
    const double ys = ss.dot(q_), yss = sss.dot(q_), yst = ss.dot(qd_);
    double rate;
    // approach, and the law's compression and force in series with the element's compliance
    delta[w] = rigid() ? 0.0 : r0 + excitation(w, t, rate) - lw.Y + s.dot(q_);
    double compression = delta[w], Ne = lw.N;
    if (!rigid() && model_.contact.element_compliance) {
      const SeriesForce sf = series_normal_force(law(), model_.contact.stiffness, g.G, delta[w]);
      compression = sf.compression;
      Ne = sf.N;
    }
    // the rail under the load: the element's own deflection G N_e included
    const double yc = s.dot(q_) - g.G * Ne;
    rec.push(Field::x_wheel, Xw);
    rec.push(Field::y_wheel, lw.Y);
    rec.push(Field::ydot_wheel, lw.Yd);
    rec.push(Field::theta, v * t / r0);
    rec.push(Field::thetadot, v / r0);
    rec.push(Field::contact_s, Xw);
    rec.push(Field::y_contact, yc);
    rec.push(Field::normal_force, lw.N);
    rec.push(Field::tangential_force, 0.0);
    rec.push(Field::slip, 0.0);
    rec.push(Field::v_error, 0.0);
    const double phi = std::atan(ys), gg = 1.0 + ys * ys;
    const double phi_s = yss / gg, phi_t = yst / gg;
    rec.push(Field::phi, phi);
    record_acc_terms(rec, (r0 - delta[w]) * std::cos(phi), v / r0, v, phi_s, phi_t);
    rec.push(Field::acc_contact, s.dot(qdd_) + 2.0 * v * ss.dot(qd_) + v * v * yss);
    rec.push(Field::reaction, 0.0);
    rec.push(Field::penetration, compression);
    rec.push(Field::slip_state, lw.N > 0.0 ? 1 : 0);
  }
  for (int b = 0; b < nb_; ++b) rec.push_body(zb_(2 * b), zb_(2 * b + 1));
  if (!rec.wants(Field::energy)) return;
  Eigen::VectorXd Mqd, Kq;
  tr_.M.multiply(qd_, Mqd);
  tr_.K.multiply(q_, Kq);
  double E = 0.5 * qd_.dot(Mqd) + 0.5 * q_.dot(Kq) - tr_.Qg.dot(q_);
  if (!sl_.empty()) E += sl_.energy(q_, tr_.y_of_full, z_, zd_);
  for (int w = 0; w < nw_; ++w) {
    const WheelParams& p = model_.wheels[w];
    E += 0.5 * p.mass * wh_[w].Yd * wh_[w].Yd;
    E += p.total_load() * wh_[w].Y;
    if (!rigid())
      E += model_.contact.element_compliance
               ? series_potential(law(), model_.contact.stiffness,
                                  compliance_at(X(w, t) - origin_).G, delta[w])
               : contact_potential(law(), model_.contact.stiffness, delta[w]);
    else if (opt_.wheel_model == WheelModel::MovingMass && model_.contact.element_compliance)
      E += 0.5 * compliance_at(X(w, t) - origin_).G * wh_[w].N * wh_[w].N;  // the element's
  }
  if (nb_ > 0) {
    Eigen::VectorXd u(nw_ + 2 * nb_), ud(nw_ + 2 * nb_);
    for (int w = 0; w < nw_; ++w) {
      u(w) = wh_[w].Y;
      ud(w) = wh_[w].Yd;
    }
    u.tail(2 * nb_) = zb_;
    ud.tail(2 * nb_) = zbd_;
    E += vehicle_energy(vm_, u, ud);
  }
  rec.push(Field::energy, E);
}

}  // namespace

SimOutput simulate_linear(const Model& model, const SimSettings& set, const LinearOptions& opt,
                          const ProgressFn& progress) {
  check_settings(set);
  check_model(model);
  if (model.n_bodies() > 0 && opt.wheel_model == WheelModel::MovingForce)
    throw std::invalid_argument(
        "a vehicle with bodies needs wheel dynamics: wheel_model moving_mass, sprung or hertz, "
        "not moving_force");
  SimOutput out;
  out.rec.start(model.n_wheels(), set.record_energy,
                static_cast<std::size_t>(n_steps_of(set) / set.output_every + 2));
  out.rec.start_bodies(model.n_bodies());
  const Divergence div(set, [&set] {
    return "the time step " + format3(set.dt) + " s is too large for the contact";
  });
  LinearStepper stepper(model, set, opt, out, div);
  Watchdog wd;
  for (int w = 0; w < model.n_wheels(); ++w) {
    const WheelParams& p = model.wheels[w];
    wd.energy_cap += 100.0 * std::max(p.total_load(), 1.0) * p.radius;
    wd.y0.push_back(stepper.wheel_height(w));
    wd.reach.push_back(10.0 * p.radius);
  }
  wd.energy_cap += 100.0 * vehicle_weight(model.vehicle) * model.wheels[0].radius;
  stepper.record_sample(0.0);
  run_time_loop(stepper, set, wd, div, out, progress);
  return out;
}

Eigen::VectorXd linear_static_line(const RailModel& rail, const BeamParams& beam, double load,
                                   const std::vector<double>& x, int n_modes,
                                   bool element_compliance) {
  const LinearTrack tr(rail, n_modes, beam);
  Sleepers sl(rail);
  if (!sl.empty() && tr.modal)
    throw std::invalid_argument("n_modes (modal superposition) does not take layered supports");
  // the sleepers at rest condensed, as in LinearStepper::initial_state
  sl.set_coefficients(0.0, 0.0, 1.0);
  BandMatrix K = tr.K;
  sl.condense_matrix(tr.y_of_full, K);
  if (!K.factorize()) throw std::runtime_error("rail stiffness is singular");
  Eigen::VectorXd q_rail = tr.Qg, rs, s, ss, sss;  // the track under its own weight
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(sl.size());
  sl.forces(Eigen::VectorXd::Zero(tr.nq), nullptr, tr.y_of_full, z, nullptr, rs);
  sl.condense_rhs(rs, tr.y_of_full, q_rail);
  K.solve_in_place(q_rail);
  Eigen::VectorXd y(static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) {
    tr.coupling(x[i], s, ss, sss);
    Eigen::VectorXd u = s;  // K^-1 s: the track under a unit upward load at X_i
    K.solve_in_place(u);
    y(static_cast<Eigen::Index>(i)) = s.dot(q_rail) - load * s.dot(u);
    if (element_compliance) {  // the element's own deflection under the load
      const double l = rail.element_length(), xi = tr.point(x[i]).xi;
      const double cs = beam.timoshenko() ? 1.0 / beam.shear_stiffness : 0.0;
      y(static_cast<Eigen::Index>(i)) -=
          load * fixed_end_compliance(rail.params().EI, cs, l, xi * l).G;
    }
  }
  return y;
}

}  // namespace trackwheel
