// Bindings of the linear path: the wheel models, its options, the time simulation on the linear
// track (the GIL released while the kernel runs) and the linear track's quasi-static line.
#include "common.hpp"
#include "linear_track.hpp"
#include "static_line.hpp"

namespace trackwheel::bindings {

namespace {

py::dict simulate_linear_of(const RailModel& rail, const std::vector<WheelParams>& wheels,
                            const ContactParams& c, const SimSettings& s, const LinearOptions& opt,
                            py::object progress, const VehicleParams& vehicle) {
  const ProgressFn fn = python_progress(progress);
  const Model model = make_model(rail, wheels, c, vehicle);
  SimOutput o;
  {
    py::gil_scoped_release nogil;
    o = simulate_linear(model, s, opt, fn);
  }
  py::dict d = output_to_dict(std::move(o));
  d["final_state"] = py::none();
  return d;
}

}  // namespace

void bind_linear(py::module_& m) {
  py::enum_<WheelModel>(m, "WheelModel")
      .value("moving_force", WheelModel::MovingForce)
      .value("moving_mass", WheelModel::MovingMass)
      .value("sprung", WheelModel::Sprung)
      .value("hertz", WheelModel::Hertz);
  py::class_<LinearOptions>(m, "LinearOptions")
      .def(py::init<>())
      .def_readwrite("wheel_model", &LinearOptions::wheel_model)
      .def_readwrite("n_modes", &LinearOptions::n_modes)
      .def_readwrite("sudden", &LinearOptions::sudden)
      .def_readwrite("drop_height", &LinearOptions::drop_height)
      .def_readwrite("beam", &LinearOptions::beam);
  m.def("simulate_linear", &simulate_linear_of, py::arg("rail"), py::arg("wheels"),
        py::arg("contact"), py::arg("settings"), py::arg("options"),
        py::arg("progress") = py::none(), py::arg("vehicle") = VehicleParams(),
        "Linear vertical track fast path (Euler-Bernoulli or Timoshenko rail, constant matrices)");
  m.def("linear_static_line", &linear_static_line, py::arg("rail"), py::arg("beam"),
        py::arg("load"), py::arg("x"), py::arg("n_modes") = 0,
        py::arg("element_compliance") = false, py::call_guard<py::gil_scoped_release>(),
        "Quasi-static line of the linear track: y(X_i) [m] under the load P [N] resting at "
        "each X_i [m] (K q = Q_g - P s(X)); n_modes > 0: of its modal reduction; "
        "element_compliance: the element's own deflection under the load G(X_i) P included.");
  m.def("linear_static_line_selected", &linear_static_line_selected, py::arg("rail"),
        py::arg("beam"), py::arg("load"), py::arg("x"), py::arg("element_compliance") = false,
        py::call_guard<py::gil_scoped_release>(),
        "linear_static_line in all coordinates from the selected inverse of K (the entries of "
        "K^-1 within its band): O(1) per position after one factorisation; a unilateral "
        "ballast falls back to a solve per position.");
  m.def("linear_static_flexibility", &linear_static_flexibility, py::arg("rail"), py::arg("beam"),
        py::arg("xa"), py::arg("xb"), py::call_guard<py::gil_scoped_release>(),
        "The linear track's static flexibility s(xa_k)^T K^-1 s(xb_k) [m/N] for each pair k "
        "(the receptance at 0 Hz), from the entries of K^-1 within the pairs' largest "
        "coordinate distance: O(1) per pair after one pass over the rail.");
}

}  // namespace trackwheel::bindings
