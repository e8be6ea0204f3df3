#include "linear_alpha.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace trackwheel {

LinearAlpha::LinearAlpha(LinearSystem& sys, SimState& st, Accel& acc, SimOutput& out,
                         const Divergence& div)
    : LinearStepper(sys, st, acc, out, div),
      c_(sys.settings().rho_inf, sys.settings().dt),
      layout_(sys.layout()),
      alg_(acc),
      pred_(st),
      s1_(st) {}

void LinearAlpha::step(long n) {
  const double t1 = n * c_.h;
  shift_window(t1, {&acc_, &alg_});
  sys_.sleepers().begin_step();
  sys_.couple(t1);
  ga_predictor(c_, layout_, st_, acc_, alg_, pred_, alg_pred_);
  sys_.begin_step(pred_);
  // Newton from q''_{n+1} = 0, the wheels' and bodies' accelerations 0, the contact forces N
  // from the step before
  x_.edd.setZero(acc_.edd.size());
  x_.zdd.setZero(acc_.zdd.size());
  x_.x = acc_.x;
  for (int w = 0; w < layout_.n_wheels; ++w) x_.x(layout_.y(w)) = 0.0;
  for (int k = 0; k < 2 * layout_.n_bodies; ++k) x_.x(layout_.body(k)) = 0.0;
  if (!newton(n, t1))
    div_.fail(n, "Newton did not converge in " +
                     std::to_string(std::max(sys_.settings().max_newton, 1)) + " iterations");
  ga_corrected_alg(c_, layout_, alg_pred_, x_, alg_);
  if (sys_.options().wheel_model == WheelModel::MovingForce)
    for (int w = 0; w < layout_.n_wheels; ++w) {  // the wheel follows the rail, for the record
      s1_.wheels[w].y = sys_.coupling(w).dot(s1_.e) + sys_.model().wheels[w].radius;
      s1_.wheels[w].ydot = 0.0;
    }
  std::swap(st_, s1_);
  std::swap(acc_, x_);
  sys_.sleepers().commit(c_.h);
}

// One iteration solves a linear level exactly. A unilateral ballast: the step starts in the
// states of the step before; after each correction the states at the new iterate are set by the
// law, and the step has converged when none changed (the matrix, refactorised in the new states
// otherwise, was that of the last correction).
bool LinearAlpha::newton(long n, double t1) {
  const SimSettings& set = sys_.settings();
  const bool hertz = sys_.options().wheel_model == WheelModel::Hertz;
  const bool unilateral = sys_.sleepers().unilateral();
  bool converged = false;
  for (int it = 0; it < std::max(set.max_newton, 1) + (unilateral ? 1 : 0); ++it) {
    ga_corrector(c_, layout_, pred_, x_, s1_);
    if (unilateral && it > 0) {
      if (sys_.update_ballast(s1_) > 0) {
        ++out_.factorizations;
        sys_.couple(t1);
      } else if (converged) {
        return true;  // s1_ is the state at the final accelerations
      }
    }
    sys_.residual(it, s1_, x_, r1_);
    if (!sys_.solve(t1, s1_, x_, r1_, x1_, xb_, dz_)) div_.fail(n, "singular iteration matrix");
    ++out_.newton_iterations;
    bool small_force = true;
    const double dq = apply_correction(small_force);
    converged = !hertz || (dq <= set.newton_tol && small_force);
    if (converged && !unilateral) {
      ga_corrector(c_, layout_, pred_, x_, s1_);  // the state at the final accelerations
      return true;
    }
  }
  return false;
}

double LinearAlpha::apply_correction(bool& small_force) {
  x_.edd += x1_;
  double dq = x1_.lpNorm<Eigen::Infinity>();
  if (dz_.size() > 0) {
    x_.zdd += dz_;
    dq = std::max(dq, dz_.lpNorm<Eigen::Infinity>());
  }
  for (int w = 0; w < layout_.n_wheels; ++w) {
    const int iy = layout_.y(w);
    x_.x(iy) += xb_(2 * w);
    x_.x(iy + layout_.multiplier) += xb_(2 * w + 1);
    dq = std::max(dq, std::abs(xb_(2 * w)));
    small_force &= std::abs(xb_(2 * w + 1)) <= 1e-6 * std::max(1.0, sys_.static_load(w));
  }
  const int nb2 = 2 * layout_.n_bodies;
  if (nb2 > 0) {
    x_.x.segment(layout_.body(0), nb2) += xb_.tail(nb2);
    dq = std::max(dq, xb_.tail(nb2).lpNorm<Eigen::Infinity>());
  }
  return dq * c_.cq;
}

}  // namespace trackwheel
