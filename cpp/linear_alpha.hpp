// Generalized-alpha on the linear path (the scheme: ga_scheme.hpp, in its predictor-corrector
// form): the track's iteration matrix is constant and factorised once (LinearSystem), so a step
// is the predictor, the couplings at t_{n+1} and Newton from q''_{n+1} = 0, exact in one
// iteration for the linear wheel models (moving force, moving mass, sprung); the Hertz wheel
// iterates to newton_tol.
#pragma once

#include "ga_scheme.hpp"
#include "linear_path.hpp"

namespace trackwheel {

class LinearAlpha : public LinearStepper {
 public:
  // acc: the accelerations at the start state (the algorithmic ones start equal to them).
  LinearAlpha(LinearSystem& sys, SimState& st, Accel& acc, SimOutput& out, const Divergence& div);
  void step(long n) override;
  void record(long n) override { record_sample(n * c_.h); }

 private:
  // Newton from x = 0 (the multipliers N from the step before) at t1; on return s1_ is the
  // state at the converged iterate x_.
  bool newton(long n, double t1);
  // x += the correction (dx1, xb, dz); the largest displacement correction [m] (cq dx) and
  // whether every contact force correction is below 1e-6 of its wheel's static load.
  double apply_correction(bool& small_force);

  const GACoefficients c_;
  const BorderLayout layout_;
  Accel alg_;           // algorithmic accelerations
  SimState pred_, s1_;  // the predictor (the state at x = 0) and the Newton iterate's state
  Accel alg_pred_, x_;  // the predictor's algorithmic accelerations and the Newton iterate
  Eigen::VectorXd r1_, x1_, xb_, dz_;
};

}  // namespace trackwheel
