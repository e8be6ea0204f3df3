#include "system.hpp"

#include <cmath>
#include <stdexcept>

#include "slip.hpp"

namespace trackwheel {

System::System(const Model& model, const SimSettings& set)
    : model_(model),
      set_(set),
      origin_(set.window.active() ? set.window.origin : 0.0),
      nf_(model.rail.n_free()),
      nw_(model.n_wheels()),
      nb_(model.n_bodies()),
      vehicle_(model.vehicle, layout()),
      static_load_(static_wheel_loads(model)),
      sl_(model.rail, set.window.streams_unilateral()),
      identity_(model.rail.n_dof()) {
  for (int i = 0; i < model.rail.n_dof(); ++i) identity_[i] = i;
  Mfac_ = model.rail.mass();
  if (!Mfac_.factorize()) throw std::runtime_error("rail mass matrix is singular");
  const int m = n_border();
  Bb_.resize(nf_, m);
  Cb_.resize(m, nf_);
  Db_.resize(m, m);
  J_.resize(nf_, kHalfBandwidth);
  lam_.resize(nw_);
  const int mw = kBorderPerWheel * nw_, r = kContactCoordinates * nw_;
  split_.resize(nf_, nw_, kContactCoordinates, mw);
  Es_.resize(r, r);
  Fs_.resize(r, mw);
  Cs_.resize(mw, r);
  local_.assign(r + m, -1);
}

void System::evaluate(double t, const SimState& st, bool jac, Eval& ev) const {
  ev.w.resize(nw_);
  for (int w = 0; w < nw_; ++w) {
    WheelEval& we = ev.w[w];
    we.x = x_at(w, t);
    const double shift = origin_ - (set_.window.active() ? set_.window.origin : 0.0);
    we.pt = find_contact_point(rail(), st.e, Eigen::Vector2d(we.x - origin_, st.wheels[w].y),
                               st.wheels[w].s, shift);
  }
  contact_terms(st, jac, ev);
  rail().internal_force(st.e, &st.edot, ev.Qint);
  if (!sl_.empty()) sl_.add_rail_force(st.z, &st.zdot, identity_, ev.Qint);
}

void System::contact_terms(const SimState& st, bool jac, Eval& ev) const {
  for (int w = 0; w < nw_; ++w) {
    WheelEval& we = ev.w[w];
    const int d0 = we.pt.mp.dof0();
    Vec10 qdot;
    qdot(0) = set_.speed;
    qdot(1) = st.wheels[w].ydot;
    qdot.tail<8>() = st.edot.segment<8>(d0);
    // an out-of-round wheel: the radius at the contact is rho0 + Delta rho(theta)
    we.drho = model_.wheels[w].radius_change(st.wheels[w].theta);
    ContactParams c = model_.contact_of(w);
    c.radius += we.drho.r;
    we.cf = contact_force(c, we.pt, qdot, jac, we.drho.rx * st.wheels[w].thetadot);
    if (we.cf.compliant) {
      // the wheel rolls on the rail under the load: rho_r = rho + G N_e = rho0 - delta_c
      we.rk = rolling_kinematics(we.pt, we.pt.rho + we.cf.deflection,
                                 we.cf.grad_rho + we.cf.ddeflection_dq, qdot, st.wheels[w].thetadot,
                                 jac);
      we.drolling_dtheta = we.pt.compliance.G * we.cf.dN_ddelta * we.drho.rx;
    } else {
      we.rk = rolling_kinematics(we.pt, we.cf.grad_rho, qdot, st.wheels[w].thetadot, jac);
      we.drolling_dtheta = 0.0;
    }
  }
}

double System::prescribed_lambda(const SimState& st, const Eval& ev, int w) const {
  return trackwheel::prescribed_lambda(set_.rolling, model_.contact.friction, st.wheels[w],
                                       ev.w[w]);
}

void System::forces(const SimState& st, const Eval& ev, const Eigen::VectorXd& lam,
                    Eigen::VectorXd& fr, Eigen::VectorXd& fb) const {
  fr = rail().gravity_force() - ev.Qint;
  fb.setZero(n_border());
  for (int w = 0; w < nw_; ++w) {
    const WheelEval& we = ev.w[w];
    const WheelParams& p = model_.wheels[w];
    const int d0 = we.pt.mp.dof0(), o = kBorderPerWheel * w;
    fr.segment<8>(d0) += we.cf.F.tail<8>() + lam(w) * we.rk.b.segment<8>(2);
    fb(o + kY) = -p.total_load() + we.cf.F(1) + lam(w) * we.rk.b(1);
    fb(o + kTheta) = wheel_torque(p, we, lam(w));
    if (p.brake_torque > 0.0) fb(o + kTheta) += brake_torque(p, st.wheels[w]);
  }
  if (nb_ > 0) vehicle_.add_forces(st, fb);
}

void System::accelerations(const SimState& st, const Eval& ev, Accel& acc) {
  Eigen::VectorXd& lam_p = lam_p_;
  lam_p.resize(nw_);
  for (int w = 0; w < nw_; ++w) {
    lam_p(w) = prescribed_lambda(st, ev, w);
    lam_(w) = std::isnan(lam_p(w)) ? 0.0 : lam_p(w);
  }
  Eigen::VectorXd &fr = fr_, &fb = fb_;
  forces(st, ev, lam_, fr, fb);
  Bb_.setZero();
  Cb_.setZero();
  Db_.setZero();
  Eigen::VectorXd &r1 = r1_, &r2 = r2_;
  r1 = rail().to_free(fr);
  r2.setZero(n_border());
  const auto& f2f = rail().full_to_free();
  for (int w = 0; w < nw_; ++w) {
    const WheelEval& we = ev.w[w];
    const int o = kBorderPerWheel * w;
    Db_(o + kY, o + kY) = model_.wheels[w].mass;
    Db_(o + kTheta, o + kTheta) = model_.wheels[w].inertia;
    r2(o + kY) = fb(o + kY);
    r2(o + kTheta) = fb(o + kTheta);
    if (!std::isnan(lam_p(w))) {
      Db_(o + kLambda, o + kLambda) = 1.0;
      r2(o + kLambda) = lam_p(w);
      continue;
    }
    const int d0 = we.pt.mp.dof0();
    for (int a = 0; a < 8; ++a) {
      const int i = f2f[d0 + a];
      if (i < 0) continue;
      Bb_(i, o + kLambda) = -we.rk.b(2 + a);
      Cb_(o + kLambda, i) = we.rk.b(2 + a);
    }
    Db_(o + kY, o + kLambda) = -we.rk.b(1);
    Db_(o + kTheta, o + kLambda) = -we.rk.b(10);
    Db_(o + kLambda, o + kY) = we.rk.b(1);
    Db_(o + kLambda, o + kTheta) = we.rk.b(10);
    // d/dt g = b . qdd + dg/dq . qdot = -alpha g   (X_A'' = 0, X_A' = v)
    Vec10 qdot;
    qdot(0) = set_.speed;
    qdot(1) = st.wheels[w].ydot;
    qdot.tail<8>() = st.edot.segment<8>(d0);
    r2(o + kLambda) = -we.rk.dg_dq.dot(qdot) - set_.baumgarte * we.rk.g;
    // dg/dtheta theta' = -theta'^2 d rho_r/d theta (compliance and out-of-roundness)
    const double thd = st.wheels[w].thetadot;
    if (we.drolling_dtheta != 0.0) r2(o + kLambda) += thd * thd * we.drolling_dtheta;
  }
  lock_theta_rows(st, &r2, Cb_);
  if (nb_ > 0) {
    vehicle_.add_block(Db_, true, 0.0, 0.0);
    const int o = kBorderPerWheel * nw_;
    r2.segment(o, 2 * nb_) = fb.segment(o, 2 * nb_);
  }
  if (!factorize_bordered(Mfac_, false))
    throw std::runtime_error("acceleration system is singular");
  solve_bordered(r1, r2, x1_, acc.x);
  acc.edd.setZero(rail().n_dof());
  rail().add_from_free(x1_, acc.edd);
  sl_.update_states(st.z, &st.zdot, false);  // the law at this state
  sl_.accelerations(st.e, &st.edot, identity_, st.z, &st.zdot, acc.zdd);
}

void System::residual(const SimState& st, const Eval& ev, const Accel& acc, double cv,
                      Eigen::VectorXd& r1, Eigen::VectorXd& r2) {
  for (int w = 0; w < nw_; ++w) lam_(w) = acc.x(kBorderPerWheel * w + kLambda);
  forces(st, ev, lam_, fr_, fb_);
  rail().to_free(acc.edd, free_);
  rail().mass().multiply(free_, Medd_);
  rail().to_free(fr_, free_);
  r1 = free_ - Medd_;
  r2.resize(n_border());
  for (int w = 0; w < nw_; ++w) {
    const int o = kBorderPerWheel * w;
    const WheelParams& p = model_.wheels[w];
    const double lam_p = prescribed_lambda(st, ev, w);
    r2(o + kY) = -(p.mass * acc.x(o + kY) - fb_(o + kY));
    r2(o + kTheta) = -(p.inertia * acc.x(o + kTheta) - fb_(o + kTheta));
    r2(o + kLambda) = std::isnan(lam_p) ? -ev.w[w].rk.g / cv : -(lam_(w) - lam_p);
    // a locked wheel: the velocity theta'_{n+1} = 0, scaled as d theta'_{n+1} / d theta'' = cv
    if (st.wheels[w].locked) r2(o + kTheta) = -st.wheels[w].thetadot / cv;
  }
  vehicle_.body_residual(acc.x, fb_, r2);
  sl_.update_states(st.z, &st.zdot);  // a unilateral ballast's state at this iterate
  sl_.residual(st.e, &st.edot, identity_, st.z, &st.zdot, acc.zdd, rs_);
}

void System::solve(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, Eigen::VectorXd& x1,
                   Eigen::VectorXd& x2, Eigen::VectorXd& dz) {
  // The sleepers touch only the rail band and the bodies only the border, so the two
  // condensations are independent: sleepers out of the right-hand side here, bodies inside.
  if (sl_.empty()) {
    solve_split(r1, r2, x1, x2);
    dz.resize(0);
    return;
  }
  r1c_ = r1;
  sl_.condense_rhs(rs_, rail().full_to_free(), r1c_);
  solve_split(r1c_, r2, x1, x2);
  sl_.back_substitute(rs_, x1, rail().full_to_free(), dz);
}

template <class Solver>
void System::solve_condensed(const Solver& solver, const BodyCondensation& bodies,
                             const Eigen::VectorXd& r1, const Eigen::VectorXd& r2,
                             Eigen::VectorXd& x1, Eigen::VectorXd& x2) const {
  auto wheels = [&solver](const Eigen::VectorXd& a, const Eigen::VectorXd& b, Eigen::VectorXd& y1,
                          Eigen::VectorXd& y2) { solver.solve(a, b, y1, y2); };
  if (nb_ == 0)
    wheels(r1, r2, x1, x2);
  else
    bodies.solve(wheels, r1, r2, x1, x2);
}

void System::solve_split(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, Eigen::VectorXd& x1,
                         Eigen::VectorXd& x2) const {
  if (!split_solve_) {
    solve_bordered(r1, r2, x1, x2);
    return;
  }
  solve_condensed(split_, bodies_split_, r1, r2, x1, x2);
}

void System::add_entry(int i, int j, double v) {
  if (i < 0 || j < 0 || v == 0.0) return;
  if (i < nf_ && j < nf_)
    J_.add(i, j, v);
  else if (i < nf_)
    Bb_(i, j - nf_) += v;
  else if (j < nf_)
    Cb_(i - nf_, j) += v;
  else
    Db_(i - nf_, j - nf_) += v;
}

// The rail's part M + cv C_s + cq K_t(e), rebuilt on refresh_rail (or on the first call).
// Returns whether it was rebuilt.
bool System::refresh_rail_matrix(const SimState& st, double cq, double cv, bool refresh_rail) {
  if (!refresh_rail && Jrail_.size() == nf_) return false;
  Jrail_.resize(nf_, kHalfBandwidth);
  Jrail_.set_linear_combination(1.0, rail().mass(), cv, rail().support_damping());
  rail().add_tangent(st.e, cq, Jrail_);
  sl_.set_coefficients(1.0, cv, cq);
  return true;
}

void System::add_contact_blocks(const SimState& st, const Eval& ev, const Accel& acc, double cq,
                                double cv) {
  set_local_map(ev);
  Db_.setZero();
  for (int w = 0; w < nw_; ++w) {
    const int o = kBorderPerWheel * w;
    Db_(o + kY, o + kY) = model_.wheels[w].mass;
    Db_(o + kTheta, o + kTheta) = model_.wheels[w].inertia;
  }
  for (int w = 0; w < nw_; ++w) add_wheel_block(st, ev, acc, w, cq, cv);
  lock_theta_rows(st, nullptr, split_mode_ ? Cs_ : Cb_);
  if (nb_ > 0) vehicle_.add_block(Db_, false, cq, cv);
}

void System::assemble_iteration_matrix(const SimState& st, const Eval& ev, const Accel& acc,
                                       double cq, double cv, bool refresh_rail) {
  if (refresh_rail_matrix(st, cq, cv, refresh_rail)) a0_valid_ = false;
  J_ = Jrail_;
  // the sleepers in their present states (a unilateral ballast's change between two rail
  // refreshes); the same additions onto the same cached sums as when condensed into Jrail_
  sl_.condense_matrix(rail().full_to_free(), J_);
  Bb_.setZero();
  Cb_.setZero();
  split_mode_ = false;
  add_contact_blocks(st, ev, acc, cq, cv);
}

bool System::update_iteration_matrix(const SimState& st, const Eval& ev, const Accel& acc,
                                     double cq, double cv, bool refresh_rail) {
  if (refresh_rail_matrix(st, cq, cv, refresh_rail)) a0_valid_ = false;
  if (!a0_valid_ || sl_.version() != a0_version_) {
    A0_ = Jrail_;
    sl_.condense_matrix(rail().full_to_free(), A0_);  // the sleepers in their present states
    ++band_factorizations_;
    if (!A0_.factorize()) return false;
    split_.set_band(A0_);
    a0_valid_ = true;
    a0_version_ = sl_.version();
  }
  split_solve_ = true;
  Es_.setZero();
  Fs_.setZero();
  Cs_.setZero();
  split_mode_ = true;
  add_contact_blocks(st, ev, acc, cq, cv);
  split_mode_ = false;
  for (int w = 0; w < nw_; ++w) split_.set_group(w, &local_[kContactCoordinates * w]);
  if (nb_ == 0) return split_.factorize(Es_, Fs_, Cs_, Db_);
  return bodies_split_.compute(Db_, kBorderPerWheel * nw_, 2 * nb_) &&
         split_.factorize(Es_, Fs_, Cs_, bodies_split_.reduced());
}

bool System::factorize_iteration_matrix() {
  split_solve_ = false;
  return factorize_bordered(J_, true);
}

void System::set_local_map(const Eval& ev) {
  const auto& f2f = rail().full_to_free();
  const int r = kContactCoordinates * nw_;
  for (int w = 0; w < nw_; ++w) {
    const int d0 = ev.w[w].pt.mp.dof0();
    for (int a = 0; a < kContactCoordinates; ++a) local_[kContactCoordinates * w + a] = f2f[d0 + a];
  }
  for (int k = 0; k < n_border(); ++k) local_[r + k] = nf_ + k;
}

void System::add_local(int li, int lj, double v) {
  if (li < 0 || lj < 0) return;
  if (!split_mode_) {
    add_entry(local_[li], local_[lj], v);
    return;
  }
  if (v == 0.0 || local_[li] < 0 || local_[lj] < 0) return;
  const int r = kContactCoordinates * nw_;
  if (li < r && lj < r)
    Es_(li, lj) += v;
  else if (li < r)
    Fs_(li, lj - r) += v;  // a wheel's column: the bodies touch no rail coordinate
  else if (lj < r)
    Cs_(li - r, lj) += v;
  else
    Db_(li - r, lj - r) += v;
}

// A locked wheel's theta row holds theta' = 0 (the brake's stiction) in place of J theta'' =
// torques: its rows of Cb_ and Db_ become the identity's, for theta'' = 0 at acceleration level
// (r2 given: its entry 0) and for generalized-alpha's velocity row (residual()).
void System::lock_theta_rows(const SimState& st, Eigen::VectorXd* r2, Eigen::MatrixXd& C) {
  for (int w = 0; w < nw_; ++w) {
    if (!st.wheels[w].locked) continue;
    const int i = kBorderPerWheel * w + kTheta;
    C.row(i).setZero();
    Db_.row(i).setZero();
    Db_(i, i) = 1.0;
    if (r2) (*r2)(i) = 0.0;
  }
}

// Wheel w's contact, rolling and slip terms. Local index 1 -> Y, 2..9 -> rail, 10 -> theta.
void System::add_wheel_block(const SimState& st, const Eval& ev, const Accel& acc, int w, double cq,
                             double cv) {
  const WheelEval& we = ev.w[w];
  const WheelState& ws = st.wheels[w];
  const int r = kContactCoordinates * nw_;
  const int o = r + kBorderPerWheel * w;  // the border's local offset
  const double lambda = acc.x(kBorderPerWheel * w + kLambda);
  auto glob = [&](int a) -> int {
    if (a == 1) return o + kY;
    if (a >= 2 && a <= 9) return kContactCoordinates * w + a - 2;
    if (a == 10) return o + kTheta;
    return -1;
  };
  for (int a = 1; a <= 10; ++a) {
    const int i = glob(a);
    for (int c = 1; c <= 9; ++c) {
      double v = -lambda * we.rk.db_dq(a, c) * cq;
      if (a <= 9) v += cq * we.cf.K(a, c) + cv * we.cf.C(a, c);
      add_local(i, glob(c), v);
    }
    add_local(i, o + kLambda, -we.rk.b(a));  // d r / d lambda
  }
  int g[11];
  for (int a = 0; a <= 10; ++a) g[a] = glob(a);
  add_out_of_round_block(we, g, o, cq, cv);
  // the torque -rho_r lambda and g's -rho_r theta' through rho_r(theta) (compliance and
  // out-of-roundness)
  const double drt = we.drolling_dtheta;
  if (drt != 0.0) add_local(o + kTheta, o + kTheta, lambda * drt * cq);
  if (sticking(set_.rolling, ws, we)) {
    // row: (cq dg/dq + cv b) / cv
    for (int c = 1; c <= 10; ++c) {
      const double v = (c <= 9 ? cq * we.rk.dg_dq(c) : 0.0) / cv + we.rk.b(c);
      add_local(o + kLambda, glob(c), v);
    }
    if (drt != 0.0) add_local(o + kLambda, o + kTheta, -cq * ws.thetadot * drt / cv);
    return;
  }
  Db_(o - r + kLambda, o - r + kLambda) = 1.0;
  if (set_.rolling && ws.state == SlipState::Slip && we.cf.active) {
    // lambda - sigma mu N(q, qdot):  dN/dq = -dNe grad_rho, dN/dqdot = -c grad_rho,
    // dN/dtheta = dNe dDelta rho/dpsi, dN/dthetadot = c dDelta rho/dpsi
    const double sm = ws.sigma * model_.contact.friction;
    const double dn = we.cf.dN_ddelta * cq + model_.contact.damping * cv;
    if (we.cf.compliant) {  // dN_e/dq = -k_t u (contact.hpp), not along grad_rho
      const double cc = model_.contact.damping * cv;
      for (int c = 1; c <= 9; ++c)
        add_local(o + kLambda, glob(c), sm * (cc * we.cf.grad_rho(c) - cq * we.cf.dNe_dq(c)));
    } else {
      for (int c = 1; c <= 9; ++c) add_local(o + kLambda, glob(c), sm * we.cf.grad_rho(c) * dn);
    }
    add_local(o + kLambda, o + kTheta, -sm * we.drho.rx * dn);
  }
}

// The coupling of an out-of-round wheel's rotation with its contact force (a round wheel adds
// nothing): N = N_e(delta) + c delta', delta = rho0 + Delta rho(theta) - rho(q), the force
// N grad_rho on q and the moment -N Delta rho' on theta (the damper's own dependence on q and
// theta neglected, as in contact_force's K).
void System::add_out_of_round_block(const WheelEval& we, const int* g, int o, double cq,
                                    double cv) {
  const double d1 = we.drho.rx, d2 = we.drho.rxx;
  if (!we.cf.active || (d1 == 0.0 && d2 == 0.0)) return;
  const double dNe = we.cf.dN_ddelta, c = model_.contact.damping;
  const double dn = dNe * cq + c * cv;
  for (int a = 1; a <= 9; ++a) {
    // d1 dN/dq'' (the element compliance's N_e depends on q along u, contact.hpp)
    const double v = we.cf.compliant ? d1 * (cq * we.cf.dNe_dq(a) - c * cv * we.cf.grad_rho(a))
                                     : -we.cf.grad_rho(a) * d1 * dn;
    add_local(g[a], o + kTheta, v);
    add_local(o + kTheta, g[a], v);
  }
  add_local(o + kTheta, o + kTheta, (dNe * d1 * d1 + we.cf.N * d2) * cq + c * d1 * d1 * cv);
}

bool System::factorize_bordered(BandMatrix& A, bool factor_band) {
  if (nb_ == 0)
    return factor_band ? solver_.factorize(A, Bb_, Cb_, Db_)
                       : solver_.factorize_border(A, Bb_, Cb_, Db_);
  if (factor_band && !A.factorize()) return false;
  const int mw = kBorderPerWheel * nw_;
  return bodies_.compute(Db_, mw, 2 * nb_) &&
         solver_.factorize_border(A, Bb_.leftCols(mw), Cb_.topRows(mw), bodies_.reduced());
}

void System::solve_bordered(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2,
                            Eigen::VectorXd& x1, Eigen::VectorXd& x2) const {
  solve_condensed(solver_, bodies_, r1, r2, x1, x2);
}

Eigen::MatrixXd System::iteration_matrix_dense() const {
  const int m = n_border(), ns = sl_.size();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nf_ + m + ns, nf_ + m + ns);
  Eigen::MatrixXd Jr = J_.dense();
  if (ns == 0) {
    A << Jr, Bb_, Cb_, Db_;
    return A;
  }
  sl_.uncondense_dense(rail().full_to_free(), Jr);
  Eigen::MatrixXd Bs;
  Eigen::VectorXd Ds;
  sl_.coupling_blocks(rail().full_to_free(), nf_, Bs, Ds);
  A.topLeftCorner(nf_, nf_) = Jr;
  A.block(0, nf_, nf_, m) = Bb_;
  A.block(nf_, 0, m, nf_) = Cb_;
  A.block(nf_, nf_, m, m) = Db_;
  A.block(0, nf_ + m, nf_, ns) = Bs;
  A.block(nf_ + m, 0, ns, nf_) = Bs.transpose();
  A.bottomRightCorner(ns, ns) = Ds.asDiagonal();
  return A;
}

}  // namespace trackwheel
