#include "linear_system.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace trackwheel {

LinearRest::LinearRest(const LinearTrack& track, const Sleepers& sleepers)
    : tr_(track), sl_(sleepers) {
  sl_.set_coefficients(0.0, 0.0, 1.0);
  factorize();
}

void LinearRest::factorize() {
  K_ = tr_.K;
  sl_.condense_matrix(tr_.y_of_full, K_);
  if (!K_.factorize()) throw std::runtime_error("rail stiffness is singular");
}

// The sleepers at rest condensed: their residual at z = 0 is -m_s g (less k_b g_j on a closed
// sleeper over a void), and z follows from the rail by back-substitution. The problem is linear
// in each set of states, so an active-set pass solves it exactly; a sleeper that flips back and
// forth is frozen (Sleepers::kMaxFlips).
void LinearRest::solve(Eigen::VectorXd& q, Eigen::VectorXd& z) {
  Eigen::VectorXd rs;
  const Eigen::VectorXd rhs = sl_.unilateral() ? q : Eigen::VectorXd();
  sl_.begin_step();
  for (;;) {
    z = Eigen::VectorXd::Zero(sl_.size());
    sl_.forces(Eigen::VectorXd::Zero(tr_.nq), nullptr, tr_.y_of_full, z, nullptr, rs);
    sl_.condense_rhs(rs, tr_.y_of_full, q);
    K_.solve_in_place(q);
    sl_.back_substitute(rs, q, tr_.y_of_full, z);
    // ends: every change spends one of a sleeper's kMaxFlips flips
    if (!sl_.unilateral() || sl_.update_states(z, nullptr) == 0) return;
    factorize();
    q = rhs;
  }
}

void WheelCoupling::set(const LinearTrack& tr, const BeamPoint& bp, double X) {
  sparse = !tr.modal;
  if (!sparse) {
    tr.coupling(X, s, ss, sss);
    return;
  }
  for (int a = 0; a < 4; ++a) {
    idx[a] = tr.y_of_full[4 * bp.element + 2 * a + 1];
    n[a] = bp.n[a];
    ns[a] = bp.ns[a];
    nss[a] = bp.nss[a];
  }
}

static double sparse_dot(const int* idx, const double* v, const WheelCoupling::Vec& x) {
  double a = 0.0;
  for (int k = 0; k < 4; ++k)
    if (idx[k] >= 0) a += v[k] * x(idx[k]);
  return a;
}

double WheelCoupling::dot(const Vec& x) const { return sparse ? sparse_dot(idx, n, x) : s.dot(x); }

double WheelCoupling::dot_s(const Vec& x) const {
  return sparse ? sparse_dot(idx, ns, x) : ss.dot(x);
}

double WheelCoupling::dot_ss(const Vec& x) const {
  return sparse ? sparse_dot(idx, nss, x) : sss.dot(x);
}

void WheelCoupling::add_to(double a, Eigen::VectorXd& r) const {
  if (!sparse) {
    r += a * s;
    return;
  }
  for (int k = 0; k < 4; ++k)
    if (idx[k] >= 0) r(idx[k]) += a * n[k];
}

double WheelCoupling::u_dot(const Vec& x) const {
  const double a = cs * dot(x);
  return css == 0.0 ? a : a + css * dot_s(x);
}

double WheelCoupling::u_dot_z(const WheelCoupling& v) const {
  double a = 0.0;
  for (int k = 0; k < 4; ++k) a += v.zn[k] * u_dot(v.W.col(k));
  return a;
}

void WheelCoupling::sub_z(double a, Eigen::VectorXd& x) const {
  const Eigen::Vector4d c(a * zn[0], a * zn[1], a * zn[2], a * zn[3]);
  x.segment(lo, hi - lo).noalias() -= W.middleRows(lo, hi - lo) * c;
}

void WheelCoupling::set_support() {
  const int n = static_cast<int>(W.rows());
  lo = n;
  hi = 0;
  for (int k = 0; k < 4; ++k) {
    const double top = W.col(k).cwiseAbs().maxCoeff();
    if (top == 0.0) continue;  // a fixed coordinate's column
    const double cut = kNegligible * top;
    int i0 = 0, i1 = n;
    while (std::abs(W(i0, k)) <= cut) ++i0;
    while (std::abs(W(i1 - 1, k)) <= cut) --i1;
    lo = std::min(lo, i0);
    hi = std::max(hi, i1);
  }
  if (lo >= hi) lo = hi = 0;
}

