// The time loop, written once for every integrator and for the linear path: the recording's
// start, the watchdog (non-finite state, energy runaway, runaway wheel) set up from the model and
// the start state, the steps, decimated recording, progress callbacks (which is also where Ctrl-C
// reaches the kernel) and divergence reports that name the time, step, wheel position and likely
// cause.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "model.hpp"
#include "output.hpp"
#include "state.hpp"

namespace trackwheel {

class DivergenceError : public std::runtime_error {
 public:
  DivergenceError(const std::string& msg, double time, long step, const std::string& cause)
      : std::runtime_error(msg), time(time), step(step), cause(cause) {}
  double time;  // [s]
  long step;
  std::string cause;
};

using ProgressFn = std::function<void(long step, long n_steps)>;

// A number with 3 significant digits, for error messages.
std::string format3(double x);

// Output of a run: the recorded fields and the counters.
struct SimOutput {
  Recording rec;
  SupportEnvelope envelope;  // every support the run saw, along the track
  long steps = 0;            // time steps taken
  long newton_iterations = 0;
  long factorizations = 0;  // Newton matrix factorisations (generalized-alpha)
  // of which the full path's rail band factorisations, and its band solves for the contact
  // coupling (system.hpp: the split iteration matrix)
  long band_factorizations = 0;
  long band_solves = 0;
  long state_changes = 0;  // slip/contact state switches, summed over wheels
  // A unilateral ballast (sleepers.hpp): its sleepers' state changes from step to step, the
  // sleepers frozen in a step after flipping back and forth, each sleeper's time on its ballast
  // [s] (empty without sleepers).
  long ballast_events = 0;
  long ballast_frozen = 0;
  Eigen::VectorXd ballast_contact_time;
  SimState final_state;
  double stability_limit = 0.0;  // explicit RK4: predicted dt limit at the start [s]
};

// Throws DivergenceError with a message naming the time, step, position of the first wheel
// and the likely cause (given, or from the run's cause function).
class Divergence {
 public:
  Divergence(const SimSettings& set, std::function<std::string()> cause)
      : set_(set), cause_(std::move(cause)) {}
  [[noreturn]] void fail(long step, const std::string& what) const { fail(step, what, cause_()); }
  [[noreturn]] void fail(long step, const std::string& what, const std::string& cause) const;

 private:
  const SimSettings& set_;
  std::function<std::string()> cause_;
};

// What the time loop needs from an integrator.
class Stepper {
 public:
  virtual ~Stepper() = default;
  virtual void step(long n) = 0;  // advance from step n - 1 to step n
  virtual bool finite() const = 0;
  virtual double vibration_energy() const = 0;   // [J]
  virtual double wheel_height(int w) const = 0;  // Y_A of wheel w [m]
  virtual void record(long n) = 0;               // append the sample at step n
  virtual void record_sample(double t) = 0;      // append the sample of the state at t [s]
};

long n_steps_of(const SimSettings& set);

// Runs the stepper from its start state (sample 0) to settings.t_end. The watchdog fails the run
// when the vibration energy exceeds 100 (F + M g) rho0 summed over the wheels (a wheel that fell
// ten radii), plus as much per newton of the vehicle's bodies' weight, or when a wheel centre is
// ten radii from its start.
void run_time_loop(Stepper& stepper, const Model& model, const SimSettings& set,
                   const Divergence& divergence, SimOutput& out, const ProgressFn& progress);

}  // namespace trackwheel
