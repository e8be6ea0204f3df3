// What the linear path's integrator shares with the full path's (full_path.hpp): the run's state,
// its true accelerations (acc.x: [Y'', N] per wheel, then the bodies') and its system workspace
// (linear_system.hpp), the watchdog's view of them, the recorder of one output sample and the
// travelling window's shift of the state.
#pragma once

#include "linear_system.hpp"
#include "time_loop.hpp"
#include "window.hpp"

namespace trackwheel {

class LinearStepper : public Stepper {
 public:
  LinearStepper(LinearSystem& sys, SimState& st, Accel& acc, SimOutput& out, const Divergence& div);
  // The positions only (the track, sleepers, bodies and wheel heights): a non-finite rate
  // reaches them within the step, and the check runs every step.
  bool finite() const override;
  double vibration_energy() const override;
  double wheel_height(int w) const override { return st_.wheels[w].y; }
  // Append the sample of the current state and accelerations at time t [s].
  void record_sample(double t) override;
  // The travelling window streams the supports in through feed, which sets them on the run's
  // own rail (the LinearSystem's): after a change the track, its factorisation and the rest
  // state follow.
  void stream_supports(SupportFeed& feed);

 protected:
  // Moves the track one bay back in the window while the rearmost wheel at t1 is past the hold
  // point (window.hpp): the state and the integrator's accelerations accs; true if it moved.
  // The track is linear, so the departure from the rest state obeys the same equations in
  // every window position.
  bool shift_window(double t1, std::initializer_list<Accel*> accs);

  LinearSystem& sys_;
  SimState& st_;
  Accel& acc_;
  SimOutput& out_;
  const Divergence& div_;
  WindowFollower win_;
  SupportRecorder supports_;

 private:
  // One wheel's fields of the sample at t; delta: its contact approach [m] (0: rigid).
  void record_wheel(int w, double t, double& delta);
  // The total mechanical energy [J] (as the full path's total_energy) at t, with each wheel's
  // approach delta.
  double total_energy(double t, const std::vector<double>& delta) const;
  std::vector<double> delta_;
  WheelCoupling at_;  // a wheel's coupling at the sample (a buffer)
};

}  // namespace trackwheel
