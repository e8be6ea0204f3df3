// What both full-path integrators share: the run's state, its evaluation and accelerations
// (owned by simulate()), the watchdog's view of them and the recorder of one output sample.
#pragma once

#include "system.hpp"
#include "time_loop.hpp"

namespace trackwheel {

class FullStepper : public Stepper {
 public:
  FullStepper(System& sys, SimState& st, Eval& ev, Accel& acc, SimOutput& out,
              const Divergence& div)
      : sys_(sys), st_(st), ev_(ev), acc_(acc), out_(out), div_(div) {}
  bool finite() const override { return finite_state(st_); }
  double vibration_energy() const override {
    return trackwheel::vibration_energy(sys_.model(), st_);
  }
  double wheel_height(int w) const override { return st_.wheels[w].y; }
  // Append the sample of the current state, evaluation and accelerations at time t [s].
  void record_sample(double t);

 protected:
  System& sys_;
  SimState& st_;
  Eval& ev_;
  Accel& acc_;
  SimOutput& out_;
  const Divergence& div_;
};

}  // namespace trackwheel