LinearSystem::LinearSystem(const Model& model, const SimSettings& set, const LinearOptions& opt)
    : model_(model),
      set_(set),
      opt_(opt),
      tr_(model.rail, opt.n_modes, opt.beam),
      c_(set.rho_inf, set.dt),
      nw_(model.n_wheels()),
      nb_(model.n_bodies()),
      sl_(model.rail, set.window.streams_unilateral()),
      damped_(!tr_.C.is_zero()),
      vehicle_(model.vehicle, layout()),
      static_load_(static_wheel_loads(model)),
      wc_(nw_),
      origin_(set.window.active() ? set.window.origin : 0.0) {
  if (tr_.modal && !sl_.empty())
    throw std::invalid_argument(
        "n_modes (modal superposition) does not take layered supports (sleeper_mass given); "
        "with sleepers use all coordinates (n_modes=None in trackwheel.simulate)");
  if (tr_.modal && set.window.active())
    throw std::invalid_argument("the travelling window needs all coordinates, not n_modes");
  factorize_iteration_matrix();
  for (WheelCoupling& wc : wc_) wc.W.resize(tr_.nq, 4);
}

void LinearSystem::factorize_iteration_matrix() {
  A_.resize(tr_.nq, tr_.bw);
  A_.set_linear_combination(1.0, tr_.M, c_.cv, tr_.C);
  A_.add_scaled(c_.cq, tr_.K);
  sl_.set_coefficients(1.0, c_.cv, c_.cq);
  if (sl_.unilateral()) A0_ = A_;
  sl_.condense_matrix(tr_.y_of_full, A_);
  if (!A_.factorize()) throw std::runtime_error("iteration matrix is singular");
  ballast_version_ = sl_.version();
}

// Only the supports change: rebuilding the whole track would assemble the beam's elements again
// (the ANCF tangent at the reference, the costly part); the beam's part is kept instead.
void LinearSystem::assemble_supports() {
  const RailModel& rail = model_.rail;
  const SupportParams& sp = rail.supports();
  if (support_s_.empty()) {
    // the beam alone: no pads, and no sleepers (they are condensed apart, Sleepers), so no
    // void that would need a pad to hang on
    SupportParams bare;
    bare.position = sp.position;
    bare.stiffness.assign(sp.position.size(), 0.0);
    bare.damping.assign(sp.position.size(), 0.0);
    const LinearTrack beam(RailModel(rail.params(), bare), opt_.n_modes, opt_.beam);
    Kbeam_ = beam.K;
    Cbeam_ = beam.C;
    Eigen::VectorXd s, ss, sss;
    for (double x : sp.position) {
      tr_.coupling(x, s, ss, sss);
      std::vector<std::pair<int, double>> nz;
      for (int i = 0; i < tr_.nq; ++i)
        if (s(i) != 0.0) nz.emplace_back(i, s(i));
      support_s_.push_back(std::move(nz));
    }
  }
  tr_.K = Kbeam_;
  tr_.C = Cbeam_;
  for (std::size_t j = 0; j < support_s_.size(); ++j)
    for (const auto& [a, wa] : support_s_[j])
      for (const auto& [b, wb] : support_s_[j]) {
        tr_.K.add(a, b, sp.stiffness[j] * wa * wb);
        tr_.C.add(a, b, sp.damping[j] * wa * wb);
      }
}

void LinearSystem::supports_changed() {
  assemble_supports();
  sl_.take_properties(model_.rail);
  damped_ = !tr_.C.is_zero();
  factorize_iteration_matrix();
  drop_cached_columns();
}

int LinearSystem::update_ballast(const SimState& s1) {
  const int changed = sl_.update_states(s1.z, &s1.zdot);
  if (changed > 0) refactorize_ballast();
  return changed;
}

bool LinearSystem::sync_ballast() {
  if (!sl_.unilateral() || sl_.version() == ballast_version_) return false;
  refactorize_ballast();
  return true;
}

void LinearSystem::refactorize_ballast() {
  A_ = A0_;
  sl_.condense_matrix(tr_.y_of_full, A_);
  if (!A_.factorize()) throw std::runtime_error("iteration matrix is singular");
  ballast_version_ = sl_.version();
  drop_cached_columns();
}

