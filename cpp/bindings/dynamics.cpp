// Bindings of the full path's dynamics: the run settings, the state, the output table and the
// time simulation (the GIL released while the kernel runs), the explicit stability limit, and
// the kernel's DivergenceError as trackwheel.DivergenceError.
#include "dynamics.hpp"

#include "common.hpp"
#include "output.hpp"

namespace trackwheel::bindings {

namespace {

// The output table's per-sample and per-wheel rows as (name, unit, doc, per_wheel, dtype).
py::tuple output_table() {
  py::list rows;
  for (const FieldInfo& f : output_fields())
    if (!f.per_support)
      rows.append(
          py::make_tuple(f.name, f.unit, f.doc, f.per_wheel, f.integer ? "int32" : "float64"));
  return py::tuple(rows);
}

// The output table's per-support rows as (name, unit, doc).
py::tuple support_table() {
  py::list rows;
  for (const FieldInfo& f : output_fields())
    if (f.per_support) rows.append(py::make_tuple(f.name, f.unit, f.doc));
  return py::tuple(rows);
}

// The support envelope's fields as (name, unit, doc).
py::tuple envelope_table() {
  py::list rows;
  for (const EnvelopeInfo& f : envelope_fields())
    rows.append(py::make_tuple(f.name, f.unit, f.doc));
  return py::tuple(rows);
}

py::dict simulate_full(const RailModel& rail, const std::vector<WheelParams>& wheels,
                       const ContactParams& c, const SimSettings& s, const SimState& init,
                       py::object progress, const VehicleParams& vehicle) {
  const ProgressFn fn = python_progress(progress);
  const Model model = make_model(rail, wheels, c, vehicle);
  SimOutput o;
  {
    py::gil_scoped_release nogil;
    o = simulate(model, s, init, fn);
  }
  return output_to_dict(std::move(o));
}

double highest_frequency_of(const RailModel& rail, const WheelParams& w, const ContactParams& c,
                            const Eigen::VectorXd& e, double x, double y) {
  check_coordinates(rail, e, "e");
  return highest_frequency(make_model(rail, {w}, c), e, {x}, {y});
}

void bind_state(py::module_& m) {
  py::enum_<Integrator>(m, "Integrator")
      .value("generalized_alpha", Integrator::GeneralizedAlpha)
      .value("explicit", Integrator::ExplicitRK4);
  py::enum_<SlipState>(m, "SlipState")
      .value("free", SlipState::Free)
      .value("stick", SlipState::Stick)
      .value("slip", SlipState::Slip);
  py::class_<SimSettings>(m, "SimSettings")
      .def(py::init<>())
      .def_readwrite("integrator", &SimSettings::integrator)
      .def_readwrite("speed", &SimSettings::speed)
      .def_readwrite("x_start", &SimSettings::x_start)
      .def_readwrite("t_end", &SimSettings::t_end)
      .def_readwrite("dt", &SimSettings::dt)
      .def_readwrite("rho_inf", &SimSettings::rho_inf)
      .def_readwrite("baumgarte", &SimSettings::baumgarte)
      .def_readwrite("rolling", &SimSettings::rolling)
      .def_readwrite("output_every", &SimSettings::output_every)
      .def_readwrite("max_newton", &SimSettings::max_newton)
      .def_readwrite("newton_tol", &SimSettings::newton_tol)
      .def_readwrite("reuse_jacobian", &SimSettings::reuse_jacobian)
      .def_readwrite("fresh_contact", &SimSettings::fresh_contact)
      .def_readwrite("record_energy", &SimSettings::record_energy)
      .def_readwrite("record_supports", &SimSettings::record_supports,
                     "record each support's forces and sleeper displacement per kept sample "
                     "(a fixed rail)")
      .def_readwrite("progress_every", &SimSettings::progress_every)
      .def_readwrite("window", &SimSettings::window, "the travelling window (a copy: assign it)");
  py::class_<WheelState>(m, "WheelState")
      .def(py::init<>())
      .def_readwrite("y", &WheelState::y, "Y_A [m]")
      .def_readwrite("ydot", &WheelState::ydot, "dY_A/dt [m/s]")
      .def_readwrite("theta", &WheelState::theta, "rolling angle [rad]")
      .def_readwrite("thetadot", &WheelState::thetadot, "rolling rate [rad/s]")
      .def_readwrite("s", &WheelState::s, "contact parameter warm start [m]")
      .def_readwrite("state", &WheelState::state)
      .def_readwrite("sigma", &WheelState::sigma, "sign of the sliding friction force")
      .def_readwrite("locked", &WheelState::locked, "held by the brake at theta' = 0")
      .def_readwrite("brake_sign", &WheelState::brake_sign,
                     "sign of the brake torque on the turning wheel (-sign theta')");
  py::class_<SimState>(m, "SimState")
      .def(py::init<>())
      .def_readwrite("e", &SimState::e, "rail coordinates (n_dof,)")
      .def_readwrite("edot", &SimState::edot, "rail velocities (n_dof,)")
      .def_readwrite("wheels", &SimState::wheels,
                     "one WheelState per wheel (a copy: assign the whole list)")
      .def_readwrite("body", &SimState::body, "(2 n_bodies,) [z, phi] per vehicle body")
      .def_readwrite("bodydot", &SimState::bodydot, "(2 n_bodies,) rates")
      .def_readwrite("z", &SimState::z,
                     "sleeper heights (n_sleepers,) [m]; empty: at rest under the initial rail")
      .def_readwrite("zdot", &SimState::zdot, "sleeper velocities (n_sleepers,) [m/s]");
}

}  // namespace

void bind_dynamics(py::module_& m) {
  bind_state(m);
  // trackwheel.DivergenceError(message, time=, step=, cause=) for the kernel's DivergenceError
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const DivergenceError& e) {
      py::object cls = py::module_::import("trackwheel").attr("DivergenceError");
      py::object exc = cls(e.what(), e.time, e.step, e.cause);
      PyErr_SetObject(cls.ptr(), exc.ptr());
    }
  });

  m.attr("OUTPUT_FIELDS") = output_table();
  m.attr("SUPPORT_FIELDS") = support_table();
  m.attr("ENVELOPE_FIELDS") = envelope_table();
  m.def("simulate", &simulate_full, py::arg("rail"), py::arg("wheels"), py::arg("contact"),
        py::arg("settings"), py::arg("initial"), py::arg("progress") = py::none(),
        py::arg("vehicle") = VehicleParams(),
        "Run the whole time loop in C++ (GIL released; progress(step, n_steps) called every "
        "settings.progress_every steps with the GIL held, which also checks for Ctrl-C). Returns "
        "{field: array} for every OUTPUT_FIELDS row (per-wheel fields (n_samples, n_wheels)), "
        "every SUPPORT_FIELDS row ((n_samples, n_supports) if settings.record_supports, else "
        "None), support_envelope ({ENVELOPE_FIELDS name: (n_supports_seen,)}), "
        "the vehicle's body_z, body_phi (n_samples, n_bodies), the counters steps, "
        "newton_iterations, factorizations (band_factorizations, band_solves), state_changes, "
        "stability_limit, final_state");
  m.def("highest_frequency", &highest_frequency_of,
        "omega_max [rad/s] of the linearised rail + wheel-on-contact-spring system");
  m.def("explicit_stability_limit", &explicit_stability_limit,
        "The explicit RK4 stability limit 2 sqrt(2) / omega_max [s] for omega_max [rad/s]");
}

}  // namespace trackwheel::bindings
