#include "generalized_alpha.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "slip.hpp"

namespace trackwheel {

GeneralizedAlpha::GeneralizedAlpha(System& sys, SimState& st, Eval& ev, Accel& acc, SimOutput& out,
                                   const Divergence& div)
    : FullStepper(sys, st, ev, acc, out, div),
      c_(sys.settings().rho_inf, sys.settings().dt),
      layout_(sys.layout()),
      alg_(acc),
      prev_(acc),
      key_(sys.n_wheels()),
      dedd_(Eigen::VectorXd::Zero(sys.rail().n_dof())) {
  theta_max_ = 0.1 * (1.0 - sys.settings().rho_inf);
  const Model& m = sys.model();
  fresh_contact_ = !m.rail.profile().empty();
  for (const WheelParams& w : m.wheels) fresh_contact_ |= !w.out_of_round.empty();
  if (sys.settings().fresh_contact >= 0) fresh_contact_ = sys.settings().fresh_contact > 0;
}

void GeneralizedAlpha::predict(const SimState& s0, const Accel& acc0, const Accel& x,
                               SimState& s1) {
  ga_state_at(c_, layout_, s0, acc0, alg_, x, s1, alg1_);
}

bool GeneralizedAlpha::matrix_is_stale(const SimState& s1, int it) const {
  if (!have_matrix_ || it >= 4 || !sys_.settings().reuse_jacobian || fresh_contact_) return true;
  if (sys_.sleepers().version() != ballast_version_) return true;
  const double reach = 0.05 * sys_.rail().element_length();
  for (int w = 0; w < sys_.n_wheels(); ++w) {
    const MatrixKey& k = key_[w];
    const WheelEval& we = ev_.w[w];
    if (k.element != we.pt.mp.element || k.state != s1.wheels[w].state ||
        k.sigma != s1.wheels[w].sigma || k.locked != s1.wheels[w].locked ||
        std::abs(we.pt.s - k.s) > reach)
      return true;
  }
  return false;
}

// Rebuild policy: the rail part too on the first build, after three slow iterations and on
// every 64th factorisation (the rail's tangent drifts slowly) -- every 512 steps where the
// contact block is new at every iteration (about the same interval); the contact part always.
void GeneralizedAlpha::rebuild_matrix(long n, const SimState& s1, const Accel& x, int it) {
  const bool periodic = fresh_contact_ ? n - rail_step_ >= 512 : out_.factorizations % 64 == 0;
  const bool refresh_rail = !have_matrix_ || it >= 3 || periodic;
  if (refresh_rail) rail_step_ = n;
  sys_.contact_terms(s1, true, ev_);
  bool ok;
  if (fresh_contact_) {
    ok = sys_.update_iteration_matrix(s1, ev_, x, c_.cq, c_.cv, refresh_rail);
  } else {
    sys_.assemble_iteration_matrix(s1, ev_, x, c_.cq, c_.cv, refresh_rail);
    ok = sys_.factorize_iteration_matrix();
  }
  if (!ok) div_.fail(n, "singular Newton matrix");
  have_matrix_ = true;
  ballast_version_ = sys_.sleepers().version();
  for (int w = 0; w < sys_.n_wheels(); ++w)
    key_[w] = {ev_.w[w].pt.mp.element, s1.wheels[w].state, s1.wheels[w].sigma, ev_.w[w].pt.s,
               s1.wheels[w].locked};
  ++out_.factorizations;
}

// Newton on (e''_{n+1}, Y''_{n+1}, theta''_{n+1}, lambda) from the predictor x. The size of a
// correction, e = max(|displacement correction| / newton_tol, |tangential force correction| /
// (1e-6 wheel load)), is 1 at the tolerance. Converged when e <= 1, or when the error left in
// the iterate, estimated from the contraction theta = e_k / e_{k-1} of the (modified) Newton
// iteration as theta / (1 - theta) e_k, is (Hairer & Wanner, Solving ODEs II, IV.8): a stale
// matrix contracts linearly, and a correction a few times the tolerance after one a thousand
// times it leaves an error a hundredth of it. Only while theta <= theta_max_ = (1 - rho_inf) /
// 10: a stopped iteration perturbs the step's amplification by about theta, which the
// scheme's damping of its highest modes absorbs (at rho_inf = 1 nothing does). On return s1 is
// the state at the converged iterate (ev_ is one correction older). A pass that contracts
// slower than 4x drops the matrix for a rebuild.
bool GeneralizedAlpha::newton(long n, double t1, const SimState& s0, const Accel& acc0, Accel& x,
                              SimState& s1) {
  const SimSettings& set = sys_.settings();
  double prev_dq = INFINITY, prev_e = INFINITY;
  for (int it = 0; it < set.max_newton; ++it) {
    predict(s0, acc0, x, s1);
    if (!finite_state(s1)) div_.fail(n, "non-finite state in Newton");
    sys_.evaluate(t1, s1, false, ev_);
    for (int w = 0; w < sys_.n_wheels(); ++w) s1.wheels[w].s = ev_.w[w].pt.s;
    sys_.residual(s1, ev_, x, c_.cv, r1_, r2_);
    if (matrix_is_stale(s1, it)) rebuild_matrix(n, s1, x, it);
    sys_.solve(r1_, r2_, x1_, x2_, dz_);
    ++out_.newton_iterations;
    dedd_.setZero();
    sys_.rail().add_from_free(x1_, dedd_);
    x.edd += dedd_;
    x.x += x2_;
    double dq = x1_.lpNorm<Eigen::Infinity>();
    if (dz_.size() > 0) {
      x.zdd += dz_;
      dq = std::max(dq, dz_.lpNorm<Eigen::Infinity>());
    }
    double dlambda = 0.0;  // the largest tangential force correction, in its tolerance
    for (int w = 0; w < sys_.n_wheels(); ++w) {
      const int o = kBorderPerWheel * w;
      const WheelParams& p = sys_.model().wheels[w];
      dq = std::max({dq, std::abs(x2_(o + kY)), p.radius * std::abs(x2_(o + kTheta))});
      dlambda = std::max(dlambda,
                         std::abs(x2_(o + kLambda)) / (1e-6 * std::max(1.0, sys_.static_load(w))));
    }
    const int ob = kBorderPerWheel * sys_.n_wheels();
    for (int k = 0; k < 2 * sys_.n_bodies(); k += 2)  // body pitch: as the 1 m-arm displacement
      dq = std::max({dq, std::abs(x2_(ob + k)), std::abs(x2_(ob + k + 1))});
    dq *= c_.cq;
    const double e = std::max(dq / set.newton_tol, dlambda);
    const double theta = e / prev_e;
    if (e <= 1.0 || (std::isfinite(prev_e) && theta <= theta_max_ && theta * e <= 1.0 - theta)) {
      predict(s0, acc0, x, s1);
      if (!finite_state(s1)) div_.fail(n, "non-finite state in Newton");
      // a sleeper crossed its threshold in the last correction: iterate on in its new state
      if (sys_.sleepers().update_states(s1.z, &s1.zdot) == 0) return true;
      prev_dq = prev_e = INFINITY;
      continue;
    }
    if (it >= 1 && dq > 0.25 * prev_dq) have_matrix_ = false;
    prev_dq = dq;
    prev_e = e;
  }
  return false;
}

// Applies the slip and brake state machines to every wheel at the converged iterate; returns how
// many state changes there were (changed: any).
int GeneralizedAlpha::commit_slip_states(Accel& x, SimState& s1, bool& changed) {
  const SimSettings& set = sys_.settings();
  int n_changed = 0;
  for (int w = 0; w < sys_.n_wheels(); ++w) {
    const double lambda = x.x(kBorderPerWheel * w + kLambda);
    n_changed += update_slip_state(set.rolling, sys_.model().contact.friction, set.speed,
                                   s1.wheels[w], ev_.w[w], lambda);
    n_changed += update_brake_state(sys_.model().wheels[w], s1.wheels[w], ev_.w[w], lambda);
  }
  changed = n_changed > 0;
  return n_changed;
}

void GeneralizedAlpha::step(long n) {
  const double t1 = n * c_.h;
  // the window moved: the accelerations, their algorithmic counterparts and the predictor's
  // history moved with the state; the cached matrix holds the rail's tangent at the unshifted
  // state, so it is rebuilt, the rail part too
  if (shift_window(t1, {&acc_, &alg_, &prev_})) have_matrix_ = false;
  s0_ = st_;  // members: the copies reuse their storage, nothing is allocated per step
  acc0_ = acc_;
  sys_.sleepers().begin_step();
  for (int attempt = 0; attempt < 4; ++attempt) {
    // predictor: linear extrapolation of the accelerations (constant on the first step and
    // after a state change)
    if (have_prev_ && attempt == 0) {
      x_.edd = 2.0 * acc0_.edd - prev_.edd;
      x_.x = 2.0 * acc0_.x - prev_.x;
      if (acc0_.zdd.size() > 0) x_.zdd = 2.0 * acc0_.zdd - prev_.zdd;
    } else {
      x_ = acc0_;
    }
    s1_ = st_;  // carries the slip states of this attempt
    if (!newton(n, t1, s0_, acc0_, x_, s1_))
      div_.fail(n, "Newton did not converge in " + std::to_string(sys_.settings().max_newton) +
                       " iterations");
    bool changed = false;
    const int n_changed = commit_slip_states(x_, s1_, changed);
    if (changed && attempt < 3) {  // redo the step in the new states
      out_.state_changes += n_changed;
      for (int w = 0; w < sys_.n_wheels(); ++w) {
        st_.wheels[w].state = s1_.wheels[w].state;
        st_.wheels[w].sigma = s1_.wheels[w].sigma;
        st_.wheels[w].locked = s1_.wheels[w].locked;
        st_.wheels[w].brake_sign = s1_.wheels[w].brake_sign;
      }
      continue;
    }
    have_prev_ = !changed && attempt == 0;
    std::swap(prev_, acc0_);
    std::swap(st_, s1_);
    std::swap(alg_, alg1_);
    std::swap(acc_, x_);
    sys_.sleepers().commit(c_.h);
    out_.band_factorizations = sys_.band_factorizations();
    out_.band_solves = sys_.band_solves();
    return;
  }
}

void GeneralizedAlpha::probe(double t1, const Accel& x, Eigen::VectorXd& minus_r,
                             Eigen::MatrixXd& J, Eigen::VectorXd& dx) {
  SimState s1 = st_;
  predict(st_, acc_, x, s1);
  sys_.evaluate(t1, s1, true, ev_);
  sys_.residual(s1, ev_, x, c_.cv, r1_, r2_);
  sys_.assemble_iteration_matrix(s1, ev_, x, c_.cq, c_.cv, true);
  J = sys_.iteration_matrix_dense();
  const Eigen::VectorXd& rs = sys_.sleeper_residual();
  minus_r.resize(r1_.size() + r2_.size() + rs.size());
  minus_r << r1_, r2_, rs;
  const bool ok = fresh_contact_ ? sys_.update_iteration_matrix(s1, ev_, x, c_.cq, c_.cv, false)
                                 : sys_.factorize_iteration_matrix();
  if (!ok) throw std::runtime_error("singular Newton matrix");
  sys_.solve(r1_, r2_, x1_, x2_, dz_);
  dx.resize(minus_r.size());
  dx << x1_, x2_, dz_;
}

}  // namespace trackwheel