bool LinearSystem::rigid() const {
  return opt_.wheel_model == WheelModel::MovingForce || opt_.wheel_model == WheelModel::MovingMass;
}

ContactLaw LinearSystem::law() const {
  return opt_.wheel_model == WheelModel::Sprung ? ContactLaw::Linear : ContactLaw::Hertz;
}

ElementCompliance LinearSystem::compliance_at(double s) const {
  if (!model_.contact.element_compliance) return ElementCompliance();
  const double cs = opt_.beam.timoshenko() ? 1.0 / opt_.beam.shear_stiffness : 0.0;
  const double l = model_.rail.element_length();
  return fixed_end_compliance(model_.rail.params().EI, cs, l, tr_.point(s).xi * l);
}

double LinearSystem::excitation(int w, double t, double& rate) const {
  const WheelParams& p = model_.wheels[w];
  const double v = set_.speed;
  const ProfileValue r = model_.rail.profile()(x_at(w, t));
  const ProfileValue d = p.radius_change(v * t / p.radius);
  rate = r.rx * v + d.rx * v / p.radius;
  return r.r + d.r;
}

double LinearSystem::contact_force(int w, double t, const SimState& st, double& dN) const {
  const WheelCoupling& wc = wc_[w];
  const WheelState& ws = st.wheels[w];
  double rate;
  const double e = excitation(w, t, rate);
  const double delta = model_.wheels[w].radius + e - ws.y + wc.dot(st.e);
  double Ne;
  if (model_.contact.element_compliance) {
    const SeriesForce sf = series_normal_force(law(), model_.contact.stiffness, wc.g.G, delta);
    Ne = sf.N;
    dN = sf.slope;
  } else {
    Ne = elastic_normal_force(law(), model_.contact.stiffness, delta, dN);
  }
  const double c = model_.contact.damping;
  if (c == 0.0) return Ne;
  const double delta_dot = rate - ws.ydot + wc.dot(st.edot) + set_.speed * wc.dot_s(st.e);
  const double N = Ne + c * delta_dot;
  if (law() == ContactLaw::Hertz && (delta <= 0.0 || N <= 0.0)) {  // open, or a pulling damper
    dN = 0.0;
    return 0.0;
  }
  return N;
}

void LinearSystem::couple(double t) {
  for (int w = 0; w < nw_; ++w) {
    WheelCoupling& wc = wc_[w];
    const double X = s_at(w, t);
    const BeamPoint bp = tr_.point(X);
    wc.set(tr_, bp, X);
    wc.g = compliance_at(X);
    if (bp.element != wc.cache_el) {
      for (int k = 0; k < 4; ++k) {
        wc.W.col(k) = tr_.basis(4 * bp.element + 2 * k + 1);
        if (!wc.W.col(k).isZero(0.0)) A_.solve_in_place(wc.W.col(k));
      }
      wc.cache_el = bp.element;
      wc.set_support();
    }
    std::copy(bp.n, bp.n + 4, wc.zn);
  }
}

void LinearSystem::drop_cached_columns() {
  for (WheelCoupling& wc : wc_) wc.cache_el = -1;
}

void LinearSystem::begin_step(const SimState& p) {
  tr_.K.multiply(p.e, g_);
  if (damped_) {
    tr_.C.multiply(p.edot, Cq_);
    g_ += Cq_;
  }
  g_ -= tr_.Qg;
}

// r(q'') = (M + cv C + cq K) q'' + g + sum_w s_w N_w with g = K q_p + C q'_p - Q_g (begin_step),
// evaluated as M q'' + (cq K q'' + g) + sum_w s_w N_w + cv C q''.
void LinearSystem::residual(int it, const SimState& s1, const Accel& x, Eigen::VectorXd& r1) {
  const BorderLayout b = layout();
  if (it == 0) {
    tmp_ = g_;
  } else {
    tr_.M.multiply(x.edd, r1);
    tr_.K.multiply(x.edd, Kq_);
    tmp_ = c_.cq * Kq_ + g_;
  }
  for (int w = 0; w < nw_; ++w) wc_[w].add_to(x.x(b.y(w) + b.multiplier), tmp_);
  if (it == 0) {
    r1 = -tmp_;
  } else {
    r1 += tmp_;
    if (damped_) {
      tr_.C.multiply(x.edd, Cq_);
      r1 += c_.cv * Cq_;
    }
    r1 = -r1;
  }
  if (sl_.empty()) return;
  // the sleepers' pull on the rail, their own negated residual and its condensation
  const std::vector<int>& map = tr_.y_of_full;
  sl_.add_rail_force(s1.z, &s1.zdot, map, r1, 1.0);
  sl_.residual(s1.e, &s1.edot, map, s1.z, &s1.zdot, x.zdd, rs_);
  sl_.condense_rhs(rs_, map, r1);
}

