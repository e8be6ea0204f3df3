// What both full-path integrators share: the run's state, its evaluation and accelerations
// (owned by simulate()), the watchdog's view of them, the recorder of one output sample and the
// travelling window's shift of the state.
#pragma once

#include "system.hpp"
#include "time_loop.hpp"
#include "window.hpp"

namespace trackwheel {

class FullStepper : public Stepper {
 public:
  FullStepper(System& sys, SimState& st, Eval& ev, Accel& acc, SimOutput& out,
              const Divergence& div);
  bool finite() const override { return finite_state(st_); }
  double vibration_energy() const override {
    return trackwheel::vibration_energy(sys_.model(), st_);
  }
  double wheel_height(int w) const override { return st_.wheels[w].y; }
  // Append the sample of the current state, evaluation and accelerations at time t [s].
  void record_sample(double t) override;
  // The travelling window streams the supports in through feed, which sets them on the run's
  // own rail (the System's): after a change the System's sleepers and the rest state follow.
  void stream_supports(SupportFeed& feed);

 protected:
  // Moves the track one bay back in the window while the rearmost wheel at t1 is past the hold
  // point (window.hpp): the state and the integrator's accelerations accs; true if it moved.
  bool shift_window(double t1, std::initializer_list<Accel*> accs);

  System& sys_;
  SimState& st_;
  Eval& ev_;
  Accel& acc_;
  SimOutput& out_;
  const Divergence& div_;
  WindowFollower win_;
  SupportRecorder supports_;
};

}  // namespace trackwheel
