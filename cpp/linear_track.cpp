#include "linear_track.hpp"

#include <optional>
#include <stdexcept>

#include "linear_alpha.hpp"
#include "linear_system.hpp"

namespace trackwheel {

SimOutput simulate_linear(const Model& model_in, const SimSettings& set, const LinearOptions& opt,
                          const ProgressFn& progress) {
  check_settings(set);
  check_model(model_in);
  // a travelling window that streams the supports in sets them on the run's own rail
  std::optional<RailModel> own_rail;
  SupportFeed feed;
  if (set.window.streams()) {
    own_rail.emplace(model_in.rail);
    feed = SupportFeed(set.window, *own_rail);
  }
  const Model model =
      own_rail ? Model{*own_rail, model_in.wheels, model_in.contact, model_in.vehicle} : model_in;
  if (model.n_bodies() > 0 && opt.wheel_model == WheelModel::MovingForce)
    throw std::invalid_argument(
        "a vehicle with bodies needs wheel dynamics: wheel_model moving_mass, sprung or hertz, "
        "not moving_force");
  LinearSystem sys(model, set, opt);
  SimOutput out;
  SimState st;
  Accel acc;
  sys.start(st, acc);
  const Divergence div(set, [&set] {
    return "the time step " + format3(set.dt) + " s is too large for the contact";
  });
  LinearAlpha stepper(sys, st, acc, out, div);
  stepper.stream_supports(feed);
  run_time_loop(stepper, model, set, div, out, progress);
  record_ballast(sys.sleepers(), out);
  return out;
}

Eigen::VectorXd linear_static_line(const RailModel& rail, const BeamParams& beam, double load,
                                   const std::vector<double>& x, int n_modes,
                                   bool element_compliance) {
  const LinearTrack tr(rail, n_modes, beam);
  const Sleepers sl(rail);
  if (!sl.empty() && tr.modal)
    throw std::invalid_argument("n_modes (modal superposition) does not take layered supports");
  LinearRest rest(tr, sl);
  Eigen::VectorXd q_rail = tr.Qg, z, s, ss, sss;  // the track under its own weight
  rest.solve(q_rail, z);
  Eigen::VectorXd y(static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) {
    tr.coupling(x[i], s, ss, sss);
    if (sl.unilateral()) {  // no superposition: the active set under each load, warm-started
      Eigen::VectorXd q = tr.Qg - load * s;
      rest.solve(q, z);
      y(static_cast<Eigen::Index>(i)) = s.dot(q);
    } else {
      Eigen::VectorXd u = s;  // K^-1 s: the track under a unit upward load at X_i
      rest.solve_in_place(u);
      y(static_cast<Eigen::Index>(i)) = s.dot(q_rail) - load * s.dot(u);
    }
    if (element_compliance) {  // the element's own deflection under the load
      const double l = rail.element_length(), xi = tr.point(x[i]).xi;
      const double cs = beam.timoshenko() ? 1.0 / beam.shear_stiffness : 0.0;
      y(static_cast<Eigen::Index>(i)) -=
          load * fixed_end_compliance(rail.params().EI, cs, l, xi * l).G;
    }
  }
  return y;
}

}  // namespace trackwheel
