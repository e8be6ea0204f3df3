#include "time_loop.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "limits.hpp"

namespace trackwheel {

std::string format3(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

void check_settings(const SimSettings& set) {
  if (!(set.dt > 0.0) || !std::isfinite(set.dt)) throw std::invalid_argument("dt must be > 0 s");
  if (!(set.t_end >= 0.0) || !std::isfinite(set.t_end))
    throw std::invalid_argument("t_end must be >= 0 s");
  if (set.output_every < 1) throw std::invalid_argument("output_every must be >= 1");
  if (!(set.rho_inf >= 0.0 && set.rho_inf <= 1.0))
    throw std::invalid_argument("rho_inf must be in [0, 1]");
  if (set.fresh_contact < -1 || set.fresh_contact > 1)
    throw std::invalid_argument("fresh_contact must be -1 (by the run), 0 or 1");
  if (set.record_supports && set.window.active())
    throw std::invalid_argument(
        "record_supports needs a fixed rail: a travelling window keeps each support's envelope "
        "along the track");
  if (!(set.speed >= 0.0 && set.speed <= limits::kMaxSpeed))
    throw std::invalid_argument("speed must be in [0, " + format3(limits::kMaxSpeed) + "] m/s");
}

long n_steps_of(const SimSettings& set) {
  return static_cast<long>(std::llround(set.t_end / set.dt));
}

void Divergence::fail(long step, const std::string& what, const std::string& cause) const {
  const double t = step * set_.dt;
  std::ostringstream msg;
  msg << "simulation diverged at t = " << format3(t) << " s (step " << step
      << ", X_A = " << format3(set_.x_start + set_.speed * t) << " m): " << what
      << ". Likely cause: " << cause;
  throw DivergenceError(msg.str(), t, step, cause);
}

namespace {

struct Watchdog {
  double energy_cap = 0.0;        // [J]
  std::vector<double> y0, reach;  // start height and allowed excursion per wheel [m]
};

Watchdog watchdog_of(const Model& model, const Stepper& s) {
  Watchdog wd;
  for (int w = 0; w < model.n_wheels(); ++w) {
    const WheelParams& p = model.wheels[w];
    wd.energy_cap += 100.0 * std::max(p.total_load(), 1.0) * p.radius;
    wd.y0.push_back(s.wheel_height(w));
    wd.reach.push_back(10.0 * p.radius);
  }
  // the bodies' weight reaches the track through the wheels: the same cap per newton of load
  wd.energy_cap += 100.0 * vehicle_weight(model.vehicle) * model.wheels[0].radius;
  return wd;
}

void watch(Stepper& s, long n, const Watchdog& wd, const Divergence& div) {
  const double Ev = s.vibration_energy();
  if (!(Ev <= wd.energy_cap))
    div.fail(n, "vibration energy " + format3(Ev) + " J exceeds 100 (F + M g) rho0 = " +
                    format3(wd.energy_cap) + " J (energy runaway)");
  for (std::size_t w = 0; w < wd.y0.size(); ++w) {
    const double dy = s.wheel_height(static_cast<int>(w)) - wd.y0[w];
    if (std::abs(dy) > wd.reach[w])
      div.fail(n, "the wheel centre moved " + format3(dy) + " m from its start");
  }
}

}  // namespace

void run_time_loop(Stepper& s, const Model& model, const SimSettings& set, const Divergence& div,
                   SimOutput& out, const ProgressFn& progress) {
  const long n_steps = n_steps_of(set);
  const int n_supports = static_cast<int>(model.rail.supports().position.size());
  out.rec.start(model.n_wheels(), set.record_energy,
                static_cast<std::size_t>(n_steps / set.output_every + 2),
                set.record_supports ? n_supports : 0);
  out.rec.start_bodies(model.n_bodies());
  const Watchdog wd = watchdog_of(model, s);
  s.record_sample(0.0);
  for (long n = 1; n <= n_steps; ++n) {
    try {
      s.step(n);
      out.steps = n;
      if (!s.finite()) div.fail(n, "non-finite state");
      if (n % 16 == 0 || n == n_steps) watch(s, n, wd, div);
      if (n % set.output_every == 0) s.record(n);
    } catch (const DivergenceError&) {
      throw;
    } catch (const std::runtime_error& err) {  // contact search, singular systems
      div.fail(n, err.what());
    }
    if (progress && set.progress_every > 0 && n % set.progress_every == 0) progress(n, n_steps);
  }
}

}  // namespace trackwheel
