// Explicit RK4, the paper's way: the rolling constraints differentiated to acceleration level
// (paper eqs. 20-21, 25), the index-1 system solved for the accelerations and multipliers at
// each stage, classical 4th-order Runge-Kutta on (q, qdot) with the slip states frozen over
// the step; optional Baumgarte stabilisation g' + alpha g = 0. Stable for omega_max dt < 2
// sqrt(2) (explicit_stability_limit).
#pragma once

#include "full_path.hpp"

namespace trackwheel {

class ExplicitRK4 : public FullStepper {
 public:
  using FullStepper::FullStepper;
  void step(long n) override;
  // Also evaluates the accelerations at the recorded state, where the next step starts.
  void record(long n) override;

 private:
  void derivative(double t, const SimState& s, Accel& a);
  void stage(double c, const Accel& a, const SimState& from_rate, SimState& k) const;

  bool start_ready_ = false;  // ev_ and acc_ already hold the evaluation of the current state
  Eval scratch_;
  SimState k1_, k2_, k3_, k4_;  // stage states (members: no allocation per step)
  Accel a2_, a3_, a4_;
};

}  // namespace trackwheel