bool LinearSystem::solve(double t, const SimState& s1, const Accel& x, const Eigen::VectorXd& r1,
                         Eigen::VectorXd& x1, Eigen::VectorXd& xb, Eigen::VectorXd& dz) {
  x1 = r1;
  A_.solve_in_place(x1);
  if (!solve_border(t, s1, x, x1, xb)) return false;
  for (int v = 0; v < nw_; ++v) wc_[v].sub_z(xb(2 * v + 1), x1);
  if (!sl_.empty()) sl_.back_substitute(rs_, x1, tr_.y_of_full, dz);
  return true;
}

// The Schur complement S [dY''; dN]_w = rhs on the 2-wide borders (the vehicle's rows too) with
// Z_w = A^-1 s_w. One wheel takes a fixed-size 2x2 solve (the common case; a dynamic LU costs
// more than the rest of the border work).
bool LinearSystem::solve_border(double t, const SimState& s1, const Accel& x,
                                const Eigen::VectorXd& x1, Eigen::VectorXd& xb) {
  Eigen::Matrix2d D;
  Eigen::Vector2d r2;
  if (nw_ == 1 && nb_ == 0) {
    border(0, t, s1, x, D, r2);
    D(1, 1) -= wc_[0].u_dot_z(wc_[0]);
    const Eigen::Vector2d rhs(r2(0), r2(1) - wc_[0].u_dot(x1));
    const double det = D.determinant();
    if (!std::isfinite(det) || det == 0.0) return false;
    xb = D.partialPivLu().solve(rhs);
    return true;
  }
  const int m = layout().size();
  S_.setZero(m, m);
  rhs_.setZero(m);
  for (int w = 0; w < nw_; ++w) {
    border(w, t, s1, x, D, r2);
    S_.block<2, 2>(2 * w, 2 * w) = D;
    for (int v = 0; v < nw_; ++v) S_(2 * w + 1, 2 * v + 1) -= wc_[w].u_dot_z(wc_[v]);
    rhs_(2 * w) = r2(0);
    rhs_(2 * w + 1) = r2(1) - wc_[w].u_dot(x1);
  }
  if (nb_ > 0) {
    vehicle_.add_forces(s1, rhs_);
    vehicle_.body_residual(x.x, rhs_, rhs_);
    vehicle_.add_block(S_, false, c_.cq, c_.cv);
  }
  lu_.compute(S_);
  const double det = lu_.determinant();
  if (!std::isfinite(det) || det == 0.0) return false;
  xb = lu_.solve(rhs_);
  return true;
}

// u = cs s + css s_s is the contact row's dependence on q'' (through y(X_A) = s.q and, for the
// damper, s.q' and the convected s_s.q v).
void LinearSystem::border(int w, double t, const SimState& s1, const Accel& x, Eigen::Matrix2d& D,
                          Eigen::Vector2d& r2) {
  WheelCoupling& wc = wc_[w];
  const WheelParams& p = model_.wheels[w];
  const double P = p.total_load(), cq = c_.cq, Ydd = x.x(2 * w), N = x.x(2 * w + 1);
  D.setZero();
  switch (opt_.wheel_model) {
    case WheelModel::MovingForce:
      r2(0) = -Ydd;  // dummy: the 'wheel' follows nothing
      r2(1) = -(N - P);
      D(0, 0) = 1.0;
      D(1, 1) = 1.0;
      wc.cs = wc.css = 0.0;
      break;
    case WheelModel::MovingMass: {
      double rate;
      const double e = excitation(w, t, rate);
      // Y_A = y(X_A) + rho0 + e - G N: the rail under the load, the element's own deflection
      // included (G = 0 without element compliance)
      r2(0) = -(p.mass * Ydd - N + P);
      r2(1) = -(s1.wheels[w].y - wc.dot(s1.e) - p.radius - e + wc.g.G * N) / cq;
      D(0, 0) = p.mass;
      D(0, 1) = -1.0;
      D(1, 0) = 1.0;
      D(1, 1) = wc.g.G / cq;
      wc.cs = -1.0;
      wc.css = 0.0;
      break;
    }
    default: {
      double dN;
      const double Nd = contact_force(w, t, s1, dN);
      const double c = Nd == 0.0 && law() == ContactLaw::Hertz ? 0.0 : model_.contact.damping;
      const double k = dN * cq + c * c_.cv;  // d N_contact / d(-Y'') = d N_contact / d(s.q'')
      r2(0) = -(p.mass * Ydd - N + P);
      r2(1) = -(N - Nd);
      D(0, 0) = p.mass;
      D(0, 1) = -1.0;
      D(1, 1) = 1.0;
      D(1, 0) = k;
      wc.cs = -k;
      wc.css = -c * set_.speed * cq;
    }
  }
}

// Static equilibrium under the wheels; contact_force reads the start state, so the wheels are
// placed before their forces are taken.
void LinearSystem::start(SimState& st, Accel& acc) {
  const std::vector<int>& map = tr_.y_of_full;
  LinearRest rest(tr_, sl_);
  st.e = tr_.Qg;
  for (int w = 0; w < nw_; ++w) {
    const double X = s_at(w, 0.0);
    wc_[w].set(tr_, tr_.point(X), X);
    wc_[w].g = compliance_at(X);
    if (!opt_.sudden) wc_[w].add_to(-static_load(w), st.e);
  }
  rest.solve(st.e, st.z);
  st.zdot = Eigen::VectorXd::Zero(sl_.size());
  st.edot = Eigen::VectorXd::Zero(tr_.nq);
  st.wheels.assign(nw_, WheelState());
  acc.x.setZero(layout().size());
  // the iteration matrix in the ballast states of the law at the start state
  if (sl_.unilateral()) {
    sl_.begin_step();
    update_ballast(st);
  }
  Eigen::VectorXd rhs = tr_.Qg, Kq;
  for (int w = 0; w < nw_; ++w) {
    const WheelCoupling& wc = wc_[w];
    const WheelParams& p = model_.wheels[w];
    const double P = static_load(w), k = model_.contact.stiffness;
    // the approach under P: the law's compression, the element's own deflection G P in series
    // (rigid contact: G P alone)
    double compression = 0.0;
    if (!opt_.sudden)
      compression = rigid() ? (opt_.wheel_model == WheelModel::MovingMass ? wc.g.G * P : 0.0)
                    : model_.contact.element_compliance
                        ? series_static_approach(law(), k, wc.g.G, P)
                        : static_compression(law(), k, P);
    double rate;
    const double e = opt_.wheel_model == WheelModel::MovingForce ? 0.0 : excitation(w, 0.0, rate);
    st.wheels[w].y = wc.dot(st.e) + p.radius + e + opt_.drop_height - compression;
    st.wheels[w].ydot = 0.0;
    double N, dN;
    if (opt_.wheel_model == WheelModel::MovingForce)
      N = P;
    else if (opt_.wheel_model == WheelModel::MovingMass)
      N = opt_.sudden ? 0.0 : P;
    else
      N = contact_force(w, 0.0, st, dN);
    acc.x(2 * w + 1) = N;
    wc.add_to(-N, rhs);
  }
  tr_.K.multiply(st.e, Kq);
  sl_.add_rail_force(st.z, &st.zdot, map, Kq);
  rhs -= Kq;
  sl_.accelerations(st.e, &st.edot, map, st.z, &st.zdot, acc.zdd);
  BandMatrix Mf = tr_.M;
  if (!Mf.factorize()) throw std::runtime_error("rail mass matrix is singular");
  Mf.solve_in_place(rhs);
  acc.edd = rhs;
  for (int w = 0; w < nw_; ++w)
    acc.x(2 * w) =
        rigid() ? wc_[w].dot(acc.edd) : (acc.x(2 * w + 1) - static_load(w)) / model_.wheels[w].mass;
  st.body = st.bodydot = Eigen::VectorXd::Zero(2 * nb_);
  if (nb_ > 0) {  // the bodies where their springs carry the static loads, at rest
    Eigen::VectorXd Y(nw_);
    for (int w = 0; w < nw_; ++w) Y(w) = st.wheels[w].y;
    st.body = static_bodies(vehicle_.matrices(), Y);
  }
}

}  // namespace trackwheel
